"""The Total Complementary Energy solver: one model and material, Clarabel called directly.

For a model (:mod:`tce.core.model`), a material (:class:`tce.core.material.Material`), a load
multiplier ``lam``, a load pattern (:class:`tce.core.loads.LoadPattern`; by default the
paper's: self-weight plus ``lam`` times the weights in direction ``alpha``, degrees) and
prescribed support motions ``U_s = (ux, uy, uz, rx, ry, rz)`` (m, rad, about each support
centroid), it solves the discretised minimum of the Total Complementary Energy (problem (11)
of the paper, *3D exploration of internal stresses due to lateral loads and foundation
movements in a semicircular arch*)::

    minimise    1/2 F' D F  -  sum_s (R_s . U_s + M_s . Omega_s)
    subject to  A_eq F + b_fixed + lam * b_live = 0
                fn >= 0 and ||ft|| <= mu fn at every contact  (fn >= 0 only if mu is None)

where ``(R_s, M_s) = B_s F`` is the wrench support ``s`` exerts on the structure and ``D``
the diagonal compliance (zero for rigid contacts). The problem is built once per solver
(:func:`tce.core.problem.tce_problem`); a new ``lam``, load pattern or settlement only updates
the vectors ``q`` and ``b`` of the warm Clarabel solver (:mod:`tce.core.clarabel_solver`).

Statuses (``docs/conventions.md``):

``optimal``
    Clarabel converged and the answer passed the residual checks (equilibrium and contact
    law, relative to the total weight, below ``residual_tol``).
``infeasible``
    No admissible force state (Clarabel's infeasibility certificate, or the phase-1
    problem, :func:`tce.core.problem.phase1_problem`, has a residual above ``feas_tol``).
``unbounded``
    Admissible states exist but the TCE has no minimum: with rigid contacts, a self-stress
    ``d`` (``A_eq d = 0``, ``d`` admissible) that lowers the energy (``q . d < 0``,
    :func:`tce.core.problem.recession_problem`).
``numerical``
    Anything else: no number of such an answer is reported.

When Clarabel's own verdict is not clean, the phase-1 and recession problems decide (a
phase-1 residual close to ``feas_tol`` is decided again with tight tolerances), and a
feasible, bounded problem is retried: first with a fresh solver equilibrated for this
problem (``rescaled``; the warm solver keeps the scaling of its first problem), then with
robust settings. The result always says what decided (``retry``).

A fill's passive restraint (:mod:`tce.core.passive`) adds ``k`` unknowns
``0 <= p <= capacity`` without energy to the same problems
(:func:`tce.core.problem.with_bounded_forces`); verdicts, retries, residual checks (``G p``
in the equilibrium rows, the bounds in the law's violation) and the canonical state are
otherwise those of the problem without it.
"""

from __future__ import annotations

import logging
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace
from functools import cached_property, partial
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .clarabel_solver import SOLVER_NAME, ClarabelSolver, Solution, SolverOptions, solve_once
from .loads import LoadPattern, as_pattern, check_in_plane, load_vectors
from .passive import Restraint, passive_restraint
from .material import Material
from .model import InterfaceMap, Model
from .canonical import Check, CanonicalSolver
from .problem import (ConicProblem, Formulation, bounded_b, phase1_b, phase1_problem, q_scale, recession_problem,
                      restrained_phase1_problem, restrained_tce_problem, tce_b, tce_problem)
from .result import STATUSES, WRENCH_COMPONENTS, XYZ, Result

if TYPE_CHECKING:
    import xarray as xr

__all__ = [
    "SOLVER_NAME",
    "STATUSES",
    "SolverOptions",
    "ForceState",
    "TCEResult",
    "TCESolver",
    "check_settlements",
    "settlement_vector",
]

log = logging.getLogger(__name__)


def _b_norm(b: NDArray[np.float64]) -> float:
    """``max |b|`` of a scaled problem (:meth:`SolverOptions.settings`' ``b_norm``)."""
    return float(np.abs(b).max(initial=0.0))


def check_settlements(names: tuple[str, ...], settlements: Mapping[str, ArrayLike] | None) -> dict[str, NDArray[np.float64]]:
    """Support motions ``{name: (ux, uy, uz, rx, ry, rz)}`` as float arrays, checked.

    Raises
    ------
    ValueError
        Unknown support name, a vector that is not 6 finite numbers.
    """
    out = {}
    for name, u in (settlements or {}).items():
        if name not in names:
            raise ValueError(f"unknown support {name!r}; supports are {list(names)}")
        v = np.asarray(u, dtype=float).ravel()
        if v.shape != (6,):
            raise ValueError(
                f"support {name!r}: a displacement is 6 numbers [ux, uy, uz, rx, ry, rz], got {len(v)}"
            )
        if not np.all(np.isfinite(v)):
            raise ValueError(f"support {name!r}: displacement has NaN or infinite entries")
        out[name] = v
    return out


def settlement_vector(model: Model, settlements: Mapping[str, ArrayLike] | None) -> NDArray[np.float64]:
    """Stack support motions in support order (zeros for supports not named), checked."""
    names = model.assembly.support_names
    U = np.zeros((len(names), 6))
    for name, v in check_settlements(names, settlements).items():
        U[names.index(name)] = v
    return U.ravel()


@dataclass(frozen=True, eq=False)
class ForceState:
    """One force state of a solve and what it gives (NaN unless the solve is optimal).

    Attributes
    ----------
    forces : (nc, dim) ndarray
        Contact forces of the model in their interface frames (kN).
    support_wrenches : (ns, 6) ndarray
        ``(Fx, Fy, Fz, Mx, My, Mz)`` each support exerts on the structure, global frame,
        about the support centroid (kN, kN m).
    tce : float
        Total complementary energy (kN m).
    eq_residual, cone_residual : float
        Relative equilibrium residual and contact-law violation.
    unique : bool or None
        Whether the optimum is unique (:attr:`TCEResult.unique`).
    restraint_forces : (k,) ndarray or None
        The fill's passive restraint forces (kN; None without a restraint).
    solve_time : float
        Wall time of the set-up and solves that selected this state after the optimum (s; 0
        for the optimum itself).
    """

    forces: NDArray[np.float64]
    support_wrenches: NDArray[np.float64]
    tce: float
    eq_residual: float
    cone_residual: float
    unique: bool | None
    restraint_forces: NDArray[np.float64] | None
    solve_time: float = 0.0


@dataclass(frozen=True, eq=False, kw_only=True, repr=False)
class TCEResult(Result):
    """Answer of one TCE solve (status words: :data:`tce.core.result.STATUSES`).

    The status is decided by the solver's optimum (:attr:`optimum`); the state the result
    reports (:attr:`state`: :attr:`forces` and the properties after it) is the canonical one
    (:mod:`tce.core.canonical`) where the optimum of a rigid scene may not be unique. Both are
    built on their first read, once: a caller that only reads the status (a load path's
    decisions) pays for neither, and the result is a value all the same (``docs/conventions.md``).

    Attributes
    ----------
    lam, alpha : float
        Load multiplier and the direction of the lateral pattern (degrees; NaN when the
        pattern has no lateral part).
    loads : LoadPattern
        The load pattern solved.
    model : str
        ``"spatial"`` or ``"planar"``: the model that ran.
    settlements : (6 ns,) ndarray
        Stacked support motions (m, rad), support order.
    iterations : int
        Interior-point iterations (main problem).
    setup_time : float
        Wall time of the solver set-up and vector updates this answer needed (s);
        ``solve_time`` is the solve calls alone (the canonical state's are
        :attr:`canonical_time`).
    retry : str
        What decided the status when Clarabel's first answer was not clean ("" if nothing).
    interface_map : InterfaceMap
        The model's arrays that turn ``forces`` into vertex forces and resultants.
    """

    HEADLINE = ("lam", "alpha", "model", "tce", "eq_residual", "cone_residual", "unique")

    lam: float
    alpha: float
    loads: LoadPattern = field(repr=False)
    model: str
    settlements: NDArray[np.float64] = field(repr=False)
    iterations: int = 0
    setup_time: float = 0.0
    retry: str = ""
    interface_map: InterfaceMap = field(repr=False)
    #: ``selector(canonical)``: the optimum's state (False) or the state reported (True), built
    #: on first read; dropped (with the solver it holds) once both are
    selector: Callable[[bool], ForceState] | None = field(repr=False)

    @cached_property
    def optimum(self) -> ForceState:
        """The solver's own optimal state (NaN unless optimal; ``unique`` None where undecided)."""
        assert self.selector is not None
        return self.selector(False)

    @cached_property
    def state(self) -> ForceState:
        """The state reported: the canonical state of a rigid optimum, else :attr:`optimum`."""
        assert self.selector is not None
        out = self.selector(True)
        self.optimum  # noqa: B018 (built before the selector goes)
        object.__setattr__(self, "selector", None)
        return out

    def __getstate__(self) -> dict[str, Any]:
        """Pickled with its state selected (the selector holds a solver)."""
        self.state  # noqa: B018 (selects the state)
        return self.__dict__

    @property
    def forces(self) -> NDArray[np.float64]:
        """Contact forces of the model in their interface frames (kN), ``(nc, dim)``; NaN unless optimal."""
        return self.state.forces

    @property
    def support_wrenches(self) -> NDArray[np.float64]:
        """``(Fx, Fy, Fz, Mx, My, Mz)`` each support exerts on the structure, global frame,
        about the support centroid (kN, kN m), ``(ns, 6)``; NaN unless optimal."""
        return self.state.support_wrenches

    @property
    def tce(self) -> float:
        """Total complementary energy (kN m); NaN unless optimal."""
        return self.state.tce

    @property
    def eq_residual(self) -> float:
        """Relative equilibrium residual of the state."""
        return self.state.eq_residual

    @property
    def cone_residual(self) -> float:
        """Contact-law violation of the state, relative to the total weight."""
        return self.state.cone_residual

    @property
    def unique(self) -> bool | None:
        """Whether the optimum is unique: True with compliance (strictly convex). Rigid:
        decided by comparing the solver's answer with the canonical state
        (:mod:`tce.core.canonical`); None when the canonical state could not be found or was
        not asked for (``SolverOptions(canonical=False)``; a rigid scene without support
        motion is then False: every admissible state is a minimiser)."""
        return self.state.unique

    @property
    def restraint_forces(self) -> NDArray[np.float64] | None:
        """The fill's passive restraint forces ``0 <= p <= capacity`` of the state (kN, along
        :class:`tce.core.passive.Restraint`'s directions, into the ring); None without a
        restraint, NaN unless optimal."""
        return self.state.restraint_forces

    @property
    def canonical_time(self) -> float:
        """Wall time of the canonical state's solves (s; 0 until :attr:`state` is read, and
        for a state that needs none)."""
        return self.state.solve_time if "state" in self.__dict__ else 0.0

    @property
    def interfaces(self) -> tuple[int, ...]:
        """Assembly index of each interface slot of :attr:`resultants` and friends."""
        return self.interface_map.interfaces

    @cached_property
    def vertex_forces(self) -> NDArray[np.float64]:
        """Force at every 3D interface vertex, ``(fn, ft1, ft2)`` in its interface frame (kN)."""
        return (self.interface_map.lift @ self.forces.ravel()).reshape(-1, 3)

    @cached_property
    def _resultants(self) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        from .resultants import interface_resultants

        return interface_resultants(self.interface_map, self.vertex_forces)

    @property
    def resultants(self) -> NDArray[np.float64]:
        """Resultant force of each interface slot, global frame (kN), acting on block B."""
        return self._resultants[0]

    @property
    def pressure_points(self) -> NDArray[np.float64]:
        """Pressure point of each interface slot (m): where the normal forces' resultant meets the plane."""
        return self._resultants[1]

    @property
    def torques(self) -> NDArray[np.float64]:
        """Torque about the interface normal at the pressure point (kN m), on block B."""
        return self._resultants[2]

    @property
    def reactions(self) -> xr.DataArray:
        """:attr:`support_wrenches` labelled: dims ``(support, component)``, the support block
        names and ``Fx Fy Fz Mx My Mz`` (kN, kN m; NaN unless optimal), e.g.
        ``r.reactions.sel(support="right", component="Fx")``."""
        import xarray as xr

        return xr.DataArray(
            self.support_wrenches, dims=("support", "component"), name="reaction",
            coords={"support": list(self.interface_map.supports), "component": list(WRENCH_COMPONENTS)},
            attrs={"units": "kN, kN m", "long_name": "wrench each support exerts on the structure, global frame, "
                   "about the support centroid"},
        )

    def _arrays(self) -> tuple[dict[str, tuple], dict[str, Any]]:
        """Reactions, interface resultants, pressure points, torques and vertex forces, labelled."""
        from .resultants import global_vertex_forces

        imap = self.interface_map
        data = {
            "reaction": (("support", "component"), self.support_wrenches, {"units": "kN, kN m"}),
            "resultant": (("interface", "xyz"), self.resultants, {"units": "kN"}),
            "pressure_point": (("interface", "xyz"), self.pressure_points, {"units": "m"}),
            "torque": (("interface",), self.torques, {"units": "kN m"}),
            "vertex_force": (("vertex", "xyz"), global_vertex_forces(imap, self.vertex_forces), {"units": "kN"}),
            "vertex_point": (("vertex", "xyz"), imap.vertex_points, {"units": "m"}),
        }
        coords = {"support": list(imap.supports), "component": list(WRENCH_COMPONENTS),
                  "interface": list(imap.labels), "xyz": list(XYZ)}
        return data, coords


class TCESolver:
    """Clarabel-direct TCE solver for one model and material (see module docstring).

    Parameters
    ----------
    model : Model
    material : Material
    options : SolverOptions, optional
    formulation : Formulation, optional
        The scaled operators of ``model`` and ``material`` (with the material's own contact
        law) when the caller already has them: :class:`tce.core.analysis.Analysis` shares
        one between its TCE and limit solvers.
    """

    #: Phase-1 residuals in ``(feas_tol, PHASE1_BAND * feas_tol]`` are decided with tight tolerances.
    PHASE1_BAND: float = 100.0

    def __init__(
        self, model: Model, material: Material, options: SolverOptions | None = None, formulation: Formulation | None = None
    ) -> None:
        if formulation is not None and (formulation.model is not model or formulation.material is not material
                                        or not formulation.own_law):
            raise ValueError("TCESolver: a formulation must be of the same model and material, with its own law")
        self.model = model
        self.material = material
        self.options = options or SolverOptions()
        self.formulation = formulation or Formulation(model, material)
        self.scaling = self.formulation.scaling
        self._warm: ClarabelSolver | None = None
        self._warm_q: NDArray[np.float64] | None = None
        self._warm_restraint: Restraint | None = None
        self._feas: ClarabelSolver | None = None
        self._feas_restraint: Restraint | None = None
        self._recession_cache: dict[bytes, tuple[float, float, NDArray[np.float64]]] = {}
        self._vectors_last: tuple[LoadPattern, tuple[NDArray[np.float64], NDArray[np.float64]]] | None = None
        #: (the last pattern's fill, its restraint): one Restraint per fill, so the warm solvers stay
        self._restraint_last: tuple[Any, Restraint | None] | None = None
        self._canonical: CanonicalSolver | None = None

    # ------------------------------------------------------------ problem vectors
    def vectors(self, loads: LoadPattern) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """``(b_fixed, b_live)`` of a load pattern (kN, kN m; :func:`tce.core.loads.load_vectors`);
        the last pattern's are kept (a load path asks for the same ones at every step)."""
        last = self._vectors_last
        if last is not None and (last[0] is loads or last[0] == loads):
            return last[1]
        v = load_vectors(self.model, loads)
        self._vectors_last = (loads, v)
        if self._restraint_last is None or self._restraint_last[0] != loads.fill:
            self._restraint_last = (loads.fill, passive_restraint(self.model, loads.fill))
        return v

    def restraint(self, loads: LoadPattern) -> Restraint | None:
        """The passive restraint of the pattern's fill (:func:`tce.core.passive.passive_restraint`),
        None without one; kept while the patterns' fill is the same (a moving vehicle)."""
        self.vectors(loads)
        return self._restraint_last[1]

    def rhs(self, lam: float, alpha: float | None = None, loads: LoadPattern | None = None) -> NDArray[np.float64]:
        """Physical right-hand side ``b_fixed + lam * b_live`` (kN, kN m) of the pattern
        ``loads``, or of the default pattern in direction ``alpha``: ``b_dead + lam * b_lat(alpha)``."""
        b_fixed, b_live = self.vectors(as_pattern(alpha, loads))
        return b_fixed + lam * b_live

    def _check_scene(self, loads: LoadPattern, U: NDArray[np.float64]) -> None:
        names = self.model.assembly.support_names
        check_in_plane(self.model, loads, {n: U[6 * i : 6 * i + 6] for i, n in enumerate(names)})

    # ------------------------------------------------------------ clarabel calls
    def _bounded(self, b: NDArray[np.float64], restraint: Restraint | None) -> NDArray[np.float64]:
        """``b`` of a problem followed by the rows of the restraint's bounds
        (:func:`tce.core.problem.bounded_b`; ``b`` itself without a restraint)."""
        return b if restraint is None else bounded_b(b, restraint.capacity / self.scaling.force)

    def _problem(self, b: NDArray[np.float64], U: NDArray[np.float64], restraint: Restraint | None) -> ConicProblem:
        """The TCE problem of the scaled right-hand side ``b`` (:meth:`_bounded` of
        :func:`tce.core.problem.tce_b`): :func:`tce.core.problem.tce_problem`, with the
        restraint's bounded columns (:func:`tce.core.problem.restrained_tce_problem`)."""
        if restraint is None:
            return tce_problem(self.formulation, b, U)
        return restrained_tce_problem(self.formulation, b[: -2 * restraint.size], U, restraint.G, restraint.capacity)

    def _check(self, b: NDArray[np.float64], restraint: Restraint | None) -> Check:
        """Scaled unknowns of the TCE problem of ``b`` -> (forces (kN), restraint forces (kN) or
        None, (equilibrium, contact-law) residuals): the check every ``optimal`` answer passes.
        The restraint's forces enter the equilibrium residual and their bounds the law's."""
        f, W = self.formulation, self.scaling.force
        b_eq = b[: f.A_eq.shape[0]]

        def check(x: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64] | None, tuple[float, float]]:
            F = f.forces(x)
            if restraint is None:
                return F, None, f.residuals_scaled(F, b_eq)
            p = x[f.n : f.n + restraint.size] * W
            eq, law = f.residuals_scaled(F, b_eq - (restraint.G @ p) / f.row_div)
            bound = float(np.maximum(-p, p - restraint.capacity).max(initial=0.0)) / W
            return F, p, (eq, max(law, bound))
        return check

    def _main(self, q: NDArray[np.float64], U: NDArray[np.float64], b: NDArray[np.float64],
              restraint: Restraint | None) -> Solution:
        """Solve the TCE problem of the scaled objective ``q`` and right-hand side ``b`` with the
        warm solver: set up on the first call and for a new restraint, then only its vectors are
        updated. A scene whose objective is rescaled (:func:`tce.core.problem.q_scale`) gets a
        solver of its own."""
        rescaled = q_scale(q) != 1.0
        if self._warm is not None and restraint is self._warm_restraint and not rescaled:
            if np.array_equal(q, self._warm_q):
                self._warm.update(b=b)
            else:
                self._warm.update(q=q if restraint is None else np.concatenate([q, np.zeros(restraint.size)]), b=b)
                self._warm_q = q
            return self._warm.solve()
        settings = self.options.settings(refine=self.options.refine, kkt=self.formulation.kkt, b_norm=_b_norm(b))
        if rescaled:
            return solve_once(self._problem(b, U, restraint), settings)
        self._warm = ClarabelSolver(self._problem(b, U, restraint), settings)
        self._warm_q, self._warm_restraint = q, restraint
        return self._warm.solve()

    def _phase1(self, rhs: NDArray[np.float64], restraint: Restraint | None = None) -> tuple[float, float, str]:
        """Smallest equilibrium residual reachable by admissible forces for the right-hand
        side ``rhs`` (with the restraint's bounded forces when given).

        Solves :func:`tce.core.problem.phase1_problem` (or
        :func:`tce.core.problem.restrained_phase1_problem`). Returns ``(r, solve_time, clarabel
        status)``; ``r <= feas_tol`` means the load is carried. A residual that is undecided
        (NaN) or within ``PHASE1_BAND`` times ``feas_tol`` is decided again with tight
        tolerances; the status then ends with ``tight: ...``."""
        f = self.formulation

        def problem() -> ConicProblem:
            if restraint is None:
                return phase1_problem(f, rhs)
            return restrained_phase1_problem(f, rhs, restraint.G, restraint.capacity)

        if self._feas is None or restraint is not self._feas_restraint:
            self._feas = ClarabelSolver(problem(), self.options.settings(kkt=self.formulation.kkt))
            self._feas_restraint = restraint
        else:
            self._feas.update(b=self._bounded(phase1_b(f, rhs), restraint))
        sol = self._feas.solve()
        r = float(sol.x[f.n]) if sol.solved else float("nan")
        t, status = sol.solve_time, sol.status
        if not r <= self.options.feas_tol and not r > self.PHASE1_BAND * self.options.feas_tol:
            # a fresh solver, so also a fresh equilibration
            sol = solve_once(problem(), self.options.settings(tight=True, kkt=f.kkt))
            t += sol.solve_time
            if sol.solved:
                r = float(np.nanmin([r, float(sol.x[f.n])]))  # each is reached by some admissible state
            status = f"{status}, tight: {sol.status}"
        return r, t, status

    def recession(self, U: NDArray[np.float64]) -> tuple[float, float]:
        """Steepest descent of the rigid TCE along self-stresses
        (:func:`tce.core.problem.recession_problem`). A negative value means the TCE is
        unbounded below (when feasible). Returns ``(value, solve_time)``; cached per ``U``
        (the check does not depend on the load)."""
        val, t, _ = self._recession(U)
        return val, t

    def recession_direction(self, U: NDArray[np.float64]) -> NDArray[np.float64]:
        """The self-stress ``d`` (model variables, scaled) of :meth:`recession`: where an
        incompatible support motion drives the forces without end (NaN if not solved)."""
        return self._recession(U)[2]

    def _recession(self, U: NDArray[np.float64]) -> tuple[float, float, NDArray[np.float64]]:
        key = np.asarray(U, dtype=float).tobytes()
        if key not in self._recession_cache:
            sol = solve_once(recession_problem(self.formulation, np.asarray(U, dtype=float)), self.options.settings(kkt=self.formulation.kkt))
            val = sol.objective if sol.solved else float("nan")
            d = sol.x if sol.solved else np.full(self.model.n_vars, np.nan)
            self._recession_cache[key] = (val, sol.solve_time, d)
        return self._recession_cache[key]

    # ------------------------------------------------------------ main entry
    def solve(
        self,
        lam: float = 0.0,
        alpha: float | None = None,
        settlements: Mapping[str, ArrayLike] | NDArray[np.float64] | None = None,
        loads: LoadPattern | None = None,
    ) -> TCEResult:
        """Minimise the TCE for load multiplier ``lam`` of the load pattern ``loads`` (default:
        the paper's pattern in direction ``alpha``, degrees; 0 when None) with support motions
        ``settlements`` (``{support: [ux, uy, uz, rx, ry, rz]}`` in m and rad, or the stacked
        vector). Returns a :class:`TCEResult`; never raises on solver trouble.

        Raises
        ------
        ValueError
            A non-finite ``lam`` or ``alpha``, ``alpha`` and a pattern with another one, an
            unknown support or a bad motion vector, loads that cannot be applied
            (:class:`tce.core.loads.LoadError`), or a scene out of a planar model's plane.
        """
        t0 = time.perf_counter()
        if not np.isfinite(lam):
            raise ValueError(f"lam must be a finite number, got lam={lam!r}")
        pattern = as_pattern(alpha, loads)
        if isinstance(settlements, np.ndarray):
            U = np.array(settlements, dtype=float)  # the result's own
        else:
            U = settlement_vector(self.model, settlements)
        self._check_scene(pattern, U)
        return self.solve_scene(lam, pattern, U, t0)

    def solve_scene(self, lam: float, loads: LoadPattern | float, U: NDArray[np.float64], t0: float | None = None) -> TCEResult:
        """:meth:`solve` for a scene already checked: finite ``lam``, a load pattern (or the
        direction ``alpha`` of the default one) and ``U`` the stacked motions (m, rad) of a
        scene this model can carry (:class:`tce.core.analysis.Analysis` checks each scene
        once)."""
        t0 = time.perf_counter() if t0 is None else t0
        pattern = loads if isinstance(loads, LoadPattern) else as_pattern(loads)
        b_fixed, b_live = self.vectors(pattern)
        rhs = b_fixed + lam * b_live
        restraint = self.restraint(pattern)
        f = self.formulation
        b = self._bounded(tce_b(f, rhs), restraint)
        check = self._check(b, restraint)
        q = f.q(U)
        sol = self._main(q, U, b, restraint)
        stime, setup = sol.solve_time, sol.setup_time
        notes = [f"clarabel: {sol.status}"]
        status, retry, F, p, res = "numerical", "", None, None, None

        if sol.solved:
            F, p, res = check(sol.x)
            if self._passes(res):
                status = "optimal"
            else:
                notes.append("residual check failed")
        elif sol.status == "PrimalInfeasible":
            status = "infeasible"
        if status == "numerical" and sol.status != "PrimalInfeasible":
            # Clarabel's verdict is not clean (or claims unboundedness): decide feasibility first.
            r, t, fstat = self._phase1(rhs, restraint)
            stime += t
            notes.append(f"phase-1 residual {r:.3g} ({fstat})")
            rigid = f.D is None
            if not np.isfinite(r):
                retry = "phase-1 failed"
            elif r > self.options.feas_tol:
                status, retry = "infeasible", "phase-1 (tight)" if "tight" in fstat else "phase-1"
            elif sol.status == "DualInfeasible" and rigid:
                status, retry = "unbounded", ""
            elif rigid and np.any(U):
                # the restraint's forces are bounded: the recession directions are the self-stresses
                val, t = self.recession(U)
                stime += t
                notes.append(f"recession {val:.3g}")
                if val < -1e-7:
                    status, retry = "unbounded", "recession"
            # feasible and bounded (or undecided): retry (module docstring)
            for name, robust in (("rescaled", False), ("robust settings", True)):
                if status != "numerical":
                    break
                sol2 = solve_once(self._problem(b, U, restraint), self.options.settings(
                    robust=robust, kkt=f.kkt, b_norm=_b_norm(b)))
                stime += sol2.solve_time
                setup += sol2.setup_time
                notes.append(f"{name} retry: {sol2.status}")
                if sol2.solved:
                    F2, p2, res = check(sol2.x)
                    if self._passes(res):
                        status, retry, F, p = "optimal", name, F2, p2
        if status != "optimal":
            F = p = res = None
        if restraint is not None:
            notes.append(f"passive restraint: {restraint.size} bounded forces")
        canon = (b, q, check) if status == "optimal" and f.D is None and self.options.canonical else None
        if retry:
            log.debug("solve at lam=%g of %s: %s decided by %s (%s)", lam, pattern, status, retry, "; ".join(notes))
        return TCEResult(
            status=status, message="; ".join(notes), solver=SOLVER_NAME, solve_time=stime,
            wall_time=time.perf_counter() - t0, lam=float(lam), alpha=pattern.direction, loads=pattern,
            model=self.model.kind, settlements=U, iterations=sol.iterations, setup_time=setup, retry=retry,
            interface_map=self.model.interface_map, selector=partial(self._select, F, p, res, U, restraint, canon),
        )

    def _select(
        self, F: NDArray[np.float64] | None, p: NDArray[np.float64] | None, res: tuple[float, float] | None,
        U: NDArray[np.float64], restraint: Restraint | None,
        canon: tuple[NDArray[np.float64], NDArray[np.float64], Check] | None, canonical: bool,
    ) -> ForceState:
        """:attr:`TCEResult.selector`: the state of the optimum (physical forces ``F``, restraint
        forces ``p``, residuals ``res``; None: not optimal), or with ``canonical`` and ``canon``
        (the scaled ``b``, ``q`` and check of a rigid optimum) its canonical state
        (:meth:`tce.core.canonical.CanonicalSolver.state`); the optimum, uniqueness undecided,
        where that cannot be found."""
        if not canonical or canon is None:
            return self._state(F, p, res, U, restraint)
        assert F is not None
        b, q, check = canon
        x = (F if p is None else np.concatenate([F, p])) / self.scaling.force
        can = self._canonical_solver().state(b, q, x, check, restraint)
        if can.forces is None or can.residuals is None:
            log.warning("canonical state not found: the solver's state kept (%s model)", self.model.kind)
            state = self._state(F, p, res, U, restraint)
        else:
            state = self._state(can.forces, can.restraint_forces, can.residuals, U, restraint, can.unique)
        return replace(state, solve_time=can.solve_time + can.setup_time)

    def _canonical_solver(self) -> CanonicalSolver:
        """The warm solver of canonical states (built on first use)."""
        if self._canonical is None:
            self._canonical = CanonicalSolver(self.formulation, self.options)
        return self._canonical

    # ------------------------------------------------------------ checks and results
    def _passes(self, res: tuple[float, float]) -> bool:
        tol = self.options.residual_tol
        return res[0] <= tol and res[1] <= tol

    def _state(
        self, F: NDArray[np.float64] | None, p: NDArray[np.float64] | None, res: tuple[float, float] | None,
        U: NDArray[np.float64], restraint: Restraint | None, unique: bool | None = None,
    ) -> ForceState:
        """The :class:`ForceState` of physical forces ``F`` (None: not optimal, all NaN), restraint
        forces ``p`` and residuals ``res``. ``unique`` is True with compliance, and False for a
        rigid scene without support motion that left it undecided."""
        model = self.model
        if self.formulation.D is not None:
            unique = True
        elif unique is None and not np.any(U):
            unique = False  # every admissible state is a minimiser
        if restraint is not None and p is None:
            p = np.full(restraint.size, np.nan)
        if F is None or res is None:
            nan = float("nan")
            return ForceState(np.full((model.n_contacts, model.dim), nan),
                              np.full((len(model.assembly.support_indices), 6), nan), nan, nan, nan, unique, p)
        wrench = model.B_sup @ F
        return ForceState(F.reshape(model.n_contacts, model.dim), wrench.reshape(-1, 6),
                          self.formulation.energy(F, U, wrench), res[0], res[1], unique, p)

