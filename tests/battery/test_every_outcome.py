"""Every figure kind, ``tce show`` and the report on every outcome word (issue 37).

A small arch study is run through the command line with every figure kind asked for, in
variants that end each load path with one outcome word of :data:`tce.study.runner.OUTCOMES`,
and one that mixes them:

- ``limit`` is the ordinary case, run by the rest of the suite;
- ``unbounded``: a Heyman material and a transversal support motion (the paper: problem (9)
  with such a motion "in the space Sym+ is unbounded"; issue 37 item 7: the transversal
  figure raised "no drawn state has a solved step");
- ``infeasible``: a friction too low for the arch to stand at all;
- ``capped``: ``lambda_cap`` below the collapse load;
- ``no_limit``: the live load on the springing voussoir, straight above its support joint
  (the direct limit is unbounded: the load is carried at any lambda);
- ``numerical``: no small scene makes the solver fail on purpose, so the ``capped`` study's
  results have their last step marked undecided afterwards, as the load path leaves them
  when the solver cannot decide its last steps (:func:`undecided`: status ``numerical``, no
  state, outcome ``numerical``, no lambda_max), and are drawn again by ``tce plot``;
- ``mixed``: a Heyman arch too thin to stand and one that stands, each still and moved
  across, capped: ``infeasible``, ``capped`` and ``unbounded`` in one study, and one of
  the thin arch's paths marked undecided (``numerical``).

Each study must run to the end (exit 0), every figure kind that applies must draw, and the
figures without a state must say in words why.
"""

from __future__ import annotations

import html
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from tce.cli import main
from tce.plot.capacity import influence_line
from tce.plot.data import plot_spec
from tce.plot.figures import base_figure, transversal_figure
from tce.plot.output import figure_tasks
from tce.study.names import PLOT_KINDS
from tce.study.runner import OUTCOMES

STUDY = """
[study]
name = "outcomes"

[structure]
type = "semicircular_arch"
voussoirs = 6

[material]
{material}

[loads]
alpha = 0.0
lambda_step = 0.01
lambda_cap = {cap}
tolerance = 1e-3

[[loads.point]]
on_top = [0.25, 0.0]
force = [0.0, 0.0, -1.0]

[sweep]
thickness = {thickness}
load_x = {load_x}

{scenarios}

[plots]
steps = [0.0, "max"]
kinds = {kinds}
"""

STILL = "[scenarios.still]\nright = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]"
ACROSS = "[scenarios.across]\nright = [0.0, 0.001, 0.0, 0.0, 0.0, 0.0]"


@dataclass(frozen=True)
class Case:
    """A study variant: its sections, the outcome of each scenario by its name without the
    load position (``across/thickness=0.25``: two scenarios, the load at each ``load_x``),
    and the scenarios (so named) whose last step is marked undecided after the run
    (:func:`undecided`)."""

    outcomes: dict[str, str]
    material: str = ""
    cap: float = 1.0
    thickness: tuple[float, ...] = (0.2, 0.25)
    load_x: tuple[float, ...] = (-0.25, 0.25)
    scenarios: str = ACROSS
    undecided: tuple[str, ...] = field(default=())
    #: the figure kinds that do not apply beyond :data:`NOT_APPLYING`
    not_drawn: frozenset[str] = frozenset()

    def outcome(self, scenario: str) -> str:
        """The outcome expected of ``scenario`` (its full name)."""
        return self.outcomes[scenario.rsplit("/load_x=", 1)[0]]


#: the kinds that apply to none of these studies: no friction is swept (bracket), no
#: settlement path and no uncertainty is asked for (their outcome words: tests/plot/test_uncertainty.py)
NOT_APPLYING = {"bracket", "settlement", "settlement_shapes", "fragility", "capacity_samples", "sensitivity",
                "convergence"}

#: both thicknesses of the single-outcome studies
BOTH = ("thickness=0.2", "thickness=0.25")

CASES = {
    "unbounded": Case({f"across/{t}": "unbounded" for t in BOTH}),
    "infeasible": Case({f"across/{t}": "infeasible" for t in BOTH}, material="friction = 0.05"),
    "capped": Case({f"still/{t}": "capped" for t in BOTH}, material="friction = 0.6", cap=0.02, scenarios=STILL),
    # on the extrados above the springing joint (x from -1.1 to -0.9 at thickness 0.2)
    # (nothing collapses: no mechanism to draw)
    "no_limit": Case({f"still/{t}": "no_limit" for t in BOTH}, material="friction = 0.6", load_x=(-1.05, -1.0),
                     scenarios=STILL, not_drawn=frozenset({"mechanism"})),
    "numerical": Case({f"still/{t}": "numerical" for t in BOTH}, material="friction = 0.6", cap=0.02, scenarios=STILL,
                      undecided=tuple(f"still/{t}" for t in BOTH)),
    "mixed": Case(
        {"still/thickness=0.05": "infeasible", "still/thickness=0.25": "capped",
         "across/thickness=0.05": "numerical", "across/thickness=0.25": "unbounded"},
        cap=0.02, thickness=(0.05, 0.25), scenarios=f"{STILL}\n\n{ACROSS}", undecided=("across/thickness=0.05",),
    ),
}


def test_the_cases_cover_every_outcome_word() -> None:
    """Every outcome word but ``limit`` (the rest of the suite's) has its study here."""
    assert {o for c in CASES.values() for o in c.outcomes.values()} == set(OUTCOMES) - {"limit"}


def undecided(ds: xr.Dataset, scenario: str) -> xr.Dataset:
    """``ds`` with the last solved step of ``scenario`` undecided: its status ``numerical``,
    its state NaN, the outcome ``numerical`` with no lambda_max (what
    :func:`tce.analysis.loadpath.load_path` reports when the solver cannot decide its last
    steps)."""
    out = ds.copy(deep=True)
    for name in ("status", "outcome"):  # room for the word (a fixed-width string array)
        out[name] = out[name].astype(object)
    solved = np.flatnonzero(out["status"].sel(scenario=scenario).values != "")
    at = {"scenario": scenario, "step": int(solved[-1])}
    for name, var in out.data_vars.items():
        if {"scenario", "step"} <= set(var.dims) and name not in ("lam", "status") and var.dtype.kind == "f":
            var.loc[at] = np.nan
    out["status"].loc[at] = "numerical"
    out["outcome"].loc[{"scenario": scenario}] = "numerical"
    for name in ("lambda_max", "lambda_upper"):
        out[name].loc[{"scenario": scenario}] = np.nan
    return out


@pytest.fixture(scope="module", params=list(CASES))
def ran(request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory) -> tuple[Case, int, Path]:
    """The case's study run through the command line, every figure kind asked for (the
    figures drawn again by ``tce plot`` after a step is marked undecided): the case, the
    exit codes' largest and the results folder."""
    case = CASES[request.param]
    tmp = tmp_path_factory.mktemp(request.param)
    study = tmp / "arch.toml"
    kinds = "[" + ", ".join(f'"{k}"' for k in PLOT_KINDS) + "]"
    study.write_text(STUDY.format(material=case.material, cap=case.cap, thickness=list(case.thickness),
                                  load_x=list(case.load_x), scenarios=case.scenarios, kinds=kinds))
    out = tmp / "out"
    rc = main(["run", str(study), "--out", str(out), "--jobs", "1"])
    folder = out / "outcomes"
    if case.undecided:
        ds = xr.load_dataset(folder / "results.nc")
        for scenario in ds["scenario"].values.tolist():
            if scenario.rsplit("/load_x=", 1)[0] in case.undecided:
                ds = undecided(ds, scenario)
        ds.to_netcdf(folder / "results.nc")
        rc = max(rc, main(["plot", str(folder / "results.nc")]))
    return case, rc, folder


def test_run_show_report_on_every_outcome(ran: tuple[Case, int, Path], capsys: pytest.CaptureFixture) -> None:
    """The run (and the redrawing) ends with exit 0 and its figures; ``tce show`` names every
    scenario's outcome; the report's warnings say what each outcome other than a capped
    path means."""
    case, rc, folder = ran
    assert rc == 0
    ds = xr.load_dataset(folder / "results.nc")
    outcomes = dict(zip(ds["scenario"].values.tolist(), ds["outcome"].values.tolist(), strict=True))
    assert len(outcomes) == len(case.outcomes) * len(case.load_x)
    assert outcomes == {s: case.outcome(s) for s in outcomes}
    across = ["transversal.png"] if "[scenarios.across]" in case.scenarios else []
    for name in ("states.png", "thrust.png", "summary.png", "capacity.png", "view.html", *across):
        assert (folder / name).stat().st_size > 0, name
    capsys.readouterr()
    assert main(["show", str(folder / "results.nc")]) == 0
    shown = capsys.readouterr().out
    for scenario, outcome in outcomes.items():
        line = next(x for x in shown.splitlines() if scenario in x)
        assert outcome.replace("_", " ") in line.replace("_", " "), (scenario, line)
    assert main(["report", "--no-pdf", str(folder / "results.nc")]) == 0
    report = " ".join(html.unescape(re.sub(r"<[^>]+>", " ", (folder / "report.html").read_text())).split())
    for scenario, outcome in outcomes.items():
        if outcome != "capped":
            assert f"{scenario}: {outcome}: " in report, (scenario, outcome)
    assert "no state of finite energy" in report or "unbounded" not in case.outcomes.values()


def test_every_figure_kind_drawn_on_every_outcome(ran: tuple[Case, int, Path]) -> None:
    """Every kind that applies was drawn (a figure that raises ends the run, or ``tce plot``,
    with exit 1: ``test_run_show_report_on_every_outcome``); the transversal figure applies
    where a support moves across."""
    case, rc, folder = ran
    assert rc == 0
    ds = xr.load_dataset(folder / "results.nc")
    tasks = figure_tasks(ds, plot_spec(ds))
    flat = set() if "[scenarios.across]" in case.scenarios else {"transversal"}
    assert {t.kind for t in tasks} == set(PLOT_KINDS) - NOT_APPLYING - case.not_drawn - flat
    for task in tasks:
        assert (folder / task.name).stat().st_size > 0, task.name


@pytest.mark.parametrize("kind", ["transversal", "base"])
def test_figures_without_a_state_say_why(ran: tuple[Case, int, Path], kind: str) -> None:
    """The transversal and base figures of a scenario without a drawn state (unbounded,
    infeasible) say it in words (on main before issue 37 they drew nothing without a word,
    or raised)."""
    case, _, folder = ran
    ds = xr.load_dataset(folder / "results.nc")
    draw = {"transversal": transversal_figure, "base": base_figure}[kind]
    for scenario in ds["scenario"].values.tolist():
        outcome = case.outcome(scenario)
        if outcome in ("unbounded", "infeasible"):
            words = _words(draw(ds, [scenario], [0.0]))
            assert f"{outcome}: " in words, (scenario, words)
            assert "no state of finite energy" in words or outcome != "unbounded"
            assert "beyond the limit" not in words  # at 0 nothing stands: there is no limit to be beyond
            assert "cannot stand" in words or outcome != "infeasible"


def test_capacity_figure_words_every_outcome(ran: tuple[Case, int, Path]) -> None:
    """No position has a finite lambda_max in these studies: the capacity figure counts the
    scenarios of each outcome and says what it means, with the numbers it names (a capped
    path said "capped at lambda = nan, below the collapse load lambda_direct = nan")."""
    case, _, folder = ran
    ds = xr.load_dataset(folder / "results.nc")
    words = _words(influence_line(ds))
    for outcome in set(case.outcomes.values()):
        n = sum(case.outcome(s) == outcome for s in ds["scenario"].values.tolist())
        assert f"{n} scenario(s) {outcome.replace('_', ' ')}" in words, (outcome, words)
    assert "nan" not in words, words
    if "capped" in case.outcomes.values():
        assert f"capped at λ = {case.cap:.6g}, below the collapse load λ_direct = " in words, words


def _words(fig) -> str:
    """Every text of a figure, its line breaks folded."""
    return " ".join(" ".join(t.get_text() for t in fig.texts + [t for ax in fig.axes for t in ax.texts]).split())
