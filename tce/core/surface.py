"""What every load module shares: the errors of a load declaration, its checked vectors, and
the exposed top surface of an assembly on which loads act (:func:`top_surface`, found by a
downward ray through the upward-facing faces: :func:`_on_top`).

:mod:`tce.core.loads` (point and distributed loads, patterns, resolution),
:mod:`tce.core.vehicles` (axle groups) and :mod:`tce.core.fill` (fill over an arch) build on
it; it imports none of them.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np
import shapely
from numpy.typing import ArrayLike, NDArray

from ..structures.assembly import Assembly

__all__ = ["UPWARD", "LoadError", "top_surface"]

#: a face is part of the top surface when its outward normal has a z component above this
UPWARD = 1e-6


class LoadError(ValueError):
    """A load declaration that cannot be applied: ``key`` names it (``point[0].force``)."""

    def __init__(self, key: str, problem: str, fix: str) -> None:
        self.key, self.problem, self.fix = key, problem, fix
        super().__init__(f"{key}: {problem}; fix: {fix}" if key else f"{problem}; fix: {fix}")

    def within(self, prefix: str) -> LoadError:
        """The same error with its key under ``prefix`` (``point[0]`` + ``force``)."""
        return LoadError(f"{prefix}.{self.key}" if self.key else prefix, self.problem, self.fix)


def _vector(value: ArrayLike, n: int, key: str, unit: str) -> tuple[float, ...]:
    """``value`` as a tuple of ``n`` finite floats (``LoadError`` naming ``key`` otherwise)."""
    try:
        v = np.asarray(value, dtype=float).ravel()
    except (TypeError, ValueError):
        raise LoadError(key, f"not a list of numbers ({value!r})", f"give {n} numbers ({unit})") from None
    if v.shape != (n,):
        raise LoadError(key, f"{len(v)} numbers given", f"give exactly {n} numbers ({unit})")
    if not np.all(np.isfinite(v)):
        raise LoadError(key, f"NaN or infinite entries ({value!r})", f"give finite numbers ({unit})")
    return tuple(float(x) for x in v)


# ---------------------------------------------------------------------------- top surface
@dataclass(frozen=True, eq=False)
class _Faces:
    """Upward-facing faces of an assembly: owner block, plan polygon and plane."""

    block: NDArray[np.int64]
    plan: NDArray[np.object_]  # shapely Polygons, the faces projected on the x-y plane
    point: NDArray[np.float64]  # (k, 3) a point of each face
    normal: NDArray[np.float64]  # (k, 3) outward unit normals, n_z > UPWARD

    def z(self, k: int | NDArray[np.int64], x: ArrayLike, y: ArrayLike) -> NDArray[np.float64]:
        """Height (m) of face(s) ``k``'s plane above plan point(s) ``(x, y)``."""
        p, n = self.point[k], self.normal[k]
        return p[..., 2] - (n[..., 0] * (np.asarray(x) - p[..., 0]) + n[..., 1] * (np.asarray(y) - p[..., 1])) / n[..., 2]


@lru_cache(maxsize=16)
def _upward_faces(assembly: Assembly) -> _Faces:
    block, plan, point, normal = [], [], [], []
    for i, b in enumerate(assembly.blocks):
        for k, n in enumerate(b.shape.face_normals):
            if n[2] > UPWARD:
                pts = b.shape.face_points(k)
                block.append(i)
                plan.append(shapely.Polygon(pts[:, :2]))
                point.append(pts.mean(axis=0))
                normal.append(n)
    return _Faces(np.array(block, dtype=np.int64), np.array(plan, dtype=object),
                  np.array(point).reshape(-1, 3), np.array(normal).reshape(-1, 3))


@lru_cache(maxsize=16)
def top_surface(assembly: Assembly) -> tuple[tuple[int, int, shapely.Polygon], ...]:
    """The exposed top surface of an assembly, in plan: ``(block, face, polygon)`` parts.

    An upward-facing face (outward normal with ``n_z > UPWARD``) is exposed where no other
    upward-facing face lies above it: for each plan point, only the highest face counts
    (the extrados of an arch, not the joints under the next voussoir). Two faces whose plan
    projections overlap are ordered by their heights at a point of the overlap (blocks do
    not interpenetrate, so one lies above the other over all of it). ``face`` indexes the
    assembly's upward faces; each polygon is one connected exposed piece (m, plan).
    """
    faces = _upward_faces(assembly)
    tree = shapely.STRtree(faces.plan)
    eps = (1e-9 * assembly.size) ** 2
    out = []
    for i, poly in enumerate(faces.plan):
        exposed = poly
        for j in tree.query(poly, predicate="intersects"):
            if j == i:
                continue
            overlap = poly.intersection(faces.plan[j])
            if overlap.area <= eps:
                continue
            q = overlap.representative_point()
            if faces.z(j, q.x, q.y) > faces.z(i, q.x, q.y):
                exposed = exposed.difference(faces.plan[j])
        for piece in getattr(exposed, "geoms", [exposed]):
            if isinstance(piece, shapely.Polygon) and piece.area > eps:
                out.append((int(faces.block[i]), i, piece))
    return tuple(out)


def _on_top(assembly: Assembly, xy: tuple[float, float]) -> tuple[int, NDArray[np.float64]]:
    """Block and point of the highest top surface above plan point ``xy`` (a downward ray
    through the upward-facing faces); ties go to a free block. Raises ``LoadError``."""
    faces = _upward_faces(assembly)
    x, y = xy
    hit = np.flatnonzero(shapely.intersects_xy(faces.plan, x, y))
    if hit.size == 0:
        lo, hi = assembly.face_table.lo.min(axis=0), assembly.face_table.hi.max(axis=0)
        raise LoadError(
            "on_top", f"[{x:g}, {y:g}] is outside the plan of the structure: no block lies under it (the plan spans "
            f"x from {lo[0]:.4g} to {hi[0]:.4g} m, y from {lo[1]:.4g} to {hi[1]:.4g} m)",
            "give a plan point above a block",
        )
    z = faces.z(hit, x, y)
    top = z.max()
    support = np.array([assembly.blocks[b].support for b in faces.block[hit]])
    best = hit[(z >= top - 1e-9 * assembly.size) & ~support]
    k = int(best[0]) if best.size else int(hit[np.argmax(z)])
    return int(faces.block[k]), np.array([x, y, float(faces.z(k, x, y))])


