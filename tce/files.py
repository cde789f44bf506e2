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
import errno
import os
import secrets
import shutil
from collections.abc import Iterator
from pathlib import Path

__all__ = ["MIN_FREE", "StorageError", "atomic_write", "storage_error", "temporaries"]

#: free space a command needs before it writes (bytes)
MIN_FREE = 2**20


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


class StorageError(OSError):
    """A results file or folder that cannot be written; the message names the path and the cause."""


_CAUSES = {
    errno.ENOSPC: "no space left on the device",
    errno.EDQUOT: "disk quota exceeded",
    errno.EROFS: "read-only file system",
    errno.EACCES: "permission denied",
    errno.EPERM: "permission denied",
    errno.ENOTDIR: "a file is in the way of a folder",
    errno.EEXIST: "a file is in the way of a folder",
    errno.EISDIR: "a folder is in the way of a file",
}


def storage_error(path: Path, exc: BaseException) -> StorageError:
    """A :class:`StorageError` for ``path`` saying why ``exc`` happened, and what to do."""
    no = getattr(exc, "errno", None)
    try:  # the netCDF library reports a full disk as "NetCDF: HDF error" or "Permission denied"
        full = shutil.disk_usage(next(p for p in (path, *path.parents) if p.exists())).free < MIN_FREE
    except OSError:
        full = False
    cause = "no space left on the device" if full else _CAUSES.get(no or 0, str(exc))
    fix = "free some space" if "space" in cause or "quota" in cause else "choose another --out"
    err = StorageError(f"cannot write {path}: {cause}; fix: {fix}, then run the same command again")
    err.errno = no
    return err
