"""The haptic device's driver: :class:`HapticDevice` takes a transport (a port, a pty, memory).

A background reader thread owns the transport's read side: it hands replies to the command that
waits for them and keeps the latest ``PO`` sample and the events. Commands (one at a time) are
retried with the same SEQ, which the protocol makes safe, after a timeout or a ``0 ER 1``/
``0 ER 9`` (the device saw a damaged line); ``FO`` force frames go out without a reply (SEQ 0)
from any thread, e.g. the :class:`~afmsmiler.hardware.haptic.bridge.ForceBridge`'s.

Every wait has a timeout: a command raises :class:`DeviceNotResponding` after its retries, a wait
for a position sample raises it after ``timeout``; an unplugged port raises
:class:`TransportClosed`; a device of another protocol version raises
:class:`ProtocolVersionError` at :meth:`HapticDevice.connect`.
"""
from __future__ import annotations

import collections
import queue
import threading
import time

from ...validation import check_positive
from ..errors import (RESEND_CODES, DeviceNotResponding, FrameError, ReplyError,
                      TransportClosed, TransportTimeout, WatchdogTripped)
from ..framed import FramedDevice
from ..framing import Frame, decode_frame, encode_frame, reply_frame
from ..protocol import WIRE_UNITS, _lookup
from .codec import (DEVICE, PARAMETERS, TABLE, Command, Flag, Param, PositionSample, Status,
                    force_frame, param_to_wire, parse_position, parse_status)

__all__ = ["HapticDevice", "free_decay_start", "open_haptic"]

_NAMES = {spec.si_name: p for p, spec in PARAMETERS.items()}


def _param(param):
    """A parameter by its SI name (``"max_force"``), code or member, else named."""
    return (_NAMES.get(param) if isinstance(param, str) else None) or \
        _lookup("param", Param, param)


class HapticDevice(FramedDevice):
    """The one-axis haptic device of ``hardware/haptic`` over any transport.

    Parameters
    ----------
    transport : Transport
        The link to the device (a :class:`~afmsmiler.hardware.SerialTransport` at 1 000 000
        baud, a twin's :class:`~afmsmiler.hardware.MemoryTransport` end...). Not opened here.
    timeout : float
        Seconds to wait for each reply or position sample, > 0.
    retries : int
        Extra attempts of a command after a timeout or a damaged line, 0 to 10.

    Attributes
    ----------
    identity : tuple or None
        (device, protocol version, firmware version) after :meth:`connect`.
    events : collections.deque
        The latest event words (``BOOT``, ``WATCHDOG``, ``ESTOP``, ``LIMIT``), most recent last.
    faults : collections.deque
        Error numbers the device reported unsolicited (``0 ER n``, n not 1 or 9).
    garbage : int
        Lines the reader could not decode (ignored).
    stream_period : float or None
        The period in s of the position stream this host last asked for (:meth:`start_stream`),
        None before it or after :meth:`stop_stream`.

    Examples
    --------
    >>> from afmsmiler.hardware import open_twin
    >>> from afmsmiler.hardware.haptic import HapticTwin
    >>> host, server = open_twin(HapticTwin())
    >>> with HapticDevice(host) as dev:
    ...     dev.connect()[0]
    'HAPTIC'
    >>> server.stop()
    """

    DEVICE = DEVICE
    TABLE = TABLE

    def __init__(self, transport, *, timeout: float = 1.0, retries: int = 3):
        super().__init__(transport, timeout=timeout, retries=retries, max_retries=10)
        if self.timeout > 60:
            raise ValueError(f"timeout must be in (0, 60] s, got {timeout!r}")
        self.identity = None
        self.events = collections.deque(maxlen=100)
        self.faults = collections.deque(maxlen=100)
        self._replies = queue.Queue()
        self._write_lock = threading.Lock()
        self._command_lock = threading.Lock()
        self._sample_cond = threading.Condition()
        self._sample = None
        self._samples = 0
        self._closed_error = None
        self._recording = None  # a list while ring_down records every PO sample
        self._stop = threading.Event()
        self._reader = None
        self.read_only = {}
        self.stream_period = None

    # -- the reader thread --------------------------------------------------------------------
    def _start_reader(self):
        if self._reader is None:
            self._reader = threading.Thread(target=self._read_loop, name="HapticDevice-reader",
                                            daemon=True)
            self._reader.start()

    def _read_loop(self):
        while not self._stop.is_set():
            try:
                line = self.transport.readline(0.05)
            except TransportTimeout:
                continue
            except (TransportClosed, OSError) as exc:
                self._closed_error = exc if isinstance(exc, TransportClosed) else \
                    TransportClosed(f"the haptic device's port failed: {exc}")
                self._replies.put(None)
                with self._sample_cond:
                    self._sample_cond.notify_all()
                return
            try:
                frame = decode_frame(line)
            except FrameError:
                self.garbage += 1
                continue
            if frame.seq != 0:
                self._replies.put(frame)
            elif frame.code == Command.POSITION.value:
                try:
                    sample = parse_position(frame)
                except ReplyError:
                    self.garbage += 1
                    continue
                with self._sample_cond:
                    self._sample = sample
                    self._samples += 1
                    if self._recording is not None:
                        self._recording.append(sample)
                    self._sample_cond.notify_all()
            elif frame.code == Command.EVENT.value and frame.args:
                self.events.append(str(frame.args[0]))
            elif frame.code == Command.ERROR.value and frame.args:
                if frame.args[0] in RESEND_CODES:
                    self._replies.put(frame)      # the pending command goes out again
                else:
                    self.faults.append(frame.args[0])

    def _check_open(self):
        if self._closed_error is not None:
            raise TransportClosed(str(self._closed_error))

    # -- commands -----------------------------------------------------------------------------
    def _send(self, data: bytes) -> None:
        with self._write_lock:   # the force bridge writes FO frames from its own thread
            self.transport.write(data)

    def _receive(self, timeout: float) -> Frame:
        """The next reply the reader thread took (or its ``0 ER 1``/``0 ER 9``), within timeout."""
        try:
            frame = self._replies.get(timeout=max(0.0, timeout))
        except queue.Empty:
            raise TransportTimeout(f"no reply within {timeout:g} s") from None
        if frame is None:
            self._check_open()
        return frame

    def command(self, code, *args) -> tuple:
        """Send one command and return its reply's results (retried with the same SEQ).

        The reply is awaited until one deadline per attempt, whatever the device sends: a
        command lasts at most ``(retries + 1) * timeout``.

        Parameters
        ----------
        code : Command or str
            The two-letter command.
        *args : int or str
            Its arguments.

        Returns
        -------
        tuple
            The OK reply's results after the echoed code.

        Raises
        ------
        DeviceError
            The device answered ``ER`` (code, word, command attached).
        DeviceNotResponding
            No valid reply after ``retries`` retries.
        TransportClosed
            The port is gone.
        """
        code = _lookup("code", Command, code).value
        self._start_reader()
        with self._command_lock:
            self._check_open()
            while True:  # drop stale replies of earlier commands
                try:
                    self._replies.get_nowait()
                except queue.Empty:
                    break
            return self._exchange(code, *args)

    def connect(self) -> tuple:
        """Identify the device (protocol version check) and read its read-only parameters.

        Returns
        -------
        tuple
            (device name, protocol version, firmware version).

        Raises
        ------
        ProtocolVersionError
            If the device speaks another protocol version.
        HardwareError
            If the device is not a HAPTIC.
        """
        self._start_reader()
        with self._command_lock:
            self.identity = self._identify()
        self.read_only = {spec.si_name: self.get(p)
                          for p, spec in PARAMETERS.items() if spec.read_only}
        return self.identity

    def set(self, param, value: float) -> float:
        """Set a parameter from its SI value; returns the value the device took (SI).

        Parameters
        ----------
        param : Param, str
            ``Param.SPRING``, ``"KS"`` or its SI name ``"spring"`` (:data:`codec.PARAMETERS`).
        value : float
            SI value (N/m for the spring, rad for the phase...).

        Returns
        -------
        float

        Raises
        ------
        ValueError
            If the value is outside the table's range or the parameter read-only (nothing sent).
        ReplyError
            If the device's reply is outside the table's range.
        """
        p = _param(param)
        spec = PARAMETERS[p]
        wire = spec.check(param_to_wire(p, value))
        return spec.to_si(self._checked(self.command(Command.SET, p.value, wire),
                                        Command.SET.value, p.value))

    def get(self, param) -> float:
        """A parameter's value in SI units.

        Parameters
        ----------
        param : Param or str
            The parameter (code or SI name).

        Returns
        -------
        float
        """
        p = _param(param)
        return PARAMETERS[p].to_si(self._checked(self.command(Command.GET, p.value),
                                                 Command.GET.value, p.value))

    def configure(self, **values) -> None:
        """Set several parameters by SI name (``spring=500.0, qgain=-0.5``...).

        Parameters
        ----------
        **values
            SI name -> SI value; all are checked before any is sent.
        """
        unknown = sorted(set(values) - set(_NAMES))
        if unknown:
            raise TypeError(f"unknown parameter(s) {unknown}; known: {sorted(_NAMES)}")
        for name, value in values.items():  # each named by its keyword
            PARAMETERS[_NAMES[name]].to_wire(value)
        for name, value in values.items():
            self.set(name, value)

    @property
    def max_force(self) -> float:
        """The device's largest force in N (reads MF)."""
        return self.get(Param.MAX_FORCE)

    def enable(self) -> None:
        """Motor on (ACTIVE): from now on FO frames must come within the watchdog time."""
        self.command(Command.ENABLE)

    def disable(self) -> None:
        """Motor off (IDLE); clears a FAULT."""
        self.command(Command.DISABLE)

    def zero(self) -> None:
        """Call the handle's present position zero (only while the motor is off)."""
        self.command(Command.ZERO)

    def estop(self) -> None:
        """Emergency stop: current zero, FAULT until :meth:`disable`."""
        self.command(Command.ESTOP)

    def status(self) -> Status:
        """The device's state, flags since the last status, position and force.

        Returns
        -------
        Status
        """
        args = self.command(Command.STATUS)
        return parse_status(reply_frame(1, Command.STATUS, *args))

    def start_stream(self, period: float = 1e-3) -> None:
        """Have the device stream ``PO`` frames every ``period`` s (1 ms to 1 s, whole ms).

        Parameters
        ----------
        period : float
            Stream period in s.

        Raises
        ------
        ValueError
            If ``period`` is not a finite number of 1 ms to 1 s (NaN included).
        """
        ms = round(check_positive("period", period, "s") / WIRE_UNITS["ms"].scale)
        if not 1 <= ms <= 1000:
            raise ValueError(f"period must be in [0.001, 1] s, got {period!r}")
        self.command(Command.STREAM, ms)
        self.stream_period = ms * WIRE_UNITS["ms"].scale

    def stop_stream(self) -> None:
        """Stop the position stream."""
        self.command(Command.STREAM, 0)
        self.stream_period = None

    def send_force(self, force: float) -> None:
        """Stream one force setpoint ``0 FO <uN>`` (no reply; feeds the device's watchdog).

        Parameters
        ----------
        force : float
            Force on the handle in N (the device scales it by FS and clips it at MF).
        """
        self._check_open()
        self._send(encode_frame(force_frame(force)))

    def latest(self) -> PositionSample | None:
        """The latest position sample (None before the first); raises if the port is gone.

        Returns
        -------
        PositionSample or None
        """
        self._check_open()
        return self._sample

    @property
    def samples_received(self) -> int:
        """How many PO frames the reader has taken."""
        return self._samples

    def wait_position(self, timeout: float | None = None) -> PositionSample:
        """Wait for the next position sample.

        Parameters
        ----------
        timeout : float, optional
            Seconds (default: the device's ``timeout``).

        Returns
        -------
        PositionSample

        Raises
        ------
        ValueError
            If ``timeout`` is not finite and > 0 (NaN would wait forever).
        DeviceNotResponding
            If none arrives in time (a silent device: its watchdog has zeroed the force).
        """
        self._start_reader()
        wait = self.timeout if timeout is None else check_positive("timeout", timeout, "s")
        with self._sample_cond:
            start = self._samples
            deadline = time.monotonic() + wait
            while self._samples == start:
                self._check_open()
                left = deadline - time.monotonic()
                if left <= 0:
                    raise DeviceNotResponding(f"{DEVICE} sent no position for {wait:g} s")
                self._sample_cond.wait(min(left, 1.0))  # 1e300 s would overflow the lock
            return self._sample

    def ring_down(self, force: float = 1.0, *, hold: float = 0.5, duration: float = 1.0):
        """Hold the handle with a force, release it, and record its free motion.

        A :class:`~afmsmiler.hardware.haptic.bridge.ForceBridge` streams ``force`` for ``hold`` s
        and then zero for ``duration`` s at 1 kHz (so the watchdog stays fed); every ``PO``
        sample is recorded. The device must be enabled and streaming positions.

        Parameters
        ----------
        force : float
            Holding force in N (within the device's maximum force).
        hold : float
            Seconds of holding, in [0.05, 10] (long enough for the handle to settle).
        duration : float
            Seconds recorded after the release, in [0.05, 10].

        Returns
        -------
        (ndarray, ndarray)
            Times in s from 5 ms after the release (device clock; the margin keeps frames still
            in flight out) and positions in m.

        Raises
        ------
        WatchdogTripped
            If the device is not ACTIVE (enable it: its watchdog disables it whenever the force
            frames stop, e.g. at the end of a bridge's run), or its watchdog fired meanwhile.
        DeviceNotResponding
            If no position sample came after the release.
        """
        import numpy as np

        from ...validation import check_range
        from .bridge import ForceBridge
        hold = check_range("hold", hold, 0.05, 10.0, "s")
        duration = check_range("duration", duration, 0.05, 10.0, "s")
        force = check_range("force", force, -100.0, 100.0, "N")
        self.send_force(force)  # feeds the watchdog before the status round trip
        state = self.status().state
        if state != "ACTIVE":
            raise WatchdogTripped(f"{DEVICE} is {state}, not ACTIVE: call enable() first (its "
                                "watchdog disables it whenever the force frames stop)")
        self._recording = []
        release = None
        trips = list(self.events).count("WATCHDOG")

        def law(t, _x):
            return force if t < hold else 0.0

        try:
            bridge = ForceBridge(law, self, max_force=max(abs(force), 1e-9))
            bridge.run(duration=hold + duration)
        finally:
            samples, self._recording = self._recording, None
        after_run = self.status()  # its reply comes after every frame the run made the device send
        if list(self.events).count("WATCHDOG") > trips or after_run.flags & Flag.WATCHDOG or \
                after_run.state != "ACTIVE":
            raise WatchdogTripped(f"{DEVICE}'s watchdog fired during the ring-down: this host "
                                "paused longer than the watchdog time between force frames; "
                                "set a longer one (configure(watchdog=0.2)) and repeat")
        if samples:  # the release by the device's clock, plus 5 ms for the frames in flight
            release = samples[0].device_time + hold + 5e-3
        t = np.array([s.device_time for s in samples])
        x = np.array([s.position for s in samples])
        start = free_decay_start(t, x, release) if release is not None else t.size
        if t.size - start < 8:
            raise DeviceNotResponding(f"{DEVICE} sent {t.size - start} positions after the "
                                      "release (is it enabled and streaming?)")
        return t[start:] - t[start], x[start:]

    @property
    def is_open(self) -> bool:
        """Connected and not closed, its link not lost."""
        return self.identity is not None and not self._stop.is_set() and \
            self._closed_error is None

    def close(self) -> None:
        """Stop the reader and close the transport (idempotent)."""
        self._stop.set()
        if self._reader is not None:
            self._reader.join(1.0)
        self.transport.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def free_decay_start(time, position, release: float, *, tolerance: float = 0.02) -> int:
    """The index of the first sample of a ring-down's free decay, found in the data.

    The release by the clocks (the recording's first sample plus the hold) is only an earliest
    estimate: a host that stalls (another thread holding the interpreter) reads samples late,
    so its first recorded sample is older than the moment its force stream began, and the
    estimate falls inside the hold. A sample that still sits on the hold's plateau is then not
    free motion, and a damped cosine fitted through it finds a wrong frequency and Q. The
    decay starts at the first sample after ``release`` that has left the plateau (the median of
    the positions before ``release``) by more than ``tolerance`` of the way to the rest
    position (the median of the last tenth).

    Parameters
    ----------
    time : ndarray
        The samples' device times in s, increasing.
    position : ndarray
        Their positions in m.
    release : float
        The earliest time in s at which the decay can have begun.
    tolerance : float
        The fraction of the hold-to-rest distance that counts as having left the plateau,
        in (0, 0.5).

    Returns
    -------
    int
        The index (``len(time)`` when no sample after ``release`` left the plateau).
    """
    import numpy as np
    t, x = np.asarray(time, dtype=float), np.asarray(position, dtype=float)
    if not 0.0 < tolerance < 0.5:
        raise ValueError(f"tolerance must be in (0, 0.5), got {tolerance!r}")
    first = int(np.searchsorted(t, release))
    if first == 0 or first >= t.size:
        return first
    hold = float(np.median(x[:first]))
    rest = float(np.median(x[-max(1, t.size // 10):]))
    left = np.flatnonzero(np.abs(x[first:] - hold) > tolerance * abs(rest - hold))
    return first + int(left[0]) if left.size else t.size


def open_haptic(port: str | None = None, *, time_scale: float = 1.0):
    """The haptic device on a serial ``port``, or its twin served in this process.

    Parameters
    ----------
    port : str or None
        A serial port (e.g. ``"/dev/ttyACM0"``) at the device's 1 Mbaud; None: the twin.
    time_scale : float
        The twin's pace (1: real time), as :func:`~afmsmiler.hardware.twin.open_twin`.

    Returns
    -------
    (HapticDevice, TwinServer or None)
        The device, not yet connected, and the twin's server (None for a real port: stop it when
        done).

    Raises
    ------
    TypeError
        If ``port`` is neither None nor a str.
    TransportClosed
        If the port cannot be opened (no such port, or busy), naming it: whether a name is a
        port is the machine's answer at the time, as ``open()``'s ``FileNotFoundError`` is.
    """
    from ..transport import SerialTransport
    from ..twin import open_twin
    from .twin import HapticTwin
    if port is None:
        link, server = open_twin(HapticTwin(), time_scale=time_scale)
        return HapticDevice(link), server
    if not isinstance(port, str):
        raise TypeError(f"port must be a serial port's name (str) or None, got {port!r}")
    return HapticDevice(SerialTransport(port, baudrate=1_000_000)), None
