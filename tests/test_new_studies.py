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


def test_groin_vault_study_limit_is_the_same_along_x_and_y(tmp_path):
    """The square groin vault maps onto itself by a quarter turn: the load paths along x and y
    meet the same lambda_max, and (rigid blocks) the piers' spreading does not change it."""
    ds = xr.load_dataset(run_study(load_study(STUDIES / "groin_vault.toml"), out=tmp_path, jobs=1, plots=False).results)
    assert set(ds.outcome.values) == {"limit"}
    lam = ds.lambda_max.values
    assert np.ptp(lam) <= 1e-9 * lam.max()
    assert np.all(np.abs(ds.lambda_gap.values) <= 1e-4)  # the study's bisection tolerance


def test_barrel_vault_study_structure_has_finite_limits_both_ways():
    from tce.analysis import Analysis
    from tce.study.schema import build_material, build_structure

    (sc, *_) = load_study(STUDIES / "barrel_vault.toml").scenarios()
    an = Analysis(build_structure(sc.structure), build_material(sc.material))
    # an odd number of courses: the running bond is symmetric about x = 0 and about y = 0
    assert load_study(STUDIES / "barrel_vault.toml").spec.structure.courses % 2 == 1
    for alpha in (0.0, 90.0):
        lim, back = an.limit(alpha), an.limit(alpha + 180.0)
        assert lim.status == "optimal" and lim.certificate_gap < 1e-6
        assert back.lambda_max == pytest.approx(lim.lambda_max, rel=1e-6)
