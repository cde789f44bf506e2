"""Hostile studies, by generator: every value of a valid study replaced in turn by each of a
list of hostile values; study "files" that are not files (devices, pipes, links to them,
folders, binary, too big, too deep, NUL in the path); and studies that ask for unbounded work
(every structure type at a huge size, huge sweeps, drawn states, load steps). Each must end
with exit 2 and one line naming the file and the key (or the path), nothing written."""

from __future__ import annotations

import copy
import json
import math
import os
import re
import resource
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from tce.study import guards
from tce.cli import main
from tce.study.schema import STRUCTURE_TYPES, StudyError, parse_study

from .common import clean, errors, replaced

HOSTILE: list[Any] = [
    "no", "false", "", "1", "heavy", "a\x00b", 1.5, True, False, {"a": 1}, [], [1, 2, 3], -1, 0, 5,
    math.nan, math.inf, 10**30,
]

VALID = {
    "study": {"name": "tiny"},
    "structure": {"type": "semicircular_arch", "voussoirs": 6, "thickness": 0.2},
    "material": {"friction": 0.8},
    "loads": {"lambda_step": 0.05, "tolerance": 1e-3, "alpha": [0.0]},
    "sweep": {"magnitude": [1.0, 2.0]},
    "scenarios": {"none": {}, "outward": {"right": [0.001, 0.0, 0.0, 0.0, 0.0, 0.0]}},
    "plots": {"steps": [0.0, "max"]},
}


def _value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float) and not math.isfinite(v):
        return "nan" if math.isnan(v) else "inf"
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)  # its escapes (\u0000) are TOML's
    if isinstance(v, list):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    return "{" + ", ".join(f"{json.dumps(k)} = {_value(x)}" for k, x in v.items()) + "}"


def toml(doc: dict) -> str:
    """A study as TOML: top-level tables, their sub-tables as [a.b]."""
    lines = []
    for name, table in doc.items():
        lines.append(f"[{name}]")
        subs = {k: v for k, v in table.items() if isinstance(v, dict) and name == "scenarios"}
        lines += [f"{json.dumps(k)} = {_value(v)}" for k, v in table.items() if k not in subs]
        for k, v in subs.items():
            lines.append(f"[{name}.{json.dumps(k)}]")
            lines += [f"{json.dumps(kk)} = {_value(vv)}" for kk, vv in v.items()]
    return "\n".join(lines) + "\n"


def _num(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


RIGHT = {
    "name": lambda v: isinstance(v, str) and re.fullmatch(r"[A-Za-z0-9_][A-Za-z0-9_.-]*", v) is not None,
    "count": lambda v: isinstance(v, int) and not isinstance(v, bool) and v >= 1,
    "positive": lambda v: _num(v) and v > 0,
    "nonnegative": lambda v: _num(v) and v >= 0,
    "number": _num,
    "alpha": lambda v: _num(v) or (isinstance(v, list) and bool(v) and all(_num(x) for x in v)),
    "numbers": lambda v: isinstance(v, list) and bool(v) and all(_num(x) for x in v),
    "vector": lambda v: isinstance(v, list) and len(v) == 6 and all(_num(x) for x in v),
    "steps": lambda v: isinstance(v, list) and bool(v) and all(x == "max" or _num(x) and x >= 0 for x in v),
    "step": lambda v: v == "max" or _num(v) and v >= 0,
}

#: (place, kind of value, key the message must name)
SLOTS = [
    (("study", "name"), "name", "study.name"),
    (("structure", "voussoirs"), "count", "structure.voussoirs"),
    (("structure", "thickness"), "positive", "structure.thickness"),
    (("material", "friction"), "nonnegative", "material.friction"),
    (("loads", "lambda_step"), "positive", "loads.lambda_step"),
    (("loads", "alpha"), "alpha", "loads.alpha"),
    (("sweep", "magnitude"), "numbers", "sweep.magnitude"),
    (("sweep", "magnitude", 0), "number", "sweep.magnitude"),
    (("scenarios", "outward", "right"), "vector", "scenarios.outward.right"),
    (("scenarios", "outward", "right", 0), "number", "scenarios.outward.right[0]"),
    (("plots", "steps"), "steps", "plots.steps"),
    (("plots", "steps", 0), "step", "plots.steps"),  # the list is checked as a whole
]


def study_with(place: tuple, value: Any) -> dict:
    return replaced(VALID, place, value)


def test_the_valid_study_parses() -> None:
    assert len(parse_study(toml(VALID), "s.toml").scenarios()) == 4


@pytest.mark.parametrize("place, kind, key", SLOTS, ids=[s[2] for s in SLOTS])
def test_every_value_of_a_study(place: tuple, kind: str, key: str) -> None:
    """The generator: every place x every hostile value; only StudyError may come out."""
    for value in HOSTILE:
        try:
            parse_study(toml(study_with(place, value)), "s.toml")
        except StudyError as exc:
            assert str(exc).startswith("s.toml: "), exc
            assert RIGHT[kind](value) or key in str(exc), (key, value, str(exc))
        else:
            assert RIGHT[kind](value), (key, value)


STUDY = toml(VALID)


def _refused(argv: list[str], capsys, *words: str) -> str:
    assert main(argv) == 2
    err = capsys.readouterr().err
    clean(err)
    (line,) = errors(err)
    for word in words:
        assert word in line, line
    return line


#: study "files" that are no such thing: name -> (make it in the folder, words of the message)
def _fifo(p: Path) -> None:
    os.mkfifo(p)


def _link(target: str):
    def make(p: Path) -> None:
        if target == "fifo":
            os.mkfifo(p.with_name("pipe"))
        p.symlink_to(p.with_name("pipe") if target == "fifo" else target)
    return make


NOT_FILES = {
    "/dev/zero": (_link("/dev/zero"), "a device"),
    "a pipe": (_fifo, "a pipe"),
    "a link to a pipe": (_link("fifo"), "a pipe"),
    "a folder": (lambda p: p.mkdir(), "a folder"),
    "binary": (lambda p: p.write_bytes(b"\xff\xfe\x00" * 10), "not a UTF-8 text file"),
    "missing": (lambda p: None, "cannot read the study file"),
    "too big": (lambda p: p.write_text(STUDY + "#" * guards.MAX_STUDY_BYTES), "MAX_STUDY_BYTES"),
    "arrays 100,000 deep": (lambda p: p.write_text(STUDY + "x = " + "[" * 100_000 + "]" * 100_000), "MAX_TOML_DEPTH"),
    "inline tables 100,000 deep": (lambda p: p.write_text(STUDY + "x = " + "{a = " * 100_000 + "1" + "}" * 100_000), "MAX_TOML_DEPTH"),
    "a dotted key 100,000 deep": (lambda p: p.write_text(STUDY + "a" + ".a" * 100_000 + " = 1"), "MAX_TOML_DEPTH"),
    "a table 50,000 deep": (lambda p: p.write_text(STUDY + "[" + "a." * 50_000 + "a]"), "MAX_TOML_DEPTH"),
    "a NUL in a scenario name": (lambda p: p.write_text(STUDY + '[scenarios."a\\u0000b"]\n'), "scenarios: the key 'a\\x00b'"),
    "a NUL in the block file's path": (
        lambda p: p.write_text(STUDY.replace('"type" = "semicircular_arch"', '"type" = "file"\npath = "a\\u0000b.json"')
                               .replace('"voussoirs" = 6\n"thickness" = 0.2\n', "")),
        "structure.path",
    ),
}


@pytest.mark.parametrize("case", sorted(NOT_FILES))
def test_a_study_file_that_is_not_a_study(case: str, tmp_path: Path, capsys) -> None:
    make, words = NOT_FILES[case]
    path = tmp_path / "study.toml"
    make(path)
    _refused(["run", str(path), "--out", str(tmp_path / "out")], capsys, str(path), words)
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("option", ["study", "out"])
def test_a_nul_in_a_path_on_the_command_line(option: str, tmp_path: Path, capsys) -> None:
    study = tmp_path / "study.toml"
    study.write_text(STUDY)
    argv = ["run", f"{study}\0x" if option == "study" else str(study), "--out", f"{tmp_path}/o\0ut" if option == "out" else str(tmp_path / "out")]
    _refused(argv, capsys, "NUL", "STUDY" if option == "study" else "--out")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["study.toml"]


#: the largest parameters of each structure type: more blocks than MAX_BLOCKS
HUGE = {
    "semicircular_arch": {"voussoirs": 10_000_000},
    "pointed_arch": {"voussoirs": 10_000_000},
    "segmental_arch": {"voussoirs": 10_000_000},
    "arch_on_piers": {"voussoirs": 10_000_000},
    "barrel_vault": {"voussoirs": 1000, "courses": 1000},
    "groin_vault": {"voussoirs": 1_000_000},
    "dome": {"sectors": 1000, "courses": 1000},
    "arch_bridge": {"spans": 10_000_000},
}


#: the generators' refusals run in one child process whose address space is capped at this
#: (bytes; RLIMIT_AS): refusing a study took a peak of 0.39 GB of address space (0.14 GB
#: resident), a generator that builds its ten million blocks needed 21 GB
REFUSAL_MEMORY = 2 << 30
#: and within this time (s): refusing all of them took about 3 s (interpreter start included)
REFUSAL_TIME = 120.0

#: the child: ``tce run`` on each study (argv[1]: JSON {kind: [study, out]}), in one process;
#: prints {kind: [exit code, stderr]} as JSON, with a MemoryError as its exit code
_REFUSE = """
import contextlib, io, json, sys
from tce.cli import main
out = {}
for kind, (study, folder) in json.loads(sys.argv[1]).items():
    err = io.StringIO()
    try:
        with contextlib.redirect_stderr(err):
            code = main(["run", study, "--out", folder])
    except MemoryError:
        code = "MemoryError"
    out[kind] = [code, err.getvalue()]
print(json.dumps(out))
"""


def _cap_memory() -> None:
    """``preexec_fn`` of the child: its address space capped at :data:`REFUSAL_MEMORY`."""
    resource.setrlimit(resource.RLIMIT_AS, (REFUSAL_MEMORY, REFUSAL_MEMORY))


GENERATORS = [t for t in STRUCTURE_TYPES if t != "file"]


@pytest.fixture(scope="module")
def refusals(tmp_path_factory) -> dict[str, tuple[Any, str, Path]]:
    """Every generator at a size past MAX_BLOCKS, run by ``tce run`` in a child process under
    a memory cap and a time limit (:data:`REFUSAL_MEMORY`, :data:`REFUSAL_TIME`), so that with
    the block cap broken the tests fail on their own (a MemoryError or the time limit) instead
    of taking the machine's memory (issue 25's mutation check: 21 GB when they ran before the
    fast test of ``check_blocks``). Returns ``{kind: (exit code, stderr, out folder)}``."""
    root = tmp_path_factory.mktemp("generators")
    runs = {}
    for kind in GENERATORS:
        doc = copy.deepcopy(VALID)
        doc["structure"] = {"type": kind, **HUGE[kind]}
        doc["scenarios"] = {"none": {}}
        (root / kind).mkdir()
        (root / kind / "study.toml").write_text(toml(doc))
        runs[kind] = [str(root / kind / "study.toml"), str(root / kind / "out")]
    try:
        child = subprocess.run([sys.executable, "-c", _REFUSE, json.dumps(runs)], capture_output=True, text=True,
                               timeout=REFUSAL_TIME, preexec_fn=_cap_memory)
    except subprocess.TimeoutExpired:
        pytest.fail(f"the generators' refusals did not end within {REFUSAL_TIME:g} s (is the block cap checked?)")
    assert child.returncode == 0, child.stderr[-2000:]
    return {k: (code, err, root / k / "out") for k, (code, err) in json.loads(child.stdout).items()}


@pytest.mark.parametrize("kind", GENERATORS)
def test_every_generator_refuses_too_many_blocks(kind: str, refusals) -> None:
    code, err, out = refusals[kind]
    assert code == 2, err[-2000:]
    clean(err)
    (line,) = errors(err)
    for word in ("50000", "structure"):
        assert word in line, line
    assert any(k in line for k in HUGE[kind])  # the parameter that sets the count
    assert not out.exists()


def _many(n: int, start: float = 0.0) -> list[float]:
    return [start + k * 1e-3 for k in range(n)]


WORK = {
    "100,000 directions": (("loads", "alpha"), _many(100_000), ["loads.alpha", "x 100000 direction(s)", "MAX_SCENARIOS"]),
    "1,000 x 1,000 sweep": (("sweep",), {"magnitude": _many(1000, 1.0), "friction": _many(1000, 0.1)},
                            ["x 1000 values of sweep.magnitude", "scenarios, more than MAX_SCENARIOS"]),
    "5,000 drawn steps": (("plots", "steps"), _many(5000), ["plots.steps", "MAX_DRAWN_STATES"]),
    "100,000 load steps": (("loads",), {"lambda_step": 0.001, "lambda_cap": 100.0, "tolerance": 1e-3, "alpha": [0.0]},
                           ["loads", "MAX_INCREMENTS"]),  # a path anchored on its limit needs a cap to be long
    "5,000 scenarios of 5,000 steps": (
        ("sweep",), {"magnitude": _many(2500, 1.0), "lambda_step": None}, ["loads", "solves at most", "MAX_SOLVES"]
    ),
}


@pytest.mark.parametrize("case", sorted(WORK))
def test_unbounded_work_is_refused_with_its_estimate(case: str, tmp_path: Path, capsys) -> None:
    place, value, words = WORK[case]
    doc = study_with(place, value)
    if case.startswith("5,000 scenarios"):
        doc["sweep"].pop("lambda_step")
        doc["loads"]["lambda_step"] = 0.02  # lambda_cap 100: 5001 steps each, 5000 scenarios
    path = tmp_path / "study.toml"
    path.write_text(toml(doc))
    _refused(["run", str(path), "--out", str(tmp_path / "out")], capsys, *words)
    assert not (tmp_path / "out").exists()


def test_drawn_states_are_counted_before_anything_runs() -> None:
    """MAX_DRAWN_STATES is checked at parse time (issue 25): one step past the cap is refused
    with its count, the cap itself parses; without the check, "5,000 drawn steps" would only
    be caught by the run's timeout."""
    drawn = len(parse_study(toml(VALID), "s.toml").scenarios())  # every scenario is drawn by default
    steps = guards.MAX_DRAWN_STATES // drawn
    parse_study(toml(study_with(("plots", "steps"), _many(steps))), "s.toml")
    with pytest.raises(StudyError) as exc:
        parse_study(toml(study_with(("plots", "steps"), _many(steps + 1))), "s.toml")
    msg = str(exc.value)
    assert "plots.steps" in msg and f"{drawn * (steps + 1)} drawn states" in msg and "MAX_DRAWN_STATES" in msg, msg
