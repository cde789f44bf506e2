"""Live loads after a finite settlement (``[settlement_path] live_at``, :mod:`tce.study.settlement`)
and the small-displacement answer that a settlement's magnitude cannot change (issue 37 item 4).

Checked against independent expectations: the path's first state against tce's TCE solve of
the undeformed structure with the same fixed loads; the live loads' factor at magnitude 0
against the critical-position search on the undeformed structure; the deformed contacts
against the placements (every kept point in the plane of block A's face, within the gap).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from tce.analysis import critical
from tce.analysis.critical import critical_position
from tce.analysis.settlement_path import settlement_path
from tce.cli import main
from tce.core.analysis import Analysis
from tce.core.loads import LoadPattern, resolve
from tce.structures.arch import semicircular_arch
from tce.study import load_study
from tce.study import positions
from tce.study.runner import run_study
from tce.study.settlement import deformed_assembly, fixed_part

BRIDGE = """
[study]
name = "pier"

[structure]
type = "arch_bridge"
spans = 2
span = 7.0
rise = 1.75
thickness = 0.45
depth = 3.0
voussoirs = 12
pier_width = 1.0
pier_height = 3.0
piers = "free"

[loads]
lateral = false
critical_position = true
lambda_step = 20.0
tolerance = 1e-4
lambda_cap = 2000.0

[loads.fill]
depth = 0.3
unit_weight = 18.0
dispersion = 0.0
k0 = 0.0

[[loads.vehicle]]
name = "axle"
axles = [[0.0, 100.0]]
wheels = [-0.9, 0.9]

[scenarios.pier_settles]
foundation1 = [0.0, 0.0, -1.0, 0.0, 0.0, 0.0]

[settlement_path]
increment = 0.005
s_max = 0.04
live_at = [0.0, 0.04]
"""


def _write(tmp: Path, text: str, name: str = "study.toml") -> Path:
    path = tmp / name
    path.write_text(text, encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def bridge(tmp_path_factory) -> tuple[xr.Dataset, Path]:
    tmp = tmp_path_factory.mktemp("pier")
    report = run_study(load_study(_write(tmp, BRIDGE)), out=tmp / "results", jobs=1, plots=False)
    return xr.open_dataset(report.results), report.results


def test_live_loads_after_a_settlement(bridge):
    """The adequacy of the vehicle at magnitude 0 is the search on the undeformed bridge;
    after 40 mm of pier settlement it is a different, smaller number, found standing."""
    ds, _ = bridge
    status = ds["settlement_live_status"].values[0]
    assert list(status) == ["optimal", "optimal"]
    lam = ds["settlement_live_lambda"].values[0]
    np.testing.assert_allclose(lam[0], float(ds["critical_lambda"].values[0]), rtol=1e-6)
    assert lam[1] < lam[0] * (1 - 1e-4)  # the settlement changes the answer
    np.testing.assert_allclose(ds["settlement_live_step"].values[0], [0.0, 0.04], atol=1e-12)
    gap = ds["settlement_live_gap"].values[0]
    assert gap[0] == 0.0 and 0.0 < gap[1] < 1e-3 * 20  # within the default contact gap (1e-3 of the size)


def test_show_and_report_state_the_answer(bridge, capsys):
    from tce.report.content import report_content

    ds, path = bridge
    assert main(["show", str(path)]) == 0
    out = capsys.readouterr().out
    lam = ds["settlement_live_lambda"].values[0]
    assert "live loads after a finite settlement" in out
    assert "pier_settles: no_collapse: capacity >= 0.04 (first not standing –)" in out  # stood to s_max
    assert f"s = 0.04 (path step 0.04): optimal: lambda_max {lam[1]:.6g}" in out
    content = report_content(ds, path)
    assert [r["lambda"] for r in content.settlement["live"]] == [f"{v:.6g}" for v in lam]
    assert not any("does not depend on the support motions" in w for w in content.warnings)


def test_the_path_carries_the_fixed_loads():
    """The first state of a path with an off-centroid fixed point load is tce's TCE solve of the
    undeformed arch under the same motion (the load's moment about the block's centroid)."""
    arch = semicircular_arch(inner_radius=0.9, thickness=0.2, voussoirs=12)
    c = arch.centroids[arch.names.index("v04")]
    pattern = LoadPattern(lateral=True, point=[dict(force=(0.0, 0.0, -0.3), block="v04",
                                                      at=(c[0] + 0.05, 0.0, c[2] + 0.05), scaled=False)])
    motion = {"left": [-1.0, 0, 0, 0, 0, 0], "right": [1.0, 0, 0, 0, 0, 0]}
    dead = resolve(fixed_part(pattern), arch)
    path = settlement_path(arch, motion, increment=0.005, s_max=0.01, dead=dead)
    ref = Analysis(arch).solve(lam=0.0, settlements=motion, loads=pattern)
    assert ref.status == "optimal"
    np.testing.assert_allclose(path.wrenches()[0], ref.support_wrenches, rtol=1e-6, atol=1e-7)
    bare = settlement_path(arch, motion, increment=0.005, s_max=0.01)
    assert abs(bare.wrenches()[0][0, 0] - path.wrenches()[0][0, 0]) > 1e-3  # the load matters


def test_deformed_contacts():
    """Every kept contact point lies in the plane of block A's turned face and opens by at
    most the gap; magnitude 0 gives the undeformed contacts."""
    arch = semicircular_arch(inner_radius=0.9, thickness=0.2, voussoirs=12)
    path = settlement_path(arch, {"right": [0.0, 0, -1.0, 0, 0, 0]}, increment=0.01, s_max=0.03)
    same, _, widest = deformed_assembly(arch, path, 0, 1e-9)
    assert widest == 0.0 and len(same.interfaces) == len(arch.interfaces)
    for a, b in zip(arch.interfaces, same.interfaces):
        np.testing.assert_allclose(b.points, a.points, atol=1e-12)
    k = len(path.magnitudes) - 1
    tight, move, _ = deformed_assembly(arch, path, k, 1e-7 * arch.size)
    loose, _, widest = deformed_assembly(arch, path, k, 1.0)
    assert len(loose.interfaces) == len(arch.interfaces) and widest > 1e-4
    hinged = 0
    for itf in tight.interfaces:
        ref = next(r for r in arch.interfaces if (r.a, r.b) == (itf.a, itf.b))
        face = move[itf.a, :3, :3] @ ref.points[0] + move[itf.a, :3, 3]
        np.testing.assert_allclose((itf.points - face) @ itf.normal, 0.0, atol=1e-12)  # one plane
        hinged += not np.allclose(itf.points, ref.points @ move[itf.a, :3, :3].T + move[itf.a, :3, 3], atol=1e-9)
    assert hinged >= 1  # some joint opened: its open points moved to the hinge


DOME = """
[study]
name = "dome"
[structure]
type = "dome"
radius = 5.0
thickness = 0.5
sectors = 8
courses = 4
[loads]
lateral = false
[[loads.point]]
on_top = [0.0, 0.0]
force = [0.0, 0.0, -10.0]
[scenarios.spread]
s01 = [0.923879532511, 0.382683432365, 0, 0, 0, 0]
[settlement_path]
increment = 0.01
s_max = 0.05
live_at = [0.0, 0.02]
"""


@pytest.mark.parametrize("case", ["no live_at", "live_at without live loads", "live_at beyond s_max", "spatial"])
def test_bad_live_at_exit_2(case, tmp_path: Path, capsys):
    text = {
        "no live_at": BRIDGE.replace("live_at = [0.0, 0.04]\n", ""),
        "live_at without live loads": BRIDGE.replace("lateral = false", "lateral = true").replace(
            "[[loads.vehicle]]\nname = \"axle\"\naxles = [[0.0, 100.0]]\nwheels = [-0.9, 0.9]\n", "").replace(
            "critical_position = true\n", ""),
        "live_at beyond s_max": BRIDGE.replace("live_at = [0.0, 0.04]", "live_at = [0.0, 0.05]"),
        # a dome's crown load came out unbounded after 2 cm of spread: spurious tangential forces
        "spatial": DOME,
    }[case]
    study = _write(tmp_path, text)
    out = tmp_path / "results"
    assert main(["run", str(study), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "live_at" in err and "fix:" in err and "Traceback" not in err
    assert not out.exists()


def test_magnitude_sweep_searches_once(tmp_path: Path, monkeypatch, capsys):
    """Scenarios that differ only in their settlement share one critical-position search (the
    direct limit does not depend on support motions), and show says so."""
    calls = []

    def counted(*args, **kwargs):
        calls.append(1)
        return critical_position(*args, **kwargs)

    monkeypatch.setattr(critical, "critical_position", counted)  # positions.search imports it when it runs
    monkeypatch.setattr(positions, "_SEARCHES", {})
    text = BRIDGE.split("[settlement_path]")[0] + "[sweep]\nmagnitude = [0.0, 0.02, 0.05]\n"
    report = run_study(load_study(_write(tmp_path, text)), out=tmp_path / "results", jobs=1, plots=False)
    assert len(calls) == 1
    ds = xr.open_dataset(report.results)
    assert len(set(np.round(ds["critical_lambda"].values, 12))) == 1
    assert main(["show", str(report.results)]) == 0
    assert "lambda_max does not depend on the support motions" in capsys.readouterr().out


def test_fixed_position_and_beyond_the_capacity(tmp_path: Path):
    """A live point load at its declared position (no search): at magnitude 0 the direct limit
    of the undeformed arch; beyond the settlement capacity nothing stands (``not_standing``)."""
    text = """
[study]
name = "arch"

[structure]
type = "semicircular_arch"
inner_radius = 0.9
thickness = 0.2
voussoirs = 12

[loads]
lateral = false

[[loads.point]]
force = [0.0, 0.0, -1.0]
on_top = [-0.4, 0.0]

[scenarios.spread]
left = [-1.0, 0, 0, 0, 0, 0]
right = [1.0, 0, 0, 0, 0, 0]

[settlement_path]
increment = 0.02
s_max = 1.0
live_at = [0.0, 0.9]
"""
    study = load_study(_write(tmp_path, text))
    report = run_study(study, out=tmp_path / "results", jobs=1, plots=False)
    ds = xr.open_dataset(report.results)
    assert str(ds["settlement_outcome"].values[0]) in ("collapse", "snap_through", "contact_lost")
    assert float(ds["settlement_capacity"].values[0]) < 0.9
    assert list(ds["settlement_live_status"].values[0]) == ["optimal", "not_standing"]
    sc = study.scenarios()[0]
    ref = Analysis(study.assembly(sc.structure)).limit(loads=sc.loads_pattern)
    np.testing.assert_allclose(ds["settlement_live_lambda"].values[0, 0], ref.lambda_max, rtol=1e-6)
    assert np.isnan(ds["settlement_live_x"].values[0]).all() and np.isnan(ds["settlement_live_lambda"].values[0, 1])
