"""The fill's passive restraint in study files (`[loads.fill] kp`): the load path carries it
(its lambda_max is the direct limit within the bracket tolerance, as without it), the dataset
stores the summed restraint of each state (`passive_force`), and studies/bridge_passive.toml
parses with it. Its validation against an independent LP is tests/validation/test_passive_restraint.py."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from tce.cli import main
from tce.core.analysis import Analysis
from tce.core.fill import passive_bounds
from tce.structures.arch import segmental_arch
from tce.study.schema import parse_study

ROOT = Path(__file__).resolve().parents[2]

STUDY = """
[study]
name = "passive"

[structure]
type = "segmental_arch"
span = 6.0
rise = 1.5
thickness = 0.3
depth = 3.0
voussoirs = 12
unit_weight = 20.0

[loads]
lateral = false
lambda_step = 0.25
tolerance = 1e-6
lambda_cap = 10.0

[loads.fill]
depth = 0.3
unit_weight = 18.0
dispersion = 0.0
k0 = 0.5
kp = KP

[[loads.vehicle]]
axles = [[0.0, 100.0]]
wheels = [0.0]
x = -1.8

[scenarios.none]
"""


def run(tmp_path: Path, kp: float) -> xr.Dataset:
    path = tmp_path / f"kp{kp:g}.toml"
    path.write_text(STUDY.replace("KP", repr(kp)))
    out = tmp_path / f"out{kp:g}"
    assert main(["run", str(path), "--out", str(out), "--jobs", "1", "--no-plots"]) == 0
    return xr.load_dataset(out / "passive" / "results.nc")


def test_study_load_path_carries_the_passive_restraint(tmp_path) -> None:
    on, off = run(tmp_path, 3.0), run(tmp_path, 0.0)
    lam, direct = float(on.lambda_max[0]), float(on.lambda_direct[0])
    assert str(on.outcome.values[0]) == "limit"
    # the bracket [lambda_max, lambda_upper] holds the direct limit (tolerance 1e-6)
    assert lam <= direct + 1e-9 <= float(on.lambda_upper[0]) + 2e-9
    assert lam == pytest.approx(direct, abs=2e-6)
    assert lam > 1.2 * float(off.lambda_max[0])  # kp = 3 is not kp = 0
    # each optimal state's restraint within [0, sum of the caps]; NaN where there is none
    scen = parse_study(STUDY.replace("KP", "3.0")).scenarios()[0]
    ring = segmental_arch(span=6.0, rise=1.5, thickness=0.3, depth=3.0, voussoirs=12, unit_weight=20.0)
    cap = sum(b[3] for b in passive_bounds(ring, scen.loads_pattern.fill))
    ok = on.status.values[0] == "optimal"
    p = on.passive_force.values[0][ok]
    assert ok.sum() >= 5 and np.all(p >= -1e-6) and np.all(p <= cap + 1e-6) and p.max() > 1.0
    assert np.isnan(on.passive_force.values[0][~ok]).all()
    # the stored value is the state's summed restraint: the same solve through the Python API
    i = int(np.flatnonzero(ok)[-1])
    state = Analysis(ring).solve(float(on.lam.values[0][i]), loads=scen.loads_pattern)
    assert float(on.passive_force.values[0][i]) == pytest.approx(state.restraint_forces.sum(), rel=1e-6)
    assert np.isnan(off.passive_force.values).all()


def test_bridge_passive_study_parses_with_its_passive_coefficient() -> None:
    path = ROOT / "studies" / "bridge_passive.toml"
    fill = parse_study(path.read_text(), path).scenarios()[0].loads_pattern.fill
    assert (fill.depth, fill.k0, fill.kp) == (0.3, 0.5, 3.0)


def test_passive_restraint_with_a_non_associative_material_exits_2(tmp_path, capsys) -> None:
    # the non-associative estimate does not carry the restraint: refused before anything runs
    path = tmp_path / "na.toml"
    path.write_text(STUDY.replace("KP", "3.0").replace("[loads]", '[material]\nfriction = 0.6\nflow = "non-associative"\n\n[loads]'))
    code = main(["run", str(path), "--out", str(tmp_path / "out"), "--jobs", "1", "--no-plots"])
    err = capsys.readouterr().err
    assert code == 2 and f"{path}: loads.fill.kp" in err and "fix:" in err
    assert not (tmp_path / "out").exists()


def test_drawn_states_say_the_passive_restraint_they_carry(tmp_path) -> None:
    """`states.png` draws the ring's interface forces, not the fill's pieces: a state that
    leans on the restraint says how much (the stored sum) in its note; one without says nothing."""
    from tce.plot import data, figures

    on, off = run(tmp_path, 3.0), run(tmp_path, 0.0)
    st = data.find_state(on, "none", "max")
    pushed = float(on.passive_force.sel(scenario="none", step=st.step))
    assert pushed > 1.0 and f"pushes {pushed:.3g} kN" in st.note
    fig = figures.states_figure(on, [("none", "max")])
    assert any(f"pushes {pushed:.3g} kN" in t.get_text() for t in fig.axes[0].texts)
    assert "passive" not in data.find_state(off, "none", "max").note
