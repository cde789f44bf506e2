"""Finite settlements: a support motion followed in increments, the geometry updated as it moves.

For a planar assembly (an arch in its own plane: :func:`tce.core.model.find_plane`), rigid
blocks and a Heyman material (no tension, no sliding, unlimited compressive strength), the
support motion ``s * U`` (``U`` the scenario's settlement vectors, ``s`` the magnitude, a
multiple of ``U``) grows from ``s = 0``. At every configuration the contact points are the
ends of the interfaces (the two ends of each joint's trace in the plane, carried by both of
its blocks); an end is *closed* when its two copies meet (the gap, measured along block A's
normal, is within ``gap_tol``) and *open* otherwise. On the closed ends, the Total
Complementary Energy of the rigid problem (the paper, eq. (11), ``D = 0``)::

    minimise    sum_j f_j . h_j                     (= -sum_s R_s . U_s)
    subject to  G' f + b = 0,   fn >= 0             (G: compatibility, b: self-weight)

and its dual, the kinematic problem of the blocks driven by the support velocity ``U``::

    maximise    b . v
    subject to  G_n v + h_n >= 0   (no interpenetration: the closed ends may open)
                G_t v + h_t  = 0   (no sliding at the closed ends)

are one linear program, solved with HiGHS (:func:`scipy.optimize.linprog`): its primal ``v``
is the mechanism (block velocities per unit magnitude, about the current centroids: blocks
rotating about the closed ends that stay closed), its duals the TCE force state ``f``. The
program is bounded exactly when an admissible force state exists on the current geometry
(weak and strong duality), infeasible when the motion cannot be accommodated without
interpenetration (``incompatible``), unbounded when nothing stands (collapse).

An increment ``ds`` moves every block rigidly by ``v ds`` (a rotation about its centroid and
a translation; the supports exactly by ``ds U``), then projects the configuration back onto
the contacts that stayed closed (one Gauss-Newton step on their relative displacements, so
that the hinges of a long path do not drift apart), reclassifies every end (a joint that
hinged has one closed end; a joint whose rotation reverses closes again; a new hinge forms
wherever the program lets a closed joint rotate, which is how hinges migrate to a
neighbouring joint as the geometry changes) and solves again. An increment after which the
program is unbounded is bisected (from the last standing configuration) until the bracket
is narrower than ``atol``: the settlement capacity is the largest magnitude found standing.

Outcomes (``status``): ``collapse`` (bracketed: no admissible state above ``capacity``),
``snap_through`` (the mechanism's speed per unit support motion exceeds ``snap_ratio``
times the supports' own: the structure jumps under a vanishing support motion, which a
quasi-static path cannot follow), ``contact_lost`` (no admissible state above ``capacity``
and an interface lost all of its contact points in the last increment: the structure came
apart), ``no_collapse`` (still standing at ``s_max``), ``infeasible`` (nothing stands at
``s = 0``), ``incompatible`` (the motion needs interpenetration at ``s = 0``),
``numerical`` (the solver failed, an equilibrium residual above tolerance, two blocks
interpenetrate, or more than :data:`MAX_STEPS` increments were needed). The ``message``
says which.

Sign conventions: in-plane coordinates ``(x, z)`` with ``x`` along the plane's horizontal
direction ``e`` (:attr:`tce.core.model.Plane.e`), rotations positive counter-clockwise
from ``e`` towards ``+z`` (the rotation vector ``-theta m``). Reactions are the wrench
``(Rx, Rz, M)`` that the support exerts on the structure (kN, kN m), the moment about the
support's current centroid.

References
----------
Ochsendorf J.A. (2002), *Collapse of masonry structures*, PhD thesis, University of Cambridge;
(2006) The masonry arch on spreading supports, *The Structural Engineer* 84(2), 27-34.
Coccia S., Di Carlo F., Rinaldi Z. (2015), Collapse displacements for a mechanism of spreading-
induced supports in a masonry arch, *International Journal of Advanced Structural Engineering* 7.
Livesley R.K. (1978), Limit analysis of structures formed from rigid blocks, *IJNME* 12.
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray
import scipy.sparse as sp

from ..core.material import Material
from ..core.model import EZ, Plane, find_plane, lateral_direction
from ..core.result import Result
from ..core.solve import check_settlements
from ..structures.assembly import Assembly, Block
from ..structures.geometry import Polyhedron

__all__ = ["MAX_STEPS", "SettlementPathResult", "check_path_scene", "settlement_path"]

#: Most increments (accepted or bisected) one path may take.
MAX_STEPS = 20_000

#: Most snaps (falls to a new standing configuration, :func:`_snap`) one path may take.
MAX_SNAPS = 100

_FEAS = 1e-9  # relative tolerance of the equilibrium residual and of "velocity is zero"


@dataclass(frozen=True)
class _Scene:
    """The planar reduction of an assembly: per block its weight, reference centroid and the
    in-plane coordinates of its interface ends; the support velocities per unit magnitude."""

    plane: Plane
    weights: NDArray[np.float64]  # (nb,)
    c0: NDArray[np.float64]  # (nb, 2) reference centroids (x, z)
    free: NDArray[np.int64]  # indices of the free blocks
    ia: NDArray[np.int64]  # (ni,) block A of each interface
    ib: NDArray[np.int64]
    ends: NDArray[np.float64]  # (ni, 2, 2) the two ends of each interface's trace (reference)
    normal: NDArray[np.float64]  # (ni, 2) reference normal, A -> B
    support: NDArray[np.int64]  # support block indices
    velocity: NDArray[np.float64]  # (ns, 3) (ux, uz, w) per unit magnitude about the centroid
    size: float

    def to2d(self, p: NDArray[np.float64]) -> NDArray[np.float64]:
        q = np.asarray(p, dtype=float) - self.plane.origin
        return np.stack([q @ self.plane.e, q @ EZ], axis=-1)


def _linprog(*args, **kwargs):
    """:func:`scipy.optimize.linprog`, imported on first use: with scipy.sparse.linalg and joblib,
    scipy.optimize cost every run 0.24 CPU-s to import (issue 24), with or without a settlement path."""
    from scipy.optimize import linprog

    return linprog(*args, **kwargs)


def _lsqr(*args, **kwargs):
    """:func:`scipy.sparse.linalg.lsqr`, imported on first use (as :func:`_linprog`)."""
    from scipy.sparse.linalg import lsqr

    return lsqr(*args, **kwargs)


def _rot(theta: NDArray[np.float64] | float) -> NDArray[np.float64]:
    c, s = np.cos(theta), np.sin(theta)
    return np.stack([np.stack([c, -s], -1), np.stack([s, c], -1)], -2)


def _perp(r: NDArray[np.float64]) -> NDArray[np.float64]:
    """``w x r`` for a unit counter-clockwise rotation: ``(-r_z, r_x)``."""
    return np.stack([-r[..., 1], r[..., 0]], axis=-1)


def _scene(assembly: Assembly, settlements: Mapping[str, ArrayLike]) -> _Scene:
    plane = find_plane(assembly)
    if plane is None:
        raise ValueError("settlement_path needs a planar assembly (a vertical symmetry plane, interfaces in it)")
    names = assembly.support_names
    sett = check_settlements(names, settlements)
    e, m = plane.e, plane.m
    vel = np.zeros((len(names), 3))
    for name, u in sett.items():
        u = np.asarray(u, dtype=float)
        out = abs(u[:3] @ m) + np.linalg.norm(u[3:] - (u[3:] @ m) * m)
        if out > 1e-12 * max(1.0, np.abs(u).max()):
            raise ValueError(f"settlements[{name!r}] leaves the assembly's plane: only in-plane motions are followed")
        vel[names.index(name)] = (u[:3] @ e, u[2], -(u[3:] @ m))
    t = assembly.interface_table
    to2d = lambda p: np.stack([(p - plane.origin) @ e, p[:, 2]], axis=-1)  # noqa: E731
    ends = np.zeros((len(t), 2, 2))
    normal = np.zeros((len(t), 2))
    for k in range(len(t)):
        p = to2d(t.points[t.start[k] : t.start[k + 1]])
        n = np.array([t.normal[k] @ e, t.normal[k][2]])
        s = p @ _perp(n)
        ends[k] = p[[np.argmin(s), np.argmax(s)]]
        normal[k] = n / np.linalg.norm(n)
    c = assembly.centroids
    return _Scene(
        plane=plane,
        weights=assembly.weights,
        c0=to2d(c),
        free=np.asarray(assembly.free_indices, dtype=np.int64),
        ia=t.a.astype(np.int64),
        ib=t.b.astype(np.int64),
        ends=ends,
        normal=normal,
        support=np.asarray(assembly.support_indices, dtype=np.int64),
        velocity=vel,
        size=float(assembly.size),
    )


@dataclass(frozen=True)
class _Config:
    """Placement of every block: centroid ``c`` (nb, 2) and rotation ``theta`` (nb,) from the
    reference, at magnitude ``s``."""

    s: float
    c: NDArray[np.float64]
    theta: NDArray[np.float64]

    def place(self, idx: NDArray[np.int64], p: NDArray[np.float64], sc: _Scene) -> NDArray[np.float64]:
        """Current position of reference points ``p`` (..., 2) carried by blocks ``idx``."""
        r = np.einsum("...ij,...j->...i", _rot(self.theta[idx]), p - sc.c0[idx])
        return self.c[idx] + r


def _contacts(sc: _Scene, cf: _Config) -> tuple[NDArray, NDArray, NDArray]:
    """Per interface end: current point (ni, 2, 2), A's normal (ni, 2) and gap (ni, 2),
    the gap being B's copy minus A's copy along A's normal (m; > 0 open)."""
    pa = cf.place(sc.ia[:, None].repeat(2, 1), sc.ends, sc)
    pb = cf.place(sc.ib[:, None].repeat(2, 1), sc.ends, sc)
    n = np.einsum("kij,kj->ki", _rot(cf.theta[sc.ia]), sc.normal)
    gap = np.einsum("kej,kj->ke", pb - pa, n)
    return 0.5 * (pa + pb), n, gap


@dataclass(frozen=True)
class _Step:
    """One linear program on one configuration and its closed ends."""

    status: str  # optimal / unbounded / infeasible / numerical
    v: NDArray[np.float64] | None = None  # (nb, 3) block velocities (supports included)
    fn: NDArray[np.float64] | None = None  # (ni, 2) normal forces at the ends (0 where open)
    ft: NDArray[np.float64] | None = None
    reactions: NDArray[np.float64] | None = None  # (ns, 3)
    dn: NDArray[np.float64] | None = None  # (ni, 2) opening velocity at the ends
    message: str = ""


def _operators(sc: _Scene, cf: _Config, closed: NDArray[np.bool_]):
    """Compatibility rows of the closed ends: ``(Gn, Gt, hn, ht, kj, p, n)`` with ``G``
    (sparse, one row per closed end) over the free blocks' ``(vx, vz, w)``, ``h`` the
    supports' part, ``kj`` the (interface, end) pairs, ``p`` and ``n`` the contacts."""
    p, n, _ = _contacts(sc, cf)
    kk, ee = np.nonzero(closed)
    nf = len(sc.free)
    col = np.full(len(sc.weights), -1)
    col[sc.free] = np.arange(nf)
    vsup = np.zeros((len(sc.weights), 3))
    vsup[sc.support] = sc.velocity
    pt = p[kk, ee]
    rows = np.arange(len(kk))
    out = []
    for d in (n[kk], _perp(n[kk])):
        G = sp.csr_matrix((len(kk), 3 * nf))
        h = np.zeros(len(kk))
        for blk, sign in ((sc.ib[kk], 1.0), (sc.ia[kk], -1.0)):
            # velocity of the point on block blk per unit (vx, vz, w): (1, 0), (0, 1), w x r
            r = pt - cf.c[blk]
            coef = sign * np.column_stack([d[:, 0], d[:, 1], r[:, 0] * d[:, 1] - r[:, 1] * d[:, 0]])
            free = col[blk] >= 0
            cols = 3 * col[blk][free, None] + np.arange(3)
            G = G + sp.csr_matrix(
                (coef[free].ravel(), (np.repeat(rows[free], 3), cols.ravel())), shape=(len(kk), 3 * nf)
            )
            h[~free] += np.einsum("ij,ij->i", coef[~free], vsup[blk[~free]])
        out += [G, h]
    Gn, hn, Gt, ht = out
    return Gn, Gt, hn, ht, (kk, ee), p, n


def _solve(sc: _Scene, cf: _Config, closed: NDArray[np.bool_]) -> _Step:
    """The TCE and its kinematic dual on the closed ends of configuration ``cf`` (module
    docstring); the equilibrium of the duals is checked."""
    Gn, Gt, hn, ht, (kk, ee), p, n = _operators(sc, cf, closed)
    nf = len(sc.free)
    w = sc.weights / sc.weights[sc.free].sum()  # scaled: forces in units of the free weight
    b = np.zeros(3 * nf)
    b[1::3] = -w[sc.free]
    res = _linprog(-b, A_ub=-Gn, b_ub=hn, A_eq=Gt, b_eq=-ht, bounds=(None, None), method="highs")
    if res.status == 2:
        return _Step("infeasible", message="the support motion needs interpenetration: " + res.message)
    if res.status == 3:
        return _Step("unbounded", message="a mechanism lowers the weights with the supports held: " + res.message)
    if res.status != 0:
        return _Step("numerical", message="HiGHS: " + res.message)
    fn_ = -np.asarray(res.ineqlin.marginals)
    ft_ = np.asarray(res.eqlin.marginals)
    resid = Gn.T @ fn_ + Gt.T @ ft_ + b
    if np.abs(resid).max(initial=0.0) > 1e3 * _FEAS or fn_.min(initial=0.0) < -1e3 * _FEAS:
        return _Step("numerical", message=f"equilibrium residual {np.abs(resid).max():.2e} of the dual state")
    v = np.zeros((len(sc.weights), 3))
    v[sc.free] = res.x.reshape(-1, 3)
    v[sc.support] = sc.velocity
    total = sc.weights[sc.free].sum()
    fn = np.zeros(closed.shape)
    ft = np.zeros(closed.shape)
    fn[kk, ee] = fn_ * total
    ft[kk, ee] = ft_ * total
    dn = np.zeros(closed.shape)
    dn[kk, ee] = Gn @ res.x + hn
    # reactions: the force +f acts on B, -f on A; keep the supports' side, as exerted on the structure
    reac = np.zeros((len(sc.support), 3))
    pos = {int(s): i for i, s in enumerate(sc.support)}
    tang = _perp(n)
    for k, end in zip(kk, ee):
        f = fn[k, end] * n[k] + ft[k, end] * tang[k]
        for blk, sign in ((sc.ia[k], 1.0), (sc.ib[k], -1.0)):
            if int(blk) in pos:  # the structure's block is the other one: it receives sign * f
                r = p[k, end] - cf.c[blk]
                reac[pos[int(blk)]] += sign * np.array([f[0], f[1], r[0] * f[1] - r[1] * f[0]])
    return _Step("optimal", v=v, fn=fn, ft=ft, reactions=reac, dn=dn)


def _limit(sc: _Scene, cf: _Config, closed: NDArray[np.bool_], direction: float) -> tuple[str, float]:
    """lambda_max of the lateral pattern (weights times ``direction`` = +-1 along ``e``) on the
    closed ends of ``cf``: ``max lam  s.t.  G' f + b + lam b_lat = 0, fn >= 0`` (no sliding)."""
    Gn, Gt, *_ = _operators(sc, cf, closed)
    nf = len(sc.free)
    w = sc.weights[sc.free] / sc.weights[sc.free].sum()
    b = np.zeros(3 * nf)
    b[1::3] = -w
    blat = np.zeros(3 * nf)
    blat[0::3] = direction * w
    nn, nt = Gn.shape[0], Gt.shape[0]
    A = sp.hstack([Gn.T, Gt.T, sp.csr_matrix(blat[:, None])])
    c = np.zeros(nn + nt + 1)
    c[-1] = -1.0
    bounds = [(0, None)] * nn + [(None, None)] * nt + [(None, None)]
    res = _linprog(c, A_eq=A, b_eq=-b, bounds=bounds, method="highs")
    if res.status == 0:
        return "optimal", float(res.x[-1])
    return {2: "infeasible", 3: "unbounded"}.get(res.status, "numerical"), float("nan")


def _move(sc: _Scene, cf: _Config, v: NDArray[np.float64], ds: float, advance: bool = True) -> _Config:
    """Every free block moved rigidly by ``v ds``; the supports to their exact place at
    ``s + ds`` (at ``s`` when not ``advance``: a motion with the supports held)."""
    c = cf.c + ds * v[:, :2]
    theta = cf.theta + ds * v[:, 2]
    s = cf.s + ds if advance else cf.s
    c[sc.support] = sc.c0[sc.support] + s * sc.velocity[:, :2]
    theta[sc.support] = s * sc.velocity[:, 2]
    return _Config(s, c, theta)


def _project(sc: _Scene, cf: _Config, keep: NDArray[np.bool_]) -> _Config:
    """One Gauss-Newton step that closes the relative displacement (both components) of the
    ends ``keep`` by the least change of the free blocks' placements."""
    if not keep.any():
        return cf
    Gn, Gt, *_ = _operators(sc, cf, keep)
    pa = cf.place(sc.ia[:, None].repeat(2, 1), sc.ends, sc)
    pb = cf.place(sc.ib[:, None].repeat(2, 1), sc.ends, sc)
    _, n, _ = _contacts(sc, cf)
    kk, ee = np.nonzero(keep)
    d = pb[kk, ee] - pa[kk, ee]
    mis = np.concatenate([np.einsum("ij,ij->i", d, n[kk]), np.einsum("ij,ij->i", d, _perp(n[kk]))])
    J = sp.vstack([Gn, Gt]).tocsr()
    dq = _lsqr(J, -mis, atol=1e-15, btol=1e-15, iter_lim=100 * J.shape[1])[0].reshape(-1, 3)  # least norm
    c = cf.c.copy()
    theta = cf.theta.copy()
    c[sc.free] += dq[:, :2]
    theta[sc.free] += dq[:, 2]
    return _Config(cf.s, c, theta)


def _snap(
    sc: _Scene, cf: _Config, closed: NDArray[np.bool_], gtol: float, limit: float
) -> tuple[_Config, NDArray[np.bool_], _Step] | None:
    """Follow the structure's fall with the supports held from a configuration where nothing
    stands, until an open end closes and the structure stands again.

    At each sub-step the direction is the kinematic program's steepest descent of the
    weights with the supports held (block speeds bounded by 1, rotations times the size by
    1); the blocks move along it until the first open end closes (the closing end is then
    shut exactly by the projection) or by at most 1 % of the size. The fall is taken as
    quasi-static with perfectly inelastic impacts: the energy released is dissipated when
    the joint closes. Returns the standing configuration, its closed ends and its program,
    or None when no end closes before some block has turned by ``limit`` rad or moved by
    ``limit`` times the size (a collapse), or the program fails.
    """
    nf = len(sc.free)
    w = sc.weights[sc.free] / sc.weights[sc.free].sum()
    b = np.zeros(3 * nf)
    b[1::3] = -w
    bounds = [(-1.0, 1.0), (-1.0, 1.0), (-1.0 / sc.size, 1.0 / sc.size)] * nf
    start = cf
    everything = np.ones(closed.shape, dtype=bool)
    for _ in range(2000):
        Gn, Gt, *_ = _operators(sc, cf, closed)
        res = _linprog(-b, A_ub=-Gn, b_ub=np.zeros(Gn.shape[0]), A_eq=Gt, b_eq=np.zeros(Gt.shape[0]), bounds=bounds, method="highs")
        if res.status != 0 or -res.fun <= _FEAS:
            return None
        d = np.zeros((len(sc.weights), 3))
        d[sc.free] = res.x.reshape(-1, 3)
        GnA, *_ = _operators(sc, cf, everything)
        rate = (GnA @ res.x).reshape(closed.shape)  # opening rate of every end along d
        _, _, gap = _contacts(sc, cf)
        closing = ~closed & (rate < -_FEAS)
        t_close = float((gap[closing] / -rate[closing]).min()) if closing.any() else math.inf
        t = min(t_close, 0.01 * sc.size)
        new = _move(sc, cf, d, t, advance=False)
        keep = closed & (np.abs(rate) <= _FEAS * 1e3)
        if t == t_close:
            keep |= closing & (gap / np.maximum(-rate, 1e-300) <= t_close * (1 + 1e-9))
        new = _project(sc, new, keep)
        moved = np.abs(new.c - start.c).max() / sc.size
        turned = np.abs(new.theta - start.theta).max()
        if max(moved, turned) > limit:
            return None
        _, _, gap = _contacts(sc, new)
        now = gap <= gtol
        if t == t_close:
            step = _solve(sc, new, now)
            if step.status == "optimal":
                return new, now, step
            if step.status != "unbounded":
                return None
        cf, closed = new, now
    return None


def _checked(
    assembly: Assembly, material: Material | None, settlements: Mapping[str, ArrayLike], alpha: float | None
) -> tuple[_Scene, float]:
    """The planar scene of a path and the lateral direction along ``e`` (+-1; 0 without
    ``alpha``), checked (:func:`check_path_scene`)."""
    material = material or Material()
    if material != Material(flow=material.flow):
        raise ValueError(
            "settlement_path follows rigid blocks of a Heyman material (no friction limit, cohesion, "
            "strengths or stiffness): sliding and crushing are not followed"
        )
    sc = _scene(assembly.validate(), settlements)
    if alpha is None:
        return sc, 0.0
    direction = float(lateral_direction(alpha) @ sc.plane.e)
    if abs(abs(direction) - 1.0) > 1e-12:
        raise ValueError(f"alpha = {alpha} leaves the assembly's plane: lambda_max is followed in plane only")
    return sc, direction


def check_path_scene(
    assembly: Assembly, material: Material | None, settlements: Mapping[str, ArrayLike], alpha: float | None = None
) -> None:
    """Whether :func:`settlement_path` can follow this scene.

    Raises
    ------
    ValueError
        A material other than the rigid Heyman one, an assembly that is not planar, a
        motion out of its plane or of an unknown support, or (``alpha`` given) a lateral
        direction out of the plane.
    """
    _checked(assembly, material, settlements, alpha)


@dataclass(frozen=True, eq=False, kw_only=True)
class SettlementPathResult(Result):
    """A finite-settlement path (``ok`` when ``status`` is ``collapse``, ``snap_through`` or
    ``contact_lost``: a capacity was bracketed).

    Attributes
    ----------
    status : str
        How the path ended (module docstring); ``message`` says what decided it.
    settlements : dict
        The scenario's settlement vectors ``{support: [ux, uy, uz, rx, ry, rz]}`` (m, rad):
        the motion at magnitude ``s`` is ``s`` times these.
    capacity : float
        Settlement capacity: the largest magnitude found standing (multiples of the
        settlement vectors; NaN unless ``ok``).
    upper : float
        Smallest magnitude found not standing (NaN if none).
    magnitudes : (k,) ndarray
        Magnitude of every standing configuration of the path, increasing.
    reactions : (k, n_supports, 3) ndarray
        ``(Rx, Rz, M)`` of each support on the structure (kN, kN m) at each magnitude:
        ``Rx`` along the plane's horizontal direction, ``M`` counter-clockwise about the
        support's current centroid.
    lambda_max : (k,) ndarray
        lambda_max of the lateral pattern (``alpha``) on the deformed structure (NaN when
        not asked for).
    placements : (k, n_blocks, 3) ndarray
        ``(dx, dz, theta)`` of every block from its reference placement (m, rad).
    hinges : list of list of int
        Per magnitude, the interfaces that rotate in the mechanism (hinges).
    hinge_points : (k, n_interfaces, 3) ndarray
        Per magnitude, the current position of each hinge (the closed end of a rotating
        interface that opens least; m, global frame), NaN for the other interfaces.
    open_ends : (k, n_interfaces, 2) bool ndarray
        Which ends of each interface are open, per magnitude.
    hinge_sequence : list of tuple
        ``(magnitude, interface, event)``: ``event`` is ``"hinge"`` when an interface starts
        rotating, ``"closed"`` when an open joint closes again along the path, ``"snap"``
        when it closes at the end of a fall (:attr:`snaps`).
    plane : Plane
        The assembly's plane (for drawing in 3D).
    snaps : list of float
        Magnitudes at which nothing stood and the structure fell, with the supports held,
        to a new standing configuration (a joint closed: a hinge migrated); each appears
        twice in ``magnitudes``, before and after the fall.
    n_solves : int
    """

    OK = ("collapse", "snap_through", "contact_lost")

    settlements: dict
    capacity: float
    upper: float
    magnitudes: NDArray[np.float64] = field(repr=False)
    reactions: NDArray[np.float64] = field(repr=False)
    lambda_max: NDArray[np.float64] = field(repr=False)
    placements: NDArray[np.float64] = field(repr=False)
    hinges: list = field(repr=False)
    hinge_points: NDArray[np.float64] = field(repr=False)
    open_ends: NDArray[np.bool_] = field(repr=False)
    hinge_sequence: list = field(repr=False)
    plane: Plane = field(repr=False)
    snaps: list = field(default_factory=list)
    n_solves: int = 0

    def deformed(self, assembly: Assembly, index: int = -1) -> Assembly:
        """``assembly`` with its blocks at the placement of step ``index`` (the interfaces as
        in the reference: for drawing)."""
        e, m = self.plane.e, self.plane.m
        blocks = []
        for k, blk in enumerate(assembly.blocks):
            dx, dz, th = self.placements[index, k]
            c = blk.shape.centroid
            v = blk.shape.vertices - c
            ve, vz = v @ e, v[:, 2]
            cs, sn = math.cos(th), math.sin(th)
            rest = v - np.outer(ve, e) - np.outer(vz, EZ)
            ne, nz = cs * ve - sn * vz, sn * ve + cs * vz
            pts = c + rest + np.outer(ne + dx, e) + np.outer(nz + dz, EZ)
            blocks.append(Block(blk.name, Polyhedron(pts, blk.shape.faces), blk.unit_weight, blk.support))
        return Assembly(tuple(blocks), assembly.interfaces, dict(assembly.meta))


def settlement_path(
    assembly: Assembly,
    settlements: Mapping[str, ArrayLike],
    material: Material | None = None,
    increment: float = 1e-3,
    s_max: float = 1.0,
    atol: float | None = None,
    lam: bool = False,
    alpha: float = 0.0,
    gap_tol: float = 1e-7,
    snap_ratio: float = 1e3,
    snap_limit: float = 0.3,
) -> SettlementPathResult:
    """Follow the support motion ``s * settlements`` from ``s = 0`` until nothing stands.

    Parameters
    ----------
    assembly : Assembly
        A planar assembly (module docstring).
    settlements : dict
        ``{support: [ux, uy, uz, rx, ry, rz]}`` (m, rad) about each support's centroid, in
        the assembly's plane: the motion of unit magnitude.
    material : Material, optional
        Must be the rigid Heyman material (the default): no friction limit, cohesion,
        strengths or stiffness (sliding and crushing are not followed).
    increment : float
        Magnitude step (> 0).
    s_max : float
        Largest magnitude followed (``no_collapse`` beyond); ``s_max / increment`` at most
        :data:`MAX_STEPS`.
    atol : float, optional
        Width of the final bracket on the magnitude; default ``increment / 64``.
    lam : bool
        Also lambda_max of the lateral pattern in direction ``alpha`` (0 or 180 degrees: in
        the plane) on the deformed structure at every standing magnitude.
    gap_tol : float
        An interface end is closed when its gap is below ``gap_tol`` times the assembly's size.
    snap_ratio : float
        Largest ratio of the mechanism's speed to the supports' before ``snap_through``.
    snap_limit : float
        Where nothing stands, the structure's fall with the supports held is followed until
        an open joint closes (a snap, after which the path goes on); a fall in which some
        block turns by more than ``snap_limit`` rad, or moves by more than ``snap_limit``
        times the assembly's size, before any joint closes is a collapse.

    Returns
    -------
    SettlementPathResult
    """
    t0 = time.perf_counter()
    if not (math.isfinite(increment) and increment > 0):
        raise ValueError(f"increment must be a finite number > 0, got {increment!r}")
    if not (math.isfinite(s_max) and s_max > 0 and s_max / increment <= MAX_STEPS):
        raise ValueError(f"s_max must be > 0 with s_max / increment <= {MAX_STEPS}, got {s_max!r}")
    atol = increment / 64 if atol is None else float(atol)
    if not (math.isfinite(atol) and atol > 0):
        raise ValueError(f"atol must be a finite number > 0, got {atol!r}")
    sc, direction = _checked(assembly, material, settlements, alpha if lam else None)
    gtol = gap_tol * sc.size
    sett = {k: list(np.asarray(v, dtype=float)) for k, v in settlements.items()}
    n_solves = 0

    def solve(cf: _Config, closed: NDArray[np.bool_]) -> _Step:
        nonlocal n_solves
        n_solves += 1
        return _solve(sc, cf, closed)

    nb = len(sc.weights)
    cf = _Config(0.0, sc.c0.copy(), np.zeros(nb))
    closed = np.ones(sc.ends.shape[:2], dtype=bool)
    step = solve(cf, closed)
    vref = np.abs(sc.velocity).max() * max(1.0, sc.size)
    records: list[tuple[_Config, NDArray, _Step]] = []
    sequence: list[tuple[float, int, str]] = []

    def record(cf: _Config, closed: NDArray, st: _Step) -> None:
        records.append((cf, closed.copy(), st))

    status, message, upper = "", "", float("nan")
    if step.status == "unbounded":
        status, message = "infeasible", "nothing stands at s = 0: " + step.message
    elif step.status == "infeasible":
        status, message = "incompatible", step.message
    elif step.status != "optimal":
        status, message = "numerical", step.message
    else:
        record(cf, closed, step)
    rotating_prev: set[int] = set()

    def rotating(st: _Step) -> set[int]:
        assert st.v is not None
        dw = np.abs(st.v[sc.ib, 2] - st.v[sc.ia, 2])
        return set(np.flatnonzero(dw * sc.size > 1e-7 * vref).tolist())

    ds = increment
    n_steps = 0
    lost_at_upper, upper_msg = False, ""
    upper_state: tuple[_Config, NDArray[np.bool_]] = (cf, closed)
    snaps: list[float] = []
    while not status:
        cf, closed, step = records[-1]
        assert step.v is not None and step.dn is not None
        rot = rotating(step)
        for k in sorted(rot - rotating_prev):
            sequence.append((cf.s, k, "hinge"))
        rotating_prev = rot
        speed = np.abs(step.v[sc.free]).max() * max(1.0, sc.size)
        if speed > snap_ratio * vref:
            status = "snap_through"
            message = f"the mechanism moves {speed / vref:.3g} times faster than the supports at s = {cf.s:.6g}"
            upper = cf.s
            break
        if cf.s >= s_max:
            status, message = "no_collapse", f"still standing at s_max = {s_max}"
            break
        n_steps += 1
        if n_steps > MAX_STEPS:
            status, message = "numerical", f"more than {MAX_STEPS} increments"
            break
        h = min(ds, s_max - cf.s)
        trial = _move(sc, cf, step.v, h)
        stays = closed & (step.dn <= _FEAS * vref * 1e3)
        trial = _project(sc, trial, stays)
        _, _, gap = _contacts(sc, trial)
        if gap.min() < -10 * gtol:
            # an open end closed within the increment (or the projection failed): shorter step
            if h > atol:
                ds = h / 2
                continue
            status, message = "numerical", f"interpenetration {-gap.min():.3g} m at s = {trial.s:.6g} with the shortest step"
            break
        now = gap <= gtol
        lost = [k for k in range(len(now)) if not now[k].any()]
        new = solve(trial, now)
        if new.status == "optimal":
            for k in np.flatnonzero((now & ~closed).any(axis=1)):
                sequence.append((trial.s, int(k), "closed"))
            record(trial, now, new)
            if upper == upper and trial.s >= upper:
                upper = float("nan")  # reached in shorter steps: the larger one overshot the path
            if ds < increment and upper != upper:  # after an event: back to the full increment
                ds = increment
            if not (upper == upper and upper - trial.s <= atol):
                continue
        elif new.status == "unbounded":
            upper, upper_state = trial.s, (trial, now)
            lost_at_upper = bool(lost)
            upper_msg = new.message + (f"; interfaces {lost} lost every contact" if lost else "")
            if upper - cf.s > atol:
                ds = h / 2
                continue
        else:
            status = "numerical" if new.status == "numerical" else "incompatible"
            message = f"at s = {trial.s:.6g}: {new.message}"
            break
        # bracketed: nothing stands at `upper`; does the structure come to rest after a snap?
        fallen = _snap(sc, *upper_state, gtol, snap_limit) if len(snaps) < MAX_SNAPS else None
        if fallen is None:
            status = "contact_lost" if lost_at_upper else "collapse"
            message = f"no admissible state at s = {upper:.6g}: {upper_msg}"
            break
        before = upper_state[1]
        for k in np.flatnonzero((fallen[1] & ~before).any(axis=1)):
            sequence.append((fallen[0].s, int(k), "snap"))
        snaps.append(fallen[0].s)
        record(*fallen)
        upper, ds = float("nan"), increment

    ok = status in SettlementPathResult.OK
    k = len(records)
    lam_max = np.full(k, np.nan)
    if lam:
        for i, (c, cl, _) in enumerate(records):
            st, val = _limit(sc, c, cl, direction)
            n_solves += 1
            lam_max[i] = val if st == "optimal" else np.nan
    placements = np.zeros((k, nb, 3))
    hinge_points = np.full((k, len(sc.ia), 3), np.nan)
    plane = sc.plane
    for i, (c, cl, st) in enumerate(records):
        placements[i, :, :2] = c.c - sc.c0
        placements[i, :, 2] = c.theta
        # the hinge of a rotating interface: its closed end that opens least
        p, _, _ = _contacts(sc, c)
        rot = sorted(rotating(st))
        assert st.dn is not None
        end = np.argmin(np.where(cl[rot], st.dn[rot], np.inf), axis=1)
        xz = p[rot, end]
        hinge_points[i, rot] = plane.origin + np.outer(xz[:, 0], plane.e) + np.outer(xz[:, 1] - plane.origin[2], EZ)
    return SettlementPathResult(
        status=status,
        message=message,
        solver="HiGHS (scipy.optimize.linprog)",
        settlements=sett,
        capacity=float(records[-1][0].s) if ok else float("nan"),
        upper=float(upper),
        magnitudes=np.array([c.s for c, _, _ in records]),
        reactions=np.array([st.reactions for _, _, st in records]).reshape(k, len(sc.support), 3),
        lambda_max=lam_max,
        placements=placements,
        hinges=[sorted(rotating(st)) for _, _, st in records],
        hinge_points=hinge_points,
        open_ends=np.array([~cl for _, cl, _ in records]).reshape(k, *sc.ends.shape[:2]),
        hinge_sequence=sequence,
        plane=sc.plane,
        snaps=snaps,
        n_solves=n_solves,
        wall_time=time.perf_counter() - t0,
    )
