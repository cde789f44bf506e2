"""Polyhedra and planar polygons: exact volumes, centroids, normals and frames.

Conventions (docs/conventions.md): SI units (m), z up. A polyhedron is a closed surface of
planar polygonal faces whose vertex loops run counter-clockwise seen from outside, so
that Newell normals point outwards. Faces may be non-convex; so may the polyhedron.
Volumes and centroids follow from the divergence theorem (signed tetrahedra on a fan
triangulation of every face), which is exact for any closed, consistently oriented
polyhedron with planar faces.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "GeometryError",
    "Polyhedron",
    "box",
    "prism",
    "frame_from_normal",
    "newell_normal",
    "polygon_area",
    "polygon_centroid",
    "tributary_areas",
]


class GeometryError(ValueError):
    """Raised for geometry that cannot describe a rigid block (open, inverted, non-planar...)."""


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
    p = np.asarray(points, dtype=float)
    p = p - p.mean(axis=0)
    return np.cross(p, np.roll(p, -1, axis=0)).sum(axis=0)


def polygon_area(points: ArrayLike) -> float:
    """Area (m^2) of a planar polygon given by its ordered vertices."""
    return 0.5 * float(np.linalg.norm(newell_normal(points)))


def polygon_centroid(points: ArrayLike) -> NDArray[np.float64]:
    """Area centroid (m) of a planar, possibly non-convex, polygon.

    Uses a fan of signed triangles from the vertex mean, weighted by their signed area
    along the polygon normal, which is exact for any simple planar polygon.
    """
    p = np.asarray(points, dtype=float)
    o = p.mean(axis=0)
    n = newell_normal(p)
    nn = np.linalg.norm(n)
    if nn == 0.0:
        return o
    n = n / nn
    a, b = p - o, np.roll(p, -1, axis=0) - o
    w = np.cross(a, b) @ n  # twice the signed triangle areas
    total = w.sum()
    if total == 0.0:
        return o
    return o + (w[:, None] * (a + b) / 3.0).sum(axis=0) / total


def tributary_areas(points: ArrayLike) -> NDArray[np.float64]:
    """Share of a planar polygon's area attributed to each of its vertices (m^2).

    Each vertex receives the quadrilateral spanned by itself, the midpoints of its two
    edges and the polygon centroid (the usual nodal lumping; a rectangle gives a quarter
    of its area to each corner). The shares sum to the polygon area for convex polygons
    and for star-shaped ones about the centroid.
    """
    p = np.asarray(points, dtype=float)
    c = polygon_centroid(p)
    nxt = np.roll(p, -1, axis=0)
    prv = np.roll(p, 1, axis=0)
    m_next = 0.5 * (p + nxt)
    m_prev = 0.5 * (p + prv)
    # two triangles (c, m_prev, p) and (c, p, m_next)
    t1 = 0.5 * np.linalg.norm(np.cross(m_prev - c, p - c), axis=1)
    t2 = 0.5 * np.linalg.norm(np.cross(p - c, m_next - c), axis=1)
    return t1 + t2


def frame_from_normal(normal: ArrayLike) -> NDArray[np.float64]:
    """Orthonormal interface frame ``(n, t1, t2)`` as the rows of a 3x3 array.

    ``t1`` is the projection of global ``+z`` on the interface plane (the dip direction)
    when the plane is not horizontal, and ``+x`` otherwise; ``t2 = n x t1``. For the
    interfaces of an arch spanning along x this puts ``t1`` in the arch plane and ``t2``
    along ``+-y`` (out of plane).
    """
    n = np.asarray(normal, dtype=float)
    n = n / np.linalg.norm(n)
    ez = np.array([0.0, 0.0, 1.0])
    t1 = ez - (ez @ n) * n
    if np.linalg.norm(t1) < 1e-6:
        ex = np.array([1.0, 0.0, 0.0])
        t1 = ex - (ex @ n) * n
    t1 = t1 / np.linalg.norm(t1)
    t2 = np.cross(n, t1)
    return np.vstack([n, t1, t2])


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
        if not np.all(np.isfinite(v)):
            raise GeometryError("vertices contain NaN or infinite coordinates")
        v.setflags(write=False)
        faces = tuple(tuple(int(i) for i in f) for f in self.faces)
        object.__setattr__(self, "vertices", v)
        object.__setattr__(self, "faces", faces)
        for k, f in enumerate(faces):
            if len(f) < 3:
                raise GeometryError(f"face {k} has {len(f)} vertices; a face needs at least 3")
            if min(f) < 0 or max(f) >= len(v):
                raise GeometryError(f"face {k} refers to a vertex index outside 0..{len(v) - 1}")

    def face_points(self, k: int) -> NDArray[np.float64]:
        """Coordinates (m) of face ``k``'s vertices, in order."""
        return self.vertices[list(self.faces[k])]

    @cached_property
    def face_normals(self) -> NDArray[np.float64]:
        """Outward unit normals of the faces, (n_faces, 3)."""
        out = np.empty((len(self.faces), 3))
        for k in range(len(self.faces)):
            n = newell_normal(self.face_points(k))
            out[k] = n / (np.linalg.norm(n) or 1.0)
        return out

    @cached_property
    def _moments(self) -> tuple[float, NDArray[np.float64]]:
        o = self.vertices.mean(axis=0)
        vol = 0.0
        first = np.zeros(3)
        for f in self.faces:
            p = self.vertices[list(f)] - o
            a = p[0]
            b, c = p[1:-1], p[2:]
            dv = np.einsum("j,ij->i", a, np.cross(b, c)) / 6.0
            vol += dv.sum()
            first += (dv[:, None] * (a + b + c) / 4.0).sum(axis=0)
        return vol, o + (first / vol if vol != 0.0 else 0.0)

    @property
    def volume(self) -> float:
        """Signed volume (m^3); positive when faces are oriented outwards."""
        return float(self._moments[0])

    @property
    def centroid(self) -> NDArray[np.float64]:
        """Volume centroid (m)."""
        return self._moments[1]

    @cached_property
    def size(self) -> float:
        """Diagonal of the axis-aligned bounding box (m): the block's characteristic length."""
        return float(np.linalg.norm(np.ptp(self.vertices, axis=0)))

    def validate(self, name: str = "block", tol: float = 1e-6) -> None:
        """Check that the polyhedron can be a rigid block.

        Raises
        ------
        GeometryError
            Naming ``name`` and the problem: an open surface (an edge not shared by exactly
            two faces in opposite directions), a non-planar face (a vertex farther than
            ``tol`` times the block size from the face plane), a face of (relatively) zero
            area, or inverted faces (non-positive volume).
        """
        edges: dict[tuple[int, int], int] = {}
        for f in self.faces:
            for i, j in zip(f, f[1:] + f[:1]):
                edges[(i, j)] = edges.get((i, j), 0) + 1
        for (i, j), count in edges.items():
            if count != 1 or edges.get((j, i), 0) != 1:
                raise GeometryError(
                    f"{name}: the surface is not closed or not consistently oriented "
                    f"(edge {i}-{j} is not shared by exactly two faces in opposite directions)"
                )
        scale = max(self.size, np.finfo(float).tiny)
        for k, f in enumerate(self.faces):
            p = self.face_points(k)
            nv = newell_normal(p)
            if 0.5 * np.linalg.norm(nv) <= (1e-3 * tol * scale) ** 2:
                raise GeometryError(f"{name}: face {k} has zero area")
            d = np.abs((p - p.mean(axis=0)) @ (nv / np.linalg.norm(nv)))
            if d.max() > tol * scale:
                raise GeometryError(
                    f"{name}: face {k} is not planar (a vertex lies {d.max():.3g} m off its plane)"
                )
        if not self.volume > 0.0:
            raise GeometryError(
                f"{name}: the faces are inverted (volume {self.volume:.6g} m^3 <= 0); "
                "list each face counter-clockwise seen from outside"
            )


_HEX_FACES = ((0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7))


def prism(bottom: ArrayLike, top: ArrayLike) -> Polyhedron:
    """Polyhedron between two polygonal loops with the same number of vertices.

    ``bottom[i]`` is joined to ``top[i]`` by a side face. The loops may run either way:
    faces are oriented outwards from the sign of the volume.
    """
    b, t = np.asarray(bottom, float), np.asarray(top, float)
    k = len(b)
    faces = [tuple(range(k - 1, -1, -1)), tuple(range(k, 2 * k))]
    faces += [(i, (i + 1) % k, k + (i + 1) % k, k + i) for i in range(k)]
    poly = Polyhedron(np.vstack([b, t]), faces)
    if poly.volume < 0:
        poly = Polyhedron(poly.vertices, [f[::-1] for f in faces])
    return poly


def box(lo: ArrayLike, hi: ArrayLike) -> Polyhedron:
    """Axis-aligned box between corners ``lo`` and ``hi`` (m), faces oriented outwards."""
    (x0, y0, z0), (x1, y1, z1) = np.asarray(lo, float), np.asarray(hi, float)
    bottom = [[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0]]
    top = [[x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]]
    return prism(bottom, top)
