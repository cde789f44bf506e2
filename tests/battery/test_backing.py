"""Backing behind the haunches in the battery (issue 40, item 2; :mod:`tce.structures.backing`).

- Moves: a two-ring arch with backing blocks (their own cohesive law on the faces of kind
  ``"backing"``) or with the backing as fill, under a live point load: the answer moves with
  the scene turned in plan, mirrored, and in mm and N; as a study, against the same study of
  the moved blocks written to a block file (the interfaces' kinds and the fill's heavier
  voussoirs stored in it).
- Runners: a thickness sweep of a two-ring arch with backing blocks and a
  ``[backing_interface]`` law: two worker processes and a run resumed after one scenario file
  is removed give the in-process dataset.
- Relation: lambda_max never falls as the backing law grows (frictionless bearing, then
  friction, then bonded): every force state admissible under the weaker law is admissible
  under the stronger, the blocks, their weights and the other laws the same. The relation the
  issue suggests, "backing on a frictionless bearing never lowers the capacity against no
  backing", is not a theorem and is not tested: the backing's weight must go somewhere, and
  on a frictionless bearing (walls behind included) it all bears on the extrados, a fixed
  load the arch without backing does not carry (docs/materials.md: the same load as the
  fill model), which may as well load a haunch into a mechanism as stabilise it.
"""

from __future__ import annotations

import math

import pytest

from tce.core.analysis import Analysis
from tce.core.loads import LoadPattern, PointLoad
from tce.core.material import Material
from tce.structures.arch import RING, pointed_arch, segmental_arch, semicircular_arch
from tce.structures.backing import BACKING, Backing

from .cases import Scene, answer, path_settings
from .relations import same_answer
from .transform import Similarity

JOINTS = 0.7
RING_LAW = Material(friction=0.4)
BACKING_LAW = Material(friction=0.1, cohesion=0.5)  # its cohesion governs (lambda 11 without)
HEIGHT = 0.6


def _arch(model: str):
    return semicircular_arch(1.0, 0.3, 0.25, 6, rings=2, backing=Backing(HEIGHT, 22.0, model))


def _material(backing: Material | None) -> Material:
    laws = {RING: RING_LAW} | ({} if backing is None else {BACKING: backing})
    return Material(friction=JOINTS, interfaces=laws)


def _on_top(asm) -> LoadPattern:
    return LoadPattern(point=[PointLoad(force=(0.0, 0.0, -0.2 * asm.total_weight), on_top=(-0.3, 0.0))])


def _scene(model: str) -> Scene:
    asm = _arch(model)
    return Scene(asm, _material(BACKING_LAW if model == "blocks" else None), _on_top(asm))


MOVES = [Similarity.rotation(90.0), Similarity.mirror(30.0), Similarity.units(1000.0, 1000.0)]


@pytest.mark.parametrize("t", MOVES, ids=["rotation", "mirror", "mm_N"])
@pytest.mark.parametrize("model", ["blocks", "fill"])
def test_backing_moves_with_the_scene(model, t):
    sc = _scene(model)
    a = answer(sc)
    assert math.isfinite(a.lambda_direct)
    b = answer(sc.mapped(t), lam=a.lam, step=path_settings(a.lambda_direct), about=t.points(a.about))
    same_answer(a, b, t)


def _section(model: str) -> dict:
    return {"type": "semicircular_arch", "thickness": 0.3, "voussoirs": 6, "rings": 2,
            "backing": {"height": HEIGHT, "unit_weight": 22.0, "model": model}}


def _backing_study(name: str, structure: dict, material: Material, pattern: LoadPattern,
                   step: tuple[float, float], sweep: dict[str, list[float]] | None = None) -> str:
    """A study with ``[ring_interface]``, and ``[backing_interface]`` where ``material`` gives
    the backing a law, the laws of ``material``; ``step``: the load path's step and cap
    (:func:`tests.battery.cases.path_settings`)."""
    from .studies import _table, material_section, study_text

    loads = {"lambda_step": step[0], "lambda_cap": step[1], "tolerance": 1e-6}
    text = study_text(name, structure, material, pattern, {"none": {}}, loads=loads, sweep=sweep)
    text += _table("ring_interface", material_section(material.law(RING)))
    if BACKING in dict(material.interfaces):
        text += _table("backing_interface", material_section(material.law(BACKING)))
    return text


@pytest.mark.parametrize(("model", "t"), [("blocks", Similarity.mirror(30.0)), ("blocks", Similarity.units(1000.0, 1000.0)),
                                          ("fill", Similarity.units(1000.0, 1000.0))],
                         ids=["blocks-mirror", "blocks-mm_N", "fill-mm_N"])
def test_backing_study_moved_as_a_block_file(model, t, tmp_path):
    """The study of a two-ring arch with backing blocks (or fill), against the same study
    mirrored or in mm and N, its structure a block file (the kinds of the interfaces, and the
    fill's heavier voussoirs, stored in it): the same story."""
    from .studies import file_section, run
    from .test_studies import same_results

    sc = _scene(model)
    step = path_settings(answer(sc).lambda_direct)
    a = run(_backing_study("built", _section(model), sc.material, sc.pattern, step), tmp_path)
    backing = {"backing_left", "backing_right", "wall_left", "wall_right"}
    assert (backing <= set(a["block"].values.tolist())) == (model == "blocks")
    moved = sc.mapped(t)
    b = run(_backing_study("moved", file_section(moved.assembly, tmp_path, "moved"), moved.material, moved.pattern,
                           step), tmp_path)
    same_results(a, b, t)


def test_backing_sweep_runners(tmp_path):
    """Two worker processes and a resumed run give the in-process dataset of a thickness sweep
    of a two-ring arch with backing blocks."""
    from .studies import runners_agree

    sc = _scene("blocks")
    text = _backing_study("runners", _section("blocks"), sc.material, LoadPattern(alpha=0.0), (0.05, 1.0),
                          sweep={"thickness": [0.3, 0.36]})
    assert runners_agree(text, tmp_path).sizes["scenario"] == 2


# ----------------------------------------------------------------------------- relation
ARCHES = {
    "semicircular_rings": lambda b: semicircular_arch(1.0, 0.3, 0.25, 6, rings=2, backing=b),
    "segmental": lambda b: segmental_arch(2.0, 0.6, 0.15, 0.25, 6, backing=b),
    "pointed_staggered": lambda b: pointed_arch(2.0, thickness=0.2, voussoirs=6, rings=2, stagger=True, backing=b),
}
#: backing laws from the weakest to the strongest
LAWS = [Material(friction=0.0), Material(friction=0.5), Material(friction=0.5, cohesion=2.0), Material(bonded=True)]


@pytest.mark.parametrize("load", ["lateral", "crown"])
@pytest.mark.parametrize("arch", sorted(ARCHES))
def test_stronger_backing_law_never_lowers_the_capacity(arch, load):
    asm = ARCHES[arch](Backing(0.5 if arch == "semicircular_rings" else 0.3))
    assert BACKING in {i.kind for i in asm.interfaces}
    pattern = (LoadPattern(alpha=0.0) if load == "lateral"
               else LoadPattern(lateral=False, point=[PointLoad(force=(0.0, 0.0, -1.0), on_top=(0.0, 0.0))]))
    lams = []
    for law in LAWS:
        r = Analysis(asm, _material(law)).limit(loads=pattern)
        assert r.status in ("optimal", "unbounded", "infeasible"), r.status
        lams.append(-math.inf if r.status == "infeasible" else r.lambda_max if r.status == "optimal" else math.inf)
    assert math.isfinite(lams[0]), lams
    for weak, strong in zip(lams, lams[1:]):
        assert weak <= strong * (1 + 1e-7) + 1e-9, lams
