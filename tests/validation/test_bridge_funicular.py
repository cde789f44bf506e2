"""Why a tandem straddling the crown of the 6 m bridge (studies/bridge_fill.toml) is carried
at any multiplier: the two axle loads' own funicular polygon crosses every joint inside the
0.4 m ring, so rigid voussoirs that neither crush nor slide carry them at any magnitude
(Heyman). tce's direct limit is ``unbounded`` exactly where the independent funicular LP of
tests/reference/funicular.py (HiGHS, its own geometry; never imports tce) finds such a
polygon, and finite elsewhere; a finite crushing strength makes it finite everywhere."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tce.core.analysis import Analysis
from tce.core.fill import Fill
from tce.core.loads import LoadPattern
from tce.core.material import Material
from tce.core.vehicles import Vehicle, standard_vehicle
from tce.structures.arch import segmental_arch

from reference.funicular import carried_at_any_magnitude

SPAN, RISE, T, N = 6.0, 1.5, 0.4, 12
RING = segmental_arch(span=SPAN, rise=RISE, thickness=T, depth=3.0, voussoirs=N, unit_weight=20.0)
AN = Analysis(RING)
# every reference position of a 1.2 m tandem with both axles on the ring, at 0.05 m
POSITIONS = np.round(np.arange(-2.95, 1.75 + 1e-9, 0.05), 10)


@pytest.mark.parametrize("ratio", [1.0, 1.5])
def test_unbounded_exactly_where_the_loads_funicular_fits(ratio):
    pattern = LoadPattern(lateral=False, vehicle=[Vehicle(axles=((0.0, 100.0), (1.2, 100.0 * ratio)))])
    fits = np.array([carried_at_any_magnitude(SPAN, RISE, T, N, x, x + 1.2, ratio) > 1e-9 for x in POSITIONS])
    lam = np.array([AN.limit(loads=pattern.moved(float(x)), mechanism=False).lambda_max for x in POSITIONS])
    assert fits.sum() >= 10 and (~fits).sum() >= 10  # both kinds of position are tested
    assert np.array_equal(np.isinf(lam), fits), POSITIONS[np.isinf(lam) != fits]
    assert np.all(np.isfinite(lam[~fits]) & (lam[~fits] > 0))


def test_bridge_fill_tandem_over_the_crown_is_unbounded_until_the_masonry_may_crush():
    # studies/bridge_fill.toml at the symmetric position (axles at -0.6 and +0.6 m): the LM1
    # tandem's patches dispersed 2:1 through 0.3 m of fill, fill weight and k0 = 0.5
    pattern = LoadPattern(lateral=False, vehicle=[standard_vehicle("en1991_lm1_tandem_lane1")],
                          fill=Fill(depth=0.3, unit_weight=18.0, k0=0.5))
    assert carried_at_any_magnitude(SPAN, RISE, T, N, -0.6, 0.6) > 0.5
    assert AN.limit(loads=pattern.moved(-0.6), mechanism=False).status == "unbounded"
    crushing = Analysis(RING, material=Material(compressive_strength=5000.0))  # 5 MPa
    res = crushing.limit(loads=pattern.moved(-0.6), mechanism=False)
    assert res.status == "optimal" and math.isfinite(res.lambda_max)
