"""A small build's replay page in a real browser: Debian's chromium, headless, driven by
Playwright (its Python package alone: the browser is the system's, nothing is downloaded).
It loads from disk with no console error, its canvas draws, and the slider moves the arms:
two frames' screenshots differ where the arms are and match where nothing moved.

Skipped where chromium or Playwright is missing, except in CI (CI=true), which installs both
(.ci/run) and where their absence fails the test."""

import io
import os
import shutil
import time

import numpy as np
import pytest

import pyramid_sim
from pyramid_sim.cli import main

pytestmark = pytest.mark.physics

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
# A software WebGL (SwiftShader) where there is no GPU, as on a headless server.
FLAGS = ["--enable-unsafe-swiftshader", "--use-angle=swiftshader", "--no-sandbox"]
VIEW = {"width": 960, "height": 600}
NEAR = 60  # px around a moving body's place on the canvas that may change


def _playwright():
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        return None
    return sync_playwright


@pytest.fixture(scope="module")
def browser(tmp_path_factory):
    sync_playwright = _playwright()
    missing = [w for w, ok in (("chromium", CHROMIUM), ("playwright", sync_playwright)) if not ok]
    if missing:
        why = f"{' and '.join(missing)} not installed (apt-get install chromium; pip install playwright)"
        if os.environ.get("CI") == "true":
            pytest.fail(f"CI must test the replay page in a browser: {why}")
        pytest.skip(why)
    with sync_playwright() as p:
        home = tmp_path_factory.mktemp("chromium-home")  # its crash reports and caches go here
        env = {
            **os.environ,
            "HOME": str(home),
            "XDG_CONFIG_HOME": str(home / "config"),
            "XDG_CACHE_HOME": str(home / "cache"),
        }
        browser = p.chromium.launch(executable_path=CHROMIUM, args=FLAGS, env=env)
        yield browser
        browser.close()


@pytest.fixture(scope="module")
def page_file(tmp_path_factory):
    folder = tmp_path_factory.mktemp("replay-browser")
    pyramid_sim.build("pyramid-even", layers=1, out=folder / "run")
    assert main(["replay", str(folder / "run"), "--html", str(folder / "replay.html")]) == 0
    return folder / "replay.html"


def _canvas(page) -> np.ndarray:
    from PIL import Image

    png = page.locator("canvas").screenshot()
    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB")).astype(int)


def _drawn(page):
    page.evaluate("() => new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)))")


def test_the_page_loads_draws_and_its_slider_moves_the_arms(browser, page_file, tmp_path):
    page = browser.new_page(viewport=VIEW)
    said = []
    page.on("console", lambda m: said.append(f"{m.type}: {m.text}"))
    page.on("pageerror", lambda e: said.append(f"pageerror: {e}"))
    page.on(
        "request", lambda r: said.append(f"request: {r.url}") if r.url.startswith("http") else 0
    )
    start = time.perf_counter()
    page.goto(page_file.as_uri())
    page.wait_for_function("window.replay && window.replay.ready", timeout=60_000)
    loaded = time.perf_counter() - start
    _drawn(page)
    first = _canvas(page)
    assert first.std() > 20 and len(np.unique(first.reshape(-1, 3), axis=0)) > 200  # not blank

    frames = page.evaluate("window.replay.frames")
    bodies = ["left/panda_hand", "right/panda_hand", "left/panda_link4", "right/panda_link4"]
    before = {b: page.evaluate(f"window.replay.onCanvas('{b}')") for b in bodies}
    page.locator("#slider").fill(str(frames // 2))  # as a user drags it: an input event
    _drawn(page)
    assert page.evaluate("window.replay.frame") == frames // 2
    second = _canvas(page)
    after = {b: page.evaluate(f"window.replay.onCanvas('{b}')") for b in bodies}
    _save(tmp_path, first, second)

    changed = np.abs(first - second).sum(axis=2) > 30
    h, w = changed.shape
    ys, xs = np.mgrid[0:h, 0:w]
    near = np.zeros_like(changed)
    for b in bodies:
        for x, y in (before[b], after[b]):
            box = (abs(xs - x) < NEAR) & (abs(ys - y) < NEAR)
            near |= box
            assert changed[box].mean() > 0.02, f"nothing changed around {b} at ({x:.0f}, {y:.0f})"
    top = changed[: h // 8]  # the back wall above the arms: nothing there moves
    assert top.mean() == 0, f"{top.mean():.1%} of the wall's strip changed"
    assert said == [], said
    assert loaded < 30, f"loaded in {loaded:.1f} s"
    page.close()


def _save(folder, *images) -> None:
    """The screenshots, for a person to look at (pytest's tmp folder, kept a few runs)."""
    from PIL import Image

    for i, image in enumerate(images):
        Image.fromarray(image.astype(np.uint8)).save(folder / f"replay_{i}.png")
