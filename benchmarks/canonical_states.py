"""The cost of canonical states (development benchmark): the paper's arch's load path (step
0.02, atol 1e-6, no mechanism) to lambda_max (no state read: what its decisions need), with the
state of every step read (as a study stores them: the canonical states), and with
``SolverOptions(canonical=False)`` and every step read (the solver's own states); interleaved, CPU
time, planar LP and 3D SOCP, with how many steps each decided unique.

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

#: method -> (canonical states, every step's state read)
VARIANTS = {"to lambda_max, no state read": (True, False),
            "every step's canonical state read (the default)": (True, True),
            "every step's solver state read (canonical=False)": (False, True)}


def canonical(quick: bool) -> list[dict[str, Any]]:
    """Rows of the load path's variants (:data:`VARIANTS`); the ratio to the first is in ``note``."""
    arch = semicircular_arch().validate()
    rows: list[dict[str, Any]] = []
    scenes = (("arch in plane, 1 mm spreading (planar LP)", SETTLEMENT),
              ("arch, 1 mm transversal motion (3D SOCP)", {"right": [0.0, 0.001, 0.0, 0.0, 0.0, 0.0]}))
    for case, sett in scenes:
        times: dict[str, list[float]] = {k: [] for k in VARIANTS}
        res: dict[str, Any] = {}
        for i in range(1 if quick else 5):
            for name in (list(VARIANTS) if i % 2 else list(VARIANTS)[::-1]):
                on, read = VARIANTS[name]
                an = Analysis(arch, Material(friction=FRICTION), options=SolverOptions(canonical=on))
                t0 = time.process_time()
                res[name] = load_path(an, 0.0, sett, step=0.02, atol=1e-6, mechanism=False)
                if read:
                    for s in res[name].steps:
                        s.state  # noqa: B018
                times[name].append(time.process_time() - t0)
        base = statistics.median(times[next(iter(VARIANTS))])
        for name in VARIANTS:
            r = res[name]
            unique = [s.unique for s in r.steps if s.ok]
            med = statistics.median(times[name])
            rows.append(row("canonical", case, name, model=r.steps[-1].model, n_blocks=len(arch.blocks),
                            n_solves=r.n_solves, time_s=med,
                            note=f"{med / base:.2f}x to lambda_max (CPU); {r.outcome}; steps unique: "
                                 f"{sum(u is True for u in unique)}, not unique: {sum(u is False for u in unique)}, "
                                 f"undecided: {sum(u is None for u in unique)}"))
    return rows

if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="one repeat")
    print(report(pd.DataFrame(canonical(parser.parse_args().quick), columns=COLUMNS)), end="")
