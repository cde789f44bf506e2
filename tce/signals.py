"""Signals of the ``tce`` program: SIGTERM and SIGHUP end it as Ctrl-C does.

:func:`handle_signals` (called first thing by :func:`tce.cli.main`, before the heavy
imports, and by nothing else: importing tce changes no signal disposition) makes SIGINT,
SIGTERM and SIGHUP raise :class:`Interrupted` (a :class:`KeyboardInterrupt`) in the main
thread, so that every command stops the same way whatever ends it: a run stops its workers,
keeps every finished scenario and removes its temporary files (:mod:`tce.study.runner`), and
the program prints one line and exits with ``128 + signal`` (130 for Ctrl-C, 143 for SIGTERM,
129 for SIGHUP). Later signals are ignored while it stops (SIGKILL still ends it at once);
before ``main`` runs, Ctrl-C is left to Python.

:func:`quiet_children` starts processes with Ctrl-C ignored from their first instruction
(an ignored signal stays ignored across ``exec``), so that a worker still importing prints
no traceback when Ctrl-C reaches its process group. :func:`deferred` holds a stop signal
received inside its block and raises it when the block ends: a worker pool's ``submit``
interrupted half-way leaves the pool in a state its shutdown waits on for ever.
"""

from __future__ import annotations

import contextlib
import signal
import threading
from collections.abc import Iterator
from types import FrameType

__all__ = ["Interrupted", "deferred", "exit_code", "handle_signals", "quiet_children", "restore_signals"]

_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)
#: inside :func:`deferred`: the stop signals received there (None outside)
_held: list[int] | None = None


class Interrupted(KeyboardInterrupt):
    """The program was asked to stop by ``signum`` (Ctrl-C is SIGINT)."""

    def __init__(self, signum: int) -> None:
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


def _stop(signum: int, frame: FrameType | None) -> None:
    for sig in _SIGNALS:  # stopping: further signals are not allowed to break the clean-up
        signal.signal(sig, signal.SIG_IGN)
    if _held is not None:  # raised when the deferring block ends
        _held.append(signum)
        return
    raise Interrupted(signum)


def handle_signals() -> dict[int, object]:
    """SIGINT, SIGTERM and SIGHUP raise :class:`Interrupted` in the main thread (module
    docstring); returns the dispositions it replaced, for :func:`restore_signals`."""
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
    return 128 + int(getattr(exc, "signum", signal.SIGINT))


@contextlib.contextmanager
def deferred() -> Iterator[None]:
    """Within the block a stop signal (:func:`handle_signals`) is held, and raised as
    :class:`Interrupted` as soon as the block ends (nested blocks: the outermost)."""
    global _held
    if _held is not None or threading.current_thread() is not threading.main_thread():
        yield
        return
    _held = []
    try:
        yield
    finally:
        got, _held = _held, None
        if got:
            raise Interrupted(got[0])


@contextlib.contextmanager
def quiet_children() -> Iterator[None]:
    """Within the block, processes started inherit an ignored Ctrl-C (module docstring); this
    process ignores it only while it starts them."""
    if threading.current_thread() is not threading.main_thread():  # only the main thread sets handlers
        yield
        return
    before = signal.getsignal(signal.SIGINT)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, before)
