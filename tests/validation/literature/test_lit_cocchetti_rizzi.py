"""Cocchetti & Rizzi (2020): the least-thickness semicircular arch at decreasing friction.

Source: Cocchetti, G. & Rizzi, E. (2020). Analytical and numerical analysis on the collapse
modes of least-thickness circular masonry arches at decreasing friction. *Frattura ed
Integrità Strutturale* 51, 356-375, doi:10.3221/IGF-ESIS.51.26.

Published (Table 3, Fig. 7; complete semicircular arch, radial joints, self-weight, Coulomb
friction mu at the joints, Heyman otherwise):

| quantity | published | tce, 160 voussoirs | tce, 640 voussoirs | continuous LP |
|---|---|---|---|---|
| t/R, purely rotational (mu > mu_rm) | 0.107426 | 0.107458 | 0.107477 | 0.107478 |
| crown thrust h = H/(gamma d R t) there | 0.621772 | 0.62086 | - | 0.62088 |
| mu_rm (sliding joins the hinges below it) | 0.395832 | 0.39528 | docs/validation.md | - |
| mu_ms (no equilibrium below it) | 0.309215 | 0.309183 | docs/validation.md | 0.3092153 |
| t/R at mu_ms | 0.200637 | 0.19865 | docs/validation.md | - |
| h at mu_ms | 0.485714 | 0.48563 | - | - |

tce's values come from the discrete arch (joints every 180/n degrees, supports as blocks);
"continuous LP" is ``tests/reference/continuous_arch.py``, the static problem of the continuous
ring written from the problem statement without tce. tce and the continuous LP agree to 2e-7
in t/R at 640 voussoirs, so the residual 5.2e-5 between them and the printed 0.107426 is not a
discretisation error; Milankovitch's value as Makris & Alexakis quote it (0.1075) agrees.
Where the published solution loses those 5e-5 was not found (the same shift shows in h).
Tolerances (tce.quality.validation.CASES): 1e-4 on t/R (the 5e-5 above plus the 160-voussoir
discretisation, 2e-5), 2e-3 on mu_rm (the discrete joints sample the continuous T/N curve),
2e-4 on mu_ms, 4e-3 on t/R at mu_ms (t/R has a vertical tangent there: a shift of 1e-5 in
mu moves it by 1e-3), 2e-3 and 3e-3 on the thrusts.
"""

import pytest
from _atlas import check_case

from reference import continuous_arch as ref
from tce import Material
from tce.analysis.thickness import arch_minimum_thickness
from tce.quality.validation import min_ratio


@pytest.mark.parametrize(
    "name",
    ["cr_eta_rotational", "cr_thrust_rotational", "cr_mu_rotational", "cr_mu_sliding", "cr_eta_sliding",
     "cr_thrust_sliding"],
)
def test_published_value(name):
    check_case(name)


def test_tce_agrees_with_the_continuous_ring_where_it_departs_from_the_table():
    """The difference to Table 3 is not tce's: an LP of the continuous ring gives tce's value."""
    continuous = ref.minimum_thickness("radial", m=500, tol=1e-7)
    assert continuous == pytest.approx(0.107478, abs=2e-6)
    assert min_ratio(mu=None) == pytest.approx(continuous, abs=3e-5)  # 160 voussoirs, from below
    assert continuous - 0.107426 > 4e-5  # the published value is lower: stated in docs/validation.md


def test_mixed_mode_thickness_against_the_continuous_ring():
    """Between mu_ms and mu_rm sliding and hinging mix and t/R rises; at mu = 0.35 tce (80
    voussoirs) and the continuous ring agree to 1e-4 (Fig. 7's curve, read from no table)."""
    tce = arch_minimum_thickness(1.0, 80, material=Material(friction=0.35), tol=1e-6).ratio
    continuous = ref.minimum_thickness("radial", mu=0.35, m=500, tol=1e-7)
    assert tce == pytest.approx(continuous, abs=1e-4)
    assert tce > min_ratio(mu=None) + 0.04


def test_continuous_ring_has_the_published_mu_ms():
    """The continuous ring's least friction is Table 3's mu_ms = 0.309215 (bisected to 1e-8 in
    docs/make_validation_figures.py: 0.3092153); here it is bracketed by two solves."""
    assert ref.stands(0.25, mu=0.30923, m=500) and not ref.stands(0.25, mu=0.30920, m=500)


def test_no_equilibrium_below_mu_ms():
    """Below mu_ms = 0.309215 no thickness stands: not even t/R = 0.5 at mu = 0.30."""
    with pytest.raises(ValueError, match="does not stand at the upper thickness"):
        arch_minimum_thickness(1.0, 40, material=Material(friction=0.30), tol=1e-3)
