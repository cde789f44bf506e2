"""Materials beyond the paper against closed forms and an LP written by hand (moved from
tests/core/test_materials.py): cohesion, tensile and compressive strength on one block, the stress
block reached with strips, and the non-associative bracket of two blocks side by side.

Every reference is a closed form derived here or an LP written in the test (scipy's HiGHS on
equilibrium equations written by hand), never tce's operators.

Blocks of :func:`helpers.block_on_support`: b = 0.4 (x) by d = 0.3 (y) by h = 1.0 m, unit
weight 20 kN/m^3, so W = 2.4 kN, base area A = 0.12 m^2 (each corner a quarter, A/4), the
centroid at h_c = 0.5 m; lateral load lam W at the centroid along +x. Rigid rocking is at
lam = b / (2 h_c) = 0.4.
"""

from __future__ import annotations

import numpy as np
import pytest
from helpers import block_on_support, equal_blocks_side_by_side, limits
from scipy.optimize import linprog

from tce import Analysis, Material, semicircular_arch
from tce.analysis.nonassoc import nonassociative_limit
from tce.core.limit import LimitSolver
from tce.core.model import build_model
from tce.quality.validation import block_on_strips

B, D, H = 0.4, 0.3, 1.0
W = 20.0 * B * D * H
AREA = B * D
HC = H / 2


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
    for lam in limits(block_on_strips(n, B, D, H), Material(None, compressive_strength=fc)).values():
        if exact:
            assert lam == pytest.approx(block, rel=1e-7)
        else:
            assert block - 1e-9 <= lam <= block + (B / n) / (2 * HC)
    # corners only (one interface): the hinge stays at the edge while the toe corners carry W
    assert per_vertex_rocking(fc) > block + 0.05


# ----------------------------------------------------------------------------- non-associative
@pytest.mark.parametrize(("mu", "expected"), [(0.2, 0.2), (0.3, 0.3), (0.6, B / (2 * HC)), (1.0, B / (2 * HC))])
def test_one_block_sliding_or_rocking_both_flows(mu: float, expected: float) -> None:
    """Pure sliding (lam = mu) and pure rocking (lam = b / h): no dilatancy to gain."""
    r = nonassociative_limit(Analysis(block_on_support(), Material(mu, flow="non-associative")))
    assert r.status == "converged" and r.converged
    assert r.lambda_assoc == pytest.approx(expected, rel=1e-8)
    assert r.lambda_nonassoc == pytest.approx(expected, rel=1e-7)
    assert r.dilatancy < 1e-6


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
    # in the family, below the associative top (the bracket is real); the nearest-state
    # iterates reach its lowest end, each block rocking alone (0.500001 at mu 0.6 and 0.8)
    assert 0.5 - 1e-6 <= lam < top - 1e-3
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
