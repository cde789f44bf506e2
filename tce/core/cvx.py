"""The TCE problem written in cvxpy: a second, independent path to the same answer.

It states, from the model's operators and in physical units scaled by the total weight
``W`` (forces ``F = W f``)::

    minimise    1/2 F' D F - U' B_sup F
    subject to  A_eq F + rhs = 0
                fn >= 0, ||ft|| <= mu fn  (spatial: second-order cones; planar: |ft| <= mu fn)

with ``rhs = b_fixed + lam * b_live`` of the load pattern (:mod:`tce.core.loads`; by default
``b_dead + lam * b_lat(alpha)``). The right-hand side and the support motions are cvxpy
Parameters, so one :class:`CvxTCE` can be re-solved (DPP), or rebuilt for every solve.
Any solver cvxpy offers for the problem class can be used (CLARABEL, ECOS, SCS; HIGHS for
rigid planar LPs).
"""

from __future__ import annotations

import time
from collections.abc import Mapping
from dataclasses import dataclass, field

import cvxpy as cp
import numpy as np
from numpy.typing import ArrayLike, NDArray

from .loads import LoadPattern, scene_vectors
from .passive import refuse_passive
from .material import Material
from .model import Model
from .result import Result
from .solve import check_settlements, settlement_vector

__all__ = ["CvxResult", "CvxTCE"]

_STATUS = {
    cp.OPTIMAL: "optimal",
    cp.INFEASIBLE: "infeasible",
    cp.UNBOUNDED: "unbounded",
}


@dataclass(frozen=True, eq=False, kw_only=True, repr=False)
class CvxResult(Result):
    """Answer of a cvxpy solve (statuses: :data:`tce.core.result.STATUSES`).

    Attributes
    ----------
    forces : (nc, dim) ndarray
        Contact forces (kN), NaN unless optimal.
    support_wrenches : (ns, 6) ndarray
        Support wrenches (kN, kN m), NaN unless optimal.
    tce : float
        Total complementary energy (kN m).

    ``solver`` is the cvxpy solver's name; ``solve_time`` is the wall time of
    ``Problem.solve`` (cvxpy's canonicalisation included); ``message`` is cvxpy's status.
    """

    HEADLINE = ("tce",)

    forces: NDArray[np.float64] = field(repr=False)
    support_wrenches: NDArray[np.float64] = field(repr=False)
    tce: float = float("nan")


class CvxTCE:
    """Parametrised cvxpy TCE problem of one model and material.

    Parameters
    ----------
    model : Model
    material : Material
        One law for every contact: laws of interface kinds are refused (ValueError).
    """

    def __init__(self, model: Model, material: Material) -> None:
        if material.interfaces:
            raise ValueError("CvxTCE takes one law for every contact, not laws of interface kinds")
        self.model = model
        self.material = material
        W = model.assembly.total_weight
        self._W = W
        n = model.n_vars
        nc, dim = model.n_contacts, model.dim
        self.f = cp.Variable(n)
        self.rhs = cp.Parameter(model.A_eq.shape[0])
        self.U = cp.Parameter(model.B_sup.shape[0])
        F = W * self.f
        fr = cp.reshape(self.f, (nc, dim), order="C")
        cons = [model.A_eq @ F + self.rhs == 0, fr[:, 0] >= 0]
        mu = material.friction
        if mu is not None:
            if mu == 0.0:
                cons.append(fr[:, 1:] == 0)
            elif dim == 3:
                cons.append(cp.SOC(mu * fr[:, 0], fr[:, 1:], axis=1))
            else:
                cons.append(cp.abs(fr[:, 1]) <= mu * fr[:, 0])
        work = self.U @ (model.B_sup @ F)
        if material.rigid:
            obj = -work
        else:
            D = model.compliance(material.normal_stiffness, material.shear_stiffness)
            obj = 0.5 * cp.sum(cp.multiply(W**2 * D, cp.square(self.f))) - work
        self.problem = cp.Problem(cp.Minimize(obj), cons)

    def solve(
        self,
        lam: float = 0.0,
        alpha: float | None = None,
        settlements: Mapping[str, ArrayLike] | None = None,
        solver: str = "CLARABEL",
        loads: LoadPattern | None = None,
        **solver_options,
    ) -> CvxResult:
        """Solve for one scene (multiplier ``lam`` of the pattern ``loads``, or of the lateral
        pattern in direction ``alpha``) with cvxpy solver ``solver`` (statuses:
        ``docs/conventions.md``).

        Raises
        ------
        ValueError
            Loads that cannot be applied, a bad settlement, or a scene out of a planar model's plane.
        """
        t0 = time.perf_counter()
        sett = check_settlements(self.model.assembly.support_names, settlements)
        pattern, b_fixed, b_live = scene_vectors(self.model, alpha, loads, sett)
        refuse_passive(pattern, "a TCE solve")
        self.rhs.value = b_fixed + lam * b_live
        self.U.value = settlement_vector(self.model, settlements)
        t1 = time.perf_counter()
        try:
            self.problem.solve(solver=solver, **solver_options)
            raw = self.problem.status
        except cp.SolverError as err:
            raw = f"solver error: {err}"
        stime = time.perf_counter() - t1
        status = _STATUS.get(raw, "numerical")
        nan = np.full((self.model.n_contacts, self.model.dim), np.nan)
        if status == "optimal":
            F = self.f.value * self._W
            forces = F.reshape(self.model.n_contacts, self.model.dim)
            wrenches = (self.model.B_sup @ F).reshape(-1, 6)
            value = float(self.problem.value)
        else:
            forces, wrenches, value = nan, np.full((len(self.model.assembly.support_names), 6), np.nan), float("nan")
        return CvxResult(
            status=status, message=f"cvxpy: {raw}", solver=solver, solve_time=stime,
            wall_time=time.perf_counter() - t0, forces=forces, support_wrenches=wrenches, tce=value,
        )
