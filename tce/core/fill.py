"""Fill over an arch: its weight on each block, live loads dispersed through it, its at-rest
horizontal pressure. Each part can be switched off.

The fill is a soil layer whose surface (the road) lies ``depth`` above the highest point of
the free blocks' exposed top surface (the crown's extrados); it bears on that top surface
(:func:`tce.core.surface.top_surface`). It is a load, not blocks: its weight and pressure are
fixed loads (part of ``b_fixed``), and it adds no strength of its own.

- **Weight** (``weight = true``): each exposed top-surface piece of a free block carries the
  fill column above it, ``W = gamma * integral over the piece's plan of (road - z) dA``
  (kN), vertical, at the column's plan centroid on the face. Pieces of support blocks carry
  theirs into the ground (left out).
- **Dispersion** (``dispersion`` > 0, degrees from the vertical): a vehicle's wheel at road
  level (a point, or its contact patch ``l x w``) spreads through the fill to the extrados
  as a rectangle ``(l + 2 h tan(theta)) x (w + 2 h tan(theta))`` under a uniform pressure,
  ``h`` the fill thickness under the wheel's centre. The default, 26.57 degrees (a slope of
  1 horizontal to 2 vertical), is the "2:1 method" of soil mechanics (e.g. Holtz & Kovacs,
  *An Introduction to Geotechnical Engineering*, 1981, stress distribution under a loaded
  area); 0 switches it off (the wheel load is applied at the extrados as declared).
- **Boussinesq dispersion** (``dispersion = "boussinesq"``): each wheel (a point, or its
  patch as 4 x 4 equal point loads at the centres of its cells) spreads as in an elastic
  half-space under a vertical point load ``Q`` at its surface (Boussinesq, *Application des
  potentiels*, 1885): the vertical stress on a horizontal plane at depth ``h`` is
  ``sigma_z = 3 Q h^3 / (2 pi (r^2 + h^2)^(5/2))`` (e.g. Holtz & Kovacs 1981, stresses from a
  point load). ``h`` is the fill under the wheel's centre, as for the spread angle; each
  exposed top-surface piece takes the integral of ``sigma_z`` over its plan (the extrados
  projected onto that plane) at the stress's centroid, both in closed form over the piece's
  plan rectangle (the integral over a rectangle is Newmark's corner influence factor, 1935);
  the part beyond the deck (the stress has an infinite tail) or over a support is dropped with
  a note. Pieces must be rectangles in plan (any orientation), as every top face of the arch
  and bridge generators is; it needs ``depth`` > 0.
- **Horizontal pressure at rest** (``k0`` > 0): the fill presses on each exposed piece with
  the vertical stress ``sigma_v = gamma (road - z)`` and the horizontal stress ``k0 sigma_v``
  (at rest; Jaky 1944: ``k0 = 1 - sin(phi)`` for a normally consolidated soil of friction
  angle ``phi``). On a plane face of outward normal ``n`` the horizontal traction per unit
  plan area is ``-k0 sigma_v (n_x, n_y) / n_z``; it is proportional to the column's weight
  density, so its resultant ``-k0 (n_x, n_y) / n_z * W`` acts at the same point as the
  weight, exactly. It pushes each haunch towards the crown.
- **Passive restraint** (``kp`` > 0; 0, the default, switches it off): the fill resists a
  voussoir that moves into it with a horizontal pressure up to the passive one, ``kp
  sigma_v`` (Rankine: ``kp = (1 + sin(phi)) / (1 - sin(phi))``). It is not a fixed load: each
  exposed piece gets a horizontal force ``p`` of its own, pointing from the fill into the
  ring, ``0 <= p <= (kp - k0) |n_h| / n_z * W`` (the pressure between at rest and passive
  over the piece's vertical projection; ``n_h`` the horizontal part of the outward normal),
  an unknown of the direct limit analysis and of every TCE force state
  (:mod:`tce.core.passive`): the fill resists, never drives. This is the backfill restraint
  of mechanism programs for arch bridges, specified separately from the live load's spread
  (Gilbert, Smith, Melbourne and Wang, "Experimental study of soil-arch interaction in
  masonry bridges"; M. A. Crisfield and A. J. Packham, "A mechanism program for computing
  the strength of masonry arch bridges", TRRL Research Report 124, 1987; M. Gilbert, *RING
  1.5 Theory and Modelling Guide*, University of Sheffield, 2005, "Modelling backfill"),
  here with the full passive pressure and no wall friction; a partly mobilised pressure is a
  smaller ``kp`` (e.g. ``k0 + m (Kp - k0)``, ``m`` the mobilisation).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import shapely

from ..structures.assembly import Assembly
from .surface import LoadError, _upward_faces, _vector, top_surface

__all__ = ["BOUSSINESQ", "DISPERSION_2_TO_1", "Fill", "boussinesq_parts", "boussinesq_rectangle", "fill_columns", "fill_forces", "passive_bounds", "road_level"]

#: the 2:1 method's spread angle from the vertical (degrees): atan(1/2)
DISPERSION_2_TO_1 = math.degrees(math.atan(0.5))
#: the ``dispersion`` of Boussinesq's elastic distribution
BOUSSINESQ = "boussinesq"
#: a wheel's patch is this many x this many equal point loads under Boussinesq's distribution
PATCH_POINTS = 4


@dataclass(frozen=True)
class Fill:
    """Fill over the top surface (see module docstring).

    Parameters
    ----------
    depth : float
        Depth of fill over the crown (m, >= 0): the road lies this far above the highest
        point of the free blocks' top surface.
    unit_weight : float
        Unit weight of the fill (kN/m^3, > 0).
    weight : bool
        Apply the weight of the fill columns (default true).
    dispersion : float or "boussinesq"
        Spread angle of wheel loads through the fill, degrees from the vertical, in
        ``[0, 60]``; default :data:`DISPERSION_2_TO_1`; 0: no dispersion; or
        ``"boussinesq"``: Boussinesq's elastic distribution (module docstring).
    k0 : float
        Coefficient of horizontal pressure at rest (>= 0, < 1 as soils have it); 0
        (default): no horizontal pressure.
    kp : float
        Coefficient of passive pressure (0, the default: no passive restraint; else >= 1 and
        > ``k0``), the bound of the fill's resistance to a voussoir moving into it.
    """

    depth: float
    unit_weight: float
    weight: bool = True
    dispersion: float | str = DISPERSION_2_TO_1
    k0: float = 0.0
    kp: float = 0.0

    def __post_init__(self) -> None:
        (depth,) = _vector([self.depth], 1, "depth", "m")
        (gamma,) = _vector([self.unit_weight], 1, "unit_weight", "kN/m^3")
        if isinstance(self.dispersion, str):
            if self.dispersion != BOUSSINESQ:
                raise LoadError("dispersion", repr(self.dispersion), f"give a spread angle (degrees) or {BOUSSINESQ!r}")
            if not depth > 0:
                raise LoadError("dispersion", f"{BOUSSINESQ!r} under {depth:g} m of fill",
                                "give a positive depth (a point load at the surface has no spread)")
            angle = BOUSSINESQ
        else:
            (angle,) = _vector([self.dispersion], 1, "dispersion", "degrees from the vertical")
        (k0,) = _vector([self.k0], 1, "k0", "-")
        (kp,) = _vector([self.kp], 1, "kp", "-")
        if depth < 0:
            raise LoadError("depth", f"{depth:g} m", "give a depth of fill over the crown >= 0 (m)")
        if not gamma > 0:
            raise LoadError("unit_weight", f"{gamma:g} kN/m^3", "give a positive unit weight (kN/m^3)")
        if angle != BOUSSINESQ and not 0 <= angle <= 60:
            raise LoadError("dispersion", f"{angle:g} degrees", "give a spread angle from 0 to 60 degrees from the vertical")
        if not 0 <= k0 < 1:
            raise LoadError("k0", f"{k0:g}", "give a coefficient at rest from 0 to below 1 (Jaky: 1 - sin(phi))")
        if kp != 0.0 and not (kp >= 1.0 and kp > k0):
            raise LoadError("kp", f"{kp:g}", "give 0 (no passive restraint) or a passive coefficient >= 1 and above k0 "
                            "(Rankine: (1 + sin(phi)) / (1 - sin(phi)))")
        if not isinstance(self.weight, bool):
            raise LoadError("weight", f"not true or false ({self.weight!r})", "write true or false")
        for key, v in (("depth", depth), ("unit_weight", gamma), ("dispersion", angle), ("k0", k0), ("kp", kp)):
            object.__setattr__(self, key, v)

    def to_dict(self) -> dict[str, Any]:
        """Plain data, the keys of a ``[loads.fill]`` table."""
        return {"depth": self.depth, "unit_weight": self.unit_weight, "weight": self.weight,
                "dispersion": self.dispersion, "k0": self.k0, "kp": self.kp}

    def spread(self, h: float) -> float:
        """How far a load spreads on each side through ``h`` m of fill (m), by the spread
        angle (0 with Boussinesq's distribution, which has no edge)."""
        if self.dispersion == BOUSSINESQ:
            return 0.0
        return max(h, 0.0) * math.tan(math.radians(self.dispersion))


def road_level(assembly: Assembly, fill: Fill) -> float:
    """Height of the road (m): ``fill.depth`` above the highest point of the free blocks'
    exposed top surface."""
    faces = _upward_faces(assembly)
    top = max(
        float(np.max(faces.z(face, *np.asarray(poly.exterior.coords).T)))
        for block, face, poly in top_surface(assembly) if not assembly.blocks[block].support
    )
    return top + fill.depth


def _triangles(poly: shapely.Polygon) -> list[np.ndarray]:
    """Triangles ``(3, 2)`` covering a plan polygon."""
    tris = shapely.constrained_delaunay_triangles(poly)
    return [np.asarray(t.exterior.coords)[:3] for t in getattr(tris, "geoms", [tris])]


def fill_forces(assembly: Assembly, fill: Fill) -> list[tuple[int, np.ndarray, np.ndarray]]:
    """``(block, point, force)`` of the fill's weight and at-rest pressure on every exposed
    top-surface piece of a free block (kN, m); empty when both are switched off."""
    if not fill.weight and fill.k0 == 0.0:
        return []
    out = []
    for block, point, W, n in fill_columns(assembly, fill):
        force = np.array([-fill.k0 * n[0] / n[2] * W, -fill.k0 * n[1] / n[2] * W, -W if fill.weight else 0.0])
        out.append((block, point, force))
    return out


def passive_bounds(assembly: Assembly, fill: Fill) -> list[tuple[int, np.ndarray, np.ndarray, float]]:
    """``(block, point, direction, capacity)`` of the passive restraint on every exposed
    top-surface piece of a free block whose face is not horizontal: the unit horizontal
    direction from the fill into the ring and the largest extra force ``(kp - k0) |n_h| / n_z
    W`` (kN; module docstring); empty when ``kp`` is 0."""
    if fill.kp == 0.0:
        return []
    out = []
    for block, point, W, n in fill_columns(assembly, fill):
        nh = math.hypot(n[0], n[1])
        if nh <= 1e-12:
            continue
        out.append((block, point, np.array([-n[0] / nh, -n[1] / nh, 0.0]), (fill.kp - fill.k0) * nh / n[2] * W))
    return out


def fill_columns(assembly: Assembly, fill: Fill) -> list[tuple[int, np.ndarray, float, np.ndarray]]:
    """``(block, point, W, normal)`` of the fill column over every exposed top-surface piece
    of a free block: its weight ``W = gamma * integral of (road - z) dA`` (kN, > 0), the
    point on the face under the column's plan centroid (m), the face's outward unit normal.

    The column integrals are exact for plane faces: edge-midpoint quadrature on a
    triangulation of each piece (exact for the quadratic ``x (road - z)``).
    """
    faces = _upward_faces(assembly)
    road = road_level(assembly, fill)
    out = []
    for block, face, poly in top_surface(assembly):
        if assembly.blocks[block].support:
            continue
        vol, moment = 0.0, np.zeros(2)
        for t in _triangles(poly):
            area = 0.5 * abs((t[1, 0] - t[0, 0]) * (t[2, 1] - t[0, 1]) - (t[2, 0] - t[0, 0]) * (t[1, 1] - t[0, 1]))
            mid = (t + np.roll(t, -1, axis=0)) / 2.0
            h = road - faces.z(face, mid[:, 0], mid[:, 1])
            vol += area * h.mean()
            moment += area * (mid * h[:, None]).mean(axis=0)
        if vol <= 0.0:
            continue
        c = moment / vol
        out.append((block, np.array([c[0], c[1], float(faces.z(face, c[0], c[1]))]), fill.unit_weight * vol,
                    np.asarray(faces.normal[face], dtype=float)))
    return out


def boussinesq_rectangle(u1: float, u2: float, v1: float, v2: float, h: float) -> tuple[float, float, float]:
    """``(fraction, Mu, Mv)``: the integral of Boussinesq's ``sigma_z / Q`` over the plan
    rectangle ``[u1, u2] x [v1, v2]`` (m, the point load at the origin) on the plane ``h`` m
    below it, and its first moments about the origin (m).

    The fraction is Newmark's corner factor ``F(a, b) = (a b h (a^2 + b^2 + 2 h^2) /
    ((a^2 + h^2)(b^2 + h^2) R) + atan(a b / (h R))) / (2 pi)``, ``R^2 = a^2 + b^2 + h^2`` (odd
    in ``a`` and ``b``), at the four corners; the moments integrate ``u sigma_z`` first in
    ``u``, then in ``v`` with ``int dv / (v^2 + k^2)^(3/2) = v / (k^2 sqrt(v^2 + k^2))``.
    """
    def F(a: float, b: float) -> float:
        R = math.sqrt(a * a + b * b + h * h)
        return (a * b * h * (a * a + b * b + 2 * h * h) / ((a * a + h * h) * (b * b + h * h) * R)
                + math.atan(a * b / (h * R))) / (2.0 * math.pi)

    def G(t: float, k2: float) -> float:
        return t / (k2 * math.sqrt(t * t + k2))

    def M(a1: float, a2: float, b1: float, b2: float) -> float:
        k1, k2 = a1 * a1 + h * h, a2 * a2 + h * h
        return h**3 / (2.0 * math.pi) * ((G(b2, k1) - G(b1, k1)) - (G(b2, k2) - G(b1, k2)))

    frac = F(u2, v2) - F(u1, v2) - F(u2, v1) + F(u1, v1)
    return frac, M(u1, u2, v1, v2), M(v1, v2, u1, u2)


def boussinesq_parts(
    assembly: Assembly, x: float, y: float, patch: tuple[float, float] | None, h: float,
) -> tuple[list[tuple[int, tuple[float, float, float], float]], float]:
    """``(block, point, fraction of the wheel load)`` on each exposed top-surface piece of a
    free block under Boussinesq's distribution of a wheel at plan ``(x, y)`` through ``h`` m
    of fill (its ``patch``, ``(l, w)`` m or None, as :data:`PATCH_POINTS` squared point loads),
    and the fraction off the deck (module docstring).

    Raises
    ------
    LoadError
        A piece that is not a rectangle in plan.
    """
    if patch is None:
        sources = [(x, y, 1.0)]
    else:
        n = PATCH_POINTS
        off = (np.arange(n) + 0.5) / n - 0.5
        sources = [(x + a * patch[0], y + b * patch[1], 1.0 / n**2) for a in off for b in off]
    faces = _upward_faces(assembly)
    parts, on = [], 0.0
    for block, face, poly in top_surface(assembly):
        if assembly.blocks[block].support:
            continue
        o, e1, e2, (L1, L2) = _plan_rectangle(poly, assembly.names[block])
        frac, mu, mv = 0.0, 0.0, 0.0
        for sx, sy, w in sources:
            du, dv = (sx - o[0]) * e1[0] + (sy - o[1]) * e1[1], (sx - o[0]) * e2[0] + (sy - o[1]) * e2[1]
            f, a, b = boussinesq_rectangle(-du, L1 - du, -dv, L2 - dv, h)
            frac += w * f
            mu += w * (a + du * f)  # first moments about the rectangle's corner o
            mv += w * (b + dv * f)
        if frac <= 1e-15:
            continue
        c = o + (mu / frac) * e1 + (mv / frac) * e2
        parts.append((block, (float(c[0]), float(c[1]), float(faces.z(face, c[0], c[1]))), frac))
        on += frac
    return parts, max(0.0, 1.0 - on)


def _plan_rectangle(poly: shapely.Polygon, name: str) -> tuple[np.ndarray, np.ndarray, np.ndarray, tuple[float, float]]:
    """Corner ``o``, unit edge directions ``e1``, ``e2`` and side lengths of a plan polygon
    that is a rectangle (any orientation)."""
    rect = shapely.minimum_rotated_rectangle(poly)
    if not (rect.area > 0 and abs(rect.area - poly.area) <= 1e-9 * rect.area):
        raise LoadError("fill.dispersion", f"{BOUSSINESQ!r} on block {name!r}, whose top face is not a rectangle in plan",
                        "use a spread angle for this structure")
    c = np.asarray(rect.exterior.coords)[:4]
    d1, d2 = c[1] - c[0], c[3] - c[0]
    L1, L2 = float(np.hypot(*d1)), float(np.hypot(*d2))
    e1, e2 = d1 / L1, d2 / L2
    return c[0], e1, e2, (L1, L2)
