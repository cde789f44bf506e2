"""Backing in study files (issue 40, item 2): ``[structure] backing`` and ``[backing_interface]``."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import xarray as xr

from tce.cli import main
from tce.core.material import Material
from tce.structures.backing import BACKING
from tce.study.schema import StudyError, build_material, parse_study

HEAD = """
[study]
name = "backed"

[structure]
type = "segmental_arch"
span = 2.0
rise = 0.6
thickness = 0.15
voussoirs = 8
backing = { height = 0.3, unit_weight = 22.0 }

[material]
friction = 0.6

[loads]
lateral = false
lambda_step = 0.5

[[loads.point]]
force = [0.0, 0.0, -1.0]
on_top = [0.0, 0.0]
"""


def _lambda(tmp_path: Path, text: str) -> tuple[float, xr.Dataset]:
    tmp_path.mkdir(parents=True, exist_ok=True)
    study = tmp_path / "backed.toml"
    study.write_text(text, encoding="utf-8")
    assert main(["-q", "run", str(study), "--out", str(tmp_path), "--no-plots", "--jobs", "1"]) == 0
    ds = xr.load_dataset(tmp_path / "backed" / "results.nc")
    return float(ds["lambda_max"].values[0]), ds


def test_backing_interface_sets_the_law_of_the_backing_faces(tmp_path: Path):
    """Backing to 0.3 m on the arch (3.52 kN at the crown without backing): 4.08 kN bearing
    without friction, 4.94 kN with friction 0.2."""
    bearing, _ = _lambda(tmp_path / "a", HEAD + "\n[backing_interface]\nfriction = 0.0\n")
    rough, ds = _lambda(tmp_path / "b", HEAD + "\n[backing_interface]\nfriction = 0.2\n")
    assert bearing == pytest.approx(4.08, abs=0.01) and rough == pytest.approx(4.94, abs=0.01)
    mat = build_material(json.loads(ds.attrs["material"]))
    assert mat.law(BACKING) == Material(friction=0.2) and mat.friction == 0.6
    assert "backing_left" in ds.attrs["assembly"] and "wall_left" in ds.attrs["assembly"]
    bonded = parse_study(HEAD + "\n[backing_interface]\nbonded = true\n")
    assert build_material(bonded.scenarios()[0].material).law(BACKING) == Material(bonded=True)


def test_fill_backing_parses_to_heavier_voussoirs():
    study = parse_study(HEAD.replace("unit_weight = 22.0 }", "unit_weight = 22.0, model = \"fill\" }"))
    asm = study.assembly(study.scenarios()[0].structure)
    assert asm.meta["backing"]["model"] == "fill" and "backing_left" not in asm.names


@pytest.mark.parametrize("edit, words", [
    (lambda t: t.replace("height = 0.3", "height = 0.05") + "\n[backing_interface]\nfriction = 0.3\n",
     "no backing blocks"),
    (lambda t: t.replace("height = 0.3", "height = 0.3, model = \"fill\"") + "\n[backing_interface]\nbonded = true\n",
     "no backing blocks"),
    (lambda t: t + "\n[backing_interface]\nbonded = true\nfriction = 0.3\n", "bonded"),
    (lambda t: t.replace("height = 0.3", "height = 0.9"), "crown"),
    (lambda t: t.replace("unit_weight = 22.0 }", "model = \"rubble\" }"), "model"),
])
def test_errors(edit, words):
    with pytest.raises(StudyError, match=words):
        parse_study(edit(HEAD))
