"""Figures of a results dataset: what is drawn, not only that a file exists.

The datasets come from the real solver (the paper's arch, in plane with settlements and
out of plane), assembled here following docs/results.md.
"""

from __future__ import annotations

import json
from collections.abc import Mapping

import numpy as np
import pytest
import xarray as xr
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from tce.plot import figures as plot
from tce.analysis import Analysis
from tce.structures.arch import semicircular_arch
from tce.structures.assembly import Assembly
from tce.analysis.loadpath import LoadPathResult, load_path
from tce.core.material import Material
from tce.core.resultants import global_vertex_forces

COMPONENTS = ["Fx", "Fy", "Fz", "Mx", "My", "Mz"]


def dataset_from_load_paths(assembly: Assembly, runs: Mapping[str, LoadPathResult]) -> xr.Dataset:
    """A results dataset (docs/results.md, the variables the plots read) from load paths.

    Parameters
    ----------
    assembly : Assembly
    runs : mapping of scenario name to LoadPathResult

    Returns
    -------
    xarray.Dataset
        Also holds the optional ``vertex_force`` / ``vertex_point`` variables.
    """
    names = list(runs)
    asm = assembly
    nstep = max(len(r.path) for r in runs.values())
    ni, nb, ns = len(asm.interfaces), len(asm.blocks), len(asm.support_names)
    first = next(r for lp in runs.values() for r in lp.path if r.ok)
    nv = len(first.interface_map.vertex_points)

    def full(*shape: int) -> np.ndarray:
        return np.full(shape, np.nan)

    lam, status = full(len(names), nstep), np.full((len(names), nstep), "", dtype=object)
    reaction, tce = full(len(names), nstep, ns, 6), full(len(names), nstep)
    res, pp, torque = full(len(names), nstep, ni, 3), full(len(names), nstep, ni, 3), full(len(names), nstep, ni)
    vforce = full(len(names), nstep, nv, 3)
    mech, hinge = full(len(names), nb, 6), full(len(names), ni, 3)
    mode = np.full((len(names), ni), "", dtype=object)
    model = np.full(len(names), "", dtype=object)
    for s, lp in enumerate(runs.values()):
        for k, r in enumerate(lp.path):
            lam[s, k], status[s, k] = r.lam, r.status
            model[s] = r.model
            if not r.ok:
                continue
            slots = list(r.interfaces)
            reaction[s, k], tce[s, k] = r.support_wrenches, r.tce
            res[s, k, slots], pp[s, k, slots], torque[s, k, slots] = r.resultants, r.pressure_points, r.torques
            vforce[s, k] = global_vertex_forces(r.interface_map, r.vertex_forces)
        m = lp.limit.mechanism
        if m is not None:
            mech[s] = m.velocities
            slots = list(r.interfaces)
            mode[s, slots], hinge[s, slots] = m.modes, m.hinge_points
    sc, st, itf = ("scenario",), ("scenario", "step"), ("scenario", "step", "interface")

    def var(dims: tuple, data: np.ndarray, units: str, long_name: str) -> xr.Variable:
        return xr.Variable(dims, data, attrs=dict(units=units, long_name=long_name))

    ds = xr.Dataset(
        {
            "lambda_max": var(sc, np.array([r.lambda_max for r in runs.values()]), "1", "lambda max"),
            "lambda_upper": var(sc, np.array([r.lambda_upper for r in runs.values()]), "1", "lambda upper"),
            "lambda_direct": var(sc, np.array([r.lambda_direct for r in runs.values()]), "1", "direct"),
            "outcome": var(sc, np.array([r.outcome for r in runs.values()], dtype=object), "-", "outcome"),
            "model": var(sc, model, "-", "model"),
            "lam": var(st, lam, "1", "load multiplier"),
            "status": var(st, status, "-", "status"),
            "reaction": var(st + ("support", "component"), reaction, "kN, kN m", "support reaction"),
            "tce": var(st, tce, "kN m", "total complementary energy"),
            "resultant": var(itf + ("xyz",), res, "kN", "interface resultant"),
            "pressure_point": var(itf + ("xyz",), pp, "m", "pressure point"),
            "torque": var(itf, torque, "kN m", "torque about the normal"),
            "vertex_force": var(st + ("vertex", "xyz"), vforce, "kN", "vertex force"),
            "vertex_point": var(("vertex", "xyz"), first.interface_map.vertex_points, "m", "vertex position"),
            "mechanism": var(("scenario", "block", "dof"), mech, "m, rad", "collapse mechanism"),
            "interface_mode": var(("scenario", "interface"), mode, "-", "interface mode"),
            "hinge_point": var(("scenario", "interface", "xyz"), hinge, "m", "hinge point"),
            "interface_a": var(("interface",), np.array([asm.names[i.a] for i in asm.interfaces], object), "-", "A"),
            "interface_b": var(("interface",), np.array([asm.names[i.b] for i in asm.interfaces], object), "-", "B"),
            "block_centroid": var(("block", "xyz"), asm.centroids, "m", "block centroid"),
            "block_support": var(("block",), np.array([int(b.support) for b in asm.blocks]), "-", "support"),
        },
        coords={
            "scenario": names,
            "step": np.arange(nstep),
            "support": list(asm.support_names),
            "component": COMPONENTS,
            "interface": [f"{asm.names[i.a]}|{asm.names[i.b]}" for i in asm.interfaces],
            "xyz": ["x", "y", "z"],
            "block": list(asm.names),
            "dof": ["vx", "vy", "vz", "wx", "wy", "wz"],
            "alpha": ("scenario", np.array([r.alpha for r in runs.values()])),
        },
        attrs={"study_name": "arch-test", "assembly": json.dumps(asm.to_dict())},
    )
    return ds


def arch_dataset(alpha: float, scenarios: Mapping[str, dict], friction: float = 0.8) -> xr.Dataset:
    """The paper's arch under lateral loads in direction ``alpha``, one load path per scenario."""
    asm = semicircular_arch()
    analysis = Analysis(asm, Material(friction=friction))
    runs = {name: load_path(analysis, alpha, sett, step=0.04, atol=2e-3) for name, sett in scenarios.items()}
    return dataset_from_load_paths(asm, runs)


@pytest.fixture(scope="module")
def planar() -> xr.Dataset:
    return arch_dataset(
        0.0,
        {
            "loads only": {},
            "right outward": {"right": [0.001, 0, 0, 0, 0, 0]},
            "right inward": {"right": [-0.001, 0, 0, 0, 0, 0]},
        },
    )


@pytest.fixture(scope="module")
def spatial() -> xr.Dataset:
    return arch_dataset(90.0, {"out of plane": {}, "out of plane, right sinks": {"right": [0, 0, -0.001, 0, 0, 0]}})


def axes_of(fig: Figure) -> list[Axes]:
    return fig.get_axes()


def by_gid(ax: Axes, gid: str) -> list:
    return [a for a in ax.get_children() if a.get_gid() == gid]


# ---------------------------------------------------------------------------- thrust curves
def test_thrust_curves_one_line_per_scenario_and_support(planar: xr.Dataset) -> None:
    fig = plot.thrust_curves(planar)
    ax_h, ax_v = axes_of(fig)
    for ax, component in ((ax_h, "H"), (ax_v, "V")):
        for s in planar.scenario.values:
            lines = [ln for ln in ax.get_lines() if str(ln.get_gid()).startswith(f"reaction:{s}:")]
            assert len(lines) == planar.sizes["support"]
            for ln in lines:
                sup = ln.get_gid().split(":")[-1]
                sel = planar.sel(scenario=s, support=sup)
                ok = (sel.status == "optimal").values
                f = sel.reaction.values[ok]
                expected = np.hypot(f[:, 0], f[:, 1]) if component == "H" else f[:, 2]
                order = np.argsort(sel.lam.values[ok])
                np.testing.assert_allclose(ln.get_xdata(), sel.lam.values[ok][order])
                np.testing.assert_allclose(ln.get_ydata(), expected[order])
    assert ax_h.get_xlabel().endswith("(–)") and "(kN)" in ax_h.get_ylabel() and "(kN)" in ax_v.get_ylabel()


def test_thrust_curves_mark_lambda_max_and_differ_in_greyscale(planar: xr.Dataset) -> None:
    fig = plot.thrust_curves(planar)
    marked = {ln.get_xdata()[0] for ln in by_gid(axes_of(fig)[0], "lambda_max")}
    np.testing.assert_allclose(sorted(marked), sorted(set(np.round(planar.lambda_max.values, 9))))
    assert len(marked) == 1  # same direction: one limit, the curves meet there
    styles = {(str(ln.get_linestyle()), ln.get_marker()) for ln in axes_of(fig)[0].get_lines() if "reaction" in str(ln.get_gid())}
    assert len(styles) == planar.sizes["scenario"] * planar.sizes["support"]
    legend_text = {t.get_text() for lg in fig.legends for t in lg.get_texts()}
    assert set(map(str, planar.scenario.values)) <= legend_text


def test_curves_meet_at_the_limit(planar: xr.Dataset) -> None:
    """The paper's Fig. 8: at lambda_max the support motions no longer matter."""
    at = [plot.default_step(planar, s) for s in planar.scenario.values]
    h = [planar.reaction.sel(scenario=s, step=k, support="right", component="Fx").item() for s, k in zip(planar.scenario.values, at)]
    np.testing.assert_allclose(h, h[0], rtol=2e-2)


# ---------------------------------------------------------------------------- assembly view
@pytest.mark.parametrize("view", ["axo", "elevation", "plan"])
def test_assembly_view_arrows_at_pressure_points(spatial: xr.Dataset, view: str) -> None:
    s = "out of plane"
    fig = plot.assembly_view(spatial, s, view=view)
    (ax,) = axes_of(fig)
    k = plot.default_step(spatial, s)
    assert spatial.lam.sel(scenario=s, step=k).item() == spatial.lambda_max.sel(scenario=s).item()
    pp = spatial.pressure_point.sel(scenario=s, step=k).values
    res = spatial.resultant.sel(scenario=s, step=k).values
    (quiver,) = by_gid(ax, "resultants")
    shafts = np.array(quiver._segments3d[: len(pp)])
    np.testing.assert_allclose(shafts.mean(axis=1), pp, atol=1e-12)
    lengths = np.linalg.norm(shafts[:, 1] - shafts[:, 0], axis=1)
    scale = lengths / np.linalg.norm(res, axis=1)
    np.testing.assert_allclose(scale, scale[0])  # one scale for every arrow ...
    legend = " ".join(t.get_text() for lg in fig.legends for t in lg.get_texts())
    assert f"1 kN = {scale[0]:.3g} m" in legend  # ... and the legend states it
    (points,) = by_gid(ax, "pressure_points")
    np.testing.assert_allclose(np.array(points.get_data_3d()).T, pp)
    # equal scales: the box aspect follows the axis ranges
    ranges = np.array([np.ptp(ax.get_xlim()), np.ptp(ax.get_ylim()), np.ptp(ax.get_zlim())])
    np.testing.assert_allclose(ax.get_box_aspect() / ax.get_box_aspect().max(), ranges / ranges.max(), rtol=1e-9)
    assert by_gid(ax, "blocks") and by_gid(ax, "supports")


def test_assembly_view_torques_and_vertex_forces(spatial: xr.Dataset) -> None:
    s = "out of plane, right sinks"
    fig = plot.assembly_view(spatial, s, vertex_forces=True)
    (ax,) = axes_of(fig)
    k = plot.default_step(spatial, s)
    tq = spatial.torque.sel(scenario=s, step=k).values
    res = spatial.resultant.sel(scenario=s, step=k).values
    significant = np.abs(tq) > plot.TORQUE_TOL * np.linalg.norm(res, axis=1).max() * semicircular_arch().size
    arcs = by_gid(ax, "torques")
    assert len(arcs) == int(significant.any())
    if arcs:
        assert len(arcs[0]._segments3d) == 2 * significant.sum()  # an arc and a head each
    (vf,) = by_gid(ax, "vertex_forces")
    n_live = np.sum(np.linalg.norm(spatial.vertex_force.sel(scenario=s, step=k).values, axis=1) > 0)
    assert len(vf._segments3d) == 3 * n_live


# ---------------------------------------------------------------------------- thrust line
def test_thrust_line_through_pressure_points(planar: xr.Dataset) -> None:
    s = "right outward"
    k_max = plot.default_step(planar, s)
    for step, drawn in ((None, [k_max]), (0, [0]), ([0, k_max], [0, k_max])):
        fig = plot.thrust_line(planar, s, step=step)
        (ax,) = axes_of(fig)
        for k in drawn:
            pp = planar.pressure_point.sel(scenario=s, step=k).values
            (line,) = by_gid(ax, f"thrust_line:{k}")
            np.testing.assert_allclose(line.get_xdata(), pp[:, 0])
            np.testing.assert_allclose(line.get_ydata(), pp[:, 2])
        assert ax.get_aspect() == 1.0
        outlines = [p for p in ax.patches if str(p.get_gid()).startswith("block:")]
        assert len(outlines) == planar.sizes["block"]
        # at the limit the line of thrust shows the hinges of the mechanism
        hinges = by_gid(ax, "hinges")
        assert len(hinges) == (k_max in drawn)
        if hinges:
            hp = planar.hinge_point.sel(scenario=s).values[planar.interface_mode.sel(scenario=s).values == "hinge"]
            np.testing.assert_allclose(hinges[0].get_xdata(), hp[:, 0])


# ---------------------------------------------------------------------------- mechanism
@pytest.mark.parametrize("which", ["planar", "spatial"])
def test_mechanism_hinges_at_hinge_points(which: str, request: pytest.FixtureRequest) -> None:
    ds = request.getfixturevalue(which)
    s = str(ds.scenario.values[0])
    fig = plot.mechanism_view(ds, s)
    (ax,) = axes_of(fig)
    modes = ds.interface_mode.sel(scenario=s).values
    hp = ds.hinge_point.sel(scenario=s).values[modes == "hinge"]
    assert len(hp) >= 1
    (marks,) = by_gid(ax, "hinges")
    if which == "planar":
        np.testing.assert_allclose(np.column_stack([marks.get_xdata(), marks.get_ydata()]), hp[:, [0, 2]])
        assert ax.get_aspect() == 1.0
        moved = [p for p in ax.patches if str(p.get_gid()).startswith("block:")]
        ghosts = [p for p in ax.patches if str(p.get_gid()).startswith("ghost:")]
        assert len(moved) == len(ghosts) == ds.sizes["block"]
    else:
        np.testing.assert_allclose(np.array(marks.get_data_3d()).T, hp)
        assert by_gid(ax, "blocks-ghost")
    assert "exaggerated" in ax.get_title() and f"{ds.lambda_max.sel(scenario=s).item():.3f}" in ax.get_title()


def test_mechanism_moves_the_blocks_that_move(planar: xr.Dataset) -> None:
    fig = plot.mechanism_view(planar, "loads only")
    (ax,) = axes_of(fig)
    vel = planar.mechanism.sel(scenario="loads only")
    for b in semicircular_arch().blocks:
        (ghost,) = [p for p in ax.patches if p.get_gid() == f"ghost:{b.name}"]
        (moved,) = [p for p in ax.patches if p.get_gid() == f"block:{b.name}"]
        still = np.allclose(ghost.get_xy(), moved.get_xy())
        assert still == (not np.any(np.abs(vel.sel(block=b.name).values) > 1e-9))
        assert still or not b.support


# ---------------------------------------------------------------------------- sheet and files
def test_figure_sheet_panels(planar: xr.Dataset) -> None:
    fig = plot.figure_sheet(planar)
    n = planar.sizes["scenario"]
    three_d = [ax for ax in fig.get_axes() if ax.name == "3d"]
    flat = [ax for ax in fig.get_axes() if ax.name != "3d"]
    assert len(three_d) == n  # assembly view per scenario
    assert len(flat) == 2 + 2 * n  # thrust curves (H, V) + thrust line + mechanism per scenario


def test_write_figures(planar: xr.Dataset, spatial: xr.Dataset, tmp_path) -> None:
    both = [planar, spatial]
    for ds in both:
        out = tmp_path / ds.scenario.values[0].replace(" ", "_")
        ds.to_netcdf(out.with_suffix(".nc"))  # default engine: h5py may be absent
        reread = xr.open_dataset(out.with_suffix(".nc"))
        paths = plot.write_figures(reread, out)
        names = {p.name for p in paths}
        n = ds.sizes["scenario"]
        planar_model = bool((ds.model == "planar").all())
        assert {"thrust.png", "sheet.png", "sheet.pdf"} <= names
        assert sum(p.startswith("assembly_") for p in names) == n
        assert sum(p.startswith("thrust_line_") for p in names) == (n if planar_model else 0)
        assert sum(p.startswith("mechanism_") for p in names) == n
        assert all(p.exists() and p.stat().st_size > 1000 for p in paths)
