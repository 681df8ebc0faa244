"""The educational AFM's driver: connect, configure, scan into a Sample and a live height field.

:class:`EducationalAFM` takes a transport (never opens a port itself): a
:class:`~afmsmiler.hardware.SerialTransport` to the instrument, or the host end of
:func:`~afmsmiler.hardware.open_twin` serving :class:`EducationalAFMTwin`. Every read has a
timeout; a command is retried with the same SEQ (safe: the device re-sends its last reply
instead of running a command twice) after a timeout, a ``0 ER 1``/``0 ER 9`` (the device got a
damaged line) or a damaged reply; pixels lost on the way are fetched again with ``GL`` when their
line ends. A scan interrupted by a fault, an unplugged cable or a silent device raises with the
finished lines attached as ``.partial`` (a :class:`~afmsmiler.samples.Sample`).
"""
from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Callable

import numpy as np

from ...samples import Sample
from ...validation import check_integer, check_positive
from ..protocol import _lookup
from ..errors import (RESEND_CODES, DeviceError, DeviceNotResponding, HardwareError, ReplyError,
                      TransportClosed, TransportTimeout)
from ..framed import FramedDevice
from ..framing import Frame, reply_frame
from .codec import DEVICE, TABLE, Command, ErrorCode, Event, Param, State, command

__all__ = ["EducationalAFM", "DeviceInfo", "live_view"]


@dataclass(frozen=True)
class DeviceInfo:
    """What ``ID`` and the read-only parameters say.

    Parameters
    ----------
    device : str
        ``"EDUAFM"``.
    protocol : int
        Protocol version.
    firmware : str
        Firmware version.
    z_step : float
        Height per count in m (ZS).
    """

    device: str
    protocol: int
    firmware: str
    z_step: float


def live_view(scene) -> Callable:
    """An ``on_line`` callback that draws the finished rows in module (f)'s 3D height field.

    Parameters
    ----------
    scene : afmsmiler.scenes.imaging.ImagingScene
        The scene (its image field on the right is replaced as lines finish).

    Returns
    -------
    callable
        ``on_line(image, lines)``: ``image`` the Sample of rows 0..k, ``lines`` the full count.
    """
    if not callable(getattr(scene, "show_image", None)):  # named now, not at the first line
        raise TypeError(f"scene must have show_image(image, lines=...) (an ImagingScene), got "
                        f"{type(scene).__name__} {scene!r}"[:160])

    def on_line(image: Sample, lines: int) -> None:
        scene.show_image(image, lines=lines)
    return on_line


class EducationalAFM(FramedDevice):
    """The educational AFM on a transport.

    Parameters
    ----------
    transport : Transport
        The link (write, readline(timeout), close).
    timeout : float
        Longest wait for a command's reply in s, per attempt (one deadline, whatever the device
        sends meanwhile); also the longest a scan waits for progress before it asks the status.
    retries : int
        Retries of a command before :class:`DeviceNotResponding`.

    Attributes
    ----------
    stats : dict
        ``retries`` (commands sent again), ``bad_lines`` (lines that were not frames) and
        ``refetched_lines`` (lines asked again with ``GL``).

    Examples
    --------
    >>> from afmsmiler.hardware import open_twin
    >>> from afmsmiler.samples import particles
    >>> from afmsmiler.hardware.educational import EducationalAFMTwin
    >>> twin = EducationalAFMTwin(particles(shape=(64, 64), pixel_size=20e-9, seed=1))
    >>> host, server = open_twin(twin)
    >>> afm = EducationalAFM(host, timeout=0.5)
    >>> afm.connect().device
    'EDUAFM'
    >>> afm.configure(pixels=8, lines=4, pitch=50e-9); afm.scan().shape
    (4, 8)
    >>> server.stop(); host.close()
    """

    DEVICE = DEVICE
    TABLE = TABLE

    def __init__(self, transport, *, timeout: float = 1.0, retries: int = 3):
        super().__init__(transport, timeout=timeout, retries=retries)
        self.info = None
        self._refetched = 0
        self._on_stream = None
        self._params = {}

    @property
    def stats(self) -> dict:
        """Counts of the link's troubles: retries, bad lines, refetched lines."""
        return {"retries": self.retried, "bad_lines": self.garbage,
                "refetched_lines": self._refetched}

    # -- the link --------------------------------------------------------------------------
    def _stream(self, frame: Frame) -> None:
        if self._on_stream is not None:
            self._on_stream(frame)

    def request(self, code: Command, *args) -> Frame:
        """Send a command and return its OK reply, retrying where the protocol makes it safe.

        The reply is awaited until one deadline per attempt (``timeout`` after the send),
        whatever the device sends meanwhile: a request lasts at most
        ``(retries + 1) * timeout``.

        Parameters
        ----------
        code : Command
            The command.
        *args : int or str or Param
            Its arguments.

        Returns
        -------
        Frame
            The ``SEQ OK CODE ...`` reply.

        Raises
        ------
        DeviceError
            If the device answers ``ER`` (its number and word attached).
        DeviceNotResponding
            If no valid reply comes after ``retries`` retries.
        TransportClosed
            If the link is gone.
        """
        frame = command(1, code, *args)
        results = self._exchange(frame.code, *frame.args)
        return reply_frame(self._seq, frame.code, *results)

    # -- commands --------------------------------------------------------------------------
    def connect(self) -> DeviceInfo:
        """Identify the device (protocol version check) and read ZS.

        Returns
        -------
        DeviceInfo

        Raises
        ------
        ProtocolVersionError
            If the device speaks another protocol version.
        HardwareError
            If it is not an EDUAFM.
        ReplyError
            If its replies are not of the protocol's shape, or ZS is outside the table's range.
        """
        _, version, firmware = self._identify()
        z_step = TABLE[Param.ZSTEP].to_si(self.get(Param.ZSTEP))
        self.info = DeviceInfo(DEVICE, version, firmware, z_step)
        return self.info

    def set(self, par: Param, value: int) -> int:
        """Set a parameter (an integer in the unit of :data:`~.codec.TABLE`).

        Parameters
        ----------
        par : Param
            The parameter.
        value : int
            Its value.

        Returns
        -------
        int
            The value the device took (checked against the table).

        Raises
        ------
        ValueError
            If the value is outside the table's range or the parameter is read-only (nothing
            sent).
        """
        return self._set_wire(_lookup("par", Param, par).value, value)

    def get(self, par: Param) -> int:
        """Read a parameter.

        Parameters
        ----------
        par : Param
            The parameter.

        Returns
        -------
        int
            Checked against the table (:class:`ReplyError` if the device reports a value
            outside it).
        """
        return self._get_wire(_lookup("par", Param, par).value)

    def configure(self, *, pixels: int = TABLE[Param.NX].default, lines: int | None = None,
                  pitch: float = TABLE[Param.PITCH].to_si(TABLE[Param.PITCH].default)) -> None:
        """Set the scan: pixels per line, lines and pixel spacing (m, sent in whole nm).

        The ranges are those of :data:`~.codec.TABLE` (the protocol's).

        Parameters
        ----------
        pixels : int
            Pixels per line, 2..512.
        lines : int, optional
            Lines, 1..512; default ``pixels``.
        pitch : float
            Pixel spacing in m (1 nm to 100 um).

        Raises
        ------
        ValueError
            Naming the parameter, its value and the valid range (nothing sent).
        """
        nx, ny, dx = TABLE[Param.NX], TABLE[Param.NY], TABLE[Param.PITCH]
        pixels = check_integer("pixels", pixels, nx.low, nx.high)
        lines = pixels if lines is None else check_integer("lines", lines, ny.low, ny.high)
        nm = dx.to_wire(check_positive("pitch", pitch, "m"))
        self._params = {Param.NX: self.set(Param.NX, pixels), Param.NY: self.set(Param.NY, lines),
                        Param.PITCH: self.set(Param.PITCH, nm)}

    def abort(self) -> None:
        """Stop a running scan."""
        self.request(Command.ABORT)

    def _status(self) -> tuple:
        """``ST``: (state, row, col), checked."""
        results = self.request(Command.STATUS).args[1:]
        if len(results) != 3 or results[0] not in {s.value for s in State} or \
                not all(isinstance(v, int) for v in results[1:]):
            raise ReplyError(f"{DEVICE}'s ST reply must be <IDLE|SCANNING|FAULT> <row> <col>, "
                             f"got {tuple(results)!r}")
        return tuple(results)

    def scan(self, *, on_pixel: Callable | None = None,
             on_line: Callable | None = None) -> Sample:
        """Start a scan and collect its pixels into a Sample (heights in m).

        The scan waits at most ``timeout`` for progress (a new pixel, a line's end, an event),
        whatever else the device sends; then it asks the device's status, and a device that made
        no progress between two such checks (or over ``retries + 1`` of them) has stopped.

        Parameters
        ----------
        on_pixel : callable, optional
            ``on_pixel(row, col, height)`` for each pixel as it arrives (m).
        on_line : callable, optional
            ``on_line(image, lines)`` after each finished line: ``image`` the Sample of the
            finished rows, ``lines`` the image's row count (see :func:`live_view`).

        Returns
        -------
        Sample
            The image, pixel size DX.

        Raises
        ------
        DeviceError
            If the scan faults (``.partial``: the finished lines).
        DeviceNotResponding
            If the device goes silent or makes no progress (``.partial``).
        TransportClosed
            If the link goes away (``.partial``).
        ReplyError
            If the device reports a scan size outside the protocol's table.
        """
        for name, func in (("on_pixel", on_pixel), ("on_line", on_line)):
            if func is not None and not callable(func):
                raise TypeError(f"{name} must be None or a callable, got {type(func).__name__}")
        if self.info is None:
            self.connect()
        if not self._params:
            self._params = {p: self.get(p) for p in (Param.NX, Param.NY, Param.PITCH)}
        nx, ny = self._params[Param.NX], self._params[Param.NY]
        pitch = TABLE[Param.PITCH].to_si(self._params[Param.PITCH])
        counts = np.full((ny, nx), np.nan)
        state = {"done": False, "finished": 0, "fault": None, "aborted": False, "new": False}

        def image(rows: int) -> Sample | None:
            if rows < 1:
                return None
            h = counts[:rows] * self.info.z_step
            if h.size < 2:
                return None
            return Sample(h, pitch, name=f"{DEVICE} scan", metadata={
                "lines_done": rows, "pixels": nx, "lines": ny})

        def finish_rows(upto: int) -> None:
            """Rows below ``upto`` are over: fetch lost pixels, then report each finished row."""
            while state["finished"] < min(upto, ny):
                row = state["finished"]
                for _ in range(self.retries + 1):     # GL is idempotent: ask again if its
                    if not np.isnan(counts[row]).any():  # own pixels were damaged on the way
                        break
                    self._refetched += 1
                    self.request(Command.GETLINE, row)
                if np.isnan(counts[row]).any():
                    raise DeviceNotResponding(f"line {row} is still incomplete after "
                                              f"{self.retries + 1} GL requests")
                state["finished"] += 1
                if on_line is not None:
                    on_line(image(state["finished"]), ny)

        def stream(frame: Frame) -> None:
            args = frame.args
            if frame.code == "PX":
                if len(args) == 3 and all(isinstance(a, int) for a in args) and \
                        0 <= args[0] < ny and 0 <= args[1] < nx:
                    row, col, z = args
                    state["new"] |= bool(np.isnan(counts[row, col]))
                    counts[row, col] = z
                    if on_pixel is not None:
                        on_pixel(row, col, z * self.info.z_step)
                else:
                    self.garbage += 1
            elif frame.code == "EV" and frame.args:
                if frame.args[0] == Event.DONE:
                    state["done"] = True
                elif frame.args[0] == Event.ABORTED:
                    state["aborted"] = True
                elif frame.args[0] == Event.FAULT:
                    state["fault"] = ErrorCode.SENSOR
            elif frame.code == "ER" and frame.args and frame.args[0] not in RESEND_CODES:
                state["fault"] = frame.args[0] if isinstance(frame.args[0], int) \
                    else ErrorCode.SENSOR
        self._on_stream = stream
        pending = []                       # line ends seen, handled outside the stream callback
        last_status = None
        quiet = 0                          # status checks since the last new pixel
        try:
            self.request(Command.START)
            deadline = time.monotonic() + self.timeout       # of the next progress
            while not state["done"]:
                if state["fault"] is not None:
                    raise DeviceError(state["fault"], "", device=DEVICE, command="")
                if state["aborted"]:
                    raise HardwareError(f"the {DEVICE} scan was aborted")
                left = deadline - time.monotonic()
                try:
                    if left <= 0:
                        raise TransportTimeout(f"{DEVICE} made no progress for "
                                               f"{self.timeout:g} s")
                    frame = self._receive(left)
                except TransportTimeout:
                    # quiet: the end event may have been lost, or the device stopped; ask it
                    status = self._status()
                    quiet += 1
                    if status[0] == State.IDLE.value:
                        break                         # finished: DONE was lost on the way
                    if status[0] == State.FAULT.value:
                        state["fault"] = ErrorCode.SENSOR
                    elif status == last_status or quiet > self.retries + 1:
                        raise DeviceNotResponding(f"{DEVICE} made no progress for "
                                                  f"{quiet * self.timeout:g} s (at row "
                                                  f"{status[1]}, col {status[2]})") from None
                    last_status = status
                    deadline = time.monotonic() + self.timeout
                    continue
                if frame is None:
                    continue
                if frame.code == "LN" and len(frame.args) == 2 and \
                        all(isinstance(a, int) for a in frame.args):
                    pending.append(min(max(frame.args[0], -1), ny))
                else:
                    stream(frame)
                if state["new"]:                      # progress: the deadline moves on
                    state["new"], quiet = False, 0
                    deadline = time.monotonic() + self.timeout
                if pending:
                    finish_rows(max(pending) + 1)
                    pending.clear()
                elif frame.code == "PX" and len(frame.args) == 3 and \
                        isinstance(frame.args[0], int) and state["finished"] < frame.args[0] < ny:
                    finish_rows(frame.args[0])      # a line end was lost on the way
            finish_rows(ny)
        except (HardwareError, TransportClosed) as exc:
            exc.partial = image(state["finished"])
            raise
        finally:
            self._on_stream = None
        return image(ny)

    def close(self) -> None:
        """Close the transport."""
        self.transport.close()
