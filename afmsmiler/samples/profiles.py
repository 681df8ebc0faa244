"""The named line profiles that module (c)'s controller scans: ideal shapes, a real line and a
synthetic particle line, all at one pixel size and feature height."""
from __future__ import annotations

import numpy as np

from ..validation import check_choice, check_finite, check_integer, check_positive
from .readers import REAL_IMAGE, real_image
from .sample import MAX_LINE_PIXELS, Sample
from .synthetic import grating, particles, step

__all__ = ["PROFILES", "REAL_LINE_ROW", "profile"]

#: Line profiles offered by the controller panel, by name.
PROFILES = ("step", "grating", "real line", "particles")
#: The row of :func:`~afmsmiler.samples.readers.real_image` that ``profile("real line")`` takes
#: (it crosses three islands and their terraces).
REAL_LINE_ROW = 256


def profile(name: str, pixels: int = 512, pixel_size: float = 4e-9,
            height: float = 50e-9) -> Sample:
    """A named line profile, scaled to a feature ``height``.

    ``"step"`` and ``"grating"`` (4 periods) are ideal; ``"real line"`` is a row of the real AFM
    image :func:`real_image` (row :data:`REAL_LINE_ROW`, islands a few nm high and the
    surface's roughness), its first ``pixels`` pixels put on the requested pixel size and its
    range scaled to ``height``: the shape of a real line at the scale of the other profiles
    (for the line at its own scale, 3.9 nm pixels and about 17 nm high, use
    ``real_image().line(REAL_LINE_ROW)``);
    ``"particles"`` is the highest row of :func:`particles`, a synthetic image.

    Parameters
    ----------
    name : str
        One of :data:`PROFILES`.
    pixels : int
        Number of pixels (at most 512 for ``"real line"``).
    pixel_size : float
        Pixel size in m.
    height : float
        Feature height in m (step height, grating depth, range of the real line, particle
        diameter).

    Returns
    -------
    Sample
    """
    check_choice("name", name, PROFILES)
    if name in ("step", "grating"):  # named here: the generators call it their shape
        check_integer("pixels", pixels, 2, MAX_LINE_PIXELS)
    if name == "step":
        return step(pixels, pixel_size, height)
    if name == "grating":
        return grating(pixels, pixel_size, pixels * pixel_size / 4, height)
    if name == "real line":
        row = _real_row()
        n = check_integer("pixels", pixels, 2, row.size)
        pixel_size = check_positive("pixel_size", pixel_size, "m")
        height = check_finite("height", height, "m")
        h = row[:n] - np.min(row[:n])
        return Sample(h * (height / np.ptp(h)), pixel_size,
                      f"real line (row {REAL_LINE_ROW} of {REAL_IMAGE.name}, rescaled)")
    img = particles((64, pixels), pixel_size, count=max(4, pixels // 16), radius=height / 2,
                    rms=height / 50, seed=3)
    rows = img.heights.max(axis=1)
    return Sample(img.heights[int(np.argmax(rows))], pixel_size, "particles line (synthetic)")


_REAL_ROW: list = []


def _real_row() -> np.ndarray:
    if not _REAL_ROW:
        _REAL_ROW.append(real_image().heights[REAL_LINE_ROW].copy())
    return _REAL_ROW[0]
