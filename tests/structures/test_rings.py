"""Multi-ring arches (:func:`tce.structures.arch.ring_arch`): blocks, volumes against closed
forms, the faces between rings and their kind, the half-brick stagger, errors."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from tce.structures.arch import RING, pointed_arch, segmental_arch, semicircular_arch, semicircular_arch_on_piers
from tce.structures.bridge import arch_bridge


def _sector_area(r: float, dtheta: float) -> float:
    """Area of the triangle between the centre and a chord of radius ``r`` over ``dtheta``."""
    return 0.5 * r * r * math.sin(dtheta)


@pytest.mark.parametrize("rings", [2, 3, [0.05, 0.1, 0.15]])
def test_aligned_rings_split_each_voussoir_at_the_ring_radii(rings):
    n, ri, t, depth = 6, 1.0, 0.3, 0.25
    asm = semicircular_arch(ri, t, depth, n, rings=rings).validate()
    thick = [t / rings] * rings if isinstance(rings, int) else rings
    radii = ri + np.concatenate([[0.0], np.cumsum(thick)])
    R = len(thick)
    names = ["left"] + [f"r{r + 1}v{k + 1:02d}" for r in range(R) for k in range(n)] + ["right"]
    assert list(asm.names) == names
    dtheta = math.pi / n
    for r in range(R):
        area = _sector_area(radii[r + 1], dtheta) - _sector_area(radii[r], dtheta)
        vols = asm.volumes[1 + r * n : 1 + (r + 1) * n]
        np.testing.assert_allclose(vols, area * depth, rtol=1e-12)
    one = semicircular_arch(ri, t, depth, n)
    assert asm.total_weight == pytest.approx(one.total_weight, rel=1e-12)
    kinds = [i.kind for i in asm.interfaces]
    assert kinds.count(RING) == (R - 1) * n
    assert len(asm.interfaces) == R * (n + 1) + (R - 1) * n
    assert asm.meta["rings"] == rings and asm.meta["stagger"] is False


def test_staggered_rings_follow_the_half_brick_rule():
    """Ring 2 is cut half a voussoir further: n + 1 voussoirs, half ones at the springings; the
    faces between rings run through the joints of both (2 n of them)."""
    n, ri, t, depth = 6, 1.0, 0.3, 0.25
    asm = semicircular_arch(ri, t, depth, n, rings=2, stagger=True).validate()
    assert [b for b in asm.names if b.startswith("r2")] == [f"r2v{k + 1:02d}" for k in range(n + 1)]
    d, rm, re = math.pi / n, ri + t / 2, ri + t
    ring1 = asm.volumes[1 : 1 + n] / depth
    ring2 = asm.volumes[1 + n : 2 + 2 * n] / depth
    # ring 1: inner chord over d, outer polyline of two chords over d / 2
    np.testing.assert_allclose(ring1, 2 * _sector_area(rm, d / 2) - _sector_area(ri, d), rtol=1e-12)
    # ring 2: half voussoirs at the springings, whole ones between
    half = _sector_area(re, d / 2) - _sector_area(rm, d / 2)
    whole = _sector_area(re, d) - 2 * _sector_area(rm, d / 2)
    np.testing.assert_allclose(ring2, [half] + [whole] * (n - 1) + [half], rtol=1e-12)
    ring = [i for i in asm.interfaces if i.kind == RING]
    assert len(ring) == 2 * n
    for i in ring:  # from the inner ring into the outer one: outwards
        assert asm.names[i.a].startswith("r1") and asm.names[i.b].startswith("r2")
        assert i.normal @ i.centroid > 0


@pytest.mark.parametrize("build", [
    lambda: segmental_arch(rings=3, stagger=True),
    lambda: pointed_arch(voussoirs=7, rings=[0.08, 0.12], stagger=True),
    lambda: pointed_arch(voussoirs=8, rings=2),
    lambda: semicircular_arch_on_piers(voussoirs=6, rings=2, stagger=True),
])
def test_other_arches_take_rings(build):
    asm = build().validate()
    assert RING in asm.interface_table.kind


@pytest.mark.parametrize("call, word", [
    (lambda: semicircular_arch(thickness=0.3, rings=[0.1, 0.1]), "sum to"),
    (lambda: semicircular_arch(rings=2, joints="vertical"), "radial"),
    (lambda: semicircular_arch(rings=0), "rings"),
    (lambda: semicircular_arch(thickness=0.3, rings=[0.3, -0.0]), "rings[1]"),
])
def test_bad_rings_are_named(call, word):
    with pytest.raises(ValueError, match=re.escape(word)):
        call()


@pytest.mark.parametrize("spans, piers", [(1, "free"), (2, "free"), (2, "fixed")])
def test_bridge_spans_take_rings(spans, piers):
    """Every span's rings between its abutment and pier; aligned rings have the single ring's
    weight and one face between rings per voussoir and boundary."""
    one = arch_bridge(spans=spans, voussoirs=6, piers=piers)
    asm = arch_bridge(spans=spans, voussoirs=6, piers=piers, rings=3).validate()
    assert asm.total_weight == pytest.approx(one.total_weight, rel=1e-12)
    assert [i.kind for i in asm.interfaces].count(RING) == spans * 2 * 6
    assert [n for n in asm.names if n.startswith("s1r2")] == [f"s1r2v{k + 1:02d}" for k in range(6)]
    assert set(asm.support_names) == set(one.support_names)
    staggered = arch_bridge(spans=spans, voussoirs=6, piers=piers, rings=2, stagger=True).validate()
    assert [i.kind for i in staggered.interfaces].count(RING) == spans * 12
