"""The twin pattern: a device's protocol simulated in Python, served on the far end of a transport.

A :class:`Twin` is the device side of the protocol, pure: it turns a host frame into reply (and
stream) frames, and a time into the stream frames due by then; no threads, no I/O. A
:class:`TwinServer` serves it in a thread on a transport (a :class:`MemoryTransport` end or a
pty's device end), answering malformed lines as the firmware does (``0 ER 1`` checksum,
``0 ER 9`` malformed), so the host's driver cannot tell the twin from a board.
:func:`open_twin` does both in one call.

The base :class:`Twin` implements what every device shares: ``ID`` and safe retries (a command
with the same SEQ and body as the last one executed gets the last reply again, without being
executed twice). Subclasses implement :meth:`Twin.execute` and, for streams, :meth:`Twin.poll`
and :meth:`Twin.next_due`.
"""
from __future__ import annotations

import threading
import time

from ..validation import check_flag, check_finite, check_positive
from .errors import ChecksumError, ErrorCode, FrameError, TransportClosed, TransportTimeout
from .framing import (PROTOCOL_VERSION, Frame, decode_frame, encode_frame, error_frame,
                      reply_frame)
from .transport import MemoryTransport, PtyLink, _check_transport

__all__ = ["Twin", "TwinServer", "open_twin"]


class Twin:
    """The device side of the protocol, pure (no threads, no I/O).

    Subclasses set :attr:`DEVICE` and :attr:`FIRMWARE_VERSION` and implement :meth:`execute`.

    Attributes
    ----------
    now : float
        The twin's clock (s): the latest time given to :meth:`poll`.
    protocol_version : int
        What ``ID`` reports (set another value to play a device with the wrong firmware).
    """

    DEVICE = "TWIN"
    FIRMWARE_VERSION = "0.1.0"

    def __init__(self):
        self.now = 0.0
        self.protocol_version = PROTOCOL_VERSION
        self._last = None  # (seq, code, args) of the last command executed, and its reply
        self._last_reply = None

    # -- helpers for subclasses -------------------------------------------------------------
    @staticmethod
    def _host_frame(frame) -> Frame:
        """``frame``, refused by name unless it is a :class:`Frame` (a twin gets decoded ones)."""
        if not isinstance(frame, Frame):
            raise TypeError(f"frame must be a Frame, got {type(frame).__name__}")
        return frame

    @staticmethod
    def ok(frame: Frame, *results) -> Frame:
        """The OK reply to ``frame``: ``SEQ OK CODE [RESULT ...]``.

        Parameters
        ----------
        frame : Frame
            The host's command.
        *results : int or str
            The reply's results.

        Returns
        -------
        Frame
        """
        return reply_frame(Twin._host_frame(frame).seq, frame.code, *results)

    @staticmethod
    def error(frame: Frame, code: int, word: str | None = None) -> Frame:
        """The error reply to ``frame``: ``SEQ ER ERRNO [WORD]``.

        Parameters
        ----------
        frame : Frame
            The host's command.
        code : int
            The error number.
        word : str, optional
            A word saying more (an axis, a parameter).

        Returns
        -------
        Frame
        """
        return error_frame(Twin._host_frame(frame).seq, code, word)

    # -- the protocol ------------------------------------------------------------------------
    def handle(self, frame: Frame) -> list[Frame]:
        """The frames the device sends for one host frame (its reply last, stream frames first).

        Parameters
        ----------
        frame : Frame
            A valid frame from the host.

        Returns
        -------
        list of Frame
            Nothing for a host stream frame (SEQ 0) unless the device answers it; otherwise
            whatever :meth:`execute` returns, or the last reply again for a retry.
        """
        key = (self._host_frame(frame).seq, frame.code, frame.args)
        if frame.seq != 0 and key == self._last and self._last_reply is not None:
            return [self._last_reply]
        if frame.code == "ID" and frame.seq != 0:
            out = [self.ok(frame, self.DEVICE, self.protocol_version, self.FIRMWARE_VERSION)]
        else:
            out = list(self.execute(frame))
        if frame.seq != 0:
            replies = [f for f in out if f.seq == frame.seq]
            self._last = key
            self._last_reply = replies[-1] if replies else None
        return out

    def execute(self, frame: Frame) -> list[Frame]:
        """Run one (new) host command: the device-specific part of :meth:`handle`.

        Parameters
        ----------
        frame : Frame
            The host's command (not a retry).

        Returns
        -------
        list of Frame
            The frames to send; the reply (same SEQ) must be among them when ``frame.seq != 0``.
        """
        if self._host_frame(frame).seq == 0:
            return []
        return [self.error(frame, ErrorCode.UNKNOWN_COMMAND, frame.code)]

    def poll(self, now: float) -> list[Frame]:
        """The stream frames due by time ``now`` (pixels, events); advances the twin's clock.

        Parameters
        ----------
        now : float
            The twin's time (s); never goes backwards.

        Returns
        -------
        list of Frame
        """
        self.now = max(self.now, check_finite("now", now, "s"))
        return []

    def next_due(self) -> float | None:
        """When the next stream frame is due (s on the twin's clock), ``None`` if none.

        Returns
        -------
        float or None
        """
        return None


class TwinServer:
    """Serve a twin on a transport in a thread, as the firmware serves its serial port.

    Parameters
    ----------
    twin : Twin
        The device to serve.
    transport : Transport
        The device's end of the link (closed by :meth:`stop`).
    time_scale : float
        Real seconds per second of the twin's clock: 1 runs at the real machine's pace, 0 as fast
        as possible (tests: the twin's clock jumps to its next due frame), 0.1 ten times faster.

    Attributes
    ----------
    exception : BaseException or None
        An error the twin raised in the serving thread (re-raised by :meth:`stop`).
    """

    #: The longest one wait for a host line lasts (s): bounds how late stop() is seen.
    SLICE = 0.02

    def __init__(self, twin: Twin, transport, *, time_scale: float = 1.0):
        if not isinstance(twin, Twin):
            raise TypeError(f"twin must be a Twin, got {type(twin).__name__}")
        if isinstance(time_scale, bool) or not isinstance(time_scale, (int, float)) or \
                not 0 <= time_scale <= 1e3:
            raise ValueError(f"time_scale must be in [0, 1000] s per s, got {time_scale!r}")
        self.twin = twin
        self.transport = _check_transport("transport", transport)
        self.time_scale = float(time_scale)
        self.exception = None
        self._stop = threading.Event()
        self._thread = None
        self._resources = []
        self._lock = threading.Lock()

    def start(self) -> "TwinServer":
        """Start serving in a daemon thread.

        Returns
        -------
        TwinServer
            ``self``, so that ``server = TwinServer(...).start()`` reads well.
        """
        if self._thread is not None:
            raise RuntimeError("this TwinServer was already started")
        self._thread = threading.Thread(target=self._run, name=f"TwinServer-{self.twin.DEVICE}",
                                        daemon=True)
        self._thread.start()
        return self

    @property
    def running(self) -> bool:
        """Whether the serving thread is alive."""
        return self._thread is not None and self._thread.is_alive()

    def stop(self, timeout: float = 5.0) -> None:
        """Stop serving, join the thread, close the transport; re-raise the twin's error if any.

        Parameters
        ----------
        timeout : float
            The longest to wait for the thread (s), finite and > 0.
        """
        timeout = check_positive("timeout", timeout, "s")
        self._stop.set()
        self.transport.close()  # wakes a thread waiting to write to a host that does not read
        if self._thread is not None:
            self._thread.join(timeout)
            if self._thread.is_alive():
                raise RuntimeError(f"TwinServer thread did not stop within {timeout} s")
        for resource in self._resources:
            resource.close()
        if self.exception is not None:
            exc, self.exception = self.exception, None
            raise exc

    def __enter__(self):
        if self._thread is None:
            self.start()
        return self

    def __exit__(self, *exc):
        self.stop()

    def _send(self, frames) -> None:
        for frame in frames:
            data = encode_frame(frame)
            while True:  # a host that does not read makes the device wait, as a full buffer
                try:
                    self.transport.write(data)
                    break
                except TransportTimeout:
                    if self._stop.is_set():
                        return

    def _run(self) -> None:
        twin, scale = self.twin, self.time_scale
        origin = time.monotonic() - twin.now * scale
        try:
            while not self._stop.is_set():
                if scale > 0:
                    twin_now = (time.monotonic() - origin) / scale
                else:
                    twin_now = twin.now
                self._send(twin.poll(twin_now))
                due = twin.next_due()
                if due is None:
                    wait = self.SLICE
                elif scale > 0:
                    wait = min(self.SLICE, max(0.0, (due - twin_now) * scale))
                else:
                    wait = 0.0
                try:
                    line = self.transport.readline(wait)
                except TransportTimeout:
                    if scale == 0 and due is not None:
                        self._send(twin.poll(max(twin.now, due)))
                    continue
                try:
                    frame = decode_frame(line)
                except ChecksumError:
                    self._send([error_frame(0, ErrorCode.CHECKSUM)])
                    continue
                except FrameError:
                    self._send([error_frame(0, ErrorCode.MALFORMED)])
                    continue
                if scale > 0:
                    # the clock at arrival: what fell due before the command goes out first
                    self._send(twin.poll((time.monotonic() - origin) / scale))
                self._send(twin.handle(frame))
        except TransportClosed:
            pass  # the host went away: the device just stops serving
        except BaseException as exc:  # a bug in the twin: surfaced by stop()
            self.exception = exc


#: Bytes the in-memory link holds unread per direction (a board's serial buffers): a twin at
#: time_scale 0 runs at most this far ahead of its host, as a real device at its own pace would.
LINK_CAPACITY = 256


def open_twin(twin: Twin, *, pty: bool = False, time_scale: float = 0.0):
    """Serve ``twin`` on a new link and return the host's side of it.

    Parameters
    ----------
    twin : Twin
        The device to serve.
    pty : bool
        Serve on a pseudo-terminal (the host gets a path that pyserial opens like a real port)
        instead of an in-memory pair.
    time_scale : float
        See :class:`TwinServer` (0: as fast as possible).

    Returns
    -------
    host : MemoryTransport or str
        The host's transport, or the pty's path when ``pty``.
    server : TwinServer
        The running server; ``server.stop()`` ends it and closes the link.

    Examples
    --------
    >>> host, server = open_twin(Twin())
    >>> host.write(b"1 ID*C1\\n"); host.readline(1.0)
    b'1 OK ID TWIN 1 0.1.0*E3'
    >>> server.stop(); host.close()
    """
    pty = check_flag("pty", pty)
    if pty:
        link = PtyLink()
        server = TwinServer(twin, link.device_end, time_scale=time_scale)
        server._resources.append(link)
        return link.path, server.start()
    host, device = MemoryTransport.pair(capacity=LINK_CAPACITY)
    server = TwinServer(twin, device, time_scale=time_scale)
    return host, server.start()
