"""An uncertainty study file against a closed form tce did not produce: a flat block on a slab
slides at lambda = mu (it rocks at b / h = 10), so with a lognormal friction, mean 0.6 and
c.o.v. 0.15, P(lambda_max < x) is the lognormal CDF, written out here from the mean and c.o.v.
Through ``tce``'s study path: the section read from TOML, the draw, the jobs of samples, the
merged statistics and fragility curve, FORM (exact here: the limit state is monotone in one
variable) and subset simulation."""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr
from scipy import special

from study.test_uncertainty import SLIDING, sliding
from tce.study import runner
from tce.study.schema import parse_study


def _lognormal_cdf(x: np.ndarray) -> np.ndarray:
    s2 = math.log(1 + 0.15**2)
    return special.ndtr((np.log(x) - (math.log(0.6) - s2 / 2)) / math.sqrt(s2))


@pytest.fixture(scope="module")
def results(tmp_path_factory) -> xr.Dataset:
    folder = tmp_path_factory.mktemp("sliding")
    text = SLIDING.replace("samples = 20", "samples = 400").replace("chunk = 8", "chunk = 100").replace(
        "threshold = 0.55", "threshold = 0.55\nform = true\nsubset = true\nsubset_samples = 200")
    study = parse_study(text, sliding(folder, text))
    return xr.load_dataset(runner.run_study(study, folder / "out", jobs=1).results)


def test_each_capacity_is_the_drawn_friction(results):
    np.testing.assert_allclose(results["sample_capacity"].values[0], results["sample_input"].values[:, 0], rtol=1e-8)


def test_failure_probability_is_the_lognormal_cdf(results):
    """P(lambda_max < 0.55) and the whole fragility curve have the lognormal CDF inside their
    Clopper-Pearson intervals (95 %)."""
    exact = float(_lognormal_cdf(np.array(0.55)))
    assert float(results["failure_low"][0]) <= exact <= float(results["failure_high"][0])
    assert abs(float(results["failure_probability"][0]) - exact) < 0.02
    assert float(results["reliability_index"][0]) == pytest.approx(-special.ndtri(float(results["failure_probability"][0])))
    x = results["fragility_intensity"].values[0]
    cdf = _lognormal_cdf(x)
    assert np.all(results["fragility_low"].values[0] <= cdf + 1e-12)
    assert np.all(cdf <= results["fragility_high"].values[0] + 1e-12)
    assert results.attrs["uncertainty_interval"] == "clopper-pearson" and results.attrs["uncertainty_samples"] == 400


def test_form_is_exact_and_subset_within_its_accuracy(results):
    exact = float(_lognormal_cdf(np.array(0.55)))
    assert results["form_status"].values[0] == "converged"
    assert float(results["form_pf"][0]) == pytest.approx(exact, abs=1e-6)
    assert float(results["form_design_point"][0, 0]) == pytest.approx(0.55, rel=1e-6)
    assert results["subset_status"].values[0] == "converged"
    pf, cov = float(results["subset_pf"][0]), float(results["subset_cov"][0])
    assert abs(pf - exact) <= 3 * cov * exact
