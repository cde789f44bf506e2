"""Issue 21, problem 1: a geometry sweep stores and draws each scenario on its own structure.

On the old main a study with ``[sweep] thickness = [0.2, 0.3, 0.4]`` stored the first
structure only (``vertex_point``, ``block_centroid``, the ``assembly`` attr), and the
figures, the view and the VTK export drew the 0.3 and 0.4 m scenarios' pressure points on
the 0.2 m ring. Here every stored coordinate is compared with a fresh build of that
scenario's structure, and every pressure point that a figure draws is checked to lie
inside its own ring (on the drawn data).
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import matplotlib
import numpy as np
import pytest
import xarray as xr

matplotlib.use("Agg")

from tce.core.analysis import Analysis  # noqa: E402
from tce.core.material import Material  # noqa: E402
from tce.plot import data  # noqa: E402
from tce.plot import write_figures  # noqa: E402
from tce.plot.export import export_vtk  # noqa: E402
from tce.plot.figures import states_figure  # noqa: E402
from tce.plot.output import figure_tasks  # noqa: E402
from tce.plot.view import view_data  # noqa: E402
from tce.structures.arch import semicircular_arch  # noqa: E402
from tce.study import load_study  # noqa: E402
from tce.study.runner import run_study  # noqa: E402

THICKNESS = (0.2, 0.3, 0.4)
STUDY = """
[study]
name = "sweep_t"

[structure]
type = "semicircular_arch"
inner_radius = 1.0
thickness = 0.2
depth = 0.25
voussoirs = 8
unit_weight = 20.0

[material]

[loads]
lambda_step = 0.1

[sweep]
thickness = [0.2, 0.3, 0.4]

[scenarios.none]

[plots]
steps = [0.0, "max"]
scenarios = ["*"]
kinds = ["states", "view"]
"""


@pytest.fixture(scope="module")
def results(tmp_path_factory: pytest.TempPathFactory) -> Path:
    d = tmp_path_factory.mktemp("sweep")
    path = d / "study.toml"
    path.write_text(STUDY)
    report = run_study(load_study(path), out=d / "results", jobs=1,
                       plots=lambda ds, folder, jobs: write_figures(ds, folder, jobs=jobs))
    return report.results


def _fresh(t: float):
    return semicircular_arch(inner_radius=1.0, thickness=t, depth=0.25, voussoirs=8, unit_weight=20.0)


def _name(t: float) -> str:
    return f"none/thickness={t:g}"


def test_each_scenario_stores_its_own_coordinates(results: Path) -> None:
    ds = xr.load_dataset(results)
    for t in THICKNESS:
        s = _name(t)
        asm = _fresh(t)
        names = [str(b) for b in ds["block"].values]
        np.testing.assert_allclose(ds.block_centroid.sel(scenario=s).values, asm.centroids[[asm.index[n] for n in names]],
                                   rtol=0, atol=1e-14)
        imap = Analysis(asm, Material()).model("planar").interface_map
        np.testing.assert_allclose(ds.vertex_point.sel(scenario=s).values, imap.vertex_points, rtol=0, atol=1e-14)
        # the attr the figures draw is that structure too
        drawn = data.assembly(ds, s)
        np.testing.assert_allclose(drawn.centroids, asm.centroids, rtol=0, atol=1e-14)
    assert sorted(set(ds.geometry.values.tolist())) == [0, 1, 2]


def _inside_ring(points: np.ndarray, t: float, slack: float = 1e-9) -> np.ndarray:
    """Whether each (x, z) point lies in the ring between radius 1 and 1 + t (``slack`` m)."""
    r = np.hypot(points[:, 0], points[:, -1])
    return (r >= 1.0 - slack) & (r <= 1.0 + t + slack)


def test_drawn_pressure_points_lie_in_their_own_blocks(results: Path) -> None:
    ds = xr.load_dataset(results)
    # the states figure: one structure per figure; the drawn points are those of each panel
    tasks = [t for t in figure_tasks(ds, data.plot_spec(ds)) if t.kind == "states"]
    assert len(tasks) == 3  # one page per thickness
    for task in tasks:
        (panels,) = task.args
        names = list(dict.fromkeys(s for s, _ in panels))
        assert len(names) == 1
        t = float(ds.thickness.sel(scenario=names[0]))
        fig = states_figure(ds, panels)
        ax = fig.axes[0]
        lines = [ln for ln in ax.get_lines() if ln.get_gid() == "pressure_points"]
        blocks = [c for c in ax.collections if c.get_gid() == "blocks"]
        assert len(lines) == len(blocks) == 2  # lambda = 0 and lambda_max, each with its blocks
        for ln, coll, (s, target) in zip(lines, blocks, panels):
            # every drawn pressure point lies in (or on the edge of) a block drawn in its panel
            xy = np.column_stack(ln.get_data())
            paths = coll.get_paths()
            inside = [any(p.contains_point(q, radius=1e-9) or p.contains_point(q, radius=-1e-9) for p in paths)
                      for q in xy]
            assert all(inside), (s, target)
            st = data.find_state(ds, s, target)
            pp = ds.pressure_point.sel(scenario=s).isel(step=st.step).values
            assert np.all(_inside_ring(pp[np.all(np.isfinite(pp), axis=1)], t))
    # the view: each scenario names its own structure, and its points lie in that structure's blocks
    v = view_data(ds)
    for sc in v["scenarios"]:
        t = float(ds.thickness.sel(scenario=sc["name"]))
        mesh = v["structures"][sc["structure"]]["mesh"]
        fresh = np.vstack([b.shape.vertices for b in _fresh(t).blocks])
        np.testing.assert_allclose(np.column_stack([mesh[a] for a in "xyz"]), fresh, atol=1e-5)
        for st in sc["steps"]:
            pts = np.column_stack([st["pts"]["x"], st["pts"]["y"], st["pts"]["z"]])
            assert np.all(_inside_ring(pts, t, slack=2e-5))  # the page rounds to 1e-5 m


def test_vtk_export_gives_each_scenario_its_blocks(results: Path, tmp_path: Path) -> None:
    import meshio

    ds = xr.load_dataset(results)
    export_vtk(ds, tmp_path)
    for t in THICKNESS:
        s = _name(t)
        pvd = (tmp_path / f"{data.slug(s)}.pvd").read_text()
        blocks = set(re.findall(r'part="2" file="([^"]+)"', pvd))
        assert len(blocks) == 1
        pts = meshio.read(tmp_path / blocks.pop()).points
        np.testing.assert_allclose(pts, np.vstack([b.shape.vertices for b in _fresh(t).blocks]), rtol=0, atol=1e-12)
        forces = meshio.read(tmp_path / data.slug(s) / "forces_000.vtu").points
        np.testing.assert_allclose(forces, ds.vertex_point.sel(scenario=s).values)


def test_the_attrs_hold_every_structure(results: Path) -> None:
    ds = xr.load_dataset(results)
    for t in THICKNESS:
        s = _name(t)
        k = int(ds.geometry.sel(scenario=s))
        text = ds.attrs["assembly" if k == 0 else f"assembly_{k}"]
        blocks = json.loads(text)["blocks"]
        assert len(blocks) == 10
        asm = _fresh(t)
        np.testing.assert_allclose(data.assembly(ds, s).centroids, asm.centroids, atol=1e-14)
