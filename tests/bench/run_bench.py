"""Run ``tce bench`` as a script (not collected by pytest: no ``test_`` prefix).

Usage::

    python tests/bench/run_bench.py [--quick] [--out results/bench] [--section per_solve ...]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from tce.quality.bench import add_bench_arguments, bench_command  # noqa: E402

if __name__ == "__main__":
    parser = add_bench_arguments(argparse.ArgumentParser(description="tce speed-against-error bench"))
    sys.exit(bench_command(parser.parse_args()))
