"""Finite settlements against references tce did not produce: the semicircular arch on
symmetric spreading supports worked out by hinge kinematics with a thrust-line check on the
deformed geometry (tests/reference/spreading.py, after Ochsendorf 2002, 2006), and the small
magnitude limit against today's TCE and limit analysis."""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import pytest

from reference import spreading as rs
from tce.analysis import Analysis
from tce.analysis.settlement_path import settlement_path
from tce.structures.arch import semicircular_arch

SPREAD = {"left": [-1.0, 0, 0, 0, 0, 0], "right": [1.0, 0, 0, 0, 0, 0]}  # 1 m outward per support


def arch(t_over_r: float, n: int):
    """Centreline radius 1 m, thickness t (m), depth 0.25 m, n voussoirs."""
    return semicircular_arch(inner_radius=1.0 - t_over_r / 2, thickness=t_over_r, voussoirs=n)


@lru_cache(maxsize=None)
def path(t_over_r: float, n: int, increment: float = 0.004):
    return settlement_path(arch(t_over_r, n), SPREAD, increment=increment, s_max=0.5)


#: (0.225, 72) snaps: about 30 CPU-s, most of it following its falls (docs/performance.md), run with -m slow
@pytest.mark.parametrize("t_over_r, n", [(0.12, 36), (0.15, 36), (0.2, 36), (0.25, 36), (0.15, 72), (0.13, 72),
                                         pytest.param(0.225, 72, marks=pytest.mark.slow)])
def test_capacity_brackets_the_hinge_kinematics(t_over_r, n):
    """The reference's capacity (each support's outward motion at which the thrust line of
    the three hinges leaves the deformed arch, the haunch hinge moving to a neighbouring
    joint when that one stands) lies in tce's final bracket, at most increment / 64 wide;
    the path's hinges are the reference's, and so are the motions at which a hinge moved
    (t/R = 0.13 with 72 voussoirs: from 32.5 to 35 degrees above the springing; t/R = 0.225:
    from 27.5 to 30 degrees, the blocks turning back by about the hinge's opening to close it)."""
    u_ref, hinges, snaps = rs.path_capacity(1.0, t_over_r, n)
    r = path(t_over_r, n)
    width = 0.004 / 64 + 1e-12
    assert r.status == "collapse", r.message
    assert r.upper - r.capacity <= width
    assert r.capacity - 1e-9 <= u_ref <= r.upper + 1e-9
    assert r.hinges[0] == [n // 2 - hinges[0], n // 2, n // 2 + hinges[0]]
    assert r.hinges[-1] == [n // 2 - hinges[-1], n // 2, n // 2 + hinges[-1]]
    assert len(r.snaps) == len(snaps)
    for got, want in zip(r.snaps, snaps):
        assert want - 1e-9 <= got <= want + width


@pytest.mark.parametrize("t_over_r, n", [(0.15, 36), (0.25, 36)])
def test_thrust_follows_the_deformed_thrust_line(t_over_r, n):
    """At every standing magnitude, tce's thrust (per unit weight of the arch) is the
    reference's thrust through the three hinges of the deformed geometry, and the thrust line
    is inside the arch there."""
    r = path(t_over_r, n)
    half = rs.HalfArch.of(1.0, t_over_r, n)
    j = half.hinge()
    assert not r.snaps
    W = r.reactions[0, 0, 1] + r.reactions[0, 1, 1]  # total vertical reaction: the arch's weight
    for s, reac in zip(r.magnitudes, r.reactions):
        ok, H, _ = half.deformed(j, s).check(j, tol=1e-9)
        assert ok
        # rel 1e-7: HiGHS's primal and dual feasibility tolerance (the thrust is a dual value)
        assert reac[0, 0] / W == pytest.approx(H / (2 * half.w.sum()), rel=1e-7)
        assert reac[1, 0] == pytest.approx(-reac[0, 0], rel=1e-9)


@pytest.mark.parametrize(
    "motion",
    [
        SPREAD,
        {"right": [0.0, 0, -1.0, 0, 0, 0]},
        {"right": [0.0, 0, 0, 0, 1.0, 0]},
        {"left": [0.0, 0, 0, 0, -1.0, 0], "right": [0.5, 0, 0.2, 0, 0, 0]},
    ],
    ids=["spread", "sink", "rotate", "mixed"],
)
def test_small_magnitude_limit_is_todays_tce(motion):
    """At s = 0 the path's state is the TCE of the undeformed arch under the same motion
    (the support wrenches of tce's conic solver: its objective is the thrust's work, so a
    wrong sign of a translation or a rotation shows), and its lambda_max tce's direct limit."""
    a = arch(0.15, 36)
    r = settlement_path(a, motion, increment=0.004, s_max=0.004, lam=True)
    an = Analysis(a)
    tce = an.solve(settlements={k: 1e-3 * np.asarray(v) for k, v in motion.items()})
    assert tce.status == "optimal"
    w = tce.support_wrenches  # (Fx, Fy, Fz, Mx, My, Mz) per support; the path's (Rx, Rz, M), M = -My
    scale = np.abs(w).max()
    np.testing.assert_allclose(r.reactions[0][:, 0], w[:, 0], atol=1e-6 * scale)
    np.testing.assert_allclose(r.reactions[0][:, 1], w[:, 2], atol=1e-6 * scale)
    np.testing.assert_allclose(r.reactions[0][:, 2], -w[:, 4], atol=1e-6 * scale)
    assert r.lambda_max[0] == pytest.approx(an.limit(0.0).lambda_max, rel=1e-7)


def test_halving_the_increment_moves_the_capacity_less_than_1e_3():
    """The convergence check of docs/settlements.md on one arch."""
    a = path(0.15, 36, 0.004)
    b = path(0.15, 36, 0.002)
    assert abs(a.capacity - b.capacity) < 1e-3


@pytest.mark.slow
def test_a_snap_is_followed_as_far_as_the_hinge_opened():
    """t/R = 0.225 with 72 voussoirs snaps (its haunch hinge moves from 27.5 to 30 degrees)
    by turning its blocks back by the opening of the hinge it closes; the fall is followed
    to twice the widest opening whatever ``snap_limit`` says, so a small limit (0.05 rad,
    below that opening) still reaches the reference's capacity, with the same snap."""
    u_ref, _, snaps = rs.path_capacity(1.0, 0.225, 72)
    r = settlement_path(arch(0.225, 72), SPREAD, increment=0.004, s_max=0.5, snap_limit=0.05)
    assert r.status == "collapse" and len(r.snaps) == len(snaps) == 1
    assert r.capacity <= u_ref + 1e-6 and u_ref <= r.upper + 1e-6
