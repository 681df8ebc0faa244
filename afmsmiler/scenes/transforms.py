"""Rigid transforms of scene objects: 4x4 homogeneous matrices as meshcat's ``set_transform``
takes them, in scene units (the pure geometry, :func:`rotation_between` and :func:`reflect`, lives
in :mod:`afmsmiler.geometry` and is re-exported here)."""
from __future__ import annotations

import numpy as np

from ..geometry import reflect, rotation_between
from ..validation import check_array

__all__ = ["reflect", "translation", "rotation_between", "check_point"]


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
