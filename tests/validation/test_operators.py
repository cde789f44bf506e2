"""tce's operators equal the independent references of ``tests/reference``.

On the paper's arch, a dome, the running-bond wall of ``studies/data/wall.json`` and random
stacks of boxes (random offsets, unit weights, supports, interface orientations, stiffness
multipliers and rotations): block weights and centroids, interface frames, ``Model.A_eq``,
``B_sup``, ``b_dead``, ``b_lateral(alpha)``, ``compliance(kn, ks)`` of the spatial model, and
``cone_violation``. The planar model is checked through the reference 3D operators: the forces
it lifts (``Model.lift``) must give the same wrenches, loads and energy.
"""

from __future__ import annotations

import numpy as np
import pytest
from scenes import SCENES, assert_same_blocks

from reference import geometry as rg
from reference import operators as ro
from tce.core.conic import cone_violation
from tce.core.model import build_model

ALPHAS = (0.0, 90.0, 30.0, 180.0, 270.0, -45.0)


def _reference(name: str):
    asm, blocks = SCENES[name]()
    return asm, blocks, ro.build(blocks, ro.contacts_of(asm))


@pytest.fixture(scope="module", params=sorted(SCENES))
def scene(request):
    asm, blocks, ops = _reference(request.param)
    return request.param, asm, blocks, ops


def test_block_weights_and_centroids(scene):
    _, asm, blocks, _ = scene
    assert_same_blocks(asm, blocks)


def test_interface_frames(scene):
    _, asm, _, _ = scene
    for itf in asm.interfaces:
        np.testing.assert_allclose(itf.frame, rg.frame(itf.normal), atol=1e-13)
        # right-handed and orthonormal
        assert np.linalg.det(itf.frame) == pytest.approx(1.0, abs=1e-13)


def test_equilibrium_and_support_wrenches(scene):
    _, asm, _, ops = scene
    m = build_model(asm, "spatial")
    L, W = asm.size, asm.total_weight
    assert m.A_eq.shape == ops.A_eq.shape and m.B_sup.shape == ops.B_sup.shape
    np.testing.assert_allclose(m.A_eq.toarray(), ops.A_eq, atol=1e-13 * L)
    np.testing.assert_allclose(m.B_sup.toarray(), ops.B_sup, atol=1e-13 * L)
    np.testing.assert_allclose(m.vertex_points, ops.vertices, atol=1e-13 * L)
    np.testing.assert_allclose(m.b_dead, ops.b_dead, atol=1e-12 * W)


@pytest.mark.parametrize("alpha", ALPHAS)
def test_lateral_load(scene, alpha):
    _, asm, _, ops = scene
    m = build_model(asm, "spatial")
    np.testing.assert_allclose(m.b_lateral(alpha), ops.b_lateral(alpha), atol=1e-12 * asm.total_weight)


def test_compliance_normal_and_shear(scene):
    _, asm, _, ops = scene
    m = build_model(asm, "spatial")
    for kn, ks in ((1e6, 4e5), (3e4, 9e7)):
        np.testing.assert_allclose(m.compliance(kn, ks), ops.compliance(kn, ks), rtol=1e-12)


@pytest.mark.parametrize("friction", [None, 0.0, 0.4, 2.0])
def test_cone_violation(scene, friction):
    _, asm, _, _ = scene
    m = build_model(asm, "spatial")
    rng = np.random.default_rng(7)
    for _ in range(5):
        f = rng.normal(size=(m.n_contacts, 3)) + np.array([0.8, 0.0, 0.0])
        assert cone_violation(m, friction, f) == pytest.approx(ro.cone_violation(f, friction), rel=1e-14, abs=1e-300)
    inside = np.column_stack([np.ones(m.n_contacts), np.zeros((m.n_contacts, 2))])
    assert cone_violation(m, friction, inside) == 0.0


# ------------------------------------------------------------------ the planar model
PLANAR = ("arch", "wall")


@pytest.fixture(scope="module", params=PLANAR)
def planar(request):
    asm, blocks, ops = _reference(request.param)
    m = build_model(asm, "planar")
    assert m.kind == "planar"
    return asm, ops, m


def test_planar_operators_through_lifted_forces(planar):
    asm, ops, m = planar
    inplane, outplane = ro.in_plane_rows(m.plane.m)
    nf = len(asm.free_indices)
    rng = np.random.default_rng(3)
    F2 = rng.normal(size=(m.n_vars, 4))
    F3 = m.lift.toarray() @ F2
    wrench = ops.A_eq @ F3  # (6 nf, 4)
    per_block = wrench.reshape(nf, 6, -1)
    L = asm.size
    np.testing.assert_allclose(np.einsum("ij,bjk->bik", inplane, per_block).reshape(3 * nf, -1), m.A_eq @ F2, atol=1e-12 * L)
    np.testing.assert_allclose(np.einsum("ij,bjk->bik", outplane, per_block), 0.0, atol=1e-12 * L)
    np.testing.assert_allclose(m.B_sup @ F2, ops.B_sup @ F3, atol=1e-12 * L)


def test_planar_loads(planar):
    asm, ops, m = planar
    inplane, _ = ro.in_plane_rows(m.plane.m)
    nf = len(asm.free_indices)
    project = lambda v: np.einsum("ij,bj->bi", inplane, v.reshape(nf, 6)).ravel()  # noqa: E731
    W = asm.total_weight
    np.testing.assert_allclose(m.b_dead, project(ops.b_dead), atol=1e-12 * W)
    for alpha in (0.0, 180.0):
        np.testing.assert_allclose(m.b_lateral(alpha), project(ops.b_lateral(alpha)), atol=1e-12 * W)


def test_planar_compliance_is_that_of_the_lifted_vertices(planar):
    """Springs in parallel: the energy of a planar force equals that of its lifted vertex forces."""
    _, ops, m = planar
    L = m.lift.toarray()
    for kn, ks in ((1e6, 4e5), (3e4, 9e7)):
        energy = L.T @ np.diag(ops.compliance(kn, ks)) @ L
        np.testing.assert_allclose(energy, np.diag(m.compliance(kn, ks)), rtol=1e-12, atol=1e-12 * energy.max())


@pytest.mark.parametrize("friction", [None, 0.0, 0.5])
def test_planar_cone_violation(planar, friction):
    _, _, m = planar
    rng = np.random.default_rng(11)
    f = rng.normal(size=(m.n_contacts, 2)) + np.array([0.5, 0.0])
    assert cone_violation(m, friction, f) == pytest.approx(ro.cone_violation(f, friction), rel=1e-14, abs=1e-300)
    # the lift maps the planar contact law onto the spatial one: no vertex of an admissible
    # planar state leaves its cone
    mu = 0.5 if friction is None else friction
    ok = np.column_stack([np.abs(f[:, 0]) + 1.0, mu * rng.uniform(-1, 1, m.n_contacts) * (np.abs(f[:, 0]) + 1.0)])
    lifted = (m.lift @ ok.ravel()).reshape(-1, 3)
    assert ro.cone_violation(lifted, mu) <= 1e-14 * np.abs(ok).max()
