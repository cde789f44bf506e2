"""Progress: a tqdm bar on a real terminal, one-line progress in logs otherwise, no long silence."""

from __future__ import annotations

import fcntl
import logging
import os
import pty
import re
import struct
import subprocess
import sys
import termios
import threading
from pathlib import Path

from tce.study.progress import Progress, track

STUDY = Path(__file__).resolve().parents[2] / "studies" / "fig9_outofplane.toml"


def _run_on_pty(args: list[str]) -> str:
    """Run ``args`` with stdout and stderr on a pseudo-terminal; everything it wrote."""
    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 120, 0, 0))  # a 120-column terminal
    proc = subprocess.Popen(args, stdin=slave, stdout=slave, stderr=slave, close_fds=True)
    os.close(slave)
    out = b""
    while True:
        try:
            chunk = os.read(master, 65536)
        except OSError:  # the child closed the terminal
            break
        if not chunk:
            break
        out += chunk
    proc.wait(timeout=120)
    os.close(master)
    assert proc.returncode == 0, out.decode(errors="replace")
    return out.decode(errors="replace")


def test_run_shows_a_bar_on_a_terminal(tmp_path):
    out = _run_on_pty([sys.executable, "-m", "tce.cli", "run", str(STUDY), "--out", str(tmp_path), "--no-plots"])
    # tqdm's bar: description, done/total, the unit and the rate, redrawn with carriage returns
    assert "fig9_outofplane" in out and "/3 [" in out and "scenario/s" in out and "\r" in out
    assert "3/3" in out and "load steps" in out


def test_run_logs_plain_progress_when_not_a_terminal(tmp_path):
    out = subprocess.run(
        [sys.executable, "-m", "tce.cli", "run", str(STUDY), "--out", str(tmp_path), "--no-plots"],
        capture_output=True, text=True, check=True,
    )
    assert re.search(r"fig9_outofplane: 3/3 scenarios \(\d+ load steps\), \d+ s", out.stderr)
    assert "\r" not in out.stderr and "%|" not in out.stderr


def test_long_items_are_not_silent(caplog):
    spoke = threading.Event()

    class Heard(logging.Handler):
        def emit(self, record: logging.LogRecord) -> None:
            if "still working" in record.getMessage():
                spoke.set()

    heard = Heard()
    logging.getLogger("tce.study.progress").addHandler(heard)
    try:
        with caplog.at_level(logging.DEBUG, logger="tce"):
            with Progress(3, "slow things", unit="thing", every=0.2, bar=False) as bar:
                bar.doing("the first")
                assert spoke.wait(60)  # one long item: the heartbeat speaks meanwhile
                bar.update()
    finally:
        logging.getLogger("tce.study.progress").removeHandler(heard)
    lines = [r.getMessage() for r in caplog.records if r.name == "tce.study.progress"]
    assert any(line.startswith("slow things: still working, 0/3 things (the first)") for line in lines)
    assert lines[-1].startswith("slow things: stopped at 1/3 things")


def test_track_counts_every_item(caplog):
    with caplog.at_level(logging.INFO, logger="tce"):
        assert list(track(range(5), "numbers", unit="number")) == [0, 1, 2, 3, 4]
    lines = [r.getMessage() for r in caplog.records if r.name == "tce.study.progress"]
    assert lines and lines[-1].startswith("numbers: 5/5 numbers (4)")


def test_callback_form_updates_the_total(caplog):
    with caplog.at_level(logging.INFO, logger="tce"):
        with Progress(0, "bisection", unit="solve", bar=False) as bar:
            bar(1, 20)
            bar(18, 18)
    assert bar.total == 18 and bar.done == 18


def test_drawing_shows_a_bar_naming_the_file_on_a_terminal(tmp_path):
    out = _run_on_pty([sys.executable, "-m", "tce.cli", "run", str(STUDY), "--out", str(tmp_path), "--no-report"])
    assert "figures:" in out and "/6 [" in out and "file/s" in out and "states.png]" in out
    assert "6/6" in out
