"""Load-path driver: raise lambda until the TCE has no admissible answer, then bisect.

For one scenario (support motions, possibly none), a load pattern (the lateral direction
``alpha``, or a :class:`tce.core.loads.LoadPattern` whose live part lambda multiplies) and
the analysis' material, :func:`load_path` solves the TCE at ``lam = 0, step, 2 step, ...``
until the first step whose status is not ``optimal`` (``numerical`` steps are kept,
reported and stepped over: they are never taken as the limit). When that step is
``infeasible``, it narrows the bracket between the last ``optimal`` and the first
``infeasible`` multiplier until ``hi - lo <= max(atol, rtol * hi)`` or until no float lies
between them; ``lambda_max`` is the last ``optimal`` multiplier (a safe lower bound). A
path never takes more than :data:`MAX_INCREMENTS` increments. Every run also reports the
direct lambda_max (:mod:`tce.core.limit`) and the gap.

Narrowing (``bracket``): ``"direct"`` (default) first solves the two ends of a bracket
narrower than the tolerance around the direct lambda_max (:func:`_confirm_direct`), then
bisects what remains; ``"bisection"`` halves the bracket from the last increment. Both give
a verified admissible ``lambda_max`` within the tolerance of the limit.
"""

from __future__ import annotations

import logging
import math
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from numpy.typing import ArrayLike

from ..core.loads import LoadPattern, as_pattern
from ..core.result import Result

if TYPE_CHECKING:
    from ..core.analysis import Analysis
    from ..core.limit import LimitResult
    from ..core.solve import TCEResult

__all__ = [
    "AUTO_INCREMENTS",
    "DEFAULT_CAP",
    "DEFAULT_RTOL",
    "DEFAULT_STEP",
    "MAX_INCREMENTS",
    "LoadPathResult",
    "increments_and_cap",
    "load_path",
]

log = logging.getLogger(__name__)

#: Most load increments a path may take (``lam_cap / step``; the limit itself is bisected to ``atol``).
MAX_INCREMENTS = 10_000
#: increments a path takes up to its direct limit when no step is given
AUTO_INCREMENTS = 20
#: increment of a path without a step whose direct limit is not a positive number
DEFAULT_STEP = 0.02
#: cap of a path without one whose direct limit is undecided (``numerical``)
DEFAULT_CAP = 100.0
#: relative tolerance on lambda_max of a study that gives no ``tolerance``
DEFAULT_RTOL = 1e-6
#: where a bracket closed on undecided steps is tried once more: ``hi - CLOSING * tolerance``,
#: the multiplier furthest below the inadmissible end that still closes it
CLOSING = 0.99


@dataclass(frozen=True, eq=False, kw_only=True, repr=False)
class LoadPathResult(Result):
    """A load path and its limit (``ok`` when ``status == "limit"``).

    Attributes
    ----------
    status : str
        How the path ended (also :attr:`outcome`): ``limit`` (bisected to an infeasible
        load), ``unbounded`` (a step is unbounded: the support motion is incompatible with
        the material), ``infeasible`` (no admissible state at lambda = 0), ``no_limit``
        (still admissible at ``lam_cap``), ``numerical`` (undecided: the bracket, the
        steps before the first infeasible one, or the last steps up to ``lam_cap`` could
        not be decided, or no optimal step lies within the tolerance of the first
        inadmissible one).
    alpha : float
        Direction of the lateral loads (degrees; NaN when the pattern has no lateral part).
    loads : LoadPattern
        The load pattern.
    settlements : dict
        Support motions of the scenario ``{support: [ux, uy, uz, rx, ry, rz]}`` (m, rad).
    steps : list of TCEResult
        Every solve, in the order made: the increments, then the bisection.
    lambda_max : float
        Last admissible multiplier of the bisection (NaN unless ``outcome == "limit"``).
    lambda_upper : float
        Smallest multiplier found inadmissible (NaN if none).
    limit : LimitResult
        The direct limit analysis of the same pattern.
    n_solves : int
    """

    HEADLINE = ("lambda_max", "lambda_upper", "lambda_direct", "alpha", "n_solves")

    OK = ("limit",)

    alpha: float
    loads: LoadPattern = field(repr=False)
    settlements: dict
    steps: list[TCEResult] = field(repr=False)
    lambda_max: float
    lambda_upper: float
    limit: LimitResult = field(repr=False)
    n_solves: int = 0

    @property
    def outcome(self) -> str:
        """How the path ended: the :attr:`status`."""
        return self.status

    @property
    def lambda_direct(self) -> float:
        """lambda_max of the direct conic program."""
        return self.limit.lambda_max

    @property
    def gap(self) -> float:
        """``lambda_max - lambda_direct`` (NaN when either is undefined)."""
        return self.lambda_max - self.lambda_direct

    @property
    def path(self) -> list[TCEResult]:
        """The steps sorted by lambda."""
        return sorted(self.steps, key=lambda r: r.lam)

    def _arrays(self) -> tuple[dict[str, tuple], dict[str, Any]]:
        """The steps sorted by lambda along ``step``: ``lam``, ``status``, ``tce``, residuals
        and each step's labelled arrays (:meth:`tce.core.solve.TCEResult.to_xarray`)."""
        path = self.path
        if not path:
            return {}, {}
        first, coords = path[0]._arrays()
        data: dict[str, tuple] = {
            "lam": (("step",), np.array([r.lam for r in path])),
            "status": (("step",), np.array([r.status for r in path], dtype=object)),
            "tce": (("step",), np.array([r.tce for r in path]), {"units": "kN m"}),
            "eq_residual": (("step",), np.array([r.eq_residual for r in path])),
            "cone_residual": (("step",), np.array([r.cone_residual for r in path])),
        }
        per_step = [first] + [r._arrays()[0] for r in path[1:]]
        for name, (dims, _, attrs) in first.items():
            if name != "vertex_point":
                data[name] = (("step", *dims), np.stack([a[name][1] for a in per_step]), attrs)
        data["vertex_point"] = first["vertex_point"]
        return data, coords

    @property
    def at_limit(self) -> TCEResult | None:
        """The optimal step at ``lambda_max``."""
        ok = [r for r in self.steps if r.ok and r.lam == self.lambda_max]
        return ok[0] if ok else None


def _confirm_direct(
    run: Callable[[float], TCEResult], lo: float, hi: float, direct: float, atol: float, rtol: float
) -> tuple[float, float]:
    """Narrow the bracket ``(lo, hi)`` (``lo`` optimal, ``hi`` infeasible) around ``direct``.

    Solves the TCE at ``direct -+ 0.49 w`` (``w = max(atol, rtol * direct)``, the bisection's
    tolerance; ends outside ``(lo, hi)`` are not solved): an ``optimal`` lower end and an
    ``infeasible`` upper end confirm the limit; otherwise the bracket becomes the narrowest
    one the solved ends support (a ``numerical`` end tells nothing). With no finite direct
    value, ``(lo, hi)`` is returned unchanged.

    Returns
    -------
    (float, float)
        The last ``optimal`` multiplier and the first ``infeasible`` one.
    """
    if not (math.isfinite(direct) and lo < direct < hi):
        return lo, hi
    half = 0.49 * max(atol, rtol * abs(direct))
    for lam in (direct - half, direct + half):
        if not lo < lam < hi:
            continue
        status = run(lam).status
        if status == "optimal":
            lo = lam
        elif status == "infeasible":
            hi = lam
            break  # nothing above it is admissible
        else:
            break  # undecided: bisection decides
    return lo, hi


def _first_inadmissible(lo: float | None, steps: list[TCEResult]) -> str:
    """Outcome when an increment is infeasible: ``limit`` above an admissible step;
    ``infeasible`` only when every step before it was decided too (at lambda = 0, nothing
    stands); ``numerical`` when undecided steps came first (the structure may stand)."""
    if lo is not None:
        return "limit"
    return "numerical" if any(s.status == "numerical" for s in steps) else "infeasible"


def increments_and_cap(
    lim: LimitResult, step: float | None, lam_cap: float | None
) -> tuple[float, float, str]:
    """The increment and the largest multiplier the path tries, anchored on the direct limit.

    See :func:`load_path`. Returns ``(increment, cap, note)``; ``note`` says when an
    explicit step was coarsened.
    """
    finite = lim.status == "optimal" and math.isfinite(lim.lambda_max) and lim.lambda_max > 0
    note = ""
    if step is None:
        step = lim.lambda_max / (AUTO_INCREMENTS + 0.5) if finite else DEFAULT_STEP
    elif finite and lim.lambda_max / step > MAX_INCREMENTS:
        note = (f"; lambda_step = {step:g} would take {lim.lambda_max / step:.3g} increments to the direct limit "
                f"{lim.lambda_max:.6g}: {AUTO_INCREMENTS} increments of {lim.lambda_max / (AUTO_INCREMENTS + 0.5):.6g} "
                "were taken")
        step = lim.lambda_max / (AUTO_INCREMENTS + 0.5)
    if lam_cap is not None:
        cap = lam_cap
    elif lim.status == "optimal":
        cap = math.inf  # the first infeasible increment lies just above the direct limit
    elif lim.status in ("unbounded", "infeasible"):
        cap = AUTO_INCREMENTS * step  # the direct problem decided it; the increments trace the path
    else:
        cap = DEFAULT_CAP  # the direct limit is undecided: search as far as a cap
    return step, cap, note


def load_path(
    analysis: Analysis,
    alpha: float | None = None,
    settlements: Mapping[str, ArrayLike] | None = None,
    step: float | None = None,
    atol: float = 1e-6,
    rtol: float = 0.0,
    lam_cap: float | None = None,
    loads: LoadPattern | None = None,
    bracket: Literal["direct", "bisection"] = "direct",
    mechanism: bool = True,
) -> LoadPathResult:
    """Increment lambda from 0, then narrow the first inadmissible increment.

    The direct limit (:meth:`tce.core.analysis.Analysis.limit`) is solved first and anchors
    the path, so that the number of solves does not depend on the live load's size:

    - **step**: by default ``lambda_direct / (AUTO_INCREMENTS + 0.5)`` (no increment falls
      on the limit itself); :data:`DEFAULT_STEP` when the direct limit is not a positive
      number. An explicit step is kept unless it would take more than
      :data:`MAX_INCREMENTS` increments to reach the direct limit (then the default is
      taken and the message says so).
    - **cap**: none by default when the direct limit is finite (the path goes on until an
      increment is inadmissible); ``AUTO_INCREMENTS * step`` when it is unbounded or
      infeasible (the direct problem decided: the increments trace the path);
      :data:`DEFAULT_CAP` when it is undecided. A cap given below the direct limit ends
      the path with the outcome ``capped`` ("capped at X, below the collapse load Y").
    - when the increments end admissible at the cap (or at :data:`MAX_INCREMENTS`) below a
      finite direct limit that the cap does not cut, the bracket around the direct limit
      (:func:`_confirm_direct`) is solved to find the inadmissible end.
    - ``no_limit`` only when the direct limit is unbounded and every increment up to the
      cap is admissible; with a finite direct limit that the path cannot confirm, or an
      undecided one, the outcome is ``numerical``.

    Parameters
    ----------
    analysis : Analysis
    alpha : float, optional
        Lateral direction (degrees, from +x towards +y) of the default pattern (0 when None).
    settlements : dict, optional
        Support motions (m, rad) about each support centroid.
    step : float, optional
        Load increment (> 0); default anchored on the direct limit (above).
    atol, rtol : float
        Bisection stops when ``hi - lo <= max(atol, rtol * hi)``; at least one > 0.
    lam_cap : float, optional
        Largest multiplier the increments try (above); ``lam_cap / step`` may not exceed
        :data:`MAX_INCREMENTS` and ``step`` may not exceed ``lam_cap``.
    loads : LoadPattern, optional
        The load pattern instead of ``alpha`` (its live part is multiplied by lambda).
    bracket : {"direct", "bisection"}
        How the last increment is narrowed (module docstring): first a bracket around the
        direct lambda_max, or bisection alone.
    mechanism : bool
        Whether the result's direct ``limit`` carries its collapse mechanism (classified
        once, after the path).

    Returns
    -------
    LoadPathResult
    """
    if step is not None and not (math.isfinite(step) and step > 0):
        raise ValueError(f"step must be a finite number > 0, got {step!r}")
    if lam_cap is not None and not (math.isfinite(lam_cap) and lam_cap > 0):
        raise ValueError(f"lam_cap must be a finite number > 0, got {lam_cap!r}")
    if not (atol >= 0 and rtol >= 0 and (atol > 0 or rtol > 0)):
        raise ValueError(f"tolerances must be >= 0 and not both 0, got atol={atol!r}, rtol={rtol!r}")
    if bracket not in ("direct", "bisection"):
        raise ValueError(f"bracket must be 'direct' or 'bisection', got {bracket!r}")
    if step is not None and lam_cap is not None:
        if step > lam_cap:
            raise ValueError(f"step = {step!r} is larger than lam_cap = {lam_cap!r}: no increment but 0 would be tried")
        if not lam_cap / step <= MAX_INCREMENTS:
            raise ValueError(
                f"lam_cap / step = {lam_cap / step:.3g} load increments, more than {MAX_INCREMENTS}: "
                "use a larger step or a smaller lam_cap"
            )
    t0 = time.perf_counter()
    pattern = as_pattern(alpha, loads)
    sett = {k: list(np.asarray(v, dtype=float)) for k, v in (settlements or {}).items()}
    steps: list[TCEResult] = []
    solve_at = analysis.path(settlements=sett, loads=pattern)
    lim = analysis.limit(loads=pattern, mechanism=False)  # the mechanism, when asked, at the end
    direct = lim.lambda_max
    step, cap, note = increments_and_cap(lim, step, lam_cap)
    if note:
        log.warning("load path%s", note)

    def run(lam: float) -> TCEResult:
        r = solve_at(lam)
        steps.append(r)
        return r

    lo: float | None = None
    hi: float | None = None
    outcome = ""
    k = 0
    while k <= MAX_INCREMENTS and math.isfinite(lam := k * step) and lam <= cap:
        r = run(lam)
        if r.status == "optimal":
            lo = lam
        elif r.status == "infeasible":
            hi = lam
            outcome = _first_inadmissible(lo, steps)
            break
        elif r.status == "unbounded":
            outcome = "unbounded"
            break
        elif lim.status == "optimal" and lam > direct:
            break  # undecided above the direct limit (a huge step): the bracket around it decides
        k += 1
    width = max(atol, rtol * abs(direct)) if math.isfinite(direct) else atol
    if not outcome:  # the increments ended admissible at the cap, or undecided
        if lim.status == "optimal" and lam_cap is not None and lam_cap < direct - width and steps[-1].ok:
            outcome = "capped"
        elif lim.status == "optimal" and lo is not None and (steps[-1].ok or steps[-1].lam > direct):
            lo, top = _confirm_direct(run, lo, math.inf, direct, atol, rtol)
            outcome, hi = ("limit", top) if math.isfinite(top) else ("numerical", None)
        elif not steps[-1].ok:
            outcome = "numerical"  # the last steps are undecided: not known to stand
        else:
            outcome = "no_limit" if lim.status == "unbounded" else "numerical"
    if outcome == "limit":
        assert lo is not None and hi is not None
        if bracket == "direct":
            lo, hi = _confirm_direct(run, lo, hi, direct, atol, rtol)
        lo_bracket = lo  # admissible end of the bracket; `lo` stays the last optimal step
        while hi - lo_bracket > max(atol, rtol * abs(hi)):
            mid = 0.5 * (lo_bracket + hi)
            if not lo_bracket < mid < hi:
                break  # the bracket is two neighbouring floats: no multiplier lies between them
            r = run(mid)
            if r.status == "optimal":
                lo = lo_bracket = mid
            elif r.status == "infeasible":
                hi = mid
            elif r.status == "numerical" and math.isfinite(direct):
                # an undecided step stays `numerical` and is never the answer; the direct
                # limit tells on which side of it the limit lies
                if mid > direct:
                    hi = mid
                else:
                    lo_bracket = mid
            else:
                outcome = "numerical"
                break
        if outcome == "limit" and hi - lo > max(atol, rtol * abs(hi), math.ulp(hi)):
            # the bracket closed on undecided steps next to the limit, where the admissible
            # set thins to a point: the multiplier furthest from the limit that still closes
            # the bracket is solved once more
            lam = hi - CLOSING * max(atol, rtol * abs(hi))
            if lo < lam < hi and run(lam).status == "optimal":
                lo = lam
        if outcome == "limit" and hi - lo > max(atol, rtol * abs(hi), math.ulp(hi)):
            # no optimal step lies within the tolerance of the limit, so the last optimal
            # one is not the answer
            outcome = "numerical"
    lam_max = lo if outcome == "limit" and lo is not None else float("nan")
    if outcome == "capped":
        message = f"capped at lambda = {cap:.6g}, below the collapse load lambda_direct = {direct:.6g}"
    else:
        message = f"{outcome} after {len(steps)} solves"
    return LoadPathResult(
        status=outcome,
        message=message + note,
        alpha=pattern.direction,
        loads=pattern,
        settlements=sett,
        steps=steps,
        lambda_max=float(lam_max),
        lambda_upper=float(hi) if hi is not None else float("nan"),
        limit=analysis.limit(loads=pattern, mechanism=True) if mechanism else lim,
        n_solves=len(steps),
        solve_time=float(sum(s.solve_time for s in steps)),
        wall_time=time.perf_counter() - t0,
    )
