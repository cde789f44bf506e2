"""Independent reference for a filled segmental ring with the fill's passive restraint: a
planar LP of the voussoirs (scipy's HiGHS), written from docs/conventions.md and the
docstrings of tce.core.fill; never imports tce.

The ring: :func:`reference.funicular.joints` (radial joints at equal angles, the springing
joints the supports'); every voussoir is the quadrilateral of its joints' ends, its weight
``gamma d A`` at the polygon's centroid; ``d`` the width along y. Heyman material: at each
end of each joint a normal force ``n >= 0`` and an unlimited tangential force.

The fill (per voussoir ``k``, over its extrados chord ``E_k E_k+1``): the road lies
``depth`` above the highest extrados point; the column over the chord weighs
``W_k = gamma_f d integral (road - z(x)) dx`` (closed form: the chord is straight, so the
integrand is linear) and acts at the column's centroid abscissa on the chord. With the chord's
outward unit normal ``(n_x, n_z)`` (n_z > 0), the at-rest force is ``-k0 n_x / n_z W_k``
(horizontal, fixed) and the passive force is an unknown ``p_k`` along ``-sign(n_x)``,
``0 <= p_k <= (kp - k0) |n_x| / n_z W_k``, at the same point.

    maximise lam  s.t.  sum of joint forces + weights + fill forces + p + lam P = 0 per voussoir

A vertical live point load ``P`` at abscissa ``x`` acts on the voussoir whose extrados chord
spans ``x``, on the chord.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import linprog

from reference.funicular import joints
from reference.moving_load import joint_matrix, voussoir_weights


class FilledRing:
    """A segmental ring (span ``s``, intrados rise ``f``, thickness ``t``, ``n`` voussoirs,
    width ``d``, unit weight ``gamma``) under ``depth`` of fill of unit weight ``gamma_f``."""

    def __init__(self, s: float, f: float, t: float, n: int, d: float, gamma: float,
                 depth: float, gamma_f: float, k0: float = 0.0, kp: float = 0.0) -> None:
        self.n = n
        self.ji, self.je = joints(s, f, t, n)
        R = (s**2 / 4.0 + f**2) / (2.0 * f)
        centre = np.array([0.0, f - R])
        u = (self.ji - centre) / R
        self.nrm = np.column_stack([u[:, 1], -u[:, 0]])  # normal of joint j, from voussoir j-1 into j
        self.tan = u
        self.weight, self.centroid = voussoir_weights(self.ji, self.je, gamma, d)
        road = self.je[:, 1].max() + depth
        # fill columns over the extrados chords: W, point, fixed horizontal, passive bound and sign
        self.fill = []
        for k in range(n):
            (x0, z0), (x1, z1) = self.je[k], self.je[k + 1]
            h0, h1 = road - z0, road - z1
            L = x1 - x0
            W = gamma_f * d * L * (h0 + h1) / 2.0
            xc = x0 + L * (h0 + 2.0 * h1) / (3.0 * (h0 + h1))  # centroid of a trapezoid's load
            zc = z0 + (z1 - z0) * (xc - x0) / L
            nx, nz = -(z1 - z0), (x1 - x0)  # outward (upward) normal of the chord, left to right
            norm = math.hypot(nx, nz)
            nx, nz = nx / norm, nz / norm
            self.fill.append((W, xc, zc, -k0 * nx / nz * W, (kp - k0) * abs(nx) / nz * W, -math.copysign(1.0, nx)))

    def on_top(self, x: float) -> tuple[int, float]:
        """Voussoir and extrados height under plan abscissa ``x``."""
        ex = self.je[:, 0]
        k = min(max(int(np.searchsorted(ex, x, side="right")) - 1, 0), self.n - 1)
        s = (x - ex[k]) / (ex[k + 1] - ex[k])
        return k, float(self.je[k, 1] + s * (self.je[k + 1, 1] - self.je[k, 1]))

    def lambda_max(self, loads: list[tuple[float, float]], passive: bool = True) -> tuple[float, np.ndarray]:
        """Largest multiplier of vertical loads ``[(x, P)]`` (kN downwards) and the passive
        forces at the limit (kN); inf when unbounded, NaN when the LP fails."""
        n = self.n
        nj = 4 * (n + 1)
        nv = nj + n + 1
        A = joint_matrix(self.ji, self.je, self.nrm, self.tan, nv)
        b = np.zeros(3 * n)
        for k in range(n):
            cx, cz = self.centroid[k]
            W, xc, zc, H0, _, sgn = self.fill[k]
            # fixed: self-weight, fill weight, at-rest thrust (moments about the origin)
            b[3 * k:3 * k + 3] -= np.array([0.0, -self.weight[k], -cx * self.weight[k]])
            b[3 * k:3 * k + 3] -= np.array([H0, -W, xc * (-W) - zc * H0])
            # passive force sgn * p (horizontal) at (xc, zc)
            A[3 * k:3 * k + 3, nj + k] += np.array([sgn, 0.0, -zc * sgn])
        for x, P in loads:
            k, z = self.on_top(x)
            A[3 * k:3 * k + 3, -1] += np.array([0.0, -P, -x * P])
        caps = [f[4] if passive else 0.0 for f in self.fill]
        bounds = ([(0.0, None) if c % 2 == 0 else (None, None) for c in range(nj)]
                  + [(0.0, cap) for cap in caps] + [(None, None)])
        c = np.zeros(nv)
        c[-1] = -1.0
        res = linprog(c, A_eq=A, b_eq=b, bounds=bounds, method="highs")
        if res.status == 3:
            return math.inf, np.full(n, np.nan)
        if res.status != 0:
            return math.nan, np.full(n, np.nan)
        return float(res.x[-1]), res.x[nj:nj + n]
