"""Static export of an AFM image: a PNG with a scale bar and, optionally, a colour bar.

:func:`save_png` draws a :class:`~afmsmiler.samples.Sample` as AFM software exports it
(Gwyddion's "Export to image": the image at a whole number of PNG pixels per image pixel, an
inset scale bar of a round length, a false-colour map such as ``"afmhot"``), with matplotlib's
Agg renderer (a static file, not a live figure). The first row of the image (y = 0) is at the
bottom and y grows upwards, as in the panel's live figure (:mod:`afmsmiler.plots.imaging`) and
the 3D view. :func:`scale_bar_length` picks the bar's round length.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import matplotlib
import numpy as np
from matplotlib import patheffects
from matplotlib.figure import Figure
from matplotlib.patches import Rectangle

from ..parameters import unit_scale
from ..samples import Sample
from ..validation import (check_flag, check_instance, check_integer, check_positive, check_range,
                          check_writable_path)

__all__ = ["PngExport", "save_png", "scale_bar_length", "scale_bar_label", "MAX_PNG_SIDE",
           "BAR_FRACTION"]

#: The longest side of an exported PNG in pixels.
MAX_PNG_SIDE = 4096
#: The scale bar is the longest round length (1, 2 or 5 x 10^n m) at most this fraction of the
#: image's width.
BAR_FRACTION = 0.3
_TARGET_SIDE = 512  # the default zoom makes the image's longest side at least about this
_DPI = 100
_BAR_COLOR = "white"


@dataclass(frozen=True)
class PngExport:
    """What :func:`save_png` wrote.

    Attributes
    ----------
    path : str
        The PNG file.
    size : (int, int)
        Its width and height in pixels.
    zoom : int
        PNG pixels per image pixel along x.
    bar_length : float or None
        Length of the scale bar in m (None without one).
    bar_label : str
        Its label, e.g. ``"200 nm"`` (empty without one).
    bar_pixels : float
        Its length in PNG pixels, ``bar_length / pixel_size * zoom`` (0 without one).
    """

    path: str
    size: tuple[int, int]
    zoom: int
    bar_length: float | None
    bar_label: str
    bar_pixels: float


def scale_bar_length(width: float, fraction: float = BAR_FRACTION) -> float:
    """The longest round length, 1, 2 or 5 x 10^n m, at most ``fraction`` of ``width``.

    Parameters
    ----------
    width : float
        Width of the image in m (> 0).
    fraction : float
        Largest share of the width the bar may take, in (0, 1].

    Returns
    -------
    float
        The length in m.

    Examples
    --------
    >>> scale_bar_length(1e-6)  # a 1 um image gets a 200 nm bar
    2e-07
    """
    width = check_positive("width", width, "m")
    fraction = check_range("fraction", fraction, 0.0, 1.0, low_inclusive=False)
    limit = width * fraction
    exponent = math.floor(math.log10(limit))
    best = 10.0 ** exponent
    for mantissa in (2.0, 5.0, 10.0):
        candidate = float(f"{mantissa}e{exponent}")  # the decimal, not a rounded product
        if candidate <= limit * (1 + 1e-12):
            best = candidate
    return float(f"{best:.1g}")


def scale_bar_label(length: float) -> str:
    """``length`` (m) written as a scale bar's label: in nm below 1 um, um below 1 mm, else mm.

    Parameters
    ----------
    length : float
        Length in m (> 0).

    Examples
    --------
    >>> scale_bar_label(2e-7), scale_bar_label(5e-6)
    ('200 nm', '5 µm')
    """
    length = check_positive("length", length, "m")
    unit = "nm" if length < 1e-6 else "um" if length < 1e-3 else "mm"
    value = float(f"{length * unit_scale(unit, 'm'):.6g}")
    shown = "µm" if unit == "um" else unit
    return f"{value:g} {shown}"


def _value_unit(sample: Sample):
    """(factor, unit label) to show the sample's values in: nm or um for heights."""
    if sample.unit != "m":
        return 1.0, sample.unit
    span = float(np.ptp(sample.heights)) or float(np.abs(sample.heights).max())
    display = "um" if span >= 1e-6 else "nm"
    return unit_scale(display, "m"), "µm" if display == "um" else display


def save_png(sample: Sample, path, *, scale_bar: bool = True, cmap: str = "afmhot",
             colorbar: bool = False, zoom: int | None = None) -> PngExport:
    """Write ``sample`` (an image) to a PNG file with a scale bar and optionally a colour bar.

    Every image pixel becomes ``zoom`` x ``zoom`` PNG pixels (``zoom`` x ``zoom`` times
    pixel_size_y / pixel_size for rectangular pixels), so the image keeps its aspect ratio and a
    length L spans L / pixel_size x zoom PNG pixels: that is how long the scale bar is drawn
    (white with a black rim, bottom left, labelled above), for the round length
    :func:`scale_bar_length` picks.
    The colour bar, on the right, is labelled with the channel and its unit (heights in nm or
    um).

    Parameters
    ----------
    sample : Sample
        An image (2-D values).
    path : str or os.PathLike
        The PNG file to write, in an existing folder (replaced if it exists).
    scale_bar : bool
        Draw the scale bar.
    cmap : str
        A matplotlib colormap name (``"afmhot"``, AFM software's usual map).
    colorbar : bool
        Add a colour bar to the right of the image.
    zoom : int, optional
        PNG pixels per image pixel, 1 up to what keeps the PNG within :data:`MAX_PNG_SIDE`;
        default the smallest that makes the longest side at least 512 pixels.

    Returns
    -------
    PngExport
        The file, its size and the scale bar drawn.

    Raises
    ------
    ValueError
        If ``sample`` is not an image, ``cmap`` is unknown, ``zoom`` is out of range or the path
        cannot be written (the message names the path and the reason).
    """
    check_instance("sample", sample, Sample)
    h = sample.heights
    if h.ndim != 2:
        raise ValueError(f"sample must be an image (2-D heights), got shape {h.shape}")
    path = check_writable_path("path", path, "a PNG file")
    try:
        colormap = matplotlib.colormaps[cmap]
    except (KeyError, TypeError):
        raise ValueError(f"cmap must be a matplotlib colormap name, got {cmap!r}") from None
    scale_bar, colorbar = check_flag("scale_bar", scale_bar), check_flag("colorbar", colorbar)
    rows, cols = h.shape
    aspect = sample.pixel_size_y / sample.pixel_size
    longest = max(cols, rows * aspect)
    if longest > MAX_PNG_SIDE:
        raise ValueError(f"sample would need a PNG of {cols} x {rows * aspect:.0f} pixels at its "
                         f"pixel sizes ({sample.pixel_size:.3g} m x {sample.pixel_size_y:.3g} m); "
                         f"at most {MAX_PNG_SIDE} per side: resample it first")
    max_zoom = max(1, int(MAX_PNG_SIDE // longest))
    if zoom is None:
        zoom = min(max_zoom, max(1, math.ceil(_TARGET_SIDE / longest)))
    zoom = check_integer("zoom", zoom, 1, max_zoom)
    width_px = cols * zoom
    height_px = max(1, round(rows * aspect * zoom))
    bar_strip = 0
    if colorbar:
        bar_strip = max(90, width_px // 5)
    fig_w, fig_h = width_px + bar_strip, height_px
    fig = Figure(figsize=(fig_w / _DPI, fig_h / _DPI), dpi=_DPI)
    ax = fig.add_axes((0.0, 0.0, width_px / fig_w, 1.0))
    ax.set_axis_off()
    factor, unit = _value_unit(sample)
    image = ax.imshow(h * factor, cmap=colormap, interpolation="nearest", origin="lower",
                      aspect=aspect)
    ax.set_xlim(-0.5, cols - 0.5)
    ax.set_ylim(-0.5, rows - 0.5)
    font_px = max(10.0, 0.045 * height_px)
    length, label, bar_px = None, "", 0.0
    if scale_bar:
        width = cols * sample.pixel_size
        length = scale_bar_length(width)
        label = scale_bar_label(length)
        bar_px = length / sample.pixel_size * zoom
        # in image pixels (data units): a margin of 4 % of the width from the lower-left corner
        margin = round(0.04 * cols * zoom) / zoom
        thick = max(2.0, round(0.012 * height_px)) / (zoom * aspect)
        x0 = -0.5 + margin
        y0 = -0.5 + margin / aspect
        rim_x, rim_y = 1.0 / zoom, 1.0 / (zoom * aspect)  # one PNG pixel of black around it
        ax.add_patch(Rectangle((x0 - rim_x, y0 - rim_y), length / sample.pixel_size + 2 * rim_x,
                               thick + 2 * rim_y, facecolor="black", edgecolor="none",
                               antialiased=False))
        ax.add_patch(Rectangle((x0, y0), length / sample.pixel_size, thick,
                               facecolor=_BAR_COLOR, edgecolor="none", antialiased=False))
        above = y0 + thick + 0.3 * font_px / (zoom * aspect)
        text = ax.text(x0 + 0.5 * length / sample.pixel_size, above, label, color=_BAR_COLOR,
                       ha="center", va="bottom", fontsize=font_px * 72 / _DPI)
        text.set_path_effects([patheffects.withStroke(linewidth=2, foreground="black")])
    if colorbar:
        cax = fig.add_axes((width_px / fig_w + 0.12 * bar_strip / fig_w, 0.08,
                            0.12 * bar_strip / fig_w, 0.84))
        bar = fig.colorbar(image, cax=cax)
        channel = sample.channel or "height"
        bar.set_label(f"{channel} [{unit}]" if unit else channel, fontsize=font_px * 0.6)
        bar.ax.tick_params(labelsize=font_px * 0.5)
    try:
        fig.savefig(path, dpi=_DPI, format="png")
    except OSError as err:
        raise ValueError(f"path {path!r} cannot be written: {err.strerror or err}") from None
    return PngExport(path, (fig_w, fig_h), zoom, length, label, bar_px)
