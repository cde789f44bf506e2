"""Backing behind the haunches (issue 40, item 2; :mod:`tce.structures.backing`).

- Backing of zero height, or below the extrados' springing, is the arch without backing: the
  same blocks and joints, the same lambda_max (of the lateral load).
- Backing blocks bonded to a Heyman arch raise lambda_max under a crown point load against no
  backing, and above the same blocks bearing without friction (the law of kind ``"backing"``
  is the one applied).
- Backing blocks on a frictionless bearing joint (the extrados and the walls behind) and the
  same backing as fill weight put the same vertical load on the arch (a bridge of two spans
  on a free pier too): under self-weight the arch's supports carry the same vertical load, to
  1e-8 of the weight, and the walls none.
- The backing's weight against a closed form: on a semicircular arch of two voussoirs the
  extrados chord from the springing rises at 45 degrees, so the backing up to ``h`` is a
  right triangle of area ``h^2 / 2`` per side.
"""

from __future__ import annotations

import numpy as np
import pytest

from tce.core.analysis import Analysis
from tce.core.loads import LoadPattern
from tce.core.material import Material
from tce.structures.arch import pointed_arch, segmental_arch, semicircular_arch
from tce.structures.backing import BACKING, Backing
from tce.structures.bridge import arch_bridge

#: a unit point load at the crown's extrados, the live load
CROWN = LoadPattern(lateral=False, point=[dict(force=(0.0, 0.0, -1.0), on_top=(0.0, 0.0))])

ARCHES = {
    "semicircular": lambda backing: semicircular_arch(1.0, 0.12, 0.25, 12, backing=backing),
    "segmental": lambda backing: segmental_arch(2.0, 0.6, 0.15, 0.25, 8, backing=backing),
    "pointed-rings": lambda backing: pointed_arch(2.0, thickness=0.2, voussoirs=9, rings=2, stagger=True,
                                                  backing=backing),
    "bridge-rings": lambda backing: arch_bridge(2, 4.0, 1.0, 0.3, 1.0, 6, pier_width=0.8, pier_height=1.0, rings=2,
                                                backing=backing),
}


@pytest.mark.parametrize("arch", sorted(ARCHES))
def test_backing_of_zero_height_is_the_arch_without_backing(arch):
    build = ARCHES[arch]
    bare = build(None)
    ground = build(Backing(0.0))
    assert [b.name for b in ground.blocks] == [b.name for b in bare.blocks]
    assert len(ground.interfaces) == len(bare.interfaces)
    one = Analysis(bare, Material(friction=0.6)).limit(0.0)  # the lateral load along +x
    two = Analysis(ground, Material(friction=0.6)).limit(0.0)
    assert one.status == two.status == "optimal"
    assert two.lambda_max == one.lambda_max


def test_backing_below_the_extrados_springing_is_none():
    bare = segmental_arch(2.0, 0.6, 0.15, 0.25, 8)
    springing = max(b.shape.vertices[:, 2].max() for b in bare.blocks if b.name == "left")
    low = segmental_arch(2.0, 0.6, 0.15, 0.25, 8, backing=Backing(0.9 * springing))
    assert len(low.blocks) == len(bare.blocks) and "backing" not in low.meta


def test_bonded_backing_raises_the_crown_capacity_of_a_heyman_arch():
    """A semicircular arch of t/R = 0.12 (Heyman: no tension, no sliding), backing up to 0.3 m;
    bonded it carries 39 times the bare arch's crown load (2.11 against 0.0535 kN), and nearly
    ten times what it carries bearing on a frictionless extrados and abutment (0.223 kN)."""
    bare = Analysis(semicircular_arch(1.0, 0.12, 0.25, 12), Material()).limit(loads=CROWN)
    backed = semicircular_arch(1.0, 0.12, 0.25, 12, backing=Backing(0.3))
    bonded = Analysis(backed, Material(interfaces={BACKING: Material(bonded=True)})).limit(loads=CROWN)
    slippery = Analysis(backed, Material(interfaces={BACKING: Material(friction=0.0)})).limit(loads=CROWN)
    assert bare.status == bonded.status == slippery.status == "optimal"
    assert bonded.lambda_max > 10.0 * bare.lambda_max
    assert bonded.lambda_max > 5.0 * slippery.lambda_max > 5.0 * bare.lambda_max


@pytest.mark.parametrize("arch", sorted(ARCHES))
def test_frictionless_backing_blocks_load_the_arch_as_their_weight(arch):
    build = ARCHES[arch]
    frictionless = Material(friction=0.6, interfaces={BACKING: Material(friction=0.0)})
    blocks = build(Backing(0.5, 22.0, "blocks"))
    fill = build(Backing(0.5, 22.0, "fill"))
    r_blocks = Analysis(blocks, frictionless).solve(0.0).reactions.sel(component="Fz")
    r_fill = Analysis(fill, frictionless).solve(0.0).reactions.sel(component="Fz")
    weight = sum(b.weight for b in fill.blocks if not b.support)
    assert weight == pytest.approx(sum(b.weight for b in blocks.blocks if not b.support), rel=1e-12)
    walls = ["wall_left", "wall_right"]
    arch = float(r_blocks.drop_sel(support=walls).sum())
    assert arch == pytest.approx(float(r_fill.sum()), abs=1e-8 * weight)
    assert arch == pytest.approx(weight, abs=1e-8 * weight)
    assert np.abs(r_blocks.sel(support=walls).values).max() < 1e-8 * weight


@pytest.mark.parametrize("h", [0.2, 0.55, 0.9])
def test_backing_weight_against_the_triangle_behind_a_45_degree_chord(h):
    """Two voussoirs of a semicircular arch (outer radius 1.2 m): the extrados chord from
    (-1.2, 0) to (0, 1.2); the backing up to h is a triangle of legs h, weight gamma d h^2 / 2."""
    gamma, depth = 22.0, 0.4
    bare = semicircular_arch(1.0, 0.2, depth, 2)
    blocks = semicircular_arch(1.0, 0.2, depth, 2, backing=Backing(h, gamma))
    fill = semicircular_arch(1.0, 0.2, depth, 2, backing=Backing(h, gamma, "fill"))
    exact = gamma * depth * h**2 / 2.0
    for side in ("left", "right"):
        assert blocks.blocks[blocks.index[f"backing_{side}"]].weight == pytest.approx(exact, rel=1e-12)
    for name in ("v01", "v02"):
        k = bare.index[name]
        assert fill.blocks[k].weight - bare.blocks[k].weight == pytest.approx(exact, rel=1e-12)
