"""The Total Complementary Energy solver (Clarabel, called directly).

For a model (:mod:`tce.model`), a material (:class:`tce.material.Material`), a load
multiplier ``lam``, a lateral direction ``alpha`` (degrees) and prescribed support motions
``U_s = (ux, uy, uz, rx, ry, rz)`` (m, rad, about each support centroid), it solves::

    minimise    1/2 F' D F  -  sum_s (R_s . U_s + M_s . Omega_s)
    subject to  A_eq F + b_dead + lam * b_lat(alpha) = 0
                fn >= 0 and ||ft|| <= mu fn at every contact  (fn >= 0 only if mu is None)

where ``(R_s, M_s) = B_s F`` is the wrench support ``s`` exerts on the structure and
``D`` the diagonal compliance (zero for rigid contacts): an LP (planar, rigid), a QP, an
SOCP (spatial with friction) or a QP with cones. The conic data are assembled once per
solver; a new ``lam``, ``alpha`` or settlement only updates the vectors ``q`` and ``b``.

Statuses (DESIGN.md):

``optimal``
    Clarabel converged and the answer passed the residual checks (equilibrium and contact
    law, relative to the total weight, below ``residual_tol``).
``infeasible``
    No admissible force state (Clarabel's infeasibility certificate, or the phase-1
    problem ``min r s.t. |A_eq F + b| <= r, F admissible`` has ``r > feas_tol``).
``unbounded``
    Admissible states exist but the TCE has no minimum: with rigid contacts, a self-stress
    ``d`` (``A_eq d = 0``, ``d`` admissible) that lowers the energy (``q . d < 0``).
``numerical``
    Anything else: no number of such an answer is reported.

When Clarabel's own verdict is not clean, the phase-1 and recession problems decide (a
phase-1 residual close to ``feas_tol`` is decided again with tight tolerances), and a
feasible, bounded problem is retried: first with a fresh solver equilibrated for this
problem (``rescaled``; the warm solver keeps the scaling of its first problem), then with
robust settings. The result always says what decided (``retry``).
"""

from __future__ import annotations

import logging
import time
from collections.abc import Mapping
from dataclasses import dataclass, field
from functools import cached_property

import clarabel
import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike, NDArray

from .conic import Scaling, cone_rows, cone_violation
from .material import Material
from .model import Model, scene_in_plane

__all__ = ["STATUSES", "SolverOptions", "TCEResult", "TCESolver", "check_settlements", "settlement_vector"]

log = logging.getLogger(__name__)

STATUSES = ("optimal", "infeasible", "unbounded", "numerical")
SOLVER_NAME = f"clarabel {clarabel.__version__}"


@dataclass(frozen=True)
class SolverOptions:
    """Tolerances of the solver.

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
        Clarabel's iterative refinement of the KKT solves in the warm solver (retries
        always refine). Off by default: on ~2,000 load-path solves the statuses were the
        same, infeasible loads got their certificate in ~15 iterations instead of running
        to the limit, and solves were 1.5-3x faster; an answer still has to pass
        ``residual_tol``, so a load within ~1e-8 of lambda_max may be ``optimal``.
    """

    tol: float = 1e-10
    residual_tol: float = 1e-9
    feas_tol: float = 1e-9
    max_iter: int = 200
    refine: bool = False

    def clarabel_settings(self, robust: bool = False, tight: bool = False) -> clarabel.DefaultSettings:
        """Clarabel settings; ``robust`` raises iterations and equilibration for a retry;
        ``tight`` sets the gap and feasibility tolerances a thousand times below ``feas_tol``
        (for a phase-1 residual too close to ``feas_tol`` to be trusted)."""
        s = clarabel.DefaultSettings()
        s.verbose = False
        s.presolve_enable = False  # keeps the data layout fixed, so updates are allowed
        s.chordal_decomposition_enable = False
        tol = min(self.tol, 1e-3 * self.feas_tol) if tight else self.tol
        s.tol_gap_abs = s.tol_gap_rel = tol
        s.tol_feas = tol
        s.tol_infeas_abs = s.tol_infeas_rel = min(1e-8, 10 * self.tol)
        s.tol_ktratio = 1e-7
        s.max_iter = self.max_iter
        if robust:
            s.max_iter = 5 * self.max_iter
            s.equilibrate_max_iter = 50
            s.static_regularization_constant = 1e-9
            s.iterative_refinement_max_iter = 50
            s.max_step_fraction = 0.95
        return s


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
class TCEResult:
    """Answer of one TCE solve.

    Attributes
    ----------
    status : str
        One of :data:`STATUSES`.
    lam, alpha : float
        Load multiplier and its direction (degrees).
    model : str
        ``"spatial"`` or ``"planar"``.
    forces : (nc, dim) ndarray
        Contact forces of the model in their interface frames (kN); NaN unless optimal.
    tce : float
        Total complementary energy (kN m); NaN unless optimal.
    eq_residual, cone_residual : float
        Relative equilibrium residual and contact-law violation of the answer.
    unique : bool or None
        True with compliance (strictly convex); False for a rigid scene with no support
        motion (every admissible state is a minimiser); None otherwise (unknown).
    solver : str
        Solver name and version.
    solve_time : float
        Clarabel's own solve time (s), summed over the problems this answer needed.
    wall_time : float
        Time of the whole call, from Python (s).
    iterations : int
        Interior-point iterations (main problem).
    retry : str
        What decided the status when Clarabel's first answer was not clean ("" if nothing).
    message : str
        Clarabel's raw status and notes.
    """

    status: str
    lam: float
    alpha: float
    model_ref: Model = field(repr=False)
    settlements: NDArray[np.float64] = field(repr=False)
    forces: NDArray[np.float64] = field(repr=False)
    tce: float = float("nan")
    eq_residual: float = float("nan")
    cone_residual: float = float("nan")
    unique: bool | None = None
    solver: str = SOLVER_NAME
    solve_time: float = 0.0
    wall_time: float = 0.0
    iterations: int = 0
    retry: str = ""
    message: str = ""

    @property
    def model(self) -> str:
        return self.model_ref.kind

    @property
    def ok(self) -> bool:
        """True when the status is ``optimal``."""
        return self.status == "optimal"

    @cached_property
    def vertex_forces(self) -> NDArray[np.float64]:
        """Force at every 3D interface vertex, ``(fn, ft1, ft2)`` in its interface frame (kN)."""
        return (self.model_ref.lift @ self.forces.ravel()).reshape(-1, 3)

    @cached_property
    def support_wrenches(self) -> NDArray[np.float64]:
        """``(n_supports, 6)``: ``(Fx, Fy, Fz, Mx, My, Mz)`` each support exerts on the structure,
        global frame, about the support centroid (kN, kN m)."""
        return (self.model_ref.B_sup @ self.forces.ravel()).reshape(-1, 6)

    @cached_property
    def _resultants(self) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        from .resultants import interface_resultants

        return interface_resultants(self.model_ref, self.vertex_forces)

    @property
    def resultants(self) -> NDArray[np.float64]:
        """Resultant force of each interface in ``model.interfaces`` order, global frame (kN),
        acting on block B."""
        return self._resultants[0]

    @property
    def pressure_points(self) -> NDArray[np.float64]:
        """Pressure point of each interface (m): where the normal forces' resultant meets the plane."""
        return self._resultants[1]

    @property
    def torques(self) -> NDArray[np.float64]:
        """Torque about the interface normal at the pressure point (kN m), on block B."""
        return self._resultants[2]


class TCESolver:
    """Clarabel-direct TCE solver for one model and material (see module docstring).

    Parameters
    ----------
    model : Model
    material : Material
    options : SolverOptions, optional
    """

    #: Phase-1 residuals in ``(feas_tol, PHASE1_BAND * feas_tol]`` are decided with tight tolerances.
    PHASE1_BAND: float = 100.0

    def __init__(self, model: Model, material: Material, options: SolverOptions | None = None) -> None:
        self.model = model
        self.material = material
        self.options = options or SolverOptions()
        self.scaling = Scaling.of(model)
        W, rows = self.scaling.force, self.scaling.rows(model)
        self._row_div = rows
        self._A_eq_hat = sp.csc_matrix(sp.diags(W / rows) @ model.A_eq)
        self._cones = cone_rows(model, material.friction)
        n = model.n_vars
        self._A = sp.vstack([self._A_eq_hat, -self._cones.M]).tocsc()
        self._b = np.zeros(self._A.shape[0])
        self._cone_list = self._cones.cones(leading_zero=model.A_eq.shape[0])
        if material.rigid:
            self._D = None
            self._P = sp.csc_matrix((n, n))
            self._obj_scale = 1.0
        else:
            self._D = model.compliance(material.normal_stiffness, material.shear_stiffness)
            P = W**2 * self._D
            self._obj_scale = float(P.max())
            self._P = sp.csc_matrix(sp.diags(P / self._obj_scale))
        self._solver: clarabel.DefaultSolver | None = None
        self._feas: clarabel.DefaultSolver | None = None
        self._recession_cache: dict[bytes, tuple[float, float, NDArray[np.float64]]] = {}

    # ------------------------------------------------------------ problem vectors
    def _rhs(self, lam: float, alpha: float) -> NDArray[np.float64]:
        """Physical right-hand side ``b_dead + lam * b_lat(alpha)`` (kN, kN m)."""
        return self.model.b_dead + lam * self.model.b_lateral(alpha)

    def _q(self, U: NDArray[np.float64]) -> NDArray[np.float64]:
        """Scaled linear objective: ``-(B_sup' U) W / obj_scale`` (normalised when rigid).

        The last one is kept: a load path re-solves with the same ``U`` and then returns
        the same array, which :meth:`_main` recognises to update only ``b``.
        """
        last = getattr(self, "_q_last", None)
        if last is not None and np.array_equal(last[0], U):
            return last[1]
        q = -(self.model.B_sup.T @ U) * self.scaling.force
        if self._D is None:
            m = np.abs(q).max(initial=0.0)
            q = q / m if m > 0 else q
        else:
            q = q / self._obj_scale
        q.flags.writeable = False
        self._q_last = (np.array(U, dtype=float), q)
        return q

    def _check_scene(self, alpha: float, U: NDArray[np.float64]) -> None:
        if self.model.kind == "planar":
            names = self.model.assembly.support_names
            sett = {n: U[6 * i : 6 * i + 6] for i, n in enumerate(names)}
            if not scene_in_plane(self.model.plane, alpha, sett):
                raise ValueError(
                    "this scene has loads or support motions out of the model's plane: "
                    "solve it with the spatial model"
                )

    # ------------------------------------------------------------ clarabel calls
    def _main(self, q: NDArray[np.float64], b: NDArray[np.float64]) -> clarabel.DefaultSolution:
        """The warm solver: built on the first call, then only its vectors are updated
        (iterative refinement as ``options.refine`` says)."""
        if self._solver is None:
            settings = self.options.clarabel_settings()
            settings.iterative_refinement_enable = self.options.refine
            self._solver = clarabel.DefaultSolver(self._P, q, self._A, b, self._cone_list, settings)
            self._q_main = q
        elif q is self._q_main:
            self._solver.update(b=b)
        else:
            self._solver.update(q=q, b=b)
            self._q_main = q
        return self._solver.solve()

    def _fresh(self, q: NDArray[np.float64], b: NDArray[np.float64], robust: bool) -> clarabel.DefaultSolution:
        """Solve the main problem with a new solver (equilibrated for this ``q`` and ``b``)."""
        # the objective's scale is free: keep q of order one (a compliance of 1e-18 with a 1 mm
        # motion puts |q| near 1e15 once P is normalised, and Clarabel then misreads the scene)
        scale = max(1.0, float(np.abs(q).max(initial=0.0)))
        s = clarabel.DefaultSolver(
            self._P / scale, q / scale, self._A, b, self._cone_list, self.options.clarabel_settings(robust=robust)
        )
        return s.solve()

    def _phase1_rows(self) -> NDArray[np.float64]:
        """Per-row divisor of the phase-1 problem: each block's own weight (force rows) and
        weight times size (moment rows), so that a small overload of a light block shows."""
        a = self.model.assembly
        free = list(a.free_indices)
        w = a.weights[free]
        size = np.array([a.blocks[i].shape.size for i in free])
        r = self.model.rows_per_block
        per_block = np.repeat(w, r)
        return np.where(self.model.row_is_moment, per_block * np.repeat(size, r), per_block)

    def phase1(self, lam: float, alpha: float) -> tuple[float, float, str]:
        """Smallest equilibrium residual reachable by admissible forces.

        Solves ``min r  s.t.  -r <= (A_eq F + b_dead + lam b_lat)_i / w_i <= r, F admissible``
        with ``w_i`` the weight (times size, for moment rows) of the row's block: always
        feasible and bounded. Returns ``(r, solve_time, clarabel status)``; ``r <= feas_tol``
        means the load is carried. A residual that is undecided (NaN) or lies within
        ``PHASE1_BAND`` times ``feas_tol`` is decided again with tight tolerances
        (:meth:`SolverOptions.clarabel_settings`); the status then ends with ``tight: ...``.
        """
        div = self._phase1_rows()
        b_eq = -self._rhs(lam, alpha) / div
        m, n = self.model.A_eq.shape
        zeros = np.zeros(self._cones.n_nonneg + 3 * self._cones.n_soc)
        b = np.concatenate([np.zeros(self._cones.n_zero), b_eq, -b_eq, zeros])
        if self._feas is None:
            A_hat = sp.diags(self.scaling.force / div) @ self.model.A_eq
            one = np.ones((m, 1))
            col = lambda rows: sp.csr_matrix((rows, 1))  # noqa: E731
            A = sp.vstack(
                [
                    sp.hstack([-self._cones.zero, col(self._cones.n_zero)]),
                    sp.hstack([A_hat, -one]),
                    sp.hstack([-A_hat, -one]),
                    sp.hstack([-self._cones.nonneg, col(self._cones.n_nonneg)]),
                    sp.hstack([-self._cones.soc, col(3 * self._cones.n_soc)]),
                ]
            ).tocsc()
            cones: list = []
            if self._cones.n_zero:
                cones.append(clarabel.ZeroConeT(self._cones.n_zero))
            cones.append(clarabel.NonnegativeConeT(2 * m + self._cones.n_nonneg))
            cones += [clarabel.SecondOrderConeT(3)] * self._cones.n_soc
            q = np.zeros(n + 1)
            q[-1] = 1.0
            self._feas_data = (sp.csc_matrix((n + 1, n + 1)), q, A, cones)
            self._feas = clarabel.DefaultSolver(*self._feas_data[:3], b, cones, self.options.clarabel_settings())
        else:
            self._feas.update(b=b)
        sol = self._feas.solve()
        r = float(sol.x[-1]) if str(sol.status) in ("Solved", "AlmostSolved") else float("nan")
        t, status = float(sol.solve_time), str(sol.status)
        if not r <= self.options.feas_tol and not r > self.PHASE1_BAND * self.options.feas_tol:
            # undecided, or too close to feas_tol for the default tolerances: decide again
            # with tight ones (a fresh solver, so also a fresh equilibration)
            P, q, A, cones = self._feas_data
            sol = clarabel.DefaultSolver(P, q, A, b, cones, self.options.clarabel_settings(tight=True)).solve()
            t += float(sol.solve_time)
            if str(sol.status) in ("Solved", "AlmostSolved"):
                r = float(np.nanmin([r, float(sol.x[-1])]))  # each is reached by some admissible state
            status = f"{status}, tight: {sol.status}"
        return r, t, status

    def recession(self, U: NDArray[np.float64]) -> tuple[float, float]:
        """Steepest descent of the rigid TCE along self-stresses.

        Solves ``min q . d  s.t.  A_eq d = 0, d admissible, -1 <= d <= 1`` with ``q`` the
        normalised linear objective for support motions ``U``. A negative value means the
        TCE is unbounded below (when feasible). Returns ``(value, solve_time)``; cached
        per ``U`` (the check does not depend on the load).
        """
        val, t, _ = self._recession(U)
        return val, t

    def recession_direction(self, U: NDArray[np.float64]) -> NDArray[np.float64]:
        """The self-stress ``d`` (model variables, scaled) of :meth:`recession`: where an
        incompatible support motion drives the forces without end (NaN if not solved)."""
        return self._recession(U)[2]

    def _recession(self, U: NDArray[np.float64]) -> tuple[float, float, NDArray[np.float64]]:
        key = np.asarray(U, dtype=float).tobytes()
        if key in self._recession_cache:
            return self._recession_cache[key]
        q = self._q(U)
        m, n = self._A_eq_hat.shape
        I = sp.identity(n, format="csr")
        A = sp.vstack([self._A_eq_hat, -self._cones.zero, I, -I, -self._cones.nonneg, -self._cones.soc]).tocsc()
        b = np.concatenate([np.zeros(m + self._cones.n_zero), np.ones(2 * n), np.zeros(self._cones.n_nonneg + 3 * self._cones.n_soc)])
        cones: list = [clarabel.ZeroConeT(m + self._cones.n_zero), clarabel.NonnegativeConeT(2 * n + self._cones.n_nonneg)]
        cones += [clarabel.SecondOrderConeT(3)] * self._cones.n_soc
        sol = clarabel.DefaultSolver(sp.csc_matrix((n, n)), q, A, b, cones, self.options.clarabel_settings()).solve()
        solved = str(sol.status) in ("Solved", "AlmostSolved")
        val = float(sol.obj_val) if solved else float("nan")
        d = np.asarray(sol.x) if solved else np.full(n, np.nan)
        out = (val, float(sol.solve_time), d)
        self._recession_cache[key] = out
        return out

    # ------------------------------------------------------------ main entry
    def solve(
        self,
        lam: float = 0.0,
        alpha: float = 0.0,
        settlements: Mapping[str, ArrayLike] | NDArray[np.float64] | None = None,
    ) -> TCEResult:
        """Minimise the TCE for load multiplier ``lam`` in direction ``alpha`` (degrees) with
        support motions ``settlements`` (``{support: [ux, uy, uz, rx, ry, rz]}`` in m and rad,
        or the stacked vector). Returns a :class:`TCEResult`; never raises on solver trouble."""
        t0 = time.perf_counter()
        if not np.isfinite(lam) or not np.isfinite(alpha):
            raise ValueError(f"lam and alpha must be finite numbers, got lam={lam!r}, alpha={alpha!r}")
        if isinstance(settlements, np.ndarray):
            U = np.asarray(settlements, dtype=float)
        else:
            U = settlement_vector(self.model, settlements)
        self._check_scene(alpha, U)
        b_eq = -self._rhs(lam, alpha) / self._row_div
        b = self._b.copy()
        b[: len(b_eq)] = b_eq
        q = self._q(U)
        # a q far from order one (extreme stiffness) goes to a solver scaled for it
        sol = self._main(q, b) if np.abs(q).max(initial=0.0) <= 1e6 else self._fresh(q, b, robust=False)
        raw = str(sol.status)
        stime = float(sol.solve_time)
        notes = [f"clarabel: {raw}"]
        status, retry, x = "numerical", "", None

        if raw in ("Solved", "AlmostSolved"):
            x = np.asarray(sol.x)
            if self._passes(x, lam, alpha):
                status = "optimal"
            else:
                notes.append("residual check failed")
        elif raw == "PrimalInfeasible":
            status = "infeasible"
        if status == "numerical" and raw != "PrimalInfeasible":
            # Clarabel's verdict is not clean (or claims unboundedness): decide feasibility first.
            r, t, fstat = self.phase1(lam, alpha)
            stime += t
            notes.append(f"phase-1 residual {r:.3g} ({fstat})")
            if not np.isfinite(r):
                retry = "phase-1 failed"
            elif r > self.options.feas_tol:
                status, retry = "infeasible", "phase-1 (tight)" if "tight" in fstat else "phase-1"
            elif raw == "DualInfeasible" and self._D is None:
                status, retry = "unbounded", ""
            elif self._D is None and np.any(U):
                val, t = self.recession(U)
                stime += t
                notes.append(f"recession {val:.3g}")
                if val < -1e-7:
                    status, retry = "unbounded", "recession"
            # feasible and bounded (or undecided): retry, first with a fresh solver whose
            # equilibration is computed for this q and b (the warm one keeps the scaling of
            # its first problem), then with robust settings
            for name, robust in (("rescaled", False), ("robust settings", True)):
                if status != "numerical":
                    break
                sol2 = self._fresh(q, b, robust)
                stime += float(sol2.solve_time)
                notes.append(f"{name} retry: {sol2.status}")
                if str(sol2.status) in ("Solved", "AlmostSolved") and self._passes(np.asarray(sol2.x), lam, alpha):
                    status, retry, x = "optimal", name, np.asarray(sol2.x)
        if status != "optimal":
            x = None
        return self._result(status, lam, alpha, U, x, stime, time.perf_counter() - t0, int(sol.iterations), retry, "; ".join(notes))

    # ------------------------------------------------------------ checks and results
    def _residuals(self, x: NDArray[np.float64], lam: float, alpha: float) -> tuple[float, float]:
        """Relative equilibrium residual and contact-law violation of the scaled answer ``x``
        (the last one is kept: :meth:`_passes` and :meth:`_result` ask for the same ``x``)."""
        last = getattr(self, "_res_last", None)
        if last is not None and last[0] is x and last[1] == (lam, alpha):
            return last[2]
        W = self.scaling.force
        F = x * W
        eq = (self.model.A_eq @ F + self._rhs(lam, alpha)) / self._row_div
        cone = cone_violation(self.model, self.material.friction, F) / W
        out = (float(np.abs(eq).max(initial=0.0)), cone)
        self._res_last = (x, (lam, alpha), out)
        return out

    def _passes(self, x: NDArray[np.float64], lam: float, alpha: float) -> bool:
        if not np.all(np.isfinite(x)):
            return False
        eq, cone = self._residuals(x, lam, alpha)
        return eq <= self.options.residual_tol and cone <= self.options.residual_tol

    def _result(
        self,
        status: str,
        lam: float,
        alpha: float,
        U: NDArray[np.float64],
        x: NDArray[np.float64] | None,
        solve_time: float,
        wall: float,
        iterations: int,
        retry: str,
        message: str,
    ) -> TCEResult:
        model = self.model
        if x is None:
            forces = np.full((model.n_contacts, model.dim), np.nan)
            tce = eq = cone = float("nan")
        else:
            F = x * self.scaling.force
            forces = F.reshape(model.n_contacts, model.dim)
            eq, cone = self._residuals(x, lam, alpha)
            tce = -float((model.B_sup @ F) @ U)
            if self._D is not None:
                tce += 0.5 * float(F @ (self._D * F))
        if self._D is not None:
            unique: bool | None = True
        elif not np.any(U):
            unique = False
        else:
            unique = None
        if retry:
            log.debug("solve at lam=%g alpha=%g: %s decided by %s (%s)", lam, alpha, status, retry, message)
        return TCEResult(
            status=status,
            lam=float(lam),
            alpha=float(alpha),
            model_ref=model,
            settlements=U,
            forces=forces,
            tce=tce,
            eq_residual=eq,
            cone_residual=cone,
            unique=unique,
            solve_time=solve_time,
            wall_time=wall,
            iterations=iterations,
            retry=retry,
            message=message,
        )
