"""QOCO (tce.core.qoco_solver, the optional extra whose CPU and CUDA builds are one code)
against Clarabel on the battery's scenes: same answers where Clarabel's pass tce's checks,
and never an answer that passes them where Clarabel certifies that none exists.

Skipped as a whole when the extra (``pip install tce[qoco]``) is absent."""

import numpy as np
import pytest

qoco = pytest.importorskip("qoco")

from battery.cases import MATERIALS, PLANAR, STRUCTURES, scene  # noqa: E402
from tce.core import qoco_solver  # noqa: E402
from tce.core.clarabel_solver import SolverOptions, solve_once  # noqa: E402
from tce.core.loads import scene_vectors  # noqa: E402
from tce.core.model import build_model  # noqa: E402
from tce.core.problem import Formulation, limit_problem, phase1_problem, recession_problem, tce_b, tce_problem  # noqa: E402
from tce.core.solve import settlement_vector  # noqa: E402

#: Clarabel as tce's LimitSolver calls it (with refinement), QOCO with the same tolerance and
#: TCESolver's iteration limit (200)
CLARABEL = SolverOptions(tol=1e-10, max_iter=500).settings(refine=True)
OPTIONS = SolverOptions(tol=1e-10)
#: the checks tce puts every answer through (LimitSolver: 1e-8 of W and W L; TCESolver: residual_tol)
LIMIT_CHECK, TCE_CHECK = 1e-8, 1e-9
#: agreement of lambda_max and of the objectives: a hundred times the solvers' tolerance
AGREE = 1e-8
#: the phase-1 residual (about 0.05-0.4 here): only its comparison with feas_tol = 1e-9 is used,
#: and the two solvers' values differ by up to 1.3e-7 relative (barrel vault with cohesion)
PHASE1_AGREE = 1e-6

MATS = ("heyman", "friction", "cohesion", "strengths", "compliant")
CASES = [(s, k, m, st) for s in STRUCTURES for k in (("planar", "spatial") if s in PLANAR else ("spatial",))
         for m in MATS for st in (("across",) if k == "spatial" else ("none", "in_plane"))]


def _problems(structure, kind, material, settlement):
    """(formulation, b_live, unbounded, [(label, problem)]) of one battery scene: the direct
    limit, the TCE at half of it and at one and a half times it (no admissible state), and the
    phase-1 residual there; ``unbounded`` is tce's own test of the TCE (the recession problem,
    as :class:`tce.core.solve.TCESolver` decides it: a Heyman scene with a motion across)."""
    sc = scene(structure, material, "lateral", settlement)
    model = build_model(sc.assembly, kind)
    f = Formulation(model, MATERIALS[material])
    sett = sc.settlements if kind == "spatial" else {}
    _, b_fixed, b_live = scene_vectors(model, None, sc.pattern, sett)
    U = settlement_vector(model, sett)
    limit = limit_problem(f, b_fixed, b_live)
    lam = float(solve_once(limit, CLARABEL).x[-1])
    out = [("limit", limit)]
    for k in (0.5, 1.5):
        out.append((f"tce {k}", tce_problem(f, tce_b(f, b_fixed + k * lam * b_live), U)))
    out.append(("phase-1 1.5", phase1_problem(f, b_fixed + 1.5 * lam * b_live)))
    rec = solve_once(recession_problem(f, U), CLARABEL)
    unbounded = f.D is None and rec.solved and rec.objective < -1e-9
    return f, b_live, unbounded, out


def _passes(f, label, problem, sol, b_live):
    """Whether ``sol`` passes tce's residual checks for ``problem`` (limit: LimitSolver's;
    TCE: TCESolver's; phase-1: no check, its answer is a residual)."""
    if not sol.solved:
        return False
    m = f.A_eq.shape[0]
    if label == "limit":
        eq, law = f.residuals_scaled(f.forces(sol.x), problem.b[:m] - float(sol.x[-1]) * b_live / f.row_div)
        return eq <= LIMIT_CHECK and law <= LIMIT_CHECK
    if label.startswith("tce"):
        eq, law = f.residuals_scaled(f.forces(sol.x), problem.b[:m])
        return eq <= TCE_CHECK and law <= TCE_CHECK
    return True


@pytest.mark.parametrize("structure, kind, material, settlement", CASES)
def test_qoco_agrees_with_clarabel(structure, kind, material, settlement):
    f, b_live, unbounded, problems = _problems(structure, kind, material, settlement)
    for label, p in problems:
        c = solve_once(p, CLARABEL)
        q = qoco_solver.solve_once(p, OPTIONS)
        if label == "tce 1.5":
            # above lambda_max: no admissible state, so no answer may pass the checks
            assert not _passes(f, label, p, c, b_live)
            assert not _passes(f, label, p, q, b_live), (label, q.status, q.objective)
        elif _passes(f, label, p, c, b_live):
            assert _passes(f, label, p, q, b_live), (label, q.status)
            tol = PHASE1_AGREE if label.startswith("phase-1") else AGREE
            assert abs(q.objective - c.objective) <= tol * max(1.0, abs(c.objective)), (label, q.objective, c.objective)
            if label == "limit":
                assert abs(q.x[-1] - c.x[-1]) <= AGREE * max(1.0, abs(c.x[-1]))
        else:
            # no minimum (a Heyman scene with a motion it cannot follow): no answer either
            assert label == "tce 0.5" and unbounded, (label, c.status)
            assert not _passes(f, label, p, q, b_live), (label, q.status, q.objective)


def test_qoco_rows_back_in_clarabel_order():
    """The multipliers come back in Clarabel's row order: those of the equilibrium rows of the
    limit problem are the collapse mechanism's virtual velocities, equal to Clarabel's where
    the mechanism is unique (the paper's arch, lateral load along the span)."""
    f, _, _, problems = _problems("semicircular_arch", "planar", "friction", "none")
    p = problems[0][1]
    c, q = solve_once(p, CLARABEL), qoco_solver.solve_once(p, OPTIONS)
    m = f.A_eq.shape[0]
    assert np.allclose(q.z[:m], c.z[:m], atol=1e-6 * np.abs(c.z[:m]).max())
    # and the slacks of the cone rows: b - A x
    assert np.allclose(q.s, p.b - p.A @ q.x, atol=1e-8)


def test_qoco_warm_update_equals_fresh_setup():
    """``QocoSolver.update`` (new ``b``) gives the answer of a solver set up on the new data."""
    f, _, _, problems = _problems("semicircular_arch", "spatial", "friction", "none")
    p = problems[1][1]
    s = qoco_solver.QocoSolver(p, OPTIONS)
    s.solve()
    b2 = p.b.copy()
    b2[: f.A_eq.shape[0]] *= 0.9  # a lighter structure
    s.update(b=b2)
    warm = s.solve()
    fresh = qoco_solver.solve_once(type(p)(p.name, p.P, p.q, p.A, b2, p.cones), OPTIONS)
    assert warm.status == fresh.status == "Solved"
    assert abs(warm.objective - fresh.objective) <= 1e-9 * abs(fresh.objective)


def test_split_keeps_every_row():
    """Every row of Clarabel's ``A`` goes to exactly one of QOCO's ``A`` (zero cone) and ``G``."""
    _, _, _, problems = _problems("dome", "spatial", "cohesion", "across")
    for _, p in problems:
        d = qoco_solver.split(p)
        rows = np.sort(np.concatenate([d.eq_rows, d.cone_rows]))
        assert np.array_equal(rows, np.arange(p.A.shape[0]))
        assert (d.G is None or (d.G != p.A[d.cone_rows]).nnz == 0) and (d.A is None or (d.A != p.A[d.eq_rows]).nnz == 0)
        assert d.l + int(d.q.sum()) == len(d.cone_rows)


def test_algebras_lists_the_cpu_build():
    assert "builtin" in qoco_solver.algebras()
