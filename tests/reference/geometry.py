"""Reference geometry: interface frames, tributary areas, closed-form block volumes and centroids.

Axes as in ``docs/conventions.md``: SI units, z up; an arch spans along x with its depth along
y from -depth/2 to +depth/2, springings at z = 0 and its centre at the origin; a dome has its
axis on z, the centre of its spheres at the origin and its base in z = 0.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

EX = np.array([1.0, 0.0, 0.0])
EZ = np.array([0.0, 0.0, 1.0])


# ---------------------------------------------------------------------- interfaces
def frame(normal) -> np.ndarray:
    """Interface frame, rows ``(n, t1, t2)``, from its definition.

    ``t1`` is the direction of steepest ascent in the interface plane (the projection of +z,
    normalised) unless the plane is horizontal, then +x; ``t2 = n x t1``.
    """
    n = np.asarray(normal, dtype=float)
    n = n / math.sqrt(n[0] ** 2 + n[1] ** 2 + n[2] ** 2)
    if math.hypot(n[0], n[1]) < 1e-6:  # horizontal plane
        t1 = EX - n[0] * n
    else:
        t1 = EZ - n[2] * n
    t1 = t1 / np.linalg.norm(t1)
    t2 = np.array([n[1] * t1[2] - n[2] * t1[1], n[2] * t1[0] - n[0] * t1[2], n[0] * t1[1] - n[1] * t1[0]])
    return np.vstack([n, t1, t2])


def _shoelace(u: np.ndarray, v: np.ndarray) -> float:
    """Signed area of a 2D polygon."""
    return 0.5 * float(np.sum(u * np.roll(v, -1) - np.roll(u, -1) * v))


def tributary_areas(points, normal) -> np.ndarray:
    """Share of a convex planar polygon's area lumped at each vertex (m^2).

    Vertex ``i`` gets the quadrilateral (midpoint of the previous edge, the vertex, midpoint
    of the next edge, polygon centroid), worked out in 2D coordinates of the polygon's plane.
    """
    p = np.asarray(points, dtype=float)
    f = frame(normal)
    u, v = (p - p[0]) @ f[1], (p - p[0]) @ f[2]
    cross = u * np.roll(v, -1) - np.roll(u, -1) * v
    area = 0.5 * cross.sum()
    cu = ((u + np.roll(u, -1)) * cross).sum() / (6.0 * area)
    cv = ((v + np.roll(v, -1)) * cross).sum() / (6.0 * area)
    out = np.empty(len(p))
    for i in range(len(p)):
        j, k = (i + 1) % len(p), (i - 1) % len(p)
        qu = np.array([(u[k] + u[i]) / 2, u[i], (u[i] + u[j]) / 2, cu])
        qv = np.array([(v[k] + v[i]) / 2, v[i], (v[i] + v[j]) / 2, cv])
        out[i] = abs(_shoelace(qu, qv))
    return out


# ---------------------------------------------------------------------- blocks
@dataclass(frozen=True)
class Blocks:
    """Reference mass data of an assembly's blocks, in block order.

    Attributes
    ----------
    volume : (nb,) m^3
    centroid : (nb, 3) m
    unit_weight : (nb,) kN/m^3
    support : (nb,) bool
    """

    volume: np.ndarray
    centroid: np.ndarray
    unit_weight: np.ndarray
    support: np.ndarray

    @property
    def weight(self) -> np.ndarray:
        """Self-weights (kN)."""
        return self.volume * self.unit_weight


def box(vertices) -> tuple[float, np.ndarray]:
    """Volume and centroid of an axis-aligned box given by its 8 corners."""
    v = np.asarray(vertices, dtype=float)
    lo, hi = v.min(axis=0), v.max(axis=0)
    corners = {tuple(c) for c in v.round(12).tolist()}
    expected = {(x, y, z) for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])}
    assert corners == {tuple(np.round(c, 12)) for c in expected}, "not an axis-aligned box"
    return float(np.prod(hi - lo)), (lo + hi) / 2.0


def ring_sector(ri: float, ro: float, a0: float, a1: float) -> tuple[float, np.ndarray]:
    """Area and centroid (2D) of the chord-faced ring sector between angles ``a0`` and ``a1``.

    The quadrilateral with corners at radii ``ri`` and ``ro`` on the rays at ``a0`` and ``a1``
    is the difference of two isosceles triangles with their apex at the centre: a triangle of
    legs r has area ``r^2 sin(da) / 2`` and its centroid at ``2/3 r cos(da/2)`` on the
    bisector.
    """
    da = abs(a1 - a0)
    am = (a0 + a1) / 2.0
    area = (ro**2 - ri**2) * math.sin(da) / 2.0
    rho = 2.0 / 3.0 * math.cos(da / 2.0) * (ro**3 - ri**3) / (ro**2 - ri**2)
    return area, rho * np.array([math.cos(am), math.sin(am)])


def semicircular_arch(inner_radius=1.0, thickness=0.2, depth=0.25, voussoirs=14, unit_weight=20.0,
                      support_height=None) -> Blocks:
    """Blocks ``left, v01 .. vN, right`` of the chord-faced semicircular arch.

    Voussoir ``i`` spans the angles ``pi (1 - (i-1)/N)`` to ``pi (1 - i/N)``; a voussoir is the
    prism of its ring-sector cross-section (x, z) times the depth. The supports are the boxes
    under the springing joints, ``thickness`` wide, ``support_height`` (default: thickness) high.
    """
    ri, ro, n = inner_radius, inner_radius + thickness, voussoirs
    h = thickness if support_height is None else support_height
    box_volume = thickness * depth * h
    vol, cen = [box_volume], [[-(ri + ro) / 2.0, 0.0, -h / 2.0]]
    for i in range(n):
        area, c = ring_sector(ri, ro, math.pi * (1 - i / n), math.pi * (1 - (i + 1) / n))
        vol.append(area * depth)
        cen.append([c[0], 0.0, c[1]])
    vol.append(box_volume)
    cen.append([(ri + ro) / 2.0, 0.0, -h / 2.0])
    support = np.zeros(n + 2, dtype=bool)
    support[[0, -1]] = True
    return Blocks(np.array(vol), np.array(cen), np.full(n + 2, float(unit_weight)), support)


def arch_centroid_height(inner_radius: float, thickness: float, voussoirs: int) -> float:
    """Height (m) of the centroid of the voussoirs of the chord-faced semicircular arch.

    Equal voussoirs with centroids at radius ``rho = 2/3 cos(da/2) (ro^3 - ri^3)/(ro^2 - ri^2)``
    on the bisectors ``(k + 1/2) da``, ``da = pi/N``; ``sum_k sin((k + 1/2) da) = 1/sin(da/2)``.
    """
    ri, ro, n = inner_radius, inner_radius + thickness, voussoirs
    da = math.pi / n
    rho = 2.0 / 3.0 * math.cos(da / 2.0) * (ro**3 - ri**3) / (ro**2 - ri**2)
    return rho / (n * math.sin(da / 2.0))


def _pyramid_over_trapezoid(r: float, th_lo: float, th_hi: float, psi0: float, psi1: float) -> tuple[float, np.ndarray]:
    """Volume and centroid of the pyramid with apex at the origin over the planar face with
    corners at radius ``r``, colatitudes ``th_lo > th_hi`` and azimuths ``psi0 < psi1``.

    The face is an isosceles trapezoid (a triangle when ``th_hi = 0``): horizontal chords of
    lengths ``c = 2 r sin(th) sin(dpsi/2)`` whose midpoints lie in the mid-meridian plane at
    ``P = r (sin(th) cos(dpsi/2), cos(th))`` (horizontal radius, height). The face is normal
    to that plane, so its distance to the apex is that of the line ``P_lo P_hi`` from the
    origin, and the pyramid's volume is ``(c_lo + c_hi) |P_lo x P_hi| / 6``. Its centroid is
    3/4 of the way from the apex to the trapezoid's centroid, which lies on ``P_lo P_hi`` at
    ``(c_lo + 2 c_hi) / (3 (c_lo + c_hi))`` of the way from ``P_lo``.
    """
    dpsi = psi1 - psi0
    pm = (psi0 + psi1) / 2.0
    c_lo, c_hi = (2 * r * math.sin(t) * math.sin(dpsi / 2) for t in (th_lo, th_hi))
    P_lo, P_hi = (r * np.array([math.sin(t) * math.cos(dpsi / 2), math.cos(t)]) for t in (th_lo, th_hi))
    vol = (c_lo + c_hi) * abs(P_lo[0] * P_hi[1] - P_lo[1] * P_hi[0]) / 6.0
    g = P_lo + (P_hi - P_lo) * (c_lo + 2 * c_hi) / (3 * (c_lo + c_hi))
    centroid = 0.75 * np.array([g[0] * math.cos(pm), g[0] * math.sin(pm), g[1]])
    return vol, centroid


def dome_voussoir(ri: float, ro: float, th_lo: float, th_hi: float, psi0: float, psi1: float) -> tuple[float, np.ndarray]:
    """Volume and centroid of a dome voussoir between radii ``ri < ro``, colatitudes
    ``th_lo > th_hi`` and azimuths ``psi0 < psi1``.

    Its meridian and bed faces lie in planes through the centre of the spheres, so the
    voussoir is the pyramid (apex at the centre) over its extrados face minus the one over
    its intrados face: ``V = (h_o A_o - h_i A_i) / 3``.
    """
    vo, co = _pyramid_over_trapezoid(ro, th_lo, th_hi, psi0, psi1)
    vi, ci = _pyramid_over_trapezoid(ri, th_lo, th_hi, psi0, psi1)
    return vo - vi, (vo * co - vi * ci) / (vo - vi)


def hemispherical_dome(radius=5.0, thickness=0.3, sectors=16, courses=8, unit_weight=20.0,
                       support_height=None) -> Blocks:
    """Blocks of the closed-crown hemispherical dome: supports ``s01 .. sS`` (prisms under the
    base joints, ``support_height`` deep, default the thickness), then the voussoirs course by
    course from the base, sector by sector; colatitudes equally spaced from 90 deg to 0,
    azimuths from 0."""
    ri, ro = radius - thickness / 2.0, radius + thickness / 2.0
    h = thickness if support_height is None else support_height
    th = np.linspace(math.pi / 2, 0.0, courses + 1)
    psi = np.linspace(0.0, 2 * math.pi, sectors + 1)
    vol, cen = [], []
    for j in range(sectors):
        area, c = ring_sector(ri, ro, psi[j], psi[j + 1])
        vol.append(area * h)
        cen.append([c[0], c[1], -h / 2.0])
    for k in range(courses):
        for j in range(sectors):
            v, c = dome_voussoir(ri, ro, th[k], th[k + 1], psi[j], psi[j + 1])
            vol.append(v)
            cen.append(c)
    nb = sectors * (courses + 1)
    support = np.arange(nb) < sectors
    return Blocks(np.array(vol), np.array(cen), np.full(nb, float(unit_weight)), support)
