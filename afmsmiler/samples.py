"""Sample topographies with their physical pixel size: steps, gratings, rough and particle
surfaces, and real AFM images read from files.

Every generator returns a :class:`Sample`, which carries the heights (m) together with the pixel
size (m), so that a scan or a plot never has to guess its units. Lines are 1-D samples, images
2-D (rows along the slow axis y, columns along the fast scan axis x). Random surfaces take a
``seed`` and are reproducible. :func:`from_file` reads a real image (WSxM ``.top``/``.stp``) in
SI units; :data:`REAL_IMAGE` is one that ships with the package (DNA on mica, 500 nm).
"""
from __future__ import annotations

import re
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from . import data
from .validation import check_array, check_choice, check_finite, check_integer, check_positive, \
    check_range

__all__ = ["Sample", "step", "grating", "rough_surface", "particles", "PROFILES", "profile",
           "REAL_LINE_ROW", "from_file", "REAL_IMAGE", "real_image"]

#: A real AFM image shipped with the package (see ``afmsmiler/data/README.md``).
REAL_IMAGE = data.path("wsxm_sample_0.top")


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
        A short description.
    pixel_size_y : float, optional
        Distance between neighbouring rows in m, if the pixels are not square; default
        ``pixel_size``.
    """

    heights: np.ndarray
    pixel_size: float
    name: str = ""
    pixel_size_y: float | None = None

    def __post_init__(self):
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
PROFILES = ("step", "grating", "real line", "particles")
#: The row of :func:`real_image` that ``profile("real line")`` takes (two molecules crossed).
REAL_LINE_ROW = 202


def profile(name: str, pixels: int = 512, pixel_size: float = 4e-9,
            height: float = 50e-9) -> Sample:
    """A named line profile, scaled to a feature ``height``.

    ``"step"`` and ``"grating"`` (4 periods) are ideal; ``"real line"`` is a row of the real AFM
    image :func:`real_image` (row :data:`REAL_LINE_ROW`, two molecules and the substrate's
    noise), its first ``pixels`` pixels put on the requested pixel size and its range scaled
    to ``height``: the shape of a real line at the scale of the other profiles (for the
    line at its own scale, 0.98 nm pixels and 2 nm high, use ``real_image().line(202)``);
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


# --- real images from files ----------------------------------------------------------------
#: Length units that image headers use, in m.
_LENGTH_UNITS = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "\u00b5m": 1e-6, "\u03bcm": 1e-6, "nm": 1e-9,
                 "\u00c5": 1e-10, "A": 1e-10, "pm": 1e-12}
_WSXM_TYPES = {"short": "<i2", "double": "<f8"}


def _wsxm_length(header: dict, key: str, path) -> float:
    """A header value such as '500 nm' or '59.7449 nm', in m."""
    if key not in header:
        raise ValueError(f"{path}: WSxM header has no {key!r}")
    match = re.fullmatch(r"\s*([-+0-9.eE]+)\s*(\S+)\s*", header[key])
    if match is None or match.group(2) not in _LENGTH_UNITS:
        raise ValueError(f"{path}: {key} must be a length (units {sorted(_LENGTH_UNITS)}), "
                         f"got {header[key]!r}")
    return float(match.group(1)) * _LENGTH_UNITS[match.group(2)]


def _read_wsxm(path: Path) -> Sample:
    """WSxM image (``.top``, ``.stp``): text header, then rows x columns little-endian values.

    Scales as Gwyddion's ``wsxmfile.c`` module does: the image spans ``X Amplitude`` by
    ``Y Amplitude`` (pixel size = amplitude / number of columns or rows) and its values are
    scaled so that their range is ``Z Amplitude``.
    """
    raw = path.read_bytes()
    match = re.search(rb"Image header size: (\d+)", raw[:200])
    if not raw.startswith(b"WSxM file copyright") or match is None:
        raise ValueError(f"{path} is not a WSxM image (no 'WSxM file copyright' and "
                         f"'Image header size' at its start)")
    size = int(match.group(1))
    header = {}
    for line in raw[:size].decode("latin-1").splitlines():
        key, sep, value = line.strip().partition(": ")
        if sep:
            header[key] = value.strip()
    rows = int(header.get("Number of rows", 0))
    cols = int(header.get("Number of columns", 0))
    dtype = _WSXM_TYPES.get(header.get("Image Data Type", "short"))
    if dtype is None:
        raise ValueError(f"{path}: Image Data Type must be one of {sorted(_WSXM_TYPES)}, "
                         f"got {header['Image Data Type']!r}")
    count = rows * cols
    if count < 4 or len(raw) < size + count * np.dtype(dtype).itemsize:
        raise ValueError(f"{path}: {rows} x {cols} values do not fit in the file")
    data = np.frombuffer(raw, dtype, count, offset=size).reshape(rows, cols).astype(float)
    z_range = _wsxm_length(header, "Z Amplitude", path)
    span = float(np.ptp(data))
    heights = data * (z_range / span) if span > 0 else data * 0.0
    name = header.get("Acquisition channel", "image")
    return Sample(heights, _wsxm_length(header, "X Amplitude", path) / cols,
                  f"{path.name} ({name})", _wsxm_length(header, "Y Amplitude", path) / rows)


_READERS = {".top": _read_wsxm, ".stp": _read_wsxm}


def from_file(path) -> Sample:
    """Read a real AFM height image, in SI units (heights and pixel sizes in m).

    Parameters
    ----------
    path : str or pathlib.Path
        A WSxM image file (``.top`` topography, ``.stp``), as written by Nanotec's WSxM and
        Dulcinea/Cervantes instruments.

    Returns
    -------
    Sample
        The image as stored (rows in file order, no levelling: see :meth:`Sample.level_rows`),
        with ``pixel_size`` along the rows (fast axis) and ``pixel_size_y`` between them.

    Raises
    ------
    ValueError
        If the file does not exist, its format is not supported, or its header lacks the scan
        size, the height range or their units (a height image must be in length units).

    Notes
    -----
    Scaled like Gwyddion's WSxM module: pixel size = ``X Amplitude`` / columns and heights
    spanning ``Z Amplitude`` (with its unit: nm, um, Angstrom, ...). A common unit error is to
    keep only the integer part of ``Z Amplitude`` or to assume nm; the tests compare with the
    independent count-to-volt-to-nm conversion of the same header.
    """
    p = Path(path)
    reader = _READERS.get(p.suffix.lower())
    if reader is None:
        raise ValueError(f"path must name a file of type {sorted(_READERS)}, got {str(path)!r}")
    if not p.is_file():
        raise ValueError(f"path must name an existing file, got {str(path)!r}")
    return reader(p)


def real_image() -> Sample:
    """The real AFM image shipped with the package, rows levelled (see :data:`REAL_IMAGE`).

    Plasmid DNA minicircles on mica, 512 x 512 pixels over 500 nm x 500 nm, heights of about
    2 nm (``afmsmiler/data/README.md`` gives its origin and licence).

    Returns
    -------
    Sample
    """
    return from_file(REAL_IMAGE).level_rows()
