"""The force bridge: forces from any source streamed to the haptic device at a steady rate.

:class:`ForceBridge` runs a deadline-based loop (in its own thread, or synchronously for tests):
tick n is due at t0 + n / rate; the loop sleeps until :data:`BUSY_WAIT` before the deadline and
busy-waits the rest on ``time.perf_counter``. Each tick reads the handle's latest position,
maps it into the source's coordinates (``position_scale``, metres of source per metre of
handle), asks the source for its force at the source's time (``time_scale`` source seconds per
real second: 1e-4 slows a 300 kHz lever to 30 Hz), scales it (``force_scale``, device newtons per
source newton), clips it at the device's maximum force (counted as saturation) and sends it as
an ``FO`` frame. A tick that starts more than one period late skips the deadlines it missed
(counted), so the loop never tries to catch up with a burst.

The bridge measures itself (:class:`BridgeStats`): the achieved rate (ticks over elapsed time) and
the jitter, the distribution of the period error |t_n - t_{n-1} - 1/rate| between successive
tick starts (median and 99th percentile, over the last :data:`STATS_WINDOW` ticks).

Sources (anything with ``force(time, position) -> N``; optional ``start()``/``stop()``):

- :class:`IndentationSource`: module (d)'s indentation force of a tip at the finger's depth;
- :class:`TappingSource`: module (g)'s tapping lever over one steady period, replayed slowed
  down: the tip-sample force (the taps) or the lever's spring force (the oscillation);
- :class:`GaugeSource`: the macroscopic AFM's strain gauge (any ``read() -> counts``, polled in
  its own thread so that a slow serial round trip never holds up the loop);
- :class:`CantileverSource`: module (a)'s lever as a spring the finger bends;
- :class:`FunctionSource`: any ``f(time, position)``, e.g. a simulation.
"""
from __future__ import annotations

import math
import sys
import threading
import time
from dataclasses import dataclass

import numpy as np

from ...parameters import Parameter, read_only
from ...validation import (check_finite, check_instance, check_nonnegative, check_positive,
                           check_range, check_real)

__all__ = ["PARAMETERS", "ForceBridge", "BridgeStats", "FunctionSource", "IndentationSource",
           "TappingSource", "GaugeSource", "CantileverSource", "BUSY_WAIT", "STATS_WINDOW",
           "MAX_RATE", "SWITCH_INTERVAL"]

#: The last part of each wait spent busy-waiting on the clock (s): sleep() overshoots by ~0.1 ms.
BUSY_WAIT = 2e-4
#: Python's thread switch interval (s) while a bridge runs: the default 5 ms lets a busy thread
#: (a twin served in the same process, a plot) hold the interpreter lock for 5 ms after the
#: bridge's sleep ended, so each late wake-up would cost up to five ticks.
SWITCH_INTERVAL = 2e-4
#: Ticks the jitter statistics keep (the last 10 s at 1 kHz).
STATS_WINDOW = 10_000
#: Highest rate the bridge accepts (Hz).
MAX_RATE = 10_000.0

#: The bridge's user-settable quantities: its rate and the scales from a source to the device.
PARAMETERS = read_only({p.name: p for p in (
    Parameter(name="rate", unit="Hz", default=1000.0, low=0.0, high=MAX_RATE,
              low_inclusive=False, slider_low=100.0, slider_high=2000.0,
              label="bridge rate"),
    Parameter(name="force_scale", unit="", default=1.0, low=-1e15, high=1e15,
              slider_low=1e4, slider_high=1e10, log=True,
              label="force scale (device N per source N)"),
    Parameter(name="time_scale", unit="", default=1.0, low=0.0, high=1e9,
              low_inclusive=False, slider_low=1e-7, slider_high=1.0, log=True,
              label="time scale (source s per real s)"),
    Parameter(name="position_scale", unit="", default=1.0, low=-1e9, high=1e9,
              slider_low=1e-9, slider_high=1.0, log=True,
              label="position scale (source m per handle m)"),
)})


@dataclass(frozen=True)
class BridgeStats:
    """The bridge's own measurement of its loop.

    Parameters
    ----------
    ticks : int
        Ticks run.
    elapsed : float
        Seconds from the first tick to the last.
    rate : float
        Achieved rate (ticks - 1) / elapsed in Hz (nan before two ticks).
    target_rate : float
        The rate asked for in Hz.
    jitter_median : float
        Median of |period - 1/rate| in s.
    jitter_p99 : float
        99th percentile of |period - 1/rate| in s.
    missed : int
        Deadlines skipped because a tick started more than a period late.
    saturated : int
        Ticks whose force was clipped at the device's maximum force.
    last_force : float
        The last force sent in N.
    max_force : float
        The device's maximum force in N used for clipping.
    """

    ticks: int
    elapsed: float
    rate: float
    target_rate: float
    jitter_median: float
    jitter_p99: float
    missed: int
    saturated: int
    last_force: float
    max_force: float

    @property
    def saturation(self) -> float:
        """Fraction of ticks that saturated."""
        return self.saturated / self.ticks if self.ticks else 0.0


class ForceBridge:
    """Stream a source's force to a haptic device at a steady rate, and measure the rate.

    Parameters
    ----------
    source : object
        Has ``force(time, position)`` returning N (time in the source's s, position in its m),
        or is such a callable.
    device : object
        Has ``send_force(force)`` and ``latest()`` (a sample with ``.position`` in m, or None),
        like :class:`~afmsmiler.hardware.haptic.HapticDevice`.
    rate : float
        Target tick rate in Hz, (0, :data:`MAX_RATE`].
    force_scale : float
        Device newtons per source newton (e.g. 1e8: 1 nN felt as 0.1 N).
    time_scale : float
        Source seconds per real second, > 0 (1e-4: a 300 kHz lever felt at 30 Hz).
    position_scale : float
        Source metres per metre of handle travel (1e-6: 1 mm of finger is 1 nm of tip).
    max_force : float, optional
        The device's maximum force in N (default: ``device.max_force`` if it has one, else
        inf).
    clock : callable
        Seconds, monotonic (default ``time.perf_counter``; tests pass a fake).
    sleep : callable
        Sleeps its argument in s (default ``time.sleep``).

    Examples
    --------
    >>> class Dev:
    ...     def send_force(self, f): self.f = f
    ...     def latest(self): return None
    >>> bridge = ForceBridge(lambda t, x: 0.5, Dev(), rate=1000.0)
    >>> bridge.run(10).ticks
    10
    """

    def __init__(self, source, device, *, rate: float = PARAMETERS["rate"].default,
                 force_scale: float = PARAMETERS["force_scale"].default,
                 time_scale: float = PARAMETERS["time_scale"].default,
                 position_scale: float = PARAMETERS["position_scale"].default, max_force=None,
                 clock=time.perf_counter, sleep=time.sleep):
        if hasattr(source, "force") and callable(source.force):
            self._force = source.force
        elif callable(source):
            self._force = source
        else:
            raise TypeError(f"source must have force(time, position) or be callable, got "
                            f"{type(source).__name__}")
        for method in ("send_force", "latest"):
            if not callable(getattr(device, method, None)):
                raise TypeError(f"device must have {method}(), got {type(device).__name__}")
        self.source = source
        self.device = device
        self.rate = PARAMETERS["rate"].check(rate)
        self.force_scale = PARAMETERS["force_scale"].check(force_scale)
        self.time_scale = PARAMETERS["time_scale"].check(time_scale)
        self.position_scale = PARAMETERS["position_scale"].check(position_scale)
        if max_force is None:
            max_force = getattr(device, "max_force", math.inf)
        max_force = check_real("max_force", max_force)
        self.max_force = max_force if max_force == math.inf else \
            check_positive("max_force", max_force, "N")
        for name, func in (("clock", clock), ("sleep", sleep)):
            if not callable(func):
                raise TypeError(f"{name} must be callable, got {type(func).__name__} "
                                f"{func!r}"[:160])
        self.clock, self.sleep = clock, sleep
        self._intervals = np.zeros(STATS_WINDOW)
        self._n_intervals = 0
        self._ticks = 0
        self._missed = 0
        self._saturated = 0
        self._first = self._last = None
        self._last_force = 0.0
        self._stop = threading.Event()
        self._thread = None
        self.exception = None

    # -- one tick ---------------------------------------------------------------------------
    def _tick(self, t_start: float, t0: float) -> None:
        sample = self.device.latest()
        position = 0.0 if sample is None else sample.position
        force = self.force_scale * float(self._force((t_start - t0) * self.time_scale,
                                                     position * self.position_scale))
        if not math.isfinite(force):
            force = 0.0
        if abs(force) > self.max_force:
            force = math.copysign(self.max_force, force)
            self._saturated += 1
        self.device.send_force(force)
        self._last_force = force
        if self._last is not None:
            self._intervals[self._n_intervals % STATS_WINDOW] = t_start - self._last
            self._n_intervals += 1
        else:
            self._first = t_start
        self._last = t_start
        self._ticks += 1

    def _wait(self, deadline: float) -> float:
        """Sleep then busy-wait until ``deadline``; the time the tick starts."""
        now = self.clock()
        if deadline - now > BUSY_WAIT:
            self.sleep(deadline - now - BUSY_WAIT)
        now = self.clock()
        while now < deadline:
            now = self.clock()
        return now

    def run(self, ticks: int | None = None, *, duration: float | None = None) -> BridgeStats:
        """Run the loop in this thread for a number of ticks or a duration, or until stopped.

        Parameters
        ----------
        ticks : int, optional
            Ticks to run, 1 to 10^8.
        duration : float, optional
            Seconds to run (by the bridge's clock), at most 1e6.

        Returns
        -------
        BridgeStats
        """
        if ticks is not None and (isinstance(ticks, bool) or not isinstance(ticks, int) or
                                  not 1 <= ticks <= 10 ** 8):
            raise ValueError(f"ticks must be an integer in [1, 1e8], got {ticks!r}")
        if duration is not None:
            duration = check_range("duration", duration, 0.0, 1e6, "s", low_inclusive=False)
        period = 1.0 / self.rate
        starter = getattr(self.source, "start", None)
        if callable(starter):
            starter()
        switch = sys.getswitchinterval()
        sys.setswitchinterval(min(switch, SWITCH_INTERVAL))
        try:
            t0 = self.clock()
            n = 0
            done = 0
            while not self._stop.is_set():
                deadline = t0 + n * period
                if duration is not None and deadline - t0 > duration:
                    break
                t_start = self._wait(deadline)
                self._tick(t_start, t0)
                done += 1
                if ticks is not None and done >= ticks:
                    break
                n += 1
                late = self.clock() - (t0 + n * period)
                if late > period:  # skip the deadlines already past
                    skip = int(late / period)
                    self._missed += skip
                    n += skip
        finally:
            sys.setswitchinterval(switch)
            stopper = getattr(self.source, "stop", None)
            if callable(stopper):
                stopper()
        return self.stats()

    def stats(self) -> BridgeStats:
        """The loop's measurement so far.

        Returns
        -------
        BridgeStats
        """
        n = min(self._n_intervals, STATS_WINDOW)
        err = np.abs(self._intervals[:n] - 1.0 / self.rate)
        elapsed = (self._last - self._first) if self._ticks > 1 else 0.0
        rate = (self._ticks - 1) / elapsed if elapsed > 0 else math.nan
        med, p99 = (float(np.median(err)), float(np.percentile(err, 99))) if n else \
            (math.nan, math.nan)
        return BridgeStats(self._ticks, elapsed, rate, self.rate, med, p99, self._missed,
                           self._saturated, self._last_force, self.max_force)

    # -- in a thread -------------------------------------------------------------------------
    def start(self) -> "ForceBridge":
        """Run the loop in a daemon thread until :meth:`stop`.

        Returns
        -------
        ForceBridge
            ``self``.
        """
        if self._thread is not None:
            raise RuntimeError("this ForceBridge was already started")
        self._thread = threading.Thread(target=self._run_thread, name="ForceBridge",
                                        daemon=True)
        self._thread.start()
        return self

    def _run_thread(self):
        try:
            self.run()
        except BaseException as exc:  # a source or the device failed: surfaced by stop()
            self.exception = exc

    @property
    def running(self) -> bool:
        """Whether the loop's thread is alive."""
        return self._thread is not None and self._thread.is_alive()

    def stop(self, timeout: float = 2.0) -> BridgeStats:
        """Stop the loop, join its thread and return the statistics (re-raises its error).

        Parameters
        ----------
        timeout : float
            The longest to wait for the thread in s, finite and >= 0.

        Returns
        -------
        BridgeStats
        """
        timeout = check_nonnegative("timeout", timeout, "s")
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout)
        if self.exception is not None:
            exc, self.exception = self.exception, None
            raise exc
        return self.stats()

    def __enter__(self):
        return self.start()

    def __exit__(self, *exc):
        self.stop()


# -- sources --------------------------------------------------------------------------------------
def _time_position(time, position) -> tuple[float, float]:
    """A source's ``time`` (s) and ``position`` (m), finite floats, or ValueError naming them.

    The bridge calls a source 1000 times a second with two finite floats: those pass on the fast
    path (a type test and ``x - x == 0``, false for NaN and +-inf: ~0.1 us); anything else goes
    through :func:`~afmsmiler.validation.check_finite`.
    """
    if type(time) is float and type(position) is float and time - time == 0.0 \
            and position - position == 0.0:
        return time, position
    return check_finite("time", time, "s"), check_finite("position", position, "m")


class FunctionSource:
    """Any force law ``func(time, position) -> N`` as a source.

    Parameters
    ----------
    func : callable
        Time in s and position in m to force in N.
    name : str
        A label for the panel.
    """

    def __init__(self, func, name: str = "function"):
        if not callable(func):
            raise TypeError(f"func must be callable, got {type(func).__name__}")
        self.func, self.name = func, check_instance("name", name, str)

    def force(self, time: float, position: float) -> float:
        """The force in N.

        Parameters
        ----------
        time : float
            Source time in s.
        position : float
            Source position in m.

        Raises
        ------
        ValueError
            Unless ``time`` and ``position`` are finite numbers (named), before ``func`` runs.
        """
        time, position = _time_position(time, position)
        return float(self.func(time, position))


class IndentationSource:
    """Module (d): the force of a tip pressed into the sample at the finger's depth.

    The finger's position x (source metres) is the indentation Z_s = max(0, x - surface); the
    force pushes back, -F(Z_s) (a table of :data:`TABLE_POINTS` depths up to ``max_depth``,
    linearly interpolated, so that a tick costs microseconds; beyond it, F(max_depth)).

    Parameters
    ----------
    system : afmsmiler.contact.ContactSystem
        Tip and sample (its tip's force law F(Z_s) with E* = E / (1 - nu^2)).
    max_depth : float
        Deepest indentation tabulated in m, > 0.
    surface : float
        Position of the sample's surface in source m.
    """

    TABLE_POINTS = 2048

    def __init__(self, system, *, max_depth: float = 50e-9, surface: float = 0.0):
        from ...contact import ContactSystem, reduced_modulus
        check_instance("system", system, ContactSystem)
        self.system = system
        self.max_depth = min(check_positive("max_depth", max_depth, "m"),
                             system.tip.depth_limit)
        self.surface = check_range("surface", surface, -1.0, 1.0, "m")
        self.name = f"indentation ({type(system.tip).__name__})"
        self._depth = np.linspace(0.0, self.max_depth, self.TABLE_POINTS)
        e_star = reduced_modulus(system.youngs_modulus, system.poisson_ratio)
        self._force = np.asarray(system.tip.force(self._depth, e_star), dtype=float)

    def force(self, time: float, position: float) -> float:
        """-F(Z_s) in N at Z_s = max(0, position - surface).

        Parameters
        ----------
        time : float
            Source time in s (unused: the elastic force has no memory).
        position : float
            Finger position in source m.
        """
        time, position = _time_position(time, position)
        depth = position - self.surface
        if depth <= 0.0:
            return 0.0
        return -float(np.interp(depth, self._depth, self._force))


class TappingSource:
    """Module (g): a tapping lever's steady period, replayed at the source's time.

    :func:`afmsmiler.modes.integrate` gives the steady motion z(t) over one drive period (its 64
    samples); the source replays, periodically and linearly interpolated, the tip-sample force
    F_ts(z_c + z) (``quantity="tip_force"``: the taps) or the lever's spring force -k z
    (``"lever_force"``: the oscillation the finger holds).

    Building it runs the reference solver once: a second or two for the default lever, a tenth
    of that for a Q of tens, tens of seconds in hard contact (z_c of a nanometre or less),
    bounded by :func:`~afmsmiler.modes.integrate`'s ``max_periods``.

    Parameters
    ----------
    distance : float
        Rest tip-sample distance z_c in m, in (0, 1e-5] (as :func:`~afmsmiler.modes.integrate`).
    lever : afmsmiler.modes.TappingLever, optional
        Lever and sample (default ``TappingLever()``).
    quantity : {"tip_force", "lever_force"}
        What to replay.
    max_periods : int
        The most drive periods the reference solver integrates before it takes the state it
        reached (:func:`~afmsmiler.modes.integrate`'s ``max_periods``).
    """

    def __init__(self, distance: float, lever=None, *, quantity: str = "tip_force",
                 max_periods: int | None = None):
        from ...modes.tapping import MAX_PERIODS, TappingLever, integrate
        from ...validation import check_choice
        check_choice("quantity", quantity, ("tip_force", "lever_force"))
        lever = TappingLever() if lever is None else lever
        check_instance("lever", lever, TappingLever)
        state = integrate(distance, lever,
                          max_periods=MAX_PERIODS if max_periods is None else max_periods)
        self.lever, self.state, self.quantity = lever, state, quantity
        self.period = 1.0 / (lever.frequency_ratio * lever.resonance_frequency)
        z = np.asarray(state.deflection)
        if quantity == "tip_force":
            values = np.asarray(lever.force(state.distance + z))
        else:
            values = -lever.spring_constant * z
        self._t = np.append(np.asarray(state.time) - state.time[0], self.period)
        self._f = np.append(values, values[0])
        self.name = f"tapping ({quantity})"

    def force(self, time: float, position: float) -> float:
        """The replayed force in N at source time ``time``.

        Parameters
        ----------
        time : float
            Source time in s.
        position : float
            Finger position in source m (unused: the lever's motion is prescribed).
        """
        time, position = _time_position(time, position)
        return float(np.interp(time % self.period, self._t, self._f))


class CantileverSource:
    """Module (a): the lever as a spring the finger bends, F = -k x.

    Parameters
    ----------
    cantilever : afmsmiler.cantilever.Cantilever
        The lever; its ``spring_constant`` in N/m.
    """

    def __init__(self, cantilever):
        from ...cantilever import Cantilever
        check_instance("cantilever", cantilever, Cantilever)
        self.cantilever = cantilever
        self.spring_constant = float(cantilever.spring_constant)
        self.name = "cantilever spring"

    def force(self, time: float, position: float) -> float:
        """-k x in N.

        Parameters
        ----------
        time : float
            Source time in s (unused).
        position : float
            Deflection of the lever's end in m.
        """
        time, position = _time_position(time, position)
        return -self.spring_constant * position


class GaugeSource:
    """The macroscopic AFM's strain gauge as a source, polled in its own thread.

    Parameters
    ----------
    read : callable
        Returns the gauge reading in counts (e.g. the ``MacroAFM``'s gauge read).
    force_per_count : float
        N per count (the gauge's calibration: counts to deflection to force, module (a)).
    zero : float
        The free reading in counts.
    interval : float
        Seconds between reads, in [1e-3, 10].

    Attributes
    ----------
    reads : int
        How many readings were taken.
    exception : BaseException or None
        The reader's error, if it failed (the force is then held at zero).
    """

    def __init__(self, read, *, force_per_count: float, zero: float = 0.0,
                 interval: float = 0.01):
        if not callable(read):
            raise TypeError(f"read must be callable, got {type(read).__name__}")
        self.read = read
        self.force_per_count = check_range("force_per_count", force_per_count, -1e6, 1e6,
                                           "N")
        self.zero = check_range("zero", zero, -1e12, 1e12, "")
        self.interval = check_range("interval", interval, 1e-3, 10.0, "s")
        self.name = "strain gauge"
        self.reads = 0
        self.exception = None
        self._value = 0.0
        self._stop = threading.Event()
        self._thread = None

    def _loop(self):
        while not self._stop.is_set():
            try:
                counts = float(self.read())
            except BaseException as exc:
                self.exception = exc
                self._value = 0.0
                return
            self._value = (counts - self.zero) * self.force_per_count
            self.reads += 1
            self._stop.wait(self.interval)

    def start(self) -> None:
        """Start polling the gauge (the bridge calls it when it starts)."""
        if self._thread is None or not self._thread.is_alive():
            self._stop.clear()
            self._thread = threading.Thread(target=self._loop, name="GaugeSource",
                                            daemon=True)
            self._thread.start()

    def stop(self) -> None:
        """Stop polling (the bridge calls it when it stops)."""
        self._stop.set()
        if self._thread is not None:
            self._thread.join(2.0)

    def force(self, time: float, position: float) -> float:
        """The latest gauge force in N.

        Parameters
        ----------
        time : float
            Source time in s (unused).
        position : float
            Source position in m (unused).
        """
        _time_position(time, position)
        return self._value
