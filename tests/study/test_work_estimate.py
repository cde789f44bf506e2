"""The work a study states (:func:`tce.study.guards.work`) counts every solve it may make."""

from __future__ import annotations

from tce.study import guards
from tce.study.schema import parse_study

PATH = ('[study]\nname = "w"\n[structure]\ntype = "semicircular_arch"\nvoussoirs = 4\n'
        '[loads]\nlateral = false\n[[loads.point]]\non_top = [0.0, 0.0]\nforce = [0.0, 0.0, -1.0]\n'
        "[scenarios.out]\nright = [0.01, 0.0, 0.0, 0.0, 0.0, 0.0]\n"
        "[settlement_path]\nincrement = 0.1\ns_max = 1.0\n")


def _solves(text: str) -> int:
    study = parse_study(text, "w.toml")
    return guards.work(study.spec, study.search_solves())[0]


def test_each_live_load_limit_of_a_settlement_path_is_one_solve() -> None:
    """Two more ``live_at`` magnitudes add two limit solves to the one scenario's count."""
    one = _solves(PATH + "live_at = [0.5]\n")
    assert _solves(PATH + "live_at = [0.0, 0.5, 1.0]\n") == one + 2
