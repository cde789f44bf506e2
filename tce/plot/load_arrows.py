"""Arrows of the declared point and distributed loads of a scenario (``load_point``,
``load_force``, ``load_scaled`` of a results dataset, ``docs/results.md``).

Each arrow ends at its point of application (it pushes on the block). On a 3D view an
arrow has the resultants' scale (``1 kN = s m``) and the force of the drawn step (a live
load times lambda); on a line of thrust, without a force scale, every arrow has one length.
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib.axes import Axes
from matplotlib.lines import Line2D
from numpy.typing import NDArray

from .data import value

__all__ = ["LOAD_COLOUR", "declared_loads", "draw_loads_2d", "draw_loads_3d"]

LOAD_COLOUR = "#009E73"  # Okabe-Ito bluish green: apart from resultants (red) and hinges (blue)
ARROW_FRACTION_2D = 0.12  # length of the load arrows on a line of thrust, fraction of the size


def declared_loads(ds: xr.Dataset, scenario: str) -> tuple[NDArray, NDArray, NDArray] | None:
    """Points (k, 3) m, forces (k, 3) kN at lambda = 1 and live flags (k,) of a scenario's
    loads (padding dropped); None when the dataset has none."""
    if "load_point" not in ds:
        return None
    p = np.asarray(value(ds, "load_point", scenario, ["load", "xyz"]), dtype=float)
    f = np.asarray(value(ds, "load_force", scenario, ["load", "xyz"]), dtype=float)
    live = np.asarray(value(ds, "load_scaled", scenario), dtype=float)
    ok = np.all(np.isfinite(p), axis=1) & np.all(np.isfinite(f), axis=1)
    return (p[ok], f[ok], live[ok] > 0.5) if ok.any() else None


def draw_loads_3d(
    ax: Axes, ds: xr.Dataset, scenario: str, lam: float, scale: float
) -> tuple[list[Line2D], NDArray[np.float64]]:
    """Arrows of the loads at multiplier ``lam`` to ``scale`` (m per kN) on a 3D axes.

    Returns the legend handles (none when nothing is drawn) and the arrows' tails (k, 3),
    for the axes limits. Gid ``"loads"``.
    """
    loads = declared_loads(ds, scenario)
    if loads is None or scale <= 0:
        return [], np.empty((0, 3))
    p, f, live = loads
    f = np.where(live[:, None], lam * f, f)
    drawn = np.linalg.norm(f, axis=1) > 0
    if not drawn.any():
        return [], np.empty((0, 3))
    vec = f[drawn] * scale
    tails = p[drawn] - vec
    ax.quiver(*tails.T, *vec.T, color=LOAD_COLOUR, linewidth=1.8, arrow_length_ratio=0.25, zorder=5, gid="loads")
    handle = Line2D([], [], color=LOAD_COLOUR, linewidth=1.8, marker=">", markersize=5,
                    label=f"applied load (live ones × λ; 1 kN = {scale:.3g} m)")
    return [handle], tails


def draw_loads_2d(ax: Axes, ds: xr.Dataset, scenario: str, size: float) -> NDArray[np.float64]:
    """Arrows (x-z projection, one length: ``ARROW_FRACTION_2D * size``) of the loads, live
    ones solid and fixed ones dashed, labelled for the legend. Returns the tails (k, 2) (x, z)
    for the axes limits. Gid ``"loads"``."""
    loads = declared_loads(ds, scenario)
    if loads is None:
        return np.empty((0, 2))
    p, f, live = loads
    d = f[:, [0, 2]]
    n = np.linalg.norm(d, axis=1)
    tails = []
    for kind, sel, style in (("live load", live, "-"), ("fixed load", ~live, "--")):
        keep = sel & (n > 0)
        for i in np.flatnonzero(keep):
            tip = p[i, [0, 2]]
            tails.append(tip - ARROW_FRACTION_2D * size * d[i] / n[i])
            ax.annotate("", xy=tip, xytext=tails[-1], gid="loads",
                        arrowprops=dict(arrowstyle="-|>", color=LOAD_COLOUR, linewidth=1.6, linestyle=style))
        if keep.any():
            ax.plot([], [], color=LOAD_COLOUR, linestyle=style, linewidth=1.6, label=f"{kind} (direction)")
    return np.array(tails).reshape(-1, 2)
