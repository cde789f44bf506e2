"""Runner: parallel sweeps that do not depend on the backend, and resume. The shipped studies'
figures: tests/validation/test_studies.py."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from tce.study import runner
from tce.study.results import TIMING
from tce.study.schema import parse_study


SWEEP = """
[study]
name = "sweep"

[structure]
type = "semicircular_arch"
inner_radius = 1.0
thickness = 0.2
depth = 0.25
voussoirs = 8

[loads]
alpha = [0.0, 90.0]
lambda_step = 0.05
tolerance = 1e-4

[sweep]
friction = [0.8, 2.0]

[scenarios.none]

[scenarios.outward]
right = [0.001, 0.0, 0.0, 0.0, 0.0, 0.0]
"""


def answer(path: Path) -> xr.Dataset:
    """A results file without what differs from run to run (timings, creation date)."""
    ds = xr.load_dataset(path).drop_vars(list(TIMING))
    ds.attrs.pop("created")
    return ds


@pytest.fixture(scope="module")
def study():
    return parse_study(SWEEP, "sweep.toml")


@pytest.fixture(scope="module")
def reference(study, tmp_path_factory) -> xr.Dataset:
    out = tmp_path_factory.mktemp("jobs1")
    report = runner.run_study(study, out, jobs=1)
    assert len(report.solved) == 8 and not report.reused
    return answer(report.results)


def test_dataset_contract(study, reference: xr.Dataset) -> None:
    ds = reference
    assert list(ds["scenario"].values[:2]) == ["none/alpha=0/friction=0.8", "none/alpha=0/friction=2"]
    assert list(ds["component"].values) == ["Fx", "Fy", "Fz", "Mx", "My", "Mz"]
    assert list(ds["support"].values) == ["left", "right"]
    assert ds["reaction"].dims == ("scenario", "step", "support", "component")
    assert ds["lam"].dims == ds["status"].dims == ("scenario", "step")
    for name in ("alpha", "friction", "settlement"):
        assert ds[name].dims == ("scenario",)
    assert set(ds["model"].values) == {"planar", "spatial"}
    for name in ds.variables:
        assert ds[name].attrs.get("units") and ds[name].attrs.get("long_name"), name
    for key in ("study", "study_name", "tce_version", "solver", "model", "assembly", "material"):
        assert ds.attrs[key]
    assert ds.attrs["study"] == SWEEP
    assert set(ds["status"].values.ravel()) <= {"optimal", "infeasible", "unbounded", "numerical", ""}
    # a reaction is the wrench on the structure: the supports carry the weight upwards
    first = ds["reaction"].isel(step=0).sel(component="Fz").sum("support")
    assert np.all(first.values > 0)


def test_same_numbers_with_two_jobs(study, reference, tmp_path) -> None:
    report = runner.run_study(study, tmp_path, jobs=2)
    xr.testing.assert_identical(answer(report.results), reference)


def test_same_numbers_on_dask(study, reference, tmp_path) -> None:
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None
    ) as cluster:
        report = runner.run_study(study, tmp_path, backend="dask", scheduler=cluster.scheduler_address)
    xr.testing.assert_identical(answer(report.results), reference)


class Stop(Exception):
    """Stands for a crash or a Ctrl-C in the middle of a sweep."""


def test_interrupted_sweep_resumes(study, reference, tmp_path, monkeypatch) -> None:
    def crash_after_three(done: int, total: int, steps: int) -> None:
        if done == 3:
            raise Stop

    with pytest.raises(Stop):
        runner.run_study(study, tmp_path, jobs=1, progress=crash_after_three)
    kept = sorted((tmp_path / "sweep" / "scenarios").glob("*.nc"))
    assert len(kept) == 3 and not (tmp_path / "sweep" / "results.nc").exists()
    assert not list((tmp_path / "sweep" / "scenarios").glob(".*"))  # no temporary left

    solved: list[str] = []
    solve = runner.solve_scenario
    monkeypatch.setattr(runner, "solve_scenario", lambda sc, asm: solved.append(sc.name) or solve(sc, asm))
    report = runner.run_study(study, tmp_path, jobs=1)
    assert len(report.reused) == 3 and len(report.solved) == 5 and sorted(solved) == sorted(report.solved)
    xr.testing.assert_identical(answer(report.results), reference)

    # a scenario whose definition changed is solved again, the others are reused
    changed = parse_study(SWEEP.replace("right = [0.001,", "right = [0.002,"), "sweep.toml")
    solved.clear()
    report = runner.run_study(changed, tmp_path, jobs=1)
    assert len(solved) == 4 and all(name.startswith("outward") for name in solved)
