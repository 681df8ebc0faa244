"""Bulk electric actuation: electrostatic (capacitive), electromagnetic (Lorentz force, magnetic).
"""
from __future__ import annotations

import math

from ..brownian import mechanical_response
from ..validation import check_array, check_nonnegative, check_range
from .base import (DEFLECTION, EPSILON_0, FORCE, SLOPE, Harmonics, Parameter, Transducer,
                   quantity)

__all__ = ["Electrostatic", "Electromagnetic"]


class Electrostatic(Transducer):
    """Electrostatic actuation: a parallel-plate capacitor between the lever's end and an electrode.

    A counter-electrode a gap g below the last ``electrode_length`` l_e of the lever (area
    A = w l_e) forms C(z) = epsilon_0 A / (g + z), so dC/dz = -epsilon_0 A / g^2. At constant
    voltage the force is F = (1/2) dC/dz V^2 (attractive: towards the electrode, z < 0). With
    V = V_dc + V_ac cos(omega t)::

        F = (1/2) dC/dz (V_dc^2 + V_ac^2 / 2)          (DC)
          + dC/dz V_dc V_ac cos(omega t)               (1 omega)
          + (1/4) dC/dz V_ac^2 cos(2 omega t)          (2 omega)

    the DC, 1-omega and 2-omega parts used by Kelvin-probe and electrostatic force microscopy
    (Hudlet et al., Eur. Phys. J. B 2, 5 (1998); Senturia, *Microsystem Design*, ch. 6). The
    force is spread uniformly over the electrode, q = F / l_e on [a, L], a = L - l_e; integrating
    the point-load influence functions of module (a) gives the tip::

        z(L) = q (3 L^4 / 4 - L a^3 + a^4 / 4) / (6 E J),     theta(L) = q (L^3 - a^3) / (6 E J)

    (the end-load values F / k and 3 F / (2 k L) when l_e -> 0; q L^4 / (8 E J) when l_e = L).
    Small deflections (|z| << g): the gap change and the electrostatic spring softening are not
    modelled; :attr:`pull_in_voltage` says where that stops being true.

    Its lever works in vacuum with the typed Q, or in a fluid (``fluid``: see
    :class:`~afmsmiler.transducers.base.Transducer`).
    """

    key = "electrostatic"
    name = "electrostatic"
    function, signal, size = "actuation", "DC&AC", "bulk"
    summary = "a voltage across the gap to a counter-electrode pulls the lever"
    BIASED = True
    BOUNDED_BY = {"electrode_length": ("length", 1.0)}
    PARAMETERS = (
        Parameter(name="gap", unit="m", display_unit="um", default=5e-6, low=0.2e-6, high=200e-6,
                  log=True, label="electrode gap g"),
        Parameter(name="electrode_length", unit="m", display_unit="um", default=50e-6, low=1e-6,
                  high=1e-3, label="electrode length l_e"),
        Parameter(name="ac_voltage", unit="V", default=1.0, low=0.0, high=50.0,
                  label="AC amplitude V_ac"),
    )
    MODES = ("actuation",)
    INPUTS = {"actuation": Parameter(name="dc_voltage", unit="V", default=5.0, low=-50.0,
                                     high=50.0, label="DC voltage V_dc")}
    OUTPUTS = {"actuation": DEFLECTION}
    SENSITIVITY = {"actuation": quantity(name="deflection_per_voltage", unit="m/V",
                                         display_unit="nm/V",
                                         label="sensitivity")}

    @property
    def capacitance_gradient(self) -> float:
        """dC/dz = -epsilon_0 w l_e / g^2 in F/m (z up, electrode below)."""
        return -EPSILON_0 * self.width * self.electrode_length / self.gap ** 2

    @property
    def compliance(self) -> tuple:
        """(tip deflection, tip slope) per newton of uniform load on the electrode (m/N, rad/N)."""
        L, a, ei = self.length, self.length - self.electrode_length, self.lever.flexural_rigidity
        q = 1.0 / self.electrode_length
        return (q * (0.75 * L ** 4 - L * a ** 3 + a ** 4 / 4) / (6 * ei),
                q * (L ** 3 - a ** 3) / (6 * ei))

    @property
    def pull_in_voltage(self) -> float:
        """Pull-in voltage sqrt(8 k_e g^3 / (27 epsilon_0 A)) in V (Senturia, sec. 6.4).

        Beyond it the electrode snaps the lever down (at z = -g/3); k_e = 1 / compliance is the
        lever's stiffness against the load on the electrode. The model is only meaningful well
        below it.
        """
        k_e = 1.0 / self.compliance[0]
        area = self.width * self.electrode_length
        return math.sqrt(8 * k_e * self.gap ** 3 / (27 * EPSILON_0 * area))

    def _validity(self, value, mode, point):
        peak = abs(value) + self.ac_voltage
        if peak >= self.pull_in_voltage:
            yield (f"|V_dc| + V_ac = {peak:.3g} V is past pull-in ({self.pull_in_voltage:.3g} V): "
                   f"the lever would snap onto the electrode")

    def force_components(self, dc_voltage: float) -> Harmonics:
        """DC, 1-omega and 2-omega force amplitudes in N for a bias ``dc_voltage`` (V)."""
        v = self.INPUTS["actuation"].check(dc_voltage)
        g, va = self.capacitance_gradient, self.ac_voltage
        return Harmonics(0.5 * g * (v * v + va * va / 2), g * v * va, 0.25 * g * va * va)

    def deflection_components(self, dc_voltage: float, frequency: float) -> Harmonics:
        """Complex tip-deflection amplitudes (m) at DC, omega and 2 omega.

        Parameters
        ----------
        dc_voltage : float
            Bias V_dc in V.
        frequency : float
            Drive frequency omega / (2 pi) in Hz; each force component passes the first mode at
            its own frequency.
        """
        frequency = check_nonnegative("frequency", frequency, "Hz")
        f = self.force_components(dc_voltage)
        c = self.compliance[0]

        def h(fr):
            return complex(c * mechanical_response(
                fr, resonance_frequency=self.resonance_frequency,
                quality_factor=self.quality_factor))
        return Harmonics(f.dc * h(0.0), f.first * h(frequency), f.second * h(2 * frequency))

    def _stages(self, v, mode):
        force = 0.5 * self.capacitance_gradient * (v * v + self.ac_voltage ** 2 / 2)
        cz, ct = self.compliance
        return [(FORCE, force), (SLOPE, ct * force), (DEFLECTION, cz * force)]

    def _sensitivity(self, mode, at):
        return self.compliance[0] * self.capacitance_gradient * at


class Electromagnetic(Transducer):
    """Electromagnetic actuation: the Lorentz force on a current at the tip, or a magnetic moment.

    A conductor loop runs along the lever's edges and across its free end; in a field B along the
    lever's axis, only the crossbar of length l (perpendicular to B) feels a vertical force::

        F = B I l        (Lorentz, F = I l x B)

    an end load, so z = F / k and theta = 3 z / (2 L) (module (a)); it works at DC and AC
    (Buguin et al., Appl. Phys. Lett. 78, 2982 (2001)). A magnetic moment m at the tip (a
    magnetic particle or coating, MAC mode) feels the force m dB/dz in a field gradient
    (:meth:`moment_force`) and the torque m B sin(angle) in a uniform field
    (:meth:`moment_torque_deflection`): an end moment M bends the lever to z = M L^2 / (2 E J),
    theta = M L / (E J) (Jackson, *Classical Electrodynamics*, sec. 5.7; Han, Lindsay and Jing,
    Appl. Phys. Lett. 69, 4111 (1996)).

    Its lever works in vacuum with the typed Q, or in a fluid (``fluid``: see
    :class:`~afmsmiler.transducers.base.Transducer`).
    """

    key = "electromagnetic"
    name = "electromagnetic"
    function, signal, size = "actuation", "DC&AC", "bulk"
    summary = "Lorentz force B I l on a current loop at the tip (or a magnetic moment)"
    PARAMETERS = (
        Parameter(name="field", unit="T", display_unit="mT", default=0.1, low=1e-4, high=2.0,
                  log=True, label="magnetic field B"),
        Parameter(name="conductor_length", unit="m", display_unit="um", default=25e-6, low=1e-6,
                  high=200e-6, label="crossbar length l"),
    )
    MODES = ("actuation",)
    INPUTS = {"actuation": Parameter(name="current", unit="A", display_unit="mA", default=5e-3,
                                     low=-50e-3, high=50e-3, label="loop current I")}
    OUTPUTS = {"actuation": DEFLECTION}
    SENSITIVITY = {"actuation": quantity(name="deflection_per_current", unit="m/A",
                                         display_unit="nm/mA",
                                         label="sensitivity")}

    def lorentz_force(self, current):
        """F = B I l in N for a loop current ``current`` (A).

        Parameters
        ----------
        current : float or array_like
            Loop current I in A (positive lifts the tip).
        """
        return self.field * check_array("current", current, "A") * self.conductor_length

    def moment_force(self, moment: float, field_gradient: float) -> float:
        """Force m dB/dz in N on a moment ``moment`` (A m^2) in a gradient ``field_gradient`` (T/m).

        Parameters
        ----------
        moment : float
            Magnetic moment m in A m^2.
        field_gradient : float
            Field gradient dB/dz in T/m.
        """
        m = check_range("moment", moment, -math.inf, math.inf, "A m^2")
        grad = check_range("field_gradient", field_gradient, -math.inf, math.inf, "T/m")
        return m * grad

    def moment_torque_deflection(self, moment: float, angle: float = math.pi / 2) -> tuple:
        """(tip deflection m, tip slope rad) from the torque m B sin(angle) of the model's field.

        Parameters
        ----------
        moment : float
            Magnetic moment in A m^2.
        angle : float
            Angle between the moment and the field in rad.
        """
        m = check_range("moment", moment, -math.inf, math.inf, "A m^2")
        angle = check_range("angle", angle, -math.pi, math.pi, "rad")
        torque = m * self.field * math.sin(angle)
        ei, L = self.lever.flexural_rigidity, self.length
        return torque * L ** 2 / (2 * ei), torque * L / ei

    def _stages(self, i, mode):
        force = self.lorentz_force(i)
        z = force / self.spring_constant
        return [(FORCE, force), (SLOPE, 1.5 * z / self.length), (DEFLECTION, z)]

    def _sensitivity(self, mode, at):
        return self.field * self.conductor_length / self.spring_constant
