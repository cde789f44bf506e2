"""Multi-ring arches in the battery (issue 40): a metamorphic relation over ring laws, and the
per-interface law carried through the battery's moves.

Relation: a multi-ring arch is never stronger than its bonded counterpart (the same blocks with
faces between rings that carry any force): every force state admissible under a ring law is
admissible when the rings are bonded, so lambda_max(ring law) <= lambda_max(bonded) (to the
direct limit's precision, 1e-7 relative) and a scene that stands with the ring law stands
bonded. The cases: aligned and staggered rings on three arch types, under the lateral pattern
and a live point load on top, with ring laws from frictionless to cohesive.
"""

from __future__ import annotations

import math

import pytest

from tce.core.analysis import Analysis
from tce.core.loads import LoadPattern, PointLoad
from tce.core.material import Material
from tce.structures.arch import RING, pointed_arch, segmental_arch, semicircular_arch
from tce.structures.defects import with_joint_loss, with_kinds, without_blocks, without_joints

from .cases import Scene, answer, path_settings
from .relations import same_answer
from .transform import Similarity

ARCHES = {
    "semicircular_aligned": lambda: semicircular_arch(1.0, 0.3, 0.25, 6, rings=2),
    "semicircular_staggered": lambda: semicircular_arch(1.0, 0.3, 0.25, 6, rings=3, stagger=True),
    "segmental_staggered": lambda: segmental_arch(2.0, 0.6, 0.25, 0.25, 5, rings=2, stagger=True),
    "pointed_listed": lambda: pointed_arch(2.0, thickness=0.25, voussoirs=6, rings=[0.1, 0.15], stagger=True),
}
RING_LAWS = {
    "frictionless": Material(friction=0.0),
    "friction": Material(friction=0.4),
    "cohesive": Material(friction=0.5, cohesion=3.0, tensile_strength=1.0),
    "heyman": Material(),
}
LOADS = {
    "lateral": lambda asm: LoadPattern(alpha=0.0),
    "on_top": lambda asm: LoadPattern(point=[PointLoad(force=(0.0, 0.0, -0.2 * asm.total_weight), on_top=(-0.3, 0.0))]),
}
JOINTS = Material(friction=0.7)


def _with_ring_law(law: Material) -> Material:
    return Material(friction=JOINTS.friction, interfaces={RING: law})


@pytest.mark.parametrize("load", sorted(LOADS))
@pytest.mark.parametrize("law", sorted(RING_LAWS))
@pytest.mark.parametrize("arch", sorted(ARCHES))
def test_never_stronger_than_bonded(arch, law, load):
    asm = ARCHES[arch]()
    pattern = LOADS[load](asm)
    rings = Analysis(asm, _with_ring_law(RING_LAWS[law])).limit(loads=pattern)
    bonded = Analysis(asm, _with_ring_law(Material(bonded=True))).limit(loads=pattern)
    # bonded, a staggered arch has no joint through its thickness but the springings': a vertical
    # load finds no mechanism (unbounded, lambda_max = inf)
    assert bonded.status in ("optimal", "unbounded"), bonded.status
    if rings.status == "infeasible":  # the rings cannot stand apart; bonded they do
        return
    assert rings.status in ("optimal", "unbounded")
    assert rings.status == "optimal" or bonded.status == "unbounded"
    assert rings.lambda_max <= bonded.lambda_max * (1 + 1e-7) + 1e-9, (rings.lambda_max, bonded.lambda_max)


def _with_defects(asm):
    """The staggered three-ring arch with an inspection's defects (tce.structures.defects)."""
    asm = with_kinds(asm, {"r2v03|r2v04": "weak"})
    asm = with_joint_loss(asm, "r1v02|r1v03", intrados=0.02)
    return without_blocks(without_joints(asm, ["r1v05|r2v05"]), ["r3v02"])


@pytest.mark.parametrize("defects", [False, True], ids=["intact", "defects"])
@pytest.mark.parametrize("t", [Similarity.rotation(90.0), Similarity.mirror(30.0), Similarity.units(1000.0, 1000.0)],
                         ids=["rotation", "mirror", "mm_N"])
def test_ring_law_moves_with_the_scene(t, defects):
    """A cohesive ring law (its cohesion and tensile strength in the scene's units) on a
    staggered arch, intact or with defects (a missing brick, a trimmed joint, a separated face,
    a weak joint's own law), under a live point load: the answer moves with the scene."""
    asm = ARCHES["semicircular_staggered"]()
    material = _with_ring_law(RING_LAWS["cohesive"])
    if defects:
        asm = _with_defects(asm)
        material = Material(friction=JOINTS.friction, interfaces={RING: RING_LAWS["cohesive"], "weak": Material(friction=0.3)})
    sc = Scene(asm, material, LOADS["on_top"](asm))
    a = answer(sc)
    assert math.isfinite(a.lambda_direct)
    b = answer(sc.mapped(t), lam=a.lam, step=path_settings(a.lambda_direct), about=t.points(a.about))
    same_answer(a, b, t)


# ----------------------------------------------------------------------------- studies
RING_SECTION = {"type": "semicircular_arch", "thickness": 0.3, "voussoirs": 6, "rings": 3, "stagger": True}


def _ring_study(name: str, structure: dict, material: Material, pattern: LoadPattern,
                sweep: dict[str, list[float]] | None = None, ring: dict | None = None) -> str:
    """A study with ``[ring_interface]``: ``ring``, default the ring law of ``material``."""
    from .studies import _table, material_section, study_text

    text = study_text(name, structure, material, pattern, {"none": {}}, loads={"lambda_step": 0.05, "tolerance": 1e-6},
                      sweep=sweep)
    return text + _table("ring_interface", material_section(material.law(RING)) if ring is None else ring)


@pytest.mark.parametrize("t", [Similarity.rotation(90.0), Similarity.units(1000.0, 1000.0)], ids=["rotation", "mm_N"])
def test_ring_study_moved_as_a_block_file(t, tmp_path):
    """The study of a staggered three-ring arch with a cohesive ring law, against the same
    study turned about z or in mm and N, its structure a block file (the interfaces' kinds
    stored in it): the same story (tests/battery/test_studies.py's comparison)."""
    from .studies import file_section, run
    from .test_studies import same_results

    asm = ARCHES["semicircular_staggered"]()
    sc = Scene(asm, _with_ring_law(RING_LAWS["cohesive"]), LOADS["on_top"](asm))
    a = run(_ring_study("built", RING_SECTION, sc.material, sc.pattern), tmp_path)
    moved = sc.mapped(t)
    b = run(_ring_study("moved", file_section(moved.assembly, tmp_path, "moved"), moved.material, moved.pattern), tmp_path)
    same_results(a, b, t)
    assert a["ring_separation"].values.tolist() == b["ring_separation"].values.tolist()


def test_ring_study_runners(tmp_path):
    """Two worker processes and a resumed run give the in-process dataset of a ring study with
    a friction sweep (of the joints and, left out of [ring_interface], of the faces between rings)."""
    from .studies import runners_agree

    asm = ARCHES["semicircular_staggered"]()
    text = _ring_study("runners", RING_SECTION, JOINTS, LOADS["lateral"](asm), sweep={"friction": [0.7, 0.9]},
                       ring={"cohesion": 1.0})
    runners_agree(text, tmp_path)
