"""The report's Uncertainty section, read as text: the sampling, the variables, what failure
means and, per scenario, the numbers ``results.nc`` holds, with the four figures; every
sample outcome word said; a study without ``[uncertainty]`` reports what it reported.

The results are a real small study's with the layout's uncertainty variables added
(``tests/plot/uncertainty_data.py``).
"""

from __future__ import annotations

import html
import re
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from plot.uncertainty_data import VARIABLES, small_study, with_uncertainty
from tce.plot.data import counts_note
from tce.report import write_report

THIN, MID, THICK = "none/thickness=0.2", "none/thickness=0.25", "none/thickness=0.3"


@pytest.fixture(scope="module")
def base(tmp_path_factory: pytest.TempPathFactory) -> xr.Dataset:
    return small_study(tmp_path_factory.mktemp("uq"))


def _report(ds: xr.Dataset, folder: Path) -> tuple[str, str]:
    """The report of ``ds`` (its figures drawn by the report): the page and its text."""
    folder.mkdir(parents=True, exist_ok=True)
    ds.to_netcdf(folder / "results.nc")
    page = write_report(folder / "results.nc", pdf=False).html.read_text(encoding="utf-8")
    return page, " ".join(html.unescape(re.sub(r"<[^>]+>", " ", page)).split())


def _section(page: str, anchor: str) -> str:
    """The HTML of the section ``<h2 id=anchor>`` up to the next ``<h2``."""
    start = page.index(f'<h2 id="{anchor}">')
    return page[start:page.index("<h2", start + 4)]


def test_the_uncertainty_section_says_what_results_nc_holds(base: xr.Dataset, tmp_path: Path) -> None:
    """Method, seed, N, the variables with their distributions, the threshold and what it
    measures, each scenario's probability with its interval, beta, counts and dominant
    variable, FORM and subset, and the four figures in the section; the summary names the
    largest probability; the sections after it are renumbered."""
    ds = with_uncertainty(base, n=300, seed=7)
    page, words = _report(ds, tmp_path)
    section = _section(page, "uncertainty")
    text = " ".join(html.unescape(re.sub(r"<[^>]+>", " ", section)).split())
    assert text.startswith("7. Uncertainty")
    assert "300 samples of the random variables below, drawn by Latin hypercube sampling (seed 7" in text
    threshold = float(ds.attrs["uncertainty_threshold"])
    assert f"Failure is the capacity below {threshold:g}, the capacity being the load multiplier λ" in text
    assert "95 % Clopper-Pearson interval" in text
    for key, spec in VARIABLES.items():
        assert f"{key} {spec['distribution']} " in text
    for k, s in enumerate(ds["scenario"].values.tolist()):
        pf, lo, hi, beta = (float(ds[v].values[k]) for v in
                            ("failure_probability", "failure_low", "failure_high", "reliability_index"))
        sens = ds["sensitivity"].values[k]
        top = str(ds["variable"].values[abs(sens).argmax()])
        assert (f"{s} lambda_max {pf:.4g} [{lo:.4g}, {hi:.4g}] {beta:.4g} {int(ds['n_failed'].values[k])} "
                f"{int(ds['n_decided'].values[k])} 0 {top} ({sens[abs(sens).argmax()]:+.2f}) β ") in text, s
        assert f"pf {float(ds['subset_pf'].values[k]):.4g} (c.o.v. 0.2), converged, 2800 evaluations" in text
    assert section.count("<img") == 4
    for title in ("Probability of collapse (fragility)", "Sampled capacities", "Sensitivity of the capacity",
                  "Failure probability against the number of samples"):
        assert title in text
    largest = int(np.argmax(ds["failure_probability"].values))
    assert (f"largest P = {float(ds['failure_probability'].values[largest]):.4g} "
            f"[{float(ds['failure_low'].values[largest]):.4g}, ") in words
    assert "8. Warnings" in words and "9. Figures" in words and "Figure 5: λmax against" in words


@pytest.mark.parametrize("modes", [{THIN: "infeasible", MID: "unbounded", THICK: "some_numerical"},
                                   {THIN: "numerical"}], ids=["unbounded-infeasible-some", "all-numerical"])
def test_every_sample_outcome_is_reported(base: xr.Dataset, tmp_path: Path, modes: dict[str, str]) -> None:
    """A scenario whose samples are all unbounded, all infeasible, all or some numerical is
    counted in the section and in the warnings; one without a decided sample has no
    probability, and says so."""
    ds = with_uncertainty(base, n=100, modes=modes)
    page, words = _report(ds, tmp_path)
    warnings = " ".join(html.unescape(re.sub(r"<[^>]+>", " ", _section(page, "warnings"))).split())
    for s in modes:
        note = counts_note(ds, s)
        assert f"{s}: {note}" in words and f"{s}: samples: {note}" in warnings, s
    if "numerical" in modes.values():
        assert f"{THIN}: samples: all 100 samples numerical: undecided (NaN: left out of the estimate); " \
               "no decided sample: no failure probability." in warnings
        assert f"{THIN} lambda_max NaN [NaN, NaN] NaN 0 0 100 undefined" in words
    else:
        assert f"{THIN} lambda_max 1 [" in words and f"{MID} lambda_max 0 [0, " in words


def test_a_study_without_uncertainty_reports_what_it_reported(base: xr.Dataset, tmp_path: Path) -> None:
    """No Uncertainty section, sentence or figure; the sections keep their numbers."""
    page, words = _report(base, tmp_path)
    assert 'id="uncertainty"' not in page and "Probability of failure" not in words
    assert "7. Warnings" in words and "8. Figures" in words and "9. Provenance" in words
    assert "Figure 1: λmax against" in words and "Figure 2" not in words
