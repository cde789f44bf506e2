"""An uncertainty study gives the same arrays, to the last bit, in-process, in two worker
processes and on a Dask cluster of two workers: each job of samples starts cold, with its own
analyses and solvers, and the samples are drawn from (samples, method, seed) alone. The study
mixes a rebuilt geometry (a normal thickness) with friction, two scenarios (one moving a
support) and jobs of unequal length."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from .studies import run

TEXT = """
[study]
name = "sampled_arch"

[structure]
type = "semicircular_arch"
voussoirs = 6

[material]
friction = 0.8

[loads]
lambda_step = 0.2
tolerance = 1e-2

[scenarios.none]

[scenarios.outward]
right = [0.001, 0.0, 0.0, 0.0, 0.0, 0.0]

[uncertainty]
samples = 8
chunk = 3
method = "sobol"
seed = 2
threshold = 0.4

[uncertainty.variables]
"material.friction" = { distribution = "lognormal", mean = 0.8, cov = 0.2 }
"structure.thickness" = { distribution = "normal", mean = 0.2, std = 0.01 }

[uncertainty.correlation]
"material.friction|structure.thickness" = -0.3
"""


@pytest.fixture(scope="module")
def reference(tmp_path_factory) -> xr.Dataset:
    ds = run(TEXT, tmp_path_factory.mktemp("in_process"))
    assert ds.sizes["sample"] == 8 and list(ds["variable"].values) == ["material.friction", "structure.thickness"]
    assert set(np.ravel(ds["sample_status"].values)) == {"optimal"}
    return ds


def test_two_jobs(reference, tmp_path: Path):
    xr.testing.assert_identical(run(TEXT, tmp_path, jobs=2), reference)


def test_dask(reference, tmp_path: Path):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None
    ) as cluster:
        ds = run(TEXT, tmp_path, backend="dask", scheduler=cluster.scheduler_address, jobs=None)
    xr.testing.assert_identical(ds, reference)


def test_a_thicker_arch_is_stronger(reference):
    """The capacity rises with the thickness and the friction (rank correlations > 0), and the
    two scenarios have the same samples (the direct limit does not depend on the settlement)."""
    assert np.all(reference["sensitivity"].sel(variable="structure.thickness").values > 0.5)
    np.testing.assert_array_equal(reference["sample_capacity"].values[0], reference["sample_capacity"].values[1])
