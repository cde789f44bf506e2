"""Crushing in an arch: tce's joints cut into strips with a finite compressive strength against an
independent convex program of the same arch with rigid-plastic stress blocks at its joints.

No published arch with a finite compressive strength could be read with its numbers
(docs/validation.md). The reference (tests/reference/lateral_arch.py, ``strength``) keeps the
compressed zone ``N / (fc d)`` of every joint inside the ring, centred on the pressure point,
which is the stress block of one block (tests/validation/literature/test_lit_stress_block.py)
at every joint: ``ri + N/(2 fc d) <= rho <= re - N/(2 fc d)``. tce bounds each strip's
vertex forces by ``fc`` times their tributary areas, so a joint of ``k`` strips is that stress
block up to a fraction of a strip: its capacity is an upper estimate that reaches the reference
as the strips are refined (exactly when the compressed zones are whole numbers of strips).

Semicircular arch, centreline radius 1 m, t/R = 0.15, 14 voussoirs, depth 0.25 m, 20 kN/m^3,
lateral load along +x, no sliding:

| fc (kN/m^2) | reference | 4 strips | 16 strips | 32 strips | 64 strips | 128 strips |
|---|---|---|---|---|---|---|
| unlimited | 0.148502 | 0.148502 | | | | |
| 250 | 0.103045 | 0.145646 | 0.106022 | 0.103399 | 0.103072 | 0.103072 |
| 100 | 0.029916 | 0.041360 | 0.030846 | 0.029946 | 0.029946 | 0.029921 |
"""

import pytest

from reference import lateral_arch as ref
from tce import Analysis, Material, semicircular_arch
from tce.quality.validation import arch_in_strips

T, N = 0.15, 14


def capacity(strips: int, fc: float | None) -> float:
    arch = arch_in_strips(semicircular_arch(1.0 - T / 2.0, T, 0.25, N), strips)
    return Analysis(arch, Material(compressive_strength=fc)).limit(0.0).lambda_max


@pytest.mark.parametrize("fc", [100.0, 250.0])
def test_strips_reach_the_stress_blocks_from_above(fc):
    reference = ref.capacity(T, N, "facets", strength=fc / 20.0)  # fc / (gamma R)
    assert reference < ref.capacity(T, N, "facets")  # crushing costs capacity
    coarse, fine = capacity(4, fc), capacity(64, fc)
    assert coarse > fine >= reference - 1e-6
    assert fine - reference < 5e-5


def test_strips_change_nothing_without_a_compressive_strength():
    assert capacity(8, None) == pytest.approx(ref.capacity(T, N, "facets"), abs=2e-7)


def test_weak_arch_does_not_stand():
    """fc = 40 kN/m^2 (fc / (gamma R) = 2): no admissible state, in the reference as in tce."""
    assert ref.capacity(T, N, "facets", strength=2.0) is None
    r = Analysis(arch_in_strips(semicircular_arch(1.0 - T / 2.0, T, 0.25, N), 16),
                 Material(compressive_strength=40.0)).solve(0.0)
    assert r.status == "infeasible"


@pytest.mark.parametrize("strips", [0, 2.5, True])
def test_strips_must_be_a_whole_number(strips):
    with pytest.raises(ValueError, match="strips must be a whole number"):
        arch_in_strips(semicircular_arch(), strips)
