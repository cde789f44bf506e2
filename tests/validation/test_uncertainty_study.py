"""An uncertainty study file against a closed form tce did not produce: a flat block on a slab
slides at lambda = mu (it rocks at b / h = 10), so with a lognormal friction, mean 0.6 and
c.o.v. 0.15, P(lambda_max < x) is the lognormal CDF, written out here from the mean and c.o.v.
Through ``tce``'s study path: the section read from TOML, the draw, the jobs of samples, the
merged statistics and fragility curve."""

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
    text = SLIDING.replace("samples = 20", "samples = 400").replace("chunk = 8", "chunk = 100")
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
