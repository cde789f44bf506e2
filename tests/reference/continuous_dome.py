"""The hemispherical dome under self-weight, axisymmetric: minimum thickness by a linear program.

A spherical shell of mid-surface radius ``R = 1`` and thickness ``t`` (intrados ``ri = 1 - t/2``,
extrados ``re = 1 + t/2``), unit weight, closed at the crown, on a rigid base at its equator, is
cut by ``m`` cones through the centre (the bed joints) at colatitudes ``theta_j = j (pi/2) / m``,
``j = 1..m``, into ``m`` courses; there are no meridian cuts (the continuous shell in azimuth).
Heyman's material: no tension, unlimited compressive strength, no sliding.

Per radian of azimuth, in the meridian plane (``r`` from the axis, ``z`` up, the moment of a
force ``(F_r, F_z)`` at ``(r, z)`` about the centre is ``r F_z - z F_r``):

- course ``k`` carries a hoop force ``H_k >= 0`` (compression). By axisymmetry the shear on the
  two meridian faces of a wedge ``d psi`` cancels and the two normal forces add to an outward
  radial force ``H_k d psi``, horizontal, at a height ``z_k`` where the horizontal line meets the
  course's section: ``ri cos theta_{k} <= z_k <= re cos theta_{k-1}``. With ``G_k = H_k z_k``
  this reads ``H_k ri cos theta_k <= G_k <= H_k re cos theta_{k-1}``;
- the cap above joint ``j`` (courses ``1..j``) weighs ``W_j = (re^3 - ri^3)/3 (1 - cos theta_j)``
  with first moment about the axis ``S_j = (re^4 - ri^4)/4 (theta_j/2 - sin(2 theta_j)/4)``;
  the joint pushes on it with ``(-sum H, W_j)``, whose component along the meridian is
  ``Q_j = W_j sin theta_j + cos theta_j sum_{k<=j} H_k >= 0``, at distance ``rho_j`` from the
  centre along the joint. Moments about the centre: ``rho_j Q_j = S_j + sum_{k<=j} G_k``;
  the locus of pressure points lies in the joint: ``ri Q_j <= S_j + sum G_k <= re Q_j``.

``shell="facets"`` replaces each course's section by the quadrilateral of its corners (straight
intrados and extrados chords), with ``W`` and ``S`` its first and second moments ``int r dA``,
``int r^2 dA``: the section of a voussoir of a block model whose intrados and extrados are planar
(every such voussoir over a sector of half-angle ``a`` is the meridian section stretched across the
sector, ``{(x, y, z): (x / cos a, z) in Q, |y| <= x tan a}``, so its equations per radian are these
whatever ``a``). With an oculus of half-angle ``theta_0`` the courses run from ``theta_0`` (a free edge) to the
base and ``W``, ``S`` are integrated from there. All constraints are linear in ``(H, G)``; the smallest ``t`` for which they are feasible is
found by bisection. A crown ring of zero radius carries nothing the hoop forces of the top
course do not. Written from the statement of the problem (Heyman, *Equilibrium of Shell
Structures*, 1977; *The Stone Skeleton*, 1995; the static theorem for axisymmetric domes),
independently of tce: it imports nothing from it.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import linprog


def _facet_moments(ri: float, re: float, th: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``int r dA`` and ``int r^2 dA`` over each course's section with straight chords: the
    quadrilateral of its corners ``(rho sin theta, rho cos theta)``, ``rho`` in ``(ri, re)``
    (the polygon formulas of the first and second moments, counter-clockwise)."""
    def corner(rho, t):
        return rho * np.sin(t), rho * np.cos(t)
    quads = [corner(ri, th[:-1]), corner(ri, th[1:]), corner(re, th[1:]), corner(re, th[:-1])]
    m1 = np.zeros(len(th) - 1)
    m2 = np.zeros(len(th) - 1)
    for (x0, y0), (x1, y1) in zip(quads, quads[1:] + quads[:1]):
        cross = x0 * y1 - x1 * y0
        m1 += (x0 + x1) * cross / 6.0
        m2 += (x0**2 + x0 * x1 + x1**2) * cross / 12.0
    return np.abs(m1), np.abs(m2)


def _rows(t: float, m: int, shell: str = "sphere", oculus: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    ri, re = 1.0 - t / 2.0, 1.0 + t / 2.0
    th = np.linspace(np.radians(oculus), np.pi / 2, m + 1)
    if shell == "sphere":  # the spherical shell itself, from the oculus (or the crown) down
        w = (re**3 - ri**3) / 3.0 * (np.cos(th[0]) - np.cos(th[1:]))
        s = (re**4 - ri**4) / 4.0 * ((th[1:] - th[0]) / 2.0 - (np.sin(2.0 * th[1:]) - np.sin(2.0 * th[0])) / 4.0)
    elif shell == "facets":  # courses with straight intrados and extrados chords
        w1, s1 = _facet_moments(ri, re, th)
        w, s = np.cumsum(w1), np.cumsum(s1)
    else:
        raise ValueError(f"unknown shell {shell!r}")
    lower = np.tril(np.ones((m, m)))  # row j sums the courses k <= j
    c, sn = np.cos(th[1:]), np.sin(th[1:])
    eye = np.eye(m)
    # variables x = [H_1..H_m, G_1..G_m]
    rows = [
        np.hstack([ri * c[:, None] * lower, -lower]),  # ri Q_j - S_j - sum G <= 0 (H part of Q)
        np.hstack([-re * c[:, None] * lower, lower]),  # S_j + sum G - re Q_j <= 0
        np.hstack([ri * np.diag(np.cos(th[1:])), -eye]),  # H_k ri cos theta_k <= G_k
        np.hstack([-re * np.diag(np.cos(th[:-1])), eye]),  # G_k <= H_k re cos theta_{k-1}
    ]
    rhs = [s - ri * w * sn, re * w * sn - s, np.zeros(m), np.zeros(m)]
    return np.vstack(rows), np.concatenate(rhs)


#: HiGHS's feasibility tolerances: its default (1e-7, absolute) on rows of the size of the
#: weight per radian (about t) accepts thicknesses about 2e-6 too thin
TOLERANCES = {"primal_feasibility_tolerance": 1e-10, "dual_feasibility_tolerance": 1e-10}


def stands(t: float, m: int = 400, shell: str = "sphere", oculus: float = 0.0) -> bool:
    """Whether an admissible state exists at thickness ratio ``t = t/R`` with ``m`` courses
    (``shell``: ``"sphere"``, the spherical shell's courses, or ``"facets"``, courses with
    straight intrados and extrados chords, as the voussoirs of a block model; ``oculus``: the
    half-angle of an open crown, degrees, its edge free)."""
    a, b = _rows(t, m, shell, oculus)
    r = linprog(np.zeros(a.shape[1]), A_ub=a, b_ub=b,
                bounds=[(0, None)] * m + [(None, None)] * m, method="highs", options=TOLERANCES)
    return r.status == 0


def minimum_thickness(m: int = 400, lo: float = 0.005, hi: float = 0.3, tol: float = 1e-7,
                      shell: str = "sphere", oculus: float = 0.0) -> float | None:
    """Smallest ``t/R`` of the hemisphere of ``m`` courses that stands (None if ``hi`` does not)."""
    if not stands(hi, m, shell, oculus):
        return None
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        if stands(mid, m, shell, oculus):
            hi = mid
        else:
            lo = mid
    return hi
