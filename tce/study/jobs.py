"""How many worker processes a run uses: in-process when the work is smaller than starting workers.

Starting workers costs about :data:`WORKER_START_S` CPU seconds (the fork server's imports,
the forks, the analyses rebuilt in the workers, the pickling), whatever the study.
:func:`choose_jobs` estimates the study's work from the first scenario's analysis (built in the
calling process, where an in-process run reuses it) and runs in-process unless the work saved
by ``k`` workers, ``work (1 - 1/k)``, exceeds their start-up. ``--jobs N`` (``jobs=N``) is
used as given.

All times are CPU seconds of this process (:func:`time.process_time`), so that the choice does
not depend on the load of a shared machine.

Estimate of the work, CPU seconds::

    sum over scenarios (increments + 2) * t_solve + settlement + scenarios * SCENARIO_S + (groups - 1) * t_build

with ``increments = lambda_max / step + 1`` from the direct limit of the scenario's direction
on the first scenario's analysis (``lam_cap / step + 1`` when there is none), ``t_solve`` a
warm TCE solve of the first scenario and ``t_build`` the time to build its analysis. A model of
more than :data:`LARGE_MODEL` unknowns is taken as large work without solving anything.
``settlement`` is the finite-settlement path of a study with ``[settlement_path]``: its
increments up to ``s_max`` (``s_max / increment`` per scenario, an upper bound: a path ends
at its collapse) times :data:`SETTLEMENT_INCREMENT_S`. A job of ``[uncertainty]`` counts
one solve per evaluation of the capacity (at most: :func:`tce.study.uncertainty.evaluations`),
or one settlement path per evaluation in a study with ``[settlement_path]`` whose scenario
moves a support.
"""

from __future__ import annotations

import logging
import math
import os
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from .uncertainty import UncertaintySection, evaluations

if TYPE_CHECKING:
    from ..core.analysis import Analysis
    from .schema import Scenario

__all__ = ["LARGE_MODEL", "SCENARIO_S", "SETTLEMENT_INCREMENT_S", "WORKER_START_S", "JobsChoice", "choose_jobs",
           "estimate_work", "settlement_increments"]

log = logging.getLogger(__name__)

#: CPU seconds to start the workers: the fork server's imports of tce's stack, the forks and the
#: analyses the workers build again.
WORKER_START_S = 1.5
#: CPU seconds to record and write one scenario's answer (its dataset and netCDF file).
SCENARIO_S = 0.02
#: CPU seconds of one increment of a settlement path (``[settlement_path]``, its linear programs
#: with ``lambda = true``; docs/performance.md).
SETTLEMENT_INCREMENT_S = 0.03
#: Unknowns above which a model is taken as large work without a timed solve.
LARGE_MODEL = 20_000
@dataclass(frozen=True)
class JobsChoice:
    """How many processes run the scenarios, and why.

    Attributes
    ----------
    jobs : int
        Worker processes (1: in the calling process).
    reason : str
        The decision in words (logged at info).
    work_s : float
        Estimated solver work of the study (s); NaN when not estimated.
    """

    jobs: int
    reason: str
    work_s: float = float("nan")


def settlement_increments(sc: Scenario) -> float:
    """Increments of the settlement path of ``sc`` up to its ``s_max`` (0 without ``[settlement_path]``
    or when ``sc`` moves no support: nothing to follow)."""
    opts = sc.settlement_path
    if opts is None or not any(any(u != 0 for u in v) for v in sc.settlements.values()):
        return 0.0
    return opts["s_max"] / opts["increment"]


def estimate_work(scenarios: Sequence[Scenario], analysis_of: Callable[[Scenario], Analysis]) -> tuple[float, str]:
    """Estimated solver work (CPU s) of ``scenarios`` and how it was reckoned (module docstring).

    Scenarios of other groups (other materials or structures) are reckoned as a path anchored
    on their limit, without building their analyses.
    """
    first = scenarios[0]
    t0 = time.process_time()
    an = analysis_of(first)
    model = an.model(an.model_kind(first.alpha, first.settlements))
    t_build = time.process_time() - t0
    if model.n_vars > LARGE_MODEL:
        return math.inf, f"a model of {model.n_vars} unknowns"
    an.solve(0.0, first.alpha, first.settlements)  # set-up
    t0 = time.process_time()
    for _ in range(3):  # CPU clocks tick coarsely on some systems: three solves, the mean
        an.solve(0.0, first.alpha, first.settlements)
    t_solve = (time.process_time() - t0) / 3
    an.reset_solvers()
    from ..analysis.loadpath import AUTO_INCREMENTS, MAX_INCREMENTS, increments_and_cap

    solves = 0.0
    sampled = 0.0
    for sc in scenarios:
        if sc.uncertainty is not None:  # a limit or a settlement path per evaluation of the capacity
            n = evaluations(UncertaintySection.model_validate_json(sc.uncertainty), sc.samples)
            solves += n
            sampled += n * settlement_increments(sc)
            continue
        if sc.group != first.group:  # another structure or material: as a path anchored on its limit
            solves += AUTO_INCREMENTS + 4
            continue
        lim = an.limit(loads=sc.loads_pattern, mechanism=False)
        step, cap, _ = increments_and_cap(lim, sc.loads["lambda_step"], sc.loads["lambda_cap"])
        lam = lim.lambda_max
        increments = min(lam, cap) / step + 1 if math.isfinite(lam) else min(cap / step, MAX_INCREMENTS) + 1
        solves += increments + 2
    groups = len({sc.group for sc in scenarios})
    increments = sampled + sum(settlement_increments(sc) for sc in scenarios if sc.uncertainty is None)
    work = (solves * t_solve + increments * SETTLEMENT_INCREMENT_S + len(scenarios) * SCENARIO_S
            + (groups - 1) * t_build)
    path = f", {increments:.0f} settlement increments of {SETTLEMENT_INCREMENT_S:.2g} s" if increments else ""
    return work, (f"about {solves:.0f} solves of {t_solve * 1e3:.2g} ms{path}, {len(scenarios)} answers of "
                  f"{SCENARIO_S:.2g} s and {groups} model(s) of {t_build:.2g} s, CPU")


def choose_jobs(
    scenarios: Sequence[Scenario],
    jobs: int | None,
    analysis_of: Callable[[Scenario], Analysis],
    backend: str = "processes",
    cpus: int | None = None,
) -> JobsChoice:
    """How many processes should solve ``scenarios`` (module docstring).

    Parameters
    ----------
    scenarios : sequence of Scenario
        The scenarios still to solve.
    jobs : int or None
        Workers asked for (``--jobs``): used as given. None: decide.
    analysis_of : callable
        ``scenario -> Analysis``, the runner's cached builder.
    backend : str
        ``"dask"`` runs on a cluster: all ``cpus`` workers, no estimate.
    cpus : int, optional
        Cores available (default ``os.cpu_count()``).
    """
    cpus = cpus or os.cpu_count() or 1
    if jobs is not None:
        return JobsChoice(jobs, f"{jobs} worker(s), as asked (--jobs {jobs})")
    if backend == "dask":
        return JobsChoice(cpus, f"{cpus} Dask worker(s), one per core")
    k = min(cpus, len(scenarios))
    if k <= 1:
        why = "one core" if cpus <= 1 else "one scenario to solve"
        return JobsChoice(1, f"in-process: {why}")
    work, how = estimate_work(scenarios, analysis_of)
    threshold = WORKER_START_S * k / (k - 1)  # parallel wins when work (1 - 1/k) > start-up
    if work > threshold:
        return JobsChoice(k, f"{k} workers: the study's work ({how}; {work:.3g} s) exceeds "
                             f"{threshold:.3g} s, what starting {k} workers would cost (CPU)", work)
    return JobsChoice(1, f"in-process: the study's work ({how}; {work:.3g} s) is below "
                         f"{threshold:.3g} s, what starting {k} workers would cost (CPU)", work)
