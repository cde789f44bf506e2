"""tce.structures.defects: each defect changes what it names and nothing else, and names what
it cannot find."""

from __future__ import annotations

import numpy as np
import pytest

from tce.structures.arch import RING, semicircular_arch
from tce.structures.assembly import AssemblyError
from tce.structures.defects import with_joint_loss, with_kinds, with_unit_weights, without_blocks, without_joints

ARCH = semicircular_arch(1.0, 0.3, 0.25, 6, rings=2, stagger=True)


def test_without_blocks_renumbers_the_interfaces():
    asm = without_blocks(ARCH, ["r2v03"])
    names = [(asm.names[i.a], asm.names[i.b]) for i in asm.interfaces]
    before = [(ARCH.names[i.a], ARCH.names[i.b]) for i in ARCH.interfaces]
    assert names == [n for n in before if "r2v03" not in n]
    assert [i.kind for i in asm.interfaces].count(RING) == 12 - 2


def test_unit_weights_and_kinds_change_only_what_they_name():
    asm = with_unit_weights(ARCH, {"r1v02": 10.0})
    assert asm.blocks[asm.index["r1v02"]].unit_weight == 10.0
    assert [b.unit_weight for b in asm.blocks if b.name != "r1v02"] == [20.0] * (len(ARCH.blocks) - 1)
    relabelled = with_kinds(ARCH, {"r1v02|r1v01": "cracked"})
    kinds = [i.kind for i in relabelled.interfaces]
    assert kinds.count("cracked") == 1 and kinds.count(RING) == 12


def test_separated_ring_faces_carry_nothing():
    asm = without_joints(ARCH, ["r1v01|r2v01", "r1v01|r2v02"])
    assert len(asm.interfaces) == len(ARCH.interfaces) - 2


def test_joint_loss_keeps_the_strip_between_the_depths():
    joint = "r1v02|r1v03"
    k = next(k for k, i in enumerate(ARCH.interfaces) if {ARCH.names[i.a], ARCH.names[i.b]} == {"r1v02", "r1v03"})
    before = ARCH.interfaces[k]
    after = with_joint_loss(ARCH, joint, intrados=0.02, extrados=0.03).interfaces[k]
    depth = 0.15  # the ring's thickness: the joint runs from the intrados to the ring boundary
    assert after.area == pytest.approx(before.area * (depth - 0.05) / depth, rel=1e-12)
    np.testing.assert_allclose(after.normal, before.normal)
    assert np.all(np.abs((after.points - before.points[0]) @ before.normal) < 1e-12)  # in the joint's plane
    r = np.hypot(after.points[:, 0], after.points[:, 2])
    assert r.min() == pytest.approx(1.02) and r.max() == pytest.approx(1.12)


@pytest.mark.parametrize("call, words", [
    (lambda: without_blocks(ARCH, ["nope"]), "unknown block"),
    (lambda: without_joints(ARCH, ["r1v01|r1v03"]), "no joint"),
    (lambda: with_joint_loss(ARCH, "r1v02|r1v03", intrados=0.1, extrados=0.1), "leaves no contact"),
    (lambda: with_joint_loss(ARCH, "r1v02|r1v03", intrados=-0.1), ">= 0"),
])
def test_errors_name_what_is_wrong(call, words):
    with pytest.raises(AssemblyError, match=words):
        call()
