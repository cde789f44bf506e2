"""A compliant closed form in which the normal and the shear stiffness give different answers.

A wedge (a trapezoidal prism, wider at the top) rests under its self-weight W between two
support blocks on its inclined side faces, whose normals (from each support into the wedge)
make the angle b with the horizontal. Contacts are elastic (normal stiffness kn, shear
stiffness ks per unit area) with no friction limit. The scene is symmetric about x = 0 and
y = 0, and the TCE with compliance is strictly convex, so its minimiser is symmetric: each side
face carries W/2 vertically, every one of its four (equal-area) vertices the same force, and
the only free quantity is the horizontal push H of each support. Minimising the energy
``(fn^2 / kn + ft^2 / ks) / A`` per face with ``fn = H cos b + W/2 sin b``,
``ft = -H sin b + W/2 cos b`` (t1 up the face) gives::

    H = (W / 2) sin b cos b (kn - ks) / (kn sin^2 b + ks cos^2 b)

zero when kn = ks, of opposite sign when kn and ks are swapped, and the TCE
``(fn^2 / kn + ft^2 / ks) / A`` with A the area of one face.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from tce.analysis import Analysis
from tce.core.material import Material
from tce.structures.assembly import Assembly, Block, Interface
from tce.structures.geometry import prism

UNIT_WEIGHT = 20.0


def _at_depth(xz, y):
    xz = np.asarray(xz, dtype=float)
    return np.column_stack([xz[:, 0], np.full(len(xz), y), xz[:, 1]])


def wedge(a: float, b: float, h: float, depth: float) -> Assembly:
    """Wedge between ``x = -+a`` at z = 0 and ``x = -+b`` at z = h (b > a), ``depth`` along y,
    between two support blocks ``left`` and ``right``."""
    d = depth / 2
    loops = {
        "left": [[-b - 0.3, 0.0], [-a, 0.0], [-b, h], [-b - 0.3, h]],
        "wedge": [[-a, 0.0], [a, 0.0], [b, h], [-b, h]],
        "right": [[a, 0.0], [b + 0.3, 0.0], [b + 0.3, h], [b, h]],
    }
    blocks = tuple(
        Block(name, prism(_at_depth(loop, -d), _at_depth(loop, d)), UNIT_WEIGHT, name != "wedge")
        for name, loop in loops.items()
    )
    L = math.hypot(b - a, h)
    left = _at_depth([[-a, 0.0], [-b, h]], -d)
    right = _at_depth([[a, 0.0], [b, h]], -d)
    left_face = np.vstack([left, left[::-1] + [0, 2 * d, 0]])
    right_face = np.vstack([right, right[::-1] + [0, 2 * d, 0]])
    interfaces = (
        Interface(0, 1, left_face, np.array([h, 0.0, b - a]) / L),  # from the left support into the wedge
        Interface(1, 2, right_face, np.array([h, 0.0, a - b]) / L),  # from the wedge into the right support
    )
    return Assembly(blocks, interfaces).validate()


def closed_form(a, b, h, depth, kn, ks):
    """(H, TCE) of the module docstring."""
    W = UNIT_WEIGHT * (a + b) * h * depth
    beta = math.atan2(b - a, h)
    s, c = math.sin(beta), math.cos(beta)
    H = W / 2 * s * c * (kn - ks) / (kn * s**2 + ks * c**2)
    fn, ft = H * c + W / 2 * s, -H * s + W / 2 * c
    area = math.hypot(b - a, h) * depth
    return H, (fn**2 / kn + ft**2 / ks) / area


GEOMETRIES = [(0.3, 0.5, 0.4, 0.25), (0.2, 0.8, 0.3, 0.5)]
STIFFNESSES = [(4e6, 1e6), (1e6, 4e6), (2.5e5, 2.5e5), (1e8, 3e5)]


@pytest.mark.parametrize("kind", ["planar", "spatial"])
@pytest.mark.parametrize("kn, ks", STIFFNESSES)
@pytest.mark.parametrize("geometry", GEOMETRIES)
def test_wedge_between_elastic_supports(kind, kn, ks, geometry):
    a, b, h, depth = geometry
    asm = wedge(a, b, h, depth)
    r = Analysis(asm, Material(None, normal_stiffness=kn, shear_stiffness=ks), model=kind).solve(0.0)  # type: ignore[arg-type]
    assert r.status == "optimal" and r.model == kind and r.unique
    H, tce = closed_form(a, b, h, depth, kn, ks)
    W = asm.total_weight
    left, right = r.support_wrenches
    assert left[0] == pytest.approx(H, abs=1e-9 * W)  # the left support pushes the wedge along +x by H
    assert right[0] == pytest.approx(-H, abs=1e-9 * W)
    assert left[2] == pytest.approx(W / 2, rel=1e-10) and right[2] == pytest.approx(W / 2, rel=1e-10)
    assert r.tce == pytest.approx(tce, rel=1e-8)


def test_swapping_the_stiffnesses_reverses_the_push():
    a, b, h, depth = GEOMETRIES[0]
    H, _ = closed_form(a, b, h, depth, 4e6, 1e6)
    H_swapped, _ = closed_form(a, b, h, depth, 1e6, 4e6)
    assert H > 0.05 * UNIT_WEIGHT * (a + b) * h * depth and H_swapped < 0  # the test can tell them apart
