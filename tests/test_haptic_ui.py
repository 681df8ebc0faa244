"""The haptic panels without a browser: figure data against closed forms, one model run per
action, the device following the sliders, the bridge's status after a run."""
import math
import sys

import numpy as np
import pytest

from afmsmiler.hardware import open_twin
from afmsmiler.hardware.haptic import HapticDevice, HapticTwin, Param
from afmsmiler.modes import qcontrol
from afmsmiler.ui import haptic as ui
from afmsmiler.ui.haptic import BridgePanel, QControlPanel


@pytest.fixture
def runs(monkeypatch):
    """Count the model calls the panel makes (closed form, ring-down, source builds)."""
    calls = {"response": 0, "ring": 0}
    for name, key in (("closed_loop_response", "response"), ("ring_down", "ring")):
        real = getattr(ui, name)

        def counting(*a, _real=real, _key=key, **k):
            calls[_key] += 1
            return _real(*a, **k)

        monkeypatch.setattr(ui, name, counting)
    return calls


def test_resonance_curve_is_the_closed_form_in_the_units_shown():
    panel = QControlPanel(quality_factor=100.0)
    panel.set(gain=0.01, phase=60.0)
    f_rel, amp = panel.figure.lines["controlled"].get_data()
    g, phi, q = 0.01, math.radians(60.0), 100.0
    w = np.asarray(f_rel)
    # the steady state of m z'' + c z' + k z = F + g k [cos(phi) z - sin(phi) z'/w0], by hand
    expected = 1.0 / np.abs(1 - g * math.cos(phi) - w ** 2 + 1j * w * (1 / q + g * math.sin(phi)))
    np.testing.assert_allclose(amp, expected, rtol=1e-12)
    free = panel.figure.lines["free"].get_data()[1]
    np.testing.assert_allclose(free, 1 / np.abs(1 - w ** 2 + 1j * w / q), rtol=1e-12)
    assert "Q_eff = " in panel.readout.value


def test_drawn_ring_down_decays_with_the_readout_q():
    panel = QControlPanel(quality_factor=400.0)
    panel.set(gain=0.0075)  # Q_eff = 1 / (1/400 + 0.0075) = 100
    t, z = panel.figure.lines["ring"].get_data()
    q = qcontrol.quality_factor_from_ringdown(np.asarray(t), np.asarray(z))
    assert q == pytest.approx(100.0, rel=2e-3)  # 24 samples a period: peaks to 0.1 %
    assert "Q_eff = 100" in panel.readout.value



@pytest.mark.parametrize("quality_factor", [10.0, 400.0, 1000.0])
def test_no_dashed_line_runs_a_long_path(quality_factor):
    # issue 24: the browser strokes a dashed line dash by dash; the ring-downs oscillate across
    # the whole axis at about a period a pixel, a path of ~150 axis widths at Q = 400: such a
    # line must be solid (a dashed one may run at most a few axis widths)
    panel = QControlPanel(quality_factor=quality_factor)
    panel.set(gain=0.001)
    for ax in panel.fig.axes:
        (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
        log = ax.get_yscale() == "log"
        if log:
            y0, y1 = math.log10(y0), math.log10(y1)
        width, height = panel.fig.get_size_inches() * ax.get_position().size
        for line in ax.get_lines():
            x, y = (np.asarray(v, dtype=float) for v in line.get_data())
            if log:
                y = np.log10(y)
            path = np.nansum(np.hypot(np.diff(x) / (x1 - x0), np.diff(y) / (y1 - y0) * height
                                      / width))  # in axis widths
            if line.get_linestyle() not in ("-", "solid"):
                assert path < 5.0, (line.get_label(), path)

def test_one_model_run_per_slider_move(runs):
    panel = QControlPanel()
    base = dict(runs)
    for v in (0.005, 0.01, -0.001):
        panel.set(gain=v)
    # each move: the closed form once with and once without the controller (the reference)
    assert runs["response"] - base["response"] == 3 * 2
    assert runs["ring"] - base["ring"] == 3 * 2


def test_unstable_gain_is_said_and_drawn_as_unstable():
    """g = -0.005 < -1/Q: no steady resonance is drawn (the notebook: 'the panel says the loop
    is unstable'), the title says why, and the ring-down grows at the rate of the closed
    loop's pole, -(w0 / 2)(1/Q + g) > 0 at phi = 90 deg (by hand)."""
    panel = QControlPanel(quality_factor=400.0)
    panel.set(gain=-0.005)
    assert "unstable" in panel.readout.value
    assert not panel.last.qc.stable
    low, _ = panel.last.stable_gains
    assert low == pytest.approx(-1 / 400.0)
    assert not np.any(np.isfinite(panel.figure.lines["controlled"].get_data()[1]))
    assert "unstable" in panel.figure.ax_response.get_title()
    assert np.all(np.isfinite(panel.figure.lines["free"].get_data()[1]))
    t, z = (np.asarray(a) for a in panel.figure.lines["ring"].get_data())
    assert np.all(np.isfinite(z))
    sigma = -0.5 * 2 * math.pi * (1 / 400.0 - 0.005)          # per period, t in periods
    peaks = [abs(z[(t >= n) & (t < n + 1)]).max() for n in (0, int(t[-1]) - 1)]
    assert peaks[1] / peaks[0] == pytest.approx(math.exp(sigma * (int(t[-1]) - 1)), rel=0.02)
    panel.set(gain=0.0075)                                   # stable again: a curve, no warning
    assert np.all(np.isfinite(panel.figure.lines["controlled"].get_data()[1]))
    assert panel.figure.ax_response.get_title() == "resonance"


def test_sliders_come_from_the_parameters():
    panel = QControlPanel()
    for name in ui.Q_DEFAULTS:
        p = qcontrol.PARAMETERS[name]
        c = panel.controls[name]
        low, high = (c.base ** c.min, c.base ** c.max) if p.log else (c.min, c.max)
        # a log slider's grid runs through the value: its ends within one step (1/40 decade)
        rel = 10 ** (1 / 40) - 1 if p.log else 1e-9
        assert low == pytest.approx(p.to_display(p.slider_low), rel=rel, abs=1e-12)
        assert high == pytest.approx(p.to_display(p.slider_high), rel=rel, abs=1e-12)
    with pytest.raises(ValueError, match="gain"):
        panel.set(gain=0.5)
    with pytest.raises(TypeError, match="unknown control"):
        QControlPanel(gian=0.1)


@pytest.fixture
def twin_device():
    twin = HapticTwin()
    host, server = open_twin(twin, time_scale=1.0)
    dev = HapticDevice(host, timeout=0.5)
    dev.connect()
    yield twin, dev
    dev.close()
    server.stop()


def test_the_device_follows_the_q_sliders(twin_device):
    twin, dev = twin_device
    panel = QControlPanel(dev)
    panel.set(gain=-0.02, phase=45.0)
    assert twin.params[Param.QGAIN] == -20 and twin.params[Param.QPHASE] == 45_000


def test_bridge_force_law_is_the_source_scaled_and_clipped():
    panel = BridgePanel(max_force=1.0)
    panel.set(source="cantilever", force_scale=1e8)
    src = panel._source("cantilever")
    x = panel.last.x
    expected = np.clip(-src.spring_constant * x * 1e-6 * 1e8, -1.0, 1.0)
    np.testing.assert_allclose(panel.last.force, expected, rtol=1e-12)
    xs, f = panel.figure.lines["force"].get_data()
    np.testing.assert_allclose(xs, x * 1e3)  # mm
    assert np.max(np.abs(f)) <= 1.0
    assert panel.figure.lines["max"].get_data()[1][0] == 1.0


def test_notebook_suggestion_cantilever_at_1e9_saturates():
    """Notebook 08: "Choose cantilever and raise the force scale to 10^9: the force law is clipped
    at 2 N, and a run counts the saturated ticks"."""
    class Held:  # a device whose handle a finger holds 2 mm in
        max_force = 2.0
        sent = []

        def send_force(self, f):
            self.sent.append(f)

        def latest(self):
            return type("S", (), {"position": 2e-3})()

    panel = BridgePanel(Held())
    panel.set(source="cantilever", force_scale=1e9)
    assert np.max(np.abs(panel.last.force)) == 2.0
    stats = panel.run(0.05)
    assert stats.saturated == stats.ticks > 0 and "100.0 %" in panel.status.value


def test_bridge_source_is_built_once_per_choice(monkeypatch):
    built = []
    real = ui.SOURCES["cantilever"]
    sources = dict(ui.SOURCES)
    sources["cantilever"] = (lambda: built.append(1) or real[0](), *real[1:])
    monkeypatch.setattr(ui, "SOURCES", sources)
    panel = BridgePanel(source="cantilever")
    for s in (1e6, 1e7, 1e9):
        panel.set(force_scale=s)
    assert len(built) == 1  # the force scale redraws, it does not rebuild the source
    panel.set(source="indentation")
    panel.set(source="cantilever")
    assert len(built) == 1


def test_bridge_run_shows_rate_and_jitter(twin_device):
    twin, dev = twin_device
    dev.configure(spring=500.0)
    dev.enable()
    dev.start_stream(1e-3)
    panel = BridgePanel(dev)
    switch = sys.getswitchinterval()
    stats = panel.run(0.2)
    assert sys.getswitchinterval() == switch  # restored after the run
    # every deadline of the run was ticked or counted missed (a loaded machine ticks fewer:
    # CI once saw 48 ticks and 153 missed in 0.2 s at 1 kHz, so no rate is asserted)
    assert stats.ticks > 0 and panel.last.stats is stats
    assert stats.ticks + stats.missed >= 0.9 * stats.elapsed * stats.target_rate, stats
    html = panel.status.value
    assert "measured rate" in html and "Hz" in html and "99th percentile" in html
    assert twin._last_force > 0  # the device took the bridge's force frames


def test_bridge_needs_a_device_to_run():
    with pytest.raises(RuntimeError, match="needs a device"):
        BridgePanel().run(0.1)


def test_gauge_source_appears_with_a_reader():
    panel = BridgePanel(gauge=lambda: 1234, gauge_calibration=1e-3, source="gauge")
    assert "gauge" in panel.controls["source"].options
    assert panel.last.source == "gauge"


@pytest.mark.slow
def test_tapping_force_law_is_periodic_in_felt_time():
    panel = BridgePanel(source="tapping", force_scale=1e7)
    t, f = panel.last.x, panel.last.force
    period = panel._source("tapping").period / ui.SOURCES["tapping"][2]
    assert period == pytest.approx(0.5)  # 2 taps a second
    half = len(t) // 2
    np.testing.assert_allclose(f[:half], f[half:2 * half], atol=1e-3 * np.ptp(f))


def test_figures_say_their_units_and_do_not_overlap():
    """test_figures_labelled's four checks on these panels' figures (the lead may list them
    there too)."""
    from tests import test_figures_labelled as labelled
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    q = QControlPanel()
    q.set(gain=0.01)
    figs = [q.fig, BridgePanel().fig, BridgePanel(source="cantilever").fig]
    for fig in figs:
        FigureCanvasAgg(fig).draw()
    labelled.test_every_axis_with_ticks_has_a_label_with_a_unit(figs)
    labelled.test_no_title_or_label_overlaps_another_axes_texts(figs)
    labelled.test_tick_labels_are_readable_numbers(figs)
    labelled.test_no_axes_is_left_empty(figs)
