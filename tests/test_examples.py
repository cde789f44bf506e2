"""The numbered scripts of ``examples/`` run as a user runs them, and the README shows the first."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = sorted((ROOT / "examples").glob("[0-9][0-9]_*.py"))

# what each script must print, and its arguments (small and fast); the numbers are those
# validated in tests/validation (the 4-hinge mechanism's 0.2428243, (d/2)/z_c = 0.17875995...)
EXPECT = {
    "01_arch_settlement.py": ([], ["optimal planar", "0.17875995", "0.2428"]),
    "02_load_path.py": ([], ["lambda_max 0.24282", "inward", "outward", "downward"]),
    "03_dome.py": ([], ["optimal (spatial)", "lambda_max"]),
    "04_study_file.py": (["{examples}/04_study.toml", "{tmp}"], ["4 scenarios solved", "limit"]),
    "05_limit_mechanism.py": ([], ["lambda_0max = 0.2428243", "v01|v02 on the intrados", "v14|right on the extrados"]),
    "06_minimum_thickness.py": (["8"], ["8 voussoirs: t/R = 0.", "Milankovitch"]),
    "07_settlement_capacity.py": ([], ["| 0.15 | 36 | 0.05606 | 0.05606 |", "30.00 -> 30.00 | 0 | collapse"]),
}


def test_every_example_is_listed():
    assert EXAMPLES and [p.name for p in EXAMPLES] == sorted(EXPECT)


@pytest.mark.parametrize("name", sorted(EXPECT))
def test_example_runs(name, tmp_path):
    args, words = EXPECT[name]
    args = [a.format(examples=ROOT / "examples", tmp=tmp_path) for a in args]
    env = dict(os.environ, MPLBACKEND="Agg")
    done = subprocess.run(
        [sys.executable, str(ROOT / "examples" / name), *args],
        cwd=tmp_path, env=env, capture_output=True, text=True, timeout=600,
    )
    assert done.returncode == 0, done.stderr
    for word in words:
        assert word in done.stdout, (word, done.stdout)


def test_readme_shows_the_first_example():
    readme = (ROOT / "README.md").read_text()
    code = (ROOT / "examples" / "01_arch_settlement.py").read_text().split('"""\n\n', 1)[1]
    assert f"```python\n{code}```" in readme
