"""The atlas' rules (docs/validation.md), case by case, without computing tce's values:

- a tolerance is at most twice the stated discretisation error of tce's value against the
  publication's own model (the reference), where tce discretises what the publication does not;
- each published value is compared at its printed digits: whether the reference rounds to it
  is stated, and the table of docs/validation.md says so for those that do not;
- CR2020's assumption (each voussoir's weight on the centreline arc) moves the weights and
  nothing else.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest

from tce.core.loads import resolve
from tce.quality.validation import CASES, _arch, centreline_weights, run_validation

DOC = (Path(__file__).resolve().parents[3] / "docs" / "validation.md").read_text(encoding="utf-8")
TABLE = {line.split("|")[1].strip(): line for line in DOC.splitlines() if line.startswith("| ") and "|" in line[2:]}


@pytest.mark.parametrize("case", [c for c in CASES if c.error is not None], ids=lambda c: c.name)
def test_tolerance_at_most_twice_the_stated_discretisation_error(case):
    assert 0 < case.error and case.tolerance <= 2 * case.error * (1 + 1e-12)
    assert case.reference is not None  # an error is against an independent reference


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.name)
def test_printed_digits_stated_and_in_the_table(case):
    rounded = round(case.expected, case.decimals)
    assert math.isclose(rounded, case.published, abs_tol=1e-12) == case.rounds
    row = TABLE[case.name]
    if not case.rounds:
        assert f"rounds to {rounded:.{case.decimals}f}, not" in row
    else:
        assert "not" not in row.split("|")[-2]


def test_a_case_that_stops_rounding_is_not_ok(monkeypatch):
    """A reference that no longer rounds as stated fails the case even within tolerance."""
    import dataclasses

    (case,) = [c for c in CASES if c.name == "stress_block"]
    wrong = dataclasses.replace(case, rounds=False)
    (row,) = run_validation([wrong]).itertuples()
    assert abs(row.difference) <= row.tolerance and row.rounds and not row.ok


@pytest.mark.parametrize("n", [6, 13])
def test_centreline_weights_move_each_voussoirs_weight_and_nothing_else(n):
    """Each voussoir keeps its weight's line of action in the radial direction of its bisector
    but at radius sin(a)/a (a = pi / 2n), and the ring sector's weight, gamma d t pi / n; the
    total weight becomes the ring's, gamma d t pi (R = 1)."""
    t = 0.12
    arch = _arch(t, n)
    applied = resolve(centreline_weights(arch), arch)
    a = math.pi / (2 * n)
    sector = 20.0 * 0.25 * t * 2 * a
    for k, i in enumerate(arch.free_indices):
        block, mine = arch.blocks[i], applied.blocks == i
        f, p = applied.forces[mine], applied.points[mine]
        assert np.allclose(f[:, :2], 0.0)
        down = block.weight - f[:, 2].sum()  # the self-weight and the two loads, downwards
        assert down == pytest.approx(sector, rel=1e-12)
        # where the three act together (x, z): on the centreline arc's centroid
        where = (block.weight * block.centroid[[0, 2]] - f[:, 2] @ p[:, [0, 2]]) / down
        phi = math.pi * (1 - (k + 0.5) / n)
        assert where == pytest.approx(math.sin(a) / a * np.array([math.cos(phi), math.sin(phi)]), abs=1e-12)
    assert -applied.forces[:, 2].sum() + sum(arch.blocks[i].weight for i in arch.free_indices) == pytest.approx(
        20.0 * 0.25 * t * math.pi, rel=1e-12)


def test_the_table_lists_every_case_with_its_tolerance():
    for case in CASES:
        cells = TABLE[case.name].split("|")
        assert float(cells[8]) == case.tolerance, case.name  # the tolerance column
    assert not re.search(r"\| cr_\w+ .*shift", DOC)


def test_weights_are_named_and_centreline_goes_with_radial_joints():
    from tce.quality.validation import min_ratio

    with pytest.raises(ValueError, match="weights must be one of"):
        min_ratio(8, weights="rings")
    with pytest.raises(ValueError, match="centreline with radial joints"):
        min_ratio(8, joints="vertical", weights="centreline")
