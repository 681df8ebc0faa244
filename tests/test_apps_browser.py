"""Every module as a web app: each notebook rendered by voila, as ``make apps`` serves them.

One voila server on 127.0.0.1 serves the notebooks' folder (its tree page is the index of the
modules, ``make apps``; ``make app NB=...`` serves one of them alone). Headless Debian Chromium
(``tests/browser.py``) opens the index and then each module's app, as a student with no Python
would (modules (e)-(h) here; (a)-(d) in tests/test_panels_browser.py): every cell runs at load
(notebook 08 starts its simulated devices), no code is shown, no cell shows an error, and a key press on the slider the registry names for the module
(``afmsmiler.ui.registry``) changes the pixels of its panel's figure (module (f)'s slider applies
to the next scan: its readout moves and the panel's figure is drawn); a panel's 3D view draws
over voila's own kernel connection (its pixels more than a few colours). Every request the pages
make, HTTP and WebSocket, goes to 127.0.0.1: an app needs no network beyond its own server.

The kernels run with ``AFMSMILER_TESTING=1`` (short animations): these tests check what the apps
show, never how long they take. Marked ``slow`` and ``browser``, all on one xdist worker with one
server (the xdist group conftest.BROWSER_GROUPS gives them); skipped, saying why, when Chromium or Playwright is missing.
"""
from pathlib import Path
from urllib.parse import urlsplit

import numpy as np
import pytest

from afmsmiler.ui.registry import MODULES
from tests import browser as B

pytestmark = [pytest.mark.slow, pytest.mark.browser]  # its xdist group: conftest.BROWSER_GROUPS

FIGURE = B.LIVE_FIGURE
SHOTS = Path(__file__).resolve().parents[1] / ".browser-shots"  # screenshots, for a person
#: The apps loaded here: modules (e)-(h). Modules (a)-(d)'s apps are loaded, their sliders
#: pressed and dragged and their requests checked by tests/test_panels_browser.py's voila
#: tests, on the same server command (tests/browser.py serves voila as afmsmiler.apps does).
APPS = [nb for letter, (nb, _) in MODULES.items() if letter in "efgh"]


def _entry(notebook: str):
    """The registry's panel of ``notebook`` whose slider redraws its figure at once (the first
    panel of the module when none does)."""
    entries = [e for e in B.PANELS.values() if e.notebook == notebook]
    return next((e for e in entries if e.figure), entries[0])


def _check_view_draws(page, notebook: str) -> None:
    """The app's first 3D view received its scene and shows more than a few colours."""
    page.wait_for_function(
        "(sel) => Array.from(document.querySelectorAll(sel))"
        ".some(e => Number(e.dataset.commands) > 0)", arg=B.SCENE_VIEW, timeout=120_000)
    image = B.scene_pixels(page, 0)
    SHOTS.mkdir(exist_ok=True)
    image.save(SHOTS / f"{notebook[:2]}_voila.png")
    colours = len(np.unique(np.asarray(image.resize((240, 120))).reshape(-1, 3), axis=0))
    assert colours > 50, f"{notebook}: the 3D view in voila is nearly uniform ({colours} colours)"


@pytest.fixture(scope="module")
def apps(chromium, root):
    """The voila server of ``make apps`` and a page that logs every address it asks for."""
    server = B.Server("voila", root, short=True).start()
    page = B.new_page(chromium)
    asked = B.watch_requests(page)
    try:
        yield server, page, asked
    finally:
        page.close()
        server.stop()


def test_the_index_lists_every_module(apps):
    server, page, asked = apps
    page.goto(f"{server.base}/?token={B.TOKEN}", wait_until="domcontentloaded")
    names = [nb for nb, _ in MODULES.values()]
    links = page.locator("a[href*='voila/render/']")
    links.first.wait_for(timeout=60_000)
    hrefs = links.evaluate_all("els => els.map(e => e.getAttribute('href'))")
    for name in names:
        assert any(urlsplit(h).path.endswith(f"voila/render/{name}") for h in hrefs), \
            f"the index has no link to {name}: {hrefs}"
    assert B.foreign(asked) == [], "the index asked for addresses beyond 127.0.0.1"


@pytest.mark.parametrize("notebook", APPS)
def test_each_app_loads_and_its_slider_moves_the_figure(apps, notebook):
    server, page, asked = apps
    e = _entry(notebook)
    start = len(asked)
    try:
        B.open_voila(page, server, notebook, e.slider_selector, timeout=300)
        # voila sends the page once every cell has run: the panels are all there, no code shown
        assert B.voila_errors(page) == [], f"{notebook} shows errors in voila"
        assert page.locator(".jp-CodeCell .jp-InputArea, .cm-editor, .CodeMirror").count() == 0, \
            f"{notebook}: the app shows code"
        slider = B.find_control(page, e)
        selector = f"{e.selector} {FIGURE}"
        B.focus_panel(page, slider, selector)
        state = B.figure_state(page, selector)
        assert state["figures"] >= 1 and state["lit"] > 0, (notebook, state)
        if e.scene:  # its 3D view draws over voila's own kernel connection (no second port)
            _check_view_draws(page, notebook)
        key, _ = B.keys(slider)
        before = B.slider_value(slider)
        if e.figure:
            times = B.press(page, slider, key, 1, selector=selector)
            assert times[0] is not None, \
                f"{notebook}: {e.slider} changed no pixel of {e.cls}'s figure"
        else:
            slider.press(key)
        assert B.slider_value(slider) != before, f"{notebook}: {key} did not move {e.slider}"
        page.wait_for_timeout(300)  # an error from the kernel's update reaches the page
        assert B.voila_errors(page) == [], f"{notebook} shows errors after {e.slider} moved"
        assert B.foreign(asked[start:]) == [], f"{notebook} asked for addresses beyond 127.0.0.1"
    finally:
        page.goto("about:blank")  # voila shuts the kernel down when its page goes
