"""Signals of the educational AFM (module (h), part 2): the 2-omega electrothermal drive chain,
a digital lock-in and the AD630 square-wave demodulator.

:mod:`.chain` simulates the active probe's chain (heater power, thermal low-pass, lever, bridge,
noise); :mod:`.lockin` recovers amplitude and phase at n omega with sine or square references;
:mod:`.ad630` models the analog demodulator the Analog Discovery 2 drives.
"""
from .ad630 import AD630Result, amplitude_from_levels, demodulate
from .chain import ActiveProbe, ChainRun, power_harmonics, simulate
from .lockin import (LockInResult, Spectrum, amplitude_spectrum, enbw, harmonic_pickup, lock_in,
                     lowpass, settling_time)

__all__ = ["ActiveProbe", "ChainRun", "simulate", "power_harmonics", "LockInResult", "Spectrum",
           "lock_in", "enbw", "settling_time", "lowpass", "harmonic_pickup",
           "amplitude_spectrum", "AD630Result", "demodulate", "amplitude_from_levels"]
