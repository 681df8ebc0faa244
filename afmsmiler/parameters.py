"""One description per quantity: SI unit, display unit, default, valid and slider ranges.

Every model parameter that a student can set from a slider, and every input of a signal chain, is
described once by a :class:`Parameter`: its name, its SI unit, the practical unit that widgets and
plots show, its default, its valid range (what the model accepts), its slider range (a part of the
valid range), linear or logarithmic, and a label. Models validate with :meth:`Parameter.check`;
the panels build every control from the same description (:func:`afmsmiler.ui.controls.control`),
so a widget can never produce a value the model rejects; docs, tables and exercises read the same
entries instead of typing the numbers again.

The display scale is never typed: it is derived from the display unit's name through one table,
:data:`UNITS` (display unit -> SI unit and the SI value of one display unit), which also checks
that the display unit measures the same quantity as the SI unit (``"nm"`` for ``"m"``, not for
``"N"``).

Examples
--------
>>> p = Parameter(name="length", unit="m", display_unit="um", default=450e-6,
...               low=20e-6, high=1e-3, label="lever length L")
>>> p.scale  # display value = SI value * scale
1000000.0
>>> p.to_display(450e-6)
450.0
>>> p.check(2e-3)
Traceback (most recent call last):
...
ValueError: length must be in [2e-05, 0.001] m, got 0.002
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from types import MappingProxyType

import numpy as np

from .validation import check_range

__all__ = ["UNITS", "Parameter", "unit_scale", "read_only"]


def read_only(mapping) -> MappingProxyType:
    """A read-only view of ``mapping`` (for module-level ``DEFAULTS``).

    Parameters
    ----------
    mapping : dict
        The defaults.

    Returns
    -------
    types.MappingProxyType
        Reads like a dict; item assignment raises ``TypeError``.
    """
    return MappingProxyType(dict(mapping))


_MU = "\u00b5"

#: Display unit -> (SI unit, SI value of one display unit). The only place a unit's factor is
#: written; ``Parameter.scale`` and every conversion in the panels derive from it.
UNITS = MappingProxyType({
    # length
    "m": ("m", 1.0), "mm": ("m", 1e-3), "um": ("m", 1e-6), "nm": ("m", 1e-9),
    "pm": ("m", 1e-12),
    "1/m": ("1/m", 1.0), "1/um": ("1/m", 1e6),
    # angle
    "rad": ("rad", 1.0), "mrad": ("rad", 1e-3), "deg": ("rad", math.pi / 180.0),
    # force, stiffness, pressure, energy per area
    "N": ("N", 1.0), "uN": ("N", 1e-6), "nN": ("N", 1e-9), "pN": ("N", 1e-12),
    "N/m": ("N/m", 1.0), "N m": ("N m", 1.0), "nN m": ("N m", 1e-9),
    "Pa": ("Pa", 1.0), "kPa": ("Pa", 1e3), "MPa": ("Pa", 1e6), "GPa": ("Pa", 1e9),
    "J/m^2": ("J/m^2", 1.0), "mJ/m^2": ("J/m^2", 1e-3),
    "1/Pa": ("1/Pa", 1.0), "1e-11/Pa": ("1/Pa", 1e-11),
    # mass, density, damping
    "kg": ("kg", 1.0), "ng": ("kg", 1e-12), "kg/m^3": ("kg/m^3", 1.0),
    "kg/s": ("kg/s", 1.0), "ng/us": ("kg/s", 1e-12 / 1e-6),
    # time, frequency, speed
    "s": ("s", 1.0), "ms": ("s", 1e-3), "us": ("s", 1e-6),
    "1/s": ("1/s", 1.0), "1/us": ("1/s", 1e6),
    "Hz": ("Hz", 1.0), "kHz": ("Hz", 1e3), "MHz": ("Hz", 1e6), "GHz": ("Hz", 1e9),
    "m/s": ("m/s", 1.0), "mm/s": ("m/s", 1e-3), "um/s": ("m/s", 1e-6),
    "Hz/m": ("Hz/m", 1.0), "GHz/nm": ("Hz/m", 1e9 / 1e-9),
    # electrical, magnetic, optical
    "V": ("V", 1.0), "mV": ("V", 1e-3), "uV": ("V", 1e-6),
    "C": ("C", 1.0), "fC": ("C", 1e-15),
    "A": ("A", 1.0), "mA": ("A", 1e-3), "uA": ("A", 1e-6),
    "W": ("W", 1.0), "mW": ("W", 1e-3), "uW": ("W", 1e-6),
    "ohm": ("ohm", 1.0), "kohm": ("ohm", 1e3),
    "T": ("T", 1.0), "mT": ("T", 1e-3),
    "A/W": ("A/W", 1.0), "m/V": ("m/V", 1.0), "nm/V": ("m/V", 1e-9), "pm/V": ("m/V", 1e-12),
    # transducer sensitivities (output per tip deflection, deflection per drive)
    "V/m": ("V/m", 1.0), "uV/nm": ("V/m", 1e-6 / 1e-9), "W/m": ("W/m", 1.0),
    "uW/nm": ("W/m", 1e-6 / 1e-9), "C/m": ("C/m", 1.0), "fC/nm": ("C/m", 1e-15 / 1e-9),
    "m/A": ("m/A", 1.0), "nm/mA": ("m/A", 1e-9 / 1e-3), "m/W": ("m/W", 1.0),
    "nm/mW": ("m/W", 1e-9 / 1e-3),
    # temperature, number density, dimensionless
    "K": ("K", 1.0), "1/m^3": ("1/m^3", 1.0), "1/cm^3": ("1/m^3", 1e6),
    "": ("", 1.0), "x": ("", 1.0), "ppm": ("", 1e-6), "microstrain": ("", 1e-6),
})


def unit_scale(display_unit: str, unit: str | None = None) -> float:
    """Display value per SI value of ``display_unit`` (1e9 for ``"nm"``), from :data:`UNITS`.

    Parameters
    ----------
    display_unit : str
        A key of :data:`UNITS`.
    unit : str, optional
        The SI unit it must measure (checked when given).

    Returns
    -------
    float
        ``1 / (SI value of one display unit)``.

    Raises
    ------
    ValueError
        If the display unit is unknown or measures another quantity than ``unit``.
    """
    if display_unit not in UNITS:
        raise ValueError(f"display_unit must be one of {sorted(UNITS)}, got {display_unit!r}")
    si, factor = UNITS[display_unit]
    if unit is not None and si != unit:
        raise ValueError(f"display_unit {display_unit!r} measures {si or 'a pure number'!r}, "
                         f"not {unit or 'a pure number'!r}")
    return 1.0 / factor


@dataclass(frozen=True, kw_only=True)
class Parameter:
    """A model parameter or input: name, units, default, valid range and slider range (SI).

    Parameters
    ----------
    name : str
        The keyword argument of the model (``"spring_constant"``).
    unit : str
        Its SI unit (``"m"``, ``"N/m"``, ``""`` for a pure number).
    display_unit : str
        Practical unit of widgets and plots, a key of :data:`UNITS` measuring ``unit``;
        default: the SI unit itself.
    default : float
        Default value in SI units; on the slider grid (see :func:`afmsmiler.ui.controls.control`).
    low, high : float
        Valid range in SI units (``-inf``/``inf`` for none).
    low_inclusive, high_inclusive : bool
        Whether the bounds belong to the valid range.
    slider_low, slider_high : float, optional
        The slider's range in SI units, inside the valid range; default: the valid bounds (which
        must then be finite, and closed or nudged inside by the slider factory).
    log : bool
        Logarithmic slider (the range spans decades; needs ``slider_low > 0``).
    label : str
        Human-readable label (``"lever spring constant k"``); default: the name.

    Raises
    ------
    ValueError
        If the units disagree, the default is not valid or the slider range leaves the valid range.
    """

    name: str
    unit: str
    display_unit: str | None = None
    default: float
    low: float = -math.inf
    high: float = math.inf
    low_inclusive: bool = True
    high_inclusive: bool = True
    slider_low: float | None = None
    slider_high: float | None = None
    log: bool = False
    label: str = ""

    def __post_init__(self):
        if self.display_unit is None:
            object.__setattr__(self, "display_unit", self.unit)
        unit_scale(self.display_unit, self.unit)  # raises on a unit mismatch
        lo = self.low if self.slider_low is None else self.slider_low
        hi = self.high if self.slider_high is None else self.slider_high
        object.__setattr__(self, "slider_low", float(lo))
        object.__setattr__(self, "slider_high", float(hi))
        where = f"parameter {self.name}"
        self.check(self.default)
        if not self.slider_low < self.slider_high:
            raise ValueError(f"{where}: slider range [{lo}, {hi}] is empty")
        if not (self.low <= self.slider_low and self.slider_high <= self.high):
            raise ValueError(f"{where}: slider range [{lo}, {hi}] leaves the valid range "
                             f"[{self.low}, {self.high}]")
        if self.log and not self.slider_low > 0:
            raise ValueError(f"{where}: a log slider needs slider_low > 0, got {lo}")

    # -- units -------------------------------------------------------------------------------
    @property
    def scale(self) -> float:
        """Display value per SI value (1e9 for m shown in nm), derived from the display unit."""
        return unit_scale(self.display_unit)

    def to_display(self, si_value):
        """``si_value`` (SI, scalar or array) in the display unit.

        Parameters
        ----------
        si_value : float or array_like
            Value(s) in SI units.
        """
        if np.ndim(si_value):
            return np.asarray(si_value) * self.scale
        return float(si_value) * self.scale

    def to_si(self, display_value):
        """``display_value`` (in the display unit) in SI.

        Parameters
        ----------
        display_value : float or array_like
            Value(s) in the display unit.
        """
        factor = UNITS[self.display_unit][1]
        if np.ndim(display_value):
            return np.asarray(display_value) * factor
        return float(display_value) * factor

    @property
    def title(self) -> str:
        """``"label [display unit]"`` for an axis or a slider."""
        text = self.label or self.name.replace("_", " ")
        return f"{text} [{self.display_unit}]" if self.display_unit not in ("", "x") else text

    # -- validation --------------------------------------------------------------------------
    def check(self, value) -> float:
        """Return ``value`` (SI) as float; raise ``ValueError`` naming the parameter unless valid.

        Parameters
        ----------
        value : float
            Candidate value in SI units.
        """
        return check_range(self.name, value, self.low, self.high, self.unit,
                           low_inclusive=self.low_inclusive, high_inclusive=self.high_inclusive)

    def with_(self, **changes) -> "Parameter":
        """A copy with some fields changed (a different default or slider range).

        Parameters
        ----------
        **changes
            Field names and their new values.
        """
        return replace(self, **changes)
