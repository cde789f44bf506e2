"""Regression: the batched geometry, checks, contact data, model operators and mechanism
classification give the numbers of the per-block code they replaced.

``data/build_reference.npz`` was written on 2026-11-22 by the per-block implementation (tce at
commit 6b1b1bd, before issue 14's vectorisation) with the recording script
``tests/regression/build_reference.py``: block volumes,
centroids, face normals and sizes; interface frames, areas, centroids and tributary areas;
every operator of the spatial and planar models (``A_eq``, ``B_sup``, ``lift``, ``b_dead``,
``b_lat``, contact data, compliance); and the mechanism classification of the direct limit's
velocities and of a random velocity field. The cases cover the generators (semicircular,
pointed with a keystone, segmental on piers, closed and open domes) and files whose
interfaces are found by contact detection (a running-bond wall and four COMPAS samples).
Tolerance: 1e-12 relative to each array's largest entry.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import scipy.sparse as sp

from tce.core.limit import mechanism_from_velocities
from tce.core.model import build_model, find_plane

from .build_reference import CASES, MODEL_ARRAYS, MODEL_OPERATORS, assembly, canonical, geometry_arrays

REF = np.load(Path(__file__).parent / "data" / "build_reference.npz")
RTOL = 1e-12


def close(name: str, got, want=None) -> None:
    want = REF[name] if want is None else want
    got = np.asarray(got)
    assert got.shape == want.shape, name
    if want.dtype.kind in "fc":
        scale = max(float(np.nanmax(np.abs(want), initial=0.0)), 1e-300)
        np.testing.assert_allclose(got, want, rtol=0, atol=RTOL * scale, err_msg=name)
    else:
        np.testing.assert_array_equal(got, want, err_msg=name)


def sparse(name: str, M) -> None:
    C = canonical(M).tocsr()
    close(name + ".shape", np.array(C.shape))
    D = sp.csr_matrix((REF[name + ".data"], (REF[name + ".row"], REF[name + ".col"])), shape=tuple(REF[name + ".shape"]))
    scale = max(float(np.abs(D.data).max(initial=0.0)), 1e-300)
    assert abs(C - D).max() <= RTOL * scale, name


@pytest.fixture(scope="module", params=CASES)
def case(request):
    return request.param, assembly(request.param).validate()


def test_geometry_and_interfaces(case):
    name, a = case
    for key, value in geometry_arrays(a).items():
        close(f"{name}/{key}", value)
    # the batched tables give the same numbers as the objects one by one
    t = a.interface_table
    close(f"{name}/volume", a.volumes)
    close(f"{name}/itf_frame", t.frame)
    close(f"{name}/itf_area", t.area)
    close(f"{name}/itf_tributary", t.tributary)


def test_model_operators(case):
    name, a = case
    for kind in ("spatial", "planar"):
        key = f"{name}/{kind}"
        if f"{key}/kind" not in REF:
            assert kind == "planar" and find_plane(a) is None
            continue
        m = build_model(a, kind)
        close(f"{key}/kind", m.kind)
        for k in MODEL_ARRAYS:
            close(f"{key}/{k}", getattr(m, k))
        for k in MODEL_OPERATORS:
            sparse(f"{key}/{k}", getattr(m, k))
        close(f"{key}/compliance", m.compliance(1e6, 4e5))
        if m.plane is not None:
            close(f"{key}/plane_m", m.plane.m)
            close(f"{key}/plane_origin", m.plane.origin)


@pytest.mark.parametrize("which", ["mech0", "mech90"])
def test_mechanism_classification(case, which):
    name, a = case
    key = f"{name}/{which}"
    planar = which == "mech0" and find_plane(a) is not None
    m = build_model(a, "planar" if planar else "spatial")
    if f"{key}/vel_in" in REF:
        mech = mechanism_from_velocities(m, REF[f"{key}/vel_in"])
        close(f"{key}/vel_out", mech.velocities)
        close(f"{key}/modes", np.array(mech.modes))
        close(f"{key}/hinge_points", mech.hinge_points)
    mech = mechanism_from_velocities(m, REF[f"{key}/rand_in"])
    close(f"{key}/rand_out", mech.velocities)
    close(f"{key}/rand_modes", np.array(mech.modes))
    close(f"{key}/rand_hinge", mech.hinge_points)
