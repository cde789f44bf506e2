"""Files are written whole (tce.files.atomic_write): a reader sees the old file or the new one,
and a writer that fails leaves the old file and no temporary behind; the report's PDF, which
another program writes, goes through the same helper."""

from __future__ import annotations

import os
import stat
from pathlib import Path

import pytest

from tce.files import atomic_write, temporaries
from tce.report import print_pdf


def test_a_write_replaces_the_file_whole(tmp_path: Path) -> None:
    path = tmp_path / "sub" / "a.txt"
    with atomic_write(path) as tmp:
        assert tmp.parent == path.parent and tmp.name.startswith(".a.txt.") and tmp.name.endswith(f".{os.getpid()}.tmp")
        tmp.write_text("new")
        assert not path.exists()  # nothing is visible before the block ends
    assert path.read_text() == "new" and not temporaries(path.parent)


def test_a_failed_write_keeps_the_old_file_and_leaves_no_temporary(tmp_path: Path) -> None:
    path = tmp_path / "a.txt"
    path.write_text("old")
    with pytest.raises(RuntimeError, match="disk"), atomic_write(path) as tmp:
        tmp.write_text("half")
        raise RuntimeError("disk full")
    assert path.read_text() == "old" and not temporaries(tmp_path)


def _browser(folder: Path, exit_code: int) -> Path:
    """A stand-in for Chromium that writes its --print-to-pdf file and exits ``exit_code``."""
    script = folder / "browser"
    script.write_text(
        "#!/bin/sh\nfor a in \"$@\"; do case $a in --print-to-pdf=*) printf '%%PDF-1.4' > \"${a#--print-to-pdf=}\";; "
        f"esac; done\nexit {exit_code}\n"
    )
    script.chmod(script.stat().st_mode | stat.S_IXUSR)
    return script


@pytest.mark.parametrize("exit_code", [0, 3])
def test_the_pdf_is_placed_whole_or_not_at_all(exit_code: int, tmp_path: Path) -> None:
    html, pdf = tmp_path / "report.html", tmp_path / "report.pdf"
    html.write_text("<p>report</p>")
    why = print_pdf(html, pdf, str(_browser(tmp_path, exit_code)))
    if exit_code == 0:
        assert why == "" and pdf.read_bytes() == b"%PDF-1.4"
    else:
        assert why.startswith("chromium failed") and "exit 3" in why and not pdf.exists()
    assert not temporaries(tmp_path)


def test_a_link_planted_at_the_temporary_name_is_not_followed(tmp_path: Path, monkeypatch) -> None:
    """The temporary is created exclusively (O_EXCL | O_NOFOLLOW): a link planted at its name,
    even one that guessed the token, makes the write fail and leaves its target as it was."""
    victim = tmp_path / "victim"
    victim.write_text("victim")
    monkeypatch.setattr("secrets.token_hex", lambda n: "guessed")
    (tmp_path / f".a.txt.guessed.{os.getpid()}.tmp").symlink_to(victim)
    with pytest.raises(FileExistsError), atomic_write(tmp_path / "a.txt") as tmp:
        tmp.write_text("new")
    assert victim.read_text() == "victim" and not (tmp_path / "a.txt").exists()
