"""Pointed and segmental arches, arches on piers."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tce.structures.arch import pointed_arch, segmental_arch, semicircular_arch, semicircular_arch_on_piers
from tce.core.material import Material
from tce.core.model import build_model
from tce.core.solve import TCESolver


def _ring_volume(asm):
    return sum(b.volume for b in asm.blocks if not b.support)


def _pointed_ring_area(span, e, t):
    """Exact area of a two-centred arch ring (both halves), centres at x = -+e on z = 0."""
    ri = span / 2 + e
    ro = ri + t

    def F(r):  # integral of r * arccos(e / r) dr
        return r * r / 2 * math.acos(e / r) - e / 2 * math.sqrt(r * r - e * e)

    return 2 * (F(ro) - F(ri))


def test_special_cases_reduce_to_the_semicircular_arch():
    ref = semicircular_arch(1.0, 0.2, 0.25, 14)
    for other in (
        pointed_arch(2.0, thickness=0.2, depth=0.25, voussoirs=14, centre_offset=0.0),
        pointed_arch(2.0, rise=1.0, thickness=0.2, depth=0.25, voussoirs=14),
        segmental_arch(2.0, 1.0, thickness=0.2, depth=0.25, voussoirs=14),
    ):
        assert other.names == ref.names
        assert np.allclose(other.centroids, ref.centroids, atol=1e-12)
        assert np.allclose(other.weights, ref.weights, rtol=1e-12)


@pytest.mark.parametrize("e", [0.3, 1.0])
def test_pointed_ring_volume_converges_to_closed_form(e):
    span, t, d = 2.0, 0.2, 0.25
    exact = _pointed_ring_area(span, e, t) * d
    errs = [abs(_ring_volume(pointed_arch(span, thickness=t, depth=d, voussoirs=n, centre_offset=e)) / exact - 1)
            for n in (8, 16, 32, 64)]
    assert errs[0] > errs[1] > errs[2] > errs[3]
    assert errs[-1] < 1e-3


def test_pointed_arch_geometry_and_meta():
    asm = pointed_arch(3.0, rise=2.0, thickness=0.3, depth=0.4, voussoirs=10, unit_weight=18.0)
    m = asm.meta
    assert m["generator"] == "pointed_arch"
    e = (2.0**2 - 1.5**2) / 3.0
    assert m["centre_offset"] == pytest.approx(e) and m["radius"] == pytest.approx(1.5 + e)
    assert m["rise"] == pytest.approx(2.0)
    assert (m["span"], m["thickness"], m["depth"], m["voussoirs"], m["unit_weight"]) == (3.0, 0.3, 0.4, 10, 18.0)
    # crown joint is vertical (even number of voussoirs) and starts at the intrados apex
    crown = asm.interfaces[5]
    assert np.allclose(crown.normal, [1.0, 0.0, 0.0])
    assert crown.points[:, 2].min() == pytest.approx(2.0)
    # springings at -+span/2 on z = 0
    pts = np.vstack([b.shape.vertices for b in asm.blocks if not b.support])
    assert pts[:, 0].min() == pytest.approx(-1.8) and pts[:, 0].max() == pytest.approx(1.8)
    assert pts[:, 2].min() == pytest.approx(0.0)
    # equilateral by default
    assert pointed_arch(2.0).meta["centre_offset"] == pytest.approx(1.0)


def test_pointed_arch_odd_voussoirs_has_a_keystone():
    asm = pointed_arch(2.0, voussoirs=9).validate()
    key = asm.blocks[asm.index["v05"]]
    assert abs(key.centroid[0]) < 1e-12
    for b in asm.blocks:
        b.shape.validate(b.name, tol=1e-12)


def test_segmental_arch_geometry_and_meta():
    span, rise, t, d = 4.0, 1.0, 0.3, 0.5
    asm = segmental_arch(span, rise, t, d, voussoirs=24).validate()
    R = (span**2 / 4 + rise**2) / (2 * rise)
    half = math.asin(span / 2 / R)
    exact = half * ((R + t) ** 2 - R**2) * d
    # 24 chord-faced voussoirs: each a ring sector of opening 2 half / 24 with chord faces
    chords = 24 * ((R + t) ** 2 - R**2) * math.sin(2 * half / 24) / 2 * d
    assert _ring_volume(asm) == pytest.approx(chords, rel=1e-12)
    assert _ring_volume(asm) < exact  # inscribed in the circular ring
    assert asm.meta["generator"] == "segmental_arch" and asm.meta["radius"] == pytest.approx(R)
    # inclined springing joints: the skewback supports carry them
    left = asm.interfaces[0]
    assert np.allclose(left.normal, [math.cos(half), 0, math.sin(half)])  # up the arch, into v01
    assert asm.blocks[0].shape.vertices[:, 2].max() == pytest.approx(t * math.cos(half))  # skewback top


def test_piers():
    for asm in (
        segmental_arch(pier_height=2.0),
        pointed_arch(pier_height=2.0),
        semicircular_arch_on_piers(pier_height=2.0),
    ):
        asm.validate()
        for k in asm.support_indices:
            assert asm.blocks[k].shape.vertices[:, 2].min() == pytest.approx(-2.0)
        assert asm.meta["pier_height"] == 2.0
    assert semicircular_arch_on_piers().meta["generator"] == "semicircular_arch_on_piers"


@pytest.mark.parametrize(
    "call, word",
    [
        (lambda: pointed_arch(2.0, rise=0.9), "rise"),
        (lambda: pointed_arch(2.0, rise=1.5, centre_offset=0.2), "either"),
        (lambda: pointed_arch(2.0, centre_offset=-0.1), "centre_offset"),
        (lambda: pointed_arch(2.0, voussoirs=1), "voussoirs"),
        (lambda: pointed_arch(-2.0), "span"),
        (lambda: segmental_arch(2.0, 1.5), "rise"),
        (lambda: segmental_arch(2.0, 0.0), "rise"),
        (lambda: segmental_arch(2.0, 0.5, thickness=0), "thickness"),
        (lambda: segmental_arch(2.0, 0.5, voussoirs=2.5), "voussoirs"),
        (lambda: segmental_arch(pier_height=-1), "support_height"),
        (lambda: semicircular_arch_on_piers(pier_height=0), "pier_height"),
    ],
)
def test_bad_parameters_are_named(call, word):
    with pytest.raises(ValueError, match=word):
        call()


def test_new_shapes_stand_and_planar_equals_spatial():
    for asm in (pointed_arch(2.0, voussoirs=10), segmental_arch(2.0, 0.6, voussoirs=10)):
        res = {}
        for kind in ("planar", "spatial"):
            r = TCESolver(build_model(asm, kind), Material(friction=0.8)).solve(
                0.0, settlements={"left": [-1e-3, 0, 0, 0, 0, 0], "right": [1e-3, 0, 0, 0, 0, 0]}
            )
            assert r.status == "optimal"
            res[kind] = r.support_wrenches
        assert np.allclose(res["planar"], res["spatial"], rtol=1e-6, atol=1e-7)
