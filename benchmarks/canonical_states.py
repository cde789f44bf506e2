"""The cost of canonical states (development benchmark): the paper's arch's load path (step
0.02, atol 1e-6) with and without them (``SolverOptions(canonical=...)``), interleaved, planar
LP and 3D SOCP, with how many steps each decided unique.

Usage: ``python benchmarks/canonical_states.py [--quick]``.
"""

from __future__ import annotations

import argparse
import statistics
import time
from typing import Any

import pandas as pd

from tce import Analysis, Material, load_path, semicircular_arch
from tce.core.solve import SolverOptions
from tce.quality.bench import COLUMNS, FRICTION, SETTLEMENT, report, row


def canonical(quick: bool) -> list[dict[str, Any]]:
    """Rows of the load paths with and without canonical states; the ratio is in ``note``."""
    arch = semicircular_arch().validate()
    rows: list[dict[str, Any]] = []
    scenes = (("arch in plane, 1 mm spreading (planar LP)", SETTLEMENT),
              ("arch, 1 mm transversal motion (3D SOCP)", {"right": [0.0, 0.001, 0.0, 0.0, 0.0, 0.0]}))
    for case, sett in scenes:
        times: dict[bool, list[float]] = {False: [], True: []}
        res: dict[bool, Any] = {}
        for _ in range(1 if quick else 5):
            for on in times:
                an = Analysis(arch, Material(friction=FRICTION), options=SolverOptions(canonical=on))
                t0 = time.perf_counter()
                res[on] = load_path(an, 0.0, sett, step=0.02, atol=1e-6)
                times[on].append(time.perf_counter() - t0)
        base = statistics.median(times[False])
        for on, r in res.items():
            unique = [s.unique for s in r.steps if s.ok]
            med = statistics.median(times[on])
            rows.append(row("canonical", case, "canonical states" if on else "solver's states",
                            model=r.steps[-1].model, n_blocks=len(arch.blocks), n_solves=r.n_solves, time_s=med,
                            note=f"{med / base:.2f}x without; {r.outcome}; steps unique: "
                                 f"{sum(u is True for u in unique)}, not unique: {sum(u is False for u in unique)}, "
                                 f"undecided: {sum(u is None for u in unique)}"))
    return rows


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="one repeat")
    print(report(pd.DataFrame(canonical(parser.parse_args().quick), columns=COLUMNS)), end="")
