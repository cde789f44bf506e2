"""The one place tce calls Clarabel: settings, setup, warm updates and timing.

Clarabel (Goulart and Chen, "Clarabel: an interior-point solver for conic programs with
quadratic objectives", 2024) solves a :class:`tce.core.problem.ConicProblem`. A
:class:`ClarabelSolver` is set up once per problem structure; a new load or support motion
only changes ``q`` and ``b``, a friction coefficient the values of ``A`` (:meth:`ClarabelSolver.update`), which keeps the symbolic
factorisation (presolve is off so that the data layout never changes).

Times are wall-clock times measured here around the calls (``time.perf_counter``):
``solve_time`` is the ``solve()`` call alone and ``setup_time`` the set-up or update that
preceded it (Clarabel's own ``solve_time`` includes its set-up).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from functools import cached_property, lru_cache

import clarabel
import numpy as np
from numpy.typing import NDArray

from .problem import ConicProblem

__all__ = ["SOLVED", "SOLVER_NAME", "ClarabelSolver", "Solution", "SolverOptions", "solve_once"]

SOLVER_NAME = f"clarabel {clarabel.__version__}"
#: Clarabel statuses whose iterate is worth checking
SOLVED = ("Solved", "AlmostSolved")


@dataclass(frozen=True)
class SolverOptions:
    """Tolerances and settings of the Clarabel solves.

    Parameters
    ----------
    tol : float
        Clarabel's gap and feasibility tolerances (relative, on the scaled problem).
    residual_tol : float
        Largest equilibrium residual and contact-law violation of an ``optimal`` answer,
        relative to the total weight (force rows) and weight times size (moment rows).
    feas_tol : float
        Phase-1 residual above which a load is declared infeasible.
    max_iter : int
        Clarabel's iteration limit.
    refine : bool
        Clarabel's iterative refinement of the KKT solves in the warm TCE solver (retries
        always refine). An answer still has to pass ``residual_tol``, so a load within
        ~1e-8 of lambda_max may be ``optimal`` without it.
    canonical : bool
        Report the canonical state of a rigid scene (:mod:`tce.core.canonical`: the optimal
        state of least unit-stiffness strain energy) and decide its uniqueness, on the first
        read of a result's state (:class:`tce.core.solve.TCEResult`); False: the solver's optimum.
    """

    tol: float = 1e-10
    residual_tol: float = 1e-9
    feas_tol: float = 1e-9
    max_iter: int = 200
    refine: bool = False
    canonical: bool = True

    def settings(
        self, robust: bool = False, tight: bool = False, refine: bool = True, kkt: str = "qdldl", b_norm: float = 0.0
    ) -> clarabel.DefaultSettings:
        """Clarabel settings.

        Parameters
        ----------
        robust : bool
            More iterations, equilibration and refinement, shorter steps (a retry).
        tight : bool
            Gap and feasibility tolerances a thousand times below ``feas_tol`` (for a
            phase-1 residual too close to ``feas_tol`` to be trusted).
        refine : bool
            Iterative refinement of the KKT solves (the warm solver passes ``self.refine``).
        kkt : {"qdldl", "faer"}
            Clarabel's direct KKT factorisation (:func:`tce.core.problem.kkt_method` chooses
            per model); faer runs on one thread.
        b_norm : float
            ``max |b|`` of the problem to solve (0: not given). Clarabel's primal residual is
            relative, ``||Ax + s - b||_inf / max(1, ||b||_inf + ||x||_inf + ||s||_inf)``
            (Goulart and Chen 2024, Sec. 5.2; ``DefaultInfo::update`` of Clarabel 0.9-0.11),
            while tce's residual check (``residual_tol``) is absolute on the scaled problem,
            so where the scaled offsets are large (a compressive strength ``fc A / W``) the
            feasibility tolerance is divided by ``max(1, 2 b_norm)`` (``||s||_inf`` is of the
            order of ``||b||_inf``; ``x`` is of order 1).
        """
        s = clarabel.DefaultSettings()
        s.verbose = False
        s.presolve_enable = False  # keeps the data layout fixed, so updates are allowed
        s.chordal_decomposition_enable = False
        tol = min(self.tol, 1e-3 * self.feas_tol) if tight else self.tol
        s.tol_gap_abs = s.tol_gap_rel = tol
        s.tol_feas = tol / max(1.0, 2.0 * b_norm)
        s.tol_infeas_abs = s.tol_infeas_rel = min(1e-8, 10 * self.tol)
        s.tol_ktratio = 1e-7
        s.max_iter = self.max_iter
        s.iterative_refinement_enable = refine or robust
        s.direct_solve_method = kkt
        if kkt == "faer":
            s.max_threads = 1
        if robust:
            s.max_iter = 5 * self.max_iter
            s.equilibrate_max_iter = 50
            s.static_regularization_constant = 1e-9
            s.iterative_refinement_max_iter = 50
            s.max_step_fraction = 0.95
        return s


@dataclass(frozen=True, eq=False)
class Solution:
    """What one Clarabel solve returned.

    Attributes
    ----------
    status : str
        Clarabel's status (``Solved``, ``AlmostSolved``, ``PrimalInfeasible``,
        ``DualInfeasible``, ``MaxIterations``, ...).
    x, z, s : ndarray
        Primal unknowns (n,), dual multipliers (m,) and slacks (m,) of the problem
        (converted from Clarabel's on first use).
    objective : float
        Primal objective value.
    iterations : int
        Interior-point iterations.
    solve_time : float
        Wall time of the ``solve()`` call (s).
    setup_time : float
        Wall time of the set-up or updates that preceded it (s).
    """

    status: str
    raw: object = field(repr=False)
    solve_time: float
    setup_time: float

    @property
    def solved(self) -> bool:
        """True when Clarabel reports a (possibly reduced-accuracy) solution."""
        return self.status in SOLVED

    @cached_property
    def x(self) -> NDArray[np.float64]:
        return np.asarray(self.raw.x)

    @cached_property
    def z(self) -> NDArray[np.float64]:
        return np.asarray(self.raw.z)

    @cached_property
    def s(self) -> NDArray[np.float64]:
        return np.asarray(self.raw.s)

    @property
    def objective(self) -> float:
        return float(self.raw.obj_val)

    @property
    def iterations(self) -> int:
        return int(self.raw.iterations)


def _cones(problem: ConicProblem) -> list:
    """Clarabel's cone objects of ``problem``, built once per cone list."""
    return _clarabel_cones(problem.cones)


@lru_cache(maxsize=64)
def _clarabel_cones(cones: tuple[tuple[str, int], ...]) -> list:
    kinds = {"zero": clarabel.ZeroConeT, "nonneg": clarabel.NonnegativeConeT, "soc": clarabel.SecondOrderConeT}
    return [kinds[k](d) for k, d in cones]


class ClarabelSolver:
    """A Clarabel solver set up for one problem; later solves may change ``q`` and ``b``.

    Parameters
    ----------
    problem : ConicProblem
    settings : clarabel.DefaultSettings
        From :meth:`SolverOptions.settings`.
    """

    def __init__(self, problem: ConicProblem, settings: clarabel.DefaultSettings) -> None:
        t0 = time.perf_counter()
        self.problem = problem
        self._solver = clarabel.DefaultSolver(problem.P, problem.q, problem.A, problem.b, _cones(problem), settings)
        self._setup = time.perf_counter() - t0

    def update(self, q: NDArray[np.float64] | None = None, b: NDArray[np.float64] | None = None,
               A: NDArray[np.float64] | None = None) -> None:
        """Replace ``q``, ``b`` and/or the nonzero values ``A`` of the constraint matrix (same
        shapes, ``A`` in the CSC order of ``problem.A.data``); the sparsity pattern and cones stay."""
        t0 = time.perf_counter()
        data = {k: v for k, v in (("q", q), ("b", b), ("A", A)) if v is not None}
        if data:
            self._solver.update(**data)
        self._setup += time.perf_counter() - t0

    def solve(self) -> Solution:
        """Solve the current data; the set-up time reported is what accrued since the last solve."""
        t0 = time.perf_counter()
        sol = self._solver.solve()
        t = time.perf_counter() - t0
        setup, self._setup = self._setup, 0.0
        return Solution(str(sol.status), sol, t, setup)


def solve_once(problem: ConicProblem, settings: clarabel.DefaultSettings) -> Solution:
    """Set up a solver for ``problem`` and solve it once."""
    return ClarabelSolver(problem, settings).solve()
