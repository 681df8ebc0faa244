"""Module (a): a rectangular lever in a viscous fluid (air, water), after Sader (1998).

A lever of width b, thickness h and density rho vibrating at angular frequency omega in a fluid of
density rho_f and viscosity eta feels, per unit length, the hydrodynamic force (Sader, "Frequency
response of cantilever beams immersed in viscous fluids with applications to the atomic force
microscope", J. Appl. Phys. 84, 64 (1998); time dependence exp(-i omega t))::

    F_hydro(x | omega) = (pi / 4) rho_f omega^2 b^2 Gamma(omega) W(x | omega)

with the dimensionless hydrodynamic function Gamma = Gamma_r + i Gamma_i of the Reynolds number::

    Re = rho_f omega b^2 / (4 eta)                                        (Sader 1998)

Its real part is an added mass (pi/4 rho_f b^2 Gamma_r per length), its imaginary part the
viscous damping. For a circular cylinder of diameter b it is exact (Stokes; Sader 1998, Eq. (18))::

    Gamma_circ(omega) = 1 + 4 i K_1(-i sqrt(i Re)) / (sqrt(i Re) K_0(-i sqrt(i Re)))

and for the thin rectangular section of a lever Sader writes Gamma_rect = Omega(Re) Gamma_circ
(Eq. (20)) with the correction Omega = Omega_r + i Omega_i fitted to Tuck's exact numerical
solution by the rational functions of tau = log10(Re) of Eqs. (21a), (21b) and (22); Sader
validated the fit for 1e-6 <= Re <= 1e4 (:data:`REYNOLDS_RANGE`), which covers AFM levers in gases
and liquids. The fifth-order coefficient of Omega_i is -0.000044510, as printed in Eq. (21b) and
in the authors' own calibration code (some reimplementations carry -0.000045510, a typo).

Outside that range :func:`hydrodynamic_function` refuses a Reynolds number unless asked to
extrapolate; then Gamma_circ stays exact and Omega is held at its value at the nearer end of the
range (Omega tends to a constant at both ends: Omega -> 1 as Re -> infinity, where Gamma_rect
-> 1, the inviscid added mass pi rho_f b^2 / 4 of a flat plate).

The modes in the fluid
----------------------
With the mass-loading ratio T = pi rho_f b / (4 rho h), flexural mode n of vacuum frequency
omega_vac,n rings in the fluid at the frequency and with the quality factor (Sader 1998, the
limit of weak dissipation, Q >> 1; restated by Sader, Chon and Mulvaney, Rev. Sci.
Instrum. 70, 3967 (1999), as the basis of their calibration)::

    omega_R,n = omega_vac,n (1 + T Gamma_r(omega_R,n))^(-1/2)   (solved self-consistently)
    Q_n       = (1/T + Gamma_r(omega_R,n)) / Gamma_i(omega_R,n)

each mode with its own frequency (:func:`fluid_mode`). The mode's stiffness seen at the tip is
k_n = k / share_n = k (b_n L)^4 / 12 (Butt and Jaschke, Nanotechnology 6, 1 (1995); Melcher, Hu
and Raman, Appl. Phys. Lett. 91, 053101 (2007)), 1.030 k for mode 1. :meth:`FluidMode.oscillator`
hands (k_n, f_R,n, Q_n) to the models that take a point-mass lever (module (g)'s tapping, FM and
Q-control levers, :class:`~afmsmiler.modes.oscillator.Oscillator`); its ``quality_factor`` is the
medium's Q for the Brownian spectrum and the lock-in's probe.

Examples
--------
>>> from afmsmiler.cantilever import Cantilever
>>> lever = Cantilever.from_material("silicon", length=450e-6, width=50e-6, thickness=2e-6)
>>> m = fluid_mode(lever, "air")
>>> round(m.resonance_frequency / lever.resonance_frequency(1), 4), round(m.quality_factor)
(0.9876, 56)
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.special
from scipy.optimize import brentq

from .cantilever import MAX_MODE, Cantilever, eigenvalue
from .parameters import Parameter, read_only
from .validation import check_array, check_flag, check_instance, check_integer, check_range

__all__ = ["FLUID_DENSITY", "VISCOSITY", "PARAMETERS", "REYNOLDS_RANGE", "Fluid", "FLUIDS",
           "FLUID_NAMES", "LOW_Q", "get_fluid", "reynolds_number", "circular_hydrodynamic_function",
           "rectangular_correction", "hydrodynamic_function", "FluidMode", "fluid_mode",
           "fluid_modes", "mass_loading"]

#: Fluid density rho_f: from a rarefied gas to the densest liquids (mercury 13 534 kg/m^3).
FLUID_DENSITY = Parameter(name="density", unit="kg/m^3", default=998.2, low=1e-3, high=2e4,
                          slider_low=0.1, slider_high=2000.0, log=True,
                          label="fluid density rho_f")
#: Dynamic viscosity eta: from a gas (~1e-5 Pa s) to glycerol (~1 Pa s) and beyond.
VISCOSITY = Parameter(name="viscosity", unit="Pa s", default=1.002e-3, low=1e-7, high=1e3,
                      slider_low=1e-5, slider_high=1.0, log=True,
                      label="fluid viscosity eta")
#: The fluid's quantities by name (read-only).
PARAMETERS = read_only({"density": FLUID_DENSITY, "viscosity": VISCOSITY})

#: Reynolds numbers over which Sader validated his fit of Omega (Sader 1998, Eqs. (21), (22)).
REYNOLDS_RANGE = (1e-6, 1e4)

# Temperatures the presets' correlations hold for (K): liquid water at 1 atm, air as an ideal gas
# with Sutherland's viscosity.
_WATER_T = (273.15, 373.15)
_AIR_T = (150.0, 600.0)
_AIR_P = (1.0, 1e7)

# Sader 1998, Eqs. (21a), (21b): Omega_r and Omega_i as ratios of polynomials in tau = log10(Re)
# (coefficients in increasing powers of tau).
_OMEGA_R_NUM = (0.91324, -0.48274, 0.46842, -0.12886, 0.044055, -0.0035117, 0.00069085)
_OMEGA_R_DEN = (1.0, -0.56964, 0.48690, -0.13444, 0.045155, -0.0035862, 0.00069085)
_OMEGA_I_NUM = (-0.024134, -0.029256, 0.016294, -0.00010961, 0.000064577, -0.000044510)
_OMEGA_I_DEN = (1.0, -0.59702, 0.55182, -0.18357, 0.079156, -0.014369, 0.0028361)


@dataclass(frozen=True)
class Fluid:
    """A Newtonian fluid: its density and viscosity (SI units).

    Parameters
    ----------
    name : str
        What it is ("water at 20 C").
    density : float
        Density rho_f in kg/m^3, in [1e-3, 2e4].
    viscosity : float
        Dynamic viscosity eta in Pa s, in [1e-7, 1e3].
    source : str
        Where the figures come from.

    Raises
    ------
    ValueError
        Naming ``density`` or ``viscosity`` when it is not a finite number in its range (a
        negative viscosity, say), before any work.

    Examples
    --------
    >>> Fluid("oil", density=870.0, viscosity=-0.1)
    Traceback (most recent call last):
    ...
    ValueError: viscosity must be in [1e-07, 1000] Pa s, got -0.1
    """

    name: str
    density: float
    viscosity: float
    source: str = ""

    def __post_init__(self):
        check_instance("name", self.name, str)
        check_instance("source", self.source, str)
        object.__setattr__(self, "density", FLUID_DENSITY.check(self.density))
        object.__setattr__(self, "viscosity", VISCOSITY.check(self.viscosity))

    @property
    def kinematic_viscosity(self) -> float:
        """nu = eta / rho_f in m^2/s."""
        return self.viscosity / self.density

    @classmethod
    def water(cls, temperature: float = 293.15) -> "Fluid":
        """Liquid water at 1 atm and ``temperature``.

        Density from Kell's rational formula in the Celsius temperature (G. S. Kell, J. Chem.
        Eng. Data 20, 97 (1975), 0 to 150 C), viscosity from the Vogel-type fit
        eta = A 10^(B / (T - C)) with A = 2.414e-5 Pa s, B = 247.8 K, C = 140 K (the common
        engineering fit, within 2.5 % from 0 to 370 C). At 20 C: 998.2 kg/m^3 and 1.002 mPa s
        (CRC Handbook: 998.21 kg/m^3, 1.0016 mPa s; tested at 20 and 25 C).

        Parameters
        ----------
        temperature : float
            T in K, in [273.15, 373.15].

        Returns
        -------
        Fluid
        """
        temperature = check_range("temperature", temperature, *_WATER_T, "K")
        t = temperature - 273.15
        density = ((999.83952 + 16.945176 * t - 7.9870401e-3 * t ** 2 - 46.170461e-6 * t ** 3
                    + 105.56302e-9 * t ** 4 - 280.54253e-12 * t ** 5) / (1.0 + 16.879850e-3 * t))
        viscosity = 2.414e-5 * 10.0 ** (247.8 / (temperature - 140.0))
        return cls(f"water at {t:.4g} C", density, viscosity,
                   "Kell, J. Chem. Eng. Data 20, 97 (1975); Vogel equation")

    @classmethod
    def air(cls, temperature: float = 293.15, pressure: float = 101325.0) -> "Fluid":
        """Dry air as an ideal gas at ``temperature`` and ``pressure``.

        Density p M / (R T) with M = 28.9647 g/mol; viscosity from Sutherland's law
        eta = 1.716e-5 Pa s (T / 273.15 K)^(3/2) (273.15 K + S) / (T + S), S = 110.4 K (F. M.
        White, *Viscous Fluid Flow*, 3rd ed. (2006), Ch. 1), independent of pressure. At 20 C and 1 atm: 1.204 kg/m^3 and 1.813e-5 Pa s (CRC Handbook: 1.204
        kg/m^3, 1.81e-5 Pa s).

        Parameters
        ----------
        temperature : float
            T in K, in [150, 600].
        pressure : float
            p in Pa, in [1, 1e7].

        Returns
        -------
        Fluid
        """
        temperature = check_range("temperature", temperature, *_AIR_T, "K")
        pressure = check_range("pressure", pressure, *_AIR_P, "Pa")
        density = pressure * 28.9647e-3 / (8.314462618 * temperature)
        viscosity = 1.716e-5 * (temperature / 273.15) ** 1.5 * (273.15 + 110.4) / (
            temperature + 110.4)
        return cls(f"air at {temperature - 273.15:.4g} C, {pressure:.6g} Pa", density, viscosity,
                   "ideal gas, M = 28.9647 g/mol; Sutherland's law (White, Viscous Fluid Flow)")


#: Presets: air and water at 20 C and 1 atm, and the air of Sader, Chon and Mulvaney (1999)
#: (rho_f = 1.18 kg/m^3, eta = 1.86e-5 Pa s, the figures of their calibration and code).
FLUIDS = read_only({
    "air": Fluid.air(293.15),
    "water": Fluid.water(293.15),
    "air_sader1999": Fluid("air (Sader et al. 1999)", 1.18, 1.86e-5,
                           "Sader, Chon and Mulvaney, Rev. Sci. Instrum. 70, 3967 (1999)"),
})

#: The media a student chooses between in the panels (keys of :data:`FLUIDS`).
FLUID_NAMES = ("air", "water")
#: Sader's Q is a weak-damping result (Q >> 1): below this Q the models that take it say that one
#: oscillator with that Q (a Lorentzian line, a fixed damping) describes the mode only roughly.
LOW_Q = 5.0


def get_fluid(fluid) -> Fluid:
    """A preset by key (``"air"``, ``"water"``, see :data:`FLUIDS`), or a Fluid passed through.

    Parameters
    ----------
    fluid : str or Fluid
        The key or the fluid.

    Returns
    -------
    Fluid

    Raises
    ------
    TypeError
        If ``fluid`` is neither a str nor a Fluid.
    ValueError
        For an unknown key.
    """
    if isinstance(fluid, Fluid):
        return fluid
    check_instance("fluid", fluid, str, "key of FLUIDS (str) or a Fluid")
    if fluid not in FLUIDS:
        raise ValueError(f"fluid must be one of {sorted(FLUIDS)} or a Fluid, got {fluid!r}")
    return FLUIDS[fluid]


def reynolds_number(angular_frequency, width: float, fluid="air"):
    """Re = rho_f omega b^2 / (4 eta) (Sader 1998; b the width, omega in rad/s).

    Parameters
    ----------
    angular_frequency : float or array_like
        omega in rad/s (> 0).
    width : float
        Lever width b in m.
    fluid : str or Fluid
        The fluid (a key of :data:`FLUIDS` or a Fluid).

    Returns
    -------
    float or ndarray
    """
    fluid = get_fluid(fluid)
    omega = check_array("angular_frequency", angular_frequency, "rad/s", low=0.0,
                        low_inclusive=False)
    width = check_range("width", width, 1e-9, 1.0, "m")
    re = fluid.density * omega * width ** 2 / (4.0 * fluid.viscosity)
    return float(re) if re.ndim == 0 else re


#: Reynolds numbers accepted when extrapolating: Gamma stays a finite double over them.
_EXTRAPOLATED = (1e-200, math.inf)
# Above this Re (|z| = 1e6) K1/K0 is its large-argument expansion (error below 1e-12; the Bessel
# routines lose accuracy and then return NaN for |z| beyond ~1e8).
_ASYMPTOTIC = 1e12


def _reynolds(re, extrapolate: bool) -> np.ndarray:
    low, high = _EXTRAPOLATED if check_flag("extrapolate", extrapolate) else REYNOLDS_RANGE
    return check_array("re", re, low=low, high=high)


def _circ(re: np.ndarray) -> np.ndarray:
    shape = np.shape(re)
    re = np.atleast_1d(re).astype(float)
    root = np.sqrt(1j * re)
    z = -1j * root
    big = re > _ASYMPTOTIC
    safe = np.where(big, 1.0, z)
    # the scaled functions kve = kv exp(z): their ratio is kv's, without underflow at large Re
    ratio = scipy.special.kve(1, safe) / scipy.special.kve(0, safe)
    # Abramowitz and Stegun 9.7.2: K_nu(z) ~ sqrt(pi / 2z) e^-z (1 + (4 nu^2 - 1) / 8z + ...)
    zb = z[big]
    ratio[big] = (1 + 3 / (8 * zb) - 15 / (128 * zb ** 2)) / (1 - 1 / (8 * zb)
                                                            + 9 / (128 * zb ** 2))
    return (1.0 + 4j * ratio / root).reshape(shape)


def _omega(re: np.ndarray) -> np.ndarray:
    tau = np.log10(np.clip(re, *REYNOLDS_RANGE))  # held at the ends of the fit's range

    def ratio(num, den):
        return np.polynomial.polynomial.polyval(tau, num) / np.polynomial.polynomial.polyval(
            tau, den)
    return ratio(_OMEGA_R_NUM, _OMEGA_R_DEN) + 1j * ratio(_OMEGA_I_NUM, _OMEGA_I_DEN)


def _out(values: np.ndarray):
    return complex(values) if values.ndim == 0 else values


def circular_hydrodynamic_function(re):
    """Exact hydrodynamic function of a circular cylinder of diameter b (Sader 1998, Eq. (18)).

    Gamma_circ = 1 + 4 i K_1(-i sqrt(i Re)) / (sqrt(i Re) K_0(-i sqrt(i Re))), from Stokes'
    solution for an oscillating cylinder, K_0 and K_1 the modified Bessel functions of the second
    kind (``scipy.special.kve``, scaled, for complex arguments).

    Parameters
    ----------
    re : float or array_like
        Reynolds number rho_f omega b^2 / (4 eta), >= 1e-200 (beyond 1e12 the large-argument
        expansion of K1 / K0, Abramowitz and Stegun 9.7.2).

    Returns
    -------
    complex or ndarray of complex
    """
    return _out(_circ(_reynolds(re, True)))


def rectangular_correction(re, *, extrapolate: bool = False):
    """Sader's correction Omega(Re) = Gamma_rect / Gamma_circ (Sader 1998, Eqs. (21a,b), (22)).

    Parameters
    ----------
    re : float or array_like
        Reynolds number, in :data:`REYNOLDS_RANGE` unless ``extrapolate``.
    extrapolate : bool
        Accept any Re >= 1e-200, holding Omega at its value at the nearer end of the fitted
        range.

    Returns
    -------
    complex or ndarray of complex
    """
    return _out(_omega(_reynolds(re, extrapolate)))


def hydrodynamic_function(re, *, extrapolate: bool = False):
    """Hydrodynamic function of a thin rectangular beam, Gamma_rect = Omega Gamma_circ.

    Sader 1998, Eq. (20), with Eqs. (18), (21a,b) and (22); validated for 1e-6 <= Re <= 1e4
    (:data:`REYNOLDS_RANGE`). The time dependence is exp(-i omega t): the
    imaginary part, the damping, is positive.

    Parameters
    ----------
    re : float or array_like
        Reynolds number rho_f omega b^2 / (4 eta) (:func:`reynolds_number`), in
        :data:`REYNOLDS_RANGE` unless ``extrapolate``.
    extrapolate : bool
        Accept any Re >= 1e-200 (Omega held at the ends of the fitted range; Gamma_circ
        exact).

    Returns
    -------
    complex or ndarray of complex
        Gamma_r + i Gamma_i.

    Raises
    ------
    ValueError
        For a Reynolds number outside the fit's range (naming ``re``) unless ``extrapolate``.

    Examples
    --------
    >>> g = hydrodynamic_function(1.0)
    >>> round(g.real, 3), round(g.imag, 3)
    (3.734, 4.075)
    """
    re = _reynolds(re, extrapolate)
    return _out(_omega(re) * _circ(re))


def mass_loading(lever: Cantilever, fluid="air") -> float:
    """The ratio T = pi rho_f b / (4 rho h) of the fluid's inviscid added mass to the lever's mass.

    Parameters
    ----------
    lever : Cantilever
        The lever (b, h, rho).
    fluid : str or Fluid
        The fluid.

    Returns
    -------
    float
    """
    lever = check_instance("lever", lever, Cantilever)
    fluid = get_fluid(fluid)
    return math.pi * fluid.density * lever.width / (4.0 * lever.density * lever.thickness)


@dataclass(frozen=True)
class FluidMode:
    """One flexural mode of a lever in a fluid (:func:`fluid_mode`), in SI units.

    Attributes
    ----------
    lever : Cantilever
        The lever.
    fluid : Fluid
        The fluid.
    mode : int
        The mode number n.
    vacuum_frequency : float
        f_vac,n in Hz.
    resonance_frequency : float
        f_R,n in Hz, in the fluid.
    quality_factor : float
        Q_n in the fluid (Sader's weak-damping formula; meaningful for Q >> 1).
    spring_constant : float
        The mode's stiffness at the tip, k_n = k / share_n, in N/m.
    reynolds_number : float
        Re at f_R,n.
    hydrodynamic : complex
        Gamma(Re) at f_R,n.
    """

    lever: Cantilever
    fluid: Fluid
    mode: int
    vacuum_frequency: float
    resonance_frequency: float
    quality_factor: float
    spring_constant: float
    reynolds_number: float
    hydrodynamic: complex

    @property
    def angular_frequency(self) -> float:
        """omega_R,n = 2 pi f_R,n in rad/s."""
        return 2.0 * math.pi * self.resonance_frequency

    @property
    def frequency_ratio(self) -> float:
        """f_R,n / f_vac,n (below 1: the fluid's added mass)."""
        return self.resonance_frequency / self.vacuum_frequency

    @property
    def in_fit_range(self) -> bool:
        """Whether Re lies where Sader's Omega fit is accurate (:data:`REYNOLDS_RANGE`)."""
        return REYNOLDS_RANGE[0] <= self.reynolds_number <= REYNOLDS_RANGE[1]

    def oscillator(self) -> dict:
        """(k_n, f_R,n, Q_n) as keyword arguments of a point-mass lever model.

        ``TappingLever(**fluid_mode(lever, "water").oscillator())``, or the same for
        :class:`~afmsmiler.modes.oscillator.Oscillator` and the lock-in demonstrations.

        Returns
        -------
        dict
            ``spring_constant`` (N/m), ``resonance_frequency`` (Hz), ``quality_factor``.
        """
        return {"spring_constant": self.spring_constant,
                "resonance_frequency": self.resonance_frequency,
                "quality_factor": self.quality_factor}


def fluid_mode(lever: Cantilever, fluid="air", mode: int = 1) -> FluidMode:
    """Resonance frequency and quality factor of flexural mode ``mode`` of ``lever`` in ``fluid``.

    Solves omega_R = omega_vac (1 + T Gamma_r(omega_R))^(-1/2) for omega_R (Brent's method on
    ln omega, Gamma_r decreasing with omega so that the root is unique) and evaluates
    Q = (1/T + Gamma_r) / Gamma_i there, T = pi rho_f b / (4 rho h) (Sader 1998; Sader, Chon and
    Mulvaney 1999). Gamma is Sader's rectangular function, held at the ends of
    its fitted Reynolds range beyond them (see :attr:`FluidMode.in_fit_range`).

    Parameters
    ----------
    lever : Cantilever
        The lever (rectangular, in vacuum: k, f_vac,n, b, h, rho).
    fluid : str or Fluid
        The fluid (a key of :data:`FLUIDS` or a Fluid).
    mode : int
        Mode number n, 1 to :data:`~afmsmiler.cantilever.MAX_MODE`.

    Returns
    -------
    FluidMode
    """
    lever = check_instance("lever", lever, Cantilever)
    fluid = get_fluid(fluid)
    mode = check_integer("mode", mode, 1, MAX_MODE)
    t = mass_loading(lever, fluid)
    f_vac = lever.resonance_frequency(mode)
    w_vac = 2.0 * math.pi * f_vac
    scale = fluid.density * lever.width ** 2 / (4.0 * fluid.viscosity)

    def gamma(log_w):
        return complex(_omega(np.array(scale * math.exp(log_w)))
                       * _circ(np.array(scale * math.exp(log_w))))

    def residual(log_w):   # ln(omega^2 (1 + T Gamma_r)) - ln(omega_vac^2): increasing in omega
        return 2.0 * (log_w - math.log(w_vac)) + math.log1p(t * gamma(log_w).real)

    high = math.log(w_vac)
    low = high - 60.0   # omega_vac e^-60: far below any root (residual < 0 there)
    log_w = high if residual(high) <= 0.0 else brentq(residual, low, high, xtol=1e-14,
                                                         rtol=1e-14, maxiter=200)
    w = math.exp(log_w)
    g = gamma(log_w)
    return FluidMode(lever=lever, fluid=fluid, mode=mode, vacuum_frequency=f_vac,
                     resonance_frequency=w / (2.0 * math.pi),
                     quality_factor=(1.0 / t + g.real) / g.imag,
                     spring_constant=lever.spring_constant * eigenvalue(mode) ** 4 / 12.0,
                     reynolds_number=scale * w, hydrodynamic=g)


def fluid_modes(lever: Cantilever, fluid="air", modes: int = 3) -> tuple:
    """:func:`fluid_mode` for modes 1 to ``modes``.

    Parameters
    ----------
    lever : Cantilever
        The lever.
    fluid : str or Fluid
        The fluid.
    modes : int
        How many modes, 1 to :data:`~afmsmiler.cantilever.MAX_MODE`.

    Returns
    -------
    tuple of FluidMode
    """
    modes = check_integer("modes", modes, 1, MAX_MODE)
    return tuple(fluid_mode(lever, fluid, n) for n in range(1, modes + 1))
