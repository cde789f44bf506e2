"""The interactive view in a real headless browser (Debian's chromium driven by selenium).

The test loads the HTML page written for a real load path, checks that the browser logged
no error, moves the load-multiplier slider with the keyboard and checks that the drawn
state changed, switches the scenario and the mechanism, and saves a screenshot under
``results/view/`` that must not be blank (pixel variance). It is skipped, with the reason,
only when no chromium or chromedriver can be found (``.ci/run`` installs them).
"""

from __future__ import annotations

from pathlib import Path

import pytest
import xarray as xr

from helpers import chromium
from tce.plot.view import view_html
from tce.study.runner import run_study
from tce.study.schema import parse_study

ROOT = Path(__file__).resolve().parents[2]
SHOT = ROOT / "results" / "view" / "view_screenshot.png"
STUDY = """
[study]
name = "browser"
[structure]
type = "semicircular_arch"
[material]
friction = 0.8
[loads]
alpha = 30.0
lambda_step = 0.05
tolerance = 1e-3
[scenarios.none]
[scenarios.transversal]
right = [0, 0.001, 0, 0, 0, 0]
"""


@pytest.fixture(scope="module")
def browser():
    with chromium() as driver:
        yield driver


def wait_for(driver, script: str, timeout: float = 30.0):
    """What ``script`` returns once it is true (selenium's wait on the page's own condition;
    ``timeout`` only bounds a page that never gets there)."""
    from selenium.common.exceptions import TimeoutException
    from selenium.webdriver.support.ui import WebDriverWait

    try:
        return WebDriverWait(driver, timeout).until(lambda d: d.execute_script(script))
    except TimeoutException:
        raise AssertionError(f"timed out waiting for: {script}") from None


def test_view_in_chromium(browser, tmp_path: Path) -> None:
    from PIL import Image, ImageStat
    from selenium.webdriver.common.by import By
    from selenium.webdriver.common.keys import Keys

    report = run_study(parse_study(STUDY, tmp_path / "b.toml"), tmp_path, jobs=1)
    ds = xr.load_dataset(report.results)
    page = tmp_path / "view.html"
    page.write_bytes(view_html(ds))
    browser.get(page.as_uri())
    wait_for(browser, "const p = document.getElementById('plot'); return p && p.data && p.data.length === 9 && "
                      "p.querySelector('canvas') !== null")
    wait_for(browser, "return document.getElementById('plot').data[2].x.length > 0")
    label = browser.find_element(By.ID, "lam").text
    assert "λmax" in label  # starts at the limit
    before = browser.execute_script("return document.getElementById('plot').data[2].x.slice(0, 6)")

    slider = browser.find_element(By.ID, "step")
    slider.send_keys(Keys.HOME)  # move the slider to lambda = 0
    wait_for(browser, "return document.getElementById('lam').textContent.startsWith('λ = 0.0000')")
    after = browser.execute_script("return document.getElementById('plot').data[2].x.slice(0, 6)")
    assert after != before  # the arrows were redrawn for the new state
    assert "not unique" in browser.find_element(By.ID, "note").text  # rigid, no support motion
    slider.send_keys(Keys.ARROW_RIGHT)
    wait_for(browser, "return document.getElementById('lam').textContent.startsWith('λ = 0.0500')")

    browser.execute_script("const s = document.getElementById('scenario'); s.value = '1'; "
                           "s.dispatchEvent(new Event('change'));")
    wait_for(browser, "return document.getElementById('lam').textContent.includes('λmax')")
    browser.find_element(By.ID, "mech").click()
    wait_for(browser, "return document.getElementById('plot').data[8].x.length > 0")  # hinge lines shown

    errors = [e for e in browser.get_log("browser") if e["level"] == "SEVERE"]
    assert not errors, errors
    SHOT.parent.mkdir(parents=True, exist_ok=True)
    assert browser.save_screenshot(str(SHOT))
    with Image.open(SHOT) as img:
        stat = ImageStat.Stat(img.convert("L"))
        assert img.size[0] >= 800 and stat.var[0] > 100.0  # not blank: blocks, arrows, controls
