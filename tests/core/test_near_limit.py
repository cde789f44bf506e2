"""Solves next to a limit: Clarabel's verdict and tce's residual check agree.

The scene is the cross-feature battery's (``tests/battery/test_regressions.py::
test_load_path_near_the_limit_is_decided``): the paper's arch of 8 voussoirs, mu = 0.8,
compressive strength 3000 kN/m^2, a live load of a tenth of the weight on the extrados above
the third free block, the right support moved 1 mm across and turned 2e-4 rad (spatial
model). Its direct lambda_max is 4.4528840 (measured on branch hdef, 2026-11-24).
"""

from __future__ import annotations

import numpy as np

from tce.core.analysis import Analysis
from tce.core.loads import LoadPattern, PointLoad
from tce.core.material import Material
from tce.structures.arch import semicircular_arch


def _scene() -> tuple[Analysis, LoadPattern, dict[str, list[float]]]:
    asm = semicircular_arch(voussoirs=8).validate()
    free = asm.free_indices
    c = asm.centroids[free[len(free) // 3]]
    load = PointLoad(force=(0.0, 0.0, -0.1 * asm.total_weight), on_top=(c[0], c[1]))
    pattern = LoadPattern(alpha=30.0, lateral=False, point=[load])
    settlements = {asm.support_names[-1]: [0.0, 1e-3, 0.0, 2e-4, 0.0, 0.0]}
    return Analysis(asm, Material(friction=0.8, compressive_strength=3000.0)), pattern, settlements


def test_a_solved_answer_passes_the_residual_check_with_large_strength_offsets() -> None:
    """Clarabel's primal residual is relative to ``1 + |b| + |x| + |s|`` (inf-norms); the
    crushing rows' offsets ``fc A / W`` (11 here) and their slacks made that about 23, so a
    `Solved` answer could miss tce's absolute ``residual_tol`` (1e-9) and cost two retries:
    before the fix 2 of these 13 fresh solves (1 to 4e-6 below the limit) were `Solved` yet
    failed the check (residuals up to 1.4e-9). The feasibility tolerance now accounts for
    ``max |b|`` (:meth:`tce.core.clarabel_solver.SolverOptions.settings`)."""
    _, pattern, settlements = _scene()
    direct = 4.452883972484937
    for d in np.linspace(1e-6, 4e-6, 13):
        an, _, _ = _scene()  # a fresh solver each time: its first answer is Clarabel's own
        r = an.solve(direct - d, settlements=settlements, loads=pattern)
        assert r.status == "optimal", r.message
        assert not r.message.startswith("clarabel: Solved; residual check failed"), (d, r.message)
