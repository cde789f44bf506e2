"""``[uncertainty]`` in study files (tce.study.uncertainty, tce.study.samples): the jobs and their
keys, bad input refused naming the key, the work estimate, the statuses counted, the warm and
rebuilt capacities, and a run killed between jobs of samples resumed to the same answer."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from helpers import block_on_support

from tce.study import runner
from tce.study.schema import StudyError, parse_study
from tce.study.uncertainty import FRAGILITY_POINTS, statistics

from faults.common import answer, errors, tce_run

#: a flat block (1.0 x 0.4 x 0.1 m) on a slab: it slides at lambda = mu (it rocks at b / h = 10)
SLIDING = """
[study]
name = "sliding"

[structure]
type = "file"
path = "block.json"

[material]
friction = 0.6

[loads]
lambda_step = 0.1
tolerance = 1e-3

[uncertainty]
samples = 20
chunk = 8
seed = 4
threshold = 0.55

[uncertainty.variables]
"material.friction" = { distribution = "lognormal", mean = 0.6, cov = 0.15 }
"""


def sliding(folder: Path, text: str = SLIDING, **replace: str) -> Path:
    """The sliding-block study written to ``folder`` (with its block file), ``replace``d."""
    (folder / "block.json").write_text(json.dumps(block_on_support(b=1.0, h=0.1, d=0.4).to_dict()))
    for old, new in replace.items():
        assert old in text, old
        text = text.replace(old, new)
    path = folder / "study.toml"
    path.write_text(text)
    return path


def test_jobs_cover_every_sample_once(tmp_path):
    """ceil(N / chunk) jobs per scenario, contiguous and disjoint; the nominal scenario's key
    does not change with [uncertainty]; a job's key changes with the section and its samples."""
    text = SLIDING.replace("[scenarios", "") + '\n[scenarios.none]\n[scenarios.up]\nbase = [0, 0, 0.001, 0, 0, 0]\n'
    study = parse_study(text, sliding(tmp_path))
    jobs = [j for j in study.jobs() if j.samples is not None]
    assert len(jobs) == 2 * math.ceil(20 / 8)
    for name in ("none", "up"):
        ranges = [j.samples for j in jobs if j.name.startswith(name + " ")]
        assert ranges == [(0, 8), (8, 16), (16, 20)]
    plain = parse_study(text.split("[uncertainty]")[0] + "[scenarios.none]\n[scenarios.up]\nbase = [0, 0, 0.001, 0, 0, 0]\n",
                        tmp_path / "study.toml")
    assert [sc.key for sc in study.scenarios()] == [sc.key for sc in plain.scenarios()]
    keys = {j.key for j in jobs}
    assert len(keys) == len(jobs)
    other = parse_study(text.replace("seed = 4", "seed = 5"), tmp_path / "study.toml")
    assert not keys & {j.key for j in other.jobs() if j.samples is not None}
    # the statistics' settings are applied when merging: the samples need not be solved again
    judged = parse_study(text.replace("threshold = 0.55", 'threshold = 0.5\ninterval = "wilson"'), tmp_path / "study.toml")
    assert keys == {j.key for j in judged.jobs() if j.samples is not None}


@pytest.mark.parametrize(
    "old, new, key",
    [
        ('distribution = "lognormal"', 'distribution = "lognormall"', "material.friction"),
        ('"material.friction"', '"material.frictio"', "material.frictio"),
        ('"material.friction"', '"material.flow"', "material.flow"),
        ('"material.friction"', '"structure.path"', "structure.path"),
        ('"material.friction"', '"loads.vehicle.0.x"', "loads.vehicle.0.x"),
        ('"material.friction"', '"assessment.live_factor"', "assessment.live_factor"),
        ('distribution = "lognormal", mean = 0.6, cov = 0.15', 'distribution = "normal", mean = 0.6, std = 0.4',
         "material.friction"),
        ('cov = 0.15 }', 'cov = 0.15 }\n"material.cohesion" = { distribution = "uniform", mean = 1, std = 0.1 }\n'
         '"material.tensile_strength" = { distribution = "uniform", mean = 0.5, std = 0.1 }\n'
         '[uncertainty.correlation]\n"material.friction|material.cohesion" = 0.9\n'
         '"material.cohesion|material.tensile_strength" = 0.9\n"material.friction|material.tensile_strength" = -0.9',
         "positive definite"),
        ('cov = 0.15 }', 'cov = 0.15 }\n[uncertainty.correlation]\n"material.friction|material.cohesion" = 0.5',
         "'material.cohesion' is not a variable"),
        ("samples = 20", "samples = 0", "uncertainty.samples"),
        ("samples = 20\nchunk = 8", "samples = 200000\nchunk = 1", "uncertainty.chunk"),
        ("threshold = 0.55", 'capacity = "settlement_capacity"', "uncertainty.capacity"),
    ],
)
def test_bad_input_names_the_key(tmp_path, old, new, key):
    """Each mistake is one StudyError naming the file and the key (the friction drawn normal
    with std 0.2 goes negative among 20 samples: its range is checked, not only its mean)."""
    with pytest.raises(StudyError) as err:
        parse_study(SLIDING.replace(old, new), sliding(tmp_path))
    assert str(tmp_path / "study.toml") in str(err.value) and key in str(err.value)


def test_bad_input_exits_2_and_writes_nothing(tmp_path):
    study = sliding(tmp_path, **{"cov = 0.15": "std = 0.3", 'distribution = "lognormal"': 'distribution = "normal"'})
    done = tce_run(study, tmp_path / "out")
    assert done.returncode == 2
    assert 'uncertainty.variables."material.friction"' in errors(done.stderr)[0], done.stderr
    assert not (tmp_path / "out").exists()


def test_work_estimate_counts_the_samples(tmp_path):
    """[study] max_solves caps the samples too."""
    study = parse_study(SLIDING, sliding(tmp_path))
    assert "20 samples" in study.work()
    with pytest.raises(StudyError, match="study.max_solves"):
        parse_study(SLIDING.replace('name = "sliding"', 'name = "sliding"\nmax_solves = 40'), tmp_path / "study.toml")


def test_statuses_are_counted_never_dropped():
    """+inf survives, -inf fails, NaN is counted apart; the fragility spans the finite capacities."""
    cap = np.array([[0.5, 1.5, np.inf, -np.inf, np.nan, 2.0]])
    status = np.array([["optimal", "optimal", "unbounded", "infeasible", "numerical", "optimal"]], dtype=object)
    ds = xr.Dataset(
        {"sample_capacity": (("scenario", "sample"), cap), "sample_status": (("scenario", "sample"), status),
         "sample_input": (("sample", "variable"), np.array([[1.0], [2.0], [3.0], [0.0], [5.0], [4.0]]))},
        coords={"scenario": ["a"], "sample": np.arange(6), "variable": ["v"]},
        attrs={"uncertainty_threshold": 1.0, "uncertainty_interval": "wilson", "uncertainty_confidence": 0.95},
    )
    out = statistics(ds)
    assert (int(out.n_failed[0]), int(out.n_decided[0]), int(out.n_numerical[0])) == (2, 5, 1)
    assert float(out.failure_probability[0]) == 0.4
    assert float(out.failure_low[0]) < 0.4 < float(out.failure_high[0])
    x = out.fragility_intensity.values[0]
    assert len(x) == FRAGILITY_POINTS and (x[0], x[-1]) == (0.5, 2.0)
    # P(capacity < x) at the largest finite capacity: 0.5, 1.5 and -inf of the 5 decided
    assert float(out.fragility_probability[0, -1]) == pytest.approx(3 / 5)
    assert float(out.sensitivity[0, 0]) == pytest.approx(0.9)  # ranks of (0.5, 1.5, inf, -inf, 2) vs inputs


def test_warm_and_rebuilt_capacities_agree(tmp_path, monkeypatch):
    """The warm solver's capacities are the rebuilt scenarios' (to 1e-7), and each is the drawn
    friction (the block slides at lambda = mu)."""
    from tce.study import samples

    study = parse_study(SLIDING, sliding(tmp_path))
    warm = runner.run_study(study, tmp_path / "warm", jobs=1)
    monkeypatch.setattr(samples, "_warm", lambda *args: None)
    rebuilt = runner.run_study(study, tmp_path / "rebuilt", jobs=1)
    a, b = (xr.load_dataset(r.results) for r in (warm, rebuilt))
    np.testing.assert_allclose(a.sample_capacity.values, b.sample_capacity.values, rtol=1e-7)
    np.testing.assert_allclose(a.sample_capacity.values[0], a.sample_input.values[:, 0], rtol=1e-7)
    assert list(a.capacity_kind.values) == ["lambda_max"]


class Stop(Exception):
    """Stands for a crash or a Ctrl-C between two jobs."""


def test_stopped_run_resumes_without_redrawing(tmp_path):
    """A run stopped after its nominal scenario and first job of samples keeps both; the rerun
    solves only the missing jobs and writes the answer of a run that was never stopped."""
    study = parse_study(SLIDING, sliding(tmp_path))
    clean = answer(runner.run_study(study, tmp_path / "clean", jobs=1).results)

    def stop_after_two(done: int, total: int, steps: int) -> None:
        if done == 2:
            raise Stop

    with pytest.raises(Stop):
        runner.run_study(study, tmp_path / "stopped", jobs=1, progress=stop_after_two)
    folder = tmp_path / "stopped" / "sliding" / "scenarios"
    kept = {p.name: p.stat().st_mtime_ns for p in folder.glob("*.nc")}
    assert sorted(kept) == sorted(p.name for p in (tmp_path / "clean" / "sliding" / "scenarios").glob("*.nc"))[:2]
    report = runner.run_study(study, tmp_path / "stopped", jobs=1)
    assert report.solved == ["none samples 8-16", "none samples 16-20"]
    assert all((folder / n).stat().st_mtime_ns == t for n, t in kept.items())
    xr.testing.assert_identical(answer(report.results), clean)


CRITICAL = """
[study]
name = "critical"

[structure]
type = "semicircular_arch"
voussoirs = 8

[material]
friction = 0.8

[loads]
lateral = false
critical_position = true
lambda_step = 1.0
tolerance = 1e-3

[[loads.point]]
on_top = [0.0, 0.0]
force = [0.0, 0.0, -1.0]

[uncertainty]
samples = 2

[uncertainty.variables]
"structure.unit_weight" = { distribution = "normal", mean = 20, cov = 0.1 }
"""


def test_critical_position_is_searched_for_each_sample(tmp_path, monkeypatch):
    """With critical_position, a sample's capacity is its own least lambda_max over the
    positions, searched for each sample (from the nominal critical position): at most its direct
    limit wherever the load stands (here at five positions)."""
    from tce.analysis import Analysis
    from tce.core.loads import LoadPattern
    from tce.study import samples
    from tce.study.schema import build_material, build_structure

    from tce.analysis import critical
    from tce.study import positions

    searches = []

    def counted(analysis, loads, start=None, **kw):
        searches.append(list(start))
        return search(analysis, loads, start=start, **kw)

    search = critical.critical_position
    monkeypatch.setattr(critical, "critical_position", counted)  # the nominal search (tce.study.positions.search)
    monkeypatch.setattr(samples, "critical_position", counted)  # the samples' searches
    monkeypatch.setattr(positions, "_SEARCHES", {})
    study = parse_study(CRITICAL, tmp_path / "study.toml")
    ds = xr.load_dataset(runner.run_study(study, tmp_path, jobs=1).results)
    # the nominal search once (the scenario's, reused by the job of its samples), then one per
    # sample from its position
    assert searches == [[], [0.0], [0.0]]
    sc = study.scenarios()[0]
    for k, weight in enumerate(ds["sample_input"].values[:, 0]):
        drawn = sc.drawn({"structure.unit_weight": float(weight)})
        analysis = Analysis(build_structure(drawn.structure), build_material(drawn.material))
        pattern = LoadPattern.from_dict(drawn.pattern)
        at = [analysis.limit(loads=pattern.moved(x), mechanism=False).lambda_max for x in (-0.8, -0.5, -0.3, 0.0, 0.4)]
        assert ds["sample_capacity"].values[0, k] <= min(at) * (1 + 1e-6)
        assert ds["sample_capacity"].values[0, k] >= 0.9 * min(at)


ASSESSED = """
[study]
name = "assessed"

[structure]
type = "semicircular_arch"
voussoirs = 6

[material]
friction = 0.7

[loads]
lateral = false
lambda_step = 1.0
tolerance = 1e-2

[[loads.point]]
on_top = [-0.4, 0.0]
force = [0.0, 0.0, -1.0]

[assessment]
dead_factor = 0.9
live_factor = 1.5

[uncertainty]
samples = 3

[uncertainty.variables]
"material.friction" = { distribution = "lognormal", mean = 0.7, cov = 0.2 }
"assessment.live_factor" = { distribution = "normal", mean = 1.5, std = 0.1 }
"""


def test_adequacy_factor_of_each_sample(tmp_path):
    """With [assessment] the samples' capacity is the adequacy factor at their friction and live
    factor: tce.analysis.assessment.adequacy_factor of the rebuilt scenario, to 1e-6."""
    from tce.analysis import Analysis
    from tce.analysis.assessment import adequacy_factor
    from tce.core.loads import LoadPattern
    from tce.study.schema import build_material, build_structure

    study = parse_study(ASSESSED, tmp_path / "study.toml")
    ds = xr.load_dataset(runner.run_study(study, tmp_path, jobs=1).results)
    assert list(ds["capacity_kind"].values) == ["adequacy_factor"]
    sc = study.scenarios()[0]
    for k, row in enumerate(ds["sample_input"].values):
        d = sc.drawn(dict(zip(ds["variable"].values, map(float, row))))
        analysis = Analysis(build_structure(d.structure), build_material(d.material))
        want = adequacy_factor(analysis, LoadPattern.from_dict(d.pattern), d.factors["dead_factor"], d.factors["live_factor"])
        assert ds["sample_capacity"].values[0, k] == pytest.approx(want.lambda_max, rel=1e-6)


SETTLED = """
[study]
name = "settled"

[structure]
type = "semicircular_arch"
voussoirs = 6

[scenarios.spreading]
right = [1.0, 0.0, 0.0, 0.0, 0.0, 0.0]

[settlement_path]
increment = 0.02
s_max = 0.4

[uncertainty]
samples = 2

[uncertainty.variables]
"settlement.magnitude" = { distribution = "uniform", mean = 1.0, std = 0.2 }
"""


def test_settlement_capacity_scales_with_the_drawn_magnitude(tmp_path):
    """With [settlement_path] and a moving support the samples' capacity is the settlement
    capacity in multiples of their own (drawn) settlement vectors: the nominal capacity over
    the magnitude, within the paths' brackets (increment / 64 each)."""
    study = parse_study(SETTLED, tmp_path / "study.toml")
    ds = xr.load_dataset(runner.run_study(study, tmp_path, jobs=1).results)
    assert list(ds["capacity_kind"].values) == ["settlement_capacity"]
    nominal = float(ds["settlement_capacity"].values[0])
    magnitude = ds["sample_input"].values[:, 0]
    assert np.all(np.abs(ds["sample_capacity"].values[0] * magnitude - nominal) <= 1e-3)
    assert list(ds["sample_status"].values[0]) == ["optimal"] * 2


def test_sensitivity_ignores_the_solvers_last_digits():
    """Capacities that differ only in their last digits (a mechanism that friction does not
    govern, solved to 1e-10) are ties: their noise, here correlated with a variable the capacity
    does not depend on, gives that variable no rank correlation."""
    rng = np.random.default_rng(1)
    friction, weight = rng.uniform(0.4, 0.8, 400), rng.uniform(18, 22, 400)
    cap = np.minimum(friction, 0.5) * (1 + 1e-13 * weight)  # a plateau at 0.5 above friction 0.5
    ds = xr.Dataset(
        {"sample_capacity": (("scenario", "sample"), cap[None]),
         "sample_status": (("scenario", "sample"), np.full((1, 400), "optimal", dtype=object)),
         "sample_input": (("sample", "variable"), np.column_stack([friction, weight]))},
        coords={"scenario": ["a"], "sample": np.arange(400), "variable": ["friction", "weight"]},
        attrs={"uncertainty_threshold": 0.45, "uncertainty_interval": "wilson", "uncertainty_confidence": 0.95},
    )
    sens = statistics(ds)["sensitivity"].values[0]
    assert sens[0] > 0.7 and abs(sens[1]) < 0.15


def test_form_beyond_the_keys_range_stops_saying_so(tmp_path):
    """FORM's first step towards a threshold the friction reaches only at about u = 8 lands where
    the friction is infinite (u = 15.9): the FORM job ends with a status, not the run."""
    text = SLIDING.replace("threshold = 0.55", "threshold = 2.0\nform = true")
    report = runner.run_study(parse_study(text, sliding(tmp_path, text)), tmp_path, jobs=1)
    ds = xr.load_dataset(report.results)
    assert ds["form_status"].values[0].startswith("capacity out_of_range at u = ")
    assert math.isnan(float(ds["form_beta"][0])) and float(ds["failure_probability"][0]) == 1.0


def test_ring_and_joint_laws_take_the_sampled_friction(tmp_path):
    """A joint law of [defects] that leaves its friction to [material] takes each sample's
    friction; a structure variable with [defects] is refused."""
    text = """
[study]
name = "laws"

[structure]
type = "semicircular_arch"
voussoirs = 6

[material]
friction = 0.6

[loads]
lambda_step = 0.2
tolerance = 1e-2

[defects]
[[defects.joint_law]]
joints = ["v01|v02"]
cohesion = 1.0

[uncertainty]
samples = 2

[uncertainty.variables]
"material.friction" = { distribution = "uniform", mean = 0.5, std = 0.05 }
"""
    study = parse_study(text, tmp_path / "study.toml")
    ds = xr.load_dataset(runner.run_study(study, tmp_path, jobs=1).results)
    from tce.analysis import Analysis
    from tce.study.schema import build_material

    sc = study.scenarios()[0]
    for k, mu in enumerate(ds["sample_input"].values[:, 0]):
        d = sc.drawn({"material.friction": float(mu)})
        want = Analysis(study.assembly(sc.structure), build_material(d.material)).limit(mechanism=False, alpha=0.0)
        assert want.status == "optimal"
        assert ds["sample_capacity"].values[0, k] == pytest.approx(want.lambda_max, rel=1e-7)
    with pytest.raises(StudyError, match='uncertainty.variables."structure.thickness"'):
        parse_study(text.replace('"material.friction"', '"structure.thickness"').replace("mean = 0.5, std = 0.05",
                                                                                        "mean = 0.2, std = 0.01"),
                    tmp_path / "study.toml")
