"""Module (b)'s piezo-acoustic base excitation against mpmath's modal integrals, the analytic
mode shape and python-control."""
import math

import control
import mpmath
import numpy as np
import pytest

from afmsmiler.transducers import PiezoAcoustic
from afmsmiler.transducers.acoustic import mode_slope_factor, participation_factor


# --- piezo-acoustic base excitation --------------------------------------------------------------
def _mode_by_mpmath(n):
    """Mode n of a clamped-free beam on [0, 1] in 30-digit arithmetic, independent of module (a):
    b from cos(b) cosh(b) = -1 by mpmath.findroot, phi = cosh bx - cos bx - s (sinh bx - sin bx)
    with s = (cosh b + cos b) / (sinh b + sin b) (Rao, Mechanical Vibrations, sec. 8.5)."""
    b = mpmath.findroot(lambda x: mpmath.cos(x) * mpmath.cosh(x) + 1, (n - 0.5) * mpmath.pi)
    s = (mpmath.cosh(b) + mpmath.cos(b)) / (mpmath.sinh(b) + mpmath.sin(b))
    return b, (lambda x: mpmath.cosh(b * x) - mpmath.cos(b * x)
               - s * (mpmath.sinh(b * x) - mpmath.sin(b * x)))


def _gamma_by_mpmath(n):
    """gamma_n = phi(1) int phi / int phi^2 (the mode normalised to 1 at the tip), by quadrature."""
    with mpmath.workdps(30):
        _, phi = _mode_by_mpmath(n)
        return float(phi(1) * mpmath.quad(phi, [0, 1]) / mpmath.quad(lambda x: phi(x) ** 2, [0, 1]))


def test_participation_factor_against_the_modal_integral():
    # Erturk and Inman, J. Intell. Mater. Syst. Struct. 19, 1311 (2008): mu_1 = 1.566 (relative
    # transverse motion at the tip, mode 1, no tip mass); then the modal integral to round-off
    assert participation_factor() == pytest.approx(1.566, abs=5e-4)
    assert participation_factor(1) == pytest.approx(_gamma_by_mpmath(1), rel=1e-13)
    assert participation_factor(2) == pytest.approx(_gamma_by_mpmath(2), rel=1e-13)
    # closed form of the same integrals: int phi = 2 s / b, int phi^2 = 1, phi(1) = 2 (mode 1)
    with mpmath.workdps(30):
        b, phi = _mode_by_mpmath(1)
        s = (mpmath.cosh(b) + mpmath.cos(b)) / (mpmath.sinh(b) + mpmath.sin(b))
        assert participation_factor() == pytest.approx(float(4 * s / b), rel=1e-13)
    with pytest.raises(ValueError, match="^mode must be an integer"):
        participation_factor(0)


def test_mode_slope_factor_against_the_analytic_mode_shape():
    # L phi'(L) / phi(L) by mpmath's numerical derivative of the independently built mode shape
    with mpmath.workdps(30):
        _, phi = _mode_by_mpmath(1)
        ref = float(mpmath.diff(phi, 1) / phi(1))
    assert mode_slope_factor() == pytest.approx(ref, rel=1e-14)
    assert 1.37 < mode_slope_factor() < 1.5    # flatter at the end than the static shape (1.5)


def test_base_excitation_against_python_control():
    model = PiezoAcoustic(quality_factor=80.0, shaker_coefficient=1e-9)
    w1 = 2 * math.pi * model.resonance_frequency
    gamma = _gamma_by_mpmath(1)
    # relative motion u = x - y, projected on mode 1: u'' + (w1/Q) u' + w1^2 u = -gamma y''
    # -> U/Y = -gamma s^2 / (s^2 + w1/Q s + w1^2) (Rao, Mechanical Vibrations, base excitation)
    sys = control.tf([-gamma, 0, 0], [1, w1 / 80.0, w1 ** 2])
    f = np.array([10.0, 1e3, 0.5, 0.9, 1.0, 1.1, 3.0])
    f[2:] *= model.resonance_frequency
    np.testing.assert_allclose(model.base_transfer(f), sys(2j * math.pi * f), rtol=1e-12)
    fr = model.frequency_response(f)
    np.testing.assert_allclose(fr.response, 1e-9 * model.base_transfer(f), rtol=1e-12)
    # resonance gain gamma Q at -90 degrees, DC gain 0 (AC only), high-frequency gain -gamma
    h1 = model.base_transfer(model.resonance_frequency)
    assert h1 == pytest.approx(-1j * gamma * 80, rel=1e-12)
    assert model.base_transfer(0.0) == 0
    r = 1e4
    assert model.base_transfer(r * model.resonance_frequency) == pytest.approx(
        -gamma * r * r / (r * r - 1 - 1j * r / 80), rel=1e-12)
    # the sensitivity at the drive frequency, d |U/Y| (half the resonance here)
    r = 0.5
    assert model.replace(drive_ratio=r).sensitivity() == pytest.approx(
        1e-9 * gamma * r * r / abs(1 - r * r + 1j * r / 80.0), rel=1e-12)
    # the chain at the drive frequency: amplitude = d V |U/Y|; the slope follows the mode shape
    chain = model.replace(drive_ratio=1.0).chain([2.0])
    assert chain.output.values[0] == pytest.approx(2.0 * 1e-9 * gamma * 80, rel=1e-12)
    assert chain.stage("base_amplitude").values[0] == pytest.approx(2e-9, rel=1e-15)
    assert chain.stage("slope").values[0] == pytest.approx(
        mode_slope_factor() * chain.output.values[0] / model.length, rel=1e-15)


def test_base_excitation_says_when_mode_2_matters():
    # two modes, each u_n / Y = gamma_n r_n^2 / (1 - r_n^2 + j r_n / Q), r_n = f / f_n, and
    # f2 / f1 = (b2 / b1)^2 = 6.267 (Rao, Mechanical Vibrations, Table 8.4)
    with mpmath.workdps(30):
        ratio = float((_mode_by_mpmath(2)[0] / _mode_by_mpmath(1)[0]) ** 2)
    g1, g2, q = _gamma_by_mpmath(1), _gamma_by_mpmath(2), 150.0
    for r in (0.5, 1.0, 2.0, 3.0):
        model = PiezoAcoustic(drive_ratio=r, quality_factor=q)
        r2 = r / ratio
        share = abs(g2 * r2 ** 2 / (1 - r2 ** 2 + 1j * r2 / q)) / abs(
            g1 * r ** 2 / (1 - r ** 2 + 1j * r / q))
        assert model.mode_2_share() == pytest.approx(share, rel=1e-9)
        assert bool(model.validity(0.1)) == (share > 0.05)
    assert PiezoAcoustic(drive_ratio=1.0).validity(1.0) == ()
    assert "second mode" in PiezoAcoustic(drive_ratio=3.0).validity(1.0)[0]


def test_base_transfer_tends_to_minus_the_participation_factor_far_above_resonance():
    # before: NaN at f = 1e300 (r^2 = inf times a response of 0); the limit of
    # gamma r^2 / (1 - r^2 + j r / Q) as r -> inf is -gamma: the tip stays still in space
    model = PiezoAcoustic()
    f = np.array([1e300, 1.7e308])
    u = model.base_transfer(f)
    assert np.isfinite(u).all()
    np.testing.assert_allclose(u, -participation_factor(), rtol=1e-15)
    assert np.isfinite(model.frequency_response(f).response).all()
    # and the same function on both sides of resonance, where the formula switches
    r = np.array([0.5, 0.999, 1.0, 1.001, 2.0, 1e3])
    q = model.quality_factor
    expected = participation_factor() * r * r / (1 - r * r + 1j * r / q)
    np.testing.assert_allclose(model.base_transfer(r * model.resonance_frequency), expected,
                               rtol=1e-12)
