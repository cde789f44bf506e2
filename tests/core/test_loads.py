"""General loads (issue 12): point and distributed loads, fixed or scaled by lambda.

Behaviour and contracts: loads with no limit, the lateral pattern as explicit point loads, the
planar and spatial models, distributed loads, load paths, diagnosis, minimum thickness, the
cvxpy cross-check and the errors. The closed forms and the independent LP are in
tests/validation/test_loads_closed_forms.py.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from helpers import block_on_support, extrados_midpoint, point

from tce.analysis.diagnose import diagnose
from tce.analysis.loadpath import load_path
from tce.analysis.thickness import arch_minimum_thickness
from tce.core.analysis import Analysis
from tce.core.cvx import CvxTCE
from tce.core.loads import DistributedLoad, LoadError, LoadPattern, PointLoad, as_pattern, top_surface
from tce.core.material import Material
from tce.structures.arch import semicircular_arch

# ---------------------------------------------------------------------------- no limit
def test_vertical_load_over_the_support_interface_has_no_limit():
    a = block_on_support()
    an = Analysis(a, Material())
    pattern = point([0.0, 0.0, -1.0], block="block", at=[0.05, 0.0, 1.0])
    lim = an.limit(loads=pattern)
    assert lim.status == "unbounded" and lim.lambda_max == math.inf
    lp = load_path(an, step=1.0, lam_cap=20.0, loads=pattern)
    assert lp.outcome == "no_limit" and lp.status == "no_limit" and not lp.ok
    assert math.isnan(lp.lambda_max)
    assert all(s.status == "optimal" for s in lp.steps)


def test_arch_load_over_the_springing_has_no_limit(arch):
    # over the left springing the extrados belongs to v02; straight below lie the joints
    # v01|v02 and left|v01: a Heyman arch carries a vertical load there at any multiplier
    an = Analysis(arch, Material())
    pattern = point([0.0, 0.0, -1.0], on_top=[-1.1, 0.0])
    assert an.applied_loads(loads=pattern).blocks.tolist() == [arch.index["v02"]]
    assert an.limit(loads=pattern).status == "unbounded"
    lp = load_path(an, step=2.0, lam_cap=20.0, loads=pattern)
    assert lp.outcome == "no_limit" and math.isnan(lp.lambda_max)


# ---------------------------------------------------------------------------- lateral as points
@pytest.mark.parametrize("alpha", [0.0, 90.0, 30.0])
def test_lateral_pattern_equals_explicit_point_loads_at_centroids(arch, alpha):
    a = math.radians(alpha)
    loads = [
        PointLoad(force=[w * math.cos(a), w * math.sin(a), 0.0], block=arch.names[i], scaled=True)
        for i, w in zip(arch.free_indices, arch.weights[list(arch.free_indices)])
    ]
    explicit = LoadPattern(alpha=alpha, lateral=False, point=loads)
    an = Analysis(arch, Material(0.8))
    ref = an.limit(alpha)
    lim = an.limit(loads=explicit)
    assert lim.model == ref.model
    assert lim.lambda_max == pytest.approx(ref.lambda_max, rel=1e-9)
    # a TCE solve below the limit: the same reactions
    U = {"right": [0.001, 0, 0, 0, 0, 0]}
    r0, r1 = an.solve(0.1, alpha, U), an.solve(0.1, settlements=U, loads=explicit)
    assert r0.ok and r1.ok
    np.testing.assert_allclose(r1.support_wrenches, r0.support_wrenches, atol=1e-7 * arch.total_weight)


# ---------------------------------------------------------------------------- planar model
def test_loads_off_the_plane_run_on_the_spatial_model(arch):
    an = Analysis(arch, Material())
    at = extrados_midpoint(6)
    off = point([0.0, 0.0, -1.0], block="v06", at=[at[0], 0.05, at[2]])
    sideways = point([0.0, 0.3, -1.0], block="v06", at=at)
    pair = LoadPattern(lateral=False, point=[PointLoad(force=[0, 0, -0.5], block="v06", at=[at[0], y, at[2]])
                                             for y in (-0.05, 0.05)])
    assert an.model_kind(loads=off) == "spatial" and an.limit(loads=off).model == "spatial"
    assert an.model_kind(loads=sideways) == "spatial"
    # two loads balanced about the plane: every block's wrench is in it, so planar is exact
    assert an.model_kind(loads=pair) == "planar"
    spatial = Analysis(arch, Material(), model="spatial")
    assert an.limit(loads=pair).lambda_max == pytest.approx(spatial.limit(loads=pair).lambda_max, rel=1e-7)
    # the eccentric load has no more capacity than the balanced pair (by symmetry and
    # convexity: the mean of its admissible state and its mirror image carries the pair)
    assert an.limit(loads=off).lambda_max <= an.limit(loads=pair).lambda_max * (1 + 1e-9)
    with pytest.raises(ValueError, match="plane"):
        Analysis(arch, Material(), model="planar").solve(0.5, loads=off)


# ---------------------------------------------------------------------------- distributed loads
@pytest.mark.parametrize("x", [(-1.2, 1.2), (-1.2, -0.9), (-0.3, 0.1), (0.95, 1.2)])
def test_distributed_load_covers_the_plan_once(arch, x):
    # the exposed top surface of the arch is its extrados (joints under the next voussoir and
    # the supports under v01 and v14 are hidden): the parts add up to the plan rectangle
    q = 3.0
    applied = Analysis(arch, Material()).applied_loads(loads=LoadPattern(distributed=[DistributedLoad(x=x, pressure=q)]))
    total = -applied.forces[:, 2].sum()
    assert total == pytest.approx(q * (x[1] - x[0]) * 0.25, rel=1e-12)
    assert not any(arch.blocks[i].support for i in applied.blocks)
    # every part's point lies on its block's extrados chord (radius of a chord at angle step pi/14)
    r = np.hypot(applied.points[:, 0], applied.points[:, 2])
    assert np.all((r <= 1.2 + 1e-12) & (r >= 1.2 * math.cos(math.pi / 28) - 1e-12))
    areas = sum(p.area for _, _, p in top_surface(arch))
    assert areas == pytest.approx(2.4 * 0.25, rel=1e-12)


def test_distributed_load_as_equivalent_point_loads(arch):
    # a live pressure over part of the extrados equals its parts as point loads
    pattern = LoadPattern(lateral=False, distributed=[DistributedLoad(x=(-0.5, 0.0), pressure=4.0)])
    an = Analysis(arch, Material())
    applied = an.applied_loads(loads=pattern)
    points = LoadPattern(lateral=False, point=[
        PointLoad(force=f, block=arch.names[i], at=p) for i, p, f in zip(applied.blocks, applied.points, applied.forces)
    ])
    assert an.limit(loads=pattern).lambda_max == pytest.approx(an.limit(loads=points).lambda_max, rel=1e-9)


# ---------------------------------------------------------------------------- downstream
def test_load_path_bisection_meets_the_direct_limit(arch):
    an = Analysis(arch, Material(0.8))
    pattern = LoadPattern(lateral=False, point=[PointLoad(force=[0, 0, -1.0], on_top=[-0.25, 0.0])],
                          distributed=[DistributedLoad(x=(-1.2, 1.2), pressure=0.5, scaled=False)])
    lp = load_path(an, settlements={"right": [0.001, 0, 0, 0, 0, 0]}, step=0.2, atol=1e-7, loads=pattern)
    assert lp.outcome == "limit" and lp.loads == pattern and math.isnan(lp.alpha)
    assert abs(lp.gap) <= 1e-7 and lp.at_limit.ok
    assert lp.limit.lambda_kinematic == pytest.approx(lp.lambda_direct, rel=1e-6)
    # a fixed surcharge over the span raises the capacity of the point load
    alone = an.limit(loads=point([0, 0, -1.0], on_top=[-0.25, 0.0])).lambda_max
    assert lp.lambda_direct > alone


def test_diagnose_a_pattern_beyond_its_limit(arch):
    an = Analysis(arch, Material())
    pattern = point([0, 0, -1.0], on_top=[-0.25, 0.0])
    lim = an.limit(loads=pattern)
    d = diagnose(an, 1.01 * lim.lambda_max, loads=pattern)
    assert d.status == "infeasible" and "load pattern's live part" in d.summary
    assert sum(m == "hinge" for m in d.mechanism.modes) == 4


def test_minimum_thickness_under_a_point_load():
    # the thinnest arch (centreline radius 1.1 m) that carries a 0.2 kN live load at x = -0.25 m
    pattern = point([0, 0, -0.2], on_top=[-0.25, 0.0])
    loaded = arch_minimum_thickness(1.1, 8, 0.25, tol=1e-3, loads=pattern, lam=1.0)
    # at the thickness found the load is (just) carried, below the bracket it is not
    t = loaded.thickness
    at = Analysis(semicircular_arch(1.1 - t / 2, t, 0.25, 8), Material()).limit(loads=pattern)
    below = Analysis(semicircular_arch(1.1 - loaded.lower / 2, loaded.lower, 0.25, 8), Material()).limit(loads=pattern)
    assert at.lambda_max >= 1.0 > below.lambda_max


def test_cvxpy_cross_check_with_a_pattern(arch):
    mat = Material(0.8, normal_stiffness=1e5)
    pattern = LoadPattern(lateral=False, point=[PointLoad(force=[0.1, 0, -1.0], on_top=[0.3, 0.0])],
                          distributed=[DistributedLoad(x=(-1.2, 0.0), pressure=0.3, scaled=False)])
    an = Analysis(arch, mat)
    U = {"right": [0.0005, 0, 0, 0, 0, 0]}
    r = an.solve(0.5, settlements=U, loads=pattern)
    cvx = CvxTCE(an.model(r.model), mat).solve(0.5, settlements=U, loads=pattern)
    assert r.ok and cvx.status == "optimal"
    np.testing.assert_allclose(cvx.support_wrenches, r.support_wrenches, atol=1e-5 * arch.total_weight)


# ---------------------------------------------------------------------------- declarations
def test_default_pattern_is_the_alpha_of_before(arch):
    an = Analysis(arch, Material())
    m = an.model("planar")
    b_fixed, b_live = an.solver("planar").vectors(LoadPattern(alpha=0.0))
    assert b_fixed is m.b_dead and b_live is m.b_lateral(0.0)
    assert an.limit(0.0) is an.limit(loads=LoadPattern(alpha=0.0))  # one cache entry per pattern


@pytest.mark.parametrize("make, key", [
    (lambda: PointLoad(force=[0, 0, 0], block="v01"), "force"),
    (lambda: PointLoad(force=[0, 0, float("nan")], block="v01"), "force"),
    (lambda: PointLoad(force=[0, 0, -1]), ""),
    (lambda: PointLoad(force=[0, 0, -1], block="v01", on_top=[0, 0]), ""),
    (lambda: PointLoad(force=[0, 0, -1], on_top=[0, 0], at=[0, 0, 1]), "at"),
    (lambda: DistributedLoad(x=[1.0, 0.0], pressure=1.0), "x"),
    (lambda: DistributedLoad(x=[0.0, 1.0], pressure=0.0), "pressure"),
    (lambda: LoadPattern(lateral=False), "lateral"),
    (lambda: LoadPattern(lateral=False, point=[{"force": [0, 0, -1], "block": "v01", "scaled": False}]), "lateral"),
    (lambda: LoadPattern(point=[{"force": [0, 0, -1], "blok": "v01"}]), "point[0].blok"),
    (lambda: LoadPattern(alpha=float("inf")), "alpha"),
])
def test_bad_declarations_name_their_key(make, key):
    with pytest.raises(LoadError) as info:
        make()
    assert info.value.key == key


@pytest.mark.parametrize("load, key, words", [
    (PointLoad(force=[0, 0, -1], block="v99"), "point[0].block", "not a block"),
    (PointLoad(force=[0, 0, -1], block="left"), "point[0].block", "support block"),
    (PointLoad(force=[0, 0, -1], block="v06", at=[5.0, 0.0, 1.0]), "point[0].at", "size"),
    (PointLoad(force=[0, 0, -1], on_top=[3.0, 0.0]), "point[0].on_top", "outside the plan"),
    (PointLoad(force=[0, 0, -1], on_top=[0.0, 0.5]), "point[0].on_top", "outside the plan"),
    (DistributedLoad(x=[2.0, 3.0], pressure=1.0), "distributed[0].x", "covers no block"),
])
def test_loads_that_cannot_be_applied_name_their_key(arch, load, key, words):
    kind = "point" if isinstance(load, PointLoad) else "distributed"
    with pytest.raises(LoadError, match=words) as info:
        Analysis(arch, Material()).limit(loads=LoadPattern(**{kind: [load]}))
    assert info.value.key == key


def test_loads_on_a_support_top_are_refused():
    a = block_on_support()  # the slab's top shows around the block
    with pytest.raises(LoadError, match="support block 'base'"):
        Analysis(a, Material()).applied_loads(loads=point([0, 0, -1], on_top=[0.35, 0.0]))
    with pytest.raises(LoadError, match="support block 'base'"):
        Analysis(a, Material()).applied_loads(loads=LoadPattern(distributed=[DistributedLoad(x=[-0.3, 0.3], pressure=1.0)]))


def test_alpha_and_pattern_given_once():
    assert as_pattern(30.0) == LoadPattern(alpha=30.0)
    assert as_pattern(0.0, LoadPattern(alpha=0.0)) == LoadPattern()
    with pytest.raises(ValueError, match="once"):
        as_pattern(30.0, LoadPattern(alpha=0.0))


def test_moving_load_and_round_trip():
    p = LoadPattern(lateral=False, point=[PointLoad(force=[0, 0, -1], on_top=[0.0, 0.1]),
                                          PointLoad(force=[0, 0, -2], on_top=[0.5, 0.0], scaled=False)])
    moved = p.moved(-0.4)
    assert moved.point[0].on_top == (-0.4, 0.1) and moved.point[1].on_top == (0.5, 0.0)
    assert LoadPattern.from_dict(moved.to_dict()) == moved
    with pytest.raises(LoadError, match="no scaled point load with on_top"):
        LoadPattern(point=[PointLoad(force=[0, 0, -1], block="v01")]).moved(0.0)


# ---------------------------------------------------------------------------- what lambda multiplies (issue 37)
LIVE = dict(point=[PointLoad(force=[0, 0, -1], on_top=[0.0, 0.0])])
FIXED = dict(point=[PointLoad(force=[0, 0, -1], on_top=[0.0, 0.0], scaled=False)])


@pytest.mark.parametrize("loads, lateral, expected", [
    ({}, None, True), ({}, True, True),
    (FIXED, None, True), (FIXED, True, True),
    (LIVE, None, False), (LIVE, True, True), (LIVE, False, False),
    (dict(distributed=[DistributedLoad(x=[-0.5, 0.5], pressure=1.0)]), None, False),
    (dict(vehicle=[dict(axles=[[0.0, 1.0]])]), None, False),
])
def test_the_lateral_pattern_joins_a_live_load_only_when_asked_for(loads, lateral, expected):
    """The rule of docs/studies.md (fails on main: a live load with lateral left out also got
    the lateral pattern)."""
    pattern = LoadPattern(lateral=lateral, **loads)
    assert pattern.lateral is expected
    assert ("the lateral load lambda*W" in pattern.multiplies) is expected


def test_lambda_multiplies_the_live_load_alone_by_default(arch):
    """A live point load at the crown without ``lateral``: its collapse load is that of the
    point load alone, not of the point load and a horizontal lambda*W together."""
    an = Analysis(arch, Material())
    alone = an.limit(loads=LoadPattern(lateral=False, **LIVE)).lambda_max
    both = an.limit(loads=LoadPattern(lateral=True, **LIVE)).lambda_max
    assert an.limit(loads=LoadPattern(**LIVE)).lambda_max == pytest.approx(alone, rel=1e-12)
    assert both < 0.5 * alone
    assert LoadPattern(**LIVE).multiplies == "lambda multiplies point[0] (1 kN); fixed: self-weight"
    assert LoadPattern(**FIXED).multiplies == ("lambda multiplies the lateral load lambda*W (every block's weight, "
                                               "horizontal) in direction alpha = 0 degrees; fixed: self-weight, point[0]")
