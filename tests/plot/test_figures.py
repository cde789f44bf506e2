"""Figures of a results dataset: what is drawn, not only that a file exists.

The datasets are written by the real runner (the paper's arch, in plane with settlements
and out of plane; a running-bond wall), so the figures read exactly what ``tce run``
stores. Independent references: the weight of the arch in closed form (equilibrium of
the forces on the supports), the geometry of the arch (hinge lines across its depth),
and direct TCE solves at the drawn multipliers.
"""

from __future__ import annotations

import logging
import math
import re
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from PIL import Image
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from tce.core.analysis import Analysis
from tce.core.material import Material
from tce.plot import data, draw, figures, output
from tce.plot.output import figure_tasks, write_figures
from tce.structures.arch import semicircular_arch
from tce.structures.dome import hemispherical_dome
from tce.study.runner import run_study
from tce.study.schema import parse_study

ARCH = """
[study]
name = "{name}"
[structure]
type = "semicircular_arch"
[material]
{material}
[loads]
alpha = {alpha}
lambda_step = {step}
tolerance = {tolerance}
{extra}
"""
#: weight of the paper's arch in closed form: 14 voussoirs with plane faces, each a trapezoid between
#: chords of the 1.0 and 1.2 m circles over pi/14: (n/2)(Re^2 - Ri^2) sin(pi/n) m^2 x 0.25 m x 20 kN/m^3
ARCH_WEIGHT = 14 / 2 * (1.2**2 - 1.0**2) * math.sin(math.pi / 14) * 0.25 * 20.0


def run(tmp: Path, name: str, alpha: float = 0.0, material: str = "", extra: str = "", step: float = 0.04,
        tolerance: float = 1e-3) -> xr.Dataset:
    text = ARCH.format(name=name, alpha=alpha, material=material, extra=extra, step=step, tolerance=tolerance)
    study = parse_study(text, tmp / f"{name}.toml")
    report = run_study(study, tmp, jobs=1)
    return xr.load_dataset(report.results)


@pytest.fixture(scope="module")
def planar(tmp_path_factory: pytest.TempPathFactory) -> xr.Dataset:
    """In-plane load paths: no settlement (non-unique), right support outward and inward; Heyman."""
    extra = """
[scenarios.none]
[scenarios.outward]
right = [0.001, 0, 0, 0, 0, 0]
[scenarios.inward]
right = [-0.001, 0, 0, 0, 0, 0]
[plots]
steps = [0.0, 0.1, "max"]
"""
    return run(tmp_path_factory.mktemp("planar"), "planar", extra=extra)


@pytest.fixture(scope="module")
def spatial(tmp_path_factory: pytest.TempPathFactory) -> xr.Dataset:
    """Out-of-plane load paths (alpha = 90): no settlement, right support down and outward."""
    extra = """
[scenarios.none]
[scenarios.downward]
right = [0, 0, -0.001, 0, 0, 0]
[scenarios.outward]
right = [0.001, 0, 0, 0, 0, 0]
[plots]
steps = ["max"]
kinds = ["states", "base", "thrust", "mechanism"]
"""
    return run(tmp_path_factory.mktemp("spatial"), "spatial", alpha=90.0, extra=extra, tolerance=1e-6)


def inside_figure(fig: Figure) -> None:
    """Every legend and text lies inside the figure (nothing clipped), and the legends below
    the panels overlap none of them (nor their tick labels)."""
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    box = fig.bbox
    renderer = canvas.get_renderer()
    for art in [*fig.legends, *fig.texts, *(t for ax in fig.axes for t in ax.texts)]:
        ext = art.get_window_extent(renderer)
        assert ext.x0 >= box.x0 - 1 and ext.x1 <= box.x1 + 1, art
        assert ext.y0 >= box.y0 - 1 and ext.y1 <= box.y1 + 1, art
    bottom = min(ax.get_tightbbox(renderer).y0 for ax in fig.axes if ax.axison or ax.collections or ax.lines)
    for legend in fig.legends:
        assert legend.get_window_extent(renderer).y1 <= bottom + 1, "legend over the panels"


# ---------------------------------------------------------------------------- forces on the supports
def test_forces_on_supports_balance_the_loads(planar: xr.Dataset, spatial: xr.Dataset) -> None:
    """The supports carry the weight (V) and the lateral load lambda W (H in plane, S out of plane)."""
    frame = data.structure_frame(semicircular_arch())
    assert frame.kind == "line"
    for ds, along in ((planar, "H"), (spatial, "S")):
        for s in data.scenarios(ds):
            ok = data.optimal_steps(ds, s)
            f = data.support_forces(ds, s, frame)
            lam = ds.lam.sel(scenario=s).values[ok]
            np.testing.assert_allclose(f["V"][ok].sum(axis=1), ARCH_WEIGHT, rtol=1e-9)
            left, right = list(ds.support.values).index("left"), list(ds.support.values).index("right")
            if along == "H":  # H is outward at each support: right along +x, left along -x
                total = f["H"][ok, right] - f["H"][ok, left]
            else:  # S is along +y at both supports
                total = f["S"][ok].sum(axis=1)
            np.testing.assert_allclose(total, lam * ARCH_WEIGHT, atol=1e-9 * ARCH_WEIGHT)
    # gravity alone: the arch pushes both supports outward
    f = data.support_forces(planar, "none", frame)
    assert np.all(f["H"][0] > 0)


def test_frames_of_arch_dome_wall(tmp_path: Path) -> None:
    dome = data.structure_frame(hemispherical_dome(sectors=8, courses=4))
    assert dome.kind == "radial"
    for s, out in dome.outward.items():  # radial: horizontal, unit, away from the centre
        assert abs(out[2]) < 1e-12 and np.isclose(np.linalg.norm(out), 1.0)
    arch = data.structure_frame(semicircular_arch())
    np.testing.assert_allclose(arch.outward["right"], [1, 0, 0])
    np.testing.assert_allclose(arch.outward["left"], [-1, 0, 0])
    np.testing.assert_allclose(arch.across["left"], [0, 1, 0])


def test_thrust_curves_draw_the_frame_components(planar: xr.Dataset, spatial: xr.Dataset) -> None:
    frame = data.structure_frame(semicircular_arch())
    for ds, comps in ((planar, "HV"), (spatial, "HSVM")):
        fig = figures.thrust_curves(ds)
        axes = fig.axes
        assert len(axes) == len(comps)
        for ax, comp in zip(axes, comps):
            assert ax.get_ylabel().startswith(comp) and "+" in ax.get_ylabel()  # sign explained
            assert ax.yaxis.get_major_formatter().get_useOffset() is False
            drawn = [ln for ln in ax.get_lines() if str(ln.get_gid()).startswith(f"reaction:{comp}:")]
            assert drawn
            for ln in drawn:
                _, _, s, sup = ln.get_gid().split(":")
                ok = data.optimal_steps(ds, s)
                j = list(ds.support.values).index(sup)
                np.testing.assert_allclose(ln.get_xdata(), ds.lam.sel(scenario=s).values[ok])
                np.testing.assert_allclose(ln.get_ydata(), data.support_forces(ds, s, frame)[comp][ok, j])
        inside_figure(fig)


def test_coincident_curves_are_named_together(spatial: xr.Dataset) -> None:
    """Out of plane, V of 'none' and 'outward' coincide (a horizontal motion does not change
    the vertical reactions of the symmetric rocking state): drawn once, named together."""
    fig = figures.thrust_curves(spatial)
    ax_v = fig.axes[2]
    frame = data.structure_frame(semicircular_arch())
    curves = [(s, j) for s in data.scenarios(spatial) for j in range(2)]
    values = {(s, j): data.support_forces(spatial, s, frame)["V"][data.optimal_steps(spatial, s), j] for s, j in curves}
    distinct = []
    for key, v in values.items():
        if not any(len(v) == len(w) and np.allclose(v, w, atol=1e-6 * np.abs(v).max()) for w in distinct):
            distinct.append(v)
    lines = [ln for ln in ax_v.get_lines() if str(ln.get_gid()).startswith("reaction:V:")]
    assert len(lines) == len(distinct) < len(curves)
    assert "coincide" in ax_v.get_title(loc="left")


def test_constant_looks_constant(spatial: xr.Dataset) -> None:
    """A constant vertical force gets a y range of at least 5 % of its value (no 1e-11 zoom)."""
    fig = figures.thrust_curves(spatial, ["none"])
    ax_v = fig.axes[2]
    lo, hi = ax_v.get_ylim()
    assert hi - lo >= 0.05 * ARCH_WEIGHT / 2
    assert not ax_v.yaxis.get_offset_text().get_text()


# ---------------------------------------------------------------------------- states
def test_states_arrows_centred_on_pressure_points(spatial: xr.Dataset) -> None:
    panels = [(s, "max") for s in data.scenarios(spatial)]
    fig = figures.states_figure(spatial, panels)
    (ax,) = fig.axes
    legend = " ".join(t.get_text() for lg in fig.legends for t in lg.get_texts())
    scale = float(legend.split("1 kN = ")[1].split(" m")[0])
    asm = semicircular_arch()
    camera = draw.Camera.for_assembly(asm, across=True)  # spatial scenarios of a long structure
    shafts = [c for c in ax.collections if c.get_gid() == "resultants"]
    points = [ln for ln in ax.get_lines() if ln.get_gid() == "pressure_points"]
    assert len(shafts) == len(points) == len(panels)
    for (s, t), shaft, pts in zip(panels, shafts, points):
        st = data.find_state(spatial, s, t)
        pp = spatial.pressure_point.sel(scenario=s, step=st.step).values
        res = spatial.resultant.sel(scenario=s, step=st.step).values
        seg = np.array(shaft.get_segments())
        mid = seg.mean(axis=1)
        np.testing.assert_allclose(mid, np.column_stack(pts.get_data()), atol=1e-12)
        off = mid[0] - camera.project(pp[0])  # one shift per panel
        np.testing.assert_allclose(mid, camera.project(pp) + off, atol=1e-12)
        np.testing.assert_allclose(seg[:, 1] - seg[:, 0], camera.project(res * scale), atol=1e-12)
    inside_figure(fig)


def test_non_unique_and_outcome_notes(planar: xr.Dataset, tmp_path: Path) -> None:
    """The rigid scene without support motion is flagged non-unique below its limit; the
    settled ones are decided (issue 21: they were NaN), and noted when not unique."""
    ok = data.optimal_steps(planar, "none")
    lam = planar.lam.sel(scenario="none").values[ok]
    assert np.all(planar.unique.sel(scenario="none").values[ok][lam < 0.9 * lam.max()] == 0.0)
    u = planar.unique.sel(scenario="outward").values[data.optimal_steps(planar, "outward")]
    assert u.size and np.all(np.isin(u, [0.0, 1.0]))
    fig = figures.states_figure(planar, [("none", 0.0), ("outward", 0.0)])
    titles = [t.get_text() for t in fig.axes[0].texts if t.get_text().startswith(("none", "outward"))]
    assert "not unique" in titles[0]
    assert ("not unique" in titles[1]) == (float(planar.unique.sel(scenario="outward", step=0)) == 0.0)
    # a state above the limit is said to have no admissible state, nothing is drawn for it
    st = data.find_state(planar, "outward", 5.0)
    assert st.step is None and "no admissible state" in st.note


def test_unique_with_compliance(tmp_path: Path) -> None:
    ds = run(tmp_path, "compliant", material="friction = 0.8\nnormal_stiffness = 1e6", extra="[scenarios.none]")
    ok = data.optimal_steps(ds, "none")
    assert np.all(ds.unique.sel(scenario="none").values[ok] == 1.0)


def test_drawn_state_is_solved_not_interpolated(planar: xr.Dataset) -> None:
    """lambda = 0.1 is not a step of the path (step 0.04): the runner solved it; it equals a
    direct solve, and the figures read it."""
    st = data.find_state(planar, "outward", 0.1)
    assert st.step is not None and math.isclose(st.lam, 0.1)
    direct = Analysis(semicircular_arch(), Material()).solve(0.1, 0.0, {"right": [0.001, 0, 0, 0, 0, 0]})
    stored = planar.reaction.sel(scenario="outward", step=st.step).values
    np.testing.assert_allclose(stored, direct.support_wrenches, atol=1e-8 * ARCH_WEIGHT)


def test_plot_solves_missing_states_on_demand(planar: xr.Dataset, tmp_path: Path) -> None:
    from tce.plot.states import missing_states, solve_states

    todo = missing_states(planar, ["inward"], [0.13, 0.1, 7.0])
    assert todo == {"inward": [0.13]}  # 0.1 is stored, 7 is above the limit
    ds = solve_states(planar, todo)
    st = data.find_state(ds, "inward", 0.13)
    direct = Analysis(semicircular_arch(), Material()).solve(0.13, 0.0, {"right": [-0.001, 0, 0, 0, 0, 0]})
    np.testing.assert_allclose(ds.pressure_point.sel(scenario="inward", step=st.step).values[1:-1],
                               direct.pressure_points[1:-1], atol=1e-9)
    for s in data.scenarios(ds):  # steps stay sorted by lambda in every scenario
        lam = ds.lam.sel(scenario=s).values
        lam = lam[np.isfinite(lam)]
        assert np.all(np.diff(lam) > 0)
    assert ds.sizes["step"] == planar.sizes["step"] + 1


def test_thrust_line_only_for_a_line_of_blocks(planar: xr.Dataset) -> None:
    arch = semicircular_arch()
    chain = data.chain_interfaces(arch)
    assert chain is not None and len(chain) == len(arch.interfaces)
    # consecutive interfaces of the chain share a block
    for a, b in zip(chain, chain[1:]):
        ia, ib = arch.interfaces[a], arch.interfaces[b]
        assert {ia.a, ia.b} & {ib.a, ib.b}
    assert data.chain_interfaces(hemispherical_dome(sectors=6, courses=3)) is None
    fig = figures.thrust_lines(planar, data.scenarios(planar), [0.0, "max"])
    (ax,) = fig.axes
    names = data.scenarios(planar)
    counts = [len([ln for ln in ax.get_lines() if ln.get_gid() == f"thrust_line:{s}"]) for s in names]
    # one line per scenario and state, coincident ones drawn once under the first scenario's
    # name: at lambda_max the states are the one collapse state (canonical states, issue 21)
    assert counts[0] == 2 and all(c >= 1 for c in counts[1:])
    inside_figure(fig)


def test_dome_views_are_thinned(tmp_path: Path) -> None:
    text = """
[study]
name = "dome"
[structure]
type = "dome"
sectors = 8
courses = 6
thickness = 0.5
[material]
friction = 0.8
[loads]
lambda_step = 0.2
tolerance = 1e-2
[scenarios.none]
[plots]
steps = ["max"]
"""
    report = run_study(parse_study(text, tmp_path / "d.toml"), tmp_path, jobs=1)
    ds = xr.load_dataset(report.results)
    fig = figures.states_figure(ds, [("none", "max")])
    (ax,) = fig.axes
    (shafts,) = [c for c in ax.collections if c.get_gid() == "resultants"]
    st = data.find_state(ds, "none", "max")
    res = ds.resultant.sel(scenario="none", step=st.step).values
    mag = np.linalg.norm(res, axis=1)
    assert np.isfinite(mag).sum() > figures.MAX_ARROWS == len(shafts.get_segments())
    # the largest are the ones drawn: the smallest drawn is not smaller than the largest left out
    lengths = np.linalg.norm(np.diff(np.array(shafts.get_segments()), axis=1)[:, 0], axis=1)
    assert len(lengths) == figures.MAX_ARROWS
    kept = np.sort(mag[np.isfinite(mag)])[::-1]
    assert kept[figures.MAX_ARROWS - 1] >= kept[figures.MAX_ARROWS]
    # hinge lines, grouped in one collection of segments inside their interfaces
    segs = data.hinge_segments(ds, "none", data.assembly(ds))
    assert len(segs) > 0
    assert [c for c in ax.collections if c.get_gid() == "hinges"]
    assert "thrust_lines" not in {t.kind for t in figure_tasks(ds, data.plot_spec(ds))}


def test_hinge_lines_cross_the_arch(planar: xr.Dataset) -> None:
    """In plane, the arch hinges about lines across its depth (along y, 0.25 m long)."""
    segs = data.hinge_segments(planar, "outward", semicircular_arch())
    assert len(segs) == 4  # the four-hinge mechanism
    d = segs[:, 1] - segs[:, 0]
    np.testing.assert_allclose(np.abs(d[:, 1]), 0.25, rtol=1e-9)
    np.testing.assert_allclose(d[:, [0, 2]], 0.0, atol=1e-12)


def test_one_mechanism_for_all_settlements(planar: xr.Dataset) -> None:
    groups = data.mechanism_groups(planar, data.scenarios(planar))
    assert groups == [data.scenarios(planar)]  # the limit analysis does not see settlements


def test_base_figure(spatial: xr.Dataset) -> None:
    names = data.scenarios(spatial)
    fig = figures.base_figure(spatial, names, ["max"])
    assert len([ax for ax in fig.axes if ax.axison]) == 2  # left|v01 and v14|right
    ax = fig.axes[0]
    for s in names:
        (pt,) = [ln for ln in ax.get_lines() if ln.get_gid() == f"base:left|v01:{s}"]
        st = data.find_state(spatial, s, "max")
        p = spatial.pressure_point.sel(scenario=s, step=st.step, interface="left|v01").values
        np.testing.assert_allclose(np.column_stack(pt.get_data())[0], p[:2])
        # on the edge y = d/2 about which the arch rocks (lambda_max within 1e-6 of the limit)
        assert math.isclose(p[1], 0.125, abs_tol=1e-5)
    inside_figure(fig)


# ---------------------------------------------------------------------------- sweeps and files
@pytest.fixture(scope="module")
def sweep(tmp_path_factory: pytest.TempPathFactory) -> xr.Dataset:
    """15 scenarios: more than the per-scenario figures draw by default."""
    extra = """
[sweep]
friction = [0.4, 0.8, 1.6]
magnitude = [0.5, 1.0, 2.0]
[scenarios.none]
[scenarios.outward]
right = [0.001, 0, 0, 0, 0, 0]
[scenarios.transversal]
right = [0, 0.001, 0, 0, 0, 0]
"""
    return run(tmp_path_factory.mktemp("sweep"), "sweep", material="friction = 0.8", extra=extra, step=0.1,
               tolerance=1e-2)


def test_large_sweep_draws_summaries_only(sweep: xr.Dataset, tmp_path: Path) -> None:
    assert sweep.sizes["scenario"] == 27 > 12
    spec = data.plot_spec(sweep)
    assert spec.scenarios == ()
    files = write_figures(sweep, tmp_path)
    assert [f.name for f in files] == ["summary.png"]
    fig = figures.summary_figure(sweep)
    # lambda_max does not depend on the settlement cases without an out-of-plane motion, nor on the
    # magnitude: the cases with equal answers share a row, the magnitudes one line
    rows = {ax.get_title(loc="left") for ax in fig.axes}
    assert any("none" in r and "outward" in r for r in rows)
    for ax in fig.axes:
        if ax.get_xlabel().startswith("friction"):
            lines = [ln for ln in ax.get_lines() if str(ln.get_gid()).startswith("summary:")]
            assert len(lines) == 1 and "identical" in lines[0].get_label()
    inside_figure(fig)


def test_sweep_colours_by_parameter_and_styles_by_case(sweep: xr.Dataset) -> None:
    names = [s for s in data.scenarios(sweep) if s.endswith("magnitude=1")]
    cases = list(dict.fromkeys(str(sweep.settlement.sel(scenario=n).values) for n in names))
    fig = figures.thrust_curves(sweep, names)
    for ax in fig.axes:
        for ln in ax.get_lines():
            if not str(ln.get_gid()).startswith("reaction:"):
                continue
            s = ln.get_gid().split(":")[2]
            mu = float(sweep.friction.sel(scenario=s))
            case = str(sweep.settlement.sel(scenario=s).values)
            assert ln.get_color() == figures.COLOURS[[0.4, 0.8, 1.6].index(mu)]
            assert ln.get_linestyle() == Line2D([], [], linestyle=figures.LINESTYLES[cases.index(case)]).get_linestyle()
    inside_figure(fig)


def test_write_figures_each_once(planar: xr.Dataset, tmp_path: Path) -> None:
    files = write_figures(planar, tmp_path)
    names = [f.name for f in files]
    assert names == ["thrust.png", "states.png", "thrust_lines.png", "mechanism.png", "view.html"]
    assert all(f.stat().st_size > 1000 for f in files)
    assert not list(tmp_path.glob(".*.tmp"))
    with Image.open(files[0]) as image:  # matplotlib's PNG at the figures' resolution
        assert image.format == "PNG" and image.info["dpi"] == pytest.approx((output.DPI, output.DPI), abs=0.01)


@pytest.mark.parametrize("jobs", [1, 2])
def test_drawing_reports_progress_file_by_file(planar: xr.Dataset, tmp_path: Path, jobs: int,
                                               monkeypatch: pytest.MonkeyPatch, caplog: pytest.LogCaptureFixture) -> None:
    """Drawing says which file is under way and how many are done, drawn in-process or by
    workers (``PARALLEL_AT`` lowered so that these five files go to two workers)."""
    from tce.plot import output

    monkeypatch.setattr(output, "PARALLEL_AT", 2)
    with caplog.at_level(logging.INFO, logger="tce"):
        files = write_figures(planar, tmp_path, jobs=jobs)
    assert [f.name for f in files] == ["thrust.png", "states.png", "thrust_lines.png", "mechanism.png", "view.html"]
    lines = [r.getMessage() for r in caplog.records if r.name == "tce.study.progress"]
    assert any(re.match(r"figures: 5/5 files \(view\.html\), \d+ s", m) for m in lines), lines
    assert (jobs == 2) == any("drawing 5 files on 2 workers" in r.getMessage() for r in caplog.records)


def test_each_file_drawn_from_what_a_worker_receives_is_the_same(sweep: xr.Dataset, tmp_path: Path) -> None:
    """A worker of ``tce plot --jobs`` receives only the part of the results a file reads
    (``output._subset``): every file drawn from it is the same, byte for byte, as drawn from
    the whole dataset (a mechanism's title once said "every scenario drawn" for a group that
    was all of its part only)."""
    names = [str(s) for s in sweep["scenario"].values]
    spec = data.plot_spec(sweep, scenarios_=[names[0], names[1], names[-1]],
                          kinds=["states", "thrust", "mechanism", "view", "summary"])
    tasks = figure_tasks(sweep, spec)
    assert {t.kind for t in tasks} == {"states", "thrust", "mechanism", "view", "summary"}
    for folder in ("whole", "part"):
        (tmp_path / folder).mkdir()
    for t in tasks:
        whole = output.render(sweep, t, tmp_path / "whole")
        part = output.render(output._subset(sweep, t), t, tmp_path / "part")
        assert whole.read_bytes() == part.read_bytes(), t.name


def _failing_open(monkeypatch: pytest.MonkeyPatch, fault: BaseException) -> None:
    """Figure files stop with ``fault`` once part of them is written (a disk that fills, Ctrl-C)."""
    class Failing:
        def __init__(self, path, mode):
            self.fh = open(path, mode)

        def __enter__(self):
            return self

        def __exit__(self, *exc):
            self.fh.close()

        def write(self, data):
            self.fh.write(bytes(data)[:10])
            raise fault

    monkeypatch.setattr(output, "open", Failing, raising=False)


@pytest.mark.parametrize("fault", [OSError(28, "No space left on device"), KeyboardInterrupt()])
def test_a_figure_cut_short_leaves_no_file(planar: xr.Dataset, tmp_path: Path, monkeypatch, fault) -> None:
    """Each figure is written atomically (a temporary name, then renamed): a write that fails or
    is interrupted leaves neither the file nor its temporary; a failure names the file."""
    (task,) = [t for t in figure_tasks(planar, data.plot_spec(planar)) if t.kind == "thrust"]
    _failing_open(monkeypatch, fault)
    with pytest.raises(type(fault)) as raised:
        output.render(planar, task, tmp_path)
    if isinstance(fault, OSError):
        assert raised.value.filename == str(tmp_path / "thrust.png") and raised.value.errno == 28
    assert list(tmp_path.iterdir()) == []
