"""Arch generators.

Axes (DESIGN.md): the arch spans along x, its depth runs along y (from -depth/2 to
+depth/2), z is up, springings at z = 0, the centre at the origin, the right springing
at +x. Voussoirs are named ``v01``, ``v02``, ... from left to right; the two support
blocks are ``left`` and ``right``. Every voussoir is a hexahedron bounded by two plane
joints and plane (chord) intrados and extrados faces.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from .assembly import Assembly, Block, Interface
from .geometry import prism

__all__ = ["arch_from_joints", "semicircular_arch", "check_positive"]


def check_positive(**params: float) -> None:
    """Raise ``ValueError`` naming the first parameter that is not a finite number > 0."""
    for name, value in params.items():
        try:
            ok = math.isfinite(float(value)) and float(value) > 0
        except (TypeError, ValueError):
            ok = False
        if not ok:
            raise ValueError(f"{name} must be a finite number > 0, got {value!r}")


def _at_depth(xz: np.ndarray, y: float) -> np.ndarray:
    """Lift (k, 2) points of the x-z plane to 3D at depth coordinate y."""
    return np.column_stack([xz[:, 0], np.full(len(xz), y), xz[:, 1]])


def arch_from_joints(
    intrados: ArrayLike,
    extrados: ArrayLike,
    depth: float,
    unit_weight: float = 20.0,
    support_height: float | None = None,
    meta: dict | None = None,
) -> Assembly:
    """Arch of voussoirs between given plane joints, on two support blocks.

    Parameters
    ----------
    intrados, extrados : (N + 1, 2) array_like
        ``(x, z)`` of the intrados and extrados ends of the N + 1 joints, from the left
        springing to the right one (m). Voussoir ``i`` lies between joints ``i`` and ``i+1``.
    depth : float
        Depth of the arch along y (m).
    unit_weight : float
        Unit weight of every block (kN/m^3).
    support_height : float, optional
        Height of the support blocks below the lower end of their springing joint (m);
        defaults to the joint length (the arch thickness at the springing). Each support
        is a prism under its springing joint, as deep as the arch, with a horizontal base.
    meta : dict, optional
        Description of the generator, stored in ``Assembly.meta``.

    Returns
    -------
    Assembly
        Blocks ``left, v01 .. vN, right``; interfaces ``left -> v01``, ``v_i -> v_{i+1}``
        and ``vN -> right``, each with its normal pointing from the left block into the
        right one.
    """
    ji = np.asarray(intrados, dtype=float)
    je = np.asarray(extrados, dtype=float)
    if ji.shape != je.shape or ji.ndim != 2 or ji.shape[1] != 2 or len(ji) < 2:
        raise ValueError("intrados and extrados must be (N + 1, 2) arrays of joint ends, N >= 1")
    check_positive(depth=depth, unit_weight=unit_weight)
    n = len(ji) - 1
    d = float(depth) / 2.0
    blocks: list[Block] = []

    def support(k: int, name: str) -> Block:
        top = np.array([ji[k], je[k]])
        height = support_height if support_height is not None else float(np.linalg.norm(je[k] - ji[k]))
        check_positive(support_height=height)
        base = top[:, 1].min() - height
        loop = np.array([top[0], top[1], [top[1, 0], base], [top[0, 0], base]])
        return Block(name, prism(_at_depth(loop, -d), _at_depth(loop, d)), unit_weight, True)

    blocks.append(support(0, "left"))
    width = len(str(n)) if n >= 10 else 2
    for i in range(n):
        loop = np.array([ji[i], ji[i + 1], je[i + 1], je[i]])
        shape = prism(_at_depth(loop, -d), _at_depth(loop, d))
        blocks.append(Block(f"v{i + 1:0{width}d}", shape, unit_weight))
    blocks.append(support(n, "right"))

    interfaces = []
    for k in range(n + 1):
        a, b = k, k + 1  # block k is left of joint k
        joint = np.array([ji[k], je[k]])
        pts = np.vstack([_at_depth(joint, -d), _at_depth(joint[::-1], d)])
        # normal in the x-z plane, perpendicular to the joint, pointing left -> right
        tx, tz = je[k] - ji[k]
        normal = np.array([tz, 0.0, -tx])
        cb, ca = blocks[b].centroid, blocks[a].centroid
        if normal @ (cb - ca) < 0:
            normal = -normal
        interfaces.append(Interface(a, b, pts, normal))
    return Assembly(tuple(blocks), tuple(interfaces), dict(meta or {}))


def semicircular_arch(
    inner_radius: float = 1.0,
    thickness: float = 0.2,
    depth: float = 0.25,
    voussoirs: int = 14,
    unit_weight: float = 20.0,
    support_height: float | None = None,
) -> Assembly:
    """The paper's semicircular arch on two support blocks.

    Parameters
    ----------
    inner_radius : float
        Intrados radius (m); default 1.00.
    thickness : float
        Radial thickness (m); default 0.20.
    depth : float
        Depth along y (m); default 0.25.
    voussoirs : int
        Number of voussoirs, equal angles; default 14.
    unit_weight : float
        Unit weight (kN/m^3); default 20.
    support_height : float, optional
        Height of the support boxes (m); default: the thickness (the paper's supports:
        as wide as the thickness, as deep as the arch, as high as the thickness).

    Returns
    -------
    Assembly
        See :func:`arch_from_joints`.
    """
    check_positive(inner_radius=inner_radius, thickness=thickness, depth=depth, unit_weight=unit_weight)
    if int(voussoirs) != voussoirs or voussoirs < 1:
        raise ValueError(f"voussoirs must be a whole number >= 1, got {voussoirs!r}")
    theta = np.linspace(np.pi, 0.0, int(voussoirs) + 1)
    c, s = np.cos(theta), np.sin(theta)
    c[[0, -1]] = [-1.0, 1.0]
    s[[0, -1]] = 0.0
    ro = inner_radius + thickness
    meta = dict(
        generator="semicircular_arch",
        inner_radius=float(inner_radius),
        thickness=float(thickness),
        depth=float(depth),
        voussoirs=int(voussoirs),
        unit_weight=float(unit_weight),
        support_height=float(support_height if support_height is not None else thickness),
    )
    return arch_from_joints(
        np.column_stack([inner_radius * c, inner_radius * s]),
        np.column_stack([ro * c, ro * s]),
        depth,
        unit_weight,
        support_height if support_height is not None else thickness,
        meta,
    )
