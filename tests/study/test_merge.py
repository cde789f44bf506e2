"""Merging scenario datasets without xarray's alignment (issue 24): the numpy stacking gives the
file xarray's concatenation gave, whether the parts were read back from their files or kept
in memory, and steps of unequal length are padded alike. tce against itself (the former
merge, ``xr.concat`` of padded parts, is the reference)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from faults.common import TINY
from tce.study import results as R
from tce.study.runner import run_study, solve_scenario
from tce.study.schema import parse_study

#: the fault suite's tiny study, with a friction low enough that its paths differ in length
STUDY = TINY.replace("friction = [0.8, 2.0]", "friction = [0.3, 2.0]")


@pytest.fixture(scope="module")
def study():
    return parse_study(STUDY, "study.toml")


@pytest.fixture(scope="module")
def parts(study, tmp_path_factory):
    """``(from disk, in memory)`` datasets of every scenario."""
    out = tmp_path_factory.mktemp("out")
    run_study(study, out, jobs=1)
    disk = R.load_finished(out / "tiny" / "scenarios", study.scenarios())
    memory = {sc.name: solve_scenario(sc, study.assembly(sc.structure)) for sc in study.scenarios()}
    return disk, memory


def _former(study, parts: dict[str, xr.Dataset]) -> xr.Dataset:
    order = [sc.name for sc in study.scenarios()]
    n = max(parts[k].sizes["step"] for k in order)
    ds = xr.concat([R._pad(parts[k], n) for k in order], dim="scenario", data_vars="minimal", coords="minimal",
                   compat="override", join="outer", combine_attrs="drop")
    ds["geometry"] = (("scenario",), np.asarray(R.geometries(study)[1], dtype=np.int64))  # each scenario's structure
    return R._label(ds)


def _written(ds: xr.Dataset, path: Path) -> xr.Dataset:
    """``ds`` as its file reads back, without timings and the study's attributes."""
    ds.to_netcdf(path)
    back = xr.load_dataset(path).drop_vars(list(R.TIMING))
    back.attrs = {}
    return back


@pytest.mark.parametrize("source", ["disk", "memory", "mixed"])
def test_stacking_writes_the_file_concatenation_wrote(study, parts, tmp_path, source):
    disk, memory = parts
    names = [sc.name for sc in study.scenarios()]
    use = {"disk": disk, "memory": memory,
           "mixed": {n: (disk if k % 2 else memory)[n] for k, n in enumerate(names)}}[source]
    assert len({use[n].sizes["step"] for n in names}) > 1  # steps of unequal length get padded
    new = R.merge_scenarios(study, use)
    old = _former(study, disk)
    a, b = _written(old, tmp_path / "old.nc"), _written(new, tmp_path / "new.nc")
    xr.testing.assert_identical(a, b)
    for k in a.variables:  # integers are int64 whatever the parts' width (int32 in scenario files)
        assert a[k].dtype == b[k].dtype or a[k].dtype.kind == b[k].dtype.kind == "i", k
    assert b["n_solves"].dtype == np.int64
    # padding: NaN for numbers, "" for text, past each scenario's own steps
    short = min(names, key=lambda n: use[n].sizes["step"])
    k = use[short].sizes["step"]
    assert np.isnan(b["lam"].sel(scenario=short).values[k:]).all()
    assert (b["status"].sel(scenario=short).values[k:] == "").all()


def test_parts_of_other_geometries_are_left_to_xarray(study, parts):
    disk, _ = parts
    names = [sc.name for sc in study.scenarios()]
    other = dict(disk)
    other[names[1]] = disk[names[1]].assign_coords(interface=[f"x{i}" for i in range(disk[names[1]].sizes["interface"])])
    assert R._stacked([other[n] for n in names], 20) is None
