"""Independent reference for moving loads on the paper's arch: a planar LP of the voussoirs
under vertical point loads on the extrados, and a brute-force scan of its collapse load over
the load position, refined by zooming to 1e-6 m. Never imports tce.

The arch: semicircular, inner radius ``r``, thickness ``t``, depth ``d`` (along y), ``n``
voussoirs between radial joints at equal angles ``a_k = pi (1 - k / n)``; every voussoir is
the quadrilateral of its joints' ends (chord intrados and extrados), weight ``gamma d A``
at the polygon's centroid. The two support blocks are fixed. Heyman material: at each end
of each joint a normal force ``n >= 0`` and an unlimited tangential force.

A vertical load at plan abscissa ``x`` acts on the voussoir whose extrados chord spans
``x`` (the left one at an edge), at the chord's height there.

    maximise  lam   s.t.  sum of joint forces on each voussoir + W_k + lam P_k = 0

(scipy's HiGHS). The scan: ``lam`` on a grid of the group's reference position, then
around each of the best local minima a grid ten times finer, repeatedly, down to 1e-6 m.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import linprog


class Arch:
    """The paper's arch (defaults: r = 1, t = 0.2, d = 0.25, 14 voussoirs, 20 kN/m^3)."""

    def __init__(self, r: float = 1.0, t: float = 0.2, d: float = 0.25, n: int = 14, gamma: float = 20.0) -> None:
        self.n = n
        a = math.pi * (1.0 - np.arange(n + 1) / n)
        self.angle = a
        u = np.column_stack([np.cos(a), np.sin(a)])
        self.ji, self.je = r * u, (r + t) * u
        self.nrm = np.column_stack([np.sin(a), -np.cos(a)])  # from voussoir k-1 into voussoir k
        self.tan = u
        self.weight, self.centroid = voussoir_weights(self.ji, self.je, gamma, d)

    def on_top(self, x: float) -> tuple[int, float] | None:
        """Voussoir and extrados height under plan abscissa ``x`` (None off the arch)."""
        ex = self.je[:, 0]
        if x < ex[0] or x > ex[-1]:
            return None
        k = min(int(np.searchsorted(ex, x, side="right")) - 1, self.n - 1)
        s = (x - ex[k]) / (ex[k + 1] - ex[k])
        return k, float(self.je[k, 1] + s * (self.je[k + 1, 1] - self.je[k, 1]))

    def lambda_max(self, loads: list[tuple[float, float]]) -> float:
        """Largest multiplier of vertical loads ``[(x, P)]`` (kN downwards); inf when
        unbounded, NaN when the LP fails."""
        n = self.n
        nv = 4 * (n + 1) + 1
        A = joint_matrix(self.ji, self.je, self.nrm, self.tan, nv)
        b = np.zeros(3 * n)
        for k in range(n):
            cx, cz = self.centroid[k]
            b[3 * k:3 * k + 3] -= np.array([0.0, -self.weight[k], -cx * self.weight[k]])
        for x, P in loads:
            hit = self.on_top(x)
            if hit is None:
                continue
            k, z = hit
            A[3 * k:3 * k + 3, -1] += np.array([0.0, -P, -x * P])
        bounds = [(0.0, None) if c % 2 == 0 else (None, None) for c in range(nv - 1)] + [(None, None)]
        c = np.zeros(nv)
        c[-1] = -1.0
        res = linprog(c, A_eq=A, b_eq=b, bounds=bounds, method="highs")
        if res.status == 3:
            return math.inf
        return float(res.x[-1]) if res.status == 0 else math.nan


def voussoir_weights(ji: np.ndarray, je: np.ndarray, gamma: float, d: float) -> tuple[np.ndarray, np.ndarray]:
    """Weight ``gamma d A`` (kN) and centroid ``(x, z)`` (m) of every voussoir, the
    quadrilateral of its joints' ends (shoelace formulas)."""
    n = len(ji) - 1
    weight, centroid = np.zeros(n), np.zeros((n, 2))
    for k in range(n):
        poly = np.array([ji[k], je[k], je[k + 1], ji[k + 1]])
        x, z = poly[:, 0], poly[:, 1]
        xs, zs = np.roll(x, -1), np.roll(z, -1)
        cross = x * zs - xs * z
        area = cross.sum() / 2.0
        centroid[k] = [((x + xs) * cross).sum() / (6 * area), ((z + zs) * cross).sum() / (6 * area)]
        weight[k] = gamma * d * abs(area)
    return weight, centroid


def joint_matrix(ji: np.ndarray, je: np.ndarray, nrm: np.ndarray, tan: np.ndarray, nv: int) -> np.ndarray:
    """Equilibrium rows ``(3 n, nv)`` (force x, force z, moment about the origin per voussoir)
    of the joint forces of ``n`` voussoirs between ``n + 1`` joints: at each end (intrados
    ``ji``, extrados ``je``) of joint ``j`` a normal (``nrm[j]``, from voussoir ``j - 1`` into
    ``j``) and a tangential (``tan[j]``) force, columns ``4 j + 2 end + (0 normal, 1 tangent)``;
    the other columns are zero."""
    n = len(ji) - 1
    A = np.zeros((3 * n, nv))
    for j in range(n + 1):
        for v, p in enumerate((ji[j], je[j])):
            for c, e in enumerate((nrm[j], tan[j])):
                col = 4 * j + 2 * v + c
                m = p[0] * e[1] - p[1] * e[0]
                for k, sign in ((j, 1.0), (j - 1, -1.0)):
                    if 0 <= k < n:
                        A[3 * k:3 * k + 3, col] += sign * np.array([e[0], e[1], m])
    return A


def scan(f, lo: float, hi: float, h: float = 0.01, finest: float = 1e-6, keep: int = 4) -> tuple[float, float]:
    """Least value of ``f`` on ``[lo, hi]``: a grid of step ``h``, then around the ``keep``
    best local minima grids of 21 points ten times finer, down to ``finest``."""
    xs = np.arange(lo, hi + h / 2, h)
    ys = np.array([f(x) for x in xs])
    ys = np.where(np.isnan(ys), np.inf, ys)
    mins = [k for k in range(len(xs)) if (k == 0 or ys[k] <= ys[k - 1]) and (k == len(xs) - 1 or ys[k] <= ys[k + 1])]
    best = (math.inf, math.nan)
    for k in sorted(mins, key=lambda k: ys[k])[:keep]:
        x0, step = xs[k], h
        y0 = ys[k]
        while step > finest:
            grid = np.clip(np.linspace(x0 - step, x0 + step, 21), lo, hi)
            vals = [f(x) for x in grid]
            i = int(np.nanargmin(vals))
            if vals[i] <= y0:
                x0, y0 = grid[i], vals[i]
            step /= 10.0
        best = min(best, (y0, x0))
    return best[1], best[0]
