"""Module (b)'s bulk optical sensors (optical beam deflection, astigmatic detection,
interferometry) against sympy, numerical integration over the detector and shot-noise formulas."""
import math

import numpy as np
import pytest
import sympy as sp
from scipy import integrate

from afmsmiler.transducers import (AstigmaticDetection, Interferometer, OpticalBeamDeflection,
                                   Optomechanical)


# --- optical beam deflection ---------------------------------------------------------------------
def test_free_end_slope_is_three_halves_z_over_l():
    model = OpticalBeamDeflection()
    lever = model.lever
    force = 1e-8
    z = float(lever.deflection(lever.length, force))
    assert float(lever.slope(lever.length, force)) == pytest.approx(1.5 * z / lever.length,
                                                                    rel=1e-13)
    chain = model.chain([z])
    assert chain.stage("slope").values[0] == pytest.approx(float(lever.slope(lever.length, force)),
                                                           rel=1e-13)


def test_optical_lever_angle_to_spot_factor_is_twice_the_path():
    # reflection doubles the angle: spot travel / tilt -> 2 D as the tilt -> 0 (law of reflection)
    model = OpticalBeamDeflection(optical_path=25e-3)
    for theta in (1e-7, 1e-6, 1e-5):
        assert model.spot_displacement(theta) / theta == pytest.approx(2 * 25e-3, rel=1e-9)


def test_split_detector_signal_against_numerical_integration():
    # the fraction of a Gaussian spot (1/e^2 radius w) on each half of a split photodiode,
    # integrated numerically over the half planes
    model = OpticalBeamDeflection(spot_radius=0.4e-3)
    w = model.spot_radius
    for s in (0.0, 0.05e-3, 0.2e-3, -0.3e-3, 0.6e-3):
        def intensity(u):  # u = y / w; the x integral cancels in the ratio
            return np.exp(-2 * (u - s / w) ** 2)
        upper, _ = integrate.quad(intensity, 0, np.inf)
        lower, _ = integrate.quad(intensity, -np.inf, 0)
        assert float(model.split_signal(s)) == pytest.approx((upper - lower) / (upper + lower),
                                                             abs=1e-10)


def test_optical_lever_sensitivity_against_sympy():
    z, L, D, w = sp.symbols("z L D w", positive=True)
    theta = sp.Rational(3, 2) * z / L            # end-loaded lever
    s = D * sp.tan(2 * theta)                    # reflected beam turned by 2 theta
    signal = sp.erf(sp.sqrt(2) * s / w)          # Gaussian spot on a split detector
    slope = sp.diff(signal, z)
    assert sp.simplify(slope.subs(z, 0) - sp.sqrt(8 / sp.pi) * 3 * D / (w * L)) == 0
    model = OpticalBeamDeflection(optical_path=40e-3, spot_radius=0.3e-3, length=150e-6)
    subs = {L: model.length, D: model.optical_path, w: model.spot_radius}
    for at in (0.0, 50e-9, -300e-9, 1e-6):
        ref = float(slope.subs(subs).subs(z, at))
        assert model.sensitivity(at=at) == pytest.approx(ref, rel=1e-12)
    # and the chain's output is the same function
    zs = np.array([-1e-6, 2e-7, 1.5e-6])
    ref = [float(signal.subs(subs).subs(z, v)) for v in zs]
    np.testing.assert_allclose(model.respond(zs), ref, rtol=1e-12)


def test_optical_lever_sensitivity_scales_as_path_over_length():
    base = OpticalBeamDeflection()
    assert base.replace(length=base.length / 2).sensitivity() == pytest.approx(
        2 * base.sensitivity(), rel=1e-12)
    assert base.replace(optical_path=3 * base.optical_path).sensitivity() == pytest.approx(
        3 * base.sensitivity(), rel=1e-12)


def test_optical_lever_shot_noise():
    # Schottky: i_n = sqrt(2 q I B); normalised by I it is sqrt(2 q B / I)
    model = OpticalBeamDeflection(power=1e-3, responsivity=0.5)
    res = model.resolution(1e4)
    current = 0.5e-3
    slope = math.sqrt(8 / math.pi) * 3 * model.optical_path / (model.spot_radius * model.length)
    expected = math.sqrt(2 * 1.602176634e-19 * current * 1e4) / current / slope
    assert res.contributions["shot"] == pytest.approx(expected, rel=1e-12)
    assert res.total == pytest.approx(math.hypot(expected, res.contributions["thermal"]), rel=1e-12)


def test_astigmatic_and_interferometer_shot_noise():
    # the displacement whose signal equals the photocurrent's shot noise sqrt(2 q I B) (Schottky)
    q_e, bw = 1.602176634e-19, 1e3
    ast = AstigmaticDetection(power=200e-6, responsivity=0.5)
    a, zr = ast.astigmatic_distance / 2, math.pi * ast.waist ** 2 / ast.wavelength
    slope = 8 * a / (math.pi * (zr ** 2 + a ** 2))      # FES slope at focus (sympy test above)
    expected = math.sqrt(2 * q_e * 0.5 * 200e-6 * bw) / (0.5 * 200e-6) / slope
    assert ast.resolution(bw).contributions["shot"] == pytest.approx(expected, rel=1e-12)
    # interferometer at quadrature: delta_d = lambda / (4 pi V) sqrt(2 q B / (R P0))
    # (Rugar, Mamin and Guethner, Appl. Phys. Lett. 55, 2588 (1989))
    ifm = Interferometer(wavelength=1310e-9, visibility=0.8, power=100e-6, responsivity=0.9)
    expected = 1310e-9 / (4 * math.pi * 0.8) * math.sqrt(2 * q_e * bw / (0.9 * 100e-6))
    assert ifm.resolution(bw).contributions["shot"] == pytest.approx(expected, rel=1e-12)
    # off quadrature (phi = 0): the mean power P0 (1 + V) and the slope vanishes
    assert ifm.replace(phase=0.0).resolution(bw).contributions["shot"] > 1e6 * expected


def test_optomechanical_shot_noise():
    # at Delta_0 = -gamma/2 the transmission is P (1 - D/2) and the slope D P G / gamma
    q_e, bw = 1.602176634e-19, 1e3
    model = Optomechanical(power=50e-6, dip_depth=0.6, coupling=2e18, responsivity=0.8)
    gamma = 299792458.0 / (model.wavelength * model.optical_q)
    current = 0.8 * 50e-6 * (1 - 0.6 / 2)
    expected = math.sqrt(2 * q_e * current * bw) / 0.8 / (0.6 * 50e-6 * 2e18 / gamma)
    assert model.resolution(bw).contributions["shot"] == pytest.approx(expected, rel=1e-12)


# --- astigmatic detection ------------------------------------------------------------------------
def _fes_by_integration(wx, wy):
    """((A+C)-(B+D))/sum for an elliptical Gaussian on quadrants split along the diagonals."""
    def density(phi):  # angular density of an elliptical Gaussian (integrated over radius)
        return 1.0 / ((math.cos(phi) / wx) ** 2 + (math.sin(phi) / wy) ** 2)
    total, _ = integrate.quad(density, 0, 2 * math.pi, limit=200)
    # |x| > |y| sectors: phi in (-pi/4, pi/4) and (3pi/4, 5pi/4)
    ac, _ = integrate.quad(density, -math.pi / 4, math.pi / 4, limit=200)
    ac *= 2
    return (2 * ac - total) / total


def test_astigmatic_fes_against_integration_over_quadrants():
    model = AstigmaticDetection()
    for d in (0.0, 0.3e-6, -0.7e-6, 1.5e-6, 6e-6):
        wx, wy = model.spot_radii(d)
        # the model names A + C the pair along the y axis of the spot, hence the sign
        assert float(model.focus_error(d)) == pytest.approx(-_fes_by_integration(wx, wy),
                                                            abs=1e-9)


@pytest.mark.slow  # a sympy derivation or a heat-equation reference, ~1-4 s
def test_astigmatic_s_curve_and_slope_against_sympy():
    d, a, zr = sp.symbols("d a z_R", positive=True)
    wx = sp.sqrt(1 + ((2 * d - a) / zr) ** 2)
    wy = sp.sqrt(1 + ((2 * d + a) / zr) ** 2)
    fes = 4 / sp.pi * sp.atan(wy / wx) - 1
    slope0 = sp.simplify(sp.diff(fes, d).subs(d, 0))
    assert sp.simplify(slope0 - 8 * a / (sp.pi * (zr ** 2 + a ** 2))) == 0
    # the largest slope at focus is at a = z_R: 4 / (pi z_R)
    best = sp.solve(sp.diff(slope0, a), a)
    assert best == [zr] and sp.simplify(slope0.subs(a, zr) - 4 / (sp.pi * zr)) == 0
    model = AstigmaticDetection()
    subs = {a: model.astigmatic_distance / 2, zr: math.pi * model.waist ** 2 / model.wavelength}
    dslope = sp.lambdify(d, sp.diff(fes, d).subs(subs))
    for at in (0.0, 0.4e-6, -1.1e-6):
        assert model.sensitivity(at=at) == pytest.approx(float(dslope(at)), rel=1e-10)
    # an S-curve: odd, zero in focus, back towards zero far away, linear range of a few um
    z = np.linspace(-10e-6, 10e-6, 2001)
    f = model.focus_error(z)
    np.testing.assert_allclose(f, -f[::-1], atol=1e-12)
    assert abs(float(model.focus_error(0.0))) < 1e-15
    assert np.all(np.diff(f[np.argmax(f):]) < 0)
    assert float(model.focus_error(200e-6)) < 0.05 * f.max()
    # the extrema: d(w_y / w_x)^2 / dd = 0 at 2 d = sqrt(a^2 + z_R^2) (sympy), a few um here
    ratio2 = ((1 + ((2 * d + a) / zr) ** 2) / (1 + ((2 * d - a) / zr) ** 2))
    (extremum,) = sp.solve(sp.numer(sp.together(sp.diff(ratio2, d))), d)
    assert sp.simplify(extremum - sp.sqrt(a ** 2 + zr ** 2) / 2) == 0
    peak = float(extremum.subs(subs))
    assert 0.5e-6 < peak < 5e-6
    assert model.sensitivity(at=peak) == pytest.approx(0.0, abs=1e-9 * model.sensitivity())
    assert z[np.argmax(f)] == pytest.approx(peak, abs=z[1] - z[0])


# --- interferometry ------------------------------------------------------------------------------
def test_interferometer_quadrature_slope_and_nonlinearity():
    model = Interferometer(wavelength=633e-9, visibility=0.9, power=200e-6)
    # textbook: dP/dd at quadrature = 4 pi V P0 / lambda (Rugar et al. 1989)
    assert model.sensitivity() == pytest.approx(4 * math.pi * 0.9 * 200e-6 / 633e-9, rel=1e-12)
    h = 1e-12
    numerical = (model.fringe(h) - model.fringe(-h)) / (2 * h)
    assert model.sensitivity() == pytest.approx(float(numerical), rel=1e-6)
    # a quarter wavelength of travel further (phase + pi) the slope reverses; lambda/8 -> 0
    assert model.sensitivity(at=633e-9 / 4) == pytest.approx(-model.sensitivity(), rel=1e-9)
    assert abs(model.sensitivity(at=633e-9 / 8)) < 1e-9 * model.sensitivity()
    # the fringe repeats every lambda / 2 of displacement
    np.testing.assert_allclose(model.fringe(0.1e-6 + 633e-9 / 2), model.fringe(0.1e-6), rtol=1e-12)
    # off quadrature (phi = 0) the small-signal slope vanishes: the nonlinearity
    assert abs(model.replace(phase=0.0).sensitivity()) < 1e-20
