"""Figures of module (h), part 1: the macroscopic AFM's image forming, and a print compared.

Heights are shown as *relief*, in um above the lowest point: the machine's z zero is its home
position, millimetres above the bed, so its raw heights of a 2 mm print read 6 to 8 mm; the
scan's relief above its lowest pixel and the print's above its lowest point read the same.

The macroscopic AFM images mm-sized printed objects with um-sized z micro-steps, so its figure
shows positions in mm and heights in um (module (f)'s :mod:`~afmsmiler.plots.imaging` shows nm
and um); every factor comes from :data:`afmsmiler.parameters.UNITS`. Nothing here computes
physics: :func:`macro_view` reads the panel's image (pixels streamed so far, NaN elsewhere) and
:func:`comparison_view` a :class:`~afmsmiler.hardware.printing.PrintComparison`.

:class:`MacroFigure` draws, top row: the height image forming, the strain gauge's image, the
last line's height profile; bottom row: the printed surface, the scan of it, their difference
(with its RMS against the z micro-step). :meth:`MacroFigure.update` swaps the data in place.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from matplotlib.figure import Figure

from ..parameters import unit_scale
from ..hardware.printing import PrintComparison
from ..validation import check_instance, check_integer, check_real
from .imaging import _clim
from .limits import data_range, hold

__all__ = ["FIGSIZE", "LENGTH_UNIT", "HEIGHT_UNIT", "MacroView", "macro_view",
           "ComparisonView", "comparison_view", "MacroFigure", "scans_figure", "modes_figure"]

#: Figure size in inches (JupyterLab's output area is about 1000 px wide).
FIGSIZE = (10.0, 7.5)
#: Positions are shown in mm, heights in um.
LENGTH_UNIT, HEIGHT_UNIT = "mm", "um"


@dataclass(frozen=True)
class MacroView:
    """What the top row shows, in the units shown.

    Attributes
    ----------
    height : numpy.ndarray
        Heights in um above the lowest pixel streamed so far (the machine's z zero is its home,
        not the bed: so the scan reads as the print's relief, as the bottom row's print and
        scan do), shape (lines, pixels), pixels not streamed yet NaN.
    gauge : numpy.ndarray
        Strain-gauge counts at each pixel, same shape.
    extent : tuple of float
        (left, right, bottom, top) in mm (pixel edges).
    x : numpy.ndarray
        Pixel positions along the fast axis in mm.
    profile : numpy.ndarray
        Heights in um of the line being scanned (or the last finished one), on the same zero.
    row : int or None
        That line's index (None before the first pixel).
    pixels_done : int
        Pixels streamed so far.
    pixels : int
        Pixels of the whole image.
    status : str
        A note for the title ("paused", "aborted", a fault, ...).
    """

    height: np.ndarray
    gauge: np.ndarray
    extent: tuple
    x: np.ndarray
    profile: np.ndarray
    row: int | None
    pixels_done: int
    pixels: int
    status: str = ""


def macro_view(height, gauge, pitch: float, pixels_done: int, status: str = "") -> MacroView:
    """Read the panel's image so far into the units shown.

    Parameters
    ----------
    height : array_like
        Heights in m, shape (lines, pixels), NaN where no pixel came yet.
    gauge : array_like
        Gauge counts, same shape, NaN where no pixel came yet.
    pitch : float
        Pixel spacing along both axes in m.
    pixels_done : int
        Pixels streamed so far (row-major order: the current row is ``pixels_done // pixels``).
    status : str
        A note for the title.

    Returns
    -------
    MacroView
    """
    h = np.asarray(height, dtype=float)
    g = np.asarray(gauge, dtype=float)
    if h.ndim != 2 or g.shape != h.shape:
        raise ValueError(f"height and gauge must be 2-D arrays of one shape, got {h.shape} and "
                         f"{g.shape}")
    rows, cols = h.shape
    done = check_integer("pixels_done", pixels_done, 0, rows * cols)
    k, kz = unit_scale(LENGTH_UNIT, "m"), unit_scale(HEIGHT_UNIT, "m")
    d = float(pitch) * k
    extent = (-0.5 * d, (cols - 0.5) * d, -0.5 * d, (rows - 0.5) * d)
    row = None if done == 0 else min((done - 1) // cols, rows - 1)
    if np.isfinite(h).any():
        h = h - np.nanmin(h)                 # heights above the lowest pixel streamed so far
    profile = h[row] * kz if row is not None else np.full(cols, np.nan)
    return MacroView(h * kz, g, extent, np.arange(cols) * d, profile, row, done, rows * cols,
                     status)


@dataclass(frozen=True)
class ComparisonView:
    """What the bottom row shows, in the units shown (heights in um, positions in mm).

    Attributes
    ----------
    reference, image, difference : numpy.ndarray
        The printed surface, the scan and their difference (offsets removed).
    extent : tuple of float
        (left, right, bottom, top) in mm.
    rms : float
        RMS of the difference in um (NaN before a comparison).
    z_step : float
        The z micro-step in um (NaN if unknown), for the title.
    """

    reference: np.ndarray
    image: np.ndarray
    difference: np.ndarray
    extent: tuple
    rms: float
    z_step: float = math.nan


def comparison_view(comparison=None, z_step: float = math.nan) -> ComparisonView:
    """Read a print comparison (or nothing yet) into the units shown.

    Parameters
    ----------
    comparison : PrintComparison, optional
        From :func:`afmsmiler.hardware.printing.compare_scan`; None gives empty images.
    z_step : float
        The machine's z micro-step in m, for the title.

    Returns
    -------
    ComparisonView
    """
    z_step = check_real("z_step", z_step)  # NaN: not known yet
    kz = unit_scale(HEIGHT_UNIT, "m")
    if comparison is not None:
        check_instance("comparison", comparison, PrintComparison)
    if comparison is None:
        empty = np.full((2, 2), np.nan)
        return ComparisonView(empty, empty, empty, (0.0, 1.0, 0.0, 1.0), math.nan,
                              z_step * kz)
    k = unit_scale(LENGTH_UNIT, "m")
    rows, cols = comparison.image.shape
    dx, dy = comparison.image.pixel_size * k, comparison.image.pixel_size_y * k
    extent = (-0.5 * dx, (cols - 0.5) * dx, -0.5 * dy, (rows - 0.5) * dy)
    return ComparisonView(comparison.reference.heights * kz, comparison.image.heights * kz,
                          comparison.difference.heights * kz, extent, comparison.rms * kz,
                          z_step * kz)


class MacroFigure:
    """The macroscopic AFM's image forming (top) and a print compared with its scan (bottom).

    Parameters
    ----------
    view : MacroView
        The first view of the top row (:func:`macro_view`).
    comparison : ComparisonView, optional
        The first view of the bottom row (default: empty, :func:`comparison_view`).
    fig : matplotlib.figure.Figure, optional
        Where to draw (a panel's); default a new Figure of :data:`FIGSIZE`.

    Attributes
    ----------
    fig : matplotlib.figure.Figure
    axes : dict
        ``"height"``, ``"gauge"``, ``"profile"``, ``"reference"``, ``"image"``,
        ``"difference"`` -> Axes.
    images : dict
        The same keys but ``"profile"`` -> AxesImage.
    lines : dict
        ``"profile"`` -> Line2D; ``"row"`` -> the marker of the current line on the image.
    """

    _IMAGES = (("height", "afmhot", f"relief [{HEIGHT_UNIT}]"),
               ("gauge", "viridis", "gauge [counts]"),
               ("reference", "afmhot", f"print's relief [{HEIGHT_UNIT}]"),
               ("image", "afmhot", f"scan's relief [{HEIGHT_UNIT}]"),
               ("difference", "RdBu_r", f"scan - print [{HEIGHT_UNIT}]"))

    def __init__(self, view: MacroView, comparison: ComparisonView | None = None,
                 fig: Figure | None = None):
        check_instance("view", view, MacroView)
        if comparison is not None:
            check_instance("comparison", comparison, ComparisonView)
        self.fig = (check_instance("fig", fig, Figure) if fig is not None
                    else Figure(figsize=FIGSIZE))
        self.fig.set_layout_engine("constrained")
        grid = self.fig.add_gridspec(2, 3)
        self.axes = {"height": self.fig.add_subplot(grid[0, 0]),
                     "gauge": self.fig.add_subplot(grid[0, 1]),
                     "profile": self.fig.add_subplot(grid[0, 2]),
                     "reference": self.fig.add_subplot(grid[1, 0]),
                     "image": self.fig.add_subplot(grid[1, 1]),
                     "difference": self.fig.add_subplot(grid[1, 2])}
        self.images, self.colorbars = {}, {}
        for key, cmap, label in self._IMAGES:
            ax = self.axes[key]
            self.images[key] = ax.imshow(np.full((2, 2), np.nan), origin="lower", cmap=cmap,
                                         interpolation="nearest", extent=(0, 1, 0, 1), vmin=0,
                                         vmax=1)
            self.colorbars[key] = self.fig.colorbar(self.images[key], ax=ax, shrink=0.8,
                                                    label=label)
            ax.set(xlabel=f"x [{LENGTH_UNIT}]", ylabel=f"y [{LENGTH_UNIT}]")
        self.lines = {}
        self.lines["profile"], = self.axes["profile"].plot([], [], color="C0")
        self.lines["row"], = self.axes["height"].plot([], [], color="C2", lw=1.0)
        self.axes["profile"].set(xlabel=f"x [{LENGTH_UNIT}]",
                                 ylabel=f"relief [{HEIGHT_UNIT}]")
        self.update(view, comparison if comparison is not None else comparison_view())

    def _image(self, key: str, values, extent, symmetric: bool = False) -> None:
        im = self.images[key]
        im.set_data(np.ma.masked_invalid(values))
        im.set_extent(extent)
        lo, hi = _clim(values)
        if symmetric:
            lo, hi = -max(abs(lo), abs(hi)), max(abs(lo), abs(hi))
        im.set_clim(lo, hi)
        self.axes[key].set(xlim=extent[:2], ylim=extent[2:])

    def update(self, view: MacroView, comparison: ComparisonView | None = None) -> None:
        """Show a new view (and comparison, if given): data, colour scales, titles in place.

        Parameters
        ----------
        view : MacroView
            From :func:`macro_view`.
        comparison : ComparisonView, optional
            From :func:`comparison_view`; None keeps the one shown.
        """
        v = view
        self._image("height", v.height, v.extent)
        self._image("gauge", v.gauge, v.extent)
        lines = v.height.shape[0]
        self.axes["height"].set_title(f"{v.pixels_done}/{v.pixels} px"
                                      + (f" ({v.status})" if v.status else ""))
        self.axes["gauge"].set_title("strain gauge")
        if v.row is None:
            self.lines["row"].set_data([], [])
        else:
            y = v.extent[2] + (v.row + 0.5) * (v.extent[3] - v.extent[2]) / lines
            self.lines["row"].set_data(list(v.extent[:2]), [y, y])
        self.lines["profile"].set_data(v.x, v.profile)
        p = self.axes["profile"]
        p.set_xlim(v.extent[0], v.extent[1])
        # lines counted from 1, as the panels of module (f) count them
        p.set_title("line" if v.row is None else f"line {v.row + 1} of {lines}")
        lo, hi = data_range(v.profile)
        if math.isfinite(lo):
            hold(p, "y", lo, hi, floor=1e-3)
        if comparison is None:
            return
        c = comparison
        for key, values in (("reference", c.reference), ("image", c.image)):
            self._image(key, values, c.extent)
        self._image("difference", c.difference, c.extent, symmetric=True)
        self.axes["reference"].set_title("print (as the needle follows it)")
        self.axes["image"].set_title("its scan")
        if math.isfinite(c.rms):
            step = f" (step {c.z_step:.3g})" if math.isfinite(c.z_step) else ""
            self.axes["difference"].set_title(f"RMS {c.rms:.3g} {HEIGHT_UNIT}{step}")
        else:
            self.axes["difference"].set_title("scan - print: scan a print")


def scans_figure(*images, titles=None, fig: Figure | None = None) -> Figure:
    """Macroscopic scans side by side (positions in mm, heights in um), each with a colour bar.

    A static figure for the notebook (contact vs jumping mode, a print vs its scan).

    Parameters
    ----------
    *images : Sample
        One to four 2-D height samples in m.
    titles : sequence of str, optional
        One per image; default the samples' names.
    fig : matplotlib.figure.Figure, optional
        Where to draw; default a new Figure 10 in wide.

    Returns
    -------
    matplotlib.figure.Figure
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
    k, kz = unit_scale(LENGTH_UNIT, "m"), unit_scale(HEIGHT_UNIT, "m")
    for ax, image, title in zip(axes, images, titles):
        values = np.asarray(image.heights, dtype=float)
        if values.ndim != 2:
            raise ValueError(f"images must be 2-D, got an array of shape {values.shape}")
        rows, cols = values.shape
        dx, dy = image.pixel_size * k, image.pixel_size_y * k
        im = ax.imshow(np.ma.masked_invalid(values * kz), origin="lower", cmap="afmhot",
                       interpolation="nearest",
                       extent=(-0.5 * dx, (cols - 0.5) * dx, -0.5 * dy, (rows - 0.5) * dy))
        im.set_clim(*_clim(values * kz))
        fig.colorbar(im, ax=ax, shrink=0.8, label=f"height [{HEIGHT_UNIT}]")
        ax.set(title=title, xlabel=f"x [{LENGTH_UNIT}]", ylabel=f"y [{LENGTH_UNIT}]")
    return fig


def modes_figure(*comparisons, labels, fig: Figure | None = None) -> Figure:
    """Scans of one print in several modes, each against the print: where and how they differ.

    Two scans of tall walls look alike at a colour scale of millimetres; their errors do not.
    Top row: each scan (on the print's zero, as :func:`~afmsmiler.hardware.printing.compare_scan`
    puts it); middle row: each scan minus the print, on one symmetric colour scale shared by
    all, titled with its RMS; bottom: the profile along the fast axis through the line where the
    largest error of all is, the print and each scan. Nothing is computed but the choice of that
    line.

    Parameters
    ----------
    *comparisons : PrintComparison
        One to three comparisons of scans with the same print, on the same grid.
    labels : sequence of str
        What each scan is (e.g. its mode), one per comparison.
    fig : matplotlib.figure.Figure, optional
        Where to draw; default a new Figure 10 in wide.

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ValueError
        For no or more than three comparisons, a label count that differs, or grids that differ.
    """
    if not 1 <= len(comparisons) <= 3:
        raise ValueError(f"comparisons must be 1 to 3, got {len(comparisons)}")
    labels = [str(label) for label in labels]
    if len(labels) != len(comparisons):
        raise ValueError(f"labels must give one label per comparison ({len(comparisons)}), got "
                         f"{len(labels)}")
    shape = comparisons[0].image.shape
    for c in comparisons[1:]:
        if c.image.shape != shape:
            raise ValueError(f"comparisons must be on one grid, got {shape} and "
                             f"{c.image.shape}")
    k, kz = unit_scale(LENGTH_UNIT, "m"), unit_scale(HEIGHT_UNIT, "m")
    first = comparisons[0].image
    rows, cols = shape
    dx, dy = first.pixel_size * k, first.pixel_size_y * k
    extent = (-0.5 * dx, (cols - 0.5) * dx, -0.5 * dy, (rows - 0.5) * dy)
    n = len(comparisons)
    fig = check_instance("fig", fig, Figure) if fig is not None else Figure(figsize=(10.0, 9.5))
    fig.set_layout_engine("constrained")
    grid = fig.add_gridspec(3, n, height_ratios=(1.0, 1.0, 0.8))
    heights = [c.image.heights * kz for c in comparisons]
    errors = [c.difference.heights * kz for c in comparisons]
    lo, hi = _clim(np.concatenate([h.ravel() for h in heights]))
    top = max(float(np.nanmax(np.abs(e))) for e in errors) or 1.0
    for i, (c, label) in enumerate(zip(comparisons, labels)):
        ax = fig.add_subplot(grid[0, i])
        im = ax.imshow(np.ma.masked_invalid(heights[i]), origin="lower", cmap="afmhot",
                       interpolation="nearest", extent=extent, vmin=lo, vmax=hi)
        fig.colorbar(im, ax=ax, shrink=0.8, label=f"relief [{HEIGHT_UNIT}]")
        ax.set(title=f"{label}: the scan", xlabel=f"x [{LENGTH_UNIT}]",
               ylabel=f"y [{LENGTH_UNIT}]")
        ax = fig.add_subplot(grid[1, i])
        im = ax.imshow(np.ma.masked_invalid(errors[i]), origin="lower", cmap="RdBu_r",
                       interpolation="nearest", extent=extent, vmin=-top, vmax=top)
        fig.colorbar(im, ax=ax, shrink=0.8, label=f"scan - print [{HEIGHT_UNIT}]")
        ax.set(title=f"{label}: scan - print, RMS {c.rms * kz:.3g} {HEIGHT_UNIT}",
               xlabel=f"x [{LENGTH_UNIT}]", ylabel=f"y [{LENGTH_UNIT}]")
    worst = max(range(n), key=lambda i: np.nanmax(np.abs(errors[i])))
    line = int(np.unravel_index(np.nanargmax(np.abs(errors[worst])), shape)[0])
    ax = fig.add_subplot(grid[2, :])
    x = np.arange(cols) * dx
    ax.plot(x, comparisons[0].reference.heights[line] * kz, color="black", lw=2.5, alpha=0.4,
            label="print (as the needle follows it)", drawstyle="steps-mid")
    for i, label in enumerate(labels):
        ax.plot(x, heights[i][line], lw=1.2, label=label, drawstyle="steps-mid")
    ax.set(title=f"line {line}, along the fast axis (the largest error)",
           xlabel=f"x [{LENGTH_UNIT}]", ylabel=f"relief [{HEIGHT_UNIT}]")
    ax.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize="small")
    return fig
