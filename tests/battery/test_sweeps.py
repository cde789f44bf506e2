"""A sweep against the same scenarios run one by one, and every runner against in-process.

Each sweep kind of ``[sweep]`` (a material parameter, the settlement magnitude, the
direction, a moving load, the geometry) runs as one study of two values and as two
studies of one value each: every scenario's numbers must be the same (each scenario starts
from cold solvers: equal to the last bit is what tce promises, 1e-10 is asked). The runners
(two worker processes, a Dask cluster, a resumed run) must give the in-process dataset of a
study that combines the features: a structure spanning y from a block file, a
non-associative material, a live point load, a fixed pressure, a settlement, a sweep.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from tce.core.loads import DistributedLoad, LoadPattern, PointLoad
from tce.core.material import Material
from tce.structures.arch import semicircular_arch

from .studies import file_section, run, study_text
from .transform import Similarity

ARCH = {"type": "semicircular_arch", "voussoirs": 8}
MATERIAL = Material(friction=0.7, cohesion=1.0, compressive_strength=4000.0, flow="non-associative")
PATTERN = LoadPattern(
    alpha=0.0,
    lateral=True,
    point=[PointLoad(force=(0.0, 0.0, -1.0), on_top=(-0.4, 0.0))],
    distributed=[DistributedLoad(x=(0.2, 0.6), y=(-0.125, 0.125), pressure=2.0, scaled=False)],
)
OUTWARD = {"right": [1e-3, 0.0, 0.0, 0.0, 0.0, 0.0]}
LOADS = {"lambda_step": 0.05, "tolerance": 1e-6}

#: sweep key -> (two values, how one value is written without the sweep)
SWEEPS = {
    "friction": ([0.7, 1.0], "material"),
    "cohesion": ([0.5, 2.0], "material"),
    "compressive_strength": ([800.0, 4000.0], "material"),
    "magnitude": ([0.5, 2.0], "settlement"),
    "load_x": ([-0.5, 0.3], "load"),
    "thickness": ([0.2, 0.3], "structure"),
}
#: per-scenario variables that must be equal (those with a step dimension: on the steps solved)
SCENARIO_VARS = ("outcome", "lambda_max", "lambda_upper", "lambda_direct", "n_solves", "model", "lambda_nonassoc",
                 "nonassoc_status")
STEP_VARS = ("lam", "status", "reaction", "resultant", "pressure_point", "vertex_force", "load_point", "load_force")


def _single(key: str, value: float) -> str:
    """The study of one value of ``key``, written without a sweep."""
    structure, material, pattern, motions = dict(ARCH), MATERIAL, PATTERN, OUTWARD
    where = SWEEPS[key][1]
    if where == "material":
        material = Material(**{**MATERIAL.__dict__, key: value})
    elif where == "settlement":
        motions = {k: [value * u for u in v] for k, v in OUTWARD.items()}
    elif where == "load":
        pattern = PATTERN.moved(value)
    else:
        structure[key] = value
    return study_text("one", structure, material, pattern, {"outward": motions}, loads=LOADS)


def _same_scenario(a: xr.Dataset, b: xr.Dataset) -> None:
    for name in SCENARIO_VARS:
        assert a[name].values.tolist() == b[name].values.tolist() or np.allclose(
            a[name].values, b[name].values, rtol=1e-10, atol=0.0, equal_nan=True), name
    n = int(np.count_nonzero(~np.isnan(a["lam"].values)))
    assert n == int(np.count_nonzero(~np.isnan(b["lam"].values)))
    for name in STEP_VARS:
        if "step" not in a[name].dims:  # load points: one set per scenario
            np.testing.assert_allclose(a[name].values, b[name].values, rtol=1e-10, atol=0.0, err_msg=name)
            continue
        va, vb = a[name].isel(step=slice(0, n)).values, b[name].isel(step=slice(0, n)).values
        if va.dtype.kind in "OUS":
            assert va.tolist() == vb.tolist(), name
        else:
            np.testing.assert_allclose(va, vb, rtol=1e-10, atol=1e-12 * float(np.nanmax(np.abs(va)) or 1.0), err_msg=name)


def _sweep_and_singles(key: str, folder: Path) -> tuple[xr.Dataset, list[xr.Dataset]]:
    values, _ = SWEEPS[key]
    sweep = run(study_text("swept", ARCH, MATERIAL, PATTERN, {"outward": OUTWARD}, loads=LOADS, sweep={key: values}),
                folder / "sweep")
    return sweep, [run(_single(key, v), folder / f"one{k}") for k, v in enumerate(values)]


@pytest.mark.parametrize("key", list(SWEEPS))
def test_sweep_against_scenarios_one_by_one(key, tmp_path):
    sweep, singles = _sweep_and_singles(key, tmp_path)
    assert sweep.sizes["scenario"] == len(singles) == 2
    for k, one in enumerate(singles):
        _same_scenario(sweep.isel(scenario=k), one.isel(scenario=0))


def test_alpha_list_against_one_direction_each(tmp_path):
    """``alpha = [0, 90, 30]``: the in-plane direction on the planar model, the others spatial."""
    alphas = [0.0, 90.0, 30.0]
    sweep = run(study_text("swept", ARCH, MATERIAL, PATTERN, {"outward": OUTWARD}, loads=LOADS, alphas=alphas),
                tmp_path / "sweep")
    assert sweep["model"].values.tolist() == ["planar", "spatial", "spatial"]
    for k, alpha in enumerate(alphas):
        one = run(study_text("one", ARCH, MATERIAL, PATTERN, {"outward": OUTWARD}, loads=LOADS, alphas=[alpha]),
                  tmp_path / f"one{k}")
        _same_scenario(sweep.isel(scenario=k), one.isel(scenario=0))


@pytest.mark.xfail(strict=True, reason="issue 21 item 1: a geometry sweep stores the first scenario's geometry, "
                   "fixed on branch i21fix")
def test_geometry_sweep_stores_each_scenarios_geometry(tmp_path):
    """Issue 21, problem 1: with ``[sweep] thickness`` every scenario's stored vertices and
    centroids are those of a fresh build of its own structure (those of its single run)."""
    sweep, singles = _sweep_and_singles("thickness", tmp_path)
    for k, one in enumerate(singles):
        mine = sweep.isel(scenario=k)
        for name in ("vertex_point", "block_centroid"):
            np.testing.assert_allclose(mine[name].values, one[name].values, rtol=0, atol=1e-12, err_msg=name)


# ---------------------------------------------------------------------- runners
def _combined(folder: Path) -> str:
    """A study that combines the features: the arch turned to span y (a block file), a
    non-associative material with cohesion and a compressive strength, the lateral pattern
    along the span, a live point load and a fixed pressure, a settlement along the span,
    a friction sweep."""
    t = Similarity.rotation(90.0)
    asm = t.assembly(semicircular_arch(voussoirs=6))
    cases = {"none": {}, "moved": t.settlements(OUTWARD)}
    return study_text("combined", file_section(asm, folder, "turned"), MATERIAL, t.pattern(PATTERN), cases,
                      loads=LOADS, sweep={"friction": [0.7, 1.0]})


@pytest.fixture(scope="module")
def combined(tmp_path_factory) -> tuple[Path, xr.Dataset]:
    folder = tmp_path_factory.mktemp("combined")
    ds = run(_combined(folder), folder / "in_process")
    assert set(ds["model"].values) == {"planar"} and list(ds["outcome"].values) == ["limit"] * 4
    return folder, ds


def test_two_jobs(combined):
    folder, reference = combined
    xr.testing.assert_identical(run(_combined(folder), folder / "jobs2", jobs=2), reference)


def test_dask(combined):
    distributed = pytest.importorskip("distributed")
    folder, reference = combined
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None
    ) as cluster:
        ds = run(_combined(folder), folder / "dask", backend="dask", scheduler=cluster.scheduler_address, jobs=None)
    xr.testing.assert_identical(ds, reference)


def test_resumed(combined):
    folder, reference = combined
    out = folder / "resumed"
    run(_combined(folder), out)
    scenarios = sorted((out / "results" / "combined" / "scenarios").glob("*.nc"))
    assert len(scenarios) == 4
    for f in scenarios[::2]:
        f.unlink()
    xr.testing.assert_identical(run(_combined(folder), out), reference)
