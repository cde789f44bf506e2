"""The bridge generator's wiring (tce.structures.bridge.arch_bridge) against hand counts: for
1, 2 and 3 spans, on free and on fixed piers, the blocks in order, which of them are
supports, which pairs every joint connects (and in which direction), where each joint is,
and that each joint's polygon is a face shared by the two blocks it names."""

from __future__ import annotations

import numpy as np
import pytest

from tce.structures.bridge import arch_bridge

SPAN, PIER_WIDTH, PIER_HEIGHT, DEPTH = 6.0, 1.0, 3.0, 3.0
N = 3  # voussoirs per span: few enough to list by hand


def hand_blocks(spans: int, piers: str) -> list[str]:
    names = ["abutment_left"]
    for s in range(1, spans + 1):
        names += [f"s{s}v01", f"s{s}v02", f"s{s}v03"]
        if s < spans:
            names.append(f"pier{s}")
    names.append("abutment_right")
    if piers == "free":
        names += [f"foundation{k}" for k in range(1, spans)]
    return names


HAND = {
    # (spans, piers): (supports, joints as (A, B) with the normal from A into B)
    (1, "free"): (
        ["abutment_left", "abutment_right"],
        [("abutment_left", "s1v01"), ("s1v01", "s1v02"), ("s1v02", "s1v03"), ("s1v03", "abutment_right")],
    ),
    (2, "free"): (
        ["abutment_left", "abutment_right", "foundation1"],
        [("abutment_left", "s1v01"), ("s1v01", "s1v02"), ("s1v02", "s1v03"), ("s1v03", "pier1"),
         ("pier1", "s2v01"), ("s2v01", "s2v02"), ("s2v02", "s2v03"), ("s2v03", "abutment_right"),
         ("pier1", "foundation1")],
    ),
    (2, "fixed"): (
        ["abutment_left", "pier1", "abutment_right"],
        [("abutment_left", "s1v01"), ("s1v01", "s1v02"), ("s1v02", "s1v03"), ("s1v03", "pier1"),
         ("pier1", "s2v01"), ("s2v01", "s2v02"), ("s2v02", "s2v03"), ("s2v03", "abutment_right")],
    ),
    (3, "free"): (
        ["abutment_left", "abutment_right", "foundation1", "foundation2"],
        [("abutment_left", "s1v01"), ("s1v01", "s1v02"), ("s1v02", "s1v03"), ("s1v03", "pier1"),
         ("pier1", "s2v01"), ("s2v01", "s2v02"), ("s2v02", "s2v03"), ("s2v03", "pier2"),
         ("pier2", "s3v01"), ("s3v01", "s3v02"), ("s3v02", "s3v03"), ("s3v03", "abutment_right"),
         ("pier1", "foundation1"), ("pier2", "foundation2")],
    ),
    (3, "fixed"): (
        ["abutment_left", "pier1", "pier2", "abutment_right"],
        [("abutment_left", "s1v01"), ("s1v01", "s1v02"), ("s1v02", "s1v03"), ("s1v03", "pier1"),
         ("pier1", "s2v01"), ("s2v01", "s2v02"), ("s2v02", "s2v03"), ("s2v03", "pier2"),
         ("pier2", "s3v01"), ("s3v01", "s3v02"), ("s3v02", "s3v03"), ("s3v03", "abutment_right")],
    ),
}


def bridge(spans: int, piers: str):
    return arch_bridge(spans=spans, span=SPAN, rise=1.5, thickness=0.4, depth=DEPTH, voussoirs=N,
                       pier_width=PIER_WIDTH, pier_height=PIER_HEIGHT, piers=piers)


@pytest.mark.parametrize("spans, piers", list(HAND))
def test_blocks_supports_and_joints_as_counted_by_hand(spans, piers):
    b = bridge(spans, piers)
    supports, joints = HAND[spans, piers]
    assert list(b.names) == hand_blocks(spans, piers)
    assert len(b.blocks) == 2 + spans * N + (spans - 1) * (2 if piers == "free" else 1)
    assert sorted(b.support_names) == sorted(supports)
    assert [(b.names[i.a], b.names[i.b]) for i in b.interfaces] == joints
    assert len(b.interfaces) == spans * (N + 1) + (spans - 1 if piers == "free" else 0)
    # every free block is joined to something, and no joint joins two supports
    joined = {name for pair in joints for name in pair}
    assert joined == set(b.names)
    assert not any(b.blocks[i.a].support and b.blocks[i.b].support for i in b.interfaces)


@pytest.mark.parametrize("spans, piers", list(HAND))
def test_each_joint_is_a_face_of_both_blocks_it_connects(spans, piers):
    """Every corner of a joint's polygon is a corner of block A and of block B, and the
    normal points from A's centroid side into B's."""
    b = bridge(spans, piers)
    for itf in b.interfaces:
        for k in (itf.a, itf.b):
            v = b.blocks[k].shape.vertices
            gap = np.min(np.linalg.norm(v[None, :, :] - itf.points[:, None, :], axis=2), axis=1)
            assert gap.max() < 1e-9, (b.names[itf.a], b.names[itf.b], b.names[k])
        c = itf.points.mean(axis=0)
        assert (b.blocks[itf.a].centroid - c) @ itf.normal < 0 < (b.blocks[itf.b].centroid - c) @ itf.normal


@pytest.mark.parametrize("spans", [1, 2, 3])
def test_springings_piers_and_foundations_where_the_dimensions_put_them(spans):
    """Span s is centred on (s - (spans + 1) / 2) (span + pier width); its intrados springings
    are at its centre -+ span / 2, z = 0; a pier's base is the gap between two spans at
    z = -pier height, its foundation's top that same rectangle."""
    b = bridge(spans, "free")
    pitch = SPAN + PIER_WIDTH
    centres = [(s - (spans + 1) / 2) * pitch for s in range(1, spans + 1)]
    by_pair = {(b.names[i.a], b.names[i.b]): i.points for i in b.interfaces}
    for s, c in enumerate(centres, start=1):
        left = "abutment_left" if s == 1 else f"pier{s - 1}"
        right = "abutment_right" if s == spans else f"pier{s}"
        for pair, x in (((left, f"s{s}v01"), c - SPAN / 2), ((f"s{s}v03", right), c + SPAN / 2)):
            springing = by_pair[pair]
            low = springing[springing[:, 2] < 1e-12]
            assert len(low) == 2 and np.allclose(low[:, 0], x)
            assert np.allclose(sorted(low[:, 1]), [-DEPTH / 2, DEPTH / 2])
    for k in range(1, spans):
        base = by_pair[f"pier{k}", f"foundation{k}"]
        x0 = centres[k - 1] + SPAN / 2
        assert np.allclose(base[:, 2], -PIER_HEIGHT)
        assert np.allclose(sorted(set(np.round(base[:, 0], 12))), [x0, x0 + PIER_WIDTH])
        foot = b.blocks[b.index[f"foundation{k}"]].shape.vertices
        assert np.allclose([foot[:, 2].min(), foot[:, 2].max()], [-PIER_HEIGHT - PIER_WIDTH, -PIER_HEIGHT])
    # the abutments' and piers' bases all at z = -pier height
    for name in ("abutment_left", "abutment_right", *(f"pier{k}" for k in range(1, spans))):
        assert b.blocks[b.index[name]].shape.vertices[:, 2].min() == pytest.approx(-PIER_HEIGHT)
