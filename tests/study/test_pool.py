"""Worker processes keep the analyses of the structures they met (issue 24). A geometry sweep
of three scenarios per structure on two workers (so some worker gets two scenarios of one
structure in a row, and every worker meets several structures) must give the in-process
dataset: a worker that reused a stale analysis would solve a scenario on another geometry."""

from __future__ import annotations

from pathlib import Path

import xarray as xr

from battery.studies import run

STUDY = """
[study]
name = "thick"
[structure]
type = "semicircular_arch"
voussoirs = 6
[material]
friction = 0.8
[loads]
lambda_step = 0.05
tolerance = 1e-6
[sweep]
thickness = [0.15, 0.2, 0.25, 0.3]
[scenarios.none]
[scenarios.outward]
right = [0.001, 0, 0, 0, 0, 0]
[scenarios.inward]
right = [-0.001, 0, 0, 0, 0, 0]
"""


def test_geometry_sweep_on_two_workers_equals_in_process(tmp_path: Path):
    here = run(STUDY, tmp_path / "one")
    pooled = run(STUDY, tmp_path / "two", jobs=2)
    assert sorted(here["geometry"].values.tolist()) == [0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3]  # dispatched in this order
    xr.testing.assert_identical(pooled, here)
