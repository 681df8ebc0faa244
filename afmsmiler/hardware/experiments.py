"""Notebook 08's experiments as one-line calls, with their numbers named and sourced here.

Each function runs one experiment of module (h) on a device (or its twin) or on module (b)'s
signal chain and returns a small named result whose text (``str``) is the readout the notebook
prints, its units from :data:`~afmsmiler.parameters.UNITS` (no factor typed in a notebook):

- :func:`virtual_lever`: the haptic handle as a 500 N/m lever, streaming its position;
- :func:`bridge_readout`: the force bridge's loop timing;
- :func:`q_control_trial`: the handle's ring-down without and with the firmware's Q control,
  beside module (g)'s closed form;
- :func:`second_harmonic`: the educational AFM's active probe driven at omega, read at 2 omega;
- :func:`reference_error`: what a square reference's harmonics add to a reading;
- :func:`ad2_reading`: the Analog Discovery 2 as drive and demodulator;
- :func:`stream_sample`, :func:`educational_twin`: the educational AFM's pixel stream.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ..modes.qcontrol import QControl, fit_ring_down
from ..parameters import shown
from ..validation import check_range
from ..signals.chain import ActiveProbe, ChainRun, simulate
from ..signals.lockin import FILTER_ORDER, TIME_CONSTANT, LockInResult, enbw, lock_in, \
    settling_time

__all__ = ["VIRTUAL_SPRING", "MAX_FORCE", "WATCHDOG", "STREAM_PERIOD", "HOLD_FORCE", "MIN_HOLD_FORCE", "MAX_SPRING", "Q_GAIN",
           "RECORD_AFTER_SETTLING", "RING_DOWN_ATTEMPTS", "haptic_device", "virtual_lever", "bridge_readout", "QControlTrial",
           "q_control_trial", "SecondHarmonic", "second_harmonic", "reference_error",
           "AD2Reading", "ad2_reading", "stream_sample", "educational_twin"]

def _check_kind(name: str, value, kind: str) -> None:
    """Refuse, naming ``name``, what is not a ``kind`` (looked up by class name: the haptic
    driver, its bridge and the lock-in demo are imported where they are used)."""
    if not any(k.__name__ == kind for k in type(value).__mro__):
        raise TypeError(f"{name} must be a {kind}, got {type(value).__name__}")


#: N/m: the virtual lever the haptic handle becomes. On the handle and a finger (about 13 g:
#: :class:`~afmsmiler.hardware.haptic.twin.Mechanics` ``handle_mass`` plus
#: :class:`~afmsmiler.hardware.haptic.twin.Finger` ``mass``, Hajian and Howe, J. Biomech. Eng.
#: 119, 109 (1997)) it resonates near 31 Hz: slow enough to see and feel a ring-down, well inside
#: the device's 0 to 2000 N/m (:data:`afmsmiler.hardware.haptic.codec.PARAMETERS`).
VIRTUAL_SPRING = 500.0
#: N: the force the motor may apply (a finger holds 2 N without effort).
MAX_FORCE = 2.0
#: s: the motor switches off this long after the force frames stop (the firmware's watchdog).
WATCHDOG = 0.2
#: s: one position frame every millisecond (the bridge's 1 kHz loop).
STREAM_PERIOD = 1e-3
#: N: the force the handle is held with before a ring-down (half of :data:`MAX_FORCE`).
HOLD_FORCE = 1.0
#: The smallest holding force in N of a Q-control trial: 0.2 mm on the 500 N/m virtual lever,
#: some 26 counts of the encoder, for a ring-down that can be fitted.
MIN_HOLD_FORCE = 0.1
#: N/m: the stiffest virtual spring the firmware takes (its KS parameter, 2,000,000 mN/m).
MAX_SPRING = 2000.0
#: The Q controller's gain, relative to the virtual spring: -0.4 undamps the handle to about two
#: and a half times its Q, short of the limit g k_s / k = -1 / Q0 (module (g)'s
#: :class:`~afmsmiler.modes.qcontrol.QControl`, Hoelscher, Ebeling and Schwarz, J. Appl.
#: Phys. 99, 084311 (2006)).
Q_GAIN = -0.4
#: s recorded after the lock-in's filter settles: about 160 periods of 2 omega at the default
#: lever's 81.5 kHz resonance, which the reading averages.
RECORD_AFTER_SETTLING = 2e-3


#: The haptic devices this kernel connected, by port (None: the twin): a cell run again gets the
#: same device, not a second twin streaming beside the first.
_HAPTICS: dict = {}


def haptic_device(port: str | None = None):
    """The connected haptic device on ``port`` (None: its twin), connected once per kernel.

    A cell that calls this again (re-run, or run out of order) gets the device it connected
    before while that one is still open; a new one only when it was closed or its link lost.
    Each twin streams its handle's position 1000 times a second while asked to (its server
    and the device's reader take some 40 % of a core meanwhile), so a second twin per re-run
    would slow every later cell; notebook 08 stops the stream when it is done with the handle.

    Parameters
    ----------
    port : str or None
        A serial port (e.g. ``"/dev/ttyACM0"``) with the device plugged in; None: its twin.

    Returns
    -------
    afmsmiler.hardware.haptic.HapticDevice
        Connected (:meth:`~afmsmiler.hardware.haptic.HapticDevice.connect` has identified it).

    Raises
    ------
    TypeError
        If ``port`` is neither None nor a str.
    TransportClosed
        If the port cannot be opened (as :func:`~afmsmiler.hardware.haptic.open_haptic`).
    """
    from .haptic import open_haptic
    from .session import connect_or_close
    if port is not None and not isinstance(port, str):
        raise TypeError(f"port must be a serial port's name (str) or None, got {port!r}"[:160])
    kept = _HAPTICS.get(port)
    if kept is not None:
        if kept[0].is_open:
            return kept[0]
        kept[0].close()  # closed or its link lost: its twin's server (if any) stops too
        if kept[1] is not None:
            kept[1].stop()
    device, server = open_haptic(port)
    _HAPTICS[port] = (connect_or_close(device, server), server)
    return device


def virtual_lever(haptic, *, spring: float = VIRTUAL_SPRING, max_force: float = MAX_FORCE,
                  watchdog: float = WATCHDOG, period: float = STREAM_PERIOD) -> None:
    """Make the haptic handle a virtual lever and stream its position.

    Parameters
    ----------
    haptic : afmsmiler.hardware.haptic.HapticDevice
        Connected.
    spring : float
        The virtual lever's stiffness in N/m.
    max_force : float
        The motor's largest force in N.
    watchdog : float
        s after the last force frame before the motor switches off.
    period : float
        s between two position frames.
    """
    _check_kind("haptic", haptic, "HapticDevice")
    haptic.configure(spring=spring, max_force=max_force, watchdog=watchdog)
    haptic.enable()
    haptic.start_stream(period)


def bridge_readout(stats) -> str:
    """The force bridge's loop as one line: rate, jitter, deadlines missed.

    Parameters
    ----------
    stats : afmsmiler.hardware.haptic.bridge.BridgeStats

    Returns
    -------
    str
    """
    _check_kind("stats", stats, "BridgeStats")
    return (f"rate {shown(stats.rate, 'Hz', '.0f')}, jitter median "
            f"{shown(stats.jitter_median, 'us', '.1f')}, 99th percentile "
            f"{shown(stats.jitter_p99, 'us', '.0f')}, {stats.missed} deadlines missed")


@dataclass(frozen=True)
class QControlTrial:
    """The handle's ring-down without and with Q control, and the closed form.

    Attributes
    ----------
    q0, f0 : float
        Quality factor and resonance in Hz without Q control (fitted).
    q, f : float
        With Q control (fitted).
    closed_form : QControl
        Module (g)'s lever with the measured Q0 and f0, the total stiffness k = m (2 pi f0)^2
        (handle and finger mass m) and the gain ``gain`` x spring / k.
    """

    q0: float
    f0: float
    q: float
    f: float
    closed_form: QControl

    def __str__(self) -> str:
        return (f"Q0 = {self.q0:.3g} at {shown(self.f0, 'Hz', '.1f')}; with Q control "
                f"Q = {self.q:.3g}, closed form "
                f"{self.closed_form.effective_quality_factor:.3g}")


def q_control_trial(haptic, *, gain: float = Q_GAIN, force: float = HOLD_FORCE,
                    spring: float = VIRTUAL_SPRING) -> QControlTrial:
    """Ring the handle down without, then with the firmware's Q control (phase pi/2 at f0).

    Parameters
    ----------
    haptic : afmsmiler.hardware.haptic.HapticDevice
        Connected (:func:`virtual_lever`); enabled again here (its watchdog switches the
        motor off whenever the force frames stop), and streaming positions for the trial (a
        stream stopped before, as notebook 08 does when it is done with the handle, is started
        and stopped again).
    gain : float
        The Q controller's gain relative to ``spring``, in [-10, 10].
    force : float
        The holding force in N before each release, from :data:`MIN_HOLD_FORCE` to
        :data:`MAX_FORCE`.
    spring : float
        The virtual lever's stiffness in N/m (as configured), in (0, :data:`MAX_SPRING`].

    Returns
    -------
    QControlTrial
    """
    _check_kind("haptic", haptic, "HapticDevice")
    gain = check_range("gain", gain, -10.0, 10.0)
    force = check_range("force", force, MIN_HOLD_FORCE, MAX_FORCE, "N")
    spring = check_range("spring", spring, 0.0, MAX_SPRING, "N/m", low_inclusive=False)
    from .haptic.twin import Finger, Mechanics

    stopped = haptic.stream_period is None
    if stopped:
        haptic.start_stream(STREAM_PERIOD)
    try:
        q0, f0 = fit_ring_down(*_ring_down(haptic, force))
        haptic.configure(qgain=gain, qphase=math.pi / 2, qfreq=f0)
        q, f = fit_ring_down(*_ring_down(haptic, force))
    finally:
        if stopped:
            haptic.stop_stream()
    k = (Mechanics().handle_mass + Finger().mass) * (2 * math.pi * f0) ** 2
    closed = QControl(spring_constant=k, resonance_frequency=f0, quality_factor=q0,
                      gain=gain * spring / k)
    return QControlTrial(q0, f0, q, f, closed)


#: Ring-downs tried before a busy host's watchdog trips are reported (each one 1.5 s).
RING_DOWN_ATTEMPTS = 3


def _ring_down(haptic, force: float):
    """Enable the motor and ring the handle down; again (at most :data:`RING_DOWN_ATTEMPTS`
    times) when this host paused so long that the device's watchdog switched the motor off."""
    from .errors import WatchdogTripped
    for attempt in range(RING_DOWN_ATTEMPTS):
        haptic.enable()
        try:
            return haptic.ring_down(force)
        except WatchdogTripped:
            if attempt == RING_DOWN_ATTEMPTS - 1:
                raise


@dataclass(frozen=True)
class SecondHarmonic:
    """The active probe's chain run and its lock-in reading at 2 omega.

    Attributes
    ----------
    run : afmsmiler.signals.chain.ChainRun
    reading : afmsmiler.signals.lockin.LockInResult
    enbw : float
        The lock-in's noise bandwidth in Hz.
    """

    run: ChainRun
    reading: LockInResult
    enbw: float

    def chain_readout(self) -> str:
        """The chain: the lever's resonance, the drive and the sampling."""
        run = self.run
        return (f"f1 = {shown(run.probe.resonance_frequency, 'kHz', '.1f')}, drive at "
                f"{shown(run.drive_frequency, 'kHz', '.2f')}, sampled at "
                f"{shown(run.sample_rate, 'MHz', '.2f')}")

    def reading_readout(self) -> str:
        """The reading beside the closed form, and the lock-in's noise bandwidth."""
        r, truth = self.reading, self.run.second
        return (f"recovered {shown(r.amplitude, 'mV', '.3f')} at "
                f"{shown(r.phase, 'deg', '.2f')}; closed form {shown(abs(truth), 'mV', '.3f')} "
                f"at {shown(math.atan2(truth.imag, truth.real), 'deg', '.2f')}; "
                f"ENBW {shown(self.enbw, 'Hz', '.1f')}")

    def __str__(self) -> str:
        return self.chain_readout() + "\n" + self.reading_readout()


def second_harmonic(probe: ActiveProbe | None = None, *,
                    time_constant: float = TIME_CONSTANT.default,
                    order: int = int(FILTER_ORDER.default), seed: int = 0) -> SecondHarmonic:
    """Drive the active probe at half its resonance and read its bending at 2 omega.

    Parameters
    ----------
    probe : ActiveProbe, optional
        Module (b)'s heater and bridge on one lever (default :class:`ActiveProbe`).
    time_constant : float
        The lock-in's time constant in s.
    order : int
        Its RC stages.
    seed : int
        Seed of the chain's noise.

    Returns
    -------
    SecondHarmonic
    """
    run = simulate(probe, record_duration=settling_time(time_constant, order)
                   + RECORD_AFTER_SETTLING, seed=seed)
    reading = lock_in(run.output, sample_rate=run.sample_rate, frequency=run.drive_frequency,
                      harmonic=2, time_constant=time_constant, order=order)
    return SecondHarmonic(run, reading, enbw(time_constant, order))


def reference_error(demo) -> str:
    """How far a lock-in reading is off, in all and in amplitude and phase.

    Parameters
    ----------
    demo : afmsmiler.signals.demo.LockInDemo
        One run of the lock-in demonstration (the lock-in panel's ``last``).

    Returns
    -------
    str
    """
    _check_kind("demo", demo, "LockInDemo")
    return (f"reading off by {shown(abs(demo.deviation), 'mV', '.2f')}, "
            f"{demo.relative_error:.1%} of the signal (amplitude "
            f"{demo.amplitude_error:+.1%}, phase {shown(demo.phase_error, 'deg', '+.1f')})")


@dataclass(frozen=True)
class AD2Reading:
    """The AD2's references and the two AD630 levels they give.

    Attributes
    ----------
    reference_frequency : float
        The square references' frequency in Hz (2 omega).
    x, y : float
        The AD630 outputs' settled levels in V (in phase, in quadrature).
    """

    reference_frequency: float
    x: float
    y: float

    @property
    def amplitude(self) -> float:
        """The 2 omega amplitude in V the two levels give (:func:`amplitude_from_levels`)."""
        from ..signals.ad630 import amplitude_from_levels
        return amplitude_from_levels(self.x, self.y)

    def __str__(self) -> str:
        return (f"references at {shown(self.reference_frequency, 'kHz', '.3f')}; AD630 levels "
                f"X = {shown(self.x, 'mV', '.2f')}, Y = {shown(self.y, 'mV', '.2f')}: amplitude "
                f"{shown(self.amplitude, 'mV', '.2f')}")


def ad2_reading(dwf, drive_frequency: float) -> AD2Reading:
    """Drive the heater from WaveGen 1 and read the AD630 levels (the AD2 closed at the end).

    Parameters
    ----------
    dwf : object
        The WaveForms library, or the simulated one (:func:`~afmsmiler.hardware.ad2.library_or_simulation`).
    drive_frequency : float
        The heater's drive omega / 2 pi in Hz.

    Returns
    -------
    AD2Reading
    """
    from .ad2 import AD2Config, AnalogDiscovery2

    with AnalogDiscovery2(dwf, config=AD2Config(drive_frequency=drive_frequency)) as ad2:
        plan = ad2.configure()
        x, y = ad2.acquire().settled()
    return AD2Reading(plan["reference"][0].frequency, x, y)


def stream_sample():
    """The sample the educational AFM's twin images: 10 particles of 120 nm on 2.56 um.

    Returns
    -------
    afmsmiler.samples.Sample
    """
    from ..samples import particles
    return particles((128, 128), 20e-9, count=10, radius=120e-9, seed=2)


def educational_twin(sample, *, pixels: int = 32, pitch: float = 60e-9):
    """The educational AFM's twin imaging ``sample``, connected and configured.

    Parameters
    ----------
    sample : afmsmiler.samples.Sample
        What the twin images.
    pixels : int
        Pixels per line and lines.
    pitch : float
        Pixel spacing in m (32 pixels of 60 nm: 1.9 um of the 2.56 um sample).

    Returns
    -------
    afm : EducationalAFM
        Connected, configured (``afm.scan(...)`` scans).
    server : TwinServer
        The twin's server (stops with the kernel, or ``server.stop()``).
    """
    from .educational import EducationalAFM, EducationalAFMTwin
    from .twin import open_twin

    host, server = open_twin(EducationalAFMTwin(sample))
    afm = EducationalAFM(host)
    afm.connect()
    afm.configure(pixels=pixels, lines=pixels, pitch=pitch)
    return afm, server
