"""Loads on an assembly: a declaration, its resolution into block wrenches, and the two
right-hand sides the solvers take.

Every solver of tce takes the loads as ``rhs = b_fixed + lam * b_live`` in the row layout of
``A_eq`` (:mod:`tce.core.model`): ``b_fixed`` is always applied, ``b_live`` is multiplied by the
load multiplier ``lam``. A :class:`LoadPattern` declares them:

- the self-weight of every block (always part of ``b_fixed``);
- the paper's lateral pattern, ``lam`` times every block's weight horizontally in direction
  ``alpha`` (degrees from +x towards +y) at its centroid, part of ``b_live`` when ``lateral``
  (:class:`LoadPattern`; :attr:`LoadPattern.multiplies` says it in words);
- point loads (:class:`PointLoad`), distributed loads (:class:`DistributedLoad`) and
  vehicles (:mod:`tce.core.vehicles`), each fixed (``scaled = False``: part of ``b_fixed``)
  or live (``scaled = True``, the default: part of ``b_live``);
- a fill (:mod:`tce.core.fill`): its weight and at-rest pressure are fixed.

:func:`resolve` turns a pattern into applied point forces on one assembly
(:class:`AppliedLoads`): a force ``f`` at ``p`` on block ``i`` adds the wrench
``(f, (p - c_i) x f)`` about the block's centroid ``c_i``; a distributed load is shared among
the blocks whose exposed top surfaces lie under its rectangle, each part's resultant at the
plan centroid of the part. :meth:`AppliedLoads.vectors` projects the wrenches on a model's
rows: 6 per free block ``(Fx, Fy, Fz, Mx, My, Mz)`` (spatial), or ``(e . F, z . F, m . M)``
(planar, ``m`` the plane normal and ``e = m x z``). The planar model is exact for a scene
only when every block's load wrench lies in the plane (no force along ``m``, no moment
about ``e`` or ``z``, :meth:`AppliedLoads.in_plane`).

Loads on support blocks are refused: the equilibrium of a support is not enforced, so such a
load would be lost without a word. Errors are :class:`LoadError` naming the key of the
declaration (``point[0].block``; a study adds ``loads.``) and the fix.
"""

from __future__ import annotations

import logging
import weakref
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from functools import cached_property, lru_cache
from typing import Any

import numpy as np
import shapely
from numpy.typing import ArrayLike, NDArray

from ..structures.assembly import Assembly
from ..structures.geometry import lateral_direction
from ..messages import did_you_mean
from .model import EZ, Model, Plane, motions_in_plane
from .fill import Fill, fill_forces
from .surface import LoadError, _on_top, _upward_faces, _vector, top_surface
from .vehicles import Vehicle, wheel_loads


__all__ = [
    "AppliedLoads",
    "DistributedLoad",
    "LoadError",
    "LoadPattern",
    "PointLoad",
    "as_pattern",
    "check_in_plane",
    "load_vectors",
    "resolve",
    "scene_vectors",
    "top_surface",
]

log = logging.getLogger(__name__)

PLANE_TOL = 1e-9


def _check_bool(value: object, key: str) -> None:
    """Refuse anything but True or False for the switch ``key``."""
    if not isinstance(value, bool):
        raise LoadError(key, f"not true or false ({value!r})", "write true or false")


def _check_keys(cls: type, data: Mapping[str, Any]) -> None:
    """Refuse a key of ``data`` that is not a field of the dataclass ``cls``."""
    unknown = sorted(set(data) - set(cls.__dataclass_fields__))
    if unknown:
        raise LoadError(unknown[0], "unknown key", f"use the keys {list(cls.__dataclass_fields__)}")


def _range(value: ArrayLike, key: str) -> tuple[float, float]:
    """A plan range ``[lo, hi]`` with ``lo < hi`` (m)."""
    lo, hi = _vector(value, 2, key, "m, [from, to]")
    if not lo < hi:
        raise LoadError(key, f"[{lo:g}, {hi:g}] is empty", "give [from, to] with from < to (m)")
    return lo, hi


@dataclass(frozen=True)
class PointLoad:
    """A force at a point of a free block.

    Parameters
    ----------
    force : (3,) array_like
        kN, global frame; not zero.
    block : str, optional
        The free block it acts on, by name (with ``at``).
    at : (3,) array_like, optional
        Point of application (m); default: the block's centroid. Within the block's size
        (bounding-box diagonal) of its centroid.
    on_top : (2,) array_like, optional
        Plan point ``(x, y)`` (m) instead of ``block``/``at``: the load acts on the highest
        top surface of the structure above it (:func:`resolve`).
    scaled : bool
        True (default): part of the live load, multiplied by lambda; False: always applied.
    """

    force: tuple[float, float, float]
    block: str | None = None
    at: tuple[float, float, float] | None = None
    on_top: tuple[float, float] | None = None
    scaled: bool = True

    def __post_init__(self) -> None:
        force = _vector(self.force, 3, "force", "kN, global frame")
        if not any(force):
            raise LoadError("force", "a zero force", "give a non-zero force (kN, global frame)")
        object.__setattr__(self, "force", force)
        if (self.block is None) == (self.on_top is None):
            raise LoadError(
                "", "give either block (with an optional at) or on_top",
                "name the free block it acts on, or give on_top = [x, y] to find it on the top surface",
            )
        if self.block is not None and not (isinstance(self.block, str) and self.block):
            raise LoadError("block", f"not a block name ({self.block!r})", "give a block name")
        if self.at is not None:
            if self.block is None:
                raise LoadError("at", "at goes with block, not with on_top", "remove at (on_top finds the point)")
            object.__setattr__(self, "at", _vector(self.at, 3, "at", "m"))
        if self.on_top is not None:
            object.__setattr__(self, "on_top", _vector(self.on_top, 2, "on_top", "m, plan point [x, y]"))
        _check_bool(self.scaled, "scaled")

    def to_dict(self) -> dict[str, Any]:
        """Plain data, the keys of a ``[[loads.point]]`` table (absent keys left out)."""
        out: dict[str, Any] = {"force": list(self.force), "scaled": self.scaled}
        for key in ("block", "at", "on_top"):
            value = getattr(self, key)
            if value is not None:
                out[key] = list(value) if isinstance(value, tuple) else value
        return out


@dataclass(frozen=True)
class DistributedLoad:
    """A pressure on the exposed top surfaces of the blocks under a plan rectangle.

    Parameters
    ----------
    x : (2,) array_like
        Plan range along x (m), ``from < to``.
    pressure : float
        kN/m^2 of plan area, acting downwards (negative: upwards); not zero.
    y : (2,) array_like, optional
        Plan range along y (m); default: the whole depth of the structure.
    scaled : bool
        True (default): part of the live load; False: always applied (e.g. fill weight).
    """

    x: tuple[float, float]
    pressure: float
    y: tuple[float, float] | None = None
    scaled: bool = True

    def __post_init__(self) -> None:
        object.__setattr__(self, "x", _range(self.x, "x"))
        if self.y is not None:
            object.__setattr__(self, "y", _range(self.y, "y"))
        (p,) = _vector([self.pressure], 1, "pressure", "kN/m^2")
        if p == 0.0:
            raise LoadError("pressure", "a zero pressure", "give a non-zero pressure (kN/m^2, downwards)")
        object.__setattr__(self, "pressure", p)
        _check_bool(self.scaled, "scaled")

    def to_dict(self) -> dict[str, Any]:
        """Plain data, the keys of a ``[[loads.distributed]]`` table."""
        out: dict[str, Any] = {"x": list(self.x), "pressure": self.pressure, "scaled": self.scaled}
        if self.y is not None:
            out["y"] = list(self.y)
        return out


def _items(cls: type, values: Sequence[Any], key: str) -> tuple[Any, ...]:
    """``values`` (instances or dicts of keyword arguments) as a tuple of ``cls``; errors
    named ``key[k]``."""
    out = []
    for k, v in enumerate(values):
        try:
            if isinstance(v, cls):
                out.append(v)
            elif isinstance(v, Mapping):
                _check_keys(cls, v)
                out.append(cls(**v))
            else:
                raise LoadError("", f"not a {cls.__name__} ({v!r})", f"give a {cls.__name__} or a table of its keys")
        except LoadError as exc:
            raise exc.within(f"{key}[{k}]") from None
        except TypeError as exc:  # a missing required key
            raise LoadError(f"{key}[{k}]", str(exc), "give the required keys (docs/studies.md)") from None
    return tuple(out)


@dataclass(frozen=True)
class LoadPattern:
    """The loads of a scene: what is always applied and what lambda multiplies.

    Parameters
    ----------
    alpha : float
        Direction of the lateral pattern (degrees, from +x towards +y).
    lateral : bool or None
        True: lambda multiplies every block's weight horizontally in direction ``alpha``
        (the paper's pattern) besides the scaled loads; False: lambda multiplies only the
        scaled loads (then at least one is needed). None (default): True when the pattern
        has no scaled (live) point load, distributed load or vehicle, else False: a live
        load declared alone is what lambda multiplies, and the lateral pattern is added to
        it only when asked for. Stored resolved (a bool) after construction.
    point : sequence of PointLoad (or dicts of its keys)
    distributed : sequence of DistributedLoad (or dicts of its keys)
    vehicle : sequence of :class:`tce.core.vehicles.Vehicle` (or dicts of its keys)
        Axle groups moving as one (:mod:`tce.core.vehicles`); wheels off the deck are
        dropped with one note per vehicle (:attr:`AppliedLoads.notes`); a vehicle with no
        wheel on the deck is an error (:func:`resolve`).
    fill : :class:`tce.core.fill.Fill` (or a dict of its keys), optional
        Fill over the top surface: its weight and at-rest pressure (fixed loads), and the
        dispersion of the vehicles' wheel loads through it (:mod:`tce.core.fill`).

    A pattern with only ``alpha`` (``lateral`` true, no loads) is the default pattern: the
    right-hand sides are exactly the model's ``b_dead`` and ``b_lateral(alpha)``. Patterns
    are hashable values (results and caches key on them).
    """

    alpha: float = 0.0
    lateral: bool | None = None
    point: tuple[PointLoad, ...] = ()
    distributed: tuple[DistributedLoad, ...] = ()
    vehicle: tuple[Vehicle, ...] = ()
    fill: Fill | None = None

    def __post_init__(self) -> None:
        if self.fill is not None and not isinstance(self.fill, Fill):
            try:
                (fill,) = _items(Fill, [self.fill], "fill")
            except LoadError as exc:  # one table: fill.depth, not fill[0].depth
                raise LoadError(exc.key.replace("fill[0]", "fill", 1), exc.problem, exc.fix) from None
            object.__setattr__(self, "fill", fill)

        (alpha,) = _vector([self.alpha], 1, "alpha", "degrees")
        object.__setattr__(self, "alpha", alpha)
        if self.lateral is not None:
            _check_bool(self.lateral, "lateral")
        object.__setattr__(self, "point", _items(PointLoad, self.point, "point"))
        object.__setattr__(self, "distributed", _items(DistributedLoad, self.distributed, "distributed"))
        object.__setattr__(self, "vehicle", _items(Vehicle, self.vehicle, "vehicle"))
        if self.lateral is None:
            object.__setattr__(self, "lateral", not self.live_loads)
        if not self.lateral and not any(p.scaled for p in (*self.point, *self.distributed, *self.vehicle)):
            raise LoadError(
                "lateral", "lateral = false and no scaled load: lambda would multiply nothing",
                "add a point or distributed load or a vehicle with scaled = true, or set lateral = true",
            )

    @property
    def default(self) -> bool:
        """True for the paper's pattern alone (self-weight and the lateral pattern)."""
        return self.lateral and not self.point and not self.distributed and not self.vehicle and self.fill is None

    @property
    def live_loads(self) -> list[str]:
        """The declared live (scaled) loads in words, in declaration order: ``vehicle
        'LM1' (600 kN)``, ``point[0] (10 kN)``, ``distributed[1] (5 kN/m^2)``."""
        out = [f"vehicle {v.label!r} ({v.total:g} kN)" for v in self.vehicle if v.scaled]
        out += [f"point[{k}] ({float(np.linalg.norm(p.force)):g} kN)" for k, p in enumerate(self.point) if p.scaled]
        out += [f"distributed[{k}] ({d.pressure:g} kN/m^2)" for k, d in enumerate(self.distributed) if d.scaled]
        return out

    @property
    def multiplies(self) -> str:
        """What lambda multiplies and what is applied fixed, in words (``tce show``, the
        report, the results' ``lambda_multiplies``)."""
        live = self.live_loads
        if self.lateral:
            live.append(f"the lateral load lambda*W (every block's weight, horizontal) in direction alpha = {self.alpha:g} "
                        "degrees")
        fixed = ["self-weight"]
        if self.fill is not None and self.fill.weight:
            fixed.append("fill weight")
        if self.fill is not None and self.fill.k0:
            fixed.append("fill at-rest pressure")
        fixed += [f"point[{k}]" for k, p in enumerate(self.point) if not p.scaled]
        fixed += [f"distributed[{k}]" for k, d in enumerate(self.distributed) if not d.scaled]
        fixed += [f"vehicle {v.label!r}" for v in self.vehicle if not v.scaled]
        return f"lambda multiplies {' and '.join(live)}; fixed: {', '.join(fixed)}"

    @property
    def direction(self) -> float:
        """``alpha`` when the lateral pattern is part of the live load, else NaN."""
        return self.alpha if self.lateral else float("nan")

    @property
    def reference_x(self) -> float:
        """Plan abscissa (m) of the moving group's reference: the first scaled vehicle's
        reference point, else the first scaled ``on_top`` point load (NaN: nothing moves)."""
        for v in self.vehicle:
            if v.scaled:
                return v.x
        for p in self.point:
            if p.scaled and p.on_top is not None:
                return p.on_top[0]
        return float("nan")

    def moved(self, x: float) -> LoadPattern:
        """The pattern with its moving loads (the scaled vehicles and the scaled ``on_top``
        point loads) moved as one rigid group, its reference (:attr:`reference_x`) to plan
        abscissa ``x`` (m): every moving load keeps its offset from the reference, so
        loads declared at different positions never merge.

        Raises
        ------
        LoadError
            Nothing to move.
        """
        ref = self.reference_x
        if ref != ref:
            raise LoadError(
                "point", "no scaled point load with on_top and no scaled vehicle to move",
                "give a point load with on_top = [x, y] and scaled = true, or a vehicle",
            )
        (x,) = _vector([x], 1, "load_x", "m")
        dx = x - ref
        point = tuple(
            replace(p, on_top=(p.on_top[0] + dx, p.on_top[1])) if p.scaled and p.on_top is not None else p
            for p in self.point
        )
        vehicle = tuple(v.at(v.x + dx) if v.scaled else v for v in self.vehicle)
        return replace(self, point=point, vehicle=vehicle)

    def to_dict(self) -> dict[str, Any]:
        """Plain data (JSON-ready), the keys of a study's ``[loads]`` table."""
        out = {
            "alpha": self.alpha,
            "lateral": self.lateral,
            "point": [p.to_dict() for p in self.point],
            "distributed": [d.to_dict() for d in self.distributed],
        }
        if self.vehicle:  # absent otherwise: a pattern without vehicles keeps its plain data
            out["vehicle"] = [v.to_dict() for v in self.vehicle]
        if self.fill is not None:
            out["fill"] = self.fill.to_dict()
        return out

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> LoadPattern:
        """Inverse of :meth:`to_dict` (missing keys take their defaults).

        Raises
        ------
        LoadError
            An unknown key or a load that cannot be declared.
        """
        _check_keys(cls, data)
        return cls(**data)


def as_pattern(alpha: float | None = None, loads: LoadPattern | None = None) -> LoadPattern:
    """The load pattern of a call that takes ``alpha`` or ``loads``: ``loads`` when given,
    else the default pattern in direction ``alpha`` (0 when None).

    Raises
    ------
    ValueError
        Both given with different directions, a non-finite ``alpha``, or ``loads`` that is
        not a :class:`LoadPattern`.
    """
    if loads is None:
        return LoadPattern(alpha=0.0 if alpha is None else alpha)
    if not isinstance(loads, LoadPattern):
        raise TypeError(f"loads must be a LoadPattern, got {type(loads).__name__}")
    if alpha is not None and alpha != loads.alpha:
        raise ValueError(
            f"alpha={alpha!r} and loads with alpha={loads.alpha!r}: give the direction once, in the pattern"
        )
    return loads


# ---------------------------------------------------------------------------- resolution
@dataclass(frozen=True, eq=False)
class AppliedLoads:
    """A :class:`LoadPattern` resolved against one assembly: the point forces it applies.

    Attributes
    ----------
    pattern : LoadPattern
    assembly : Assembly
    blocks : (k,) int
        Block of each applied force.
    points : (k, 3) float
        Points of application (m): the declared point, the point found on the top surface
        (``on_top``), or the part's resultant point of a distributed load (on the face,
        above the part's plan centroid).
    forces : (k, 3) float
        Forces (kN, global frame); a scaled force is the one at lambda = 1.
    scaled : (k,) bool
        True for the live loads.
    sources : tuple of str
        The declaration each force comes from (``point[0]``, ``distributed[1]``,
        ``vehicle[0].axle[1].wheel[0]``).
    notes : tuple of str
        One line per vehicle with wheels (or parts of contact patches) dropped because they
        lie off the deck (:func:`tce.core.vehicles.wheel_loads`).
    """

    pattern: LoadPattern
    assembly: Assembly = field(repr=False)
    blocks: NDArray[np.int64] = field(repr=False)
    points: NDArray[np.float64] = field(repr=False)
    forces: NDArray[np.float64] = field(repr=False)
    scaled: NDArray[np.bool_] = field(repr=False)
    sources: tuple[str, ...] = field(repr=False)
    notes: tuple[str, ...] = field(default=(), repr=False)

    @cached_property
    def wrenches(self) -> NDArray[np.float64]:
        """``(2, n_blocks, 6)``: the fixed (0) and live (1) loads on every block as wrenches
        ``(Fx, Fy, Fz, Mx, My, Mz)`` about its centroid (kN, kN m), self-weight and lateral
        pattern excluded."""
        out = np.zeros((2, len(self.assembly.blocks), 6))
        r = self.points - self.assembly.centroids[self.blocks]
        w = np.hstack([self.forces, np.cross(r, self.forces)])
        np.add.at(out, (self.scaled.astype(int), self.blocks), w)
        return out

    def in_plane(self, plane: Plane | None) -> bool:
        """Whether the lateral direction (when part of the pattern) and every block's load
        wrench lie in ``plane``: no force along ``m``, no moment about ``e`` or ``z``
        (relative to the weight and size of the assembly). True when ``plane`` is None."""
        if plane is None:
            return True
        if self.pattern.lateral and abs(lateral_direction(self.pattern.alpha) @ plane.m) > 1e-12:
            return False
        if not len(self.blocks):
            return True
        w = self.wrenches
        a = self.assembly
        force = max(a.total_weight, float(np.abs(self.forces).max()))
        out_force = np.abs(w[..., :3] @ plane.m).max()
        out_moment = max(np.abs(w[..., 3:] @ plane.e).max(), np.abs(w[..., 3:] @ EZ).max())
        return bool(out_force <= PLANE_TOL * force and out_moment <= PLANE_TOL * force * a.size)

    @cached_property
    def _vectors(self) -> weakref.WeakKeyDictionary[Model, tuple[NDArray[np.float64], NDArray[np.float64]]]:
        return weakref.WeakKeyDictionary()

    def vectors(self, model: Model) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """``(b_fixed, b_live)`` in ``model``'s row layout (kN, kN m), read-only.

        ``b_fixed`` is the self-weight plus the fixed loads, ``b_live`` the lateral pattern
        (when ``lateral``) plus the scaled loads. For the default pattern they are the
        model's own ``b_dead`` and ``b_lateral(alpha)``.

        Raises
        ------
        ValueError
            ``model`` is not a model of this assembly, or a planar model and the loads
            leave its plane.
        """
        if model.assembly is not self.assembly:
            raise ValueError("these loads were resolved against another assembly than the model's")
        if model in self._vectors:
            return self._vectors[model]
        if model.kind == "planar" and not self.in_plane(model.plane):
            raise ValueError("the loads leave the planar model's plane: use the spatial model")
        p = self.pattern
        b_fixed = model.b_dead
        b_live = model.b_lateral(p.alpha) if p.lateral else np.zeros_like(model.b_dead)
        fixed, live = self.wrenches
        if (~self.scaled).any():
            b_fixed = b_fixed + _block_rows(model, fixed)
        if self.scaled.any() or not p.lateral:
            b_live = b_live + _block_rows(model, live)
        for v in (b_fixed, b_live):
            if v is not model.b_dead and v is not model.b_lateral(p.alpha):  # the model's own stay as they are
                v.flags.writeable = False
        self._vectors[model] = (b_fixed, b_live)
        return b_fixed, b_live


def _block_rows(model: Model, wrenches: NDArray[np.float64]) -> NDArray[np.float64]:
    """Block wrenches ``(n_blocks, 6)`` about the centroids as a vector in ``model``'s row
    layout: 6 rows per free block (spatial) or ``(e . F, z . F, m . M)`` (planar)."""
    w = wrenches[list(model.assembly.free_indices)]
    if model.kind == "spatial":
        return w.ravel()
    plane = model.plane
    return np.column_stack([w[:, :3] @ plane.e, w[:, :3] @ EZ, w[:, 3:] @ plane.m]).ravel()


def _plan_range(assembly: Assembly, axis: int) -> tuple[float, float]:
    v = np.vstack([b.shape.vertices for b in assembly.blocks])[:, axis]
    return float(v.min()), float(v.max())


def _point(assembly: Assembly, load: PointLoad) -> tuple[int, NDArray[np.float64]]:
    """Block and point of application of a point load (raises ``LoadError``)."""
    if load.on_top is not None:
        i, p = _on_top(assembly, load.on_top)
        if assembly.blocks[i].support:
            raise LoadError(
                "on_top", f"[{load.on_top[0]:g}, {load.on_top[1]:g}] lands on support block {assembly.names[i]!r}, "
                "whose equilibrium is not enforced", "give a plan point above a free block",
            )
        return i, p
    if load.block not in assembly.index:
        free = [assembly.names[i] for i in assembly.free_indices]
        raise LoadError("block", f"{load.block!r} is not a block of the structure",
                        f"use one of the free blocks {free}{did_you_mean(load.block, free)}")
    i = assembly.index[load.block]
    b = assembly.blocks[i]
    if b.support:
        raise LoadError("block", f"{load.block!r} is a support block, whose equilibrium is not enforced",
                        f"load a free block: {[assembly.names[k] for k in assembly.free_indices]}")
    if load.at is None:
        return i, b.centroid.copy()
    p = np.array(load.at)
    dist = float(np.linalg.norm(p - b.centroid))
    if dist > b.shape.size:
        raise LoadError(
            "at", f"{list(load.at)} is {dist:.4g} m from the centroid of block {load.block!r}, more than the block's "
            f"size ({b.shape.size:.4g} m)", "give a point on the block (m, global frame)",
        )
    return i, p


def _distributed(assembly: Assembly, load: DistributedLoad) -> list[tuple[int, NDArray[np.float64], float]]:
    """``(block, point, area)`` of each part of a distributed load (raises ``LoadError``)."""
    y = load.y if load.y is not None else _plan_range(assembly, 1)
    rect = shapely.box(load.x[0], y[0], load.x[1], y[1])
    faces = _upward_faces(assembly)
    eps = (1e-9 * assembly.size) ** 2
    parts = []
    for block, face, poly in top_surface(assembly):
        part = rect.intersection(poly)
        for piece in getattr(part, "geoms", [part]):
            if not isinstance(piece, shapely.Polygon) or piece.area <= eps:
                continue
            if assembly.blocks[block].support:
                raise LoadError(
                    "x", f"the rectangle x = {list(load.x)}, y = {list(y)} covers the top of support block "
                    f"{assembly.names[block]!r}, whose equilibrium is not enforced",
                    "narrow x (or y) to the free blocks",
                )
            c = piece.centroid
            parts.append((block, np.array([c.x, c.y, float(faces.z(face, c.x, c.y))]), float(piece.area)))
    if not parts:
        raise LoadError("x", f"the rectangle x = {list(load.x)}, y = {list(y)} covers no block's top surface",
                        "give a plan rectangle over the structure")
    return parts


@lru_cache(maxsize=256)
def resolve(pattern: LoadPattern, assembly: Assembly) -> AppliedLoads:
    """The forces a pattern applies to ``assembly`` (see module docstring); cached.

    Raises
    ------
    LoadError
        An unknown block, a support block, ``at`` farther than the block's size from its
        centroid, ``on_top`` outside the plan or over a support, a distributed rectangle
        that covers no top surface or covers a support's, a vehicle none of whose wheels
        lands on the deck (:class:`tce.core.vehicles.OffDeck`).
    """
    blocks, points, forces, scaled, sources = [], [], [], [], []

    def add(block: int, point: ArrayLike, force: ArrayLike, live: bool, source: str) -> None:
        blocks.append(block)
        points.append(point)
        forces.append(force)
        scaled.append(live)
        sources.append(source)

    for k, load in enumerate(pattern.point):
        try:
            i, p = _point(assembly, load)
        except LoadError as exc:
            raise exc.within(f"point[{k}]") from None
        add(i, p, load.force, load.scaled, f"point[{k}]")
    for k, load in enumerate(pattern.distributed):
        try:
            parts = _distributed(assembly, load)
        except LoadError as exc:
            raise exc.within(f"distributed[{k}]") from None
        for i, p, area in parts:
            add(i, p, (0.0, 0.0, -load.pressure * area), load.scaled, f"distributed[{k}]")
    notes: list[str] = []
    if pattern.fill is not None:
        for k, (i, p, f) in enumerate(fill_forces(assembly, pattern.fill)):
            add(i, p, f, False, f"fill[{k}]")
    if pattern.vehicle:
        for k, vehicle in enumerate(pattern.vehicle):
            wheels, dropped = wheel_loads(vehicle, assembly, f"vehicle[{k}]", pattern.fill)
            notes += dropped
            for wheel in wheels:
                for i, p, fz in wheel.parts:
                    add(i, p, (0.0, 0.0, fz), vehicle.scaled, wheel.source)
        for note in notes:
            log.debug("%s", note)
    return AppliedLoads(
        pattern, assembly, np.array(blocks, dtype=np.int64), np.array(points, dtype=float).reshape(-1, 3),
        np.array(forces, dtype=float).reshape(-1, 3), np.array(scaled, dtype=bool), tuple(sources), tuple(notes),
    )


def load_vectors(model: Model, pattern: LoadPattern) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """``(b_fixed, b_live)`` of ``pattern`` in ``model``'s row layout (:meth:`AppliedLoads.vectors`)."""
    return resolve(pattern, model.assembly).vectors(model)


def check_in_plane(model: Model, pattern: LoadPattern, settlements: Mapping[str, ArrayLike] | None = None) -> None:
    """Raise ``ValueError`` when ``model`` is planar and the loads or support motions leave its plane."""
    if model.kind != "planar":
        return
    if not (resolve(pattern, model.assembly).in_plane(model.plane) and motions_in_plane(model.plane, settlements)):
        raise ValueError(
            "this scene has loads or support motions out of the model's plane: solve it with the spatial model"
        )


def scene_vectors(
    model: Model,
    alpha: float | None = None,
    loads: LoadPattern | None = None,
    settlements: Mapping[str, ArrayLike] | None = None,
) -> tuple[LoadPattern, NDArray[np.float64], NDArray[np.float64]]:
    """The pattern of a call that takes ``alpha`` or ``loads`` (:func:`as_pattern`), checked
    against ``model``'s plane with the support motions (:func:`check_in_plane`), and its
    ``(b_fixed, b_live)`` (:func:`load_vectors`)."""
    pattern = as_pattern(alpha, loads)
    check_in_plane(model, pattern, settlements)
    return (pattern, *load_vectors(model, pattern))
