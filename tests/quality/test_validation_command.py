"""``tce check --validation``: the atlas' table on the command line, its exit codes and
selection; and the vertical-joint arch meeting the other features (models, mirror, settlement)."""

from __future__ import annotations

import dataclasses

import pytest

from tce import Analysis, Material, semicircular_arch
from tce.quality import validation
from tce.cli import main


def test_check_validation_prints_the_selected_cases(capsys):
    assert main(["check", "--validation", "--select", "paper_"]) == 0
    out = capsys.readouterr().out
    assert "paper_in_plane" in out and "paper_out_of_plane" in out and "cr_eta" not in out
    assert "0.242824" in out and "2/2 cases within tolerance" in out


def test_check_validation_fails_a_case_out_of_tolerance(monkeypatch, capsys):
    (case,) = [c for c in validation.CASES if c.name == "paper_in_plane"]
    wrong = dataclasses.replace(case, published=0.25)
    monkeypatch.setattr(validation, "CASES", (wrong,))
    monkeypatch.setattr(validation.run_validation, "__defaults__", ((wrong,), None))
    assert main(["check", "--validation"]) == 1
    out = capsys.readouterr().out
    assert "FAILED paper_in_plane: tce 0.242824 against 0.25" in out and "0/1 cases" in out


@pytest.fixture(scope="module")
def vertical():
    return semicircular_arch(voussoirs=12, joints="vertical")


def test_vertical_joints_planar_equals_spatial(vertical):
    planar = Analysis(vertical, Material(), model="auto").limit(0.0)
    spatial = Analysis(vertical, Material(), model="spatial").limit(0.0)
    assert planar.model == "planar" and spatial.model == "spatial"
    assert planar.lambda_max == pytest.approx(spatial.lambda_max, rel=1e-7)


def test_vertical_joints_mirror_and_settlement(vertical):
    an = Analysis(vertical, Material())
    assert an.limit(0.0).lambda_max == pytest.approx(an.limit(180.0).lambda_max, rel=1e-7)
    r = an.solve(0.05, settlements={"right": [0.001, 0, 0, 0, 0, 0]})
    assert r.status == "optimal"


def test_vertical_joints_slide_with_ordinary_friction(vertical):
    """A vertical joint carries the weight above it in shear against the thrust alone
    (|T| / N = W / H): near the springings that needs mu of several units, so with mu = 0.8 the
    arch cannot stand (the continuous ring with vertical cuts agrees), while it stands with
    Heyman's unlimited friction."""
    from reference import continuous_arch as ref

    assert Analysis(vertical, Material(0.8)).solve(0.0).status == "infeasible"
    assert Analysis(vertical, Material()).solve(0.0).status == "optimal"
    assert not ref.stands(0.2 / 1.1, cuts="vertical", mu=0.8, m=200)
    assert ref.stands(0.2 / 1.1, cuts="vertical", m=200)
