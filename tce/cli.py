"""The ``tce`` command line: run studies, summarise and plot their results.

Commands: ``run`` (a study: ``<out>/<study>/results.nc``, its figures and report; resumes),
``show``, ``plot``, ``view``, ``report`` and ``export`` (of a results file), ``check`` and
``bench``.

Exit codes (``tce run``): 0 success; 2 bad input or a run that cannot start (a bad study,
an unwritable, full or locked results folder: one message on stderr, no traceback,
nothing solved); 3 a run that ended with a fault (a worker killed, a disk full, a
scenario that failed: one line each, every finished scenario kept, a rerun resumes); 4
with ``--strict``, a run whose scenarios did not all end at a limit; 130 interrupted
(Ctrl-C; finished scenarios are kept), 143 for SIGTERM and 129 for SIGHUP (:mod:`tce.signals`).

Every command: 2 for bad input (a missing, foreign or damaged results file, an ``--out``
that cannot be written: nothing written); 3 for a storage fault while it writes (one line
naming the path); an interrupted command prints one line, no traceback; a closed output
pipe (``tce show | head``) ends it quietly.
"""

from __future__ import annotations

import argparse
import contextlib
import logging
import math
import os
import sys
from collections import Counter
from collections.abc import Iterator, Sequence
from pathlib import Path

from . import __version__
from .signals import exit_code, handle_signals, restore_signals
from .study.guards import check_path
from .study.names import PLOT_KINDS

__all__ = ["main"]

log = logging.getLogger("tce")


class UsageError(Exception):
    """Bad input from the user: reported in one message, exit code 2."""


class WriteFault(Exception):
    """A storage fault while a command writes (a full disk): one message, exit code 3."""


def _jobs(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a whole number >= 1, got {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be a whole number >= 1, got {text!r}")
    return value


def _target(text: str) -> float | str:
    """A ``--step``: a load multiplier >= 0 or ``max``."""
    if text == "max":
        return text
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f'must be a number >= 0 or "max", got {text!r}') from None
    if not (value >= 0 and value != float("inf")):
        raise argparse.ArgumentTypeError(f'must be a number >= 0 or "max", got {text!r}')
    return value


def _parser() -> argparse.ArgumentParser:

    p = argparse.ArgumentParser(
        prog="tce",
        description="Total Complementary Energy analysis of masonry as rigid blocks in unilateral "
        "frictional contact: run study files, summarise and plot their results.",
        epilog="Study file format: docs/studies.md. Results format: docs/results.md.",
    )
    p.add_argument("--version", action="version", version=f"tce {__version__}")
    p.add_argument("-v", "--verbose", action="store_true", help="log debugging details")
    p.add_argument("-q", "--quiet", action="store_true", help="log warnings and errors only")
    sub = p.add_subparsers(dest="command", metavar="COMMAND", required=True)

    run = sub.add_parser(
        "run",
        help="run a study file",
        description="Validate STUDY.toml, solve every scenario not solved yet (a rerun resumes), "
        "write OUT/<study name>/results.nc and its figures.",
    )
    run.add_argument("study", type=Path, metavar="STUDY.toml", help="study file (TOML)")
    run.add_argument("--out", type=Path, default=Path("results"), metavar="DIR", help="results root (default: results)")
    run.add_argument("--jobs", type=_jobs, default=None, metavar="N", help="parallel workers (default: in-process when the study is smaller than starting workers costs, else all cores)")
    run.add_argument(
        "--backend", choices=("processes", "dask"), default="processes",
        help="processes: worker processes on this machine (default); dask: a Dask distributed cluster",
    )
    run.add_argument(
        "--scheduler", metavar="ADDR", default=None,
        help="Dask scheduler address, e.g. tcp://10.0.0.1:8786 (with --backend dask; "
        "default: a local cluster of --jobs workers)",
    )
    run.add_argument("--fresh", action="store_true", help="ignore scenarios solved by an earlier run")
    run.add_argument(
        "--strict", action="store_true",
        help="exit with code 4 unless every scenario ends at a limit (for scripted pipelines)",
    )
    run.add_argument("--no-plots", action="store_true", help="write the results only (no figures, no report)")
    run.add_argument("--no-report", action="store_true", help="no calculation report (report.html)")
    run.add_argument("--pdf", action="store_true",
                     help="also print the report as report.pdf (headless Chromium; 'tce report' prints it later)")

    show = sub.add_parser("show", help="summarise a results file", description="One line per scenario of RESULTS.nc.")
    show.add_argument("results", type=Path, metavar="RESULTS.nc")

    plot = sub.add_parser(
        "plot", help="plot a results file",
        description="Write the figures of RESULTS.nc that the study's [plots] table asks for; --scenario, --step "
        "and --kind replace its entries (with --scenario or --step and no --kind: the states figure only, its "
        "file name tagged). A load multiplier that is not a solved step is solved, not interpolated.",
    )
    plot.add_argument("results", type=Path, metavar="RESULTS.nc")
    plot.add_argument("--out", type=Path, default=None, metavar="DIR", help="folder of the figures (default: beside RESULTS.nc)")
    plot.add_argument("--scenario", action="append", default=None, metavar="NAME",
                      help="scenario to draw (name or shell pattern; repeatable)")
    plot.add_argument("--step", action="append", type=_target, default=None, metavar="LAMBDA",
                      help='load multiplier to draw (>= 0) or "max" (repeatable)')
    plot.add_argument("--kind", action="append", choices=PLOT_KINDS, default=None, help="figure kind (repeatable)")
    plot.add_argument("--jobs", type=_jobs, default=1, metavar="N", help="drawing processes (default 1)")

    view = sub.add_parser(
        "view", help="write the interactive 3D view of a results file",
        description="Write one self-contained HTML file (works offline) with the blocks, interface resultants at "
        "their pressure points, torques, loads and the collapse mechanism, a scenario selector and a slider over "
        "the solved steps.",
    )
    view.add_argument("results", type=Path, metavar="RESULTS.nc")
    view.add_argument("--out", type=Path, default=None, metavar="FILE", help="HTML file (default: view.html beside RESULTS.nc)")
    view.add_argument("--scenario", action="append", default=None, metavar="NAME",
                      help="scenario to include (name or shell pattern; repeatable; default: the study's [plots] scenarios)")
    view.add_argument("--open", action="store_true", help="open the file in the web browser")

    export = sub.add_parser(
        "export", help="export a results file for ParaView",
        description="Write VTK files (blocks, vertex forces and interface resultants per step, mechanism, one .pvd "
        "time series per scenario with lambda as time).",
    )
    export.add_argument("results", type=Path, metavar="RESULTS.nc")
    export.add_argument("--vtk", action="store_true", required=True, help="VTK XML files (.vtu, .pvd)")
    export.add_argument("--out", type=Path, default=None, metavar="DIR", help="folder (default: vtk/ beside RESULTS.nc)")
    export.add_argument("--scenario", action="append", default=None, metavar="NAME",
                        help="scenario to export (name or shell pattern; repeatable; default: all)")

    report = sub.add_parser(
        "report", help="write the calculation report of a results file",
        description="Write report.html (one self-contained file: structure, material, loads, scenarios, method and "
        "references, results tables, every figure, warnings, provenance) and report.pdf printed from it by headless "
        "Chromium (skipped, with the reason, when no chromium is found).",
    )
    report.add_argument("results", type=Path, metavar="RESULTS.nc")
    report.add_argument("--out", type=Path, default=None, metavar="DIR", help="folder (default: beside RESULTS.nc)")
    report.add_argument("--no-pdf", action="store_true", help="the HTML only")

    check = sub.add_parser(
        "check",
        help="run the numerical stability report",
        description="Solve the hard cases (near-limit loads, thin arches, extreme units, stiffness and "
        "friction, slivers, many voussoirs, unbounded settlements) and print case, expected and actual "
        "status, residual, retry used and time. Exit code 1 if a case fails.",
    )
    check.add_argument("--select", metavar="TEXT", default=None, help="only the cases whose name contains TEXT")
    check.add_argument("--validation", action="store_true",
                       help="instead, the validation atlas: tce against published values (docs/validation.md)")

    bench = sub.add_parser(
        "bench",
        help="time against error of the solves, on this machine",
        description="Time one TCE solve of each model and contact law, the direct lambda_max, the load path "
        "against the direct limit, lambda_max against the number of blocks and the samples of a reliability "
        "study (per sample against raw Clarabel, 10,000 in one call, against workers), each against its error; "
        "print the tables and write bench.csv.",
    )
    bench.add_argument("--out", type=Path, default=Path("results/bench"), metavar="DIR", help="output folder (default: results/bench)")
    bench.add_argument("--quick", action="store_true", help="fewer repeats and the smallest sizes (under a minute)")
    bench.add_argument("--section", action="append", default=None, choices=BENCH_SECTIONS,
                       help="run only this section (repeatable)")
    return p


def _setup_logging(verbose: bool, quiet: bool) -> None:
    level = logging.DEBUG if verbose else logging.WARNING if quiet else logging.INFO
    handler = logging.StreamHandler(sys.stderr)
    handler.setFormatter(logging.Formatter("tce: %(message)s"))
    log.handlers[:] = [handler]
    log.setLevel(level)
    log.propagate = False
    if not verbose:  # matplotlib's layout notes are not the user's business
        logging.getLogger("matplotlib").setLevel(logging.ERROR)


#: variables the figures and the view need (a results file of an older tce may lack some)
RESULTS_VARS = ("lambda_max", "outcome", "status", "lam", "block_centroid")


def _open_results(path: Path, needs: Sequence[str] = RESULTS_VARS):
    """The results dataset at ``path``; a missing, unreadable, foreign or older file (without
    a variable of ``needs``) is a :class:`UsageError` saying which."""
    import xarray as xr

    if not path.is_file():
        raise UsageError(f"{path}: no such results file; fix: give the results.nc written by 'tce run'")
    try:
        ds = xr.load_dataset(path)
    except (OSError, ValueError, RuntimeError) as exc:
        raise UsageError(f"{path}: not a readable results file ({exc}); fix: give the results.nc written by 'tce run'") from None
    if "tce_version" not in ds.attrs or "scenario" not in ds.dims:
        raise UsageError(
            f"{path}: not a results file written by tce (no tce_version attribute or scenario dimension); "
            "fix: give the results.nc written by 'tce run'"
        )
    if not ds.attrs.get("study"):
        raise UsageError(f"{path}: its study attribute (the study file it ran) is missing: a damaged results file; "
                         "fix: run the study again")
    missing = [v for v in needs if v not in ds.variables]
    if missing:
        raise UsageError(
            f"{path}: written by an older tce ({ds.attrs['tce_version']}): no {', '.join(missing)}; "
            "fix: run the study again with this tce"
        )
    return ds


def _out_folder(out: Path, option: str = "--out") -> Path:
    """``out`` as a folder to write into, created if needed: checked once, before anything is
    computed, for every command that writes (:class:`UsageError` naming the path if it cannot be
    written: a file, a path under a file, a link to nothing or a loop of links, a read-only or
    full disk)."""
    import shutil

    from .files import MIN_FREE, storage_error

    fix = f"fix: give another {option}"
    if out.is_symlink() and not out.exists():
        raise UsageError(f"{option}: {out} is a link to nothing (or a loop of links); {fix} (or remove the link)")
    if out.exists() and not out.is_dir():
        raise UsageError(f"{option}: {out} is a file, not a folder; fix: give a folder (or remove the file)")
    try:
        out.mkdir(parents=True, exist_ok=True)
        out.resolve(strict=True)
    except OSError as exc:
        raise UsageError(f"{option}: {storage_error(out, exc)}") from None
    except RuntimeError:  # a loop of links above it
        raise UsageError(f"{option}: cannot write {out}: a loop of links; {fix}") from None
    if not os.access(out, os.W_OK | os.X_OK):
        raise UsageError(f"{option}: cannot write {out} (read-only or not permitted); {fix}")
    free = shutil.disk_usage(out).free
    if free < MIN_FREE:
        raise UsageError(f"{option}: cannot write {out}: {free} bytes free; fix: free some space or give another {option}")
    return out


@contextlib.contextmanager
def _writing(where: Path) -> Iterator[None]:
    """An :class:`OSError` while the block writes under ``where`` (a disk that fills) is a
    :class:`WriteFault` naming the path."""
    from .files import storage_error

    try:
        yield
    except OSError as exc:
        raise WriteFault(str(storage_error(Path(exc.filename or where), exc))) from None


class _Bar:
    """Progress of a run's scenarios (:class:`tce.study.progress.Progress`): a bar on a
    terminal, one-line progress in the log otherwise."""

    def __init__(self, desc: str) -> None:
        self.desc = desc
        self.bar = None

    def __call__(self, done: int, total: int, steps: int) -> None:
        from .study.progress import Progress

        if self.bar is None:
            self.bar = Progress(total, self.desc, unit="scenario")
        self.bar.note(f"{steps} load steps")
        self.bar.set_done(done)
        if done >= total:
            self.close()  # solving is over: what follows (figures) reports itself

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()
            self.bar = None


#: exit codes of ``tce run`` (module docstring)
EXIT_FAULT, EXIT_STRICT = 3, 4
#: exit code when the standard output is closed early (a shell's 128 + SIGPIPE)
EXIT_PIPE = 141


def _draw(ds, folder: Path, jobs: int) -> list[Path]:
    """The figures and view of a finished run (:func:`tce.plot.write_figures`)."""
    from . import plot

    return plot.write_figures(ds, folder, jobs=jobs)


def _run(args: argparse.Namespace) -> int:
    """``tce run``."""
    if args.scheduler and args.backend != "dask":
        raise UsageError("--scheduler needs --backend dask")
    from .study.runner import OUTCOMES, FigureFault, RunError, RunFault, run_study
    from .study.schema import StudyError, load_study

    try:
        study = load_study(args.study)
    except StudyError as exc:
        raise UsageError(str(exc)) from None
    _out_folder(args.out / study.name)
    log.info("%s: %s", study.name, study.work())
    kept = f"finished scenarios are kept in {args.out / study.name / 'scenarios'}"
    bar = _Bar(study.name)
    try:
        report = run_study(
            study, args.out, jobs=args.jobs, backend=args.backend, scheduler=args.scheduler,
            progress=bar, plots=None if args.no_plots else _draw,
            fresh=args.fresh,
        )
    except RunError as exc:
        raise UsageError(str(exc)) from None
    except FigureFault as fault:
        bar.close()
        (line,) = fault.report.faults
        print(f"tce: error: {line}", file=sys.stderr)
        print(
            f"tce: {fault.report.results} is written, its figures are not: 'tce plot {fault.report.results}' "
            "draws them once there is space",
            file=sys.stderr,
        )
        return EXIT_FAULT
    except RunFault as fault:
        bar.close()
        for line in fault.report.faults:
            print(f"tce: error: {line}", file=sys.stderr)
        done = len(fault.report.outcomes)
        print(
            f"tce: the run ended with {len(fault.report.faults)} fault(s); {done} {kept}; "
            "results.nc was not written: run the same command again to solve the rest",
            file=sys.stderr,
        )
        return EXIT_FAULT
    except KeyboardInterrupt as exc:
        bar.close()
        print(f"tce: interrupted ({exc or 'SIGINT'}); {kept}: run the same command again to resume", file=sys.stderr)
        return exit_code(exc)
    bar.close()
    counts = {o: list(report.outcomes.values()).count(o) for o in OUTCOMES}
    counts.update({o: n for o, n in Counter(report.outcomes.values()).items() if o not in counts})
    what = f"{len(report.solved)} solved" + (f", {len(report.reused)} reused" if report.reused else "")
    tally = ", ".join(f"{n} {o}" for o, n in counts.items() if n)
    if study.spec.settlement_path is not None:
        tally += f"; settlement path: {_settlement_tally(report.results)}"
    print(f"{report.results}: {len(report.outcomes)} scenarios ({what}): {tally}; {len(report.figures)} figures")
    if not (args.no_plots or args.no_report):
        files = _write_report(report.results, figures=report.figures, pdf=args.pdf)
        _report_lines(files, "" if args.pdf else f"tce run --pdf, or tce report {report.results}")
    odd = {name: o for name, o in report.outcomes.items() if o != "limit"}
    for name, outcome in odd.items():
        print(f"  {outcome}: {name}")
    return EXIT_STRICT if args.strict and odd else 0


def _settlement_tally(results: Path) -> str:
    """How the settlement paths of the run's ``results`` ended: ``2 collapse, 1 no_motion``."""
    import xarray as xr

    with xr.open_dataset(results) as ds:
        outcomes = Counter(map(str, ds["settlement_outcome"].values))
    return ", ".join(f"{n} {o}" for o, n in outcomes.items())


def _show(args: argparse.Namespace) -> int:
    cols = ["lambda_max", "lambda_direct", "lambda_gap", "outcome", "model", "n_solves", "solve_time", "wall_time"]
    ds = _open_results(args.results, cols)
    table = ds[cols].to_dataframe()[cols].rename(columns={"lambda_direct": "direct", "lambda_gap": "gap"})
    print(f"study {ds.attrs.get('study_name', '?')} (tce {ds.attrs.get('tce_version', '?')}, {ds.attrs.get('solver', '?')})")
    print(table.to_string(float_format=lambda v: f"{v:.6g}"))
    _show_loads(ds)
    _show_outcomes(ds)
    _show_rings(ds)
    _show_small_displacements(ds)
    if "load_x" in ds.coords:
        _show_critical(ds)
    if "critical_x" in ds:
        _show_search(ds)
    if "load_notes" in ds:
        _show_notes(ds)
    if "adequacy_factor" in ds:
        _show_assessment(ds)
    if "settlement_capacity" in ds:
        _show_settlement(ds)
    if "sample_capacity" in ds:
        _show_uncertainty(ds)
    return 0


def _show_uncertainty(ds) -> None:
    """The failure probability of each scenario of an ``[uncertainty]`` study, one line each
    (:func:`tce.report.content.uncertainty_rows`)."""
    from .report.content import uncertainty_content

    u = uncertainty_content(ds)
    print(f"uncertainty ({u['method']}, N = {u['samples']}, seed {u['seed']}; failure: "
          f"{u['failure'].replace('λ', 'lambda')}; pf with its {u['interval']} interval, beta = -Phi^-1(pf); "
          f"dominant: largest |{u['sensitivity']}|):")
    for r in u["rows"]:
        extra = [f"FORM {r['form']}" if r["form"] else "", f"subset {r['subset']}" if r["subset"] else "", r["note"]]
        print(f"  {r['scenario']}: pf {r['pf']} [{r['low']}, {r['high']}], beta {r['beta']}, N {r['samples']} "
              f"({r['failed']} failed of {r['decided']} decided, {r['numerical']} numerical), dominant {r['dominant']}"
              + "".join(f"; {e.replace('β', 'beta')}" for e in extra if e))


def _show_small_displacements(ds) -> None:
    """Where a scenario moves a support: lambda_max does not depend on the settlement's
    magnitude (:func:`tce.report.content.small_displacement_note`)."""
    from .report.content import small_displacement_note

    note = small_displacement_note(ds)
    if note:
        print(f"settlements: {note.replace('λ', 'lambda_')}")


def _show_rings(ds) -> None:
    """Whether the rings separate at the limit, per scenario (:func:`tce.report.content.ring_separation`)."""
    from .report.content import ring_separation

    for line in ring_separation(ds):
        print(f"ring separation: {line}")


def _show_loads(ds) -> None:
    """What lambda multiplies (:func:`tce.report.content.lambda_multiplies`): one line for the
    study when every scenario has the same loads, else one line per scenario."""
    from .report.content import lambda_multiplies

    for line in lambda_multiplies(ds):
        print(f"loads: {line}")


def _show_outcomes(ds) -> None:
    """One line per scenario that did not end at a limit: its outcome, what it means and why
    (:func:`tce.study.outcomes.outcome_words`)."""
    from .plot.data import study_cap
    from .study.outcomes import outcome_words

    for k, name in enumerate(ds["scenario"].values):
        outcome = str(ds["outcome"].values[k])
        if outcome == "limit":
            continue
        var = f"{outcome}_reason"
        reason = str(ds[var].values[k]) if var in ds else ""
        words = outcome_words(outcome, float(ds["lambda_direct"].values[k]), study_cap(ds), label=False)
        print(f"{name}: {outcome}: {words}" + (f"; {reason}" if reason else ""))


def _show_assessment(ds) -> None:
    """The assessment of each scenario (``[assessment]``), adequacy factor included."""
    print("assessment (adequacy factor: multiplier of the factored live load at collapse under the factored "
          "dead load; >= 1: adequate):")
    for k, name in enumerate(ds["scenario"].values):
        what = str(ds["assessed_vehicles"].values[k]) or "the live loads"
        where = ""
        if "critical_x" in ds and math.isfinite(ds["critical_x"].values[k]):
            where = f" at its critical position x = {float(ds['critical_x'].values[k]):.4g} m"
        lam = float(ds["lambda_max"].values[k])
        collapse = f"collapses at {lam:.4g} x the declared live load" if math.isfinite(lam) else \
            f"load path outcome {ds['outcome'].values[k]}"
        gd, gl = float(ds["dead_factor"].values[k]), float(ds["live_factor"].values[k])
        af, status = float(ds["adequacy_factor"].values[k]), str(ds["adequacy_status"].values[k])
        if status == "optimal":
            verdict = f"adequacy factor {af:.4g}: {'adequate' if af >= 1.0 else 'NOT adequate'}"
        elif status == "unbounded":
            verdict = "adequacy factor unbounded (carried at any multiplier): adequate"
        else:
            verdict = f"no adequacy factor ({status})"
        print(f"  {name}: {what}{where}: {collapse} (unfactored); partial factors dead {gd:g}, live {gl:g}: {verdict}")


def _show_settlement(ds) -> None:
    """The settlement path's answer per scenario (``[settlement_path]``,
    :func:`tce.report.content.settlement_rows`)."""
    from .report.content import live_settlement_rows, settlement_rows, settlement_units

    print(f"settlement path (capacity: largest magnitude found standing, {settlement_units(ds)}; "
          "lateral: lambda_max of the lateral pattern on the deformed structure at the capacity):")
    for r in settlement_rows(ds):
        print(f"  {r['scenario']}: {r['outcome']}: capacity {r['capacity']} (first not standing {r['upper']}), "
              f"{r['snaps']} snap(s), lateral {r['lateral']}; hinges {r['hinges']}")
        if r["message"]:
            print(f"    {r['message']}")
    live = live_settlement_rows(ds)
    if live:
        print("live loads after a finite settlement (lambda_max on the deformed structure, the fixed loads carried; "
              "the small-displacement lambda_max does not depend on the settlement's magnitude):")
    for r in live:
        where = f" at x = {r['x']} m" if r["x"] != "–" else ""
        print(f"  {r['scenario']}: s = {r['at']} (path step {r['step']}): {r['status']}: lambda_max {r['lambda']}{where}; "
              f"gaps up to {r['gap']} mm counted closed")


def _show_search(ds) -> None:
    """The critical position each scenario's search found (``[loads] critical_position``)."""
    print("critical position of the moving loads (searched; the load path runs there):")
    for k, name in enumerate(ds["scenario"].values):
        status = str(ds["critical_status"].values[k])
        if status != "optimal":
            print(f"  {name}: {status}: no critical position"
                  + (" (carried at any multiplier at every position)" if status == "unbounded" else ""))
            continue
        ties = str(ds["critical_ties"].values[k])
        print(f"  {name}: x = {float(ds['critical_x'].values[k]):.6g} m (to {float(ds['critical_xtol'].values[k]):.2g} m), "
              f"direct lambda_max = {float(ds['critical_lambda'].values[k]):.6g}, "
              f"{int(ds['critical_solves'].values[k])} limit solves"
              + (f"; tied (same lambda_max) at x = {ties} m, the leftmost reported" if ties else ""))


def _show_notes(ds) -> None:
    """Loads dropped because they lie off the deck, per scenario."""
    for name, notes in zip(ds["scenario"].values, ds["load_notes"].values):
        for line in str(notes).splitlines():
            print(f"{name}: note: {line}")


def _show_critical(ds) -> None:
    """The critical position of a load-position sweep, per group of the other coordinates."""
    from .study.positions import critical_positions

    print("critical load position (smallest lambda_max over load_x):")
    for c in critical_positions(ds):
        where = f"{c.group}: " if c.group else ""
        if c.scenario:
            print(f"  {where}load_x = {c.load_x:.6g} m, lambda_max = {c.lambda_max:.6g} (scenario {c.scenario})"
                  + (f"; tied (same lambda_max within the tolerance) at load_x = {', '.join(f'{t:.6g}' for t in c.ties)} m"
                     if c.ties else ""))
        else:
            outcome = dict(zip(map(str, ds["scenario"].values), map(str, ds["outcome"].values)))
            seen = sorted({outcome[s] for s in c.scenarios})
            print(f"  {where}no position has a finite lambda_max (outcomes: {', '.join(seen)}; see the lines above)")


_OPTIONS = {"scenarios": "--scenario", "steps": "--step", "kinds": "--kind"}


def _spec(ds, **given):
    """The plotting spec of ``ds`` with the command line's replacements (a bad one: a usage
    error naming the option or the ``[plots]`` key)."""
    from .plot.data import PlotSpecError, plot_spec

    try:
        return plot_spec(ds, **given)
    except PlotSpecError as exc:
        replaced = {"scenarios": "scenarios_"}.get(exc.key, exc.key)
        where = _OPTIONS.get(exc.key, exc.key) if given.get(replaced) is not None else f"[plots] {exc.key}"
        raise UsageError(f"{where}: {exc.message}") from None


def _plot(args: argparse.Namespace) -> int:
    from .study.names import slug
    from .plot.output import write_figures

    ds = _open_results(args.results)
    on_demand = args.scenario is not None or args.step is not None
    kinds = args.kind or (["states"] if on_demand else None)
    spec = _spec(ds, steps=args.step, scenarios_=args.scenario, kinds=kinds)
    if on_demand and not spec.scenarios:
        raise UsageError("--scenario: no scenario selected")
    tag = slug("_".join([*(args.scenario or []), *(f"lam{s}" for s in args.step or [])]))[:80] if on_demand else ""
    outdir = _out_folder(args.out or args.results.parent)
    with _writing(outdir):
        figures = write_figures(ds, outdir, spec, jobs=args.jobs, tag=tag)
    for f in figures if on_demand else []:
        print(f)
    print(f"{len(figures)} figures in {outdir}")
    return 0


def _view(args: argparse.Namespace) -> int:
    from .files import atomic_write
    from .plot.view import view_html

    ds = _open_results(args.results)
    spec = _spec(ds, scenarios_=args.scenario)
    if not spec.scenarios:
        raise UsageError("--scenario: the study draws no scenario by default (a large sweep): name some")
    out = args.out or args.results.parent / "view.html"
    if out.suffix.lower() not in (".html", ".htm"):
        raise UsageError(f"--out: {out} is not an .html file")
    if out.is_dir():
        raise UsageError(f"--out: {out} is a folder, not an .html file")
    _out_folder(out.parent)
    page = view_html(ds, spec.scenarios)
    with _writing(out), atomic_write(out) as tmp:
        tmp.write_bytes(page)
    print(out)
    if args.open:
        import webbrowser

        webbrowser.open(out.resolve().as_uri())
    return 0


def _export(args: argparse.Namespace) -> int:
    from .plot.export import export_vtk

    ds = _open_results(args.results, (*RESULTS_VARS, "vertex_force", "vertex_point", "vertex_interface"))
    names = None
    if args.scenario:
        names = _spec(ds, scenarios_=args.scenario).scenarios
    out = _out_folder(args.out or args.results.parent / "vtk")
    with _writing(out):
        files = export_vtk(ds, out, names)
    print(f"{len(files)} VTK files in {out}")
    return 0


def _write_report(results: Path, out: Path | None = None, figures: list[Path] | None = None, pdf: bool = True):
    """The calculation report (:func:`tce.report.write_report`); a results file it cannot read is a usage error."""
    from .report import write_report

    try:
        return write_report(results, out, figures=figures, pdf=pdf)
    except (KeyError, ValueError) as exc:
        raise UsageError(f"{results}: cannot write its report: not a complete tce results file ({exc})") from None


def _report_lines(files, how_to_print: str = "") -> None:
    """The report's files, or why its PDF was not printed (``how_to_print``: the command that
    prints it, where the PDF was not asked for)."""
    if files.pdf:
        print(f"report: {files.html}, {files.pdf}")
    elif how_to_print:
        print(f"report: {files.html} (the PDF: {how_to_print})")
    else:
        print(f"report: {files.html} (PDF skipped: {files.skipped})")


def _report(args: argparse.Namespace) -> int:
    _open_results(args.results).close()  # a missing or unreadable file: one message, exit 2
    out = _out_folder(args.out or args.results.parent)
    with _writing(out):
        _report_lines(_write_report(args.results, out, pdf=not args.no_pdf))
    return 0


def _check(args: argparse.Namespace) -> int:
    from .quality.check import check_command

    return check_command(args)


#: sections of ``tce bench`` (:data:`tce.quality.bench.SECTIONS`; named here so that the parser imports no solver)
BENCH_SECTIONS = ("solve", "hot_path", "limit", "load_path", "scaling", "reliability")


def _bench(args: argparse.Namespace) -> int:
    from .quality.bench import report, run_bench

    out = _out_folder(args.out)
    df = run_bench(quick=args.quick, sections=args.section)
    with _writing(out):
        df.to_csv(out / "bench.csv", index=False)
    print(report(df), end="")
    print(f"wrote {out / 'bench.csv'} ({len(df)} rows)")
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``tce`` command: ``argv`` without the program name (default
    ``sys.argv[1:]``); returns the exit code."""
    before = handle_signals()  # first: Ctrl-C or SIGTERM from here on, imports included, ends in one line
    try:
        args = _parser().parse_args(argv)  # argparse exits with code 2 on a bad command line
        _setup_logging(args.verbose, args.quiet)
        commands = {"run": _run, "show": _show, "plot": _plot, "view": _view, "export": _export, "report": _report,
                    "check": _check, "bench": _bench}
        for option, value in vars(args).items():
            if isinstance(value, Path):
                try:
                    check_path(value, option.upper() if option in ("study", "results") else f"--{option}")
                except ValueError as exc:
                    raise UsageError(str(exc)) from None
        code = commands[args.command](args)
        sys.stdout.flush()  # a closed pipe fails here, in the handler below, not in Python's flush at exit
        return code
    except KeyboardInterrupt as exc:
        print(f"tce: interrupted ({exc or 'SIGINT'})", file=sys.stderr)
        return exit_code(exc)
    except UsageError as exc:
        print(f"tce: error: {exc}", file=sys.stderr)
        return 2
    except WriteFault as exc:
        print(f"tce: error: {exc}", file=sys.stderr)
        return EXIT_FAULT
    except BrokenPipeError:  # the reader went away (``tce show | head``): stop quietly, as SIGPIPE would
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())  # Python's own flush at exit finds no pipe
        return EXIT_PIPE
    finally:
        restore_signals(before)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
