"""Fault injection for ``tests/faults``: every Python process started with this folder on
``PYTHONPATH`` (a ``tce run`` and its workers) imports it at start-up.

``TCE_FAULT="KIND:SCENARIO[:ARG]"`` wraps ``tce.study.runner._solve_and_write`` so that,
for the scenario named SCENARIO:

- ``kill``: the process solving it kills itself with SIGKILL before solving (as the
  out-of-memory killer does);
- ``interrupt``: after its file is written (and, with ARG, once ARG scenario files are in its
  folder, so that another worker's scenario is finished too), the process sends SIGINT to its
  process group (as Ctrl-C in a terminal does) and waits 3 s before reporting it done, so the
  parent is interrupted while a finished scenario is not yet returned;
- ``fill``: after its file is written, the file system of the folder ARG is filled up;
- ``hold``: before solving, the process waits until the file ARG exists.
"""

import os

_SPEC = os.environ.get("TCE_FAULT")

if _SPEC:
    import signal
    import time
    from pathlib import Path

    from tce.study import runner

    _KIND, _NAME, *_ARG = _SPEC.split(":", 2)
    _solve_and_write = runner._solve_and_write

    def _fill(folder: Path) -> None:
        # unbuffered: a buffered file would raise ENOSPC again when closed, depending on how
        # the free space divides into chunks (that is, on the size of the files written before)
        try:
            with open(folder / "filler", "ab", buffering=0) as fh:
                while True:
                    fh.write(b"\0" * 65536)
        except OSError:
            pass

    def _faulty(sc, assembly, directory):
        if sc.name == _NAME and _KIND == "kill":
            os.kill(os.getpid(), signal.SIGKILL)
        if sc.name == _NAME and _KIND == "hold":
            while not Path(_ARG[0]).exists():
                time.sleep(0.05)
        result = _solve_and_write(sc, assembly, directory)
        if sc.name == _NAME and _KIND == "interrupt":
            while _ARG and len(list(Path(directory).glob("*.nc"))) < int(_ARG[0]):
                time.sleep(0.05)
            os.killpg(os.getpgrp(), signal.SIGINT)
            time.sleep(3)
        if sc.name == _NAME and _KIND == "fill":
            _fill(Path(_ARG[0]))
        return result

    runner._solve_and_write = _faulty
