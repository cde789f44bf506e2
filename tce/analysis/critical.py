"""The critical position of a moving load: the position of least collapse multiplier, searched.

The moving loads of a :class:`tce.core.loads.LoadPattern` (its scaled vehicles and scaled
``on_top`` point loads) move as one rigid group with one coordinate, the plan abscissa of
its reference (:meth:`~tce.core.loads.LoadPattern.moved`). :func:`critical_position`
finds the reference position ``x`` of least ``lambda_max(x)``, the direct limit
(:meth:`tce.core.analysis.Analysis.limit`), to a tolerance, whatever grid the caller gives.

Why the search is exact for point loads (wheels without a contact patch): while every
wheel stays on one planar top face of one block, ``b_live(x) = b0 + x b1`` is affine. The
set ``C`` of ``(mu, nu)`` with ``b_fixed + mu b0 + nu b1`` carried by an admissible force
state is convex and holds the origin when the fixed loads stand, and
``lambda_max(x) = 1 / g(1, x)`` with ``g`` the (convex) gauge of ``C``. So
``1 / lambda_max`` is convex on each such piece and ``lambda_max`` is least at one of its
ends: where a wheel crosses an edge of the top surface (a joint's extrados), or at an end
of the range. The breakpoints are where each wheel's line, or its patch's sides, cross the
edges of the deck's pieces in plan (:func:`tce.core.vehicles.deck_edges` of the strip it
sweeps, :func:`moving_offsets`): on a square deck the pieces' vertex abscissae, on a skew
deck the crossings of the line with the oblique joints, between them. Under a fill that
disperses the wheel loads the patch grows with the depth under the wheel and its sides are
not lines: every vertex abscissa of the deck is a breakpoint then. The search evaluates
every breakpoint on both sides (``DELTA`` of the range before and after), the midpoints
between them, the caller's positions, and refines the best local minima by bounded Brent
search (:func:`scipy.optimize.minimize_scalar`) to ``xtol``: exact for point loads, and to
``xtol`` for contact patches (whose load is not affine in ``x``) when the least value lies
inside a piece.

Vehicles off the deck: at a position where a moving vehicle has no wheel on the deck, the
search drops that vehicle there (:func:`on_deck`), and a position where no live load is
left is carried at any multiplier. A vehicle with no wheel on the deck at every position
scanned is an input error (:func:`check_on_deck`), raised before any solve.

Ties: positions (farther apart than the tolerance) whose ``lambda_max`` equals the least
within :data:`TIE_RTOL` are reported in :attr:`CriticalResult.ties`; the critical position
reported is the leftmost of them (least x), whatever the order of evaluation.

The direct limit does not depend on support motions (static theorem), so the search holds
for every settlement scenario of a rigid material; with a non-associative material it is
the associative critical position.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..core.analysis import Analysis
from ..core.loads import LoadError, LoadPattern
from ..core.result import Result
from ..core.vehicles import OffDeck, deck_edges, deck_extent, deck_range, wheel_loads
from ..structures.assembly import Assembly

__all__ = [
    "DELTA",
    "TIE_RTOL",
    "CriticalResult",
    "check_on_deck",
    "critical_position",
    "moving_offsets",
    "on_deck",
    "scan_positions",
    "search_bounds",
]

#: a breakpoint is evaluated this fraction of the range before and after it
DELTA = 1e-7
#: two positions whose lambda_max agree within this relative tolerance are tied
TIE_RTOL = 1e-6
#: local minima of the scan refined by Brent's method
REFINED = 4


@dataclass(frozen=True, eq=False, kw_only=True)
class CriticalResult(Result):
    """The critical position of a moving load group.

    Attributes
    ----------
    status : str
        ``optimal`` (a finite least lambda_max), ``unbounded`` (the load is carried at any
        multiplier at every position), ``infeasible`` (the fixed loads cannot be carried),
        ``numerical`` (a limit solve failed: no answer is given).
    critical_x : float
        Reference position of least lambda_max (m; NaN unless optimal); the leftmost of
        tied positions.
    lambda_max : float
        lambda_max there (NaN unless optimal).
    ties : tuple of float
        Other positions with the same lambda_max within :data:`TIE_RTOL` (m), e.g. the
        mirror position of a symmetric structure and load.
    bounds : (float, float)
        The range searched (m): positions where a moving load is on the deck.
    xtol : float
        Tolerance on the position (m).
    x, lam : (k,) ndarray
        Every position evaluated (sorted, m) and its lambda_max (inf: carried at any
        multiplier; NaN: the solve failed).
    n_solves : int
        Limit solves made.
    pattern : LoadPattern or None
        The pattern at the critical position.
    """

    critical_x: float = float("nan")
    lambda_max: float = float("nan")
    ties: tuple[float, ...] = ()
    bounds: tuple[float, float] = (float("nan"), float("nan"))
    xtol: float = float("nan")
    x: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0), repr=False)
    lam: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0), repr=False)
    n_solves: int = 0
    pattern: LoadPattern | None = field(default=None, repr=False)


def moving_offsets(pattern: LoadPattern) -> list[tuple[float, float, tuple[float, float] | None]]:
    """``(offset, half length, band)`` of every moving load: its offset along x from the
    group's reference (:attr:`~tce.core.loads.LoadPattern.reference_x`), the half length
    along x of its contact patch (m) and the plan ordinates ``(y0, y1)`` it sweeps (m,
    :func:`tce.core.vehicles.deck_edges`). Each wheel of each axle of a scaled vehicle: half
    its patch length (0 without a patch) and the strip of its patch's width about its line,
    or None (the whole deck) under a fill that disperses it, whose patch grows with the depth
    under the wheel, so that its sides are not lines; each scaled ``on_top`` point load: 0
    and its line."""
    ref = pattern.reference_x
    spread = pattern.fill is not None and pattern.fill.dispersion != 0.0
    out: list[tuple[float, float, tuple[float, float] | None]] = []
    for v in pattern.vehicle:
        if not v.scaled:
            continue
        half, width = (0.0, 0.0) if v.patch is None else (v.patch[0] / 2.0, v.patch[1] / 2.0)
        out += [(v.x - ref + dx, half, None if spread else (v.y + dy - width, v.y + dy + width))
                for dx, _ in v.axles for dy in v.wheels]
    out += [(p.on_top[0] - ref, 0.0, (p.on_top[1], p.on_top[1]))
            for p in pattern.point if p.scaled and p.on_top is not None]
    return out


def search_bounds(pattern: LoadPattern, assembly: Assembly) -> tuple[float, float]:
    """Reference positions (m) with a moving load on the deck (:func:`tce.core.vehicles.deck_range`):
    some axle of a vehicle, and every moving point load (a point load off the deck is an
    error, not a dropped wheel).

    Raises
    ------
    LoadError
        Moving point loads farther apart than the deck is long.
    """
    d0, d1 = deck_range(assembly)
    ref = pattern.reference_x
    veh = [v.x - ref + dx for v in pattern.vehicle if v.scaled for dx, _ in v.axles]
    pts = [p.on_top[0] - ref for p in pattern.point if p.scaled and p.on_top is not None]
    lo, hi = -math.inf, math.inf
    if veh:
        lo, hi = d0 - max(veh), d1 - min(veh)
    if pts:
        lo, hi = max(lo, d0 - min(pts)), min(hi, d1 - max(pts))
    if not lo < hi:
        raise LoadError("point", "the moving point loads are farther apart than the deck is long",
                        "move them closer together")
    return lo, hi


def on_deck(pattern: LoadPattern, assembly: Assembly) -> LoadPattern | None:
    """``pattern`` without its moving (scaled) vehicles that have no wheel on the deck at their
    position; None when no live load is left (lambda would multiply nothing).

    Raises
    ------
    OffDeck
        A fixed vehicle with no wheel on the deck (it does not move: an input error).
    """
    keep = []
    for k, v in enumerate(pattern.vehicle):
        try:
            wheel_loads(v, assembly, f"vehicle[{k}]", pattern.fill)
        except OffDeck:
            if not v.scaled:
                raise
            continue
        keep.append(v)
    if len(keep) == len(pattern.vehicle):
        return pattern
    if not (pattern.lateral or any(v.scaled for v in keep)
            or any(p.scaled for p in (*pattern.point, *pattern.distributed))):
        return None
    return replace(pattern, vehicle=tuple(keep))


def scan_positions(
    pattern: LoadPattern, assembly: Assembly, lo: float, hi: float, extra: ArrayLike = ()
) -> NDArray[np.float64]:
    """The positions the search scans in ``[lo, hi]`` (m, sorted): ``DELTA`` of the range
    before and after every breakpoint (a moving load's line, or its patch's side, crossing
    an edge of a deck piece in plan: :func:`moving_offsets`, :func:`~tce.core.vehicles.deck_edges`), the range's
    ends moved in by as much, the ``extra`` positions (clipped to them), and the midpoints
    between all of these."""
    delta = DELTA * (hi - lo)
    extra = np.clip(np.asarray(extra, dtype=float).ravel(), lo + delta, hi - delta)
    loads = moving_offsets(pattern)
    edges = {band: deck_edges(assembly, band) for band in {band for _, _, band in loads}}
    breaks = np.array([e - off + s * half for off, half, band in loads for e in edges[band] for s in (-1.0, 1.0)])
    breaks = np.unique(np.round(breaks[(breaks > lo) & (breaks < hi)], 12))
    scan = np.unique(np.concatenate([breaks - delta, breaks + delta, [lo + delta, hi - delta], extra]))
    return np.unique(np.concatenate([scan, (scan[1:] + scan[:-1]) / 2.0]))


def check_on_deck(pattern: LoadPattern, assembly: Assembly, bounds: tuple[float, float] | None = None) -> None:
    """Raise :class:`~tce.core.vehicles.OffDeck` when a moving vehicle of ``pattern`` has no
    wheel on the deck at any position the search scans (:func:`scan_positions` over
    ``bounds``, default :func:`search_bounds`); geometry only, no solve.
    """
    lo, hi = search_bounds(pattern, assembly) if bounds is None else bounds
    todo = {k for k, v in enumerate(pattern.vehicle) if v.scaled}
    first: dict[int, OffDeck] = {}
    for x in scan_positions(pattern, assembly, lo, hi):
        if not todo:
            return
        moved = pattern.moved(float(x))
        for k in list(todo):
            try:
                wheel_loads(moved.vehicle[k], assembly, f"vehicle[{k}]", pattern.fill)
                todo.discard(k)
            except OffDeck as exc:
                first.setdefault(k, exc)
    if todo:
        k = min(todo)
        (x0, x1), (y0, y1) = deck_extent(assembly)
        raise OffDeck(
            f"vehicle[{k}]", f"no wheel of {pattern.vehicle[k].label!r} lands on the deck at any position searched "
            f"(reference x = {lo:.4g} to {hi:.4g} m, line y = {pattern.vehicle[k].y:.4g} m); the deck spans "
            f"x = [{x0:.4g}, {x1:.4g}] m, y = [{y0:.4g}, {y1:.4g}] m (its load would be zero)", first[k].fix,
        )


def critical_position(
    analysis: Analysis,
    loads: LoadPattern,
    start: ArrayLike | None = None,
    xtol: float | None = None,
    bounds: tuple[float, float] | None = None,
) -> CriticalResult:
    """The reference position of least direct ``lambda_max`` of the moving loads of ``loads``.

    Parameters
    ----------
    analysis : Analysis
        The structure and material.
    loads : LoadPattern
        A pattern with moving loads (scaled vehicles or scaled ``on_top`` point loads).
    start : array_like, optional
        Positions of the reference to evaluate besides the search's own (m): the caller's
        grid. The answer does not depend on it (up to ``xtol``); positions outside
        ``bounds`` are an error.
    xtol : float, optional
        Tolerance on the position (m); default 1e-4 of the deck's length.
    bounds : (float, float), optional
        Range of the reference (m); default: every position with a moving load on the deck.

    Returns
    -------
    CriticalResult

    Raises
    ------
    LoadError
        Nothing moves, a start position outside the bounds, or bounds that are empty.
    OffDeck
        A moving vehicle with no wheel on the deck at any position (:func:`check_on_deck`),
        or a fixed vehicle with none at its position.
    """
    t0 = time.perf_counter()
    if loads.reference_x != loads.reference_x:
        loads.moved(0.0)  # raises the LoadError naming what is missing
    deck = deck_range(analysis.assembly)
    length = deck[1] - deck[0]
    xtol = 1e-4 * length if xtol is None else float(xtol)
    if not (math.isfinite(xtol) and xtol > 0):
        raise LoadError("xtol", f"{xtol!r}", "give a positive tolerance (m)")
    lo, hi = search_bounds(loads, analysis.assembly) if bounds is None else (float(bounds[0]), float(bounds[1]))
    if not lo < hi:
        raise LoadError("bounds", f"[{lo:g}, {hi:g}] is empty", "give [from, to] with from < to (m)")
    delta = DELTA * (hi - lo)
    lo_in, hi_in = lo + delta, hi - delta
    given = np.zeros(0) if start is None else np.asarray(start, dtype=float).ravel()
    outside = given[(given < lo) | (given > hi) | ~np.isfinite(given)]
    if outside.size:
        raise LoadError("start", f"position {outside[0]:g} m is outside the range [{lo:.6g}, {hi:.6g}] m "
                        "where a moving load is on the deck", "give positions inside it")

    check_on_deck(loads, analysis.assembly, (lo, hi))

    values: dict[float, float] = {}
    patterns: dict[float, LoadPattern] = {}  # positions where a moving vehicle is off the deck
    failed: list[str] = []

    def lam(x: float) -> float:
        x = float(min(max(x, lo_in), hi_in))
        if x not in values:
            moved = loads.moved(x)
            try:
                res = analysis.limit(loads=moved)
            except OffDeck:
                reduced = on_deck(moved, analysis.assembly)
                if reduced is None:  # no live load on the structure there
                    values[x] = math.inf
                    return values[x]
                patterns[x] = reduced
                res = analysis.limit(loads=reduced)
            if res.status == "infeasible":
                raise _Infeasible(res.message)
            values[x] = {"optimal": res.lambda_max, "unbounded": math.inf}.get(res.status, math.nan)
            if res.status not in ("optimal", "unbounded"):
                failed.append(f"x = {x:.6g} m: {res.status} ({res.message})")
        return values[x]

    scan = scan_positions(loads, analysis.assembly, lo, hi, given)
    try:
        for x in scan:
            lam(x)
        _refine(lam, values, xtol)
    except _Infeasible as exc:
        return CriticalResult(status="infeasible", message=f"the fixed loads cannot be carried: {exc}",
                              bounds=(lo, hi), xtol=xtol, n_solves=len(values) + 1,
                              wall_time=time.perf_counter() - t0)
    x = np.array(sorted(values))
    y = np.array([values[v] for v in x])
    common = dict(bounds=(lo, hi), xtol=xtol, x=x, lam=y, n_solves=len(values), wall_time=time.perf_counter() - t0)
    if failed:
        return CriticalResult(status="numerical", message=f"{len(failed)} limit solve(s) failed: {failed[0]}", **common)
    if not np.isfinite(y).any():
        return CriticalResult(status="unbounded", lambda_max=math.inf,
                              message="carried at any multiplier at every position", **common)
    best = float(np.nanmin(y))
    tied = _tied(x, y, best, 2.0 * xtol + 2.0 * delta)
    crit = float(tied[0])
    msg = f"{len(values)} limit solves over [{lo:.6g}, {hi:.6g}] m"
    if len(tied) > 1:
        msg += f"; tied positions (lambda_max within {TIE_RTOL:g}): {', '.join(f'{t:.6g}' for t in tied)} m"
    return CriticalResult(status="optimal", critical_x=crit, lambda_max=values[crit], ties=tuple(float(t) for t in tied[1:]),
                          pattern=patterns.get(crit, loads.moved(crit)), message=msg, **common)


class _Infeasible(Exception):
    """The fixed loads alone cannot be carried (at any position)."""


def _refine(lam, values: dict[float, float], xtol: float) -> None:
    """Bounded Brent search between the neighbours of the best local minima of the values."""
    from scipy.optimize import minimize_scalar  # imported on first use: it is slow to import

    x = np.array(sorted(values))
    y = np.array([values[v] for v in x])
    y = np.where(np.isnan(y), np.inf, y)
    mins = [k for k in range(len(x)) if y[k] < math.inf
            and (k == 0 or y[k] <= y[k - 1]) and (k == len(x) - 1 or y[k] <= y[k + 1])]
    for k in sorted(mins, key=lambda k: y[k])[:REFINED]:
        a, b = x[max(k - 1, 0)], x[min(k + 1, len(x) - 1)]
        if b - a > xtol:
            minimize_scalar(lam, bounds=(a, b), method="bounded", options=dict(xatol=xtol / 4.0))


def _tied(x: NDArray[np.float64], y: NDArray[np.float64], best: float, apart: float) -> list[float]:
    """The positions of least value within :data:`TIE_RTOL`, grouped in clusters of
    positions closer than ``apart``: the position of least value of each cluster, sorted."""
    near = np.flatnonzero(np.abs(y - best) <= TIE_RTOL * abs(best))
    clusters: list[list[int]] = []
    for k in near:
        if clusters and x[k] - x[clusters[-1][-1]] <= apart:
            clusters[-1].append(int(k))
        else:
            clusters.append([int(k)])
    return [float(x[min(c, key=lambda k: y[k])]) for c in clusters]
