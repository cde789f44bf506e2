"""Discrete operators of an assembly, built once: equilibrium, loads, support wrenches, compliance.

Two models share one layout:

``spatial`` (3D)
    One contact per interface vertex with force ``(fn, ft1, ft2)`` in the interface frame;
    6 equilibrium rows per free block ``(Fx, Fy, Fz, Mx, My, Mz)`` about its centroid.
``planar`` (2D)
    For scenes symmetric about a vertical plane (:func:`find_plane`): one contact per end of
    each interface's trace in the plane with force ``(fn, ft)``, ``ft`` along ``m x n``
    (``m`` the plane normal); 3 equilibrium rows per free block (in-plane horizontal force,
    vertical force, moment about ``m``). Each planar contact stands for the 3D vertices that
    project onto it; :attr:`Model.lift` spreads its force over them in proportion to their
    tributary areas, which is exact for equilibrium (the vertex groups are balanced about the
    plane) and for the compliance (springs in parallel). The planar LP therefore has the same
    optimum as the spatial SOCP on such scenes.

Sign conventions (``docs/conventions.md``): equilibrium reads ``A_eq F + b_dead + lam * b_lat(alpha) = 0``
(loads on each free block, kN and kN m); ``B_sup F`` stacks, per support, the wrench
``(Fx, Fy, Fz, Mx, My, Mz)`` that the support exerts on the structure, in the global frame,
about the support's centroid (kN, kN m). Interfaces between two support blocks carry no
unknowns (neither block's equilibrium is enforced) and are left out.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import Literal

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from ..structures.assembly import Assembly

__all__ = [
    "InterfaceMap",
    "Model",
    "Plane",
    "build_model",
    "find_plane",
    "lateral_direction",
    "motions_in_plane",
    "scene_in_plane",
]

ModelKind = Literal["spatial", "planar"]
EZ = np.array([0.0, 0.0, 1.0])


def lateral_direction(alpha: float) -> NDArray[np.float64]:
    """Unit horizontal vector at ``alpha`` degrees from +x towards +y."""
    a = np.deg2rad(alpha)
    return np.array([np.cos(a), np.sin(a), 0.0])


def _skew(r: NDArray[np.float64]) -> NDArray[np.float64]:
    """Stack of cross-product matrices: ``_skew(r)[k] @ v == cross(r[k], v)``."""
    z = np.zeros(len(r))
    return np.stack(
        [
            np.stack([z, -r[:, 2], r[:, 1]], axis=1),
            np.stack([r[:, 2], z, -r[:, 0]], axis=1),
            np.stack([-r[:, 1], r[:, 0], z], axis=1),
        ],
        axis=1,
    )


@dataclass(frozen=True)
class Plane:
    """A vertical symmetry plane of an assembly: normal ``m`` (horizontal), through ``origin``."""

    m: NDArray[np.float64]
    origin: NDArray[np.float64]

    @property
    def e(self) -> NDArray[np.float64]:
        """In-plane horizontal unit vector ``m x z`` (``+x`` for the plane normal to ``+y``)."""
        return np.cross(self.m, EZ)


def _contact_groups(assembly: Assembly, plane: Plane, tol: float) -> list[list[np.ndarray]] | None:
    """For each interface, the two groups of vertex indices projecting on each end of its trace.

    Returns None if some interface cannot be reduced exactly (normal out of plane, a vertex
    projecting inside the trace, or a group not balanced about the plane).
    """
    groups = []
    for itf in assembly.interfaces:
        if abs(itf.normal @ plane.m) > tol:
            return None
        rel = itf.points - plane.origin
        off = rel @ plane.m
        t = np.cross(plane.m, itf.normal)
        s = rel @ t
        lo, hi = s.min(), s.max()
        span = hi - lo
        if span <= tol * assembly.size:
            return None
        at_lo = np.abs(s - lo) <= tol * assembly.size
        at_hi = np.abs(s - hi) <= tol * assembly.size
        if not np.all(at_lo | at_hi):
            return None
        w = itf.tributary
        pair = []
        for mask in (at_lo, at_hi):
            idx = np.flatnonzero(mask)
            if abs((w[idx] * off[idx]).sum()) > tol * assembly.size * max(w[idx].sum(), 1e-300):
                return None
            pair.append(idx)
        groups.append(pair)
    return groups


def find_plane(assembly: Assembly, tol: float = 1e-9) -> Plane | None:
    """The vertical plane of symmetry that makes the assembly planar, if any.

    Candidates are the vertical planes normal to y and to x through the mean block
    centroid. A plane qualifies when every block centroid lies in it, every interface
    normal lies in it, and every interface reduces exactly to two contacts (see module
    docstring). ``tol`` is relative to the assembly size.
    """
    c = assembly.centroids
    origin = c.mean(axis=0)
    for m in (np.array([0.0, 1.0, 0.0]), np.array([1.0, 0.0, 0.0])):
        if np.abs((c - origin) @ m).max() > tol * assembly.size:
            continue
        plane = Plane(m, origin)
        if _contact_groups(assembly, plane, tol) is not None:
            return plane
    return None


@dataclass(frozen=True, eq=False)
class InterfaceMap:
    """What turns a model's force vector into vertex forces, interface resultants and support
    wrenches: arrays only (results keep this, not the model).

    Attributes
    ----------
    interfaces : tuple of int
        ``(ni,)`` assembly index of each interface the model carries (its *slots*).
    lift : (3 nv, nc * dim) sparse
        Force vector -> ``(fn, ft1, ft2)`` at every interface vertex (identity when spatial).
    vertex_slot : (nv,) int
        Slot (position in ``interfaces``) of each vertex's interface.
    vertex_points : (nv, 3) float
        Vertex positions (m).
    vertex_frames : (nv, 3, 3) float
        Interface frame of each vertex, rows ``(n, t1, t2)``.
    normals : (ni, 3) float
        Unit normal (from A into B) of each slot's interface.
    B_sup : (6 ns, nc * dim) sparse
        Support wrenches on the structure (see :class:`Model`).
    """

    interfaces: tuple[int, ...]
    lift: sp.csr_matrix
    vertex_slot: NDArray[np.int64]
    vertex_points: NDArray[np.float64]
    vertex_frames: NDArray[np.float64]
    normals: NDArray[np.float64]
    B_sup: sp.csr_matrix


@dataclass(frozen=True, eq=False)
class Model:
    """Discrete operators of an assembly (see module docstring for conventions).

    Attributes
    ----------
    kind : {"spatial", "planar"}
    assembly : Assembly
    plane : Plane or None
        The symmetry plane of a planar model.
    dim : int
        Force components per contact (3 spatial: fn, ft1, ft2; 2 planar: fn, ft).
    contact_interface : (nc,) int
        Interface index of each contact.
    contact_points : (nc, 3) float
        Contact positions (m); for a planar contact, the mean of its vertices.
    contact_area : (nc,) float
        Tributary area of each contact (m^2).
    A_eq : (m, nc*dim) sparse
        Equilibrium matrix of the free blocks (``rows_per_block`` rows each).
    b_dead : (m,)
        Self-weight on the free blocks (kN, kN m).
    b_lat : (m, 2)
        Lateral load for lambda = 1 along +x (column 0) and +y (column 1).
    B_sup : (6*ns, nc*dim) sparse
        Support wrenches on the structure, global frame, about each support centroid.
    lift : (3*nv, nc*dim) sparse
        Map to the 3D vertex forces ``(fn, ft1, ft2)`` of every interface vertex
        (identity for the spatial model).
    vertex_interface : (nv,) int
        Interface of each 3D vertex (all interface vertices, in order).
    """

    kind: ModelKind
    assembly: Assembly
    plane: Plane | None
    dim: int
    interfaces: tuple[int, ...]
    contact_interface: NDArray[np.int64]
    contact_points: NDArray[np.float64]
    contact_area: NDArray[np.float64]
    tangents: NDArray[np.float64]
    A_eq: sp.csc_matrix
    b_dead: NDArray[np.float64]
    b_lat: NDArray[np.float64]
    B_sup: sp.csr_matrix
    lift: sp.csr_matrix
    vertex_interface: NDArray[np.int64]
    vertex_points: NDArray[np.float64]

    @property
    def n_contacts(self) -> int:
        """Number of contacts."""
        return len(self.contact_interface)

    @property
    def n_vars(self) -> int:
        """Number of force unknowns."""
        return self.n_contacts * self.dim

    @property
    def rows_per_block(self) -> int:
        """Equilibrium rows per free block: 6 (spatial) or 3 (planar)."""
        return 6 if self.kind == "spatial" else 3

    @cached_property
    def vertex_frames(self) -> NDArray[np.float64]:
        """Interface frame of every 3D vertex, (nv, 3, 3), rows ``(n, t1, t2)``."""
        return np.stack([self.assembly.interfaces[k].frame for k in self.vertex_interface])

    @cached_property
    def vertex_slot(self) -> NDArray[np.int64]:
        """Position in ``interfaces`` of each 3D vertex's interface."""
        slot = {k: i for i, k in enumerate(self.interfaces)}
        return np.array([slot[k] for k in self.vertex_interface], dtype=np.int64)

    @cached_property
    def interface_map(self) -> InterfaceMap:
        """The arrays results need to report vertex forces, resultants and support wrenches."""
        normals = np.array([self.assembly.interfaces[k].normal for k in self.interfaces]).reshape(-1, 3)
        return InterfaceMap(
            self.interfaces, self.lift, self.vertex_slot, self.vertex_points, self.vertex_frames, normals, self.B_sup
        )

    @cached_property
    def row_is_moment(self) -> NDArray[np.bool_]:
        """True for the moment rows of ``A_eq``."""
        r = self.rows_per_block
        pattern = np.arange(r) >= (3 if r == 6 else 2)
        return np.tile(pattern, len(self.assembly.free_indices))

    @cached_property
    def _lateral_cache(self) -> dict[float, NDArray[np.float64]]:
        return {}

    def b_lateral(self, alpha: float) -> NDArray[np.float64]:
        """Lateral load vector for lambda = 1 in direction ``alpha`` (degrees); read-only,
        kept per direction (solves along a load path ask for the same one each time)."""
        cache = self._lateral_cache
        v = cache.get(alpha)
        if v is None:
            if len(cache) >= 64:
                cache.clear()
            v = self.b_lat @ lateral_direction(alpha)[:2]
            v.flags.writeable = False
            cache[alpha] = v
        return v

    def compliance(self, normal_stiffness: float, shear_stiffness: float) -> NDArray[np.float64]:
        """Diagonal of the compliance ``D`` (m/kN) for stiffnesses per unit area (kN/m^3).

        ``D = 1 / (k * s * A_trib)`` per component: ``k`` is ``normal_stiffness`` for fn and
        ``shear_stiffness`` for the tangential components, ``s`` the interface's own
        stiffness multiplier (:attr:`tce.assembly.Interface.stiffness`).
        """
        factor = np.array([i.stiffness for i in self.assembly.interfaces])[self.contact_interface]
        area = np.maximum(self.contact_area * factor, np.finfo(float).tiny)
        k = np.array([normal_stiffness] + [shear_stiffness] * (self.dim - 1))
        return (1.0 / (area[:, None] * k[None, :])).ravel()

    def is_planar_load(self, alpha: float, settlements: dict[str, np.ndarray] | None = None, tol: float = 1e-12) -> bool:
        """Whether a lateral direction and support motions lie in this model's plane."""
        if self.plane is None:
            return True
        return scene_in_plane(self.plane, alpha, settlements, tol)


def scene_in_plane(plane: Plane, alpha: float, settlements: dict[str, np.ndarray] | None, tol: float = 1e-12) -> bool:
    """True when the lateral direction ``alpha`` and every support motion lie in ``plane``
    (:func:`motions_in_plane`; other loads: :meth:`tce.core.loads.AppliedLoads.in_plane`)."""
    d = lateral_direction(alpha)
    if abs(d @ plane.m) > 1e-12:
        return False
    return motions_in_plane(plane, settlements, tol)


def motions_in_plane(plane: Plane, settlements: dict[str, np.ndarray] | None, tol: float = 1e-12) -> bool:
    """True when every support motion lies in ``plane``: a motion ``(u, omega)`` is in plane
    when ``u . m = 0`` and ``omega`` is parallel to ``m`` (relative to its largest entry)."""
    for u in (settlements or {}).values():
        u = np.asarray(u, dtype=float)
        scale = max(np.abs(u).max(), 1e-300)
        if abs(u[:3] @ plane.m) > tol * scale:
            return False
        rot = u[3:]
        if np.linalg.norm(rot - (rot @ plane.m) * plane.m) > tol * scale:
            return False
    return True


def _block_wrench_matrix(
    assembly: Assembly,
    points: np.ndarray,
    directions: np.ndarray,
    contact_interface: np.ndarray,
) -> sp.csr_matrix:
    """Wrench on every block (6 rows each, about its centroid) of unit force components.

    ``directions[k, j]`` is the global direction of force component ``j`` of contact ``k``
    (on interface ``contact_interface[k]``); the force acts with + on block B and - on
    block A of that interface.
    """
    nc, dim = directions.shape[:2]
    a = np.array([i.a for i in assembly.interfaces])[contact_interface]
    b = np.array([i.b for i in assembly.interfaces])[contact_interface]
    rows, cols, vals = [], [], []
    col = (np.arange(nc)[:, None] * dim + np.arange(dim)[None, :])  # (nc, dim)
    for block, sign in ((b, 1.0), (a, -1.0)):
        r = points - assembly.centroids[block]
        moment = np.einsum("kij,kdj->kdi", _skew(r), directions)  # (nc, dim, 3)
        wrench = sign * np.concatenate([directions, moment], axis=2)  # (nc, dim, 6)
        rr = block[:, None, None] * 6 + np.arange(6)[None, None, :]
        rows.append(np.broadcast_to(rr, wrench.shape).ravel())
        cols.append(np.broadcast_to(col[:, :, None], wrench.shape).ravel())
        vals.append(wrench.ravel())
    return sp.csr_matrix(
        (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
        shape=(6 * len(assembly.blocks), nc * dim),
    )


def build_model(assembly: Assembly, kind: ModelKind | Literal["auto"] = "auto", tol: float = 1e-9) -> Model:
    """Build the discrete operators of ``assembly``.

    Parameters
    ----------
    assembly : Assembly
        A validated assembly.
    kind : {"auto", "spatial", "planar"}
        ``auto`` picks ``planar`` when :func:`find_plane` finds a symmetry plane; whether a
        given load and settlement fit that plane is checked per solve.
    tol : float
        Relative tolerance of the planarity test.

    Raises
    ------
    ValueError
        ``kind="planar"`` on an assembly that is not planar.
    """
    if kind not in ("auto", "spatial", "planar"):
        raise ValueError(f"model kind must be 'auto', 'spatial' or 'planar', got {kind!r}")
    plane = find_plane(assembly, tol) if kind != "spatial" else None
    if kind == "planar" and plane is None:
        raise ValueError(
            "the assembly is not planar (no vertical symmetry plane with all centroids, interface "
            "normals and contact pairs in it): use the spatial model"
        )
    supports = set(assembly.support_indices)
    used = [
        k for k, i in enumerate(assembly.interfaces) if not (i.a in supports and i.b in supports)
    ]
    # all 3D vertices of the used interfaces
    v_itf = np.concatenate(
        [np.full(len(assembly.interfaces[k].points), k) for k in used]
    ).astype(np.int64)
    v_pts = np.vstack([assembly.interfaces[k].points for k in used])
    v_area = np.concatenate([assembly.interfaces[k].tributary for k in used])
    v_frame = np.stack([assembly.interfaces[k].frame for k in v_itf])  # (nv, 3, 3) rows n,t1,t2
    nv = len(v_itf)

    if plane is None:
        dim = 3
        directions = v_frame  # component j of contact k acts along v_frame[k, j]
        c_itf, c_pts, c_area = v_itf, v_pts, v_area
        tangents = v_frame[:, 1:, :]
        lift = sp.identity(3 * nv, format="csr")
        model_kind: ModelKind = "spatial"
    else:
        dim = 2
        groups = _contact_groups(assembly, plane, tol)
        assert groups is not None
        first = np.concatenate([[0], np.cumsum([len(assembly.interfaces[k].points) for k in used])])
        c_itf, c_pts, c_area, dirs, lr, lc, lv = [], [], [], [], [], [], []
        for pos, k in enumerate(used):
            itf = assembly.interfaces[k]
            n = itf.normal
            t = np.cross(plane.m, n)
            t /= np.linalg.norm(t)
            for idx in groups[k]:
                c = len(c_itf)
                w = itf.tributary[idx]
                share = w / w.sum() if w.sum() > 0 else np.full(len(idx), 1.0 / len(idx))
                c_itf.append(k)
                c_pts.append(itf.points[idx].mean(axis=0))
                c_area.append(w.sum())
                dirs.append(np.vstack([n, t]))
                # vertex force (fn, ft1, ft2) = share * (fn_c, ft_c * (t . t1), ft_c * (t . t2))
                proj = itf.frame[1:] @ t
                for vi, s in zip(first[pos] + idx, share):
                    lr += [3 * vi, 3 * vi + 1, 3 * vi + 2]
                    lc += [2 * c, 2 * c + 1, 2 * c + 1]
                    lv += [s, s * proj[0], s * proj[1]]
        c_itf = np.array(c_itf, dtype=np.int64)
        c_pts, c_area, directions = np.array(c_pts), np.array(c_area), np.array(dirs)
        tangents = directions[:, 1:, :]
        lift = sp.csr_matrix((lv, (lr, lc)), shape=(3 * nv, 2 * len(c_itf)))
        model_kind = "planar"

    W = _block_wrench_matrix(assembly, c_pts, directions, c_itf)
    free = np.array(assembly.free_indices)
    sup = np.array(assembly.support_indices)
    weights = assembly.weights
    if model_kind == "spatial":
        sel = (free[:, None] * 6 + np.arange(6)).ravel()
        A_eq = W[sel]
        b_dead = np.zeros((len(free), 6))
        b_dead[:, 2] = -weights[free]
        b_lat = np.zeros((len(free), 6, 2))
        b_lat[:, 0, 0] = weights[free]
        b_lat[:, 1, 1] = weights[free]
        # lateral loads act at the centroid: no moment about it
    else:
        e = plane.e
        basis = np.zeros((3, 6))
        basis[0, :3] = e
        basis[1, :3] = EZ
        basis[2, 3:] = plane.m
        blocks6 = W[(free[:, None] * 6 + np.arange(6)).ravel()]
        proj = sp.kron(sp.identity(len(free)), sp.csr_matrix(basis))
        A_eq = proj @ blocks6
        b_dead = np.zeros((len(free), 3))
        b_dead[:, 1] = -weights[free]
        b_lat = np.zeros((len(free), 3, 2))
        b_lat[:, 0, 0] = weights[free] * e[0]
        b_lat[:, 0, 1] = weights[free] * e[1]
    B_sup = -W[(sup[:, None] * 6 + np.arange(6)).ravel()]
    return Model(
        kind=model_kind,
        assembly=assembly,
        plane=plane,
        dim=dim,
        interfaces=tuple(used),
        contact_interface=c_itf,
        contact_points=c_pts,
        contact_area=c_area,
        tangents=tangents,
        A_eq=sp.csc_matrix(A_eq),
        b_dead=b_dead.ravel(),
        b_lat=b_lat.reshape(-1, 2),
        B_sup=sp.csr_matrix(B_sup),
        lift=sp.csr_matrix(lift),
        vertex_interface=v_itf,
        vertex_points=v_pts,
    )
