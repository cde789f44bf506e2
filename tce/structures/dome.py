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

Each voussoir takes the 8 points of its corners on the two spheres and is the hexahedron
they span, with **exactly planar** faces: its two meridian faces lie in meridian planes;
its two bed faces are planes through the centre (two generators of a cone through its
apex); its intrados and extrados are isosceles trapezoids (two horizontal chords symmetric
about the mid-meridian), hence planar. The blocks are inscribed in the shell (their
vertices lie on the spheres), so the facetted volume tends to the shell's from below as the
discretisation is refined.

With a closed crown (``oculus = 0``) the top course is made of ``sectors`` wedges that meet
on the axis: each is a triangular prism whose intrados and extrados are triangles with a
vertex on the axis, and whose meridian faces are planar quadrilaterals in the meridian
planes. There is no separate keystone.

Blocks and names
----------------
Support blocks ``s01 .. sS`` (one per sector, so each can move alone) come first, then the
voussoirs ``c01s01 .. cCsS`` course by course from the base (``c01``) to the crown, sector
by sector. Each support is the prism under its sector's base joint (a trapezoid in z = 0),
``support_height`` deep. Interfaces: support ``s_j`` -> ``c01s_j`` (normal up); course
``k`` -> course ``k+1`` in each sector (normal up the meridian, away from the base); and
between neighbouring sectors of a course. Every interface has ``a < b`` (block indices)
and its normal points from A into B. Supports do not get interfaces between each other
(they would carry no unknowns anyway, see :mod:`tce.model`).
"""

from __future__ import annotations

import math
import numpy as np
from numpy.typing import NDArray

from .params import check_positive, check_whole
from .assembly import Assembly, Block, Interface
from .geometry import Polyhedron, prism

__all__ = ["hemispherical_dome", "radial_settlement", "shell_centroid_height", "shell_volume"]


def _sph(r: float, theta: float, psi: float) -> NDArray[np.float64]:
    """Point at radius ``r``, colatitude ``theta`` and azimuth ``psi`` (rad)."""
    st = math.sin(theta)
    return np.array([r * st * math.cos(psi), r * st * math.sin(psi), r * math.cos(theta)])


def _wedge(ci: NDArray, co: NDArray, i1: NDArray, i2: NDArray, o1: NDArray, o2: NDArray) -> Polyhedron:
    """Triangular prism of a crown wedge: axis points ``ci`` (inner), ``co`` (outer) and the
    lower corners ``i1, i2`` (inner) and ``o1, o2`` (outer) at azimuths psi_j, psi_j+1."""
    v = np.array([ci, i1, i2, co, o1, o2])
    faces = [(0, 1, 2), (3, 5, 4), (1, 4, 5, 2), (0, 3, 4, 1), (0, 2, 5, 3)]
    poly = Polyhedron(v, faces)
    if poly.volume < 0:
        poly = Polyhedron(v, [f[::-1] for f in faces])
    return poly


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
    closed = theta0 == 0.0

    def corner(r: float, k: int, j: int) -> NDArray[np.float64]:
        p = _sph(r, thetas[k], psis[j % sectors])
        if k == 0:
            p[2] = 0.0  # exactly on the base plane
        return p

    wj = max(2, len(str(sectors)))
    wk = max(2, len(str(courses)))
    blocks: list[Block] = []
    # supports
    for j in range(sectors):
        top = np.array([corner(ri, 0, j), corner(ri, 0, j + 1), corner(ro, 0, j + 1), corner(ro, 0, j)])
        bottom = top - np.array([0.0, 0.0, h])
        blocks.append(Block(f"s{j + 1:0{wj}d}", prism(bottom, top), float(unit_weight), True))
    # voussoirs, course k between thetas[k-1] (lower) and thetas[k] (upper)
    for k in range(1, courses + 1):
        for j in range(sectors):
            name = f"c{k:0{wk}d}s{j + 1:0{wj}d}"
            if closed and k == courses:
                shape = _wedge(
                    np.array([0.0, 0.0, ri]), np.array([0.0, 0.0, ro]),
                    corner(ri, k - 1, j), corner(ri, k - 1, j + 1),
                    corner(ro, k - 1, j), corner(ro, k - 1, j + 1),
                )
            else:
                inner = [corner(ri, k - 1, j), corner(ri, k - 1, j + 1), corner(ri, k, j + 1), corner(ri, k, j)]
                outer = [corner(ro, k - 1, j), corner(ro, k - 1, j + 1), corner(ro, k, j + 1), corner(ro, k, j)]
                shape = prism(inner, outer)
            blocks.append(Block(name, shape, float(unit_weight)))

    def vid(k: int, j: int) -> int:
        """Index of the voussoir of course k (1-based) in sector j (0-based, wrapped)."""
        return sectors + (k - 1) * sectors + (j % sectors)

    interfaces: list[Interface] = []

    def add(a: int, b: int, pts: list[NDArray[np.float64]]) -> None:
        p = np.array(pts)
        if a > b:
            a, b = b, a
        itf = Interface(a, b, p)
        if itf.normal @ (blocks[b].centroid - blocks[a].centroid) < 0:
            itf = Interface(a, b, p[::-1], -itf.normal)
        interfaces.append(itf)

    for j in range(sectors):
        # base joints
        add(j, vid(1, j), [corner(ri, 0, j), corner(ri, 0, j + 1), corner(ro, 0, j + 1), corner(ro, 0, j)])
    for k in range(1, courses + 1):
        wedge_course = closed and k == courses
        for j in range(sectors):
            # bed joint above course k
            if k < courses:
                add(vid(k, j), vid(k + 1, j),
                    [corner(ri, k, j), corner(ri, k, j + 1), corner(ro, k, j + 1), corner(ro, k, j)])
            # meridian joint between sector j and j+1 at psi_{j+1}
            if wedge_course:
                pts = [corner(ri, k - 1, j + 1), corner(ro, k - 1, j + 1), np.array([0.0, 0.0, ro]), np.array([0.0, 0.0, ri])]
            else:
                pts = [corner(ri, k - 1, j + 1), corner(ro, k - 1, j + 1), corner(ro, k, j + 1), corner(ri, k, j + 1)]
            add(vid(k, j), vid(k, j + 1), pts)

    meta = dict(
        generator="hemispherical_dome",
        radius=R,
        thickness=t,
        inner_radius=ri,
        outer_radius=ro,
        sectors=sectors,
        courses=courses,
        oculus=float(oculus),
        unit_weight=float(unit_weight),
        support_height=float(h),
    )
    return Assembly(tuple(blocks), tuple(interfaces), meta)


def radial_settlement(
    assembly: Assembly,
    magnitude: float,
    centre: tuple[float, float] | None = None,
) -> dict[str, list[float]]:
    """Horizontal radial translation of every support block.

    Parameters
    ----------
    assembly : Assembly
        Any assembly with supports (typically :func:`hemispherical_dome`).
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
        :meth:`tce.solve.TCESolver.solve`.

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
