"""Regression: the batched overlap check reports what the per-pair check it replaced reported.

Each case moves one block of a valid assembly into its neighbours (or builds a known overlap)
and pins the message of :func:`tce.structures.contacts.check_overlaps`: which pair, and the
depth of the deepest test point. The messages were produced on 2026-11-22 by the per-pair
implementation (tce at commit 6c7f818, before issue 14's vectorisation of ``contacts.py``).
The non-convex cases (the L-shaped block, the curved COMPAS sample) go through the winding
number; the others through the face planes of convex blocks.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from tce.structures.arch import semicircular_arch
from tce.structures.assembly import AssemblyError, Block
from tce.structures.contacts import check_overlaps
from tce.structures.dome import hemispherical_dome
from tce.structures.geometry import Polyhedron, box, prism
from tce.structures.io import load_assembly

ROOT = Path(__file__).resolve().parents[2]
SAMPLES = ROOT / "tce" / "data" / "assemblies"


def moved(assembly, k, d):
    blocks = list(assembly.blocks)
    b = blocks[k]
    blocks[k] = replace(b, shape=Polyhedron(b.shape.vertices + np.asarray(d, float), b.shape.faces))
    return blocks


def L_block():
    L = np.array([[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]], float)
    return Block("L", prism(np.c_[L, np.zeros(6)], np.c_[L, np.ones(6)]), 20.0)


CASES = {
    "dome_in": (lambda: moved(hemispherical_dome(sectors=6, courses=4), 9, [0, 0.05, 0]),
                "blocks 'c01s03' and 'c01s04' overlap: a point of 'c01s04' lies 0.05 m inside 'c01s03'"),
    "dome_down": (lambda: moved(hemispherical_dome(sectors=6, courses=4), 14, [0, 0, -0.02]),
                  "blocks 'c01s03' and 'c02s03' overlap: a point of 'c02s03' lies 0.018 m inside 'c01s03'"),
    "arch_shift": (lambda: moved(semicircular_arch(), 5, [0.01, 0, 0]),
                   "blocks 'v05' and 'v06' overlap: a point of 'v06' lies 0.00901 m inside 'v05'"),
    "wall_shift": (lambda: moved(load_assembly(ROOT / "studies" / "data" / "wall.json", supports=["base"]), 7, [0.03, 0, 0]),
                   None),
    "shelf_drop": (lambda: moved(load_assembly(SAMPLES / "shelf.json", supports=[0]), 2, [0, 0, -0.01]),
                   "blocks '0' and '2' overlap: a point of '2' lies 0.01 m inside '0'"),
    "bridge_drop": (lambda: moved(load_assembly(SAMPLES / "bridge.json", supports=[0, 1]), 8, [0, 0, -0.05]), None),
    "L_inner": (lambda: [L_block(), Block("inner", box([0.2, 0.2, 0.2], [0.6, 0.6, 0.6]), 20.0)],
                "blocks 'L' and 'inner' overlap: a point of 'inner' lies 0.4 m inside 'L'"),
    "L_notch_over": (lambda: [L_block(), Block("over", box([0.9, 0.9, 0.0], [1.8, 1.8, 1.0]), 20.0)],
                     "blocks 'L' and 'over' overlap: a point of 'over' lies 0.141 m inside 'L'"),
    "L_L": (lambda: [L_block(), Block("L2", Polyhedron(L_block().shape.vertices + [0.5, 0.5, 0.5], L_block().shape.faces), 20.0)],
            "blocks 'L' and 'L2' overlap: a point of 'L2' lies 0.5 m inside 'L'"),
}


@pytest.mark.parametrize("name", list(CASES))
def test_overlap_message(name):
    build, message = CASES[name]
    blocks = build()
    if message is None:
        check_overlaps(blocks)
    else:
        with pytest.raises(AssemblyError) as err:
            check_overlaps(blocks)
        assert str(err.value) == message


def test_curved_sample_overlaps_by_its_facets():
    a = load_assembly(SAMPLES / "curve-3-blocks.json", supports=[0], nonplanar="triangulate", tol=1e-2,
                      angle_tol=0.2, min_area=1e-6, check_overlap=False)
    with pytest.raises(AssemblyError) as err:
        check_overlaps(a, 1e-6)
    assert str(err.value) == "blocks '0' and '1' overlap: a point of '1' lies 0.00272 m inside '0'"
    check_overlaps(a, 1e-2)
