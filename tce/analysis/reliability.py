"""Probability of collapse: random inputs, a capacity per sample, and its failure probability.

The pieces, each usable alone (``docs/reliability.md`` has the method and its sources):

- :class:`RandomVariable` and :class:`JointDistribution`: marginals from ``scipy.stats`` by
  name, given by their mean and standard deviation (or coefficient of variation), joined by
  a Gaussian copula; samples by plain Monte Carlo, Latin hypercube or scrambled Sobol
  (``scipy.stats.qmc``), drawn in standard normal space ``u`` and mapped to the physical
  values ``x``.
- Capacities: a callable ``capacity(sample) -> (status, value)`` of a sample (a mapping from
  variable name to value). :class:`WarmLimit` is the direct ``lambda_max`` of one model with
  the variables that keep the geometry (friction, cohesion, tensile strength, the fixed and
  live load factors) changed in one warm Clarabel solver; :class:`RebuiltLimit` rebuilds the
  analysis per sample (any variable, e.g. a block's width).
- Estimators: :func:`failure_probability` (the fraction of samples whose capacity is below
  a threshold, with Wilson and Clopper-Pearson intervals and the reliability index
  ``beta = -Phi^-1(pf)``), :func:`form` (the Hasofer-Lind design point by the HL-RF
  iteration) and :func:`subset_simulation` (Au and Beck 2001) with their own accuracy.

Conventions. Failure is ``capacity < threshold`` (a load multiplier below the one required).
The status of a sample's solve decides its value (:func:`outcome_value`): ``optimal`` its
capacity, ``unbounded`` (no finite limit) ``+inf`` (it survives), ``infeasible`` (nothing
stands at lambda = 0) ``-inf`` (it fails), ``numerical`` NaN: counted and reported apart,
never folded into the estimate.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, replace
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy import optimize, special, stats
from scipy.stats import qmc

from ..core.analysis import Analysis
from ..core.clarabel_solver import ClarabelSolver, SolverOptions
from ..core.limit import LimitSolver
from ..core.loads import LoadPattern, as_pattern, scene_vectors
from ..core.material import Material
from ..core.problem import ConicProblem, Formulation, limit_problem

__all__ = [
    "Capacity",
    "FailureEstimate",
    "FormResult",
    "JointDistribution",
    "RandomVariable",
    "RebuiltLimit",
    "SubsetResult",
    "WarmLimit",
    "evaluate",
    "failure_probability",
    "form",
    "outcome_value",
    "subset_simulation",
]

log = logging.getLogger(__name__)

Sample = Mapping[str, float]
#: ``capacity(sample) -> (status, value)``: a status word (docs/conventions.md) and the
#: capacity (dimensionless load multiplier; NaN unless ``optimal``)
Capacity = Callable[[Sample], tuple[str, float]]
Method = Literal["mc", "lhs", "sobol"]

#: names accepted for the scipy.stats distributions
ALIASES = {"normal": "norm", "lognormal": "lognorm", "truncated_normal": "truncnorm", "gumbel": "gumbel_r"}


@dataclass(frozen=True)
class RandomVariable:
    """One uncertain input, a ``scipy.stats`` distribution given by its mean and spread.

    Parameters
    ----------
    name : str
        The sample key (e.g. ``"friction"``).
    distribution : str
        A ``scipy.stats`` continuous distribution: ``norm`` (``normal``), ``lognorm``
        (``lognormal``), ``truncnorm`` (``truncated_normal``), or any location-scale family
        without a shape parameter (``uniform``, ``gumbel_r``, ``gumbel_l``, ``logistic``, ...).
    mean : float
        Mean of the variable (its own units).
    std, cov : float
        Standard deviation (its units) or coefficient of variation ``std / |mean|``; exactly one.
    bounds : (float, float), optional
        ``truncnorm`` only: lower and upper bound (its units; ``-inf``/``inf`` allowed).

    Notes
    -----
    The conversion to the distribution's parameters, chosen so that the frozen distribution
    has exactly the given mean ``m`` and standard deviation ``s``:

    - ``lognorm``: ``sigma_ln = sqrt(ln(1 + (s/m)^2))``, ``mu_ln = ln m - sigma_ln^2 / 2``;
      scipy's ``s = sigma_ln``, ``scale = exp(mu_ln)`` (needs ``m > 0``);
    - ``truncnorm``: the parent normal's ``loc`` and ``scale`` solved (``scipy.optimize.root``)
      so that the truncated distribution has mean ``m`` and std ``s``;
    - a location-scale family ``f`` without shape: ``scale = s / f.std()``,
      ``loc = m - scale f.mean()`` (``norm``: ``loc = m``, ``scale = s``; ``uniform``: width
      ``s sqrt(12)``; ``gumbel_r``: ``scale = s sqrt(6) / pi``, ``loc = m - 0.5772 scale``).

    Raises
    ------
    ValueError
        An unknown distribution, one with a shape parameter other than those above, both or
        neither of ``std`` and ``cov``, a non-positive spread, a lognormal with ``m <= 0``,
        bounds without ``truncnorm`` or a mean outside them.
    """

    name: str
    distribution: str
    mean: float
    std: float | None = None
    cov: float | None = None
    bounds: tuple[float, float] | None = None

    def __post_init__(self) -> None:
        if (self.std is None) == (self.cov is None):
            raise ValueError(f"{self.name}: give exactly one of std and cov")
        if not (math.isfinite(self.mean) and math.isfinite(self.spread) and self.spread > 0):
            raise ValueError(f"{self.name}: mean and a positive spread must be finite numbers, got "
                             f"mean {self.mean!r}, std {self.std!r}, cov {self.cov!r}")
        dist = ALIASES.get(self.distribution, self.distribution)
        if not isinstance(getattr(stats, dist, None), stats.rv_continuous):
            raise ValueError(f"{self.name}: {self.distribution!r} is not a scipy.stats continuous distribution")
        if (self.bounds is not None) != (dist == "truncnorm"):
            raise ValueError(f"{self.name}: bounds are given for (and needed by) truncnorm alone")
        if dist == "lognorm" and self.mean <= 0:
            raise ValueError(f"{self.name}: a lognormal variable needs a positive mean, got {self.mean!r}")
        if dist == "truncnorm" and not (self.bounds[0] < self.mean < self.bounds[1]):
            raise ValueError(f"{self.name}: the mean {self.mean!r} must lie inside the bounds {self.bounds!r}")
        if dist not in ("lognorm", "truncnorm") and getattr(stats, dist).shapes:
            raise ValueError(f"{self.name}: {dist} has shape parameters ({getattr(stats, dist).shapes}); "
                             "give a location-scale family, lognorm or truncnorm")

    @property
    def spread(self) -> float:
        """Standard deviation (the variable's units)."""
        return float(self.std) if self.std is not None else float(self.cov) * abs(self.mean)

    def frozen(self) -> stats.rv_continuous:
        """The frozen ``scipy.stats`` distribution with this mean and standard deviation."""
        dist = ALIASES.get(self.distribution, self.distribution)
        m, s = float(self.mean), self.spread
        if dist == "lognorm":
            sigma = math.sqrt(math.log1p((s / m) ** 2))
            return stats.lognorm(s=sigma, scale=math.exp(math.log(m) - sigma**2 / 2))
        if dist == "truncnorm":
            lo, hi = self.bounds

            def trunc(p: NDArray[np.float64]) -> stats.rv_continuous:
                loc, scale = p[0], math.exp(p[1])
                return stats.truncnorm((lo - loc) / scale, (hi - loc) / scale, loc=loc, scale=scale)

            sol = optimize.root(lambda p: [(trunc(p).mean() - m) / s, trunc(p).std() / s - 1.0],
                                [m, math.log(s)], tol=1e-12)
            if not sol.success:
                raise ValueError(f"{self.name}: no truncated normal in {self.bounds} has mean {m} and std {s}")
            return trunc(sol.x)
        family = getattr(stats, dist)
        scale = s / family.std()
        return family(loc=m - scale * family.mean(), scale=scale)


class JointDistribution:
    """Random variables joined by a Gaussian copula.

    A point ``u`` of the standard normal space (independent N(0, 1) components) maps to the
    physical values by ``z = L u`` (``L`` the lower Cholesky factor of the correlation
    matrix ``R`` of the normal space), then ``x_i = F_i^-1(Phi(z_i))`` with ``F_i`` the
    marginal of variable ``i`` (the Nataf transformation; ``R`` is the correlation of the
    ``z``, which for non-normal marginals differs slightly from that of the ``x``).

    Parameters
    ----------
    variables : sequence of RandomVariable
    correlation : (d, d) array_like, optional
        Symmetric positive definite with a unit diagonal; default the identity.

    Raises
    ------
    ValueError
        Repeated names, or a correlation matrix of another shape, not symmetric, without a
        unit diagonal or not positive definite.
    """

    def __init__(self, variables: Sequence[RandomVariable], correlation: ArrayLike | None = None) -> None:
        self.variables = tuple(variables)
        self.names = tuple(v.name for v in self.variables)
        if len(set(self.names)) != len(self.names) or not self.names:
            raise ValueError(f"variables need distinct names, got {list(self.names)}")
        d = len(self.names)
        R = np.eye(d) if correlation is None else np.array(correlation, dtype=float)
        if R.shape != (d, d) or not np.allclose(R, R.T, atol=1e-12) or not np.allclose(np.diag(R), 1.0, atol=1e-12):
            raise ValueError(f"correlation must be a symmetric ({d}, {d}) matrix with a unit diagonal")
        try:
            self.cholesky = np.linalg.cholesky(R)
        except np.linalg.LinAlgError:
            raise ValueError("correlation must be positive definite") from None
        self.correlation = R
        self.marginals = tuple(v.frozen() for v in self.variables)

    @property
    def dim(self) -> int:
        """Number of variables."""
        return len(self.names)

    def to_physical(self, u: ArrayLike) -> NDArray[np.float64]:
        """Physical values ``x`` ``(n, d)`` of standard normal points ``u`` ``(n, d)`` or ``(d,)``."""
        z = np.atleast_2d(np.asarray(u, dtype=float)) @ self.cholesky.T
        cdf = special.ndtr(z)
        return np.column_stack([m.ppf(cdf[:, i]) for i, m in enumerate(self.marginals)])

    def standard_normal(self, n: int, method: Method = "mc", seed: int | None = None) -> NDArray[np.float64]:
        """``n`` points ``(n, d)`` of the independent standard normal space.

        ``mc``: ``numpy.random.default_rng(seed)``; ``lhs``: ``qmc.LatinHypercube``; ``sobol``:
        scrambled ``qmc.Sobol`` (balanced when ``n`` is a power of 2). The quasi-random points
        in ``(0, 1)`` are mapped by ``Phi^-1``. The same ``(n, method, seed)`` gives the same points.
        """
        if n < 1:
            raise ValueError(f"n must be at least 1, got {n}")
        rng = np.random.default_rng(seed)
        if method == "mc":
            return rng.standard_normal((n, self.dim))
        if method == "lhs":
            return special.ndtri(qmc.LatinHypercube(self.dim, rng=rng).random(n))
        if method == "sobol":
            return special.ndtri(qmc.Sobol(self.dim, scramble=True, rng=rng).random(n))
        raise ValueError(f"method must be 'mc', 'lhs' or 'sobol', got {method!r}")

    def sample(
        self, n: int, method: Method = "mc", seed: int | None = None
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """``(u, x)``: ``n`` standard normal points and their physical values, both ``(n, d)``."""
        u = self.standard_normal(n, method, seed)
        return u, self.to_physical(u)

    def records(self, x: ArrayLike) -> list[dict[str, float]]:
        """The rows of ``x`` ``(n, d)`` as samples (name -> value)."""
        return [dict(zip(self.names, map(float, row))) for row in np.atleast_2d(x)]


def outcome_value(status: str, value: float) -> float:
    """The capacity a status stands for: ``optimal`` its value, ``unbounded`` ``+inf``,
    ``infeasible`` ``-inf``, ``numerical`` (or any other word) NaN."""
    return {"optimal": value, "unbounded": math.inf, "infeasible": -math.inf}.get(status, math.nan)


def evaluate(capacity: Capacity, samples: Sequence[Sample]) -> tuple[NDArray[np.str_], NDArray[np.float64]]:
    """Statuses and values (:func:`outcome_value`) of ``capacity`` at each sample, in order."""
    out = [capacity(s) for s in samples]
    return np.array([s for s, _ in out]), np.array([outcome_value(s, v) for s, v in out], dtype=float)


# --------------------------------------------------------------------------- capacities
#: the parameters a :class:`WarmLimit` changes without rebuilding, and what they enter
WARM_PARAMETERS = ("friction", "cohesion", "tensile_strength", "fixed_factor", "live_factor")


class WarmLimit:
    """Direct ``lambda_max`` of one model for samples that keep the geometry, in one warm solver.

    The direct limit problem (:func:`tce.core.problem.limit_problem`) is affine in each
    parameter of :data:`WARM_PARAMETERS`: the friction coefficient enters the contact-law
    rows of the constraint matrix, cohesion and tensile strength their offsets, the fixed
    load factor (multiplying ``b_fixed``, e.g. a unit weight relative to the model's) the
    right-hand side, the live load factor (multiplying ``b_live``, e.g. an axle load) the
    multiplier's column. The sensitivities are read once from the problem built at the
    model's parameters plus one; a sample's data is the base data plus the changes, given to
    the Clarabel solver set up once (the symbolic factorisation and the data layout kept).
    :class:`tce.core.limit.LimitSolver` cannot do this: it sets up a new Clarabel problem for
    every solve, with the contact law of its material.

    Each answer passes the checks of :class:`tce.core.limit.LimitSolver` (equilibrium and
    contact law to 1e-8 of ``W``, ``W L`` on the scaled problem); a solve that does not is
    solved again by a fresh :class:`~tce.core.limit.LimitSolver` with the sample's material
    (which retries with iterative refinement and proves an undecided unbounded limit); so is
    a solve that ends ``DualInfeasible``: a sample is ``unbounded`` only as the limit solver
    proves it, as for every other limit tce reports.

    Parameters
    ----------
    analysis : Analysis
        Its assembly, material and model choice; the material's value of each parameter that
        varies must be > 0 (the rows of a Heyman material, or of zero cohesion or tension,
        differ from those of a positive one).
    variables : mapping of str to str
        Sample key -> parameter of :data:`WARM_PARAMETERS` (e.g. ``{"mu": "friction"}``).
    alpha : float, optional
        Direction (degrees) of the default lateral pattern.
    loads : LoadPattern, optional
        The pattern (instead of ``alpha``); a fill's passive restraint is not supported.

    Raises
    ------
    ValueError
        An unknown parameter, a pattern with a fill, or parameters whose change alters the
        problem's structure at the model's material.
    """

    def __init__(self, analysis: Analysis, variables: Mapping[str, str], alpha: float | None = None,
                 loads: LoadPattern | None = None) -> None:
        bad = sorted(set(variables.values()) - set(WARM_PARAMETERS))
        if bad:
            raise ValueError(f"parameters {bad} are not among those changed warm: {list(WARM_PARAMETERS)}")
        pattern = as_pattern(alpha, loads)
        if pattern.fill is not None:
            raise ValueError("a fill's passive restraint is not supported warm: use RebuiltLimit")
        self.variables = dict(variables)
        self.analysis = analysis
        self.material = analysis.material
        self.model = analysis.model(analysis.model_kind(loads=pattern))
        self.pattern, self.b_fixed, self.b_live = scene_vectors(self.model, loads=pattern)
        base = self._problem({})
        self.base = base
        self.sensitivity: dict[str, tuple[NDArray[np.float64], NDArray[np.float64]]] = {}
        for p in set(self.variables.values()):
            value = self._base_value(p)
            if value == 0.0:
                raise ValueError(f"{p} changes the problem's structure from the analysis' value 0 "
                                 f"({self.material.describe()}): give the material a {p} > 0")
            # a step the material accepts (less friction or tension, more cohesion keeps
            # tensile_strength <= cohesion / friction); the data are affine in each parameter
            step = -0.5 * value if p in ("friction", "tensile_strength") else 0.5 * value
            other = self._problem({p: value + step})
            if not (np.array_equal(other.A.indices, base.A.indices) and np.array_equal(other.A.indptr, base.A.indptr)
                    and other.cones == base.cones):
                raise ValueError(f"{p} changes the problem's structure at the analysis' material "
                                 f"({self.material.describe()})")
            self.sensitivity[p] = ((other.A.data - base.A.data) / step, (other.b - base.b) / step)
        kkt = analysis.formulation(self.model.kind).kkt
        self.settings = SolverOptions(tol=1e-10, max_iter=500).settings(refine=False, kkt=kkt)  # LimitSolver's
        self.solver = ClarabelSolver(base, self.settings)
        self._A = base.A.copy()  # the current sample's constraint matrix (its values replaced per sample)
        self._rows = _cone_rows(base.cones)

    def _base_value(self, parameter: str) -> float:
        """The model's value of a parameter (the load factors are 1)."""
        return 1.0 if parameter.endswith("_factor") else float(getattr(self.material, parameter) or 0.0)

    def _values(self, sample: Sample) -> dict[str, float]:
        """Parameter -> value of a sample (the model's value for those the sample leaves out)."""
        missing = sorted(set(self.variables) - set(sample))
        if missing:
            raise KeyError(f"the sample has no value for {missing}")
        return {p: float(sample[k]) for k, p in self.variables.items()}

    def _scene(self, values: Mapping[str, float]) -> tuple[Material, NDArray[np.float64], NDArray[np.float64]]:
        """The material (checked by :class:`Material`) and ``(b_fixed, b_live)`` of parameter
        ``values`` (the model's for the others)."""
        material = replace(self.material, **{p: v for p, v in values.items() if not p.endswith("_factor")})
        return material, self.b_fixed * values.get("fixed_factor", 1.0), self.b_live * values.get("live_factor", 1.0)

    def _problem(self, values: Mapping[str, float]) -> ConicProblem:
        """The limit problem with the parameters ``values`` (the model's for the others)."""
        material, b_fixed, b_live = self._scene(values)
        return limit_problem(Formulation(self.model, material), b_fixed, b_live)

    def __call__(self, sample: Sample) -> tuple[str, float]:
        """``(status, lambda_max)`` of one sample (``lambda_max`` NaN unless ``optimal``, inf
        when unbounded).

        Raises
        ------
        KeyError
            The sample lacks a variable.
        ValueError
            A value the material refuses (a negative friction, ...), named.
        """
        A, b = self.data(sample)
        self.solver.update(b=b, A=A)
        sol = self.solver.solve()
        if sol.status == "PrimalInfeasible":
            return "infeasible", math.nan
        if sol.solved and self.violation(A, b, sol.x) <= 1e-8:
            return "optimal", float(sol.x[-1])
        return self.fallback(sample)

    def data(self, sample: Sample) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """A sample's limit problem: the nonzero values of ``A`` (in the CSC order of
        ``base.A.data``) and ``b``; the sparsity pattern, ``q`` and the cones are ``base``'s.

        Raises
        ------
        KeyError, ValueError
            As :meth:`__call__`.
        """
        values = self._values(sample)
        self._scene(values)  # a value the material refuses raises here
        A, b = self.base.A.data.copy(), self.base.b.copy()
        for p, v in values.items():
            dA, db = self.sensitivity[p]
            d = v - self._base_value(p)
            A += d * dA
            b += d * db
        return A, b

    def violation(self, A: NDArray[np.float64], b: NDArray[np.float64], x: NDArray[np.float64]) -> float:
        """Largest violation of ``A x + s = b, s in K`` by ``s = b - A x`` for the problem
        :meth:`data` gives (the equilibrium rows' residual and the contact law's violation, on
        the scaled problem: an answer is accepted at 1e-8)."""
        np.copyto(self._A.data, A)
        s = b - self._A @ x
        zero, nonneg, soc = self._rows
        cones = s[soc]
        return max(float(np.abs(s[zero]).max(initial=0.0)), float(-s[nonneg].min(initial=0.0)),
                   float((np.linalg.norm(cones[:, 1:], axis=1) - cones[:, 0]).max(initial=0.0)))

    def fallback(self, sample: Sample) -> tuple[str, float]:
        """``(status, lambda_max)`` of a sample by a fresh :class:`LimitSolver` with its
        material (retry, unbounded proof): for an answer that fails :meth:`violation`."""
        material, b_fixed, b_live = self._scene(self._values(sample))
        res = LimitSolver(self.model, material).solve_loads(b_fixed, b_live, mechanism=False)
        log.info("warm limit solve not clean; fresh solve: %s (%s)", res.status, res.message)
        return res.status, res.lambda_max


def _cone_rows(cones: Sequence[tuple[str, int]]) -> tuple[NDArray[np.int64], NDArray[np.int64], NDArray[np.int64]]:
    """The rows of the zero cones, of the nonnegative cones, and ``(k, 3)`` of the 3D
    second-order cones of a cone list (:class:`tce.core.problem.ConicProblem`)."""
    parts: dict[str, list[NDArray[np.int64]]] = {"zero": [], "nonneg": [], "soc": []}
    row = 0
    for kind, dim in cones:
        if kind == "soc" and dim != 3:
            raise ValueError(f"only 3D second-order cones are checked, got one of dimension {dim}")
        parts[kind].append(np.arange(row, row + dim))
        row += dim
    flat = {k: np.concatenate(v) if v else np.zeros(0, dtype=np.int64) for k, v in parts.items()}
    return flat["zero"], flat["nonneg"], flat["soc"].reshape(-1, 3)


class RebuiltLimit:
    """Direct ``lambda_max`` of an analysis built anew for each sample (any variable).

    Parameters
    ----------
    build : callable
        ``build(sample) -> (Analysis, LoadPattern or None)``; None is the lateral pattern at
        ``alpha = 0``.
    """

    def __init__(self, build: Callable[[Sample], tuple[Analysis, LoadPattern | None]]) -> None:
        self.build = build

    def __call__(self, sample: Sample) -> tuple[str, float]:
        """``(status, lambda_max)`` of one sample (no mechanism is classified)."""
        analysis, loads = self.build(sample)
        res = analysis.limit(alpha=None if loads is not None else 0.0, loads=loads, mechanism=False)
        return res.status, res.lambda_max


# --------------------------------------------------------------------------- estimators
@dataclass(frozen=True)
class FailureEstimate:
    """``P(capacity < threshold)`` from a sample.

    Attributes
    ----------
    pf : float
        Failures over the decided samples (NaN when none is decided).
    n : int
        Decided samples (every status but ``numerical``).
    failures : int
        Samples whose capacity is below the threshold (``infeasible`` ones included).
    numerical : int
        Samples whose solve was undecided: left out of ``pf`` and ``n``, reported here.
    statuses : dict
        Count of every status word.
    wilson, clopper_pearson : (float, float)
        Two-sided intervals of ``pf`` at ``confidence`` (binomial sampling: exact for plain
        Monte Carlo, conservative in practice for Latin hypercube and Sobol samples).
    beta : float
        Reliability index ``-Phi^-1(pf)``.
    beta_interval : (float, float)
        ``beta`` of the Clopper-Pearson bounds, in increasing order (the first from the upper
        bound of ``pf``).
    confidence : float
    """

    pf: float
    n: int
    failures: int
    numerical: int
    statuses: dict[str, int]
    wilson: tuple[float, float]
    clopper_pearson: tuple[float, float]
    beta: float
    beta_interval: tuple[float, float]
    confidence: float


def failure_probability(values: ArrayLike, threshold: float, statuses: ArrayLike | None = None,
                        confidence: float = 0.95) -> FailureEstimate:
    """Estimate ``P(capacity < threshold)`` from sampled capacities.

    Parameters
    ----------
    values : (n,) array_like
        Capacities (:func:`outcome_value`: ``-inf`` fails, ``+inf`` survives, NaN undecided).
    threshold : float
        Failure when the capacity is below it (same units as the capacities).
    statuses : (n,) array_like of str, optional
        The status words, counted in the result.
    confidence : float
        Of the intervals (``scipy.stats.binomtest``'s ``proportion_ci``: ``wilson`` and
        ``exact``, the Clopper-Pearson interval).
    """
    v = np.asarray(values, dtype=float)
    decided = ~np.isnan(v)
    n, k = int(decided.sum()), int((v[decided] < threshold).sum())
    words, counts = np.unique(np.asarray(statuses if statuses is not None else [], dtype=str), return_counts=True)
    if n == 0:
        nan2 = (math.nan, math.nan)
        return FailureEstimate(math.nan, 0, 0, int((~decided).sum()), dict(zip(words.tolist(), counts.tolist())),
                               nan2, nan2, math.nan, nan2, confidence)
    test = stats.binomtest(k, n)
    wil = test.proportion_ci(confidence, method="wilson")
    cp = test.proportion_ci(confidence, method="exact")
    beta = lambda p: float(-special.ndtri(p))  # noqa: E731
    return FailureEstimate(
        pf=k / n, n=n, failures=k, numerical=int((~decided).sum()),
        statuses=dict(zip(words.tolist(), map(int, counts))),
        wilson=(float(wil.low), float(wil.high)), clopper_pearson=(float(cp.low), float(cp.high)),
        beta=beta(k / n), beta_interval=(beta(cp.high), beta(cp.low)), confidence=confidence,
    )


@dataclass(frozen=True)
class FormResult:
    """First-order reliability (Hasofer and Lind 1974; Rackwitz and Fiessler 1978).

    Attributes
    ----------
    beta : float
        Reliability index: the distance from the origin of the standard normal space to the
        design point, negative when the mean point fails.
    pf : float
        ``Phi(-beta)``.
    u, x : ndarray
        The design point in standard normal space and in physical values.
    alpha : ndarray
        Unit vector ``-grad g / |grad g|`` at the design point (importance of each ``u_i``).
    converged : bool
        Both ``|u_k+1 - u_k| <= tol (1 + |u_k|)`` and ``|g(u)| <= tol |g(0)|`` were met.
    iterations, evaluations : int
        HL-RF steps and capacity evaluations.
    message : str
        How it ended.
    """

    beta: float
    pf: float
    u: NDArray[np.float64]
    x: NDArray[np.float64]
    alpha: NDArray[np.float64]
    converged: bool
    iterations: int
    evaluations: int
    message: str


class _Undecided(Exception):
    """A capacity evaluation whose status is not ``optimal`` (FORM needs a finite g)."""


def form(joint: JointDistribution, capacity: Capacity, threshold: float, tol: float = 1e-6, max_iter: int = 50,
         step: float = 1e-4, start: ArrayLike | None = None) -> FormResult:
    """The design point of ``g(u) = capacity(x(u)) - threshold`` by the HL-RF iteration.

    ``u_k+1 = ((grad g . u_k - g(u_k)) / |grad g|^2) grad g`` from ``start`` (default the
    origin, the mean point), the gradient by forward differences of step ``step`` in the
    standard normal space (``scipy.optimize.approx_fprime``). Exact in one step for a limit
    state linear in normal variables. It stops unconverged, saying why, where a capacity is
    not finite (a status other than ``optimal``), where the gradient vanishes (below
    ``1e-8 |g|``: a capacity flat in the variables there, e.g. a hinge mechanism that friction
    does not govern; start elsewhere) or where a step leaves ``|u| <= 40``.
    """
    evaluations = 0

    def g(u: NDArray[np.float64]) -> float:
        nonlocal evaluations
        evaluations += 1
        status, value = capacity(joint.records(joint.to_physical(u))[0])
        if status != "optimal":
            raise _Undecided(f"capacity {status} at u = {np.round(u, 6).tolist()}")
        return value - threshold

    u = np.zeros(joint.dim) if start is None else np.array(start, dtype=float).reshape(joint.dim)
    grad = np.zeros(joint.dim)
    message, converged, k = "iteration limit reached", False, 0
    try:
        g0 = gu = g(u)
        for k in range(1, max_iter + 1):
            grad = optimize.approx_fprime(u, g, step)
            norm2 = float(grad @ grad)
            if math.sqrt(norm2) <= 1e-8 * abs(gu):
                message = f"the gradient vanishes at u = {np.round(u, 6).tolist()}: the capacity is flat there"
                break
            new = (float(grad @ u) - gu) / norm2 * grad
            if not float(np.linalg.norm(new)) <= 40.0:
                message = f"diverged: a step to |u| = {float(np.linalg.norm(new)):.3g}"
                break
            moved = float(np.linalg.norm(new - u))
            u, gu = new, g(new)
            if moved <= tol * (1 + float(np.linalg.norm(u))) and abs(gu) <= tol * max(abs(g0), 1e-300):
                converged, message = True, f"converged in {k} iterations"
                break
    except _Undecided as e:
        message = str(e)
    norm = float(np.linalg.norm(grad))
    alpha = -grad / norm if norm else grad
    beta = float(alpha @ u) if converged else math.nan  # u* = beta alpha at the design point
    return FormResult(beta=beta, pf=float(special.ndtr(-beta)), u=u, x=joint.to_physical(u)[0], alpha=alpha,
                      converged=converged, iterations=k, evaluations=evaluations, message=message)


@dataclass(frozen=True)
class SubsetResult:
    """Subset simulation (Au and Beck 2001).

    Attributes
    ----------
    pf : float
        ``p0^(L-1) * P(g < 0 | F_L-1)`` over the ``L`` levels.
    cov : float
        Its coefficient of variation, ``sqrt(sum_j delta_j^2)`` with
        ``delta_j^2 = (1 - p_j) / (p_j N) (1 + gamma_j)`` (Au and Beck 2001), ``gamma_j`` from
        the correlation of the failure indicators along the Markov chains (0 at level 0); it
        neglects the correlation between levels.
    beta : float
        ``-Phi^-1(pf)``.
    thresholds : tuple of float
        The intermediate thresholds of ``g`` (capacity minus threshold), the last one 0.
    level_cov : tuple of float
        ``delta_j`` of each level.
    evaluations : int
        Capacity evaluations.
    numerical : int
        Evaluations whose solve was undecided (NaN: taken as not failing at any level,
        a Markov chain candidate rejected).
    converged : bool
        The last level reached ``g < 0`` within ``max_levels``.
    """

    pf: float
    cov: float
    beta: float
    thresholds: tuple[float, ...]
    level_cov: tuple[float, ...]
    evaluations: int
    numerical: int
    converged: bool


def subset_simulation(joint: JointDistribution, capacity: Capacity, threshold: float, n: int = 1000,
                      p0: float = 0.1, seed: int | None = None, max_levels: int = 20,
                      spread: float = 1.0) -> SubsetResult:
    """``P(capacity < threshold)`` by subset simulation with the modified Metropolis algorithm.

    Level 0 draws ``n`` plain Monte Carlo points of the standard normal space. At each level
    the ``n p0`` points of least ``g = capacity - threshold`` are the seeds; the level's
    threshold ``b_j`` is halfway between the ``n p0``-th and the next ``g`` (0 when more than
    ``n p0`` points fail: the last level). Each seed grows a chain of ``1 / p0`` states: per
    component a candidate ``xi ~ N(u_i, spread^2)`` is accepted with probability
    ``min(1, phi(xi) / phi(u_i))`` (Au and Beck 2001), the whole candidate kept when
    ``g <= b_j``, the current state repeated otherwise.

    Parameters
    ----------
    n : int
        Samples per level; ``n p0`` and ``1 / p0`` must be integers.
    p0 : float
        Conditional probability of each intermediate level.
    seed : int, optional
        ``numpy.random.default_rng`` seed.
    spread : float
        Standard deviation of the component proposal (standard normal units).
    """
    nc, ns = round(n * p0), round(1 / p0)
    if not (0 < p0 < 1 and abs(nc - n * p0) < 1e-9 and abs(ns - 1 / p0) < 1e-9 and nc >= 1):
        raise ValueError(f"n p0 and 1 / p0 must be positive integers, got n = {n}, p0 = {p0}")
    rng = np.random.default_rng(seed)
    evaluations = numerical = 0

    def g(u: NDArray[np.float64]) -> NDArray[np.float64]:
        nonlocal evaluations, numerical
        values = evaluate(capacity, joint.records(joint.to_physical(u)))[1]
        evaluations += len(u)
        numerical += int(np.isnan(values).sum())
        return np.where(np.isnan(values), np.inf, values - threshold)

    u = rng.standard_normal((n, joint.dim))
    gu = g(u)
    pf, thresholds, deltas = 1.0, [], []
    chains: NDArray[np.float64] | None = None  # (nc, ns) g along the level's chains; None at level 0
    converged = False
    for _ in range(max_levels):
        order = np.argsort(gu, kind="stable")
        converged = int((gu < 0).sum()) >= nc
        b = 0.0 if converged else 0.5 * (gu[order[nc - 1]] + gu[order[nc]])
        if not np.isfinite(b):
            log.warning("subset simulation: fewer than n p0 finite capacities at a level; stopped")
            break
        p = float(np.mean(gu < b)) if converged else p0
        thresholds.append(float(b))
        gamma = 0.0 if chains is None else _chain_gamma(chains < b, p, n)
        deltas.append(math.sqrt((1 - p) / (p * n) * (1 + gamma)))
        pf *= p
        if converged:
            break
        chains = np.empty((nc, ns))
        chain_u = np.empty((nc, ns, joint.dim))
        cu, cg = u[order[:nc]], gu[order[:nc]]
        for step in range(ns):
            xi = cu + spread * rng.standard_normal(cu.shape)
            cand = np.where(rng.random(cu.shape) < np.exp(-0.5 * (xi**2 - cu**2)), xi, cu)
            moved = np.any(cand != cu, axis=1)
            gc = cg.copy()
            if moved.any():
                gc[moved] = g(cand[moved])
            keep = moved & (gc <= b)
            cu, cg = np.where(keep[:, None], cand, cu), np.where(keep, gc, cg)
            chain_u[:, step], chains[:, step] = cu, cg
        u, gu = chain_u.reshape(n, joint.dim), chains.reshape(n)
    else:
        log.warning("subset simulation stopped after %d levels without reaching failure", max_levels)
    cov = math.sqrt(sum(d * d for d in deltas))
    return SubsetResult(pf=pf if converged else math.nan, cov=cov if converged else math.nan,
                        beta=float(-special.ndtri(pf)) if converged else math.nan, thresholds=tuple(thresholds),
                        level_cov=tuple(deltas), evaluations=evaluations, numerical=numerical, converged=converged)


def _chain_gamma(indicators: NDArray[np.bool_], p: float, n: int) -> float:
    """``gamma_j`` of Au and Beck (2001) from the failure indicators ``(nc, ns)``
    of ``nc`` Markov chains of ``ns`` states (``n = nc ns``) and the level's probability ``p``::

        R(k) = sum_j sum_l<=ns-k I_jl I_j,l+k / (n - k nc) - p^2,   rho(k) = R(k) / R(0)
        gamma = 2 sum_k=1..ns-1 (1 - k nc / n) rho(k)
    """
    nc, ns = indicators.shape
    I = indicators.astype(float)
    R = np.array([(I[:, : ns - k] * I[:, k:]).sum() / (n - k * nc) - p * p for k in range(ns)])
    if R[0] <= 0:
        return 0.0
    k = np.arange(1, ns)
    return float(2 * np.sum((1 - k * nc / n) * R[1:] / R[0]))
