"""tce.analysis.reliability: the warm capacity against fresh analyses, statuses never dropped,
reproducible samples, and the refusals."""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
import pytest

from tce.analysis import Analysis
from tce.analysis.reliability import (
    JointDistribution,
    RandomVariable,
    WarmLimit,
    evaluate,
    failure_probability,
    form,
    subset_simulation,
)
from tce.core.loads import LoadPattern, PointLoad
from tce.core.material import Material
from tce.structures.arch import semicircular_arch


@lru_cache(maxsize=None)
def _fresh(mu: float, cohesion: float = 0.0) -> float:
    """lambda_max of the paper's arch (in plane) from a new Analysis; NaN unless optimal."""
    return Analysis(semicircular_arch(), Material(mu, cohesion=cohesion)).limit(0.0, mechanism=False).lambda_max


@pytest.fixture(scope="module")
def warm() -> WarmLimit:
    return WarmLimit(Analysis(semicircular_arch(), Material(0.6)),
                     {"mu": "friction", "g": "fixed_factor", "q": "live_factor"}, alpha=0.0)


@pytest.mark.parametrize("mu", [0.2, 0.45, 0.5, 0.7, 1.3])
def test_warm_friction_is_a_fresh_analysis(warm, mu):
    """Friction changed in the warm solver gives the status and lambda_max of an analysis built
    for it (infeasible below about 0.33: the arch slides under its own weight), to 1e-8."""
    status, lam = warm({"mu": mu, "g": 1.0, "q": 1.0})
    fresh = _fresh(mu)
    assert status == ("infeasible" if math.isnan(fresh) else "optimal")
    if status == "optimal":
        assert lam == pytest.approx(fresh, abs=1e-8)


@pytest.mark.parametrize("g, q", [(2.0, 1.0), (1.0, 0.5), (1.3, 2.0)])
def test_warm_load_factors(warm, g, q):
    """Dry joints: scaling the fixed loads by g and the live ones by q scales lambda_max by g / q."""
    status, lam = warm({"mu": 0.7, "g": g, "q": q})
    assert status == "optimal"
    assert lam == pytest.approx(_fresh(0.7) * g / q, rel=1e-8)


def test_warm_cohesion_on_the_arch():
    """Cohesion changed warm gives a fresh analysis' lambda_max (and repeated samples, in any
    order, the same answers: the solver keeps no state between samples that changes them)."""
    w = WarmLimit(Analysis(semicircular_arch(), Material(0.6, cohesion=0.5)), {"c": "cohesion"}, alpha=0.0)
    first = [w({"c": c})[1] for c in (0.5, 2.0, 0.1)]
    assert first == pytest.approx([_fresh(0.6, c) for c in (0.5, 2.0, 0.1)], abs=1e-8)
    assert [w({"c": c})[1] for c in (0.1, 2.0, 0.5)] == pytest.approx(first[::-1], abs=1e-9)


def test_warm_with_tension_near_the_cone_apex():
    """A material with cohesion and a tensile strength near cohesion / friction: friction,
    cohesion and tension changed warm (together) give a fresh analysis' lambda_max."""
    base = Material(0.6, cohesion=1.0, tensile_strength=1.5)  # c / mu = 1.67 kN/m^2
    w = WarmLimit(Analysis(semicircular_arch(), base), {"mu": "friction", "c": "cohesion", "t": "tensile_strength"},
                  alpha=0.0)
    for mu, c, t in [(0.6, 1.0, 1.5), (0.9, 2.0, 0.5), (0.45, 0.8, 1.7)]:
        fresh = Analysis(semicircular_arch(), Material(mu, cohesion=c, tensile_strength=t)).limit(0.0, mechanism=False)
        assert w({"mu": mu, "c": c, "t": t}) == (fresh.status, pytest.approx(fresh.lambda_max, abs=1e-8))


def test_warm_live_point_load():
    """With a live point load on the crown, the live factor divides lambda_max (its adequacy factor)."""
    loads = LoadPattern(lateral=False, point=[PointLoad(force=[0.0, 0.0, -1.0], block="v07")])
    an = Analysis(semicircular_arch(), Material(0.8))
    w = WarmLimit(an, {"Q": "live_factor"}, loads=loads)
    base = an.limit(loads=loads, mechanism=False).lambda_max
    assert w({"Q": 2.5}) == ("optimal", pytest.approx(base / 2.5, rel=1e-8))


def test_warm_refusals():
    """Parameters the warm solver cannot change, a structure that changes, missing keys."""
    arch = semicircular_arch()
    with pytest.raises(ValueError, match="not among"):
        WarmLimit(Analysis(arch, Material(0.6)), {"t": "thickness"})
    with pytest.raises(ValueError, match="structure"):
        WarmLimit(Analysis(arch, Material()), {"mu": "friction"}, alpha=0.0)  # Heyman: no friction rows
    with pytest.raises(ValueError, match="structure"):
        WarmLimit(Analysis(arch, Material(0.6)), {"c": "cohesion"}, alpha=0.0)  # no cohesion rows at c = 0
    w = WarmLimit(Analysis(arch, Material(0.6)), {"mu": "friction"}, alpha=0.0)
    with pytest.raises(KeyError, match="mu"):
        w({"friction": 0.5})
    with pytest.raises(ValueError, match="friction"):
        w({"mu": -0.1})


def test_statuses_are_counted_never_dropped():
    """Unbounded survives, infeasible fails, numerical is counted apart and left out of pf."""
    answers = {0: ("optimal", 0.5), 1: ("optimal", 2.0), 2: ("unbounded", math.inf), 3: ("infeasible", math.nan),
               4: ("numerical", math.nan)}
    statuses, values = evaluate(lambda s: answers[int(s["k"])], [{"k": k} for k in range(5)])
    est = failure_probability(values, 1.0, statuses)
    assert (est.n, est.failures, est.numerical) == (4, 2, 1)
    assert est.pf == 0.5
    assert est.statuses == {"infeasible": 1, "numerical": 1, "optimal": 2, "unbounded": 1}
    assert est.beta == pytest.approx(0.0, abs=1e-15)
    assert est.clopper_pearson[0] < est.wilson[0] < 0.5 < est.wilson[1] < est.clopper_pearson[1]
    assert est.beta_interval[0] < 0 < est.beta_interval[1]


@pytest.mark.parametrize("method", ["mc", "lhs", "sobol"])
def test_samples_are_reproducible(method):
    """The same (n, method, seed) gives the same points; another seed others. LHS puts one
    point in each of the n strata of every variable."""
    joint = JointDistribution([RandomVariable("a", "lognormal", 0.6, cov=0.2), RandomVariable("b", "normal", 1.0, std=0.1)],
                              [[1.0, 0.4], [0.4, 1.0]])
    u1, x1 = joint.sample(64, method, seed=3)
    u2, x2 = joint.sample(64, method, seed=3)
    np.testing.assert_array_equal(x1, x2)
    assert not np.allclose(joint.sample(64, method, seed=4)[0], u1)
    assert np.all(x1[:, 0] > 0)
    if method == "lhs":
        from scipy import special

        strata = np.sort(np.floor(special.ndtr(u1) * 64), axis=0)
        np.testing.assert_array_equal(strata, np.tile(np.arange(64)[:, None], (1, 2)))


def test_variable_refusals():
    """Each refusal names the variable and what is wrong."""
    with pytest.raises(ValueError, match="exactly one of std and cov"):
        RandomVariable("a", "normal", 1.0, std=0.1, cov=0.1)
    with pytest.raises(ValueError, match="not a scipy.stats"):
        RandomVariable("a", "gaussian", 1.0, std=0.1)
    with pytest.raises(ValueError, match="positive mean"):
        RandomVariable("a", "lognormal", -1.0, std=0.1)
    with pytest.raises(ValueError, match="shape parameters"):
        RandomVariable("a", "weibull_min", 1.0, std=0.1)
    with pytest.raises(ValueError, match="bounds"):
        RandomVariable("a", "normal", 1.0, std=0.1, bounds=(0.0, 2.0))
    with pytest.raises(ValueError, match="positive definite"):
        JointDistribution([RandomVariable(k, "normal", 1.0, std=0.1) for k in "ab"], [[1.0, 1.2], [1.2, 1.0]])
    with pytest.raises(ValueError, match="distinct names"):
        JointDistribution([RandomVariable("a", "normal", 1.0, std=0.1)] * 2)
    with pytest.raises(ValueError, match="method"):
        JointDistribution([RandomVariable("a", "normal", 1.0, std=0.1)]).sample(4, "halton")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="integers"):
        subset_simulation(JointDistribution([RandomVariable("a", "normal", 1.0, std=0.1)]), lambda s: ("optimal", 1.0),
                          0.0, n=105)


def test_form_stops_on_an_undecided_capacity():
    """FORM needs a finite limit state: a status other than optimal stops it, unconverged, saying which."""
    joint = JointDistribution([RandomVariable("a", "normal", 1.0, std=0.5)])
    res = form(joint, lambda s: ("optimal", s["a"]) if s["a"] > 0.8 else ("infeasible", math.nan), threshold=0.2)
    assert not res.converged and "infeasible" in res.message and math.isnan(res.beta)


def test_form_on_the_arch_with_uncertain_friction():
    """The paper's arch (in plane) with a lognormal friction: lambda_max is flat above mu ~ 0.58
    (four hinges, friction idle), so FORM from the mean stops and says so; started in the
    sliding range it finds mu* with lambda_max(mu*) = 0.1, and with one monotone variable its
    pf is exact: the lognormal CDF at mu*."""
    warm = WarmLimit(Analysis(semicircular_arch(), Material(0.7)), {"mu": "friction"}, alpha=0.0)
    joint = JointDistribution([RandomVariable("mu", "lognormal", 0.7, cov=0.15)])
    flat = form(joint, warm, 0.1)
    assert not flat.converged and "flat" in flat.message
    res = form(joint, warm, 0.1, start=[-2.0])
    assert res.converged
    assert warm({"mu": float(res.x[0])})[1] == pytest.approx(0.1, abs=1e-6)
    assert res.pf == pytest.approx(joint.marginals[0].cdf(res.x[0]), rel=1e-9)
    assert res.beta > 0 and res.alpha[0] == pytest.approx(-1.0)


def test_a_warm_answer_failing_the_checks_is_solved_afresh(monkeypatch, caplog):
    """A warm solve reported solved whose multiplier is 1e-6 too high (equilibrium then fails
    by about that much) is not taken: a fresh LimitSolver answers, with the right value."""
    from types import SimpleNamespace

    from tce.core.clarabel_solver import Solution

    warm = WarmLimit(Analysis(semicircular_arch(), Material(0.6)), {"mu": "friction"}, alpha=0.0)
    solve = warm.solver.solve

    def off() -> Solution:
        sol = solve()
        x = sol.x.copy()
        x[-1] += 1e-6
        return Solution(sol.status, SimpleNamespace(x=x, z=sol.z, s=sol.s, obj_val=0.0, iterations=0), 0.0, 0.0)

    monkeypatch.setattr(warm.solver, "solve", off)
    with caplog.at_level("INFO", logger="tce.analysis.reliability"):
        status, lam = warm({"mu": 0.8})
    assert status == "optimal" and lam == pytest.approx(_fresh(0.8), abs=1e-9)
    assert "fresh solve" in caplog.text
