"""Figures of module (a): deflection, slope, surface stress, a cross-section profile, mode shapes.

:func:`cantilever_curves` samples a :class:`~afmsmiler.cantilever.Cantilever` and converts to the
units the figures show (x in um, z in nm, theta in mrad, stress in MPa, z_b in um, strain in
microstrain); :class:`CantileverFigure` draws them once and :meth:`CantileverFigure.update`
moves the line data in place, so a widget panel only swaps data. :func:`mode_shapes_figure`
plots the first flexural mode shapes.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from matplotlib.figure import Figure

from ..cantilever import Cantilever
from ..validation import check_integer, check_range

__all__ = ["DEFAULTS", "UNITS", "CantileverCurves", "cantilever_curves", "CantileverFigure",
           "mode_shapes_figure"]

#: Defaults of the figures, in one place.
DEFAULTS = dict(n_points=201, n_section=41, figsize=(10.0, 6.5),
                min_span=1e-3)  # smallest y span in the units shown (1 pm, 1 urad, 1 kPa)

#: Factors from SI to the units shown (value_shown = value_SI * factor).
UNITS = dict(x=1e6, z=1e9, theta=1e3, stress=1e-6, z_b=1e6, strain=1e6)


@dataclass(frozen=True)
class CantileverCurves:
    """The curves of a :class:`CantileverFigure`, in the units shown on it.

    Attributes
    ----------
    x_um : ndarray
        Positions along the lever in um.
    z_nm : ndarray
        Deflection z(x) in nm.
    theta_mrad : ndarray
        Slope theta(x) in mrad.
    stress_top_mpa : ndarray
        Bending stress on the top surface (z_b = +h/2) in MPa.
    section_x_um : float
        Position of the cross-section in um.
    z_b_um : ndarray
        Levels through the thickness in um, from -h/2 to +h/2.
    section_stress_mpa : ndarray
        sigma(section_x, z_b) in MPa.
    section_strain_micro : ndarray
        Strain at the section in microstrain (1e-6).
    youngs_modulus_gpa : float
        E in GPa (links the stress and strain axes).
    """

    x_um: np.ndarray
    z_nm: np.ndarray
    theta_mrad: np.ndarray
    stress_top_mpa: np.ndarray
    section_x_um: float
    z_b_um: np.ndarray
    section_stress_mpa: np.ndarray
    section_strain_micro: np.ndarray
    youngs_modulus_gpa: float


def cantilever_curves(lever: Cantilever, force: float, section_x: float, *,
                      n_points: int = DEFAULTS["n_points"],
                      n_section: int = DEFAULTS["n_section"]) -> CantileverCurves:
    """Sample ``lever`` under an end ``force`` for the figure, in the units it shows.

    Parameters
    ----------
    lever : Cantilever
        The lever.
    force : float
        End force in N.
    section_x : float
        Position of the cross-section in m, in [0, L].
    n_points : int
        Samples along the lever (>= 2).
    n_section : int
        Samples through the thickness (>= 2).

    Returns
    -------
    CantileverCurves

    Raises
    ------
    ValueError
        If ``section_x`` is outside [0, L] or the force is not finite (from the model).
    """
    n_points = check_integer("n_points", n_points, 2, 100_000)
    n_section = check_integer("n_section", n_section, 2, 10_000)
    section_x = check_range("section_x", section_x, 0.0, lever.length, "m")
    x = np.linspace(0.0, lever.length, n_points)
    z_b = np.linspace(-0.5, 0.5, n_section) * lever.thickness
    return CantileverCurves(
        x_um=x * UNITS["x"],
        z_nm=lever.deflection(x, force) * UNITS["z"],
        theta_mrad=lever.slope(x, force) * UNITS["theta"],
        stress_top_mpa=lever.stress(x, lever.thickness / 2, force) * UNITS["stress"],
        section_x_um=section_x * UNITS["x"],
        z_b_um=z_b * UNITS["z_b"],
        section_stress_mpa=lever.stress(section_x, z_b, force) * UNITS["stress"],
        section_strain_micro=lever.strain(section_x, z_b, force) * UNITS["strain"],
        youngs_modulus_gpa=lever.youngs_modulus * 1e-9,
    )


def _pad(lo, hi, floor):
    span = max(hi - lo, floor)
    mid = 0.5 * (hi + lo)
    return mid - 0.55 * span, mid + 0.55 * span


class CantileverFigure:
    """Four panels: z(x) [nm], theta(x) [mrad], top-surface stress [MPa] and a cross-section
    profile sigma(z_b) [MPa vs um] with its strain [microstrain] on the top axis.

    Parameters
    ----------
    curves : CantileverCurves
        The first data to show.
    fig : matplotlib.figure.Figure, optional
        Where to draw; a new pyplot-free Figure by default.

    Attributes
    ----------
    lines : dict
        ``"z"``, ``"theta"``, ``"stress_top"``, ``"section"`` lines and the ``"section_marker_*"``
        vertical lines at the section position, updated in place by :meth:`update`.
    strain_axis : matplotlib.axes.Axes
        The top axis of the section plot, strain in microstrain = stress / E.
    """

    def __init__(self, curves: CantileverCurves, fig: Figure | None = None):
        self.fig = fig if fig is not None else Figure(figsize=DEFAULTS["figsize"])
        axes = self.fig.subplots(2, 2)
        self.axes = dict(z=axes[0, 0], theta=axes[0, 1], stress_top=axes[1, 0], section=axes[1, 1])
        ax = self.axes
        self.lines = {}
        self.lines["z"], = ax["z"].plot([], [], color="C0")
        ax["z"].set(xlabel="x [um]", ylabel="deflection z [nm]", title="deflection z(x)")
        self.lines["theta"], = ax["theta"].plot([], [], color="C1")
        ax["theta"].set(xlabel="x [um]", ylabel="slope theta [mrad]", title="slope theta(x)")
        self.lines["stress_top"], = ax["stress_top"].plot([], [], color="C3")
        ax["stress_top"].set(xlabel="x [um]", ylabel="stress [MPa]",
                             title="bending stress on the top surface")
        for key in ("z", "theta", "stress_top"):
            self.lines[f"section_marker_{key}"] = ax[key].axvline(0.0, color="0.6", ls=":", lw=1)
            ax[key].axhline(0.0, color="0.85", lw=0.8)
        self.lines["section"], = ax["section"].plot([], [], color="C2", marker=".", ms=3)
        ax["section"].axvline(0.0, color="0.85", lw=0.8)
        ax["section"].set(xlabel="stress sigma [MPa]", ylabel="z_b [um] (0 = neutral plane)")
        self._e_gpa = curves.youngs_modulus_gpa
        # microstrain = MPa / (E in GPa) * 1e3
        self.strain_axis = ax["section"].secondary_xaxis(
            "top", functions=(lambda s: s / self._e_gpa * 1e3, lambda e: e * self._e_gpa / 1e3))
        self.strain_axis.set_xlabel("strain [microstrain]")
        self.fig.set_layout_engine("constrained")
        self.update(curves)

    def update(self, curves: CantileverCurves) -> None:
        """Show new curves: set the line data and rescale the axes (no new artists).

        Parameters
        ----------
        curves : CantileverCurves
            From :func:`cantilever_curves`.
        """
        L = curves.x_um
        for key, y in (("z", curves.z_nm), ("theta", curves.theta_mrad),
                       ("stress_top", curves.stress_top_mpa)):
            self.lines[key].set_data(L, y)
            self.lines[f"section_marker_{key}"].set_xdata([curves.section_x_um] * 2)
            ax = self.axes[key]
            ax.set_xlim(0.0, L[-1])
            lo, hi = float(np.min(y)), float(np.max(y))
            ax.set_ylim(*_pad(min(lo, 0.0), max(hi, 0.0),
                              max(1e-3 * max(abs(lo), abs(hi)), DEFAULTS["min_span"])))
        self.lines["section"].set_data(curves.section_stress_mpa, curves.z_b_um)
        ax = self.axes["section"]
        # the whole lever's peak (at least min_span / 2, so that F = 0 gives readable ticks)
        smax = max(float(np.abs(curves.stress_top_mpa).max()), DEFAULTS["min_span"] / 2)
        ax.set_xlim(-1.1 * smax, 1.1 * smax)
        h2 = float(curves.z_b_um[-1])
        ax.set_ylim(-1.1 * h2, 1.1 * h2)
        ax.set_title(f"cross-section at x = {curves.section_x_um:.4g} um")
        self._e_gpa = curves.youngs_modulus_gpa


def mode_shapes_figure(lever: Cantilever, modes=(1, 2, 3), *, n_points: int = DEFAULTS["n_points"],
                       ax=None):
    """Plot the flexural mode shapes of ``lever`` (normalised to 1 at the tip) against x/L.

    Parameters
    ----------
    lever : Cantilever
        The lever (its mode shapes and frequencies).
    modes : sequence of int
        Mode numbers (1-based).
    n_points : int
        Samples along the lever.
    ax : matplotlib.axes.Axes, optional
        Where to draw; a new Figure by default.

    Returns
    -------
    fig : matplotlib.figure.Figure
    lines : list of matplotlib.lines.Line2D
        One line per mode, labelled with f_n in kHz.
    """
    n_points = check_integer("n_points", n_points, 2, 100_000)
    modes = [check_integer("mode", m, 1, 50) for m in modes]
    if ax is None:
        fig = Figure(figsize=(6.0, 3.5), layout="constrained")
        ax = fig.add_subplot()
    else:
        fig = ax.figure
    x = np.linspace(0.0, lever.length, n_points)
    lines = [ax.plot(x / lever.length, lever.mode_shape(x, n),
                     label=f"mode {n}: f = {lever.resonance_frequency(n) / 1e3:.4g} kHz")[0]
             for n in modes]
    ax.axhline(0.0, color="0.8", lw=0.8)
    ax.set(xlabel="x / L (dimensionless)", ylabel="mode shape, 1 at the tip (dimensionless)",
           title="flexural mode shapes")
    ax.legend(loc="lower left", fontsize="small")
    return fig, lines
