"""The educational AFM's protocol (device ``EDUAFM``, protocol version 1): codes and frames.

Pure (no I/O). The frame format is module (h)'s (:mod:`afmsmiler.hardware.framing`); this module
names the educational AFM's commands, events and parameters (:data:`TABLE`, each described once:
code, wire unit, range, default) with module (h)'s shared error numbers, and builds its frames
(the twin sends what these functions build, never a frame typed from string literals).
``hardware/educational_afm/PROTOCOL.md`` (at the repository's root) is the specification, with
golden frames that the tests decode.

The instrument scans its sample with the active probe's 2-omega amplitude regulated (see
:mod:`afmsmiler.signals`) and streams each pixel's height as it is measured::

    0 PX <row> <col> <z-counts>        height = z-counts x ZS pm
    0 LN <row> <n-pixels>              the end of a line
    0 EV <WORD> [ARG]                  BOOT, DONE, ABORTED, FAULT
    0 ER <n>                           after EV FAULT: the scan stopped (state FAULT until SS)
"""
from __future__ import annotations

import enum

from ...validation import check_integer
from ..errors import ErrorCode   # the error numbers every device of module (h) shares
from ..framing import INT_MAX, INT_MIN, Frame, error_frame, event_frame
from ..protocol import ParamTable, WireParam, _lookup

__all__ = ["DEVICE", "TABLE", "Command", "Param", "Event", "ErrorCode", "State", "READ_ONLY",
           "command", "pixel", "line_end", "event", "stream_error"]

#: The device's name in its ``ID`` reply.
DEVICE = "EDUAFM"


class Command(str, enum.Enum):
    """Host commands (``SEQ CODE [ARG ...]``).

    Look a member up by its value (``value``); ``names``, ``module``, ``qualname``, ``type``,
    ``start`` and ``boundary`` are the arguments of Python's functional Enum API.
    """

    IDENTIFY = "ID"
    SET = "SP"
    GET = "GP"
    START = "SS"
    ABORT = "AB"
    STATUS = "ST"
    GETLINE = "GL"


#: The device's parameters, described once (wire code, unit, range, default; PROTOCOL.md's table).
TABLE = ParamTable(DEVICE, (
    WireParam("NX", "NX", "count", 2, 512, 32, si_name="pixels", meaning="pixels per line"),
    WireParam("NY", "NY", "count", 1, 512, 32, si_name="lines", meaning="lines"),
    WireParam("PITCH", "DX", "nm", 1, 100_000, 20, si_name="pitch", meaning="pixel spacing"),
    WireParam("ZSTEP", "ZS", "pm", 1, 1_000_000, 100, read_only=True, si_name="z_step",
              meaning="height per count"),
    WireParam("SETPOINT", "SE", "percent", 1, 99, 80, si_name="setpoint",
              meaning="2-omega amplitude setpoint"),
))

#: Parameters of ``SP``/``GP`` (integers), built from :data:`TABLE`.
Param = TABLE.enum(__name__)

#: Parameters the host may only read.
READ_ONLY = frozenset(Param(p.code) for p in TABLE if p.read_only)


class Event(str, enum.Enum):
    """Words of ``0 EV <WORD>``.

    Look a member up by its value (``value``); ``names``, ``module``, ``qualname``, ``type``,
    ``start`` and ``boundary`` are the arguments of Python's functional Enum API.
    """

    BOOT = "BOOT"
    DONE = "DONE"
    ABORTED = "ABORTED"
    FAULT = "FAULT"


class State(str, enum.Enum):
    """States of ``OK ST <state> <row> <col>``.

    Look a member up by its value (``value``); ``names``, ``module``, ``qualname``, ``type``,
    ``start`` and ``boundary`` are the arguments of Python's functional Enum API.
    """

    IDLE = "IDLE"
    SCANNING = "SCANNING"
    FAULT = "FAULT"


def command(seq: int, code: Command, *args) -> Frame:
    """A host command frame.

    Parameters
    ----------
    seq : int
        1..255.
    code : Command
        The command.
    *args : int or str
        Its arguments (a :class:`Param` is sent as its code).

    Raises
    ------
    ValueError
        Naming ``code`` if it is not a command, or ``seq``/``args[i]`` (see Frame).
    """
    return Frame(seq, _lookup("code", Command, code).value,
                 tuple(a.value if isinstance(a, enum.Enum) else a for a in args))


def pixel(row: int, col: int, counts: int) -> Frame:
    """The stream frame of one pixel, ``0 PX row col counts``.

    Parameters
    ----------
    row, col : int
        The pixel (row 0 scanned first, col along the fast axis).
    counts : int
        Its height in counts of ZS pm.

    Raises
    ------
    ValueError
        Naming the argument that is not an integer in its range (row and col >= 0, int32).
    """
    return Frame(0, "PX", (check_integer("row", row, 0, INT_MAX),
                           check_integer("col", col, 0, INT_MAX),
                           check_integer("counts", counts, INT_MIN, INT_MAX)))


def line_end(row: int, n: int) -> Frame:
    """The end of line ``row`` of ``n`` pixels, ``0 LN row n``.

    Parameters
    ----------
    row : int
        The line.
    n : int
        Its pixels.

    Raises
    ------
    ValueError
        Naming the argument that is not an integer in 0..2147483647.
    """
    return Frame(0, "LN", (check_integer("row", row, 0, INT_MAX),
                           check_integer("n", n, 0, INT_MAX)))


def event(word: Event, *args) -> Frame:
    """An event frame ``0 EV WORD [ARG]``.

    Parameters
    ----------
    word : Event
        The event.
    *args : int or str
        Its argument.

    Raises
    ------
    ValueError
        Naming ``word`` if it is not an :class:`Event`.
    """
    return event_frame(_lookup("word", Event, word), *args)


def stream_error(code: ErrorCode) -> Frame:
    """The unsolicited error ``0 ER n`` that ends a faulted scan.

    Parameters
    ----------
    code : ErrorCode
        The error.

    Raises
    ------
    ValueError
        Naming ``code`` if it is not an :class:`~afmsmiler.hardware.errors.ErrorCode`.
    """
    return error_frame(0, _lookup("code", ErrorCode, code))
