"""The AD630 balanced demodulator: the signal times a +-1 square wave, then an RC low-pass.

The AD630 (Analog Devices, *AD630 balanced modulator/demodulator* data sheet, rev. F) switches
its gain between +G and -G with a comparator driven by the reference, so its output is the input
multiplied by G sq(t), sq the +-1 square wave of the reference (here a pattern output of the
Analog Discovery 2 at 2 omega). By the square wave's Fourier series, sq(x) = (4/pi) sum_k
sin((2k+1) x) / (2k+1), a component A sin(x + theta) at the reference frequency leaves, after
the low-pass, the DC level::

    V_dc = G (2 / pi) A cos(theta)

and a component at the odd harmonic h of the reference the level G (2 / pi) (A_h / h) cos(theta_h)
(the leak of the 3rd, 5th ... harmonics the student sees with a square reference). With two
AD630s switched by the in-phase and the quadrature squares (the AD2's DIO 0 and DIO 1) the two
levels are X and Y, and A = (pi / (2 G)) sqrt(V_x^2 + V_y^2) (:func:`amplitude_from_levels`).
The low-pass after the AD630 is the same N-stage RC filter as the digital lock-in's
(:func:`afmsmiler.signals.lockin.lowpass`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..parameters import Parameter, read_only
from ..validation import check_array, check_integer, check_positive, check_range
from .lockin import (FILTER_ORDER, HARMONIC, LIMITS, TIME_CONSTANT, lowpass, reference_waveforms,
                     settling_time)

__all__ = ["AD630_GAIN", "PARAMETERS", "AD630Result", "switch", "demodulate",
           "amplitude_from_levels"]

AD630_GAIN = Parameter(name="ad630_gain", unit="", default=1.0, low=0.1, high=10.0,
                       label="AD630 gain G (+-1 or +-2 with its internal resistors)")
PARAMETERS = read_only({p.name: p for p in (AD630_GAIN,)})


def switch(signal, reference, *, gain: float = AD630_GAIN.default) -> np.ndarray:
    """The AD630's output before the low-pass: G x signal x sign of the reference.

    Parameters
    ----------
    signal : array_like
        Input samples (V).
    reference : array_like
        The reference square (values in [-1, 1]; a box-averaged edge sample in between), same
        length.
    gain : float
        G, > 0.

    Returns
    -------
    ndarray
        The switched waveform in V.
    """
    s = check_array("signal", signal, "V", ndim=1)
    r = check_array("reference", reference, low=-1.0, high=1.0, ndim=1)
    if r.shape != s.shape:
        raise ValueError(f"reference must have the signal's {s.size} samples, got {r.size}")
    gain = AD630_GAIN.check(gain)
    return gain * s * r


@dataclass(frozen=True)
class AD630Result:
    """The two AD630 channels (in-phase and quadrature) after their low-pass.

    Parameters
    ----------
    time : ndarray
        t in s.
    switched_x, switched_y : ndarray
        The AD630 outputs before the low-pass, in V.
    level_x, level_y : ndarray
        After the low-pass, in V (what the AD2's scope reads).
    x, y : float
        The settled levels V_x, V_y in V (mean over the whole periods after settling).
    gain : float
        G.
    """

    time: np.ndarray
    switched_x: np.ndarray
    switched_y: np.ndarray
    level_x: np.ndarray
    level_y: np.ndarray
    x: float
    y: float
    gain: float

    @property
    def amplitude(self) -> float:
        """The input component's peak amplitude A in V (see :func:`amplitude_from_levels`)."""
        return amplitude_from_levels(self.x, self.y, gain=self.gain)

    @property
    def phase(self) -> float:
        """Its phase in rad against the in-phase reference, atan2(V_y, V_x)."""
        return math.atan2(self.y, self.x)


#: The largest AD630 output level in V this module reads: 100 V (its supplies are +-15 V).
MAX_LEVEL = 100.0


def amplitude_from_levels(level_x: float, level_y: float, *,
                          gain: float = AD630_GAIN.default) -> float:
    """Peak amplitude A in V from the two settled AD630 levels: (pi / (2 G)) hypot(V_x, V_y).

    Parameters
    ----------
    level_x, level_y : float
        V_x and V_y in V, within +-:data:`MAX_LEVEL` (an AD630's output swings within its
        +-15 V supplies).
    gain : float
        The AD630's G.
    """
    vx = check_range("level_x", level_x, -MAX_LEVEL, MAX_LEVEL, "V")
    vy = check_range("level_y", level_y, -MAX_LEVEL, MAX_LEVEL, "V")
    return math.pi / (2 * AD630_GAIN.check(gain)) * math.hypot(vx, vy)


def demodulate(signal, *, sample_rate: float, frequency: float,
               harmonic: int = int(HARMONIC.default), gain: float = AD630_GAIN.default,
               time_constant: float = TIME_CONSTANT.default,
               order: int = int(FILTER_ORDER.default), phase: float = 0.0) -> AD630Result:
    """Two AD630s switched by the in-phase and quadrature squares at ``harmonic`` x ``frequency``.

    Parameters
    ----------
    signal : array_like
        The input samples in V at t_k = k / f_s.
    sample_rate : float
        f_s in Hz.
    frequency : float
        Drive frequency f in Hz.
    harmonic : int
        n: the squares are at n f.
    gain : float
        The AD630's G.
    time_constant : float
        tau of the low-pass stages in s.
    order : int
        Number of RC stages after each AD630.
    phase : float
        Phase of the in-phase square in rad.

    Returns
    -------
    AD630Result

    Raises
    ------
    ValueError
        If an argument is out of range or the record shorter than the settling time plus one
        reference period.
    """
    s = check_array("signal", signal, "V", ndim=1)
    if not 1 <= s.size <= LIMITS["samples"]:
        raise ValueError(f"signal must have 1 to {LIMITS['samples']} samples, got {s.size}")
    fs = check_positive("sample_rate", sample_rate, "Hz")
    f_ref = check_integer("harmonic", harmonic, int(HARMONIC.low), int(HARMONIC.high)) \
        * check_positive("frequency", frequency, "Hz")
    tau = TIME_CONSTANT.check(time_constant)
    settle = settling_time(tau, order)
    duration, period = s.size / fs, 1.0 / f_ref
    if settle + period > duration:
        raise ValueError(f"signal of {s.size} samples at sample_rate {fs:g} Hz lasts "
                         f"{duration:.3g} s; it must last at least {settle + period:.3g} s: the "
                         f"settling time of time_constant {tau:g} s with order {order}, plus one "
                         f"period of the reference at harmonic x frequency = {f_ref:g} Hz")
    ref_i, ref_q = reference_waveforms(s.size, sample_rate=fs, frequency=f_ref, shape="square",
                                       phase=phase)
    sw_x, sw_y = switch(s, ref_i, gain=gain), switch(s, ref_q, gain=gain)
    lx = lowpass(sw_x, sample_rate=fs, time_constant=tau, order=order)
    ly = lowpass(sw_y, sample_rate=fs, time_constant=tau, order=order)
    start = s.size - int(round(math.floor((duration - settle) / period) * period * fs))
    return AD630Result(time=np.arange(s.size) / fs, switched_x=sw_x, switched_y=sw_y,
                       level_x=lx, level_y=ly, x=float(lx[start:].mean()),
                       y=float(ly[start:].mean()), gain=AD630_GAIN.check(gain))
