"""Write the figures and the interactive view of a results dataset, each drawn once.

:func:`write_figures` reads what to draw from the study's ``[plots]`` table
(:func:`tce.plot.data.plot_spec`), solves the drawn states the file does not hold
(:mod:`tce.plot.states`), and renders one file per figure, in parallel worker processes
when there are many (:data:`PARALLEL_AT`). Files (``<tag>`` appended to each stem when
given):

``capacity.png``        load-position sweeps (:mod:`tce.plot.capacity`)
``thrust.png``          forces on the supports against lambda
``states.png``          drawn states, ``states_2.png`` ... for further pages
``thrust_lines.png``    lines of thrust (one line of blocks only)
``transversal.png``     pressure points across the depth (one line of blocks, a spatial scenario)
``base.png``            pressure points on the support interfaces
``mechanism.png``       collapse mechanism, ``mechanism_2.png`` ... for other mechanisms
``summary.png``         lambda_max against the swept parameters (sweeps only)
``bracket.png``         non-associative bracket (:mod:`tce.plot.materials`)
``view.html``           the interactive 3D view (:mod:`tce.plot.view`)
``settlement.png``      ``[settlement_path]`` only (:mod:`tce.plot.settlement`), and
``settlement_shapes.png``
``fragility.png``       ``[uncertainty]`` only (:mod:`tce.plot.uncertainty`), and
``capacity_samples.png``, ``sensitivity.png``, ``convergence.png``

Each stem is its kind. A geometry sweep draws each structure apart in the figures that draw
blocks (``base_2.png`` ... for the second structure). The number of figures does not grow
with the number of scenarios beyond those the ``[plots]`` table draws.
"""

from __future__ import annotations

import logging
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import xarray as xr

from .data import (
    UNCERTAINTY_KINDS,
    PlotSpec,
    assembly,
    chain_interfaces,
    geometry_groups,
    has_uncertainty,
    is_planar,
    mechanism_groups,
    plot_spec,
    state_pages,
    structure_frame,
    swept_parameters,
)
from ..files import atomic_write
from ..study.progress import Progress, track

__all__ = ["DPI", "PARALLEL_AT", "builder", "figure_tasks", "render", "write_figures"]

log = logging.getLogger(__name__)

#: render in parallel (when ``jobs > 1``) from this many files on
PARALLEL_AT = 8
#: resolution of the PNG files (dots per inch): a screen's
DPI = 100


@dataclass(frozen=True)
class Task:
    """One file to write: ``kind`` drawn with ``args`` into ``name``."""

    name: str
    kind: str
    args: tuple


def figure_tasks(ds: xr.Dataset, spec: PlotSpec, tag: str = "") -> list[Task]:
    """The files :func:`write_figures` writes for ``spec``, in order (see module docstring).

    A kind asked for that does not apply (no scenario drawn, no line of blocks, nothing
    swept, no mechanism) is logged and left out.
    """
    def name(stem: str, ext: str = "png") -> str:
        return f"{stem}_{tag}.{ext}" if tag else f"{stem}.{ext}"

    names = list(spec.scenarios)
    steps = list(spec.steps)
    tasks: list[Task] = []
    skipped: list[str] = []
    for kind in spec.kinds:
        if kind == "summary":
            if swept_parameters(ds):
                tasks.append(Task(name("summary"), kind, ()))
            else:
                skipped.append("summary (nothing swept)")
            continue
        if kind == "capacity":
            if "load_x" in ds.coords or "scan_x" in ds:
                tasks.append(Task(name("capacity"), kind, ()))
            else:
                skipped.append("capacity (no load-position sweep or search)")
            continue
        if kind == "bracket":
            from .materials import SWEPT

            if "lambda_nonassoc" in ds and any(p in ds.coords and len(np.unique(ds[p].values)) > 1 for p in SWEPT):
                tasks.append(Task(name("bracket"), kind, ()))
            else:
                skipped.append("bracket (no non-associative material swept: the summary has lambda_max)")
            continue
        if kind in ("settlement", "settlement_shapes"):
            from .settlement import settled_scenarios

            settled = settled_scenarios(ds)
            if settled:
                tasks.append(Task(name(kind), kind, (tuple(settled),)))
            else:
                skipped.append(f"{kind} (no settlement path: add [settlement_path] and a moving support)")
            continue
        if kind in UNCERTAINTY_KINDS:
            if has_uncertainty(ds):
                tasks.append(Task(name(kind), kind, ()))
            else:
                skipped.append(f"{kind} (no sampled capacities: add [uncertainty])")
            continue
        if not names:
            skipped.append(f"{kind} (no scenario drawn: name them in [plots] scenarios)")
            continue
        if kind in ("thrust", "view"):  # the view switches structures with the scenario
            tasks.append(Task(name(kind, "html" if kind == "view" else "png"), kind, (tuple(names),)))
            continue
        # the other kinds draw blocks: each group of scenarios on its own structure (a
        # geometry sweep), pages numbered on across the groups
        pages: list[tuple] = []
        for group in geometry_groups(ds, names):
            if kind == "states":
                pages += [(tuple(page),) for page in state_pages(group, steps)]
            elif kind == "thrust_lines":
                if chain_interfaces(assembly(ds, group[0])) is None:
                    skipped.append(f"thrust_lines of {group} (the structure is not one line of blocks)")
                else:
                    pages.append((tuple(group), tuple(steps)))
            elif kind == "transversal":
                asm = assembly(ds, group[0])
                if chain_interfaces(asm) is None or structure_frame(asm).kind == "radial":
                    skipped.append(f"transversal of {group} (the structure is not one line of blocks)")
                elif all(is_planar(ds, s) for s in group):
                    skipped.append(f"transversal of {group} (every drawn scenario is planar: the pressure points "
                                   "stay mid-depth)")
                else:
                    pages.append((tuple(group), tuple(steps)))
            elif kind == "base":
                pages.append((tuple(group), tuple(steps)))
            elif kind == "mechanism":
                pages += [(tuple(g), tuple(names)) for g in mechanism_groups(ds, group)]
        if kind == "mechanism" and not pages:
            skipped.append("mechanism (no scenario drawn has one)")
        for k, args in enumerate(pages):
            tasks.append(Task(name(kind if k == 0 else f"{kind}_{k + 1}"), kind, args))
    for what in skipped:
        log.info("not drawn: %s", what)
    return tasks


def builder(kind: str) -> Callable:
    """The function drawing figures of ``kind``, its module imported on first use (some
    import the solvers)."""
    if kind == "capacity":
        from .capacity import influence_line

        return influence_line
    if kind == "bracket":
        from .materials import bracket_figure

        return bracket_figure
    if kind in ("settlement", "settlement_shapes"):
        from . import settlement

        return settlement.settlement_curves if kind == "settlement" else settlement.settlement_shapes
    if kind in UNCERTAINTY_KINDS:
        from . import uncertainty

        return {"fragility": uncertainty.fragility_figure, "capacity_samples": uncertainty.capacity_samples_figure,
                "sensitivity": uncertainty.sensitivity_figure, "convergence": uncertainty.convergence_figure}[kind]
    if kind == "view":
        from .view import view_html

        return view_html
    from . import figures

    return {"thrust": figures.thrust_curves, "states": figures.states_figure, "thrust_lines": figures.thrust_lines,
            "transversal": figures.transversal_figure, "base": figures.base_figure,
            "mechanism": figures.mechanism_view, "summary": figures.summary_figure}[kind]


def render(ds: xr.Dataset, task: Task, outdir: Path) -> Path:
    """Draw one task and write its file whole or not at all (:func:`tce.files.atomic_write`).

    Raises
    ------
    OSError
        The file cannot be written (a full disk): its ``filename`` is the file's path.
    """
    path = Path(outdir) / task.name
    out = builder(task.kind)(ds, *task.args)
    try:
        with atomic_write(path) as tmp, open(tmp, "wb") as fh:
            if isinstance(out, bytes):  # a page (view.html)
                fh.write(out)
            else:
                out.savefig(fh, format="png", dpi=DPI)
    except OSError as exc:
        raise OSError(exc.errno, exc.strerror, str(path)) from exc
    return path


def _subset(ds: xr.Dataset, task: Task) -> xr.Dataset:
    """The part of ``ds`` a task reads (what a worker process receives)."""
    if task.kind in ("summary", "bracket", "capacity", *UNCERTAINTY_KINDS):
        return ds.drop_vars([k for k, v in ds.data_vars.items() if "step" in v.dims or "interface" in v.dims])
    names = {a for arg in task.args for a in arg if isinstance(a, str)}
    names |= {a[0] for arg in task.args for a in arg if isinstance(a, tuple)}
    return ds.sel(scenario=[s for s in ds["scenario"].values if s in names])


def write_figures(
    ds: xr.Dataset, outdir: Path | str, spec: PlotSpec | None = None, jobs: int = 1, tag: str = "",
) -> list[Path]:
    """Write every figure of ``spec`` (default: the study's ``[plots]``) into ``outdir``.

    Parameters
    ----------
    ds : xarray.Dataset
    outdir : path
        Created if missing.
    spec : PlotSpec, optional
    jobs : int
        Worker processes (joblib, used from :data:`PARALLEL_AT` files on).
    tag : str
        Appended to every file stem.

    Returns
    -------
    list of pathlib.Path
        The files written, in the order of :func:`figure_tasks`.
    """
    from .states import missing_states, solve_states  # the solvers: imported when states are missing

    spec = spec or plot_spec(ds)
    todo = missing_states(ds, spec.scenarios, [t for t in spec.steps if t != "max"])
    if todo:
        try:
            ds = solve_states(ds, todo)
        except ValueError as exc:
            log.warning("drawn states not solved (%s): their panels say so", exc)
    tasks = figure_tasks(ds, spec, tag)
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    if jobs > 1 and len(tasks) >= PARALLEL_AT:
        import joblib

        log.info("drawing %d files on %d workers", len(tasks), jobs)
        drawn = joblib.Parallel(n_jobs=min(jobs, len(tasks)), return_as="generator")(
            joblib.delayed(render)(_subset(ds, t), t, outdir) for t in tasks
        )
        files = []
        with Progress(len(tasks), "figures", unit="file") as bar:
            for path in drawn:  # in task order, as they finish
                bar.note(path.name)
                bar.update()
                files.append(path)
        return files
    return [render(ds, t, outdir) for t in track(tasks, "figures", unit="file", label=lambda t: t.name)]
