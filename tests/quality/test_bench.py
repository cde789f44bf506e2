"""``tce bench`` prints its report: every section, its rows with finite times and errors, on the
smallest sizes (``--quick``). No time is judged here."""

from __future__ import annotations

import importlib.util
import re
from importlib.util import find_spec

import numpy as np
import pandas as pd
import pytest

from tce.cli import BENCH_SECTIONS, main
from tce.quality import bench
from tce.quality.bench import SECTIONS, growth_exponent


def test_growth_exponent_is_the_log_slope():
    n = [100, 1000, 10000]
    assert growth_exponent(n, [2e-3 * k**1.5 for k in n]) == pytest.approx(1.5)
    assert np.isnan(growth_exponent([100], [1.0]))


def test_the_command_offers_the_bench_sections():
    assert BENCH_SECTIONS == tuple(SECTIONS)


def test_quick_bench_prints_every_section_with_finite_numbers(tmp_path, capsys):
    assert main(["-q", "bench", "--quick", "--out", str(tmp_path)]) == 0
    text = capsys.readouterr().out
    df = pd.read_csv(tmp_path / "bench.csv", keep_default_na=False, na_values=[""])
    assert list(df.section.unique()) == list(SECTIONS)
    for section in SECTIONS:
        assert f"[{section}]" in text
    df = df[~df.note.str.startswith("skipped")]  # an optional runner not installed: a row saying so
    assert (df.time_s > 0).all() and np.isfinite(df.time_s).all(), df[["case", "method", "time_s"]]
    measured = df[df.section != "scaling"]
    assert np.isfinite(measured.error).all(), measured[["case", "method", "error"]]
    # the direct paths at their default tolerance agree with the tight references: 2 models x 3 laws
    # solved, 6 direct limits and the cone beside the pyramids
    direct = measured[measured.method.isin(["clarabel-direct", "direct lambda_max", "direct lambda_max (cone)"])]
    assert len(direct) == 6 + 6 + 1 and (direct.error < 1e-6).all(), direct[["case", "method", "error"]]
    # the load path ends within its tolerance of the direct limit
    path = measured[measured.section == "load_path"]
    atol = path.method.str.rpartition(" ")[2].astype(float)
    assert (path.error <= atol + 1e-7).all(), path[["method", "error"]]
    scaling = df[df.section == "scaling"]
    assert len(scaling) == 4 and (scaling.build_s > 0).all() and (scaling.peak_mem_mb > 0).all()
    assert all(g.n_blocks.is_monotonic_increasing for _, g in scaling.groupby("case"))
    assert scaling.note.str.contains(r"solve ~ n\^").all()


RUNNERS = ["in process, chunks in turn", "process pool, 1 worker", "process pool, 2 workers",
           "Dask LocalCluster, 2 workers"]


def test_quick_reliability_section(tmp_path, capsys):
    """The reliability section's rows: WarmLimit and raw Clarabel per sample on both models with the
    same lambda_max, the samples in one call with their failure probability, and the same
    capacities whichever runner computed them; the report prints each row's columns."""
    assert main(["-q", "bench", "--quick", "--section", "reliability", "--out", str(tmp_path)]) == 0
    text = capsys.readouterr().out
    df = pd.read_csv(tmp_path / "bench.csv", keep_default_na=False, na_values=[""])
    assert (df.section == "reliability").all() and "[reliability]" in text
    for column in ("case", "method", "n_blocks", "n_solves", "time_ms", "error", "error_of", "note"):
        assert column in text
    for _, r in df.iterrows():
        assert r.method in text and r.note in text
    batched = df.method.str.startswith("BatchedLimit")
    assert batched.sum() == 2 and (df[batched].note.str.startswith("skipped") == (find_spec("moreau") is None)).all()
    df = df[~df.note.str.startswith("skipped")]
    assert (df.time_s > 0).all() and np.isfinite(df.error).all(), df[["method", "time_s", "error"]]
    cost = df[df.error_of == "lambda_max vs raw"]
    assert (cost.groupby("model").size() == (3 if find_spec("moreau") else 2)).all() and (cost.error < 1e-6).all()
    assert set(cost.model) == {"planar", "spatial"}
    assert cost[~cost.method.str.startswith("raw")].note.str.contains("x raw").all()
    one = df[df.method == "WarmLimit, evaluate()"].iloc[0]
    assert one.n_solves == bench.RELIABILITY_SAMPLES // 5 and one.build_s > 0
    pf, lo, hi = map(float, re.search(r"= ([\d.]+) \[([\d.]+), ([\d.]+)\]", one.note).groups())
    assert 0 < lo < pf < hi < 1 and one.error == pytest.approx((hi - lo) / 2, rel=1e-3)
    workers = df[df.error_of == "capacity vs in process"]
    assert list(workers.method) == RUNNERS and (workers.error == 0).all()
    assert (workers.n_solves == bench.RELIABILITY_SAMPLES // 10).all()
    assert workers.build_s.iloc[1:].gt(0).all()


def test_reliability_without_dask_says_so(monkeypatch):
    """Without dask[distributed] the Dask row is a note, the other runners are measured."""
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *a: None if name == "distributed" else find_spec(name, *a))
    monkeypatch.setattr(bench, "RELIABILITY_SAMPLES", 10 * 2 * bench.RELIABILITY_CHUNK)
    rows = pd.DataFrame(bench._reliability_workers(quick=True))
    assert list(rows.method) == RUNNERS
    assert rows.note.iloc[-1].startswith("skipped: dask[distributed] is not installed")
    assert np.isnan(rows.time_s.iloc[-1]) and (rows.time_s.iloc[:-1] > 0).all() and (rows.error.iloc[:-1] == 0).all()
