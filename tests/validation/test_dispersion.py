"""The fill's spread-angle dispersion of a wheel load (tce.core.fill, ``dispersion`` in degrees)
against its closed form: a point wheel at road level spreads through the fill to the extrados as
the square ``2 h tan(theta)`` wide, ``h`` the fill under the wheel's centre, under a uniform
pressure; each voussoir takes the load on the part of the square above it (the overlap of the
square with the voussoir's plan, the extrados by chords: tests/reference/funicular.py, which never
imports tce), at that part's plan centroid."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tce.core.fill import Fill, road_level
from tce.core.vehicles import Vehicle, wheel_loads
from tce.structures.arch import segmental_arch

from reference.funicular import joints


@pytest.mark.parametrize("theta", [26.565051177077994, 15.0])
@pytest.mark.parametrize("x", [-2.1, -0.95, 0.0, 1.3])
def test_wheel_share_and_point_on_each_voussoir(x, theta):
    ring = segmental_arch(span=6.0, rise=1.5, thickness=0.4, depth=3.0, voussoirs=12, unit_weight=20.0)
    fill = Fill(depth=0.3, unit_weight=18.0, dispersion=theta)
    wheel = Vehicle(axles=((0.0, 100.0),), wheels=(0.0,)).at(x)  # on the centre line: the square stays on the deck
    (load,), _ = wheel_loads(wheel, ring, "vehicle[0]", fill)
    _, E = joints(6.0, 1.5, 0.4, 12)
    h = road_level(ring, fill) - np.interp(x, E[:, 0], E[:, 1])
    s = h * math.tan(math.radians(theta))  # half the side of the square at the extrados
    assert 0.0 < s < 1.5
    got = {ring.names[i]: (fz, p) for i, p, fz in load.parts}
    total = 0.0
    for k in range(12):
        a, b = max(E[k, 0], x - s), min(E[k + 1, 0], x + s)
        name = f"v{k + 1:02d}"
        if b <= a:
            assert name not in got or got[name][0] == pytest.approx(0.0, abs=1e-10)
            continue
        share = (b - a) / (2.0 * s)
        fz, p = got[name]
        assert -fz == pytest.approx(100.0 * share, rel=1e-9)
        assert p[0] == pytest.approx(0.5 * (a + b), abs=1e-9)
        assert p[1] == pytest.approx(0.0, abs=1e-9)
        total += share
    assert total == pytest.approx(1.0, rel=1e-12)
