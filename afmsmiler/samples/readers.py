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

import math
import os
import re
import struct
from pathlib import Path

import numpy as np

from .. import data
from ..parameters import UNITS
from ..validation import check_instance, check_positive
from .sample import MAX_PIXELS, SAMPLE_UNITS, Sample

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
_HEIGHT_CHANNELS = {".ibw": ("HeightTracee", "HeightTrace", "HeightRetrace"),
                    ".jpk": ("height_trace", "height_retrace"), ".asd": ("TP",),
                    ".gwy": ("HeightTrace", "HeightRetrace", "ZSensor")}
#: Asylum .ibw channels by the start of their name (after a "DAC" or "Nap" prefix): their SI
#: unit, as Gwyddion's igorfile.c (channel_title_to_units) gives it; any other channel is in V.
#: The wave itself holds one unit for all its channels.
_IBW_UNITS = {"Height": "m", "ZSensor": "m", "Deflection": "m", "Amplitude": "m",
              "Phase": "deg", "Current": "A", "Frequency": "Hz", "Capacitance": "F",
              "Potential": "V", "Count": "", "QFactor": ""}
#: JPK channels that AFMReader returns in nm (the others in the unit of their page's tags).
_JPK_NM = ("height", "measuredHeight", "amplitude")
#: .asd channels this course reads: topography, which AFMReader returns in nm.
_ASD_UNITS = {"TP": "m"}
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
        # and warns that tqdm is missing: its progress bars are never shown here
        warnings.filterwarnings("ignore", message="the library tqdm cannot be found")
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
    """The images a NanoScope header lists (offset, length, shape), checked against the file.

    The header is read line by line as pySPM reads it (a line ends at ``\\n``; backslashes are
    dropped; ``*Ciao image list`` starts an image, ``*Scanner list`` a scanner; a key's later
    line wins), so that what is checked here is what pySPM then seeks and reads.
    """
    file_size = p.stat().st_size
    head = _head(p, min(file_size, MAX_HEADER_BYTES))
    if not head.startswith(b"\\*File list") and not head.startswith(b"\\*Force file list"):
        raise ValueError(f"{p} is not a Bruker NanoScope file (no '\\*File list' at its start)")
    lines, header_end = [], 0
    for raw in head.split(b"\n")[:-1]:  # the last piece may be a line cut by the read
        header_end += len(raw) + 1
        if raw.rstrip().replace(b"\\", b"") == b"*File list end":
            break
        lines.append(raw.rstrip(b"\r").replace(b"\\", b""))
    else:
        header_end = None
    if header_end is None:  # pySPM would read past the end of the file for ever
        raise ValueError(f"{p}: the NanoScope header has no '\\*File list end' line within its "
                         f"first {len(head)} bytes (truncated or corrupt)")
    images, mode = [], None
    for line in lines:
        if line.rstrip() in (b"*Ciao image list", b"*Scanner list"):
            mode = line.rstrip()
            if mode == b"*Ciao image list":
                images.append({})
            continue
        key, sep, value = line.decode("latin-1").partition(": ")
        if sep and mode == b"*Ciao image list":
            images[-1][key] = value.strip()
    for fields in images:
        try:  # pySPM takes each number up to a further ": "
            offset, length, cols, rows = (int(fields[key].split(": ")[0]) for key in (
                "Data offset", "Data length", "Samps/line", "Number of lines"))
            bpp = int(fields.get("Bytes/pixel", "2"))
        except (KeyError, ValueError):
            raise ValueError(f"{p}: an image of the NanoScope header lacks its Data offset, "
                             f"Data length, Samps/line or Number of lines") from None
        if not (2 <= rows and 2 <= cols and rows * cols <= MAX_PIXELS and bpp in (2, 4)):
            raise ValueError(f"{p}: an image must have 2 to {MAX_PIXELS} pixels of 2 or 4 bytes, "
                             f"the header says {rows} x {cols} of {bpp} bytes")
        if offset < header_end:
            raise ValueError(f"{p}: an image's Data offset must be at or after the header's "
                             f"end (byte {header_end}), got {offset}")
        if length // (rows * cols) != bpp:  # pySPM takes the bytes per pixel from the length
            raise ValueError(f"{p}: an image's Data length must be its {rows} x {cols} pixels of "
                             f"{bpp} bytes ({rows * cols * bpp}), got {length}")
        if offset + rows * cols * bpp > file_size:
            raise ValueError(f"{p}: the header's {rows} x {cols} image at byte {offset} needs "
                             f"{offset + rows * cols * bpp} bytes, the file has {file_size} "
                             f"(truncated?)")
        match = re.search(r'"([^"]*)"', fields.get("@2:Image Data", ""))
        fields["_name"] = match.group(1) if match else "?"
    if not images:
        raise ValueError(f"{p}: the NanoScope header lists no image")
    return images


def _gwy_check(p: Path) -> None:
    if _head(p, 4) != b"GWYP":
        raise ValueError(f"{p} is not a Gwyddion file (no 'GWYP' at its start)")


def _ibw_check(p: Path) -> None:
    """An Igor binary wave's header (version 1, 2, 3 or 5, either byte order) must announce no
    more bytes (wave header and data, note, formula, units, labels) than the file holds."""
    head = _head(p, 64)
    order = next((o for o in "<>" if len(head) >= 8
                  and struct.unpack(o + "h", head[:2])[0] in (1, 2, 3, 5)), None)
    if order is None:
        raise ValueError(f"{p} is not an Igor binary wave (its first bytes give no version)")
    version = struct.unpack(order + "h", head[:2])[0]
    # BinHeader1/2/3/5 of Igor's Technical Note PTN003: the sizes of what follows the header
    layout = {1: (8, "2xi"), 2: (16, "2x3i"), 3: (20, "2x4i"), 5: (64, "4x15i")}[version]
    if len(head) < layout[0]:
        raise ValueError(f"{p}: the Igor header is cut short (truncated?)")
    sizes = struct.unpack(order + layout[1], head[:struct.calcsize(order + layout[1])])
    need = layout[0] + sum(sizes)
    if min(sizes) < 0 or need > p.stat().st_size:
        raise ValueError(f"{p}: the Igor header announces {need} bytes, the file has "
                         f"{p.stat().st_size} (truncated or corrupt?)")


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


def _asd_header(p: Path) -> dict:
    """The .asd header (AFMReader's own header readers), after checking that the frames it
    announces fit in the file, before AFMReader reads them."""
    _quiet()
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
    names = [c for c in (header["channel1"], header["channel2"]) if c]
    need = data_start + len(names) * frames * (header["frame_header_length"] + nx * ny * 2)
    if not (frames >= 1 and nx >= 2 and ny >= 2 and nx * ny <= MAX_PIXELS and names) \
            or need > size:
        raise ValueError(f"{p}: the header's {frames} frames of {nx} x {ny} pixels in channels "
                         f"{names} need {need} bytes, the file has {size} (truncated or "
                         f"corrupt?)")
    header["_channels"] = names
    return header


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
        warnings.filterwarnings("ignore", message="the library tqdm cannot be found")
        import pySPM
    images = _spm_header(p)
    try:
        scan = pySPM.Bruker(str(p))
    except Exception as exc:  # noqa: BLE001 - whatever pySPM raises on a header it misreads
        raise ValueError(f"{p}: not a readable NanoScope file ({type(exc).__name__}: {exc})"
                         ) from None
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
    try:
        channel = _pick(p, channel, names)
        try:  # the header's sizes are checked; its scales and names are pySPM's to parse
            image = scan.get_channel(channel)
            # as AFMReader's load_spm: NanoScope stores the lines bottom up
            values = np.flipud(np.asarray(image.pixels, dtype=float))
            px_nm = spm_pixel_to_nm_scaling(p.stem, image)
            size = image.size["real"]
        except Exception as exc:  # noqa: BLE001 - KeyError, AttributeError of a damaged header
            raise ValueError(f"{p}: channel {channel!r} is not readable by pySPM "
                             f"({type(exc).__name__}: {exc})") from None
    finally:
        scan.file.close()  # pySPM leaves the file open
    unit, scale = _FILE_UNITS.get(image.zscale, (None, None))
    if unit is None:
        raise ValueError(f"{p}: channel {channel!r} has values in {image.zscale!r}, not one of "
                         f"{sorted(_FILE_UNITS)}")
    length = _FILE_UNITS.get(size["unit"], ("m", None))[1]
    # in SI from the header's scan size (AFMReader's nm scaling, rounded through nm, otherwise)
    dx = size["x"] * length / values.shape[1] if length else px_nm * 1e-9
    dy = size["y"] * length / values.shape[0] if length else px_nm * 1e-9
    if not (0 < dx < 1 and 0 < dy < 1):
        raise ValueError(f"{p}: channel {channel!r} must have a positive scan size of under "
                         f"a metre, the header gives pixels of {dx!r} x {dy!r} m")
    meta = {k: v for k, v in images[names.index(channel)].items() if not k.startswith("_")}
    return values * scale, dx, dy, channel, unit, meta


def _gwy_fields(p: Path):
    """The container gwyfile reads and its data fields by title, titles checked."""
    import gwyfile
    from gwyfile.util import get_datafields
    _gwy_check(p)
    try:
        container = gwyfile.load(str(p))
        fields = get_datafields(container)
    except Exception as exc:  # gwyfile raises struct.error, ValueError, ... on a corrupt file
        raise ValueError(f"{p}: not a readable Gwyddion file ({type(exc).__name__}: {exc})"
                         ) from None
    titles = [title for title in fields if not isinstance(title, str)]
    if titles:
        raise ValueError(f"{p}: a channel's title must be text, got {titles[0]!r:.60}")
    return container, fields


def _gwy_field(p: Path, channel: str, field) -> tuple[np.ndarray, float, float, str, str]:
    """A data field's values (rows x columns), pixel sizes and units, each component checked
    against what a GwyDataField holds before it is used: gwyfile returns a damaged file's
    components as they are (a string where the field should be, data shorter than its size)."""
    from gwyfile.objects import GwyDataField, GwySIUnit
    if not isinstance(field, GwyDataField):
        raise ValueError(f"{p}: channel {channel!r} must be a GwyDataField, the file holds a "
                         f"{type(field).__name__} ({field!r:.60})")
    xres, yres, data = field.get("xres"), field.get("yres"), field.get("data")
    if not all(isinstance(n, int) and not isinstance(n, bool) and n >= 1 for n in (xres, yres)) \
            or xres * yres > MAX_PIXELS:
        raise ValueError(f"{p}: channel {channel!r} must have xres and yres of 1 to "
                         f"{MAX_PIXELS} pixels in all, got {xres!r:.60} x {yres!r:.60}")
    if not isinstance(data, np.ndarray) or data.dtype.kind != "f":
        raise ValueError(f"{p}: channel {channel!r} must hold an array of floats, got "
                         f"{type(data).__name__} {data!r:.60}")
    if data.size != xres * yres:
        raise ValueError(f"{p}: channel {channel!r} holds {data.size} values, its xres x yres "
                         f"say {xres} x {yres} (truncated?)")
    reals = [field.get(key) for key in ("xreal", "yreal")]
    if not all(isinstance(v, float) and 0 < v < float("inf") for v in reals):
        raise ValueError(f"{p}: channel {channel!r} must have positive finite xreal and yreal "
                         f"(its size in m), got {reals[0]!r:.60} and {reals[1]!r:.60}")
    units = []
    for key, default in (("si_unit_xy", "m"), ("si_unit_z", "")):
        unit = field.get(key)
        if unit is not None and not (isinstance(unit, GwySIUnit)
                                     and isinstance(unit.get("unitstr"), str)):
            raise ValueError(f"{p}: channel {channel!r} must have a GwySIUnit as {key}, got "
                             f"{type(unit).__name__} {unit!r:.60}")
        units.append(unit["unitstr"] if unit is not None else default)
    values = np.array(data, dtype=float).reshape(yres, xres)
    return values, reals[0] / xres, reals[1] / yres, units[0], units[1]


def _read_gwy(p: Path, channel: str):
    container, fields = _gwy_fields(p)
    channel = _pick(p, channel, list(fields))
    field = fields[channel]
    values, dx, dy, xy, z = _gwy_field(p, channel, field)
    # the instrument's metadata that Gwyddion keeps beside the channel ("/0/meta")
    index = next((key[:-len("/data")] for key, value in container.items()
                  if value is field and key.endswith("/data")), None)
    kept = container.get(f"{index}/meta") if index is not None else None
    if xy != "m" or z not in _FILE_UNITS:
        raise ValueError(f"{p}: channel {channel!r} must have lateral unit 'm' and values in "
                         f"one of {sorted(_FILE_UNITS)}, got {xy!r} and {z!r}")
    unit, scale = _FILE_UNITS[z]
    meta = {str(k): v for k, v in kept.items()} if hasattr(kept, "items") else {}
    meta.update({"xres": field["xres"], "yres": field["yres"], "xreal": field.xreal,
                 "yreal": field.yreal, "si_unit_xy": xy, "si_unit_z": z})
    return values * scale, dx, dy, channel, unit, meta


def _jpk_channels(p: Path) -> dict:
    """A JPK image's channels as AFMReader names them ("height_trace", ...), each with the unit
    of its default calibration slot (JPK's TIFF tags, as Gwyddion's jpkscan.c reads them)."""
    _tiff_check(p)
    import tifffile
    units = {}
    try:
        with tifffile.TiffFile(str(p)) as tif:
            first = {tag.code: tag.value for tag in tif.pages[0].tags.values()}
            # grid-uLength / grid-iLength along the lines, grid-vLength / grid-jLength across
            grid = tuple(first.get(code) for code in (32834, 32838, 32835, 32839))
            for page in tif.pages[1:]:  # the first page is a thumbnail
                tags = {tag.code: tag.value for tag in page.tags.values()}
                if 32848 not in tags:
                    continue
                name = f"{tags[32848]}_{'trace' if tags.get(32849) == 0 else 'retrace'}"
                slots = [k for k in range(int(tags.get(32896, 0)))
                         if tags.get(32912 + 48 * k) == tags.get(32897)]
                units[name] = str(tags.get(32930 + 48 * slots[0], "")) if slots else ""
    except Exception as exc:
        raise ValueError(f"{p}: not a readable JPK image ({type(exc).__name__}: {exc})"
                         ) from None
    if units:
        try:
            dx, dy = float(grid[0]) / int(grid[1]), float(grid[2]) / int(grid[3])
        except (TypeError, ValueError, ZeroDivisionError):
            dx = dy = float("nan")
        if not (0 < dx < 1 and 0 < dy < 1):
            raise ValueError(f"{p}: the JPK grid tags (lengths in m over pixels) must give "
                             f"positive pixel sizes, got {grid}")
        units["_pixel"] = (dx, dy)
    return units


def _ibw_wave(p: Path) -> dict:
    import logging
    from igor2 import binarywave
    # igor2 logs a failed read with the raw bytes; the ValueError below says it instead
    logging.getLogger("igor2").addHandler(logging.NullHandler())
    _ibw_check(p)
    try:
        return binarywave.load(str(p))["wave"]
    except Exception as exc:
        raise ValueError(f"{p}: not a readable Igor binary wave ({type(exc).__name__}: {exc})"
                         ) from None


def _ibw_channels(wave: dict) -> list[str]:
    return [label.decode() for labels in wave["labels"] for label in labels if label]


def _read_ibw(p: Path, channel: str):
    """Asylum's image wave, read by igor2 (AFMReader's own backend) once and oriented as
    AFMReader's ``load_ibw`` does (rows along the slow axis, top down), without its float32
    round trip through nm. The pixel size is Igor's own wave scaling (``SetScale`` delta, in
    the wave's dimension unit), which Igor and Gwyddion's igorfile.c show; AFMReader 0.0.7
    divides the note's ScanSize by the points instead (0.4 % smaller for 256 points)."""
    wave = _ibw_wave(p)
    names = _ibw_channels(wave)
    channel = _pick(p, channel, names)
    title = channel[3:] if channel.startswith(("DAC", "Nap")) else channel
    unit = next((u for start, u in _IBW_UNITS.items() if title.startswith(start)), "V")
    if unit not in SAMPLE_UNITS:
        raise ValueError(f"{p}: channel {channel!r} is in {unit!r}, which a sample does not "
                         f"carry (one of {SAMPLE_UNITS})")
    header = wave["wave_header"]
    # dimUnits: up to 4 characters per dimension ("m", "um", ...)
    dims = [b"".join(row).decode("latin-1") for row in np.atleast_2d(header["dimUnits"])[:2]]
    scales = [_FILE_UNITS.get(u, ("", 0.0)) for u in dims]
    dx, dy = (float(v) * s for v, (_, s) in zip(header["sfA"][:2], scales))
    if [si for si, _ in scales] != ["m", "m"] or not (0 < dx < 1 and 0 < dy < 1):
        raise ValueError(f"{p}: the wave's x and y scaling must be positive lengths, got "
                         f"{header['sfA'][:2]} in {dims}")
    data = wave["wData"]
    if data.ndim != 3 or data.shape[2] != len(names) or min(data.shape[:2]) < 2:
        raise ValueError(f"{p}: the wave must hold one 2-D image per channel {names}, got "
                         f"shape {data.shape}")
    values = np.flipud(data[:, :, names.index(channel)].T).astype(float)
    note = wave["note"].decode("latin-1") if isinstance(wave["note"], bytes) else ""
    meta = dict(line.split(":", 1) for line in note.split("\r") if ":" in line)
    meta = {k.strip(): v.strip() for k, v in meta.items()}
    return values, dx, dy, channel, unit, meta


def _read_jpk(p: Path, channel: str):
    _quiet()
    from AFMReader import jpk
    units = _jpk_channels(p)
    dx, dy = units.pop("_pixel", (None, None))
    channel = _pick(p, channel, list(units))
    stored = units[channel]
    # AFMReader returns heights and amplitudes in nm, the other channels as calibrated
    in_nm = channel.rsplit("_", 1)[0] in _JPK_NM
    unit, scale = _FILE_UNITS.get(stored, (stored, 1.0) if stored in SAMPLE_UNITS else (None, 0))
    if unit is None or (in_nm and stored != "m"):
        raise ValueError(f"{p}: channel {channel!r} has values in {stored!r}, not one of "
                         f"{sorted(_FILE_UNITS)} or the SI units {SAMPLE_UNITS}")
    try:
        values, _ = jpk.load_jpk(p, channel)
    except ValueError as exc:
        raise ValueError(f"{p}: {exc}") from None
    return (np.asarray(values, dtype=float) * (1e-9 if in_nm else scale), dx, dy, channel, unit,
            {})


def _read_asd(p: Path, channel: str):
    from AFMReader import asd
    header = _asd_header(p)  # quiets AFMReader
    channel = _pick(p, channel, header["_channels"])
    if channel not in _ASD_UNITS:
        raise ValueError(f"{p}: this course reads the .asd channels {sorted(_ASD_UNITS)}, got "
                         f"{channel!r}")
    try:
        frames, _, _ = asd.load_asd(p, channel)
    except ValueError as exc:
        raise ValueError(f"{p}: {exc}") from None
    dx = header["x_nm"] * 1e-9 / header["x_pixels"]
    dy = header["y_nm"] * 1e-9 / header["y_pixels"]
    meta = {k: v for k, v in header.items() if not k.startswith("_")}
    return np.asarray(frames[0], dtype=float) * 1e-9, dx, dy, channel, _ASD_UNITS[channel], meta


def _pick(p: Path, channel: str, names: list) -> str:
    """``channel`` if the file has it; the format's height channel for the default "Height"."""
    check_instance("channel", channel, str)
    if channel in names:
        return channel
    if channel == "Height":
        for name in _HEIGHT_CHANNELS.get(p.suffix.lower(), ()) + ("Topography", "height"):
            if name in names:  # "height": the channel save_gwy writes for a Sample's heights
                return name
        if len(names) == 1 and p.suffix.lower() in (".top", ".stp"):
            return names[0]
    raise ValueError(f"channel must be one of the channels of {p.name}: {names}, got "
                     f"{channel!r}")


_READERS = {".spm": _read_spm, ".gwy": _read_gwy, ".top": _read_wsxm, ".stp": _read_wsxm,
            ".ibw": _read_ibw, ".jpk": _read_jpk, ".asd": _read_asd}


def _npy_check(p: Path) -> None:
    """The array a ``.npy`` header announces (numpy's own header reader) must be a 1-D or 2-D
    map of real numbers that fits the limits and the file, before numpy reads its data."""
    from numpy.lib import format as npy
    try:
        with open(p, "rb") as f:
            version = npy.read_magic(f)
            read = {(1, 0): npy.read_array_header_1_0, (2, 0): npy.read_array_header_2_0}
            if version not in read:  # 3.0 is written only for non-ASCII field names
                raise ValueError(f"format version {version} is not 1.0 or 2.0")
            shape, _, dtype = read[version](f)
            start = f.tell()
    except ValueError as exc:
        raise ValueError(f"{p}: not a readable NumPy array ({exc})") from None
    if any(n < 0 for n in shape):
        raise ValueError(f"{p}: the header's shape {shape} has a negative length (corrupt)")
    if len(shape) not in (1, 2) or not 2 <= math.prod(shape) <= MAX_PIXELS:
        raise ValueError(f"{p}: a height map must be 1-D or 2-D with 2 to {MAX_PIXELS} values, "
                         f"the header says shape {shape}")
    if dtype.kind == "c":
        raise ValueError(f"{p}: the array holds complex values ({dtype}); a height map is real "
                         f"(its imaginary part would be lost)")
    if dtype.kind not in "iuf":
        raise ValueError(f"{p}: the array must hold real numbers, it holds {dtype}")
    need = start + math.prod(shape) * dtype.itemsize
    if need > p.stat().st_size:
        raise ValueError(f"{p}: the header's {shape} {dtype} values need {need} bytes, the file "
                         f"has {p.stat().st_size} (truncated?)")


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
        _npy_check(p)
        try:
            values = np.array(np.load(p, mmap_mode="r", allow_pickle=False), dtype=float)
        except ValueError as exc:
            raise ValueError(f"{p}: not a readable NumPy array ({exc})") from None
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
        (``"HeightTracee"``, ``"HeightTrace"`` or ``"HeightRetrace"`` of ``.ibw`` and of a
        ``.gwy`` that Gwyddion made from one, ``"height_trace"`` of ``.jpk``, ``"TP"`` of
        ``.asd``, the one channel of a WSxM file).
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
        than the file holds or than :data:`~afmsmiler.samples.sample.MAX_PIXELS` pixels, a
        negative size or offset, a component of the wrong kind (a ``.gwy`` data field that is
        not one, a complex or non-numeric ``.npy``), NaN or infinite values, a channel the file does not have (the error lists those it has), a
        channel in another unit than ``unit``, or a missing ``pixel_size`` of a plain map.

    Notes
    -----
    WSxM ``.top`` heights span the header's whole ``Z Amplitude`` with its unit, as Gwyddion's
    ``wsxmfile.c`` reads them (AFMReader 0.0.7 takes the integer part of the number only:
    59 nm for "59.7449 nm", a 1.3 % height error corrected here); NanoScope 5 headers spell
    ``Scan size`` and ``Line direction`` where pySPM looks for ``Scan Size`` and
    ``Line Direction``, and are given both before pySPM reads them.

    An Asylum ``.ibw`` image's pixel size is Igor's own wave scaling, as Igor and Gwyddion
    show it (2 um over 256 points: 2 um / 255); AFMReader 0.0.7 divides the scan size by the
    points instead (0.4 % less). Its channels' units follow their names as in Gwyddion's
    igorfile.c (Height, ZSensor, Amplitude, Deflection in m; Phase in deg; Current in A;
    others in V), and its rows are oriented as both Gwyddion and AFMReader show them. A
    ``.jpk`` channel's unit is that of its calibration slot (m, deg, V); an ``.asd`` movie
    gives its first frame, topography only.

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
        return list(_gwy_fields(p)[1])
    if suffix == ".ibw":
        return _ibw_channels(_ibw_wave(p))
    if suffix == ".jpk":
        return [name for name in _jpk_channels(p) if name != "_pixel"]
    return _asd_header(p)["_channels"]


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
