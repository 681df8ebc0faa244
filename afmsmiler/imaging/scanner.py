"""The virtual scanner: where the tip goes on the sample, when, and what it records there.

A :class:`Scan` joins a sample (:class:`~afmsmiler.samples.Sample`), a tip (module (d)'s
:class:`~afmsmiler.contact.Tip`), an imaging mode (:class:`~afmsmiler.imaging.scan_modes.Mode`) and
the :class:`ScanSettings` (scan range, pixels, lines, speed, angle, offset, noise, drift, creep,
tilt). It

1. adds the tilt's plane to the sample and dilates the result by the tip
   (:func:`afmsmiler.imaging.dilation.dilate`): the apex surface, the surface the tip's apex
   follows (only over the part of the sample the scan can feel: its bounding box widened by the
   tip's reach at the sample's height range, which gives the whole dilation's values there);
2. lays the scan grid on the sample: line i, pixel j of the image is at
   (u_j, v_i) = ((j + 1/2) dx - S_x / 2, (i + 1/2) dy - S_y / 2) in the scan frame, with
   dx = S_x / pixels and dy = S_y / lines (the scan range covers pixels x lines square cells, as
   AFM software counts it), rotated by the scan angle and centred on the sample's centre plus the
   offset; drift and creep move the points with time (:meth:`ScanSettings.displacement`);
3. samples the apex surface there by bilinear interpolation (exact at the sample's own pixels), for
   the trace and the retrace separately (they pass at different times);
4. hands the mode one line at a time (:meth:`Scan.lines`, :meth:`Scan.run`, :meth:`Scan.step`)
   and adds the sensor noise to the channels in m.

The times: each line is traced (pixels 0 to n - 1) and retraced (n - 1 to 0, the turn-around
pixel shared) at the scan speed, one pixel time dt = dx / scan_speed apart, and the step to the
next line takes one more dt: a line takes (2 n - 1) dt (:attr:`ScanSettings.line_time`), the
timing of module (c)'s :func:`~afmsmiler.controller.scan_image`.

Finished lines are never lost: :attr:`Scan.result` is a :class:`ScanResult` at any time, with the
images of the lines done so far, whether the scan was stopped, and where the tip crashed.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field, replace
from types import MappingProxyType
from typing import Callable, Iterator, Mapping

import numpy as np

from ..contact import Parabolic, Tip
from ..samples import Sample
from ..validation import check_choice, check_instance, check_integer
from .scan_modes import DIRECTIONS, Crash, Mode, ScanPlan
from .settings import MAX_SCAN_PIXELS, PARAMETERS, ScanSettings

__all__ = ["ScanSettings", "Scan", "ScanResult", "LineRecord", "scan", "PARAMETERS",
           "MAX_SCAN_PIXELS"]

@dataclass(frozen=True)
class LineRecord:
    """One finished (or crashed) line of a scan, as :meth:`Scan.lines` yields it.

    Parameters
    ----------
    row : int
        Line index.
    channels : Mapping
        Channel name -> 1-D array (pixels,) in SI units, columns in increasing x, noise added.
    crash : Crash or None
        Where the tip crashed on this line (the line is then not finished).
    """

    row: int
    channels: Mapping
    crash: Crash | None = None


@dataclass(frozen=True)
class ScanResult:
    """The state of a scan: the images of the lines done, whether it stopped, where it crashed.

    Parameters
    ----------
    images : Mapping
        Channel name -> (lines, pixels) array in SI units, NaN where no line was scanned yet
        (a crashed line holds the pixels reached).
    units : Mapping
        Channel name -> SI unit.
    lines_done : int
        The row after the last finished line: rows ``first_row`` to lines_done - 1 are
        finished (rows 0 to lines_done - 1 for a scan from the first line).
    crashed : Crash or None
        Where the tip crashed (row, column, force in N), or None.
    stopped : bool
        True if :meth:`Scan.run` was stopped before the end.
    pixel_size, pixel_size_y : float
        Pixel spacing of the images in m.
    name : str
        The scanned sample's name.
    metadata : Mapping
        The scan settings (SI), given to every channel's Sample as its metadata.
    first_row : int
        The row the scan started at (0 unless :meth:`Scan.lines` was given ``start``); the rows
        before it were not scanned (NaN).
    """

    images: Mapping
    units: Mapping
    lines_done: int
    crashed: Crash | None
    stopped: bool
    pixel_size: float
    pixel_size_y: float
    name: str = ""
    metadata: Mapping = field(default_factory=lambda: MappingProxyType({}))
    first_row: int = 0

    @property
    def lines(self) -> int:
        """Lines of the full image."""
        return next(iter(self.images.values())).shape[0] if self.images else 0

    @property
    def finished(self) -> bool:
        """True when every line was scanned."""
        return self.lines_done == self.lines

    @property
    def progress(self) -> float:
        """Fraction of the lines done, 0 to 1."""
        return self.lines_done / self.lines if self.lines else 0.0

    @property
    def finished_lines(self) -> int:
        """Number of lines this scan finished (lines_done - first_row)."""
        return self.lines_done - self.first_row

    @property
    def channels(self) -> dict:
        """Channel name -> :class:`~afmsmiler.samples.Sample` of the finished lines ({} if none).

        Each sample holds rows ``first_row`` to lines_done - 1 with the scan's pixel sizes.
        """
        if self.lines_done <= self.first_row:
            return {}
        meta = {"lines_done": self.lines_done, "first_row": self.first_row, **self.metadata}
        rows = slice(self.first_row, self.lines_done)
        return {name: _sample(image[rows], self.pixel_size, self.pixel_size_y,
                              f"{self.name}: {name}" if self.name else name, name,
                              self.units[name], meta)
                for name, image in self.images.items()}


def _sample(values, pixel_size, pixel_size_y, name, channel, unit, metadata=None):
    return Sample(values, pixel_size, name, pixel_size_y=pixel_size_y, channel=channel,
                  unit=unit, metadata=metadata)


def _bilinear(heights, px, py):
    """Bilinear interpolation of heights[row, column] at fractional (column px, row py).

    Positions within 1e-9 pixel of a node are taken at the node (exact values there).
    """
    rows, cols = heights.shape
    out = []
    for p, n in ((px, cols), (py, rows)):
        r = np.rint(p)
        p = np.where(np.abs(p - r) < 1e-9, r, p)
        p = np.clip(p, 0.0, n - 1)
        i0 = np.minimum(np.floor(p).astype(np.intp), max(n - 2, 0))
        out.append((i0, p - i0))
    (j0, fx), (i0, fy) = out
    if not fx.any() and not fy.any():  # every point on a pixel of the sample (a grid aligned)
        return heights[i0, j0]
    j1 = np.minimum(j0 + 1, cols - 1)
    i1 = np.minimum(i0 + 1, rows - 1)
    top = heights[i0, j0] * (1 - fx) + heights[i0, j1] * fx
    bottom = heights[i1, j0] * (1 - fx) + heights[i1, j1] * fx
    return top * (1 - fy) + bottom * fy


def _sampled(heights, px, py, straight):
    """The heights at fractional (column px, row py): a slice when the grid is the sample's."""
    if straight:  # the scan's columns and rows may be runs of the sample's own pixels
        cols, rows = px[0], py[:, 0]
        c0, r0 = round(float(cols[0])), round(float(rows[0]))
        if (np.all(np.abs(cols - (c0 + np.arange(cols.size))) < 1e-9)
                and np.all(np.abs(rows - (r0 + np.arange(rows.size))) < 1e-9)
                and np.all(px == cols[None, :]) and np.all(py == rows[:, None])):
            return heights[r0:r0 + rows.size, c0:c0 + cols.size].copy()
    return _bilinear(heights, px, py)


def _at_least(lo: int, hi: int, need: int, size: int) -> tuple[int, int]:
    """lo:hi widened inside 0:size to at least ``need`` pixels (or all of them).

    A box clipped at an edge of the sample (a zoom into its corner) can be narrower than the
    tip's footprint although the sample is not: the dilation would refuse the part as an image
    narrower than the tip. Widening it into the sample only adds points the tip cannot reach
    first, so the apex surface over the scan does not change.
    """
    need = min(need, size)
    if hi - lo >= need:
        return lo, hi
    return (0, max(hi, need)) if lo == 0 else (min(lo, size - need), size)


def _fmt(x):
    return f"{x * 1e6:.4g} um"


class Scan:
    """A scan of a sample with a tip in an imaging mode, run line by line.

    Parameters
    ----------
    sample : afmsmiler.samples.Sample
        The sample, 2-D (at least 2 x 2 pixels), heights in m.
    tip : afmsmiler.contact.Tip or None
        The tip whose shape blurs the image (dilation); None: an ideal, infinitely sharp tip.
    mode : afmsmiler.imaging.scan_modes.Mode
        The imaging mode.
    settings : ScanSettings
        Scan range, pixels, speed, angle, offset, noise, drift, creep, tilt.
    images : dict, optional
        Channel name -> (lines, pixels) float array the lines are written into: an acquisition
        that goes on with new settings from the next line passes the image it holds, so the
        image is held once (:class:`~afmsmiler.imaging.acquisition.ScanAcquisition`). Channels
        it lacks are added to it as NaN. Default: new arrays of NaN.

    Raises
    ------
    TypeError
        If an argument is of the wrong type.
    ValueError
        If the sample is not 2-D heights in m or holds NaN, the scan range (with its angle,
        offset, drift and creep) reaches beyond the sample, the tip is wider than the image at
        the sample's height range (named ``tip``, from the dilation), the mode's own tip is not
        ``tip`` or the mode lists no channels.

    Notes
    -----
    The constructor checks everything and dilates the part of the sample the scan can feel (a
    few ms for 256 x 256 with a paraboloid), so that a tip too wide for the image is refused at
    once; the sampling of the
    apex surface (:attr:`plan`) and :meth:`Mode.start` run on the first call of :meth:`step`,
    :meth:`lines` or :meth:`run`. One line per :meth:`step` keeps a notebook responsive.

    Examples
    --------
    >>> import numpy as np
    >>> from afmsmiler.samples import Sample
    >>> from afmsmiler.controller import ContactLoop
    >>> from afmsmiler.imaging.scan_modes import ConstantForce
    >>> sample = Sample(np.zeros((32, 32)), 10e-9)
    >>> result = Scan(sample, None, ConstantForce(ContactLoop()),
    ...               ScanSettings(300e-9, pixels=16)).run()
    >>> result.lines_done, sorted(result.channels)[0]
    (16, 'error retrace')
    """

    def __init__(self, sample: Sample, tip: Tip | None, mode: Mode, settings: ScanSettings, *,
                 images: dict | None = None):
        self.sample = check_instance("sample", sample, Sample)
        self.tip = None if tip is None else check_instance("tip", tip, Tip)
        self.mode = check_instance("mode", mode, Mode)
        self.settings = check_instance("settings", settings, ScanSettings)
        h = sample.heights
        if sample.unit != "m":
            raise ValueError(f"sample must hold heights in m, got a {sample.channel!r} channel in "
                             f"{sample.unit!r}")
        if h.ndim != 2 or min(h.shape) < 2:
            raise ValueError(f"sample must be a 2-D image of at least 2 x 2 pixels, got heights "
                             f"of shape {h.shape}")
        if not np.all(np.isfinite(h)):
            i = tuple(int(k) for k in np.unravel_index(int(np.argmax(~np.isfinite(h))), h.shape))
            raise ValueError(f"sample heights must be finite m, got {float(h[i])!r} at {i}")
        if not math.isfinite(float(np.max(h)) - float(np.min(h))):
            raise ValueError(f"sample heights must span a range a float can hold (1.8e308 m), "
                             f"got {float(np.min(h)):g} to {float(np.max(h)):g} m")
        mode_tip = getattr(mode, "tip", None)
        if mode_tip is not None and tip is not None and mode_tip != tip:
            raise ValueError(f"tip ({tip!r}) must be the tip of the mode's physics "
                             f"({mode_tip!r}): one tip both blurs and touches")
        names = mode.channels
        if (not isinstance(names, tuple) or not names or len(set(names)) != len(names)
                or not all(isinstance(c, str) for c in names)):
            raise ValueError(f"mode must list its channels as a tuple of distinct names, got "
                             f"{names!r}")
        self._positions = self._geometry()
        self._metadata = MappingProxyType({"mode": type(mode).__name__, "tip": repr(tip),
                                           **asdict(settings)})
        self._apex_surface, self._apex_row, self._apex_column = self._apex()
        self._plan = None
        self._state = None
        self._images = self._buffers(images)
        self._lines_done = 0
        self._first_row = 0
        self._started = False
        self._crashed = None
        self._stopped = False
        self._rng = np.random.default_rng(settings.seed)

    def _buffers(self, images: dict | None) -> dict:
        """The arrays the lines go into: ``images`` checked (and completed), else new NaN."""
        shape = self.settings.shape
        if images is None:
            return {c: np.full(shape, np.nan) for c in self.mode.channels}
        check_instance("images", images, dict)
        for name in self.mode.channels:
            a = images.setdefault(name, np.full(shape, np.nan))
            if (not isinstance(a, np.ndarray) or a.shape != shape or a.dtype != np.float64
                    or not a.flags.writeable):
                raise ValueError(f"images[{name!r}] must be a writeable float array of shape "
                                 f"{shape} (lines, pixels), got "
                                 f"{getattr(a, 'dtype', type(a).__name__)} "
                                 f"{getattr(a, 'shape', '')}")
        return images

    @staticmethod
    def _units_of(mode):
        return {c: mode.unit(c) for c in mode.channels}

    # -- geometry --------------------------------------------------------------------------
    def _geometry(self):
        """Apex positions (x, y) on the sample in m and times in s, per pass; range checked."""
        s, sample = self.settings, self.sample
        rows, cols = sample.heights.shape
        dx, dy = s.pixel_size, s.pixel_size_y
        u = (np.arange(s.pixels) + 0.5) * dx - s.scan_size / 2
        v = (np.arange(s.lines) + 0.5) * dy - s.scan_size_y / 2
        width, height = (cols - 1) * sample.pixel_size, (rows - 1) * sample.pixel_size_y
        cx, cy = width / 2 + s.offset[0], height / 2 + s.offset[1]
        c, sn = math.cos(s.angle), math.sin(s.angle)
        uu, vv = np.meshgrid(u, v)
        x0 = cx + c * uu - sn * vv
        y0 = cy + sn * uu + c * vv
        n, dt = s.pixels, s.pixel_time
        start = np.arange(s.lines)[:, None] * (2 * n - 1)
        j = np.arange(n)[None, :]
        t_trace = (start + j) * dt
        t_retrace = (start + (n - 1) + (n - 1 - j)) * dt
        slack_x, slack_y = 1e-9 * max(width, s.scan_size), 1e-9 * max(height, s.scan_size_y)

        def outside(x, y):
            return (x.min() < -slack_x or x.max() > width + slack_x or y.min() < -slack_y
                    or y.max() > height + slack_y)

        if outside(x0, y0):
            raise ValueError(
                f"scan_size ({_fmt(s.scan_size)} x {_fmt(s.scan_size_y)}, at angle "
                f"{math.degrees(s.angle):.4g} deg, offset ({_fmt(s.offset[0])}, "
                f"{_fmt(s.offset[1])})) reaches beyond the sample ({_fmt(width)} x "
                f"{_fmt(height)}, first to last pixel): its pixels span x in "
                f"[{_fmt(x0.min())}, {_fmt(x0.max())}], y in [{_fmt(y0.min())}, "
                f"{_fmt(y0.max())}]; scan a smaller range or load a larger sample")
        out = {}
        for name, t in (("trace", t_trace), ("retrace", t_retrace)):
            if s.moves:
                ddx, ddy = s.displacement(t)
                x, y = x0 + ddx, y0 + ddy
                if outside(x, y):
                    raise ValueError(
                        f"drift ({s.drift[0]:g}, {s.drift[1]:g}) m/s and creep {s.creep:g} carry "
                        f"the scan beyond the sample ({_fmt(width)} x {_fmt(height)}) within "
                        f"the scan's {s.scan_time:.4g} s: x reaches [{_fmt(x.min())}, "
                        f"{_fmt(x.max())}], y [{_fmt(y.min())}, {_fmt(y.max())}]")
            else:
                x, y = x0, y0
            out[name] = (x, y, t)
        return out

    def _apex(self) -> tuple[Sample, int, int]:
        """The apex surface over the part of the sample the scan can feel, and its first pixel.

        Only the scan's bounding box, widened by the tip's reach at the sample's height range
        (where its surface rises by that range: farther sample points can never touch first, the
        argument that makes the dilation's cut exact), is dilated; the values there are those of
        the whole sample's dilation. Returns (apex, first row, first column).
        """
        sample, s = self.sample, self.settings
        rows, cols = sample.heights.shape
        r0, r1, c0, c1 = self._box() if self.tip is not None else (0, rows, 0, cols)
        h = sample.heights[r0:r1, c0:c1]
        if any(s.tilt):
            x = np.arange(c0, c1) * sample.pixel_size - (cols - 1) * sample.pixel_size / 2
            y = np.arange(r0, r1) * sample.pixel_size_y - (rows - 1) * sample.pixel_size_y / 2
            h = h + (math.tan(s.tilt[0]) * x[None, :] + math.tan(s.tilt[1]) * y[:, None])
        part = replace(sample, heights=h)
        if self.tip is None:
            return part, r0, c0
        from .dilation import dilate
        return dilate(part, self.tip), r0, c0

    def _box(self) -> tuple[int, int, int, int]:
        """Rows r0:r1 and columns c0:c1 of the sample that the scan's apex surface depends on."""
        sample, s, tip = self.sample, self.settings, self.tip
        rows, cols = sample.heights.shape
        dx, dy = sample.pixel_size, sample.pixel_size_y
        full = (0, rows, 0, cols)
        heights = sample.heights
        if any(s.tilt):
            x = np.arange(cols) * dx - (cols - 1) * dx / 2
            y = np.arange(rows) * dy - (rows - 1) * dy / 2
            heights = heights + (math.tan(s.tilt[0]) * x[None, :]
                                 + math.tan(s.tilt[1]) * y[:, None])
        span = float(np.max(heights)) - float(np.min(heights))
        if not math.isfinite(span):
            raise ValueError(f"sample heights with the tilt ({s.tilt[0]:g}, {s.tilt[1]:g}) rad "
                             f"must span a range a float can hold (1.8e308 m), got "
                             f"{float(np.min(sample.heights)):g} to "
                             f"{float(np.max(sample.heights)):g} m before the tilt")
        if isinstance(tip, Parabolic):  # t = rho^2 / (2 R) reaches the span at sqrt(2 R span)
            reach = math.sqrt(2.0 * tip.radius * span)
            nx, ny = math.ceil(reach / dx), math.ceil(reach / dy)
        else:
            from .dilation import tip_surface
            try:
                grid = tip_surface(tip, dx, dy, max_height=span)
            except ValueError:  # a grid too large to build: dilate everything (dilate decides)
                return full
            ny, nx = (grid.shape[0] - 1) // 2, (grid.shape[1] - 1) // 2
        xs = [p[0] / dx for p in self._positions.values()]
        ys = [p[1] / dy for p in self._positions.values()]
        c_lo = math.floor(min(float(a.min()) for a in xs)) - nx - 1
        c_hi = math.ceil(max(float(a.max()) for a in xs)) + nx + 2
        r_lo = math.floor(min(float(a.min()) for a in ys)) - ny - 1
        r_hi = math.ceil(max(float(a.max()) for a in ys)) + ny + 2
        return (*_at_least(max(r_lo, 0), min(r_hi, rows), 2 * ny + 1, rows),
                *_at_least(max(c_lo, 0), min(c_hi, cols), 2 * nx + 1, cols))

    @property
    def plan(self) -> ScanPlan:
        """The :class:`~afmsmiler.imaging.scan_modes.ScanPlan` the mode scans (computed once)."""
        if self._plan is None:
            apex = self._apex_surface
            sample, s = self.sample, self.settings
            passes = {}
            for name, (x, y, t) in self._positions.items():
                if name == "retrace" and not s.moves:  # the same points as the trace
                    passes[name] = passes["trace"].copy()
                    continue
                passes[name] = _sampled(apex.heights, x / sample.pixel_size - self._apex_column,
                                        y / sample.pixel_size_y - self._apex_row,
                                        s.angle == 0.0)
            (xt, yt, tt), (xr, yr, tr) = self._positions["trace"], self._positions["retrace"]
            origin = (self._apex_column * sample.pixel_size, self._apex_row * sample.pixel_size_y)
            self._plan = ScanPlan(passes["trace"], passes["retrace"], tt, tr, xt, yt, xr, yr,
                                  s.pixel_size, s.pixel_size_y, s.scan_speed, apex, self.tip, s,
                                  origin)
        return self._plan

    # -- running ---------------------------------------------------------------------------
    @property
    def done(self) -> bool:
        """True when every line was scanned, the tip crashed or the scan was stopped."""
        return (self._lines_done >= self.settings.lines or self._crashed is not None
                or self._stopped)

    def step(self) -> LineRecord | None:
        """Scan the next line; None when the scan is over.

        Returns
        -------
        LineRecord or None
            The line (its row, channels and crash, if any).
        """
        if self.done:
            return None
        plan = self.plan
        row = self._lines_done
        if not self._started:
            self._state = self.mode.start(plan)
            self._started = True
        out = self.mode.line(plan, row, self._state)
        channels = {}
        missing = [name for name in self.mode.channels if name not in out.channels]
        if missing:
            raise ValueError(f"mode {type(self.mode).__name__} gave no channel {missing[0]!r} "
                             f"for line {row}")
        for name in self.mode.channels:
            values = np.array(out.channels[name], dtype=float)
            if values.shape != (self.settings.pixels,):
                raise ValueError(f"mode {type(self.mode).__name__} gave channel {name!r} the "
                                 f"shape {values.shape}, not ({self.settings.pixels},)")
            if self.settings.noise > 0 and self.mode.unit(name) == "m":
                values = values + self._rng.normal(0.0, self.settings.noise, values.shape)
            channels[name] = values
            self._images[name][row] = values
        self._state = out.state
        if out.crash is not None:
            self._crashed = out.crash
        else:
            self._lines_done += 1
        return LineRecord(row, MappingProxyType(channels), out.crash)

    def lines(self, start: int | None = None) -> Iterator[LineRecord]:
        """Scan line after line, yielding each as it is done (a crashed line last).

        Parameters
        ----------
        start : int, optional
            Begin at this row instead of the first (only before any line was scanned): the rows
            before it are left unscanned (NaN), as when a panel applies new settings from the
            next line on. The mode still starts once (:meth:`Mode.start`) and is then asked
            for the rows from ``start`` on; :class:`~afmsmiler.imaging.scan_modes.ConstantForce`
            solves the whole image with the new settings, so its row ``start`` is the loop's
            state as if the new settings had scanned all the earlier lines.

        Returns
        -------
        iterator of LineRecord
            The lines as they are scanned (``start`` is checked at the call, before any line).

        Raises
        ------
        ValueError
            If ``start`` is not a row, or lines were already scanned.
        """
        if start is not None:
            start = check_integer("start", start, 0, self.settings.lines - 1)
            if self._started:
                if start != self._lines_done:
                    raise ValueError(f"start must be given before the first line (the scan is "
                                     f"at row {self._lines_done}), got {start}")
            else:
                self._lines_done = self._first_row = start
        return self._records()

    def _records(self) -> Iterator[LineRecord]:
        while (record := self.step()) is not None:
            yield record

    def run(self, stop: Callable[[], bool] | None = None) -> ScanResult:
        """Scan to the end, or until ``stop()`` returns True (checked before every line).

        Parameters
        ----------
        stop : callable, optional
            Called with no argument before each line; True stops the scan (the finished lines
            are kept and :attr:`ScanResult.stopped` is set).

        Returns
        -------
        ScanResult
        """
        if stop is not None and not callable(stop):
            raise TypeError(f"stop must be a callable or None, got {stop!r}")
        while not self.done:
            if stop is not None and stop():
                self._stopped = True
                break
            self.step()
        return self.result

    def stop(self) -> None:
        """Stop the scan after the current line (the finished lines are kept)."""
        self._stopped = True

    @property
    def result(self) -> ScanResult:
        """The images so far (a copy), the lines done, the crash and whether it was stopped."""
        images = MappingProxyType({k: v.copy() for k, v in self._images.items()})
        return ScanResult(images, MappingProxyType(self._units_of(self.mode)), self._lines_done,
                          self._crashed, self._stopped, self.settings.pixel_size,
                          self.settings.pixel_size_y, self.sample.name, self._metadata,
                          self._first_row)

    def position(self, row: int, column: int, direction: str = "trace") -> tuple[float, float]:
        """Where the apex is on the sample at a pixel, in m from the sample's first pixel.

        Parameters
        ----------
        row, column : int
            The pixel.
        direction : {"trace", "retrace"}
            The pass.

        Returns
        -------
        tuple of float
            (x, y) in m (drift and creep included).
        """
        s = self.settings
        row = check_integer("row", row, 0, s.lines - 1)
        column = check_integer("column", column, 0, s.pixels - 1)
        check_choice("direction", direction, DIRECTIONS)
        x, y, _ = self._positions[direction]
        return float(x[row, column]), float(y[row, column])


def scan(sample: Sample, tip: Tip | None, mode: Mode, settings: ScanSettings) -> ScanResult:
    """Scan a sample to the end (or until the tip crashes).

    Parameters
    ----------
    sample : afmsmiler.samples.Sample
        The sample (2-D, heights in m).
    tip : afmsmiler.contact.Tip or None
        The tip (None: ideal).
    mode : afmsmiler.imaging.scan_modes.Mode
        The imaging mode.
    settings : ScanSettings
        The scan settings.

    Returns
    -------
    ScanResult
    """
    return Scan(sample, tip, mode, settings).run()

