"""Issue 38 item 4: a command does not import what it does not need. ``tce show`` reads a
results file: before, it imported the study parser (pydantic), every solver and Clarabel on the
way to the report's table helpers (1.74 against 1.35 CPU-s on the paper's Fig. 9 results,
measured 2026-11-27)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from tce.study import load_study
from tce.study.runner import run_study

STUDY = """
[study]
name = "imports"
[structure]
type = "semicircular_arch"
voussoirs = 6
[material]
friction = 0.8
[loads]
lambda_step = 0.05
[scenarios.none]
"""

PROBE = """
import sys
from tce.cli import main
assert main(["-q", *sys.argv[2:], sys.argv[1]]) == 0
print(sorted(m for m in ("clarabel", "pydantic", "tce.core.solve", "tce.study.schema", "matplotlib") if m in sys.modules))
"""


def test_show_and_plot_import_no_solver_and_no_study_parser(tmp_path: Path) -> None:
    """``tce show`` imports neither the solvers nor pydantic; ``tce plot`` of a results file that
    holds every drawn state imports matplotlib and pydantic (for ``[plots]``) but neither the
    solvers nor the study parser, which build structures (fails before 2026-11-27; 2.54 against
    2.33 CPU-s in-process on the paper's Fig. 9 results, medians of five interleaved)."""
    path = tmp_path / "imports.toml"
    path.write_text(STUDY)
    results = run_study(load_study(path), out=tmp_path, jobs=1).results

    def imported(*command: str) -> str:
        out = subprocess.run([sys.executable, "-c", PROBE, str(results), *command], capture_output=True, text=True,
                             check=True, env={**os.environ, "MPLBACKEND": "Agg"})
        return out.stdout.strip().splitlines()[-1]

    assert imported("show") == "[]"
    assert imported("plot", "--out", str(tmp_path / "figures")) == "['matplotlib', 'pydantic']"
