"""Boussinesq's dispersion of wheel loads through fill (tce.core.fill, ``dispersion =
"boussinesq"``) against numerical integration of the elastic point-load stress
(tests/reference/boussinesq.py, scipy dblquad; never imports tce): the closed forms over a
rectangle, and the share and point of a wheel's load on every voussoir of the 6 m ring."""

from __future__ import annotations

import numpy as np
import pytest

from tce.core.fill import Fill, boussinesq_rectangle, road_level
from tce.core.loads import LoadError
from tce.core.vehicles import Vehicle, wheel_loads
from tce.structures.arch import segmental_arch
from tce.structures.dome import hemispherical_dome

from reference import boussinesq
from reference.funicular import joints


@pytest.mark.parametrize("rect", [(-0.3, 0.5, -1.0, 2.0), (0.2, 0.9, 0.1, 0.4), (-2.0, -0.1, -0.5, 0.5), (-5.0, 5.0, -5.0, 5.0)])
@pytest.mark.parametrize("h", [0.1, 0.4, 1.5])
def test_rectangle_integrals_equal_numerical_integration(rect, h):
    got = boussinesq_rectangle(*rect, h)
    ref = boussinesq.rectangle(*rect, h)
    np.testing.assert_allclose(got, ref, rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("x", [-2.1, -0.95, 0.0, 1.3])
def test_wheel_share_and_point_on_each_voussoir(x):
    ring = segmental_arch(span=6.0, rise=1.5, thickness=0.4, depth=3.0, voussoirs=12, unit_weight=20.0)
    fill = Fill(depth=0.3, unit_weight=18.0, dispersion="boussinesq")
    wheel = Vehicle(axles=((0.0, 100.0),), wheels=(0.5,)).at(x)  # 0.5 m off the centre line
    (load,), notes = wheel_loads(wheel, ring, "vehicle[0]", fill)
    _, E = joints(6.0, 1.5, 0.4, 12)
    zx = np.interp(x, E[:, 0], E[:, 1])  # the extrados under the wheel (chords)
    h = road_level(ring, fill) - zx
    assert h == pytest.approx(1.9 + 0.3 - zx, rel=1e-12)
    got = {ring.names[i]: (fz, p) for i, p, fz in load.parts}
    total = 0.0
    for k in range(12):
        f, mu, _ = boussinesq.rectangle(E[k, 0] - x, E[k + 1, 0] - x, -1.5 - 0.5, 1.5 - 0.5, h)
        fz, p = got[f"v{k + 1:02d}"]
        assert -fz == pytest.approx(100.0 * f, rel=1e-8, abs=1e-10)
        assert p[0] == pytest.approx(x + mu / f, abs=1e-8)
        total += f
    assert len(notes) == 1 and f"{100.0 * (1.0 - total):.3g}%" in notes[0]  # the tail beyond the deck


def test_pieces_that_are_not_rectangles_are_refused():
    dome = hemispherical_dome()
    fill = Fill(depth=0.3, unit_weight=18.0, dispersion="boussinesq")
    with pytest.raises(LoadError, match="not a rectangle in plan"):
        wheel_loads(Vehicle(axles=((0.0, 1.0),)).at(0.3), dome, "vehicle[0]", fill)


@pytest.mark.parametrize("kw", [dict(dispersion="elastic"), dict(dispersion="boussinesq", depth=0.0)])
def test_bad_boussinesq_declarations_name_the_key(kw):
    with pytest.raises(LoadError, match="dispersion"):
        Fill(**dict(dict(depth=0.3, unit_weight=18.0), **kw))
