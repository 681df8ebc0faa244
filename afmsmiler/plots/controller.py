"""Figures of module (c): the loop's block diagram, trace/retrace like the paper's Fig. 4, the pole
map, the polygon decomposition of a line, and scanned images.

Model results (SI) are converted here to the units shown: x in um, heights in nm, poles in 1/us
(= 1e6 1/s). :class:`ScanFigure` draws once and :meth:`ScanFigure.update` swaps the data in place,
so that a widget panel never creates artists. An unstable loop's outputs grow without bound: the
axes keep the topography's range and say how far off scale the signals went.
"""
from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
from matplotlib.figure import Figure
from matplotlib.ticker import FixedLocator, FuncFormatter
from matplotlib.patches import Circle, FancyArrowPatch, Rectangle

from ..controller import ContactLoop, Preset, ScanImage, ScanLine
from ..parameters import read_only, unit_scale
from ..samples import Sample
from ..validation import check_array, check_choice, check_instance, check_positive, check_size
from .limits import hold

__all__ = ["UNITS", "FIGSIZE", "ScanCurves", "scan_curves", "ScanFigure", "fig4_figure",
           "block_diagram", "polygon_figure", "image_figure"]

#: Factors from SI to the units shown (value_shown = value_SI * factor), from the one unit table.
UNITS = read_only(dict(x=unit_scale("um", "m"), z=unit_scale("nm", "m"),
                       pole=unit_scale("1/us", "1/s")))

#: Default figure sizes in inches, at most 10 in wide: JupyterLab's output area is about 1000 px
#: (10 in at 100 dpi) wide and clipped wider figures on the right. ``"fig4"`` is (width, height
#: per scenario row), ``"image"`` (width per image, height).
FIGSIZE = read_only(dict(scan=(10.0, 6.0), fig4=(10.0, 2.2), block=(10.0, 2.9),
                         polygon=(10.0, 3.2), image=(3.3, 3.2)))

#: The most scenarios (rows) of :func:`fig4_figure` and knots (pixels) of :func:`polygon_figure`:
#: each is drawn as its own artists, and more would not read.
MAX_SCENARIOS = 12
MAX_KNOTS = 1000


@dataclass(frozen=True)
class ScanCurves:
    """The data of a :class:`ScanFigure`, in the units shown.

    Attributes
    ----------
    x_trace_um, x_retrace_um : ndarray
        Positions in um (retrace in scan order).
    height_nm : ndarray
        True topography along the trace in nm.
    minus_znp_trace_nm, minus_znp_retrace_nm : ndarray
        -Z_np in nm.
    topo_trace_nm, topo_retrace_nm : ndarray
        Estimated topography Z_c - Z_np in nm.
    poles_per_us : ndarray
        Closed-loop poles in 1/us.
    stable : bool
        Routh-Hurwitz verdict.
    margin : float
        Routh-Hurwitz margin.
    """

    x_trace_um: np.ndarray
    x_retrace_um: np.ndarray
    height_nm: np.ndarray
    minus_znp_trace_nm: np.ndarray
    minus_znp_retrace_nm: np.ndarray
    topo_trace_nm: np.ndarray
    topo_retrace_nm: np.ndarray
    poles_per_us: np.ndarray
    stable: bool
    margin: float


def scan_curves(result, loop) -> ScanCurves:
    """Convert a :class:`~afmsmiler.controller.ScanLine` and its loop to the units shown.

    Parameters
    ----------
    result : afmsmiler.controller.ScanLine
        Trace and retrace of a line.
    loop : afmsmiler.controller.ContactLoop
        The loop that made it (for the poles and the margin).

    Returns
    -------
    ScanCurves
    """
    check_instance("result", result, ScanLine)
    check_instance("loop", loop, ContactLoop)
    z, x = UNITS["z"], UNITS["x"]
    tr, rt = result.trace, result.retrace
    stab = loop.is_stable()
    return ScanCurves(tr.x * x, rt.x * x, tr.height * z, -tr.z_np * z, -rt.z_np * z,
                      tr.topography * z, rt.topography * z, loop.poles * UNITS["pole"],
                      bool(stab), stab.margin)


def _finite(y):
    return np.where(np.isfinite(y), y, np.nan)


def _limits(reference, *signals, pad=0.08):
    """y-limits covering the reference and the signals, but at most 4 reference ranges out."""
    ref_lo, ref_hi = float(np.min(reference)), float(np.max(reference))
    ref_span = max(ref_hi - ref_lo, 1e-3)
    lo, hi = ref_lo, ref_hi
    for s in signals:
        s = s[np.isfinite(s)]
        if s.size:
            lo, hi = min(lo, float(s.min())), max(hi, float(s.max()))
    # an unstable loop's signals go off scale: never zoom out past 4 topography ranges
    lo, hi = max(lo, ref_lo - 4 * ref_span), min(hi, ref_hi + 4 * ref_span)
    span = hi - lo
    return lo - pad * span, hi + pad * span


def _on_scale(y, limits):
    """y with the points beyond the axis limits (and non-finite ones) masked as nan."""
    y = _finite(y)
    lo, hi = limits
    return np.where((y >= lo - (hi - lo)) & (y <= hi + (hi - lo)), y, np.nan)


def _off_scale(limits, *signals) -> float:
    worst = 0.0
    for s in signals:
        a = np.abs(s[np.isfinite(s)]) if np.any(np.isfinite(s)) else np.array([np.inf])
        worst = max(worst, float(a.max()) if a.size else np.inf)
        if not np.all(np.isfinite(s)):
            worst = np.inf
    return worst if worst > max(abs(limits[0]), abs(limits[1])) else 0.0


class ScanFigure:
    """Trace/retrace of -Z_np and of the estimated topography (left), the pole map (right).

    Parameters
    ----------
    curves : ScanCurves
        The first data to show.
    fig : matplotlib.figure.Figure, optional
        Where to draw; a new pyplot-free Figure by default.
    title : str
        Figure title.

    Attributes
    ----------
    lines : dict
        ``"znp_trace"``, ``"znp_retrace"``, ``"topo_trace"``, ``"topo_retrace"``, ``"height"``
        lines and the ``"poles_stable"`` and ``"poles_unstable"`` markers, updated in place by
        :meth:`update`.
    legend : matplotlib.legend.Legend
        The figure's legend, above the axes.
    axes : dict
        ``"znp"``, ``"topo"``, ``"poles"``.
    """

    def __init__(self, curves: ScanCurves, fig: Figure | None = None, title: str = ""):
        check_instance("curves", curves, ScanCurves)
        check_instance("title", title, str)
        self.fig = (check_instance("fig", fig, Figure) if fig is not None
                    else Figure(figsize=FIGSIZE["scan"]))
        self.fig.set_layout_engine("constrained")  # before the legend placed "outside"
        grid = self.fig.add_gridspec(2, 3)
        ax = self.axes = dict(znp=self.fig.add_subplot(grid[0, :2]),
                              topo=self.fig.add_subplot(grid[1, :2]),
                              poles=self.fig.add_subplot(grid[:, 2]))
        self.lines = {}
        self.lines["znp_trace"], = ax["znp"].plot([], [], color="C0", label="trace")
        self.lines["znp_retrace"], = ax["znp"].plot([], [], color="C3", ls="--", label="retrace")
        ax["znp"].set(xlabel="x [um]", ylabel="-Z_np [nm]",
                      title="positioner height (sign flipped)")
        self.lines["height"], = ax["topo"].plot([], [], color="0.6", lw=3, alpha=0.6,
                                                label="true topography T")
        self.lines["topo_trace"], = ax["topo"].plot([], [], color="C0", label="trace")
        self.lines["topo_retrace"], = ax["topo"].plot([], [], color="C3", ls="--",
                                                      label="retrace")
        ax["topo"].set(xlabel="x [um]", ylabel="Z_c - Z_np [nm]", title="estimated topography")
        # one legend above the plots, outside every axes: inside, it covered the data
        self.legend = self.fig.legend(
            handles=[self.lines[k] for k in ("znp_trace", "znp_retrace", "height")],
            loc="outside upper left", ncols=3, fontsize="small", frameon=False)
        self.texts = {k: ax[k].text(0.01, 0.95, "", transform=ax[k].transAxes, va="top",
                                    color="C3", fontsize="small") for k in ("znp", "topo")}
        # the pole map: a symmetric-log real axis, so that Re p = -0.01 and +0.01 1/us next to
        # poles of 10 1/us fall on either side of the imaginary axis instead of on it; the
        # left (stable) half-plane shaded green, the right one red; stable poles green,
        # unstable ones red
        pa = ax["poles"]
        self.shades = (pa.axvspan(-1e30, 0, color="C2", alpha=0.10, lw=0),
                       pa.axvspan(0, 1e30, color="C3", alpha=0.10, lw=0))
        pa.axvline(0, color="0.3", lw=1.0)
        pa.axhline(0, color="0.85", lw=0.8)
        pa.text(0.02, 0.02, "stable", transform=pa.transAxes, color="C2", fontsize="small")
        pa.text(0.98, 0.02, "unstable", transform=pa.transAxes, color="C3", fontsize="small",
                ha="right")
        self.lines["poles_stable"], = pa.plot([], [], "x", ms=10, mew=2, color="C2")
        self.lines["poles_unstable"], = pa.plot([], [], "x", ms=10, mew=2, color="C3")
        pa.set(ylabel="Im p [1/us]")
        if title:
            self.fig.suptitle(title)
        self.update(curves)

    def update(self, curves: ScanCurves) -> None:
        """Show new curves: set the data and limits, retitle the pole map (no new artists).

        The -Z_np and topography axes hold their limits while the curves stay inside them and
        fill a fair part of them (:func:`~afmsmiler.plots.limits.sticky_limits`; the first draw
        fits the data), so that a slider move shows the curves move; an unstable loop's signals
        still count only up to 4 topography ranges beyond it. The scan line's x range and the
        pole map (symmetric log, fitted to the poles) are set exactly.

        Parameters
        ----------
        curves : ScanCurves
            From :func:`scan_curves`.
        """
        c = curves
        reset = not getattr(self, "_limits_held", False)  # the first draw fits the data
        x_lim = (float(c.x_trace_um[0]), float(c.x_trace_um[-1]))
        self.lines["height"].set_data(c.x_trace_um, c.height_nm)
        for key, ref, (tr, rt) in (
                ("znp", c.minus_znp_trace_nm[:1] + c.height_nm - c.height_nm[0],
                 (c.minus_znp_trace_nm, c.minus_znp_retrace_nm)),
                ("topo", c.height_nm, (c.topo_trace_nm, c.topo_retrace_nm))):
            ax = self.axes[key]
            ax.set_xlim(*x_lim)
            # the data's range (8 % margins on a fit, as _limits pads; at least 1 pm high)
            lim = hold(ax, "y", *_limits(ref, tr, rt, pad=0.0), reset=reset, floor=1e-3)
            self.lines[f"{key}_trace"].set_data(c.x_trace_um, _on_scale(tr, lim))
            self.lines[f"{key}_retrace"].set_data(c.x_retrace_um, _on_scale(rt, lim))
            worst = _off_scale(lim, tr, rt)
            self.texts[key].set_text(
                "" if not worst else f"off scale: |signal| reaches {worst:.3g} nm")
        p = c.poles_per_us
        right = p.real >= 0
        self.lines["poles_stable"].set_data(p.real[~right], p.imag[~right])
        self.lines["poles_unstable"].set_data(p.real[right], p.imag[right])
        ax = self.axes["poles"]
        r = max(float(np.max(np.abs(p))), 1e-9) * 1.15
        nonzero = np.abs(p.real[p.real != 0])
        # linear within a decade below the smallest |Re p| (at most 1e-3 of the largest pole)
        small = float(nonzero.min()) if nonzero.size else r * 1e-3
        linthresh = min(small / 10, r * 1e-3)
        ax.set_xscale("symlog", linthresh=linthresh, linscale=0.5)
        ax.set_xlim(-r, r)
        # labels on every second decade 10^hi, 10^(hi-2), ... down to the linear zone and on 0,
        # a minor tick on every decade (symlog's default crowds a label on every decade; only
        # 0 and +-10^hi made the axis look linear: a pole at Re p = -0.006 1/us read as -3)
        hi = math.floor(math.log10(r))
        lo = math.ceil(math.log10(linthresh)) + 1
        decades = [10.0 ** k for k in range(hi, max(lo, hi - 12) - 1, -1)]
        labelled = decades[::2] or [10.0 ** hi]
        ticks = sorted([-t for t in labelled] + [0.0] + labelled)
        ax.set_xlabel(f"Re p [1/us] (symlog, linear within {linthresh:.1g})")
        ax.xaxis.set_major_locator(FixedLocator(ticks))
        ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
        ax.xaxis.set_minor_locator(FixedLocator(sorted([-t for t in decades] + decades)))
        ax.set_ylim(-r, r)
        verdict = "STABLE" if c.stable else "UNSTABLE"
        ax.set_title(f"closed-loop poles: {verdict}\nRouth-Hurwitz margin {c.margin:.3g}\n"
                     f"max Re p = {float(np.max(p.real)):.3g} 1/us",
                     color="C2" if c.stable else "C3", fontsize="medium")
        self._limits_held = True

    def poles(self) -> np.ndarray:
        """The poles drawn (stable and unstable markers together), in 1/us.

        Returns
        -------
        numpy.ndarray of complex
        """
        out = []
        for key in ("poles_stable", "poles_unstable"):
            x, y = self.lines[key].get_data()
            out.append(np.asarray(x, dtype=float) + 1j * np.asarray(y, dtype=float))
        return np.concatenate(out)


def fig4_figure(presets=None, sample=None, fig: Figure | None = None) -> Figure:
    """The paper's Fig. 4: -Z_np and the estimated topography of the four scenarios.

    Parameters
    ----------
    presets : dict, optional
        Name -> :class:`~afmsmiler.controller.Preset` (1 to :data:`MAX_SCENARIOS` of them);
        default the four Fig. 4 presets.
    sample : afmsmiler.samples.Sample, optional
        The line to scan; default the presets' grating.
    fig : matplotlib.figure.Figure, optional
        Where to draw; default a new Figure of FIGSIZE["fig4"] (10 in wide, 2.2 in per scenario).

    Returns
    -------
    matplotlib.figure.Figure
    """
    from ..controller import PRESETS
    presets = PRESETS if presets is None else presets
    if not isinstance(presets, Mapping) or not presets:
        raise TypeError(f"presets must be a non-empty dict of name -> Preset, got "
                        f"{type(presets).__name__} {presets!r:.60}")
    check_size("len(presets)", len(presets), MAX_SCENARIOS)
    for name, preset in presets.items():
        check_instance(f"presets[{name!r}]", preset, Preset)
    if sample is not None:
        check_instance("sample", sample, Sample)
    width, row = FIGSIZE["fig4"]
    fig = (check_instance("fig", fig, Figure) if fig is not None
           else Figure(figsize=(width, row * len(presets))))
    fig.set_layout_engine("constrained")  # before the legend placed "outside"
    axes = fig.subplots(len(presets), 2, squeeze=False)
    for row, preset in enumerate(presets.values()):
        r = preset.scan(sample)
        c = scan_curves(r, preset.loop)
        for col, (tr, rt, label) in enumerate((
                (c.minus_znp_trace_nm, c.minus_znp_retrace_nm, "-Z_np [nm]"),
                (c.topo_trace_nm, c.topo_retrace_nm, "Z_c - Z_np [nm]"))):
            ax = axes[row, col]
            if col == 1:
                ax.plot(c.x_trace_um, c.height_nm, color="0.6", lw=3, alpha=0.6, label="T")
            ref = c.height_nm if col == 1 else tr[:1] + c.height_nm - c.height_nm[0]
            lim = _limits(ref, tr, rt)
            ax.plot(c.x_trace_um, _on_scale(tr, lim), color="C0", label="trace")
            ax.plot(c.x_retrace_um, _on_scale(rt, lim), color="C3", ls="--", label="retrace")
            ax.set_ylim(*lim)
            worst = _off_scale(lim, tr, rt)
            if worst:
                ax.text(0.01, 0.95, f"off scale: reaches {worst:.3g} nm", va="top",
                        transform=ax.transAxes, color="C3", fontsize="small")
            ax.set(ylabel=label, xlim=(c.x_trace_um[0], c.x_trace_um[-1]))
            ax.set_title(f"{preset.description}, {preset.speed * 1e6:g} um/s", fontsize="small")
            ax.set_xlabel("x [um]", fontsize="small")
    # one legend above the plots, outside every axes (in the axes it covered the data)
    fig.legend(handles=axes[0, 1].get_lines(), loc="outside upper center", ncols=3,
               fontsize="small", frameon=False)
    return fig


def _box(ax, xy, text, w=1.6, h=0.8):
    ax.add_patch(Rectangle((xy[0] - w / 2, xy[1] - h / 2), w, h, fc="white", ec="black"))
    ax.text(*xy, text, ha="center", va="center", fontsize=11)


def _arrow(ax, a, b, text="", offset=(0, 0.2)):
    ax.add_patch(FancyArrowPatch(a, b, arrowstyle="-|>", mutation_scale=14, lw=1.2))
    if text:
        ax.text((a[0] + b[0]) / 2 + offset[0], (a[1] + b[1]) / 2 + offset[1], text,
                ha="center", fontsize=10)


def block_diagram(fig: Figure | None = None) -> Figure:
    """The contact-mode loop: R - Z_c -> C(s) -> Z_np, + T -> P(s) -> Z_c, fed back.

    Parameters
    ----------
    fig : matplotlib.figure.Figure, optional
        Where to draw; default a new Figure of FIGSIZE["block"] (10 x 2.9 in).

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig = (check_instance("fig", fig, Figure) if fig is not None
           else Figure(figsize=FIGSIZE["block"]))
    ax = fig.add_subplot()
    for xy, sign in (((1.2, 1.0), "$-$"), ((7.0, 1.0), "+")):
        ax.add_patch(Circle(xy, 0.2, fc="white", ec="black"))
        ax.text(xy[0] - 0.45, xy[1] - 0.5, sign, fontsize=12)
    _arrow(ax, (0.0, 1.0), (1.0, 1.0), "$R$")
    _arrow(ax, (1.4, 1.0), (2.0, 1.0))
    _box(ax, (3.9, 1.0), "$C(s) = K_P + \\frac{K_I}{s} + K_D s$", w=3.6, h=1.0)
    _arrow(ax, (5.7, 1.0), (6.8, 1.0), "$Z_{np}$")
    _arrow(ax, (7.0, 2.4), (7.0, 1.2), "topography $T$", offset=(1.1, 0.35))
    _arrow(ax, (7.2, 1.0), (8.0, 1.0))
    _box(ax, (10.3, 1.0),
         "$P(s) = \\frac{b_s s + k_s}{(m_c + m_s) s^2 + (b_c + b_s) s + k_c + k_s}$",
         w=4.6, h=1.0)
    _arrow(ax, (12.6, 1.0), (14.0, 1.0), "$Z_c$")
    ax.plot([13.4, 13.4, 1.2], [1.0, -0.3, -0.3], color="C0", lw=1.2)
    _arrow(ax, (1.2, -0.3), (1.2, 0.8))
    ax.text(7.0, -0.75, "the deflection $Z_c$ is measured and fed back; "
            "the image is the estimate $Z_c - Z_{np}$ of $T$", ha="center", fontsize=10,
            color="0.3")
    ax.set_xlim(-0.2, 14.2)
    ax.set_ylim(-1.0, 2.9)
    ax.set_aspect("equal")
    ax.axis("off")
    return fig


def polygon_figure(x, height, speed, n_show: int = 12, fig: Figure | None = None) -> Figure:
    """The paper's idea: a sampled line as a polygon in time = a step plus ramps at every knot.

    Parameters
    ----------
    x, height : array_like
        Pixel positions and heights in m (as many of each).
    speed : float
        Scan speed in m/s (turns x into time).
    n_show : int
        Number of pixels to draw (the first ones), 1 to :data:`MAX_KNOTS`.
    fig : matplotlib.figure.Figure, optional
        Where to draw; default a new Figure of FIGSIZE["polygon"] (10 x 3.2 in).

    Returns
    -------
    matplotlib.figure.Figure
    """
    n_show = check_size("n_show", n_show, MAX_KNOTS)
    x = check_array("x", x, "m", ndim=1, min_size=1)
    h = check_array("height", height, "m", ndim=1)
    if h.size != x.size:
        raise ValueError(f"x and height must have as many points, got {x.size} and {h.size}")
    x, h = x[:n_show], h[:n_show] * UNITS["z"]
    speed = check_positive("speed", speed, "m/s")
    t = (x - x[0]) / speed * 1e6  # us
    fig = (check_instance("fig", fig, Figure) if fig is not None
           else Figure(figsize=FIGSIZE["polygon"]))
    a1, a2 = fig.subplots(1, 2)
    a1.plot(t, h, "o-", color="C0")
    a1.set(xlabel="t [us]", ylabel="T [nm]", title="topography under the tip: a polygon")
    slope = np.diff(h) / np.diff(t)
    dslope = np.diff(np.r_[0.0, slope])
    tt = np.linspace(t[0], t[-1], 400)
    a2.plot(tt, np.full_like(tt, h[0]), color="C1", label="step T_0")
    for k in range(len(dslope)):
        a2.plot(tt, np.where(tt >= t[k], dslope[k] * (tt - t[k]), 0.0), color="C2", lw=0.8,
                alpha=0.7, label="ramps at the knots" if k == 0 else None)
    a2.plot(t, h, "o", color="C0", label="their sum at the knots")
    a2.set(xlabel="t [us]", ylabel="height [nm]", title="= a step + ramps of slope changes")
    a2.legend(fontsize="small", loc="upper left", bbox_to_anchor=(1.01, 1.0))  # beside it
    fig.set_layout_engine("constrained")
    return fig


def image_figure(image, heights=None, signal: str = "height", fig: Figure | None = None) -> Figure:
    """Trace and retrace images of a scan (and the true height map), in nm over um.

    Parameters
    ----------
    image : afmsmiler.controller.ScanImage
        The scan.
    heights : array_like, optional
        The true height map in m, shown first if given.
    signal : str
        ``"height"``: the positioner image -(Z_np - its flat-sample value), what a
        constant-force AFM records; ``"topography"``: the estimate Z_c - Z_np.
    fig : matplotlib.figure.Figure, optional
        Where to draw; default a new Figure of FIGSIZE["image"] (3.3 in per image, 10 in for three).

    Returns
    -------
    matplotlib.figure.Figure
    """
    check_choice("signal", signal, ("height", "topography"))
    check_instance("image", image, ScanImage)
    if signal == "height":
        panels = [("trace: -Z_np", image.height_trace), ("retrace: -Z_np", image.height_retrace)]
    else:
        panels = [("trace: Z_c - Z_np", image.trace), ("retrace: Z_c - Z_np", image.retrace)]
    if heights is not None:
        panels.insert(0, ("true topography", check_array("heights", heights, "m", ndim=2)))
    per_image, height = FIGSIZE["image"]
    fig = (check_instance("fig", fig, Figure) if fig is not None
           else Figure(figsize=(per_image * len(panels), height)))
    axes = fig.subplots(1, len(panels), squeeze=False)[0]
    rows, cols = image.trace.shape
    extent = (0, cols * image.pixel_size * UNITS["x"], 0, rows * image.pixel_size * UNITS["x"])
    ref = panels[0][1] * UNITS["z"]
    vmin, vmax = float(np.nanmin(ref)), float(np.nanmax(ref))
    for ax, (title, data) in zip(axes, panels):
        im = ax.imshow(_finite(data * UNITS["z"]), origin="lower", extent=extent, cmap="afmhot",
                       vmin=vmin, vmax=vmax)
        ax.set(title=title, xlabel="x [um] (fast axis)", ylabel="y [um]")
    fig.colorbar(im, ax=list(axes), label="height [nm]", shrink=0.8)
    fig.set_layout_engine("constrained")
    return fig
