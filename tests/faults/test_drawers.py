"""Figures drawn by the processes ``tce run`` prepares while it solves (:mod:`tce.plot.drawers`):
the same files as drawing in the run's process, and the same faults: a full disk reported as
one line naming the file, a drawer that dies replaced by the run's process, Ctrl-C and
``kill -9`` leaving no drawer and no temporary file behind."""

from __future__ import annotations

import errno
import logging
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path

import pytest
import xarray as xr

from tce.cli import main
from tce.plot import output, rendering, spare
from tce.plot import drawers as drawers_module
from tce.plot.drawers import Drawers, cpu_free
from tce.study import runner
from tce.study.schema import parse_study

from .common import TINY, as_from_a_shell, clean, errors, leftovers, write

#: the tiny study without its sweep, both scenarios drawn: four PNG files and the view
DRAWN = TINY.replace("[sweep]\nfriction = [0.8, 2.0]", "[material]\nfriction = 0.8") + '\n[plots]\nscenarios = ["none", "outward"]\nkinds = ["states", "thrust", "thrust_lines", "mechanism", "view"]\n'


@pytest.fixture(scope="module")
def finished(tmp_path_factory) -> xr.Dataset:
    study = parse_study(DRAWN, "study.toml")
    return xr.load_dataset(runner.run_study(study, tmp_path_factory.mktemp("finished"), jobs=1).results)


@pytest.fixture
def start():
    """Start drawers (after the test's patches: they are forked with them), closed after the test."""
    started = []

    def go() -> Drawers:
        d = Drawers.start(2)
        if d is None:
            pytest.skip("drawers need Linux and two usable cores")
        started.append(d)
        return d

    yield go
    for d in started:
        d.close()


def _elsewhere(request) -> bool:
    """Run this test in a fresh pytest process when this one has other threads (left by other
    tests: tce forks drawers only from a single-threaded process), and say whether it did."""
    if threading.active_count() == 1:
        return False
    assert "TCE_TEST_ALONE" not in os.environ, f"threads in a fresh pytest process: {threading.enumerate()}"
    done = subprocess.run([sys.executable, "-m", "pytest", "-v", "-p", "no:cacheprovider", "-p", "no:xdist",
                           request.node.nodeid], cwd=request.config.rootpath, capture_output=True, text=True,
                          timeout=600, env=dict(os.environ, TCE_TEST_ALONE="1"))
    assert done.returncode == 0 and "1 passed" in done.stdout, done.stdout[-4000:]
    return True


def _gone(pids: list[int], within: float = 5.0) -> None:
    """Every process of ``pids`` ends within ``within`` seconds (a zombie has ended)."""
    end = time.monotonic() + within
    while any(runner._alive(pid) for pid in pids):
        assert time.monotonic() < end, f"processes {[p for p in pids if runner._alive(p)]} are still running"
        time.sleep(0.05)


def test_the_same_files_in_the_same_order(finished, start, tmp_path, request) -> None:
    if _elsewhere(request):
        return
    here = output.write_figures(finished, tmp_path / "here")
    drawers = start()
    there = output.write_figures(finished, tmp_path / "there", draw=drawers.draw)
    assert [p.name for p in there] == [p.name for p in here] and len(here) >= 5
    for a, b in zip(here, there):
        assert a.read_bytes() == b.read_bytes(), a.name
    assert not leftovers(tmp_path)
    drawers.close()  # idle drawers end on their own when the run closes its pipes
    assert drawers.process.exitcode == 0


#: the tiny study with its sweep, three of its four scenarios drawn, every kind that applies
SWEPT = TINY + '\n[plots]\nscenarios = ["none/friction=0.8", "none/friction=2", "outward/friction=0.8"]\nkinds = ["states", "thrust", "thrust_lines", "base", "mechanism", "view", "summary"]\n'


def test_each_file_drawn_from_what_a_worker_receives_is_the_same(tmp_path) -> None:
    """A worker of ``tce plot --jobs`` receives only the part of the results a file reads
    (output._subset; a drawer of ``tce run`` receives the whole): every file drawn from it is the
    same, byte for byte, as drawn from the whole dataset (a mechanism's title once said "every
    scenario drawn" for a group that was all of its part only)."""
    ds = xr.load_dataset(runner.run_study(parse_study(SWEPT, "study.toml"), tmp_path / "run", jobs=1).results)
    tasks = output.figure_tasks(ds, output.plot_spec(ds))
    assert {t.kind for t in tasks} >= {"states", "thrust", "mechanism", "view", "summary"}
    for folder in ("whole", "part"):
        (tmp_path / folder).mkdir()
    for t in tasks:
        whole = output.render(ds, t, tmp_path / "whole")
        part = output.render(output._subset(ds, t), t, tmp_path / "part")
        assert whole.read_bytes() == part.read_bytes(), t.name


def test_spare_axes_draw_the_same_bytes(finished, tmp_path) -> None:
    """Figures drawn on the spare figures and axes a drawer makes while it waits
    (:mod:`tce.plot.spare`) are the same files, byte for byte."""
    here = output.write_figures(finished, tmp_path / "here")
    for _ in range(3 * spare.AXES):
        spare.make()
    made = spare.ready()
    there = output.write_figures(finished, tmp_path / "there")
    assert spare.ready() < made - 4  # the thrust curves took a spare figure and its four axes at least
    assert [p.name for p in there] == [p.name for p in here]
    for a, b in zip(here, there):
        assert a.read_bytes() == b.read_bytes(), a.name


#: the tce program's imports before it draws, in a fresh process: matplotlib made lean, then the figures
LEAN = """
import sys
import xarray as xr
from tce.plot import output, rendering
from tce.plot.rendering import lean_matplotlib
assert "matplotlib.artist" not in sys.modules and lean_matplotlib()
from matplotlib.lines import Line2D
assert Line2D.set.__doc__ is None  # the docstring was not written
line = Line2D([], [])
line.set(color="red", lw=3.0)  # set works as before, aliases too
assert line.get_color() == "red" and line.get_linewidth() == 3.0
output.write_figures(xr.load_dataset(sys.argv[1]), sys.argv[2])
"""


#: what a drawer has imported once warm, in a fresh process: the figure modules, not the solvers
WARM = """
import sys
import tce.cli, tce.plot.drawers
assert "numpy" not in sys.modules  # tce run forks its first drawer before it imports numpy
tce.plot.drawers._warm()
heavy = [m for m in ("scipy.sparse", "clarabel", "pydantic", "tce.study.schema", "tce.core.model") if m in sys.modules]
assert "matplotlib.figure" in sys.modules and "tce.plot.view" in sys.modules and not heavy, heavy
"""


def test_a_drawer_warms_up_without_the_solvers() -> None:
    """A drawer forked as ``tce run`` starts imports xarray, matplotlib and the figure modules
    only (issue 24: ready before the run's results, which it needs to draw)."""
    done = subprocess.run([sys.executable, "-c", WARM], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr[-2000:]


def test_lean_artists_draw_the_same_bytes(finished, tmp_path) -> None:
    """Matplotlib imported as the ``tce`` program imports it (:func:`tce.plot.rendering.lean_matplotlib`:
    no docstrings for ``set``) draws every file byte for byte as imported as usual (this process)."""
    here = output.write_figures(finished, tmp_path / "here")
    finished.to_netcdf(tmp_path / "results.nc")
    subprocess.run([sys.executable, "-c", LEAN, str(tmp_path / "results.nc"), str(tmp_path / "there")],
                   check=True, timeout=300)
    for a in here:
        assert a.read_bytes() == (tmp_path / "there" / a.name).read_bytes(), a.name


def test_a_bad_study_kills_the_drawers_it_started(tmp_path, monkeypatch, capsys, request) -> None:
    """The first drawer is forked before the study is read (it warms up meanwhile): a study
    that does not load exits 2, nothing written, its drawer killed rather than waited for."""
    if _elsewhere(request):
        return
    monkeypatch.setattr(drawers_module, "cpu_free", lambda: True)  # drawers however busy the machine is
    started = []
    start = Drawers.start.__func__

    def recorded(cls, n):
        started.append(start(cls, n))
        return started[-1]

    monkeypatch.setattr(Drawers, "start", classmethod(recorded))
    out = tmp_path / "out"
    assert main(["run", str(write(tmp_path, TINY + "\n[bogus]\nkey = 1\n")), "--out", str(out)]) == 2
    assert "bogus" in capsys.readouterr().err and not out.exists()
    (drawers,) = started
    assert drawers is not None and drawers.process.exitcode == -signal.SIGKILL


def test_no_drawers_with_one_job_or_one_core(monkeypatch) -> None:
    assert Drawers.start(1) is None
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {0})
    assert Drawers.start(2) is None


def test_no_drawers_while_other_programs_hold_the_cpus(tmp_path, monkeypatch) -> None:
    pressure = tmp_path / "cpu"
    real_open = open

    def fake_open(path, *args, **kwargs):
        return real_open(pressure if path == "/proc/pressure/cpu" else path, *args, **kwargs)

    monkeypatch.setattr("builtins.open", fake_open)
    pressure.write_text("some avg10=81.91 avg60=88.71 avg300=81.65 total=14732235240\n"
                        "full avg10=0.00 avg60=0.00 avg300=0.00 total=0\n")
    assert cpu_free() is False
    pressure.write_text("some avg10=3.10 avg60=88.71 avg300=81.65 total=14732235240\n")
    assert cpu_free() is True
    pressure.unlink()  # no pressure information: the cores decide
    assert cpu_free() is True


def _fail_on(name: str, how, monkeypatch) -> None:
    """Make a drawer call ``how(path)`` as it opens the file ``name`` to write it
    (:func:`tce.plot.rendering.save_png`'s ``open``)."""
    run = os.getpid()

    def opening(path, *args, **kwargs):
        if os.getpid() != run and Path(path).name == f".{name}.tmp":
            how(path)
        return open(path, *args, **kwargs)

    monkeypatch.setattr(rendering, "open", opening, raising=False)


def _full(path) -> None:
    raise OSError(errno.ENOSPC, "No space left on device")  # as a write says it: no file name


def test_a_full_disk_in_a_drawer_is_the_runs_figure_fault(tmp_path, monkeypatch, capsys, request) -> None:
    if _elsewhere(request):
        return
    monkeypatch.setattr(drawers_module, "cpu_free", lambda: True)  # drawers however busy the machine is
    _fail_on("thrust.png", _full, monkeypatch)
    out = tmp_path / "out"
    assert main(["run", str(write(tmp_path, DRAWN)), "--out", str(out), "--no-report"]) == 3
    err = capsys.readouterr().err
    clean(err)
    (line,) = errors(err)
    assert "no space left on the device" in line and ".thrust.png.tmp" in line
    assert (out / "tiny" / "results.nc").exists() and "tce plot" in err and not leftovers(out)


def test_results_that_cannot_be_written_leave_no_figure(tmp_path, monkeypatch, capsys, request) -> None:
    """The drawers draw while ``results.nc`` is written (issue 24): a write that fails once a
    figure is drawn leaves neither that figure nor any other, and no temporary file."""
    if _elsewhere(request):
        return
    monkeypatch.setattr(drawers_module, "cpu_free", lambda: True)  # drawers however busy the machine is
    out = tmp_path / "out"
    folder = out / "tiny"

    def failing(ds, path) -> None:  # the disk fills up once a drawer has finished a file
        end = time.monotonic() + 60
        while not [p for p in [*folder.glob("*.png"), *folder.glob(".*.png.tmp")] if p.stat().st_size > 1000]:
            assert time.monotonic() < end, "no figure was drawn while results.nc was written"
            time.sleep(0.01)
        time.sleep(0.2)
        raise runner.StorageError(f"{path}: no space left on the device")

    monkeypatch.setattr(runner, "write_atomic", failing)
    assert main(["run", str(write(tmp_path, DRAWN)), "--out", str(out), "--no-report"]) == 3
    err = capsys.readouterr().err
    assert "results.nc: no space left on the device" in err and "results.nc was not written" in err
    assert not list(folder.glob("*.png")) and not list(folder.glob("*.html")) and not leftovers(out)


def test_a_drawer_that_dies_is_replaced_by_the_run(finished, start, tmp_path, monkeypatch, caplog, request) -> None:
    if _elsewhere(request):
        return
    here = output.write_figures(finished, tmp_path / "here")
    _fail_on("thrust.png", lambda path: os.kill(os.getpid(), signal.SIGKILL), monkeypatch)
    logger = logging.getLogger("tce.plot.drawers")
    logger.addHandler(caplog.handler)  # whatever an earlier main() made of the "tce" logger
    try:
        there = output.write_figures(finished, tmp_path / "there", draw=start().draw)
    finally:
        logger.removeHandler(caplog.handler)
    assert [p.name for p in there] == [p.name for p in here]
    assert all(a.read_bytes() == b.read_bytes() for a, b in zip(here, there))
    assert "while drawing thrust.png: drawing it here" in caplog.text and not leftovers(tmp_path)


def test_ctrl_c_while_drawers_draw(finished, start, tmp_path, monkeypatch, request) -> None:
    if _elsewhere(request):
        return
    pids = tmp_path / "pids"
    pids.mkdir()

    def stuck(fname) -> None:  # a drawer half-way through writing its file
        Path(fname).write_bytes(b"half")
        (pids / str(os.getpid())).touch()
        time.sleep(60)

    _fail_on("thrust.png", stuck, monkeypatch)
    drawers = start()

    def interrupt(signum, frame):  # Ctrl-C once a drawer is stuck: pressed once (the timer stops), so
        if any(pids.iterdir()):  # that it never lands in the run's own clean-up
            signal.setitimer(signal.ITIMER_REAL, 0)
            raise KeyboardInterrupt

    before = signal.signal(signal.SIGALRM, interrupt)
    try:
        signal.setitimer(signal.ITIMER_REAL, 0.1, 0.1)
        with pytest.raises(KeyboardInterrupt):
            output.write_figures(finished, tmp_path / "out", draw=drawers.draw)
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, before)
    (stuck_pid,) = [int(p.name) for p in pids.iterdir()]
    assert not leftovers(tmp_path / "out")  # its pipe closed: it writes nothing more
    _gone([stuck_pid, drawers.process.pid])


def test_kill_9_of_the_run_ends_its_drawers(tmp_path) -> None:
    """The drawers die with ``tce run`` (a parent-death signal), even one stuck in a figure."""
    hook = tmp_path / "hook"
    hook.mkdir()
    (hook / "sitecustomize.py").write_text(textwrap.dedent(f"""
        import os, time
        from pathlib import Path
        import tce.plot.rendering
        def stuck(path, *args, **kwargs):  # opening a figure's file (the warm-up writes into memory)
            Path({str(tmp_path)!r}, "drawer-" + str(os.getpid())).touch()
            time.sleep(120)
        tce.plot.rendering.open = stuck
        import tce.plot.drawers
        tce.plot.drawers.cpu_free = lambda: True  # drawers however busy the machine is
    """))
    env = dict(os.environ, MPLBACKEND="Agg", PYTHONPATH=os.pathsep.join([str(hook), os.environ.get("PYTHONPATH", "")]))
    cmd = [sys.executable, "-m", "tce.cli", "run", str(write(tmp_path, DRAWN)), "--out", str(tmp_path / "out"),
           "--no-report"]
    run = subprocess.Popen(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, start_new_session=True,
                           preexec_fn=as_from_a_shell)
    try:
        end = time.monotonic() + 120
        while len(list(tmp_path.glob("drawer-*"))) < 2:  # both drawers inside a figure
            assert time.monotonic() < end and run.poll() is None, run.stderr.read() if run.poll() is not None else ""
            time.sleep(0.05)
        run.kill()
        run.wait()
        _gone([int(p.name.split("-")[1]) for p in tmp_path.glob("drawer-*")])
    finally:
        if run.poll() is None:
            run.kill()
        run.communicate()
    assert (tmp_path / "out" / "tiny" / "results.nc").exists()
