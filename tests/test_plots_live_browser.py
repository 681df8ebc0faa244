"""The live figure's renderer (``afmsmiler/plots/static/live.js``) read back in a real browser.

Figures are drawn by the renderer in headless Chromium (Debian's ``/usr/bin/chromium``, driven by
Playwright) from :func:`afmsmiler.plots.live.static_html`, and their pixels are compared with what
matplotlib says should be there: a curve passes through its data points and not through its NaN
gap, an image pixel has matplotlib's colour-map colour for its value, an equal-aspect box has the
data's aspect, and a frame sent to a view is counted. Skipped, with the reason, without a browser.
"""
import os
import shutil

import matplotlib
import numpy as np
import pytest
from matplotlib.figure import Figure

from afmsmiler.plots.live import static_html

pytestmark = [pytest.mark.slow, pytest.mark.browser]  # its servers: one xdist group
# (conftest.BROWSER_GROUPS)
CHROMIUM = os.environ.get("AFMSMILER_CHROMIUM", "/usr/bin/chromium")
ARGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
        "--disable-background-networking", "--disable-component-update", "--disable-sync"]


@pytest.fixture(scope="module")
def page():
    if not shutil.which(CHROMIUM) and not os.path.exists(CHROMIUM):
        pytest.skip(f"no browser at {CHROMIUM} (make test installs Debian's chromium as root)")
    sync_api = pytest.importorskip("playwright.sync_api", reason="playwright is not installed")
    with sync_api.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=ARGS)
        try:
            pg = browser.new_page(viewport={"width": 900, "height": 700})
            errors = []
            pg.on("pageerror", lambda e: errors.append(str(e)))
            pg.errors = errors
            yield pg
        finally:
            browser.close()


def _show(page, fig):
    page.set_content(f"<html><body style='margin:0'>{static_html(fig)}</body></html>")
    page.wait_for_function("document.querySelector('.afm-live')?.dataset.frames === '1'",
                           timeout=10000)
    assert page.errors == []


def _pixel(page, axes, x, y, key="y"):
    """RGBA of the canvas pixel at data (x, y) of the ``axes``-th plot."""
    return page.evaluate("""([i, x, y, key]) => {
        const u = document.querySelector('.afm-live').afmFigure.axes[i].u;
        const px = Math.round(u.valToPos(x, 'x', true)), py = Math.round(u.valToPos(y, key, true));
        return Array.from(u.ctx.getImageData(px, py, 1, 1).data);
    }""", [axes, x, y, key])


def _blank(rgba):
    """Nothing drawn: the transparent canvas (the page shows through) or white."""
    return rgba[3] == 0 or min(rgba[:3]) > 240


def test_a_curve_passes_through_its_points_and_leaves_its_nan_gap_empty(page):
    fig = Figure(figsize=(5, 4))
    ax = fig.add_subplot()
    x = np.linspace(0.0, 1.0, 101)
    y = x.copy()
    y[(x > 0.6) & (x < 0.8)] = np.nan
    ax.plot(x, y, color="#ff0000", lw=3)
    ax.set(xlim=(0, 1), ylim=(0, 1))
    _show(page, fig)
    for v in (0.25, 0.5, 0.9):
        r, g, b, a = _pixel(page, 0, v, v)
        assert r > 200 and g < 80 and b < 80, (v, (r, g, b, a))  # on the red line
    assert _blank(_pixel(page, 0, 0.7, 0.7))  # the gap: no line drawn
    assert _blank(_pixel(page, 0, 0.25, 0.75))  # away from the line: background


def test_image_pixels_have_matplotlibs_colour_for_their_value(page):
    fig = Figure(figsize=(4, 4))
    ax = fig.add_subplot()
    z = np.array([[0.0, 1.0], [2.0, np.nan]])
    ax.imshow(z, origin="lower", extent=(0, 2, 0, 2), cmap="viridis", vmin=0, vmax=3)
    _show(page, fig)
    cmap = matplotlib.colormaps["viridis"]
    for (row, col), value in np.ndenumerate(z):
        rgba = _pixel(page, 0, col + 0.5, row + 0.5)  # origin lower: row 0 at the bottom
        if np.isnan(value):
            assert _blank(rgba)  # not scanned: not drawn
            continue
        expected = np.round(np.array(cmap(value / 3)[:3]) * 255)
        np.testing.assert_allclose(rgba[:3], expected, atol=3, err_msg=f"value {value}")


def test_equal_aspect_gives_the_plot_box_the_datas_aspect(page):
    fig = Figure(figsize=(8, 4))
    ax = fig.add_subplot()
    ax.plot([0, 3], [0, 1])
    ax.set(xlim=(0, 3), ylim=(0, 1))
    ax.set_aspect("equal")
    _show(page, fig)
    w, h = page.evaluate("""(() => {
        const u = document.querySelector('.afm-live').afmFigure.axes[0].u;
        return [u.bbox.width, u.bbox.height]; })()""")
    assert w / h == pytest.approx(3.0, rel=0.02)


def test_twin_axis_curves_use_their_own_scale(page):
    fig = Figure(figsize=(5, 4))
    ax = fig.add_subplot()
    ax.plot([0, 1], [0, 1], color="#0000ff", lw=3)
    ax.set(xlim=(0, 1), ylim=(0, 1))
    twin = ax.twinx()
    twin.plot([0, 1], [100, 0], color="#ff0000", lw=3)
    twin.set_ylim(0, 100)
    _show(page, fig)
    r, g, b, _ = _pixel(page, 0, 0.25, 75.0, key="y2")  # on the red line of the right axis
    assert r > 200 and b < 80
    r, g, b, _ = _pixel(page, 0, 0.25, 0.25)  # on the blue line of the left axis
    assert b > 200 and r < 80


def test_the_static_copy_draws_alone_and_steps_aside_for_a_live_figure(page):
    fig = Figure(figsize=(4, 3))
    fig.add_subplot().plot([0, 1], [0, 1])
    alone = f"<div class='jp-OutputArea'>{static_html(fig)}</div>"
    beside = (f"<div class='jp-OutputArea'><div class='afm-live' data-frames='1'></div>"
              f"{static_html(fig)}</div>")
    page.set_content(f"<html><body>{alone}{beside}</body></html>")
    page.wait_for_function("""Array.from(document.querySelectorAll('.afm-live-static')).every(
        (c) => c.style.display === 'none' || c.querySelector('canvas'))""", timeout=10000)
    shown = page.evaluate("""Array.from(document.querySelectorAll('.afm-live-static'))
        .map((c) => getComputedStyle(c).display !== 'none' && c.querySelectorAll('canvas').length)""")
    assert shown[0] >= 1 and shown[1] is False, shown


def test_a_log_axis_just_under_a_decade_draws_at_once_with_decade_labels(page):
    # uPlot's own log ticks looped for 34 s (then threw) on a lower limit just below 10^-3
    fig = Figure(figsize=(4, 3))
    ax = fig.add_subplot()
    ax.loglog([1, 10, 100], [0.001, 1, 100])
    ax.set(xlim=(1, 100), ylim=(0.000972, 108))
    _show(page, fig)  # within its 10 s timeout
    labels = page.evaluate("""(() => { const u = document.querySelector('.afm-live')
        .afmFigure.axes[0].u; return u.axes[1]._values.filter((v) => v); })()""")
    decades = [float(v) for v in labels]
    assert decades and all(np.isclose(np.log10(d), round(np.log10(d))) for d in decades)
    steps = np.diff(np.log10(decades))
    assert np.allclose(steps, steps[0])  # one decade step for all labels


def _tick_labels(page, axes, axis):
    return page.evaluate("""([i, k]) => document.querySelector('.afm-live').afmFigure.axes[i]
        .u.axes[k]._values.filter((v) => v)""", [axes, axis])


def test_tick_labels_are_plain_decimals_with_the_digits_of_their_step(page):
    fig = Figure(figsize=(5, 3))
    a, b = fig.subplots(1, 2)
    a.plot([0, 1], [0, 0])
    a.set(xlim=(-0.0006, 0.0006), ylim=(-4000, 4000))  # matplotlib: 0.0004 steps, no separators
    b.plot([0, 1], [0, 1])
    b.set(xlim=(0, 1), ylim=(-1e-3, 1e-3))
    _show(page, fig)
    x, y = _tick_labels(page, 0, 0), _tick_labels(page, 0, 1)
    assert "-0" not in x and "0" in x and len(set(x)) == len(x) > 1, x
    assert all("," not in t for t in y) and len(set(y)) == len(y) > 1, y
    values = [float(t) for t in x]
    assert max(values) <= 0.0006 and min(values) >= -0.0006


def test_every_principle_of_the_transducer_panel_draws(page):
    # the panel's states a student reaches with one drop-down: each draws, with no page error
    from afmsmiler.transducers import PRINCIPLES
    from afmsmiler.ui.transducers import TransducerPanel
    panel = TransducerPanel(scene=False)
    for principle in PRINCIPLES:
        panel.set(principle=principle)
        for length in (50.0, 500.0):  # the ends of the slider where the log axes change most
            try:
                panel.set(length=length)
            except (ValueError, TypeError):
                continue  # a principle without a length, or with another range
            _show(page, panel.fig)


def _ticks(page, axes, which):
    """The ``which``-th uPlot axis of the ``axes``-th plot: its tick values and their labels."""
    return page.evaluate("""([i, k]) => { const a = document.querySelector('.afm-live')
        .afmFigure.axes[i].u.axes[k]; return [a._splits, a._values]; }""", [axes, which])


def test_ticks_at_half_steps_read_as_many_digits_as_their_spacing_needs(page):
    # the renderer rounded 7.5 to "8" and 2.5 to "3" (the friction loop, E_dis, FM's shift)
    fig = Figure(figsize=(9, 2))  # a short plot: uPlot steps the y axes by 2.5 units
    left, mid, right = fig.subplots(1, 3)
    for ax, (lo, hi) in ((left, (0, 10)), (mid, (-10, 0)), (right, (0, 1e-3))):
        ax.plot([0, 1], [lo, hi])
        ax.set(xlim=(0, 1), ylim=(lo, hi))
    _show(page, fig)
    for i, (step, expected) in enumerate([(2.5, ["0", "2.5", "5", "7.5", "10"]),
                                          (2.5, ["-10", "-7.5", "-5", "-2.5", "0"]),
                                          (2.5e-4, ["0", "2.5e-4", "5e-4", "7.5e-4", "1e-3"])]):
        splits, labels = _ticks(page, i, 1)
        assert np.allclose(np.diff(splits), step), f"uPlot chose other ticks: {splits}"
        assert len(splits) == len(expected), splits
        # every label shown (the renderer thins crowded ones) is its tick written to the step
        shown = [(t, e) for t, e in zip(labels, expected) if t]
        assert len(shown) >= 3 and all(t == e for t, e in shown), labels


def test_a_colour_bar_is_a_bar_beside_the_plot_with_its_labels_next_to_it(page):
    # it was a 2 px hairline, its label 100 px away (the 06 height bar was nearly invisible)
    fig = Figure(figsize=(6, 4))
    ax = fig.add_subplot()
    im = ax.imshow(np.arange(4.0).reshape(2, 2), origin="lower", extent=(0, 2, 0, 2),
                   cmap="viridis", vmin=0, vmax=4)
    fig.colorbar(im, ax=ax, label="height [nm]")
    _show(page, fig)
    bar = page.evaluate("""(() => {
        const a = document.querySelector('.afm-live').afmFigure.axes[0], cb = a.cb;
        const r = devicePixelRatio, ax = cb.axes[1];
        const x = Math.round(cb.bbox.left + cb.bbox.width / 2);
        const top = (u) => u.root.getBoundingClientRect().top + u.bbox.top / r;
        return {width: cb.bbox.width / r, height: cb.bbox.height / r, plot: a.u.bbox.height / r,
                top: top(cb), plotTop: top(a.u), room: ax._size, label: ax.label,
                splits: ax._splits, labels: ax._values,
                colours: [1, 3].map((v) => Array.from(cb.ctx.getImageData(
                    x, Math.round(cb.valToPos(v, 'c', true)), 1, 1).data))};
    })()""")
    assert 12 <= bar["width"] <= 24, bar  # a bar, as matplotlib's (a twentieth of its height)
    assert bar["height"] == pytest.approx(bar["plot"], abs=2), bar  # as tall as the plot box
    assert bar["top"] == pytest.approx(bar["plotTop"], abs=2), bar  # and level with it
    assert bar["label"] == "height [nm]"
    # its label right after its tick labels (0 ... 4 need some 20 px), not 100 px away
    assert bar["room"] <= 40, bar
    shown = [(s, t) for s, t in zip(bar["splits"], bar["labels"]) if t]
    assert len(shown) >= 3 and all(float(t) == pytest.approx(s) for s, t in shown), shown
    cmap = matplotlib.colormaps["viridis"]
    for value, rgba in zip((1, 3), bar["colours"]):
        np.testing.assert_allclose(rgba[:3], np.round(np.array(cmap(value / 4)[:3]) * 255),
                                   atol=3, err_msg=f"the bar at {value}")


def test_a_log_axis_of_a_decade_or_two_reads_its_2_and_5_ticks(page):
    # the FM panel's 0.2 to 12 nm read "1" and "10" only: nothing below 1 nm was labelled
    fig = Figure(figsize=(8, 3))
    ax = fig.add_subplot()
    ax.semilogx([0.2, 12], [0, 1])
    ax.set(xlim=(0.2, 12), ylim=(0, 1))
    _show(page, fig)
    splits, labels = _ticks(page, 0, 0)
    shown = {t: s for s, t in zip(splits, labels) if t}
    assert ["0.2", "0.5", "1", "2", "5", "10"] == list(shown), labels
    assert all(float(t) == pytest.approx(s) for t, s in shown.items())


def test_a_status_line_that_comes_and_goes_does_not_move_the_plots(page):
    """A coarse answer's status (the suptitle) and a full answer's note (an axes title) come and
    go from frame to frame: once each was shown, their room is kept, so the plots stay where they
    are and the figure is not laid out again (before, every such frame was laid out and drawn
    twice, and the plots jumped)."""
    fig = Figure(figsize=(5, 4))
    top, bottom = fig.subplots(2, 1)
    top.plot([0, 1], [0, 1])
    bottom.plot([0, 1], [1, 0])
    fig.suptitle("coarse map: the full map follows")
    _show(page, fig)
    boxes = page.evaluate("""() => {
        const F = document.querySelector('.afm-live').afmFigure;
        const [layout, frame, buffer] = F.last;
        let resized = 0;
        const resize = F.resize.bind(F);
        F.resize = () => { resized += 1; resize(); };
        const tops = () => F.axes.map((a) => Math.round(a.u.over.getBoundingClientRect().top));
        const shown = [];
        const states = [["", "E_dis = 0 on both branches"], ["coarse map", ""],
                        ["", "E_dis = 0 on both branches"], ["coarse map", ""], ["", ""]];
        for (const [status, note] of states) {
            const f = JSON.parse(JSON.stringify(frame));
            f.suptitle = status;
            f.axes[1].title = {text: note, color: ""};
            F.draw(layout, f, buffer);
            shown.push({tops: tops(), resized});
        }
        return shown;
    }""")
    assert page.errors == []
    # the note's first showing makes room for it (one layout); from then on nothing moves, the
    # status line's room (shown in the first frame, before these) kept while it is empty
    assert boxes[0]["resized"] == 1, boxes
    assert all(b["resized"] == 1 for b in boxes), boxes
    assert all(b["tops"] == boxes[0]["tops"] for b in boxes), boxes
