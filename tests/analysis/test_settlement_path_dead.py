"""The lateral capacity along a settlement path that carries fixed loads (``dead``): at the
first magnitude (nothing has moved) it is tce's direct limit of the undeformed structure
under the same fixed loads, an independent solve (Clarabel on the limit problem, not HiGHS on
the path's program)."""

from __future__ import annotations

import pytest

from tce.analysis.settlement_path import settlement_path
from tce.core.analysis import Analysis
from tce.core.loads import LoadPattern, resolve
from tce.structures.arch import semicircular_arch
from tce.study.settlement import fixed_part


def test_the_lateral_capacity_at_rest_is_the_direct_limit_under_the_dead_loads():
    """A heavy crown load on a thick arch (twice its weight, with a horizontal push) carried
    by the path: the shear cap grows with it (else the capacity would be withheld as a
    spurious strength), and the push's side matters (the capacity differs from the mirrored
    push's)."""
    arch = semicircular_arch(inner_radius=0.7, thickness=0.6, voussoirs=12)
    crown = arch.names.index("v07")
    c = arch.centroids[crown]
    W = float(arch.weights.sum())
    motion = {"left": [-1.0, 0, 0, 0, 0, 0], "right": [1.0, 0, 0, 0, 0, 0]}
    lams = []
    for push in (0.05, -0.05):
        pattern = LoadPattern(lateral=True, point=[dict(force=(push * W, 0.0, -2.0 * W), block=arch.names[crown],
                                                        at=tuple(map(float, c)), scaled=False)])
        path = settlement_path(arch, motion, increment=0.001, s_max=0.001, lam=True,
                               dead=resolve(fixed_part(pattern), arch))
        ref = Analysis(arch).limit(loads=pattern)
        assert ref.status == "optimal"
        assert path.lambda_max[0] == pytest.approx(ref.lambda_max, rel=1e-6), path.message
        lams.append(path.lambda_max[0])
    assert abs(lams[0] - lams[1]) > 1e-3 * abs(lams[0])
