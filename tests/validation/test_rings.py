"""Multi-ring arches (issue 40): rings that cannot separate against one ring, and frictionless
faces between rings against an independent linear program (tests/reference/ring_arch.py).

- Two (or three) rings with aligned joints whose faces between rings are bonded
  (``Material(bonded=True)``: any tension and shear carried) are one rigid voussoir per joint
  interval, the same blocks as one ring of the summed thickness: the joints' contact points
  at the ring boundaries lie inside the joints' traces, which adds nothing to what a joint
  can carry. So lambda_max of the lateral load and the minimum thickness agree with the
  single ring's to solver precision (the direct limit: one conic program checked to 1e-9 of
  the weight; measured 1e-10).
- Faces between rings with no friction: the rings share load by normal contact only; the
  limit is that of an LP written without tce (HiGHS), within 1e-8 (measured 1e-10); tce's
  limit state has no tangential force on those faces.
"""

from __future__ import annotations

import numpy as np
import pytest

from tce.analysis.thickness import minimum_thickness
from tce.core.analysis import Analysis
from tce.core.material import Material
from tce.structures.arch import RING, pointed_arch, segmental_arch, semicircular_arch
from tce.structures.bridge import arch_bridge

from reference.ring_arch import two_ring_lambda_max

BONDED = {RING: Material(bonded=True)}

#: (name, builder of thickness t and rings): each arch as one ring and as rings of aligned joints
ARCHES = {
    "semicircular": lambda t, rings: semicircular_arch(1.0, t, 0.25, 10, rings=rings),
    "segmental": lambda t, rings: segmental_arch(2.0, 0.6, t, 0.25, 8, rings=rings),
    "pointed": lambda t, rings: pointed_arch(2.0, thickness=t, voussoirs=9, rings=rings),
    "bridge": lambda t, rings: arch_bridge(2, 4.0, 1.0, t, 1.0, 6, pier_width=0.8, pier_height=1.0, rings=rings),
}


@pytest.mark.parametrize("rings", [2, [0.08, 0.12], 3])
@pytest.mark.parametrize("friction", [None, 0.6])
@pytest.mark.parametrize("arch", sorted(ARCHES))
def test_bonded_rings_are_one_ring_of_the_summed_thickness(arch, friction, rings):
    build = ARCHES[arch]
    one = Analysis(build(0.2, 1), Material(friction=friction)).limit(0.0)
    many = Analysis(build(0.2, rings), Material(friction=friction, interfaces=BONDED)).limit(0.0)
    assert one.status == many.status == "optimal"
    assert many.lambda_max == pytest.approx(one.lambda_max, rel=1e-8)


def test_bonded_rings_have_the_minimum_thickness_of_one_ring():
    """Milankovitch's ring (t/R about 0.11 with 10 voussoirs), bisected to 1e-6: the two brackets
    agree within one bisection step."""
    one = minimum_thickness(lambda t: semicircular_arch(1.0 - t / 2, t, 0.25, 10), 0.05, 0.2, tol=1e-6)
    two = minimum_thickness(lambda t: semicircular_arch(1.0 - t / 2, t, 0.25, 10, rings=2), 0.05, 0.2,
                            Material(interfaces=BONDED), tol=1e-6)
    assert one.status == two.status == "optimal"
    assert two.thickness == pytest.approx(one.thickness, rel=2e-6)


@pytest.mark.parametrize("rings", [(0.25, 0.25), (0.2, 0.3)])
@pytest.mark.parametrize("friction", [None, 0.8, 0.5])
def test_frictionless_ring_faces_share_load_by_normal_contact_only(friction, rings):
    asm = semicircular_arch(1.0, sum(rings), 0.3, 8, rings=list(rings))
    an = Analysis(asm, Material(friction=friction, interfaces={RING: Material(friction=0.0)}))
    lim = an.limit(0.0)
    assert lim.status == "optimal"
    assert lim.lambda_max == pytest.approx(two_ring_lambda_max(1.0, *rings, 8, friction), rel=1e-8)
    # no tangential force on the faces between rings (their tangential components are fixed to zero)
    ring = an.model(lim.model).contact_kind == RING
    assert ring.any()
    assert np.abs(lim.forces[ring, 1:]).max() <= 1e-12 * asm.total_weight
    # and friction there matters: the same rings with the joints' own law are stronger
    joined = Analysis(asm, Material(friction=friction)).limit(0.0)
    assert joined.lambda_max > lim.lambda_max * 1.1
