"""The scanner's settings: what a user sets on an AFM's scanner, validated, in SI units.

:data:`PARAMETERS` describes each quantity once (SI unit, display unit, default, valid and slider
ranges); :class:`ScanSettings` holds one scan's values, checked against them. The scanner
(:mod:`afmsmiler.imaging.scanner`), the acquisitions (:mod:`afmsmiler.imaging.acquisition`) and
the imaging panel read them from here (:mod:`~afmsmiler.imaging.scanner` re-exports both).
"""
from __future__ import annotations

import math
from dataclasses import KW_ONLY, dataclass, replace

import numpy as np

from ..controller import PARAMETERS as LOOP_PARAMETERS
from ..controller.image import MAX_IMAGE_PIXELS
from ..parameters import Parameter, read_only
from ..validation import check_array, check_integer

__all__ = ["ScanSettings", "PARAMETERS", "MAX_SCAN_PIXELS"]

#: Most pixels of a scan (pixels x lines), the bound of module (c)'s scan_image (about 4 s).
MAX_SCAN_PIXELS = MAX_IMAGE_PIXELS
_MAX_SIDE = 2048


def _length(name, label, default, low, high, slider_low, slider_high, display="um", log=False,
            low_inclusive=True):
    return Parameter(name=name, unit="m", display_unit=display, default=default, low=low,
                     high=high, low_inclusive=low_inclusive, slider_low=slider_low,
                     slider_high=slider_high, log=log, label=label)


def _angle(name, label, high, slider):
    return Parameter(name=name, unit="rad", display_unit="deg", default=0.0, low=-high,
                     high=high, low_inclusive=False, high_inclusive=False, slider_low=-slider,
                     slider_high=slider, label=label)


def _drift(name, label):
    return Parameter(name=name, unit="m/s", display_unit="nm/s", default=0.0, low=-1e-6,
                     high=1e-6, slider_low=-5e-9, slider_high=5e-9, label=label)


_SPEED = LOOP_PARAMETERS["speed"]

#: The scanner's user-settable quantities (SI; display units through ``UNITS``). Scan ranges
#: from 0.1 nm (an atom) to 100 um (the largest AFM scanners'); 2 to 2048 pixels and 1 to 2048
#: lines (at most :data:`MAX_SCAN_PIXELS` in all); the scan speed is module (c)'s ``speed``
#: (1 nm/s to 1 m/s), also settable as a line rate; the angle in (-180, 180) deg; offsets within
#: 100 um; sensor noise up to 1 um RMS; drift up to 1 um/s; creep up to 50 % per decade after
#: 1 ms to 1000 s; tilts in (-90, 90) deg.
PARAMETERS = read_only({p.name: p for p in (
    _length("scan_size", "scan size", 1e-6, 1e-10, 100e-6, 10e-9, 100e-6, log=True),
    _length("scan_size_y", "scan size y", 1e-6, 1e-10, 100e-6, 10e-9, 100e-6, log=True),
    Parameter(name="pixels", unit="", default=256, low=2, high=_MAX_SIDE, slider_low=16,
              slider_high=1024, log=True, label="pixels per line"),
    Parameter(name="lines", unit="", default=256, low=1, high=_MAX_SIDE, slider_low=16,
              slider_high=1024, log=True, label="lines"),
    _SPEED.with_(name="scan_speed"),
    Parameter(name="line_rate", unit="Hz", default=1.0, low=1e-4, high=1e4, slider_low=0.05,
              slider_high=50.0, log=True, label="line rate"),
    _angle("angle", "scan angle", math.pi, math.pi / 2),
    _length("offset_x", "offset x", 0.0, -100e-6, 100e-6, -5e-6, 5e-6),
    _length("offset_y", "offset y", 0.0, -100e-6, 100e-6, -5e-6, 5e-6),
    _length("noise", "sensor noise (RMS)", 0.0, 0.0, 1e-6, 0.0, 2e-9, display="nm"),
    _drift("drift_x", "drift x"),
    _drift("drift_y", "drift y"),
    Parameter(name="creep", unit="", default=0.0, low=0.0, high=0.5, slider_low=0.0,
              slider_high=0.05, label="creep per decade gamma"),
    Parameter(name="creep_time", unit="s", default=0.1, low=1e-3, high=1e3, slider_low=0.01,
              slider_high=10.0, log=True, label="creep time t0"),
    _angle("tilt_x", "sample tilt along x", math.pi / 2, math.radians(5.0)),
    _angle("tilt_y", "sample tilt along y", math.pi / 2, math.radians(5.0)),
)})

_P = PARAMETERS


def _pair(name, value, keys):
    """A 2-tuple of floats, each checked with its Parameter (offset -> offset_x, offset_y)."""
    try:
        a, b = value
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a pair (x, y), got {value!r}") from None
    return tuple(_P[k].check(v) for k, v in zip(keys, (a, b)))


@dataclass(frozen=True)
class ScanSettings:
    """What the user sets on the scanner, validated, in SI units.

    Parameters
    ----------
    scan_size : float
        Scan range along the fast axis in m (the side of pixels square cells: the image's width
        is pixels x pixel_size, as AFM software counts it).
    scan_size_y : float, optional
        Scan range along the slow axis in m; default ``scan_size``.
    pixels : int
        Pixels per line, 2 to 2048.
    lines : int, optional
        Lines, 1 to 2048; default ``pixels``. At most :data:`MAX_SCAN_PIXELS` pixels in all.
    scan_speed : float
        Tip speed along the fast axis in m/s (module (c)'s speed range, 1 nm/s to 1 m/s); see
        :meth:`with_line_rate` to set it in lines per second.
    angle : float
        Scan angle in rad: the scan grid is rotated by it (counter-clockwise) on the sample.
    offset : tuple of float
        (x, y) in m of the scan's centre from the sample's centre, in the sample's axes.
    noise : float
        RMS in m of the sensor noise added to every channel in m (white, Gaussian, independent
        per pixel and pass; the loop does not see it).
    drift : tuple of float
        (v_x, v_y) in m/s: a constant thermal drift of the sample under the tip.
    creep : float
        Piezo creep gamma (fraction of the offset step per decade of time, 0.01 to 0.02 for
        typical PZT; 0: none).
    creep_time : float
        The creep's time scale t0 in s.
    tilt : tuple of float
        (alpha_x, alpha_y) in rad: the sample is tilted by adding the plane
        tan(alpha_x) (x - x_c) + tan(alpha_y) (y - y_c) about its centre before the dilation.
    seed : int, optional
        Seed of the noise (numpy's default_rng); None draws a fresh one.

    Raises
    ------
    ValueError
        If a value is out of its range (:data:`PARAMETERS`), names the parameter and the range.

    Notes
    -----
    Drift and creep move the sample under the scan grid: the tip at time t is at the nominal
    point plus :meth:`displacement` (t), with t counted from the start of the scan, when the
    scanner has just stepped by ``offset``. Creep follows the logarithmic law of PZT actuators
    after a step x0, x(t) = x0 [1 + gamma log10(t / t0)] (Jung and Gweon, Rev. Sci. Instrum. 71,
    1896 (2000); Croft, Shed and Devasia, J. Dyn. Syst. Meas. Control 123, 35 (2001)), written
    here as offset x gamma log10(1 + t / t0) so that it starts at 0. Both are what makes the
    first lines after an offset bent and an image drawn slowly sheared.

    Examples
    --------
    >>> s = ScanSettings(2e-6, pixels=128, scan_speed=4e-6)
    >>> round(s.pixel_size * 1e9, 3), s.lines
    (15.625, 128)
    >>> round(s.with_line_rate(1.0).scan_speed * 1e6, 3)  # 1 line/s: 255 pixel times per line
    3.984
    """

    scan_size: float
    _: KW_ONLY
    scan_size_y: float | None = None
    pixels: int = int(_P["pixels"].default)
    lines: int | None = None
    scan_speed: float = _P["scan_speed"].default
    angle: float = _P["angle"].default
    offset: tuple = (0.0, 0.0)
    noise: float = _P["noise"].default
    drift: tuple = (0.0, 0.0)
    creep: float = _P["creep"].default
    creep_time: float = _P["creep_time"].default
    tilt: tuple = (0.0, 0.0)
    seed: int | None = None

    def __post_init__(self):
        s = object.__setattr__
        s(self, "scan_size", _P["scan_size"].check(self.scan_size))
        y = self.scan_size if self.scan_size_y is None else self.scan_size_y
        s(self, "scan_size_y", _P["scan_size_y"].check(y))
        s(self, "pixels", check_integer("pixels", self.pixels, 2, _MAX_SIDE))
        lines = self.pixels if self.lines is None else self.lines
        s(self, "lines", check_integer("lines", lines, 1, _MAX_SIDE))
        if self.pixels * self.lines > MAX_SCAN_PIXELS:
            raise ValueError(f"pixels x lines must be at most {MAX_SCAN_PIXELS} (a bound the "
                             f"scan honours in seconds), got {self.pixels} x {self.lines}")
        for name in ("scan_speed", "angle", "noise", "creep", "creep_time"):
            s(self, name, _P[name].check(getattr(self, name)))
        s(self, "offset", _pair("offset", self.offset, ("offset_x", "offset_y")))
        s(self, "drift", _pair("drift", self.drift, ("drift_x", "drift_y")))
        s(self, "tilt", _pair("tilt", self.tilt, ("tilt_x", "tilt_y")))
        if self.seed is not None:
            s(self, "seed", check_integer("seed", self.seed, 0, 2 ** 63 - 1))

    def replace(self, **changes) -> "ScanSettings":
        """A copy with some settings changed (validated again).

        Parameters
        ----------
        **changes
            New values of any of the fields.

        Returns
        -------
        ScanSettings
        """
        return replace(self, **changes)

    @property
    def shape(self) -> tuple[int, int]:
        """(lines, pixels) of the image."""
        return (self.lines, self.pixels)

    @property
    def pixel_size(self) -> float:
        """Pixel spacing along the fast axis in m: scan_size / pixels."""
        return self.scan_size / self.pixels

    @property
    def pixel_size_y(self) -> float:
        """Line spacing in m: scan_size_y / lines."""
        return self.scan_size_y / self.lines

    @property
    def pixel_time(self) -> float:
        """Time in s from one pixel to the next: pixel_size / scan_speed."""
        return self.pixel_size / self.scan_speed

    @property
    def line_time(self) -> float:
        """Time in s of one line, trace, retrace and the step to the next: (2 pixels - 1) dt."""
        return (2 * self.pixels - 1) * self.pixel_time

    @property
    def line_rate(self) -> float:
        """Lines per second in Hz (1 / :attr:`line_time`), the rate AFM software shows."""
        return 1.0 / self.line_time

    @property
    def scan_time(self) -> float:
        """Time in s of the whole scan (lines x :attr:`line_time`)."""
        return self.lines * self.line_time

    def with_line_rate(self, line_rate: float) -> "ScanSettings":
        """A copy whose scan speed gives ``line_rate`` lines per second.

        Parameters
        ----------
        line_rate : float
            Lines per second in Hz (trace, retrace and the step to the next line each).

        Returns
        -------
        ScanSettings

        Raises
        ------
        ValueError
            If the line rate, or the scan speed it needs, is out of range.
        """
        rate = _P["line_rate"].check(line_rate)
        speed = (2 * self.pixels - 1) * self.pixel_size * rate
        try:
            return self.replace(scan_speed=speed)
        except ValueError as err:
            raise ValueError(f"line_rate {rate:g} Hz needs a scan speed out of range: {err}") \
                from None

    def displacement(self, t):
        """Drift and creep displacement (d_x, d_y) in m of the sample at time t since the start.

        Parameters
        ----------
        t : float or numpy.ndarray
            Time in s, in [0, 1e12] (30 000 years: any scan's duration).

        Returns
        -------
        tuple of numpy.ndarray
            d = drift t + offset gamma log10(1 + t / t0), each shaped like ``t``.

        Raises
        ------
        ValueError
            If a time is not a number in [0, 1e12] s.
        """
        t = check_array("t", t, "s", low=0.0, high=1e12).reshape(np.shape(t))
        creep = self.creep * np.log10(1.0 + t / self.creep_time)
        return tuple(v * t + o * creep for v, o in zip(self.drift, self.offset))

    @property
    def moves(self) -> bool:
        """True when drift or creep move the sample during the scan."""
        return any(self.drift) or (self.creep > 0 and any(self.offset))
