"""Load-position sweeps in a results dataset: the critical position of a moving load.

A study with ``[sweep] load_x`` runs one scenario per position of its moving (scaled,
``on_top``) point loads; the other coordinates along ``scenario`` (the settlement case and
any other swept parameter) split the scenarios into groups, one influence line each. The
critical position of a group is the one with the smallest ``lambda_max`` (positions
whose load path found no limit are left out: the load is carried at any multiplier there).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import xarray as xr

__all__ = ["CriticalPosition", "critical_positions", "position_groups"]


@dataclass(frozen=True)
class CriticalPosition:
    """The critical position of one group of a load-position sweep.

    Attributes
    ----------
    group : str
        The group's other coordinates, ``"settlement=none"`` (``""`` when there are none).
    scenarios : tuple of str
        The group's scenarios, sorted by ``load_x``.
    scenario : str
        The critical scenario ("" when no position has a finite ``lambda_max``).
    load_x : float
        Its position (m; NaN when none).
    lambda_max : float
        Its ``lambda_max`` (NaN when none).
    """

    group: str
    scenarios: tuple[str, ...]
    scenario: str
    load_x: float
    lambda_max: float


def position_groups(ds: xr.Dataset) -> dict[str, list[str]]:
    """Scenarios of a ``load_x`` sweep grouped by their other coordinates, each sorted by
    ``load_x``; the group label is ``"key=value, ..."`` of the coordinates that vary."""
    if "load_x" not in ds.coords:
        raise ValueError("the dataset has no load_x coordinate: not a load-position sweep")
    others = [
        str(k) for k, c in ds.coords.items()
        if c.dims == ("scenario",) and k not in ("scenario", "load_x") and len(np.unique(c.values.astype(str))) > 1
    ]
    groups: dict[str, list[str]] = {}
    for s in ds["scenario"].values:
        at = ds.sel(scenario=s)
        label = ", ".join(f"{k}={at[k].values.item()}" for k in others)
        groups.setdefault(label, []).append(str(s))
    x = {str(s): float(v) for s, v in zip(ds["scenario"].values, ds["load_x"].values)}
    return {g: sorted(v, key=x.__getitem__) for g, v in groups.items()}


def critical_positions(ds: xr.Dataset) -> list[CriticalPosition]:
    """The critical position (smallest finite ``lambda_max``) of every group of a
    ``load_x`` sweep (:func:`position_groups`)."""
    lam = {str(s): float(v) for s, v in zip(ds["scenario"].values, ds["lambda_max"].values)}
    x = {str(s): float(v) for s, v in zip(ds["scenario"].values, ds["load_x"].values)}
    out = []
    for group, scen in position_groups(ds).items():
        finite = [s for s in scen if math.isfinite(lam[s])]
        best = min(finite, key=lam.__getitem__) if finite else ""
        out.append(CriticalPosition(
            group, tuple(scen), best, x[best] if best else float("nan"), lam[best] if best else float("nan")
        ))
    return out
