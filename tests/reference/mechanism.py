"""Kinematic limit analysis of a voussoir arch by enumeration of its 4-hinge mechanisms.

An arch of N voussoirs between plane joints 0..N (joint 0 on the left support, joint N on the
right one) loaded by self-weight ``W_i`` and a horizontal load ``lam W_i`` along +x at each
voussoir's centroid. A 4-hinge mechanism opens hinges at joints ``h1 < h2 < h3 < h4``, alternately at
the intrados and the extrados ends of their joints (intrados first or extrados first; the
relative rotations of consecutive hinges alternate in sign), and moves three rigid bodies: body 1 (voussoirs
``h1+1 .. h2``) rotates about hinge 1, body 3 (``h3+1 .. h4``) about hinge 4, and body 2 about
its instantaneous centre, where the line through hinges 1 and 2 meets the line through hinges 4
and 3 (Kennedy's theorem); the rest of the arch stays on the supports. Rates follow from the
hinges: ``w1 (P2 - P1) = w2 (P2 - C2)`` and ``w2 (P3 - C2) = w3 (P3 - P4)``.

A mechanism is admissible when every hinged joint opens (the relative velocity of its other end
has a non-negative component along the joint normal, from the left block into the right one),
and the lateral load does positive work. By the virtual-work equation its kinematic multiplier
is ``lam = -P_dead / P_lat``; by the kinematic theorem of limit analysis (Heyman) the smallest
one over all mechanisms is the collapse multiplier, and its hinges are the collapse hinges.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations

import numpy as np

INTRADOS, EXTRADOS = "intrados", "extrados"


@dataclass(frozen=True)
class Mechanism:
    """A kinematically admissible 4-hinge mechanism.

    Attributes
    ----------
    multiplier : float
        Kinematic load multiplier.
    hinges : tuple of (int, str)
        ``(joint, "intrados" | "extrados")`` of each hinge, left to right.
    points : (4, 2) ndarray
        ``(x, z)`` of the hinges (m).
    """

    multiplier: float
    hinges: tuple[tuple[int, str], ...]
    points: np.ndarray


def _perp(r: np.ndarray) -> np.ndarray:
    """Rotation by +90 degrees in the (x, z) plane: the velocity of ``r`` under a unit rate."""
    return np.stack([-r[..., 1], r[..., 0]], axis=-1)


def _meet(p1, p2, q1, q2) -> np.ndarray | None:
    """Intersection of the lines ``p1 p2`` and ``q1 q2`` (None when parallel)."""
    d1, d2 = p2 - p1, q2 - q1
    den = d1[0] * d2[1] - d1[1] * d2[0]
    if abs(den) < 1e-12 * np.linalg.norm(d1) * np.linalg.norm(d2):
        return None
    t = ((q1[0] - p1[0]) * d2[1] - (q1[1] - p1[1]) * d2[0]) / den
    return p1 + t * d1


def joint_normals(intrados, extrados, centroids) -> np.ndarray:
    """Unit normals ``(N+1, 2)`` of the joints, perpendicular to them and pointing from the block
    on the left (lower index) into the block on the right."""
    ji, je, c = (np.asarray(a, dtype=float) for a in (intrados, extrados, centroids))
    n = len(ji) - 1
    out = np.empty((n + 1, 2))
    for k in range(n + 1):
        t = je[k] - ji[k]
        nk = np.array([t[1], -t[0]]) / np.linalg.norm(t)
        mid = (ji[k] + je[k]) / 2
        ahead = c[k] - mid if k < n else mid - c[k - 1]  # voussoir k+1 (index k) lies right of joint k
        out[k] = nk if nk @ ahead > 0 else -nk
    return out


def mechanisms(intrados, extrados, centroids, weights) -> list[Mechanism]:
    """Every admissible 4-hinge mechanism, by increasing multiplier.

    Parameters
    ----------
    intrados, extrados : (N+1, 2) array_like
        ``(x, z)`` of the joint ends, left to right (m).
    centroids : (N, 2) array_like
        ``(x, z)`` of the voussoirs' centroids (m).
    weights : (N,) array_like
        Voussoir weights (kN).
    """
    ji, je = np.asarray(intrados, dtype=float), np.asarray(extrados, dtype=float)
    c, w = np.asarray(centroids, dtype=float), np.asarray(weights, dtype=float)
    n = len(ji) - 1
    normals = joint_normals(ji, je, c)
    ends = (ji, je)
    found = []
    for h in combinations(range(n + 1), 4):
        for sides in ((0, 1, 0, 1), (1, 0, 1, 0)):
            P = [ends[s][k] for s, k in zip(sides, h)]
            C2 = _meet(P[0], P[1], P[3], P[2])
            if C2 is None:
                continue
            w1 = 1.0
            w2 = w1 * (P[1] - P[0]) @ (P[1] - C2) / ((P[1] - C2) @ (P[1] - C2))
            w3 = w2 * (P[2] - C2) @ (P[2] - P[3]) / ((P[2] - P[3]) @ (P[2] - P[3]))
            bodies = [(h[0], h[1], w1, P[0]), (h[1], h[2], w2, C2), (h[2], h[3], w3, P[3])]

            def velocity(body: int | None, x: np.ndarray) -> np.ndarray:
                if body is None:  # a support, or voussoirs resting on one
                    return np.zeros(2)
                _, _, rate, centre = bodies[body]
                return rate * _perp(x - centre)

            p_lat = p_dead = 0.0
            for b, (k0, k1, rate, centre) in enumerate(bodies):
                v = rate * _perp(c[k0:k1] - centre)  # voussoirs k0+1 .. k1 (0-based k0 .. k1-1)
                p_lat += float(w[k0:k1] @ v[:, 0])
                p_dead -= float(w[k0:k1] @ v[:, 1])
            opening = []
            for m, k in enumerate(h):
                other = ends[1 - sides[m]][k]
                left, right = (m - 1 if m > 0 else None), (m if m < 3 else None)
                opening.append((velocity(right, other) - velocity(left, other)) @ normals[k])
            opening = np.array(opening)
            scale = np.abs(opening).max()
            if scale == 0.0:
                continue
            sign = 1.0 if np.all(opening >= -1e-12 * scale) else -1.0 if np.all(opening <= 1e-12 * scale) else 0.0
            if sign == 0.0 or sign * p_lat <= 0.0:
                continue
            found.append(Mechanism(-p_dead / p_lat, tuple((k, (INTRADOS, EXTRADOS)[s]) for k, s in zip(h, sides)), np.array(P)))
    return sorted(found, key=lambda m: m.multiplier)


def collapse(intrados, extrados, centroids, weights) -> Mechanism:
    """The mechanism of least multiplier (see :func:`mechanisms`)."""
    return mechanisms(intrados, extrados, centroids, weights)[0]


def semicircular_joints(inner_radius: float, thickness: float, voussoirs: int) -> tuple[np.ndarray, np.ndarray]:
    """``(x, z)`` of the intrados and extrados ends of the radial joints of a semicircular arch
    of ``voussoirs`` equal voussoirs, left (angle pi) to right (angle 0)."""
    a = np.pi * (1.0 - np.arange(voussoirs + 1) / voussoirs)
    u = np.column_stack([np.cos(a), np.sin(a)])
    return inner_radius * u, (inner_radius + thickness) * u
