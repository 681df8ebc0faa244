"""The lock-in panel without a browser: sliders from the Parameters, one model run per action,
the plotted data the model's, the square reference's 1/3 pickup of an interference at 6 omega
(the Fourier coefficient, typed here), out-of-range values named."""
import math

import numpy as np
import pytest

import afmsmiler.signals.demo as demo_module
import afmsmiler.ui.lockin as lockin_ui
from afmsmiler.signals.chain import AMPLIFIER_GAIN
from afmsmiler.ui.lockin import SLIDERS, LockInPanel


@pytest.fixture(scope="module")
def panel():
    return LockInPanel()


def test_sliders_are_built_from_the_parameters(panel):
    for name, p in SLIDERS.items():
        c = panel.controls[name]
        assert c.parameter is p and p.display_unit in c.description
        assert c.value == pytest.approx(p.to_display(p.default))
    assert panel.controls["shape"].options == ("sine", "square")


def test_default_panel_recovers_the_truth_within_1_percent_and_1_degree(panel):
    panel.set(shape="sine", interference=0.0)
    d = panel.last
    assert abs(d.amplitude_error) < 0.01
    assert abs(math.degrees(d.phase_error)) < 1.0
    title = panel.figure.axes["outputs"].get_title()
    assert f"{100 * d.amplitude_error:+.2f} %" in title


def test_one_action_runs_the_model_once(panel, monkeypatch):
    calls = {"demo": 0, "simulate": 0}
    real_demo, real_sim = lockin_ui.lock_in_demo, demo_module.simulate

    def demo(**kw):
        calls["demo"] += 1
        return real_demo(**kw)

    def sim(*a, **kw):
        calls["simulate"] += 1
        return real_sim(*a, **kw)
    monkeypatch.setattr(lockin_ui, "lock_in_demo", demo)
    monkeypatch.setattr(demo_module, "simulate", sim)
    panel.set(time_constant=0.5)
    assert calls == {"demo": 1, "simulate": 1}
    panel.set(order=2, shape="square")
    assert calls == {"demo": 2, "simulate": 2}


def test_plotted_data_is_the_models(panel):
    panel.set(time_constant=1.0, order=4, shape="sine", interference=0.0)
    d, ln = panel.last, panel.figure.lines
    x, y = ln["x"].get_data()
    step = max(1, math.ceil(d.reading.time.size / 3000))
    assert np.allclose(y, d.reading.x_trace[::step] * 1e3)
    assert ln["x_true"].get_ydata()[0] == pytest.approx(d.truth.real * 1e3)
    f, a = ln["spectrum"].get_data()
    k = np.argmin(abs(f - 2.0))
    assert a[k] == pytest.approx(abs(d.truth) * 1e3, rel=0.05)   # the 2-omega line


def test_square_reference_reads_a_third_of_the_interference(panel):
    interference = 100e-6                               # V at the amplifier input, at 6 omega
    panel.set(shape="square", interference=interference * 1e6, time_constant=1.0, order=4)
    d = panel.last
    gain = AMPLIFIER_GAIN.default
    # sq(x) = (4/pi)(sin x + sin 3x / 3 + ...): the in-phase square reads sin(3x) with 1/3
    assert d.reading.x - d.truth.real == pytest.approx(gain * interference / 3, rel=0.02)
    assert list(panel.figure.lines["pickup"].get_ydata()) == pytest.approx(
        [1, 0, 1 / 3, 0, 1 / 5, 0, 1 / 7])
    panel.set(shape="sine")
    assert abs(panel.last.amplitude_error) < 0.01
    assert list(panel.figure.lines["pickup"].get_ydata()) == [1, 0, 0, 0, 0, 0, 0]
    panel.set(interference=0.0)


def test_the_whole_error_shows_what_the_amplitude_error_hides(panel):
    """Notebook 08's lock-in cell: the square reference's third of the tone moves the reading by
    G I / 3 (the Fourier coefficient 1/3, typed here), mostly in phase for this tone, so the
    amplitude error alone reads a per cent or two while the reading is off by a quarter of the
    signal; the whole error |Z - Z_true| / |Z_true| says so."""
    interference = 100e-6
    gain = AMPLIFIER_GAIN.default
    panel.set(shape="square", interference=interference * 1e6, time_constant=1.0, order=4)
    d = panel.last
    third = gain * interference / 3
    assert abs(d.deviation) == pytest.approx(third, rel=0.02)
    assert d.relative_error == pytest.approx(third / abs(d.truth), rel=0.02)
    assert d.relative_error > 10 * abs(d.amplitude_error)       # what the amplitude hides
    assert abs(math.degrees(d.phase_error)) > 10                   # it went into the phase
    z = d.reading.amplitude * np.exp(1j * d.reading.phase)          # the polar reading
    assert abs(z - d.truth) == pytest.approx(abs(d.deviation), rel=1e-9)
    panel.set(shape="sine")
    assert panel.last.relative_error < 0.01
    panel.set(interference=0.0)


def test_out_of_range_values_are_named(panel):
    with pytest.raises(ValueError, match="ac_voltage"):
        panel.set(ac_voltage=50.0)
    with pytest.raises(ValueError, match="shape"):
        panel.set(shape="triangle")


def test_a_time_constant_too_long_to_simulate_is_named():
    from afmsmiler.signals.demo import lock_in_demo
    with pytest.raises(ValueError, match="time_constant 1 s with order 4 needs a record"):
        lock_in_demo(time_constant=1.0)


def test_every_medium_takes_every_drive_the_slider_offers():
    # the drive's slider ends where the bridge leaves its range in the medium with the highest
    # Q (air, Q ~ 215 against the typed 150): no medium makes the student's drive invalid
    panel = LockInPanel()
    top = panel.controls["ac_voltage"].max
    panel.set(ac_voltage=top, half_resonance_ratio=1.0)
    for fluid in ("air", "water", "typed"):
        panel.set(fluid=fluid)
        assert panel.last.run.probe.sensor.fluid == (None if fluid == "typed" else fluid)
        assert panel.controls["ac_voltage"].value == top   # never moved by the medium
    # notebook 08: in water the lever rings at 34 kHz (driven at 17 kHz) with Q ~ 4, and the
    # 2-omega line falls more than tenfold against vacuum's (and air's)
    panel.set(fluid="water")
    water = abs(panel.last.truth)
    panel.set(fluid="air")
    assert water < abs(panel.last.truth) / 10
    panel.set(fluid="typed")
    assert water < abs(panel.last.truth) / 10


@pytest.mark.parametrize("time_constant, order", [(1e-3, 4), (1e-4, 1), (3e-3, 8), (1e-5, 2)])
def test_the_record_is_settled_and_a_fast_fft_length(time_constant, order):
    # the record is rounded up to whole drive periods whose count has no prime factor above 5
    # (with 2^k samples a period the FFT's length then has none either): never shorter than the
    # filter's settling time plus the extra periods, at most a few per cent longer
    from afmsmiler.signals.demo import DEFAULTS, lock_in_demo
    from afmsmiler.signals.lockin import settling_time
    demo = lock_in_demo(time_constant=time_constant, order=order)
    f, n = demo.run.drive_frequency, demo.run.output.size
    spp = DEFAULTS["samples_per_period"]
    assert n % spp == 0
    periods = n // spp
    rest = periods
    for p in (2, 3, 5):
        while rest % p == 0:
            rest //= p
    assert rest == 1, f"{periods} periods has a prime factor above 5"
    needed = settling_time(time_constant, order) + DEFAULTS["extra_periods"] / (2 * f)
    assert periods >= needed * f - 1e-9
    assert periods <= 1.07 * math.ceil(needed * f)
