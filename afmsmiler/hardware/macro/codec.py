"""The macroscopic AFM's protocol (device ``MACROAFM``, protocol version 1): bytes <-> messages.

Pure: no I/O. The enums :class:`Command`, :class:`Event` and :class:`Param` (built from
:data:`TABLE`, the parameters described once) and module (h)'s shared
:class:`~afmsmiler.hardware.errors.ErrorCode` have the names and values of the firmware's
``protocol.h`` (``CMD_<NAME>``, ``ERR_<NAME>``, ``EVT_<NAME>``, ``PAR_<NAME>``); tests parse that
file, the firmware's limits and PROTOCOL.md's parameter table and compare, so they cannot drift.
Frames follow :mod:`afmsmiler.hardware.framing`; quantities on the wire are integers in the units
:data:`TABLE` names (um for the pitch, nm per z micro-step, gauge counts, micro-steps, steps/s).
The codec works both ways: :meth:`MacroAFMCodec.encode` writes a device message (what the twin
sends), :meth:`MacroAFMCodec.parse` reads one (what the driver receives).

Messages a device sends:

- :class:`Reply` -- ``SEQ OK CODE [RESULT ...]``
- :class:`ErrorReply` -- ``SEQ ER ERRNO [WORD]`` (``SEQ`` 0: a line the device could not read,
  or a fault during a scan)
- :class:`Pixel` -- ``0 PX <row> <col> <z-microsteps> <gauge-counts>``
- :class:`LineEnd` -- ``0 LN <row> <n-pixels>``
- :class:`EventMsg` -- ``0 EV <WORD> [ARG]``
- :class:`Status` -- parsed from the reply to ``ST``.

Examples
--------
>>> MacroAFMCodec.command(3, Command.SET, Param.PITCH, 200)
b'3 SP DX 200*E3\\n'
>>> MacroAFMCodec.parse(b"0 PX 2 5 -120 3301*E1")
Pixel(row=2, col=5, z=-120, counts=3301)
"""
from __future__ import annotations

import enum
import inspect
from dataclasses import dataclass

from ...validation import check_integer
from ..errors import ErrorCode, FrameError, ReplyError
from ..framing import (_CODE, _WORD, INT_MAX, INT_MIN, Frame, _token, _word, decode_frame, encode_frame,
                       error_frame, event_frame, reply_frame)
from ..protocol import ParamTable, WireParam, _known_flags, _lookup

__all__ = ["DEVICE", "BAUDRATE", "Command", "ErrorCode", "Event", "Param", "State", "Flag",
           "Pixel", "LineEnd", "EventMsg", "Reply", "ErrorReply", "Status", "MacroAFMCodec",
           "READ_ONLY", "TABLE"]

#: The device's name in its ``ID`` reply.
DEVICE = "MACROAFM"
#: The serial port's speed (8N1).
BAUDRATE = 115200


def _by_value(cls):
    """Give an enum the signature of its lookup, ``Kind(value)`` (what users call)."""
    cls.__signature__ = inspect.Signature(
        [inspect.Parameter("value", inspect.Parameter.POSITIONAL_OR_KEYWORD)])
    return cls


@_by_value
class Command(str, enum.Enum):
    """Host commands (``CMD_<NAME> "XX"`` in protocol.h).

    Parameters
    ----------
    value : str
        The two letters on the wire (``Command("SP")`` is ``Command.SET``).
    """

    IDENTIFY = "ID"
    SET = "SP"
    GET = "GP"
    HOME = "HM"
    START = "SS"
    PAUSE = "PA"
    RESUME = "RS"
    ABORT = "AB"
    STATUS = "ST"
    GAUGE = "RG"
    GETLINE = "GL"


@_by_value
class Event(str, enum.Enum):
    """Event words of ``0 EV <WORD> [ARG]`` (``EVT_<NAME> "<WORD>"``).

    Parameters
    ----------
    value : str
        The word on the wire.
    """

    BOOT = "BOOT"
    HOMED = "HOMED"
    DONE = "DONE"
    PAUSED = "PAUSED"
    ABORTED = "ABORTED"
    LIMIT = "LIMIT"
    ESTOP = "ESTOP"
    BUTTON = "BUTTON"


#: The device's parameters, described once (wire code, unit, range, default; PROTOCOL.md's table).
TABLE = ParamTable(DEVICE, (
    WireParam("NX", "NX", "count", 1, 128, 8, si_name="pixels", meaning="pixels per line"),
    WireParam("NY", "NY", "count", 1, 1024, 8, si_name="lines", meaning="lines"),
    WireParam("PITCH", "DX", "um", 25, 10_000, 200, multiple=25, si_name="pitch",
              meaning="pixel spacing"),
    WireParam("ZSTEP", "ZS", "nm", 1, 1_000_000, 2500, read_only=True, si_name="z_step",
              meaning="height of one z micro-step"),
    WireParam("SETPOINT", "SE", "count", 301, 4_000_000, 2000, si_name="setpoint_counts",
              meaning="deflection setpoint in gauge counts"),
    WireParam("MODE", "MO", "count", 0, 1, 0, si_name="mode", meaning="0 contact, 1 jumping"),
    WireParam("LIFT", "LI", "step", 1, 40_000, 400, si_name="lift_steps",
              meaning="jumping lift in z micro-steps"),
    WireParam("SPEED", "VE", "step/s", 10, 8000, 4000, si_name="step_rate",
              meaning="maximum step rate"),
    WireParam("ACCEL", "AC", "step/s^2", 10, 1_000_000, 40_000, si_name="step_acceleration",
              meaning="acceleration"),
    WireParam("PRESET", "PR", "count", 0, 3, 0, si_name="preset",
              meaning="the scan the START button runs"),
))

#: Integer parameters of ``SP``/``GP`` (``PAR_<NAME> "XX"``), built from :data:`TABLE`.
Param = TABLE.enum(__name__)

#: Parameters the host may read but not set.
READ_ONLY = frozenset(Param(p.code) for p in TABLE if p.read_only)


@_by_value
class State(str, enum.Enum):
    """The device's states in the ``ST`` reply.

    Parameters
    ----------
    value : str
        The state's word on the wire.
    """

    IDLE = "IDLE"
    HOMING = "HOMING"
    SCANNING = "SCANNING"
    PAUSED = "PAUSED"
    FAULT = "FAULT"


@_by_value
class Flag(enum.IntFlag):
    """Bits of the ``ST`` reply's flags integer.

    Parameters
    ----------
    value : int
        The flags integer on the wire.
    """

    HOMED = 1
    LIMIT_X = 2
    LIMIT_Y = 4
    LIMIT_Z = 8
    ESTOP = 16


@dataclass(frozen=True)
class Pixel:
    """One pixel of a scan, as streamed (``0 PX``).

    Parameters
    ----------
    row : int
        Line index (0: the first line scanned).
    col : int
        Pixel index along the fast axis.
    z : int
        Height in z micro-steps (times ZS nm: the height).
    counts : int
        Gauge reading in counts above the free reading (the deflection there).
    """

    row: int
    col: int
    z: int
    counts: int

    def __post_init__(self):
        _integers(self, row=(0, INT_MAX), col=(0, INT_MAX), z=(INT_MIN, INT_MAX),
                  counts=(INT_MIN, INT_MAX))


@dataclass(frozen=True)
class LineEnd:
    """The end of a line (``0 LN``).

    Parameters
    ----------
    row : int
        The line that ended.
    pixels : int
        How many pixels it has.
    """

    row: int
    pixels: int

    def __post_init__(self):
        _integers(self, row=(0, INT_MAX), pixels=(0, INT_MAX))


@dataclass(frozen=True)
class EventMsg:
    """An event (``0 EV <WORD> [ARG]``).

    Parameters
    ----------
    event : Event or str
        The event (a str if this driver does not know the word).
    arg : int or str or None
        Its argument (an axis for LIMIT, a preset for BUTTON).
    """

    event: object
    arg: object = None

    def __post_init__(self):
        _word("event", self.event)
        if self.arg is not None:
            _token("arg", self.arg)


@dataclass(frozen=True)
class Reply:
    """A command's success (``SEQ OK CODE [RESULT ...]``).

    Parameters
    ----------
    seq : int
        The command's sequence number.
    command : Command or str
        The command echoed.
    results : tuple
        What the command returned.
    """

    seq: int
    command: object
    results: tuple = ()

    def __post_init__(self):
        _integers(self, seq=(0, 255))
        command = getattr(self.command, "value", self.command)
        if not isinstance(command, str) or not _CODE.fullmatch(command):
            raise ValueError(f"command must be a command's two uppercase letters, got "
                             f"{self.command!r}"[:160])
        if isinstance(self.results, (str, bytes)) or not isinstance(self.results, (tuple, list)):
            raise ValueError(f"results must be a tuple of ints and words, got "
                             f"{type(self.results).__name__}")
        for i, r in enumerate(self.results):
            _token(f"results[{i}]", getattr(r, "value", r))
        object.__setattr__(self, "results", tuple(self.results))


@dataclass(frozen=True)
class ErrorReply:
    """A command's failure, or with SEQ 0 an unreadable line or a scan fault.

    Parameters
    ----------
    seq : int
        The command's sequence number (0: not a reply to a command).
    code : int
        The error number (an :class:`ErrorCode` when known).
    word : str
        The optional word ("" if none).
    """

    seq: int
    code: int
    word: str = ""

    def __post_init__(self):
        _integers(self, seq=(0, 255), code=(0, INT_MAX))
        if not isinstance(self.word, str) or not (self.word == "" or _WORD.fullmatch(self.word)):
            raise ValueError(f"word must be '' or a word of [A-Za-z0-9_.:-], got "
                             f"{self.word!r}"[:160])


@dataclass(frozen=True)
class Status:
    """The device's state (the reply to ``ST``).

    Parameters
    ----------
    state : State or str
        IDLE, HOMING, SCANNING, PAUSED or FAULT.
    row : int
        The line being scanned (or last scanned).
    col : int
        The pixel being scanned.
    flags : Flag
        Homed, limit switches, emergency stop (bits of :class:`Flag`).
    """

    state: object
    row: int
    col: int
    flags: Flag

    def __post_init__(self):
        _word("state", self.state)
        _integers(self, row=(0, INT_MAX), col=(0, INT_MAX))
        object.__setattr__(self, "flags", _known_flags("flags", Flag, self.flags))

    @property
    def homed(self) -> bool:
        """Whether the axes are homed."""
        return bool(self.flags & Flag.HOMED)


def _integers(message, **ranges) -> None:
    """Check (and store as int) the named integer fields of a frozen message."""
    for name, (low, high) in ranges.items():
        object.__setattr__(message, name, check_integer(name, getattr(message, name), low, high))


def _enum(kind, value):
    try:
        return kind(value)
    except ValueError:
        return value


def _ints(frame: Frame, n: int, what: str) -> tuple:
    if len(frame.args) != n or not all(isinstance(a, int) for a in frame.args):
        raise FrameError(f"{what} needs {n} integers, got {frame.args!r}", encode_frame(frame))
    return frame.args


class MacroAFMCodec:
    """Bytes <-> messages for the macroscopic AFM (class methods only; no state, no I/O)."""

    @staticmethod
    def command(seq: int, command: Command, *args) -> bytes:
        """The bytes of a host command.

        Parameters
        ----------
        seq : int
            Sequence number, 1..255 (0 for a frame that gets no reply).
        command : Command
            The command.
        *args : int or str or Param
            Its arguments (a :class:`Param` is sent as its two letters).

        Returns
        -------
        bytes

        Raises
        ------
        ValueError
            Naming ``command`` if it is not a :class:`Command`, or ``seq``/``args[i]``.
        """
        command = _lookup("command", Command, command)
        wire = tuple(a.value if isinstance(a, enum.Enum) else a for a in args)
        return encode_frame(Frame(seq, command.value, wire))

    @staticmethod
    def message(frame: Frame):
        """The message a device frame carries.

        Parameters
        ----------
        frame : Frame
            A decoded frame from the device.

        Returns
        -------
        Reply, ErrorReply, Pixel, LineEnd or EventMsg

        Raises
        ------
        FrameError
            If the frame is valid but not a message of this protocol.
        TypeError
            If ``frame`` is not a :class:`~afmsmiler.hardware.framing.Frame`.
        """
        if not isinstance(frame, Frame):
            raise TypeError(f"frame must be a Frame, got {type(frame).__name__}")
        try:  # a message that its dataclass refuses (a negative row) is not one either
            return MacroAFMCodec._message(frame)
        except FrameError:
            raise
        except ValueError as exc:
            raise FrameError(f"not a MACROAFM message: {frame!r}: {exc}",
                             encode_frame(frame)) from None

    @staticmethod
    def _message(frame: Frame):
        code, args = frame.code, frame.args
        if code == "OK" and frame.seq != 0 and args and isinstance(args[0], str):
            return Reply(frame.seq, _enum(Command, args[0]), tuple(args[1:]))
        if code == "ER" and args and isinstance(args[0], int) and len(args) <= 2:
            word = str(args[1]) if len(args) == 2 else ""
            return ErrorReply(frame.seq, _enum(ErrorCode, args[0]), word)
        if frame.seq == 0 and code == "PX":
            return Pixel(*_ints(frame, 4, "PX"))
        if frame.seq == 0 and code == "LN":
            return LineEnd(*_ints(frame, 2, "LN"))
        if frame.seq == 0 and code == "EV" and 1 <= len(args) <= 2 and isinstance(args[0], str):
            return EventMsg(_enum(Event, args[0]), args[1] if len(args) == 2 else None)
        raise FrameError(f"not a MACROAFM message: {frame!r}", encode_frame(frame))

    @staticmethod
    def frame(message) -> Frame:
        """The frame of a device message (the inverse of :meth:`message`).

        Parameters
        ----------
        message : Reply, ErrorReply, Pixel, LineEnd, EventMsg or Status
            What the device says (a :class:`Status` becomes ``0 OK ST ...`` with SEQ 0: give it
            to :meth:`reply_status` with the command's SEQ instead).

        Returns
        -------
        Frame

        Raises
        ------
        TypeError
            If ``message`` is not a message of this protocol.
        """
        if isinstance(message, Pixel):
            return Frame(0, "PX", (message.row, message.col, message.z, message.counts))
        if isinstance(message, LineEnd):
            return Frame(0, "LN", (message.row, message.pixels))
        if isinstance(message, EventMsg):
            return event_frame(message.event, *(() if message.arg is None else (message.arg,)))
        if isinstance(message, Reply):
            return reply_frame(message.seq, message.command, *message.results)
        if isinstance(message, ErrorReply):
            return error_frame(message.seq, message.code, message.word)
        raise TypeError(f"message must be a MACROAFM message, got {type(message).__name__}")

    @classmethod
    def encode(cls, message) -> bytes:
        """The bytes of a device message on the wire (what the firmware or a twin sends).

        Parameters
        ----------
        message : Reply, ErrorReply, Pixel, LineEnd or EventMsg
            The message.

        Returns
        -------
        bytes

        Examples
        --------
        >>> MacroAFMCodec.encode(LineEnd(0, 8))
        b'0 LN 0 8*D6\\n'
        """
        return encode_frame(cls.frame(message))

    @staticmethod
    def status_results(status: Status) -> tuple:
        """The results of the reply to ``ST`` for a :class:`Status` (the inverse of :meth:`status`).

        Parameters
        ----------
        status : Status
            The device's state.

        Returns
        -------
        tuple
            ``(state-word, row, col, flags)``.

        Raises
        ------
        TypeError
            If ``status`` is not a :class:`Status`.
        """
        if not isinstance(status, Status):
            raise TypeError(f"status must be a Status, got {type(status).__name__}")
        state = status.state.value if isinstance(status.state, enum.Enum) else status.state
        return (state, int(status.row), int(status.col), int(status.flags))

    @classmethod
    def parse(cls, line: bytes):
        """The message in one received line (decode, then :meth:`message`).

        Parameters
        ----------
        line : bytes
            One line from the device.

        Returns
        -------
        Reply, ErrorReply, Pixel, LineEnd or EventMsg

        Raises
        ------
        FrameError
            (or its ChecksumError) if the line is not a valid message.
        """
        return cls.message(decode_frame(line))

    @staticmethod
    def status(reply: Reply) -> Status:
        """The :class:`Status` in the reply to ``ST``.

        Parameters
        ----------
        reply : Reply
            ``OK ST <state-word> <row> <col> <flags-int>``.

        Returns
        -------
        Status

        Raises
        ------
        FrameError
            If the reply is not a status reply, or if its flags integer is negative or has a bit
            that :class:`Flag` does not name: the device then speaks something else than protocol
            version 1 (a new flag is met by every host, so it needs a new protocol version), and
            dropping the bit would hide, e.g., a switch or an E-stop from the driver.
        TypeError
            If ``reply`` is not a :class:`Reply`.
        """
        if not isinstance(reply, Reply):
            raise TypeError(f"reply must be a Reply, got {type(reply).__name__}")
        r = reply.results
        if (reply.command != Command.STATUS or len(r) != 4 or not isinstance(r[0], str)
                or not all(isinstance(v, int) for v in r[1:])):
            raise ReplyError(f"not a status reply: {reply!r}")
        known = sum(f.value for f in Flag)
        if r[3] < 0 or r[3] & ~known:
            unknown = r[3] & ~known if r[3] >= 0 else r[3]
            raise ReplyError(f"status flags {r[3]} have bits this driver does not know "
                             f"({unknown}; protocol version 1 knows {known} = "
                             f"{' | '.join(f'{f.value} {f.name}' for f in Flag)})")
        try:
            return Status(_enum(State, r[0]), r[1], r[2], Flag(r[3]))
        except ValueError as exc:  # a negative row or column
            raise ReplyError(f"not a status reply: {reply!r}: {exc}") from None
