"""Gilbert, Casapulla & Ahmed (2006): the 27-block semicircular arch, non-associative friction.

Source: Gilbert, M., Casapulla, C. & Ahmed, H. M. (2006). Limit analysis of masonry block
structures with non-associative frictional joints using linear programming. *Computers &
Structures* 84, 873-887, doi:10.1016/j.compstruc.2006.02.005. Their figure of the least
thickness of a semicircular arch of 27 blocks under self-weight against the friction
coefficient (0.2 to 0.8), as reproduced in the Solfec-1.0 validation pages ("after Gilbert et
al."; parmes/parmes, solfec-1.0/validation/masonry_arch/arch-modes.png): mode I (hinges only)
above mu = 0.3958 at thickness 1.072, mode II (hinges and sliding) at 0.375, 0.35, 0.325 and
0.3109 (1.2645, 1.5167, 1.785, 1.954), mode III (sliding, no equilibrium) below. The paper's
text was not accessible: the values were read off the figure's pixels (marker centroids
against the tick marks, +-1 px: +-0.011 in thickness, +-0.0007 in mu); its axis gives no radius,
and a centreline radius of 10 is assumed (the Solfec pages model it so, and mode I then gives
Heyman's t/R of about 0.107).

tce: ``semicircular_arch`` with 27 radial voussoirs, centreline radius 1. The least thickness
is the one at which an admissible state exists; it is the non-associative one because the
non-associative scheme at 1.001 times it closes the bracket (``lambda_nonassoc =
lambda_assoc > 0``: the sliding joints of mode II are statically determinate), which
``nonassoc_min_ratio`` checks. tce lies 3e-4 to 5e-4 below every read point (half a pixel);
the discretisation is the paper's (27 blocks), so there is no convergence to show: the figure
of docs/validation.md draws tce's curve at 27 voussoirs through the read points, with 160
voussoirs and CR2020's continuous values beside it.
"""

import pytest
from _atlas import check_case

from tce import Analysis, Material
from tce.analysis.nonassoc import nonassociative_limit
from tce.quality.validation import GCA_VOUSSOIRS, NONASSOC_CASES, _arch, min_ratio

NAMES = [c.name for c in NONASSOC_CASES if c.name.startswith("gca_")]


@pytest.mark.parametrize("name", NAMES)
def test_published_value(name):
    check_case(name)


@pytest.mark.parametrize(("mu", "mode_sliding"), [(0.8, False), (0.35, True)])
def test_modes_and_the_closed_bracket(mu, mode_sliding):
    """Just above the least thickness the collapse is mode I (hinges) at mu 0.8 and mode II
    (hinges and sliding) at 0.35, as in the figure; either way the non-associative estimate is
    the associative limit (the bracket is closed), and just below it nothing stands."""
    t = min_ratio(GCA_VOUSSOIRS, mu=mu, tol=1e-7)
    above = Analysis(_arch(t * 1.001, GCA_VOUSSOIRS), Material(mu, flow="non-associative"))
    assert ("sliding" in above.limit(0.0).mechanism.modes) is mode_sliding
    r = nonassociative_limit(above, 0.0)
    assert r.status == "converged" and r.lambda_assoc > 0
    assert r.lambda_nonassoc == pytest.approx(r.lambda_assoc, rel=1e-6)
    below = Analysis(_arch(t * 0.999, GCA_VOUSSOIRS), Material(mu, flow="non-associative"))
    assert below.solve(0.0).status == "infeasible"


def test_an_open_bracket_gives_no_value(monkeypatch):
    """tce's value is the non-associative least thickness only when the bracket is closed at
    1.001 times it: an estimate below the associative limit there gives NaN (never ok)."""
    from dataclasses import replace

    from tce.quality import validation

    real = validation.nonassociative_limit

    def lower(*args, **kwargs):
        r = real(*args, **kwargs)
        return replace(r, lambda_nonassoc=r.lambda_assoc * (1 - 1e-4))

    monkeypatch.setattr(validation, "nonassociative_limit", lower)
    assert validation.nonassoc_min_ratio(0.35) != validation.nonassoc_min_ratio(0.35)  # NaN
