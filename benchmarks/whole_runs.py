"""Whole ``tce run`` commands as a user runs them (development benchmark).

Each run is a fresh ``tce run STUDY --fresh`` process; the variants of a study are
interleaved (every other round reversed) and the medians of the rounds reported: wall time,
CPU time of the run and the processes it waited for (``resource.getrusage(RUSAGE_CHILDREN)``),
and each variant's wall time over the first variant's. Studies: the paper's (``studies/``), a
300-scenario sweep of the paper's arch (10 frictions x 5 settlement magnitudes x 6 cases) and a
12-scenario sweep of a dome (about a CPU-second of solving a scenario), the sweeps without figures. Variants: without figures, with figures, with figures and the calculation report
(the default), ``--jobs 1``, ``--jobs 2`` and, with ``--dask``, ``--backend dask``.

Usage: ``python benchmarks/whole_runs.py [--rounds 3] [--study fig9_outofplane ...] [--dask]``.
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

STUDIES = Path(__file__).resolve().parents[1] / "studies"
PAPER = ("fig3_4_settlements", "fig5_6_transversal", "fig7_8_inplane", "fig9_outofplane", "fig10_dome")
SWEEP_300 = """
[study]
name = "sweep300"
[structure]
type = "semicircular_arch"
[material]
friction = 0.8
[loads]
lambda_step = 0.02
tolerance = 1e-6
[sweep]
friction = [0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.2, 1.4, 1.7, 2.0]
magnitude = [0.5, 1.0, 1.5, 2.0, 3.0]
[scenarios.none]
[scenarios.outward]
right = [0.001, 0, 0, 0, 0, 0]
[scenarios.inward]
right = [-0.001, 0, 0, 0, 0, 0]
[scenarios.downward]
right = [0, 0, -0.001, 0, 0, 0]
[scenarios.transversal]
right = [0, 0.001, 0, 0, 0, 0]
[scenarios.rotation]
right = [0, 0, 0, 0.001, 0, 0]
"""
#: a sweep whose scenarios carry about a CPU-second of solving each: a dome of 12 sectors x 6 courses
#: (84 blocks, 3D SOCP) under 6 frictions x 2 settlement cases
DOME_SWEEP = """
[study]
name = "dome_sweep"
[structure]
type = "dome"
sectors = 12
courses = 6
[material]
friction = 0.8
[loads]
lambda_step = 0.05
tolerance = 1e-4
[sweep]
friction = [0.6, 0.7, 0.8, 0.9, 1.0, 1.2]
[scenarios.none]
[scenarios.one_outward]
s01 = [0.001, 0, 0, 0, 0, 0]
"""
SWEEPS = {"sweep300": SWEEP_300, "dome_sweep": DOME_SWEEP}
STUDY_VARIANTS = {"no figures": ["--no-plots"], "figures": ["--no-report"], "figures and report": []}
SWEEP_VARIANTS = {"--jobs 1": ["--no-plots", "--jobs", "1"], "--jobs 2": ["--no-plots", "--jobs", "2"],
                  "default": ["--no-plots"]}


def measured_run(study: Path, out: Path, args: list[str]) -> tuple[float, float]:
    """Wall and CPU seconds of ``tce run STUDY --fresh ARGS`` (CPU of the processes it waited for)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-m", "tce.cli", "-q", "run", str(study), "--out", str(out), "--fresh", *args],
                   check=True, capture_output=True, env=dict(os.environ, MPLBACKEND="Agg"))
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def interleaved(study: Path, out: Path, variants: dict[str, list[str]], rounds: int) -> None:
    """Run each variant ``rounds`` times, interleaved, and print the medians."""
    got: dict[str, list[tuple[float, float]]] = {k: [] for k in variants}
    for i in range(rounds):
        for label in list(variants)[:: 1 if i % 2 == 0 else -1]:
            got[label].append(measured_run(study, out, variants[label]))
    base = statistics.median(w for w, _ in next(iter(got.values())))
    for label, runs in got.items():
        wall, cpu = statistics.median(w for w, _ in runs), statistics.median(c for _, c in runs)
        print(f"{study.stem:24} {label:22} wall {wall:7.2f} s  CPU {cpu:7.2f} s  {wall / base:5.2f}x", flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=3, help="interleaved rounds (default 3)")
    parser.add_argument("--study", action="append", choices=(*PAPER, *SWEEPS), help="only these studies")
    parser.add_argument("--dask", action="store_true", help="add --backend dask to the sweeps' variants")
    args = parser.parse_args()
    print(f"load average {os.getloadavg()[0]:.1f}; medians of {args.rounds} interleaved rounds")
    with tempfile.TemporaryDirectory() as tmp:
        for name in args.study or (*PAPER, *SWEEPS):
            if name in SWEEPS:
                study = Path(tmp) / f"{name}.toml"
                study.write_text(SWEEPS[name])
                variants = dict(SWEEP_VARIANTS)
                if args.dask:
                    variants["dask, 2 workers"] = ["--no-plots", "--backend", "dask", "--jobs", "2"]
            else:
                study, variants = STUDIES / f"{name}.toml", STUDY_VARIANTS
            interleaved(study, Path(tmp) / "out", variants, args.rounds)
    print(f"load average {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
