"""Module (g)'s 3D animations with the recording fake: every frame is the model's state (the
apex at z_c + A cos(theta) times the stated factor, contact exactly where the distance falls below
a0, the spot moving with the deflection, sideways and opposite on trace and retrace for the
lateral twist); the factors are round numbers the caption states; the modes share one path."""
import math

import numpy as np
import pytest
from meshcat.animation import Animation

from afmsmiler.scenes.modes import DEFAULTS, LIMITS, ModesScene, factor_text, round_factor
from tests.recording import Recorder

A0 = 12e-9
A_CONTACT = 0.165e-9


def _track(anim: Animation, node: str, prop: str):
    """(frames, values) of one property's track of the node ``.../node``."""
    for path, clip in anim.clips.items():
        if path.lower().endswith("/" + node):
            track = clip.tracks[prop]
            return np.array(track.frames), track.values
    raise KeyError(node)


def _quaternion_angle_x(q):
    """Rotation angle about x of a quaternion [x, y, z, w] (meshcat's js order)."""
    x, _, _, w = q
    return 2 * math.atan2(x, w)


@pytest.mark.parametrize("target, expected", [(1.0, 1.0), (3.0, 2.0), (7.3e7, 5e7),
                                              (0.35 / 12e-9, 2e7), (0.99, 0.5)])
def test_round_factor_is_the_largest_1_2_5_below_the_target(target, expected):
    assert round_factor(target) == pytest.approx(expected)


@pytest.mark.parametrize("factor, text", [(2e7, "x 2e7"), (50.0, "x 50"), (1.0, "x 1"),
                                          (5e-3, "x 5e-3"), (1e3, "x 1e3")])
def test_factor_text(factor, text):
    assert factor_text(factor) == text


def test_round_factor_rejects_a_non_positive_target():
    with pytest.raises(ValueError, match="target"):
        round_factor(0.0)


@pytest.mark.parametrize("zc, amplitude, touches", [(9e-9, 9.6e-9, True),   # repulsive
                                                    (9.4e-9, 8.0e-9, False)])  # attractive
def test_tapping_frames_follow_the_state_and_touch_only_below_a0(zc, amplitude, touches):
    scene = ModesScene("tapping", vis=Recorder())
    frames, periods = 24, 2
    anim = scene.animate_tapping(zc, amplitude, free_amplitude=A0, contact_distance=A_CONTACT,
                                 frames=frames, periods=periods)
    factor = scene.factors["distance"]
    assert factor * A0 <= DEFAULTS["motion"] < 2.5 * factor * A0  # a 1-2-5 step below
    k, pos = _track(anim, "probe", "position")
    assert k.tolist() == list(range(frames * periods + 1))
    z = zc + amplitude * np.cos(2 * np.pi * k / frames)  # the first harmonic, by hand
    np.testing.assert_allclose([p[2] for p in pos], z * factor, rtol=1e-12)
    _, visible = _track(anim, "contact", "visible")
    assert visible == (z < A_CONTACT).tolist()
    assert any(visible) is touches and scene.touching_frames == sum(visible)
    assert ("touches" in scene.caption) and factor_text(factor) in scene.caption
    # the spot goes up and down with the deflection, never sideways
    _, spot = _track(anim, "spot", "position")
    spot = np.array(spot)
    assert np.ptp(spot[:, 1]) < 1e-12 and np.ptp(spot[:, 2]) > 0.05


def test_tapping_animation_is_sent_once_and_replaces_nothing_else():
    rec = Recorder()
    scene = ModesScene("tapping", vis=rec)
    objects = sum(1 for c in rec.calls if c[0] == "set_object")
    scene.animate_tapping(9e-9, 9.6e-9, free_amplitude=A0, contact_distance=A_CONTACT)
    scene.animate_tapping(9e-9, 9.0e-9, free_amplitude=A0, contact_distance=A_CONTACT)
    assert [c[0] for c in rec.calls].count("set_animation") == 2
    # only the caption and the (still) beams are redrawn per animation: the rest is drawn once
    new = [c[1] for c in rec.calls if c[0] == "set_object"][objects:]
    assert new and all("/caption/" in p or p.endswith(("/incident", "/reflected"))
                       for p in new)
    # the beams meet the lever's top at the middle of its motion
    line = rec.log["/afmsmiler/modes/incident"]["object"][0]
    top = np.asarray(line.geometry.position)[:, 1]
    s = scene.factors["distance"]
    assert top[2] == pytest.approx(9e-9 * s + DEFAULTS["tip_height"] + DEFAULTS["lever"][2],
                                   rel=1e-6)


def test_fm_lever_drifts_from_the_free_one_by_the_stated_factor():
    scene = ModesScene("fm", vis=Recorder())
    frames, periods, df, f0 = 24, 8, -40.0, 300e3
    anim = scene.animate_fm(1e-9, 5e-9, df, resonance_frequency=f0, frames=frames,
                            periods=periods)
    m = scene.factors["frequency"]
    drift = m * abs(df) / f0 * periods  # periods of drift over the animation
    assert 0.2 < drift <= 0.5
    k, probe = _track(anim, "probe", "position")
    _, ghost = _track(anim, "ghost", "position")
    s = scene.factors["distance"]
    theta = 2 * np.pi * k / frames
    np.testing.assert_allclose([p[2] for p in probe],
                               (1e-9 + 5e-9 * (1 + np.cos(theta * (1 + m * df / f0)))) * s)
    np.testing.assert_allclose([p[2] for p in ghost], (1e-9 + 5e-9 * (1 + np.cos(theta))) * s)
    assert f"df = {df:.3g} Hz" in scene.caption and factor_text(m) in scene.caption


def test_fm_without_a_shift_moves_with_the_free_lever():
    scene = ModesScene("fm", vis=Recorder())
    anim = scene.animate_fm(1e-9, 5e-9, 0.0, resonance_frequency=300e3)
    _, probe = _track(anim, "probe", "position")
    _, ghost = _track(anim, "ghost", "position")
    np.testing.assert_allclose([p[2] for p in probe], [p[2] for p in ghost])


def test_lateral_twist_and_spot_flip_between_trace_and_retrace():
    rec = Recorder()
    scene = ModesScene("lateral", vis=rec)
    n = 40
    x = np.linspace(0.0, 400e-9, n)
    twist = np.vstack((np.full(n, 3e-6), np.full(n, -2e-6)))  # friction + a slope term
    signal = np.vstack((np.full(n, 2e-4), np.full(n, -1.5e-4)))
    materials = x > 250e-9
    anim = scene.animate_lateral(x, twist, signal, materials=materials, frames=n)
    k, quat = _track(anim, "probe", "quaternion")
    angles = np.array([_quaternion_angle_x(q) for q in quat])
    tw = scene.factors["twist"]
    np.testing.assert_allclose(angles[:n], tw * 3e-6, rtol=1e-9)
    np.testing.assert_allclose(angles[n:], tw * -2e-6, rtol=1e-9)
    assert tw * 3e-6 <= DEFAULTS["twist"]
    _, pos = _track(anim, "probe", "position")
    y = np.array([p[1] for p in pos])
    assert np.all(np.diff(y[:n]) > 0) and np.all(np.diff(y[n:]) < 0)  # out, then back
    _, spot = _track(anim, "spot", "position")
    lateral = np.array([p[1] for p in spot])
    assert np.all(lateral[:n] > 0) and np.all(lateral[n:] < 0)
    assert any("/materials/" in key for key in rec.log)
    assert factor_text(tw) in scene.caption


def test_jumping_cycle_touches_where_the_model_says():
    scene = ModesScene("jumping", vis=Recorder())
    heights = np.array([20e-9, 10e-9, 0.0, 0.0, 10e-9, 20e-9, 20e-9])
    xs = np.array([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 10e-9])
    touch = heights == 0
    anim = scene.animate_jumping(heights, xs, pixel_size=10e-9, contact=touch)
    _, visible = _track(anim, "contact", "visible")
    assert visible == touch.tolist()
    _, pos = _track(anim, "probe", "position")
    np.testing.assert_allclose([p[2] for p in pos], heights * scene.factors["distance"])


def test_the_modes_share_one_path_and_the_last_drawn_owns_it():
    rec = Recorder()
    tap = ModesScene("tapping", vis=rec)
    lat = ModesScene("lateral", vis=rec)
    assert lat.owns_view and not tap.owns_view
    tap.animate_tapping(9e-9, 9.6e-9, free_amplitude=A0, contact_distance=A_CONTACT)
    assert tap.owns_view and not lat.owns_view  # drawn again before animating
    assert "/afmsmiler/modes/ghost/lever" not in rec.log


@pytest.mark.parametrize("call, match", [
    (lambda s: s.animate_tapping(-1e-9, 1e-9, free_amplitude=A0, contact_distance=A_CONTACT),
     "distance"),
    (lambda s: s.animate_tapping(9e-9, 1e-9, free_amplitude=A0, contact_distance=A_CONTACT,
                                 frames=LIMITS["frames"], periods=LIMITS["periods"]),
     "frames x periods"),
    (lambda s: s.animate_fm(1e-9, 5e-9, math.nan, resonance_frequency=3e5),
     "frequency_shift"),
    (lambda s: s.animate_lateral([0.0, 1e-9], np.zeros((2, 3)), np.zeros((2, 3))), "twist"),
    (lambda s: s.animate_lateral([0.0, 1e-9], np.zeros((2, 2)), np.full((2, 2), 2.0)),
     "signal"),
])
def test_bad_input_is_refused_before_anything_is_sent(call, match):
    rec = Recorder()
    scene = ModesScene("tapping", vis=rec)
    sent = len(rec.calls)
    with pytest.raises(ValueError, match=match):
        call(scene)
    assert not any(c[0] == "set_animation" for c in rec.calls[sent:])


def test_unknown_kind_is_refused():
    with pytest.raises(ValueError, match="kind"):
        ModesScene("contact", vis=Recorder())


@pytest.mark.slow
def test_real_view_takes_the_animation():
    from afmsmiler.scenes import static_html
    scene = ModesScene("tapping")
    scene.animate_tapping(9e-9, 9.6e-9, free_amplitude=A0, contact_distance=A_CONTACT)
    assert scene.view is not None and "<html" in static_html(scene.root).lower()
    assert any(k == "set_animation" for k, _, _ in scene.view.state.keys())


def test_lateral_without_friction_or_slope_is_drawn_unmagnified():
    scene = ModesScene("lateral", vis=Recorder())
    scene.animate_lateral(np.linspace(0.0, 1e-7, 5), np.zeros((2, 5)), np.zeros((2, 5)))
    assert scene.factors == {"twist": 1.0, "signal": 1.0}
