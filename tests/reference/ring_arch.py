"""A two-ring semicircular arch with frictionless faces between its rings: lambda_max by a linear program.

The arch: intrados radius ``ri``, two rings of thickness ``t1`` (inner) and ``t2`` (outer), ``n``
voussoirs per ring between radial joints at equal angles ``theta_k = pi (1 - k / n)`` (aligned
across the rings), every voussoir the quadrilateral between its two joints and the chords of its
inner and outer circles; unit weight ``gamma`` per unit area of the section (depth 1). Supports:
the springing joints (fixed). The load: self-weight, and ``lam`` times each voussoir's weight
along +x at its centroid.

Contacts at the two ends of every joint's trace (planar rigid blocks, the "concave" contact of
the paper): a normal force ``fn >= 0`` (no tension) and a tangential force ``ft``:

- radial joints (between voussoirs of one ring, or a voussoir and a support): friction
  ``|ft| <= mu fn`` (``mu = None``: no limit, Heyman);
- the faces between the rings: ``ft = 0`` (no friction): the rings share load only by normal
  contact.

The static theorem: ``lambda_max = max lam`` over forces in equilibrium with the loads on every
voussoir (forces and moment about its centroid) that meet these laws; solved with HiGHS by
:func:`scipy.optimize.linprog`. Written from the statement of the problem (Heyman, *The Stone
Skeleton*, 1995; Livesley 1978 for the frictional contacts), importing nothing from tce.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import linprog

#: HiGHS's feasibility tolerances (its default 1e-7 is absolute)
TOLERANCES = {"primal_feasibility_tolerance": 1e-10, "dual_feasibility_tolerance": 1e-10}


def _polygon(p: np.ndarray) -> tuple[float, np.ndarray]:
    """Area and centroid of the polygon ``p`` ((k, 2), counter-clockwise or not)."""
    x, z = p[:, 0], p[:, 1]
    xn, zn = np.roll(x, -1), np.roll(z, -1)
    cross = x * zn - xn * z
    a = cross.sum() / 2.0
    c = np.array([((x + xn) * cross).sum(), ((z + zn) * cross).sum()]) / (6.0 * a)
    return abs(a), c


def two_ring_lambda_max(ri: float, t1: float, t2: float, n: int, mu: float | None, gamma: float = 20.0) -> float:
    """``lambda_max`` of the two-ring arch (module docstring) under the lateral load along +x."""
    radii = (ri, ri + t1, ri + t1 + t2)
    theta = np.pi * (1.0 - np.arange(n + 1) / n)
    u = np.column_stack([np.cos(theta), np.sin(theta)])  # radial unit vector of each joint
    # blocks: ring r, voussoir k -> index r * n + k; corners counter-clockwise
    blocks = [np.array([radii[r] * u[k], radii[r] * u[k + 1], radii[r + 1] * u[k + 1], radii[r + 1] * u[k]])
              for r in range(2) for k in range(n)]
    props = [_polygon(p) for p in blocks]
    weight = np.array([gamma * a for a, _ in props])
    centroid = np.array([c for _, c in props])
    # contacts: (block A or -1 for a support, block B or -1, point, unit normal from A into B, frictionless)
    contacts = []
    for r in range(2):
        for k in range(n + 1):
            a = r * n + k - 1 if k > 0 else -1
            b = r * n + k if k < n else -1
            normal = np.array([np.sin(theta[k]), -np.cos(theta[k])])  # towards smaller theta: from voussoir k - 1 into k
            for rad in (radii[r], radii[r + 1]):
                contacts.append((a, b, rad * u[k], normal, False))
    for k in range(n):
        chord = radii[1] * (u[k + 1] - u[k])
        normal = np.array([chord[1], -chord[0]]) / np.linalg.norm(chord)
        if normal @ (u[k] + u[k + 1]) < 0:
            normal = -normal  # outwards: from the inner ring into the outer one
        for p in (radii[1] * u[k], radii[1] * u[k + 1]):
            contacts.append((k, n + k, p, normal, True))
    nb, nc = len(blocks), len(contacts)
    # unknowns: (fn, ft) per contact, then lam; rows: (Fx, Fz, M) per block
    A = np.zeros((3 * nb, 2 * nc + 1))
    for j, (a, b, p, nrm, _) in enumerate(contacts):
        tan = np.array([-nrm[1], nrm[0]])
        for blk, sign in ((b, 1.0), (a, -1.0)):
            if blk < 0:
                continue
            arm = p - centroid[blk]
            for col, d in ((2 * j, nrm), (2 * j + 1, tan)):
                A[3 * blk : 3 * blk + 2, col] += sign * d
                A[3 * blk + 2, col] += sign * (arm[0] * d[1] - arm[1] * d[0])
    A[0::3, -1] = weight  # lam W along +x
    b_eq = np.zeros(3 * nb)
    b_eq[1::3] = weight  # A F + lam W ex - W ez = 0
    rows, rhs = [], []
    bounds = []
    for j, (*_, frictionless) in enumerate(contacts):
        bounds.append((0.0, None))
        if frictionless:
            bounds.append((0.0, 0.0))
            continue
        bounds.append((None, None))
        if mu is not None:
            for s in (1.0, -1.0):  # s ft - mu fn <= 0
                row = np.zeros(2 * nc + 1)
                row[2 * j], row[2 * j + 1] = -mu, s
                rows.append(row)
                rhs.append(0.0)
    bounds.append((None, None))
    c = np.zeros(2 * nc + 1)
    c[-1] = -1.0
    res = linprog(c, A_ub=np.array(rows) if rows else None, b_ub=np.array(rhs) if rhs else None, A_eq=A, b_eq=b_eq,
                  bounds=bounds, method="highs", options=TOLERANCES)
    if res.status != 0:
        raise RuntimeError(f"the reference LP did not solve: {res.message}")
    return float(res.x[-1])
