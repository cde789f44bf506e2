"""Contact detection between blocks, and a check for overlapping blocks.

Interfaces (docs/conventions.md): the planar contact polygon shared by blocks A and B, with
its unit normal pointing from A into B. Here A is always the block with the lower index and
the normal is A's outward face normal.

Detection (:func:`detect_interfaces`)
    Two faces are in contact when they are coplanar with opposite outward normals (angle
    between ``n_A`` and ``-n_B`` below ``angle_tol`` radians, every vertex of B's face
    within ``tol * L`` of A's face plane, ``L`` the larger of the two blocks' bounding-box
    diagonals) and their overlap, computed with shapely in A's face plane, has an area
    above ``min_area``. Faces and blocks may be non-convex; a non-convex overlap gives one
    interface per piece. The overlap polygon is lifted back onto A's face plane, its
    vertices counter-clockwise about the normal; holes are dropped (the outer loop is kept,
    with a warning in the log). Candidate block pairs come from a sweep-and-prune of their
    (slightly padded) bounding boxes.

Overlap check (:func:`check_overlaps`)
    For every pair of blocks whose bounding boxes overlap by more than the tolerance,
    the *test points* of each block are checked against the other: its vertices and edge
    midpoints, its centroid if convex, and the centroids of its convex faces. A test point
    inside the other block deeper than ``tol * L`` from every nearby face plane means the
    two volumes intersect. Inside-ness is exact for a convex block (its face half-spaces)
    and uses the generalised winding number otherwise. Not caught: interpenetrations with
    no test point strictly inside the other block (e.g. two non-convex blocks crossing edge
    through edge, or two identical non-convex blocks).

Lengths in m, areas in m^2.
"""

from __future__ import annotations

import logging
from collections.abc import Sequence

import numpy as np
import shapely
from numpy.typing import NDArray

from .assembly import Assembly, AssemblyError, Block, Interface
from .geometry import FaceTable, _ring, frames_from_normals

__all__ = ["block_pairs", "check_overlaps", "detect_interfaces"]

log = logging.getLogger(__name__)


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
    # candidates of the box at sorted position r: those at positions r + 1 .. ends[r] - 1
    extra = np.maximum(ends - np.arange(n) - 1, 0)
    r = np.repeat(np.arange(n), extra)
    cand = r + 1 + np.arange(extra.sum()) - np.repeat(np.cumsum(extra) - extra, extra)
    i, k = order[r], order[cand]
    ok = np.all((lo[k] <= hi[i]) & (hi[k] >= lo[i]), axis=1)
    i, k = i[ok], k[ok]
    pairs = np.column_stack([np.minimum(i, k), np.maximum(i, k)]).astype(np.int64)
    return pairs[np.lexsort((pairs[:, 1], pairs[:, 0]))]


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


def _flat_polygons(geoms: NDArray[np.object_]) -> tuple[NDArray[np.object_], NDArray[np.int64]]:
    """The polygons inside each geometry (collections flattened depth first, other kinds
    dropped), and the index of the geometry each came from."""
    index = np.arange(len(geoms))
    while True:
        multi = shapely.get_num_geometries(geoms) > 1
        multi |= np.isin(shapely.get_type_id(geoms), (4, 5, 6, 7))  # collections of one part
        if not multi.any():
            break
        geoms, idx = shapely.get_parts(geoms, return_index=True)
        index = index[idx]
    poly = shapely.get_type_id(geoms) == 3
    return geoms[poly], index[poly]


def _lift(
    pieces: NDArray[np.object_], frames: NDArray[np.float64], origins: NDArray[np.float64], eps: NDArray[np.float64]
) -> list[NDArray[np.float64]]:
    """Outer loops of 2D polygons, counter-clockwise about their frame normals, back in 3D.

    A vertex closer than ``eps`` to the last vertex kept is dropped, and so is a last vertex
    that close to the first.
    """
    ring = shapely.get_exterior_ring(pieces)
    xy, owner = shapely.get_coordinates(ring, return_index=True)
    counts = np.bincount(owner, minlength=len(pieces))
    last = np.cumsum(counts) - 1
    keep = np.ones(len(xy), dtype=bool)
    keep[last] = False  # the closing repeat of the first vertex
    x, y = xy[:, 0], xy[:, 1]
    nxt = np.minimum(np.arange(len(xy)) + 1, len(xy) - 1)
    twice = np.bincount(owner, weights=np.where(keep, x * y[nxt] - x[nxt] * y, 0.0), minlength=len(pieces))
    xy, owner, counts = xy[keep], owner[keep], counts - 1
    start = np.concatenate([[0], np.cumsum(counts)])
    # counter-clockwise: a loop of negative shoelace area is reversed (keeping its first vertex)
    pos = np.arange(len(xy)) - start[owner]
    order = start[owner] + np.where(twice[owner] < 0, (counts[owner] - pos) % counts[owner], pos)
    xy = xy[order]
    # loops with a vertex within eps of its predecessor (cyclically) need the sequential rule
    prev = start[owner] + (pos - 1) % counts[owner]
    close = np.linalg.norm(xy - xy[prev], axis=1) <= eps[owner]
    redo = np.bincount(owner[close], minlength=len(pieces)) > 0
    pts = origins[owner] + np.einsum("kj,kji->ki", xy, frames[owner, 1:])
    loops = np.split(pts, start[1:-1])
    for k in np.flatnonzero(redo):
        loops[k] = origins[k] + _drop_close(xy[start[k] : start[k + 1]], eps[k]) @ frames[k, 1:]
    return loops


def _drop_close(xy: NDArray[np.float64], eps: float) -> NDArray[np.float64]:
    """``xy`` without the vertices within ``eps`` of the last one kept (and a last one within
    ``eps`` of the first)."""
    keep = [0]
    for k in range(1, len(xy)):
        if np.linalg.norm(xy[k] - xy[keep[-1]]) > eps:
            keep.append(k)
    if len(keep) > 1 and np.linalg.norm(xy[keep[-1]] - xy[keep[0]]) <= eps:
        keep.pop()
    return xy[keep]


def _pairs_within(first: NDArray[np.int64], count_a: NDArray[np.int64], count_b: NDArray[np.int64],
                  start_a: NDArray[np.int64], start_b: NDArray[np.int64]) -> tuple[NDArray, NDArray, NDArray]:
    """All pairs ``(start_a[r] + p, start_b[r] + q)``, ``p < count_a[r]``, ``q < count_b[r]``,
    for each row ``r`` of ``first``, with the row of each pair."""
    rep = count_a * count_b
    row = np.repeat(np.arange(len(first)), rep)
    local = np.arange(rep.sum()) - np.repeat(np.cumsum(rep) - rep, rep)
    return row, start_a[row] + local // count_b[row], start_b[row] + local % count_b[row]


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
    T = FaceTable.of([b.shape for b in blocks])
    size = T.size
    lo, hi = T.lo - (tol * size)[:, None], T.hi + (tol * size)[:, None]
    pairs = block_pairs(lo, hi)
    if not len(pairs):
        return []
    normal, centre = T.face_normal, T.faces.mean
    offset = np.einsum("ij,ij->i", normal, centre)
    # every face of block i against every face of block j, for each candidate pair
    nf = np.diff(T.face_start)
    pid, fa, fb = _pairs_within(
        pairs, nf[pairs[:, 0]], nf[pairs[:, 1]], T.face_start[pairs[:, 0]], T.face_start[pairs[:, 1]]
    )
    keep = np.einsum("ij,ij->i", normal[fa], normal[fb]) <= -cos_tol
    fa, fb, pid = fa[keep], fb[keep], pid[keep]
    eps = tol * np.maximum(size[pairs[pid, 0]], size[pairs[pid, 1]])
    keep = np.abs(np.einsum("ij,ij->i", normal[fa], centre[fb]) - offset[fa]) <= eps
    flo, fhi = T.face_lo, T.face_hi
    keep &= np.all((flo[fa] <= fhi[fb] + eps[:, None]) & (flo[fb] <= fhi[fa] + eps[:, None]), axis=1)
    fa, fb, pid, eps = fa[keep], fb[keep], pid[keep], eps[keep]
    if not len(fa):
        return []
    # every vertex of B's face on A's plane
    posb, rowb = _ragged(T.start, fb)
    db = np.abs(np.einsum("ij,ij->i", T.points[T.loop[posb]], normal[fa][rowb]) - offset[fa][rowb])
    worst = np.zeros(len(fb))
    np.maximum.at(worst, rowb, db)
    keep = worst <= eps
    fa, fb, pid, eps = fa[keep], fb[keep], pid[keep], eps[keep]
    if not len(fa):
        return []
    # overlap in A's face plane (2D frame of A's normal, origin at A's face centre)
    frames = frames_from_normals(normal[fa])
    origin = centre[fa]
    posa, rowa = _ragged(T.start, fa)
    posb, rowb = _ragged(T.start, fb)
    xya = np.einsum("kj,kij->ki", T.points[T.loop[posa]] - origin[rowa], frames[rowa, 1:])
    xyb = np.einsum("kj,kij->ki", T.points[T.loop[posb]] - origin[rowb], frames[rowb, 1:])
    inter = shapely.intersection(_polygons(xya, rowa), _polygons(xyb, rowb))
    area = shapely.area(inter)
    smaller = np.minimum(size[pairs[pid, 0]], size[pairs[pid, 1]])
    amin = tol * smaller**2 if min_area is None else np.full(len(fa), float(min_area))
    hit = np.flatnonzero(area > amin)
    pieces, src = _flat_polygons(inter[hit])
    k = hit[src]
    big = shapely.area(pieces) > amin[k]
    pieces, k = pieces[big], k[big]
    for h in np.flatnonzero(shapely.get_num_interior_rings(pieces) > 0):
        i, j = pairs[pid[k[h]]]
        log.warning("contact between %r and %r has a hole; only its outer loop is kept", blocks[i].name, blocks[j].name)
    loops = _lift(pieces, frames[k], origin[k], 1e-9 * eps[k] / tol) if len(k) else []
    ab = pairs[pid[k]].tolist()
    found = [
        Interface(ij[0], ij[1], pts, normal[fa[kk]]) for ij, pts, kk in zip(ab, loops, k.tolist()) if len(pts) >= 3
    ]
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


def _convex(T: FaceTable, offset: NDArray[np.float64], tol: float) -> NDArray[np.bool_]:
    """True for each polyhedron whose vertices lie on the inner side of each of its face
    planes (within ``tol`` times its size)."""
    n = len(T)
    blocks = np.arange(n)
    poly, v, f = _pairs_within(blocks, np.diff(T.vertex_start), np.diff(T.face_start), T.vertex_start[:-1], T.face_start[:-1])
    d = np.einsum("ij,ij->i", T.points[v], T.face_normal[f]) - offset[f]
    worst = np.full(n, -np.inf)
    np.maximum.at(worst, poly, d)
    return worst <= tol * T.size


def _test_points(T: FaceTable, convex: NDArray[np.bool_], tol: float) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """Points of each polyhedron that lie in it (closed): its vertices and edge midpoints; for a
    convex one also its centroid and face centres, otherwise the centres of its convex faces.

    Returns the points and the start of each polyhedron's points, ``(n + 1,)``.
    """
    owner, nxt, _ = _ring(T.start)
    i, j = T.loop, T.loop[nxt]
    nv = max(len(T.points), 1)
    edges = np.unique(np.minimum(i, j) * nv + np.maximum(i, j))
    lo, hi = edges // nv, edges % nv
    face_poly = T.face_owner
    centre = T.faces.mean
    # convex faces of the non-convex polyhedra: every turn of the loop the normal's way
    p = T.points[T.loop]
    e = p[nxt] - p
    turn = np.einsum("ij,ij->i", np.cross(e, e[nxt]), T.faces.newell[owner])
    size2 = T.size[face_poly[owner]] ** 2
    bent = np.bincount(owner, weights=(turn < -tol * size2).astype(float), minlength=len(face_poly)) > 0
    use_face = convex[face_poly] | ~bent
    parts = [
        (T.points, T.vertex_owner),
        (0.5 * (T.points[lo] + T.points[hi]), T.vertex_owner[lo]),
        (T.centroid[convex], np.flatnonzero(convex)),
        (centre[use_face], face_poly[use_face]),
    ]
    pts = np.concatenate([q for q, _ in parts])
    who = np.concatenate([o for _, o in parts])
    order = np.argsort(who, kind="stable")
    start = np.concatenate([[0], np.cumsum(np.bincount(who, minlength=len(T)))])
    return pts[order], start


def _nonconvex_depth(T: FaceTable, x: int, offset: NDArray[np.float64], pts: NDArray[np.float64]) -> NDArray[np.float64]:
    """Depth (m) of each point inside the non-convex polyhedron ``x`` (-inf when outside):
    inside by the winding number, depth a lower bound of the distance to its faces (the larger
    of the distances to each face's plane and to its bounding box)."""
    faces = np.arange(T.face_start[x], T.face_start[x + 1])
    normal, off = T.face_normal[faces], offset[faces]
    corners = [T.points[T.loop[T.start[f] : T.start[f + 1]]] for f in faces]
    tris = np.concatenate(
        [np.stack([np.repeat(c[:1], len(c) - 2, axis=0), c[1:-1], c[2:]], axis=1) for c in corners]
    )
    w = _winding_numbers(tris, pts)
    depth = np.full(len(pts), -np.inf)
    s = off[None, :] - pts @ normal.T
    flo, fhi = T.face_lo[faces], T.face_hi[faces]
    for k in np.flatnonzero(w > 0.5):
        gap = np.maximum(flo - pts[k], pts[k] - fhi).clip(min=0.0)
        depth[k] = np.maximum(np.abs(s[k]), np.linalg.norm(gap, axis=1)).min()
    return depth


def check_overlaps(assembly_or_blocks: Assembly | Sequence[Block], tol: float = 1e-6) -> None:
    """Raise if two blocks' volumes intersect (see module docstring for what is checked).

    All pairs with a convex block are checked at once (the test points of one block against
    the face planes of the other); pairs with a non-convex block one by one.

    Parameters
    ----------
    assembly_or_blocks : Assembly or sequence of Block
    tol : float
        Relative tolerance: a point must lie deeper than ``tol * L`` inside the other block
        (``L`` the larger bounding-box diagonal of the pair).

    Raises
    ------
    AssemblyError
        For the first overlapping pair (in :func:`block_pairs` order), naming both blocks and
        the depth of the deepest test point.
    """
    blocks = _blocks_of(assembly_or_blocks)
    if len(blocks) < 2:
        return
    T = FaceTable.of([b.shape for b in blocks])
    size = T.size
    lo, hi = T.lo + (tol * size)[:, None], T.hi - (tol * size)[:, None]
    pairs = block_pairs(lo, hi)
    if not len(pairs):
        return
    offset = np.einsum("ij,ij->i", T.face_normal, T.faces.mean)
    convex = _convex(T, offset, tol)
    tests, tstart = _test_points(T, convex, tol)
    # each pair both ways: the points of Y inside X
    X = pairs.ravel()
    Y = pairs[:, ::-1].ravel()
    eps = np.repeat(tol * np.maximum(size[pairs[:, 0]], size[pairs[:, 1]]), 2)
    worst = np.full(len(X), -np.inf)
    ntest = np.diff(tstart)
    nface = np.diff(T.face_start)
    todo = np.flatnonzero(convex[X])
    # in chunks of about a million (point, face) checks
    load = np.cumsum(ntest[Y[todo]] * nface[X[todo]])
    for chunk in np.split(todo, np.searchsorted(load, np.arange(1, int(load[-1] // 1_000_000) + 1) * 1_000_000)) if len(todo) else []:
        row, _, pt = _pairs_within(chunk, np.ones(len(chunk), dtype=np.int64), ntest[Y[chunk]], np.zeros(len(chunk), dtype=np.int64), tstart[Y[chunk]])
        d = chunk[row]
        p = tests[pt]
        inside = np.all((p > lo[X[d]]) & (p < hi[X[d]]), axis=1)
        d, p = d[inside], p[inside]
        r, k, f = _pairs_within(d, np.ones(len(d), dtype=np.int64), nface[X[d]], np.arange(len(d)), T.face_start[X[d]])
        s = offset[f] - np.einsum("ij,ij->i", p[k], T.face_normal[f])
        if len(s):
            depth = np.minimum.reduceat(s, np.concatenate([[0], np.cumsum(nface[X[d]])[:-1]]))
            np.maximum.at(worst, d, depth)
    for d in np.flatnonzero(~convex[X]):
        p = tests[tstart[Y[d]] : tstart[Y[d] + 1]]
        p = p[np.all((p > lo[X[d]]) & (p < hi[X[d]]), axis=1)]
        if len(p):
            worst[d] = _nonconvex_depth(T, int(X[d]), offset, p).max()
    bad = np.flatnonzero(worst > eps)
    if len(bad):
        d = bad[0]
        x, y = blocks[X[d]].name, blocks[Y[d]].name
        raise AssemblyError(f"blocks {x!r} and {y!r} overlap: a point of {y!r} lies {worst[d]:.3g} m inside {x!r}")
