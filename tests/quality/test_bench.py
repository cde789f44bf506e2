"""``tce bench`` prints its report: every section, its rows with finite times and errors, on the
smallest sizes (``--quick``). No time is judged here."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from tce.cli import BENCH_SECTIONS, main
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
