"""Load-path driver: raise lambda until the TCE has no admissible answer, then bisect.

For one scenario (support motions, possibly none), a load pattern (the lateral direction
``alpha``, or a :class:`tce.core.loads.LoadPattern` whose live part lambda multiplies) and
the analysis' material, :func:`load_path` solves the TCE at ``lam = 0, step, 2 step, ...``
until the first step whose status is not ``optimal`` (``numerical`` steps are kept,
reported and stepped over: they are never taken as the limit). When that step is
``infeasible``, it narrows the bracket between the last ``optimal`` and the first
``infeasible`` multiplier until ``hi - lo <= max(atol, rtol * hi)`` or until no float lies
between them (so any tolerance ends); ``lambda_max`` is the last ``optimal`` multiplier (a
safe lower bound). A path never takes more than :data:`MAX_INCREMENTS` increments. Every run
also reports the direct lambda_max (:mod:`tce.core.limit`) and the gap, so the answer is checked
each time.

Narrowing (``bracket``): ``"direct"`` (default) first solves the two ends of a bracket
narrower than the tolerance around the direct lambda_max (:func:`_confirm_direct`): an
``optimal`` lower end and an ``infeasible`` upper end confirm it in two solves; otherwise
what they showed narrows the bracket and bisection goes on from there. ``"bisection"``
halves the bracket from the last increment. Both give a verified admissible ``lambda_max``
within the tolerance of the limit; the direct bracket takes about half the solves.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike

from ..core.analysis import Analysis
from ..core.limit import LimitResult
from ..core.loads import LoadPattern, as_pattern
from ..core.result import Result
from ..core.solve import TCEResult

__all__ = ["MAX_INCREMENTS", "LoadPathResult", "load_path"]

#: Most load increments a path may take (``lam_cap / step``): 100,000 took 52 s on a 6-voussoir arch;
#: 10,000 resolve a path to 1e-4 of lambda_cap (the limit itself is bisected to ``atol``).
MAX_INCREMENTS = 10_000


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
    solve_time : float
        Wall time inside the solver's solve calls, summed over the steps (s).
    wall_time : float
        Time of the whole call (s).
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
    ``infeasible`` upper end confirm the limit. Either way the bracket becomes the narrowest
    one the solved ends support (a ``numerical`` end tells nothing), so bisection can go on
    from it. With no finite direct value, ``(lo, hi)`` is returned unchanged.

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


def load_path(
    analysis: Analysis,
    alpha: float | None = None,
    settlements: Mapping[str, ArrayLike] | None = None,
    step: float = 0.02,
    atol: float = 1e-6,
    rtol: float = 0.0,
    lam_cap: float = 100.0,
    loads: LoadPattern | None = None,
    bracket: Literal["direct", "bisection"] = "direct",
    mechanism: bool = True,
) -> LoadPathResult:
    """Increment lambda by ``step`` from 0, then narrow the first inadmissible increment.

    Parameters
    ----------
    analysis : Analysis
    alpha : float, optional
        Lateral direction (degrees, from +x towards +y) of the default pattern (0 when None).
    settlements : dict, optional
        Support motions (m, rad) about each support centroid.
    step : float
        Load increment (> 0).
    atol, rtol : float
        Bisection stops when ``hi - lo <= max(atol, rtol * hi)``; at least one > 0.
    lam_cap : float
        Largest multiplier tried before the path gives up (``outcome = "no_limit"``);
        ``lam_cap / step`` may not exceed :data:`MAX_INCREMENTS`.
    loads : LoadPattern, optional
        The load pattern instead of ``alpha`` (its live part is multiplied by lambda).
    bracket : {"direct", "bisection"}
        How the last increment is narrowed (module docstring): first a bracket around the
        direct lambda_max, or bisection alone.
    mechanism : bool
        Whether the result's direct ``limit`` carries its collapse mechanism (classified
        once, after the path; a study stores it). Without it the path costs its solves and
        one direct lambda_max.

    Returns
    -------
    LoadPathResult
    """
    if not (math.isfinite(step) and step > 0):
        raise ValueError(f"step must be a finite number > 0, got {step!r}")
    if not (atol >= 0 and rtol >= 0 and (atol > 0 or rtol > 0)):
        raise ValueError(f"tolerances must be >= 0 and not both 0, got atol={atol!r}, rtol={rtol!r}")
    if bracket not in ("direct", "bisection"):
        raise ValueError(f"bracket must be 'direct' or 'bisection', got {bracket!r}")
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

    def run(lam: float) -> TCEResult:
        r = solve_at(lam)
        steps.append(r)
        return r

    lo: float | None = None
    hi: float | None = None
    outcome = "no_limit"
    k = 0
    while k * step <= lam_cap:
        lam = k * step
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
        k += 1
    if outcome == "no_limit" and not steps[-1].ok:
        outcome = "numerical"  # the last steps up to lam_cap are undecided: not known to stand
    if outcome == "limit":
        assert lo is not None and hi is not None
        if bracket == "direct":
            lo, hi = _confirm_direct(run, lo, hi, analysis.limit(loads=pattern, mechanism=False).lambda_max, atol, rtol)
        lo_bracket = lo  # admissible end of the bracket; `lo` stays the last optimal step
        while hi - lo_bracket > max(atol, rtol * abs(hi)):
            mid = 0.5 * (lo_bracket + hi)
            if not lo_bracket < mid < hi:
                break  # the bracket is two neighbouring floats: no multiplier lies between them
            r = run(mid)
            direct = analysis.limit(loads=pattern, mechanism=False).lambda_max
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
            # the bracket closed on undecided steps: no optimal step lies within the
            # tolerance of the limit, so the last optimal one is not the answer
            outcome = "numerical"
    lam_max = lo if outcome == "limit" and lo is not None else float("nan")
    return LoadPathResult(
        status=outcome,
        message=f"{outcome} after {len(steps)} solves",
        alpha=pattern.direction,
        loads=pattern,
        settlements=sett,
        steps=steps,
        lambda_max=float(lam_max),
        lambda_upper=float(hi) if hi is not None else float("nan"),
        limit=analysis.limit(loads=pattern, mechanism=mechanism),
        n_solves=len(steps),
        solve_time=float(sum(s.solve_time for s in steps)),
        wall_time=time.perf_counter() - t0,
    )
