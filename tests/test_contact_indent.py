"""The cantilever equation k (Z_np - Z_s) = F(Z_s), adhesion and viscoelasticity, against
independent sources: the equation's own residual, a scalar scipy brentq solution, published JKR and
DMT pull-off forces, Johnson's Hertz surface profile, and sympy-derived hereditary integrals."""
import math

import mpmath
import numpy as np
import pytest
import sympy as sp
from scipy.integrate import quad
from scipy.optimize import brentq

from afmsmiler.contact import (Conical, Parabolic, Pyramidal, Spherical, StandardLinearSolid,
                               approach_retract, hereditary_force, indent, jkr_curve,
                               jkr_instability, reduced_modulus, residual, surface_displacement,
                               viscoelastic_approach_retract, z_np_limit)

TIPS = [Parabolic(20e-9), Spherical(500e-9), Conical(math.radians(20)), Pyramidal(math.radians(35))]
IDS = [t.key for t in TIPS]


# --- the solver -----------------------------------------------------------------------------------
@pytest.mark.parametrize("tip", TIPS, ids=IDS)
@pytest.mark.parametrize("k, e", [(0.01, 1e3), (0.1, 1e6), (40.0, 1e9), (1e3, 1.7e11),
                                  (1e-3, 1e10)])
def test_residual_is_round_off_for_a_whole_curve(tip, k, e):
    nu = 0.3
    e_star = e / (1 - nu ** 2)
    z = np.linspace(-50e-9, 400e-9, 1000)
    if isinstance(tip, Spherical):
        z = np.linspace(-50e-9, 0.99 * tip.max_z_np(k, e_star), 1000)
    c = indent(z, k, tip, e, nu)
    inside = z > 0
    # the test's own residual, with F recomputed from Z_s by the public force law
    zi, zs = z[inside], c.z_s[inside]
    res = np.abs(k * (zi - zs) - tip.force(zs, e_star)) / (k * zi)
    assert res.max() <= 1e-12
    np.testing.assert_array_equal(residual(c, k, tip, e, nu)[inside] <= 1e-12, True)
    # bookkeeping: Z_np = Z_s + Z_c and F = k Z_c in contact, nothing before contact
    np.testing.assert_allclose(c.z_s[inside] + c.z_c[inside], z[inside], rtol=1e-14)
    np.testing.assert_allclose(c.force[inside], k * c.z_c[inside], rtol=1e-15, atol=0)
    assert np.all(c.force[~inside] == 0) and np.all(c.z_s[~inside] == 0)
    assert np.all(c.contact_radius[~inside] == 0) and not c.in_contact[~inside].any()
    assert np.all(np.diff(c.force[inside]) > 0)  # monotonic


def _root_50_digits(tip, z_np, k, e_star):
    """(Z_s, F) solving k (Z_np - Z_s) = F(Z_s) by bisection in 50-digit mpmath on the issue's
    formulas (the sphere parametric in u = r / R)."""
    mpmath.mp.dps = 50
    zn, k, es = mpmath.mpf(z_np), mpmath.mpf(k), mpmath.mpf(e_star)
    if isinstance(tip, Spherical):
        rad = mpmath.mpf(tip.radius)

        def state(u):
            return rad * u * mpmath.atanh(u), es * rad ** 2 * ((1 + u * u) * mpmath.atanh(u) - u)
        lo, hi = mpmath.mpf(0), 1 - mpmath.mpf(10) ** -12
    else:
        if isinstance(tip, Parabolic):
            c, n = 4 * mpmath.sqrt(mpmath.mpf(tip.radius)) / 3, mpmath.mpf(1.5)
        elif isinstance(tip, Conical):
            c, n = 2 * mpmath.tan(mpmath.mpf(tip.half_angle)) / mpmath.pi, 2
        else:
            c, n = mpmath.tan(mpmath.mpf(tip.face_angle)) / mpmath.sqrt(2), 2

        def state(s):
            return s, es * c * s ** n
        lo, hi = mpmath.mpf(0), zn
    for _ in range(175):  # 2^-175 < 1e-52
        mid = (lo + hi) / 2
        zs, f = state(mid)
        lo, hi = (mid, hi) if k * (zn - zs) > f else (lo, mid)
    return state((lo + hi) / 2)


@pytest.mark.parametrize("tip", TIPS, ids=IDS)
@pytest.mark.parametrize("k, e", [(0.01, 1e3), (0.1, 1e6), (40.0, 1e9), (1e3, 1.7e11),
                                  (1e-3, 1e10), (1e3, 1e3), (1e-3, 1e11)])
def test_solution_is_the_correctly_rounded_root(tip, k, e):
    # The forward error, relative to Z_s and to F themselves, against a 50-digit root: stronger
    # than the residual, which is relative to k Z_np = k Z_s + F (the sum of the terms;
    # at k = 1e3 N/m on E = 1 kPa, F / (k Z_np) ~ 1e-7, and even the correctly rounded Z_s leaves
    # a residual ~ eps k Z_s, i.e. ~1e-9 of F: relative to F alone no double Z_s can reach 1e-12)
    nu = 0.3
    e_star = e / (1 - nu ** 2)
    if isinstance(tip, Spherical):
        z = np.linspace(1e-12, 0.99 * tip.max_z_np(k, e_star), 12)
    else:
        z = np.geomspace(1e-12, 400e-9, 12)
    c = indent(z, k, tip, e, nu)
    eps = np.finfo(float).eps
    for i, zz in enumerate(z):
        zs, f = _root_50_digits(tip, zz, k, e_star)
        assert abs(c.z_s[i] - float(zs)) <= 8 * eps * float(zs)
        assert abs(c.force[i] - float(f)) <= 16 * eps * float(f)
        assert abs(c.z_c[i] - float(f / k)) <= 16 * eps * float(f / k)
    assert residual(c, k, tip, e, nu).max() <= 16 * eps


@pytest.mark.parametrize("tip", TIPS, ids=IDS)
def test_solver_equals_scalar_brentq(tip):
    k, e, nu = 0.2, 5e6, 0.4
    e_star = reduced_modulus(e, nu)
    z = np.geomspace(1e-12, 150e-9, 40)
    c = indent(z, k, tip, e, nu)
    ref = [brentq(lambda s, zz=zz: k * (zz - s) - tip.force(s, e_star), 0.0, zz, xtol=1e-30,
                  rtol=1e-15) for zz in z]
    np.testing.assert_allclose(c.z_s, ref, rtol=1e-12)


def test_cone_closed_form_against_sympy():
    zs, zn, k, c = sp.symbols("Z_s Z_np k c", positive=True)
    roots = sp.solve(sp.Eq(k * (zn - zs), c * zs ** 2), zs)
    root = [r for r in roots if r.subs({k: 1, c: 1, zn: 1}).evalf() > 0][0]
    f = sp.lambdify((zn, k, c), root)
    tip = Conical(0.5)
    e_star = reduced_modulus(2e7, 0.25)
    z = np.linspace(1e-9, 1e-6, 9)
    np.testing.assert_allclose(indent(z, 3.0, tip, 2e7, 0.25).z_s,
                               f(z, 3.0, 2 * math.tan(0.5) / math.pi * e_star), rtol=1e-13)


def test_elastic_approach_and_retract_coincide():
    z = np.linspace(-10e-9, 60e-9, 50)
    ar = approach_retract(z, 0.5, Pyramidal(0.6), 1e7, 0.2)
    np.testing.assert_array_equal(ar.retract.z_np, z[::-1])
    np.testing.assert_array_equal(ar.retract.force, ar.approach.force[::-1])
    assert ar.pull_off_force == 0.0


@pytest.mark.parametrize("kwargs, match", [
    (dict(z_np=[0.0, math.nan]), "z_np must be finite"),
    (dict(spring_constant=0.0), r"spring_constant must be in \[1e-06, 1e\+06\] N/m"),
    (dict(spring_constant=-1.0), "spring_constant must be in"),
    (dict(spring_constant=1e300), "spring_constant must be in"),
    (dict(z_np=[0.0, 1e300]), r"z_np must be in \[-100, 100\] m"),
    (dict(youngs_modulus=0.0), "youngs_modulus must be in"),
    (dict(youngs_modulus=math.nan), "youngs_modulus"),
    (dict(poisson_ratio=0.5), r"poisson_ratio must be in \[0, 0.5\)"),
    (dict(poisson_ratio=-0.01), "poisson_ratio"),
    (dict(tip=Spherical(10e-9), z_np=[0.0, 1e-6]), "past its radius"),
])
def test_bad_input(kwargs, match):
    args = dict(z_np=[0.0, 1e-8], spring_constant=0.1, tip=Parabolic(1e-8), youngs_modulus=1e6,
                poisson_ratio=0.3)
    args.update(kwargs)
    with pytest.raises(ValueError, match=match):
        indent(**args)


def test_a_wrong_tip_object_is_a_type_error_naming_tip():
    with pytest.raises(TypeError, match="tip must be a Tip, got str 'cone'"):
        indent([0.0, 1e-8], 0.1, "cone", 1e6, 0.3)


def test_approach_retract_bad_input():
    with pytest.raises(ValueError, match="strictly increasing"):
        approach_retract([0.0, 2e-9, 1e-9], 0.1, Parabolic(1e-8), 1e6, 0.3)
    with pytest.raises(ValueError, match="adhesion must be one of"):
        approach_retract([0.0, 1e-9], 0.1, Parabolic(1e-8), 1e6, 0.3, adhesion="maugis",
                         work_of_adhesion=0.1)
    with pytest.raises(ValueError, match="parabolic or spherical"):
        approach_retract([0.0, 1e-9], 0.1, Conical(0.3), 1e6, 0.3, adhesion="dmt",
                         work_of_adhesion=0.1)
    with pytest.raises(ValueError, match="work_of_adhesion must be in"):
        approach_retract([0.0, 1e-9], 0.1, Parabolic(1e-8), 1e6, 0.3, adhesion="jkr")


# --- adhesion -------------------------------------------------------------------------------------
R, W = 50e-9, 0.04  # tip radius (m) and work of adhesion (J/m^2)


@pytest.mark.parametrize("tip", [Parabolic(R), Spherical(R)], ids=["parabolic", "spherical"])
def test_dmt_pull_off_is_2_pi_r_w(tip):
    # Derjaguin, Muller and Toporov, J. Colloid Interface Sci. 53, 314 (1975): F_pull-off = 2 pi R w
    k = 0.1
    z = np.linspace(-200e-9, 20e-9, 20001)
    ar = approach_retract(z, k, tip, 1e8, 0.3, adhesion="dmt", work_of_adhesion=W)
    published = 2 * math.pi * R * W
    assert ar.pull_off_force == pytest.approx(published, rel=1e-14)
    assert ar.snap_off_force == pytest.approx(-published, rel=1e-14)
    # the sampled retract curve reaches it (to the ramp step k dz) and never goes below it
    assert ar.retract.force.min() >= -published * (1 + 1e-12)
    assert ar.retract.force.min() <= -published + 2 * k * (z[1] - z[0])
    # hysteresis: at Z_np in (-2 pi R w / k, 0) the retract is in contact, the approach is not
    mid = (ar.retract.z_np < 0) & (ar.retract.z_np > -published / k)
    assert ar.retract.in_contact[mid].all()
    assert not ar.approach.in_contact[ar.approach.z_np < 0].any()


def test_jkr_pull_off_limits_are_the_published_values():
    e_star = reduced_modulus(1e7, 0.3)
    # JKR (Proc. R. Soc. A 324, 301 (1971)): load control (soft lever) 3/2 pi R w;
    # displacement control (rigid lever) 5/6 pi R w (Johnson, Contact Mechanics, sec. 5.5)
    _, _, f_soft = jkr_instability(1e-9, R, W, e_star)
    _, _, f_stiff = jkr_instability(1e9, R, W, e_star)
    assert -f_soft == pytest.approx(1.5 * math.pi * R * W, rel=1e-6)
    assert -f_stiff == pytest.approx(5 / 6 * math.pi * R * W, rel=1e-6)


def test_jkr_snap_off_is_the_cantilever_instability():
    # at snap-off the slope of the JKR force-indentation curve equals -k (dF/dZ_s = -k)
    e_star = reduced_modulus(1e7, 0.3)
    for k in (0.01, 0.3, 5.0):
        a, _, f = jkr_instability(k, R, W, e_star)
        h = a * 1e-6
        (z1, z2), (f1, f2) = jkr_curve([a - h, a + h], R, W, e_star)
        assert (f2 - f1) / (z2 - z1) == pytest.approx(-k, rel=1e-6)
        assert -f < 1.5 * math.pi * R * W


def test_jkr_zero_load_radius():
    # F = 0 at a0^3 = 9 pi w R^2 / (2 E*)  (JKR 1971 with K = 4 E* / 3)
    e_star = 3e6
    a0 = (9 * math.pi * W * R ** 2 / (2 * e_star)) ** (1 / 3)
    _, f = jkr_curve(a0, R, W, e_star)
    assert abs(float(f)) < 1e-12 * 4 * e_star * a0 ** 3 / (3 * R)


def test_jkr_cycle_shows_snap_in_and_snap_off():
    k, e, nu = 0.05, 1e7, 0.3
    z = np.linspace(-300e-9, 30e-9, 3001)
    ar = approach_retract(z, k, Parabolic(R), e, nu, adhesion="jkr", work_of_adhesion=W)
    app, ret = ar.approach, ar.retract
    # approach: no force before Z_np = 0, then a jump to a finite contact (snap-in, a > 0)
    assert np.all(app.force[z < 0] == 0)
    first = np.argmax(z >= 0)
    assert app.contact_radius[first] > 0 and app.force[first] < 0
    # retract stays on down to the instability, then leaves; the jump is a finite force
    assert ret.in_contact[ret.z_np >= ar.snap_off_z_np].all()
    assert not ret.in_contact[ret.z_np < ar.snap_off_z_np].any()
    # the most adhesive force is JKR's published pull-off force (3/2) pi R w, passed on the way
    assert ar.pull_off_force == pytest.approx(1.5 * math.pi * R * W, rel=1e-13)
    assert ret.force.min() >= -ar.pull_off_force * (1 + 1e-12)
    assert ret.force.min() <= -ar.pull_off_force * (1 - 1e-5)
    # the jump happens later, at a smaller adhesive force (the lever's instability)
    last = np.flatnonzero(ret.in_contact)[-1]
    assert ar.snap_off_force < 0 and -ar.snap_off_force < ar.pull_off_force
    # near the fold F - F_snap grows like sqrt(Z_np - Z_snap): the last sample is close, not exact
    assert ret.force[last] == pytest.approx(ar.snap_off_force, rel=5e-3)
    # on the branches: Z_np = Z_s + F / k and the parametric JKR law
    c = ret.in_contact
    np.testing.assert_allclose(ret.z_s[c] + ret.force[c] / k, ret.z_np[c], rtol=1e-10, atol=1e-20)
    zs, f = jkr_curve(ret.contact_radius[c], R, W, reduced_modulus(e, nu))
    np.testing.assert_allclose(ret.force[c], f, rtol=1e-12, atol=1e-22)


def test_surface_profile_matches_hertz_and_follows_the_tip():
    tip = Parabolic(R)
    z_s = 10e-9
    a = tip.contact_radius(z_s)
    rho = np.linspace(0, 6 * a, 301)
    u = surface_displacement(tip, z_s, rho)
    # Johnson, Contact Mechanics (1985), eq. (3.42b) outside; the paraboloid inside
    out = rho > a
    ro = rho[out]
    hertz = ((2 * a * a - ro ** 2) * np.arcsin(a / ro) + a * np.sqrt(ro ** 2 - a * a)) / (
        math.pi * R)
    np.testing.assert_allclose(u[out], hertz, rtol=1e-12)
    np.testing.assert_allclose(u[~out], z_s - rho[~out] ** 2 / (2 * R), rtol=1e-12)
    # the cone: Sneddon's closed form cot(a) [a asin(a/rho) - rho + sqrt(rho^2 - a^2)]
    cone = Conical(0.5)
    a = cone.contact_radius(z_s)
    ro = np.linspace(1.01 * a, 5 * a, 50)
    ref = (a * np.arcsin(a / ro) - ro + np.sqrt(ro ** 2 - a * a)) / math.tan(0.5)
    np.testing.assert_allclose(surface_displacement(cone, z_s, ro), ref, rtol=1e-12)


# --- viscoelasticity ------------------------------------------------------------------------------
@pytest.mark.slow  # about a second a case (make unit skips it)
@pytest.mark.parametrize("tip", TIPS, ids=IDS)
def test_sls_limits_are_the_elastic_curves(tip):
    k, nu, e_inf, e_0 = 0.1, 0.3, 1e6, 4e6
    z = np.linspace(-20e-9, 80e-9, 201)
    speed = 1e-6  # m/s: the ramp lasts 0.1 s
    fast = viscoelastic_approach_retract(z, k, tip, StandardLinearSolid(e_inf, e_0, 1e-15), nu,
                                         speed)
    slow = viscoelastic_approach_retract(z, k, tip, StandardLinearSolid(e_inf, e_0, 1e15), nu,
                                         speed)
    relaxed, glassy = indent(z, k, tip, e_inf, nu), indent(z, k, tip, e_0, nu)
    scale = glassy.force.max()
    for cyc, ref in ((fast, relaxed), (slow, glassy)):
        np.testing.assert_allclose(cyc.approach.force, ref.force, rtol=0, atol=1e-9 * scale)
        np.testing.assert_allclose(cyc.retract.force, ref.force[::-1], rtol=0, atol=1e-9 * scale)


def test_sls_separates_approach_from_retract():
    tip, k, nu = Parabolic(R), 0.1, 0.3
    z = np.linspace(-20e-9, 80e-9, 401)
    cyc = viscoelastic_approach_retract(z, k, tip, StandardLinearSolid(1e6, 4e6, 0.05), nu, 1e-6)
    back = cyc.retract.force[::-1]
    assert np.all(back <= cyc.approach.force + 1e-15)
    assert (cyc.approach.force - back).max() > 0.1 * cyc.approach.force.max()
    # bounded by the two elastic curves on approach
    lo, hi = indent(z, k, tip, 1e6, nu).force, indent(z, k, tip, 4e6, nu).force
    assert np.all(cyc.approach.force >= lo * (1 - 1e-12))
    assert np.all(cyc.approach.force <= hi * (1 + 1e-12))


def test_hereditary_integral_against_closed_forms():
    tip, nu = Conical(0.6), 0.25
    mat = StandardLinearSolid(1e6, 3e6, 0.02)
    c = 2 * math.tan(0.6) / math.pi  # F = E* c Z^2
    # (1) psi linear in time (Z = sqrt(t / T)): the exact ramp response, sympy
    t_s, s, tau, T, e_inf, de = sp.symbols("t s tau T E_inf dE", positive=True)
    psi_rate = c / T * 1e-14  # d psi / dt for Z = 1e-7 sqrt(t / T)
    f_sym = sp.integrate((e_inf + de * sp.exp(-(t_s - s) / tau)) * psi_rate, (s, 0, t_s))
    f_ref = sp.lambdify((t_s, tau, T, e_inf, de), f_sym)
    t = np.linspace(0, 0.1, 11)
    z = 1e-7 * np.sqrt(t / 0.1)
    got = hereditary_force(t, z, tip, mat, nu)
    ref = f_ref(t, 0.02, 0.1, 1e6, 2e6) / (1 - nu ** 2)
    np.testing.assert_allclose(got, ref, rtol=1e-12, atol=1e-12 * ref.max())
    # (2) the paraboloid at constant indentation speed (Lee and Radok), quadrature
    para = Parabolic(R)
    v = 1e-6
    t = np.linspace(0, 0.05, 4001)
    got = hereditary_force(t, v * t, para, mat, nu)
    b = 4 * math.sqrt(R) / 3 / (1 - nu ** 2)
    for i in (1000, 2500, 4000):
        ti = t[i]
        ref = quad(lambda s_: float(mat.modulus(ti - s_)) * b * 1.5 * v ** 1.5 * math.sqrt(s_),
                   0, ti, epsabs=0, epsrel=1e-12)[0]
        assert got[i] == pytest.approx(ref, rel=1e-5)


def test_sls_bad_input():
    with pytest.raises(ValueError, match=r"instantaneous_modulus must be >= relaxed_modulus"):
        StandardLinearSolid(2e6, 1e6, 0.1)
    with pytest.raises(ValueError, match="relaxation_time must be > 0"):
        StandardLinearSolid(1e6, 2e6, 0.0)
    with pytest.raises(ValueError, match=r"speed must be in \[1e-12, 1000\] m/s"):
        viscoelastic_approach_retract([0, 1e-9], 0.1, Parabolic(R),
                                      StandardLinearSolid(1e6, 2e6, 1.0), 0.3, 0)


def test_adhesive_sphere_is_not_indented_past_its_radius():
    from afmsmiler.contact import z_np_limit
    tip, k, e, nu = Spherical(R), 0.5, 50e6, 0.3
    e_star = reduced_modulus(e, nu)
    assert z_np_limit(k, Parabolic(R), e, nu) == math.inf
    # elastic and DMT: Z_np at Z_s = R is R + F(R) / k, less the DMT pull 2 pi R w / k
    elastic = z_np_limit(k, tip, e, nu)
    assert elastic == pytest.approx(R + tip.force(R, e_star) / k, rel=1e-13)
    dmt = z_np_limit(k, tip, e, nu, adhesion="dmt", work_of_adhesion=W)
    assert dmt == pytest.approx(elastic - 2 * math.pi * R * W / k, rel=1e-13)
    jkr = z_np_limit(k, tip, e, nu, adhesion="jkr", work_of_adhesion=W)
    assert jkr > 0
    # a soft sample: the JKR neck alone reaches the sphere's equator, no Z_np >= 0 is allowed
    assert z_np_limit(k, tip, 1e6, nu, adhesion="jkr", work_of_adhesion=W) < 0
    for model, limit in (("dmt", dmt), ("jkr", jkr)):
        ok = approach_retract(np.linspace(-300e-9, 0.999 * limit, 500), k, tip, e, nu,
                              adhesion=model, work_of_adhesion=W)
        assert ok.approach.contact_radius.max() < R
        assert ok.approach.contact_radius.max() > 0.8 * R  # the limit is where the sphere ends
        with pytest.raises(ValueError, match="past its radius"):
            approach_retract(np.linspace(-300e-9, 1.001 * limit, 500), k, tip, e, nu,
                             adhesion=model, work_of_adhesion=W)


def _ting_reference(t, tip_c, exponent, mat, nu, v, t_m):
    """Ting's force for Z_s = v t up to t_m and v (2 t_m - t) after, psi = c Z_s^exponent, by
    quadrature and brentq on the integrals as printed (Ting 1966; Efremov et al. 2017)."""
    def e(s):
        return float(mat.modulus(s))

    def d_psi(s):  # d psi / ds on the loading
        return tip_c * exponent * (v * s) ** (exponent - 1) * v

    q = dict(epsabs=0, epsrel=1e-12, limit=200)
    if t <= t_m:
        return quad(lambda s: e(t - s) * d_psi(s), 0, t, **q)[0] / (1 - nu ** 2)

    def cond(t1):  # integral_t1^t E(t - s) dZ_s = 0
        return (quad(lambda s: e(t - s) * v, t1, t_m, **q)[0]
                - quad(lambda s: e(t - s) * v, t_m, t, **q)[0])

    if cond(0.0) <= 0:
        return 0.0  # the surface has receded from the tip
    t1 = brentq(cond, 0.0, t_m, xtol=1e-17)
    return quad(lambda s: e(t - s) * d_psi(s), 0, t1, **q)[0] / (1 - nu ** 2)


@pytest.mark.slow  # about a second a case (make unit skips it)
@pytest.mark.parametrize("tip, c, n", [
    (Conical(0.6), 2 * math.tan(0.6) / math.pi, 2.0),
    (Parabolic(R), 4 * math.sqrt(R) / 3, 1.5)], ids=["conical", "parabolic"])
def test_retract_follows_tings_solution(tip, c, n):
    # a triangular indentation history: Lee and Radok while it grows, Ting's t1 while it shrinks
    nu, v, t_m = 0.25, 1e-6, 0.05
    mat = StandardLinearSolid(1e6, 3e6, 0.02)
    t = np.linspace(0, 2 * t_m, 1601)
    z = np.maximum(v * np.minimum(t, 2 * t_m - t), 0.0)
    ref = np.array([_ting_reference(ti, c, n, mat, nu, v, t_m) for ti in t[::20]])
    got = hereditary_force(t, z, tip, mat, nu)[::20]
    # second order in the step (psi linear between samples): 1601 samples give ~1e-6
    np.testing.assert_allclose(got, ref, rtol=0, atol=2e-5 * ref.max())
    assert np.all((got == 0) == (ref == 0))  # the tip leaves where Ting's t1 reaches 0
    assert (ref == 0).sum() >= 5  # ... before the indentation returns to 0
    # Lee and Radok's integral carried on through the unloading would pull at the end (tensile)
    end = 2 * t_m
    lee_radok = quad(lambda s: float(mat.modulus(end - s)) * c * n * (v * min(s, end - s)) ** (
        n - 1) * (v if s < t_m else -v), 0, end, points=[t_m], epsabs=0, epsrel=1e-10)[0]
    assert lee_radok < -0.01 * ref.max() and got[-1] == 0.0
    # a stiff lever (F / k << Z_s) is the prescribed indentation: same forces
    cyc = viscoelastic_approach_retract(np.linspace(0, v * t_m, 801), 1e5, tip, mat, nu, v)
    both = np.r_[cyc.approach.force, cyc.retract.force[1:]][::20]
    np.testing.assert_allclose(both, ref, rtol=0, atol=2e-5 * ref.max())


@pytest.mark.slow  # about a second a case (make unit skips it)
@pytest.mark.parametrize("tip", TIPS, ids=IDS)
@pytest.mark.parametrize("tau", [0.005, 0.05, 0.5])
def test_sls_retract_never_pulls_and_leaves_at_zero_force(tip, tau):
    # no adhesion: the retract force is compressive until the tip leaves (Ting), then zero
    k, nu = 0.1, 0.3
    z = np.linspace(-20e-9, 80e-9, 401)
    cyc = viscoelastic_approach_retract(z, k, tip, StandardLinearSolid(1e6, 4e6, tau), nu, 1e-6)
    ret = cyc.retract
    c = ret.in_contact
    assert np.all(ret.force >= 0) and ret.force.max() > 0
    last = np.flatnonzero(c)[-1]
    assert not c[last + 1:].any() and np.all(ret.force[last + 1:] == 0)
    assert ret.force[last] < 2e-3 * ret.force.max()  # it reaches ~0 (to a step) where it leaves
    assert ret.z_np[last] > ret.z_np[-1]  # ... before the ramp ends
    np.testing.assert_allclose(ret.force[c], k * (ret.z_np[c] - ret.z_s[c]), rtol=1e-12,
                               atol=1e-15 * ret.force.max())
    # the contact radius has one maximum (creep may still widen it just after the turn)
    rad = ret.contact_radius[c]
    peak = int(np.argmax(rad))
    assert np.all(np.diff(rad[:peak + 1]) >= 0) and np.all(np.diff(rad[peak:]) <= 0)


@pytest.mark.parametrize("k, e", [(0.05, 1e7), (0.01, 1e6), (5.0, 1e9), (100.0, 1e5)])
def test_jkr_branch_and_snap_off_against_40_digits(k, e):
    # Z_np(a) = a^2/R - sqrt(2 pi w a / E*) + [4 E* a^3 / (3R) - sqrt(8 pi w E* a^3)] / k
    # (JKR 1971 with the lever in series) in 40-digit mpmath: its minimum is the snap-off, its
    # inverse the stable branch
    mpmath.mp.dps = 40
    e_star = reduced_modulus(e, 0.3)
    rm, wm, em, km = map(mpmath.mpf, (R, W, e_star, k))

    def z_np(a):
        return (a * a / rm - mpmath.sqrt(2 * mpmath.pi * wm * a / em)
                + (4 * em * a ** 3 / (3 * rm) - mpmath.sqrt(8 * mpmath.pi * wm * em * a ** 3)) / km)

    a_min, z_min, _ = jkr_instability(k, R, W, e_star)
    a_ref = mpmath.findroot(lambda a: mpmath.diff(z_np, a), mpmath.mpf(a_min) * 1.01)
    assert a_min == pytest.approx(float(a_ref), rel=1e-13)
    assert z_min == pytest.approx(float(z_np(a_ref)), rel=1e-14)
    z = np.linspace(1.5 * z_min, 30e-9, 60)
    ret = approach_retract(z, k, Parabolic(R), e, 0.3, adhesion="jkr", work_of_adhesion=W).retract
    c = ret.in_contact
    for zz, a in zip(ret.z_np[c], ret.contact_radius[c]):
        ref = mpmath.findroot(lambda x, zz=zz: z_np(x) - zz, mpmath.mpf(a))
        assert a == pytest.approx(float(ref), rel=1e-13)  # the fold's conditioning: ~20 eps


@pytest.mark.slow
def test_sls_cycles_over_random_parameters_are_physical():
    # fixed draws over the whole range (lever 1e-3-100 N/m, E 1 kPa-1 GPa, E_0/E_inf 1-100,
    # tau 1 us-1000 s, speed 10 nm/s-100 um/s): no failure, no tension, between the elastic curves
    rng = np.random.default_rng(0)
    for _ in range(12):
        key = rng.choice(["parabolic", "spherical", "conical", "pyramidal"])
        tip = {"conical": Conical(0.35), "pyramidal": Pyramidal(0.6)}.get(key) or (
            Parabolic if key == "parabolic" else Spherical)(float(10 ** rng.uniform(-8, -6)))
        k, e_inf = 10 ** rng.uniform(-3, 2), 10 ** rng.uniform(3, 9)
        mat = StandardLinearSolid(e_inf, e_inf * 10 ** rng.uniform(0, 2), 10 ** rng.uniform(-6, 3))
        nu, speed = rng.uniform(0, 0.49), 10 ** rng.uniform(-8, -4)
        z_max = 200e-9
        if isinstance(tip, Spherical):
            z_max = min(z_max, 0.9 * tip.max_z_np(k, reduced_modulus(e_inf, nu)))
        z = np.linspace(-0.2 * z_max, z_max, int(rng.integers(20, 400)))
        cyc = viscoelastic_approach_retract(z, k, tip, mat, nu, speed)
        f = np.r_[cyc.approach.force, cyc.retract.force]
        assert np.isfinite(f).all() and f.min() >= 0
        lo, hi = indent(z, k, tip, mat.relaxed_modulus, nu), indent(z, k, tip,
                                                                    mat.instantaneous_modulus, nu)
        assert np.all(cyc.approach.force >= lo.force * (1 - 1e-9))
        assert np.all(cyc.approach.force <= hi.force * (1 + 1e-9))


# --- extreme and wrong input: named errors (bad-input campaign, issue 8) --------------------------
@pytest.mark.parametrize("w", [math.nan, None, "0.03", True, 1 + 1j, np.array([0.0, math.nan]),
                               11.0])
def test_work_of_adhesion_is_checked_even_without_adhesion(w):
    # without an adhesion model w was ignored: NaN, None or a string passed silently
    tip = Parabolic(R)
    with pytest.raises(ValueError, match="^work_of_adhesion must be"):
        approach_retract(np.linspace(-10e-9, 10e-9, 5), 0.1, tip, 1e6, 0.3, work_of_adhesion=w)
    with pytest.raises(ValueError, match="^work_of_adhesion must be"):
        z_np_limit(0.1, tip, 1e6, 0.3, work_of_adhesion=w)


def test_jkr_functions_name_values_that_would_overflow():
    # each returned inf before: a^3 of a = 1e300 m, w = 1e300 J/m^2, w / E* with E* = 1e-320 Pa,
    # and a snap-off of a 1e300 m tip
    e_star = reduced_modulus(1e7, 0.3)
    a = np.linspace(1e-9, 15e-9, 10)
    with pytest.raises(ValueError, match=r"^contact_radius must be in \[0, 100\] m"):
        jkr_curve(1e300, R, W, e_star)
    with pytest.raises(ValueError, match=r"^work_of_adhesion must be in \[0, 10\] J/m\^2"):
        jkr_curve(a, R, 1e300, e_star)
    with pytest.raises(ValueError, match=r"^reduced_modulus must be in \[1, 1\.33333e\+13\] Pa"):
        jkr_curve(a, R, W, 1e-320)
    with pytest.raises(ValueError, match=r"^radius must be in \[1e-12, 0\.01\] m"):
        jkr_instability(0.1, 1e300, W, e_star)
    # the corners of the ranges stay finite
    for args in ((100.0, 1e-12, 10.0, 1.0), (100.0, 1e-2, 0.0, 1e13 / 0.75)):
        assert all(np.isfinite(x).all() for x in jkr_curve(*args))


def test_sls_and_cycle_name_the_quantity_at_fault():
    # relaxed_modulus = 1e300 was blamed on instantaneous_modulus; a 2-sample time on the
    # indentation; speed = 1e-320 m/s gave infinite times
    with pytest.raises(ValueError, match=r"^relaxed_modulus must be in \[1, 1e\+13\] Pa"):
        StandardLinearSolid(1e300, 2e6, 1e-3)
    with pytest.raises(ValueError, match="^instantaneous_modulus must be >= relaxed_modulus"):
        StandardLinearSolid(1e9, 2e6, 1e-3)
    mat = StandardLinearSolid(1e6, 2e6, 1e-3)
    with pytest.raises(ValueError, match="^indentation and time must have the same length"):
        hereditary_force([0.0, 1.0], np.linspace(0.0, 20e-9, 50), Parabolic(R), mat, 0.3)
    with pytest.raises(ValueError, match=r"^speed must be in \[1e-12, 1000\] m/s"):
        viscoelastic_approach_retract(np.linspace(-1e-8, 1e-8, 9), 0.1, Parabolic(R), mat, 0.3,
                                      1e-320)
    slow = viscoelastic_approach_retract(np.linspace(-1e-8, 1e-8, 9), 0.1, Parabolic(R), mat,
                                         0.3, 1e-12)
    assert np.isfinite(slow.time).all()
