"""Vehicles: groups of axles that move across a structure as one rigid pattern.

A :class:`Vehicle` is a set of axles, each at an offset along x from the vehicle's
reference point and carrying a load (kN, downwards), each axle on wheels at transverse
offsets (along y, from the vehicle's line ``y``) that share the axle load equally. A wheel
is a point load on the top surface (no ``patch``) or a uniform pressure on a contact patch
``(length along x, width along y)`` centred on it. The whole vehicle has one position
coordinate, the plan abscissa ``x`` of its reference point: moving it moves every axle by
the same amount (:meth:`tce.core.loads.LoadPattern.moved`), so axles never merge.

A wheel whose point (or whole patch) lies off the deck (outside the plan of the structure,
or over a support block, whose load goes straight into the ground) is dropped; the part of
a patch that lies off the deck is dropped the same way. The dropped wheels of a vehicle are
summarised in one note (:attr:`tce.core.loads.AppliedLoads.notes`). A vehicle none of whose
wheels lands on the deck is an input error (:class:`OffDeck`, naming the vehicle and the
deck's extent): its load would be zero, and lambda would multiply nothing of it. Nothing is
merged: every wheel on the deck stays a load of its own.

Standard vehicles (:data:`STANDARD`, by name) are built by the functions of this module;
each docstring states its figures and their source. Only figures taken from the cited
documents are given: the generic axle groups (:func:`single_axle`, :func:`tandem`,
:func:`tridem`) take the load and spacing from the caller.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np
import shapely
from numpy.typing import NDArray

from ..structures.assembly import Assembly
from .surface import LoadError, _on_top, _upward_faces, _vector, top_surface

if TYPE_CHECKING:
    from .fill import Fill

__all__ = [
    "OffDeck",
    "STANDARD",
    "Vehicle",
    "VehicleLoad",
    "STANDARD_GRAVITY",
    "aashto_hl93_truck",
    "cs454_double_bogie",
    "cs454_single_axle",
    "deck_edges",
    "deck_extent",
    "deck_range",
    "eurocode_lm1_tandem",
    "eurocode_lm2_axle",
    "single_axle",
    "standard_vehicle",
    "tandem",
    "tridem",
    "wheel_loads",
]


@dataclass(frozen=True)
class Vehicle:
    """Axles and wheels moving as one rigid pattern.

    Parameters
    ----------
    axles : sequence of (offset, load)
        Offset along x from the vehicle's reference point (m) and axle load (kN, > 0,
        acting downwards; a live vehicle's load at lambda = 1). Offsets distinct.
    wheels : sequence of float
        Transverse offsets (m, along y from the vehicle's line ``y``) of each axle's wheels,
        distinct; the axle load is shared equally. Default: one wheel on the line.
    patch : (2,) float, optional
        Contact patch of each wheel, ``(length along x, width along y)`` (m, > 0), loaded
        by a uniform pressure; default: none (each wheel a point load on the top surface).
    x : float
        Plan abscissa of the reference point (m): the vehicle's position.
    y : float
        Plan ordinate of the vehicle's line (m).
    name : str
        A label (in notes and figures).
    scaled : bool
        True (default): a live load, multiplied by lambda; False: always applied.
    """

    axles: tuple[tuple[float, float], ...]
    wheels: tuple[float, ...] = (0.0,)
    patch: tuple[float, float] | None = None
    x: float = 0.0
    y: float = 0.0
    name: str = ""
    scaled: bool = True

    def __post_init__(self) -> None:
        if isinstance(self.axles, (str, bytes)) or not len(self.axles):
            raise LoadError("axles", "no axle given", "give axles = [[offset (m), load (kN)], ...]")
        axles = tuple(_vector(a, 2, f"axles[{k}]", "[offset (m), load (kN)]") for k, a in enumerate(self.axles))
        for k, (_, load) in enumerate(axles):
            if not load > 0.0:
                raise LoadError(f"axles[{k}]", f"axle load {load:g} kN", "give a positive axle load (kN, downwards)")
        _distinct([a[0] for a in axles], "axles", "two axles at the same offset would be one load")
        object.__setattr__(self, "axles", axles)
        if isinstance(self.wheels, (str, bytes)) or not len(self.wheels):
            raise LoadError("wheels", "no wheel given", "give the wheels' transverse offsets (m), e.g. [-1.0, 1.0]")
        wheels = _vector(self.wheels, len(self.wheels), "wheels", "m, transverse offsets")
        _distinct(list(wheels), "wheels", "two wheels at the same offset would be one load")
        object.__setattr__(self, "wheels", wheels)
        if self.patch is not None:
            patch = _vector(self.patch, 2, "patch", "m, [length along x, width along y]")
            if not min(patch) > 0.0:
                raise LoadError("patch", f"{list(patch)}", "give a positive length and width (m)")
            object.__setattr__(self, "patch", patch)
        (x,) = _vector([self.x], 1, "x", "m")
        (y,) = _vector([self.y], 1, "y", "m")
        object.__setattr__(self, "x", x)
        object.__setattr__(self, "y", y)
        if not isinstance(self.name, str):
            raise LoadError("name", f"not a text ({self.name!r})", "give a quoted name")
        if not isinstance(self.scaled, bool):
            raise LoadError("scaled", f"not true or false ({self.scaled!r})", "write true or false")

    @property
    def label(self) -> str:
        """The name, or ``"vehicle"``."""
        return self.name or "vehicle"

    @property
    def total(self) -> float:
        """Sum of the axle loads (kN)."""
        return float(sum(load for _, load in self.axles))

    @property
    def offsets(self) -> NDArray[np.float64]:
        """Axle offsets along x from the reference point (m)."""
        return np.array([a[0] for a in self.axles])

    def at(self, x: float) -> Vehicle:
        """The vehicle with its reference point at plan abscissa ``x`` (m)."""
        return replace(self, x=x)

    def wheel_points(self) -> list[tuple[int, int, float, float, float]]:
        """``(axle, wheel, x, y, load)`` of every wheel at the vehicle's position (m, kN)."""
        share = 1.0 / len(self.wheels)
        return [
            (a, w, self.x + dx, self.y + dy, load * share)
            for a, (dx, load) in enumerate(self.axles)
            for w, dy in enumerate(self.wheels)
        ]

    def to_dict(self) -> dict[str, Any]:
        """Plain data, the keys of a ``[[loads.vehicle]]`` table (absent keys left out)."""
        out: dict[str, Any] = {"axles": [list(a) for a in self.axles], "wheels": list(self.wheels),
                               "x": self.x, "y": self.y, "scaled": self.scaled}
        if self.patch is not None:
            out["patch"] = list(self.patch)
        if self.name:
            out["name"] = self.name
        return out


def _distinct(values: list[float], key: str, why: str) -> None:
    if len(set(values)) != len(values):
        raise LoadError(key, f"a value listed twice ({values})", f"give distinct values ({why})")


class OffDeck(LoadError):
    """A vehicle none of whose wheels lands on the deck (:func:`wheel_loads`)."""


@dataclass(frozen=True)
class VehicleLoad:
    """One wheel of a vehicle resolved on an assembly: ``(block, point, force)`` parts.

    A point wheel has one part; a patch has one part per exposed top-surface piece it
    covers (its resultant at the piece's plan centroid, on the face).
    """

    source: str
    parts: tuple[tuple[int, tuple[float, float, float], float], ...]  # (block, point, Fz in kN)


def wheel_loads(
    vehicle: Vehicle, assembly: Assembly, key: str, fill: Fill | None = None
) -> tuple[list[VehicleLoad], list[str]]:
    """The wheels of ``vehicle`` that lie on the deck of ``assembly``, and one note (none when
    nothing is dropped) listing the wheels, or parts of contact patches, dropped because
    they lie off the deck.

    ``key`` names the vehicle in sources and notes (``vehicle[0]``). The deck is the top
    surface of the free blocks (:func:`tce.core.surface.top_surface`); a wheel over a support
    block or outside the plan is off the deck. With a ``fill`` whose dispersion is on, each
    wheel's patch (a point: 0 x 0) grows by the spread through the fill under the wheel's
    centre (:meth:`tce.core.fill.Fill.spread`) on each side before it is laid on the deck.

    Raises
    ------
    OffDeck
        No wheel of the vehicle lands on the deck (key ``key``; the message names the
        vehicle, its position and the deck's extent, :func:`deck_extent`).
    """
    loads: list[VehicleLoad] = []
    dropped: list[str] = []
    road = None
    if fill is not None and fill.dispersion != 0.0:
        from .fill import road_level

        road = road_level(assembly, fill)
    for a, w, x, y, load in vehicle.wheel_points():
        source = f"{key}.axle[{a}].wheel[{w}]"
        where = f"axle {a + 1} wheel {w + 1} (x = {x:.4g} m, y = {y:.4g} m)"
        patch = vehicle.patch
        if road is not None and fill is not None and isinstance(fill.dispersion, str):
            from .fill import boussinesq_parts

            try:
                _, p = _on_top(assembly, (x, y))
            except LoadError:
                dropped.append(f"{where} off the deck")
                continue
            parts, off = boussinesq_parts(assembly, x, y, patch, road - float(p[2]))
            if off > 1e-9:
                dropped.append(f"{where} {100.0 * off:.3g}% of its load spread beyond the deck or over a support")
            if parts:
                loads.append(VehicleLoad(source, tuple((i, p, -load * frac) for i, p, frac in parts)))
            continue
        if road is not None and fill is not None:
            try:
                _, p = _on_top(assembly, (x, y))
                spread = 2.0 * fill.spread(road - float(p[2]))
            except LoadError:
                spread = 0.0
            base = patch or (0.0, 0.0)
            patch = (base[0] + spread, base[1] + spread) if spread > 0.0 else vehicle.patch
        if patch is None:
            try:
                i, p = _on_top(assembly, (x, y))
            except LoadError:
                dropped.append(f"{where} off the deck")
                continue
            if assembly.blocks[i].support:
                dropped.append(f"{where} over support block {assembly.names[i]!r}")
                continue
            loads.append(VehicleLoad(source, ((i, tuple(float(v) for v in p), -load),)))
            continue
        parts, off = _patch_parts(assembly, x, y, patch)
        if off > 1e-9:
            dropped.append(f"{where} {100.0 * off:.3g}% of its contact patch off the deck or over a support")
        if parts:
            loads.append(VehicleLoad(source, tuple((i, p, -load * frac) for i, p, frac in parts)))
    if not loads:
        (x0, x1), (y0, y1) = deck_extent(assembly)
        raise OffDeck(
            key, f"no wheel of {vehicle.label!r} at x = {vehicle.x:.4g} m, y = {vehicle.y:.4g} m lands on the deck, "
            f"which spans x = [{x0:.4g}, {x1:.4g}] m, y = [{y0:.4g}, {y1:.4g}] m (its load would be zero)",
            "place the vehicle over the deck: check x, y and the axle and wheel offsets (m, not mm)",
        )
    n = len(vehicle.axles) * len(vehicle.wheels)
    notes = [f"{key} ({vehicle.label}) at x = {vehicle.x:.4g} m: {len(dropped)} of {n} wheels dropped in whole or "
             f"part: {'; '.join(dropped)}"] if dropped else []
    return loads, notes


def _patch_parts(
    assembly: Assembly, x: float, y: float, patch: tuple[float, float]
) -> tuple[list[tuple[int, tuple[float, float, float], float]], float]:
    """``(block, point, fraction of the patch)`` of each free top-surface piece under a patch
    centred at ``(x, y)``, and the fraction of the patch off the deck."""
    lx, ly = patch
    rect = shapely.box(x - lx / 2.0, y - ly / 2.0, x + lx / 2.0, y + ly / 2.0)
    faces = _upward_faces(assembly)
    eps = (1e-9 * assembly.size) ** 2
    parts, on = [], 0.0
    for block, face, poly in top_surface(assembly):
        if assembly.blocks[block].support:
            continue
        part = rect.intersection(poly)
        for piece in getattr(part, "geoms", [part]):
            if not isinstance(piece, shapely.Polygon) or piece.area <= eps:
                continue
            c = piece.centroid
            parts.append((block, (c.x, c.y, float(faces.z(face, c.x, c.y))), piece.area / rect.area))
            on += piece.area / rect.area
    return parts, max(0.0, 1.0 - on)


def deck_range(assembly: Assembly) -> tuple[float, float]:
    """Plan range along x (m) of the top surface of the free blocks (the deck).

    Raises
    ------
    LoadError
        No free block has an exposed top surface.
    """
    return deck_extent(assembly)[0]


def deck_extent(assembly: Assembly) -> tuple[tuple[float, float], tuple[float, float]]:
    """Plan ranges ``((x0, x1), (y0, y1))`` (m) of the top surface of the free blocks (the deck).

    Raises
    ------
    LoadError
        No free block has an exposed top surface.
    """
    polys = [poly for block, _, poly in top_surface(assembly) if not assembly.blocks[block].support]
    if not polys:
        raise LoadError("vehicle", "the structure has no exposed top surface on a free block",
                        "load a structure with a deck")
    x0, y0, x1, y1 = shapely.union_all(polys).bounds
    return (float(x0), float(x1)), (float(y0), float(y1))


def deck_edges(assembly: Assembly, band: tuple[float, float] | None = None) -> NDArray[np.float64]:
    """Sorted distinct plan abscissae (m) where a load moving along x passes from one
    top-surface piece of the free blocks (or one face) to the next.

    Parameters
    ----------
    assembly : Assembly
        The structure.
    band : (float, float), optional
        Plan ordinates ``(y0, y1)`` (m, ``y0 <= y1``) swept by the load: a line (``y0 == y1``,
        a point wheel) or a strip (a contact patch's sides). The abscissae are those of the
        vertices of the pieces clipped to it: the pieces' own vertices inside the strip and
        the crossings of the line (or of the strip's sides) with the pieces' edges, which on a
        skew deck lie between the vertices' abscissae. Default: the vertices of the whole
        pieces (a load anywhere across the deck).
    """
    pieces = [poly for block, _, poly in top_surface(assembly) if not assembly.blocks[block].support]
    if band is not None and pieces:
        y0, y1 = band
        x0, _, x1, _ = shapely.union_all(pieces).bounds
        clip = (shapely.LineString([(x0 - 1.0, y0), (x1 + 1.0, y0)]) if y1 <= y0
                else shapely.box(x0 - 1.0, y0, x1 + 1.0, y1))
        pieces = [poly.intersection(clip) for poly in pieces]
    v = np.sort(np.concatenate([shapely.get_coordinates(p)[:, 0] for p in pieces])) if pieces else np.zeros(0)
    if not len(v):
        return v
    keep = np.concatenate([[True], np.diff(v) > 1e-9 * assembly.size])
    return v[keep]


# ---------------------------------------------------------------------------- library
def single_axle(load: float, wheels: Sequence[float] = (0.0,), patch: Sequence[float] | None = None, name: str = "single axle") -> Vehicle:
    """One axle of ``load`` kN at the reference point (offset 0) on ``wheels``."""
    return Vehicle(axles=((0.0, load),), wheels=tuple(wheels), patch=None if patch is None else tuple(patch), name=name)


def tandem(load: float, spacing: float, wheels: Sequence[float] = (0.0,), patch: Sequence[float] | None = None,
           name: str = "tandem") -> Vehicle:
    """Two axles of ``load`` kN each, ``spacing`` m apart, the reference point on the first."""
    return _group(load, spacing, 2, wheels, patch, name)


def tridem(load: float, spacing: float, wheels: Sequence[float] = (0.0,), patch: Sequence[float] | None = None,
           name: str = "tridem") -> Vehicle:
    """Three axles of ``load`` kN each, ``spacing`` m apart, the reference point on the first."""
    return _group(load, spacing, 3, wheels, patch, name)


def _group(load: float, spacing: float, n: int, wheels: Sequence[float], patch: Sequence[float] | None,
           name: str) -> Vehicle:
    if not spacing > 0.0:
        raise LoadError("spacing", f"{spacing!r}", "give a positive axle spacing (m)")
    return Vehicle(axles=tuple((k * spacing, load) for k in range(n)), wheels=tuple(wheels),
                   patch=None if patch is None else tuple(patch), name=name)


def eurocode_lm1_tandem(lane: int = 1, alpha_q: float = 1.0) -> Vehicle:
    """The tandem system TS of Eurocode Load Model 1 in one notional lane.

    EN 1991-2:2003, 4.3.2 (Figure 4.2a, Table 4.2): two axles 1.20 m apart, each of
    ``alpha_q * Q_ik`` with ``Q_1k = 300``, ``Q_2k = 200``, ``Q_3k = 100`` kN for lanes 1,
    2 and 3; two wheels per axle 2.00 m apart (transverse), each on a square contact
    surface of 0.40 m x 0.40 m. ``alpha_q`` is the adjustment factor of the National Annex
    (recommended minimum 0.8 for lane 1 in the EN; 1.0 here unless given). The lane's
    uniformly distributed load of LM1 is not part of the tandem.
    """
    q = {1: 300.0, 2: 200.0, 3: 100.0}
    if lane not in q:
        raise LoadError("lane", f"{lane!r}", "give lane 1, 2 or 3 (EN 1991-2, Table 4.2)")
    return tandem(alpha_q * q[lane], 1.20, wheels=(-1.0, 1.0), patch=(0.40, 0.40), name=f"EN 1991-2 LM1 TS lane {lane}")


def eurocode_lm2_axle(beta_q: float = 1.0) -> Vehicle:
    """Eurocode Load Model 2: a single axle of ``beta_q * 400`` kN.

    EN 1991-2:2003, 4.3.3 (Figure 4.3): one axle load ``beta_q * Q_ak``, ``Q_ak = 400``
    kN, on two wheels 2.00 m apart, each on a contact surface 0.35 m along the direction
    of travel by 0.60 m across it.
    """
    return single_axle(beta_q * 400.0, wheels=(-1.0, 1.0), patch=(0.35, 0.60), name="EN 1991-2 LM2 axle")


def aashto_hl93_truck(rear_spacing: float = 4.3) -> Vehicle:
    """The AASHTO design truck of HL-93 (United States).

    AASHTO LRFD Bridge Design Specifications, 3.6.1.2.2 (Figure 3.6.1.2.2-1, SI units):
    axles of 35, 145 and 145 kN; 4.30 m from the front axle to the second, 4.30 to
    9.00 m (``rear_spacing``) from the second to the third; wheels 1.80 m apart
    (transverse). Tire contact area (3.6.1.2.5): 0.51 m wide by 0.25 m long. The design
    lane load of HL-93 is not part of the truck. The reference point is the front axle,
    the others at positive offsets.
    """
    if not 4.3 <= rear_spacing <= 9.0:
        raise LoadError("rear_spacing", f"{rear_spacing!r}", "give 4.3 to 9.0 m (AASHTO LRFD 3.6.1.2.2)")
    return Vehicle(
        axles=((0.0, 35.0), (4.3, 145.0), (4.3 + rear_spacing, 145.0)),
        wheels=(-0.9, 0.9), patch=(0.25, 0.51), name="AASHTO HL-93 design truck",
    )


#: standard gravity (m/s^2): an axle load in tonnes times this is in kN
STANDARD_GRAVITY = 9.80665


def cs454_single_axle(tonnes: float = 11.5) -> Vehicle:
    """A single axle of the UK assessment of masonry arches (normal traffic: 11.5 t).

    CS 454 (*Assessment of highway bridges and structures*, Design Manual for Roads and
    Bridges, Revision 0), 7.3, Table 7.3.1a "Authorised axle loads and spacings for normal and
    restricted traffic": a single axle of 11.5 t for normal traffic and for the 33, 26 and 18
    tonne restricted levels (lower levels: 9, 7, 5.5, 2 t). The load is ``tonnes`` times
    :data:`STANDARD_GRAVITY` (kN). The table gives axle loads only: the axle is one load on
    the centre line (``wheels = (0,)``); give the wheels (``dataclasses.replace``) to spread it.
    """
    return single_axle(tonnes * STANDARD_GRAVITY, name=f"CS 454 single axle {tonnes:g} t")


def cs454_double_bogie(spacing: float, lift_off: bool = False) -> Vehicle:
    """A double-axle bogie of the UK assessment of masonry arches (normal traffic).

    CS 454 Revision 0, Table 7.3.1a: the axle load depends on the axle spacing ``s``: 8 t for
    1.00 <= s < 1.30 m, 9.5 t for 1.30 <= s < 1.80 m, 10 t for s >= 1.80 m. With
    ``lift_off`` (Table 7.3.1b, to be assessed on humped or fast approaches, 7.3.2) the axle
    loads are multiplied by 1.5 (the first axle, the reference point) and 0.5 (the second);
    the table says the two are interchangeable, so assess the reversed order too (the same
    vehicle with its axles swapped). Loads in kN (tonnes times :data:`STANDARD_GRAVITY`), one
    load per axle on the centre line, as :func:`cs454_single_axle`.
    """
    if not (isinstance(spacing, int | float) and spacing >= 1.0):
        raise LoadError("spacing", f"{spacing!r}", "give an axle spacing >= 1.00 m (CS 454, Table 7.3.1a)")
    tonnes = 8.0 if spacing < 1.30 else 9.5 if spacing < 1.80 else 10.0
    f1, f2 = (1.5, 0.5) if lift_off else (1.0, 1.0)
    load = tonnes * STANDARD_GRAVITY
    name = f"CS 454 double-axle bogie {tonnes:g} t, s = {spacing:g} m" + (" (axle lift-off)" if lift_off else "")
    return Vehicle(axles=((0.0, f1 * load), (float(spacing), f2 * load)), name=name)


#: standard vehicles by name (``[[loads.vehicle]] standard = "..."``)
STANDARD: dict[str, Callable[[], Vehicle]] = {
    "cs454_single_axle": cs454_single_axle,
    "cs454_double_bogie_s100": lambda: cs454_double_bogie(1.00),
    "cs454_double_bogie_s130": lambda: cs454_double_bogie(1.30),
    "cs454_double_bogie_s180": lambda: cs454_double_bogie(1.80),
    "en1991_lm1_tandem_lane1": lambda: eurocode_lm1_tandem(1),
    "en1991_lm1_tandem_lane2": lambda: eurocode_lm1_tandem(2),
    "en1991_lm1_tandem_lane3": lambda: eurocode_lm1_tandem(3),
    "en1991_lm2_axle": eurocode_lm2_axle,
    "aashto_hl93_truck": aashto_hl93_truck,
}


def standard_vehicle(name: str, **changes: Any) -> Vehicle:
    """The standard vehicle ``name`` (:data:`STANDARD`) with ``changes`` (``x``, ``y``,
    ``scaled``, ...) applied.

    Raises
    ------
    LoadError
        An unknown name.
    """
    if name not in STANDARD:
        raise LoadError("standard", f"unknown vehicle {name!r}", f"use one of {sorted(STANDARD)}")
    return replace(STANDARD[name](), **changes)
