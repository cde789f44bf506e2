"""The capacity of a structure against the position of a moving load (an influence line).

A load-position sweep (``[sweep] load_x``, ``docs/studies.md``) runs one load path per
position of its moving live point loads. :func:`influence_line` draws ``lambda_max`` (the
multiplier of the live load at collapse: for a 1 kN load, the collapse load in kN) against
the position, one line per group of the other coordinates (e.g. per settlement case), the
critical position of each marked (:func:`tce.study.positions.critical_positions`); the
mechanism and the states at the critical positions are the other figures of the study
(:mod:`tce.plot.output` draws those scenarios by default).
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from ..study.positions import critical_positions
from .figures import COLOURS, LINESTYLES, MARKERS

__all__ = ["critical_scenarios", "influence_line"]


def critical_scenarios(ds: xr.Dataset) -> list[str]:
    """The critical scenario of every group of a load-position sweep, in dataset order (the
    scenarios the per-scenario figures of :func:`tce.plot.figures.write_figures` show; a
    group without a finite lambda_max shows its first position)."""
    chosen = {c.scenario or c.scenarios[0] for c in critical_positions(ds)}
    return [str(s) for s in ds["scenario"].values if str(s) in chosen]


def influence_line(ds: xr.Dataset) -> Figure:
    """lambda_max against the position of the moving load, and the mechanism at the critical one.

    Parameters
    ----------
    ds : xarray.Dataset
        Results of a load-position sweep (a ``load_x`` coordinate along ``scenario``).

    Returns
    -------
    Figure
        One axes: one line per group (gid ``"capacity:<group>"``), its critical position a
        star (gid ``"critical:<group>"``), positions where the load path found no limit a
        triangle at the top (gid ``"no_limit:<group>"``), positions capped below their collapse
        load a downward triangle (gid ``"capped:<group>"``).
    """
    crit = critical_positions(ds)
    fig = Figure(figsize=(7.0, 5.0))
    ax = fig.add_axes((0.11, 0.24, 0.85, 0.68))
    ax.ticklabel_format(useOffset=False)
    x_all = {str(s): float(v) for s, v in zip(ds["scenario"].values, ds["load_x"].values)}
    lam_all = {str(s): float(v) for s, v in zip(ds["scenario"].values, ds["lambda_max"].values)}
    outcome = {str(s): str(v) for s, v in zip(ds["scenario"].values, ds["outcome"].values)}
    handles, lines = [], []
    for i, c in enumerate(crit):
        colour, style, marker = COLOURS[i % len(COLOURS)], LINESTYLES[i % len(LINESTYLES)], MARKERS[i % len(MARKERS)]
        name = c.group or "λmax"
        x = np.array([x_all[s] for s in c.scenarios])
        lam = np.array([lam_all[s] for s in c.scenarios])
        ax.plot(x, lam, color=colour, linestyle=style, marker=marker, markersize=4, linewidth=1.4,
                gid=f"capacity:{c.group}")
        handles.append(Line2D([], [], color=colour, linestyle=style, marker=marker, markersize=4, label=name))
        for kind, mark in (("no_limit", "^"), ("capped", "v")):
            top = np.array([outcome[s] == kind for s in c.scenarios])
            if top.any():
                ax.plot(x[top], np.full(top.sum(), 0.97), transform=ax.get_xaxis_transform(), linestyle="none",
                        marker=mark, color=colour, markerfacecolor="white", gid=f"{kind}:{c.group}")
        if c.scenario:
            ax.plot([c.load_x], [c.lambda_max], linestyle="none", marker="*", markersize=15, color=colour,
                    markeredgecolor="black", zorder=5, gid=f"critical:{c.group}")
            lines.append(f"{c.group + ': ' if c.group else ''}x = {c.load_x:.4g} m, λmax = {c.lambda_max:.4g}")
    if any(outcome[s] == "no_limit" for c in crit for s in c.scenarios):
        handles.append(Line2D([], [], linestyle="none", marker="^", color="black", markerfacecolor="white",
                              label="no limit (direct limit unbounded: carried at any λ)"))
    if any(outcome[s] == "capped" for c in crit for s in c.scenarios):
        handles.append(Line2D([], [], linestyle="none", marker="v", color="black", markerfacecolor="white",
                              label="capped: lambda_cap below the collapse load (see lambda_direct)"))
    handles.append(Line2D([], [], linestyle="none", marker="*", markersize=12, color="grey", markeredgecolor="black",
                          label="critical position (smallest λmax)"))
    if lines:
        ax.text(0.5, 0.96, "critical position\n" + "\n".join(lines), transform=ax.transAxes, ha="center", va="top",
                fontsize=8, bbox=dict(boxstyle="round", facecolor="white", edgecolor="#9a9a9a", alpha=0.9))
    finite = [v for v in lam_all.values() if math.isfinite(v)]
    ax.set_ylim(0.0, 1.15 * max(finite) if finite else 1.0)
    ax.set_xlabel("position x of the moving live load (m)")
    ax.set_ylabel("λmax: live-load multiplier at collapse (–)")
    ax.set_title("capacity against load position (influence line)", fontsize=10)
    ax.grid(True, linewidth=0.3, alpha=0.6)
    fig.legend(handles=handles, loc="lower center", bbox_to_anchor=(0.5, 0.0), ncols=min(len(handles), 3), fontsize=8,
               frameon=False)
    return fig
