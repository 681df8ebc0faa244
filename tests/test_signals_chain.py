"""The educational AFM's chain against the closed form of the electrothermal 2-omega drive.

The closed form is written here independently of the chain: the 2-omega power term of
(V_ac sin w t)^2 / R = V_ac^2 / (2R) (1 - cos 2 w t) (trigonometry), through the fin's thermal
response H_uniform (Carslaw and Jaeger 1959, sec. 3.3, typed here from the formula) and the
lever's second-order mode built with python-control (``control.tf``), times module (b)'s static
bimorph gain (a number, m/W).
"""
import math

import control
import numpy as np
import pytest

from afmsmiler.signals import ActiveProbe, lock_in, simulate
from afmsmiler.signals.chain import power_harmonics
from afmsmiler.signals.lockin import settling_time
from afmsmiler.transducers import Electrothermal, Piezoresistive


def _h_uniform(f, length, diffusivity):
    u = length * np.sqrt(2j * math.pi * f / diffusivity)
    return 8 / u ** 2 * (0.5 - np.tanh(u) / u + (1 - 1 / np.cosh(u)) / u ** 2)


def _closed_form_deflection(probe, f, ac_voltage, dc_voltage=0.0):
    """Phasors (A e^{j theta} of A sin(n w t + theta)) of the tip deflection at w and 2 w."""
    a = probe.actuator
    w1 = 2 * math.pi * a.resonance_frequency
    lever = control.tf([1.0], [1 / w1 ** 2, 1 / (a.quality_factor * w1), 1.0])
    out = []
    for n, p in ((1, 2 * dc_voltage * ac_voltage / a.resistance),
                 (2, ac_voltage ** 2 / (2 * a.resistance) * np.exp(-0.5j * math.pi))):
        fn = n * f
        h = (a.deflection_per_watt() * _h_uniform(fn, a.length, a.thermal_diffusivity)
             * complex(lever(2j * math.pi * fn)))
        out.append(p * h)
    return out


def _component(x, n, spp):
    """Exact projection of x (whole drive periods, spp samples each) on sin/cos(n w t)."""
    k = np.arange(x.size)
    arg = 2 * math.pi * n * k / spp
    return 2 * np.mean(x * np.sin(arg)) + 2j * np.mean(x * np.cos(arg))


@pytest.mark.parametrize("ratio", [0.99, 1.0, 1.005, 0.5])
def test_two_omega_deflection_equals_the_closed_form(ratio):
    probe = ActiveProbe.build(ac_voltage=1.2)
    run = simulate(probe, half_resonance_ratio=ratio, noise=False, record_duration=2e-4)
    _, z2 = _closed_form_deflection(probe, run.drive_frequency, 1.2)
    simulated = _component(run.deflection, 2, 128)
    assert abs(simulated) == pytest.approx(abs(z2), rel=1e-9)
    assert np.angle(simulated / z2) == pytest.approx(0.0, abs=1e-9)
    # and the chain's own closed form (from module (b)'s thermal lag and module (a)) agrees
    assert run.second_deflection == pytest.approx(z2, rel=1e-9)


def test_unbiased_drive_has_no_first_harmonic_and_a_bias_adds_it():
    probe = ActiveProbe.build(ac_voltage=1.0)
    run = simulate(probe, dc_voltage=0.0, noise=False, record_duration=2e-4)
    z2 = _component(run.deflection, 2, 128)
    assert abs(_component(run.deflection, 1, 128)) < 1e-12 * abs(z2)
    biased = simulate(probe, dc_voltage=0.8, noise=False, record_duration=2e-4)
    z1, _ = _closed_form_deflection(probe, biased.drive_frequency, 1.0, 0.8)
    assert _component(biased.deflection, 1, 128) == pytest.approx(z1, rel=1e-9)


def test_power_expansion():
    dc, first, second = power_harmonics(0.3, 1.1, 2e3)
    t = np.linspace(0, 1, 64, endpoint=False)
    p = (0.3 + 1.1 * np.sin(2 * math.pi * t)) ** 2 / 2e3
    rebuilt = (dc.real + (first * np.exp(2j * math.pi * t)).imag
               + (second * np.exp(4j * math.pi * t)).imag)
    assert rebuilt == pytest.approx(p, rel=1e-12)


def test_output_two_omega_is_the_deflection_through_the_bridge_and_gain():
    probe = ActiveProbe.build(ac_voltage=0.8)
    run = simulate(probe, noise=False, amplifier_gain=50.0, record_duration=2e-4)
    out = _component(run.output, 2, 128)
    assert out == pytest.approx(run.second, rel=1e-4)    # the bridge's own curvature: ~dR/R
    assert run.first == 0


def test_noisy_chain_lock_in_recovers_the_closed_form_within_1_percent_and_1_degree():
    """The Done-means check on the whole chain, default noise (SNR 5.6e3 sqrt(Hz) at 2 w)."""
    tau, order = 1e-3, 4
    probe = ActiveProbe()
    for seed in range(3):
        run = simulate(probe, seed=seed, record_duration=settling_time(tau, order) + 1e-3)
        assert run.snr > 5e3
        r = lock_in(run.output, sample_rate=run.sample_rate, frequency=run.drive_frequency,
                    harmonic=2, time_constant=tau, order=order)
        assert r.amplitude == pytest.approx(abs(run.second), rel=0.01)
        assert abs(math.degrees(r.phase - np.angle(run.second))) < 1.0


def test_noise_records_have_their_densities_variance():
    probe = ActiveProbe()
    run = simulate(probe, amplifier_noise=1e-12, amplifier_gain=1.0, record_duration=5e-3, seed=3)
    # the electrical noise is white (the amplifier's dominates): variance e_n^2 f_s / 2
    electrical = run.output - run.bridge
    assert np.var(electrical) == pytest.approx(1e-12 * run.sample_rate / 2, rel=0.03)
    # Brownian: module (a)'s spectrum integrated over the record's band
    f = np.fft.rfftfreq(run.time.size, 1 / run.sample_rate)[1:]
    from afmsmiler.signals.chain import brownian_density
    expected = np.sum(brownian_density(probe, f)) * f[0]
    assert np.var(run.brownian) == pytest.approx(expected, rel=0.25)


def test_probe_and_arguments_are_checked():
    with pytest.raises(ValueError, match="share the lever: length"):
        ActiveProbe(Electrothermal(length=300e-6), Piezoresistive())
    with pytest.raises(TypeError, match="sensor"):
        ActiveProbe(Electrothermal(), "bridge")
    with pytest.raises(ValueError, match="record_duration .* samples"):
        simulate(record_duration=1.0)
    with pytest.raises(ValueError, match="half_resonance_ratio"):
        simulate(half_resonance_ratio=5.0)
    with pytest.raises(TypeError, match="unknown"):
        ActiveProbe.build(bias_voltage=3.0)


def test_the_largest_drive_keeps_the_deflection_inside_the_bridge_range():
    # The lock-in panel's drive slider reached 5 V, where at resonance the lever deflects 2.3 um
    # and module (b)'s bridge (range +-2 um) refused every move. max_ac_voltage bounds the peak by
    # V^2/(2R) (|H(0)| + |H(2f)|); simulated without noise at every drive ratio of the slider, the
    # peak deflection stays inside the range and uses most of it at resonance.
    from afmsmiler.signals.chain import HALF_RESONANCE_RATIO, ActiveProbe, simulate
    from afmsmiler.signals.demo import max_ac_voltage
    volts = max_ac_voltage(margin=1.0)
    probe = ActiveProbe.build(ac_voltage=volts)
    reach = probe.sensor.input_quantity("sensing").high
    peaks = []
    for ratio in np.linspace(HALF_RESONANCE_RATIO.slider_low, HALF_RESONANCE_RATIO.slider_high, 5):
        run = simulate(probe, half_resonance_ratio=float(ratio), noise=False,
                       record_duration=0.05)
        peaks.append(float(np.max(np.abs(run.deflection))))
    assert max(peaks) <= reach and max(peaks) > 0.5 * reach
    assert max_ac_voltage() == pytest.approx(math.sqrt(0.8) * volts, rel=1e-12)
    with pytest.raises(ValueError, match="margin must be in"):
        max_ac_voltage(margin=0.0)


def test_the_transfer_function_does_not_depend_on_the_drive_amplitude():
    # issue 24: why simulate may reuse it when V_ac moves (module (b)'s heat -> deflection is
    # linear: V_ac enters through P = V^2 / R only)
    f = np.linspace(0.0, 400e3, 2001)
    h = ActiveProbe.build(ac_voltage=0.5).deflection_per_power(f)
    for v in (0.0, 0.37, 2.9):
        np.testing.assert_array_equal(ActiveProbe.build(ac_voltage=v).deflection_per_power(f), h)


@pytest.mark.parametrize("noise", [True, False])
def test_a_drive_move_reuses_drive_and_noise_and_equals_the_full_simulation(noise):
    from afmsmiler.signals import chain
    fields = ("time", "heater_voltage", "power", "deflection", "brownian", "bridge", "output")
    chain._DRIVES.clear()
    chain._NOISES.clear()
    simulate(ActiveProbe.build(ac_voltage=0.5), record_duration=2e-3, noise=noise, seed=4)
    probe = ActiveProbe.build(ac_voltage=1.3)
    warm = simulate(probe, record_duration=2e-3, noise=noise, seed=4)  # from the memos
    assert len(chain._DRIVES.entries) == 1 and len(chain._NOISES.entries) == int(noise)
    chain._DRIVES.clear()
    chain._NOISES.clear()
    full = simulate(probe, record_duration=2e-3, noise=noise, seed=4)
    for name in fields:
        np.testing.assert_array_equal(getattr(warm, name), getattr(full, name))
    assert (warm.first, warm.second, warm.noise_density) == \
        (full.first, full.second, full.noise_density)
    other = simulate(probe, record_duration=2e-3, noise=noise, seed=5)  # another seed: new noise
    assert noise == (not np.array_equal(other.brownian, full.brownian))


def test_the_memo_keeps_a_bounded_number_of_bytes():
    from afmsmiler.signals.chain import _Memo
    memo = _Memo(size=3, max_bytes=1000)
    for i in range(5):
        memo.get(i, lambda: (np.zeros(40),))  # 320 bytes each: three fit
    assert [k for k, _ in memo.entries] == [2, 3, 4]
    big = memo.get("big", lambda: (np.zeros(200),))  # 1600 bytes: computed, not kept
    assert big[0].flags.writeable  # not shared
    assert [k for k, _ in memo.entries] == [2, 3, 4]
    assert memo.get(3, lambda: pytest.fail("recomputed"))[0].flags.writeable is False


def test_the_chain_is_not_linear_in_the_drive_so_runs_are_never_scaled():
    # issue 24 asked whether a unit-amplitude run could be scaled: the deflection scales as
    # V_ac^2 exactly (V_dc = 0), but the bridge's reading does not (5e-4 of it at 0.5 -> 1 V)
    a = simulate(ActiveProbe.build(ac_voltage=0.5), record_duration=1e-3, noise=False)
    b = simulate(ActiveProbe.build(ac_voltage=1.0), record_duration=1e-3, noise=False)
    np.testing.assert_allclose(b.deflection, 4 * a.deflection, rtol=0,
                               atol=1e-14 * np.max(np.abs(b.deflection)))
    assert np.max(np.abs(b.bridge - 4 * a.bridge)) > 1e-4 * np.max(np.abs(b.bridge))


@pytest.mark.parametrize("dc_voltage", [0.0, 0.7])
def test_the_deflection_is_the_fft_of_the_sampled_power_through_the_transfer_function(dc_voltage):
    # issue 24: simulate adds the remembered deflections of the sampled 1, sin and sin^2 with
    # P's coefficients; here the sampled P itself goes through rfft, H at the bins and irfft
    probe = ActiveProbe.build(ac_voltage=1.1)
    run = simulate(probe, dc_voltage=dc_voltage, half_resonance_ratio=1.004, noise=False,
                   record_duration=1e-3)
    n = run.time.size
    power = (dc_voltage + 1.1 * np.sin(2 * math.pi * run.drive_frequency * run.time)) ** 2 \
        / probe.actuator.resistance
    h = probe.deflection_per_power(np.fft.rfftfreq(n, 1 / run.sample_rate))
    direct = np.fft.irfft(np.fft.rfft(power) * h, n)
    np.testing.assert_allclose(run.power, power, rtol=1e-12)
    np.testing.assert_allclose(run.deflection, direct, rtol=0,
                               atol=1e-12 * np.max(np.abs(direct)))
