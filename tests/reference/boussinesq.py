"""Independent reference for Boussinesq's distribution of a wheel load through fill: the
vertical stress under a point load ``Q`` at the surface of an elastic half-space,
``sigma_z = 3 Q h^3 / (2 pi (r^2 + h^2)^(5/2))`` at depth ``h`` and plan distance ``r``
(Boussinesq 1885; e.g. Holtz & Kovacs 1981), integrated numerically over plan rectangles by
scipy's ``dblquad`` (no closed form). Never imports tce."""

from __future__ import annotations

import math

from scipy.integrate import dblquad


def kernel(u: float, v: float, h: float) -> float:
    """``sigma_z / Q`` (1/m^2) at plan offset ``(u, v)`` from the load, depth ``h``."""
    return 3.0 * h**3 / (2.0 * math.pi * (u * u + v * v + h * h) ** 2.5)


def rectangle(u1: float, u2: float, v1: float, v2: float, h: float) -> tuple[float, float, float]:
    """``(fraction, Mu, Mv)``: integral of ``sigma_z / Q`` over ``[u1, u2] x [v1, v2]`` and its
    first moments about the load's plan position (m)."""
    opts = dict(epsabs=1e-13, epsrel=1e-11)
    f = dblquad(lambda v, u: kernel(u, v, h), u1, u2, v1, v2, **opts)[0]
    mu = dblquad(lambda v, u: u * kernel(u, v, h), u1, u2, v1, v2, **opts)[0]
    mv = dblquad(lambda v, u: v * kernel(u, v, h), u1, u2, v1, v2, **opts)[0]
    return f, mu, mv
