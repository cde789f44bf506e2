"""Rigid Heyman problems (fn >= 0, no friction limit) as linear programs on the reference
operators, solved by HiGHS through :func:`scipy.optimize.linprog` (not tce's Clarabel).

- The TCE of rigid contacts (the paper's problem (11) with D = 0 and no cone)::

      minimise  -U . (B_sup F)   s.t.  A_eq F + b_dead + lam b_lateral(alpha) = 0,  fn >= 0

- The largest load multiplier (the static theorem of limit analysis, Heyman)::

      maximise  lam             s.t.  A_eq F + b_dead + lam b_lateral(alpha) = 0,  fn >= 0
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import linprog

from .operators import Operators


@dataclass(frozen=True)
class LPResult:
    """``status``: "optimal", "infeasible" or "unbounded"; ``value`` the optimum (the TCE in kN m,
    or lambda_max); ``forces`` ``(nv, 3)`` in the interface frames (kN), NaN unless optimal."""

    status: str
    value: float
    forces: np.ndarray


_STATUS = {0: "optimal", 2: "infeasible", 3: "unbounded"}


def _bounds(nv: int) -> list[tuple[float | None, float | None]]:
    return [(0.0, None) if j % 3 == 0 else (None, None) for j in range(3 * nv)]


def _solve(c, A, b, bounds) -> tuple[str, float, np.ndarray]:
    res = linprog(c, A_eq=A, b_eq=b, bounds=bounds, method="highs",
                  options=dict(primal_feasibility_tolerance=1e-10, dual_feasibility_tolerance=1e-10))
    status = _STATUS.get(res.status, "numerical")
    x = res.x if status == "optimal" else np.full(A.shape[1], np.nan)
    return status, float(res.fun) if status == "optimal" else float("nan"), x


def rigid_tce(ops: Operators, lam: float, alpha: float, U) -> LPResult:
    """Minimum of the rigid TCE for support motions ``U`` ((6 ns,), stacked per support)."""
    nv = len(ops.area)
    c = -(ops.B_sup.T @ np.asarray(U, dtype=float))
    status, value, x = _solve(c, ops.A_eq, -(ops.b_dead + lam * ops.b_lateral(alpha)), _bounds(nv))
    return LPResult(status, value, x.reshape(nv, 3))


def lambda_max(ops: Operators, alpha: float) -> LPResult:
    """Largest multiplier of the lateral load in direction ``alpha`` (degrees)."""
    nv = len(ops.area)
    A = np.hstack([ops.A_eq, ops.b_lateral(alpha)[:, None]])
    c = np.zeros(3 * nv + 1)
    c[-1] = -1.0
    status, _, x = _solve(c, A, -ops.b_dead, _bounds(nv) + [(None, None)])
    return LPResult(status, float(x[-1]), x[:-1].reshape(nv, 3))
