"""The three-dimensional arch bridge (skew, in running-bonded courses, under fill and a live
wheel load on its deck) turned in plan by any angle or mirrored gives the same
answer: the battery's relations (``relations.same_answer``: outcome, lambda_max, statuses,
reactions) on a scene of its own, beside the drawn scenes of ``test_relations.py``. A
vehicle moves along x and cannot be turned, so the wheel is a point load on the top surface."""

from __future__ import annotations

from functools import cache

import pytest

from tce.core.loads import LoadPattern, PointLoad
from tce.core.material import Material
from tce.structures.bridge import arch_bridge

from .cases import Answer, Scene, answer, path_settings
from .relations import same_answer
from .transform import Similarity

BRIDGE = arch_bridge(span=4.0, rise=1.0, thickness=0.3, depth=1.5, voussoirs=5, courses=3, bond="running",
                     skew=25.0, pier_height=0.5).validate()
SCENE = Scene(BRIDGE, Material(friction=0.6),
              LoadPattern(lateral=False, fill=dict(depth=0.2, unit_weight=18.0),
                          point=[PointLoad(force=(0.0, 0.0, -20.0), on_top=(-1.1, 0.4))]),
              {"abutment_right": [1e-3, 0.0, -5e-4, 0.0, 0.0, 0.0]})


@cache
def original() -> Answer:
    return answer(SCENE)


@pytest.mark.parametrize("t", [Similarity.rotation(-137.5), Similarity.mirror(30.0)], ids=["turn-137.5", "mirror30"])
def test_skew_bridge_turned_in_plan_gives_the_same_answer(t):
    a = original()
    assert a.outcome == "limit"
    b = answer(SCENE.mapped(t), lam=a.lam, step=path_settings(a.lambda_direct), about=t.points(a.about))
    same_answer(a, b, t)
