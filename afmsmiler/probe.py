"""Module (a): "your probe", a vendor's lever (or one you describe) in air and in water, calibrated.

One call, :func:`probe_report`, gathers what the notebook's "your probe" section shows for any
:class:`~afmsmiler.planform.Lever` (rectangular, pointed or V-shaped): its spring constant and
vacuum resonance (the frame model of :mod:`afmsmiler.planform`), the frequency and Q of mode 1 in
air and in water, a thermal spectrum recorded in the chosen fluid with the laser spot where the
student puts it, the thermal-noise calibration of that spectrum and Sader's method on its fitted
f and Q, each against the true k, with the reasons they differ.

The lever in a fluid (an approximation of this module). Sader's hydrodynamic function
(:mod:`afmsmiler.hydrodynamics`) is that of a rectangular section of width b. A lever of another
planform is handed to it as its *equivalent rectangle* (:func:`equivalent_cantilever`): the mean
width b = A / L (plan-view area over length), the lever's mass per area (coating included) and
thickness, and a length and Young's modulus chosen so that the rectangle has the lever's own
spring constant k and vacuum frequency f_1. Sader's frequency and Q depend only on b, the
mass-loading ratio T = pi rho_f b / (4 rho h) and f_1 (Sader, J. Appl. Phys. 84, 64 (1998)), so
for a rectangle this is Sader's theory itself (the equivalent rectangle is the lever, to the frame
model's discretisation, 1e-6); for a pointed lever it averages the width the fluid sees over the
length; for a V-shaped lever the flow through the open V is not that of a plate, which this
approximation does not capture (Sader, Pacifico, Green and Mulvaney, J. Appl. Phys. 97, 124903
(2005), treat arbitrary planforms with a measured hydrodynamic function). The thermal spectrum
is that of the equivalent rectangle (its modes' shares and the optical-lever factor are the
rectangle's).

Sader's method as in the lab takes the plan view as it is, L and the mean width b (Sader, Chon
and Mulvaney, Rev. Sci. Instrum. 70, 3967 (1999)); for a lever that is not a rectangle the
rectangle that rings like it has another length L_e, and Sader's k is off by about L / L_e - 1
(:attr:`ProbeReport.plan_view_ratio`).

Examples
--------
>>> from afmsmiler.planform import preset
>>> report = probe_report(preset("ContAl-G"), "water", seed=1)
>>> round(report.modes["water"].quality_factor, 1)
2.3
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from .calibration import (LIMITS, ThermalCalibration, ThermalSpectrum, optical_lever_correction,
                          sader_spring_constant, thermal_calibration, thermal_spectrum)
from .cantilever import Cantilever
from .hydrodynamics import FLUID_NAMES, LOW_Q, fluid_mode  # FLUID_NAMES: the fluids a report compares
from .parameters import Parameter, read_only
from .planform import Lever
from .validation import (check_array, check_choice, check_instance, check_integer,
                         check_range, check_size)

__all__ = ["SPOT", "FLUID_NAMES", "DEFAULTS", "mean_width", "equivalent_cantilever",
           "planform_outline", "half_widths", "ProbeReport", "probe_report", "oscillator"]

#: Where the laser spot sits on the lever, as a fraction x/L of its length from the clamp.
SPOT = Parameter(name="spot", unit="", default=1.0, low=0.0, high=1.0, low_inclusive=False,
                 slider_low=0.4, slider_high=1.0, label="laser spot x/L")

#: The report's defaults: the thermal spectrum's bins and averages (2^14 bins of 16 averages: a
#: panel step of a few milliseconds, a statistical error of k of about 2 % for a contact lever in
#: air), the noise's seed, and the Q below which the methods' assumptions (an oscillator line,
#: Q >> 1) are called out (:data:`afmsmiler.hydrodynamics.LOW_Q`).
DEFAULTS = read_only(dict(points=2 ** 14, averages=16, seed=0, low_q=LOW_Q, resolved_bins=5.0))


def mean_width(lever: Lever) -> float:
    """The mean width A / L of a lever's plan view in m (the width, for a rectangle).

    Parameters
    ----------
    lever : Lever
        The lever.

    Returns
    -------
    float
    """
    lever = check_instance("lever", lever, Lever)
    return lever.area / lever.length


def equivalent_cantilever(lever: Lever) -> Cantilever:
    """The rectangle that the fluid and the thermal spectrum see for ``lever`` (module notes).

    Width the mean width A / L, thickness t, density the lever's mass per area over t (its
    coating included); length L_e and Young's modulus E_e such that k and f_1 equal the lever's
    (k ~ E / L^3 and f_1 ~ sqrt(E) / L^2 at fixed width, thickness and density, scaled from
    the rectangle of the lever's own L and E). For a rectangular lever it is that rectangle.

    Parameters
    ----------
    lever : Lever
        Any planform; its tip at the free end or elsewhere (k is the tip's).

    Returns
    -------
    Cantilever
    """
    lever = check_instance("lever", lever, Lever)
    b, t = mean_width(lever), lever.thickness
    density = lever.section[2] / t
    reference = Cantilever(lever.length, b, t, lever.youngs_modulus, density)
    kappa = lever.spring_constant / reference.spring_constant
    phi = lever.resonance_frequency(1) / reference.resonance_frequency(1)
    length = lever.length * kappa / phi ** 2
    return Cantilever(length, b, t, lever.youngs_modulus * kappa * (length / lever.length) ** 3,
                      density)


def planform_outline(lever: Lever) -> tuple:
    """The plan view's outline as a closed polygon (x along the lever from the clamp, y across).

    Parameters
    ----------
    lever : Lever
        The lever.

    Returns
    -------
    x, y : ndarray
        Vertices in m, the first repeated at the end.
    """
    lever = check_instance("lever", lever, Lever)
    L, h = lever.length, lever.width / 2
    if lever.planform == "rectangular":
        x, y = [0, L, L, 0, 0], [-h, -h, h, h, -h]
    elif lever.planform == "pointed":
        a = lever.point_length
        x, y = [0, L - a, L, L - a, 0, 0], [-h, -h, 0, h, h, -h]
    else:   # the outer edges to the apex, the inner ones to x_j where the arms meet
        inner = h - lever.arm_width / math.cos(lever.half_angle)
        x, y = [0, L, 0, 0, lever.solid_from, 0, 0], [-h, 0, h, inner, 0, -inner, -h]
    return np.array(x, float), np.array(y, float)


def half_widths(lever: Lever, x) -> tuple:
    """The plan view's section at ``x`` on one side of the axis: from ``inner`` to ``outer``.

    The lever is symmetric about its axis (y = 0); on the side y >= 0 it covers
    inner(x) <= y <= outer(x) (:func:`planform_outline`): a rectangle or a pointed lever from the
    axis (inner = 0) to its half width (narrowing linearly over the point), a V-shaped lever from
    its arm's inner edge to its outer edge where the arms are apart (x < x_j) and from the axis to
    the outer edge where they meet.

    Parameters
    ----------
    lever : Lever
        The lever.
    x : array_like
        Positions along the lever in m, in [0, L].

    Returns
    -------
    inner, outer : ndarray
        In m, 0 <= inner <= outer.
    """
    lever = check_instance("lever", lever, Lever)
    L, h = lever.length, lever.width / 2
    x = check_array("x", x, "m", low=0.0, high=L)
    if lever.planform == "rectangular":
        return np.zeros_like(x), np.full_like(x, h)
    if lever.planform == "pointed":
        a = lever.point_length
        return np.zeros_like(x), h * np.clip((L - x) / a, 0.0, 1.0)
    inner0 = h - lever.arm_width / math.cos(lever.half_angle)
    return (inner0 * np.clip(1.0 - x / lever.solid_from, 0.0, 1.0), h * (1.0 - x / L))


@dataclass(frozen=True)
class ProbeReport:
    """A lever in air and in water, and its calibration in one of them (:func:`probe_report`).

    Attributes
    ----------
    lever : Lever
        The lever.
    cantilever : Cantilever
        Its equivalent rectangle (:func:`equivalent_cantilever`).
    fluid : str
        The fluid of the spectrum and the calibration (a key of :data:`FLUID_NAMES`).
    modes : dict
        Mode 1 in each fluid of :data:`FLUID_NAMES`, a :class:`FluidMode` by key.
    spectrum : ThermalSpectrum
        The recorded thermal spectrum (in ``fluid``, the spot at ``spot``).
    thermal : ThermalCalibration
        The thermal-noise calibration, the spot assumed at ``assumed_spot``.
    sader : float
        Sader's k in N/m from the plan view (L, mean width) and the fitted f and Q (NaN where
        the Reynolds number leaves the range of Sader's function).
    spot : float
        Where the spot really is, x/L.
    assumed_spot : float
        Where the calibration assumes it, x/L.
    """

    lever: Lever
    cantilever: Cantilever
    fluid: str
    modes: dict
    spectrum: ThermalSpectrum
    thermal: ThermalCalibration
    sader: float
    spot: float
    assumed_spot: float

    @property
    def spring_constant(self) -> float:
        """The model's true k in N/m (the frame model's, at the tip)."""
        return self.lever.spring_constant

    @property
    def vacuum_frequency(self) -> float:
        """f_1 in vacuum in Hz."""
        return self.lever.resonance_frequency(1)

    @property
    def thermal_error(self) -> float:
        """k_thermal / k - 1."""
        return self.thermal.spring_constant / self.spring_constant - 1.0

    @property
    def sader_error(self) -> float:
        """k_Sader / k - 1 (NaN where Sader's method did not apply)."""
        return self.sader / self.spring_constant - 1.0

    @property
    def spot_bias(self) -> float:
        """(chi(spot) / chi(assumed_spot))^2: the factor a misplaced spot puts on the thermal k.

        The detector reports z* = z / chi(spot) and the calibration divides by chi(assumed)^2,
        so k_thermal = k chi(spot)^2 / chi(assumed)^2 (module (a)'s optical lever,
        :func:`~afmsmiler.calibration.optical_lever_correction`).
        """
        return (optical_lever_correction(1, self.spot)
                / optical_lever_correction(1, self.assumed_spot)) ** 2

    @property
    def plan_view_ratio(self) -> float:
        """L / L_e: the plan view's length over the equivalent rectangle's (1 for a rectangle).

        Sader's k is proportional to the length it is given; a lever that is not a rectangle
        rings like a rectangle of length L_e, so Sader's k from the plan view is off by about
        this factor.
        """
        return self.lever.length / self.cantilever.length

    def reasons(self) -> list:
        """Why the calibrated spring constants differ from the true k, in words with numbers.

        Returns
        -------
        list of str
        """
        out = []
        fit, d = self.thermal.fit, DEFAULTS
        sigma = self.thermal.uncertainty / self.thermal.spring_constant
        out.append(f"thermal: statistical error +-{100 * sigma:.1f} % "
                   f"from {self.spectrum.frequency.size} bins of {self.spectrum.averages} "
                   f"averaged spectra (a longer record or more averages shrink it)")
        if not math.isclose(self.spot, self.assumed_spot, rel_tol=1e-9):
            out.append(f"thermal: the spot sits at x/L = {self.spot:.3g}, the calibration assumes "
                       f"{self.assumed_spot:.3g}: k off by (chi(spot) / chi(assumed))^2 = "
                       f"{self.spot_bias:.3f}")
        if self.lever.planform == "v_shaped" and self.spot * self.lever.length \
                < self.lever.solid_from:
            out.append(f"the spot at x/L = {self.spot:.3g} lies between the arms of the V (they "
                       f"meet at x/L = {self.lever.solid_from / self.lever.length:.3g}): no light "
                       f"would come back")
        if fit.bins_per_linewidth < d["resolved_bins"]:
            out.append(f"thermal: the peak is {fit.bins_per_linewidth:.2g} bins wide, too few "
                       f"to resolve it: record longer")
        mode = self.modes[self.fluid]
        if mode.quality_factor < d["low_q"]:
            out.append(f"thermal: at Q = {mode.quality_factor:.2g} the peak is no oscillator line "
                       f"(the fluid's damping changes across it)")
            out.append(f"Sader: the method assumes Q >> 1, here Q = {mode.quality_factor:.2g}")
        if not math.isfinite(self.sader):
            out.append("Sader: the fitted resonance's Reynolds number is outside the range of "
                       "Sader's hydrodynamic function")
        if self.lever.planform != "rectangular":
            out.append(f"Sader: the plan view is not a rectangle; the rectangle of the same "
                       f"mean width that rings like this lever is {1 / self.plan_view_ratio:.3g} "
                       f"L long, so k from L is off by about {self.plan_view_ratio:.3g}x")
        return out


@functools.lru_cache(maxsize=32)
def _fluid_modes(rectangle: Cantilever) -> dict:
    """Mode 1 of ``rectangle`` in each fluid of :data:`FLUID_NAMES` (kept for the same lever:
    a panel's spot or fluid moves need not solve them again)."""
    return read_only({name: fluid_mode(rectangle, name, 1) for name in FLUID_NAMES})


def oscillator(lever: Lever, fluid: str = "air") -> dict:
    """Mode 1 of ``lever`` in ``fluid`` as the point-mass oscillator of the modes' models.

    Sader's frequency and Q of mode 1 of the equivalent rectangle (module notes) and the mode's
    stiffness at the tip, k_1 = k lambda_1^4 / 12 (:meth:`~afmsmiler.hydrodynamics.FluidMode.
    oscillator`): ``TappingLever(**oscillator(preset("AC160TS"), "water"), ...)`` taps in
    water with the Q the water gives, not a typed one.

    Parameters
    ----------
    lever : Lever
        Any planform (a vendor's :func:`~afmsmiler.planform.preset`).
    fluid : str
        ``"air"`` or ``"water"``.

    Returns
    -------
    dict
        ``spring_constant`` (N/m), ``resonance_frequency`` (Hz, in the fluid),
        ``quality_factor``.

    Examples
    --------
    >>> from afmsmiler.planform import preset
    >>> round(oscillator(preset("ContAl-G"), "water")["quality_factor"], 1)
    2.3
    """
    lever = check_instance("lever", lever, Lever)
    fluid = check_choice("fluid", fluid, FLUID_NAMES)
    return _fluid_modes(equivalent_cantilever(lever))[fluid].oscillator()


def probe_report(lever: Lever, fluid: str = "air", *, spot: float = SPOT.default,
                 assumed_spot: float = 1.0, points: int = DEFAULTS["points"],
                 averages: int = DEFAULTS["averages"], seed: int = DEFAULTS["seed"]) -> ProbeReport:
    """Mode 1 of ``lever`` in air and water, a thermal spectrum in ``fluid`` and its calibration.

    Frequencies and Q from :func:`~afmsmiler.hydrodynamics.fluid_mode` of the equivalent
    rectangle (module notes), the spectrum from :func:`~afmsmiler.calibration.thermal_spectrum`,
    the thermal-noise method from :func:`~afmsmiler.calibration.thermal_calibration` and
    Sader's from :func:`~afmsmiler.calibration.sader_spring_constant` with the plan view's L and
    mean width and the fit's f and Q.

    Parameters
    ----------
    lever : Lever
        The lever (a vendor's :func:`~afmsmiler.planform.preset` or one of its constructors).
    fluid : str
        ``"air"`` or ``"water"``: where the spectrum is recorded.
    spot : float
        Where the laser spot really is, x/L in (0, 1].
    assumed_spot : float
        Where the calibration assumes it, x/L in (0, 1].
    points : int
        Bins of the spectrum, 16 to 2^22 (the panel's 2^14 by default).
    averages : int
        Spectra averaged, 1 to 100 000.
    seed : int
        The noise's seed, 0 to 2^63 - 1 (the same seed, the same noise).

    Returns
    -------
    ProbeReport
    """
    lever = check_instance("lever", lever, Lever)
    fluid = check_choice("fluid", fluid, FLUID_NAMES)
    spot = SPOT.check(spot)
    assumed_spot = check_range("assumed_spot", assumed_spot, 0.0, 1.0, low_inclusive=False)
    points = check_size("points", points, LIMITS["points"], 16)
    averages = check_size("averages", averages, LIMITS["averages"])
    seed = check_integer("seed", seed, 0, 2 ** 63 - 1)
    rectangle = equivalent_cantilever(lever)
    modes = _fluid_modes(rectangle)
    spectrum = thermal_spectrum(rectangle, fluid, points=points, averages=averages, spot=spot,
                                seed=seed)
    thermal = thermal_calibration(spectrum, spot=assumed_spot)
    try:
        sader = sader_spring_constant(lever.length, mean_width(lever),
                                      thermal.fit.resonance_frequency,
                                      thermal.fit.quality_factor, fluid)
    except ValueError:   # the fitted f outside Sader's Reynolds range: the method does not apply
        sader = math.nan
    return ProbeReport(lever=lever, cantilever=rectangle, fluid=fluid, modes=modes,
                       spectrum=spectrum, thermal=thermal, sader=sader, spot=spot,
                       assumed_spot=assumed_spot)
