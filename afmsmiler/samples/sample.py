"""The sample type: heights on a regular grid with their pixel size, always in SI units."""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from .. import validation
from ..validation import check_array, check_instance, check_integer, check_positive

__all__ = ["Sample", "MAX_PIXELS", "MAX_LINE_PIXELS", "check_shape"]

#: The most pixels of an image (2048 x 2048): generated (an FFT) or read in about a second.
MAX_PIXELS = 2048 * 2048
#: The most pixels of a line.
MAX_LINE_PIXELS = 1 << 20


def check_shape(shape) -> tuple[int, ...]:
    """``shape`` as the pixels of a line ``(n,)`` or an image ``(rows, columns)``.

    Parameters
    ----------
    shape : int or tuple of int
        Pixels of a line (2 to :data:`MAX_LINE_PIXELS`) or (rows, columns) of an image (each
        >= 2, at most :data:`MAX_PIXELS` in all).

    Returns
    -------
    tuple of int

    Raises
    ------
    ValueError
        If ``shape`` is not one or two integers in range.
    """
    shape = (shape,) if isinstance(shape, (int, np.integer)) else shape
    try:
        shape = tuple(shape)
    except TypeError:
        raise ValueError(f"shape must be an int or a pair of ints, got {shape!r}") from None
    if not 1 <= len(shape) <= 2:
        raise ValueError(f"shape must be an int or a pair of ints, got {shape!r}")
    if len(shape) == 1:
        return (check_integer("shape", shape[0], 2, MAX_LINE_PIXELS),)
    return validation.check_shape("shape", shape, 2, MAX_PIXELS, low=2)


@dataclass(frozen=True)
class Sample:
    """Heights on a regular grid, with the pixel size.

    Parameters
    ----------
    heights : numpy.ndarray
        Topography in m, 1-D (a line) or 2-D (rows along y, columns along x).
    pixel_size : float
        Distance between neighbouring pixels along x (the fast axis) in m.
    name : str
        A short description (a str; anything else is a TypeError naming ``name``).
    pixel_size_y : float, optional
        Distance between neighbouring rows in m, if the pixels are not square; default
        ``pixel_size``.
    """

    heights: np.ndarray
    pixel_size: float
    name: str = ""
    pixel_size_y: float | None = None

    def __post_init__(self):
        check_instance("name", self.name, str)
        h = check_array("heights", self.heights, "m", min_size=2)
        if h.ndim not in (1, 2):
            raise ValueError(f"heights must be a 1-D or 2-D array, got shape {h.shape}")
        object.__setattr__(self, "heights", h)
        object.__setattr__(self, "pixel_size", check_positive("pixel_size", self.pixel_size, "m"))
        dy = self.pixel_size if self.pixel_size_y is None else self.pixel_size_y
        object.__setattr__(self, "pixel_size_y", check_positive("pixel_size_y", dy, "m"))

    @property
    def x(self) -> np.ndarray:
        """Pixel positions along the fast axis in m, starting at 0."""
        return np.arange(self.heights.shape[-1]) * self.pixel_size

    @property
    def size(self) -> float:
        """Length of the fast axis in m (first to last pixel)."""
        return (self.heights.shape[-1] - 1) * self.pixel_size

    def line(self, row: int) -> "Sample":
        """One row of an image as a line sample.

        Parameters
        ----------
        row : int
            Row index (0-based).

        Returns
        -------
        Sample
        """
        if self.heights.ndim != 2:
            raise ValueError("line() needs a 2-D sample (an image)")
        row = check_integer("row", row, 0, self.heights.shape[0] - 1)
        return Sample(self.heights[row], self.pixel_size, f"{self.name}, row {row}")

    def level_rows(self) -> "Sample":
        """A copy with each row's median height subtracted (AFM "line levelling").

        Removes the offset that slow-axis drift and the loop's integrator leave from line to
        line, as image software does before showing an AFM image. A line is levelled as one row.

        Returns
        -------
        Sample
        """
        h = self.heights - np.median(self.heights, axis=-1, keepdims=True)
        return replace(self, heights=h, name=f"{self.name}, rows levelled")
