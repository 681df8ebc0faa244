"""Bimodal AFM: the two flexural modes of module (a)'s beam, their free response, the second
mode's phase as the compositional channel.

Independent sources: the published clamped-free eigenvalues b_1 L = 1.875104, b_2 L = 4.694091
(Rao, *Vibration of Continuous Systems*, Table 11.1: f_2 / f_1 = 6.267); the modal mass of every
mode of a uniform beam with the tip normalised to 1, m / 4 (the integral of the mode shape's
square is L / 4: Melcher, Hu and Raman, APL 91, 053101 (2007)); the analytic driven harmonic
oscillators for the free motion; for the second mode near the sample, an oscillator whose
stiffness is raised by the force gradient averaged over the first mode's cycle (Garcia and
Proksch, Eur. Polym. J. 49, 1897 (2013)), its phase atan2(k_2 / Q_2, k_eff) at resonance.
"""
import math

import numpy as np
import pytest

from afmsmiler.cantilever import Cantilever
from afmsmiler.modes import TappingLever
from afmsmiler.modes import bimodal
from afmsmiler.modes.bimodal import (FLEXURAL_RATIO, BimodalLever, averaged_gradient,
                                     bimodal_response, modal_stiffness)

LEVER = Cantilever.from_material("silicon", length=125e-6, width=30e-6, thickness=4e-6)


def test_mode_frequency_ratio_is_the_published_eigenvalues():
    assert FLEXURAL_RATIO == pytest.approx((4.694091 / 1.875104) ** 2, rel=1e-6)
    assert FLEXURAL_RATIO == pytest.approx(6.267, abs=1e-3)
    assert LEVER.resonance_frequency(2) / LEVER.resonance_frequency(1) == pytest.approx(
        FLEXURAL_RATIO, rel=1e-12)


@pytest.mark.parametrize("mode", [1, 2, 3])
def test_modal_stiffness_is_a_quarter_of_the_mass_times_w_squared(mode):
    mass = LEVER.density * LEVER.length * LEVER.width * LEVER.thickness
    w = 2 * math.pi * LEVER.resonance_frequency(mode)
    assert modal_stiffness(LEVER, mode) == pytest.approx(mass / 4 * w * w, rel=1e-9)


def test_from_cantilever():
    b = BimodalLever.from_cantilever(LEVER, quality_factor=200.0, quality_factor_2=600.0)
    k1, k2 = b.stiffnesses
    assert k1 == pytest.approx(modal_stiffness(LEVER, 1))
    # the dynamic stiffness of mode 1 is 3 % above the static 3 E J / L^3: (1.8751^4 / 4) / 3
    assert k1 / LEVER.spring_constant == pytest.approx(1.875104 ** 4 / 12, rel=1e-5)
    assert k2 / k1 == pytest.approx(FLEXURAL_RATIO ** 2, rel=1e-9)
    assert b.mode_frequency_ratio == pytest.approx(FLEXURAL_RATIO, rel=1e-12)
    assert b.quality_factors == (200.0, 600.0)


def test_free_response_is_the_sum_of_driven_oscillators():
    b = BimodalLever(TappingLever(quality_factor=50.0), quality_factor_2=150.0)
    (k1, k2), (w1, w2) = b.stiffnesses, b.angular_frequencies
    f1, f2 = b.drive_forces
    for f, w, a0 in ((f1, w1, 10e-9), (f2, w2, 1e-9)):  # both at resonance (W = 1)
        c = sum(1 / (k * (1 - (w / wi) ** 2 + 1j * (w / wi) / q))
                for k, wi, q in ((k1, w1, 50.0), (k2, w2, 150.0)))
        assert abs(f * c) == pytest.approx(a0, rel=1e-12)
        assert b.compliance(w) == pytest.approx(c, rel=1e-12)
    (a1, p1), (a2, p2) = b.free_response()
    assert (a1, a2) == pytest.approx((10e-9, 1e-9), rel=1e-12)
    # each drive mostly moves its own mode: the phase is near 90 deg, shifted by the other mode
    assert math.degrees(p1) == pytest.approx(90.0, abs=0.05)
    assert math.degrees(p2) == pytest.approx(90.0, abs=0.5)


@pytest.mark.slow
def test_time_integration_far_from_the_sample_is_the_driven_oscillators():
    b = BimodalLever(TappingLever(quality_factor=50.0), quality_factor_2=150.0)
    state = bimodal_response(1e-6, b, start_ratio=0.95)  # off the steady state
    assert state.converged
    (a1, p1), (a2, p2) = b.free_response()
    assert state.amplitude_1 == pytest.approx(a1, rel=2e-4)
    assert state.amplitude_2 == pytest.approx(a2, rel=2e-4)
    assert math.degrees(state.phase_1 - p1) == pytest.approx(0.0, abs=0.02)
    assert math.degrees(state.phase_2 - p2) == pytest.approx(0.0, abs=0.02)
    assert abs(state.mean_deflection) < 1e-4 * a1


@pytest.mark.slow
def test_second_mode_phase_is_the_averaged_force_gradient():
    """Near the sample (z_c = 7 nm, A_01 = 10 nm, A_02 = 0.3 nm), the second mode's phase
    follows atan2(k_2 / Q_2, <-dF/dz>) with the gradient averaged over the first mode's
    motion (within 4 deg: A_02 / A_1 = 4 % and the first mode's force harmonics are left out),
    and it separates a 1 GPa from a 10 GPa sample by more than the first mode's phase does."""
    phases = []
    for e in (1e9, 10e9):
        b = BimodalLever(TappingLever(quality_factor=100.0, youngs_modulus=e),
                         quality_factor_2=300.0, free_amplitude_2=0.3e-9)
        state = bimodal_response(7e-9, b)
        assert state.converged
        k_eff = averaged_gradient(7e-9, state.amplitude_1, b,
                                  mean_deflection=state.mean_deflection)
        expected = math.atan2(b.stiffnesses[1] / 300.0, k_eff)
        assert math.degrees(state.phase_2 - expected) == pytest.approx(0.0, abs=4.0)
        phases.append((state.phase_1, state.phase_2))
    d1 = abs(phases[1][0] - phases[0][0])
    d2 = abs(phases[1][1] - phases[0][1])
    assert math.degrees(d2) > 20.0 and d2 > 1.5 * d1


def test_averaged_gradient_far_is_van_der_waals():
    """Out of contact the gradient of -H R / (6 d^2) is -H R / (3 d^3) (attractive: < 0)."""
    b = BimodalLever()
    h, r = b.lever.hamaker_constant, b.lever.radius
    assert averaged_gradient(50e-9, 0.0, b) == pytest.approx(-h * r / (3 * 50e-9 ** 3),
                                                             rel=1e-6)


@pytest.mark.parametrize("kwargs, name", [
    (dict(quality_factor_2=0.0), "quality_factor_2"),
    (dict(free_amplitude_2=-1e-9), "free_amplitude_2"),
    (dict(mode_frequency_ratio=1.0), "mode_frequency_ratio"),
    (dict(mode_stiffness_ratio=0.5), "mode_stiffness_ratio")])
def test_bad_lever_is_named(kwargs, name):
    with pytest.raises(ValueError, match=name):
        BimodalLever(**kwargs)


def test_bad_input_is_named_before_integrating():
    with pytest.raises(TypeError, match="lever"):
        BimodalLever(lever="tapping")
    with pytest.raises(ValueError, match="distance"):
        bimodal_response(0.1e-9)
    with pytest.raises(ValueError, match="distance"):
        bimodal_response(-1e-9)
    with pytest.raises(ValueError, match="max_periods"):
        bimodal_response(1e-6, max_periods=5)
    with pytest.raises(ValueError, match="start_ratio"):
        bimodal_response(1e-6, start_ratio=0.0)
    with pytest.raises(ValueError, match="mode"):
        modal_stiffness(LEVER, 11)
    with pytest.raises(TypeError, match="cantilever"):
        modal_stiffness("lever")
    with pytest.raises(ValueError, match="amplitude"):
        averaged_gradient(5e-9, -1e-9)
    with pytest.raises(ValueError, match="angular_frequency"):
        BimodalLever().compliance(0.0)


def test_parameters_table():
    assert set(bimodal.PARAMETERS) == {"quality_factor_2", "free_amplitude_2",
                                       "mode_frequency_ratio", "mode_stiffness_ratio"}
    for p in bimodal.PARAMETERS.values():
        assert p.low <= p.default <= p.high
    assert np.isclose(bimodal.PARAMETERS["mode_stiffness_ratio"].default, 39.27, atol=0.01)
