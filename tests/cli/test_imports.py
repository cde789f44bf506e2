"""Issue 38 item 4: a command does not import what it does not need. ``tce show`` reads a
results file: before, it imported the study parser (pydantic), every solver and Clarabel on the
way to the report's table helpers (1.74 against 1.35 CPU-s on the paper's Fig. 9 results,
measured 2026-11-27)."""

from __future__ import annotations

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
assert main(["-q", "show", sys.argv[1]]) == 0
print(sorted(m for m in ("clarabel", "pydantic", "tce.core.solve", "tce.study.schema", "matplotlib") if m in sys.modules))
"""


def test_show_imports_no_solver_and_no_study_parser(tmp_path: Path) -> None:
    path = tmp_path / "imports.toml"
    path.write_text(STUDY)
    results = run_study(load_study(path), out=tmp_path, jobs=1).results
    out = subprocess.run([sys.executable, "-c", PROBE, str(results)], capture_output=True, text=True, check=True)
    assert out.stdout.strip().splitlines()[-1] == "[]", out.stdout
