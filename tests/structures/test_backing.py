"""Backing blocks and fill on the arch generators (:mod:`tce.structures.backing`)."""

from __future__ import annotations

import numpy as np
import pytest

from tce.structures.arch import pointed_arch, segmental_arch, semicircular_arch, semicircular_arch_on_piers
from tce.structures.backing import BACKING, Backing
from tce.structures.bridge import arch_bridge
from tce.structures.contacts import detect_interfaces

from structures.test_contacts import _same_interfaces


@pytest.mark.parametrize("asm", [
    semicircular_arch(1.0, 0.12, 0.25, 10, backing=Backing(0.6)),
    segmental_arch(2.0, 0.6, 0.2, 0.25, 8, backing=Backing(0.5, 22.0)),
    pointed_arch(2.0, thickness=0.2, voussoirs=9, rings=2, stagger=True, backing=Backing(0.8)),
    semicircular_arch_on_piers(1.0, 0.2, 0.25, 10, 1.5, rings=3, backing=Backing(0.45)),
    arch_bridge(3, 4.0, 1.0, 0.3, 1.0, 6, pier_width=0.8, pier_height=1.0, backing=Backing(0.6)),
    arch_bridge(2, 4.0, 1.0, 0.3, 1.0, 6, pier_width=0.8, pier_height=1.0, piers="fixed", rings=3, stagger=True,
                backing=Backing(0.6)),
], ids=["semicircular", "segmental", "pointed-staggered-rings", "on-piers-3-rings", "bridge-3-spans",
        "bridge-fixed-piers-rings"])
def test_detection_finds_exactly_the_generator_interfaces(asm):
    """The backing's faces with the extrados and the abutments are those contact detection finds."""
    asm.validate()
    _same_interfaces(asm, detect_interfaces(asm))
    kinds = asm.interface_table.kind
    # per side: the chords under the height and the abutment behind
    assert (kinds == BACKING).sum() == sum(1 for i in asm.interfaces if asm.blocks[i.b].name.startswith(("backing_", "wall_")))
    assert asm.support_names[-2:] == ("wall_left", "wall_right")
    piers = [name for name in asm.names if name.startswith("pier")]
    assert [name for name in asm.names if name.startswith("backing_pier")] == [f"backing_{p}" for p in piers]


def test_the_backing_top_is_at_its_height_and_its_back_over_the_springing():
    asm = segmental_arch(2.0, 0.6, 0.2, 0.25, 8, backing=Backing(0.5))
    left = asm.blocks[asm.index["backing_left"]].shape.vertices
    springing = asm.blocks[asm.index["left"]].shape.vertices
    assert left[:, 2].max() == pytest.approx(0.5, abs=1e-15)
    assert left[:, 0].min() == pytest.approx(springing[:, 0].min(), abs=1e-15)
    assert asm.meta["backing"] == dict(height=0.5, unit_weight=20.0, model="blocks")


def test_fill_makes_the_voussoirs_under_it_heavier_and_adds_no_block():
    bare = semicircular_arch(1.0, 0.2, 0.25, 10)
    fill = semicircular_arch(1.0, 0.2, 0.25, 10, backing=Backing(0.5, model="fill"))
    assert fill.names == bare.names and len(fill.interfaces) == len(bare.interfaces)
    heavier = [b.name for b, c in zip(fill.blocks, bare.blocks) if b.weight > c.weight]
    assert heavier == ["v01", "v02", "v09", "v10"]  # the extrados reaches 0.5 m within the second voussoir
    assert np.isclose(fill.blocks[1].weight, fill.blocks[10].weight)


@pytest.mark.parametrize("make, words", [
    (lambda: semicircular_arch(1.0, 0.2, 0.25, 10, backing=Backing(1.2)), "reaches the extrados' crown"),
    (lambda: semicircular_arch(1.0, 0.2, 0.25, 10, joints="vertical", backing=Backing(0.3)), "radial"),
    (lambda: Backing(-0.1), "height"),
    (lambda: Backing(0.3, 0.0), "unit_weight"),
    (lambda: Backing(0.3, model="rubble"), "model"),
    (lambda: arch_bridge(2, 4.0, 1.0, 0.3, 1.0, 6, courses=2, backing=Backing(0.5)), "one course"),
])
def test_errors(make, words):
    with pytest.raises(ValueError, match=words):
        make()
