"""The TCE solver: residuals, statuses, invariances, and cross-checks between tce's own paths
(planar vs spatial, Clarabel direct vs cvxpy). Closed forms and independent references:
tests/validation/."""

import numpy as np
import pytest

from tce.analysis import Analysis
from tce.core.cvx import CvxTCE
from tce.core.clarabel_solver import SolverOptions
from tce.core.limit import LimitSolver
from tce.core.material import Material
from tce.core.model import build_model
from tce.core.solve import TCESolver

MM = 1e-3
SCENES = {
    "none": {},
    "outward": {"right": [MM, 0, 0, 0, 0, 0]},
    "inward": {"right": [-MM, 0, 0, 0, 0, 0]},
    "down": {"right": [0, 0, -MM, 0, 0, 0]},
    "rot+": {"right": [0, 0, 0, 0, MM, 0]},
    "rot-": {"right": [0, 0, 0, 0, -MM, 0]},
    "spread": {"left": [-MM, 0, 0, 0, 0, 0], "right": [MM, 0, 0, 0, 0, 0]},
    "transversal": {"right": [0, MM, 0, 0, 0, 0]},
}
MATERIALS = {"heyman": Material(), "mu0.8": Material(0.8), "elastic": Material(0.8, normal_stiffness=1e5, shear_stiffness=4e4)}


def H(r, support):
    """Horizontal reaction along x of a support (kN)."""
    return r.support_wrenches[("left", "right").index(support), 0]


# every scene is admissible but one: a transversal motion of a Heyman arch (unbounded)
OPTIMAL = [(m, s) for m in MATERIALS for s in SCENES if (m, s) != ("heyman", "transversal")]


@pytest.mark.parametrize("lam", [0.0, 0.15])
def test_unbounded_answer_has_no_numbers(arch, lam):
    r = Analysis(arch, MATERIALS["heyman"]).solve(lam, 0.0, SCENES["transversal"])
    assert r.status == "unbounded"
    assert np.all(np.isnan(r.forces))  # no numbers from a failed solve
    assert np.isnan(r.tce) and np.all(np.isnan(r.support_wrenches))


@pytest.mark.parametrize("mat, scene", OPTIMAL)
@pytest.mark.parametrize("lam", [0.0, 0.15])
def test_residuals_of_every_optimal_answer(arch, mat, scene, lam):
    an = Analysis(arch, MATERIALS[mat])
    r = an.solve(lam, 0.0, SCENES[scene])
    assert r.status == "optimal", r.message
    assert r.eq_residual < 1e-9 and r.cone_residual < 1e-9
    # independent recomputation of the residuals in physical units
    m = an.model(r.model)
    F = r.forces.ravel()
    res = m.A_eq @ F + m.b_dead + lam * m.b_lateral(0.0)
    W, L = arch.total_weight, arch.size
    assert np.abs(res[~m.row_is_moment]).max() < 1e-9 * W
    assert np.abs(res[m.row_is_moment]).max() < 1e-9 * W * L
    assert r.forces[:, 0].min() > -1e-9 * W
    # the supports carry the weight, and the lateral load
    total = r.support_wrenches[:, :3].sum(axis=0)
    np.testing.assert_allclose(total, [-lam * W, 0, W], atol=1e-8 * W)


def test_result_records_model_solver_and_time(arch):
    r = Analysis(arch, Material(0.8)).solve(0.1, 0.0, SCENES["down"])
    assert r.model == "planar" and r.solver.startswith("clarabel")
    assert r.solve_time > 0 and r.wall_time >= r.solve_time
    r3 = Analysis(arch, Material(0.8)).solve(0.1, 0.0, SCENES["transversal"])
    assert r3.model == "spatial"


def test_outward_gives_minimum_and_inward_maximum_thrust(arch):
    an = Analysis(arch, Material())
    h = {k: -H(an.solve(0, 0, SCENES[k]), "right") for k in ("outward", "inward", "none", "down")}
    assert h["outward"] < h["down"] < h["inward"]
    assert h["outward"] < h["none"] < h["inward"]
    # the values themselves: tests/validation/test_answers.py::test_arch_thrust_bounds


def test_vertical_reactions_sum_to_the_weight(arch):
    r = Analysis(arch, Material()).solve(0, 0, SCENES["down"])
    assert r.support_wrenches[:, 2].sum() == pytest.approx(arch.total_weight, rel=1e-12)


def test_mirrored_settlement_gives_mirrored_reactions(arch):
    an = Analysis(arch, Material(0.8))
    r = an.solve(0, 0, {"right": [MM, 0, -MM, 0, 2 * MM, 0]})
    m = an.solve(0, 0, {"left": [-MM, 0, -MM, 0, -2 * MM, 0]})
    mirror = np.array([-1, 1, 1, 1, -1, 1])  # x -> -x flips Fx and My
    np.testing.assert_allclose(m.support_wrenches[0], r.support_wrenches[1] * mirror, atol=1e-8)
    np.testing.assert_allclose(m.support_wrenches[1], r.support_wrenches[0] * mirror, atol=1e-8)


@pytest.mark.parametrize("factor", [10.0, 1e-3])
@pytest.mark.parametrize("scene", ["outward", "down", "rot+", "transversal"])
def test_rigid_state_independent_of_settlement_magnitude(arch, factor, scene):
    an = Analysis(arch, Material(0.8))
    base = an.solve(0.1, 0, SCENES[scene])
    scaled = an.solve(0.1, 0, {k: np.asarray(v) * factor for k, v in SCENES[scene].items()})
    np.testing.assert_allclose(scaled.support_wrenches, base.support_wrenches, atol=1e-7 * arch.total_weight)


def test_units_change_no_dimensionless_result(arch):
    mm_n = arch.scaled(length=1e3, force=1e3)  # m -> mm, kN -> N
    for mat, scene in [(Material(), "outward"), (Material(0.8), "transversal")]:
        r = Analysis(arch, mat).solve(0.1, 0, SCENES[scene])
        u = {k: np.r_[np.asarray(v[:3]) * 1e3, v[3:]] for k, v in SCENES[scene].items()}
        s = Analysis(mm_n, mat).solve(0.1, 0, u)
        np.testing.assert_allclose(s.support_wrenches[:, :3] / mm_n.total_weight, r.support_wrenches[:, :3] / arch.total_weight, atol=1e-8)
        np.testing.assert_allclose(
            s.support_wrenches[:, 3:] / (mm_n.total_weight * 1e3), r.support_wrenches[:, 3:] / arch.total_weight, atol=1e-8
        )
    assert LimitSolver(build_model(mm_n), Material()).solve(0).lambda_max == pytest.approx(
        LimitSolver(build_model(arch), Material()).solve(0).lambda_max, rel=1e-9
    )


def test_transversal_movement_needs_friction(arch):
    an = {mu: Analysis(arch, Material(mu)) for mu in (None, 0.8, 2.0)}
    scene = SCENES["transversal"]
    assert an[None].solve(0, 0, scene).status == "unbounded"
    assert an[None].solve(0, 0, {"right": [0, 0, 0, MM, 0, 0]}).status == "unbounded"  # transversal rotation
    r08, r20 = an[0.8].solve(0, 0, scene), an[2.0].solve(0, 0, scene)
    assert r08.status == r20.status == "optimal"
    assert abs(r20.support_wrenches[1, 1]) > abs(r08.support_wrenches[1, 1]) > 0
    assert np.nanmax(np.abs(r20.torques)) > 1e-3 * arch.total_weight  # torques appear (paper's Fig. 5)


def test_beyond_collapse_is_infeasible_not_a_failure(arch):
    an = Analysis(arch, Material())
    for lam in (0.2429, 0.25, 0.5, 2.0):
        r = an.solve(lam, 0.0, SCENES["outward"])
        assert r.status == "infeasible", r.message
        assert np.all(np.isnan(r.forces))


# a rigid scene with no support motion has many minimisers: left out
AGREE = [(m, s) for m in MATERIALS for s in ("none", "outward", "down", "rot-") if not (s == "none" and MATERIALS[m].rigid)]


@pytest.mark.parametrize("mat, scene", AGREE)
def test_planar_and_spatial_models_agree(arch, mat, scene):
    p = Analysis(arch, MATERIALS[mat], model="planar").solve(0.12, 0.0, SCENES[scene])
    s = Analysis(arch, MATERIALS[mat], model="spatial").solve(0.12, 0.0, SCENES[scene])
    assert p.model == "planar" and s.model == "spatial"
    scale = np.abs(s.support_wrenches).max()
    np.testing.assert_allclose(p.support_wrenches, s.support_wrenches, atol=1e-6 * scale)
    np.testing.assert_allclose(p.resultants, s.resultants, atol=1e-6 * scale)


def test_planar_model_refuses_out_of_plane_scenes(arch):
    with pytest.raises(ValueError, match="plane"):
        Analysis(arch, Material(0.8), model="planar").solve(0.1, 90.0)


# a transversal motion leaves the plane: spatial model only; with a Heyman material it is unbounded
CROSS = [
    (kind, m, s)
    for kind in ("planar", "spatial")
    for m in MATERIALS
    for s in ("outward", "down", "transversal")
    if not (kind == "planar" and s == "transversal") and (m, s) != ("heyman", "transversal")
]


def test_clarabel_direct_and_cvxpy_agree_on_unbounded(arch):
    model = build_model(arch, "spatial")
    direct = TCESolver(model, MATERIALS["heyman"]).solve(0.1, 0.0, SCENES["transversal"])
    assert direct.status == "unbounded"
    # cvxpy + Clarabel stops on numerical trouble here; ECOS certifies
    assert CvxTCE(model, MATERIALS["heyman"]).solve(0.1, 0.0, SCENES["transversal"], solver="ECOS").status == "unbounded"


@pytest.mark.parametrize("kind, mat, scene", CROSS)
def test_clarabel_direct_and_cvxpy_agree(arch, kind, mat, scene):
    model = build_model(arch, kind)
    # the solvers' own states: where the optimum is not unique both return a point near the
    # analytic centre of the optimal face, not tce's canonical state (tests/core/test_canonical.py)
    direct = TCESolver(model, MATERIALS[mat], SolverOptions(canonical=False)).solve(0.1, 0.0, SCENES[scene])
    cvx = CvxTCE(model, MATERIALS[mat]).solve(
        0.1, 0.0, SCENES[scene], solver="CLARABEL", tol_gap_abs=1e-11, tol_gap_rel=1e-11, tol_feas=1e-11
    )
    assert cvx.status == direct.status == "optimal"
    scale = np.abs(direct.support_wrenches).max()
    np.testing.assert_allclose(cvx.support_wrenches, direct.support_wrenches, atol=1e-6 * scale)
    assert cvx.tce == pytest.approx(direct.tce, rel=1e-6, abs=1e-9)


def test_settlement_input_is_checked(arch):
    an = Analysis(arch, Material())
    with pytest.raises(ValueError, match="unknown support 'middle'"):
        an.solve(0, 0, {"middle": [0] * 6})
    with pytest.raises(ValueError, match="6 numbers"):
        an.solve(0, 0, {"right": [0, 0, 1]})
    with pytest.raises(ValueError, match="NaN"):
        an.solve(0, 0, {"right": [float("nan"), 0, 0, 0, 0, 0]})


def test_material_checks():
    with pytest.raises(ValueError, match="friction"):
        Material(-0.1)
    with pytest.raises(ValueError, match="normal_stiffness"):
        Material(0.5, normal_stiffness=0.0)


def test_uniqueness_flag(arch):
    assert Analysis(arch, Material()).solve(0.0).unique is False
    assert Analysis(arch, Material(0.8, normal_stiffness=1e6)).solve(0.0).unique is True


def test_a_result_is_a_value_no_later_solve_changes(arch):
    """A result is frozen, and the next solves of the same solver (another multiplier, another
    motion, another pattern) leave every array it holds as it was."""
    import copy
    from dataclasses import FrozenInstanceError, fields

    an = Analysis(arch, Material(0.8))
    path = an.path(0.0, {"right": [1e-3, 0, 0, 0, 0, 0]})
    r = path(0.1)
    arrays = [f.name for f in fields(r)] + [f.name for f in fields(r.state)]
    held = copy.deepcopy({k: getattr(r, k) for k in arrays if isinstance(getattr(r, k), np.ndarray)})
    assert {"forces", "support_wrenches", "settlements"} <= held.keys()
    path(0.2)
    an.solve(0.05, 0.0, {"right": [0, 0, -1e-3, 0, 0, 0]})
    an.solve(0.05, 90.0)
    for name, value in held.items():
        np.testing.assert_array_equal(getattr(r, name), value, err_msg=name)
    with pytest.raises(FrozenInstanceError):
        r.lam = 0.2
