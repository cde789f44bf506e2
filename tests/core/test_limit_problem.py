"""The direct limit (issue 24), tce against itself: limit problems do not share arrays;
the mechanism classified later equals the one classified at once; one formulation is shared
by an analysis's TCE and limit solvers. Speed is measured in ``benchmarks/solver_overhead.py``,
never here."""

import numpy as np
import pytest

from tce.analysis import Analysis
from tce.analysis.loadpath import load_path
from tce.core.limit import LimitSolver
from tce.core.loads import scene_vectors
from tce.core.material import Material
from tce.core.model import build_model
from tce.core.problem import Formulation, limit_problem
from tce.core.solve import TCESolver


def test_fresh_limit_problems_do_not_share_arrays(arch):
    f = Formulation(build_model(arch, "planar"), Material(friction=0.6))
    b_fixed, b_live = f.model.b_dead, f.model.b_lateral(0.0)
    p = limit_problem(f, b_fixed, b_live)
    before = p.A.copy()
    limit_problem(f, b_fixed, 7.0 * b_live)
    assert abs(p.A - before).max() == 0.0


@pytest.mark.parametrize("kind, alpha", [("spatial", 0.0), ("spatial", 90.0), ("planar", 0.0)])
def test_mechanism_later_equals_mechanism_at_once(arch, kind, alpha):
    model = build_model(arch, kind)
    solver = LimitSolver(model, Material(friction=0.8))
    bare = solver.solve(alpha, mechanism=False)
    full = solver.solve(alpha)
    assert bare.status == full.status == "optimal"
    assert bare.mechanism is None and np.isnan(bare.admissibility)
    assert bare.lambda_max == full.lambda_max
    later = solver.with_mechanism(bare)
    assert later.mechanism is not None and later is not bare
    np.testing.assert_array_equal(later.mechanism.velocities, full.mechanism.velocities)
    assert later.mechanism.modes == full.mechanism.modes
    assert later.admissibility == full.admissibility <= 1e-6
    assert later.lambda_max == bare.lambda_max and later.forces is bare.forces
    assert solver.with_mechanism(later) is later


def test_solve_loads_without_mechanism_keeps_the_certificate(arch):
    model = build_model(arch, "planar")
    solver = LimitSolver(model, Material(friction=0.8))
    _, b_fixed, b_live = scene_vectors(model, 0.0)
    res = solver.solve_loads(b_fixed, b_live, mechanism=False)
    assert res.certificate_gap <= 1e-6
    np.testing.assert_allclose(res.row_velocities @ b_live, 1.0, rtol=1e-8)


def test_analysis_shares_one_formulation(arch):
    an = Analysis(arch, Material(friction=0.8), model="planar")
    lim = an.limit(0.0, mechanism=False)
    f = an.formulation("planar")
    assert an.solver("planar").formulation is f
    assert an._limit_solvers["planar"].formulation is f
    assert lim.mechanism is None
    again = an.limit(0.0)  # asked for now: classified once and kept
    assert again.mechanism is not None and again.lambda_max == lim.lambda_max
    assert an.limit(0.0) is again


def test_load_path_mechanism_only_when_asked(arch):
    settle = {"right": [1e-3, 0, 0, 0, 0, 0]}
    bare = load_path(Analysis(arch, Material(friction=0.8)), 0.0, settle, atol=1e-6, mechanism=False)
    full = load_path(Analysis(arch, Material(friction=0.8)), 0.0, settle, atol=1e-6)
    assert bare.limit.mechanism is None and full.limit.mechanism is not None
    assert bare.lambda_max == full.lambda_max and bare.n_solves == full.n_solves


def test_a_formulation_of_another_model_or_law_is_refused(arch):
    planar, spatial = build_model(arch, "planar"), build_model(arch, "spatial")
    mat = Material(friction=0.8)
    f = Formulation(planar, mat)
    with pytest.raises(ValueError, match="same model"):
        LimitSolver(spatial, mat, formulation=f)
    with pytest.raises(ValueError, match="same model"):
        LimitSolver(planar, Material(friction=0.5), formulation=f)
    with pytest.raises(ValueError, match="same model"):
        TCESolver(spatial, mat, formulation=f)
    from tce.core.pyramid import pyramid_rows

    rows = pyramid_rows(planar, 0.8, 4, "inscribed")
    with pytest.raises(ValueError, match="same model"):
        TCESolver(planar, mat, formulation=Formulation(planar, mat, rows))


def test_one_solver_many_patterns_equals_fresh_solvers(arch):
    """The solver keeps the last pattern's load vectors: a new direction or pattern is not it."""
    from tce.core.loads import LoadPattern

    model = build_model(arch, "spatial")
    mat = Material(friction=0.8)
    solver = LimitSolver(model, mat)
    calls = [dict(alpha=0.0), dict(alpha=90.0), dict(alpha=None), dict(loads=LoadPattern(alpha=45.0)),
             dict(loads=LoadPattern(alpha=45.0)), dict(alpha=0.0)]
    for kw in calls:
        got = solver.solve(mechanism=False, **kw)
        ref = LimitSolver(model, mat).solve(mechanism=False, **kw)
        assert got.lambda_max == pytest.approx(ref.lambda_max, rel=1e-9)
        assert got.alpha == ref.alpha
