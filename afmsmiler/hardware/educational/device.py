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

from dataclasses import dataclass
from typing import Callable

import numpy as np

from ...samples import Sample
from ...validation import check_integer, check_positive
from ..errors import (DeviceError, DeviceNotResponding, FrameError, HardwareError,
                      ProtocolVersionError, TransportClosed, TransportTimeout)
from ..framing import PROTOCOL_VERSION, Frame, decode_frame, encode_frame
from .codec import DEVICE, Command, ErrorCode, Event, Param, State, command

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
    def on_line(image: Sample, lines: int) -> None:
        scene.show_image(image, lines=lines)
    return on_line


class EducationalAFM:
    """The educational AFM on a transport.

    Parameters
    ----------
    transport : Transport
        The link (write, readline(timeout), close).
    timeout : float
        Longest wait for one line in s.
    retries : int
        Retries of a command before :class:`DeviceNotResponding`.

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

    def __init__(self, transport, *, timeout: float = 1.0, retries: int = 3):
        for method in ("write", "readline", "close"):
            if not callable(getattr(transport, method, None)):
                raise TypeError(f"transport must have {method}(), got {type(transport).__name__}")
        self.transport = transport
        self.timeout = check_positive("timeout", timeout, "s")
        self.retries = check_integer("retries", retries, 0, 100)
        self.info = None
        self._seq = 0
        self.stats = {"retries": 0, "bad_lines": 0, "refetched_lines": 0}
        self._on_stream = None
        self._params = {}

    # -- the link --------------------------------------------------------------------------
    def _next_seq(self) -> int:
        self._seq = self._seq % 255 + 1
        return self._seq

    def _read(self) -> Frame | None:
        """One frame, or None for a damaged line (TransportTimeout/Closed propagate)."""
        line = self.transport.readline(self.timeout)
        try:
            return decode_frame(line)
        except FrameError:
            self.stats["bad_lines"] += 1
            return None

    def _stream(self, frame: Frame) -> None:
        if self._on_stream is not None:
            self._on_stream(frame)

    def request(self, code: Command, *args) -> Frame:
        """Send a command and return its OK reply, retrying where the protocol makes it safe.

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
        frame = command(self._next_seq(), code, *args)
        data = encode_frame(frame)
        for attempt in range(self.retries + 1):
            if attempt:
                self.stats["retries"] += 1
            self.transport.write(data)
            while True:
                try:
                    reply = self._read()
                except TransportTimeout:
                    break                             # retry the same SEQ
                if reply is None:
                    continue                          # a damaged line: maybe our reply; wait
                if reply.seq == 0:
                    if reply.code == "ER" and reply.args and reply.args[0] in (
                            ErrorCode.CHECKSUM, ErrorCode.MALFORMED):
                        break                         # our command arrived damaged: resend
                    self._stream(reply)
                    continue
                if reply.seq != frame.seq:
                    continue                          # a late reply to an earlier try
                if reply.code == "ER":
                    number = int(reply.args[0]) if reply.args else 0
                    word = str(reply.args[1]) if len(reply.args) > 1 else ""
                    raise DeviceError(number, word, device=DEVICE, command=frame.code)
                return reply
        raise DeviceNotResponding(f"{DEVICE} did not answer {frame.code} after "
                                  f"{self.retries + 1} tries of {self.timeout:g} s")

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
        """
        reply = self.request(Command.IDENTIFY)
        _, name, version, firmware = (list(reply.args) + ["", "", ""])[:4]
        if name != DEVICE:
            raise HardwareError(f"the device is a {name!r}, not an {DEVICE}")
        if version != PROTOCOL_VERSION:
            raise ProtocolVersionError(version, PROTOCOL_VERSION, device=DEVICE)
        z_step = self.get(Param.ZSTEP) * 1e-12
        self.info = DeviceInfo(DEVICE, int(version), str(firmware), z_step)
        return self.info

    def set(self, par: Param, value: int) -> int:
        """Set a parameter (an integer in the unit PROTOCOL.md names).

        Parameters
        ----------
        par : Param
            The parameter.
        value : int
            Its value.
        """
        return int(self.request(Command.SET, Param(par), int(value)).args[2])

    def get(self, par: Param) -> int:
        """Read a parameter.

        Parameters
        ----------
        par : Param
            The parameter.
        """
        return int(self.request(Command.GET, Param(par)).args[2])

    def configure(self, *, pixels: int = 32, lines: int | None = None,
                  pitch: float = 20e-9) -> None:
        """Set the scan: pixels per line, lines and pixel spacing (m, sent in whole nm).

        Parameters
        ----------
        pixels : int
            Pixels per line, 2..512.
        lines : int, optional
            Lines, 1..512; default ``pixels``.
        pitch : float
            Pixel spacing in m (1 nm to 100 um).
        """
        pixels = check_integer("pixels", pixels, 2, 512)
        lines = pixels if lines is None else check_integer("lines", lines, 1, 512)
        nm = int(round(check_positive("pitch", pitch, "m") * 1e9))
        if not 1 <= nm <= 100_000:
            raise ValueError(f"pitch must be 1 nm to 100 um, got {pitch:g} m")
        self._params = {Param.NX: self.set(Param.NX, pixels), Param.NY: self.set(Param.NY, lines),
                        Param.PITCH: self.set(Param.PITCH, nm)}

    def abort(self) -> None:
        """Stop a running scan."""
        self.request(Command.ABORT)

    def scan(self, *, on_pixel: Callable | None = None,
             on_line: Callable | None = None) -> Sample:
        """Start a scan and collect its pixels into a Sample (heights in m).

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
            If the device goes silent (``.partial``).
        TransportClosed
            If the link goes away (``.partial``).
        """
        if self.info is None:
            self.connect()
        if not self._params:
            self._params = {p: self.get(p) for p in (Param.NX, Param.NY, Param.PITCH)}
        nx, ny = self._params[Param.NX], self._params[Param.NY]
        pitch = self._params[Param.PITCH] * 1e-9
        counts = np.full((ny, nx), np.nan)
        state = {"done": False, "finished": 0, "fault": None, "aborted": False}

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
                    self.stats["refetched_lines"] += 1
                    self.request(Command.GETLINE, row)
                if np.isnan(counts[row]).any():
                    raise DeviceNotResponding(f"line {row} is still incomplete after "
                                              f"{self.retries + 1} GL requests")
                state["finished"] += 1
                if on_line is not None:
                    on_line(image(state["finished"]), ny)

        def stream(frame: Frame) -> None:
            if frame.code == "PX" and len(frame.args) == 3:
                row, col, z = frame.args
                if 0 <= row < ny and 0 <= col < nx:
                    counts[row, col] = z
                    if on_pixel is not None:
                        on_pixel(row, col, z * self.info.z_step)
            elif frame.code == "EV" and frame.args:
                if frame.args[0] == Event.DONE:
                    state["done"] = True
                elif frame.args[0] == Event.ABORTED:
                    state["aborted"] = True
                elif frame.args[0] == Event.FAULT:
                    state["fault"] = ErrorCode.SENSOR
            elif frame.code == "ER" and frame.args and frame.args[0] not in (
                    ErrorCode.CHECKSUM, ErrorCode.MALFORMED):   # a late answer to a bad line
                state["fault"] = int(frame.args[0])
        self._on_stream = stream
        pending = []                       # line ends seen, handled outside the stream callback
        last_status = None
        try:
            self.request(Command.START)
            while not state["done"]:
                if state["fault"] is not None:
                    raise DeviceError(state["fault"], "", device=DEVICE, command="")
                if state["aborted"]:
                    raise HardwareError(f"the {DEVICE} scan was aborted")
                try:
                    frame = self._read()
                except TransportTimeout:
                    # quiet: the end event may have been lost, or the device stopped; ask it
                    status = self.request(Command.STATUS).args[1:]
                    if status[0] == State.IDLE.value:
                        break                         # finished: DONE was lost on the way
                    if status[0] == State.FAULT.value:
                        state["fault"] = ErrorCode.SENSOR
                    elif status == last_status:
                        raise DeviceNotResponding(f"{DEVICE} made no progress for "
                                                  f"{2 * self.timeout:g} s (at row "
                                                  f"{status[1]}, col {status[2]})") from None
                    last_status = status
                    continue
                if frame is None:
                    continue
                if frame.code == "LN" and len(frame.args) == 2:
                    pending.append(int(frame.args[0]))
                else:
                    stream(frame)
                if pending:
                    finish_rows(max(pending) + 1)
                    pending.clear()
                elif frame.code == "PX" and frame.args[0] > state["finished"]:
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
