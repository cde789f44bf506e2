"""Interface modes of hand-made velocity fields on one block standing on a support."""

from __future__ import annotations

import numpy as np
import pytest
from helpers import block_on_support

from tce.core.limit import mechanism_from_velocities
from tce.core.model import build_model


@pytest.fixture(scope="module")
def model():
    return build_model(block_on_support(b=0.4, h=1.0, d=0.3).validate(), "spatial")


@pytest.mark.parametrize(
    "v, mode",
    [
        ([0, 0, 0, 0, 0, 0], "closed"),
        ([0, 0, 1, 0, 0, 0], "opening"),  # lifts off
        ([0.05, 0, 1, 0, 0, 0], "sliding"),  # lifts off and moves sideways by 5 % of it
        ([0.005, 0, 1, 0, 0, 0], "opening"),  # 0.5 % sideways: below the 1 % threshold
        ([1, 0, 0, 0, 0, 0], "sliding"),
    ],
)
def test_translations(model, v, mode):
    vel = np.zeros((2, 6))
    vel[1] = v
    assert mechanism_from_velocities(model, vel).modes == (mode,)


def test_rocking_about_an_edge_is_a_hinge_there(model):
    # rotation about the edge x = +b/2, z = 0 (axis +y... the block tips towards +x):
    # v = w x (c - p) with p on the edge, c = (0, 0, h/2) the centroid, w = (0, 1, 0)
    c, p, w = np.array([0, 0, 0.5]), np.array([0.2, 0, 0]), np.array([0.0, 1.0, 0.0])
    vel = np.zeros((2, 6))
    vel[1, :3] = np.cross(w, c - p)
    vel[1, 3:] = w
    mech = mechanism_from_velocities(model, vel)
    assert mech.modes == ("hinge",)
    assert mech.hinge_points[0][0] == pytest.approx(0.2) and mech.hinge_points[0][2] == pytest.approx(0.0)
    # rescaled so that the largest vertex velocity component is 1: a top corner moves by
    # w x (x - p) = (z, 0, -(x - 0.2)), largest |component| z = h = 1 at the top
    np.testing.assert_allclose(mech.velocities[1], np.r_[np.cross(w, c - p), w], rtol=1e-12)
