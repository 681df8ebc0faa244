"""Transports: a line-oriented byte pipe to a device (a serial port, a pty, memory), and faults.

Every transport has the same three methods (:class:`Transport`): ``write(bytes)``,
``readline(timeout)`` (one line without its ``\\n``; a ``\\r`` before it is dropped) and
``close()``. A read never blocks longer than its timeout (:class:`TransportTimeout`); a port that
is unplugged or a far end that has gone raises :class:`TransportClosed`. A run of more than
:data:`MAX_LINE` bytes without a newline is returned as one (junk) line, so that the frame decoder
rejects it instead of the buffer growing without bound.

- :class:`MemoryTransport` -- ``MemoryTransport.pair()``: two connected ends in one process
  (thread-safe), for a twin served in a thread.
- :class:`SerialTransport` -- a real port through pyserial (``/dev/ttyACM0``, ``COM3``, or a pty).
- :class:`PtyLink` -- a pseudo-terminal: pyserial opens ``.path`` like a real port while a twin
  serves ``.device_end``; the notebook cannot tell it from a board.
- :class:`FaultyTransport` -- wraps another transport and injects the faults of a real cable
  (corrupted bytes, garbage, partial and dropped lines, an unplug, a device gone silent),
  deterministically from a seed.
"""
from __future__ import annotations

import os
import random
import select
import threading
import time
import tty
from typing import Protocol, runtime_checkable

from ..validation import check_flag, check_integer, check_real
from .errors import TransportClosed, TransportTimeout
from .framing import as_bytes

__all__ = ["MAX_LINE", "Transport", "MemoryTransport", "SerialTransport", "PtyLink",
           "FaultyTransport"]

#: A run of more bytes than this without a newline is returned as one junk line.
MAX_LINE = 256
#: The longest a single write may wait for the far end to take its bytes (s).
WRITE_TIMEOUT = 2.0


@runtime_checkable
class Transport(Protocol):
    """What a device class needs from a link to its device."""

    def write(self, data: bytes) -> None:
        """Send ``data`` (raises TransportClosed if the link is gone)."""

    def readline(self, timeout: float) -> bytes:
        """One line without ``\\n`` within ``timeout`` s (TransportTimeout/TransportClosed)."""

    def close(self) -> None:
        """Close the link (idempotent)."""


def _check_timeout(timeout) -> float:
    timeout = check_real("timeout", timeout)  # a str, a bool, 10**400: named
    if not timeout >= 0 or timeout == float("inf"):
        raise ValueError(f"timeout must be a finite number of seconds >= 0, got {timeout!r}")
    return timeout


def _check_transport(name: str, transport):
    """``transport``, refused naming ``name`` unless it has ``write``, ``readline`` and ``close``.

    Parameters
    ----------
    name : str
        The parameter's name, for the message.
    transport : Transport
        The link to check.

    Returns
    -------
    Transport

    Raises
    ------
    TypeError
        Naming ``name`` for an object without the three methods.
    """
    for method in ("write", "readline", "close"):
        if not callable(getattr(transport, method, None)):
            raise TypeError(f"{name} must be a transport (write/readline/close), got "
                            f"{type(transport).__name__}")
    return transport


def _take_line(buf: bytearray) -> bytes | None:
    """Remove and return the first complete line of ``buf`` (or a junk run), else None."""
    end = buf.find(b"\n")
    if end < 0 or end > MAX_LINE:
        if len(buf) > MAX_LINE:
            line = bytes(buf[:MAX_LINE])
            del buf[:MAX_LINE]
            return line
        return None
    line = bytes(buf[:end])
    del buf[:end + 1]
    return line[:-1] if line.endswith(b"\r") else line


class _Channel:
    """One direction of a memory pair: a byte buffer behind a condition variable."""

    def __init__(self, capacity: int | None = None):
        self.cond = threading.Condition()
        self.buf = bytearray()
        self.closed = False
        self.capacity = capacity


class MemoryTransport:
    """One end of an in-process link; make both ends with :meth:`pair`.

    Parameters
    ----------
    inbound : _Channel
        The channel this end reads (the other end writes it).
    outbound : _Channel
        The channel this end writes.
    """

    def __init__(self, inbound: _Channel, outbound: _Channel):
        self._in = inbound
        self._out = outbound

    @classmethod
    def pair(cls, capacity: int | None = None) -> tuple["MemoryTransport", "MemoryTransport"]:
        """Two connected ends: what one writes, the other reads.

        Parameters
        ----------
        capacity : int, optional
            Bytes each direction holds unread before a write waits for the reader (as a serial
            port's buffers make a fast device wait for its host); None: unbounded. A write that
            waits longer than WRITE_TIMEOUT raises TransportTimeout.

        Returns
        -------
        tuple of MemoryTransport
            ``(host_end, device_end)``; closing either closes the link for both.
        """
        if capacity is not None:
            capacity = check_integer("capacity", capacity, 1, 2 ** 31)
        a_to_b, b_to_a = _Channel(capacity), _Channel(capacity)
        return cls(b_to_a, a_to_b), cls(a_to_b, b_to_a)

    def write(self, data: bytes) -> None:
        """Send ``data`` to the other end.

        Parameters
        ----------
        data : bytes
            The bytes to send (usually one encoded frame).

        Raises
        ------
        TypeError
            If ``data`` is not bytes.
        TransportClosed
            If either end has been closed.
        """
        data = as_bytes("data", data)
        out = self._out
        deadline = time.monotonic() + WRITE_TIMEOUT
        with out.cond:
            while True:
                if out.closed or self._in.closed:
                    raise TransportClosed("the memory link is closed")
                if out.capacity is None or len(out.buf) < out.capacity:
                    break
                remaining = deadline - time.monotonic()
                if remaining <= 0:
                    raise TransportTimeout(f"the reader took no bytes for {WRITE_TIMEOUT} s")
                out.cond.wait(min(remaining, 0.05))
            out.buf += data
            out.cond.notify_all()

    def readline(self, timeout: float) -> bytes:
        """The next line from the other end.

        Parameters
        ----------
        timeout : float
            The longest to wait for a complete line (s); 0 only takes a line already there.

        Returns
        -------
        bytes
            The line without ``\\n`` (and without a ``\\r`` before it).

        Raises
        ------
        TransportTimeout
            If no complete line arrived within ``timeout``.
        TransportClosed
            If the link is closed and no complete line is left.
        """
        deadline = time.monotonic() + _check_timeout(timeout)
        with self._in.cond:
            while True:
                line = _take_line(self._in.buf)
                if line is not None:
                    self._in.cond.notify_all()  # a writer may wait for room
                    return line
                if self._in.closed:
                    raise TransportClosed("the memory link is closed")
                remaining = deadline - time.monotonic()
                if remaining <= 0:
                    raise TransportTimeout(f"no complete line within {timeout} s")
                self._in.cond.wait(min(remaining, 1.0))  # 1e300 s would overflow the lock

    def close(self) -> None:
        """Close both directions (the other end's reads raise TransportClosed once drained)."""
        for channel in (self._in, self._out):
            with channel.cond:
                channel.closed = True
                channel.cond.notify_all()


class SerialTransport:
    """A serial port through pyserial: an Arduino's USB port, or a pty that a twin serves.

    Parameters
    ----------
    port : str
        The port's name (``/dev/ttyACM0``, ``COM3``, a :class:`PtyLink`'s ``.path``).
    baudrate : int
        Bits per second (the devices of module (h) use 115200, 8N1).
    read_slice : float
        The port's read timeout (s): ``readline`` waits in slices of this length, so that no
        read blocks longer than its own timeout plus one slice.
    write_timeout : float
        The port's write timeout (s).

    Raises
    ------
    TransportClosed
        If the port cannot be opened (absent, unplugged, or in use).
    """

    def __init__(self, port: str, *, baudrate: int = 115200, read_slice: float = 0.02,
                 write_timeout: float = WRITE_TIMEOUT):
        import serial  # pyserial, imported here so that the pure modules do not need it

        self._serial_mod = serial
        self.port = str(port)
        self._buf = bytearray()
        self._lock = threading.Lock()
        try:
            self._port = serial.Serial(self.port, baudrate=int(baudrate), bytesize=8,
                                       parity="N", stopbits=1, timeout=_check_timeout(read_slice),
                                       write_timeout=_check_timeout(write_timeout))
        except (serial.SerialException, OSError, ValueError) as exc:
            raise TransportClosed(f"cannot open serial port {self.port}: {exc}") from exc

    def _closed(self, exc) -> TransportClosed:
        return TransportClosed(f"serial port {self.port} is closed or was unplugged: {exc}")

    def write(self, data: bytes) -> None:
        """Send ``data`` on the port.

        Parameters
        ----------
        data : bytes
            The bytes to send.

        Raises
        ------
        TransportTimeout
            If the port did not take the bytes within its write timeout.
        TransportClosed
            If the port is closed or was unplugged.
        """
        serial = self._serial_mod
        try:
            self._port.write(as_bytes("data", data))
        except serial.SerialTimeoutException as exc:
            raise TransportTimeout(f"serial port {self.port}: write timed out") from exc
        except (serial.SerialException, OSError, TypeError, AttributeError) as exc:
            raise self._closed(exc) from exc

    def readline(self, timeout: float) -> bytes:
        """The next line from the port.

        Parameters
        ----------
        timeout : float
            The longest to wait for a complete line (s).

        Returns
        -------
        bytes
            The line without ``\\n`` (and without a ``\\r`` before it).

        Raises
        ------
        TransportTimeout
            If no complete line arrived within ``timeout``.
        TransportClosed
            If the port is closed or was unplugged.
        """
        serial = self._serial_mod
        deadline = time.monotonic() + _check_timeout(timeout)
        with self._lock:
            while True:
                line = _take_line(self._buf)
                if line is not None:
                    return line
                try:
                    waiting = self._port.in_waiting
                    if waiting or time.monotonic() < deadline:
                        chunk = self._port.read(max(1, waiting))  # waits at most one slice
                    else:
                        chunk = None
                except (serial.SerialException, OSError, TypeError, AttributeError) as exc:
                    raise self._closed(exc) from exc
                if chunk is None:
                    raise TransportTimeout(f"serial port {self.port}: no complete line "
                                           f"within {timeout} s")
                self._buf += chunk

    def close(self) -> None:
        """Close the port (idempotent)."""
        try:
            self._port.close()
        except (self._serial_mod.SerialException, OSError):
            pass


class _FdTransport:
    """A transport over a raw file descriptor (the master side of a pty).

    Parameters
    ----------
    fd : int
        The open descriptor; it is made non-blocking and is closed by :meth:`close`.
    name : str
        What to call it in error messages.
    """

    def __init__(self, fd: int, name: str = "pty"):
        self._fd = fd
        self._name = name
        self._buf = bytearray()
        self._closed = False
        os.set_blocking(fd, False)

    def write(self, data: bytes) -> None:
        """Send ``data``, waiting at most WRITE_TIMEOUT for the far end to take it.

        Parameters
        ----------
        data : bytes
            The bytes to send.
        """
        view = memoryview(as_bytes("data", data))
        deadline = time.monotonic() + WRITE_TIMEOUT
        while view:
            if self._closed:
                raise TransportClosed(f"{self._name} is closed")
            try:
                sent = os.write(self._fd, view)
                view = view[sent:]
                continue
            except BlockingIOError:
                pass
            except OSError as exc:
                raise TransportClosed(f"{self._name} is closed: {exc}") from exc
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                raise TransportTimeout(f"{self._name}: the far end took no bytes for "
                                       f"{WRITE_TIMEOUT} s")
            select.select([], [self._fd], [], min(remaining, 0.05))

    def readline(self, timeout: float) -> bytes:
        """The next line (see :meth:`MemoryTransport.readline`).

        Parameters
        ----------
        timeout : float
            The longest to wait for a complete line (s).

        Returns
        -------
        bytes
            The line without its newline.
        """
        deadline = time.monotonic() + _check_timeout(timeout)
        while True:
            line = _take_line(self._buf)
            if line is not None:
                return line
            if self._closed:
                raise TransportClosed(f"{self._name} is closed")
            remaining = max(0.0, deadline - time.monotonic())
            # short slices, so that close() from another thread is seen promptly
            try:
                ready, _, _ = select.select([self._fd], [], [], min(remaining, 0.05))
            except (OSError, ValueError) as exc:
                raise TransportClosed(f"{self._name} is closed: {exc}") from exc
            if not ready:
                if time.monotonic() >= deadline:
                    raise TransportTimeout(f"{self._name}: no complete line within {timeout} s")
                continue
            try:
                chunk = os.read(self._fd, 4096)
            except BlockingIOError:
                continue
            except OSError as exc:  # EIO: the other side of the pty has closed
                raise TransportClosed(f"{self._name} is closed: {exc}") from exc
            if not chunk:
                raise TransportClosed(f"{self._name} is closed")
            self._buf += chunk

    def close(self) -> None:
        """Close the descriptor (idempotent)."""
        if not self._closed:
            self._closed = True
            try:
                os.close(self._fd)
            except OSError:
                pass


class PtyLink:
    """A pseudo-terminal pair: a twin serves ``.device_end``, pyserial opens ``.path``.

    The terminal is in raw mode (no echo, no line editing, no newline translation), as a real
    USB serial port; pyserial opens ``.path`` exactly as it opens ``/dev/ttyACM0``.

    Attributes
    ----------
    path : str
        The host side's device name (e.g. ``/dev/pts/5``).
    device_end : Transport
        The device side, for a :class:`~afmsmiler.hardware.twin.TwinServer`.
    """

    def __init__(self):
        master, slave = os.openpty()
        tty.setraw(slave)
        self.path = os.ttyname(slave)
        self._slave = slave  # kept open so the master reads no EIO before the host opens .path
        self.device_end = _FdTransport(master, f"pty {self.path} (device side)")

    def close(self) -> None:
        """Close both sides (idempotent)."""
        self.device_end.close()
        if self._slave is not None:
            try:
                os.close(self._slave)
            except OSError:
                pass
            self._slave = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


class FaultyTransport:
    """A transport that injects a real cable's faults, deterministically from a seed.

    Wraps the host's end of a link. Each line read (and each line written, if ``writes``) meets,
    with the given probabilities: a corrupted byte (its checksum no longer matches), a garbage line
    before it, truncation (a partial line), or loss (dropped). After ``unplug_after_lines`` lines
    read the link is unplugged (TransportClosed from then on, and the far end sees it closed);
    after ``silent_after_lines`` lines read the device goes silent (reads time out, writes are
    lost).

    Parameters
    ----------
    inner : Transport
        The transport to wrap.
    seed : int
        Seed of the fault generator (the same seed gives the same faults for the same lines).
    corrupt : float
        Probability that a line has one byte changed (0..1).
    garbage : float
        Probability that a garbage line (random bytes) comes before a line (0..1).
    drop : float
        Probability that a line is lost (0..1).
    partial : float
        Probability that a line is cut short (0..1).
    unplug_after_lines : int or None
        Unplug after this many lines have been read (``None``: never).
    silent_after_lines : int or None
        Go silent after this many lines have been read (``None``: never).
    writes : bool
        Apply ``corrupt``, ``drop`` and ``partial`` to the lines written too.

    Attributes
    ----------
    counts : dict
        How many of each fault were injected (``corrupt``, ``garbage``, ``drop``, ``partial``),
        and ``lines`` read.
    """

    def __init__(self, inner, *, seed: int = 0, corrupt: float = 0.0, garbage: float = 0.0,
                 drop: float = 0.0, partial: float = 0.0, unplug_after_lines: int | None = None,
                 silent_after_lines: int | None = None, writes: bool = True):
        for name, p in (("corrupt", corrupt), ("garbage", garbage), ("drop", drop),
                        ("partial", partial)):
            if isinstance(p, bool) or not isinstance(p, (int, float)) or not 0.0 <= p <= 1.0:
                raise ValueError(f"{name} must be a probability in [0, 1], got {p!r}")
        for name, n in (("unplug_after_lines", unplug_after_lines),
                        ("silent_after_lines", silent_after_lines)):
            if n is not None and (isinstance(n, bool) or not isinstance(n, int) or n < 0):
                raise ValueError(f"{name} must be None or an integer >= 0, got {n!r}")
        self.inner = _check_transport("inner", inner)
        self.corrupt, self.garbage, self.drop, self.partial = corrupt, garbage, drop, partial
        self.unplug_after_lines = unplug_after_lines
        self.silent_after_lines = silent_after_lines
        self.writes = check_flag("writes", writes)
        seed = check_integer("seed", seed, -2 ** 63, 2 ** 63)
        self._read_rng = random.Random(seed)
        self._write_rng = random.Random(seed + 0x5EED)
        self._pending = []
        self._unplugged = False
        self.counts = {"lines": 0, "corrupt": 0, "garbage": 0, "drop": 0, "partial": 0}

    @staticmethod
    def _corrupt(line: bytes, rng: random.Random) -> bytes:
        if not line:
            return b"?"
        i = rng.randrange(len(line))
        old = line[i]
        new = old
        while new == old or new in (0x2A, 0x0A):
            new = rng.randrange(0x20, 0x7F)
        return line[:i] + bytes([new]) + line[i + 1:]

    def _check_plugged(self):
        if self._unplugged:
            raise TransportClosed("the cable was unplugged (FaultyTransport)")
        if self.unplug_after_lines is not None and self.counts["lines"] >= self.unplug_after_lines:
            self._unplugged = True
            self.inner.close()
            raise TransportClosed(f"the cable was unplugged after {self.counts['lines']} lines "
                                  "(FaultyTransport)")

    def _silent(self) -> bool:
        return (self.silent_after_lines is not None
                and self.counts["lines"] >= self.silent_after_lines)

    def write(self, data: bytes) -> None:
        """Send ``data`` through the faults.

        Parameters
        ----------
        data : bytes
            The bytes to send (one frame per call for the faults to apply per line).
        """
        self._check_plugged()
        if self._silent():
            return
        data = as_bytes("data", data)
        if self.writes and data.endswith(b"\n"):
            rng = self._write_rng
            if rng.random() < self.drop:
                self.counts["drop"] += 1
                return
            if rng.random() < self.corrupt:
                self.counts["corrupt"] += 1
                data = self._corrupt(data[:-1], rng) + b"\n"
            if rng.random() < self.partial:
                self.counts["partial"] += 1
                data = data[:rng.randrange(len(data))] + b"\n"
        self.inner.write(data)

    def readline(self, timeout: float) -> bytes:
        """The next line through the faults.

        Parameters
        ----------
        timeout : float
            The longest to wait (s), as for the wrapped transport.

        Returns
        -------
        bytes
            A line (possibly corrupted, cut short, or garbage).
        """
        timeout = _check_timeout(timeout)
        deadline = time.monotonic() + timeout
        self._check_plugged()
        if self._pending:
            return self._count(self._pending.pop(0))
        if self._silent():
            while time.monotonic() < deadline:  # in slices: sleep(1e300) overflows
                time.sleep(max(0.0, min(deadline - time.monotonic(), 1.0)))
            raise TransportTimeout(f"no complete line within {timeout} s (device silent)")
        rng = self._read_rng
        while True:
            line = self.inner.readline(max(0.0, deadline - time.monotonic()))
            if rng.random() < self.drop:
                self.counts["drop"] += 1
                continue
            if rng.random() < self.corrupt:
                self.counts["corrupt"] += 1
                line = self._corrupt(line, rng)
            if rng.random() < self.partial:
                self.counts["partial"] += 1
                line = line[:rng.randrange(max(1, len(line)))]
            if rng.random() < self.garbage:
                self.counts["garbage"] += 1
                junk = bytes(rng.randrange(256) for _ in range(rng.randrange(1, 40)))
                self._pending.append(line)
                return self._count(junk.replace(b"\n", b"#"))
            return self._count(line)

    def _count(self, line: bytes) -> bytes:
        self.counts["lines"] += 1
        return line

    def close(self) -> None:
        """Close the wrapped transport."""
        self.inner.close()
