"""Drawing primitives: blocks, arrows, torque arcs and hinges on plain 2D matplotlib axes.

3D scenes are drawn as orthographic projections onto flat axes (:class:`Camera`), not
with ``mplot3d`` (far slower): one collection of shaded polygons per panel, sorted far to
near, back faces culled, forces on top. An elevation (screen = (x, z)) and a plan
(screen = (x, y)) are exact drawings in metres with true axes.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from matplotlib.axes import Axes
from matplotlib.collections import LineCollection, PolyCollection
from matplotlib.colors import to_rgb
from numpy.typing import NDArray

from ..structures.assembly import Assembly
from ..structures.geometry import PolygonTable

__all__ = ["BlockArt", "Camera", "arrows", "nice", "torque_arcs"]

BLOCK_COLOUR = "#d8c3a0"  # sandstone
SUPPORT_COLOUR = "#8c8c8c"
EDGE_COLOUR = "#4a4a4a"


@dataclass(frozen=True)
class Camera:
    """An orthographic camera: ``elev`` above the x-y plane, ``azim`` from +x about z (degrees),
    as in ``mplot3d``'s ``view_init``. ``eye`` points from the scene towards the viewer."""

    elev: float
    azim: float

    @classmethod
    def elevation(cls) -> Camera:
        """Looking along +y: screen = (x, z)."""
        return cls(0.0, -90.0)

    @classmethod
    def plan(cls) -> Camera:
        """Looking down: screen = (x, y)."""
        return cls(90.0, -90.0)

    @cached_property
    def basis(self) -> NDArray[np.float64]:
        """Rows ``right``, ``up``, ``eye`` (unit, right-handed)."""
        e, a = math.radians(self.elev), math.radians(self.azim)
        eye = np.array([math.cos(e) * math.cos(a), math.cos(e) * math.sin(a), math.sin(e)])
        right = np.array([-math.sin(a), math.cos(a), 0.0])
        up = np.cross(eye, right)
        return np.round(np.vstack([right, up, eye]), 15)

    @property
    def flat(self) -> bool:
        """True for the elevation and the plan (screen axes are global axes)."""
        return (self.elev, self.azim) in ((0.0, -90.0), (90.0, -90.0))

    @property
    def axis_names(self) -> tuple[str, str]:
        """Names of the screen axes for a flat camera."""
        return ("x", "z") if self.elev == 0.0 else ("x", "y")

    def project(self, p: NDArray[np.float64]) -> NDArray[np.float64]:
        """Screen coordinates ``(..., 2)`` of points ``(..., 3)`` (m)."""
        return np.asarray(p, dtype=float) @ self.basis[:2].T

    def depth(self, p: NDArray[np.float64]) -> NDArray[np.float64]:
        """Distance towards the viewer (larger is nearer)."""
        return np.asarray(p, dtype=float) @ self.basis[2]

    @classmethod
    def for_assembly(cls, asm: Assembly, across: bool = False) -> Camera:
        """An axonometric camera, lower for long structures than for domes; turned towards the
        span when ``across`` (forces or motions across the plane to be seen)."""
        ext = np.ptp(np.vstack([b.shape.vertices for b in asm.blocks]), axis=0)
        if ext[0] > 2.5 * max(ext[1], 1e-12):
            return cls(20.0, -38.0) if across else cls(18.0, -62.0)
        return cls(28.0, -55.0)


def nice(x: float) -> float:
    """The 1-2-5 number nearest below ``x`` (> 0)."""
    e = math.floor(math.log10(x))
    f = x / 10**e
    return float((5 if f >= 5 else 2 if f >= 2 else 1) * 10**e)


@dataclass(frozen=True)
class BlockArt:
    """The blocks of an assembly as seen by a camera: shaded polygons sorted far to near,
    built once (:meth:`of`) and drawn in any number of panels (:meth:`draw`)."""

    polygons: list[NDArray[np.float64]]
    facecolors: list
    points: NDArray[np.float64]
    ghost: bool

    @classmethod
    def of(cls, asm: Assembly, camera: Camera, verts: Sequence[NDArray[np.float64]] | None = None,
           ghost: bool = False) -> BlockArt:
        """Blocks (supports grey) with back faces culled; ``verts`` replaces each block's
        vertices (a displaced mechanism); ``ghost`` keeps every face for dashed outlines."""
        verts = [np.asarray(b.shape.vertices, float) for b in asm.blocks] if verts is None else verts
        right, up, eye = camera.basis
        light = eye + 0.6 * up - 0.3 * right
        light /= np.linalg.norm(light)
        faces = [(b, v, v[list(face)]) for b, v in zip(asm.blocks, verts) for face in b.shape.faces]
        normals = PolygonTable.of([p for _, _, p in faces]).newell
        normals /= np.maximum(np.linalg.norm(normals, axis=1), 1e-300)[:, None]
        polys, depth, colours = [], [], []
        for (b, v, p), n in zip(faces, normals):
            if (p.mean(axis=0) - v.mean(axis=0)) @ n < 0:
                n = -n
            if n @ eye <= 1e-9 and not ghost:  # back face (or seen edge-on)
                continue
            base = np.array(to_rgb(SUPPORT_COLOUR if b.support else BLOCK_COLOUR))
            polys.append(camera.project(p))
            depth.append(float(camera.depth(p).mean()))
            colours.append((*np.clip(base * (0.62 + 0.38 * abs(n @ light)), 0, 1), 0.62))
        order = np.argsort(depth, kind="stable")
        return cls([polys[k] for k in order], [colours[k] for k in order], camera.project(np.vstack(verts)), ghost)

    def draw(self, ax: Axes, offset: Sequence[float] = (0.0, 0.0), gid: str = "blocks") -> NDArray[np.float64]:
        """Add the polygons shifted by ``offset`` (gid ``gid``, ``gid + "-ghost"`` for a
        ghost); return the shifted vertices ``(n, 2)``."""
        off = np.asarray(offset, dtype=float)
        coll = PolyCollection(
            [p + off for p in self.polygons],
            facecolors="none" if self.ghost else self.facecolors,
            edgecolors="#9a9a9a" if self.ghost else EDGE_COLOUR,
            linewidths=0.5 if self.ghost else 0.45,
            linestyles="--" if self.ghost else "-",
            zorder=1,
        )
        coll.set_gid(f"{gid}-ghost" if self.ghost else gid)
        ax.add_collection(coll)
        return self.points + off


def arrows(
    ax: Axes,
    start: NDArray[np.float64],
    end: NDArray[np.float64],
    colour: str | Sequence,
    head: float,
    linewidth: float = 1.5,
    gid: str = "",
    zorder: float = 4,
) -> None:
    """Arrows from ``start`` to ``end`` (screen coordinates ``(n, 2)``): one line collection
    of shafts (gid ``gid``) and one polygon collection of heads (``gid + "-heads"``).
    Heads are ``head`` long (screen units), at most 40 % of their arrow."""
    start, end = np.asarray(start, float).reshape(-1, 2), np.asarray(end, float).reshape(-1, 2)
    if not len(start):
        return
    shafts = LineCollection(np.stack([start, end], axis=1), colors=colour, linewidths=linewidth, zorder=zorder,
                            capstyle="butt")
    shafts.set_gid(gid)
    ax.add_collection(shafts)
    d = end - start
    length = np.linalg.norm(d, axis=1)
    keep = length > 1e-12
    if not keep.any():
        return
    u = d[keep] / length[keep, None]
    h = np.minimum(head, 0.4 * length[keep])[:, None]
    n = np.column_stack([-u[:, 1], u[:, 0]])
    tip = end[keep]
    tri = np.stack([tip, tip - h * u + 0.38 * h * n, tip - h * u - 0.38 * h * n], axis=1)
    colours = colour if isinstance(colour, str) else np.asarray(colour, dtype=object)[keep].tolist()
    heads = PolyCollection(tri, facecolors=colours, edgecolors="none", zorder=zorder)
    heads.set_gid(f"{gid}-heads")
    ax.add_collection(heads)


def torque_arcs(
    centres: NDArray[np.float64], normals: NDArray[np.float64], torques: NDArray[np.float64], scale: float
) -> list[NDArray[np.float64]]:
    """3D polylines: a 270-degree arc of radius ``scale * |T|`` around each normal, turning by
    the right-hand rule with the torque's sign, and an arrow head at its end (two polylines
    per torque, arc then head)."""
    c = np.asarray(centres, float).reshape(-1, 3)
    n = np.asarray(normals, float).reshape(-1, 3)
    t = np.asarray(torques, float).ravel()
    if not len(t):
        return []
    ref = np.where(np.abs(n[:, 2:3]) < 0.9, [[0.0, 0.0, 1.0]], [[1.0, 0.0, 0.0]])
    a = np.cross(n, ref)
    a /= np.linalg.norm(a, axis=1)[:, None]
    b = np.cross(n, a)  # (a, b, n) right-handed: positive angle = positive torque
    r = (scale * np.abs(t))[:, None, None]
    phi = np.linspace(0.0, 1.5 * math.pi, 19)[None, :] * np.sign(t)[:, None]
    arcs = c[:, None, :] + r * (np.cos(phi)[..., None] * a[:, None, :] + np.sin(phi)[..., None] * b[:, None, :])
    tip = arcs[:, -1]
    tangent = tip - arcs[:, -2]
    tangent /= np.linalg.norm(tangent, axis=1)[:, None]
    radial = (tip - c) / r[:, 0]
    h = 0.35 * r[:, 0]
    heads = np.stack([tip - h * (tangent - 0.6 * radial), tip, tip - h * (tangent + 0.6 * radial)], axis=1)
    out: list[NDArray[np.float64]] = []
    for arc, head in zip(arcs, heads):
        out += [arc, head]
    return out
