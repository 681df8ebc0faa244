"""Module (d) tip shapes against independent sources: the issue's parametric formulas evaluated in
50-digit mpmath, Sneddon's general axisymmetric-punch integrals (Sneddon, Int. J. Eng. Sci. 3, 47
(1965)) evaluated with scipy.integrate.quad and derived with sympy, the sphere -> paraboloid limit
from a sympy series, and the metadata registry (nanite's model-style test)."""
import math

import mpmath
import numpy as np
import pytest
import sympy as sp
from scipy.integrate import quad

from afmsmiler.contact import (TIPS, Conical, Parabolic, Pyramidal, Spherical, make_tip,
                               reduced_modulus, tip_table)

E_STAR = 2.5e6  # Pa
TIPS_UNDER_TEST = [Parabolic(35e-9), Spherical(2e-6), Conical(math.radians(25)),
                   Pyramidal(math.radians(35))]


# --- the issue's formulas, parametric in r, in 50-digit arithmetic ----------------------------
def issue_formula(tip, r):
    """(Z_s, F) at contact radius r from the formulas printed in the issue (mpmath, E* = E_STAR)."""
    mpmath.mp.dps = 50
    r = mpmath.mpf(r)
    e = mpmath.mpf(E_STAR)
    if isinstance(tip, Parabolic):
        R = mpmath.mpf(tip.radius)
        z = r ** 2 / R
        return z, 4 * mpmath.sqrt(R) / 3 * e * z ** 1.5
    if isinstance(tip, Spherical):
        R = mpmath.mpf(tip.radius)
        ln = mpmath.log((R + r) / (R - r))
        return r / 2 * ln, e * ((r ** 2 + R ** 2) / 2 * ln - r * R)
    if isinstance(tip, Conical):
        t = mpmath.tan(mpmath.mpf(tip.half_angle))
        z = mpmath.pi * r / (2 * t)
        return z, e * 2 * t / mpmath.pi * z ** 2
    t = mpmath.tan(mpmath.mpf(tip.face_angle))
    z = mpmath.sqrt(2) * r / t
    return z, e * t / mpmath.sqrt(2) * z ** 2


@pytest.mark.parametrize("tip", TIPS_UNDER_TEST, ids=lambda t: t.key)
def test_force_and_radius_match_the_printed_formulas(tip):
    scale = tip.radius if hasattr(tip, "radius") else 100e-9
    radii = scale * np.array([1e-6, 1e-3, 0.01, 0.1, 0.3, 0.5, 0.7, 0.8])
    for r in radii:
        z, f = issue_formula(tip, r)
        assert tip.force(float(z), E_STAR) == pytest.approx(float(f), rel=2e-14)
        assert tip.contact_radius(float(z)) == pytest.approx(r, rel=2e-14)
        assert tip.depth_for_radius(r) == pytest.approx(float(z), rel=2e-14)
    # vectorised call equals the scalar calls
    zs = np.array([float(issue_formula(tip, r)[0]) for r in radii])
    np.testing.assert_allclose(tip.force(zs, E_STAR), [tip.force(z, E_STAR) for z in zs],
                               rtol=2e-15)


# --- Sneddon's general punch: numerical quadrature --------------------------------------------
def sneddon_quad(slope, a):
    """Indentation and force (E* = E_STAR) of a punch of profile slope f'(rho) at contact radius a.

    delta = a int_0^1 f'(a x) / sqrt(1 - x^2) dx,
    F = 2 E* a^2 int_0^1 x^2 f'(a x) / sqrt(1 - x^2) dx
    """
    w = dict(weight="alg", wvar=(0.0, -0.5), epsabs=0.0, epsrel=1e-13, limit=200)
    # the algebraic weight (1 - x)^-1/2 handles the endpoint; the rest is (1 + x)^-1/2
    d = a * quad(lambda x: slope(a * x) / math.sqrt(1 + x), 0.0, 1.0, **w)[0]
    f = 2 * E_STAR * a * a * quad(lambda x: x * x * slope(a * x) / math.sqrt(1 + x), 0.0, 1.0,
                                  **w)[0]
    return d, f


@pytest.mark.parametrize("tip, slope", [
    (Parabolic(35e-9), lambda rho: rho / 35e-9),
    (Spherical(2e-6), lambda rho: rho / math.sqrt((2e-6 - rho) * (2e-6 + rho))),
    (Conical(math.radians(25)), lambda rho: 1 / math.tan(math.radians(25))),
], ids=["parabolic", "spherical", "conical"])
def test_axisymmetric_tips_match_sneddons_integrals(tip, slope):
    for a in tip.radius * np.array([0.01, 0.2, 0.6, 0.8]) if hasattr(tip, "radius") else \
            np.array([1e-9, 30e-9, 400e-9]):
        d, f = sneddon_quad(slope, a)
        assert tip.depth_for_radius(a) == pytest.approx(d, rel=1e-11)
        assert tip.force(d, E_STAR) == pytest.approx(f, rel=1e-11)


@pytest.mark.slow
def test_sympy_derivation_of_cone_and_paraboloid_from_sneddon():
    x, a, R, al, E, d = sp.symbols("x a R alpha E delta", positive=True)
    for slope, expected in ((a * x / R, 4 * sp.sqrt(R) / 3 * E * d ** sp.Rational(3, 2)),
                            (1 / sp.tan(al), 2 * sp.tan(al) / sp.pi * E * d ** 2)):
        depth = sp.simplify(a * sp.integrate(slope / sp.sqrt(1 - x ** 2), (x, 0, 1)))
        force = sp.simplify(2 * E * a ** 2 * sp.integrate(x ** 2 * slope / sp.sqrt(1 - x ** 2),
                                                          (x, 0, 1)))
        a_of_d = sp.solve(sp.Eq(depth, d), a)[0]
        assert sp.simplify(force.subs(a, a_of_d) - expected) == 0
    # the library against the derived closed forms
    z = np.linspace(0, 300e-9, 7)
    f_cone = sp.lambdify((al, E, d), 2 * sp.tan(al) / sp.pi * E * d ** 2)
    np.testing.assert_allclose(Conical(0.4).force(z, 3e6), f_cone(0.4, 3e6, z), rtol=1e-14)


def test_pyramid_lies_between_its_inscribed_and_circumscribed_cones():
    # Bilodeau's four-sided pyramid (F = E* tan(b)/sqrt2 Z^2, from its own formula via sympy)
    b, E, d = sp.symbols("beta E delta", positive=True)
    f_pyr = sp.lambdify((b, E, d), sp.tan(b) / sp.sqrt(2) * E * d ** 2)
    for beta in np.radians([10, 35, 60, 80]):
        z = np.array([1e-9, 50e-9])
        f = Pyramidal(beta).force(z, 3e6)
        np.testing.assert_allclose(f, f_pyr(beta, 3e6, z), rtol=1e-14)
        inner = Conical(beta).force(z, 3e6)  # the cone touching the faces
        outer = Conical(math.atan(math.sqrt(2) * math.tan(beta))).force(z, 3e6)  # through the edges
        assert np.all(inner < f) and np.all(f < outer)


def test_contact_stiffness_is_2_e_star_r():
    for tip in TIPS_UNDER_TEST:
        z = np.array([1e-10, 1e-8, 3e-7])
        h = z * 1e-6
        numeric = (tip.force(z + h, E_STAR) - tip.force(z - h, E_STAR)) / (2 * h)
        np.testing.assert_allclose(tip.contact_stiffness(z, E_STAR), numeric, rtol=1e-8)


# --- the sphere tends to the paraboloid -----------------------------------------------------------
@pytest.mark.slow  # sympy series: about a second
def test_sphere_tends_to_paraboloid_with_the_sympy_series_correction():
    u, zeta = sp.symbols("u zeta", positive=True)
    # F_sphere / F_paraboloid at the same depth, as a series in zeta = Z_s / R
    h = u * sp.atanh(u)
    ratio = ((1 + u ** 2) * sp.atanh(u) - u) / (sp.Rational(4, 3) * h ** sp.Rational(3, 2))
    c_force = sp.limit((ratio - 1) / h, u, 0)  # first-order coefficient in zeta
    c_radius = sp.limit((u / sp.sqrt(h) - 1) / h, u, 0)
    assert c_force == sp.Rational(-1, 10) and c_radius == sp.Rational(-1, 6)
    R = 1e-6
    sphere, para = Spherical(R), Parabolic(R)
    for z in [1e-17, 1e-14, 1e-12, 1e-10, 1e-9]:
        zeta_v = z / R
        ratio_v = sphere.force(z, E_STAR) / para.force(z, E_STAR)
        # full precision at Z_s << R: the deviation is the series term, not round-off
        assert (ratio_v - 1) == pytest.approx(float(c_force) * zeta_v, rel=1e-4, abs=3e-16)
        r_ratio = sphere.contact_radius(z) / para.contact_radius(z)
        assert (r_ratio - 1) == pytest.approx(float(c_radius) * zeta_v, rel=1e-4, abs=3e-16)


def test_sphere_at_its_radius():
    R = 1e-6
    # u artanh(u) = 1 at u = 0.83355..., from mpmath
    u = mpmath.findroot(lambda v: v * mpmath.atanh(v) - 1, (mpmath.mpf("0.7"), mpmath.mpf("0.9")),
                        solver="illinois")
    assert Spherical(R).contact_radius(R) == pytest.approx(float(u) * R, rel=1e-14)
    with pytest.raises(ValueError, match=r"z_s must be in \[0, 1e-06\] m"):
        Spherical(R).force(1.01 * R, E_STAR)


# --- registry ------------------------------------------------------------------------------------
@pytest.mark.parametrize("key", list(TIPS))
def test_registry_metadata_is_consistent(key):
    cls = TIPS[key]
    assert cls.key == key
    tip = cls()
    assert make_tip(key) == tip
    assert {p.name for p in cls.parameters} <= set(tip.values())
    for p in cls.parameters:
        assert p.low < p.slider_low < p.default < p.slider_high < p.high
        assert p.unit in ("m", "rad") and p.scale > 0
        assert p.name in (cls.__doc__ or "")
        p.check(p.slider_low), p.check(p.slider_high)
    assert key in tip_table()


def test_make_tip_rejects_unknown_key_and_parameter():
    with pytest.raises(ValueError, match="key must be one of"):
        make_tip("flat")
    with pytest.raises(TypeError, match="no parameter"):
        make_tip("conical", radius=1e-9)


# --- bad input -----------------------------------------------------------------------------------
@pytest.mark.parametrize("bad", [0.0, -1e-9, 1e-13, 1e-320, math.nan, math.inf])
@pytest.mark.parametrize("cls", [Parabolic, Spherical])
def test_bad_radius(cls, bad):
    # below 1 pm no tip exists, and R-divided terms (a^2 / R) would overflow
    with pytest.raises(ValueError, match=r"^radius must be in \[1e-12, 0.01\] m"):
        cls(bad)


@pytest.mark.parametrize("bad", [0.0, math.pi / 2, -0.1, 2.0, math.nan])
@pytest.mark.parametrize("cls, name", [(Conical, "half_angle"), (Pyramidal, "face_angle")])
def test_bad_angle(cls, name, bad):
    with pytest.raises(ValueError, match=rf"^{name} must be in \(0, 1.5708\) rad"):
        cls(bad)


@pytest.mark.parametrize("e, nu, match", [
    (0.0, 0.3, "youngs_modulus"), (-1.0, 0.3, "youngs_modulus"), (math.nan, 0.3, "youngs_modulus"),
    (1e6, 0.5, r"poisson_ratio must be in \[0, 0.5\)"), (1e6, -0.1, "poisson_ratio"),
    (1e6, math.nan, "poisson_ratio")])
def test_bad_moduli(e, nu, match):
    with pytest.raises(ValueError, match=match):
        reduced_modulus(e, nu)


@pytest.mark.parametrize("z", [-1e-9, math.nan, [0.0, math.inf]])
def test_bad_depths(z):
    with pytest.raises(ValueError, match="z_s must be"):
        Parabolic(1e-8).force(z, E_STAR)


def test_reduced_modulus_is_for_a_rigid_tip():
    assert reduced_modulus(1e6, 0.0) == 1e6
    assert reduced_modulus(3e6, 0.5 - 1e-12) == pytest.approx(4e6, rel=1e-11)


# --- extreme input: a physical bound instead of an overflow (bad-input campaign, issue 8) --------
@pytest.mark.parametrize("tip", [Parabolic(), Conical(), Pyramidal()], ids=["par", "cone", "pyr"])
def test_depths_and_radii_beyond_the_positioner_travel_are_named_errors(tip):
    # Z_s <= Z_np <= 100 m: deeper was accepted and returned F = inf (1e300 m)
    with pytest.raises(ValueError, match=r"^z_s must be in \[0, 100\] m, got 1e\+300"):
        tip.force(1e300, 1e6)
    with pytest.raises(ValueError, match=r"^contact_radius must be in \[0, "):
        tip.depth_for_radius(1e300)
    with pytest.raises(ValueError, match=r"^r must be in \[0, 100\] m"):
        tip.profile(1e300)
    # at the bounds, with the stiffest sample the ranges allow, every law is finite
    e_star = reduced_modulus(1e13, 0.4999)
    assert math.isfinite(tip.force(100.0, e_star))
    assert tip.depth_for_radius(tip.max_radius) == pytest.approx(100.0, rel=1e-12)
    assert math.isfinite(tip.profile(100.0))


@pytest.mark.parametrize("key", [["parabolic"], np.array([1.0, math.nan]), None])
def test_make_tip_names_key_for_an_unhashable_or_missing_key(key):
    # a list or an array raised "unhashable type: 'list'", naming nothing
    with pytest.raises(ValueError, match="^key must be one of"):
        make_tip(key)


def test_tip_table_writes_each_range_with_its_own_brackets():
    # the radius range is closed, [1 pm, 1 cm] (1e-3 to 1e7 nm); the angles are open at both ends
    table = tip_table()
    assert "| [0.001, 1e+07] |" in table
    assert "| (0, 90) |" in table
