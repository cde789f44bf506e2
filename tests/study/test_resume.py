"""Issue 21, problem 7: a rerun reuses a finished scenario only when nothing that can change
its answer changed: every input, the bracket method, the solver settings and the installed
code.

On the old main a change of the installed code that kept the version number (a solver
tolerance, an iteration limit) reused every finished scenario although a fresh run gives
another lambda_max. Each case below changes one thing and checks that the scenario is
solved again (and that nothing changed reuses it).
"""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from tce.core import clarabel_solver
from tce.study import load_study
from tce.study.runner import run_study

BASE = """
[study]
name = "resume"

[structure]
type = "semicircular_arch"
voussoirs = 6
thickness = 0.2

[material]
friction = 0.8

[loads]
alpha = 0.0
lambda_step = 0.05
tolerance = 1e-4

[scenarios.outward]
right = [0.001, 0.0, 0.0, 0.0, 0.0, 0.0]
"""

#: one edit of the study text per input
EDITS = {
    "structure": ("thickness = 0.2", "thickness = 0.25"),
    "material": ("friction = 0.8", "friction = 0.7"),
    "settlement": ("right = [0.001,", "right = [0.002,"),
    "direction": ("alpha = 0.0", "alpha = 180.0"),
    "step": ("lambda_step = 0.05", "lambda_step = 0.04"),
    "tolerance": ("tolerance = 1e-4", "tolerance = 1e-5"),
    "cap": ("tolerance = 1e-4", "tolerance = 1e-4\nlambda_cap = 5.0"),
    "point load": ("[scenarios.outward]", "[[loads.point]]\nblock = \"v03\"\nforce = [0.0, 0.0, -1.0]\n"
                   "scaled = false\n\n[scenarios.outward]"),
}


def _run(folder: Path, text: str) -> tuple[list[str], list[str]]:
    path = folder / "study.toml"
    path.write_text(text)
    report = run_study(load_study(path), out=folder / "out", jobs=1)
    return report.solved, report.reused


@pytest.fixture
def finished(tmp_path: Path) -> Path:
    """A folder whose study was run once."""
    assert _run(tmp_path, BASE) == (["outward"], [])
    return tmp_path


def test_nothing_changed_is_reused(finished: Path) -> None:
    assert _run(finished, BASE) == ([], ["outward"])


@pytest.mark.parametrize("what", list(EDITS))
def test_each_input_solves_again(finished: Path, what: str) -> None:
    old, new = EDITS[what]
    assert old in BASE
    assert _run(finished, BASE.replace(old, new)) == (["outward"], [])


def test_the_bracket_method_solves_again(finished: Path, monkeypatch) -> None:
    from tce.study import keys

    monkeypatch.setattr(keys, "BRACKET", "bisection")
    assert _run(finished, BASE) == (["outward"], [])


@pytest.mark.parametrize("field", ["tol", "residual_tol", "max_iter"])
def test_solver_settings_solve_again(finished: Path, monkeypatch, field: str) -> None:
    """A tolerance or an iteration limit of the installed solver settings."""
    init = clarabel_solver.SolverOptions.__init__
    names = list(init.__code__.co_varnames[1:init.__code__.co_argcount])
    defaults = list(init.__defaults__)
    k = names.index(field)
    defaults[k] = defaults[k] * 2 if field != "max_iter" else defaults[k] + 50
    monkeypatch.setattr(init, "__defaults__", tuple(defaults))
    assert _run(finished, BASE) == (["outward"], [])


def test_a_change_of_the_installed_code_solves_again(finished: Path, tmp_path_factory, monkeypatch) -> None:
    """The same version number, one line of the code changed."""
    from tce.study import keys

    copy = tmp_path_factory.mktemp("code") / "tce"
    shutil.copytree(keys.PACKAGE, copy, ignore=shutil.ignore_patterns("__pycache__", "data"))
    target = copy / "core" / "clarabel_solver.py"
    target.write_text(target.read_text().replace("max_iter: int = 200", "max_iter: int = 150"))
    digest = keys.code_digest
    assert digest(copy) != digest()
    monkeypatch.setattr(keys, "code_digest", lambda: digest(copy))
    assert _run(finished, BASE) == (["outward"], [])
