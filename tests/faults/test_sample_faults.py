"""A real ``tce run`` of an uncertainty study killed (SIGKILL, as the out-of-memory killer does)
while it solves a job of samples: the jobs finished are kept, and the rerun solves only the
missing ones to the answer of a run that was never stopped (tests/study/test_uncertainty.py
stops a run in-process, fast; this one kills the process)."""

from __future__ import annotations

import pytest
import xarray as xr

from faults.common import answer, tce_run
from study.test_uncertainty import sliding


@pytest.mark.slow
def test_killed_run_resumes_without_redrawing(tmp_path):
    study = sliding(tmp_path)
    clean = tce_run(study, tmp_path / "clean", "--jobs", "1")
    assert clean.returncode == 0, clean.stderr
    out = tmp_path / "killed"
    killed = tce_run(study, out, "--jobs", "1", fault="kill:none samples 8-16")
    assert killed.returncode != 0
    kept = {p.name: p.stat().st_mtime_ns for p in (out / "sliding" / "scenarios").glob("*.nc")}
    assert len(kept) == 2 and any("samples_0-8" in n for n in kept)
    resumed = tce_run(study, out, "--jobs", "1")
    assert resumed.returncode == 0, resumed.stderr
    assert "2 of 4 scenarios already solved" in resumed.stderr
    assert all((out / "sliding" / "scenarios" / n).stat().st_mtime_ns == t for n, t in kept.items())
    xr.testing.assert_identical(answer(out / "sliding" / "results.nc"), answer(tmp_path / "clean" / "sliding" / "results.nc"))
