"""The adequacy factor of a load assessment: the live load's collapse multiplier with
partial factors on the dead and live loads.

With partial factors ``gamma_dead`` on every fixed load (self-weight, fill, fixed point and
distributed loads) and ``gamma_live`` on the live loads, the adequacy factor is the largest
``lam`` such that ``gamma_dead b_fixed + lam gamma_live b_live`` is carried (a direct limit
analysis, :class:`tce.core.limit.LimitSolver`): the number of times the factored live load
(e.g. a vehicle at its critical position) can be applied before collapse. At least 1: the
structure is adequate for the load; below 1: it is not.

Defaults are 1.0 on both (no factor): the factors are the assessing engineer's (a code's)
choice. For a material without cohesion or strengths (Heyman, friction) the admissible
loads form a cone, so the factored answer is ``lambda_max gamma_dead / gamma_live`` exactly:
a larger factor on the (stabilising) dead load of an arch raises the adequacy factor; codes
that treat dead load as favourable choose ``gamma_dead <= 1`` for it.
"""

from __future__ import annotations

from ..core.analysis import Analysis
from ..core.limit import LimitResult, LimitSolver
from ..core.loads import LoadPattern, load_vectors
from ..core.passive import passive_restraint

__all__ = ["adequacy_factor"]


def adequacy_factor(analysis: Analysis, loads: LoadPattern, dead_factor: float = 1.0, live_factor: float = 1.0) -> LimitResult:
    """The direct limit of ``loads`` with the fixed loads times ``dead_factor`` and the live
    loads times ``live_factor``; its ``lambda_max`` is the adequacy factor (see module).

    Raises
    ------
    ValueError
        A factor that is not a positive finite number.
    """
    for name, v in (("dead_factor", dead_factor), ("live_factor", live_factor)):
        if not (isinstance(v, int | float) and 0.0 < v < float("inf")):
            raise ValueError(f"{name} must be a positive finite number, got {v!r}")
    model = analysis.model(analysis.model_kind(loads=loads))
    b_fixed, b_live = load_vectors(model, loads)
    # the fill's passive restraint (a resistance of the soil) is not factored
    return LimitSolver(model, analysis.material).solve_loads(dead_factor * b_fixed, live_factor * b_live,
                                                             loads.direction, loads,
                                                             restraint=passive_restraint(model, loads.fill))
