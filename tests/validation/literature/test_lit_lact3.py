"""LACT3 v1.0: the collapse tilt of its sample wall on a tilting table (a code's value, not a paper's).

Source: LACT3, Limit Analysis Code for Tilting Table Tests, v1.0 (released 6 February 2025;
Y. Hua, M. Buzzetti, N. Pingaro, L. C. M. da Silva, G. Milani; public repository
GabrieleMilani/LACT3_v1.0). Its automated solver test (``LACT3_SolverTest.m``, ``testwall``)
takes its sample wall (``sample/wall.dxf``), a friction angle of 26 deg, no cohesion, and a
tilt of 16.73 deg, and checks that its upper- and lower-bound programs both give a load of
magnitude below 1e-3 there: the collapse tilt. The joints are associative Mohr-Coulomb, as in
tce's limit problem. The paper the README asks to cite was not found; the value is the code's
own, so it is not counted among the atlas's published values.

LACT3 finds the tilt by stepping it up, halving the step when the wall no longer carries load,
until the step is below its converging tolerance (0.01 deg by default, ``LACT3.m``), and
reports the last tilt at which the upper-bound load is positive, to 0.01 deg. The collapse tilt
is therefore within 0.015 deg of the printed one: the tolerance.

tce: :func:`tce.quality.walls.lact3_wall` rebuilds the wall from a description of its layout
(27 courses of 0.25 m units in running bond, a door and a window with a lintel; the 182 blocks
coincide with the file's, checked once against it); without cohesion the collapse tilt is
``atan(lambda_max)`` under the lateral pattern towards +x: 16.7376 deg (difference +0.0076
deg). Towards -x the same wall fails at 10.6250 deg, so the direction is not a detail. There is
no discretisation to converge: the blocks are the structure.
"""

import math

import pytest
from _atlas import check_case

from tce import Analysis, Material
from tce.quality.walls import LACT3_DOOR, LACT3_WINDOW, lact3_wall, tilt_angle, tilted

PHI = 26.0
H = 1.5 / 27  # course height (m)


def test_published_value():
    check_case("lact3_wall_tilt")


def _rects(assembly):
    """(x0, x1, z0, z1) of every free block of the upright wall."""
    out = []
    for b in assembly.blocks:
        if not b.support:
            v = b.shape.vertices
            out.append((v[:, 0].min(), v[:, 0].max(), v[:, 2].min(), v[:, 2].max()))
    return out


def test_the_layout_is_the_described_one():
    """182 blocks; the wall's 2.0 x 1.5 m less the door (24 courses) and the window (22
    courses); every course but the lintel's made of units of 0.25 or 0.125 m or pieces cut at a
    jamb; one lintel, 0.75 m long, in course 24 over the window."""
    rects = _rects(lact3_wall())
    assert len(rects) == 182
    door = (LACT3_DOOR[1] - LACT3_DOOR[0]) * (LACT3_DOOR[3] - LACT3_DOOR[2] + 1) * H
    window = (LACT3_WINDOW[1] - LACT3_WINDOW[0]) * (LACT3_WINDOW[3] - LACT3_WINDOW[2] + 1) * H
    area = sum((x1 - x0) * (z1 - z0) for x0, x1, z0, z1 in rects)
    assert area == pytest.approx(2.0 * 1.5 - door - window, rel=1e-12)
    long = [r for r in rects if r[1] - r[0] > 0.25 + 1e-9]
    assert len(long) == 1
    x0, x1, z0, _ = long[0]
    assert (x0, x1) == pytest.approx((0.75, 1.5)) and z0 == pytest.approx(24 * H)


def test_the_tilted_wall_stands_below_the_angle_and_not_above():
    """The equivalence the comparison rests on, checked inside tce: the wall itself turned by
    the collapse tilt -+ 0.01 deg (left end up, so that the table pulls it towards +x) stands
    under self-weight alone below the angle and has no admissible state above it."""
    theta = tilt_angle(lact3_wall(), PHI)
    mat = Material(friction=math.tan(math.radians(PHI)))
    assert Analysis(tilted(lact3_wall(), theta - 0.01), mat).solve(0.0).status == "optimal"
    assert Analysis(tilted(lact3_wall(), theta + 0.01), mat).solve(0.0).status == "infeasible"
