"""Independent reference: can a segmental ring of rigid voussoirs carry two vertical point
loads at ANY magnitude? Yes exactly when the loads' own funicular polygon (self-weight
negligible beside them) crosses every joint inside the masonry. Never imports tce.

Why (Heyman, *The Masonry Arch*, 1982, ch. 2; *The Stone Skeleton*, 1995): with rigid
voussoirs that take no tension and do not slide (Heyman's material, no crushing), a load
system is carried when some line of thrust in equilibrium with it lies within the masonry at
every joint. Under loads ``lam P`` plus the self-weight ``W``, as ``lam`` grows the thrust
line tends to the funicular polygon of ``P`` alone; when that polygon fits with some margin,
the weight's small correction fits too, and the ring carries every ``lam``: tce's direct
limit is then ``unbounded`` (``lambda_max = inf``).

The ring (as :func:`tce.structures.arch.segmental_arch` documents it, written here from the
docstring): intrados the circular arc through ``(-+s/2, 0)`` and ``(0, f)``, radius
``R = (s^2/4 + f^2) / (2 f)``, centre ``(0, f - R)``; radial thickness ``t``; ``n``
voussoirs between radial joints at equal angles; the springing joints are the supports'.

The polygon for loads ``P1`` at ``x1`` and ``P2 = ratio P1`` at ``x2 > x1``, horizontal thrust
``H > 0``: slopes ``s0`` (left of ``x1``), ``s0 - p`` (between), ``s0 - p (1 + ratio)``
(right of ``x2``) with ``p = P1 / H``, through ``(x1, h)``. A load acts on the voussoir whose
extrados spans its ``x`` (as tce applies an ``on_top`` / wheel load); the force across joint
``j`` is the resultant of the loads on the voussoirs to its left, so its line is the piece of
the polygon for those loads, extended. Joint ``j`` runs from ``I_j`` (intrados) to ``E_j``
(extrados); the line crosses it inside when ``z(I_j) <= L(x_I)`` and ``z(E_j) >= L(x_E)``
(the line passes above the intrados end and below the extrados end, the orientation of a
thrust line rising from the springings towards the loads). Both are linear in ``(h, s0, p)``,
so the largest ``p`` (capped at 1) is a linear program (scipy's HiGHS): ``p > 0`` means the
ring carries the loads at any magnitude.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import linprog


def joints(span: float, rise: float, thickness: float, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Intrados and extrados ends ``(n + 1, 2)`` of the radial joints, left to right (m)."""
    R = (span**2 / 4.0 + rise**2) / (2.0 * rise)
    zc = rise - R
    half = math.asin(span / 2.0 / R) if rise < R else math.pi / 2.0
    a = math.pi / 2.0 + half - np.arange(n + 1) * (2.0 * half / n)  # from the left springing
    u = np.column_stack([np.cos(a), np.sin(a)])
    c = np.array([0.0, zc])
    return c + R * u, c + (R + thickness) * u


def voussoir_of(x: float, E: np.ndarray) -> int:
    """Index (0-based) of the voussoir whose extrados chord spans ``x`` (the left one at a joint)."""
    k = int(np.searchsorted(E[:, 0], x, side="left")) - 1
    return min(max(k, 0), len(E) - 2)


def carried_at_any_magnitude(span: float, rise: float, thickness: float, n: int,
                             x1: float, x2: float, ratio: float = 1.0) -> float:
    """Largest ``p = P1 / H`` (<= 1) of a funicular polygon of the two loads that crosses every
    joint inside the ring; 0 when none does (then the loads' capacity is finite). Loads at
    ``x1 < x2`` (m), ``P2 = ratio P1``."""
    I, E = joints(span, rise, thickness, n)
    k1, k2 = voussoir_of(x1, E), voussoir_of(x2, E)
    A, b = [], []
    for j in range(n + 1):
        # loads on voussoirs left of joint j (voussoir k lies between joints k and k + 1)
        left1, left2 = k1 < j, k2 < j
        for point, sign in ((I[j], 1.0), (E[j], -1.0)):
            x, z = point
            # L(x) = h + s0 (x - x1) - p [left1 (x - x1) + ratio left2 (x - x2)]
            row = np.array([1.0, x - x1, -(left1 * (x - x1) + ratio * left2 * (x - x2))])
            # intrados: z <= L  ->  -L <= -z ;  extrados: z >= L  ->  L <= z
            A.append(-row if sign > 0 else row)
            b.append(-z if sign > 0 else z)
    res = linprog(c=[0.0, 0.0, -1.0], A_ub=np.array(A), b_ub=np.array(b),
                  bounds=[(None, None), (None, None), (0.0, 1.0)], method="highs")
    if res.status == 2:  # not even a polygon with p = 0 (a straight line) fits: none does
        return 0.0
    if res.status != 0:
        raise RuntimeError(f"funicular LP: {res.message}")
    return float(res.x[2])
