"""Metamorphic relations over whole studies: tce's runner, its datasets and stored geometry.

A drawn scene is written as a study twice: as built (its generator's ``type``) and moved by
a map (rotated about z, mirrored, translated or in mm and N) as a block file; the two
``results.nc`` must tell the same story: outcomes, lambda_max, the total reaction at every
common load step, each support's reaction where the state is unique, and the stored
geometry (block centroids, interface vertices, load points) moved by the map.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import xarray as xr
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

from tce.core.analysis import Analysis

from .cases import LOADS, SETTLEMENTS, Scene, path_settings, scene
from .studies import SECTIONS, file_section, run, study_text, total_reaction
from .transform import Similarity

SETTINGS = settings(
    max_examples=8, deadline=None, phases=(Phase.explicit, Phase.reuse, Phase.generate),
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture],
)
#: materials of the study relations (the non-associative scheme: tests/battery/test_sweeps.py)
STUDY_MATERIALS = ("heyman", "friction", "cohesion", "strengths", "compliant")


def scene_study(sc: Scene, name: str, structure: dict, settings_: dict) -> str:
    """The study of a scene (one settlement case, ``moved`` or ``none``)."""
    case = {"moved": sc.settlements} if sc.settlements else {"none": {}}
    return study_text(name, structure, sc.material, sc.pattern, case, loads=settings_)


def path_section(sc: Scene) -> dict:
    """``[loads]`` settings of a scene: four increments to the direct limit, bisection to 1e-6."""
    lim = Analysis(sc.assembly, sc.material).limit(loads=sc.pattern)
    step, cap = path_settings(lim.lambda_max if lim.ok else math.nan)
    return {"lambda_step": step, "lambda_cap": cap, "tolerance": 1e-6}


def _common_steps(a: xr.Dataset, b: xr.Dataset, k: int) -> list[tuple[int, int]]:
    """Steps of scenario ``k`` solved at the same multiplier in ``a`` and ``b``, both optimal."""
    la, lb = a["lam"].values[k], b["lam"].values[k]
    sa, sb = a["status"].values[k], b["status"].values[k]
    out = []
    for i, lam in enumerate(la):
        j = np.flatnonzero(lb == lam)
        if len(j) and sa[i] == sb[j[0]] == "optimal":
            out.append((i, int(j[0])))
    return out


def same_results(a: xr.Dataset, b: xr.Dataset, t: Similarity) -> None:
    """``b`` is ``a`` seen through ``t`` (tolerances: ``relations.py``)."""
    size = float(np.linalg.norm(np.ptp(a["vertex_point"].values, axis=0))) * t.length
    # stored geometry, moved by the map
    names = a["block"].values
    np.testing.assert_allclose(b["block_centroid"].sel(block=names).values, t.points(a["block_centroid"].values),
                               atol=1e-12 * size, err_msg="block_centroid")
    np.testing.assert_allclose(b["vertex_point"].values, t.points(a["vertex_point"].values), atol=1e-12 * size,
                               err_msg="vertex_point")
    if "load_point" in a:
        np.testing.assert_allclose(b["load_point"].values, t.points(a["load_point"].values), atol=1e-9 * size,
                                   err_msg="load_point")
        np.testing.assert_allclose(b["load_force"].values, t.forces(a["load_force"].values),
                                   atol=1e-12 * t.force * float(np.nanmax(np.abs(a["load_force"].values))),
                                   err_msg="load_force")
    # answers
    assert list(a["outcome"].values) == list(b["outcome"].values)
    for x, y, tol in (("lambda_direct", "lambda_direct", 1e-7), ("lambda_max", "lambda_max", 2e-6)):
        va, vb = a[x].values, b[y].values
        assert np.array_equal(np.isnan(va), np.isnan(vb)), (x, va, vb)
        ok = ~np.isnan(va)
        np.testing.assert_allclose(vb[ok], va[ok], rtol=tol, atol=tol, err_msg=x)
    weight = float(a["reaction"].isel(step=0).sel(component="Fz").sum("support").max()) * t.force
    ta, tb = total_reaction(a, np.zeros(3)), total_reaction(b, t.points(np.zeros(3)))
    for k in range(a.sizes["scenario"]):
        pairs = _common_steps(a, b, k)
        assert pairs, "no step in common"
        for i, j in pairs:
            exp = t.wrenches(ta[k, i])
            np.testing.assert_allclose(tb[k, j, :3], exp[:3], atol=1e-8 * weight, err_msg="total reaction force")
            np.testing.assert_allclose(tb[k, j, 3:], exp[3:], atol=1e-8 * weight * size, err_msg="total reaction moment")
            if a["unique"].values[k, i] == 1:
                ra = t.wrenches(a["reaction"].values[k, i])
                rb = b["reaction"].sel(support=a["support"].values).values[k, j]
                np.testing.assert_allclose(rb[:, :3], ra[:, :3], atol=1e-6 * weight, err_msg="reaction force")
                np.testing.assert_allclose(rb[:, 3:], ra[:, 3:], atol=1e-6 * weight * size, err_msg="reaction moment")
                pa, pb = a["pressure_point"].values[k, i], b["pressure_point"].values[k, j]
                loaded = ~np.isnan(pa[:, 0])
                np.testing.assert_allclose(pb[loaded], t.points(pa[loaded]), atol=1e-6 * size, err_msg="pressure_point")


MAPS = st.one_of(
    st.floats(-180.0, 180.0).map(Similarity.rotation),
    st.sampled_from((90.0, -90.0, 180.0)).map(Similarity.rotation),
    st.sampled_from((0.0, 90.0)).map(Similarity.mirror),
    st.just(Similarity.units(1000.0, 1000.0)),
    st.tuples(st.floats(-20.0, 20.0), st.floats(-20.0, 20.0), st.floats(-5.0, 5.0)).map(Similarity.translation),
)


def _axes_kept(sc: Scene, t: Similarity) -> Similarity:
    """``t``, or a quarter turn when it turns a plan rectangle off the axes."""
    if sc.pattern.distributed and not np.all(np.isin(t.Q[:2, :2], (-1.0, 0.0, 1.0))):
        return Similarity.rotation(90.0)
    return t


@SETTINGS
@given(
    names=st.tuples(st.sampled_from(tuple(SECTIONS)), st.sampled_from(STUDY_MATERIALS), st.sampled_from(LOADS),
                    st.sampled_from(tuple(SETTLEMENTS)), st.sampled_from((0.0, 90.0, 30.0))),
    t=MAPS,
)
def test_study_moved_as_a_block_file(names, t, tmp_path_factory):
    """The study of a generated structure against the same study moved by ``t``, the
    structure given as a block file (so: structures spanning y, in mm, anywhere)."""
    sc = scene(*names)
    t = _axes_kept(sc, t)
    folder = tmp_path_factory.mktemp("moved")
    s = path_section(sc)
    a = run(scene_study(sc, "built", SECTIONS[names[0]], s), folder)
    moved = sc.mapped(t)
    b = run(scene_study(moved, "moved", file_section(moved.assembly, folder, "moved"), s), folder)
    same_results(a, b, t)


def test_block_file_study_moved(tmp_path: Path):
    """The block-file structure (a running-bond wall read from a file, interfaces found
    from the geometry) turned to run along y, under a live point load and its own weight
    across: the same answers and geometry."""
    sc = scene("file", "friction", "distributed", "in_plane", 90.0)
    t = Similarity.rotation(-90.0)
    s = path_section(sc)
    wall = {"type": "file", "path": str(Path(__file__).resolve().parents[2] / "studies" / "data" / "wall.json"),
            "supports": ["base"]}
    a = run(scene_study(sc, "wall", wall, s), tmp_path)
    moved = sc.mapped(t)
    b = run(scene_study(moved, "moved", file_section(moved.assembly, tmp_path, "moved"), s), tmp_path)
    same_results(a, b, t)
