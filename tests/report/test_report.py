"""The calculation report (``tce report``, written by ``tce run``): one self-contained HTML file
and its PDF, opened in a real headless Chromium (selenium), printed and read back (pypdf).

What it must hold: every number ``tce show`` prints (a newcomer finds the same numbers), the
structure, material, loads, scenarios, method and references, every figure of the run
(embedded, no network), the warnings and the provenance. Skipped, with the reason, only where
chromium or chromedriver is missing.
"""

from __future__ import annotations

import hashlib
import html
import re
from html.parser import HTMLParser
from pathlib import Path

import pytest

from helpers import BROWSER, chromium
from tce.cli import main

ROOT = Path(__file__).resolve().parents[2]
SHOT = ROOT / "results" / "report" / "report_screenshot.png"

STUDY = """
[study]
name = "rep"
description = "a small arch for the report's test"

[structure]
type = "semicircular_arch"
inner_radius = 1.0
thickness = 0.2
depth = 0.25
voussoirs = 6

[material]
friction = 0.8

[loads]
alpha = 0.0
lambda_step = 0.05
tolerance = 1e-4

[sweep]
friction = [0.8, 2.0]

[scenarios.none]

[scenarios.outward]
right = [0.001, 0.0, 0.0, 0.0, 0.0, 0.0]

[plots]
steps = [0.0, "max"]
kinds = ["states", "thrust", "summary"]
"""


class _Text(HTMLParser):
    """The text of every table cell and the sources of every image of a page."""

    def __init__(self) -> None:
        super().__init__()
        self.cells: list[str] = []
        self.sources: list[str] = []
        self.links: list[str] = []
        self._cell: list[str] | None = None

    def handle_starttag(self, tag: str, attrs: list) -> None:
        a = dict(attrs)
        if tag in ("td", "th"):
            self._cell = []
        if tag == "img":
            self.sources.append(a.get("src", ""))
        for key in ("href", "src"):
            if key in a and tag != "img":
                self.links.append(a[key])

    def handle_endtag(self, tag: str) -> None:
        if tag in ("td", "th") and self._cell is not None:
            self.cells.append("".join(self._cell).strip())
            self._cell = None

    def handle_data(self, data: str) -> None:
        if self._cell is not None:
            self._cell.append(data)


@pytest.fixture(scope="module")
def run(tmp_path_factory) -> dict[str, object]:
    """``tce run --pdf`` of the small study (figures, report and PDF) and its ``tce show`` output."""
    import contextlib
    import io

    tmp = tmp_path_factory.mktemp("report")
    study = tmp / "rep.toml"
    study.write_text(STUDY, encoding="utf-8")
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert main(["-q", "run", str(study), "--out", str(tmp / "out"), "--jobs", "1", "--pdf"]) == 0
    folder = tmp / "out" / "rep"
    show = io.StringIO()
    with contextlib.redirect_stdout(show):
        assert main(["show", str(folder / "results.nc")]) == 0
    return {"folder": folder, "run": out.getvalue(), "show": show.getvalue()}


def _page(folder: Path) -> tuple[str, _Text]:
    text = (folder / "report.html").read_text(encoding="utf-8")
    parsed = _Text()
    parsed.feed(text)
    return text, parsed


def test_run_writes_the_report(run) -> None:
    folder = run["folder"]
    assert (folder / "report.html").is_file()
    assert f"report: {folder / 'report.html'}" in run["run"]
    if BROWSER is not None:
        assert (folder / "report.pdf").is_file()


def test_a_plain_run_writes_no_pdf_and_says_how(tmp_path: Path, capsys, monkeypatch) -> None:
    """The PDF is printed on request only (``--pdf``, or ``tce report``): a plain run never
    starts Chromium."""
    import tce.report

    def no_browser(*args, **kwargs):
        raise AssertionError("a run without --pdf started Chromium")

    monkeypatch.setattr(tce.report, "print_pdf", no_browser)
    study = tmp_path / "rep.toml"
    study.write_text(STUDY, encoding="utf-8")
    assert main(["-q", "run", str(study), "--out", str(tmp_path / "out"), "--jobs", "1"]) == 0
    folder = tmp_path / "out" / "rep"
    assert (folder / "report.html").is_file() and not (folder / "report.pdf").exists()
    assert f"(the PDF: tce run --pdf, or tce report {folder / 'results.nc'})" in capsys.readouterr().out


NUMBER = r"(?<![\w.])-?\d+(?:\.\d+)?(?:e[-+]?\d+)?(?![\w.])"


def _missing(show: str, page: _Text) -> tuple[list[str], list[str]]:
    """The numbers ``tce show`` prints (title line and the ``loads:`` sentence left out: the report
    prints that sentence whole, test_the_report_and_show_say_what_lambda_multiplies) and those
    no table cell of the page holds."""
    found = {t for c in page.cells for t in re.findall(NUMBER, c)}
    body = [line for line in show.split("\n")[1:] if not line.startswith("loads: ")]
    numbers = re.findall(NUMBER, "\n".join(body))
    return numbers, [n for n in numbers if n not in found]


def test_every_number_of_tce_show_is_in_the_report(run) -> None:
    _, page = _page(run["folder"])
    cells = set(page.cells)
    numbers, missing = _missing(run["show"], page)
    assert len(numbers) >= 2 * 8  # two rows of eight columns at least
    assert not missing, missing
    assert not [n for n in numbers if n not in cells]  # each in a cell of its own, as show prints it
    for word in ("limit", "planar", "none", "outward"):
        assert any(word in c for c in cells)


def test_the_report_and_show_say_what_lambda_multiplies(run) -> None:
    """Issue 37 item 1: the loads section and the results say what lambda multiplies, as
    ``tce show`` does (fails on main: neither said it)."""
    text, _ = _page(run["folder"])
    words = "lambda multiplies the lateral load lambda*W (every block's weight, horizontal) in direction alpha = 0 " \
            "degrees; fixed: self-weight"
    assert f"loads: {words}" in run["show"]
    assert html.unescape(text).count(words) == 2  # section 4 (loads) and section 6 (results)


def test_the_report_says_what_an_engineer_hands_in(run) -> None:
    text, page = _page(run["folder"])
    for needed in ("Structure", "Material and contact law", "Coulomb friction mu = 0.8", "Settlement scenarios",
                   "Sweep", "Method and assumptions", "References", "Heyman", "Results", "Brackets and checks",
                   "Warnings", "Figures", "Provenance", "SHA-256", "tce run rep.toml", "[scenarios.outward]"):
        assert needed in text, needed
    # the rigid scenario without settlement: its states are not unique, and the report says so
    assert "not necessarily unique" in text
    digest = hashlib.sha256((run["folder"] / "results.nc").read_bytes()).hexdigest()
    assert digest in text


def test_the_report_embeds_every_figure_and_fetches_nothing(run) -> None:
    text, page = _page(run["folder"])
    pngs = sorted(p.name for p in run["folder"].glob("*.png"))
    assert pngs and len(page.sources) == len(pngs) + 1  # the structure drawing and every figure of the run
    assert all(s.startswith("data:image/png;base64,") for s in page.sources)
    assert not [u for u in page.links if re.match(r"[a-z]+://", u)]
    assert "http://" not in text.replace("http://www.w3.org", "") and "https://" not in text


def test_report_in_chromium_and_its_pdf(run) -> None:
    from PIL import Image, ImageStat

    pypdf = pytest.importorskip("pypdf")
    page = (run["folder"] / "report.html").as_uri()
    with chromium() as browser:
        browser.get(page)
        loaded = browser.execute_script(
            "return Array.from(document.images).map(i => i.complete && i.naturalWidth > 0)")
        assert loaded and all(loaded)
        fetched = browser.execute_script(
            "return performance.getEntriesByType('resource').map(e => e.name).filter(n => !n.startsWith('data:'))")
        assert fetched == []
        errors = [e for e in browser.get_log("browser") if e["level"] == "SEVERE"]
        assert not errors, errors
        SHOT.parent.mkdir(parents=True, exist_ok=True)
        assert browser.save_screenshot(str(SHOT))
    with Image.open(SHOT) as img:
        assert ImageStat.Stat(img.convert("L")).var[0] > 100.0  # not blank
    reader = pypdf.PdfReader(run["folder"] / "report.pdf")
    assert len(reader.pages) >= 3  # structure, results, figures
    first = reader.pages[0].extract_text()
    assert "Calculation report: rep" in first


def test_report_command(run, tmp_path: Path, capsys, monkeypatch) -> None:
    import tce.report

    monkeypatch.setattr(tce.report, "find_browser", lambda: None)
    assert main(["report", str(run["folder"] / "results.nc"), "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert (tmp_path / "report.html").is_file() and not (tmp_path / "report.pdf").exists()
    assert "PDF skipped: no chromium found" in out


def test_report_draws_the_figures_a_run_did_not(run, tmp_path: Path) -> None:
    """``tce report`` of a results file without its figures beside it draws them for the report."""
    import shutil

    shutil.copy(run["folder"] / "results.nc", tmp_path / "results.nc")
    assert main(["report", str(tmp_path / "results.nc"), "--no-pdf"]) == 0
    _, page = _page(tmp_path)
    assert len(page.sources) == len(list(run["folder"].glob("*.png"))) + 1
    assert not list(tmp_path.glob("*.png"))  # drawn for the report only


@pytest.mark.parametrize("content", [None, b"not a netCDF file"])
def test_report_of_a_bad_file_is_a_usage_error(tmp_path: Path, capsys, content) -> None:
    path = tmp_path / "results.nc"
    if content is not None:
        path.write_bytes(content)
    assert main(["report", str(path)]) == 2
    assert "results.nc" in capsys.readouterr().err
    assert not (tmp_path / "report.html").exists()


def test_the_assessment_and_the_searched_position_are_in_the_report(run, tmp_path: Path, capsys) -> None:
    """The numbers of ``tce show``'s assessment, critical-position search and load notes (values set
    by hand on the run's file: the printing is what is checked)."""
    import numpy as np
    import xarray as xr

    ds = xr.load_dataset(run["folder"] / "results.nc")
    n = ds.sizes["scenario"]
    text = lambda v: ("scenario", np.array([v] * n, dtype=object))  # noqa: E731
    ds = ds.assign(
        adequacy_factor=("scenario", np.linspace(0.78431, 1.2, n)), adequacy_status=text("optimal"),
        dead_factor=("scenario", np.full(n, 1.35)), live_factor=("scenario", np.full(n, 1.5)),
        assessed_vehicles=text("LM1 lane 1 (600 kN)"), critical_x=("scenario", np.full(n, -2.46243)),
        critical_status=text("optimal"), critical_xtol=("scenario", np.full(n, 0.00066)),
        critical_lambda=("scenario", np.full(n, 1.176483)), critical_solves=("scenario", np.full(n, 247)),
        critical_ties=text("1.2624"), load_notes=text("vehicle[0] axle 1 wheel 1 at x = -2.462 m: 17% dropped"),
    )
    path = tmp_path / "results.nc"
    ds.to_netcdf(path)
    assert main(["show", str(path)]) == 0
    show = capsys.readouterr().out
    assert "adequacy factor 0.7843" in show and "247 limit solves" in show
    assert main(["report", str(path), "--no-pdf"]) == 0
    text_, page = _page(tmp_path)
    numbers, missing = _missing(show, page)
    assert not missing, missing
    assert "NOT adequate" in text_ and "0.7843" in text_


def test_the_settlement_path_has_its_section(run, tmp_path: Path, capsys) -> None:
    """The numbers ``tce show`` prints of the settlement path (values set by hand on the run's file:
    the printing is what is checked) are in the report's section of their own, after the results,
    and the sections after it are numbered on (fails on main: no settlement section)."""
    import numpy as np
    import xarray as xr

    ds = xr.load_dataset(run["folder"] / "results.nc")
    n = ds.sizes["scenario"]
    outcomes = ["collapse", "collapse", "numerical", "no_motion"][:n]
    mags = np.array([[0.0, 0.05, 0.135, np.nan], [0.0, 0.0454687, 0.2, 0.662969],
                     [0.0, 0.5, 0.747, np.nan], [np.nan] * 4])[:n]
    lam = np.array([[0.285, 0.01, 0.000666482, np.nan], [0.285, 0.05, 0.03, 0.0168379],
                    [0.285, 0.1, 0.2, np.nan], [np.nan] * 4])[:n]
    ds = ds.assign(
        settlement_capacity=("scenario", np.array([0.135, 0.662969, np.nan, np.nan])[:n]),
        settlement_upper=("scenario", np.array([0.135156, 0.663125, 0.747969, np.nan])[:n]),
        settlement_outcome=("scenario", np.array(outcomes, dtype=object)),
        settlement_hinge_sequence=("scenario", np.array([
            "s=0: v02|v03 hinge; s=0: v06|v07 hinge",
            "s=0: v02|v03 hinge; s=0.0454687: v07|v08 snap; s=0.0454687: v06|v07 hinge",
            "s=0: v01|v02 hinge", ""][:n], dtype=object)),
        settlement_message=("scenario", np.array(["", "", "lateral capacity NaN at 2 magnitudes", ""][:n], dtype=object)),
        settlement_magnitude=(("scenario", "settlement_step"), mags),
        settlement_lambda_max=(("scenario", "settlement_step"), lam),
    )
    path = tmp_path / "results.nc"
    ds.to_netcdf(path)
    assert main(["show", str(path)]) == 0
    show = capsys.readouterr().out
    assert "collapse: capacity 0.662969 (first not standing 0.663125), 1 snap(s), lateral 0.0168379; " \
           "hinges s=0: hinge v02|v03; s=0.0454687: snap v07|v08, hinge v06|v07" in show
    assert "numerical: capacity NaN (first not standing 0.747969), 0 snap(s), lateral –" in show
    assert "    lateral capacity NaN at 2 magnitudes\n" in show  # why the path says what it says
    assert main(["report", str(path), "--no-pdf"]) == 0
    text, page = _page(tmp_path)
    numbers, missing = _missing(show, page)
    assert not missing, missing
    heads = re.findall(r'<h2 id="(\w+)">(\d+)\. ', text)
    assert [h for h, _ in heads][5:8] == ["results", "settlement", "warnings"]
    assert [int(k) for _, k in heads] == list(range(1, len(heads) + 1))
    assert "s=0: hinge v02|v03; s=0.0454687: snap v07|v08, hinge v06|v07" in page.cells
    assert "0.0168379" in page.cells
    assert "lateral capacity NaN at 2 magnitudes" in text
