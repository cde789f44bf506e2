"""Loads in study files: [loads] point and distributed tables, [sweep] load_x, datasets,
`tce show` and the figures; bad declarations exit 2 naming their key, nothing written."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from tce.cli import main
from tce.study.schema import parse_study

STUDY = """
[study]
name = "moving"

[structure]
type = "semicircular_arch"

[loads]
lateral = false
lambda_step = 0.25
tolerance = 1e-6
lambda_cap = 5.0

[[loads.point]]
on_top = [0.0, 0.0]
force = [0.0, 0.0, -1.0]

[[loads.distributed]]
x = [-1.2, 1.2]
pressure = 0.5
scaled = false

[sweep]
load_x = [-1.1, -0.3, 0.0, 0.35]

[scenarios.none]

[scenarios.outward]
right = [0.001, 0.0, 0.0, 0.0, 0.0, 0.0]
"""


def write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "study.toml"
    path.write_text(text, encoding="utf-8")
    return path


def test_load_x_sweep_expands_and_moves_the_live_load() -> None:
    study = parse_study(STUDY)
    scen = study.scenarios()
    assert [s.name for s in scen][:2] == ["none/load_x=-1.1", "none/load_x=-0.3"] and len(scen) == 8
    for s in scen:
        pattern = s.loads_pattern
        assert pattern.point[0].on_top == (s.params["load_x"], 0.0)
        assert pattern.distributed[0].scaled is False and pattern.lateral is False
    keys = {s.key for s in scen}
    assert len(keys) == 8  # the position is part of what determines the answer


def test_the_loads_are_part_of_the_scenario_key() -> None:
    plain = STUDY.split("[[loads.point]]")[0].replace("lateral = false", "") + "[scenarios.none]\n"
    (default,) = parse_study(plain).scenarios()
    (written,) = parse_study(plain.replace("[loads]", "[loads]\nlateral = true")).scenarios()
    (loaded,) = parse_study(plain + "[[loads.point]]\nblock = 'v06'\nforce = [0.0, 0.0, -1.0]\n").scenarios()
    assert default.key == written.key != loaded.key


@pytest.fixture(scope="module")
def sweep(tmp_path_factory) -> tuple[Path, xr.Dataset]:
    tmp = tmp_path_factory.mktemp("sweep")
    assert main(["run", str(write(tmp, STUDY)), "--out", str(tmp / "out"), "--jobs", "1", "--no-plots"]) == 0
    path = tmp / "out" / "moving" / "results.nc"
    return path, xr.load_dataset(path)


def test_sweep_dataset(sweep) -> None:
    _, ds = sweep
    x = ds["load_x"].values
    assert sorted(set(x.tolist())) == [-1.1, -0.3, 0.0, 0.35]
    # the moving load sits on the extrados above its position; the fixed pressure's parts follow
    p = ds["load_point"].transpose("scenario", "load", "xyz").values
    f = ds["load_force"].transpose("scenario", "load", "xyz").values
    live = ds["load_scaled"].values
    np.testing.assert_allclose(p[:, 0, 0], x)
    np.testing.assert_allclose(f[:, 0], [[0.0, 0.0, -1.0]] * 8)
    assert np.all(live[:, 0] == 1) and np.all(live[:, 1:] == 0)
    np.testing.assert_allclose(-f[:, 1:, 2].sum(axis=1), 0.5 * 2.4 * 0.25, rtol=1e-12)
    # over the springing the load goes straight into the support: no limit, no number
    over = ds.sel(scenario="none/load_x=-1.1")
    assert str(over["outcome"].values) == "no_limit" and math.isnan(float(over["lambda_max"].values))
    why = str(over["no_limit_reason"].values)
    assert why.startswith("no finite collapse load for the live loads") and "v01|v02 and left|v01" in why
    at = ds.sel(scenario="none/load_x=-0.3")
    assert str(at["outcome"].values) == "limit" and str(at["model"].values) == "planar"
    # the settlement does not change the capacity of a rigid Heyman arch
    np.testing.assert_allclose(ds["lambda_max"].values[4:], ds["lambda_max"].values[:4], rtol=1e-5)
    declared = json.loads(ds.attrs["loads"])
    assert declared["point"][0]["force"] == [0.0, 0.0, -1.0] and declared["lateral"] is False


def test_show_names_the_critical_position(sweep, capsys) -> None:
    path, ds = sweep
    assert main(["show", str(path)]) == 0
    out = capsys.readouterr().out
    lam = {float(x): float(v) for x, v in zip(ds["load_x"].values[:4], ds["lambda_max"].values[:4])}
    best = min((v, x) for x, v in lam.items() if math.isfinite(v))[1]
    assert "critical load position" in out
    assert f"settlement=none: load_x = {best:.6g} m" in out and f"settlement=outward: load_x = {best:.6g} m" in out


def test_influence_line_figure(sweep) -> None:
    from tce.plot.capacity import influence_line
    from tce.plot.figures import states_figure

    _, ds = sweep
    fig = influence_line(ds)
    ax = fig.axes[0]
    lines = {ln.get_gid(): ln for ln in ax.get_lines()}
    crit = lines["critical:settlement=none"]
    finite = ds["lambda_max"].values[:4]
    assert crit.get_ydata()[0] == pytest.approx(np.nanmin(finite))
    assert lines["no_limit:settlement=none"].get_xdata().tolist() == [-1.1]
    # the states figure draws the applied loads: one arrow per load, ending where it acts; at
    # lambda = 0 the live (moving) load is zero and not drawn, at lambda_max all are
    view = states_figure(ds, [("none/load_x=-0.3", 0.0), ("none/load_x=-0.3", "max")])
    at_zero, at_max = [c for c in view.axes[0].collections if c.get_gid() == "loads"]
    live = int(ds["load_scaled"].sel(scenario="none/load_x=-0.3").sum())
    assert len(at_max.get_segments()) == ds.sizes["load"] == len(at_zero.get_segments()) + live


FIXED = STUDY.split("[sweep]")[0] + "[scenarios.none]\n"  # no moving load

def test_write_figures_of_a_sweep(sweep, tmp_path) -> None:
    from tce.plot.data import plot_spec
    from tce.plot.output import write_figures

    _, ds = sweep
    names = [p.name for p in write_figures(ds, tmp_path)]
    assert names[0] == "capacity.png"
    # the per-scenario figures show the critical position of each settlement case only
    lam = ds["lambda_max"].values
    assert lam[1] == np.nanmin(lam[:4])  # -0.3 is the critical position of this sweep
    assert set(plot_spec(ds).scenarios) == {"none/load_x=-0.3", "outward/load_x=-0.3"}
    assert "states.png" in names


BAD = {
    "unknown block": ('on_top = [0.0, 0.0]', 'block = "v99"', "loads.point[0].block"),
    "support block": ('on_top = [0.0, 0.0]', 'block = "left"', "loads.point[0].block"),
    "at far from its block": ('on_top = [0.0, 0.0]', 'block = "v06"\nat = [3.0, 0.0, 1.0]', "loads.point[0].at"),
    "on_top outside the plan": ('on_top = [0.0, 0.0]', 'on_top = [0.0, 0.9]', "loads.point[0].on_top"),
    "load_x outside the plan": ("load_x = [-1.1,", "load_x = [-1.5,", "loads.point[0].on_top"),
    "zero force": ("force = [0.0, 0.0, -1.0]", "force = [0.0, 0.0, 0.0]", "loads.point[0].force"),
    "non-finite force": ("force = [0.0, 0.0, -1.0]", "force = [0.0, 0.0, nan]", "loads.point[0].force"),
    "short force": ("force = [0.0, 0.0, -1.0]", "force = [0.0, -1.0]", "loads.point[0].force"),
    "misspelt key": ("force = [0.0, 0.0, -1.0]", "force = [0.0, 0.0, -1.0]\nscaeld = true", "loads.point[0].scaeld"),
    "block and on_top": ("on_top = [0.0, 0.0]", 'on_top = [0.0, 0.0]\nblock = "v06"', "loads.point[0]"),
    "rectangle on no block": ("x = [-1.2, 1.2]", "x = [2.0, 3.0]", "loads.distributed[0].x"),
    "empty rectangle": ("x = [-1.2, 1.2]", "x = [1.0, -1.0]", "loads.distributed[0].x"),
    "nothing scaled": ("force = [0.0, 0.0, -1.0]", "force = [0.0, 0.0, -1.0]\nscaled = false", "loads.lateral"),
    "load_x with nothing to move": ("on_top = [0.0, 0.0]", 'block = "v06"', "sweep.load_x"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_loads_exit_2_naming_the_key(case: str, tmp_path: Path, capsys) -> None:
    old, new, key = BAD[case]
    text = FIXED if new.startswith("block") and key != "sweep.load_x" else STUDY
    assert old in text
    path = write(tmp_path, text.replace(old, new, 1))
    assert main(["run", str(path), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("tce: error: ")
    assert re.search(rf": {re.escape(key)}(\[\d\])?: ", err[0]) and "fix: " in err[0], err[0]
    assert not (tmp_path / "out").exists()
