"""Synthetic samples: a step, a grating, a Gaussian rough surface, particles on a substrate.

Each returns a :class:`~afmsmiler.samples.sample.Sample` in SI units. Random surfaces take a
``seed`` and are reproducible; every size is bounded (:data:`~.sample.MAX_PIXELS`) so that each
accepted call finishes within seconds.
"""
from __future__ import annotations

import math

import numpy as np

from ..validation import (check_choice, check_finite, check_instance, check_integer,
                          check_positive, check_range)
from .sample import MAX_LINE_PIXELS, Sample, check_shape

__all__ = ["step", "grating", "terraces", "rough_surface", "particles", "fibres", "MAX_HEIGHT",
           "MAX_PARTICLE_WORK", "MAX_FIBRE_POINTS"]

#: The largest height of a synthetic sample in m (an AFM's z range is at most about 100 um).
MAX_HEIGHT = 1e-3
#: The most pixels that :func:`particles` may paint in all (count x pixels under one particle).
MAX_PARTICLE_WORK = 1 << 26
#: The most points of all the chains of :func:`fibres` (a k-d tree of them takes about a second).
MAX_FIBRE_POINTS = 1 << 21


def _n(shape):
    return check_integer("shape", shape, 2, MAX_LINE_PIXELS)


def step(shape: int = 512, pixel_size: float = 4e-9, height: float = 50e-9,
         position: float = 0.5) -> Sample:
    """A line with one step up of ``height`` at ``position`` (fraction of the line).

    Parameters
    ----------
    shape : int
        Pixels of the line (>= 2): a line's shape, named like every generator's.
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
    n = _n(shape)
    pixel_size = check_positive("pixel_size", pixel_size, "m")
    height = check_finite("height", height, "m")
    position = check_range("position", position, 0, 1, low_inclusive=False, high_inclusive=False)
    x = np.arange(n) / (n - 1)
    return Sample(np.where(x >= position, height, 0.0), pixel_size, "step")


def grating(shape=512, pixel_size: float = 4e-9, period: float = 500e-9,
            height: float = 50e-9, duty: float = 0.5, pattern: str = "lines") -> Sample:
    """A rectangular calibration grating: raised lines (or squares) of ``height``.

    As a line (``shape`` an int) or an image (``shape`` = (rows, columns)): ``"lines"`` are
    stripes along y, ``duty * period`` wide, repeating along x every ``period`` (the pitch), like
    a TGZ step grating; ``"squares"`` are square pillars ``duty * period`` wide on a square
    lattice of pitch ``period``, like a TGQ/TGX grating.

    Parameters
    ----------
    shape : int or tuple of int
        Pixels of a line (>= 2) or (rows, columns) of an image.
    pixel_size : float
        Pixel size in m (square pixels).
    period : float
        Grating period (pitch) in m, at least two pixels, ``2 * pixel_size`` (a shorter one
        would alias).
    height : float
        Height of the lines in m.
    duty : float
        Fraction of a period that is raised, in (0, 1).
    pattern : str
        ``"lines"`` or ``"squares"`` (an image only).

    Returns
    -------
    Sample
    """
    given = shape
    if isinstance(shape, (int, np.integer)):
        shape = (_n(shape),)
    else:
        try:
            shape = check_shape(shape)
        except ValueError as exc:
            raise ValueError(f"shape must be an int or a pair (rows, columns): {exc}") from None
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
    check_choice("pattern", pattern, ("lines", "squares"))
    if pattern == "squares" and len(shape) != 2:
        raise ValueError(f"pattern 'squares' needs an image: shape must be (rows, columns), "
                         f"got {given!r}")
    raised = np.mod(np.arange(shape[-1]) * pixel_size / period, 1.0) < duty
    if len(shape) == 2:
        rows = np.mod(np.arange(shape[0]) * pixel_size / period, 1.0) < duty
        raised = (raised[None, :] & rows[:, None] if pattern == "squares"
                  else np.broadcast_to(raised, shape))
    meta = dict(generator="grating", period=period, height=height, duty=duty, pattern=pattern)
    return Sample(np.where(raised, height, 0.0), pixel_size, "grating", metadata=meta)


def terraces(shape=(256, 256), pixel_size: float = 4e-9, step_height: float = 0.3e-9,
             terrace_width: float = 100e-9, direction: float = 0.0, offset: float = 0.0) -> Sample:
    """A vicinal surface: flat terraces separated by straight monatomic steps.

    The height rises by ``step_height`` every ``terrace_width`` along ``direction``:
    h = step_height * floor((x cos(direction) + y sin(direction) + offset) / terrace_width),
    e.g. 0.31 nm steps of a cleaved graphite or mica surface, 0.2-0.3 nm of Si(111), 0.5 nm of
    a GaN c-plane.

    Parameters
    ----------
    shape : int or tuple of int
        Pixels of a line or (rows, columns) of an image.
    pixel_size : float
        Pixel size in m.
    step_height : float
        Height of one step in m (negative: the surface steps down along ``direction``).
    terrace_width : float
        Width of a terrace across the steps in m, at least two pixels.
    direction : float
        Direction in rad (from the x axis towards y) in which the surface steps up.
    offset : float
        Where the first step is, in m along ``direction`` (the steps are at
        ``k * terrace_width - offset``).

    Returns
    -------
    Sample
    """
    shape = check_shape(shape)
    pixel_size = check_positive("pixel_size", pixel_size, "m")
    step_height = check_range("step_height", step_height, -MAX_HEIGHT, MAX_HEIGHT, "m")
    try:
        terrace_width = check_range("terrace_width", terrace_width, 2 * pixel_size, np.inf, "m")
    except ValueError as exc:
        raise ValueError(f"{exc} (at least two pixels, with pixel_size = {pixel_size:g} m)"
                         ) from None
    direction = check_finite("direction", direction, "rad")
    offset = check_finite("offset", offset, "m")
    x = np.arange(shape[-1]) * pixel_size
    y = np.arange(shape[0]) * pixel_size if len(shape) == 2 else np.zeros(1)
    u = x[None, :] * np.cos(direction) + y[:, None] * np.sin(direction) + offset
    steps = np.floor(u / terrace_width)
    steps -= steps.min()
    if abs(step_height) * steps.max() > MAX_HEIGHT:
        raise ValueError(f"step_height must keep the staircase within {MAX_HEIGHT} m (an AFM's z "
                         f"range), got {step_height:g} m x {int(steps.max())} steps")
    h = step_height * steps
    meta = dict(generator="terraces", step_height=step_height, terrace_width=terrace_width,
                direction=direction)
    return Sample(h if len(shape) == 2 else h[0], pixel_size, "terraces", metadata=meta)


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


def _stretched_field(shape, pixel_size, correlation_length, hurst, rng):
    """A periodic Gaussian random field of unit standard deviation whose autocorrelation is
    exp(-(r / T)^(2 H)): white noise filtered by the square root of that function's discrete
    power spectrum (its FFT on the periodic grid, minimum-image distances; the few negative
    rounding values clipped to 0)."""
    axes = [np.minimum(np.arange(n), n - np.arange(n)) for n in shape]
    r2 = sum(np.meshgrid(*[a.astype(float) ** 2 for a in axes], indexing="ij", sparse=True))
    t = correlation_length / pixel_size
    acf = np.exp(-(r2 / (t * t)) ** hurst)
    psd = np.maximum(np.fft.rfftn(acf).real, 0.0)
    psd.flat[0] = 0.0
    noise = rng.standard_normal(shape)
    dims = tuple(range(len(shape)))
    field = np.fft.irfftn(np.fft.rfftn(noise, axes=dims) * np.sqrt(psd), s=shape, axes=dims)
    return field / field.std()


def rough_surface(shape=(256, 256), pixel_size: float = 4e-9, rms: float = 2e-9,
                  correlation_length: float = 20e-9, hurst: float = 1.0,
                  seed: int = 0) -> Sample:
    """A self-affine random rough surface of given RMS height, correlation length and Hurst
    exponent.

    Heights with the autocorrelation function G(r) = rms^2 exp(-(r / T)^(2 H)), T the
    correlation length (where G falls to 1/e of rms^2) and H the Hurst exponent (Sinha et al.,
    Phys. Rev. B 38, 2297 (1988); Palasantzas, Phys. Rev. B 48, 14472 (1993)): the
    height-height correlation 2 rms^2 (1 - exp(-(r / T)^(2 H))) grows as r^(2 H) below T and
    saturates at 2 rms^2 beyond it. H = 1 is the Gaussian surface of Gwyddion's statistical
    functions and ISO 25178, made by filtering white noise with the analytic spectrum (Garcia
    and Stoll, Phys. Rev. Lett. 52, 1798 (1984)); H < 1 filters it with the discrete spectrum of
    G. The heights are relative to their mean and scaled to exactly ``rms``.

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
    hurst : float
        Hurst exponent H in [0.1, 1] (1: smooth Gaussian surface; 0.5: Brownian-like; lower:
        rougher at short range).
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
    hurst = check_range("hurst", hurst, 0.1, 1.0)
    rng = np.random.default_rng(check_integer("seed", seed, 0))
    if hurst == 1.0:
        field = _gaussian_field(shape, pixel_size, correlation_length, rng)
    else:
        field = _stretched_field(shape, pixel_size, correlation_length, hurst, rng)
    meta = dict(generator="rough_surface", rms=rms, correlation_length=correlation_length,
                hurst=hurst, seed=seed)
    return Sample(rms * field, pixel_size, "rough surface", metadata=meta)


def _paint(h, pixel_size, centres, radii, profile):
    """Put ``profile(rho2, r)`` (height, -inf outside) at each centre (y, x in m), the highest
    surface winning; only the pixels of each feature's square are computed."""
    rows, cols = h.shape
    for (cy, cx), r in zip(centres, radii):
        half = int(math.ceil(min(r / pixel_size, max(rows, cols))))
        i0, i1 = max(int(cy / pixel_size) - half, 0), min(int(cy / pixel_size) + half + 2, rows)
        j0, j1 = max(int(cx / pixel_size) - half, 0), min(int(cx / pixel_size) + half + 2, cols)
        if i0 >= i1 or j0 >= j1:
            continue
        y = (np.arange(i0, i1) * pixel_size - cy)[:, None]
        x = (np.arange(j0, j1) * pixel_size - cx)[None, :]
        np.maximum(h[i0:i1, j0:j1], profile(x * x + y * y, r), out=h[i0:i1, j0:j1])


def _sphere(rho2, r):
    return np.where(rho2 < r * r, r + np.sqrt(np.maximum(r * r - rho2, 0.0)), -np.inf)


def particles(shape=(256, 256), pixel_size: float = 4e-9, count: int = 30,
              radius: float = 25e-9, rms: float = 1e-9, seed: int = 1, *,
              coverage: float | None = None, spread: float = 0.0,
              overlap: bool = True) -> Sample:
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
        Number of particles, 0 to 10000 (ignored when ``coverage`` is given).
    radius : float
        Particle radius in m (the mean radius with a ``spread``), in (0, ``MAX_HEIGHT / 2``]:
        a particle's top is at 2 r, and every synthetic height is at most :data:`MAX_HEIGHT`
        (an AFM's z range).
    rms : float
        RMS roughness of the substrate in m.
    seed : int
        Seed of the random generator.
    coverage : float, optional
        Fraction of the image's area that the particles' discs cover, in (0, 0.5] (equal discs
        placed at random without overlap jam at 0.547: Feder, J. Theor. Biol. 87, 237 (1980));
        sets ``count`` = round(coverage * area / (pi radius^2)).
    spread : float
        Relative standard deviation of the radii, in [0, 1): log-normal radii of mean
        ``radius`` (0: all equal).
    overlap : bool
        If False, particles are placed one by one at random positions that overlap no earlier
        particle (random sequential adsorption), with at most 200 tries per particle.

    Returns
    -------
    Sample
        Its ``metadata`` holds the ``centres`` (y, x in m) and ``radii`` (m).

    Raises
    ------
    ValueError
        If a parameter is out of range, the particles would cover more than
        :data:`MAX_PARTICLE_WORK` pixels in all (``count`` x the pixels of one particle's
        square, each clipped to the image: painting them would take more than seconds), or
        non-overlapping particles do not fit.
    """
    shape = check_shape(shape)
    if len(shape) != 2:
        raise ValueError(f"shape must be a pair (rows, columns), got {shape!r}")
    rows, cols = shape
    pixel_size = check_positive("pixel_size", pixel_size, "m")
    seed = check_integer("seed", seed, 0)
    # a particle's top is at 2 r: at most MAX_HEIGHT, an AFM's z range, like every height here
    radius = check_range("radius", radius, 0, MAX_HEIGHT / 2, "m", low_inclusive=False)
    spread = check_range("spread", spread, 0, 1, high_inclusive=False)
    check_instance("overlap", overlap, bool)
    if coverage is not None:
        coverage = check_range("coverage", coverage, 0, 0.5, low_inclusive=False)
        count = int(round(coverage * rows * cols * pixel_size ** 2 / (math.pi * radius ** 2)))
        if count > 10000:
            raise ValueError(f"coverage must give at most 10000 particles of radius "
                             f"{radius:g} m, got {coverage:g}: {count} particles")
    count = check_integer("count", count, 0, 10000)
    rng = np.random.default_rng(seed + 1)
    if spread > 0:
        sigma = math.sqrt(math.log1p(spread ** 2))
        radii = np.minimum(radius * np.exp(sigma * rng.standard_normal(count) - sigma ** 2 / 2),
                           MAX_HEIGHT / 2)
    else:
        radii = np.full(count, radius)
    # a particle's square: (2 half + 1)^2 pixels, clipped to the image (no overflow to int for a
    # radius of very many pixels)
    half = np.ceil(np.minimum(radii / pixel_size, max(rows, cols)))
    work = int(np.sum(np.minimum(2 * half + 1, rows) * np.minimum(2 * half + 1, cols)))
    if work > MAX_PARTICLE_WORK:
        raise ValueError(f"count and radius must cover at most {MAX_PARTICLE_WORK} pixels in "
                         f"all, got count={count} particles of radius {radius:g} m = "
                         f"{int(half.max()) if count else 0} pixels: {work} pixels")
    correlation = min(4.0, max(rows, cols) / 4) * pixel_size
    base = rough_surface((rows, cols), pixel_size, rms, correlation, seed=seed)
    if overlap:
        centres = np.column_stack((rng.uniform(0, rows * pixel_size, count),
                                   rng.uniform(0, cols * pixel_size, count)))
    else:
        centres = np.empty((count, 2))
        for i in range(count):
            for _ in range(200):
                c = rng.uniform((0, 0), (rows * pixel_size, cols * pixel_size))
                if np.all(np.hypot(*(centres[:i] - c).T) >= radii[:i] + radii[i]):
                    break
            else:
                raise ValueError(f"count (or coverage) must let {count} non-overlapping "
                                 f"particles fit: only {i} of radius ~{radius:g} m were placed "
                                 f"in 200 tries each")
            centres[i] = c
    h = base.heights.copy()
    _paint(h, pixel_size, centres, radii, _sphere)
    meta = dict(generator="particles", centres=centres, radii=radii, count=count)
    return Sample(h, pixel_size, "particles on a rough substrate", metadata=meta)


def fibres(shape=(256, 256), pixel_size: float = 2e-9, count: int = 5,
           contour_length: float = 300e-9, persistence_length: float = 50e-9,
           width: float = 6e-9, height: float = 1.0e-9, rms: float = 0.1e-9,
           seed: int = 2) -> Sample:
    """Fibres or strands (DNA-like) lying on a flat rough substrate: 2-D worm-like chains.

    Each fibre is a worm-like chain in the plane (Kratky-Porod): its direction turns by a
    Gaussian angle of variance ds / P over each length ds, so that the tangents' correlation
    along the chain is <cos theta(s)> = exp(-s / (2 P)) (the 2-D form, Rivetti et al., J. Mol.
    Biol. 264, 919 (1996), which AFM studies of DNA on mica use; P = 50 nm for double-stranded
    DNA). Its cross-section is a half ellipse, ``height`` high and ``width`` wide (DNA on mica
    images about 0.5-2 nm high and, broadened by the tip, 5-15 nm wide).

    Parameters
    ----------
    shape : tuple of int
        (rows, columns).
    pixel_size : float
        Pixel size in m.
    count : int
        Number of fibres, 0 to 1000.
    contour_length : float
        Length of each fibre in m, up to 100 x the image's longer side.
    persistence_length : float
        Persistence length P in m (> 0).
    width : float
        Width of a fibre in m (> 0).
    height : float
        Height of a fibre in m, in (0, ``MAX_HEIGHT``].
    rms : float
        RMS roughness of the substrate in m.
    seed : int
        Seed of the random generator.

    Returns
    -------
    Sample
        Its ``metadata`` holds each fibre's ``paths`` (arrays of (x, y) in m, one point per
        ``step`` along the chain).

    Raises
    ------
    ValueError
        If a parameter is out of range or the chains would have more than
        :data:`MAX_FIBRE_POINTS` points.
    """
    shape = check_shape(shape)
    if len(shape) != 2:
        raise ValueError(f"shape must be a pair (rows, columns), got {shape!r}")
    rows, cols = shape
    pixel_size = check_positive("pixel_size", pixel_size, "m")
    count = check_integer("count", count, 0, 1000)
    seed = check_integer("seed", seed, 0)
    longest = max(rows, cols) * pixel_size
    try:
        contour_length = check_range("contour_length", contour_length, 0, 100 * longest, "m",
                                     low_inclusive=False)
    except ValueError as exc:
        raise ValueError(f"{exc} (at most 100 x the image's longer side, with shape = {shape} "
                         f"and pixel_size = {pixel_size:g} m)") from None
    persistence_length = check_positive("persistence_length", persistence_length, "m")
    width = check_range("width", width, 0, longest, "m", low_inclusive=False)
    height = check_range("height", height, 0, MAX_HEIGHT, "m", low_inclusive=False)
    # points a quarter pixel (or less: P / 20, width / 4) apart trace a smooth tube
    step = min(pixel_size / 4, persistence_length / 20, width / 4)
    n = int(math.ceil(contour_length / step)) + 1
    if count * n > MAX_FIBRE_POINTS:
        raise ValueError(f"count and contour_length must give at most {MAX_FIBRE_POINTS} chain "
                         f"points, got count={count} fibres of {contour_length:g} m: "
                         f"{count * n} points {step:g} m apart (the smallest of pixel_size / 4, "
                         f"persistence_length / 20 and width / 4, with pixel_size = "
                         f"{pixel_size:g} m, persistence_length = {persistence_length:g} m, "
                         f"width = {width:g} m)")
    step = contour_length / (n - 1)
    correlation = min(4.0, max(rows, cols) / 4) * pixel_size
    h = rough_surface((rows, cols), pixel_size, rms, correlation, seed=seed).heights.copy()
    rng = np.random.default_rng(seed + 1)
    paths = []
    for _ in range(count):
        start = rng.uniform((0, 0), (cols * pixel_size, rows * pixel_size))
        turns = rng.normal(0, math.sqrt(step / persistence_length), n - 2)
        angles = rng.uniform(0, 2 * np.pi) + np.concatenate(([0.0], np.cumsum(turns)))
        steps = step * np.column_stack((np.cos(angles), np.sin(angles)))
        paths.append(start + np.concatenate(([[0.0, 0.0]], np.cumsum(steps, axis=0))))
    if paths:
        # the tubes' union: a half-ellipse of the distance to the nearest chain point (it falls
        # with the distance, so the highest section is the nearest one's)
        from scipy.spatial import cKDTree
        a = width / 2
        points = np.concatenate(paths)
        tree = cKDTree(points / pixel_size)
        y, x = np.mgrid[0:rows, 0:cols]
        dist, _ = tree.query(np.column_stack((x.ravel(), y.ravel())),
                             distance_upper_bound=a / pixel_size)
        rho = dist.reshape(rows, cols) * pixel_size
        with np.errstate(invalid="ignore"):
            tube = np.where(rho < a, height * np.sqrt(np.maximum(1 - (rho / a) ** 2, 0.0)),
                            -np.inf)
        np.maximum(h, tube, out=h)
    meta = dict(generator="fibres", paths=tuple(paths), step=step,
                persistence_length=persistence_length, contour_length=contour_length,
                width=width, height=height)
    return Sample(h, pixel_size, "fibres on a substrate", metadata=meta)
