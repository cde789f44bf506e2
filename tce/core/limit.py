"""Direct limit analysis: lambda_max as one conic program, and the collapse mechanism.

For a load pattern (:class:`tce.core.loads.LoadPattern`: by default the lateral pattern in
direction ``alpha``) it solves (:func:`tce.core.problem.limit_problem`, scaled as in
:mod:`tce.core.conic`)::

    maximise    lam
    subject to  A_eq F + b_fixed + lam * b_live = 0,   F admissible (cones)

(``b_fixed = b_dead``, ``b_live = b_lat(alpha)`` for the default pattern). Its dual is the
kinematic (upper-bound) problem. The multipliers ``z`` of the equilibrium rows, divided by
the row scaling, are the virtual velocities ``v`` of the free blocks (translation and
rotation about each centroid; supports are fixed), normalised so that the live load does
unit power: ``v . b_live = 1``. The mechanism's virtual work then gives
``lam_kin = (-v . b_fixed + h . y / W) / v . b_live`` (the second term, zero for the paper's
laws, is what the offsets of the contact law dissipate: cohesion, tensile and compressive
strength, with ``y`` the multipliers of the law's rows), which equals ``lam_max`` at the
optimum (strong duality): the certificate reported with every answer. Relative velocities at
the contacts, ``A_eq' v``, lie in the dual cone (opening ``>= mu`` times sliding, associated
flow).
This is the lower-bound (static) theorem of limit analysis for rigid blocks with
associated Coulomb friction (Heyman, *The stone skeleton*, 1966, for the no-tension,
no-sliding material; Livesley, 1978, and Gilbert and Melbourne, 1994, for blocks in
frictional contact), written as a conic program.

Sign conventions: a velocity is positive along the global axes; the relative velocity of an
interface is that of block B with respect to block A (positive normal part = opening).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .clarabel_solver import Solution, SolverOptions, solve_once
from .conic import ConeRows, law_violation
from .loads import LoadPattern, scene_vectors
from .material import Material
from .model import EZ, Model
from .passive import Restraint, passive_restraint
from .problem import Formulation, lateral_ray_problem, limit_problem, phase1_problem, restrained_limit_problem
from .. import display
from .result import DOFS, Result

__all__ = ["LimitResult", "LimitSolver", "Mechanism", "mechanism_from_velocities"]


@dataclass(frozen=True, eq=False)
class Mechanism:
    """Virtual velocities of every block and what happens at each interface.

    Attributes
    ----------
    velocities : (n_blocks, 6) ndarray
        ``(vx, vy, vz, wx, wy, wz)`` of every block about its centroid (supports: zero),
        scaled so that the largest vertex velocity is 1 (m per unit amplitude).
    modes : tuple of str
        Per interface of ``model.interfaces``: ``"hinge"`` (relative rotation),
        ``"sliding"`` (relative tangential translation, no rotation), ``"opening"``
        (separation by translation) or ``"closed"``.
    hinge_points : (ni, 3) ndarray
        For hinges, the contact point of least relative normal velocity (the hinge line's
        trace); NaN elsewhere.
    """

    velocities: NDArray[np.float64]
    modes: tuple[str, ...]
    hinge_points: NDArray[np.float64]

    def __repr__(self) -> str:
        counts = {m: self.modes.count(m) for m in ("hinge", "sliding", "opening") if m in self.modes}
        return display.call("Mechanism", {}, head=f"{len(self.velocities)} blocks; interfaces: "
                            + (", ".join(f"{m} {n}" for m, n in counts.items()) or "no relative motion"))

    @property
    def hinges(self) -> list[int]:
        """Slots (in ``model.interfaces``) of the interfaces that hinge."""
        return [k for k, m in enumerate(self.modes) if m == "hinge"]

    @property
    def sliding(self) -> list[int]:
        """Slots of the interfaces that slide."""
        return [k for k, m in enumerate(self.modes) if m == "sliding"]


def _block_velocities(model: Model, v: NDArray[np.float64]) -> NDArray[np.float64]:
    """Velocities ``(n_blocks, 6)`` from the per-row multipliers ``v`` of the equilibrium rows."""
    nb = len(model.assembly.blocks)
    out = np.zeros((nb, 6))
    free = np.array(model.assembly.free_indices)
    if model.kind == "spatial":
        out[free] = v.reshape(-1, 6)
    else:
        vv = v.reshape(-1, 3)
        e, m = model.plane.e, model.plane.m
        out[free, :3] = vv[:, [0]] * e + vv[:, [1]] * EZ
        out[free, 3:] = vv[:, [2]] * m
    return out


def mechanism_from_velocities(model: Model, vel: NDArray[np.float64], tol: float = 1e-4) -> Mechanism:
    """Classify the interfaces of ``model`` under block velocities ``vel`` ((n_blocks, 6)).

    The velocities are rescaled so that the largest vertex speed is 1. An interface whose
    largest relative speed is below ``tol`` is closed; otherwise it hinges when the relative
    rotation times the interface's width exceeds 1 % of that speed, slides when the
    tangential part does, and opens when only the normal part is left.
    """
    a = model.assembly
    c = a.centroids
    faces = a.face_table
    owner = faces.vertex_owner
    speed = vel[owner, :3] + np.cross(vel[owner, 3:], faces.points - c[owner])
    vmax = np.abs(speed).max(initial=0.0)
    vel = vel / vmax if vmax > 0 else vel
    # every vertex of the model's interfaces (interface by interface, in slot order)
    t = a.interface_table
    slots = np.asarray(model.interfaces, dtype=np.int64)
    counts = t.polygons.counts[slots]
    first = np.concatenate([[0], np.cumsum(counts)[:-1]]).astype(np.int64)
    slot = np.repeat(np.arange(len(slots)), counts)
    k = slots[slot]
    p = t.points[t.start[k] + np.arange(len(slot)) - first[slot]]
    ia, ib, n = t.a[k], t.b[k], t.normal[k]
    rel = (vel[ib, :3] + np.cross(vel[ib, 3:], p - c[ib])) - (vel[ia, :3] + np.cross(vel[ia, 3:], p - c[ia]))
    dn = np.einsum("ij,ij->i", rel, n)
    dt = rel - dn[:, None] * n
    modes = np.full(len(slots), "opening", dtype=object)
    hp = np.full((len(slots), 3), np.nan)
    if len(slots):
        width = (np.maximum.reduceat(p, first) - np.minimum.reduceat(p, first)).max(axis=1)
        moving = np.maximum.reduceat(np.abs(rel).max(axis=1), first)
        sliding = np.maximum.reduceat(np.abs(dt).max(axis=1), first) > 1e-2 * moving
        turning = np.linalg.norm(vel[t.b[slots], 3:] - vel[t.a[slots], 3:], axis=1) * width > 1e-2 * moving
        closed = moving <= tol
        modes[~closed & ~turning & sliding] = "sliding"
        hinge = ~closed & turning
        modes[hinge] = "hinge"
        modes[closed] = "closed"
        # the hinge line's trace: the first vertex of least |dn| of each interface
        order = np.lexsort((np.arange(len(slot)), np.abs(dn), slot))
        least = order[np.searchsorted(slot[order], np.arange(len(slots)))]
        hp[hinge] = p[least[hinge]]
    modes = modes.tolist()
    return Mechanism(vel, tuple(modes), hp)


@dataclass(frozen=True, eq=False, kw_only=True, repr=False)
class LimitResult(Result):
    """Answer of a direct limit analysis.

    Attributes
    ----------
    status : str
        ``optimal`` (finite lambda_max), ``infeasible`` (the structure cannot carry its
        fixed loads for any lambda), ``unbounded`` (no finite limit) or ``numerical``.
    alpha : float
        Direction (degrees) of the lateral loads (NaN when the live load has no lateral part).
    loads : LoadPattern or None
        The load pattern (None for vectors given to :meth:`LimitSolver.solve_loads`).
    lambda_max : float
        Largest load multiplier (NaN unless optimal; inf when unbounded).
    lambda_kinematic : float
        Multiplier from the virtual work of the loads on the mechanism.
    certificate_gap : float
        ``|lambda_kinematic - lambda_max| / max(|lambda_max|, 1e-12)``.
    admissibility : float
        Largest violation of the dual cone by the mechanism's relative velocities (relative
        to the largest relative velocity); NaN without the mechanism.
    forces : (nc, dim) ndarray
        A limit force state (kN); NaN unless optimal.
    mechanism : Mechanism or None
        None when not asked for (:meth:`LimitSolver.with_mechanism` adds it).
    row_velocities : (m_eq,) ndarray or None
        Virtual velocities per equilibrium row of the model (``z / row_div``, ``A_eq``'s row
        layout: m/s and rad/s per unit power of the live load), from which the mechanism is
        classified; None when the solve gave none.
    model : str
        ``"spatial"`` or ``"planar"``.
    iterations : int
    setup_time : float
        Wall time of the solver set-up (s).
    restraint_forces : (k,) ndarray or None
        The bounded extra forces of a restrained problem at the limit (kN; the fill's
        passive restraint, :mod:`tce.core.passive`); None without them, NaN unless optimal.
    """

    HEADLINE = ("lambda_max", "alpha", "model", "lambda_kinematic", "certificate_gap")

    alpha: float
    loads: LoadPattern | None = field(default=None, repr=False)
    lambda_max: float = float("nan")
    lambda_kinematic: float = float("nan")
    certificate_gap: float = float("nan")
    admissibility: float = float("nan")
    forces: NDArray[np.float64] = field(repr=False)
    mechanism: Mechanism | None = field(default=None, repr=False)
    row_velocities: NDArray[np.float64] | None = field(default=None, repr=False)
    model: str = "spatial"
    iterations: int = 0
    setup_time: float = 0.0
    restraint_forces: NDArray[np.float64] | None = field(default=None, repr=False)

    def _arrays(self) -> tuple[dict[str, tuple], dict[str, Any]]:
        """The collapse mechanism (``mechanism``: dims ``(block, dof)``, blocks in assembly order)."""
        if self.mechanism is None:
            return {}, {}
        data = {"mechanism": (("block", "dof"), self.mechanism.velocities, {"units": "m, rad (unit amplitude)"})}
        return data, {"dof": list(DOFS)}


class LimitSolver:
    """Direct lambda_max for one model and material; one Clarabel problem per load pattern.

    Parameters
    ----------
    model : Model
    material : Material
    tol : float
        Clarabel's tolerances on the scaled problem.
    rows : ConeRows, optional
        Another contact law than the material's (e.g. a friction pyramid).
    formulation : Formulation, optional
        The scaled operators of ``model`` and ``material`` when the caller already has them
        (:class:`tce.core.analysis.Analysis` shares one with its TCE solver); not with ``rows``.
    """

    def __init__(
        self,
        model: Model,
        material: Material,
        tol: float = 1e-10,
        rows: ConeRows | None = None,
        formulation: Formulation | None = None,
    ) -> None:
        if formulation is not None and (rows is not None or formulation.model is not model
                                        or formulation.material is not material or not formulation.own_law):
            raise ValueError("LimitSolver: a formulation must be of the same model and material, without rows")
        self.model = model
        self.material = material
        self.tol = tol
        self.formulation = formulation or Formulation(model, material, rows)
        self.options = SolverOptions(tol=tol, max_iter=500)
        #: Clarabel settings without and with iterative refinement (the retry)
        self._settings = tuple(self.options.settings(refine=r, kkt=self.formulation.kkt) for r in (False, True))

    def solve(self, alpha: float | None = None, loads: LoadPattern | None = None, mechanism: bool = True) -> LimitResult:
        """Largest multiplier of the live part of the pattern ``loads`` (default: the lateral
        pattern in direction ``alpha``, degrees), with its mechanism unless ``mechanism`` is
        False (see :meth:`solve_loads`).

        Raises
        ------
        ValueError
            A pattern that cannot be applied, or that leaves a planar model's plane.
        """
        pattern, b_fixed, b_live = scene_vectors(self.model, alpha, loads)
        return self.solve_loads(b_fixed, b_live, pattern.direction, pattern, mechanism=mechanism,
                                restraint=passive_restraint(self.model, pattern.fill))

    def solve_loads(
        self,
        b_fixed: NDArray[np.float64],
        b_live: NDArray[np.float64],
        alpha: float = float("nan"),
        loads: LoadPattern | None = None,
        mechanism: bool = True,
        restraint: Restraint | None = None,
    ) -> LimitResult:
        """Largest multiplier of the live loads ``b_live`` with ``b_fixed`` always applied
        (both in ``A_eq``'s row layout, kN and kN m); ``alpha`` and ``loads`` are recorded in
        the result. With ``restraint``, its bounded forces are unknowns of the problem too
        (:func:`tce.core.problem.restrained_limit_problem`; :meth:`solve` takes the fill's
        passive restraint from the pattern) and the result carries their values.

        The mechanism is classified only when ``mechanism`` is True; the result carries the
        virtual velocities ``row_velocities`` either way (:meth:`with_mechanism`)."""
        t0 = time.perf_counter()
        model, f = self.model, self.formulation
        m = f.A_eq.shape[0]
        if restraint is None:
            problem = limit_problem(f, b_fixed, b_live)
        else:
            problem = restrained_limit_problem(f, b_fixed, b_live, restraint.G, restraint.capacity)
        rhs_scaled = problem.b[:m]
        # without iterative refinement first (cheaper); an answer that is not clean is solved
        # again with it
        sol = solve_once(problem, self._settings[0])
        retried, spent = "", (0.0, 0.0)
        checked = self._checked(sol, rhs_scaled, b_live, restraint)
        if sol.status not in ("PrimalInfeasible", "DualInfeasible") and checked is None:
            retried, spent = f" (after {sol.status} without iterative refinement)", (sol.solve_time, sol.setup_time)
            sol = solve_once(problem, self._settings[1])
            checked = self._checked(sol, rhs_scaled, b_live, restraint)
        no_restraint = None if restraint is None else np.full(restraint.size, np.nan)
        common = dict(alpha=alpha, loads=loads, model=model.kind, solve_time=sol.solve_time + spent[0],
                      setup_time=sol.setup_time + spent[1],
                      iterations=sol.iterations)
        if sol.status == "PrimalInfeasible":
            # Farkas certificate: block velocities under which the fixed loads do positive
            # work while every contact opens or slides admissibly: the collapse under them
            v = sol.z[:m] / f.row_div
            mech = mechanism_from_velocities(model, _block_velocities(model, v)) if np.any(v) else None
            return LimitResult(status="infeasible", forces=self._no_forces(), mechanism=mech, row_velocities=v,
                               message=f"clarabel: {sol.status}", wall_time=time.perf_counter() - t0,
                               restraint_forces=no_restraint, **common)
        if sol.status == "DualInfeasible":
            return LimitResult(status="unbounded", lambda_max=float("inf"), forces=self._no_forces(), message=f"clarabel: {sol.status}",
                               wall_time=time.perf_counter() - t0,
                               restraint_forces=no_restraint, **common)
        if checked is None and (proof := self._unbounded_proof(b_fixed, b_live)):
            return LimitResult(status="unbounded", lambda_max=float("inf"), forces=self._no_forces(),
                               message=f"clarabel: {sol.status}{retried}; {proof}", wall_time=time.perf_counter() - t0,
                               restraint_forces=no_restraint, **common)
        if checked is None:
            eq = f.residuals_scaled(f.forces(sol.x), rhs_scaled - float(sol.x[f.n]) * b_live / f.row_div)[0]
            return LimitResult(status="numerical", forces=self._no_forces(), message=f"clarabel: {sol.status}{retried}; residual {eq:.3g}",
                               wall_time=time.perf_counter() - t0, restraint_forces=no_restraint, **common)
        lam, F, p = checked
        v = sol.z[:m] / f.row_div  # virtual velocities per equilibrium row, v . b_live = 1
        # power of the fixed loads plus what the offsets of the other rows dissipate (the
        # law's cohesion, tension, crushing: h . y with y the law rows' multipliers, zero for
        # the paper's laws; a restraint's capacities times its upper-bound rows' multipliers)
        lam_kin = float((-(v @ b_fixed) + problem.b[m:] @ sol.z[m:]) / (v @ b_live))
        gap = abs(lam_kin - lam) / max(abs(lam), 1e-12)
        mech, adm = self._mechanism(v) if mechanism else (None, float("nan"))
        return LimitResult(
            status="optimal", lambda_max=lam, lambda_kinematic=lam_kin, certificate_gap=gap, admissibility=adm,
            forces=F.reshape(model.n_contacts, model.dim), mechanism=mech, row_velocities=v,
            message=f"clarabel: {sol.status}{retried}", wall_time=time.perf_counter() - t0, restraint_forces=p, **common,
        )

    def _no_forces(self) -> NDArray[np.float64]:
        """The forces of an answer that has none: NaN, shaped as an optimal answer's."""
        return np.full((self.model.n_contacts, self.model.dim), np.nan)

    def with_mechanism(self, result: LimitResult) -> LimitResult:
        """``result`` (an optimal answer of this solver) with its mechanism classified from
        its ``row_velocities``, and the mechanism's ``admissibility``; the same object when
        it has them or is not optimal."""
        if result.mechanism is not None or result.row_velocities is None or result.status != "optimal":
            return result
        mech, adm = self._mechanism(result.row_velocities)
        return replace(result, mechanism=mech, admissibility=adm)

    def _mechanism(self, v: NDArray[np.float64]) -> tuple[Mechanism, float]:
        """The mechanism of the virtual velocities ``v`` (per equilibrium row) and the dual
        cone's violation by its relative contact velocities (``A_eq' v``, B w.r.t. A)."""
        mech = mechanism_from_velocities(self.model, _block_velocities(self.model, v))
        return mech, self._dual_cone_violation(self.model.A_eq.T @ v)

    def _checked(
        self, sol: Solution, rhs_scaled: NDArray[np.float64], b_live: NDArray[np.float64],
        restraint: Restraint | None = None,
    ) -> tuple[float, NDArray[np.float64], NDArray[np.float64] | None] | None:
        """``(lam, F, p)`` of a limit solve that passes the residual checks (1e-8 of W and W
        L; a restraint's forces within their bounds to 1e-8 of W), else None; ``rhs_scaled``
        is the fixed loads' scaled right-hand side (``b[:m_eq]``); ``p`` the restraint's
        forces (kN; None without one)."""
        if not sol.solved:
            return None
        f = self.formulation
        lam = float(sol.x[f.n])  # unknowns (x, lam) or, restrained, (x, lam, p / W)
        F = f.forces(sol.x)
        rhs = rhs_scaled - lam * b_live / f.row_div
        p = None
        if restraint is not None:
            W = f.scaling.force
            p = sol.x[f.n + 1 :] * W
            rhs = rhs - restraint.G @ p / f.row_div
            if np.any(p < -1e-8 * W) or np.any(p > restraint.capacity + 1e-8 * W):
                return None
        eq, law = f.residuals_scaled(F, rhs)
        return (lam, F, p) if eq <= 1e-8 and law <= 1e-8 else None

    def _dual_cone_violation(self, rel: NDArray[np.float64]) -> float:
        """Violation of ``dn >= mu ||dt||`` (tangential free of constraint for mu = 0; no sliding
        for Heyman; no relative motion at all at a bonded contact), relative to the largest
        relative velocity, each contact by its own law. With a compressive strength a contact
        may also close (crushing at ``fn = fc A``): ``dn`` is then free. Cohesion and tensile
        strength shift the law without changing its recession cone, so they leave the flow
        rule as it is."""
        d = rel.reshape(self.model.n_contacts, self.model.dim)
        scale = max(np.abs(rel).max(initial=0.0), 1e-300)
        dn = d[:, 0]
        dt = np.abs(d[:, 1]) if self.model.dim == 2 else np.hypot(d[:, 1], d[:, 2])
        law = self.formulation.contact_law

        def each(key: str, absent: float) -> NDArray[np.float64]:
            v = law[key]
            return np.broadcast_to(np.asarray(absent if v is None else v, dtype=float), dn.shape)

        mu, crush, bonded = each("friction", np.nan), np.isfinite(each("compressive_strength", np.inf)), \
            np.isinf(each("tensile_strength", 0.0))
        dn = np.where(crush, np.inf, dn)
        with np.errstate(invalid="ignore"):
            viol = np.where(np.isnan(mu), np.maximum(-dn, dt), np.maximum(np.nan_to_num(mu) * dt - dn, 0.0))
        viol = np.where(bonded, np.maximum(np.abs(d[:, 0]), dt), viol)
        return float(viol.max(initial=0.0) / scale)

    def _unbounded_proof(self, b_fixed: NDArray[np.float64], b_live: NDArray[np.float64]) -> str:
        """Decide an undecided limit solve as unbounded, independently of Clarabel's certificate.

        Clarabel's certificate of dual infeasibility can stall between its full and reduced
        tolerances (``AlmostDualInfeasible``), which is no verdict. The limit is unbounded
        when both of these hold (each a well-posed, bounded problem):

        - a live-load ray: the least-force state carrying the unit live load alone under the
          homogeneous law (:meth:`lateral_ray`'s problem), with equilibrium residual and law
          violation below ``residual_tol`` (relative to ``W`` and ``W L``);
        - an admissible state at ``lam = 0``: the phase-1 residual of the fixed loads
          (:func:`tce.core.problem.phase1_problem`) is at most ``feas_tol``.

        Then ``F0 + t dF`` is admissible at ``lam = t`` for every ``t >= 0``. Returns what
        proved it, or ``""`` when either part fails (the answer stays ``numerical``).
        """
        ray = self._ray(b_live, np.ones(self.model.n_contacts, dtype=bool))
        tol = self.options.residual_tol
        if ray is None or ray[1] > tol or ray[2] > tol:
            return ""
        f = self.formulation
        sol = solve_once(phase1_problem(f, b_fixed), self.options.settings(kkt=f.kkt))
        if not (sol.solved and float(sol.x[-1]) <= self.options.feas_tol):
            return ""
        return (f"unbounded: the live load alone is carried (ray residuals {ray[1]:.2g}, {ray[2]:.2g}) "
                f"and the fixed loads are (phase-1 residual {float(sol.x[-1]):.2g})")

    def _ray(
        self, b_live: NDArray[np.float64], allowed: NDArray[np.bool_]
    ) -> tuple[NDArray[np.float64], float, float] | None:
        """The least-force state carrying ``b_live`` alone on the ``allowed`` contacts
        (:func:`tce.core.problem.lateral_ray_problem`), with its equilibrium residual
        (relative to ``W``, ``W L``) and violation of the homogeneous law (over ``W``); None
        when the solve fails."""
        model, f = self.model, self.formulation
        sol = solve_once(lateral_ray_problem(f, b_live, allowed), self.options.settings(kkt=f.kkt))
        if not sol.solved:
            return None
        F = f.forces(sol.x)
        F.reshape(model.n_contacts, model.dim)[~allowed] = 0.0
        eq = float(np.abs((model.A_eq @ F + b_live) / f.row_div).max(initial=0.0))
        law = law_violation(replace(f.law, h=None), F) / f.scaling.force  # the homogeneous law: a direction
        return F, eq, law

    def lateral_ray(
        self, alpha: float | None = None, contacts: NDArray[np.bool_] | None = None, loads: LoadPattern | None = None
    ) -> NDArray[np.float64] | None:
        """A force state carrying the unit live load alone (by default the lateral pattern),
        with the least total contact force.

        Solves, scaled as :meth:`solve`::

            minimise    sum_k ||F_k||
            subject to  A_eq F + b_live = 0,   F admissible (cones),
                        F_k = 0 for the contacts not in ``contacts``

        When the direct limit is unbounded, such a state exists: Clarabel's certificate of
        dual infeasibility of the max-lambda problem is a direction ``(dF, dlam)`` with
        ``A_eq dF + dlam b_live = 0``, ``dF`` admissible and ``dlam > 0``, and ``dF / dlam``
        is one: the contacts it loads carry the live load without limit. The least total
        force loads few contacts (those that lock), where an interior-point certificate loads
        all of them. The fill's passive restraint (:mod:`tce.core.passive`) has no column:
        its forces are bounded, so their share vanishes along a ray.

        Parameters
        ----------
        alpha : float, optional
            Direction of the lateral load (degrees) of the default pattern.
        contacts : (n_contacts,) bool array, optional
            The contacts allowed to carry force (default: all).
        loads : LoadPattern, optional
            The pattern whose live part ``b_live`` is carried, instead of ``alpha``.

        Returns
        -------
        (n_contacts, dim) ndarray or None
            Contact forces (kN per unit lambda), or None when no such state exists (the limit
            is finite, or the allowed contacts cannot carry the load) or the solve fails.
        """
        model = self.model
        allowed = np.ones(model.n_contacts, dtype=bool) if contacts is None else np.asarray(contacts, dtype=bool)
        ray = self._ray(scene_vectors(model, alpha, loads)[2], allowed)
        if ray is None or ray[1] > 1e-7 or ray[2] > 1e-7:
            return None
        return ray[0].reshape(model.n_contacts, model.dim)
