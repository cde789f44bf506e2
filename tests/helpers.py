"""Builders shared by the tests: a single block on a support (closed forms), two blocks side by side,
an arch centroid height, a one-point-load pattern, the planar and spatial limits of a scene, and a
headless Chromium driven by selenium."""

from __future__ import annotations

import shutil
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager

import numpy as np
import pytest

from tce.core.limit import LimitSolver
from tce.core.loads import LoadPattern, PointLoad
from tce.core.material import Material
from tce.core.model import build_model
from tce.structures.assembly import Assembly, Block, Interface
from tce.structures.geometry import box


def block_on_support(b: float = 0.4, h: float = 1.0, d: float = 0.3, unit_weight: float = 20.0) -> Assembly:
    """A b x d x h block (x, y, z) standing on a wider support slab: rocks at lambda = b/h."""
    base = Block("base", box([-b, -d, -0.2], [b, d, 0.0]), unit_weight, support=True)
    top = Block("block", box([-b / 2, -d / 2, 0.0], [b / 2, d / 2, h]), unit_weight)
    pts = np.array([[-b / 2, -d / 2, 0], [b / 2, -d / 2, 0], [b / 2, d / 2, 0], [-b / 2, d / 2, 0]])
    return Assembly((base, top), (Interface(0, 1, pts, [0, 0, 1]),))


def arch_centroid_height(assembly: Assembly) -> float:
    """Height of the voussoirs' centroid above the springings (m)."""
    free = list(assembly.free_indices)
    w = assembly.weights[free]
    return float((w * assembly.centroids[free, 2]).sum() / w.sum())


def limits(assembly: Assembly, material: Material, alpha: float = 0.0) -> dict[str, float]:
    """Direct lambda_max in the planar and the spatial model."""
    return {kind: LimitSolver(build_model(assembly, kind), material).solve(alpha).lambda_max for kind in ("planar", "spatial")}


def point(force, **kw) -> LoadPattern:
    """A pattern whose only live load is one point load (lateral pattern off)."""
    return LoadPattern(lateral=False, point=[PointLoad(force=force, **kw)])


def equal_blocks_side_by_side(b: float = 0.5, h: float = 1.0, d: float = 0.5) -> Assembly:
    """Two b x h blocks L (x in [0, b]) and R (x in [b, 2b]) on a support, in contact along x = b."""
    def itf(x0: float, x1: float, z0: float, z1: float, vertical: bool) -> np.ndarray:
        if vertical:
            return np.array([[x0, -d / 2, z0], [x0, d / 2, z0], [x0, d / 2, z1], [x0, -d / 2, z1]])
        return np.array([[x0, -d / 2, z0], [x1, -d / 2, z0], [x1, d / 2, z0], [x0, d / 2, z0]])

    base = Block("base", box([-1, -d / 2, -0.2], [3 * b, d / 2, 0.0]), 20.0, support=True)
    left = Block("L", box([0, -d / 2, 0], [b, d / 2, h]), 20.0)
    right = Block("R", box([b, -d / 2, 0], [2 * b, d / 2, h]), 20.0)
    return Assembly(
        (base, left, right),
        (Interface(0, 1, itf(0, b, 0, 0, False), [0, 0, 1]), Interface(0, 2, itf(b, 2 * b, 0, 0, False), [0, 0, 1]),
         Interface(1, 2, itf(b, b, 0, h, True), [1, 0, 0])),
    )


def extrados_midpoint(k: int, ri=1.0, t=0.2, n=14) -> list[float]:
    """Midpoint of the extrados chord of voussoir k (1-based) of a semicircular arch (m)."""
    th = np.pi * (1 - np.array([k - 1, k]) / n)
    return [(ri + t) * float(np.cos(th).mean()), 0.0, (ri + t) * float(np.sin(th).mean())]


BROWSER = shutil.which("chromium") or shutil.which("chromium-browser") or shutil.which("google-chrome")
DRIVER = shutil.which("chromedriver")
#: no network, no first-run or background traffic, software WebGL
CHROMIUM_FLAGS = ("--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                  "--disable-background-networking", "--disable-component-update", "--disable-sync",
                  "--enable-unsafe-swiftshader", "--window-size=1200,800")


@contextmanager
def chromium() -> Iterator[object]:
    """A selenium driver of Debian's headless chromium (browser console logged), with a
    throw-away profile; skips the test, with the reason, when selenium, chromium or
    chromedriver is missing (``.ci/run`` installs them)."""
    pytest.importorskip("selenium", reason="selenium is not installed (pip install -e '.[test]')")
    if BROWSER is None or DRIVER is None:
        pytest.skip("no chromium/chromedriver on PATH (apt-get install chromium chromium-driver)")
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    opts = webdriver.ChromeOptions()
    opts.binary_location = BROWSER
    profile = tempfile.mkdtemp(prefix="tce-chromium-")
    for flag in (*CHROMIUM_FLAGS, f"--user-data-dir={profile}"):
        opts.add_argument(flag)
    opts.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    driver = webdriver.Chrome(service=Service(DRIVER), options=opts)
    try:
        yield driver
    finally:
        driver.quit()
        shutil.rmtree(profile, ignore_errors=True)
