"""The comparisons every metamorphic relation of the battery makes (:func:`same_answer`).

Tolerances, each from how the number is computed:

- the direct lambda_max is one conic program solved to Clarabel's tolerances and checked to
  1e-9 of the weight: two scenes that are the same problem in other coordinates give it to
  1e-7 (relative; measured: at most 1e-9 over the battery's scenes);
- the load path's lambda_max is the last optimal step of a bisection closed to
  ``atol = 1e-6``: two runs may stop on either side of a bisection point, so 2e-6;
- the total support reaction (forces, and moments about one point) is fixed by global
  equilibrium: 1e-8 of the weight (of the weight times the size for moments);
- one support's reaction, an interface's resultant and pressure point are answers only
  where the state is unique (compliant contacts): 1e-6 of the weight, pressure points
  1e-5 of the size under a resultant above 1e-3 of the weight (a QP solved by an
  interior-point method; measured: 1e-9);
- the non-associative estimate stops when lambda's last two changes are each within its
  ``tol = 1e-6`` (absolute below 1), and so is what is left of a creep between them: 1e-5.
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


def _same_interfaces(a: Answer, b: Answer, t: Similarity, w: float, size: float) -> None:
    """Pressure points and resultants of a unique state, moved by ``t`` (an interface read
    from its other side in ``b`` carries the opposite resultant)."""
    assert len(a.interfaces) == len(b.interfaces)
    for (A, B), (p, f) in a.interfaces.items():
        q, g = b.interfaces[(A, B)] if (A, B) in b.interfaces else (b.interfaces[(B, A)][0], -b.interfaces[(B, A)][1])
        np.testing.assert_allclose(g, t.forces(f), rtol=0, atol=1e-6 * w, err_msg=f"resultant {A}|{B}")
        if np.linalg.norm(f) > 1e-3 * w:  # a pressure point is well defined under a force
            np.testing.assert_allclose(q, t.points(p), rtol=0, atol=1e-5 * size, err_msg=f"pressure point {A}|{B}")


def same_answer(a: Answer, b: Answer, t: Similarity | None = None, rename: dict[str, str] | None = None,
                same_model: bool = True) -> None:
    """Assert that ``b`` is ``a`` seen through ``t`` (default: the identity); ``rename`` maps
    ``a``'s support names to ``b``'s; ``same_model``: on the same model (planar or spatial:
    a planar scene moved stays planar, in whatever vertical plane)."""
    t = t or Similarity()
    if same_model:
        assert a.model == b.model, (a.model, b.model)
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
            _same_interfaces(a, b, t, w, size)
    if a.nonassoc is not None:
        assert b.nonassoc is not None and a.nonassoc[0] == b.nonassoc[0], (a.nonassoc, b.nonassoc)
        assert _close(a.nonassoc[1], b.nonassoc[1], 1e-5), (a.nonassoc, b.nonassoc)
