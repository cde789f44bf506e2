"""Backing: masonry or concrete behind the haunches of an arch, up to a height above the springing.

Axes as :mod:`tce.structures.arch` (the arch spans along x, z up, the springings at z = 0).
The backing region on each side is bounded below by the extrados (its chords, from the
extrados end of the springing joint up to where the extrados reaches ``height``), above by
the horizontal plane ``z = height`` and behind by the vertical plane through the extrados end
of the springing joint: ``{(x, z): x between x0 and the extrados, e(x) <= z <= height}``, ``e``
the extrados (which rises monotonically from each springing to the crown on every arch
generator).

Over the pier between two spans of a bridge the backing of both haunches is one region, on
the pier's top between the two extrados springings.

Two models (:class:`Backing`):

- ``"blocks"``: rigid blocks on the extrados, ``backing_left``, ``backing_pier1`` ...
  (resting on each pier's top), ``backing_right``; each end block bears against a support
  block behind it, ``wall_left`` and ``wall_right`` (a square of the backing's height behind
  the vertical plane, with its own prescribed motion: a scenario that spreads the supports
  moves them too by naming them). Every face of a backing block in contact, with the
  voussoirs of the outer ring, a pier or a wall, is an interface of kind ``"backing"``
  (:data:`BACKING`), which a material may give its own law
  (``Material(interfaces={"backing": ...})``, ``bonded=True`` for backing bonded to the
  extrados).
- ``"fill"``: no blocks; the weight of the region above each extrados chord (the vertical
  column over it, up to ``height``) is added to the voussoir under it, and that over a pier's
  top to the pier, as a heavier unit weight: a fixed vertical load of that weight at the
  block's centroid.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Literal

import numpy as np
import shapely
from numpy.typing import ArrayLike

from .assembly import Assembly, Block, Interface
from .geometry import prism

__all__ = ["BACKING", "Backing", "backing_regions", "with_backing"]

#: interface kind of the faces of a backing block (:func:`with_backing`)
BACKING = "backing"

#: the backing models (module docstring)
MODELS = ("blocks", "fill")


@dataclass(frozen=True)
class Backing:
    """Backing behind both haunches (module docstring).

    Parameters
    ----------
    height : float
        Height of its horizontal top above the springing line z = 0 (m, >= 0; 0 or a height
        below the extrados' springing: no backing). Below the extrados' crown.
    unit_weight : float
        Unit weight of the backing (kN/m^3, > 0).
    model : {"blocks", "fill"}
        Rigid blocks on the extrados or a heavier fill (module docstring).
    """

    height: float
    unit_weight: float = 20.0
    model: Literal["blocks", "fill"] = "blocks"

    def __post_init__(self) -> None:
        if not (np.isfinite(self.height) and self.height >= 0.0):
            raise ValueError(f"backing height must be a finite number >= 0 (m), got {self.height!r}")
        if not (np.isfinite(self.unit_weight) and self.unit_weight > 0.0):
            raise ValueError(f"backing unit_weight must be a finite number > 0 (kN/m^3), got {self.unit_weight!r}")
        if self.model not in MODELS:
            raise ValueError(f"backing model must be one of {', '.join(MODELS)}, got {self.model!r}")


def _side(extrados: np.ndarray, height: float) -> tuple[np.ndarray, list[np.ndarray]]:
    """The backing section on the side whose springing is ``extrados[0]`` (``(x, z)``, m): its
    loop (springing end, the extrados points below ``height``, the extrados at ``height``, the
    top of the back plane) and, per extrados chord, the part of the chord under ``height``
    (``(2, 2)``; none once the extrados is above)."""
    x0, z0 = extrados[0]
    loop, chords = [extrados[0]], []
    for p, q in zip(extrados[:-1], extrados[1:]):
        if p[1] >= height:
            break
        if q[1] > height:
            q = p + (height - p[1]) / (q[1] - p[1]) * (q - p)
        chords.append(np.array([p, q]))
        loop.append(q)
    loop.append(np.array([x0, height]))
    return np.array(loop), chords


def backing_regions(extrados: ArrayLike, height: float) -> list[tuple[np.ndarray, list[np.ndarray]]]:
    """The backing sections of both sides (module docstring).

    Parameters
    ----------
    extrados : (m + 1, 2) array_like
        The extrados polyline ``(x, z)`` (m) from the left springing to the right one.
    height : float
        Height of the backing's top above z = 0 (m).

    Returns
    -------
    list of (loop, chords)
        Left then right; empty when ``height`` does not reach above the extrados' springings.
        ``loop``: the section ``(k, 2)``; ``chords``: the part under ``height`` of each extrados
        chord from that side's springing (``(2, 2)`` each, from the springing end).

    Raises
    ------
    ValueError
        A height at or above the extrados' crown (the two sides would meet), or an extrados
        that does not rise from each springing to the crown.
    """
    e = np.asarray(extrados, dtype=float)
    top = int(np.argmax(e[:, 1]))
    if height >= e[top, 1]:
        raise ValueError(f"backing height {height:g} m reaches the extrados' crown at z = {e[top, 1]:g} m; "
                         "fix: a lower height")
    if np.any(np.diff(e[: top + 1, 1]) < 0) or np.any(np.diff(e[top:, 1]) > 0):
        raise ValueError("backing: the extrados does not rise from each springing to the crown")
    if height <= max(e[0, 1], e[-1, 1]):
        return []
    return [_side(e, height), _side(e[::-1], height)]


def _at_depth(xz: np.ndarray, y: float) -> np.ndarray:
    return np.column_stack([xz[:, 0], np.full(len(xz), y), xz[:, 1]])


def with_backing(asm: Assembly, extrados: Sequence[ArrayLike], voussoirs: Sequence[ArrayLike], depth: float,
                 backing: Backing, piers: Sequence[int] = ()) -> Assembly:
    """A new planar arch or bridge ``asm`` with backing behind the haunches of every span
    (module docstring).

    Parameters
    ----------
    asm : Assembly
        Arches along x side by side, their springings at z = 0.
    extrados : sequence of (m + 1, 2) array_like
        Each span's extrados polyline ``(x, z)`` (m), from its left springing to its right
        one, the spans from left to right.
    voussoirs : sequence of (m,) array_like of int
        Each span's block under each extrados chord.
    depth : float
        The depth along y (m), centred on y = 0.
    backing : Backing
        Height, unit weight and model.
    piers : sequence of int
        The block between span ``s`` and ``s + 1`` (one fewer than the spans): a pier whose
        top runs between the two extrados springings, level.

    Returns
    -------
    Assembly
        ``asm`` itself when the backing does not reach above the springings. With
        ``"blocks"``: appended, ``backing_left``, ``backing_pier1`` ... (over each pier: the
        backing of both haunches, one block on the pier's top), ``backing_right``, then the
        supports ``wall_left``, ``wall_right`` behind the end ones; the faces of every backing
        block (with the voussoirs, the piers and the walls) of kind ``"backing"``, normals
        from the lower block index into the higher. With ``"fill"``: the voussoirs under the
        backing, and the piers, heavier by the backing's weight over them.
        ``meta["backing"]`` records the backing.
    """
    if len(extrados) != len(voussoirs) or len(piers) != len(extrados) - 1:
        raise ValueError("backing: one extrados and its voussoirs per span, one pier between two spans")
    under = [np.asarray(v, dtype=int) for v in voussoirs]
    if any(len(v) != len(np.asarray(e)) - 1 for e, v in zip(extrados, under)):
        raise ValueError("backing: one voussoir per extrados chord")
    h, gamma = float(backing.height), float(backing.unit_weight)
    spans = [backing_regions(e, h) for e in extrados]
    if not all(spans):
        return asm
    meta = dict(asm.meta, backing=dict(height=h, unit_weight=gamma, model=backing.model))
    # the sides from left to right: (loop, chords, blocks under them); over a pier, two sides meet
    sides = [(region[0], region[1], blocks[::sign]) for regions, blocks in zip(spans, under)
             for region, sign in zip(regions, (1, -1))]
    if backing.model == "fill":
        def column(p: np.ndarray, q: np.ndarray) -> float:
            """Weight (kN) of the backing over the segment ``p q``, up to its top."""
            return gamma * depth * shapely.Polygon([p, q, [q[0], h], [p[0], h]]).area

        extra = np.zeros(len(asm.blocks))
        for _, chords, blocks in sides:
            for (p, q), k in zip(chords, blocks):
                extra[k] += column(p, q)
        for s, pier in enumerate(piers):
            extra[pier] += column(sides[2 * s + 1][0][0], sides[2 * s + 2][0][0])
        blocks = tuple(b if not w else replace(b, unit_weight=b.unit_weight + w / b.volume)
                       for b, w in zip(asm.blocks, extra))
        return Assembly(blocks, asm.interfaces, meta)
    d = float(depth) / 2.0
    n, nb = len(asm.blocks), len(piers) + 2
    loops = [sides[0][0]] + [np.vstack([sides[2 * s + 1][0][:-1], sides[2 * s + 2][0][-2::-1]])
                             for s in range(len(piers))] + [sides[-1][0]]
    names = ["backing_left"] + [f"backing_pier{s + 1}" for s in range(len(piers))] + ["backing_right"]
    new = [Block(name, prism(_at_depth(loop, -d), _at_depth(loop, d)), gamma) for name, loop in zip(names, loops)]
    interfaces = list(asm.interfaces)
    for k, (_, chords, blocks) in enumerate(sides):
        for (p, q), v in zip(chords, blocks):
            t = q - p
            normal = np.array([-t[1], 0.0, t[0]])  # out of the extrados (upwards), into the backing
            interfaces.append(Interface(int(v), n + (k + 1) // 2, _face(p, q, d), normal if normal[2] > 0 else -normal,
                                        kind=BACKING))
    for s, pier in enumerate(piers):
        p, q = sides[2 * s + 1][0][0], sides[2 * s + 2][0][0]
        interfaces.append(Interface(int(pier), n + s + 1, _face(p, q, d), np.array([0.0, 0.0, 1.0]), kind=BACKING))
    for k, (loop, sign, name) in enumerate(((sides[0][0], -1.0, "left"), (sides[-1][0], 1.0, "right"))):
        (x0, z0), far = loop[0], loop[0][0] + sign * (h - loop[0][1])
        wall = np.array([[x0, z0], [x0, h], [far, h], [far, z0]])
        new.append(Block(f"wall_{name}", prism(_at_depth(wall, -d), _at_depth(wall, d)), gamma, support=True))
        interfaces.append(Interface(n + k * (nb - 1), n + nb + k, _face(loop[0], loop[-1], d),
                                    np.array([sign, 0.0, 0.0]), kind=BACKING))
    return Assembly(asm.blocks + tuple(new), tuple(interfaces), meta)


def _face(p: np.ndarray, q: np.ndarray, d: float) -> np.ndarray:
    """The rectangle on the segment ``p``-``q`` (``(x, z)``, m) across the depth ``-d .. d``."""
    return np.vstack([_at_depth(np.array([p, q]), -d), _at_depth(np.array([q, p]), d)])
