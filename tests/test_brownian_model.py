"""Module (a)'s Brownian motion against independent sources: the modal shares of k_B T / k from
mpmath's roots of cos(x) cosh(x) = -1 and the sum rule, Butt and Jaschke's published 0.971, the
oscillator response against python-control, the spectra against scipy's quadrature (equipartition)
and the band integral's antiderivative against sympy."""
import math

import control
import mpmath
import numpy as np
import pytest
import sympy as sp
from scipy import integrate

from afmsmiler.brownian import (BOLTZMANN, QUALITY_FACTOR, TEMPERATURE, deflection_variance,
                                mechanical_response, mode_share, thermal_deflection_noise,
                                thermal_noise_density)
from afmsmiler.cantilever import MAX_MODE, Cantilever
from afmsmiler.transducers import Electromagnetic, OpticalBeamDeflection

LEVER = Cantilever.from_material("silicon", length=225e-6, width=28e-6, thickness=3e-6)


def _root_by_mpmath(n):
    """b_n L: the n-th root of cos(x) cosh(x) + 1 = 0 (30 digits), independent of the code's
    (divided by cosh(x), which keeps the residual well scaled for large n)."""
    mpmath.mp.dps = 30
    x = mpmath.findroot(lambda x: mpmath.cos(x) + 1 / mpmath.cosh(x), (n - 0.5) * mpmath.pi)
    assert abs(mpmath.cos(x) * mpmath.cosh(x) + 1) < mpmath.mpf(10) ** -20 * mpmath.cosh(x)
    return x


def _share_by_mpmath(n):
    return float(12 / _root_by_mpmath(n) ** 4)


#: Butt and Jaschke, Nanotechnology 6, 1 (1995): the first mode of a point-loaded rectangular
#: lever holds 0.971 of k_B T / k (their Table 1 and text), the second 0.0246 ~ 0.025.
PUBLISHED_FIRST_SHARE = 0.971


def test_mode_shares_against_mpmath_and_the_published_value():
    for n in (1, 2, 3, 7, 20):
        assert mode_share(n) == pytest.approx(_share_by_mpmath(n), rel=1e-12)
    # the published share, to the three digits printed
    assert round(mode_share(1), 3) == PUBLISHED_FIRST_SHARE
    assert mode_share(2) == pytest.approx(0.0247, abs=1e-4)


def test_mode_shares_sum_to_one():
    # the sum rule: sum_n 12 / (b_n L)^4 = 1 (all modes give the static spring's k_B T / k).
    # The tail beyond MAX_MODE, with b_n L ~ (n - 1/2) pi, is 12 / pi^4 sum 1/(n - 1/2)^4.
    mpmath.mp.dps = 30
    tail = 12 / mpmath.pi ** 4 * mpmath.nsum(lambda n: 1 / (n - 0.5) ** 4,
                                             [MAX_MODE + 1, mpmath.inf])
    total = sum(mode_share(n) for n in range(1, MAX_MODE + 1))
    assert total + float(tail) == pytest.approx(1.0, abs=1e-12)
    assert sum(_share_by_mpmath(n) for n in range(1, 6)) + float(
        12 / mpmath.pi ** 4 * mpmath.nsum(lambda n: 1 / (n - 0.5) ** 4, [6, mpmath.inf])) \
        == pytest.approx(1.0, abs=2e-6)  # the asymptotic roots are that close from n = 6 on


def test_deflection_variance_is_the_mode_share_of_equipartition():
    k_t = BOLTZMANN * 300.0 / LEVER.spring_constant
    assert deflection_variance(LEVER, temperature=300.0) == pytest.approx(k_t, rel=1e-15)
    assert deflection_variance(LEVER, temperature=300.0, mode=1) == pytest.approx(
        _share_by_mpmath(1) * k_t, rel=1e-12)


def test_mechanical_response_is_a_damped_oscillator():
    # python-control: G(s) = w1^2 / (s^2 + (w1/Q) s + w1^2)
    f1, q = 80e3, 150.0
    w1 = 2 * math.pi * f1
    sys = control.tf([w1 ** 2], [1, w1 / q, w1 ** 2])
    f = np.array([0.0, 1e3, 40e3, 79e3, f1, 81e3, 300e3])
    np.testing.assert_allclose(mechanical_response(f, resonance_frequency=f1, quality_factor=q),
                               sys(2j * math.pi * f), rtol=1e-12)


@pytest.mark.parametrize("mode", [1, 2, 3])
def test_each_mode_spectrum_integrates_to_its_share(mode):
    # equipartition per mode: int_0^inf S_n(f) df = share_n k_B T / k (scipy quadrature)
    fn = LEVER.resonance_frequency(mode)
    total, _ = integrate.quad(
        lambda f: float(thermal_noise_density(LEVER, [f], quality_factor=30.0, temperature=300.0,
                                              mode=mode)[0]),
        0, np.inf, points=None, limit=500)
    ref = _share_by_mpmath(mode) * BOLTZMANN * 300.0 / LEVER.spring_constant
    assert total == pytest.approx(ref, rel=1e-6)
    # and the closed-form band integral over everything agrees
    assert thermal_deflection_noise(LEVER, quality_factor=30.0, temperature=300.0,
                                    bandwidth=1e6 * fn, low_frequency=0.0, mode=mode) ** 2 \
        == pytest.approx(ref, rel=1e-6)


@pytest.mark.slow  # sympy derivatives and quadratures at six Q, ~1 s
def test_band_integral_of_the_brownian_spectrum():
    # the closed-form antiderivative differentiates back to |H|^2 (sympy, 30 digits)
    r, q = sp.symbols("r Q", positive=True)
    b = sp.sqrt(4 - 1 / q ** 2)
    x = b * r / (1 + r ** 2)
    antiderivative = (r / (2 * (1 + r ** 2)) * sp.atanh(x) / x
                      + q / 2 * sp.atan2(r, q * (1 - r ** 2)))
    residual = sp.diff(antiderivative, r) - 1 / ((1 - r ** 2) ** 2 + r ** 2 / q ** 2)
    for qv, rv in (("0.51", "0.3"), ("0.7", "2"), ("30", "0.99"), ("10000", "1.0001"),
                   ("150", "7")):
        assert abs(sp.N(residual.subs({q: sp.Rational(qv), r: sp.Rational(rv)}), 30)) < 1e-20
    # overdamped (Q < 1/2): b = j c, atanh(x) / x -> atan(y) / y, y = c r / (1 + r^2)
    c = sp.sqrt(1 / q ** 2 - 4)
    y = c * r / (1 + r ** 2)
    overdamped = (r / (2 * (1 + r ** 2)) * sp.atan(y) / y
                  + q / 2 * sp.atan2(r, q * (1 - r ** 2)))
    residual = sp.diff(overdamped, r) - 1 / ((1 - r ** 2) ** 2 + r ** 2 / q ** 2)
    for qv, rv in (("0.49", "0.3"), ("0.1", "2"), ("0.3", "0.99"), ("1/100", "50")):
        assert abs(sp.N(residual.subs({q: sp.Rational(qv), r: sp.Rational(rv)}), 30)) < 1e-20
    # the band noise against scipy's quadrature of S_0 |H|^2 (python-control's H), first mode
    share = _share_by_mpmath(1)
    for qv in (0.1, 0.3, 0.5, 0.7, 30.0, 1e4):
        # an overdamped Q is a fluid's (the transducers take it from their medium), so below
        # 1/2 the lever's spectrum is asked of module (a) directly
        model = OpticalBeamDeflection(quality_factor=max(qv, 0.5))
        f1 = model.resonance_frequency
        s0 = share * 4 * BOLTZMANN * model.temperature / (model.spring_constant * 2 * math.pi
                                                            * f1 * qv)
        w1 = 2 * math.pi * f1
        sys = control.tf([w1 ** 2], [1, w1 / qv, w1 ** 2])
        for lo, hi in ((1.0, 1e3), (0.5 * f1, 1.5 * f1), (0.0, 3 * f1), (2 * f1, 20 * f1)):
            ref, _ = integrate.quad(lambda f: s0 * abs(sys(2j * math.pi * f)) ** 2, lo, hi,
                                    points=[p for p in (f1,) if lo < p < hi], limit=2000,
                                    epsabs=0, epsrel=1e-11)
            assert thermal_deflection_noise(
                model.lever, quality_factor=qv, temperature=model.temperature,
                bandwidth=hi - lo, low_frequency=lo) == pytest.approx(math.sqrt(ref), rel=1e-8)
            if qv < 0.5:
                continue
            assert model.thermal_noise(hi - lo, lo) == pytest.approx(math.sqrt(ref), rel=1e-8)
            np.testing.assert_allclose(model.thermal_noise_density([lo, hi]),
                                       [s0 * abs(sys(2j * math.pi * f)) ** 2 for f in (lo, hi)],
                                       rtol=1e-12)
    # all frequencies: the first mode's share of equipartition, k = E w h^3 / (4 L^3)
    model = OpticalBeamDeflection(quality_factor=150.0)
    k = 169e9 * model.width * model.thickness ** 3 / (4 * model.length ** 3)
    assert model.thermal_noise(1e6 * model.resonance_frequency, 0.0) == pytest.approx(
        math.sqrt(PUBLISHED_FIRST_SHARE * BOLTZMANN * model.temperature / k), rel=1e-3)
    assert model.thermal_noise(1e6 * model.resonance_frequency, 0.0) == pytest.approx(
        math.sqrt(share * BOLTZMANN * model.temperature / k), rel=1e-6)
    # a sensor's resolution counts the band's motion, resonance included; a drive, the white floor
    wide = model.resolution(2 * model.resonance_frequency)
    assert wide.contributions["thermal"] == pytest.approx(
        model.thermal_noise(2 * model.resonance_frequency, 1.0), rel=1e-12)
    assert wide.contributions["thermal"] > 10 * model.thermal_noise(2 * model.resonance_frequency)
    drive = Electromagnetic(quality_factor=150.0).resolution(2 * model.resonance_frequency)
    assert drive.contributions["thermal"] == pytest.approx(
        model.thermal_noise(2 * model.resonance_frequency) / Electromagnetic().sensitivity(),
        rel=1e-12)
    with pytest.raises(ValueError, match=r"^quality_factor must be in \(0, 100000\]"):
        thermal_deflection_noise(model.lever, quality_factor=0.0, temperature=300.0,
                                 bandwidth=1e3, low_frequency=0.0)
    with pytest.raises(ValueError, match="^low_frequency must be in"):
        model.thermal_noise(1e3, -1.0)


def test_extreme_bands_stay_finite():
    # a band reaching past 1e308 Hz: (f_a + B) / f_n overflowed and F(inf) / inf gave NaN
    full = math.sqrt(mode_share(1) * BOLTZMANN * 295.0 / LEVER.spring_constant)
    assert thermal_deflection_noise(LEVER, bandwidth=1e308, low_frequency=0.0) == \
        pytest.approx(full, rel=1e-9)
    assert thermal_deflection_noise(LEVER, bandwidth=1e308, low_frequency=1e308) == 0.0
    assert math.isfinite(thermal_deflection_noise(LEVER, bandwidth=1e308))


def test_parameters_and_defaults():
    assert QUALITY_FACTOR.default == 150.0 and TEMPERATURE.default == 295.0
    assert QUALITY_FACTOR.unit == "" and TEMPERATURE.unit == "K"
    # defaults are bound from the Parameters
    assert thermal_deflection_noise(LEVER, bandwidth=1e3) == thermal_deflection_noise(
        LEVER, quality_factor=150.0, temperature=295.0, bandwidth=1e3)


BAD = [
    (lambda v: mechanical_response(v, resonance_frequency=1e5, quality_factor=100.0), "f",
     (math.nan, -1.0)),
    (lambda v: mechanical_response(1e3, resonance_frequency=v, quality_factor=100.0),
     "resonance_frequency", (0.0, math.inf)),
    (lambda v: mechanical_response(1e3, resonance_frequency=1e5, quality_factor=v),
     "quality_factor", (-1.0, math.nan)),
    (lambda v: thermal_deflection_noise(LEVER, bandwidth=v), "bandwidth", (0.0, math.nan)),
    (lambda v: thermal_deflection_noise(LEVER, quality_factor=v, bandwidth=1.0), "quality_factor",
     (0.0, math.inf)),
    (lambda v: thermal_deflection_noise(LEVER, temperature=v, bandwidth=1.0), "temperature",
     (-1.0, math.nan)),
    (lambda v: thermal_deflection_noise(LEVER, bandwidth=1.0, mode=v), "mode", (0, 51, 1.5)),
    (lambda v: thermal_noise_density(LEVER, v), "f", (-1.0, [math.inf])),
    (lambda v: deflection_variance(LEVER, temperature=v), "temperature", (0.0, 1e4)),
    (lambda v: mode_share(v), "mode", (0, MAX_MODE + 1)),
]


@pytest.mark.parametrize("call, name, values", BAD, ids=[c[1] for c in BAD])
def test_bad_input_names_the_parameter(call, name, values):
    for v in values:
        with pytest.raises((ValueError, TypeError), match=f"^{name}"):
            call(v)


def test_lever_must_be_a_cantilever():
    for call in (lambda: thermal_deflection_noise(1.0, bandwidth=1.0),
                 lambda: thermal_noise_density("lever", [1.0]),
                 lambda: deflection_variance(None)):
        with pytest.raises(TypeError, match="^lever must be"):
            call()
