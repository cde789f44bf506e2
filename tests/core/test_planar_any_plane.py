"""The planar model in any vertical plane: a structure turned about z keeps its planar model.

The turned arch is built by rotating the generator's vertices by hand (numpy, not tce);
its lambda_max is the closed-form-checked one of the arch along x (tests/validation) only
through the relation: a rotation changes no answer.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from tce.core.analysis import Analysis
from tce.core.material import Material
from tce.core.model import find_plane
from tce.structures.arch import semicircular_arch
from tce.structures.assembly import Assembly, Block, Interface
from tce.structures.geometry import Polyhedron


def turned(asm: Assembly, degrees: float) -> Assembly:
    a = math.radians(degrees)
    Q = np.array([[math.cos(a), -math.sin(a), 0.0], [math.sin(a), math.cos(a), 0.0], [0.0, 0.0, 1.0]])
    blocks = [Block(b.name, Polyhedron(b.shape.vertices @ Q.T, b.shape.faces), b.unit_weight, b.support) for b in asm.blocks]
    interfaces = [Interface(i.a, i.b, i.points @ Q.T, Q @ i.normal) for i in asm.interfaces]
    return Assembly(tuple(blocks), tuple(interfaces))


@pytest.mark.parametrize("degrees", [30.0, 137.5, -60.0, 180.0])
def test_turned_arch_keeps_its_planar_model(degrees):
    arch = semicircular_arch(voussoirs=8)
    along_x = Analysis(arch, Material(0.6))
    an = Analysis(turned(arch, degrees), Material(0.6))
    a = math.radians(degrees)
    assert an.plane is not None
    np.testing.assert_allclose(abs(an.plane.m @ [-math.sin(a), math.cos(a), 0.0]), 1.0, atol=1e-12)
    # the lateral load along the span is in the plane; across it, out of it
    assert an.model_kind(alpha=degrees) == "planar" and an.model_kind(alpha=degrees + 90.0) == "spatial"
    for offset in (0.0, 180.0):
        lim = an.limit(alpha=degrees + offset)
        assert lim.model == "planar"
        assert lim.lambda_max == pytest.approx(along_x.limit(alpha=offset).lambda_max, rel=1e-9)


def test_fitted_plane_does_not_make_a_spatial_structure_planar():
    """The fitted candidate is one more plane to check, not an answer: a barrel vault (blocks
    along its length) and a groin vault, turned by 30 degrees, have no symmetry plane."""
    from tce.structures.vault import barrel_vault, groin_vault

    for asm in (barrel_vault(voussoirs=6, courses=2, depth=0.5), groin_vault(voussoirs=4)):
        assert find_plane(turned(asm, 30.0)) is None
