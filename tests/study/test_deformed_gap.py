"""The gap rule of :func:`tce.study.settlement.deformed_assembly` at its edge: a contact point
that opens by exactly ``gap`` is still a contact (the widest opening a user reads as
``settlement_live_gap`` is that point's)."""

from __future__ import annotations

import numpy as np

from tce.analysis.settlement_path import settlement_path
from tce.structures.arch import semicircular_arch
from tce.study.settlement import deformed_assembly


def test_a_point_open_by_the_gap_is_kept_where_block_a_carries_it():
    arch = semicircular_arch(inner_radius=0.9, thickness=0.2, voussoirs=12)
    path = settlement_path(arch, {"right": [0.0, 0, -1.0, 0, 0, 0]}, increment=0.01, s_max=0.03)
    k = len(path.magnitudes) - 1
    _, _, widest = deformed_assembly(arch, path, k, 1.0)  # every point kept: the widest opening
    assert widest > 1e-4
    edge, move, at_edge = deformed_assembly(arch, path, k, widest)
    assert at_edge == widest and len(edge.interfaces) == len(arch.interfaces)
    for ref, itf in zip(arch.interfaces, edge.interfaces, strict=True):
        np.testing.assert_allclose(itf.points, ref.points @ move[ref.a, :3, :3].T + move[ref.a, :3, 3], atol=1e-12)
