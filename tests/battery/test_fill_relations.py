"""The fill (weight, at-rest pressure, passive restraint) in the battery's relations: the
direct limit of a segmental ring under fill and a live ``on_top`` point load is the same
after a rotation about z (the ring then spans another direction: the planar model is left
for the spatial one at 30 degrees), a mirror, a translation and a change of units (mm, N),
and with the live load split in halves. A frame, unit or direction leaking into the
passive restraint's directions, bounds or moments would change it."""

from __future__ import annotations

from dataclasses import replace

import pytest

from tce.core.analysis import Analysis
from tce.core.fill import Fill
from tce.core.loads import LoadPattern, PointLoad
from tce.structures.arch import segmental_arch

from .transform import Similarity

RING = segmental_arch(span=6.0, rise=1.5, thickness=0.3, depth=1.0, voussoirs=8, unit_weight=20.0).validate()
FILL = Fill(depth=0.3, unit_weight=18.0, k0=0.5, kp=3.0, dispersion=0.0)
PATTERN = LoadPattern(lateral=False, point=[PointLoad(force=(0.0, 0.0, -50.0), on_top=(-1.7, 0.1))], fill=FILL)


def lam(asm, pattern) -> float:
    res = Analysis(asm).limit(loads=pattern, mechanism=False)
    assert res.status == "optimal"
    return res.lambda_max


def mapped_fill(t: Similarity) -> Fill:
    return replace(FILL, depth=FILL.depth * t.length, unit_weight=FILL.unit_weight * t.force / t.length**3)


BASE = lam(RING, PATTERN)


@pytest.mark.parametrize("t", [Similarity.rotation(90.0), Similarity.rotation(30.0), Similarity.mirror(0.0),
                               Similarity.translation([2.0, -1.0, 0.5]), Similarity.units(1000.0, 1000.0)],
                         ids=["rot90", "rot30", "mirror", "translate", "mm_N"])
def test_direct_limit_with_passive_restraint_is_invariant(t):
    pattern = replace(t.pattern(PATTERN), fill=mapped_fill(t))
    assert lam(t.assembly(RING), pattern) == pytest.approx(BASE, rel=1e-7)


def test_split_live_load_gives_the_same_limit():
    half = PointLoad(force=(0.0, 0.0, -25.0), on_top=(-1.7, 0.1))
    assert lam(RING, replace(PATTERN, point=(half, half))) == pytest.approx(BASE, rel=1e-8)


def test_passive_restraint_matters_here():
    # the relation is not empty: without kp the limit is lower
    assert lam(RING, replace(PATTERN, fill=replace(FILL, kp=0.0))) < 0.9 * BASE


@pytest.mark.parametrize("t", [Similarity.translation([0.0, 0.0, 0.0]), Similarity.rotation(30.0), Similarity.mirror(0.0),
                               Similarity.units(1000.0, 1000.0)], ids=["none", "rot30", "mirror", "mm_N"])
def test_load_path_with_passive_restraint_brackets_the_same_limit(t):
    # the TCE force states carry the restraint (tce.core.problem.restrained_tce_problem): the
    # load path's bracket holds the untransformed direct limit, in any frame and units
    from tce.analysis.loadpath import load_path

    pattern = replace(t.pattern(PATTERN), fill=mapped_fill(t))
    path = load_path(Analysis(t.assembly(RING)), loads=pattern, atol=0.0, rtol=1e-6)
    assert path.status == "limit"
    assert path.lambda_max <= BASE * (1 + 1e-7) and BASE <= path.lambda_upper * (1 + 1e-7)
