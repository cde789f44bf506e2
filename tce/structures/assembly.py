"""Assemblies of rigid blocks: blocks, interfaces between them, and supports.

Conventions (docs/conventions.md): an interface is the planar contact polygon shared by blocks A and
B; its unit normal ``n`` points from A into B, and its frame is ``(n, t1, t2)`` (rows of
``Interface.frame``, see :func:`tce.geometry.frame_from_normal`). Support blocks have a
prescribed rigid motion about their own centroid; their equilibrium is not enforced.
Lengths in m, unit weights in kN/m^3, weights in kN.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .geometry import (
    GeometryError,
    Polyhedron,
    frame_from_normal,
    newell_normal,
    polygon_area,
    polygon_centroid,
    tributary_areas,
)

__all__ = ["Assembly", "AssemblyError", "Block", "Interface"]


class AssemblyError(ValueError):
    """Raised for an assembly that cannot be analysed (no support, a loose block, ...)."""


@dataclass(frozen=True, eq=False)
class Block:
    """A rigid block.

    Parameters
    ----------
    name : str
        Unique name within its assembly.
    shape : Polyhedron
        Closed polyhedron (m).
    unit_weight : float
        Unit weight (kN/m^3), > 0.
    support : bool
        True for a support block (prescribed motion, takes reactions).
    """

    name: str
    shape: Polyhedron
    unit_weight: float
    support: bool = False

    @property
    def volume(self) -> float:
        """Volume (m^3)."""
        return self.shape.volume

    @property
    def weight(self) -> float:
        """Self-weight (kN)."""
        return self.unit_weight * self.shape.volume

    @property
    def centroid(self) -> NDArray[np.float64]:
        """Centroid (m), where self-weight and lateral loads are applied."""
        return self.shape.centroid


@dataclass(frozen=True, eq=False)
class Interface:
    """Planar contact polygon between blocks ``a`` and ``b`` (indices in the assembly).

    Parameters
    ----------
    a, b : int
        Block indices; the normal points from ``a`` into ``b``.
    points : (k, 3) array_like
        Contact vertices (m), in order around the polygon.
    normal : (3,) array_like, optional
        Unit normal from A into B. Defaults to the Newell normal of ``points``.
    stiffness : float
        Multiplier of the material's stiffness on this interface (> 0; default 1): a mortar
        joint or a stiffer bed, for the compliance term only.
    """

    a: int
    b: int
    points: NDArray[np.float64]
    normal: NDArray[np.float64] | None = field(default=None)
    stiffness: float = 1.0

    def __post_init__(self) -> None:
        p = np.array(self.points, dtype=float)
        if p.ndim != 2 or p.shape[1] != 3 or len(p) < 2:
            raise AssemblyError(f"interface {self.a}-{self.b}: points must be a (k>=2, 3) array")
        if self.normal is None:
            n = newell_normal(p)
        else:
            n = np.asarray(self.normal, dtype=float)
        norm = np.linalg.norm(n)
        if not np.isfinite(norm) or norm == 0.0:
            raise AssemblyError(f"interface {self.a}-{self.b}: cannot determine a normal")
        if not (np.isfinite(self.stiffness) and self.stiffness > 0):
            raise AssemblyError(f"interface {self.a}-{self.b}: stiffness multiplier must be > 0, got {self.stiffness!r}")
        p.setflags(write=False)
        object.__setattr__(self, "points", p)
        object.__setattr__(self, "normal", n / norm)

    @cached_property
    def frame(self) -> NDArray[np.float64]:
        """Rows ``(n, t1, t2)`` of the interface frame."""
        return frame_from_normal(self.normal)

    @cached_property
    def area(self) -> float:
        """Contact area (m^2)."""
        return polygon_area(self.points) if len(self.points) > 2 else 0.0

    @cached_property
    def centroid(self) -> NDArray[np.float64]:
        """Area centroid of the contact polygon (m)."""
        return polygon_centroid(self.points)

    @cached_property
    def tributary(self) -> NDArray[np.float64]:
        """Tributary area of each contact vertex (m^2), used by the compliance."""
        if len(self.points) < 3:
            return np.zeros(len(self.points))
        return tributary_areas(self.points)


@dataclass(frozen=True, eq=False)
class Assembly:
    """Blocks, the interfaces between them and the supports.

    Parameters
    ----------
    blocks : sequence of Block
    interfaces : sequence of Interface
    meta : dict
        Free-form description (generator and parameters), carried into results.
    """

    blocks: tuple[Block, ...]
    interfaces: tuple[Interface, ...]
    meta: dict = field(default_factory=dict)

    def __post_init__(self) -> None:
        object.__setattr__(self, "blocks", tuple(self.blocks))
        object.__setattr__(self, "interfaces", tuple(self.interfaces))

    # ------------------------------------------------------------------ lookups
    @cached_property
    def names(self) -> tuple[str, ...]:
        """Block names, in block order."""
        return tuple(b.name for b in self.blocks)

    @cached_property
    def index(self) -> dict[str, int]:
        """Block index by name."""
        return {n: i for i, n in enumerate(self.names)}

    @cached_property
    def support_indices(self) -> tuple[int, ...]:
        """Indices of the support blocks."""
        return tuple(i for i, b in enumerate(self.blocks) if b.support)

    @cached_property
    def support_names(self) -> tuple[str, ...]:
        """Names of the support blocks, in block order."""
        return tuple(self.blocks[i].name for i in self.support_indices)

    @cached_property
    def free_indices(self) -> tuple[int, ...]:
        """Indices of the free (non-support) blocks."""
        return tuple(i for i, b in enumerate(self.blocks) if not b.support)

    @cached_property
    def centroids(self) -> NDArray[np.float64]:
        """Block centroids, (n_blocks, 3), m."""
        return np.array([b.centroid for b in self.blocks])

    @cached_property
    def weights(self) -> NDArray[np.float64]:
        """Block self-weights, (n_blocks,), kN."""
        return np.array([b.weight for b in self.blocks])

    @property
    def total_weight(self) -> float:
        """Self-weight of the free blocks (kN): the load the supports carry."""
        return float(self.weights[list(self.free_indices)].sum())

    @cached_property
    def size(self) -> float:
        """Characteristic length (m): diagonal of the bounding box of all blocks."""
        pts = np.vstack([b.shape.vertices for b in self.blocks])
        return float(np.linalg.norm(np.ptp(pts, axis=0)))

    # ------------------------------------------------------------------ edits
    def with_supports(self, names: Iterable[str]) -> Assembly:
        """A copy in which exactly the named blocks are supports."""
        names = list(names)
        unknown = [n for n in names if n not in self.index]
        if unknown:
            raise AssemblyError(
                f"unknown support block(s) {unknown}; blocks are {list(self.names)}"
            )
        chosen = set(names)
        blocks = tuple(replace(b, support=b.name in chosen) for b in self.blocks)
        return replace(self, blocks=blocks)

    def with_interfaces(self, interfaces: Sequence[Interface]) -> Assembly:
        """A copy with the given interfaces (for example, found by contact detection)."""
        return replace(self, interfaces=tuple(interfaces))

    def scaled(self, length: float = 1.0, force: float = 1.0) -> Assembly:
        """The same assembly in other units: lengths times ``length``, forces times ``force``.

        Unit weights scale by ``force / length**3``.
        """
        blocks = tuple(
            replace(
                b,
                shape=Polyhedron(b.shape.vertices * length, b.shape.faces),
                unit_weight=b.unit_weight * force / length**3,
            )
            for b in self.blocks
        )
        interfaces = tuple(
            Interface(i.a, i.b, i.points * length, i.normal, i.stiffness) for i in self.interfaces
        )
        return replace(self, blocks=blocks, interfaces=interfaces)

    # ------------------------------------------------------------------ serialisation
    def to_dict(self) -> dict:
        """Plain-data form (tce's block format): blocks with ``name``, ``vertices`` (m),
        ``faces``, ``support``, ``unit_weight`` (kN/m^3); interfaces with block names
        ``a``, ``b``, ``points`` (m) and ``normal``; and ``meta``."""
        return {
            "blocks": [
                {
                    "name": b.name,
                    "vertices": b.shape.vertices.tolist(),
                    "faces": [list(f) for f in b.shape.faces],
                    "support": bool(b.support),
                    "unit_weight": float(b.unit_weight),
                }
                for b in self.blocks
            ],
            "interfaces": [
                {
                    "a": self.names[i.a],
                    "b": self.names[i.b],
                    "points": i.points.tolist(),
                    "normal": i.normal.tolist(),
                    "stiffness": float(i.stiffness),
                }
                for i in self.interfaces
            ],
            "meta": dict(self.meta),
        }

    @classmethod
    def from_dict(cls, data: dict) -> Assembly:
        """Inverse of :meth:`to_dict` (interfaces may be absent: detect them separately)."""
        blocks = tuple(
            Block(
                str(b["name"]),
                Polyhedron(np.asarray(b["vertices"], dtype=float), [tuple(f) for f in b["faces"]]),
                float(b["unit_weight"]),
                bool(b.get("support", False)),
            )
            for b in data["blocks"]
        )
        index = {b.name: k for k, b in enumerate(blocks)}
        interfaces = tuple(
            Interface(
                index[i["a"]], index[i["b"]], np.asarray(i["points"], float), i.get("normal"), float(i.get("stiffness", 1.0))
            )
            for i in data.get("interfaces", [])
        )
        return cls(blocks, interfaces, dict(data.get("meta", {})))

    # ------------------------------------------------------------------ checks
    def validate(self) -> Assembly:
        """Check the assembly and return it.

        Raises
        ------
        AssemblyError
            Duplicate names, a non-positive or non-finite unit weight, an interface that
            refers to a missing block or joins a block to itself, no support, no free
            block, a block that touches nothing, or a degenerate interface.
        GeometryError
            A block that is not a valid closed polyhedron (named).
        """
        if len(set(self.names)) != len(self.names):
            dup = sorted({n for n in self.names if self.names.count(n) > 1})
            raise AssemblyError(f"duplicate block names {dup}")
        for b in self.blocks:
            if not (np.isfinite(b.unit_weight) and b.unit_weight > 0):
                raise AssemblyError(
                    f"block {b.name!r}: unit weight must be a positive number, got {b.unit_weight}"
                )
            try:
                b.shape.validate(name=f"block {b.name!r}")
            except GeometryError:
                raise
        if not self.support_indices:
            raise AssemblyError("the assembly has no support block: mark at least one block as support")
        if not self.free_indices:
            raise AssemblyError("every block is a support: nothing to analyse")
        touched = np.zeros(len(self.blocks), dtype=bool)
        nb = len(self.blocks)
        for k, i in enumerate(self.interfaces):
            if not (0 <= i.a < nb and 0 <= i.b < nb) or i.a == i.b:
                raise AssemblyError(f"interface {k} joins blocks {i.a} and {i.b}: invalid")
            if len(i.points) < 3 or i.area <= 0.0:
                raise AssemblyError(
                    f"interface {k} between {self.names[i.a]!r} and {self.names[i.b]!r} has no area"
                )
            touched[[i.a, i.b]] = True
        loose = [self.names[k] for k in range(nb) if not touched[k]]
        if loose:
            raise AssemblyError(f"block(s) {loose} touch nothing: no interface found for them")
        return self
