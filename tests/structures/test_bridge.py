"""Arch bridges (tce.structures.bridge): one span is the segmental arch; spans on fixed piers
act alone, on free piers together; pier foundations settle; the generator's geometry."""

from __future__ import annotations

import numpy as np
import pytest

from tce.analysis.loadpath import load_path
from tce.core.analysis import Analysis
from tce.core.loads import LoadPattern
from tce.structures.arch import segmental_arch
from tce.structures.bridge import arch_bridge

AXLE = [dict(axles=[[0.0, 2.0]], wheels=[-0.9, 0.9])]


def test_one_span_is_the_segmental_arch_on_its_abutments():
    b = arch_bridge(spans=1, span=6.0, rise=1.5, thickness=0.4, depth=3.0, voussoirs=12, pier_height=0.4)
    a = segmental_arch(6.0, 1.5, 0.4, 3.0, 12)
    assert b.names[1:-1] == tuple(f"s1v{k:02d}" for k in range(1, 13))
    np.testing.assert_allclose(b.centroids, a.centroids, atol=1e-12)
    p = LoadPattern(lateral=False, vehicle=[dict(AXLE[0], x=-1.5)])
    assert Analysis(b).limit(loads=p).lambda_max == pytest.approx(Analysis(a).limit(loads=p).lambda_max, rel=1e-9)


def test_spans_on_fixed_piers_act_alone_on_free_piers_together():
    fixed = arch_bridge(spans=3, piers="fixed")
    free = arch_bridge(spans=3, piers="free")
    assert fixed.support_names == ("abutment_left", "pier1", "pier2", "abutment_right")
    assert free.support_names == ("abutment_left", "abutment_right", "foundation1", "foundation2")
    single = Analysis(segmental_arch(6.0, 1.5, 0.4, 3.0, 12))
    for x in (-1.5, 0.7):  # the middle span is centred on x = 0: the same load on the single arch
        p = LoadPattern(lateral=False, vehicle=[dict(AXLE[0], x=x)])
        lam_fixed = Analysis(fixed).limit(loads=p).lambda_max
        assert lam_fixed == pytest.approx(single.limit(loads=p).lambda_max, rel=1e-9)
        # the same load on an outer span: moved by the pitch (span + pier width)
        q = LoadPattern(lateral=False, vehicle=[dict(AXLE[0], x=x + 7.0)])
        assert Analysis(fixed).limit(loads=q).lambda_max == pytest.approx(lam_fixed, rel=1e-9)
        # free piers can rock: the capacity is not higher
        assert Analysis(free).limit(loads=p).lambda_max <= lam_fixed * (1 + 1e-9)


def test_mirror_of_the_bridge_mirrors_the_critical_load():
    an = Analysis(arch_bridge(spans=2))
    a = an.limit(loads=LoadPattern(lateral=False, vehicle=[dict(AXLE[0], x=-2.0)])).lambda_max
    b = an.limit(loads=LoadPattern(lateral=False, vehicle=[dict(AXLE[0], x=2.0)])).lambda_max
    assert a == pytest.approx(b, rel=1e-7)


def test_pier_settlement_scenario():
    an = Analysis(arch_bridge(spans=2))
    p = LoadPattern(lateral=False, vehicle=[dict(AXLE[0], x=-2.0)])
    still = load_path(an, loads=p, step=20.0, lam_cap=1000.0, atol=1e-4)
    sunk = load_path(an, settlements={"foundation1": [0.0, 0.0, -0.01, 0.0, 0.0, 0.0]}, loads=p, step=20.0,
                     lam_cap=1000.0, atol=1e-4)
    assert still.outcome == sunk.outcome == "limit"
    # rigid blocks: the support motion selects the state, not the capacity (small displacements)
    assert sunk.lambda_max == pytest.approx(still.lambda_max, abs=2e-4)
    r0 = an.solve(lam=0.0, loads=p)
    r1 = an.solve(lam=0.0, loads=p, settlements={"foundation1": [0.0, 0.0, -0.01, 0.0, 0.0, 0.0]})
    assert r0.ok and r1.ok and not np.allclose(r0.support_wrenches, r1.support_wrenches, atol=1e-3)


def test_bad_bridges_are_refused():
    with pytest.raises(ValueError, match="pier_width must be >="):
        arch_bridge(spans=2, pier_width=0.1)
    with pytest.raises(ValueError, match="piers must be"):
        arch_bridge(piers="loose")
    with pytest.raises(ValueError):
        arch_bridge(spans=0)
