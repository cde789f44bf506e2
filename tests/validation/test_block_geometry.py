"""Generated blocks against closed-form volumes, centroids and weights (tests/reference/geometry.py).

Each voussoir of the semicircular arch is the prism of a chord-faced ring sector; each voussoir
of the hemispherical dome is the difference of two pyramids with their apex at the centre of the
spheres (all its side faces lie in planes through it), over its extrados and intrados faces:
``V = (h_o A_o - h_i A_i) / 3``. Weights are checked against the unit weight the generator was
given, course by course, so a course built with another unit weight shows.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from reference import geometry as rg
from scenes import assert_same_blocks
from tce.core.model import build_model
from tce.structures.arch import semicircular_arch
from tce.structures.dome import hemispherical_dome


@pytest.mark.parametrize(
    "inner_radius, thickness, depth, voussoirs", [(1.0, 0.2, 0.25, 14), (3.0, 0.45, 1.0, 9), (0.5, 0.1, 0.2, 40)]
)
def test_arch_voussoirs(inner_radius, thickness, depth, voussoirs):
    uw = 18.5
    asm = semicircular_arch(inner_radius, thickness, depth, voussoirs, unit_weight=uw)
    assert_same_blocks(asm, rg.semicircular_arch(inner_radius, thickness, depth, voussoirs, unit_weight=uw))
    ro = inner_radius + thickness
    ring = (ro**2 - inner_radius**2) * math.sin(math.pi / voussoirs) / 2 * depth * voussoirs
    assert asm.total_weight == pytest.approx(uw * ring, rel=1e-12)


DOMES = [(5.0, 0.5, 8, 4), (5.0, 0.3, 16, 8), (2.0, 0.3, 5, 3), (10.0, 0.8, 12, 6)]


@pytest.mark.parametrize("radius, thickness, sectors, courses", DOMES)
def test_dome_voussoirs(radius, thickness, sectors, courses):
    uw = 21.0
    asm = hemispherical_dome(radius, thickness, sectors, courses, unit_weight=uw)
    assert_same_blocks(asm, rg.hemispherical_dome(radius, thickness, sectors, courses, unit_weight=uw), rtol=1e-11)


@pytest.mark.parametrize("radius, thickness, sectors, courses", DOMES)
def test_dome_weight_course_by_course(radius, thickness, sectors, courses):
    """Every course (the crown wedges included) weighs the given unit weight times its
    closed-form volume, and the dead load is the total."""
    uw = 21.0
    asm = hemispherical_dome(radius, thickness, sectors, courses, unit_weight=uw)
    ri, ro = radius - thickness / 2, radius + thickness / 2
    th = np.linspace(math.pi / 2, 0.0, courses + 1)
    weights = asm.weights[sectors:].reshape(courses, sectors)
    total = 0.0
    for k in range(courses):
        course = sum(rg.dome_voussoir(ri, ro, th[k], th[k + 1], 2 * math.pi * j / sectors, 2 * math.pi * (j + 1) / sectors)[0]
                     for j in range(sectors))
        assert weights[k].sum() == pytest.approx(uw * course, rel=1e-11), f"course {k + 1}"
        total += uw * course
    assert asm.total_weight == pytest.approx(total, rel=1e-11)
    assert -build_model(asm, "spatial").b_dead.reshape(-1, 6)[:, 2].sum() == pytest.approx(total, rel=1e-11)


def test_dome_closed_form_reaches_the_shell():
    """The facetted voussoirs are inscribed in the shell: their closed-form total volume rises
    towards the shell's 2/3 pi (ro^3 - ri^3) as the discretisation is refined (second order)."""
    R, t = 5.0, 0.3
    shell = 2 / 3 * math.pi * ((R + t / 2) ** 3 - (R - t / 2) ** 3)
    errors = []
    for s, c in ((8, 4), (16, 8), (32, 16), (64, 32)):
        ref = rg.hemispherical_dome(R, t, s, c)
        errors.append(1 - ref.volume[~ref.support].sum() / shell)
    assert all(e > 0 for e in errors)
    ratios = [a / b for a, b in zip(errors, errors[1:])]
    assert all(3.9 < r < 4.1 for r in ratios[1:]), ratios
