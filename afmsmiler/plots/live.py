"""Live figures: a panel's matplotlib figure drawn in the browser with uPlot, frame by frame.

A panel's figure classes (:mod:`afmsmiler.plots.cantilever` and the others) describe what to show
with matplotlib's artists and update them in place; that description is what tests read and what a
static page or the book renders with Agg. Rasterising it with Agg in the kernel at every slider move
and shipping a PNG took most of a second. :class:`LiveFigure` instead reads the artists
(:func:`describe`: lines, reference lines and spans, texts, titles, legends, images with their
colour bars, limits, log/symlog scales, twin and secondary axes, equal aspect, the grid of axes)
into a small JSON description and ONE binary buffer of float32 holding every curve and image, and
sends both in one comm message; the browser (``static/live.js``) draws them with uPlot, the small
fast charting library shipped in ``static/`` (fetched and hash-checked by ``tools/vendor_uplot.py``).

No physics here and none in the browser: every number comes from the figure's artists.

Artists this cannot show raise ``NotImplementedError`` naming them (nothing is dropped silently).

A line of many more points than its axes has pixel columns is sent as its per-column extremes
(:func:`decimate`): what the canvas draws is the same, the message a fraction (Q control's 20,804
points, 166 kB a frame, rasterised in 27-44 ms). The artists keep the full data (tests read it).

A panel's sliders reach the kernel as ipywidgets sends them: one update in flight, the moves made
meanwhile merged into the next (a quick drag of 15 key presses arrives as 4 to 6 updates, the
last one the value the student stopped at). The panel runs the model once for the moves that
queued while it was busy (:meth:`afmsmiler.ui.panel.Panel._move`), and the browser paints every
frame that comes back exactly once, one per animation frame.

Examples
--------
A module's panel (``Panel.redraw`` does this for every panel):

>>> from matplotlib.figure import Figure
>>> fig = Figure(figsize=(4, 3))
>>> line, = fig.add_subplot().plot([0.0, 1.0], [0.0, 1.0])
>>> live = LiveFigure(fig)           # display it as any widget
>>> line.set_ydata([0.0, 2.0])       # the figure class updates its artists ...
>>> d = live.sync()                  # ... and one message carries the new frame
>>> live.frames_sent, d.values(d.frame["axes"][0]["series"][0]["y"]).tolist()
(2, [0.0, 2.0])
"""
from __future__ import annotations

import base64
import json
import math
import time
import uuid
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import anywidget
import numpy as np
import traitlets
from matplotlib import colors as mcolors
from matplotlib.artist import Artist
from matplotlib.cm import ScalarMappable
from matplotlib.figure import Figure
from matplotlib.patches import Polygon, Rectangle
from matplotlib.ticker import FixedLocator

from ..validation import check_choice, check_finite, check_instance, check_integer, check_positive

__all__ = ["Description", "LiveFigure", "decimate", "describe", "static_html", "set_clim"]

STATIC = Path(__file__).with_name("static")
#: Seconds a panel waits at most for a view to say it painted a frame before it sends more than
#: :data:`FRAMES_AHEAD` ahead (:meth:`LiveFigure.busy`): a page whose main thread is saturated
#: (a drag) paints a frame in 20-40 ms, and the frames sent meanwhile queued behind each other,
#: each a step the student had already passed; a page that never answers costs no more than this.
PAINT_WAIT = 0.25
#: Frames a panel may have sent and not yet seen painted when it runs its next update
#: (:meth:`LiveFigure.busy`): one, so the model computes a drag's next step while the page
#: paints the last (waiting for that paint put a whole round trip, 20-40 ms, between the last
#: key's move reaching the kernel and its frame), and no more, so frames never queue in a page
#: slower than the model.
FRAMES_AHEAD = 1
#: Pixels per inch of a live figure (as ipympl's canvas): figsize (10, 6) is 1000 x 600 px.
DPI = 100
_PX = DPI / 72  # px per point (line widths, marker and font sizes are given in points)
#: Largest buffer one frame may send (float32 values): 4 M values, 16 MB, about 0.1 s on loopback.
MAX_VALUES = 4_000_000

_MARKERS = {"o", ".", "x", "+", "s", "D", "^", "v"}


@lru_cache(maxsize=None)
def _read(name: str) -> str:
    return (STATIC / name).read_text(encoding="utf-8")


def _esm() -> str:
    """The widget's module: uPlot's release file, then the renderer (one module, no network)."""
    return _read("uPlot.iife.min.js") + "\n" + _read("live.js")


def _css() -> str:
    return _read("uPlot.min.css") + "\n" + _read("live.css")


# -- reading the artists ------------------------------------------------------------------------

def _num(v) -> float | None:
    v = float(v)
    return v if math.isfinite(v) else None


def _color(c, alpha=None) -> str:
    """``c`` with ``alpha`` as #rrggbbaa (cached: a figure repeats a handful of colours)."""
    key = (tuple(np.ravel(c).tolist()) if not isinstance(c, str) else c, alpha)
    try:
        return _COLORS[key]
    except KeyError:
        if len(_COLORS) > 4096:  # bounded: a figure recolouring every frame cannot grow it
            _COLORS.clear()
        out = _COLORS[key] = mcolors.to_hex(mcolors.to_rgba(c, alpha), keep_alpha=True)
        return out
    except TypeError:  # an unhashable colour
        return mcolors.to_hex(mcolors.to_rgba(c, alpha), keep_alpha=True)


_COLORS: dict = {}


def _floats(values) -> np.ndarray:
    """A flat float array; masked values (an image's unscanned pixels) become NaN."""
    if isinstance(values, np.ma.MaskedArray):
        return np.ma.filled(values.astype(float), np.nan).ravel()
    return np.asarray(values, dtype=float).ravel()


class _Packer:
    """Arrays appended into one float32 buffer; each is referred to as [offset, length]."""

    def __init__(self):
        self.parts, self.size = [], 0

    def add(self, values) -> list:
        a = np.asarray(values, dtype=np.float32).ravel()
        ref = [self.size, int(a.size)]
        self.parts.append(a)
        self.size += a.size
        if self.size > MAX_VALUES:
            raise ValueError(f"a live figure's frame must hold at most {MAX_VALUES} values, "
                             f"got {self.size}")
        return ref

    def bytes(self) -> bytes:
        return np.concatenate(self.parts).tobytes() if self.parts else b""


def _kind(artist, ax) -> str:
    """'data', 'v' (x in data, y in axes fraction), 'h' (the other way) or 'axes'."""
    t = Artist.get_transform(artist)
    if t is ax.transData:
        return "data"
    if t is ax.get_xaxis_transform():
        return "v"
    if t is ax.get_yaxis_transform():
        return "h"
    if t is ax.transAxes:
        return "axes"
    raise NotImplementedError(f"{artist!r} on {ax!r} uses a transform a live figure cannot show")


def _linestyle(line):
    """None (no line), [] (solid) or the dash pattern in px (matplotlib's, scaled with the width)."""
    if line.get_linestyle() in ("None", "none", "", " "):
        return None
    _offset, seq = line._dash_pattern  # in points, already scaled by the line width
    return [] if not seq else [float(d) * _PX for d in seq]


def _positions(x, lim, scale: str, linthresh: float) -> np.ndarray:
    """``x`` on the axis as the browser places it: 0 at ``lim[0]``, 1 at ``lim[1]`` (NaN where
    it cannot be drawn). uPlot's log axis is log10, its symlog axis asinh(x / linthresh)."""
    x = np.asarray(x, dtype=float)
    lo, hi = (float(v) for v in lim)
    with np.errstate(divide="ignore", invalid="ignore"):
        if scale == "log":
            f = np.log10
            x = np.where(x > 0, x, np.nan)
        elif scale == "symlog":
            def f(v):
                return np.arcsinh(np.asarray(v, dtype=float) / linthresh)
        else:
            def f(v):
                return np.asarray(v, dtype=float)
        a, b = f(lo), f(hi)
        return (f(x) - a) / (b - a)


def decimate(x, y, *, lim, columns: int, xscale: str = "linear", linthresh: float = 1.0,
             ylog: bool = False) -> np.ndarray:
    """The points of a line that draw it as all its points do at ``columns`` pixel columns.

    Each run of consecutive points in one pixel column of the x axis keeps its first, last,
    lowest and highest point (the M4 aggregation of Jugel et al., VLDB 7, 797 (2014)): a line
    through them covers in that column exactly the pixels the full line covers (a continuous
    path from first to last through both extremes spans the same vertical range), and it enters
    and leaves the column at the same points. Points off the axis' limits are kept the same way
    in one column each side, so the line enters the view as before. A run of points the browser
    cannot draw (NaN, or not positive on a log axis) keeps its first: the gap stays. Runs are
    taken in the line's order, so any x order (a loop, trace and retrace) is drawn alike.

    Parameters
    ----------
    x, y : array_like
        The line's data.
    lim : (float, float)
        The x axis' limits.
    columns : int
        Pixel columns of the axis (its width in px).
    xscale : {"linear", "log", "symlog"}
    linthresh : float
        A symlog axis' linear threshold.
    ylog : bool
        Whether the y axis is logarithmic (y <= 0 is not drawn).

    Returns
    -------
    numpy.ndarray
        Indices into ``x`` and ``y``, increasing: the points to send.

    Raises
    ------
    ValueError
        If ``x`` and ``y`` differ in length, ``lim`` is not two distinct finite numbers,
        ``columns`` is not a positive integer or ``xscale`` is not one of the three.

    Examples
    --------
    >>> x = np.linspace(0.0, 1.0, 10_001)
    >>> keep = decimate(x, np.sin(200 * x), lim=(0.0, 1.0), columns=100)
    >>> len(keep) <= 4 * 102, int(keep[0]), int(keep[-1])
    (True, 0, 10000)
    """
    x, y = np.asarray(x, dtype=float).ravel(), np.asarray(y, dtype=float).ravel()
    if x.size != y.size:
        raise ValueError(f"x and y must have one length, got {x.size} and {y.size}")
    columns = check_integer("columns", columns, 1)
    check_choice("xscale", xscale, ("linear", "log", "symlog"))
    linthresh = check_positive("linthresh", linthresh)
    lim = tuple(check_finite("lim", v) for v in lim)
    if len(lim) != 2 or lim[0] == lim[1]:
        raise ValueError(f"lim must be two distinct finite numbers, got {lim}")
    n = x.size
    if n == 0:
        return np.zeros(0, dtype=np.intp)
    pos = _positions(x, lim, xscale, linthresh)
    ok = np.isfinite(pos) & np.isfinite(y)
    if ylog:
        ok &= y > 0
    col = np.full(n, -2, dtype=np.int64)  # -2: not drawn
    col[ok] = np.clip(np.floor(pos[ok] * columns), -1, columns).astype(np.int64)
    starts = np.flatnonzero(np.r_[True, col[1:] != col[:-1]])
    ends = np.r_[starts[1:], n] - 1
    group = np.repeat(np.arange(starts.size), np.diff(np.r_[starts, n]))
    drawn = col[starts] != -2
    yy = np.where(ok, y, 0.0)
    low, high = np.minimum.reduceat(yy, starts), np.maximum.reduceat(yy, starts)
    kept = np.zeros(n, dtype=bool)  # the kept indices, in order, each once
    kept[starts] = True
    kept[ends[drawn]] = True
    for extreme in (low, high):
        at = np.flatnonzero(ok & (yy == extreme[group]))
        g = group[at]  # non-decreasing: the first point of each run reaching the extreme
        first = np.flatnonzero(np.r_[True, g[1:] != g[:-1]]) if g.size else g
        kept[at[first][drawn[g[first]]]] = True
    return np.flatnonzero(kept)


def _thinner(ax, columns: int):
    """``thin(x, y)`` for the lines of ``ax`` (see :func:`_line_specs`): :func:`decimate`'s
    indices for a line of more than four points per pixel column, else None."""
    xscale = ax.xaxis.get_scale()
    linthresh = float(ax.xaxis.get_transform().linthresh) if xscale == "symlog" else 1.0
    lim, ylog = ax.get_xlim(), ax.yaxis.get_scale() == "log"
    if not all(math.isfinite(v) for v in lim) or lim[0] == lim[1]:
        return lambda x, y: None

    def thin(x, y):
        if x.size <= 4 * (columns + 2):
            return None
        return decimate(x.astype(float), y.astype(float), lim=lim, columns=columns, xscale=xscale, linthresh=linthresh,
                        ylog=ylog)
    return thin


def _columns(ax, fig) -> int:
    """Pixel columns of ``ax`` in the browser, at most: the width of its cell of the grid."""
    ss = ax.get_subplotspec()
    gs = ss.get_gridspec()
    ratios = gs.get_width_ratios() or [1] * gs.get_geometry()[1]
    share = sum(ratios[ss.colspan.start:ss.colspan.stop]) / sum(ratios)
    return max(1, math.ceil(float(fig.get_size_inches()[0]) * DPI * share))


def _line_specs(line, axis, packer, thin=None):
    """The layout entries and frame entries of one Line2D of the data (a line and/or markers).

    ``thin(x, y)`` gives the indices of a line's points to send (:func:`decimate`), or None to
    send them all; markers are always sent whole.
    """
    color = _color(line.get_color(), line.get_alpha())
    marker = line.get_marker()
    marker = None if marker in (None, "None", "none", "", " ") else str(marker)
    if marker is not None and marker not in _MARKERS:
        raise NotImplementedError(f"{line!r}: a live figure draws the markers {sorted(_MARKERS)}, "
                                  f"not {marker!r}")
    dash = _linestyle(line)
    label = line.get_label()
    label = "" if label.startswith("_") else label
    # as the browser gets them (float32): a point is placed in the column the browser draws it in
    x = _floats(line.get_xdata()).astype(np.float32)
    y = _floats(line.get_ydata()).astype(np.float32)
    if thin is not None and marker is None and dash is not None and x.size == y.size:
        keep = thin(x, y)
        if keep is not None:
            x, y = x[keep], y[keep]
    refs = {"x": packer.add(x), "y": packer.add(y), "label": label}  # labels change with the data (the mode shapes' frequencies)
    layout, frame = [], []
    base = dict(color=color, axis=axis, visible=bool(line.get_visible()))
    if dash is not None:
        layout.append(dict(base, width=line.get_linewidth() * _PX, dash=dash or None,
                           marker=None, line=True))
        frame.append(refs)
    if marker is not None:
        size = line.get_markersize() * (0.5 if marker == "." else 1.0)
        layout.append(dict(base, color=_color(line.get_markeredgecolor(), line.get_alpha()),
                           fill=_color(line.get_markerfacecolor(), line.get_alpha()),
                           marker=marker, size=size, line=False,
                           filled=marker not in ("x", "+") and line.get_fillstyle() != "none",
                           edge=line.get_markeredgewidth() * _PX, width=1.0, dash=None))
        frame.append(refs)
    return layout, frame


def _axis(ax, which: str) -> tuple[dict, dict]:
    axis = ax.xaxis if which == "x" else ax.yaxis
    lo, hi = ax.get_xlim() if which == "x" else ax.get_ylim()
    scale = axis.get_scale()
    if scale not in ("linear", "log", "symlog"):
        raise NotImplementedError(f"a live figure shows linear, log and symlog axes, not {scale!r}")
    layout = {"scale": scale, "grid": bool(axis._major_tick_kw.get("gridOn", False)),
              "show": bool(ax.axison and axis.get_visible())}
    label = axis.label
    frame = {"label": label.get_text() if label.get_visible() else "",
             "color": _color(label.get_color()), "lim": [_num(lo), _num(hi)]}
    if scale == "symlog":
        frame["linthresh"] = float(axis.get_transform().linthresh)
    locator = axis.get_major_locator()
    if isinstance(locator, FixedLocator):
        a, b = min(lo, hi), max(lo, hi)
        ticks = [float(t) for t in locator.locs if a <= t <= b]
        frame["ticks"] = ticks
        frame["ticklabels"] = list(axis.get_major_formatter().format_ticks(ticks))
    return layout, frame


def _secondary(ax):
    """The linear secondary x axis on top of ``ax`` (``secondary_xaxis``), as factor and offset."""
    for child in ax.child_axes:
        if type(child).__name__ != "SecondaryAxis":
            raise NotImplementedError(f"{child!r}: a live figure shows no inset axes")
        if child._orientation != "x":
            raise NotImplementedError("a live figure shows secondary x axes only")
        forward = child._functions[0]
        lo, hi = ax.get_xlim()
        f0, f1, fm = (float(forward(np.array(v))) for v in (lo, hi, 0.5 * (lo + hi)))
        if not math.isclose(fm, 0.5 * (f0 + f1), rel_tol=1e-9, abs_tol=1e-12 * abs(f1 - f0)):
            raise NotImplementedError("a live figure shows linear secondary axes only")
        label = child.xaxis.label
        return {"label": label.get_text(), "color": _color(label.get_color()),
                "lim": [_num(f0), _num(f1)]}
    return None


def _texts(ax):
    out = []
    for t in ax.texts:
        if not t.get_visible():
            continue
        kind = _kind(t, ax)
        if kind not in ("data", "axes"):
            raise NotImplementedError(f"{t!r}: texts are placed in data or axes coordinates")
        if t.get_rotation() % 360:
            raise NotImplementedError(f"{t!r}: a live figure draws texts unrotated")
        x, y = t.get_position()
        out.append(dict(text=t.get_text(), x=_num(x), y=_num(y), coords=kind,
                        color=_color(t.get_color()), ha=t.get_horizontalalignment(),
                        va=t.get_verticalalignment(), size=t.get_fontsize() * _PX))
    return out


def _legend(legend):
    if legend is None or not legend.get_visible():
        return []
    out = []
    for handle, text in zip(legend.legend_handles, legend.get_texts()):
        if handle is None:
            continue
        if hasattr(handle, "get_linestyle") and hasattr(handle, "get_marker"):
            marker = handle.get_marker()
            marker = None if marker in (None, "None", "none", "", " ") else str(marker)
            ls = handle.get_linestyle()
            out.append(dict(label=text.get_text(), color=_color(handle.get_color(),
                                                                handle.get_alpha()),
                            dash=ls not in ("-", "solid"), line=ls not in ("None", "", " "),
                            marker=marker, width=handle.get_linewidth() * _PX))
        else:  # a patch
            out.append(dict(label=text.get_text(), color=_color(handle.get_facecolor()),
                            dash=False, line=True, marker=None, width=8))
    return out


def _patches(ax):
    spans = []
    for p in ax.patches:
        if not p.get_visible():
            continue
        kind = _kind(p, ax)
        if kind not in ("v", "h") or not isinstance(p, (Rectangle, Polygon)):
            raise NotImplementedError(f"{p!r}: a live figure shows axvspan and axhspan patches")
        xy = p.get_path().vertices if isinstance(p, Rectangle) else p.get_xy()
        xy = p.get_patch_transform().transform(xy) if isinstance(p, Rectangle) else xy
        coords = xy[:, 0] if kind == "v" else xy[:, 1]
        spans.append(dict(kind=kind, lo=_num(np.min(coords)), hi=_num(np.max(coords)),
                          color=_color(p.get_facecolor())))
    return spans


def _lut(cmap, luts):
    """Put ``cmap`` into ``luts`` as 256 RGB bytes (base64), once per figure; return it."""
    if cmap.name not in luts:
        rgb = (cmap(np.linspace(0.0, 1.0, 256))[:, :3] * 255).round().astype(np.uint8)
        luts[cmap.name] = base64.b64encode(rgb.tobytes()).decode()
    return cmap


def _images(ax, packer, luts):
    layout, frame = [], []
    for im in ax.images:
        a = np.ma.asarray(im.get_array())
        if a.ndim != 2:
            raise NotImplementedError("a live figure shows 2-D height maps (with a colour map), "
                                      f"not arrays of shape {a.shape}")
        im.norm.autoscale_None(a)
        cmap = _lut(im.get_cmap(), luts)
        layout.append({"cmap": cmap.name})
        frame.append(dict(data=packer.add(_floats(a)), shape=list(a.shape), cmap=cmap.name,
                          extent=[_num(v) for v in im.get_extent()], origin=im.origin,
                          vmin=_num(im.norm.vmin), vmax=_num(im.norm.vmax)))
    return layout, frame


def set_clim(image, low: float, high: float) -> None:
    """Set an image's colour limits; its colour bar is redrawn only when the figure is rasterised.

    ``image.set_clim`` has matplotlib redraw the image's colour bar at once (its mesh of
    colours, ticks and locator: some 5 ms per bar), work a live figure never shows: the browser
    draws the bar from the norm's limits (:func:`describe` reads them). Here the norm changes
    without that callback, and the colour bar is marked stale: the figure's next ``draw`` (Agg,
    a saved PNG, a test) brings it up to date first, so a rasterised figure is the same as with
    ``set_clim``.

    Parameters
    ----------
    image : matplotlib.image.AxesImage
        An image of a figure (with or without a colour bar).
    low, high : float
        The colour limits, in the image's units.

    Raises
    ------
    TypeError
        If ``image`` is not an image of matplotlib's (a mappable with a norm).
    """
    check_instance("image", image, ScalarMappable)
    norm = image.norm
    with norm.callbacks.blocked():
        norm.vmin, norm.vmax = low, high
    image.stale = True
    bar = image.colorbar
    if bar is None:
        return
    fig = bar.ax.figure
    stale = fig.__dict__.get("_afm_stale_colorbars")
    if stale is None:  # wrap the figure's draw once: stale colour bars are redrawn first
        stale = fig._afm_stale_colorbars = {}
        plain = fig.draw

        def draw(renderer, *args, **kwargs):
            while stale:
                _, cb = stale.popitem()
                cb.update_normal(cb.mappable)
            return plain(renderer, *args, **kwargs)

        fig.draw = draw
    stale[id(bar)] = bar
    bar.ax.stale = True


@dataclass(frozen=True)
class Description:
    """A figure as the browser draws it.

    Attributes
    ----------
    layout : dict
        What rarely changes: the grid of axes, their scales, the series' styles and labels. A new
        layout rebuilds the charts in the browser.
    frame : dict
        What changes with the data: limits, titles, axis labels, texts, reference lines, spans,
        legends, and for each series and image its place in ``buffer``.
    buffer : bytes
        Every curve and image of the frame, float32, little-endian.
    """

    layout: dict
    frame: dict
    buffer: bytes

    def values(self, ref) -> np.ndarray:
        """The array at ``ref`` (``[offset, length]`` from the frame) as float32."""
        offset, length = ref
        return np.frombuffer(self.buffer, dtype="<f4", count=length, offset=4 * offset)


def describe(fig: Figure) -> Description:
    """Read a matplotlib figure's artists into a :class:`Description` (no rendering).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        Its axes on one grid (``subplots``/``add_gridspec``), with twins (``twinx``), linear
        secondary x axes, colour bars.

    Returns
    -------
    Description

    Raises
    ------
    TypeError
        If ``fig`` is not a Figure.
    NotImplementedError
        For an artist a live figure cannot show (named).
    """
    fig = check_instance("fig", fig, Figure)
    packer, luts = _Packer(), {}
    hosts, twins, colorbars = [], {}, {}
    for ax in fig.axes:
        if hasattr(ax, "_colorbar"):
            cb = ax._colorbar
            colorbars[id(cb.mappable.axes)] = cb
            continue
        ss = ax.get_subplotspec()
        if ss is None:
            raise NotImplementedError(f"{ax!r} is not on a grid of subplots")
        host = next((h for h in hosts if h.get_subplotspec() == ss), None)
        if host is None:
            hosts.append(ax)
        elif (host in ax._twinned_axes.get_siblings(ax) and id(host) not in twins
              and host.get_shared_x_axes().joined(host, ax)):
            twins[id(host)] = ax
        else:
            raise NotImplementedError(f"{ax!r} shares its place with another axes")
    if not hosts:
        raise ValueError("fig must hold at least one axes")
    gs = hosts[0].get_subplotspec().get_gridspec()
    rows, cols = gs.get_geometry()
    layout_axes, frame_axes = [], []
    for ax in hosts:
        ss = ax.get_subplotspec()
        if ss.get_gridspec() is not gs:
            raise NotImplementedError("a live figure's axes must share one grid")
        if ax._left_title.get_text() or ax._right_title.get_text():
            raise NotImplementedError(f"{ax!r}: a live figure shows centred titles only")
        xl, xf = _axis(ax, "x")
        yl, yf = _axis(ax, "y")
        columns = _columns(ax, fig)
        la = dict(row=ss.rowspan.start, rowspan=len(ss.rowspan), col=ss.colspan.start,
                  colspan=len(ss.colspan), visible=bool(ax.get_visible()), x=xl, y=yl,
                  aspect="equal" if ax.get_aspect() == 1.0 else None, series=[], images=[])
        fa = dict(axes=dict(x=xf, y=yf), series=[], refs=[], texts=[], spans=[], legend=[],
                  title=dict(text=ax.get_title(), color=_color(ax.title.get_color())))
        members = [(ax, "y")]
        twin = twins.get(id(ax))
        if twin is not None:
            tl, tf = _axis(twin, "y")
            la["y2"] = dict(tl, visible=bool(twin.get_visible()))
            fa["axes"]["y2"] = tf
            members.append((twin, "y2"))
        sec = _secondary(ax)
        if sec is not None:
            la["x2"] = {"scale": "linear", "grid": False}
            fa["axes"]["x2"] = sec
        for member, axis in members:
            if not member.get_visible():
                continue
            data_lines = [(ln.get_zorder(), i) for i, ln in enumerate(member.lines)
                          if _kind(ln, member) == "data"]
            thin = _thinner(member, columns)
            for index, line in enumerate(member.lines):
                kind = _kind(line, member)
                if kind == "data":
                    lay, fr = _line_specs(line, axis, packer, thin)
                    la["series"] += lay
                    fa["series"] += fr
                elif kind in ("v", "h") and line.get_visible():
                    x, y = _floats(line.get_xdata()), _floats(line.get_ydata())
                    at, (a, b) = (x[0], y) if kind == "v" else (y[0], x)
                    fa["refs"].append(dict(kind=kind, at=_num(at), axis=axis,
                                           **{"from": _num(min(a, b)), "to": _num(max(a, b))},
                                           color=_color(line.get_color(), line.get_alpha()),
                                           width=line.get_linewidth() * _PX,
                                           dash=_linestyle(line) or None,
                                           over=any((line.get_zorder(), index) > d
                                                    for d in data_lines)))
                elif kind not in ("v", "h"):
                    raise NotImplementedError(f"{line!r}: a line in axes coordinates")
            fa["texts"] += _texts(member)
            fa["spans"] += [dict(s, axis=axis) for s in _patches(member)]
            fa["legend"] += _legend(member.get_legend())
            if member.collections:
                raise NotImplementedError(f"{member.collections[0]!r}: a live figure shows lines, "
                                          "markers, spans and images, not collections")
        il, fi = _images(ax, packer, luts)
        la["images"], fa["images"] = il, fi
        cb = colorbars.get(id(ax))
        if cb is not None:
            la["colorbar"] = True
            fa["colorbar"] = dict(label=cb.ax.get_ylabel(), cmap=cb.cmap.name,
                                  vmin=_num(cb.norm.vmin), vmax=_num(cb.norm.vmax))
            _lut(cb.cmap, luts)
        layout_axes.append(la)
        frame_axes.append(fa)
    unplaced = set(colorbars) - {id(ax) for ax in hosts}
    if unplaced:
        raise NotImplementedError("a colour bar's image must be on one of the figure's axes")
    width, height = (float(v) * DPI for v in fig.get_size_inches())
    ratios = gs.get_width_ratios() or [1] * cols, gs.get_height_ratios() or [1] * rows
    layout = dict(width=round(width), height=round(height), rows=rows, cols=cols,
                  col_ratios=[float(r) for r in ratios[0]],
                  row_ratios=[float(r) for r in ratios[1]], axes=layout_axes, luts=luts)
    suptitle = fig._suptitle.get_text() if getattr(fig, "_suptitle", None) is not None else ""
    legend = [e for lg in fig.legends for e in _legend(lg)]
    frame = dict(axes=frame_axes, suptitle=suptitle, legend=legend)
    return Description(layout, frame, packer.bytes())


# -- the widget and the static page -------------------------------------------------------------

class LiveFigure(anywidget.AnyWidget):
    """A matplotlib figure drawn in the browser; :meth:`sync` sends its current state.

    Parameters
    ----------
    figure : matplotlib.figure.Figure
        The figure to mirror; its figure class updates the artists, then calls :meth:`sync`.

    Attributes
    ----------
    figure : matplotlib.figure.Figure
    frames_sent : int
        Frames sent so far (one per :meth:`sync` that changed something); the browser shows it
        as ``data-seq``.
    frames_painted : int
        The newest frame a view of this figure said it painted (0 before any view did).
    """

    _esm = _esm()
    _css = _css()
    _layout = traitlets.Dict().tag(sync=True)
    _frame = traitlets.Dict().tag(sync=True)
    _buffer = traitlets.Bytes().tag(sync=True)

    def __init__(self, figure: Figure, **kwargs):
        super().__init__(**kwargs)
        self.figure = check_instance("figure", figure, Figure)
        self.frames_sent = 0
        self.frames_painted = 0
        self._sent_at = 0.0  # time.monotonic() of the newest frame sent
        self._sent_frame = None
        self.on_msg(self._handle_message)
        self.sync()

    def busy(self, now: float | None = None) -> bool:
        """Whether the browser has more than :data:`FRAMES_AHEAD` frames to paint, the newest
        sent less than :data:`PAINT_WAIT` s ago.

        ``now`` is ``time.monotonic()`` (the default; asyncio's ``loop.time()`` is the same
        clock).

        A view says which frame it painted (a message ``{"painted": seq}``, sent from the
        animation-frame callback that draws the frame, whose rendering update paints it); a
        frame sent after the newest painted one is in flight. Where no view ever said so (no
        browser: tests, nbval, a static export) or it has not answered within
        :data:`PAINT_WAIT` s (its page was closed, a view of another kind), nothing is in
        flight: a panel never waits on a page that cannot answer.
        """
        if self.frames_painted == 0 or self.frames_sent - self.frames_painted <= FRAMES_AHEAD:
            return False
        now = time.monotonic() if now is None else check_finite("now", now, "s")
        return now - self._sent_at < PAINT_WAIT

    def _handle_message(self, _widget, content, _buffers) -> None:
        if not isinstance(content, dict):
            return
        painted = content.get("painted")
        if isinstance(painted, int) and not isinstance(painted, bool) and \
                0 < painted <= self.frames_sent:
            self.frames_painted = max(self.frames_painted, painted)

    def sync(self) -> Description:
        """Send the figure's current state to the browser as one message; return it.

        A state equal to the last one sent is not sent again.

        Returns
        -------
        Description
        """
        d = describe(self.figure)
        if d.frame == self._sent_frame and d.buffer == self._buffer and d.layout == self._layout:
            return d  # nothing changed (the mode shapes on a force step): no message, no redraw
        self._sent_frame = d.frame
        self.frames_sent += 1
        self._sent_at = time.monotonic()
        with self.hold_sync():
            self._layout = d.layout
            self._buffer = d.buffer
            self._frame = dict(d.frame, seq=self.frames_sent)
        return d

    def static_html(self) -> str:
        """The figure as a self-contained HTML fragment (uPlot inlined, no network, no kernel)."""
        return static_html(self.figure)


def _script_json(value) -> str:
    return json.dumps(value, allow_nan=False).replace("</", "<\\/")


def static_html(fig: Figure) -> str:
    """``fig`` drawn by the live figure's renderer in a static page (an export, the book).

    Parameters
    ----------
    fig : matplotlib.figure.Figure

    Returns
    -------
    str
        A ``<div>`` with its style and an inline module script: uPlot, the renderer and the frame
        (its buffer in base64). It needs no network and no kernel.
    """
    d = describe(fig)
    key = f"afm-live-{uuid.uuid4().hex}"
    data = base64.b64encode(d.buffer).decode()
    css = _css().replace("</", "<\\/")
    return (f'<div class="afm-live-static"><style>{css}</style>'
            f'<div id="{key}"></div><script type="module">\n{_esm()}\n'
            f'drawStatic(document.getElementById("{key}"), {_script_json(d.layout)}, '
            f'{_script_json(dict(d.frame, seq=0))}, "{data}");\n</script></div>')
