"""Per-interface contact laws (:attr:`tce.core.material.Material.interfaces`): what a material
gives each contact, what it refuses, its words, and the law on both models."""

from __future__ import annotations

import numpy as np
import pytest

from tce.core.analysis import Analysis
from tce.core.material import Material
from tce.structures.arch import RING, semicircular_arch


def test_contact_law_is_the_materials_scalars_without_laws_of_kinds():
    m = Material(friction=0.6, cohesion=2.0, tensile_strength=1.0, interfaces={RING: Material(friction=0.3)})
    assert m.contact_law(np.array(["", ""], dtype=object)) == {"friction": 0.6, **m.strengths}


def test_contact_law_per_contact():
    m = Material(compressive_strength=500.0,
                 interfaces={RING: Material(friction=0.3, cohesion=2.0), "glued": Material(bonded=True)})
    law = m.contact_law(np.array(["", RING, "glued", "other"], dtype=object))
    np.testing.assert_array_equal(law["friction"], [np.nan, 0.3, np.nan, np.nan])
    np.testing.assert_array_equal(law["cohesion"], [0.0, 2.0, 0.0, 0.0])
    np.testing.assert_array_equal(law["tensile_strength"], [0.0, 0.0, np.inf, 0.0])
    np.testing.assert_array_equal(law["compressive_strength"], [500.0, np.inf, np.inf, 500.0])
    assert m.law(RING).friction == 0.3 and m.law("other") is m


@pytest.mark.parametrize("call, word", [
    (lambda: Material(bonded=True, friction=0.5), "bonded"),
    (lambda: Material(interfaces={RING: Material(normal_stiffness=1e6)}), "stiffness"),
    (lambda: Material(friction=0.5, flow="non-associative", interfaces={RING: Material(friction=0.3)}), "non-associative"),
    (lambda: Material(interfaces={"": Material()}), "kinds"),
])
def test_refused(call, word):
    with pytest.raises((ValueError, TypeError), match=word):
        call()


def test_words_list_every_law():
    m = Material(friction=0.6, interfaces={RING: Material(friction=0.3), "glued": Material(bonded=True)})
    words = m.describe()
    assert words.startswith("Coulomb friction mu = 0.6")
    assert '"ring" interfaces: Coulomb friction mu = 0.3' in words
    assert '"glued" interfaces: bonded' in words


@pytest.mark.parametrize("material", [
    Material(friction=0.6, interfaces={RING: Material(friction=0.3, cohesion=2.0, tensile_strength=1.0)}),
    Material(interfaces={RING: Material(friction=0.4)}),
    Material(friction=0.7, interfaces={RING: Material(bonded=True)}),
])
def test_interface_laws_planar_equals_spatial(material):
    """The cone rows per contact on both models (the spatial one's cones mix friction
    coefficients, unlimited friction and bonded contacts)."""
    asm = semicircular_arch(1.0, 0.3, 0.25, 6, rings=2, stagger=True)
    planar = Analysis(asm, material).limit(0.0)
    spatial = Analysis(asm, material, model="spatial").limit(0.0)
    assert planar.model == "planar" and spatial.model == "spatial"
    assert planar.status == spatial.status == "optimal"
    assert spatial.lambda_max == pytest.approx(planar.lambda_max, rel=1e-7)
    assert planar.admissibility < 1e-6 and spatial.admissibility < 1e-6
