"""Piezo-acoustic actuation: a piezo shaker under the chip shakes the lever's base (AC only).
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np

from ..cantilever import Cantilever
from ..validation import check_array
from .base import FrequencyResponse, Parameter, Quantity, Transducer, mechanical_response

__all__ = ["PiezoAcoustic", "participation_factor", "mode_slope_factor"]


@lru_cache(maxsize=None)
def _mode_integrals(points: int = 20001):
    lever = Cantilever(1.0, 1.0, 1.0, 1.0, 1.0)  # the shape of mode 1 does not depend on size
    x = np.linspace(0.0, 1.0, points)
    phi = lever.mode_shape(x, 1)
    slope = (3 * phi[-1] - 4 * phi[-2] + phi[-3]) / (2 * (x[1] - x[0]))
    return float(np.trapezoid(phi, x)), float(np.trapezoid(phi * phi, x)), float(slope)


def participation_factor() -> float:
    """gamma_1 = int phi / int phi^2 of mode 1 (phi = 1 at the tip): 1.566 for a uniform lever.

    The base acceleration loads every element of the lever with its inertia; projected on mode 1
    (normalised to 1 at the free end) it drives the tip with gamma_1 times the base motion
    (Erturk and Inman, J. Intell. Mater. Syst. Struct. 19, 1311 (2008)).
    """
    integral, norm, _ = _mode_integrals()
    return integral / norm


def mode_slope_factor() -> float:
    """L phi'(L) / phi(L) of mode 1: the free-end slope is this times z / L (1.377; 1.5 static)."""
    return _mode_integrals()[2]


class PiezoAcoustic(Transducer):
    """Acoustic (base) excitation by a piezo shaker: the standard tapping-mode drive.

    A drive voltage of amplitude V at frequency f moves the chip by Y = d V (d: the shaker's
    displacement coefficient). A rigidly moved base does not bend the lever, so only the inertial
    load -rho A y''(t), projected on mode 1 (participation factor gamma_1 = 1.566), drives the
    bending. The tip deflection relative to the base, the quantity the detectors see, is::

        U / Y = gamma_1 (f / f1)^2 / (1 - (f / f1)^2 + j f / (Q f1))

    zero at DC (AC only), gamma_1 Q at resonance (phase -90 degrees), gamma_1 far above it
    (Garcia, *Amplitude Modulation AFM*, ch. 2; Rao, *Mechanical Vibrations*, base excitation).
    The free-end slope follows the mode shape: theta = 1.377 U / L. The chain's input is the
    drive amplitude at ``drive_ratio`` = f / f1; stages are amplitudes.
    """

    key = "piezo_acoustic"
    name = "piezo-acoustic"
    function, signal, size = "actuation", "AC only", "bulk"
    summary = "a piezo shaker vibrates the chip: base excitation"
    PARAMETERS = (
        Parameter("shaker_coefficient", "m/V", "nm/V", 1e9, "shaker displacement d", 0.5e-9,
                  1e-12, 1e-6, log=True),
        Parameter("drive_ratio", "", "", 1.0, "drive frequency / f1", 1.0, 0.01, 3.0),
    )
    MODES = ("actuation",)
    INPUTS = {"actuation": Parameter("drive_voltage", "V", "V", 1.0, "drive amplitude V", 0.1,
                                     0.0, 10.0)}
    OUTPUTS = {"actuation": Quantity("deflection", "m", "nm", 1e9, "tip amplitude")}
    SENSITIVITY = {"actuation": Quantity("sensitivity", "m/V", "nm/V", 1e9, "sensitivity")}
    BASE = Quantity("base_amplitude", "m", "nm", 1e9, "base amplitude")

    def base_transfer(self, f):
        """Complex U / Y (tip deflection relative to the base, per base displacement) at ``f`` Hz."""
        f = check_array("f", f, "Hz", low=0.0)
        r = f / self.resonance_frequency
        return participation_factor() * r * r * mechanical_response(
            f, self.resonance_frequency, self.quality_factor)

    @property
    def _gain(self) -> float:
        return float(np.abs(self.base_transfer(self.drive_ratio * self.resonance_frequency)))

    def _stages(self, v, mode):
        y = self.shaker_coefficient * v
        u = self._gain * y
        return [(self.BASE, y),
                (Quantity("slope", "rad", "mrad", 1e3, "free-end slope amplitude"),
                 mode_slope_factor() * u / self.length),
                (self.OUTPUTS["actuation"], u)]

    def _sensitivity(self, mode, at):
        return self.shaker_coefficient * self._gain

    def _static_gain(self, mode, at):
        # the Brownian motion at the drive frequency is amplified by the same |H| as the drive,
        # so the input-referred floor uses the drive's gain without the resonance
        r = self.drive_ratio
        return self.shaker_coefficient * participation_factor() * r * r

    def frequency_response(self, f, mode=None) -> FrequencyResponse:
        """Complex tip amplitude per drive volt, d U / Y, at frequencies ``f`` (Hz); zero at DC.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz, >= 0.
        mode : str, optional
            ``"actuation"`` (the only mode).
        """
        mode = self._mode(mode)
        response = self.shaker_coefficient * self.base_transfer(f)
        f = np.asarray(f, dtype=float)
        return FrequencyResponse(f, response, self.INPUTS[mode], self.OUTPUTS[mode], "m/V")

