"""Figures of an uncertainty study (``[uncertainty]``: the samples' capacities, ``docs/results.md``).

:func:`fragility_figure`
    ``P(capacity < x)`` against the intensity ``x`` per scenario with its band, the threshold
    marked with the failure probability there; with a sweep, the failure probability with
    its interval against each swept parameter.
:func:`capacity_samples_figure`
    The histogram of each scenario's sampled capacities, the samples without a finite
    capacity counted in the legend.
:func:`sensitivity_figure`
    The sensitivity of the capacity to each variable (the method named), and FORM's
    importance factors alpha where present.
:func:`convergence_figure`
    The running failure-probability estimate against the number of samples with its
    interval, FORM and subset estimates as horizontal lines.

Every figure counts the samples whose status is not ``optimal`` (unbounded: +inf, survives;
infeasible: -inf, fails; numerical: NaN, left out) and names the scenarios it leaves out.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import xarray as xr
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from numpy.typing import NDArray

from ..analysis.reliability import failure_probability
from .data import (
    SWEPT,
    capacity_label,
    counts_note,
    join_names,
    sample_counts,
    scenarios,
    settlement_parameter,
    sweep_axes,
    text,
    value,
)
from .figures import (FONT, LINESTYLES, MARKERS, NOTE_COLOUR, _bottom_legend, _Grid, _legend_height, _palette,
                      _study, _wrap)

__all__ = ["MAX_CURVES", "MAX_PANELS", "capacity_samples_figure", "convergence_figure", "drawn_scenarios",
           "fragility_figure", "running_estimate", "sensitivity_figure"]

#: most scenarios drawn as curves or bars in one panel
MAX_CURVES = 8
#: most scenarios drawn one panel each
MAX_PANELS = 12
#: points of the running estimate
RUNNING_POINTS = 60
BAND_ALPHA = 0.2
#: the box behind words written over a panel's curves
NOTE_BOX = {"facecolor": "white", "edgecolor": "none", "alpha": 0.85, "pad": 1.5}


def drawn_scenarios(ds: xr.Dataset, most: int) -> tuple[list[str], str]:
    """At most ``most`` scenarios, evenly spread over the study's (first and last kept), and
    a note naming how many are left out ("" when none is)."""
    names = scenarios(ds)
    if len(names) <= most:
        return names, ""
    pick = np.unique(np.round(np.linspace(0, len(names) - 1, most)).astype(int))
    return [names[k] for k in pick], (f"{len(pick)} of {len(names)} scenarios drawn, evenly spread; every scenario's "
                                       "numbers are in results.nc and tce show")


def _threshold(ds: xr.Dataset) -> float:
    return float(ds.attrs.get("uncertainty_threshold", math.nan))


def _interval_name(ds: xr.Dataset) -> str:
    name = str(ds.attrs.get("uncertainty_interval", "clopper-pearson"))
    conf = float(ds.attrs.get("uncertainty_confidence", 0.95))
    return f"{100 * conf:g} % {'Wilson' if name == 'wilson' else 'Clopper-Pearson'} interval"


def _kinds(ds: xr.Dataset, names: Sequence[str]) -> dict[str, list[str]]:
    """The scenarios of ``names`` grouped by ``capacity_kind`` (order of first appearance)."""
    out: dict[str, list[str]] = {}
    for s in names:
        out.setdefault(text(ds, "capacity_kind", s, "lambda_max"), []).append(s)
    return out


def _notes(ds: xr.Dataset, names: Sequence[str], extra: Sequence[str] = ()) -> list[str]:
    """One line per scenario of ``names`` with samples other than ``optimal``, then ``extra``."""
    return [f"{s}: {n}" for s in names if (n := counts_note(ds, s))] + [e for e in extra if e]


def _notes_height(notes: Sequence[str], width: float) -> float:
    return sum(0.15 * (_wrap(n, width - 0.6).count("\n") + 1) for n in notes) + (0.1 if notes else 0.0)


def _write_notes(fig: Figure, notes: Sequence[str], width: float, height: float, top: float) -> None:
    """``notes`` wrapped, from ``top`` inches above the bottom edge down."""
    y = top
    for n in notes:
        wrapped = _wrap(n, width - 0.6)
        fig.text(0.3 / width, y / height, wrapped, ha="left", va="top", fontsize=FONT - 0.5, color=NOTE_COLOUR)
        y -= 0.15 * (wrapped.count("\n") + 1)


def _title(title: str, width: float) -> tuple[str, float]:
    """``title`` wrapped to a figure ``width`` inches wide (its font is larger than the notes'),
    and the top margin (inches) that holds its lines above the panels."""
    wrapped = _wrap(title, (width - 0.4) * (FONT - 0.5) / (FONT + 2))
    return wrapped, 0.6 + 0.2 * wrapped.count("\n")


def _finish(grid: _Grid, handles: list, notes: Sequence[str], title: str) -> Figure:
    """The legend at the bottom, the notes above it, the title (from :func:`_title`) on top."""
    _bottom_legend(grid, handles)
    _write_notes(grid.fig, notes, grid.width, grid.height, grid.below - 0.05)
    grid.fig.suptitle(title, fontsize=FONT + 2, y=1 - 0.12 / grid.height)
    return grid.fig


def _constant_probability(ds: xr.Dataset, s: str) -> float:
    """``P(capacity < x)`` of a scenario without a finite capacity (the same at every x): the
    fraction of its decided samples that are infeasible (NaN: none decided)."""
    counts = sample_counts(ds, s)
    decided = counts.get("unbounded", 0) + counts.get("infeasible", 0) + counts.get("optimal", 0)
    return counts.get("infeasible", 0) / decided if decided else math.nan


# ---------------------------------------------------------------------------- fragility
def fragility_figure(ds: xr.Dataset) -> Figure:
    """Fragility curves: ``P(capacity < x)`` against the intensity ``x``, one row per
    capacity kind.

    Left: each scenario's curve (``fragility_*``, gid ``"fragility:<scenario>"``) with its
    band, the threshold a vertical line and the failure probability there a point with its
    interval (gid ``"pf:<scenario>"``); a scenario without a finite capacity is a
    horizontal dashed line at its constant probability. Right (when the scenarios differ
    in a numeric coordinate, or their settlement cases in one number: :func:`_sweeps`):
    ``failure_probability`` with its interval against it, one line per value of the others
    (gid ``"pf_sweep:<axis label>:<k>"``). At most :data:`MAX_CURVES` scenarios on the left.
    """
    names = scenarios(ds)
    drawn, left_out = drawn_scenarios(ds, MAX_CURVES)
    threshold = _threshold(ds)
    kinds = _kinds(ds, names)
    axes_of = _sweeps(ds, names)
    colours = dict(zip(drawn, _palette(len(drawn))))
    handles: list = [Line2D([], [], color=colours[s], marker=MARKERS[k % len(MARKERS)], markersize=4, linewidth=1.3,
                            label=s) for k, s in enumerate(drawn)]
    handles += [Patch(facecolor="#777777", alpha=BAND_ALPHA, label=f"band: {_interval_name(ds)}"),
                Line2D([], [], color="#555555", linestyle=":", linewidth=1.0,
                       label=f"threshold {threshold:g} (failure: capacity < {threshold:g})")]
    if "lambda_multiplies" in ds and "lambda_max" in kinds and len(set(map(str, ds["lambda_multiplies"].values))) == 1:
        loads = [str(ds["lambda_multiplies"].values[0]).replace("lambda", "λ")]
    else:
        loads = []
    notes = _notes(ds, names, [left_out, *loads])
    w, h = 3.8, 2.7
    width = 0.8 + (1 + len(axes_of)) * w + len(axes_of) * 0.8 + 0.2
    legend_h = _legend_height([hd.get_label() for hd in handles], width)
    below = legend_h + _notes_height(notes, width) + 0.1
    title, top = _title(f"{_study(ds)}: probability of collapse P(capacity < x)", width)
    grid = _Grid(len(kinds), 1 + len(axes_of), w, h, left=0.8, wspace=0.8, hspace=0.75, top=top, bottom=0.55,
                 below=below)
    for r, (kind, members) in enumerate(kinds.items()):
        ax = grid.axes[r][0]
        for k, s in enumerate(m for m in members if m in colours):
            _fragility_curve(ax, ds, s, colours[s], MARKERS[k % len(MARKERS)], threshold)
        ax.axvline(threshold, color="#555555", linestyle=":", linewidth=1.0)
        ax.set_ylim(-0.02, 1.02)
        ax.set_xlabel(_wrap(f"x: {capacity_label(kind)}", w), fontsize=FONT)
        ax.set_ylabel("P(capacity < x)", fontsize=FONT)
        ax.grid(True, linewidth=0.3, alpha=0.6)
        if len(kinds) > 1:
            ax.set_title(_wrap(f"capacity: {kind}", w), fontsize=FONT, loc="left")
        for c, (label, values, others) in enumerate(axes_of):
            _pf_sweep(grid.axes[r][c + 1], ds, [s for s in members if s in values], label, values, others)
    return _finish(grid, handles, notes, title)


def _fragility_curve(ax: Axes, ds: xr.Dataset, s: str, colour: str, marker: str, threshold: float) -> None:
    x = np.asarray(value(ds, "fragility_intensity", s, ["fragility"]), dtype=float)
    if np.isfinite(x).any():
        p, lo, hi = (np.asarray(value(ds, v, s, ["fragility"]), dtype=float)
                     for v in ("fragility_probability", "fragility_low", "fragility_high"))
        ax.fill_between(x, lo, hi, color=colour, alpha=BAND_ALPHA, linewidth=0)
        ax.plot(x, p, color=colour, linewidth=1.3, gid=f"fragility:{s}")
    else:  # no finite capacity: the same probability at every intensity
        const = _constant_probability(ds, s)
        if math.isfinite(const):
            ax.axhline(const, color=colour, linestyle="--", linewidth=1.3, gid=f"fragility:{s}")
    pf = float(value(ds, "failure_probability", s))
    if math.isfinite(pf) and math.isfinite(threshold):
        lo, hi = float(value(ds, "failure_low", s)), float(value(ds, "failure_high", s))
        bars = ax.errorbar([threshold], [pf], yerr=[[pf - lo], [hi - pf]], color=colour, marker=marker, markersize=4,
                           capsize=2.5, linewidth=1.0)
        bars.lines[0].set_gid(f"pf:{s}")


def _sweeps(ds: xr.Dataset, names: Sequence[str]) -> list[tuple[str, dict[str, float], dict[str, tuple]]]:
    """What the failure probability is drawn against: ``(axis label, scenario -> value,
    scenario -> the key of its line)``, one per numeric coordinate the scenarios differ in
    (:func:`tce.plot.data.sweep_axes`; a line per value of the others and settlement case),
    else the one number their settlement cases differ by
    (:func:`tce.plot.data.settlement_parameter`)."""
    numeric = sweep_axes(ds, names)
    case = {s: str(value(ds, "settlement", s)) if "settlement" in ds.coords else "" for s in names}
    out = []
    for p in numeric:
        unit = SWEPT.get(p, "m" if p == "load_x" else "")
        values = {s: float(value(ds, p, s)) for s in names}
        others = {s: (case[s], *((q, float(value(ds, q, s))) for q in numeric if q != p)) for s in names}
        out.append((p + (f" ({unit})" if unit else ""), values, others))
    moved = settlement_parameter(ds, names) if not numeric else None
    if moved:
        out.append((f"settlement case: {moved[0]}", moved[1], {s: ("",) for s in names}))
    return out


def _pf_sweep(ax: Axes, ds: xr.Dataset, members: Sequence[str], label: str, values: dict[str, float],
              others: dict[str, tuple]) -> None:
    """``failure_probability`` with its interval against ``values``, a line per key of
    ``others`` (gid ``"pf_sweep:<label>:<k>"``)."""
    lines: dict[tuple, list[str]] = {}
    for s in members:
        lines.setdefault(others[s], []).append(s)
    palette = _palette(len(lines))
    undecided = []
    cases = {key[0] for key in lines}
    for k, (key, ss) in enumerate(lines.items()):
        ss = sorted(ss, key=lambda s: values[s])
        x = np.array([values[s] for s in ss])
        pf, lo, hi = (np.array([float(value(ds, v, s)) for s in ss])
                      for v in ("failure_probability", "failure_low", "failure_high"))
        undecided += [s for s, v in zip(ss, pf) if not math.isfinite(v)]
        parts = ([key[0]] if len(cases) > 1 else []) + [f"{q} = {v:g}" for q, v in key[1:]]
        bars = ax.errorbar(x, pf, yerr=[pf - lo, hi - pf], color=palette[k], linestyle=LINESTYLES[k % len(LINESTYLES)],
                           marker=MARKERS[k % len(MARKERS)], markersize=3.5, capsize=2.5, linewidth=1.2,
                           label=", ".join(parts) or None)
        bars.lines[0].set_gid(f"pf_sweep:{label}:{k}")
    ax.set_ylim(-0.02, 1.02)
    ax.set_xlabel(label, fontsize=FONT)
    ax.set_ylabel("P(failure) at the threshold", fontsize=FONT)
    ax.grid(True, linewidth=0.3, alpha=0.6)
    if len(lines) > 1:
        ax.legend(fontsize=FONT - 1, frameon=False, loc="best")
    if undecided:
        ax.text(0.02, 0.97, _wrap(f"no estimate (no decided sample): {join_names(undecided, 3)}", 3.6),
                transform=ax.transAxes, ha="left", va="top", fontsize=FONT - 1, color=NOTE_COLOUR, bbox=NOTE_BOX)


# ---------------------------------------------------------------------------- histograms
def capacity_samples_figure(ds: xr.Dataset) -> Figure:
    """The histogram of each scenario's finite sampled capacities (gid ``"samples:<scenario>"``),
    one panel per scenario (at most :data:`MAX_PANELS`), the threshold a vertical line; the
    legend of each panel counts the samples of each status (``+inf``, ``-inf``, NaN) and
    those below the threshold."""
    drawn, left_out = drawn_scenarios(ds, MAX_PANELS)
    threshold = _threshold(ds)
    ncols = min(3, len(drawn))
    nrows = math.ceil(len(drawn) / ncols)
    w, h = 3.2, 2.2
    width = 0.8 + ncols * w + (ncols - 1) * 0.7 + 0.2
    notes = [left_out] if left_out else []
    handles: list = [Line2D([], [], color="#555555", linestyle=":", linewidth=1.0,
                            label=f"threshold {threshold:g} (failure: capacity < {threshold:g})")]
    legend_h = _legend_height([hd.get_label() for hd in handles], width)
    n = int(ds.sizes.get("sample", 0))
    title, top = _title(f"{_study(ds)}: sampled capacities ({n} samples per scenario)", width)
    grid = _Grid(nrows, ncols, w, h, left=0.8, wspace=0.7, hspace=0.85, top=top, bottom=0.55,
                 below=legend_h + _notes_height(notes, width) + 0.1)
    colours = _palette(len(drawn))
    for k, s in enumerate(drawn):
        ax = grid.axes[k // ncols][k % ncols]
        v = np.asarray(value(ds, "sample_capacity", s), dtype=float)
        finite = v[np.isfinite(v)]
        counts = sample_counts(ds, s)
        entries = []
        if finite.size:
            ax.hist(finite, bins=min(40, max(5, int(math.sqrt(finite.size)))), color=colours[k], alpha=0.6,
                    gid=f"samples:{s}")
            below = int((finite < threshold).sum())
            entries.append(f"finite: {finite.size} ({below} below the threshold)")
        else:
            ax.text(0.5, 0.5, "no finite capacity", transform=ax.transAxes, ha="center", va="center",
                    fontsize=FONT, color=NOTE_COLOUR)
            ax.set_yticks([])
        symbol = {"unbounded": "+inf, survive", "infeasible": "-inf, fail", "numerical": "NaN, left out"}
        entries += [f"{w_}: {n} ({symbol.get(w_, 'counted apart')})" for w_, n in counts.items() if w_ != "optimal"]
        ax.axvline(threshold, color="#555555", linestyle=":", linewidth=1.0)
        ax.legend(handles=[Patch(facecolor="none", edgecolor="none", label=e) for e in entries], fontsize=FONT - 1,
                  loc="upper right", handlelength=0, handletextpad=0, framealpha=0.85, edgecolor="none")
        kind = text(ds, "capacity_kind", s, "lambda_max")
        ax.set_xlabel(_wrap(f"capacity: {capacity_label(kind)}", w), fontsize=FONT - 0.5)
        ax.set_ylabel("samples", fontsize=FONT)
        ax.set_title(_wrap(s, w), fontsize=FONT, loc="left")
        ax.grid(True, linewidth=0.3, alpha=0.6)
    for k in range(len(drawn), nrows * ncols):
        grid.axes[k // ncols][k % ncols].set_visible(False)
    return _finish(grid, handles, notes, title)


# ---------------------------------------------------------------------------- sensitivity
def sensitivity_figure(ds: xr.Dataset) -> Figure:
    """Horizontal bars of ``sensitivity`` per variable, one colour per scenario (at most
    :data:`MAX_CURVES`; gid ``"sensitivity:<scenario>"``), the method in the title; a second
    panel of FORM's ``form_alpha`` where present (gid ``"alpha:<scenario>"``)."""
    drawn, left_out = drawn_scenarios(ds, MAX_CURVES)
    variables = [str(v) for v in ds["variable"].values]
    method = str(ds.attrs.get("sensitivity_method", "sensitivity"))
    panels = [("sensitivity", f"{method} of the capacity\n(> 0: the capacity grows with the variable)")]
    if "form_alpha" in ds:
        panels.append(("form_alpha", "FORM importance factor α at the design point\n"
                                     "(> 0: raising the variable lowers the capacity)"))
    colours = _palette(len(drawn))
    handles: list = [Patch(facecolor=colours[k], label=s) for k, s in enumerate(drawn)]
    undefined = [s for s in drawn if not np.isfinite(np.asarray(value(ds, "sensitivity", s), dtype=float)).any()]
    notes = ([f"sensitivity undefined (no decided sample, or a constant capacity): {join_names(undefined, 6)}"]
             if undefined else []) + _notes(ds, drawn, [left_out])
    w = 3.6
    h = max(1.6, 0.22 * len(variables) * max(1, len(drawn)) ** 0.5 + 0.8)
    left = 0.3 + 0.065 * max(len(v) for v in variables)
    width = left + len(panels) * w + (len(panels) - 1) * 0.5 + 0.2
    legend_h = _legend_height([hd.get_label() for hd in handles], width)
    title, top = _title(f"{_study(ds)}: sensitivity of the capacity ({method})", width)
    grid = _Grid(1, len(panels), w, h, left=left, wspace=0.5, top=top, bottom=0.75,
                 below=legend_h + _notes_height(notes, width) + 0.1)
    y = np.arange(len(variables), dtype=float)
    bar = 0.8 / max(1, len(drawn))
    for c, (var, label) in enumerate(panels):
        ax = grid.axes[0][c]
        for k, s in enumerate(drawn):
            vals = np.asarray(value(ds, var, s, ["variable"]), dtype=float)
            ax.barh(y - 0.4 + (k + 0.5) * bar, np.nan_to_num(vals), height=bar, color=colours[k],
                    gid=f"{'sensitivity' if var == 'sensitivity' else 'alpha'}:{s}")
        ax.axvline(0.0, color="#333333", linewidth=0.6)
        ax.set_xlim(-1.05, 1.05)
        ax.set_yticks(y, variables if c == 0 else [""] * len(variables), fontsize=FONT - 0.5)
        ax.invert_yaxis()
        ax.set_xlabel(label, fontsize=FONT)
        ax.grid(True, axis="x", linewidth=0.3, alpha=0.6)
    return _finish(grid, handles, notes, title)


# ---------------------------------------------------------------------------- convergence
def running_estimate(values: NDArray[np.float64], threshold: float, confidence: float, interval: str,
                     points: int = RUNNING_POINTS) -> tuple[NDArray[np.int64], NDArray[np.float64], NDArray[np.float64],
                                                             NDArray[np.float64]]:
    """The failure-probability estimate of the first ``n`` samples at about ``points``
    log-spaced ``n`` (:func:`tce.analysis.reliability.failure_probability`): ``n``, the
    estimate and its interval (``"wilson"`` or Clopper-Pearson), NaN while no sample is decided."""
    total = len(values)
    ns = np.unique(np.round(np.geomspace(1, max(total, 1), points)).astype(np.int64)) if total else np.array([], int)
    est = [failure_probability(values[:n], threshold, confidence=confidence) for n in ns]
    ci = [e.wilson if interval == "wilson" else e.clopper_pearson for e in est]
    return ns, np.array([e.pf for e in est]), np.array([c[0] for c in ci]), np.array([c[1] for c in ci])


def convergence_figure(ds: xr.Dataset) -> Figure:
    """The running failure-probability estimate against the number of samples (log axis),
    one panel per scenario (at most :data:`MAX_PANELS`; gid ``"running:<scenario>"``), with
    its interval as a band; FORM's ``form_pf`` (dashed, gid ``"form:<scenario>"``) and the
    subset estimate ``subset_pf`` (dash-dotted, gid ``"subset:<scenario>"``) as horizontal
    lines when present. The probability axis is logarithmic when every positive estimate is
    below 0.05 (an estimate of 0 is then not drawn, and said so)."""
    drawn, left_out = drawn_scenarios(ds, MAX_PANELS)
    threshold = _threshold(ds)
    confidence = float(ds.attrs.get("uncertainty_confidence", 0.95))
    interval = str(ds.attrs.get("uncertainty_interval", "clopper-pearson"))
    ncols = min(3, len(drawn))
    nrows = math.ceil(len(drawn) / ncols)
    w, h = 3.2, 2.3
    width = 0.8 + ncols * w + (ncols - 1) * 0.75 + 0.2
    handles: list = [Line2D([], [], color="#000000", linewidth=1.3,
                            label="Monte Carlo estimate of the first n samples"),
                     Patch(facecolor="#000000", alpha=BAND_ALPHA, label=_interval_name(ds))]
    if "form_pf" in ds:
        handles.append(Line2D([], [], color="#D55E00", linestyle="--", linewidth=1.2, label="FORM Φ(−β)"))
    if "subset_pf" in ds:
        handles.append(Line2D([], [], color="#0072B2", linestyle="-.", linewidth=1.2, label="subset simulation"))
    notes = _notes(ds, drawn, [left_out])
    legend_h = _legend_height([hd.get_label() for hd in handles], width)
    title, top = _title(f"{_study(ds)}: P(capacity < {threshold:g}) against the number of samples", width)
    grid = _Grid(nrows, ncols, w, h, left=0.8, wspace=0.75, hspace=0.85, top=top, bottom=0.55,
                 below=legend_h + _notes_height(notes, width) + 0.1)
    for k, s in enumerate(drawn):
        ax = grid.axes[k // ncols][k % ncols]
        values = np.asarray(value(ds, "sample_capacity", s), dtype=float)
        ns, pf, lo, hi = running_estimate(values, threshold, confidence, interval)
        others = {name: float(value(ds, name, s)) for name in ("form_pf", "subset_pf") if name in ds}
        positive = [v for v in [*pf[np.isfinite(pf)], *others.values()] if math.isfinite(v) and v > 0]
        log = bool(positive) and max(positive) < 0.05
        ax.fill_between(ns, lo, hi, color="#000000", alpha=BAND_ALPHA, linewidth=0, step="post")
        ax.plot(ns, np.where(pf > 0, pf, np.nan) if log else pf, color="#000000", linewidth=1.3,
                drawstyle="steps-post", gid=f"running:{s}")
        words = []
        if "form_pf" in others and math.isfinite(others["form_pf"]):
            ax.axhline(others["form_pf"], color="#D55E00", linestyle="--", linewidth=1.2, gid=f"form:{s}")
        elif "form_pf" in others:
            words.append(f"FORM: no estimate ({text(ds, 'form_status', s, '?')})")
        if "subset_pf" in others and math.isfinite(others["subset_pf"]):
            ax.axhline(others["subset_pf"], color="#0072B2", linestyle="-.", linewidth=1.2, gid=f"subset:{s}")
            cov = float(value(ds, "subset_cov", s)) if "subset_cov" in ds else math.nan
            if math.isfinite(cov):
                words.append(f"subset c.o.v. {cov:.2g}")
        elif "subset_pf" in others:
            words.append(f"subset: no estimate ({text(ds, 'subset_status', s, '?')})")
        if not np.isfinite(pf).any():
            words.append("no decided sample: no estimate")
        elif log and (pf[np.isfinite(pf)] == 0).any():
            words.append("estimate 0 before the first failure (not drawn on the log axis)")
        ax.set_xscale("log")
        ax.set_xlim(1, max(2, len(values)))
        if log:
            ax.set_yscale("log")
        else:
            ax.set_ylim(-0.02, 1.02)
        if words:
            ax.text(0.98, 0.97, _wrap("; ".join(words), 0.7 * w), transform=ax.transAxes, ha="right", va="top",
                    fontsize=FONT - 1, color=NOTE_COLOUR, bbox=NOTE_BOX)
        ax.set_xlabel("number of samples n", fontsize=FONT)
        ax.set_ylabel("P(failure)", fontsize=FONT)
        ax.set_title(_wrap(s, w), fontsize=FONT, loc="left")
        ax.grid(True, which="both", linewidth=0.3, alpha=0.5)
    for k in range(len(drawn), nrows * ncols):
        grid.axes[k // ncols][k % ncols].set_visible(False)
    return _finish(grid, handles, notes, title)
