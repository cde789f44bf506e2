"""The semicircular arch under a horizontal acceleration: tce's lateral capacity against an
independent LP (tests/reference/lateral_arch.py), over the thickness ratio t/R.

No published value of this curve could be read (Ochsendorf 2002; DeJong 2009; Alexakis &
Makris 2014; docs/validation.md says what was searched), so the reference is the static problem
of the same arch written without tce: the reaction at the left springing and the multiplier as
unknowns, the pressure point of every joint inside the ring. Over the voussoirs' own joints and
chord-faced voussoirs (``shell="facets"``) it is the block model's problem in one plane, and tce
(3D blocks, contact forces at the vertices) agrees to 1e-7; over a fine ring (``shell="ring"``)
it is the continuous arch, which the voussoirs approach from above.
"""

import pytest

from reference import lateral_arch as ref
from tce import Analysis, Material, semicircular_arch


def capacity(t: float, n: int) -> float:
    """tce's lambda_max of the arch of centreline radius 1 m, thickness ratio t, n voussoirs."""
    return Analysis(semicircular_arch(1.0 - t / 2.0, t, 0.25, n), Material()).limit(0.0).lambda_max


@pytest.mark.parametrize("t", [0.12, 0.15, 0.2, 0.3, 0.5])
@pytest.mark.parametrize("n", [14, 40])
def test_tce_equals_the_lp_of_its_voussoirs(t, n):
    assert capacity(t, n) == pytest.approx(ref.capacity(t, n, "facets"), abs=2e-7)


def test_voussoirs_converge_on_the_continuous_arch_from_above():
    """Fewer joints, fewer places for a hinge: 14 and 40 voussoirs carry more than the ring."""
    ring = ref.capacity(0.15, 2000)
    assert ring == pytest.approx(0.14433, abs=2e-5)
    assert capacity(0.15, 14) > capacity(0.15, 40) > ring
    assert capacity(0.15, 40) - ring < 5e-4


def test_no_capacity_below_the_least_thickness():
    """Below Milankovitch's t/R = 0.1075 the arch does not stand: no multiplier in the LP either."""
    assert ref.capacity(0.105, 2000) is None
    assert ref.capacity(0.108, 2000) == pytest.approx(0.0, abs=5e-3)
