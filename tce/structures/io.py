"""Reading and writing block assemblies.

Three input formats, chosen by :func:`load_assembly` from the extension and the content:

tce JSON (``.json`` with a top-level ``"blocks"`` list); see ``docs/assembly-format.md``::

    {
      "format": "tce-assembly",            # optional tag
      "version": 1,                        # optional
      "units": {"length": "m", "force": "kN"},   # optional; length m|cm|mm, force kN|N
      "unit_weight": 20.0,                 # optional default, force/length^3 (kN/m^3)
      "blocks": [
        {"name": "b1",                     # unique; defaults to "b<index>"
         "vertices": [[x, y, z], ...],
         "faces": [[i, j, k, ...], ...],   # 0-based, counter-clockwise seen from outside
         "support": false,                 # optional
         "unit_weight": 22.0},             # optional, overrides the default
        ...
      ],
      "interfaces": [                      # optional; detected from the geometry if absent
        {"a": "b1", "b": "b2", "points": [[x, y, z], ...], "normal": [nx, ny, nz]}
      ],
      "meta": {...}                        # optional, free-form
    }

Wavefront OBJ (``.obj``)
    One object (``o name``, or ``g name``) per block; ``v`` lines and ``f`` lines (1-based
    or negative indices, ``i/t/n`` forms accepted; faces counter-clockwise seen from
    outside). OBJ has no supports: name them with ``supports=``.

COMPAS assembly JSON (``.json`` with ``dtype``/``data`` and a graph, as written by
compas_assembly and compas_cra)
    ``data.graph.data.node`` maps node keys to ``{"block": {"data": {"vertex": {id: {x, y,
    z}}, "face": {id: [vertex ids]}}}, "is_support": bool}`` (the ``data`` wrappers and the
    ``is_support`` flag are optional; vertices may also be ``[x, y, z]`` lists). Blocks
    are named after their node keys (``"0"``, ``"1"``, ...) in key order. A non-planar face
    of a COMPAS block is split into a fan of triangles by default (COMPAS meshes may have
    them). Interfaces stored on the edges (``data.graph.data.edge[u][v]["interfaces"]``: a
    polygon ``points`` with a ``frame`` whose z axis points from block u into block v) are
    used after checks. COMPAS 2 ``Point`` objects (``{"dtype": "compas.geometry/Point",
    "data": [x, y, z]}``) are read wherever a point is expected.

compas_dem ``BlockModel`` JSON (``data.elements`` and ``data.graph``)
    Each graph node names an element (``{"element": guid}``): a ``Block`` whose ``geometry``
    is its mesh, with ``is_support`` and an optional ``transformation`` (applied). Contacts
    on the edges (``"contacts"``, ``FrictionContact`` objects) are stored interfaces.

Every value is checked for its type, not its truthiness (``"support": "no"`` is an error;
a face index must be a whole number, a coordinate a JSON number, a name a string), and an
error names the file and the key (``blocks[1] (top).faces[0][2]``): a tce file through the
pydantic model :class:`TceAssemblyFile`, a (free-form) COMPAS file through typed access to
the values tce reads.

Stored interfaces (tce or COMPAS)
    A file's interfaces are used instead of detection (the fallback when it stores none).
    Each is checked: at least three points; planar (every point within ``min(tol, 1e-6) L``
    of the polygon's plane, ``L`` the larger size of its two blocks), in the plane of its
    frame when it has one; and on the surface of **both** its blocks (every point within
    ``interface_tol * L`` of a face of each). ``interface_tol`` is loose by default (5e-3)
    because curved contacts stored by COMPAS approximate two facetted surfaces meshed
    differently; the overlap check then tolerates a depth of ``interface_tol * L`` too. The
    normal is oriented from block A (the one of lower index) into block B by the faces it
    lies on. A failed check names the file, the interface (``A|B``) and what is wrong.

Limits (:class:`InputLimitError`, naming the limit): a file of at most
:data:`MAX_FILE_BYTES`, JSON nested at most :data:`MAX_DEPTH` deep (checked before decoding),
at most :data:`MAX_BLOCKS` blocks,
:data:`MAX_BLOCK_VERTICES` vertices per block and :data:`MAX_VERTICES` in all. The path
must be a regular file (not a folder, a device or a pipe).

Units are SI (m, kN) after loading. Every loaded block is checked (closed, consistently
oriented, planar faces, positive volume), blocks must not overlap
(:func:`tce.structures.contacts.check_overlaps`), interfaces are read and checked or detected
(:func:`tce.structures.contacts.detect_interfaces`) and the assembly is validated (a support, no
loose block). Errors name the file and the block or interface.
"""

from __future__ import annotations

import json
import logging
import math
import re
import stat
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Annotated, Any, Literal

import numpy as np

import shapely
from pydantic import AfterValidator, BaseModel, BeforeValidator, ConfigDict, Field, TypeAdapter, ValidationError
from shapely.geometry import Polygon

from ..files import atomic_write
from ..messages import describe, did_you_mean
from ..messages import key as location_key
from .assembly import Assembly, AssemblyError, Block, Interface
from .contacts import check_overlaps, detect_interfaces
from .geometry import GeometryError, Polyhedron, frame_from_normal, newell_normal
from .params import MAX_BLOCKS

__all__ = [
    "MAX_BLOCKS",
    "MAX_BLOCK_VERTICES",
    "MAX_DEPTH",
    "MAX_FILE_BYTES",
    "MAX_VERTICES",
    "InputLimitError",
    "TceAssemblyFile",
    "load_assembly",
    "read_compas_json",
    "read_obj",
    "read_tce_json",
    "save_assembly_json",
]

log = logging.getLogger(__name__)

#: Largest block file read (bytes).
MAX_FILE_BYTES = 256 * 2**20
#: Deepest nesting of JSON arrays and objects (a tce file needs 4, a COMPAS file about 8).
MAX_DEPTH = 64
#: Most vertices of one block.
MAX_BLOCK_VERTICES = 10_000
#: Most vertices of all blocks together.
MAX_VERTICES = 2_000_000

DEFAULT_UNIT_WEIGHT = 20.0
#: Planarity tolerance of faces, relative to the block size: the one Assembly.validate uses.
PLANAR_TOL = 1e-6
#: Default distance (relative to the larger block size) of a stored interface from its blocks' faces.
INTERFACE_TOL = 5e-3
_LENGTH = {"m": 1.0, "cm": 0.01, "mm": 0.001}
_FORCE = {"kN": 1.0, "N": 0.001}


@dataclass
class RawBlock:
    """A block as read from a file, before checks (lengths in the file's units)."""

    name: str
    vertices: np.ndarray
    faces: list[list[int]]
    support: bool = False
    unit_weight: float | None = None


@dataclass
class RawAssembly:
    """What a reader returns: blocks, optional interfaces, defaults and units."""

    blocks: list[RawBlock]
    interfaces: list[dict] | None = None
    unit_weight: float | None = None
    length: float = 1.0  # file length unit in m
    force: float = 1.0  # file force unit in kN
    meta: dict = field(default_factory=dict)


class InputLimitError(AssemblyError):
    """A block file beyond one of the module's limits (size, nesting, block or vertex count)."""


# ---------------------------------------------------------------------- readers
def _err(path: Path | str, msg: str) -> AssemblyError:
    return AssemblyError(f"{path}: {msg}")


def _check_file(path: Path) -> None:
    """Refuse what is not a regular file of at most :data:`MAX_FILE_BYTES`."""
    try:
        info = path.stat()
    except FileNotFoundError:
        raise FileNotFoundError(f"{path}: no such file") from None
    if not stat.S_ISREG(info.st_mode):
        raise _err(path, "not a regular file (a folder, device or pipe cannot hold blocks)")
    if info.st_size > MAX_FILE_BYTES:
        raise InputLimitError(f"{path}: {info.st_size} bytes, more than MAX_FILE_BYTES = {MAX_FILE_BYTES}")


def _read_text(path: Path) -> str:
    """The text of a regular file of at most :data:`MAX_FILE_BYTES`."""
    _check_file(path)
    try:
        return path.read_text(encoding="utf-8")
    except UnicodeDecodeError as exc:
        raise _err(path, f"not a text file ({exc})") from None


_JSON_STRING = re.compile(r'"(?:[^"\\]|\\.)*"')


def _load_json(path: Path, text: str) -> Any:
    """Decode JSON ``text`` after checking, in one linear pass, that it nests at most
    :data:`MAX_DEPTH` deep (the decoder recurses once per level)."""
    bare = np.frombuffer(_JSON_STRING.sub("", text).encode("utf-8"), dtype=np.uint8)
    step = np.isin(bare, (ord("["), ord("{"))).astype(np.int64) - np.isin(bare, (ord("]"), ord("}")))
    depth = int(np.cumsum(step).max(initial=0))
    if depth > MAX_DEPTH:
        raise InputLimitError(f"{path}: JSON nested {depth} deep, more than MAX_DEPTH = {MAX_DEPTH}")
    try:
        return json.loads(text)
    except json.JSONDecodeError as exc:
        raise _err(path, f"not valid JSON ({exc})") from None


def _check_counts(path: Path, blocks: list[RawBlock]) -> None:
    """Refuse more than :data:`MAX_BLOCKS` blocks or too many vertices, naming the limit."""
    if len(blocks) > MAX_BLOCKS:
        raise InputLimitError(f"{path}: {len(blocks)} blocks, more than MAX_BLOCKS = {MAX_BLOCKS}")
    for b in blocks:
        if len(b.vertices) > MAX_BLOCK_VERTICES:
            raise InputLimitError(
                f"{path}: block {b.name!r} has {len(b.vertices)} vertices, more than MAX_BLOCK_VERTICES = {MAX_BLOCK_VERTICES}"
            )
    total = sum(len(b.vertices) for b in blocks)
    if total > MAX_VERTICES:
        raise InputLimitError(f"{path}: {total} vertices, more than MAX_VERTICES = {MAX_VERTICES}")


def _point_data(value: Any) -> Any:
    """The data of a COMPAS 2 ``Point`` or ``Vector`` (``{"dtype": "compas.geometry/Point",
    "data": [x, y, z]}``); any other value as it is."""
    if isinstance(value, Mapping) and "dtype" in value:
        if not str(value["dtype"]).endswith(("/Point", "/Vector")):
            raise ValueError(f"must be a point, got a {value['dtype']!r}; fix: write [x, y, z]")
        return value.get("data")
    return value


class _Doc:
    """Typed access to a decoded COMPAS document (free-form: tce reads some of its values): each
    value read is checked for its type (not its truthiness), and every error names the file
    and the key (``graph.node.1.vertex.0.x``)."""

    def __init__(self, path: Path) -> None:
        self.path = path

    def fail(self, key: str, msg: str) -> AssemblyError:
        return AssemblyError(f"{self.path}: {key}: {msg}")

    @staticmethod
    def _got(value: Any) -> str:
        text = json.dumps(value) if isinstance(value, (str, int, float, bool, type(None))) else repr(value)
        return text if len(text) <= 40 else text[:37] + "..."

    def _typed(self, key: str, value: Any, kind: type, words: str) -> Any:
        if not isinstance(value, kind):
            raise self.fail(key, f"must be {words}, got {self._got(value)}")
        return value

    def obj(self, key: str, value: Any) -> Mapping:
        return self._typed(key, value, Mapping, "an object {...}")

    def array(self, key: str, value: Any) -> list:
        return self._typed(key, value, list, "a list [...]")

    def flag(self, key: str, value: Any) -> bool:
        return self._typed(key, value, bool, "true or false")

    def number(self, key: str, value: Any, positive: bool = False) -> float:
        """A finite JSON number (not a boolean, not a quoted number); ``> 0`` when ``positive``."""
        ok = isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)
        if not ok or (positive and not value > 0):
            raise self.fail(key, f"must be a finite number{' > 0' if positive else ''}, got {self._got(value)}")
        return float(value)

    def point(self, key: str, value: Any) -> list[float]:
        """``[x, y, z]``, ``{"x": .., "y": .., "z": ..}`` or a COMPAS 2 ``Point``
        (``{"dtype": "compas.geometry/Point", "data": [x, y, z]}``)."""
        try:
            value = _point_data(value)
        except ValueError as exc:
            raise self.fail(key, str(exc)) from None
        if isinstance(value, Mapping):
            return [self.number(f"{key}.{c}", value.get(c)) for c in "xyz"]
        if not isinstance(value, list) or len(value) != 3:
            raise self.fail(key, f"must be a point [x, y, z], got {self._got(value)}")
        return [self.number(f"{key}[{i}]", c) for i, c in enumerate(value)]

    def points(self, key: str, value: Any) -> np.ndarray:
        return np.array([self.point(f"{key}[{i}]", p) for i, p in enumerate(self.array(key, value))], dtype=float).reshape(-1, 3)


# ------------------------------------------------------ the tce JSON format, as pydantic models
def _given(value: Any) -> Any:
    """Refuse an explicit ``null`` where a key may only be left out."""
    if value is None:
        raise ValueError("null is not a value here; fix: give a value or leave the key out")
    return value


def _as_list(value: Any) -> Any:
    """A COMPAS 2 ``Point`` or ``{"x": .., "y": .., "z": ..}`` as ``[x, y, z]``; any other
    value as it is."""
    value = _point_data(value)
    if isinstance(value, Mapping) and {"x", "y", "z"} & set(value):
        return [value.get(c) for c in "xyz"]
    return value


def _version_1(value: int) -> int:
    if value != 1:
        raise ValueError(f"this tce reads version 1; fix: write 1 (a file of version {value} needs another tce)")
    return value


Absent = AfterValidator(_given)
Positive = Annotated[float, Field(gt=0)]
#: a non-empty name without control characters (names become labels and file names)
Name = Annotated[str, Field(min_length=1, pattern=r"^[^\x00-\x1f\x7f]*$")]
Point = Annotated[list[float], BeforeValidator(_as_list), Field(min_length=3, max_length=3)]
Face = Annotated[list[int], Field(min_length=3)]
_NAME = TypeAdapter(Name, config=ConfigDict(strict=True))


class _Strict(BaseModel):
    # a number is a JSON number (not a boolean, not quoted, finite), a flag true or false
    model_config = ConfigDict(extra="forbid", allow_inf_nan=False, frozen=True, strict=True)


class UnitsItem(_Strict):
    """``units``: the file's length and force units."""

    length: Literal["m", "cm", "mm"] = "m"
    force: Literal["kN", "N"] = "kN"


class BlockItem(_Strict):
    """One of ``blocks``: its name (default ``b<position>``), vertices, faces (0-based
    indices, counter-clockwise seen from outside), support flag and unit weight."""

    name: Annotated[Name | None, Absent] = None
    vertices: list[Point]
    faces: list[Face]
    support: bool = False
    unit_weight: Annotated[Positive | None, Absent] = None


class InterfaceItem(_Strict):
    """One of ``interfaces``: blocks ``a`` and ``b`` by name, the polygon ``points``, an
    optional ``normal`` from ``a`` into ``b``, a stiffness multiplier and a ``kind`` (a label a
    material may give its own contact law, e.g. ``"ring"``)."""

    a: Name
    b: Name
    points: list[Point]
    normal: Point | None = None
    stiffness: Positive = 1.0
    kind: str = ""


class TceAssemblyFile(_Strict):
    """A tce JSON assembly (``docs/assembly-format.md``)."""

    format: Literal["tce-assembly"] = "tce-assembly"
    version: Annotated[int, AfterValidator(_version_1)] = 1
    units: UnitsItem = UnitsItem()
    unit_weight: Annotated[Positive | None, Absent] = None
    blocks: list[BlockItem]
    interfaces: Annotated[list[InterfaceItem] | None, Absent] = None
    meta: dict[str, Any] = Field(default_factory=dict)


#: hints of a block file that replace :data:`tce.messages.HINTS`
_HINTS = {
    "model_type": "it must be an object {{...}} of the keys in docs/assembly-format.md",
    "dict_type": "it must be an object {{...}}",
    "string_pattern_mismatch": "remove the control characters",
    "too_short": "give at least {min_length} items ([x, y, z] for a point, 3 vertex indices for a face)",
    "too_long": "give exactly 3 numbers [x, y, z]",  # only a point has a longest length
}


def _where(d: Mapping) -> Callable[[tuple[Any, ...]], str]:
    """The key of a location in the tce document ``d``, a block's name beside its position
    (``blocks[1] (top).support``) when it has a valid one."""

    def where(loc: tuple[Any, ...]) -> str:
        text = location_key(loc)
        if len(loc) > 2 and loc[0] == "blocks" and loc[2] != "name":
            block = d["blocks"][loc[1]]
            try:
                name = _NAME.validate_python(block.get("name"))
            except (ValidationError, AttributeError):  # no valid name, or the block is no object
                return text
            text = text.replace(f"blocks[{loc[1]}]", f"blocks[{loc[1]}] ({name})", 1)
        return text

    return where


def read_tce_json(path: str | Path, data: Mapping | None = None) -> RawAssembly:
    """Parse a tce JSON assembly (see module docstring), checking every value's type
    (:class:`TceAssemblyFile`); the first problem is raised, naming the file and the key."""
    path = Path(path)
    d = _load_json(path, _read_text(path)) if data is None else data
    if not isinstance(d, Mapping) or "blocks" not in d:
        raise _err(path, f'not a tce assembly: expected an object with a "blocks" list, got {_kind(d)}')
    if isinstance(d["blocks"], list) and len(d["blocks"]) > MAX_BLOCKS:
        raise InputLimitError(f"{path}: {len(d['blocks'])} blocks, more than MAX_BLOCKS = {MAX_BLOCKS}")
    try:
        doc = TceAssemblyFile.model_validate(d)
    except ValidationError as exc:
        raise AssemblyError(describe(path, exc, TceAssemblyFile, "docs/assembly-format.md", _HINTS, where=_where(d))[0]) from None
    blocks = []
    for k, b in enumerate(doc.blocks):
        name = b.name if b.name is not None else f"b{k + 1}"
        for i, face in enumerate(b.faces):
            for j, index in enumerate(face):
                if not 0 <= index < len(b.vertices):
                    raise AssemblyError(
                        f"{path}: {_where(d)(('blocks', k, 'faces', i, j))}: must be a vertex index, a whole number "
                        f"from 0 to {len(b.vertices) - 1}, got {index}"
                    )
        vertices = np.array(b.vertices, dtype=float).reshape(-1, 3)
        blocks.append(RawBlock(name, vertices, [list(f) for f in b.faces], b.support, b.unit_weight))
    interfaces = None
    if doc.interfaces is not None:
        interfaces = [it.model_dump() | {"label": f"interfaces[{k}]"} for k, it in enumerate(doc.interfaces)]
    return RawAssembly(
        blocks, interfaces, doc.unit_weight, _LENGTH[doc.units.length], _FORCE[doc.units.force], dict(doc.meta)
    )


def _kind(value: Any) -> str:
    """What a decoded JSON value is, in words."""
    if isinstance(value, Mapping):
        return f"an object with keys {list(value)[:6]}"
    return {list: "a JSON list", str: "a JSON string", bool: "a JSON boolean", type(None): "null"}.get(
        type(value), "a JSON number"
    )


def read_obj(path: str | Path) -> RawAssembly:
    """Parse a Wavefront OBJ file: one object (``o`` or ``g``) per block."""
    path = Path(path)
    verts: list[list[float]] = []
    groups: list[tuple[str, list[list[int]]]] = []
    for lineno, line in enumerate(_read_text(path).splitlines(), 1):
        tok = line.split("#", 1)[0].split()
        if not tok:
            continue
        try:
            if tok[0] == "v":
                xyz = [float(x) for x in tok[1:4]]
                if len(xyz) != 3 or not all(math.isfinite(c) for c in xyz):
                    raise ValueError
                verts.append(xyz)
            elif tok[0] in ("o", "g"):
                name = " ".join(tok[1:]) or f"block{len(groups) + 1}"
                if groups and not groups[-1][1] and tok[0] == "g":
                    groups[-1] = (name, [])  # 'o name' followed by 'g name': keep one block
                else:
                    groups.append((name, []))
            elif tok[0] == "f":
                if not groups:
                    groups.append(("block1", []))
                idx = []
                for t in tok[1:]:
                    i = int(t.split("/")[0])
                    idx.append(i - 1 if i > 0 else len(verts) + i)
                groups[-1][1].append(idx)
        except ValueError:
            raise _err(path, f"line {lineno}: cannot parse {line.strip()!r}") from None
    V = np.asarray(verts, dtype=float).reshape(-1, 3)
    blocks = []
    for name, faces in groups:
        if not faces:
            continue
        used = sorted({i for f in faces for i in f})
        if used and (used[0] < 0 or used[-1] >= len(V)):
            raise _err(path, f"block {name!r}: a face refers to a vertex that does not exist")
        local = {g: k for k, g in enumerate(used)}
        blocks.append(RawBlock(name, V[used], [[local[i] for i in f] for f in faces]))
    return RawAssembly(blocks)


def _unwrap(obj: Any) -> Any:
    """COMPAS objects are ``{"dtype": ..., "data": {...}}``: return the data."""
    while isinstance(obj, Mapping) and "dtype" in obj and isinstance(obj.get("data"), Mapping):
        obj = obj["data"]
    return obj


def _or(value: Any, default: Any) -> Any:
    """``value``, or ``default`` when it is null (COMPAS writes null for an unset attribute)."""
    return default if value is None else value


def _node_order(nodes: Mapping) -> list:
    """Node keys in order: whole numbers first, by value, then the others as text."""
    return sorted(nodes, key=lambda k: (0, int(k)) if str(k).lstrip("-").isdigit() else (1, str(k)))


def read_compas_json(path: str | Path, data: Any = None) -> RawAssembly:
    """Parse a COMPAS assembly JSON file (compas_assembly, compas_cra) or a compas_dem
    ``BlockModel`` (module docstring), checking every value's type."""
    path = Path(path)
    raw = _load_json(path, _read_text(path)) if data is None else data
    doc = _Doc(path)
    d = _unwrap(raw)
    graph = _unwrap(d.get("graph", d)) if isinstance(d, Mapping) else None
    nodes = graph.get("node", graph.get("nodes")) if isinstance(graph, Mapping) else None
    if not isinstance(nodes, Mapping):
        raise _err(
            path,
            f"not a block file tce reads: got {_kind(raw)}; expected a tce assembly (an object with a "
            '"blocks" list), a COMPAS assembly (data.graph.data.node) or a compas_dem BlockModel',
        )
    elements = d.get("elements") if isinstance(d.get("elements"), Mapping) else None  # a compas_dem BlockModel
    defaults = graph.get("default_node_attributes") or {}
    default_support = doc.flag("graph.default_node_attributes.is_support", _or(defaults.get("is_support"), False))
    blocks = []
    for key in _node_order(nodes):
        where = f"graph.node.{key}"
        node = doc.obj(where, _or(nodes[key], {}))
        support = node.get("is_support", default_support)
        if elements is not None and "element" in node:
            guid = node["element"]
            if not isinstance(guid, str) or guid not in elements:
                raise doc.fail(f"{where}.element", f"no element {doc._got(guid)} in data.elements")
            where = f"elements.{guid}"
            element = doc.obj(where, _unwrap(elements[guid]))
            support = element.get("is_support", support)
            mesh = _unwrap(element.get("geometry"))
            transform = _unwrap(element.get("transformation"))
        else:
            mesh, transform = _unwrap(node.get("block", node)), None
        if not isinstance(mesh, Mapping) or "vertex" not in mesh or "face" not in mesh:
            raise _err(path, f"block {key!r} ({where}): no block mesh with 'vertex' and 'face'")
        vertex = doc.obj(f"{where}.vertex", mesh["vertex"])
        vid = {str(k): n for n, k in enumerate(vertex)}
        v = np.array([doc.point(f"{where}.vertex.{k}", vertex[k]) for k in vertex], dtype=float).reshape(-1, 3)
        if transform is not None:
            v = _transformed(doc, f"{where}.transformation", transform, v)
        faces_d = mesh["face"]
        if isinstance(faces_d, Mapping):
            fitems = [(f"{where}.face.{k}", faces_d[k]) for k in _node_order(faces_d)]
        else:
            fitems = [(f"{where}.face[{k}]", f) for k, f in enumerate(doc.array(f"{where}.face", faces_d))]
        faces = []
        for fkey, loop in fitems:
            loop = doc.array(fkey, loop)
            if len(loop) < 3:
                raise doc.fail(fkey, f"a face needs at least 3 vertices, got {doc._got(loop)}")
            for i in loop:
                if isinstance(i, bool) or not isinstance(i, (int, str)) or str(i) not in vid:
                    raise doc.fail(fkey, f"refers to vertex {doc._got(i)} that does not exist")
            faces.append([vid[str(i)] for i in loop])
        blocks.append(RawBlock(str(key), v, faces, doc.flag(f"{where}.is_support", support)))
    return RawAssembly(blocks, _compas_interfaces(doc, graph, [b.name for b in blocks]) or None)


def _transformed(doc: _Doc, key: str, transform: Any, v: np.ndarray) -> np.ndarray:
    """``v`` moved by a COMPAS ``Transformation`` (``{"matrix": 4 x 4 rows}``)."""
    rows = doc.array(f"{key}.matrix", doc.obj(key, transform).get("matrix"))
    if len(rows) != 4:
        raise doc.fail(f"{key}.matrix", "must be 4 rows of 4 numbers")
    m = np.array([[doc.number(f"{key}.matrix[{i}][{j}]", x) for j, x in enumerate(doc.array(f"{key}.matrix[{i}]", r))]
                  for i, r in enumerate(rows)], dtype=object)
    if m.shape != (4, 4):
        raise doc.fail(f"{key}.matrix", "must be 4 rows of 4 numbers")
    m = m.astype(float)
    if not np.allclose(m[3], [0.0, 0.0, 0.0, 1.0]):
        raise doc.fail(f"{key}.matrix", "a projective transformation (its last row is not [0, 0, 0, 1])")
    return v @ m[:3, :3].T + m[:3, 3]


def _compas_frame_normal(doc: _Doc, key: str, frame: Any) -> np.ndarray | None:
    """z axis (``xaxis x yaxis``) of a COMPAS frame ``{point, xaxis, yaxis}`` or ``[point, xaxis, yaxis]``."""
    frame = _unwrap(frame)
    if frame is None:
        return None
    if isinstance(frame, Mapping):
        if frame.get("xaxis") is None or frame.get("yaxis") is None:
            return None
        axes = frame["xaxis"], frame["yaxis"]
    elif isinstance(frame, list) and len(frame) == 3:
        axes = frame[1], frame[2]
    else:
        raise doc.fail(key, f"must be a frame {{point, xaxis, yaxis}}, got {doc._got(frame)}")
    return np.cross(doc.point(f"{key}.xaxis", axes[0]), doc.point(f"{key}.yaxis", axes[1]))


def _compas_interfaces(doc: _Doc, graph: Mapping, order: list[str]) -> list[dict]:
    """Interfaces stored on the graph's edges, as tce interface items (see :func:`_file_interfaces`).

    An edge ``u -> v`` holds a list ``"interfaces"`` (compas_cra), one ``"interface"``
    (compas_assembly) or a list ``"contacts"`` (compas_dem); each is ``{"points": [...],
    "frame": {...}}`` (points as ``[x, y, z]`` or COMPAS 2 ``Point`` objects), its frame's
    z axis from u into v. Items are given with ``a`` the block of lower index (points and
    normal reversed when needed) and a ``label`` for messages.
    """
    edges = graph.get("edge", graph.get("edges"))
    if edges is None:
        return []
    position = {name: k for k, name in enumerate(order)}
    out = []
    for u, row in doc.obj("graph.edge", edges).items():
        for v, attr in doc.obj(f"graph.edge.{u}", _or(row, {})).items():
            attr = doc.obj(f"graph.edge.{u}.{v}", _or(attr, {}))
            stored = attr.get("interfaces")
            if stored is None:
                stored = attr.get("contacts")
            if stored is None and attr.get("interface") is not None:
                stored = [attr["interface"]]
            for k, item in enumerate(doc.array(f"graph.edge.{u}.{v}.interfaces", _or(stored, []))):
                item = _unwrap(item)
                label = f"interface {k} of edge {u}-{v}"
                if str(u) not in position or str(v) not in position:
                    raise _err(doc.path, f"{label}: the edge joins a block that does not exist")
                if not isinstance(item, Mapping) or "points" not in item:
                    raise _err(doc.path, f"{label}: no 'points' polygon")
                pts = doc.points(f"{label}: points", item["points"])
                normal = _compas_frame_normal(doc, f"{label}: frame", item.get("frame"))
                a, b = str(u), str(v)
                if position[a] > position[b]:
                    a, b, pts = b, a, pts[::-1]
                    normal = None if normal is None else -normal
                out.append(dict(a=a, b=b, points=pts.tolist(), normal=None if normal is None else normal.tolist(), label=label))
    return out


# ---------------------------------------------------------------------- checks
def _triangulate_nonplanar(v: np.ndarray, faces: list[list[int]], tol: float, size: float) -> tuple[list[list[int]], int]:
    """Split every face whose vertices lie farther than ``tol * size`` from its mean plane into
    a fan of triangles from its lexicographically smallest vertex (so that two blocks that
    share such a face split it the same way). Returns the faces and the number split."""
    out, split = [], 0
    for f in faces:
        p = v[f]
        n = newell_normal(p)
        nn = np.linalg.norm(n)
        if len(f) > 3 and nn > 0 and np.abs((p - p.mean(axis=0)) @ (n / nn)).max() > tol * size:
            r = min(range(len(f)), key=lambda k: tuple(np.round(p[k], 12)))
            g = f[r:] + f[:r]
            out.extend([g[0], g[k], g[k + 1]] for k in range(1, len(g) - 1))
            split += 1
        else:
            out.append(list(f))
    return out, split


class _Surface:
    """The faces of a block, for distances from points to its surface."""

    def __init__(self, shape: Polyhedron) -> None:
        self.shape = shape
        self.loops = [shape.vertices[list(f)] for f in shape.faces]
        self.lo = np.array([q.min(axis=0) for q in self.loops])
        self.hi = np.array([q.max(axis=0) for q in self.loops])
        self._planar: dict[int, tuple[np.ndarray, np.ndarray, Polygon]] = {}

    def _face(self, k: int) -> tuple[np.ndarray, np.ndarray, Polygon]:
        """Frame rows (n, t1, t2), centre and 2D polygon (in the frame) of face ``k``."""
        if k not in self._planar:
            frame = frame_from_normal(self.shape.face_normals[k])
            centre = self.loops[k].mean(axis=0)
            self._planar[k] = frame, centre, Polygon((self.loops[k] - centre) @ frame[1:].T)
        return self._planar[k]

    def distance(self, pts: np.ndarray, cutoff: float) -> tuple[np.ndarray, np.ndarray]:
        """Distance (m) from each point to the surface (inf beyond ``cutoff`` of every face),
        and the outward normal of the nearest face (NaN when none is within ``cutoff``)."""
        inside = (pts[:, None, :] >= self.lo[None] - cutoff) & (pts[:, None, :] <= self.hi[None] + cutoff)
        p, f = np.nonzero(np.all(inside, axis=2))
        dist = np.full(len(pts), np.inf)
        normal = np.full((len(pts), 3), np.nan)
        if not len(p):
            return dist, normal
        data = [self._face(int(k)) for k in f]
        axes = np.array([d[0] for d in data])  # (pairs, 3, 3) rows n, t1, t2
        off = pts[p] - np.array([d[1] for d in data])
        uv = np.einsum("kj,kij->ki", off, axes[:, 1:])
        inplane = shapely.distance(shapely.points(uv), [d[2] for d in data])
        d = np.hypot(np.einsum("kj,kj->k", off, axes[:, 0]), inplane)
        order = np.lexsort((d, p))  # per point, the nearest face first
        first = order[np.r_[True, p[order][1:] != p[order][:-1]]]
        dist[p[first]] = d[first]
        normal[p[first]] = axes[first, 0]
        return dist, normal


def _file_interfaces(
    path: Path, items: list[dict], blocks: list[Block], scale: float, planar_tol: float, interface_tol: float
) -> list[Interface]:
    """The interfaces stored in a file, checked against the blocks (module docstring)."""
    index = {b.name: k for k, b in enumerate(blocks)}
    surfaces: dict[int, _Surface] = {}
    out = []
    for k, it in enumerate(items):
        label = it.get("label", f"interface {k}")
        # the readers checked the types: points are finite [x, y, z], a normal 3 finite numbers
        try:
            a, b = index[it["a"]], index[it["b"]]
        except KeyError as exc:
            raise _err(path, f"{label}: unknown block {exc}") from None
        if a > b:
            raise _err(path, f"{label}: 'a' must be the block listed first (normal from a into b)")
        name = f"{label} ({blocks[a].name}|{blocks[b].name})"
        pts, n = np.asarray(it["points"], dtype=float).reshape(-1, 3) * scale, it.get("normal")
        if len(pts) < 3:
            raise _err(path, f"{name}: needs at least 3 finite points [x, y, z]")
        size = max(blocks[a].shape.size, blocks[b].shape.size)
        nv = newell_normal(pts)
        if np.linalg.norm(nv) <= (1e-9 * size) ** 2:
            raise _err(path, f"{name}: the polygon has no area")
        nv = nv / np.linalg.norm(nv)
        off = np.abs((pts - pts.mean(axis=0)) @ nv).max()
        if off > planar_tol * size:
            raise _err(path, f"{name}: not planar (a point lies {off:.3g} m off its plane)")
        if n is not None:
            n = np.asarray(n, dtype=float)
            if not np.all(np.isfinite(n)) or np.linalg.norm(n) == 0.0:  # a COMPAS frame's xaxis x yaxis
                raise _err(path, f"{name}: its normal (frame z axis) must be 3 finite numbers, not all 0")
            n = n / np.linalg.norm(n)
            tilt = np.linalg.norm(np.cross(n, nv))
            if tilt * float(np.ptp(pts, axis=0).max()) > planar_tol * size:
                raise _err(path, f"{name}: its polygon does not lie in the plane of its frame (normal off by {np.degrees(np.arcsin(min(tilt, 1.0))):.3g} deg)")
        far = interface_tol * size
        facing = []
        for i in (a, b):
            blk = blocks[i]
            if i not in surfaces:
                surfaces[i] = _Surface(blk.shape)
            surface = surfaces[i]
            dist, fn = surface.distance(np.vstack([pts, pts.mean(axis=0)]), far)
            if dist.max() > far:
                worst = "more than" if not np.isfinite(dist.max()) else f"{dist.max():.3g} m,"
                raise _err(
                    path,
                    f"{name}: does not lie on block {blk.name!r} (a point is {worst} {far:.3g} m off its faces; "
                    f"interface_tol = {interface_tol:g} of the block size): check the interface's blocks",
                )
            facing.append(float(fn[-1] @ nv))
        # the faces it lies on: A's faces out along +n, B's along -n
        if facing[0] > 0 > facing[1]:
            n_ab = nv
        elif facing[0] < 0 < facing[1]:
            n_ab = -nv
        else:
            raise _err(path, f"{name}: it does not separate its two blocks (their faces there do not face each other)")
        if n is not None:
            if n @ n_ab < 0:
                log.info("%s: %s: the stored normal points from B into A; oriented from A into B", path, name)
            n_ab = n if n @ n_ab > 0 else -n
        out.append(Interface(a, b, pts, n_ab, stiffness=it.get("stiffness", 1.0), kind=it.get("kind", "")))
    return out


def load_assembly(
    path: str | Path,
    supports: Iterable[str | int] | None = None,
    unit_weight: float | Mapping[str, float] | None = None,
    tol: float = 1e-6,
    min_area: float | None = None,
    angle_tol: float | None = None,
    nonplanar: Literal["error", "triangulate"] | None = None,
    check_overlap: bool = True,
    detect: bool | None = None,
    interface_tol: float = INTERFACE_TOL,
) -> Assembly:
    """Read, check and assemble a block assembly file (see module docstring).

    Parameters
    ----------
    path : str or Path
        A ``.json`` (tce or COMPAS, told apart by content) or ``.obj`` file.
    supports : iterable of str or int, optional
        Names (or COMPAS node keys) of the support blocks; replaces the file's flags.
    unit_weight : float or mapping, optional
        Unit weight (kN/m^3): one value for every block, or ``{name: value}`` for some
        blocks. Priority: this mapping, a block's own value in the file, this float, the
        file's default, then 20 kN/m^3.
    tol : float
        Relative geometric tolerance of the contact and overlap checks, see
        :func:`tce.structures.contacts.detect_interfaces`. Faces must be planar within
        ``min(tol, 1e-6)`` times the block size (what :meth:`Assembly.validate` requires).
    min_area, angle_tol : float, optional
        Passed to :func:`tce.structures.contacts.detect_interfaces`.
    nonplanar : {"error", "triangulate"}, optional
        What to do with a face that is not planar: report it, or split it into triangles
        (for curved surfaces given as quad meshes). Default: ``"triangulate"`` for COMPAS
        files, ``"error"`` otherwise. *Detecting* the contacts of two curved surfaces meshed
        differently needs a looser ``tol`` and ``angle_tol`` (and ``check_overlap=False`` if
        the facets interpenetrate); stored interfaces need neither.
    check_overlap : bool
        Run :func:`tce.structures.contacts.check_overlaps` (at ``max(tol, interface_tol)`` when the
        file's interfaces are used).
    detect : bool, optional
        Detect the interfaces from the geometry; by default only when the file stores none
        (tce JSON and COMPAS files may store them).
    interface_tol : float
        How far (relative to the larger block size) the points of a stored interface may lie
        from each of its blocks' faces (module docstring).

    Returns
    -------
    Assembly
        Validated; ``meta`` records the source file, its format and the tolerances.

    Raises
    ------
    AssemblyError or GeometryError
        Naming the file, and the block when one is at fault.
    FileNotFoundError
        When the file does not exist.
    """
    path = Path(path)
    if nonplanar not in (None, "error", "triangulate"):
        raise ValueError(f"nonplanar must be 'error' or 'triangulate', got {nonplanar!r}")
    for key, value in (("tol", tol), ("interface_tol", interface_tol)):
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"{key} must be a finite number > 0, got {value!r}")
    ext = path.suffix.lower()
    if ext == ".obj":
        raw, fmt = read_obj(path), "obj"
    elif ext == ".json":
        data = _load_json(path, _read_text(path))
        if isinstance(data, Mapping) and "blocks" in data:
            raw, fmt = read_tce_json(path, data), "tce-json"
        else:
            raw, fmt = read_compas_json(path, data), "compas-json"
    else:
        raise _err(path, f"unknown file type {ext!r}: expected .json or .obj")
    if not raw.blocks:
        raise _err(path, "the file holds no blocks")
    if nonplanar is None:
        nonplanar = "triangulate" if fmt == "compas-json" else "error"
    _check_counts(path, raw.blocks)

    names = [b.name for b in raw.blocks]
    if len(set(names)) != len(names):
        dup = sorted({n for n in names if names.count(n) > 1})
        raise _err(path, f"duplicate block names {dup}")
    uw_map = dict(unit_weight) if isinstance(unit_weight, Mapping) else {}
    unknown = [n for n in uw_map if str(n) not in names]
    if unknown:
        raise _err(path, f"unit_weight given for unknown block(s) {unknown}{did_you_mean(unknown[0], names)}")
    uw_map = {str(k): float(v) for k, v in uw_map.items()}
    uw_all = None if isinstance(unit_weight, Mapping) or unit_weight is None else float(unit_weight)

    support_set = None if supports is None else {str(s) for s in supports}
    if support_set is not None:
        missing = sorted(support_set - set(names))
        if missing:
            raise _err(
                path,
                f"support block(s) {missing} not found{did_you_mean(missing[0], names)}; blocks are {names[:20]}"
                + (f" and {len(names) - 20} more" if len(names) > 20 else ""),
            )

    # units: the file's lengths and unit weights are converted to m and kN/m^3 here
    ls, fs = raw.length, raw.force
    blocks, split_total = [], 0
    for rb in raw.blocks:
        label = f"{path.name}: block {rb.name!r}"
        v = rb.vertices * ls
        faces = rb.faces
        try:
            if nonplanar == "triangulate":
                size = float(np.linalg.norm(np.ptp(v, axis=0))) if len(v) else 0.0
                faces, n_split = _triangulate_nonplanar(v, faces, min(tol, PLANAR_TOL), size)
                split_total += n_split
            shape = Polyhedron(v, faces)
            shape.validate(name=label, tol=min(tol, PLANAR_TOL))
        except GeometryError as exc:
            msg = str(exc)
            raise GeometryError(msg if msg.startswith(label) else f"{label}: {msg}") from None
        if rb.name in uw_map:
            uw = uw_map[rb.name]
        elif rb.unit_weight is not None:
            uw = rb.unit_weight * fs / ls**3
        elif uw_all is not None:
            uw = uw_all
        elif raw.unit_weight is not None:
            uw = raw.unit_weight * fs / ls**3
        else:
            uw = DEFAULT_UNIT_WEIGHT
        is_support = rb.name in support_set if support_set is not None else rb.support
        blocks.append(Block(rb.name, shape, uw, is_support))
    if split_total:
        log.info("%s: split %d non-planar faces into triangles", path, split_total)

    if detect is None:
        detect = not raw.interfaces
    if check_overlap:
        try:
            check_overlaps(blocks, tol if detect else max(tol, interface_tol))
        except AssemblyError as exc:
            raise _err(path, str(exc)) from None
    if detect:
        interfaces = detect_interfaces(blocks, tol=tol, min_area=min_area, angle_tol=angle_tol)
    else:
        interfaces = _file_interfaces(path, raw.interfaces or [], blocks, ls, min(tol, PLANAR_TOL), interface_tol)
    meta = dict(raw.meta, source=str(path), format=fmt, tol=tol, nonplanar=nonplanar)
    meta["interfaces"] = "detected" if detect else "from file"
    if not detect:
        meta["interface_tol"] = interface_tol
    if split_total:
        meta["faces_triangulated"] = split_total
    asm = Assembly(tuple(blocks), tuple(interfaces), meta)
    try:
        asm.validate()
    except AssemblyError as exc:
        raise _err(path, str(exc)) from None
    except GeometryError as exc:
        raise GeometryError(f"{path}: {exc}") from None
    return asm


# ---------------------------------------------------------------------- writer
def save_assembly_json(assembly: Assembly, path: str | Path, interfaces: bool = True) -> Path:
    """Write ``assembly`` in the tce JSON format (m, kN), readable by :func:`load_assembly`:
    :meth:`Assembly.to_dict` with the most common unit weight as the file's default.

    Parameters
    ----------
    path : str or Path
        Output file (``.json``), written whole (:func:`tce.files.atomic_write`); parent
        directories are created.
    interfaces : bool
        Store the interfaces too, with their stiffness multipliers (then
        :func:`load_assembly` uses them instead of detecting them again).

    Returns
    -------
    Path
        The path written.
    """
    path = Path(path)
    data = assembly.to_dict()
    uws = [b["unit_weight"] for b in data["blocks"]]
    default = max(set(uws), key=uws.count) if uws else DEFAULT_UNIT_WEIGHT
    blocks = [{k: v for k, v in b.items() if k != "unit_weight" or v != default} for b in data["blocks"]]
    doc: dict[str, Any] = {
        "format": "tce-assembly",
        "version": 1,
        "units": {"length": "m", "force": "kN"},
        "unit_weight": float(default),
        "blocks": blocks,
        "meta": data["meta"],
    }
    if interfaces:
        doc["interfaces"] = data["interfaces"]
    with atomic_write(path) as tmp:
        # numpy values of the meta as numbers and lists, anything else JSON lacks as text
        text = json.dumps(doc, indent=1, default=lambda v: v.tolist() if isinstance(v, (np.ndarray, np.generic)) else str(v))
        tmp.write_text(text, encoding="utf-8")
    return path
