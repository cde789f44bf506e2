"""Signals and storage faults in every command: SIGTERM and SIGKILL of the main process, Ctrl-C
while tce imports its modules, a closed output pipe, a disk that fills while figures are
drawn, read-only results, ``--out`` at a file, foreign and older netCDF files, a full disk
when the lock is taken. Each: the documented exit code, one line without a traceback,
nothing new written, no finished scenario lost."""

from __future__ import annotations

import errno
import os
import signal
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from tce.plot import output
from tce.study import results, runner
from tce.cli import main
from tce.study.schema import parse_study

from .common import NAMES, TINY, as_from_a_shell, answer, clean, errors, leftovers, tce_run, write
from .test_run_faults import files, resume_equals, tmpfs  # noqa: F401  (tmpfs: a fixture)


@pytest.fixture(scope="module")
def study():
    return parse_study(TINY, "study.toml")


@pytest.fixture(scope="module")
def reference(study, tmp_path_factory) -> xr.Dataset:
    report = runner.run_study(study, tmp_path_factory.mktemp("reference"), jobs=1, plots=False)
    return answer(report.results)


@pytest.fixture(scope="module")
def finished(study, tmp_path_factory) -> Path:
    """A results file of the tiny study (no figures)."""
    return runner.run_study(study, tmp_path_factory.mktemp("finished"), jobs=1, plots=False).results


def _started(study: Path, out: Path, *args: str, fault: str) -> subprocess.Popen:
    env = dict(os.environ, MPLBACKEND="Agg", TCE_FAULT=fault)
    env["PYTHONPATH"] = os.pathsep.join([str(Path(__file__).parent / "hook"), *filter(None, [env.get("PYTHONPATH")])])
    cmd = [sys.executable, "-m", "tce.cli", "run", str(study), "--out", str(out), "--no-plots", *args]
    return subprocess.Popen(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True,
                            preexec_fn=as_from_a_shell)


def _until_three_done(run: subprocess.Popen) -> None:
    """Read the run's progress lines until three of its four scenarios are done (and written):
    the fourth is held, so a line says ``3/4`` within seconds (a "still working" one at least)."""
    for line in run.stderr:
        if "3/4 scenarios" in line:
            return
    raise AssertionError("the run ended before three scenarios were done")


@pytest.mark.parametrize("jobs", ["1", "2"])
def test_sigterm_stops_a_run_as_ctrl_c_does(study, reference, tmp_path: Path, jobs: str) -> None:
    """SIGTERM to the main process (as a scheduler or ``kill`` sends it) while the last
    scenario is held: exit 143, one line, three scenarios kept, a rerun equals a full run."""
    out = tmp_path / "out"
    run = _started(write(tmp_path), out, "--jobs", jobs, fault=f"hold:{NAMES[-1]}")
    _until_three_done(run)
    run.send_signal(signal.SIGTERM)
    _, err = run.communicate(timeout=60)
    assert run.returncode == 143
    clean(err)
    assert "interrupted (SIGTERM)" in err and "run the same command again to resume" in err
    assert files(study, out) == {n: n != NAMES[-1] for n in NAMES} and not leftovers(out)
    resume_equals(study, reference, out, reused=3)


def test_sigkill_of_the_main_process_leaves_workers_silent(study, reference, tmp_path: Path) -> None:
    """``kill -9`` of ``tce run``: its workers end without a traceback (one of them is held
    inside a scenario, the other waits for one), every finished scenario is kept, a rerun resumes."""
    out = tmp_path / "out"
    run = _started(write(tmp_path), out, "--jobs", "2", fault=f"hold:{NAMES[-1]}")
    _until_three_done(run)
    run.send_signal(signal.SIGKILL)
    _, err = run.communicate(timeout=60)  # the pipes close when the workers have ended too
    assert run.returncode == -signal.SIGKILL
    assert "Traceback" not in err and "Error" not in err, err
    assert files(study, out) == {n: n != NAMES[-1] for n in NAMES}
    assert [p.name for p in leftovers(out)] == [results.LOCK_NAME]  # stale: the rerun takes it over
    resume_equals(study, reference, out, reused=3)


def test_ctrl_c_while_a_command_imports_its_modules(finished: Path) -> None:
    """Signal handlers are the command line's: ``import tce`` leaves them alone, and Ctrl-C
    while a command imports xarray ends it with one line, exit 130."""
    code = (
        "import builtins, os, signal, sys\n"
        "import tce.cli\n"
        "assert signal.getsignal(signal.SIGINT) is signal.default_int_handler\n"
        "real = builtins.__import__\n"
        "def ctrl_c_at_xarray(name, *args, **kwargs):\n"
        "    if name == 'xarray':\n"
        "        os.kill(os.getpid(), signal.SIGINT)\n"
        "    return real(name, *args, **kwargs)\n"
        "builtins.__import__ = ctrl_c_at_xarray\n"
        f"sys.exit(tce.cli.main(['show', {str(finished)!r}]))\n"
    )
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60,
                         preexec_fn=as_from_a_shell)
    assert run.returncode == 130, run.stderr
    assert run.stderr == "tce: interrupted (SIGINT)\n"


@pytest.mark.parametrize("unbuffered", ["", "1"], ids=["buffered", "unbuffered"])
def test_a_closed_output_pipe_ends_quietly(finished: Path, unbuffered: str) -> None:
    """``tce show RESULTS | head``: the reader went away before tce wrote (its end of the pipe is
    closed before tce starts, so every write fails). Exit 141 as SIGPIPE, nothing on stderr,
    whether the output is block-buffered (a shell's default: the write fails at the flush) or
    unbuffered (``PYTHONUNBUFFERED``: it fails at the first line)."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONUNBUFFERED"} | ({"PYTHONUNBUFFERED": "1"} if unbuffered else {})
    read, write_end = os.pipe()
    os.close(read)
    try:
        run = subprocess.run([sys.executable, "-m", "tce.cli", "show", str(finished)], stdout=write_end,
                             stderr=subprocess.PIPE, text=True, env=env)
    finally:
        os.close(write_end)
    assert (run.returncode, run.stderr) == (141, "")


def test_a_disk_that_fills_while_figures_are_drawn(tmp_path: Path, monkeypatch, capsys) -> None:
    out = tmp_path / "out"
    drawn = []

    def full(path, *args, **kwargs):  # the second PNG file fills the disk (a write names no file)
        drawn.append(path)
        if len(drawn) == 2:
            raise OSError(errno.ENOSPC, "No space left on device")
        return open(path, *args, **kwargs)

    monkeypatch.setattr(output, "open", full, raising=False)
    text = TINY.replace("[sweep]\nfriction = [0.8, 2.0]", "[material]\nfriction = 0.8")
    assert main(["run", str(write(tmp_path, text)), "--out", str(out), "--jobs", "1"]) == 3
    err = capsys.readouterr().err
    clean(err)
    (line,) = errors(err)
    figure = Path(drawn[1]).with_name(Path(drawn[1]).name[1:].rsplit(".", 3)[0])  # its temporary: .NAME.TOKEN.PID.tmp
    assert "no space left on the device" in line and str(figure) in line
    assert (out / "tiny" / "results.nc").exists() and "tce plot" in err and not leftovers(out)
    assert not figure.exists()


def test_results_that_cannot_be_written_get_no_figures(tmp_path: Path, monkeypatch, capsys) -> None:
    """Figures are drawn once ``results.nc`` is written: a write that fails leaves none."""
    def full(ds, path) -> None:
        raise runner.StorageError(f"{path}: no space left on the device")

    monkeypatch.setattr(runner, "write_atomic", full)
    out = tmp_path / "out"
    assert main(["run", str(write(tmp_path)), "--out", str(out), "--jobs", "1"]) == 3
    err = capsys.readouterr().err
    assert "results.nc: no space left on the device" in err and "results.nc was not written" in err
    assert not list((out / "tiny").glob("*.png")) and not list((out / "tiny").glob("*.html")) and not leftovers(out)


@pytest.fixture
def results_copy(finished: Path, tmp_path: Path) -> Path:
    path = tmp_path / "results.nc"
    path.write_bytes(finished.read_bytes())
    return path


@pytest.mark.parametrize("command", [["plot"], ["view"], ["export", "--vtk"]])
def test_out_at_a_file(command: list[str], results_copy: Path, capsys) -> None:
    target = results_copy.parent / "taken"
    target.write_text("keep me")
    argv = [command[0], str(results_copy), *command[1:], "--out", str(target if command[0] != "view" else target / "v.html")]
    assert main(argv) == 2
    err = capsys.readouterr().err
    clean(err)
    (line,) = errors(err)
    assert "--out" in line and str(target) in line and "is a file" in line
    assert target.read_text() == "keep me"
    assert sorted(p.name for p in results_copy.parent.iterdir()) == ["results.nc", "taken"]


def test_read_only_results(finished: Path, tmpfs: Path) -> None:  # noqa: F811
    (tmpfs / "results.nc").write_bytes(finished.read_bytes())
    subprocess.run(["mount", "-o", "remount,ro", str(tmpfs)], check=True)
    for command in (["plot"], ["view"], ["export", "--vtk"]):
        run = subprocess.run([sys.executable, "-m", "tce.cli", command[0], str(tmpfs / "results.nc"), *command[1:]],
                             capture_output=True, text=True, timeout=300, env=dict(os.environ, MPLBACKEND="Agg"))
        assert run.returncode == 2, run.stderr
        clean(run.stderr)
        (line,) = errors(run.stderr)
        assert "cannot write" in line and str(tmpfs) in line


@pytest.mark.parametrize("command", [["show"], ["plot"], ["view"], ["export", "--vtk"]])
@pytest.mark.parametrize("kind", ["foreign", "older", "not netCDF"])
def test_foreign_and_older_files(kind: str, command: list[str], finished: Path, tmp_path: Path, capsys) -> None:
    path = tmp_path / "other.nc"
    if kind == "foreign":
        xr.Dataset({"t": ("x", np.arange(3.0))}, attrs={"title": "a model"}).to_netcdf(path)
    elif kind == "older":  # what tce wrote before it stored outcomes
        xr.load_dataset(finished).drop_vars(["outcome"]).to_netcdf(path)
    else:
        path.write_text("lambda_max = 1\n")
    assert main([command[0], str(path), *command[1:]]) == 2
    err = capsys.readouterr().err
    clean(err)
    (line,) = errors(err)
    words = {"foreign": "not a results file written by tce", "older": "written by an older tce",
             "not netCDF": "not a readable results file"}[kind]
    assert str(path) in line and words in line
    assert sorted(p.name for p in tmp_path.iterdir()) == ["other.nc"]


def test_a_full_disk_when_the_lock_is_taken_leaves_no_lock(tmp_path: Path, monkeypatch, capsys) -> None:
    def full(fd, data, offset):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(results.os, "pwrite", full)
    assert main(["run", str(write(tmp_path)), "--out", str(tmp_path / "out"), "--no-plots"]) == 2
    err = capsys.readouterr().err
    clean(err)
    (line,) = errors(err)
    assert results.LOCK_NAME in line and "no space left" in line
    assert not leftovers(tmp_path / "out")


def test_a_signal_inside_a_deferred_block_is_raised_when_it_ends() -> None:
    """A Ctrl-C that arrives while the runner submits to its pool is held and raised right after
    the submit (raised inside it, it left the pool half-updated and its shutdown waiting for ever:
    a run hung for 300 s in test_ctrl_c_keeps_a_finished_scenario_not_yet_returned[2]); outside
    such a block it is raised at once."""
    from tce.signals import Interrupted, deferred, handle_signals, restore_signals

    before = handle_signals()
    try:
        reached = []
        with pytest.raises(Interrupted) as stop:
            with deferred():
                # raise(3): to this thread, its handler run before the next bytecode (os.kill may
                # hand it to another thread of the process, xdist's, and the handler run late)
                signal.raise_signal(signal.SIGINT)
                reached.append("end of the block")
        assert reached == ["end of the block"] and stop.value.signum == signal.SIGINT
    finally:
        restore_signals(before)
    before = handle_signals()
    try:
        with pytest.raises(Interrupted):
            signal.raise_signal(signal.SIGINT)
    finally:
        restore_signals(before)
