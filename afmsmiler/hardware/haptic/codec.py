"""The haptic device's protocol: codes, parameters and messages (pure, no I/O).

Device ``HAPTIC``, protocol version 1, 1 000 000 baud (a 16 MHz AVR makes it exactly: UBRR = 1
with U2X), frames of the module (h) contract (:mod:`afmsmiler.hardware.framing`). The names and
values of :class:`Command`, :class:`ErrorCode`, :class:`Event` and :class:`Param` are those of
``hardware/haptic/protocol.h`` (a test parses it). No floats on the wire: each quantity is an
integer in the unit :data:`PARAMETERS` names; this module converts to and from SI.

- host -> device stream (SEQ 0, no reply): ``0 FO <force uN>``, the force setpoint;
- device -> host stream (SEQ 0): ``0 PO <position um> <velocity um/s> <time us>``, the handle's
  position and velocity at the device's clock (microseconds modulo 2^31), and events
  ``0 EV <WORD>`` (:class:`Event`);
- ``n ST`` -> ``n OK ST <state> <flags> <position um> <force uN>``: :class:`Status`.
"""
from __future__ import annotations

import enum
import inspect
import math
from dataclasses import dataclass
from types import MappingProxyType

from ..framing import Frame

__all__ = ["DEVICE", "BAUDRATE", "FIRMWARE_VERSION", "Command", "ErrorCode", "Event", "Param",
           "ParamSpec", "PARAMETERS", "STATES", "Flag", "Status", "PositionSample",
           "force_frame", "parse_position", "parse_status", "param_to_wire", "param_from_wire",
           "TIME_WRAP"]

#: The name the device reports to ``ID``.
DEVICE = "HAPTIC"
#: Serial speed in baud.
BAUDRATE = 1_000_000
#: The firmware version the twin reports.
FIRMWARE_VERSION = "0.1.0"
#: The device clock in ``PO`` frames wraps at this many microseconds.
TIME_WRAP = 2 ** 31


class Command(str, enum.Enum):
    """Frame codes (``CMD_<NAME>`` of protocol.h): host commands, then the device's codes."""

    IDENTIFY = "ID"
    SET = "SP"
    GET = "GP"
    ENABLE = "EN"
    DISABLE = "DS"
    ZERO = "ZR"
    STREAM = "SS"
    STATUS = "ST"
    ESTOP = "ES"
    FORCE = "FO"
    POSITION = "PO"
    EVENT = "EV"
    OK = "OK"
    ERROR = "ER"


class ErrorCode(enum.IntEnum):
    """Error numbers shared by every device of module (h) (``ERR_<NAME>``)."""

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


class Event(str, enum.Enum):
    """Event words of ``0 EV <WORD>`` (``EVT_<NAME>``)."""

    BOOT = "BOOT"
    WATCHDOG = "WATCHDOG"
    ESTOP = "ESTOP"
    LIMIT = "LIMIT"


class Param(str, enum.Enum):
    """Parameter codes of ``SP``/``GP`` (``PAR_<NAME>``)."""

    MAX_FORCE = "MF"
    FORCE_SCALE = "FS"
    SPRING = "KS"
    WALL_STIFFNESS = "KW"
    WALL_POSITION = "XW"
    QGAIN = "QG"
    QPHASE = "QP"
    QFREQ = "QF"
    WATCHDOG = "WD"
    VFILTER = "VF"
    TRAVEL = "XL"
    RESOLUTION = "RE"
    FORCE_CONSTANT = "KT"
    CURRENT_LIMIT = "IL"


class Flag(enum.IntFlag):
    """Status flags (config.h ``FLAG_<NAME>``), set since the previous ``ST``."""

    SATURATED = 1
    WATCHDOG = 2
    LIMIT = 4
    ESTOP = 8


# an enum is called with one code (``Command("ID")``): say so to introspection (numpydoc checks)
for _enum in (Command, ErrorCode, Event, Param, Flag):
    _enum.__signature__ = inspect.Signature(
        [inspect.Parameter("value", inspect.Parameter.POSITIONAL_ONLY)])
    _enum.__doc__ += "\n\n    ``{0}(value)`` looks a member up by its wire value.\n".format(
        _enum.__name__)
del _enum

#: The device's states, as ``ST`` reports them.
STATES = ("IDLE", "ACTIVE", "FAULT")


@dataclass(frozen=True)
class ParamSpec:
    """One device parameter: its wire unit, SI scale, range and default.

    Parameters
    ----------
    name : str
        The quantity's name in SI (``"max_force"``).
    si_unit : str
        Its SI unit (``"N"``, ``"N/m"``, ``"m"``, ``"rad"``, ``"Hz"``, ``"s"``, ``""``, ``"A"``).
    scale : float
        SI value of one wire unit (1e-6 for uN).
    low, high : int
        Valid range on the wire (inclusive).
    default : int
        The firmware's value after reset, on the wire.
    read_only : bool
        Set by the mechanics (``SP`` answers ``ER 3``).
    """

    name: str
    si_unit: str
    scale: float
    low: int
    high: int
    default: int
    read_only: bool = False


_MDEG = math.pi / 180e3  # one millidegree in rad
#: Param -> ParamSpec: wire units, ranges and the firmware's defaults (haptic.ino has the same).
PARAMETERS = MappingProxyType({
    Param.MAX_FORCE: ParamSpec("max_force", "N", 1e-6, 0, 5_000_000, 2_000_000),
    Param.FORCE_SCALE: ParamSpec("force_scale", "", 1e-3, -1_000_000, 1_000_000, 1000),
    Param.SPRING: ParamSpec("spring", "N/m", 1e-3, 0, 2_000_000, 0),
    Param.WALL_STIFFNESS: ParamSpec("wall_stiffness", "N/m", 1e-3, 0, 5_000_000, 0),
    Param.WALL_POSITION: ParamSpec("wall_position", "m", 1e-6, -50_000, 50_000, 10_000),
    Param.QGAIN: ParamSpec("qgain", "", 1e-3, -10_000, 10_000, 0),
    Param.QPHASE: ParamSpec("qphase", "rad", _MDEG, -180_000, 180_000, 90_000),
    Param.QFREQ: ParamSpec("qfreq", "Hz", 1e-3, 100, 1_000_000, 10_000),
    Param.WATCHDOG: ParamSpec("watchdog", "s", 1e-3, 5, 1000, 50),
    Param.VFILTER: ParamSpec("vfilter", "Hz", 1.0, 10, 500, 200),
    Param.TRAVEL: ParamSpec("travel", "m", 1e-6, 1000, 60_000, 40_000),
    Param.RESOLUTION: ParamSpec("resolution", "m", 1e-9, 1, 100_000, 7670, read_only=True),
    Param.FORCE_CONSTANT: ParamSpec("force_constant", "N/A", 1e-3, 1, 1_000_000, 1760,
                                    read_only=True),
    Param.CURRENT_LIMIT: ParamSpec("current_limit", "A", 1e-3, 1, 100_000, 1500,
                                   read_only=True),
})

_INT32 = 2 ** 31 - 1


def param_to_wire(param, value: float) -> int:
    """The wire integer of an SI value of a parameter, checked against its range.

    Parameters
    ----------
    param : Param or str
        The parameter (``Param.MAX_FORCE`` or ``"MF"``).
    value : float
        Its value in SI units (see :data:`PARAMETERS`).

    Returns
    -------
    int

    Raises
    ------
    ValueError
        Naming the parameter, the value and the valid range (in SI) when it is outside it.
    """
    p = Param(param)
    spec = PARAMETERS[p]
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ValueError(f"{spec.name} must be a finite number ({spec.si_unit or 'ratio'}), "
                         f"got {value!r}")
    wire = round(value / spec.scale)
    if not spec.low <= wire <= spec.high:
        unit = f" {spec.si_unit}" if spec.si_unit else ""
        raise ValueError(f"{spec.name} must be in [{spec.low * spec.scale:g}, "
                         f"{spec.high * spec.scale:g}]{unit}, got {value!r}")
    return int(wire)


def param_from_wire(param, wire: int) -> float:
    """The SI value of a parameter's wire integer.

    Parameters
    ----------
    param : Param or str
        The parameter.
    wire : int
        The integer the device sent.

    Returns
    -------
    float
    """
    return PARAMETERS[Param(param)].scale * int(wire)


def force_frame(force: float) -> Frame:
    """The stream frame ``0 FO <force uN>`` of a force setpoint in N (clipped to int32).

    Parameters
    ----------
    force : float
        Force on the handle in N, positive along +x.

    Returns
    -------
    Frame
    """
    micro = round(force * 1e6) if math.isfinite(force) else 0
    return Frame(0, Command.FORCE.value, (max(-_INT32, min(_INT32, micro)),))


@dataclass(frozen=True)
class PositionSample:
    """One ``PO`` frame in SI units.

    Parameters
    ----------
    position : float
        Handle position in m.
    velocity : float
        Handle velocity in m/s (the firmware's filtered estimate).
    device_time : float
        The device's clock in s (wraps at 2^31 us, about 35.8 min).
    """

    position: float
    velocity: float
    device_time: float


def parse_position(frame: Frame) -> PositionSample:
    """A ``0 PO <um> <um/s> <us>`` frame as a :class:`PositionSample`.

    Parameters
    ----------
    frame : Frame
        The frame (code ``PO``).

    Returns
    -------
    PositionSample

    Raises
    ------
    ValueError
        If the frame is not a well-formed ``PO`` frame.
    """
    a = frame.args
    if frame.code != Command.POSITION.value or len(a) != 3 or \
            not all(isinstance(x, int) for x in a):
        raise ValueError(f"not a PO frame with 3 integers: {frame!r}")
    return PositionSample(a[0] * 1e-6, a[1] * 1e-6, a[2] * 1e-6)


@dataclass(frozen=True)
class Status:
    """The reply to ``ST`` in SI units.

    Parameters
    ----------
    state : str
        One of :data:`STATES`.
    flags : Flag
        What happened since the previous ``ST`` (saturation, watchdog, limit, E-stop).
    position : float
        Handle position in m.
    force : float
        The force the motor was last asked for in N (after saturation).
    """

    state: str
    flags: Flag
    position: float
    force: float

    @property
    def saturated(self) -> bool:
        """Whether the force was clipped at the maximum force since the previous status."""
        return bool(self.flags & Flag.SATURATED)


def parse_status(frame: Frame) -> Status:
    """``n OK ST <state> <flags> <um> <uN>`` as a :class:`Status`.

    Parameters
    ----------
    frame : Frame
        The OK reply to ``ST``.

    Returns
    -------
    Status

    Raises
    ------
    ValueError
        If the frame is not such a reply.
    """
    a = frame.args
    if frame.code != "OK" or len(a) != 5 or a[0] != "ST" or a[1] not in STATES or \
            not all(isinstance(x, int) for x in a[2:]):
        raise ValueError(f"not an OK ST reply: {frame!r}")
    return Status(a[1], Flag(a[2] & 15), a[3] * 1e-6, a[4] * 1e-6)
