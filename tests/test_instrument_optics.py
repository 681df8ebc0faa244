"""The paraxial optics of the OBD head, against independent sources.

Ray matrices against sympy's product of the textbook matrices; the fold mirror against the
first-order law (2 phi in plane, 2 psi cos i out of it) and the exact in-plane rotation; the
focused waist and the beam's growth against the complex beam parameter q propagated through the
lens (Saleh and Teich, *Fundamentals of Photonics*, sec. 3.2: 1/q' = 1/q - 1/f, q(z) = q0 + z,
w^2 = -lambda / (pi Im(1/q))) and a numerical minimum; the Gaussian shares and moments against
scipy's quadrature of the intensity exp(-2 x^2 / w^2).
"""
import math

import numpy as np
import pytest
import sympy as sp
from scipy.integrate import dblquad, quad
from scipy.optimize import minimize_scalar

from afmsmiler.instrument.optics import (beam_radius_at, focal_plane_ray, focused_waist,
                                         free_space, interval_fraction, interval_moments,
                                         mirror_deviation, rayleigh_range, rectangle_fraction,
                                         thin_lens)

LAMBDA = 670e-9


def _gauss(x, m, w):
    return math.exp(-2 * (x - m) ** 2 / w ** 2)


def test_focal_plane_matrix_is_sympys_product():
    f = sp.symbols("f", positive=True)
    space = sp.Matrix([[1, f], [0, 1]])
    lens = sp.Matrix([[1, 0], [-1 / f, 1]])
    m = sp.simplify(space * lens * space)
    assert m == sp.Matrix([[0, f], [-1 / f, 0]])  # x = f theta, slope 0: telecentric
    fv = 20e-3
    num = free_space(fv) @ thin_lens(fv) @ free_space(fv)
    np.testing.assert_allclose(num, np.array(m.subs(f, fv), dtype=float), atol=1e-15)
    x, slope = focal_plane_ray([0.01, -0.02], fv)
    np.testing.assert_allclose(x, [fv * 0.01, -fv * 0.02], rtol=1e-14)
    np.testing.assert_allclose(slope, 0.0, atol=1e-15)


@pytest.mark.parametrize("incidence", [math.pi / 4, math.radians(30)])
def test_mirror_deviation_first_order(incidence):
    eps = 1e-5
    u, w = mirror_deviation(eps, 0.0, incidence)
    assert u == pytest.approx(2 * eps, rel=1e-8) and w == pytest.approx(0.0, abs=1e-15)
    u, w = mirror_deviation(0.0, eps, incidence)
    assert w == pytest.approx(2 * eps * math.cos(incidence), rel=1e-6)
    assert abs(u) < 1e-9  # second order only


def test_mirror_in_plane_tilt_is_exact_double_angle():
    # a rotation about the normal of the plane of incidence turns the beam by exactly 2 phi
    for phi in (0.01, 0.05, -0.1):
        assert mirror_deviation(phi, 0.0)[0] == pytest.approx(math.tan(2 * phi), rel=1e-12)


def _q_waist_and_position(w_in, f, lam):
    """Waist and its distance behind the lens from the q parameter (waist at the lens)."""
    q0 = 1j * math.pi * w_in ** 2 / lam
    q1 = 1 / (1 / q0 - 1 / f)

    def radius(z):
        return math.sqrt(-lam / (math.pi * (1 / (q1 + z)).imag))
    best = minimize_scalar(radius, bounds=(0.0, 2 * f), method="bounded",
                           options={"xatol": 1e-12})
    return best.fun, best.x, radius


@pytest.mark.parametrize("w_in, f", [(0.25e-3, 20e-3), (1e-3, 50e-3), (0.1e-3, 80e-3)])
def test_focused_waist_against_q_parameter(w_in, f):
    w0, z0, _ = _q_waist_and_position(w_in, f, LAMBDA)
    assert focused_waist(w_in, f, LAMBDA) == pytest.approx(w0, rel=1e-6)
    z_in = math.pi * w_in ** 2 / LAMBDA   # Saleh and Teich sec. 3.2: z' = f z_in^2 / (f^2 + z_in^2)
    assert z0 == pytest.approx(f * z_in ** 2 / (f ** 2 + z_in ** 2), rel=1e-4)


def test_focused_waist_far_field_limit():
    # f << z_in: w0 -> lambda f / (pi w_in)
    assert focused_waist(2e-3, 5e-3, LAMBDA) == pytest.approx(LAMBDA * 5e-3 / (math.pi * 2e-3),
                                                              rel=1e-7)


def test_beam_radius_against_q_parameter():
    w0 = 17e-6
    q0 = 1j * math.pi * w0 ** 2 / LAMBDA
    for z in (0.0, 1e-3, 30e-3):
        w = math.sqrt(-LAMBDA / (math.pi * (1 / (q0 + z)).imag))
        assert beam_radius_at(z, w0, LAMBDA) == pytest.approx(w, rel=1e-12)
    assert rayleigh_range(w0, LAMBDA) == pytest.approx(q0.imag)


@pytest.mark.parametrize("m, w, lo, hi", [(0.0, 1.0, -0.5, 0.5), (0.3, 0.2, 0.0, 1.0),
                                          (1.2, 0.4, 0.0, 1.0), (-3.0, 1.0, -1.0, 2.0)])
def test_interval_fraction_against_quad(m, w, lo, hi):
    total = math.sqrt(math.pi / 2) * w
    expected = quad(_gauss, lo, hi, args=(m, w), epsabs=1e-14)[0] / total
    assert float(interval_fraction(m, w, lo, hi)) == pytest.approx(expected, rel=1e-9, abs=1e-15)


def test_rectangle_fraction_against_dblquad():
    mx, my, wx, wy = 440e-6, 5e-6, 17.4e-6, 17e-6
    xr, yr = (0.0, 450e-6), (-25e-6, 25e-6)
    norm = math.pi / 2 * wx * wy
    expected = dblquad(lambda y, x: _gauss(x, mx, wx) * _gauss(y, my, wy), *xr, *yr,
                       epsabs=1e-22)[0] / norm
    got = float(rectangle_fraction(mx, my, wx, wy, xr, yr))
    assert got == pytest.approx(expected, rel=1e-8)


@pytest.mark.parametrize("m", [0.5, 0.95, 1.0, 1.05, -0.02])
def test_interval_moments_against_quad(m):
    w, a, b = 0.04, 0.0, 1.0
    mass = quad(_gauss, a, b, args=(m, w), points=[m] if a < m < b else None)[0]
    first = quad(lambda x: x * _gauss(x, m, w), a, b)[0] / mass
    second = quad(lambda x: x * x * _gauss(x, m, w), a, b)[0] / mass
    frac, mean, mean2 = interval_moments(m, w, a, b)
    assert float(frac) == pytest.approx(mass / (math.sqrt(math.pi / 2) * w), rel=1e-9)
    assert float(mean) == pytest.approx(first, rel=1e-9)
    assert float(mean2) == pytest.approx(second, rel=1e-9)


def test_interval_moments_far_from_the_interval_stay_finite():
    frac, mean, mean2 = interval_moments(np.array([-10.0, 10.0]), 0.01, 0.0, 1.0)
    assert np.all(frac == 0.0)
    np.testing.assert_allclose(mean, [0.0, 1.0])
    np.testing.assert_allclose(mean2, [0.0, 1.0])


@pytest.mark.parametrize("call, name", [
    (lambda: free_space(-1.0), "distance"),
    (lambda: thin_lens(0.0), "focal_length"),
    (lambda: focal_plane_ray(2.0, 0.02), "slope"),
    (lambda: mirror_deviation(0.3, 0.0), "tilt_in_plane"),
    (lambda: mirror_deviation(0.0, 0.0, math.pi / 2), "incidence"),
    (lambda: focused_waist(-1e-3, 0.02, LAMBDA), "beam_radius"),
    (lambda: beam_radius_at(-1.0, 1e-5, LAMBDA), "distance"),
    (lambda: interval_fraction(0.0, 0.0, -1.0, 1.0), "radius"),
    (lambda: interval_moments(0.0, 1.0, 1.0, 0.0), "high"),
    (lambda: interval_fraction(float("nan"), 1.0, -1.0, 1.0), "centre"),
    # found by the bad-input campaign: each was an overflow, a silent NaN or the wrong name
    (lambda: focused_waist(1e300, 0.02, LAMBDA), "beam_radius"),
    (lambda: rayleigh_range(1e300, LAMBDA), "waist"),
    (lambda: beam_radius_at(1.0, 1e-300, LAMBDA), "waist"),
    (lambda: interval_fraction(0.0, 1.0, float("nan"), 1.0), "low"),
    (lambda: interval_fraction(0.0, 1.0, -1.0, float("nan")), "high"),
    (lambda: interval_fraction(0.0, 1.0, 1.0, -1.0), "high"),
    (lambda: rectangle_fraction(float("nan"), 0.0, 1.0, 1.0, (0, 1), (0, 1)), "centre_x"),
    (lambda: rectangle_fraction(0.0, 0.0, 1.0, 0.0, (0, 1), (0, 1)), "radius_y"),
    (lambda: rectangle_fraction(0.0, 0.0, 1.0, 1.0, (0, 1), (1, float("nan"))), "y_range"),
    (lambda: interval_moments(1e300, 1.0, 0.0, 1.0), "centre"),
    (lambda: interval_moments(0.0, 1e256, 0.0, 1.0), "radius"),
    (lambda: interval_moments(0.0, 1.0, 1e300, 1.0), "low"),
])
def test_bad_inputs_name_the_parameter(call, name):
    with pytest.raises(ValueError, match=name):
        call()


def test_a_pair_that_is_not_a_pair_is_named():
    with pytest.raises(TypeError, match="x_range"):
        rectangle_fraction(0.0, 0.0, 1.0, 1.0, 1.0, (0, 1))


def test_infinite_interval_ends_are_allowed():
    assert float(interval_fraction(0.0, 1.0, -math.inf, math.inf)) == 1.0
    assert float(interval_fraction(0.0, 1.0, 0.0, math.inf)) == pytest.approx(0.5)
