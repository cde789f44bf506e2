"""The slow-mode extrapolation of the non-associative scheme (tce.analysis.nonassoc.slow_mode_limit).

The extrapolation against a linear fixed-point map whose fixed point is known (the reference:
the map is built here, its fixed point is a closed form), the cases it must refuse, its
safeguard, and the fixed points it must leave alone (regression pins, measured 2026-11-24
before and after it: identical to the last digit). The groin vault it was written for is in
tests/battery/test_regressions.py.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from battery.transform import permuted
from core.test_materials import running_bond_wall
from helpers import equal_blocks_side_by_side

from tce import Analysis, LoadPattern, Material
from tce.analysis import nonassoc
from tce.analysis.nonassoc import nonassociative_limit, slow_mode_limit
from tce.structures.io import load_assembly

WALL = Path(__file__).resolve().parents[2] / "studies" / "data" / "wall.json"

W_RELAX = 0.5


def linear_sequence(rates, n_steps=60, dim=12, seed=1, turn=0.0):
    """The relaxed iterates of ``T(x) = x* + M (x - x*)``, ``M`` with the eigenvalues ``rates``
    (and 0 on the rest of the space) in a random orthonormal basis, from a random start;
    ``turn`` (radians) rotates the plane of the first two modes by that much a step.

    Returns the iterates ``x_j``, their steps ``T(x_j) - x_j``, ``lambda_j = 1 + a . (x_j -
    x*)`` (a load factor carried by the modes) and ``x*``."""
    rng = np.random.default_rng(seed)
    q, _ = np.linalg.qr(rng.normal(size=(dim, dim)))
    eig = np.zeros(dim)
    eig[: len(rates)] = rates
    D = np.diag(eig)
    D[:2, :2] = rates[0] * np.array([[np.cos(turn), -np.sin(turn)], [np.sin(turn), np.cos(turn)]]) if turn else D[:2, :2]
    M = q @ D @ q.T
    x_star = rng.normal(size=dim) * 10.0
    a = q[:, 0] * 0.01 + q[:, 1] * 0.002
    x = x_star + q[:, : len(rates)] @ rng.uniform(0.5, 1.0, len(rates))
    xs, ds, lams = [], [], []
    for _ in range(n_steps):
        d = (x_star + M @ (x - x_star)) - x
        xs.append(x.copy())
        ds.append(d)
        lams.append(1.0 + a @ (x - x_star))
        x = x + W_RELAX * d
    return np.array(xs), np.array(ds), np.array(lams), x_star


def window(xs, ds, lams, end):
    """The last seven plain steps before ``end`` (the scheme's window)."""
    k = nonassoc.ACCELERATION_DEPTH + 1
    return xs[end - k : end], ds[end - k : end], lams[end - k : end]


def test_limit_of_a_slow_linear_approach():
    """Two modes, the slow one of the groin vault (relaxed ratio 0.978: T's eigenvalue
    0.956) and a faster one: the plain relaxed steps after 30 iterations are still 0.5 away
    from the fixed point; the extrapolation from the last seven lands on it (to 1e-9 of its
    size: exact for a linear map of two modes)."""
    xs, ds, lams, x_star = linear_sequence([0.956, 0.7])
    guess = slow_mode_limit(*window(xs, ds, lams, 30), W_RELAX)
    assert guess is not None
    assert np.linalg.norm(xs[29] - x_star) > 0.1
    assert np.linalg.norm(guess - x_star) <= 1e-9 * np.linalg.norm(x_star)


def test_same_in_every_order_of_the_contacts():
    """The extrapolation permuted with the contacts (the scheme's frame independence)."""
    xs, ds, lams, _ = linear_sequence([0.956, 0.7])
    perm = np.random.default_rng(3).permutation(xs.shape[1])
    a = slow_mode_limit(*window(xs, ds, lams, 30), W_RELAX)
    b = slow_mode_limit(*window(xs[:, perm], ds[:, perm], lams, 30), W_RELAX)
    np.testing.assert_allclose(b, a[perm], rtol=0, atol=1e-9 * np.abs(a).max())


@pytest.mark.parametrize(
    ("case", "rates", "end", "turn"),
    [
        # lambda settles (its changes shrink by 0.84 a step, the walls' case) while the
        # normal forces creep: the polish step ends that approach, no extrapolation
        ("lambda settles", [0.956, 0.68], 40, 0.0),
        # the ratio of successive steps still drifts (spread 0.0075 over the window; steps
        # aligned to 0.9995 and lambda creeping)
        ("ratios drift", [0.956, 0.8], 8, 0.0),
        # the steps turn (a pair of complex eigenvalues: successive steps 0.075 rad apart,
        # cosine 0.9972), lambda creeping
        ("steps turn", [0.99, 0.99], 20, 0.15),
        # lambda speeds up while the steps contract (LACT3's wall before its lambda turns:
        # docs/materials.md): the approach is not yet linear
        ("lambda speeds up", [0.956, 0.7], 30, 0.0),
        # a growing step: no fixed point to extrapolate to
        ("diverging", [1.02], 30, 0.0),
    ],
)
def test_refused(case, rates, end, turn):
    """Each case fails one condition of the slow linear approach and meets the others."""
    xs, ds, lams, _ = linear_sequence(rates, turn=turn)
    if case == "lambda settles":
        # lambda carried by the 0.68-mode only (relaxed ratio 0.84)
        lams = 1.0 + 0.01 * 0.84 ** np.arange(len(lams))
    elif case == "lambda speeds up":
        lams = 1.0 + 0.01 * 1.03 ** np.arange(len(lams))
    elif case == "diverging":
        # lambda creeping as in the vault (only the growing steps fail)
        lams = 1.0 + 0.01 * 0.978 ** np.arange(len(lams))
    assert slow_mode_limit(*window(xs, ds, lams, end), W_RELAX) is None


def test_refused_where_lambda_turns_back():
    """lambda's changes over the window of both signs: not a creep along one mode."""
    xs, ds, lams, _ = linear_sequence([0.956, 0.7])
    x, d, lam = window(xs, ds, lams, 30)
    assert slow_mode_limit(x, d, lam, W_RELAX) is not None
    lam = lam.copy()
    lam[3] = lam[2] + 0.5 * (lam[2] - lam[1]) * -1.0
    assert slow_mode_limit(x, d, lam, W_RELAX) is None


def test_safeguard_falls_back_to_the_plain_step(monkeypatch):
    """A useless extrapolation (every capacity zero) offered wherever the window is full: the
    safeguard refuses it (the state of those capacities is further from a fixed point), the
    scheme goes on from the plain step it replaced, extrapolates no more, and reaches the
    same fixed point as without it, one iteration later (two blocks side by side, mu 0.8:
    26 iterations, 0.5000011)."""
    an = Analysis(equal_blocks_side_by_side(), Material(0.8, flow="non-associative"))
    plain = nonassociative_limit(an, 0.0)
    offered = []

    def useless(fn, steps, lambdas, relaxation):
        offered.append(len(fn))
        return np.zeros(fn.shape[1])

    monkeypatch.setattr(nonassoc, "slow_mode_limit", useless)
    r = nonassociative_limit(an, 0.0)
    assert len(offered) == 1 and r.status == "converged"
    assert r.iterations == plain.iterations + 1
    assert r.lambda_nonassoc == pytest.approx(plain.lambda_nonassoc, abs=1e-7)


@pytest.mark.parametrize(
    ("build", "mu", "iterations", "expected"),
    [
        # (measured before and after the extrapolation, 2026-11-24: unchanged to the last digit;
        # the two blocks one iteration later and 3e-7 nearer to 0.5 since lambda must settle
        # over two changes, 2026-11-27; the wall 7 and the blocks at mu 0.6 one iteration later
        # since a creep must end within tol, the wall 2e-6 lower, 2026-11-27)
        (running_bond_wall, 0.65, 44, 0.6399694),
        (equal_blocks_side_by_side, 0.6, 24, 0.5000007),
        (equal_blocks_side_by_side, 0.8, 26, 0.5000011),
    ],
)
def test_fixed_points_left_alone(build, mu, iterations, expected):
    """The fixed points published in docs/materials.md where lambda settles before the
    normal forces do (the polish step ends those approaches): the extrapolation does not
    start there. Regression pins."""
    r = nonassociative_limit(Analysis(build(), Material(mu, flow="non-associative")), 0.0)
    assert r.status == "converged" and r.iterations == iterations
    assert r.lambda_nonassoc == pytest.approx(expected, abs=1e-7)


def test_same_in_every_order_of_blocks_and_interfaces():
    """The block-file wall under the lateral pattern at 225 degrees (spatial model, mu 0.5):
    its scheme creeps towards lambda 0, halving lambda every step, where the nearest state
    sought 1e-8 (relative) below a lambda of 5e-5 failed in some orders and the solver's own
    state restarted the scheme (issue 36: 2e-7 in one order, 2.3e-5 to 3.1e-5 after a slow
    creep in others). Five shuffled orders (every other interface read from its other side,
    as tests/battery/test_relations.py does) give the same status and lambda to the
    scheme's ``tol`` (1e-6, absolute below 1)."""
    asm = load_assembly(WALL, supports=["base"])
    material, loads = Material(0.5, flow="non-associative"), LoadPattern(alpha=225.0)
    reference = nonassociative_limit(Analysis(asm, material), loads=loads)
    assert reference.status == "converged"
    rng = np.random.default_rng(0)
    swap = [k % 2 == 1 for k in range(len(asm.interfaces))]
    for _ in range(5):
        shuffled = permuted(asm, rng.permutation(len(asm.blocks)), rng.permutation(len(asm.interfaces)), swap)
        r = nonassociative_limit(Analysis(shuffled, material), loads=loads)
        assert r.status == reference.status
        assert r.lambda_nonassoc == pytest.approx(reference.lambda_nonassoc, abs=1e-6)
