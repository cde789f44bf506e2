"""The continuous semicircular arch under self-weight: minimum thickness by a linear program.

A semicircular ring of centreline radius ``R = 1``, thickness ``t`` (intrados ``ri = 1 - t/2``,
extrados ``re = 1 + t/2``), unit weight and depth 1, symmetric. The half arch from the crown
to a cut carries the crown thrust ``H`` (horizontal, at height ``y0`` on the crown section) and
its weight ``W``; the resultant on the cut is ``(-H, W)``. The static theorem (Heyman) asks for
``(H, M = H y0)`` with ``ri H <= M <= re H`` such that on every cut of the family

- the resultant crosses the cut inside the ring (the locus of pressure points lies in the
  section), and
- with friction ``mu``, ``|T| <= mu N`` on the cut (Coulomb; ``T``, ``N`` its tangential and
  normal components),

all of which are linear in ``(H, M)``. Cuts (the stereotomy):

- ``radial``: the cut at angle ``phi`` from the crown; the annular sector ``[0, phi]`` weighs
  ``W = phi t`` at radius ``rc = (2/3) (re^3 - ri^3) / (re^2 - ri^2) sin(phi/2) / (phi/2)`` on
  its bisector. The pressure point on the cut lies at radius
  ``rho = (M + W xc) / (H cos phi + W sin phi)`` with ``xc = rc sin(phi/2)``;
  ``N = H cos phi + W sin phi`` and ``T = H sin phi - W cos phi``.
- ``vertical``: the cut at abscissa ``x`` from the intrados (the springing line beyond it) to
  the extrados; the part ``[0, x]`` of the ring weighs ``W(x)`` with first moment ``S(x)``
  about the crown axis (integrated in closed form below). The pressure point lies at height
  ``z = (M - (W x - S)) / H``; ``N = H`` and ``T = W``.

The smallest ``t`` for which the program is feasible is found by bisection. Written from the
statement of the problem (Heyman, *The Stone Skeleton*, 1995; Cocchetti & Rizzi 2020;
Makris & Alexakis 2013), independently of tce: it imports nothing from it.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import linprog


def _segment_area(r: float, x: np.ndarray) -> np.ndarray:
    """Area under ``z = sqrt(r^2 - u^2)`` for ``u`` in ``[0, min(x, r)]``."""
    u = np.minimum(x, r)
    return 0.5 * (u * np.sqrt(r**2 - u**2) + r**2 * np.arcsin(u / r))


def _segment_moment(r: float, x: np.ndarray) -> np.ndarray:
    """First moment ``int u sqrt(r^2 - u^2) du`` over ``[0, min(x, r)]``."""
    u = np.minimum(x, r)
    return (r**3 - (r**2 - u**2) ** 1.5) / 3.0


def _rows(t: float, cuts: str, mu: float | None, m: int) -> tuple[np.ndarray, np.ndarray]:
    ri, re = 1.0 - t / 2.0, 1.0 + t / 2.0
    rows = [np.array([[ri, -1.0], [-re, 1.0]])]
    rhs = [np.zeros(2)]
    if cuts == "radial":
        phi = np.linspace(np.pi / 2 / m, np.pi / 2, m)
        w = phi * t
        rc = (2.0 / 3.0) * (re**3 - ri**3) / (re**2 - ri**2) * np.sin(phi / 2) / (phi / 2)
        xc = rc * np.sin(phi / 2)
        c, s = np.cos(phi), np.sin(phi)
        zero = np.zeros(m)
        # ri (H c + W s) <= M + W xc <= re (H c + W s)
        rows += [np.column_stack([ri * c, -np.ones(m)]), np.column_stack([-re * c, np.ones(m)])]
        rhs += [w * xc - ri * w * s, re * w * s - w * xc]
        if mu is not None:  # +-(H s - W c) <= mu (H c + W s)
            rows += [np.column_stack([s - mu * c, zero]), np.column_stack([-s - mu * c, zero])]
            rhs += [w * c + mu * w * s, -w * c + mu * w * s]
    elif cuts == "vertical":
        x = np.linspace(re / m, re * (1 - 1e-12), m)
        w = _segment_area(re, x) - _segment_area(ri, x)
        first = _segment_moment(re, x) - _segment_moment(ri, x)
        lever = w * x - first  # moment of the part's weight about the cut's abscissa
        zi = np.sqrt(np.maximum(ri**2 - x**2, 0.0))
        ze = np.sqrt(re**2 - x**2)
        # zi H <= M - lever <= ze H
        rows += [np.column_stack([zi, -np.ones(m)]), np.column_stack([-ze, np.ones(m)])]
        rhs += [-lever, lever]
        if mu is not None:  # W <= mu H
            rows += [np.column_stack([-mu * np.ones(m), np.zeros(m)])]
            rhs += [-w]
    else:
        raise ValueError(f"unknown cuts {cuts!r}")
    return np.vstack(rows), np.concatenate(rhs)


def thrust_range(t: float, cuts: str = "radial", mu: float | None = None, m: int = 2000) -> tuple[float, float] | None:
    """Least and greatest crown thrust ``H / (t R^2 gamma d)`` admissible at thickness ``t``
    (None when none is)."""
    a, b = _rows(t, cuts, mu, m)
    out = []
    for sense in (1.0, -1.0):
        r = linprog([sense, 0.0], A_ub=a, b_ub=b, bounds=[(0, None), (None, None)], method="highs")
        if r.status != 0:
            return None
        out.append(r.x[0] / t)
    return out[0], out[1]


def stands(t: float, cuts: str = "radial", mu: float | None = None, m: int = 2000) -> bool:
    """Whether an admissible state exists at thickness ratio ``t = t/R``."""
    a, b = _rows(t, cuts, mu, m)
    r = linprog([0.0, 0.0], A_ub=a, b_ub=b, bounds=[(0, None), (None, None)], method="highs")
    return r.status == 0


def minimum_thickness(cuts: str = "radial", mu: float | None = None, m: int = 2000,
                      lo: float = 0.05, hi: float = 0.6, tol: float = 1e-7) -> float | None:
    """Smallest ``t/R`` that stands (None if even ``hi`` does not)."""
    if not stands(hi, cuts, mu, m):
        return None
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        if stands(mid, cuts, mu, m):
            hi = mid
        else:
            lo = mid
    return hi
