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
from dataclasses import dataclass, field
from types import MappingProxyType

from ..parameters import UNITS
from .errors import ReplyError

__all__ = ["WireUnit", "WIRE_UNITS", "WireParam", "ParamTable"]


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
        if self.unit not in WIRE_UNITS:
            raise ValueError(f"parameter {self.name}: unit must be a key of WIRE_UNITS, "
                             f"got {self.unit!r}")
        if not (isinstance(self.code, str) and len(self.code) == 2 and self.code.isupper()):
            raise ValueError(f"parameter {self.name}: code must be two uppercase letters, "
                             f"got {self.code!r}")
        if not self.low <= self.default <= self.high or self.default % self.multiple:
            raise ValueError(f"parameter {self.name}: default {self.default} outside "
                             f"{self._range()}")

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
        """
        return self.scale * int(wire)

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
        label = self.si_name or self.name
        unit = f" {self.si_unit}" if self.si_unit else ""
        if isinstance(value, bool) or not isinstance(value, (int, float)) or \
                not math.isfinite(value):
            raise ValueError(f"{label} must be a finite number{unit and ' in' + unit}, "
                             f"got {value!r}")
        wire = round(value / self.scale / self.multiple) * self.multiple
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
        if self.read_only:
            raise ValueError(f"{self.name} ({self.meaning or self.code}) is read-only")
        if not self.valid(wire):
            raise ValueError(f"{self.name} ({self.meaning or self.code}) must be an integer "
                             f"{self._range()}, got {wire!r}")
        return int(wire)

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
                             f"{wire!r}, outside its valid range {self._range()}")
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
        params = tuple(self.params)
        if not all(isinstance(p, WireParam) for p in params):
            raise TypeError("params must be WireParam descriptions")
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
            raise KeyError(f"{self.device} has no parameter {code!r}; it has "
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
        """
        for p in self.params:
            if p.si_name and p.si_name == name:
                return p
        raise KeyError(f"{self.device} has no parameter called {name!r}")

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
        """
        if len(results) != 2 or not isinstance(results[0], str):
            raise ReplyError(f"{self.device}'s {command} reply must be <PAR> <int>, "
                             f"got {tuple(results)!r}")
        if results[0] not in self._by_code:
            raise ReplyError(f"{self.device}'s {command} reply names an unknown parameter "
                             f"{results[0]!r}")
        return self._by_code[results[0]].check_reply(results[1])
