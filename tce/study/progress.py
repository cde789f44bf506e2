"""Feedback while users wait: a progress bar on a terminal, one-line progress in logs otherwise.

:class:`Progress` counts finished items out of a known total. When standard error is a
terminal and tce logs at info level it draws a tqdm bar there (done / total, rate, ETA, the
current item), redrawn every second by a heartbeat. Otherwise it logs (logger
``tce.study.progress``, info) a line when an item finishes, at most one every ``every``
seconds, and a "still working" line after ``every`` seconds of silence.

Typical use (figures, say)::

    from tce.study.progress import Progress

    with Progress(len(names), "figures", unit="figure") as bar:
        for name in names:
            bar.doing(name)   # what is under way: shown beside the bar
            draw(name)
            bar.update()

or, for a plain loop, ``for name in track(names, "figures", unit="figure"): ...``.
"""

from __future__ import annotations

import logging
import sys
import threading
import time
from collections.abc import Callable, Iterable, Iterator
from typing import Any, TypeVar

__all__ = ["Progress", "track"]

log = logging.getLogger(__name__)
T = TypeVar("T")


def _terminal() -> bool:
    """Bars only on a terminal, and only when tce logs at info level or below (not ``-q``)."""
    stream = sys.stderr
    return bool(getattr(stream, "isatty", lambda: False)()) and logging.getLogger("tce").isEnabledFor(logging.INFO)


class Progress:
    """Progress of ``total`` items (see module docstring).

    Parameters
    ----------
    total : int
        Items to finish.
    desc : str
        What the items make up (``"fig7_8_inplane"``, ``"figures"``).
    unit : str
        What one item is (``"scenario"``, ``"figure"``).
    every : float
        Seconds between log lines when not on a terminal (and the heartbeat's silence limit).
    bar : bool, optional
        Force (True) or refuse (False) a terminal bar; default: a bar when stderr is a
        terminal and tce logs at info level.
    """

    def __init__(self, total: int, desc: str, unit: str = "item", every: float = 5.0, bar: bool | None = None) -> None:
        self.total = int(total)
        self.desc = desc
        self.unit = unit
        self.every = float(every)
        self.done = 0
        self.current = ""
        self.extra = ""
        self._t0 = time.monotonic()
        self._last_line = self._t0
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._bar: Any = None
        if _terminal() if bar is None else bar:
            from tqdm import tqdm

            self._bar = tqdm(total=self.total, desc=desc, unit=unit, file=sys.stderr, dynamic_ncols=True, leave=True)
        self._beat = threading.Thread(target=self._heartbeat, name=f"progress {desc}", daemon=True)
        self._beat.start()

    # ------------------------------------------------------------------ feeding
    def doing(self, item: str) -> None:
        """Name the item under way (shown beside the bar, and in "still working" lines)."""
        with self._lock:
            self.current = str(item)
            if self._bar is not None:
                self._bar.set_postfix_str(self._postfix(), refresh=True)

    def note(self, text: str) -> None:
        """A short status shown after the item (e.g. ``"412 steps"``)."""
        with self._lock:
            self.extra = str(text)
            if self._bar is not None:
                self._bar.set_postfix_str(self._postfix(), refresh=False)

    def update(self, n: int = 1) -> None:
        """``n`` more items finished."""
        self.set_done(self.done + n)

    def set_done(self, done: int) -> None:
        """``done`` items finished in all."""
        with self._lock:
            step = done - self.done
            self.done = done
            if self._bar is not None:
                self._bar.update(step)
                return
            now = time.monotonic()
            if done >= self.total or now - self._last_line >= min(self.every, 2.0):
                self._line(now)

    def __call__(self, done: int, total: int | None = None) -> None:
        """``done`` items finished out of ``total`` (which may change): a progress callback."""
        if total is not None and total != self.total:
            with self._lock:
                self.total = int(total)
                if self._bar is not None:
                    self._bar.total = self.total
        self.set_done(done)

    def close(self) -> None:
        """Stop the heartbeat; the bar stays on screen (a log says where it stopped at debug level)."""
        self._stop.set()
        self._beat.join(timeout=2.0)
        with self._lock:
            if self._bar is not None:
                self._bar.close()
                self._bar = None
            elif self.done < self.total:
                self._line(time.monotonic(), "stopped at ", logging.DEBUG)  # the caller says why

    def __enter__(self) -> Progress:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # ------------------------------------------------------------------ output
    def _postfix(self) -> str:
        return ", ".join(x for x in (self.current, self.extra) if x)

    def _line(self, now: float, prefix: str = "", level: int = logging.INFO) -> None:
        what = f" ({self._postfix()})" if self._postfix() else ""
        log.log(level, "%s: %s%d/%d %ss%s, %.0f s", self.desc, prefix, self.done, self.total, self.unit, what,
                now - self._t0)
        self._last_line = now

    def _heartbeat(self) -> None:
        tick = 1.0 if self._bar is not None else min(self.every, 1.0)
        while not self._stop.wait(tick):
            with self._lock:
                if self._bar is not None:
                    self._bar.refresh()  # elapsed time and rate move on
                elif self.done < self.total and time.monotonic() - self._last_line >= self.every:
                    self._line(time.monotonic(), "still working, ")


def track(
    items: Iterable[T], desc: str, unit: str = "item", total: int | None = None,
    label: Callable[[T], str] = str, every: float = 5.0,
) -> Iterator[T]:
    """Iterate over ``items`` with a :class:`Progress` (each item named by ``label``)."""
    seq = items if total is not None else list(items)
    n = total if total is not None else len(seq)  # type: ignore[arg-type]
    with Progress(n, desc, unit, every) as bar:
        for item in seq:
            bar.doing(label(item))
            yield item
            bar.update()
