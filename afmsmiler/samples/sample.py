"""The sample type: values on a regular grid with their pixel size, always in SI units."""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from types import MappingProxyType

import numpy as np

from .. import validation
from ..parameters import UNITS, unit_scale
from ..validation import check_array, check_instance, check_integer, check_positive

__all__ = ["Sample", "MAX_PIXELS", "MAX_LINE_PIXELS", "check_shape"]

#: The most pixels of an image (2048 x 2048): generated (an FFT) or read in about a second.
MAX_PIXELS = 2048 * 2048
#: The most pixels of a line.
MAX_LINE_PIXELS = 1 << 20
#: SI units a sample's values may carry (the quantities of AFM channels).
SAMPLE_UNITS = tuple(sorted({si for si, _ in UNITS.values()} | {"deg"}))


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


def _span(name: str, value, low: float, high: float, step: float, unit: str = "m"):
    """A (start, end) pair inside [low, high] (with half a pixel of slack for rounding)."""
    try:
        start, end = (float(v) for v in value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a pair (start, end) in {unit}, got {value!r}") from None
    slack = 0.5 * step
    if not (math.isfinite(start) and math.isfinite(end)
            and low - slack <= start < end <= high + slack):
        raise ValueError(f"{name} must be a pair (start, end) with {low:g} <= start < end <= "
                         f"{high:g} {unit} (the image's extent), got {value!r}")
    return start, end


@dataclass(frozen=True)
class Sample:
    """Values on a regular grid (heights by default), with the pixel size and units.

    A sample never loses its pixel size: every method returns a :class:`Sample` on a grid that
    it states. Positions run from the first pixel (0 m) to the last: :attr:`width` is the
    distance between the first and last column, ``(columns - 1) * pixel_size``, as :attr:`x`
    and :attr:`size` count it (an instrument's "scan size" is one pixel more:
    ``columns * pixel_size``).

    Parameters
    ----------
    heights : numpy.ndarray
        Values in ``unit`` (topography in m), 1-D (a line) or 2-D (rows along y, the slow axis;
        columns along x, the fast axis).
    pixel_size : float
        Distance between neighbouring pixels along x (the fast axis) in m.
    name : str
        A short description (a str; anything else is a TypeError naming ``name``).
    pixel_size_y : float, optional
        Distance between neighbouring rows in m, if the pixels are not square; default
        ``pixel_size``.
    channel : str
        The channel the values come from ("height", a file's "Height", "Amplitude" ...).
    unit : str
        SI unit of the values: ``"m"`` for heights, ``"V"`` for a deflection in volts, ``"deg"``
        for a phase (one of :data:`SAMPLE_UNITS`).
    metadata : mapping, optional
        The file's own metadata (or a generator's parameters), kept as a read-only mapping.

    Examples
    --------
    >>> s = Sample(np.zeros((3, 5)), 2e-9)
    >>> s.shape, s.width, s.height_extent
    ((3, 5), 8e-09, 4e-09)
    """

    heights: np.ndarray
    pixel_size: float
    name: str = ""
    pixel_size_y: float | None = None
    channel: str = "height"
    unit: str = "m"
    metadata: object = field(default=None, compare=False)

    def __post_init__(self):
        check_instance("name", self.name, str)
        check_instance("channel", self.channel, str)
        validation.check_choice("unit", self.unit, SAMPLE_UNITS)
        h = check_array("heights", self.heights, self.unit, min_size=2)
        if h.ndim not in (1, 2):
            raise ValueError(f"heights must be a 1-D or 2-D array, got shape {h.shape}")
        object.__setattr__(self, "heights", h)
        object.__setattr__(self, "pixel_size", check_positive("pixel_size", self.pixel_size, "m"))
        dy = self.pixel_size if self.pixel_size_y is None else self.pixel_size_y
        object.__setattr__(self, "pixel_size_y", check_positive("pixel_size_y", dy, "m"))
        meta = {} if self.metadata is None else self.metadata
        try:
            meta = MappingProxyType(dict(meta))
        except (TypeError, ValueError):
            raise TypeError(f"metadata must be a mapping, got {self.metadata!r}") from None
        object.__setattr__(self, "metadata", meta)

    # --- the grid ------------------------------------------------------------------------------
    @property
    def shape(self) -> tuple[int, ...]:
        """Pixels: ``(n,)`` of a line, ``(rows, columns)`` of an image."""
        return self.heights.shape

    @property
    def x(self) -> np.ndarray:
        """Pixel positions along the fast axis in m, starting at 0."""
        return np.arange(self.heights.shape[-1]) * self.pixel_size

    @property
    def y(self) -> np.ndarray:
        """Row positions along the slow axis in m, starting at 0 (``[0.0]`` for a line)."""
        rows = self.heights.shape[0] if self.heights.ndim == 2 else 1
        return np.arange(rows) * self.pixel_size_y

    @property
    def size(self) -> float:
        """Length of the fast axis in m (first to last pixel); the same as :attr:`width`."""
        return (self.heights.shape[-1] - 1) * self.pixel_size

    @property
    def width(self) -> float:
        """Extent along x in m, first to last column: ``(columns - 1) * pixel_size``."""
        return self.size

    @property
    def height_extent(self) -> float:
        """Extent along y in m, first to last row: ``(rows - 1) * pixel_size_y`` (0 for a
        line)."""
        rows = self.heights.shape[0] if self.heights.ndim == 2 else 1
        return (rows - 1) * self.pixel_size_y

    # --- new samples on a stated grid ----------------------------------------------------------
    def with_heights(self, heights) -> "Sample":
        """The same grid, channel, unit and metadata with new values.

        Parameters
        ----------
        heights : array_like
            New values in :attr:`unit`, of the same shape as :attr:`heights`.

        Returns
        -------
        Sample

        Raises
        ------
        ValueError
            If the shape differs or a value is not finite.
        """
        h = check_array("heights", heights, self.unit, min_size=2)
        if h.shape != self.heights.shape:
            raise ValueError(f"heights must have this sample's shape {self.heights.shape}, got "
                             f"{h.shape}")
        return replace(self, heights=h)

    def crop(self, x=None, y=None) -> "Sample":
        """The pixels inside a window, positions in m from the image's origin (its first pixel).

        Keeps the pixels whose positions lie in ``[x0, x1]`` and ``[y0, y1]`` (ends included,
        to a quarter of a pixel); the result starts at its own origin, same pixel sizes.

        Parameters
        ----------
        x : tuple of float, optional
            ``(x0, x1)`` in m, inside ``[0, width]``; default: the whole width.
        y : tuple of float, optional
            ``(y0, y1)`` in m, inside ``[0, height_extent]``; default: all rows (a line has no
            ``y``).

        Returns
        -------
        Sample

        Raises
        ------
        ValueError
            If a window lies outside the image, is empty or holds fewer than 2 pixels.
        """
        h = self.heights
        cols = self._window("x", x, self.width, self.pixel_size, h.shape[-1])
        if h.ndim == 1:
            if y is not None:
                raise ValueError(f"y must be None for a line (a 1-D sample), got {y!r}")
            out = h[cols]
        else:
            rows = self._window("y", y, self.height_extent, self.pixel_size_y, h.shape[0])
            out = h[rows, cols]
        return replace(self, heights=out.copy(), name=f"{self.name}, cropped")

    @staticmethod
    def _window(name, span, extent, step, n):
        if span is None:
            return slice(0, n)
        start, end = _span(name, span, 0.0, extent, step)
        i0 = max(int(math.ceil(start / step - 0.25)), 0)
        i1 = min(int(math.floor(end / step + 0.25)), n - 1)
        if i1 - i0 < 1:
            raise ValueError(f"{name} must hold at least 2 pixels ({step:g} m apart), got "
                             f"{span!r}")
        return slice(i0, i1 + 1)

    def resample(self, pixel_size: float | None = None, pixel_size_y: float | None = None, *,
                 shape=None) -> "Sample":
        """The same surface on another grid, by linear interpolation (ends kept).

        Give new pixel sizes (the grid keeps the origin and as many whole pixels as fit in
        :attr:`width` and :attr:`height_extent`) or a new ``shape`` (the pixel sizes then
        follow from the extents, first to last pixel kept).

        Parameters
        ----------
        pixel_size : float, optional
            New pixel size along x in m.
        pixel_size_y : float, optional
            New row spacing in m (default: ``pixel_size`` if given, else the present one).
        shape : int or tuple of int, optional
            New pixels (as :func:`check_shape`), instead of pixel sizes.

        Returns
        -------
        Sample

        Raises
        ------
        ValueError
            If both or neither of ``pixel_size`` and ``shape`` are given, or the new grid has
            fewer than 2 or more than :data:`MAX_PIXELS` pixels.

        Notes
        -----
        Linear interpolation makes no new extrema; downsampling by more than two pixels per
        new pixel averages nothing (it picks), so fine features may alias: crop first if you
        want them.
        """
        h = self.heights
        if (pixel_size is None) == (shape is None):
            raise ValueError("give either pixel_size (m) or shape, not both or neither; got "
                             f"pixel_size={pixel_size!r}, shape={shape!r}")
        if shape is not None:
            if pixel_size_y is not None:
                raise ValueError(f"pixel_size_y must be None with shape, got {pixel_size_y!r}")
            new = check_shape(shape)
            if len(new) != h.ndim:
                raise ValueError(f"shape must have {h.ndim} dimension(s) like the sample, got "
                                 f"{shape!r}")
            dx = self.width / (new[-1] - 1)
            dy = self.height_extent / (new[0] - 1) if h.ndim == 2 else self.pixel_size_y
        else:
            dx = check_positive("pixel_size", pixel_size, "m")
            dy = dx if pixel_size_y is None else check_positive("pixel_size_y", pixel_size_y,
                                                                 "m")
            if h.ndim == 1:
                dy = self.pixel_size_y
            counts = [self.width / dx]
            if h.ndim == 2:
                counts.insert(0, self.height_extent / dy)
            if max(counts) > MAX_LINE_PIXELS:
                raise ValueError(f"pixel_size must give at most {MAX_LINE_PIXELS} pixels per "
                                 f"side, got {dx:g} m (and pixel_size_y = {dy:g} m)")
            new = tuple(int(math.floor(c + 1e-9)) + 1 for c in counts)
            try:
                new = check_shape(new if len(new) == 2 else new[0])
            except ValueError as exc:
                raise ValueError(f"{exc} (from pixel_size = {dx:g} m, pixel_size_y = {dy:g} m "
                                 f"over the extent {self.width:g} x {self.height_extent:g} m)"
                                 ) from None
        xs = np.arange(new[-1]) * (dx / self.pixel_size)
        xs = np.minimum(xs, h.shape[-1] - 1)  # rounding at the last pixel
        out = np.array([np.interp(xs, np.arange(h.shape[-1]), row)
                        for row in np.atleast_2d(h)])
        if h.ndim == 2:
            ys = np.minimum(np.arange(new[0]) * (dy / self.pixel_size_y), h.shape[0] - 1)
            out = np.array([np.interp(ys, np.arange(h.shape[0]), col) for col in out.T]).T
        else:
            out = out[0]
        return replace(self, heights=out, pixel_size=dx, pixel_size_y=dy,
                       name=f"{self.name}, resampled")

    def values_in(self, display_unit: str) -> np.ndarray:
        """The values in ``display_unit`` (e.g. ``"nm"``), through :data:`parameters.UNITS`.

        Parameters
        ----------
        display_unit : str
            A unit of :data:`~afmsmiler.parameters.UNITS` that measures :attr:`unit`.

        Returns
        -------
        numpy.ndarray
            A new array.

        Raises
        ------
        ValueError
            If the unit is unknown or measures another quantity (``"nN"`` for a height).
        """
        if self.unit == "deg":  # a phase channel, stored in degrees as instruments do
            if display_unit == "deg":
                return self.heights.copy()
            return self.heights / unit_scale("deg", "rad") * unit_scale(display_unit, "rad")
        return self.heights * unit_scale(display_unit, self.unit)

    # --- lines and levelling -------------------------------------------------------------------
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
        return replace(self, heights=self.heights[row].copy(), name=f"{self.name}, row {row}",
                       pixel_size_y=None)

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
