"""The hard cases of :mod:`tce.hard`: each must end with its expected status, residuals within
its bound, its invariants kept, and no exception."""

from __future__ import annotations

import pytest

from tce.quality.hard import CASES, run_case


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_hard_case(case):
    run = run_case(case)
    assert run.ok, "; ".join(run.errors)
    assert run.n_solves > 0


def test_check_table_lists_every_case(capsys):
    from tce.quality.check import check_command, run_checks

    table = run_checks(select="friction 0")
    assert list(table["case"]) == ["friction 0"] and bool(table["ok"].all())

    class Args:
        select = "transversal"

    assert check_command(Args()) == 0
    out = capsys.readouterr().out
    assert "transversal motion, Heyman" in out and "unbounded" in out and "recession" in out
