"""Hemispherical dome generator and radial support settlements.

Axes (docs/conventions.md): z is up, the dome's axis is the z axis, its centre (the centre of the
sphere) is at the origin and its base ring lies in the plane z = 0. Lengths in m, unit
weights in kN/m^3.

Discretisation
--------------
The shell between the spheres of radii ``Ri = R - t/2`` and ``Ro = R + t/2`` (``R`` the
mid-surface radius, ``t`` the thickness) is cut by

* ``sectors`` meridian planes through the axis, at azimuths ``psi_j = 2 pi j / sectors``
  measured from +x towards +y, and
* ``courses + 1`` cones with their apex at the centre (the bed joints, normal to the
  meridians), at colatitudes ``theta_k`` equally spaced from the crown opening ``theta_0``
  (the ``oculus`` half-angle; 0 for a closed crown) down to the base ``theta = 90 deg``.

Each voussoir is the hexahedron spanned by its 8 corners on the two spheres, with **exactly
planar** faces: meridian faces in meridian planes, bed faces through the centre (two
generators of a cone through its apex), intrados and extrados isosceles trapezoids. The
blocks are inscribed in the shell, so the facetted volume tends to the shell's from below
as the discretisation is refined.

With a closed crown (``oculus = 0``) the top course is made of ``sectors`` wedges that meet
on the axis: triangular prisms whose intrados and extrados are triangles with a vertex on
the axis (no separate keystone).

Blocks and names
----------------
Support blocks ``s01 .. sS`` (one per sector, so each can move alone) come first, then the
voussoirs ``c01s01 .. cCsS`` course by course from the base (``c01``) to the crown, sector
by sector. Each support is the prism under its sector's base joint (a trapezoid in z = 0),
``support_height`` deep. Interfaces: support ``s_j`` -> ``c01s_j`` (normal up); course
``k`` -> course ``k+1`` in each sector (normal up the meridian); and between neighbouring
sectors of a course. Every interface has ``a < b`` (block indices), its normal from A into
B. Supports have no interfaces between each other (they would carry no unknowns,
:mod:`tce.core.model`).
"""

from __future__ import annotations

import math
import numpy as np
from numpy.typing import NDArray

from .params import check_blocks, check_positive, check_whole
from .assembly import Assembly, Block, Interface
from .geometry import FaceTable, PolygonTable, oriented_polyhedra, prisms

__all__ = ["hemispherical_dome", "radial_settlement", "shell_centroid_height", "shell_volume"]


def _corners(r: float, thetas: NDArray[np.float64], psis: NDArray[np.float64]) -> NDArray[np.float64]:
    """Points at radius ``r`` (m), colatitudes ``thetas`` and azimuths ``psis`` (rad), as a
    ``(len(thetas), len(psis), 3)`` grid; the base row (``thetas[0]``, 90 deg) exactly at z = 0."""
    st = np.sin(thetas)[:, None]
    x = r * st * np.cos(psis)[None, :]
    y = r * st * np.sin(psis)[None, :]
    z = np.broadcast_to(r * np.cos(thetas)[:, None], x.shape).copy()
    z[0] = 0.0
    return np.stack([x, y, z], axis=-1)


#: faces of a crown wedge with vertices (axis inner, i1, i2, axis outer, o1, o2)
_WEDGE_FACES = ((0, 1, 2), (3, 5, 4), (1, 4, 5, 2), (0, 3, 4, 1), (0, 2, 5, 3))


def hemispherical_dome(
    radius: float = 5.0,
    thickness: float = 0.3,
    sectors: int = 16,
    courses: int = 8,
    oculus: float = 0.0,
    unit_weight: float = 20.0,
    support_height: float | None = None,
) -> Assembly:
    """Hemispherical dome of voussoirs on one support block per sector.

    Parameters
    ----------
    radius : float
        Radius of the **mid-surface** (centre-line) sphere, ``R`` (m), as in Heyman's
        ``t/R``; the intrados radius is ``R - t/2`` and the extrados radius ``R + t/2``.
    thickness : float
        Shell thickness ``t`` (m), ``0 < t < 2 R``.
    sectors : int
        Number of meridian sectors (>= 3).
    courses : int
        Number of courses (rings) between the crown and the base (>= 1).
    oculus : float
        Half-angle (degrees) of the crown opening, measured from the axis; 0 closes the
        crown with wedges meeting on the axis. ``0 <= oculus < 90``.
    unit_weight : float
        Unit weight of every block (kN/m^3).
    support_height : float, optional
        Height of the support blocks below z = 0 (m); defaults to the thickness.

    Returns
    -------
    Assembly
        See the module docstring for names, order and interfaces. ``meta`` holds the
        generator's name and parameters (``generator="hemispherical_dome"``).

    Raises
    ------
    ValueError
        A parameter out of range, naming it.
    """
    check_positive(radius=radius, thickness=thickness, unit_weight=unit_weight)
    sectors = check_whole(sectors, "sectors", 3)
    courses = check_whole(courses, "courses")
    check_blocks(sectors * (courses + 1), f"sectors x (courses + 1) = {sectors} x ({courses} + 1)")
    if not thickness < 2.0 * radius:
        raise ValueError(f"thickness must be < 2 * radius (the intrados radius R - t/2 > 0), got {thickness!r}")
    try:
        ok = math.isfinite(float(oculus)) and 0.0 <= float(oculus) < 90.0
    except (TypeError, ValueError):
        ok = False
    if not ok:
        raise ValueError(f"oculus must be a half-angle in degrees, 0 <= oculus < 90, got {oculus!r}")
    h = float(thickness) if support_height is None else support_height
    check_positive(support_height=h)

    R, t = float(radius), float(thickness)
    ri, ro = R - t / 2.0, R + t / 2.0
    theta0 = math.radians(float(oculus))
    # colatitudes from the base (index 0, theta = 90 deg) up to the crown opening
    thetas = np.linspace(math.pi / 2.0, theta0, courses + 1)
    psis = np.linspace(0.0, 2.0 * math.pi, sectors + 1)
    S, C = sectors, courses
    # corners on the intrados and extrados: [k, j] at colatitude thetas[k], azimuth psis[j % S]
    around = psis[np.arange(S + 1) % S]
    inner, outer = _corners(ri, thetas, around), _corners(ro, thetas, around)
    wedges = theta0 == 0.0  # a closed crown: wedges meeting on the axis
    lo, hi = slice(0, S), slice(1, S + 1)  # sector j spans azimuths j .. j + 1

    # supports: the prism under each sector's base joint
    top = np.stack([inner[0, lo], inner[0, hi], outer[0, hi], outer[0, lo]], axis=1)  # (S, 4, 3)
    shapes = prisms(top - np.array([0.0, 0.0, h]), top)
    # voussoirs of the courses k = 1 .. C (between thetas[k - 1] and thetas[k]), sector by sector
    ring = C - 1 if wedges else C
    k0 = np.repeat(np.arange(ring), S)  # lower joint index of each voussoir
    js = np.tile(np.arange(S), ring)
    quad = lambda g, k, j: np.stack([g[k, j], g[k, j + 1], g[k + 1, j + 1], g[k + 1, j]], axis=1)  # noqa: E731
    shapes += prisms(quad(inner, k0, js), quad(outer, k0, js))
    j = np.arange(S)
    axis_i = np.broadcast_to([0.0, 0.0, ri], (S, 3))  # the crown wedges' points on the axis
    axis_o = np.broadcast_to([0.0, 0.0, ro], (S, 3))
    if wedges:
        # crown wedges: axis points (inner, outer) and the lower corners of the top course
        verts = np.stack([axis_i, inner[C - 1, j], inner[C - 1, j + 1], axis_o, outer[C - 1, j], outer[C - 1, j + 1]], axis=1)
        shapes += oriented_polyhedra(verts, _WEDGE_FACES)
    wj = max(2, len(str(S)))
    wk = max(2, len(str(C)))
    names = [f"s{j + 1:0{wj}d}" for j in range(S)]
    names += [f"c{k:0{wk}d}s{j + 1:0{wj}d}" for k in range(1, C + 1) for j in range(S)]
    uw = float(unit_weight)
    blocks = [Block(name, shape, uw, i < S) for i, (name, shape) in enumerate(zip(names, shapes))]

    def vid(k: int | NDArray, j: int | NDArray) -> NDArray:
        """Index of the voussoir of course k (1-based) in sector j (0-based, wrapped)."""
        return S + (np.asarray(k) - 1) * S + (np.asarray(j) % S)

    # interfaces in order: base joints; then per course, sector by sector, the bed joint above
    # it (below the top course) and the meridian joint at psi_{j+1} towards the next sector
    parts = [(j, vid(1, j), top)]
    for k in range(1, C + 1):
        if wedges and k == C:
            mer = np.stack([inner[k - 1, j + 1], outer[k - 1, j + 1], axis_o, axis_i], axis=1)
        else:
            mer = np.stack([inner[k - 1, j + 1], outer[k - 1, j + 1], outer[k, j + 1], inner[k, j + 1]], axis=1)
        if k < C:
            bed = np.stack([inner[k, j], inner[k, j + 1], outer[k, j + 1], outer[k, j]], axis=1)
            a = np.stack([vid(k, j), vid(k, j)], axis=1).ravel()
            b = np.stack([vid(k + 1, j), vid(k, j + 1)], axis=1).ravel()
            parts.append((a, b, np.stack([bed, mer], axis=1).reshape(-1, 4, 3)))
        else:
            parts.append((vid(k, j), vid(k, j + 1), mer))
    a = np.concatenate([p[0] for p in parts])
    b = np.concatenate([p[1] for p in parts])
    pts = np.concatenate([p[2] for p in parts])
    a, b = np.minimum(a, b), np.maximum(a, b)
    normal = PolygonTable(pts.reshape(-1, 3), np.arange(len(pts) + 1) * 4).newell
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    centroids = FaceTable.of(shapes).centroid
    flip = np.einsum("ij,ij->i", normal, centroids[b] - centroids[a]) < 0
    pts[flip] = pts[flip, ::-1]
    normal[flip] *= -1.0
    interfaces = [Interface(int(a[i]), int(b[i]), pts[i], normal[i]) for i in range(len(a))]

    meta = dict(generator="hemispherical_dome", radius=R, thickness=t, inner_radius=ri, outer_radius=ro,
                sectors=sectors, courses=courses, oculus=float(oculus), unit_weight=float(unit_weight),
                support_height=float(h))
    return Assembly(tuple(blocks), tuple(interfaces), meta)


def radial_settlement(
    assembly: Assembly,
    magnitude: float,
    centre: tuple[float, float] | None = None,
) -> dict[str, list[float]]:
    """Horizontal radial translation of every support block.

    Parameters
    ----------
    magnitude : float
        Displacement (m) along each support's own horizontal radius: positive outward
        (away from the axis), negative inward.
    centre : (x, y), optional
        Point of the vertical axis (m); defaults to the origin for a generated dome
        (``meta["generator"] == "hemispherical_dome"``) and to the mean of the support
        centroids otherwise.

    Returns
    -------
    dict
        ``{support_name: [ux, uy, 0, 0, 0, 0]}`` (m, rad), ready for
        :meth:`tce.core.solve.TCESolver.solve`.

    Raises
    ------
    ValueError
        A non-finite magnitude, or a support whose centroid lies on the axis.
    """
    m = float(magnitude)
    if not math.isfinite(m):
        raise ValueError(f"magnitude must be a finite number, got {magnitude!r}")
    idx = assembly.support_indices
    c = assembly.centroids[list(idx)] if idx else np.zeros((0, 3))
    if centre is None:
        if assembly.meta.get("generator") == "hemispherical_dome" or not len(c):
            o = np.zeros(2)
        else:
            o = c[:, :2].mean(axis=0)
    else:
        o = np.asarray(centre, dtype=float).reshape(2)
    out: dict[str, list[float]] = {}
    for i, ci in zip(idx, c):
        d = ci[:2] - o
        nd = float(np.linalg.norm(d))
        if nd <= 1e-12 * max(assembly.size, 1.0):
            raise ValueError(f"support {assembly.names[i]!r} lies on the axis: no radial direction")
        u = m * d / nd
        out[assembly.names[i]] = [float(u[0]), float(u[1]), 0.0, 0.0, 0.0, 0.0]
    return out


def shell_volume(radius: float, thickness: float, oculus: float = 0.0) -> float:
    """Volume (m^3) of the exact hemispherical shell of mid-surface radius ``radius`` and
    thickness ``thickness``, with a crown opening of half-angle ``oculus`` (degrees)."""
    ri, ro = radius - thickness / 2.0, radius + thickness / 2.0
    return 2.0 / 3.0 * math.pi * (ro**3 - ri**3) * math.cos(math.radians(oculus))


def shell_centroid_height(radius: float, thickness: float) -> float:
    """Height (m) of the centroid of the exact closed hemispherical shell above its base."""
    ri, ro = radius - thickness / 2.0, radius + thickness / 2.0
    return 3.0 / 8.0 * (ro**4 - ri**4) / (ro**3 - ri**3)
