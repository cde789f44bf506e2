"""Draw a run's figures in processes that got ready while the run solved (issue 24).

Figures cost a ``tce run`` of the paper's arch more than its solving: importing xarray,
matplotlib and tce's figure modules (0.7-0.85 CPU-s, matplotlib made lean,
:func:`tce.plot.rendering.lean_matplotlib`) and drawing them (0.55-0.75 CPU-s for Fig. 9's six
files), against 1.0-1.3 CPU-s for the whole run without figures. None of the imports needs the
results, and the figures do not need each other. :meth:`Drawers.start` therefore forks one
process as ``tce run`` starts (:mod:`tce.cli`, which imports neither numpy nor the study's
schema before it), that imports those modules and nothing of the solvers (scipy, Clarabel,
pydantic: the kinds whose modules need them are imported on :meth:`Drawers.prepare`, sent once
the study is read) and draws a small figure (fonts loaded, caches filled) while the run
imports, reads the study and solves; then, until the results come, it makes spare axes with
their ticks (:mod:`tce.plot.spare`: :data:`SPARES`, about a third of the drawing's own work
on Fig. 9, none of it needing the results), and forks the others from itself (a fork of a warm
process is ready at once, spares included). On the paper's arch the first is warm 0.15-0.35 s before the
results are. As soon as the results are merged, :meth:`Drawers.draw` hands the figures out
one at a time to whichever drawer is free, the costliest kinds first (:data:`COST`), the
dataset with a drawer's first figure only; the run writes ``results.nc`` while the first ones
are drawn, then puts each file in place as it comes back (a drawer leaves it under its
temporary name), and returns them in the order of :func:`tce.plot.output.figure_tasks`. On two
cores the imports overlap the solving and the drawing is split in two, so a run with figures
waits about half of what drawing them costs; the CPU spent is that of drawing them in the
run's own process plus the drawer's own imports of xarray (0.3-0.4 CPU-s).

Drawers are used only where they should not be slower than drawing in the run's process: on
Linux (a fork, a parent-death signal), with at least two cores usable, more than one job
allowed (``--jobs 1`` draws in its own process as before), a single-threaded caller (a fork
copies only the calling thread) and, as ``tce run`` decides, CPUs that other programs leave
free (:func:`cpu_free`). The drawers spend a little more CPU than the run's process would
(their fork and the pages it copies; collections skip the inherited objects, ``gc.freeze``).

Faults are those of drawing in the run's process:

- each figure is written atomically (:func:`tce.plot.output.render`, put in place by the run
  only once ``results.nc`` is written: a write that fails leaves no figure); a failure (a full disk
  is an :class:`OSError` naming the file) is raised in the run's process as if it had happened
  there, after the figures being drawn elsewhere are finished; no further figure is started;
- a drawer that dies leaves its figure to be drawn again in the run's process, with the others
  no drawer took;
- drawers ignore Ctrl-C and SIGHUP (the run decides), are ended by :meth:`Drawers.close` (the
  run's Ctrl-C and every exit go through it: it removes the temporary file of a figure cut
  short), and die with the process that started them (``PR_SET_PDEATHSIG``), so a
  ``kill -9`` of ``tce run`` leaves none behind. They are started before the run takes its
  folder's lock, so they never hold it.
"""

from __future__ import annotations

import contextlib
import gc
import logging
import multiprocessing as mp
import multiprocessing.connection
import os
import pickle
import signal
import sys
import threading
import traceback
from collections import deque
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..signals import quiet_children
from ..study.progress import Progress

if TYPE_CHECKING:
    from collections.abc import Callable, Iterable

    import xarray as xr

__all__ = ["PRESSURE_LIMIT", "Drawers", "cpu_free"]

log = logging.getLogger(__name__)

#: CPU pressure (percent of the last 10 s some task waited for a CPU) from which drawing in the
#: run's process is chosen (:func:`cpu_free`)
PRESSURE_LIMIT = 25.0
#: seconds to wait for a drawer to end before killing it
_GRACE = 5.0
#: spare axes (:mod:`tce.plot.spare`) the first drawer makes while it waits, before it forks the
#: others (three figures of four axes: Fig. 9's files use 12 axes in five figures)
SPARES = 12
#: rough CPU (ms) of one file of each kind, measured in drawers on Fig. 7-8 and Fig. 9 (other
#: kinds: :data:`_USUAL`): the drawers take the costliest first, so that the last files handed
#: out are short and the drawers finish together (largest first, Graham's LPT rule)
COST = {"thrust": 160, "states": 120, "transversal": 120, "base": 110, "view": 80, "mechanism": 60}
_USUAL = 100


class DrawerTraceback(Exception):
    """The traceback of a figure that failed in a drawer (the cause of the error re-raised)."""


def _die_with(parent: int) -> None:
    """End this process when ``parent`` ends (Linux ``PR_SET_PDEATHSIG``), or now if it has."""
    import ctypes

    ctypes.CDLL(None).prctl(1, signal.SIGKILL, 0, 0, 0)  # PR_SET_PDEATHSIG
    if os.getppid() != parent:  # it ended before the request
        os._exit(0)


def _warm() -> None:
    """Import the figure modules of the paper's kinds (:func:`tce.plot.output.builder`; the
    others on :meth:`Drawers.prepare`), read plotly.js (:func:`tce.plot.view.plotly_js`,
    11 ms) and draw a small figure with text (loads the fonts), encoded as the figures are
    (:func:`tce.plot.rendering.png_bytes`)."""
    from .rendering import lean_matplotlib, png_bytes

    lean_matplotlib()
    from matplotlib.figure import Figure

    from .output import builder
    from .view import plotly_js

    for kind in ("thrust", "view"):
        builder(kind)
    plotly_js()
    fig = Figure(figsize=(1, 1))
    ax = fig.add_subplot()
    ax.plot([0, 1], [0, 1], label="λ")
    ax.set_title("warm")
    ax.legend()
    png_bytes(fig)


def _prepare(kinds: Iterable[str]) -> None:
    """Import the modules drawing ``kinds`` (:meth:`Drawers.prepare`)."""
    from .output import builder

    for kind in kinds:
        with contextlib.suppress(Exception):  # drawing the kind will say what is wrong
            builder(kind)


def _spares(conn: mp.connection.Connection) -> tuple | None:
    """Make spare axes (:mod:`tce.plot.spare`, one at a time, 10-15 ms each) until
    :data:`SPARES` are made or the run sends a figure, handling ``prepare`` messages meanwhile.

    Returns the first ``draw`` message, or None (all made, or the run closed its end)."""
    from . import spare

    while spare.ready() < SPARES:
        try:
            if not conn.poll():
                spare.make()
                continue
            msg = conn.recv()
        except (EOFError, OSError):  # the run closed its end: _serve finds out
            return None
        if msg[0] != "prepare":
            return msg
        _prepare(msg[1])
    return None


def _serve(conn: mp.connection.Connection, first: tuple | None = None) -> None:
    """Draw the tasks the run sends on ``conn``, replying with the file or the failure.

    A message is ``("prepare", kinds)`` (import what drawing those kinds needs, no reply) or
    ``("draw", ds, task, outdir)``, where ``ds`` is the results dataset with the first task and
    None after it (the one kept is drawn); the file is left under its temporary name
    (:func:`tce.plot.output.render` with ``place=False``): the run puts it in place once
    ``results.nc`` is written. ``first`` is a message received already (:func:`_spares`)."""
    from .output import render

    ds = None
    while True:
        try:
            msg, first = first or conn.recv(), None
        except (EOFError, OSError):  # the run closed its end
            return
        if msg[0] == "prepare":
            _prepare(msg[1])
            continue
        _, sent, task, outdir = msg
        ds = sent if sent is not None else ds
        try:
            reply: tuple = ("drawn", render(ds, task, Path(outdir), place=False))
        except Exception as exc:  # noqa: BLE001 - raised again in the run's process
            reply = ("failed", exc, traceback.format_exc())
        try:
            try:
                conn.send(reply)
            except (pickle.PicklingError, TypeError, AttributeError):  # an exception that does not pickle
                conn.send(("failed", RuntimeError(f"{type(reply[1]).__name__}: {reply[1]}"), reply[2]))
        except OSError:
            return


def _first(conns: list, run_ends: list, parent: int) -> None:
    """The drawer forked from the run: warm up, fork the others, serve ``conns[0]``."""
    _die_with(parent)
    for sig in (signal.SIGINT, signal.SIGHUP):
        signal.signal(sig, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    for c in run_ends:  # the run's ends: its death must reach us as an end of file
        c.close()
    try:
        _warm()
    except Exception:  # noqa: BLE001 - the figures themselves will say what is wrong
        log.debug("warming up a drawer failed", exc_info=True)
    try:
        first = _spares(conns[0])  # the others are forked with them
    except Exception:  # noqa: BLE001 - drawn without spares
        log.debug("making spare axes failed", exc_info=True)
        first = None
    me = os.getpid()
    gc.freeze()
    for k in range(1, len(conns)):
        if os.fork() == 0:
            try:
                _die_with(me)
                for j, c in enumerate(conns):
                    if j != k:
                        c.close()
                _serve(conns[k])
            finally:
                os._exit(0)
        conns[k].close()
    _serve(conns[0], first)
    conns[0].close()
    # not waiting for the others: they end as their pipes close (the run closes them all at
    # once, with no figure under way) or die with this process; the run waits for this one
    # only (each exit takes 7-8 ms on Fig. 9, and one waited for the other)


def cpu_free(limit: float = PRESSURE_LIMIT) -> bool:
    """Whether the CPUs are free enough for drawers to gain time: tasks waited for a CPU less
    than ``limit`` percent of the last 10 s (Linux's pressure stall information,
    ``/proc/pressure/cpu``, ``some avg10``; True where it cannot be read).

    While other programs keep every core busy, a second process gains no wall time and the
    drawers' own cost (a fork, the pages it copies and a second process: 0.5-0.6 CPU-s more than
    drawing in the run's process on the paper's arch at a load average of 6) makes the run
    slower than drawing in its own process."""
    try:
        with open("/proc/pressure/cpu") as fh:
            some = fh.readline().split()
        return float(some[1].split("=")[1]) < limit
    except (OSError, IndexError, ValueError):
        return True


class Drawers:
    """Processes that draw a run's figures (module docstring); start with :meth:`start`."""

    def __init__(self, process: mp.process.BaseProcess, conns: list) -> None:
        self.process = process
        self.conns = conns
        #: whether :meth:`draw` handed out a figure (else :meth:`close` need not wait for them)
        self.drew = False

    @classmethod
    def start(cls, n: int) -> Drawers | None:
        """Fork ``n`` drawers (the first from this process, the others from it once warm), or
        None where drawing here is as fast (module docstring: fewer than two usable cores or
        ``n < 2``, not Linux, other threads running)."""
        cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else 1
        n = min(n, cores)
        if n < 2 or not sys.platform.startswith("linux") or threading.active_count() > 1:
            return None
        ctx = mp.get_context("fork")
        pairs = [ctx.Pipe() for _ in range(n)]
        ours, theirs = [a for a, _ in pairs], [b for _, b in pairs]
        process = ctx.Process(target=_first, args=(theirs, ours, os.getpid()), daemon=True,
                              name="tce-drawer")
        gc.freeze()  # the drawers' collections skip what they inherit: no copies of its pages
        try:
            with quiet_children():  # Ctrl-C between the fork and its handlers is the run's
                process.start()
        finally:
            gc.unfreeze()
        for c in theirs:
            c.close()
        log.debug("drawers: %d, the first is process %d", n, process.pid)
        return cls(process, ours)

    def prepare(self, kinds: Iterable[str]) -> None:
        """Have the drawers import what drawing ``kinds`` needs beyond the paper's kinds (the
        load-position and settlement figures import the solvers), while the run solves."""
        for conn in self.conns:
            with contextlib.suppress(OSError):  # a drawer that died: draw() finds out
                conn.send(("prepare", tuple(kinds)))

    def draw(self, ds: xr.Dataset, tasks: list, outdir: Path, written: Callable[[], None] | None = None) -> list[Path]:
        """Draw ``tasks`` (:func:`tce.plot.output.figure_tasks`) of ``ds`` into ``outdir``.

        ``written()`` (``tce run`` writes ``results.nc`` with it) is called once every drawer has
        its first figure, and before any file is put in place: the drawers leave each file
        under its temporary name, renamed here as it comes back; if ``written`` raises, the
        drawers are ended and no figure is left.

        Returns the files in task order; raises the first failure (module docstring)."""
        from .output import render, temporary

        queue = deque(sorted(range(len(tasks)), key=lambda k: -COST.get(tasks[k].kind, _USUAL)))
        busy: dict[Any, int] = {}
        files: dict[int, Path] = {}
        failure: tuple | None = None
        given: set[Any] = set()  # drawers that hold ``ds``

        def feed(conn: Any) -> None:
            if not queue or failure is not None:
                return
            k = queue.popleft()
            busy[conn] = k
            self.drew = True
            bar.doing(tasks[k].name)  # the file last handed out, as drawing here names the file under way
            try:  # the dataset once (a drawer keeps it): 0.8 ms to pickle Fig. 9's, against
                # 2.5 ms for the part each file reads (output._subset, as tce plot --jobs sends)
                conn.send(("draw", None if conn in given else ds, tasks[k], str(outdir)))
                given.add(conn)
            except OSError:  # it died: drawn here or by another
                del busy[conn]
                queue.appendleft(k)
                self._drop(conn)

        try:
            with Progress(len(tasks), "figures", unit="file") as bar:
                for conn in list(self.conns):
                    feed(conn)
                if written is not None:  # while they draw
                    written()
                while busy:
                    for conn in mp.connection.wait(list(busy)):
                        try:
                            reply = conn.recv()
                        except (EOFError, OSError):
                            k = busy.pop(conn)
                            log.warning("a figure drawer ended while drawing %s: drawing it here", tasks[k].name)
                            queue.appendleft(k)
                            self._drop(conn)
                            continue
                        k = busy.pop(conn)
                        if reply[0] == "drawn":  # under its temporary name: put in place
                            files[k] = Path(outdir) / tasks[k].name
                            Path(reply[1]).replace(files[k])
                            bar.update()
                        elif failure is None:
                            failure = reply[1:]
                        feed(conn)
                if failure is not None:
                    exc, tb = failure
                    raise exc from DrawerTraceback(tb)
                for k in queue:  # no drawer left
                    files[k] = render(ds, tasks[k], outdir)
                    bar.update()
        except BaseException:
            if busy:  # interrupted (Ctrl-C, a failed write) while drawers draw: end them, remove what they left
                self._kill()
                for k in busy.values():
                    temporary(Path(outdir) / tasks[k].name).unlink(missing_ok=True)
            raise
        return [files[k] for k in range(len(tasks))]

    def _drop(self, conn: Any) -> None:
        self.conns.remove(conn)
        conn.close()

    def _kill(self) -> None:
        """Kill the drawers (the first; the others die with it) and wait until each is gone
        (its end of the pipe closes)."""
        self.process.kill()
        for conn in self.conns:
            with contextlib.suppress(EOFError, OSError):
                while conn.poll(_GRACE):
                    conn.recv()
        self.close()

    def close(self) -> None:
        """End the drawers: each ends when its pipe closes, the others at the latest with the
        first, which this waits for; drawers never handed a figure (a bad study, a failed run)
        are killed: they may still be warming up, and have no file to finish. Idempotent."""
        for conn in self.conns:
            conn.close()
        self.conns = []
        if not self.drew:
            self.process.kill()
        self.process.join(_GRACE)
        if self.process.is_alive():
            self.process.kill()
            self.process.join()
