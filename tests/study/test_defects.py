"""``[defects]`` in study files (issue 40): the structure each scenario runs on carries them,
the dataset lists the joint laws, and names the structure lacks are refused with the key."""

from __future__ import annotations

import pytest

from tce.core.material import Material
from tce.structures.defects import with_joint_loss, with_kinds, with_unit_weights, without_blocks, without_joints
from tce.structures.arch import semicircular_arch
from tce.study.schema import StudyError, build_material, parse_study

HEAD = """
[study]
name = "defects"

[structure]
type = "semicircular_arch"
thickness = 0.3
voussoirs = 8
rings = 3

[material]
friction = 0.6
"""
DEFECTS = """
[defects]
missing = ["r3v04"]
unit_weight = { r1v02 = 15.0 }
separated = ["r1v06|r2v06"]

[[defects.mortar_loss]]
joint = "r1v02|r1v03"
intrados = 0.03

[[defects.joint_law]]
joints = ["r2v03|r2v04"]
friction = 0.3
"""


def test_the_structure_carries_the_defects():
    study = parse_study(HEAD + DEFECTS)
    sc = study.scenarios()[0]
    built = study.assembly(sc.structure)
    expected = semicircular_arch(1.0, 0.3, 0.25, 8, rings=3)
    expected = with_kinds(expected, {"r2v03|r2v04": "joints1"})
    expected = with_joint_loss(expected, "r1v02|r1v03", intrados=0.03)
    expected = without_blocks(with_unit_weights(without_joints(expected, ["r1v06|r2v06"]), {"r1v02": 15.0}), ["r3v04"])
    assert built.to_dict()["interfaces"] == expected.to_dict()["interfaces"]
    assert built.names == expected.names
    assert [b.unit_weight for b in built.blocks] == [b.unit_weight for b in expected.blocks]
    mat = build_material(sc.material)
    assert mat.law("joints1") == Material(friction=0.3) and mat.friction == 0.6


@pytest.mark.parametrize("defects, words", [
    ('\n[defects]\nmissing = ["r9v01"]\n', "defects: unknown block"),
    ('\n[defects]\nseparated = ["r1v01|r1v05"]\n', "defects: no joint"),
    ('\n[[defects.mortar_loss]]\njoint = "r1v02|r1v03"\nintrados = 0.2\n', "leaves no contact"),
])
def test_names_the_structure_lacks_are_refused(defects, words):
    with pytest.raises(StudyError, match=words) as err:
        parse_study(HEAD + defects)
    assert "fix: name the blocks and joints of [defects]" in str(err.value)
