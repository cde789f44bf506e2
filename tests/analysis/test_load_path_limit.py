"""Limit analysis, tce against itself: the load path's bisection against the direct lambda_max,
the mechanism's certificate, statuses along a path. The paper's figures, closed forms and the
collapse mechanism against independent references: tests/validation/test_limits.py."""

import numpy as np
import pytest

from tce.analysis import Analysis
from tce.analysis.loadpath import load_path
from tce.core.material import Material

MM = 1e-3


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


def test_the_limit_is_an_optimal_step(arch):
    lp = load_path(Analysis(arch, Material(0.8)), 0.0, {}, step=0.05, atol=1e-8)
    assert lp.at_limit is not None and lp.at_limit.status == "optimal"
    assert lp.at_limit.lam == lp.lambda_max


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
    # ... at the limit they coincide (unique limit state in the plane): the bisection stops
    # within 1e-7 of lambda_max, where the admissible states differ by ~1e-7 (measured 8e-8)
    at = {k: p.at_limit.support_wrenches for k, p in paths.items()}
    scale = np.abs(at["inward"]).max()
    for k in ("outward", "downward"):
        np.testing.assert_allclose(at[k], at["inward"], atol=1e-6 * scale)


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


def test_large_meshes_are_factorised_by_faer_with_the_same_limit(monkeypatch):
    """The KKT factorisation is chosen per model (``kkt_method``: faer for large meshes,
    qdldl for chains and small models) and does not change the answer: a dome made to count
    as large gives the qdldl limit to 1e-9; an arch (a chain) stays on qdldl whatever its size."""
    from tce.core import problem
    from tce.core.clarabel_solver import SolverOptions
    from tce.core.limit import LimitSolver
    from tce.core.model import build_model
    from tce.structures.arch import semicircular_arch
    from tce.structures.dome import hemispherical_dome

    dome = build_model(hemispherical_dome(sectors=8, courses=4).validate(), "spatial")
    arch = build_model(semicircular_arch().validate(), "spatial")
    qdldl = LimitSolver(dome, Material(0.8)).solve(0.0)
    assert problem.Formulation(dome, Material(0.8)).kkt == "qdldl"
    monkeypatch.setattr(problem, "FAER_FROM", 100)
    f = problem.Formulation(dome, Material(0.8))
    assert f.kkt == "faer" and problem.kkt_method(arch) == "qdldl"
    s = SolverOptions().settings(kkt=f.kkt)
    assert s.direct_solve_method == "faer" and s.max_threads == 1
    faer = LimitSolver(dome, Material(0.8)).solve(0.0)
    assert qdldl.status == faer.status == "optimal"
    assert faer.lambda_max == pytest.approx(qdldl.lambda_max, rel=1e-9)


@pytest.mark.parametrize("kind", ["planar", "spatial"])
def test_problems_and_results_are_values_no_later_solve_changes(arch, kind, monkeypatch):
    """Every limit problem handed to Clarabel and every result returned stay as they were when
    the same solver solves again: the same direction scaled (the live load's nonzero rows
    unchanged), then another pattern."""
    import copy
    from dataclasses import fields

    from tce.core import limit
    from tce.core.limit import LimitSolver
    from tce.core.loads import scene_vectors
    from tce.core.model import build_model

    handed = []
    real = limit.solve_once
    monkeypatch.setattr(limit, "solve_once", lambda problem, settings: handed.append(problem) or real(problem, settings))
    model = build_model(arch, kind)
    solver = LimitSolver(model, Material(0.8))
    _, b_fixed, b_live = scene_vectors(model, 0.0)
    first = solver.solve_loads(b_fixed, b_live)
    problem = handed[0]
    held = copy.deepcopy({"A": problem.A.toarray(), "b": problem.b, "q": problem.q, "P": problem.P.toarray(),
                          **{f.name: getattr(first, f.name) for f in fields(first)
                             if isinstance(getattr(first, f.name), np.ndarray)}})
    second = solver.solve_loads(b_fixed, 2.0 * b_live)
    assert second.lambda_max == pytest.approx(first.lambda_max / 2.0, rel=1e-8)
    solver.solve(180.0 if kind == "planar" else 90.0)
    assert len(handed) >= 3 and handed[1] is not problem
    for name in ("A", "P"):
        np.testing.assert_array_equal(getattr(problem, name).toarray(), held.pop(name), err_msg=name)
    for name in ("b", "q"):
        np.testing.assert_array_equal(getattr(problem, name), held.pop(name), err_msg=name)
    for name, value in held.items():
        np.testing.assert_array_equal(getattr(first, name), value, err_msg=name)
