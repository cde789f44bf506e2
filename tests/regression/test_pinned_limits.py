"""Regression pins: numbers measured from tce itself, kept to notice when they change.

Nothing here is a validation (tests/validation/ compares with references tce did not
produce): a failure means an answer moved, to be explained before a pin is updated.

Measured with tce 0.1.0 (Clarabel 0.11.1) at commit 81fada9 on 2026-11-21 (first pinned) and
re-measured at commit 6b1b1bd on 2026-11-22: every lambda_max and the dome thrust came out
bit-for-bit the same; the 8 x 6 dome's minimum thickness came out one bisection step lower
(0.0393945 instead of 0.0394141), and is pinned at that value. The samples use the README's
supports, friction and unit weights (see tests/structures/test_io.py).

Tolerances: the direct lambda_max and the thrust are one Clarabel solve at tolerance 1e-10,
reproducible to ~1e-9: pinned to 1e-7. A minimum thickness is the upper end of a bisection
bracket of relative width 1e-3: a status decided differently near the limit moves it by one
bracket, so it is pinned to 1e-3.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import pytest

from tce.analysis import Analysis
from tce.structures.dome import hemispherical_dome, radial_settlement
from tce.core.material import Material
from tce.analysis.thickness import minimum_thickness

from structures.test_io import SAMPLES, _load_sample

# ---------------------------------------------------------------- the compas_cra samples
# Direct lambda_max (spatial model) in x (alpha 0) and y (alpha 90), measured (see the module
# docstring); None = unbounded.
# The unbounded ones are honest: the shelf's blocks are clamped between faces of the support
# (contacts with normals +-x and +-z), type-b's wedge sits between two supports with unlimited
# (Heyman) friction, and the curved sample's facetted contacts interlock under Heyman friction;
# the TCE at lam = 1000 is optimal for all three (checked below).
SAMPLE_LIMITS = {
    "bridge": (0.5672067335895938, 0.8093627650602756),
    "cubes": (0.3239796756703493, 0.3229939826941563),
    "curve-3-blocks": (None, None),
    "shelf": (None, None),
    "type-b": (None, None),
}


@lru_cache(maxsize=None)
def _sample_analysis(name):
    return Analysis(_load_sample(name), Material(friction=SAMPLES[name]["mu"]), model="spatial")


def test_every_sample_is_pinned():
    assert set(SAMPLE_LIMITS) == set(SAMPLES)


@pytest.mark.parametrize("name", sorted(SAMPLE_LIMITS))
def test_sample_stands_and_its_limits(name):
    an = _sample_analysis(name)
    assert an.solve(0.0).status == "optimal"
    for alpha, expected in zip((0.0, 90.0), SAMPLE_LIMITS[name]):
        lim = an.limit(alpha)
        assert lim.model == "spatial"
        if expected is None:
            assert lim.status == "unbounded" and lim.lambda_max == np.inf
            assert an.solve(1000.0, alpha).status == "optimal"
        else:
            assert lim.status == "optimal"
            assert lim.lambda_max == pytest.approx(expected, rel=1e-7)
            assert lim.certificate_gap < 1e-6


def test_curved_sample_with_friction_has_a_finite_limit():
    """With its stored interfaces (planar strips along the curved contacts) and Coulomb friction
    0.84, the curved sample has a finite lambda_max in every direction: the upper blocks slide or
    rock on the curved seats. Measured with tce 0.1.0 at commit eb3aa03 (stored interfaces) on
    2026-11-22, and the same to the last digit after the merge of the test reorganisation:
    lambda_max(0) = 0.151037, lambda_max(90) = 0.502530, lambda_max(180) = 1.372894."""
    an = Analysis(_load_sample("curve-3-blocks"), Material(friction=0.84), model="spatial")
    assert an.solve(0.0).status == "optimal"
    for alpha, expected in ((0.0, 0.15103730021735354), (90.0, 0.5025301956182282), (180.0, 1.3728939196743408)):
        lim = an.limit(alpha)
        assert lim.status == "optimal" and np.isfinite(lim.lambda_max)
        assert lim.certificate_gap < 1e-6
        assert lim.lambda_max == pytest.approx(expected, rel=1e-7)


# ---------------------------------------------------------------- hemispherical dome
R = 5.0


def test_dome_radial_settlement_gives_equal_thrusts():
    """Self-weight plus a 1 mm outward radial spread of every support: the TCE picks the
    minimum-thrust state, the same horizontal thrust (pushing outward) on every support."""
    dome = hemispherical_dome(R, 0.1 * R, 8, 6)
    res = Analysis(dome, Material(friction=0.8)).solve(0.0, settlements=radial_settlement(dome, 0.001))
    assert res.status == "optimal"
    w = res.support_wrenches
    h = np.hypot(w[:, 0], w[:, 1])
    assert h.max() - h.min() <= 1e-6 * h.max()
    # kN, measured (issue 21: the canonical state; the solver's own state, 31.23619602, lay
    # 2.6e-7 above the minimum, which the canonical solve's energy bound does not allow)
    assert h.mean() == pytest.approx(31.23618782, rel=1e-7)
    c = dome.centroids[list(dome.support_indices), :2]
    radial = (w[:, :2] * c).sum(axis=1) / np.linalg.norm(c, axis=1)
    assert np.all(radial < 0)  # the support pushes inward: the dome thrusts outward
    assert w[:, 2].sum() == pytest.approx(dome.total_weight, rel=2e-9)


# lambda_max in x, 12 sectors x 6 courses, mu 0.8, spatial model: measured per t/R (module docstring).
DOME_LIMITS = {0.06: 0.35772205384012096, 0.10: 0.5733325703761792, 0.15: 0.6863512026545059}


def test_dome_lateral_limit_is_finite_and_grows_with_thickness():
    got = []
    for ratio, expected in DOME_LIMITS.items():
        lim = Analysis(hemispherical_dome(R, ratio * R, 12, 6), Material(friction=0.8), model="spatial").limit(0.0)
        assert lim.status == "optimal" and np.isfinite(lim.lambda_max)
        assert lim.certificate_gap < 1e-6
        assert lim.lambda_max == pytest.approx(expected, rel=1e-7)
        got.append(lim.lambda_max)
    assert got[0] < got[1] < got[2]


# ---------------------------------------------------------------- dome minimum thickness
# Heyman material (unlimited friction), fixed mid-surface radius R, bisection in [0.035 R, 0.05 R]
# to tol 1e-3. Measured t/R (upper end of the final bracket):
#
#   sectors x courses   4 courses   6 courses   8 courses
#   8                   0.040713    0.039395    0.042236
#   12                  0.040703    0.039395    0.042236
#   16                                          0.042227
#
# The value depends on the number of courses, not on the number of sectors, and is not monotone
# in the courses (4: 0.0407, 5: 0.0398, 6: 0.0394, 7: 0.0417, 8: 0.0422). All stay within about
# 7 % of Heyman's continuous t/R ~ 0.042 for a hemispherical dome without hoop tension, and
# 8 courses lands on it. Why they differ from 0.042:
# * in the block dome the no-tension condition is enforced only at the courses + 1 bed joints,
#   not at every colatitude of a continuous shell; depending on where the joints fall relative
#   to the critical sections (where the meridional thrust touches the intrados or extrados),
#   a coarse dome can be thinner than the continuum (4-6 courses) or match it (8 courses);
# * the facetted blocks are inscribed in the shell, so the weight and its distribution differ;
# * the rigid no-tension meridian joints carry hoop compression but no hoop tension (as in
#   Heyman's cracked-lune model), and the solver finds any admissible hoop distribution rather
#   than an assumed one. With hoop compression free across sectors, the sector count hardly matters.
DOME_MIN = {(8, 4): 0.040712890625, (8, 6): 0.03939453125, (8, 8): 0.042236328125}


@lru_cache(maxsize=None)
def _dome_min(sectors, courses):
    return minimum_thickness(lambda t: hemispherical_dome(R, t, sectors, courses),
                             0.035 * R, 0.05 * R, tol=1e-3, reference=R)


@pytest.mark.parametrize("sc", sorted(DOME_MIN), ids=lambda sc: f"{sc[0]}x{sc[1]}")
def test_dome_minimum_thickness(sc):
    res = _dome_min(*sc)
    assert res.undecided == 0
    assert res.ratio == pytest.approx(DOME_MIN[sc], rel=1e-3)
    assert res.ratio == pytest.approx(0.042, rel=0.07)  # near Heyman's continuous value


def test_dome_minimum_thickness_trend():
    r = {sc: _dome_min(*sc).ratio for sc in DOME_MIN}
    # not monotone in the courses: 6 courses is the thinnest, 8 courses the thickest
    assert r[(8, 6)] < r[(8, 4)] < r[(8, 8)]
    assert abs(r[(8, 8)] / 0.042 - 1.0) < 0.01
    # more sectors at the same courses: the same thickness within the bisection tolerance
    assert _dome_min(12, 6).ratio == pytest.approx(r[(8, 6)], rel=1e-3)
