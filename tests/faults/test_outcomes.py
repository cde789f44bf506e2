"""Runs that end and outcomes that are honest: float-spacing bisection, capped increments,
extreme stiffness and friction, undecided steps, and a run summary by outcome."""

from __future__ import annotations

import math
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from tce.analysis.loadpath import MAX_INCREMENTS, load_path
from tce.core.analysis import Analysis
from tce.core.material import Material
from tce.structures.arch import semicircular_arch
from tce.cli import main

from .common import TINY, clean, write

SPREAD = {"right": [0.001, 0.0, 0.0, 0.0, 0.0, 0.0]}
TRANSVERSAL = {"right": [0.0, 0.001, 0.0, 0.0, 0.0, 0.0]}


@pytest.fixture(scope="module")
def arch():
    return semicircular_arch(voussoirs=6)


def test_a_tolerance_below_float_spacing_ends(arch) -> None:
    """tolerance = 1e-300 bisected forever once the bracket was two neighbouring floats."""
    lp = load_path(Analysis(arch, Material(friction=0.8)), 0.0, SPREAD, step=0.05, atol=1e-300)
    assert lp.outcome == "limit" and lp.lambda_upper == math.nextafter(lp.lambda_max, math.inf)
    assert lp.n_solves < 100  # 8 increments, then about 55 halvings of 0.05 down to float spacing


def test_increments_are_capped(arch) -> None:
    with pytest.raises(ValueError, match="MAX_INCREMENTS|more than 10000"):
        load_path(Analysis(arch, Material(friction=0.8)), step=1e-12, lam_cap=100.0)
    assert MAX_INCREMENTS == 10_000


@pytest.mark.parametrize("stiffness", [1e16, 1e18, 1e20])
def test_extreme_stiffness_gives_the_rigid_answer(arch, stiffness: float) -> None:
    """Stiffness of 1e18 with a 1 mm spreading was 'infeasible' at lambda = 0. Contacts that
    stiff are rigid to the last digit: the reactions are the rigid scene's (the minimum
    thrust for the spreading), and the limit is the direct one (admissibility does not
    depend on stiffness)."""
    rigid = Analysis(arch, Material(friction=0.8)).solve(0.0, 0.0, SPREAD)
    stiff = Analysis(arch, Material(friction=0.8, normal_stiffness=stiffness))
    step0 = stiff.solve(0.0, 0.0, SPREAD)
    assert step0.status == "optimal"
    np.testing.assert_allclose(step0.support_wrenches, rigid.support_wrenches, rtol=1e-6, atol=1e-7)
    lp = load_path(stiff, 0.0, SPREAD, step=0.05, atol=1e-4)
    assert lp.outcome == "limit"
    assert abs(lp.lambda_max - lp.lambda_direct) <= 1e-4 + 1e-6


def test_extreme_friction_is_right_or_numerical(arch) -> None:
    """mu = 1e6 with a transversal motion: 13 numerical steps then one infeasible used to end
    'infeasible' (nothing stands), for an arch that stands."""
    lp = load_path(Analysis(arch, Material(friction=1e6)), 0.0, TRANSVERSAL, step=0.05, atol=1e-3)
    assert lp.outcome in ("limit", "numerical")
    if lp.outcome == "limit":
        assert abs(lp.lambda_max - lp.lambda_direct) <= 1e-3 + 1e-6
    else:
        assert math.isnan(lp.lambda_max)


class Scripted:
    """An analysis whose steps have the statuses given by ``status(lam)`` (to test the outcome logic alone)."""

    def __init__(self, status, direct: float = float("nan")) -> None:
        self.status, self.direct = status, direct

    def path(self, alpha=None, settlements=None, loads=None):
        """The solve of each step of a path (as :meth:`tce.core.analysis.Analysis.path`)."""

        def solve_at(lam):
            s = self.status(lam)
            return SimpleNamespace(lam=lam, status=s, ok=s == "optimal", solve_time=0.0)

        return solve_at

    def limit(self, alpha=None, loads=None, mechanism=True):
        return SimpleNamespace(lambda_max=self.direct)


def test_bisection_below_float_spacing_ends_with_neighbouring_floats() -> None:
    """The same with scripted statuses: fails (instead of hanging) if the bisection does not stop."""
    calls = []

    def status(lam: float) -> str:
        calls.append(lam)
        if len(calls) > 500:
            raise RuntimeError("the bisection does not end")
        return "optimal" if lam < 0.25 else "infeasible"

    lp = load_path(Scripted(status, direct=0.25), step=0.1, atol=1e-300, lam_cap=1.0)
    assert lp.outcome == "limit" and lp.lambda_upper == math.nextafter(lp.lambda_max, math.inf)
    assert lp.lambda_max < 0.25 <= lp.lambda_upper


@pytest.mark.parametrize(
    ("status", "outcome"),
    [
        (lambda lam: "infeasible", "infeasible"),
        (lambda lam: "numerical" if lam < 0.3 else "infeasible", "numerical"),
        (lambda lam: "optimal" if lam < 0.2 else "numerical", "numerical"),
        (lambda lam: "optimal", "no_limit"),
        (lambda lam: "optimal" if lam < 0.25 else "infeasible", "limit"),
        (lambda lam: "numerical" if lam == 0.0 else "optimal" if lam < 0.25 else "infeasible", "limit"),
        (lambda lam: "optimal" if lam <= 0.1 else "numerical" if lam < 0.3 else "infeasible", "numerical"),
    ],
    ids=["infeasible at 0", "numerical before infeasible", "numerical to the cap", "no limit", "limit",
         "one numerical step below the limit", "limit bracketed by undecided steps only"],
)
def test_outcome_logic(status, outcome: str) -> None:
    lp = load_path(Scripted(status, direct=0.25), step=0.1, atol=1e-3, lam_cap=1.0)
    assert lp.outcome == outcome
    assert math.isnan(lp.lambda_max) == (outcome != "limit")


HEYMAN = TINY.replace("[sweep]\nfriction = [0.8, 2.0]\n", "").replace(
    "right = [0.001, 0.0, 0.0, 0.0, 0.0, 0.0]", "right = [0.0, 0.001, 0.0, 0.0, 0.0, 0.0]"
)


@pytest.mark.parametrize("strict", [False, True])
def test_summary_counts_outcomes_and_strict_exits_4(strict: bool, tmp_path: Path, capsys) -> None:
    """A Heyman arch under a transversal motion is unbounded: it was reported '1 solved', exit 0."""
    argv = ["run", str(write(tmp_path, HEYMAN)), "--out", str(tmp_path / "out"), "--jobs", "1", "--no-plots"]
    assert main(argv + (["--strict"] if strict else [])) == (4 if strict else 0)
    captured = capsys.readouterr()
    clean(captured.err)
    assert "2 scenarios (2 solved): 1 limit, 1 unbounded" in captured.out
    assert "  unbounded: outward" in captured.out.splitlines()
