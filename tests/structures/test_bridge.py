"""Arch bridges (tce.structures.bridge): one span is the segmental arch; spans on fixed piers
act alone, on free piers together; pier foundations settle; the generator's geometry: courses
across the width (stack and running bond) and skew, their joints against contact detection."""

from __future__ import annotations

import numpy as np
import pytest

from tce.analysis.loadpath import load_path
from tce.core.analysis import Analysis
from tce.core.loads import LoadPattern
from tce.structures.arch import segmental_arch
from tce.structures.bridge import arch_bridge
from tce.structures.contacts import check_overlaps, detect_interfaces

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


@pytest.mark.parametrize("kw", [dict(courses=3), dict(courses=4, bond="running", voussoirs=5),
                                dict(courses=3, bond="running", skew=30.0, spans=2, voussoirs=6),
                                dict(courses=2, skew=-45.0, spans=3, piers="fixed"),
                                dict(rings=2, stagger=True, courses=3, skew=25.0, spans=2)])
def test_courses_and_skew_joints_are_the_shared_faces_contact_detection_finds(kw):
    b = arch_bridge(**kw).validate()
    check_overlaps(b)
    found = {(i.a, i.b): i for i in detect_interfaces(b)}
    assert sorted(found) == sorted((i.a, i.b) for i in b.interfaces)
    for i in b.interfaces:
        j = found[i.a, i.b]
        assert i.area == pytest.approx(j.area, rel=1e-9)
        np.testing.assert_allclose(i.normal, j.normal, atol=1e-9)
        np.testing.assert_allclose(i.centroid, j.centroid, atol=1e-9)
    # the faces between rings keep their kind in every course
    assert {i.kind for i in b.interfaces} == ({"", "ring"} if kw.get("rings", 1) > 1 else {""})


def test_courses_names_and_running_bond():
    stack = arch_bridge(spans=2, voussoirs=3, courses=2)
    assert stack.names[:8] == ("abutment_left", "s1c01v01", "s1c01v02", "s1c01v03", "s1c02v01", "s1c02v02", "s1c02v03",
                               "pier1")
    running = arch_bridge(voussoirs=3, courses=3, bond="running")
    assert [n for n in running.names if n.startswith("s1c02")] == ["s1c02v01", "s1c02v02", "s1c02v03", "s1c02v04"]
    assert len([n for n in running.names if n.startswith("s1c03")]) == 3
    # stack bond: the courses split the one-course bridge's voussoirs across the width
    one = arch_bridge(voussoirs=3)
    np.testing.assert_allclose(stack.volumes[1:4] + stack.volumes[4:7], arch_bridge(spans=2, voussoirs=3).volumes[1:4],
                               rtol=1e-12)
    assert running.meta["courses"] == 3 and running.meta["bond"] == "running" and one.meta["skew"] == 0.0


def test_skew_is_the_square_bridge_sheared_in_plan():
    phi = 30.0
    square, skew = arch_bridge(spans=2, courses=2), arch_bridge(spans=2, courses=2, skew=phi)
    t = np.tan(np.radians(phi))
    np.testing.assert_allclose(skew.volumes, square.volumes, rtol=1e-12)
    c = square.centroids
    np.testing.assert_allclose(skew.centroids, np.column_stack([c[:, 0] + t * c[:, 1], c[:, 1], c[:, 2]]), atol=1e-12)
    # abutment faces and bed joints parallel to the line x = y tan(phi); course joints on y = const
    along = np.array([np.sin(np.radians(phi)), np.cos(np.radians(phi)), 0.0])
    for i in skew.interfaces:
        ring = abs(i.normal[1]) == 1.0
        assert ring or abs(i.normal @ along) < 1e-12
    # an abutment's plan is a parallelogram: its extent along x grows by depth tan(phi)
    left = skew.blocks[0].shape.vertices
    assert left[:, 0].max() - left[:, 0].min() == pytest.approx(square.extent[1] * t + np.ptp(
        square.blocks[0].shape.vertices[:, 0]), rel=1e-12)


def test_bad_3d_bridges_are_refused():
    with pytest.raises(ValueError, match="skew must be"):
        arch_bridge(skew=75.0)
    with pytest.raises(ValueError, match="bond must be"):
        arch_bridge(bond="flemish")
    with pytest.raises(ValueError, match="courses must be"):
        arch_bridge(courses=0)
    with pytest.raises(ValueError, match="running' across the width is built with one ring only"):
        arch_bridge(rings=2, courses=2, bond="running")
