"""Crushing: one block with a finite compressive strength reaches the stress block's closed form.

Source: the rigid-plastic stress block (closed form, not a published table): a block b wide,
d deep, h tall, weight W, compressive strength fc; under a lateral load lam W at its centroid it
rotates about a compressed zone x = W / (fc d) at its toe, so lam = (b - W/(fc d)) / h. For
b = 0.4, d = 0.3, h = 1 m, W = 2.4 kN, fc = 40 kN/m^2: lam = 0.2 (the corner model, without
strips, keeps the rigid b/h = 0.4; docs/materials.md). tce with the base joint cut into n strips:
each strip keeps its resultant at its centre, so the error is at most half a strip's lever and
vanishes when x is a whole number of strips (x = 0.2 m: 20 strips of 0.01 m out of 40).
Tolerance 1e-9: exact up to the solver. No published arch with a finite compressive strength
was reproduced (docs/validation.md says why).
"""

import pytest
from _atlas import check_case

from tce.quality.validation import stress_block_column


def test_published_value():
    check_case("stress_block")


@pytest.mark.parametrize("strips", [1, 3, 7])
def test_fewer_strips_overestimate_and_converge(strips):
    """Coarse strips put the toe resultant further out: an upper estimate, within b / strips."""
    lam = stress_block_column(strips)
    assert 0.2 - 1e-9 <= lam <= 0.2 + 0.4 / strips
