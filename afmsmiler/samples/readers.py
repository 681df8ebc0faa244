"""Real AFM images read from files through the field's kept libraries, in SI units.

:func:`load` picks a reader by the file's suffix: AFMReader (the reader behind TopoStats) for
Bruker NanoScope ``.spm`` (through its pySPM backend), Asylum/Igor ``.ibw``, JPK ``.jpk``, high
speed ``.asd`` and WSxM ``.top``/``.stp``; gwyfile for Gwyddion ``.gwy``; NumPy for ``.npy`` and
text height maps (``.txt``, ``.csv``, ``.asc``), whose pixel size the caller states.
:func:`channels` lists a file's channels, :func:`save_gwy` writes a sample to a ``.gwy`` file that
Gwyddion, gwyfile and AFMReader read back with its pixel size and units.

Before a library reads a byte of data, a pre-flight check reads the file's first bytes and
compares the image that the header announces with the file's size: a missing, empty, truncated,
corrupt or hostile file is a ValueError naming the file and what is wrong, in milliseconds,
never an attempt to allocate what a corrupt header claims.
"""
from __future__ import annotations

import ast
import os
import re
import struct
from pathlib import Path

import numpy as np

from .. import data
from ..parameters import UNITS
from ..validation import check_instance, check_positive
from .sample import MAX_PIXELS, Sample

__all__ = ["load", "channels", "save_gwy", "from_file", "REAL_IMAGE", "REAL_CHANNEL",
           "real_image", "SUFFIXES", "MAX_FILE_BYTES", "MAX_HEADER_BYTES"]

#: The real AFM image shipped with the package (``afmsmiler/data/README.md``: a Bruker
#: NanoScope file, MIT licence).
REAL_IMAGE = data.path("bruker_d3100.spm")
#: Its height channel.
REAL_CHANNEL = "Height"

#: The longest text header a pre-flight check reads (WSxM and NanoScope headers are a few kB
#: to tens of kB).
MAX_HEADER_BYTES = 1 << 20
#: The largest file :func:`load` opens (a multi-channel instrument file is tens of MB).
MAX_FILE_BYTES = 1 << 30

#: Supported suffixes and what reads them.
SUFFIXES = {".spm": "Bruker NanoScope (AFMReader, pySPM)", ".ibw": "Igor/Asylum (AFMReader)",
            ".jpk": "JPK image (AFMReader)", ".asd": "high-speed AFM movie, first frame "
            "(AFMReader)", ".top": "WSxM topography (AFMReader)", ".stp": "WSxM (AFMReader)",
            ".gwy": "Gwyddion (gwyfile)", ".npy": "NumPy array (pixel_size required)",
            ".txt": "text height map (pixel_size required)", ".csv": "text height map "
            "(pixel_size required)", ".asc": "text height map (pixel_size required)"}

#: The height channel of each format, taken when the default ``"Height"`` is not in a file.
_HEIGHT_CHANNELS = {".ibw": ("HeightTracee", "HeightTrace"), ".jpk": ("height_trace",),
                    ".asd": ("TP",)}
#: Units in which instruments write lengths and other channels: (SI unit, SI value of one).
_FILE_UNITS = {"m": ("m", 1.0), "mm": ("m", 1e-3), "um": ("m", 1e-6), "\u00b5m": ("m", 1e-6),
               "~m": ("m", 1e-6), "nm": ("m", 1e-9), "pm": ("m", 1e-12), "\u00c5": ("m", 1e-10),
               "A": ("m", 1e-10), "V": ("V", 1.0), "mV": ("V", 1e-3), "deg": ("deg", 1.0),
               "\u00ba": ("deg", 1.0), "\u00b0": ("deg", 1.0)}
_WSXM_MAGIC = b"WSxM file copyright"


def _quiet():
    """AFMReader logs every step at INFO to stderr (loguru): silence it for the course."""
    import warnings
    with warnings.catch_warnings():  # pySPM 0.2.23 imports scipy.ndimage.filters (deprecated)
        warnings.simplefilter("ignore", DeprecationWarning)
        import AFMReader.general_loader  # noqa: F401 (every reader: each enables the log)
    from loguru import logger
    logger.disable("AFMReader")


# --- paths and pre-flight checks --------------------------------------------------------------
def _path(path) -> Path:
    try:
        p = Path(os.fspath(path))
    except TypeError:
        raise ValueError(f"path must be a str or os.PathLike, got {path!r}") from None
    suffix = p.suffix.lower()
    if suffix not in SUFFIXES:
        raise ValueError(f"path must name a file of type {sorted(SUFFIXES)}, got {str(path)!r}")
    if not p.is_file():
        raise ValueError(f"path must name an existing file, got {str(path)!r}")
    size = p.stat().st_size
    if size == 0:
        raise ValueError(f"{p}: the file is empty")
    if size > MAX_FILE_BYTES:
        raise ValueError(f"{p}: the file has {size} bytes, more than any AFM image this course "
                         f"reads ({MAX_FILE_BYTES})")
    try:
        with open(p, "rb") as f:
            f.read(1)
    except OSError as exc:
        raise ValueError(f"{p}: the file cannot be read ({exc.strerror or exc})") from None
    return p


def _head(p: Path, n: int) -> bytes:
    with open(p, "rb") as f:
        return f.read(n)


def _wsxm_header(p: Path) -> dict:
    """The WSxM header as a dict, after checking it against the file's size."""
    file_size = p.stat().st_size
    start = _head(p, 200)
    match = re.search(rb"Image header size: (\d+)", start)
    if not start.startswith(_WSXM_MAGIC) or match is None:
        raise ValueError(f"{p} is not a WSxM image (no 'WSxM file copyright' and "
                         f"'Image header size' at its start)")
    size = int(match.group(1))
    if not len(start) <= size <= min(MAX_HEADER_BYTES, file_size):
        raise ValueError(f"{p}: Image header size must be in [{len(start)}, "
                         f"{min(MAX_HEADER_BYTES, file_size)}] bytes, got {size}")
    header = {}
    for line in _head(p, size).decode("latin-1").splitlines():
        key, sep, value = line.strip().partition(": ")
        if sep:
            header[key] = value.strip()
    counts = []
    for key in ("Number of rows", "Number of columns"):
        text = header.get(key, "")
        if not text.isdigit() or not 2 <= int(text) <= MAX_PIXELS // 2:
            raise ValueError(f"{p}: {key} must be an integer in [2, {MAX_PIXELS // 2}], got "
                             f"{text!r}")
        counts.append(int(text))
    rows, cols = counts
    if rows * cols > MAX_PIXELS:
        raise ValueError(f"{p}: the image must have at most {MAX_PIXELS} pixels, its header "
                         f"says {rows} x {cols}")
    kind = header.get("Image Data Type", "short" if p.suffix.lower() == ".top" else "double")
    itemsize = {"short": 2, "double": 8}.get(kind)
    if itemsize is None or (p.suffix.lower() == ".top") != (kind == "short"):
        raise ValueError(f"{p}: Image Data Type must be 'short' in a .top file and 'double' in "
                         f"a .stp file, got {kind!r}")
    need = size + rows * cols * itemsize
    if file_size < need:
        raise ValueError(f"{p}: the header's {rows} x {cols} {kind} values need {need} bytes, "
                         f"the file has {file_size} (truncated?)")
    header["_rows"], header["_cols"], header["_size"] = rows, cols, size
    return header


def _wsxm_length(p, header: dict, key: str) -> float:
    """A header value such as '500 nm' or '59.7449 nm', in m (> 0)."""
    match = re.fullmatch(r"\s*([-+0-9.eE]+)\s*(\S+)\s*", header.get(key, ""))
    unit = _FILE_UNITS.get(match.group(2)) if match else None
    if match is None or unit is None or unit[0] != "m":
        raise ValueError(f"{p}: {key} must be a length (a number and one of nm, um, Angstrom), "
                         f"got {header.get(key)!r}")
    try:
        value = float(match.group(1)) * unit[1]
    except ValueError:
        raise ValueError(f"{p}: {key} must be a number and a length unit, got "
                         f"{header[key]!r}") from None
    if not 0 < value < float("inf"):
        raise ValueError(f"{p}: {key} must be a positive length, got {header[key]!r} (a "
                         f"negative amplitude would mirror the image)")
    return value


def _spm_header(p: Path) -> list[dict]:
    """The images a NanoScope header lists (offset, length, shape), checked against the file."""
    file_size = p.stat().st_size
    head = _head(p, min(file_size, MAX_HEADER_BYTES))
    if not head.startswith(b"\\*File list") and not head.startswith(b"\\*Force file list"):
        raise ValueError(f"{p} is not a Bruker NanoScope file (no '\\*File list' at its start)")
    end = head.find(b"\\*File list end")
    if end < 0:
        raise ValueError(f"{p}: the NanoScope header has no '\\*File list end' within its first "
                         f"{len(head)} bytes (truncated or corrupt)")
    images = []
    for part in head[:end].split(b"\\*Ciao image list")[1:]:
        fields = {}
        for line in part.decode("latin-1").splitlines():
            key, sep, value = line.lstrip("\\").partition(": ")
            if sep:
                fields.setdefault(key.strip(), value.strip())
        try:
            offset, length = int(fields["Data offset"]), int(fields["Data length"])
            bpp = int(fields.get("Bytes/pixel", "2"))
            cols, rows = int(fields["Samps/line"]), int(fields["Number of lines"])
        except (KeyError, ValueError):
            raise ValueError(f"{p}: an image of the NanoScope header lacks its Data offset, "
                             f"Data length, Samps/line or Number of lines") from None
        if not (2 <= rows and 2 <= cols and rows * cols <= MAX_PIXELS and bpp in (2, 4)):
            raise ValueError(f"{p}: an image must have 2 to {MAX_PIXELS} pixels of 2 or 4 bytes, "
                             f"the header says {rows} x {cols} of {bpp} bytes")
        if rows * cols * bpp > length or offset + rows * cols * bpp > file_size:
            raise ValueError(f"{p}: the header's {rows} x {cols} image at byte {offset} needs "
                             f"{offset + rows * cols * bpp} bytes, the file has {file_size} "
                             f"(truncated?)")
        match = re.search(r'"([^"]*)"', fields.get("@2:Image Data", ""))
        images.append(dict(fields, _name=match.group(1) if match else "?"))
    if not images:
        raise ValueError(f"{p}: the NanoScope header lists no image")
    return images


def _gwy_check(p: Path) -> None:
    if _head(p, 4) != b"GWYP":
        raise ValueError(f"{p} is not a Gwyddion file (no 'GWYP' at its start)")


def _ibw_check(p: Path) -> None:
    head = _head(p, 8)
    if len(head) < 8 or struct.unpack("<h", head[:2])[0] not in (1, 2, 3, 5) \
            and struct.unpack(">h", head[:2])[0] not in (1, 2, 3, 5):
        raise ValueError(f"{p} is not an Igor binary wave (its first bytes give no version)")


def _tiff_check(p: Path) -> None:
    """A JPK image is a TIFF file: each page's pixels and strips within the file and the limits
    (tifffile reads the tags only, lazily)."""
    if _head(p, 4) not in (b"II*\x00", b"MM\x00*"):
        raise ValueError(f"{p} is not a JPK image (a TIFF file)")
    import tifffile
    size = p.stat().st_size
    try:
        with tifffile.TiffFile(str(p)) as tif:
            for page in tif.pages:
                pixels = int(np.prod(page.shape, dtype=float))
                ends = [o + c for o, c in zip(page.dataoffsets, page.databytecounts)]
                if pixels > 4 * MAX_PIXELS or (ends and max(ends) > size):
                    raise ValueError(f"{p}: a page of {page.shape} pixels, its data ending at "
                                     f"byte {max(ends, default=0)}: the file has {size} bytes "
                                     f"and an image at most {MAX_PIXELS} pixels (corrupt?)")
    except ValueError:
        raise
    except Exception as exc:
        raise ValueError(f"{p}: not a readable TIFF/JPK file ({type(exc).__name__}: {exc})"
                         ) from None


def _asd_check(p: Path) -> None:
    """The frames that an .asd header announces (AFMReader's own header readers) must fit in
    the file before AFMReader reads them."""
    from AFMReader import asd
    size = p.stat().st_size
    try:
        with open(p, "rb") as f:
            version = asd.read_file_version(f)
            reader = {0: asd.read_header_file_version_0, 1: asd.read_header_file_version_1,
                      2: asd.read_header_file_version_2}.get(version)
            if reader is None:
                raise ValueError(f"{p}: .asd file version must be 0, 1 or 2, got {version}")
            header = reader(f)
            data_start = f.tell()
    except ValueError:
        raise
    except Exception as exc:
        raise ValueError(f"{p}: not a readable .asd file ({type(exc).__name__}: {exc})"
                         ) from None
    frames, nx, ny = header["num_frames"], header["x_pixels"], header["y_pixels"]
    need = data_start + frames * (header["frame_header_length"] + nx * ny * 2)
    if not (frames >= 1 and nx >= 2 and ny >= 2 and nx * ny <= MAX_PIXELS) or need > size:
        raise ValueError(f"{p}: the header's {frames} frames of {nx} x {ny} pixels need {need} "
                         f"bytes, the file has {size} (truncated or corrupt?)")


# --- the readers ------------------------------------------------------------------------------
def _read_wsxm(p: Path, channel: str):
    _quiet()
    from AFMReader import stp, top
    header = _wsxm_header(p)
    name = header.get("Acquisition channel", "Topography")
    _pick(p, channel, [name])
    x_span = _wsxm_length(p, header, "X Amplitude")
    y_span = _wsxm_length(p, header, "Y Amplitude")
    if p.suffix.lower() == ".top":
        z_range = _wsxm_length(p, header, "Z Amplitude")
        # AFMReader 0.0.7 spreads the counts over the integer part of Z Amplitude's number
        # (59 for "59.7449 nm") whatever its unit; Gwyddion's wsxmfile.c spreads them over the
        # whole Z Amplitude: rescale to that
        whole = int(re.match(r"\s*(\d*)", header["Z Amplitude"]).group(1) or 0)
        if whole == 0:
            raise ValueError(f"{p}: AFMReader reads only the integer part of Z Amplitude "
                             f"({header['Z Amplitude']!r} gives 0): not readable")
    try:
        if p.suffix.lower() == ".top":
            heights = top.load_top(p)[0] / whole * z_range
        else:
            heights = stp.load_stp(p)[0] * 1e-9
    except (ValueError, NotImplementedError) as exc:  # e.g. AFMReader reads square scans only
        raise ValueError(f"{p}: AFMReader cannot read it ({exc})") from None
    meta = {k: v for k, v in header.items() if not k.startswith("_")}
    return heights, x_span / header["_cols"], y_span / header["_rows"], name, "m", meta


def _spm_scan(p: Path):
    _quiet()
    import warnings
    with warnings.catch_warnings():  # pySPM 0.2.23 imports scipy.ndimage.filters (deprecated)
        warnings.simplefilter("ignore", DeprecationWarning)
        import pySPM
    images = _spm_header(p)
    scan = pySPM.Bruker(str(p))
    for layer in scan.layers:  # NanoScope 5 headers spell two keys that pySPM needs otherwise
        for old, new in ((b"Scan size", b"Scan Size"), (b"Line direction", b"Line Direction")):
            if old in layer:
                layer.setdefault(new, layer[old])
        layer.setdefault(b"Line Direction", [b"Trace"])
    return scan, images


def _read_spm(p: Path, channel: str):
    scan, images = _spm_scan(p)
    from AFMReader.spm import spm_pixel_to_nm_scaling
    names = [im["_name"] for im in images]
    channel = _pick(p, channel, names)
    image = scan.get_channel(channel)
    # as AFMReader's load_spm: NanoScope stores the lines bottom up
    values = np.flipud(np.asarray(image.pixels, dtype=float))
    px_nm = spm_pixel_to_nm_scaling(p.stem, image)
    size = image.size["real"]
    unit, scale = _FILE_UNITS.get(image.zscale, (None, None))
    if unit is None:
        raise ValueError(f"{p}: channel {channel!r} has values in {image.zscale!r}, not one of "
                         f"{sorted(_FILE_UNITS)}")
    length = _FILE_UNITS.get(size["unit"], ("m", None))[1]
    # in SI from the header's scan size (AFMReader's nm scaling, rounded through nm, otherwise)
    dx = size["x"] * length / values.shape[1] if length else px_nm * 1e-9
    dy = size["y"] * length / values.shape[0] if length else px_nm * 1e-9
    meta = {k: v for k, v in images[names.index(channel)].items() if not k.startswith("_")}
    return values * scale, dx, dy, channel, unit, meta


def _read_gwy(p: Path, channel: str):
    import gwyfile
    from gwyfile.util import get_datafields
    _gwy_check(p)
    try:
        fields = get_datafields(gwyfile.load(str(p)))
    except Exception as exc:  # gwyfile raises struct.error, ValueError, ... on a corrupt file
        raise ValueError(f"{p}: not a readable Gwyddion file ({type(exc).__name__}: {exc})"
                         ) from None
    channel = _pick(p, channel, list(fields))
    field = fields[channel]
    try:
        values = np.array(field.data, dtype=float)
    except ValueError:
        raise ValueError(f"{p}: channel {channel!r} holds fewer values than xres x yres "
                         f"(truncated?)") from None
    xy = field.si_unit_xy.unitstr if field.si_unit_xy else "m"
    z = field.si_unit_z.unitstr if field.si_unit_z else ""
    if xy != "m" or z not in _FILE_UNITS:
        raise ValueError(f"{p}: channel {channel!r} must have lateral unit 'm' and values in "
                         f"one of {sorted(_FILE_UNITS)}, got {xy!r} and {z!r}")
    unit, scale = _FILE_UNITS[z]
    meta = {"xres": field["xres"], "yres": field["yres"], "xreal": field.xreal,
            "yreal": field.yreal, "si_unit_xy": xy, "si_unit_z": z}
    return (values * scale, field.xreal / values.shape[1], field.yreal / values.shape[0],
            channel, unit, meta)


def _afmreader_channels(p: Path) -> list[str]:
    """The channels AFMReader lists when asked for one that no file has."""
    _quiet()
    from AFMReader import asd, jpk
    loader = {".jpk": jpk.load_jpk, ".asd": asd.load_asd}[p.suffix.lower()]
    try:
        loader(p, "\x00 no channel")
    except ValueError as exc:
        match = re.search(r"channel list: (.*)$", str(exc))
        if match:
            listed = ast.literal_eval(match.group(1))
            return list(listed)
        raise ValueError(f"{p}: {exc}") from None
    except Exception as exc:
        raise ValueError(f"{p}: not readable by AFMReader ({type(exc).__name__}: {exc})"
                         ) from None
    return []


def _ibw_channels(p: Path) -> list[str]:
    from igor2 import binarywave
    _ibw_check(p)
    try:
        wave = binarywave.load(str(p))
    except Exception as exc:
        raise ValueError(f"{p}: not a readable Igor binary wave ({type(exc).__name__}: {exc})"
                         ) from None
    return [label.decode() for labels in wave["wave"]["labels"] for label in labels if label]


def _read_afmreader(p: Path, channel: str):
    _quiet()
    from AFMReader import asd, ibw, jpk
    suffix = p.suffix.lower()
    {".ibw": _ibw_check, ".jpk": _tiff_check, ".asd": _asd_check}[suffix](p)
    names = _ibw_channels(p) if suffix == ".ibw" else _afmreader_channels(p)
    channel = _pick(p, channel, names)
    try:
        if suffix == ".ibw":
            nm, px = ibw.load_ibw(p, channel)
        elif suffix == ".jpk":
            nm, px = jpk.load_jpk(p, channel)
        else:
            frames, px, _ = asd.load_asd(p, channel)
            nm = frames[0]
    except ValueError as exc:
        raise ValueError(f"{p}: {exc}") from None
    return np.asarray(nm, dtype=float) * 1e-9, px * 1e-9, px * 1e-9, channel, "m", {}


def _pick(p: Path, channel: str, names: list) -> str:
    """``channel`` if the file has it; the format's height channel for the default "Height"."""
    check_instance("channel", channel, str)
    if channel in names:
        return channel
    if channel == "Height":
        for name in _HEIGHT_CHANNELS.get(p.suffix.lower(), ()) + ("Topography",):
            if name in names:
                return name
        if len(names) == 1 and p.suffix.lower() in (".top", ".stp"):
            return names[0]
    raise ValueError(f"channel must be one of the channels of {p.name}: {names}, got "
                     f"{channel!r}")


_READERS = {".spm": _read_spm, ".gwy": _read_gwy, ".top": _read_wsxm, ".stp": _read_wsxm,
            ".ibw": _read_afmreader, ".jpk": _read_afmreader, ".asd": _read_afmreader}


def _read_array(p: Path, pixel_size, unit: str) -> Sample:
    if pixel_size is None:
        raise ValueError(f"pixel_size must be given (in m) for a {p.suffix} height map, which "
                         f"does not store it: {p}")
    pixel_size = check_positive("pixel_size", pixel_size, "m")
    if unit not in UNITS:
        raise ValueError(f"unit must be one of {sorted(UNITS)} (the unit of the stored values), "
                         f"got {unit!r}")
    si, factor = UNITS[unit]
    if p.suffix.lower() == ".npy":
        try:
            arr = np.load(p, mmap_mode="r", allow_pickle=False)
        except ValueError as exc:
            raise ValueError(f"{p}: not a readable NumPy array ({exc})") from None
        if arr.size > MAX_PIXELS:
            raise ValueError(f"{p}: the array must have at most {MAX_PIXELS} values, got shape "
                             f"{arr.shape}")
        values = np.array(arr, dtype=float)
    else:
        if p.stat().st_size > 64 * MAX_PIXELS:
            raise ValueError(f"{p}: a text height map must be under {64 * MAX_PIXELS} bytes")
        delimiter = "," if p.suffix.lower() == ".csv" else None
        try:
            values = np.loadtxt(p, delimiter=delimiter, ndmin=1)
        except ValueError as exc:
            raise ValueError(f"{p}: not a text height map of numbers ({exc})") from None
    if values.ndim not in (1, 2):
        raise ValueError(f"{p}: a height map must be 1-D or 2-D, got shape {values.shape}")
    _finite(p, values)
    return Sample(values * factor, pixel_size, p.name, channel="height", unit=si)


def _finite(p, values):
    bad = np.count_nonzero(~np.isfinite(values))
    if bad:
        raise ValueError(f"{p}: the image holds {bad} values that are not finite (NaN or inf)")


def load(path, channel: str = "Height", *, pixel_size: float | None = None,
         unit: str = "m") -> Sample:
    """Read one channel of a real AFM image, in SI units.

    Parameters
    ----------
    path : str or os.PathLike
        A file of a type of :data:`SUFFIXES`: ``.spm``, ``.ibw``, ``.jpk``, ``.asd``, ``.top``,
        ``.stp`` (AFMReader), ``.gwy`` (gwyfile), ``.npy`` or a text map (``.txt``, ``.csv``,
        ``.asc``: rows of numbers).
    channel : str
        The channel's name as the file gives it (see :func:`channels`). The default
        ``"Height"`` also takes a format's own height channel where the file has no "Height"
        (``"HeightTracee"`` of ``.ibw``, ``"height_trace"`` of ``.jpk``, ``"TP"`` of ``.asd``,
        the one channel of a WSxM file).
    pixel_size : float, optional
        Pixel size in m of a ``.npy`` or text map (required there; instrument files carry it).
    unit : str
        For instrument files, the SI unit the channel must measure (``"m"`` for heights,
        ``"V"`` for a deflection in volts, ``"deg"`` for a phase); for ``.npy`` and text maps,
        the unit the values are stored in, a key of :data:`~afmsmiler.parameters.UNITS`
        (``"nm"`` converts to m).

    Returns
    -------
    Sample
        Values as stored (no levelling), rows as the reader returns them (as Gwyddion shows
        them, first row at the top), ``pixel_size`` along the rows and ``pixel_size_y``
        between them, the channel's name, SI ``unit`` and the file's ``metadata``.

    Raises
    ------
    ValueError
        Naming the file and what is wrong: not a path, missing, empty, unreadable, of an
        unsupported type, not of the format its suffix says, a header that announces more data
        than the file holds or than :data:`~afmsmiler.samples.sample.MAX_PIXELS` pixels, NaN
        or infinite values, a channel the file does not have (the error lists those it has), a
        channel in another unit than ``unit``, or a missing ``pixel_size`` of a plain map.

    Notes
    -----
    WSxM ``.top`` heights span the header's whole ``Z Amplitude`` with its unit, as Gwyddion's
    ``wsxmfile.c`` reads them (AFMReader 0.0.7 takes the integer part of the number only:
    59 nm for "59.7449 nm", a 1.3 % height error corrected here); NanoScope 5 headers spell
    ``Scan size`` and ``Line direction`` where pySPM looks for ``Scan Size`` and
    ``Line Direction``, and are given both before pySPM reads them.

    Examples
    --------
    >>> s = load(REAL_IMAGE)
    >>> s.shape, s.pixel_size, s.unit
    ((512, 512), 3.90625e-09, 'm')
    """
    check_instance("unit", unit, str)
    p = _path(path)
    if p.suffix.lower() in (".npy", ".txt", ".csv", ".asc"):
        check_instance("channel", channel, str)
        return _read_array(p, pixel_size, unit)
    if pixel_size is not None:
        raise ValueError(f"pixel_size must be None for a {p.suffix} file, which states its "
                         f"own, got {pixel_size!r}")
    values, dx, dy, name, file_unit, meta = _READERS[p.suffix.lower()](p, channel)
    if file_unit != unit:
        raise ValueError(f"unit: channel {name!r} of {p.name} is in {file_unit!r}, not "
                         f"{unit!r} (pass unit={file_unit!r} to read it)")
    values = np.asarray(values, dtype=float)
    if values.ndim != 2 or values.size > MAX_PIXELS:
        raise ValueError(f"{p}: channel {name!r} must be an image of at most {MAX_PIXELS} "
                         f"pixels, got shape {values.shape}")
    _finite(p, values)
    return Sample(values, dx, f"{p.name} ({name})", dy, channel=name, unit=file_unit,
                  metadata=meta)


#: The name this module's reader had before AFMReader read the files: the same function.
from_file = load


def channels(path) -> list[str]:
    """The names of a file's channels, as :func:`load` takes them.

    Parameters
    ----------
    path : str or os.PathLike
        A file of a type of :data:`SUFFIXES`.

    Returns
    -------
    list of str
        ``["height"]`` for a ``.npy`` or text map.

    Raises
    ------
    ValueError
        As :func:`load`, for a file that cannot be read.
    """
    p = _path(path)
    suffix = p.suffix.lower()
    if suffix in (".npy", ".txt", ".csv", ".asc"):
        return ["height"]
    if suffix == ".spm":
        return [im["_name"] for im in _spm_header(p)]
    if suffix in (".top", ".stp"):
        return [_wsxm_header(p).get("Acquisition channel", "Topography")]
    if suffix == ".gwy":
        import gwyfile
        from gwyfile.util import get_datafields
        _gwy_check(p)
        try:
            return list(get_datafields(gwyfile.load(str(p))))
        except Exception as exc:
            raise ValueError(f"{p}: not a readable Gwyddion file ({type(exc).__name__}: "
                             f"{exc})") from None
    if suffix == ".ibw":
        return _ibw_channels(p)
    (_tiff_check if suffix == ".jpk" else _asd_check)(p)
    return _afmreader_channels(p)


def save_gwy(sample: Sample, path) -> Path:
    """Write an image to a Gwyddion ``.gwy`` file with its pixel sizes and units.

    Gwyddion, gwyfile and AFMReader read it back (AFMReader 0.0.7 square images only: it
    reshapes the data as ``(xres, yres)``).

    Parameters
    ----------
    sample : Sample
        A 2-D sample (an image).
    path : str or os.PathLike
        The file to write, ending in ``.gwy``.

    Returns
    -------
    pathlib.Path

    Raises
    ------
    ValueError
        If the sample is a line, the path does not end in ``.gwy`` or its folder is missing.
    """
    from gwyfile.objects import GwyContainer, GwyDataField, GwySIUnit
    check_instance("sample", sample, Sample)
    if sample.heights.ndim != 2:
        raise ValueError(f"sample must be an image (2-D) to write a .gwy file, got shape "
                         f"{sample.heights.shape}")
    try:
        p = Path(os.fspath(path))
    except TypeError:
        raise ValueError(f"path must be a str or os.PathLike, got {path!r}") from None
    if p.suffix.lower() != ".gwy" or not p.parent.is_dir():
        raise ValueError(f"path must end in .gwy in an existing folder, got {str(path)!r}")
    rows, cols = sample.heights.shape
    field = GwyDataField(np.ascontiguousarray(sample.heights, dtype="<f8"),
                         xreal=cols * sample.pixel_size, yreal=rows * sample.pixel_size_y,
                         si_unit_xy=GwySIUnit(unitstr="m"),
                         si_unit_z=GwySIUnit(unitstr=sample.unit))
    container = GwyContainer()
    container["/0/data"] = field
    container["/0/data/title"] = sample.channel or sample.name or "Height"
    container.tofile(str(p))
    return p


def real_image() -> Sample:
    """The real AFM image shipped with the package, rows levelled (see :data:`REAL_IMAGE`).

    A Bruker Dimension 3100 height image, 512 x 512 pixels over 2 um x 2 um: islands and
    terraces a few nm high (``afmsmiler/data/README.md`` gives its origin and licence).

    Returns
    -------
    Sample
    """
    return load(REAL_IMAGE, REAL_CHANNEL).level_rows()
