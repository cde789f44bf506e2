"""Hemispherical dome generator: exact planar facets, closed-form volume and centroid, settlements."""

from __future__ import annotations

import numpy as np
import pytest

from reference import geometry as rg
from tce.structures.dome import hemispherical_dome, radial_settlement, shell_centroid_height, shell_volume
from tce.core.material import Material
from tce.core.model import build_model
from tce.core.solve import TCESolver

R, T = 5.0, 0.3


def _volume_centroid(asm):
    free = list(asm.free_indices)
    v = np.array([asm.blocks[i].volume for i in free])
    z = asm.centroids[free, 2]
    return v.sum(), (v * z).sum() / v.sum()


def _errors(sectors, courses):
    asm = hemispherical_dome(R, T, sectors, courses)
    vol, zc = _volume_centroid(asm)
    return vol / shell_volume(R, T) - 1.0, zc / shell_centroid_height(R, T) - 1.0


def test_shell_closed_forms_are_the_limit_of_the_blocks():
    """shell_volume and shell_centroid_height are the limits of the closed-form voussoirs
    (tests/reference) as the discretisation is refined: the errors (~1e-3) fall as h^2, so
    Richardson's extrapolation of two fine discretisations lands on them, up to the O(h^4)
    remainder (~1e-6)."""
    def totals(s, c):
        ref = rg.hemispherical_dome(R, T, s, c)
        v, z = ref.volume[~ref.support], ref.centroid[~ref.support, 2]
        return v.sum(), (v * z).sum() / v.sum()

    (v1, z1), (v2, z2) = totals(56, 22), totals(112, 44)
    assert (4 * v2 - v1) / 3 == pytest.approx(shell_volume(R, T), rel=1e-5)
    assert (4 * z2 - z1) / 3 == pytest.approx(shell_centroid_height(R, T), rel=1e-5)
    assert abs(v2 / shell_volume(R, T) - 1.0) < 1e-3


def test_errors_shrink_as_discretisation_refines():
    errs = [_errors(s, c) for s, c in [(8, 4), (16, 8), (32, 16)]]
    ev = [abs(e[0]) for e in errs]
    ez = [abs(e[1]) for e in errs]
    # inscribed facets: the volume is always too small, and second-order convergent
    assert all(e[0] < 0 for e in errs)
    assert ev[0] > ev[1] > ev[2] and ez[0] > ez[1] > ez[2]
    assert 3.0 < ev[0] / ev[1] < 5.0 and 3.0 < ev[1] / ev[2] < 5.0


def test_oculus_volume_converges_to_open_shell():
    e = [
        abs(sum(b.volume for b in hemispherical_dome(R, T, s, c, oculus=30).blocks if not b.support)
            / shell_volume(R, T, oculus=30) - 1.0)
        for s, c in [(8, 3), (16, 6), (32, 12)]
    ]
    assert e[0] > e[1] > e[2] and e[2] < 1e-2


@pytest.mark.parametrize("oculus", [0.0, 20.0])
def test_blocks_are_exactly_planar_closed_and_named(oculus):
    s, c = 8, 6
    asm = hemispherical_dome(R, T, s, c, oculus=oculus).validate()
    for b in asm.blocks:
        b.shape.validate(b.name, tol=1e-12)  # every face planar to round-off
    assert asm.support_names == tuple(f"s{j:02d}" for j in range(1, s + 1))
    assert asm.names[s:] == tuple(f"c{k:02d}s{j:02d}" for k in range(1, c + 1) for j in range(1, s + 1))
    crown = [asm.blocks[asm.index[f"c{c:02d}s{j:02d}"]].shape for j in range(1, s + 1)]
    if oculus == 0.0:  # wedges meeting on the axis: triangular prisms
        assert all(len(p.vertices) == 6 and len(p.faces) == 5 for p in crown)
        assert all(np.sum(np.linalg.norm(p.vertices[:, :2], axis=1) < 1e-12) == 2 for p in crown)
    else:
        assert all(len(p.vertices) == 8 for p in crown)
        assert min(np.linalg.norm(p.vertices[:, :2], axis=1).min() for p in crown) > 1.0
    # base ring in z = 0, supports below it
    for j in range(s):
        assert asm.blocks[j].shape.vertices[:, 2].max() == pytest.approx(0.0, abs=1e-15)
        assert asm.blocks[j].shape.vertices[:, 2].min() == pytest.approx(-T)
    # vertices on the two spheres
    free_pts = np.vstack([asm.blocks[i].shape.vertices for i in asm.free_indices])
    r = np.linalg.norm(free_pts, axis=1)
    assert np.all(np.isclose(r, R - T / 2) | np.isclose(r, R + T / 2))


def test_interfaces_point_from_a_into_b():
    s, c = 8, 6
    asm = hemispherical_dome(R, T, s, c)
    assert len(asm.interfaces) == s + s * (c - 1) + s * c
    for itf in asm.interfaces:
        assert itf.a < itf.b
        assert itf.normal @ (asm.blocks[itf.b].centroid - asm.blocks[itf.a].centroid) > 0
        # interface points lie on both blocks' faces: within the blocks' vertex sets
        va, vb = asm.blocks[itf.a].shape.vertices, asm.blocks[itf.b].shape.vertices
        for p in itf.points:
            assert np.linalg.norm(va - p, axis=1).min() < 1e-12
            assert np.linalg.norm(vb - p, axis=1).min() < 1e-12
    pairs = {(asm.names[i.a], asm.names[i.b]) for i in asm.interfaces}
    assert ("s01", "c01s01") in pairs and ("c01s01", "c02s01") in pairs
    assert ("c01s01", "c01s02") in pairs and ("c01s01", "c01s08") in pairs  # wrap-around
    assert not any(a.startswith("s") and b.startswith("s") for a, b in pairs)


def test_meta_records_parameters():
    asm = hemispherical_dome(4.0, 0.4, 6, 3, oculus=10, unit_weight=18.0, support_height=1.0)
    m = asm.meta
    assert m["generator"] == "hemispherical_dome"
    assert (m["radius"], m["thickness"], m["sectors"], m["courses"], m["oculus"]) == (4.0, 0.4, 6, 3, 10.0)
    assert (m["inner_radius"], m["outer_radius"], m["unit_weight"], m["support_height"]) == (3.8, 4.2, 18.0, 1.0)


@pytest.mark.parametrize(
    "kwargs, word",
    [
        (dict(radius=0.0), "radius"),
        (dict(thickness=-1.0), "thickness"),
        (dict(radius=1.0, thickness=2.0), "thickness"),
        (dict(sectors=2), "sectors"),
        (dict(courses=1.5), "courses"),
        (dict(oculus=90.0), "oculus"),
        (dict(oculus=float("nan")), "oculus"),
        (dict(unit_weight=0.0), "unit_weight"),
        (dict(support_height=0.0), "support_height"),
    ],
)
def test_bad_parameters_are_named(kwargs, word):
    with pytest.raises(ValueError, match=word):
        hemispherical_dome(**kwargs)


def test_radial_settlement_moves_each_support_along_its_radius():
    asm = hemispherical_dome(R, T, 8, 3)
    u = radial_settlement(asm, 0.01)
    assert set(u) == set(asm.support_names)
    for name, vec in u.items():
        c = asm.blocks[asm.index[name]].centroid
        radial = np.array([c[0], c[1], 0.0]) / np.linalg.norm(c[:2])
        assert np.allclose(vec[:3], 0.01 * radial) and vec[3:] == [0.0, 0.0, 0.0]
    inward = radial_settlement(asm, -0.02)
    assert np.allclose(inward["s03"], -2.0 * np.asarray(u["s03"]))
    with pytest.raises(ValueError, match="magnitude"):
        radial_settlement(asm, float("inf"))


def _thrusts(asm, result):
    W = result.support_wrenches
    c = asm.centroids[list(asm.support_indices)]
    radial = c[:, :2] / np.linalg.norm(c[:, :2], axis=1)[:, None]
    return -(W[:, :2] * radial).sum(axis=1), W[:, 2]  # outward thrust of the dome, vertical reaction


def test_dome_under_radial_settlement_has_equal_thrusts():
    asm = hemispherical_dome(5.0, 0.5, 8, 6).validate()
    solver = TCESolver(build_model(asm, "spatial"), Material(friction=0.8))
    H = {}
    for mag in (1e-3, -1e-3):
        res = solver.solve(0.0, settlements=radial_settlement(asm, mag))
        assert res.status == "optimal"
        h, v = _thrusts(asm, res)
        assert np.allclose(h, h.mean(), rtol=1e-6, atol=0)
        assert np.allclose(v, asm.total_weight / 8, rtol=1e-6)
        assert np.abs(res.support_wrenches[:, :2]).sum(axis=1).min() > 0
        H[mag] = h.mean()
    # outward spreading gives the minimum thrust, inward the maximum (docs/conventions.md)
    assert 0 < H[1e-3] < H[-1e-3]
