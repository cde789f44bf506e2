"""Signals of the ``tce`` program: SIGTERM and SIGHUP end it as Ctrl-C does.

:func:`handle_signals` (called first thing by :func:`tce.cli.main`, before the heavy
imports) makes SIGINT, SIGTERM and SIGHUP raise :class:`Interrupted` (a
:class:`KeyboardInterrupt`) in the main thread, so that every command stops the same way
whatever ends it: a run stops its workers, keeps every finished scenario and removes its
temporary files (:mod:`tce.study.runner`), and the program prints one line and exits with
``128 + signal`` (130 for Ctrl-C, 143 for SIGTERM, 129 for SIGHUP). Later signals are
ignored while it stops (SIGKILL still ends it at once; no finished scenario is lost, since
each is written before its worker reports it). ``import tce`` in the ``tce`` program (and
only there: ``sys.argv[0]`` is ``tce``) installs the handlers first thing, in a mode that
ends the process with one line, so that Ctrl-C while numpy and the rest are imported prints
no traceback; only the interpreter's own start-up, before any tce code runs, is left to
Python.

:func:`quiet_children` starts processes with Ctrl-C ignored from their first instruction
(an ignored signal stays ignored across ``exec``, and Python keeps it so), so that a worker
still importing its modules prints no traceback when Ctrl-C reaches its process group.
"""

from __future__ import annotations

# only what the interpreter has loaded already, and _signal (signal without its enums, which
# take milliseconds to import): this module is imported first
import _signal as signal
import contextlib
import os
from types import FrameType

__all__ = ["Interrupted", "exit_code", "handle_signals", "quiet_children", "restore_signals"]

_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)
_NAMES = {signal.SIGINT: "SIGINT", signal.SIGTERM: "SIGTERM", signal.SIGHUP: "SIGHUP"}


class Interrupted(KeyboardInterrupt):
    """The program was asked to stop by ``signum`` (Ctrl-C is SIGINT)."""

    def __init__(self, signum: int) -> None:
        super().__init__(_NAMES.get(signum, f"signal {signum}"))
        self.signum = signum


_raising = False


def _stop(signum: int, frame: FrameType | None) -> None:
    for sig in _SIGNALS:  # stopping: further signals are not allowed to break the clean-up
        signal.signal(sig, signal.SIG_IGN)
    if not _raising:  # still importing: nothing to clean up, and nothing to catch an exception
        os.write(2, f"tce: interrupted ({_NAMES.get(signum, signum)})\n".encode())
        os._exit(128 + signum)
    raise Interrupted(signum)


def handle_signals(raising: bool = True) -> dict[int, object]:
    """SIGINT, SIGTERM and SIGHUP raise :class:`Interrupted` in the main thread (module
    docstring); with ``raising=False`` (while the program imports its modules, before
    anything could catch it) they print one line and end the process at once.

    Returns the dispositions it replaced, for :func:`restore_signals`: a caller that is not the
    ``tce`` program (a script or a test calling :func:`tce.cli.main`) gets its own back.
    """
    global _raising
    _raising = raising
    before = {sig: signal.getsignal(sig) for sig in _SIGNALS}
    for sig in _SIGNALS:
        if before[sig] is not signal.SIG_IGN:  # nohup's choice is kept
            signal.signal(sig, _stop)
    return before


def restore_signals(before: dict[int, object]) -> None:
    """Put back the dispositions :func:`handle_signals` replaced (also the ignored signals a
    stop leaves behind), so that processes started afterwards do not inherit an ignored Ctrl-C."""
    for sig, handler in before.items():
        if handler is not None:  # None: set from outside Python, not restorable
            signal.signal(sig, handler)


def exit_code(exc: KeyboardInterrupt) -> int:
    """``128 + signal``: 130 for Ctrl-C (a plain KeyboardInterrupt too), 143 for SIGTERM."""
    return 128 + getattr(exc, "signum", signal.SIGINT)


@contextlib.contextmanager
def quiet_children():  # -> Iterator[None]
    """Within the block, processes started inherit an ignored Ctrl-C (module docstring).

    This process ignores Ctrl-C only while it starts them (a fork and an exec).
    """
    import threading

    if threading.current_thread() is not threading.main_thread():  # only the main thread sets handlers
        yield
        return
    before = signal.getsignal(signal.SIGINT)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, before)
