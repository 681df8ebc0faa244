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


@pytest.mark.parametrize("key", list(PRINCIPLES))
def test_every_principle_takes_every_medium(key):
    for fluid in ("air", "water"):
        model = PRINCIPLES[key](fluid=fluid)
        op = model.operate(model.input_quantity().default, bandwidth=1e3)
        assert math.isfinite(op.sensitivity) and op.resolution.total > 0


def test_a_bad_medium_is_named():
    with pytest.raises(ValueError, match=r"^fluid must be one of .*'air'.*'water'.*got 'oil'"):
        OpticalBeamDeflection(fluid="oil")


def test_the_lock_in_lever_rings_in_its_medium():
    probe = ActiveProbe.build(fluid="water")
    assert probe.resonance_frequency == fluid_mode(probe.sensor.lever, "water", 1) \
        .resonance_frequency
    with pytest.raises(ValueError, match="must share the lever: its medium is 'air'"):
        ActiveProbe(Electrothermal(fluid="air"), Piezoresistive())
    with pytest.raises(ValueError, match="^fluid must be one of"):
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
    lock_in_demo(fluid=None)
    cached = lock_in_demo(fluid="air")   # after the vacuum run, with its drive in the memo
    chain_module._DRIVES.clear()
    chain_module._NOISES.clear()
    fresh = lock_in_demo(fluid="air")
    assert cached.truth == fresh.truth
    np.testing.assert_array_equal(cached.run.output, fresh.run.output)
