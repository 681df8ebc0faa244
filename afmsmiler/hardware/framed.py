"""The host side every framed device shares: sequence numbers, one deadline, retries, identify.

:class:`FramedDevice` is the base of :class:`~afmsmiler.hardware.macro.MacroAFM`,
:class:`~afmsmiler.hardware.educational.EducationalAFM` and
:class:`~afmsmiler.hardware.haptic.HapticDevice`. A command is numbered 1..255 (255 wraps to 1)
and sent; its reply is awaited until one deadline, ``timeout`` after the send, whatever the device
sends meanwhile (garbage lines, stream frames, replies to other SEQs never extend it). After the
deadline, or at once when the device answers ``0 ER 1``/``0 ER 9`` (it could not read the line),
the command is sent again with the same SEQ (the device re-sends its last reply instead of running
it twice); after ``retries`` retries :class:`~afmsmiler.hardware.errors.DeviceNotResponding`. So a
request lasts at most ``(retries + 1) * timeout`` whatever the device does.
"""
from __future__ import annotations

import time

from ..validation import check_integer, check_positive
from .errors import (RESEND_CODES, DeviceError, DeviceNotResponding, FrameError, HardwareError,
                     ProtocolVersionError, ReplyError, TransportTimeout)
from .framing import PROTOCOL_VERSION, Frame, decode_frame, encode_frame
from .transport import _check_transport

__all__ = ["FramedDevice"]


class FramedDevice:
    """A device that speaks module (h)'s frames on a transport (subclassed per device).

    Subclasses set :attr:`DEVICE` and :attr:`TABLE`; they may override :meth:`_receive` (where
    replies come from), :meth:`_send` (how a command is written) and :meth:`_stream` (what to do
    with a SEQ 0 frame met while waiting).

    Parameters
    ----------
    transport : Transport
        The link (``write``, ``readline(timeout)``, ``close``); never opened here.
    timeout : float
        The longest to wait for a command's reply, per attempt (s), finite and > 0.
    retries : int
        How often a command is sent again (same SEQ) before :class:`DeviceNotResponding`.
    max_retries : int
        The largest ``retries`` accepted.

    Attributes
    ----------
    garbage : int
        Lines received that were not valid frames.
    retried : int
        Commands sent again.
    """

    #: The device's name in its ``ID`` reply.
    DEVICE = ""
    #: The device's :class:`~afmsmiler.hardware.protocol.ParamTable`.
    TABLE = None

    def __init__(self, transport, *, timeout: float = 1.0, retries: int = 3,
                 max_retries: int = 100):
        self.transport = _check_transport("transport", transport)
        self.timeout = check_positive("timeout", timeout, "s")
        max_retries = check_integer("max_retries", max_retries, 0, 10 ** 6)
        self.retries = check_integer("retries", retries, 0, max_retries)
        self.garbage = 0
        self.retried = 0
        self._seq = 0

    def _next_seq(self) -> int:
        self._seq = self._seq % 255 + 1
        return self._seq

    # -- hooks -----------------------------------------------------------------------------
    def _receive(self, timeout: float) -> Frame | None:
        """The next frame within ``timeout`` s, None for a line that is not one.

        Raises TransportTimeout when nothing came; TransportClosed when the link is gone.
        """
        line = self.transport.readline(timeout)
        try:
            return decode_frame(line)
        except FrameError:
            self.garbage += 1
            return None

    def _send(self, data: bytes) -> None:
        """Write one encoded command (a subclass that writes from several threads locks here)."""
        self.transport.write(data)

    def _stream(self, frame: Frame) -> None:
        """A SEQ 0 frame met while waiting for a reply (pixels, events, faults)."""

    # -- one request -----------------------------------------------------------------------
    def _exchange(self, code: str, *args) -> tuple:
        """Send ``SEQ code args``; the OK reply's results (after the echoed code).

        Raises DeviceError for an ER reply, DeviceNotResponding after the retries.
        """
        seq = self._next_seq()
        data = encode_frame(Frame(seq, code, args))
        for attempt in range(self.retries + 1):
            if attempt:
                self.retried += 1
            self._send(data)
            deadline = time.monotonic() + self.timeout   # one deadline per attempt
            while True:
                left = deadline - time.monotonic()
                if left <= 0:
                    break
                try:
                    frame = self._receive(left)
                except TransportTimeout:
                    break
                if frame is None:
                    continue
                if frame.seq == 0:
                    if frame.code == "ER" and frame.args and frame.args[0] in RESEND_CODES:
                        break                            # our line arrived damaged: resend
                    self._stream(frame)
                    continue
                if frame.seq != seq:
                    continue                             # a late reply to an earlier command
                if frame.code == "ER" and frame.args and isinstance(frame.args[0], int):
                    word = str(frame.args[1]) if len(frame.args) > 1 else ""
                    raise DeviceError(frame.args[0], word, self.DEVICE, code)
                if frame.code == "OK" and frame.args[:1] == (code,):
                    return frame.args[1:]
                self.garbage += 1                        # our SEQ, not a reply: wait on
        raise DeviceNotResponding(
            f"{self.DEVICE} did not answer {code} after {self.retries + 1} tries ({self.retries} "
            f"retries) of "
            f"{self.timeout:g} s: is it powered, on this port, running firmware of protocol "
            f"{PROTOCOL_VERSION}?")

    def _identify(self) -> tuple:
        """``ID``: (device, protocol version, firmware version), checked.

        Raises ReplyError for a reply of another shape, ProtocolVersionError for another
        version, HardwareError for another device.
        """
        results = self._exchange("ID")
        if len(results) != 3 or not isinstance(results[0], str):
            raise ReplyError(f"an ID reply must be <device> <protocol> <firmware>, got "
                             f"{tuple(results)!r}")
        name, version, firmware = results
        if version != PROTOCOL_VERSION:
            raise ProtocolVersionError(version, PROTOCOL_VERSION, str(name))
        if name != self.DEVICE:
            raise HardwareError(f"expected a {self.DEVICE} on this port, found {name!r}")
        return str(name), int(version), str(firmware)

    def _checked(self, results: tuple, command: str, code: str) -> int:
        """The value of an ``OK SP|GP <PAR> <int>`` reply about ``code``, checked."""
        value = self.TABLE.check_reply(results, command)
        if results[0] != code:
            raise ReplyError(f"{self.DEVICE} answered {command} {code} about {results[0]}")
        return value

    def _get_wire(self, code: str) -> int:
        """``GP code``: the device's integer, checked against :attr:`TABLE`."""
        return self._checked(self._exchange("GP", code), "GP", code)

    def _set_wire(self, code: str, value: int) -> int:
        """``SP code value`` (checked against :attr:`TABLE` first): the value the device took."""
        spec = self.TABLE[code]
        spec._check(value, spec._value_label("value"))
        return self._checked(self._exchange("SP", code, int(value)), "SP", code)
