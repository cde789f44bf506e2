"""Time and error against the number of voussoirs (development benchmark): the arch's
lambda_90max (3D, direct) against its closed form ``(d/2) / z_c`` (``z_c`` the height of the
voussoirs' centroid), and its minimum thickness against Milankovitch's t/R = 0.1075.

Usage: ``python benchmarks/discretisation.py [--quick]``.
"""

from __future__ import annotations

import argparse
from typing import Any

import pandas as pd

from tce import Material, arch_minimum_thickness, semicircular_arch
from tce.core.limit import LimitSolver
from tce.core.model import build_model
from tce.quality.bench import COLUMNS, FRICTION, median_time, report, row

THICKNESS_REF = 0.1075


def discretisation(quick: bool) -> list[dict[str, Any]]:
    """Rows of lambda_90max and of the minimum thickness for arches of 8 to 400 voussoirs."""
    rows: list[dict[str, Any]] = []
    for n in (8, 16, 32) if quick else (8, 16, 32, 64, 128, 256, 400):
        arch = semicircular_arch(voussoirs=n).validate()
        free = list(arch.free_indices)
        w = arch.weights[free]
        closed = (arch.meta["depth"] / 2) / float((w * arch.centroids[free, 2]).sum() / w.sum())
        solver = LimitSolver(build_model(arch, "spatial"), Material(friction=FRICTION))
        med, res = median_time(lambda i, s=solver: s.solve(90.0), 3 if quick else 5)
        rows.append(row("discretisation", f"arch {n} voussoirs", "lambda_90max (direct, 3D)", model="spatial",
                        n_blocks=len(arch.blocks), n_solves=len(res), time_s=med,
                        error=abs(res[-1].lambda_max - closed), error_of="lambda_90max vs (d/2)/z_c"))
        if n == 16 or not quick:
            th = arch_minimum_thickness(1.0, n, tol=1e-5)
            rows.append(row("discretisation", f"arch {n} voussoirs", "minimum thickness (bisection 1e-5)",
                            model="planar", n_blocks=n + 2, n_solves=th.n_solves, time_s=th.wall_time,
                            error=abs(th.ratio - THICKNESS_REF), error_of="t/R vs 0.1075", note=f"t/R {th.ratio:.5f}"))
    return rows


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="three sizes")
    print(report(pd.DataFrame(discretisation(parser.parse_args().quick), columns=COLUMNS)), end="")
