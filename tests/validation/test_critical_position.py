"""The critical position of a moving vehicle on the paper's arch, found by
tce.analysis.critical without a grid, against an independent scan of an independent LP
(tests/reference/moving_load.py: HiGHS, its own geometry, refined by zooming to 1e-6 m)."""

from __future__ import annotations

from functools import cache

import pytest

from tce.analysis.critical import critical_position
from tce.core.analysis import Analysis
from tce.core.loads import LoadPattern
from tce.structures.arch import semicircular_arch

from reference.moving_load import Arch, scan

ARCH = Arch()
AN = Analysis(semicircular_arch())


@cache
def single_load_reference() -> tuple[float, float]:
    return scan(lambda x: ARCH.lambda_max([(x, 1.0)]), -1.2, 1.2, h=0.02)


def test_two_unequal_axles_critical_position_and_per_axle_load():
    # axles 0.5 m apart, 1 kN and 1.5 kN: lambda_max is the collapse load of the 1 kN axle (kN)
    axles = [(0.0, 1.0), (0.5, 1.5)]
    x_ref, lam_ref = scan(lambda x: ARCH.lambda_max([(x + dx, P) for dx, P in axles]), -1.7, 1.2, h=0.02)
    res = critical_position(AN, LoadPattern(lateral=False, vehicle=[dict(axles=axles)]))
    assert res.status == "optimal" and res.ties == ()
    assert res.lambda_max == pytest.approx(lam_ref, rel=1e-4)
    assert res.critical_x == pytest.approx(x_ref, abs=1e-3 * 2.4)


def test_two_equal_axles_mirror_tie_stated():
    axles = [(0.0, 1.0), (0.4, 1.0)]
    x_ref, lam_ref = scan(lambda x: ARCH.lambda_max([(x + dx, P) for dx, P in axles]), -1.6, 1.2, h=0.02)
    res = critical_position(AN, LoadPattern(lateral=False, vehicle=[dict(axles=axles)]))
    assert res.lambda_max == pytest.approx(lam_ref, rel=1e-4)
    # the vehicle and its mirror image: reference at x and at -x - 0.4; the leftmost is reported
    assert res.critical_x == pytest.approx(min(x_ref, -x_ref - 0.4), abs=2.4e-3)
    assert len(res.ties) == 1 and res.ties[0] == pytest.approx(max(x_ref, -x_ref - 0.4), abs=2.4e-3)


@pytest.mark.parametrize("grid", [None, [0.0], [-0.9 + 0.2 * k for k in range(10)], [-0.9 + 0.05 * k for k in range(37)]])
def test_single_load_same_answer_whatever_grid(grid):
    x_ref, lam_ref = single_load_reference()
    res = critical_position(AN, LoadPattern(lateral=False, point=[dict(on_top=[0.0, 0.0], force=[0, 0, -1.0])]), start=grid)
    assert res.lambda_max == pytest.approx(lam_ref, rel=1e-4)
    assert abs(res.critical_x) == pytest.approx(abs(x_ref), abs=2.4e-3) and res.critical_x < 0
    assert res.ties and res.ties[0] == pytest.approx(-res.critical_x, abs=1e-6)


def test_a_failed_solve_gives_no_position(monkeypatch):
    """Honest statuses: one limit solve that fails makes the search numerical, with no number."""
    from dataclasses import replace

    an = Analysis(semicircular_arch())
    real = an.limit
    calls = []

    def flaky(*args, **kwargs):
        res = real(*args, **kwargs)
        calls.append(res)
        return replace(res, status="numerical", message="planted") if len(calls) == 7 else res

    monkeypatch.setattr(an, "limit", flaky)
    res = critical_position(an, LoadPattern(lateral=False, vehicle=[dict(axles=[(0.0, 1.0)])]))
    assert res.status == "numerical" and not res.ok and "planted" in res.message
    assert res.critical_x != res.critical_x and res.lambda_max != res.lambda_max and res.pattern is None
