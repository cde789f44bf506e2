"""Arch generators.

Axes (docs/conventions.md): the arch spans along x, its depth runs along y (from -depth/2 to
+depth/2), z is up, springings at z = 0, the centre at the origin, the right springing
at +x. Voussoirs are named ``v01``, ``v02``, ... from left to right; the two support
blocks are ``left`` and ``right``. Every voussoir is a hexahedron bounded by two plane
joints and plane (chord) intrados and extrados faces.

Multi-ring arches (``rings`` > 1 or a list of ring thicknesses; :func:`ring_arch`): brick
arches built as several rings, one on the other. Ring 1 is the intrados ring. Each ring has
its own voussoirs (``r1v01``, ``r1v02``, ... for ring 1) between its own radial joints; the
rings share the two support blocks. The faces between two rings are interfaces of kind
``"ring"`` (:attr:`tce.structures.assembly.Interface.kind`), which a material may give their
own contact law (:attr:`tce.core.material.Material.interfaces`). Joints are either aligned
(``stagger = False``: every ring cut at the same joints, so that rings that cannot separate
are one ring of the summed thickness) or staggered by the **half-brick rule**
(``stagger = True``): the odd rings (1, 3, ...) are cut at the voussoir joints, the even
rings (2, 4, ...) half a voussoir further, so that an even ring has one voussoir more and a
half voussoir at each springing. A face between two rings then runs through the joints of
both (a voussoir's face towards a staggered ring is two chords).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from collections.abc import Callable, Sequence

from .assembly import Assembly, Block, Interface
from .backing import Backing, with_backing
from .geometry import FaceTable, prism, prisms
from .params import check_blocks, check_positive, check_whole

__all__ = [
    "RING",
    "RingLayout",
    "arch_from_joints",
    "ring_arch",
    "ring_fractions",
    "semicircle_joints",
    "pointed_arch",
    "segmental_arch",
    "semicircular_arch",
    "semicircular_arch_on_piers",
]


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
        Height of the support blocks (prisms under their springing joints, with a horizontal
        base) below the lower end of their springing joint (m); default: the joint length.
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

    def support(k: int) -> np.ndarray:
        top = np.array([ji[k], je[k]])
        height = support_height if support_height is not None else float(np.linalg.norm(je[k] - ji[k]))
        check_positive(support_height=height)
        base = top[:, 1].min() - height
        return _at_depth(np.array([top[0], top[1], [top[1, 0], base], [top[0, 0], base]]), -d)[None]

    # section loops (x, z) of every block: left support, voussoirs 1..n, right support
    loops = np.stack([ji[:-1], ji[1:], je[1:], je[:-1]], axis=1)  # (n, 4, 2)
    front = np.concatenate([support(0), _at_depth(loops.reshape(-1, 2), -d).reshape(n, 4, 3), support(n)])
    back = front.copy()
    back[:, :, 1] = d
    shapes = prisms(front, back)
    width = len(str(n)) if n >= 10 else 2
    names = ["left"] + [f"v{i + 1:0{width}d}" for i in range(n)] + ["right"]
    uw = float(unit_weight)
    blocks = [Block(name, shape, uw, k in (0, n + 1)) for k, (name, shape) in enumerate(zip(names, shapes))]

    centroids = FaceTable.uniform(np.concatenate([front, back], axis=1), shapes[0].faces).centroid  # either orientation
    return Assembly(tuple(blocks), tuple(_joints(ji, je, d, centroids)), dict(meta or {}))


def _joints(ji: np.ndarray, je: np.ndarray, d: float, centroids: np.ndarray) -> list[Interface]:
    """Interfaces on the plane joints ``k`` from ``ji[k]`` to ``je[k]`` (``(x, z)``, m) across the
    depth ``-d .. d``, joint ``k`` between blocks ``k`` and ``k + 1`` (``centroids`` theirs;
    :func:`_segment_face`)."""
    return [_segment_face(k, k + 1, ji[k], je[k], centroids, d) for k in range(len(ji))]


#: interface kind of the faces between two rings (:func:`ring_arch`)
RING = "ring"

Rings = int | Sequence[float]


def ring_fractions(rings: Rings, thickness: float) -> np.ndarray:
    """The ring boundaries as fractions of the thickness, from the intrados (0) to the
    extrados (1), ``(R + 1,)``.

    Parameters
    ----------
    rings : int or sequence of float
        The number of equal rings (>= 1), or the thickness of each ring (m, > 0) from the
        intrados out, summing to ``thickness``.
    thickness : float
        The whole arch's thickness (m).

    Raises
    ------
    ValueError
        Not a whole number >= 1, a thickness that is not > 0, or thicknesses whose sum is
        not ``thickness`` (to 1e-9, relative).
    """
    if isinstance(rings, (int, np.integer)) and not isinstance(rings, bool):
        r = check_whole(rings, "rings")
        return np.linspace(0.0, 1.0, r + 1)
    if isinstance(rings, (str, bool)) or not isinstance(rings, Sequence) or not len(rings):
        raise ValueError(f"rings must be a whole number >= 1 or a list of ring thicknesses (m), got {rings!r}")
    check_positive(**{f"rings[{k}]": v for k, v in enumerate(rings)})
    total = float(sum(float(v) for v in rings))
    if abs(total - float(thickness)) > 1e-9 * float(thickness):
        raise ValueError(f"the ring thicknesses {list(rings)} sum to {total:g} m, not the thickness {float(thickness):g} m")
    cum = np.concatenate([[0.0], np.cumsum(np.asarray(rings, dtype=float))]) / total
    cum[-1] = 1.0
    return cum


def _ring_joints(n: int, ring: int, stagger: bool) -> list[int]:
    """Half-step joint indices (0 .. 2 n) of ring ``ring`` (1 from the intrados): the
    voussoir joints ``0, 2, ..., 2 n``, or for an even ring of a staggered arch ``0, 1, 3,
    ..., 2 n - 1, 2 n`` (the half-brick rule, module docstring)."""
    if stagger and ring % 2 == 0:
        return [0] + list(range(1, 2 * n, 2)) + [2 * n]
    return list(range(0, 2 * n + 1, 2))


def ring_arch(
    intrados: ArrayLike,
    extrados: ArrayLike,
    depth: float,
    fractions: ArrayLike,
    stagger: bool = False,
    unit_weight: float = 20.0,
    support_height: float | None = None,
    meta: dict | None = None,
) -> Assembly:
    """Multi-ring arch between given radial joints, on two support blocks (module docstring).

    Parameters
    ----------
    intrados, extrados : (2 N + 1, 2) array_like
        ``(x, z)`` of the intrados and extrados ends of the joints of an N-voussoir ring and of
        the joints half-way between them (m): entry ``2 k`` is voussoir joint ``k``, entry
        ``2 k + 1`` the joint through the middle of voussoir ``k + 1``. A ring boundary at
        fraction ``s`` of the thickness meets joint ``j`` at ``intrados[j] + s (extrados[j] -
        intrados[j])`` (on a radial joint of a circular arc: on the circle of radius
        ``R + s t``).
    depth : float
        Depth of the arch along y (m).
    fractions : (R + 1,) array_like
        Ring boundaries as fractions of the thickness, 0 to 1 (:func:`ring_fractions`).
    stagger : bool
        Joints staggered by the half-brick rule (True) or aligned (False).
    unit_weight, support_height, meta
        As :func:`arch_from_joints`; the support blocks stand under the whole springing joints.

    Returns
    -------
    Assembly
        Blocks ``left``, ring 1's voussoirs ``r1v01 ..``, ring 2's, ..., ``right``;
        interfaces: the supports with the first and last voussoir of every ring, the radial
        joints inside each ring, and the faces between rings (kind ``"ring"``), each normal
        pointing from block A into block B (A the lower index).
    """
    layout = RingLayout(intrados, extrados, fractions, stagger)
    check_positive(depth=depth, unit_weight=unit_weight)
    ji, je, d = layout.ji, layout.je, float(depth) / 2.0
    height = support_height if support_height is not None else float(np.linalg.norm(je[0] - ji[0]))
    check_positive(support_height=height)

    def support(j: int) -> np.ndarray:
        top = np.array([ji[j], je[j]])
        base = top[:, 1].min() - height
        return np.array([top[0], top[1], [top[1, 0], base], [top[0, 0], base]])

    loops, names = [support(0)], ["left"]
    loops += layout.loops
    names += layout.names
    loops.append(support(len(ji) - 1))
    names.append("right")
    shapes = [prism(_at_depth(loop, -d), _at_depth(loop, d)) for loop in loops]
    uw = float(unit_weight)
    blocks = tuple(Block(name, shape, uw, k in (0, len(loops) - 1)) for k, (name, shape) in enumerate(zip(names, shapes)))
    centroids = np.array([shape.centroid for shape in shapes])
    interfaces = layout.interfaces(1, 0, len(loops) - 1, centroids, d)
    return Assembly(blocks, tuple(interfaces), dict(meta or {}))


def _segment_face(a: int, b: int, p: np.ndarray, q: np.ndarray, centroids: np.ndarray, d: float, kind: str = "") -> Interface:
    """The interface between blocks ``a`` and ``b`` on the segment ``p``-``q`` (``(x, z)``, m) across
    the depth ``-d .. d``: the points ``(p, q)`` at ``-d``, ``(q, p)`` at ``+d``; the normal in the
    x-z plane, perpendicular to the segment, pointing from ``a`` into ``b`` (by their
    ``centroids``)."""
    t = q - p
    normal = np.array([t[1], 0.0, -t[0]])
    if normal @ (centroids[b] - centroids[a]) < 0:
        normal = -normal
    pts = np.vstack([_at_depth(np.array([p, q]), -d), _at_depth(np.array([q, p]), d)])
    return Interface(a, b, pts, normal, kind=kind)


class RingLayout:
    """The voussoirs and joints of the rings of one arch between two supports (module docstring).

    Parameters
    ----------
    intrados, extrados : (2 N + 1, 2) array_like
        Half-step joint ends (m), as :func:`ring_arch` takes them.
    fractions : (R + 1,) array_like
        Ring boundaries as fractions of the thickness (:func:`ring_fractions`).
    stagger : bool
        The half-brick rule (True) or aligned joints.

    Attributes
    ----------
    loops : list of (k, 2) ndarray
        Section of every voussoir, ring 1's first (m).
    names : list of str
        ``r1v01, r1v02, ..., r2v01, ...``, in the order of ``loops``.
    """

    def __init__(self, intrados: ArrayLike, extrados: ArrayLike, fractions: ArrayLike, stagger: bool) -> None:
        ji, je = np.asarray(intrados, dtype=float), np.asarray(extrados, dtype=float)
        if ji.shape != je.shape or ji.ndim != 2 or ji.shape[1] != 2 or len(ji) < 3 or len(ji) % 2 == 0:
            raise ValueError("intrados and extrados must be (2 N + 1, 2) arrays of joint ends, N >= 1")
        self.ji, self.je, self.s = ji, je, np.asarray(fractions, dtype=float)
        n, R = (len(ji) - 1) // 2, len(self.s) - 1
        self.joints = [_ring_joints(n, r + 1, stagger) for r in range(R)]
        J = self.joints
        # the joints each ring boundary runs through (the intrados: ring 1's; the extrados: the last ring's)
        self.bounds = [J[0]] + [sorted(set(J[r]) | set(J[r + 1])) for r in range(R - 1)] + [J[-1]]
        self.first = list(np.cumsum([0] + [len(j) - 1 for j in J[:-1]]))  # each ring's first voussoir
        width = max(2, len(str(max(len(j) - 1 for j in J))))
        self.loops: list[np.ndarray] = []
        self.names: list[str] = []
        for r, Jr in enumerate(J):
            for k, (a, c) in enumerate(zip(Jr[:-1], Jr[1:])):
                inner = [j for j in self.bounds[r] if a <= j <= c]
                outer = [j for j in self.bounds[r + 1] if a <= j <= c][::-1]
                self.loops.append(np.vstack([self.at(self.s[r], inner), self.at(self.s[r + 1], outer)]))
                self.names.append(f"r{r + 1}v{k + 1:0{width}d}")

    def at(self, frac: float, j: int | Sequence[int]) -> np.ndarray:
        """Where the ring boundary at ``frac`` of the thickness meets joint(s) ``j`` (m)."""
        return self.ji[j] + frac * (self.je[j] - self.ji[j])

    def interfaces(self, offset: int, left: int, right: int, centroids: np.ndarray, d: float) -> list[Interface]:
        """The supports ``left`` and ``right`` with the first and last voussoir of every ring,
        the radial joints inside each ring and the faces between rings (kind ``"ring"``), for
        voussoirs numbered from ``offset`` in the assembly (``centroids``: every block's, m)."""
        s, J, out = self.s, self.joints, []

        def block_of(r: int, j0: int) -> int:
            """Ring ``r``'s voussoir holding the boundary segment that starts at joint ``j0``."""
            return offset + self.first[r] + sum(1 for j in J[r][1:-1] if j <= j0)

        for r, Jr in enumerate(J):
            lo, hi = self.at(s[r], Jr), self.at(s[r + 1], Jr)
            first = offset + self.first[r]
            out.append(_segment_face(left, first, lo[0], hi[0], centroids, d))
            out += [_segment_face(first + k - 1, first + k, lo[k], hi[k], centroids, d) for k in range(1, len(Jr) - 1)]
            out.append(_segment_face(first + len(Jr) - 2, right, lo[-1], hi[-1], centroids, d))
            if r + 1 < len(J):
                B = self.bounds[r + 1]
                pts = self.at(s[r + 1], B)
                out += [_segment_face(block_of(r, j0), block_of(r + 1, j0), pts[k], pts[k + 1], centroids, d, RING)
                        for k, j0 in enumerate(B[:-1])]
        return out


def semicircular_arch(
    inner_radius: float = 1.0,
    thickness: float = 0.2,
    depth: float = 0.25,
    voussoirs: int = 14,
    unit_weight: float = 20.0,
    support_height: float | None = None,
    joints: str = "radial",
    rings: Rings = 1,
    stagger: bool = False,
    backing: Backing | None = None,
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
        Height of the support boxes (m); default: the thickness (the paper's supports).
    joints : {"radial", "vertical"}
        The stereotomy. ``radial`` (default): every joint on a radius, at equal angles.
        ``vertical``: horizontal springing joints and ``voussoirs - 1`` vertical cuts whose
        lower ends lie at the radial joints' equal angles on the intrados; the end voussoirs
        reach beyond the intrados' width, bounded by the extrados arc (chords about
        ``pi / voussoirs`` apart). Makris and Alexakis (2013, *The effect of stereotomy on
        the shape of the thrust-line and the minimum thickness of semicircular masonry
        arches*, Archive of Applied Mechanics 83, 1511-1533) give the minimum thickness
        ``t/R = 0.1095`` with vertical cuts against Milankovitch's 0.1075 with radial ones
        (docs/validation.md). Several rings need radial joints.
    rings : int or list of float
        Number of equal rings (default 1: one ring of voussoirs), or the thickness of each
        ring from the intrados out (m), summing to ``thickness`` (:func:`ring_arch`).
    stagger : bool
        With several rings: radial joints staggered by the half-brick rule (True) or aligned
        (False, the default); module docstring.
    backing : Backing, optional
        Backing behind the haunches up to a height above the springing, as blocks or as
        a heavier fill (:mod:`tce.structures.backing`).

    Returns
    -------
    Assembly
        See :func:`arch_from_joints` (one ring) or :func:`ring_arch`; ``meta["joints"]``
        records the stereotomy, ``meta["rings"]`` and ``meta["stagger"]`` the rings.
    """
    check_positive(inner_radius=inner_radius, thickness=thickness, depth=depth, unit_weight=unit_weight)
    n = check_whole(voussoirs, "voussoirs")
    check_blocks(n + 2, f"voussoirs + 2 supports = {n} + 2")
    if joints not in JOINTS:
        raise ValueError(f"joints must be one of {', '.join(JOINTS)}, got {joints!r}")
    height = thickness if support_height is None else support_height
    meta = dict(generator="semicircular_arch", inner_radius=float(inner_radius), thickness=float(thickness),
                depth=float(depth), voussoirs=n, unit_weight=float(unit_weight), support_height=float(height))
    fractions = ring_fractions(rings, thickness)
    if joints == "vertical":
        if len(fractions) > 2:
            raise ValueError("rings: several rings need joints = 'radial'")
        if backing is not None:
            raise ValueError("backing: needs joints = 'radial' (the end voussoirs of vertical joints follow the "
                             "extrados arc)")
        return _vertical_joint_arch(float(inner_radius), float(thickness), float(depth), n, float(unit_weight),
                                    float(height), {**meta, "joints": "vertical"})
    return _rings_or_one(lambda m: semicircle_joints(inner_radius, inner_radius + thickness, np.linspace(np.pi, 0.0, m + 1)),
                         n, fractions, rings, stagger, depth, unit_weight, height, meta, backing)


def _rings_or_one(joints: Callable[[int], tuple[np.ndarray, np.ndarray]], n: int, fractions: np.ndarray, rings: Rings,
                  stagger: bool, depth: float, unit_weight: float, height: float, meta: dict,
                  backing: Backing | None = None) -> Assembly:
    """One ring of ``n`` voussoirs on the joints ``joints(n)`` (:func:`arch_from_joints`), or
    several on the half-step joints ``joints(2 n)`` (:func:`ring_arch`), with ``rings`` and
    ``stagger`` recorded in the meta, and the ``backing`` on the extrados
    (:func:`tce.structures.backing.with_backing`)."""
    if len(fractions) == 2:
        ji, je = joints(n)
        asm = arch_from_joints(ji, je, depth, unit_weight, height, meta)
        extrados, over = je, np.arange(1, n + 1)
    else:
        check_blocks((len(fractions) - 1) * (n + 1) + 2, "rings x (voussoirs + 1) + 2 supports")
        meta = dict(meta, rings=rings if isinstance(rings, int) else [float(v) for v in rings], stagger=bool(stagger))
        ji, je = joints(2 * n)
        asm = ring_arch(ji, je, depth, fractions, stagger, unit_weight, height, meta)
        layout = RingLayout(ji, je, fractions, stagger)  # the outer ring's voussoirs hold the extrados
        extrados, over = je[layout.joints[-1]], 1 + layout.first[-1] + np.arange(len(layout.joints[-1]) - 1)
    return asm if backing is None else with_backing(asm, [extrados], [over], depth, backing)


#: joint directions of :func:`semicircular_arch`
JOINTS = ("radial", "vertical")


def _vertical_joint_arch(ri: float, t: float, depth: float, n: int, unit_weight: float, height: float,
                         meta: dict) -> Assembly:
    """The semicircular ring cut by vertical joints (``semicircular_arch(..., joints="vertical")``).

    Joint ``k`` (``0 < k < n``) is the vertical segment at ``x_k = ri cos(pi (1 - k / n))``
    from the intrados up to the extrados; joints 0 and ``n`` are the horizontal springing
    joints. Voussoirs 2 .. n-1 have chord intrados and extrados faces; the two end voussoirs
    follow the extrados arc down to the springing line.
    """
    if n < 2:
        raise ValueError(f"vertical joints need voussoirs >= 2, got {n}")
    re = ri + t
    ji, _ = semicircle_joints(ri, ri, np.linspace(np.pi, 0.0, n + 1))
    x = ji[:, 0]
    je = np.column_stack([x, np.sqrt(np.maximum(re**2 - x**2, 0.0))])
    je[0], je[-1] = [-re, 0.0], [re, 0.0]
    # exact mirror images (the crown joint, for even n, on x = 0)
    ji, je = _mirror_joints(ji[: n // 2 + 1], n), _mirror_joints(je[: n // 2 + 1], n)
    asm = arch_from_joints(ji, je, depth, unit_weight, height, meta)
    # the end voussoirs: base, the short intrados chord, the vertical joint, the extrados arc
    top = math.atan2(je[1, 1], -je[1, 0])  # extrados angle of joint 1, measured from -x
    m = max(1, math.ceil(top / (math.pi / n)))
    arc = np.linspace(top, 0.0, m + 1)[1:-1]
    left = np.vstack([ji[0], ji[1], je[1], np.column_stack([-re * np.cos(arc), re * np.sin(arc)]), je[0]])
    right = left[::-1] * np.array([-1.0, 1.0])
    d = depth / 2.0
    ends = prisms(np.stack([_at_depth(left, -d), _at_depth(right, -d)]), np.stack([_at_depth(left, d), _at_depth(right, d)]))
    blocks = list(asm.blocks)
    for k, shape in zip((1, n), ends):
        blocks[k] = Block(blocks[k].name, shape, unit_weight, False)
    return Assembly(tuple(blocks), asm.interfaces, asm.meta)


def semicircle_joints(inner_radius: float, outer_radius: float, theta: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Intrados and extrados ends ``(x, z)`` (m) of radial joints of a semicircular ring.

    Parameters
    ----------
    inner_radius, outer_radius : float
        Radii of the intrados and extrados (m), centred at the origin.
    theta : (k,) array_like
        Joint angles (rad) from +x towards +z; the springings are ``pi`` (left) and ``0``
        (right), and the crown ``pi / 2``.

    Returns
    -------
    (k, 2) ndarray, (k, 2) ndarray
        Joint ends on the intrados and on the extrados. Joints at the springings and at the
        crown are snapped to exactly ``z = 0`` and ``x = 0``, so that mirrored joints are
        exact mirror images.
    """
    t = np.asarray(theta, dtype=float)
    c, s = np.cos(t), np.sin(t)
    c[np.isclose(t, np.pi / 2, rtol=0.0, atol=1e-14)] = 0.0
    for edge, sign in ((0.0, 1.0), (np.pi, -1.0)):
        at = np.isclose(t, edge, rtol=0.0, atol=1e-14)
        c[at], s[at] = sign, 0.0
    cs = np.column_stack([c, s])
    return inner_radius * cs, outer_radius * cs


def _mirror_joints(left: np.ndarray, n: int) -> np.ndarray:
    """All ``n + 1`` joint ends of a symmetric arch from those of its left half.

    ``left`` holds the ends of joints ``0 .. n // 2`` (a crown joint, for even ``n``, is the
    last row and lies on ``x = 0``); the right half is their mirror image about x = 0.
    """
    right = left[: (n + 1) // 2][::-1] * np.array([-1.0, 1.0])
    out = np.vstack([left, right])
    assert len(out) == n + 1
    return out


def pointed_arch(
    span: float = 2.0,
    rise: float | None = None,
    thickness: float = 0.2,
    depth: float = 0.25,
    voussoirs: int = 14,
    centre_offset: float | None = None,
    unit_weight: float = 20.0,
    pier_height: float | None = None,
    rings: Rings = 1,
    stagger: bool = False,
    backing: Backing | None = None,
) -> Assembly:
    """Pointed (two-centred) arch on two support blocks (piers).

    Each half is a circular arc whose centre lies on the springing line (z = 0) on the
    *other* side of the midspan, at ``x = +-e`` (``e`` the centre offset); ``e = 0`` is the
    semicircular arch and ``e = span / 2`` the equilateral arch. The intrados radius is
    ``R = span / 2 + e`` and the rise ``f = sqrt(span**2 / 4 + span * e)``.

    Parameters
    ----------
    span : float
        Clear span between the intrados springings (m); they lie at ``x = -+span/2, z = 0``.
    rise : float, optional
        Intrados rise at the crown (m), ``>= span / 2``. Give either ``rise`` or
        ``centre_offset``; with neither, ``centre_offset = span / 2`` (equilateral arch).
    thickness : float
        Radial thickness (m); the extrados arcs share the intrados centres.
    depth : float
        Depth along y (m).
    voussoirs : int
        Number of voussoirs (>= 2). Joints are radial to their arc, at equal angles on each
        half. An even number gives a vertical crown joint (where the two arcs meet); an odd
        number gives a keystone across the crown, with chord faces.
    centre_offset : float, optional
        ``e >= 0`` (m), the distance of each centre from the midspan.
    unit_weight : float
        Unit weight (kN/m^3).
    pier_height : float, optional
        Height of the support blocks below the springing joints (m); defaults to the
        thickness. A tall value models an arch on piers.
    rings : int or list of float
        Number of equal rings (default 1: one ring of voussoirs), or the thickness of each
        ring from the intrados out (m), summing to ``thickness`` (:func:`ring_arch`).
    stagger : bool
        With several rings: radial joints staggered by the half-brick rule (True) or aligned
        (False, the default); module docstring.
    backing : Backing, optional
        Backing behind the haunches up to a height above the springing, as blocks or as
        a heavier fill (:mod:`tce.structures.backing`).

    Returns
    -------
    Assembly
        See :func:`arch_from_joints` or :func:`ring_arch`; ``meta["generator"] == "pointed_arch"``.
    """
    check_positive(span=span, thickness=thickness, depth=depth, unit_weight=unit_weight)
    n = check_whole(voussoirs, "voussoirs", 2)
    check_blocks(n + 2, f"voussoirs + 2 supports = {n} + 2")
    s = float(span)
    if rise is not None and centre_offset is not None:
        raise ValueError("give either rise or centre_offset, not both")
    if rise is not None:
        check_positive(rise=rise)
        if rise < s / 2.0:
            raise ValueError(f"rise must be >= span / 2 = {s / 2.0} for a pointed arch, got {rise!r}")
        e = (float(rise) ** 2 - s**2 / 4.0) / s
    else:
        e = s / 2.0 if centre_offset is None else float(centre_offset)
        if not (math.isfinite(e) and e >= 0.0):
            raise ValueError(f"centre_offset must be a finite number >= 0, got {centre_offset!r}")
    R = s / 2.0 + e
    f = math.sqrt(R**2 - e**2)
    t = float(thickness)
    fractions = ring_fractions(rings, t)

    def joints(n: int) -> tuple[np.ndarray, np.ndarray]:
        # left half: arc centred at (+e, 0), angles from pi (left springing) to the crown
        a0, a1 = math.pi, math.atan2(f, -e)
        m = n // 2
        frac = np.arange(m + 1) / (n / 2.0)
        ang = a0 + (a1 - a0) * frac
        ji = np.column_stack([e + R * np.cos(ang), R * np.sin(ang)])
        je = np.column_stack([e + (R + t) * np.cos(ang), (R + t) * np.sin(ang)])
        ji[0] = [-s / 2.0, 0.0]
        je[0] = [-s / 2.0 - t, 0.0]
        if n % 2 == 0:  # vertical crown joint where the two arcs meet
            ji[-1] = [0.0, f]
            je[-1] = [0.0, math.sqrt((R + t) ** 2 - e**2)]
        return _mirror_joints(ji, n), _mirror_joints(je, n)

    h = t if pier_height is None else pier_height
    meta = dict(generator="pointed_arch", span=s, rise=f, centre_offset=e, radius=R, thickness=t, depth=float(depth),
                voussoirs=n, unit_weight=float(unit_weight), pier_height=float(h))
    return _rings_or_one(joints, n, fractions, rings, stagger, depth, unit_weight, h, meta, backing)


def segmental_arch(
    span: float = 2.0,
    rise: float = 0.5,
    thickness: float = 0.2,
    depth: float = 0.25,
    voussoirs: int = 12,
    unit_weight: float = 20.0,
    pier_height: float | None = None,
    rings: Rings = 1,
    stagger: bool = False,
    backing: Backing | None = None,
) -> Assembly:
    """Segmental (circular, less than a semicircle) arch on two skewback supports.

    The intrados is the circular arc through the springings ``(-+span/2, 0)`` and the
    crown ``(0, rise)``: radius ``R = (span**2 / 4 + rise**2) / (2 rise)``, centre
    ``(0, rise - R)`` (below the springing line unless ``rise = span / 2``). Joints are
    radial, at equal angles; the springing joints are inclined, and each support block is
    the prism under its springing joint (a skewback), with a horizontal base.

    Parameters
    ----------
    span : float
        Clear span between the intrados springings (m).
    rise : float
        Intrados rise (m), ``0 < rise <= span / 2``.
    thickness : float
        Radial thickness (m).
    depth : float
        Depth along y (m).
    voussoirs : int
        Number of voussoirs (>= 1).
    unit_weight : float
        Unit weight (kN/m^3).
    pier_height : float, optional
        Height of the support blocks below the lower end of their springing joint (m);
        defaults to the thickness. A tall value models an arch on piers.
    rings : int or list of float
        Number of equal rings (default 1: one ring of voussoirs), or the thickness of each
        ring from the intrados out (m), summing to ``thickness`` (:func:`ring_arch`).
    stagger : bool
        With several rings: radial joints staggered by the half-brick rule (True) or aligned
        (False, the default); module docstring.
    backing : Backing, optional
        Backing behind the haunches up to a height above the springing, as blocks or as
        a heavier fill (:mod:`tce.structures.backing`).

    Returns
    -------
    Assembly
        See :func:`arch_from_joints` or :func:`ring_arch`; ``meta["generator"] == "segmental_arch"``.
    """
    check_positive(span=span, rise=rise, thickness=thickness, depth=depth, unit_weight=unit_weight)
    n = check_whole(voussoirs, "voussoirs")
    check_blocks(n + 2, f"voussoirs + 2 supports = {n} + 2")
    s, f, t = float(span), float(rise), float(thickness)
    if f > s / 2.0 * (1.0 + 1e-12):
        raise ValueError(f"rise must be <= span / 2 = {s / 2.0} for a segmental arch, got {rise!r}")
    R = (s**2 / 4.0 + f**2) / (2.0 * f)
    zc = f - R
    half = math.atan2(s / 2.0, -zc)  # half opening angle, measured from the vertical
    fractions = ring_fractions(rings, t)

    def joints(n: int) -> tuple[np.ndarray, np.ndarray]:
        ang = np.linspace(math.pi / 2.0 + half, math.pi / 2.0 - half, n + 1)
        c, sn = np.cos(ang), np.sin(ang)
        ji = np.column_stack([R * c, zc + R * sn])
        je = np.column_stack([(R + t) * c, zc + (R + t) * sn])
        ji[0], ji[-1] = [-s / 2.0, 0.0], [s / 2.0, 0.0]
        return ji, je

    h = t if pier_height is None else pier_height
    meta = dict(generator="segmental_arch", span=s, rise=f, radius=R, thickness=t, depth=float(depth), voussoirs=n,
                unit_weight=float(unit_weight), pier_height=float(h))
    return _rings_or_one(joints, n, fractions, rings, stagger, depth, unit_weight, h, meta, backing)


def semicircular_arch_on_piers(
    inner_radius: float = 1.0,
    thickness: float = 0.2,
    depth: float = 0.25,
    voussoirs: int = 14,
    pier_height: float = 1.0,
    unit_weight: float = 20.0,
    rings: Rings = 1,
    stagger: bool = False,
    backing: Backing | None = None,
) -> Assembly:
    """The semicircular arch of :func:`semicircular_arch` on two piers ``pier_height`` tall (m),
    of one ring or of several (``rings``, ``stagger``: :func:`semicircular_arch`), with a
    ``backing`` (:func:`semicircular_arch`).

    The piers are the support blocks (their motion is prescribed, their equilibrium is not
    checked); ``meta["generator"] == "semicircular_arch_on_piers"``.
    """
    check_positive(pier_height=pier_height)
    asm = semicircular_arch(inner_radius, thickness, depth, voussoirs, unit_weight, pier_height, rings=rings,
                            stagger=stagger, backing=backing)
    meta = dict(asm.meta, generator="semicircular_arch_on_piers", pier_height=float(pier_height))
    meta.pop("support_height", None)
    return Assembly(asm.blocks, asm.interfaces, meta)
