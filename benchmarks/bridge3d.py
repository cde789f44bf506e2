"""Time of the three-dimensional arch bridge's direct lambda_max against its number of blocks
(courses x voussoirs; development benchmark): the 8 m, 30-degree skew bridge of
``studies/bridge_skew30_lm1.toml`` (running bond, friction 0.6, compressive strength 5 MPa,
0.5 m of fill) under the LM1 tandem of lane 1 on the line y = -1.5 m. Per size: the generator,
the first limit (the spatial model built, the loads resolved, one SOCP), and the median of the
limits at other positions of the tandem (each a critical-position search's unit of work: loads
resolved again, one SOCP) with the share of that time spent in Clarabel's solve; then, on the
smallest sizes, a whole critical-position search along x (its limit solves and time).

Usage: ``python benchmarks/bridge3d.py [--quick | --large]``.
"""

from __future__ import annotations

import argparse
import time
from typing import Any

import pandas as pd

from tce.analysis.critical import critical_position
from tce.core.analysis import Analysis
from tce.core.clarabel_solver import ClarabelSolver
from tce.core.loads import LoadPattern
from tce.core.material import Material
from tce.core.vehicles import eurocode_lm1_tandem
from tce.quality.bench import COLUMNS, report, row
from tce.structures.bridge import arch_bridge

MATERIAL = Material(friction=0.6, compressive_strength=5000.0)
PATTERN = LoadPattern(lateral=False, vehicle=[dict(eurocode_lm1_tandem().to_dict(), x=-2.5, y=-1.5)],
                      fill=dict(depth=0.5, unit_weight=18.0))
SIZES = ((1, 8), (2, 8), (4, 16), (8, 16), (8, 32), (16, 32), (16, 64))
LARGE = ((32, 64), (32, 128))
#: sizes (courses, voussoirs) whose whole critical-position search is timed
SEARCHED = ((1, 8), (2, 8))


class _Timed:
    """Wall time spent in :meth:`ClarabelSolver.solve` while the context is open (s)."""

    def __enter__(self) -> _Timed:
        self.total = 0.0
        self._solve = ClarabelSolver.solve
        timed = self

        def solve(solver: ClarabelSolver, *args: Any, **kwargs: Any) -> Any:
            t0 = time.perf_counter()
            try:
                return timed._solve(solver, *args, **kwargs)
            finally:
                timed.total += time.perf_counter() - t0

        ClarabelSolver.solve = solve  # type: ignore[method-assign]
        return self

    def __exit__(self, *exc: object) -> None:
        ClarabelSolver.solve = self._solve  # type: ignore[method-assign]


def bridge(courses: int, voussoirs: int, skew: float = 30.0):
    return arch_bridge(span=8.0, rise=2.0, thickness=0.5, depth=7.0, voussoirs=voussoirs, pier_height=1.0,
                       courses=courses, bond="running", skew=skew)


def rows(sizes: tuple[tuple[int, int], ...]) -> list[dict[str, Any]]:
    out: list[dict[str, Any]] = []
    for courses, voussoirs in sizes:
        case = f"{courses} courses x {voussoirs} voussoirs"
        t0 = time.perf_counter()
        asm = bridge(courses, voussoirs).validate()
        build = time.perf_counter() - t0
        an = Analysis(asm, MATERIAL)
        t0 = time.perf_counter()
        first = an.limit(loads=PATTERN)
        out.append(row("bridge3d", case, "first lambda_max (model built, one SOCP)", model=first.model,
                       n_blocks=len(asm.blocks), n_solves=1, time_s=time.perf_counter() - t0, build_s=build,
                       note=f"{first.status} {first.lambda_max:.4f}; {len(asm.interfaces)} interfaces"))
        times = []
        with _Timed() as clarabel:
            for x in (-3.0, -2.0, -1.0):
                t0 = time.perf_counter()
                an.limit(loads=PATTERN.moved(x))
                times.append(time.perf_counter() - t0)
        out.append(row("bridge3d", case, "lambda_max at another position", model=first.model,
                       n_blocks=len(asm.blocks), n_solves=3, time_s=sorted(times)[1],
                       note=f"Clarabel's solve {clarabel.total / sum(times):.0%} of the time"))
        if (courses, voussoirs) in SEARCHED:
            for skew in (0.0, 30.0):
                an = Analysis(bridge(courses, voussoirs, skew).validate(), MATERIAL)
                t0 = time.perf_counter()
                res = critical_position(an, PATTERN)
                out.append(row("bridge3d", case, f"critical position along x, skew {skew:g}", model=first.model,
                               n_blocks=len(asm.blocks), n_solves=res.n_solves, time_s=time.perf_counter() - t0,
                               note=f"x = {res.critical_x:.3f} m, lambda_max {res.lambda_max:.4f}"))
    return out


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    group = parser.add_mutually_exclusive_group()
    group.add_argument("--quick", action="store_true", help="the four smallest sizes")
    group.add_argument("--large", action="store_true", help="also 2,000 and 4,000 blocks (minutes)")
    args = parser.parse_args()
    sizes = SIZES[:4] if args.quick else SIZES + (LARGE if args.large else ())
    print(report(pd.DataFrame(rows(sizes), columns=COLUMNS)), end="")
