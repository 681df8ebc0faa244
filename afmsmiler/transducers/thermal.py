"""Thermal actuation: the photothermal (bulk) and electrothermal (embedded) bimorph.

Heat deposited in a lever made of two layers with different thermal expansion bends it
(a bimorph). Both models share three first-principles steps:

1. Conduction to the clamp (1-D fin, no convection or radiation, the clamp at ambient): with
   the layers' thermal conductance per unit width G/w = sum(kappa_i t_i),

   * heat P at the free end (a laser spot):     Delta T(x) = P x / G
   * heat P spread along the lever (a heater):  Delta T(x) = P (L x - x^2 / 2) / (L G)

2. Bimorph curvature per kelvin (Timoshenko, J. Opt. Soc. Am. 11, 233 (1925))::

       C = 6 (alpha_2 - alpha_1) (1 + m)^2 / (h (3 (1 + m)^2 + (1 + m n) (m^2 + 1 / (m n))))

   with m = t_1 / t_2, n = E_1 / E_2, h = t_1 + t_2, layer 1 the silicon lever and layer 2 the
   top film. A top film that expands more bends the lever down, towards the sample:
   z''(x) = -C Delta T(x).

3. Deflection of the free end from the curvature (clamped at x = 0)::

       z(L) = int_0^L (L - x) z''(x) dx,     theta(L) = int_0^L z''(x) dx

   i.e. z = -C P L^3 / (6 G) (tip heating) and z = -C P L^3 / (8 G) (uniform heating).

4. Dynamics: heat needs time to spread. With D = sum(kappa_i t_i) / sum(rho_i c_i t_i) the
   thermal diffusivity, a heat input P e^{j omega t} obeys D T'' - j omega T = -(source), with
   T(0) = 0 and no flux out of the free end; with u = q L, q = sqrt(j omega / D), the fin's
   exact solution gives the tip deflection per its DC value::

       H_tip(u)     = 6 (tanh u - u sech u) / u^3                      (heat at the free end)
       H_uniform(u) = (8 / u^2) (1/2 - tanh(u) / u + (1 - sech u) / u^2)  (heat spread along it)

   (Carslaw and Jaeger, *Conduction of Heat in Solids*, 1959, sec. 3.3). Its slowest mode has
   the time constant tau = 4 L^2 / (pi^2 D), and below about 1 / (2 pi tau) both responses are
   close to the first-order low-pass 1 / (1 + j 2 pi f tau) (at 1 / (2 pi tau): within 1 % in
   magnitude and 6 degrees in phase);
   far above it they part ways. Heat at the free end stays there, where bending moves the tip
   little: H_tip ~ 6 / u^3 falls as f^(-3/2), 6.5 times below the first-order lag at
   100 / (2 pi tau), about where the default levers resonate. Heat along the lever bends it near
   the clamp too: H_uniform ~ 4 / u^2 falls as 1 / f but 1.5 times above the lag there
   (Ramos et al., J. Appl. Phys. 99, 124904 (2006) for photothermal AFM excitation).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..materials import get_material
from ..parameters import read_only
from ..validation import check_array, check_finite, check_nonnegative, check_positive
from ..brownian import mechanical_response
from .base import DEFLECTION, SLOPE, Harmonics, Parameter, Transducer, quantity

__all__ = ["ThermalProperties", "THERMAL", "bimorph_curvature", "Photothermal", "Electrothermal"]


@dataclass(frozen=True)
class ThermalProperties:
    """Thermal figures of a material (SI).

    Parameters
    ----------
    expansion : float
        Linear thermal expansion coefficient alpha in 1/K.
    conductivity : float
        Thermal conductivity kappa in W/(m K).
    specific_heat : float
        Specific heat capacity c in J/(kg K).
    source : str
        Where the figures come from.
    """

    expansion: float
    conductivity: float
    specific_heat: float
    source: str = ""


#: Thermal figures of the presets of :mod:`afmsmiler.materials` used in the bimorphs.
THERMAL = read_only({
    "silicon": ThermalProperties(2.6e-6, 148.0, 705.0,
                                 "Okada and Tokumaru, J. Appl. Phys. 56, 314 (1984); CRC Handbook"),
    "gold": ThermalProperties(14.2e-6, 318.0, 129.0, "CRC Handbook of Chemistry and Physics"),
    "aluminium": ThermalProperties(23.1e-6, 237.0, 897.0, "CRC Handbook of Chemistry and Physics"),
})


def bimorph_curvature(expansion_1: float, thickness_1: float, modulus_1: float,
                      expansion_2: float, thickness_2: float, modulus_2: float) -> float:
    """Timoshenko's bimorph curvature per kelvin, in 1/(m K), positive towards layer 1.

    Parameters
    ----------
    expansion_1, expansion_2 : float
        Thermal expansion coefficients in 1/K of the bottom (1) and top (2) layer.
    thickness_1, thickness_2 : float
        Layer thicknesses in m, > 0.
    modulus_1, modulus_2 : float
        Young's moduli in Pa, > 0.

    Returns
    -------
    float
        6 (alpha_2 - alpha_1) (1 + m)^2 / (h (3 (1 + m)^2 + (1 + m n)(m^2 + 1/(m n)))): the
        curvature that bends the bilayer towards layer 1 (down, if layer 2 is on top) per kelvin.

    Raises
    ------
    ValueError
        If an expansion coefficient is not finite, or a thickness or modulus not finite and > 0.
    """
    expansion_1 = check_finite("expansion_1", expansion_1, "1/K")
    expansion_2 = check_finite("expansion_2", expansion_2, "1/K")
    thickness_1 = check_positive("thickness_1", thickness_1, "m")
    thickness_2 = check_positive("thickness_2", thickness_2, "m")
    modulus_1 = check_positive("modulus_1", modulus_1, "Pa")
    modulus_2 = check_positive("modulus_2", modulus_2, "Pa")
    m = thickness_1 / thickness_2
    n = modulus_1 / modulus_2
    h = thickness_1 + thickness_2
    return (6 * (expansion_2 - expansion_1) * (1 + m) ** 2
            / (h * (3 * (1 + m) ** 2 + (1 + m * n) * (m * m + 1 / (m * n)))))


#: Taylor coefficients of H_tip and H_uniform in s = u^2 (sympy), used for |s| < _SERIES_RADIUS
#: where the closed forms lose digits to cancellation; they converge for |s| < pi^2 / 4.
_SERIES = {
    "tip": (1.0, -9 / 20, 31 / 168, -647 / 8640, 67313 / 2217600, -1160699 / 94348800,
            83589031 / 16765056000, -39930121163 / 19760412672000),
    "uniform": (1.0, -7 / 18, 113 / 720, -9613 / 151200, 140249 / 5443200,
                -8753431 / 838252800, 1229844983 / 290594304000,
                -80746852831 / 47076277248000),
}
_SERIES_RADIUS = 0.02


def _fin_response(s, heating: str):
    """H(u) of the module docstring for s = u^2 = j omega L^2 / D (array); heating tip/uniform."""
    s = np.asarray(s, dtype=complex)
    out = np.zeros_like(s)                        # H -> 0 as |s| -> inf (an overflowed s)
    small = np.abs(s) < _SERIES_RADIUS
    large = ~small & np.isfinite(s)
    out[small] = np.polynomial.polynomial.polyval(s[small], _SERIES[heating])
    u = np.sqrt(s[large])                        # Re u > 0
    v = 1 / u                                     # in powers of 1 / u: no u^3 to overflow
    e2 = np.exp(-2 * u)                           # overflow-free tanh and sech
    tanh, sech = (1 - e2) / (1 + e2), 2 * np.exp(-u) / (1 + e2)
    if heating == "tip":
        out[large] = 6 * (tanh - u * sech) * v ** 3
    else:
        out[large] = 8 * v ** 2 * (0.5 - tanh * v + (1 - sech) * v ** 2)
    return out


class _Bimorph(Transducer):
    """Shared thermal and bimorph steps (see the module docstring)."""

    FILM = "gold"
    FILM_THICKNESS = "coating_thickness"
    #: "tip" (laser spot) or "uniform" (heater along the lever)
    HEATING = "tip"
    TEMPERATURE = quantity(name="tip_temperature", unit="K", label="tip temperature rise")

    @property
    def _layers(self):
        si, film = THERMAL["silicon"], THERMAL[self.FILM]
        t1, t2 = self.thickness, getattr(self, self.FILM_THICKNESS)
        return si, film, t1, t2

    @property
    def thermal_conductance(self) -> float:
        """G = w sum(kappa_i t_i) in W m / K (heat flow along the lever per kelvin per metre)."""
        si, film, t1, t2 = self._layers
        return self.width * (si.conductivity * t1 + film.conductivity * t2)

    @property
    def thermal_time_constant(self) -> float:
        """tau = 4 L^2 / (pi^2 D) in s, the slowest thermal mode of the clamped lever."""
        return 4 * self.length ** 2 / (math.pi ** 2 * self.thermal_diffusivity)

    @property
    def thermal_diffusivity(self) -> float:
        """D = sum(kappa_i t_i) / sum(rho_i c_i t_i) of the two layers, in m^2/s."""
        si, film, t1, t2 = self._layers
        rho_c = (get_material("silicon").density * si.specific_heat * t1
                 + get_material(self.FILM).density * film.specific_heat * t2)
        return (si.conductivity * t1 + film.conductivity * t2) / rho_c

    @property
    def curvature_per_kelvin(self) -> float:
        """Timoshenko's C in 1/(m K) for the silicon lever and its top film."""
        si, film, t1, t2 = self._layers
        return bimorph_curvature(si.expansion, t1, get_material("silicon").youngs_modulus,
                                 film.expansion, t2, get_material(self.FILM).youngs_modulus)

    def temperature_profile(self, x, power):
        """Temperature rise Delta T(x) in K along the lever for a heat input ``power`` (W).

        Parameters
        ----------
        x : float or array_like
            Position along the lever in m, in [0, L] (the clamp at 0, held at ambient).
        power : float or array_like
            Heat deposited in the lever in W, >= 0 (broadcasts against ``x``).
        """
        x = check_array("x", x, "m", low=0.0, high=self.length)
        p_over_g = check_array("power", power, "W", low=0.0) / self.thermal_conductance
        if self.HEATING == "tip":
            return p_over_g * x
        return p_over_g * (self.length * x - x * x / 2) / self.length

    @property
    def _shape(self):
        """(tip temperature, tip deflection, tip slope) per watt of heat, DC."""
        L, g, c = self.length, self.thermal_conductance, self.curvature_per_kelvin
        if self.HEATING == "tip":
            return L / g, -c * L ** 3 / (6 * g), -c * L ** 2 / (2 * g)
        return L / (2 * g), -c * L ** 3 / (8 * g), -c * L ** 2 / (3 * g)

    def deflection_per_watt(self) -> float:
        """Static tip deflection per watt of heat, in m/W (negative: towards the sample)."""
        return self._shape[1]

    def thermal_lag(self, f):
        """Tip deflection per its DC value for a heat input at frequency ``f``: the fin's H(u).

        H_tip or H_uniform (see the module docstring), u = L sqrt(j 2 pi f / D); close to
        1 / (1 + j 2 pi f tau) below 1 / (2 pi tau), steeper above.

        Parameters
        ----------
        f : float or array_like
            Frequencies in Hz, >= 0.

        Returns
        -------
        complex or ndarray of complex
            Same shape as ``f``; 1 at DC, tending to 0 as ``f`` -> inf (finite for every
            finite ``f``).
        """
        f = check_array("f", f, "Hz", low=0.0)
        # L^2 / D first: 2 pi f alone overflows for the largest floats
        with np.errstate(over="ignore"):
            s = f * (self.length ** 2 / self.thermal_diffusivity) * (2j * math.pi)
        return _fin_response(s, self.HEATING)

    def _heat_stages(self, heat):
        t, z, th = self._shape
        return [(self.TEMPERATURE, t * heat), (SLOPE, th * heat), (DEFLECTION, z * heat)]

    def _dynamics(self, f, mode):
        return self.thermal_lag(f)

    #: Largest temperature rise (K) for which constant material properties are a fair model.
    MAX_TEMPERATURE_RISE = 300.0

    def _validity(self, value, mode, point):
        rise = float(point.stage("tip_temperature").values[0])
        if rise > self.MAX_TEMPERATURE_RISE:
            yield (f"the tip is {rise:.0f} K above ambient: the linear, constant-property model "
                   f"no longer holds")


class Photothermal(_Bimorph):
    """Photothermal actuation: a laser spot at the free end heats the gold-coated lever.

    Absorbed power P_abs = A P (absorptance A of the coated back) flows to the clamp, the
    temperature rises linearly along the lever, Delta T(x) = P_abs x / G, and the silicon/gold
    bimorph bends the lever down: z = -C P_abs L^3 / (6 G), through the thermal low-pass of time
    constant tau (see :mod:`afmsmiler.transducers.thermal`). Works at DC and AC (bulk: the
    laser comes from outside); used for clean, resonance-free drive in liquid.

    Its lever works in vacuum with the typed Q, or in a fluid (``fluid``: see
    :class:`~afmsmiler.transducers.base.Transducer`).
    """

    key = "photothermal"
    name = "photothermal"
    function, signal, size = "actuation", "DC&AC", "bulk"
    summary = "a laser heats the coated lever: bimorph bending"
    PARAMETERS = (
        Parameter(name="absorptance", unit="", default=0.1, low=1e-3, high=1.0,
                  label="absorptance of the coating"),
        Parameter(name="coating_thickness", unit="m", display_unit="nm", default=50e-9, low=5e-9,
                  high=500e-9, label="gold coating thickness"),
    )
    MODES = ("actuation",)
    INPUTS = {"actuation": Parameter(name="laser_power", unit="W", display_unit="mW",
                                     default=1e-3, low=0.0, high=20e-3,
                                     label="incident laser power")}
    OUTPUTS = {"actuation": DEFLECTION}
    SENSITIVITY = {"actuation": quantity(name="deflection_per_power", unit="m/W",
                                         display_unit="nm/mW",
                                         label="sensitivity")}
    ABSORBED = quantity(name="absorbed_power", unit="W", display_unit="mW",
                        label="absorbed power")

    def _stages(self, p, mode):
        heat = self.absorptance * p
        return [(self.ABSORBED, heat)] + self._heat_stages(heat)

    def _sensitivity(self, mode, at):
        return self.absorptance * self.deflection_per_watt()


class Electrothermal(_Bimorph):
    """Electrothermal actuation: a resistive heater on the lever and an aluminium bimorph layer.

    A voltage V = V_dc + V_ac cos(omega t) across the heater R dissipates P = V^2 / R::

        P = (V_dc^2 + V_ac^2 / 2) / R                  (DC)
          + (2 V_dc V_ac / R) cos(omega t)             (1 omega)
          + (V_ac^2 / (2 R)) cos(2 omega t)            (2 omega)

    so an unbiased drive (V_dc = 0) moves the lever at 2 omega only, and the 1-omega gain is
    proportional to the bias. The heat, spread along the lever, gives Delta T(x) =
    P (L x - x^2/2) / (L G) and, through the silicon/aluminium bimorph, z = -C P L^3 / (8 G),
    low-passed by the thermal time constant tau (Pedrak et al., J. Vac. Sci. Technol. B 21, 3102
    (2003)). The model is linear (properties do not change with temperature, nothing melts):
    :meth:`validity` flags temperature rises beyond ``MAX_TEMPERATURE_RISE``. The chain's input
    is the DC heater voltage; the AC amplitude is a parameter whose rectified part
    V_ac^2 / (2 R) adds to the DC heat.

    Its lever works in vacuum with the typed Q, or in a fluid (``fluid``: see
    :class:`~afmsmiler.transducers.base.Transducer`).
    """

    key = "electrothermal"
    name = "electrothermal"
    function, signal, size = "actuation", "DC&AC", "embedded"
    summary = "an integrated heater warms an aluminium/silicon bimorph"
    FILM = "aluminium"
    FILM_THICKNESS = "film_thickness"
    HEATING = "uniform"
    BIASED = True
    PARAMETERS = (
        Parameter(name="resistance", unit="ohm", display_unit="kohm", default=1e3, low=10.0,
                  high=1e6, log=True, label="heater resistance R"),
        Parameter(name="ac_voltage", unit="V", default=0.5, low=0.0, high=5.0,
                  label="AC amplitude V_ac"),
        Parameter(name="film_thickness", unit="m", display_unit="nm", default=200e-9, low=10e-9,
                  high=2e-6, label="aluminium film thickness"),
    )
    MODES = ("actuation",)
    INPUTS = {"actuation": Parameter(name="dc_voltage", unit="V", default=2.0, low=-5.0, high=5.0,
                                     label="DC heater voltage V_dc")}
    OUTPUTS = {"actuation": DEFLECTION}
    SENSITIVITY = {"actuation": quantity(name="deflection_per_voltage", unit="m/V",
                                         display_unit="nm/V",
                                         label="sensitivity")}
    POWER = quantity(name="power", unit="W", display_unit="mW", label="mean heater power")

    def power_components(self, dc_voltage: float) -> Harmonics:
        """DC, 1-omega and 2-omega heater power in W for a bias ``dc_voltage`` (V)."""
        v = self.INPUTS["actuation"].check(dc_voltage)
        r, va = self.resistance, self.ac_voltage
        return Harmonics((v * v + va * va / 2) / r, 2 * v * va / r, va * va / (2 * r))

    def deflection_components(self, dc_voltage: float, frequency: float) -> Harmonics:
        """Complex tip-deflection amplitudes (m) at DC, omega and 2 omega.

        Parameters
        ----------
        dc_voltage : float
            Bias V_dc in V.
        frequency : float
            Drive frequency omega / (2 pi) in Hz; each power component passes the thermal lag
            and the first mode at its own frequency.
        """
        frequency = check_nonnegative("frequency", frequency, "Hz")
        p = self.power_components(dc_voltage)
        k = self.deflection_per_watt()

        def h(f):
            return complex(k * self.thermal_lag(f)
                           * mechanical_response(f, resonance_frequency=self.resonance_frequency,
                                               quality_factor=self.quality_factor))
        return Harmonics(p.dc * h(0.0), p.first * h(frequency), p.second * h(2 * frequency))

    def _stages(self, v, mode):
        heat = (v * v + self.ac_voltage ** 2 / 2) / self.resistance
        return [(self.POWER, heat)] + self._heat_stages(heat)

    def _sensitivity(self, mode, at):
        return self.deflection_per_watt() * 2 * at / self.resistance
