"""Bounds of the study file that no later check repeats (:mod:`tce.study.schema`)."""

from __future__ import annotations

import pytest

from tce.study.guards import StudyError
from tce.study.schema import parse_study

PATH = ('[study]\nname = "b"\n[structure]\ntype = "semicircular_arch"\nvoussoirs = 4\n'
        '[loads]\nlateral = false\n[[loads.point]]\non_top = [0.0, 0.0]\nforce = [0.0, 0.0, -1.0]\n'
        "[scenarios.out]\nright = [0.01, 0.0, 0.0, 0.0, 0.0, 0.0]\n"
        "[settlement_path]\nincrement = 0.1\ns_max = 1.0\nlive_at = [{at}]\n")


def test_live_loads_are_applied_at_a_magnitude_of_the_path() -> None:
    """A negative magnitude is no point of the path (it runs from 0 to ``s_max``): refused
    naming the key, where it would have been reported as ``not_standing``."""
    parse_study(PATH.format(at=0.0), "b.toml")
    with pytest.raises(StudyError, match=r"^b\.toml: settlement_path\.live_at"):
        parse_study(PATH.format(at=-0.01), "b.toml")
