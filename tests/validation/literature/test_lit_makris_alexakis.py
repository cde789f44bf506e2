"""Makris & Alexakis (2013): radial against vertical joints (stereotomy) of the semicircular arch.

Source: Makris, N. & Alexakis, H. (2013). The effect of stereotomy on the shape of the
thrust-line and the minimum thickness of semicircular masonry arches. *Archive of Applied
Mechanics* 83, 1511-1533. The values were read from the abstract of Makris's seminar of the same
title (Cambridge University Engineering Department, 1 November 2013): Milankovitch's least
thickness with radial cuts ``t/R = 0.1075``; with vertical cuts ``t/R = 0.1095``; the catenary
needs 0.1117 (not a block model: not compared).

tce: ``semicircular_arch(..., joints="vertical")`` cuts the ring by vertical joints whose lower
ends are those of the radial joints on the intrados; the springing joints stay horizontal.

| voussoirs | 10 | 20 | 40 | 80 | 160 | continuous LP |
|---|---|---|---|---|---|---|
| radial | 0.107011 | 0.107348 | 0.107432 | 0.107453 | 0.107458 | 0.107478 |
| vertical | 0.107778 | 0.108905 | 0.109285 | 0.109366 | 0.109451 | 0.109460 |

The references are the continuous LPs (0.1074776 and 0.1094599), which round to the printed
0.1075 and 0.1095; the tolerances are twice the 160-voussoir values' distance to them (2e-5
and 9e-6): 4e-5 and 1.8e-5.
"""

from pathlib import Path

import numpy as np
import pytest
from _atlas import check_case

from reference import continuous_arch as ref
from tce.quality.validation import min_ratio
from tce.structures.arch import semicircular_arch
from tce.study.schema import StudyError, parse_study

STUDY = Path(__file__).resolve().parents[3] / "studies" / "fig7_8_inplane.toml"


@pytest.mark.parametrize("name", ["ma_radial", "ma_vertical"])
def test_published_value(name):
    check_case(name)


def test_vertical_joints_need_more_thickness_at_every_discretisation():
    for n in (20, 40):
        assert min_ratio(n, joints="vertical", tol=1e-5) > min_ratio(n, joints="radial", tol=1e-5) + 1e-3


def test_continuous_vertical_cuts():
    """The independent LP of the continuous ring with vertical cuts gives the published 0.1095."""
    assert ref.minimum_thickness("vertical", m=500, tol=1e-7) == pytest.approx(0.1095, abs=1e-4)


@pytest.mark.parametrize("n", [7, 12, 40])
def test_vertical_joint_geometry(n):
    """Joints between voussoirs are vertical, the springing joints horizontal, the blocks fill
    the ring (less the chord segments) and the arch is its own mirror image."""
    ri, t, d = 0.9, 0.2, 0.25
    a = semicircular_arch(ri, t, d, n, joints="vertical")
    normals = np.array([i.normal for i in a.interfaces])
    assert np.allclose(np.abs(normals[[0, -1], 2]), 1.0)
    assert np.allclose(normals[1:-1, 2], 0.0) and np.allclose(np.abs(normals[1:-1, 0]), 1.0)
    vol = sum(b.shape.volume for b in a.blocks if not b.support)
    ring = np.pi / 2 * ((ri + t) ** 2 - ri**2) * d
    assert vol == pytest.approx(ring, rel=1.5 / n**2)  # chords about pi/n apart
    c = np.array([b.shape.centroid for b in a.blocks])
    assert np.allclose(c[::-1] * [-1, 1, 1], c, atol=1e-12)
    assert a.meta["joints"] == "vertical"


def test_joints_keyword_checked_and_in_study_files():
    with pytest.raises(ValueError, match="joints must be one of radial, vertical"):
        semicircular_arch(joints="oblique")
    text = STUDY.read_text()
    assert 'type = "semicircular_arch"' in text
    vertical = text.replace('type = "semicircular_arch"', 'type = "semicircular_arch"\njoints = "vertical"')
    assert parse_study(vertical).spec.structure.build().meta["joints"] == "vertical"
    with pytest.raises(StudyError, match="joints"):
        parse_study(vertical.replace('"vertical"', '"oblique"'))
