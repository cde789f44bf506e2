"""The probability of collapse (tce.analysis.reliability) against closed forms tce did not produce.

- a block that slides at lambda = mu (rocking far above): with a lognormal mu, P(lambda_max < x)
  is the lognormal CDF; with cohesion c on a contact of area A under weight W, lambda = mu + c A / W;
- a block b wide and h high that rocks at lambda = b / h, with a normal width;
- FORM on a limit state linear in correlated normal variables: beta = g(m) / sqrt(a' C a) and
  the design point x* = m - g(m) C a / (a' C a), exact;
- subset simulation at a probability near 1e-3 against the exact one, within its stated c.o.v.;
- the Wilson and Clopper-Pearson intervals covering the exact probability at their stated rate.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from helpers import block_on_support
from scipy import special

from tce.analysis import Analysis
from tce.analysis.reliability import (
    JointDistribution,
    RandomVariable,
    RebuiltLimit,
    WarmLimit,
    evaluate,
    failure_probability,
    form,
    subset_simulation,
)
from tce.core.material import Material

#: a flat block, 1.0 x 0.4 x 0.1 m: rocks at b / h = 10, so it slides at lambda = mu for any mu drawn
FLAT = dict(b=1.0, h=0.1, d=0.4)
FRICTION = RandomVariable("mu", "lognormal", 0.6, cov=0.15)


@pytest.fixture(scope="module")
def sliding() -> WarmLimit:
    an = Analysis(block_on_support(**FLAT), Material(0.6, cohesion=1.0), model="spatial")
    return WarmLimit(an, {"mu": "friction", "c": "cohesion"}, alpha=0.0)


def _lognormal_cdf(x: float) -> float:
    """P(mu < x) of FRICTION from its mean and c.o.v., written out (not scipy's lognorm)."""
    s2 = math.log(1 + 0.15**2)
    return float(special.ndtr((math.log(x) - (math.log(0.6) - s2 / 2)) / math.sqrt(s2)))


def test_marginals_have_the_given_mean_and_std():
    """Every conversion gives a distribution with exactly the mean and std asked for, and the
    lognormal's CDF is the closed form (a std given where the variance belongs fails here)."""
    for rv in [RandomVariable("a", "normal", 2.0, std=0.3), RandomVariable("b", "lognormal", 0.6, cov=0.15),
               RandomVariable("c", "uniform", 1.0, std=0.2), RandomVariable("d", "gumbel_r", 5.0, cov=0.3),
               RandomVariable("e", "truncnorm", 0.6, std=0.2, bounds=(0.3, 1.2))]:
        f = rv.frozen()
        assert f.mean() == pytest.approx(rv.mean, rel=1e-9), rv
        assert f.std() == pytest.approx(rv.spread, rel=1e-9), rv
    assert FRICTION.frozen().cdf(0.5) == pytest.approx(_lognormal_cdf(0.5), rel=1e-12)
    # Gumbel written out: scale = s sqrt(6) / pi, loc = m - Euler gamma scale
    g = RandomVariable("d", "gumbel_r", 5.0, std=1.5).frozen()
    beta = 1.5 * math.sqrt(6) / math.pi
    assert g.cdf(5.5) == pytest.approx(math.exp(-math.exp(-(5.5 - (5.0 - np.euler_gamma * beta)) / beta)), rel=1e-12)


def test_copula_correlation_in_normal_space():
    """Normal marginals keep the copula's correlation: the sample correlation of 20000 points
    is the one asked for within 4 standard errors (1 - r^2) / sqrt(n)."""
    R = np.array([[1.0, 0.6, -0.3], [0.6, 1.0, 0.2], [-0.3, 0.2, 1.0]])
    joint = JointDistribution([RandomVariable(k, "normal", 1.0, std=0.1) for k in "abc"], R)
    _, x = joint.sample(20000, "mc", seed=5)
    got = np.corrcoef(x.T)
    np.testing.assert_allclose(got, R, atol=4 * (1 - R**2).max() / math.sqrt(20000) + 1e-12)


def test_sliding_block_lognormal_friction(sliding):
    """lambda_max = mu + c A / W for every drawn mu (to 1e-8), and the estimate of
    P(lambda_max < x) has the lognormal CDF inside its Wilson interval at three levels."""
    joint = JointDistribution([FRICTION])
    _, x = joint.sample(400, "lhs", seed=11)
    cA_W = 1.0 * 0.4 / (20.0 * 0.04)  # c A / W: A = 1.0 x 0.4 m^2, W = 20 kN/m^3 x 0.04 m^3
    samples = [{"mu": mu, "c": 0.0} for mu in x[:, 0]]
    statuses, values = evaluate(sliding, samples)
    assert set(statuses) == {"optimal"}
    np.testing.assert_allclose(values, x[:, 0], rtol=1e-8)
    _, with_c = evaluate(sliding, [{"mu": mu, "c": 1.0} for mu in x[:40, 0]])
    np.testing.assert_allclose(with_c, x[:40, 0] + cA_W, rtol=1e-8)
    for level in (0.45, 0.55, 0.7):
        est = failure_probability(values, level, statuses)
        assert est.n == 400 and est.numerical == 0
        assert est.wilson[0] <= _lognormal_cdf(level) <= est.wilson[1], (level, est)


def test_rocking_block_normal_width():
    """A block of normal width b (h = 1 m, unlimited friction) rebuilt per sample rocks at
    lambda = b / h, and P(lambda_max < x) = Phi((x h - m) / s) lies in the Wilson interval."""
    width = RandomVariable("b", "normal", 0.4, std=0.03)
    capacity = RebuiltLimit(lambda s: (Analysis(block_on_support(s["b"], 1.0), Material(), model="spatial"), None))
    joint = JointDistribution([width])
    _, x = joint.sample(128, "sobol", seed=2)
    statuses, values = evaluate(capacity, joint.records(x))
    np.testing.assert_allclose(values, x[:, 0] / 1.0, rtol=1e-9)
    for level in (0.37, 0.42):
        est = failure_probability(values, level, statuses)
        assert est.wilson[0] <= special.ndtr((level - 0.4) / 0.03) <= est.wilson[1]


def test_form_exact_on_a_linear_limit_state():
    """g = a0 + a . x with x normal and correlated: beta = g(m) / sqrt(a' C a) and the design
    point x* = m - g(m) C a / (a' C a), to 1e-6."""
    m, s = np.array([1.0, 2.0, 0.5]), np.array([0.5, 0.3, 0.2])
    R = np.array([[1.0, 0.5, -0.2], [0.5, 1.0, 0.3], [-0.2, 0.3, 1.0]])
    a, a0 = np.array([1.0, -2.0, 3.0]), 4.0
    C = R * np.outer(s, s)
    joint = JointDistribution([RandomVariable(k, "normal", mk, std=sk) for k, mk, sk in zip("xyz", m, s)], R)
    res = form(joint, lambda d: ("optimal", a0 + a @ [d["x"], d["y"], d["z"]]), threshold=0.0)
    gm, var = a0 + a @ m, a @ C @ a
    assert res.converged
    assert res.beta == pytest.approx(gm / math.sqrt(var), abs=1e-6)
    np.testing.assert_allclose(res.x, m - gm * C @ a / var, atol=1e-6)
    assert res.pf == pytest.approx(special.ndtr(-gm / math.sqrt(var)), rel=1e-5)


def test_subset_simulation_near_1e3_on_the_sliding_block(sliding):
    """P(lambda_max < x) with x the lognormal's 1e-3 quantile, by subset simulation over tce's
    solves: within 3 of its stated c.o.v. of the exact 1e-3."""
    x = float(FRICTION.frozen().ppf(1e-3))
    joint = JointDistribution([FRICTION])
    res = subset_simulation(joint, lambda s: sliding({"mu": s["mu"], "c": 0.0}), x, n=500, seed=4)
    assert res.converged and res.numerical == 0 and len(res.thresholds) == 3
    assert abs(res.pf / 1e-3 - 1) <= 3 * res.cov, res


def test_subset_simulation_cov_is_what_it_states():
    """Over 40 seeds on a linear limit state in two normals (pf = Phi(-3.09) ~ 1e-3): the
    estimates' mean is the exact value within 3 standard errors and their scatter (c.o.v.) is
    within a factor 1.6 of the c.o.v. each run states."""
    joint = JointDistribution([RandomVariable("a", "normal", 0.0, std=1.0), RandomVariable("b", "normal", 0.0, std=1.0)])
    beta = 3.09
    exact = float(special.ndtr(-beta))
    runs = [subset_simulation(joint, lambda s: ("optimal", beta - (s["a"] + s["b"]) / math.sqrt(2)), 0.0, n=500, seed=k)
            for k in range(40)]
    pf = np.array([r.pf for r in runs])
    stated = float(np.mean([r.cov for r in runs]))
    assert abs(pf.mean() - exact) <= 3 * pf.std(ddof=1) / math.sqrt(len(pf))
    assert stated / 1.6 <= pf.std(ddof=1) / exact <= 1.6 * stated


@pytest.mark.parametrize("pf, n", [(0.1, 100), (0.02, 300)])
def test_intervals_cover_at_their_rate(pf, n):
    """Over 600 seeds of n plain Monte Carlo samples of a closed-form capacity (a standard normal
    with failure below its pf-quantile): the 95 % Clopper-Pearson interval covers the exact pf
    at least 95 % of the time (to 3 binomial standard errors) and the Wilson interval 95 % to
    3 standard errors (it is approximate, not conservative)."""
    joint = JointDistribution([RandomVariable("z", "normal", 0.0, std=1.0)])
    level = float(special.ndtri(pf))
    cover = np.zeros((600, 2), dtype=bool)
    for k in range(600):
        est = failure_probability(joint.sample(n, "mc", seed=k)[1][:, 0], level)
        cover[k] = (est.wilson[0] <= pf <= est.wilson[1], est.clopper_pearson[0] <= pf <= est.clopper_pearson[1])
    se = 3 * math.sqrt(0.95 * 0.05 / 600)
    wilson, cp = cover.mean(axis=0)
    assert cp >= 0.95 - se
    assert abs(wilson - 0.95) <= se
