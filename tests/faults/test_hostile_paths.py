"""Hostile inputs by class (issue 42), each class a generator: a link planted at every path tce
writes, scenario names with separators and names that slug alike, an absurd magnitude in every
numeric key of every section, output paths that cannot be written, and faults around the
start of a run's workers. Each ends with exit 2 (input) or 3 (fault) and one line naming the
file, key or path, and no file outside the study's output folder changes."""

from __future__ import annotations

import contextlib
import copy
import os
import re
import select
import signal
import subprocess
import sys
from pathlib import Path
from typing import Any, get_args

import pytest
import xarray as xr
from pydantic import BaseModel

from tce.cli import main
from tce.study import runner
from tce.study.schema import (
    _STRUCTURES,
    AssessmentSection,
    BackingSection,
    DistributedLoadSection,
    FileStructure,
    FillSection,
    LoadsSection,
    MaterialSection,
    PointLoadSection,
    SettlementPathSection,
    StudyError,
    SweepSection,
    VehicleSection,
    parse_study,
)

from .common import HOOK, TINY, as_from_a_shell, clean, errors, write
from .test_hostile_studies import toml

SMALL = TINY.replace("voussoirs = 6", "voussoirs = 4").replace("[sweep]\nfriction = [0.8, 2.0]\n", "")


@pytest.fixture(scope="module")
def finished(tmp_path_factory) -> Path:
    """A finished run's results file (two scenarios)."""
    out = tmp_path_factory.mktemp("finished")
    assert main(["run", str(write(out, SMALL)), "--out", str(out / "out"), "--jobs", "1", "--no-plots"]) == 0
    return out / "out" / "tiny" / "results.nc"


def _victim(folder: Path) -> Path:
    victim = folder / "victim"
    victim.mkdir()
    (victim / "file").write_text("victim")
    return victim


def _untouched(victim: Path) -> None:
    assert sorted(p.name for p in victim.iterdir()) == ["file"] and (victim / "file").read_text() == "victim"


#: paths a run writes in its study folder, each planted as a link to a file (a folder for "scenarios")
RUN_PATHS = [".tce-run.lock", "scenarios", "results.nc"]


@pytest.mark.parametrize("name", RUN_PATHS)
def test_a_link_planted_where_a_run_writes(name: str, tmp_path: Path, capsys) -> None:
    victim = _victim(tmp_path)
    folder = tmp_path / "out" / "tiny"
    folder.mkdir(parents=True)
    (folder / name).symlink_to(victim if name == "scenarios" else victim / "file")
    code = main(["run", str(write(tmp_path, SMALL)), "--out", str(tmp_path / "out"), "--jobs", "1", "--no-plots"])
    err = capsys.readouterr().err
    clean(err)
    _untouched(victim)
    if code:  # a link tce would have to follow is refused, naming it
        assert code == 2 and name in errors(err)[0]
    else:  # a link at a final name is replaced by the file
        assert not (folder / name).is_symlink()


#: commands that write beside a results file: argv after the results file, the file they write
WRITERS = {
    "view": ([], "view.html"),
    "report": (["--no-pdf"], "report.html"),
    "export": (["--vtk"], "vtk/none.pvd"),
    "plot": (["--kind", "thrust"], "thrust.png"),
}


@pytest.mark.parametrize("command", sorted(WRITERS))
def test_a_link_planted_where_a_command_writes(command: str, finished: Path, tmp_path: Path, capsys) -> None:
    victim = _victim(tmp_path)
    results = tmp_path / "study" / "results.nc"
    results.parent.mkdir()
    results.write_bytes(finished.read_bytes())
    args, name = WRITERS[command]
    (results.parent / name).parent.mkdir(exist_ok=True)
    (results.parent / name).symlink_to(victim / "file")
    assert main([command, str(results), *args]) == 0
    clean(capsys.readouterr().err)
    _untouched(victim)
    assert (results.parent / name).is_file() and not (results.parent / name).is_symlink()


#: output paths that cannot be written, made under a folder
def _file(p: Path) -> None:
    p.write_text("keep")


def _dangling(p: Path) -> None:
    p.symlink_to(p.with_name("nothing"))


def _loop(p: Path) -> None:
    p.symlink_to(p.with_name("loop2"))
    p.with_name("loop2").symlink_to(p)


BAD_OUT = {"a file": (_file, ""), "under a file": (_file, "sub"), "a dangling link": (_dangling, ""),
           "a loop of links": (_loop, ""), "under a loop of links": (_loop, "sub")}
OUT_COMMANDS = {"run": None, "plot": [], "view": [], "export": ["--vtk"], "report": ["--no-pdf"]}


@pytest.mark.parametrize("case", sorted(BAD_OUT))
@pytest.mark.parametrize("command", sorted(OUT_COMMANDS))
def test_an_output_path_that_cannot_be_written(command: str, case: str, finished: Path, tmp_path: Path,
                                               capsys) -> None:
    make, below = BAD_OUT[case]
    make(tmp_path / "taken")
    out = tmp_path / "taken" / below if below else tmp_path / "taken"
    study = write(tmp_path, SMALL)
    before = sorted(p.name for p in tmp_path.iterdir())
    if command == "run":
        argv = ["run", str(study), "--out", str(out)]
    else:
        argv = [command, str(finished), *OUT_COMMANDS[command], "--out", str(out / "v.html" if command == "view" else out)]
    assert main(argv) == 2
    err = capsys.readouterr().err
    clean(err)
    (line,) = errors(err)
    assert "--out" in line and str(tmp_path / "taken") in line
    assert sorted(p.name for p in tmp_path.iterdir()) == before


def test_a_results_file_without_its_study(finished: Path, tmp_path: Path, capsys) -> None:
    ds = xr.load_dataset(finished)
    del ds.attrs["study"]
    damaged = tmp_path / "results.nc"
    ds.to_netcdf(damaged)
    for command in (["show"], ["plot"], ["report", "--no-pdf"]):
        assert main([command[0], str(damaged), *command[1:]]) == 2
        (line,) = errors(capsys.readouterr().err)
        assert str(damaged) in line and "study attribute" in line
    assert sorted(p.name for p in tmp_path.iterdir()) == ["results.nc"]


STUDY = {"study": {"name": "s"}, "structure": {"type": "semicircular_arch", "voussoirs": 4}}

#: settlement case names that are not one plain name, and pairs of names that make one file name
SEPARATED = ["..", ".", "a/b", "a\\b", "../x", "x/..", "..."]
TWINS = [("a b", "a_b"), ("a!", "a?"), ("a.", "a"), ("_a_", "a"), ("a  b", "a b")]


@pytest.mark.parametrize("name", SEPARATED)
def test_a_settlement_case_with_a_separator(name: str) -> None:
    with pytest.raises(StudyError, match=r"^s\.toml: scenarios: .*path separator"):
        parse_study(toml(STUDY | {"scenarios": {name: {}}}), "s.toml")


@pytest.mark.parametrize("twins", TWINS, ids=["|".join(t) for t in TWINS])
def test_scenarios_whose_names_slug_alike(twins: tuple[str, str]) -> None:
    with pytest.raises(StudyError, match=r"^s\.toml: scenarios\..*share the file name"):
        parse_study(toml(STUDY | {"scenarios": dict.fromkeys(twins, {})}), "s.toml")


# ------------------------------------------------------------ absurd magnitudes, every numeric key
#: valid studies that give every numeric key of every section (with the model of each section)
LOADED = {
    "study": {"name": "s"},
    "structure": {"type": "semicircular_arch", "voussoirs": 8},
    "material": {"friction": 0.8, "normal_stiffness": 1e6, "shear_stiffness": 1e6, "cohesion": 1.0,
                 "tensile_strength": 1.0, "compressive_strength": 1e4},
    "loads": {"alpha": 0.0, "lateral": False, "critical_position": True, "positions": [0.0], "lambda_step": 0.1,
              "tolerance": 1e-3, "lambda_cap": 10.0,
              "point": [{"block": "v04", "at": [0.0, 0.0, 1.1], "force": [0.0, 0.0, -1.0], "scaled": False},
                        {"on_top": [0.3, 0.0], "force": [0.0, 0.0, -1.0], "scaled": False}],
              "distributed": [{"x": [-0.5, 0.5], "y": [-0.1, 0.1], "pressure": 1.0, "scaled": False}],
              "vehicle": [{"axles": [[0.0, 1.0]], "wheels": [0.0], "patch": [0.1, 0.1], "x": 0.0, "y": 0.0}],
              "fill": {"depth": 0.2, "unit_weight": 18.0, "dispersion": 26.6, "k0": 0.3, "kp": 3.0}},
    "sweep": {"friction": [0.8], "cohesion": [1.0], "tensile_strength": [1.0], "compressive_strength": [1e4],
              "inner_radius": [1.0], "thickness": [0.2], "depth": [0.25]},
    "assessment": {"dead_factor": 1.0, "live_factor": 1.5},
}
MOVED = {
    "study": {"name": "s"},
    "structure": {"type": "semicircular_arch", "voussoirs": 8},
    "loads": {"point": [{"on_top": [0.0, 0.0], "force": [0.0, 0.0, -1.0]}]},
    "sweep": {"magnitude": [1.0], "load_x": [0.0]},
    "scenarios": {"out": {"right": [0.001, 0.0, 0.0, 0.0, 0.0, 0.0]}},
    "plots": {"steps": [0.0, "max"]},
}
SETTLING = {
    "study": {"name": "s"},
    "structure": {"type": "semicircular_arch", "voussoirs": 8},
    "loads": {"point": [{"on_top": [0.3, 0.0], "force": [0.0, 0.0, -1.0]}]},
    "scenarios": {"out": {"right": [0.001, 0.0, 0.0, 0.0, 0.0, 0.0]}},
    "settlement_path": {"increment": 0.01, "s_max": 0.1, "tolerance": 1e-3, "live_at": [0.05], "contact_gap": 1e-3},
}
#: section (dotted place in the study) -> (the study that gives it, its model)
SECTIONS: dict[str, tuple[dict, type[BaseModel]]] = {
    "material": (LOADED, MaterialSection),
    "loads": (LOADED, LoadsSection),
    "loads.point.0": (LOADED, PointLoadSection),
    "loads.point.1": (LOADED, PointLoadSection),
    "loads.distributed.0": (LOADED, DistributedLoadSection),
    "loads.vehicle.0": (LOADED, VehicleSection),
    "loads.fill": (LOADED, FillSection),
    "assessment": (LOADED, AssessmentSection),
    "sweep": (LOADED, SweepSection),
    "sweep:moved": (MOVED, SweepSection),
    "settlement_path": (SETTLING, SettlementPathSection),
}
def _holds_numbers(annotation: Any) -> bool:
    return annotation in (float, int) or any(_holds_numbers(a) for a in get_args(annotation))


BASES = [LOADED, MOVED, SETTLING]
for _cls in _STRUCTURES:
    if _cls is not FileStructure:
        _kind = _cls.model_fields["type"].annotation.__args__[0]
        _given = {k: f.default for k, f in _cls.model_fields.items() if k != "type" and f.default is not None}
        _lengths = {k: 1.0 for k, f in _cls.model_fields.items()
                    if f.default is None and k not in ("centre_offset", "rise") and _holds_numbers(f.annotation)}
        _doc = {"study": {"name": "s"}, "structure": {"type": _kind, **_given, **_lengths}}
        if _kind == "pointed_arch":  # rise or centre_offset
            _other = copy.deepcopy(_doc)
            _doc["structure"]["rise"] = 1.5
            _other["structure"]["centre_offset"] = 0.3
            SECTIONS["structure:pointed_arch:offset"] = (_other, _cls)
            BASES.append(_other)
        if _kind == "dome":
            _doc["sweep"] = {"radius": [5.0]}
            SECTIONS["sweep:dome"] = (_doc, SweepSection)
        SECTIONS[f"structure:{_kind}"] = (_doc, _cls)
        BASES.append(_doc)
#: backing behind the haunches of the semicircular arch of radius 1 m (its extrados crown at 1.2 m)
BACKED = {"study": {"name": "s"}, "structure": {"type": "semicircular_arch", "voussoirs": 6,
                                                "backing": {"height": 0.8, "unit_weight": 22.0}}}
SECTIONS["structure.backing"] = (BACKED, BackingSection)
BASES.append(BACKED)


def _numeric(cls: type[BaseModel]) -> list[str]:
    """The keys of ``cls`` that hold numbers (alone or in lists)."""
    return [k for k, f in cls.model_fields.items() if _holds_numbers(f.annotation)]


def _node(doc: dict, place: str) -> dict:
    node: Any = doc
    for part in place.split(":")[0].split("."):
        node = node[int(part)] if part.isdigit() else node[part]
    return node


def _absurd(value: Any, number: float) -> Any:
    """``value`` with each number replaced by ``number``."""
    if isinstance(value, list):
        return [_absurd(v, number) for v in value]
    return number if isinstance(value, (int, float)) and not isinstance(value, bool) else value


def test_the_bases_are_valid_and_give_every_numeric_key() -> None:
    for doc in BASES:
        parse_study(toml(doc), "s.toml")
    given: dict[type, set[str]] = {}
    for place, (doc, cls) in SECTIONS.items():
        given.setdefault(cls, set()).update(_node(doc, place))
    for cls, keys in given.items():
        assert set(_numeric(cls)) <= keys, (cls.__name__, set(_numeric(cls)) - keys)


KEYS = [(place, key) for place, (doc, cls) in SECTIONS.items() for key in _numeric(cls) if key in _node(doc, place)]


@pytest.mark.parametrize("place, key", KEYS, ids=[f"{p}.{k}" for p, k in KEYS])
@pytest.mark.parametrize("number", [1e308, -1e308, 1e-308])
def test_an_absurd_magnitude_in_every_numeric_key(place: str, key: str, number: float) -> None:
    """1e308 and -1e308 are refused naming the key; 1e-308 wherever a small value is meaningless
    (by its bound, or as a structure or material that cannot be built)."""
    doc = SECTIONS[place][0]
    hostile = copy.deepcopy(doc)
    node = _node(hostile, place)
    node[key] = _absurd(node[key], number)
    try:
        parse_study(toml(hostile), "s.toml")
    except StudyError as exc:
        section = place.split(":")[0].split(".")[0]
        assert str(exc).startswith("s.toml: ") and (number == 1e-308 or str(exc).startswith(f"s.toml: {section}")
                                                    and key in str(exc)), str(exc)
    else:
        assert number == 1e-308 and key not in ("dead_factor", "live_factor"), (place, key)


# ---------------------------------------------------------------- faults around the workers' start
def test_ctrl_c_while_the_workers_start_is_honoured(tmp_path: Path) -> None:
    """Ctrl-C while the run starts its workers (the fork server imports tce, for seconds; the
    fault hook holds the run there until the Ctrl-C is sent): exit 130, one line."""
    marker = tmp_path / "starting"
    os.mkfifo(marker)
    os.mkfifo(f"{marker}.sent")
    env = dict(os.environ, MPLBACKEND="Agg", TCE_FAULT=f"starting:-:{marker}",
               PYTHONPATH=os.pathsep.join([str(HOOK), *filter(None, [os.environ.get("PYTHONPATH")])]))
    cmd = [sys.executable, "-m", "tce.cli", "run", str(write(tmp_path)), "--out", str(tmp_path / "out"),
           "--jobs", "2", "--no-plots"]
    with subprocess.Popen(cmd, env=env, stderr=subprocess.PIPE, stdout=subprocess.DEVNULL, text=True,
                          start_new_session=True, preexec_fn=as_from_a_shell) as proc:
        held = os.open(marker, os.O_RDONLY | os.O_NONBLOCK)
        lines = []
        try:  # wait on the hook's byte (the run is starting its workers), or on the run's end
            while True:
                ready = select.select([held, proc.stderr], [], [])[0]
                if held in ready and os.read(held, 1):
                    break
                if proc.stderr in ready:
                    lines.append(proc.stderr.readline())
                    assert lines[-1], "".join(lines)  # the run ended before it started a worker
        finally:
            os.close(held)
        os.killpg(proc.pid, signal.SIGINT)
        with contextlib.suppress(OSError):  # ENXIO: the run has already ended
            os.close(os.open(f"{marker}.sent", os.O_WRONLY | os.O_NONBLOCK))
        err = "".join(lines) + proc.stderr.read()
        assert proc.wait(timeout=300) == 130, err
    clean(err)
    assert "interrupted" in err


def test_a_fork_server_that_ends_while_workers_start(tmp_path: Path, monkeypatch, capsys) -> None:
    class Ended(runner.ProcessPoolExecutor):
        def submit(self, *args, **kwargs):
            raise EOFError("unexpected EOF")  # what connecting to a dead fork server raises

    monkeypatch.setattr(runner, "ProcessPoolExecutor", Ended)
    assert main(["run", str(write(tmp_path, SMALL)), "--out", str(tmp_path / "out"), "--jobs", "2", "--no-plots"]) == 3
    err = capsys.readouterr().err
    clean(err)
    assert "fork server ended" in errors(err)[0]


# ------------------------------------------------------------------------ work stated and capped
#: large work of each kind, as [section] text added to a small study
LARGE = {
    "a critical-position search over 2,000 positions": (
        '[loads]\nlateral = false\ncritical_position = true\npositions = [{}]\n[[loads.vehicle]]\naxles = [[0.0, 1.0]]\n'
        .format(", ".join(f"{-1.1 + 2.2 * k / 1999:.6f}" for k in range(2000))), "critical-position search"),
    "a sweep of critical searches": (
        "[loads]\nlateral = false\ncritical_position = true\n[[loads.vehicle]]\naxles = [[0.0, 1.0]]\n"
        "[sweep]\nfriction = [{}]\n".format(", ".join(str(0.5 + k / 100) for k in range(100))), "critical-position search"),
    "100 magnitudes x 20,000 settlement steps": (
        "[sweep]\nmagnitude = [{}]\n[scenarios.out]\nright = [0.001, 0.0, 0.0, 0.0, 0.0, 0.0]\n"
        "[settlement_path]\nincrement = 0.0001\ns_max = 2.0\n".format(", ".join(str(1 + k) for k in range(100))),
        "settlement path of 20000 increments"),
    "a load path of 10,000 steps per scenario": ("[loads]\nlambda_step = 0.001\nlambda_cap = 10.0\n", "10001 load steps"),
}
BASE = '[study]\nname = "large"\n{cap}[structure]\ntype = "semicircular_arch"\nvoussoirs = 6\n'


@pytest.mark.parametrize("case", sorted(LARGE))
def test_large_work_is_stated_and_refused_over_the_cap(case: str) -> None:
    text, words = LARGE[case]
    study = parse_study(BASE.format(cap="") + text, "s.toml")
    assert words in study.work() and "[study] max_solves" in study.work()
    with pytest.raises(StudyError, match=r"^s\.toml: study\.max_solves: .*" + re.escape(words) + ".*raise \\[study\\] max_solves"):
        parse_study(BASE.format(cap="max_solves = 1000\n") + text, "s.toml")


def test_a_run_states_its_work_before_it_starts(tmp_path: Path, capsys) -> None:
    assert main(["run", str(write(tmp_path, SMALL)), "--out", str(tmp_path / "out"), "--jobs", "1", "--no-plots"]) == 0
    err = capsys.readouterr().err
    work = next(k for k, line in enumerate(err.splitlines()) if "solves at most" in line)
    running = next(k for k, line in enumerate(err.splitlines()) if line.startswith("tce: running"))
    assert work < running and "max_solves = 20000000" in err.splitlines()[work]


def test_a_disk_that_fills_while_the_report_is_written(finished: Path, tmp_path: Path, monkeypatch, capsys) -> None:
    """One line naming the path, exit 3, no temporary left (it was a traceback and .report.html.tmp)."""
    import errno

    from tce import report

    def full(self, *args, **kwargs):
        raise OSError(errno.ENOSPC, "No space left on device", str(self))

    monkeypatch.setattr(Path, "write_text", full)
    monkeypatch.setattr(report, "study_figures", lambda ds, folder, scratch: [])
    assert main(["report", str(finished), "--no-pdf", "--out", str(tmp_path)]) == 3
    err = capsys.readouterr().err
    clean(err)
    (line,) = errors(err)
    assert "no space left on the device" in line and str(tmp_path) in line
    assert list(tmp_path.iterdir()) == []
