"""Rigid transforms of scene objects: 4x4 homogeneous matrices as meshcat's ``set_transform``
takes them, in scene units."""
from __future__ import annotations

import numpy as np

from ..validation import check_array

__all__ = ["translation", "rotation_between", "check_point"]


def translation(p) -> np.ndarray:
    """4x4 homogeneous translation to point ``p`` (3 values)."""
    t = np.eye(4)
    t[:3, 3] = np.asarray(p, dtype=float)
    return t


def rotation_between(a, b) -> np.ndarray:
    """3x3 rotation matrix turning direction ``a`` into direction ``b`` (Rodrigues)."""
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    a = a / np.linalg.norm(a)
    b = b / np.linalg.norm(b)
    v = np.cross(a, b)
    c = float(np.dot(a, b))
    if c < -1 + 1e-12:  # opposite: turn by pi about any axis perpendicular to a
        axis = np.cross(a, [1.0, 0.0, 0.0])
        if np.linalg.norm(axis) < 1e-6:
            axis = np.cross(a, [0.0, 1.0, 0.0])
        axis /= np.linalg.norm(axis)
        return 2 * np.outer(axis, axis) - np.eye(3)
    vx = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
    return np.eye(3) + vx + vx @ vx / (1 + c)



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
