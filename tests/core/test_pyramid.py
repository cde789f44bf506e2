"""Friction pyramids bracket the cone's lambda_max, and the bracket narrows as k grows."""

from __future__ import annotations

import numpy as np
import pytest

from tce.structures.arch import semicircular_arch
from tce.core.limit import LimitSolver
from tce.core.material import Material
from tce.core.model import build_model
from tce.core.pyramid import pyramid_bracket, pyramid_lambda_max, pyramid_rows


@pytest.fixture(scope="module")
def arch():
    return semicircular_arch().validate()


@pytest.fixture(scope="module")
def spatial(arch):
    return build_model(arch, "spatial")


# friction low enough that sliding governs (the Heyman value out of plane is 0.1788)
@pytest.mark.parametrize("mu, alpha", [(0.35, 90.0), (0.5, 45.0)])
def test_bracket_holds_and_narrows(spatial, mu, alpha):
    cone = LimitSolver(spatial, Material(friction=mu)).solve(alpha)
    heyman = LimitSolver(spatial, Material()).solve(alpha)
    assert cone.status == "optimal"
    assert cone.lambda_max < heyman.lambda_max - 1e-3  # sliding matters
    widths = []
    for k in (4, 8, 16, 32):
        lo, hi = pyramid_bracket(spatial, mu, alpha, k)
        assert lo <= cone.lambda_max + 1e-8
        assert hi >= cone.lambda_max - 1e-8
        widths.append(hi - lo)
    assert all(b <= a + 1e-9 for a, b in zip(widths, widths[1:]))
    assert widths[0] > 1e-3
    assert widths[-1] < 0.03 * cone.lambda_max


def test_statuses_and_kinds(spatial):
    lo = pyramid_lambda_max(spatial, 0.35, 90.0, 8, "inscribed")
    hi = pyramid_lambda_max(spatial, 0.35, 90.0, 8, "circumscribed")
    assert lo.status == hi.status == "optimal"
    assert lo.certificate_gap < 1e-6 and hi.certificate_gap < 1e-6
    # the circumscribed forces leave the cone but stay in the circle of radius mu / cos(pi/k)
    f = hi.forces
    assert np.all(np.linalg.norm(f[:, 1:], axis=1) <= 0.35 / np.cos(np.pi / 8) * f[:, 0] + 1e-8)


def test_planar_pyramid_is_the_cone(arch):
    planar = build_model(arch, "planar")
    cone = LimitSolver(planar, Material(friction=0.4)).solve(0.0)
    lo, hi = pyramid_bracket(planar, 0.4, 0.0, 4)
    assert lo == pytest.approx(cone.lambda_max, abs=1e-8)
    assert hi == pytest.approx(cone.lambda_max, abs=1e-8)


def test_heyman_has_no_pyramid(spatial):
    rows = pyramid_rows(spatial, None, 8)
    assert rows.n_soc == 0 and rows.n_nonneg == spatial.n_contacts


def test_bad_input(spatial):
    with pytest.raises(ValueError, match="k >= 3"):
        pyramid_rows(spatial, 0.5, 2)
    with pytest.raises(ValueError, match="kind"):
        pyramid_rows(spatial, 0.5, 8, "outer")  # type: ignore[arg-type]
