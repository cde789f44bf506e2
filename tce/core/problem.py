"""Conic problems in Clarabel's standard form, and the four named builders tce solves.

Every problem tce hands to a solver is a :class:`ConicProblem`::

    minimise    1/2 x' P x + q' x
    subject to  A x + s = b,   s in K = K_1 x K_2 x ...

(the standard form of Clarabel: Goulart and Chen, "Clarabel: an interior-point solver for
conic programs with quadratic objectives", 2024). With ``n`` unknowns and ``m`` rows:

==========  ===============  ====================================================
``P``       (n, n) CSC       upper triangle of the (positive semidefinite) Hessian
``q``       (n,)             linear objective
``A``       (m, n) CSC       constraint matrix
``b``       (m,)             right-hand side
``cones``   tuple            ``(kind, dim)`` with kind ``"zero"``, ``"nonneg"`` or
                             ``"soc"``; the dims sum to ``m``, rows in that order
==========  ===============  ====================================================

A :class:`Formulation` holds what the problems of one model and contact law share, scaled
to be dimensionless (:mod:`tce.core.conic`): the force unknowns ``x = F / W`` (``W`` the
total weight of the free blocks), the equilibrium rows ``A_eq F + rhs = 0`` divided by
``W`` (force rows) or ``W L`` (moment rows), and the contact law ``M F + h in K``. The
physical right-hand side ``rhs = b_fixed + lam * b_live`` (kN, kN m; ``A_eq``'s row
layout) is the loads' business (:meth:`tce.core.model.Model.b_lateral`); the builders
take it as a vector. The builders:

:func:`tce_problem`
    the minimum of the Total Complementary Energy (the paper's problem (11), the
    discretised form of its minimum problem (9))::

        min  1/2 F' D F - U' B_sup F   s.t.  A_eq F + rhs = 0,  F admissible

    with ``D`` the diagonal compliance (absent for rigid contacts) and ``U`` the stacked
    support motions (m, rad).
:func:`phase1_problem`
    the smallest equilibrium residual reachable by admissible forces (always feasible and
    bounded): ``min r  s.t.  |(A_eq F + rhs)_i| / w_i <= r,  F admissible``, each row
    divided by the weight ``w_i`` of its own block (times its size for moment rows).
:func:`recession_problem`
    the steepest descent of the rigid TCE along self-stresses:
    ``min q . d  s.t.  A_eq d = 0,  M d in K,  -1 <= d <= 1``; negative means the TCE is
    unbounded below when the problem is feasible.
:func:`limit_problem`
    the direct limit analysis: ``max lam  s.t.  A_eq F + b_fixed + lam b_live = 0,  F
    admissible``, unknowns ``(x, lam)``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cached_property, partial

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike, NDArray

from .conic import ConeRows, LawCheck, Scaling, cone_rows, law_violation
from .material import Material
from .model import Model

__all__ = [
    "ConicProblem",
    "Formulation",
    "lateral_ray_problem",
    "least_violation_problem",
    "limit_problem",
    "nearest_least_violation_problem",
    "nearest_state_problem",
    "phase1_b",
    "phase1_problem",
    "recession_problem",
    "restrained_limit_problem",
    "restrained_phase1_problem",
    "restrained_tce_problem",
    "tce_b",
    "tce_problem",
    "bounded_b",
    "with_bounded_forces",
]

Cone = tuple[str, int]


def _cones(*blocks: tuple[str, int], n_soc: int = 0) -> tuple[Cone, ...]:
    """Cone list from ``(kind, rows)`` blocks (empty ones dropped) and ``n_soc`` 3D cones."""
    return tuple((k, n) for k, n in blocks if n) + (("soc", 3),) * n_soc


@dataclass(frozen=True, eq=False)
class ConicProblem:
    """``min 1/2 x'Px + q'x  s.t.  Ax + s = b,  s in K`` (shapes in the module docstring).

    Attributes
    ----------
    name : str
        What the problem is (``"tce"``, ``"phase-1"``, ``"recession"``, ``"limit"``).
    """

    name: str
    P: sp.csc_matrix = field(repr=False)
    q: NDArray[np.float64] = field(repr=False)
    A: sp.csc_matrix = field(repr=False)
    b: NDArray[np.float64] = field(repr=False)
    cones: tuple[Cone, ...] = field(repr=False)

    def __post_init__(self) -> None:
        m, n = self.A.shape
        rows = sum(d for _, d in self.cones)
        if self.P.shape != (n, n) or self.q.shape != (n,) or self.b.shape != (m,) or rows != m:
            raise ValueError(
                f"{self.name}: inconsistent shapes P {self.P.shape}, q {self.q.shape}, A {self.A.shape}, "
                f"b {self.b.shape}, cone rows {rows}"
            )

    @property
    def shape(self) -> tuple[int, int]:
        """``(m, n)``: rows and unknowns."""
        return self.A.shape


#: unknowns from which a model whose blocks form a mesh is factorised by faer (:func:`kkt_method`)
FAER_FROM = 50_000


def kkt_method(model: Model) -> str:
    """Clarabel's KKT factorisation for a model's problems: ``"faer"`` (supernodal) for a
    model of at least :data:`FAER_FROM` unknowns whose blocks form a mesh (on average at
    least 1.5 interfaces per free block: domes, vaults, walls), ``"qdldl"`` otherwise (a
    chain's factor has no fill, so a supernodal method gains nothing on it).
    """
    free = len(model.assembly.free_indices)
    mesh = free > 0 and len(model.interfaces) >= 1.5 * free
    return "faer" if mesh and model.n_vars >= FAER_FROM else "qdldl"


class Formulation:
    """What the problems of one model and contact law share, built once and scaled.

    Parameters
    ----------
    model : Model
    material : Material
        Its friction and strengths, and those of its interface kinds, give the contact law
        (:func:`tce.core.conic.cone_rows` with :meth:`tce.core.material.Material.contact_law`);
        its stiffnesses the compliance.
    rows : ConeRows, optional
        Another contact law (e.g. friction pyramids, :mod:`tce.core.pyramid`); default: the
        material's own (:func:`tce.core.conic.cone_rows`).

    Attributes
    ----------
    scaling : Scaling
        Reference force ``W`` (kN) and length ``L`` (m).
    row_div : (m_eq,) ndarray
        Divisor of each equilibrium row: ``W`` (force rows) or ``W L`` (moment rows).
    A_eq : (m_eq, n) CSC
        Scaled equilibrium operator on ``x``: ``diag(W / row_div) A_eq``.
    law : ConeRows
        The contact law on the physical forces.
    own_law : bool
        Whether ``law`` is the material's own (no ``rows`` given).
    D : (n,) ndarray or None
        Diagonal compliance (m/kN), None for rigid contacts.
    kkt : str
        Clarabel's KKT factorisation for this model (:func:`kkt_method`).
    """

    def __init__(self, model: Model, material: Material, rows: ConeRows | None = None) -> None:
        self.model = model
        self.material = material
        self.scaling = Scaling.of(model)
        W = self.scaling.force
        self.row_div = self.scaling.rows(model)
        self.A_eq = sp.csc_matrix(sp.diags(W / self.row_div) @ model.A_eq)
        #: the material's law per contact (keyword arguments of :func:`tce.core.conic.cone_rows`)
        self.contact_law = material.contact_law(model.contact_kind)
        self.law = rows if rows is not None else cone_rows(model, **self.contact_law)
        self.own_law = rows is None
        if rows is None:
            self.law_check: Callable[[NDArray[np.float64]], float] = LawCheck(model, **self.contact_law)
        else:
            self.law_check = partial(law_violation, rows)
        self.kkt = kkt_method(model)
        n = model.n_vars
        if material.rigid:
            self.D: NDArray[np.float64] | None = None
            self.P = sp.csc_matrix((n, n))
            self.obj_scale = 1.0
        else:
            self.D = model.compliance(material.normal_stiffness, material.shear_stiffness)
            P = W**2 * self.D
            self.obj_scale = float(P.max())
            self.P = sp.csc_matrix(sp.diags(P / self.obj_scale))

    @property
    def n(self) -> int:
        """Number of force unknowns."""
        return self.model.n_vars

    @cached_property
    def constraints(self) -> sp.csc_matrix:
        """``[A_eq; -M]`` ((m_eq + law rows, n), CSC), built once: the constraint matrix of
        :func:`tce_problem` and the first ``n`` columns of :func:`limit_problem`'s."""
        return sp.vstack([self.A_eq, -self.law.M]).tocsc()

    @cached_property
    def cones(self) -> tuple[Cone, ...]:
        """The cones of the rows of :attr:`constraints`: the equilibrium rows with the law's
        zero rows, then its nonnegative rows and its cones."""
        law = self.law
        return _cones(("zero", self.A_eq.shape[0] + law.n_zero), ("nonneg", law.n_nonneg), n_soc=law.n_soc)

    @cached_property
    def law_h(self) -> NDArray[np.float64]:
        """Scaled offset of the contact-law rows, ``h / W``."""
        return self.law.offset() / self.scaling.force

    @cached_property
    def _B_sup_T(self) -> sp.csr_matrix:
        """``B_sup'``, built once (scipy builds a new matrix object for every ``.T``, which costs
        more than the product in :meth:`q`)."""
        return self.model.B_sup.T.tocsr()

    def q(self, U: NDArray[np.float64]) -> NDArray[np.float64]:
        """Scaled linear objective of the TCE: ``-(B_sup' U) W``, divided by the Hessian's
        largest entry (compliant) or normalised to a largest entry of 1 (rigid)."""
        q = -(self._B_sup_T @ U) * self.scaling.force
        if self.D is None:
            m = np.abs(q).max(initial=0.0)
            return q / m if m > 0 else q
        return q / self.obj_scale

    def b_eq(self, rhs: NDArray[np.float64]) -> NDArray[np.float64]:
        """Scaled equilibrium right-hand side ``-rhs / row_div``."""
        return -rhs / self.row_div

    def forces(self, x: NDArray[np.float64]) -> NDArray[np.float64]:
        """Physical forces ``F = W x`` (kN) of the first ``n`` unknowns of ``x``."""
        return x[: self.n] * self.scaling.force

    def residuals(self, F: NDArray[np.float64], rhs: NDArray[np.float64]) -> tuple[float, float]:
        """``(equilibrium, contact law)`` residuals of physical forces ``F``, relative.

        The equilibrium residual is ``max |A_eq F + rhs| / row_div`` (relative to ``W`` and
        ``W L``); the contact-law residual, over ``W``, is
        :func:`tce.core.conic.cone_violation` for the material's own law (``max(-fn,
        ||ft|| - mu fn)`` per contact for the paper's law, in force units whatever mu; with
        the material's cohesion and strengths, the violation of each of its bounds) and
        :func:`tce.core.conic.law_violation` of the rows for another law.
        """
        return self.residuals_scaled(F, self.b_eq(rhs))

    def residuals_scaled(self, F: NDArray[np.float64], b_eq: NDArray[np.float64]) -> tuple[float, float]:
        """:meth:`residuals` for the scaled right-hand side ``b_eq = -rhs / row_div`` (the first
        ``m_eq`` entries of :func:`tce_b`, which a solve has already computed)."""
        # diag(1 / row_div) A_eq F as the scaled operator times F / W: no second copy of the
        # model's largest operator
        eq = self.A_eq @ (F / self.scaling.force) - b_eq
        return float(np.abs(eq).max(initial=0.0)), self.law_check(F) / self.scaling.force

    def energy(self, F: NDArray[np.float64], U: NDArray[np.float64], wrench: NDArray[np.float64] | None = None) -> float:
        """Total complementary energy ``1/2 F'DF - U' B_sup F`` (kN m); ``wrench`` is
        ``B_sup F`` when the caller has it."""
        e = -float((self.model.B_sup @ F if wrench is None else wrench) @ U)
        if self.D is not None:
            e += 0.5 * float(F @ (self.D * F))
        return e

    @cached_property
    def phase1_div(self) -> NDArray[np.float64]:
        """Per-row divisor of the phase-1 problem: the weight of the row's block (force rows)
        and weight times the block's size (moment rows), so a small overload of a light
        block shows."""
        a = self.model.assembly
        free = list(a.free_indices)
        w = a.weights[free]
        size = np.array([a.blocks[i].shape.size for i in free])
        r = self.model.rows_per_block
        per_block = np.repeat(w, r)
        return np.where(self.model.row_is_moment, per_block * np.repeat(size, r), per_block)


def tce_b(f: Formulation, rhs: NDArray[np.float64]) -> NDArray[np.float64]:
    """``b`` of :func:`tce_problem` for right-hand side ``rhs`` (a warm solver updates only this)."""
    return np.concatenate([f.b_eq(rhs), f.law_h])


def tce_problem(f: Formulation, b: NDArray[np.float64], U: NDArray[np.float64]) -> ConicProblem:
    """The TCE minimum for the scaled right-hand side ``b = tce_b(f, rhs)`` and support motions
    ``U`` (module docstring).

    Unknowns ``x = F / W`` (n); rows: ``m_eq`` equalities, then the contact law.
    """
    # the objective's scale is free: a q far from order one (a compliance of 1e-18 with a 1 mm
    # motion gives |q| near 1e15), which Clarabel misreads as infeasible or unbounded, is
    # brought back to one
    q = f.q(U)
    s = q_scale(q)
    return ConicProblem("tce", f.P / s, q / s, f.constraints, b, f.cones)


#: Largest ``|q|`` of a TCE objective solved as it is (see :func:`q_scale`): a 1 mm motion with a
#: stiffness of 1e15 kN/m^3 gives about 1e10; rescaling well-posed scenes below costs accuracy.
Q_MAX = 1e10


def q_scale(q: NDArray[np.float64]) -> float:
    """Divisor of a TCE objective: ``max |q|`` when it exceeds :data:`Q_MAX`, else 1."""
    m = float(np.abs(q).max(initial=0.0))
    return m if m > Q_MAX else 1.0


def phase1_b(f: Formulation, rhs: NDArray[np.float64]) -> NDArray[np.float64]:
    """``b`` of :func:`phase1_problem` for right-hand side ``rhs``."""
    law, h = f.law, f.law_h
    nz, nn = law.n_zero, law.n_nonneg
    b_eq = -rhs / f.phase1_div
    return np.concatenate([h[:nz], b_eq, -b_eq, h[nz : nz + nn], h[nz + nn :]])


def phase1_problem(f: Formulation, rhs: NDArray[np.float64]) -> ConicProblem:
    """Smallest per-block-relative equilibrium residual of admissible forces (module docstring).

    Unknowns ``(x, r)`` (n + 1); rows: the law's zero rows, ``2 m_eq`` residual bounds and
    the law's nonnegative rows (one nonnegative block), then its cones.
    """
    law = f.law
    m, n = f.A_eq.shape
    A_hat = sp.diags(f.scaling.force / f.phase1_div) @ f.model.A_eq
    one = np.ones((m, 1))
    col = lambda rows: sp.csr_matrix((rows, 1))  # noqa: E731
    A = sp.vstack(
        [
            sp.hstack([-law.zero, col(law.n_zero)]),
            sp.hstack([A_hat, -one]),
            sp.hstack([-A_hat, -one]),
            sp.hstack([-law.nonneg, col(law.n_nonneg)]),
            sp.hstack([-law.soc, col(3 * law.n_soc)]),
        ]
    ).tocsc()
    q = np.zeros(n + 1)
    q[-1] = 1.0
    cones = _cones(("zero", law.n_zero), ("nonneg", 2 * m + law.n_nonneg), n_soc=law.n_soc)
    return ConicProblem("phase-1", sp.csc_matrix((n + 1, n + 1)), q, A, phase1_b(f, rhs), cones)


def recession_problem(f: Formulation, U: NDArray[np.float64]) -> ConicProblem:
    """Steepest descent of the rigid TCE along self-stresses ``d`` (module docstring).

    The self-stresses satisfy the homogeneous contact law ``M d in K`` (the recession cone
    of ``M F + h in K``). Unknowns ``d`` (n, scaled); rows: ``m_eq`` equalities and the law's
    zero rows, ``2 n`` box rows and the law's nonnegative rows, then its cones.
    """
    law = f.law
    m, n = f.A_eq.shape
    I = sp.identity(n, format="csr")
    A = sp.vstack([f.A_eq, -law.zero, I, -I, -law.nonneg, -law.soc]).tocsc()
    b = np.concatenate([np.zeros(m + law.n_zero), np.ones(2 * n), np.zeros(law.n_nonneg + 3 * law.n_soc)])
    cones = _cones(("zero", m + law.n_zero), ("nonneg", 2 * n + law.n_nonneg), n_soc=law.n_soc)
    return ConicProblem("recession", sp.csc_matrix((n, n)), f.q(U), A, b, cones)


def limit_problem(f: Formulation, b_fixed: NDArray[np.float64], b_live: NDArray[np.float64]) -> ConicProblem:
    """The largest multiplier ``lam`` of ``b_live`` with ``b_fixed`` always applied (module docstring).

    Unknowns ``(x, lam)`` (n + 1); rows: ``m_eq`` equalities, then the contact law. The
    multipliers ``z`` of the equality rows, divided by ``row_div``, are the virtual block
    velocities of the collapse mechanism (:mod:`tce.core.limit`).
    """
    law = f.law
    m, n = f.A_eq.shape
    live = b_live / f.row_div
    rows = np.flatnonzero(live)  # the live load's column: nonzero in the equilibrium rows only
    column = sp.csc_matrix((live[rows], rows, [0, len(rows)]), shape=(m + law.n_rows, 1))
    A = sp.hstack([f.constraints, column], format="csc")
    q = np.zeros(n + 1)
    q[-1] = -1.0
    return ConicProblem("limit", sp.csc_matrix((n + 1, n + 1)), q, A, tce_b(f, b_fixed), f.cones)


def restrained_limit_problem(
    f: Formulation, b_fixed: NDArray[np.float64], b_live: NDArray[np.float64],
    G: NDArray[np.float64], capacity: NDArray[np.float64],
) -> ConicProblem:
    """:func:`limit_problem` with ``k`` bounded extra forces ``0 <= p <= capacity`` (kN) whose
    unit wrenches are the columns of ``G`` (``(m_eq, k)``, ``A_eq``'s row layout)::

        max lam  s.t.  A_eq F + G p + b_fixed + lam b_live = 0,  F admissible,  0 <= p <= capacity

    (the passive restraint of a fill, :mod:`tce.core.passive`). Unknowns ``(x, lam, p / W)``
    (n + 1 + k: ``lam`` stays at index ``n``); rows as :func:`limit_problem`, then
    :func:`with_bounded_forces`'. The multipliers of the equality rows are the virtual
    velocities, as in :func:`limit_problem`.
    """
    return _restrained(f, limit_problem(f, b_fixed, b_live), G, capacity)


def least_violation_problem(
    f: Formulation, rhs: NDArray[np.float64], target: ConeRows, normal_ref: NDArray[np.float64]
) -> ConicProblem:
    """The state of least violation of a second law ``target`` among the equilibrium states
    that meet ``f.law`` (:mod:`tce.analysis.nonassoc`)::

        min  t  s.t.  A_eq F + rhs = 0,   M F + h in K             (f.law, exactly)
                      T F + g + t e in K_T,  |T_0 F + g_0| <= t    (target, slack t)
                      |fn_k - normal_ref_k| <= t  where normal_ref_k is finite
                      t >= 0

    ``e`` is 1 on the target's nonnegative rows and on the first row of each of its
    second-order cones, so ``t`` bounds :func:`tce.core.conic.law_violation` of ``target``;
    ``T_0`` are its zero rows. Unknowns ``(x, t)`` (n + 1, ``t`` in units of ``W``); rows:
    ``m_eq`` equalities and the law's zero rows; the law's nonnegative rows, ``2 n_zero``
    rows for the target's zero rows, its nonnegative rows, ``2 k`` rows for the ``k``
    normal forces held, ``t >= 0``; the law's cones, then the target's.
    """
    law = f.law
    m, n = f.A_eq.shape
    W = f.scaling.force
    g = target.offset() / W
    held = np.flatnonzero(np.isfinite(normal_ref))
    S = sp.csr_matrix((np.ones(len(held)), (np.arange(len(held)), held * f.model.dim)), shape=(len(held), n))
    u = np.asarray(normal_ref, dtype=float)[held] / W

    def col(k: int, v: float = 0.0) -> sp.csr_matrix:
        """The column of ``t`` over ``k`` rows, every entry ``v``."""
        return sp.csr_matrix(np.full((k, 1), v)) if v and k else sp.csr_matrix((k, 1))

    nz_t, nn_t = target.n_zero, target.n_nonneg
    head = np.zeros(3 * target.n_soc)
    head[0::3] = 1.0
    A = sp.vstack(
        [
            sp.hstack([f.A_eq, col(m)]),
            sp.hstack([-law.zero, col(law.n_zero)]),
            sp.hstack([-law.nonneg, col(law.n_nonneg)]),
            sp.hstack([-target.zero, col(nz_t, -1.0)]),
            sp.hstack([target.zero, col(nz_t, -1.0)]),
            sp.hstack([-target.nonneg, col(nn_t, -1.0)]),
            sp.hstack([-S, col(len(held), -1.0)]),
            sp.hstack([S, col(len(held), -1.0)]),
            sp.hstack([sp.csr_matrix((1, n)), col(1, -1.0)]),
            sp.hstack([-law.soc, col(3 * law.n_soc)]),
            sp.hstack([-target.soc, sp.csr_matrix(-head[:, None])]),
        ]
    ).tocsc()
    h = f.law_h
    nz, nn = law.n_zero, law.n_nonneg
    b = np.concatenate(
        [f.b_eq(rhs), h[:nz], h[nz : nz + nn], g[:nz_t], -g[:nz_t], g[nz_t : nz_t + nn_t], -u, u, [0.0],
         h[nz + nn :], g[nz_t + nn_t :]]
    )
    q = np.zeros(n + 1)
    q[-1] = 1.0
    cones = _cones(("zero", m + nz), ("nonneg", nn + 2 * nz_t + nn_t + 2 * len(held) + 1), n_soc=law.n_soc + target.n_soc)
    return ConicProblem("least-violation", sp.csc_matrix((n + 1, n + 1)), q, A, b, cones)


def nearest_least_violation_problem(
    f: Formulation,
    rhs: NDArray[np.float64],
    target: ConeRows,
    normal_ref: NDArray[np.float64],
    normal_near: NDArray[np.float64],
    t_max: float,
) -> ConicProblem:
    """:func:`least_violation_problem` with its slack held to ``t <= t_max`` (in units of
    ``W``) and, among those states, the one nearest to the normal forces ``normal_near`` with
    the least tangential forces (the objective of :func:`nearest_state_problem`): a unique
    state where the least violation has many. Unknowns and rows as
    :func:`least_violation_problem`, its row ``t >= 0`` replaced by ``t <= t_max``.
    """
    base = least_violation_problem(f, rhs, target, normal_ref)
    n, dim = f.n, f.model.dim
    held = int(np.isfinite(normal_ref).sum())
    row = f.A_eq.shape[0] + f.law.n_zero + f.law.n_nonneg + 2 * target.n_zero + target.n_nonneg + 2 * held
    A = base.A.tolil()
    A[row, :] = 0.0
    A[row, n] = 1.0
    b = base.b.copy()
    b[row] = t_max
    q = np.zeros(n + 1)
    q[0:n:dim] = -np.asarray(normal_near, dtype=float) / f.scaling.force
    P = sp.diags(np.r_[np.ones(n), 0.0]).tocsc()
    return ConicProblem("nearest-least-violation", P, q, A.tocsc(), b, base.cones)


def nearest_state_problem(f: Formulation, rhs: NDArray[np.float64], normal_ref: NDArray[np.float64]) -> ConicProblem:
    """The admissible equilibrium state nearest to a reference (:mod:`tce.analysis.nonassoc`)::

        min  1/2 sum_k ((fn_k - normal_ref_k)^2 + ||ft_k||^2) / W^2
        s.t. A_eq F + rhs = 0,   M F + h in K   (f.law)

    The objective is strictly convex, so the minimiser is unique; it depends on the normal
    forces and the lengths of the tangential forces only, so it does not change when the scene
    or the interfaces' tangential frames turn. Unknowns ``x = F / W`` (n); rows as
    :func:`tce_problem`.
    """
    n, dim = f.n, f.model.dim
    q = np.zeros(n)
    q[0::dim] = -np.asarray(normal_ref, dtype=float) / f.scaling.force
    return ConicProblem("nearest-state", sp.identity(n, format="csc"), q, f.constraints, tce_b(f, rhs), f.cones)


# Certificate of no finite limit: the least-force state that carries the live load alone,
# solved by :meth:`tce.core.limit.LimitSolver.lateral_ray`.
def lateral_ray_problem(f: Formulation, b_live: NDArray[np.float64], allowed: NDArray[np.bool_]) -> ConicProblem:
    """``min sum_k ||F_k||  s.t.  A_eq F + b_live = 0,  M F in K,  F_k = 0 off ``allowed````.

    The homogeneous contact law (the recession cone of ``M F + h in K``, as in
    :func:`recession_problem`): the state is a direction along which the live load grows
    without limit. Unknowns ``(x, t)`` (n + nc), ``t_k >= ||x_k||`` one second-order cone of
    dimension ``dim + 1`` per contact; rows: ``m_eq`` equalities, the forces fixed to zero
    on the contacts not allowed and the law's zero rows, its nonnegative rows, its cones,
    then the norm cones.
    """
    law = f.law
    m, n = f.A_eq.shape
    nc, dim = f.model.n_contacts, f.model.dim
    off = (np.flatnonzero(~np.asarray(allowed, dtype=bool))[:, None] * dim + np.arange(dim)).ravel()
    fixed = sp.csr_matrix((np.ones(len(off)), (np.arange(len(off)), off)), shape=(len(off), n))
    rows = (np.arange(nc)[:, None] * (dim + 1) + np.arange(1, dim + 1)).ravel()
    norm_x = sp.csr_matrix((-np.ones(n), (rows, np.arange(n))), shape=(nc * (dim + 1), n))
    norm_t = sp.csr_matrix((-np.ones(nc), (np.arange(nc) * (dim + 1), np.arange(nc))), shape=(nc * (dim + 1), nc))
    zeros = lambda k: sp.csr_matrix((k, nc))  # noqa: E731
    A = sp.vstack(
        [
            sp.hstack([f.A_eq, zeros(m)]),
            sp.hstack([fixed, zeros(len(off))]),
            sp.hstack([-law.M, zeros(law.n_rows)]),
            sp.hstack([norm_x, norm_t]),
        ]
    ).tocsc()
    b = np.concatenate([f.b_eq(b_live), np.zeros(A.shape[0] - m)])
    q = np.concatenate([np.zeros(n), np.ones(nc)])
    cones = _cones(("zero", m + len(off) + law.n_zero), ("nonneg", law.n_nonneg), n_soc=law.n_soc)
    return ConicProblem("lateral-ray", sp.csc_matrix((n + nc, n + nc)), q, A, b, cones + (("soc", dim + 1),) * nc)


def _equilibrium_columns(f: Formulation, G: NDArray[np.float64]) -> sp.csr_matrix:
    """The columns of bounded extra forces ``p / W`` (wrenches ``G``, ``(m_eq, k)``) in the rows
    of :attr:`Formulation.constraints`: ``G W / row_div`` in the equilibrium rows, zero in the
    contact law's."""
    W = f.scaling.force
    return sp.vstack([sp.csr_matrix(G * (W / f.row_div)[:, None]), sp.csr_matrix((f.law.M.shape[0], G.shape[1]))], format="csr")


def _restrained(f: Formulation, problem: ConicProblem, G: NDArray[np.float64], capacity: ArrayLike) -> ConicProblem:
    """``problem`` (whose rows are those of :attr:`Formulation.constraints`) with the bounded
    extra forces ``0 <= p <= capacity`` (kN) of wrenches ``G`` (:func:`with_bounded_forces`)."""
    return with_bounded_forces(problem, _equilibrium_columns(f, G), np.asarray(capacity, dtype=float) / f.scaling.force)


def with_bounded_forces(problem: ConicProblem, columns: sp.spmatrix, upper: NDArray[np.float64]) -> ConicProblem:
    """``problem`` with ``k`` extra unknowns ``0 <= y <= upper`` appended after its own.

    ``columns`` ``(m, k)`` are the new unknowns' entries in ``problem``'s rows (zero outside
    the equilibrium rows); they carry no objective (zero ``P`` and ``q`` entries). Rows:
    ``problem``'s, then ``-y + s = 0`` and ``y + s = upper`` as one nonnegative block of
    ``2 k`` rows after its cones (Clarabel takes the cones in any order).
    """
    m, n = problem.A.shape
    k = columns.shape[1]
    eye = sp.identity(k, format="csr")
    A = sp.bmat([[problem.A, columns], [None, -eye], [None, eye]], format="csc", dtype=float)
    P = sp.block_diag([problem.P, sp.csc_matrix((k, k))], format="csc")
    return ConicProblem(problem.name, P, np.concatenate([problem.q, np.zeros(k)]), A, bounded_b(problem.b, upper),
                        problem.cones + (("nonneg", 2 * k),))


def bounded_b(b: NDArray[np.float64], upper: NDArray[np.float64]) -> NDArray[np.float64]:
    """``b`` of :func:`with_bounded_forces`' problem from its base problem's ``b`` and the bounds
    ``upper`` (what a warm solver of the bounded problem updates): ``(b, 0, upper)``."""
    upper = np.asarray(upper, dtype=float)
    return np.concatenate([b, np.zeros(len(upper)), upper])


def restrained_tce_problem(
    f: Formulation, b: NDArray[np.float64], U: NDArray[np.float64], G: NDArray[np.float64], capacity: NDArray[np.float64],
) -> ConicProblem:
    """:func:`tce_problem` with ``k`` bounded extra forces ``0 <= p <= capacity`` (kN) whose unit
    wrenches are the columns of ``G`` (``(m_eq, k)``, ``A_eq``'s row layout)::

        min  1/2 F' D F - U' B_sup F   s.t.  A_eq F + G p + rhs = 0,  F admissible,  0 <= p <= capacity

    (the passive restraint of a fill, :mod:`tce.core.passive`). The forces ``p`` carry no
    complementary energy (a rigid-plastic fill stores none and does not move with the
    supports); they only widen the admissible set, as in :func:`restrained_limit_problem`.
    Unknowns ``(x, p / W)`` (n + k); rows as :func:`tce_problem`, then
    :func:`with_bounded_forces`'.
    """
    return _restrained(f, tce_problem(f, b, U), G, capacity)


def restrained_phase1_problem(
    f: Formulation, rhs: NDArray[np.float64], G: NDArray[np.float64], capacity: NDArray[np.float64],
) -> ConicProblem:
    """:func:`phase1_problem` with the bounded extra forces of :func:`restrained_tce_problem`:
    the smallest per-block-relative residual of ``A_eq F + G p + rhs``. Unknowns ``(x, r,
    p / W)`` (n + 1 + k): ``r`` stays at index ``n``."""
    law, W = f.law, f.scaling.force
    Gh = sp.csr_matrix(G * (W / f.phase1_div)[:, None])
    k = G.shape[1]
    cols = sp.vstack([sp.csr_matrix((law.n_zero, k)), Gh, -Gh,
                      sp.csr_matrix((law.n_nonneg + 3 * law.n_soc, k))])
    return with_bounded_forces(phase1_problem(f, rhs), cols, np.asarray(capacity, dtype=float) / W)
