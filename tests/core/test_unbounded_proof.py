"""An undecided direct limit is decided as unbounded only by a proof tce checks itself.

:meth:`tce.core.limit.LimitSolver._unbounded_proof`: a live-load ray (the least-force state
carrying the live load alone under the homogeneous law) and an admissible state at lambda = 0
(phase-1). The wall is ``studies/data/wall.json`` with its base as support (the battery's
block file), under a live vertical point load on its block 'B3' of a tenth of its weight.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from tce.core.analysis import Analysis
from tce.core.loads import LoadPattern, PointLoad, scene_vectors
from tce.core.material import Material
from tce.structures.arch import semicircular_arch
from tce.structures.assembly import Assembly
from tce.structures.io import load_assembly

WALL = Path(__file__).resolve().parents[2] / "studies" / "data" / "wall.json"


def _wall() -> tuple[Assembly, LoadPattern]:
    asm = load_assembly(WALL, supports=["base"]).validate()
    k = asm.free_indices[len(asm.free_indices) // 3]
    load = PointLoad(force=(0.0, 0.0, -0.1 * asm.total_weight), block=asm.names[k])
    return asm, LoadPattern(lateral=False, point=[load])


def _limit_solver(an: Analysis, pattern: LoadPattern):
    an.limit(loads=pattern)
    (solver,) = an._limit_solvers.values()
    return solver


def test_the_wall_turned_by_any_angle_has_no_limit() -> None:
    """Turned by 88.96 degrees the limit solve ended ``AlmostDualInfeasible`` (Clarabel's
    ray residual 3.7e-9 of its size, measured on branch hdef) and the limit was `numerical`:
    the proof decides it. At the other angles Clarabel's own certificate does."""
    from battery.transform import Similarity

    asm, pattern = _wall()
    for angle in (0.0, 30.0, 88.95955609983429, 90.0):
        turned = Similarity.rotation(angle).assembly(asm)
        lim = Analysis(turned, Material(), model="spatial").limit(loads=pattern)
        assert lim.status == "unbounded" and math.isinf(lim.lambda_max), (angle, lim.message)


def test_the_proof_needs_the_ray_and_the_fixed_loads_carried() -> None:
    """The proof is refused when the live load alone is not carried (the paper's arch under
    its lateral pattern, a finite limit) and when the fixed loads are not (the wall pushed
    sideways by ten times its weight as a fixed load: a ray exists, no admissible state)."""
    asm, pattern = _wall()
    an = Analysis(asm, Material(), model="spatial")
    solver = _limit_solver(an, pattern)
    _, b_fixed, b_live = scene_vectors(solver.model, None, pattern)
    assert "live load alone is carried" in solver._unbounded_proof(b_fixed, b_live)
    pushed = b_fixed + 10.0 * solver.model.b_lateral(0.0)
    assert solver._unbounded_proof(pushed, b_live) == ""
    arch = Analysis(semicircular_arch(voussoirs=8).validate(), Material())
    lateral = LoadPattern()
    arch_solver = _limit_solver(arch, lateral)
    _, b_fixed, b_live = scene_vectors(arch_solver.model, None, lateral)
    assert arch_solver._unbounded_proof(b_fixed, b_live) == ""
    assert np.isfinite(arch.limit(loads=lateral).lambda_max)


def test_a_ray_that_misses_the_residual_tolerance_proves_nothing(monkeypatch) -> None:
    """A ray whose equilibrium residual or law violation exceeds ``residual_tol`` (1e-9 of
    the weight) is no proof, whatever the rest says."""
    asm, pattern = _wall()
    solver = _limit_solver(Analysis(asm, Material(), model="spatial"), pattern)
    _, b_fixed, b_live = scene_vectors(solver.model, None, pattern)
    F, eq, law = solver._ray(b_live, np.ones(solver.model.n_contacts, dtype=bool))
    assert max(eq, law) <= 1e-12
    for bad in ((F, 2e-9, law), (F, eq, 2e-9)):
        monkeypatch.setattr(solver, "_ray", lambda *args, bad=bad: bad)
        assert solver._unbounded_proof(b_fixed, b_live) == ""
