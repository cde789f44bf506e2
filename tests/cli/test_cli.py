"""The tce command line: exit codes, messages, run/show/plot end to end."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
import xarray as xr

import tce
from tce.cli import main
from study.test_settlement_path import STUDY as SETTLEMENT_STUDY

STUDY = """
[study]
name = "cli"

[structure]
type = "semicircular_arch"
inner_radius = 1.0
thickness = 0.2
depth = 0.25
voussoirs = 6

[loads]
alpha = 0.0
lambda_step = 0.05
tolerance = 1e-4

[scenarios.outward]
right = [0.001, 0.0, 0.0, 0.0, 0.0, 0.0]
"""

BAD = {
    "unknown key": ("voussoirs = 6", "voussoirs = 6\nvousoirs = 7", "structure.vousoirs"),
    "wrong type": ("depth = 0.25", "depth = [0.25]", "structure.depth"),
    "negative thickness": ("thickness = 0.2", "thickness = -0.2", "structure.thickness"),
    "friction below 0": ("[loads]", "[material]\nfriction = -0.5\n\n[loads]", "material.friction"),
    "NaN": ("tolerance = 1e-4", "tolerance = nan", "loads.tolerance"),
    "displacement of wrong length": ("0.0, 0.0, 0.0, 0.0, 0.0]", "0.0]", "scenarios.outward.right"),
    "unknown support": ("right = [", "centre = [", "scenarios.outward.centre"),
}


def write(tmp_path: Path, text: str, name: str = "study.toml") -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def test_version(capsys) -> None:
    with pytest.raises(SystemExit) as info:
        main(["--version"])
    assert info.value.code == 0 and tce.__version__ in capsys.readouterr().out


@pytest.mark.parametrize("argv", [["--help"], ["run", "--help"], ["show", "--help"], ["plot", "--help"]])
def test_help(argv: list[str], capsys) -> None:
    with pytest.raises(SystemExit) as info:
        main(argv)
    assert info.value.code == 0 and "usage: tce" in capsys.readouterr().out


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_study_exit_2_no_traceback_no_file(case: str, tmp_path: Path, capsys) -> None:
    old, new, key = BAD[case]
    assert old in STUDY
    study = write(tmp_path, STUDY.replace(old, new, 1))
    out = tmp_path / "results"
    assert main(["run", str(study), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert f"{study}: {key}" in err and "fix:" in err and "Traceback" not in err
    assert not out.exists()


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["run", "missing.toml"], "cannot read"),
        (["run", "{study}", "--scheduler", "tcp://127.0.0.1:1"], "--backend dask"),
        (["show", "missing.nc"], "no such results file"),
        (["plot", "{study}"], "not a readable results file"),
    ],
)
def test_bad_arguments_exit_2(argv: list[str], message: str, tmp_path: Path, capsys) -> None:
    study = write(tmp_path, STUDY)
    assert main([a.format(study=study) for a in argv]) == 2
    err = capsys.readouterr().err
    assert message in err and "Traceback" not in err


def test_bad_jobs_is_a_usage_error(tmp_path: Path, capsys) -> None:
    with pytest.raises(SystemExit) as info:
        main(["run", str(write(tmp_path, STUDY)), "--jobs", "0"])
    assert info.value.code == 2 and "--jobs" in capsys.readouterr().err


def test_run_show_plot(tmp_path: Path, capsys, monkeypatch) -> None:
    import tce.plot

    study = write(tmp_path, STUDY)
    out = tmp_path / "results"
    drawn: list[Path] = []
    monkeypatch.setattr(tce.plot, "write_figures", lambda ds, outdir, **kw: drawn.append(outdir) or [outdir / "a.png"])
    assert main(["run", str(study), "--out", str(out), "--jobs", "1"]) == 0
    results = out / "cli" / "results.nc"
    stdout = capsys.readouterr().out
    assert str(results) in stdout and "1 solved" in stdout and "1 figures" in stdout
    assert drawn == [out / "cli"]  # tce run plots beside the results
    monkeypatch.undo()
    ds = xr.open_dataset(results)
    assert list(ds["scenario"].values) == ["outward"] and ds.attrs["study"] == STUDY
    ds.close()

    assert main(["-q", "run", str(study), "--out", str(out), "--no-plots"]) == 0
    assert "0 solved, 1 reused" in capsys.readouterr().out

    assert main(["show", str(results)]) == 0
    table = capsys.readouterr().out
    for column in ("lambda_max", "direct", "gap", "outcome", "model", "n_solves", "outward", "limit", "planar"):
        assert column in table

    figures = tmp_path / "figures"
    assert main(["plot", str(results), "--out", str(figures)]) == 0
    assert "figures in" in capsys.readouterr().out
    assert list(figures.glob("*.png"))


def test_main_gives_the_callers_signal_handlers_back(tmp_path) -> None:
    """A script or a test calling main() keeps its own Ctrl-C: handlers replaced for the command
    are put back, whether the command succeeds, fails or is refused."""
    import signal

    before = signal.getsignal(signal.SIGINT)
    assert main(["show", str(tmp_path / "missing.nc")]) == 2
    assert signal.getsignal(signal.SIGINT) is before


def test_show_prints_the_settlement_path(tmp_path: Path, capsys) -> None:
    """``tce run`` counts the settlement paths' outcomes and ``tce show`` prints, per scenario, the
    settlement outcome, the capacity (equal to the dataset's at its printed digits), the snaps,
    the hinge sequence in order and the lateral lambda_max at the capacity (fails on main:
    neither said anything about the settlement path)."""
    import re

    import numpy as np

    study = tmp_path / "spreading.toml"
    study.write_text(SETTLEMENT_STUDY, encoding="utf-8")
    assert main(["-q", "run", str(study), "--out", str(tmp_path), "--no-plots", "--jobs", "1"]) == 0
    results = tmp_path / "spreading" / "results.nc"
    ds = xr.load_dataset(results)
    outcomes = list(map(str, ds["settlement_outcome"].values))
    summary = capsys.readouterr().out
    tally = ", ".join(f"{outcomes.count(o)} {o}" for o in dict.fromkeys(outcomes))
    assert f"; settlement path: {tally};" in summary and "no_motion" in tally
    assert main(["show", str(results)]) == 0
    show = capsys.readouterr().out
    assert "settlement path (capacity: largest magnitude found standing, × the scenario's settlement vectors" in show
    line = re.compile(r"^  (\w+): (\w+): capacity (\S+) \(first not standing (\S+)\), (\d+) snap\(s\), "
                      r"lateral (\S+); hinges (.*)$", re.M)
    rows = {m[1]: m.groups()[1:] for m in line.finditer(show)}
    assert list(rows) == list(map(str, ds["scenario"].values))
    for k, (name, (outcome, capacity, upper, snaps, lateral, hinges)) in enumerate(rows.items()):
        assert outcome == outcomes[k]
        digits = len(capacity.split("e")[0].replace(".", "").lstrip("0"))  # significant digits printed
        expected = float(ds["settlement_capacity"].values[k])
        if math.isnan(expected):
            assert capacity == "NaN" and lateral == "–"
        else:
            assert float(capacity) == float(f"{expected:.{digits}g}")
            step = int(np.flatnonzero(ds["settlement_magnitude"].values[k] == expected)[-1])
            assert float(lateral) == pytest.approx(float(ds["settlement_lambda_max"].values[k][step]), rel=1e-5)
        want = float(ds["settlement_upper"].values[k])
        assert upper == "–" if math.isnan(want) else float(upper) == pytest.approx(want, rel=1e-5)
        stored = [e.split(": ", 1) for e in str(ds["settlement_hinge_sequence"].values[k]).split("; ") if e]
        joints = [what.rsplit(" ", 1)[0] for _, what in stored]
        assert re.findall(r"\w+\|\w+", hinges) == joints  # the joints in the stored order
        assert int(snaps) == len({s for s, what in stored if what.endswith(" snap")})
    assert rows["spread"][0] == "collapse" and rows["none"][0] == "no_motion"
