"""Sample topographies with their physical pixel size: steps, gratings, rough and particle surfaces.

Every generator returns a :class:`Sample`, which carries the heights (m) together with the pixel
size (m), so that a scan or a plot never has to guess its units. Lines are 1-D samples, images
2-D (rows along the slow axis y, columns along the fast scan axis x). Random surfaces take a
``seed`` and are reproducible.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .validation import check_array, check_choice, check_finite, check_integer, check_positive, \
    check_range

__all__ = ["Sample", "step", "grating", "rough_surface", "particles", "PROFILES", "profile"]


@dataclass(frozen=True)
class Sample:
    """Heights on a regular grid, with the pixel size.

    Parameters
    ----------
    heights : numpy.ndarray
        Topography in m, 1-D (a line) or 2-D (rows along y, columns along x).
    pixel_size : float
        Distance between neighbouring pixels in m.
    name : str
        A short description.
    """

    heights: np.ndarray
    pixel_size: float
    name: str = ""

    def __post_init__(self):
        h = check_array("heights", self.heights, "m", min_size=2)
        if h.ndim not in (1, 2):
            raise ValueError(f"heights must be a 1-D or 2-D array, got shape {h.shape}")
        object.__setattr__(self, "heights", h)
        object.__setattr__(self, "pixel_size", check_positive("pixel_size", self.pixel_size, "m"))

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


def _n(pixels):
    return check_integer("pixels", pixels, 2, 1 << 20)


def step(pixels: int = 512, pixel_size: float = 4e-9, height: float = 50e-9,
         position: float = 0.5) -> Sample:
    """A line with one step up of ``height`` at ``position`` (fraction of the line).

    Parameters
    ----------
    pixels : int
        Number of pixels (>= 2).
    pixel_size : float
        Pixel size in m.
    height : float
        Step height in m (any sign).
    position : float
        Where the step is, as a fraction of the line in (0, 1).

    Returns
    -------
    Sample
    """
    n = _n(pixels)
    pixel_size = check_positive("pixel_size", pixel_size, "m")
    height = check_finite("height", height, "m")
    position = check_range("position", position, 0, 1, low_inclusive=False, high_inclusive=False)
    x = np.arange(n) / (n - 1)
    return Sample(np.where(x >= position, height, 0.0), pixel_size, "step")


def grating(pixels: int = 512, pixel_size: float = 4e-9, period: float = 500e-9,
            height: float = 50e-9, duty: float = 0.5) -> Sample:
    """A rectangular grating: lines of ``height`` and width ``duty * period``.

    Parameters
    ----------
    pixels : int
        Number of pixels (>= 2).
    pixel_size : float
        Pixel size in m.
    period : float
        Grating period in m (> 0).
    height : float
        Height of the lines in m.
    duty : float
        Fraction of a period that is raised, in (0, 1).

    Returns
    -------
    Sample
    """
    n = _n(pixels)
    pixel_size = check_positive("pixel_size", pixel_size, "m")
    period = check_positive("period", period, "m")
    height = check_finite("height", height, "m")
    duty = check_range("duty", duty, 0, 1, low_inclusive=False, high_inclusive=False)
    phase = np.mod(np.arange(n) * pixel_size / period, 1.0)
    return Sample(np.where(phase < duty, height, 0.0), pixel_size, "grating")


def _gaussian_field(shape, pixel_size, correlation_length, rng):
    noise = rng.standard_normal(shape)
    freqs = [np.fft.fftfreq(n, d=pixel_size) for n in shape]
    k2 = sum(np.meshgrid(*[f ** 2 for f in freqs], indexing="ij"))
    spectrum = np.exp(-(np.pi * correlation_length) ** 2 * k2)
    field = np.fft.ifftn(np.fft.fftn(noise) * spectrum).real
    return field / field.std()


def rough_surface(shape=(256, 256), pixel_size: float = 4e-9, rms: float = 2e-9,
                  correlation_length: float = 20e-9, seed: int = 0) -> Sample:
    """A Gaussian random rough surface of given RMS height and correlation length.

    White noise filtered by a Gaussian in Fourier space, scaled to the requested RMS.

    Parameters
    ----------
    shape : int or tuple of int
        Pixels of a line (int) or (rows, columns) of an image.
    pixel_size : float
        Pixel size in m.
    rms : float
        RMS roughness in m (>= 0).
    correlation_length : float
        Lateral correlation length in m (> 0).
    seed : int
        Seed of the random generator.

    Returns
    -------
    Sample
    """
    shape = (shape,) if isinstance(shape, (int, np.integer)) else tuple(shape)
    if not 1 <= len(shape) <= 2:
        raise ValueError(f"shape must be an int or a pair of ints, got {shape!r}")
    shape = tuple(check_integer("shape", n, 2, 1 << 14) for n in shape)
    pixel_size = check_positive("pixel_size", pixel_size, "m")
    rms = check_range("rms", rms, 0, np.inf, "m")
    correlation_length = check_positive("correlation_length", correlation_length, "m")
    rng = np.random.default_rng(check_integer("seed", seed, 0))
    return Sample(rms * _gaussian_field(shape, pixel_size, correlation_length, rng), pixel_size,
                  "rough surface")


def particles(shape=(256, 256), pixel_size: float = 4e-9, count: int = 30,
              radius: float = 25e-9, rms: float = 1e-9, seed: int = 1) -> Sample:
    """A "real-like" image: spherical particles (e.g. nanoparticles) on a rough substrate.

    Each particle of radius r shows as the cap sqrt(r^2 - rho^2) (its height reaching 2 r at the
    top, as a tip convolution-free AFM would see a sphere on the substrate, upper half only:
    r + sqrt(r^2 - rho^2)); overlapping particles take the highest one.

    Parameters
    ----------
    shape : tuple of int
        (rows, columns).
    pixel_size : float
        Pixel size in m.
    count : int
        Number of particles (>= 0).
    radius : float
        Particle radius in m (> 0).
    rms : float
        RMS roughness of the substrate in m.
    seed : int
        Seed of the random generator.

    Returns
    -------
    Sample
    """
    rows, cols = (check_integer("shape", n, 2, 1 << 14) for n in shape)
    count = check_integer("count", count, 0, 10000)
    radius = check_positive("radius", radius, "m")
    base = rough_surface((rows, cols), pixel_size, rms, 4 * pixel_size, seed)
    rng = np.random.default_rng(seed + 1)
    y, x = np.mgrid[0:rows, 0:cols] * base.pixel_size
    h = base.heights.copy()
    for cy, cx in zip(rng.uniform(0, rows * base.pixel_size, count),
                      rng.uniform(0, cols * base.pixel_size, count)):
        rho2 = (x - cx) ** 2 + (y - cy) ** 2
        cap = np.where(rho2 < radius ** 2, radius + np.sqrt(np.maximum(radius ** 2 - rho2, 0)), 0)
        h = np.maximum(h, cap)
    return Sample(h, base.pixel_size, "particles on a rough substrate")


#: Line profiles offered by the controller panel, by name.
PROFILES = ("step", "grating", "real line")


def profile(name: str, pixels: int = 512, pixel_size: float = 4e-9,
            height: float = 50e-9) -> Sample:
    """A named line profile: ``"step"``, ``"grating"`` or ``"real line"`` (a row of
    :func:`particles`, a synthetic but realistic image), scaled to a feature ``height``.

    Parameters
    ----------
    name : str
        One of :data:`PROFILES`.
    pixels : int
        Number of pixels.
    pixel_size : float
        Pixel size in m.
    height : float
        Feature height in m (step height, grating depth, particle diameter).

    Returns
    -------
    Sample
    """
    check_choice("name", name, PROFILES)
    if name == "step":
        return step(pixels, pixel_size, height)
    if name == "grating":
        return grating(pixels, pixel_size, pixels * pixel_size / 4, height)
    img = particles((64, pixels), pixel_size, count=max(4, pixels // 16), radius=height / 2,
                    rms=height / 50, seed=3)
    rows = img.heights.max(axis=1)
    return Sample(img.heights[int(np.argmax(rows))], pixel_size, "real-like line")
