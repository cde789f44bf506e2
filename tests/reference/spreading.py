"""The semicircular voussoir arch on symmetric spreading supports: hinge kinematics and a
thrust-line check on the deformed geometry (Ochsendorf 2002, 2006).

The arch: centreline radius ``R``, radial thickness ``t``, ``n`` voussoirs (``n`` even, so
that the crown is a joint) between radial joints at equal angles, each voussoir the
quadrilateral of its joint ends (plane intrados and extrados faces, as built by the tce arch
generator and described in ``docs/conventions.md``), weights proportional to the areas
(unit weight times depth is a common factor and drops out of every ratio reported here).
Joints are numbered 0 (left springing) .. n (right springing); by symmetry only the right
half (joints ``n/2 .. n``) is computed.

Undeformed state of minimum thrust (the state spreading supports select): the thrust line
passes through the crown joint's extrados end C with a horizontal thrust H (by symmetry) and
touches the intrados end I_j of one joint j of the half: ``H_j = sum_k W_k (I_jx - x_k) /
(C_z - I_jz)`` over the voussoirs between the crown and joint j; the admissible minimum is
``H = max_j H_j``, and its j is the haunch hinge. The mechanism: three hinges, C and the two
I_j; the voussoirs between the crown and I_j rotate about I_j as one body, those below it move
with the support.

Finite motion: each support moves outward by ``u`` (m); the right crown body rotates by the
angle ``theta(u)`` about I_j (carried by the support) that keeps C on the axis of symmetry
(exact, no linearisation). On that deformed geometry the (statically determinate) thrust
line through C and I_j is computed and checked at every joint of the half: its line of action
must cross the joint between its two ends, in compression. The largest ``u`` at which the
check holds everywhere is the capacity of this fixed hinge set (bisection on ``u``).

Hinge migration (:func:`path_capacity`): for a fixed hinge set every joint but the three
hinges is closed, so the deformed geometry at ``u`` depends on the hinge set only, not on
the history. When the thrust line of hinge j leaves the arch at the neighbouring joint
j - 1 or j + 1 and the hinge set with the haunch hinge there stands at that ``u``, the hinge
moves there (joint j closes again: a snap of the rigid blocks) and the path goes on with
the new set; otherwise the arch collapses.

This file imports nothing from tce.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


def joints(R: float, t: float, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Intrados and extrados ends ``(n + 1, 2)`` of the radial joints, left to right."""
    a = np.linspace(math.pi, 0.0, n + 1)
    ri, re = R - t / 2, R + t / 2
    u = np.column_stack([np.cos(a), np.sin(a)])
    u[0], u[-1], u[n // 2] = (-1.0, 0.0), (1.0, 0.0), (0.0, 1.0)
    return ri * u, re * u


def quad(p: np.ndarray) -> tuple[float, np.ndarray]:
    """Area and centroid of a simple polygon (shoelace)."""
    x, z = p[:, 0], p[:, 1]
    xn, zn = np.roll(x, -1), np.roll(z, -1)
    cr = x * zn - xn * z
    area = cr.sum() / 2
    return abs(area), np.array([((x + xn) * cr).sum(), ((z + zn) * cr).sum()]) / (6 * area)


def _rot(p: np.ndarray, centre: np.ndarray, theta: float) -> np.ndarray:
    c, s = math.cos(theta), math.sin(theta)
    d = p - centre
    return centre + np.column_stack([c * d[:, 0] - s * d[:, 1], s * d[:, 0] + c * d[:, 1]])


@dataclass(frozen=True)
class HalfArch:
    """The right half of the arch: joints ``n/2 .. n`` and the voussoirs between them."""

    ji: np.ndarray  # (m + 1, 2) intrados ends, crown first
    je: np.ndarray
    w: np.ndarray  # (m,) weights (areas)
    g: np.ndarray  # (m, 2) centroids

    @classmethod
    def of(cls, R: float, t: float, n: int) -> HalfArch:
        ji, je = joints(R, t, n)
        ji, je = ji[n // 2 :], je[n // 2 :]
        props = [quad(np.array([ji[k], ji[k + 1], je[k + 1], je[k]])) for k in range(len(ji) - 1)]
        return cls(ji, je, np.array([a for a, _ in props]), np.array([c for _, c in props]))

    def thrusts(self) -> np.ndarray:
        """``H_j`` (per unit weight-area) of the thrust line through C and I_j, j = 1 .. m."""
        C = self.je[0]
        out = np.zeros(len(self.w))
        for j in range(1, len(self.w) + 1):
            I = self.ji[j]
            out[j - 1] = (self.w[:j] * (I[0] - self.g[:j, 0])).sum() / (C[1] - I[1])
        return out

    def hinge(self) -> int:
        """The haunch hinge j (joints counted from the crown) of the minimum thrust."""
        return int(np.argmax(self.thrusts())) + 1

    def deformed(self, j: int, u: float) -> HalfArch:
        """The half at outward support motion ``u``: body 0..j rotated about I_j, all moved by u."""
        I0 = self.ji[j]
        C0 = self.je[0]
        dx, dz = C0[0] - I0[0], C0[1] - I0[1]
        r0, phi0 = math.hypot(dx, dz), math.atan2(dz, dx)
        arg = (dx - u) / r0
        if not -1.0 <= arg <= 1.0:
            raise ValueError("the crown cannot reach the axis: the half has turned past its hinge")
        theta = math.acos(arg) - phi0
        shift = np.array([u, 0.0])
        ji, je, g = self.ji.copy(), self.je.copy(), self.g.copy()
        ji[: j + 1] = _rot(ji[: j + 1], I0, theta)
        je[: j + 1] = _rot(je[: j + 1], I0, theta)
        g[:j] = _rot(g[:j], I0, theta)
        ji[j] = self.ji[j]  # the hinge itself stays on the lower body (exactly)
        return HalfArch(ji + shift, je + shift, self.w, g + shift)

    def check(self, j: int, tol: float = 1e-12) -> tuple[bool, float, np.ndarray]:
        """Thrust line through C (horizontal) and I_j on this geometry: ``(ok, H, margins)``,
        ``margins[k]`` the distance of the line of action's crossing of joint k from the nearer
        end, as a fraction of the joint (> 0 inside, 0 at a hinge, < 0 outside); ok when
        every margin >= -tol and every joint is in compression."""
        C, I = self.je[0], self.ji[j]
        H = (self.w[:j] * (I[0] - self.g[:j, 0])).sum() / (C[1] - I[1])
        margins = np.zeros(len(self.w))
        ok = True
        for k in range(1, len(self.w) + 1):
            W = self.w[:k].sum()
            # moment of the loads above joint k about a point P (counter-clockwise)
            def m(P: np.ndarray) -> float:
                return -H * (C[1] - P[1]) - (self.w[:k] * (self.g[:k, 0] - P[0])).sum()

            mi, me = m(self.ji[k]), m(self.je[k])
            # the line of action meets the joint at ji + lam (je - ji), where the moment vanishes
            lam = mi / (mi - me) if mi != me else -math.inf
            margins[k - 1] = min(lam, 1.0 - lam)
            tang = self.je[k] - self.ji[k]
            normal = np.array([tang[1], -tang[0]])  # from the upper (crown side) body into the lower
            if np.array([H, -W]) @ normal <= 0:
                ok = False
        ok = ok and bool(margins.min() >= -tol)
        return ok, float(H), margins


def capacity(R: float, t: float, n: int, tol: float = 1e-9) -> tuple[float, int, float]:
    """Largest outward motion ``u`` (m, each support) with an admissible thrust line for the
    fixed minimum-thrust hinge set: ``(u_max, j, H0)`` with j counted from the crown joint."""
    half = HalfArch.of(R, t, n)
    j = half.hinge()
    H0 = half.check(j)[1]

    def stands(u: float) -> bool:
        try:
            return half.deformed(j, u).check(j)[0]
        except ValueError:
            return False

    lo, hi = 0.0, R / 64
    while stands(hi):
        lo, hi = hi, 2 * hi
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if stands(mid) else (lo, mid)
    return lo, j, H0


def _last_standing(half: HalfArch, j: int, u0: float, tol: float) -> float:
    """Largest u >= u0 such that hinge set j stands on [u0, u] (it stands at u0)."""

    def stands(u: float) -> bool:
        try:
            return half.deformed(j, u).check(j)[0]
        except ValueError:
            return False

    lo, step = u0, 1.0 / 256
    while stands(lo + step):
        lo += step
    hi = lo + step
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if stands(mid) else (lo, mid)
    return lo


def path_capacity(R: float, t: float, n: int, tol: float = 1e-10) -> tuple[float, list[int], list[float]]:
    """Capacity with hinge migration to a neighbouring joint: ``(u_max, hinges, snaps)``,
    the haunch hinges in the order they formed (joints from the crown) and the motions u at
    which the hinge moved."""
    half = HalfArch.of(R, t, n)
    j = half.hinge()
    hinges, snaps, u = [j], [], 0.0
    while True:
        u = _last_standing(half, j, u, tol)
        beyond = u + 4 * tol
        margins = half.deformed(j, beyond).check(j)[2]
        k = int(np.argmin(margins)) + 1
        if abs(k - j) != 1 or not half.deformed(k, beyond).check(k, tol=1e-9)[0]:
            return u, hinges, snaps
        j = k
        hinges.append(j)
        snaps.append(u)
