"""The judge of the hard-case suite itself: a case passes only when every solve ends with an
expected status, every optimal residual is within the bound, its invariants hold, it raised
nothing and it solved something."""

from __future__ import annotations

from dataclasses import replace
from functools import lru_cache

import pytest
from helpers import block_on_support

from tce.analysis import Analysis
from tce.core.material import Material
from tce.quality.hard import HardCase, Outcome, run_case


@lru_cache(maxsize=None)
def _results():
    """A real optimal and a real infeasible answer (the block rocks at lambda = 0.4)."""
    an = Analysis(block_on_support(0.4, 1.0), Material(), model="spatial")
    return an.solve(0.2), an.solve(0.5)


def _case(*results, expected=("optimal",), bound=1e-9, errors=()):
    def run():
        out = Outcome()
        for r in results:
            out.add(r)
        out.errors.extend(errors)
        return out

    return HardCase("fake", run, expected, bound)


def test_the_real_answers():
    ok, over = _results()
    assert ok.status == "optimal" and max(ok.eq_residual, ok.cone_residual) < 1e-9
    assert over.status == "infeasible"


def test_expected_statuses_pass():
    ok, over = _results()
    run = run_case(_case(ok, over, expected=("optimal", "infeasible")))
    assert run.ok and run.errors == ()
    assert run.statuses == ("optimal", "infeasible") and run.n_solves == 2


@pytest.mark.parametrize("expected", [("optimal",), ("infeasible",), ("unbounded",)])
def test_an_unexpected_status_fails(expected):
    ok, over = _results()
    run = run_case(_case(ok, over, expected=expected))
    assert not run.ok
    wrong = [r.status for r in (ok, over) if r.status not in expected]
    assert len(run.errors) == len(wrong)
    assert all(repr(s) in e for s, e in zip(wrong, run.errors))


@pytest.mark.parametrize("field", ["eq_residual", "cone_residual"])
def test_a_residual_above_the_bound_fails(field):
    ok, _ = _results()

    def with_state(value):  # the result with its state's residual replaced
        return replace(ok, selector=lambda canonical: replace(ok.state, **{field: value}))

    noisy = with_state(1e-6)
    assert not run_case(_case(noisy, bound=1e-7)).ok
    assert run_case(_case(noisy, bound=1e-5)).ok
    nan = with_state(float("nan"))
    assert not run_case(_case(nan)).ok  # a residual that was not computed is not within bounds


def test_a_broken_invariant_fails():
    ok, _ = _results()
    run = run_case(_case(ok, errors=["H/W: 0.5 != 0.6"]))
    assert not run.ok and run.errors == ("H/W: 0.5 != 0.6",)


def test_an_exception_fails():
    def run():
        raise RuntimeError("boom")

    result = run_case(HardCase("raises", run, ("optimal",)))
    assert not result.ok and result.statuses == ("error",) and "boom" in result.errors[0]


def test_a_case_that_solves_nothing_fails():
    run = run_case(_case())
    assert not run.ok and run.n_solves == 0
