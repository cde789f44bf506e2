"""The report of a geometry sweep describes each scenario with its own structure.

With ``[sweep] thickness = [0.2, 0.3, 0.4]`` the report used to draw and tabulate the first
structure only (thickness 0.2 m) and so described the 0.3 and 0.4 m scenarios with the
0.2 m ring. Here the Structure section must hold one table per structure, naming its
scenarios, its thickness and its own overall dimensions, and one drawing per structure.
"""

from __future__ import annotations

import re
from pathlib import Path

import matplotlib
import pytest
import xarray as xr

matplotlib.use("Agg")

from tce.plot.data import assembly  # noqa: E402
from tce.report import write_report  # noqa: E402
from tce.study import load_study  # noqa: E402
from tce.study.runner import run_study  # noqa: E402
from study.test_geometry_sweep import STUDY as GEOMETRY_SWEEP  # noqa: E402

STUDY = GEOMETRY_SWEEP.split("\n[plots]")[0]  # the thickness sweep of test_geometry_sweep, without its figures


@pytest.fixture(scope="module")
def report(tmp_path_factory: pytest.TempPathFactory) -> tuple[xr.Dataset, str]:
    d = tmp_path_factory.mktemp("sweep_report")
    path = d / "study.toml"
    path.write_text(STUDY)
    results = run_study(load_study(path), out=d / "results", jobs=1).results
    files = write_report(results, pdf=False, figures=[])
    page = files.html.read_text(encoding="utf-8")
    section = page[page.index('<h2 id="structure">'):page.index('<h2 id="material">')]
    return xr.load_dataset(results), section


def test_each_thickness_has_its_own_structure_table(report) -> None:
    ds, section = report
    tables = re.findall(r"<table.*?</table>", section, flags=re.S)
    assert len(tables) == 3
    names = [str(s) for s in ds["scenario"].values]
    for name, t, table in zip(names, ds["thickness"].values, tables):
        cells = [re.sub(r"<[^>]+>", "", c).strip() for c in re.findall(r"<t[dh]>(.*?)</t[dh]>", table, flags=re.S)]
        assert name in cells[cells.index("scenarios") + 1]
        assert cells[cells.index("thickness (swept)") + 1] == f"{float(t):g}"
        # the extent is that structure's own: the ring's outer radius 1 + t spans 2 (1 + t) in x
        dx = assembly(ds, name).extent[0]
        assert abs(dx - 2 * (1.0 + float(t))) < 1e-9
        assert cells[cells.index("overall dimensions") + 1].startswith(f"{dx:.4g} ×")


def test_each_structure_is_drawn(report) -> None:
    _, section = report
    assert section.count('alt="structure drawing') == 3
