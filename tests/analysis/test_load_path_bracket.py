"""The load path's bracket around the direct lambda_max, and its fall-back to bisection."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from tce.analysis.loadpath import load_path
from tce.core.analysis import Analysis
from tce.core.material import Material

from helpers import block_on_support

MM = 1e-3


def verified(lp, atol):
    """The answer is a verified bracket: an optimal step at lambda_max, an infeasible one at
    lambda_upper, at most atol apart."""
    assert lp.outcome == "limit"
    at = {s.lam: s.status for s in lp.steps}
    assert at[lp.lambda_max] == "optimal" and at[lp.lambda_upper] == "infeasible"
    assert 0 < lp.lambda_upper - lp.lambda_max <= atol


@pytest.mark.parametrize("atol", [1e-3, 1e-6, 1e-8])
def test_block_rocks_at_b_over_h(atol):
    # validation: a rigid block b wide and h tall rocks on its edge at lambda = b / h
    b, h = 0.4, 1.0
    lp = load_path(Analysis(block_on_support(b, h), Material(0.8)), 0.0, step=0.1, atol=atol)
    verified(lp, atol)
    assert b / h - atol <= lp.lambda_max <= b / h + 1e-8 * b / h


@pytest.mark.parametrize("sett", [{}, {"right": [MM, 0, 0, 0, 0, 0]}, {"right": [0, 0, -MM, 0, 0, 0]}])
def test_direct_bracket_takes_fewer_solves_for_the_same_limit(arch, sett):
    paths = {b: load_path(Analysis(arch, Material(0.8)), 0.0, sett, step=0.02, atol=1e-6, bracket=b)
             for b in ("direct", "bisection")}
    for lp in paths.values():
        verified(lp, 1e-6)
        assert abs(lp.gap) <= 1e-6
    # the increments are shared; the direct bracket confirms in 2 solves what bisection takes ~15 for
    increments = sum(1 for s in paths["bisection"].steps if round(s.lam / 0.02, 9).is_integer())
    assert paths["direct"].n_solves == increments + 2
    assert paths["bisection"].n_solves > increments + 10
    # the curves (the increments) are the same
    for a, b in zip(paths["direct"].steps[:increments], paths["bisection"].steps[:increments]):
        assert a.lam == b.lam and a.status == b.status


@pytest.mark.parametrize("shift", [+3e-3, -3e-3, +5e-7, float("nan")])
def test_a_wrong_direct_value_falls_back_to_bisection(arch, shift):
    an = Analysis(arch, Material(0.8))
    true = an.limit(0.0)
    an.limit = lambda *a, **k: dataclasses.replace(true, lambda_max=true.lambda_max + shift)  # type: ignore[method-assign]
    lp = load_path(an, 0.0, {"right": [MM, 0, 0, 0, 0, 0]}, step=0.02, atol=1e-6)
    verified(lp, 1e-6)
    assert abs(lp.lambda_max - true.lambda_max) <= 1e-6


def test_bracket_choice_is_checked(arch):
    with pytest.raises(ValueError, match="bracket"):
        load_path(Analysis(arch, Material(0.8)), 0.0, bracket="secant")  # type: ignore[arg-type]
    assert np.isfinite(load_path(Analysis(arch, Material(0.8)), 0.0, atol=1e-4, bracket="bisection").lambda_max)
