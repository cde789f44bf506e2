"""Settlement capacity of the semicircular arch on symmetric spreading supports.

For each thickness ratio t/R (R the centreline radius) and voussoir count, the supports spread
symmetrically (each moves outward by s R) until the arch collapses; s at collapse is the span
increase as a fraction of the centreline span. The path is run with the increment h and h/2
(convergence: the capacities differ by less than 1e-3) and printed as a Markdown table, with
the haunch hinge's angle above the springing. ``docs/settlements.md`` shows the table made by

    python examples/07_settlement_capacity.py 0.11,0.12,0.13,0.15,0.175,0.2,0.225,0.25 36,72,144 0.004

Run with no arguments for one quick row.
"""

from __future__ import annotations

import sys
import time

from tce.analysis.settlement_path import settlement_path
from tce.structures.arch import semicircular_arch

SPREAD = {"left": [-1.0, 0, 0, 0, 0, 0], "right": [1.0, 0, 0, 0, 0, 0]}  # R = 1 m: s = span increase / span


def row(t_over_r: float, n: int, h: float) -> str:
    arch = semicircular_arch(inner_radius=1.0 - t_over_r / 2, thickness=t_over_r, voussoirs=n)
    t0 = time.perf_counter()
    coarse = settlement_path(arch, SPREAD, increment=h, s_max=1.0)
    fine = settlement_path(arch, SPREAD, increment=h / 2, s_max=1.0)
    wall = time.perf_counter() - t0
    if not (coarse.ok and fine.ok):
        return f"| {t_over_r:g} | {n} | {coarse.status} | {fine.status} | | | | |"
    # the right haunch hinge (joint index from the left springing) at the start and at collapse
    first, last = (180.0 * (n - h[-1]) / n for h in (fine.hinges[0], fine.hinges[-1]))
    diff = abs(coarse.capacity - fine.capacity)
    return (
        f"| {t_over_r:g} | {n} | {coarse.capacity:.5f} | {fine.capacity:.5f} | {diff:.1e} | "
        f"{first:.2f} -> {last:.2f} | {len(fine.snaps)} | {fine.status} ({wall:.0f} s) |"
    )


def main(argv: list[str]) -> None:
    ratios = [float(x) for x in argv[0].split(",")] if argv else [0.15]
    counts = [int(x) for x in argv[1].split(",")] if len(argv) > 1 else [36]
    h = float(argv[2]) if len(argv) > 2 else 0.004
    print(
        f"| t/R | voussoirs | capacity (h = {h:g}) | capacity (h = {h / 2:g}) | difference "
        "| haunch hinge, start -> collapse (deg above springing) | snaps | outcome |"
    )
    print("|---|---|---|---|---|---|---|---|")
    for t in ratios:
        for n in counts:
            print(row(t, n, h), flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
