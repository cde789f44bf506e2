"""``tce bench``'s whole-run arithmetic (issue 24) on made-up measurements: the CPU on the
longest chain of processes of a run and the targets read from the ``sweeps`` rows. No
timing is measured here (speed belongs to the bench)."""

from __future__ import annotations

import pandas as pd
import pytest

from tce.quality.bench import _row, critical_cpu, evaluate_targets

FORKSERVER = "python -c from multiprocessing.forkserver import main; main(5, 6, ['tce.study.runner'])"


def test_longest_chain_is_parent_fork_server_busiest_worker_and_the_rest():
    got = {
        "root": 100,
        "procs": {
            "100": [2.0, 1, "tce run"],
            "101": [1.0, 100, FORKSERVER],
            "102": [5.0, 101, FORKSERVER],  # workers: forked from the fork server (same command line)
            "103": [7.0, 101, FORKSERVER],
            "104": [0.5, 100, "chromium --headless"],
        },
    }
    assert critical_cpu(got) == pytest.approx(2.0 + 1.0 + 7.0 + 0.5)


def test_in_process_run_is_its_own_chain():
    assert critical_cpu({"root": 7, "procs": {"7": [3.25, 1, "tce run"]}}) == 3.25


def _sweep_rows(wall: dict[str, float], chain: dict[str, float]) -> list[dict]:
    return [_row("sweeps", "sweep of 300 scenarios (arch, no figures)", k, time_s=wall[k], cpu_s=chain[k],
                 solver_time_s=4.0, note=f"1x; CPU {9.0 if k == '--jobs 1' else 10.0:.2f} s, ...; load average 5.0 (4-6)")
            for k in wall]


def _targets(rows: list[dict]) -> dict[str, tuple[str, bool]]:
    return {t: (m, ok) for t, m, ok in evaluate_targets(pd.DataFrame(rows))}


def test_sweep_targets_by_wall_and_by_longest_chain():
    rows = _sweep_rows({"--jobs 1": 10.0, "--jobs 2": 9.0, "default": 10.2}, {"--jobs 1": 9.0, "--jobs 2": 5.0, "default": 9.0})
    t = _targets(rows)
    case = "sweep of 300 scenarios (arch, no figures)"
    assert t[f"{case}: --jobs 2 at least 1.6x faster than --jobs 1 (wall)"][1] is False  # 1.11x
    chain = t[f"{case}: --jobs 2 at least 1.6x faster than --jobs 1 (CPU on the longest chain of processes)"]
    assert chain == ("1.80x (9.0 / 5.0 CPU-s)", True)
    assert t[f"{case}: the default no slower than --jobs 1 (wall)"][1] is True  # 1.02x, within 5 %
    assert t[f"{case}: --jobs 1 at most 3x its own solving (CPU of the run / CPU of its load paths)"] == (
        "2.2x (9.0 / 4.00 s)", True)


def _figure_rows(plain: tuple[float, float], figs: tuple[float, float], here: tuple[float, float] | None = None):
    """``sweeps`` rows of fig9: (wall s, CPU s) without figures, with them, and drawn in the run's process."""
    variants = {"--no-plots": plain, "figures (--no-report)": figs}
    if here:
        variants["figures (--no-report), --jobs 1: drawn in the run's process"] = here
    return [_row("sweeps", "tce run fig9_outofplane", k, time_s=w, cpu_s=c, note=f"CPU {c:.2f} s; load average 1.2 (1-2)")
            for k, (w, c) in variants.items()]


def test_figure_target_is_the_cpu_ratio_to_the_no_plots_run():
    case = "tce run fig9_outofplane: with figures at most 1.5x its own --no-plots run (CPU, every process)"
    rows = _figure_rows((3.0, 2.0), (4.0, 3.2))
    measured, ok = _targets(rows)[case]
    assert measured.startswith("1.60x (3.20 / 2.00 CPU-s") and ok is False
    rows[1]["cpu_s"] = 2.9
    measured, ok = _targets(rows)[case]
    assert measured.startswith("1.45x") and ok is True


def test_figure_target_by_wall_is_a_line_of_its_own():
    """The drawers gain wall time, not CPU: each measure says whether it is met."""
    t = _targets(_figure_rows((2.0, 1.2), (2.8, 2.6)))
    assert t["tce run fig9_outofplane: with figures at most 1.5x its own --no-plots run (wall)"] == (
        "1.40x (2.80 / 2.00 s; load average 1.2 (1-2))", True)
    assert t["tce run fig9_outofplane: with figures at most 1.5x its own --no-plots run (CPU, every process)"][1] is False
    t = _targets(_figure_rows((2.0, 1.2), (3.1, 2.6)))
    assert t["tce run fig9_outofplane: with figures at most 1.5x its own --no-plots run (wall)"][1] is False


def test_run_by_run_pairs_the_runs_of_each_round():
    from tce.quality.bench import run_by_run

    assert run_by_run([{"wall": 3.0}, {"wall": 1.5}], [{"wall": 2.0}, {"wall": 1.0}]) == [1.5, 1.5]
    with pytest.raises(ValueError):
        run_by_run([{"wall": 3.0}], [{"wall": 2.0}, {"wall": 1.0}])


def test_figure_target_by_wall_quotes_the_run_by_run_ratio():
    """The ratio of the runs of each round (same speed of this shared machine) is quoted; the target is
    still the ratio of the medians."""
    rows = _figure_rows((2.0, 1.2), (3.1, 2.6))
    rows[1]["note"] = ("CPU 2.60 s, 2.17x --no-plots (CPU); wall 1.55x --no-plots, 1.45x (1.30-1.62x) run by run "
                       "in the same rounds; drawers usable (CPUs free) in 5 of 5 runs; load average 1.2 (1-2)")
    assert _targets(rows)["tce run fig9_outofplane: with figures at most 1.5x its own --no-plots run (wall)"] == (
        "1.55x (3.10 / 2.00 s; load average 1.2 (1-2); 1.45x (1.30-1.62x) run by run in the same rounds)", False)


def test_drawers_against_drawing_in_the_runs_process():
    key = "tce run fig9_outofplane: figures by the drawers no slower than drawn in the run's process (--jobs 1; wall)"
    assert _targets(_figure_rows((2.0, 1.2), (2.8, 2.6), here=(3.4, 2.5)))[key] == ("0.82x (2.80 / 3.40 s; CPU 1.04x)", True)
    assert _targets(_figure_rows((2.0, 1.2), (3.0, 2.6), here=(2.8, 2.5)))[key][1] is False  # 1.07x
    assert key not in _targets(_figure_rows((2.0, 1.2), (2.8, 2.6)))
