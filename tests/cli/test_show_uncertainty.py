"""``tce show`` on an uncertainty study: one line per scenario with the failure probability,
its interval, beta, N and the dominant variable, every sample outcome word said, and nothing
new for a study without ``[uncertainty]`` (results from ``tests/plot/uncertainty_data.py``)."""

from __future__ import annotations

from pathlib import Path

import pytest
import xarray as xr

from plot.uncertainty_data import small_study, with_uncertainty
from tce.cli import main
from tce.plot.data import counts_note

THIN, MID, THICK = "none/thickness=0.2", "none/thickness=0.25", "none/thickness=0.3"


@pytest.fixture(scope="module")
def base(tmp_path_factory: pytest.TempPathFactory) -> xr.Dataset:
    return small_study(tmp_path_factory.mktemp("uq"))


def _show(ds: xr.Dataset, tmp_path: Path, capsys: pytest.CaptureFixture) -> list[str]:
    ds.to_netcdf(tmp_path / "results.nc")
    capsys.readouterr()
    assert main(["show", str(tmp_path / "results.nc")]) == 0
    return capsys.readouterr().out.splitlines()


def test_one_line_per_scenario(base: xr.Dataset, tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    """The header states the method, N, the seed, the threshold and the interval; each
    scenario's line its stored numbers, the dominant variable, FORM and subset."""
    ds = with_uncertainty(base, n=250, seed=3)
    lines = _show(ds, tmp_path, capsys)
    start = next(k for k, line in enumerate(lines) if line.startswith("uncertainty ("))
    threshold = float(ds.attrs["uncertainty_threshold"])
    assert lines[start].startswith(f"uncertainty (Latin hypercube, N = 250, seed 3; failure: the capacity below "
                                   f"{threshold:g}, the capacity being the load multiplier lambda")
    assert "95 % Clopper-Pearson interval" in lines[start]
    for k, s in enumerate(ds["scenario"].values.tolist()):
        line = lines[start + 1 + k]
        pf, lo, hi, beta = (float(ds[v].values[k]) for v in
                            ("failure_probability", "failure_low", "failure_high", "reliability_index"))
        assert line.startswith(f"  {s}: pf {pf:.4g} [{lo:.4g}, {hi:.4g}], beta {beta:.4g}, N 250 "
                               f"({int(ds['n_failed'].values[k])} failed of 250 decided, 0 numerical), "
                               "dominant material.friction (+1.00); FORM beta "), line
        assert f"; subset pf {float(ds['subset_pf'].values[k]):.4g} (c.o.v. 0.2), converged" in line


def test_every_sample_outcome_is_said(base: xr.Dataset, tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    """All unbounded, all infeasible, all or some numerical: the line counts them and says
    what they stand for; without a decided sample the probability is NaN, not 0."""
    modes = {THIN: "infeasible", MID: "unbounded", THICK: "some_numerical"}
    ds = with_uncertainty(base, n=100, modes=modes)
    lines = _show(ds, tmp_path, capsys)
    for s in modes:
        (line,) = [x for x in lines if x.startswith(f"  {s}: pf ")]
        assert line.endswith(f"; {counts_note(ds, s)}"), line
    (thin,) = [x for x in lines if x.startswith(f"  {THIN}: pf ")]
    assert thin.startswith(f"  {THIN}: pf 1 [") and "beta -inf" in thin and "dominant undefined" in thin
    ds = with_uncertainty(base, n=100, modes={THIN: "numerical"})
    (thin,) = [x for x in _show(ds, tmp_path, capsys) if x.startswith(f"  {THIN}: pf ")]
    assert thin.startswith(f"  {THIN}: pf NaN [NaN, NaN], beta NaN, N 100 (0 failed of 0 decided, 100 numerical)")
    assert thin.endswith("; all 100 samples numerical: undecided (NaN: left out of the estimate)")


def test_no_uncertainty_no_line(base: xr.Dataset, tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    lines = _show(base, tmp_path, capsys)
    assert lines and not any("uncertainty" in x or ": pf " in x for x in lines)
