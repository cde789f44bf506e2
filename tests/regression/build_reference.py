"""The cases of ``test_build_vectorised.py`` and the script that recorded its reference numbers.

Run from the repository root as ``python -m tests.regression.build_reference OUT.npz``. The
pinned ``data/build_reference.npz`` was written by this script on 2026-11-22 against tce at
commit 6b1b1bd (the per-block geometry, checks and model building that issue 14 replaced).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import scipy.sparse as sp

from tce.core.limit import LimitSolver, mechanism_from_velocities
from tce.core.material import Material
from tce.core.model import build_model, find_plane
from tce.structures.arch import pointed_arch, segmental_arch, semicircular_arch
from tce.structures.assembly import Assembly
from tce.structures.dome import hemispherical_dome
from tce.structures.io import load_assembly

ROOT = Path(__file__).resolve().parents[2]
SAMPLES = ROOT / "tce" / "data" / "assemblies"

CASES = ["arch16", "pointed7", "segmental5", "dome6x4", "dome5x3oc", "wall", "bridge", "cubes", "shelf", "typeb"]


def assembly(name: str) -> Assembly:
    """The assembly of case ``name``."""
    builders = {
        "arch16": lambda: semicircular_arch(),
        "pointed7": lambda: pointed_arch(voussoirs=7),
        "segmental5": lambda: segmental_arch(voussoirs=5, pier_height=0.7),
        "dome6x4": lambda: hemispherical_dome(sectors=6, courses=4),
        "dome5x3oc": lambda: hemispherical_dome(sectors=5, courses=3, oculus=20.0),
        "wall": lambda: load_assembly(ROOT / "studies" / "data" / "wall.json", supports=["base"]),
        "bridge": lambda: load_assembly(SAMPLES / "bridge.json", supports=[0, 1]),
        "cubes": lambda: load_assembly(SAMPLES / "cubes.json", supports=[0]),
        "shelf": lambda: load_assembly(SAMPLES / "shelf.json", supports=[0]),
        "typeb": lambda: load_assembly(SAMPLES / "type-b.json", supports=[0, 1]),
    }
    return builders[name]()


def geometry_arrays(a: Assembly) -> dict[str, np.ndarray]:
    """Block and interface measures of ``a``, computed one object at a time."""
    return {
        "volume": np.array([b.volume for b in a.blocks]),
        "centroid": a.centroids,
        "face_normals": np.vstack([b.shape.face_normals for b in a.blocks]),
        "size": np.array([b.shape.size for b in a.blocks]),
        "asm_size": np.asarray(a.size),
        "itf_ab": np.array([[i.a, i.b] for i in a.interfaces]),
        "itf_normal": np.array([i.normal for i in a.interfaces]),
        "itf_frame": np.array([i.frame for i in a.interfaces]),
        "itf_area": np.array([i.area for i in a.interfaces]),
        "itf_centroid": np.array([i.centroid for i in a.interfaces]),
        "itf_points": np.vstack([i.points for i in a.interfaces]),
        "itf_npts": np.array([len(i.points) for i in a.interfaces]),
        "itf_tributary": np.concatenate([i.tributary for i in a.interfaces]),
    }


#: dense arrays of a model compared one to one
MODEL_ARRAYS = ("contact_interface", "contact_points", "contact_area", "tangents", "b_dead", "b_lat",
                "vertex_interface", "vertex_points", "interfaces")
#: sparse operators of a model, stored as COO (row, col, data, shape) without explicit zeros
MODEL_OPERATORS = ("A_eq", "B_sup", "lift")


def canonical(M: sp.spmatrix) -> sp.coo_matrix:
    """``M`` with duplicates summed, explicit zeros dropped and entries in row order."""
    C = sp.coo_matrix(M)
    C.sum_duplicates()
    C = C.tocsr()
    C.sort_indices()
    C.eliminate_zeros()
    return C.tocoo()


def record(path: str | Path) -> None:
    """Write the reference arrays of every case to ``path`` (npz)."""
    out: dict[str, np.ndarray] = {}

    def put(key: str, val) -> None:
        out[key] = np.asarray(val)

    def mech(prefix: str, m, alpha: float) -> None:
        r = LimitSolver(m, Material(friction=0.8)).solve(alpha)
        if r.mechanism is not None:
            mm = mechanism_from_velocities(m, r.mechanism.velocities)
            put(f"{prefix}/vel_in", r.mechanism.velocities)
            put(f"{prefix}/vel_out", mm.velocities)
            put(f"{prefix}/modes", np.array(mm.modes))
            put(f"{prefix}/hinge_points", mm.hinge_points)
        vr = np.random.default_rng(0).standard_normal((len(m.assembly.blocks), 6))
        vr[list(m.assembly.support_indices)] = 0
        mr = mechanism_from_velocities(m, vr)
        put(f"{prefix}/rand_in", vr)
        put(f"{prefix}/rand_out", mr.velocities)
        put(f"{prefix}/rand_modes", np.array(mr.modes))
        put(f"{prefix}/rand_hinge", mr.hinge_points)

    for name in CASES:
        a = assembly(name).validate()
        for k, v in geometry_arrays(a).items():
            put(f"{name}/{k}", v)
        planar = find_plane(a) is not None
        for kind in ("spatial", "planar") if planar else ("spatial",):
            m = build_model(a, kind)
            key = f"{name}/{kind}"
            put(f"{key}/kind", m.kind)
            for k in MODEL_ARRAYS:
                put(f"{key}/{k}", getattr(m, k))
            for k in MODEL_OPERATORS:
                C = canonical(getattr(m, k))
                for part, val in (("row", C.row), ("col", C.col), ("data", C.data), ("shape", C.shape)):
                    put(f"{key}/{k}.{part}", val)
            put(f"{key}/compliance", m.compliance(1e6, 4e5))
            if m.plane is not None:
                put(f"{key}/plane_m", m.plane.m)
                put(f"{key}/plane_origin", m.plane.origin)
        spatial = build_model(a, "spatial")
        mech(f"{name}/mech90", spatial, 90.0)
        mech(f"{name}/mech0", build_model(a, "planar") if planar else spatial, 0.0)
    np.savez_compressed(path, **out)


if __name__ == "__main__":  # pragma: no cover
    record(sys.argv[1])
