"""``[settlement_path]`` in study files: validation (one clear error, exit 2, nothing written),
the dataset's variables, and a sweep against single runs."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from tce.analysis.settlement_path import settlement_path
from tce.structures.arch import semicircular_arch
from tce.study import load_study
from tce.cli import main
from tce.study.runner import run_study

STUDY = """
[study]
name = "spreading"

[structure]
type = "semicircular_arch"
inner_radius = 0.9
thickness = 0.2
voussoirs = 12

[scenarios.spread]
left = [-1.0, 0, 0, 0, 0, 0]
right = [1.0, 0, 0, 0, 0, 0]

[scenarios.sink]
right = [0, 0, -1.0, 0, 0, 0]

[scenarios.none]

[settlement_path]
increment = 0.01
lambda = true
"""

BAD = {
    "friction": ("[settlement_path]", "[material]\nfriction = 0.6\n\n[settlement_path]", "settlement_path"),
    "out of plane": ("right = [1.0, 0", "right = [0.0, 1.0", "settlement_path"),
    "lateral out of plane": ("[settlement_path]", "[loads]\nalpha = 90\n\n[settlement_path]", "settlement_path"),
    "unknown key": ("lambda = true", "lambda = true\nstep = 2", "settlement_path.step"),
    "negative increment": ("increment = 0.01", "increment = -0.01", "settlement_path.increment"),
    "too many increments": ("increment = 0.01", "increment = 1e-7", "settlement_path"),
    "lambda not a boolean": ("lambda = true", 'lambda = "yes"', "settlement_path.lambda"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_section_exit_2_nothing_written(case, tmp_path: Path, capsys):
    old, new, key = BAD[case]
    assert old in STUDY
    study = tmp_path / "study.toml"
    study.write_text(STUDY.replace(old, new, 1), encoding="utf-8")
    out = tmp_path / "results"
    assert main(["run", str(study), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert f"{study}: {key}" in err and "fix:" in err and "Traceback" not in err
    assert not out.exists()


@pytest.fixture(scope="module")
def dataset(tmp_path_factory) -> xr.Dataset:
    tmp = tmp_path_factory.mktemp("settle")
    path = tmp / "study.toml"
    path.write_text(STUDY, encoding="utf-8")
    report = run_study(load_study(path), out=tmp / "results", jobs=1, plots=False)
    return xr.open_dataset(report.results)


def test_dataset_variables(dataset):
    """Per scenario: the capacity and outcome; per magnitude: reactions, lambda_max, hinges;
    the scenario that moves nothing says so; paths of different lengths are padded."""
    ds = dataset
    out = dict(zip(ds.scenario.values.tolist(), ds.settlement_outcome.values.tolist()))
    assert out["spread"] == "collapse" and out["none"] == "no_motion"
    assert out["sink"] in ("collapse", "contact_lost")
    assert np.isnan(ds.settlement_capacity.sel(scenario="none"))
    mags = ds.settlement_magnitude.sel(scenario="spread").values
    mags = mags[np.isfinite(mags)]
    assert mags[0] == 0 and mags[-1] == pytest.approx(float(ds.settlement_capacity.sel(scenario="spread")))
    assert ds.settlement_capacity.attrs["units"] == "1"
    assert ds.settlement_reaction.dims == ("scenario", "settlement_step", "support", "component")
    lam = ds.settlement_lambda_max.sel(scenario="spread").values
    assert np.isfinite(lam[: len(mags)]).all() and lam[0] > lam[len(mags) - 1]
    hinge = ds.settlement_hinge.sel(scenario="spread").values[0]
    assert hinge.sum() == 3  # the three hinges of the spreading arch
    assert "hinge" in str(ds.settlement_hinge_sequence.sel(scenario="spread").values)


def test_study_equals_the_function(dataset):
    """The study's capacity and reactions are those of settlement_path on the same arch."""
    a = semicircular_arch(inner_radius=0.9, thickness=0.2, voussoirs=12)
    r = settlement_path(a, {"left": [-1.0, 0, 0, 0, 0, 0], "right": [1.0, 0, 0, 0, 0, 0]}, increment=0.01, lam=True)
    assert float(dataset.settlement_capacity.sel(scenario="spread")) == r.capacity
    got = dataset.settlement_reaction.sel(scenario="spread").values[: len(r.magnitudes)]
    np.testing.assert_allclose(got[:, :, [0, 2]], r.reactions[:, :, :2], rtol=1e-12)
    np.testing.assert_allclose(got[:, :, 4], -r.reactions[:, :, 2], rtol=1e-12)


@pytest.mark.parametrize("gap", [None, 1e-9])
def test_contact_gap_reaches_the_lateral_capacity(gap, tmp_path: Path):
    """``contact_gap`` (m) is the lateral capacity's gap too: the study's lambda_max along the
    path is settlement_path's with the same ``contact_gap``, and a gap below the closed
    tolerance (the structure as it stands) gives far less than the default once the joints
    have opened."""
    text = STUDY.replace("increment = 0.01", "increment = 0.001\ns_max = 0.002")
    if gap is not None:
        text += f"contact_gap = {gap}\n"
    path = tmp_path / "study.toml"
    path.write_text(text, encoding="utf-8")
    ds = xr.open_dataset(run_study(load_study(path), out=tmp_path / "results", jobs=1, plots=False).results)
    got = ds.settlement_lambda_max.sel(scenario="spread").values[:3]
    a = semicircular_arch(inner_radius=0.9, thickness=0.2, voussoirs=12)
    spread = {"left": [-1.0, 0, 0, 0, 0, 0], "right": [1.0, 0, 0, 0, 0, 0]}
    mine = settlement_path(a, spread, increment=0.001, s_max=0.002, lam=True, contact_gap=gap)
    np.testing.assert_allclose(got, mine.lambda_max, rtol=1e-12)
    closed = settlement_path(a, spread, increment=0.001, s_max=0.002, lam=True, contact_gap=0.0)
    if gap is None:
        assert (got[1:] > 2 * closed.lambda_max[1:]).all()
    else:
        np.testing.assert_allclose(got, closed.lambda_max, rtol=1e-12)


def test_the_figure_marks_a_withheld_lateral_capacity(dataset):
    """A lateral capacity missing between computed ones (withheld as a spurious strength, or
    not solved) is counted below the panel, and a value left alone between missing ones is
    drawn as a dot (a line needs two neighbours)."""
    from tce.plot.settlement import settlement_curves

    name = "spread"
    lam = dataset["settlement_lambda_max"].copy()
    vals = lam.sel(scenario=name).values.copy()
    assert np.isfinite(vals[:5]).all()
    vals[[2, 4]] = np.nan  # the value at step 3 is left alone
    lam.loc[{"scenario": name}] = vals
    fig = settlement_curves(dataset.assign(settlement_lambda_max=lam), [name])
    ax = next(a for a in fig.axes if a.get_title() == "Lateral capacity left")
    dots = [line for line in ax.lines if line.get_gid() == f"lambda_alone:{name}"]
    assert len(dots) == 1 and list(dots[0].get_xdata()) == [dataset["settlement_magnitude"].sel(scenario=name).values[3]]
    notes = [t.get_text() for t in ax.texts]
    assert any(t.startswith(f"{name}: no lateral capacity at 2 magnitude(s)") for t in notes), notes
