"""Module (b)'s lever in a medium (issue 23): with ``fluid="air"`` or ``"water"`` a transducer's
lever rings at its frequency in the fluid with the fluid's Q (Sader 1998, module (a)'s
:mod:`afmsmiler.hydrodynamics`), its thermal motion and response follow, and so does the
lock-in chain of module (h) built on two of them.

Independent sources: equipartition (the first mode's share of k_B T / k whatever the medium,
Butt and Jaschke 1995, with k = E w t^3 / (4 L^3)); near its peak in air the oscillator with
Sader's f_R and Q equals the spectrum with Sader's hydrodynamic function at every frequency
(:func:`afmsmiler.calibration.thermal_spectrum`, a different model: no fixed Q); at resonance a
driven oscillator's amplitude is Q times its static one."""
import math

import numpy as np
import pytest

from afmsmiler.brownian import BOLTZMANN
from afmsmiler.calibration import optical_lever_correction, thermal_spectrum
from afmsmiler.hydrodynamics import fluid_mode
from afmsmiler.signals import chain as chain_module
from afmsmiler.signals.chain import ActiveProbe
from afmsmiler.signals.demo import lock_in_demo
from afmsmiler.transducers import (PRINCIPLES, Electrothermal, OpticalBeamDeflection,
                                   PiezoAcoustic, Piezoresistive)
from afmsmiler.hydrodynamics import LOW_Q

#: Butt and Jaschke (1995): the first mode's share of k_B T / k at the tip.
PUBLISHED_FIRST_SHARE = 0.971
SILICON_E = 169e9


@pytest.mark.parametrize("fluid", ["air", "water"])
def test_a_lever_in_a_fluid_rings_where_sader_says_with_its_k(fluid):
    vacuum = OpticalBeamDeflection()
    model = OpticalBeamDeflection(fluid=fluid)
    assert model.spring_constant == vacuum.spring_constant   # the fluid adds mass, not stiffness
    for n in (1, 2):
        m = fluid_mode(model.lever, fluid, n)
        assert model.mode_in_medium(n) == (m.resonance_frequency, m.quality_factor)
    assert model.resonance_frequency < vacuum.resonance_frequency
    assert model.quality_factor == fluid_mode(model.lever, fluid, 1).quality_factor
    # the typed Q is not the lever's in a fluid: changing it changes nothing
    assert model.replace(quality_factor=20.0).quality_factor == model.quality_factor
    assert model.replace(length=150e-6).fluid == fluid   # replace keeps the medium
    assert model != vacuum and model == OpticalBeamDeflection(fluid=fluid)
    assert f"fluid={fluid!r}" in repr(model)


def test_water_lowers_f1_and_q_more_than_air():
    air, water = OpticalBeamDeflection(fluid="air"), OpticalBeamDeflection(fluid="water")
    assert water.resonance_frequency < air.resonance_frequency
    assert water.quality_factor < air.quality_factor / 10


@pytest.mark.parametrize("fluid", [None, "air", "water"])
def test_the_thermal_motion_in_a_fluid_keeps_the_first_modes_share_of_kt(fluid):
    model = OpticalBeamDeflection(fluid=fluid)
    k = SILICON_E * model.width * model.thickness ** 3 / (4 * model.length ** 3)
    total = model.thermal_noise(1e6 * model.resonance_frequency, 0.0)
    assert total == pytest.approx(
        math.sqrt(PUBLISHED_FIRST_SHARE * BOLTZMANN * model.temperature / k), rel=1e-3)


def test_an_overdamped_lever_in_water_keeps_its_share_too():
    # 1 mm x 5 um x 0.2 um of silicon in water: Q = 0.16, overdamped
    model = OpticalBeamDeflection(fluid="water", length=1e-3, width=5e-6, thickness=0.2e-6)
    assert model.quality_factor < 0.5
    k = SILICON_E * model.width * model.thickness ** 3 / (4 * model.length ** 3)
    total = model.thermal_noise(1e6 * model.resonance_frequency, 0.0)
    assert total == pytest.approx(
        math.sqrt(PUBLISHED_FIRST_SHARE * BOLTZMANN * model.temperature / k), rel=1e-3)
    assert any("Q >> 1" in note for note in model.validity(0.0))


def test_near_its_peak_in_air_the_oscillator_is_sader_full_spectrum():
    model = OpticalBeamDeflection(fluid="air")
    f_r, q = model.resonance_frequency, model.quality_factor
    spectrum = thermal_spectrum(model.lever, "air", temperature=model.temperature, modes=1,
                                detector_noise=0.0, points=2 ** 16, averages=1, seed=0,
                                sample_rate=4 * f_r)
    f = spectrum.frequency
    near = np.abs(f - f_r) < 2 * f_r / q
    assert near.sum() > 20
    # the optical lever reports z / chi: its spectrum over the tip's is 1 / chi^2
    full = spectrum.expected[near] * optical_lever_correction(1, 1.0) ** 2
    np.testing.assert_allclose(model.thermal_noise_density(f[near]), full, rtol=0.03)


def test_below_q_five_in_a_fluid_the_readout_says_the_oscillator_is_rough():
    assert OpticalBeamDeflection(fluid="water").quality_factor < LOW_Q
    note = [n for n in OpticalBeamDeflection(fluid="water").operate(0.0).validity
            if "Q >> 1" in n]
    assert len(note) == 1 and "water" in note[0]
    assert OpticalBeamDeflection(fluid="air").operate(0.0).validity == ()
    assert OpticalBeamDeflection().operate(0.0).validity == ()


def test_the_shaker_second_mode_rings_in_the_same_medium():
    model = PiezoAcoustic(fluid="water", drive_ratio=2.0)
    f2, q2 = model.mode_in_medium(2)
    m2 = fluid_mode(model.lever, "water", 2)
    assert (f2, q2) == (m2.resonance_frequency, m2.quality_factor)
    assert f2 < model.lever.resonance_frequency(2)
    # each mode n responds to the base as gamma_n r_n^2 / (1 - r_n^2 + j r_n / Q_n), at f_n and
    # Q_n in the medium; gamma_1 = 1.566 and gamma_2 = -0.868 for a uniform clamped-free beam
    # (Erturk and Inman, J. Intell. Mater. Syst. Struct. 19, 1311 (2008))
    f = model.drive_ratio * model.resonance_frequency
    f1, q1 = model.mode_in_medium(1)

    def response(fn, qn, g):
        r = f / fn
        return g * r * r / (1 - r * r + 1j * r / qn)
    ratio = abs(response(f2, q2, -0.868)) / abs(response(f1, q1, 1.566))
    assert model.mode_2_share() == pytest.approx(ratio, rel=1e-3)


@pytest.mark.parametrize("key", list(PRINCIPLES))
def test_every_principle_takes_every_medium(key):
    for fluid in ("air", "water"):
        model = PRINCIPLES[key](fluid=fluid)
        op = model.operate(model.input_quantity().default, bandwidth=1e3)
        assert math.isfinite(op.sensitivity) and op.resolution.total > 0


def test_a_bad_medium_is_named():
    with pytest.raises(ValueError, match=r"^fluid must be None \(vacuum, the typed Q\) or one of "
                                         r"\['air', 'water'\], got 'oil'"):
        OpticalBeamDeflection(fluid="oil")


def test_the_lock_in_lever_rings_in_its_medium():
    probe = ActiveProbe.build(fluid="water")
    assert probe.resonance_frequency == fluid_mode(probe.sensor.lever, "water", 1) \
        .resonance_frequency
    with pytest.raises(ValueError, match="must share the lever: its medium is 'air'"):
        ActiveProbe(Electrothermal(fluid="air"), Piezoresistive())
    with pytest.raises(ValueError, match="^fluid must be None"):
        ActiveProbe.build(fluid="oil")


def test_at_resonance_the_2_omega_line_grows_with_the_mediums_q():
    # drive at half the resonance: the lever moves at 2 omega = omega_1, where a driven
    # oscillator's amplitude is Q times its static one; the heater's thermal lag at that
    # frequency is nearly the same in vacuum and in air (81.5 and 81.2 kHz)
    typed = lock_in_demo(half_resonance_ratio=1.0)
    air = lock_in_demo(half_resonance_ratio=1.0, fluid="air")
    q_air = ActiveProbe.build(fluid="air").sensor.quality_factor
    q_typed = ActiveProbe.build().sensor.quality_factor
    assert abs(air.truth) / abs(typed.truth) == pytest.approx(q_air / q_typed, rel=0.02)


def test_the_chains_memo_never_hands_one_mediums_drive_to_another():
    # two probes that differ in their medium only, at the same frequency and record: the
    # memo must not hand the first one's transfer function and noise to the second
    f, n, fs = 40e3, 4096, 40e3 * 64
    vacuum, water = ActiveProbe.build(), ActiveProbe.build(fluid="water")
    h_vacuum = chain_module._drive(vacuum, f, n, fs)[4]
    h_water = chain_module._drive(water, f, n, fs)[4]
    freqs = np.fft.rfftfreq(n, 1.0 / fs)
    np.testing.assert_array_equal(h_water, water.deflection_per_power(freqs))
    assert not np.array_equal(h_vacuum, h_water)
    noise_vacuum = chain_module._noises(vacuum, 1e-16, freqs, n, fs, 0)[0]
    noise_water = chain_module._noises(water, 1e-16, freqs, n, fs, 0)[0]
    assert not np.array_equal(noise_vacuum, noise_water)


def test_the_books_figures_for_the_default_lever_in_water():
    # book chapter 2: 81.5 kHz in vacuum, 34.3 kHz and Q ~ 3.9 in water, Brownian motion in
    # 1 kHz from 0.27 to 2.6 pm, above the optical lever's shot noise; each from its formula:
    # k = E w t^3 / (4 L^3), f1 = (1.8751^2 / (2 pi L^2)) sqrt(E t^2 / (12 rho)) (Euler-Bernoulli),
    # the white floor sqrt(0.971 x 4 k_B T B / (k omega Q)) at vacuum's or water's f and Q
    vacuum, water = OpticalBeamDeflection(), OpticalBeamDeflection(fluid="water")
    length, width, t, temperature = vacuum.length, vacuum.width, vacuum.thickness, 295.0
    rho = vacuum.lever.density
    k = SILICON_E * width * t ** 3 / (4 * length ** 3)
    f1 = 1.8751041 ** 2 / (2 * math.pi * length ** 2) * math.sqrt(SILICON_E * t ** 2 / (12 * rho))
    assert round(f1 / 1e3, 1) == 81.5
    m = fluid_mode(water.lever, "water", 1)
    assert round(m.resonance_frequency / 1e3, 1) == 34.3 and round(m.quality_factor, 1) == 3.9

    def floor(f, q):
        return math.sqrt(PUBLISHED_FIRST_SHARE * 4 * BOLTZMANN * temperature * 1e3
                         / (k * 2 * math.pi * f * q))
    assert round(floor(f1, 150.0) * 1e12, 2) == 0.27
    assert round(floor(m.resonance_frequency, m.quality_factor) * 1e12, 1) == 2.6
    assert vacuum.thermal_noise(1e3, 1.0) == pytest.approx(floor(f1, 150.0), rel=2e-3)
    assert water.thermal_noise(1e3, 1.0) == pytest.approx(
        floor(m.resonance_frequency, m.quality_factor), rel=2e-3)
    res = water.resolution(1e3)
    assert res.dominant == "thermal" and res.contributions["shot"] < res.contributions["thermal"]


def test_outside_sader_fit_the_readout_says_the_medium_is_extrapolated():
    # a short, wide, thick lever: Re = rho w^2 omega / (4 eta) beyond Sader's fit (1e4) in air
    from afmsmiler.hydrodynamics import FLUIDS, REYNOLDS_RANGE
    model = OpticalBeamDeflection(fluid="air", length=20e-6, width=100e-6, thickness=10e-6)
    air = FLUIDS["air"]
    re = air.density * model.width ** 2 * 2 * math.pi * model.resonance_frequency \
        / (4 * air.viscosity)
    assert re > REYNOLDS_RANGE[1]
    notes = [n for n in model.operate(0.0).validity if "outside Sader's fit" in n]
    assert len(notes) == 1 and "air" in notes[0]
