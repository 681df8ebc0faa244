"""Module (d)'s system object: ContactSystem against the free functions and the published limits,
Tip.outline / Tip.adhesive / validated helpers, bounded JKR searches, and the JKR neck drawn from
Johnson's surface displacement."""
import math
import signal

import numpy as np
import pytest

from afmsmiler.cantilever import Cantilever
from afmsmiler.contact import (PARAMETERS, TIPS, ContactSystem, Conical, Parabolic, Pyramidal,
                               Spherical, adhesion_extrema, approach_retract, contact_surface,
                               indent, jkr_curve, surface_displacement, z_np_limit)
from afmsmiler.parameters import Parameter

RAMP = np.linspace(-150e-9, 40e-9, 300)


# --- the system object ----------------------------------------------------------------------------
def test_system_takes_keywords_only_and_validates_once():
    with pytest.raises(TypeError):
        ContactSystem(Parabolic(), 0.1, 1e6, 0.3)  # no positional soup
    with pytest.raises(ValueError, match=r"spring_constant must be in \[1e-06, 1e\+06\] N/m"):
        ContactSystem(spring_constant=-1.0)
    with pytest.raises(ValueError, match=r"poisson_ratio must be in \[0, 0.5\)"):
        ContactSystem(poisson_ratio=0.5)
    with pytest.raises(ValueError, match="adhesion must be one of"):
        ContactSystem(adhesion="maugis")
    with pytest.raises(ValueError, match="needs a tip with a smooth apex"):
        ContactSystem(tip=Conical(), adhesion="jkr")
    with pytest.raises(TypeError, match="tip must be a Tip, got str"):
        ContactSystem(tip="cone")
    with pytest.raises(ValueError, match="work_of_adhesion must be in"):
        ContactSystem(adhesion="dmt", work_of_adhesion=0.0)
    s = ContactSystem()
    with pytest.raises(AttributeError):
        s.spring_constant = 1.0  # frozen
    assert all(isinstance(p, Parameter) for p in PARAMETERS.values())


@pytest.mark.parametrize("adhesion", [None, "dmt", "jkr"])
def test_system_equals_the_free_functions(adhesion):
    tip = Parabolic(radius=50e-9)
    s = ContactSystem(tip=tip, spring_constant=0.1, youngs_modulus=20e6, poisson_ratio=0.3,
                      adhesion=adhesion, work_of_adhesion=0.03)
    kw = dict(adhesion=adhesion, work_of_adhesion=0.03) if adhesion else {}
    ref = approach_retract(RAMP, 0.1, tip, 20e6, 0.3, **kw)
    got = s.approach_retract(RAMP)
    for branch in ("approach", "retract"):
        np.testing.assert_array_equal(getattr(got, branch).force, getattr(ref, branch).force)
    # the snap-off and pull-off without solving a curve equal the cycle's
    assert (s.snap_off_z_np, s.snap_off_force, s.pull_off_force) == pytest.approx(
        (ref.snap_off_z_np, ref.snap_off_force, ref.pull_off_force), rel=1e-14, abs=0)
    # the state at one Z_np on each branch is the cycle's point there
    i = 100
    for branch in ("approach", "retract"):
        curve = getattr(ref, branch)
        j = i if branch == "approach" else RAMP.size - 1 - i
        point = s.at(RAMP[i], branch)
        assert point.force[0] == pytest.approx(curve.force[j], rel=1e-12, abs=1e-24)
        assert point.in_contact[0] == curve.in_contact[j]


@pytest.mark.parametrize("adhesion", [None, "dmt", "jkr"])
@pytest.mark.parametrize("tip", [Spherical(radius=2e-6), Conical()], ids=["sphere", "cone"])
def test_system_equals_the_free_functions_for_every_field_and_refuses_the_same_ramps(tip,
                                                                                     adhesion):
    # issue 24: the system checks only the ramp (its fields were checked when it was made): the
    # same cycle, bit for bit, and the same errors for a bad ramp as the free function
    if adhesion and not tip.adhesive:
        return
    s = ContactSystem(tip=tip, spring_constant=0.5, youngs_modulus=5e6, poisson_ratio=0.45,
                      adhesion=adhesion, work_of_adhesion=0.02)
    kw = dict(adhesion=adhesion, work_of_adhesion=0.02) if adhesion else {}
    ref = approach_retract(RAMP, 0.5, tip, 5e6, 0.45, **kw)
    got = s.approach_retract(RAMP)
    for branch in ("approach", "retract"):
        for name in ("z_np", "z_s", "z_c", "force", "contact_radius", "in_contact"):
            np.testing.assert_array_equal(getattr(getattr(got, branch), name),
                                          getattr(getattr(ref, branch), name))
    for bad in (RAMP[::-1], RAMP[:1], np.r_[RAMP, np.nan], RAMP.reshape(2, -1),
                np.linspace(-1e-9, 1e-9, 100_001), np.r_[RAMP, 1e3]):
        with pytest.raises(ValueError) as free:
            approach_retract(bad, 0.5, tip, 5e6, 0.45, **kw)
        with pytest.raises(ValueError) as system:
            s.approach_retract(bad)
        assert str(system.value) == str(free.value)


def test_published_pull_off_forces():
    # DMT: 2 pi R w (Derjaguin, Muller, Toporov 1975); JKR soft-lever limit: 3/2 pi R w
    # (Johnson, Kendall, Roberts 1971)
    R, w = 20e-9, 0.05
    dmt = ContactSystem(tip=Parabolic(R), adhesion="dmt", work_of_adhesion=w)
    jkr = ContactSystem(tip=Parabolic(R), adhesion="jkr", work_of_adhesion=w,
                        youngs_modulus=10e6)
    assert dmt.pull_off_force == pytest.approx(2 * math.pi * R * w, rel=1e-14)
    assert jkr.pull_off_force == pytest.approx(1.5 * math.pi * R * w, rel=1e-12)


def test_system_from_a_module_a_cantilever():
    lever = Cantilever.from_material("silicon", length=450e-6, width=50e-6, thickness=2e-6)
    s = ContactSystem.from_cantilever(lever, tip=Spherical(1e-6), youngs_modulus=5e6)
    # k from the lever's geometry: E w h^3 / (4 L^3) for a rectangular end-loaded beam
    k = lever.youngs_modulus * 50e-6 * (2e-6) ** 3 / (4 * (450e-6) ** 3)
    assert s.spring_constant == pytest.approx(k, rel=1e-12)
    assert s.tip == Spherical(1e-6) and s.poisson_ratio == PARAMETERS["poisson_ratio"].default
    assert s.z_np_limit == pytest.approx(z_np_limit(lever.spring_constant, Spherical(1e-6), 5e6,
                                                    s.poisson_ratio), rel=1e-15)
    with pytest.raises(TypeError, match="cantilever must be a Cantilever"):
        ContactSystem.from_cantilever(0.1)
    with pytest.raises(TypeError, match="spring_constant comes from the cantilever"):
        ContactSystem.from_cantilever(lever, spring_constant=1.0)


# --- bounded loops --------------------------------------------------------------------------------
# (k, R, w, E): each of these never returned before (a `while True` doubling the JKR bracket
# until Z_np(a) >= z_max, which a NaN never satisfies)
HANGS = [(1e-300, 1e-300, 1e-300, 1e6), (1e-6, 1e-300, 1e-300, 1e6), (1e300, 1e-300, 1e-300, 1e6),
         (1e-300, 1e-300, 0.02, 1e300), (1e-6, 1e-300, 0.02, 1e300)]


@pytest.mark.parametrize("k, radius, w, e", HANGS)
def test_jkr_returns_or_raises_a_named_value_error_in_time(k, radius, w, e, hang_guard):
    def alarm(*_):  # a real hang never returns to the guard's check: the alarm ends it
        raise TimeoutError("approach_retract ran past 10 s")

    old = signal.signal(signal.SIGALRM, alarm)
    signal.alarm(10)
    try:
        with hang_guard(5, expected=0.02):
            try:
                cycle = approach_retract(np.array([-1e-9, 0.0, 1e-9]), k, Parabolic(radius), e,
                                         0.3, adhesion="jkr", work_of_adhesion=w)
            except ValueError as exc:  # named: the quantity out of its range, or all of them
                assert any(n in str(exc) for n in ("spring_constant", "youngs_modulus",
                                                   "work_of_adhesion", "radius")), str(exc)
            else:  # no silent non-finite result
                for b in (cycle.approach, cycle.retract):
                    assert np.isfinite(b.force).all() and np.isfinite(b.z_s).all()
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


def test_adhesion_extrema_rejects_out_of_range_values_by_name():
    with pytest.raises(ValueError, match=r"spring_constant must be in \[1e-06, 1e\+06\] N/m"):
        adhesion_extrema(1e-300, Parabolic(1e-3), 1e6, 0.3, adhesion="jkr",
                         work_of_adhesion=0.01)
    with pytest.raises(ValueError, match=r"radius must be in \[1e-12, 0.01\] m"):
        Parabolic(1e300)
    with pytest.raises(ValueError, match=r"work_of_adhesion must be in \[1e-06, 10\] J/m\^2"):
        adhesion_extrema(0.1, Parabolic(), 1e6, 0.3, adhesion="dmt", work_of_adhesion=1e300)


# --- tips: outline, adhesive, validated helpers ---------------------------------------------------
@pytest.mark.parametrize("cls", list(TIPS.values()), ids=list(TIPS))
def test_outline_is_the_profile_and_adhesive_is_the_smooth_apex(cls):
    tip = cls()
    x, z = tip.outline(80e-9)
    assert x.size == z.size and z.min() == 0.0 and x[np.argmin(z)] == 0.0
    np.testing.assert_allclose(x, -x[::-1], atol=1e-24)  # symmetric about the axis
    assert tip.adhesive == isinstance(tip, (Parabolic, Spherical))
    with pytest.raises(ValueError, match="height must be > 0"):
        tip.outline(-1e-9)
    with pytest.raises(ValueError, match="n must be"):
        tip.outline(1e-9, n=10 ** 9)


def test_public_helpers_validate():
    with pytest.raises(ValueError, match=r"^r must be in \[0, inf\) m|^r must be"):
        Parabolic().profile(-1e-9)
    with pytest.raises(ValueError, match="^r must be"):
        Spherical(10e-9).profile(11e-9)  # past the equator
    with pytest.raises(ValueError, match="spring_constant must be > 0"):
        Spherical().max_z_np(-1.0, 1e6)
    with pytest.raises(ValueError, match="reduced_modulus must be > 0"):
        Spherical().max_z_np(0.1, math.nan)
    with pytest.raises(TypeError, match="tip must be a Tip"):
        surface_displacement(None, 1e-9, [0.0])


def test_tip_parameters_are_shared_parameters_with_open_bounds():
    for cls in TIPS.values():
        for p in cls.parameters:
            assert isinstance(p, Parameter) and p.display_unit in ("nm", "deg")
            # angles open at 0 and pi/2; 1 pm <= R <= 1 cm
            assert p.low_inclusive == p.high_inclusive == (p.name == "radius")
    assert Conical.parameters[0].to_display(math.radians(20)) == pytest.approx(20.0, rel=1e-15)


# --- the JKR neck: the surface the figure and the scene draw --------------------------------------
def test_jkr_neck_surface_is_hertz_plus_a_flat_punch():
    # Johnson, Contact Mechanics (1985) sec. 5.5: JKR = Hertz at contact radius a plus a flat punch
    # of radius a; outside, Hertz u = [(2a^2 - rho^2) asin(a/rho) + a sqrt(rho^2 - a^2)] / (pi R)
    # and the punch u = (2/pi) d_p asin(a/rho), d_p = Z_s - a^2 / R
    R, w, e_star = 20e-9, 0.02, 1e6 / (1 - 0.3 ** 2)
    s = ContactSystem(tip=Parabolic(R), adhesion="jkr", work_of_adhesion=w)
    state = s.at(-20e-9, "retract")  # the review's state: stuck, F ~ -1.7 nN, a ~ 35 nm
    a, z_s = float(state.contact_radius[0]), float(state.z_s[0])
    assert state.in_contact[0] and z_s < 0 and state.force[0] == pytest.approx(-1.739e-9, rel=1e-3)
    zs_ref, f_ref = jkr_curve(a, R, w, e_star)
    assert z_s == pytest.approx(float(zs_ref), rel=1e-12)
    rho = np.array([0.0, 0.5 * a, a, 1.5 * a, 4 * a])
    u = contact_surface(s.tip, state, rho)
    d_p = z_s - a * a / R
    out = rho[rho > a]
    hertz = ((2 * a * a - out ** 2) * np.arcsin(a / out) + a * np.sqrt(out ** 2 - a * a)) / (
        math.pi * R)
    np.testing.assert_allclose(u[rho > a], hertz + 2 / math.pi * d_p * np.arcsin(a / out),
                               rtol=1e-10)
    np.testing.assert_allclose(u[rho <= a], z_s - rho[rho <= a] ** 2 / (2 * R), rtol=1e-12)
    assert u[0] == z_s  # the apex touches the surface, above the undeformed plane
    # elastic: unchanged (no punch term)
    el = indent([30e-9], 0.1, Parabolic(R), 1e6, 0.3)
    np.testing.assert_allclose(contact_surface(Parabolic(R), el, rho),
                               surface_displacement(Parabolic(R), el.z_s[0], rho), rtol=1e-14)


def test_pyramid_registry_cites_both_forms():
    assert "Rico" in Pyramidal.title and "Bilodeau" in Pyramidal.title
    assert "0.7453" in Pyramidal.formula


@pytest.mark.slow
def test_ramp_size_is_bounded_and_the_bound_runs_in_seconds(hang_guard):
    from afmsmiler.contact.indent import MAX_POINTS
    with pytest.raises(ValueError, match=rf"z_np must have at most {MAX_POINTS} points"):
        indent(np.zeros(MAX_POINTS + 1), 0.1, Parabolic(), 1e6, 0.3)
    s = ContactSystem(adhesion="jkr", work_of_adhesion=0.02)
    with hang_guard(20, expected=1.5):  # about 1.5 s on one loaded core
        cycle = s.approach_retract(np.linspace(-100e-9, 300e-9, MAX_POINTS))
    assert np.isfinite(cycle.retract.force).all()


def test_residual_checks_its_objects():
    with pytest.raises(TypeError, match="curve must be a IndentationCurve|curve must be an"):
        from afmsmiler.contact import residual
        residual(None, 0.1, Parabolic(), 1e6, 0.3)


def test_tips_say_how_they_are_drawn():
    assert [cls.faces for cls in TIPS.values()] == [None, None, None, 4]
    assert [cls.adhesive for cls in TIPS.values()] == [True, True, False, False]


@pytest.mark.slow
def test_campaign_over_the_valid_ranges_finds_only_finite_results_or_named_errors():
    # hypothesis over every tip, k, E, nu, adhesion, w and Z_np the Parameters allow (and past
    # them): a finite state, or a ValueError naming the quantity; never an overflow (a sphere of
    # radius 1e154 m raised OverflowError, a lever of 1e103 N/m returned an infinite force)
    from hypothesis import HealthCheck, given, settings
    from hypothesis import strategies as st
    angle = st.floats(1e-9, math.pi / 2 - 1e-9)
    radius = st.floats(1e-12, 1e-2)
    tips = st.one_of(radius.map(lambda r: Parabolic(radius=r)),
                     radius.map(lambda r: Spherical(radius=r)),
                     angle.map(lambda a: Conical(half_angle=a)),
                     angle.map(lambda a: Pyramidal(face_angle=a)))
    wide = st.floats(1e-300, 1e300)

    @settings(max_examples=300, deadline=2000, suppress_health_check=list(HealthCheck),
              derandomize=True)
    @given(tips, st.one_of(st.floats(1e-6, 1e6), wide), st.one_of(st.floats(1.0, 1e13), wide),
           st.floats(0.0, 0.4999), st.sampled_from([None, "dmt", "jkr"]),
           st.one_of(st.floats(1e-6, 10.0), wide), st.floats(-100.0, 100.0),
           st.sampled_from(["approach", "retract"]))
    def check(tip, k, e, nu, adhesion, w, z, branch):
        adhesion = adhesion if tip.adhesive else None
        try:
            s = ContactSystem(tip=tip, spring_constant=k, youngs_modulus=e, poisson_ratio=nu,
                              adhesion=adhesion, work_of_adhesion=w)
            point = s.at(z, branch)
            assert math.isfinite(s.pull_off_force)
        except ValueError as exc:
            assert any(n in str(exc) for n in ("spring_constant", "youngs_modulus", "z_np",
                                               "work_of_adhesion", "radius")), str(exc)
            return
        for f in ("z_s", "z_c", "force", "contact_radius"):
            assert np.isfinite(getattr(point, f)).all(), (f, point)

    check()


@pytest.mark.parametrize("z_s", [[1e-9, 2e-9], np.ones((3, 3)), np.array([]), 1e300])
def test_surface_displacement_names_a_z_s_that_is_not_one_depth(z_s):
    # an array raised numpy's "only 0-dimensional arrays can be converted", naming nothing
    with pytest.raises(ValueError, match="^z_s must be"):
        surface_displacement(Parabolic(), z_s, [0.0, 1e-8])


def test_contact_surface_checks_tip_and_rho_out_of_contact_too():
    # out of contact it returned zeros for any tip and for NaN distances
    off = indent(np.array([-10e-9]), 0.1, Parabolic(), 1e6, 0.3)
    assert not off.in_contact[0]
    with pytest.raises(TypeError, match="^tip must be a Tip"):
        contact_surface("parabolic", off, [0.0, 1e-8])
    with pytest.raises(ValueError, match="^rho must be finite"):
        contact_surface(Parabolic(), off, [0.0, math.nan])


def test_ramp_reaches_past_the_dmt_snap_off():
    # DMT on a paraboloid: the contact stiffness falls to zero at zero indentation, so the tip
    # leaves there, under the pull-off force 2 pi R w (Derjaguin, Muller and Toporov 1975): the
    # lever is then bent by -2 pi R w / k and Z_np = -2 pi R w / k
    from afmsmiler.contact import system as model
    r, w = 20e-9, 0.02
    for k, expected in ((0.01, 1.25 * -2 * math.pi * r * w / 0.01), (0.001, -2000e-9)):
        s = ContactSystem(spring_constant=k, tip=Parabolic(radius=r), adhesion="dmt",
                          work_of_adhesion=w)
        assert s.snap_off_z_np == pytest.approx(-2 * math.pi * r * w / k, rel=1e-9)
        low, high = s.ramp(-50e-9, 200e-9)
        assert low == pytest.approx(expected, rel=1e-12)  # 1.25 x the snap-off, or the floor
        assert high == 200e-9  # a paraboloid has no limit
    plain = ContactSystem(spring_constant=0.01, tip=Parabolic(radius=r))
    assert plain.ramp(-50e-9, 200e-9) == (-50e-9, 200e-9)
    assert model.SNAP_OFF_MARGIN == 1.25 and model.RAMP_FLOOR == -2000e-9
    with pytest.raises(ValueError, match="low must be below high"):
        plain.ramp(1e-9, 1e-9)


def test_ramp_stops_short_of_a_buried_sphere_and_drops_useless_adhesion():
    from afmsmiler.contact import system as model
    sphere = ContactSystem(spring_constant=1.0, tip=Spherical(radius=10e-9), youngs_modulus=1e9)
    assert sphere.ramp(-50e-9, 1e-3)[1] == pytest.approx(0.9 * sphere.z_np_limit, rel=1e-15)
    assert sphere.for_ramp() is sphere
    # weak and strong adhesion on a soft lever: kept while the ramp has room, else dropped
    kept = sphere.replace(adhesion="dmt", work_of_adhesion=1e-3)
    assert model.RAMP_MARGIN * kept.z_np_limit >= model.RAMP_MIN_RANGE and kept.for_ramp() is kept
    sticky = ContactSystem(spring_constant=1e-3, tip=Spherical(radius=10e-9),
                           youngs_modulus=1e5, adhesion="jkr", work_of_adhesion=0.5)
    assert sticky.z_np_limit < 0.0  # pulled in past its radius before any load
    shown = sticky.for_ramp()
    assert shown.adhesion is None and shown == sticky.replace(adhesion=None)
