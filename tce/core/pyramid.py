"""Friction pyramids: the Coulomb cone replaced by polygons, a linear-programming bracket.

In the spatial model the friction law of a contact, ``||(ft1, ft2)|| <= mu fn``, is a
second-order cone. Replacing the disc of radius ``mu fn`` by a regular polygon of ``k``
sides gives a linear program:

``inscribed``
    the polygon's vertices lie on the circle, at angles ``2 pi j / k`` from ``t1``; its
    facets are ``cos(phi_i) ft1 + sin(phi_i) ft2 <= mu cos(pi / k) fn`` with
    ``phi_i = (2 i + 1) pi / k``. The polygon lies inside the cone: every force state it
    admits is admissible, so its lambda_max is a **lower bound** of the cone's.
``circumscribed``
    the facets are tangent to the circle, ``cos(phi_i) ft1 + sin(phi_i) ft2 <= mu fn``
    with ``phi_i = 2 i pi / k``. The polygon contains the cone, so its lambda_max is an
    **upper bound**.

Doubling ``k`` keeps the previous polygons' vertices (inscribed) and facets
(circumscribed), so the bracket narrows monotonically along ``k = 4, 8, 16, ...``; its
relative width is at most ``1 / cos(pi / k) - 1`` of the friction (about
``(pi / k)^2 / 2``). In a planar model the friction law is already linear
(``|ft| <= mu fn``) and both pyramids are the cone itself; with ``mu = 0`` or a Heyman
material there is no cone either. Scaling, the dual mechanism and the statuses are those
of :class:`tce.core.limit.LimitSolver`.
"""

from __future__ import annotations

from typing import Literal

import numpy as np
import scipy.sparse as sp

from .conic import ConeRows, cone_rows
from .limit import LimitResult, LimitSolver
from .material import Material
from .model import Model

__all__ = ["PyramidKind", "pyramid_rows", "pyramid_lambda_max", "pyramid_bracket"]

PyramidKind = Literal["inscribed", "circumscribed"]


def pyramid_rows(model: Model, friction: float | None, k: int, kind: PyramidKind = "inscribed") -> ConeRows:
    """Contact law of ``model`` with every friction cone replaced by a ``k``-sided pyramid.

    Parameters
    ----------
    model : Model
    friction : float or None
        Friction coefficient mu (None: Heyman, no friction limit).
    k : int
        Number of sides of the polygon (>= 3).
    kind : {"inscribed", "circumscribed"}
        Polygon inside the cone (lower bound) or around it (upper bound).

    Returns
    -------
    ConeRows
        Nonnegative rows only (an LP): ``fn >= 0`` and ``k`` facets per contact, or the
        exact law of :func:`tce.core.conic.cone_rows` when it is already linear (planar model,
        ``mu = 0``, Heyman).
    """
    if int(k) != k or k < 3:
        raise ValueError(f"a pyramid needs k >= 3 whole sides, got {k!r}")
    if kind not in ("inscribed", "circumscribed"):
        raise ValueError(f"kind must be 'inscribed' or 'circumscribed', got {kind!r}")
    if friction is None or float(friction) == 0.0 or model.dim == 2:
        return cone_rows(model, friction)
    k = int(k)
    mu = float(friction)
    nc = model.n_contacts
    if kind == "inscribed":
        phi = (2.0 * np.arange(k) + 1.0) * np.pi / k
        reach = mu * np.cos(np.pi / k)
    else:
        phi = 2.0 * np.arange(k) * np.pi / k
        reach = mu
    # facet row i of contact c: reach * fn - cos(phi_i) ft1 - sin(phi_i) ft2 >= 0
    coef = np.column_stack([np.full(k, reach), -np.cos(phi), -np.sin(phi)])  # (k, 3)
    rows = np.arange(nc * k)
    cols = (3 * np.arange(nc))[:, None, None] + np.arange(3)[None, None, :]  # (nc, 1, 3)
    facets = sp.csr_matrix(
        (
            np.broadcast_to(coef, (nc, k, 3)).ravel(),
            (np.repeat(rows, 3), np.broadcast_to(cols, (nc, k, 3)).ravel()),
        ),
        shape=(nc * k, model.n_vars),
    )
    normal = sp.csr_matrix((np.ones(nc), (np.arange(nc), 3 * np.arange(nc))), shape=(nc, model.n_vars))
    return ConeRows(sp.vstack([normal, facets]).tocsr(), 0, nc * (k + 1), 0)


def pyramid_lambda_max(
    model: Model,
    friction: float | None,
    alpha: float = 0.0,
    k: int = 8,
    kind: PyramidKind = "inscribed",
    tol: float = 1e-10,
) -> LimitResult:
    """lambda_max with the friction cones replaced by ``k``-sided pyramids (an LP).

    Parameters
    ----------
    model : Model
    friction : float or None
        Friction coefficient mu of the cone being bracketed.
    alpha : float
        Lateral direction (degrees).
    k : int
        Sides of the pyramid (>= 3).
    kind : {"inscribed", "circumscribed"}
        ``inscribed`` gives a lower bound of the cone's lambda_max, ``circumscribed`` an
        upper bound.
    tol : float
        Clarabel's tolerances on the scaled problem.

    Returns
    -------
    LimitResult
        As :meth:`tce.core.limit.LimitSolver.solve`; ``lambda_max`` is the bound. Its mechanism's
        ``admissibility`` is measured against the (possibly enlarged) cone, not the pyramid.
    """
    # residuals are checked on the pyramid's own rows, the mechanism against the cone the
    # pyramid is inscribed in (mu / cos(pi / k) for a circumscribed pyramid, mu otherwise)
    check = friction
    if friction is not None and kind == "circumscribed" and model.dim == 3:
        check = float(friction) / np.cos(np.pi / int(k))
    return LimitSolver(model, Material(friction=check), tol, rows=pyramid_rows(model, friction, k, kind)).solve(alpha)


def pyramid_bracket(model: Model, friction: float | None, alpha: float = 0.0, k: int = 8) -> tuple[float, float]:
    """``(lower, upper)`` bounds of the cone's lambda_max from the inscribed and circumscribed
    ``k``-sided pyramids (NaN where a bound's LP is not ``optimal``)."""
    lo = pyramid_lambda_max(model, friction, alpha, k, "inscribed")
    hi = pyramid_lambda_max(model, friction, alpha, k, "circumscribed")
    return lo.lambda_max, hi.lambda_max
