"""The capacity of a structure against the position of a moving load (an influence line).

A load-position sweep (``[sweep] load_x``, ``docs/studies.md``) runs one load path per
position of its moving live point loads. :func:`influence_line` draws ``lambda_max`` (the
multiplier of the live load at collapse: for a 1 kN load, the collapse load in kN) against
the position, one line per group of the other coordinates, the critical position of each
marked (:func:`tce.study.positions.critical_positions`).
"""

from __future__ import annotations

import math
import textwrap
from collections import Counter
from dataclasses import dataclass

import numpy as np
import xarray as xr
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from ..study.outcomes import outcome_words
from ..study.positions import critical_positions
from .data import study_cap, value
from .figures import COLOURS, LINESTYLES, MARKERS, NOTE_COLOUR

__all__ = ["influence_line"]


@dataclass(frozen=True)
class _Curve:
    """One capacity curve: positions, lambda_max, where it is carried at any multiplier,
    its critical position (NaN: none) and tied positions."""

    group: str
    x: np.ndarray
    lam: np.ndarray
    free: np.ndarray
    critical_x: float
    critical_lambda: float
    ties: tuple[float, ...] = ()


def _sweep_curves(ds: xr.Dataset) -> list[_Curve]:
    """The influence lines of a ``load_x`` sweep, one per group."""
    x_all = {str(s): float(v) for s, v in zip(ds["scenario"].values, ds["load_x"].values)}
    lam_all = {str(s): float(v) for s, v in zip(ds["scenario"].values, ds["lambda_max"].values)}
    outcome = {str(s): str(v) for s, v in zip(ds["scenario"].values, ds["outcome"].values)}
    return [
        _Curve(c.group, np.array([x_all[s] for s in c.scenarios]), np.array([lam_all[s] for s in c.scenarios]),
               np.array([outcome[s] == "no_limit" for s in c.scenarios]), c.load_x, c.lambda_max, c.ties)
        for c in critical_positions(ds)
    ]


def _search_curves(ds: xr.Dataset) -> list[_Curve]:
    """The scans of a critical-position search, one per scenario."""
    out = []
    for name in map(str, ds["scenario"].values):
        x, lam = value(ds, "scan_x", name), value(ds, "scan_lambda", name)
        keep = np.isfinite(x)
        x, lam = x[keep], lam[keep]
        ties = str(value(ds, "critical_ties", name))
        out.append(_Curve(
            name, x, np.where(np.isinf(lam), np.nan, lam), np.isinf(lam),
            float(value(ds, "critical_x", name)), float(value(ds, "critical_lambda", name)),
            tuple(float(t) for t in ties.split(",")) if ties else (),
        ))
    return out


def _outcome_words(ds: xr.Dataset, outcome: str) -> str:
    """The words of ``outcome`` for the scenarios of ``ds`` that end with it: a capped path
    with the study's cap and the lowest of their direct limits (each is capped below its own)."""
    direct = ds["lambda_direct"].values[ds["outcome"].values == outcome] if "lambda_direct" in ds else np.array([])
    lowest = float(np.nanmin(direct)) if np.isfinite(direct).any() else math.nan
    words = outcome_words(outcome, direct=lowest, cap=study_cap(ds), lam="λ")
    return words + " (the lowest of theirs)" if outcome == "capped" and direct.size and np.ptp(direct) > 0 else words


def influence_line(ds: xr.Dataset) -> Figure:
    """lambda_max against the position of the moving loads, the critical position marked.

    Parameters
    ----------
    ds : xarray.Dataset
        Results of a load-position sweep (a ``load_x`` coordinate along ``scenario``: one
        line per group of the other coordinates) or of a critical-position search
        (``scan_x``, ``scan_lambda``: one line per scenario, the positions the search
        evaluated).

    Returns
    -------
    Figure
        One axes: one line per group (gid ``"capacity:<group>"``), its critical position a
        star (``"critical:<group>"``), tied positions hollow stars (``"tie:<group>"``),
        positions carried at any multiplier a triangle at the top (``"no_limit:<group>"``);
        the critical positions written beside the axes. When no position has a finite
        lambda_max, the axes say why in words (gid ``"no_lambda"``: each outcome's meaning).
    """
    search = "scan_x" in ds
    curves = _search_curves(ds) if search else _sweep_curves(ds)
    fig = Figure(figsize=(9.0, 5.0))
    ax = fig.add_axes((0.08, 0.12, 0.60, 0.80))
    ax.ticklabel_format(useOffset=False)
    handles, lines = [], []
    for i, c in enumerate(curves):
        colour, style, marker = COLOURS[i % len(COLOURS)], LINESTYLES[i % len(LINESTYLES)], MARKERS[i % len(MARKERS)]
        size = 0 if search else 4  # a search evaluates many positions: a line, no markers
        ax.plot(c.x, c.lam, color=colour, linestyle=style, marker=marker, markersize=size, linewidth=1.2,
                gid=f"capacity:{c.group}")
        handles.append(Line2D([], [], color=colour, linestyle=style, marker=marker, markersize=size,
                              label=c.group or "λmax"))
        if c.free.any():
            ax.plot(c.x[c.free], np.full(c.free.sum(), 0.97), transform=ax.get_xaxis_transform(), linestyle="none",
                    marker="^", color=colour, markerfacecolor="white", gid=f"no_limit:{c.group}")
        if math.isfinite(c.critical_x):
            ax.plot([c.critical_x], [c.critical_lambda], linestyle="none", marker="*", markersize=15, color=colour,
                    markeredgecolor="black", zorder=5, gid=f"critical:{c.group}")
            text = f"x = {c.critical_x:.4g} m, λmax = {c.critical_lambda:.4g}"
            if c.ties:
                ax.plot(list(c.ties), [c.critical_lambda] * len(c.ties), linestyle="none", marker="*", markersize=13,
                        markerfacecolor="white", markeredgecolor=colour, zorder=5, gid=f"tie:{c.group}")
                text += f"\n  tied at x = {', '.join(f'{t:.4g}' for t in c.ties)} m"
            lines.append(f"{c.group}:\n  {text}" if c.group else text)
    if any(c.free.any() for c in curves):
        handles.append(Line2D([], [], linestyle="none", marker="^", color="black", markerfacecolor="white",
                              label="no limit (carried at any λ)"))
    handles.append(Line2D([], [], linestyle="none", marker="*", markersize=12, color="grey", markeredgecolor="black",
                          label="critical position (" + ("found by the search" if search else "smallest λmax") + ")"))
    if any(c.ties for c in curves):
        handles.append(Line2D([], [], linestyle="none", marker="*", markersize=11, markerfacecolor="white",
                              markeredgecolor="grey", label="tied position (same λmax)"))
    title = "critical position" + (" (searched)" if search else " (of the positions run)")
    box = fig.text(0.70, 0.92, title + "\n" + ("\n".join(lines) if lines else "none (no finite λmax)"), ha="left",
                   va="top", fontsize=8, bbox=dict(boxstyle="round", facecolor="white", edgecolor="#9a9a9a"))
    finite = [v for c in curves for v in c.lam if math.isfinite(v)]
    ax.set_ylim(0.0, 1.15 * max(finite) if finite else 1.0)
    if not finite:  # no position has a limit (unbounded, infeasible, numerical...): say why
        xs = np.concatenate([c.x for c in curves])
        if xs.size and np.ptp(xs) > 0:
            ax.set_xlim(xs.min() - 0.05 * np.ptp(xs), xs.max() + 0.05 * np.ptp(xs))
        counts = Counter(map(str, ds["outcome"].values))
        why = "\n".join(textwrap.fill(f"{n} scenario(s) {_outcome_words(ds, o)}", 70) for o, n in sorted(counts.items()))
        ax.text(0.5, 0.5, "no finite λmax at any position:\n" + why, transform=ax.transAxes, ha="center",
                va="center", fontsize=8, color=NOTE_COLOUR, gid="no_lambda")
    ax.set_xlabel("position x of the moving live load" + ("s' reference" if search else "") + " (m)")
    ax.set_ylabel("λmax: live-load multiplier at collapse (–)")
    ax.set_title("capacity against load position" + (" (direct limit at each position)" if search else " (influence line)"),
                 fontsize=10)
    ax.grid(True, linewidth=0.3, alpha=0.6)
    # the legend in the right-hand column, under the critical positions
    renderer = FigureCanvasAgg(fig).get_renderer()
    below = fig.transFigure.inverted().transform(box.get_window_extent(renderer))[0, 1]
    fig.legend(handles=handles, loc="upper left", bbox_to_anchor=(0.695, below - 0.02), ncols=1, fontsize=8,
               frameon=False)
    return fig
