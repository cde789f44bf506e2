"""Direct limit analysis: lambda_max as one conic program, and the collapse mechanism.

For a lateral direction ``alpha`` it solves (scaled as in :mod:`tce.conic`)::

    maximise    lam
    subject to  A_eq F + b_dead + lam * b_lat(alpha) = 0,   F admissible (cones)

Its dual is the kinematic (upper-bound) problem. The multipliers ``z`` of the equilibrium
rows, divided by the row scaling, are the virtual velocities ``v`` of the free blocks
(translation and rotation about each centroid; supports are fixed), normalised so that the
lateral load does unit power: ``v . b_lat = 1``. The mechanism's virtual work then gives
``lam_kin = -v . b_dead``, which equals ``lam_max`` at the optimum (strong duality): the
certificate reported with every answer. Relative velocities at the contacts,
``A_eq' v``, lie in the dual cone (opening ``>= mu`` times sliding, associated flow).

Sign conventions: a velocity is positive along the global axes; the relative velocity of an
interface is that of block B with respect to block A (positive normal part = opening).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import clarabel
import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from .conic import Scaling, cone_rows, cone_violation
from .material import Material
from .model import EZ, Model

__all__ = ["LimitResult", "LimitSolver", "Mechanism", "mechanism_from_velocities"]


@dataclass(frozen=True, eq=False)
class Mechanism:
    """Virtual velocities of every block and what happens at each interface.

    Attributes
    ----------
    velocities : (n_blocks, 6) ndarray
        ``(vx, vy, vz, wx, wy, wz)`` of every block about its centroid (supports: zero),
        scaled so that the largest point velocity of any block vertex is 1 (m per unit
        amplitude).
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
    pts = np.vstack([b.shape.vertices for b in a.blocks])
    owner = np.concatenate([np.full(len(b.shape.vertices), i) for i, b in enumerate(a.blocks)])
    speed = vel[owner, :3] + np.cross(vel[owner, 3:], pts - a.centroids[owner])
    vmax = np.abs(speed).max(initial=0.0)
    vel = vel / vmax if vmax > 0 else vel
    modes, hp = [], np.full((len(model.interfaces), 3), np.nan)
    for slot, k in enumerate(model.interfaces):
        itf = a.interfaces[k]
        dw = vel[itf.b, 3:] - vel[itf.a, 3:]
        p = itf.points
        rel = (vel[itf.b, :3] + np.cross(vel[itf.b, 3:], p - a.centroids[itf.b])) - (
            vel[itf.a, :3] + np.cross(vel[itf.a, 3:], p - a.centroids[itf.a])
        )
        dn = rel @ itf.normal
        dt = rel - dn[:, None] * itf.normal
        width = np.ptp(p, axis=0).max()
        moving = np.abs(rel).max()
        if moving <= tol:
            modes.append("closed")
        elif np.linalg.norm(dw) * width > 1e-2 * moving:
            modes.append("hinge")
            hp[slot] = p[np.argmin(np.abs(dn))]
        elif np.abs(dt).max() > 1e-2 * moving:
            modes.append("sliding")
        else:
            modes.append("opening")
    return Mechanism(vel, tuple(modes), hp)


@dataclass(frozen=True, eq=False)
class LimitResult:
    """Answer of a direct limit analysis.

    Attributes
    ----------
    status : str
        ``optimal`` (finite lambda_max), ``infeasible`` (the structure cannot carry its
        self-weight for any lambda in this direction), ``unbounded`` (no finite limit) or
        ``numerical``.
    alpha : float
        Direction (degrees).
    lambda_max : float
        Largest load multiplier (NaN unless optimal; inf when unbounded).
    lambda_kinematic : float
        Multiplier from the virtual work of the loads on the mechanism.
    certificate_gap : float
        ``|lambda_kinematic - lambda_max| / max(|lambda_max|, 1e-12)``.
    admissibility : float
        Largest violation of the dual cone by the mechanism's relative velocities (relative
        to the largest relative velocity).
    forces : (nc, dim) ndarray
        A limit force state (kN).
    mechanism : Mechanism or None
    solve_time, wall_time : float
        Clarabel's time and the call's time (s).
    message : str
    """

    status: str
    alpha: float
    lambda_max: float
    lambda_kinematic: float
    certificate_gap: float
    admissibility: float
    forces: NDArray[np.float64] = field(repr=False)
    mechanism: Mechanism | None = field(repr=False)
    model: str = "spatial"
    solve_time: float = 0.0
    wall_time: float = 0.0
    iterations: int = 0
    message: str = ""


class LimitSolver:
    """Direct lambda_max for one model and material; one Clarabel problem per direction.

    Parameters
    ----------
    model : Model
    material : Material
    tol : float
        Clarabel's tolerances on the scaled problem.
    """

    def __init__(self, model: Model, material: Material, tol: float = 1e-10) -> None:
        self.model = model
        self.material = material
        self.tol = tol
        self.scaling = Scaling.of(model)
        self._row_div = self.scaling.rows(model)
        self._A_eq_hat = sp.csc_matrix(sp.diags(self.scaling.force / self._row_div) @ model.A_eq)
        self._cones = cone_rows(model, material.friction)

    def _settings(self) -> clarabel.DefaultSettings:
        s = clarabel.DefaultSettings()
        s.verbose = False
        s.tol_gap_abs = s.tol_gap_rel = s.tol_feas = self.tol
        s.tol_ktratio = 1e-7
        s.max_iter = 500
        return s

    def solve(self, alpha: float = 0.0) -> LimitResult:
        """Largest multiplier of lateral loads in direction ``alpha`` (degrees), with its mechanism."""
        t0 = time.perf_counter()
        model = self.model
        if model.kind == "planar" and abs(np.cos(np.deg2rad(alpha)) * model.plane.m[0] + np.sin(np.deg2rad(alpha)) * model.plane.m[1]) > 1e-12:
            raise ValueError("lateral direction out of the planar model's plane: use the spatial model")
        m, n = self._A_eq_hat.shape
        lat = model.b_lateral(alpha) / self._row_div
        rhs = -model.b_dead / self._row_div
        A = sp.vstack(
            [
                sp.hstack([self._A_eq_hat, sp.csc_matrix(lat[:, None])]),
                sp.hstack([-self._cones.M, sp.csr_matrix((self._cones.M.shape[0], 1))]),
            ]
        ).tocsc()
        b = np.concatenate([rhs, np.zeros(self._cones.M.shape[0])])
        q = np.zeros(n + 1)
        q[-1] = -1.0
        solver = clarabel.DefaultSolver(
            sp.csc_matrix((n + 1, n + 1)), q, A, b, self._cones.cones(leading_zero=m), self._settings()
        )
        sol = solver.solve()
        raw = str(sol.status)
        nan = float("nan")
        empty = np.full((model.n_contacts, model.dim), np.nan)
        if raw == "PrimalInfeasible":
            # Farkas certificate: block velocities under which the self-weight does positive
            # work while every contact opens or slides admissibly: the collapse under self-weight
            v = np.asarray(sol.z)[:m] / self._row_div
            mech = mechanism_from_velocities(model, _block_velocities(model, v)) if np.any(v) else None
            return LimitResult("infeasible", alpha, nan, nan, nan, nan, empty, mech, model.kind,
                               sol.solve_time, time.perf_counter() - t0, sol.iterations, f"clarabel: {raw}")
        if raw == "DualInfeasible":
            return LimitResult("unbounded", alpha, float("inf"), nan, nan, nan, empty, None, model.kind,
                               sol.solve_time, time.perf_counter() - t0, sol.iterations, f"clarabel: {raw}")
        x = np.asarray(sol.x)
        lam = float(x[-1])
        F = x[:-1] * self.scaling.force
        eq = (model.A_eq @ F + model.b_dead + lam * model.b_lateral(alpha)) / self._row_div
        ok = (
            raw in ("Solved", "AlmostSolved")
            and np.abs(eq).max(initial=0.0) <= 1e-8
            and cone_violation(model, self.material.friction, F) / self.scaling.force <= 1e-8
        )
        if not ok:
            return LimitResult("numerical", alpha, nan, nan, nan, nan, empty, None, model.kind,
                               sol.solve_time, time.perf_counter() - t0, sol.iterations,
                               f"clarabel: {raw}; residual {np.abs(eq).max():.3g}")
        z = np.asarray(sol.z)
        v = z[:m] / self._row_div  # virtual velocities per equilibrium row, v . b_lat = 1
        lam_kin = float(-(v @ model.b_dead) / (v @ model.b_lateral(alpha)))
        gap = abs(lam_kin - lam) / max(abs(lam), 1e-12)
        rel = model.A_eq.T @ v  # relative contact velocities (B w.r.t. A), model variables
        adm = self._dual_cone_violation(rel)
        mech = mechanism_from_velocities(model, _block_velocities(model, v))
        return LimitResult(
            "optimal", alpha, lam, lam_kin, gap, adm, F.reshape(model.n_contacts, model.dim), mech,
            model.kind, float(sol.solve_time), time.perf_counter() - t0, int(sol.iterations), f"clarabel: {raw}",
        )

    def _dual_cone_violation(self, rel: NDArray[np.float64]) -> float:
        """Violation of ``dn >= mu ||dt||`` (tangential free of constraint for mu = 0; no sliding
        for Heyman), relative to the largest relative velocity."""
        d = rel.reshape(self.model.n_contacts, self.model.dim)
        scale = max(np.abs(d).max(initial=0.0), 1e-300)
        dn, dt = d[:, 0], np.linalg.norm(d[:, 1:], axis=1)
        mu = self.material.friction
        if mu is None:
            viol = np.maximum(-dn, dt)
        elif mu == 0.0:
            viol = np.maximum(-dn, 0.0)
        else:
            viol = np.maximum(mu * dt - dn, 0.0)
        return float(viol.max(initial=0.0) / scale)

    # ------------------------------------------------------------------------------------
    # Certificate of no finite limit (added with issue 15, kept apart from `solve` so that
    # the conic problem refactor can carry it over as one more named problem).
    def lateral_ray(self, alpha: float = 0.0, contacts: NDArray[np.bool_] | None = None) -> NDArray[np.float64] | None:
        """A force state carrying the unit lateral load alone, with the least total contact force.

        Solves, scaled as :meth:`solve`::

            minimise    sum_k ||F_k||
            subject to  A_eq F + b_lat(alpha) = 0,   F admissible (cones),
                        F_k = 0 for the contacts not in ``contacts``

        When the direct limit is unbounded, such a state exists: Clarabel's certificate of
        dual infeasibility of the max-lambda problem is a direction ``(dF, dlam)`` with
        ``A_eq dF + dlam b_lat = 0``, ``dF`` admissible and ``dlam > 0``, and ``dF / dlam``
        is one. Adding any multiple of it to an admissible state at ``lam`` gives one at any
        larger ``lam``: the contacts it loads carry the lateral load without limit. Among all
        such states this is the one of least total force, which loads few contacts (those
        that lock), where an interior-point certificate loads all of them.

        Parameters
        ----------
        alpha : float
            Direction of the lateral load (degrees).
        contacts : (n_contacts,) bool array, optional
            The contacts allowed to carry force (default: all).

        Returns
        -------
        (n_contacts, dim) ndarray or None
            Contact forces (kN per unit lambda), or None when no such state exists (the limit
            is finite, or the allowed contacts cannot carry the load) or the solve fails.
        """
        model = self.model
        m, n = self._A_eq_hat.shape
        nc, dim = model.n_contacts, model.dim
        keep = np.ones(nc, dtype=bool) if contacts is None else np.asarray(contacts, dtype=bool)
        off = (np.flatnonzero(~keep)[:, None] * dim + np.arange(dim)).ravel()
        fixed = sp.csr_matrix((np.ones(len(off)), (np.arange(len(off)), off)), shape=(len(off), n))
        # t_k >= ||F_k||: one second-order cone (t_k, F_k) per contact, rows -(t_k, F_k)
        rows = (np.arange(nc)[:, None] * (dim + 1) + np.arange(1, dim + 1)).ravel()
        norm_f = sp.csr_matrix((-np.ones(n), (rows, np.arange(n))), shape=(nc * (dim + 1), n))
        norm_t = sp.csr_matrix((-np.ones(nc), (np.arange(nc) * (dim + 1), np.arange(nc))), shape=(nc * (dim + 1), nc))
        A = sp.vstack(
            [
                sp.hstack([self._A_eq_hat, sp.csr_matrix((m, nc))]),
                sp.hstack([fixed, sp.csr_matrix((len(off), nc))]),
                sp.hstack([-self._cones.M, sp.csr_matrix((self._cones.M.shape[0], nc))]),
                sp.hstack([norm_f, norm_t]),
            ]
        ).tocsc()
        b = np.concatenate([-model.b_lateral(alpha) / self._row_div, np.zeros(A.shape[0] - m)])
        q = np.concatenate([np.zeros(n), np.ones(nc)])
        cones = self._cones.cones(leading_zero=m + len(off)) + [clarabel.SecondOrderConeT(dim + 1)] * nc
        sol = clarabel.DefaultSolver(sp.csc_matrix((n + nc, n + nc)), q, A, b, cones, self._settings()).solve()
        if str(sol.status) not in ("Solved", "AlmostSolved"):
            return None
        F = np.asarray(sol.x)[:n] * self.scaling.force
        F[off] = 0.0
        eq = (model.A_eq @ F + model.b_lateral(alpha)) / self._row_div
        if np.abs(eq).max(initial=0.0) > 1e-7 or cone_violation(model, self.material.friction, F) > 1e-7 * self.scaling.force:
            return None
        return F.reshape(nc, dim)
