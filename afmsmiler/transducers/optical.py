"""Bulk optical sensing: optical beam deflection, astigmatic detection and interferometry.

All three read the lever's free end with a laser from outside ("bulk"), at DC and AC; their
shot-noise-limited resolution is computed from the photocurrent (Schottky: a current I has the
one-sided noise density sqrt(2 q I) A/sqrt(Hz)).
"""
from __future__ import annotations

import math

import numpy as np
from scipy.special import erf

from ..validation import check_array
from .base import (ELEMENTARY_CHARGE, TIP_DEFLECTION_INPUT, Parameter, Transducer, quantity)

__all__ = ["OpticalBeamDeflection", "AstigmaticDetection", "Interferometer"]

_RESPONSIVITY = Parameter(name="responsivity", unit="A/W", default=0.4, low=0.05, high=1.0,
                          label="photodiode responsivity")
_BANDWIDTH = Parameter(name="detector_bandwidth", unit="Hz", display_unit="kHz", default=2e6,
                       low=1e3, high=1e8, log=True, label="detector bandwidth")


def _detector_lowpass(f, bandwidth):
    """A first-order photoreceiver: 1 / (1 + j f / f_c)."""
    return 1.0 / (1.0 + 1j * f / bandwidth)


def _shot_noise_current(current: float, bandwidth: float) -> float:
    """Rms shot noise sqrt(2 q I B) in A of a photocurrent ``current``."""
    return math.sqrt(2 * ELEMENTARY_CHARGE * abs(current) * bandwidth)


class OpticalBeamDeflection(Transducer):
    """The optical lever: a laser reflected off the free end onto a four-quadrant photodiode.

    A tip deflection z tilts the free end by theta = 3 z / (2 L) (end-loaded lever, module (a)).
    Reflection doubles the angle, so the spot moves by s = D tan(2 theta) ~ 2 D theta = 3 D z / L
    on a detector at optical path D. For a Gaussian spot of 1/e^2 radius w, the fractions of
    power on the upper (A + B) and lower (C + D) halves are (1 +- erf(sqrt(2) s / w)) / 2, so the
    normalised difference signal is::

        S = ((A + B) - (C + D)) / (A + B + C + D) = erf(sqrt(2) s / w)

    and the small-signal sensitivity at the null is dS/dz = sqrt(8 / pi) / w * 3 D / L (1/m): it
    grows with the optical path and falls as 1/L (Meyer and Amer, Appl. Phys. Lett. 53, 1045 (1988);
    Sarid, *Scanning Force Microscopy*, ch. 5; Putman et al., J. Appl. Phys. 72, 6 (1992)).
    The displacement of the reflection point itself (of order z, not D z / L) is neglected.

    Noise: the difference current carries the shot noise of the whole photocurrent I = R P, so
    the rms noise of S is sqrt(2 q B / I).

    Its lever works in vacuum with the typed Q, or in a fluid (``fluid``: see
    :class:`~afmsmiler.transducers.base.Transducer`).
    """

    key = "optical_beam_deflection"
    name = "optical beam deflection"
    function, signal, size = "sensing", "DC&AC", "bulk"
    summary = "laser reflected off the lever onto a four-quadrant photodiode"
    PARAMETERS = (
        Parameter(name="optical_path", unit="m", display_unit="mm", default=30e-3, low=1e-3,
                  high=0.2, label="optical path D (lever to detector)"),
        Parameter(name="spot_radius", unit="m", display_unit="mm", default=0.5e-3, low=20e-6,
                  high=5e-3, label="spot 1/e^2 radius on the detector"),
        Parameter(name="power", unit="W", display_unit="mW", default=1e-3, low=1e-6, high=20e-3,
                  log=True, label="laser power on the detector"),
        _RESPONSIVITY, _BANDWIDTH,
    )
    INPUTS = {"sensing": TIP_DEFLECTION_INPUT}
    OUTPUTS = {"sensing": quantity(name="signal", unit="", label="(A+B-C-D)/(A+B+C+D)")}
    SENSITIVITY = {"sensing": quantity(name="signal_per_deflection", unit="1/m",
                                       display_unit="1/um",
                                       label="sensitivity")}
    SPOT = quantity(name="spot_displacement", unit="m", display_unit="um",
                    label="spot travel on the detector")

    def spot_displacement(self, slope):
        """Spot travel s = D tan(2 theta) in m for a free-end slope ``slope`` (rad).

        Parameters
        ----------
        slope : float or array_like
            Free-end slope theta in rad, in (-pi/4, pi/4) (beyond, the beam no longer returns).
        """
        slope = check_array("slope", slope, "rad", low=-math.pi / 4, high=math.pi / 4,
                            low_inclusive=False, high_inclusive=False)
        return self.optical_path * np.tan(2 * slope)

    def split_signal(self, spot):
        """Normalised difference signal erf(sqrt(2) s / w) for a spot offset ``spot`` (m).

        Parameters
        ----------
        spot : float or array_like
            Spot centre's offset from the split line in m (positive towards A + B).
        """
        spot = check_array("spot", spot, "m")
        return erf(math.sqrt(2.0) * spot / self.spot_radius)

    def _stages(self, z, mode):
        lever = self._lever_stages(z)
        s = self.spot_displacement(lever[0][1])
        return lever + [(self.SPOT, s), (self.OUTPUTS["sensing"], self.split_signal(s))]

    def _sensitivity(self, mode, at):
        two_theta = 3 * at / self.length
        s = self.optical_path * math.tan(two_theta)
        ds_dz = 3 * self.optical_path / (self.length * math.cos(two_theta) ** 2)
        return (math.sqrt(8 / math.pi) / self.spot_radius
                * math.exp(-2 * (s / self.spot_radius) ** 2) * ds_dz)

    def _dynamics(self, f, mode):
        return _detector_lowpass(f, self.detector_bandwidth)

    def _detector_noise(self, bandwidth, low_frequency, mode):
        current = self.responsivity * self.power
        return {"shot": _shot_noise_current(current, bandwidth) / current}


class AstigmaticDetection(Transducer):
    """Astigmatic detection: the focus-error signal of an optical disc (DVD) pickup head.

    The pickup focuses a laser onto the lever; on the way back a cylindrical lens makes the beam
    astigmatic, with two line foci (x and y) separated by Delta (referred to the lever side),
    and a four-quadrant detector sits midway, its split lines at 45 degrees to the foci. A
    displacement d of the reflector moves the returning focus by 2 d, so the Gaussian beam radii
    on the detector (waist w0, Rayleigh range z_R = pi w0^2 / lambda, a = Delta / 2) are::

        w_x ~ sqrt(1 + ((2 d - a) / z_R)^2),     w_y ~ sqrt(1 + ((2 d + a) / z_R)^2)

    For an elliptical Gaussian spot the diagonal quadrant pairs receive the angular fractions
    (2/pi) atan(w_y / w_x) and 1 - (2/pi) atan(w_y / w_x), so the focus-error signal is::

        FES = ((A + C) - (B + D)) / (A + B + C + D) = (4 / pi) atan(w_y / w_x) - 1

    an S-curve: zero in focus, extrema at d = +-sqrt(a^2 + z_R^2) / 2, back to zero far away.
    Its slope at focus is 8 a / (pi (z_R^2 + a^2)) (largest, 4 / (pi z_R), for a = z_R), and its
    linear range is a few um (Braat, Dirksen and Janssen, "Diffractive read-out of optical
    discs", in *Optical Imaging and Microscopy*, Springer 2003; the astigmatic detection system
    AFM with a DVD pickup head: Hwu et al., Appl. Phys. Lett. 91, 221908 (2007), Nanotechnology
    19, 115501 (2008)).
    Noise: shot noise of the detector current, as for the optical lever.

    Its lever works in vacuum with the typed Q, or in a fluid (``fluid``: see
    :class:`~afmsmiler.transducers.base.Transducer`).
    """

    key = "astigmatic"
    name = "astigmatic detection"
    function, signal, size = "sensing", "DC&AC", "bulk"
    summary = "focus-error S-curve of a DVD pickup head (cylindrical lens, four quadrants)"
    PARAMETERS = (
        Parameter(name="wavelength", unit="m", display_unit="nm", default=650e-9, low=350e-9,
                  high=1.6e-6, label="laser wavelength"),
        Parameter(name="waist", unit="m", display_unit="um", default=0.6e-6, low=0.2e-6,
                  high=5e-6, label="focused spot radius w0"),
        Parameter(name="astigmatic_distance", unit="m", display_unit="um", default=4e-6,
                  low=0.2e-6, high=50e-6, label="line-foci separation Delta"),
        Parameter(name="power", unit="W", display_unit="uW", default=100e-6, low=1e-6, high=5e-3,
                  log=True, label="laser power on the detector"),
        _RESPONSIVITY, _BANDWIDTH,
    )
    INPUTS = {"sensing": Parameter(name="deflection", unit="m", display_unit="nm", default=50e-9,
                                   low=-10e-6, high=10e-6, label="tip deflection")}
    OUTPUTS = {"sensing": quantity(name="signal", unit="", label="focus-error signal FES")}
    SENSITIVITY = {"sensing": quantity(name="signal_per_deflection", unit="1/m",
                                       display_unit="1/um",
                                       label="FES slope")}
    RATIO = quantity(name="axis_ratio", unit="", label="spot axis ratio w_y / w_x")
    #: The largest displacement from focus in m that :meth:`spot_radii` and :meth:`focus_error`
    #: accept: the objective of a DVD pickup works about 1 mm from the disc (its working
    #: distance), so no reflector in front of it is farther than that from focus (and the
    #: near-focus Gaussian beam of this model has long stopped describing the spot).
    MAX_DISPLACEMENT = 1e-3

    @property
    def rayleigh_range(self) -> float:
        """z_R = pi w0^2 / lambda in m."""
        return math.pi * self.waist ** 2 / self.wavelength

    def spot_radii(self, d):
        """Beam radii (w_x, w_y) on the detector in units of w0 for a displacement ``d`` (m).

        Parameters
        ----------
        d : float or array_like
            Displacement of the reflector (the lever) from focus in m, at most
            :attr:`MAX_DISPLACEMENT` (1 mm, the pickup's working distance) either way.

        Returns
        -------
        tuple of ndarray
            (w_x, w_y), each of the shape of ``d``.

        Raises
        ------
        ValueError
            If a displacement is not finite or beyond :attr:`MAX_DISPLACEMENT`.
        """
        d = check_array("d", d, "m", low=-self.MAX_DISPLACEMENT, high=self.MAX_DISPLACEMENT)
        a, zr = self.astigmatic_distance / 2, self.rayleigh_range
        return np.sqrt(1 + ((2 * d - a) / zr) ** 2), np.sqrt(1 + ((2 * d + a) / zr) ** 2)

    def focus_error(self, d):
        """FES = (4/pi) atan(w_y / w_x) - 1 for a displacement ``d`` (m) of the reflector.

        Parameters
        ----------
        d : float or array_like
            Displacement of the reflector from focus in m, at most :attr:`MAX_DISPLACEMENT`
            (1 mm) either way.

        Returns
        -------
        ndarray
            FES, in (-1, 1), of the shape of ``d``.

        Raises
        ------
        ValueError
            As :meth:`spot_radii`.
        """
        wx, wy = self.spot_radii(d)
        return 4 / math.pi * np.arctan(wy / wx) - 1

    def _stages(self, z, mode):
        wx, wy = self.spot_radii(z)
        fes = 4 / math.pi * np.arctan(wy / wx) - 1
        return self._lever_stages(z) + [(self.RATIO, wy / wx), (self.OUTPUTS["sensing"], fes)]

    def _sensitivity(self, mode, at):
        a, zr = self.astigmatic_distance / 2, self.rayleigh_range
        u, v = (2 * at + a) / zr, (2 * at - a) / zr
        wx, wy = self.spot_radii(at)
        r = float(wy / wx)
        return 4 / math.pi * r / (1 + r * r) * 2 / zr * (u / (1 + u * u) - v / (1 + v * v))

    def _dynamics(self, f, mode):
        return _detector_lowpass(f, self.detector_bandwidth)

    def _detector_noise(self, bandwidth, low_frequency, mode):
        current = self.responsivity * self.power
        return {"shot": _shot_noise_current(current, bandwidth) / current}


class Interferometer(Transducer):
    """A (fibre) interferometer reading the lever's back: the two-beam fringe.

    The light reflected by the lever interferes with a reference; a displacement d changes the
    round-trip path by 2 d, so the detected power is (Hecht, *Optics*, ch. 9; Rugar, Mamin and
    Guethner, Appl. Phys. Lett. 55, 2588 (1989))::

        P(d) = P0 (1 + V cos(4 pi d / lambda + phi))

    with visibility V and operating phase phi. Its slope -P0 V (4 pi / lambda) sin(phi) is
    largest at quadrature, phi = -pi/2 (the default), where it is 4 pi V P0 / lambda; far from
    it the response is nonlinear and even folds over each half fringe (lambda / 4 of travel).
    Noise: shot noise of the photocurrent at the operating point.

    Its lever works in vacuum with the typed Q, or in a fluid (``fluid``: see
    :class:`~afmsmiler.transducers.base.Transducer`).
    """

    key = "interferometry"
    name = "interferometry"
    function, signal, size = "sensing", "DC&AC", "bulk"
    summary = "fibre interferometer: the fringe and its quadrature point"
    PARAMETERS = (
        Parameter(name="wavelength", unit="m", display_unit="nm", default=1310e-9, low=350e-9,
                  high=2e-6, label="laser wavelength"),
        Parameter(name="visibility", unit="", default=0.8, low=0.01, high=1.0,
                  label="fringe visibility V"),
        Parameter(name="power", unit="W", display_unit="uW", default=100e-6, low=1e-6, high=5e-3,
                  log=True, label="mean power P0 on the detector"),
        Parameter(name="phase", unit="rad", default=-math.pi / 2, low=-math.pi, high=math.pi,
                  label="operating phase phi"),
        _RESPONSIVITY, _BANDWIDTH,
    )
    INPUTS = {"sensing": Parameter(name="deflection", unit="m", display_unit="nm", default=20e-9,
                                   low=-1e-6, high=1e-6, label="tip deflection")}
    OUTPUTS = {"sensing": quantity(name="power_detected", unit="W", display_unit="uW",
                                   label="detected power")}
    SENSITIVITY = {"sensing": quantity(name="power_per_deflection", unit="W/m",
                                       display_unit="uW/nm",
                                       label="sensitivity")}
    PHASE = quantity(name="optical_phase", unit="rad",
                     label="optical phase 4 pi d / lambda + phi")

    def fringe(self, d):
        """Detected power P0 (1 + V cos(4 pi d / lambda + phi)) in W at displacement ``d`` (m).

        Parameters
        ----------
        d : float or array_like
            Displacement of the lever in m (it changes the round-trip path by 2 d), within
            +-1 m (a larger one leaves no digit of the fringe's phase).
        """
        phase = 4 * math.pi * check_array("d", d, "m", low=-1.0, high=1.0) / self.wavelength
        phase = phase + self.phase
        return self.power * (1 + self.visibility * np.cos(phase))

    def _stages(self, z, mode):
        phase = 4 * math.pi * z / self.wavelength + self.phase
        return self._lever_stages(z) + [(self.PHASE, phase),
                                        (self.OUTPUTS["sensing"], self.fringe(z))]

    def _sensitivity(self, mode, at):
        k = 4 * math.pi / self.wavelength
        return -self.power * self.visibility * k * math.sin(k * at + self.phase)

    def _dynamics(self, f, mode):
        return _detector_lowpass(f, self.detector_bandwidth)

    def _detector_noise(self, bandwidth, low_frequency, mode):
        power = float(self.fringe(0.0))
        current = self.responsivity * power
        return {"shot": _shot_noise_current(current, bandwidth) / self.responsivity}
