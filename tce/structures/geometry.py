"""Polyhedra and planar polygons: exact volumes, centroids, normals and frames.

Conventions (``docs/conventions.md``): SI units (m), z up. A polyhedron is a closed surface of
planar polygonal faces whose vertex loops run counter-clockwise seen from outside, so
that Newell normals point outwards. Faces may be non-convex; so may the polyhedron.
Volumes and centroids follow from the divergence theorem (signed tetrahedra on a fan
triangulation of every face), which is exact for any closed, consistently oriented
polyhedron with planar faces.

Everything is computed in batches: :class:`FaceTable` (faces of many polyhedra: normals,
volumes, centroids, checks) and :class:`PolygonTable` (many planar polygons: areas,
centroids, tributary areas) work on flattened arrays in one numpy pass; the functions of one
polyhedron or polygon are a batch of one.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import cached_property, lru_cache

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "FaceTable",
    "GeometryError",
    "PolygonTable",
    "Polyhedron",
    "box",
    "frame_from_normal",
    "frames_from_normals",
    "lateral_direction",
    "newell_normal",
    "oriented_polyhedra",
    "polygon_area",
    "polygon_centroid",
    "prism",
    "prisms",
    "tributary_areas",
]


class GeometryError(ValueError):
    """Raised for geometry that cannot describe a rigid block (open, inverted, non-planar...)."""


def _segment_sum(values: NDArray[np.float64], owner: NDArray[np.int64], n: int) -> NDArray[np.float64]:
    """Sum of the rows of ``values`` ((k,) or (k, d)) per ``owner`` (0..n-1)."""
    if values.ndim == 1:
        return np.bincount(owner, weights=values, minlength=n)
    return np.stack([np.bincount(owner, weights=values[:, j], minlength=n) for j in range(values.shape[1])], axis=1)


def _ring(start: NDArray[np.int64]) -> tuple[NDArray[np.int64], NDArray[np.int64], NDArray[np.int64]]:
    """For loops stored one after the other (loop ``k`` is ``start[k]:start[k + 1]``): the loop
    of every entry, and the positions of the next and previous entries of the same loop."""
    counts = np.diff(start)
    owner = np.repeat(np.arange(len(counts)), counts)
    pos = np.arange(start[-1]) - start[owner]
    nxt = start[owner] + (pos + 1) % counts[owner]
    prv = start[owner] + (pos - 1) % counts[owner]
    return owner, nxt, prv


# ------------------------------------------------------------------------------ polygons
@dataclass(frozen=True, eq=False)
class PolygonTable:
    """Many planar polygons, flattened.

    Parameters
    ----------
    points : (nv, 3) ndarray
        Vertices of every polygon, one polygon after the other, each in order around it (m).
    start : (k + 1,) ndarray of int
        Polygon ``i`` is ``points[start[i]:start[i + 1]]`` (at least one vertex each).
    """

    points: NDArray[np.float64]
    start: NDArray[np.int64]

    @classmethod
    def of(cls, polygons: Sequence[ArrayLike]) -> PolygonTable:
        """The table of a sequence of ``(k_i, 3)`` vertex arrays."""
        arrays = [np.asarray(p, dtype=float).reshape(-1, 3) for p in polygons]
        counts = np.array([len(p) for p in arrays], dtype=np.int64)
        pts = np.concatenate(arrays) if arrays else np.zeros((0, 3))
        return cls(pts, np.concatenate([[0], np.cumsum(counts)]).astype(np.int64))

    def __len__(self) -> int:
        return len(self.start) - 1

    @cached_property
    def _ring(self) -> tuple[NDArray[np.int64], NDArray[np.int64], NDArray[np.int64]]:
        return _ring(self.start)

    @property
    def owner(self) -> NDArray[np.int64]:
        """Polygon of every vertex, (nv,)."""
        return self._ring[0]

    @cached_property
    def counts(self) -> NDArray[np.int64]:
        """Vertices per polygon, (k,)."""
        return np.diff(self.start)

    @cached_property
    def mean(self) -> NDArray[np.float64]:
        """Mean of each polygon's vertices, (k, 3) (m)."""
        return _segment_sum(self.points, self.owner, len(self)) / self.counts[:, None]

    @cached_property
    def _edges(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Vertices and their successors relative to their polygon's mean, (nv, 3) each."""
        r = self.points - self.mean[self.owner]
        return r, r[self._ring[1]]

    @cached_property
    def newell(self) -> NDArray[np.float64]:
        """Newell vector of each polygon, (k, 3): twice its vector area (m^2)."""
        a, b = self._edges
        return _segment_sum(np.cross(a, b), self.owner, len(self))

    @cached_property
    def area(self) -> NDArray[np.float64]:
        """Area of each polygon (m^2); polygons of fewer than 3 vertices have none."""
        return np.where(self.counts > 2, 0.5 * np.linalg.norm(self.newell, axis=1), 0.0)

    @cached_property
    def centroid(self) -> NDArray[np.float64]:
        """Area centroid of each polygon (m), exact for any simple planar polygon.

        A fan of signed triangles from the vertex mean, weighted by their signed area along
        the polygon normal; the vertex mean when the polygon has no area.
        """
        n = self.newell
        nn = np.linalg.norm(n, axis=1)
        unit = n / np.where(nn > 0, nn, 1.0)[:, None]
        a, b = self._edges
        w = np.einsum("ij,ij->i", np.cross(a, b), unit[self.owner])  # twice the signed triangle areas
        total = _segment_sum(w, self.owner, len(self))
        moment = _segment_sum(w[:, None] * (a + b) / 3.0, self.owner, len(self))
        ok = (nn > 0) & (total != 0)
        return self.mean + np.where(ok[:, None], moment / np.where(ok, total, 1.0)[:, None], 0.0)

    @cached_property
    def tributary(self) -> NDArray[np.float64]:
        """Share of its polygon's area attributed to each vertex, (nv,) (m^2).

        Each vertex receives the quadrilateral spanned by itself, the midpoints of its two
        edges and the polygon centroid (the usual nodal lumping; a rectangle gives a quarter
        of its area to each corner). The shares sum to the polygon area for convex polygons
        and for star-shaped ones about the centroid. Polygons of fewer than 3 vertices get 0.
        """
        owner, nxt, prv = self._ring
        p, c = self.points, self.centroid[owner]
        m_next, m_prev = 0.5 * (p + p[nxt]), 0.5 * (p + p[prv])
        t1 = 0.5 * np.linalg.norm(np.cross(m_prev - c, p - c), axis=1)
        t2 = 0.5 * np.linalg.norm(np.cross(p - c, m_next - c), axis=1)
        return np.where(self.counts[owner] > 2, t1 + t2, 0.0)


def newell_normal(points: ArrayLike) -> NDArray[np.float64]:
    """Newell's vector of a polygon: twice its vector area.

    Parameters
    ----------
    points : (k, 3) array_like
        Polygon vertices in order (m).

    Returns
    -------
    (3,) ndarray
        ``sum_i p_i x p_{i+1}``; its norm is twice the area (m^2) and its direction the
        normal given by the right-hand rule on the vertex order.
    """
    return PolygonTable.of([points]).newell[0]


def polygon_area(points: ArrayLike) -> float:
    """Area (m^2) of a planar polygon given by its ordered vertices."""
    return float(0.5 * np.linalg.norm(newell_normal(points)))


def polygon_centroid(points: ArrayLike) -> NDArray[np.float64]:
    """Area centroid (m) of a planar, possibly non-convex, polygon (see :attr:`PolygonTable.centroid`)."""
    return PolygonTable.of([points]).centroid[0]


def tributary_areas(points: ArrayLike) -> NDArray[np.float64]:
    """Share of a planar polygon's area attributed to each of its vertices (m^2); see
    :attr:`PolygonTable.tributary`."""
    return PolygonTable.of([points]).tributary


# ------------------------------------------------------------------------------ frames
def frames_from_normals(normals: ArrayLike) -> NDArray[np.float64]:
    """Orthonormal interface frames ``(n, t1, t2)`` as the rows of ``(k, 3, 3)`` arrays.

    ``t1`` is the projection of global ``+z`` on the interface plane (the dip direction)
    when the plane is not horizontal (``|t1| >= 1e-6`` before normalising), and ``+x``
    otherwise; ``t2 = n x t1``. For the interfaces of an arch spanning along x this puts
    ``t1`` in the arch plane and ``t2`` along ``+-y`` (out of plane).
    """
    n = np.asarray(normals, dtype=float).reshape(-1, 3)
    n = n / np.linalg.norm(n, axis=1)[:, None]
    t1 = -n[:, 2:3] * n
    t1[:, 2] += 1.0
    flat = np.linalg.norm(t1, axis=1) < 1e-6
    if flat.any():
        t1[flat] = -n[flat, 0:1] * n[flat]
        t1[flat, 0] += 1.0
    t1 /= np.linalg.norm(t1, axis=1)[:, None]
    return np.stack([n, t1, np.cross(n, t1)], axis=1)


def frame_from_normal(normal: ArrayLike) -> NDArray[np.float64]:
    """Orthonormal interface frame ``(n, t1, t2)`` as the rows of a 3x3 array
    (:func:`frames_from_normals` of one normal)."""
    return frames_from_normals(normal)[0]


# ------------------------------------------------------------------------------ polyhedra
@dataclass(frozen=True, eq=False)
class Polyhedron:
    """A closed polyhedron with planar polygonal faces.

    Parameters
    ----------
    vertices : (n, 3) array_like
        Vertex coordinates (m).
    faces : sequence of sequences of int
        Vertex indices of each face, counter-clockwise seen from outside.
    """

    vertices: NDArray[np.float64]
    faces: tuple[tuple[int, ...], ...] = field(default=())

    def __post_init__(self) -> None:
        v = np.array(self.vertices, dtype=float)
        if v.ndim != 2 or v.shape[1] != 3:
            raise GeometryError(f"vertices must be an (n, 3) array, got shape {v.shape}")
        if not np.isfinite(v).all():
            raise GeometryError("vertices contain NaN or infinite coordinates")
        v.setflags(write=False)
        faces = _checked_faces(self.faces, len(v))
        object.__setattr__(self, "vertices", v)
        object.__setattr__(self, "faces", faces)

    def face_points(self, k: int) -> NDArray[np.float64]:
        """Coordinates (m) of face ``k``'s vertices, in order."""
        return self.vertices[list(self.faces[k])]

    @cached_property
    def _table(self) -> FaceTable:
        return FaceTable.of([self])

    @cached_property
    def face_normals(self) -> NDArray[np.float64]:
        """Outward unit normals of the faces, (n_faces, 3)."""
        return self._table.face_normal

    @property
    def volume(self) -> float:
        """Signed volume (m^3); positive when faces are oriented outwards."""
        return float(self._table.volume[0])

    @property
    def centroid(self) -> NDArray[np.float64]:
        """Volume centroid (m)."""
        return self._table.centroid[0]

    @cached_property
    def size(self) -> float:
        """Diagonal of the axis-aligned bounding box (m): the block's characteristic length."""
        return float(np.linalg.norm(np.ptp(self.vertices, axis=0)))

    def validate(self, name: str = "block", tol: float = 1e-6) -> None:
        """Check that the polyhedron can be a rigid block (see :meth:`FaceTable.validate`)."""
        self._table.validate([name], tol)


def _checked_faces(faces: Sequence[Sequence[int]], nv: int) -> tuple[tuple[int, ...], ...]:
    """``faces`` as a tuple of tuples of int, checked against ``nv`` vertices."""
    try:
        out, lowest, span = _canonical_faces(faces if isinstance(faces, tuple) else tuple(map(tuple, faces)))
    except TypeError:  # unhashable entries
        out, lowest, span = _canonical_faces(tuple(tuple(int(i) for i in f) for f in faces))
    if lowest < 0 or span > nv:
        k = next(k for k, f in enumerate(out) if min(f) < 0 or max(f) >= nv)
        raise GeometryError(f"face {k} refers to a vertex index outside 0..{nv - 1}")
    return out


@lru_cache(maxsize=1024)
def _canonical_faces(faces: tuple) -> tuple[tuple[tuple[int, ...], ...], int, int]:
    """Faces as tuples of int (checked to have 3 vertices or more), their smallest index and
    one more than their largest (cached: generators give thousands of blocks one face list)."""
    out = tuple(tuple(int(i) for i in f) for f in faces)
    for k, f in enumerate(out):
        if len(f) < 3:
            raise GeometryError(f"face {k} has {len(f)} vertices; a face needs at least 3")
    return out, min((min(f) for f in out), default=0), max((max(f) for f in out), default=-1) + 1


@lru_cache(maxsize=1024)
def _flat_faces(faces: tuple[tuple[int, ...], ...]) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    """The corners of a face list, face after face, and the corners per face (read-only;
    cached: generators give thousands of blocks one face list)."""
    loop = np.fromiter((i for f in faces for i in f), dtype=np.int64)
    counts = np.fromiter((len(f) for f in faces), dtype=np.int64, count=len(faces))
    loop.setflags(write=False)
    counts.setflags(write=False)
    return loop, counts


@dataclass(frozen=True, eq=False)
class FaceTable:
    """The faces of many polyhedra, flattened into arrays.

    Attributes
    ----------
    points : (nv, 3) ndarray
        Vertices of every polyhedron, one polyhedron after the other (m).
    vertex_start : (np + 1,) ndarray of int
        Polyhedron ``p`` owns ``points[vertex_start[p]:vertex_start[p + 1]]``.
    loop : (nl,) ndarray of int
        Index in ``points`` of every face corner, face after face.
    start : (nf + 1,) ndarray of int
        Face ``f`` is ``loop[start[f]:start[f + 1]]``.
    face_start : (np + 1,) ndarray of int
        Polyhedron ``p`` owns faces ``face_start[p]:face_start[p + 1]``.
    """

    points: NDArray[np.float64]
    vertex_start: NDArray[np.int64]
    loop: NDArray[np.int64]
    start: NDArray[np.int64]
    face_start: NDArray[np.int64]

    @classmethod
    def of(cls, polyhedra: Sequence[Polyhedron]) -> FaceTable:
        """The table of ``polyhedra`` (a face list that several share is flattened once)."""
        npoly = len(polyhedra)
        if not npoly:
            z = np.zeros(1, dtype=np.int64)
            return cls(np.zeros((0, 3)), z, np.zeros(0, dtype=np.int64), z, z)
        nverts = np.fromiter((len(p.vertices) for p in polyhedra), dtype=np.int64, count=npoly)
        vstart = np.concatenate([[0], np.cumsum(nverts)])
        points = np.concatenate([p.vertices for p in polyhedra])
        # a polyhedron's corners are those of its face list plus its offset
        loops, counts = [], []
        for p, offset in zip(polyhedra, vstart[:-1]):
            loop, count = _flat_faces(p.faces)
            loops.append(loop + offset)
            counts.append(count)
        loop = np.concatenate(loops)
        fcounts = np.concatenate(counts)
        start = np.concatenate([[0], np.cumsum(fcounts)]).astype(np.int64)
        fstart = np.concatenate([[0], np.cumsum([len(c) for c in counts])])
        return cls(points, vstart.astype(np.int64), loop, start, fstart.astype(np.int64))

    @classmethod
    def uniform(cls, vertices: ArrayLike, faces: Sequence[Sequence[int]]) -> FaceTable:
        """The table of ``n`` polyhedra that share one face list, from their vertices alone.

        Parameters
        ----------
        vertices : (n, k, 3) array_like
            Vertices of each polyhedron (m).
        faces : sequence of sequences of int
            Their common face list (indices into ``0..k-1``).
        """
        v = np.asarray(vertices, dtype=float)
        n, k = v.shape[:2]
        fl = _checked_faces(faces, k)
        lp, counts = _flat_faces(fl)
        loop = (lp[None, :] + (np.arange(n) * k)[:, None]).ravel()
        start = np.concatenate([[0], np.cumsum(np.tile(counts, n))]).astype(np.int64)
        return cls(v.reshape(-1, 3), np.arange(n + 1, dtype=np.int64) * k, loop, start,
                   np.arange(n + 1, dtype=np.int64) * len(fl))

    def __len__(self) -> int:
        return len(self.face_start) - 1

    # ---------------------------------------------------------------- layout
    @cached_property
    def faces(self) -> PolygonTable:
        """The faces as polygons (in face order)."""
        return PolygonTable(self.points[self.loop], self.start)

    @cached_property
    def face_owner(self) -> NDArray[np.int64]:
        """Polyhedron of every face, (nf,)."""
        return np.repeat(np.arange(len(self)), np.diff(self.face_start))

    @cached_property
    def vertex_owner(self) -> NDArray[np.int64]:
        """Polyhedron of every vertex, (nv,)."""
        return np.repeat(np.arange(len(self)), np.diff(self.vertex_start))

    # ---------------------------------------------------------------- measures
    @cached_property
    def face_normal(self) -> NDArray[np.float64]:
        """Unit Newell normal of every face, (nf, 3) (zero for a face of no area)."""
        n = self.faces.newell
        norm = np.linalg.norm(n, axis=1)
        return n / np.where(norm > 0, norm, 1.0)[:, None]

    @cached_property
    def face_lo(self) -> NDArray[np.float64]:
        """Lower corner of each face's bounding box, (nf, 3) (m)."""
        return np.minimum.reduceat(self.faces.points, self.start[:-1], axis=0)

    @cached_property
    def face_hi(self) -> NDArray[np.float64]:
        """Upper corner of each face's bounding box, (nf, 3) (m)."""
        return np.maximum.reduceat(self.faces.points, self.start[:-1], axis=0)

    @cached_property
    def lo(self) -> NDArray[np.float64]:
        """Lower corner of each polyhedron's bounding box, (np, 3) (m)."""
        return np.minimum.reduceat(self.points, self.vertex_start[:-1], axis=0)

    @cached_property
    def hi(self) -> NDArray[np.float64]:
        """Upper corner of each polyhedron's bounding box, (np, 3) (m)."""
        return np.maximum.reduceat(self.points, self.vertex_start[:-1], axis=0)

    @cached_property
    def size(self) -> NDArray[np.float64]:
        """Bounding-box diagonal of each polyhedron, (np,) (m)."""
        return np.linalg.norm(self.hi - self.lo, axis=1)

    @cached_property
    def _moments(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        n = len(self)
        vo = self.vertex_owner
        origin = _segment_sum(self.points, vo, n) / np.diff(self.vertex_start)[:, None]
        # fan of each face from its first corner: triangles (first, j, j + 1)
        fo = self.face_owner
        owner, nxt, _ = _ring(self.start)
        pos = np.arange(len(self.loop)) - self.start[owner]
        tri = np.flatnonzero((pos >= 1) & (pos <= np.diff(self.start)[owner] - 2))
        poly = fo[owner[tri]]
        o = origin[poly]
        a = self.points[self.loop[self.start[owner[tri]]]] - o
        b = self.points[self.loop[tri]] - o
        c = self.points[self.loop[nxt[tri]]] - o
        dv = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6.0
        vol = np.bincount(poly, weights=dv, minlength=n)
        first = _segment_sum(dv[:, None] * (a + b + c) / 4.0, poly, n)
        with np.errstate(invalid="ignore", divide="ignore"):
            shift = np.where((vol != 0.0)[:, None], first / np.where(vol != 0.0, vol, 1.0)[:, None], 0.0)
        return vol, origin + shift

    @property
    def volume(self) -> NDArray[np.float64]:
        """Signed volume of each polyhedron, (np,) (m^3); positive when faces point outwards."""
        return self._moments[0]

    @property
    def centroid(self) -> NDArray[np.float64]:
        """Volume centroid of each polyhedron, (np, 3) (m)."""
        return self._moments[1]

    # ---------------------------------------------------------------- checks
    def first_fault(self, tol: float = 1e-6) -> tuple[int, str] | None:
        """The first polyhedron (in order) that cannot be a rigid block, and what is wrong.

        The checks, in the order a polyhedron's fault is reported: an open surface (an edge
        not shared by exactly two faces in opposite directions; the first such edge in face
        order), then face by face a (relatively) zero area or a non-planar face (a vertex
        farther than ``tol`` times the polyhedron's size from the face plane), then inverted
        faces (non-positive volume).

        Returns
        -------
        (int, str) or None
            The polyhedron's index and the problem in words; None when all are valid.
        """
        n = len(self)
        none = np.iinfo(np.int64).max
        inverted_code = none - 1
        bad = np.full(n, none)  # per polyhedron: 0 open surface, 1 + f face f, inverted_code
        # closed and consistently oriented: every directed edge once, its reverse once
        owner, nxt, _ = _ring(self.start)
        i, j = self.loop, self.loop[nxt]
        nv = max(len(self.points), 1)
        key, rev = i * nv + j, j * nv + i
        uniq, inv, cnt = np.unique(key, return_inverse=True, return_counts=True)
        at = np.minimum(np.searchsorted(uniq, rev), len(uniq) - 1)
        rev_cnt = np.where(uniq[at] == rev, cnt[at], 0) if len(uniq) else rev
        edge_bad = np.flatnonzero((cnt[inv] != 1) | (rev_cnt != 1))
        corner_poly = self.face_owner[owner]
        first_edge = np.full(n, len(key))
        np.minimum.at(first_edge, corner_poly[edge_bad], edge_bad)
        bad[first_edge < len(key)] = 0
        # faces: zero area, then planarity, face by face
        scale = np.maximum(self.size, np.finfo(float).tiny)
        fo = self.face_owner
        newell = self.faces.newell
        norm = np.linalg.norm(newell, axis=1)
        zero = 0.5 * norm <= (1e-3 * tol * scale[fo]) ** 2
        unit = newell / np.where(norm > 0, norm, 1.0)[:, None]
        d = np.abs(np.einsum("ij,ij->i", self.faces._edges[0], unit[owner]))
        dmax = np.zeros(len(fo))
        np.maximum.at(dmax, owner, d)
        face_bad = np.flatnonzero(zero | (dmax > tol * scale[fo]))
        np.minimum.at(bad, fo[face_bad], 1 + face_bad)
        # orientation
        vol = self.volume
        bad[(bad == none) & ~(vol > 0.0)] = inverted_code
        faulty = np.flatnonzero(bad != none)
        if not len(faulty):
            return None
        p = int(faulty[0])
        code = int(bad[p])
        if code == 0:
            c, base = int(first_edge[p]), int(self.vertex_start[p])
            return p, (
                "the surface is not closed or not consistently oriented "
                f"(edge {i[c] - base}-{j[c] - base} is not shared by exactly two faces in opposite directions)"
            )
        if code == inverted_code:
            return p, (
                f"the faces are inverted (volume {vol[p]:.6g} m^3 <= 0); "
                "list each face counter-clockwise seen from outside"
            )
        f = code - 1
        k = f - int(self.face_start[p])
        if zero[f]:
            return p, f"face {k} has zero area"
        return p, f"face {k} is not planar (a vertex lies {dmax[f]:.3g} m off its plane)"

    def validate(self, names: Sequence[str], tol: float = 1e-6) -> None:
        """Check that every polyhedron can be a rigid block (:meth:`first_fault`).

        Parameters
        ----------
        names : sequence of str
            What to call each polyhedron in a message (e.g. ``"block 'v01'"``).
        tol : float
            Relative planarity tolerance.

        Raises
        ------
        GeometryError
            Naming the first polyhedron at fault and the problem.
        """
        fault = self.first_fault(tol)
        if fault is not None:
            raise GeometryError(f"{names[fault[0]]}: {fault[1]}")


@lru_cache(maxsize=64)
def _prism_faces(k: int) -> tuple[tuple[int, ...], ...]:
    """The face list of a prism of ``k`` sides (one object shared by all such prisms)."""
    faces = [tuple(range(k - 1, -1, -1)), tuple(range(k, 2 * k))]
    faces += [(i, (i + 1) % k, k + (i + 1) % k, k + i) for i in range(k)]
    return tuple(faces)


def oriented_polyhedra(vertices: ArrayLike, faces: Sequence[Sequence[int]]) -> list[Polyhedron]:
    """Polyhedra that share one face list, each with its faces turned outwards.

    Parameters
    ----------
    vertices : (n, k, 3) array_like
        The vertices of ``n`` polyhedra (m).
    faces : sequence of sequences of int
        Their common face list, oriented the same way (all outwards or all inwards) for
        each polyhedron: a polyhedron whose volume comes out negative gets it reversed.
    """
    v = np.asarray(vertices, dtype=float)
    if v.ndim != 3 or v.shape[2] != 3:
        raise GeometryError(f"vertices must be an (n, k, 3) array, got shape {v.shape}")
    fw = _checked_faces(faces, v.shape[1])
    bw = tuple(f[::-1] for f in fw)
    vol = FaceTable.uniform(v, fw).volume
    return [Polyhedron(p, fw if vol_p >= 0 else bw) for p, vol_p in zip(v, vol)]


def prisms(bottom: ArrayLike, top: ArrayLike) -> list[Polyhedron]:
    """Polyhedra between pairs of polygonal loops with the same number of vertices.

    Parameters
    ----------
    bottom, top : (n, k, 3) array_like
        ``n`` pairs of loops (m); ``bottom[p, i]`` is joined to ``top[p, i]`` by a side face.
        The loops may run either way: each prism's faces are oriented outwards from the
        sign of its volume.
    """
    b, t = np.asarray(bottom, float), np.asarray(top, float)
    if b.ndim != 3 or b.shape != t.shape or b.shape[2] != 3:
        raise GeometryError(f"bottom and top must be (n, k, 3) arrays of the same shape, got {b.shape} and {t.shape}")
    return oriented_polyhedra(np.concatenate([b, t], axis=1), _prism_faces(b.shape[1]))


def prism(bottom: ArrayLike, top: ArrayLike) -> Polyhedron:
    """Polyhedron between two polygonal loops with the same number of vertices.

    ``bottom[i]`` is joined to ``top[i]`` by a side face. The loops may run either way:
    faces are oriented outwards from the sign of the volume.
    """
    b, t = np.asarray(bottom, float), np.asarray(top, float)
    return prisms(b[None], t[None])[0]


def box(lo: ArrayLike, hi: ArrayLike) -> Polyhedron:
    """Axis-aligned box between corners ``lo`` and ``hi`` (m), faces oriented outwards."""
    (x0, y0, z0), (x1, y1, z1) = np.asarray(lo, float), np.asarray(hi, float)
    bottom = [[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0]]
    top = [[x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]]
    return prism(bottom, top)


def lateral_direction(alpha: float) -> NDArray[np.float64]:
    """Unit horizontal vector at ``alpha`` degrees from +x towards +y."""
    a = np.deg2rad(alpha)
    return np.array([np.cos(a), np.sin(a), 0.0])
