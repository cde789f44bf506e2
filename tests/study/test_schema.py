"""Study files: validation messages and the expansion of sweeps."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from tce.study.schema import StudyError, load_study, parse_study

STUDIES = Path(__file__).resolve().parents[2] / "studies"

BASE = """
[study]
name = "t"

[structure]
type = "semicircular_arch"
inner_radius = 1.0
thickness = 0.2
depth = 0.25
voussoirs = 14

[material]
friction = 0.8

[loads]
alpha = 0.0
lambda_step = 0.02
tolerance = 1e-6

[scenarios.outward]
right = [0.001, 0.0, 0.0, 0.0, 0.0, 0.0]
"""


def study_text(replace: dict[str, str] | None = None, extra: str = "") -> str:
    """BASE with lines replaced (old -> new) and text appended."""
    text = BASE
    for old, new in (replace or {}).items():
        assert old in text
        text = text.replace(old, new)
    return text + extra


def test_base_is_valid() -> None:
    study = parse_study(study_text())
    (sc,) = study.scenarios()
    assert sc.name == "outward" and sc.alpha == 0.0 and sc.material["friction"] == 0.8
    assert sc.settlements == {"right": [0.001, 0.0, 0.0, 0.0, 0.0, 0.0]}


BAD = {
    "unknown key": ({"voussoirs = 14": "voussoirs = 14\ncolour = 3"}, "structure.colour", "remove it"),
    "wrong type": ({"thickness = 0.2": 'thickness = "thick"'}, "structure.thickness", "write a number"),
    "negative thickness": ({"thickness = 0.2": "thickness = -0.2"}, "structure.thickness", "> 0"),
    "friction below 0": ({"friction = 0.8": "friction = -0.1"}, "material.friction", ">= 0"),
    "NaN": ({"depth = 0.25": "depth = nan"}, "structure.depth", "finite"),
    "short displacement": (
        {"right = [0.001, 0.0, 0.0, 0.0, 0.0, 0.0]": "right = [0.001, 0.0]"},
        "scenarios.outward.right",
        "6 numbers",
    ),
    "long displacement": (
        {"right = [0.001, 0.0, 0.0, 0.0, 0.0, 0.0]": "right = [0.001, 0, 0, 0, 0, 0, 0]"},
        "scenarios.outward.right",
        "6 numbers",
    ),
    "unknown support": (
        {"right = [0.001": "middle = [0.001"},
        "scenarios.outward.middle",
        "'left', 'right'",
    ),
    "unknown structure type": (
        {'type = "semicircular_arch"': 'type = "bridge"'},
        "structure",
        "structure types",
    ),
    "missing name": ({'name = "t"': ""}, "study.name", "add it"),
    "bad toml": ({"[material]": "[material"}, "not valid TOML", "syntax"),
    "zero step": ({"lambda_step = 0.02": "lambda_step = 0"}, "loads.lambda_step", "> 0"),
    "empty sweep": ({}, "sweep.friction", "at least one"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_input_names_file_key_and_fix(case: str) -> None:
    replace, key, fix = BAD[case]
    extra = "\n[sweep]\nfriction = []\n" if case == "empty sweep" else ""
    with pytest.raises(StudyError) as info:
        parse_study(study_text(replace, extra), "my_study.toml")
    message = str(info.value)
    assert message.startswith("my_study.toml: ")
    assert key in message and fix in message and "fix" in message


def test_missing_file() -> None:
    with pytest.raises(StudyError, match="cannot read"):
        load_study("no/such/study.toml")


def test_sweep_is_cartesian_product() -> None:
    extra = "\n[sweep]\nfriction = [0.6, 0.8]\nmagnitude = [1.0, 2.0, -1.0]\nthickness = [0.2, 0.25]\n"
    text = study_text({"alpha = 0.0": "alpha = [0.0, 90.0]"}, extra + "\n[scenarios.none]\n")
    scenarios = parse_study(text).scenarios()
    assert len(scenarios) == 2 * 2 * 2 * 3 * 2
    names = [sc.name for sc in scenarios]
    assert len(set(names)) == len(names)
    sc = next(s for s in scenarios if s.name == "outward/alpha=90/friction=0.6/magnitude=-1/thickness=0.25")
    assert sc.alpha == 90.0 and sc.material["friction"] == 0.6 and sc.structure["thickness"] == 0.25
    assert math.isclose(sc.settlements["right"][0], -0.001)
    assert sc.params == {"alpha": 90.0, "friction": 0.6, "magnitude": -1.0, "thickness": 0.25}
    # scenarios sharing structure and material share one analysis
    assert len({s.group for s in scenarios}) == 2 * 2


def test_no_scenarios_means_one_without_settlement() -> None:
    text = study_text().split("[scenarios.outward]")[0]
    (sc,) = parse_study(text).scenarios()
    assert sc.name == "none" and sc.settlements == {}


def test_heyman_when_friction_absent() -> None:
    (sc,) = parse_study(study_text({"friction = 0.8": ""})).scenarios()
    assert sc.material["friction"] is None


@pytest.mark.parametrize("path", sorted(STUDIES.glob("*.toml")), ids=lambda p: p.name)
def test_shipped_studies_are_valid(path: Path) -> None:
    study = load_study(path)
    assert study.name == path.stem and study.scenarios()


def test_file_structure_relative_to_study(tmp_path: Path) -> None:
    import json

    from tce.structures.arch import semicircular_arch
    from tce.study.schema import build_structure

    (tmp_path / "blocks").mkdir()
    (tmp_path / "blocks" / "arch.json").write_text(json.dumps(semicircular_arch(voussoirs=6).to_dict()))
    text = """
[study]
name = "from_file"

[structure]
type = "file"
path = "blocks/arch.json"
supports = ["left", "right"]

[scenarios.down]
right = [0.0, 0.0, -0.001, 0.0, 0.0, 0.0]
"""
    path = tmp_path / "study.toml"
    path.write_text(text)
    (sc,) = load_study(path).scenarios()
    assert sc.structure["path"] == str((tmp_path / "blocks" / "arch.json").resolve())
    assert build_structure(sc.structure).support_names == ("left", "right")
    path.write_text(text.replace("right = [", "keystone = ["))
    with pytest.raises(StudyError, match="scenarios.down.keystone"):
        load_study(path)
    path.write_text(text.replace("blocks/arch.json", "blocks/none.json"))
    with pytest.raises(StudyError, match="structure: cannot build it"):
        load_study(path)
