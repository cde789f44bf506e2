"""``[plots]`` tables, drawn states solved by the runner, the HTML view's data, the VTK export and
the ``tce plot / view / export`` commands (exit codes, messages, nothing written on bad input)."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from tce.core.analysis import Analysis
from tce.core.material import Material
from tce.plot import data
from tce.plot.export import export_vtk
from tce.plot.view import view_data, view_html
from tce.structures.arch import semicircular_arch
from tce.cli import main
from tce.study.runner import run_study
from tce.study.schema import StudyError, parse_study

STUDY = """
[study]
name = "tools"
[structure]
type = "semicircular_arch"
voussoirs = 8
[material]
friction = 0.8
[loads]
alpha = {alpha}
lambda_step = 0.05
tolerance = 1e-3
[scenarios.none]
[scenarios.outward]
right = [0.001, 0, 0, 0, 0, 0]
[plots]
steps = [0.0, 0.13, "max"]
"""


@pytest.fixture(scope="module")
def results(tmp_path_factory: pytest.TempPathFactory) -> Path:
    tmp = tmp_path_factory.mktemp("tools")
    study = parse_study(STUDY.format(alpha=30.0), tmp / "tools.toml")
    return run_study(study, tmp, jobs=1).results


# ---------------------------------------------------------------------------- [plots]
@pytest.mark.parametrize(
    "table, key",
    [
        ('steps = [-0.1]', "plots.steps"),
        ('steps = ["maximum"]', "plots.steps"),
        ('steps = []', "plots.steps"),
        ('scenarios = ["inward"]', "plots.scenarios[0]"),
        ('kinds = ["sheet"]', "plots.kinds[0]"),
        ('stpes = [0.0]', "plots.stpes"),
    ],
)
def test_bad_plots_table(table: str, key: str) -> None:
    text = STUDY.format(alpha=0.0).replace('steps = [0.0, 0.13, "max"]', table)
    with pytest.raises(StudyError) as info:
        parse_study(text, "s.toml")
    assert f"s.toml: {key}:" in str(info.value) and "\n" not in str(info.value)


def test_plots_select_the_drawn_states_without_changing_the_key() -> None:
    study = parse_study(STUDY.format(alpha=0.0), "s.toml")
    plain = parse_study(STUDY.format(alpha=0.0).replace('[plots]\nsteps = [0.0, 0.13, "max"]\n', ""), "s.toml")
    assert [sc.draw for sc in study.scenarios()] == [(0.0, 0.13)] * 2
    assert [sc.key for sc in study.scenarios()] == [sc.key for sc in plain.scenarios()]  # resuming keeps them
    only = parse_study(STUDY.format(alpha=0.0) + 'scenarios = ["out*"]\n', "s.toml")
    assert [sc.draw for sc in only.scenarios()] == [(), (0.0, 0.13)]


def test_runner_solves_the_drawn_states(results: Path) -> None:
    ds = xr.load_dataset(results)
    st = data.find_state(ds, "outward", 0.13)  # not a step of 0.05: solved after the path
    assert st.step is not None
    direct = Analysis(semicircular_arch(voussoirs=8), Material(friction=0.8)).solve(
        0.13, 30.0, {"right": [0.001, 0, 0, 0, 0, 0]})
    np.testing.assert_allclose(ds.reaction.sel(scenario="outward", step=st.step).values, direct.support_wrenches,
                               atol=1e-7)
    lam = ds.lam.sel(scenario="outward").values
    lam = lam[np.isfinite(lam)]
    assert np.all(np.diff(lam) > 0)  # still sorted
    assert int(ds.n_solves.sel(scenario="outward")) == len(lam)


# ---------------------------------------------------------------------------- stored vertex forces
def test_vertex_forces_add_up_to_resultants_and_reactions(results: Path) -> None:
    """Independent of the stored resultants: summing the stored vertex forces per interface gives
    them back, and the support interfaces give the reactions (on the structure: +, on the support: -)."""
    ds = xr.load_dataset(results)
    owner = [str(x) for x in ds.vertex_interface.values]
    for s in data.scenarios(ds):
        for k in data.optimal_steps(ds, s):
            vf = ds.vertex_force.sel(scenario=s, step=k).values
            res = ds.resultant.sel(scenario=s, step=k)
            for name in ds.interface.values:
                rows = [i for i, o in enumerate(owner) if o == name]
                np.testing.assert_allclose(vf[rows].sum(axis=0), res.sel(interface=name).values, atol=1e-10)
            left = ds.reaction.sel(scenario=s, step=k, support="left").values[:3]
            right = ds.reaction.sel(scenario=s, step=k, support="right").values[:3]
            first, last = str(ds.interface.values[0]), str(ds.interface.values[-1])
            assert first.startswith("left|") and last.endswith("|right")
            np.testing.assert_allclose(vf[[i for i, o in enumerate(owner) if o == first]].sum(axis=0), left, atol=1e-10)
            np.testing.assert_allclose(-vf[[i for i, o in enumerate(owner) if o == last]].sum(axis=0), right, atol=1e-10)


# ---------------------------------------------------------------------------- view
def test_view_page_is_self_contained(results: Path) -> None:
    ds = xr.load_dataset(results)
    page = view_html(ds).decode("utf-8")
    assert len(page) > 1_000_000 and "Plotly.newPlot" in page
    assert not re.search(r"<(script|link|img)[^>]+(src|href)=", page)  # nothing loaded from elsewhere
    payload = re.search(r'<script type="application/json" id="data">(.*?)</script>', page, re.S).group(1)
    assert json.loads(payload.replace("<\\/", "</"))["title"] == "tools"


def test_view_data_matches_the_dataset(results: Path) -> None:
    ds = xr.load_dataset(results)
    d = view_data(ds)
    assert [s["name"] for s in d["scenarios"]] == data.scenarios(ds)
    scale = float(d["scale"].split("1 kN = ")[1].split(" m")[0])
    for sc in d["scenarios"]:
        ok = data.optimal_steps(ds, sc["name"])
        assert [st["lam"] for st in sc["steps"]] == pytest.approx(ds.lam.sel(scenario=sc["name"]).values[ok])
        k = ok[sc["start"]]
        assert ds.lam.sel(scenario=sc["name"], step=k).item() == pytest.approx(ds.lambda_max.sel(scenario=sc["name"]).item())
        st = sc["steps"][sc["start"]]
        pp = ds.pressure_point.sel(scenario=sc["name"], step=k).values
        res = ds.resultant.sel(scenario=sc["name"], step=k).values
        live = np.all(np.isfinite(pp), axis=1)
        np.testing.assert_allclose(np.column_stack([st["pts"][a] for a in "xyz"]), pp[live], atol=1e-5)
        # the first polyline of each arrow is its shaft, centred on the pressure point, |R| * scale long
        xyz = np.column_stack([[np.nan if v is None else v for v in st["res"][a]] for a in "xyz"])
        shafts = xyz.reshape(-1, 15, 3)[:, :2]  # shaft, gap, then 4 head lines of 3 rows
        np.testing.assert_allclose(shafts.mean(axis=1), pp[live], atol=1e-5)
        np.testing.assert_allclose(np.linalg.norm(shafts[:, 1] - shafts[:, 0], axis=1),
                                   np.linalg.norm(res[live], axis=1) * scale, atol=2e-5)
        assert sc["mechanism"]["hinges"]["x"]  # the mechanism's hinge lines are there
    none = d["scenarios"][0]
    assert all("not unique" in st["note"] for st in none["steps"][:-1])  # below the limit: a family


# ---------------------------------------------------------------------------- VTK
def test_export_vtk(results: Path, tmp_path: Path) -> None:
    import meshio

    ds = xr.load_dataset(results)
    files = export_vtk(ds, tmp_path)
    blocks = meshio.read(tmp_path / "blocks.vtu")
    assert set(blocks.cell_data["block"][0]) == set(range(ds.sizes["block"]))
    pvd = (tmp_path / "outward.pvd").read_text()
    stamps = [float(t) for t in re.findall(r'timestep="([^"]+)" part="0"', pvd)]
    ok = data.optimal_steps(ds, "outward")
    np.testing.assert_allclose(stamps, ds.lam.sel(scenario="outward").values[ok], rtol=1e-11)
    for n, k in enumerate(ok):
        forces = meshio.read(tmp_path / "outward" / f"forces_{n:03d}.vtu")
        np.testing.assert_allclose(forces.points, ds.vertex_point.sel(scenario="outward").values)
        np.testing.assert_allclose(forces.point_data["force"], ds.vertex_force.sel(scenario="outward", step=k).values)
        res = meshio.read(tmp_path / "outward" / f"resultants_{n:03d}.vtu")
        itf = res.point_data["interface"]
        np.testing.assert_allclose(res.point_data["resultant"],
                                   ds.resultant.sel(scenario="outward", step=k).values[itf])
    mech = meshio.read(tmp_path / "outward" / "mechanism.vtu")
    assert np.abs(mech.point_data["displacement"]).max() > 0
    assert all(f.exists() for f in files)


# ---------------------------------------------------------------------------- commands
def test_plot_one_state_on_demand(results: Path, tmp_path: Path, capsys) -> None:
    out = tmp_path / "one"
    assert main(["plot", str(results), "--scenario", "outward", "--step", "0.07", "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert [p.name for p in out.iterdir()] == ["states_outward_lam0.07.png"] and "states_outward_lam0.07.png" in printed


@pytest.mark.parametrize(
    "argv, option",
    [
        (["--scenario", "inward"], "--scenario"),
        (["--step", "-1"], "--step"),
        (["--step", "nan"], "--step"),
        (["--step", "big"], "--step"),
        (["--kind", "sheet"], "--kind"),
        (["--jobs", "0"], "--jobs"),
    ],
)
def test_plot_bad_options(results: Path, tmp_path: Path, capsys, argv: list[str], option: str) -> None:
    out = tmp_path / "bad"
    try:
        code = main(["plot", str(results), "--out", str(out), *argv])
    except SystemExit as exc:  # argparse
        code = exc.code
    assert code == 2
    err = capsys.readouterr().err
    assert option in err and len(err.strip().splitlines()[-1]) < 300
    assert not out.exists()


def test_view_and_export_commands(results: Path, tmp_path: Path, capsys) -> None:
    page = tmp_path / "v.html"
    assert main(["view", str(results), "--out", str(page), "--scenario", "outward"]) == 0
    d = re.search(r'id="data">(.*?)</script>', page.read_text(), re.S).group(1)
    assert [s["name"] for s in json.loads(d)["scenarios"]] == ["outward"]
    assert main(["view", str(results), "--out", str(tmp_path / "v.txt")]) == 2
    assert main(["view", str(results), "--scenario", "nope", "--out", str(tmp_path / "w.html")]) == 2
    assert not (tmp_path / "v.txt").exists() and not (tmp_path / "w.html").exists()
    with pytest.raises(SystemExit) as info:
        main(["export", str(results)])  # --vtk is required
    assert info.value.code == 2
    assert main(["export", str(results), "--vtk", "--out", str(tmp_path / "vtk"), "--scenario", "none"]) == 0
    assert (tmp_path / "vtk" / "none.pvd").exists() and not (tmp_path / "vtk" / "outward.pvd").exists()
    assert main(["export", str(tmp_path / "missing.nc"), "--vtk"]) == 2
    assert "no such results file" in capsys.readouterr().err


def test_notes_for_outcomes_other_than_limit(tmp_path: Path) -> None:
    """A Heyman arch cannot follow a transversal support motion: unbounded, said on the figures."""
    text = STUDY.format(alpha=0.0).replace("friction = 0.8", "").replace(
        "right = [0.001, 0, 0, 0, 0, 0]", "right = [0, 0.001, 0, 0, 0, 0]")
    ds = xr.load_dataset(run_study(parse_study(text, tmp_path / "s.toml"), tmp_path, jobs=1).results)
    assert str(ds.outcome.sel(scenario="outward").values) == "unbounded"
    note = data.outcome_note(ds, "outward")
    assert note.startswith("unbounded")
    st = data.find_state(ds, "outward", 0.0)
    assert st.step is None and st.note.startswith("unbounded")
    from tce.plot import figures

    fig = figures.thrust_curves(ds)
    assert any(note in " ".join(t.get_text().split()) for t in fig.texts)  # wrapped to the figure's width
    fig = figures.states_figure(ds, [("outward", 0.0)])
    assert any("unbounded" in t.get_text() for t in fig.axes[0].texts)
    assert math.isnan(float(ds.lambda_max.sel(scenario="outward")))
