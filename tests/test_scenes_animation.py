"""Animations filled from arrays (:mod:`afmsmiler.scenes.animation`) against meshcat's own frame
by frame API: the same tracks, the same rotations (meshcat's ``quaternion_from_matrix``, an
eigen-decomposition, is the independent reference), and on the wire the typed buffers three.js's
``KeyframeTrack.parse`` takes (``times``, ``values``) in place of meshcat's ``keys``."""
import math

import numpy as np
import pytest
import umsgpack
from meshcat.animation import Animation
from meshcat.transformations import quaternion_from_matrix

from afmsmiler.scenes.animation import quaternions_about_x, set_track, set_translations
from afmsmiler.scenes.transforms import translation
from tests.recording import Recorder


def _rotation_x(angle):
    c, s = math.cos(angle), math.sin(angle)
    r = np.eye(4)
    r[1:3, 1:3] = [[c, -s], [s, c]]
    return r


def _decoded(data: dict) -> dict:
    """A lowered track as the viewer sees it: float32 buffers decoded."""
    out = dict(data)
    for key in ("times", "values"):
        if isinstance(out[key], umsgpack.Ext):
            assert out[key].type == 0x17  # meshcat's Float32Array
            out[key] = np.frombuffer(out[key].data, dtype=np.float32)
    return out


def test_quaternions_about_x_equal_meshcats_from_the_matrix():
    angles = np.linspace(-3.1, 3.1, 41)
    expected = [quaternion_from_matrix(_rotation_x(a)) for a in angles]  # [w, x, y, z]
    expected = np.array([[q[1], q[2], q[3], q[0]] for q in expected])   # three.js order
    np.testing.assert_allclose(quaternions_about_x(angles), expected, atol=1e-12)


def test_translations_and_twists_equal_meshcats_frame_by_frame_animation():
    rng = np.random.default_rng(7)
    y, twist = rng.uniform(-1, 1, 25), rng.uniform(-0.5, 0.5, 25)
    reference, fast = Animation(default_framerate=24), Animation(default_framerate=24)
    vis = Recorder()
    for k in range(25):
        with reference.at_frame(vis, k) as frame:
            frame["probe"].set_transform(translation([0.0, y[k], 0.1]) @ _rotation_x(twist[k]))
    positions = np.column_stack((np.zeros(25), y, np.full(25, 0.1)))
    set_translations(fast, vis["probe"], np.arange(25), positions, quaternions_about_x(twist))
    (path, ref_clip), = reference.clips.items()
    clip = fast.clips[path]
    assert clip.fps == ref_clip.fps == 24
    for prop in ("position", "quaternion"):
        assert list(clip.tracks[prop].frames) == ref_clip.tracks[prop].frames
        np.testing.assert_allclose(clip.tracks[prop].values, ref_clip.tracks[prop].values,
                                   atol=1e-12)


def test_a_translation_carries_the_identity_rotation_as_meshcat_sends_it():
    anim, vis = Animation(), Recorder()
    set_translations(anim, vis["spot"], [0, 1, 2], np.ones((3, 3)))
    q = anim.clips[vis["spot"].path].tracks["quaternion"].values
    np.testing.assert_array_equal(q, [[0, 0, 0, 1]] * 3)


def test_lowered_tracks_are_the_buffers_three_js_parses():
    anim, vis = Animation(default_framerate=30), Recorder()
    positions = np.arange(12.0).reshape(4, 3) / 7
    set_translations(anim, vis["probe"], np.arange(4), positions)
    set_track(anim, vis["contact"], "visible", np.arange(4), [0, 1, 1, 0])
    lowered = umsgpack.unpackb(umsgpack.packb(anim.lower()))
    by_path = {item["path"]: item["clip"] for item in lowered}
    probe = by_path[vis["probe"].path.lower()]
    assert probe["fps"] == 30
    tracks = {t["name"]: _decoded(t) for t in probe["tracks"]}
    assert tracks[".position"]["type"] == "vector3" and "keys" not in tracks[".position"]
    np.testing.assert_array_equal(tracks[".position"]["times"], [0, 1, 2, 3])
    np.testing.assert_allclose(tracks[".position"]["values"], positions.ravel(), rtol=1e-7)
    contact = {t["name"]: t for t in by_path[vis["contact"].path.lower()]["tracks"]}
    assert contact[".visible"]["type"] == "boolean"
    assert contact[".visible"]["values"] == [False, True, True, False]


@pytest.mark.parametrize("kwargs, match", [
    (dict(prop="colour"), "prop"),
    (dict(values=np.zeros((3, 4))), r"shape \(3, 3\)"),
    (dict(frames=[0, 2, 1]), "frames"),
    (dict(values=np.full((3, 3), np.nan)), "values"),
])
def test_bad_tracks_are_named(kwargs, match):
    args = dict(prop="position", frames=[0, 1, 2], values=np.zeros((3, 3)))
    args.update(kwargs)
    with pytest.raises(ValueError, match=match):
        set_track(Animation(), Recorder(), **args)


def test_a_foreign_animation_or_visualizer_is_named():
    with pytest.raises(TypeError, match="anim"):
        set_translations({}, Recorder(), [0], np.zeros((1, 3)))
    with pytest.raises(TypeError, match="vis"):
        set_translations(Animation(), "probe", [0], np.zeros((1, 3)))
