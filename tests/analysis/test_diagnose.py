"""Why a scene fails: binding interfaces and mechanisms named for the user."""

from tce.analysis import Analysis
from tce.structures.arch import semicircular_arch
from tce.analysis.diagnose import diagnose
from tce.core.material import Material

MM = 1e-3


def test_overload_names_the_four_hinges(arch):
    d = diagnose(Analysis(arch, Material(0.8)), 0.3, 0.0)
    assert d.status == "infeasible"
    assert "exceeds lambda_max = 0.242824" in d.summary
    assert sorted(n for n, what in d.binding if what == "hinge") == ["v01|v02", "v06|v07", "v11|v12", "v14|right"]
    assert len(d.mechanism.hinges) == 4


def test_incompatible_settlement_names_the_self_stress(arch):
    d = diagnose(Analysis(arch, Material()), 0.0, 0.0, {"right": [0, MM, 0, 0, 0, 0]})
    assert d.status == "unbounded"
    assert "friction coefficient" in d.summary
    assert ("v14|right", "self-stress") in d.binding


def test_admissible_state_reports_its_limits(arch):
    # an outward spreading opens three hinges (the minimum-thrust state)
    d = diagnose(Analysis(arch, Material()), 0.0, 0.0, {"left": [-MM, 0, 0, 0, 0, 0], "right": [MM, 0, 0, 0, 0, 0]})
    assert d.status == "optimal"
    assert len([b for b in d.binding if b[1] == "hinge"]) == 3


def test_too_thin_arch_cannot_stand():
    d = diagnose(Analysis(semicircular_arch(0.96, 0.08), Material()), 0.0, 0.0)
    assert d.status == "infeasible"
    assert "cannot carry" in d.summary
