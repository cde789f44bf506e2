"""Files written whole: every file tce writes goes through :func:`atomic_write`.

A reader (or a machine that loses power) sees the old file or the complete new one, never a
part: the writer writes a temporary file in the same folder, which is flushed to the disk
(fsync), renamed onto its name (:func:`os.replace`, atomic within a file system) and made
durable by an fsync of the folder. The temporary is created by this module with ``O_EXCL`` and
``O_NOFOLLOW`` under a name no one can guess, so that a link planted where tce writes is never
followed (the rename replaces a link at the final name, not its target). A writer that fails or
is interrupted leaves no temporary behind; one killed mid-write leaves
``.<name>.<token>.<pid>.tmp``, which :func:`temporaries` finds.
This module imports nothing of tce: every floor may use it.
"""

from __future__ import annotations

import contextlib
import os
import secrets
from collections.abc import Iterator
from pathlib import Path

__all__ = ["atomic_write", "temporaries"]


@contextlib.contextmanager
def atomic_write(path: Path | str) -> Iterator[Path]:
    """Write ``path`` whole or not at all.

    Yields the temporary path ``.<name>.<token>.<pid>.tmp`` beside ``path`` (its folder is
    created), an empty file this call created, for the caller to write by any means. When the
    block ends normally, the file is fsynced, renamed onto ``path`` and the folder fsynced;
    when it raises, the file is removed.

    Raises
    ------
    OSError
        The folder cannot be created (or is a file), or the file cannot be created, flushed or
        renamed (a full disk).
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{secrets.token_hex(4)}.{os.getpid()}.tmp")
    os.close(os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW, 0o666))
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
