"""Builders shared by the tests: a single block on a support (closed forms), arch centroid height,
a headless Chromium driven by selenium."""

from __future__ import annotations

import shutil
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager

import numpy as np
import pytest

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
