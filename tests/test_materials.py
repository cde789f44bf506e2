"""Materials beyond the paper: cohesion, tensile and compressive strength, non-associative friction.

Validation tests: every reference is a closed form derived here or an LP written in the test
(scipy's HiGHS on equilibrium equations written by hand), never tce's operators.

Blocks of :func:`helpers.block_on_support`: b = 0.4 (x) by d = 0.3 (y) by h = 1.0 m, unit
weight 20 kN/m^3, so W = 2.4 kN, base area A = 0.12 m^2 (each corner a quarter, A/4), the
centroid at h_c = 0.5 m; lateral load lam W at the centroid along +x. Rigid rocking is at
lam = b / (2 h_c) = 0.4.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from helpers import block_on_support
from scipy.optimize import linprog

from tce import Analysis, Material, semicircular_arch
from tce.analysis.nonassoc import NonAssocSolver, nonassociative_limit
from tce.core.conic import cone_rows, cone_violation, law_violation
from tce.core.limit import LimitSolver
from tce.core.model import build_model
from tce.structures.assembly import Assembly, Block, Interface
from tce.structures.contacts import detect_interfaces
from tce.structures.geometry import box
from tce.cli import main
from tce.study.schema import StudyError, parse_study

B, D, H = 0.4, 0.3, 1.0
W = 20.0 * B * D * H
AREA = B * D
HC = H / 2


def limits(assembly: Assembly, material: Material, alpha: float = 0.0) -> dict[str, float]:
    """Direct lambda_max in the planar and the spatial model."""
    return {kind: LimitSolver(build_model(assembly, kind), material).solve(alpha).lambda_max for kind in ("planar", "spatial")}


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


# ----------------------------------------------------------------------------- closed forms
def test_cohesion_alone_holds_a_block_until_cA() -> None:
    """mu = 0: the base shears at lam W = c A (rocking, 0.4, is higher)."""
    c = 5.0
    for lam in limits(block_on_support(), Material(0.0, cohesion=c)).values():
        assert lam == pytest.approx(c * AREA / W, rel=1e-8)


def test_cohesion_adds_to_friction() -> None:
    """Mohr-Coulomb sliding: lam W = mu W + c A (0.15 < rocking 0.4)."""
    mu, c = 0.1, 1.0
    for lam in limits(block_on_support(), Material(mu, cohesion=c)).values():
        assert lam == pytest.approx(mu + c * AREA / W, rel=1e-8)


def test_tensile_strength_adds_a_resisting_moment() -> None:
    """Rocking about the toe with the heel's two corners pulling t A / 2 at lever b:
    lam W h_c = W b / 2 + t (A / 2) b."""
    t = 5.0
    expected = (W * B / 2 + t * AREA / 2 * B) / (W * HC)
    for lam in limits(block_on_support(), Material(None, tensile_strength=t)).values():
        assert lam == pytest.approx(expected, rel=1e-8)


def per_vertex_rocking(fc: float) -> float:
    """Rocking limit with corner forces bounded by fc A / 4 (two corners at the toe, two at the heel).

    At the limit the toe corners carry min(W, fc A / 2) and the heel the rest, so the
    resultant sits at e = b/2 (toe alone) or e = (fc A - W) b / (2 W): lam = e / h_c.
    Infeasible (NaN) when fc A < W.
    """
    if fc * AREA < W:
        return float("nan")
    toe = min(W, fc * AREA / 2)
    return (toe - (W - toe)) * (B / 2) / (W * HC)


@pytest.mark.parametrize("fc", [21.0, 25.0, 30.0, 35.0, 40.0, 100.0, 1e4])
def test_compressive_strength_one_block_per_vertex_closed_form(fc: float) -> None:
    for lam in limits(block_on_support(), Material(None, compressive_strength=fc)).values():
        assert lam == pytest.approx(per_vertex_rocking(fc), rel=1e-7)


def test_compressive_strength_below_the_weight_is_infeasible() -> None:
    r = LimitSolver(build_model(block_on_support(), "planar"), Material(None, compressive_strength=15.0)).solve(0.0)
    assert r.status == "infeasible"


def test_compressive_strength_monotone_and_tends_to_rigid() -> None:
    arch = semicircular_arch()
    model = build_model(arch, "planar")
    rigid = LimitSolver(model, Material(0.8)).solve(0.0).lambda_max
    strengths = [50.0, 55.0, 60.0, 65.0, 70.0, 80.0, 1e3, 1e5]
    lams = np.array([LimitSolver(model, Material(0.8, compressive_strength=fc)).solve(0.0).lambda_max for fc in strengths])
    assert np.all(np.diff(lams[:5]) > 1e-3) and np.all(np.diff(lams) >= -1e-9)  # rises, then stays
    assert lams[0] < 0.5 * rigid
    np.testing.assert_allclose(lams[5:], rigid, rtol=1e-8)


def block_on_strips(n: int, b: float = B, d: float = D, h: float = H) -> Assembly:
    """block_on_support with its base given as n interfaces, strips of width b / n along x."""
    base = Block("base", box([-b, -d, -0.2], [b, d, 0.0]), 20.0, support=True)
    top = Block("block", box([-b / 2, -d / 2, 0.0], [b / 2, d / 2, h]), 20.0)
    x = np.linspace(-b / 2, b / 2, n + 1)
    strips = [
        Interface(0, 1, np.array([[x0, -d / 2, 0], [x1, -d / 2, 0], [x1, d / 2, 0], [x0, d / 2, 0]]), [0, 0, 1])
        for x0, x1 in zip(x[:-1], x[1:])
    ]
    return Assembly((base, top), tuple(strips))


@pytest.mark.parametrize(("fc", "exact"), [(40.0, True), (30.0, False)])
def test_compressive_strength_tends_to_the_stress_block_as_the_joint_is_refined(fc: float, exact: bool) -> None:
    """With the base cut into n strips, the corners of each strip carry half its capacity at
    either end: the per-vertex bound keeps each full strip's resultant at its centre, so the
    compressed zone x = W / (fc d) at the toe acts as a stress block and the hinge is set
    back by x / 2: lam = (b - W / (fc d)) / (2 h_c). Exact when x is a whole number of
    strips (fc = 40: x = 0.2 m, 20 strips of 0.01 m); otherwise the partial strip's force may
    sit up to one strip further out: at most s / (2 h_c) above."""
    n = 40
    block = (B - W / (fc * D)) / (2 * HC)
    for lam in limits(block_on_strips(n), Material(None, compressive_strength=fc)).values():
        if exact:
            assert lam == pytest.approx(block, rel=1e-7)
        else:
            assert block - 1e-9 <= lam <= block + (B / n) / (2 * HC)
    # corners only (one interface): the hinge stays at the edge while the toe corners carry W
    assert per_vertex_rocking(fc) > block + 0.05


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
@pytest.mark.parametrize(("mu", "expected"), [(0.2, 0.2), (0.3, 0.3), (0.6, B / (2 * HC)), (1.0, B / (2 * HC))])
def test_one_block_sliding_or_rocking_both_flows(mu: float, expected: float) -> None:
    """Pure sliding (lam = mu) and pure rocking (lam = b / h): no dilatancy to gain."""
    r = nonassociative_limit(Analysis(block_on_support(), Material(mu, flow="non-associative")))
    assert r.status == "converged" and r.converged
    assert r.lambda_assoc == pytest.approx(expected, rel=1e-8)
    assert r.lambda_nonassoc == pytest.approx(expected, rel=1e-7)
    assert r.dilatancy < 1e-6


def equal_blocks_side_by_side(b: float = 0.5, h: float = 1.0, d: float = 0.5) -> Assembly:
    """Two b x h blocks L (x in [0, b]) and R (x in [b, 2b]) on a support, in contact along x = b."""
    def itf(x0: float, x1: float, z0: float, z1: float, vertical: bool) -> np.ndarray:
        if vertical:
            return np.array([[x0, -d / 2, z0], [x0, d / 2, z0], [x0, d / 2, z1], [x0, -d / 2, z1]])
        return np.array([[x0, -d / 2, z0], [x1, -d / 2, z0], [x1, d / 2, z0], [x0, d / 2, z0]])

    base = Block("base", box([-1, -d / 2, -0.2], [3 * b, d / 2, 0.0]), 20.0, support=True)
    left = Block("L", box([0, -d / 2, 0], [b, d / 2, h]), 20.0)
    right = Block("R", box([b, -d / 2, 0], [2 * b, d / 2, h]), 20.0)
    return Assembly(
        (base, left, right),
        (Interface(0, 1, itf(0, b, 0, 0, False), [0, 0, 1]), Interface(0, 2, itf(b, 2 * b, 0, 0, False), [0, 0, 1]),
         Interface(1, 2, itf(b, b, 0, h, True), [1, 0, 0])),
    )


def two_block_assoc_lp(mu: float, b: float = 0.5, h: float = 1.0) -> float:
    """Associative lambda_max of the two blocks side by side, as an LP written by hand.

    2D, weights W = 1 each at (b/2, h/2) and (3b/2, h/2), lateral load lam along +x at the
    centroids. Contacts (fn >= 0, |ft| <= mu fn): L's base corners (0, 0) and (b, 0), R's
    base corners (b, 0) and (2b, 0) (normal +z, tangent +x, force on the block), and the
    joint corners (b, 0), (b, h) (force on R: +fn x + ft z, on L the opposite).
    """
    # unknowns: fn, ft of the 6 contacts, then lam
    rows = np.zeros((6, 13))  # (Fx, Fz, M) of L then of R
    rhs = np.zeros(6)
    cl, cr = np.array([b / 2, h / 2]), np.array([3 * b / 2, h / 2])

    def add(block: int, k: int, point: np.ndarray, n: np.ndarray, t: np.ndarray, sign: float) -> None:
        c = cl if block == 0 else cr
        r = point - c
        for j, v in ((2 * k, n), (2 * k + 1, t)):
            f = sign * v
            rows[3 * block, j] += f[0]
            rows[3 * block + 1, j] += f[1]
            rows[3 * block + 2, j] += r[1] * f[0] - r[0] * f[1]  # moment about +y of (fx, fz) at r = (rx, rz)

    ez, ex = np.array([0.0, 1.0]), np.array([1.0, 0.0])
    add(0, 0, np.array([0.0, 0.0]), ez, ex, 1.0)
    add(0, 1, np.array([b, 0.0]), ez, ex, 1.0)
    add(1, 2, np.array([b, 0.0]), ez, ex, 1.0)
    add(1, 3, np.array([2 * b, 0.0]), ez, ex, 1.0)
    for k, z in ((4, 0.0), (5, h)):
        add(1, k, np.array([b, z]), ex, ez, 1.0)
        add(0, k, np.array([b, z]), ex, ez, -1.0)
    for blk in (0, 1):
        rows[3 * blk, 12] = 1.0  # lam W along +x
        rhs[3 * blk + 1] = 1.0  # weight: sum Fz + (-1) = 0
    a_ub, b_ub = [], []
    for k in range(6):
        for s in (1.0, -1.0):
            row = np.zeros(13)
            row[2 * k + 1], row[2 * k] = s, -mu
            a_ub.append(row)
            b_ub.append(0.0)
    bounds = [(0, None), (None, None)] * 6 + [(None, None)]
    c = np.zeros(13)
    c[12] = -1.0
    res = linprog(c, A_ub=np.array(a_ub), b_ub=b_ub, A_eq=rows, b_eq=rhs, bounds=bounds, method="highs")
    assert res.status == 0
    return float(res.x[12])


@pytest.mark.parametrize("mu", [0.6, 0.8])
def test_two_blocks_side_by_side_bracket(mu: float) -> None:
    """Two equal blocks (b = 0.5, h = 1) pushed together: the associative limit needs the joint
    to open while it slides; without dilatancy the blocks rock together and the joint slides.

    By hand (moments about each block's toe, joint force P at height e on R with the joint's
    friction mu P pulling R's heel down): L gives P e = W (lam / 2 - 1/4), R gives
    W (lam - 1/2) = mu P b, so P = 2 W (lam - 1/2) / mu and e = mu / 4 for every lam of the
    family; R's base friction, lam W + P <= mu (W + mu P), ends it at
    lam = 1 / (mu + 2 - 2 mu^2): the associative limit (checked against an LP written here).
    Non-dilatant collapse states exist for every lam in [1/2, 1 / (mu + 2 - 2 mu^2)] (at 1/2
    each block rocks alone, P = 0); the scheme must return one of them.
    """
    top = 1.0 / (mu + 2 - 2 * mu**2)
    assert two_block_assoc_lp(mu) == pytest.approx(top, rel=1e-9)
    assembly = equal_blocks_side_by_side()
    an = Analysis(assembly, Material(mu, flow="non-associative"))
    r = nonassociative_limit(an, 0.0)
    assert r.status == "converged"
    assert r.lambda_assoc == pytest.approx(top, rel=1e-8)
    lam = r.lambda_nonassoc
    assert 0.5 < lam < top - 1e-3  # strictly inside: the bracket is real
    # the final state is a member of the family derived above
    model = an.model(r.model)
    w = assembly.weights[1]
    joint = model.contact_interface == 2
    fn = r.forces[joint, 0]
    P = fn.sum()
    e = (fn * model.contact_points[joint, 2]).sum() / P
    tol = 1e-5 * assembly.total_weight  # the scheme's fixed point holds to 1e-6 W
    assert P == pytest.approx(2 * w * (lam - 0.5) / mu, abs=tol)
    assert P * e == pytest.approx(P * mu / 4, abs=tol)
    assert r.mechanism.modes == ("hinge", "hinge", "sliding") and r.dilatancy < 1e-6


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

    from tce.plot.materials import write_material_figures

    study = parse_study(STUDY, tmp_path / "study.toml")
    report = run_study(study, tmp_path, jobs=1)  # no figures; the bracket one below
    ds = xr.load_dataset(report.results)
    assert list(ds["nonassoc_status"].values) == ["converged", "converged"]
    np.testing.assert_allclose(ds["lambda_assoc"].values, ds["lambda_direct"].values, rtol=0, atol=0)
    assert np.all(ds["lambda_nonassoc"].values <= ds["lambda_assoc"].values * (1 + 1e-7))
    assert ds["lambda_nonassoc"].attrs["units"] == "1" and "nonassoc_iterations" in ds
    assert np.all(ds["nonassoc_consistency"].values <= 1e-6) and ds["nonassoc_consistency"].attrs["units"] == "1"
    assert write_material_figures(ds, tmp_path) == [tmp_path / "bracket.png"]
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
