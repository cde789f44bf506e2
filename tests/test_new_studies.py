"""The shipped dome (Fig. 10) and file-based wall studies run end to end and give their closed forms."""

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from tce.study.runner import run_study
from tce.study.schema import load_study

STUDIES = Path(__file__).resolve().parent.parent / "studies"


def test_wall_from_file_rocks_out_of_plane_at_t_over_h(tmp_path):
    ds = xr.load_dataset(run_study(load_study(STUDIES / "wall_from_file.toml"), out=tmp_path, jobs=1, plots=False).results)
    lam = dict(zip(ds.scenario.values, ds.lambda_max.values))
    # the whole 1.0 m high, 0.2 m thick wall rocks about its base edge: lambda = t / h
    assert lam["none/alpha=90"] == pytest.approx(0.2, rel=1e-5)
    assert 0.2 < lam["none/alpha=0"] < 1.0
    assert np.all(np.abs(ds.lambda_gap.values) <= 1e-5)


def test_fig10_dome_limit_does_not_depend_on_the_settlement(tmp_path):
    ds = xr.load_dataset(run_study(load_study(STUDIES / "fig10_dome.toml"), out=tmp_path, jobs=1, plots=False).results)
    lam = ds.lambda_max.values
    assert np.all(np.isfinite(lam)) and lam[0] == pytest.approx(lam[1], rel=1e-9)
    assert set(ds.outcome.values) == {"limit"}
