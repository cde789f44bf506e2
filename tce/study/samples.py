"""The sampled capacities of an uncertainty study (``[uncertainty]``, ``docs/reliability.md``).

Keys. A variable of ``[uncertainty.variables]`` is a study key holding a real number:
``material.<key>``, ``structure.<key>`` (``unit_weight`` included), ``loads.alpha``,
``loads.fill.<key>``, ``loads.vehicle.<i>.x`` and ``.y`` (``i`` from 0, in file order),
``assessment.dead_factor`` and ``.live_factor``, ``settlement.magnitude`` (multiplies the
scenario's settlement vectors). :func:`check_uncertainty` refuses, naming the key, one that the
study does not have or that is not a real number, and one whose smallest or largest drawn value
its section refuses (a normal thickness drawn negative).

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

import copy
import logging
import math
from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import Any, get_args, get_origin

import numpy as np
import xarray as xr
from pydantic import ValidationError

from ..analysis.assessment import adequacy_factor
from ..analysis.critical import critical_position, search_bounds
from ..analysis.reliability import Capacity, WarmLimit, evaluate
from ..core.analysis import Analysis
from ..core.loads import LoadError, LoadPattern, resolve
from ..messages import did_you_mean
from ..structures.assembly import Assembly
from .schema import (
    MAX_MULTIPLIER,
    SAMPLES_SEPARATOR,
    AssessmentSection,
    FillSection,
    MaterialSection,
    Scenario,
    Study,
    StudyError,
    build_material,
    build_structure,
)
from .settlement import follow
from .uncertainty import UncertaintySection, capacity_kind, draw, label, statistics, study_attrs

__all__ = ["SAMPLE_VARS", "Drawn", "apply", "check_uncertainty", "kind_of", "solve_samples", "with_samples"]

log = logging.getLogger(__name__)

#: data variables every file of a job of samples holds
SAMPLE_VARS = ("sample_capacity", "sample_status", "capacity_kind")
#: variables a warm solver changes: study key -> WarmLimit parameter
WARM_MATERIAL = {"material.friction": "friction", "material.cohesion": "cohesion",
                 "material.tensile_strength": "tensile_strength"}
#: status of a sample of each settlement-path outcome: a bracketed capacity is optimal, a path standing
#: at s_max survives (+inf), nothing standing at s = 0 fails (-inf); the rest is undecided
SETTLEMENT_STATUS = {"collapse": "optimal", "snap_through": "optimal", "contact_lost": "optimal",
                     "no_collapse": "unbounded", "infeasible": "infeasible"}


# ----------------------------------------------------------------------------- keys
def _real(annotation: Any) -> bool:
    """Whether a field's annotation takes a real number (not a list of them)."""
    if annotation is float:
        return True
    if get_origin(annotation) in (list, tuple, dict):
        return False
    return any(_real(a) for a in get_args(annotation))


def _numeric(fields: Mapping[str, Any]) -> list[str]:
    return [k for k, f in fields.items() if _real(f.annotation)]


def _key_problem(study: Study, key: str) -> str | None:
    """Why ``key`` is not a variable of ``study`` (None when it is one)."""
    spec = study.spec
    head, _, rest = key.partition(".")
    sections = {"material": MaterialSection.model_fields, "structure": type(spec.structure).model_fields,
                "loads.fill": FillSection.model_fields, "assessment": AssessmentSection.model_fields}
    if head == "loads" and rest.startswith("fill."):
        head, rest = "loads.fill", rest[5:]
        if spec.loads.fill is None:
            return "the study has no [loads.fill]"
    if head in sections:
        if head == "assessment" and spec.assessment is None:
            return "the study has no [assessment]"
        numeric = _numeric(sections[head])
        if rest in numeric:
            return None
        if rest in sections[head]:
            return f"{head}.{rest} is not a real number; use one of {[f'{head}.{k}' for k in numeric]}"
        return f"{head} has no key {rest!r}; use one of {[f'{head}.{k}' for k in numeric]}{did_you_mean(rest, numeric)}"
    if key in ("loads.alpha", "settlement.magnitude"):
        return None
    if head == "loads" and rest.startswith("vehicle."):
        _, i, coord = (rest.split(".") + ["", ""])[:3]
        n = len(spec.loads.vehicle)
        if not (i.isdigit() and int(i) < n and coord in ("x", "y") and rest.count(".") == 2):
            return f"use loads.vehicle.<i>.x or .y with i from 0 to {n - 1}" if n else "the study has no [[loads.vehicle]]"
        if coord == "x" and spec.loads.critical_position:
            return "the critical-position search sets the vehicles' x itself; fix: remove the variable"
        return None
    known = ["material.<key>", "structure.<key>", "loads.alpha", "loads.fill.<key>", "loads.vehicle.<i>.x",
             "loads.vehicle.<i>.y", "assessment.dead_factor", "assessment.live_factor", "settlement.magnitude"]
    return f"not a key a variable can set; use one of {known}"


@dataclass(frozen=True)
class Drawn:
    """A scenario's sections with one sample's values (plain data, as in :class:`Scenario`)."""

    structure: dict[str, Any]
    material: dict[str, Any]
    pattern: dict[str, Any]
    factors: dict[str, float]
    settlements: dict[str, list[float]]


def apply(sc: Scenario, values: Mapping[str, float]) -> Drawn:
    """The sections of scenario ``sc`` with the sample ``values`` (study key -> value) set;
    ``settlement.magnitude`` multiplies its settlement vectors. ``sc`` is not changed."""
    structure, material, pattern = dict(sc.structure), dict(sc.material), copy.deepcopy(sc.pattern)
    factors = {k: float(sc.loads[k]) for k in ("dead_factor", "live_factor") if k in sc.loads}
    scale = 1.0
    for key, v in values.items():
        head, _, rest = key.partition(".")
        if head == "material":
            material[rest] = v
        elif head == "structure":
            structure[rest] = v
        elif head == "assessment":
            factors[rest] = v
        elif key == "settlement.magnitude":
            scale = v
        elif key == "loads.alpha":
            pattern["alpha"] = v
        elif rest.startswith("fill."):
            pattern["fill"][rest[5:]] = v
        else:  # loads.vehicle.<i>.<x|y>
            _, i, coord = rest.split(".")
            pattern["vehicle"][int(i)][coord] = v
    settlements = {s: [scale * u for u in vec] for s, vec in sc.settlements.items()}
    return Drawn(structure, material, pattern, factors, settlements)


def _reason(exc: Exception) -> str:
    if isinstance(exc, ValidationError):
        return "; ".join(f"{'.'.join(map(str, e['loc']))}: {e['msg']}" for e in exc.errors()[:2])
    return str(exc)


def _refused(study: Study, sc: Scenario, key: str, value: float) -> str | None:
    """Why the section of ``key`` refuses ``value`` in scenario ``sc`` (None when it takes it)."""
    d = apply(sc, {key: value})
    head = key.partition(".")[0]
    try:
        if head == "material":
            build_material(d.material)
        elif head == "structure":
            build_structure(d.structure).validate()
        elif head == "assessment":
            AssessmentSection.model_validate(d.factors)
        elif key == "settlement.magnitude":
            if not abs(value) <= MAX_MULTIPLIER:
                return f"beyond +-{MAX_MULTIPLIER:g}"
        elif key == "loads.alpha":
            if not abs(value) <= 360.0:
                return "an angle beyond +-360 degrees"
        else:
            if "fill" in d.pattern:
                FillSection.model_validate(d.pattern["fill"])
            pattern = LoadPattern.from_dict(d.pattern)
            if not sc.loads.get("critical_position"):
                resolve(pattern, study.assembly(sc.structure))
    except (ValueError, ValidationError, LoadError, OSError) as exc:
        return _reason(exc)
    return None


def kind_of(sc: Scenario, section: UncertaintySection) -> str:
    """The capacity the samples of scenario ``sc`` compute (:func:`capacity_kind`)."""
    moves = any(any(u != 0 for u in v) for v in sc.settlements.values())
    return capacity_kind(section.capacity, sc.settlement_path is not None, moves, "dead_factor" in sc.loads)


def check_uncertainty(study: Study) -> None:
    """Refuse an ``[uncertainty]`` section that cannot run on ``study`` (module docstring),
    naming the file and the key (:class:`StudyError`)."""
    section = study.spec.uncertainty
    if section is None:
        return
    path, spec = study.path, study.spec
    where = lambda key: f'{path}: uncertainty.variables."{key}"'  # noqa: E731
    for key in section.names:
        problem = _key_problem(study, key)
        if problem is not None:
            raise StudyError(f"{where(key)}: {problem}" + ("" if "fix:" in problem else "; fix: correct the key"))
    needs = {"adequacy_factor": ("assessment", spec.assessment), "settlement_capacity":
             ("settlement_path", spec.settlement_path)}
    if section.capacity in needs and needs[section.capacity][1] is None:
        name = needs[section.capacity][0]
        raise StudyError(f"{path}: uncertainty.capacity: {section.capacity} needs a [{name}] section; fix: add it or "
                         "capacity = \"auto\"")
    kinds = {sc.name: kind_of(sc, section) for sc in study.scenarios()}
    for sc in study.scenarios():
        if kinds[sc.name] == "settlement_capacity" and not any(any(u != 0 for u in v) for v in sc.settlements.values()):
            raise StudyError(f"{path}: uncertainty.capacity: scenario {sc.name!r} moves no support: it has no settlement "
                             "capacity; fix: capacity = \"auto\"")
    for key in section.names:
        if key.startswith("assessment.") and any(k != "adequacy_factor" for k in kinds.values()):
            raise StudyError(f"{where(key)}: the assessment's factors enter the adequacy factor alone, and some "
                             "scenario computes another capacity; fix: capacity = \"adequacy_factor\" or remove the variable")
        if key.startswith("material.") and "settlement_capacity" in kinds.values():
            raise StudyError(f"{where(key)}: a settlement path follows the rigid Heyman material (no friction limit, "
                             "cohesion or strengths); fix: remove the variable, or capacity = \"lambda_max\"")
    _, x = draw(section)
    first = study.scenarios()[0]
    for j, key in enumerate(section.names):
        lo, hi = float(x[:, j].min()), float(x[:, j].max())
        for value in (lo, hi) if hi > lo else (lo,):
            problem = _refused(study, first, key, value)
            if problem is not None:
                raise StudyError(
                    f"{where(key)}: the {section.samples} drawn values span [{lo:.6g}, {hi:.6g}] and {value:.6g} is "
                    f"refused ({problem}); fix: a distribution within the key's range (truncnorm with bounds, "
                    "lognormal for a positive quantity) or a smaller spread"
                )


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
        nominal = critical_position(Analysis(assembly, build_material(job.material)), job.loads_pattern,
                                    start=job.loads["positions"])
        start = [nominal.critical_x] if nominal.ok else []

    def capacity(sample: Mapping[str, float]) -> tuple[str, float]:
        d = apply(job, sample)
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


def solve_samples(job: Scenario, assembly: Assembly) -> xr.Dataset:
    """The capacities of the samples ``job.samples`` of the job's scenario (:func:`kind_of`):
    a dataset of ``sample_capacity`` and
    ``sample_status`` on ``(scenario, sample)`` and ``capacity_kind``, with the job's key
    (``scenario_key``) and name (``job``) in its attrs."""
    section = UncertaintySection.model_validate_json(job.uncertainty)
    lo, hi = job.samples
    _, x = draw(job.uncertainty)
    records = [dict(zip(section.names, map(float, row), strict=True)) for row in x[lo:hi]]
    kind = kind_of(job, section)
    capacity = _warm(job, assembly, kind, section) or _rebuilt(job, assembly, kind)
    statuses, values = evaluate(capacity, records)
    scenario = job.name.rpartition(SAMPLES_SEPARATOR)[0]
    ds = xr.Dataset(
        {
            "sample_capacity": (("scenario", "sample"), values[None]),
            "sample_status": (("scenario", "sample"), np.asarray(statuses, dtype=object)[None]),
            "capacity_kind": (("scenario",), np.asarray([kind], dtype=object)),
        },
        coords={"scenario": np.asarray([scenario], dtype=object), "sample": np.arange(lo, hi)},
        attrs={"scenario_key": job.key, "job": job.name},
    )
    log.debug("job %r: %d samples, %s", job.name, hi - lo, dict(zip(*np.unique(statuses, return_counts=True))))
    return label(ds)


def with_samples(ds: xr.Dataset, study: Study, parts: Mapping[str, xr.Dataset]) -> xr.Dataset:
    """The study dataset ``ds`` with the samples of its jobs in ``parts`` (job name -> dataset)
    and their statistics (:func:`tce.study.uncertainty.statistics`)."""
    section = study.spec.uncertainty
    names = [sc.name for sc in study.scenarios()]
    jobs = [job for job in study.jobs() if job.samples is not None]
    cap = np.full((len(names), section.samples), np.nan)
    status = np.full((len(names), section.samples), "", dtype=object)
    kinds = np.full(len(names), "", dtype=object)
    for job in jobs:
        part = parts[job.name]
        i, (lo, hi) = names.index(job.name.rpartition(SAMPLES_SEPARATOR)[0]), job.samples
        cap[i, lo:hi] = part["sample_capacity"].values[0]
        status[i, lo:hi] = part["sample_status"].values[0].astype(str)
        kinds[i] = str(part["capacity_kind"].values[0])
    _, x = draw(section)
    out = ds.assign(
        sample_input=(("sample", "variable"), np.asarray(x)),
        sample_capacity=(("scenario", "sample"), cap),
        sample_status=(("scenario", "sample"), status),
        capacity_kind=(("scenario",), kinds),
    ).assign_coords(sample=np.arange(section.samples), variable=np.asarray(section.names, dtype=object))
    out.attrs.update(study_attrs(section))
    return statistics(label(out))
