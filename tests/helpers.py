"""Builders shared by the tests: a single block on a support (closed forms), arch centroid height."""

from __future__ import annotations

import numpy as np

from tce.structures.assembly import Assembly, Block, Interface
from tce.structures.geometry import box


def block_on_support(b: float = 0.4, h: float = 1.0, d: float = 0.3, unit_weight: float = 20.0) -> Assembly:
    """A b x d x h block (x, y, z) standing on a wider support slab: rocks at lambda = b/h."""
    base = Block("base", box([-b, -d, -0.2], [b, d, 0.0]), unit_weight, support=True)
    top = Block("block", box([-b / 2, -d / 2, 0.0], [b / 2, d / 2, h]), unit_weight)
    pts = np.array([[-b / 2, -d / 2, 0], [b / 2, -d / 2, 0], [b / 2, d / 2, 0], [-b / 2, d / 2, 0]])
    return Assembly((base, top), (Interface(0, 1, pts, [0, 0, 1]),))


def arch_centroid_height(assembly: Assembly) -> float:
    """Height of the voussoirs' centroid above the springings (m)."""
    free = list(assembly.free_indices)
    w = assembly.weights[free]
    return float((w * assembly.centroids[free, 2]).sum() / w.sum())
