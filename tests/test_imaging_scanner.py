"""The virtual scanner and its modes (module (f)).

References: module (c)'s :func:`afmsmiler.controller.scan_image` and
:meth:`ContactLoop.response` (constant force), module (d)'s :meth:`ContactSystem.indent`
(constant height), numpy's ``rot90`` (scan angle), exact planes (bilinear sampling, tilt) and the
drift and creep law written out here (Jung and Gweon 2000).
"""
import math

import numpy as np
import pytest

from afmsmiler.contact import ContactSystem, Parabolic
from afmsmiler.controller import ContactLoop, scan_image
from afmsmiler.imaging.scan_modes import (ConstantForce, ConstantHeight, Crash, Mode, ModeLine,
                                     PARAMETERS as MODE_PARAMETERS)
from afmsmiler.imaging.scanner import PARAMETERS, Scan, ScanResult, ScanSettings, scan
from afmsmiler.parameters import UNITS
from afmsmiler.samples import Sample, particles

PX = 4e-9
SPEED = 1e-3  # m/s: 4 us per pixel, fast enough that the loop lags visibly


@pytest.fixture(scope="module")
def image():
    return particles((48, 64), PX, seed=3)


def whole(sample, **kw):
    """Settings whose scan grid is the sample's own pixels."""
    rows, cols = sample.heights.shape
    return ScanSettings(cols * sample.pixel_size, scan_size_y=rows * sample.pixel_size_y,
                        pixels=cols, lines=rows, scan_speed=SPEED, **kw)


def loop():
    return ContactLoop(kp=0.3, ki=5e3)  # a loop that lags: trace and retrace differ


# -- settings ---------------------------------------------------------------------------------
def test_settings_defaults_and_derived_quantities():
    s = ScanSettings(2e-6, pixels=128, scan_speed=4e-6)
    assert (s.scan_size_y, s.lines, s.shape) == (2e-6, 128, (128, 128))
    assert s.pixel_size == pytest.approx(2e-6 / 128, rel=1e-15)
    assert s.pixel_time == pytest.approx(s.pixel_size / 4e-6, rel=1e-15)
    assert s.line_time == pytest.approx(255 * s.pixel_time, rel=1e-15)
    assert s.line_rate == pytest.approx(1 / s.line_time)
    fast = s.with_line_rate(2.0)
    assert fast.line_rate == pytest.approx(2.0, rel=1e-12)
    assert fast.scan_speed == pytest.approx(255 * s.pixel_size * 2.0, rel=1e-12)
    assert ScanSettings(1e-6, scan_size_y=0.5e-6, pixels=64, lines=32).pixel_size_y == \
        pytest.approx(0.5e-6 / 32)


def test_parameters_are_si_with_display_units_from_the_table():
    for p in PARAMETERS.values():
        assert p.display_unit in UNITS and UNITS[p.display_unit][0] == p.unit, p.name
    assert PARAMETERS["scan_speed"].unit == "m/s" and PARAMETERS["angle"].display_unit == "deg"
    assert PARAMETERS["drift_x"].display_unit == "nm/s"
    assert PARAMETERS["drift_x"].to_display(2e-9) == pytest.approx(2.0)
    assert MODE_PARAMETERS["damage_force"].unit == "N"


@pytest.mark.parametrize("kw, name", [
    (dict(pixels=0), "pixels"), (dict(pixels=1), "pixels"), (dict(lines=0), "lines"),
    (dict(pixels=2.5), "pixels"), (dict(scan_speed=0.0), "scan_speed"),
    (dict(scan_speed=10.0), "scan_speed"), (dict(scan_speed=math.nan), "scan_speed"),
    (dict(angle=4.0), "angle"), (dict(noise=-1e-9), "noise"), (dict(offset=(1.0,)), "offset"),
    (dict(offset=(1e-3, 0.0)), "offset_x"), (dict(drift=(0.0, 1.0)), "drift_y"),
    (dict(tilt=(2.0, 0.0)), "tilt_x"), (dict(creep=-0.1), "creep"), (dict(seed=-1), "seed"),
    (dict(pixels=2048, lines=2048, scan_size_y=1e-6), None),
])
def test_settings_reject_bad_values_naming_them(kw, name):
    if name is None:  # in range one by one: a bound on the product, not an error
        ScanSettings(1e-6, **kw)
        return
    with pytest.raises(ValueError, match=name):
        ScanSettings(1e-6, **kw)
    with pytest.raises(ValueError, match="scan_size"):
        ScanSettings(0.0)


def test_line_rate_out_of_range_is_named():
    with pytest.raises(ValueError, match="line_rate"):
        ScanSettings(1e-6).with_line_rate(0.0)
    with pytest.raises(ValueError, match="line_rate .*scan_speed"):
        ScanSettings(100e-6, pixels=2048, lines=16).with_line_rate(1e4)


# -- bad input --------------------------------------------------------------------------------
def test_a_scan_range_larger_than_the_sample_names_both(image):
    big = ScanSettings(1e-6, pixels=64)  # the sample is 63 x 4 nm = 252 nm wide
    with pytest.raises(ValueError, match=r"scan_size \(1 um x 1 um.*beyond the sample \(0.252 um"):
        Scan(image, None, ConstantForce(loop()), big)
    rotated = whole(image, angle=math.radians(30))  # its corners leave the sample
    with pytest.raises(ValueError, match="scan_size .* at angle 30 deg"):
        Scan(image, None, ConstantForce(loop()), rotated)
    shifted = ScanSettings(100e-9, pixels=16, offset=(80e-9, 0.0))
    with pytest.raises(ValueError, match="offset"):
        Scan(image, None, ConstantForce(loop()), shifted)


def test_drift_that_leaves_the_sample_is_named(image):
    s = ScanSettings(100e-9, pixels=16, scan_speed=1e-7, drift=(5e-9, 0.0))
    assert s.scan_time == pytest.approx(31.0)  # 16 lines of 31 pixel times of 62.5 ms
    # 155 nm of drift; the scan's edge is 76 nm from the sample's
    Scan(image, None, ConstantForce(loop()), s.replace(drift=(2e-9, 0.0)))  # 62 nm: inside
    with pytest.raises(ValueError, match=r"drift \(5e-09, 0\) m/s"):
        Scan(image, None, ConstantForce(loop()), s)


def test_nan_heights_and_wrong_types_are_rejected(image):
    with pytest.raises(ValueError, match="heights"):
        Sample(np.full((8, 8), np.nan), PX)
    bad = Sample(image.heights.copy(), PX)
    bad.heights[3, 4] = np.nan  # an array mutated after the Sample was made
    with pytest.raises(ValueError, match=r"sample heights must be finite.*\(3, 4\)"):
        Scan(bad, None, ConstantForce(loop()), whole(image))
    with pytest.raises(TypeError, match="sample"):
        Scan(image.heights, None, ConstantForce(loop()), whole(image))
    with pytest.raises(TypeError, match="mode"):
        Scan(image, None, loop(), whole(image))
    with pytest.raises(TypeError, match="tip"):
        Scan(image, 20e-9, ConstantForce(loop()), whole(image))
    with pytest.raises(TypeError, match="loop"):
        ConstantForce(ContactSystem())
    volts = Sample(image.heights * 1e9, PX, channel="deflection", unit="V")
    with pytest.raises(ValueError, match="sample must hold heights in m"):
        Scan(volts, None, ConstantForce(loop()), whole(image))
    with pytest.raises(ValueError, match="sample must be a 2-D"):
        Scan(Sample(np.zeros(16), PX), None, ConstantForce(loop()), ScanSettings(40e-9))


def test_zero_pixels_is_rejected_before_any_work():
    with pytest.raises(ValueError, match="pixels must be an integer in"):
        ScanSettings(1e-6, pixels=0)


# -- geometry ---------------------------------------------------------------------------------
class Topography(Mode):
    """A tiny mode defined outside the package: records the apex surface it is handed."""

    channels = ("height trace", "height retrace", "phase trace")
    units = {"phase trace": "rad"}

    def line(self, plan, row, state):
        count = (state or 0) + 1
        return ModeLine({"height trace": plan.trace[row], "height retrace": plan.retrace[row],
                         "phase trace": np.full(plan.shape[1], 0.5)}, count)


def test_a_mode_defined_elsewhere_plugs_in_and_keeps_its_state(image):
    result = scan(image, None, Topography(), whole(image))
    assert result.finished and result.lines_done == 48 and not result.stopped
    np.testing.assert_array_equal(result.images["height trace"], image.heights)
    np.testing.assert_array_equal(result.images["height retrace"], image.heights)
    assert result.units["phase trace"] == "rad" and result.units["height trace"] == "m"
    assert result.channels["phase trace"].unit == "rad"
    s = Scan(image, None, Topography(), whole(image))
    s.run()
    assert s._state == 48  # the state went from line to line


def test_the_scan_angle_rotates_the_grid_on_the_sample():
    h = np.random.default_rng(1).normal(size=(32, 32)) * 1e-9
    sample = Sample(h, PX)
    result = scan(sample, None, Topography(), whole(sample, angle=math.pi / 2))
    np.testing.assert_allclose(result.images["height trace"], np.rot90(h), rtol=0, atol=1e-24)


def test_bilinear_sampling_is_exact_on_a_plane_at_any_angle_and_offset():
    rows, cols = 40, 50
    x, y = np.arange(cols) * PX, np.arange(rows) * PX
    a, b, c = 0.03, -0.02, 1e-9
    sample = Sample(a * x[None, :] + b * y[:, None] + c, PX)
    s = ScanSettings(90e-9, scan_size_y=60e-9, pixels=30, lines=20, angle=0.4,
                     offset=(5e-9, -7e-9), scan_speed=SPEED)
    run = Scan(sample, None, Topography(), s)
    result = run.run()
    plan = run.plan
    expected = a * plan.x_trace + b * plan.y_trace + c
    np.testing.assert_allclose(result.images["height trace"], expected, rtol=1e-12, atol=1e-22)
    # the grid is the rotated, offset one: centre of the scan = sample centre + offset
    u = (np.arange(30) + 0.5) * 3e-9 - 45e-9
    v = (np.arange(20) + 0.5) * 3e-9 - 30e-9
    cx, cy = 49 * PX / 2 + 5e-9, 39 * PX / 2 - 7e-9
    np.testing.assert_allclose(plan.x_trace, cx + np.cos(0.4) * u[None] - np.sin(0.4) * v[:, None],
                               rtol=0, atol=1e-20)
    np.testing.assert_allclose(plan.y_trace, cy + np.sin(0.4) * u[None] + np.cos(0.4) * v[:, None],
                               rtol=0, atol=1e-20)


def test_tilt_adds_a_plane_about_the_sample_centre():
    sample = Sample(np.zeros((20, 30)), PX)
    tilt = (math.radians(2.0), math.radians(-1.0))
    result = scan(sample, None, Topography(), whole(sample, tilt=tilt))
    x, y = np.arange(30) * PX, np.arange(20) * PX
    expected = (math.tan(tilt[0]) * (x - x[-1] / 2)[None, :]
                + math.tan(tilt[1]) * (y - y[-1] / 2)[:, None])
    np.testing.assert_allclose(result.images["height trace"], expected, rtol=1e-12, atol=1e-24)


def test_drift_and_creep_follow_the_stated_law(image):
    drift, gamma, t0, offset = (2e-9, -1e-9), 0.02, 0.05, (20e-9, 10e-9)
    s = ScanSettings(120e-9, pixels=12, scan_speed=1e-6, drift=drift, creep=gamma,
                     creep_time=t0, offset=offset)
    run = Scan(image, None, Topography(), s)
    nominal = Scan(image, None, Topography(), s.replace(drift=(0.0, 0.0), creep=0.0))
    dt = 10e-9 / 1e-6
    for row, col, direction in ((0, 0, "trace"), (5, 7, "trace"), (11, 3, "retrace")):
        k = row * 23 + (col if direction == "trace" else 11 + (11 - col))
        t = k * dt
        creep = gamma * math.log10(1 + t / t0)
        x0, y0 = nominal.position(row, col, direction)
        x, y = run.position(row, col, direction)
        assert x == pytest.approx(x0 + drift[0] * t + offset[0] * creep, rel=1e-12, abs=1e-21)
        assert y == pytest.approx(y0 + drift[1] * t + offset[1] * creep, rel=1e-12, abs=1e-21)
    plan = run.plan
    assert not np.array_equal(plan.trace, plan.retrace)  # the passes see different points


def test_noise_is_seeded_gaussian_and_only_on_channels_in_metres(image):
    s = whole(image, noise=1e-9, seed=7)
    a = scan(image, None, Topography(), s)
    b = scan(image, None, Topography(), s)
    np.testing.assert_array_equal(a.images["height trace"], b.images["height trace"])
    d = a.images["height trace"] - image.heights
    assert d.std() == pytest.approx(1e-9, rel=0.05) and abs(d.mean()) < 1e-10
    np.testing.assert_array_equal(a.images["phase trace"], 0.5)
    c = scan(image, None, Topography(), s.replace(seed=8))
    assert not np.array_equal(a.images["height trace"], c.images["height trace"])


# -- constant force ---------------------------------------------------------------------------
def test_constant_force_equals_module_c_called_directly(image):
    lp = loop()
    mode = ConstantForce(lp, setpoint=5e-9)
    result = scan(image, None, mode, whole(image))
    ref = scan_image(lp, image.heights, PX, speed=SPEED, setpoint=5e-9)
    assert np.ptp(ref.height_trace - ref.height_retrace) > 1e-10  # the loop lags: a real test
    for ours, theirs in (("height trace", ref.height_trace),
                         ("height retrace", ref.height_retrace),
                         ("error trace", ref.trace + ref.trace_z_np - 5e-9),
                         ("error retrace", ref.retrace + ref.retrace_z_np - 5e-9)):
        np.testing.assert_allclose(result.images[ours], theirs, rtol=0,
                                   atol=1e-12 * np.ptp(image.heights))


def test_constant_force_on_a_rotated_grid_equals_scan_image_on_the_sampled_surface(image):
    lp = loop()
    s = ScanSettings(150e-9, scan_size_y=100e-9, pixels=40, lines=25, angle=0.3,
                     offset=(10e-9, 5e-9), scan_speed=SPEED)
    run = Scan(image, None, ConstantForce(lp), s)
    result = run.run()
    ref = scan_image(lp, run.plan.trace, s.pixel_size, speed=SPEED)
    np.testing.assert_allclose(result.images["height trace"], ref.height_trace, rtol=0,
                               atol=1e-12 * np.ptp(image.heights))
    np.testing.assert_allclose(result.images["height retrace"], ref.height_retrace, rtol=0,
                               atol=1e-12 * np.ptp(image.heights))


def test_line_by_line_gives_the_numbers_of_the_whole_image(image):
    lp = loop()
    run = Scan(image, None, ConstantForce(lp), whole(image))
    records = list(run.lines())
    assert [r.row for r in records] == list(range(48))
    assert all(r.crash is None for r in records)
    ref = scan_image(lp, image.heights, PX, speed=SPEED)
    stacked = np.array([r.channels["height trace"] for r in records])
    np.testing.assert_array_equal(stacked, ref.height_trace)
    stacked = np.array([r.channels["height retrace"] for r in records])
    np.testing.assert_array_equal(stacked, ref.height_retrace)


def test_constant_force_with_drift_runs_the_chained_polygon_of_both_passes(image):
    lp = loop()
    s = ScanSettings(120e-9, pixels=20, lines=10, scan_speed=1e-4, drift=(3e-8, 1e-8))
    run = Scan(image, None, ConstantForce(lp), s)
    result = run.run()
    plan = run.plan
    n = 20
    # module (c)'s public response on the same path, built here: trace i, retrace i, ...
    path = np.concatenate([np.concatenate((plan.trace[i], plan.retrace[i, ::-1][1:]))
                           for i in range(10)])
    t = np.arange(path.size) * s.pixel_time
    z_c, z_np = lp.response(t, path - path[0])
    z_np = z_np + lp.steady_state(10e-9, path[0]).z_np
    z_np = z_np.reshape(10, 2 * n - 1)
    flat = lp.steady_state(10e-9, 0.0).z_np
    np.testing.assert_allclose(result.images["height trace"], -(z_np[:, :n] - flat), rtol=0,
                               atol=1e-9 * np.ptp(path))
    np.testing.assert_allclose(result.images["height retrace"], -(z_np[:, n - 1:][:, ::-1] - flat),
                               rtol=0, atol=1e-9 * np.ptp(path))


# -- stop, result ------------------------------------------------------------------------------
def test_a_scan_stopped_half_way_keeps_its_finished_lines(image):
    lp = loop()
    full = scan(image, None, ConstantForce(lp), whole(image))
    run = Scan(image, None, ConstantForce(lp), whole(image))
    assert run.result.lines_done == 0 and run.result.channels == {}
    calls = []

    def stop():
        calls.append(1)
        return len(calls) > 20

    result = run.run(stop=stop)
    assert result.stopped and result.lines_done == 20 and not result.finished
    assert result.progress == pytest.approx(20 / 48)
    height = result.channels["height trace"]
    assert isinstance(height, Sample) and height.heights.shape == (20, 64)
    assert (height.channel, height.unit) == ("height trace", "m")
    assert height.metadata["lines_done"] == 20 and height.metadata["scan_speed"] == SPEED
    assert height.metadata["mode"] == "ConstantForce"
    assert height.pixel_size == PX and height.pixel_size_y == PX
    np.testing.assert_array_equal(height.heights, full.images["height trace"][:20])
    assert np.isnan(result.images["height trace"][20:]).all()
    assert run.step() is None and run.result.lines_done == 20  # a stopped scan stays stopped


def test_stop_method_and_result_snapshot(image):
    run = Scan(image, None, Topography(), whole(image))
    for record in run.lines():
        if record.row == 4:
            run.stop()
    snapshot = run.result
    assert isinstance(snapshot, ScanResult) and snapshot.lines_done == 5 and snapshot.stopped
    snapshot.images["height trace"][0, 0] = 1.0  # a copy: the scan's own data is untouched
    assert run.result.images["height trace"][0, 0] == image.heights[0, 0]
    with pytest.raises(TypeError, match="stop"):
        Scan(image, None, Topography(), whole(image)).run(stop=3)


# -- constant height --------------------------------------------------------------------------
def system():
    return ContactSystem(spring_constant=0.5, tip=Parabolic(radius=10e-9), youngs_modulus=1e9,
                         poisson_ratio=0.3)


def test_constant_height_equals_module_d_at_every_pixel(image):
    sy = system()
    mode = ConstantHeight(sy, z_np=2e-9, damage_force=1.0)
    result = scan(image, None, mode, whole(image))
    assert result.crashed is None and result.finished
    z = 2e-9 + image.heights
    expected = np.array([[sy.indent(zz).z_c[0] for zz in row] for row in z[::7]])
    np.testing.assert_allclose(result.images["deflection trace"][::7], expected, rtol=1e-14,
                               atol=0)
    np.testing.assert_array_equal(result.images["deflection retrace"],
                                  result.images["deflection trace"])
    assert (result.images["deflection trace"] == 0).any()  # out of contact over the holes
    assert (result.images["deflection trace"] > 0).any()


def test_constant_height_crash_is_flagged_and_keeps_the_finished_lines(image):
    sy = system()
    z = 2e-9 + image.heights
    force = sy.indent(z.ravel()).force.reshape(z.shape)
    peak = np.maximum.accumulate(force.max(axis=1))  # the largest force up to each row
    first = 5 + int(np.argmax(peak[5:] > peak[4:-1]))  # a row after 5 beats all earlier ones
    threshold = peak[first - 1]  # passed first on that row (|F| > threshold is strict)
    over = np.argwhere(np.abs(force) > threshold)
    row, col = over[0]  # the first in scan order: rows first, then the trace's columns
    assert row == first
    result = scan(image, None, ConstantHeight(sy, 2e-9, threshold), whole(image))
    assert result.crashed == Crash(int(row), int(col), pytest.approx(force[row, col], rel=1e-14),
                                   "trace")
    assert result.lines_done == row and not result.finished and not result.stopped
    safe = scan(image, None, ConstantHeight(sy, 2e-9, 1.0), whole(image))
    np.testing.assert_array_equal(result.images["deflection trace"][:row],
                                  safe.images["deflection trace"][:row])
    line = result.images["deflection trace"][row]
    np.testing.assert_array_equal(line[:col + 1], safe.images["deflection trace"][row, :col + 1])
    assert np.isnan(line[col + 1:]).all()
    assert np.isnan(result.images["deflection trace"][row + 1:]).all()
    assert np.isnan(result.images["deflection retrace"][row:]).all()
    assert result.channels["deflection trace"].heights.shape == (row, 64)


def test_constant_height_validates_its_arguments():
    with pytest.raises(TypeError, match="system"):
        ConstantHeight(loop(), 1e-9, 1e-8)
    with pytest.raises(ValueError, match="damage_force"):
        ConstantHeight(system(), 1e-9, 0.0)
    with pytest.raises(ValueError, match="z_np"):
        ConstantHeight(system(), math.nan, 1e-8)


def test_the_mode_tip_must_be_the_scan_tip(image):
    mode = ConstantHeight(system(), 1e-9, 1e-6)
    with pytest.raises(ValueError, match="tip .* must be the tip of the mode"):
        Scan(image, Parabolic(radius=30e-9), mode, whole(image))


# -- with a real tip ---------------------------------------------------------------------------
def test_a_tip_scans_the_dilated_surface(image):
    from afmsmiler.imaging.dilation import dilate
    tip = Parabolic(radius=15e-9)
    lp = loop()
    run = Scan(image, tip, ConstantForce(lp), whole(image))
    result = run.run()
    apex = dilate(image, tip)
    np.testing.assert_array_equal(run.plan.apex.heights, apex.heights)
    assert (apex.heights >= image.heights).all() and (apex.heights > image.heights).any()
    ref = scan_image(lp, apex.heights, PX, speed=SPEED)
    np.testing.assert_allclose(result.images["height trace"], ref.height_trace, rtol=0,
                               atol=1e-12 * np.ptp(image.heights))
    np.testing.assert_allclose(result.images["error retrace"],
                               ref.retrace + ref.retrace_z_np - 10e-9, rtol=0,
                               atol=1e-12 * np.ptp(image.heights))


def test_constant_height_with_its_tip_follows_the_dilated_surface(image):
    from afmsmiler.imaging.dilation import dilate
    sy = system()
    result = scan(image, sy.tip, ConstantHeight(sy, 2e-9, 1.0), whole(image))
    z = 2e-9 + dilate(image, sy.tip).heights
    np.testing.assert_allclose(result.images["deflection trace"],
                               sy.indent(z.ravel()).z_c.reshape(z.shape), rtol=1e-14, atol=0)


def test_tilt_is_added_before_the_dilation():
    from afmsmiler.imaging.dilation import dilate
    sample = particles((32, 32), PX, count=3, seed=2)
    tip, tilt = Parabolic(radius=20e-9), (math.radians(3.0), 0.0)
    result = scan(sample, tip, Topography(), whole(sample, tilt=tilt))
    x = np.arange(32) * PX
    tilted = Sample(sample.heights + math.tan(tilt[0]) * (x - x[-1] / 2)[None, :], PX)
    np.testing.assert_allclose(result.images["height trace"], dilate(tilted, tip).heights,
                               rtol=0, atol=1e-22)


def adhesive(model):
    return ContactSystem(spring_constant=0.5, tip=Parabolic(radius=10e-9), youngs_modulus=1e9,
                         poisson_ratio=0.3, adhesion=model, work_of_adhesion=0.05)


@pytest.mark.parametrize("model", ["dmt", "jkr"])
def test_adhesive_constant_height_follows_approach_then_retract(model):
    sy = adhesive(model)
    assert -12e-9 < sy.snap_off_z_np < -2e-9
    x = np.arange(40) * PX
    sample = Sample(np.tile(x * 14e-9 / x[-1], (3, 1)), PX)  # a slope: 0 to 14 nm along x
    result = scan(sample, None, ConstantHeight(sy, -10e-9, 1.0), whole(sample))
    cycle = sy.approach_retract(-10e-9 + sample.heights[0])  # module (d) on the same ramp
    for row in range(3):  # every line snaps off before its end: each starts afresh
        np.testing.assert_allclose(result.images["deflection trace"][row], cycle.approach.z_c,
                                   rtol=1e-12, atol=0)
        np.testing.assert_allclose(result.images["deflection retrace"][row][::-1],
                                   cycle.retract.z_c, rtol=1e-12, atol=0)
    retrace = result.images["deflection retrace"][0]
    trace = result.images["deflection trace"][0]
    stuck = (retrace < 0) & (trace == 0)  # held by adhesion on the way back only
    assert stuck.any()


def test_an_adhesive_contact_carries_over_to_the_next_line():
    sy = adhesive("dmt")
    x = np.arange(40) * PX
    sample = Sample(np.tile(x * 10e-9 / x[-1], (3, 1)), PX)
    z_np = 0.4 * sy.snap_off_z_np  # above the snap-off, below 0: stuck if in contact
    result = scan(sample, None, ConstantHeight(sy, z_np, 1.0), whole(sample))
    first = result.images["deflection trace"]
    assert first[0, 0] == 0.0  # line 0 starts out of contact (approach branch)
    assert first[1, 0] < 0.0 and first[2, 0] < 0.0  # later lines start stuck (retract branch)
    assert first[1, 0] == pytest.approx(sy.at(z_np, "retract").z_c[0], rel=1e-12)


def test_a_scan_can_start_at_a_later_row(image):
    lp = loop()
    full = scan(image, None, ConstantForce(lp), whole(image))
    run = Scan(image, None, ConstantForce(lp), whole(image))
    rows = [record.row for record in run.lines(start=10)]
    assert rows == list(range(10, 48))
    result = run.result
    assert (result.first_row, result.lines_done, result.finished_lines) == (10, 48, 38)
    assert result.finished and np.isnan(result.images["height trace"][:10]).all()
    np.testing.assert_array_equal(result.channels["height trace"].heights,
                                  full.images["height trace"][10:])
    assert result.channels["height trace"].metadata["first_row"] == 10
    with pytest.raises(ValueError, match="start must be an integer"):
        list(Scan(image, None, Topography(), whole(image)).lines(start=48))
    begun = Scan(image, None, Topography(), whole(image))
    begun.step()
    with pytest.raises(ValueError, match="start must be given before the first line"):
        next(begun.lines(start=5))
    assert next(begun.lines(start=1)).row == 1  # where it is: no change


def test_a_tip_wider_than_the_image_is_refused_at_once(image):
    with pytest.raises(ValueError, match="tip"):
        Scan(image, Parabolic(radius=1e-6), ConstantForce(loop()), whole(image))


class Broken(Mode):
    channels = ("a", "b")

    def line(self, plan, row, state):
        return ModeLine({"a": np.zeros(plan.shape[1])})


def test_a_mode_that_breaks_the_interface_is_named(image):
    with pytest.raises(ValueError, match="gave no channel 'b'"):
        Scan(image, None, Broken(), whole(image)).step()

    class Empty(Broken):
        channels = ()

    with pytest.raises(ValueError, match="mode must list its channels"):
        Scan(image, None, Empty(), whole(image))
    with pytest.raises(TypeError):
        Mode()  # abstract: line() is required


def test_a_sphere_buried_crashes_with_an_infinite_force():
    from afmsmiler.contact import Spherical
    sy = ContactSystem(spring_constant=100.0, tip=Spherical(radius=5e-9), youngs_modulus=1e6,
                       poisson_ratio=0.3)
    sample = Sample(np.zeros((4, 8)), PX)
    result = scan(sample, None, ConstantHeight(sy, 1.5 * sy.z_np_limit, 1.0), whole(sample))
    assert result.crashed == Crash(0, 0, math.inf, "trace") and result.lines_done == 0
    assert np.isnan(result.images["deflection trace"]).all() and result.channels == {}


@pytest.mark.parametrize("tip", [Parabolic(radius=15e-9), "sphere", "cone", "pyramid"])
def test_a_zoomed_scan_dilates_only_what_it_can_feel_and_gets_the_same_surface(tip):
    from scipy.ndimage import map_coordinates

    from afmsmiler.contact import Conical, Pyramidal, Spherical
    from afmsmiler.imaging.dilation import dilate
    tip = {"sphere": Spherical(radius=12e-9), "cone": Conical(half_angle=math.radians(30)),
           "pyramid": Pyramidal(face_angle=math.radians(40))}.get(tip, tip)
    big = particles((120, 160), PX, seed=5)
    s = ScanSettings(120e-9, scan_size_y=80e-9, pixels=40, lines=30, angle=0.5,
                     offset=(60e-9, -40e-9), scan_speed=SPEED, tilt=(0.02, -0.01))
    run = Scan(big, tip, Topography(), s)
    plan = run.plan
    assert plan.apex.heights.size < 0.6 * big.heights.size  # a part of the sample
    x, y = np.arange(160) * PX, np.arange(120) * PX
    tilted = Sample(big.heights + math.tan(0.02) * (x - x[-1] / 2)[None, :]
                    + math.tan(-0.01) * (y - y[-1] / 2)[:, None], PX)
    whole_apex = dilate(tilted, tip).heights
    expected = map_coordinates(whole_apex, [plan.y_trace / PX, plan.x_trace / PX], order=1)
    np.testing.assert_allclose(plan.trace, expected, rtol=0, atol=1e-12 * np.ptp(whole_apex))
    # inside the scan's bounding box the part equals the whole sample's dilation
    c0, r0 = (round(v / PX) for v in plan.apex_origin)
    xs = np.concatenate((plan.x_trace, plan.x_retrace)) / PX
    ys = np.concatenate((plan.y_trace, plan.y_retrace)) / PX
    cols = slice(int(np.floor(xs.min())), int(np.ceil(xs.max())) + 1)
    rows = slice(int(np.floor(ys.min())), int(np.ceil(ys.max())) + 1)
    part = plan.apex.heights[rows.start - r0:rows.stop - r0, cols.start - c0:cols.stop - c0]
    np.testing.assert_allclose(part, whole_apex[rows, cols], rtol=0,
                               atol=1e-15 * np.ptp(whole_apex))


# -- bad input found by the API campaign (tests/test_api_campaign.py) -------------------------
def small_scan(mode):
    sample = Sample(np.zeros((8, 8)), 10e-9)
    return Scan(sample, getattr(mode, "tip", None), mode, ScanSettings(60e-9, pixels=4))


def height_mode():
    return ConstantHeight(ContactSystem(tip=Parabolic(50e-9)), z_np=1e-9)


@pytest.mark.parametrize("make", [lambda: ConstantForce(loop()), height_mode])
def test_a_mode_names_a_plan_that_is_not_a_plan_and_a_row_outside_it(make):
    mode = make()
    plan = small_scan(mode).plan
    state = mode.start(plan)
    for bad in (None, 0.0, "plan", plan.trace):
        with pytest.raises(TypeError, match="^plan"):
            mode.start(bad)
        with pytest.raises(TypeError, match="^plan"):
            mode.line(bad, 0, state)
    for bad in (-1, 4, 1.0, True, np.nan, "0"):
        with pytest.raises(ValueError, match=r"^row must be an integer in \[0, 3\]"):
            mode.line(plan, bad, state)


def test_constant_force_names_a_state_that_start_did_not_return():
    mode = ConstantForce(loop())
    plan = small_scan(mode).plan
    for bad in (None, 1.0, {"height trace": plan.trace}):
        with pytest.raises(TypeError, match="^state must be the images ConstantForce.start"):
            mode.line(plan, 0, bad)
    other = mode.start(Scan(Sample(np.zeros((8, 8)), 10e-9), None, mode,
                            ScanSettings(60e-9, pixels=2, lines=2)).plan)
    with pytest.raises(ValueError, match=r"^state must hold images of the plan's shape \(4, 4\)"):
        mode.line(plan, 0, other)


def test_constant_height_state_is_none_or_a_bool():
    mode = height_mode()
    plan = small_scan(mode).plan
    assert mode.line(plan, 0, True).channels.keys() == mode.line(plan, 0, None).channels.keys()
    for bad in (np.nan, "no", np.ones(3)):
        with pytest.raises(TypeError, match="^state must be None or a bool"):
            mode.line(plan, 0, bad)


def test_a_mode_names_a_channel_it_does_not_have():
    mode = ConstantForce(loop())
    assert mode.unit("error trace") == "m"
    for bad in ("deflection trace", np.nan, ["error trace"]):
        with pytest.raises(ValueError, match="^channel must be one of"):
            mode.unit(bad)


def test_displacement_names_a_time_that_is_not_finite_and_non_negative():
    s = ScanSettings(1e-6, pixels=16, drift=(1e-9, 0.0))
    dx, dy = s.displacement(np.array([[0.0, 2.0]]))
    assert dx.shape == (1, 2) and dx[0, 1] == 2e-9 and not dy.any()
    for bad in (np.nan, -1.0, np.inf, "1", [0.0, np.nan]):
        with pytest.raises(ValueError, match="^t must be"):
            s.displacement(bad)


def test_lines_checks_its_start_at_the_call_not_at_the_first_line():
    scan_ = small_scan(ConstantForce(loop()))
    for bad in (-1, 4, 1.5, "1"):
        with pytest.raises(ValueError, match="^start must be an integer"):
            scan_.lines(bad)  # not iterated: a generator would have raised nothing here
    assert scan_.result.lines_done == 0 and [r.row for r in scan_.lines(2)] == [2, 3]


def test_position_names_a_direction_that_is_not_one():
    scan_ = small_scan(ConstantForce(loop()))
    for bad in (np.ones(3), "up", None):
        with pytest.raises(ValueError, match="^direction must be one of"):
            scan_.position(0, 0, bad)


def test_heights_whose_range_overflows_a_float_are_named():
    h = np.full((8, 8), 1.7e308)
    h[::2] = -1.7e308  # each value finite, max - min = inf
    sample = Sample(h, 10e-9)
    for tip in (None, Parabolic(50e-9)):
        with pytest.raises(ValueError, match="^sample heights must span a range a float"):
            Scan(sample, tip, ConstantForce(loop()), ScanSettings(60e-9, pixels=4))


@pytest.mark.parametrize("tip", [Parabolic(radius=400e-9), "cone"])
def test_a_zoom_into_a_corner_with_a_blunt_tip_scans_the_whole_samples_dilation(tip):
    # the part of the sample the scan can feel, clipped at the corner, was narrower than the
    # tip's footprint although the sample is not: the scan was refused as "a tip wider than
    # the image (22 pixels)"; the reference is the dilation of the whole sample
    from afmsmiler.contact import Conical
    from afmsmiler.imaging.dilation import dilate
    tip = Conical(half_angle=math.radians(75)) if tip == "cone" else tip
    sample = particles((64, 64), 10e-9, seed=1)
    settings = ScanSettings(40e-9, pixels=4, offset=(-280e-9, -280e-9), scan_speed=SPEED)
    plan = Scan(sample, tip, ConstantForce(loop()), settings).plan
    np.testing.assert_allclose(plan.trace, dilate(sample, tip).heights[2:6, 2:6], rtol=0,
                               atol=1e-15 * np.ptp(sample.heights))


def test_an_unstable_loop_crashes_where_it_overflows_and_keeps_the_finished_lines():
    # module (c) scans an unstable loop too (its signals grow to inf, then NaN); the image used
    # to come back NaN from there on with nothing said. Reference: module (c)'s scan_image
    unstable = ContactLoop(ki=2.2e6)
    assert not unstable.is_stable().stable
    sample = particles((48, 48), 10e-9, seed=2)
    settings = ScanSettings(400e-9, pixels=16, lines=40, scan_speed=3e-3)
    run = Scan(sample, None, ConstantForce(unstable, setpoint=5e-9), settings)
    result = run.run()
    ref = scan_image(unstable, run.plan.trace, settings.pixel_size, speed=3e-3, setpoint=5e-9)
    with np.errstate(invalid="ignore"):  # inf - inf where module (c)'s signals overflowed
        error = ref.trace + ref.trace_z_np - 5e-9
    row = int(np.argmin(np.isfinite(error).all(axis=1)))  # the first line that overflows
    assert 0 < row < 40 and result.crashed is not None and not result.finished
    assert (result.crashed.row, result.lines_done, result.crashed.direction) == (
        row, row, "trace")
    assert result.crashed.force == math.inf
    assert result.crashed.column == int(np.argmin(np.isfinite(error[row])))
    for name, image in result.channels.items():  # the finished lines, finite
        assert np.isfinite(image.heights).all() and image.heights.shape == (row, 16), name
    np.testing.assert_array_equal(result.images["error trace"][:row], error[:row])
    np.testing.assert_array_equal(result.images["height trace"][:row], ref.height_trace[:row])
    assert np.isnan(result.images["height trace"][row, result.crashed.column:]).all()
    assert np.isnan(result.images["height retrace"][row:]).all()
