"""The statistics users read off an AFM image: roughness, the height histogram, line profiles.

- :func:`rms` (Rq, Sq) and :func:`ra` (Ra, Sa): roughness about the mean height;
- :func:`histogram`: the height distribution (counts and probability density);
- :func:`line_profile`: heights along a straight segment between two points given in m,
  sampled by interpolation.

All take a :class:`~afmsmiler.samples.Sample` (a line or an image) and an optional boolean
``mask`` of the pixels to leave out, and work in SI units. Roughness is measured about the mean
of the values as given: level the image first (:mod:`afmsmiler.imaging.corrections`), since a
tilt would count as roughness.

Sources: ISO 4287 (Ra, Rq of a profile) and ISO 25178-2 (Sa, Sq of a surface); Gwyddion user
guide, "Statistical Analysis" (Statistical Quantities, Height Distribution) and "Profile
Extraction", https://gwyddion.net/documentation/.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import ndimage

from ..samples import Sample
from ..validation import check_array, check_choice, check_instance, check_integer, check_range

__all__ = ["rms", "ra", "Histogram", "histogram", "Profile", "line_profile", "MAX_BINS",
           "MAX_PROFILE_POINTS"]

#: The most bins of a height histogram.
MAX_BINS = 100_000
#: The most points of a line profile.
MAX_PROFILE_POINTS = 1_000_000


def _values(sample: Sample, mask) -> np.ndarray:
    """The sample's values not masked, as a flat array."""
    check_instance("sample", sample, Sample)
    h = sample.heights
    if mask is None:
        return h.ravel()
    m = np.asarray(mask)
    if m.dtype != bool:
        raise ValueError(f"mask must be a boolean array (True on pixels to leave out), got an "
                         f"array of {m.dtype}")
    if m.shape != h.shape:
        raise ValueError(f"mask must have the sample's shape {h.shape}, got {m.shape}")
    v = h[~m]
    if v.size == 0:
        raise ValueError("mask must leave at least one pixel, got all of them masked")
    return v


def rms(sample: Sample, mask=None) -> float:
    """Root mean square roughness about the mean: Rq (a line) or Sq (an image).

    Rq = sqrt(mean((z - mean(z))^2)) over the pixels not masked (ISO 4287, ISO 25178-2;
    Gwyddion's "RMS roughness"). A sine of amplitude A has Rq = A / sqrt(2).

    Parameters
    ----------
    sample : Sample
        A line or an image.
    mask : ndarray of bool, optional
        Pixels to leave out (True), of the sample's shape.

    Returns
    -------
    float
        In the sample's unit (m for heights).
    """
    v = _values(sample, mask)
    return float(np.sqrt(np.mean((v - v.mean()) ** 2)))


def ra(sample: Sample, mask=None) -> float:
    """Arithmetic mean roughness about the mean: Ra (a line) or Sa (an image).

    Ra = mean(|z - mean(z)|) over the pixels not masked (ISO 4287, ISO 25178-2). A sine of
    amplitude A has Ra = 2 A / pi.

    Parameters
    ----------
    sample : Sample
        A line or an image.
    mask : ndarray of bool, optional
        Pixels to leave out (True), of the sample's shape.

    Returns
    -------
    float
        In the sample's unit (m for heights).
    """
    v = _values(sample, mask)
    return float(np.mean(np.abs(v - v.mean())))


@dataclass(frozen=True)
class Histogram:
    """A height histogram.

    Attributes
    ----------
    counts : ndarray of int
        Pixels in each bin.
    edges : ndarray
        Bin edges in the sample's unit (m), one more than ``counts``.
    """

    counts: np.ndarray
    edges: np.ndarray

    @property
    def centres(self) -> np.ndarray:
        """Bin centres in the sample's unit (m)."""
        return 0.5 * (self.edges[1:] + self.edges[:-1])

    @property
    def density(self) -> np.ndarray:
        """The probability density in 1/(sample's unit) (1/m): counts / (total x bin width), so
        that it integrates to 1 over the bins (Gwyddion's "Height Distribution")."""
        return self.counts / (self.counts.sum() * np.diff(self.edges))


def histogram(sample: Sample, bins: int = 100, mask=None, *, range=None) -> Histogram:
    """The distribution of the heights (values) of a sample.

    Parameters
    ----------
    sample : Sample
        A line or an image.
    bins : int
        Number of equal bins, 1 to :data:`MAX_BINS`.
    mask : ndarray of bool, optional
        Pixels to leave out (True), of the sample's shape.
    range : (float, float), optional
        Lowest and highest edge in the sample's unit (m); default the lowest and highest value
        (values outside are not counted).

    Returns
    -------
    Histogram
    """
    v = _values(sample, mask)
    bins = check_integer("bins", bins, 1, MAX_BINS)
    if range is not None:
        low, high = check_array("range", range, "m", ndim=1, size=2)
        check_range("range[1]", high, low, math.inf, "m", low_inclusive=False)
        range = (low, high)
    counts, edges = np.histogram(v, bins=bins, range=range)
    return Histogram(counts, edges)


@dataclass(frozen=True)
class Profile:
    """Heights sampled along a straight segment of an image.

    Attributes
    ----------
    distance : ndarray
        Distance from the start point along the segment in m.
    x, y : ndarray
        Positions of the samples in m, from the image's first pixel.
    heights : ndarray
        Interpolated values there (in the sample's unit, m for heights).
    """

    distance: np.ndarray
    x: np.ndarray
    y: np.ndarray
    heights: np.ndarray

    def as_sample(self) -> Sample:
        """The profile as a line :class:`~afmsmiler.samples.Sample` (its points are equally
        spaced; a profile of one point cannot be one)."""
        return Sample(self.heights, float(self.distance[1] - self.distance[0]), "profile")


def line_profile(sample: Sample, start, end, *, points: int | None = None,
                 order: int = 1) -> Profile:
    """The heights along the segment from ``start`` to ``end`` (positions in m).

    Points are spaced evenly from ``start`` to ``end`` (both included), and the image is
    interpolated there (Gwyddion's "Profile" tool): ``order=1`` bilinearly, ``3`` with cubic
    splines, ``0`` takes the nearest pixel. Pixel (row i, column j) lies at
    x = j pixel_size, y = i pixel_size_y.

    Parameters
    ----------
    sample : Sample
        An image (2-D).
    start, end : (float, float)
        End points (x, y) in m, inside the image: 0 <= x <= (columns - 1) pixel_size and
        0 <= y <= (rows - 1) pixel_size_y; distinct.
    points : int, optional
        Number of points, 2 to :data:`MAX_PROFILE_POINTS`; default one per pixel along the
        segment (its length over the smaller pixel size, plus one).
    order : {0, 1, 3}
        Interpolation order.

    Returns
    -------
    Profile

    Raises
    ------
    ValueError
        If a point lies outside the image, the points coincide or a setting is out of range.
    """
    check_instance("sample", sample, Sample)
    if sample.heights.ndim != 2:
        raise ValueError(f"sample must be an image (2-D heights), got shape "
                         f"{sample.heights.shape}")
    rows, cols = sample.heights.shape
    width = (cols - 1) * sample.pixel_size
    height = (rows - 1) * sample.pixel_size_y
    ends = []
    for name, point in (("start", start), ("end", end)):
        x, y = check_array(name, point, "m", ndim=1, size=2)
        check_range(f"{name}[0] (x)", x, 0.0, width, "m")
        check_range(f"{name}[1] (y)", y, 0.0, height, "m")
        ends.append((x, y))
    (x0, y0), (x1, y1) = ends
    length = math.hypot(x1 - x0, y1 - y0)
    if length == 0.0:
        raise ValueError(f"end must differ from start, got both at {tuple(ends[0])} m")
    if points is None:
        points = min(MAX_PROFILE_POINTS,
                     int(math.ceil(length / min(sample.pixel_size, sample.pixel_size_y))) + 1)
    points = check_integer("points", points, 2, MAX_PROFILE_POINTS)
    order = check_choice("order", order, (0, 1, 3))
    t = np.linspace(0.0, 1.0, points)
    x = x0 + t * (x1 - x0)
    y = y0 + t * (y1 - y0)
    coords = np.stack([y / sample.pixel_size_y, x / sample.pixel_size])
    # round-off may put the last point a hair outside: clip to the grid
    coords[0] = np.clip(coords[0], 0, rows - 1)
    coords[1] = np.clip(coords[1], 0, cols - 1)
    z = ndimage.map_coordinates(sample.heights, coords, order=order, mode="nearest")
    return Profile(t * length, x, y, z)
