"""The built book in a real browser: math typeset, every figure and 3D page drawn, no network.

The book is built once per session (module fixture) the way ``make book`` builds it, from a copy
of ``book/`` beside links to the rest of the checkout (a clean clone's layout): the pages of
:mod:`afmsmiler.ui.pages` into ``_static/panels``, the pinned MathJax into ``_extra/mathjax``
(``tools/vendor_mathjax.py``; its hash-checked tarball is cached in ``book/_vendor`` after the
first fetch), then ``jupyter-book build -W -n --keep-going``: a warning fails the build and the
test. Headless Debian Chromium (``tests/browser.py``, never Playwright's download) opens every
page from ``file://`` and checks that

* MathJax typeset every ``.math`` element (an ``mjx-container`` in each, no ``mjx-merror``);
* every embedded page (``<iframe>``: a panel's figure, a 3D view, an instrument) is drawn: in
  a figure's screenshot in place at least 1 % of the pixels differ from its background colour
  (a blank canvas gives 0, a figure with empty axes about 4 %), and its frame does not cut it
  off; a 3D view's own objects paint at least 1 % of its pixels (the view shot with them and
  with them hidden: its background is a gradient, so "not one colour" would say nothing);
* every request went to ``file:``/``data:``/``blob:`` or 127.0.0.1 and none failed (a MathJax
  component or font missing from the build would fail).

Cost, measured on the shared 2-core machine with other developers' work beside it (load
average about 12): the whole file took 57-91 s of wall time in four runs and about 22 s of CPU;
the build 17-30 s of it (about 13 s of CPU: the pages 6 s, jupyter-book 7 s), the chapter with
nine embedded pages (module (g)) 13 s. ``make test`` builds the book here rather than reusing
``book/_build`` (which may be stale or absent), on one worker beside the other tests; ``make
unit`` skips it (slow, browser).
"""
from __future__ import annotations

import importlib.util
import io
import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path
from urllib.parse import urlparse

import pytest

from afmsmiler.ui.registry import MODULES
from tests import browser as B

ROOT = Path(__file__).resolve().parents[1]
BUILD_TIMEOUT = 300  # s: a bound, not a speed check (the build takes ~10 s)
DRAW_TIMEOUT = 10.0  # s: a page not drawn by then fails (a wait, not a speed check)
LIT = 0.01  # share of a frame's pixels a drawn figure or 3D view paints, at least (blank: 0)

pytestmark = [pytest.mark.slow, pytest.mark.browser]  # one build: its tests share an xdist
# group (conftest.BROWSER_GROUPS)

CHAPTERS = [nb[: -len(".ipynb")] for nb, _ in MODULES.values()]
PAGES = ["intro", *CHAPTERS, "instructor_guide"]


def _vendor_mathjax():
    spec = importlib.util.spec_from_file_location("vendor_mathjax", ROOT / "tools" / "vendor_mathjax.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _unavailable() -> str | None:
    reason = B.unavailable()
    if reason:
        return reason
    if shutil.which("jupyter-book", path=str(B.BIN)) is None:
        return "jupyter-book is not installed (pip install -e '.[book]')"
    return None


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """The book built into a temporary folder; yields its html folder."""
    reason = _unavailable()
    if reason:
        pytest.skip(reason)
    tmp = tmp_path_factory.mktemp("book-build")
    for entry in ROOT.iterdir():  # a clean clone's layout: the chapters link ../notebooks etc.
        if entry.name not in ("book", ".git", ".venv"):
            (tmp / entry.name).symlink_to(entry)
    src = tmp / "book"
    shutil.copytree(ROOT / "book", src,
                    ignore=shutil.ignore_patterns("_build", "_static", "_extra", "_vendor"))
    start = time.monotonic()
    from afmsmiler.ui.pages import write_pages
    write_pages(src / "_static" / "panels")
    mathjax = _vendor_mathjax()
    try:
        mathjax.vendor(src / "_extra" / "mathjax")
    except SystemExit as err:  # no cached tarball and no network
        pytest.skip(f"MathJax could not be vendored: {err}")
    proc = subprocess.run([str(B.BIN / "jupyter-book"), "build", "-W", "-n", "--keep-going",
                           str(src)], capture_output=True, text=True, timeout=BUILD_TIMEOUT,
                          env={**os.environ, "PYTHONPATH": str(ROOT)})
    seconds = time.monotonic() - start
    print(f"\nbook built in {seconds:.1f} s (pages, MathJax, jupyter-book -W)", file=sys.stderr)
    assert proc.returncode == 0, f"make book's build failed (warnings are errors):\n" \
                                 f"{proc.stdout[-3000:]}\n{proc.stderr[-3000:]}"
    yield src / "_build" / "html"


@pytest.fixture(scope="module")
def page(built, chromium):
    """A page of the suite's Chromium (conftest.py) that records every request (HTTP and
    WebSocket, as tests/browser.py:watch_requests does) and every failure."""
    p = B.new_page(chromium)
    p.failed = []
    p.requests = B.watch_requests(p)
    p.on("requestfailed", lambda r: p.failed.append(f"{r.url}: {r.failure}"))
    yield p
    p.close()


def _offsite(urls) -> list[str]:
    """The URLs that left the machine: neither file/data/blob/about nor 127.0.0.1."""
    out = []
    for url in urls:
        u = urlparse(url)
        if u.scheme in ("file", "data", "blob", "about") or u.hostname == "127.0.0.1":
            continue
        out.append(url)
    return out


def _open(page, html: Path) -> None:
    page.goto(html.as_uri(), wait_until="load")
    if page.evaluate("() => document.querySelector('.math') !== null"):
        page.wait_for_function("() => window.MathJax && MathJax.startup && MathJax.startup.promise")
        page.evaluate("() => MathJax.startup.promise")  # resolves when the first typeset is done


def _figure_drawn(page, frame) -> float:
    """The share of a figure's pixels that are not its background, once it has drawn (bounded)."""
    deadline = time.monotonic() + DRAW_TIMEOUT
    while True:  # a figure draws on its first animation frames
        lit = _lit(frame.screenshot())
        if lit >= LIT or time.monotonic() > deadline:
            return lit
        page.wait_for_timeout(100)


def _scene_drawn(page, frame, content) -> float:
    """The share of a 3D view's pixels that its objects paint (the view with them minus without).

    The background of a meshcat view is a gradient, so "not the most common colour" says nothing
    there: the view is shot as drawn, then with every mesh, line and point set hidden and
    rendered again, and the pixels that differ are the scene's own. meshcat's own grid, axes,
    lights and background are not the scene's and stay as they are.
    """
    from PIL import Image, ImageChops
    content.evaluate("""() => { window.__afmOwn = (o) => {
        if (!(o.isMesh || o.isLine || o.isPoints)) return false;
        for (let p = o; p; p = p.parent)
          if (["Grid", "Axes", "Lights", "Background"].includes(p.name)) return false;
        return true; }; }""")
    count = content.evaluate("""() => { let n = 0;
        document.querySelector('.afm-scene').afmView.viewer.scene.traverse(o => {
          if (window.__afmOwn(o)) n += 1; });
        return n; }""")
    assert count > 0, "the 3D page's scene holds no object"
    deadline = time.monotonic() + DRAW_TIMEOUT
    while True:
        page.wait_for_timeout(150)  # meshcat paints on its next animation frames
        shown = frame.screenshot()
        content.evaluate("""() => { const v = document.querySelector('.afm-scene').afmView.viewer;
            window.__hidden = [];
            v.scene.traverse(o => { if (window.__afmOwn(o) && o.visible) {
              o.visible = false; window.__hidden.push(o); } });
            v.render(); }""")
        hidden = frame.screenshot()
        content.evaluate("""() => { for (const o of window.__hidden) o.visible = true;
            document.querySelector('.afm-scene').afmView.viewer.render(); }""")
        a, b = (Image.open(io.BytesIO(x)).convert("RGB") for x in (shown, hidden))
        diff = ImageChops.difference(a, b).convert("L").point(lambda v: 255 if v > 8 else 0)
        share = diff.histogram()[255] / (a.width * a.height)
        if share >= LIT or time.monotonic() > deadline:
            return share


def _lit(png: bytes) -> float:
    """The share of a screenshot's pixels that differ from its most common colour."""
    from PIL import Image
    im = Image.open(io.BytesIO(png)).convert("RGB")
    counts = im.getcolors(im.width * im.height)
    background = max(counts)[0]
    return 1 - background / (im.width * im.height)


def test_the_build_ships_mathjax_and_names_no_remote_script(built):
    assert (built / "mathjax" / "tex-mml-chtml.js").exists()
    for name in PAGES:
        text = (built / f"{name}.html").read_text(encoding="utf-8")
        assert not re.findall(r'<(?:script|link|iframe|img)[^>]+(?:src|href)="(?:https?:)?//', text), name
        if name in CHAPTERS:  # Sphinx loads MathJax on the pages with math
            assert 'src="_static/../mathjax/tex-mml-chtml.js' in text, name


@pytest.mark.parametrize("name", PAGES)
def test_a_page_typesets_its_math_and_draws_its_embedded_pages(page, built, name):
    page.requests.clear()
    page.failed.clear()
    _open(page, built / f"{name}.html")
    math = page.evaluate("""() => ({math: document.querySelectorAll('.math').length,
        typeset: document.querySelectorAll('.math mjx-container').length,
        errors: document.querySelectorAll('mjx-merror').length})""")
    assert math["typeset"] == math["math"] and math["errors"] == 0, math
    if name in CHAPTERS:
        assert math["math"] > 0, f"{name} has no math to check"
    frames = page.locator("iframe")
    srcs = [frames.nth(i).get_attribute("src") for i in range(frames.count())]
    drawn = {}
    for i, src in enumerate(srcs):
        frame = frames.nth(i)
        frame.scroll_into_view_if_needed()
        content = frame.element_handle().content_frame()
        content.wait_for_load_state("load")
        content.wait_for_function("() => document.querySelector('canvas') !== null")
        if content.evaluate("() => document.querySelector('.afm-scene') !== null"):  # a 3D page
            content.wait_for_function("() => !!document.querySelector('.afm-scene').afmView",
                                      timeout=DRAW_TIMEOUT * 1000)
            drawn[src] = _scene_drawn(page, frame, content)
        else:
            drawn[src] = _figure_drawn(page, frame)
            bottom = content.evaluate("""() => { const f = document.querySelector('.afm-live');
                return f ? f.getBoundingClientRect().bottom : 0; }""")
            assert bottom <= float(frame.get_attribute("height")) + 1, f"{src} is cut off"
    print(name, {s.rsplit("/", 1)[-1]: round(v, 3) for s, v in drawn.items()}, file=sys.stderr)
    blank = {s: round(v, 4) for s, v in drawn.items() if v < LIT}
    assert not blank, f"{name}: embedded pages drawn blank (share of lit pixels): {blank}"
    assert not page.failed, f"{name}: failed requests {page.failed}"
    assert not _offsite(page.requests), f"{name} asked the network for {_offsite(page.requests)}"


def test_every_chapter_embeds_what_was_built(built):
    """Each iframe of a chapter names a page the build holds (a stale name would show nothing)."""
    for name in CHAPTERS:
        text = (built / f"{name}.html").read_text(encoding="utf-8")
        for src in re.findall(r'<iframe src="([^"]+)"', text):
            assert (built / src).exists(), f"{name}.html embeds missing {src}"
