"""The arch bridge in three dimensions (tce.structures.bridge.arch_bridge with ``courses``,
``bond`` and ``skew``; issue 41) against what must hold whatever the numbers:

- a square bridge of several stack-bonded courses under loads uniform across its width (the
  fill's weight and a pressure over the whole width) is the 2D bridge per unit width: the
  one-course bridge one metre wide, solved by the planar model, to solver precision;
- lanes mirrored about the centreline carry the same load (square bridges, stack and running
  bond: an odd number of courses keeps the running bond symmetric), and a lane off the
  centreline carries another load than on it; a skew bridge is symmetric under a half turn in plan
  instead, which takes a vehicle at ``(x, y)`` to the reversed vehicle at ``(-x, -y)``;
- a wheel's contact patch, spread through the fill by the 2:1 rule in both directions, loads
  the courses and voussoirs under it by area (worked out here from the ring's geometry);
- the skew bridge tends to the square one as the skew tends to 0, on the spatial model, from
  the one-course square bridge's planar answer too: lambda_max is differentiable at 0 (the
  difference quotients from both sides agree).

Turning the bridge in plan by any angle is a relation of the battery
(``tests/battery/test_bridge_rotation.py``).
"""

from __future__ import annotations

import numpy as np
import pytest

from tce.core.analysis import Analysis
from tce.core.fill import Fill
from tce.core.loads import LoadPattern
from tce.core.material import Material
from tce.core.vehicles import Vehicle, wheel_loads
from tce.structures.bridge import arch_bridge

MATERIAL = Material(friction=0.6)
FILL = dict(depth=0.3, unit_weight=18.0)
BRIDGE = dict(span=6.0, rise=1.5, thickness=0.4, voussoirs=8)
#: one axle of 100 kN on two wheels 1.2 m apart with 0.3 m square patches
AXLE = dict(axles=[[0.0, 100.0]], wheels=[-0.6, 0.6], patch=[0.3, 0.3])


def _limit(asm, pattern, model="auto"):
    r = Analysis(asm, MATERIAL, model=model).limit(loads=pattern)
    assert r.status == "optimal", r.status
    return r


@pytest.mark.parametrize("courses", [3, 5])
def test_square_stack_bridge_under_uniform_loads_is_the_2d_bridge_per_unit_width(courses):
    depth = 2.5
    p = LoadPattern(lateral=False, distributed=[dict(x=(-2.0, -1.0), pressure=10.0)], fill=FILL)
    strip = _limit(arch_bridge(depth=1.0, **BRIDGE), p, model="planar")
    wide = arch_bridge(depth=depth, courses=courses, **BRIDGE)
    r = _limit(wide, p)
    assert r.model == "spatial"
    assert r.lambda_max == pytest.approx(strip.lambda_max, rel=1e-8)
    # the abutments' reactions per unit width at the same multiplier, on the canonical states
    lam = 0.5 * strip.lambda_max
    a = Analysis(arch_bridge(depth=1.0, **BRIDGE), MATERIAL, model="planar").solve(lam, loads=p)
    b = Analysis(wide, MATERIAL).solve(lam, loads=p)
    assert a.ok and b.ok
    wa = np.asarray(a.support_wrenches).reshape(-1, 6)[:, [0, 2]]
    wb = np.asarray(b.support_wrenches).reshape(-1, 6)[:, [0, 2]] / depth
    np.testing.assert_allclose(wb, wa, rtol=0, atol=1e-7 * np.abs(wa).max())


@pytest.mark.parametrize("bond", ["stack", "running"])
def test_lanes_mirrored_about_the_centreline_carry_the_same_load(bond):
    an = Analysis(arch_bridge(depth=3.0, courses=5, bond=bond, **BRIDGE), MATERIAL)
    lam = {y: an.limit(loads=LoadPattern(lateral=False, vehicle=[dict(AXLE, x=-1.4, y=y)], fill=FILL)).lambda_max
           for y in (-0.7, 0.0, 0.7)}
    assert lam[0.7] == pytest.approx(lam[-0.7], rel=1e-7)
    # the lane matters: the wheels' patches load other courses (the vehicle's y is not ignored)
    assert abs(lam[0.7] - lam[0.0]) > 1e-3 * lam[0.0]


def test_skew_bridge_is_symmetric_under_a_half_turn_in_plan():
    an = Analysis(arch_bridge(depth=3.0, courses=4, skew=30.0, **BRIDGE), MATERIAL)
    tandem = dict(AXLE, axles=[[0.0, 100.0], [1.2, 100.0]])
    reverse = dict(AXLE, axles=[[-1.2, 100.0], [0.0, 100.0]])

    def lam(vehicle):
        return an.limit(loads=LoadPattern(lateral=False, vehicle=[vehicle], fill=FILL)).lambda_max

    a, b = lam(dict(tandem, x=-1.8, y=0.5)), lam(dict(reverse, x=1.8, y=-0.5))
    assert a == pytest.approx(b, rel=1e-7)
    # a mirror in the centreline is no symmetry of a skew bridge
    assert abs(lam(dict(tandem, x=-1.8, y=-0.5)) - a) > 1e-3 * a


@pytest.mark.parametrize(("courses", "y"), [(1, 0.0), (4, 0.3)])
def test_skew_tends_to_the_square_bridge(courses, y):
    """One course on the centreline: the square bridge's answer is the planar model's."""
    kw = dict(depth=2.0, courses=courses, **BRIDGE)
    p = LoadPattern(lateral=False, vehicle=[dict(AXLE, x=-1.4, y=y)], fill=FILL)
    square = _limit(arch_bridge(**kw), p)
    assert square.model == ("planar" if courses == 1 else "spatial")
    slope = {}
    for phi in (1e-3, -1e-3, 1e-4, -1e-4):
        r = _limit(arch_bridge(skew=phi, **kw), p)
        assert r.model == "spatial"
        slope[phi] = (r.lambda_max - square.lambda_max) / phi
    scale = square.lambda_max / 10.0  # lambda per degree: the slopes are about 1.5e-2 lambda
    for h in (1e-3, 1e-4):
        assert abs(slope[h] - slope[-h]) < 1e-3 * scale, slope
    assert abs(slope[1e-3] - slope[1e-4]) < 1e-3 * scale, slope


def test_a_wheel_loads_the_courses_under_its_patch_spread_in_both_directions():
    """A 100 kN wheel (0.3 m square patch) at (0.1, 0.1) near the crown of a bridge of four
    0.5 m courses: through the fill it spreads at 1 horizontal to 2 vertical on all four
    sides, so its patch is ``w = 0.3 + h`` square (``h`` the fill under the wheel: the road
    0.3 m over the crown's extrados, the crown voussoir's extrados chord worked out here), and
    each course and each voussoir takes its share of that square by area."""
    b = arch_bridge(depth=2.0, courses=4, **BRIDGE)
    v = Vehicle(axles=((0.0, 100.0),), patch=(0.3, 0.3), x=0.1, y=0.1)
    (wheel,), notes = wheel_loads(v, b, "vehicle[0]", Fill(**FILL))
    assert notes == []
    # the segmental ring: R = (s^2/4 + f^2) / 2f, centre at z = f - R; 8 joints at equal angles
    s, f, t = BRIDGE["span"], BRIDGE["rise"], BRIDGE["thickness"]
    R = (s**2 / 4 + f**2) / (2 * f)
    half = np.arctan2(s / 2, R - f)
    a = np.pi / 2 - 2 * half / 8  # the joint right of the crown joint (x = 0)
    crown, joint = np.array([0.0, f - R + R + t]), np.array([(R + t) * np.cos(a), f - R + (R + t) * np.sin(a)])
    z = crown[1] + (joint[1] - crown[1]) * 0.1 / joint[0]
    w = 0.3 + (crown[1] + FILL["depth"] - z)
    share = {}
    for block, _, fz in wheel.parts:
        name = b.names[block]
        share[name[2:5], name[5:]] = share.get((name[2:5], name[5:]), 0.0) - fz
    below = (w / 2 - 0.1) / w  # of the square's side on the side y < 0 (and x < 0)
    assert sorted(share) == [("c02", "v04"), ("c02", "v05"), ("c03", "v04"), ("c03", "v05")]
    assert share["c02", "v04"] + share["c02", "v05"] == pytest.approx(100.0 * below, rel=1e-9)
    assert share["c02", "v04"] + share["c03", "v04"] == pytest.approx(100.0 * below, rel=1e-9)
    assert share["c02", "v04"] == pytest.approx(100.0 * below**2, rel=1e-9)
