"""Memory and time of one large model, stage by stage (docs/scaling.md, "One machine").

:func:`dome_stages` builds a hemispherical dome of ``n`` sectors and ``n`` courses and solves
its direct lambda_max (3D SOCP, mu = 0.8, alpha = 0) the way :class:`tce.core.limit.LimitSolver`
does first (no iterative refinement, the model's KKT method), recording after each stage the
process's resident memory and its peak so far (Linux ``/proc/self/status``: ``VmRSS``,
``VmHWM``) and the CPU time the stage took. Run it in a fresh process (``python -m
tce.quality.scale N``) so that the peak is this model's.

The generators refuse more than :data:`tce.structures.params.MAX_BLOCKS` blocks; ``max_blocks``
raises that limit in this process only (a 100,172-block dome is ``n = 316``).
"""

from __future__ import annotations

import json
import sys
import time
from typing import Any

__all__ = ["dome_stages", "memory"]


def memory() -> tuple[float, float]:
    """``(resident, peak resident)`` memory of this process (GB), from ``/proc/self/status``."""
    got = {}
    with open("/proc/self/status") as fh:
        for line in fh:
            key, _, value = line.partition(":")
            if key in ("VmRSS", "VmHWM"):
                got[key] = int(value.split()[0]) / 1e6  # kB
    return got["VmRSS"], got["VmHWM"]


def dome_stages(n: int, max_blocks: int | None = None) -> dict[str, Any]:
    """Stages of building and solving the ``n x n`` dome (module docstring).

    Returns
    -------
    dict
        ``stages``: list of ``{stage, cpu_s, rss_gb, peak_gb}``; the sizes (``n_blocks``,
        ``n_contacts``, ``n_vars``, ``rows``, ``nnz_A``), ``status``, ``iterations`` and
        ``lambda_max`` of the solve.
    """
    import numpy as np

    from ..core.clarabel_solver import ClarabelSolver, SolverOptions
    from ..core.material import Material
    from ..core.model import build_model
    from ..core.problem import Formulation, limit_problem
    from ..structures import params
    from ..structures.dome import hemispherical_dome

    if max_blocks is not None:
        params.MAX_BLOCKS = max_blocks
    stages: list[dict[str, Any]] = []
    clock = [time.process_time()]

    def mark(name: str) -> None:
        now = time.process_time()
        rss, peak = memory()
        stages.append(dict(stage=name, cpu_s=now - clock[0], rss_gb=rss, peak_gb=peak))
        clock[0] = now

    mark("imports")
    assembly = hemispherical_dome(sectors=n, courses=n).validate()
    mark("assembly generated and checked")
    model = build_model(assembly, "spatial")
    mark("model's operators built")
    f = Formulation(model, Material(friction=0.8))
    mark("formulation")
    problem = limit_problem(f, model.b_dead, model.b_lateral(0.0))
    mark("[A_eq; -M] and the limit problem")
    solver = ClarabelSolver(problem, SolverOptions(tol=1e-10, max_iter=500).settings(refine=False, kkt=f.kkt))
    mark("Clarabel set up")
    sol = solver.solve()
    mark("Clarabel solved")
    return dict(
        stages=stages, n_blocks=len(assembly.blocks), n_contacts=model.n_contacts, n_vars=model.n_vars,
        rows=problem.A.shape[0], nnz_A=int(problem.A.nnz), status=sol.status, iterations=sol.iterations,
        lambda_max=float(sol.x[-1]) if sol.solved else float(np.nan),
    )


if __name__ == "__main__":  # pragma: no cover - the measuring process of docs/scaling.md
    size = int(sys.argv[1])
    print(json.dumps(dome_stages(size, max_blocks=max(size * (size + 1), 50_000))))
