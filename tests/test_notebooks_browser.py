"""Notebooks 05-08 in a real browser: the 3D views survive Run All and every re-run.

Headless Debian Chromium driven by Playwright (``tests/browser.py``) against JupyterLab serving
copies of the course notebooks. For each notebook, as a student would: Run All; every 3D view
draws its own scene (their pixels differ from each other's, and each is more than meshcat's empty
grid); a panel's slider moves its figure *and* its 3D view; every code cell is run again, last
first (each after the cells below it: out of order, as a student who goes back does), with no
error shown; the kernel has started no process and listens on
no port but its own connection's. In voila the 3D views draw too (no second port exists that a
remote browser could not reach): tests/test_apps_browser.py checks it in each app.

The kernels run with ``AFMSMILER_TESTING=1`` (short animations): these tests check what the
cells show and that they can be re-run, never how long anything takes. Marked ``slow`` and
``browser``; skipped, saying why, when Chromium or Playwright is missing.
"""
import itertools
from pathlib import Path

import numpy as np
import pytest

from tests import browser as B

pytestmark = [pytest.mark.slow, pytest.mark.browser]  # not grouped: 08 alone takes minutes, so
# each xdist worker may start its own server for the notebooks it runs

SHOTS = Path(__file__).resolve().parents[1] / ".browser-shots"  # screenshots, for a person to see

#: notebook -> 3D views after Run All. Every panel the registry lists in a notebook is moved by
#: its slider (registry.PanelEntry.slider): its figure changes unless its slider applies to the
#: next scan, and exactly its own 3D view updates (none for a panel without one).
NOTEBOOKS = {"08_hardware_interaction.ipynb": 2, "07_imaging_modalities.ipynb": 4,
             "06_virtual_imaging.ipynb": 1, "05_system_overview.ipynb": 1}  # the longest first


#: The kernel's child processes and the ports it listens on (its own connection's, at first).
PORTS = """
import psutil
me = psutil.Process()
print(len(me.children(recursive=True)),
      sorted(c.laddr.port for c in me.net_connections('inet') if c.status == psutil.CONN_LISTEN))
"""


#: Each panel's box: whether its content is painted (``content-visibility: auto``, live.css,
#: skips a box out of view) and how far it lies from the viewport, in viewport heights.
PAINTED = """() => Array.from(document.querySelectorAll('.afm-panel')).map(p => {
  const r = p.getBoundingClientRect(), h = window.innerHeight;
  return {painted: p.firstElementChild.checkVisibility({contentVisibilityAuto: true}),
          away: r.top > h ? (r.top - h) / h : (r.bottom < 0 ? -r.bottom / h : 0)};
})"""


@pytest.fixture(scope="module")
def lab(chromium, root):
    server = B.Server("lab", root, short=True).start()
    page = B.new_page(chromium)
    try:
        yield server, page
    finally:
        page.close()
        server.stop()


def _distinct(images) -> None:
    """Each view's pixels differ from every other's, and each shows more than a few colours."""
    arrays = [np.asarray(im.resize((480, 240)), dtype=float) for im in images]
    for i, a in enumerate(arrays):
        colours = len(set(map(tuple, a.reshape(-1, 3).astype(int).tolist())))
        assert colours > 50, f"3D view {i} is nearly uniform ({colours} colours)"
    for (i, a), (j, b) in itertools.combinations(enumerate(arrays), 2):
        # the same instrument may frame two modes: at least 1 % of the pixels must differ clearly
        differ = np.mean(np.max(np.abs(a - b), axis=2) > 32)
        assert differ > 0.01, f"3D views {i} and {j} show the same pixels ({differ:.2%} differ)"


@pytest.mark.parametrize("notebook", list(NOTEBOOKS))
def test_views_survive_run_all_and_every_rerun(lab, notebook):
    server, page = lab
    n_views = NOTEBOOKS[notebook]
    entries = [e for e in B.PANELS.values() if e.notebook == notebook]
    B.open_lab(page, server, notebook, timeout=120)
    fresh = B.kernel_eval(page, PORTS).strip()
    B.run_all(page, timeout=600)
    assert B.lab_errors(page) == []
    views = B.scene_views(page)
    assert len(views) == n_views, views
    assert all(v["commands"] > 0 and v["canvases"] >= 1 and v["width"] > 0 for v in views), views
    SHOTS.mkdir(exist_ok=True)
    shots = [B.scene_pixels(page, i) for i in range(n_views)]
    for i, im in enumerate(shots):
        im.save(SHOTS / f"{notebook[:2]}_view{i}.png")
    _distinct(shots)

    # a panel out of view is not painted (its canvases and slider handles, composited layers,
    # cost the page's every rendering update 10-15 ms in notebook 07), one in view is
    page.wait_for_timeout(300)  # skipped or not from the next rendering update on
    boxes = page.evaluate(PAINTED)
    assert len(boxes) >= len(entries), boxes
    assert all(b["painted"] for b in boxes if b["away"] == 0), boxes
    assert not any(b["painted"] for b in boxes if b["away"] > 1), boxes

    # each panel's slider moves its figure and its own 3D view, and the kernel holds its value
    for e in entries:
        slider = B.find_control(page, e)
        B.focus_panel(page, slider, f"{e.selector} {B.LIVE_FIGURE}")
        key, _ = B.keys(slider)
        before = B.scene_views(page)
        if e.figure:
            times = B.press(page, slider, key, 1, selector=f"{e.selector} {B.LIVE_FIGURE}",
                            timeout=15.0)
            assert times[0] is not None, f"{e.key}: the figure did not change"
        else:
            slider.press(key)
        B.wait_idle(page)
        # a view applies its commands after the page's next paint: on a loaded machine that
        # comes late, so wait for it (bounded), then a little more for a view that should not move
        for _ in range(50):
            page.wait_for_timeout(200)
            after = B.scene_views(page)
            moved = [a["applied"] > b["applied"] for a, b in zip(after, before)]
            if sum(moved) >= int(e.scene):
                break
        page.wait_for_timeout(300)
        after = B.scene_views(page)
        moved = [a["applied"] > b["applied"] for a, b in zip(after, before)]
        assert sum(moved) == int(e.scene), f"{e.key}: views updated {moved}"
        held = float(B.kernel_eval(page, f"print({e.variable}.values()[{e.slider!r}])"))
        assert held == pytest.approx(float(B.slider_value(slider).replace("\u2212", "-")),
                                     rel=1e-3, abs=1e-3), f"{e.key}: the kernel holds {held}"
        assert B.lab_errors(page) == [], f"{e.key}: an error after its slider moved"

    # every cell again, last first (out of order; Run All ran them in order): no error, the views
    # still there
    cells = B.code_cells(page)
    for index in cells[::-1]:
        B.run_cell(page, index, timeout=300)
        assert B.lab_errors(page) == [], f"cell {index} of {notebook}"
    views = B.scene_views(page)
    assert len(views) == n_views and all(v["commands"] > 0 for v in views), views
    _distinct([B.scene_pixels(page, i) for i in range(n_views)])
    assert B.kernel_eval(page, PORTS).strip() == fresh, "the notebook started a process or a port"


def test_run_all_stops_at_an_error_at_once_and_names_it(lab):
    """A cell that raises stops Run All (the cells after it never run): the helper says so at
    once with the error, where it once waited out its whole timeout (10 min in CI)."""
    import nbformat
    server, page = lab
    name = "raises.ipynb"
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell("x = 1"),
                                         nbformat.v4.new_code_cell("1 / 0"),
                                         nbformat.v4.new_code_cell("y = 2")],
                                  metadata={"kernelspec": {"name": "python3",
                                                           "display_name": "Python 3",
                                                           "language": "python"}})
    nbformat.write(nb, server.root / "notebooks" / name)
    B.open_lab(page, server, name, timeout=120)
    with pytest.raises(AssertionError, match="ZeroDivisionError"):
        B.run_all(page, timeout=120)
