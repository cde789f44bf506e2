"""Issue 21, problem 2: the load path is anchored on the direct limit.

A 6 m segmental bridge with two 1 kN wheel loads collapses at about 189 kN per wheel (the
issue's bridge collapsed at 168.431; its exact dimensions were not given, this one is
span 6 m, rise 1.5 m, ring 0.44 m x 1.0 m, 16 voussoirs, Heyman material, wheels 1.2 m
apart on the extrados). On the old main, with the default step 0.02 and cap 100, its
outcome was ``no_limit`` after 5,001 solves; a user cap below the collapse load also gave
``no_limit`` ("carried at any lambda"), and ``lambda_step > lambda_cap`` was accepted.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest
import xarray as xr

from tce.analysis.loadpath import load_path
from tce.core.analysis import Analysis
from tce.core.loads import LoadPattern
from tce.core.material import Material
from tce.structures.arch import segmental_arch, semicircular_arch
from tce.study import load_study
from tce.cli import main
from tce.study.runner import run_study

BRIDGE = """
[study]
name = "bridge"

[structure]
type = "segmental_arch"
span = 6.0
rise = 1.5
thickness = 0.44
depth = 1.0
voussoirs = 16
unit_weight = 20.0

[material]

[loads]
lateral = false
{extra}

[[loads.point]]
on_top = [-1.5, 0.0]
force = [0.0, 0.0, {f}]

[[loads.point]]
on_top = [-0.3, 0.0]
force = [0.0, 0.0, {f}]

[scenarios.none]
"""


def _run(tmp_path: Path, name: str, force: float, extra: str = "") -> xr.Dataset:
    path = tmp_path / f"{name}.toml"
    path.write_text(BRIDGE.format(f=-force, extra=extra).replace('name = "bridge"', f'name = "{name}"'))
    report = run_study(load_study(path), out=tmp_path / "out", jobs=1)
    return xr.load_dataset(report.results)


@pytest.fixture(scope="module")
def bridges(tmp_path_factory: pytest.TempPathFactory) -> dict[float, xr.Dataset]:
    d = tmp_path_factory.mktemp("bridge")
    return {f: _run(d, f"bridge_{k}", f) for k, f in enumerate((1.0, 1000.0))}


def test_the_1_kN_bridge_finds_its_limit_with_the_defaults(bridges) -> None:
    ds = bridges[1.0].isel(scenario=0)
    assert str(ds.outcome.values) == "limit"
    lam, direct = float(ds.lambda_max), float(ds.lambda_direct)
    assert 150.0 < direct < 250.0  # beyond the old default cap of 100
    # within the default tolerance, 1e-6 of the limit; the bracket confirms the direct limit
    assert 0.0 <= direct - lam <= 1e-6 * direct
    assert float(ds.lambda_upper) > direct
    assert int(ds.n_solves) <= 25  # 21 admissible increments, one infeasible, the bracket: not 5,001


def test_the_size_of_the_live_load_changes_nothing_but_the_factor(bridges) -> None:
    one, thousand = (bridges[f].isel(scenario=0) for f in (1.0, 1000.0))
    assert int(one.n_solves) == int(thousand.n_solves)
    assert float(one.lambda_max) == pytest.approx(1000.0 * float(thousand.lambda_max), rel=2e-6)
    assert float(one.lambda_direct) == pytest.approx(1000.0 * float(thousand.lambda_direct), rel=1e-8)


def test_1_N_to_1_MN_in_the_same_number_of_solves() -> None:
    an = Analysis(segmental_arch(span=6.0, rise=1.5, thickness=0.44, depth=1.0, voussoirs=16), Material())
    runs = {}
    for f in (1e-3, 1.0, 1e3):
        pattern = LoadPattern(lateral=False, point=[
            {"on_top": [x, 0.0], "force": [0.0, 0.0, -f]} for x in (-1.5, -0.3)])
        runs[f] = load_path(an, loads=pattern, atol=0.0, rtol=1e-6)
    assert {lp.outcome for lp in runs.values()} == {"limit"}
    assert len({lp.n_solves for lp in runs.values()}) == 1
    factors = [lp.lambda_max * f for f, lp in runs.items()]  # the collapse load of one wheel, kN
    assert max(factors) - min(factors) <= 2e-6 * max(factors)


def test_a_cap_below_the_collapse_load_is_named(tmp_path: Path, capsys) -> None:
    ds = _run(tmp_path, "capped", 1.0, "lambda_cap = 100.0").isel(scenario=0)
    assert str(ds.outcome.values) == "capped"
    assert math.isnan(float(ds.lambda_max)) and str(ds.no_limit_reason.values) == ""
    assert main(["show", str(tmp_path / "out" / "capped" / "results.nc")]) == 0
    out = capsys.readouterr().out
    assert "none: capped: at lambda = 100, below the collapse load lambda_direct = 188.9" in out
    assert "carried at any" not in out and "no_limit" not in out


@pytest.mark.parametrize(
    ("extra", "key"),
    [("lambda_step = 2.0\nlambda_cap = 1.0", "lambda_step"), ("lambda_step = inf", "lambda_step"),
     ("lambda_cap = nan", "lambda_cap"), ("tolerance = inf", "tolerance")],
    ids=["step above cap", "infinite step", "NaN cap", "infinite tolerance"],
)
def test_bad_path_settings_are_refused(tmp_path: Path, capsys, extra: str, key: str) -> None:
    path = tmp_path / "bad.toml"
    path.write_text(BRIDGE.format(f=-1.0, extra=extra))
    assert main(["run", str(path), "--out", str(tmp_path / "out"), "--no-plots"]) == 2
    err = capsys.readouterr().err
    assert str(path) in err and key in err
    assert not (tmp_path / "out" / "bridge" / "results.nc").exists()


def test_a_step_beyond_the_limit_finds_it() -> None:
    """lambda_step = 200 (or 1e308) gave no_limit for an arch whose limit is 0.309."""
    an = Analysis(semicircular_arch(thickness=0.3, voussoirs=8), Material())
    direct = an.limit(0.0).lambda_max
    for step in (200.0, 1e308):
        lp = load_path(an, 0.0, step=step, atol=0.0, rtol=1e-6)
        assert lp.outcome == "limit"
        assert 0.0 <= direct - lp.lambda_max <= 1e-6 * direct


def test_unbounded_is_explained_and_never_called_inadmissible(tmp_path: Path, capsys) -> None:
    """Issue 21, problem 5: figures captioned ``unbounded`` as "no admissible state" (that is
    ``infeasible``) and ``tce show`` explained ``no_limit`` but not ``unbounded``."""
    from tce.plot import data

    study = tmp_path / "transversal.toml"
    study.write_text("""
[study]
name = "transversal"
[structure]
type = "semicircular_arch"
voussoirs = 6
[material]
[loads]
lambda_step = 0.05
[scenarios.transversal]
right = [0.0, 0.001, 0.0, 0.0, 0.0, 0.0]
[plots]
steps = [0.0, "max"]
""")
    assert main(["-q", "run", str(study), "--out", str(tmp_path), "--jobs", "1", "--no-plots"]) == 0
    ds = xr.load_dataset(tmp_path / "transversal" / "results.nc")
    assert str(ds.outcome.values[0]) == "unbounded"
    why = str(ds.unbounded_reason.values[0])
    assert why.startswith("the motion of support right (uy = 0.001) cannot be followed")
    assert "Heyman" in why and "cannot slide" in why
    capsys.readouterr()
    assert main(["show", str(tmp_path / "transversal" / "results.nc")]) == 0
    out = capsys.readouterr().out
    assert f"transversal: unbounded: admissible states exist, but the support motion is incompatible" in out
    assert why in out
    for target in (0.0, "max"):
        note = data.find_state(ds, "transversal", target).note
        assert "no admissible state" not in note and note.startswith("unbounded")
