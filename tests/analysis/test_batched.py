"""tce.analysis.batched (optional extra ``batched``): a batch of WarmLimit samples solved together
gives each sample's WarmLimit status and lambda_max. Skipped without Moreau."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("moreau")

from tce.analysis import Analysis  # noqa: E402
from tce.analysis.batched import BatchedLimit  # noqa: E402
from tce.analysis.reliability import WarmLimit  # noqa: E402
from tce.core.material import Material  # noqa: E402
from tce.structures.arch import semicircular_arch  # noqa: E402


@pytest.mark.parametrize("kind", ["planar", "spatial"])
def test_batch_is_each_warm_sample(kind):
    """Frictions across the infeasible range (below about 0.33), the sliding range and the hinge
    mechanism, with load factors; 11 samples in batches of 4 (the last one padded): the statuses
    and lambda_max of WarmLimit sample by sample, to 1e-8."""
    warm = WarmLimit(Analysis(semicircular_arch(), Material(0.6), model=kind),
                     {"mu": "friction", "g": "fixed_factor", "q": "live_factor"}, alpha=0.0)
    samples = [{"mu": mu, "g": g, "q": q} for mu, g, q in
               [(0.2, 1.0, 1.0), (0.3, 1.1, 1.0), (0.4, 1.0, 0.9), (0.45, 0.95, 1.0), (0.5, 1.0, 1.0),
                (0.55, 1.2, 1.3), (0.6, 1.0, 1.0), (0.7, 0.9, 1.1), (0.9, 1.0, 1.0), (1.3, 1.05, 0.8), (2.0, 1.0, 1.0)]]
    batched = BatchedLimit(warm, batch_size=4)
    statuses, values = batched(samples)
    assert batched.resolved == 0  # every answer is the batch's own
    expected = [warm(s) for s in samples]
    assert list(statuses) == [s for s, _ in expected]
    assert "infeasible" in statuses and "optimal" in statuses
    np.testing.assert_allclose(values, [v for _, v in expected], atol=1e-8, equal_nan=True)


def test_batch_refuses_what_warm_refuses():
    warm = WarmLimit(Analysis(semicircular_arch(), Material(0.6)), {"mu": "friction"}, alpha=0.0)
    batched = BatchedLimit(warm, batch_size=2)
    with pytest.raises(KeyError, match="mu"):
        batched([{"friction": 0.5}])
    with pytest.raises(ValueError, match="friction"):
        batched([{"mu": 0.5}, {"mu": -0.1}])
