"""Synthetic samples: a step, a grating, a Gaussian rough surface, particles on a substrate.

Each returns a :class:`~afmsmiler.samples.sample.Sample` in SI units. Random surfaces take a
``seed`` and are reproducible; every size is bounded (:data:`~.sample.MAX_PIXELS`) so that each
accepted call finishes within seconds.
"""
from __future__ import annotations

import math

import numpy as np

from ..validation import check_finite, check_integer, check_positive, check_range
from .sample import MAX_LINE_PIXELS, Sample, check_shape

__all__ = ["step", "grating", "rough_surface", "particles", "MAX_HEIGHT",
           "MAX_PARTICLE_WORK"]

#: The largest height of a synthetic sample in m (an AFM's z range is at most about 100 um).
MAX_HEIGHT = 1e-3
#: The most pixels that :func:`particles` may paint in all (count x pixels under one particle).
MAX_PARTICLE_WORK = 1 << 26


def _n(pixels):
    return check_integer("pixels", pixels, 2, MAX_LINE_PIXELS)


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
        Grating period in m, at least two pixels, ``2 * pixel_size`` (a shorter one would alias).
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
    # a period under two pixels would alias into a different, longer one (Nyquist); the message
    # names pixel_size too, since either may be the one the caller got wrong
    try:
        period = check_range("period", period, 2 * pixel_size, np.inf, "m")
    except ValueError as exc:
        raise ValueError(f"{exc} (at least two pixels, 2 * pixel_size, with pixel_size = "
                         f"{pixel_size:g} m)") from None
    height = check_finite("height", height, "m")
    duty = check_range("duty", duty, 0, 1, low_inclusive=False, high_inclusive=False)
    phase = np.mod(np.arange(n) * pixel_size / period, 1.0)
    return Sample(np.where(phase < duty, height, 0.0), pixel_size, "grating")


def _gaussian_field(shape, pixel_size, correlation_length, rng):
    """A periodic Gaussian random field of zero mean and unit standard deviation whose
    autocorrelation is exp(-r^2 / correlation_length^2).

    White noise filtered in Fourier space by the square root of that autocorrelation's power
    spectrum, exp(-(pi correlation_length k)^2 / 2) (the Fourier transform of exp(-r^2 / T^2)
    is pi T^2 exp(-(pi T k)^2) in 2-D, sqrt(pi) T exp(-(pi T k)^2) in 1-D); the mean (k = 0) is
    dropped, so the heights are relative to the mean plane.
    """
    noise = rng.standard_normal(shape)
    # in cycles per pixel and pixels, so that no tiny or huge pixel size overflows
    freqs = [np.fft.fftfreq(n) for n in shape[:-1]]
    freqs.append(np.fft.rfftfreq(shape[-1]))
    k2 = sum(np.meshgrid(*[f ** 2 for f in freqs], indexing="ij", sparse=True))
    spectrum = np.exp(-0.5 * (np.pi * correlation_length / pixel_size) ** 2 * k2)
    spectrum.flat[0] = 0.0
    axes = tuple(range(len(shape)))
    field = np.fft.irfftn(np.fft.rfftn(noise, axes=axes) * spectrum, s=shape, axes=axes)
    return field / field.std()


def rough_surface(shape=(256, 256), pixel_size: float = 4e-9, rms: float = 2e-9,
                  correlation_length: float = 20e-9, seed: int = 0) -> Sample:
    """A Gaussian random rough surface of given RMS height and correlation length.

    Heights with a Gaussian autocorrelation function G(r) = rms^2 exp(-r^2 / T^2), T the
    correlation length (the definition of Gwyddion's statistical functions and of ISO 25178's
    Gaussian surfaces), made by filtering white noise in Fourier space (Garcia and Stoll, Phys.
    Rev. Lett. 52, 1798 (1984)), relative to their mean and scaled to exactly ``rms``.

    Parameters
    ----------
    shape : int or tuple of int
        Pixels of a line (int) or (rows, columns) of an image (see
        :func:`~afmsmiler.samples.sample.check_shape`).
    pixel_size : float
        Pixel size in m.
    rms : float
        RMS roughness in m, 0 to :data:`MAX_HEIGHT`.
    correlation_length : float
        Lateral correlation length T in m (> 0), at most a quarter of the longest side
        (``max(shape) * pixel_size / 4``).
    seed : int
        Seed of the random generator.

    Returns
    -------
    Sample

    Raises
    ------
    ValueError
        If a parameter is out of range, in particular a correlation length longer than a
        quarter of the image.

    Notes
    -----
    The surface is synthesised periodic over its own length P (an FFT), so its autocorrelation
    is the periodic sum of exp(-(r - m P)^2 / T^2): it is the asked Gaussian only while its
    neighbours are negligible, exp(-(P - T)^2 / T^2) < 1.3e-4 for T <= P / 4. Beyond that the
    image cannot show a correlation length: for T >~ P the spectrum has no power left at the
    image's lowest frequency, and the old code returned noise at the level of rounding, scaled
    into a flat surface at -4.6e6 m. A correlation length longer than the image is physically a
    tilt and a bow, which AFM images have levelled away; use a larger image (or smaller pixels).
    """
    shape = check_shape(shape)
    pixel_size = check_positive("pixel_size", pixel_size, "m")
    rms = check_range("rms", rms, 0, MAX_HEIGHT, "m")
    longest = max(shape) * pixel_size
    try:
        correlation_length = check_range("correlation_length", correlation_length, 0,
                                         longest / 4, "m", low_inclusive=False)
    except ValueError as exc:  # name all three: any of them may be the one that is off
        raise ValueError(f"{exc} (at most a quarter of the image, max(shape) * pixel_size / 4, "
                         f"with shape = {shape} and pixel_size = {pixel_size:g} m)") from None
    rng = np.random.default_rng(check_integer("seed", seed, 0))
    return Sample(rms * _gaussian_field(shape, pixel_size, correlation_length, rng), pixel_size,
                  "rough surface")


def particles(shape=(256, 256), pixel_size: float = 4e-9, count: int = 30,
              radius: float = 25e-9, rms: float = 1e-9, seed: int = 1) -> Sample:
    """A "real-like" image: spherical particles (e.g. nanoparticles) on a rough substrate.

    Each particle of radius r lies on the substrate's mean plane and shows as its upper half,
    r + sqrt(r^2 - rho^2) within rho < r of its centre (its top at 2 r, as an AFM with an ideal
    tip would see it); overlapping particles take the highest one. The substrate is a
    :func:`rough_surface` of correlation length 4 pixels (less on a very small image).

    Parameters
    ----------
    shape : tuple of int
        (rows, columns), at most :data:`~afmsmiler.samples.sample.MAX_PIXELS` pixels.
    pixel_size : float
        Pixel size in m.
    count : int
        Number of particles, 0 to 10000.
    radius : float
        Particle radius in m, in (0, ``MAX_HEIGHT / 2``]: a particle's top is at 2 r, and every
        synthetic height is at most :data:`MAX_HEIGHT` (an AFM's z range).
    rms : float
        RMS roughness of the substrate in m.
    seed : int
        Seed of the random generator.

    Returns
    -------
    Sample

    Raises
    ------
    ValueError
        If a parameter is out of range, or the particles would cover more than
        :data:`MAX_PARTICLE_WORK` pixels in all (``count`` x the pixels of one particle's
        square, each clipped to the image): painting them would take more than seconds.
    """
    shape = check_shape(shape)
    if len(shape) != 2:
        raise ValueError(f"shape must be a pair (rows, columns), got {shape!r}")
    rows, cols = shape
    pixel_size = check_positive("pixel_size", pixel_size, "m")
    count = check_integer("count", count, 0, 10000)
    # a particle's top is at 2 r: at most MAX_HEIGHT, an AFM's z range, like every height here
    radius = check_range("radius", radius, 0, MAX_HEIGHT / 2, "m", low_inclusive=False)
    # a particle's square: (2 half + 1)^2 pixels, clipped to the image (no overflow to int for a
    # radius of very many pixels)
    half = int(math.ceil(min(radius / pixel_size, max(rows, cols))))
    work = count * min(2 * half + 1, rows) * min(2 * half + 1, cols)
    if work > MAX_PARTICLE_WORK:
        raise ValueError(f"count and radius must cover at most {MAX_PARTICLE_WORK} pixels in "
                         f"all, got count={count} particles of radius {radius:g} m = {half} "
                         f"pixels: {work} pixels")
    correlation = min(4.0, max(rows, cols) / 4) * pixel_size
    base = rough_surface((rows, cols), pixel_size, rms, correlation, seed)
    rng = np.random.default_rng(seed + 1)
    h = base.heights.copy()
    r2 = radius ** 2
    for cy, cx in zip(rng.uniform(0, rows * pixel_size, count),
                      rng.uniform(0, cols * pixel_size, count)):
        # only the pixels of the particle's square: the same heights, count x fewer pixels
        i0, i1 = max(int(cy / pixel_size) - half, 0), min(int(cy / pixel_size) + half + 2, rows)
        j0, j1 = max(int(cx / pixel_size) - half, 0), min(int(cx / pixel_size) + half + 2, cols)
        if i0 >= i1 or j0 >= j1:
            continue
        y = (np.arange(i0, i1) * pixel_size - cy)[:, None]
        x = (np.arange(j0, j1) * pixel_size - cx)[None, :]
        rho2 = x * x + y * y
        cap = np.where(rho2 < r2, radius + np.sqrt(np.maximum(r2 - rho2, 0.0)), -np.inf)
        np.maximum(h[i0:i1, j0:j1], cap, out=h[i0:i1, j0:j1])
    return Sample(h, pixel_size, "particles on a rough substrate")
