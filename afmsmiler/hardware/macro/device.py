"""The macroscopic AFM's driver: :class:`MacroAFM` takes a transport and speaks protocol 1.

Like scikit-rf's instrument drivers without their coupling: the device class never opens a port
itself, so the same code drives a board (``SerialTransport("/dev/ttyACM0")``), the firmware in
simavr (a pty), or the twin (``open_twin(MacroAFMTwin())``), and the tests inject faults through
:class:`~afmsmiler.hardware.transport.FaultyTransport`.

Every read has a timeout. A command is retried with the same SEQ (the device re-sends its last
reply instead of executing it twice) when its reply does not come within ``timeout`` or the
device answers ``0 ER 1``/``0 ER 9`` (it could not read our line); after ``retries`` retries
:class:`~afmsmiler.hardware.errors.DeviceNotResponding`. A scan's pixels lost to garbage are
fetched again with ``GL``. A scan interrupted by a fault, an unplugged cable or a silent device
raises with the finished lines attached as ``.partial`` (a :class:`~afmsmiler.samples.Sample`,
which :meth:`MacroAFM.save` writes).
"""
from __future__ import annotations

import queue
import threading
import time
from dataclasses import dataclass

import numpy as np

from ...parameters import Parameter, read_only
from ...samples import Sample
from ..protocol import _lookup
from ...validation import check_flag, check_choice, check_instance, check_integer, check_positive
from ..errors import (DeviceError, DeviceNotResponding, FrameError, HardwareError, ReplyError,
                      TransportTimeout)
from ..framed import FramedDevice
from ..framing import Frame
from .codec import (DEVICE, TABLE, Command, ErrorCode, ErrorReply, Event, EventMsg, Flag,
                    LineEnd, MacroAFMCodec, Param, Pixel, Reply, State, Status)
from .mechanics import GaugeCalibration

__all__ = ["MacroAFM", "DeviceInfo", "ScanProgress", "PARAMETERS", "MODES"]

#: Imaging modes and their wire values (``MO`` of :data:`~.codec.TABLE`).
MODES = read_only({"contact": 0, "jumping": 1})

#: The z micro-step of the machine as built (``ZS``'s default), for the lift's range in m.
_NOMINAL_Z_STEP = TABLE[Param.ZSTEP].to_si(TABLE[Param.ZSTEP].default)


def _from_table(param, label: str, **slider) -> Parameter:
    """An SI Parameter whose range and default are the protocol table's (never retyped)."""
    w = TABLE[param]
    return Parameter(name=w.si_name, unit=w.si_unit, default=w.to_si(w.default),
                     low=w.to_si(w.low), high=w.to_si(w.high), label=label, **slider)


#: What :meth:`MacroAFM.configure` takes (SI), validated before anything is sent: the ranges are
#: the protocol table's (:data:`~.codec.TABLE`, the firmware's limits).
PARAMETERS = read_only({p.name: p for p in (
    _from_table(Param.NX, "pixels per line"),
    _from_table(Param.NY, "lines"),
    _from_table(Param.PITCH, "pixel spacing", display_unit="mm", slider_low=0.05e-3,
                slider_high=2e-3),
    Parameter(name="setpoint_force", unit="N", display_unit="mN", default=10e-3, low=1e-5,
              high=1.0, slider_low=1e-3, slider_high=50e-3, label="setpoint force"),
    Parameter(name="lift", unit="m", display_unit="mm", default=0.5e-3,
              low=TABLE[Param.LIFT].low * _NOMINAL_Z_STEP,
              high=TABLE[Param.LIFT].high * _NOMINAL_Z_STEP,
              slider_low=0.05e-3, slider_high=5e-3, label="jumping lift"),
    _from_table(Param.SPEED, "max step rate", slider_low=100.0, slider_high=5000.0),
    _from_table(Param.ACCEL, "step acceleration", slider_low=1e3, slider_high=1e5, log=True),
    _from_table(Param.PRESET, "button preset"),
)})


@dataclass(frozen=True)
class DeviceInfo:
    """What ``ID`` and the read-only parameters say about the device.

    Parameters
    ----------
    device : str
        The device's name (``MACROAFM``).
    protocol_version : int
        The protocol it speaks.
    firmware_version : str
        Its firmware's version.
    z_step : float
        The z micro-step in m (``ZS``).
    """

    device: str
    protocol_version: int
    firmware_version: str
    z_step: float


@dataclass(frozen=True)
class ScanProgress:
    """One pixel arrived: where, its height, and how far the scan is.

    Parameters
    ----------
    row : int
        Its line.
    col : int
        Its pixel along the line.
    height : float
        Its height in m (z micro-steps times ZS).
    counts : int
        The gauge's reading there (counts above the free reading).
    done : int
        Pixels received so far.
    total : int
        Pixels of the scan.
    image : numpy.ndarray
        The live image (lines x pixels, m, NaN where no pixel has arrived): the same array all
        along the scan, for a live figure to redraw.
    """

    row: int
    col: int
    height: float
    counts: int
    done: int
    total: int
    image: np.ndarray

    @property
    def fraction(self) -> float:
        """Fraction of the scan done, 0..1."""
        return self.done / self.total


class _Scan:
    """The host's record of a running scan."""

    def __init__(self, nx, ny, pitch, z_step):
        self.nx, self.ny, self.pitch, self.z_step = nx, ny, pitch, z_step
        self.image = np.full((ny, nx), np.nan)
        self.counts = np.zeros((ny, nx), dtype=np.int64)
        self.have = np.zeros((ny, nx), dtype=bool)
        self.ended = set()
        self.new = []
        self.done = self.aborted = self.paused = False
        self.fault = None
        self.fault_word = ""
        self.last_row = 0


class MacroAFM(FramedDevice):
    """The macroscopic AFM (a steel ruler scanned by a 3D printer's steppers), over a transport.

    Parameters
    ----------
    transport : Transport
        The link to the device (never opened here).
    timeout : float
        The longest to wait for a command's reply (s), per attempt.
    retries : int
        How often a command is sent again (same SEQ) before :class:`DeviceNotResponding`.
    calibration : GaugeCalibration, optional
        Gauge counts per newton (for the setpoint force); default predicted from the steel
        ruler (:meth:`GaugeCalibration.from_ruler`).
    stream_timeout : float
        The longest a scan waits for its next pixel before asking the device's status (s): a
        pixel of a slow machine (or an emulator) can take seconds.
    home_timeout : float
        The longest homing may take (s).

    Attributes
    ----------
    info : DeviceInfo or None
        Set by :meth:`connect`.
    events : list
        Events the device sent (:class:`~afmsmiler.hardware.macro.codec.EventMsg`).
    result : Sample or None
        The last scan's image (or the finished lines of an interrupted one).
    garbage : int
        Lines received that were not valid frames.

    Examples
    --------
    >>> from afmsmiler.hardware import open_twin
    >>> from afmsmiler.hardware.macro import MacroAFMTwin
    >>> host, server = open_twin(MacroAFMTwin())
    >>> afm = MacroAFM(host)
    >>> afm.connect().device
    'MACROAFM'
    >>> afm.close(); server.stop()
    """

    DEVICE = DEVICE
    TABLE = TABLE

    def __init__(self, transport, *, timeout: float = 1.0, retries: int = 3,
                 calibration: GaugeCalibration | None = None, stream_timeout: float = 30.0,
                 home_timeout: float = 300.0):
        super().__init__(transport, timeout=timeout, retries=retries)
        self.calibration = GaugeCalibration.from_ruler() if calibration is None else \
            check_instance("calibration", calibration, GaugeCalibration)
        self.stream_timeout = check_positive("stream_timeout", stream_timeout, "s")
        self.home_timeout = check_positive("home_timeout", home_timeout, "s")
        self.info = None
        self.events = []
        self.result = None
        self._io = threading.RLock()
        self._scan = None
        self._scan_thread = None
        self._requests = queue.Queue()
        self._homed_event = False

    # -- the wire ------------------------------------------------------------------------------
    def _read(self, timeout: float):
        """One message (None for a line that is not one); stream messages dispatched."""
        line = self.transport.readline(timeout)
        try:
            msg = MacroAFMCodec.parse(line)
        except FrameError:
            self.garbage += 1
            return None
        if isinstance(msg, (Pixel, LineEnd, EventMsg)):
            self._dispatch(msg)
        elif isinstance(msg, ErrorReply) and msg.seq == 0 and msg.code not in (
                ErrorCode.CHECKSUM, ErrorCode.MALFORMED):
            self._dispatch(msg)
        return msg

    def _exchange(self, code: str, *args) -> tuple:
        """One request (FramedDevice's: one deadline per attempt, retries) holding the link."""
        with self._io:
            return super()._exchange(code, *args)

    def _stream(self, frame: Frame) -> None:
        """A SEQ 0 frame met while waiting for a reply: into the scan, or an event noted."""
        try:
            msg = MacroAFMCodec.message(frame)
        except FrameError:
            self.garbage += 1
            return
        self._dispatch(msg)

    def _command(self, command: Command, *args) -> tuple:
        """Send a command and return its results, retrying with the same SEQ where safe."""
        command = Command(command)
        return self._exchange(command.value, *(a.value if isinstance(a, Param) else a
                                               for a in args))

    def _dispatch(self, msg) -> None:
        """A stream message: into the running scan's image, or an event noted."""
        scan = self._scan
        if isinstance(msg, EventMsg):
            self.events.append(msg)
            if msg.event == Event.HOMED:
                self._homed_event = True
            if scan is not None:
                if msg.event == Event.DONE:
                    scan.done = True
                elif msg.event == Event.ABORTED:
                    scan.aborted = True
                elif msg.event == Event.PAUSED:
                    scan.paused = True
                elif msg.event in (Event.LIMIT, Event.ESTOP):
                    scan.fault_word = "" if msg.arg is None else str(msg.arg)
            return
        if isinstance(msg, ErrorReply):  # a fault: 0 ER <n> after its event
            if scan is not None:
                scan.fault = DeviceError(int(msg.code), scan.fault_word, DEVICE)
            else:
                self.events.append(msg)
            return
        if scan is None:
            return
        if isinstance(msg, Pixel):
            if 0 <= msg.row < scan.ny and 0 <= msg.col < scan.nx:
                first = not scan.have[msg.row, msg.col]
                scan.image[msg.row, msg.col] = msg.z * scan.z_step
                scan.counts[msg.row, msg.col] = msg.counts
                scan.have[msg.row, msg.col] = True
                if first:
                    scan.new.append(msg)
                if msg.row > scan.last_row:
                    scan.ended.update(range(scan.last_row, msg.row))  # a lost LN
                    scan.last_row = msg.row
        elif isinstance(msg, LineEnd) and 0 <= msg.row < scan.ny:
            scan.ended.add(msg.row)

    def _call(self, command: Command, *args) -> tuple:
        """A command from any thread: queued to the scanning thread while a scan runs."""
        if self._scan is not None and self._scan_thread not in (None, threading.get_ident()):
            done = threading.Event()
            box = {}
            self._requests.put((command, args, done, box))
            deadline = time.monotonic() + (self.retries + 1) * self.timeout + \
                self.stream_timeout + 1.0
            while not done.wait(0.05):
                if self._scan is None:  # the scan ended before serving us: serve it here
                    with self._io:
                        self._serve_requests()
                elif time.monotonic() > deadline:
                    raise DeviceNotResponding(f"the scan did not pass on {command.name}")
            if "error" in box:
                raise box["error"]
            return box["result"]
        return self._command(command, *args)

    # -- commands ------------------------------------------------------------------------------
    def connect(self) -> DeviceInfo:
        """Identify the device, check its protocol version, read its read-only parameters.

        Returns
        -------
        DeviceInfo

        Raises
        ------
        ProtocolVersionError
            If the firmware speaks another protocol version (both versions named).
        HardwareError
            If the device is not a MACROAFM.
        ReplyError
            If a reply is not of the protocol's shape, or ZS is outside the table's range.
        """
        device, version, firmware = self._identify()
        z_step = TABLE[Param.ZSTEP].to_si(self.get(Param.ZSTEP))
        self.info = DeviceInfo(device, version, firmware, z_step)
        return self.info

    def _require_info(self) -> DeviceInfo:
        if self.info is None:
            raise HardwareError("call connect() first (it reads the z micro-step)")
        return self.info

    def get(self, param: Param) -> int:
        """One parameter's value on the wire (``GP``).

        Parameters
        ----------
        param : Param
            The parameter.

        Returns
        -------
        int

        Raises
        ------
        ReplyError
            If the reply names another parameter or its value is outside the table's range
            (e.g. ``ZS 0`` or ``NX 2147483647``), naming the parameter, value and range.
        """
        param = _lookup("param", Param, param)
        return self._checked(self._call(Command.GET, param.value), Command.GET.value,
                             param.value)

    def set(self, param: Param, value: int) -> None:
        """Set one parameter on the wire (``SP``), as an integer in the device's unit.

        Parameters
        ----------
        param : Param
            The parameter.
        value : int
            Its value in the unit :data:`~.codec.TABLE` names (um, counts, micro-steps,
            steps/s ...).

        Raises
        ------
        ValueError
            If the parameter is read-only or the value outside the table's range (nothing sent).
        """
        param = _lookup("param", Param, param)
        spec = TABLE[param]
        self._call(Command.SET, param.value, spec._check(value, spec._value_label("value")))

    def wire_values(self, **values) -> dict:
        """The integers :meth:`configure` would send for SI ``values``, validated, nothing sent.

        Parameters
        ----------
        **values
            ``pixels``, ``lines``, ``pitch`` (m), ``setpoint_force`` (N), ``mode``
            ("contact"/"jumping"), ``lift`` (m), ``step_rate`` (steps/s),
            ``step_acceleration`` (steps/s^2), ``preset``.

        Returns
        -------
        dict
            :class:`Param` -> int.

        Raises
        ------
        ValueError
            Naming the parameter, its value and the valid range (the protocol table's).
        TypeError
            For an unknown keyword.
        """
        out = {}
        for name, value in values.items():
            if name == "mode":
                out[Param.MODE] = MODES[check_choice("mode", value, tuple(MODES))]
                continue
            if name not in PARAMETERS:
                raise TypeError(f"configure() got an unexpected keyword argument {name!r}; "
                                f"valid: {sorted([*PARAMETERS, 'mode'])}")
            p = PARAMETERS[name]
            if name in ("pixels", "lines", "preset"):
                out[Param(TABLE.by_si_name(name).code)] = \
                    check_integer(name, value, int(p.low), int(p.high))
                continue
            si = p.check(value)
            if name == "setpoint_force":
                counts = round(self.calibration.counts(si))
                se = TABLE[Param.SETPOINT]
                if not se.valid(counts):
                    raise ValueError(f"setpoint_force {si:g} N is {counts} gauge counts; the "
                                     f"firmware takes {se.low} to {se.high} counts (SE)")
                out[Param.SETPOINT] = counts
            elif name == "lift":
                steps = round(si / self._require_info().z_step)
                li = TABLE[Param.LIFT]
                if not li.valid(steps):
                    raise ValueError(f"lift {si:g} m is {steps} z micro-steps; the firmware "
                                     f"takes {li.low} to {li.high} (LI)")
                out[Param.LIFT] = steps
            else:   # pitch (to whole multiples of 25 um), step_rate, step_acceleration
                out[Param(TABLE.by_si_name(name).code)] = TABLE.by_si_name(name).to_wire(si)
        return out

    def configure(self, **values) -> dict:
        """Set the imaging parameters in SI units (all validated before anything is sent).

        Parameters
        ----------
        **values
            ``pixels`` (1..128), ``lines`` (1..1024), ``pitch`` (m, 25 um to 10 mm, sent as
            the nearest multiple of 25 um), ``setpoint_force`` (N, converted to gauge counts by
            the calibration), ``mode`` ("contact" or "jumping"), ``lift`` (m, converted to z
            micro-steps), ``step_rate`` (10..8000 steps/s), ``step_acceleration``
            (10..1000000 steps/s^2), ``preset`` (0..3): the ranges of :data:`~.codec.TABLE`.

        Returns
        -------
        dict
            What was sent: :class:`Param` -> int.

        Raises
        ------
        ValueError
            Naming the parameter, its value and the valid range (nothing sent).
        TypeError
            For an unknown keyword.
        """
        wire = self.wire_values(**values)
        for param, value in wire.items():
            self.set(param, value)
        return wire

    def configuration(self) -> dict:
        """The device's imaging parameters read back (``GP``), in the SI units of configure().

        Returns
        -------
        dict
            ``pixels``, ``lines``, ``pitch`` (m), ``setpoint_force`` (N, through the
            calibration), ``mode``, ``lift`` (m), ``step_rate`` (steps/s),
            ``step_acceleration`` (steps/s^2), ``preset``.
        """
        z_step = self._require_info().z_step
        wire = {param: self.get(param) for param in Param if param != Param.ZSTEP}
        modes = {v: k for k, v in MODES.items()}
        return {"pixels": wire[Param.NX], "lines": wire[Param.NY],
                "pitch": TABLE[Param.PITCH].to_si(wire[Param.PITCH]),
                "setpoint_force": self.calibration.force(wire[Param.SETPOINT]),
                "mode": modes.get(wire[Param.MODE], wire[Param.MODE]),
                "lift": wire[Param.LIFT] * z_step, "step_rate": float(wire[Param.SPEED]),
                "step_acceleration": float(wire[Param.ACCEL]), "preset": wire[Param.PRESET]}

    def status(self) -> Status:
        """The device's state, position in the scan and flags (``ST``).

        Returns
        -------
        Status
        """
        return MacroAFMCodec.status(Reply(0, Command.STATUS, self._call(Command.STATUS)))

    def gauge(self) -> int:
        """One gauge reading in counts above the free reading (``RG``).

        Returns
        -------
        int
        """
        results = self._call(Command.GAUGE)
        if len(results) != 1 or not isinstance(results[0], int):
            raise ReplyError(f"{DEVICE}'s RG reply must be one integer, got {results!r}")
        return results[0]

    def force(self) -> float:
        """The force on the needle in N, from one gauge reading and the calibration.

        Returns
        -------
        float
        """
        return self.calibration.force(self.gauge())

    def home(self) -> None:
        """Home the axes (``HM``) and wait for the ``HOMED`` event (at most home_timeout).

        Raises
        ------
        DeviceError
            If homing faults (a limit switch, the emergency stop).
        DeviceNotResponding
            If homing does not finish within ``home_timeout``.
        """
        with self._io:
            self._homed_event = False
            self._command(Command.HOME)
            deadline = time.monotonic() + self.home_timeout
            while not self._homed_event:
                remaining = deadline - time.monotonic()
                if remaining <= 0:
                    raise DeviceNotResponding(f"{DEVICE} did not finish homing within "
                                              f"{self.home_timeout:g} s")
                try:
                    msg = self._read(min(remaining, self.timeout))
                except TransportTimeout:  # quiet: the HOMED event may have been lost, ask
                    status = self.status()
                    if status.state == State.IDLE and status.homed:
                        return
                    if status.state != State.HOMING:
                        raise DeviceError(int(ErrorCode.LIMIT if status.state == State.FAULT
                                              else ErrorCode.STATE), status.state.value, DEVICE,
                                          Command.HOME.value) from None
                    continue
                if isinstance(msg, ErrorReply) and msg.seq == 0 and msg.code not in (
                        ErrorCode.CHECKSUM, ErrorCode.MALFORMED):
                    raise DeviceError(int(msg.code), "", DEVICE, Command.HOME.value)

    def pause(self) -> None:
        """Pause the scan after the current pixel (``PA``); from any thread."""
        self._call(Command.PAUSE)

    def resume(self) -> None:
        """Resume a paused scan (``RS``); from any thread."""
        if self._scan is not None:
            self._scan.paused = False
        self._call(Command.RESUME)

    def abort(self) -> None:
        """Abort the scan (``AB``); :meth:`scan` then returns the finished lines."""
        self._call(Command.ABORT)

    def wait_button(self, timeout: float) -> int:
        """Wait until someone presses the machine's start button; then :meth:`scan` (start=False).

        Parameters
        ----------
        timeout : float
            The longest to wait (s).

        Returns
        -------
        int
            The preset the button started.

        Raises
        ------
        TransportTimeout
            If nobody pressed it within ``timeout``.
        """
        timeout = check_positive("timeout", timeout, "s")
        seen = len(self.events)
        deadline = time.monotonic() + timeout
        with self._io:
            while True:
                for event in self.events[seen:]:
                    if event.event == Event.BUTTON:
                        return event.arg
                seen = len(self.events)
                remaining = deadline - time.monotonic()
                if remaining <= 0:
                    raise TransportTimeout(f"nobody pressed the start button within {timeout} s")
                try:
                    self._read(min(remaining, 0.1))
                except TransportTimeout:
                    continue

    # -- scanning ------------------------------------------------------------------------------
    def _partial(self, scan: _Scan, name: str) -> Sample | None:
        complete = scan.have.all(axis=1)
        rows = int(np.argmin(complete)) if not complete.all() else scan.ny
        if rows == 0:
            return None
        return Sample(scan.image[:rows].copy(), scan.pitch, name,
                      metadata={"device": DEVICE, "rows_finished": rows, "rows": scan.ny,
                                "z_step": scan.z_step})

    def _fetch_line(self, scan: _Scan, row: int) -> None:
        """Ask the device to re-send a line whose pixels were lost (``GL``)."""
        for _ in range(self.retries + 1):
            if scan.have[row].all():
                return
            try:
                self._command(Command.GETLINE, row)
            except DeviceError as exc:
                if exc.code == ErrorCode.BAD_ARGUMENT:
                    raise HardwareError(f"line {row} lost pixels and the device no longer keeps "
                                        f"it (it keeps the last two lines)") from exc
                raise
        if not scan.have[row].all():
            raise HardwareError(f"line {row}: pixels still missing after {self.retries + 1} "
                                f"GL requests")

    def _check_lines(self, scan: _Scan) -> None:
        for row in sorted(scan.ended):
            if not scan.have[row].all():
                self._fetch_line(scan, row)
            scan.ended.discard(row)

    def _serve_requests(self) -> None:
        while True:
            try:
                command, args, done, box = self._requests.get_nowait()
            except queue.Empty:
                return
            try:
                box["result"] = self._command(command, *args)
            except Exception as exc:  # handed to the calling thread
                box["error"] = exc
            done.set()

    def _stalled(self, scan: _Scan) -> None:
        """No pixel for stream_timeout: ask the device where it is."""
        status = self.status()
        if status.state == State.FAULT:
            code = ErrorCode.ESTOP if status.flags & Flag.ESTOP else ErrorCode.LIMIT
            axis = next((a for a, f in (("X", Flag.LIMIT_X), ("Y", Flag.LIMIT_Y),
                                        ("Z", Flag.LIMIT_Z)) if status.flags & f), "")
            scan.fault = DeviceError(int(code), axis, DEVICE)
        elif status.state == State.IDLE:
            scan.ended.update(range(scan.ny))
            self._check_lines(scan)
            if scan.have.all():
                scan.done = True
            else:
                raise HardwareError("the device is idle but the scan is incomplete (its end "
                                    "was lost)")
        elif status.state == State.SCANNING and status.row > 0:
            scan.ended.update(range(max(0, status.row - 1), status.row))

    def scan_iter(self, start: bool = True):
        """Start a scan and yield a :class:`ScanProgress` per pixel as it arrives.

        The generator's return value (``StopIteration.value``; :meth:`scan` returns it) is the
        image as a :class:`~afmsmiler.samples.Sample`: heights in m (z micro-steps x ZS), pixel
        size the pitch DX. An aborted scan returns its finished lines (or None).

        Parameters
        ----------
        start : bool
            Send ``SS``; False follows a scan the machine runs already (its start button, see
            :meth:`wait_button`): the pixels sent before are fetched again with ``GL``.

        Returns
        -------
        generator of ScanProgress

        Raises
        ------
        DeviceError
            If the device faults during the scan (a limit switch, the emergency stop), with the
            finished lines as ``.partial``.
        TransportClosed
            If the cable is unplugged, with ``.partial``.
        DeviceNotResponding
            If the device stops answering, with ``.partial``.
        """
        start = check_flag("start", start)
        info = self._require_info()
        nx, ny = self.get(Param.NX), self.get(Param.NY)
        pitch = TABLE[Param.PITCH].to_si(self.get(Param.PITCH))
        scan = _Scan(nx, ny, pitch, info.z_step)
        self.result = None
        name = f"{DEVICE} scan"
        with self._io:
            self._scan = scan
            self._scan_thread = threading.get_ident()
            try:
                if start:
                    self._command(Command.START)
                last = time.monotonic()
                stalls = 0
                done = 0
                budget = 20 * nx * ny + 10_000  # messages: a device streaming on and on is a bug
                while True:
                    self._serve_requests()
                    if scan.fault is not None:
                        raise scan.fault
                    self._check_lines(scan)
                    while scan.new:
                        px = scan.new.pop(0)
                        done += 1
                        yield ScanProgress(px.row, px.col, px.z * scan.z_step, px.counts, done,
                                           nx * ny, scan.image)
                    if scan.done:
                        scan.ended.update(range(ny))
                        self._check_lines(scan)
                        if not scan.have.all():
                            raise HardwareError("the scan ended with pixels missing")
                        break
                    if scan.aborted:
                        break
                    if time.monotonic() - last > self.stream_timeout:
                        # no progress for stream_timeout, whatever else came: ask the device
                        stalls += 1
                        if stalls > self.retries + 1:
                            raise DeviceNotResponding(
                                f"{DEVICE} sent no pixel for {stalls - 1} waits of "
                                f"{self.stream_timeout:g} s while saying it scans")
                        self._stalled(scan)
                        last = time.monotonic()
                        continue
                    try:
                        msg = self._read(min(self.timeout, 0.1,
                                             max(1e-3, last + self.stream_timeout
                                                 - time.monotonic())))
                    except TransportTimeout:
                        continue
                    if isinstance(msg, (Pixel, LineEnd, EventMsg, ErrorReply)) and \
                            (len(scan.new) or not isinstance(msg, Pixel)):
                        last = time.monotonic()
                        stalls = 0
                    budget -= 1
                    if budget < 0:
                        raise HardwareError(f"{DEVICE} sent far more than the {nx} x {ny} "
                                            f"pixels of the scan: stopping")
            except HardwareError as exc:
                exc.partial = self._partial(scan, name + " (interrupted)")
                self.result = exc.partial
                raise
            except (KeyboardInterrupt, GeneratorExit):  # the user stopped us: stop the machine
                self.result = self._partial(scan, name + " (interrupted)")
                if not (scan.done or scan.aborted):
                    try:
                        self._command(Command.ABORT)
                    except HardwareError:
                        pass
                raise
            finally:
                self._scan = None
                self._scan_thread = None
                self._serve_requests()
        if scan.aborted:
            self.result = self._partial(scan, name + " (aborted)")
        else:
            self.result = Sample(scan.image.copy(), pitch, name,
                                 metadata={"device": DEVICE, "z_step": info.z_step})
        return self.result

    def scan(self, callback=None, *, start: bool = True) -> Sample | None:
        """Scan an image, calling ``callback(progress)`` for each pixel as it arrives.

        Parameters
        ----------
        callback : callable, optional
            Called with a :class:`ScanProgress` per pixel (a live figure redraws
            ``progress.image``); it may call :meth:`pause`, :meth:`resume` or :meth:`abort`.
        start : bool
            Send ``SS`` (False: follow a scan the start button began, see :meth:`scan_iter`).

        Returns
        -------
        Sample or None
            The image (see :meth:`scan_iter`).
        """
        if callback is not None and not callable(callback):
            raise TypeError(f"callback must be callable or None, got {callback!r}")
        it = self.scan_iter(start)
        while True:
            try:
                progress = next(it)
            except StopIteration as stop:
                return stop.value
            if callback is not None:
                callback(progress)

    def save(self, path, sample: Sample | None = None):
        """Write the last scan (or ``sample``) to a Gwyddion ``.gwy`` file (module (f)).

        Parameters
        ----------
        path : str or os.PathLike
            The file, ending in ``.gwy``.
        sample : Sample, optional
            What to save; default the last scan's image (or finished lines).

        Returns
        -------
        pathlib.Path
        """
        from ...samples import save_gwy
        sample = self.result if sample is None else sample
        if sample is None:
            raise HardwareError("no scan to save: scan first (an interrupted scan saves the "
                                "lines it finished)")
        return save_gwy(sample, path)

    def close(self) -> None:
        """Close the transport."""
        self.transport.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
