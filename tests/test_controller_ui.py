"""Module (c) panel, figures and exercises without a browser: the plotted data equal the model,
slider bounds cannot produce a loop the model rejects, checkers judge by simulating the answer."""
import itertools
from dataclasses import astuple

import numpy as np
import pytest
from matplotlib.figure import Figure

from afmsmiler import samples
from afmsmiler.controller import PRESETS, ContactLoop, scan_image
from afmsmiler.controller.defaults import SETPOINT, line_profile
from afmsmiler.exercises import controller as ex
from afmsmiler.plots import controller as plots
from afmsmiler.ui.controller import BOUNDS, DEFAULTS, ControllerPanel, preset_values


@pytest.fixture(scope="module")
def panel():
    return ControllerPanel()


def test_panel_plots_what_the_model_says(panel):
    panel.set(kp=2.0, ki=0.05, kd=0.01, speed=500.0, profile="step", setpoint=5.0, height=40.0)
    v = panel.values()
    loop = ContactLoop(m_c=v["m_c"] * 1e-12, m_s=v["m_s"] * 1e-12, b_c=v["b_c"] * 1e-6,
                       b_s=v["b_s"] * 1e-6, k_c=v["k_c"], k_s=v["k_s"], kp=2.0, ki=0.05e6,
                       kd=0.01e-6)
    line = samples.profile("step", 512, 4e-9, 40e-9)
    r = loop.scan_line(line.x, line.heights, 500e-6, 5e-9)
    lines = panel.figure.lines
    x, y = lines["znp_trace"].get_data()
    np.testing.assert_allclose(x, line.x * 1e6, rtol=1e-12)
    np.testing.assert_allclose(y, -r.trace.z_np * 1e9, rtol=1e-9)
    x, y = lines["topo_retrace"].get_data()
    np.testing.assert_allclose(x, line.x[::-1] * 1e6, rtol=1e-12)
    np.testing.assert_allclose(y, r.retrace.topography * 1e9, rtol=1e-9)
    np.testing.assert_allclose(lines["height"].get_data()[1], line.heights * 1e9)
    px, py = lines["poles"].get_data()
    np.testing.assert_allclose(np.sort_complex(px + 1j * np.asarray(py)),
                               np.sort_complex(loop.poles * 1e-6), rtol=1e-9)
    assert "STABLE" in panel.indicator.value
    np.testing.assert_allclose(astuple(panel.last.loop), astuple(loop), rtol=1e-12)


def test_preset_sets_every_slider_and_flags_instability(panel):
    panel.set(preset="d_unstable")
    assert panel.values()["kp"] == 100.0 and panel.values()["ki"] == pytest.approx(100.0)
    assert not panel.last.scan.stable
    assert "UNSTABLE" in panel.indicator.value
    assert "UNSTABLE" in panel.figure.axes["poles"].get_title()
    panel.set(preset="a_good_tracking")
    np.testing.assert_allclose(astuple(panel.last.loop), astuple(PRESETS["a_good_tracking"].loop),
                               rtol=1e-12)
    assert preset_values("b_soft_sample")["k_s"] == 1.0


def test_slider_bounds_lie_inside_the_model_ranges():
    corners = {k: v for k, v in BOUNDS.items()}
    for m_c, k_s, kp, ki, kd, speed in itertools.product(
            corners["m_c"], corners["k_s"], corners["kp"], corners["ki"], corners["kd"],
            corners["speed"]):
        loop = ContactLoop(m_c=m_c * 1e-12, m_s=1e-12, b_c=BOUNDS["b_c"][0] * 1e-6,
                           b_s=BOUNDS["b_s"][0] * 1e-6, k_c=BOUNDS["k_c"][0], k_s=k_s, kp=kp,
                           ki=ki * 1e6, kd=kd * 1e-6)
        loop.scan_line([0.0, 1e-9, 2e-9], [0.0, 1e-9, 0.0], speed * 1e-6, 0.0)
    for name, (low, high) in BOUNDS.items():
        assert low <= DEFAULTS[name] <= high, name


def test_unknown_control_is_rejected():
    with pytest.raises(TypeError, match="unknown control"):
        ControllerPanel(gain=3)


def test_figures_draw():
    for fig in (plots.fig4_figure(), plots.block_diagram(),
                plots.polygon_figure(line_profile().x, line_profile().heights, 1e-3)):
        assert isinstance(fig, Figure) and fig.axes
    img = samples.particles((16, 32), 4e-9, count=2)
    im = scan_image(PRESETS["c_fast_scan"].loop, img.heights, img.pixel_size, 1e-3, SETPOINT)
    fig = plots.image_figure(im, img.heights, signal="topography")
    np.testing.assert_allclose(fig.axes[1].images[0].get_array(), im.trace * 1e9)
    fig = plots.image_figure(im)
    loop = PRESETS["c_fast_scan"].loop
    flat = (loop.k_c + loop.k_s) * SETPOINT / loop.k_s  # Z_np on a flat sample, from the docs
    np.testing.assert_allclose(fig.axes[1].images[0].get_array(),
                               -(im.retrace_z_np - flat) * 1e9, rtol=1e-12)
    with pytest.raises(ValueError, match="signal must be one of"):
        plots.image_figure(im, signal="phase")


def test_off_scale_signals_are_masked_and_reported():
    p = PRESETS["d_unstable"]
    c = plots.scan_curves(p.scan(), p.loop)
    f = plots.ScanFigure(c)
    lo, hi = f.axes["znp"].get_ylim()
    y = np.asarray(f.lines["znp_retrace"].get_data()[1], dtype=float)
    assert np.all(np.isnan(y) | ((y > lo - (hi - lo)) & (y < hi + (hi - lo))))
    assert "off scale" in f.texts["znp"].get_text()
    assert hi - lo < 20 * np.ptp(c.height_nm)


# --- exercises ------------------------------------------------------------------------------------
def test_fast_scan_checker_simulates_the_answer():
    assert not ex.check_fast_scan(None, 1.0, 0.0)
    # the preset's own gains are too slow at 1000 um/s, preset (d)'s gains are unstable
    assert not ex.check_fast_scan(0.5, 1e4, 0.0, 1e-3)
    assert "unstable" in str(ex.check_fast_scan(100, 1e8, 0.0, 1e-3))
    assert not ex.check_fast_scan(30, 3e6, 1e-7, 1e-4)  # too slow a scan
    assert not ex.check_fast_scan(-1, 3e6, 1e-7, 1e-3)
    good = ex.check_fast_scan(30, 3e6, 1e-7, 1e-3)
    assert good
    # its verdict is the error of an independent evaluation of -Z_np against T
    loop = PRESETS["a_good_tracking"].loop.replace(kp=30, ki=3e6, kd=1e-7)
    line = line_profile("real line")
    r = loop.scan_line(line.x, line.heights, 1e-3, SETPOINT)
    shift = (loop.k_c + loop.k_s) * SETPOINT / loop.k_s  # steady Z_np for T = 0
    rms = max(np.sqrt(np.mean((-(p.z_np - shift) - p.height) ** 2)) for p in (r.trace, r.retrace))
    assert rms < 1e-9 and f"{rms * 1e9:.3g} nm" in str(good)


def test_critical_ki_is_the_hurwitz_condition():
    loop = PRESETS["d_unstable"].loop
    A = loop.m_c + loop.m_s
    B = loop.b_c + loop.b_s + loop.b_s * loop.kp
    K = loop.k_c + loop.k_s
    # B (K + b_s K_I + k_s K_P) = A k_s K_I, solved by hand for K_I
    ki_star = B * (K + loop.k_s * loop.kp) / (A * loop.k_s - B * loop.b_s)
    assert ex.critical_ki(100.0) == pytest.approx(ki_star, rel=1e-9)
    assert ex.check_critical_ki(ki_star * 1.005)
    assert not ex.check_critical_ki(1e8)
    assert not ex.check_critical_ki(None)
    assert not loop.replace(ki=ki_star * 1.01).is_stable()
    assert loop.replace(ki=ki_star * 0.99).is_stable()


# --- layout ---------------------------------------------------------------------------------------
def test_controls_and_indicator_share_a_row_above_the_figure():
    # In one column with the indicator under the sliders and the figure under that, the panel
    # was about 1300 px high in JupyterLab: no slider and the plots it moves on one screen.
    import ipywidgets as widgets

    from afmsmiler.ui.panel import arrange
    p = ControllerPanel()
    w = arrange(p.widget())
    row, figure = w.children
    assert isinstance(w, widgets.VBox) and isinstance(row, widgets.HBox)
    *columns, indicator = row.children
    assert indicator is p.indicator and len(columns) == 2
    shown = [c for col in columns for c in col.children]
    assert sorted(map(id, shown)) == sorted(map(id, p.controls.values()))  # each once, all there
    assert max(len(col.children) for col in columns) <= 7  # two short columns, not one of 14
    assert figure is not indicator and figure not in shown and p.indicator not in shown
    assert row.layout.flex_flow == "row wrap"  # a narrow notebook wraps, never squeezes
    assert all(col.layout.flex == "0 0 auto" for col in row.children)
    width_px = sum(int(c.layout.width.removesuffix("px")) for c in (columns[0].children[1],
                                                                      columns[1].children[1],
                                                                      indicator))
    assert width_px <= 1200
    fig_w, fig_h = p.fig.get_size_inches() * p.fig.dpi
    assert fig_w <= 1000 and fig_h <= 600


def _overlaps(fig):
    """Pairs of titles/axis labels of different axes whose boxes overlap once drawn."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    FigureCanvasAgg(fig).draw()
    r = fig.canvas.get_renderer()
    boxes = [(id(ax), t.get_text(), t.get_window_extent(r)) for ax in fig.axes
             for t in (ax.title, ax.xaxis.label, ax.yaxis.label) if t.get_text().strip()]
    return [(ta, tb) for i, (a, ta, ba) in enumerate(boxes) for b, tb, bb in boxes[i + 1:]
            if a != b and ba.overlaps(bb)]


def test_stand_alone_figures_fit_the_notebook_by_default():
    # 11-12.6 in wide figures were clipped on the right of JupyterLab's output area; the
    # notebook now calls the builders without a figure, so their defaults must fit (<= 10 in)
    # with no title or label running into another axes'.
    image = samples.particles((32, 32), pixel_size=32e-9)
    scan = scan_image(PRESETS["c_fast_scan"].loop, image.heights, image.pixel_size, speed=1e-3,
                      setpoint=10e-9)
    line = line_profile("real line")
    c = plots.scan_curves(PRESETS["a_good_tracking"].scan(), PRESETS["a_good_tracking"].loop)
    figs = dict(fig4=plots.fig4_figure(), block=plots.block_diagram(),
                image=plots.image_figure(scan, image.heights),
                image2=plots.image_figure(scan, signal="topography"),
                polygon=plots.polygon_figure(line.x, line.heights, speed=1e-3, n_show=14),
                scan=plots.ScanFigure(c).fig)
    for name, fig in figs.items():
        width, height = fig.get_size_inches()
        assert width <= 10.0 and height <= 9.0, (name, width, height)
        assert not _overlaps(fig), (name, _overlaps(fig))
