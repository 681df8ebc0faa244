"""The lock-in and the AD630 against closed forms: ENBW, settling, harmonic pickup, recovery.

Sources: the ENBW of N RC stages is the integral of |H|^2 (computed here by scipy.integrate.quad,
independently of the Gamma-function closed form) and the SR830 manual's table (1/(4 tau),
1/(8 tau), 3/(32 tau), 5/(64 tau)); the square wave's Fourier coefficients 4 / (pi h).
"""
import math

import numpy as np
import pytest
import scipy.integrate

from afmsmiler.signals import ad630, lockin
from afmsmiler.signals.lockin import (amplitude_spectrum, enbw, harmonic_pickup, lock_in, lowpass,
                                      settling_time, square_wave)


@pytest.mark.parametrize("order", range(1, 9))
def test_enbw_is_the_integral_of_the_power_response(order):
    tau = 1.7e-3
    integral, _ = scipy.integrate.quad(lambda f: (1 + (2 * math.pi * f * tau) ** 2) ** -order,
                                       0, np.inf)
    assert enbw(tau, order) == pytest.approx(integral, rel=1e-9)


def test_enbw_matches_the_sr830_table():
    tau = 1.0
    assert [enbw(tau, n) for n in (1, 2, 3, 4)] == pytest.approx([1 / 4, 1 / 8, 3 / 32, 5 / 64])


@pytest.mark.parametrize("order", [1, 2, 4, 8])
def test_step_response_settles_at_the_settling_time(order):
    fs, tau = 1e6, 1e-4
    t_s = settling_time(tau, order)
    y = lowpass(np.ones(int(2 * t_s * fs)), sample_rate=fs, time_constant=tau, order=order)
    k = int(round(t_s * fs))
    assert 1 - y[k] == pytest.approx(1e-4, rel=0.05)        # one sample's worth of slack
    assert 1 - y[k - int(0.5 * tau * fs)] > 1e-4


def test_lowpass_gain_is_that_of_n_rc_stages():
    fs, tau, f, order = 1e6, 1e-4, 800.0, 3
    t = np.arange(int(0.05 * fs)) / fs
    y = lowpass(np.sin(2 * math.pi * f * t), sample_rate=fs, time_constant=tau, order=order)
    tail = y[-int(fs / f) * 5:]
    expected = abs(1 / (1 + 2j * math.pi * f * tau)) ** order
    assert (tail.max() - tail.min()) / 2 == pytest.approx(expected, rel=2e-3)



@pytest.mark.parametrize("order", [1, 4])
def test_lowpass_is_the_rc_recursion_stage_after_stage(order):
    # issue 24: the stages run in one sosfilt pass; here each is the zero-order-hold recursion
    # y[k] = y[k-1] + a (x[k] - y[k-1]) written out, a = 1 - exp(-dt / tau), from rest
    fs, tau = 1e5, 3e-4
    x = np.random.default_rng(2).standard_normal(400)
    a = 1 - math.exp(-1 / (fs * tau))
    y = x.tolist()
    for _ in range(order):
        prev, out = 0.0, []
        for v in y:
            prev = prev + a * (v - prev)
            out.append(prev)
        y = out
    np.testing.assert_allclose(lowpass(x, sample_rate=fs, time_constant=tau, order=order), y,
                               rtol=1e-12, atol=1e-15)

def _tone(amplitude, phase, f, fs, n):
    return amplitude * np.sin(2 * math.pi * f * np.arange(n) / fs + phase)


# The stated SNR: a 2-omega sine of peak A in white noise of rms A / (10 sqrt 2) over the sampled
# band (input SNR 20 dB, signal rms over noise rms), f_s = 64 f_ref, tau = 8 reference periods,
# order 4: ENBW = 5 / (64 tau) and the output noise sqrt(2 S ENBW) = A / 572 (S = 2 sigma^2 / f_s),
# so 1 % is 5.7 sigma in amplitude and 1 degree is 10 sigma in phase.
SNR_IN = 10.0


def _noisy_record(seed, amplitude=2.5e-3, phase=math.radians(37.0)):
    f = 40e3
    f_ref = 2 * f
    fs = 64 * f_ref
    tau = 8 / f_ref
    n = int((settling_time(tau, 4) + 40 / f_ref) * fs)
    sigma = amplitude / math.sqrt(2) / SNR_IN
    rng = np.random.default_rng(seed)
    s = _tone(amplitude, phase, f_ref, fs, n) + sigma * rng.standard_normal(n)
    return s, f, fs, tau, sigma


@pytest.mark.parametrize("seed", range(10))
def test_recovers_two_omega_amplitude_within_1_percent_and_phase_within_1_degree(seed):
    amplitude, phase = 2.5e-3, math.radians(37.0)
    s, f, fs, tau, sigma = _noisy_record(seed, amplitude, phase)
    r = lock_in(s, sample_rate=fs, frequency=f, harmonic=2, time_constant=tau, order=4)
    predicted = r.noise(2 * sigma ** 2 / fs)
    assert predicted == pytest.approx(amplitude / 572, rel=0.01)
    assert r.amplitude == pytest.approx(amplitude, rel=0.01)
    assert abs(math.degrees(r.phase - phase)) < 1.0


def test_output_noise_follows_the_enbw():
    """White noise alone: the variance of X(t) is 2 S ENBW (an independent statistical check)."""
    fs, f, tau, order = 200e3, 5e3, 2e-3, 2
    n = int(4.0 * fs)
    sigma = 1.0
    rng = np.random.default_rng(7)
    r = lock_in(sigma * rng.standard_normal(n), sample_rate=fs, frequency=f, harmonic=1,
                time_constant=tau, order=order)
    k = int(r.settle_time * fs)
    measured = np.var(np.concatenate([r.x_trace[k:], r.y_trace[k:]]))
    s = 2 * sigma ** 2 / fs
    assert measured == pytest.approx(2 * s * enbw(tau, order), rel=0.1)
    assert math.sqrt(measured) == pytest.approx(r.noise(s), rel=0.05)


@pytest.mark.parametrize("h", [1, 3, 5, 7])
def test_square_reference_picks_up_odd_harmonics_with_their_fourier_weight(h):
    f_ref, fs = 10e3, 512 * 10e3
    tau = 20 / f_ref
    n = int((settling_time(tau, 4) + 50 / f_ref) * fs)
    phase = math.radians(25.0)
    s = _tone(1.0, phase, h * f_ref, fs, n)
    r = lock_in(s, sample_rate=fs, frequency=f_ref, harmonic=1, time_constant=tau, order=4,
                shape="square")
    # the Fourier coefficient of harmonic h over the fundamental's: (4 / (pi h)) / (4 / pi)
    assert r.amplitude == pytest.approx(1.0 / h, rel=1e-3)
    assert harmonic_pickup(h, "square") == 1.0 / h
    # the quadrature square sq(x + pi/2) carries sin(h x + h pi/2) = (-1)^((h-1)/2) cos(h x):
    # the leak's phase reads as itself for h = 1, 5, ... and mirrored for h = 3, 7, ...
    sign = 1 if h % 4 == 1 else -1
    assert math.degrees(r.phase) == pytest.approx(sign * 25.0, abs=0.1)


@pytest.mark.parametrize("h", [2, 4])
def test_square_reference_ignores_even_harmonics(h):
    f_ref, fs = 10e3, 512 * 10e3
    tau = 20 / f_ref
    n = int((settling_time(tau, 4) + 50 / f_ref) * fs)
    r = lock_in(_tone(1.0, 0.3, h * f_ref, fs, n), sample_rate=fs, frequency=f_ref, harmonic=1,
                time_constant=tau, order=4, shape="square")
    assert r.amplitude < 1e-3
    assert harmonic_pickup(h, "square") == 0.0


def test_sine_reference_rejects_the_third_harmonic():
    f_ref, fs = 10e3, 512 * 10e3
    tau = 20 / f_ref
    n = int((settling_time(tau, 4) + 50 / f_ref) * fs)
    r = lock_in(_tone(1.0, 0.3, 3 * f_ref, fs, n), sample_rate=fs, frequency=f_ref, harmonic=1,
                time_constant=tau, order=4, shape="sine")
    assert r.amplitude < 1e-5
    assert harmonic_pickup(3, "sine") == 0.0


def test_ad630_levels_are_two_over_pi_times_the_component():
    f, fs = 10e3, 256 * 20e3
    tau = 20 / (2 * f)
    n = int((settling_time(tau, 2) + 50 / (2 * f)) * fs)
    theta = math.radians(-60.0)
    s = _tone(0.2, theta, 2 * f, fs, n) + 0.05       # a DC offset must not leak through
    r = ad630.demodulate(s, sample_rate=fs, frequency=f, harmonic=2, gain=2.0, time_constant=tau,
                         order=2)
    assert r.x == pytest.approx(2.0 * 2 / math.pi * 0.2 * math.cos(theta), rel=1e-3)
    assert r.y == pytest.approx(2.0 * 2 / math.pi * 0.2 * math.sin(theta), rel=1e-3)
    assert r.amplitude == pytest.approx(0.2, rel=1e-3)
    assert math.degrees(r.phase) == pytest.approx(-60.0, abs=0.1)
    # the switched waveform is the signal times +-G
    assert np.allclose(np.abs(r.switched_x[1:200:7]), 2.0 * np.abs(s[1:200:7]), rtol=0, atol=1e-12)


def test_square_wave_values_and_box_average():
    assert list(square_wave([0.1, 0.4, 0.6, 0.9])) == [1.0, 1.0, -1.0, -1.0]
    # an edge centred in the window averages to 0; a window a quarter over it to 1/2
    assert square_wave([0.5], 0.1)[0] == pytest.approx(0.0, abs=1e-12)
    assert square_wave([0.525], 0.1)[0] == pytest.approx(-0.5)
    # the box-averaged square has the mean of the ideal one over each sample
    u = np.linspace(0, 3, 301)
    assert abs(square_wave(u, 0.01).mean()) < 0.02


def test_average_filter_rejects_other_harmonics_exactly():
    f, fs = 1e3, 64e3
    n = 64 * 50
    s = _tone(0.7, 0.2, 2 * f, fs, n) + _tone(0.3, 1.0, f, fs, n) + _tone(0.1, 0, 3 * f, fs, n)
    r = lock_in(s, sample_rate=fs, frequency=f, harmonic=2, filter="average")
    assert r.amplitude == pytest.approx(0.7, rel=1e-12)
    assert r.phase == pytest.approx(0.2, abs=1e-12)


def test_spectrum_reads_a_bin_centred_sine():
    fs, n = 1e4, 1000
    s = _tone(0.3, 0.5, 1000.0, fs, n) + 1.0
    sp = amplitude_spectrum(s, sample_rate=fs)
    k = int(np.argmin(abs(sp.frequency - 1000.0)))
    assert sp.amplitude[k] == pytest.approx(0.3, rel=1e-9)
    assert sp.amplitude[0] < 1e-9


def test_errors_name_the_parameter_and_range():
    s = np.zeros(1000)
    with pytest.raises(ValueError, match="signal of 1000 samples .* time_constant"):
        lock_in(s, sample_rate=1e5, frequency=1e3, time_constant=1e-3)
    with pytest.raises(ValueError, match="shape"):
        lock_in(s, sample_rate=1e5, frequency=1e3, shape="triangle")
    with pytest.raises(ValueError, match="order"):
        enbw(1e-3, 9)
    with pytest.raises(ValueError, match="frequency must be at most"):
        lock_in(s, sample_rate=1e3, frequency=400.0, harmonic=1, filter="average")
    with pytest.raises(ValueError, match="signal must have"):
        lock_in(np.zeros(lockin.LIMITS["samples"] + 1), sample_rate=1e6, frequency=1e3)
    with pytest.raises(ValueError, match="reference must have"):
        ad630.switch(np.zeros(3), np.zeros(4))


def test_a_box_averaged_square_stays_within_plus_minus_one():
    """The campaign's valid call demodulate(2 kHz at 1 MHz) failed: the mean of two ramps
    rounded to 1 + 2e-16 and the AD630's switch refused its own reference."""
    from afmsmiler.signals.ad630 import demodulate
    from afmsmiler.signals.lockin import square_wave
    u = np.arange(40_000) * 2e3 / 1e6
    sq = square_wave(u, step=2e-3)
    assert np.all(np.abs(sq) <= 1.0)
    tone = 0.1 * np.sin(2 * np.pi * 2e3 * np.arange(40_000) / 1e6)
    out = demodulate(tone, sample_rate=1e6, frequency=1e3, time_constant=1e-3)
    assert np.isfinite(out.x)


def test_remembered_references_and_window_equal_the_computed_ones():
    # issue 24: lock_in and amplitude_spectrum reuse them from one call to the next
    rng = np.random.default_rng(0)
    s = np.sin(2 * math.pi * 2e3 * np.arange(20000) / 1e6) + 0.1 * rng.standard_normal(20000)
    lockin._references.cache_clear()
    lockin._hann.cache_clear()
    first = lock_in(s, sample_rate=1e6, frequency=1e3, time_constant=1e-3, shape="square")
    spectrum = amplitude_spectrum(s, sample_rate=1e6)
    again = lock_in(s, sample_rate=1e6, frequency=1e3, time_constant=1e-3, shape="square")
    assert lockin._references.cache_info().hits == 1
    assert (first.x, first.y) == (again.x, again.y)
    refs = lockin._references(s.size, 1e6, 2e3, "square", 0.0)
    for cached, computed in zip(refs, lockin.reference_waveforms(
            s.size, sample_rate=1e6, frequency=2e3, shape="square")):
        np.testing.assert_array_equal(cached, computed)
        assert not cached.flags.writeable
    np.testing.assert_array_equal(lockin._hann(s.size), np.hanning(s.size + 1)[:-1])
    np.testing.assert_array_equal(amplitude_spectrum(s, sample_rate=1e6).amplitude,
                                  spectrum.amplitude)
