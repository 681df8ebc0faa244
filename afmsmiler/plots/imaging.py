"""Figures of module (f): an AFM image forming line by line, as the virtual scan runs.

:func:`scan_view` reads a scan's result (a :class:`~afmsmiler.imaging.scanner.ScanResult`, or
an acquisition's :class:`~afmsmiler.acquisition.Snapshot`: full images per channel and
``lines_done``) into a :class:`ScanView` in the units shown: the main image (the height channel of a
constant-force scan, the deflection of a constant-height one) with the rows not scanned yet set
to NaN (drawn transparent), the error channel, and the trace and retrace of the last finished line.
Values in m are shown in nm and forces in nN; positions in um (nm for a scan under 1 um);
every factor comes from :data:`afmsmiler.parameters.UNITS`. Nothing here computes physics.

:class:`ImagingFigure` draws a view once and :meth:`ImagingFigure.update` swaps the data in
place (images with colour bars, two profiles), so that a panel never creates artists while the
scan runs and :func:`afmsmiler.plots.live.describe` can send each line's frame to the browser.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import matplotlib
import numpy as np
from matplotlib.figure import Figure

from ..parameters import UNITS, read_only, unit_scale
from ..validation import check_choice, check_instance, check_integer
from .limits import data_range, hold

__all__ = ["FIGSIZE", "DISPLAY_UNITS", "ScanView", "scan_view", "ImagingFigure",
           "main_channel", "error_channel", "side_channel", "crash_note", "length_unit",
           "images_figure"]

#: Figure size in inches (10 in: JupyterLab's output area is about 1000 px wide).
FIGSIZE = (10.0, 7.0)

#: SI unit of a channel -> the unit it is shown in (a unit not listed is shown as it is).
DISPLAY_UNITS = read_only({"m": "nm", "N": "nN"})

#: The height channel of a constant-force scan, then the others that make a main image.
_MAIN = ("height trace", "deflection trace")
_ERROR = ("error trace", "deflection trace")


def main_channel(channels) -> str:
    """The channel a scan's image shows: its height, else its deflection, else the first trace.

    Parameters
    ----------
    channels : mapping
        Channel name -> Sample (e.g. ``"height trace"``, ``"error retrace"``).

    Returns
    -------
    str

    Raises
    ------
    ValueError
        If there is no channel.
    """
    names = list(channels)
    if not names:
        raise ValueError("channels must hold at least one channel, got none")
    for name in _MAIN:
        if name in channels:
            return name
    return next((n for n in names if n.endswith(" trace")), names[0])


def error_channel(channels, main: str) -> str | None:
    """The channel shown beside the image: the error (deflection) signal, or None.

    Parameters
    ----------
    channels : mapping
        Channel name -> Sample.
    main : str
        The main channel (never returned).

    Returns
    -------
    str or None
    """
    return next((n for n in _ERROR if n in channels and n != main), None)


def side_channel(channels, main: str) -> str | None:
    """The channel shown beside the image: the error signal, else the main channel's retrace.

    A constant-height scan has no error channel (its deflection, the main image, is the error
    signal); beside it the retrace shows what trace and retrace disagree on, where an empty
    "no error channel" axes stood.

    Parameters
    ----------
    channels : mapping
        Channel name -> Sample.
    main : str
        The main channel (never returned).

    Returns
    -------
    str or None
        None if there is neither.
    """
    err = error_channel(channels, main)
    if err is not None:
        return err
    twin = main.replace("trace", "retrace") if main.endswith(" trace") else None
    return twin if twin in channels else None


def crash_note(crash) -> str:
    """A crash said in words and the units shown, lines and pixels counted from 1.

    Parameters
    ----------
    crash : Crash or object
        A :class:`~afmsmiler.imaging.scan_modes.Crash` (``row``, ``column``, ``force`` in N,
        ``direction``); anything else is shown as its text.

    Returns
    -------
    str
        E.g. ``"tip crashed: 120 nN on line 4 (trace), pixel 17"``.

    Examples
    --------
    >>> from afmsmiler.imaging.scan_modes import Crash
    >>> crash_note(Crash(3, 16, 1.2e-7, "retrace"))
    'tip crashed: 120 nN on line 4 (retrace), pixel 17'
    >>> crash_note(Crash(0, 0, float("inf")))
    'tip crashed: tip buried (force without bound) on line 1 (trace), pixel 1'
    """
    if not all(hasattr(crash, a) for a in ("row", "column", "force")):
        return f"crashed: {crash}"
    force = float(crash.force)
    shown, factor = _value_unit("N")
    how = (f"{force * factor:.3g} {shown}" if math.isfinite(force)
           else "tip buried (force without bound)")
    return (f"tip crashed: {how} on line {int(crash.row) + 1} "
            f"({getattr(crash, 'direction', 'trace')}), pixel {int(crash.column) + 1}")


def length_unit(extent: float) -> str:
    """The unit positions are shown in: ``"um"`` from 1 um of scan on, ``"nm"`` below.

    Parameters
    ----------
    extent : float
        The larger side of the scanned area in m.

    Returns
    -------
    str
    """
    return "um" if extent >= UNITS["um"][1] else "nm"


def _value_unit(unit: str) -> tuple[str, float]:
    """The display unit of a channel's SI ``unit`` and its factor (value shown per SI value)."""
    shown = DISPLAY_UNITS.get(unit)
    if shown is None:
        return unit, 1.0
    return shown, unit_scale(shown, unit)


@dataclass(frozen=True)
class ScanView:
    """What :class:`ImagingFigure` draws, in the units shown.

    Attributes
    ----------
    image : numpy.ndarray
        The main channel, shape (lines, pixels), rows not scanned yet NaN.
    image_label : str
        Its name and unit, e.g. ``"height trace [nm]"``.
    error : numpy.ndarray
        The channel shown beside the image (:func:`side_channel`: the error channel, else the
        main channel's retrace), same shape (all NaN if the scan has neither).
    error_label : str
        Its name and unit, or ``"no error channel"``.
    error_is_retrace : bool
        ``error`` is the main channel's retrace (shown on the main image's colour scale).
    extent : tuple of float
        (left, right, bottom, top) of the image in ``length_unit`` (pixel edges).
    length_unit : str
        ``"um"`` or ``"nm"``.
    x : numpy.ndarray
        Pixel positions along the fast axis in ``length_unit``.
    trace, retrace : numpy.ndarray
        The main channel's last finished line, trace and retrace (both in increasing x), NaN
        before the first line.
    value_unit : str
        The unit of ``image``, ``trace`` and ``retrace``.
    row : int or None
        Index of the last finished line (None before the first); titles count lines from 1.
    lines_done : int
        Lines finished.
    lines : int
        Lines of the whole scan.
    status : str
        ``""``, ``"stopped"`` or the crash message (:func:`crash_note`).
    """

    image: np.ndarray
    image_label: str
    error: np.ndarray
    error_label: str
    extent: tuple
    length_unit: str
    x: np.ndarray
    trace: np.ndarray
    retrace: np.ndarray
    value_unit: str
    row: int | None
    lines_done: int
    lines: int
    status: str = ""
    error_is_retrace: bool = False


def _shown_rows(sample, lines_done: int, factor: float) -> np.ndarray:
    """The sample's values times ``factor``, rows from ``lines_done`` on set to NaN."""
    values = np.array(sample.heights, dtype=float, copy=True)
    if values.ndim == 1:
        values = values[np.newaxis, :]
    values[lines_done:] = np.nan
    return values * factor


@dataclass(frozen=True)
class _Channel:
    """One channel of a scan's full image (rows not scanned NaN), as :func:`scan_view` reads it."""

    heights: np.ndarray
    pixel_size: float
    pixel_size_y: float
    unit: str


def _full_images(result) -> dict:
    """Channel name -> its full image: a ScanResult's ``images`` (all lines, NaN where none was
    scanned), else ``channels`` (already the full image, e.g. the imaging panel's)."""
    images = getattr(result, "images", None)
    if images is None:
        if not isinstance(getattr(result, "channels", None), dict):
            raise TypeError(f"result must be a ScanResult (or hold its channels), got "
                            f"{type(result).__name__} {result!r:.60}")
        return dict(result.channels)
    units = getattr(result, "units", {})
    return {name: _Channel(np.asarray(a, dtype=float), float(result.pixel_size),
                           float(result.pixel_size_y), units.get(name, "m"))
            for name, a in images.items()}


def scan_view(result, *, main: str | None = None, status: str | None = None) -> ScanView:
    """Read a scan's result (at any time during the scan) into the units shown.

    Parameters
    ----------
    result : ScanResult
        A :class:`~afmsmiler.imaging.scanner.ScanResult` (its full ``images`` with their
        ``units`` and pixel sizes are read), or any object whose ``channels`` map channel names
        to the full images (``heights`` of shape (lines, pixels) in the channel's SI ``unit``,
        ``pixel_size`` and ``pixel_size_y`` in m). ``result.lines_done`` is the number of
        finished lines (rows 0 to ``lines_done - 1``; rows never scanned are NaN). ``crashed``
        and ``stopped`` are read if present.
    main : str, optional
        The channel to show as the image (default :func:`main_channel`); its ``" retrace"``
        twin gives the retrace profile.
    status : str, optional
        A note for the title; default from ``result.crashed`` / ``result.stopped``.

    Returns
    -------
    ScanView

    Raises
    ------
    ValueError
        If ``main`` is not a channel, or ``lines_done`` is not in [0, lines].
    """
    if status is not None:
        check_instance("status", status, str)
    channels = _full_images(result)
    main = main_channel(channels) if main is None else check_choice("main", main, list(channels))
    image = channels[main]
    shape = np.shape(image.heights)
    rows, cols = (1, shape[0]) if len(shape) == 1 else shape
    done = check_integer("lines_done", result.lines_done, 0, rows)
    unit, factor = _value_unit(getattr(image, "unit", "m"))
    dx = float(image.pixel_size)
    dy = float(getattr(image, "pixel_size_y", None) or dx)
    lu = length_unit(max(cols * dx, rows * dy))
    k = unit_scale(lu, "m")
    values = _shown_rows(image, done, factor)
    x = np.arange(cols) * dx * k
    extent = (-0.5 * dx * k, (cols - 0.5) * dx * k, -0.5 * dy * k, (rows - 0.5) * dy * k)
    row = done - 1 if done else None
    trace = values[row] if row is not None else np.full(cols, np.nan)
    twin = main.replace("trace", "retrace") if main.endswith("trace") else None
    if twin in channels and row is not None:
        retrace = _shown_rows(channels[twin], done, factor)[row]
    else:
        retrace = np.full(cols, np.nan)
    err_name = side_channel(channels, main)
    if err_name is None:
        error, error_label = np.full((rows, cols), np.nan), "no error channel"
    else:
        e_unit, e_factor = _value_unit(getattr(channels[err_name], "unit", "m"))
        error = _shown_rows(channels[err_name], done, e_factor)
        error_label = f"{err_name} [{e_unit}]"
    if status is None:
        crashed = getattr(result, "crashed", None)
        status = (crash_note(crashed) if crashed is not None else
                  "stopped" if getattr(result, "stopped", False) else "")
    return ScanView(values, f"{main} [{unit}]", error, error_label, extent, lu, x, trace,
                    retrace, unit, row, done, rows, status,
                    err_name is not None and err_name == twin)


def _clim(values) -> tuple[float, float]:
    """Colour limits: the finite values' range (a flat image gets a small span; none: 0..1)."""
    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v)]
    if not v.size:
        return 0.0, 1.0
    lo, hi = float(v.min()), float(v.max())
    if hi - lo <= 1e-12 * max(abs(lo), abs(hi), 1e-30):
        pad = max(abs(lo) * 1e-3, 1e-3)
        return lo - pad, hi + pad
    return lo, hi


class ImagingFigure:
    """The image forming (with its colour bar), the error image, the last line's profiles.

    Parameters
    ----------
    view : ScanView
        The first view (from :func:`scan_view`).
    fig : matplotlib.figure.Figure, optional
        Where to draw (a panel's); default a new Figure of :data:`FIGSIZE`.
    cmap : str
        Colour map of the main image (``"afmhot"``, as image software shows heights).

    Attributes
    ----------
    fig : matplotlib.figure.Figure
    axes : dict
        ``"image"``, ``"error"``, ``"profile"`` -> Axes.
    images : dict
        ``"image"``, ``"error"`` -> AxesImage.
    lines : dict
        ``"trace"``, ``"retrace"`` -> Line2D; ``"row"`` -> the marker of the last line.
    colorbars : dict
        ``"image"``, ``"error"`` -> Colorbar.
    """

    #: Colour map of the error channel (diverging: zero error in its middle).
    ERROR_CMAP = "RdBu_r"

    def __init__(self, view: ScanView, fig: Figure | None = None, cmap: str = "afmhot"):
        check_instance("view", view, ScanView)
        if not isinstance(cmap, str) or cmap not in matplotlib.colormaps:
            raise ValueError(f"cmap must be a matplotlib colormap name (e.g. 'afmhot'), got "
                             f"{cmap!r:.60}")
        self.fig = (check_instance("fig", fig, Figure) if fig is not None
                    else Figure(figsize=FIGSIZE))
        self.fig.set_layout_engine("constrained")
        grid = self.fig.add_gridspec(2, 2, height_ratios=(3, 2))
        ax = self.axes = dict(image=self.fig.add_subplot(grid[0, 0]),
                              error=self.fig.add_subplot(grid[0, 1]),
                              profile=self.fig.add_subplot(grid[1, :]))
        self.images, self.colorbars = {}, {}
        self.cmap = cmap
        for key, cm in (("image", cmap), ("error", self.ERROR_CMAP)):
            self.images[key] = ax[key].imshow(np.full((2, 2), np.nan), origin="lower",
                                              cmap=cm, interpolation="nearest",
                                              extent=(0, 1, 0, 1), vmin=0, vmax=1)
            self.colorbars[key] = self.fig.colorbar(self.images[key], ax=ax[key], shrink=0.9)
        self.lines = {}
        self.lines["trace"], = ax["profile"].plot([], [], color="C0", label="trace")
        self.lines["retrace"], = ax["profile"].plot([], [], color="C3", ls="--",
                                                    label="retrace")
        # the last finished line, marked on the image (a horizontal line at its y)
        self.lines["row"], = ax["image"].plot([], [], color="C2", lw=1.0)
        ax["profile"].legend(loc="upper right", fontsize="small")
        self.update(view)

    def update(self, view: ScanView) -> None:
        """Show a new view: set the images, colour scales, profiles and titles (no new artists).

        The profile's y axis holds its limits while the lines stay inside them
        (:func:`~afmsmiler.plots.limits.hold`), so that line after line the eye compares
        them on one scale; the images' colour scales span the finished lines (the error's
        symmetric about zero, the middle of its diverging colour map).

        Parameters
        ----------
        view : ScanView
            From :func:`scan_view`.
        """
        v = view
        ax = self.axes
        lu = "um" if v.length_unit == "um" else "nm"
        # a retrace beside its trace shares its colour map and scale, so that the eye compares
        shared = _clim(np.r_[v.image.ravel(), v.error.ravel()]) if v.error_is_retrace else None
        for key, values, label in (("image", v.image, v.image_label),
                                   ("error", v.error, v.error_label)):
            im = self.images[key]
            im.set_data(np.ma.masked_invalid(values))
            im.set_extent(v.extent)
            lo, hi = _clim(values) if shared is None else shared
            if key == "error":
                cmap = self.cmap if v.error_is_retrace else self.ERROR_CMAP
                if im.get_cmap().name != cmap:
                    im.set_cmap(cmap)
                    self.colorbars[key].update_normal(im)
                if not v.error_is_retrace:  # a diverging map: zero error in its middle
                    lo, hi = -max(abs(lo), abs(hi)), max(abs(lo), abs(hi))
            im.set_clim(lo, hi)
            self.colorbars[key].set_label(label)
            # no channel (yet): an empty bar shows no scale
            self.colorbars[key].ax.yaxis.set_visible(label.endswith("]"))
            ax[key].set(xlim=v.extent[:2], ylim=v.extent[2:], xlabel=f"x [{lu}] (fast axis)",
                        ylabel=f"y [{lu}]")
        name = v.image_label.rsplit(" [", 1)[0]
        progress = f"line {v.lines_done} of {v.lines}"  # lines counted from 1, as in the profile
        ax["image"].set_title(f"{name}: {progress}" + (f"; {v.status}" if v.status else ""))
        ax["error"].set_title(v.error_label.rsplit(" [", 1)[0])
        if v.row is None:
            self.lines["row"].set_data([], [])
        else:
            y = v.extent[2] + (v.row + 0.5) * (v.extent[3] - v.extent[2]) / v.lines
            self.lines["row"].set_data(list(v.extent[:2]), [y, y])
        self.lines["trace"].set_data(v.x, v.trace)
        self.lines["retrace"].set_data(v.x, v.retrace)
        p = ax["profile"]
        p.set_xlim(v.extent[0], v.extent[1])
        quantity = name.removesuffix(" trace")  # trace and retrace share the axis
        p.set(xlabel=f"x [{lu}]", ylabel=f"{quantity} [{v.value_unit}]",
              title="last line" if v.row is None else f"line {v.row + 1}: trace and retrace")
        # a new quantity on the axis (another channel) is fitted afresh
        reset = getattr(self, "_held", None) != v.image_label
        lo, hi = data_range(v.trace, v.retrace)
        if math.isfinite(lo):
            hold(p, "y", lo, hi, reset=reset, floor=1e-3)
            self._held = v.image_label


def images_figure(*images, titles=None, cmap: str = "afmhot", fig: Figure | None = None) -> Figure:
    """Images side by side, each with its colour bar (values in nm for m), axes in um or nm.

    A static figure for the notebook (a sample, its dilation, a levelled copy ...); each image
    keeps its own colour scale.

    Parameters
    ----------
    *images : Sample
        One to four 2-D samples (their ``unit``, default m, decides the colour bar's unit).
    titles : sequence of str, optional
        One per image; default the samples' names.
    cmap : str
        Colour map.
    fig : matplotlib.figure.Figure, optional
        Where to draw; default a new Figure 10 in wide.

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ValueError
        If no image, more than four, a 1-D one, or a number of titles that does not match.
    """
    if not 1 <= len(images) <= 4:
        raise ValueError(f"images must be 1 to 4 samples, got {len(images)}")
    titles = [getattr(im, "name", "") for im in images] if titles is None else list(titles)
    if len(titles) != len(images):
        raise ValueError(f"titles must give one title per image ({len(images)}), got "
                         f"{len(titles)}")
    fig = (check_instance("fig", fig, Figure) if fig is not None
           else Figure(figsize=(10.0, 10.0 / max(len(images), 2) + 0.6)))
    fig.set_layout_engine("constrained")
    axes = fig.subplots(1, len(images), squeeze=False)[0]
    for ax, image, title in zip(axes, images, titles):
        values = np.asarray(image.heights, dtype=float)
        if values.ndim != 2:
            raise ValueError(f"images must be 2-D, got an array of shape {values.shape}")
        unit, factor = _value_unit(getattr(image, "unit", "m"))
        rows, cols = values.shape
        dx = float(image.pixel_size)
        dy = float(getattr(image, "pixel_size_y", None) or dx)
        lu = length_unit(max(cols * dx, rows * dy))
        k = unit_scale(lu, "m")
        shown = values * factor
        im = ax.imshow(np.ma.masked_invalid(shown), origin="lower", cmap=cmap,
                       interpolation="nearest", extent=(-0.5 * dx * k, (cols - 0.5) * dx * k,
                                                        -0.5 * dy * k, (rows - 0.5) * dy * k))
        im.set_clim(*_clim(shown))
        channel = getattr(image, "channel", "height")
        fig.colorbar(im, ax=ax, shrink=0.6 if len(images) > 2 else 0.8,
                     label=f"{channel} [{unit}]")
        ax.set(title=title, xlabel=f"x [{lu}]", ylabel=f"y [{lu}]")
    return fig
