"""Tapping (amplitude-modulation) mode: force law, fast steady states against time integration.

References used as independent checks: sympy's derivative of the sphere-plane van der Waals
energy -H R / (6 d) (Israelachvili, Sec. 13.1), module (d)'s Hertz force of a paraboloid and DMT's
pull-off force 2 pi R w, scipy.integrate.quad of the first-harmonic integrals' definitions, the
analytic driven harmonic oscillator, and scipy's odeint (LSODA) run to steady state (the reference
solver) for the fast solver and the energy balance.
"""
import math

import numpy as np
import pytest
import sympy as sp
from scipy.integrate import quad

from afmsmiler.contact import Parabolic, reduced_modulus
from afmsmiler.modes import (FORCE_PARAMETERS, TAPPING_PARAMETERS, TappingLever, amplitude_curve,
                             free_response, integrate, setpoint_state, tip_sample_force,
                             work_of_adhesion)
from afmsmiler.modes import tapping
from afmsmiler.parameters import Parameter
from tests.steps import run_steps

H, R, A0_, E, NU = 6.4e-20, 10e-9, 0.165e-9, 1e9, 0.3


# -- the force law ---------------------------------------------------------------------------------
def test_van_der_waals_is_minus_the_derivative_of_the_sphere_plane_energy():
    d, h, r = sp.symbols("d H R", positive=True)
    force = sp.lambdify((d, h, r), -sp.diff(-h * r / (6 * d), d))
    ds = np.array([0.2e-9, 0.5e-9, 2e-9, 30e-9])
    assert np.allclose(tip_sample_force(ds), force(ds, H, R), rtol=1e-14, atol=0)


def test_force_is_continuous_at_a0():
    below, above = tip_sample_force(A0_ * (1 - 1e-12)), tip_sample_force(A0_ * (1 + 1e-12))
    contact_value = -H * R / (6 * A0_ ** 2)
    assert below == pytest.approx(contact_value, rel=1e-9)
    assert above == pytest.approx(contact_value, rel=1e-9)


def test_contact_branch_is_module_d_dmt_force():
    """Hertz force of module (d)'s paraboloid minus DMT's pull-off force 2 pi R w."""
    w = work_of_adhesion(H, A0_)
    assert 2 * math.pi * R * w == pytest.approx(H * R / (6 * A0_ ** 2), rel=1e-14)
    delta = np.array([0.0, 0.01e-9, 0.3e-9, 2e-9])
    hertz = Parabolic(R).force(delta, reduced_modulus(E, NU))
    assert np.allclose(tip_sample_force(A0_ - delta), hertz - 2 * math.pi * R * w,
                       rtol=1e-12, atol=1e-22)


def test_damping_opposes_the_motion_in_contact_only():
    kw = dict(sample_viscosity=200.0)
    d = A0_ - 0.5e-9
    up, still, down = (tip_sample_force(d, v, **kw) for v in (1e-3, 0.0, -1e-3))
    assert up - still == pytest.approx(-200.0 * math.sqrt(R * 0.5e-9) * 1e-3, rel=1e-12)
    assert down - still == pytest.approx(-(up - still), rel=1e-12)
    assert tip_sample_force(1e-9, 1e-3, **kw) == tip_sample_force(1e-9, 0.0, **kw)


# -- the first-harmonic integrals against their definitions ----------------------------------------
@pytest.mark.parametrize("zc, a", [(15e-9, 10e-9), (10.2e-9, 10e-9), (8e-9, 9e-9),
                                   (2e-9, 3e-9), (0.1e-9, 0.05e-9)])
def test_harmonic_integrals_equal_quadrature_of_their_definition(zc, a):
    lever = TappingLever(sample_viscosity=300.0)
    w = 2 * math.pi * lever.resonance_frequency * lever.frequency_ratio

    def f(theta):
        return lever.force(zc + a * math.cos(theta), -w * a * math.sin(theta))

    brk = []
    u = (lever.intermolecular_distance - zc) / a
    if -1 < u < 1:
        brk = [math.acos(u), 2 * math.pi - math.acos(u)]
    scale = H * R / (6 * lever.intermolecular_distance ** 2)  # the contact force scale
    opts = dict(points=brk or None, limit=400, epsabs=1e-12 * scale, epsrel=1e-11)
    i_c = quad(lambda t: f(t) * math.cos(t), 0, 2 * math.pi, **opts)[0] / math.pi
    i_s = quad(lambda t: f(t) * math.sin(t), 0, 2 * math.pi, **opts)[0] / math.pi
    got_c, got_s = tapping._integrals(lever, np.array([zc]), np.array([a]))
    assert got_c[0] == pytest.approx(i_c, rel=1e-5, abs=1e-6 * scale)
    assert got_s[0] == pytest.approx(i_s, rel=1e-4, abs=1e-6 * scale)


# -- far from the sample: the driven harmonic oscillator -------------------------------------------
def _oscillator(k, q, w, f0):
    return f0 / (k * math.sqrt((1 - w * w) ** 2 + (w / q) ** 2)), math.atan2(w / q, 1 - w * w)


@pytest.mark.parametrize("ratio", [1.0, 0.998, 1.003])
def test_far_from_sample_fast_solver_is_the_driven_oscillator(ratio):
    lever = TappingLever(frequency_ratio=ratio)
    a, phi = _oscillator(40.0, 400.0, ratio, lever.drive_force)
    curve = amplitude_curve([5e-6], lever)
    amp, phase = curve.branch("attractive")
    assert np.count_nonzero(np.isfinite(curve.amplitude)) == 1
    assert amp[0] == pytest.approx(a, rel=1e-9)
    assert phase[0] == pytest.approx(phi, abs=1e-9)
    assert free_response(lever) == pytest.approx((a, phi), rel=1e-12)


@pytest.mark.parametrize("ratio", [1.0, 0.998])
def test_far_from_sample_time_integration_is_the_driven_oscillator(ratio):
    lever = TappingLever(frequency_ratio=ratio, quality_factor=100.0)
    a, phi = _oscillator(40.0, 100.0, ratio, lever.drive_force)
    state = integrate(5e-6, lever, start=(0.8 * a, phi + 0.2))  # off the steady state
    assert state.converged
    assert state.amplitude == pytest.approx(a, rel=1e-3)
    assert math.degrees(state.phase - phi) == pytest.approx(0.0, abs=0.05)


# -- fast solver against the time integration, on both branches ------------------------------------
DISTANCES = [2e-9, 4.5e-9, 7e-9, 8.5e-9, 10e-9]


@pytest.fixture(scope="module")
def runs():
    """Every stable root of the fast solver at DISTANCES and the integration started on it."""
    lever = TappingLever(sample_viscosity=100.0)
    curve = amplitude_curve(DISTANCES, lever)
    out = []
    for i, zc in enumerate(DISTANCES):
        for j in np.flatnonzero(curve.stable[i]):
            a, phi = curve.amplitude[i, j], curve.phase[i, j]
            out.append((zc, not curve.repulsive_branch[i, j], a, phi, curve.dissipated_energy[i, j],
                        integrate(zc, lever, start=(a, phi))))
    return lever, curve, out


@pytest.mark.slow
# the tests of the integrated runs share one worker: the fixture costs 28 s of integration
@pytest.mark.xdist_group("tapping_runs")
def test_fast_solver_matches_time_integration_on_both_branches(runs):
    lever, curve, out = runs
    assert curve.coexist[:3].all() and not curve.coexist[-1]  # both branches where they coexist
    assert {r[1] for r in out} == {True, False}
    for zc, att, a, phi, _, state in out:
        assert state.converged
        assert state.amplitude == pytest.approx(a, rel=0.01), (zc, att)
        assert abs(math.degrees(state.phase - phi)) < 2.0, (zc, att)


@pytest.mark.slow
@pytest.mark.parametrize("ratio", [0.998, 1.002])
def test_fast_solver_matches_time_integration_off_resonance(ratio):
    lever = TappingLever(frequency_ratio=ratio, sample_viscosity=100.0)
    curve = amplitude_curve([3e-9, 6e-9], lever)
    for i, zc in enumerate(curve.distance):
        for j in np.flatnonzero(curve.stable[i]):
            a, phi = curve.amplitude[i, j], curve.phase[i, j]
            state = integrate(zc, lever, start=(a, phi))
            assert state.converged
            assert state.amplitude == pytest.approx(a, rel=0.01), (zc, j)
            assert abs(math.degrees(state.phase - phi)) < 2.0, (zc, j)


@pytest.mark.slow
@pytest.mark.xdist_group("tapping_runs")
def test_dissipated_energy_from_phase_is_the_damping_work(runs):
    """E_dis = pi F0 A sin(phi) - pi k W A^2 / Q counts only the first harmonic of the lever's
    own damping, and assumes the stored energy no longer changes: the higher harmonics and the
    transient the criterion leaves (< 1e-4 A0) each carry some 1e-4 of pi k A^2 / Q, the
    difference of the two terms; the tolerance is 1e-3 of it."""
    lever, _, out = runs
    for zc, att, a, phi, e_fast, state in out:
        scale = math.pi * lever.spring_constant * state.amplitude ** 2 / lever.quality_factor
        assert state.damping_work >= 0  # 0 where the tip never touches (10 nm)
        assert abs(state.dissipated_energy - state.damping_work) < 1e-3 * scale, (zc, att)
        # the fast solver's own E_dis carries its phase error: dE/dphi = pi F0 A cos(phi), some
        # 0.01 pi k A^2 / Q for the 0.2 deg it has on the repulsive branch
        assert abs(e_fast - state.damping_work) < 0.02 * scale + 0.03 * state.damping_work, \
            (zc, att)
        if not att:  # repulsive: the sample takes a sizeable share, compare it relatively
            assert state.dissipated_energy == pytest.approx(state.damping_work, rel=0.01)


def test_dissipated_energy_is_cleveland_formula_at_resonance_and_positive_for_a_lossy_sample():
    """(pi k A^2 / Q)[(A0 / A) sin(phi) - w / w0] (Cleveland et al. 1998), typed here."""
    lever = TappingLever()
    a, phi = 6e-9, math.radians(70.0)
    typed = math.pi * 40.0 * a ** 2 / 400.0 * (10e-9 / a * math.sin(phi) - 1.0)
    assert lever.dissipated_energy(a, phi) == pytest.approx(typed, rel=1e-12)
    assert typed > 0  # energy lost to the sample counts positive
    assert lever.dissipated_energy(10e-9, math.pi / 2) == pytest.approx(0.0, abs=1e-30)


def test_without_sample_damping_no_energy_is_dissipated():
    curve = amplitude_curve(np.linspace(1e-9, 12e-9, 30))
    lever = curve.lever
    scale = math.pi * lever.spring_constant * lever.free_amplitude ** 2 / lever.quality_factor
    assert np.nanmax(np.abs(curve.dissipated_energy)) < 1e-6 * scale


@pytest.mark.parametrize("a0", [5e-9, 12e-9, 50e-9])
def test_zero_dissipation_is_zero_within_the_models_accuracy_and_its_bound_holds(a0):
    """A conservative force (no viscosity) takes no energy over a cycle, and neither does a
    viscous sample the tip never touches (z_c > A + a0): E_dis is exactly 0 there, where the
    formula's two terms left some 1e-11 zJ of either sign ("-8.744e-12 zJ" in the readout). The
    bound is honest: the formula's raw value, whose true value is 0, lies within it; and a real
    dissipation is far above it and kept."""
    z = a0 * np.linspace(1.5, 0.01, tapping.SETPOINT_GRID)
    dry = amplitude_curve(z, TappingLever(free_amplitude=a0))
    ok = np.isfinite(dry.amplitude)
    raw = dry.lever.dissipated_energy(dry.amplitude[ok], dry.phase[ok])  # the formula, unrounded
    assert np.all(np.abs(raw) <= dry.dissipated_energy_error[ok])
    assert np.any(raw != 0.0)  # there was round-off to remove
    assert np.all(dry.dissipated_energy[ok] == 0.0)
    for r in (0.5, 0.8, 0.9):
        assert tapping.operating_point(dry, r)[2] == 0.0
    wet = amplitude_curve(z, TappingLever(free_amplitude=a0, sample_viscosity=10.0))
    ok = np.isfinite(wet.amplitude)
    apart = ok & (wet.distance[:, None] > wet.amplitude + wet.lever.intermolecular_distance)
    assert apart.any() and np.all(wet.dissipated_energy[apart] == 0.0)
    touching = ok & (wet.distance[:, None] < wet.amplitude)  # the tip goes into the sample
    e = wet.dissipated_energy[touching]
    assert touching.any() and np.all(e > 0)  # damping only takes energy, and it is kept
    # the bound is round-off: far below the 1e-3 of pi k A^2 / Q the time integration checks
    scale = math.pi * wet.lever.spring_constant * a0 ** 2 / wet.lever.quality_factor
    assert np.nanmax(wet.dissipated_energy_error) < 1e-12 * scale


# -- roots, stability, jumps -----------------------------------------------------------------------
def test_roots_solve_the_amplitude_equation_and_alternate_in_stability():
    lever = TappingLever(sample_viscosity=50.0)
    z = np.linspace(0.5e-9, 14e-9, 200)
    curve = amplitude_curve(z, lever)
    ok = np.isfinite(curve.amplitude)
    zz = np.broadcast_to(z[:, None], ok.shape)[ok]
    g = tapping._balance(lever, zz, curve.amplitude[ok])[0]
    assert np.max(np.abs(g)) < 1e-9 * lever.drive_force
    three = np.isfinite(curve.amplitude).sum(axis=1) == 3
    assert three.any()
    assert (curve.stable[three] == [True, False, True]).all()  # the middle root is the saddle
    assert (~curve.repulsive_branch[three, 0]).all() and curve.repulsive_branch[three, 2].all()
    assert curve.attractive[three, 0].all()  # the low branch always attracts on the whole
    # the high branch repels, except at its far end where the net force turns (phase < 90 deg)
    high = curve.repulsive_branch[three, 2]
    assert (curve.attractive[three, 2] == (curve.phase[three, 2] > math.pi / 2))[high].all()


def test_array_call_equals_point_calls():
    z = [3e-9, 6e-9, 9.5e-9]
    curve = amplitude_curve(z)
    for i, zc in enumerate(z):
        one = amplitude_curve([zc])
        n = np.count_nonzero(np.isfinite(one.amplitude))
        assert np.allclose(one.amplitude[0, :n], curve.amplitude[i, :n], rtol=1e-12)


def test_approach_jumps_where_the_attractive_branch_ends_and_retract_where_repulsive_does():
    # at A0 = 15 nm the low branch ends inside the range (at 10 nm it reaches z_c < 0.2 A0)
    lever = TappingLever(free_amplitude=15e-9)
    z = np.linspace(0.2, 1.5, 400) * 15e-9
    curve = amplitude_curve(z, lever)
    down_a, _, down = curve.sweep("approach")
    up_a, _, up = curve.sweep("retract")
    assert len(down) == 1 and len(up) == 1
    both = z[curve.coexist]
    assert both.size > 2
    assert down[0] == pytest.approx(z[z < both.min()].max())  # the low branch ends
    assert up[0] == pytest.approx(z[z > both.max()].min())  # the high branch ends
    i, j = np.flatnonzero(z == down[0])[0], np.flatnonzero(z == up[0])[0]
    assert down_a[i] - down_a[i + 1] > 5 * abs(down_a[i + 2] - down_a[i + 1])  # a jump up
    assert up_a[j - 1] - up_a[j] > 5 * abs(up_a[j - 2] - up_a[j - 1])  # a jump down
    assert up[0] > down[0]  # hysteresis


@pytest.mark.slow
def test_unstable_root_leaves_for_a_stable_one():
    lever = TappingLever()
    curve = amplitude_curve([6e-9], lever)
    middle = np.flatnonzero(np.isfinite(curve.amplitude[0]) & ~curve.stable[0])
    assert middle.size == 1
    j = middle[0]
    state = integrate(6e-9, lever, start=(curve.amplitude[0, j] * 1.003, curve.phase[0, j]))
    stable = curve.amplitude[0][curve.stable[0]]
    assert np.min(np.abs(stable - state.amplitude)) < 0.01 * state.amplitude
    assert abs(state.amplitude - curve.amplitude[0, j]) > 0.03 * state.amplitude


def test_setpoint_state_lies_on_the_approach_curve():
    lever = TappingLever()
    zc, phase, e_dis, attractive = setpoint_state(0.7, lever)
    curve = amplitude_curve([zc], lever)
    amp, phs = curve.branch("attractive" if attractive else "repulsive")
    assert amp[0] == pytest.approx(0.7 * lever.free_amplitude, rel=2e-3)
    assert phs[0] == pytest.approx(phase, abs=math.radians(0.5))


# -- parameters and bad input ----------------------------------------------------------------------
# -- where the tip touches the sample ---------------------------------------------------------------
def test_indentation_is_a0_less_the_closest_distance_of_the_first_harmonic():
    lever = TappingLever()
    z, a = np.array([12e-9, 10e-9, 9e-9]), np.array([11.8e-9, 10e-9, 10e-9])
    # closest distance z_c - A: 0.2 nm (clear of a0 = 0.165 nm), 0 and -1 nm (in the sample)
    np.testing.assert_allclose(lever.indentation(z, a), [-0.035e-9, 0.165e-9, 1.165e-9],
                               rtol=1e-9)
    with pytest.raises(ValueError, match="distance and amplitude"):
        lever.indentation(z, a[:2])


def test_a_viscous_sample_takes_energy_exactly_from_the_states_that_touch():
    # the sample's damping acts only in contact (d < a0): on a viscous sample every state whose
    # motion stays clear dissipates nothing and every state that dips in dissipates, both
    # branches alike (E_dis from the phase, Cleveland's energy balance)
    lever = TappingLever(free_amplitude=12e-9, sample_viscosity=200.0)
    curve = amplitude_curve(12e-9 * np.linspace(1.5, 0.01, tapping.SETPOINT_GRID), lever)
    stable = curve.stable & np.isfinite(curve.amplitude)
    depth, e_dis = curve.indentation[stable], curve.dissipated_energy[stable]
    scale = math.pi * lever.spring_constant * 12e-9 ** 2 / lever.quality_factor
    clear, deep = depth < -0.01e-9, depth > 0.01e-9
    assert clear.any() and deep.any()
    assert np.all(np.abs(e_dis[clear]) < 1e-9 * scale)
    assert np.all(e_dis[deep] > 1e-6 * scale)
    # and the attractive branch holds states of both kinds at the defaults
    att = stable & ~curve.repulsive_branch
    assert (curve.indentation[att] > 0.1e-9).any() and (curve.indentation[att] < -0.1e-9).any()


@pytest.mark.slow
def test_the_time_integration_touches_where_indentation_says():
    # independent of the first-harmonic balance: integrate the lever on a viscous sample at two
    # attractive states the feedback holds (setpoints 0.9 and 0.99 of A0 = 12 nm); the sample's
    # damping does work only while the tip is in contact
    lever = TappingLever(free_amplitude=12e-9, sample_viscosity=200.0)
    for ratio, touches in ((0.9, True), (0.99, False)):
        zc, _, e_dis, attractive = setpoint_state(ratio, lever)
        assert attractive
        depth = lever.indentation(zc, ratio * 12e-9)
        assert (depth > 0) is touches and abs(depth) > 0.05e-9  # clear of the edge
        s = integrate(zc, lever, start=(ratio * 12e-9, math.pi / 2))
        closest = zc + float(s.deflection.min())
        assert (closest < lever.intermolecular_distance) is touches
        if touches:  # tens of zJ, as the phase says
            assert s.damping_work > 10e-21
            assert s.damping_work == pytest.approx(e_dis, rel=0.1)
        else:
            assert s.damping_work == 0.0


def test_parameter_tables_are_parameters_with_their_defaults_in_range():
    for table in (FORCE_PARAMETERS, TAPPING_PARAMETERS):
        for name, p in table.items():
            assert isinstance(p, Parameter) and p.name == name
            assert p.check(p.default) == p.default


@pytest.fixture
def no_integration(monkeypatch):
    def boom(*args, **kwargs):
        raise AssertionError("integration started before the input was checked")
    monkeypatch.setattr(tapping.integration, "odeint", boom)


@pytest.mark.parametrize("call, name", [
    (lambda: TappingLever(quality_factor=0.0), "quality_factor"),
    (lambda: TappingLever(quality_factor=-5.0), "quality_factor"),
    (lambda: TappingLever(frequency_ratio=3.0), "frequency_ratio"),
    (lambda: TappingLever(frequency_ratio=0.1), "frequency_ratio"),
    (lambda: TappingLever(free_amplitude=-1e-9), "free_amplitude"),
    (lambda: TappingLever(hamaker_constant=-1e-20), "hamaker_constant"),
    (lambda: integrate(0.1e-9, start=(0.05e-9, 0.0)), "start amplitude"),
    (lambda: integrate(-1e-9), "distance"),
    (lambda: integrate(5e-9, max_periods=10**9), "max_periods"),
    (lambda: amplitude_curve([5e-9, 0.0]), "distances"),
    (lambda: amplitude_curve(np.full(tapping.MAX_DISTANCES + 1, 5e-9)), "distances"),
    (lambda: setpoint_state(1.2), "setpoint_ratio"),
    (lambda: setpoint_state(1.0), "setpoint_ratio"),
    (lambda: tip_sample_force(1e-9, sample_viscosity=-1.0), "sample_viscosity"),
])
def test_bad_input_names_the_parameter_before_any_integration(no_integration, call, name):
    with pytest.raises(ValueError, match=name):
        call()


def test_lever_is_type_checked():
    with pytest.raises(TypeError, match="lever"):
        amplitude_curve([5e-9], lever={"quality_factor": 100})


# -- imaging through module (f)'s scanner ----------------------------------------------------------
def test_tapping_mode_images_a_two_material_sample_with_phase_contrast_from_dissipation():
    from afmsmiler.imaging.scanner import ScanSettings, scan
    from afmsmiler.modes import TappingMode
    from afmsmiler.samples import Sample

    px, n = 2e-9, 16
    heights = np.zeros((n, n))
    heights[:, :4] = 1e-9  # a terrace: topography the height channel must show
    hard = TappingLever(youngs_modulus=1e9)
    soft = TappingLever(youngs_modulus=1e9, sample_viscosity=300.0)  # same but dissipative

    def material(x, y):  # the right half is the dissipative one
        return (np.asarray(x) >= n * px / 2).astype(int)

    mode = TappingMode([hard, soft], setpoint_ratio=0.6, material=material)
    settings = ScanSettings(n * px, pixels=n, lines=n, scan_speed=1e-6)
    result = scan(Sample(heights, px), None, mode, settings)
    assert result.finished
    phase, e_dis = result.images["phase trace"], result.images["dissipation trace"]
    left, right = np.s_[:, 5:7], np.s_[:, 10:]
    # each half has the phase and dissipation of its own setpoint state
    for region, lever in ((left, hard), (right, soft)):
        _, phi, e, _ = setpoint_state(0.6, lever)
        assert np.allclose(phase[region], phi) and np.allclose(e_dis[region], e)
    assert abs(np.ptp(phase)) > math.radians(0.5)  # a contrast a phase image shows
    scale = math.pi * 40.0 * (0.6 * 10e-9) ** 2 / 400.0
    assert np.all(np.abs(e_dis[left]) < 1e-6 * scale) and np.all(e_dis[right] > 1e-3 * scale)
    # the phase contrast is the dissipation: E_dis from each half's phase is its channel value
    a = 0.6 * hard.free_amplitude
    assert np.allclose(soft.dissipated_energy(a, phase[right]), e_dis[right], rtol=1e-9)
    # height: the terrace, and a material step of z_c(soft) - z_c(hard)
    h = result.images["height trace"]
    assert np.allclose(h[:, 1] - h[:, 6], 1e-9)
    step = setpoint_state(0.6, soft)[0] - setpoint_state(0.6, hard)[0]
    assert np.allclose(h[:, 12] - h[:, 6], step)
    assert np.allclose(result.images["phase retrace"], phase)


def test_tapping_mode_checks_its_arguments_before_any_scan():
    from afmsmiler.modes import TappingMode
    with pytest.raises(ValueError, match="setpoint_ratio"):
        TappingMode(TappingLever(), setpoint_ratio=1.1)
    with pytest.raises(TypeError, match="lever"):
        TappingMode([TappingLever(), "soft"])
    with pytest.raises(TypeError, match="material"):
        TappingMode(TappingLever(), material=np.zeros((4, 4)))


# -- amplitude feedback with a finite bandwidth ------------------------------------------------
def _free_step(lever, ratio, times):
    """Open loop (no gains): the surface drops far away at t = 0+, the lever is free after."""
    t = np.concatenate(([0.0, 1e-15], times))
    r = np.concatenate(([0.0], np.full(times.size + 1, -1e-6)))
    return tapping.amplitude_feedback(r, t, lever, setpoint_ratio=ratio, amplitude_kp=0.0,
                                      amplitude_ki=0.0)


@pytest.mark.parametrize("ratio", [1.0, 0.998])
def test_amplitude_step_response_is_the_slow_flow_closed_form(ratio):
    """Averaged equations of the free lever: a = A e^(-i phi) relaxes as
    a(t) = a_inf + (a_0 - a_inf) exp(-(1/tau - i Delta) t), tau = 2 Q / w0,
    Delta = w0 (1 - W^2) / (2 W): its distance to the new state decays exponentially with tau."""
    lever = TappingLever(frequency_ratio=ratio)
    w0 = 2 * math.pi * lever.resonance_frequency
    tau = 2 * lever.quality_factor / w0
    assert lever.time_constant == pytest.approx(tau, rel=1e-15)
    times = np.linspace(0.0, 8 * tau, 81)[1:]
    line = _free_step(lever, 0.8, times)
    z_sp, phi_sp, _, _ = setpoint_state(0.8, lever)
    a_free, phi_free = free_response(lever)
    a_inf = a_free * np.exp(-1j * phi_free)
    a_0 = 0.8 * lever.free_amplitude * np.exp(-1j * phi_sp)
    delta = w0 * (1 - ratio ** 2) / (2 * ratio)
    expected = a_inf + (a_0 - a_inf) * np.exp(-(1 / tau - 1j * delta) * times)
    got = line.amplitude[2:] * np.exp(-1j * line.phase[2:])
    assert np.max(np.abs(got - expected)) < 1e-5 * lever.free_amplitude  # a_0: interpolated
    a_0 = line.amplitude[0] * np.exp(-1j * line.phase[0])  # the loop's own start, exactly
    expected = a_inf + (a_0 - a_inf) * np.exp(-(1 / tau - 1j * delta) * times)
    assert np.max(np.abs(got - expected)) < 1e-9 * lever.free_amplitude
    assert np.allclose(np.abs(got - a_inf), np.abs(a_0 - a_inf) * np.exp(-times / tau),
                       rtol=1e-6)
    # starting in phase with the free state, the amplitude itself is the exponential
    start = (0.0, 0.0, 1e-6, 0.8 * lever.free_amplitude, phi_free, 0.0)
    same = tapping.amplitude_feedback(np.full(times.size, -1e-6), times, lever,
                                      amplitude_kp=0.0, amplitude_ki=0.0, state=start)
    if ratio == 1.0:
        assert np.allclose(same.amplitude, lever.free_amplitude * (
            1 - 0.2 * np.exp(-times / tau)), rtol=1e-12)


@pytest.mark.slow
def test_amplitude_step_response_against_the_time_integration():
    """From the setpoint state, the sample taken away: scipy's integration of the full motion
    (lock-in over periods N - 10 to N) against the slow flow averaged over the same window,
    within 0.1 % of A0 (the averaging neglects terms of order 1/Q = 0.25 %)."""
    lever = TappingLever()
    z_sp, phi_sp, _, _ = setpoint_state(0.8, lever)
    period = 1 / lever.resonance_frequency
    for n in (20, 140, 300):
        state = integrate(1e-6, lever, start=(0.8 * lever.free_amplitude, phi_sp),
                          max_periods=n)
        window = (n - 10 + np.arange(640) / 64) * period
        line = _free_step(lever, 0.8, window)
        a = line.amplitude[2:] * np.exp(-1j * line.phase[2:])
        assert state.periods == n
        assert abs(np.mean(a)) == pytest.approx(state.amplitude, abs=1e-3 * 10e-9), n


def test_scanning_too_fast_the_tip_parachutes_off_a_down_step():
    """On a down step the amplitude rises at most to A0, the error saturates at A_sp - A0 and
    the positioner descends no faster than K_I (A0 - A_sp): the tip parachutes out of contact
    (z_c > A: it touches nothing) until it lands; scanned slowly it follows the step."""
    lever = TappingLever()
    tau = lever.time_constant
    ki, step = 2000.0, 10e-9
    n = 400
    r = np.where(np.arange(n) >= 50, -step, 0.0)
    fast = tapping.amplitude_feedback(r, np.arange(n) * tau / 10, lever, setpoint_ratio=0.8,
                                      amplitude_ki=ki)
    slow = tapping.amplitude_feedback(r, np.arange(n) * tau * 10, lever, setpoint_ratio=0.8,
                                      amplitude_ki=ki)
    assert np.max(np.abs(slow.height - r)[60:]) < 0.01 * step
    assert np.max(np.abs(slow.error)[60:]) < 0.01 * lever.free_amplitude
    lost = fast.distance > fast.amplitude + lever.intermolecular_distance
    assert lost[50:].sum() > 40  # more than 40 pixels (4 tau) out of contact
    # the landing takes at least step / (K_I (A0 - A_sp)) (the fastest descent)
    landed = 50 + int(np.argmax(np.abs(fast.height[50:] - r[50:]) < 0.05 * step))
    fastest = step / (ki * (lever.free_amplitude - 0.8 * lever.free_amplitude))
    assert (landed - 50) * tau / 10 > fastest
    # while out of contact the error is the saturated A_sp - A, never below A_sp - A0
    assert np.all(fast.error <= 0.2 * lever.free_amplitude + 1e-18)


def test_tapping_mode_with_pi_feedback_through_the_scanner():
    from afmsmiler.imaging.scanner import ScanSettings, scan
    from afmsmiler.modes import TappingMode
    from afmsmiler.samples import Sample

    lever = TappingLever()
    px, n = 5e-9, 32
    heights = np.zeros((4, n))
    heights[:, 10:20] = 5e-9
    sample = Sample(heights, px)
    ideal = scan(sample, None, TappingMode(lever, 0.8), ScanSettings(
        (n - 2) * px, scan_size_y=2 * px, pixels=n - 2, lines=2))
    # scanned slowly (10 ms a pixel, about 24 tau), the loop follows: the ideal image
    slow_settings = ScanSettings((n - 2) * px, scan_size_y=2 * px, pixels=n - 2, lines=2,
                                 scan_speed=px / 10e-3)
    mode = TappingMode(lever, 0.8, feedback="pi")
    assert mode.channels[-2:] == ("error trace", "error retrace")
    assert mode.unit("error trace") == "m"
    slow = scan(sample, None, mode, slow_settings)
    # at the edges the surface under the tip ramps by 5 nm in a pixel time: a PI loop follows
    # a ramp of speed v behind by v / K_I (dA/dz_c is about 1 on the attractive branch)
    lag = 5e-9 / 10e-3 / mode.amplitude_ki
    assert np.max(np.abs(slow.images["height trace"] - ideal.images["height trace"])) < 1.5 * lag
    assert np.max(np.abs(slow.images["error trace"])) < 1.5 * lag
    # scanned at 100 um/s (50 us a pixel, tau / 8): the edges smear and the error shows them
    fast = scan(sample, None, mode, slow_settings.replace(scan_speed=1e-4))
    error = fast.images["error trace"]
    assert np.max(np.abs(error)) > 0.1 * lever.free_amplitude
    assert np.max(np.abs(fast.images["height trace"] - ideal.images["height trace"])) > 1e-9


def test_feedback_bad_input():
    from afmsmiler.modes import TappingMode
    lever = TappingLever()
    with pytest.raises(ValueError, match="feedback"):
        TappingMode(lever, feedback="pid")
    with pytest.raises(TypeError, match="levers"):
        TappingMode(1.0)
    with pytest.raises(TypeError, match="levers"):
        TappingMode([lever, 2])
    with pytest.raises(ValueError, match="amplitude_ki"):
        TappingMode(lever, feedback="pi", amplitude_ki=1e6)
    with pytest.raises(ValueError, match="amplitude_kp"):
        TappingMode(lever, feedback="pi", amplitude_kp=-1.0)
    with pytest.raises(ValueError, match="levers"):
        TappingMode([lever, TappingLever(quality_factor=100.0)], feedback="pi")
    with pytest.raises(ValueError, match="times"):
        tapping.amplitude_feedback([0.0, 0.0], [1.0, 0.0])
    with pytest.raises(ValueError, match="times"):
        tapping.amplitude_feedback([0.0, 0.0], [0.0, 200.0])  # 200 s: 470 000 tau
    with pytest.raises(ValueError, match="setpoint_ratio"):
        tapping.amplitude_feedback([0.0], [0.0], setpoint_ratio=1.0)
    with pytest.raises(TypeError, match="state"):
        tapping.amplitude_feedback([0.0], [0.0], state=[1, 2])


def test_a_curve_carries_its_jumps_from_one_run_per_direction(monkeypatch):
    lever = TappingLever(free_amplitude=15e-9)
    z = np.linspace(0.2, 1.5, 400) * 15e-9
    curve = amplitude_curve(z, lever)
    runs = []
    original = tapping.AmplitudeCurve._sweep
    monkeypatch.setattr(tapping.AmplitudeCurve, "_sweep",
                        lambda self, way: runs.append(way) or original(self, way))
    zc = tapping.operating_point(curve, 0.8)[0]  # follows the approach
    jumps = curve.jumps
    assert sorted(runs) == ["approach", "retract"]  # each direction once, not the approach twice
    assert tapping.operating_point(curve, 0.8)[0] == zc and len(runs) == 2
    # the marks are where the branches end (the definition, as the jump test above reads it
    # off the coexistence region)
    both = z[curve.coexist]
    assert jumps["approach"] == [pytest.approx(z[z < both.min()].max())]
    assert jumps["retract"] == [pytest.approx(z[z > both.max()].min())]
    amp = curve.sweep("approach")[0]
    with pytest.raises(ValueError):  # the memo is the curve's: nobody writes into it
        amp[0] = 0.0


def test_on_branch_lines_each_roots_quantity_up_with_the_branch():
    lever = TappingLever(sample_viscosity=20.0)
    z = np.linspace(0.3, 1.5, 200) * lever.free_amplitude
    curve = amplitude_curve(z, lever)
    for name in tapping.BRANCHES:
        a, phi = curve.branch(name)
        ok = np.isfinite(a)
        assert ok.sum() > 10
        assert np.array_equal(curve.on_branch(curve.amplitude, name)[ok], a[ok])
        # independent of which column was picked: the lever's own formulas at (z_c, A, phi)
        depth = curve.on_branch(curve.indentation, name)
        assert depth[ok] == pytest.approx(lever.indentation(z[ok], a[ok]), rel=1e-12, abs=1e-21)
        e = curve.on_branch(curve.dissipated_energy, name)
        bound = curve.on_branch(curve.dissipated_energy_error, name)
        assert np.all(np.abs(e[ok] - lever.dissipated_energy(a[ok], phi[ok])) <= bound[ok])
    with pytest.raises(ValueError, match="values"):
        curve.on_branch(np.zeros(3), "attractive")
    with pytest.raises(ValueError, match="name"):
        curve.on_branch(curve.amplitude, "high")


def _reference_sweep(curve, direction):
    """The slow approach or retraction as the loop of numpy calls it was before issue 24."""
    order = np.argsort(curve.distance)
    order = order[::-1] if direction == "approach" else order
    n = curve.distance.size
    amp, phs = np.full(n, np.nan), np.full(n, np.nan)
    jumps, prev, side = [], None, None
    for i in order:
        js = np.flatnonzero(curve.stable[i] & np.isfinite(curve.amplitude[i]))
        if js.size == 0:
            continue
        js = js[np.argsort(curve.amplitude[i, js])]
        here = curve.amplitude[i, js]
        if prev is None:
            pick = 0 if direction == "approach" else js.size - 1
        elif js.size >= 2 and prev.size >= 2:
            pick = 0 if side == 0 else js.size - 1
        else:
            pick = int(np.argmin(np.abs(here - prev[side])))
            if prev.size >= 2 and js.size == 1 and \
                    np.argmin(np.abs(prev - here[0])) != (side % prev.size):
                jumps.append(float(curve.distance[i]))
        side = 0 if pick == 0 else -1
        amp[i], phs[i] = here[pick], curve.phase[i, js[pick]]
        prev = here
    return amp, phs, jumps


@pytest.mark.parametrize("a0, viscosity", [(5e-9, 0.0), (8e-9, 100.0), (12e-9, 100.0),
                                           (20e-9, 0.0)])
def test_the_sweep_equals_the_reference_walk(a0, viscosity):
    # issue 24: the sweep walks Python scalars (0.5 ms instead of 10); same states, same jumps
    lever = TappingLever(free_amplitude=a0, sample_viscosity=viscosity)
    curve = amplitude_curve(a0 * np.linspace(1.5, 0.01, tapping.SETPOINT_GRID), lever)
    jumped = 0
    for direction in tapping.SWEEPS:
        amp, phs, jumps = curve.sweep(direction)
        ref_amp, ref_phs, ref_jumps = _reference_sweep(curve, direction)
        np.testing.assert_array_equal(amp, ref_amp)
        np.testing.assert_array_equal(phs, ref_phs)
        assert jumps == ref_jumps
        jumped += len(jumps)
    assert jumped >= 1  # each case has a coexistence region to jump out of


@pytest.mark.parametrize("block", [1, 7, 50, 399, None])
@pytest.mark.parametrize("viscosity", [0.0, 300.0])
def test_a_curve_made_in_steps_is_the_curve_made_at_once(block, viscosity):
    """issue 24: the tapping panel makes its full curve a block of distances per turn of the
    kernel's loop; the steps sample g at ``block`` distances each (yielding the distances
    done), then refine every root at once, and return amplitude_curve's curve, bit for bit
    (both branches, their jumps, with and without the sample's viscosity)."""
    lever = TappingLever(free_amplitude=12e-9, sample_viscosity=viscosity)
    distances = lever.free_amplitude * np.linspace(1.5, 0.01, 400)
    whole = amplitude_curve(distances, lever)
    yielded, stepped = run_steps(tapping.amplitude_curve_steps(distances, lever,
                                                                block_distances=block))
    size = 400 if block is None else block
    assert yielded == [*range(size, 400, size), 400]
    for key in ("distance", "amplitude", "phase", "stable", "attractive", "repulsive_branch",
                "dissipated_energy", "dissipated_energy_error"):
        np.testing.assert_array_equal(getattr(stepped, key), getattr(whole, key))
    assert stepped.lever == whole.lever and stepped.jumps == whole.jumps
    # both branches are in the curve compared
    assert whole.repulsive_branch.any() and (whole.stable & ~whole.repulsive_branch).any()


@pytest.mark.parametrize("kwargs, name", [
    (dict(block_distances=0), "block_distances"),
    (dict(block_distances=tapping.MAX_DISTANCES + 1), "block_distances"),
    (dict(block_distances=2.5), "block_distances"),
    (dict(distances=[5e-9, -1e-9]), "distances"),
    (dict(lever="lever"), "lever")])
def test_curve_steps_check_their_arguments_when_called(monkeypatch, kwargs, name):
    """Bad input is named when the steps are asked for, before g is sampled anywhere (not at
    the first step, which a panel runs later, on the kernel's loop)."""
    def no_balance(*args, **kw):
        raise AssertionError("g was sampled")
    monkeypatch.setattr(tapping.balance, "_balance", no_balance)
    args = {"distances": [5e-9, 8e-9], "lever": TappingLever(), **kwargs}
    with pytest.raises((ValueError, TypeError), match=name):
        tapping.amplitude_curve_steps(**args)
