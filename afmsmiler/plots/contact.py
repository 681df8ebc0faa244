"""Figures of module (d), contact mechanics: tip geometries to scale, force curves, fits.

Units shown: lengths in nm, forces in nN (:data:`UNITS`). :func:`contact_curves` samples the model
results of one panel state and converts them; :class:`ContactFigure` draws them once and
:meth:`ContactFigure.update` swaps the line data in place, so a widget panel never rebuilds a
figure.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from matplotlib.figure import Figure

from ..contact import (TIPS, ApproachRetract, FitResult, ForceCurve, IndentationCurve, Tip,
                       contact_surface)
from ..contact.viscoelastic import ViscoelasticCycle
from ..parameters import read_only, unit_scale
from ..validation import check_instance, check_positive, check_range, check_size
from .limits import data_range, hold

__all__ = ["DEFAULTS", "UNITS", "tip_geometries_figure", "ContactCurves",
           "contact_curves", "ContactFigure", "cycles_figure", "fit_figure", "fit_label",
           "fit_window"]

#: Defaults of the figures, in one place.
DEFAULTS = read_only(dict(figsize=(10.5, 4.2), geometry_height=100e-9, n_profile=121,
                          surface_extent=3.0, fit_zoom=1e-6))

#: The longest length drawn (a tip's height, a cross-section's half-width): the figures are in
#: nm, and a millimetre is already 10**6 of them.
MAX_LENGTH = 1e-3

#: The most tips drawn side by side.
MAX_TIPS = 12

#: Factors from SI to the units shown (value_shown = value_SI * factor), from the unit table.
UNITS = read_only(dict(length=unit_scale("nm", "m"), force=unit_scale("nN", "N")))

#: Legends sit above the axes, outside the data (a legend "best" placed can still cover it).
_LEGEND_ABOVE = dict(loc="lower left", bbox_to_anchor=(0.0, 1.02), ncol=3, fontsize=8,
                     frameon=False, borderaxespad=0.0)

_COLORS = dict(approach="#1f77b4", retract="#d62728", point="k", tip="#555555", sample="#b5651d")


def tip_geometries_figure(tips=None, height=DEFAULTS["geometry_height"], fig=None) -> Figure:
    """The four tip shapes side by side, drawn to the same scale (nm, equal aspect).

    Parameters
    ----------
    tips : list of Tip, optional
        The tips to draw (1 to :data:`MAX_TIPS`); by default one of each registry class with its
        default parameters.
    height : float
        Height of the drawn tips in m, in (0, :data:`MAX_LENGTH`].
    fig : Figure, optional
        Figure to draw into.

    Returns
    -------
    Figure
    """
    if tips is None:
        tips = [cls() for cls in TIPS.values()]
    else:
        if not isinstance(tips, (list, tuple)):
            raise TypeError(f"tips must be a list or tuple of Tip, got {type(tips).__name__} "
                            f"{tips!r:.60}")
        check_size("len(tips)", len(tips), MAX_TIPS)
        tips = [check_instance(f"tips[{i}]", tip, Tip) for i, tip in enumerate(tips)]
    height = check_range("height", height, 0.0, MAX_LENGTH, "m", low_inclusive=False)
    fig = (check_instance("fig", fig, Figure) if fig is not None
           else Figure(figsize=(2.6 * len(tips), 3.2)))
    axes = fig.subplots(1, len(tips), sharex=True, sharey=True, squeeze=False)[0]
    s = UNITS["length"]
    for ax, tip in zip(axes, tips):
        x, z = tip.outline(height)
        ax.fill_between(x * s, z * s, height * s, color=_COLORS["tip"], alpha=0.35, lw=0)
        ax.plot(x * s, z * s, color=_COLORS["tip"], lw=1.5)
        ax.axhline(0.0, color=_COLORS["sample"], lw=2)
        params = ", ".join(
            f"{p.label} {p.to_display(getattr(tip, p.name)):.3g} {p.display_unit}"
            for p in tip.parameters)
        ax.set_title(f"{tip.title}\n{params}", fontsize=9)
        ax.set_aspect("equal")
        ax.set_xlabel("x [nm]")
    axes[0].set_ylabel("height above apex [nm]")
    axes[0].set_ylim(-0.1 * height * s, 1.05 * height * s)
    fig.tight_layout()
    return fig


@dataclass(frozen=True)
class ContactCurves:
    """What a :class:`ContactFigure` shows, in nm and nN.

    Attributes
    ----------
    approach_nm, approach_nN : ndarray
        Z_np and F of the approach branch.
    retract_nm, retract_nN : ndarray
        Z_np and F of the retract branch.
    point_nm, point_nN : float
        The current Z_np and F (on the approach branch).
    rho_nm : ndarray
        Radial positions of the cross-section, from -extent to +extent.
    surface_nm : ndarray
        Height of the deformed sample surface (0 = undeformed).
    tip_x_nm, tip_z_nm : ndarray
        Outline of the tip at its current position.
    depth_nm, radius_nm : float
        Current indentation Z_s and contact radius.
    """

    approach_nm: np.ndarray
    approach_nN: np.ndarray
    retract_nm: np.ndarray
    retract_nN: np.ndarray
    point_nm: float
    point_nN: float
    rho_nm: np.ndarray
    surface_nm: np.ndarray
    tip_x_nm: np.ndarray
    tip_z_nm: np.ndarray
    depth_nm: float
    radius_nm: float


def contact_curves(cycle, current, tip, extent) -> ContactCurves:
    """Sample a panel state for :class:`ContactFigure` (units: nm, nN).

    Parameters
    ----------
    cycle : ApproachRetract
        The approach-retract curves.
    current : IndentationCurve
        The current state (one point, on the approach branch).
    tip : Tip
        The tip shape.
    extent : float
        Half-width of the drawn cross-section in m, in (0, :data:`MAX_LENGTH`].

    Returns
    -------
    ContactCurves
    """
    if not isinstance(cycle, (ApproachRetract, ViscoelasticCycle)):
        raise ValueError(f"cycle must be an ApproachRetract, got {cycle!r}")
    if not isinstance(current, IndentationCurve):
        raise ValueError(f"current must be an IndentationCurve, got {current!r}")
    extent = check_range("extent", extent, 0.0, MAX_LENGTH, "m", low_inclusive=False)
    s, f = UNITS["length"], UNITS["force"]
    rho = np.linspace(-extent, extent, 2 * DEFAULTS["n_profile"] + 1)
    z_s = float(current.z_s[0])
    # the apex sits at the separation Z_c - Z_np: -Z_s in contact (above the undeformed surface
    # on a JKR neck, Z_s < 0), above the surface off contact
    apex = float(current.separation[0])
    u = contact_surface(tip, current, np.abs(rho))
    x, z = tip.outline(2 * extent)
    return ContactCurves(
        cycle.approach.z_np * s, cycle.approach.force * f, cycle.retract.z_np * s,
        cycle.retract.force * f, float(current.z_np[0]) * s, float(current.force[0]) * f,
        rho * s, -u * s, x * s, (z + apex) * s, z_s * s, float(current.contact_radius[0]) * s)


class ContactFigure:
    """F vs Z_np with the current point, and the contact drawn to scale beside it.

    Parameters
    ----------
    curves : ContactCurves
        The first state to draw.
    fig : Figure, optional
        Figure to draw into (a panel passes its own).

    Attributes
    ----------
    fig : Figure
    approach, retract, point, surface, tip : matplotlib artists updated in place.
    """

    def __init__(self, curves: ContactCurves, fig=None):
        check_instance("curves", curves, ContactCurves)
        self.fig = (check_instance("fig", fig, Figure) if fig is not None
                    else Figure(figsize=DEFAULTS["figsize"]))
        self.ax_curve, self.ax_contact = self.fig.subplots(
            1, 2, gridspec_kw=dict(width_ratios=[1.3, 1]))
        ax = self.ax_curve
        (self.approach,) = ax.plot([], [], color=_COLORS["approach"], label="approach")
        (self.retract,) = ax.plot([], [], "--", color=_COLORS["retract"], label="retract")
        (self.point,) = ax.plot([], [], "o", color=_COLORS["point"], ms=7, label="current Z_np")
        ax.axhline(0.0, color="0.7", lw=0.8)
        ax.set_xlabel("nano-positioner displacement Z_np [nm]")
        ax.set_ylabel("tip-sample force F [nN]")
        ax.legend(**_LEGEND_ABOVE)
        ax.grid(alpha=0.3)
        ax = self.ax_contact
        (self.surface,) = ax.plot([], [], color=_COLORS["sample"], lw=2, label="sample surface")
        (self.tip,) = ax.plot([], [], color=_COLORS["tip"], lw=1.5, label="tip")
        ax.set_aspect("equal", adjustable="box")
        ax.set_xlabel("x [nm] (to scale)")
        ax.set_ylabel("z [nm]")
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=2, fontsize=8,
                  frameon=False)  # under the x label: never on the drawing
        self.update(curves)
        self.fig.tight_layout()

    def update(self, curves: ContactCurves) -> None:
        """Swap in new data and set the limits (no new artists).

        The force curve's axes hold their limits while the curves stay inside them and fill a
        fair part of them (:func:`~afmsmiler.plots.limits.sticky_limits`; the first draw fits
        the data and F = 0), so that a slider move shows the curves move. The drawing of the
        contact keeps its equal-aspect box of the cross-section's extent.

        Parameters
        ----------
        curves : ContactCurves
            The new state.
        """
        reset = not getattr(self, "_limits_held", False)  # the first draw fits the data
        self.curves = curves
        self.approach.set_data(curves.approach_nm, curves.approach_nN)
        self.retract.set_data(curves.retract_nm, curves.retract_nN)
        self.point.set_data([curves.point_nm], [curves.point_nN])
        self.surface.set_data(curves.rho_nm, curves.surface_nm)
        self.tip.set_data(curves.tip_x_nm, curves.tip_z_nm)
        # F = 0 always in view (autoscale_view included the axhline at 0 too)
        hold(self.ax_curve, "x", *data_range(curves.approach_nm, curves.retract_nm,
                                             curves.point_nm), reset=reset)
        hold(self.ax_curve, "y", *data_range(curves.approach_nN, curves.retract_nN,
                                             curves.point_nN, 0.0), reset=reset)
        ext = float(curves.rho_nm.max())
        self.ax_contact.set_xlim(-ext, ext)
        self.ax_contact.set_ylim(-ext, ext)
        self.ax_contact.set_title(f"Z_s = {curves.depth_nm:.3g} nm, r = {curves.radius_nm:.3g} nm",
                                  fontsize=9)
        self._limits_held = True


def cycles_figure(cycles, fig=None) -> Figure:
    """Approach (solid) and retract (dashed) of several cycles on one F vs Z_np plot.

    Parameters
    ----------
    cycles : dict
        Label -> :class:`~afmsmiler.contact.ApproachRetract` or
        :class:`~afmsmiler.contact.ViscoelasticCycle`.
    fig : Figure, optional
        Figure to draw into.

    Returns
    -------
    Figure
    """
    fig = check_instance("fig", fig, Figure) if fig is not None else Figure(figsize=(6.5, 4.2))
    ax = fig.subplots()
    s, f = UNITS["length"], UNITS["force"]
    for i, (label, cyc) in enumerate(cycles.items()):
        color = f"C{i}"
        ax.plot(cyc.approach.z_np * s, cyc.approach.force * f, color=color,
                label=f"{label}: approach")
        ax.plot(cyc.retract.z_np * s, cyc.retract.force * f, "--", color=color,
                label=f"{label}: retract")
    ax.axhline(0.0, color="0.7", lw=0.8)
    ax.set_xlabel("nano-positioner displacement Z_np [nm]")
    ax.set_ylabel("tip-sample force F [nN]")
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=8, frameon=False)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    return fig


def fit_figure(curve, result, *, report_poisson_ratio=None, zoom=DEFAULTS["fit_zoom"],
               fig=None) -> Figure:
    """A force curve, its fitted model and the residuals (nm, nN), zoomed on the contact.

    Parameters
    ----------
    curve : ForceCurve
        The data (its force is plotted against ``result.x``).
    result : FitResult
        The fit.
    report_poisson_ratio : float, optional
        A Poisson's ratio in [0, 0.5] at which to also state E, converted from the measured
        reduced modulus: E(nu) = (1 - nu^2) E*. It may be 0.5, which the fit itself refuses.
    zoom : float or None
        Width in m of the default view around the fitted contact point: it shows the whole
        contact region and baseline before it up to this width (the contact region alone if
        it is wider). None shows the whole curve.
    fig : Figure, optional
        Figure to draw into.

    Returns
    -------
    Figure

    Raises
    ------
    ValueError
        If ``curve``/``result`` have the wrong types, ``report_poisson_ratio`` is outside
        [0, 0.5] or ``zoom`` is not > 0.

    Notes
    -----
    A fit measures only the reduced modulus E* = E / (1 - nu^2) (rigid tip); the legend states
    the Poisson's ratio the fit assumed, E and E*, so that a value quoted at another nu can be
    compared with it.
    """
    if not isinstance(curve, ForceCurve) or not isinstance(result, FitResult):
        raise ValueError("curve must be a ForceCurve and result a FitResult")
    if report_poisson_ratio is not None:
        report_poisson_ratio = check_range("report_poisson_ratio", report_poisson_ratio, 0.0, 0.5)
    if zoom is not None:
        zoom = check_positive("zoom", zoom, "m")
    fig = check_instance("fig", fig, Figure) if fig is not None else Figure(figsize=(6.5, 5.0))
    ax, axr = fig.subplots(2, 1, sharex=True, gridspec_kw=dict(height_ratios=[3, 1]))
    s, f = UNITS["length"], UNITS["force"]
    order = np.argsort(result.x)
    ax.plot(result.x * s, curve.force * f, ".", ms=2, color="0.5", label="data")
    ax.plot(result.x[order] * s, result.model_force[order] * f, color=_COLORS["retract"],
            label=fit_label(result, report_poisson_ratio))
    ax.axvline(result.contact_point * s, color="k", lw=0.8, ls=":", label="contact point")
    ax.set_ylabel("force [nN]")
    ax.legend(**{**_LEGEND_ABOVE, "ncol": 2})  # above the data; the zoom is told under the axes
    axr.plot(result.x * s, (curve.force - result.model_force) * f, ".", ms=2, color="0.3")
    axr.set_ylabel("residual [nN]")
    axr.set_xlabel("position (Z_np, or tip position) [nm]")
    if zoom is not None and fit_window(result, zoom) != (result.x.min(), result.x.max()):
        lo, hi = fit_window(result, zoom)
        axr.set_xlim(lo * s, hi * s)
        inside = (result.x >= lo) & (result.x <= hi)
        for a, y in ((ax, np.r_[curve.force[inside], result.model_force[inside]]),
                     (axr, (curve.force - result.model_force)[inside])):
            pad = 0.05 * (np.ptp(y) or 1e-12)
            a.set_ylim((y.min() - pad) * f, (y.max() + pad) * f)
        axr.set_xlabel(f"{axr.get_xlabel()}\nzoom: {(hi - lo) * 1e6:.2g} um around the contact "
                       f"point (full curve: {np.ptp(result.x) * 1e6:.2g} um)")
    fig.tight_layout()
    return fig


def fit_label(result, report_poisson_ratio=None) -> str:
    """Legend text of a fit: E at the Poisson's ratio assumed, E*, and E at another nu.

    Parameters
    ----------
    result : FitResult
        The fit.
    report_poisson_ratio : float, optional
        Also state E(nu) = (1 - nu^2) E* at this nu, in [0, 0.5].

    Returns
    -------
    str
        E.g. ``"fit at nu = 0: E = 310.8 +/- 1.4 kPa, E* = E/(1 - nu^2) = 310.8 kPa"``
        with, if asked, a second line ``"E(nu = 0.5) = (1 - nu^2) E* = 233.1 +/- 1.1 kPa"``.
    """
    if not isinstance(result, FitResult):
        raise ValueError(f"result must be a FitResult, got {result!r}")
    nu = result.poisson_ratio
    e_star = result.youngs_modulus / (1 - nu ** 2)
    e_star_err = result.youngs_modulus_error / (1 - nu ** 2)
    text = (f"fit at nu = {nu:g}: E = {result.youngs_modulus / 1e3:.4g} +/- "
            f"{result.youngs_modulus_error / 1e3:.2g} kPa, E* = E/(1 - nu^2) = "
            f"{e_star / 1e3:.4g} kPa")
    form = getattr(result.tip, "form", None)
    if form is not None:  # a pyramid: which published prefactor the modulus rests on
        text += f"\npyramid law: {form} (c = {result.tip.prefactor:.4g})"
    if report_poisson_ratio is not None:
        nu2 = check_range("report_poisson_ratio", report_poisson_ratio, 0.0, 0.5)
        text += (f"\nE(nu = {nu2:g}) = (1 - nu^2) E* = {(1 - nu2 ** 2) * e_star / 1e3:.4g} +/- "
                 f"{(1 - nu2 ** 2) * e_star_err / 1e3:.2g} kPa")
    return text


def fit_window(result, width):
    """The x range (m) of :func:`fit_figure`'s default view.

    Parameters
    ----------
    result : FitResult
        The fit.
    width : float
        Width of the view in m, > 0.

    Returns
    -------
    (lo, hi) : tuple of float
        In m, lo < hi: the contact region (from the contact point to the farthest datum on the
        side where the model force rises) and, before the contact point, baseline up to a total
        of ``width``; if the contact region alone is wider, it and width/2 of baseline. Clipped
        to the data.
    """
    check_instance("result", result, FitResult)
    width = check_positive("width", width, "m")
    x, cp = result.x, result.contact_point
    side = 1.0 if x[np.argmax(result.model_force)] >= cp else -1.0
    depth = max(float(np.max(side * (x - cp))), 0.0)
    before = max(width - depth, width / 2)
    ends = (cp - side * before, cp + side * depth)
    return max(min(ends), float(x.min())), min(max(ends), float(x.max()))
