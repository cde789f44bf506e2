"""Canonical force states where the TCE optimum is not unique.

With rigid contacts the TCE is linear (``Pi_c = -U' B_sup F``), and its minimisers form a
face of the admissible set: every admissible state when no support moves, often a segment
or more with a settlement. An interior-point solver returns some point of that face (near
its analytic centre), which depends on the solver's path: curves along a load path then
zigzag between points of the face. tce reports one state chosen by a rule that does not
depend on the solver:

**The canonical state** is the optimal state of least complementary strain energy for a
uniform unit stiffness: among the admissible states ``F`` with ``Pi_c(F) <= Pi_c* + eps``
(the optimal face, ``eps`` relative to the optimum), the minimiser of

    1/2 F' C F,    C = diag(1 / (s_k a_k))  (per force component; s the interface's
                                               stiffness multiplier, a the tributary area)

i.e. ``tce.core.model.Model.compliance(1, 1)``: the limit, as the stiffness grows without
bound, of the compliant answer with equal normal and shear stiffness (the strictly convex
term selects one point of the face). The objective is strictly convex, so the canonical
state is unique; the planar model gives the spatial one (its contact force spread over the
vertices in proportion to their areas is the least-energy spread). ``eps`` is
:data:`FACE_SLACK` times the optimum (about the solver's own accuracy), so the quantities
the energy fixes (the thrust under a spreading) move by at most that fraction. When
Clarabel cannot solve the problem with a face that thin, it is solved again with the next
slack of :data:`FACE_SLACKS`, and those quantities move by at most that fraction. An
answer counts as solved only when it passes the caller's residual check
(``residual_tol``); at the last slack a warm solver that fails is followed by a fresh one
(equilibrated for this problem), then by one with robust settings
(:meth:`tce.core.clarabel_solver.SolverOptions.settings`): a thin face is as hard for an
interior-point method as a load next to its limit (the admissible set is a sliver).

**Uniqueness is decided** by comparing the solver's answer with the canonical state: an
interior-point answer lies in the relative interior of the optimal face, so when the face
is more than a point the two differ (by more than :data:`SAME_STATE` of the total weight
at some contact) and the state is flagged not unique (``unique = False``); when they agree,
the optimum is unique (``unique = True``). The test is exact for a face of one point and
fails only when the analytic centre of a larger face happens to be its least-energy point
(a symmetric face), which the comparison then reports as unique.

Cost: one more conic problem per rigid optimal state read (the TCE problem's constraints and
one row bounding the energy), with a warm solver per support motion. A solve's status does not
need it: :class:`tce.core.solve.TCEResult` selects its canonical state on the first read of the
state (``docs/conventions.md``), so a load path's decisions do not pay for it.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass
from functools import partial

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from .clarabel_solver import ClarabelSolver, SolverOptions
from .passive import Restraint
from .problem import ConicProblem, Formulation, _cones, _equilibrium_columns, with_bounded_forces

__all__ = ["FACE_SLACK", "FACE_SLACKS", "SAME_STATE", "Canonical", "CanonicalSolver", "Check", "canonical_b", "canonical_problem",
           "RESTRAINT_WEIGHT", "restrained_canonical_problem"]

#: slack of the energy bound of the optimal face, relative to the optimum
FACE_SLACK = 1e-10
#: the slacks tried in turn when the thinner face cannot be solved
FACE_SLACKS = (FACE_SLACK, 1e-8)
#: weight of the passive restraint's forces in the canonical selection (:func:`restrained_canonical_problem`)
RESTRAINT_WEIGHT = 1e4
#: two states differ when a force component differs by more than this, relative to W
SAME_STATE = 1e-6


def canonical_b(f: Formulation, b: NDArray[np.float64], bound: float) -> NDArray[np.float64]:
    """Right-hand side of :func:`canonical_problem` (what a warm solver updates) from the TCE
    problem's ``b`` (:func:`tce.core.problem.tce_b`, followed by the bounds of
    :func:`tce.core.problem.with_bounded_forces` for :func:`restrained_canonical_problem`):
    ``b`` with the energy bound inserted after the law's zero rows."""
    i = f.A_eq.shape[0] + f.law.n_zero
    return np.concatenate([b[:i], [bound], b[i:]])


def _insert_row(A: sp.csc_matrix, i: int, row: NDArray[np.float64]) -> sp.csc_matrix:
    """``A`` (CSC, sorted indices) with the nonzeros of the dense ``row`` inserted as row ``i``:
    the arrays ``sp.vstack([A[:i], row, A[i:]]).tocsc()`` has, without slicing and stacking
    (every new support motion direction sets up a canonical solver)."""
    cols = np.flatnonzero(row)
    ptr = A.indptr
    above = np.concatenate([[0], np.cumsum(A.indices < i)])  # entries of rows < i, counted
    at = ptr[cols] + (above[ptr[cols + 1]] - above[ptr[cols]])  # each new entry's place in its column
    indices = np.where(A.indices < i, A.indices, A.indices + 1)
    counts = np.zeros(A.shape[1], dtype=ptr.dtype)
    counts[cols] = 1
    return sp.csc_matrix(
        (np.insert(A.data, at, row[cols]), np.insert(indices, at, i).astype(A.indices.dtype),
         ptr + np.concatenate([[0], np.cumsum(counts)]).astype(ptr.dtype)),
        shape=(A.shape[0] + 1, A.shape[1]),
    )


def canonical_problem(f: Formulation, b: NDArray[np.float64], q: NDArray[np.float64], bound: float) -> ConicProblem:
    """``min 1/2 x' C x  s.t.  A_eq x = b_eq,  law,  q' x <= bound`` on the scaled unknowns
    ``x = F / W`` (the rows of :func:`tce.core.problem.tce_problem` plus one nonnegative row).

    ``C`` is the unit-stiffness compliance (module docstring), normalised to a largest
    entry of 1; without a motion (``q = 0``) the energy row is ``0 <= bound`` (every
    admissible state is optimal).
    """
    law = f.law
    m, n = f.A_eq.shape
    c = f.model.compliance(1.0, 1.0)
    P = sp.diags(c / c.max()).tocsc()
    nz = law.n_zero
    A = _insert_row(f.constraints, m + nz, q)
    cones = _cones(("zero", m + nz), ("nonneg", law.n_nonneg + 1), n_soc=law.n_soc)
    return ConicProblem("canonical", P, np.zeros(n), A, canonical_b(f, b, bound), cones)


def restrained_canonical_problem(
    f: Formulation, b: NDArray[np.float64], q: NDArray[np.float64], bound: float,
    G: NDArray[np.float64], capacity: NDArray[np.float64],
) -> ConicProblem:
    """:func:`canonical_problem` with the bounded extra forces ``0 <= p <= capacity`` (kN) of
    :func:`tce.core.problem.restrained_tce_problem` (the fill's passive restraint) in its
    equilibrium rows. Unknowns ``(x, p / W)``.

    ``p`` carries no TCE, but in the selection it carries the energy ``RESTRAINT_WEIGHT / 2
    (p / W)^2`` (:data:`RESTRAINT_WEIGHT` times the most compliant contact component's, whose
    normalised entry is 1): without it the least-energy state would lean on the free
    restraint and the fill would push with its full capacity far below collapse; with it the
    restraint is mobilised only where the contacts cannot carry the load alone (a rule of
    selection among equally admissible states, not a model of the fill's stiffness). The
    objective stays strictly convex: the canonical state is unique."""
    W = f.scaling.force
    k = G.shape[1]
    # zero in the energy row too: it comes after the equilibrium rows
    cols = sp.vstack([_equilibrium_columns(f, G), sp.csr_matrix((1, k))])
    out = with_bounded_forces(canonical_problem(f, b, q, bound), cols, np.asarray(capacity, dtype=float) / W)
    n = out.P.shape[0] - k
    P = sp.block_diag([out.P[:n, :n], sp.identity(k) * RESTRAINT_WEIGHT], format="csc")
    return ConicProblem(out.name, P, out.q, out.A, out.b, out.cones)


@dataclass(frozen=True)
class Canonical:
    """The canonical state of one solve.

    Attributes
    ----------
    forces : (n,) ndarray or None
        Physical forces (kN) of the canonical state; None when its solve failed or missed
        the residual check at every slack (the solver's answer is kept, uniqueness unknown).
    restraint_forces : (k,) ndarray or None
        Its passive restraint forces (kN; None without a restraint or without a state).
    residuals : tuple of float or None
        The caller's residuals of ``forces`` (equilibrium, contact law).
    unique : bool or None
        Whether the optimum is unique (module docstring); None when undecided.
    solve_time, setup_time : float
        Time of the extra solve (s).
    """

    forces: NDArray[np.float64] | None
    restraint_forces: NDArray[np.float64] | None
    residuals: tuple[float, float] | None
    unique: bool | None
    solve_time: float
    setup_time: float


#: What :meth:`CanonicalSolver.state` checks: scaled unknowns -> (forces (kN), restraint forces
#: (kN) or None, (equilibrium, contact-law) residuals)
Check = Callable[[NDArray[np.float64]], tuple[NDArray[np.float64], NDArray[np.float64] | None, tuple[float, float]]]


class CanonicalSolver:
    """Canonical states for one formulation; a warm Clarabel solver per support motion and
    passive restraint (a load path changes only the right-hand side and the energy bound)."""

    def __init__(self, f: Formulation, options: SolverOptions) -> None:
        self.f = f
        self.options = options
        self._warm: ClarabelSolver | None = None
        self._q: NDArray[np.float64] | None = None
        self._restraint: Restraint | None = None

    def state(
        self, b: NDArray[np.float64], q: NDArray[np.float64], x: NDArray[np.float64], check: Check,
        restraint: Restraint | None = None,
    ) -> Canonical:
        """The canonical state of the optimal answer ``x`` (scaled unknowns: ``F / W``, then the
        restraint's ``p / W``) of the TCE problem with scaled right-hand side ``b``
        (:func:`tce.core.problem.tce_b`, then the restraint's bounds,
        :func:`tce.core.problem.bounded_b`) and scaled objective ``q`` (``n``).

        ``check`` gives the forces and the equilibrium and contact-law residuals of scaled
        unknowns; a slack's answer is taken when both residuals are within
        ``options.residual_tol``, else the next slack is tried."""
        n = self.f.n
        value = float(q @ x[:n])
        solve_time = setup_time = 0.0
        for slack in FACE_SLACKS:
            # relative to the optimum itself (an absolute slack would move the quantities the
            # energy fixes, e.g. a thrust, by slack / |value|), with a floor at the rounding of q x
            bound = value + slack * abs(value) + 1e-15 * float(np.abs(q) @ np.abs(x[:n]))
            for solver in self._solvers(b, q, bound, restraint, fresh=slack == FACE_SLACKS[-1]):
                sol = solver.solve()
                solve_time += sol.solve_time
                setup_time += sol.setup_time
                if not sol.solved:
                    continue
                F, p, res = check(sol.x)
                if max(res) <= self.options.residual_tol:
                    same = float(np.abs(sol.x - x).max(initial=0.0)) <= SAME_STATE
                    return Canonical(F, p, res, same, solve_time, setup_time)
        return Canonical(None, None, None, None, solve_time, setup_time)

    def _solvers(
        self, b: NDArray[np.float64], q: NDArray[np.float64], bound: float, restraint: Restraint | None, fresh: bool
    ) -> Iterator[ClarabelSolver]:
        """The warm solver set to ``(b, q, bound)``, set up anew when it was for another ``q``
        or restraint; then, with ``fresh`` (the last slack), a new one (the warm solver keeps
        the equilibration of its first problem) and last one with robust settings.

        The warm solver refines its KKT solves as the warm TCE solver does
        (``options.refine``) where no support moves (``q = 0``: the face is the whole
        admissible set, and the answer's residuals are those of the TCE solve's), and always
        on the thin face of a motion (unrefined, its equilibrium residual reaches 1e-10);
        the fresh one always refines."""
        f = self.f
        if restraint is None:
            problem = partial(canonical_problem, f, b, q, bound)
        else:
            problem = partial(restrained_canonical_problem, f, b[: -2 * restraint.size], q, bound, restraint.G,
                              restraint.capacity)
        if self._warm is not None and np.array_equal(self._q, q) and self._restraint is restraint:
            self._warm.update(b=canonical_b(f, b, bound))
            yield self._warm
        else:
            refine = self.options.refine or bool(np.any(q))
            self._warm = ClarabelSolver(problem(), self.options.settings(refine=refine, kkt=f.kkt))
            self._q, self._restraint = q, restraint
            yield self._warm
        if fresh:
            yield ClarabelSolver(problem(), self.options.settings(kkt=f.kkt))
            yield ClarabelSolver(problem(), self.options.settings(robust=True, kkt=f.kkt))
