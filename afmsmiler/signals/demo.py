"""One run of the lock-in demonstration: the chain simulated, demodulated and its spectrum taken.

:func:`lock_in_demo` is what the lock-in panel (:mod:`afmsmiler.ui.lockin`) computes once per user
action: the educational AFM's chain (:func:`afmsmiler.signals.chain.simulate`) for a record long
enough for the chosen filter to settle (rounded up to a count of periods that makes a fast
FFT), its demodulation at 2 omega with the chosen reference
(:func:`afmsmiler.signals.lockin.lock_in`), the output's spectrum, the closed-form truth and what
the reference's harmonics pick up (:func:`afmsmiler.signals.lockin.harmonic_pickup`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.fft

from ..parameters import read_only
from ..validation import check_choice, check_integer, check_range
from .chain import (AC_VOLTAGE, AMPLIFIER_GAIN, AMPLIFIER_NOISE, HALF_RESONANCE_RATIO,
                    INTERFERENCE, ActiveProbe, ChainRun, simulate)
from .lockin import (FILTER_ORDER, LIMITS, REFERENCES, TIME_CONSTANT, LockInResult, Spectrum,
                     amplitude_spectrum, harmonic_pickup, lock_in, settling_time)

__all__ = ["LockInDemo", "lock_in_demo", "max_ac_voltage", "DEFAULTS"]

#: Defaults of the demonstration, in one place: the spectrum up to ``max_harmonic`` x f,
#: ``extra_periods`` reference periods read after the filter settles, ``harmonics`` the
#: reference harmonics whose pickup is listed.
DEFAULTS = read_only(dict(max_harmonic=8, extra_periods=200, harmonics=7,
                          samples_per_period=128))


@dataclass(frozen=True)
class LockInDemo:
    """A demonstration run (SI units).

    Parameters
    ----------
    run : ChainRun
        The simulated chain.
    reading : LockInResult
        The lock-in's reading at 2 omega.
    spectrum : Spectrum
        The output's amplitude spectrum up to ``DEFAULTS["max_harmonic"]`` x f.
    pickup : ndarray
        The reference's weight on its harmonics 1..``DEFAULTS["harmonics"]`` (1, 0, 1/3, ... for
        a square; 1, 0, 0, ... for a sine).
    """

    run: ChainRun
    reading: LockInResult
    spectrum: Spectrum
    pickup: np.ndarray

    @property
    def truth(self) -> complex:
        """The closed-form 2-omega phasor of the output, V."""
        return self.run.second

    @property
    def deviation(self) -> complex:
        """The recovered phasor minus the true one, V (X - X_true + j (Y - Y_true)).

        What an interference adds to the reading: a square reference's third harmonic picks up
        a tone at three times the reference with weight 1/3, whatever its phase, so it shows in
        the amplitude, the phase or both; the amplitude error alone can hide it.
        """
        return complex(self.reading.x, self.reading.y) - self.truth

    @property
    def relative_error(self) -> float:
        """|recovered - true phasor| / |true phasor|: the whole error, amplitude and phase
        (NaN without a drive: there is no true phasor to compare with)."""
        return abs(self.deviation) / abs(self.truth) if self.truth != 0 else math.nan

    @property
    def amplitude_error(self) -> float:
        """Recovered over true amplitude, minus 1 (blind to an error in phase: see
        :attr:`relative_error`); NaN without a drive."""
        return self.reading.amplitude / abs(self.truth) - 1.0 if self.truth != 0 else math.nan

    @property
    def phase_error(self) -> float:
        """Recovered minus true phase in rad, wrapped to (-pi, pi]."""
        d = self.reading.phase - float(np.angle(self.truth))
        return math.atan2(math.sin(d), math.cos(d))


def max_ac_voltage(*, margin: float = 0.8, **lever) -> float:
    """The largest drive V_ac whose deflection stays inside the sensor's range at any drive ratio.

    With no DC offset the heater power is ``V_ac^2 / (2 R) (1 - cos 2wt)``: a steady part and a
    2w part, so the driven deflection never exceeds ``V_ac^2 / (2 R) (|H(0)| + |H(2f)|)`` with
    ``H`` the deflection per watt (:meth:`ActiveProbe.deflection_per_power`). Its worst case over
    the drive ratios of :data:`HALF_RESONANCE_RATIO`'s slider (``2f`` through ``f1``, where
    ``|H|`` peaks) is held to ``margin`` of the sensor's deflection range, leaving room for the
    lever's Brownian motion; a drive above it is refused by module (b)'s bridge.

    Parameters
    ----------
    margin : float
        Share of the deflection range the drive may use, in (0, 1].
    **lever
        The shared lever parameters of :meth:`ActiveProbe.build`, and its ``fluid`` (the medium:
        the peak, and so the largest drive, follows the medium's Q).

    Returns
    -------
    float
        V_ac in V, at most :data:`AC_VOLTAGE`'s upper bound.
    """
    margin = check_range("margin", margin, 0.0, 1.0, low_inclusive=False)
    probe = ActiveProbe.build(**lever)
    f1 = probe.resonance_frequency
    ratios = np.linspace(HALF_RESONANCE_RATIO.slider_low, HALF_RESONANCE_RATIO.slider_high, 801)
    h = np.abs(probe.deflection_per_power(np.append(ratios * f1, f1)))
    h0 = abs(probe.deflection_per_power(np.array([0.0]))[0])
    reach = probe.sensor.input_quantity("sensing").high
    volts = math.sqrt(margin * reach * 2 * probe.actuator.resistance / (h0 + float(h.max())))
    return min(volts, AC_VOLTAGE.high)


def _fast_record(record: float, f: float) -> float:
    """``record`` (s) rounded up to a whole number of drive periods (``f`` in Hz) whose count has
    no prime factor above 5.

    The samples per period are a power of two, so the record's length is then a fast length of
    the spectrum's FFT (``scipy.fft.next_fast_len``): 750 periods of 128 samples take 1.4 ms
    where the 749 that just settle (95,872 = 2^7 x 7 x 107 samples) take 3.0 ms. The record
    grows by at most a few per cent: the filter is as settled as before, or more.
    """
    periods = max(1, math.ceil(record * f - 1e-9))
    return scipy.fft.next_fast_len(periods, real=True) / f


def lock_in_demo(*, ac_voltage: float = AC_VOLTAGE.default,
                 half_resonance_ratio: float = HALF_RESONANCE_RATIO.default,
                 amplifier_noise: float = AMPLIFIER_NOISE.default,
                 time_constant: float = TIME_CONSTANT.default,
                 order: int = int(FILTER_ORDER.default), shape: str = "sine",
                 interference: float = INTERFERENCE.default,
                 amplifier_gain: float = AMPLIFIER_GAIN.default, seed: int = 0,
                 fluid: str | None = None) -> LockInDemo:
    """Simulate the chain, demodulate at 2 omega, take the spectrum (one model run).

    Parameters
    ----------
    ac_voltage : float
        Heater drive amplitude V_ac in V.
    half_resonance_ratio : float
        Drive frequency over f1 / 2.
    amplifier_noise : float
        Amplifier input noise density e_n^2 in V^2/Hz.
    time_constant : float
        Lock-in time constant in s.
    order : int
        Lock-in filter order (RC stages).
    shape : {"sine", "square"}
        Reference shape.
    interference : float
        Tone at 3 x 2 omega at the amplifier input, V peak.
    amplifier_gain : float
        Amplifier gain.
    seed : int
        Noise seed.
    fluid : str, optional
        The lever's medium, ``"air"`` or ``"water"`` (its f1 and Q there, Sader 1998); default
        None: in vacuum with the typed Q (:meth:`ActiveProbe.build`).

    Returns
    -------
    LockInDemo
    """
    shape = check_choice("shape", shape, REFERENCES)
    order = check_integer("order", order, int(FILTER_ORDER.low), int(FILTER_ORDER.high))
    tau = TIME_CONSTANT.check(time_constant)
    probe = ActiveProbe.build(ac_voltage=AC_VOLTAGE.check(ac_voltage), fluid=fluid)
    f = HALF_RESONANCE_RATIO.check(half_resonance_ratio) * probe.resonance_frequency / 2
    record = _fast_record(settling_time(tau, order) + DEFAULTS["extra_periods"] / (2 * f), f)
    if round(record * f) * DEFAULTS["samples_per_period"] > LIMITS["samples"]:
        longest = LIMITS["samples"] / (DEFAULTS["samples_per_period"] * f)
        raise ValueError(f"time_constant {tau:g} s with order {order} needs a record of "
                         f"{record:.3g} s; at most {longest:.3g} s ({LIMITS['samples']} samples) "
                         f"can be simulated: choose a shorter time constant")
    run = simulate(probe, half_resonance_ratio=half_resonance_ratio,
                   amplifier_noise=amplifier_noise, amplifier_gain=amplifier_gain,
                   interference=interference, samples_per_period=DEFAULTS["samples_per_period"],
                   record_duration=record, seed=seed)
    reading = lock_in(run.output, sample_rate=run.sample_rate, frequency=run.drive_frequency,
                      harmonic=2, time_constant=tau, order=order, shape=shape)
    full = amplitude_spectrum(run.output, sample_rate=run.sample_rate)
    keep = full.frequency <= DEFAULTS["max_harmonic"] * run.drive_frequency
    pickup = np.array([harmonic_pickup(h, shape) for h in range(1, DEFAULTS["harmonics"] + 1)])
    return LockInDemo(run=run, reading=reading,
                      spectrum=Spectrum(full.frequency[keep], full.amplitude[keep]),
                      pickup=pickup)
