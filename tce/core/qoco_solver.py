"""A second conic backend whose CPU and CUDA builds are one code: QOCO.

QOCO (Chari and Acikmese, "QOCO: a quadratic objective conic optimizer with custom solver
generation", Mathematical Programming Computation, 2026; BSD-3-Clause) is a primal-dual
interior-point method for quadratic programs with second-order cone constraints::

    minimise    1/2 x' P x + c' x
    subject to  A x = b,   h - G x in C = R^l_+ x Q^{q_1} x ... x Q^{q_nsoc}

Its Python package selects the linear algebra at set-up: ``QOCO(algebra="builtin")`` (``pip
install qoco``, CPU) or ``QOCO(algebra="cuda")`` (``pip install qoco-cuda``, the same solver
with its vectors, matrices and KKT solves on an NVIDIA GPU). So the prototype measured here on
CPU is the code a GPU machine would run; ``pip install tce[qoco]`` brings the CPU build,
``tce[gpu]`` both (docs/scaling.md, "GPUs").

A :class:`tce.core.problem.ConicProblem` (Clarabel's ``A x + s = b, s in K``) maps onto it
row by row: the zero-cone rows become ``A x = b``, the nonnegative rows then the second-order
cones (in their order) become ``G, h`` with ``G`` the same rows of ``A``. The answer is put
back in Clarabel's row order, so a :class:`QocoSolver` returns the same
:class:`tce.core.clarabel_solver.Solution` as :class:`tce.core.clarabel_solver.ClarabelSolver`
and its statuses are read with Clarabel's words.

Statuses: QOCO has no infeasibility certificate. A problem without an admissible point, or
unbounded below, ends in ``MaxIterations`` or ``NumericalError`` (tce: ``numerical``), never in
``PrimalInfeasible``/``DualInfeasible``; a load path on QOCO alone could therefore not tell
collapse from trouble without the phase-1 problem (:func:`tce.core.problem.phase1_problem`),
which is always feasible and bounded. QOCO's "inaccurate" status is no certificate either: it
was returned for a TCE problem with no admissible state (the wall of ``studies/data/wall.json``,
Heyman's material, 1.5 lambda_max) and for unbounded ones (Heyman scenes with a support motion
across); there, as for every answer, tce's residual checks are what refuse it
(tests/test_qoco_backend.py).
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from types import SimpleNamespace

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from .clarabel_solver import Solution, SolverOptions
from .problem import ConicProblem

try:  # the optional extra: pip install tce[qoco] (CPU) or tce[gpu] (CPU and CUDA)
    import qoco
except ImportError:  # pragma: no cover - exercised where the extra is absent
    qoco = None

__all__ = ["AVAILABLE", "QocoData", "QocoSolver", "algebras", "solve_once", "split"]

#: whether the ``qoco`` package is installed
AVAILABLE = qoco is not None

#: QOCO's status words in Clarabel's (:data:`tce.core.clarabel_solver.SOLVED` are the first two)
STATUS = {
    "QOCO_SOLVED": "Solved",
    "QOCO_SOLVED_INACCURATE": "AlmostSolved",
    "QOCO_MAX_ITER": "MaxIterations",
    "QOCO_NUMERICAL_ERROR": "NumericalError",
    "QOCO_UNSOLVED": "NumericalError",
}


#: QOCO's settings beyond the tolerances, tried in turn until one ends in ``QOCO_SOLVED``. The
#: first refines its KKT solves more than its defaults (``ir_tol`` 1e-6, 5 steps); the second
#: adds Ruiz equilibration (off by default); the third a smaller static regularisation of the
#: constraint block (default 1e-8). With QOCO's defaults at ``tol`` 1e-10, 6 of 12 spatial
#: battery problems (limits and TCE minima of arches, vaults and the dome) failed tce's
#: residual checks (equilibrium 1e-9 to 6e-8). On tests/test_qoco_backend.py's 90 scenes, each
#: set alone leaves some "inaccurate" or short: the first 1 scene (the dome with a compressive
#: strength, its limit), the second 3, the third 3 (among them lambda_max 2e-7 low on an arch
#: on piers with cohesion); in turn, none (measured 2026-11-24)
SETTINGS: tuple[dict[str, float], ...] = (
    {"ir_tol": 1e-12, "max_ir_iters": 20},
    {"ir_tol": 1e-12, "max_ir_iters": 20, "ruiz_iters": 10},
    {"ir_tol": 1e-12, "max_ir_iters": 20, "ruiz_iters": 10, "kkt_static_reg_A": 1e-11},
)

def algebras() -> tuple[str, ...]:
    """QOCO's linear-algebra backends installed here: ``"builtin"`` (CPU) and/or ``"cuda"``."""
    return tuple(qoco.algebras_available()) if AVAILABLE else ()


@dataclass(frozen=True, eq=False)
class QocoData:
    """A conic problem in QOCO's form (module docstring).

    Attributes
    ----------
    P : (n, n) CSC
        Upper triangle of the Hessian.
    c : (n,) ndarray
    A : (p, n) CSC
        The zero-cone rows of Clarabel's ``A``.
    b : (p,) ndarray
    G : (m, n) CSC
        The nonnegative rows, then the second-order cones' rows, of Clarabel's ``A``.
    h : (m,) ndarray
    l : int
        Number of nonnegative rows of ``G``.
    q : (nsoc,) int ndarray
        Dimensions of the second-order cones.
    eq_rows, cone_rows : int ndarray
        Positions of ``A``'s and ``G``'s rows in Clarabel's row order.
    """

    P: sp.csc_matrix
    c: NDArray[np.float64]
    A: sp.csc_matrix | None
    b: NDArray[np.float64] | None
    G: sp.csc_matrix | None
    h: NDArray[np.float64] | None
    l: int
    q: NDArray[np.int32]
    eq_rows: NDArray[np.int64]
    cone_rows: NDArray[np.int64]


def _row_sets(problem: ConicProblem) -> tuple[NDArray[np.int64], NDArray[np.int64], NDArray[np.int64], list[int]]:
    """Rows of Clarabel's order that are zero, nonnegative and second-order cone rows, and the cones' dimensions."""
    zero, nonneg, soc, dims = [], [], [], []
    start = 0
    for kind, d in problem.cones:
        rows = np.arange(start, start + d)
        {"zero": zero, "nonneg": nonneg, "soc": soc}[kind].append(rows)
        if kind == "soc":
            dims.append(d)
        start += d
    cat = lambda parts: np.concatenate(parts) if parts else np.zeros(0, dtype=np.int64)  # noqa: E731
    return cat(zero), cat(nonneg), cat(soc), dims


def split(problem: ConicProblem) -> QocoData:
    """``problem`` in QOCO's form: zero-cone rows to ``A x = b``, the others to ``G x <=_C h``."""
    zero, nonneg, soc, dims = _row_sets(problem)
    cone = np.concatenate([nonneg, soc])
    A = problem.A.tocsr()
    pick = lambda rows: A[rows].tocsc() if len(rows) else None  # noqa: E731
    return QocoData(
        P=sp.triu(problem.P, format="csc"),
        c=np.asarray(problem.q, dtype=float),
        A=pick(zero),
        b=problem.b[zero] if len(zero) else None,
        G=pick(cone),
        h=problem.b[cone] if len(cone) else None,
        l=len(nonneg),
        q=np.asarray(dims, dtype=np.int32),
        eq_rows=zero,
        cone_rows=cone,
    )


class QocoSolver:
    """QOCO set up for one problem; later solves may change ``q`` and ``b`` (as
    :class:`tce.core.clarabel_solver.ClarabelSolver`).

    Parameters
    ----------
    problem : ConicProblem
    options : SolverOptions
        ``tol`` is QOCO's absolute and relative tolerance (``abstol``, ``reltol``), ``max_iter``
        its iteration limit; the other settings are :data:`SETTINGS`.
    algebra : {"builtin", "cuda"}
        QOCO's linear algebra: CPU, or the CUDA build (``qoco-cuda``).

    Raises
    ------
    RuntimeError
        QOCO, or the algebra asked for, is not installed.
    """

    def __init__(self, problem: ConicProblem, options: SolverOptions = SolverOptions(), algebra: str = "builtin") -> None:
        if not AVAILABLE:
            raise RuntimeError("QOCO is not installed: pip install tce[qoco] (CPU) or tce[gpu] (CUDA)")
        t0 = time.perf_counter()
        self.problem = problem
        self.data = split(problem)
        self._vectors = {"c": self.data.c, "b": self.data.b, "h": self.data.h}
        self._common = dict(verbose=0, abstol=options.tol, reltol=options.tol, max_iters=options.max_iter)
        self._algebra = algebra
        self._solvers = [self._make(SETTINGS[0])]
        self._setup = time.perf_counter() - t0

    def _make(self, settings: dict[str, float]) -> object:
        """A QOCO solver of the current data with ``settings``."""
        d, v = self.data, self._vectors
        solver = qoco.QOCO(algebra=self._algebra)
        solver.setup(self.problem.A.shape[1], len(d.cone_rows), len(d.eq_rows), d.P, v["c"], d.A, v["b"], d.G, v["h"],
                     d.l, len(d.q), d.q, **self._common, **settings)
        return solver

    def update(self, q: NDArray[np.float64] | None = None, b: NDArray[np.float64] | None = None) -> None:
        """Replace ``q`` and/or ``b`` (same shapes, Clarabel's row order); the matrices stay."""
        t0 = time.perf_counter()
        d = self.data
        new = {}
        if q is not None:
            new["c"] = np.asarray(q, dtype=float)
        if b is not None:
            new.update(b=b[d.eq_rows] if len(d.eq_rows) else None, h=b[d.cone_rows] if len(d.cone_rows) else None)
        self._vectors.update(new)
        for solver in self._solvers:
            solver.update_vector_data(**new)
        self._setup += time.perf_counter() - t0

    def solve(self) -> Solution:
        """Solve the current data with each of :data:`SETTINGS` in turn until one ends in
        ``QOCO_SOLVED`` (the last attempt's answer otherwise); multipliers and slacks come back
        in Clarabel's row order, the iterations and times are those of all attempts."""
        t0 = time.perf_counter()
        iterations = 0
        for k, settings in enumerate(SETTINGS):
            if k == len(self._solvers):
                self._solvers.append(self._make(settings))
            r = self._solvers[k].solve()
            iterations += int(r.iters)
            if r.status == "QOCO_SOLVED":
                break
        t = time.perf_counter() - t0
        d = self.data
        z, s = np.zeros(self.problem.A.shape[0]), np.zeros(self.problem.A.shape[0])
        z[d.eq_rows] = r.y
        z[d.cone_rows] = r.z
        s[d.cone_rows] = r.s
        raw = SimpleNamespace(x=np.asarray(r.x), z=z, s=s, obj_val=float(r.obj), iterations=iterations)
        setup, self._setup = self._setup, 0.0
        return Solution(STATUS.get(r.status, "NumericalError"), raw, t, setup)


def solve_once(problem: ConicProblem, options: SolverOptions = SolverOptions(), algebra: str = "builtin") -> Solution:
    """Set up QOCO for ``problem`` and solve it once."""
    return QocoSolver(problem, options, algebra).solve()
