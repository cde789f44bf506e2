"""The shipped studies, run end to end by the study runner, give the paper's figures and their
closed forms."""

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from reference import geometry as rg
from tce.study.runner import run_study
from tce.study.schema import load_study

STUDIES = Path(__file__).resolve().parents[2] / "studies"
PAPER_LAMBDA_0 = 0.2428243  # tests/validation/test_limits.py: the 4-hinge mechanism, by hand


def _run(name, tmp_path):
    report = run_study(load_study(STUDIES / f"{name}.toml"), out=tmp_path, jobs=1)
    return xr.load_dataset(report.results)


def test_fig7_8_in_plane_limit(tmp_path):
    """Every settlement scenario meets at the paper's lambda_0max = 0.243 (Fig. 8), the 4-hinge
    mechanism's 0.2428243; the bisection stops within the study's tolerance (1e-6) below it."""
    ds = _run("fig7_8_inplane", tmp_path)
    assert ds.sizes["scenario"] >= 3 and (ds["outcome"].values == "limit").all()
    np.testing.assert_allclose(ds["lambda_direct"].values, PAPER_LAMBDA_0, atol=1e-7)
    assert np.all(np.abs(ds["lambda_direct"].values - 0.243) < 1e-3)
    gap = ds["lambda_max"].values - ds["lambda_direct"].values
    assert np.all((gap <= 1e-8) & (gap >= -1e-6))


def test_fig9_out_of_plane_limit(tmp_path):
    """lambda_90max = 0.178 (the paper, Fig. 9, printed to 3 digits): the rocking of the whole
    arch about its springing edges, (d/2)/z_c."""
    ds = _run("fig9_outofplane", tmp_path)
    assert ds.sizes["scenario"] >= 3 and (ds["outcome"].values == "limit").all()
    expected = 0.125 / rg.arch_centroid_height(1.0, 0.2, 14)
    np.testing.assert_allclose(ds["lambda_direct"].values, expected, atol=1e-10)
    assert np.all(np.abs(ds["lambda_direct"].values - 0.178) < 1e-3)
    gap = ds["lambda_max"].values - ds["lambda_direct"].values
    assert np.all((gap <= 1e-8) & (gap >= -1e-6))


def test_wall_from_file_rocks_out_of_plane_at_t_over_h(tmp_path):
    ds = _run("wall_from_file", tmp_path)
    lam = dict(zip(ds.scenario.values, ds.lambda_direct.values))
    # the whole 1.0 m high, 0.2 m thick wall rocks about its base edge: lambda = t / h
    assert lam["none/alpha=90"] == pytest.approx(0.2, abs=1e-10)
    assert 0.2 < lam["none/alpha=0"] < 1.0
    assert np.all(np.abs(ds.lambda_gap.values) <= 1e-5)  # the study's tolerance


def test_fig10_dome_limit_does_not_depend_on_the_settlement(tmp_path):
    ds = _run("fig10_dome", tmp_path)
    lam = ds.lambda_max.values
    assert np.all(np.isfinite(lam)) and lam[0] == pytest.approx(lam[1], rel=1e-9)
    assert set(ds.outcome.values) == {"limit"}


def test_groin_vault_study_limit_is_the_same_along_x_and_y(tmp_path):
    """The square groin vault maps onto itself by a quarter turn: the load paths along x and y
    meet the same lambda_max, and (rigid blocks) the piers' spreading does not change it."""
    ds = _run("groin_vault", tmp_path)
    assert set(ds.outcome.values) == {"limit"}
    lam = ds.lambda_max.values
    assert np.ptp(lam) <= 1e-9 * lam.max()
    assert np.all(np.abs(ds.lambda_gap.values) <= 1e-4)  # the study's bisection tolerance


def test_barrel_vault_study_structure_has_finite_limits_both_ways():
    """An odd number of courses in running bond is symmetric about x = 0 and y = 0: the limits
    along +x and -x (and +y and -y) are the same."""
    from tce.analysis import Analysis
    from tce.study.schema import build_material, build_structure

    (sc, *_) = load_study(STUDIES / "barrel_vault.toml").scenarios()
    an = Analysis(build_structure(sc.structure), build_material(sc.material))
    assert load_study(STUDIES / "barrel_vault.toml").spec.structure.courses % 2 == 1
    for alpha in (0.0, 90.0):
        lim, back = an.limit(alpha), an.limit(alpha + 180.0)
        assert lim.status == "optimal" and lim.certificate_gap < 1e-6
        assert back.lambda_max == pytest.approx(lim.lambda_max, rel=1e-6)
