"""Fault injection for ``tests/faults``: every Python process started with this folder on
``PYTHONPATH`` (a ``tce run`` and its workers) imports it at start-up.

``TCE_FAULT="KIND:SCENARIO[:ARG]"`` wraps ``tce.study.runner._solve_and_write`` so that,
for the scenario named SCENARIO:

- ``kill``: the process solving it kills itself with SIGKILL before solving (as the
  out-of-memory killer does);
- ``kill-once``: the same, the first time only (the file ARG, created then, says it was done);
- ``interrupt``: after its file is written, the process sends SIGINT to its process group (as
  Ctrl-C in a terminal does) and waits until it is ended, so that the parent is interrupted
  while a finished scenario is not yet returned;
- ``fill``: after its file is written, the file system of the folder ARG is filled up;
- ``hold``: before solving, the process waits until it is ended (a signal, or the parent
  ending its workers);
- ``starting`` (SCENARIO unused): the first time the run submits a scenario to its pool
  (which starts a worker), it writes a byte into the named pipe ARG and waits until the named
  pipe ``ARG.sent`` is closed by the test (which sends its Ctrl-C in between).
"""

import os

_SPEC = os.environ.get("TCE_FAULT")

if _SPEC:
    import signal
    import threading
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

    def _until_ended() -> None:
        """Block until this process is ended (in the main thread a signal handler's exception
        interrupts the wait)."""
        threading.Event().wait()

    def _faulty(sc, assembly, directory):
        if sc.name == _NAME and _KIND == "kill-once":
            try:
                Path(_ARG[0]).touch(exist_ok=False)
            except FileExistsError:
                pass
            else:
                os.kill(os.getpid(), signal.SIGKILL)
        if sc.name == _NAME and _KIND == "kill":
            os.kill(os.getpid(), signal.SIGKILL)
        if sc.name == _NAME and _KIND == "hold":
            _until_ended()
        result = _solve_and_write(sc, assembly, directory)
        if sc.name == _NAME and _KIND == "interrupt":
            os.killpg(os.getpgrp(), signal.SIGINT)
            _until_ended()
        if sc.name == _NAME and _KIND == "fill":
            _fill(Path(_ARG[0]))
        return result

    runner._solve_and_write = _faulty

    if _KIND == "starting":
        import select

        class _Held(runner.ProcessPoolExecutor):
            held = False

            def submit(self, *args, **kwargs):
                if not _Held.held:
                    _Held.held = True
                    sent = os.open(_ARG[0] + ".sent", os.O_RDONLY | os.O_NONBLOCK)
                    with open(_ARG[0], "w") as fifo:  # the test waits on this pipe's first byte,
                        fifo.write("x")
                    select.select([sent], [], [])  # sends its Ctrl-C, then opens and closes this pipe
                    os.close(sent)
                return super().submit(*args, **kwargs)

        runner.ProcessPoolExecutor = _Held
