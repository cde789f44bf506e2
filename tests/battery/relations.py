"""The comparisons every metamorphic relation of the battery makes (:func:`same_answer`).

Tolerances, each from how the number is computed:

- the direct lambda_max is one conic program solved to Clarabel's tolerances and checked to
  1e-9 of the weight: two scenes that are the same problem in other coordinates give it to
  1e-7 (relative; measured: at most 1e-9 over the battery's scenes);
- the load path's lambda_max is the last optimal step of a bisection closed to
  ``atol = 1e-6``: two runs may stop on either side of a bisection point, so 2e-6;
- the total support reaction (forces, and moments about one point) is fixed by global
  equilibrium: 1e-8 of the weight (of the weight times the size for moments);
- one support's reaction is an answer only where the state is unique (compliant contacts):
  1e-6 of the weight (a QP solved by an interior-point method; measured: 1e-9);
- the non-associative estimate stops when lambda moves less than its ``tol = 1e-6``: 1e-5.
"""

from __future__ import annotations

import math

import numpy as np

from .cases import Answer
from .transform import Similarity


def _close(a: float, b: float, tol: float) -> bool:
    if math.isnan(a) or math.isnan(b):
        return math.isnan(a) and math.isnan(b)
    if math.isinf(a) or math.isinf(b):
        return a == b
    return abs(a - b) <= tol * max(1.0, abs(a))


def same_answer(a: Answer, b: Answer, t: Similarity | None = None, rename: dict[str, str] | None = None) -> None:
    """Assert that ``b`` is ``a`` seen through ``t`` (default: the identity); ``rename`` maps
    ``a``'s support names to ``b``'s."""
    t = t or Similarity()
    what = f"{a.outcome}/{b.outcome} lambda {a.lambda_max!r}/{b.lambda_max!r} direct {a.lambda_direct!r}/{b.lambda_direct!r}"
    assert (a.outcome, a.direct_status, a.status) == (b.outcome, b.direct_status, b.status), what
    assert _close(a.lambda_direct, b.lambda_direct, 1e-7), what
    assert _close(a.lambda_max, b.lambda_max, 2e-6), what
    w, size = a.weight * t.force, a.size * t.length
    if a.status == "optimal":
        expected = t.wrenches(a.total)
        np.testing.assert_allclose(b.total[:3], expected[:3], rtol=0, atol=1e-8 * w, err_msg="total reaction force")
        np.testing.assert_allclose(b.total[3:], expected[3:], rtol=0, atol=1e-8 * w * size, err_msg="total reaction moment")
        if a.unique:
            for name, wrench in a.reactions.items():
                other = b.reactions[(rename or {}).get(name, name)]
                exp = t.wrenches(wrench)
                np.testing.assert_allclose(other[:3], exp[:3], rtol=0, atol=1e-6 * w, err_msg=f"reaction force of {name}")
                np.testing.assert_allclose(other[3:], exp[3:], rtol=0, atol=1e-6 * w * size, err_msg=f"reaction moment of {name}")
    if a.nonassoc is not None:
        assert b.nonassoc is not None and a.nonassoc[0] == b.nonassoc[0], (a.nonassoc, b.nonassoc)
        assert _close(a.nonassoc[1], b.nonassoc[1], 1e-5), (a.nonassoc, b.nonassoc)
