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
from decimal import Decimal
from dataclasses import dataclass, replace
from collections.abc import Mapping
from types import MappingProxyType

import numpy as np

from .validation import check_range, check_real

__all__ = ["UNITS", "Parameter", "unit_scale", "read_only", "shown", "PARAMETERS",
           "SPRING_CONSTANT", "RESONANCE_FREQUENCY", "QUALITY_FACTOR", "UNDERDAMPED_QUALITY_FACTOR"]


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

    Raises
    ------
    TypeError
        If ``mapping`` is not a mapping.
    """
    if not isinstance(mapping, Mapping):
        raise TypeError(f"mapping must be a mapping (a dict), got {type(mapping).__name__}")
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
    "turn": ("rad", 2 * math.pi),
    # force, stiffness, pressure, energy per area
    "N": ("N", 1.0), "uN": ("N", 1e-6), "nN": ("N", 1e-9), "pN": ("N", 1e-12),
    "N/m": ("N/m", 1.0), "N m": ("N m", 1.0), "nN m": ("N m", 1e-9),
    "Pa": ("Pa", 1.0), "kPa": ("Pa", 1e3), "MPa": ("Pa", 1e6), "GPa": ("Pa", 1e9),
    "J/m^2": ("J/m^2", 1.0), "mJ/m^2": ("J/m^2", 1e-3),
    "J": ("J", 1.0), "aJ": ("J", 1e-18), "zJ": ("J", 1e-21),
    "1/Pa": ("1/Pa", 1.0), "1e-11/Pa": ("1/Pa", 1e-11),
    "mN": ("N", 1e-3), "1/N": ("1/N", 1.0),
    # mass, density, damping
    "kg": ("kg", 1.0), "ng": ("kg", 1e-12), "kg/m^3": ("kg/m^3", 1.0),
    "kg/s": ("kg/s", 1.0), "ng/us": ("kg/s", 1e-12 / 1e-6), "Pa s": ("Pa s", 1.0),
    # time, frequency, speed
    "s": ("s", 1.0), "ms": ("s", 1e-3), "us": ("s", 1e-6),
    "1/s": ("1/s", 1.0), "1/us": ("1/s", 1e6), "1/s^2": ("1/s^2", 1.0),
    "Hz": ("Hz", 1.0), "kHz": ("Hz", 1e3), "MHz": ("Hz", 1e6), "GHz": ("Hz", 1e9),
    "m/s": ("m/s", 1.0), "mm/s": ("m/s", 1e-3), "um/s": ("m/s", 1e-6), "nm/s": ("m/s", 1e-9),
    "Hz/m": ("Hz/m", 1.0), "GHz/nm": ("Hz/m", 1e9 / 1e-9),
    "m^2/Hz": ("m^2/Hz", 1.0), "pm^2/Hz": ("m^2/Hz", 1e-24),  # deflection spectra
    # electrical, magnetic, optical
    "V": ("V", 1.0), "mV": ("V", 1e-3), "uV": ("V", 1e-6),
    "V^2/Hz": ("V^2/Hz", 1.0), "nV^2/Hz": ("V^2/Hz", 1e-18),
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
        ``1 / (SI value of one display unit)``, exactly 1e9 for ``"nm"`` (``1 / 1e-9`` in
        floating point is 999999999.9999999).

    Raises
    ------
    ValueError
        If the display unit is unknown or measures another quantity than ``unit``.
    """
    if not isinstance(display_unit, str):
        raise TypeError(f"display_unit must be a str, got {display_unit!r}")
    if unit is not None and not isinstance(unit, str):
        raise TypeError(f"unit must be a str, got {unit!r}")
    if display_unit not in UNITS:
        raise ValueError(f"display_unit must be one of {sorted(UNITS)}, got {display_unit!r}")
    si, factor = UNITS[display_unit]
    if unit is not None and si != unit:
        raise ValueError(f"display_unit {display_unit!r} measures {si or 'a pure number'!r}, "
                         f"not {unit or 'a pure number'!r}")
    inverse = _exact_inverse(factor)
    return 1.0 / factor if inverse is None else inverse


def _exact_inverse(factor: float) -> float | None:
    """``1 / factor`` when it is an integer that a float holds exactly (1e6 for "um"), else None.

    Dividing by such an integer is correctly rounded, so ``20 um`` becomes exactly the float
    ``2e-05``; multiplying by the factor ``1e-6`` (itself not exact in binary) gave
    ``1.9999999999999998e-05``, which a model bounded at 20 um rejected at the slider's end.
    """
    if factor >= 1.0:
        return None
    inverse = round(1.0 / factor)
    if inverse < 2 ** 53 and abs(1.0 / factor - inverse) <= 1e-9 * inverse:
        return float(inverse)
    return None


def _convert(value, factor: float, to_si: bool, name: str = "value"):
    """``value`` times ``factor`` (to SI) or divided by it (to display), correctly rounded."""
    inverse = _exact_inverse(factor)
    if np.ndim(value):
        value = np.asarray(value)
        if value.dtype.kind not in "iuf":
            raise TypeError(f"{name} must be real numbers, got an array of {value.dtype}")
    else:
        if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer,
                                                                         np.floating)):
            raise TypeError(f"{name} must be a real number, got {value!r}")
        value = check_real(name, value)  # 10**400: a ValueError naming it, not OverflowError
    if inverse is None:
        out = value * factor if to_si else value / factor
    elif not np.ndim(value) and math.isfinite(value):
        # the decimal the value reads as, shifted by the power of ten, then rounded once:
        # 0.1 um is the float nearest 1e-7 m (0.1 / 1e6 gives 1.0000000000000001e-07, above a
        # bound of 1e-7 m that the slider's end stands for)
        d = Decimal(repr(value))
        out = float(d / Decimal(int(inverse)) if to_si else d * Decimal(int(inverse)))
    else:
        out = value / inverse if to_si else value * inverse
    if not to_si and not np.ndim(out) and math.isfinite(out):
        # A product is off the decimal by an ulp (1.5e-08 * 1e9 = 14.999999999999998): show
        # the shortest nearby decimal when it converts back to the same SI value, so a default
        # reads 15 nm on its slider and the model gets exactly the default back.
        short = float(f"{out:.15g}")
        if short != out and _convert(short, factor, to_si=True) == value:
            return short
    with np.errstate(invalid="ignore"):
        overflow = np.isinf(out) & np.isfinite(value)
    if np.any(overflow):
        raise ValueError(f"{name} must be within the float range in "
                         f"{'SI units' if to_si else 'display units'}: "
                         f"{np.asarray(value)[overflow].flat[0] if np.ndim(value) else value!r} "
                         f"overflows")
    return out


def shown(si_value, display_unit: str, spec: str = ".4g") -> str:
    """``si_value`` written in ``display_unit`` with its unit, for readouts and messages.

    The factor comes from :data:`UNITS`, as every slider's does, so a readout never types one.

    Parameters
    ----------
    si_value : float
        The value in SI units.
    display_unit : str
        A key of :data:`UNITS`.
    spec : str
        Format specification of the number.

    Returns
    -------
    str
        e.g. ``"1.739 nN"``.

    Examples
    --------
    >>> shown(-1.739e-9, "nN")
    '-1.739 nN'
    """
    if isinstance(si_value, (bool, np.bool_)) or not isinstance(si_value, (int, float, np.integer,
                                                                          np.floating)):
        raise TypeError(f"si_value must be a real number, got {si_value!r}")
    value = check_real("si_value", si_value)
    if not math.isfinite(value):
        raise ValueError(f"si_value must be a finite number, got {si_value!r}")
    value *= unit_scale(display_unit)
    if not isinstance(spec, str):
        raise TypeError(f"spec must be a format specification (a str such as '.4g'), got "
                        f"{spec!r:.60}")
    try:
        text = f"{value:{spec}}"
    except ValueError as exc:
        raise ValueError(f"spec must be a format specification of a float (such as '.4g'), got "
                         f"{spec!r:.60} ({exc})") from None
    return f"{text} {display_unit}".rstrip()


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
        if not (isinstance(self.name, str) and self.name.isidentifier()):
            raise ValueError(f"Parameter name must be a Python identifier (the model's keyword), "
                             f"got {self.name!r}")
        where = f"parameter {self.name}"
        if not isinstance(self.unit, str):
            raise TypeError(f"{where}: unit must be a str, got {self.unit!r}")
        if self.display_unit is None:
            object.__setattr__(self, "display_unit", self.unit)
        elif not isinstance(self.display_unit, str):
            raise TypeError(f"{where}: display_unit must be a str, got {self.display_unit!r}")
        if self.unit not in {si for si, _ in UNITS.values()}:
            raise ValueError(f"{where}: unit must be an SI unit of UNITS, got {self.unit!r}")
        unit_scale(self.display_unit, self.unit)  # raises on a unit mismatch
        for field in ("low", "high"):
            bound = getattr(self, field)
            if isinstance(bound, bool) or not isinstance(bound, (int, float, np.integer,
                                                                 np.floating)) \
                    or math.isnan(check_real(f"{where}: {field}", bound)):
                raise ValueError(f"{where}: {field} must be a real number (inf for none), "
                                 f"got {bound!r}")
        for field in ("low_inclusive", "high_inclusive", "log"):
            if not isinstance(getattr(self, field), bool):
                raise TypeError(f"{where}: {field} must be True or False, "
                                f"got {getattr(self, field)!r}")
        if not isinstance(self.label, str):
            raise TypeError(f"{where}: label must be a str, got {self.label!r}")
        if not self.low < self.high:
            raise ValueError(f"{where}: low must be below high, got low={self.low}, "
                             f"high={self.high}")
        try:
            object.__setattr__(self, "default", self.check(self.default))
        except ValueError:
            left, right = "[" if self.low_inclusive else "(", "]" if self.high_inclusive else ")"
            raise ValueError(f"{where}: default must be a real number in [low, high] = "
                             f"{left}{self.low:g}, {self.high:g}{right} {self.unit}".rstrip()
                             + f", got {self.default!r}") from None
        lo = self.low if self.slider_low is None else self.slider_low
        hi = self.high if self.slider_high is None else self.slider_high
        for field, bound in (("slider_low", lo), ("slider_high", hi)):
            if isinstance(bound, bool) or not isinstance(bound, (int, float, np.integer,
                                                                 np.floating)) \
                    or math.isnan(check_real(f"{where}: {field}", bound)):
                raise ValueError(f"{where}: {field} must be a real number, got {bound!r}")
        object.__setattr__(self, "slider_low", check_real(f"{where}: slider_low", lo))
        object.__setattr__(self, "slider_high", check_real(f"{where}: slider_high", hi))
        if not self.slider_low < self.slider_high:
            raise ValueError(f"{where}: slider_low must be below slider_high, got "
                             f"slider_low={lo}, slider_high={hi}")
        if not (self.low <= self.slider_low and self.slider_high <= self.high):
            raise ValueError(f"{where}: slider_low and slider_high must lie in the valid range "
                             f"[{self.low}, {self.high}], got [{lo}, {hi}]")
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
            Value(s) in SI units; NaN stays NaN (a gap in a plotted curve), :meth:`check`
            validates.

        Raises
        ------
        TypeError
            If ``si_value`` is not a real number or an array of them.
        """
        return _convert(si_value, UNITS[self.display_unit][1], to_si=False, name="si_value")

    def to_si(self, display_value):
        """``display_value`` (in the display unit) in SI.

        Parameters
        ----------
        display_value : float or array_like
            Value(s) in the display unit; NaN stays NaN.

        Raises
        ------
        TypeError
            If ``display_value`` is not a real number or an array of them.
        """
        return _convert(display_value, UNITS[self.display_unit][1], to_si=True,
                        name="display_value")

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


# -- the quantities every lever shares ---------------------------------------------------------
# One valid range each, whatever the mode: a lever valid in contact, tapping, FM, Q control or the
# Brownian model is valid in all of them. A module changes only the default and the slider
# (``SPRING_CONSTANT.with_(default=40.0, ...)``), never the valid range; a test walks the package
# and holds every description of these names to these ranges.
#: Lever spring constant k: from a soft contact lever's 1 uN/m to a qPlus sensor's kN/m and beyond.
SPRING_CONSTANT = Parameter(name="spring_constant", unit="N/m", display_unit="N/m", default=0.1,
                            low=1e-6, high=1e6, slider_low=0.005, slider_high=100.0, log=True,
                            label="lever spring constant k")
#: Free resonance frequency f0: from a lever felt by hand (~10 Hz, down to 0.1 Hz) to 1 GHz.
RESONANCE_FREQUENCY = Parameter(name="resonance_frequency", unit="Hz", display_unit="kHz",
                                default=300e3, low=0.1, high=1e9, slider_low=10e3,
                                slider_high=2e6, log=True, label="resonance frequency f0")
#: Quality factor Q, any damping up to a lever in vacuum (Q < 1/2 is overdamped: a Q-controlled
#: lever rings down without oscillating); the slider starts at critical damping.
QUALITY_FACTOR = Parameter(name="quality_factor", unit="", default=150.0, low=0.0, high=1e5,
                           low_inclusive=False, slider_low=0.5, slider_high=1e5, log=True,
                           label="quality factor Q")
#: The same quantity for the models that take only an underdamped mode, Q >= 1/2 (the contact
#: loop's lever, whose damping m w / Q it bounds, and the transducers' Q typed in vacuum, from
#: critical damping up: a lower Q is a fluid's, which the transducers compute): the one named
#: narrowing of :data:`QUALITY_FACTOR`, written here and nowhere else.
UNDERDAMPED_QUALITY_FACTOR = QUALITY_FACTOR.with_(low=0.5, low_inclusive=True)
#: The shared lever quantities by name (read-only).
PARAMETERS = read_only({p.name: p for p in (SPRING_CONSTANT, RESONANCE_FREQUENCY,
                                             QUALITY_FACTOR)})
