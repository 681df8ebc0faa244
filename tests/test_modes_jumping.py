"""Jumping mode: the pixel's force curve, the image, the comparison with contact mode, the time.

Independent sources: Hertz's closed form for a paraboloid, F = (4/3) E* sqrt(R) d^(3/2), with the
lever in series (Z_t = d + F_t / k); the pull-off forces 2 pi R w (DMT) and (3/2) pi R w (JKR);
module (f)'s dilation (:func:`afmsmiler.imaging.dilation.dilate`) for the true image a tip can
give; the slope of that surface and Amontons' law with adhesion (F_L = mu (F_N + F_ad) + F_N
tan(theta), Ogletree et al. 1996) for the lateral force of contact mode; the times counted by
hand from the lift, the z speed and the scan speed.
"""
import math

import numpy as np
import pytest

from afmsmiler.contact import ContactSystem, Parabolic, Spherical
from afmsmiler.controller import ContactLoop
from afmsmiler.imaging.dilation import dilate
from afmsmiler.imaging.scan_modes import ConstantForce
from afmsmiler.imaging.scanner import Scan, ScanSettings, scan
from afmsmiler.modes import jumping
from afmsmiler.modes.jumping import JumpingMode, apex_path, jump_curve, trigger_z_np
from afmsmiler.modes.lateral import friction_loop
from afmsmiler.samples import Sample, grating

TIP = Parabolic(radius=10e-9)
HARD = ContactSystem(spring_constant=1.0, tip=TIP, youngs_modulus=1e9, poisson_ratio=0.3)
STEP = 200e-9
# a tall grating: 200 nm lines, 320 nm wide, on 10 nm pixels; the scan grid falls on its pixels
SAMPLE = grating((16, 128), 10e-9, period=640e-9, height=STEP)
SETTINGS = ScanSettings(1240e-9, scan_size_y=40e-9, pixels=124, lines=4, scan_speed=100e-6)
F_T = 10e-9


def hertz_trigger(system, force):
    """Z_t = d + F / k with Hertz's d = (3 F / (4 E* sqrt(R)))^(2/3) (a paraboloid)."""
    d = (3 * force / (4 * system.reduced_modulus * math.sqrt(system.tip.radius))) ** (2 / 3)
    return d + force / system.spring_constant


# -- one pixel ------------------------------------------------------------------------------
@pytest.mark.parametrize("force", [0.5e-9, 10e-9, 200e-9])
def test_trigger_against_hertz(force):
    assert trigger_z_np(HARD, force) == pytest.approx(hertz_trigger(HARD, force), rel=1e-9)




@pytest.mark.parametrize("spring_constant", [0.1, 1.0, 40.0])
@pytest.mark.parametrize("youngs_modulus", [1e6, 1e9, 1e11])
def test_trigger_is_within_its_tolerance_of_hertz(spring_constant, youngs_modulus):
    # the search's stated tolerance, 1e-15 m + 1e-12 Z_t, against Hertz's closed form over soft
    # and stiff levers and samples and five decades of force (issue 24: the search stops on an
    # estimate of its interpolation error)
    system = ContactSystem(spring_constant=spring_constant, tip=TIP,
                           youngs_modulus=youngs_modulus, poisson_ratio=0.3)
    for force in (1e-10, 1e-8, 1e-6, 1e-5):
        z = hertz_trigger(system, force)
        assert abs(trigger_z_np(system, force) - z) <= 1e-15 + 1e-12 * z

@pytest.mark.parametrize("force", [0.5e-9, 10e-9, 200e-9])
def test_dmt_trigger_against_the_closed_form(force):
    # DMT: F = (4/3) E* sqrt(R) d^(3/2) - 2 pi R w in contact (Derjaguin, Muller and Toporov
    # 1975), so d = (3 (F_t + 2 pi R w) / (4 E* sqrt R))^(2/3) and Z_t = d + F_t / k
    system = HARD.replace(adhesion="dmt", work_of_adhesion=0.05)
    loaded = force + 2 * math.pi * TIP.radius * 0.05
    d = (3 * loaded / (4 * system.reduced_modulus * math.sqrt(TIP.radius))) ** (2 / 3)
    assert trigger_z_np(system, force) == pytest.approx(d + force / system.spring_constant,
                                                        rel=1e-11)


@pytest.mark.parametrize("model", ["dmt", "jkr", None])
def test_the_approach_branch_at_a_point_does_not_depend_on_the_ramp(model):
    # issue 24: the trigger's search runs the approach branch on grids of Z_np; each value must be
    # the one-point state system.at gives (the branch has no memory on approach)
    system = HARD.replace(adhesion=model, work_of_adhesion=0.05) if model else HARD
    z = np.linspace(-2e-9, 30e-9, 41)
    grid = jumping._approach_force(system, z)
    alone = np.array([system.at(v, "approach").force[0] for v in z])
    np.testing.assert_allclose(grid, alone, rtol=1e-12, atol=1e-24)
    # and the trigger found on those grids is where the one-point state crosses F_t, within the
    # tolerance 1e-15 m + 1e-12 Z_t
    z_t = trigger_z_np(system, F_T)
    tol = 1e-15 + 1e-12 * z_t
    assert system.at(z_t - tol).force[0] < F_T < system.at(z_t + tol).force[0]

def test_a_kept_trigger_is_the_one_of_the_system_asked_for():
    """The trigger is kept per (system, force): an equal system gets it again, a system that
    differs in any field (a panel's modulus slider) gets its own, each against Hertz."""
    first = trigger_z_np(HARD, F_T)
    again = trigger_z_np(HARD.replace(), F_T)  # an equal, distinct object
    assert again == first == pytest.approx(hertz_trigger(HARD, F_T), rel=1e-9)
    for other in (HARD.replace(youngs_modulus=HARD.youngs_modulus / 3),
                  HARD.replace(spring_constant=HARD.spring_constant * 2)):
        z = trigger_z_np(other, F_T)
        assert z != first and z == pytest.approx(hertz_trigger(other, F_T), rel=1e-9)
    assert trigger_z_np(HARD, 2 * F_T) == pytest.approx(hertz_trigger(HARD, 2 * F_T), rel=1e-9)


@pytest.mark.parametrize("model, factor", [("dmt", 2.0), ("jkr", 1.5)])
def test_curve_reaches_the_trigger_and_pulls_off(model, factor):
    w = 0.05
    system = HARD.replace(adhesion=model, work_of_adhesion=w)
    curve = jump_curve(system, trigger_force=F_T, lift_height=60e-9, z_speed=10e-6, points=2001)
    assert curve.approach_force[-1] == pytest.approx(F_T, rel=1e-9)
    assert curve.pull_off_force == pytest.approx(factor * math.pi * TIP.radius * w, rel=1e-9)
    # the sampled retract reaches down to the pull-off (within the ramp's resolution) and ends
    # off the surface: the lift took the tip beyond the jump-off
    assert -curve.retract_force.min() == pytest.approx(curve.pull_off_force, rel=2e-2)
    assert curve.retract_force[-1] == 0.0
    assert curve.retract_z_np[-1] < curve.snap_off_z_np


def test_curve_times_and_dmt_trigger():
    w = 0.05
    system = HARD.replace(adhesion="dmt", work_of_adhesion=w)
    curve = jump_curve(system, trigger_force=F_T, lift_height=60e-9, z_speed=10e-6)
    # DMT: the elastic force at the trigger is F_t + 2 pi R w
    f_ad = 2 * math.pi * TIP.radius * w
    d = (3 * (F_T + f_ad) / (4 * system.reduced_modulus * math.sqrt(TIP.radius))) ** (2 / 3)
    assert curve.trigger_z_np == pytest.approx(d + F_T / system.spring_constant, rel=1e-9)
    assert curve.cycle_time == pytest.approx(2 * 60e-9 / 10e-6)
    assert curve.approach_time[-1] == pytest.approx(6e-3)
    assert curve.retract_time[-1] == pytest.approx(12e-3)


def test_lift_must_clear_the_jump_off():
    system = HARD.replace(adhesion="dmt", work_of_adhesion=0.1)
    needed = trigger_z_np(system, F_T) - system.snap_off_z_np
    with pytest.raises(ValueError, match=r"lift_height must be > .* got 1e-08 m"):
        jump_curve(system, trigger_force=F_T, lift_height=10e-9)
    with pytest.raises(ValueError, match="lift_height"):
        JumpingMode(system, trigger_force=F_T, lift_height=0.999 * needed)
    JumpingMode(system, trigger_force=F_T, lift_height=1.001 * needed)


def test_sphere_cannot_reach_a_huge_trigger():
    soft = ContactSystem(spring_constant=10.0, tip=Spherical(radius=5e-9), youngs_modulus=1e5)
    with pytest.raises(ValueError, match="trigger_force"):
        trigger_z_np(soft, 1e-6)


@pytest.mark.parametrize("kwargs, name", [
    (dict(trigger_force=0.0), "trigger_force"), (dict(trigger_force=-1e-9), "trigger_force"),
    (dict(lift_height=-1e-9), "lift_height"), (dict(z_speed=0.0), "z_speed"),
    (dict(z_speed=10.0), "z_speed"), (dict(points=1), "points")])
def test_bad_input_is_named(kwargs, name):
    with pytest.raises(ValueError, match=name):
        jump_curve(HARD, **kwargs)


def test_bad_mode_input():
    with pytest.raises(TypeError, match="systems"):
        JumpingMode([HARD, "soft"])
    with pytest.raises(TypeError, match="systems"):
        JumpingMode(1.0)
    with pytest.raises(ValueError, match="systems"):
        JumpingMode([])
    with pytest.raises(TypeError, match="tip"):
        JumpingMode([HARD, HARD.replace(tip=Parabolic(radius=20e-9))])
    with pytest.raises(TypeError, match="material"):
        JumpingMode(HARD, material=3)
    with pytest.raises(ValueError, match="z_speed"):
        JumpingMode(HARD, z_speed=-1.0)


# -- the image and contact mode ------------------------------------------------------------------
def test_jumping_gives_the_dilated_surface_where_contact_mode_lags():
    """On a 200 nm grating at 100 um/s, jumping's height is the dilated sample (module (f)),
    contact mode's is off by a fifth of the step at the edges: it must follow the edge while
    moving, jumping measures at rest."""
    mode = JumpingMode(HARD, trigger_force=F_T, lift_height=250e-9)
    result = scan(SAMPLE, TIP, mode, SETTINGS)
    assert result.finished and result.crashed is None
    # the scan's pixels are the sample's columns 2..125 (the grid lies on the sample's pixels)
    true = dilate(SAMPLE, TIP).heights[6:10, 2:126]
    for d in ("trace", "retrace"):
        assert np.max(np.abs(result.images[f"height {d}"] - true)) < 1e-15
        assert np.all(result.images[f"lateral force {d}"] == 0.0)
    contact = scan(SAMPLE, TIP, ConstantForce(ContactLoop()), SETTINGS)
    error = np.max(np.abs(contact.images["height trace"] - true))
    assert error > 0.2 * STEP


def test_lateral_force_of_contact_mode_at_the_step():
    """The reason, quantified: sliding up the tip-dilated edge, the lever pushes with
    F_N (mu + tan(theta)), tan(theta) the steepest slope between pixels, 5 F_N here; jumping
    moves in the air (0)."""
    line = dilate(SAMPLE, TIP).heights[8]
    mu, f_n = 0.2, 10e-9
    loop = friction_loop(line, mu, SAMPLE.pixel_size, normal_force=f_n)
    steepest = np.max(np.abs(np.gradient(line, SAMPLE.pixel_size)))
    assert steepest > 4.0  # the paraboloid's flank: slope rho / R up to sqrt(2 h / R) = 6.3
    assert np.max(loop.trace) == pytest.approx(f_n * (mu + steepest), rel=1e-12)
    assert np.max(loop.trace) > 5 * f_n


def test_sticky_sample_adhesion_channel_and_contact_friction():
    """Sticky islands: the adhesion channel gives each material's 2 pi R w; in contact mode the
    adhesion adds to the load, so friction drags with mu (F_N + F_ad)."""
    flat = Sample(np.zeros((16, 64)), 10e-9)
    clean = HARD.replace(adhesion="dmt", work_of_adhesion=0.005)
    sticky = HARD.replace(adhesion="dmt", work_of_adhesion=0.2)

    def material(x, y):
        return (x > 320e-9).astype(int)

    mode = JumpingMode([clean, sticky], trigger_force=F_T, lift_height=60e-9, material=material)
    settings = ScanSettings(600e-9, scan_size_y=40e-9, pixels=60, lines=4)
    result = scan(flat, TIP, mode, settings)
    adhesion = result.images["adhesion trace"]
    x = Scan(flat, TIP, mode, settings).plan.x_trace
    for system, where in ((clean, x <= 320e-9), (sticky, x > 320e-9)):
        assert np.allclose(adhesion[where], 2 * math.pi * TIP.radius * system.work_of_adhesion,
                           rtol=1e-12)
    mu, f_n = 0.2, F_T
    f_ad = 2 * math.pi * TIP.radius * sticky.work_of_adhesion
    loop = friction_loop(np.zeros(60), mu, 10e-9, normal_force=f_n + f_ad)
    assert loop.friction[30] == pytest.approx(mu * (f_n + f_ad))
    assert np.all(result.images["lateral force trace"] == 0.0)


def test_softer_material_looks_lower_by_its_deeper_trigger():
    soft = HARD.replace(youngs_modulus=5e6)
    flat = Sample(np.zeros((16, 64)), 10e-9)

    def material(x, y):
        return (x > 320e-9).astype(int)

    mode = JumpingMode([HARD, soft], trigger_force=F_T, lift_height=100e-9, material=material)
    result = scan(flat, TIP, mode, ScanSettings(600e-9, scan_size_y=40e-9, pixels=60, lines=4))
    h = result.images["height trace"]
    drop = hertz_trigger(soft, F_T) - hertz_trigger(HARD, F_T)
    assert np.allclose(h[:, -5:], -drop, rtol=1e-9)
    assert np.allclose(h[:, :5], 0.0, atol=1e-18)


def test_a_lift_below_the_step_runs_into_the_wall():
    # the tip's flank spreads the 200 nm step over some 6 pixels of the apex surface: a 40 nm
    # lift is too small for its steepest rise between pixels
    mode = JumpingMode(HARD, trigger_force=F_T, lift_height=40e-9)
    result = scan(SAMPLE, TIP, mode, SETTINGS)
    crash = result.crashed
    assert crash is not None and crash.row == 0 and crash.direction == "trace"
    assert math.isinf(crash.force)
    # the first pixel whose apex surface rises more than lift - Z_t above the previous one
    row = Scan(SAMPLE, TIP, mode, SETTINGS).plan.trace[0]
    rise = np.diff(row) > 40e-9 - trigger_z_np(HARD, F_T)
    assert crash.column == int(np.argmax(rise)) + 1
    assert np.isnan(result.images["height trace"][0, crash.column:]).all()


# -- the price -------------------------------------------------------------------------------
def test_acquisition_time_against_contact_mode():
    lift, v_z = 250e-9, 20e-6
    mode = JumpingMode(HARD, trigger_force=F_T, lift_height=lift, z_speed=v_z)
    dt = SETTINGS.pixel_size / SETTINGS.scan_speed
    assert mode.pixel_time(SETTINGS) == pytest.approx(2 * lift / v_z + dt)
    jump = mode.acquisition_time(SETTINGS)
    assert jump == pytest.approx(4 * 2 * 124 * (25e-3 + 1e-4))
    contact = SETTINGS.scan_time
    assert contact == pytest.approx(4 * 247 * 1e-4)
    assert jump / contact > 200
    with pytest.raises(TypeError, match="settings"):
        mode.pixel_time(3.0)


def test_parameters_table():
    assert set(jumping.PARAMETERS) == {"trigger_force", "lift_height", "z_speed"}
    for p in jumping.PARAMETERS.values():
        assert p.low <= p.default <= p.high
    with pytest.raises(TypeError):
        jumping.PARAMETERS["z_speed"] = None


def test_compare_with_contact_in_one_call():
    sticky = HARD.replace(adhesion="dmt", work_of_adhesion=0.1)
    out = jumping.compare_with_contact(SAMPLE, TIP, SETTINGS, system=sticky, setpoint=10e-9,
                                       trigger_force=F_T, lift_height=250e-9)
    assert out.crashed is None
    assert out.jumping_error < 1e-15
    assert out.contact_error > 0.2 * STEP
    # the load: k_c R = 1 N/m x 10 nm plus DMT's 2 pi R w
    f_n = 1.0 * 10e-9 + 2 * math.pi * TIP.radius * 0.1
    assert out.normal_force == pytest.approx(f_n)
    steepest = np.max(np.abs(np.gradient(out.true_height, SETTINGS.pixel_size, axis=1)))
    assert out.contact_lateral_max == pytest.approx(f_n * (0.2 + steepest), rel=1e-12)
    assert np.all(out.jumping_lateral == 0.0)
    assert out.contact_time == pytest.approx(SETTINGS.scan_time)
    assert out.jumping_time / out.contact_time > 100
    with pytest.raises(ValueError, match="friction_coefficient"):
        jumping.compare_with_contact(SAMPLE, TIP, SETTINGS, system=HARD,
                                     friction_coefficient=-0.1)
    with pytest.raises(TypeError, match="settings"):
        jumping.compare_with_contact(SAMPLE, TIP, None, system=HARD)


def test_a_bad_material_map_is_named():
    flat = Sample(np.zeros((8, 16)), 10e-9)
    mode = JumpingMode([HARD, HARD.replace(youngs_modulus=5e6)],
                       material=lambda x, y: np.full(np.shape(x), 2))
    with pytest.raises(ValueError, match=r"material\(x, y\) must give integers in \[0, 1\]"):
        scan(flat, TIP, mode, ScanSettings(100e-9, scan_size_y=20e-9, pixels=10, lines=2))


def test_line_refuses_a_state_that_is_not_a_height():
    """The campaign found JumpingMode.line(state=nan) accepted silently."""
    mode = JumpingMode(HARD, trigger_force=F_T)
    plan = Scan(SAMPLE, None, mode, SETTINGS).plan
    with pytest.raises(ValueError, match="state"):
        mode.line(plan, 0, float("nan"))


def test_apex_path_touches_where_the_curve_has_a_contact_force():
    # independent of the path's Z_np thresholds: in module (d)'s DMT law the free tip feels no
    # force and the touching tip the elastic force less the adhesion 2 pi R w (never zero)
    system = ContactSystem(spring_constant=1.0, tip=Parabolic(radius=10e-9),
                           youngs_modulus=1e9, adhesion="dmt", work_of_adhesion=20e-3)
    curve = jump_curve(system)
    n = curve.approach_z_np.size
    surface = np.array([0.0, 5e-9, -3e-9])
    path = apex_path(curve, surface, 20e-9, frames=n)
    assert path.height.shape == path.x.shape == path.touching.shape == (3 * 2 * n,)
    force = np.concatenate((curve.approach_force, curve.retract_force))
    z = np.concatenate((curve.approach_z_np, curve.retract_z_np))
    for j, s in enumerate(surface):
        cycle = slice(2 * n * j, 2 * n * (j + 1))
        assert np.array_equal(path.touching[cycle], force != 0.0)
        assert np.all(path.x[cycle] == 20e-9 * j)
        h = path.height[cycle]
        touch = path.touching[cycle]
        assert np.all(h[touch] == s)  # on the surface while touching
        assert h[~touch] == pytest.approx(s + np.abs(z[~touch]), abs=1e-18)  # |Z_np| above it
    # the snap-off lies below Z_np = 0: the retract holds on past where the approach touched
    assert curve.snap_off_z_np < 0.0
    with pytest.raises(ValueError, match="frames"):
        apex_path(curve, surface, 20e-9, frames=1)
    with pytest.raises(ValueError, match="pixel_size"):
        apex_path(curve, surface, 0.0)
