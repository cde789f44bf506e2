"""Limit analysis against references tce did not produce: the paper, closed forms, Heyman's
kinematic theorem worked out by hand (tests/reference/mechanism.py), Milankovitch's minimum
thickness, and the minimum thickness found with the reference operators and HiGHS."""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
import pytest
from helpers import block_on_support

from reference import geometry as rg
from reference import lp
from reference import mechanism as rm
from reference import operators as ro
from tce.analysis import Analysis
from tce.analysis.thickness import arch_minimum_thickness
from tce.core.material import Material
from tce.structures.arch import semicircular_arch

PAPER_LAMBDA_0 = 0.2428243  # the paper's arch: tce's direct lambda_0max, to the 7 digits the method gives


@pytest.fixture(scope="module")
def collapse() -> rm.Mechanism:
    """The collapse mechanism of the paper's arch under in-plane lateral load (+x), by
    enumeration of the 4-hinge mechanisms on the closed-form voussoir weights and centroids."""
    blocks = rg.semicircular_arch()
    ji, je = rm.semicircular_joints(1.0, 0.2, 14)
    return rm.collapse(ji, je, blocks.centroid[1:-1][:, [0, 2]], blocks.weight[1:-1])


def test_reference_mechanism_is_the_papers(collapse):
    """The hand-made kinematic analysis gives the paper's lambda_0max = 0.243 (printed to 3
    digits) and tce's value to 1e-7; the hinges alternate intrados / extrados."""
    assert abs(collapse.multiplier - 0.243) < 5e-4
    assert collapse.multiplier == pytest.approx(PAPER_LAMBDA_0, abs=1e-7)
    assert [side for _, side in collapse.hinges] == ["intrados", "extrados", "intrados", "extrados"]


@pytest.mark.parametrize("kind, mu", [("planar", None), ("spatial", None), ("planar", 0.8), ("spatial", 0.8)])
def test_in_plane_collapse_mechanism(collapse, kind, mu):
    """lambda_0max and the four hinges: which joints, and on which edge (intrados or extrados)."""
    lim = Analysis(semicircular_arch(), Material(mu), model=kind).limit(0.0)  # type: ignore[arg-type]
    assert lim.status == "optimal" and lim.model == kind
    assert lim.lambda_max == pytest.approx(collapse.multiplier, abs=1e-8)
    assert lim.lambda_max == pytest.approx(PAPER_LAMBDA_0, abs=1e-7)
    mech = lim.mechanism
    assert mech.hinges == [k for k, _ in collapse.hinges]  # slots are the joints 0..14
    assert not mech.sliding
    for (k, side), point in zip(collapse.hinges, collapse.points):
        np.testing.assert_allclose(mech.hinge_points[k][[0, 2]], point, atol=1e-12, err_msg=f"joint {k} ({side})")
    assert all(mode == "closed" for k, mode in enumerate(mech.modes) if k not in mech.hinges)


@pytest.mark.parametrize(
    "depth, thickness, voussoirs",
    [(0.25, 0.2, 14), (0.5, 0.2, 14), (0.15, 0.3, 8), (0.4, 0.15, 21), (0.25, 0.2, 100)],
)
@pytest.mark.parametrize("alpha", [90.0, 270.0])
def test_out_of_plane_rocking_closed_form(depth, thickness, voussoirs, alpha):
    """Out of plane the whole arch rocks about the springing edges on the side the load points
    to: lambda_90max = (d/2) / z_c, z_c the closed-form centroid height of the voussoirs; to
    1e-10, the limit solver's gap tolerance."""
    a = semicircular_arch(1.0, thickness, depth, voussoirs)
    lim = Analysis(a, Material()).limit(alpha)
    expected = (depth / 2) / rg.arch_centroid_height(1.0, thickness, voussoirs)
    assert lim.lambda_max == pytest.approx(expected, abs=1e-10)
    assert lim.mechanism.hinges == [0, voussoirs]
    side = math.copysign(depth / 2, math.sin(math.radians(alpha)))  # +y for alpha = 90
    np.testing.assert_allclose(lim.mechanism.hinge_points[[0, voussoirs], 1], side, atol=1e-12)


@pytest.mark.parametrize("b, h", [(0.4, 1.0), (0.3, 1.5), (1.0, 0.8)])
@pytest.mark.parametrize("alpha", [0.0, 180.0])
def test_single_block_rocks_at_b_over_h(b, h, alpha):
    """A block b wide and h high rocks about its leeward base edge at lambda = b/h."""
    an = Analysis(block_on_support(b, h), Material(), model="spatial")
    lim = an.limit(alpha)
    assert lim.lambda_max == pytest.approx(b / h, rel=1e-9)
    assert lim.mechanism.modes == ("hinge",)
    assert lim.mechanism.hinge_points[0][0] == pytest.approx(b / 2 * math.cos(math.radians(alpha)), abs=1e-12)
    assert an.solve(b / h * (1 - 1e-6), alpha).status == "optimal"
    assert an.solve(b / h * (1 + 1e-6), alpha).status == "infeasible"


@pytest.mark.parametrize("mu", [0.1, 0.25])
@pytest.mark.parametrize("alpha", [0.0, 30.0, 90.0])
def test_single_block_slides_at_mu(mu, alpha):
    """Where friction is weaker than rocking (b/h = 0.4 both ways), the block slides at lambda = mu."""
    lim = Analysis(block_on_support(0.4, 1.0, 0.4), Material(mu), model="spatial").limit(alpha)
    assert lim.lambda_max == pytest.approx(mu, rel=1e-8)
    assert lim.mechanism.modes == ("sliding",)


def _reference_stands(t: float, voussoirs: int, R: float = 1.0, depth: float = 0.25) -> bool:
    blocks = rg.semicircular_arch(R - t / 2, t, depth, voussoirs)
    ops = ro.build(blocks, ro.semicircular_arch_contacts(R - t / 2, t, depth, voussoirs))
    return lp.rigid_tce(ops, 0.0, 0.0, np.zeros(12)).status == "optimal"


@lru_cache(maxsize=None)
def _minimum_thickness_14():
    return arch_minimum_thickness(voussoirs=14, tol=1e-6)


def test_minimum_thickness_equals_the_reference():
    """tce's minimum thickness of the 14-voussoir arch (centreline radius 1 m) is the one found by
    bisection on the reference operators with HiGHS, within the bisection's tolerance."""
    lo, hi = 0.05, 0.2
    while hi - lo > 1e-8:
        mid = (lo + hi) / 2
        lo, hi = (lo, mid) if _reference_stands(mid, 14) else (mid, hi)
    res = _minimum_thickness_14()
    assert res.undecided == 0
    assert res.lower <= hi and res.thickness >= lo  # the two brackets overlap
    assert res.thickness == pytest.approx(hi, rel=1.1e-6)


def test_minimum_thickness_converges_to_milankovitch():
    """Milankovitch's t/R = 0.1075 for the continuous semicircular arch (Heyman, The Stone
    Skeleton, 1995), given to 4 digits: 60 voussoirs are within 1e-4 of it (the discrete value
    rises towards it from below: 0.10652 at 14 voussoirs, 0.10744 at 60)."""
    fine = arch_minimum_thickness(voussoirs=60, tol=1e-6).ratio
    assert fine < 0.1075 + 5e-5
    assert fine == pytest.approx(0.1075, abs=1e-4)


def test_minimum_thickness_brackets_the_limit():
    res = _minimum_thickness_14()
    t, R = res.thickness, 1.0
    below = semicircular_arch(R - 0.999 * t / 2, 0.999 * t)
    above = semicircular_arch(R - 1.001 * t / 2, 1.001 * t)
    assert Analysis(above, Material()).solve(0.0).status == "optimal"
    assert Analysis(below, Material()).solve(0.0).status == "infeasible"
