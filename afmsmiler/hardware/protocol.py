"""One declarative table per device protocol: each parameter's wire code, unit, range and default.

Pure (no I/O). A device's parameters are described once, here in the shape of scikit-rf's
``skrf.vi`` command descriptors: a :class:`WireParam` names the parameter (``PAR_<NAME>`` of the
firmware's ``protocol.h``), its two-letter code, its wire unit (a key of :data:`WIRE_UNITS`, the one
table of wire-unit factors), its range and default on the wire, and whether the host may set it. A
:class:`ParamTable` gathers a device's parameters; its codec builds the ``Param`` enum from it, its
twin takes ranges and defaults from it, its driver converts SI values and checks every reply
against it. ``tests/test_hardware_protocol.py`` parses each device's ``PROTOCOL.md`` parameter
table, ``protocol.h`` and firmware limits and fails when they disagree with the table.

Examples
--------
>>> nx = WireParam("NX", "NX", "count", 1, 128, 8, meaning="pixels per line")
>>> nx.check_reply(64)
64
>>> nx.check_reply(2 ** 31 - 1)
Traceback (most recent call last):
...
afmsmiler.hardware.errors.ReplyError: the device reported NX (pixels per line) = 2147483647, \
outside its valid range 1..128
"""
from __future__ import annotations

import enum
import inspect
import math
import re
from dataclasses import dataclass, field
from numbers import Integral
from types import MappingProxyType

from ..parameters import UNITS
from ..validation import _short, check_finite, check_integer, check_positive
from .errors import ReplyError
from .framing import _CODE, INT_MAX, INT_MIN

__all__ = ["WireUnit", "WIRE_UNITS", "WireParam", "ParamTable", "UnknownParameter"]

_NAME = re.compile(r"[A-Z][A-Z0-9_]*")
_DEVICE = re.compile(r"[A-Z][A-Z0-9_]*")


class UnknownParameter(KeyError, ValueError):
    """A name or code a device's :class:`ParamTable` does not have (a KeyError, and a
    ValueError as the rest of the API raises for a bad value).

    Parameters
    ----------
    message : str
        Naming the parameter asked for and the ones the table has.
    """

    def __str__(self):
        return str(self.args[0]) if self.args else ""


def _lookup(name: str, kind: type, value):
    """The member of the enum ``kind`` that ``value`` is or names (its wire value), else a
    ValueError naming ``name``, the value and the valid values (the codecs' shared check)."""
    try:  # True and 3.0 would find the members 1 and 3 of an int enum
        if isinstance(value, bool) or (issubclass(kind, int) and not isinstance(value,
                                                                                 Integral)):
            raise TypeError
        return kind(value)
    except (ValueError, TypeError):
        raise ValueError(f"{name} must be one of {[m.value for m in kind]}, got "
                         f"{_short(value)}") from None


def _si_to_wire(name: str, value, scale: float, unit: str) -> int:
    """The int32 on the wire of an SI value in units of ``scale`` (``unit`` for the message),
    rounded; a ValueError naming ``name`` for what is not a finite number or does not fit."""
    x = check_finite(name, value, unit)
    wire = round(x / scale)
    if not INT_MIN <= wire <= INT_MAX:
        raise ValueError(f"{name} must be within +-{INT_MAX * scale:g} {unit} (an int32 of "
                         f"{scale:g} {unit} on the wire), got {x!r}")
    return wire


def _known_flags(name: str, kind: type, value) -> enum.IntFlag:
    """``value`` as the IntFlag ``kind``, refused naming ``name`` if it is not an integer or
    has a bit that ``kind`` does not name (dropping it would hide a fault)."""
    known = sum(f.value for f in kind)
    value = check_integer(name, value, 0, INT_MAX)
    if value & ~known:
        raise ValueError(f"{name} has bits this driver does not know ({value & ~known}; "
                         f"protocol version 1 knows {known} = "
                         f"{' | '.join(f'{f.value} {f.name}' for f in kind)}), got {value}")
    return kind(value)


@dataclass(frozen=True)
class WireUnit:
    """One unit of integers on the wire.

    Parameters
    ----------
    si_unit : str
        The SI unit it measures (``"m"``, ``"N/m"``, ``""`` for a count or a ratio).
    scale : float
        SI value of one wire unit (``1e-6`` for um).
    spellings : tuple of str
        How the protocols' ``PROTOCOL.md`` tables write it (the first is the canonical one).
    """

    si_unit: str
    scale: float
    spellings: tuple = ()

    def __post_init__(self):
        if not isinstance(self.si_unit, str):
            raise TypeError(f"si_unit must be a str (an SI unit, '' for none), got "
                            f"{_short(self.si_unit)}")
        scale = check_positive("scale", self.scale)
        if isinstance(self.spellings, str) or not isinstance(self.spellings, (tuple, list)) \
                or not all(isinstance(w, str) for w in self.spellings):
            raise TypeError(f"spellings must be a tuple of str, got {_short(self.spellings)}")
        object.__setattr__(self, "scale", scale)
        object.__setattr__(self, "spellings", tuple(self.spellings))


def _u(name: str) -> float:
    return UNITS[name][1]


#: The one table of wire units: key -> :class:`WireUnit` (factors from
#: :data:`afmsmiler.parameters.UNITS`).
WIRE_UNITS = MappingProxyType({
    "count": WireUnit("", 1.0, ("", "pixels", "lines", "counts")),
    "step": WireUnit("", 1.0, ("z micro-steps",)),
    "step/s": WireUnit("1/s", 1.0, ("steps/s",)),
    "step/s^2": WireUnit("1/s^2", 1.0, ("steps/s²", "steps/s^2")),
    "um": WireUnit("m", _u("um"), ("µm", "um")),
    "nm": WireUnit("m", _u("nm"), ("nm",)),
    "pm": WireUnit("m", _u("pm"), ("pm",)),
    "nm/count": WireUnit("m", _u("nm"), ("nm/count",)),
    "uN": WireUnit("N", _u("uN"), ("uN", "µN")),
    "mN/m": WireUnit("N/m", _u("mN"), ("mN/m",)),
    "uN/mA": WireUnit("N/A", _u("uN") / _u("mA"), ("uN/mA",)),
    "mA": WireUnit("A", _u("mA"), ("mA",)),
    "ms": WireUnit("s", _u("ms"), ("ms",)),
    "us": WireUnit("s", _u("us"), ("us", "µs")),
    "um/s": WireUnit("m/s", _u("um/s"), ("um/s", "µm/s")),
    "Hz": WireUnit("Hz", _u("Hz"), ("Hz",)),
    "mHz": WireUnit("Hz", _u("Hz") * 1e-3, ("mHz",)),
    "mdeg": WireUnit("rad", _u("deg") * 1e-3, ("millidegree",)),
    "permille": WireUnit("", 1e-3, ("1/1000",)),
    "percent": WireUnit("", 1e-2, ("% of the free amplitude", "%")),
})


@dataclass(frozen=True)
class WireParam:
    """One integer parameter of ``SP``/``GP``, described once.

    Parameters
    ----------
    name : str
        Its name in ``protocol.h`` (``PAR_<name>``) and in the codec's ``Param`` enum.
    code : str
        The two uppercase letters on the wire.
    unit : str
        Its wire unit, a key of :data:`WIRE_UNITS`.
    low, high : int
        The valid range on the wire, inclusive (the firmware's; for a read-only parameter the
        values a device may report).
    default : int
        The firmware's value after reset.
    read_only : bool
        Set by the mechanics: ``SP`` answers ``ER 3``.
    multiple : int
        The value must be a multiple of this (1: any integer).
    si_name : str
        The quantity's name at the driver's SI API (``""``: the driver has none).
    meaning : str
        What it is, in a few words (error messages say it).
    """

    name: str
    code: str
    unit: str
    low: int
    high: int
    default: int
    read_only: bool = False
    multiple: int = 1
    si_name: str = ""
    meaning: str = ""

    def __post_init__(self):
        if not isinstance(self.name, str) or not _NAME.fullmatch(self.name):
            raise ValueError(f"name must be a protocol.h name (PAR_<name>) of [A-Z0-9_], got "
                             f"{_short(self.name)}")
        label = f"parameter {self.name}"
        if not (isinstance(self.code, str) and _CODE.fullmatch(self.code)):
            raise ValueError(f"{label}: code must be two uppercase letters, got "
                             f"{_short(self.code)}")
        if not isinstance(self.unit, str) or self.unit not in WIRE_UNITS:
            raise ValueError(f"{label}: unit must be a key of WIRE_UNITS "
                             f"({', '.join(WIRE_UNITS)}), got {_short(self.unit)}")
        for field_name in ("low", "high", "default"):
            check_integer(f"{label}: {field_name}", getattr(self, field_name), INT_MIN, INT_MAX)
        if self.low > self.high:
            raise ValueError(f"{label}: low must be <= high, got low={self.low}, "
                             f"high={self.high}")
        check_integer(f"{label}: multiple", self.multiple, 1, INT_MAX)
        if not isinstance(self.read_only, bool):
            raise TypeError(f"{label}: read_only must be a bool, got {_short(self.read_only)}")
        if not isinstance(self.si_name, str) or not (self.si_name == ""
                                                     or self.si_name.isidentifier()):
            raise ValueError(f"{label}: si_name must be '' or a Python name, got "
                             f"{_short(self.si_name)}")
        if not isinstance(self.meaning, str):
            raise TypeError(f"{label}: meaning must be a str, got {_short(self.meaning)}")
        for field_name in ("low", "high", "default", "multiple"):
            object.__setattr__(self, field_name, int(getattr(self, field_name)))
        if not self.low <= self.default <= self.high or self.default % self.multiple:
            raise ValueError(f"{label}: default {self.default} outside {self._range()} (low..high, "
                             f"a multiple of multiple)")

    # -- units -----------------------------------------------------------------------------
    @property
    def si_unit(self) -> str:
        """The SI unit the wire unit measures."""
        return WIRE_UNITS[self.unit].si_unit

    @property
    def scale(self) -> float:
        """SI value of one wire unit."""
        return WIRE_UNITS[self.unit].scale

    def to_si(self, wire: int) -> float:
        """The SI value of a wire integer.

        Parameters
        ----------
        wire : int
            The integer on the wire.

        Returns
        -------
        float

        Raises
        ------
        ValueError
            Naming the parameter, if ``wire`` is not an integer in int32.
        """
        label = f"wire value of {self.name}"
        return self.scale * check_integer(label, wire, INT_MIN, INT_MAX)

    def to_wire(self, value: float) -> int:
        """The wire integer of an SI value, rounded and checked against the range.

        Parameters
        ----------
        value : float
            The value in :attr:`si_unit`.

        Returns
        -------
        int

        Raises
        ------
        ValueError
            Naming the parameter, the value and the valid range in SI.
        """
        return self._to_wire(value, self.si_name or self.name)

    def _to_wire(self, value, label: str) -> int:
        """:meth:`to_wire`, its messages naming the value ``label`` (a caller's parameter)."""
        unit = f" {self.si_unit}" if self.si_unit else ""
        try:
            value = check_finite(label, value, self.si_unit)
        except ValueError:
            raise ValueError(f"{label} must be a finite number{unit and ' in' + unit}, "
                             f"got {_short(value)}") from None
        wire = value / self.scale / self.multiple
        if not abs(wire) < 2.0 ** 62:
            wire = math.copysign(2.0 ** 62, wire)  # past either end: refused below
        wire = round(wire) * self.multiple
        if not self.low <= wire <= self.high:
            raise ValueError(f"{label} must be in [{self.low * self.scale:g}, "
                             f"{self.high * self.scale:g}]{unit}, got {value!r}")
        return int(wire)

    # -- checks ----------------------------------------------------------------------------
    def _range(self) -> str:
        step = f" in steps of {self.multiple}" if self.multiple != 1 else ""
        unit = f" {self.unit}" if self.unit not in ("count",) else ""
        return f"{self.low}..{self.high}{unit}{step}"

    def valid(self, wire) -> bool:
        """Whether ``wire`` is a valid value of this parameter (an int in range, on the grid).

        Parameters
        ----------
        wire : object
            The value to test.

        Returns
        -------
        bool
        """
        return (isinstance(wire, int) and not isinstance(wire, bool)
                and self.low <= wire <= self.high and wire % self.multiple == 0)

    def check(self, wire) -> int:
        """A value the host is about to send, checked (the firmware would answer ``ER 3``).

        Parameters
        ----------
        wire : int
            The integer.

        Returns
        -------
        int

        Raises
        ------
        ValueError
            If it is read-only, not an integer or outside the range (named).
        """
        return self._check(wire, f"{self.name} ({self.meaning or self.code})")

    def _check(self, wire, label: str) -> int:
        """:meth:`check`, its range message naming the value ``label`` (a caller's parameter)."""
        if self.read_only:
            raise ValueError(f"{self.name} ({self.meaning or self.code}) is read-only")
        if not self.valid(wire):
            raise ValueError(f"{label} must be an integer {self._range()}, got {_short(wire)}")
        return int(wire)

    def _value_label(self, name: str) -> str:
        """How a setter's messages name its argument ``name``: ``value for NX (pixels per line)``."""
        return f"{name} for {self.name} ({self.meaning or self.code})"

    def check_reply(self, wire) -> int:
        """A value a device reported, checked against the table.

        Parameters
        ----------
        wire : int
            The integer the device sent.

        Returns
        -------
        int

        Raises
        ------
        ReplyError
            Naming the parameter, the value and the valid range.
        """
        if not self.valid(wire):
            raise ReplyError(f"the device reported {self.name} ({self.meaning or self.code}) = "
                             f"{_short(wire)}, outside its valid range {self._range()}")
        return int(wire)


@dataclass(frozen=True)
class ParamTable:
    """A device's parameters (:class:`WireParam`), in the order of its ``PROTOCOL.md``.

    Parameters
    ----------
    device : str
        The device's name in its ``ID`` reply.
    params : tuple of WireParam
        Its parameters.
    """

    device: str
    params: tuple
    _by_code: dict = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        if not isinstance(self.device, str) or not _DEVICE.fullmatch(self.device):
            raise ValueError(f"device must be the name in the device's ID reply "
                             f"([A-Z0-9_]+), got {_short(self.device)}")
        if isinstance(self.params, (str, bytes)) or not hasattr(self.params, "__iter__"):
            raise TypeError(f"params must be a tuple of WireParam, got {_short(self.params)}")
        params = tuple(self.params)
        if not all(isinstance(p, WireParam) for p in params):
            raise TypeError(f"params must be WireParam descriptions, got "
                            f"{sorted({type(p).__name__ for p in params})}")
        by_code = {p.code: p for p in params}
        if len(by_code) != len(params) or len({p.name for p in params}) != len(params):
            raise ValueError(f"{self.device}: parameter names and codes must be unique")
        object.__setattr__(self, "params", params)
        object.__setattr__(self, "_by_code", by_code)

    def __iter__(self):
        return iter(self.params)

    def __len__(self) -> int:
        return len(self.params)

    def __getitem__(self, code) -> WireParam:
        """The parameter of a code (``"NX"``, or a ``Param`` member).

        Parameters
        ----------
        code : str or Param
            The two letters.

        Returns
        -------
        WireParam
        """
        key = code.value if isinstance(code, enum.Enum) else code
        try:
            return self._by_code[key]
        except (KeyError, TypeError):
            raise UnknownParameter(f"{self.device} has no parameter {_short(code)}; it has "
                                   f"{sorted(self._by_code)}") from None

    def by_si_name(self, name: str) -> WireParam:
        """The parameter of an SI name (``"max_force"``).

        Parameters
        ----------
        name : str
            The SI name.

        Returns
        -------
        WireParam

        Raises
        ------
        KeyError
            For a name the table does not have (a ``LookupError``, and a ``ValueError`` too).
        TypeError
            If ``name`` is not a str.
        """
        if not isinstance(name, str):
            raise TypeError(f"name must be a str (an SI name), got {_short(name)}")
        for p in self.params:
            if p.si_name and p.si_name == name:
                return p
        names = [p.si_name for p in self.params if p.si_name]
        raise UnknownParameter(f"{self.device} has no parameter called {_short(name)}: name "
                               f"must be one of {names}")

    def enum(self, module: str, doc: str = "") -> type:
        """The codec's ``Param`` enum: members named as in protocol.h, valued by their code.

        Parameters
        ----------
        module : str
            The codec module that holds the enum (for pickling and the docs).
        doc : str
            The enum's docstring.

        Returns
        -------
        type
            A ``str`` enum; ``Param("NX")`` looks a member up by its code.
        """
        if not isinstance(module, str) or not all(part.isidentifier()
                                                  for part in module.split(".")):
            raise ValueError(f"module must be a dotted module name, got {_short(module)}")
        if not isinstance(doc, str):
            raise TypeError(f"doc must be a str, got {_short(doc)}")
        kind = enum.Enum("Param", [(p.name, p.code) for p in self.params], type=str,
                         module=module)
        kind.__doc__ = doc or (f"Parameters of ``SP``/``GP`` of the {self.device} "
                               f"(``PAR_<NAME>``).\n\n    Parameters\n    ----------\n"
                               f"    value : str\n        The two letters on the wire.\n")
        kind.__signature__ = inspect.Signature(
            [inspect.Parameter("value", inspect.Parameter.POSITIONAL_OR_KEYWORD)])
        return kind

    def defaults(self) -> dict:
        """Code -> the firmware's value after reset.

        Returns
        -------
        dict
        """
        return {p.code: p.default for p in self.params}

    def check_reply(self, results, command: str) -> int:
        """The value of a ``OK SP|GP <PAR> <int>`` reply's results, checked against the table.

        Parameters
        ----------
        results : tuple
            The reply's results after the echoed command (``(PAR, value)``).
        command : str
            ``"SP"`` or ``"GP"`` (for the message).

        Returns
        -------
        int

        Raises
        ------
        ReplyError
            If the results are not one known parameter and an integer in its range.
        ValueError
            If ``command`` is not ``"SP"`` or ``"GP"``.
        """
        if not isinstance(command, str) or command not in ("SP", "GP"):
            raise ValueError(f"command must be 'SP' or 'GP', got {_short(command)}")
        if not isinstance(results, (tuple, list)) or len(results) != 2 \
                or not isinstance(results[0], str):
            raise ReplyError(f"{self.device}'s {command} reply must be <PAR> <int>, "
                             f"got {_short(results)} (results)")
        if results[0] not in self._by_code:
            raise ReplyError(f"{self.device}'s {command} reply names an unknown parameter "
                             f"{_short(results[0])} (results)")
        return self._by_code[results[0]].check_reply(results[1])
