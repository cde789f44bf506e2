"""Transformations of a whole scene, for the metamorphic relations of the battery.

A :class:`Similarity` maps a point ``x`` to ``s Q x + d`` and a force ``F`` to ``f Q F``:
``Q`` an orthogonal matrix that keeps the vertical (a rotation about z, possibly composed
with a mirror in a vertical plane), ``d`` a translation (in the new units), ``s`` the length
factor and ``f`` the force factor of a change of units (m, kN -> mm, N is ``s = f = 1000``).
Gravity stays along -z, so every answer of tce must transform with the scene:

- lambda_max, outcomes and statuses do not change (lambda is dimensionless);
- reactions, wrenches about the support centroids: forces ``f Q F``, moments
  ``det(Q) f s Q M`` (a moment is a pseudovector: a mirror reverses it);
- support motions (about the support's centroid): ``s Q u`` and ``det(Q) Q omega``;
- material: friction unchanged, strengths and cohesion (kN/m^2) times ``f / s^2``,
  stiffnesses per unit area (kN/m^3) times ``f / s^3``; unit weights times ``f / s^3``.

Also :func:`permuted`: the same assembly with its blocks (and interfaces) listed in another
order, some interfaces read from the other side (``a`` and ``b`` swapped, the normal
reversed). Everything here is written from ``docs/conventions.md`` with numpy alone; it
builds tce's data classes but uses none of tce's geometry (``Assembly.scaled`` included),
so that the relations test tce rather than this module. Its own checks are in
``test_transform.py`` (volumes and centroids against closed forms).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace

import numpy as np
from numpy.typing import ArrayLike, NDArray

from tce.core.loads import DistributedLoad, LoadPattern, PointLoad
from tce.core.material import Material
from tce.structures.assembly import Assembly, Block, Interface
from tce.structures.geometry import Polyhedron

__all__ = ["Similarity", "permuted"]


def _rotation(degrees: float) -> NDArray[np.float64]:
    """Rotation about +z by ``degrees`` (exact for multiples of 90)."""
    if float(degrees) % 90.0 == 0.0:
        k = int(round(float(degrees) / 90.0)) % 4
        c, s = ((1, 0), (0, 1), (-1, 0), (0, -1))[k]
    else:
        a = math.radians(degrees)
        c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]], dtype=float)


@dataclass(frozen=True)
class Similarity:
    """``x -> length * Q x + shift``, forces ``F -> force * Q F`` (module docstring).

    Parameters
    ----------
    Q : (3, 3) array_like
        Orthogonal, with ``Q e_z = e_z``.
    shift : (3,) array_like
        Translation, in the new units.
    length, force : float
        Unit factors (new unit per old unit of length and of force).
    """

    Q: NDArray[np.float64] = field(default_factory=lambda: np.eye(3))
    shift: NDArray[np.float64] = field(default_factory=lambda: np.zeros(3))
    length: float = 1.0
    force: float = 1.0

    def __post_init__(self) -> None:
        Q = np.asarray(self.Q, dtype=float)
        assert np.allclose(Q.T @ Q, np.eye(3), atol=1e-14) and np.allclose(Q[:, 2], [0, 0, 1], atol=1e-14), Q
        object.__setattr__(self, "Q", Q)
        object.__setattr__(self, "shift", np.asarray(self.shift, dtype=float).reshape(3))

    # ------------------------------------------------------------------ constructors
    @classmethod
    def rotation(cls, degrees: float) -> Similarity:
        """Rotation about the z axis by ``degrees`` (from +x towards +y)."""
        return cls(Q=_rotation(degrees))

    @classmethod
    def mirror(cls, degrees: float = 0.0) -> Similarity:
        """Reflection in the vertical plane through the origin whose normal is at ``degrees``
        from +x (0: x -> -x)."""
        a = math.radians(degrees)
        m = np.array([math.cos(a), math.sin(a), 0.0]) if degrees % 90 else _rotation(degrees)[:, 0]
        return cls(Q=np.eye(3) - 2.0 * np.outer(m, m))

    @classmethod
    def translation(cls, shift: ArrayLike) -> Similarity:
        """A rigid translation by ``shift`` (m)."""
        return cls(shift=np.asarray(shift, dtype=float))

    @classmethod
    def units(cls, length: float, force: float) -> Similarity:
        """A change of units: lengths times ``length``, forces times ``force``."""
        return cls(length=length, force=force)

    # ------------------------------------------------------------------ geometry
    @property
    def det(self) -> float:
        """+1 for a rotation, -1 when a mirror is part of the map."""
        return float(round(np.linalg.det(self.Q)))

    def points(self, x: ArrayLike) -> NDArray[np.float64]:
        """Points ``(..., 3)`` in the new scene."""
        return self.length * (np.asarray(x, dtype=float) @ self.Q.T) + self.shift

    def directions(self, v: ArrayLike) -> NDArray[np.float64]:
        """Unit vectors ``(..., 3)`` (normals, directions)."""
        return np.asarray(v, dtype=float) @ self.Q.T

    def forces(self, F: ArrayLike) -> NDArray[np.float64]:
        """Forces ``(..., 3)`` (kN in the old units)."""
        return self.force * self.directions(F)

    def moments(self, M: ArrayLike) -> NDArray[np.float64]:
        """Moments ``(..., 3)``: pseudovectors, reversed by a mirror."""
        return self.det * self.force * self.length * self.directions(M)

    def wrenches(self, W: ArrayLike) -> NDArray[np.float64]:
        """Wrenches ``(..., 6)`` ``(F, M)`` about a point that moves with the scene."""
        W = np.asarray(W, dtype=float)
        return np.concatenate([self.forces(W[..., :3]), self.moments(W[..., 3:])], axis=-1)

    def alpha(self, degrees: float) -> float:
        """The direction of a horizontal load at ``degrees`` from +x, after the map (degrees)."""
        a = math.radians(degrees)
        v = self.Q @ np.array([math.cos(a), math.sin(a), 0.0])
        out = math.degrees(math.atan2(v[1], v[0]))
        if abs(out - round(out)) < 1e-9:  # whole degrees exactly (multiples of 90 above all)
            out = float(round(out))
        return out + 0.0  # -0 -> 0

    # ------------------------------------------------------------------ scene
    def assembly(self, asm: Assembly) -> Assembly:
        """The assembly in the new scene: vertices mapped, faces reversed by a mirror (to stay
        counter-clockwise seen from outside), unit weights in the new units; interface
        normals mapped (explicitly: a mirror reverses the Newell normal of the points)."""
        flip = self.det < 0
        blocks = tuple(
            Block(
                b.name,
                Polyhedron(self.points(b.shape.vertices), [tuple(reversed(f)) if flip else f for f in b.shape.faces]),
                b.unit_weight * self.force / self.length**3,
                b.support,
            )
            for b in asm.blocks
        )
        interfaces = tuple(
            Interface(i.a, i.b, self.points(i.points), self.directions(i.normal), i.stiffness, i.kind)
            for i in asm.interfaces
        )
        return Assembly(blocks, interfaces, dict(asm.meta))

    def settlements(self, sett: Mapping[str, ArrayLike] | None) -> dict[str, list[float]]:
        """Support motions ``(u, omega)`` in the new scene (rotations are pseudovectors)."""
        out = {}
        for name, v in (sett or {}).items():
            v = np.asarray(v, dtype=float)
            out[name] = [float(x) for x in (*(self.length * self.directions(v[:3])), *(self.det * self.directions(v[3:])))]
        return out

    def material(self, mat: Material) -> Material:
        """The material in the new units (the laws of its interface kinds too)."""
        stress, stiffness = self.force / self.length**2, self.force / self.length**3
        return replace(
            mat,
            normal_stiffness=None if mat.normal_stiffness is None else mat.normal_stiffness * stiffness,
            shear_stiffness=None if mat.shear_stiffness is None else mat.shear_stiffness * stiffness,
            cohesion=mat.cohesion * stress,
            tensile_strength=mat.tensile_strength * stress,
            compressive_strength=None if mat.compressive_strength is None else mat.compressive_strength * stress,
            interfaces={kind: self.material(law) for kind, law in mat.interfaces},
        )

    def plan(self, xy: Sequence[float]) -> tuple[float, float]:
        """A plan point ``(x, y)`` in the new scene."""
        p = self.points([xy[0], xy[1], 0.0])
        return float(p[0]), float(p[1])

    def _rectangle(self, x: Sequence[float], y: Sequence[float]) -> tuple[tuple[float, float], tuple[float, float]]:
        """A plan rectangle in the new scene: only maps that keep the axes (multiples of 90)."""
        assert np.all(np.isin(self.Q[:2, :2], (-1.0, 0.0, 1.0))), "a rotated rectangle is not a plan rectangle"
        corners = np.array([self.plan((a, b)) for a in x for b in y])
        lo, hi = corners.min(axis=0), corners.max(axis=0)
        return (float(lo[0]), float(hi[0])), (float(lo[1]), float(hi[1]))

    def pattern(self, p: LoadPattern) -> LoadPattern:
        """A load pattern in the new scene (distributed loads need their ``y`` range and a
        map that keeps the axes)."""
        point = []
        for q in p.point:
            if q.on_top is not None:
                point.append(replace(q, force=tuple(self.forces(q.force)), on_top=self.plan(q.on_top)))
            else:
                at = None if q.at is None else tuple(self.points(q.at))
                point.append(replace(q, force=tuple(self.forces(q.force)), at=at))
        distributed = []
        for d in p.distributed:
            assert d.y is not None, "give the y range: the default (the whole depth) follows the scene's axes"
            x, y = self._rectangle(d.x, d.y)
            distributed.append(replace(d, x=x, y=y, pressure=d.pressure * self.force / self.length**2))
        return replace(p, alpha=self.alpha(p.alpha), point=tuple(point), distributed=tuple(distributed))


def permuted(asm: Assembly, order: Sequence[int], interface_order: Sequence[int] | None = None,
             swap: Sequence[bool] | None = None) -> Assembly:
    """The same assembly listed in another order.

    Parameters
    ----------
    order : sequence of int
        Block ``k`` of the result is block ``order[k]`` of ``asm``.
    interface_order : sequence of int, optional
        Interface ``k`` of the result is interface ``interface_order[k]`` of ``asm``.
    swap : sequence of bool, optional
        Per interface of ``asm``: read it from the other side (``a``, ``b`` swapped, the
        normal reversed, the polygon listed the other way round).
    """
    order = list(order)
    assert sorted(order) == list(range(len(asm.blocks)))
    new_index = {old: new for new, old in enumerate(order)}
    ni = len(asm.interfaces)
    interface_order = list(range(ni)) if interface_order is None else list(interface_order)
    swap = [False] * ni if swap is None else list(swap)
    interfaces = []
    for k in interface_order:
        i = asm.interfaces[k]
        a, b = new_index[i.a], new_index[i.b]
        if swap[k]:
            interfaces.append(Interface(b, a, i.points[::-1], -np.asarray(i.normal), i.stiffness, i.kind))
        else:
            interfaces.append(Interface(a, b, i.points, i.normal, i.stiffness, i.kind))
    return Assembly(tuple(asm.blocks[k] for k in order), tuple(interfaces), dict(asm.meta))
