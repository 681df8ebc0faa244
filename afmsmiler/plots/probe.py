"""The "your probe" figure of module (a): the thermal spectrum and its fit, the lever's plan view.

:func:`probe_curves` converts a :class:`~afmsmiler.probe.ProbeReport` to the units shown
(frequency in kHz, spectral density in pm^2/Hz, lengths in um; the factors come from
:data:`afmsmiler.parameters.UNITS`); :class:`ProbeFigure` draws two axes once and moves their data
in place (:meth:`ProbeFigure.update`). Nothing here computes physics: the spectrum, its true mean,
the fitted line and the outline all come from the model.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from matplotlib.figure import Figure

from ..parameters import read_only, unit_scale
from ..probe import ProbeReport, planform_outline
from ..validation import check_instance
from .limits import data_range, hold

__all__ = ["DEFAULTS", "UNITS", "ProbeCurves", "probe_curves", "ProbeFigure"]

#: Figure defaults: the size, and how far below the fitted peak the frequency axis starts (a
#: factor).
DEFAULTS = read_only(dict(figsize=(10.0, 3.6), below_peak=30.0))
#: Display unit of each quantity shown.
UNITS = read_only(dict(frequency="kHz", psd="pm^2/Hz", length="um"))


@dataclass(frozen=True)
class ProbeCurves:
    """What :class:`ProbeFigure` draws, in the units shown on it.

    Attributes
    ----------
    frequency_khz : ndarray
        The spectrum's bins in kHz.
    psd : ndarray
        The recorded one-sided deflection spectrum in pm^2/Hz.
    expected : ndarray
        Its mean (the true spectrum) in pm^2/Hz.
    fitted_khz : ndarray
        The fitted band's bins in kHz.
    fitted : ndarray
        The fitted oscillator line plus background there, in pm^2/Hz.
    f0_khz : float
        The fitted resonance in kHz.
    quality_factor : float
        The fitted Q.
    fluid : str
        The medium.
    outline_x_um, outline_y_um : ndarray
        The plan view's outline in um.
    spot_um : float
        The laser spot's position along the lever in um.
    tip_um : float
        The tip's position in um.
    name : str
        The lever's name (a vendor's product, or "custom").
    """

    frequency_khz: np.ndarray
    psd: np.ndarray
    expected: np.ndarray
    fitted_khz: np.ndarray
    fitted: np.ndarray
    f0_khz: float
    quality_factor: float
    fluid: str
    outline_x_um: np.ndarray
    outline_y_um: np.ndarray
    spot_um: float
    tip_um: float
    name: str


def probe_curves(report: ProbeReport) -> ProbeCurves:
    """The model's ``report`` in the units the figure shows (no physics computed here).

    Parameters
    ----------
    report : ProbeReport
        From :func:`~afmsmiler.probe.probe_report`.

    Returns
    -------
    ProbeCurves
    """
    report = check_instance("report", report, ProbeReport)
    s, fit, lever = report.spectrum, report.thermal.fit, report.lever
    fk, pk, um = unit_scale(UNITS["frequency"]), unit_scale(UNITS["psd"]), unit_scale("um")
    x, y = planform_outline(lever)
    band = (s.frequency >= fit.band[0]) & (s.frequency <= fit.band[1])   # the fitted bins
    return ProbeCurves(
        frequency_khz=s.frequency * fk, psd=s.psd * pk, expected=s.expected * pk,
        fitted_khz=s.frequency[band] * fk, fitted=fit.model(s.frequency[band]) * pk,
        f0_khz=fit.resonance_frequency * fk, quality_factor=fit.quality_factor,
        fluid=report.fluid, outline_x_um=x * um, outline_y_um=y * um,
        spot_um=report.spot * lever.length * um, tip_um=lever.tip_position * um,
        name=lever.name or "custom")


class ProbeFigure:
    """Two axes: the thermal spectrum with its true mean and the fit; the lever's plan view.

    Parameters
    ----------
    curves : ProbeCurves
        The first data to show.
    fig : matplotlib.figure.Figure, optional
        Where to draw; a new pyplot-free Figure by default.

    Attributes
    ----------
    axes : dict
        ``"spectrum"`` and ``"plan"``.
    lines : dict
        ``"psd"``, ``"expected"``, ``"fitted"``, ``"f0"``, ``"outline"``, ``"spot"``, ``"tip"``,
        updated in place.
    """

    def __init__(self, curves: ProbeCurves, fig: Figure | None = None):
        check_instance("curves", curves, ProbeCurves)
        self.fig = (check_instance("fig", fig, Figure) if fig is not None
                    else Figure(figsize=DEFAULTS["figsize"]))
        spectrum, plan = self.fig.subplots(1, 2, width_ratios=(1.6, 1.0))
        self.axes = dict(spectrum=spectrum, plan=plan)
        u, ln = UNITS, {}
        ln["psd"], = spectrum.loglog([1.0], [1.0], color="0.6", lw=0.6, label="recorded")
        ln["expected"], = spectrum.loglog([1.0], [1.0], color="C0", lw=1.2, label="true mean")
        ln["fitted"], = spectrum.loglog([1.0], [1.0], color="C3", lw=1.2, ls="--",
                                        label="SHO fit")
        ln["f0"] = spectrum.axvline(1.0, color="C3", ls=":", lw=0.8)
        spectrum.set(xlabel=f"frequency [{u['frequency']}]",
                     ylabel=f"deflection PSD [{u['psd']}]")
        spectrum.legend(loc="upper left", fontsize="small")
        ln["outline"], = plan.plot([], [], color="0.3", lw=1.2)
        ln["tip"], = plan.plot([], [], "^", color="C2", ms=7, label="tip")
        ln["spot"], = plan.plot([], [], "o", color="C3", ms=8, label="laser spot")
        plan.axhline(0.0, color="0.85", lw=0.8)
        plan.set_aspect("equal")   # the true shape
        plan.set(xlabel=f"x [{u['length']}] (from the clamp)", ylabel=f"y [{u['length']}]")
        plan.legend(loc="upper left", fontsize="small")
        self.lines = ln
        self.fig.set_layout_engine("constrained")
        self.update(curves)

    def update(self, curves: ProbeCurves) -> None:
        """Show new curves: line data, titles and limits in place.

        Parameters
        ----------
        curves : ProbeCurves
            From :func:`probe_curves`.
        """
        c = check_instance("curves", curves, ProbeCurves)
        ax, ln = self.axes, self.lines
        ln["psd"].set_data(c.frequency_khz, c.psd)
        ln["expected"].set_data(c.frequency_khz, c.expected)
        ln["fitted"].set_data(c.fitted_khz, c.fitted)
        ln["f0"].set_xdata([c.f0_khz] * 2)
        # from 1/30 of the peak (the floor of the line's low side) to the last bin
        low = max(float(c.frequency_khz[0]), c.f0_khz / DEFAULTS["below_peak"])
        ax["spectrum"].set_xlim(low, float(c.frequency_khz[-1]))
        hold(ax["spectrum"], "y", *data_range(c.psd, c.expected, log=True), reset=True,
             log=True, margin=0.05)
        ax["spectrum"].set_title(f"thermal spectrum in {c.fluid}: fit f0 = {c.f0_khz:.4g} "
                                 f"{UNITS['frequency']}, Q = {c.quality_factor:.3g}",
                                 fontsize="medium")
        ln["outline"].set_data(c.outline_x_um, c.outline_y_um)
        ln["tip"].set_data([c.tip_um], [0.0])
        ln["spot"].set_data([c.spot_um], [0.0])
        length = float(np.max(c.outline_x_um))
        half = float(np.max(np.abs(c.outline_y_um)))
        span = max(length, 2 * half)
        ax["plan"].set_xlim(-0.05 * span, 1.05 * span)
        ax["plan"].set_ylim(-0.55 * span, 0.55 * span)
        ax["plan"].set_title(f"{c.name}: plan view", fontsize="medium")
