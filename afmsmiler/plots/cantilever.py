"""Figures of module (a): deflection, slope, surface stress, a cross-section profile, mode shapes.

:func:`cantilever_curves` converts a :class:`~afmsmiler.cantilever.Bending` (the model's result for
one load case) to the units the figures show (x in um, z in nm, theta in mrad, stress in MPa, z_b
in um, strain in microstrain; the factors come from :data:`afmsmiler.parameters.UNITS`);
:class:`CantileverFigure` draws them once and :meth:`CantileverFigure.update` moves the line data in
place, so a widget panel only swaps data. :class:`ModeShapesFigure` (and the one-call
:func:`mode_shapes_figure`) plots the first flexural mode shapes the same way. Nothing here computes
physics: every number comes from the model's result.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from ..cantilever import Bending, Cantilever, check_modes
from ..parameters import read_only, unit_scale
from ..validation import check_instance
from .limits import data_range, hold

__all__ = ["DEFAULTS", "UNITS", "CantileverCurves", "cantilever_curves", "CantileverFigure",
           "ModeShapesFigure", "mode_shapes_figure"]

#: Defaults of the figures, in one place.
DEFAULTS = read_only(dict(
    n_points=121, figsize=(10.0, 6.5), modes_figsize=(6.0, 3.2),
    min_span=1e-3))  # smallest y span in the units shown (1 pm, 1 urad, 1 kPa)

#: Display unit of each quantity shown (value_shown = value_SI * unit_scale(unit)).
UNITS = read_only(dict(x="um", z="nm", theta="mrad", stress="MPa", z_b="um",
                       strain="microstrain", youngs_modulus="GPa", frequency="kHz"))


def _scale(quantity: str) -> float:
    return unit_scale(UNITS[quantity])


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
    mode_u : ndarray
        x / L of the mode shapes.
    mode_shapes : ndarray, shape (modes, n)
        The first flexural mode shapes, 1 at the tip.
    frequencies_khz : tuple of float
        Their frequencies in kHz.
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
    mode_u: np.ndarray
    mode_shapes: np.ndarray
    frequencies_khz: tuple


def cantilever_curves(bending: Bending) -> CantileverCurves:
    """The model's result ``bending`` in the units the figures show (no physics computed here).

    Parameters
    ----------
    bending : Bending
        From :meth:`Cantilever.bending`.

    Returns
    -------
    CantileverCurves

    Raises
    ------
    TypeError
        If ``bending`` is not a :class:`~afmsmiler.cantilever.Bending`.
    """
    b = check_instance("bending", bending, Bending)
    sx, sz, st = _scale("x"), _scale("z"), _scale("stress")
    return CantileverCurves(
        x_um=b.x * sx,
        z_nm=b.deflection * sz,
        theta_mrad=b.slope * _scale("theta"),
        stress_top_mpa=b.top_stress * st,
        section_x_um=b.section_x * sx,
        z_b_um=b.section_z_b * _scale("z_b"),
        section_stress_mpa=b.section_stress * st,
        section_strain_micro=b.section_strain * _scale("strain"),
        youngs_modulus_gpa=b.lever.youngs_modulus * _scale("youngs_modulus"),
        mode_u=b.x / b.lever.length,
        mode_shapes=b.mode_shapes,
        frequencies_khz=tuple(f * _scale("frequency") for f in b.frequencies),
    )


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
        check_instance("curves", curves, CantileverCurves)
        self.fig = (check_instance("fig", fig, Figure) if fig is not None
                    else Figure(figsize=DEFAULTS["figsize"]))
        axes = self.fig.subplots(2, 2)
        self.axes = dict(z=axes[0, 0], theta=axes[0, 1], stress_top=axes[1, 0], section=axes[1, 1])
        ax = self.axes
        self.lines = {}
        u = UNITS
        xl = f"x [{u['x']}]"
        self.lines["z"], = ax["z"].plot([], [], color="C0")
        ax["z"].set(xlabel=xl, ylabel=f"deflection z [{u['z']}]", title="deflection z(x)")
        self.lines["theta"], = ax["theta"].plot([], [], color="C1")
        ax["theta"].set(xlabel=xl, ylabel=f"slope theta [{u['theta']}]", title="slope theta(x)")
        self.lines["stress_top"], = ax["stress_top"].plot([], [], color="C3")
        ax["stress_top"].set(xlabel=xl, ylabel=f"stress [{u['stress']}]",
                             title="bending stress on the top surface")
        for key in ("z", "theta", "stress_top"):
            self.lines[f"section_marker_{key}"] = ax[key].axvline(0.0, color="0.6", ls=":", lw=1)
            ax[key].axhline(0.0, color="0.85", lw=0.8)
        self.lines["section"], = ax["section"].plot([], [], color="C2", marker=".", ms=3)
        ax["section"].axvline(0.0, color="0.85", lw=0.8)
        ax["section"].set(xlabel=f"stress sigma [{u['stress']}]",
                          ylabel=f"z_b [{u['z_b']}] (0 = neutral plane)")
        self._e_gpa = curves.youngs_modulus_gpa
        # strain = stress / E, each in its display unit: r = strain shown per (stress / E) shown
        r = _scale("strain") * unit_scale(u["youngs_modulus"]) / _scale("stress")
        self.strain_axis = ax["section"].secondary_xaxis(
            "top", functions=(lambda s: s / self._e_gpa * r, lambda e: e * self._e_gpa / r))
        self.strain_axis.set_xlabel(f"strain [{u['strain']}]")
        self.fig.set_layout_engine("constrained")
        self.update(curves)

    def update(self, curves: CantileverCurves) -> None:
        """Show new curves: set the line data and the limits (no new artists).

        The limits hold while the curves stay inside them and fill a fair part of them, so that
        a slider move shows the curve move (:func:`~afmsmiler.plots.limits.sticky_limits`); the
        first draw fits the data. The y axes always show z = 0, theta = 0, stress = 0; x runs
        from the clamp (0) and keeps room beyond the tip after the length changed.

        Parameters
        ----------
        curves : CantileverCurves
            From :func:`cantilever_curves`.
        """
        reset = not getattr(self, "_limits_held", False)  # the first draw fits the data
        floor = DEFAULTS["min_span"]
        L = curves.x_um
        for key, y in (("z", curves.z_nm), ("theta", curves.theta_mrad),
                       ("stress_top", curves.stress_top_mpa)):
            self.lines[key].set_data(L, y)
            self.lines[f"section_marker_{key}"].set_xdata([curves.section_x_um] * 2)
            ax = self.axes[key]
            # from the clamp; a quarter of the length as room after a length change (not a
            # half: beyond the longest lever on the slider the axis would be mostly empty)
            hold(ax, "x", 0.0, float(L[-1]), reset=reset, margin=0.0, headroom=0.25)
            lo, hi = data_range(y, 0.0)
            hold(ax, "y", lo, hi, reset=reset, floor=floor)
        self.lines["section"].set_data(curves.section_stress_mpa, curves.z_b_um)
        ax = self.axes["section"]
        # the whole lever's peak (at least min_span / 2, so that F = 0 gives readable ticks),
        # symmetric about 0: tension on one side of the neutral plane, compression on the other
        smax = max(float(np.abs(curves.stress_top_mpa).max()), floor / 2)
        hold(ax, "x", -smax, smax, reset=reset, margin=0.1)
        h2 = abs(float(curves.z_b_um[-1]))
        hold(ax, "y", -h2, h2, reset=reset, margin=0.1)
        ax.set_title(f"cross-section at x = {curves.section_x_um:.4g} {UNITS['x']}")
        self._e_gpa = curves.youngs_modulus_gpa
        self._limits_held = True


class ModeShapesFigure:
    """The first flexural mode shapes against x/L, updated in place (a panel's second figure).

    Parameters
    ----------
    curves : CantileverCurves
        The first data to show (its ``mode_shapes`` and ``frequencies_khz``).
    fig : matplotlib.figure.Figure, optional
        Where to draw; a new pyplot-free Figure by default.
    ax : matplotlib.axes.Axes, optional
        Draw into these axes instead (``fig`` is then theirs).
    modes : sequence of int, optional
        The mode numbers of the curves' shapes, for the labels (default 1, 2, ...).

    Attributes
    ----------
    lines : list of matplotlib.lines.Line2D
        One line per mode, labelled ``"mode n: f = ... kHz"``.
    legend : matplotlib.legend.Legend
        Outside the axes, on the right, so that it never covers a curve.
    """

    def __init__(self, curves: CantileverCurves, fig: Figure | None = None, ax=None,
                 modes=None):
        curves = check_instance("curves", curves, CantileverCurves)
        if ax is not None:
            check_instance("ax", ax, Axes, "matplotlib Axes")
        n = len(curves.frequencies_khz)
        self.modes = tuple(range(1, n + 1)) if modes is None else tuple(check_modes(modes))
        if len(self.modes) != n:
            raise ValueError(f"modes must number the {n} modes of curves, got {len(self.modes)}")
        if ax is None:
            self.fig = (check_instance("fig", fig, Figure) if fig is not None
                        else Figure(figsize=DEFAULTS["modes_figsize"]))
            ax = self.fig.add_subplot()
            self.fig.set_layout_engine("constrained")
        else:
            self.fig = ax.figure
        self.ax = ax
        self.lines = [ax.plot([], [], color=f"C{i}")[0] for i in range(n)]
        ax.axhline(0.0, color="0.8", lw=0.8)
        ax.set(xlabel="x / L (dimensionless)", ylabel="mode shape, 1 at the tip (dimensionless)",
               title="flexural mode shapes", xlim=(0.0, 1.0))
        self.legend = None
        self.update(curves)

    def update(self, curves: CantileverCurves) -> None:
        """Show the mode shapes of ``curves`` (line data and labels in place).

        Parameters
        ----------
        curves : CantileverCurves
            From :func:`cantilever_curves`, with as many modes as the figure has lines.
        """
        curves = check_instance("curves", curves, CantileverCurves)
        if len(curves.frequencies_khz) != len(self.lines):
            raise ValueError(f"curves must hold {len(self.lines)} modes, got "
                             f"{len(curves.frequencies_khz)}")
        for n, line, shape, f in zip(self.modes, self.lines, curves.mode_shapes,
                                     curves.frequencies_khz):
            line.set_data(curves.mode_u, shape)
            line.set_label(f"mode {n}: f = {f:.4g} {UNITS['frequency']}")
        lo = min(-1.0, float(np.min(curves.mode_shapes, initial=0.0)))
        self.ax.set_ylim(1.1 * lo, 1.1)
        if self.legend is not None:
            self.legend.remove()
        # beside the axes: inside, every corner of [0, 1] x [-1, 1] holds a mode's curve
        self.legend = self.ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0),
                                     borderaxespad=0.0, fontsize="small")


def mode_shapes_figure(bending, modes=(1, 2, 3), *, ax=None):
    """Plot flexural mode shapes (normalised to 1 at the tip) against x/L.

    Parameters
    ----------
    bending : Bending or Cantilever
        The model's result (its mode shapes), or a lever, whose
        :meth:`~afmsmiler.cantilever.Cantilever.bending` is then computed once here.
    modes : sequence of int
        Mode numbers (1-based, at most :data:`~afmsmiler.cantilever.MAX_MODE`).
    ax : matplotlib.axes.Axes, optional
        Where to draw; a new Figure by default.

    Returns
    -------
    fig : matplotlib.figure.Figure
    lines : list of matplotlib.lines.Line2D
        One line per mode, labelled with f_n in kHz.
    """
    check_instance("bending", bending, (Bending, Cantilever), "Bending or Cantilever")
    if ax is not None:
        check_instance("ax", ax, Axes, "matplotlib Axes")
    modes = check_modes(modes)
    if isinstance(bending, Cantilever):
        bending = bending.bending(0.0, n_length=DEFAULTS["n_points"], modes=max(modes))
    elif len(bending.frequencies) < max(modes):
        raise ValueError(f"modes must be at most {len(bending.frequencies)} (the modes in "
                         f"bending), got {max(modes)}")
    c = cantilever_curves(bending)
    idx = [m - 1 for m in modes]
    c = CantileverCurves(**{**c.__dict__, "mode_shapes": c.mode_shapes[idx],
                            "frequencies_khz": tuple(c.frequencies_khz[i] for i in idx)})
    figure = ModeShapesFigure(c, ax=ax, modes=modes)
    return figure.fig, figure.lines
