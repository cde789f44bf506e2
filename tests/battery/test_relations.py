"""Metamorphic relations over generated scenes (issue 21, "a cross-feature battery").

Hypothesis draws a scene: a structure type (every generator and a block file), a material
kind (Heyman, friction, cohesion with a tensile strength, compressive strength, compliant,
non-associative), a load kind (the lateral pattern; a point load on a block, on the top
surface, or a pressure on a plan rectangle, each live or fixed) and a settlement (none, in
the structure's plane, across it); then each relation moves the whole scene and checks that
tce's answers move with it (``relations.same_answer``: outcome, lambda_max, statuses,
reactions). Derandomized like the rest of the suite (tests/conftest.py).

Relations: rotation about z by any angle (planar models in any vertical plane, structures
spanning y; at angles that are not multiples of 90 degrees the model is spatial: planar
against spatial too), translation, mirror in a vertical plane, m/kN -> mm/N, blocks and
interfaces permuted (and read from the other side), a load split into two halves, and the
spatial model forced on a planar scene.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

from tce.core.loads import LoadPattern

from .cases import LOADS, MATERIALS, PLANAR, SETTLEMENTS, STRUCTURES, Scene, answer, path_settings, scene
from .relations import same_answer
from .transform import Similarity, permuted

# no shrinking: an example costs up to a second, and the drawn scene is named by its parts
SETTINGS = settings(
    max_examples=20, deadline=None, phases=(Phase.explicit, Phase.reuse, Phase.generate),
    suppress_health_check=[HealthCheck.too_slow],
)


def _material(structure: str) -> st.SearchStrategy[str]:
    """Material kinds for ``structure``: the non-associative scheme (up to 100 solves of
    the spatial model) only on the structures with a planar model; spatial ones in
    ``test_regressions.py``."""
    kinds = tuple(MATERIALS)
    return st.sampled_from(kinds if structure in PLANAR else tuple(k for k in kinds if k != "non_associative"))


def _scenes(loads: tuple[str, ...]) -> st.SearchStrategy[Scene]:
    return st.sampled_from(STRUCTURES).flatmap(
        lambda s: st.builds(
            scene, st.just(s), _material(s), st.sampled_from(loads), st.sampled_from(tuple(SETTLEMENTS)),
            st.sampled_from((0.0, 90.0, 30.0, 225.0)),
        )
    )


scenes = _scenes(LOADS)
#: multiples of 90 degrees first (a planar model stays planar: its plane normal to x or y)
angles = st.one_of(st.sampled_from((90.0, 180.0, -90.0)), st.floats(-180.0, 180.0))


def _check(sc: Scene, t: Similarity, model: str = "auto") -> None:
    a = answer(sc)
    b = answer(sc.mapped(t), lam=a.lam, step=path_settings(a.lambda_direct), about=t.points(a.about), model=model)
    same_answer(a, b, t)


def _axes_kept(sc: Scene, angle: float) -> float:
    """``angle``, or the nearest multiple of 90 when the scene has a plan rectangle (a
    rotated rectangle is not one)."""
    return float(round(angle / 90.0) * 90.0) if sc.pattern.distributed else angle


@SETTINGS
@given(sc=scenes, angle=angles)
def test_rotation_about_z(sc, angle):
    _check(sc, Similarity.rotation(_axes_kept(sc, angle)))


@SETTINGS
@given(sc=scenes, shift=st.tuples(st.floats(-50.0, 50.0), st.floats(-50.0, 50.0), st.floats(-10.0, 10.0)))
def test_translation(sc, shift):
    _check(sc, Similarity.translation(shift))


@SETTINGS
@given(sc=scenes, angle=angles)
def test_mirror(sc, angle):
    _check(sc, Similarity.mirror(_axes_kept(sc, angle)))


@SETTINGS
@given(sc=scenes)
def test_units_mm_and_newtons(sc):
    _check(sc, Similarity.units(1000.0, 1000.0))


@SETTINGS
@given(sc=scenes, data=st.data())
def test_permuted_blocks_and_interfaces(sc, data):
    """Blocks and interfaces listed in another order, every other interface read from its
    other side (``a`` and ``b`` swapped, the normal reversed)."""
    asm = sc.assembly
    order = data.draw(st.permutations(range(len(asm.blocks))), label="block order")
    iorder = data.draw(st.permutations(range(len(asm.interfaces))), label="interface order")
    swap = [k % 2 == 1 for k in range(len(asm.interfaces))]
    a = answer(sc)
    b = answer(replace(sc, assembly=permuted(asm, order, iorder, swap)), lam=a.lam, step=path_settings(a.lambda_direct))
    same_answer(a, b)


def _halves(p: LoadPattern) -> LoadPattern:
    """Every point load as two of half its force at the same place, every distributed load
    as two on the halves of its x range."""
    point = [replace(q, force=tuple(0.5 * np.asarray(q.force))) for q in p.point for _ in range(2)]
    distributed = []
    for d in p.distributed:
        mid = 0.5 * (d.x[0] + d.x[1])
        distributed += [replace(d, x=(d.x[0], mid)), replace(d, x=(mid, d.x[1]))]
    return replace(p, point=tuple(point), distributed=tuple(distributed))


@SETTINGS
@given(
    sc=_scenes(tuple(k for k in LOADS if k != "lateral"))
)
def test_load_split_in_two_halves(sc):
    a = answer(sc)
    b = answer(replace(sc, pattern=_halves(sc.pattern)), lam=a.lam, step=path_settings(a.lambda_direct))
    same_answer(a, b)


@SETTINGS
@given(sc=scenes, angle=st.sampled_from((0.0, 90.0, 180.0, 270.0)))
def test_planar_against_spatial(sc, angle):
    """The spatial model forced on a scene turned by a multiple of 90 degrees (planar models
    in the planes normal to y and to x) gives the answer of the model tce chooses."""
    _check(sc.mapped(Similarity.rotation(angle)), Similarity(), model="spatial")
