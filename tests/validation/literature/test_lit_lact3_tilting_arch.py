"""LACT3's arch on a tilting table: the tilt angle at collapse.

Source: Hua, Y., Buzzetti, M., Pingaro, N., da Silva, L. C. M. & Milani, G. (2025). LACT3,
*Limit Analysis Code for Tilting Table Tests* (a MATLAB tool, released 6 February 2025;
its paper, "A computerized tool for the kinematic limit analysis of 2D masonry structures
failing on a tilting table", was not accessible). The public repository
(GabrieleMilani/LACT3_v1.0) holds the sample arch ``sample/arch_1.dxf`` and the automatic test
``LACT3_SolverTest.m``, which asserts that both their upper- and lower-bound programs reach
collapse at a tilt of **17.10 deg** for that arch with friction angle 30 deg and no cohesion.
The value is the authors' computation as published in their repository, not a printed table.
LACT3 (``LACT3.m``) reports the last tilt at which both programs find the arch standing: it
steps the tilt from the last stable one, halving the step (1 deg by default) after every
collapse until it is below the tolerance (0.01 deg by default), and prints it to 0.01 deg. The
collapse is therefore at most two final steps (0.016 deg) above the reported tilt, which is
also rounded (0.005 deg): the tolerance is 0.02 deg, and tce must lie above 17.095 deg.

Geometry (read from the drawing, mm): a semicircle of 27 radial voussoirs of 20/3 deg,
centre on the table's surface, intrados radius 317.0, extrados 373.3 (t/R = 0.16312 with R the
centreline radius 345.15); the lowest voussoir on each side is part of the base, so 25
voussoirs stand on two skewbacks at pi/27 above the springing line. tce builds it with
``segmental_arch`` (``tce.quality.validation.tilting_arch``); the drawing's 52 voussoir corners
lie on the two circles and on the 26 joint radii to 6e-4 mm. The tilt is
``tce.quality.walls.tilt_angle``, as for LACT3's wall in ``test_lit_lact3.py``.

tce: on a table tilted by theta every weight has the component ``W sin theta`` along the table
and ``W cos theta`` across it; the contact law is homogeneous in the forces, so the collapse
tilt is ``atan(lambda_max)`` of the level arch under the lateral pattern: 0.3077487, 17.1057 deg
(+0.0057 deg: above the reported last stable tilt, as it must be). The tilted table itself,
solved with gravity along the rotated axis, stands at 17.10 and 17.105 deg and falls at
17.106 deg. The collapse is a four-hinge mechanism; the friction angle does not enter (Heyman's
material gives the same multiplier to 1e-11). The independent reference is
``tests/reference/lateral_arch.py`` over the same 25 chord-faced voussoirs of the same embrace
(``start = pi/27``): 0.3077487 to 1e-11. The discretisation is the source's: the continuous ring
of the same embrace carries 0.3066997 (17.0508 deg); 25 joints leave fewer places for a hinge.
"""

import math

import pytest
from _atlas import check_case

from reference import lateral_arch as ref
from tce import Analysis, Material
from tce.quality.validation import TILT_FRICTION_ANGLE, TILT_RADII, tilting_arch
from tce.quality.walls import tilt_angle, tilted

MU = math.tan(math.radians(TILT_FRICTION_ANGLE))
START = math.pi / 27.0


def tilt(n: int = 25, friction_angle: float = TILT_FRICTION_ANGLE) -> float:
    """Collapse tilt (deg) of the arch of ``n`` voussoirs."""
    return tilt_angle(tilting_arch(n), friction_angle)


def ratio() -> float:
    """t/R of the arch, R the centreline radius."""
    ri, re = TILT_RADII
    return (re - ri) / ((re + ri) / 2.0)


def test_published_value():
    """Within the tolerance, and above the reported tilt less its rounding: LACT3 reports the
    last tilt at which the arch still stands."""
    assert check_case("lact3_arch_tilt") > 17.10 - 0.005


@pytest.mark.parametrize("n", [25, 9])
def test_tce_equals_the_lp_of_its_voussoirs(n):
    """The 3D block model and the plane LP of the same chord-faced voussoirs, same embrace."""
    lam = Analysis(tilting_arch(n), Material()).limit(0.0).lambda_max
    assert lam == pytest.approx(ref.capacity(ratio(), n, "facets", start=START), abs=1e-9)


def test_the_tilted_table_stands_until_the_tilt_angle():
    """Gravity along the rotated axis, no lateral pattern: the arch stands at LACT3's 17.10 deg
    and at 17.105 deg and falls at 17.106 deg, either way round (the arch is symmetric)."""
    material = Material(friction=MU)
    assert tilt() == pytest.approx(17.10568, abs=1e-5)
    for sign in (1.0, -1.0):
        for stands in (17.10, 17.105):
            assert Analysis(tilted(tilting_arch(), sign * stands), material).solve(0.0).status == "optimal"
        assert Analysis(tilted(tilting_arch(), sign * 17.106), material).solve(0.0).status == "infeasible"


def test_four_hinges_and_no_sliding_at_thirty_degrees():
    """The friction angle of the source does not bind: the same multiplier as Heyman's
    material, a mechanism of four hinges and no sliding joint; a low friction does bind."""
    r = Analysis(tilting_arch(), Material(friction=MU)).limit(0.0)
    assert r.mechanism.modes.count("hinge") == 4 and "sliding" not in r.mechanism.modes
    assert r.lambda_max == pytest.approx(Analysis(tilting_arch(), Material()).limit(0.0).lambda_max, abs=1e-9)
    assert tilt(friction_angle=math.degrees(math.atan(0.4))) < 10.5


def test_the_voussoirs_stand_above_the_continuous_ring():
    """The source's 25 joints against the continuous ring of the same embrace (reference only):
    fewer places for a hinge, a larger tilt, by 0.055 deg."""
    ring = math.degrees(math.atan(ref.capacity(ratio(), 2000, start=START)))
    assert ring == pytest.approx(17.0508, abs=1e-4)
    assert 0.05 < tilt() - ring < 0.06
