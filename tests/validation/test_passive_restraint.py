"""The fill's passive restraint (tce.core.fill ``kp``, tce.core.passive) against an
independent planar LP (tests/reference/passive_fill.py: HiGHS, its own ring geometry, fill
columns in closed form; never imports tce): a 6 m segmental ring (1.5 m rise, 0.3 m thick,
12 voussoirs, 3 m wide, 20 kN/m^3) under 0.3 m of fill (18 kN/m^3, k0 = 0.5), one 100 kN
wheel on the deck's centre line without dispersion, at several positions, with kp = 0
(off), 2 and 4."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tce.analysis.assessment import adequacy_factor
from tce.core.analysis import Analysis
from tce.core.fill import Fill, passive_bounds
from tce.core.loads import LoadError, LoadPattern
from tce.core.vehicles import Vehicle
from tce.structures.arch import segmental_arch

from reference.passive_fill import FilledRing

GEOM = dict(span=6.0, rise=1.5, thickness=0.3, depth=3.0, voussoirs=12, unit_weight=20.0)
RING = segmental_arch(**GEOM)
AN = Analysis(RING)
WHEEL = Vehicle(axles=((0.0, 100.0),))


def pattern(kp: float) -> LoadPattern:
    return LoadPattern(lateral=False, vehicle=[WHEEL], fill=Fill(depth=0.3, unit_weight=18.0, k0=0.5, kp=kp, dispersion=0.0))


def reference(kp: float) -> FilledRing:
    return FilledRing(6.0, 1.5, 0.3, 12, 3.0, 20.0, 0.3, 18.0, 0.5, kp)


@pytest.mark.parametrize("kp", [0.0, 2.0, 4.0])
@pytest.mark.parametrize("x", [-2.2, -1.8, -1.0, 0.5])
def test_collapse_load_equals_the_independent_lp(kp, x):
    res = AN.limit(loads=pattern(kp).moved(x), mechanism=False)
    lam_ref, _ = reference(kp).lambda_max([(x, 100.0)], passive=kp > 0)
    assert res.status == "optimal" and math.isfinite(lam_ref)
    assert res.lambda_max == pytest.approx(lam_ref, rel=1e-8)
    # the mechanism's virtual work, passive dissipation included, certifies the same value
    assert res.certificate_gap < 1e-7


def test_passive_forces_stay_within_their_bounds_and_are_mobilised():
    res = AN.limit(loads=pattern(2.0).moved(-1.8), mechanism=False)
    cap = np.array([b[3] for b in passive_bounds(RING, pattern(2.0).fill)])
    ref_cap = np.array([f[4] for f in reference(2.0).fill])
    np.testing.assert_allclose(cap, ref_cap, rtol=1e-12)
    p = res.restraint_forces
    assert p.shape == cap.shape and np.all(p >= -1e-6) and np.all(p <= cap + 1e-6)
    assert np.isclose(p, cap, rtol=1e-6).any()  # some piece resists with its full passive pressure


def test_passive_restraint_raises_the_collapse_load_and_switches_off():
    lam = [AN.limit(loads=pattern(kp).moved(-1.8), mechanism=False).lambda_max for kp in (0.0, 2.0, 4.0)]
    assert lam[0] < lam[1] < lam[2]
    off = AN.limit(loads=pattern(0.0).moved(-1.8), mechanism=False)
    assert off.restraint_forces is None  # kp = 0: the plain limit problem


def test_adequacy_factor_carries_the_passive_restraint_unfactored():
    # factors 1: the adequacy factor is the direct limit, restraint included
    pat = pattern(2.0).moved(-1.8)
    assert adequacy_factor(AN, pat).lambda_max == pytest.approx(AN.limit(loads=pat).lambda_max, rel=1e-8)


@pytest.mark.parametrize("kp", [0.5, 0.4, -1.0, float("nan")])
def test_bad_passive_coefficient_names_the_key(kp):
    with pytest.raises(LoadError, match="kp"):
        Fill(depth=0.3, unit_weight=18.0, k0=0.5, kp=kp)


@pytest.mark.parametrize("kp", [2.0, 4.0])
def test_load_path_with_the_restraint_brackets_the_direct_limit(kp):
    # the load path's force states carry the restraint: its bracket holds the direct limit
    # (which the independent LP checks above), as without the restraint
    from tce.analysis.loadpath import load_path

    pat = pattern(kp).moved(-1.8)
    direct = AN.limit(loads=pat, mechanism=False).lambda_max
    path = load_path(AN, loads=pat)
    assert path.status == "limit"
    assert path.lambda_max <= direct + 1e-9 <= path.lambda_upper + 2e-9
    assert path.lambda_max == pytest.approx(direct, rel=2e-4)
    # the refusal of kp is lifted: with kp = 0 the path stops far lower
    assert load_path(AN, loads=pattern(0.0).moved(-1.8)).lambda_max < 0.9 * direct


def test_force_state_keeps_the_restraint_within_its_bounds_and_in_equilibrium():
    pat = pattern(2.0).moved(-1.8)
    lam = 0.95 * AN.limit(loads=pat, mechanism=False).lambda_max
    r = AN.solve(lam, loads=pat)
    assert r.status == "optimal"
    cap = np.array([b[3] for b in passive_bounds(RING, pat.fill)])
    p = r.restraint_forces
    assert p.shape == cap.shape and np.all(p >= -1e-7) and np.all(p <= cap + 1e-7)
    assert p.max() > 1e-3  # the state leans on the fill: without it lam is not carried
    # equilibrium of every free block with the restraint forces, checked on the model's operators
    kind = AN.model_kind(loads=pat)
    model, solver = AN.model(kind), AN.solver(kind)
    b_fixed, b_live = solver.vectors(pat)
    G = solver.restraint(pat).G
    eq = model.A_eq @ r.forces.ravel() + G @ p + b_fixed + lam * b_live
    assert np.abs(eq).max() <= 1e-6 * np.abs(b_fixed).max()
    assert r.unique is False and "canonical state not found" not in r.message
    # the canonical state leans on the fill only where the joints need it: below the
    # collapse load without restraint, next to nothing (tce.core.canonical.RESTRAINT_WEIGHT)
    low = 0.5 * AN.limit(loads=pattern(0.0).moved(-1.8), mechanism=False).lambda_max
    assert AN.solve(low, loads=pat).restraint_forces.sum() <= 1e-2 * cap.sum()
    assert AN.solve(lam, loads=pattern(0.0).moved(-1.8)).status == "infeasible"
    assert AN.solve(lam, loads=pattern(0.0).moved(-1.8)).restraint_forces is None


def test_cvxpy_and_the_non_associative_estimate_refuse_the_passive_restraint():
    # these do not carry it: they refuse rather than leave it out silently
    from tce.core.cvx import CvxTCE

    with pytest.raises(LoadError, match="fill.kp"):
        CvxTCE(AN.model(AN.model_kind(loads=pattern(2.0))), AN.material).solve(0.5, loads=pattern(2.0).moved(-1.8))
