"""The ``[uncertainty]`` section of a study file and the statistics of its sampled capacities.

A study with ``[uncertainty]`` (``docs/studies.md``, ``docs/reliability.md``) draws ``samples``
points of its random variables (:class:`tce.analysis.reliability.JointDistribution`: marginals
by mean and spread, a Gaussian copula, plain Monte Carlo, Latin hypercube or Sobol) from
``(samples, method, seed)`` (:func:`draw`: the same points on every run and in every process),
and solves each scenario's capacity at every point (:mod:`tce.study.samples`). This module holds
what needs neither structures nor solvers: the section (:class:`UncertaintySection`), the draw,
the rule that picks the capacity (:func:`capacity_kind`) and the per-scenario statistics of the
sampled capacities in a results dataset (:func:`statistics`), so that ``tce plot``, ``report``
and ``show`` read them from ``results.nc`` alone.
"""

from __future__ import annotations

import functools
import json
import logging
import warnings
from typing import Annotated, Any, Literal

import numpy as np
import xarray as xr
from pydantic import Field, ValidationInfo, field_validator, model_validator
from scipy import stats

from ..analysis.reliability import JointDistribution, RandomVariable, failure_probability
from .sections import _Strict

__all__ = [
    "CAPACITY_KINDS",
    "FRAGILITY_POINTS",
    "MAX_JOBS",
    "MAX_SAMPLES",
    "UncertaintySection",
    "VariableSection",
    "capacity_kind",
    "draw",
    "evaluations",
    "statistics",
]

log = logging.getLogger(__name__)

#: most samples of a study
MAX_SAMPLES = 1_000_000
#: most jobs of samples of a study (files under ``scenarios/``): scenarios x ceil(samples / chunk)
MAX_JOBS = 100_000
#: intensities of a fragility curve
FRAGILITY_POINTS = 41
#: what a sample's capacity is: the direct limit of the scenario's loads, the adequacy factor of
#: ``[assessment]``, or the settlement capacity of ``[settlement_path]``
CAPACITY_KINDS = ("lambda_max", "adequacy_factor", "settlement_capacity")
#: the method named in the results (``sensitivity``)
SENSITIVITY_METHOD = "Spearman rank correlation"
#: largest magnitude of a mean, spread or bound: beyond every bound of a study's keys
_MAX_VALUE = 1e12

_Real = Annotated[float, Field(ge=-_MAX_VALUE, le=_MAX_VALUE)]
_Spread = Annotated[float, Field(gt=0, le=_MAX_VALUE)]


class VariableSection(_Strict):
    """One ``[uncertainty.variables]`` entry: a ``scipy.stats`` distribution by name (``normal``,
    ``lognormal``, ``truncnorm``, ``uniform``, ``gumbel_r``, ...) with its mean and either its
    standard deviation ``std`` or coefficient of variation ``cov``; ``bounds`` for ``truncnorm``
    (:class:`tce.analysis.reliability.RandomVariable`)."""

    distribution: str = Field(min_length=1, max_length=40)
    mean: _Real
    std: _Spread | None = None
    cov: _Spread | None = None
    bounds: Annotated[list[_Real], Field(min_length=2, max_length=2)] | None = None

    def variable(self, name: str) -> RandomVariable:
        """The :class:`RandomVariable` of this entry, named ``name``."""
        bounds = None if self.bounds is None else (float(self.bounds[0]), float(self.bounds[1]))
        return RandomVariable(name, self.distribution, float(self.mean), self.std, self.cov, bounds)

    @model_validator(mode="after")
    def _a_distribution(self) -> VariableSection:
        try:
            self.variable("").frozen()
        except ValueError as exc:
            text = str(exc).removeprefix(": ")
            if "not a scipy.stats" in text:
                text += ("; fix: use normal, lognormal, truncnorm (with bounds), uniform, gumbel_r, gumbel_l or "
                         "another scipy.stats location-scale family")
            raise ValueError(text) from None
        return self


def _pair(key: str) -> tuple[str, str]:
    """The two variables of a correlation key ``"a|b"``."""
    a, sep, b = key.partition("|")
    if not sep or not a or not b:
        raise ValueError(f"{key!r}: name two variables as \"a|b\"")
    return a, b


class UncertaintySection(_Strict):
    """``[uncertainty]``: random variables of a study and how their samples are drawn, solved
    and judged (``docs/studies.md``).

    Attributes
    ----------
    samples : int
        Points drawn, N.
    method : {"mc", "lhs", "sobol"}
        Plain Monte Carlo, Latin hypercube, scrambled Sobol.
    seed : int
        Seed of the draw (recorded in the results).
    threshold : float
        Failure is ``capacity < threshold`` (the capacity's units: a load multiplier, an
        adequacy factor, a settlement magnitude).
    interval, confidence
        The interval of the failure probability stored in ``failure_low``/``failure_high``
        (Clopper-Pearson or Wilson) and its confidence.
    chunk : int
        Samples per job: one file under ``scenarios/``, the unit of resuming and of parallel work.
    capacity : {"auto", "lambda_max", "adequacy_factor", "settlement_capacity"}
        What each sample computes (:func:`capacity_kind`).
    form, subset : bool
        Also FORM and subset simulation per scenario; ``subset_samples`` per level.
    variables : dict
        Study key -> :class:`VariableSection`, in file order.
    correlation : dict
        ``"a|b"`` -> correlation of the Gaussian copula (normal space).
    """

    samples: Annotated[int, Field(ge=1, le=MAX_SAMPLES)]
    method: Literal["mc", "lhs", "sobol"] = "lhs"
    seed: Annotated[int, Field(ge=0, le=2**63 - 1)] = 0
    threshold: _Real = 1.0
    interval: Literal["clopper-pearson", "wilson"] = "clopper-pearson"
    confidence: Annotated[float, Field(gt=0, lt=1)] = 0.95
    chunk: Annotated[int, Field(ge=1, le=MAX_SAMPLES)] = 250
    capacity: Literal["auto", "lambda_max", "adequacy_factor", "settlement_capacity"] = "auto"
    form: bool = False
    subset: bool = False
    subset_samples: Annotated[int, Field(ge=10, le=MAX_SAMPLES, multiple_of=10)] = 1000
    variables: Annotated[dict[Annotated[str, Field(min_length=1, max_length=100)], VariableSection],
                         Field(min_length=1, max_length=100)]
    correlation: dict[str, Annotated[float, Field(ge=-1, le=1)]] = Field(default_factory=dict)

    @field_validator("correlation")
    @classmethod
    def _pairs_of_variables(cls, v: dict[str, float], info: ValidationInfo) -> dict[str, float]:
        names = list(info.data.get("variables") or {})
        seen: set[frozenset[str]] = set()
        for key in v:
            a, b = _pair(key)
            for name in (a, b):
                if name not in names:
                    raise ValueError(f"{key!r}: {name!r} is not a variable of [uncertainty.variables]; fix: use "
                                     f"two of {names}")
            if a == b or frozenset((a, b)) in seen:
                raise ValueError(f"{key!r}: {'a variable with itself' if a == b else 'the pair is given twice'}; "
                                 "fix: one entry per pair of distinct variables")
            seen.add(frozenset((a, b)))
        return v

    @model_validator(mode="after")
    def _positive_definite(self) -> UncertaintySection:
        if self.correlation:
            try:
                np.linalg.cholesky(self.correlation_matrix())
            except np.linalg.LinAlgError:
                raise ValueError("the correlation matrix of [uncertainty.correlation] is not positive definite; fix: "
                                 "smaller correlations (the pairs must be consistent, e.g. a|b = b|c = 0.9 needs "
                                 "a|c above 0.62)") from None
        return self

    @property
    def names(self) -> tuple[str, ...]:
        """The variables' keys, in file order."""
        return tuple(self.variables)

    def correlation_matrix(self) -> np.ndarray:
        """The copula's correlation matrix (normal space), variables in file order."""
        index = {k: i for i, k in enumerate(self.variables)}
        R = np.eye(len(index))
        for key, r in self.correlation.items():
            a, b = _pair(key)
            R[index[a], index[b]] = R[index[b], index[a]] = r
        return R

    def joint(self) -> JointDistribution:
        """The joint distribution of the variables."""
        return JointDistribution([v.variable(k) for k, v in self.variables.items()], self.correlation_matrix())

    def answer_spec(self, samples: bool) -> str:
        """What decides the answer of a job (JSON, part of its key): for a job of samples the
        variables, their correlation, the draw and the capacity; for FORM and subset
        simulation also the threshold and their settings. The interval, its confidence and
        the threshold of the statistics are applied when the results are merged: changing them
        solves nothing again."""
        keep = {"variables", "correlation", "samples", "method", "seed", "capacity"}
        if not samples:
            keep |= {"threshold", "form", "subset", "subset_samples"}
        return json.dumps(self.model_dump(include=keep))

    def spec(self) -> str:
        """The section as JSON, the variables in file order (a job's copy of it, and the key of its draw)."""
        return json.dumps(self.model_dump())


@functools.lru_cache(maxsize=4)
def _drawn(spec: str) -> tuple[np.ndarray, np.ndarray]:
    section = UncertaintySection.model_validate_json(spec)
    with warnings.catch_warnings():  # scipy's warning of a Sobol sample not a power of 2: said once, in the log
        warnings.simplefilter("ignore", UserWarning)
        u, x = section.joint().sample(section.samples, section.method, section.seed)
    n = section.samples
    if section.method == "sobol" and n & (n - 1):
        log.warning("[uncertainty] samples = %d: a Sobol sample keeps its balance properties only for a power "
                    "of 2 (e.g. %d)", n, 1 << (n.bit_length() - 1))
    u.setflags(write=False)
    x.setflags(write=False)
    return u, x


def draw(section: UncertaintySection | str) -> tuple[np.ndarray, np.ndarray]:
    """``(u, x)``: the section's points in standard normal space and their physical values,
    both ``(samples, variables)``, read-only; drawn once per process from ``(samples, method,
    seed)`` and the variables (:meth:`JointDistribution.sample`): the same on every run."""
    return _drawn(section if isinstance(section, str) else section.spec())


#: most iterations of FORM (:func:`tce.analysis.reliability.form`) and levels of subset simulation
#: (:func:`tce.analysis.reliability.subset_simulation`) of a study
FORM_ITERATIONS, SUBSET_LEVELS = 50, 20


def evaluations(section: UncertaintySection, samples: tuple[int, int] | None = None) -> int:
    """Most evaluations of the capacity of one job of ``section``: its samples ``(lo, hi)``, or
    (``samples`` None) FORM's ``FORM_ITERATIONS (d + 1) + 1`` plus subset simulation's
    ``subset_samples SUBSET_LEVELS``, as the section asks for them."""
    if samples is not None:
        return samples[1] - samples[0]
    d = len(section.variables)
    return section.form * (FORM_ITERATIONS * (d + 1) + 1) + section.subset * section.subset_samples * SUBSET_LEVELS


def capacity_kind(capacity: str, settlement_path: bool, moves: bool, assessment: bool) -> str:
    """The capacity a scenario's samples compute: ``capacity`` unless ``"auto"``, which takes
    ``settlement_capacity`` when the study has ``[settlement_path]`` and the scenario ``moves``
    a support, else ``adequacy_factor`` when the study has ``[assessment]``, else ``lambda_max``."""
    if capacity != "auto":
        return capacity
    if settlement_path and moves:
        return "settlement_capacity"
    return "adequacy_factor" if assessment else "lambda_max"


# ----------------------------------------------------------------------------- statistics
#: what each statistic is: name -> (units, long_name)
META: dict[str, tuple[str, str]] = {
    "sample": ("-", "sample of the random variables ([uncertainty])"),
    "variable": ("-", "random variable: the study key it sets"),
    "fragility": ("-", "intensity of a fragility curve"),
    "sample_input": ("-", "drawn physical value of each variable (its key's units; the same for every scenario)"),
    "sample_capacity": ("1", "capacity of the sample (capacity_kind): +inf no finite limit (survives), -inf "
                        "infeasible (fails), NaN numerical (undecided)"),
    "sample_status": ("-", "status of the sample's solve (optimal, unbounded, infeasible, numerical)"),
    "capacity_kind": ("-", "what the samples' capacity is (lambda_max, adequacy_factor, settlement_capacity)"),
    "failure_probability": ("1", "P(capacity < threshold): failed over decided samples"),
    "failure_low": ("1", "lower end of the interval of failure_probability (uncertainty_interval, "
                    "uncertainty_confidence)"),
    "failure_high": ("1", "upper end of the interval of failure_probability"),
    "reliability_index": ("1", "beta = -Phi^-1(failure_probability)"),
    "n_failed": ("-", "samples whose capacity is below the threshold (infeasible ones included)"),
    "n_decided": ("-", "samples with a decided capacity (every status but numerical)"),
    "n_numerical": ("-", "samples whose solve was undecided (left out of the estimate)"),
    "sensitivity": ("1", "Spearman rank correlation of the capacity with each variable over the decided samples"),
    "fragility_intensity": ("1", "intensity x of the fragility curve (the capacity's units), spanning the "
                            "finite capacities"),
    "fragility_probability": ("1", "P(capacity < x) over the decided samples"),
    "fragility_low": ("1", "lower end of the interval of fragility_probability"),
    "fragility_high": ("1", "upper end of the interval of fragility_probability"),
    "form_beta": ("1", "FORM reliability index (distance to the design point in standard normal space)"),
    "form_pf": ("1", "FORM failure probability Phi(-form_beta)"),
    "form_status": ("-", "how FORM ended (converged, or why not)"),
    "form_evaluations": ("-", "capacity evaluations of FORM"),
    "form_design_point": ("-", "FORM design point, physical values (each variable's units)"),
    "form_alpha": ("1", "FORM importance vector (unit, -grad g / |grad g| in standard normal space)"),
    "subset_pf": ("1", "failure probability by subset simulation"),
    "subset_cov": ("1", "coefficient of variation of subset_pf (Au and Beck 2001)"),
    "subset_status": ("-", "how subset simulation ended (converged or not_converged)"),
    "subset_evaluations": ("-", "capacity evaluations of subset simulation"),
}


def _interval(estimate: Any, interval: str) -> tuple[float, float]:
    return estimate.clopper_pearson if interval == "clopper-pearson" else estimate.wilson


#: significant digits of a capacity that its rank reads: the solver's answers agree to about 1e-10
#: relative, so capacities equal to this many digits are ties, not ordered by their last digits' noise
RANK_DIGITS = 8


def _significant(values: np.ndarray, digits: int = RANK_DIGITS) -> np.ndarray:
    """``values`` rounded to ``digits`` significant digits (0, infinities and NaN kept)."""
    finite = np.isfinite(values) & (values != 0)
    scale = np.ones_like(values)
    scale[finite] = 10.0 ** (digits - 1 - np.floor(np.log10(np.abs(values[finite]))))
    return np.where(finite, np.round(values * scale) / scale, values)


def _spearman(values: np.ndarray, inputs: np.ndarray) -> np.ndarray:
    """Spearman's rank correlation of ``values`` with each column of ``inputs`` over the
    decided values (NaN left out; +-inf ranked as the extremes; values equal to
    :data:`RANK_DIGITS` significant digits tied); NaN where either is constant."""
    keep = ~np.isnan(values)
    out = np.full(inputs.shape[1], np.nan)
    if keep.sum() < 3:
        return out
    ranked = _significant(values[keep])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", stats.ConstantInputWarning)
        for j in range(inputs.shape[1]):
            out[j] = stats.spearmanr(ranked, inputs[keep, j]).statistic
    return out


def statistics(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` with the per-scenario statistics of its sampled capacities (``docs/results.md``).

    Reads ``sample_capacity``, ``sample_status`` and ``sample_input`` and the attrs
    ``uncertainty_threshold``, ``uncertainty_interval`` and ``uncertainty_confidence``; adds
    ``failure_probability``, ``failure_low``, ``failure_high``, ``reliability_index``,
    ``n_failed``, ``n_decided``, ``n_numerical`` (:func:`tce.analysis.reliability.failure_probability`),
    ``sensitivity`` (``scenario, variable``) and the fragility curves on
    :data:`FRAGILITY_POINTS` intensities spanning each scenario's finite capacities
    (``fragility_intensity``, ``fragility_probability``, ``fragility_low``, ``fragility_high``;
    NaN where no capacity is finite). A dataset without ``sample_capacity`` is returned as it is.
    """
    if "sample_capacity" not in ds:
        return ds
    threshold = float(ds.attrs["uncertainty_threshold"])
    interval = str(ds.attrs["uncertainty_interval"])
    confidence = float(ds.attrs["uncertainty_confidence"])
    cap = ds["sample_capacity"].transpose("scenario", "sample").values
    status = ds["sample_status"].transpose("scenario", "sample").values.astype(str)
    inputs = ds["sample_input"].transpose("sample", "variable").values
    n_sc, K = cap.shape[0], FRAGILITY_POINTS
    scalars = {k: np.full(n_sc, np.nan) for k in ("failure_probability", "failure_low", "failure_high",
                                                   "reliability_index")}
    counts = {k: np.zeros(n_sc, dtype=np.int64) for k in ("n_failed", "n_decided", "n_numerical")}
    sens = np.full((n_sc, inputs.shape[1]), np.nan)
    frag = {k: np.full((n_sc, K), np.nan) for k in ("intensity", "probability", "low", "high")}
    for i in range(n_sc):
        est = failure_probability(cap[i], threshold, status[i], confidence)
        lo, hi = _interval(est, interval)
        scalars["failure_probability"][i], scalars["reliability_index"][i] = est.pf, est.beta
        scalars["failure_low"][i], scalars["failure_high"][i] = lo, hi
        counts["n_failed"][i], counts["n_decided"][i], counts["n_numerical"][i] = est.failures, est.n, est.numerical
        sens[i] = _spearman(cap[i], inputs)
        finite = cap[i][np.isfinite(cap[i])]
        if not len(finite):
            continue
        xs = np.linspace(finite.min(), finite.max(), K) if finite.max() > finite.min() else np.full(K, finite[0])
        frag["intensity"][i] = xs
        for k, x in enumerate(xs):
            e = failure_probability(cap[i], float(x), confidence=confidence)
            frag["probability"][i, k] = e.pf
            frag["low"][i, k], frag["high"][i, k] = _interval(e, interval)
    out = ds.assign(
        {k: (("scenario",), v) for k, v in (scalars | counts).items()}
        | {"sensitivity": (("scenario", "variable"), sens)}
        | {f"fragility_{k}": (("scenario", "fragility"), v) for k, v in frag.items()}
    ).assign_coords(fragility=np.arange(K))
    out.attrs["sensitivity_method"] = SENSITIVITY_METHOD
    return label(out)


def label(ds: xr.Dataset) -> xr.Dataset:
    """Give the uncertainty variables of ``ds`` their ``units`` and ``long_name``."""
    for name in META:
        if name in ds.variables:
            units, long_name = META[name]
            ds[name].attrs.update(units=units, long_name=long_name)
    return ds


def study_attrs(section: UncertaintySection) -> dict[str, Any]:
    """The results' ``uncertainty_*`` attrs of a section."""
    return {
        "uncertainty_method": section.method,
        "uncertainty_seed": section.seed,
        "uncertainty_samples": section.samples,
        "uncertainty_threshold": section.threshold,
        "uncertainty_interval": section.interval,
        "uncertainty_confidence": section.confidence,
        "uncertainty_variables": json.dumps({k: v.model_dump(exclude_none=True) for k, v in section.variables.items()}),
        "uncertainty_correlation": json.dumps(section.correlation),
        "uncertainty_capacity": section.capacity,
    }

