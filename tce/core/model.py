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

from .. import display
from ..structures.assembly import Assembly
from ..structures.geometry import lateral_direction

__all__ = [
    "InterfaceMap",
    "Model",
    "Plane",
    "build_model",
    "find_plane",
    "motions_in_plane",
]

ModelKind = Literal["spatial", "planar"]
EZ = np.array([0.0, 0.0, 1.0])


@dataclass(frozen=True)
class Plane:
    """A vertical symmetry plane of an assembly: normal ``m`` (horizontal), through ``origin``."""

    m: NDArray[np.float64]
    origin: NDArray[np.float64]

    @property
    def e(self) -> NDArray[np.float64]:
        """In-plane horizontal unit vector ``m x z`` (``+x`` for the plane normal to ``+y``)."""
        return np.cross(self.m, EZ)


def _contact_groups(assembly: Assembly, plane: Plane, tol: float) -> tuple[NDArray[np.bool_], NDArray[np.bool_]] | None:
    """Which interface vertices project on the low and on the high end of their interface's trace.

    Returns the masks ``(at_lo, at_hi)`` over all interface vertices
    (:attr:`tce.structures.assembly.InterfaceTable.points` order), or None if some interface
    cannot be reduced exactly (normal out of plane, a trace of no length, a vertex
    projecting inside the trace, or a group not balanced about the plane).
    """
    t = assembly.interface_table
    if not len(t):
        return np.zeros(0, dtype=bool), np.zeros(0, dtype=bool)
    if np.any(np.abs(t.normal @ plane.m) > tol):
        return None
    owner, start = t.vertex_interface, t.start[:-1]
    eps = tol * assembly.size
    rel = t.points - plane.origin
    off = rel @ plane.m
    s = np.einsum("ij,ij->i", rel, np.cross(plane.m[None, :], t.normal)[owner])
    lo, hi = np.minimum.reduceat(s, start), np.maximum.reduceat(s, start)
    if np.any(hi - lo <= eps):
        return None
    at_lo = np.abs(s - lo[owner]) <= eps
    at_hi = np.abs(s - hi[owner]) <= eps
    if not np.all(at_lo | at_hi):
        return None
    w = t.tributary
    for mask in (at_lo, at_hi):
        moment = np.bincount(owner[mask], weights=(w * off)[mask], minlength=len(t))
        area = np.bincount(owner[mask], weights=w[mask], minlength=len(t))
        if np.any(np.abs(moment) > eps * np.maximum(area, 1e-300)):
            return None
    return at_lo, at_hi


def _plan_line_normal(rel: NDArray[np.float64]) -> NDArray[np.float64] | None:
    """Horizontal unit normal of the vertical plane that best fits points ``rel`` (relative
    to their mean) in plan: across their principal plan direction; None when they do not
    spread in plan. Its sign makes the first non-zero of ``(m_y, m_x)`` positive, so a
    structure and its copy turned by 180 degrees get the same plane."""
    xy = rel[:, :2]
    if len(xy) < 2 or not np.any(xy):
        return None
    d = np.linalg.svd(xy, full_matrices=False)[2][0]
    if d[0] < 0 or (d[0] == 0 and d[1] > 0):
        return np.array([d[1], -d[0], 0.0])
    return np.array([-d[1], d[0], 0.0])


def find_plane(assembly: Assembly, tol: float = 1e-9) -> Plane | None:
    """The vertical plane of symmetry that makes the assembly planar, if any.

    Candidates are the vertical planes normal to y and to x through the mean block
    centroid, then the vertical plane through the centroids' principal direction in plan
    (a structure turned about z by any angle). A plane qualifies when every block centroid
    lies in it, every interface normal lies in it, and every interface reduces exactly to
    two contacts (see module docstring). ``tol`` is relative to the assembly size.
    """
    c = assembly.centroids
    origin = c.mean(axis=0)
    fitted = _plan_line_normal(c - origin)
    candidates = [np.array([0.0, 1.0, 0.0]), np.array([1.0, 0.0, 0.0])] + ([fitted] if fitted is not None else [])
    for m in candidates:
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
    supports : tuple of str
        Support block names, in the order of the rows of ``B_sup`` (the labels of a result's
        support wrenches).
    labels : tuple of str
        ``"A|B"`` block names of each slot's interface.
    """

    interfaces: tuple[int, ...]
    lift: sp.csr_matrix
    vertex_slot: NDArray[np.int64]
    vertex_points: NDArray[np.float64]
    vertex_frames: NDArray[np.float64]
    normals: NDArray[np.float64]
    B_sup: sp.csr_matrix
    supports: tuple[str, ...] = ()
    labels: tuple[str, ...] = ()

    def __repr__(self) -> str:
        return display.call("InterfaceMap", {}, head=f"{len(self.interfaces)} interfaces, "
                            f"{len(self.vertex_points)} vertices, supports {display.names(self.supports)}")


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

    def __repr__(self) -> str:
        return display.call("Model", {}, head=f"{self.kind}, {self.n_contacts} contacts x {self.dim} force "
                            f"components, {self.A_eq.shape[0]} equilibrium rows, {len(self.interfaces)} interfaces")

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
    def contact_kind(self) -> NDArray[np.object_]:
        """Interface kind of each contact (:attr:`tce.structures.assembly.Interface.kind`), (nc,)."""
        return self.assembly.interface_table.kind[self.contact_interface]

    @cached_property
    def vertex_frames(self) -> NDArray[np.float64]:
        """Interface frame of every 3D vertex, (nv, 3, 3), rows ``(n, t1, t2)``."""
        return self.assembly.interface_table.frame[self.vertex_interface]

    @cached_property
    def vertex_slot(self) -> NDArray[np.int64]:
        """Position in ``interfaces`` of each 3D vertex's interface."""
        slot = np.full(len(self.assembly.interfaces), -1, dtype=np.int64)
        slot[list(self.interfaces)] = np.arange(len(self.interfaces))
        return slot[self.vertex_interface]

    @cached_property
    def interface_map(self) -> InterfaceMap:
        """The arrays results need to report vertex forces, resultants and support wrenches."""
        normals = self.assembly.interface_table.normal[list(self.interfaces)].reshape(-1, 3)
        a = self.assembly
        labels = tuple(f"{a.names[a.interfaces[k].a]}|{a.names[a.interfaces[k].b]}" for k in self.interfaces)
        return InterfaceMap(
            self.interfaces, self.lift, self.vertex_slot, self.vertex_points, self.vertex_frames, normals, self.B_sup,
            a.support_names, labels,
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
        stiffness multiplier (:attr:`tce.structures.assembly.Interface.stiffness`).
        """
        factor = self.assembly.interface_table.stiffness[self.contact_interface]
        area = np.maximum(self.contact_area * factor, np.finfo(float).tiny)
        k = np.array([normal_stiffness] + [shear_stiffness] * (self.dim - 1))
        return (1.0 / (area[:, None] * k[None, :])).ravel()


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


def _wrench_operators(
    assembly: Assembly,
    points: NDArray[np.float64],
    directions: NDArray[np.float64],
    contact_interface: NDArray[np.int64],
    basis: NDArray[np.float64] | None = None,
) -> tuple[sp.csc_matrix, sp.csr_matrix]:
    """Equilibrium rows of the free blocks and support wrenches of unit force components.

    ``directions[k, j]`` is the global direction of force component ``j`` of contact ``k``
    (at ``points[k]``, on interface ``contact_interface[k]``); the force acts with + on
    block B and - on block A of that interface. The wrench ``(F, M)`` on a block is about
    its centroid. ``A_eq`` stacks, per free block, the wrench projected on ``basis`` (rows;
    identity for the spatial model); ``B_sup``, per support, minus the full wrench on it (the
    wrench the support exerts on the structure). Both are assembled in one call each.

    Returns
    -------
    A_eq : (r * n_free, nc * dim) CSC
    B_sup : (6 * n_sup, nc * dim) CSR
    """
    nc, dim = directions.shape[:2]
    t = assembly.interface_table
    nb = len(assembly.blocks)
    is_sup = np.zeros(nb, dtype=bool)
    is_sup[list(assembly.support_indices)] = True
    rank = np.empty(nb, dtype=np.int64)  # position among the free blocks, or among the supports
    rank[~is_sup] = np.arange(nb - is_sup.sum())
    rank[is_sup] = np.arange(is_sup.sum())
    r = 6 if basis is None else len(basis)
    col = np.broadcast_to((np.arange(nc)[:, None] * dim + np.arange(dim)[None, :])[:, :, None], (nc, dim, 6))
    eq: list[tuple[NDArray, NDArray, NDArray]] = []
    sup: list[tuple[NDArray, NDArray, NDArray]] = []
    for block, sign in ((t.b[contact_interface], 1.0), (t.a[contact_interface], -1.0)):
        arm = points - assembly.centroids[block]
        wrench = sign * np.concatenate([directions, np.cross(arm[:, None, :], directions)], axis=2)  # (nc, dim, 6)
        free, on_sup = ~is_sup[block], is_sup[block]
        w6 = wrench[on_sup]
        rows6 = rank[block[on_sup]][:, None, None] * 6 + np.arange(6)
        sup.append((np.broadcast_to(rows6, w6.shape).ravel(), col[on_sup].ravel(), -w6.ravel()))
        wf = wrench[free] if basis is None else wrench[free] @ basis.T  # (k, dim, r)
        rows = rank[block[free]][:, None, None] * r + np.arange(r)
        eq.append((np.broadcast_to(rows, wf.shape).ravel(), col[free][:, :, :r].ravel(), wf.ravel()))

    def assemble(parts: list, shape: tuple[int, int], fmt: type) -> sp.spmatrix:
        rows, cols, vals = (np.concatenate(x) for x in zip(*parts))
        keep = vals != 0.0  # exact zeros (components along a zero axis) would only widen the KKT system
        return fmt((vals[keep], (rows[keep], cols[keep])), shape=shape)

    A_eq = assemble(eq, (r * int((~is_sup).sum()), nc * dim), sp.csc_matrix)
    B_sup = assemble(sup, (6 * int(is_sup.sum()), nc * dim), sp.csr_matrix)
    return A_eq, B_sup


def build_model(assembly: Assembly, kind: ModelKind | Literal["auto"] = "auto", tol: float = 1e-9) -> Model:
    """Build the discrete operators of ``assembly``.

    Every operator is computed over all interfaces and contacts at once and assembled as a
    sparse matrix in one call (cost linear in the number of contacts).

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
    t = assembly.interface_table
    is_sup = np.zeros(len(assembly.blocks), dtype=bool)
    is_sup[list(assembly.support_indices)] = True
    used = np.flatnonzero(~(is_sup[t.a] & is_sup[t.b]))  # interfaces between two supports carry nothing
    # all 3D vertices of the used interfaces
    v_sel = np.flatnonzero(np.isin(t.vertex_interface, used))
    v_itf = t.vertex_interface[v_sel]
    v_pts = t.points[v_sel]
    v_area = t.tributary[v_sel]
    v_frame = t.frame[v_itf]  # (nv, 3, 3) rows n, t1, t2
    nv = len(v_itf)

    if plane is None:
        dim = 3
        directions = v_frame  # component j of contact k acts along v_frame[k, j]
        c_itf, c_pts, c_area = v_itf, v_pts, v_area
        tangents = v_frame[:, 1:, :]
        lift = sp.identity(3 * nv, format="csr")
        model_kind: ModelKind = "spatial"
        basis = None
    else:
        dim = 2
        groups = _contact_groups(assembly, plane, tol)
        assert groups is not None
        slot = np.full(len(t), -1)
        slot[used] = np.arange(len(used))
        # memberships (vertex among v_sel, contact): contact 2 * slot + 0 (low end) or + 1 (high end)
        member_v, member_c = [], []
        for g, mask in enumerate(groups):
            vi = np.flatnonzero(mask[v_sel])
            member_v.append(vi)
            member_c.append(2 * slot[v_itf[vi]] + g)
        mv, mc = np.concatenate(member_v), np.concatenate(member_c)
        order = np.lexsort((mv, mc))  # contact by contact, vertices in order
        mv, mc = mv[order], mc[order]
        nc = 2 * len(used)
        count = np.bincount(mc, minlength=nc)
        w = v_area[mv]
        c_area = np.bincount(mc, weights=w, minlength=nc)
        c_pts = np.stack([np.bincount(mc, weights=v_pts[mv, j], minlength=nc) for j in range(3)], axis=1) / count[:, None]
        share = np.where(c_area[mc] > 0, w / np.where(c_area[mc] > 0, c_area[mc], 1.0), 1.0 / count[mc])
        c_itf = np.repeat(used, 2)
        n = t.normal[c_itf]
        tan = np.cross(plane.m[None, :], n)
        tan /= np.linalg.norm(tan, axis=1)[:, None]
        directions = np.stack([n, tan], axis=1)  # (nc, 2, 3)
        tangents = directions[:, 1:, :]
        # vertex force (fn, ft1, ft2) = share * (fn_c, ft_c * (t . t1), ft_c * (t . t2))
        proj = np.einsum("kij,kj->ki", t.frame[c_itf][:, 1:, :], tan)  # (nc, 2)
        lr = (3 * mv[:, None] + np.arange(3)).ravel()
        lc = np.stack([2 * mc, 2 * mc + 1, 2 * mc + 1], axis=1).ravel()
        lv = np.stack([share, share * proj[mc, 0], share * proj[mc, 1]], axis=1).ravel()
        lift = sp.csr_matrix((lv, (lr, lc)), shape=(3 * nv, 2 * nc))
        model_kind = "planar"
        basis = np.zeros((3, 6))
        basis[0, :3] = plane.e
        basis[1, :3] = EZ
        basis[2, 3:] = plane.m

    A_eq, B_sup = _wrench_operators(assembly, c_pts, directions, c_itf, basis)
    free = np.array(assembly.free_indices)
    weights = assembly.weights[free]
    if model_kind == "spatial":
        b_dead = np.zeros((len(free), 6))
        b_dead[:, 2] = -weights
        b_lat = np.zeros((len(free), 6, 2))
        b_lat[:, 0, 0] = weights
        b_lat[:, 1, 1] = weights
        # lateral loads act at the centroid: no moment about it
    else:
        e = plane.e
        b_dead = np.zeros((len(free), 3))
        b_dead[:, 1] = -weights
        b_lat = np.zeros((len(free), 3, 2))
        b_lat[:, 0, 0] = weights * e[0]
        b_lat[:, 0, 1] = weights * e[1]
    return Model(
        kind=model_kind,
        assembly=assembly,
        plane=plane,
        dim=dim,
        interfaces=tuple(used.tolist()),
        contact_interface=c_itf,
        contact_points=c_pts,
        contact_area=c_area,
        tangents=tangents,
        A_eq=A_eq,
        b_dead=b_dead.ravel(),
        b_lat=b_lat.reshape(-1, 2),
        B_sup=B_sup,
        lift=lift,
        vertex_interface=v_itf,
        vertex_points=v_pts,
    )
