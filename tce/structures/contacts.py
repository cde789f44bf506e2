"""Contact detection between blocks, and a check for overlapping blocks.

Interfaces (docs/conventions.md): the planar contact polygon shared by blocks A and B, with
its unit normal pointing from A into B. Here A is always the block with the lower index and
the normal is A's outward face normal.

Detection (:func:`detect_interfaces`)
    Two faces are in contact when they are coplanar with opposite outward normals (angle
    between ``n_A`` and ``-n_B`` below ``angle_tol`` radians, every vertex of B's face
    within ``tol * L`` of A's face plane, ``L`` the larger of the two blocks' bounding-box
    diagonals) and their overlap, computed with shapely in A's face plane, has an area
    above ``min_area``. Faces and blocks may be non-convex; a non-convex overlap may give
    several interfaces for one face pair (one per piece). The overlap polygon is lifted
    back onto A's face plane, its vertices ordered counter-clockwise about the normal.
    Holes in an overlap are dropped (the outer loop is kept, with a warning in the log).
    Candidate block pairs come from a sweep-and-prune of their (slightly padded) bounding
    boxes, so the cost grows with the number of neighbours, not the square of the number
    of blocks.

Overlap check (:func:`check_overlaps`)
    For every pair of blocks whose bounding boxes overlap by more than the tolerance,
    the *test points* of each block are checked against the other: its vertices and edge
    midpoints, and, for a convex block, also its centroid and the centroids of its convex
    faces (all of which lie in the closed block). A test point lying inside the other block
    deeper than ``tol * L`` from every nearby face plane means the two volumes intersect.
    Inside-ness is exact for a convex block (its face half-spaces) and uses the
    generalised winding number otherwise. Not caught: interpenetrations with no test point
    strictly inside the other block (e.g. two non-convex blocks crossing edge through
    edge, or two identical non-convex blocks).

Lengths in m, areas in m^2.
"""

from __future__ import annotations

import logging
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import shapely
from numpy.typing import NDArray
from shapely.geometry import Polygon
from shapely.geometry.polygon import orient

from .assembly import Assembly, AssemblyError, Block, Interface
from .geometry import newell_normal

__all__ = ["block_pairs", "check_overlaps", "detect_interfaces"]

log = logging.getLogger(__name__)


@dataclass(frozen=True, eq=False)
class _BlockData:
    """Per-block arrays used by the detection and the overlap check."""

    block: Block

    @cached_property
    def vertices(self) -> NDArray[np.float64]:
        return self.block.shape.vertices

    @cached_property
    def size(self) -> float:
        return self.block.shape.size

    @cached_property
    def faces(self) -> list[NDArray[np.float64]]:
        return [self.block.shape.face_points(k) for k in range(len(self.block.shape.faces))]

    @cached_property
    def normals(self) -> NDArray[np.float64]:
        return self.block.shape.face_normals

    @cached_property
    def centres(self) -> NDArray[np.float64]:
        return np.array([f.mean(axis=0) for f in self.faces])

    @cached_property
    def offsets(self) -> NDArray[np.float64]:
        """``n . x`` of each face plane (through the mean of the face's vertices)."""
        return np.einsum("ij,ij->i", self.normals, self.centres)

    @cached_property
    def face_lo(self) -> NDArray[np.float64]:
        return np.array([f.min(axis=0) for f in self.faces])

    @cached_property
    def face_hi(self) -> NDArray[np.float64]:
        return np.array([f.max(axis=0) for f in self.faces])

    def convex(self, tol: float) -> bool:
        """True when every vertex lies on the inner side of every face plane (within tol * size)."""
        d = self.vertices @ self.normals.T - self.offsets
        return bool(d.max() <= tol * self.size)

    @cached_property
    def edge_midpoints(self) -> NDArray[np.float64]:
        v = self.vertices
        mids = {}
        for f in self.block.shape.faces:
            for i, j in zip(f, f[1:] + f[:1]):
                key = (min(i, j), max(i, j))
                mids[key] = 0.5 * (v[i] + v[j])
        return np.array(list(mids.values()))

    @cached_property
    def triangles(self) -> NDArray[np.float64]:
        """Fan triangles of the faces, (nt, 3, 3), for the winding number."""
        tris = [np.stack([np.repeat(f[:1], len(f) - 2, axis=0), f[1:-1], f[2:]], axis=1) for f in self.faces]
        return np.concatenate(tris, axis=0)


def _blocks_of(assembly_or_blocks: Assembly | Sequence[Block]) -> tuple[Block, ...]:
    if isinstance(assembly_or_blocks, Assembly):
        return assembly_or_blocks.blocks
    return tuple(assembly_or_blocks)


def block_pairs(lo: NDArray[np.float64], hi: NDArray[np.float64]) -> NDArray[np.int64]:
    """Pairs ``(i, j)``, ``i < j``, of boxes ``[lo, hi]`` that overlap (touching counts).

    Sweep and prune along the axis that gives the fewest candidates; the boxes should be
    padded by the caller for a tolerance.

    Parameters
    ----------
    lo, hi : (n, 3) ndarray
        Lower and upper corners of the axis-aligned boxes (m).

    Returns
    -------
    (k, 2) ndarray of int
    """
    n = len(lo)
    if n < 2:
        return np.zeros((0, 2), dtype=np.int64)
    best = None
    for ax in range(3):
        order = np.argsort(lo[:, ax], kind="stable")
        ends = np.searchsorted(lo[order, ax], hi[order, ax], side="right")
        count = int(np.maximum(ends - np.arange(n) - 1, 0).sum())
        if best is None or count < best[0]:
            best = (count, order, ends)
    _, order, ends = best
    out = []
    for r in range(n):
        if ends[r] <= r + 1:
            continue
        i = order[r]
        ks = order[r + 1 : ends[r]]
        ok = np.all((lo[ks] <= hi[i]) & (hi[ks] >= lo[i]), axis=1)
        ks = ks[ok]
        if len(ks):
            out.append(np.column_stack([np.minimum(i, ks), np.maximum(i, ks)]))
    if not out:
        return np.zeros((0, 2), dtype=np.int64)
    pairs = np.concatenate(out)
    return pairs[np.lexsort((pairs[:, 1], pairs[:, 0]))]


def _padded_boxes(data: Sequence[_BlockData], tol: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    lo = np.array([d.vertices.min(axis=0) for d in data])
    hi = np.array([d.vertices.max(axis=0) for d in data])
    pad = np.array([tol * d.size for d in data])[:, None]
    return lo - pad, hi + pad


@dataclass(frozen=True)
class _FaceTable:
    """All faces of all blocks, flattened.

    ``loop`` holds global vertex indices of the faces, one after the other; face ``f`` is
    ``loop[start[f]:start[f + 1]]`` and belongs to block ``block[f]``; the faces of block
    ``b`` are ``first[b]:first[b + 1]``.
    """

    points: NDArray[np.float64]
    loop: NDArray[np.int64]
    start: NDArray[np.int64]
    block: NDArray[np.int64]
    first: NDArray[np.int64]
    normal: NDArray[np.float64]
    centre: NDArray[np.float64]
    lo: NDArray[np.float64]
    hi: NDArray[np.float64]

    @property
    def offset(self) -> NDArray[np.float64]:
        return np.einsum("ij,ij->i", self.normal, self.centre)


def _face_table(blocks: Sequence[Block]) -> _FaceTable:
    pts, loops, counts, owner, nfaces = [], [], [], [], []
    base = 0
    for b, blk in enumerate(blocks):
        v = blk.shape.vertices
        pts.append(v)
        for f in blk.shape.faces:
            loops.append(np.asarray(f, dtype=np.int64) + base)
            counts.append(len(f))
        owner.append(np.full(len(blk.shape.faces), b, dtype=np.int64))
        nfaces.append(len(blk.shape.faces))
        base += len(v)
    P = np.vstack(pts)
    loop = np.concatenate(loops)
    counts = np.asarray(counts, dtype=np.int64)
    start = np.concatenate([[0], np.cumsum(counts)])
    seg = start[:-1]
    fid = np.repeat(np.arange(len(counts)), counts)
    q = P[loop]
    centre = np.add.reduceat(q, seg, axis=0) / counts[:, None]
    r = q - centre[fid]
    pos = np.arange(len(loop)) - seg[fid]
    nxt = seg[fid] + (pos + 1) % counts[fid]
    nv = np.add.reduceat(np.cross(r, r[nxt]), seg, axis=0)
    norm = np.linalg.norm(nv, axis=1)
    normal = nv / np.where(norm > 0, norm, 1.0)[:, None]
    lo = np.minimum.reduceat(q, seg, axis=0)
    hi = np.maximum.reduceat(q, seg, axis=0)
    first = np.concatenate([[0], np.cumsum(nfaces)]).astype(np.int64)
    return _FaceTable(P, loop, start, np.concatenate(owner), first, normal, centre, lo, hi)


def _frames(n: NDArray[np.float64]) -> NDArray[np.float64]:
    """Vectorised :func:`tce.geometry.frame_from_normal`: (k, 3, 3), rows (n, t1, t2)."""
    ez = np.array([0.0, 0.0, 1.0])
    t1 = ez - n[:, 2:3] * n
    flat = np.linalg.norm(t1, axis=1) < 1e-6
    if flat.any():
        ex = np.array([1.0, 0.0, 0.0])
        t1[flat] = ex - n[flat, 0:1] * n[flat]
    t1 /= np.linalg.norm(t1, axis=1)[:, None]
    t2 = np.cross(n, t1)
    return np.stack([n, t1, t2], axis=1)


def _ragged(start: NDArray[np.int64], faces: NDArray[np.int64]) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    """Positions in the flat loop array of the vertices of ``faces``, and their row in ``faces``."""
    counts = start[faces + 1] - start[faces]
    row = np.repeat(np.arange(len(faces)), counts)
    first = np.concatenate([[0], np.cumsum(counts)[:-1]])
    pos = start[faces][row] + np.arange(counts.sum()) - first[row]
    return pos, row


def _polygons(xy: NDArray[np.float64], row: NDArray[np.int64]) -> NDArray[np.object_]:
    polys = shapely.polygons(shapely.linearrings(xy, indices=row))
    bad = ~shapely.is_valid(polys)
    if bad.any():
        polys[bad] = shapely.make_valid(polys[bad])
    return polys


def _pieces(geom: object) -> list[Polygon]:
    out: list[Polygon] = []
    for g in getattr(geom, "geoms", [geom]):
        if isinstance(g, Polygon):
            out.append(g)
        elif hasattr(g, "geoms"):
            out.extend(_pieces(g))
    return out


def _lift(poly: Polygon, frame: NDArray[np.float64], origin: NDArray[np.float64], eps: float) -> NDArray[np.float64]:
    """Outer loop of a 2D polygon, counter-clockwise about the frame normal, back in 3D."""
    poly = orient(poly, 1.0)
    xy = np.asarray(poly.exterior.coords)[:-1]
    keep = [0]
    for k in range(1, len(xy)):
        if np.linalg.norm(xy[k] - xy[keep[-1]]) > eps:
            keep.append(k)
    if len(keep) > 1 and np.linalg.norm(xy[keep[-1]] - xy[keep[0]]) <= eps:
        keep.pop()
    xy = xy[keep]
    return origin + xy @ frame[1:]


def detect_interfaces(
    assembly_or_blocks: Assembly | Sequence[Block],
    tol: float = 1e-6,
    min_area: float | None = None,
    angle_tol: float | None = None,
) -> list[Interface]:
    """Find the contact interfaces between blocks (see module docstring).

    Parameters
    ----------
    assembly_or_blocks : Assembly or sequence of Block
        The blocks; an assembly's existing interfaces are ignored.
    tol : float
        Relative distance tolerance: a face vertex is on a plane when closer than
        ``tol * L`` (m), ``L`` the larger bounding-box diagonal of the two blocks.
    min_area : float, optional
        Smallest overlap area kept (m^2); defaults to ``tol * l**2``, ``l`` the smaller
        block diagonal of the pair.
    angle_tol : float, optional
        Largest angle (rad) between ``n_A`` and ``-n_B``; defaults to ``max(tol, 1e-9)``.

    Returns
    -------
    list of Interface
        Sorted by ``(a, b)``, with ``a < b`` and the normal from A into B.
    """
    if not (np.isfinite(tol) and tol > 0):
        raise ValueError(f"tol must be a finite number > 0, got {tol!r}")
    if min_area is not None and not (np.isfinite(min_area) and min_area >= 0):
        raise ValueError(f"min_area must be a finite number >= 0, got {min_area!r}")
    atol = max(tol, 1e-9) if angle_tol is None else float(angle_tol)
    if not (np.isfinite(atol) and atol >= 0):
        raise ValueError(f"angle_tol must be a finite number >= 0, got {angle_tol!r}")
    cos_tol = np.cos(atol)
    blocks = _blocks_of(assembly_or_blocks)
    if len(blocks) < 2:
        return []
    T = _face_table(blocks)
    size = np.array([b.shape.size for b in blocks])
    lo = np.array([b.shape.vertices.min(axis=0) for b in blocks]) - (tol * size)[:, None]
    hi = np.array([b.shape.vertices.max(axis=0) for b in blocks]) + (tol * size)[:, None]
    pairs = block_pairs(lo, hi)
    if not len(pairs):
        return []
    # every face of block i against every face of block j, for each candidate pair
    nf = np.diff(T.first)
    na, nb = nf[pairs[:, 0]], nf[pairs[:, 1]]
    rep = na * nb
    pid = np.repeat(np.arange(len(pairs)), rep)
    local = np.arange(rep.sum()) - np.repeat(np.concatenate([[0], np.cumsum(rep)[:-1]]), rep)
    fa = T.first[pairs[pid, 0]] + local // nb[pid]
    fb = T.first[pairs[pid, 1]] + local % nb[pid]
    keep = np.einsum("ij,ij->i", T.normal[fa], T.normal[fb]) <= -cos_tol
    fa, fb, pid = fa[keep], fb[keep], pid[keep]
    eps = tol * np.maximum(size[pairs[pid, 0]], size[pairs[pid, 1]])
    offset = T.offset
    keep = np.abs(np.einsum("ij,ij->i", T.normal[fa], T.centre[fb]) - offset[fa]) <= eps
    keep &= np.all((T.lo[fa] <= T.hi[fb] + eps[:, None]) & (T.lo[fb] <= T.hi[fa] + eps[:, None]), axis=1)
    fa, fb, pid, eps = fa[keep], fb[keep], pid[keep], eps[keep]
    if not len(fa):
        return []
    # every vertex of B's face on A's plane
    posb, rowb = _ragged(T.start, fb)
    db = np.abs(np.einsum("ij,ij->i", T.points[T.loop[posb]], T.normal[fa][rowb]) - offset[fa][rowb])
    worst = np.zeros(len(fb))
    np.maximum.at(worst, rowb, db)
    keep = worst <= eps
    fa, fb, pid, eps = fa[keep], fb[keep], pid[keep], eps[keep]
    if not len(fa):
        return []
    # overlap in A's face plane (2D frame of A's normal, origin at A's face centre)
    frames = _frames(T.normal[fa])
    origin = T.centre[fa]
    posa, rowa = _ragged(T.start, fa)
    posb, rowb = _ragged(T.start, fb)
    xya = np.einsum("kj,kij->ki", T.points[T.loop[posa]] - origin[rowa], frames[rowa, 1:])
    xyb = np.einsum("kj,kij->ki", T.points[T.loop[posb]] - origin[rowb], frames[rowb, 1:])
    inter = shapely.intersection(_polygons(xya, rowa), _polygons(xyb, rowb))
    area = shapely.area(inter)
    smaller = np.minimum(size[pairs[pid, 0]], size[pairs[pid, 1]])
    amin = tol * smaller**2 if min_area is None else np.full(len(fa), float(min_area))
    found: list[Interface] = []
    for k in np.flatnonzero(area > amin):
        i, j = (int(x) for x in pairs[pid[k]])
        for piece in _pieces(inter[k]):
            if piece.area <= amin[k]:
                continue
            if len(piece.interiors):
                log.warning(
                    "contact between %r and %r has a hole; only its outer loop is kept",
                    blocks[i].name, blocks[j].name,
                )
            pts = _lift(piece, frames[k], origin[k], 1e-9 * eps[k] / tol)
            if len(pts) >= 3:
                found.append(Interface(i, j, pts, T.normal[fa[k]]))
    found.sort(key=lambda itf: (itf.a, itf.b))
    log.info(
        "detect_interfaces: %d blocks, %d coplanar face pairs, %d interfaces", len(blocks), len(fa), len(found)
    )
    return found


def _winding_numbers(tris: NDArray[np.float64], pts: NDArray[np.float64]) -> NDArray[np.float64]:
    """Generalised winding number of a closed triangle soup at each point (van Oosterom-Strackee)."""
    out = np.empty(len(pts))
    for k, p in enumerate(pts):
        a, b, c = tris[:, 0] - p, tris[:, 1] - p, tris[:, 2] - p
        la, lb, lc = (np.linalg.norm(x, axis=1) for x in (a, b, c))
        num = np.einsum("ij,ij->i", a, np.cross(b, c))
        den = (
            la * lb * lc
            + np.einsum("ij,ij->i", a, b) * lc
            + np.einsum("ij,ij->i", b, c) * la
            + np.einsum("ij,ij->i", c, a) * lb
        )
        out[k] = 2.0 * np.arctan2(num, den).sum() / (4.0 * np.pi)
    return out


def _test_points(d: _BlockData, tol: float) -> NDArray[np.float64]:
    pts = [d.vertices, d.edge_midpoints]
    if d.convex(tol):
        pts.append(d.block.centroid[None, :])
        pts.append(d.centres)
    else:
        for f in d.faces:  # centroids of convex faces only
            n = newell_normal(f)
            e = np.roll(f, -1, axis=0) - f
            turn = np.cross(e, np.roll(e, -1, axis=0)) @ n
            if np.all(turn >= -tol * d.size**2):
                pts.append(f.mean(axis=0)[None, :])
    return np.vstack(pts)


def _inside_depth(d: _BlockData, pts: NDArray[np.float64], eps: float, convex: bool) -> NDArray[np.float64]:
    """Depth (m) of each point inside block ``d`` (<= 0 when outside or on its surface)."""
    s = d.offsets[None, :] - pts @ d.normals.T  # > 0 on the inner side of each face plane
    if convex:
        return s.min(axis=1)
    w = _winding_numbers(d.triangles, pts)
    depth = np.full(len(pts), -np.inf)
    for k in np.flatnonzero(w > 0.5):
        # lower bound of the distance to each face: the larger of the distances to its
        # plane and to its bounding box
        gap = np.maximum(d.face_lo - pts[k], pts[k] - d.face_hi).clip(min=0.0)
        depth[k] = np.maximum(np.abs(s[k]), np.linalg.norm(gap, axis=1)).min()
    return depth


def check_overlaps(assembly_or_blocks: Assembly | Sequence[Block], tol: float = 1e-6) -> None:
    """Raise if two blocks' volumes intersect (see module docstring for what is checked).

    Parameters
    ----------
    assembly_or_blocks : Assembly or sequence of Block
    tol : float
        Relative tolerance: a point must lie deeper than ``tol * L`` inside the other block
        (``L`` the larger bounding-box diagonal of the pair).

    Raises
    ------
    AssemblyError
        Naming both blocks and the depth of the deepest test point.
    """
    blocks = _blocks_of(assembly_or_blocks)
    data = [_BlockData(b) for b in blocks]
    lo, hi = _padded_boxes(data, -tol)
    convex = [d.convex(tol) for d in data]
    tests = [None] * len(data)
    for i, j in block_pairs(lo, hi):
        eps = tol * max(data[i].size, data[j].size)
        for x, y in ((i, j), (j, i)):
            if tests[y] is None:
                tests[y] = _test_points(data[y], tol)
            p = tests[y]
            box = np.all((p > lo[x]) & (p < hi[x]), axis=1)
            if not box.any():
                continue
            depth = _inside_depth(data[x], p[box], eps, convex[x])
            if depth.max() > eps:
                raise AssemblyError(
                    f"blocks {blocks[x].name!r} and {blocks[y].name!r} overlap: a point of "
                    f"{blocks[y].name!r} lies {depth.max():.3g} m inside {blocks[x].name!r}"
                )
