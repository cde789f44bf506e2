"""Load-position sweeps in a results dataset: the critical position of a moving load.

A study with ``[sweep] load_x`` runs one scenario per position of its moving (scaled,
``on_top``) point loads; the other coordinates along ``scenario`` (the settlement case and
any other swept parameter) split the scenarios into groups, one influence line each. The
critical position of a group is the one with the smallest ``lambda_max`` (positions
whose load path found no limit are left out: the load is carried at any multiplier there).

A study with ``[loads] critical_position = true`` searches the position instead
(:func:`tce.analysis.critical.critical_position`) and runs each scenario's load path there;
:func:`with_critical` stores the search's answer and scan in the scenario's dataset.
"""

from __future__ import annotations

import json
import logging
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import xarray as xr

if TYPE_CHECKING:
    from ..analysis.critical import CriticalResult
    from ..core.analysis import Analysis
    from ..core.limit import LimitResult
    from ..core.loads import LoadPattern
    from .schema import Scenario

__all__ = ["CriticalPosition", "critical_positions", "position_groups", "search", "with_adequacy", "with_critical"]

log = logging.getLogger(__name__)

#: a process's critical-position searches of the run: search key -> result (most recently used last)
_SEARCHES: dict[str, CriticalResult] = {}
#: searches a process keeps
_KEEP = 8


def search(sc: Scenario, analysis: Analysis, pattern: LoadPattern) -> CriticalResult:
    """The critical-position search of a scenario (or of a job of its samples, which starts
    each sample's search there), run once per process for every scenario with the same
    structure, material, loads and starting grid: the direct limit does not depend on support
    motions (the static theorem), so scenarios that differ only in their settlements (a
    magnitude sweep) share one search. ``analysis`` starts cold (no warm solver), so the
    answer does not depend on which scenario asked first."""
    from ..analysis.critical import critical_position  # here: the plots import this module without the solvers

    key = json.dumps([sc.group, sc.pattern, sc.loads["positions"]], sort_keys=True)
    crit = _SEARCHES.pop(key, None)
    if crit is None:
        crit = critical_position(analysis, pattern, start=sc.loads["positions"])
    else:
        log.debug("scenario %r: the critical position of an earlier scenario with other settlements", sc.name)
    _SEARCHES[key] = crit
    while len(_SEARCHES) > _KEEP:
        _SEARCHES.pop(next(iter(_SEARCHES)))
    return crit


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
    ties : tuple of float
        The other positions of the group whose ``lambda_max`` is the same (within the load
        path's tolerance, :func:`critical_positions`), e.g. mirror positions; the critical
        position is the leftmost of the tied ones.
    """

    group: str
    scenarios: tuple[str, ...]
    scenario: str
    load_x: float
    lambda_max: float
    ties: tuple[float, ...] = ()


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
    ``load_x`` sweep (:func:`position_groups`).

    Positions whose ``lambda_max`` exceeds the smallest by no more than twice the load
    path's tolerance (``[loads] tolerance`` of the study, the width of the bisection
    bracket; 1e-6 relative at least) are tied: the leftmost is the critical position, the
    others are :attr:`CriticalPosition.ties`. The rule does not depend on the order of the
    scenarios (a symmetric structure's mirror positions give one answer on any machine).
    """
    lam = {str(s): float(v) for s, v in zip(ds["scenario"].values, ds["lambda_max"].values)}
    x = {str(s): float(v) for s, v in zip(ds["scenario"].values, ds["load_x"].values)}
    tol = json.loads(ds.attrs.get("loads", "{}")).get("tolerance")
    atol = 2.0 * float(tol or 0.0)  # no tolerance: the path's is 1e-6 of the limit (DEFAULT_RTOL)
    out = []
    for group, scen in position_groups(ds).items():
        finite = [s for s in scen if math.isfinite(lam[s])]
        if not finite:
            out.append(CriticalPosition(group, tuple(scen), "", float("nan"), float("nan")))
            continue
        least = min(lam[s] for s in finite)
        tied = [s for s in finite if lam[s] - least <= max(atol, 2e-6 * abs(least))]  # sorted by load_x
        best = tied[0]
        out.append(CriticalPosition(group, tuple(scen), best, x[best], lam[best], tuple(x[s] for s in tied[1:])))
    return out


def with_critical(ds: xr.Dataset, crit: CriticalResult) -> xr.Dataset:
    """A one-scenario dataset with the critical-position search's answer and its scan
    (``critical_*`` and ``scan_x``/``scan_lambda`` along ``scan``, ``docs/results.md``)."""
    one = ("scenario",)
    return ds.assign(
        critical_x=(one, [crit.critical_x]),
        critical_lambda=(one, [crit.lambda_max]),
        critical_status=(one, np.asarray([crit.status], dtype=object)),
        critical_ties=(one, np.asarray([", ".join(f"{t:.6g}" for t in crit.ties)], dtype=object)),
        critical_solves=(one, [crit.n_solves]),
        critical_xtol=(one, [crit.xtol]),
        scan_x=(("scenario", "scan"), crit.x[None]),
        scan_lambda=(("scenario", "scan"), crit.lam[None]),
    ).assign_coords(scan=np.arange(len(crit.x)))


def with_adequacy(
    ds: xr.Dataset, limit: LimitResult, pattern: LoadPattern, dead_factor: float, live_factor: float
) -> xr.Dataset:
    """A one-scenario dataset with the adequacy factor (``[assessment]``): the factored
    direct limit's ``lambda_max`` (NaN unless optimal, inf when unbounded) and status, the
    partial factors, and the vehicles' names and total loads (kN) for the assessment's
    wording."""
    one = ("scenario",)
    vehicles = "; ".join(f"{v.label} ({v.total:g} kN)" for v in pattern.vehicle if v.scaled)
    value = limit.lambda_max if limit.status in ("optimal", "unbounded") else float("nan")
    return ds.assign(
        adequacy_factor=(one, [value]),
        adequacy_status=(one, np.asarray([limit.status], dtype=object)),
        assessed_vehicles=(one, np.asarray([vehicles], dtype=object)),
        dead_factor=(one, [float(dead_factor)]),
        live_factor=(one, [float(live_factor)]),
    )
