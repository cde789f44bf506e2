"""Backing: masonry or concrete behind the haunches of an arch, up to a height above the springing.

Axes as :mod:`tce.structures.arch` (the arch spans along x, z up, the springings at z = 0).
The backing region on each side is bounded below by the extrados (its chords, from the
extrados end of the springing joint up to where the extrados reaches ``height``), above by
the horizontal plane ``z = height`` and behind by the vertical plane through the extrados end
of the springing joint: ``{(x, z): x between x0 and the extrados, e(x) <= z <= height}``, ``e``
the extrados (which rises monotonically from each springing to the crown on every arch
generator).

Two models (:class:`Backing`):

- ``"blocks"``: one rigid block per side, ``left_backing`` and ``right_backing``, on the
  extrados; each bears against a support block behind it, ``left_abutment`` and
  ``right_abutment`` (a prism of the backing's height and width behind the vertical plane,
  with its own prescribed motion: a scenario that moves an abutment names it beside
  ``left`` / ``right``). Every face of a backing block in contact, with the voussoirs and with
  its abutment, is an interface of kind ``"backing"`` (:data:`BACKING`), which a material may
  give its own law (``Material(interfaces={"backing": ...})``, ``bonded=True`` for backing
  bonded to the extrados).
- ``"fill"``: no blocks; the weight of the region above each extrados chord (the vertical
  column over it, up to ``height``) is added to the voussoir under it, as a heavier unit
  weight: a fixed vertical load of that weight at the voussoir's centroid.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Literal

import numpy as np
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


def _area(loop: np.ndarray) -> float:
    """Area of a simple polygon ``(k, 2)`` (m^2, either orientation)."""
    x, z = loop[:, 0], loop[:, 1]
    return 0.5 * abs(float(x @ np.roll(z, -1) - z @ np.roll(x, -1)))


def _at_depth(xz: np.ndarray, y: float) -> np.ndarray:
    return np.column_stack([xz[:, 0], np.full(len(xz), y), xz[:, 1]])


def with_backing(asm: Assembly, extrados: ArrayLike, voussoirs: ArrayLike, depth: float, backing: Backing) -> Assembly:
    """A new planar arch ``asm`` with backing behind its haunches (module docstring).

    Parameters
    ----------
    asm : Assembly
        An arch along x with its springings at z = 0.
    extrados : (m + 1, 2) array_like
        Its extrados polyline ``(x, z)`` (m), from the left springing to the right one.
    voussoirs : (m,) array_like of int
        The block under each extrados chord.
    depth : float
        The arch's depth along y (m), centred on y = 0.
    backing : Backing
        Height, unit weight and model.

    Returns
    -------
    Assembly
        ``asm`` itself when the backing does not reach above the springings; with
        ``"blocks"``: the blocks ``left_backing``, ``right_backing``, ``left_abutment``,
        ``right_abutment`` appended and the interfaces of kind ``"backing"`` (normals from
        the lower block index into the higher); with ``"fill"``: the voussoirs under the
        backing heavier by its weight. ``meta["backing"]`` records the backing.
    """
    e = np.asarray(extrados, dtype=float)
    under = np.asarray(voussoirs, dtype=int)
    if len(under) != len(e) - 1:
        raise ValueError("backing: one voussoir per extrados chord")
    regions = backing_regions(e, float(backing.height))
    if not regions:
        return asm
    meta = dict(asm.meta, backing=dict(height=float(backing.height), unit_weight=float(backing.unit_weight),
                                       model=backing.model))
    chord_blocks = [under, under[::-1]]
    if backing.model == "fill":
        extra = np.zeros(len(asm.blocks))
        for (_, chords), blocks in zip(regions, chord_blocks):
            for (p, q), k in zip(chords, blocks):
                column = np.array([p, q, [q[0], backing.height], [p[0], backing.height]])
                extra[k] += backing.unit_weight * depth * _area(column)
        blocks = tuple(b if not w else replace(b, unit_weight=b.unit_weight + w / b.volume)
                       for b, w in zip(asm.blocks, extra))
        return Assembly(blocks, asm.interfaces, meta)
    d = float(depth) / 2.0
    n = len(asm.blocks)
    new, interfaces = [], list(asm.interfaces)
    for side, ((loop, chords), blocks) in enumerate(zip(regions, chord_blocks)):
        name = ("left", "right")[side]
        sign = -1.0 if side == 0 else 1.0  # outwards from the span
        (x0, z0), h = loop[0], float(backing.height)
        wall = np.array([[x0, z0], [x0, h], [x0 + sign * (h - z0), h], [x0 + sign * (h - z0), z0]])
        new.append(Block(f"{name}_backing", prism(_at_depth(loop, -d), _at_depth(loop, d)),
                         float(backing.unit_weight)))
        new.append(Block(f"{name}_abutment", prism(_at_depth(wall, -d), _at_depth(wall, d)),
                         float(backing.unit_weight), support=True))
        me = n + 2 * side
        for (p, q), k in zip(chords, blocks):
            t = q - p
            normal = np.array([-t[1], 0.0, t[0]])  # out of the extrados (upwards), into the backing
            interfaces.append(Interface(int(k), me, _face(p, q, d), normal if normal[2] > 0 else -normal, kind=BACKING))
        interfaces.append(Interface(me, me + 1, _face(loop[0], loop[-1], d), np.array([sign, 0.0, 0.0]), kind=BACKING))
    return Assembly(asm.blocks + tuple(new), tuple(interfaces), meta)


def _face(p: np.ndarray, q: np.ndarray, d: float) -> np.ndarray:
    """The rectangle on the segment ``p``-``q`` (``(x, z)``, m) across the depth ``-d .. d``."""
    return np.vstack([_at_depth(np.array([p, q]), -d), _at_depth(np.array([q, p]), d)])
