"""The haptic device's protocol: codes, parameters and messages (pure, no I/O).

Device ``HAPTIC``, protocol version 1, 1 000 000 baud (a 16 MHz AVR makes it exactly: UBRR = 1
with U2X), frames of the module (h) contract (:mod:`afmsmiler.hardware.framing`). The names and
values of :class:`Command`, :class:`Event`, :class:`Param` (built from :data:`TABLE`, the
parameters described once) and module (h)'s shared :class:`~afmsmiler.hardware.errors.ErrorCode`
are those of ``hardware/haptic/protocol.h`` (a test parses it). No floats on the wire: each
quantity is an integer in the unit :data:`TABLE` names (from the one unit table
:data:`~afmsmiler.hardware.protocol.WIRE_UNITS`); this module converts to and from SI, both ways
(the twin sends what :func:`position_frame` and :func:`status_results` build).

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

from ...validation import check_finite, check_integer, check_real
from ..errors import ErrorCode, ReplyError
from ..framing import INT_MAX, INT_MIN, Frame
from ..protocol import WIRE_UNITS, ParamTable, WireParam, _known_flags, _lookup, _si_to_wire

__all__ = ["DEVICE", "BAUDRATE", "FIRMWARE_VERSION", "Command", "ErrorCode", "Event", "Param",
           "TABLE", "PARAMETERS", "STATES", "Flag", "Status", "PositionSample",
           "force_frame", "force_from_wire", "parse_position", "parse_status", "position_frame",
           "status_results",
           "param_to_wire", "param_from_wire", "TIME_WRAP"]

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


class Event(str, enum.Enum):
    """Event words of ``0 EV <WORD>`` (``EVT_<NAME>``)."""

    BOOT = "BOOT"
    WATCHDOG = "WATCHDOG"
    ESTOP = "ESTOP"
    LIMIT = "LIMIT"


#: The device's parameters, described once (wire code, unit, range, default; the firmware's
#: LIMITS table in haptic.ino and PROTOCOL.md's table have the same, a test compares).
TABLE = ParamTable(DEVICE, (
    WireParam("MAX_FORCE", "MF", "uN", 0, 5_000_000, 2_000_000, si_name="max_force",
              meaning="largest force asked of the motor"),
    WireParam("FORCE_SCALE", "FS", "permille", -1_000_000, 1_000_000, 1000,
              si_name="force_scale", meaning="scale of the FO stream"),
    WireParam("SPRING", "KS", "mN/m", 0, 2_000_000, 0, si_name="spring",
              meaning="virtual spring about x = 0"),
    WireParam("WALL_STIFFNESS", "KW", "mN/m", 0, 5_000_000, 0, si_name="wall_stiffness",
              meaning="virtual wall"),
    WireParam("WALL_POSITION", "XW", "um", -50_000, 50_000, 10_000, si_name="wall_position",
              meaning="the wall's face"),
    WireParam("QGAIN", "QG", "permille", -10_000, 10_000, 0, si_name="qgain",
              meaning="Q-control gain"),
    WireParam("QPHASE", "QP", "mdeg", -180_000, 180_000, 90_000, si_name="qphase",
              meaning="Q-control phase lag"),
    WireParam("QFREQ", "QF", "mHz", 100, 1_000_000, 10_000, si_name="qfreq",
              meaning="reference frequency of the phase shifter"),
    WireParam("WATCHDOG", "WD", "ms", 5, 1000, 50, si_name="watchdog",
              meaning="force zeroed after this long without FO"),
    WireParam("VFILTER", "VF", "Hz", 10, 500, 200, si_name="vfilter",
              meaning="velocity low-pass cut-off"),
    WireParam("TRAVEL", "XL", "um", 1000, 60_000, 40_000, si_name="travel",
              meaning="soft travel limit"),
    WireParam("RESOLUTION", "RE", "nm/count", 1, 100_000, 7670, read_only=True,
              si_name="resolution", meaning="encoder resolution at the handle"),
    WireParam("FORCE_CONSTANT", "KT", "uN/mA", 1, 1_000_000, 1760, read_only=True,
              si_name="force_constant", meaning="handle force per motor current"),
    WireParam("CURRENT_LIMIT", "IL", "mA", 1, 100_000, 1500, read_only=True,
              si_name="current_limit", meaning="the amplifier's current limit"),
))

#: Parameter codes of ``SP``/``GP`` (``PAR_<NAME>``), built from :data:`TABLE`.
Param = TABLE.enum(__name__)

class Flag(enum.IntFlag):
    """Status flags (config.h ``FLAG_<NAME>``), set since the previous ``ST``."""

    SATURATED = 1
    WATCHDOG = 2
    LIMIT = 4
    ESTOP = 8


# an enum is called with one code (``Command("ID")``): say so to introspection (numpydoc checks)
for _enum in (Command, Event, Flag):
    _enum.__signature__ = inspect.Signature(
        [inspect.Parameter("value", inspect.Parameter.POSITIONAL_ONLY)])
    _enum.__doc__ += "\n\n    ``{0}(value)`` looks a member up by its wire value.\n".format(
        _enum.__name__)
del _enum

#: The device's states, as ``ST`` reports them.
STATES = ("IDLE", "ACTIVE", "FAULT")


#: Param -> its :class:`~afmsmiler.hardware.protocol.WireParam` (the rows of :data:`TABLE`).
PARAMETERS = MappingProxyType({Param(p.code): p for p in TABLE})
#: The wire units of the stream frames' quantities (``PO``, ``FO``, ``ST``).
_POSITION, _VELOCITY, _TIME, _FORCE = (WIRE_UNITS[u].scale for u in ("um", "um/s", "us", "uN"))

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
    spec = PARAMETERS[_lookup("param", Param, param)]
    return spec._to_wire(value, f"value for {spec.si_name or spec.name}")


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

    Raises
    ------
    ValueError
        Naming ``param`` (not a parameter of the device) or the wire value (not an int32).
    """
    return PARAMETERS[_lookup("param", Param, param)].to_si(wire)


def force_frame(force: float) -> Frame:
    """The stream frame ``0 FO <force uN>`` of a force setpoint in N (clipped to int32).

    Parameters
    ----------
    force : float
        Force on the handle in N, positive along +x; a non-finite force (NaN, +-inf) is sent as
        0, the safe setpoint (a force law that breaks down does not push the student's finger).

    Returns
    -------
    Frame

    Raises
    ------
    ValueError
        Naming ``force`` if it is not a real number (a string, None, a complex, 10**400).
    """
    force = check_real("force", force)
    micro = round(force / _FORCE) if math.isfinite(force) else 0
    return Frame(0, Command.FORCE.value, (max(-_INT32, min(_INT32, micro)),))


def force_from_wire(micro: int) -> float:
    """The force in N of a ``0 FO <uN>`` frame's integer (the inverse of :func:`force_frame`).

    Parameters
    ----------
    micro : int
        The integer on the wire (an int32).

    Returns
    -------
    float

    Raises
    ------
    ValueError
        Naming ``micro`` if it is not an int32.
    """
    return check_integer("micro", micro, INT_MIN, INT_MAX) * _FORCE


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

    def __post_init__(self):
        for name, unit in (("position", "m"), ("velocity", "m/s"), ("device_time", "s")):
            object.__setattr__(self, name, check_finite(name, getattr(self, name), unit))


def _check_frame(frame) -> None:
    if not isinstance(frame, Frame):
        raise TypeError(f"frame must be a Frame, got {type(frame).__name__}")


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
    ReplyError
        If the frame is not a well-formed ``PO`` frame.
    TypeError
        If ``frame`` is not a :class:`~afmsmiler.hardware.framing.Frame`.
    """
    _check_frame(frame)
    a = frame.args
    if frame.code != Command.POSITION.value or len(a) != 3 or \
            not all(isinstance(x, int) for x in a):
        raise ReplyError(f"not a PO frame with 3 integers: {frame!r}")
    return PositionSample(a[0] * _POSITION, a[1] * _VELOCITY, a[2] * _TIME)


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

    def __post_init__(self):
        if not isinstance(self.state, str) or self.state not in STATES:
            raise ValueError(f"state must be one of {list(STATES)}, got {self.state!r}")
        object.__setattr__(self, "flags", _known_flags("flags", Flag, self.flags))
        object.__setattr__(self, "position", check_finite("position", self.position, "m"))
        object.__setattr__(self, "force", check_finite("force", self.force, "N"))

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
    ReplyError
        If the frame is not such a reply, or its flags integer is negative or has a bit that
        :class:`Flag` does not name (as the macro AFM's codec: dropping it would hide a fault).
    TypeError
        If ``frame`` is not a :class:`~afmsmiler.hardware.framing.Frame`.
    """
    _check_frame(frame)
    a = frame.args
    if frame.code != "OK" or len(a) != 5 or a[0] != "ST" or a[1] not in STATES or \
            not all(isinstance(x, int) for x in a[2:]):
        raise ReplyError(f"not an OK ST reply: {frame!r}")
    known = sum(f.value for f in Flag)
    if a[2] < 0 or a[2] & ~known:
        raise ReplyError(f"status flags {a[2]} have bits this driver does not know (protocol "
                         f"version 1 knows {known} = "
                         f"{' | '.join(f'{f.value} {f.name}' for f in Flag)})")
    return Status(a[1], Flag(a[2]), a[3] * _POSITION, a[4] * _FORCE)


def position_frame(position: float, velocity: float, device_time: float) -> Frame:
    """The stream frame ``0 PO <um> <um/s> <us>`` the device sends (the inverse of
    :func:`parse_position`).

    Parameters
    ----------
    position : float
        Handle position in m.
    velocity : float
        Handle velocity in m/s.
    device_time : float
        The device's clock in s (wrapped at :data:`TIME_WRAP` microseconds).

    Returns
    -------
    Frame

    Raises
    ------
    ValueError
        Naming the quantity that is not a finite number or does not fit an int32 on the wire.
    """
    time_us = round(check_finite("device_time", device_time, "s") / _TIME) % TIME_WRAP
    return Frame(0, Command.POSITION.value, (_si_to_wire("position", position, _POSITION, "m"),
                                             _si_to_wire("velocity", velocity, _VELOCITY,
                                                         "m/s"), time_us))


def status_results(state: str, flags: int, position: float, force: float) -> tuple:
    """The results of the device's reply to ``ST`` (the inverse of :func:`parse_status`).

    Parameters
    ----------
    state : str
        One of :data:`STATES`.
    flags : int
        :class:`Flag` bits.
    position : float
        Handle position in m.
    force : float
        The force last asked of the motor in N.

    Returns
    -------
    tuple
        ``(state, flags, um, uN)``.

    Raises
    ------
    ValueError
        Naming the argument that is not one of the states, known flag bits, or a finite number
        that fits an int32 on the wire.
    """
    if not isinstance(state, str) or state not in STATES:
        raise ValueError(f"state must be one of {list(STATES)}, got {state!r}")
    return (state, int(_known_flags("flags", Flag, flags)),
            _si_to_wire("position", position, _POSITION, "m"),
            _si_to_wire("force", force, _FORCE, "N"))
