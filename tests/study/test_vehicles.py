"""Vehicles and the critical-position search in study files: [[loads.vehicle]],
[loads] critical_position and positions, the dataset's critical_* and scan variables,
`tce show`, the capacity figure; bad declarations exit 2 naming their key, nothing written."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from tce.analysis.critical import critical_position
from tce.core.analysis import Analysis
from tce.core.loads import LoadPattern
from tce.structures.arch import segmental_arch, semicircular_arch
from tce.cli import main
from tce.study.schema import parse_study

ROOT = Path(__file__).resolve().parents[2]

STUDY = """
[study]
name = "vehicle"

[structure]
type = "semicircular_arch"

[loads]
lateral = false
critical_position = true            # search the vehicle's reference x for the lowest lambda_max
lambda_step = 0.25
tolerance = 1e-6
lambda_cap = 5.0

[[loads.vehicle]]
axles = [[0.0, 1.0], [0.4, 1.0]]    # [offset x from the vehicle's reference (m), axle load (kN)]

[scenarios.none]
"""


def write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "study.toml"
    path.write_text(text, encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def run(tmp_path_factory) -> tuple[Path, xr.Dataset]:
    tmp = tmp_path_factory.mktemp("vehicle")
    assert main(["run", str(write(tmp, STUDY)), "--out", str(tmp / "out"), "--jobs", "1", "--no-plots"]) == 0
    path = tmp / "out" / "vehicle" / "results.nc"
    return path, xr.load_dataset(path)


def test_issue_form_runs_at_the_critical_position(run) -> None:
    _, ds = run
    an = Analysis(parse_study(STUDY).assembly(parse_study(STUDY).scenarios()[0].structure))
    direct = critical_position(an, LoadPattern(lateral=False, vehicle=[dict(axles=[[0.0, 1.0], [0.4, 1.0]])]))
    assert float(ds["critical_x"].values[0]) == direct.critical_x
    assert float(ds["lambda_max"].values[0]) == pytest.approx(direct.lambda_max, abs=1e-6)
    assert str(ds["outcome"].values[0]) == "limit" and str(ds["critical_status"].values[0]) == "optimal"
    # the load path ran with the vehicle at the critical position: both axles, 0.4 m apart
    p = ds["load_point"].values[0]
    assert p[:, 0] == pytest.approx([direct.critical_x, direct.critical_x + 0.4])
    assert str(ds["load_notes"].values[0]) == ""
    assert ds["critical_ties"].values[0] != ""  # the mirror image of the vehicle
    assert ds.sizes["scan"] == direct.n_solves and ds["scan_x"].attrs["units"] == "m"


def test_show_states_the_critical_position_and_the_tie(run, capsys) -> None:
    path, ds = run
    assert main(["show", str(path)]) == 0
    out = capsys.readouterr().out
    assert f"none: x = {float(ds['critical_x'].values[0]):.6g} m" in out and "tied (same lambda_max) at x = " in out


def test_capacity_figure_marks_the_minimum_clear_of_the_data(run) -> None:
    from tce.plot.capacity import influence_line

    _, ds = run
    fig = influence_line(ds)
    ax = fig.axes[0]
    lines = {ln.get_gid(): ln for ln in ax.get_lines()}
    crit = lines["critical:none"]
    assert crit.get_xdata()[0] == float(ds["critical_x"].values[0])
    assert crit.get_ydata()[0] == pytest.approx(np.nanmin(np.where(np.isinf(ds["scan_lambda"].values), np.nan,
                                                                    ds["scan_lambda"].values)))
    assert "tie:none" in lines
    # the annotation is a figure text right of the axes: it covers no data
    fig.canvas.draw() if hasattr(fig.canvas, "draw") else None
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    renderer = FigureCanvasAgg(fig).get_renderer()
    (box,) = [t for t in fig.texts if t.get_text().startswith("critical position")]
    assert box.get_window_extent(renderer).x0 > ax.get_window_extent(renderer).x1


def test_same_critical_load_whatever_grid_on_the_6m_bridge() -> None:
    # issue 22: span 6, rise 1.5, ring 0.4, fixed 10 kN/m^2 fill, one two-wheel axle; a 0.2 m
    # and a 0.05 m load_x grid gave 168.4 and 158.4 kN per wheel
    an = Analysis(segmental_arch(span=6.0, rise=1.5, thickness=0.4, depth=3.0, voussoirs=12))
    pattern = LoadPattern(lateral=False, distributed=[dict(x=[-3.5, 3.5], pressure=10.0, scaled=False)],
                          vehicle=[dict(axles=[[0.0, 2.0]], wheels=[-0.9, 0.9])])
    found = [critical_position(an, pattern, start=grid) for grid in
             (None, np.arange(-2.8, 0.01, 0.2), np.arange(-2.8, 2.81, 0.05), [1.3])]
    lam = [r.lambda_max for r in found]
    assert max(lam) - min(lam) <= 1e-9 * min(lam)
    # the grids alone: what the sweep would have reported is higher (unconservative)
    grid = [an.limit(loads=pattern.moved(x)).lambda_max for x in np.arange(-2.8, 0.01, 0.2)]
    assert min(grid) > min(lam) * (1 + 1e-3)
    assert abs(found[0].critical_x) == pytest.approx(abs(found[0].ties[0]), abs=1e-6)  # the mirror tie


def test_study_files_of_the_repository_parse() -> None:
    for name in ("arch_vehicle.toml", "bridge_axle.toml", "bridge_fill.toml"):
        study = parse_study((ROOT / "studies" / name).read_text(), ROOT / "studies" / name)
        assert all(sc.loads["critical_position"] for sc in study.scenarios())
    fill = parse_study((ROOT / "studies" / "bridge_fill.toml").read_text()).scenarios()[0].loads_pattern.fill
    assert (fill.depth, fill.unit_weight, fill.k0, fill.weight) == (0.3, 18.0, 0.5, True)
    assert fill.dispersion == pytest.approx(26.565051177)


def test_standard_vehicle_and_load_x_sweep_move_the_vehicle(tmp_path) -> None:
    text = STUDY.replace("critical_position = true", "").replace(
        "axles = [[0.0, 1.0], [0.4, 1.0]]", 'standard = "en1991_lm1_tandem_lane1"\nwheels = [0.0]\npatch = [0.1, 0.1]'
    ) + "[sweep]\nload_x = [-0.5, 0.1]\n"
    scen = parse_study(text).scenarios()
    v = [sc.loads_pattern.vehicle[0] for sc in scen]
    assert [x.x for x in v] == [-0.5, 0.1] and v[0].axles == ((0.0, 300.0), (1.2, 300.0)) and v[0].wheels == (0.0,)


def test_notes_of_wheels_off_the_deck_are_shown(tmp_path, capsys) -> None:
    text = STUDY.replace("critical_position = true", "").replace("[0.4, 1.0]]", "[0.4, 1.0]]\nx = 0.9")
    path = write(tmp_path, text)
    assert main(["run", str(path), "--out", str(tmp_path / "out"), "--jobs", "1", "--no-plots"]) == 0
    capsys.readouterr()
    assert main(["show", str(tmp_path / "out" / "vehicle" / "results.nc")]) == 0
    out = capsys.readouterr().out
    assert "none: note: vehicle[0] (vehicle) at x = 0.9 m: 1 of 2 wheels dropped in whole or part: " \
           "axle 2 wheel 1 (x = 1.3 m, y = 0 m) off the deck" in out


@pytest.mark.parametrize(
    "edit, key",
    [
        (("critical_position = true", "critical_position = true\npositions = [0.0, 5.0]"), "loads.positions[1]"),
        (("critical_position = true", "positions = [0.0]"), "loads.positions"),
        (("[scenarios.none]", "[sweep]\nload_x = [0.0, 0.1]\n[scenarios.none]"), "loads.critical_position"),
        (("axles = [[0.0, 1.0], [0.4, 1.0]]", 'axles = [[0.0, 1.0]]\nstandard = "en1991_lm2_axle"'), "loads.vehicle[0]"),
        (("axles = [[0.0, 1.0], [0.4, 1.0]]", 'standard = "lm9"'), "loads.vehicle[0].standard"),
        (("axles = [[0.0, 1.0], [0.4, 1.0]]", "axles = [[0.0, 1.0], [0.0, 1.0]]"), "loads.vehicle[0].axles"),
        (("axles = [[0.0, 1.0], [0.4, 1.0]]", "axles = [[0.0, -1.0]]"), "loads.vehicle[0].axles[0]"),
        (("axles = [[0.0, 1.0], [0.4, 1.0]]", "axles = [[0.0, 1.0]]\nwheel = [0.0]"), "loads.vehicle[0].wheel"),
        (("[scenarios.none]", "[loads.fill]\ndepth = 0.3\n[scenarios.none]"), "loads.fill.unit_weight"),
        (("[scenarios.none]", "[loads.fill]\ndepth = 0.3\nunit_weight = 18.0\nk0 = 1.0\n[scenarios.none]"),
         "loads.fill.k0"),
        # passive coefficient: 0 (off) or >= 1 (tce.core.fill)
        (("[scenarios.none]", "[loads.fill]\ndepth = 0.3\nunit_weight = 18.0\nkp = 0.5\n[scenarios.none]"),
         "loads.fill.kp"),
        # issue 37 item 2: no wheel on the deck at any position searched (wheels 6 m apart, or in mm)
        (("axles = [[0.0, 1.0], [0.4, 1.0]]", "axles = [[0.0, 1.0]]\nwheels = [-3.0, 3.0]"), "loads.vehicle[0]"),
        (("axles = [[0.0, 1.0], [0.4, 1.0]]", "axles = [[0.0, 1.0]]\nwheels = [-1000.0, 1000.0]"), "loads.vehicle[0]"),
        # ... or at the declared position, without a search
        (("critical_position = true", "x = 0.0"), None),
        # issue 37 item 3: a dead factor above 1 would raise the adequacy factor
        (("[scenarios.none]", "[assessment]\ndead_factor = 1.35\n[scenarios.none]"), "assessment.dead_factor"),
    ],
)
def test_bad_declarations_exit_2_naming_the_key(tmp_path, capsys, edit, key) -> None:
    if key is None:  # the vehicle 9 m from the arch's crown, no search
        edit, key = ("critical_position = true", ""), "loads.vehicle[0]"
        text = STUDY.replace(*edit).replace("[0.4, 1.0]]", "[0.4, 1.0]]\nx = 9.0")
    else:
        text = STUDY.replace(*edit)
    assert text != STUDY
    path = write(tmp_path, text)
    code = main(["run", str(path), "--out", str(tmp_path / "out"), "--jobs", "1", "--no-plots"])
    err = capsys.readouterr().err
    assert code == 2 and f"{path}: {key}" in err and "fix:" in err
    assert not (tmp_path / "out").exists()


def test_a_vehicle_alone_is_what_lambda_multiplies(tmp_path, capsys) -> None:
    """Issue 37 item 1 (fails on main: without ``lateral = false`` lambda also multiplied a
    horizontal load of every block's weight, and nothing said so). The lateral pattern joins
    the vehicle only when asked for, and ``tce show`` says what lambda multiplies."""
    text = STUDY.replace("lateral = false\n", "")
    assert text != STUDY
    sc = parse_study(text).scenarios()[0]
    assert sc.loads_pattern.lateral is False
    both = parse_study(text.replace("[loads]\n", "[loads]\nlateral = true\n")).scenarios()[0].loads_pattern
    assert both.lateral is True
    an = Analysis(parse_study(text).assembly(sc.structure))
    alone = critical_position(an, LoadPattern(lateral=False, vehicle=[dict(axles=[[0.0, 1.0], [0.4, 1.0]])]))
    path = write(tmp_path, text)
    assert main(["run", str(path), "--out", str(tmp_path / "out"), "--jobs", "1", "--no-plots"]) == 0
    ds = xr.load_dataset(tmp_path / "out" / "vehicle" / "results.nc")
    assert float(ds["critical_lambda"].values[0]) == pytest.approx(alone.lambda_max, rel=1e-9)
    assert str(ds["lambda_multiplies"].values[0]) == "lambda multiplies vehicle 'vehicle' (2 kN); fixed: self-weight"
    capsys.readouterr()
    assert main(["show", str(tmp_path / "out" / "vehicle" / "results.nc")]) == 0
    out = capsys.readouterr().out
    assert "loads: lambda multiplies vehicle 'vehicle' (2 kN); fixed: self-weight" in out and "lateral" not in out
    assert "and the lateral load lambda*W (every block's weight, horizontal) in direction alpha = 0 degrees" in both.multiplies


def test_a_vehicle_off_the_deck_is_an_error_not_unbounded() -> None:
    """Issue 37 item 2 (fails on main: LimitResult('unbounded', lambda_max=inf) and a note)."""
    an = Analysis(segmental_arch())
    far = LoadPattern(vehicle=[dict(axles=[[0.0, 1.0]], x=9.0)])
    with pytest.raises(ValueError, match=r"vehicle\[0\]: no wheel .* lands on the deck, which spans x = "):
        an.limit(loads=far)
    with pytest.raises(ValueError, match="at any position searched"):
        critical_position(an, LoadPattern(vehicle=[dict(axles=[[0.0, 1.0]], wheels=[-5.0, 5.0])]))


def test_the_search_drops_a_moving_vehicle_where_it_is_off_the_deck() -> None:
    """Two vehicles 3 m apart on a 2.4 m arch: never both on the deck. Where one is off, the
    other alone is the live load; the search's least value is that of one vehicle alone."""
    an = Analysis(semicircular_arch())
    two = LoadPattern(vehicle=[dict(axles=[[0.0, 1.0]], name="a"), dict(axles=[[0.0, 1.0]], x=3.0, name="b")])
    one = critical_position(an, LoadPattern(vehicle=[dict(axles=[[0.0, 1.0]])]))
    both = critical_position(an, two)
    assert both.ok and both.lambda_max == pytest.approx(one.lambda_max, rel=1e-6)
    assert len(both.pattern.vehicle) == 1  # the vehicle off the deck there is not part of the pattern
    assert an.limit(loads=both.pattern).lambda_max == pytest.approx(both.lambda_max, rel=1e-9)


# ---------------------------------------------------------------------------- assessment
def test_adequacy_factor_scales_as_the_cone_says() -> None:
    from tce.analysis.assessment import adequacy_factor

    an = Analysis(segmental_arch(span=6.0, rise=1.5, thickness=0.4, depth=3.0, voussoirs=12))
    p = LoadPattern(lateral=False, distributed=[dict(x=[-3.5, 3.5], pressure=10.0, scaled=False)],
                    vehicle=[dict(axles=[[0.0, 2.0]], wheels=[-0.9, 0.9], x=-1.5)])
    lam = an.limit(loads=p).lambda_max
    for gd, gl in ((1.0, 1.0), (1.0, 1.5), (0.9, 2.0)):
        assert adequacy_factor(an, p, gd, gl).lambda_max == pytest.approx(lam * gd / gl, rel=1e-7)
    with pytest.raises(ValueError, match="live_factor"):
        adequacy_factor(an, p, 1.0, 0.0)


def test_a_dead_factor_above_one_is_refused_citing_the_code() -> None:
    """Issue 37 item 3 (fails on main: 1.35 on the favourable dead load raised the adequacy
    factor by 35 %)."""
    from tce.analysis.assessment import adequacy_factor

    an = Analysis(segmental_arch())
    p = LoadPattern(vehicle=[dict(axles=[[0.0, 1.0]])])
    with pytest.raises(ValueError, match=r"favourable .* gamma_G,inf = 1\.00 \(EN 1990:2002, Table A2\.4\(B\)\)"):
        adequacy_factor(an, p, 1.35, 1.5)


def test_assessment_study_reads_as_an_assessment(tmp_path, capsys) -> None:
    text = STUDY + "\n[assessment]\ndead_factor = 0.9\nlive_factor = 1.5\n"
    path = write(tmp_path, text.replace('name = "vehicle"', 'name = "assessed"'))
    assert main(["run", str(path), "--out", str(tmp_path / "out"), "--jobs", "1", "--no-plots"]) == 0
    ds = xr.load_dataset(tmp_path / "out" / "assessed" / "results.nc")
    lam = float(ds["critical_lambda"].values[0])
    assert float(ds["adequacy_factor"].values[0]) == pytest.approx(lam * 0.9 / 1.5, rel=1e-7)
    capsys.readouterr()
    assert main(["show", str(tmp_path / "out" / "assessed" / "results.nc")]) == 0
    out = capsys.readouterr().out
    assert "assessment (adequacy factor" in out and "partial factors dead 0.9, live 1.5" in out
    assert f"adequacy factor {lam * 0.9 / 1.5:.4g}: NOT adequate" in out and "vehicle (2 kN)" in out


def test_bad_partial_factor_exits_2(tmp_path, capsys) -> None:
    path = write(tmp_path, STUDY + "\n[assessment]\ndead_factor = 0.0\n")
    assert main(["run", str(path), "--out", str(tmp_path / "out"), "--no-plots"]) == 2
    assert f"{path}: assessment.dead_factor" in capsys.readouterr().err and not (tmp_path / "out").exists()


def test_search_in_workers_and_resumed_gives_the_same_dataset(run, tmp_path) -> None:
    _, ds = run
    path = write(tmp_path, STUDY)
    for _ in range(2):  # solved by two workers, then reused
        assert main(["run", str(path), "--out", str(tmp_path / "out"), "--jobs", "2", "--no-plots"]) == 0
        other = xr.load_dataset(tmp_path / "out" / "vehicle" / "results.nc")
        for name in ("critical_x", "critical_lambda", "lambda_max", "scan_x", "scan_lambda"):
            np.testing.assert_array_equal(other[name].values, ds[name].values)


def test_capacity_figure_has_no_empty_legend_band(run) -> None:
    """capacity.png kept a band of 22 % of its height under the axes for a legend of one or
    two rows, mostly white (seen on arch_vehicle and arch_point_load). The legend now stands
    in the right-hand column under the critical positions, the axes reach down to 12 %, and
    nothing overlaps or leaves the figure."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from tce.plot.capacity import influence_line

    _, ds = run
    fig = influence_line(ds)
    ax = fig.axes[0]
    renderer = FigureCanvasAgg(fig).get_renderer()
    (box,) = [t for t in fig.texts if t.get_text().startswith("critical position")]
    (legend,) = fig.legends
    to_fig = fig.transFigure.inverted().transform
    a, b, g = (to_fig(x.get_window_extent(renderer)) for x in (ax, box, legend))
    assert a[0, 1] <= 0.15  # the axes' bottom edge: no band below them
    assert g[0, 0] > a[1, 0] and g[1, 1] < b[0, 1]  # right of the axes, under the box
    assert g[0, 1] >= 0.0 and g[1, 0] <= 1.0  # within the figure


def test_boussinesq_on_a_dome_exits_2_naming_the_key(tmp_path, capsys) -> None:
    # Boussinesq's closed forms need plan rectangles; a dome's top faces are not
    text = ('[study]\nname = "dome_bq"\n[structure]\ntype = "dome"\n[loads]\nlateral = false\n'
            '[loads.fill]\ndepth = 0.3\nunit_weight = 18.0\ndispersion = "boussinesq"\n'
            '[[loads.vehicle]]\naxles = [[0.3, 1.0]]\n[scenarios.none]\n')
    path = write(tmp_path, text)
    code = main(["run", str(path), "--out", str(tmp_path / "out"), "--jobs", "1", "--no-plots"])
    err = capsys.readouterr().err
    assert code == 2 and f"{path}: loads.fill.dispersion" in err and "not a rectangle in plan" in err
    assert not (tmp_path / "out").exists()
