"""Module (g)'s panels without a browser: one model run per slider move (none for a setpoint
move: the curve is the same), the state the panel shows equals the model run directly
(setpoint_state, friction_loop, frequency_shift_curve, jump_curve) or an independent formula
(DMT's pull-off 2 pi R w, the blend's moduli), and the suggestions notebook 07 makes happen as it
says (the setpoint that picks the branch, the slope that leaks into a trace but not into the
friction map, the lift that clears the bars, the noise that biases the modulus map)."""
import functools
import html
import math
import re

import numpy as np
import pytest

from afmsmiler.contact import ContactSystem, Parabolic
from afmsmiler.modes import fm, force_volume, jumping, lateral, tapping
from afmsmiler.modes import (TappingLever, friction_loop, friction_sample, setpoint_state,
                             tip_sample_force)
from afmsmiler.parameters import UNITS
from afmsmiler.ui.modes import (FM_DEFAULTS, FM_DISTANCES, FORCE_VOLUME_DEFAULTS,
                                     FORCE_VOLUME_MAP, FORCE_VOLUME_SLIDERS, JUMPING_DEFAULTS,
                                     JUMPING_SCAN,
                                     LATERAL_DEFAULTS, LATERAL_SAMPLE, TAPPING_DEFAULTS,
                                     ForceVolumePanel, FrequencyShiftPanel, JumpingPanel,
                                     LateralPanel, TappingPanel, lateral_lever, operating_point)
from tests.recording import Recorder

NM = 1 / UNITS["nm"][1]


def _count(monkeypatch, module, name):
    calls = []
    original = getattr(module, name)

    def counting(*args, **kwargs):
        calls.append(1)
        return original(*args, **kwargs)

    monkeypatch.setattr(module, name, counting)
    return calls


# -- tapping ------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def tap():
    return TappingPanel()


def test_tapping_panel_one_curve_per_move_and_none_for_the_setpoint(monkeypatch):
    # every curve, made at once (amplitude_curve) or in steps, is one run of these steps
    calls = _count(monkeypatch, tapping.balance, "_amplitude_curve_steps")
    panel = TappingPanel()
    assert len(calls) == 1 and panel.model_runs == 1
    panel.set(setpoint_ratio=0.9)
    assert len(calls) == 1  # the same lever: the curve is read again, not computed
    for name, value in (("quality_factor", 300.0), ("free_amplitude", 15.0),
                        ("sample_viscosity", 100.0), ("hamaker_constant", 100.0)):
        panel.set(**{name: value})
    assert len(calls) == 5 and panel.model_runs == 5


def _from_browser(panel, **values):
    """Set ``values`` as a drag's moves from the browser reach the panel in a live kernel (the
    update its loop runs for them, :meth:`Panel._settle`)."""
    panel.in_drag = True
    try:
        panel.set(**values)
    finally:
        panel.in_drag = False


def test_tapping_panel_live_shows_a_coarse_curve_then_the_full_one(monkeypatch):
    """In a live kernel a lever move shows the curve at every s-th distance at once, said so on
    screen, with no jumps, held state or readout from it; a move during the wait replaces the
    pending full curve, a move back to the lever shown cancels it; both curves equal the
    model's own at their distances."""
    import asyncio

    import afmsmiler.ui.panel as ui_panel
    from afmsmiler.ui.modes import TAPPING_COARSE_STRIDE as s
    panel = TappingPanel()
    start = panel.last
    monkeypatch.setattr(ui_panel, "running_as_notebook", lambda: True)
    # the order of moves and full curves is tested, not the delay: a loaded machine's sleep of
    # a third of it must still end before it
    panel.full_delay = 0.15
    runs = panel.model_runs

    def title():
        return panel.figure.axes["amplitude"].get_title()

    async def drag():
        _from_browser(panel, free_amplitude=15.0)
        first = panel.coarse
        assert title().startswith("coarse curve") and "nm" not in title()
        assert "computing the full curve" in panel.readout.value
        assert panel.last is start  # nothing read from the coarse curve
        assert not panel.figure.lines["amplitude", "jump approach"].get_visible()
        assert len(panel.figure.lines["amplitude", "point"].get_xdata()) == 0
        await asyncio.sleep(panel.full_delay / 3)
        _from_browser(panel, free_amplitude=16.0)  # before the first full curve was due
        await asyncio.sleep(3 * panel.full_delay)
        full16 = panel.last
        _from_browser(panel, free_amplitude=18.0)
        await asyncio.sleep(panel.full_delay / 3)
        _from_browser(panel, free_amplitude=16.0)  # back to the curve shown: nothing pending
        assert panel.coarse is None and panel.last.curve is full16.curve
        await asyncio.sleep(3 * panel.full_delay)
        # a value a cell sets, and a panel made in a live kernel, are whole at once (the cell
        # may read them; the 3D view is shown with the panel)
        panel.set(free_amplitude=17.0)
        assert panel.coarse is None and panel.last.lever.free_amplitude == pytest.approx(17e-9)
        made = TappingPanel()
        assert made.coarse is None and made.last is not None
        panel.set(free_amplitude=16.0)
        return first, full16

    first, full16 = asyncio.run(drag())
    assert panel.model_runs - runs == 6  # three coarse curves, one full drag (16 nm), two sets
    for curve, a0 in ((first, 15e-9), (full16.curve, 16e-9)):
        lever = curve.lever
        assert lever.free_amplitude == pytest.approx(a0, rel=1e-12)
        distances = a0 * np.linspace(1.5, 0.01, tapping.SETPOINT_GRID)
        coarse = curve is first
        model = tapping.amplitude_curve(distances[::s] if coarse else distances, lever)
        np.testing.assert_allclose(curve.distance, model.distance, rtol=1e-15)
        np.testing.assert_allclose(curve.amplitude, model.amplitude, rtol=1e-12)
        np.testing.assert_array_equal(curve.stable, model.stable)
    assert first.distance.size == tapping.SETPOINT_GRID // s
    assert not title().startswith("coarse") and "A0 = 16 nm" in title()
    assert "nm" in panel.readout.value and "computing" not in panel.readout.value
    zc, *_ = setpoint_state(panel.last.setpoint_ratio, panel.last.lever)
    assert panel.last.distance == pytest.approx(zc, rel=1e-12)


def test_tapping_panel_holds_the_state_setpoint_state_finds(tap):
    for r in (0.8, 0.9, 0.6):
        tap.set(setpoint_ratio=r)
        s = tap.last
        zc, phase, e_dis, attractive = setpoint_state(r, s.lever)
        assert s.distance == pytest.approx(zc, rel=1e-12)
        assert s.phase == pytest.approx(phase, rel=1e-12)
        assert s.dissipated_energy == pytest.approx(e_dis, rel=1e-9, abs=1e-30)
        assert s.attractive is attractive
        x, y = tap.figure.lines["amplitude", "point"].get_data()
        assert x[0] == pytest.approx(zc * NM) and y[0] == pytest.approx(r * 12.0)


def _coexistence_runs(curve):
    z = np.sort(curve.distance)
    both = curve.coexist[np.argsort(curve.distance)].astype(int)
    edges = np.flatnonzero(np.diff(np.r_[0, both, 0]))
    return [(z[i], z[j - 1]) for i, j in zip(edges[::2], edges[1::2])]


def test_notebook_tapping_text_says_what_the_model_shows():
    # notebook 07's tapping section, at the panel's defaults: the attractive branch's phase lag
    # lies above 90 deg, the repulsive branch's tip is in the sample all along, the grey comes in
    # two stretches with no attractive branch between about 3 and 9.5 nm, and the tip touches
    # where A lies above z_c - a0 (the dash-dotted line), the attractive branch's too near its end
    panel = TappingPanel()
    curve = panel.last.curve
    a, phase = curve.branch("attractive")
    r, _ = curve.branch("repulsive")
    assert np.all(np.degrees(phase[np.isfinite(a)]) > 90.0)
    lever = curve.lever
    assert np.all(lever.indentation(curve.distance[np.isfinite(r)], r[np.isfinite(r)]) > 1e-9)
    (lo1, hi1), (lo2, hi2) = _coexistence_runs(curve)
    assert 2.5e-9 < hi1 < 3.5e-9 and 9e-9 < lo2 < 10e-9
    between = (curve.distance > 3.5e-9) & (curve.distance < 9e-9)
    assert np.all(np.isnan(a[between]))
    touching = np.isfinite(a) & (lever.indentation(curve.distance, np.nan_to_num(a)) > 0)
    assert touching.any()
    panel.set(setpoint_ratio=0.82)  # the book: the lowest attractive setpoint, 0.41 nm deep
    assert panel.last.branch == "attractive" and f"{panel.last.indentation * NM:.2g}" == "0.41"
    z, amp = panel.figure.lines["amplitude", "contact"].get_data()
    np.testing.assert_allclose(np.asarray(amp) / NM, np.asarray(z) / NM
                               - lever.intermolecular_distance, rtol=1e-12, atol=1e-21)


def test_notebook_suggestion_the_setpoint_picks_the_branch():
    # notebook 07, from the defaults: setpoint 0.8 ends on the repulsive branch, 1.7 nm into the
    # sample; 0.9 keeps the tip on the attractive one, dipping about 0.1 nm in; at 0.99 it stays
    # clear; with A0 = 8 nm even 0.5 stays attractive, tapping gently
    assert TAPPING_DEFAULTS["free_amplitude"] == 12.0 and TAPPING_DEFAULTS["setpoint_ratio"] == 0.8
    tap = TappingPanel(vis=Recorder())
    s = tap.last
    assert s.branch == "repulsive" and s.touches
    assert f"{s.indentation * NM:.2g}" == "1.7"
    title = tap.figure.axes["amplitude"].get_title()
    assert "repulsive branch, tip 1.7 nm into the sample" in title
    assert "yes, 1.7 nm deep" in tap.readout.value
    tap.set(setpoint_ratio=0.9)
    s = tap.last
    assert s.branch == "attractive" and s.touches and 0.05e-9 < s.indentation < 0.2e-9
    assert "attractive branch, tip 0.13 nm into the sample" in \
        tap.figure.axes["amplitude"].get_title()
    assert tap.scene.touching_frames > 0  # the 3D view's tip turns orange: it touches
    tap.set(setpoint_ratio=0.99)
    s = tap.last
    assert s.branch == "attractive" and not s.touches
    assert "clear of it" in tap.figure.axes["amplitude"].get_title()
    assert "no, " in tap.readout.value and tap.scene.touching_frames == 0
    tap.set(free_amplitude=8.0, setpoint_ratio=0.5)
    s = tap.last
    assert s.branch == "attractive" and s.indentation < 0.1e-9  # gently: 1.7 nm repulsive


# -- a vendor's probe in its fluid (issue 23) -------------------------------------------------
def test_each_tapping_probe_rings_within_the_sliders_in_air_and_water():
    from afmsmiler.ui.modes import TAPPING_LEVER, TAPPING_FLUIDS, TAPPING_PROBES, TAPPING_SLIDERS
    from afmsmiler.planform import PRESETS, preset
    from afmsmiler.probe import equivalent_cantilever, oscillator

    def fits(name, fluid):
        o = oscillator(preset(name), fluid)
        return all(TAPPING_SLIDERS[n].slider_low <= o[n] <= TAPPING_SLIDERS[n].slider_high
                   for n in TAPPING_LEVER)

    assert set(TAPPING_PROBES) <= set(PRESETS)
    for name in TAPPING_PROBES:
        assert all(fits(name, m) for m in TAPPING_FLUIDS), name
    # the contact levers left out: they ring below the f0 slider's 10 kHz in water
    assert not fits("ContAl-G", "water") and not fits("MLCT-A", "water")
    # an independent bound: viscosity only adds mass to the inviscid load (Gamma_r > 1), so
    # f_water <= f_vac (1 + T)^(-1/2), T = pi rho_f b / (4 rho h) (Sader 1998, Eq. 14)
    for name in TAPPING_PROBES:
        rect = equivalent_cantilever(preset(name))
        t = math.pi * 998.2 * rect.width / (4 * rect.density * rect.thickness)
        f_water = oscillator(preset(name), "water")["resonance_frequency"]
        assert f_water < rect.resonance_frequency(1) / math.sqrt(1 + t), name


def test_a_probe_in_a_fluid_sets_the_lever_in_one_run():
    from afmsmiler.planform import preset
    from afmsmiler.probe import oscillator
    panel = TappingPanel()
    c = panel.controls
    assert c["fluid"].disabled and not any(c[n].disabled for n in
                                            ("quality_factor", "spring_constant"))
    runs = panel.model_runs
    c["probe"].value = "AC160TS"
    assert panel.model_runs == runs + 1
    for fluid in ("air", "water"):
        c["fluid"].value = fluid
        o = oscillator(preset("AC160TS"), fluid)
        lever = panel.last.lever
        assert (lever.spring_constant, lever.resonance_frequency, lever.quality_factor) == (
            o["spring_constant"], o["resonance_frequency"], o["quality_factor"])
        assert c["quality_factor"].value == pytest.approx(o["quality_factor"], rel=1e-9)
        assert c["resonance_frequency"].value == pytest.approx(o["resonance_frequency"] / 1e3,
                                                               rel=1e-9)  # Hz -> kHz
        assert c["quality_factor"].disabled and not c["fluid"].disabled
        # the browser snaps to the grid: a probe's sliders on one fine enough to show its values
        q = c["quality_factor"]
        snapped = 10 ** (q.min + round((math.log10(q.value) - q.min) / q.step) * q.step)
        assert f"{snapped:{q.readout_format}}" == f"{o['quality_factor']:{q.readout_format}}"
        zc, phase, _, attractive = setpoint_state(0.8, lever)
        assert panel.last.distance == pytest.approx(zc, rel=1e-12)
        assert f"AC160TS in {fluid}" in panel.readout.value
    assert panel.model_runs == runs + 2  # air was already chosen: no run for it
    # moving a lever slider (in code: the browser cannot move a disabled one) types the lever
    panel.set(quality_factor=100.0)
    assert panel.values()["probe"] == "typed" and panel.last.lever.quality_factor == 100.0
    assert not c["quality_factor"].disabled and c["fluid"].disabled
    assert c["quality_factor"].step == TappingPanel().controls["quality_factor"].step  # typed
    assert panel.model_runs == runs + 3


def test_the_browsers_echo_of_a_probes_lever_before_its_update_keeps_the_probe():
    # in a live kernel the choice's update waits for the moves queued behind it; the browser's
    # echo of the synced Q, snapped to the log slider's grid, may come first: no move (it made
    # the lever typed again in JupyterLab)
    panel = TappingPanel()
    c = panel.controls
    panel._hold = True  # the choice's update deferred, as on a live kernel's loop
    c["probe"].value = "AC160TS"
    q = c["quality_factor"]
    snapped = 10 ** (round(math.log10(q.value) / q.step) * q.step)
    assert snapped != q.value
    q.value = snapped  # the echo
    assert c["probe"].value == "AC160TS"
    # two syncs in a row (air, then water) and the air echo arriving late: still no move
    c["fluid"].value = "water"
    q.value = snapped
    assert c["probe"].value == "AC160TS"
    q.value = q.value * 10 ** (2 * q.step)  # a real move, two steps away: typed
    assert c["probe"].value == "typed"


def test_set_with_a_probe_and_a_lever_slider_starts_the_typed_lever_from_the_probe():
    from afmsmiler.planform import preset
    from afmsmiler.probe import oscillator
    o = oscillator(preset("AC160TS"), "water")
    for kwargs in ({"probe": "AC160TS", "fluid": "water", "quality_factor": 100.0},
                   {"quality_factor": 100.0, "fluid": "water", "probe": "AC160TS"}):
        panel = TappingPanel()
        runs = panel.model_runs
        panel.set(**kwargs)
        lever, v = panel.last.lever, panel.values()
        assert v["probe"] == "typed" and v["quality_factor"] == 100.0
        assert lever.quality_factor == 100.0 and panel.model_runs == runs + 1
        # the others from the probe in water, on the sliders' grid (6 % steps)
        assert lever.spring_constant == pytest.approx(o["spring_constant"], rel=0.04)
        assert lever.resonance_frequency == pytest.approx(o["resonance_frequency"], rel=0.04)
        assert lever.spring_constant == v["spring_constant"]  # what the slider shows runs
        panel.set(free_amplitude=13.0)   # and nothing runs twice or drifts afterwards
        assert panel.model_runs == runs + 2 and panel.last.lever.quality_factor == 100.0


def test_back_to_typed_the_lever_is_what_the_sliders_show():
    panel = TappingPanel(probe="AC160TS", fluid="water")
    c = panel.controls
    c["probe"].value = "typed"
    q = c["quality_factor"]
    on_grid = 10 ** (q.min + round((math.log10(q.value) - q.min) / q.step) * q.step)
    assert q.value == pytest.approx(on_grid, rel=1e-9) and q.step == 0.025
    assert panel.last.lever.quality_factor == pytest.approx(q.value, rel=1e-9)
    assert panel.last.lever.quality_factor == pytest.approx(7.475, rel=0.04)


def test_a_probe_is_refused_with_a_lever_given_and_an_unknown_one_by_name():
    with pytest.raises(ValueError, match="probe"):
        TappingPanel(probe="AC160TS", quality_factor=300.0)
    with pytest.raises(ValueError, match="probe"):
        TappingPanel(probe="ContAl-G")  # a contact lever: not offered
    with pytest.raises(ValueError, match="fluid"):
        TappingPanel(probe="AC160TS", fluid="oil")


def test_notebook_suggestion_water_leaves_one_repulsive_branch():
    # notebook 07: the probe AC160TS has Q about 470 in air; in water Q falls to about 7.5 and f0
    # from 225 to 99 kHz, the branches no longer coexist, the one left is repulsive, and at
    # setpoint 0.8 the tip presses some 5.6 nm into the sample
    panel = TappingPanel(probe="AC160TS")
    air = panel.last
    assert f"{air.lever.quality_factor:.2g}" == "4.7e+02"
    assert f"{air.lever.resonance_frequency / 1e3:.3g}" == "225"
    assert air.curve.coexist.any() and air.branch == "attractive"
    panel.set(fluid="water")
    s = panel.last
    assert f"{s.lever.quality_factor:.2g}" == "7.5"
    assert f"{s.lever.resonance_frequency / 1e3:.2g}" == "99"
    assert not s.curve.coexist.any() and s.branch == "repulsive"
    assert f"{s.indentation * NM:.2g}" == "5.6"
    assert math.degrees(s.phase) < 90.0  # repulsive: the phase lag below 90 deg


def test_notebook_suggestion_viscosity_lights_up_the_dissipation(tap):
    tap.set(sample_viscosity=0.0, setpoint_ratio=0.9)
    dry = tap.last.dissipated_energy
    tap.set(sample_viscosity=200.0)
    wet = tap.last.dissipated_energy
    lever = tap.last.curve.lever
    scale = math.pi * lever.spring_constant * lever.free_amplitude ** 2 / lever.quality_factor
    # a conservative sample dissipates nothing: 0 to round-off of pi k A^2 / Q (the setpoint's
    # phase interpolated between grid points and E_dis recomputed from it gave 0.1 zJ)
    assert abs(dry) < 1e-9 * scale
    # and it reads zero: the readout said "-8.744e-12 zJ", flipping sign from move to move
    tap.set(sample_viscosity=0.0)
    assert tap.last.dissipated_energy == 0.0
    assert "<td>E_dis per cycle</td><td style='text-align:right'><b>0 zJ</b>" in \
        tap.readout.value
    assert wet > 1e-20  # from zero to tens of zJ
    tap.set(sample_viscosity=0.0, setpoint_ratio=0.8)


def test_operating_point_refuses_a_setpoint_never_reached():
    curve = tapping.amplitude_curve(np.linspace(30e-9, 20e-9, 5), TappingLever())
    with pytest.raises(ValueError, match="setpoint_ratio"):
        operating_point(curve, 0.5)


def test_tapping_panel_refuses_out_of_range_values_by_name(tap):
    with pytest.raises(ValueError, match="setpoint_ratio"):
        tap.set(setpoint_ratio=1.2)
    with pytest.raises(TypeError, match="unknown"):
        TappingPanel(drive=1.0)


def test_tapping_panel_animates_the_held_state():
    rec = Recorder()
    panel = TappingPanel(vis=rec)
    s = panel.last
    assert panel.scene is not None and "set_animation" in [c[0] for c in rec.calls]
    clip = next(c for p, c in panel.scene.animation.clips.items() if p.lower().endswith("/probe"))
    z = np.array([v[2] for v in clip.tracks["position"].values]) / panel.scene.factors["distance"]
    assert z.max() == pytest.approx(s.distance + s.setpoint_ratio * 12e-9, rel=1e-9)
    assert panel.scene.touching_frames > 0  # the default state is on the repulsive branch
    assert html.escape(panel.scene.caption) in panel.caption.value


# -- lateral ------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def lat():
    return LateralPanel()


def test_lateral_panel_one_scan_per_move(monkeypatch):
    calls = _count(monkeypatch, lateral, "friction_scan")
    panel = LateralPanel()
    for name, value in (("friction_b", 0.6), ("tilt", 0.0), ("normal_force", 50.0)):
        panel.set(**{name: value})
    assert len(calls) == 4 and panel.model_runs == 4


def test_lateral_panel_loop_is_the_model_loop_of_the_middle_line(lat):
    s = lat.last
    v = lat.values()
    deg = UNITS["deg"][1]
    topo, mu = friction_sample(LATERAL_SAMPLE["shape"], LATERAL_SAMPLE["pixel_size"],
                               coefficients=(v["friction_a"], v["friction_b"]),
                               tilt=v["tilt"] * deg)
    loop = friction_loop(topo.heights[s.row], mu.heights[s.row], topo.pixel_size,
                         normal_force=v["normal_force"] * UNITS["nN"][1],
                         lateral_stiffness=lateral_lever().spring_constant)
    np.testing.assert_allclose(s.loop.trace, loop.trace, rtol=1e-12)
    np.testing.assert_allclose(s.loop.retrace, loop.retrace, rtol=1e-12)
    np.testing.assert_allclose(s.twist, lateral_lever().twist(np.vstack((loop.trace,
                                                                         loop.retrace))))


def test_notebook_suggestion_tilt_moves_the_trace_not_the_friction_map(lat):
    # notebook 07: the trace alone mixes slope and friction; half the difference does not
    maps, traces = [], []
    for tilt in (0.0, 5.0):
        lat.set(tilt=tilt)
        maps.append(lat.last.images.friction_coefficient.heights[:, 1:-1])
        traces.append(np.mean(lat.last.loop.trace[1:-1]) / lat.last.loop.normal_force)
    np.testing.assert_allclose(maps[0], maps[1], atol=1e-12)
    assert traces[1] - traces[0] == pytest.approx(math.tan(math.radians(5.0)), rel=1e-6)
    # the readout the notebook points at shows the same mean trace over the load
    shown = float(re.search(r"mean trace / load \(line\)</td><td[^>]*><b>([-0-9.e]+)<",
                            lat.readout.value).group(1))
    assert shown == pytest.approx(traces[1], rel=1e-3)
    # the map recovers the two coefficients where each material lies
    mu = lat.last.friction[:, 1:-1]
    np.testing.assert_allclose(maps[1], mu, atol=1e-12)
    lat.set(tilt=LATERAL_DEFAULTS["tilt"])


def test_lateral_noise_stays_within_its_rms(lat):
    lat.set(lateral_noise=1.0)
    s = lat.last
    err = s.images.friction_coefficient.heights[:, 1:-1] - s.friction[:, 1:-1]
    sigma = 1e-9 / np.sqrt(2) / s.loop.normal_force  # half the difference of two noises
    assert abs(np.std(err) / sigma - 1) < 0.15
    lat.set(lateral_noise=0.0)


def test_lateral_panel_animates_trace_and_retrace():
    panel = LateralPanel(vis=Recorder())
    assert panel.scene.kind == "lateral" and panel.scene.factors["twist"] > 1


# -- frequency modulation -----------------------------------------------------------------------
@pytest.fixture(scope="module")
def fmp():
    return FrequencyShiftPanel()


def test_fm_panel_one_round_trip_per_move(monkeypatch):
    calls = _count(monkeypatch, fm, "frequency_shift_curve")
    panel = FrequencyShiftPanel()
    panel.set(amplitude=0.1)
    panel.set(hamaker_constant=200.0)
    assert len(calls) == 3 and panel.model_runs == 3


def test_fm_panel_curve_is_the_model_round_trip(fmp):
    v = fmp.values()
    law = dict(hamaker_constant=v["hamaker_constant"] * UNITS["zJ"][1],
               radius=v["radius"] * UNITS["nm"][1],
               youngs_modulus=v["youngs_modulus"] * UNITS["GPa"][1])
    z = np.linspace(FM_DISTANCES["low"], FM_DISTANCES["high"], FM_DISTANCES["points"])
    ref = fm.frequency_shift_curve(functools.partial(tip_sample_force, **law), z,
                                   amplitude=v["amplitude"] * UNITS["nm"][1],
                                   spring_constant=v["spring_constant"],
                                   resonance_frequency=v["resonance_frequency"] * UNITS["kHz"][1])
    np.testing.assert_allclose(fmp.last.curve.frequency_shift, ref.frequency_shift, rtol=1e-12)
    np.testing.assert_allclose(fmp.last.curve.recovered_force, ref.recovered_force, rtol=1e-12)
    assert FM_DEFAULTS["amplitude"] == pytest.approx(5.0)


def test_notebook_suggestion_small_amplitude_meets_the_gradient(fmp):
    # notebook 07: at A = 11 pm df is within a few per cent of the force-gradient shift
    # -f0/(2k) dF/dz (from 1 nm on); at the default 5 nm it is some thirty times smaller 1 nm
    # from the sample
    p = fmp.controls["amplitude"]
    assert f"{10 ** p.min * 1e3:.2g}" == "11"  # the slider's smallest value: 11 pm
    fmp.set(amplitude=10 ** p.min)
    c = fmp.last.curve
    far = c.z > 1e-9
    np.testing.assert_allclose(c.frequency_shift[far], c.gradient_shift[far], rtol=0.05)
    small = c.frequency_shift[far][0]
    fmp.set(amplitude=5.0)
    big = fmp.last.curve.frequency_shift[fmp.last.curve.z > 1e-9][0]
    assert 20 < abs(small) / abs(big) < 50  # "some thirty times"


def test_fm_panel_inversion_within_a_few_per_cent(fmp):
    # notebook 07: "whatever the amplitude": across the slider's whole range
    p = fmp.controls["amplitude"]
    for exponent in np.linspace(p.min, p.max, 7):
        fmp.set(amplitude=10 ** exponent)
        c = fmp.last.curve
        assert np.max(np.abs(c.error)) < 0.05 * np.max(np.abs(c.force))
    fmp.set(amplitude=FM_DEFAULTS["amplitude"])


# -- jumping ------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def jump():
    return JumpingPanel()


def test_jumping_panel_one_curve_and_one_scan_per_move(monkeypatch):
    curves = _count(monkeypatch, jumping, "jump_curve")
    lines = _count(monkeypatch, jumping.JumpingMode, "line")
    panel = JumpingPanel()
    n_lines = len(lines)
    assert len(curves) == 1 and n_lines == JUMPING_SCAN["lines"]
    panel.set(trigger_force=5.0)
    panel.set(work_of_adhesion=100.0)
    assert len(curves) == 3 and len(lines) == 3 * n_lines and panel.model_runs == 3


def test_jumping_panel_curve_is_the_model_curve(jump):
    v = jump.values()
    system = ContactSystem(spring_constant=JUMPING_SCAN["spring_constant"],
                           tip=Parabolic(radius=JUMPING_SCAN["tip_radius"]),
                           youngs_modulus=v["youngs_modulus"] * UNITS["MPa"][1], adhesion="dmt",
                           work_of_adhesion=v["work_of_adhesion"] * UNITS["mJ/m^2"][1])
    ref = jumping.jump_curve(system, trigger_force=v["trigger_force"] * UNITS["nN"][1],
                             lift_height=v["lift_height"] * UNITS["nm"][1],
                             z_speed=v["z_speed"] * UNITS["um/s"][1])
    np.testing.assert_allclose(jump.last.curve.retract_force, ref.retract_force, rtol=1e-12)
    # DMT pull-off 2 pi R w, independent of the model's code
    assert jump.last.curve.pull_off_force == pytest.approx(
        2 * math.pi * JUMPING_SCAN["tip_radius"] * v["work_of_adhesion"] * UNITS["mJ/m^2"][1],
        rel=1e-9)


def test_notebook_suggestion_a_low_lift_crashes_into_the_bars(jump):
    # notebook 07: at the default lift (150 nm) the grating of 100 nm bars is imaged with no
    # lateral force; at 30 nm the lifted tip runs into a bar's side on the first line; 50 nm clears
    # the steps between pixels
    assert jump.last.result.crashed is None
    assert np.nanmax(np.abs(jump.last.result.images["lateral force trace"])) == 0.0
    jump.set(lift_height=30.0)
    assert jump.last.result.crashed is not None and jump.last.result.crashed.row == 0
    c = jump.last.result.crashed
    # the first line is line 1 in the title and the readout, as module (f) counts lines
    assert jump.figure.axes["image"].get_title() == "height (trace): crashed on line 1"
    assert f"<b>line 1, pixel {c.column + 1}</b>" in jump.readout.value
    jump.set(lift_height=50.0)
    assert jump.last.result.crashed is None
    assert re.search(r"largest lateral force</td><td[^>]*><b>0 nN<", jump.readout.value)
    jump.set(lift_height=JUMPING_DEFAULTS["lift_height"])


def test_notebook_suggestion_jumping_costs_time():
    # notebook 07, the readout's two times: at the default lift (150 nm) the jumping image takes
    # some seventeen times as long as in contact mode, at 50 nm still some six times
    jump = JumpingPanel()

    def times():
        found = [float(re.search(rf"image in {m} mode</td><td[^>]*><b>([0-9.e]+) s<",
                                 jump.readout.value).group(1)) for m in ("jumping", "contact")]
        assert found == pytest.approx([jump.last.acquisition_time, jump.last.contact_time],
                                      rel=2e-3)  # shown to 3 or 4 digits
        return found[0] / found[1]

    assert JUMPING_DEFAULTS["lift_height"] == 150.0
    assert 15 < times() < 20
    jump.set(lift_height=50.0)
    assert 5 < times() < 7


def test_jumping_panel_animates_touching_where_the_curve_touches():
    panel = JumpingPanel(vis=Recorder())
    anim = panel.scene.animation
    clip = next(c for p, c in anim.clips.items() if p.lower().endswith("/contact"))
    visible = clip.tracks["visible"].values
    assert any(visible) and not all(visible)


# -- force volume -------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def fvp():
    return ForceVolumePanel()


@pytest.mark.slow
def test_force_volume_panel_one_map_per_move(monkeypatch):
    # every map, made at once (force_volume) or in steps, is one run of force_volume_steps
    calls = _count(monkeypatch, force_volume, "force_volume_steps")
    panel = ForceVolumePanel()
    panel.set(peak_force=20.0)
    assert len(calls) == 2 and panel.model_runs == 2


async def _turns(done, most=2000):
    """Let the kernel's loop turn until ``done()`` (True), or ``most`` ms (False)."""
    import asyncio
    for _ in range(most):  # bounded: a few seconds of a busy loop at most
        if done():
            return True
        await asyncio.sleep(0.001)
    return False


def _move_from_browser(panel, **values):
    """A move from the browser as the kernel's loop gets it (:meth:`Panel._move`): the values
    land, and the update waits for the loop."""
    panel._hold = True
    for name, value in values.items():
        panel.controls[name].value = value
    panel._hold = False
    panel._move(from_browser=True)


def _full_map(**si):
    """The panel's full map for slider values ``si`` (SI), made here from the model directly."""
    d = FORCE_VOLUME_MAP
    sample, labels = force_volume.two_material_sample(
        d["shape"], d["pixel_size"], island_radius=d["island_radius"],
        island_count=d["island_count"], seed=d["seed"])
    return force_volume.force_volume(sample, force_volume.BLEND, Parabolic(radius=d["tip_radius"]),
                                     labels=labels, seed=d["noise_seed"], **si)


def test_force_volume_panel_live_shows_a_coarse_map_then_the_full_one(monkeypatch):
    """In a live kernel a move shows the map of every other pixel at once, said so on screen,
    with no readout from it; a move during the wait replaces the pending full map; the full map
    follows once the slider rests, and both equal the model's full computation."""
    import asyncio

    import afmsmiler.ui.modes as ui_modes
    import afmsmiler.ui.panel as ui_panel
    panel = ForceVolumePanel()
    monkeypatch.setattr(ui_panel, "running_as_notebook", lambda: True)
    # the order of moves and full maps is tested, not the delay: one long enough that a loaded
    # machine's sleep of a third of it still ends before it
    panel.full_delay = 0.15
    runs = panel.model_runs
    si = {k: FORCE_VOLUME_SLIDERS[k].to_si(v) for k, v in FORCE_VOLUME_DEFAULTS.items()}
    peak = FORCE_VOLUME_SLIDERS["peak_force"]

    async def drag():
        _from_browser(panel, peak_force=15.0)
        first = panel.coarse
        assert "coarse map" in panel.fig.get_suptitle()
        assert "computing the full map" in panel.readout.value and "MPa" not in \
            panel.readout.value
        # the frame that shows the coarse map is the one the panel names (the bench dates the
        # drag's last position by it)
        assert panel.last_quick_frame == panel.live.frames_sent
        await asyncio.sleep(panel.full_delay / 3)
        _from_browser(panel, peak_force=20.0)  # before the first full map was due
        assert panel.last_quick_frame == panel.live.frames_sent
        await asyncio.sleep(3 * panel.full_delay)
        return first

    sent = panel.live.frames_sent
    first = asyncio.run(drag())
    assert panel.model_runs - runs == 3  # two coarse maps, one full map (the last values)
    assert panel.last_quick_frame == sent + 2 and panel.live.frames_sent == sent + 3
    full15 = _full_map(**{**si, "peak_force": peak.to_si(15.0)})
    full20 = _full_map(**{**si, "peak_force": peak.to_si(20.0)})
    s = ui_modes.COARSE_STRIDE
    assert first.modulus.shape == full15.modulus[::s, ::s].shape
    assert first.pixel_size == pytest.approx(s * full15.pixel_size, rel=1e-12)
    for key in ("modulus", "adhesion", "deformation", "dissipation"):
        np.testing.assert_array_equal(getattr(first, key), getattr(full15, key)[::s, ::s])
        np.testing.assert_array_equal(getattr(panel.last, key), getattr(full20, key))
    assert panel.coarse is None and panel.fig.get_suptitle() == ""
    assert "MPa" in panel.readout.value


def test_force_volume_panel_makes_its_full_map_in_blocks_that_a_move_interrupts(monkeypatch):
    """In a live kernel the full map is made one block of pixels per turn of the loop, so a
    move from the browser that comes between two blocks is run first: it drops the rest of the
    older map, which is never shown; the map shown equals the model's made at once."""
    import asyncio

    import afmsmiler.ui.modes as ui_modes
    import afmsmiler.ui.panel as ui_panel
    panel = ForceVolumePanel()
    monkeypatch.setattr(ui_panel, "running_as_notebook", lambda: True)
    si = {k: FORCE_VOLUME_SLIDERS[k].to_si(v) for k, v in FORCE_VOLUME_DEFAULTS.items()}
    peak = FORCE_VOLUME_SLIDERS["peak_force"]
    start, runs, sent = panel.last, panel.model_runs, panel.live.frames_sent
    pixels = int(np.prod(FORCE_VOLUME_MAP["shape"]))
    assert 1 < ui_modes.FULL_BLOCK < pixels  # more than one block to a map

    async def drag():
        _from_browser(panel, peak_force=15.0)
        assert await _turns(lambda: panel._full_steps is not None)  # the full map under way
        assert panel.coarse is not None and panel.last is start  # ... and not shown yet
        # a move from the browser, as the kernel's loop gets it (Panel._move): it waits for one
        # block, then its update runs and drops the rest of the map of 15 nN
        _move_from_browser(panel, peak_force=20.0)
        assert await _turns(lambda: panel.last is not start and panel._full_pending is None
                           and panel._full_steps is None)

    asyncio.run(drag())
    # a coarse and a full map of 15 nN begun, a coarse and a full map of 20 nN: the first full
    # map was never shown (three frames)
    assert panel.model_runs - runs == 4 and panel.live.frames_sent == sent + 3
    full20 = _full_map(**{**si, "peak_force": peak.to_si(20.0)})
    for key in ("modulus", "modulus_error", "adhesion", "deformation", "dissipation"):
        np.testing.assert_array_equal(getattr(panel.last, key), getattr(full20, key))
    assert panel.coarse is None and panel.fig.get_suptitle() == "" and \
        "MPa" in panel.readout.value


def test_tapping_panel_makes_its_full_curve_in_blocks_that_a_move_interrupts(monkeypatch):
    """In a live kernel the full curve is sampled one block of distances per turn of the loop,
    so a move from the browser that comes between two blocks is run first: it drops the rest of
    the older curve, which is never shown; the curve shown, its jumps and the state held equal
    the model's made at once."""
    import asyncio

    import afmsmiler.ui.panel as ui_panel
    from afmsmiler.ui.modes import TAPPING_FULL_BLOCK
    panel = TappingPanel()
    monkeypatch.setattr(ui_panel, "running_as_notebook", lambda: True)
    start, runs, sent = panel.last, panel.model_runs, panel.live.frames_sent
    assert 1 < TAPPING_FULL_BLOCK < tapping.SETPOINT_GRID  # more than one block to a curve

    async def drag():
        _from_browser(panel, free_amplitude=15.0)
        assert await _turns(lambda: panel._full_steps is not None)  # the full curve under way
        assert panel.coarse is not None and panel.last is start  # ... and not shown yet
        _move_from_browser(panel, free_amplitude=16.0)
        assert await _turns(lambda: panel.last is not start and panel._full_pending is None
                           and panel._full_steps is None)

    asyncio.run(drag())
    # a coarse and a full curve of 15 nm begun, a coarse and a full curve of 16 nm: the first
    # full curve was never shown (three frames)
    assert panel.model_runs - runs == 4 and panel.live.frames_sent == sent + 3
    lever = panel.last.lever
    assert lever.free_amplitude == pytest.approx(16e-9, rel=1e-12)
    model = tapping.amplitude_curve(lever.free_amplitude *
                                    np.linspace(1.5, 0.01, tapping.SETPOINT_GRID), lever)
    for key in ("distance", "amplitude", "phase", "stable", "repulsive_branch",
                "dissipated_energy"):
        np.testing.assert_array_equal(getattr(panel.last.curve, key), getattr(model, key))
    assert panel.last.curve.jumps == model.jumps
    r = panel.last.setpoint_ratio
    assert panel.last.distance == operating_point(model, r)[0]
    assert panel.coarse is None and "held at z_c" in panel.readout.value and \
        "computing" not in panel.readout.value


def test_a_full_map_waits_for_the_page_to_paint_the_coarse_one(monkeypatch):
    """The full map begins once the page painted the coarse map it follows (a page busy with
    the student's keys paints nothing, and sends no move, until they stop), or PAINT_WAIT s
    after it was sent from a page that does not say."""
    import asyncio

    import afmsmiler.ui.panel as ui_panel
    from afmsmiler.plots.live import PAINT_WAIT
    panel = ForceVolumePanel()
    monkeypatch.setattr(ui_panel, "running_as_notebook", lambda: True)
    panel.full_delay = 0.0
    live = panel.live
    live.frames_painted = live.frames_sent  # a page that said what it painted

    async def wait(done, seconds):
        for _ in range(int(seconds / 0.002)):  # bounded
            if done():
                return True
            await asyncio.sleep(0.002)
        return False

    async def drag():
        start = panel.last
        _from_browser(panel, peak_force=15.0)
        assert not await wait(lambda: panel.last is not start, PAINT_WAIT / 3)
        assert panel.coarse is not None and panel._full_steps is None  # not begun
        live._handle_message(live, {"painted": panel.last_quick_frame}, [])  # the page says
        assert await wait(lambda: panel.last is not start, 5.0)
        assert panel.last.modulus.shape == FORCE_VOLUME_MAP["shape"]
        shown, sent = panel.last, asyncio.get_running_loop().time()
        _from_browser(panel, peak_force=20.0)  # and a page that does not say
        assert await wait(lambda: panel.last is not shown, 5.0)
        assert asyncio.get_running_loop().time() - sent >= PAINT_WAIT

    asyncio.run(drag())


def test_notebook_suggestion_the_maps_separate_the_materials(fvp):
    # notebook 07: at the defaults the modulus map gives each material's E within 2 % and the
    # adhesion map DMT's 2 pi R w within 5 %
    v, labels = fvp.last, fvp.labels
    r = FORCE_VOLUME_MAP["tip_radius"]
    text = re.sub("<[^>]+>", " ", fvp.readout.value)  # what the student reads
    moduli = [float(x) * 1e6 for x in re.findall(r"E \(median of the map\)\s+([0-9.]+) MPa",
                                                 text)]
    adhesions = [float(x) * 1e-9 for x in re.findall(r"adhesion \(median\)\s+([0-9.]+) nN",
                                                     text)]
    assert len(moduli) == len(adhesions) == len(force_volume.BLEND)
    for i, m in enumerate(force_volume.BLEND):
        assert np.nanmedian(v.modulus[labels == i]) == pytest.approx(m.youngs_modulus, rel=0.02)
        assert np.nanmedian(v.adhesion[labels == i]) == pytest.approx(
            2 * math.pi * r * m.work_of_adhesion, rel=0.05)
        assert moduli[i] == pytest.approx(m.youngs_modulus, rel=0.02)
        assert adhesions[i] == pytest.approx(2 * math.pi * r * m.work_of_adhesion, rel=0.05)


@pytest.mark.slow
def test_notebook_suggestion_noise_scatters_and_biases_the_modulus(fvp):
    # notebook 07: 500 pN of force noise scatters the modulus map some twenty times more and
    # both materials come out too stiff (the noisy minimum added back)
    quiet = [np.nanstd(fvp.last.modulus[fvp.labels == i]) for i in (0, 1)]
    fvp.set(force_noise=500.0)
    for i, m in enumerate(force_volume.BLEND):
        mask = fvp.labels == i
        assert np.nanstd(fvp.last.modulus[mask]) > 10 * quiet[i]
        assert np.nanmedian(fvp.last.modulus[mask]) > 1.1 * m.youngs_modulus
    fvp.set(force_noise=FORCE_VOLUME_DEFAULTS["force_noise"])


def test_tapping_panel_marks_where_the_approach_jumps(tap):
    tap.set(free_amplitude=12.0, setpoint_ratio=0.8)
    _, _, jumps = tap.last.curve.sweep("approach")
    line = tap.figure.lines["amplitude", "jump approach"]
    assert jumps and line.get_visible()
    assert line.get_xdata()[0] == pytest.approx(jumps[0] * NM)
    # the held state lies beyond the jump: the approach passed it and landed on the H branch
    assert tap.last.distance < jumps[0] and tap.last.branch == "repulsive"


def test_a_setpoint_never_reached_shows_the_curves_and_says_so():
    panel = TappingPanel(quality_factor=1.005)  # a lever so damped the approach stays above
    assert math.isnan(panel.last.distance)
    assert "never gets down" in panel.readout.value
    assert not panel.figure.lines["amplitude", "setpoint"].get_visible()
    panel.set(quality_factor=400.0)
    assert panel.last.distance > 0 and "held at z_c" in panel.readout.value
    # with a 3D view: it keeps the last state it drew, and its caption says so
    viewed = TappingPanel(vis=Recorder())
    drawn = viewed.scene.caption
    assert html.escape(drawn) in viewed.caption.value
    viewed.set(quality_factor=1.005)
    assert "never gets down" in viewed.readout.value
    assert viewed.caption.value == \
        f"<div>3D view: still the last state held, {html.escape(drawn)}</div>"


def test_notebook_viscosity_dissipates_only_while_the_tip_touches():
    # notebook 07, from the defaults: at setpoint 0.9, 200 Pa s makes E_dis grow from zero to some
    # 70 zJ and the phase lag move by about 0.2 deg; at 0.99 (clear of the sample) it takes nothing
    tap = TappingPanel()
    tap.set(setpoint_ratio=0.9)
    dry, dry_phase = tap.last.dissipated_energy, tap.last.phase
    lever = tap.last.curve.lever
    scale = math.pi * lever.spring_constant * lever.free_amplitude ** 2 / lever.quality_factor
    # a conservative sample dissipates nothing: 0 to round-off of pi k A^2 / Q (the setpoint's
    # phase interpolated between grid points and E_dis recomputed from it gave 0.1 zJ)
    assert abs(dry) < 1e-9 * scale
    tap.set(sample_viscosity=200.0)
    s = tap.last
    assert s.branch == "attractive" and s.touches
    assert 50e-21 < s.dissipated_energy < 90e-21  # "some 70 zJ"
    assert 0.1 < abs(math.degrees(s.phase - dry_phase)) < 0.4  # "about 0.2 deg"
    tap.set(setpoint_ratio=0.99)
    s = tap.last
    assert not s.touches and abs(s.dissipated_energy) < 1e-9 * scale


def test_tapping_panel_follows_each_sweep_once_per_move(monkeypatch):
    runs = []
    original = tapping.AmplitudeCurve._sweep
    monkeypatch.setattr(tapping.AmplitudeCurve, "_sweep",
                        lambda self, way: runs.append(way) or original(self, way))
    panel = TappingPanel()
    assert sorted(runs) == ["approach", "retract"]  # the state and both jump marks
    panel.set(setpoint_ratio=0.7)  # the same curve: nothing followed again
    assert sorted(runs) == ["approach", "retract"]
    panel.set(free_amplitude=15.0)  # a new curve: each direction once more
    assert sorted(runs) == ["approach", "approach", "retract", "retract"]
