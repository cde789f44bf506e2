"""Assemblies of the validation tests, each with its reference block data (tests/reference).

``arch``    the paper's semicircular arch (14 chord-faced voussoirs on two support boxes)
``dome``    a closed-crown hemispherical dome, 8 sectors x 4 courses
``wall``    the running-bond wall of ``studies/data/wall.json`` (bricks found in contact by tce)
``stack``   random boxes stacked with random offsets, unit weights, interface orientations
            (A below or above B) and stiffness multipliers, then turned by a random rotation
            (``tilted``) or about z only, with the supports chosen at random
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

import numpy as np

from reference import geometry as ref
from tce.structures.arch import semicircular_arch
from tce.structures.assembly import Assembly, Block, Interface
from tce.structures.dome import hemispherical_dome
from tce.structures.geometry import Polyhedron, box
from tce.structures.io import load_assembly

WALL = Path(__file__).resolve().parents[2] / "studies" / "data" / "wall.json"
DOME = dict(radius=5.0, thickness=0.5, sectors=8, courses=4, unit_weight=20.0)


@lru_cache(maxsize=None)
def arch() -> tuple[Assembly, ref.Blocks]:
    return semicircular_arch().validate(), ref.semicircular_arch()


@lru_cache(maxsize=None)
def dome() -> tuple[Assembly, ref.Blocks]:
    return hemispherical_dome(**DOME).validate(), ref.hemispherical_dome(**DOME)


@lru_cache(maxsize=None)
def wall() -> tuple[Assembly, ref.Blocks]:
    asm = load_assembly(WALL)
    props = [ref.box(b.shape.vertices) for b in asm.blocks]
    blocks = ref.Blocks(
        np.array([v for v, _ in props]),
        np.array([c for _, c in props]),
        np.full(len(props), 18.0),  # the file's unit weight
        np.array([b.name == "base" for b in asm.blocks]),
    )
    return asm, blocks


def _rotation(rng: np.random.Generator, tilted: bool) -> np.ndarray:
    if not tilted:
        a = rng.uniform(0, 2 * np.pi)
        return np.array([[np.cos(a), -np.sin(a), 0.0], [np.sin(a), np.cos(a), 0.0], [0.0, 0.0, 1.0]])
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    q = q * np.sign(np.diag(r))
    return q if np.linalg.det(q) > 0 else -q


@lru_cache(maxsize=None)
def stack(seed: int, tilted: bool = True, random_supports: bool = True) -> tuple[Assembly, ref.Blocks]:
    """Random boxes stacked in a column (see module docstring). Without ``random_supports``
    the bottom box is the only support; the offsets keep every box's centroid above the one
    below, so the stack stands under its self-weight."""
    rng = np.random.default_rng(seed)
    n = int(rng.integers(4, 7))
    Q, shift = _rotation(rng, tilted), rng.normal(size=3)
    lows, highs, z = [], [], 0.0
    for i in range(n):
        size = rng.uniform([0.3, 0.3, 0.1], [1.0, 1.0, 0.6])
        if i == 0:
            xy = rng.uniform(-0.5, 0.5, 2)
        else:  # the centre of this box stays above the one below
            centre = (lows[-1][:2] + highs[-1][:2]) / 2 + rng.uniform(-0.2, 0.2, 2) * (highs[-1][:2] - lows[-1][:2])
            xy = centre - size[:2] / 2
        lows.append(np.array([xy[0], xy[1], z]))
        highs.append(lows[-1] + size)
        z = highs[-1][2]
    if random_supports:
        support = np.zeros(n, dtype=bool)
        support[rng.choice(n, size=int(rng.integers(1, 3)), replace=False)] = True
        if support.all():
            support[-1] = False
    else:
        support = np.arange(n) == 0
    unit_weight = rng.uniform(10.0, 30.0, n)
    blocks, volume, centroid = [], [], []
    for i in range(n):
        shape = box(lows[i], highs[i])
        blocks.append(Block(f"b{i}", Polyhedron(shape.vertices @ Q.T + shift, shape.faces), float(unit_weight[i]), bool(support[i])))
        volume.append(float(np.prod(highs[i] - lows[i])))
        centroid.append(Q @ ((lows[i] + highs[i]) / 2) + shift)
    interfaces = []
    for i in range(n - 1):
        (x0, y0), (x1, y1) = np.maximum(lows[i][:2], lows[i + 1][:2]), np.minimum(highs[i][:2], highs[i + 1][:2])
        zt = highs[i][2]
        pts = np.array([[x0, y0, zt], [x1, y0, zt], [x1, y1, zt], [x0, y1, zt]]) @ Q.T + shift
        normal = Q @ np.array([0.0, 0.0, 1.0])
        k = float(rng.uniform(0.5, 2.0))
        if rng.random() < 0.5:
            interfaces.append(Interface(i, i + 1, pts, normal, k))
        else:  # the same contact seen from the upper block: A above, normal down
            interfaces.append(Interface(i + 1, i, pts[::-1], -normal, k))
    asm = Assembly(tuple(blocks), tuple(interfaces)).validate()
    return asm, ref.Blocks(np.array(volume), np.array(centroid), unit_weight, support)


def assert_same_blocks(assembly: Assembly, blocks: ref.Blocks, rtol: float = 1e-12) -> None:
    """tce's volumes, weights, centroids and support flags equal the reference's."""
    np.testing.assert_allclose([b.volume for b in assembly.blocks], blocks.volume, rtol=rtol)
    np.testing.assert_allclose(assembly.weights, blocks.weight, rtol=rtol)
    np.testing.assert_allclose(assembly.centroids, blocks.centroid, atol=rtol * assembly.size)
    assert [b.support for b in assembly.blocks] == blocks.support.tolist()


SCENES = {
    "arch": arch,
    "dome": dome,
    "wall": wall,
    "stack0": lambda: stack(0),
    "stack1": lambda: stack(1),
    "stack2": lambda: stack(2, tilted=False),
}
