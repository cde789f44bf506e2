"""A results dataset of an uncertainty study, built without the study integration.

:func:`small_study` runs a small arch study through :func:`tce.study.runner.run_study` (three
thicknesses: a sweep coordinate); :func:`with_uncertainty` adds the variables, coordinates
and attrs of the agreed layout of ``[uncertainty]`` results (issue 39, the plan's
``uq_layout.md``) with xarray: drawn inputs, capacities made from each scenario's nominal
``lambda_max`` and the drawn friction, the failure probability and fragility from
:func:`tce.analysis.reliability.failure_probability`, Spearman sensitivities from scipy, and
stand-in FORM and subset results. A scenario may be given a mode that ends its samples in
other outcome words (every sample unbounded, infeasible or numerical, or some numerical).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import xarray as xr
from scipy import special, stats

from tce.analysis.reliability import failure_probability
from tce.study.runner import run_study
from tce.study.schema import parse_study

STUDY = """
[study]
name = "uq"
[structure]
type = "semicircular_arch"
voussoirs = 6
[material]
friction = 0.6
[loads]
alpha = 0.0
lambda_step = 0.05
tolerance = 1e-3
[sweep]
thickness = [0.2, 0.25, 0.3]
[scenarios.none]
"""
#: the variables' specs as a study file gives them (file order)
VARIABLES = {
    "material.friction": {"distribution": "lognormal", "mean": 0.6, "cov": 0.15},
    "structure.unit_weight": {"distribution": "normal", "mean": 20.0, "std": 1.0},
    "loads.alpha": {"distribution": "uniform", "mean": 0.0, "std": 2.0},
}
#: points of the fragility curves
K = 41
#: the modes a scenario's samples may be given: every sample unbounded, infeasible or
#: numerical, or every tenth numerical
MODES = ("unbounded", "infeasible", "numerical", "some_numerical")


#: the figures of :func:`small_study`: its summary and the uncertainty kinds
KINDS = '["summary", "fragility", "capacity_samples", "sensitivity", "convergence"]'


def small_study(folder: Path, name: str = "uq", kinds: str = KINDS) -> xr.Dataset:
    """The results of :data:`STUDY` run in ``folder`` (about 2 s), the figures ``kinds``."""
    text = STUDY.replace('name = "uq"', f'name = "{name}"') + f"[plots]\nkinds = {kinds}\n"
    report = run_study(parse_study(text, folder / f"{name}.toml"), folder, jobs=1)
    return xr.load_dataset(report.results)


def _fragility(values: np.ndarray, statuses: np.ndarray, confidence: float) -> tuple[np.ndarray, ...]:
    """Intensities spanning the finite capacities (NaN when none is finite) and
    ``P(capacity < x)`` with its Clopper-Pearson interval at each."""
    finite = values[np.isfinite(values)]
    if not finite.size:
        nan = np.full(K, math.nan)
        return nan, nan, nan, nan
    x = np.linspace(0.0, 1.1 * float(finite.max()), K)
    est = [failure_probability(values, xi, statuses, confidence) for xi in x]
    return (x, np.array([e.pf for e in est]), np.array([e.clopper_pearson[0] for e in est]),
            np.array([e.clopper_pearson[1] for e in est]))


def with_uncertainty(ds: xr.Dataset, n: int = 400, seed: int = 0, modes: dict[str, str] | None = None,
                     form: bool = True, subset: bool = True, kind: str = "lambda_max",
                     threshold: float | None = None) -> xr.Dataset:
    """``ds`` with the layout's uncertainty variables (a new dataset; ``ds`` is not changed).

    Parameters
    ----------
    n : int
        Samples.
    modes : dict, optional
        Scenario -> one of :data:`MODES`.
    form, subset : bool
        Add the FORM and subset variables.
    kind : str
        The ``capacity_kind`` of every scenario.
    threshold : float, optional
        Default: the first scenario's nominal lambda_max (a failure probability near 1/2 there).
    """
    modes = modes or {}
    names = [str(s) for s in ds["scenario"].values]
    lam = np.asarray(ds["lambda_max"].values, dtype=float)
    threshold = float(lam[0]) if threshold is None else threshold
    rng = np.random.default_rng(seed)
    keys = list(VARIABLES)
    sigma = math.sqrt(math.log1p(0.15**2))  # the lognormal of mean 0.6, c.o.v. 0.15
    friction = stats.lognorm(s=sigma, scale=0.6 * math.exp(-sigma**2 / 2)).rvs(n, random_state=rng)
    weight = rng.normal(20.0, 1.0, n)
    alpha = rng.uniform(-math.sqrt(3) * 2, math.sqrt(3) * 2, n)
    inputs = np.column_stack([friction, weight, alpha])
    capacity = np.empty((len(names), n))
    status = np.empty((len(names), n), dtype=object)
    for i, name in enumerate(names):
        # the capacity grows with the friction, barely with the unit weight, not with alpha
        capacity[i] = lam[i] * (friction / 0.6) ** 0.8 * (1 + 0.005 * (weight - 20.0))
        status[i] = "optimal"
        mode = modes.get(name)
        if mode == "unbounded":
            capacity[i], status[i] = math.inf, "unbounded"
        elif mode == "infeasible":
            capacity[i], status[i] = -math.inf, "infeasible"
        elif mode == "numerical":
            capacity[i], status[i] = math.nan, "numerical"
        elif mode == "some_numerical":
            capacity[i, ::10], status[i, ::10] = math.nan, "numerical"
    out = ds.copy()
    out = out.assign_coords(sample=np.arange(n), variable=keys, fragility=np.arange(K))
    out["sample_input"] = (("sample", "variable"), inputs)
    out["sample_capacity"] = (("scenario", "sample"), capacity)
    out["sample_status"] = (("scenario", "sample"), status.astype(str))
    out["capacity_kind"] = (("scenario",), np.array([kind] * len(names)))
    estimates = [failure_probability(capacity[i], threshold, status[i].astype(str)) for i in range(len(names))]
    out["failure_probability"] = (("scenario",), np.array([e.pf for e in estimates]))
    out["failure_low"] = (("scenario",), np.array([e.clopper_pearson[0] for e in estimates]))
    out["failure_high"] = (("scenario",), np.array([e.clopper_pearson[1] for e in estimates]))
    out["reliability_index"] = (("scenario",), np.array([e.beta for e in estimates]))
    out["n_failed"] = (("scenario",), np.array([e.failures for e in estimates]))
    out["n_decided"] = (("scenario",), np.array([e.n for e in estimates]))
    out["n_numerical"] = (("scenario",), np.array([e.numerical for e in estimates]))
    sens = np.full((len(names), len(keys)), math.nan)
    for i in range(len(names)):
        ok = ~np.isnan(capacity[i])
        if ok.sum() > 2 and len(np.unique(capacity[i, ok])) > 1:
            sens[i] = [stats.spearmanr(capacity[i, ok], inputs[ok, j]).statistic for j in range(len(keys))]
    out["sensitivity"] = (("scenario", "variable"), sens)
    frag = [_fragility(capacity[i], status[i].astype(str), 0.95) for i in range(len(names))]
    for j, var in enumerate(("fragility_intensity", "fragility_probability", "fragility_low", "fragility_high")):
        out[var] = (("scenario", "fragility"), np.array([f[j] for f in frag]))
    pf = np.array([e.pf for e in estimates])
    if form:
        beta = np.where(np.isnan(pf), math.nan, -special.ndtri(np.clip(pf, 1e-12, 1 - 1e-12)) + 0.05)
        ok = np.array([modes.get(s) is None or modes.get(s) == "some_numerical" for s in names])
        out["form_beta"] = (("scenario",), np.where(ok, beta, math.nan))
        out["form_pf"] = (("scenario",), np.where(ok, special.ndtr(-beta), math.nan))
        out["form_status"] = (("scenario",), np.array(["converged" if o else "numerical" for o in ok]))
        out["form_evaluations"] = (("scenario",), np.array([12] * len(names)))
        point = np.where(ok[:, None], [0.5, 20.5, 0.0], math.nan)
        out["form_design_point"] = (("scenario", "variable"), point)
        # alpha = -grad g / |grad g|: raising the friction raises the capacity, away from failure
        out["form_alpha"] = (("scenario", "variable"), np.where(ok[:, None], [-0.98, -0.2, 0.0], math.nan))
    if subset:
        out["subset_pf"] = (("scenario",), np.minimum(1.1 * pf, 1.0))
        out["subset_cov"] = (("scenario",), np.full(len(names), 0.2))
        out["subset_status"] = (("scenario",), np.array(["converged"] * len(names)))
        out["subset_evaluations"] = (("scenario",), np.array([2800] * len(names)))
    out.attrs.update(uncertainty_method="lhs", uncertainty_seed=seed, uncertainty_samples=n,
                     uncertainty_threshold=threshold, uncertainty_interval="clopper-pearson",
                     uncertainty_confidence=0.95, uncertainty_variables=json.dumps(VARIABLES),
                     sensitivity_method="Spearman rank correlation")
    return out
