"""Rigid transforms of scene objects: 4x4 homogeneous matrices as meshcat's ``set_transform``
takes them, in scene units (the pure geometry, :func:`rotation_between` and :func:`reflect`, lives
in :mod:`afmsmiler.geometry` and is re-exported here)."""
from __future__ import annotations

import numpy as np

from ..geometry import reflect, rotation_between
from ..validation import check_array

__all__ = ["reflect", "translation", "rotation_between", "check_point", "check_visualizer"]


def translation(p) -> np.ndarray:
    """4x4 homogeneous translation to point ``p`` (3 values)."""
    t = np.eye(4)
    t[:3, 3] = np.asarray(p, dtype=float)
    return t


def check_point(name: str, p) -> np.ndarray:
    """``p`` as a point (3 finite values), or a ValueError naming ``name``.

    Parameters
    ----------
    name : str
        The parameter's name for the message.
    p : array_like, shape (3,)
        The point, in scene units.
    """
    return check_array(name, p, ndim=1, size=3)


def check_visualizer(name: str, vis):
    """``vis``, or a TypeError naming ``name`` unless it is a visualizer to draw into.

    A visualizer is meshcat's ``Visualizer`` or anything that draws like one (a test's recorder,
    a sub-path ``vis["beam"]``, the instrument's colouring canvas): it takes a path by
    ``vis[...]`` and has ``set_object`` and ``set_transform``. Checked where a scene receives
    it, so that a wrong object is named at once instead of failing deep inside with "'str'
    object has no attribute 'set_object'".

    Parameters
    ----------
    name : str
        The parameter's name for the message.
    vis : meshcat.Visualizer
        The visualizer.

    Returns
    -------
    meshcat.Visualizer
        ``vis``.
    """
    if isinstance(vis, (str, bytes)) or not all(
            callable(getattr(vis, method, None))
            for method in ("__getitem__", "set_object", "set_transform")):
        raise TypeError(f"{name} must be a meshcat.Visualizer (or draw like one), got "
                        f"{type(vis).__name__} {vis!r:.60}")
    return vis
