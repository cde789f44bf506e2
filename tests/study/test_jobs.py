"""Choosing in-process or parallel runs."""

from __future__ import annotations

from pathlib import Path

import pytest

from tce.core.analysis import Analysis
from tce.core.material import Material
from tce.structures.arch import semicircular_arch
from tce.study import jobs as jobs_module
from tce.study.jobs import LARGE_MODEL, choose_jobs, estimate_work
from tce.study.runner import _analysis as _runner_analysis, run_study
from tce.study.schema import load_study

STUDIES = Path(__file__).resolve().parents[2] / "studies"


FIG8 = load_study(STUDIES / "fig7_8_inplane.toml")


def _analysis(sc):
    """The runner's analysis of a scenario (as run_study builds it)."""
    return _runner_analysis(sc, FIG8.assembly(sc.structure))


@pytest.fixture(scope="module")
def fig8():
    return FIG8.scenarios()


def test_jobs_asked_for_are_used(fig8):
    assert choose_jobs(fig8, 3, _analysis).jobs == 3
    assert choose_jobs(fig8, 1, _analysis, cpus=8).jobs == 1
    assert choose_jobs(fig8, None, _analysis, backend="dask", cpus=4).jobs == 4


def test_one_scenario_or_one_core_runs_in_process(fig8):
    assert choose_jobs(fig8[:1], None, _analysis, cpus=8).jobs == 1
    assert choose_jobs(fig8, None, _analysis, cpus=1).jobs == 1


def test_small_study_runs_in_process(fig8):
    choice = choose_jobs(fig8, None, _analysis, cpus=2)
    assert choice.jobs == 1 and choice.reason.startswith("in-process")
    # the estimate counts the increments up to the direct limit (0.243 / 0.02) plus the bracket
    assert 4 * (0.243 / 0.02 + 3) == pytest.approx(float(choice.reason.split("about ")[1].split(" ")[0]), rel=0.1)
    assert 0 < choice.work_s < jobs_module.WORKER_START_S


def test_work_above_worker_start_up_goes_parallel(fig8, monkeypatch):
    monkeypatch.setattr(jobs_module, "WORKER_START_S", 0.0)
    choice = choose_jobs(fig8, None, _analysis, cpus=2)
    assert choice.jobs == 2 and "2 workers" in choice.reason
    assert choose_jobs(fig8, None, _analysis, cpus=8).jobs == 4  # never more workers than scenarios


def test_large_model_is_large_work_without_a_solve(fig8):
    big = Analysis(semicircular_arch(voussoirs=LARGE_MODEL // 4 + 10), Material(0.8))  # planar: 4 unknowns a joint
    work, how = estimate_work(fig8, lambda sc: big)
    assert work == float("inf") and "unknowns" in how
    assert not big._solvers and not big._limits  # nothing was solved
    assert choose_jobs(fig8, None, lambda sc: big, cpus=2).jobs == 2


def test_run_logs_its_choice(tmp_path, caplog):
    study = load_study(STUDIES / "fig7_8_inplane.toml")
    with caplog.at_level("INFO", logger="tce"):
        run_study(study, tmp_path)
    assert any(r.message.startswith("running fig7_8_inplane: 4 scenarios; in-process: the study's work")
               for r in caplog.records)


def test_the_estimate_is_cpu_time_not_wall(fig8, monkeypatch):
    """A busy machine stretches wall time, not CPU time: a wall clock that jumps 10 s per
    reading leaves the estimate (and the choice) as it was."""
    import itertools

    ticks = itertools.count(step=10.0)
    monkeypatch.setattr(jobs_module.time, "perf_counter", lambda: next(ticks))
    choice = choose_jobs(fig8, None, _analysis, cpus=2)
    assert choice.jobs == 1 and choice.work_s < jobs_module.WORKER_START_S


def test_a_sweep_of_many_scenarios_counts_their_answers(fig8, monkeypatch):
    """Recording and writing an answer is work the workers share: many scenarios go parallel
    even when their solves are cheap."""
    monkeypatch.setattr(jobs_module, "SCENARIO_S", 1.0)
    work, how = estimate_work(fig8, _analysis)
    assert work >= 4.0 and "4 answers" in how
    assert choose_jobs(fig8, None, _analysis, cpus=2).jobs == 2


def test_other_groups_are_reckoned_with_the_first_limits():
    """A sweep over frictions has one group per friction: each is reckoned as a path anchored
    on its direct limit (about AUTO_INCREMENTS steps and the bracket), not as a path running to
    lam_cap (which sent every sweep to workers)."""
    from tce.analysis.loadpath import AUTO_INCREMENTS
    from tce.study.schema import parse_study

    text = (STUDIES / "fig7_8_inplane.toml").read_text()
    sweep = parse_study(text + "\n[sweep]\nfriction = [0.6, 0.8, 1.0]\n", "sweep.toml")
    scenarios = sweep.scenarios()
    assert len({sc.group for sc in scenarios}) == 3

    def analysis(sc):
        return _runner_analysis(sc, sweep.assembly(sc.structure))

    work, how = estimate_work(scenarios, analysis)
    solves = float(how.split("about ")[1].split(" ")[0])
    assert 0.9 * AUTO_INCREMENTS * len(scenarios) <= solves <= (AUTO_INCREMENTS + 5) * len(scenarios)


def test_the_estimate_counts_the_settlement_path():
    """A study with ``[settlement_path]`` adds its increments up to s_max (1 / 0.001 for each of
    the two scenarios of arch_spreading) at SETTLEMENT_INCREMENT_S each, and goes parallel
    (fails on main: the path was left out, 0.144 s estimated against 193 s taken)."""
    import dataclasses

    study = load_study(STUDIES / "arch_spreading.toml")
    with_path = study.scenarios()
    without = [dataclasses.replace(sc, settlement_path=None) for sc in with_path]
    analysis_of = lambda sc: _runner_analysis(sc, study.assembly(sc.structure))  # noqa: E731
    assert [jobs_module.settlement_increments(sc) for sc in with_path] == pytest.approx([1000, 1000])
    assert [jobs_module.settlement_increments(sc) for sc in without] == [0, 0]
    assert jobs_module.settlement_increments(dataclasses.replace(with_path[0], settlements={})) == 0  # no_motion
    work_with, how = estimate_work(with_path, analysis_of)
    work_without, how_without = estimate_work(without, analysis_of)
    assert "2000 settlement increments" in how and "settlement" not in how_without
    path = 2000 * jobs_module.SETTLEMENT_INCREMENT_S
    assert work_with - work_without == pytest.approx(path, abs=0.1 * path)
    assert choose_jobs(with_path, None, analysis_of, cpus=2).jobs == 2
    assert choose_jobs(without, None, analysis_of, cpus=2).jobs == 1
