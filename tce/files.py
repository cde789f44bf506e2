"""Files written whole: every file tce writes goes through :func:`atomic_write`.

A reader (or a machine that loses power) sees the old file or the complete new one, never a
part: the writer writes a temporary file in the same folder, which is flushed to the disk
(fsync), renamed onto its name (:func:`os.replace`, atomic within a file system) and made
durable by an fsync of the folder. A writer that fails or is interrupted leaves no temporary
behind; one killed mid-write leaves ``.<name>.<pid>.tmp``, which :func:`temporaries` finds.
This module imports nothing of tce: every floor may use it.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Iterator
from pathlib import Path

__all__ = ["atomic_write", "temporaries"]


@contextlib.contextmanager
def atomic_write(path: Path | str) -> Iterator[Path]:
    """Write ``path`` whole or not at all.

    Yields the temporary path ``.<name>.<pid>.tmp`` beside ``path`` (its folder is created),
    for the caller to write by any means. When the block ends normally, the file is fsynced,
    renamed onto ``path`` and the folder fsynced; when it raises, the file is removed.

    Raises
    ------
    OSError
        The folder cannot be created, or the file cannot be flushed or renamed (a full disk).
    FileNotFoundError
        The block wrote nothing at the temporary path.
    """
    path = Path(path)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    path.parent.mkdir(parents=True, exist_ok=True)
    try:
        yield tmp
        _fsync(tmp)
        os.replace(tmp, path)
        _fsync(path.parent)
    finally:
        with contextlib.suppress(OSError):
            tmp.unlink(missing_ok=True)


def _fsync(path: Path) -> None:
    """Flush a file's data, or a folder's entries, to the disk."""
    fd = os.open(path, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def temporaries(folder: Path, pid: int | None = None) -> list[Path]:
    """The temporary files :func:`atomic_write` left in ``folder`` (a writer killed
    mid-write): those of process ``pid``, or every ``.*.tmp`` file."""
    return sorted(folder.glob(f".*.{pid}.tmp" if pid is not None else ".*.tmp"))
