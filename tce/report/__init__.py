"""The calculation report of a study: one self-contained HTML file and a PDF printed from it.

:func:`write_report` gathers what the report says (:func:`tce.report.content.report_content`),
embeds the structure drawing and the study's figures as ``data:`` URIs (the page opens
offline) and renders ``templates/report.html.j2``. Headless Chromium prints the PDF
(:func:`print_pdf`); without one the PDF is skipped, with the reason.
"""

from __future__ import annotations

import base64
import contextlib
import io
import logging
import os
import shutil
import signal
import subprocess
import tempfile
from dataclasses import dataclass
from pathlib import Path

import xarray as xr

from ..files import atomic_write
from ..plot.data import UNCERTAINTY_KINDS  # shown in the report's Uncertainty section

__all__ = ["ReportFiles", "find_browser", "print_pdf", "report_html", "write_report"]

log = logging.getLogger(__name__)

#: figure kinds -> (title, caption) in the report
CAPTIONS = {
    "states": ("Force states", "The blocks at the drawn load multipliers, with each interface's resultant at its "
               "pressure point, the torques about the interface normals and the applied loads; one panel per "
               "scenario and step."),
    "thrust": ("Support reactions against λ", "The components of the support reactions along the load path of "
               "every drawn scenario, λmax marked."),
    "thrust_lines": ("Lines of thrust", "The pressure points of the interfaces joined along the arch (the line of "
                     "thrust) at the drawn multipliers."),
    "mechanism": ("Collapse mechanisms", "The blocks displaced by the collapse mechanism at λmax (hinges and "
                  "sliding interfaces marked), beside the undeformed outline."),
    "summary": ("λmax against the swept parameters", "λmax of every scenario against the swept coordinates."),
    "capacity": ("Influence line", "λmax against the position of the moving load, the critical position marked."),
    "bracket": ("Associative and non-associative λ", "The bracket of the non-associative friction law."),
    "base": ("Support reactions at the base", "The reactions and pressure points at the supports."),
    "transversal": ("Transversal shift of the pressure points", "End and plan views of the interfaces with the "
                    "resultant's position across the depth."),
    "fragility": ("Probability of collapse (fragility)", "P(capacity < x) against the intensity x for each scenario, "
                  "with its band; the threshold marked with the failure probability there and its interval; with a "
                  "sweep, the failure probability against the swept parameter."),
    "capacity_samples": ("Sampled capacities", "The histogram of each scenario's finite sampled capacities; the "
                         "samples without one (unbounded: +inf, infeasible: −inf, numerical: NaN) counted in the "
                         "legend."),
    "sensitivity": ("Sensitivity of the capacity", "The sensitivity of the capacity to each random variable (the "
                    "method in the title), and FORM's importance factors where computed."),
    "convergence": ("Failure probability against the number of samples", "The estimate from the first n samples "
                    "with its interval; FORM and subset simulation estimates as horizontal lines where computed."),
}
#: command-line flags of headless Chromium for printing (no network, no profile left behind)
CHROMIUM_FLAGS = ("--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking",
                  "--disable-component-update", "--disable-sync", "--no-pdf-header-footer")
PRINT_TIMEOUT = 180.0  # s


@dataclass(frozen=True)
class ReportFiles:
    """What :func:`write_report` wrote: the HTML, the PDF (None when skipped) and why it was skipped."""

    html: Path
    pdf: Path | None
    skipped: str = ""


def _data_uri(png: bytes) -> str:
    return "data:image/png;base64," + base64.b64encode(png).decode("ascii")


def _figure_png(fig) -> bytes:
    """``fig`` as the bytes of a PNG image at 110 dots per inch (matplotlib's ``savefig``)."""
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110)
    return buf.getvalue()


def _kind(path: Path) -> str:
    stem = path.stem
    for kind in sorted(CAPTIONS, key=len, reverse=True):
        if stem == kind or stem.startswith(kind + "_"):
            return kind
    return stem


def _figures(paths: list[Path]) -> list[dict[str, str]]:
    out = []
    for p in paths:
        title, caption = CAPTIONS.get(_kind(p), (p.stem, ""))
        suffix = p.stem[len(_kind(p)):].lstrip("_")
        out.append({"title": f"{title}{f' ({suffix})' if suffix else ''}", "caption": f"{caption} File {p.name}.",
                    "uri": _data_uri(p.read_bytes())})
    return out


def study_figures(ds: xr.Dataset, folder: Path, scratch: Path) -> list[Path]:
    """The PNG figures of the study's ``[plots]``: those in ``folder`` (written by ``tce run``),
    the missing ones drawn into ``scratch``."""
    from ..plot.data import plot_spec
    from ..plot.output import figure_tasks, write_figures

    spec = plot_spec(ds)
    names = [t.name for t in figure_tasks(ds, spec) if t.name.endswith(".png")]
    if all((folder / n).is_file() for n in names):
        return [folder / n for n in names]
    kinds = tuple(k for k in spec.kinds if k != "view")
    drawn = write_figures(ds, scratch, type(spec)(steps=spec.steps, scenarios=spec.scenarios, kinds=kinds))
    return [p for p in drawn if p.suffix == ".png"]


def report_html(ds: xr.Dataset, results: Path, figures: list[Path]) -> str:
    """The report page of ``ds`` (read from ``results``) with ``figures`` (PNG files) embedded."""
    import jinja2

    from .content import report_content
    from .drawing import structure_figure

    content = report_content(ds, results)
    for geometry in content.structure["geometries"]:
        geometry["drawing"] = _data_uri(_figure_png(structure_figure(geometry.pop("assembly"))))
    content.figures = _figures([p for p in figures if _kind(p) not in UNCERTAINTY_KINDS])
    if content.uncertainty:
        content.uncertainty["figures"] = _figures([p for p in figures if _kind(p) in UNCERTAINTY_KINDS])
    env = jinja2.Environment(loader=jinja2.PackageLoader("tce.report", "templates"),
                             autoescape=jinja2.select_autoescape(["html", "j2"]), undefined=jinja2.StrictUndefined)
    return env.get_template("report.html.j2").render(c=content)


def find_browser() -> str | None:
    """The Chromium that prints the PDF (``TCE_CHROMIUM`` or ``chromium`` on the PATH), or None."""
    return os.environ.get("TCE_CHROMIUM") or shutil.which("chromium") or shutil.which("chromium-browser")


def print_pdf(html: Path, pdf: Path, browser: str | None = None) -> str:
    """Print ``html`` to ``pdf`` with headless Chromium (atomically); return "" on success or
    the reason it was skipped (no browser, the browser failed or timed out).

    Chromium runs in a session of its own, and every process of that session (its helpers,
    which may outlive the main one) is ended before this returns."""
    browser = browser or find_browser()
    if browser is None:
        return "no chromium found (apt-get install chromium, or set TCE_CHROMIUM)"
    try:
        with atomic_write(pdf) as tmp, tempfile.TemporaryDirectory(prefix="tce-chromium-") as profile:
            cmd = [browser, *CHROMIUM_FLAGS, f"--user-data-dir={profile}", f"--print-to-pdf={tmp}",
                   html.resolve().as_uri()]
            with subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                                  start_new_session=True) as chromium:
                try:
                    _, err = chromium.communicate(timeout=PRINT_TIMEOUT)
                finally:
                    with contextlib.suppress(ProcessLookupError, PermissionError):
                        os.killpg(chromium.pid, signal.SIGKILL)
            if chromium.returncode != 0 or not tmp.is_file() or tmp.stat().st_size == 0:
                raise ChildProcessError(f"exit {chromium.returncode}: {err.strip()[-300:]}")
    except (OSError, subprocess.TimeoutExpired) as exc:  # ChildProcessError is an OSError
        return f"chromium failed: {exc}"
    return ""


def write_report(results: Path, out: Path | None = None, figures: list[Path] | None = None,
                 pdf: bool = True) -> ReportFiles:
    """Write ``report.html`` (and ``report.pdf``) of a results file.

    Parameters
    ----------
    results : Path
        A study's ``results.nc``.
    out : Path, optional
        Folder of the report (default: beside ``results``).
    figures : list of Path, optional
        The figures to embed (default: :func:`study_figures`).
    pdf : bool
        Print the PDF as well.
    """
    results = Path(results)
    out = Path(out) if out is not None else results.parent
    out.mkdir(parents=True, exist_ok=True)
    ds = xr.load_dataset(results)
    with tempfile.TemporaryDirectory(prefix="tce-report-") as scratch:
        pngs = [p for p in figures if p.suffix == ".png" and p.is_file()] if figures is not None else \
            study_figures(ds, results.parent, Path(scratch))
        page = report_html(ds, results, pngs)
    html = out / "report.html"
    with atomic_write(html) as tmp:
        tmp.write_text(page, encoding="utf-8")
    if not pdf:
        return ReportFiles(html, None, "not asked for")
    why = print_pdf(html, out / "report.pdf")
    if why:
        log.warning("report PDF skipped: %s; the HTML report is %s", why, html)
        return ReportFiles(html, None, why)
    return ReportFiles(html, out / "report.pdf")
