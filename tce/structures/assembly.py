"""Assemblies of rigid blocks: blocks, interfaces between them, and supports.

Conventions (docs/conventions.md): an interface is the planar contact polygon shared by blocks A and
B; its unit normal ``n`` points from A into B, and its frame is ``(n, t1, t2)`` (rows of
``Interface.frame``, see :func:`tce.structures.geometry.frame_from_normal`). Support blocks have a
prescribed rigid motion about their own centroid; their equilibrium is not enforced.
Lengths in m, unit weights in kN/m^3, weights in kN.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from .. import display

from .geometry import (
    FaceTable,
    GeometryError,
    PolygonTable,
    Polyhedron,
    frame_from_normal,
    frames_from_normals,
    newell_normal,
    polygon_area,
    polygon_centroid,
    tributary_areas,
)

__all__ = ["Assembly", "AssemblyError", "Block", "Interface", "InterfaceTable"]


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

    def __repr__(self) -> str:
        kind = "support, " if self.support else ""
        return display.call("Block", {"volume": self.volume, "unit_weight": self.unit_weight},
                            head=f"{self.name!r}, {kind}{len(self.shape.vertices)} vertices")


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
    kind : str
        What joint this is (``""``, the default: an ordinary joint; ``"ring"``: between two
        rings of a multi-ring arch). A material may give a kind its own contact law
        (:attr:`tce.core.material.Material.interfaces`).
    """

    a: int
    b: int
    points: NDArray[np.float64]
    normal: NDArray[np.float64] | None = field(default=None)
    stiffness: float = 1.0
    kind: str = ""

    def __post_init__(self) -> None:
        p = np.array(self.points, dtype=float)
        if p.ndim != 2 or p.shape[1] != 3 or len(p) < 2:
            raise AssemblyError(f"interface {self.a}-{self.b}: points must be a (k>=2, 3) array")
        if self.normal is None:
            n = newell_normal(p)
        else:
            n = np.asarray(self.normal, dtype=float).ravel()
        norm = float(np.sqrt(n @ n)) if n.shape == (3,) else float("nan")
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

    def __repr__(self) -> str:
        normal = "(" + ", ".join(f"{v:.3g}" for v in self.normal) + ")"
        return display.call("Interface", {"area": self.area, "stiffness": self.stiffness},
                            head=f"{self.a}-{self.b}, {len(self.points)} vertices, normal {normal}")


@dataclass(frozen=True, eq=False)
class InterfaceTable:
    """The interfaces of an assembly as arrays (what :class:`Interface` gives one by one).

    Attributes
    ----------
    a, b : (ni,) ndarray of int
        Blocks of each interface; the normal points from ``a`` into ``b``.
    polygons : PolygonTable
        Contact vertices of every interface, one interface after the other (m).
    normal : (ni, 3) ndarray
        Unit normals.
    stiffness : (ni,) ndarray
        Stiffness multipliers.
    kind : (ni,) ndarray of str (object)
        Interface kinds (:attr:`Interface.kind`).
    """

    a: NDArray[np.int64]
    b: NDArray[np.int64]
    polygons: PolygonTable
    normal: NDArray[np.float64]
    stiffness: NDArray[np.float64]
    kind: NDArray[np.object_]

    @classmethod
    def of(cls, interfaces: Sequence[Interface]) -> InterfaceTable:
        n = len(interfaces)
        return cls(
            np.fromiter((i.a for i in interfaces), dtype=np.int64, count=n),
            np.fromiter((i.b for i in interfaces), dtype=np.int64, count=n),
            PolygonTable.of([i.points for i in interfaces]),
            np.array([i.normal for i in interfaces], dtype=float).reshape(n, 3),
            np.fromiter((i.stiffness for i in interfaces), dtype=float, count=n),
            np.array([i.kind for i in interfaces], dtype=object),
        )

    def __len__(self) -> int:
        return len(self.a)

    @property
    def points(self) -> NDArray[np.float64]:
        """Every contact vertex, (nv, 3) (m)."""
        return self.polygons.points

    @property
    def start(self) -> NDArray[np.int64]:
        """Interface ``k`` owns vertices ``start[k]:start[k + 1]``, (ni + 1,)."""
        return self.polygons.start

    @property
    def vertex_interface(self) -> NDArray[np.int64]:
        """Interface of every vertex, (nv,)."""
        return self.polygons.owner

    @cached_property
    def frame(self) -> NDArray[np.float64]:
        """Frames ``(n, t1, t2)`` as rows, (ni, 3, 3) (see :func:`tce.structures.geometry.frames_from_normals`)."""
        return frames_from_normals(self.normal)

    @property
    def area(self) -> NDArray[np.float64]:
        """Contact areas (m^2), (ni,)."""
        return self.polygons.area

    @property
    def centroid(self) -> NDArray[np.float64]:
        """Area centroids of the contact polygons (m), (ni, 3)."""
        return self.polygons.centroid

    @property
    def tributary(self) -> NDArray[np.float64]:
        """Tributary area of every vertex (m^2), (nv,)."""
        return self.polygons.tributary


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
    def face_table(self) -> FaceTable:
        """The faces of every block, flattened (block order)."""
        return FaceTable.of([b.shape for b in self.blocks])

    @cached_property
    def interface_table(self) -> InterfaceTable:
        """The interfaces as arrays (interface order)."""
        return InterfaceTable.of(self.interfaces)

    @property
    def volumes(self) -> NDArray[np.float64]:
        """Block volumes, (n_blocks,), m^3."""
        return self.face_table.volume

    @property
    def centroids(self) -> NDArray[np.float64]:
        """Block centroids, (n_blocks, 3), m."""
        return self.face_table.centroid

    @cached_property
    def unit_weights(self) -> NDArray[np.float64]:
        """Block unit weights, (n_blocks,), kN/m^3."""
        return np.fromiter((b.unit_weight for b in self.blocks), dtype=float, count=len(self.blocks))

    @cached_property
    def weights(self) -> NDArray[np.float64]:
        """Block self-weights, (n_blocks,), kN."""
        return self.unit_weights * self.volumes

    @property
    def sizes(self) -> NDArray[np.float64]:
        """Bounding-box diagonal of every block, (n_blocks,), m."""
        return self.face_table.size

    @property
    def total_weight(self) -> float:
        """Self-weight of the free blocks (kN): the load the supports carry."""
        return float(self.weights[list(self.free_indices)].sum())

    @cached_property
    def size(self) -> float:
        """Characteristic length (m): diagonal of the bounding box of all blocks."""
        return float(np.linalg.norm(np.ptp(self.face_table.points, axis=0)))

    @property
    def extent(self) -> NDArray[np.float64]:
        """Size of the bounding box of all blocks along x, y, z (m), (3,)."""
        return np.ptp(self.face_table.points, axis=0)

    # ------------------------------------------------------------------ display
    def _facts(self) -> dict[str, str]:
        """What the repr and the HTML table show: counts, supports, weight, extent, origin."""
        dx, dy, dz = self.extent
        facts = {
            "blocks": str(len(self.blocks)),
            "supports": f"{len(self.support_indices)} {display.names(self.support_names, 3)}",
            "interfaces": str(len(self.interfaces)),
            "weight": f"{self.total_weight:.4g} kN (free blocks)",
            "extent": f"{dx:.4g} x {dy:.4g} x {dz:.4g} m (x, y, z)",
        }
        if "generator" in self.meta:
            facts["generator"] = str(self.meta["generator"])
        return facts

    def __repr__(self) -> str:
        f = self._facts()
        text = (f"{f['blocks']} blocks, {f['supports'].replace(' ', ' supports ', 1)}, {f['interfaces']} interfaces, "
                f"weight {f['weight']}, extent {f['extent']}" + (f", {f['generator']}" if "generator" in f else ""))
        return display.call("Assembly", {}, head=text)

    def _repr_html_(self) -> str:
        return display.html_table("Assembly", self._facts().items())

    # ------------------------------------------------------------------ edits
    def with_supports(self, names: Iterable[str]) -> Assembly:
        """A copy in which exactly the named blocks are supports."""
        names = list(names)
        unknown = [n for n in names if n not in self.index]
        if unknown:
            raise AssemblyError(f"unknown support block(s) {unknown}; blocks are {list(self.names)}")
        chosen = set(names)
        return replace(self, blocks=tuple(replace(b, support=b.name in chosen) for b in self.blocks))

    def with_interfaces(self, interfaces: Sequence[Interface]) -> Assembly:
        """A copy with the given interfaces (for example, found by contact detection)."""
        return replace(self, interfaces=tuple(interfaces))

    def scaled(self, length: float = 1.0, force: float = 1.0) -> Assembly:
        """The same assembly in other units: lengths times ``length``, forces times ``force``.

        Unit weights scale by ``force / length**3``.
        """
        blocks = tuple(replace(b, shape=Polyhedron(b.shape.vertices * length, b.shape.faces),
                               unit_weight=b.unit_weight * force / length**3) for b in self.blocks)
        interfaces = tuple(replace(i, points=i.points * length) for i in self.interfaces)
        return replace(self, blocks=blocks, interfaces=interfaces)

    # ------------------------------------------------------------------ serialisation
    def to_dict(self) -> dict:
        """Plain-data form (tce's block format): blocks with ``name``, ``vertices`` (m),
        ``faces``, ``support``, ``unit_weight`` (kN/m^3); interfaces with block names
        ``a``, ``b``, ``points`` (m), ``normal``, ``stiffness`` and, when not ``""``,
        ``kind``; and ``meta``."""
        blocks = [{"name": b.name, "vertices": b.shape.vertices.tolist(), "faces": [list(f) for f in b.shape.faces],
                   "support": bool(b.support), "unit_weight": float(b.unit_weight)} for b in self.blocks]
        interfaces = [{"a": self.names[i.a], "b": self.names[i.b], "points": i.points.tolist(),
                       "normal": i.normal.tolist(), "stiffness": float(i.stiffness)} | ({"kind": i.kind} if i.kind else {})
                      for i in self.interfaces]
        return {"blocks": blocks, "interfaces": interfaces, "meta": dict(self.meta)}

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
                index[i["a"]], index[i["b"]], np.asarray(i["points"], float), i.get("normal"), float(i.get("stiffness", 1.0)),
                str(i.get("kind", "")),
            )
            for i in data.get("interfaces", [])
        )
        return cls(blocks, interfaces, dict(data.get("meta", {})))

    # ------------------------------------------------------------------ checks
    def validate(self) -> Assembly:
        """Check the assembly and return it (the checks run once per assembly).

        Raises
        ------
        AssemblyError
            Duplicate names, a non-positive or non-finite unit weight, an interface that
            refers to a missing block or joins a block to itself, no support, no free
            block, a block that touches nothing, or a degenerate interface.
        GeometryError
            A block that is not a valid closed polyhedron (named).
        """
        return self._validated

    @cached_property
    def _validated(self) -> Assembly:
        if len(set(self.names)) != len(self.names):
            raise AssemblyError(f"duplicate block names {sorted(n for n, c in Counter(self.names).items() if c > 1)}")
        # blocks in order: a block's unit weight is checked before its geometry
        uw = self.unit_weights
        bad_weight = np.flatnonzero(~(np.isfinite(uw) & (uw > 0)))
        fault = self.face_table.first_fault()
        if len(bad_weight) and (fault is None or bad_weight[0] <= fault[0]):
            b = self.blocks[bad_weight[0]]
            raise AssemblyError(f"block {b.name!r}: unit weight must be a positive number, got {b.unit_weight}")
        if fault is not None:
            raise GeometryError(f"block {self.names[fault[0]]!r}: {fault[1]}")
        if not self.support_indices:
            raise AssemblyError("the assembly has no support block: mark at least one block as support")
        if not self.free_indices:
            raise AssemblyError("every block is a support: nothing to analyse")
        nb = len(self.blocks)
        t = self.interface_table
        invalid = ~((0 <= t.a) & (t.a < nb) & (0 <= t.b) & (t.b < nb)) | (t.a == t.b)
        no_area = (t.polygons.counts < 3) | ~(t.area > 0.0)
        wrong = np.flatnonzero(invalid | no_area)
        if len(wrong):
            k = int(wrong[0])
            if invalid[k]:
                raise AssemblyError(f"interface {k} joins blocks {t.a[k]} and {t.b[k]}: invalid")
            raise AssemblyError(
                f"interface {k} between {self.names[t.a[k]]!r} and {self.names[t.b[k]]!r} has no area"
            )
        touched = np.zeros(nb, dtype=bool)
        touched[t.a] = touched[t.b] = True
        loose = [self.names[k] for k in np.flatnonzero(~touched)]
        if loose:
            raise AssemblyError(f"block(s) {loose} touch nothing: no interface found for them")
        return self
