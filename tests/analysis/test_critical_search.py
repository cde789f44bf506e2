"""The critical-position search (tce.analysis.critical) part by part, against expectations
worked out without it: the range it searches from the deck's ends and the load offsets by
hand, its position and factor against a brute-force scan of the direct limit at fine
resolution (a grid, then zoomed grids around its best minima), and its mirror ties.

The paper's arch (14 voussoirs, deck from x = -1.2 to 1.2 m) keeps each direct limit at a
few milliseconds. Contact patches make the load non-affine in the position, so the least
multiplier lies inside a piece between two deck edges, where only the search's refinement
(Brent's method between the neighbours of a scanned minimum) can find it.
"""

from __future__ import annotations

from functools import cache

import numpy as np
import pytest

from tce.analysis.critical import DELTA, critical_position, scan_positions, search_bounds
from tce.core.analysis import Analysis
from tce.core.fill import DISPERSION_2_TO_1, Fill
from tce.core.loads import LoadPattern
from tce.core.vehicles import deck_edges
from tce.structures.arch import semicircular_arch
from tce.structures.bridge import arch_bridge

AN = Analysis(semicircular_arch())
DECK = (-1.2, 1.2)  # the paper's arch: centreline radius 1.1 m, extrados radius 1.2 m
XTOL = 1e-4 * (DECK[1] - DECK[0])  # the search's default tolerance on the position (m)

ONE_PATCH = dict(axles=[[0.0, 1.0]], patch=[0.3, 0.2])  # symmetric: least at +-0.298, inside a piece
TWO_PATCHES = dict(axles=[[0.0, 1.0], [0.5, 1.5]], patch=[0.2, 0.2])  # unequal axles: one least position


def pattern(vehicle: dict) -> LoadPattern:
    return LoadPattern(lateral=False, vehicle=[vehicle])


def lam_at(p: LoadPattern, x: float) -> float:
    return AN.limit(loads=p.moved(x)).lambda_max


def brute_force(p: LoadPattern, lo: float, hi: float, h: float = 0.01,
                finest: float = 2e-5) -> list[tuple[float, float]]:
    """``(lambda, x)`` of every local minimum of ``lambda_max(x)`` on a grid of step ``h`` over
    ``[lo, hi]`` within 1e-3 of the least, each zoomed by grids of 21 points ten times finer
    down to ``finest`` (m); sorted by lambda."""
    xs = np.linspace(lo, hi, int(round((hi - lo) / h)) + 1)
    ys = np.array([lam_at(p, x) for x in xs])
    mins = [k for k in range(len(xs)) if (k == 0 or ys[k] <= ys[k - 1]) and (k == len(xs) - 1 or ys[k] <= ys[k + 1])
            and ys[k] <= ys.min() * (1 + 1e-3)]
    assert mins
    found = []
    for k in mins:
        x0, y0, step = xs[k], ys[k], h
        while step > finest:
            grid = np.clip(np.linspace(x0 - step, x0 + step, 21), lo, hi)
            vals = [lam_at(p, x) for x in grid]
            i = int(np.argmin(vals))
            if vals[i] <= y0:
                x0, y0 = float(grid[i]), float(vals[i])
            step /= 10.0
        found.append((y0, x0))
    return sorted(found)


@cache
def searched(name: str):
    return critical_position(AN, pattern(dict(ONE_PATCH=ONE_PATCH, TWO_PATCHES=TWO_PATCHES)[name]))


@cache
def scanned(name: str) -> list[tuple[float, float]]:
    lo, hi = dict(ONE_PATCH=(-1.2 - 1e-6, 1.2 + 1e-6), TWO_PATCHES=(-1.7, 1.2))[name]
    # a wheel's centre on the deck: the hand-computed range, a hair inside
    return brute_force(pattern(dict(ONE_PATCH=ONE_PATCH, TWO_PATCHES=TWO_PATCHES)[name]), lo + 1e-6, hi - 1e-6)


# ------------------------------------------------------------------------------- bounds
@pytest.mark.parametrize("loads, bounds", [
    # one axle: its reference is on the deck
    (dict(vehicle=[dict(axles=[[0.0, 1.0]])]), (-1.2, 1.2)),
    # axles at 0 and 0.5 m: from the second axle on the left end to the first on the right end
    (dict(vehicle=[dict(axles=[[0.0, 1.0], [0.5, 1.5]])]), (-1.7, 1.2)),
    # axles behind the reference (offsets -0.3 and 0.4): -1.2 - 0.4 to 1.2 + 0.3
    (dict(vehicle=[dict(axles=[[-0.3, 1.0], [0.4, 1.0]])]), (-1.6, 1.5)),
    # moving point loads 0.6 m apart stay on the deck together: the reference (the first, at
    # x = -0.1) from -1.2 to 1.2 - 0.6
    (dict(point=[dict(on_top=[-0.1, 0.0], force=[0, 0, -1.0]), dict(on_top=[0.5, 0.0], force=[0, 0, -1.0])]),
     (-1.2, 0.6)),
])
def test_the_range_searched_is_where_a_moving_load_is_on_the_deck(loads, bounds):
    res = critical_position(AN, LoadPattern(lateral=False, **loads))
    assert res.status == "optimal"
    assert res.bounds == pytest.approx(bounds, abs=1e-9)
    assert res.x.min() >= bounds[0] and res.x.max() <= bounds[1]
    # the scan reaches both ends of the range (within DELTA of it)
    assert res.x.min() == pytest.approx(bounds[0], abs=1e-6) and res.x.max() == pytest.approx(bounds[1], abs=1e-6)


# ---------------------------------------------------------------- position and factor
@pytest.mark.parametrize("name", ["ONE_PATCH", "TWO_PATCHES"])
def test_position_and_factor_against_a_brute_force_scan(name):
    """The least multiplier is no higher than the scan's, and found where the scan finds it
    (the leftmost of mirror positions), to the search's tolerance."""
    res = searched(name)
    lam_ref, x_ref = scanned(name)[0]
    assert res.status == "optimal" and res.xtol == pytest.approx(XTOL)
    assert res.lambda_max == pytest.approx(lam_ref, rel=1e-7)
    leftmost = min(x for lam, x in scanned(name) if lam <= lam_ref * (1 + 1e-6))
    assert res.critical_x == pytest.approx(leftmost, abs=XTOL)
    # the reported factor is the direct limit at the reported position
    assert lam_at(pattern(dict(ONE_PATCH=ONE_PATCH, TWO_PATCHES=TWO_PATCHES)[name]), res.critical_x) == pytest.approx(
        res.lambda_max, rel=1e-12)


@pytest.mark.parametrize("name", ["ONE_PATCH", "TWO_PATCHES"])
def test_the_least_lies_inside_a_piece_where_only_the_refinement_finds_it(name):
    """The brute-force least is farther than the tolerance from every position the search
    scans before refining, and lower than all of them: the refinement (not the scan) found
    it, between the scanned neighbours of a minimum."""
    res = searched(name)
    lam_ref, x_ref = scanned(name)[0]
    p = pattern(dict(ONE_PATCH=ONE_PATCH, TWO_PATCHES=TWO_PATCHES)[name])
    scan = scan_positions(p, AN.assembly, *res.bounds)
    assert np.abs(scan - x_ref).min() > 10 * XTOL
    on_scan = {float(x): float(y) for x, y in zip(res.x, res.lam)}
    assert min(on_scan[float(x)] for x in scan if float(x) in on_scan) > lam_ref * (1 + 1e-5)
    # the bracket: the scanned positions either side of the answer hold it between them
    k = np.searchsorted(scan, res.critical_x)
    assert 0 < k < len(scan) and scan[k - 1] < res.critical_x < scan[k]


# ------------------------------------------------------------------------------- ties
def test_a_symmetric_load_ties_with_its_mirror_image_and_the_leftmost_is_reported():
    """One axle on the symmetric arch: lambda_max(x) = lambda_max(-x). The scan finds the least
    at both, the search reports the left one with the right one as its only tie."""
    res = searched("ONE_PATCH")
    minima = scanned("ONE_PATCH")
    assert len(minima) == 2 and minima[0][0] == pytest.approx(minima[1][0], rel=1e-7)
    assert sorted(x for _, x in minima) == pytest.approx([-0.298, 0.298], abs=2e-3)
    assert res.critical_x < 0 and len(res.ties) == 1
    assert res.ties[0] == pytest.approx(-res.critical_x, abs=XTOL)
    assert lam_at(pattern(ONE_PATCH), res.ties[0]) == pytest.approx(res.lambda_max, rel=1e-6)
    assert "tied positions" in res.message


def test_an_unsymmetric_load_has_no_tie():
    """Unequal axles: the mirror position is a different load, with a higher multiplier."""
    res = searched("TWO_PATCHES")
    assert res.ties == () and "tied" not in res.message
    mirror = -res.critical_x - 0.5  # the axles' mirror images: the 1.5 kN axle first
    assert lam_at(pattern(TWO_PATCHES), mirror) > res.lambda_max * (1 + 1e-3)


def test_two_equal_point_axles_tie_with_their_mirror_the_leftmost_reported():
    """Two equal axles 0.4 m apart at reference x stand where their mirror image stands at
    -x - 0.4: the search's two tied answers are each other's mirror."""
    p = pattern(dict(axles=[[0.0, 1.0], [0.4, 1.0]]))
    res = critical_position(AN, p)
    lam_ref, x_ref = brute_force(p, -1.6 + 1e-6, 1.2 - 1e-6)[0]
    # the least is at a kink (an axle on a joint's extrados), which the zoom approaches from above
    assert lam_ref * (1 - 1e-6) <= res.lambda_max <= lam_ref
    assert len(res.ties) == 1
    assert res.critical_x < res.ties[0]
    assert res.critical_x + res.ties[0] == pytest.approx(-0.4, abs=2 * XTOL)
    assert res.critical_x == pytest.approx(min(x_ref, -x_ref - 0.4), abs=XTOL)


# ---------------------------------------------------------------------------- skew decks
SKEW = 30.0  # degrees: the bed joints' extrados edges run at this angle from the y axis


def _bridge(skew: float, bond: str = "stack"):
    return arch_bridge(span=6.0, rise=1.5, thickness=0.4, depth=2.0, voussoirs=4, courses=2, bond=bond,
                       skew=skew, pier_height=1.0)


def _breakpoints(p: LoadPattern, assembly) -> np.ndarray:
    """The breakpoints behind a scan: the midpoints of its pairs of positions DELTA of the
    range either side of one (the scan's ends and midpoints left out)."""
    lo, hi = search_bounds(p, assembly)
    scan = scan_positions(p, assembly, lo, hi)
    d = DELTA * (hi - lo)
    return np.array([x + d for x in scan if np.isclose(scan, x + 2 * d, rtol=0, atol=1e-3 * d).any()])


@pytest.mark.parametrize("y", [-0.7, 0.3, 1.0])
def test_a_skew_deck_breaks_where_the_wheel_line_crosses_the_oblique_joints(y):
    """A point wheel on the line y over a skew deck of stacked courses passes from voussoir to
    voussoir where its line crosses the oblique extrados joints: at the square deck's joint
    abscissae shifted by y tan(skew), and nowhere else (the other courses' vertices, at
    other abscissae, are not breakpoints: the wheel never meets them)."""
    p = pattern(dict(axles=[[0.0, 1.0]], y=y))
    square = deck_edges(_bridge(0.0))
    assert len(square) == 5  # the abutments' faces and the 3 joints between 4 voussoirs
    assert _breakpoints(p, _bridge(0.0)) == pytest.approx(square[1:-1], abs=1e-12)  # the ends: the range's
    skew = _bridge(SKEW)
    assert len(deck_edges(skew)) == 15  # every course's vertices: 10 of them are not on the line
    want = square + y * np.tan(np.radians(SKEW))
    lo, hi = search_bounds(p, skew)
    assert _breakpoints(p, skew) == pytest.approx(want[(want > lo) & (want < hi)], abs=1e-9)


def test_a_patch_breaks_where_its_sides_cross_the_oblique_joints():
    """A patch 0.4 m wide on the line y = 0.3 (its sides at y = 0.1 and 0.5) over the skew
    deck: its edges meet each oblique joint twice, at the joint's abscissae on its two sides,
    each shifted by half the patch's length either way."""
    y, (lx, ly) = 0.3, (0.2, 0.4)
    p = pattern(dict(axles=[[0.0, 1.0]], y=y, patch=[lx, ly]))
    joints = deck_edges(_bridge(0.0))
    t = np.tan(np.radians(SKEW))
    want = np.sort([j + side * t + s * lx / 2 for j in joints for side in (y - ly / 2, y + ly / 2) for s in (-1, 1)])
    got = _breakpoints(p, _bridge(SKEW))
    lo, hi = search_bounds(p, _bridge(SKEW))
    assert got == pytest.approx(want[(want > lo) & (want < hi)], abs=1e-9)


@pytest.mark.parametrize("dispersion", [0.0, DISPERSION_2_TO_1])
def test_under_a_dispersing_fill_every_deck_vertex_stays_a_breakpoint(dispersion):
    """A point wheel under a fill that spreads it: its patch grows with the depth under the
    wheel (its sides are not lines), so every vertex abscissa of the skew deck is a
    breakpoint; without dispersion, only its line's crossings."""
    skew = _bridge(SKEW)
    p = LoadPattern(lateral=False, vehicle=[dict(axles=[[0.0, 1.0]], y=0.3)],
                    fill=Fill(depth=0.5, unit_weight=18.0, dispersion=dispersion))
    lo, hi = search_bounds(p, skew)
    want = deck_edges(skew) if dispersion else deck_edges(skew, (0.3, 0.3))
    assert _breakpoints(p, skew) == pytest.approx(want[(want > lo) & (want < hi)], abs=1e-9)
