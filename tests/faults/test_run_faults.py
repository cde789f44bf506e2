"""Faults during a run: a killed worker, Ctrl-C, a full or unwritable destination, damaged
scenario files, two runs at once. Each checks the exit code, one message without a
traceback, the files on disk (every finished scenario kept, no temporary or lock left),
and that the resumed results equal an uninterrupted run's exactly."""

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

from tce.study import runner
from tce.cli import main
from tce.study.results import LOCK_NAME, content_digest, folder_lock, scenario_path
from tce.study.schema import parse_study

from .common import NAMES, TINY, answer, as_from_a_shell, clean, errors, leftovers, tce_run, write


@pytest.fixture(scope="module")
def study():
    return parse_study(TINY, "study.toml")


@pytest.fixture(scope="module")
def reference(study, tmp_path_factory) -> xr.Dataset:
    """The uninterrupted run every resumed one must equal."""
    report = runner.run_study(study, tmp_path_factory.mktemp("reference"), jobs=1)
    return answer(report.results)


def files(study, out: Path) -> dict[str, bool]:
    """Which scenarios have a file under ``out``."""
    folder = out / study.name / "scenarios"
    return {sc.name: scenario_path(folder, sc).exists() for sc in study.scenarios()}


def resume_equals(study, reference, out: Path, reused: int) -> None:
    """A plain rerun ends with exit 0, reuses ``reused`` scenarios and equals ``reference``."""
    rerun = tce_run(write(out.parent, name="again.toml"), out)
    assert rerun.returncode == 0, rerun.stderr
    solved = len(NAMES) - reused
    assert (f"{solved} solved, {reused} reused" if reused else f"({solved} solved)") in rerun.stdout
    xr.testing.assert_identical(answer(out / study.name / "results.nc"), reference)
    assert not leftovers(out)


def test_killed_worker_is_named_and_the_others_are_kept(study, reference, tmp_path) -> None:
    """A scenario that kills its worker every time: solved again alone, killed again, reported."""
    out = tmp_path / "out"
    victim = "none/friction=2"
    run = tce_run(write(tmp_path), out, "--jobs", "2", fault=f"kill:{victim}")
    assert run.returncode == 3
    clean(run.stderr)
    (line,) = errors(run.stderr)
    assert "ended abruptly" in line and repr(victim) in line
    assert files(study, out) == {n: n != victim for n in NAMES}  # the run went on: 3 kept, 0 lost
    assert not (out / "tiny" / "results.nc").exists() and not leftovers(out)
    resume_equals(study, reference, out, reused=3)


def test_a_worker_killed_once_costs_nothing(study, reference, tmp_path) -> None:
    """A worker killed once (the scenario goes through when solved again): a warning naming the
    scenarios that were running, every scenario solved, exit 0."""
    out = tmp_path / "out"
    victim = "none/friction=2"
    run = tce_run(write(tmp_path), out, "--jobs", "2", fault=f"kill-once:{victim}:{tmp_path / 'killed'}")
    assert run.returncode == 0, run.stderr
    clean(run.stderr)
    assert (tmp_path / "killed").exists() and not errors(run.stderr)
    (warning,) = [line for line in run.stderr.splitlines() if "ended abruptly" in line]
    assert repr(victim) in warning and warning.endswith("ran: solved again, each alone")
    assert all(files(study, out).values()) and not leftovers(out)
    xr.testing.assert_identical(answer(out / study.name / "results.nc"), reference)


@pytest.mark.parametrize("jobs", ["1", "2"])
def test_ctrl_c_keeps_a_finished_scenario_not_yet_returned(study, reference, tmp_path, jobs: str) -> None:
    out = tmp_path / "out"
    # the third scenario dispatched: a worker takes it once it has written its first (in-process,
    # after two); the interrupt is sent once its own file is written
    finished = "none/friction=2"
    run = tce_run(write(tmp_path), out, "--jobs", jobs, fault=f"interrupt:{finished}")
    assert run.returncode == 130, run.stderr
    clean(run.stderr)
    said = [line for line in run.stderr.strip().splitlines() if not line.startswith("tce: tiny: ")]  # progress lines
    assert "interrupted" in run.stderr and len(said) <= 2
    kept = files(study, out)
    assert kept[finished] and sum(kept.values()) >= 2  # both written before the parent was told
    assert not leftovers(out)
    resume_equals(study, reference, out, reused=sum(kept.values()))


def test_disk_full_during_the_run(study, reference, tmp_path, monkeypatch, capsys) -> None:
    """An injected ENOSPC at the third write: exit 3 naming the path, two scenarios kept."""
    out = tmp_path / "out"
    to_netcdf = xr.Dataset.to_netcdf
    calls = []

    def full(self, path=None, *args, **kwargs):
        calls.append(path)
        if len(calls) == 3:
            Path(path).write_bytes(b"\0" * 10)  # a partial temporary file, as a full disk leaves
            raise OSError(errno.ENOSPC, "No space left on device")
        return to_netcdf(self, path, *args, **kwargs)

    monkeypatch.setattr(xr.Dataset, "to_netcdf", full)
    assert main(["run", str(write(tmp_path)), "--out", str(out), "--jobs", "1", "--no-plots"]) == 3
    err = capsys.readouterr().err
    clean(err)
    (line,) = errors(err)
    assert "no space left on the device" in line and str(out / "tiny" / "scenarios") in line
    assert sum(files(study, out).values()) == 2 and not leftovers(out)
    monkeypatch.undo()
    resume_equals(study, reference, out, reused=2)


@pytest.fixture
def tmpfs(tmp_path):
    """A 4 MiB tmpfs (skipped where mounting is not permitted)."""
    mount = tmp_path / "disk"
    mount.mkdir()
    made = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=4m", "tmpfs", str(mount)], capture_output=True)
    if made.returncode != 0:
        pytest.skip("cannot mount a tmpfs here (not root?)")
    yield mount
    subprocess.run(["umount", "-l", str(mount)], check=False)


def test_real_full_disk_before_and_during_the_run(study, reference, tmp_path, tmpfs) -> None:
    out = tmpfs / "out"
    # filled up by the first scenario's worker: the others cannot be written
    run = tce_run(write(tmp_path), out, "--jobs", "1", fault=f"fill:{NAMES[0]}:{tmpfs}")
    assert run.returncode == 3
    clean(run.stderr)
    assert "no space left on the device" in errors(run.stderr)[0]
    assert sum(files(study, out).values()) == 1 and not leftovers(out)
    # still full: refused before anything is solved
    again = tce_run(write(tmp_path), out)
    assert again.returncode == 2
    clean(again.stderr)
    (line,) = errors(again.stderr)
    assert str(out / "tiny") in line and "free some space" in line
    (tmpfs / "filler").unlink()
    resume_equals(study, reference, out, reused=1)


def test_read_only_destination(tmp_path, tmpfs) -> None:
    subprocess.run(["mount", "-o", "remount,ro", str(tmpfs)], check=True)
    run = tce_run(write(tmp_path), tmpfs / "out")
    assert run.returncode == 2
    clean(run.stderr)
    (line,) = errors(run.stderr)
    assert "read-only file system" in line and str(tmpfs / "out") in line


def test_a_file_where_the_folder_should_be(tmp_path, capsys) -> None:
    (tmp_path / "out").write_text("not a folder")
    assert main(["run", str(write(tmp_path)), "--out", str(tmp_path / "out"), "--no-plots"]) == 2
    err = capsys.readouterr().err
    clean(err)
    (line,) = errors(err)
    assert "a file is in the way" in line and str(tmp_path / "out") in line
    assert (tmp_path / "out").read_text() == "not a folder"


def test_damaged_scenario_files_are_solved_again(study, reference, tmp_path, caplog) -> None:
    out = tmp_path / "out"
    runner.run_study(study, out, jobs=1)
    folder = out / "tiny" / "scenarios"
    by_name = {sc.name: scenario_path(folder, sc) for sc in study.scenarios()}
    truncated = by_name[NAMES[0]]
    truncated.write_bytes(truncated.read_bytes()[:2000])
    edited = by_name[NAMES[1]]  # a number changed, the attrs kept (a silent corruption)
    ds = xr.load_dataset(edited)
    ds["lambda_max"] = ds["lambda_max"] + 0.1
    ds.to_netcdf(edited)
    holed = by_name[NAMES[2]]  # a variable missing, the key and a matching digest kept (was reused: a NaN hole)
    ds = xr.load_dataset(holed).drop_vars("lambda_direct")
    ds.attrs["content_sha256"] = content_digest(ds)
    ds.to_netcdf(holed)
    resume_equals(study, reference, out, reused=1)


def test_two_runs_on_one_folder(study, reference, tmp_path) -> None:
    """A second run on a folder that a held run writes is refused, naming the holder; the
    first, ended by SIGTERM, leaves a folder that a rerun completes."""
    out = tmp_path / "out"
    first = subprocess.Popen(
        [sys.executable, "-m", "tce.cli", "run", str(write(tmp_path)), "--out", str(out), "--no-plots", "--jobs", "1"],
        env=dict(os.environ, TCE_FAULT=f"hold:{NAMES[0]}", PYTHONPATH=str(Path(__file__).parent / "hook")),
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True, preexec_fn=as_from_a_shell,
    )
    try:
        for line in first.stderr:  # the run says it is running once it holds the folder
            if line.startswith("tce: running tiny"):
                break
        assert (out / "tiny" / LOCK_NAME).exists()
        second = tce_run(write(tmp_path, name="second.toml"), out)
        assert second.returncode == 2
        clean(second.stderr)
        (line,) = errors(second.stderr)
        assert "another run is writing this folder" in line and f"pid {first.pid}" in line
    finally:
        first.send_signal(signal.SIGTERM)
        _, stderr = first.communicate(timeout=300)
    assert first.returncode == 143, stderr
    clean(stderr)
    resume_equals(study, reference, out, reused=0)


def test_a_stale_lock_is_taken_over(study, tmp_path) -> None:
    folder = tmp_path / "out" / "tiny"
    folder.mkdir(parents=True)
    (folder / LOCK_NAME).write_text("pid 999999 on elsewhere since 2020-01-01T00:00:00")  # its holder is gone
    report = runner.run_study(study, tmp_path / "out", jobs=1)
    assert len(report.solved) == 4 and not (folder / LOCK_NAME).exists()


def test_a_held_lock_refuses_in_process(study, tmp_path) -> None:
    folder = tmp_path / "out" / "tiny"
    folder.mkdir(parents=True)
    with folder_lock(folder):
        with pytest.raises(runner.RunError, match="another run is writing this folder"):
            runner.run_study(study, tmp_path / "out", jobs=1)
    assert not list(folder.glob("scenarios/*.nc"))


def test_a_study_folder_that_links_outside_out(study, tmp_path) -> None:
    (tmp_path / "out").mkdir()
    (tmp_path / "elsewhere").mkdir()
    (tmp_path / "out" / "tiny").symlink_to(tmp_path / "elsewhere")
    with pytest.raises(runner.RunError, match="outside"):
        runner.run_study(study, tmp_path / "out", jobs=1)
    assert not any((tmp_path / "elsewhere").iterdir())


def test_fresh_deletes_only_its_own_scenarios(study, reference, tmp_path) -> None:
    out = tmp_path / "out"
    runner.run_study(study, out, jobs=1)
    other = out / "other" / "scenarios"
    other.mkdir(parents=True)
    (other / "keep.nc").write_text("x")
    report = runner.run_study(study, out, jobs=1, fresh=True)
    assert len(report.solved) == 4 and (other / "keep.nc").exists()
    xr.testing.assert_identical(answer(report.results), reference)
    assert np.isfinite(reference["lambda_max"]).all()
