"""The Analog Discovery 2 as the educational AFM's drive and demodulator, through pydwf.

The paper's upgrade of the low-cost educational AFM (Xia et al., Mechatronics 76, 102550 (2021))
replaces the function generator and lock-in with a Digilent Analog Discovery 2 (AD2) and an AD630:
WaveGen 1 makes the heater's sine at w, the pattern generator's DIO 0 and DIO 1 make the two
square references of the AD630 demodulators, and the scope reads the AD630's low-passed outputs.
Because the heater moves the lever at 2 w (P = V^2 / R), both squares run at 2 w: DIO 0 in phase
with sin(2 w t), DIO 1 a quarter of its period later (quadrature), so the two AD630 levels are X
and Y (:mod:`afmsmiler.signals.ad630`). The paper names the two pattern channels as the AD630's
references; that they are the in-phase and quadrature squares at 2 w is our reading of the
2-omega scheme (``AD2Config.reference_phases`` changes it).

Keeping them in phase: the pattern generator and the scope are triggered by WaveGen 1's start
(``DwfTriggerSource.AnalogOut1``), so all three start together; the squares' frequency is what the
pattern clock can make (100 MHz / (divider x counts per period)), and the sine is set to
exactly that over ``harmonic``, so they never drift apart. A fixed delay between the instruments'
starts (a few clock counts) or in the AD630 boards shifts every reading's phase by the same angle:
calibrate it once with ``reference_phases`` (both shifted together).

The code takes a ``DwfLibrary``-like object (dependency injection): pydwf's own, or
:class:`SimulatedDwfLibrary`, which records every call and answers the scope with the AD630
output of the simulated chain (:mod:`afmsmiler.signals.chain`). Without Digilent's WaveForms
runtime, ``pydwf.DwfLibrary()`` raises ``PyDwfError``; :func:`open_library` turns that (and a
missing pydwf) into :class:`AD2Unavailable` naming the reason.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from ..validation import (check_finite, check_instance, check_integer, check_positive,
                          check_range)
from .errors import HardwareError

__all__ = ["AD2Unavailable", "AD2Config", "PatternTiming", "Acquisition", "pattern_timing",
           "open_library", "library_or_simulation", "AnalogDiscovery2", "SimulatedDwfLibrary"]

#: The fastest pattern clock accepted (Hz): the AD2's is 100 MHz; 1 THz bounds any generator.
MAX_CLOCK = 1e12
#: The largest device (and configuration) index accepted: WaveForms enumerates a few devices.
MAX_DEVICES = 1024


class AD2Unavailable(HardwareError):
    """No Analog Discovery 2 can be used: pydwf or the WaveForms runtime is missing, or no device.

    Parameters
    ----------
    reason : str
        What is missing, for a visible skip or a notebook message.
    """

    def __init__(self, reason: str):
        super().__init__(f"Analog Discovery 2 unavailable: {reason}")
        self.reason = reason


def _pydwf():
    try:
        import pydwf
    except ImportError as exc:     # the hardware extra is not installed
        raise AD2Unavailable(f"pydwf is not installed ({exc}); pip install pydwf") from exc
    return pydwf


def open_library(factory=None):
    """A ``DwfLibrary``: pydwf's, or whatever ``factory()`` builds.

    Parameters
    ----------
    factory : callable, optional
        Builds the library (default: ``pydwf.DwfLibrary``).

    Returns
    -------
    object
        The library.

    Raises
    ------
    AD2Unavailable
        If pydwf is missing or the WaveForms runtime (libdwf) cannot be loaded, with the reason.
    """
    if factory is not None and not callable(factory):
        raise TypeError(f"factory must be callable (it builds the library) or None, got "
                        f"{type(factory).__name__} {factory!r}"[:160])
    pydwf = _pydwf()
    factory = pydwf.DwfLibrary if factory is None else factory
    try:
        return factory()
    except pydwf.PyDwfError as exc:
        raise AD2Unavailable(f"Digilent's WaveForms runtime (libdwf) could not be loaded ({exc}); "
                             f"install WaveForms from digilent.com to use a real AD2") from exc


def _check_library(name: str, dwf):
    """``dwf`` if it is a DwfLibrary-like object (has ``deviceControl.open``), else TypeError."""
    if not callable(getattr(getattr(dwf, "deviceControl", None), "open", None)):
        raise TypeError(f"{name} must be a DwfLibrary (pydwf's or SimulatedDwfLibrary: with "
                        f"deviceControl.open), got {type(dwf).__name__} {dwf!r}"[:200])
    return dwf


def library_or_simulation(factory=None) -> tuple[object, str | None]:
    """The real AD2's library if Digilent's runtime loads, else the simulated one, and why.

    Parameters
    ----------
    factory : callable, optional
        Builds the real library (default: ``pydwf.DwfLibrary``), as in :func:`open_library`.

    Returns
    -------
    (object, str or None)
        The library (pydwf's, or a :class:`SimulatedDwfLibrary`) and None for the real one, or
        the reason the real one could not be opened.
    """
    try:
        return open_library(factory), None
    except AD2Unavailable as exc:
        return SimulatedDwfLibrary(), exc.reason


@dataclass(frozen=True)
class AD2Config:
    """How the AD2 drives the heater and reads the demodulators (SI units).

    Parameters
    ----------
    drive_frequency : float
        The heater sine's frequency f in Hz, the lever's f1 / 2 (adjusted to what the pattern
        clock makes, see :func:`pattern_timing`).
    ac_voltage : float
        The sine's amplitude V_ac in V (WaveGen range: 0 to 5 V).
    dc_voltage : float
        Its offset V_dc in V (0: the pure 2-w drive).
    harmonic : int
        The references run at ``harmonic`` x f (2 for the 2-w drive).
    reference_pins : tuple of int
        The pattern generator's pins of the in-phase and quadrature squares (DIO 0, DIO 1).
    reference_phases : tuple of float
        Their phases in rad against sin(n w t) (0 and pi/2: in phase and quadrature).
    scope_channels : tuple of int
        Scope channels reading the X and Y AD630 outputs (0, 1 = channels 1 and 2).
    scope_range : float
        Scope input range in V (peak to peak).
    sample_rate : float
        Scope sample rate in Hz (the AD630 levels are slow: 100 kHz is plenty).
    samples : int
        Scope record length (the AD2 keeps 8192 samples per channel).
    timeout : float
        Longest wait for the scope's record, in s beyond its own length.
    """

    drive_frequency: float = 40e3
    ac_voltage: float = 0.5
    dc_voltage: float = 0.0
    harmonic: int = 2
    reference_pins: tuple = (0, 1)
    reference_phases: tuple = (0.0, math.pi / 2)
    scope_channels: tuple = (0, 1)
    scope_range: float = 5.0
    sample_rate: float = 100e3
    samples: int = 8192
    timeout: float = 2.0

    def __post_init__(self):
        check_range("drive_frequency", self.drive_frequency, 1.0, 10e6, "Hz")
        check_range("ac_voltage", self.ac_voltage, 0.0, 5.0, "V")
        check_range("dc_voltage", self.dc_voltage, -5.0, 5.0, "V")
        check_integer("harmonic", self.harmonic, 1, 16)
        for name in ("reference_pins", "reference_phases", "scope_channels"):
            value = getattr(self, name)
            if not isinstance(value, tuple) or len(value) != 2:
                raise ValueError(f"{name} must be a pair, got {value!r}")
        for pin in self.reference_pins:
            check_integer("reference_pins", pin, 0, 15)
        for phase in self.reference_phases:
            check_finite("reference_phases", phase, "rad")
        for channel in self.scope_channels:
            check_integer("scope_channels", channel, 0, 1)
        check_range("scope_range", self.scope_range, 0.01, 50.0, "V")
        check_range("sample_rate", self.sample_rate, 1.0, 100e6, "Hz")
        check_integer("samples", self.samples, 16, 8192)
        check_range("timeout", self.timeout, 0.0, 60.0, "s")


@dataclass(frozen=True)
class PatternTiming:
    """One pattern pin's square wave in the pattern generator's terms.

    Parameters
    ----------
    divider : int
        Clock divider.
    low_count, high_count : int
        Counts low and high; they differ by at most one (an odd period), so the frequency steps by
        one count of the period, not two.
    start_high : bool
        The level at the trigger.
    start_count : int
        Counts left in that level at the trigger.
    frequency : float
        The square's frequency in Hz: clock / (divider (low_count + high_count)).
    phase : float
        The phase in rad it realises (the nearest count to the one asked).
    """

    divider: int
    low_count: int
    high_count: int
    start_high: bool
    start_count: int
    frequency: float
    phase: float

    @property
    def period(self) -> int:
        """Counts per period."""
        return self.low_count + self.high_count


def pattern_timing(clock: float, frequency: float, phase: float = 0.0, *,
                   max_count: int = 32768, max_divider: int = 2 ** 30) -> PatternTiming:
    """Divider and counts for a square sq(2 pi f t + phase) (high first half) from ``clock``.

    The period is the whole number of (divided) clock counts nearest to clock / f, split into a
    high and a low half that differ by at most one count; the smallest divider keeps each half
    within ``max_count`` (the finest frequency step: one count of the period, 0.08 % at 81 kHz
    from 100 MHz). The phase is set by the counts already spent at the trigger, the nearest one
    to ``phase`` (within half a count: 0.15 degrees at 81 kHz).

    Parameters
    ----------
    clock : float
        The pattern generator's clock in Hz (100 MHz on the AD2).
    frequency : float
        The square's frequency in Hz.
    phase : float
        Its phase in rad (0: rising edge at the trigger).
    max_count : int
        The largest count the counters hold.
    max_divider : int
        The largest divider.

    Returns
    -------
    PatternTiming

    Raises
    ------
    ValueError
        If the frequency cannot be made (above clock / 4 or below the slowest square).
    """
    clock = check_range("clock", clock, 0.0, MAX_CLOCK, "Hz", low_inclusive=False)
    frequency = check_positive("frequency", frequency, "Hz")
    phase = check_finite("phase", phase, "rad")
    max_count = check_integer("max_count", max_count, 4, 2 ** 32)
    max_divider = check_integer("max_divider", max_divider, 1, 2 ** 32)
    if frequency > clock / 4:
        raise ValueError(f"frequency must be at most clock / 4 = {clock / 4:g} Hz, "
                         f"got {frequency:g} Hz")
    divider = max(1, math.ceil(clock / (2 * frequency * max_count)))
    if divider > max_divider:
        raise ValueError(f"frequency {frequency:g} Hz is below the slowest square the pattern "
                         f"generator makes, {clock / (2 * max_divider * max_count):g} Hz "
                         f"(clock / (2 max_divider max_count))")
    period = max(4, round(clock / (divider * frequency)))
    high = period - period // 2
    pos = round((phase / (2 * math.pi)) % 1.0 * period) % period   # counts into the period
    start_high = pos < high
    left = (high - pos) if start_high else (period - pos)
    return PatternTiming(divider=divider, low_count=period // 2, high_count=high,
                         start_high=start_high, start_count=int(left),
                         frequency=clock / (divider * period), phase=2 * math.pi * pos / period)


@dataclass(frozen=True)
class Acquisition:
    """The scope's record of the two AD630 outputs and what it means.

    Parameters
    ----------
    time : ndarray
        t in s from the trigger (the drive's start).
    level_x, level_y : ndarray
        The X and Y AD630 outputs in V.
    drive_frequency : float
        The sine's frequency as set, Hz.
    reference_frequency : float
        The squares' frequency as made by the pattern clock, Hz.
    """

    time: np.ndarray
    level_x: np.ndarray
    level_y: np.ndarray
    drive_frequency: float
    reference_frequency: float

    def settled(self, fraction: float = 0.5) -> tuple[float, float]:
        """Mean X and Y levels in V over the last ``fraction`` of the record.

        Parameters
        ----------
        fraction : float
            In (0, 1].
        """
        fraction = check_range("fraction", fraction, 0.0, 1.0, low_inclusive=False)
        k = int(len(self.time) * (1 - fraction))
        return float(self.level_x[k:].mean()), float(self.level_y[k:].mean())


class AnalogDiscovery2:
    """The AD2 set up for the 2-w drive and the AD630 demodulators.

    Parameters
    ----------
    dwf : DwfLibrary-like
        ``pydwf.DwfLibrary()`` (see :func:`open_library`) or :class:`SimulatedDwfLibrary`.
    config : AD2Config
        The set-up.

    Examples
    --------
    >>> ad2 = AnalogDiscovery2(SimulatedDwfLibrary())
    >>> ad2.open(); plan = ad2.configure()
    >>> round(plan["reference"][0].frequency / plan["drive_frequency"])
    2
    >>> ad2.close()
    """

    def __init__(self, dwf, *, config: AD2Config | None = None):
        _check_library("dwf", dwf)
        self.dwf = dwf
        self.config = AD2Config() if config is None else config
        if not isinstance(self.config, AD2Config):
            raise TypeError(f"config must be an AD2Config, got {type(self.config).__name__}")
        self.device = None
        self.plan = None

    def open(self, device_index: int = -1) -> None:
        """Open the device (-1: the first one found).

        Parameters
        ----------
        device_index : int
            Index of the enumerated device, -1 for the first.

        Raises
        ------
        AD2Unavailable
            If no device can be opened (the library's message attached).
        """
        device_index = check_integer("device_index", device_index, -1, MAX_DEVICES)
        pydwf = _pydwf()
        try:
            self.device = self.dwf.deviceControl.open(device_index)
        except pydwf.DwfLibraryError as exc:
            raise AD2Unavailable(f"no Analog Discovery could be opened: {exc}") from exc

    def _require(self):
        if self.device is None:
            raise HardwareError("the AD2 is not open: call open() first")
        return self.device

    def configure(self) -> dict:
        """Set up WaveGen 1, the two pattern pins and the scope (nothing starts yet).

        Returns
        -------
        dict
            ``drive_frequency`` (Hz, as set), ``reference`` (the two :class:`PatternTiming`),
            ``scope_rate`` (Hz).
        """
        pydwf = _pydwf()
        dev, c = self._require(), self.config
        node, trigger = pydwf.DwfAnalogOutNode.Carrier, pydwf.DwfTriggerSource.AnalogOut1
        # the pattern generator: two squares at n f, their frequency on the clock's grid
        out = dev.digitalOut
        out.reset()
        clock = out.internalClockInfo()
        refs = []
        for pin, phase in zip(c.reference_pins, c.reference_phases):
            _, max_count = out.counterInfo(pin)
            _, max_divider = out.dividerInfo(pin)
            timing = pattern_timing(clock, c.harmonic * c.drive_frequency, phase,
                                    max_count=max_count, max_divider=max_divider)
            out.enableSet(pin, True)
            out.typeSet(pin, pydwf.DwfDigitalOutType.Pulse)
            out.idleSet(pin, pydwf.DwfDigitalOutIdle.Low)
            out.dividerSet(pin, timing.divider)
            out.counterSet(pin, timing.low_count, timing.high_count)
            out.counterInitSet(pin, timing.start_high, timing.start_count)
            refs.append(timing)
        out.triggerSourceSet(trigger)
        out.runSet(0.0)                      # run until stopped
        out.repeatSet(0)
        drive = refs[0].frequency / c.harmonic
        # WaveGen 1: V_dc + V_ac sin(2 pi f t)
        wave = dev.analogOut
        wave.reset(0)
        wave.nodeEnableSet(0, node, True)
        wave.nodeFunctionSet(0, node, pydwf.DwfAnalogOutFunction.Sine)
        wave.nodeFrequencySet(0, node, drive)
        wave.nodeAmplitudeSet(0, node, c.ac_voltage)
        wave.nodeOffsetSet(0, node, c.dc_voltage)
        wave.nodePhaseSet(0, node, 0.0)
        # the scope: both AD630 outputs, a record starting at WaveGen 1's start
        scope = dev.analogIn
        scope.reset()
        for channel in c.scope_channels:
            scope.channelEnableSet(channel, True)
            scope.channelRangeSet(channel, c.scope_range)
        scope.frequencySet(c.sample_rate)
        scope.bufferSizeSet(c.samples)
        scope.acquisitionModeSet(pydwf.DwfAcquisitionMode.Single)
        scope.triggerSourceSet(trigger)
        # the trigger position is measured from the record's middle: half a record puts it first
        scope.triggerPositionSet(c.samples / c.sample_rate / 2)
        scope.configure(False, False)
        self.plan = {"drive_frequency": drive, "reference": tuple(refs),
                     "scope_rate": c.sample_rate}
        return self.plan

    def acquire(self) -> Acquisition:
        """Arm the scope and the pattern, start WaveGen 1 (the trigger), read the record.

        Returns
        -------
        Acquisition

        Raises
        ------
        HardwareError
            If the record does not arrive within its length plus ``config.timeout``.
        """
        pydwf = _pydwf()
        dev, c = self._require(), self.config
        if self.plan is None:
            self.configure()
        dev.analogIn.configure(False, True)
        dev.digitalOut.configure(True)
        dev.analogOut.configure(0, True)
        deadline = time.monotonic() + c.samples / c.sample_rate + c.timeout
        while dev.analogIn.status(True) != pydwf.DwfState.Done:
            if time.monotonic() > deadline:
                raise HardwareError(f"the AD2's scope record did not complete within "
                                    f"{c.samples / c.sample_rate + c.timeout:.3g} s")
            time.sleep(0.001)
        x = np.asarray(dev.analogIn.statusData(c.scope_channels[0], c.samples), dtype=float)
        y = np.asarray(dev.analogIn.statusData(c.scope_channels[1], c.samples), dtype=float)
        return Acquisition(time=np.arange(c.samples) / c.sample_rate, level_x=x, level_y=y,
                           drive_frequency=self.plan["drive_frequency"],
                           reference_frequency=self.plan["reference"][0].frequency)

    def stop(self) -> None:
        """Stop the wave generator and the pattern (the heater off)."""
        dev = self._require()
        dev.analogOut.configure(0, False)
        dev.digitalOut.configure(False)

    def close(self) -> None:
        """Stop everything and close the device (safe to call twice)."""
        if self.device is not None:
            try:
                self.stop()
            finally:
                self.device.close()
                self.device = None

    def __enter__(self):
        if self.device is None:
            self.open()
        return self

    def __exit__(self, *exc):
        self.close()


# -- the simulated device -------------------------------------------------------------------
class _Instrument:
    """Records every call as (instrument, method, args) in the device's ``calls``."""

    def __init__(self, device, name):
        self._device, self._name = device, name

    def _record(self, method, *args):
        self._device.calls.append((self._name, method, args))


class _AnalogOut(_Instrument):
    def __getattr__(self, method):
        if method.startswith("_"):
            raise AttributeError(method)

        def call(*args):
            self._record(method, *args)
            if method == "configure" and args[1]:
                self._device._run()
        return call


class _DigitalOut(_Instrument):
    def internalClockInfo(self):
        self._record("internalClockInfo")
        return self._device.clock

    def counterInfo(self, pin):
        self._record("counterInfo", pin)
        return (0, 32768)

    def dividerInfo(self, pin):
        self._record("dividerInfo", pin)
        return (1, 2 ** 30)

    def __getattr__(self, method):
        if method.startswith("_"):
            raise AttributeError(method)
        return lambda *args: self._record(method, *args)


class _AnalogIn(_Instrument):
    def status(self, read_data):
        self._record("status", read_data)
        return _pydwf().DwfState.Done if self._device._record_data else \
            _pydwf().DwfState.Armed

    def statusData(self, channel, count):
        self._record("statusData", channel, count)
        return self._device._record_data[channel][:count]

    def __getattr__(self, method):
        if method.startswith("_"):
            raise AttributeError(method)
        return lambda *args: self._record(method, *args)


class _SimulatedDevice:
    """A simulated AD2 wired to the educational AFM: the chain, two AD630s and their low-pass."""

    def __init__(self, library):
        self.library = library
        self.clock = 100e6
        self.calls = []
        self.analogOut = _AnalogOut(self, "analogOut")
        self.digitalOut = _DigitalOut(self, "digitalOut")
        self.analogIn = _AnalogIn(self, "analogIn")
        self._record_data = None
        self.closed = False

    def close(self):
        self.calls.append(("device", "close", ()))
        self.closed = True

    def last(self, instrument, method):
        """The arguments of the last call of ``instrument.method`` (None if never called).

        Parameters
        ----------
        instrument : str
            ``"analogOut"``, ``"digitalOut"`` or ``"analogIn"``.
        method : str
            The pydwf method's name.
        """
        for inst, name, args in reversed(self.calls):
            if inst == instrument and name == method:
                return args
        return None

    def _pin_square(self, pin):
        divider = low = high = start_high = count = None
        for inst, name, args in self.calls:
            if inst != "digitalOut" or not args or args[0] != pin:
                continue
            if name == "dividerSet":
                divider = args[1]
            elif name == "counterSet":
                low, high = args[1], args[2]
            elif name == "counterInitSet":
                start_high, count = args[1], args[2]
        if None in (divider, low, start_high, count):
            return None
        period = low + high
        pos = (high - count) if start_high else (period - count)
        return self.clock / (divider * period), 2 * math.pi * pos / period

    def _run(self):
        """WaveGen 1 started: simulate the chain and the AD630s, fill the scope's record."""
        from ..signals.chain import ActiveProbe, simulate
        from ..signals.lockin import lowpass, reference_waveforms
        lib = self.library
        pydwf = _pydwf()
        node = pydwf.DwfAnalogOutNode.Carrier
        f = self.last("analogOut", "nodeFrequencySet")[2]
        va = self.last("analogOut", "nodeAmplitudeSet")[2]
        vdc = self.last("analogOut", "nodeOffsetSet")[2]
        if self.last("analogOut", "nodeFunctionSet")[1:] != (node,
                                                             pydwf.DwfAnalogOutFunction.Sine):
            raise HardwareError("the simulated AD2 models a sine on WaveGen 1 only")
        fs = self.last("analogIn", "frequencySet")[0]
        n = self.last("analogIn", "bufferSizeSet")[0]
        wave_start = (pydwf.DwfTriggerSource.AnalogOut1,)
        triggered = (self.last("digitalOut", "triggerSourceSet") == wave_start
                     and self.last("analogIn", "triggerSourceSet") == wave_start)
        # an untriggered pattern starts whenever it was armed: a phase nobody knows
        slip = 0.0 if triggered else float(np.random.default_rng(lib.seed).uniform(0, 2 * np.pi))
        # the library's probe with WaveGen's amplitude: its lever, typed Q and medium as they are
        probe = ActiveProbe(lib.probe.actuator.replace(ac_voltage=va), lib.probe.sensor)
        spp = 64
        run = simulate(probe, dc_voltage=vdc,
                       half_resonance_ratio=2 * f / probe.resonance_frequency,
                       amplifier_gain=lib.amplifier_gain, samples_per_period=spp,
                       record_duration=n / fs, seed=lib.seed, noise=lib.noise)
        levels = []
        for pin in lib.reference_pins:
            square = self._pin_square(pin)
            if square is None:                       # the pin was never set up: no switching
                levels.append(np.zeros(run.output.size))
                continue
            f_ref, phase = square
            ref, _ = reference_waveforms(run.output.size, sample_rate=run.sample_rate,
                                         frequency=f_ref, shape="square", phase=phase + slip)
            levels.append(lowpass(lib.ad630_gain * run.output * ref, sample_rate=run.sample_rate,
                                  time_constant=lib.ad630_time_constant, order=lib.ad630_order))
        t_scope = np.arange(n) / fs
        channels = {}
        for channel, level in zip(self.last_channels(), levels):
            channels[channel] = np.interp(t_scope, run.time, level)
        self.run = run
        self._record_data = channels

    def last_channels(self):
        """The scope channels enabled last (X first)."""
        return [args[0] for inst, name, args in self.calls
                if inst == "analogIn" and name == "channelEnableSet" and args[1]][-2:]


@dataclass
class SimulatedDwfLibrary:
    """A ``DwfLibrary`` stand-in: an AD2 wired to the simulated educational AFM and two AD630s.

    It records every pydwf call the host makes (``device.calls``) and, when WaveGen 1 starts,
    simulates the chain (:func:`afmsmiler.signals.chain.simulate`) at the frequency, amplitude and
    offset set, switches it with the squares the pattern pins were set to (an untriggered pattern
    gets a random phase), low-passes it like the AD630 boards' RC filters and hands the scope
    those levels at its sample rate.

    Parameters
    ----------
    probe : ActiveProbe, optional
        The lever (default: module (b)'s defaults).
    amplifier_gain : float
        Gain before the AD630s.
    ad630_gain : float
        The AD630's G.
    ad630_time_constant : float
        tau of the RC stages after each AD630, s.
    ad630_order : int
        Number of RC stages.
    reference_pins : tuple of int
        Pattern pins wired to the two AD630s' comparators (X, Y).
    noise : bool
        Simulate the noise sources.
    seed : int
        Seed of the noise (and of an untriggered pattern's phase).
    devices : list
        The devices opened so far (each records its ``calls``; tests read them).
    """

    probe: object = None
    amplifier_gain: float = 100.0
    ad630_gain: float = 1.0
    ad630_time_constant: float = 1e-3
    ad630_order: int = 2
    reference_pins: tuple = (0, 1)
    noise: bool = True
    seed: int = 0
    devices: list = field(default_factory=list)

    def __post_init__(self):
        from ..signals.ad630 import AD630_GAIN
        from ..signals.chain import AMPLIFIER_GAIN, ActiveProbe
        from ..signals.lockin import FILTER_ORDER, TIME_CONSTANT
        self.probe = ActiveProbe() if self.probe is None else \
            check_instance("probe", self.probe, ActiveProbe)
        self.amplifier_gain = AMPLIFIER_GAIN.check(self.amplifier_gain)
        self.ad630_gain = AD630_GAIN.check(self.ad630_gain)
        self.ad630_time_constant = check_range("ad630_time_constant", self.ad630_time_constant,
                                               TIME_CONSTANT.low, TIME_CONSTANT.high, "s")
        self.ad630_order = check_integer("ad630_order", self.ad630_order,
                                         int(FILTER_ORDER.low), int(FILTER_ORDER.high))
        if not isinstance(self.reference_pins, tuple) or len(self.reference_pins) != 2:
            raise ValueError(f"reference_pins must be a pair of pattern pins (X, Y), got "
                             f"{self.reference_pins!r}"[:160])
        for pin in self.reference_pins:
            check_integer("reference_pins", pin, 0, 15)
        check_instance("noise", self.noise, (bool, np.bool_), "bool")
        self.seed = check_integer("seed", self.seed, 0, 2 ** 63 - 1)
        check_instance("devices", self.devices, list)
        self.deviceControl = self

    def open(self, device_index: int = -1, config_index=None):
        """Open the simulated device (``deviceControl.open``).

        Parameters
        ----------
        device_index : int
            Ignored (one device).
        config_index : int, optional
            Ignored.
        """
        check_integer("device_index", device_index, -1, MAX_DEVICES)
        if config_index is not None:
            check_integer("config_index", config_index, 0, MAX_DEVICES)
        device = _SimulatedDevice(self)
        self.devices.append(device)
        return device
