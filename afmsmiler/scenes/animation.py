"""Animations built from arrays: meshcat's animation objects, filled a whole track at a time.

meshcat's own way (``with anim.at_frame(vis, k) as frame: frame[...].set_transform(m)``) is made
for a few frames: every key is a Python dict, every transform's rotation is found from its
matrix by an eigen-decomposition (``quaternion_from_matrix``), and msgpack then packs each number
on its own. A module (g) animation of 600 frames spent 50-100 ms of a slider move on that, ten
times its model. Here a track is filled from arrays at once and sent as three.js takes it
(``times`` and ``values``, each one float32 buffer: msgpack's typed-array extension 0x17, which
meshcat's viewer decodes to a ``Float32Array``; three.js's ``KeyframeTrack.parse`` takes
``times``/``values`` in place of its ``keys`` list). The objects are meshcat's own
(:class:`meshcat.animation.Animation` with its ``clips`` and their ``tracks``), so whatever reads
an animation (the tests, the recording fake, a static export) reads these the same way.
"""
from __future__ import annotations

import numpy as np
import umsgpack
from meshcat.animation import Animation, AnimationClip, AnimationTrack

from ..validation import check_array, check_choice, check_instance
from .transforms import check_visualizer

__all__ = ["PROPERTIES", "set_track", "set_translations", "quaternions_about_x"]

#: msgpack's extension code of a float32 array, as meshcat packs its geometry.
_FLOAT32 = 0x17
#: The properties an animation moves: the three.js track type of each and its values' width.
PROPERTIES = {"position": ("vector3", 3), "quaternion": ("quaternion", 4),
              "scale": ("vector3", 3), "visible": ("boolean", 1)}


class _ArrayTrack(AnimationTrack):
    """One property's keys as arrays: ``frames`` (n,) and ``values`` (n, width) or a list.

    Numeric tracks (``vector3``, ``quaternion``) are lowered to float32 buffers;
    a ``boolean`` track keeps its values as a list of bools (three.js stores those in a plain
    array).
    """

    __slots__ = ()

    def set_property(self, frame, value):  # pragma: no cover - arrays are set whole
        raise TypeError("an _ArrayTrack is set whole (set_track), not one frame at a time")

    def lower(self) -> dict:
        """The track as three.js's ``KeyframeTrack.parse`` takes it (times in frames)."""
        times = np.ascontiguousarray(self.frames, dtype=np.float32)
        if self.jstype == "boolean":
            values = [bool(v) for v in self.values]
        else:
            values = umsgpack.Ext(_FLOAT32, np.ascontiguousarray(
                self.values, dtype=np.float32).tobytes())
        return {"name": "." + self.name, "type": self.jstype,
                "times": umsgpack.Ext(_FLOAT32, times.tobytes()), "values": values}


def _clip(anim: Animation, vis) -> AnimationClip:
    path = vis.path
    clip = anim.clips.get(path)
    if clip is None:
        clip = anim.clips[path] = AnimationClip(fps=anim.default_framerate)
    return clip


def _checked(name: str, prop: str, frames: np.ndarray, values):
    """``values`` of a ``prop`` track of ``frames`` keys, or a ValueError naming ``name``."""
    jstype, width = PROPERTIES[prop]
    n = frames.size
    shape = (n,) if width == 1 else (n, width)
    if jstype == "boolean":
        v = np.asarray(values)
        if v.dtype != bool and not np.issubdtype(v.dtype, np.integer):
            raise ValueError(f"{name} must be flags (bool), got an array of {v.dtype}")
        v = [bool(x) for x in v.reshape(-1)] if v.shape == shape else None
    else:
        v = check_array(name, values)
    if v is None or (jstype != "boolean" and v.shape != shape):
        raise ValueError(f"{name} of a {prop} track must have shape {shape}, one per frame "
                         f"(frames has {n}), got {np.shape(values)}")
    return v


def set_track(anim: Animation, vis, prop: str, frames, values) -> _ArrayTrack:
    """Set the whole track of property ``prop`` of the object at ``vis`` in ``anim``.

    Parameters
    ----------
    anim : meshcat.animation.Animation
        The animation to add to.
    vis : meshcat.Visualizer
        The object (a path of the scene, e.g. ``scene.vis["probe"]``).
    prop : str
        The three.js property, a key of :data:`PROPERTIES` (``"position"``, ``"quaternion"``,
        ``"scale"``, ``"visible"``).
    frames : array_like
        The frame of each key (n increasing values).
    values : array_like
        The values: shape (n, 3) for a position or a scale, (n, 4) [x, y, z, w] for a
        quaternion, (n,) flags for ``visible``.

    Returns
    -------
    _ArrayTrack
        The track (also in ``anim.clips[vis.path].tracks[prop]``).

    Raises
    ------
    ValueError
        For an unknown ``prop``, frames that do not increase, or values of the wrong shape.
    TypeError
        If ``anim`` is not an Animation or ``vis`` not a visualizer.
    """
    check_instance("anim", anim, Animation)
    check_visualizer("vis", vis)
    check_choice("prop", prop, tuple(PROPERTIES))
    k = check_array("frames", frames, ndim=1, min_size=1, increasing=True)
    return _put(anim, vis, prop, k, _checked("values", prop, k, values))


def _put(anim, vis, prop, frames, values) -> _ArrayTrack:
    track = _ArrayTrack(prop, PROPERTIES[prop][0], frames, values)
    _clip(anim, vis).tracks[prop] = track
    return track


def set_translations(anim: Animation, vis, frames, positions, quaternions=None) -> None:
    """Animate the pose of the object at ``vis``: its position and its rotation at each frame.

    As meshcat's ``frame.set_transform`` does a frame at a time, both tracks are set: the
    rotation is the identity (a pure translation) unless ``quaternions`` is given.

    Parameters
    ----------
    anim : meshcat.animation.Animation
        The animation to add to.
    vis : meshcat.Visualizer
        The object.
    frames : array_like
        The frame of each key (n increasing values).
    positions : array_like, shape (n, 3)
        Its position at each key, in scene units.
    quaternions : array_like, shape (n, 4), optional
        Its rotation at each key as [x, y, z, w] (three.js's order).

    Raises
    ------
    ValueError
        For frames that do not increase or positions or quaternions of the wrong shape.
    TypeError
        If ``anim`` is not an Animation or ``vis`` not a visualizer.
    """
    check_instance("anim", anim, Animation)
    check_visualizer("vis", vis)
    k = check_array("frames", frames, ndim=1, min_size=1, increasing=True)
    positions = _checked("positions", "position", k, positions)
    if quaternions is None:
        quaternions = np.zeros((k.size, 4))
        quaternions[:, 3] = 1.0
    quaternions = _checked("quaternions", "quaternion", k, quaternions)
    _put(anim, vis, "position", k, positions)
    _put(anim, vis, "quaternion", k, quaternions)


def quaternions_about_x(angles) -> np.ndarray:
    """Rotations by ``angles`` (rad) about the x axis as quaternions [x, y, z, w], shape (n, 4).

    The unit quaternion of a rotation by a about the axis u is (u sin(a/2), cos(a/2)) (e.g.
    Kuipers, *Quaternions and Rotation Sequences*, 1999, Sec. 5.4); its sign is chosen with
    w >= 0, as meshcat's ``quaternion_from_matrix`` chooses it.
    """
    a = check_array("angles", angles, "rad", ndim=1)
    q = np.zeros((a.size, 4))
    q[:, 0] = np.sin(a / 2)
    q[:, 3] = np.cos(a / 2)
    q[q[:, 3] < 0] *= -1.0
    return q
