"""Multi-ring arches in study files (issue 40): ``rings``, ``stagger`` and ``[ring_interface]``,
what the dataset stores about ring separation, and what ``tce show`` says."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
import xarray as xr

from tce.cli import main
from tce.core.material import Material
from tce.structures.arch import RING
from tce.study.schema import StudyError, build_material, parse_study

HEAD = """
[study]
name = "rings"

[structure]
type = "semicircular_arch"
thickness = 0.3
voussoirs = 6
rings = 2

[material]
friction = 0.6
"""


def _run(tmp_path: Path, text: str, capsys) -> tuple[xr.Dataset, str]:
    tmp_path.mkdir(parents=True, exist_ok=True)
    study = tmp_path / "rings.toml"
    study.write_text(text, encoding="utf-8")
    assert main(["-q", "run", str(study), "--out", str(tmp_path), "--no-plots", "--jobs", "1"]) == 0
    results = tmp_path / "rings" / "results.nc"
    capsys.readouterr()
    assert main(["show", str(results)]) == 0
    return xr.load_dataset(results), capsys.readouterr().out


def test_debonded_rings_separate_and_bonded_ones_do_not(tmp_path: Path, capsys):
    debonded, shown = _run(tmp_path / "a", HEAD + "\n[ring_interface]\nfriction = 0.3\n", capsys)
    assert float(debonded["ring_separation"].values[0]) == 1.0
    where = str(debonded["ring_separation_at"].values[0])
    assert "faces between rings" in where
    assert f"ring separation: none: the rings separate at the limit ({where})" in shown
    kinds = debonded["interface_kind"].values.tolist()
    assert kinds.count(RING) == 6 and kinds.count("") == 2 * 7
    # the dataset lists the law of the faces between rings, the keys left out taken from [material]
    mat = build_material(json.loads(debonded.attrs["material"]))
    assert mat.law(RING) == Material(friction=0.3) and mat.friction == 0.6

    bonded, shown = _run(tmp_path / "b", HEAD + "\n[ring_interface]\nbonded = true\n", capsys)
    assert float(bonded["ring_separation"].values[0]) == 0.0
    assert str(bonded["ring_separation_at"].values[0]) == ""
    assert "ring separation: none: the rings act together at the limit" in shown
    assert float(bonded["lambda_max"].values[0]) > float(debonded["lambda_max"].values[0])


def test_without_rings_nothing_is_stored(tmp_path: Path, capsys):
    ds, shown = _run(tmp_path, HEAD.replace("rings = 2", "rings = 1"), capsys)
    assert "ring_separation" not in ds and "interface_kind" not in ds
    assert "ring separation" not in shown


@pytest.mark.parametrize("extra, words", [
    ("\n[ring_interface]\nfriction = 0.3\n", "no faces between rings"),  # with rings = 1 below
    ("\n[ring_interface]\nbonded = true\nfriction = 0.3\n", "bonded rings carry any force"),
    ("\n[ring_interface]\nfriction = 0.3\ntensile_strength = 5.0\n", "tensile_strength"),
])
def test_ring_interface_errors(extra, words):
    text = HEAD + extra
    if "no faces" in words:
        text = text.replace("rings = 2", "rings = 1")
    with pytest.raises(StudyError, match=words):
        parse_study(text)


def test_listed_rings_must_sum_to_the_thickness():
    with pytest.raises(StudyError, match="sum to"):
        parse_study(HEAD.replace("rings = 2", "rings = [0.1, 0.1]"))


def test_staggered_rings_build_and_run_in_a_study():
    study = parse_study(HEAD.replace("rings = 2", "rings = [0.1, 0.2]\nstagger = true"))
    sc = study.scenarios()[0]
    asm = study.assembly(sc.structure)
    assert asm.meta["rings"] == [0.1, 0.2] and asm.meta["stagger"] is True
    assert math.isclose(sum(asm.meta["rings"]), 0.3)


def test_the_mechanism_figure_marks_turns_on_faces_between_rings_apart(tmp_path: Path, capsys):
    """The debonded rings turn on many faces between rings: those are drawn as small markers of
    their own (gid ``ring_hinges``, a legend entry saying the rings separate), the hinge markers
    keep the joints across a ring; bonded rings have none."""
    from tce.plot.figures import mechanism_view

    def drawn(ds: xr.Dataset) -> tuple[int, int, list[str]]:
        fig = mechanism_view(ds, ["none"])
        lines = fig.axes[0].get_lines()
        count = {gid: sum(len(a.get_xdata()) for a in lines if a.get_gid() == gid) for gid in ("hinges", "ring_hinges")}
        labels = [t.get_text() for legend in fig.legends for t in legend.get_texts()]
        return count["hinges"], count["ring_hinges"], labels

    debonded, _ = _run(tmp_path / "a", HEAD + "\n[ring_interface]\nfriction = 0.3\n", capsys)
    modes = debonded["interface_mode"].values[0].astype(str)
    kinds = debonded["interface_kind"].values.astype(str)
    hinges, ring_hinges, labels = drawn(debonded)
    assert ring_hinges == int(((modes == "hinge") & (kinds == RING)).sum()) > 0
    assert hinges == int(((modes == "hinge") & (kinds != RING)).sum())
    assert any("between rings" in str(label) for label in labels)
    bonded, _ = _run(tmp_path / "b", HEAD + "\n[ring_interface]\nbonded = true\n", capsys)
    _, ring_hinges, labels = drawn(bonded)
    assert ring_hinges == 0 and not any("between rings" in str(label) for label in labels)
