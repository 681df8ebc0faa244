"""The exceptions of module (h): one family, so that a notebook can catch ``HardwareError``.

Each error says what went wrong in words a student can act on (which port, which command, which
versions). Errors raised while a scan runs carry the finished part of the image as ``.partial``
(a :class:`~afmsmiler.samples.Sample` of the finished rows, or ``None``).
"""
from __future__ import annotations

import enum
import inspect

__all__ = ["HardwareError", "FrameError", "ChecksumError", "TransportTimeout", "TransportClosed",
           "DeviceNotResponding", "WatchdogTripped", "ProtocolVersionError", "DeviceError", "ReplyError",
           "ErrorCode", "RESEND_CODES"]


class ErrorCode(enum.IntEnum):
    """The error numbers of ``SEQ ER ERRNO [WORD]``, shared by every device of module (h).

    Each device's ``protocol.h`` has them as ``ERR_<NAME> <n>`` (a test compares).

    Parameters
    ----------
    value : int
        The error number on the wire (``ErrorCode(3)`` is ``ErrorCode.BAD_ARGUMENT``).
    """

    CHECKSUM = 1
    UNKNOWN_COMMAND = 2
    BAD_ARGUMENT = 3
    BUSY = 4
    NOT_HOMED = 5
    LIMIT = 6
    ESTOP = 7
    SENSOR = 8
    MALFORMED = 9
    STATE = 10


ErrorCode.__signature__ = inspect.Signature(
    [inspect.Parameter("value", inspect.Parameter.POSITIONAL_OR_KEYWORD)])

#: The errors with which a device says it could not read the host's line (``0 ER 1``, ``0 ER 9``):
#: the host sends its pending command again with the same SEQ.
RESEND_CODES = frozenset({ErrorCode.CHECKSUM, ErrorCode.MALFORMED})


class HardwareError(Exception):
    """Base of every error of module (h).

    Attributes
    ----------
    partial : Sample or None
        The finished rows of a scan this error interrupted (``None`` outside a scan).
    """

    partial = None


class FrameError(HardwareError, ValueError):
    """A line that is not a valid frame (too long, no checksum, bad tokens).

    Parameters
    ----------
    message : str
        What is wrong with the line.
    line : bytes
        The offending line as received (kept as ``.line``).
    """

    def __init__(self, message: str, line: bytes = b""):
        super().__init__(message)
        self.line = bytes(line)


class ChecksumError(FrameError):
    """A well-formed line whose CRC-8 does not match its body (a corrupted byte).

    Parameters
    ----------
    message : str
        Which checksum was expected and found.
    line : bytes
        The offending line as received (kept as ``.line``).
    """


class TransportTimeout(HardwareError, TimeoutError):
    """No complete line arrived (or could be written) within the timeout."""


class TransportClosed(HardwareError, ConnectionError):
    """The port was unplugged or closed, or the far end has gone."""


class DeviceNotResponding(HardwareError, TimeoutError):
    """A command got no valid reply after all its retries."""


class WatchdogTripped(HardwareError):
    """The device's watchdog switched its motor off: this host sent no force frame for longer
    than the watchdog time (a host that paused; a longer watchdog or a retry helps)."""


class ProtocolVersionError(HardwareError):
    """The device speaks another protocol version than this driver.

    Parameters
    ----------
    device_version : int or str
        The protocol version the device reported.
    host_version : int
        The version this driver speaks (:data:`afmsmiler.hardware.framing.PROTOCOL_VERSION`).
    device : str
        The device's name (e.g. ``"MACROAFM"``).
    """

    def __init__(self, device_version, host_version: int, device: str = "device"):
        super().__init__(
            f"{device} speaks protocol version {device_version}, this driver speaks version "
            f"{host_version}: flash firmware of protocol {host_version} or use a matching driver")
        self.device_version = device_version
        self.host_version = host_version
        self.device = device


class DeviceError(HardwareError):
    """The device answered a command with an error frame (``SEQ ER ERRNO [WORD]``).

    Parameters
    ----------
    code : int
        The error number (an ``ErrorCode`` of the device's codec).
    word : str
        The error's optional word (e.g. the axis of a limit switch), ``""`` if none.
    device : str
        The device's name.
    command : str
        The two-letter code of the command that failed, ``""`` for a scan fault.
    """

    def __init__(self, code: int, word: str = "", device: str = "device", command: str = ""):
        self.code = int(code)
        self.word = str(word)
        self.device = device
        self.command = command
        name = ErrorCode(self.code).name if self.code in ErrorCode._value2member_map_ \
            else "UNKNOWN"
        what = f"{device} refused {command}" if command else f"{device} reported a fault"
        extra = f" ({self.word})" if self.word else ""
        super().__init__(f"{what}: error {self.code} {name}{extra}")



class ReplyError(FrameError):
    """A well-formed reply the host refuses: a value outside the device's parameter table, a
    reply with too few results, a status with bits the protocol does not name.

    Parameters
    ----------
    message : str
        What is wrong, naming the parameter, the value and the valid range.
    line : bytes
        The offending line (kept as ``.line``), ``b""`` if not at hand.
    """
