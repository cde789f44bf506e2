"""Run a study: solve its missing scenarios in parallel, keep each as it finishes, merge, plot.

:func:`run_study` expands a :class:`tce.study.Study` into scenarios, skips those already
written under ``<out>/<study name>/scenarios/`` with an unchanged definition, and solves
the rest with :class:`joblib.Parallel` (``loky`` processes on this machine, or a Dask
distributed cluster through joblib's ``dask`` backend). Each worker process keeps the
:class:`tce.analysis.Analysis` of every structure and material it has met (a small
cache), so the operators and solvers are built once and reused for all the load steps
and scenarios that share them; the scenarios are dispatched grouped by analysis. The
answer of a scenario does not depend on where or in which order it runs.

Each finished scenario is written at once by the calling process (atomically), so an
interruption loses nothing finished. When all are done, ``results.nc`` is written
(atomically) beside them, then the figures (:mod:`tce.plot`).
"""

from __future__ import annotations

import contextlib
import json
import logging
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
from typing import Literal

import joblib
import xarray as xr

from ..core.analysis import Analysis
from ..analysis.loadpath import load_path
from .jobs import choose_jobs
from .results import load_finished, merge_scenarios, scenario_dataset, scenario_path, write_atomic
from .schema import Scenario, Study, build_material, build_structure

__all__ = ["RunError", "RunReport", "run_study", "solve_scenario", "write_plots"]

log = logging.getLogger(__name__)

Backend = Literal["loky", "dask"]
#: called after each finished scenario with (scenarios done, scenarios to solve, load steps done)
Progress = Callable[[int, int, int], None]


class RunError(RuntimeError):
    """A run that cannot start (for example an unreachable Dask scheduler)."""


@dataclass
class RunReport:
    """What :func:`run_study` did.

    Attributes
    ----------
    results : Path
        The study's ``results.nc``.
    solved, reused : list of str
        Scenarios solved by this run, and scenarios taken from an earlier run.
    figures : list of Path
        Figures written beside the results.
    """

    results: Path
    solved: list[str] = field(default_factory=list)
    reused: list[str] = field(default_factory=list)
    figures: list[Path] = field(default_factory=list)


# ----------------------------------------------------------------------------- worker side
@lru_cache(maxsize=8)
def _analysis(group: str) -> Analysis:
    """The analysis of a scenario group (built once per worker process, then reused)."""
    structure, material = json.loads(group)
    log.debug("building the analysis of %s", group)
    return Analysis(build_structure(structure), build_material(material))


def _cold(analysis: Analysis) -> Analysis:
    """``analysis`` with its warm TCE solvers dropped (its model operators are kept).

    A warm solver keeps the scaling of the first problem it met, so its answers depend, in
    the last digits, on the scenarios the process solved before. Starting each scenario
    cold makes every answer independent of the backend, the number of jobs and resuming.
    Building a solver costs about a millisecond; the operators are the expensive part.
    """
    analysis.reset_solvers()
    return analysis


def solve_scenario(sc: Scenario) -> xr.Dataset:
    """Run the load path of one scenario and return its one-scenario dataset."""
    analysis = _cold(_analysis(sc.group))
    lp = load_path(
        analysis,
        alpha=sc.alpha,
        settlements=sc.settlements,
        step=sc.loads["lambda_step"],
        atol=sc.loads["tolerance"],
        lam_cap=sc.loads["lambda_cap"],
    )
    log.debug("scenario %r: %s, lambda_max = %s", sc.name, lp.outcome, lp.lambda_max)
    return scenario_dataset(sc, lp, analysis)


# ----------------------------------------------------------------------------- caller side
@contextlib.contextmanager
def _backend(backend: Backend, scheduler: str | None, jobs: int) -> Iterator[int]:
    """Configure joblib for ``backend``; yield the ``n_jobs`` to give :class:`joblib.Parallel`."""
    if backend == "loky":
        yield jobs
        return
    if backend != "dask":
        raise RunError(f"unknown backend {backend!r}: use 'loky' or 'dask'")
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        raise RunError("the dask backend needs dask[distributed]: pip install 'tce[dask]'") from None
    with contextlib.ExitStack() as stack:
        try:
            if scheduler:
                client = stack.enter_context(Client(scheduler, timeout="10s"))
            else:
                cluster = stack.enter_context(
                    LocalCluster(n_workers=jobs, threads_per_worker=1, host="127.0.0.1", dashboard_address=None)
                )
                client = stack.enter_context(Client(cluster))
        except (OSError, TimeoutError, ValueError) as exc:
            raise RunError(f"cannot reach the Dask scheduler {scheduler!r}: {exc}") from None
        log.info("running on the Dask cluster %s", client.scheduler.address)
        stack.enter_context(joblib.parallel_config(backend="dask"))
        yield -1


def _grouped(scenarios: list[Scenario]) -> list[Scenario]:
    """Scenarios ordered so that those sharing an analysis are dispatched together."""
    first = {}
    for k, sc in enumerate(scenarios):
        first.setdefault(sc.group, k)
    return sorted(scenarios, key=lambda sc: first[sc.group])


def write_plots(ds: xr.Dataset, outdir: Path) -> list[Path]:
    """Figures of a results dataset (:func:`tce.plot.write_figures`), imported only when drawn."""
    from .. import plot

    return list(plot.write_figures(ds, Path(outdir)))


def _solve_missing(
    todo: list[Scenario], directory: Path, jobs: int, backend: Backend, scheduler: str | None, progress: Progress | None
) -> dict[str, xr.Dataset]:
    """Solve ``todo``, writing each scenario file as soon as its answer arrives."""
    done: dict[str, xr.Dataset] = {}
    by_name = {sc.name: sc for sc in todo}
    steps = 0
    with _backend(backend, scheduler, jobs) as n_jobs:
        parallel = joblib.Parallel(n_jobs=n_jobs, return_as="generator_unordered")
        for ds in parallel(joblib.delayed(solve_scenario)(sc) for sc in _grouped(todo)):
            name = str(ds["scenario"].values[0])
            write_atomic(ds, scenario_path(directory, by_name[name]))
            done[name] = ds
            steps += int(ds["n_solves"].values[0])
            if progress is not None:
                progress(len(done), len(todo), steps)
    return done


def run_study(
    study: Study,
    out: Path | str = "results",
    jobs: int | None = None,
    backend: Backend = "loky",
    scheduler: str | None = None,
    progress: Progress | None = None,
    plots: bool = True,
) -> RunReport:
    """Solve every scenario of ``study`` not solved yet and write ``results.nc`` (and figures).

    Parameters
    ----------
    study : Study
        A validated study (:func:`tce.study.load_study`).
    out : path
        Results root: the study writes into ``out/<study name>/``.
    jobs : int, optional
        Parallel workers. Default: in-process when the study's estimated work is below
        what starting workers costs, all cores otherwise (:func:`tce.study.jobs.choose_jobs`,
        its reason logged at info). With ``backend="dask"`` and no ``scheduler``, the size
        of the local cluster started for the run (default: all cores).
    backend : {"loky", "dask"}
    scheduler : str, optional
        Address of a running Dask scheduler (``tcp://host:port``).
    progress : callable, optional
        ``progress(done, total, steps)`` before the first scenario (``done = 0``) and after
        each scenario solved.
    plots : bool
        Write the figures after the results.

    Returns
    -------
    RunReport

    Raises
    ------
    RunError
        The backend cannot start.
    """
    if jobs is not None and jobs < 1:
        raise RunError(f"jobs must be >= 1, got {jobs}")
    directory = Path(out) / study.name
    scenarios = study.scenarios()
    parts = load_finished(directory / "scenarios", scenarios)
    todo = [sc for sc in scenarios if sc.name not in parts]
    if todo:
        choice = choose_jobs(_grouped(todo), jobs, _analysis, backend)
        log.info("%s", choice.reason)
        jobs = choice.jobs
    jobs = jobs or 1
    if parts:
        log.info(
            "resuming %s: %d of %d scenarios already solved, solving the %d missing",
            study.name, len(parts), len(scenarios), len(todo),
        )
    else:
        where = "in-process" if jobs == 1 and backend == "loky" else f"on {jobs} {backend} worker(s)"
        log.info("running %s: %d scenarios %s", study.name, len(todo), where)
    report = RunReport(directory / "results.nc", reused=list(parts))
    if todo:
        if progress is not None:
            progress(0, len(todo), 0)  # the bar shows (and ticks) from the start
        solved = _solve_missing(todo, directory / "scenarios", jobs, backend, scheduler, progress)
        parts.update(solved)
        report.solved = [sc.name for sc in todo]
    ds = merge_scenarios(study, parts)
    write_atomic(ds, report.results)
    log.info("wrote %s", report.results)
    if plots:
        report.figures = write_plots(ds, directory)
    return report
