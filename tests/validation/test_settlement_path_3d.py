"""The finite-settlement path in space (``settlement_path`` on spatial assemblies).

Validation: Rodrigues' rotation against scipy's (an independent implementation); the
semicircular arch followed in space (six dofs per block, four contact points per joint)
against the independent hinge kinematics of tests/reference/spreading.py and against its own
planar path; the dome's first state against today's TCE (tce's conic solver). Regression
pins (measured on this branch, 2026-11-24): the coarse dome's capacity under a uniform
radial spread, and the block-file arch of studies/arch_file_spreading.toml.
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from scipy.spatial.transform import Rotation

from reference import spreading as rs
from tce.analysis import Analysis
from tce.analysis.settlement_path import settlement_path
from tce.structures.arch import semicircular_arch
from tce.structures.dome import hemispherical_dome, radial_settlement
from tce.study.runner import run_study
from tce.study.schema import load_study

STUDIES = Path(__file__).resolve().parents[2] / "studies"
SPREAD = {"left": [-1.0, 0, 0, 0, 0, 0], "right": [1.0, 0, 0, 0, 0, 0]}


@lru_cache(maxsize=None)
def arch_paths():
    a = semicircular_arch(inner_radius=0.925, thickness=0.15, voussoirs=36)
    return {m: settlement_path(a, SPREAD, increment=0.004, s_max=0.5, lam=True, model=m) for m in ("auto", "spatial")}


def test_arch_in_space_brackets_the_hinge_kinematics():
    """t/R = 0.15, 36 voussoirs, followed in space: the reference capacity lies in the final
    bracket (increment / 64 wide), the hinges are the reference's three."""
    u_ref, hinges, _ = rs.path_capacity(1.0, 0.15, 36)
    r = arch_paths()["spatial"]
    assert r.plane is None and r.status == "collapse"
    assert r.capacity <= u_ref + 1e-6 and u_ref <= r.upper + 1e-6
    assert r.upper - r.capacity <= 0.004 / 64 + 1e-12
    assert r.hinges[0] == [6, 18, 30]


def test_arch_in_space_equals_its_planar_path():
    """Same magnitudes, in-plane reactions (the out-of-plane tangential forces of a rigid
    Heyman arch are statically indeterminate: not compared), block motions and lambda_max."""
    plane, space = arch_paths()["auto"], arch_paths()["spatial"]
    np.testing.assert_allclose(space.magnitudes, plane.magnitudes, atol=1e-12)
    wp, ws = plane.wrenches(), space.wrenches()
    scale = np.abs(wp).max()
    np.testing.assert_allclose(ws[..., [0, 2, 4]], wp[..., [0, 2, 4]], atol=1e-6 * scale)
    np.testing.assert_allclose(space.displacements(), plane.displacements(), atol=1e-9)
    np.testing.assert_allclose(space.lambda_max, plane.lambda_max, rtol=1e-6)


def dome():
    return hemispherical_dome(radius=5.0, thickness=0.5, sectors=8, courses=4)


@lru_cache(maxsize=None)
def dome_path(increment: float):
    return settlement_path(dome(), radial_settlement(dome(), 1.0), increment=increment, s_max=2.0)


def test_dome_first_state_is_todays_tce():
    """At s = 0 the work of the reactions on the motion, -sum R_s . U_s (the TCE the path
    minimises; unique, unlike the share of each support), equals tce's conic TCE solve."""
    d = dome()
    U = radial_settlement(d, 1.0)
    r = dome_path(0.02)
    an = Analysis(d)
    tce = an.solve(settlements={k: 1e-3 * np.asarray(v) for k, v in U.items()})
    assert tce.status == "optimal"
    names = d.support_names
    u = np.array([U[n] for n in names])
    mine = -np.einsum("sj,sj->", r.wrenches()[0], u)
    theirs = -np.einsum("sj,sj->", tce.support_wrenches, u)
    assert mine == pytest.approx(theirs, rel=1e-6)
    assert r.wrenches()[0][:, 2].sum() == pytest.approx(d.weights[list(d.free_indices)].sum(), rel=1e-9)


def test_dome_radial_spread_cracks_symmetrically_and_converges():
    """The lunes: every meridian joint opens, each lune hinges at the intrados of its
    course 1|2 joint and at the extrados of its course 3|4 joint; the eight sectors move
    alike (rotational symmetry); halving the increment moves the last standing magnitude
    less than 1e-3, and nothing stands one bracket (increment / 64) beyond it. Pin: 0.74781 m
    of radial spread (measured here with both increments). Beyond it the lunes fall; HiGHS
    (1.x with scipy 1.17) fails on the program of the configuration where their fall closes
    a joint, so whether they come to rest there is undecided: ``numerical``, never a collapse
    (``collapse`` once HiGHS decides it)."""
    a, b = dome_path(0.02), dome_path(0.01)
    for r, h in ((a, 0.02), (b, 0.01)):
        assert r.status in ("collapse", "numerical"), r.message
        assert r.status == "collapse" or "HiGHS" in r.message, r.message
        assert 0 < r.upper - r.magnitudes[-1] <= h / 64 + 1e-12
    assert abs(a.magnitudes[-1] - b.magnitudes[-1]) < 1e-3
    assert b.magnitudes[-1] == pytest.approx(0.74781, abs=2e-4)
    d = dome()
    disp = b.displacements()[-1]
    # sector j's blocks are sector 1's turned by 45 j degrees about z
    for course in range(1, 5):
        ref = disp[d.index[f"c{course:02d}s01"]]
        for j in range(1, 8):
            R = Rotation.from_euler("z", 45.0 * j, degrees=True).as_matrix()
            got = disp[d.index[f"c{course:02d}s{j + 1:02d}"]]
            np.testing.assert_allclose(got[:3], R @ ref[:3], atol=1e-7)
            np.testing.assert_allclose(got[3:], R @ ref[3:], atol=1e-7)
    radius = {k: np.linalg.norm(b.hinge_points[0, k]) for k in b.hinges[0]}
    names = {k: (d.names[d.interfaces[k].a], d.names[d.interfaces[k].b]) for k in radius}
    base = [radius[k] for k, (p, q) in names.items() if p[:3] == "c01" and q[:3] == "c02"]
    crown = [radius[k] for k, (p, q) in names.items() if p[:3] == "c03" and q[:3] == "c04"]
    assert len(base) == len(crown) == 8
    np.testing.assert_allclose(base, 4.75, atol=1e-9)  # intrados
    np.testing.assert_allclose(crown, 5.25, atol=1e-9)  # extrados


def test_dome_lateral_capacity_is_never_a_spurious_strength():
    """Issue 37 item 5. At s = 0 the path's lateral capacity is tce's direct lambda_max of the
    undeformed dome (1.718). Once the base has spread, the no-sliding rows of the lunes' joints
    lock motions that the reference allows; the lateral program then read 2.13 at 1 cm of
    spread, carried by tangential forces of hundreds of times the dome's weight. Every value
    after s = 0 is NaN (the message says why: withheld as a spurious strength, or HiGHS
    failed) or within O(spread) of the undeformed one, for both contact rules, a spread of
    1e-6 m included; at 1 cm the gap rule's value is withheld."""
    d = dome()
    U = radial_settlement(d, 1.0)
    direct = Analysis(d).limit(alpha=0.0)
    assert direct.status == "optimal" and direct.lambda_max == pytest.approx(1.7184, abs=1e-4)
    paths = [settlement_path(d, U, lam=True, **kwargs) for kwargs in (
        dict(increment=0.01, s_max=0.03), dict(increment=0.01, s_max=0.03, contact_gap=0.0), dict(increment=1e-6, s_max=1e-6))]
    for r in paths:
        assert r.lambda_max[0] == pytest.approx(direct.lambda_max, rel=1e-7)
        later, s = r.lambda_max[1:], r.magnitudes[1:]
        known = np.isfinite(later)
        assert (later[known] <= direct.lambda_max * (1 + 10 * s[known] / d.size)).all(), later
        assert known.all() or "lateral capacity NaN" in r.message, r.message
    assert np.isnan(paths[0].lambda_max[1]) and "spurious strength" in paths[0].message


@pytest.mark.parametrize(
    "study, outcomes, standing",
    [("dome_spreading.toml", ("collapse", "numerical"), 0.74781), ("arch_file_spreading.toml", ("collapse",), 0.22825)],
    ids=["dome", "block_file"],
)
def test_study_files_run_the_path(study, outcomes, standing, tmp_path):
    """The dome's radial spread and a user's block file run from their study files (pins of
    the last standing magnitude measured here, the capacity of a collapse; the file's arch is
    compas_dem's, studies/data). The dome's fall is undecided by HiGHS (see above)."""
    report = run_study(load_study(STUDIES / study), out=tmp_path, jobs=1, plots=False)
    ds = xr.open_dataset(report.results)
    outcome = str(ds.settlement_outcome.values[0])
    assert outcome in outcomes
    assert float(ds.settlement_magnitude.max()) == pytest.approx(standing, abs=2e-4)
    if outcome == "collapse":
        assert float(ds.settlement_capacity.values[0]) == pytest.approx(standing, abs=2e-4)
    assert ds.settlement_reaction.dims == ("scenario", "settlement_step", "support", "component")
