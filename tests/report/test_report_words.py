"""What the report's summary, warnings and references say (issue 37 item 8).

A Heyman arch with four settlement cases: with rigid blocks and small displacements the
collapse load does not depend on a support motion, so the four lambda_max tie; three of
the cases move a support. On main the summary named one scenario of the tie, the warnings
said "(rigid contacts, no support motion)" for the moving ones, and the references were
numbered [1], [2], [5].
"""

from __future__ import annotations

import html
import re
from pathlib import Path

import pytest
import xarray as xr

from tce.cli import main
from tce.study.names import same_lambda

STUDY = """
[study]
name = "words"

[structure]
type = "semicircular_arch"
voussoirs = 6

[material]

[loads]
alpha = 0.0
lambda_step = 0.1
tolerance = 1e-4

[scenarios.none]

[scenarios.outward]
right = [0.001, 0.0, 0.0, 0.0, 0.0, 0.0]

[scenarios.down]
right = [0.0, 0.0, -0.001, 0.0, 0.0, 0.0]

[scenarios.inward]
right = [-0.001, 0.0, 0.0, 0.0, 0.0, 0.0]

[plots]
kinds = ["thrust"]
"""

MOVING = ("outward", "down", "inward")


@pytest.fixture(scope="module")
def report(tmp_path_factory: pytest.TempPathFactory) -> tuple[str, xr.Dataset]:
    """The report's text (tags removed) and the results of the study's run."""
    tmp = tmp_path_factory.mktemp("words")
    study = tmp / "words.toml"
    study.write_text(STUDY)
    assert main(["-q", "run", str(study), "--out", str(tmp / "out"), "--jobs", "1"]) == 0
    folder = tmp / "out" / "words"
    text = html.unescape(re.sub(r"<[^>]+>", "\n", (folder / "report.html").read_text(encoding="utf-8")))
    return " ".join(text.split()), xr.load_dataset(folder / "results.nc")


def test_the_summary_names_every_tied_scenario(report: tuple[str, xr.Dataset]) -> None:
    text, ds = report
    lam = ds["lambda_max"].values
    assert all(same_lambda(x, lam[0]) for x in lam)  # the premise: a four-way tie
    summary = re.search(r"The smallest load multiplier at collapse is λmax = \S+ \(([^)]*)\)", text)
    assert summary is not None
    assert summary[1] == "scenarios none, outward, down, inward, tied within 1e-09 relative"


def test_the_uniqueness_warning_says_whether_a_support_moves(report: tuple[str, xr.Dataset]) -> None:
    text, _ = report
    warnings = dict(re.findall(r"(\w+): \d+ optimal step\(s\) are not necessarily unique \(([^)]*)\)", text))
    assert set(warnings) == {"none", *MOVING}  # the premise: every scenario has non-unique steps
    assert "no support motion" in warnings["none"]
    for name in MOVING:
        assert "no support motion" not in warnings[name], name


def test_references_are_numbered_in_order_of_first_citation(report: tuple[str, xr.Dataset]) -> None:
    text, _ = report
    method, refs = text.split("Method and assumptions", 1)[1].split("References", 1)
    cited = list(dict.fromkeys(re.findall(r"\[(\d+)\]", method)))
    assert cited == [str(k) for k in range(1, len(cited) + 1)]
    labels = re.findall(r"\[(\d+)\] \S", refs.split("Results", 1)[0])
    assert labels == cited
    assert "Heyman" in refs and "Ochsendorf" in refs  # the Heyman material and the settlements are cited
