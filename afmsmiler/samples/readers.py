"""Real AFM images read from files, in SI units (heights and pixel sizes in m).

:func:`from_file` picks a reader by the file's suffix; :data:`REAL_IMAGE` is a real image that
ships with the package and :func:`real_image` reads it. A reader checks the header from the
file's first bytes and the file's size against the image the header announces before it reads
any data, so a wrong or hostile file costs milliseconds, not the memory of its whole length.
"""
from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np

from .. import data
from .sample import MAX_PIXELS, Sample

__all__ = ["from_file", "REAL_IMAGE", "real_image", "MAX_HEADER_BYTES"]

#: A real AFM image shipped with the package (see ``afmsmiler/data/README.md``).
REAL_IMAGE = data.path("wsxm_sample_0.top")

#: The longest text header a reader accepts (WSxM headers are a few kB).
MAX_HEADER_BYTES = 1 << 16

#: Length units that image headers use, in m.
_LENGTH_UNITS = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "\u00b5m": 1e-6, "\u03bcm": 1e-6, "nm": 1e-9,
                 "\u00c5": 1e-10, "A": 1e-10, "pm": 1e-12}
_WSXM_TYPES = {"short": "<i2", "double": "<f8"}
_WSXM_MAGIC = b"WSxM file copyright"


def _wsxm_length(header: dict, key: str, path) -> float:
    """A header value such as '500 nm' or '59.7449 nm', in m."""
    if key not in header:
        raise ValueError(f"{path}: WSxM header has no {key!r}")
    match = re.fullmatch(r"\s*([-+0-9.eE]+)\s*(\S+)\s*", header[key])
    if match is None or match.group(2) not in _LENGTH_UNITS:
        raise ValueError(f"{path}: {key} must be a length (units {sorted(_LENGTH_UNITS)}), "
                         f"got {header[key]!r}")
    try:
        value = float(match.group(1))
    except ValueError:
        raise ValueError(f"{path}: {key} must be a number and a length unit, got "
                         f"{header[key]!r}") from None
    return value * _LENGTH_UNITS[match.group(2)]


def _wsxm_positive(header: dict, key: str, path) -> float:
    value = _wsxm_length(header, key, path)
    if not 0 < value < float("inf"):
        raise ValueError(f"{path}: {key} must be a positive length, got {header[key]!r} (a "
                         f"negative amplitude would mirror the image)")
    return value


def _wsxm_count(header: dict, key: str, path) -> int:
    text = header.get(key, "")
    if not text.isdigit() or not 2 <= int(text) <= MAX_PIXELS // 2:
        raise ValueError(f"{path}: {key} must be an integer in [2, {MAX_PIXELS // 2}], got "
                         f"{text!r}")
    return int(text)


def _read_wsxm(path: Path) -> Sample:
    """WSxM image (``.top``, ``.stp``): text header, then rows x columns little-endian values.

    Scales as Gwyddion's ``wsxmfile.c`` module does: the image spans ``X Amplitude`` by
    ``Y Amplitude`` (pixel size = amplitude / number of columns or rows) and its values are
    scaled so that their range is ``Z Amplitude``.
    """
    file_size = path.stat().st_size
    with open(path, "rb") as f:
        start = f.read(200)
        match = re.search(rb"Image header size: (\d+)", start)
        if not start.startswith(_WSXM_MAGIC) or match is None:
            raise ValueError(f"{path} is not a WSxM image (no 'WSxM file copyright' and "
                             f"'Image header size' at its start)")
        size = int(match.group(1))
        if not len(start) <= size <= min(MAX_HEADER_BYTES, file_size):
            raise ValueError(f"{path}: Image header size must be in [{len(start)}, "
                             f"{min(MAX_HEADER_BYTES, file_size)}] bytes, got {size}")
        raw_header = start + f.read(size - len(start))
        header = {}
        for line in raw_header.decode("latin-1").splitlines():
            key, sep, value = line.strip().partition(": ")
            if sep:
                header[key] = value.strip()
        rows = _wsxm_count(header, "Number of rows", path)
        cols = _wsxm_count(header, "Number of columns", path)
        if rows * cols > MAX_PIXELS:
            raise ValueError(f"{path}: the image must have at most {MAX_PIXELS} pixels, its "
                             f"header says {rows} x {cols}")
        kind = header.get("Image Data Type", "short")
        dtype = _WSXM_TYPES.get(kind)
        if dtype is None:
            raise ValueError(f"{path}: Image Data Type must be one of {sorted(_WSXM_TYPES)}, "
                             f"got {kind!r}")
        z_range = _wsxm_positive(header, "Z Amplitude", path)
        x_span = _wsxm_positive(header, "X Amplitude", path)
        y_span = _wsxm_positive(header, "Y Amplitude", path)
        n_bytes = rows * cols * np.dtype(dtype).itemsize
        if file_size < size + n_bytes:
            raise ValueError(f"{path}: the header's {rows} x {cols} {kind} values need "
                             f"{size + n_bytes} bytes, the file has {file_size}")
        values = np.frombuffer(f.read(n_bytes), dtype).reshape(rows, cols).astype(float)
    if not np.isfinite(values).all():
        raise ValueError(f"{path}: the image holds values that are not finite (NaN or inf)")
    span = float(np.ptp(values))
    heights = values * (z_range / span) if span > 0 else values * 0.0
    name = header.get("Acquisition channel", "image")
    return Sample(heights, x_span / cols, f"{path.name} ({name})", y_span / rows)


_READERS = {".top": _read_wsxm, ".stp": _read_wsxm}


def from_file(path) -> Sample:
    """Read a real AFM height image, in SI units (heights and pixel sizes in m).

    Parameters
    ----------
    path : str or os.PathLike
        A WSxM image file (``.top`` topography, ``.stp``), as written by Nanotec's WSxM and
        Dulcinea/Cervantes instruments.

    Returns
    -------
    Sample
        The image as stored (rows in file order, no levelling: see
        :meth:`~afmsmiler.samples.Sample.level_rows`), with ``pixel_size`` along the rows (fast
        axis) and ``pixel_size_y`` between them.

    Raises
    ------
    ValueError
        If ``path`` is not a path, the file does not exist, its format is not supported, its
        header lacks the scan size, the height range or their units (a height image must be in
        length units), gives a negative or zero amplitude, or announces more data than the file
        holds or than :data:`~afmsmiler.samples.sample.MAX_PIXELS` pixels.

    Notes
    -----
    Scaled like Gwyddion's WSxM module: pixel size = ``X Amplitude`` / columns and heights
    spanning ``Z Amplitude`` (with its unit: nm, um, Angstrom, ...). A common unit error is to
    keep only the integer part of ``Z Amplitude`` or to assume nm; the tests compare with the
    independent count-to-volt-to-nm conversion of the same header.
    """
    try:
        p = Path(os.fspath(path))
    except TypeError:
        raise ValueError(f"path must be a str or os.PathLike, got {path!r}") from None
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
