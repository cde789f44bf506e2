"""Run a study: solve its missing scenarios in parallel, keep each as it finishes, merge.

:func:`run_study` expands a :class:`tce.study.Study` into scenarios, skips those already
written under ``<out>/<study name>/scenarios/`` that can be trusted
(:func:`tce.study.results.load_finished`), and solves the rest: in this process with
``jobs=1``, in a :class:`concurrent.futures.ProcessPoolExecutor` of ``jobs`` worker processes
with ``jobs > 1`` (``backend="processes"``, the default; see :func:`_context`), or on a Dask
distributed cluster through joblib's ``dask`` backend. Each worker keeps the
:class:`tce.analysis.Analysis` of the structures and materials it has met; the structures are
built once per run and sent to each worker once, when it starts. The answer of a scenario does
not depend on where or in which order it runs.

Faults (``docs/studies.md``, "Faults and resuming"):

- Each scenario is written, atomically, by the process that solved it, before the
  parent is told it is done; what is finished is on disk whatever happens next.
- A worker that dies (e.g. by the out-of-memory killer) breaks the pool
  (:class:`concurrent.futures.process.BrokenProcessPool`), failing every scenario in it
  without saying which one killed it. The pool holds at most ``jobs + 1`` scenarios (one
  queued), the suspects: the others go on in a new pool and each suspect is solved again
  alone. A suspect that breaks the pool alone is reported and not retried; a worker death
  that every suspect survives is a warning. A results folder that cannot be written, or a fork
  server that ends while it starts a worker, stops the dispatch (the running scenarios finish).
  A lost or failed scenario ends the run with :class:`RunFault` (exit code 3 in the CLI)
  after every other scenario is kept; ``results.nc`` is not replaced, and a rerun solves
  only what is missing.
- Workers start with Ctrl-C ignored (:mod:`tce.signals`; forked from a fork server that
  started so), while this process heeds Ctrl-C throughout, the seconds the fork server takes
  to import tce included. Each worker holds the read end of a pipe whose only write end is
  the parent's: when the parent closes it (Ctrl-C, SIGTERM) or ends (``kill -9``), each
  worker ends at once, after the scenario file it may be writing. The parent then removes
  the temporary files and re-raises.
- One run at a time per study folder (:func:`tce.study.results.folder_lock`), created and
  locked before anything is solved: an unwritable destination raises :class:`RunError` first.
"""

from __future__ import annotations

import contextlib
import logging
import multiprocessing as mp
from multiprocessing import forkserver
import os
import shutil
import threading
import time
import traceback
from collections import deque
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import FIRST_COMPLETED, BrokenExecutor, Future, ProcessPoolExecutor, wait
from multiprocessing.connection import Connection
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Literal

import xarray as xr

from ..analysis.loadpath import DEFAULT_RTOL, LoadPathResult, load_path
from ..analysis.nonassoc import nonassociative_limit
from ..core.analysis import Analysis
from ..structures.assembly import Assembly
from ..analysis.assessment import adequacy_factor
from ..files import MIN_FREE, StorageError, storage_error
from . import keys
from .jobs import choose_jobs
from .names import missing_lambdas
from .positions import search, with_adequacy, with_critical
from .results import (
    FolderLocked,
    folder_lock,
    load_finished,
    merge_scenarios,
    remove_temporaries,
    scenario_dataset,
    write_atomic,
    write_scenario,
)
from .samples import solve_job
from .schema import Scenario, Study, build_material
from ..signals import deferred, quiet_children
from .settlement import settlement_vars

__all__ = [
    "FigureFault",
    "RunError",
    "RunFault",
    "RunReport",
    "run_study",
    "solve_scenario",
    "with_drawn_states",
]

log = logging.getLogger(__name__)

Backend = Literal["processes", "dask"]
#: called after each finished scenario with (scenarios done, scenarios to solve, load steps done)
Progress = Callable[[int, int, int], None]
#: draws a results dataset: (dataset, study folder, processes) -> files written
Draw = Callable[[xr.Dataset, Path, int], Sequence[Path]]
#: outcomes of a load path, in the order the run summary lists them
OUTCOMES = ("limit", "capped", "no_limit", "unbounded", "infeasible", "numerical")


class RunError(RuntimeError):
    """A run that cannot start: an unreachable Dask scheduler, an unwritable or locked
    results folder (exit code 2 in the CLI; nothing was solved)."""


class RunFault(RuntimeError):
    """A run that ended with a fault (a worker died, a file could not be written, a
    scenario failed): every finished scenario is kept, ``results.nc`` is not replaced.

    Attributes
    ----------
    report : RunReport
        What the run did before and after the fault (``report.faults`` lists them).
    """

    def __init__(self, report: RunReport) -> None:
        super().__init__("\n".join(report.faults))
        self.report = report


class FigureFault(RunFault):
    """``results.nc`` was written, but its figures could not be (a full or unwritable disk;
    exit code 3 in the CLI): ``tce plot`` draws them again."""


@dataclass
class RunReport:
    """What :func:`run_study` did.

    Attributes
    ----------
    results : Path
        The study's ``results.nc`` (written only when every scenario is solved).
    solved, reused : list of str
        Jobs (scenarios and jobs of samples, :meth:`tce.study.Study.jobs`) solved by this run,
        and those taken from an earlier run.
    outcomes : dict
        ``{scenario: outcome}`` of every finished scenario, in the study's order.
    faults : list of str
        One line per fault (empty for a run that went through).
    figures : list of Path
        Figures written beside the results.
    """

    results: Path
    solved: list[str] = field(default_factory=list)
    reused: list[str] = field(default_factory=list)
    outcomes: dict[str, str] = field(default_factory=dict)
    faults: list[str] = field(default_factory=list)
    figures: list[Path] = field(default_factory=list)


# ----------------------------------------------------------------------------- worker side
_ANALYSES: dict[str, Analysis] = {}
_KEEP = 8  # analyses a worker keeps (most recently used)


def _analysis(sc: Scenario, assembly: Assembly) -> Analysis:
    """The analysis of a scenario group (built once per process, then reused)."""
    analysis = _ANALYSES.pop(sc.group, None)
    if analysis is None:
        log.debug("building the analysis of %s", sc.group)
        analysis = Analysis(assembly, build_material(sc.material))
    _ANALYSES[sc.group] = analysis
    while len(_ANALYSES) > _KEEP:
        _ANALYSES.pop(next(iter(_ANALYSES)))
    return analysis


def _cold(analysis: Analysis) -> Analysis:
    """``analysis`` with its warm TCE solvers dropped (its model operators are kept).

    A warm solver keeps the scaling of the first problem it met, so its answers would depend,
    in the last digits, on the scenarios the process solved before; a cold start makes every
    answer independent of the backend, the number of jobs and resuming.
    """
    analysis.reset_solvers()
    return analysis


def solve_scenario(sc: Scenario, assembly: Assembly) -> xr.Dataset:
    """Run the load path of one scenario on its built ``assembly``; return its dataset (for a
    job of ``[uncertainty]``, :attr:`Scenario.uncertainty`, its answer: :func:`tce.study.samples.solve_job`).

    The multipliers the study's figures draw (:attr:`Scenario.draw`) that the load path did
    not reach are solved after it and stored as steps like the others
    (:func:`with_drawn_states`).
    """
    if sc.uncertainty is not None:
        return solve_job(sc, assembly)
    analysis = _cold(_analysis(sc, assembly))
    tol = sc.loads["tolerance"]
    pattern, crit = sc.loads_pattern, None
    if sc.loads.get("critical_position"):
        crit = search(sc, analysis, pattern)
        if crit.ok:
            log.debug("scenario %r: critical position %s", sc.name, crit.message)
            pattern = crit.pattern
        else:
            log.warning("scenario %r: no critical position (%s): %s; the load path runs at the declared position",
                        sc.name, crit.status, crit.message)
    lp = load_path(
        analysis,
        settlements=sc.settlements,
        step=sc.loads["lambda_step"],
        # no tolerance given: relative to the limit, so the adequacy factor of a live load
        # does not depend on its size
        atol=0.0 if tol is None else tol,
        rtol=DEFAULT_RTOL if tol is None else 0.0,
        lam_cap=sc.loads["lambda_cap"],
        loads=pattern,
        bracket=keys.BRACKET,
    )
    log.debug("scenario %r: %s, lambda_max = %s", sc.name, lp.outcome, lp.lambda_max)
    bracket = None
    if analysis.material.flow == "non-associative":
        bracket = nonassociative_limit(analysis, loads=pattern)
    settlement = settlement_vars(sc, assembly, analysis.material) if sc.settlement_path is not None else None
    ds = scenario_dataset(
        sc, with_drawn_states(analysis, lp, sc.draw), analysis, nonassoc=bracket, settlement=settlement
    )
    if "dead_factor" in sc.loads:
        factors = sc.loads["dead_factor"], sc.loads["live_factor"]
        ds = with_adequacy(ds, adequacy_factor(analysis, pattern, *factors), pattern, *factors)
    return ds if crit is None else with_critical(ds, crit)


def with_drawn_states(analysis: Analysis, lp: LoadPathResult, lams: Sequence[float]) -> LoadPathResult:
    """``lp`` with the multipliers ``lams`` solved and added to its steps (when missing).

    See :func:`missing_lambdas`. Nothing is solved when the path has no optimal step. The
    counts and times of the result include the added solves.
    """
    if not any(r.ok for r in lp.steps):
        return lp
    todo = missing_lambdas([r.lam for r in lp.steps], lams, lp.lambda_upper)
    if not todo:
        return lp
    t0 = time.perf_counter()
    solve = analysis.path(settlements=lp.settlements, loads=lp.loads)
    extra = [solve(lam) for lam in todo]
    log.debug("solved the drawn states %s", todo)
    return replace(
        lp,
        steps=lp.steps + extra,
        n_solves=lp.n_solves + len(extra),
        solve_time=lp.solve_time + sum(r.solve_time for r in extra),
        wall_time=lp.wall_time + time.perf_counter() - t0,
    )


#: held by a process while it writes a scenario file: a worker told to end finishes the file first
_WRITING = threading.Lock()


def _solve_and_write(sc: Scenario, assembly: Assembly, directory: Path) -> xr.Dataset:
    """Solve ``sc`` and write its file; return its dataset (what the file holds), which the
    run merges without reading the file back."""
    ds = solve_scenario(sc, assembly)
    with _WRITING:
        write_scenario(ds, directory, sc)
    return ds


#: a pool worker's structures of the run: assembly digest -> assembly (set when it starts)
_ASSEMBLIES: dict[str, Assembly] = {}


def _start_worker(stop: Connection, level: int, assemblies: dict[str, Assembly]) -> None:
    """Initializer of a pool worker: the ``tce`` log level of the parent, the run's structures
    (sent once per worker, not with each scenario), and a thread that ends the process when
    ``stop`` reads end-of-file (module docstring)."""
    logging.getLogger("tce").setLevel(level)
    _ASSEMBLIES.update(assemblies)
    threading.Thread(target=_end_on_close, args=(stop,), daemon=True).start()


def _solve_in_worker(sc: Scenario, directory: Path) -> xr.Dataset:
    """A pool worker's task: :func:`_solve_and_write` on the scenario's structure."""
    return _solve_and_write(sc, _ASSEMBLIES[sc.assembly_digest], directory)


def _end_on_close(stop: Connection) -> None:
    """Wait until the parent closes its end of ``stop`` or ends, then end this process (after
    the scenario file it may be writing)."""
    with contextlib.suppress(EOFError, OSError):
        stop.recv_bytes()  # the parent never writes: this returns only by raising
    with _WRITING:
        os._exit(1)


# ----------------------------------------------------------------------------- caller side
@contextlib.contextmanager
def _dask(scheduler: str | None, jobs: int) -> Iterator[None]:
    """joblib's ``dask`` backend on the cluster at ``scheduler`` (or a local one of ``jobs`` workers)."""
    import joblib  # here: only the Dask backend needs it

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
        yield


def _grouped(scenarios: list[Scenario]) -> list[Scenario]:
    """Scenarios ordered so that those sharing an analysis are dispatched together."""
    first = {}
    for k, sc in enumerate(scenarios):
        first.setdefault(sc.group, k)
    return sorted(scenarios, key=lambda sc: first[sc.group])


class _Tally:
    """Outcomes, faults and progress of one dispatch."""

    def __init__(self, total: int, progress: Progress | None) -> None:
        self.total, self.progress = total, progress
        self.outcomes: dict[str, str] = {}
        #: the datasets of the scenarios solved and written (merged without reading them back)
        self.datasets: dict[str, xr.Dataset] = {}
        self.faults: list[str] = []
        self.steps = 0

    def done(self, name: str, ds: xr.Dataset) -> None:
        """Job ``name`` is solved and its file written; ``ds`` is its dataset."""
        if "outcome" in ds:  # a scenario's load path (not a job of samples)
            self.outcomes[name] = str(ds["outcome"].values[0])
        self.datasets[name] = ds
        self.steps += int(ds["n_solves"].values[0]) if "n_solves" in ds else ds.sizes.get("sample", 0)
        if self.progress is not None:
            self.progress(len(self.datasets), self.total, self.steps)

    def fault(self, line: str, details: str = "") -> None:
        log.debug("fault: %s\n%s", line, details)
        self.faults.append(line)


def _failed(sc: Scenario, exc: BaseException) -> str:
    return f"scenario {sc.name!r} failed: {type(exc).__name__}: {exc} (run with -v for the traceback)"


def _in_process(todo: list[Scenario], study: Study, directory: Path, tally: _Tally) -> None:
    """Solve ``todo`` one after the other in this process."""
    for sc in todo:
        try:
            ds = _solve_and_write(sc, study.assembly(sc.structure), directory)
        except StorageError as exc:
            tally.fault(str(exc))
            return  # the destination takes no more: stop
        except Exception as exc:  # noqa: BLE001 - reported as a fault, the others go on
            tally.fault(_failed(sc, exc), traceback.format_exc())
            continue
        tally.done(sc.name, ds)


def _lost(sc: Scenario) -> str:
    """One line on a scenario whose worker died when it ran alone."""
    return (f"scenario {sc.name!r} is not saved: its worker process ended abruptly, twice, the second time "
            "alone (killed, as the out-of-memory killer does, or crashed); the other scenarios went on")


def _context() -> mp.context.BaseContext:
    """How worker processes start: forked from a fork server that has imported tce once
    (``forkserver`` with :mod:`tce.study.runner` preloaded), where the platform has one;
    spawned elsewhere.

    The fork server is started by the first pool of the process and kept for later runs; it
    ignores Ctrl-C and ends with the process. ``dask.array`` is preloaded too, since xarray
    imports it (where installed) for its first Dataset; where it is not installed, the fork
    server ignores the ImportError."""
    if "forkserver" not in mp.get_all_start_methods():
        return mp.get_context("spawn")
    ctx = mp.get_context("forkserver")
    ctx.set_forkserver_preload([__name__, "dask.array"])
    return ctx


def _in_pool(todo: list[Scenario], study: Study, directory: Path, jobs: int, tally: _Tally) -> None:
    """Solve ``todo`` in ``jobs`` worker processes (see the module docstring for faults)."""
    ctx = _context()
    starting = quiet_children  # a spawned worker starts with Ctrl-C ignored (the start is short)
    if ctx.get_start_method() == "forkserver":  # its workers inherit the fork server's ignored Ctrl-C, and
        with quiet_children():  # this process heeds a Ctrl-C while the server imports tce (seconds)
            forkserver.ensure_running()
        starting = deferred  # a Ctrl-C inside a submit is raised after it (the pool stays whole)
    stop, keep = ctx.Pipe(duplex=False)  # workers hold ``stop``; closing ``keep`` ends them
    waiting = deque(todo)
    again: deque[Scenario] = deque()  # running when a worker died: each is solved again alone
    retried: set[str] = set()
    running: dict[Future, Scenario] = {}
    level = logging.getLogger("tce").getEffectiveLevel()
    assemblies = {sc.assembly_digest: study.assembly(sc.structure) for sc in todo}
    pool: ProcessPoolExecutor | None = None
    stopping = False
    try:
        while running or (waiting or again) and not stopping:
            if pool is None:
                pool = ProcessPoolExecutor(jobs, mp_context=ctx, initializer=_start_worker,
                                           initargs=(stop, level, assemblies))
            broken = False
            # a scenario solved again runs alone; the others fill the pool
            while not stopping and not any(sc.name in retried for sc in running.values()):
                if again and not running:
                    sc = again.popleft()
                elif waiting and not again and len(running) <= jobs:  # one queued: a worker that ends finds its next
                    sc = waiting.popleft()
                else:
                    break
                try:
                    with starting():  # workers start with Ctrl-C ignored; here a Ctrl-C waits for the submit
                        running[pool.submit(_solve_in_worker, sc, directory)] = sc
                except BrokenExecutor:  # a worker died between scenarios
                    (again if sc.name in retried else waiting).appendleft(sc)
                    broken = True
                    break
                except (EOFError, OSError) as exc:  # the fork server ended while it started a worker
                    tally.fault(f"worker processes cannot start: the fork server ended ({type(exc).__name__}: {exc}); "
                                "the scenarios already running finish")
                    stopping = True
            done = wait(running, return_when=FIRST_COMPLETED).done if running else set()
            if broken or any(isinstance(f.exception(), BrokenExecutor) for f in done):
                done = wait(running).done  # the broken pool fails every scenario it holds
                pool.shutdown()
                pool = None
            suspects = []
            for future in done:
                sc = running.pop(future)
                exc = future.exception()
                if exc is None:
                    tally.done(sc.name, future.result())
                elif isinstance(exc, StorageError):
                    tally.fault(str(exc))
                    stopping = True  # the destination takes no more: the running ones finish
                elif not isinstance(exc, BrokenExecutor):
                    tally.fault(_failed(sc, exc), "".join(traceback.format_exception(exc)))
                elif sc.name in retried:
                    tally.fault(_lost(sc))
                else:
                    suspects.append(sc)
            if suspects:
                log.warning("a worker process ended abruptly while %s ran: solved again, each alone",
                            ", ".join(repr(sc.name) for sc in suspects))
                retried.update(sc.name for sc in suspects)
                again.extend(suspects)
        if pool is not None:
            pool.shutdown()  # the workers end on the pool's own request
    finally:
        keep.close()  # workers still running a scenario end now
        if pool is not None:
            pool.shutdown(cancel_futures=True)
        stop.close()
        remove_temporaries(directory)  # of the workers ended mid-write (this run holds the folder)


def _on_dask(todo: list[Scenario], study: Study, directory: Path, scheduler: str | None, jobs: int, tally: _Tally) -> None:
    """Solve ``todo`` on a Dask cluster; this process writes each answer as it arrives
    (the workers of a remote cluster may not see ``directory``)."""
    import joblib

    by_name = {sc.name: sc for sc in todo}
    with _dask(scheduler, jobs):
        tasks = (joblib.delayed(solve_scenario)(sc, study.assembly(sc.structure)) for sc in _grouped(todo))
        try:
            for ds in joblib.Parallel(n_jobs=-1, return_as="generator_unordered")(tasks):
                sc = by_name[ds.attrs.get("job", str(ds["scenario"].values[0]))]
                try:
                    write_scenario(ds, directory, sc)
                except StorageError as exc:
                    tally.fault(str(exc))
                    return
                tally.done(sc.name, ds)
        except Exception as exc:  # noqa: BLE001 - a lost worker or a failed task, reported as a fault
            tally.fault(f"the Dask run failed: {type(exc).__name__}: {exc}", traceback.format_exc())


def _study_folder(out: Path | str, name: str) -> Path:
    """``out/name``, checked to resolve to a folder directly inside ``out``."""
    root = Path(out).resolve()
    directory = (root / name).resolve()
    if directory.parent != root:
        raise RunError(
            f"{Path(out) / name}: resolves to {directory}, outside {root}; fix: give the study a plain name "
            "or remove the link"
        )
    return directory


def _lock(stack: contextlib.ExitStack, directory: Path) -> None:
    """Create the study folder and take its lock (in ``stack``), or raise :class:`RunError`."""
    folder = directory / "scenarios"
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise RunError(str(storage_error(folder, exc))) from None
    if folder.is_symlink():  # tce writes only into the folder it made
        raise RunError(f"{folder}: a link, not a folder; fix: remove the link, then run the same command again")
    try:
        stack.enter_context(folder_lock(directory))
    except (FolderLocked, StorageError) as exc:
        raise RunError(str(exc)) from None
    free = shutil.disk_usage(directory).free
    if free < MIN_FREE:
        raise RunError(
            f"cannot write {directory}: {free} bytes free, less than {MIN_FREE}; fix: free some space, "
            "then run the same command again"
        )



def run_study(
    study: Study,
    out: Path | str = "results",
    jobs: int | None = None,
    backend: Backend = "processes",
    scheduler: str | None = None,
    progress: Progress | None = None,
    plots: Draw | None = None,
    fresh: bool = False,
) -> RunReport:
    """Solve every scenario of ``study`` not solved yet and write ``results.nc`` (and, given
    ``plots``, its figures).

    Parameters
    ----------
    study : Study
        A validated study (:func:`tce.study.load_study`).
    out : path
        Results root: the study writes into ``out/<study name>/``.
    jobs : int, optional
        Parallel workers; 1 solves in this process. Default: in-process when the study's
        estimated work is below what starting workers costs, all cores otherwise
        (:func:`tce.study.jobs.choose_jobs`, its reason logged at info). With
        ``backend="dask"`` and no ``scheduler``, the size of the local cluster started
        (default: all cores).
    backend : {"processes", "dask"}
        ``processes``: worker processes on this machine; ``dask``: a Dask distributed cluster.
    scheduler : str, optional
        Address of a running Dask scheduler (``tcp://host:port``).
    progress : callable, optional
        ``progress(done, total, steps)`` before the first scenario (``done = 0``) and after
        each scenario solved.
    plots : callable, optional
        ``plots(ds, folder, jobs) -> list of Path``: draws the results dataset into the
        study's folder (still under its lock) with up to ``jobs`` processes, once ``results.nc``
        is written; the files it returns are :attr:`RunReport.figures`. The command line passes
        :func:`tce.plot.write_figures`; default: no figures.
    fresh : bool
        Delete the scenario files of earlier runs first (under the folder's lock).

    Returns
    -------
    RunReport

    Raises
    ------
    RunError
        The run cannot start (backend, unwritable, full or locked folder); nothing solved.
    RunFault
        The run ended with a fault; every finished scenario is on disk, ``results.nc``
        was not replaced.
    FigureFault
        ``results.nc`` was written but a figure could not be (a :class:`RunFault`).
    KeyboardInterrupt
        Ctrl-C; every finished scenario is on disk.
    """
    if jobs is not None and jobs < 1:
        raise RunError(f"jobs must be >= 1, got {jobs}")
    if backend not in ("processes", "dask"):
        raise RunError(f"unknown backend {backend!r}: use 'processes' or 'dask'")
    directory = _study_folder(out, study.name)
    folder = directory / "scenarios"
    scenarios, jobs_all = study.scenarios(), study.jobs()
    with contextlib.ExitStack() as stack:
        _lock(stack, directory)
        for d in (directory, folder):
            remove_temporaries(d)  # left by a run that was killed mid-write
        if fresh:
            for old in folder.glob("*.nc"):
                old.unlink()
        parts = load_finished(folder, jobs_all)
        todo = [sc for sc in jobs_all if sc.name not in parts]
        how = ""
        if todo:
            choice = choose_jobs(_grouped(todo), jobs, lambda sc: _analysis(sc, study.assembly(sc.structure)), backend)
            jobs, how = choice.jobs, f"; {choice.reason}"
        jobs = jobs or 1
        if parts:
            log.info(
                "resuming %s: %d of %d scenarios already solved, solving the %d missing%s",
                study.name, len(parts), len(jobs_all), len(todo), how,
            )
        else:
            log.info("running %s: %d scenarios%s", study.name, len(todo), how)
        report = RunReport(directory / "results.nc", reused=list(parts))
        if todo:
            tally = _Tally(len(todo), progress)
            if progress is not None:
                progress(0, len(todo), 0)  # the bar shows (and ticks) from the start
            if backend == "dask":
                _on_dask(todo, study, folder, scheduler, jobs, tally)
            elif jobs == 1:
                _in_process(todo, study, folder, tally)
            else:
                _in_pool(_grouped(todo), study, folder, jobs, tally)
            report.solved = [sc.name for sc in todo if sc.name in tally.datasets]
            report.faults = tally.faults
            # each was written atomically before it counted as done: merged from memory
            parts.update(tally.datasets)
        report.outcomes = {sc.name: str(parts[sc.name]["outcome"].values[0]) for sc in scenarios if sc.name in parts}
        if report.faults:
            raise RunFault(report)
        ds = merge_scenarios(study, parts)
        try:
            write_atomic(ds, report.results)
        except StorageError as exc:
            report.faults.append(str(exc))
            raise RunFault(report) from None
        log.info("wrote %s", report.results)
        if plots:
            try:
                report.figures = list(plots(ds, directory, jobs))
            except OSError as exc:  # a full or unwritable disk: results.nc is written
                report.faults.append(str(storage_error(Path(exc.filename or directory), exc)))
                raise FigureFault(report) from None
    return report
