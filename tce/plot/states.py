"""States a figure draws that the results file does not hold, solved on demand.

A run solves the multipliers of its ``[plots] steps`` with each scenario
(:func:`tce.study.runner.with_drawn_states`). A state asked for later (``tce plot
--step 0.1``, a changed ``[plots]`` table) is solved here, never interpolated: the analysis
is rebuilt from the dataset (the ``assembly`` attr and the study text in the ``study``
attr) and the new steps are merged into a copy of the dataset; the file is not changed.
"""

from __future__ import annotations

import json
import logging
import tomllib
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import xarray as xr

from ..study.names import missing_lambdas
from .data import assembly, optimal_steps, scenarios, value

if TYPE_CHECKING:
    from ..study.schema import Study

__all__ = ["missing_states", "solve_states"]

log = logging.getLogger(__name__)


def missing_states(ds: xr.Dataset, names: Sequence[str], lams: Sequence[float]) -> dict[str, list[float]]:
    """Multipliers of ``lams`` not solved for each scenario of ``names`` that may be admissible
    (:func:`tce.study.names.missing_lambdas`; none for a scenario without an optimal step)."""
    out = {}
    for s in names:
        if not optimal_steps(ds, s).size:
            continue
        lam = value(ds, "lam", s).astype(float)
        upper = float(value(ds, "lambda_upper", s)) if "lambda_upper" in ds else float("nan")
        todo = missing_lambdas(lam[np.isfinite(lam)].tolist(), lams, upper)
        if todo:
            out[s] = todo
    return out


def _study(ds: xr.Dataset) -> Study:
    """The study stored in ``ds``, the stored assembly standing for its structure (a block
    file's relative path would not resolve from here)."""
    from ..study.schema import GEOMETRY_SWEEPS, Study, StudyFile  # the parser: only when states are solved

    text = str(ds.attrs.get("study", ""))
    if not text:
        raise ValueError("the dataset holds no study text ('study' attr): states cannot be solved again")
    spec = StudyFile.model_validate(tomllib.loads(text))
    seed = {}
    if not any(getattr(spec.sweep, k) for k in GEOMETRY_SWEEPS):
        seed[json.dumps(spec.structure.model_dump(), sort_keys=True)] = assembly(ds)
    return Study(Path("<results>"), text, spec, _assemblies=seed)


def solve_states(ds: xr.Dataset, todo: Mapping[str, Sequence[float]]) -> xr.Dataset:
    """``ds`` with the states ``todo`` (scenario -> multipliers) solved and merged in.

    Returns
    -------
    xarray.Dataset
        A copy with longer ``step`` (padded as in ``merge_scenarios``), each scenario's
        steps sorted by lambda; a multiplier found inadmissible is stored ``infeasible``.

    Raises
    ------
    ValueError
        The dataset holds no study text, or a scenario is not in it.
    """
    todo = {s: list(v) for s, v in todo.items() if v}
    if not todo:
        return ds
    from ..core.analysis import Analysis  # the solvers: only when states are solved
    from ..study.results import steps_dataset
    from ..study.schema import build_material

    study = _study(ds)
    scenarios_ = {sc.name: sc for sc in study.scenarios()}
    analyses: dict[str, "Analysis"] = {}
    parts = []
    n_itf = ds.sizes["interface"]
    for s, lams in todo.items():
        if s not in scenarios_:
            raise ValueError(f"scenario {s!r} is not in the study text of the dataset")
        sc = scenarios_[s]
        if sc.group not in analyses:
            analyses[sc.group] = Analysis(study.assembly(sc.structure), build_material(sc.material))
        solve = analyses[sc.group].path(settlements=sc.settlements, loads=sc.loads_pattern)
        results = [solve(lam) for lam in lams]
        log.info("solved %s at lambda = %s for the figures", s, ", ".join(f"{x:g}" for x in lams))
        parts.append(steps_dataset(s, results, n_itf))
    return _insert_steps(ds, parts)


def _insert_steps(ds: xr.Dataset, parts: Sequence[xr.Dataset]) -> xr.Dataset:
    """Append the steps of ``parts`` (one scenario each) to ``ds`` and sort every scenario's
    steps by ``lam`` (NaN last)."""
    names = scenarios(ds)
    n_old = ds.sizes["step"]
    n_new = n_old + max(p.sizes["step"] for p in parts)
    stepped = [k for k, v in ds.data_vars.items() if "step" in v.dims]
    arrays = {}
    for k in stepped:
        v = ds[k].transpose("scenario", "step", ...)
        text = v.dtype.kind in "OSU"
        a = np.full((len(names), n_new) + v.shape[2:], "" if text else np.nan, dtype=object if text else float)
        a[:, :n_old] = v.values
        arrays[k] = (v.dims, a)
    for p in parts:
        i = names.index(str(p["scenario"].values[0]))
        m = p.sizes["step"]
        for k in stepped:
            if k in p:
                arrays[k][1][i, n_old:n_old + m] = p[k].transpose("scenario", "step", *arrays[k][0][2:]).values[0]
    lam = arrays["lam"][1].astype(float)
    order = np.argsort(np.where(np.isfinite(lam), lam, np.inf), axis=1, kind="stable")
    out = ds.drop_vars(stepped).assign_coords(step=np.arange(n_new))
    for k, (dims, a) in arrays.items():
        idx = order.reshape(order.shape + (1,) * (a.ndim - 2))
        out[k] = (dims, np.take_along_axis(a, idx, axis=1), ds[k].attrs)
    return out
