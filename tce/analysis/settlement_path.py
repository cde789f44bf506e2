"""Finite settlements: a support motion followed in increments, the geometry updated as it moves.

For rigid blocks of a Heyman material (no tension, no sliding, unlimited compressive
strength), the support motion ``s * U`` (``U`` the scenario's settlement vectors, ``s`` the
magnitude) grows from ``s = 0``. A planar assembly (:func:`tce.core.model.find_plane`) is
followed in its plane, with three dofs per block; any other in space, with six
(:class:`_Planar` and :class:`_Spatial` hold the only differences). At every configuration
the contact points are those of the interfaces, carried by both of their blocks: in the
plane the two ends of each joint's trace, in space the vertices of its polygon. A point is
*closed* when its two copies meet (the gap, measured along block A's normal, is within
``gap_tol``) and *open* otherwise. On the closed points, the Total Complementary Energy of
the rigid problem (the paper, eq. (11), ``D = 0``)::

    minimise    sum_j f_j . h_j                     (= -sum_s R_s . U_s)
    subject to  G' f + b = 0,   fn >= 0             (G: compatibility, b: self-weight, dead loads)

and its dual, the kinematic problem of the blocks driven by the support velocity ``U``::

    maximise    b . v
    subject to  G_n v + h_n >= 0   (no interpenetration: the closed ends may open)
                G_t v + h_t  = 0   (no sliding at the closed ends: every tangent)

are one linear program, solved with HiGHS (:func:`scipy.optimize.linprog`): its primal ``v``
is the mechanism (block velocities per unit magnitude, about the current centroids: blocks
rotating about the closed ends that stay closed), its duals the TCE force state ``f``. The
program is bounded exactly when an admissible force state exists on the current geometry
(weak and strong duality), infeasible when the motion cannot be accommodated without
interpenetration (``incompatible``), unbounded when nothing stands (collapse).

An increment ``ds`` moves every block rigidly by ``v ds`` (a rotation about its centroid
and a translation; the supports exactly to ``(s + ds) U``), projects the configuration back
onto the contacts that stayed closed (one Gauss-Newton step on their relative
displacements, its least-norm solution on one sparse factorisation, so that the hinges of a
long path do not drift apart), reclassifies every contact point (hinges open, close again
or migrate to a neighbouring joint as the geometry changes) and solves again. An increment after which the program is unbounded is bisected
(from the last standing configuration) until the bracket is narrower than ``atol``: the
settlement capacity is the largest magnitude found standing.

With ``lam``, lambda_max of the lateral pattern on each standing configuration lets every
contact point whose gap is within ``contact_gap`` (m) carry compression (a gap closed by a
motion that limit analysis neglects; ``contact_gap = 0``: only the closed points, the
structure as it stands; ``docs/settlements.md``). It is withheld (NaN, and the ``message``
says where) on a configuration where it needs tangential forces above :data:`SHEAR_CAP` times
the load (:func:`_limit`): the no-sliding model's unbounded tangential forces then carry
the load through a near self-stress that grows as the inverse of the geometry's change, a
spurious strength (a spread dome's lunes, whose meridian joints are no longer parallel, lock
by no sliding alone the mechanism of the undeformed dome).

Outcomes (``status``): ``collapse`` (bracketed: no admissible state above ``capacity``),
``snap_through`` (the mechanism's speed per unit support motion exceeds ``snap_ratio``
times the supports' own: the structure jumps under a vanishing support motion, which a
quasi-static path cannot follow), ``contact_lost`` (no admissible state above ``capacity``
and an interface lost all of its contact points in the last increment: the structure came
apart), ``no_collapse`` (still standing at ``s_max``), ``infeasible`` (nothing stands at
``s = 0``), ``incompatible`` (the motion needs interpenetration at ``s = 0``),
``numerical`` (HiGHS failed, also while following the fall beyond a bracket: whether the
structure comes to rest is then undecided; an equilibrium residual above tolerance, two blocks
interpenetrate, or more than :data:`MAX_STEPS` increments were needed). The ``message``
says which.

Sign conventions: in the plane, coordinates ``(x, z)`` with ``x`` along the plane's
horizontal direction ``e`` (:attr:`tce.core.model.Plane.e`), rotations positive
counter-clockwise from ``e`` towards ``+z`` (the rotation vector ``-theta m``); reactions are
the wrench ``(Rx, Rz, M)`` that the support exerts on the structure (kN, kN m), the moment
about the support's current centroid. In space, global ``(x, y, z)``, rotation vectors
(rad) and wrenches ``(Fx, Fy, Fz, Mx, My, Mz)``. A support's motion at magnitude ``s`` is the
translation ``s (ux, uy, uz)`` and the rotation by the vector ``s (rx, ry, rz)`` about its
centroid.

References
----------
Ochsendorf J.A. (2002), *Collapse of masonry structures*, PhD thesis, University of Cambridge;
(2006) The masonry arch on spreading supports, *The Structural Engineer* 84(2), 27-34.
Coccia S., Di Carlo F., Rinaldi Z. (2015), Collapse displacements for a mechanism of spreading-
induced supports in a masonry arch, *International Journal of Advanced Structural Engineering* 7.
Zessin J., Lau W., Ochsendorf J. (2010), Equilibrium of cracked masonry domes, *Proceedings of
the ICE - Engineering and Computational Mechanics* 163(3), 135 ff.
Livesley R.K. (1978), Limit analysis of structures formed from rigid blocks, *IJNME* 12.
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray
import scipy.sparse as sp

from ..core.loads import AppliedLoads
from ..core.material import Material
from ..core.model import EZ, Plane, find_plane
from ..core.result import Result
from ..core.solve import check_settlements
from ..structures.assembly import Assembly, Block
from ..structures.geometry import Polyhedron, lateral_direction

if TYPE_CHECKING:
    from scipy.optimize import OptimizeResult

__all__ = ["CONTACT_GAP", "MAX_STEPS", "SHEAR_CAP", "SettlementPathResult", "check_path_scene", "settlement_path"]

#: Most increments (accepted or bisected) one path may take.
MAX_STEPS = 20_000

#: Most snaps (falls to a new standing configuration, :func:`_snap`) one path may take.
MAX_SNAPS = 100

#: Default ``contact_gap``, relative to the assembly's size (its bounding box's diagonal): an
#: open contact point whose gap is at most ``contact_gap`` still carries compression in the
#: settled structure's lateral capacity and in the live loads after a settlement
#: (:mod:`tce.study.settlement`; ``docs/settlements.md``).
CONTACT_GAP = 1e-3

_FEAS = 1e-9  # relative tolerance of the equilibrium residual and of "velocity is zero"

#: Regularisation of the projection's normal equations (:func:`_project`), relative to their
#: largest diagonal entry, and its number of iterates: a direction of the misfit whose squared
#: singular value is 1e-8 of the largest keeps 1e-8 of its error.
_TIKHONOV = 1e-10
_REFINE = 4

#: Largest tangential force at one contact point, in multiples of the load (the free blocks'
#: weight and the fixed forces' magnitudes), that the lateral capacity of a settled structure
#: may use (:func:`_limit`); a capacity that needs more is withheld (a structure whose lateral
#: load alone needs more, lambda_max of tens, would be withheld too). The undeformed dome of
#: ``studies/dome_spreading.toml`` reaches its 1.718 within 0.3 times its weight; 1 cm of
#: spread later its program climbs with the bound (1.740 at 1, 1.849 at 10, 2.130 from 100
#: times the weight): a strength bought with forces that no friction provides.
SHEAR_CAP = 10.0

#: status word (``docs/conventions.md``) of each :func:`scipy.optimize.linprog` status; any
#: other (1 iteration limit, 4 numerical difficulties) is ``numerical``
_LP_STATUS = {0: "optimal", 2: "infeasible", 3: "unbounded"}


def _linprog(c: NDArray[np.float64], **kwargs: object) -> tuple[str, OptimizeResult]:
    """``min c . x`` by HiGHS (:func:`scipy.optimize.linprog`, ``kwargs`` its constraints and
    bounds), and the status word of the answer.

    A program that HiGHS fails to solve is solved again without its presolve; the answer is
    ``numerical`` only when that fails too. Near a collapse HiGHS's presolve ends some programs
    in "Solve error" that its simplex, given the program as it is, proves unbounded.
    """
    from scipy.optimize import linprog  # imported on first use: it is slow to import

    res = linprog(c, method="highs", **kwargs)
    if res.status not in _LP_STATUS:
        res = linprog(c, method="highs", options={"presolve": False}, **kwargs)
    return _LP_STATUS.get(res.status, "numerical"), res


@dataclass(frozen=True)
class _Planar:
    """Kinematics in a vertical plane: coordinates ``(x, z)`` (``x`` along ``plane.e``), one
    rotation ``w`` counter-clockwise from ``e`` towards ``+z`` (the rotation vector ``-w m``)."""

    plane: Plane
    dim = 2
    nrot = 1

    @staticmethod
    def moment(r: NDArray[np.float64], d: NDArray[np.float64]) -> NDArray[np.float64]:
        """Velocity along ``d`` of the point at ``r`` from the centroid per unit rotation
        (``(w x r) . d``), which is also the moment of a force ``d`` at ``r``: ``(n, 1)``."""
        return (r[:, 0] * d[:, 1] - r[:, 1] * d[:, 0])[:, None]

    @staticmethod
    def rotation(w: NDArray[np.float64]) -> NDArray[np.float64]:
        c, s = np.cos(w[..., 0]), np.sin(w[..., 0])
        return np.stack([np.stack([c, -s], -1), np.stack([s, c], -1)], -2)

    @staticmethod
    def angles(R: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.arctan2(R[..., 1, 0], R[..., 0, 0])[..., None]

    @staticmethod
    def tangents(n: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.stack([-n[:, 1], n[:, 0]], axis=-1)[:, None, :]

    def to_global(self, p: NDArray[np.float64]) -> NDArray[np.float64]:
        """Global points ``(..., 3)`` of in-plane points ``(..., 2)``."""
        o = self.plane.origin
        return o + p[..., :1] * self.plane.e + (p[..., 1:2] - o[2]) * EZ

    def reduce(self, u: NDArray[np.float64], name: str) -> NDArray[np.float64]:
        """In-plane ``(ux, uz, w)`` of a support motion ``(ux, uy, uz, rx, ry, rz)``."""
        e, m = self.plane.e, self.plane.m
        out = abs(u[:3] @ m) + np.linalg.norm(u[3:] - (u[3:] @ m) * m)
        if out > 1e-12 * max(1.0, np.abs(u).max()):
            raise ValueError(f"settlements[{name!r}] leaves the assembly's plane: only in-plane motions are followed")
        return np.array([u[:3] @ e, u[2], -(u[3:] @ m)])

    def lift(self, q: NDArray[np.float64]) -> NDArray[np.float64]:
        """Global 6-vectors ``(x, y, z, rx, ry, rz)`` of in-plane ``(x, z, w)`` (forces and
        moments, or displacements and rotations)."""
        e, m = self.plane.e, self.plane.m
        return np.concatenate([q[..., :1] * e + q[..., 1:2] * EZ, -q[..., 2:3] * m], axis=-1)


@dataclass(frozen=True)
class _Spatial:
    """Kinematics in space: coordinates ``(x, y, z)``, rotation vectors ``(rx, ry, rz)``."""

    dim = 3
    nrot = 3

    @staticmethod
    def moment(r: NDArray[np.float64], d: NDArray[np.float64]) -> NDArray[np.float64]:
        """``(w x r) . d = w . (r x d)``: the coefficients ``r x d`` ``(n, 3)``."""
        return np.cross(r, d)

    @staticmethod
    def rotation(w: ArrayLike) -> NDArray[np.float64]:
        """Rotation matrices ``(n, 3, 3)`` of rotation vectors ``w`` ``(n, 3)`` (rad, right-handed
        about the vector's direction)."""
        from scipy.spatial.transform import Rotation  # imported on first use

        return Rotation.from_rotvec(np.asarray(w, dtype=float).reshape(-1, 3)).as_matrix()

    @staticmethod
    def angles(R: NDArray[np.float64]) -> NDArray[np.float64]:
        """Rotation vectors ``(n, 3)`` (rad, angles up to pi) of rotation matrices ``(n, 3, 3)``."""
        from scipy.spatial.transform import Rotation  # imported on first use

        return Rotation.from_matrix(np.asarray(R, dtype=float).reshape(-1, 3, 3)).as_rotvec()

    @staticmethod
    def tangents(n: NDArray[np.float64]) -> NDArray[np.float64]:
        """Two unit tangents per normal: ``t1`` the projection of ``+z`` (``+x`` for a
        horizontal plane), ``t2 = n x t1``."""
        ref = np.where((np.abs(n[:, 2]) > 1 - 1e-9)[:, None], np.array([1.0, 0.0, 0.0]), EZ)
        t1 = ref - np.einsum("ij,ij->i", ref, n)[:, None] * n
        t1 /= np.linalg.norm(t1, axis=1, keepdims=True)
        return np.stack([t1, np.cross(n, t1)], axis=1)

    @staticmethod
    def to_global(p: NDArray[np.float64]) -> NDArray[np.float64]:
        return p

    @staticmethod
    def reduce(u: NDArray[np.float64], name: str) -> NDArray[np.float64]:
        return u

    @staticmethod
    def lift(q: NDArray[np.float64]) -> NDArray[np.float64]:
        return q


@dataclass(frozen=True)
class _Scene:
    """What the path needs of an assembly: per block its weight and reference centroid, the
    contact points (per interface: the ends of its trace in the plane, or the vertices of
    its polygon in space), carried by both blocks; the support velocities per unit magnitude."""

    kin: _Planar | _Spatial
    weights: NDArray[np.float64]  # (nb,)
    c0: NDArray[np.float64]  # (nb, dim) reference centroids
    free: NDArray[np.int64]  # indices of the free blocks
    ia: NDArray[np.int64]  # (ni,) block A of each interface
    ib: NDArray[np.int64]
    ci: NDArray[np.int64]  # (nc,) interface of each contact point
    slot: NDArray[np.int64]  # (nc,) its place in its interface
    points: NDArray[np.float64]  # (nc, dim) reference contact points
    normal: NDArray[np.float64]  # (ni, dim) reference normal, A -> B
    support: NDArray[np.int64]  # support block indices
    velocity: NDArray[np.float64]  # (ns, ndof) per unit magnitude about the centroid
    size: float
    dead: tuple[NDArray[np.int64], NDArray[np.float64], NDArray[np.float64]] | None = None  # blocks, points, forces

    @property
    def dim(self) -> int:
        return self.kin.dim

    @property
    def ndof(self) -> int:
        return self.kin.dim + self.kin.nrot

    @property
    def scale(self) -> NDArray[np.float64]:
        """Per dof of a block, the factor of its scaled velocity: 1 for a translation, the
        size for a rotation (:func:`_operators`)."""
        return np.array([1.0] * self.kin.dim + [self.size] * self.kin.nrot)


def _scene(assembly: Assembly, settlements: Mapping[str, ArrayLike], model: str = "auto") -> _Scene:
    plane = find_plane(assembly) if model == "auto" else None
    kin: _Planar | _Spatial = _Planar(plane) if plane is not None else _Spatial()
    names = assembly.support_names
    sett = check_settlements(names, settlements)
    vel = np.zeros((len(names), kin.dim + kin.nrot))
    for name, u in sett.items():
        vel[names.index(name)] = kin.reduce(np.asarray(u, dtype=float), name)
    t = assembly.interface_table
    if plane is not None:
        e = plane.e
        local = lambda p: np.stack([(p - plane.origin) @ e, p[..., 2]], axis=-1)  # noqa: E731
        normal = np.stack([t.normal @ e, t.normal[:, 2]], axis=-1) if len(t) else np.zeros((0, 2))
        normal /= np.linalg.norm(normal, axis=1, keepdims=True)
        pts = []
        for k in range(len(t)):  # the two ends of the interface's trace
            p = local(t.points[t.start[k] : t.start[k + 1]])
            s = p @ _Planar.tangents(normal[k : k + 1])[0, 0]
            pts.append(p[[np.argmin(s), np.argmax(s)]])
        points = np.concatenate(pts) if pts else np.zeros((0, 2))
        ci = np.repeat(np.arange(len(t)), 2)
        centroids = local(assembly.centroids)
    else:
        normal = np.asarray(t.normal, dtype=float)
        points = np.asarray(t.points, dtype=float)
        ci = np.asarray(t.vertex_interface, dtype=np.int64)
        centroids = assembly.centroids
    slot = np.arange(len(ci)) - np.searchsorted(ci, ci)
    return _Scene(
        kin=kin,
        weights=assembly.weights,
        c0=np.asarray(centroids, dtype=float),
        free=np.asarray(assembly.free_indices, dtype=np.int64),
        ia=t.a.astype(np.int64),
        ib=t.b.astype(np.int64),
        ci=ci.astype(np.int64),
        slot=slot.astype(np.int64),
        points=points,
        normal=normal,
        support=np.asarray(assembly.support_indices, dtype=np.int64),
        velocity=vel,
        size=float(assembly.size),
    )


@dataclass(frozen=True)
class _Config:
    """Placement of every block: centroid ``c`` (nb, dim) and rotation ``R`` (nb, dim, dim)
    from the reference, at magnitude ``s``: a reference point ``p`` of block ``i`` is at
    ``c_i + R_i (p - c0_i)``."""

    s: float
    c: NDArray[np.float64]
    R: NDArray[np.float64]

    def place(self, idx: NDArray[np.int64], p: NDArray[np.float64], sc: _Scene) -> NDArray[np.float64]:
        """Current position of reference points ``p`` (n, dim) carried by blocks ``idx``."""
        return self.c[idx] + np.einsum("nij,nj->ni", self.R[idx], p - sc.c0[idx])

    def turned(self, sc: _Scene, dq: NDArray[np.float64], blocks: NDArray[np.int64]) -> _Config:
        """The free ``blocks`` moved rigidly by ``dq`` (n, ndof): translated by its first
        ``dim`` entries and turned about their centroids by the rest (a rotation vector,
        composed on the left: ``R <- rot(dq) R``)."""
        c, R = self.c.copy(), self.R.copy()
        c[blocks] += dq[:, : sc.dim]
        R[blocks] = sc.kin.rotation(dq[:, sc.dim :]) @ R[blocks]
        return _Config(self.s, c, R)


def _per_interface(sc: _Scene, mask: NDArray[np.bool_]) -> NDArray[np.bool_]:
    """Whether any contact point of each interface is in ``mask`` (one per contact point)."""
    return np.bincount(sc.ci, weights=mask.astype(float), minlength=len(sc.ia)) > 0


def _contacts(sc: _Scene, cf: _Config) -> tuple[NDArray, NDArray, NDArray]:
    """Per contact point: current point (nc, dim), A's normal (nc, dim) and gap (nc,), the
    gap being B's copy minus A's copy along A's normal (m; > 0 open)."""
    pa = cf.place(sc.ia[sc.ci], sc.points, sc)
    pb = cf.place(sc.ib[sc.ci], sc.points, sc)
    n = np.einsum("kij,kj->ki", cf.R[sc.ia[sc.ci]], sc.normal[sc.ci])
    gap = np.einsum("kj,kj->k", pb - pa, n)
    return 0.5 * (pa + pb), n, gap


@dataclass(frozen=True)
class _Step:
    """One linear program on one configuration and its closed contacts."""

    status: str  # optimal / unbounded / infeasible / numerical
    v: NDArray[np.float64] | None = None  # (nb, ndof) block velocities (supports included)
    fn: NDArray[np.float64] | None = None  # (nc,) normal forces at the contacts (0 where open)
    reactions: NDArray[np.float64] | None = None  # (ns, ndof)
    dn: NDArray[np.float64] | None = None  # (nc,) opening velocity at the contacts
    message: str = ""


def _operators(sc: _Scene, cf: _Config, closed: NDArray[np.bool_], on_a: bool = False):
    """Compatibility rows of the closed contacts: ``(Gn, Gt, hn, ht, kc, p, dirs)``.

    ``G`` (sparse) acts on the free blocks' scaled velocities ``(v, w L)`` (``L`` the
    assembly's size: every column is a length per unit magnitude, whatever the unit of
    length; :func:`_unscale`); ``Gn`` has one row per closed contact, ``Gt`` one per closed
    contact and tangent (tangent by tangent); ``h`` is the supports' part, ``kc`` the closed
    contacts, ``p`` their points and ``dirs`` (nk, dim, dim) their directions ``(n, t...)``.

    The points are midway between the two copies of each contact point, or with ``on_a`` block
    A's copies: those of one interface then lie in a plane normal to ``n`` exactly, so that the
    tangential forces, unbounded without a friction limit, make no moment about it even where
    the copies are apart (an open point carrying compression: :func:`_limit`)."""
    p, n, _ = _contacts(sc, cf)
    if on_a:
        p = cf.place(sc.ia[sc.ci], sc.points, sc)
    kc = np.flatnonzero(closed)
    nk, nf, nd, dim = len(kc), len(sc.free), sc.ndof, sc.dim
    col = np.full(len(sc.weights), -1)
    col[sc.free] = np.arange(nf)
    vsup = np.zeros((len(sc.weights), nd))
    vsup[sc.support] = sc.velocity
    pt = p[kc]
    dirs = np.concatenate([n[kc][:, None, :], sc.kin.tangents(n[kc])], axis=1) if nk else np.zeros((0, dim, dim))
    rows = np.arange(dim * nk).reshape(dim, nk)  # direction by direction: normal, then the tangents
    vals, ri, cj = [], [], []
    h = np.zeros((dim, nk))
    for blk, sign in ((sc.ib[sc.ci[kc]], 1.0), (sc.ia[sc.ci[kc]], -1.0)):
        # velocity of the point on block blk along each direction d per unit (v, w): d, and (w x r) . d
        r = pt - cf.c[blk]
        coef = sign * np.stack([np.column_stack([dirs[:, j], sc.kin.moment(r, dirs[:, j])]) for j in range(dim)])
        free = col[blk] >= 0
        vals.append((coef[:, free] / sc.scale).ravel())
        ri.append(np.repeat(rows[:, free], nd))
        cj.append(np.broadcast_to(nd * col[blk][free, None] + np.arange(nd), (dim, int(free.sum()), nd)).ravel())
        h[:, ~free] += np.einsum("jmd,md->jm", coef[:, ~free], vsup[blk[~free]])
    G = sp.csr_matrix((np.concatenate(vals), (np.concatenate(ri), np.concatenate(cj))), shape=(dim * nk, nd * nf))
    return G[:nk], G[nk:], h[0], h[1:].ravel(), kc, pt, dirs


def _unscale(sc: _Scene, x: NDArray[np.float64]) -> NDArray[np.float64]:
    """Free blocks' velocities ``(nf, ndof)`` from the scaled ones of :func:`_operators`."""
    return x.reshape(-1, sc.ndof) / sc.scale


def _weights(sc: _Scene, cf: _Config | None = None) -> NDArray[np.float64]:
    """The self-weight load vector over the free blocks' dofs, in units of their total weight;
    with ``cf``, plus the dead point loads (:func:`settlement_path`'s ``dead``) carried by their
    blocks to configuration ``cf`` (their points moved, their forces unchanged)."""
    b = np.zeros(sc.ndof * len(sc.free))
    total = sc.weights[sc.free].sum()
    b[sc.dim - 1 :: sc.ndof] = -sc.weights[sc.free] / total
    if cf is not None and sc.dead is not None:
        blocks, points, forces = sc.dead  # on free blocks only (:func:`_dead`)
        col = np.full(len(sc.weights), -1)
        col[sc.free] = np.arange(len(sc.free))
        r = cf.place(blocks, points, sc) - cf.c[blocks]
        w = np.column_stack([forces, sc.kin.moment(r, forces)]) / sc.scale / total  # scaled dofs (:func:`_operators`)
        np.add.at(b, (sc.ndof * col[blocks])[:, None] + np.arange(sc.ndof), w)
    return b


def _solve(sc: _Scene, cf: _Config, closed: NDArray[np.bool_]) -> _Step:
    """The TCE and its kinematic dual on the closed contacts of configuration ``cf`` (module
    docstring); the equilibrium of the duals is checked."""
    Gn, Gt, hn, ht, kc, p, dirs = _operators(sc, cf, closed)
    b = _weights(sc, cf)
    V = np.abs(sc.velocity).max(initial=0.0) or 1.0  # velocities in units of the supports' largest
    status, res = _linprog(-b, A_ub=-Gn, b_ub=hn / V, A_eq=Gt, b_eq=-ht / V, bounds=(None, None))
    if status == "infeasible":
        return _Step(status, message="the support motion needs interpenetration: " + res.message)
    if status == "unbounded":
        return _Step(status, message="a mechanism lowers the weights with the supports held: " + res.message)
    if status != "optimal":
        return _Step(status, message="HiGHS: " + res.message)
    fn_ = -np.asarray(res.ineqlin.marginals)
    ft_ = np.asarray(res.eqlin.marginals)
    resid = Gn.T @ fn_ + Gt.T @ ft_ + b
    if np.abs(resid).max(initial=0.0) > 1e3 * _FEAS or fn_.min(initial=0.0) < -1e3 * _FEAS:
        return _Step("numerical", message=f"equilibrium residual {np.abs(resid).max():.2e} of the dual state")
    nd = sc.ndof
    v = np.zeros((len(sc.weights), nd))
    v[sc.free] = V * _unscale(sc, res.x)
    v[sc.support] = sc.velocity
    total = sc.weights[sc.free].sum()
    fn = np.zeros(closed.shape)
    fn[kc] = fn_ * total
    dn = np.zeros(closed.shape)
    dn[kc] = V * (Gn @ res.x) + hn
    # the force at each closed contact (global in-frame components), +f on B and -f on A
    comps = np.column_stack([fn_, ft_.reshape(sc.dim - 1, -1).T]) * total if len(kc) else np.zeros((0, sc.dim))
    f = np.einsum("kj,kjd->kd", comps, dirs)
    reac = np.zeros((len(sc.support), nd))
    pos = np.full(len(sc.weights), -1)
    pos[sc.support] = np.arange(len(sc.support))
    for blk, sign in ((sc.ia[sc.ci[kc]], 1.0), (sc.ib[sc.ci[kc]], -1.0)):
        on = pos[blk] >= 0  # the structure's block is the other one: it receives sign * f
        wrench = sign * np.column_stack([f[on], sc.kin.moment(p[on] - cf.c[blk[on]], f[on])])
        np.add.at(reac, pos[blk[on]], wrench)
    return _Step("optimal", v=v, fn=fn, reactions=reac, dn=dn)


def _limit(
    sc: _Scene, cf: _Config, closed: NDArray[np.bool_], direction: NDArray[np.float64]
) -> tuple[str, float, int]:
    """lambda_max of the lateral pattern (the weights along the horizontal ``direction``, in
    the scene's coordinates) on the contacts ``closed`` of ``cf``:
    ``max lam  s.t.  G' f + b + lam b_lat = 0, fn >= 0`` (no sliding), the contacts at block
    A's copies of their points (:func:`_operators`).

    Solved as stated; where its optimum carries a tangential force above :data:`SHEAR_CAP`
    times the load (the free blocks' weight and the fixed forces' magnitudes; not the lateral
    load found, which the spurious strength inflates), solved again with every tangential
    force within that cap (an optimum within the cap is the capped program's optimum too).
    Where the capped program gives less (relative 1e-7), the capacity rests on tangential
    forces that no friction provides, a near self-stress of a geometry that lost the symmetry
    of the reference: the status is ``withheld`` (NaN). Returns the status, lambda_max and
    the number of programs solved."""
    Gn, Gt, *_ = _operators(sc, cf, closed, on_a=True)
    b, weight = _weights(sc, cf), _weights(sc)
    blat = np.zeros_like(b)
    for j in range(sc.dim):
        blat[j :: sc.ndof] = -weight[sc.dim - 1 :: sc.ndof] * direction[j]
    nn, nt = Gn.shape[0], Gt.shape[0]
    A = sp.hstack([Gn.T, Gt.T, sp.csr_matrix(blat[:, None])])
    c = np.zeros(nn + nt + 1)
    c[-1] = -1.0
    bounds = [(0, None)] * nn + [(None, None)] * nt + [(None, None)]
    status, res = _linprog(c, A_eq=A, b_eq=-b, bounds=bounds)
    if status != "optimal":
        return status, float("nan"), 1
    lam = float(res.x[-1])
    dead = 0.0 if sc.dead is None else float(np.linalg.norm(sc.dead[2], axis=1).sum())
    cap = SHEAR_CAP * (1.0 + dead / sc.weights[sc.free].sum())  # forces in units of the weight
    if np.abs(res.x[nn : nn + nt]).max(initial=0.0) <= cap:
        return status, lam, 1
    capped_status, capped = _linprog(c, A_eq=A, b_eq=-b, bounds=bounds[:nn] + [(-cap, cap)] * nt + bounds[-1:])
    if capped_status != "optimal" or capped.x[-1] < lam - 1e-7 * max(1.0, abs(lam)):
        return "withheld", float("nan"), 2
    return status, lam, 2


def _move(sc: _Scene, cf: _Config, v: NDArray[np.float64], ds: float, advance: bool = True) -> _Config:
    """Every free block moved rigidly by ``v ds``; the supports to their exact place at
    ``s + ds`` (at ``s`` when not ``advance``: a motion with the supports held)."""
    new = cf.turned(sc, ds * v[sc.free], sc.free)
    s = cf.s + ds if advance else cf.s
    c, R = new.c, new.R
    c[sc.support] = sc.c0[sc.support] + s * sc.velocity[:, : sc.dim]
    R[sc.support] = sc.kin.rotation(s * sc.velocity[:, sc.dim :])
    return _Config(s, c, R)


def _project(sc: _Scene, cf: _Config, keep: NDArray[np.bool_]) -> _Config:
    """One Gauss-Newton step that closes the relative displacement (every component) of the
    contacts ``keep`` by the least change of the free blocks' placements.

    The step is the least-norm least-squares solution ``dq = -J+ mis`` of the linearised
    misfit (``J`` the compatibility rows of :func:`_operators`, rank-deficient where a block
    is free to turn about a hinge or where the contact rows are redundant), computed on one
    sparse factorisation of ``J'J + mu I`` by iterated Tikhonov regularisation: every
    iterate stays in the row space of ``J`` (no motion along a mechanism), and the error in a
    direction of singular value ``sigma`` shrinks by ``mu / (sigma**2 + mu)`` per iterate.
    """
    from scipy.sparse.linalg import splu  # imported on first use

    if not keep.any():
        return cf
    Gn, Gt, _, _, kc, _, dirs = _operators(sc, cf, keep)
    pa = cf.place(sc.ia[sc.ci[kc]], sc.points[kc], sc)
    pb = cf.place(sc.ib[sc.ci[kc]], sc.points[kc], sc)
    mis = np.einsum("kd,kjd->jk", pb - pa, dirs).ravel()  # normal rows, then tangent by tangent
    J = sp.vstack([Gn, Gt]).tocsc()
    JtJ = (J.T @ J).tocsc()
    mu = _TIKHONOV * max(float(JtJ.diagonal().max(initial=0.0)), 1.0)
    lu = splu((JtJ + mu * sp.identity(J.shape[1], format="csc")).tocsc())
    dq = np.zeros(J.shape[1])
    for _ in range(_REFINE):
        dq += lu.solve(-(J.T @ (mis + J @ dq)))
    return cf.turned(sc, _unscale(sc, dq), sc.free)


def _snap(
    sc: _Scene, cf: _Config, closed: NDArray[np.bool_], gtol: float, limit: float
) -> tuple[_Config, NDArray[np.bool_], _Step] | _Step | None:
    """Follow the structure's fall with the supports held from a configuration where nothing
    stands, until an open contact closes and the structure stands again.

    At each sub-step the direction is the kinematic program's steepest descent of the
    weights with the supports held (block speeds bounded by 1, rotations times the size by
    1); the blocks move along it until the first open contact closes (then shut exactly by
    the projection), by at most 1 % of the size. The fall is taken as quasi-static with
    perfectly inelastic impacts (the energy released is dissipated when the joint closes).

    Returns the standing configuration, its closed contacts and its program; None when no
    contact closes before some block has turned by ``reach`` rad or moved by ``reach`` times
    the size, or when the fall does not lower the weights (a collapse); the failed
    :class:`_Step` (``numerical``) when HiGHS fails. ``reach`` is ``limit`` or, if larger,
    twice the widest relative rotation of a joint open at the start of the fall (a snap
    turns the blocks back by the opening of the joint it closes).
    """
    bounds = (-1.0, 1.0)  # scaled velocities (:func:`_operators`)
    start = cf
    ajar = _per_interface(sc, ~closed)
    rel = sc.kin.angles(cf.R[sc.ib[ajar]] @ np.swapaxes(cf.R[sc.ia[ajar]], -1, -2))
    reach = max(limit, 2.0 * float(np.linalg.norm(rel, axis=-1).max(initial=0.0)))
    everything = np.ones(closed.shape, dtype=bool)
    nc = len(closed)
    for _ in range(2000):
        b = _weights(sc, cf)
        GnA, GtA, *_ = _operators(sc, cf, everything)  # every contact's rows; the closed ones' below
        kc = np.flatnonzero(closed)
        Gn, Gt = GnA[kc], GtA[(nc * np.arange(sc.dim - 1)[:, None] + kc).ravel()]
        status, res = _linprog(-b, A_ub=-Gn, b_ub=np.zeros(Gn.shape[0]), A_eq=Gt, b_eq=np.zeros(Gt.shape[0]), bounds=bounds)
        if status != "optimal":
            return _Step("numerical", message="HiGHS, following the fall: " + res.message)
        if -res.fun <= _FEAS:
            return None
        d = np.zeros((len(sc.weights), sc.ndof))
        d[sc.free] = _unscale(sc, res.x)
        rate = GnA @ res.x  # opening rate of every contact along d
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
        turned = np.linalg.norm(sc.kin.angles(new.R @ np.swapaxes(start.R, -1, -2)), axis=-1).max()
        if max(moved, turned) > reach:
            return None
        _, _, gap = _contacts(sc, new)
        now = gap <= gtol
        if t == t_close:
            step = _solve(sc, new, now)
            if step.status == "optimal":
                return new, now, step
            if step.status == "numerical":
                return step
            if step.status != "unbounded":
                return None
        cf, closed = new, now
    return None


def _dead(sc: _Scene, dead: AppliedLoads) -> _Scene:
    """``sc`` with the fixed forces of ``dead`` (resolved on the same assembly) in its coordinates."""
    if dead.scaled.any():
        raise ValueError("dead: the settlement path carries fixed loads only; live loads are searched after it")
    if isinstance(sc.kin, _Planar):
        plane = sc.kin.plane
        if not dead.in_plane(plane):
            raise ValueError("dead: loads out of the assembly's plane; only in-plane loads are followed")
        points = np.column_stack([(dead.points - plane.origin) @ plane.e, dead.points[:, 2]])
        forces = np.column_stack([dead.forces @ plane.e, dead.forces[:, 2]])
    else:
        points, forces = dead.points, dead.forces
    return replace(sc, dead=(dead.blocks, points, forces))


def _checked(
    assembly: Assembly,
    material: Material | None,
    settlements: Mapping[str, ArrayLike],
    alpha: float | None,
    model: str = "auto",
) -> tuple[_Scene, NDArray[np.float64]]:
    """The scene of a path and the lateral direction in its coordinates (zero without
    ``alpha``), checked (:func:`check_path_scene`)."""
    material = material or Material()
    if material != Material(flow=material.flow):
        raise ValueError(
            "settlement_path follows rigid blocks of a Heyman material (no friction limit, cohesion, "
            "strengths or stiffness): sliding and crushing are not followed"
        )
    if model not in ("auto", "spatial"):
        raise ValueError(f"model must be 'auto' or 'spatial', got {model!r}")
    sc = _scene(assembly.validate(), settlements, model)
    if alpha is None:
        return sc, np.zeros(sc.dim)
    d = lateral_direction(alpha)
    if isinstance(sc.kin, _Spatial):
        return sc, np.asarray(d, dtype=float)
    direction = float(d @ sc.kin.plane.e)
    if abs(abs(direction) - 1.0) > 1e-12:
        raise ValueError(f"alpha = {alpha} leaves the assembly's plane: lambda_max is followed in plane only")
    return sc, np.array([direction, 0.0])


def check_path_scene(
    assembly: Assembly, material: Material | None, settlements: Mapping[str, ArrayLike], alpha: float | None = None
) -> None:
    """Whether :func:`settlement_path` can follow this scene.

    Raises
    ------
    ValueError
        A material other than the rigid Heyman one, a motion of an unknown support, or, for
        a planar assembly (:func:`tce.core.model.find_plane`), a motion out of its plane or
        (``alpha`` given) a lateral direction out of the plane.
    """
    _checked(assembly, material, settlements, alpha)


@dataclass(frozen=True, eq=False, kw_only=True)
class SettlementPathResult(Result):
    """A finite-settlement path (``ok`` when ``status`` is ``collapse``, ``snap_through`` or
    ``contact_lost``: a capacity was bracketed).

    Coordinates and signs as in the module docstring: planar with ``plane`` set, spatial
    with ``plane`` None; :meth:`wrenches` and :meth:`displacements` give both in the
    global frame.

    Attributes
    ----------
    status : str
        How the path ended (module docstring); ``message`` says what decided it.
    settlements : dict
        The scenario's settlement vectors ``{support: [ux, uy, uz, rx, ry, rz]}`` (m, rad).
    capacity : float
        Settlement capacity: the largest magnitude found standing (multiples of the
        settlement vectors; NaN unless ``ok``).
    upper : float
        Smallest magnitude found not standing (NaN if none).
    magnitudes : (k,) ndarray
        Magnitude of every standing configuration of the path, increasing.
    reactions : (k, n_supports, 3 or 6) ndarray
        The wrench of each support on the structure at each magnitude (kN, kN m): planar
        ``(Rx, Rz, M)``, spatial ``(Fx, Fy, Fz, Mx, My, Mz)``, about the support's current
        centroid.
    lambda_max : (k,) ndarray
        lambda_max of the lateral pattern (``alpha``) on the deformed structure, every
        contact point within ``contact_gap`` carrying compression (NaN when not asked for,
        where HiGHS fails, or where the program is withheld: module docstring).
    placements : (k, n_blocks, 3 or 6) ndarray
        Every block's displacement from its reference placement (the centroid's translation,
        m, and the rotation about it, rad): planar ``(dx, dz, theta)``, spatial
        ``(dx, dy, dz, rx, ry, rz)``.
    hinges : list of list of int
        Per magnitude, the interfaces that rotate in the mechanism (hinges).
    hinge_points : (k, n_interfaces, 3) ndarray
        Per magnitude, the current position of each hinge (the closed contact point of a
        rotating interface that opens least; m, global frame), NaN for the other interfaces.
    open_ends : (k, n_interfaces, p) bool ndarray
        Which contact points of each interface are open, per magnitude (``p`` = 2 in the
        plane: the two ends; in space the polygon's vertices in order, padded with False).
    hinge_sequence : list of tuple
        ``(magnitude, interface, event)``: ``event`` is ``"hinge"`` when an interface starts
        rotating, ``"closed"`` when an open joint closes again along the path, ``"snap"``
        when it closes at the end of a fall (:attr:`snaps`).
    plane : Plane or None
        The assembly's plane (planar assemblies).
    snaps : list of float
        Magnitudes at which nothing stood and the structure fell, with the supports held,
        to a new standing configuration (a joint closed: a hinge migrated); each appears
        twice in ``magnitudes``, before and after the fall.
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
    plane: Plane | None = field(repr=False)
    snaps: list = field(default_factory=list)
    n_solves: int = 0

    def _lift(self, q: NDArray[np.float64]) -> NDArray[np.float64]:
        return _Spatial.lift(q) if self.plane is None else _Planar(self.plane).lift(q)

    def wrenches(self) -> NDArray[np.float64]:
        """Reactions ``(k, n_supports, 6)`` in the global frame ``(Fx, Fy, Fz, Mx, My, Mz)``."""
        return self._lift(self.reactions)

    def displacements(self) -> NDArray[np.float64]:
        """Block displacements ``(k, n_blocks, 6)`` in the global frame: ``(ux, uy, uz)`` of
        the centroid and the rotation vector ``(rx, ry, rz)`` about it."""
        return self._lift(self.placements)

    def moves(self, assembly: Assembly, index: int = -1) -> NDArray[np.float64]:
        """The placement of every block of ``assembly`` at step ``index``: homogeneous
        matrices ``(n_blocks, 4, 4)`` taking a point of the block in the reference to its
        place (global frame, m)."""
        disp = self.displacements()[index]
        R = _Spatial.rotation(disp[:, 3:])
        c = assembly.centroids
        move = np.zeros((len(c), 4, 4))
        move[:, :3, :3] = R
        move[:, :3, 3] = c + disp[:, :3] - np.einsum("nij,nj->ni", R, c)
        move[:, 3, 3] = 1.0
        return move

    def deformed(self, assembly: Assembly, index: int = -1) -> Assembly:
        """``assembly`` with its blocks at the placement of step ``index`` (:meth:`moves`; the
        interfaces as in the reference: for drawing)."""
        blocks = tuple(
            Block(blk.name, Polyhedron(blk.shape.vertices @ m[:3, :3].T + m[:3, 3], blk.shape.faces), blk.unit_weight,
                  blk.support)
            for blk, m in zip(assembly.blocks, self.moves(assembly, index))
        )
        return Assembly(blocks, assembly.interfaces, dict(assembly.meta))


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
    model: str = "auto",
    dead: AppliedLoads | None = None,
    contact_gap: float | None = None,
) -> SettlementPathResult:
    """Follow the support motion ``s * settlements`` from ``s = 0`` until nothing stands.

    Parameters
    ----------
    settlements : dict
        ``{support: [ux, uy, uz, rx, ry, rz]}`` (m, rad) about each support's centroid (in
        the plane of a planar assembly): the motion of unit magnitude (module docstring).
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
        Also lambda_max of the lateral pattern in direction ``alpha`` (for a planar
        assembly 0 or 180 degrees: in the plane) on the deformed structure at every
        standing magnitude.
    gap_tol : float
        A contact point is closed when its gap is below ``gap_tol`` times the assembly's size.
    snap_ratio : float
        Largest ratio of the mechanism's speed to the supports' before ``snap_through``.
    snap_limit : float
        Where nothing stands, the structure's fall with the supports held is followed until
        an open joint closes (a snap, after which the path goes on); a fall in which some
        block turns by more than ``snap_limit`` rad, or moves by more than ``snap_limit``
        times the assembly's size, before any joint closes is a collapse (the limit is
        raised to twice the widest opening of an open joint when that is larger).
    model : {"auto", "spatial"}
        ``"auto"`` follows a planar assembly in its plane and any other in space;
        ``"spatial"`` follows every assembly in space (the same path: a check of the
        spatial kinematics on a planar structure).
    dead : AppliedLoads, optional
        Fixed loads besides the self-weight (:func:`tce.core.loads.resolve` of a pattern on
        ``assembly`` without live loads: a fill's weight, fixed point loads), carried along
        the path by the blocks they act on: each force keeps its direction and magnitude, its
        point moves with its block. The lateral pattern of ``lam`` stays the self-weight's.
    contact_gap : float, optional
        For ``lam``: every contact point whose gap is at most ``contact_gap`` (m; default
        :data:`CONTACT_GAP` times the assembly's size, the study key of the same name) may
        carry compression in the lateral capacity (a gap that small is closed by a motion of
        the order that limit analysis neglects; ``docs/settlements.md``, "The lateral
        capacity of the settled structure"); 0 lets only the closed points carry it (the
        structure as it stands, no gap closing).
    """
    t0 = time.perf_counter()
    if not (math.isfinite(increment) and increment > 0):
        raise ValueError(f"increment must be a finite number > 0, got {increment!r}")
    if not (math.isfinite(s_max) and s_max > 0 and s_max / increment <= MAX_STEPS):
        raise ValueError(f"s_max must be > 0 with s_max / increment <= {MAX_STEPS}, got {s_max!r}")
    atol = increment / 64 if atol is None else float(atol)
    if not (math.isfinite(atol) and atol > 0):
        raise ValueError(f"atol must be a finite number > 0, got {atol!r}")
    if contact_gap is not None and not (math.isfinite(contact_gap) and contact_gap >= 0):
        raise ValueError(f"contact_gap must be a finite number >= 0 (m), got {contact_gap!r}")
    sc, direction = _checked(assembly, material, settlements, alpha if lam else None, model)
    if dead is not None:
        sc = _dead(sc, dead)
    gtol = gap_tol * sc.size
    sett = {k: list(np.asarray(v, dtype=float)) for k, v in settlements.items()}
    n_solves = 0
    ni = len(sc.ia)

    def solve(cf: _Config, closed: NDArray[np.bool_]) -> _Step:
        nonlocal n_solves
        n_solves += 1
        return _solve(sc, cf, closed)

    nb = len(sc.weights)
    cf = _Config(0.0, sc.c0.copy(), np.broadcast_to(np.eye(sc.dim), (nb, sc.dim, sc.dim)).copy())
    closed = np.ones(len(sc.ci), dtype=bool)
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
        dw = np.linalg.norm(st.v[sc.ib, sc.dim :] - st.v[sc.ia, sc.dim :], axis=1)
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
        if s_max - cf.s - h <= 1e-9 * increment:  # the rounding of a sum of increments: end at s_max
            h = s_max - cf.s
        trial = _move(sc, cf, step.v, h)
        stays = closed & (step.dn <= _FEAS * vref * 1e3)
        trial = _project(sc, trial, stays)
        _, _, gap = _contacts(sc, trial)
        if gap.min(initial=0.0) < -10 * gtol:
            # an open contact closed within the increment (or the projection failed): shorter step
            if h > atol:
                ds = h / 2
                continue
            status, message = "numerical", f"interpenetration {-gap.min():.3g} m at s = {trial.s:.6g} with the shortest step"
            break
        now = gap <= gtol
        lost = np.flatnonzero(_per_interface(sc, closed) & ~_per_interface(sc, now)).tolist()  # in this increment
        new = solve(trial, now)
        if new.status == "optimal":
            for k in np.flatnonzero(_per_interface(sc, now & ~closed)):
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
        if isinstance(fallen, _Step):
            status, message = "numerical", f"after s = {upper:.6g}: {fallen.message}"
            break
        if fallen is None:
            status = "contact_lost" if lost_at_upper else "collapse"
            message = f"no admissible state at s = {upper:.6g}: {upper_msg}"
            break
        for k in np.flatnonzero(_per_interface(sc, fallen[1] & ~upper_state[1])):
            sequence.append((fallen[0].s, int(k), "snap"))
        snaps.append(fallen[0].s)
        record(*fallen)
        upper, ds = float("nan"), increment

    ok = status in SettlementPathResult.OK
    k = len(records)
    lam_max = np.full(k, np.nan)
    if lam:
        reach = CONTACT_GAP * sc.size if contact_gap is None else contact_gap
        missing: dict[str, list[float]] = {}  # magnitudes without a lateral capacity, per status
        for i, (c, cl, _) in enumerate(records):
            _, _, gap = _contacts(sc, c)
            st, val, solved = _limit(sc, c, cl | (gap <= reach), direction)
            n_solves += solved
            lam_max[i] = val if st == "optimal" else np.nan
            if st != "optimal":
                missing.setdefault(st, []).append(c.s)
        why = {
            "withheld": f"it needs tangential forces above {SHEAR_CAP:g} times the load, a spurious strength of "
            "the no-sliding model on a geometry that lost the reference's symmetry",
        }
        for st, at in missing.items():
            message += (
                f"; lateral capacity NaN at {len(at)} magnitudes from s = {at[0]:.6g} to {at[-1]:.6g}: "
                + why.get(st, f"its program ended {st} (HiGHS)")
            )
    placements = np.zeros((k, nb, sc.ndof))
    hinge_points = np.full((k, ni, 3), np.nan)
    width = int(sc.slot.max(initial=-1)) + 1
    open_ends = np.zeros((k, ni, width), dtype=bool)
    for i, (c, cl, st) in enumerate(records):
        placements[i, :, : sc.dim] = c.c - sc.c0
        placements[i, :, sc.dim :] = sc.kin.angles(c.R)
        open_ends[i, sc.ci, sc.slot] = ~cl
        # the hinge of a rotating interface: its closed contact point that opens least
        p, _, _ = _contacts(sc, c)
        assert st.dn is not None
        for kk in sorted(rotating(st)):
            mine = np.flatnonzero((sc.ci == kk) & cl)
            if len(mine):
                hinge_points[i, kk] = sc.kin.to_global(p[mine[np.argmin(st.dn[mine])]])
    return SettlementPathResult(
        status=status,
        message=message,
        solver="HiGHS (scipy.optimize.linprog)",
        settlements=sett,
        capacity=float(records[-1][0].s) if ok else float("nan"),
        upper=float(upper),
        magnitudes=np.array([c.s for c, _, _ in records]),
        reactions=np.array([st.reactions for _, _, st in records]).reshape(k, len(sc.support), sc.ndof),
        lambda_max=lam_max,
        placements=placements,
        hinges=[sorted(rotating(st)) for _, _, st in records],
        hinge_points=hinge_points,
        open_ends=open_ends,
        hinge_sequence=sequence,
        plane=sc.kin.plane if isinstance(sc.kin, _Planar) else None,
        snaps=snaps,
        n_solves=n_solves,
        wall_time=time.perf_counter() - t0,
    )
