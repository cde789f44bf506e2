"""Hostile and careless input: each gets exit code 2, one message naming the key (or the
file) and the fix, no traceback, and nothing written."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest
import xarray as xr

from tce.study import runner
from tce.cli import main
from tce.study.schema import parse_study
from tce.structures import io

from .common import TINY, answer, clean, errors, write

#: case -> (text replaced, replacement, words the message must hold)
BAD = {
    "name ..": ('name = "tiny"', 'name = ".."', ["study.name", "fix:"]),
    "name .": ('name = "tiny"', 'name = "."', ["study.name"]),
    "name with a separator": ('name = "tiny"', 'name = "a/b"', ["study.name"]),
    "name with a backslash": ('name = "tiny"', 'name = "a\\\\b"', ["study.name"]),
    "reserved name": ('name = "tiny"', 'name = "CON"', ["study.name", "reserved"]),
    "reserved name with an extension": ('name = "tiny"', 'name = "nul.txt"', ["study.name", "reserved"]),
    "name ending with a dot": ('name = "tiny"', 'name = "tiny."', ["study.name"]),
    "300-character name": ('name = "tiny"', f'name = "{"a" * 300}"', ["study.name", "at most 100"]),
    "boolean friction": ("[sweep]", "[material]\nfriction = true\n\n[sweep]", ["material.friction", "write a number"]),
    "boolean motion": ("right = [0.001,", "right = [true,", ["scenarios.outward.right[0]", "write a number"]),
    "quoted number": ("tolerance = 1e-3", 'tolerance = "1e-3"', ["loads.tolerance", "write a number"]),
    "float voussoirs": ("voussoirs = 6", "voussoirs = 6.0", ["structure.voussoirs", "whole number"]),
    "no scenarios": ("[scenarios.none]\n\n[scenarios.outward]\nright = [0.001, 0.0, 0.0, 0.0, 0.0, 0.0]", "scenarios = {}", ["scenarios"]),
    "repeated sweep value": ("friction = [0.8, 2.0]", "friction = [0.8, 0.8]", ["sweep", "listed twice"]),
    "repeated direction": ("[loads]", "[loads]\nalpha = [0, 0]", ["loads.alpha", "listed twice"]),
    "1e14 increments": ("lambda_step = 0.05", "lambda_step = 1e-12", ["loads", "MAX_INCREMENTS", "larger lambda_step"]),
    "100 million voussoirs": ("voussoirs = 6", "voussoirs = 100000000", ["structure.voussoirs", "<= 50000"]),
    "misspelt key": ("[loads]", "[material]\nfricton = 0.5\n\n[loads]", ["material.fricton", "did you mean 'friction'"]),
    "misspelt support": ("right = [", "rigth = [", ["scenarios.outward.rigth", "did you mean 'right'"]),
    "misspelt structure type": ('type = "semicircular_arch"', 'type = "semicircular_ach"', ["did you mean 'semicircular_arch'"]),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_study(case: str, tmp_path: Path, capsys) -> None:
    old, new, words = BAD[case]
    assert old in TINY
    out = tmp_path / "out" / "inner"
    assert main(["run", str(write(tmp_path, TINY.replace(old, new, 1))), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    clean(err)
    (line,) = errors(err)
    for word in words:
        assert word in line
    assert not (tmp_path / "out").exists() and sorted(p.name for p in tmp_path.iterdir()) == ["study.toml"]


FILE_STUDY = """
[study]
name = "blocks"

[structure]
type = "file"
path = "{path}"
{supports}
"""


def cube(name: str, z: float, support: bool = False) -> dict:
    v = [[x, y, z + h] for h in (0.0, 1.0) for x, y in ((0, 0), (1, 0), (1, 1), (0, 1))]
    faces = [[3, 2, 1, 0], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]]
    return {"name": name, "vertices": v, "faces": faces, "support": support}


def file_study(tmp_path: Path, content: str | None, supports: str = "", name: str = "blocks.json") -> Path:
    if content is not None:
        (tmp_path / name).write_text(content)
    return write(tmp_path, FILE_STUDY.format(path=name, supports=supports))


def deep(n: int) -> str:
    return '{"blocks": ' + "[" * n + "]" * n + "}"


def many_vertices(n: int) -> str:
    block = cube("b", 0.0)
    block["vertices"] += [[0.5, 0.5, 0.5]] * (n - 8)
    return json.dumps({"blocks": [cube("base", -1.0, True), block]})


HOSTILE_FILES = {
    "nested 100,000 deep": (deep(100_000), "", ["MAX_DEPTH", "nested 100001 deep"]),
    "a block with 20,000 vertices": (many_vertices(20_000), "", ["MAX_BLOCK_VERTICES", "'b'"]),
    "blocks that are numbers": ('{"blocks": [1, 2]}', "", ["blocks[0]", "must be an object"]),
    "not JSON": ('{"blocks": [', "", ["not valid JSON"]),
    "no supports": (json.dumps({"blocks": [cube("a", 0.0), cube("b", 1.0)]}), "", ["supports = [...]"]),
    "misspelt support block": (
        json.dumps({"blocks": [cube("base", 0.0), cube("top", 1.0)]}), 'supports = ["bsae"]', ["did you mean 'base'"]
    ),
}


@pytest.mark.parametrize("case", sorted(HOSTILE_FILES))
def test_hostile_block_file(case: str, tmp_path: Path, capsys) -> None:
    content, supports, words = HOSTILE_FILES[case]
    study = file_study(tmp_path, content, supports)
    assert main(["run", str(study), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    clean(err)
    (line,) = errors(err)
    for word in words:
        assert word in line, line
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("target", ["folder", "pipe"])
def test_path_must_be_a_regular_file(target: str, tmp_path: Path, capsys) -> None:
    """A folder, or a pipe that would block the reader forever."""
    if target == "folder":
        (tmp_path / "blocks.json").mkdir()
    else:
        os.mkfifo(tmp_path / "blocks.json")
    study = file_study(tmp_path, None)
    assert main(["run", str(study), "--out", str(tmp_path / "out")]) == 2
    (line,) = errors(capsys.readouterr().err)
    assert "not a regular file" in line and "[structure] path" in line


def test_file_size_cap(tmp_path: Path, monkeypatch, capsys) -> None:
    monkeypatch.setattr(io, "MAX_FILE_BYTES", 100)
    study = file_study(tmp_path, json.dumps({"blocks": [cube("base", 0.0, True), cube("top", 1.0)]}))
    assert main(["run", str(study), "--out", str(tmp_path / "out")]) == 2
    (line,) = errors(capsys.readouterr().err)
    assert "MAX_FILE_BYTES = 100" in line


def test_colliding_sweep_values_are_two_scenarios(tmp_path: Path) -> None:
    """0.8000001 and 0.8000002 were both labelled 0.8: one was never solved."""
    study = parse_study(TINY.replace("friction = [0.8, 2.0]", "friction = [0.8000001, 0.8000002]"), "s.toml")
    names = [sc.name for sc in study.scenarios()]
    assert names[:2] == ["none/friction=0.8000001", "none/friction=0.8000002"]
    report = runner.run_study(study, tmp_path, jobs=1)
    assert len(report.solved) == 4
    ds = xr.load_dataset(report.results)
    assert ds["friction"].values.tolist() == [0.8000001, 0.8000002] * 2


def test_block_file_edited_between_runs(tmp_path: Path) -> None:
    """The resume key follows the file's content, not its path."""
    blocks = [cube("base", -1.0, True), cube("a", 0.0), cube("b", 1.0)]
    (tmp_path / "blocks.json").write_text(json.dumps({"blocks": blocks}))
    text = FILE_STUDY.format(path="blocks.json", supports="") + "\n[material]\nfriction = 0.6\n[loads]\nalpha = [0, 90]\nlambda_step = 0.1\ntolerance = 1e-3\n"
    study = write(tmp_path, text)
    first = runner.run_study(parse_study(study.read_text(), study), tmp_path / "out", jobs=1)
    assert len(first.solved) == 2
    before = answer(first.results)
    blocks[2]["vertices"] = [[x * 0.5, y, z] for x, y, z in blocks[2]["vertices"]]  # a slimmer top block
    (tmp_path / "blocks.json").write_text(json.dumps({"blocks": blocks}))
    second = runner.run_study(parse_study(study.read_text(), study), tmp_path / "out", jobs=1)
    assert len(second.solved) == 2 and not second.reused
    fresh = runner.run_study(parse_study(study.read_text(), study), tmp_path / "fresh", jobs=1)
    xr.testing.assert_identical(answer(second.results), answer(fresh.results))
    assert (before["lambda_max"] != answer(second.results)["lambda_max"]).any()  # the old answer was not reused
