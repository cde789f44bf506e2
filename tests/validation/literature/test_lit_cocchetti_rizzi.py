"""Cocchetti & Rizzi (2020): the least-thickness semicircular arch at decreasing friction.

Source: Cocchetti, G. & Rizzi, E. (2020). Analytical and numerical analysis on the collapse
modes of least-thickness circular masonry arches at decreasing friction. *Frattura ed
Integrità Strutturale* 51, 356-375, doi:10.3221/IGF-ESIS.51.26.

Published (Table 3, Fig. 7; complete semicircular arch, radial joints, self-weight, Coulomb
friction mu at the joints, Heyman otherwise). "continuous LP" is tests/reference/continuous_arch.py,
the static problem of the continuous ring written without tce (2000 cuts), with each portion's
weight lumped on the centreline arc ("centreline", CR2020's assumption: it reproduces Table 3
digit by digit) or at the ring's own centroid ("ring", what rigid voussoirs carry). tce's cases
take CR2020's assumption too: each voussoir's own weight is lifted at its centroid and its ring
sector's weight hung on the centreline arc (tce.quality.validation.centreline_weights), so that
tce's value converges on the published one and the only difference left is the discretisation:

| quantity | published | continuous LP, centreline | tce, centreline, 160 voussoirs | error | tolerance | continuous LP, ring |
|---|---|---|---|---|---|---|
| t/R, purely rotational (mu > mu_rm) | 0.107426 | 0.10742605 | 0.1074077 | 1.9e-5 | 3.8e-5 | 0.1074776 |
| crown thrust h = H/(gamma d R t) there | 0.621772 | 0.621772 | 0.621763 | 1e-5 | 2e-5 | 0.620882 |
| mu_rm (sliding joins the hinges below it; at t/R x (1 + 1e-6)) | 0.395832 | 0.3958318 | 0.3958264 | 6e-6 | 1.2e-5 | 0.395264 |
| mu_ms (no equilibrium below it) | 0.309215 | 0.3092153 | 0.309183 (either weights) | 3.3e-5 | 6.6e-5 | 0.3092153 |
| t/R at mu_ms | 0.200637 | 0.2006366 | 0.2006715 | 3.5e-5 | 7e-5 | 0.198610 |
| h at mu_ms | 0.485714 | 0.4857144 | 0.4856635 | 5.1e-5 | 1.02e-4 | 0.485714 |

Every continuous value rounds to the published one at its six printed digits. The error is
tce's at 160 voussoirs against the continuous LP: the joints, every 1.125 deg, sample the
hinges and sliding sections of the continuous ring, so the values converge in steps with the
voussoirs rather than as a power of them (docs/validation.md). Each tolerance is twice that
error. With the ring's own centroids (tce's arch as it is) the values move to the last column:
a difference of assumptions, not of method, and no tolerance covers it.
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


def test_purely_rotational_least_thickness_is_heymans_above_mu_rm():
    """With mu = 0.5 > mu_rm nothing slides: the least thickness is the one without sliding
    (what the cr_eta_rotational case computes)."""
    assert min_ratio(40, mu=0.5, tol=1e-7) == pytest.approx(min_ratio(40, mu=None, tol=1e-7), abs=2e-8)


def test_tce_agrees_with_the_continuous_ring_where_it_departs_from_the_table():
    """The difference to Table 3 is not tce's: an LP of the continuous ring with the ring's own
    centroids gives tce's value (two solves bracket it)."""
    assert ref.stands(0.107479, m=500) and not ref.stands(0.107476, m=500)
    assert min_ratio(mu=None) == pytest.approx(0.1074777, abs=3e-5)  # 160 voussoirs, from below


def test_centreline_weights_give_table_3():
    """The explanation: lumping each portion's weight on the centreline reproduces Table 3's
    t/R = 0.107426, h = 0.621772 and, at mu_ms = 0.309215, t/R = 0.200637 (each bracketed)."""
    kw = dict(m=500, weight="centreline")
    assert ref.stands(0.1074270, **kw) and not ref.stands(0.1074250, **kw)
    lo, hi = ref.thrust_range(0.1074262, **kw)
    assert lo == pytest.approx(0.621772, abs=2e-5) and hi == pytest.approx(0.621772, abs=2e-5)
    assert ref.stands(0.200645, mu=0.3092154, **kw) and not ref.stands(0.200625, mu=0.3092154, **kw)
    at = 0.1074259 * (1 + 1e-5)  # just above the least thickness: mu_rm = 0.395831 brackets
    assert ref.stands(at, mu=0.39585, **kw) and not ref.stands(at, mu=0.39581, **kw)
    # with the ring's own centroids mu_rm moves to 0.395264, where tce's 0.395278 lies
    at = 0.1074777 * (1 + 1e-5)
    assert ref.stands(at, mu=0.39529, m=500) and not ref.stands(at, mu=0.39524, m=500)


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
