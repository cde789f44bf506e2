"""The sampled capacities of an uncertainty study (``[uncertainty]``, ``docs/reliability.md``).

Keys. A variable of ``[uncertainty.variables]`` is a study key holding a real number
(:meth:`tce.study.Scenario.drawn` sets it; :func:`tce.study.schema.check_uncertainty` refuses,
naming the key, one the study does not have, one that is not a real number, and one whose
smallest or largest drawn value its section refuses).

Jobs. Each scenario keeps its nominal load path; its samples are solved in jobs of ``chunk``
samples (:meth:`tce.study.Study.jobs`: a :class:`tce.study.Scenario` with ``samples = (lo,
hi)``), each written to its own file under ``scenarios/`` and solved cold, with its own
analyses and solvers (:func:`solve_samples`): the capacities depend neither on the runner, the
number of workers, the order nor resuming.

Capacity of a sample (:func:`tce.study.uncertainty.capacity_kind`). Samples that keep the
geometry and the loads' structure (friction, cohesion, tensile strength, the unit weight where
the self-weight is the only fixed load, the assessment's factors), without a fill or a
critical-position search, share one warm solver per job (:class:`tce.analysis.reliability.WarmLimit`,
its base material at the variables' means). Any other sample rebuilds the scenario with its
drawn values through the study's own sections and builders and solves its direct limit
(``lambda_max``), its adequacy factor (:func:`tce.analysis.assessment.adequacy_factor`; with
``[loads] critical_position`` the least over the positions, searched for each sample from the
nominal scenario's critical position) or its settlement capacity
(:func:`tce.analysis.settlement_path.settlement_path` without the lateral capacity). The status
of each solve gives its value (:func:`tce.analysis.reliability.outcome_value`); none is dropped.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Mapping
from dataclasses import replace
from typing import Any

import numpy as np
import xarray as xr
from pydantic import ValidationError

from ..analysis.assessment import adequacy_factor
from ..analysis.critical import critical_position, search_bounds
from ..analysis.reliability import Capacity, WarmLimit, evaluate, form, subset_simulation
from ..core.analysis import Analysis
from ..core.loads import LoadError, LoadPattern
from ..structures.assembly import Assembly
from .schema import Scenario, Study, build_material, build_structure
from .positions import search
from .settlement import follow
from .uncertainty import UncertaintySection, draw, label, statistics, study_attrs

__all__ = ["FORM_VARS", "SAMPLE_VARS", "SUBSET_VARS", "job_vars", "solve_job", "with_samples"]

log = logging.getLogger(__name__)

#: data variables every file of a job of samples holds
SAMPLE_VARS = ("sample_capacity", "sample_status", "capacity_kind")
#: data variables of a job of FORM (with ``form = true``) and of subset simulation (``subset = true``)
FORM_VARS = ("form_beta", "form_pf", "form_status", "form_evaluations", "form_design_point", "form_alpha")
SUBSET_VARS = ("subset_pf", "subset_cov", "subset_status", "subset_evaluations")
#: variables a warm solver changes: study key -> WarmLimit parameter
WARM_MATERIAL = {"material.friction": "friction", "material.cohesion": "cohesion",
                 "material.tensile_strength": "tensile_strength"}
#: status of a sample of each settlement-path outcome: a bracketed capacity is optimal, a path standing
#: at s_max survives (+inf), nothing standing at s = 0 fails (-inf); the rest is undecided
SETTLEMENT_STATUS = {"collapse": "optimal", "snap_through": "optimal", "contact_lost": "optimal",
                     "no_collapse": "unbounded", "infeasible": "infeasible"}


# ----------------------------------------------------------------------------- solving
def _weight_scales(pattern: LoadPattern) -> bool:
    """Whether the unit weight scales ``b_fixed`` alone, or ``b_fixed`` and ``b_live`` alike:
    the self-weight is the only fixed load, and the live load is either the lateral pattern
    alone or declared loads alone."""
    loads = (*pattern.point, *pattern.distributed, *pattern.vehicle)
    return pattern.fill is None and all(p.scaled for p in loads) and (not pattern.lateral or not loads)


def _warm(job: Scenario, assembly: Assembly, kind: str, section: UncertaintySection) -> Capacity | None:
    """One warm solver for the job's samples (module docstring), or None when they need rebuilding."""
    pattern = job.loads_pattern
    if kind == "settlement_capacity" or job.loads.get("critical_position") or pattern.fill is not None:
        return None
    if {"ring_interface", "backing_interface", "joint_law"} & set(job.material):
        return None  # laws of interface kinds take [material]'s keys when built: rebuilt with each sample's
    weight = job.structure.get("unit_weight")
    for key in section.names:
        if not (key in WARM_MATERIAL or key.startswith("assessment.")
                or key == "structure.unit_weight" and weight and _weight_scales(pattern)):
            return None
    means = {WARM_MATERIAL[k]: float(section.variables[k].mean) for k in section.names if k in WARM_MATERIAL}
    factors = {k: float(job.loads[k]) for k in ("dead_factor", "live_factor")} if kind == "adequacy_factor" else {}
    params = dict.fromkeys(means) | dict.fromkeys(("fixed_factor", "live_factor"))
    try:
        analysis = Analysis(assembly, build_material(job.material | means))
        warm = WarmLimit(analysis, {p: p for p in params}, loads=pattern)
    except (ValueError, ValidationError) as exc:
        log.debug("scenario %r: samples rebuilt (%s)", job.name, exc)
        return None

    def capacity(sample: Mapping[str, float]) -> tuple[str, float]:
        values = {WARM_MATERIAL[k]: v for k, v in sample.items() if k in WARM_MATERIAL}
        ratio = sample.get("structure.unit_weight", weight) / weight if weight else 1.0
        dead = sample.get("assessment.dead_factor", factors.get("dead_factor", 1.0))
        live = sample.get("assessment.live_factor", factors.get("live_factor", 1.0))
        values["fixed_factor"] = dead * ratio
        values["live_factor"] = live * (ratio if pattern.lateral else 1.0)
        return warm(values)

    return capacity


def _rebuilt(job: Scenario, assembly: Assembly, kind: str) -> Capacity:
    """The capacity of a sample with the job's scenario rebuilt at its values (module docstring)."""
    start: list[float] = []
    if job.loads.get("critical_position"):  # the nominal scenario's critical position starts each search
        nominal = search(job, Analysis(assembly, build_material(job.material)), job.loads_pattern)
        start = [nominal.critical_x] if nominal.ok else []

    def capacity(sample: Mapping[str, float]) -> tuple[str, float]:
        d = job.drawn(sample)
        built = assembly if d.structure == job.structure else build_structure(d.structure)
        material = build_material(d.material)
        pattern = LoadPattern.from_dict(d.pattern)
        if kind == "settlement_capacity":
            path, _ = follow(replace(job, settlements=d.settlements, pattern=d.pattern), built, material, lam=False)
            status = SETTLEMENT_STATUS.get(path.status, "numerical")
            return status, path.capacity if status == "optimal" else math.nan
        analysis = Analysis(built, material)
        if job.loads.get("critical_position"):
            lo, hi = search_bounds(pattern, built)
            grid = [*job.loads["positions"], *(min(max(x, lo), hi) for x in start)]
            crit = critical_position(analysis, pattern, start=grid)
            if kind == "lambda_max" or not crit.ok:
                return crit.status, crit.lambda_max
            pattern = crit.pattern
        if kind == "adequacy_factor":
            res = adequacy_factor(analysis, pattern, d.factors["dead_factor"], d.factors["live_factor"])
        else:
            res = analysis.limit(loads=pattern, mechanism=False)
        return res.status, res.lambda_max

    return capacity


def job_vars(job: Scenario) -> tuple[str, ...]:
    """The data variables the file of a job of ``[uncertainty]`` holds (a file without one of
    them is solved again)."""
    if job.samples is not None:
        return SAMPLE_VARS
    section = UncertaintySection.model_validate_json(job.uncertainty)
    return ("capacity_kind",) + FORM_VARS * section.form + SUBSET_VARS * section.subset


def solve_job(job: Scenario, assembly: Assembly) -> xr.Dataset:
    """The answer of a job of ``[uncertainty]`` (:attr:`Scenario.uncertainty`) on the built
    ``assembly`` of its scenario, computed cold (module docstring) as the scenario's capacity
    (:meth:`tce.study.Scenario.capacity_kind`): for a job of samples their ``sample_capacity``
    and ``sample_status`` on ``(scenario, sample)``; for the job of FORM and subset simulation
    their ``form_*`` and ``subset_*`` variables (``docs/results.md``); with ``capacity_kind``,
    the job's key (``scenario_key``) and name (``job``) in its attrs."""
    section = UncertaintySection.model_validate_json(job.uncertainty)
    kind = job.capacity_kind(section.capacity)
    capacity = _warm(job, assembly, kind, section) or _rebuilt(job, assembly, kind)
    data: dict[str, tuple] = {"capacity_kind": (("scenario",), np.asarray([kind], dtype=object))}
    coords: dict[str, Any] = {"scenario": np.asarray([job.of], dtype=object)}
    if job.samples is not None:
        lo, hi = job.samples
        _, x = draw(job.uncertainty)
        records = [dict(zip(section.names, map(float, row), strict=True)) for row in x[lo:hi]]
        statuses, values = evaluate(capacity, records)
        data["sample_capacity"] = (("scenario", "sample"), values[None])
        data["sample_status"] = (("scenario", "sample"), np.asarray(statuses, dtype=object)[None])
        coords["sample"] = np.arange(lo, hi)
        log.debug("job %r: %s", job.name, dict(zip(*np.unique(statuses, return_counts=True))))
    else:
        data |= _estimators(section, capacity)
        coords["variable"] = np.asarray(section.names, dtype=object)
    return label(xr.Dataset(data, coords=coords, attrs={"scenario_key": job.key, "job": job.name}))


#: the status of a point FORM or subset simulation reaches whose values the study's sections refuse
OUT_OF_RANGE = "out_of_range"


def _within_range(capacity: Capacity) -> Capacity:
    """``capacity``, with :data:`OUT_OF_RANGE` (NaN) for values the study's sections refuse:
    FORM and subset simulation go beyond the drawn values (a lognormal friction of 1e30 at
    ``u = 40``); FORM stops there, saying so, and subset simulation counts it undecided."""

    def checked(sample: Mapping[str, float]) -> tuple[str, float]:
        try:
            return capacity(sample)
        except (ValueError, ValidationError, LoadError) as exc:
            log.debug("capacity at %s: %s", dict(sample), exc)
            return OUT_OF_RANGE, math.nan

    return checked


def _estimators(section: UncertaintySection, capacity: Capacity) -> dict[str, tuple]:
    """FORM and subset simulation of ``capacity < threshold``, as the section asks for them."""
    joint, data, capacity = section.joint(), {}, _within_range(capacity)
    one = lambda v: (("scenario",), np.asarray([v], dtype=object if isinstance(v, str) else None))  # noqa: E731
    if section.form:
        f = form(joint, capacity, section.threshold)
        data |= {"form_beta": one(f.beta), "form_pf": one(f.pf), "form_evaluations": one(f.evaluations),
                 "form_status": one("converged" if f.converged else f.message),
                 "form_design_point": (("scenario", "variable"), f.x[None]),
                 "form_alpha": (("scenario", "variable"), f.alpha[None])}
    if section.subset:
        r = subset_simulation(joint, capacity, section.threshold, n=section.subset_samples, seed=section.seed)
        data |= {"subset_pf": one(r.pf), "subset_cov": one(r.cov), "subset_evaluations": one(r.evaluations),
                 "subset_status": one("converged" if r.converged else "not_converged")}
    return data


def with_samples(ds: xr.Dataset, study: Study, parts: Mapping[str, xr.Dataset]) -> xr.Dataset:
    """The study dataset ``ds`` with the samples of its jobs in ``parts`` (job name -> dataset)
    and their statistics (:func:`tce.study.uncertainty.statistics`)."""
    section = study.spec.uncertainty
    names = [sc.name for sc in study.scenarios()]
    cap = np.full((len(names), section.samples), np.nan)
    status = np.full((len(names), section.samples), "", dtype=object)
    kinds = np.full(len(names), "", dtype=object)
    estimators: list[xr.Dataset] = []  # the jobs of FORM and subset simulation, in the scenarios' order
    for job in study.jobs():
        if job.uncertainty is None:
            continue
        part, i = parts[job.name], names.index(job.of)
        kinds[i] = str(part["capacity_kind"].values[0])
        if job.samples is None:
            estimators.append(part.drop_vars("capacity_kind"))
            continue
        lo, hi = job.samples
        cap[i, lo:hi] = part["sample_capacity"].values[0]
        status[i, lo:hi] = part["sample_status"].values[0].astype(str)
    _, x = draw(section)
    out = ds.assign(
        sample_input=(("sample", "variable"), np.asarray(x)),
        sample_capacity=(("scenario", "sample"), cap),
        sample_status=(("scenario", "sample"), status),
        capacity_kind=(("scenario",), kinds),
    ).assign_coords(sample=np.arange(section.samples), variable=np.asarray(section.names, dtype=object))
    if estimators:
        merged = xr.concat(estimators, dim="scenario")
        out = out.assign({k: (v.dims, v.values.astype(object) if v.dtype.kind in "OUS" else v.values)
                          for k, v in merged.data_vars.items()})
    out.attrs.update(study_attrs(section))
    return statistics(label(out))
