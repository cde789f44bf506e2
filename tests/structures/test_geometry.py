"""Exact volumes and centroids, block checks, the arch generator and the model operators."""

import numpy as np
import pytest

from tce.structures.arch import semicircular_arch
from tce.structures.assembly import AssemblyError
from tce.structures.geometry import GeometryError, Polyhedron, box, prism, tributary_areas
from tce.core.model import build_model


def test_box_volume_and_centroid():
    p = box([0, 0, 0], [2, 3, 4])
    assert p.volume == pytest.approx(24.0, rel=1e-14)
    np.testing.assert_allclose(p.centroid, [1, 1.5, 2], rtol=1e-14)
    p.validate()


def test_non_convex_prism_exact():
    # an L-shaped section (area 3, centroid (5/6, 5/6)) extruded by 2 along z
    L = np.array([[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]], float)
    p = prism(np.column_stack([L, np.zeros(6)]), np.column_stack([L, np.full(6, 2.0)]))
    p.validate()
    assert p.volume == pytest.approx(6.0, rel=1e-14)
    np.testing.assert_allclose(p.centroid, [5 / 6, 5 / 6, 1.0], rtol=1e-13)


def test_tributary_areas_of_rectangle():
    r = np.array([[0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0]], float)
    np.testing.assert_allclose(tributary_areas(r), 0.5)


@pytest.mark.parametrize(
    "mutate, message",
    [
        (lambda p: Polyhedron(p.vertices, p.faces[:-1]), "not closed"),
        (lambda p: Polyhedron(p.vertices, [f[::-1] for f in p.faces]), "inverted"),
        (lambda p: Polyhedron(p.vertices + np.r_[[[0, 0, 0]] * 6, [[0, 0, 0.1]], [[0, 0, 0]]], p.faces), "not planar"),
    ],
)
def test_block_checks_name_the_problem(mutate, message):
    with pytest.raises(GeometryError, match=message):
        mutate(box([0, 0, 0], [1, 1, 1])).validate(name="block 'b1'")


def test_arch_generator_defaults(arch):
    assert arch.names[0] == "left" and arch.names[-1] == "right"
    assert len(arch.free_indices) == 14 and arch.support_names == ("left", "right")
    left = arch.blocks[0]
    np.testing.assert_allclose(left.shape.vertices.min(axis=0), [-1.2, -0.125, -0.2])
    np.testing.assert_allclose(left.shape.vertices.max(axis=0), [-1.0, 0.125, 0.0])
    # chord voussoirs: 14 equal trapezoidal prisms
    vol = [arch.blocks[i].volume for i in arch.free_indices]
    theta = np.pi / 14
    expect = 0.5 * (1.2**2 - 1.0**2) * np.sin(theta) * 0.25
    np.testing.assert_allclose(vol, expect, rtol=1e-12)
    for itf in arch.interfaces:  # normals point from A into B
        assert itf.normal @ (arch.centroids[itf.b] - arch.centroids[itf.a]) > 0


@pytest.mark.parametrize("bad", [dict(thickness=-0.2), dict(inner_radius=float("nan")), dict(voussoirs=0), dict(depth="a")])
def test_arch_rejects_bad_parameters(bad):
    with pytest.raises(ValueError, match=next(iter(bad))):
        semicircular_arch(**bad)


def test_assembly_checks():
    a = semicircular_arch()
    with pytest.raises(AssemblyError, match="no support"):
        a.with_supports([]).validate()
    with pytest.raises(AssemblyError, match="touch nothing"):
        a.with_interfaces(a.interfaces[1:]).validate()
    with pytest.raises(AssemblyError, match="unknown support"):
        a.with_supports(["nowhere"])


def test_operators_shapes_and_rigid_motion(arch):
    m = build_model(arch, "spatial")
    assert m.A_eq.shape == (6 * 14, 3 * 60)
    assert m.B_sup.shape == (12, 180)
    # the dead load sums to the weight of the voussoirs
    assert -m.b_dead.reshape(-1, 6)[:, 2].sum() == pytest.approx(arch.total_weight)
    p = build_model(arch)
    assert p.kind == "planar" and p.A_eq.shape == (3 * 14, 2 * 30)
    # lifting planar forces gives 3D vertex forces whose equilibrium matches
    rng = np.random.default_rng(0)
    f2 = rng.normal(size=p.n_vars)
    f3 = p.lift @ f2
    r2 = p.B_sup @ f2
    r3 = m.B_sup @ f3
    np.testing.assert_allclose(r2, r3, atol=1e-12)
    np.testing.assert_allclose(np.abs(m.A_eq @ f3)[[1, 3, 5]], 0, atol=1e-12)  # out-of-plane rows of block 1
