"""Piezo-acoustic actuation: a piezo shaker under the chip shakes the lever's base (AC only).
"""
from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from ..cantilever import MAX_MODE, Cantilever, eigenvalue
from ..validation import check_array, check_integer
from ..brownian import mechanical_response
from .base import FrequencyResponse, Parameter, Transducer, quantity

__all__ = ["PiezoAcoustic", "participation_factor", "mode_slope_factor"]

#: Gauss-Legendre nodes of the modal integrals (exact to round-off for every mode offered).
_GAUSS_NODES = 200
#: Share of the second mode in the tip response above which :meth:`PiezoAcoustic.validity` warns.
MAX_MODE_2_SHARE = 0.05


@lru_cache(maxsize=None)
def participation_factor(mode: int = 1) -> float:
    """gamma_n = int phi_n dx / int phi_n^2 dx of flexural mode ``mode``, phi_n = 1 at the free end.

    A base moving by y(t) loads every element of the lever with its inertia -rho A y''; projected
    on mode n (normalised to 1 at the free end) this drives the tip's motion *relative to the
    base* with gamma_n times the base motion. For mode 1 of a uniform clamped-free beam
    gamma_1 = 1.566 (Erturk and Inman, J. Intell. Mater. Syst. Struct. 19, 1311 (2008), the
    correction factor mu_1 of the base-excited cantilever without tip mass); gamma_2 = -0.868.

    Parameters
    ----------
    mode : int
        Mode number, 1 to :data:`afmsmiler.cantilever.MAX_MODE`.

    Returns
    -------
    float
        gamma_n (dimensionless), from Gauss-Legendre quadrature of module (a)'s mode shape
        (:meth:`afmsmiler.cantilever.Cantilever.mode_shape`).

    Raises
    ------
    ValueError
        If ``mode`` is not an integer in [1, MAX_MODE].
    """
    check_integer("mode", mode, 1, MAX_MODE)
    nodes, weights = np.polynomial.legendre.leggauss(_GAUSS_NODES)
    unit = Cantilever(1.0, 1.0, 1.0, 1.0, 1.0)  # mode shapes do not depend on size
    phi = unit.mode_shape((nodes + 1.0) / 2.0, mode)
    return float(weights @ phi / (weights @ (phi * phi)))


@lru_cache(maxsize=None)
def mode_slope_factor() -> float:
    """L phi_1'(L) / phi_1(L) of mode 1: the free-end slope is this times z / L (1.3765).

    The static end-load shape gives 1.5 instead (theta = 3 z / (2 L)), so an optical lever
    calibrated statically reads a mode-1 vibration of amplitude U as 1.3765 / 1.5 U = 0.918 U.
    Closed form from phi = cosh bx - cos bx - s (sinh bx - sin bx),
    s = (cosh bL + cos bL) / (sinh bL + sin bL), with b L from
    :func:`~afmsmiler.cantilever.eigenvalue`.
    """
    bl = eigenvalue(1)
    ch, c, sh, sn = math.cosh(bl), math.cos(bl), math.sinh(bl), math.sin(bl)
    s = (ch + c) / (sh + sn)
    return bl * (sh + sn - s * (ch - c)) / (ch - c - s * (sh - sn))


class PiezoAcoustic(Transducer):
    """Acoustic (base) excitation by a piezo shaker: the standard tapping-mode drive.

    A drive voltage of amplitude V at frequency f moves the chip by Y = d V (d: the shaker's
    displacement coefficient). A rigidly moved base does not bend the lever, so only the inertial
    load -rho A y''(t), projected on mode 1 (participation factor gamma_1 = 1.566), drives the
    bending. The tip deflection relative to the base, the quantity the detectors see, is::

        U / Y = gamma_1 (f / f1)^2 / (1 - (f / f1)^2 + j f / (Q f1))

    zero at DC (AC only), gamma_1 Q at resonance (phase -90 degrees), -gamma_1 far above it
    (Garcia, *Amplitude Modulation AFM*, ch. 2; Rao, *Mechanical Vibrations*, base excitation).
    U is the bending of the lever, the motion *relative to the base*: the absolute tip motion is
    Y + U (it tends to (1 - gamma_1) Y above resonance in this one-mode model). The optical lever
    sees U only, since translating the chip does not tilt the free end; the free-end slope
    follows the mode shape, theta = 1.377 U / L (:func:`mode_slope_factor`). The chain's input
    is the drive amplitude at ``drive_ratio`` = f / f1; stages are amplitudes.

    Only mode 1 is modelled: the second mode (at f2 = 6.27 f1, gamma_2 = -0.868) would add about
    1.4 % to the tip amplitude well below f1, next to nothing at f1 (where mode 1 resonates), 2 %
    at 1.5 f1, 5 % at 2 f1 and 15 % at 3 f1; :meth:`validity` says so when its share exceeds
    ``MAX_MODE_2_SHARE``.

    Its lever works in vacuum with the typed Q, or in a fluid (``fluid``: see
    :class:`~afmsmiler.transducers.base.Transducer`).
    """

    key = "piezo_acoustic"
    name = "piezo-acoustic"
    function, signal, size = "actuation", "AC only", "bulk"
    summary = "a piezo shaker vibrates the chip: base excitation"
    PARAMETERS = (
        Parameter(name="shaker_coefficient", unit="m/V", display_unit="nm/V", default=0.5e-9,
                  low=1e-12, high=1e-6, log=True, label="shaker displacement d"),
        Parameter(name="drive_ratio", unit="", default=1.0, low=0.01, high=3.0,
                  label="drive frequency / f1"),
    )
    MODES = ("actuation",)
    INPUTS = {"actuation": Parameter(name="drive_voltage", unit="V", default=0.1, low=0.0,
                                     high=10.0, label="drive amplitude V")}
    OUTPUTS = {"actuation": quantity(name="deflection", unit="m", display_unit="nm",
                                     label="tip amplitude")}
    SENSITIVITY = {"actuation": quantity(name="deflection_per_voltage", unit="m/V",
                                         display_unit="nm/V",
                                         label="sensitivity")}
    BASE = quantity(name="base_amplitude", unit="m", display_unit="nm", label="base amplitude")

    def base_transfer(self, f):
        """Complex U / Y (tip deflection relative to the base, per base displacement) at ``f`` Hz.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz, >= 0.

        Returns
        -------
        ndarray of complex
            gamma r^2 H(r), r = f / f_1 and H the first mode's
            :func:`~afmsmiler.brownian.mechanical_response`: 0 at DC, tending to -gamma (the
            tip stays still while the base moves) as f -> inf, finite for every finite ``f``.
        """
        f = check_array("f", f, "Hz", low=0.0)
        r = f / self.resonance_frequency
        q = self.quality_factor
        # r^2 / (1 - r^2 + j r / Q); above resonance divided through by r^2, so that no r^2
        # overflows into inf * 0 (NaN) for a huge f
        u = 1 / np.maximum(r, 1.0)                    # 1 / r above resonance
        above = 1 / (u * u - 1 + 1j * u / q)
        low = np.minimum(r, 1.0)
        below = low * low * mechanical_response(low * self.resonance_frequency,
                                                resonance_frequency=self.resonance_frequency,
                                                quality_factor=q)
        return participation_factor() * np.where(r > 1, above, below)

    @property
    def _gain(self) -> float:
        return float(np.abs(self.base_transfer(self.drive_ratio * self.resonance_frequency)))

    def _stages(self, v, mode):
        y = self.shaker_coefficient * v
        u = self._gain * y
        return [(self.BASE, y),
                (quantity(name="slope", unit="rad", display_unit="mrad",
                          label="free-end slope amplitude"),
                 mode_slope_factor() * u / self.length),
                (self.OUTPUTS["actuation"], u)]

    def deflection_shape(self, u) -> tuple:
        """The first flexural mode shape (base excitation drives mode 1), 1 at the tip.

        Parameters
        ----------
        u : array_like
            Positions along the lever as fractions of L, in [0, 1].

        Returns
        -------
        tuple of ndarray
            (shape, d shape / du, d^2 shape / du^2), the derivatives by finite differences.
        """
        u = check_array("u", u, low=0.0, high=1.0)
        shape = self.lever.mode_shape(u * self.length, 1)
        dshape = np.gradient(shape, u) if u.size > 1 else np.zeros_like(u)
        curv = np.gradient(dshape, u) if u.size > 1 else np.zeros_like(u)
        return shape, dshape, curv

    def _sensitivity(self, mode, at):
        return self.shaker_coefficient * self._gain

    def mode_2_share(self) -> float:
        """|tip response of mode 2| / |tip response of mode 1| at the drive frequency.

        Each mode n responds as gamma_n r_n^2 / (1 - r_n^2 + j r_n / Q_n), r_n = f / f_n, at
        f_n and Q_n in the lever's medium (:meth:`mode_in_medium`: in vacuum the typed Q for
        both, an assumption; only the order of magnitude matters here).
        """
        f = self.drive_ratio * self.resonance_frequency
        f2, q2 = self.mode_in_medium(2)
        r2 = f / f2
        second = participation_factor(2) * r2 * r2 * mechanical_response(
            f, resonance_frequency=f2, quality_factor=q2)
        return float(abs(second) / abs(self.base_transfer(f)))

    def _validity(self, value, mode, point):
        share = self.mode_2_share()
        if share > MAX_MODE_2_SHARE:
            yield (f"at {self.drive_ratio:.3g} f1 the second mode adds {100 * share:.0f} % to the "
                   f"tip amplitude: the one-mode model no longer holds")

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

