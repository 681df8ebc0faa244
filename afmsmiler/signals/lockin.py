"""A digital lock-in amplifier: amplitude and phase of a signal at n times a reference frequency.

Demodulation
------------
A component ``A sin(n w t + theta)`` of the signal, multiplied by the two references
``2 sin(n w t)`` and ``2 cos(n w t)``, gives ``A cos(theta)`` and ``A sin(theta)`` plus terms at
2 n w (and at the sums and differences with the signal's other frequencies). A low-pass removes
those and leaves::

    X = A cos(theta),   Y = A sin(theta),   R = sqrt(X^2 + Y^2) = A,   theta = atan2(Y, X)

so R is the component's peak amplitude and theta its phase against ``sin(n w t)`` (Meade,
*Lock-in amplifiers: principles and applications*, Peter Peregrinus 1983, ch. 1; Stanford
Research Systems, *SR830 DSP lock-in amplifier manual*, ch. 3, which reports rms, ``R / sqrt 2``).

Square references (the analog demodulator's, :mod:`afmsmiler.signals.ad630`)
------------------------------------------------------------------------
A square wave of the reference's period is ``sq(x) = sign(sin x) = (4 / pi) sum_k
sin((2k + 1) x) / (2k + 1)``: multiplying by it demodulates at the fundamental with weight 4 / pi
AND at every odd harmonic h with weight 4 / (pi h). Scaled by pi / 2 (instead of the sine
reference's 2) it reads the fundamental's A as the sine reference does, and a component at the
odd harmonic h of the reference with the weight 1 / h (1/3, 1/5, ...): the harmonic pickup.
Even harmonics are not picked up. The quadrature square sq(x + pi/2) carries
sin(h x + h pi/2) = (-1)^((h-1)/2) cos(h x), so a leak's phase reads as its own for h = 1, 5,
9 ... and mirrored (-theta_h) for h = 3, 7, .... Each sample of the square reference is its
mean over the sample interval (a box average), so an edge between two samples is not moved to
the nearer one; this multiplies harmonic h by sinc(h f_ref / f_s) = 1 - (pi h f_ref / f_s)^2 / 6
+ ...

The low-pass and its noise bandwidth
------------------------------------
``order`` N identical first-order RC stages of time constant tau in cascade (6 dB/octave each),
each discretised exactly for an input held constant over a sample (zero-order hold)::

    y[k] = y[k-1] + a (x[k] - y[k-1]),     a = 1 - exp(-dt / tau)

Its equivalent noise bandwidth, ENBW = int_0^inf |H(f)|^2 df with |H|^2 = (1 + (2 pi f tau)^2)^-N,
is (the integral of (1 + x^2)^-N, Gradshteyn and Ryzhik 3.251.11)::

    ENBW = Gamma(N - 1/2) / (4 sqrt(pi) tau Gamma(N))

1/(4 tau), 1/(8 tau), 3/(32 tau), 5/(64 tau) for N = 1..4, the table of the SR830 manual. A white
input noise of one-sided density S (V^2/Hz) leaves X and Y each with the rms noise
``sqrt(2 S ENBW)`` (the factor 2: peak, not rms, amplitudes). The N stages' step response
reaches within epsilon of its end value at the time t with Q(N, t / tau) = epsilon (the
regularised upper incomplete gamma function: the Erlang distribution), the settling time.

Reading the output
------------------
:func:`lock_in` reports the mean of X(t) and Y(t) over the whole reference periods after the
settling time, as a user reads a settled meter (the residual ripple at 2 n w averages out).
``filter="average"`` replaces the RC stages by the mean over whole periods from t = 0 (a boxcar,
sinc-shaped, that rejects every other harmonic of the fundamental exactly).
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
import scipy.signal
import scipy.special

from ..parameters import Parameter, read_only
from ..validation import (check_array, check_choice, check_finite, check_integer, check_positive,
                          check_range)

__all__ = ["TIME_CONSTANT", "FILTER_ORDER", "HARMONIC", "REFERENCES", "FILTERS", "PARAMETERS",
           "LIMITS", "LockInResult", "Spectrum", "enbw", "settling_time", "lowpass",
           "reference_waveforms", "square_wave", "harmonic_pickup", "lock_in",
           "amplitude_spectrum"]

TIME_CONSTANT = Parameter(name="time_constant", unit="s", display_unit="ms", default=1e-3,
                          low=1e-7, high=10.0, slider_low=1e-5, slider_high=20e-3, log=True,
                          label="lock-in time constant")
FILTER_ORDER = Parameter(name="filter_order", unit="", default=4, low=1, high=8,
                         label="low-pass order (6 dB/octave per stage)")
HARMONIC = Parameter(name="harmonic", unit="", default=2, low=1, high=64,
                     label="demodulated harmonic n of the drive")
#: Reference shapes: a digital sine/cosine pair, or the analog demodulator's square waves.
REFERENCES = ("sine", "square")
#: Output filters: N RC stages, or the mean over whole reference periods.
FILTERS = ("rc", "average")
PARAMETERS = read_only({p.name: p for p in (TIME_CONSTANT, FILTER_ORDER, HARMONIC)})
#: Largest record (samples) a lock-in or spectrum accepts: a few tens of ms on this machine.
LIMITS = read_only(dict(samples=1 << 22, min_samples_per_period=4))
#: Residual of the filter's step response accepted as settled (see :func:`settling_time`).
SETTLED = 1e-4


def enbw(time_constant: float = TIME_CONSTANT.default,
         order: int = int(FILTER_ORDER.default)) -> float:
    """Equivalent noise bandwidth in Hz of ``order`` cascaded RC stages of ``time_constant``.

    Parameters
    ----------
    time_constant : float
        tau of each stage in s, > 0.
    order : int
        Number of stages N, 1 to 8.

    Returns
    -------
    float
        Gamma(N - 1/2) / (4 sqrt(pi) tau Gamma(N)) (see the module docstring).

    Raises
    ------
    ValueError
        If ``time_constant`` is not positive or ``order`` not an integer in range.
    """
    tau = TIME_CONSTANT.check(time_constant)
    n = check_integer("order", order, int(FILTER_ORDER.low), int(FILTER_ORDER.high))
    return math.exp(math.lgamma(n - 0.5) - math.lgamma(n)) / (4 * math.sqrt(math.pi) * tau)


def settling_time(time_constant: float = TIME_CONSTANT.default,
                  order: int = int(FILTER_ORDER.default), residual: float = SETTLED) -> float:
    """Time in s for the step response of the N stages to come within ``residual`` of its end.

    Parameters
    ----------
    time_constant : float
        tau in s, > 0.
    order : int
        N, 1 to 8.
    residual : float
        Fraction of the step still missing, in (0, 1).

    Returns
    -------
    float
        tau x the root of Q(N, x) = residual (about 9.2 tau for N = 1, 16 tau for N = 4 at
        1e-4).
    """
    tau = TIME_CONSTANT.check(time_constant)
    n = check_integer("order", order, int(FILTER_ORDER.low), int(FILTER_ORDER.high))
    residual = check_range("residual", residual, 0.0, 1.0, low_inclusive=False,
                           high_inclusive=False)
    return tau * float(scipy.special.gammainccinv(n, residual))


def lowpass(x, *, sample_rate: float, time_constant: float = TIME_CONSTANT.default,
            order: int = int(FILTER_ORDER.default)) -> np.ndarray:
    """``x`` through ``order`` identical RC stages (exact zero-order-hold discretisation).

    Parameters
    ----------
    x : array_like
        Samples (1-D), the filter starting from rest.
    sample_rate : float
        f_s in Hz, > 0.
    time_constant : float
        tau of each stage in s, > 0.
    order : int
        Number of stages, 1 to 8.

    Returns
    -------
    ndarray
        The filtered samples, same length.
    """
    x = check_array("x", x, ndim=1)
    fs = check_positive("sample_rate", sample_rate, "Hz")
    tau = TIME_CONSTANT.check(time_constant)
    n = check_integer("order", order, int(FILTER_ORDER.low), int(FILTER_ORDER.high))
    return _stages(x, fs, tau, n)


def _stages(x: np.ndarray, fs: float, tau: float, n: int) -> np.ndarray:
    """:func:`lowpass` of checked arguments along the last axis of ``x`` (rows filtered alike).

    The ``n`` stages are ``n`` first-order sections of one ``scipy.signal.sosfilt`` pass: the same
    recursion y[k] = y[k-1] + a (x[k] - y[k-1]) per stage as a cascade of ``lfilter`` calls
    (equal to it, tested), in one loop over the samples instead of ``n``, for X and Y at once.
    """
    if x.shape[-1] == 0:  # nothing to filter (sosfilt refuses an empty axis)
        return np.array(x, dtype=float)
    a = -math.expm1(-1.0 / (fs * tau))
    sos = np.tile([a, 0.0, 0.0, 1.0, a - 1.0, 0.0], (n, 1))
    return scipy.signal.sosfilt(sos, x, axis=-1)


def square_wave(cycles, step: float = 0.0) -> np.ndarray:
    """sign(sin(2 pi u)) at ``cycles`` u, each value its mean over [u - step/2, u + step/2].

    Parameters
    ----------
    cycles : array_like
        Phase in cycles (turns) u.
    step : float
        Width of the averaging window in cycles, in [0, 0.5): the phase advance per sample
        (0: the ideal square, +1 on [0, 1/2), -1 on [1/2, 1)).

    Returns
    -------
    ndarray
        Values in [-1, 1]; 0 on an edge centred in the window.
    """
    u = check_array("cycles", cycles)
    step = check_range("step", step, 0.0, 0.5, high_inclusive=False)
    if step == 0.0:
        return np.where(np.mod(u, 1.0) < 0.5, 1.0, -1.0)

    def ramp(v):   # the integral of the square: a triangle wave, 0 at v = 0, 1/2 at v = 1/2
        return 0.5 - np.abs(np.mod(v, 1.0) - 0.5)
    # the difference of two ramps can round a hair beyond +-1: the mean of a +-1 square cannot
    return np.clip((ramp(u + step / 2) - ramp(u - step / 2)) / step, -1.0, 1.0)


def reference_waveforms(n_samples: int, *, sample_rate: float, frequency: float,
                        shape: str = "sine", phase: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """The in-phase and quadrature references at ``frequency``, unscaled (amplitude 1).

    Parameters
    ----------
    n_samples : int
        Record length.
    sample_rate : float
        f_s in Hz.
    frequency : float
        Reference frequency f_ref in Hz (already n times the drive's), below f_s / 4.
    shape : {"sine", "square"}
        ``sin`` and ``cos``, or the square waves ``sq(x)`` and ``sq(x + pi/2)``.
    phase : float
        Reference phase phi in rad: the in-phase reference is ``sin(2 pi f_ref t + phi)``.

    Returns
    -------
    tuple of ndarray
        (in-phase, quadrature), sampled at t = k / f_s.
    """
    n = check_integer("n_samples", n_samples, 1, LIMITS["samples"])
    fs = check_positive("sample_rate", sample_rate, "Hz")
    f = check_positive("frequency", frequency, "Hz")
    shape = check_choice("shape", shape, REFERENCES)
    phase = check_finite("phase", phase, "rad")
    step = f / fs
    if step * LIMITS["min_samples_per_period"] > 1:
        raise ValueError(f"frequency must be at most sample_rate / "
                         f"{LIMITS['min_samples_per_period']} = "
                         f"{fs / LIMITS['min_samples_per_period']:g} Hz, got {f:g} Hz")
    cycles = np.arange(n) * step + phase / (2 * math.pi)
    if shape == "sine":
        arg = 2 * math.pi * cycles
        return np.sin(arg), np.cos(arg)
    return square_wave(cycles, step), square_wave(cycles + 0.25, step)


#: Longest record whose references and window are remembered (8 MB an array, 4 of each).
_REMEMBERED = 1 << 20


@functools.lru_cache(maxsize=4)
def _references(n, fs, f, shape, phase):
    """:func:`reference_waveforms` as rows of one (2, n) array, remembered (read-only): a lock-in
    of the same record length, rate and reference (every move of the lock-in panel but its
    frequency's) reuses them, and mixes both with one product."""
    out = np.stack(reference_waveforms(n, sample_rate=fs, frequency=f, shape=shape, phase=phase))
    out.setflags(write=False)
    return out


@functools.lru_cache(maxsize=4)
def _hann(n: int) -> np.ndarray:
    """The periodic Hann window of ``n`` samples (read-only, remembered)."""
    window = np.hanning(n + 1)[:-1]
    window.setflags(write=False)
    return window


def harmonic_pickup(harmonic: int, shape: str = "square") -> float:
    """Weight with which a reference of ``shape`` reads a component at ``harmonic`` x f_ref.

    Parameters
    ----------
    harmonic : int
        h >= 1, the component's frequency over the reference's.
    shape : {"sine", "square"}
        The reference.

    Returns
    -------
    float
        Sine: 1 for h = 1, else 0. Square (scaled to read the fundamental as 1): the ratio of
        its Fourier coefficients, 1/h for odd h, 0 for even h.
    """
    h = check_integer("harmonic", harmonic, 1, 10 ** 6)
    shape = check_choice("shape", shape, REFERENCES)
    if shape == "sine":
        return 1.0 if h == 1 else 0.0
    return 1.0 / h if h % 2 else 0.0


@dataclass(frozen=True)
class LockInResult:
    """The lock-in's reading and its traces.

    Parameters
    ----------
    x, y : float
        The settled outputs X = A cos(theta) and Y = A sin(theta), in the signal's unit.
    time : ndarray
        t of the traces in s.
    x_trace, y_trace : ndarray
        X(t) and Y(t) after the low-pass (for ``filter="average"``: the running mean).
    reference_frequency : float
        n f in Hz.
    shape : str
        ``"sine"`` or ``"square"``.
    filter : str
        ``"rc"`` or ``"average"``.
    time_constant : float
        tau in s (for the RC filter).
    order : int
        Number of RC stages.
    enbw : float
        Equivalent noise bandwidth in Hz of the output filter.
    settle_time : float
        Time in s after which the reading was averaged.
    """

    x: float
    y: float
    time: np.ndarray
    x_trace: np.ndarray
    y_trace: np.ndarray
    reference_frequency: float
    shape: str
    filter: str
    time_constant: float
    order: int
    enbw: float
    settle_time: float

    @property
    def amplitude(self) -> float:
        """R = sqrt(X^2 + Y^2), the peak amplitude, in the signal's unit."""
        return math.hypot(self.x, self.y)

    @property
    def phase(self) -> float:
        """theta = atan2(Y, X) in rad, against the in-phase reference."""
        return math.atan2(self.y, self.x)

    def noise(self, density: float) -> float:
        """Rms noise of X (and of Y) for a white input noise of one-sided ``density``.

        Parameters
        ----------
        density : float
            S in (signal unit)^2/Hz.

        Returns
        -------
        float
            sqrt(2 S ENBW) for the sine reference; for the square reference its odd harmonics
            add their noise too: sqrt(2 S ENBW) x (pi / (2 sqrt 2)) (the square's power is 1, not
            1/2 as the sine's, and it is scaled by pi / 2 instead of 2).
        """
        s = check_range("density", density, 0.0, math.inf)
        factor = 1.0 if self.shape == "sine" else math.pi / (2 * math.sqrt(2))
        return math.sqrt(2 * self.enbw) * math.sqrt(s) * factor  # no overflow of 2 S


def lock_in(signal, *, sample_rate: float, frequency: float,
            harmonic: int = int(HARMONIC.default), time_constant: float = TIME_CONSTANT.default,
            order: int = int(FILTER_ORDER.default), shape: str = "sine", phase: float = 0.0,
            filter: str = "rc") -> LockInResult:
    """Demodulate ``signal`` at ``harmonic`` x ``frequency``: amplitude and phase.

    Parameters
    ----------
    signal : array_like
        Samples s(t_k), t_k = k / f_s (1-D, at most ``LIMITS["samples"]``).
    sample_rate : float
        f_s in Hz.
    frequency : float
        The drive (fundamental) frequency f in Hz; the reference is at n f.
    harmonic : int
        n, 1 to 64 (2 for the electrothermal drive's 2 omega).
    time_constant : float
        tau of the RC stages in s.
    order : int
        Number of RC stages, 1 to 8.
    shape : {"sine", "square"}
        Digital sine/cosine references, or square waves (an analog switching demodulator).
    phase : float
        Reference phase in rad (0: the in-phase reference is sin(2 pi n f t)).
    filter : {"rc", "average"}
        The output filter (see the module docstring).

    Returns
    -------
    LockInResult

    Raises
    ------
    ValueError
        If an argument is out of range, or the record is shorter than the filter's settling time
        plus one reference period (the message names the time needed).
    """
    s = check_array("signal", signal, ndim=1)
    if not 1 <= s.size <= LIMITS["samples"]:
        raise ValueError(f"signal must have 1 to {LIMITS['samples']} samples, got {s.size}")
    fs = check_positive("sample_rate", sample_rate, "Hz")
    f = check_positive("frequency", frequency, "Hz")
    n = check_integer("harmonic", harmonic, int(HARMONIC.low), int(HARMONIC.high))
    tau = TIME_CONSTANT.check(time_constant)
    order = check_integer("order", order, int(FILTER_ORDER.low), int(FILTER_ORDER.high))
    shape = check_choice("shape", shape, REFERENCES)
    filter = check_choice("filter", filter, FILTERS)
    phase = check_finite("phase", phase, "rad")
    f_ref = n * f
    if s.size <= _REMEMBERED:
        refs = _references(s.size, fs, f_ref, shape, phase)
    else:
        refs = np.stack(reference_waveforms(s.size, sample_rate=fs, frequency=f_ref,
                                            shape=shape, phase=phase))
    scale = 2.0 if shape == "sine" else math.pi / 2
    mixed = refs * (scale * s)  # rows: in-phase, quadrature
    mixed_i, mixed_q = mixed
    t = np.arange(s.size) / fs
    duration = s.size / fs
    period = 1.0 / f_ref
    if filter == "rc":
        settle = settling_time(tau, order)
        if settle + period > duration:
            raise ValueError(f"signal of {s.size} samples at sample_rate {fs:g} Hz lasts "
                             f"{duration:.3g} s; it must last at least {settle + period:.3g} s: "
                             f"the settling time of time_constant {tau:g} s with order {order}, "
                             f"plus one period of the reference at harmonic x frequency = "
                             f"{f_ref:g} Hz")
        x_trace, y_trace = _stages(mixed, fs, tau, order)
        whole = math.floor((duration - settle) / period) * period
        start = s.size - int(round(whole * fs))
        bandwidth = enbw(tau, order)
    else:
        whole = math.floor(duration / period) * period
        if whole <= 0:
            raise ValueError(f"signal of {s.size} samples at sample_rate {fs:g} Hz lasts "
                             f"{duration:.3g} s; filter 'average' needs one period of the "
                             f"reference at harmonic x frequency = {f_ref:g} Hz, {period:.3g} s")
        count = np.arange(1, s.size + 1)
        x_trace, y_trace = np.cumsum(mixed_i) / count, np.cumsum(mixed_q) / count
        settle, start = 0.0, 0
        mixed_i = mixed_i[:int(round(whole * fs))]
        mixed_q = mixed_q[:int(round(whole * fs))]
        bandwidth = 1.0 / (2.0 * whole)      # a boxcar of length T: ENBW = 1 / (2 T)
    if filter == "rc":
        x, y = float(np.mean(x_trace[start:])), float(np.mean(y_trace[start:]))
    else:
        x, y = float(np.mean(mixed_i)), float(np.mean(mixed_q))
    return LockInResult(x=x, y=y, time=t, x_trace=x_trace, y_trace=y_trace,
                        reference_frequency=f_ref, shape=shape, filter=filter, time_constant=tau,
                        order=order, enbw=bandwidth, settle_time=settle)


@dataclass(frozen=True)
class Spectrum:
    """A one-sided amplitude spectrum.

    Parameters
    ----------
    frequency : ndarray
        Bin frequencies in Hz.
    amplitude : ndarray
        Peak amplitude of a sine centred in each bin, in the signal's unit (Hann window,
        corrected for its coherent gain 1/2).
    """

    frequency: np.ndarray
    amplitude: np.ndarray


def amplitude_spectrum(signal, *, sample_rate: float) -> Spectrum:
    """One-sided amplitude spectrum of ``signal`` through a Hann window.

    Parameters
    ----------
    signal : array_like
        Samples (1-D, 2 to ``LIMITS["samples"]``).
    sample_rate : float
        f_s in Hz.

    Returns
    -------
    Spectrum
        A sine of peak amplitude A centred on a bin reads A there.
    """
    s = check_array("signal", signal, ndim=1)
    if not 2 <= s.size <= LIMITS["samples"]:
        raise ValueError(f"signal must have 2 to {LIMITS['samples']} samples, got {s.size}")
    fs = check_positive("sample_rate", sample_rate, "Hz")
    # periodic Hann: coherent gain exactly 1/2
    window = _hann(s.size) if s.size <= _REMEMBERED else np.hanning(s.size + 1)[:-1]
    spectrum = np.fft.rfft((s - s.mean()) * window)
    amplitude = 2.0 * np.abs(spectrum) / (s.size * 0.5)
    amplitude[0] /= 2.0
    return Spectrum(np.fft.rfftfreq(s.size, 1.0 / fs), amplitude)
