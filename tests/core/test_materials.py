"""Materials beyond the paper: cohesion, tensile and compressive strength, non-associative friction.

Behaviour and contracts: parameter checks, the residual of the law, planar against spatial,
the kinematic certificate, the non-associative scheme's fixed point, statuses and study files.
The closed forms and the LPs written by hand are in
tests/validation/test_materials_closed_forms.py.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from helpers import block_on_support, equal_blocks_side_by_side, limits

from tce import Analysis, Material, semicircular_arch
from tce.analysis.nonassoc import NonAssocSolver, nonassociative_limit
from tce.core.conic import cone_rows, cone_violation, law_violation
from tce.core.limit import LimitSolver
from tce.core.model import build_model
from tce.structures.assembly import Assembly, Block
from tce.structures.contacts import detect_interfaces
from tce.structures.geometry import box
from tce.cli import main
from tce.study.schema import StudyError, parse_study

# ----------------------------------------------------------------------------- material checks
@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"friction": 0.5, "cohesion": -1.0}, "cohesion"),
        ({"friction": 0.5, "tensile_strength": -1.0}, "tensile_strength"),
        ({"compressive_strength": 0.0}, "compressive_strength"),
        ({"compressive_strength": float("nan")}, "compressive_strength"),
        ({"flow": "non-associated"}, "flow"),
        ({"cohesion": 10.0}, "cohesion"),  # Heyman: nothing for cohesion to raise
        ({"friction": 0.5, "cohesion": 10.0, "tensile_strength": 30.0}, "tensile_strength"),  # above c/mu = 20
        ({"friction": 0.5, "tensile_strength": 1.0}, "tensile_strength"),  # no cohesion: the cone caps tension at 0
    ],
)
def test_bad_material_names_the_parameter(kwargs: dict, name: str) -> None:
    with pytest.raises(ValueError, match=f"^{name} "):
        Material(**kwargs)


def test_plain_law_unchanged() -> None:
    """The paper's laws keep their rows (no offsets) and their residual measure."""
    model = build_model(semicircular_arch(), "spatial")
    for mu in (None, 0.0, 0.5):
        rows = cone_rows(model, mu)
        assert rows.h is None
        f = np.random.default_rng(1).normal(size=(model.n_contacts, 3))
        fn, ft = f[:, 0], np.linalg.norm(f[:, 1:], axis=1)
        expected = max(0.0, -fn.min()) if mu is None else max(0.0, -fn.min(), (ft - mu * fn).max())
        assert cone_violation(model, mu, f) == pytest.approx(expected, abs=1e-15)


@pytest.mark.parametrize("kind", ["planar", "spatial"])
@pytest.mark.parametrize(
    "mat", [Material(0.5, cohesion=8.0, tensile_strength=6.0, compressive_strength=90.0), Material(0.0, cohesion=5.0),
            Material(None, tensile_strength=3.0, compressive_strength=50.0)],
)
def test_residual_measures_the_law_exactly(kind: str, mat: Material) -> None:
    """cone_violation of the material's law equals the violation of its rows (law_violation)."""
    model = build_model(semicircular_arch(), kind)
    rows = cone_rows(model, mat.friction, **mat.strengths)
    rng = np.random.default_rng(7)
    for _ in range(5):
        f = rng.normal(scale=2.0, size=(model.n_contacts, model.dim))
        assert cone_violation(model, mat.friction, f, **mat.strengths) == pytest.approx(law_violation(rows, f), rel=1e-12, abs=1e-12)


@pytest.mark.parametrize(
    "mat",
    [Material(0.6, cohesion=3.0, tensile_strength=2.0), Material(0.8, compressive_strength=80.0),
     Material(0.0, cohesion=20.0), Material(None, tensile_strength=1.0, compressive_strength=70.0)],
)
def test_planar_equals_spatial_with_strengths(mat: Material) -> None:
    """Bounds linear in the area aggregate exactly into the planar contacts."""
    lam = limits(semicircular_arch(), mat)
    assert np.isfinite(lam["planar"])
    assert lam["planar"] == pytest.approx(lam["spatial"], rel=1e-7, abs=1e-9)


def test_kinematic_certificate_counts_the_dissipation_of_the_strengths() -> None:
    model = build_model(semicircular_arch(), "planar")
    r = LimitSolver(model, Material(0.5, cohesion=5.0, tensile_strength=3.0, compressive_strength=100.0)).solve(0.0)
    assert r.status == "optimal" and r.certificate_gap < 1e-6


def test_tce_solve_respects_the_strengths() -> None:
    """The TCE state is admissible for the extended law (its residual is measured on it)."""
    an = Analysis(semicircular_arch(), Material(0.6, cohesion=3.0, tensile_strength=2.0, compressive_strength=200.0))
    r = an.solve(0.5 * an.limit(0.0).lambda_max)
    assert r.ok and r.cone_residual < 1e-8
    assert an.solve(1.01 * an.limit(0.0).lambda_max).status == "infeasible"


# ----------------------------------------------------------------------------- non-associative
@pytest.mark.parametrize("mu", [0.35, 0.4, 0.5, 0.6, 0.8])
def test_arch_nonassoc_never_above_assoc(mu: float) -> None:
    r = nonassociative_limit(Analysis(semicircular_arch(), Material(mu, flow="non-associative")), 0.0)
    assert r.status == "converged"
    assert r.lambda_nonassoc <= r.lambda_assoc * (1 + 1e-7)
    assert r.admissibility < 1e-6 and r.dilatancy < 1e-4


def test_equal_when_the_mechanism_has_no_sliding() -> None:
    """mu = 0.8: the arch collapses by four hinges; nothing slides, nothing to gain."""
    an = Analysis(semicircular_arch(), Material(0.8, flow="non-associative"))
    assert "sliding" not in an.limit(0.0).mechanism.modes
    r = nonassociative_limit(an, 0.0)
    assert r.lambda_nonassoc == pytest.approx(r.lambda_assoc, rel=1e-8)


def running_bond_wall(courses: int = 6, per_course: int = 5, L: float = 0.4, H: float = 0.175) -> Assembly:
    """A running-bond wall of the kind Ferris and Tin-Loi (2001) analysed: ``courses`` courses of
    L x H x 1 m blocks, ``per_course`` to a course, half blocks at the ends of alternate courses,
    on a support."""
    blocks = [Block("base", box([-0.5, 0, -H], [per_course * L + 0.5, 1.0, 0.0]), 10.0, support=True)]
    for c in range(courses):
        widths = [0.5] + [1.0] * (per_course - 1) + [0.5] if c % 2 == 0 else [1.0] * per_course
        x = 0.0
        for j, w in enumerate(widths):
            blocks.append(Block(f"b{c}_{j}", box([x, 0, c * H], [x + w * L, 1.0, (c + 1) * H]), 10.0))
            x += w * L
    a = Assembly(tuple(blocks), ())
    return Assembly(a.blocks, tuple(detect_interfaces(a)))


def test_running_bond_wall_reaches_a_fixed_point() -> None:
    """The plain scheme cycles on this wall (lambda between 0.641341 and 0.641355, the normal
    forces of contacts outside the mechanism moving by 1e-4 W: the sub-problems' optimal states
    are not unique). What is returned must be a non-associative collapse state, checked here on
    the returned arrays: equilibrium at lambda_nonassoc, the Coulomb law met, and every contact
    that slides in the mechanism at its Coulomb capacity, sliding without opening."""
    mu = 0.65
    assembly = running_bond_wall()
    an = Analysis(assembly, Material(mu, flow="non-associative"))
    r = nonassociative_limit(an, 0.0)
    assert r.status == "converged" and r.ok
    assert r.lambda_nonassoc < r.lambda_assoc - 1e-4  # a real bracket, not the associative state
    W = assembly.total_weight
    F = r.forces
    fn, ft = F[:, 0], np.abs(F[:, 1])  # planar model: one tangential component
    tol = 1e-6 * W
    assert fn.min() >= -tol and (ft - mu * fn).max() <= tol  # Coulomb, written here
    model = an.model(r.model)
    lateral = model.b_lateral(0.0)
    residual = model.A_eq @ F.ravel() + model.b_dead + r.lambda_nonassoc * lateral
    assert np.abs(residual).max() <= 1e-8 * W
    # contact velocities of the mechanism, written here: v_B - v_A at each contact point
    v = r.mechanism.velocities
    a = assembly
    ia = np.array([i.a for i in a.interfaces])[model.contact_interface]
    ib = np.array([i.b for i in a.interfaces])[model.contact_interface]
    p, c = model.contact_points, a.centroids
    rel = (v[ib, :3] + np.cross(v[ib, 3:], p - c[ib])) - (v[ia, :3] + np.cross(v[ia, 3:], p - c[ia]))
    normal = np.array([a.interfaces[k].normal for k in model.contact_interface])
    dn = np.einsum("ij,ij->i", rel, normal)
    dt = np.linalg.norm(rel - dn[:, None] * normal, axis=1)
    sliding = dt > 1e-4
    assert sliding.sum() > 0
    assert (mu * fn[sliding] - ft[sliding]).max() <= tol  # sliding only at the capacity
    assert np.abs(dn[sliding & (fn > tol)]).max() <= 1e-4  # and without opening


def test_heyman_and_zero_friction_need_no_iteration() -> None:
    for mu in (None, 0.0):
        r = nonassociative_limit(Analysis(block_on_support(), Material(mu, tensile_strength=0.0)))
        assert r.status == "converged" and r.iterations == 0 and r.lambda_nonassoc == r.lambda_assoc


def test_not_converged_says_so() -> None:
    """One iteration is too few for the two blocks: no number is reported as converged."""
    model = build_model(equal_blocks_side_by_side(), "planar")
    r = NonAssocSolver(model, Material(0.8), max_iter=1).solve(0.0)
    assert r.status == "not_converged" and not r.ok and not r.converged
    assert np.isnan(r.lambda_nonassoc) and len(r.history) == 2


def test_failed_associative_limit_gives_no_bracket() -> None:
    r = nonassociative_limit(Analysis(semicircular_arch(), Material(0.3)), 0.0)
    assert r.status == "infeasible" and np.isnan(r.lambda_nonassoc)


@pytest.mark.parametrize("kwargs", [{"max_iter": 0}, {"tol": -1.0}, {"relaxation": 0.0}, {"relaxation": 1.5}])
def test_bad_scheme_arguments(kwargs: dict) -> None:
    with pytest.raises(ValueError, match=next(iter(kwargs))):
        NonAssocSolver(build_model(block_on_support(), "planar"), Material(0.5), **kwargs)


# ----------------------------------------------------------------------------- studies
STUDY = """
[study]
name = "materials"

[structure]
type = "semicircular_arch"
voussoirs = 6

[material]
friction = 0.6
cohesion = 0.0
flow = "non-associative"

[loads]
lambda_step = 0.1
tolerance = 1e-3

[sweep]
friction = [0.5, 0.8]
"""


@pytest.mark.parametrize(
    ("old", "new", "key"),
    [
        ("cohesion = 0.0", "cohesion = -1.0", "material.cohesion"),
        ("cohesion = 0.0", "compressive_strength = -5.0", "material.compressive_strength"),
        ("cohesion = 0.0", "tensile_strength = -5.0", "material.tensile_strength"),
        ('flow = "non-associative"', 'flow = "nonassociative"', "material.flow"),
        ("friction = [0.5, 0.8]", "friction = [0.5]\ncohesion = [-2.0]", "sweep.cohesion"),
        ("cohesion = 0.0", "tensile_strength = 5.0", "material.tensile_strength"),  # above c / mu = 0
        ("friction = 0.6\ncohesion = 0.0", "cohesion = 3.0", "material.cohesion"),  # Heyman with a sweep of no friction
    ],
)
def test_bad_material_in_a_study_exits_2_naming_the_key(old: str, new: str, key: str, tmp_path: Path, capsys) -> None:
    assert old in STUDY
    text = STUDY.replace(old, new, 1).replace("friction = [0.5, 0.8]", "magnitude = [1.0]" if key == "material.cohesion" else "friction = [0.5, 0.8]")
    path = tmp_path / "study.toml"
    path.write_text(text, encoding="utf-8")
    out = tmp_path / "out"
    assert main(["run", str(path), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert f"{path}: {key}" in err and "fix:" in err and "Traceback" not in err
    assert not out.exists()


def test_strengths_are_sweepable() -> None:
    text = STUDY.replace("friction = [0.5, 0.8]", "compressive_strength = [50.0, 100.0]\ncohesion = [0.0, 2.0]")
    scenarios = parse_study(text).scenarios()
    # sweeps multiply in the order of the [sweep] keys' declaration: cohesion before compressive_strength
    assert [(s.material["cohesion"], s.material["compressive_strength"]) for s in scenarios] == [
        (0.0, 50.0), (0.0, 100.0), (2.0, 50.0), (2.0, 100.0)]


def test_study_dataset_carries_the_bracket_and_the_figure(tmp_path: Path) -> None:
    from tce.study.runner import run_study

    from tce.plot.output import Task, render

    study = parse_study(STUDY, tmp_path / "study.toml")
    report = run_study(study, tmp_path, jobs=1)  # no figures; the bracket one below
    ds = xr.load_dataset(report.results)
    assert list(ds["nonassoc_status"].values) == ["converged", "converged"]
    np.testing.assert_allclose(ds["lambda_assoc"].values, ds["lambda_direct"].values, rtol=0, atol=0)
    assert np.all(ds["lambda_nonassoc"].values <= ds["lambda_assoc"].values * (1 + 1e-7))
    assert ds["lambda_nonassoc"].attrs["units"] == "1" and "nonassoc_iterations" in ds
    assert np.all(ds["nonassoc_consistency"].values <= 1e-6) and ds["nonassoc_consistency"].attrs["units"] == "1"
    assert render(ds, Task("bracket.png", "bracket", ()), tmp_path) == tmp_path / "bracket.png"
    assert (tmp_path / "bracket.png").stat().st_size > 10_000


def test_bracket_figure_only_for_material_sweeps(tmp_path: Path) -> None:
    from tce.plot.materials import bracket_figure
    from tce.study.runner import run_study

    study = parse_study(STUDY.replace("friction = [0.5, 0.8]", "magnitude = [1.0]"), tmp_path / "study.toml")
    ds = xr.load_dataset(run_study(study, tmp_path, jobs=1).results)
    assert bracket_figure(ds) is None


def test_study_error_type() -> None:
    with pytest.raises(StudyError, match="material.flow"):
        parse_study(STUDY.replace('"non-associative"', '"dilatant"'))


@pytest.mark.parametrize("name", ["friction", "normal_stiffness", "cohesion", "tensile_strength",
                                  "compressive_strength"])
@pytest.mark.parametrize("bad", ["0.8", True])
def test_a_parameter_that_is_not_a_number_is_named(name: str, bad: object) -> None:
    """``Material(friction="0.8")`` raised a bare TypeError from a comparison (issue 37 item 8)."""
    kwargs = {"friction": 0.8, name: bad}
    with pytest.raises(TypeError, match=f"^{name} must be a real number \\(float\\), got {type(bad).__name__}"):
        Material(**kwargs)
