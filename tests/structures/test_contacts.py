"""Interface detection and the overlapping-block check."""

from __future__ import annotations

import numpy as np
import pytest

from tce.structures.arch import pointed_arch, semicircular_arch
from tce.structures.assembly import AssemblyError, Block
from tce.structures.contacts import block_pairs, check_overlaps, detect_interfaces
from tce.structures.dome import hemispherical_dome
from tce.structures.geometry import box, prism


def _same_interfaces(asm, found):
    """Detected interfaces equal the generator's: same pairs, polygons as point sets, normals."""
    sup = set(asm.support_indices)
    found = [f for f in found if not (f.a in sup and f.b in sup)]  # generators skip support-support
    gen = {(i.a, i.b): i for i in asm.interfaces}
    det: dict = {}
    for f in found:
        det.setdefault((f.a, f.b), []).append(f)
    assert set(det) == set(gen)
    for key, g in gen.items():
        assert len(det[key]) == 1
        d = det[key][0]
        assert len(d.points) == len(g.points)
        dist = np.linalg.norm(d.points[:, None, :] - g.points[None, :, :], axis=2)
        assert dist.min(axis=1).max() < 1e-9 and dist.min(axis=0).max() < 1e-9
        assert np.allclose(d.normal, g.normal, atol=1e-9)
        assert d.normal @ (asm.blocks[d.b].centroid - asm.blocks[d.a].centroid) > 0


@pytest.mark.parametrize(
    "asm",
    [
        semicircular_arch(),
        pointed_arch(voussoirs=9),
        hemispherical_dome(5.0, 0.3, 8, 6),
        hemispherical_dome(5.0, 0.3, 12, 5, oculus=15.0),
    ],
    ids=["semicircular", "pointed", "dome", "dome-oculus"],
)
def test_detection_finds_exactly_the_generator_interfaces(asm):
    found = detect_interfaces(list(asm.blocks))
    assert all(f.a < f.b for f in found)
    _same_interfaces(asm, found)


def test_detection_on_a_big_dome():
    """A thousand blocks: every neighbour found, nothing more (its speed belongs to the bench)."""
    asm = hemispherical_dome(5.0, 0.3, 40, 24)
    assert len(asm.blocks) == 1000
    _same_interfaces(asm, detect_interfaces(asm))


def _L_block(name="L"):
    poly = np.array([[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]], float)
    return Block(name, prism(np.c_[poly, np.zeros(6)], np.c_[poly, np.ones(6)]), 20.0)


def _box(name, lo, hi):
    return Block(name, box(lo, hi), 20.0)


def test_non_convex_contact_polygon():
    found = detect_interfaces([_L_block(), _box("top", [0.5, 0.5, 1.0], [1.5, 1.5, 2.0])])
    assert len(found) == 1
    itf = found[0]
    assert (itf.a, itf.b) == (0, 1)
    assert np.allclose(itf.normal, [0, 0, 1])
    assert itf.area == pytest.approx(0.75)
    assert len(itf.points) == 6 and np.allclose(itf.points[:, 2], 1.0)
    # counter-clockwise about the normal (Newell normal along +n)
    from tce.structures.geometry import newell_normal

    assert newell_normal(itf.points) @ itf.normal > 0


def test_non_convex_face_overlap_in_two_pieces():
    # a U-shaped top face under a bar: two separate contact pieces
    u = np.array([[0, 0], [3, 0], [3, 2], [2, 2], [2, 1], [1, 1], [1, 2], [0, 2]], float)
    ublk = Block("U", prism(np.c_[u, np.zeros(8)], np.c_[u, np.ones(8)]), 20.0)
    bar = _box("bar", [-0.5, 1.5, 1.0], [3.5, 1.8, 1.5])
    found = detect_interfaces([ublk, bar])
    assert len(found) == 2
    assert sum(f.area for f in found) == pytest.approx(2 * 0.3)


def test_partial_overlap_gap_and_edge_contact():
    a = _box("a", [0, 0, 0], [1, 1, 1])
    shifted = _box("b", [0.4, 0.3, 1], [1.4, 1.3, 2])
    (itf,) = detect_interfaces([a, shifted])
    assert itf.area == pytest.approx(0.6 * 0.7)
    assert detect_interfaces([a, _box("gap", [0, 0, 1 + 1e-4], [1, 1, 2])]) == []
    assert detect_interfaces([a, _box("edge", [1, 0, 1], [2, 1, 2])]) == []  # touch along an edge only
    # within tolerance: found; and min_area filters small overlaps
    assert len(detect_interfaces([a, _box("near", [0, 0, 1 + 1e-7], [1, 1, 2])])) == 1
    assert detect_interfaces([a, shifted], min_area=0.5) == []
    # the normal points from the lower index into the higher one
    (rev,) = detect_interfaces([shifted, a])
    assert (rev.a, rev.b) == (0, 1) and np.allclose(rev.normal, [0, 0, -1])


def test_block_pairs_matches_brute_force():
    rng = np.random.default_rng(1)
    lo = rng.uniform(0, 10, (200, 3))
    hi = lo + rng.uniform(0.1, 2.0, (200, 3))
    brute = {
        (i, j)
        for i in range(200)
        for j in range(i + 1, 200)
        if np.all(lo[i] <= hi[j]) and np.all(lo[j] <= hi[i])
    }
    assert {tuple(p) for p in block_pairs(lo, hi).tolist()} == brute


def test_overlap_check():
    a = _box("a", [0, 0, 0], [1, 1, 1])
    check_overlaps([a, _box("b", [1, 0, 0], [2, 1, 1])])  # touching is fine
    for other in (
        _box("b", [0.5, 0, 0], [2, 1, 1]),  # corner inside
        _box("b", [0, 0, 0], [1, 1, 1]),  # duplicate (convex: its centroid is inside)
        _box("b", [0.3, -1, -1], [0.6, 2, 2]),  # a slab through the box, no vertex inside
    ):
        with pytest.raises(AssemblyError, match="'a' and 'b'|'b' and 'a'"):
            check_overlaps([a, other])
    L = _L_block()
    check_overlaps([L, _box("notch", [1.2, 1.2, 0], [1.8, 1.8, 1])])  # in the notch, not inside L
    check_overlaps([L, _box("fill", [1, 1, 0], [2, 2, 1])])  # fills the notch, touching
    with pytest.raises(AssemblyError, match="'L' and 'inner'"):
        check_overlaps([L, _box("inner", [0.2, 0.2, 0.2], [0.6, 0.6, 0.6])])
    check_overlaps(hemispherical_dome(5.0, 0.3, 8, 4))
