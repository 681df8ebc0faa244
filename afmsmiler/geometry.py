"""Pure geometry of directions in 3D: rotations between directions and mirror reflections.

Shared by the models (the instruments' assembly, :mod:`afmsmiler.instrument.assembly`) and the
scenes (:mod:`afmsmiler.scenes.transforms` re-exports them); numpy only, any length unit.
"""
from __future__ import annotations

import numpy as np

from .validation import check_array

__all__ = ["rotation_between", "reflect"]


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



def reflect(direction, normal) -> np.ndarray:
    """A ray's direction after a mirror (the law of reflection, r = d - 2 (d . n) n).

    Parameters
    ----------
    direction : array_like
        The incoming direction (3 values, any length).
    normal : array_like
        The mirror's normal (3 values, normalised here; either side).

    Returns
    -------
    numpy.ndarray
        The reflected direction, as long as ``direction``.

    Examples
    --------
    >>> reflect([1.0, 0.0, -1.0], [0.0, 0.0, 1.0]).tolist()
    [1.0, 0.0, 1.0]
    """
    d = check_array("direction", direction, size=3)
    n = check_array("normal", normal, size=3)
    length = np.linalg.norm(n)
    if not length > 0:
        raise ValueError("normal must not be zero")
    n = n / length
    return d - 2 * np.dot(d, n) * n

