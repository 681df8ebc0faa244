"""Module (a): the Brownian (thermal) motion of a cantilever, mode by mode.

A lever at temperature T in a viscous medium is pushed about by the thermal force of its
surroundings. Each flexural mode n of a rectangular :class:`~afmsmiler.cantilever.Cantilever`
(eigenvalue b_n L, the n-th root of cos(x) cosh(x) = -1; resonance f_n; quality factor Q) is a
damped harmonic oscillator seen at the free end, with the response to a force at f normalised
to 1 at DC::

    H_n(f) = 1 / (1 - (f/f_n)^2 + j f / (Q f_n))          (= 1 at DC, ~ -j Q at f_n)

(Sarid, *Scanning Force Microscopy*, OUP 1994, ch. 1; Garcia, *Amplitude Modulation AFM*, Wiley
2010, ch. 2).

How k_B T is shared between the modes
-------------------------------------
Equipartition gives every mode k_B T / 2 of potential energy. Expanding the end deflection of
the point-loaded lever in its modes, the mean-square end deflection of mode n is::

    <z_n^2> = 12 / (b_n L)^4 * k_B T / k,          k = 3 E J / L^3 (end-load spring constant)

and the shares 12 / (b_n L)^4 (0.971, 0.0247, 0.00315, ...) sum to 1, so that all modes together
give the static spring's k_B T / k (Butt and Jaschke, "Calculation of thermal noise in atomic
force microscopy", Nanotechnology 6, 1 (1995), Eq. (9)): the first mode carries 0.971 of it.
Mode n therefore behaves, at the tip, as an oscillator of stiffness k_n = k / share_n, and its
one-sided power spectral density follows from the fluctuation-dissipation theorem::

    S_n(f) = S_n0 |H_n(f)|^2,   S_n0 = 4 k_B T / (k_n 2 pi f_n Q) = share_n 4 k_B T / (k omega_n Q)

which integrates to share_n k_B T / k over all frequencies (int_0^inf |H_n|^2 df = pi Q f_n / 2).
The rms deflection in a band [f_a, f_b] is sqrt(S_n0 f_n (F(f_b / f_n) - F(f_a / f_n))) with the
closed-form antiderivative of |H_n|^2 in r = f / f_n, b = sqrt(4 - 1/Q^2) (partial fractions of
1 / (r^2 - b r + 1)(r^2 + b r + 1))::

    F(r) = r / (2 (1 + r^2)) atanh(x) / x + (Q / 2) atan2(r, Q (1 - r^2)),   x = b r / (1 + r^2)

(F(inf) = pi Q / 2). For an overdamped mode (Q < 1/2) b is imaginary, b = j c with
c = sqrt(1/Q^2 - 4), and atanh(x) / x becomes atan(y) / y, y = c r / (1 + r^2): the same F for
every Q > 0 (a lever in water can be overdamped: 1 mm x 5 um x 0.2 um of silicon has Q = 0.16
there). Well below resonance it is sqrt(S_n0 B), the white floor under every detector's
resolution. The same Q is used for every mode (a simplification: in air Q grows with the mode
number).

In a fluid the mode rings at f_R,n below its vacuum f_n (the fluid's added mass) with the
fluid's Q_n (:func:`afmsmiler.hydrodynamics.fluid_mode`, Sader 1998): the functions take that
f_R,n as ``resonance_frequency``, and S_n0 = share_n 4 k_B T / (k omega_R,n Q_n) still
integrates to share_n k_B T / k (the added mass changes the frequency, not the stiffness).

Examples
--------
>>> round(mode_share(1), 4)
0.9707
"""
from __future__ import annotations

import math

import numpy as np
import scipy.constants

from .cantilever import MAX_MODE, Cantilever, eigenvalue
from .parameters import QUALITY_FACTOR, Parameter, read_only
from .validation import (check_array, check_instance, check_integer, check_positive,
                         check_range)

__all__ = ["QUALITY_FACTOR", "TEMPERATURE", "PARAMETERS", "BOLTZMANN", "mode_share",
           "deflection_variance", "mechanical_response", "thermal_noise_density",
           "thermal_deflection_noise"]

#: Boltzmann constant k_B in J/K (scipy's CODATA value).
BOLTZMANN = scipy.constants.k

#: The lever's temperature (its quality factor is the vocabulary's
#: :data:`afmsmiler.parameters.QUALITY_FACTOR`, any Q > 0: the closed form of the thermal
#: spectrum holds for an overdamped mode too).
TEMPERATURE = Parameter(name="temperature", unit="K", default=295.0, low=1.0, high=600.0,
                        label="temperature T")
#: Name -> Parameter of the Brownian motion's own parameters.
PARAMETERS = read_only({p.name: p for p in (QUALITY_FACTOR, TEMPERATURE)})


def mode_share(mode: int = 1) -> float:
    """Share 12 / (b_n L)^4 of k_B T / k in the end deflection of flexural mode ``mode``.

    Parameters
    ----------
    mode : int
        Mode number n, 1 to :data:`~afmsmiler.cantilever.MAX_MODE`.

    Returns
    -------
    float
        0.9707 for mode 1, 0.0247 for mode 2, ...; the shares of all modes sum to 1
        (Butt and Jaschke 1995).
    """
    return 12.0 / eigenvalue(check_integer("mode", mode, 1, MAX_MODE)) ** 4


def _check_lever(lever) -> Cantilever:
    return check_instance("lever", lever, Cantilever)


def deflection_variance(lever: Cantilever, *, temperature: float = TEMPERATURE.default,
                        mode: int | None = None) -> float:
    """Mean-square Brownian end deflection <z^2> in m^2 of one mode, or of all modes together.

    Parameters
    ----------
    lever : Cantilever
        The lever (its end-load spring constant k).
    temperature : float
        T in K.
    mode : int, optional
        Mode number n (share 12 / (b_n L)^4 of k_B T / k); default: all modes, k_B T / k.

    Returns
    -------
    float
        In m^2.
    """
    lever = _check_lever(lever)
    temperature = TEMPERATURE.check(temperature)
    share = 1.0 if mode is None else mode_share(mode)
    return share * BOLTZMANN * temperature / lever.spring_constant


def mechanical_response(f, *, resonance_frequency: float,
                        quality_factor: float = QUALITY_FACTOR.default) -> np.ndarray:
    """A mode's tip response to a tip force, normalised to 1 at DC (a damped oscillator).

    Parameters
    ----------
    f : array_like
        Frequencies in Hz (>= 0).
    resonance_frequency : float
        f_n in Hz.
    quality_factor : float
        Q (> 0).

    Returns
    -------
    ndarray of complex
        1 / (1 - (f/f_n)^2 + j f / (Q f_n)).

    Raises
    ------
    ValueError
        If a frequency is negative or not finite, or f_n or Q is not finite and positive.
    """
    f = check_array("f", f, "Hz", low=0.0)
    resonance_frequency = check_positive("resonance_frequency", resonance_frequency, "Hz")
    quality_factor = check_positive("quality_factor", quality_factor)
    r = f / resonance_frequency
    with np.errstate(over="ignore"):   # far above f_n, r^2 -> inf and the response -> 0
        return 1.0 / (1.0 - r * r + 1j * r / quality_factor)


def _response_power_integral(r, quality_factor: float):
    """int_0^r |1 / (1 - u^2 + j u / Q)|^2 du (see the module docstring), for Q > 0, r >= 0."""
    # beyond r = 1e150, F(r) equals F(inf) = pi Q / 2 to double precision (and r^2 overflows)
    r = np.minimum(np.asarray(r, dtype=float), 1e150)
    b2 = 4.0 - 1.0 / quality_factor ** 2          # b^2: negative for an overdamped mode
    x = math.sqrt(abs(b2)) * r / (1.0 + r * r)
    safe = np.where(x > 1e-6, x, 0.5)   # a dummy where the series is used
    if b2 >= 0.0:                       # atanh(x) / x, x = b r / (1 + r^2) < 1
        ratio = np.where(x > 1e-6, np.arctanh(safe) / safe, 1.0 + x * x / 3.0)
    else:                               # b = j c: atanh(j y) / (j y) = atan(y) / y
        ratio = np.where(x > 1e-6, np.arctan(safe) / safe, 1.0 - x * x / 3.0)
    return (r / (2.0 * (1.0 + r * r)) * ratio
            + quality_factor / 2.0 * np.arctan2(r, quality_factor * (1.0 - r * r)))


def _white_floor(lever: Cantilever, quality_factor: float, temperature: float,
                 mode: int, resonance_frequency: float | None) -> tuple[float, float]:
    """(S_n0 in m^2/Hz, f_n in Hz) of mode ``mode``, ringing at ``resonance_frequency`` (Hz;
    None: the lever's own f_n in vacuum)."""
    fn = (lever.resonance_frequency(mode) if resonance_frequency is None
          else check_positive("resonance_frequency", resonance_frequency, "Hz"))
    s0 = (mode_share(mode) * 4 * BOLTZMANN * temperature
          / (lever.spring_constant * 2 * math.pi * fn * quality_factor))
    return s0, fn


def thermal_noise_density(lever: Cantilever, f, *, quality_factor: float = QUALITY_FACTOR.default,
                          temperature: float = TEMPERATURE.default, mode: int = 1,
                          resonance_frequency: float | None = None) -> np.ndarray:
    """One-sided power spectral density of mode ``mode``'s Brownian end deflection in m^2/Hz.

    S_n(f) = share_n 4 k_B T / (k omega_n Q) |H_n(f)|^2 (see the module docstring); it
    integrates to share_n k_B T / k.

    Parameters
    ----------
    lever : Cantilever
        The lever (k and f_n).
    f : array_like
        Frequencies in Hz, >= 0.
    quality_factor : float
        Q of the mode, > 0.
    temperature : float
        T in K.
    mode : int
        Mode number n.
    resonance_frequency : float, optional
        Where the mode rings, in Hz: its f_R,n in a fluid
        (:func:`~afmsmiler.hydrodynamics.fluid_mode`); default the lever's f_n in vacuum.

    Returns
    -------
    ndarray
        S_n at each frequency, m^2/Hz.
    """
    lever = _check_lever(lever)
    quality_factor = QUALITY_FACTOR.check(quality_factor)
    temperature = TEMPERATURE.check(temperature)
    s0, fn = _white_floor(lever, quality_factor, temperature, mode, resonance_frequency)
    response = mechanical_response(f, resonance_frequency=fn, quality_factor=quality_factor)
    return s0 * np.abs(response) ** 2


def thermal_deflection_noise(lever: Cantilever, *, quality_factor: float = QUALITY_FACTOR.default,
                             temperature: float = TEMPERATURE.default, bandwidth: float,
                             low_frequency: float | None = None, mode: int = 1,
                             resonance_frequency: float | None = None) -> float:
    """Rms Brownian end deflection of mode ``mode`` in m within a bandwidth.

    Without ``low_frequency``: sqrt(S_n0 B), the white floor of the mode's thermal spectrum well
    below its resonance (what a drive at any frequency competes with, since drive and Brownian
    force pass the same |H_n|). With it: the spectrum S_n0 |H_n(f)|^2 integrated over
    [low_frequency, low_frequency + B] in closed form (see the module docstring), the tip's
    actual rms motion in that band, resonance included.

    Parameters
    ----------
    lever : Cantilever
        The lever (its k and f_n).
    quality_factor : float
        Q of the mode, in (0, 1e5].
    temperature : float
        T in K.
    bandwidth : float
        B in Hz, > 0.
    low_frequency : float, optional
        Lower edge of the band in Hz, >= 0.
    mode : int
        Mode number n (its share of k_B T / k: 0.971 for mode 1).
    resonance_frequency : float, optional
        Where the mode rings, in Hz (its f_R,n in a fluid); default the lever's f_n in vacuum.

    Returns
    -------
    float
        Rms deflection in m.

    Raises
    ------
    TypeError
        If ``lever`` is not a Cantilever.
    ValueError
        If a number is not finite and in its range.
    """
    lever = _check_lever(lever)
    quality_factor = QUALITY_FACTOR.check(quality_factor)
    temperature = TEMPERATURE.check(temperature)
    bandwidth = check_positive("bandwidth", bandwidth, "Hz")
    s0, fn = _white_floor(lever, quality_factor, temperature, mode, resonance_frequency)
    if low_frequency is None:
        return math.sqrt(s0 * bandwidth)
    low_frequency = check_range("low_frequency", low_frequency, 0.0, math.inf, "Hz")
    edges = _response_power_integral([low_frequency / fn, (low_frequency + bandwidth) / fn],
                                     quality_factor)
    return math.sqrt(s0 * fn * max(float(edges[1] - edges[0]), 0.0))
