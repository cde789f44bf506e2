"""Limit analysis: the paper's anchors, closed forms, bisection vs direct, mechanisms, minimum thickness."""

import numpy as np
import pytest
from helpers import arch_centroid_height, block_on_support

from tce.analysis import Analysis
from tce.structures.arch import semicircular_arch
from tce.analysis.loadpath import load_path
from tce.core.material import Material
from tce.analysis.thickness import arch_minimum_thickness

MM = 1e-3


@pytest.mark.parametrize("mu", [None, 0.8])
def test_paper_anchors(arch, mu):
    an = Analysis(arch, Material(mu))
    assert an.limit(0.0).lambda_max == pytest.approx(0.243, rel=0.01)
    assert an.limit(90.0).lambda_max == pytest.approx(0.178, rel=0.005)


@pytest.mark.parametrize("depth, thickness", [(0.25, 0.2), (0.5, 0.2), (0.15, 0.3), (0.4, 0.15)])
def test_out_of_plane_rocking_closed_form(depth, thickness):
    a = semicircular_arch(1.0, thickness, depth, 14)
    lim = Analysis(a, Material()).limit(90.0)
    assert lim.lambda_max == pytest.approx((depth / 2) / arch_centroid_height(a), rel=1e-5)
    # the whole arch rocks on its two springing edges
    assert lim.mechanism.hinges == [0, len(a.interfaces) - 1]


@pytest.mark.parametrize("tol", [1e-2, 1e-4, 1e-6, 1e-8])
@pytest.mark.parametrize("alpha", [0.0, 90.0])
def test_bisection_agrees_with_direct(arch, tol, alpha):
    lp = load_path(Analysis(arch, Material(0.8)), alpha, {"right": [MM, 0, 0, 0, 0, 0]}, step=0.02, atol=tol)
    assert lp.outcome == "limit"
    assert abs(lp.gap) <= tol
    # the bisection's answer passed the residual checks (1e-9 of the weight), so it may sit
    # above the exact limit only by that much
    assert lp.gap <= 2e-8 * lp.lambda_direct
    assert lp.at_limit is not None and lp.at_limit.ok


def test_numerical_steps_are_never_the_limit(arch):
    lp = load_path(Analysis(arch, Material(0.8)), 0.0, {}, step=0.05, atol=1e-8)
    assert all(s.status != "numerical" or s.lam != lp.lambda_max for s in lp.steps)
    assert lp.at_limit.status == "optimal"


def test_in_plane_scenarios_meet_at_the_limit(arch):
    an = Analysis(arch, Material())
    scenes = {
        "inward": {"right": [-MM, 0, 0, 0, 0, 0]},
        "outward": {"right": [MM, 0, 0, 0, 0, 0]},
        "downward": {"right": [0, 0, -MM, 0, 0, 0]},
    }
    paths = {k: load_path(an, 0.0, v, step=0.02, atol=1e-7) for k, v in scenes.items()}
    # below the limit the thrusts differ ...
    mid = {k: next(r for r in p.path if abs(r.lam - 0.1) < 1e-12).support_wrenches for k, p in paths.items()}
    assert abs(mid["inward"][1, 0] - mid["outward"][1, 0]) > 0.05 * arch.total_weight
    # ... at the limit they coincide (unique limit state in the plane)
    at = {k: p.at_limit.support_wrenches for k, p in paths.items()}
    scale = np.abs(at["inward"]).max()
    for k in ("outward", "downward"):
        np.testing.assert_allclose(at[k], at["inward"], atol=1e-3 * scale)


def test_unbounded_settlement_stops_the_path(arch):
    lp = load_path(Analysis(arch, Material()), 0.0, {"right": [0, MM, 0, 0, 0, 0]}, step=0.05)
    assert lp.outcome == "unbounded" and np.isnan(lp.lambda_max)
    assert lp.steps[0].status == "unbounded"
    assert np.isfinite(lp.lambda_direct)  # the structure's capacity is still known


@pytest.mark.parametrize("alpha", [0.0, 90.0, 45.0])
@pytest.mark.parametrize("mu", [None, 0.8])
def test_mechanism_certificate(arch, alpha, mu):
    lim = Analysis(arch, Material(mu)).limit(alpha)
    assert lim.status == "optimal"
    assert lim.lambda_kinematic == pytest.approx(lim.lambda_max, rel=1e-6)
    assert lim.certificate_gap < 1e-6
    assert lim.admissibility < 1e-6


def test_in_plane_mechanism_has_four_hinges(arch):
    lim = Analysis(arch, Material()).limit(0.0)
    assert len(lim.mechanism.hinges) == 4
    assert not lim.mechanism.sliding
    # the hinge points lie on the intrados or the extrados
    r = np.hypot(lim.mechanism.hinge_points[lim.mechanism.hinges, 0], lim.mechanism.hinge_points[lim.mechanism.hinges, 2])
    assert np.all(np.isclose(r, 1.0) | np.isclose(r, 1.2))


def test_single_block_limits():
    an = Analysis(block_on_support(0.3, 1.2), Material(0.9))
    assert an.limit(0.0).lambda_max == pytest.approx(0.25, rel=1e-8)  # rocks: b/h
    an = Analysis(block_on_support(0.3, 1.2), Material(0.2))
    assert an.limit(0.0).lambda_max == pytest.approx(0.2, rel=1e-7)  # slides: mu


def test_minimum_thickness_converges_to_milankovitch():
    coarse = arch_minimum_thickness(voussoirs=14, tol=1e-6).ratio
    fine = arch_minimum_thickness(voussoirs=60, tol=1e-6).ratio
    assert coarse < fine <= 0.1075 * 1.005
    assert fine == pytest.approx(0.1075, rel=0.005)
    assert abs(fine - 0.1075) < abs(coarse - 0.1075)


def test_minimum_thickness_brackets_the_limit():
    res = arch_minimum_thickness(voussoirs=14, tol=1e-6)
    t, R = res.thickness, 1.0
    below = semicircular_arch(R - 0.995 * t / 2, 0.995 * t)
    above = semicircular_arch(R - 1.005 * t / 2, 1.005 * t)
    assert Analysis(above, Material()).solve(0.0).status == "optimal"
    assert Analysis(below, Material()).solve(0.0).status == "infeasible"
