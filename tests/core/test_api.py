"""The Python API explains itself: short reprs, notebook tables, labelled support wrenches,
``to_xarray`` on results (issue 26).

The equilibrium checks are validation (a closed form: the supports carry the free blocks'
weight, computed from the block volumes here, not by tce's solver); the rest are properties of
the API.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import tce
from tce import Analysis, Material, diagnose, hemispherical_dome, load_path, semicircular_arch
from tce.analysis.nonassoc import nonassociative_limit
from tce.analysis.thickness import arch_minimum_thickness
from tce.display import MAX_REPR
from tce.structures.vault import groin_vault

ARCH = semicircular_arch()
AN = Analysis(ARCH, Material(friction=0.8))


@pytest.fixture(scope="module")
def results() -> dict[str, object]:
    lp = load_path(AN, alpha=0.0, step=0.05)
    spatial = Analysis(ARCH, Material(friction=0.8), model="spatial")
    return {
        "tce": AN.solve(0.1, alpha=0.0, settlements={"right": [0.001, 0, 0, 0, 0, 0]}),
        "tce_spatial": spatial.solve(0.1, alpha=90.0),
        "failed": AN.solve(5.0, alpha=0.0),
        "limit": AN.limit(0.0),
        "path": lp,
        "diagnosis": diagnose(AN, alpha=0.0, lam=5.0),
        "nonassoc": nonassociative_limit(Analysis(ARCH, Material(friction=0.4, flow="non-associative")), alpha=0.0),
        "thickness": arch_minimum_thickness(tol=1e-3),
    }


@pytest.mark.parametrize("build", [semicircular_arch, hemispherical_dome, groin_vault])
def test_assembly_repr_is_short_and_says_what_it_is(build) -> None:
    asm = build()
    text = repr(asm)
    assert len(text) < MAX_REPR
    assert f"{len(asm.blocks)} blocks" in text and f"{len(asm.interfaces)} interfaces" in text
    assert f"{len(asm.support_indices)} supports" in text and f"{asm.total_weight:.4g} kN" in text
    assert "extent" in text and "array" not in text
    html = asm._repr_html_()
    assert html.startswith("<div>") and str(len(asm.blocks)) in html
    assert len(repr(asm.blocks[0])) < 200 and len(repr(asm.interfaces[0])) < 200


def test_assembly_extent_is_the_bounding_box() -> None:
    # semicircular_arch(): inner radius 1, thickness 0.2 -> outer radius 1.1; supports 0.2 high
    np.testing.assert_allclose(ARCH.extent, [2.4, 0.25, 1.1 + 0.2 + 0.1], atol=0.2)
    pts = np.vstack([b.shape.vertices for b in ARCH.blocks])
    np.testing.assert_allclose(ARCH.extent, pts.max(axis=0) - pts.min(axis=0), rtol=0, atol=1e-12)


def test_analysis_repr_names_models_and_material() -> None:
    text = repr(AN)
    assert len(text) < MAX_REPR and "Coulomb friction mu = 0.8" in text and "planar" in text
    heyman = repr(Analysis(hemispherical_dome(), Material(normal_stiffness=1e6)))
    assert "Heyman" in heyman and "spatial" in heyman and "compliant" in heyman and len(heyman) < MAX_REPR
    assert "Analysis" in AN._repr_html_()


def test_result_reprs_are_short_with_status_and_headline(results) -> None:
    for name, r in results.items():
        text = repr(r)
        assert len(text) < MAX_REPR, (name, text)
        assert text.startswith(f"{type(r).__name__}('{r.status}'"), text
        for key in r.HEADLINE:
            assert f"{key}=" in text
        html = r._repr_html_()
        assert r.status in html and type(r).__name__ in html
    assert "lambda_max=0.2428" in repr(results["path"])
    assert "message='clarabel" in repr(results["failed"])  # a failure says why
    assert "exceeds" in repr(results["diagnosis"])


def test_reactions_are_the_support_wrenches_labelled(results) -> None:
    r = results["tce"]
    da = r.reactions
    assert da.dims == ("support", "component")
    assert list(da["support"].values) == list(ARCH.support_names)
    assert list(da["component"].values) == ["Fx", "Fy", "Fz", "Mx", "My", "Mz"]
    np.testing.assert_array_equal(da.values, r.support_wrenches)  # the array stays as it was
    assert float(da.sel(support="right", component="Fx")) == r.support_wrenches[1, 0]


def test_reactions_carry_the_weight(results) -> None:
    """Validation: the supports carry the free blocks' weight (volumes x unit weight)."""
    weight = sum(b.shape.volume * b.unit_weight for b in ARCH.blocks if not b.support)
    for key in ("tce", "tce_spatial"):
        fz = results[key].reactions.sel(component="Fz").sum()
        assert float(fz) == pytest.approx(weight, rel=1e-7)


def test_tce_result_to_xarray(results) -> None:
    r = results["tce_spatial"]
    ds = r.to_xarray()
    assert ds.attrs["status"] == "optimal" and ds.attrs["model"] == "spatial"
    assert float(ds["lam"]) == 0.1 and float(ds["tce"]) == r.tce
    np.testing.assert_array_equal(ds["reaction"].values, r.support_wrenches)
    np.testing.assert_array_equal(ds["resultant"].values, r.resultants)
    assert list(ds["interface"].values)[0] == f"{ARCH.names[ARCH.interfaces[0].a]}|{ARCH.names[ARCH.interfaces[0].b]}"
    # the vertex forces of each interface sum to its resultant
    owner = np.asarray(r.interface_map.vertex_slot)
    summed = np.zeros_like(r.resultants)
    np.add.at(summed, owner, ds["vertex_force"].values)
    np.testing.assert_allclose(summed, r.resultants, atol=1e-9 * ARCH.total_weight)


def test_failed_result_to_xarray_holds_no_numbers(results) -> None:
    ds = results["failed"].to_xarray()
    assert ds.attrs["ok"] == 0 and ds.attrs["status"] == "infeasible"
    assert np.isnan(ds["reaction"].values).all() and np.isnan(float(ds["tce"]))


def test_load_path_to_xarray_stacks_the_sorted_steps(results) -> None:
    lp = results["path"]
    ds = lp.to_xarray()
    path = lp.path
    assert ds.sizes["step"] == len(path) == lp.n_solves
    np.testing.assert_array_equal(ds["lam"].values, [s.lam for s in path])
    assert list(ds["status"].values) == [s.status for s in path]
    for k in (0, len(path) - 1):
        np.testing.assert_array_equal(ds["reaction"].values[k], path[k].support_wrenches)
    assert float(ds["lambda_max"]) == lp.lambda_max and ds.attrs["status"] == "limit"


def test_limit_and_other_results_to_xarray(results) -> None:
    lim = results["limit"].to_xarray()
    assert lim["mechanism"].dims == ("block", "dof") and lim.sizes["block"] == len(ARCH.blocks)
    na = results["nonassoc"].to_xarray()
    assert na.sizes["iteration"] == len(results["nonassoc"].history)
    th = results["thickness"].to_xarray()
    assert float(th["thickness"]) == results["thickness"].thickness


def test_public_names() -> None:
    for name in tce.__all__:
        assert getattr(tce, name) is not None
    assert {"LoadPattern", "PointLoad", "DistributedLoad", "load_assembly", "save_assembly_json"} <= set(tce.__all__)


def test_the_other_objects_a_user_meets_have_short_reprs(results) -> None:
    from tce.core.model import build_model
    from tce.study.schema import load_study

    study = load_study(Path(__file__).resolve().parents[2] / "studies" / "fig5_6_transversal.toml")
    mech = results["limit"].mechanism
    objects = {
        "Study": study, "Scenario": study.scenarios()[0], "Mechanism": mech,
        "InterfaceMap": results["tce"].interface_map, "Model": build_model(hemispherical_dome(), "spatial"),
        "Material": Material(friction=0.8), "LoadPattern": tce.LoadPattern(alpha=30.0),
    }
    for name, obj in objects.items():
        text = repr(obj)
        assert len(text) < MAX_REPR and text.startswith(name), text
    assert f"hinge {len(mech.hinges)}" in repr(mech)
    assert "4 scenarios" in repr(study)
