"""Metamorphic relations of the finite-settlement path in space (tce against itself): the
dome under radial spread turned about z, shifted, mirrored, in mm and N, and with its blocks
listed in another order (some interfaces read from the other side) has the same capacity,
the same hinges and the same work of the reactions against the motion (transformed). The
capacity is compared as the last standing magnitude: beyond it HiGHS fails on the dome's
fall, so the outcome is ``numerical`` (``tests/validation/test_settlement_path_3d.py``)."""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import pytest

from battery.transform import Similarity, permuted
from tce.analysis.settlement_path import settlement_path
from tce.structures.dome import hemispherical_dome, radial_settlement

H = 0.02  # increment (m of radial spread); the capacity is bracketed to H / 64
#: outcomes of the dome's path: a collapse, or undecided where HiGHS fails on the fall beyond it
ENDS = ("collapse", "numerical")


def dome():
    return hemispherical_dome(radius=5.0, thickness=0.5, sectors=8, courses=4)


@lru_cache(maxsize=None)
def reference():
    d = dome()
    return settlement_path(d, radial_settlement(d, 1.0), increment=H, s_max=2.0)


def work(r, sett, names) -> float:
    """-sum_s R_s . u_s at s = 0: the work the TCE minimises (unique, unlike each reaction)."""
    u = np.array([sett.get(n, [0.0] * 6) for n in names], dtype=float)
    return float(-np.einsum("sj,sj->", r.wrenches()[0][:, :3], u[:, :3]))


@pytest.mark.parametrize(
    "S",
    [Similarity.rotation(30.0), Similarity.translation([3.0, -2.0, 1.5]), Similarity.mirror(20.0),
     Similarity.units(1000.0, 1000.0)],
    ids=["rotated_30", "shifted", "mirrored", "mm_N"],
)
def test_moved_scene_same_path(S):
    d = dome()
    ref = reference()
    sett = S.settlements(radial_settlement(d, 1.0))
    r = settlement_path(S.assembly(d), sett, increment=H, s_max=2.0)
    assert r.plane is None and r.status in ENDS and ref.status in ENDS
    assert r.magnitudes[-1] == pytest.approx(ref.magnitudes[-1], abs=H / 64 + 1e-9)
    assert r.hinges[0] == ref.hinges[0]
    w_ref = work(ref, radial_settlement(d, 1.0), d.support_names)
    assert work(r, sett, d.support_names) == pytest.approx(S.force * S.length * w_ref, rel=1e-7)


def test_permuted_blocks_same_path():
    d = dome()
    ref = reference()
    rng = np.random.default_rng(5)
    order = rng.permutation(len(d.blocks))
    ni = len(d.interfaces)
    p = permuted(d, order, rng.permutation(ni), rng.random(ni) < 0.5)
    r = settlement_path(p, radial_settlement(d, 1.0), increment=H, s_max=2.0)
    assert r.status in ENDS
    assert r.magnitudes[-1] == pytest.approx(ref.magnitudes[-1], abs=H / 64 + 1e-9)
    assert len(r.hinges[0]) == len(ref.hinges[0])
    assert work(r, radial_settlement(d, 1.0), p.support_names) == pytest.approx(
        work(ref, radial_settlement(d, 1.0), d.support_names), rel=1e-7)
