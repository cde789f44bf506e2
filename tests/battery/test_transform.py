"""The battery's scene transformations checked on their own, against closed forms.

The volumes and centroids of the transformed paper's arch are worked out from the closed
forms of ``tests/reference/geometry.py`` (mapped by hand: ``s Q c + d``, ``s^3 V``) and
compared with what tce computes from the transformed vertices (the divergence theorem):
a transform that misplaced a vertex or reversed a face would change both.
"""

from __future__ import annotations

import numpy as np
import pytest

from reference import geometry as rg
from tce.structures.arch import semicircular_arch

from .transform import Similarity, permuted

MAPS = {
    "rotate 90": Similarity.rotation(90.0),
    "rotate 33": Similarity.rotation(33.0),
    "mirror x": Similarity.mirror(0.0),
    "mirror 120": Similarity.mirror(120.0),
    "translate": Similarity.translation([3.0, -2.0, 0.7]),
    "mm, N": Similarity.units(1000.0, 1000.0),
}


@pytest.mark.parametrize("name", MAPS)
def test_volumes_centroids_and_weights_follow_the_map(name):
    t = MAPS[name]
    ref = rg.semicircular_arch()
    asm = t.assembly(semicircular_arch())
    np.testing.assert_allclose(asm.volumes, ref.volume * t.length**3, rtol=1e-12)
    expected = t.length * ref.centroid @ t.Q.T + t.shift
    np.testing.assert_allclose(asm.centroids, expected, atol=1e-12 * t.length)
    np.testing.assert_allclose(asm.weights, ref.volume * ref.unit_weight * t.force, rtol=1e-12)
    asm.validate()  # closed, outward faces
    for i in asm.interfaces:  # each interface normal still points from a into b
        a, b = asm.centroids[i.a], asm.centroids[i.b]
        assert (b - a) @ i.normal > 0


def test_inverse_maps_and_pseudovectors():
    r, m = Similarity.rotation(90.0), Similarity.mirror(0.0)
    assert r.alpha(0.0) == 90.0 and r.alpha(90.0) == 180.0 and m.alpha(0.0) == 180.0 and m.alpha(90.0) == 90.0
    # a rotation about +y (omega = e_y) mirrored in x = 0 is a rotation about -y: omega -> -Q omega
    assert m.settlements({"right": [1, 0, 0, 0, 1, 0]})["right"] == [-1, 0, 0, 0, -1, 0]
    np.testing.assert_array_equal(m.moments([0, 1, 0]), [0, -1, 0])
    np.testing.assert_array_equal(r.settlements({"s": [1, 0, 0, 1, 0, 0]})["s"], [0, 1, 0, 0, 1, 0])


def test_permutation_keeps_every_block_and_contact():
    asm = semicircular_arch(voussoirs=5)
    order = [3, 0, 6, 1, 5, 2, 4]
    ni = len(asm.interfaces)
    p = permuted(asm, order, interface_order=list(range(ni))[::-1], swap=[k % 2 == 0 for k in range(ni)])
    assert p.names == tuple(asm.names[k] for k in order)
    np.testing.assert_array_equal(p.volumes, asm.volumes[order])
    before = {frozenset((asm.names[i.a], asm.names[i.b])): i for i in asm.interfaces}
    for i in p.interfaces:
        j = before[frozenset((p.names[i.a], p.names[i.b]))]
        sign = 1.0 if p.names[i.a] == asm.names[j.a] else -1.0
        np.testing.assert_allclose(i.normal, sign * j.normal, atol=1e-15)  # renormalised
        assert {tuple(x) for x in i.points} == {tuple(x) for x in j.points}
