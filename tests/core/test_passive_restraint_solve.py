"""One solve path with and without the fill's passive restraint (tce.core.solve, issue 24
follow-up): the restraint is bounded columns of the same warm problem, phase-1, retries,
residual check and canonical state, so

- the canonical problem's data are those the module docstring writes (sparse stacking), also
  with the restraint and with a law that has zero rows;
- one solver that changes between patterns with and without a restraint gives what fresh
  solvers give (its warm solvers follow the restraint);
- a restrained state passes the residual check that counts ``G p`` in equilibrium and the
  bounds in the law, and the canonical state of a restrained scene is of least selection
  energy among the optimal states (checked against states the solver reports at other points).

tce against itself: the validation of the restraint is tests/validation/test_passive_restraint.py
(an independent LP) and of the canonical state tests/core/test_canonical.py. Speed is measured in
``benchmarks/solver_overhead.py``, never here.
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from tce.core.analysis import Analysis
from tce.core.canonical import RESTRAINT_WEIGHT, canonical_problem, restrained_canonical_problem
from tce.core.fill import Fill
from tce.core.loads import LoadPattern
from tce.core.material import Material
from tce.core.model import build_model
from tce.core.passive import passive_restraint
from tce.core.problem import Formulation, tce_b
from tce.core.vehicles import Vehicle
from tce.structures.arch import segmental_arch

RING = segmental_arch(span=6.0, rise=1.5, thickness=0.3, depth=3.0, voussoirs=12, unit_weight=20.0)
WHEEL = Vehicle(axles=((0.0, 100.0),))
SPREAD = {"right": [0.002, 0.0, 0.0, 0.0, 0.0, 0.0]}


def pattern(kp: float, x: float = -1.8) -> LoadPattern:
    return LoadPattern(lateral=False, vehicle=[WHEEL],
                       fill=Fill(depth=0.3, unit_weight=18.0, k0=0.5, kp=kp, dispersion=0.0)).moved(x)


def _stacked(f: Formulation, q: np.ndarray) -> sp.csc_matrix:
    """The canonical problem's matrix as its docstring writes it: the TCE rows, the energy row
    ``q'x`` after the law's zero rows."""
    M, nz = f.law.M.tocsr(), f.law.n_zero
    return sp.vstack([f.A_eq, -M[:nz], sp.csr_matrix(q.reshape(1, -1)), -M[nz:]]).tocsc()


def _arrays_equal(a: sp.csc_matrix, b: sp.csc_matrix) -> bool:
    return a.shape == b.shape and all(np.array_equal(getattr(a, k), getattr(b, k)) for k in ("data", "indices", "indptr"))


@pytest.mark.parametrize("kind", ["planar", "spatial"])
@pytest.mark.parametrize("friction", [0.0, 0.6, None])  # 0: the law has zero rows (ft = 0)
def test_canonical_problem_is_the_stacked_one(arch, kind, friction):
    f = Formulation(build_model(arch, kind), Material(friction=friction))
    U = np.zeros(12)
    U[6] = 0.001
    q = f.q(U)
    b = tce_b(f, f.model.b_dead)
    p = canonical_problem(f, b, q, 0.5)
    # the very arrays the stacking gives (a different order of the same entries would change
    # Clarabel's iterates): the canonical states stay those of the stacked problem
    assert _arrays_equal(p.A, _stacked(f, q))
    i = f.A_eq.shape[0] + f.law.n_zero
    np.testing.assert_array_equal(p.b, np.concatenate([b[:i], [0.5], b[i:]]))


def test_restrained_canonical_problem_appends_the_bounded_columns():
    model = build_model(RING, "planar")
    f = Formulation(model, Material())
    r = passive_restraint(model, pattern(2.0).fill)
    q = f.q(np.r_[np.zeros(6), SPREAD["right"]])
    b = tce_b(f, model.b_dead)
    p = restrained_canonical_problem(f, b, q, 0.5, r.G, r.capacity)
    n, k, W = f.n, r.size, f.scaling.force
    base = canonical_problem(f, b, q, 0.5)
    m = base.A.shape[0]
    assert p.A.shape == (m + 2 * k, n + k)
    assert abs(p.A[:m, :n] - base.A).max() == 0.0
    np.testing.assert_allclose(p.A[: f.A_eq.shape[0], n:].toarray(), r.G * (W / f.row_div)[:, None], rtol=1e-15)
    assert p.A[f.A_eq.shape[0] : m, n:].nnz == 0
    np.testing.assert_array_equal(p.b, np.concatenate([base.b, np.zeros(k), r.capacity / W]))
    np.testing.assert_array_equal(p.P.diagonal()[n:], RESTRAINT_WEIGHT)


def test_one_solver_across_patterns_with_and_without_the_restraint_gives_what_fresh_ones_give():
    shared = Analysis(RING)
    for kp, lam, sett in ((2.0, 1.5, None), (0.0, 1.0, None), (2.0, 1.5, SPREAD), (4.0, 2.0, SPREAD), (2.0, 1.5, None)):
        pat = pattern(kp)
        a, b = shared.solve(lam, loads=pat, settlements=sett), Analysis(RING).solve(lam, loads=pat, settlements=sett)
        assert a.status == b.status == "optimal"
        assert (a.restraint_forces is None) == (b.restraint_forces is None) == (kp == 0.0)
        # canonical states (unique minimisers), reached along different solver histories
        np.testing.assert_allclose(a.forces, b.forces, atol=1e-6 * RING.total_weight)
        if kp:
            np.testing.assert_allclose(a.restraint_forces, b.restraint_forces, atol=1e-6 * RING.total_weight)
            assert a.message.endswith(f"passive restraint: {len(a.restraint_forces)} bounded forces")


def test_a_moving_vehicle_keeps_the_restraint_of_its_fill():
    solver = Analysis(RING).solver("planar")
    one, two = solver.restraint(pattern(2.0, -1.8)), solver.restraint(pattern(2.0, 0.5))
    assert one is two  # one Restraint per fill: the warm solvers are kept
    assert solver.restraint(pattern(3.0, 0.5)) is not one
    assert solver.restraint(pattern(0.0, 0.5)) is None


@pytest.mark.parametrize("sett", [None, SPREAD])
def test_restrained_states_pass_the_check_with_the_restraint_and_are_least_selection_energy(sett):
    from tce.core.clarabel_solver import SolverOptions

    an = Analysis(RING)
    pat = pattern(2.0)
    lam = 1.0  # below the collapse without the restraint (1.571): the optimal face is wide
    r = an.solve(lam, loads=pat, settlements=sett)
    assert r.status == "optimal" and r.eq_residual <= 1e-9 and r.cone_residual <= 1e-9
    solver = an.solver(r.model)
    model, f = solver.model, solver.formulation
    rest = solver.restraint(pat)
    p = r.restraint_forces
    assert np.all(p >= -1e-9 * RING.total_weight) and np.all(p <= rest.capacity + 1e-9 * RING.total_weight)
    # equilibrium holds with the restraint's wrenches
    b_fixed, b_live = solver.vectors(pat)
    eq = (model.A_eq @ r.forces.ravel() + rest.G @ p + b_fixed + lam * b_live) / f.row_div
    assert np.abs(eq).max() <= 1e-9
    # the selection energy of the canonical state is below that of the solver's own optimal state
    # (another point of the optimal face, same TCE), which the option canonical=False reports
    raw = Analysis(RING, options=SolverOptions(canonical=False)).solve(lam, loads=pat, settlements=sett)
    assert raw.tce == pytest.approx(r.tce, abs=1e-8 * RING.total_weight)
    c = model.compliance(1.0, 1.0)
    W = f.scaling.force

    def selection(s) -> float:
        return float((s.forces.ravel() / W) @ (c / c.max() * s.forces.ravel() / W)
                     + RESTRAINT_WEIGHT * (s.restraint_forces / W) @ (s.restraint_forces / W))

    assert selection(r) <= selection(raw) + 1e-9 * selection(r)
    if sett is None:  # no motion: every admissible state is optimal; the solver's leans on the fill
        assert selection(r) < 0.1 * selection(raw) and p.sum() < 0.01 * raw.restraint_forces.sum()


@pytest.mark.parametrize("lam, status", [(2.0, "optimal"), (2.5, "infeasible")])
def test_an_undecided_restrained_solve_is_decided_with_the_restraint(monkeypatch, lam, status):
    """The warm solve reports a numerical failure: phase-1 decides, with the restraint's forces
    (the ring carries the wheel to 1.571 without them and to 2.280 with kp = 2, the direct
    limits of tests/validation/test_passive_restraint.py), then the retries solve it."""
    from types import SimpleNamespace

    from tce.core.clarabel_solver import Solution
    from tce.core.solve import TCESolver

    monkeypatch.setattr(TCESolver, "_main", lambda self, q, U, b, restraint: Solution(
        "NumericalError", SimpleNamespace(iterations=0), 0.0, 0.0))
    r = Analysis(RING).solve(lam, loads=pattern(2.0))
    assert r.status == status
    assert r.retry == ("rescaled" if status == "optimal" else "phase-1")
    if status == "optimal":
        assert r.eq_residual <= 1e-9 and r.restraint_forces.sum() > 1.0
