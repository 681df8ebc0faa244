"""Module (b)'s exercise checkers: the expected answers come from closed forms, not the model."""
import math

import pytest

from afmsmiler.exercises.transducers import (DEFAULTS, check_bridge_output,
                                             check_length_doubling_sensitivity,
                                             check_quadrature_phase, check_two_omega_power)


def test_length_that_doubles_the_optical_lever_sensitivity():
    # sensitivity = sqrt(8/pi) / w * 3 D / L ~ 1 / L, so half the length doubles it
    assert check_length_doubling_sensitivity(DEFAULTS["length"] / 2)
    assert check_length_doubling_sensitivity(112e-6)          # 0.4 % off: within 2 %
    fb = check_length_doubling_sensitivity(2 * DEFAULTS["length"])
    assert not fb and "L" in str(fb)
    assert not check_length_doubling_sensitivity(DEFAULTS["length"] / math.sqrt(2))
    assert not check_length_doubling_sensitivity(None)
    assert not check_length_doubling_sensitivity("short")
    assert not check_length_doubling_sensitivity(1.0)          # outside the model's range
    assert check_length_doubling_sensitivity(50e-6, reference_length=100e-6)


def test_a_length_in_um_or_mm_is_named_as_a_unit_slip_not_only_as_out_of_range():
    # half the default length (sensitivity ~ 1/L) typed in um or mm: the prefix slip is named
    # (the answer is not given), where the range alone said only "the model takes lengths in"
    half = DEFAULTS["length"] / 2
    for answer, words in ((half * 1e6, "10^6 times"), (half * 1e3, "10^3 times"),
                          (-half, "sign is wrong")):
        fb = check_length_doubling_sensitivity(answer)
        assert not fb and words in str(fb), str(fb)
        assert f"{half:g}" not in str(fb) and f"{half * 1e6:.4g} um" not in str(fb)
    fb = check_length_doubling_sensitivity(1.0)  # no slip of the answer: the range is said
    assert not fb and "the model takes lengths in" in str(fb)


def test_two_omega_power():
    # (V cos wt)^2 / R = V^2 / (2 R) + V^2 / (2 R) cos 2wt: 2^2 / (2 * 1000) = 2 mW
    assert check_two_omega_power(2e-3)
    assert not check_two_omega_power(4e-3)                     # forgot the 1/2
    assert check_two_omega_power(0.5 ** 2 / (2 * 50.0), ac_voltage=0.5, resistance=50.0)
    assert not check_two_omega_power(None)
    assert not check_two_omega_power(math.inf)


def test_bridge_output_against_the_closed_form():
    # default lever: silicon, L = 225 um, w = 28 um, h = 3 um; E = 169 GPa; k = E w h^3 / (4 L^3)
    E, L, w, h = 169e9, 225e-6, 28e-6, 3e-6
    k = E * w * h ** 3 / (4 * L ** 3)
    z = DEFAULTS["deflection"]
    F = k * z
    lr, dj, pi_l, vb = 50e-6, 0.3e-6, 71.8e-11, 2.0
    sigma = -6 * F * (L - lr / 2) / (w * h ** 2) * (1 - dj / h)   # compression on top
    expected = vb / 4 * pi_l * sigma                               # small signal V_b dR / (4 R)
    assert check_bridge_output(expected)
    assert not check_bridge_output(-expected)                      # sign matters
    # a wrong sign is named, and the answer is not given (it printed the exact value)
    fb = check_bridge_output(-expected)
    assert "sign" in fb.message
    for shown in (f"{expected:.4g}", f"{expected:.3g}", f"{expected * 1e6:.3g}"):
        assert shown not in fb.message
    fb = check_bridge_output(-2 * expected)
    assert f"{expected:.4g}" not in fb.message and f"{expected:.3g}" not in fb.message
    fb = check_bridge_output(expected * 1e6)                       # uV typed for V
    assert "10^6" in fb.message or "1e6" in fb.message or "unit" in fb.message
    assert not check_bridge_output(2 * expected)
    assert not check_bridge_output(None)


def test_quadrature_phase():
    assert check_quadrature_phase(-math.pi / 2)
    assert check_quadrature_phase(math.pi / 2)
    assert check_quadrature_phase(3 * math.pi / 2)                 # wraps around
    assert not check_quadrature_phase(0.0)
    assert not check_quadrature_phase(math.pi / 4)                 # 71 % of the best
    assert not check_quadrature_phase(None)


def test_bad_givens_raise():
    with pytest.raises(ValueError, match="^reference_length must be in"):
        check_length_doubling_sensitivity(1e-4, reference_length=-1.0)
    with pytest.raises(ValueError, match="^reference_length must be in"):
        check_length_doubling_sensitivity(1e-4, reference_length=5e-3)   # beyond the model's 1 mm
    with pytest.raises(ValueError, match="^rtol must be in"):
        check_two_omega_power(1.0, rtol=0.0)
    with pytest.raises(ValueError, match="^deflection must be in"):
        check_bridge_output(1.0, deflection=1.0)
    with pytest.raises(ValueError, match="^resistance must be in"):
        check_two_omega_power(1.0, resistance=-5.0)
