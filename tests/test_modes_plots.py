"""Module (g)'s figures draw the models' results in the units shown, nothing recomputed: both
branches of the amplitude curve and the region where they coexist, the held state; a friction
loop with half its difference (friction) and half its sum (slope); df and the force recovered.
Each figure can be drawn live (plots.live.describe) and labels every axis with a unit."""
import math
import re

import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg

from afmsmiler.modes import (FrictionLoop, TappingLever, amplitude_curve, friction_loop,
                             friction_sample, friction_scan, frequency_shift_curve,
                             setpoint_state, tip_sample_force)
from afmsmiler.modes.tapping import SETPOINT_GRID
from afmsmiler.parameters import UNITS
from afmsmiler.plots.live import describe
from afmsmiler.plots.modes import (FrequencyShiftFigure, LateralFigure, TappingFigure,
                                   branch_values, unstable_roots)

NM = 1 / UNITS["nm"][1]
NN = 1 / UNITS["nN"][1]
ZJ = 1 / UNITS["zJ"][1]


@pytest.fixture(scope="module")
def tapping():
    lever = TappingLever(free_amplitude=12e-9, sample_viscosity=200.0)
    curve = amplitude_curve(12e-9 * np.linspace(1.5, 0.01, SETPOINT_GRID), lever)
    return lever, curve, (0.8, *setpoint_state(0.8, lever))


def _xy(line):
    return np.asarray(line.get_xdata(), float), np.asarray(line.get_ydata(), float)


def test_tapping_figure_draws_both_branches_in_nm_deg_and_zj(tapping):
    lever, curve, point = tapping
    fig = TappingFigure(curve, point)
    order = np.argsort(curve.distance)
    for branch in ("attractive", "repulsive"):
        a, p = curve.branch(branch)
        x, y = _xy(fig.lines["amplitude", branch])
        np.testing.assert_allclose(x, curve.distance[order] * NM)
        np.testing.assert_allclose(y, a[order] * NM)
        np.testing.assert_allclose(_xy(fig.lines["phase", branch])[1],
                                   np.degrees(p[order]))
    # E_dis on the attractive branch is the lever's energy balance at that amplitude and phase
    a, p = curve.branch("attractive")
    e = _xy(fig.lines["energy", "attractive"])[1]
    ok = np.isfinite(a[order])
    np.testing.assert_allclose(e[ok], lever.dissipated_energy(a[order][ok], p[order][ok]) * ZJ,
                               rtol=1e-9, atol=1e-9)
    describe(fig.fig)  # the live figure can show every artist


def test_no_dissipation_reads_zero_on_a_scale_where_dissipation_would_show(tapping):
    # the E_dis axis showed round-off (-8.7e-12 zJ, flipping sign) as a flat line on +-5e-4 zJ
    lever = TappingLever(free_amplitude=12e-9)  # no viscosity: a conservative force
    curve = amplitude_curve(12e-9 * np.linspace(1.5, 0.01, SETPOINT_GRID), lever)
    fig = TappingFigure(curve, (0.8, *setpoint_state(0.8, lever)))
    for branch in ("attractive", "repulsive", "point"):
        y = _xy(fig.lines["energy", branch])[1]
        assert np.all(y[np.isfinite(y)] == 0.0), branch
    lo, hi = fig.axes["energy"].get_ylim()
    # at least k_B T at 295 K (CODATA k_B = 1.380649e-23 J/K): 4.07 zJ, the lever's thermal
    # energy, around the zero
    assert hi - lo >= 1.380649e-23 * 295.0 * ZJ and lo < 0.0 < hi
    assert "E_dis = 0" in fig.axes["energy"].get_title()
    _, wet, point = tapping  # a viscous sample: its dissipation is drawn, nothing said
    fig.update(wet, point)
    assert fig.axes["energy"].get_title() == ""
    assert np.nanmax(_xy(fig.lines["energy", "repulsive"])[1]) > 0


def test_tapping_figure_marks_the_coexistence_region_and_the_held_state(tapping):
    _, curve, point = tapping
    fig = TappingFigure(curve, point)
    # each run of neighbouring distances where both branches are stable is shaded on its own:
    # at A0 = 12 nm the attractive branch is absent between about 3 and 9.5 nm
    z = np.sort(curve.distance)
    both = curve.coexist[np.argsort(curve.distance)]
    runs = [(z[i], z[j - 1]) for i, j in
            zip(*[iter(np.flatnonzero(np.diff(np.r_[0, both.astype(int), 0])))] * 2)]
    assert len(runs) == 2
    shown = [s for s in fig.spans["amplitude"] if s.get_visible()]
    assert len(shown) == 2
    for span, (lo, hi) in zip(shown, runs):
        assert span.get_x() == pytest.approx(lo * NM)
        assert span.get_x() + span.get_width() == pytest.approx(hi * NM)
    title = fig.axes["amplitude"].get_title()
    assert " and ".join(f"from {lo * NM:.3g} to {hi * NM:.3g}" for lo, hi in runs) in title
    # no grey between the runs: over most of it the attractive branch is missing
    gap = (z > runs[0][1]) & (z < runs[1][0])
    missing = np.isnan(curve.branch("attractive")[0][np.argsort(curve.distance)][gap])
    assert missing.mean() > 0.5
    # the contact line: a state's tip dips below a0 where its amplitude lies above it
    x, y = _xy(fig.lines["amplitude", "contact"])
    np.testing.assert_allclose(y, x - 0.165, rtol=1e-12, atol=1e-12)
    ratio, zc, phase, e_dis, attractive = point
    x, y = _xy(fig.lines["amplitude", "point"])
    assert x[0] == pytest.approx(zc * NM) and y[0] == pytest.approx(ratio * 12.0)
    assert _xy(fig.lines["phase", "point"])[1][0] == pytest.approx(math.degrees(phase))
    assert fig.lines["amplitude", "setpoint"].get_ydata()[0] == pytest.approx(ratio * 12.0)
    title = fig.axes["amplitude"].get_title()
    assert ("attractive" if attractive else "repulsive") + " branch" in title
    zu, au, _ = unstable_roots(curve)
    assert zu.size and np.all(~np.isnan(au))
    np.testing.assert_allclose(np.sort(_xy(fig.lines["amplitude", "unstable"])[1]),
                               np.sort(au * NM))


def test_without_coexistence_the_span_hides():
    curve = amplitude_curve(np.linspace(20e-9, 30e-9, 20), TappingLever())  # far: free lever
    fig = TappingFigure(curve)
    assert not any(s.get_visible() for s in fig.spans["amplitude"])
    assert not fig.lines["amplitude", "setpoint"].get_visible()


def test_branch_values_refuses_a_wrong_shape(tapping):
    _, curve, _ = tapping
    with pytest.raises(ValueError, match="values"):
        branch_values(curve, np.zeros(3), "attractive")
    with pytest.raises(ValueError, match="name"):
        branch_values(curve, curve.amplitude, "high")


@pytest.fixture(scope="module")
def lateral():
    topo, mu = friction_sample((16, 40), 10e-9, coefficients=(0.1, 0.4), tilt=math.radians(4))
    images = friction_scan(topo, mu, normal_force=20e-9, lateral_stiffness=100.0)
    row = 8
    loop = friction_loop(topo.heights[row], mu.heights[row], 10e-9, normal_force=20e-9,
                         lateral_stiffness=100.0)
    return topo, mu, images, row, loop


def test_lateral_figure_splits_the_loop_into_friction_and_slope(lateral):
    topo, mu, images, row, loop = lateral
    fig = LateralFigure(loop, images, row)
    x, trace = _xy(fig.lines["trace"])
    np.testing.assert_allclose(x, np.arange(40) * 10.0)
    np.testing.assert_allclose(trace, loop.trace * NN)
    np.testing.assert_allclose(_xy(fig.lines["retrace"])[1], loop.retrace * NN)
    f = _xy(fig.lines["friction"])[1]
    s = _xy(fig.lines["slope"])[1]
    np.testing.assert_allclose(f, (loop.trace - loop.retrace) / 2 * NN)
    # on the sliding pixels: friction is mu F_N, the slope term F_N tan(theta) (linear model)
    np.testing.assert_allclose(f[1:-1], mu.heights[row][1:-1] * 20.0, rtol=1e-9)
    np.testing.assert_allclose(s[1:-1], 20.0 * math.tan(math.radians(4)), rtol=1e-6)
    np.testing.assert_allclose(fig.images["friction"].get_array(),
                               images.friction_coefficient.heights)
    describe(fig.fig)


def test_the_slope_map_shows_a_uniform_tilt_inside_its_colour_scale(lateral):
    # 20 nN tan(3 deg) = 1.05 nN sat at the end of a +-1.05 nN bar: the map was saturated
    topo, mu, images, row, loop = lateral
    fig = LateralFigure(loop, images, row)
    lo, hi = fig.images["slope"].get_clim()
    slope = 20.0 * math.tan(math.radians(4))  # F_N tan(theta) in nN, 1.40 nN
    assert lo == -hi  # the diverging map's white at zero
    assert slope == pytest.approx(hi * 2 / 3, rel=1e-6)  # two thirds of the way to the end
    fig.update(loop, images, row)
    assert fig.images["slope"].get_clim() == (lo, hi)  # held while it stays inside
    assert fig.colorbars["slope"].norm.vmax == hi


def test_lateral_figure_loop_only():
    loop = FrictionLoop(np.arange(5) * 1e-9, np.ones(5) * 1e-9, -np.ones(5) * 1e-9, 10e-9, 1.0)
    fig = LateralFigure(loop)
    assert set(fig.axes) == {"loop"}
    describe(fig.fig)


@pytest.fixture(scope="module")
def fm_curve():
    return frequency_shift_curve(tip_sample_force, np.linspace(0.2e-9, 12e-9, 200),
                                 amplitude=1e-9)


def test_frequency_shift_figure_draws_the_round_trip(fm_curve):
    fig = FrequencyShiftFigure(fm_curve)
    x, df = _xy(fig.lines["giessibl"])
    np.testing.assert_allclose(x, fm_curve.z * NM)
    np.testing.assert_allclose(df, fm_curve.frequency_shift)
    np.testing.assert_allclose(_xy(fig.lines["gradient"])[1], fm_curve.gradient_shift)
    np.testing.assert_allclose(_xy(fig.lines["input"])[1], fm_curve.force * NN)
    np.testing.assert_allclose(_xy(fig.lines["recovered"])[1], fm_curve.recovered_force * NN)
    worst = np.max(np.abs(fm_curve.error)) / np.max(np.abs(fm_curve.force))
    assert f"{100 * worst:.2g} %" in fig.axes["force"].get_title()
    # distances on a log axis (shared): the first nanometre, where df and F change, takes
    # half the width (it took a twelfth of a linear axis to 12 nm)
    for ax in fig.axes.values():
        assert ax.get_xscale() == "log"
    lo, hi = fig.axes["force"].get_xlim()
    assert (lo, hi) == pytest.approx((0.2, 12.0))
    assert np.log10(1.0 / lo) / np.log10(hi / lo) > 0.35
    d = describe(fig.fig)
    assert d.layout["axes"][1]["x"]["scale"] == "log"


def _figures(tapping, lateral, fm_curve):
    _, curve, point = tapping
    topo, mu, images, row, loop = lateral
    return [TappingFigure(curve, point).fig, LateralFigure(loop, images, row).fig,
            FrequencyShiftFigure(fm_curve).fig]


def test_every_axis_is_labelled_with_a_unit(tapping, lateral, fm_curve, jumping_run):
    from afmsmiler.plots.modes import JumpingFigure
    for fig in [*_figures(tapping, lateral, fm_curve), JumpingFigure(*jumping_run).fig]:
        FigureCanvasAgg(fig).draw()
        for ax in fig.axes:  # colour bars too
            for axis in (ax.xaxis, ax.yaxis):
                shows = any(t.get_text().strip() for t in axis.get_ticklabels())
                label = axis.label.get_text()
                if shows:
                    assert re.search(r"\[[^\]]+\]|\(dimensionless\)", label), label
            if not hasattr(ax, "_colorbar"):
                assert ax.yaxis.label.get_text(), f"{ax.get_title()!r} has no y label"


def test_update_keeps_the_artists(tapping):
    _, curve, point = tapping
    fig = TappingFigure(curve, point)
    line = fig.lines["amplitude", "attractive"]
    n = len(fig.fig.axes[0].lines)
    fig.update(curve, (0.9, *setpoint_state(0.9, curve.lever)))
    assert fig.lines["amplitude", "attractive"] is line and len(fig.fig.axes[0].lines) == n


@pytest.fixture(scope="module")
def jumping_run():
    from afmsmiler.contact import ContactSystem, Parabolic
    from afmsmiler.imaging.scanner import ScanSettings, scan
    from afmsmiler.modes.jumping import JumpingMode, jump_curve
    from afmsmiler.samples import grating
    tip = Parabolic(radius=10e-9)
    system = ContactSystem(spring_constant=1.0, tip=tip, youngs_modulus=1e9, adhesion="dmt",
                           work_of_adhesion=0.05)
    curve = jump_curve(system, trigger_force=2e-9, lift_height=150e-9)
    result = scan(grating((32, 64), 10e-9, period=320e-9, height=100e-9), tip,
                  JumpingMode(system, trigger_force=2e-9, lift_height=150e-9),
                  ScanSettings(300e-9, pixels=16, lines=4))
    return curve, result


def test_jumping_figure_draws_the_curve_and_the_image(jumping_run):
    from afmsmiler.plots.modes import JumpingFigure
    curve, result = jumping_run
    fig = JumpingFigure(curve, result)
    x, y = _xy(fig.lines["approach"])
    np.testing.assert_allclose(x, curve.approach_z_np * NM)
    np.testing.assert_allclose(y, curve.approach_force * NN)
    np.testing.assert_allclose(_xy(fig.lines["retract time"])[0],
                               curve.retract_time / UNITS["ms"][1])
    assert fig.lines["trigger"].get_ydata()[0] == pytest.approx(2.0)
    np.testing.assert_allclose(np.ma.filled(fig.images["height"].get_array(), np.nan),
                               result.images["height trace"] * NM)
    row = result.images["height trace"].shape[0] // 2
    np.testing.assert_allclose(_xy(fig.lines["trace"])[1],
                               result.images["height trace"][row] * NM)
    # the profile's line is counted from 1, as module (f)'s figure counts them
    assert fig.axes["profile"].get_title() == f"line {row + 1}: trace and retrace"
    describe(fig.fig)


def test_force_volume_figure_draws_the_maps():
    from afmsmiler.contact import Parabolic
    from afmsmiler.modes.force_volume import BLEND, force_volume, two_material_sample
    from afmsmiler.plots.modes import ForceVolumeFigure
    sample, labels = two_material_sample((6, 6), 20e-9, island_radius=40e-9, island_count=1,
                                         seed=3)
    fv = force_volume(sample, BLEND, Parabolic(radius=10e-9), labels=labels, seed=0, points=100)
    fig = ForceVolumeFigure(fv, [m.name for m in BLEND])
    np.testing.assert_allclose(fig.images["modulus"].get_array(), fv.modulus / UNITS["MPa"][1])
    np.testing.assert_allclose(fig.images["adhesion"].get_array(), fv.adhesion * NN)
    np.testing.assert_allclose(fig.images["dissipation"].get_array(), fv.dissipation * ZJ)
    np.testing.assert_allclose(_xy(fig.lines["approach", 1])[1], fv.approach[1] * NN)
    # one pixel as measured beside the noise-free curve (they stayed smooth while the maps
    # scattered), and negative dissipation said to be the noise's, with the model's scatter
    for i in (0, 1):
        np.testing.assert_allclose(_xy(fig.lines["measured approach", i])[1],
                                   fv.measured_approach[i] * NN)
        np.testing.assert_allclose(_xy(fig.lines["measured retract", i])[1],
                                   fv.measured_retract[i] * NN)
    quiet = force_volume(sample, BLEND, Parabolic(radius=10e-9), labels=labels, points=100,
                         force_noise=0.0)
    fig.update(quiet)  # without noise no loop area is below 0: nothing to say
    assert np.min(quiet.dissipation) >= 0 and fig.axes["dissipation"].get_title() == \
        "dissipation map"
    noisy = force_volume(sample, BLEND, Parabolic(radius=10e-9), labels=labels, seed=0,
                         points=100, force_noise=500e-12)
    assert np.min(noisy.dissipation) < 0
    fig.update(noisy)
    title = fig.axes["dissipation"].get_title()
    assert "< 0: noise" in title and f"{np.max(noisy.dissipation_noise) * ZJ:.3g} zJ" in title
    lo, hi = fig.axes["curves"].get_ylim()
    assert lo <= np.min(noisy.measured_retract) * NN and hi >= np.max(noisy.measured_approach) * NN
    describe(fig.fig)
    with pytest.raises(ValueError, match="names"):
        ForceVolumeFigure(fv, ["one"])


def test_tapping_figure_marks_the_jumps_of_a_slow_approach_and_retraction(tapping):
    _, curve, point = tapping
    jumps = {way: curve.sweep(way)[2] for way in ("approach", "retract")}
    assert jumps["retract"]  # this lever jumps on the way out
    fig = TappingFigure(curve, point, jumps=jumps)
    for way in ("approach", "retract"):
        line = fig.lines["phase", f"jump {way}"]
        assert line.get_visible() is bool(jumps[way])
        if jumps[way]:
            assert line.get_xdata()[0] == pytest.approx(jumps[way][0] * NM)
    fig.update(curve, point)  # no jumps given: none marked
    assert not fig.lines["amplitude", "jump retract"].get_visible()
    describe(fig.fig)


def test_force_volume_maps_updated_in_place_equal_maps_drawn_afresh():
    # issue 24: an update that keeps the maps' frame skips set_extent and the axes' limits;
    # the maps are those of a figure made with the new volume, and a new frame is applied
    from afmsmiler.contact import Parabolic
    from afmsmiler.modes.force_volume import BLEND, force_volume, two_material_sample
    from afmsmiler.plots.modes import ForceVolumeFigure
    tip = Parabolic(radius=10e-9)
    names = [m.name for m in BLEND]
    fig = None
    for pixel, noise in ((20e-9, 20e-12), (20e-9, 200e-12), (30e-9, 50e-12)):
        sample, labels = two_material_sample((6, 6), pixel, island_radius=40e-9,
                                             island_count=1, seed=3)
        fv = force_volume(sample, BLEND, tip, labels=labels, seed=0, points=100,
                          force_noise=noise)
        if fig is None:
            fig = ForceVolumeFigure(fv, names)
        else:
            fig.update(fv)
        fresh = ForceVolumeFigure(fv, names)
        for key, im in fig.images.items():
            ax, ref_ax, ref = fig.axes[key], fresh.axes[key], fresh.images[key]
            assert tuple(im.get_extent()) == tuple(ref.get_extent())
            assert (ax.get_xlim(), ax.get_ylim()) == (ref_ax.get_xlim(), ref_ax.get_ylim())
            assert (ax.get_xlabel(), ax.get_ylabel()) == (ref_ax.get_xlabel(),
                                                          ref_ax.get_ylabel())
            assert im.get_clim() == ref.get_clim()
            np.testing.assert_array_equal(im.get_array(), ref.get_array())
        layout = describe(fig.fig).layout["axes"]
        ref_layout = describe(fresh.fig).layout["axes"]
        for mine, theirs in zip(layout, ref_layout):
            if mine["images"]:
                assert mine == theirs


def test_a_coarse_map_keeps_the_full_map_s_frame_and_shows_its_own_pixels():
    # issue 24: a coarse map (every 2nd pixel, each twice as large) of the field shown keeps the
    # axes' limits (no relayout between the coarse and the full map of a move); its image spans
    # its own pixels; the full map again is the figure drawn afresh; another field is framed
    from afmsmiler.contact import Parabolic
    from afmsmiler.modes.force_volume import BLEND, force_volume, two_material_sample
    from afmsmiler.plots.modes import ForceVolumeFigure
    tip, names = Parabolic(radius=10e-9), [m.name for m in BLEND]
    sample, labels = two_material_sample((6, 6), 20e-9, island_radius=40e-9, island_count=1,
                                         seed=3)
    args = dict(labels=labels, seed=0, points=100)
    full = force_volume(sample, BLEND, tip, **args)
    coarse = force_volume(sample, BLEND, tip, stride=2, **args)
    fig = ForceVolumeFigure(full, names)
    frame = {key: (ax.get_xlim(), ax.get_ylim()) for key, ax in fig.axes.items()}
    fig.update(coarse, status="coarse")
    half = 0.5 * 40.0  # nm: half a coarse pixel, centred on every 2nd full pixel (20 nm apart)
    for key, im in fig.images.items():
        assert (fig.axes[key].get_xlim(), fig.axes[key].get_ylim()) == frame[key]
        np.testing.assert_allclose(im.get_extent(), (-half, 2 * 40.0 + half, -half,
                                                     2 * 40.0 + half), rtol=1e-12)
        np.testing.assert_array_equal(np.ma.filled(im.get_array(), np.nan).shape, (3, 3))
    sent = [a["images"][0] for a in describe(fig.fig).frame["axes"] if a["images"]]
    assert len(sent) == 4 and all(img["shape"] == [3, 3] and img["extent"] == pytest.approx(
        [-half, 2 * 40.0 + half, -half, 2 * 40.0 + half]) for img in sent)
    fig.update(full)
    fresh = ForceVolumeFigure(full, names)
    for key, im in fig.images.items():
        assert tuple(im.get_extent()) == tuple(fresh.images[key].get_extent())
        assert (fig.axes[key].get_xlim(), fig.axes[key].get_ylim()) == \
            (fresh.axes[key].get_xlim(), fresh.axes[key].get_ylim())
    wider, wider_labels = two_material_sample((6, 6), 30e-9, island_radius=40e-9,
                                              island_count=1, seed=3)
    other = force_volume(wider, BLEND, tip, labels=wider_labels, seed=0, points=100)
    fig.update(other)
    assert fig.axes["modulus"].get_xlim() == pytest.approx((-15.0, 165.0))
