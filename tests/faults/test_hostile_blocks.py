"""Hostile block files, by generator: every value of a valid tce file (and of a COMPAS 2 file
written by compas_cra) is replaced in turn by each of a list of hostile values. A value of the
wrong type must be refused with an error naming the file and the key; a value of the right
type may load or be refused, but only with tce's own errors naming the file. A hypothesis
property draws arbitrary JSON at every place. The issue's examples also go through
``tce run``: exit 2, one line naming the key, nothing written."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tce.structures.assembly import AssemblyError
from tce.structures.geometry import GeometryError
from tce.structures.io import load_assembly
from tce.cli import main

from .common import clean, errors, replaced, write
from .test_hostile_input import FILE_STUDY, cube

DATA = Path(__file__).resolve().parents[1] / "data" / "compas2"

#: values that stand in for any value of a file
HOSTILE: list[Any] = [
    "no", "false", "", "1", "heavy", "a\x00b", 1.5, True, False, None, {"a": 1}, [], [1, 2, 3],
    -1, 0, 5, math.nan, math.inf,
]


def _number(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


#: what a value must be at each kind of place
RIGHT = {
    "number": _number,
    "positive": lambda v: _number(v) and v > 0,
    "flag": lambda v: isinstance(v, bool),
    "text": lambda v: isinstance(v, str) and v != "" and "\x00" not in v,
    "index": lambda v: isinstance(v, int) and not isinstance(v, bool) and 0 <= v < 8,
    "object": lambda v: isinstance(v, dict),
    "list": lambda v: isinstance(v, list),
    "point": lambda v: isinstance(v, list) and len(v) == 3 and all(_number(c) for c in v),
    "optional point": lambda v: v is None or RIGHT["point"](v),
    "vertex": lambda v: (isinstance(v, int) and not isinstance(v, bool) or isinstance(v, str)) and str(v) in [str(i) for i in range(8)],
    "length": lambda v: v in ("m", "cm", "mm"),
    "force": lambda v: v in ("kN", "N"),
    "version": lambda v: v == 1 and not isinstance(v, bool),
    "format": lambda v: v == "tce-assembly",
}


def valid_doc() -> dict:
    base, top = cube("base", -1.0, True), cube("top", 0.0)
    top["unit_weight"] = 22.0
    return {
        "format": "tce-assembly", "version": 1, "units": {"length": "m", "force": "kN"}, "unit_weight": 20.0,
        "blocks": [base, top],
        "interfaces": [{"a": "base", "b": "top", "points": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]],
                        "normal": [0, 0, 1], "stiffness": 1.0}],
        "meta": {"by": "test"},
    }


#: (place in the document, kind of value there, the key an error must name)
SLOTS = [
    (("unit_weight",), "positive", "unit_weight"),
    (("units",), "object", "units"),
    (("units", "length"), "length", "units.length"),
    (("units", "force"), "force", "units.force"),
    (("version",), "version", "version"),
    (("format",), "format", "format"),
    (("meta",), "object", "meta"),
    (("blocks",), "list", "blocks"),
    (("blocks", 1), "object", "blocks[1]"),
    (("blocks", 1, "name"), "text", "blocks[1].name"),
    (("blocks", 1, "support"), "flag", "blocks[1] (top).support"),
    (("blocks", 1, "unit_weight"), "positive", "blocks[1] (top).unit_weight"),
    (("blocks", 1, "vertices"), "list", "blocks[1] (top).vertices"),
    (("blocks", 1, "vertices", 2), "point", "blocks[1] (top).vertices[2]"),
    (("blocks", 1, "vertices", 2, 0), "number", "blocks[1] (top).vertices[2][0]"),
    (("blocks", 1, "faces"), "list", "blocks[1] (top).faces"),
    (("blocks", 1, "faces", 0), "list", "blocks[1] (top).faces[0]"),
    (("blocks", 1, "faces", 0, 1), "index", "blocks[1] (top).faces[0][1]"),
    (("interfaces",), "list", "interfaces"),
    (("interfaces", 0), "object", "interfaces[0]"),
    (("interfaces", 0, "a"), "text", "interfaces[0].a"),
    (("interfaces", 0, "points"), "list", "interfaces[0].points"),
    (("interfaces", 0, "points", 1), "point", "interfaces[0].points[1]"),
    (("interfaces", 0, "points", 1, 2), "number", "interfaces[0].points[1][2]"),
    (("interfaces", 0, "normal"), "optional point", "interfaces[0].normal"),
    (("interfaces", 0, "stiffness"), "positive", "interfaces[0].stiffness"),
]


def outcome(path: Path) -> Exception | None:
    """None if ``path`` loads; the error otherwise (only tce's own errors may come out)."""
    try:
        load_assembly(path)
    except (AssemblyError, GeometryError) as exc:
        assert str(path) in str(exc) or path.name in str(exc), exc
        return exc
    return None


def test_the_valid_documents_load(tmp_path: Path) -> None:
    (tmp_path / "a.json").write_text(json.dumps(valid_doc()))
    asm = load_assembly(tmp_path / "a.json")
    assert asm.names == ("base", "top") and asm.meta["interfaces"] == "from file"
    assert load_assembly(DATA / "cra_cubes_contacts.json").meta["interfaces"] == "from file"


@pytest.mark.parametrize("place, kind, key", SLOTS, ids=[s[2] for s in SLOTS])
def test_every_value_of_a_tce_file(place: tuple, kind: str, key: str, tmp_path: Path) -> None:
    """The generator: every place x every hostile value."""
    wrong = 0
    for k, value in enumerate(HOSTILE):
        path = tmp_path / f"h{k}.json"
        path.write_text(json.dumps(replaced(valid_doc(), place, value)))
        exc = outcome(path)
        if not RIGHT[kind](value):
            wrong += 1
            assert exc is not None, (key, value)
            assert f": {key}" in str(exc) or f": {key}." in str(exc), (key, value, str(exc))
    assert wrong >= len(HOSTILE) - 4  # the list exercises mostly wrong values at every place


def _compas_slots() -> list[tuple[tuple, str, str]]:
    """Places in compas_cra's file: a node's flag, a vertex coordinate, a face's vertex, an
    interface point (a serialised Point) and its coordinate, a frame axis."""
    edge = ("data", "graph", "data", "edge", "1", "0", "interfaces", 0, "data")
    node = ("data", "graph", "data", "node", "1")
    mesh = (*node, "block", "data")
    return [
        ((*node, "is_support"), "flag", "graph.node.1.is_support"),
        ((*mesh, "vertex", "0", "x"), "number", "graph.node.1.vertex.0.x"),
        ((*mesh, "face", "0", 1), "vertex", "graph.node.1.face.0"),
        ((*edge, "points", 0), "point", "interface 0 of edge 1-0: points[0]"),
        ((*edge, "points", 0, "data", 2), "number", "interface 0 of edge 1-0: points[0][2]"),
        ((*edge, "frame", "data", "xaxis"), "optional point", "interface 0 of edge 1-0: frame.xaxis"),
    ]


@pytest.mark.parametrize("place, kind, key", _compas_slots(), ids=[s[2] for s in _compas_slots()])
def test_every_value_of_a_compas_file(place: tuple, kind: str, key: str, tmp_path: Path) -> None:
    doc = json.loads((DATA / "cra_cubes_contacts.json").read_text())
    right = RIGHT[kind]
    for k, value in enumerate(HOSTILE):
        path = tmp_path / f"h{k}.json"
        path.write_text(json.dumps(replaced(doc, place, value)))
        exc = outcome(path)
        if not right(value):
            assert exc is not None and f": {key}" in str(exc), (key, value, exc)


JSON = st.recursive(
    st.none() | st.booleans() | st.integers(-10, 10) | st.floats(allow_nan=True) | st.text(max_size=5),
    lambda inner: st.lists(inner, max_size=3) | st.dictionaries(st.text(max_size=4), inner, max_size=3),
    max_leaves=8,
)


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(slot=st.sampled_from(SLOTS), value=JSON)
def test_any_json_anywhere_gives_a_named_error_or_a_model(slot, value, tmp_path: Path) -> None:
    path = tmp_path / "any.json"
    path.write_text(json.dumps(replaced(valid_doc(), slot[0], value)))
    outcome(path)  # loads, or a tce error naming the file; never another exception


#: the issue's examples: (change to the top block, words of the one error line)
EXAMPLES = {
    "support 'no'": (("blocks", 1, "support"), "no", ["blocks[1] (top).support", "true or false"]),
    "support 'false'": (("blocks", 1, "support"), "false", ["blocks[1] (top).support"]),
    "face index 1.5": (("blocks", 1, "faces", 0, 1), 1.5, ["faces[0][1]", "whole number"]),
    "face index true": (("blocks", 1, "faces", 0, 1), True, ["faces[0][1]"]),
    "string coordinate": (("blocks", 1, "vertices", 0, 0), "0", ["vertices[0][0]", "number"]),
    "name 5": (("blocks", 1, "name"), 5, ["blocks[1].name", "string"]),
    "name an object": (("blocks", 1, "name"), {"a": 1}, ["blocks[1].name"]),
    "interfaces an object": (("interfaces",), {"a": 1}, ["interfaces", "list"]),
    "unit_weight 'heavy'": (("blocks", 1, "unit_weight"), "heavy", ["unit_weight", "number"]),
}


@pytest.mark.parametrize("case", sorted(EXAMPLES))
def test_the_issues_examples_through_tce_run(case: str, tmp_path: Path, capsys) -> None:
    place, value, words = EXAMPLES[case]
    (tmp_path / "blocks.json").write_text(json.dumps(replaced(valid_doc(), place, value)))
    study = write(tmp_path, FILE_STUDY.format(path="blocks.json", supports=""))
    assert main(["run", str(study), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    clean(err)
    (line,) = errors(err)
    for word in words + ["blocks.json"]:
        assert word in line, line
    assert not (tmp_path / "out").exists()


def test_a_plain_json_list_is_named(tmp_path: Path, capsys) -> None:
    (tmp_path / "blocks.json").write_text("[1, 2]")
    study = write(tmp_path, FILE_STUDY.format(path="blocks.json", supports=""))
    assert main(["run", str(study), "--out", str(tmp_path / "out")]) == 2
    (line,) = errors(capsys.readouterr().err)
    assert "got a JSON list" in line and "tce assembly" in line and "COMPAS" in line


def test_the_block_cap_refuses_before_building() -> None:
    """check_blocks itself (issue 25): one block past MAX_BLOCKS is refused naming how the count
    follows from the parameters, the cap passes. Without it the generator tests of
    test_hostile_studies.py do not fail: they build ten million blocks and run out of memory."""
    from tce.structures.params import MAX_BLOCKS, check_blocks

    check_blocks(MAX_BLOCKS, "voussoirs + 2")
    with pytest.raises(ValueError, match=rf"voussoirs \+ 2 = {MAX_BLOCKS + 1} blocks, more than MAX_BLOCKS"):
        check_blocks(MAX_BLOCKS + 1, "voussoirs + 2")
