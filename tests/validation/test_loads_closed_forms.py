"""General loads against references tce did not produce (moved from tests/core/test_loads.py):
closed forms of rigid blocks (rocking, sliding, overturning of a column, a surcharge) and the
paper's arch against a linear program written here from its geometry (scipy's HiGHS, not
tce's model or solver).
"""

from __future__ import annotations

import numpy as np
import pytest
from helpers import block_on_support, extrados_midpoint, point
from scipy.optimize import linprog

from tce.core.analysis import Analysis
from tce.core.loads import DistributedLoad, LoadPattern
from tce.core.material import Material
from tce.structures.assembly import Assembly, Block, Interface
from tce.structures.geometry import box

UNIT_WEIGHT = 20.0  # kN/m^3


def column(n: int, side: float = 0.5, unit_weight: float = UNIT_WEIGHT) -> Assembly:
    """``n`` equal cubes of ``side`` stacked on a wider support slab (cube k from z = k side)."""
    s = side
    blocks = [Block("base", box([-s, -s, -0.2], [s, s, 0.0]), unit_weight, support=True)]
    blocks += [Block(f"c{k + 1}", box([-s / 2, -s / 2, k * s], [s / 2, s / 2, (k + 1) * s]), unit_weight) for k in range(n)]
    interfaces = []
    for k in range(n):
        z = k * s
        pts = np.array([[-s / 2, -s / 2, z], [s / 2, -s / 2, z], [s / 2, s / 2, z], [-s / 2, s / 2, z]])
        interfaces.append(Interface(k, k + 1, pts, [0, 0, 1]))
    return Assembly(tuple(blocks), tuple(interfaces))


# ---------------------------------------------------------------------------- closed forms
@pytest.mark.parametrize("model", ["auto", "spatial"])
@pytest.mark.parametrize("height", [1.0, 0.6, 0.25])
def test_single_block_rocks_at_w_b_over_h(model, height):
    # block of width 0.4 (half-width b = 0.2), height 1.0, depth 0.3 on a slab; horizontal
    # live load P at `height` above the base: rocking about the far edge at P = W b / h
    width, h, depth = 0.4, 1.0, 0.3
    a = block_on_support(width, h, depth, UNIT_WEIGHT)
    W = UNIT_WEIGHT * width * h * depth
    lim = Analysis(a, Material(), model=model).limit(loads=point([1.0, 0, 0], block="block", at=[-0.2, 0.0, height]))
    assert lim.status == "optimal"
    assert lim.lambda_max == pytest.approx(W * (width / 2) / height, rel=1e-7)
    assert lim.mechanism.hinges == [0]
    assert lim.lambda_kinematic == pytest.approx(lim.lambda_max, rel=1e-7)


@pytest.mark.parametrize("model", ["auto", "spatial"])
def test_single_block_slides_at_mu_w(model):
    # a squat block (half-width 0.4, load at 0.5: rocking at 0.8 W) slides first at mu W
    a = block_on_support(0.8, 1.0, 0.3, UNIT_WEIGHT)
    W = UNIT_WEIGHT * 0.8 * 1.0 * 0.3
    lim = Analysis(a, Material(0.2), model=model).limit(loads=point([1.0, 0, 0], block="block", at=[0.0, 0.0, 0.5]))
    assert lim.status == "optimal"
    assert lim.lambda_max == pytest.approx(0.2 * W, rel=1e-7)
    assert lim.mechanism.sliding == [0]


@pytest.mark.parametrize("n", [1, 2, 3, 5])
def test_column_lateral_pattern_one_over_n(n):
    lim = Analysis(column(n), Material()).limit(0.0)
    assert lim.lambda_max == pytest.approx(1.0 / n, rel=1e-7)


@pytest.mark.parametrize("direction", [[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.6, 0.8, 0.0]])
@pytest.mark.parametrize("n", [1, 2, 4])
def test_column_top_point_load_overturns_about_the_base_edge(n, direction):
    # one horizontal point load P d on the top face of the top cube: the column (and every
    # part of it above a joint) stands while the resultant of weight and load meets its
    # square base, |P h d_x| and |P h d_y| <= (n W) s / 2 with h = n s: overturning about the
    # base edge facing the larger component of d
    s = 0.5
    W = UNIT_WEIGHT * s**3
    d = np.asarray(direction)
    lim = Analysis(column(n, s), Material()).limit(loads=point(list(d), block=f"c{n}", at=[0.0, 0.0, n * s]))
    arm = (s / 2) / max(abs(d[0]), abs(d[1]))
    assert lim.lambda_max == pytest.approx(n * W * arm / (n * s), rel=1e-7)


def test_surcharge_on_a_block_raises_its_rocking_limit():
    # a fixed distributed load q on the right half of the top face (resultant Q at x = b/4)
    # and the lateral pattern: lam W h/2 = W b/2 + Q b/4 about the right edge
    b, h, d, q = 0.4, 1.0, 0.3, 7.0
    a = block_on_support(b, h, d, UNIT_WEIGHT)
    W = UNIT_WEIGHT * b * h * d
    Q = q * (b / 2) * d
    half = LoadPattern(distributed=[DistributedLoad(x=[0.0, b / 2], y=[-d / 2, d / 2], pressure=q, scaled=False)])
    lim = Analysis(a, Material()).limit(loads=half)
    assert lim.lambda_max == pytest.approx((W * b / 2 + Q * b / 4) / (W * h / 2), rel=1e-7)
    full = LoadPattern(distributed=[DistributedLoad(x=[-b / 2, b / 2], y=[-d / 2, d / 2], pressure=q, scaled=False)])
    assert Analysis(a, Material()).limit(loads=full).lambda_max == pytest.approx((W + 2 * Q) * b / (W * h), rel=1e-7)


# ---------------------------------------------------------------------------- independent LP
def _arch_lp(k: int, mu: float | None, ri=1.0, t=0.2, depth=0.25, n=14, gamma=UNIT_WEIGHT) -> float:
    """Collapse load (kN) of a vertical point load on the extrados midpoint of voussoir k
    (1-based) of a semicircular arch: max P s.t. 2D equilibrium (moments about the origin),
    fn >= 0 at both ends of every joint, |ft| <= mu fn (no limit when mu is None)."""
    ro = ri + t
    th = np.pi * (1 - np.arange(n + 1) / n)
    c, s = np.cos(th), np.sin(th)
    c[[0, -1]], s[[0, -1]] = [-1.0, 1.0], 0.0
    # unknowns: joint j (0..n), end e (intrados, extrados), component (fn, ft); then P
    nv = 4 * (n + 1) + 1
    A = np.zeros((3 * n, nv))
    b = np.zeros(3 * n)
    for j in range(n + 1):
        nrm = np.array([s[j], -c[j]])  # tangent towards decreasing angle: from block j into j+1
        tan = np.array([-nrm[1], nrm[0]])
        for e, r in enumerate((ri, ro)):
            p = r * np.array([c[j], s[j]])
            for comp, d in enumerate((nrm, tan)):
                col = 4 * j + 2 * e + comp
                for blk, sign in ((j, 1.0), (j - 1, -1.0)):  # + on voussoir j (B), - on j-1 (A)
                    if 0 <= blk < n:
                        f = sign * d
                        A[3 * blk : 3 * blk + 3, col] += [f[0], f[1], p[1] * f[0] - p[0] * f[1]]
    for i in range(n):  # self-weight of voussoir i (1-based i + 1): a quadrilateral
        poly = np.array([[ri * c[i], ri * s[i]], [ri * c[i + 1], ri * s[i + 1]],
                         [ro * c[i + 1], ro * s[i + 1]], [ro * c[i], ro * s[i]]])
        x, z = poly[:, 0], poly[:, 1]
        cr = x * np.roll(z, -1) - np.roll(x, -1) * z
        area = cr.sum() / 2
        cx = ((x + np.roll(x, -1)) * cr).sum() / (6 * area)
        w = gamma * abs(area) * depth
        b[3 * i : 3 * i + 3] = -np.array([0.0, -w, cx * w])  # A F + P load + weight = 0; (0, -w) at (cx, cz)
    q = ro * np.array([(c[k - 1] + c[k]) / 2, (s[k - 1] + s[k]) / 2])  # extrados chord midpoint
    A[3 * (k - 1) : 3 * k, -1] = [0.0, -1.0, q[0]]  # (0, -1) at q: moment z fx - x fz = q_x
    bounds = [(0, None) if j % 2 == 0 else (None, None) for j in range(nv - 1)] + [(None, None)]
    A_ub, b_ub = [], []
    if mu is not None:
        for j in range(0, nv - 1, 2):
            for sign in (1.0, -1.0):
                row = np.zeros(nv)
                row[j + 1], row[j] = sign, -mu
                A_ub.append(row)
                b_ub.append(0.0)
    cost = np.zeros(nv)
    cost[-1] = -1.0
    res = linprog(cost, A_ub=np.array(A_ub) if A_ub else None, b_ub=b_ub or None, A_eq=A, b_eq=b, bounds=bounds,
                  method="highs", options=dict(primal_feasibility_tolerance=1e-10, dual_feasibility_tolerance=1e-10))
    assert res.status == 0, res.message
    return float(res.x[-1])


@pytest.mark.parametrize("mu", [None, 0.8])
@pytest.mark.parametrize("k", [4, 5, 6, 7])
def test_arch_point_load_against_an_independent_lp(arch, k, mu):
    reference = _arch_lp(k, mu)
    at = extrados_midpoint(k)
    by_block = point([0.0, 0.0, -1.0], block=f"v{k:02d}", at=at)
    on_top = point([0.0, 0.0, -1.0], on_top=at[:2])
    for model in ("auto", "spatial"):
        an = Analysis(arch, Material(mu), model=model)
        for pattern in (by_block, on_top):
            lim = an.limit(loads=pattern)
            assert lim.model == ("planar" if model == "auto" else "spatial")
            # the limit solver's tolerance is 1e-10 on the scaled problem (measured: <= 4e-10)
            assert lim.lambda_max == pytest.approx(reference, rel=1e-8)
            assert lim.certificate_gap < 1e-8
