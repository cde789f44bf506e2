"""Figures, ``tce show`` and the report of scenarios whose every step is unbounded (or infeasible).

The paper: problem (9) with a transversal support motion "in the space Sym+ is unbounded"
for a Heyman material (no friction limit). Such a study must run to the end (exit 0) and
every figure kind that applies must say in words why it draws no state, not raise
(issue 37 item 7: the transversal figure raised "no drawn state has a solved step").
"""

from __future__ import annotations

import html
import re
from pathlib import Path

import pytest
import xarray as xr

from tce.cli import main
from tce.plot.capacity import influence_line
from tce.plot.figures import base_figure, transversal_figure
from tce.plot.data import plot_spec
from tce.plot.output import figure_tasks, render
from tce.study.names import PLOT_KINDS

STUDY = """
[study]
name = "heyman_transversal"

[structure]
type = "semicircular_arch"
voussoirs = 6

[material]
{material}

[loads]
alpha = 0.0
lambda_step = 0.1
tolerance = 1e-3

[[loads.point]]
on_top = [0.25, 0.0]
force = [0.0, 0.0, -1.0]

[sweep]
thickness = [0.2, 0.25]
load_x = [-0.25, 0.25]

[scenarios.transversal]
right = [0.0, 0.001, 0.0, 0.0, 0.0, 0.0]

[plots]
steps = [0.0, "max"]
kinds = {kinds}
"""


#: outcome -> the material that gives it: Heyman (the paper's unbounded case), and a friction
#: too low for the arch to stand at all
MATERIALS = {"unbounded": "", "infeasible": "friction = 0.05"}


@pytest.fixture(scope="module", params=list(MATERIALS))
def ran(request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory) -> tuple[str, int, Path]:
    """The study run through the command line, every figure kind asked for: the outcome
    expected of every scenario, the exit code and the results folder."""
    tmp = tmp_path_factory.mktemp(request.param)
    study = tmp / "arch.toml"
    study.write_text(STUDY.format(material=MATERIALS[request.param],
                                  kinds="[" + ", ".join(f'"{k}"' for k in PLOT_KINDS) + "]"))
    out = tmp / "out"
    rc = main(["run", str(study), "--out", str(out), "--jobs", "1"])
    return request.param, rc, out / "heyman_transversal"


def test_run_show_report_of_a_study_without_a_state(ran: tuple[str, int, Path], capsys: pytest.CaptureFixture) -> None:
    outcome, rc, folder = ran
    assert rc == 0
    ds = xr.load_dataset(folder / "results.nc")
    assert set(ds["outcome"].values) == {outcome}
    for name in ("states.png", "transversal.png", "thrust.png", "summary.png", "capacity.png", "view.html"):
        assert (folder / name).stat().st_size > 0, name
    capsys.readouterr()
    assert main(["show", str(folder / "results.nc")]) == 0
    assert outcome in capsys.readouterr().out
    assert main(["report", str(folder / "results.nc")]) == 0
    report = " ".join(html.unescape(re.sub(r"<[^>]+>", " ", (folder / "report.html").read_text())).split())
    # the warning says what the outcome means (on main: "outcome unbounded: no λmax is reported for it")
    assert f"{ds['scenario'].values[0]}: {outcome}: " in report
    assert "no state of finite energy" in report or outcome != "unbounded"


@pytest.mark.parametrize("kind", PLOT_KINDS)
def test_every_figure_kind_tolerates_steps_without_a_state(ran: tuple[str, int, Path], kind: str,
                                                           tmp_path: Path) -> None:
    """Each kind that applies to the study draws (none raises); the transversal, capacity and
    base figures say why they have no state. (bracket, settlement and settlement_shapes do not
    apply: a Heyman material has no friction to sweep and no settlement path follows a motion
    out of the arch's plane.)"""
    outcome, _, folder = ran
    ds = xr.load_dataset(folder / "results.nc")
    spec = plot_spec(ds, kinds=[kind])
    for task in figure_tasks(ds, spec):
        assert render(ds, task, tmp_path).stat().st_size > 0
    first = [str(ds["scenario"].values[0])]
    says = {"transversal": lambda: transversal_figure(ds, first, [0.0]), "base": lambda: base_figure(ds, first, [0.0]),
            "capacity": lambda: influence_line(ds)}
    if kind in says:  # the figures that drew nothing without a word (or raised) on main say why
        fig = says[kind]()
        texts = fig.texts + [t for ax in fig.axes for t in ax.texts]
        words = " ".join(" ".join(t.get_text() for t in texts).split())
        assert f"{outcome}: " in words
        assert "no state of finite energy" in words or outcome != "unbounded"
