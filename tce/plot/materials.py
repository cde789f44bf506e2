"""Figures of the material studies: lambda_max against a swept strength or friction.

:func:`bracket_figure` draws, for a study that sweeps ``friction``, ``compressive_strength``,
``cohesion`` or ``tensile_strength``, the direct (associative) ``lambda_max`` of every
scenario against the swept value, one line per settlement case and direction. When the
material's flow is non-associative (``lambda_nonassoc`` in the dataset) the bracket is
shaded between the associative value (upper) and the non-associative estimate (lower);
scenarios whose scheme did not converge are marked and left out of the lower line.
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib.figure import Figure

from .figures import COLOURS, MARKERS

__all__ = ["SWEPT", "bracket_figure"]

#: swept material parameters, in the order one is chosen for the horizontal axis
SWEPT = ("friction", "compressive_strength", "cohesion", "tensile_strength")
_LABELS = {
    "friction": "friction coefficient $\\mu$",
    "compressive_strength": "compressive strength $f_c$ (kN/m$^2$)",
    "cohesion": "cohesion $c$ (kN/m$^2$)",
    "tensile_strength": "tensile strength $f_t$ (kN/m$^2$)",
}


def _swept(ds: xr.Dataset) -> str | None:
    """The first material parameter that takes more than one value across the scenarios."""
    for name in SWEPT:
        if name in ds.coords and ds[name].dims == ("scenario",) and len(np.unique(ds[name].values)) > 1:
            return name
    return None


def bracket_figure(ds: xr.Dataset) -> Figure | None:
    """lambda_max against the swept material parameter, with the non-associative bracket.

    Returns None when the study sweeps no material parameter.
    """
    x_name = _swept(ds)
    if x_name is None:
        return None
    x = ds[x_name].values.astype(float)
    assoc = ds["lambda_direct"].values.astype(float)
    nonassoc = ds["lambda_nonassoc"].values.astype(float) if "lambda_nonassoc" in ds else None
    status = ds["nonassoc_status"].values.astype(str) if "nonassoc_status" in ds else None
    groups: dict[str, list[int]] = {}
    for i in range(ds.sizes["scenario"]):
        key = f"{ds['settlement'].values[i]}" + (f", alpha {float(ds['alpha'].values[i]):g} deg" if "alpha" in ds.coords else "")
        groups.setdefault(key, []).append(i)
    fig = Figure(figsize=(6.4, 4.4), layout="constrained")
    ax = fig.add_subplot()
    for g, (key, idx) in enumerate(groups.items()):
        idx = np.array(idx)[np.argsort(x[idx])]
        colour, marker = COLOURS[g % len(COLOURS)], MARKERS[g % len(MARKERS)]
        label = key if len(groups) > 1 else None
        ax.plot(x[idx], assoc[idx], color=colour, marker=marker, linestyle="-",
                label=f"associative{f' ({label})' if label else ''}")
        if nonassoc is not None and status is not None:
            ok = idx[status[idx] == "converged"]
            ax.plot(x[ok], nonassoc[ok], color=colour, marker=marker, linestyle="--", markerfacecolor="white",
                    label=f"non-associative{f' ({label})' if label else ''}")
            if len(ok):
                ax.fill_between(x[ok], nonassoc[ok], assoc[ok], color=colour, alpha=0.15, linewidth=0)
            bad = idx[status[idx] != "converged"]
            if len(bad):
                ax.plot(x[bad], assoc[bad], color=colour, linestyle="none", marker="x", markersize=9,
                        label="non-associative scheme did not converge")
    if np.all(x > 0) and x.max() > 50 * x.min():
        ax.set_xscale("log")  # strengths swept over decades
    ax.set_xlabel(_LABELS[x_name])
    ax.set_ylabel("load multiplier at the limit $\\lambda_{max}$")
    title = "lambda_max against " + x_name.replace("_", " ")
    if nonassoc is not None:
        title += ": associative (upper) and non-associative bracket"
    ax.set_title(title, fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="best")
    return fig
