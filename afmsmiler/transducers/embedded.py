"""Embedded transducers: piezoresistive bridge, piezoelectric film and optomechanical cavity.

All three are built into the lever (or next to it on the chip) and need no external laser
alignment; their signals come from the lever's bending stress (piezoresistive, piezoelectric) or
from its displacement shifting an optical resonance (optomechanical).
"""
from __future__ import annotations

import math

import numpy as np

from ..validation import check_array, check_finite
from .base import (BOLTZMANN, DEFLECTION, ELEMENTARY_CHARGE, EPSILON_0, SLOPE,
                   TIP_DEFLECTION_INPUT, Parameter, Transducer, quantity)

__all__ = ["Piezoresistive", "Piezoelectric", "Optomechanical", "quarter_bridge_output",
           "SPEED_OF_LIGHT"]

#: Speed of light in vacuum in m/s (exact).
SPEED_OF_LIGHT = 299792458.0


def quarter_bridge_output(bias_voltage, relative_change):
    """Output in V of a quarter Wheatstone bridge: one arm R (1 + delta), three arms R.

    V_out = V_b [R (1 + delta) / (R (1 + delta) + R) - 1/2] = (V_b / 4) delta / (1 + delta / 2),
    which is V_b delta / 4 for small delta.

    Parameters
    ----------
    bias_voltage : float
        Bridge bias V_b in V.
    relative_change : float or array_like
        delta = dR / R of the active arm, >= -1 (a resistance cannot be negative).

    Raises
    ------
    ValueError
        If ``bias_voltage`` is not finite or a ``relative_change`` not finite and >= -1.
    """
    bias_voltage = check_finite("bias_voltage", bias_voltage, "V")
    d = check_array("relative_change", relative_change, low=-1.0)
    out = np.multiply(d, 0.5, out=np.empty_like(d))  # (V_b / 4) d / (1 + d / 2), in place
    out += 1.0
    np.divide(d, out, out=out)
    out *= bias_voltage / 4
    return out if out.ndim else out[()]


class Piezoresistive(Transducer):
    """A piezoresistor at the clamp, read in a quarter Wheatstone bridge.

    A tip deflection z needs the end force F = k z (module (a)), which stresses the top surface
    by sigma(x) = -E z_b z''(x) (:meth:`afmsmiler.cantilever.Cantilever.stress`). A U-shaped
    p-type resistor of leg length l_r and junction depth d_j at the clamp averages the stress at
    x = l_r / 2 and z_b = h/2 - d_j/2 (the stress is linear in both). Its resistance changes by
    dR / R = pi_l sigma (longitudinal piezoresistive coefficient; p-Si along <110>,
    pi_l = (pi_11 + pi_12 + pi_44) / 2 = 71.8e-11 1/Pa, Smith, Phys. Rev. 94, 42 (1954)), or
    GF * strain with the gauge factor GF = pi_l E. The quarter bridge gives
    V_out = (V_b / 4) delta / (1 + delta / 2) (:func:`quarter_bridge_output`), small-signal
    V_b delta / 4. The sign: a lever bent up (z > 0) compresses its top, so a p-type resistor
    (pi_l > 0) loses resistance and the output is negative. The linear model is flagged by
    :meth:`validity` beyond |dR/R| = ``MAX_RELATIVE_CHANGE`` or a clamp stress of
    ``FRACTURE_STRESS``; dR/R is clipped at -1, where the bridge output reaches its rail -V_b / 2.

    Noise (Harley and Kenny, J. Microelectromech. Syst. 9, 226 (2000); all four arms matched
    resistors of N = p V carriers each, V = 2 l_r (w/4) d_j): Johnson noise of the bridge's
    output resistance R, sqrt(4 k_B T R B), and Hooge 1/f noise, V_b^2 alpha_H / (4 N) *
    ln(f_2 / f_1) over the band [f_1, f_2].

    Its lever works in vacuum with the typed Q, or in a fluid (``fluid``: see
    :class:`~afmsmiler.transducers.base.Transducer`).
    """

    key = "piezoresistive"
    name = "piezoresistive"
    function, signal, size = "sensing", "DC&AC", "embedded"
    summary = "a piezoresistor at the clamp in a Wheatstone bridge"
    BOUNDED_BY = {"resistor_length": ("length", 1.0), "junction_depth": ("thickness", 0.5)}
    PARAMETERS = (
        Parameter(name="bias_voltage", unit="V", default=2.0, low=0.01, high=10.0,
                  label="bridge bias V_b"),
        Parameter(name="resistance", unit="ohm", display_unit="kohm", default=5e3, low=100.0,
                  high=1e6, log=True, label="resistance R"),
        Parameter(name="piezo_coefficient", unit="1/Pa", display_unit="1e-11/Pa",
                  default=71.8e-11, low=-150e-11, high=150e-11, label="coefficient pi_l"),
        Parameter(name="resistor_length", unit="m", display_unit="um", default=50e-6, low=1e-6,
                  high=1e-3, label="resistor leg length l_r"),
        Parameter(name="junction_depth", unit="m", display_unit="um", default=0.3e-6, low=0.01e-6,
                  high=5e-6, label="junction depth d_j"),
        Parameter(name="hooge", unit="", default=1e-5, low=1e-8, high=1e-2, log=True,
                  label="Hooge parameter alpha_H"),
        Parameter(name="carrier_density", unit="1/m^3", display_unit="1/cm^3", default=1e25,
                  low=1e22, high=1e27, log=True, label="carrier density p"),
    )
    INPUTS = {"sensing": TIP_DEFLECTION_INPUT}
    OUTPUTS = {"sensing": quantity(name="bridge_voltage", unit="V", display_unit="uV",
                                   label="bridge output")}
    SENSITIVITY = {"sensing": quantity(name="voltage_per_deflection", unit="V/m",
                                       display_unit="uV/nm",
                                       label="sensitivity")}
    STRESS = quantity(name="stress", unit="Pa", display_unit="MPa",
                      label="stress in the resistor")
    CHANGE = quantity(name="relative_change", unit="", display_unit="ppm", label="dR/R")

    @property
    def gauge_factor(self) -> float:
        """GF = pi_l E (dimensionless): dR/R per unit strain."""
        return self.piezo_coefficient * self.lever.youngs_modulus

    @property
    def stress_per_newton(self) -> float:
        """Mean stress in the resistor per newton of tip force in Pa/N (from the lever's stress)."""
        z_b = self.thickness / 2 - self.junction_depth / 2
        return float(self.lever.stress(self.resistor_length / 2, z_b, 1.0))

    @property
    def carrier_number(self) -> float:
        """N = p V carriers in one resistor (two legs of width w/4)."""
        volume = 2 * self.resistor_length * self.width / 4 * self.junction_depth
        return self.carrier_density * volume

    #: Largest |dR/R| for which a constant piezoresistive coefficient is a fair model.
    MAX_RELATIVE_CHANGE = 0.1
    #: Surface stress (Pa) at the clamp beyond which an etched silicon lever is likely to break
    #: (fracture strengths of etched silicon microstructures are 1-3 GPa; Petersen, Proc. IEEE
    #: 70, 420 (1982) gives 7 GPa for flawless crystal).
    FRACTURE_STRESS = 1e9

    def _delta(self, z):
        """dR/R of the resistor for tip deflections ``z``, clipped at -1 (a resistance >= 0)."""
        stress = self.stress_per_newton * self.spring_constant * z
        return stress, np.maximum(self.piezo_coefficient * stress, -1.0)

    def _stages(self, z, mode):
        stress, delta = self._delta(z)
        return self._lever_stages(z) + [(self.STRESS, stress), (self.CHANGE, delta),
                                        (self.OUTPUTS["sensing"],
                                         quarter_bridge_output(self.bias_voltage, delta))]

    def _sensitivity(self, mode, at):
        d_delta_dz = self.piezo_coefficient * self.stress_per_newton * self.spring_constant
        delta = d_delta_dz * at
        if delta <= -1.0:      # the clipped branch: the arm is a short, the output at -V_b / 2
            return 0.0
        return self.bias_voltage / 4 * d_delta_dz / (1 + delta / 2) ** 2

    def _validity(self, value, mode, point):
        clamp = abs(float(self.lever.stress(0.0, self.thickness / 2,
                                            self.spring_constant * value)))
        delta = self.piezo_coefficient * float(self._delta(value)[0])
        if clamp > self.FRACTURE_STRESS:
            yield (f"the clamp's surface stress is {clamp / 1e9:.3g} GPa: an etched silicon lever "
                   f"breaks at 1-3 GPa")
        if abs(delta) > self.MAX_RELATIVE_CHANGE:
            yield (f"dR/R = {delta:.3g}: far beyond the small stresses where the piezoresistive "
                   f"coefficient is constant" + (" (clipped at -1: a resistance cannot be negative)"
                                                  if delta < -1 else ""))

    def _detector_noise(self, bandwidth, low_frequency, mode):
        johnson = math.sqrt(4 * BOLTZMANN * self.temperature * self.resistance * bandwidth)
        hooge = math.sqrt(self.bias_voltage ** 2 * self.hooge / (4 * self.carrier_number)
                          * math.log((low_frequency + bandwidth) / low_frequency))
        return {"johnson": johnson, "hooge": hooge}


class Piezoelectric(Transducer):
    """A thin piezoelectric film (AlN, ZnO, PZT) on the lever: it senses and it actuates.

    The film of thickness t_p, modulus E_p and coefficient d31 covers the lever from the clamp
    to ``electrode_length`` l_e; its mid-plane lies z_p = (h + t_p) / 2 above the neutral axis
    (a thin film: its own stiffness is neglected).

    Sensing (direct effect): bending strains the film by eps(x) = -z_p z''(x), and the
    short-circuit charge on the electrodes is (D_3 = d31 sigma_1)::

        Q = d31 E_p w int_0^{l_e} eps(x) dx = -d31 E_p w z_p l_e z''(l_e / 2)

    with z''(x) = F (L - x) / (E J) from module (a) for the tip force F = k z. The charge leaks
    through the film and amplifier resistance (time constant tau_leak = R C), a high-pass
    j omega tau / (1 + j omega tau): the signal is "AC mostly". Noise: the Johnson current
    of that resistance, integrated by the charge amplifier, (4 k_B T / R) (1/f_1 - 1/f_2) /
    (4 pi^2) in C^2 over [f_1, f_2].

    Actuation (converse effect): a voltage V across the film (field V / t_p) makes it want to
    strain by d31 V / t_p; held by the lever, it pulls with the force d31 E_p w V about the
    neutral axis, i.e. the bending moment M = -d31 E_p w z_p V on [0, l_e], and the curvature
    z'' = M / (E J) there gives the tip::

        z(L) = (M / E J) l_e (L - l_e / 2),      theta(L) = (M / E J) l_e

    Maxwell's reciprocity holds: the charge per tip force equals the tip deflection per volt
    (DeVoe and Pisano, J. Microelectromech. Syst. 6, 266 (1997); Smits and Choi, IEEE Trans.
    Ultrason. Ferroelectr. Freq. Control 38, 256 (1991); AlN: d31 = -2.0 pm/V, E = 330 GPa,
    eps_r = 10.5, Tsubouchi and Mikoshiba, IEEE Trans. Sonics Ultrason. 32, 634 (1985)).

    Its lever works in vacuum with the typed Q, or in a fluid (``fluid``: see
    :class:`~afmsmiler.transducers.base.Transducer`).
    """

    key = "piezoelectric"
    name = "piezoelectric"
    function, signal, size = "both", "AC mostly", "embedded"
    summary = "a piezoelectric film: charge from strain, bending from voltage"
    BOUNDED_BY = {"electrode_length": ("length", 1.0)}
    PARAMETERS = (
        Parameter(name="d31", unit="m/V", display_unit="pm/V", default=-2.0e-12, low=-300e-12,
                  high=300e-12, label="coefficient d31"),
        Parameter(name="film_modulus", unit="Pa", display_unit="GPa", default=330e9, low=10e9,
                  high=500e9, label="film modulus E_p"),
        Parameter(name="film_thickness", unit="m", display_unit="um", default=0.5e-6, low=0.01e-6,
                  high=5e-6, label="film thickness t_p"),
        Parameter(name="permittivity", unit="", default=10.5, low=1.0, high=5000.0, log=True,
                  label="relative permittivity eps_r"),
        Parameter(name="electrode_length", unit="m", display_unit="um", default=100e-6, low=1e-6,
                  high=1e-3, label="electrode length l_e"),
        Parameter(name="leakage_time_constant", unit="s", default=1.0, low=1e-6, high=1e4,
                  log=True, label="leakage time constant R C"),
    )
    MODES = ("sensing", "actuation")
    INPUTS = {"sensing": TIP_DEFLECTION_INPUT,
              "actuation": Parameter(name="voltage", unit="V", default=5.0, low=-50.0, high=50.0,
                                     label="film voltage V")}
    OUTPUTS = {"sensing": quantity(name="charge", unit="C", display_unit="fC",
                                   label="charge on the electrodes"),
               "actuation": DEFLECTION}
    SENSITIVITY = {"sensing": quantity(name="charge_per_deflection", unit="C/m",
                                       display_unit="fC/nm",
                                       label="sensitivity"),
                   "actuation": quantity(name="deflection_per_voltage", unit="m/V",
                                         display_unit="nm/V",
                                         label="sensitivity")}
    STRAIN = quantity(name="film_strain", unit="", display_unit="ppm",
                      label="mean strain in the film")
    MOMENT = quantity(name="moment", unit="N m", display_unit="nN m", label="bending moment")

    @property
    def film_offset(self) -> float:
        """z_p = (h + t_p) / 2: film mid-plane above the neutral axis, in m."""
        return (self.thickness + self.film_thickness) / 2

    @property
    def capacitance(self) -> float:
        """Film capacitance eps_0 eps_r w l_e / t_p in F."""
        area = self.width * self.electrode_length
        return EPSILON_0 * self.permittivity * area / self.film_thickness

    @property
    def mean_strain_per_newton(self) -> float:
        """Mean film strain per newton of tip force (1/N): -z_p z''(l_e / 2)."""
        return -self.film_offset * float(self.lever.curvature(self.electrode_length / 2, 1.0))

    @property
    def charge_per_newton(self) -> float:
        """Short-circuit charge per newton of tip force in C/N."""
        return (self.d31 * self.film_modulus * self.width * self.electrode_length
                * self.mean_strain_per_newton)

    @property
    def moment_per_volt(self) -> float:
        """Bending moment per volt, -d31 E_p w z_p, in N m / V."""
        return -self.d31 * self.film_modulus * self.width * self.film_offset

    @property
    def deflection_per_volt(self) -> float:
        """Free tip deflection per volt in m/V."""
        le = self.electrode_length
        return self.moment_per_volt / self.lever.flexural_rigidity * le * (self.length - le / 2)

    def _stages(self, x, mode):
        if mode == "sensing":
            force = self.spring_constant * x
            return self._lever_stages(x) + [
                (self.STRAIN, self.mean_strain_per_newton * force),
                (self.OUTPUTS["sensing"], self.charge_per_newton * force)]
        moment = self.moment_per_volt * x
        curvature = moment / self.lever.flexural_rigidity
        return [(self.MOMENT, moment), (SLOPE, curvature * self.electrode_length),
                (DEFLECTION, self.deflection_per_volt * x)]

    def _sensitivity(self, mode, at):
        if mode == "sensing":
            return self.charge_per_newton * self.spring_constant
        return self.deflection_per_volt

    def _dynamics(self, f, mode):
        if mode == "actuation":
            return np.ones_like(f, dtype=complex)
        jwt = 2j * math.pi * f * self.leakage_time_constant
        return jwt / (1 + jwt)

    def _detector_noise(self, bandwidth, low_frequency, mode):
        if mode == "actuation":
            return {}
        r_leak = self.leakage_time_constant / self.capacitance
        q2 = (4 * BOLTZMANN * self.temperature / r_leak / (4 * math.pi ** 2)
              * (1 / low_frequency - 1 / (low_frequency + bandwidth)))
        return {"leakage": math.sqrt(q2)}


class Optomechanical(Transducer):
    """Cavity optomechanical readout: the lever's motion detunes an on-chip optical resonator.

    An optical cavity (a microdisk or photonic-crystal cavity beside the lever) of frequency
    nu_c = c / lambda and loaded quality factor Q_o has the linewidth gamma = nu_c / Q_o
    (kappa = 2 pi gamma, finesse F = free spectral range / gamma). The lever at displacement x
    shifts the resonance by G x (G = d nu_c / dx, the optomechanical coupling / 2 pi), so a
    laser at detuning Delta_0 sees Delta = Delta_0 - G x and the transmitted power through the
    Lorentzian dip of depth D is::

        P_T = P_in (1 - D (gamma/2)^2 / (Delta^2 + (gamma/2)^2))

    At the half-linewidth point Delta_0 = -gamma / 2 (the default) the slope is
    dP_T / dx = D P_in G / gamma (its sign flips on the other flank, Delta_0 = +gamma / 2; the
    steepest slope, 3 sqrt(3) / 4 = 1.30 times that, is at |Delta_0| = gamma / (2 sqrt 3))
    (Aspelmeyer, Kippenberg and Marquardt, Rev. Mod. Phys. 86, 1391 (2014); Srinivasan et al.,
    Nano Lett. 11, 791 (2011)). The intracavity field follows x with the amplitude decay rate
    kappa / 2, a low-pass at gamma / 2. Noise: shot noise of the transmitted photocurrent.

    Its lever works in vacuum with the typed Q, or in a fluid (``fluid``: see
    :class:`~afmsmiler.transducers.base.Transducer`).
    """

    key = "optomechanical"
    name = "optomechanical"
    function, signal, size = "sensing", "DC&AC", "embedded"
    summary = "an on-chip optical cavity detuned by the lever's motion"
    PARAMETERS = (
        Parameter(name="wavelength", unit="m", display_unit="nm", default=1550e-9, low=400e-9,
                  high=2e-6, label="cavity wavelength"),
        Parameter(name="optical_q", unit="", default=1e5, low=1e2, high=1e8, log=True,
                  label="optical quality factor Q_o"),
        Parameter(name="coupling", unit="Hz/m", display_unit="GHz/nm", default=1e18, low=1e15,
                  high=1e20, log=True, label="coupling G / 2 pi"),
        Parameter(name="power", unit="W", display_unit="uW", default=100e-6, low=1e-6, high=5e-3,
                  log=True, label="input power P_in"),
        Parameter(name="dip_depth", unit="", default=0.8, low=0.01, high=1.0,
                  label="dip depth D"),
        Parameter(name="detuning", unit="", default=-0.5, low=-3.0, high=3.0,
                  label="laser detuning Delta_0 / gamma"),
        Parameter(name="responsivity", unit="A/W", default=0.9, low=0.05, high=1.0,
                  label="photodiode responsivity"),
    )
    INPUTS = {"sensing": Parameter(name="deflection", unit="m", display_unit="nm", default=0.2e-9,
                                   low=-50e-9, high=50e-9, label="tip deflection")}
    OUTPUTS = {"sensing": quantity(name="transmitted_power", unit="W", display_unit="uW",
                                   label="transmitted power")}
    SENSITIVITY = {"sensing": quantity(name="power_per_deflection", unit="W/m",
                                       display_unit="uW/nm",
                                       label="sensitivity")}
    DETUNING = quantity(name="detuning_hz", unit="Hz", display_unit="GHz",
                        label="laser-cavity detuning")

    @property
    def linewidth(self) -> float:
        """gamma = c / (lambda Q_o) in Hz (kappa / 2 pi)."""
        return SPEED_OF_LIGHT / (self.wavelength * self.optical_q)

    def transmission(self, x):
        """Transmitted power P_T in W for a displacement ``x`` (m).

        Parameters
        ----------
        x : float or array_like
            Displacement of the lever in m (moves the resonance by G x).
        """
        g2 = (self.linewidth / 2) ** 2
        delta = self.detuning * self.linewidth - self.coupling * check_array("x", x, "m")
        return self.power * (1 - self.dip_depth * g2 / (delta * delta + g2))

    def _stages(self, z, mode):
        delta = self.detuning * self.linewidth - self.coupling * z
        return self._lever_stages(z) + [(self.DETUNING, delta),
                                        (self.OUTPUTS["sensing"], self.transmission(z))]

    def _sensitivity(self, mode, at):
        g2 = (self.linewidth / 2) ** 2
        delta = self.detuning * self.linewidth - self.coupling * at
        lorentzian_slope = 2 * delta * g2 / (delta ** 2 + g2) ** 2
        return -self.power * self.dip_depth * self.coupling * lorentzian_slope

    def _dynamics(self, f, mode):
        return 1.0 / (1.0 + 1j * f / (self.linewidth / 2))

    def _detector_noise(self, bandwidth, low_frequency, mode):
        current = self.responsivity * float(self.transmission(0.0))
        return {"shot": math.sqrt(2 * ELEMENTARY_CHARGE * current * bandwidth) / self.responsivity}
