"""The semicircular arch under a uniform horizontal acceleration: its capacity by a linear program.

A semicircular ring of centreline radius ``R = 1``, thickness ``t`` (intrados ``ri = 1 - t/2``,
extrados ``re = 1 + t/2``), unit weight and depth 1, on two springings; joints radial (Heyman's
material: no tension, no sliding, unlimited compressive strength). Every part of the ring
weighs ``dW`` and carries ``lam dW`` along +x at its centroid (a horizontal acceleration
``lam g``, or the arch on a table tilted by ``atan(lam)``). The static theorem asks for the
largest ``lam`` for which a reaction ``(Rx, Rz)`` with moment ``M0`` about the centre at the left
springing keeps the pressure point of every cut inside the ring.

The cut at angle ``b`` from the left springing (``u = (-cos b, sin b)`` along the cut, normal
``n = (sin b, cos b)`` towards the crown) carries from the part ``[0, b]`` (weight ``W``, first
moments ``Sx = int x dW``, ``Sz = int z dW``) onto the rest the force
``P = (Rx + lam W, Rz - W)``; moments about the centre put its pressure point at ``rho`` with
``rho N = Sx + lam Sz - M0``, ``N = P . n >= 0``. So ``ri N <= Sx + lam Sz - M0 <= re N``: linear in
``(Rx, Rz, M0, lam)``. The cut ``b = 0`` is the left springing, ``b = pi`` the right one.

``shell="ring"``: ``m`` cuts, each part an annular sector (its centroid at radius
``(2/3)(re^3 - ri^3)/(re^2 - ri^2) sin(b/2)/(b/2)`` on its bisector): the continuous arch as
``m`` grows. An arch of embrace ``pi - 2 a`` (``start=a``: its springing joints on the radii at
``a`` above the springing line, as a semicircle whose lowest parts are built into the supports)
has its cuts from ``b = a`` to ``b = pi - a`` and the parts ``[a, b]``; the equations are the
same. With a finite compressive strength ``f = fc / (gamma R)`` (dimensionless) every
joint is a rigid-plastic stress block: the compressed zone ``N / f`` is centred on the pressure
point, so ``ri + N / (2 f) <= rho <= re - N / (2 f)``, i.e.
``N^2 / (2 f) <= Sx + lam Sz - M0 - ri N`` and ``N^2 / (2 f) <= re N - (Sx + lam Sz - M0)``: convex,
solved as a second-order cone program (cvxpy). ``shell="facets"``: the ``m + 1`` joints of ``m`` voussoirs with straight intrados
and extrados chords (quadrilaterals; polygon moments), as a block model's voussoirs. Written
from the statement of the problem (Heyman, *The Stone Skeleton*, 1995; Oppenheim 1992;
Ochsendorf 2002), independently of tce: it imports nothing from it.
"""

from __future__ import annotations

import numpy as np
import cvxpy as cp
from scipy.optimize import linprog

#: HiGHS's feasibility tolerances (its default 1e-7 is absolute, on rows the size of t)
TOLERANCES = {"primal_feasibility_tolerance": 1e-10, "dual_feasibility_tolerance": 1e-10}


def _moments(t: float, m: int, shell: str, start: float = 0.0) -> tuple[np.ndarray, ...]:
    """Angles ``b`` of the cuts and the weight and first moments of the parts ``[start, b]``."""
    ri, re = 1.0 - t / 2.0, 1.0 + t / 2.0
    b = np.linspace(start, np.pi - start, m + 1)
    if shell == "ring":
        h = (b - start) / 2  # half-angle of the sector [start, b], its bisector at start + h
        rc = np.ones_like(b) * (2.0 / 3.0) * (re**3 - ri**3) / (re**2 - ri**2)
        rc[1:] *= np.sin(h[1:]) / h[1:]
        w = t * (b - start)
        return b, w, -w * rc * np.cos(start + h), w * rc * np.sin(start + h)
    if shell != "facets":
        raise ValueError(f"unknown shell {shell!r}")
    area, sx, sz = np.zeros(m + 1), np.zeros(m + 1), np.zeros(m + 1)
    for k in range(m):  # voussoir k between b[k] and b[k+1], corners counter-clockwise
        a0, a1 = b[k], b[k + 1]
        pts = [(-ri * np.cos(a0), ri * np.sin(a0)), (-ri * np.cos(a1), ri * np.sin(a1)),
               (-re * np.cos(a1), re * np.sin(a1)), (-re * np.cos(a0), re * np.sin(a0))]
        a = mx = mz = 0.0
        for (x0, z0), (x1, z1) in zip(pts, pts[1:] + pts[:1]):
            c = x0 * z1 - x1 * z0
            a += c / 2.0
            mx += (x0 + x1) * c / 6.0
            mz += (z0 + z1) * c / 6.0
        area[k + 1], sx[k + 1], sz[k + 1] = a, mx, mz
    return b, np.cumsum(area), np.cumsum(sx), np.cumsum(sz)


def capacity(t: float, m: int = 2000, shell: str = "ring", strength: float | None = None,
             start: float = 0.0) -> float | None:
    """Largest ``lam`` (horizontal acceleration / g) the arch of thickness ratio ``t`` carries
    (None if it does not stand under self-weight); ``strength``: ``fc / (gamma R)``, None for
    unlimited; ``start``: angle (rad) of the springing joints above the springing line, for an
    arch of embrace ``pi - 2 start`` (its springing joints on the radii at ``start`` and
    ``pi - start`` from the left springing; 0: the semicircle)."""
    ri, re = 1.0 - t / 2.0, 1.0 + t / 2.0
    b, w, sx, sz = _moments(t, m, shell, start)
    s, c = np.sin(b), np.cos(b)
    zero = np.zeros_like(b)
    # variables x = (Rx, Rz, M0, lam): N = n_rows x - n_rhs; rho N = Sx + lam Sz - M0 = mom x + sx
    n_rows = np.column_stack([s, c, zero, s * w])
    n_rhs = c * w
    mom = np.column_stack([zero, zero, -np.ones_like(b), sz])
    if strength is not None:
        x = cp.Variable(4)
        normal = n_rows @ x - n_rhs
        moment = mom @ x + sx
        block = cp.square(normal) / (2.0 * strength)  # N^2 / (2 f): half the compressed zone times N
        problem = cp.Problem(cp.Maximize(x[3]), [normal >= 0, x[3] >= 0, block <= moment - ri * normal,
                                                 block <= re * normal - moment])
        problem.solve(solver=cp.CLARABEL)
        return float(x.value[3]) if problem.status == cp.OPTIMAL else None
    a_ub = np.vstack([ri * n_rows - mom, mom - re * n_rows, -n_rows])
    b_ub = np.concatenate([ri * n_rhs + sx, -sx - re * n_rhs, -n_rhs])
    r = linprog([0, 0, 0, -1.0], A_ub=a_ub, b_ub=b_ub, bounds=[(None, None)] * 3 + [(0, None)],
                method="highs", options=TOLERANCES)
    return None if r.status != 0 else float(r.x[3])
