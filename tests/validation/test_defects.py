"""Defects from an inspection (issue 40, tce.structures.defects) against closed forms and
against the same structure built another way.

- Mortar lost to a depth from one side of a joint is a thinner joint: a block on a support
  whose bed lost ``delta`` from the side it tips towards rocks at ``lam = (b - 2 delta) / h``
  (its toe moved in by ``delta``), from the other side at ``lam = b / h`` (Heyman); the same as
  the block on a bed polygon given ``delta`` narrower.
- A missing block is the structure built without it: a three-ring arch whose outer ring lost
  its crown brick, against the same blocks with their interfaces found again by contact
  detection (tce.structures.contacts), to solver precision.
"""

from __future__ import annotations

import numpy as np
import pytest

from tce.core.analysis import Analysis
from tce.core.material import Material
from tce.structures.arch import semicircular_arch
from tce.structures.assembly import Assembly, Interface
from tce.structures.contacts import detect_interfaces
from tce.structures.defects import with_joint_loss, without_blocks

from helpers import block_on_support

B, H, D = 0.4, 1.0, 0.3


@pytest.mark.parametrize("delta", [0.05, 0.12])
def test_mortar_loss_is_a_thinner_joint(delta):
    asm = block_on_support(B, H, D)
    towards = with_joint_loss(asm, "base|block", extrados=delta)  # the bed's +x side: the toe of a load along +x
    away = with_joint_loss(asm, "block|base", intrados=delta)
    lam = lambda a: Analysis(a, Material()).limit(0.0).lambda_max  # noqa: E731
    assert lam(towards) == pytest.approx((B - 2 * delta) / H, rel=1e-8)
    assert lam(away) == pytest.approx(B / H, rel=1e-8)
    x0, x1 = -B / 2, B / 2 - delta
    bed = np.array([[x0, -D / 2, 0], [x1, -D / 2, 0], [x1, D / 2, 0], [x0, D / 2, 0]])
    thinner = Assembly(asm.blocks, (Interface(0, 1, bed, [0, 0, 1]),))
    assert lam(towards) == pytest.approx(lam(thinner), rel=1e-10)
    np.testing.assert_allclose(towards.interfaces[0].area, (B - delta) * D, rtol=1e-12)


def test_missing_block_is_the_structure_built_without_it():
    arch = semicircular_arch(1.0, 0.3, 0.25, 8, rings=3)
    crown = "r3v04"
    missing = without_blocks(arch, [crown]).validate()
    assert crown not in missing.names and len(missing.blocks) == len(arch.blocks) - 1
    rebuilt = Assembly(missing.blocks, tuple(detect_interfaces(missing.blocks)))
    assert len(rebuilt.interfaces) == len(missing.interfaces)
    mat = Material(friction=0.6)
    a, b = Analysis(missing, mat).limit(0.0), Analysis(rebuilt, mat).limit(0.0)
    assert a.status == b.status == "optimal"
    assert a.lambda_max == pytest.approx(b.lambda_max, rel=1e-8)
    assert missing.total_weight == pytest.approx(arch.total_weight - arch.weights[arch.index[crown]], rel=1e-12)
