"""Shared pieces of the fault-injection suite: a tiny study, a real ``tce run`` in a
subprocess (with the fault hook of ``hook/sitecustomize.py``), and the comparison of
results files without what differs from run to run."""

from __future__ import annotations

import copy
import os
import signal
import subprocess
import sys
from pathlib import Path
from typing import Any

import xarray as xr

from tce.study.results import TIMING

HOOK = Path(__file__).resolve().parent / "hook"

#: four scenarios of about a second each: a 6-voussoir arch, two settlement cases, two frictions
TINY = """
[study]
name = "tiny"

[structure]
type = "semicircular_arch"
voussoirs = 6

[loads]
lambda_step = 0.05
tolerance = 1e-3

[sweep]
friction = [0.8, 2.0]

[scenarios.none]

[scenarios.outward]
right = [0.001, 0.0, 0.0, 0.0, 0.0, 0.0]
"""
NAMES = ["none/friction=0.8", "none/friction=2", "outward/friction=0.8", "outward/friction=2"]


def replaced(doc: Any, place: tuple, value: Any) -> Any:
    """A deep copy of ``doc`` with the value at ``place`` (keys and indices) replaced."""
    doc = copy.deepcopy(doc)
    node = doc
    for key in place[:-1]:
        node = node[key]
    node[place[-1]] = value
    return doc


def write(folder: Path, text: str = TINY, name: str = "study.toml") -> Path:
    path = folder / name
    path.write_text(text, encoding="utf-8")
    return path


def answer(path: Path) -> xr.Dataset:
    """A results file without its timings and creation date (they differ from run to run)."""
    ds = xr.load_dataset(path).drop_vars(list(TIMING))
    ds.attrs.pop("created")
    return ds


def tce_run(study: Path, out: Path, *args: str, fault: str | None = None, timeout: float = 300) -> subprocess.CompletedProcess:
    """``tce run STUDY --out OUT --no-plots ARGS`` in a new process group (its own Ctrl-C)."""
    env = dict(os.environ, MPLBACKEND="Agg")
    env.pop("TCE_FAULT", None)
    if fault:
        env["TCE_FAULT"] = fault
        env["PYTHONPATH"] = os.pathsep.join([str(HOOK), *filter(None, [env.get("PYTHONPATH")])])
    cmd = [sys.executable, "-m", "tce.cli", "run", str(study), "--out", str(out), "--no-plots", *args]
    return subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=timeout, start_new_session=True,
                          preexec_fn=as_from_a_shell)


def as_from_a_shell() -> None:
    """In the child before it runs tce: Ctrl-C, SIGTERM and SIGHUP at their defaults and not
    blocked, as a shell starts a program (an ignored or blocked signal would be inherited from
    whatever the test process did before, and the Ctrl-C fault would never reach tce)."""
    for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
        signal.signal(sig, signal.SIG_DFL)
    signal.pthread_sigmask(signal.SIG_UNBLOCK, (signal.SIGINT, signal.SIGTERM, signal.SIGHUP))


def clean(err: str) -> None:
    """No traceback and no leaked-resource warning reached the user."""
    assert "Traceback" not in err, err
    assert "leaked" not in err and "UserWarning" not in err, err


def errors(err: str) -> list[str]:
    """The ``tce: error:`` lines of stderr."""
    return [line for line in err.splitlines() if line.startswith("tce: error:")]


def leftovers(folder: Path) -> list[Path]:
    """Temporary and lock files left anywhere under ``folder``."""
    return sorted(p for p in folder.rglob(".*") if p.is_file())
