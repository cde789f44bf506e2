"""The adequacy factor of a load assessment: the live load's collapse multiplier with
partial factors on the dead and live loads.

With partial factors ``gamma_dead`` on every fixed load (self-weight, fill, fixed point and
distributed loads) and ``gamma_live`` on the live loads, the adequacy factor is the largest
``lam`` such that ``gamma_dead b_fixed + lam gamma_live b_live`` is carried (a direct limit
analysis, :class:`tce.core.limit.LimitSolver`): the number of times the factored live load
(e.g. a vehicle at its critical position) can be applied before collapse. At least 1: the
structure is adequate for the load; below 1: it is not.

Defaults are 1.0 on both: the factors are the assessing engineer's (a code's) choice,
within one rule (:data:`DEAD_FACTOR_RULE`). For a material without cohesion or strengths
(Heyman, friction) the admissible loads form a cone, so the factored answer is
``lambda_max gamma_dead / gamma_live`` exactly: the dead load of an arch holds it up
(favourable), and a factor above 1 on it would raise the adequacy factor. A favourable
permanent action takes the code's lower partial factor (EN 1990:2002, 6.4.3.2 and Annex A2,
Table A2.4(B): ``gamma_G,sup = 1.35`` unfavourable, ``gamma_G,inf = 1.00`` favourable), so
a ``dead_factor`` above 1 is refused (:func:`check_dead_factor`: a study exits 2, a call
raises ``ValueError``); one below 1 is applied as given.
"""

from __future__ import annotations

from ..core.analysis import Analysis
from ..core.limit import LimitResult, LimitSolver
from ..core.loads import LoadPattern, load_vectors
from ..core.passive import passive_restraint

__all__ = ["DEAD_FACTOR_RULE", "adequacy_factor", "check_dead_factor"]

#: the rule on the dead load's partial factor, with its source (in messages and docs)
DEAD_FACTOR_RULE = (
    "the dead load of an arch is favourable (it holds the arch up), so it takes the favourable partial factor "
    "gamma_G,inf = 1.00 (EN 1990:2002, Table A2.4(B)); a dead_factor above 1 would raise the adequacy factor"
)


def check_dead_factor(dead_factor: float) -> None:
    """Raise ``ValueError`` for a ``dead_factor`` above 1 (:data:`DEAD_FACTOR_RULE`)."""
    if dead_factor > 1.0:
        raise ValueError(f"dead_factor = {dead_factor:g}: {DEAD_FACTOR_RULE}; fix: dead_factor = 1.0 "
                         "(or the code's favourable factor, at most 1)")


def adequacy_factor(analysis: Analysis, loads: LoadPattern, dead_factor: float = 1.0, live_factor: float = 1.0) -> LimitResult:
    """The direct limit of ``loads`` with the fixed loads times ``dead_factor`` and the live
    loads times ``live_factor``; its ``lambda_max`` is the adequacy factor (see module).

    Raises
    ------
    ValueError
        A factor that is not a positive finite number, or a ``dead_factor`` above 1
        (:func:`check_dead_factor`).
    """
    for name, v in (("dead_factor", dead_factor), ("live_factor", live_factor)):
        if not (isinstance(v, int | float) and 0.0 < v < float("inf")):
            raise ValueError(f"{name} must be a positive finite number, got {v!r}")
    check_dead_factor(dead_factor)
    model = analysis.model(analysis.model_kind(loads=loads))
    b_fixed, b_live = load_vectors(model, loads)
    # the fill's passive restraint (a resistance of the soil) is not factored
    return LimitSolver(model, analysis.material).solve_loads(dead_factor * b_fixed, live_factor * b_live,
                                                             loads.direction, loads,
                                                             restraint=passive_restraint(model, loads.fill))
