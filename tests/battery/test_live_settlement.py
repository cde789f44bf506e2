"""The battery's relations for live loads after a finite settlement (a vehicle x a settlement
path x ``live_at``, :mod:`tce.study.settlement`): a mirrored settlement gives the same
adequacy factors at the mirrored critical positions, and two worker processes give the
in-process dataset (each scenario's path and searches start cold).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from .studies import run

BRIDGE = """
[study]
name = "mirror"

[structure]
type = "arch_bridge"
spans = 1
span = 6.0
rise = 1.5
thickness = 0.4
depth = 3.0
voussoirs = 8

[loads]
lateral = false
critical_position = true
lambda_step = 20.0
tolerance = 1e-4
lambda_cap = 2000.0

[loads.fill]
depth = 0.3
unit_weight = 18.0
dispersion = 0.0
k0 = 0.0

[[loads.vehicle]]
name = "axle"
axles = [[0.0, 100.0]]
wheels = [-0.9, 0.9]

[scenarios.left_sinks]
abutment_left = [0.0, 0.0, -1.0, 0.0, 0.0, 0.0]

[scenarios.right_sinks]
abutment_right = [0.0, 0.0, -1.0, 0.0, 0.0, 0.0]

[settlement_path]
increment = 0.01
s_max = 0.03
live_at = [0.0, 0.03]
"""


@pytest.fixture(scope="module")
def mirrored(tmp_path_factory) -> tuple[Path, xr.Dataset]:
    folder = tmp_path_factory.mktemp("live")
    return folder, run(BRIDGE, folder / "in_process")


def test_mirrored_settlement_same_factor(mirrored):
    """The bridge is symmetric about x = 0 and so is the axle: sinking the left abutment is
    the mirror image of sinking the right one."""
    _, ds = mirrored
    status = ds["settlement_live_status"].values
    assert (status == "optimal").all(), status
    lam = ds["settlement_live_lambda"].values
    np.testing.assert_allclose(lam[0], lam[1], rtol=1e-6)
    assert lam[0, 1] != pytest.approx(lam[0, 0], rel=1e-5)  # the settlement changes the answer
    x = ds["settlement_live_x"].values
    # the leftmost of tied positions is reported: compare the set {x, -x} of each scenario
    for j in range(x.shape[1]):
        assert min(abs(x[0, j] + x[1, j]), abs(x[0, j] - x[1, j])) < 2 * float(ds["critical_xtol"].values[0])
    np.testing.assert_allclose(ds["settlement_live_gap"].values[0], ds["settlement_live_gap"].values[1], rtol=1e-6, atol=1e-12)


def test_two_jobs_same_dataset(mirrored):
    folder, reference = mirrored
    xr.testing.assert_identical(run(BRIDGE, folder / "jobs2", jobs=2), reference)
