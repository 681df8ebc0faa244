"""afmsmiler.parameters: the unit table, the conversions and the checks of a Parameter.

The unit table is checked against an independent spelling of each unit: its name is parsed into
SI prefixes and base units, the prefixes' values taken from ``scipy.constants`` (CODATA/SI
brochure), so that ``"ng/us"`` must measure ``kg/s`` with the factor nano*gram/micro. Conversions
are checked against Python's own parsing of the decimal literal (``float("20e-6")`` is the float
nearest to 20 um), which is what a student typing ``20e-6`` gets.
"""
import math
import re

import numpy as np
import pytest
import scipy.constants as sc
from hypothesis import given
from hypothesis import strategies as st

from afmsmiler.parameters import UNITS, Parameter, read_only, unit_scale

# -- an independent spelling of the units: SI prefixes and base units -----------------------------
PREFIXES = {"": 1.0, "z": sc.zepto, "a": sc.atto,
            "f": sc.femto, "p": sc.pico, "n": sc.nano, "u": sc.micro, "\u00b5": sc.micro,
            "m": sc.milli, "c": sc.centi, "k": sc.kilo, "M": sc.mega, "G": sc.giga}
#: base unit -> (the SI unit it is measured in, SI value of one base unit)
BASES = {"m": ("m", 1.0), "g": ("kg", sc.gram), "s": ("s", 1.0), "N": ("N", 1.0),
         "Pa": ("Pa", 1.0), "J": ("J", 1.0), "rad": ("rad", 1.0), "deg": ("rad", sc.degree),
         "Hz": ("Hz", 1.0), "V": ("V", 1.0), "A": ("A", 1.0), "W": ("W", 1.0),
         "ohm": ("ohm", 1.0), "T": ("T", 1.0), "K": ("K", 1.0), "C": ("C", 1.0),
         "F": ("F", 1.0), "H": ("H", 1.0), "S": ("S", 1.0), "L": ("m^3", 1e-3),
         "turn": ("rad", 2 * math.pi)}  # one revolution (SI brochure: a full angle is 2 pi rad)


def _factor(term: str) -> tuple[str, float]:
    """``"nm^2"`` -> ("m^2", 1e-18); a number ``"1e-11"`` -> ("", 1e-11)."""
    m = re.fullmatch(r"([^\^]+)(?:\^(-?\d+))?", term)
    body, power = m.group(1), int(m.group(2) or 1)
    try:
        return "", float(body) ** power
    except ValueError:
        pass
    for base in sorted(BASES, key=len, reverse=True):  # the longest base first: "Pa" before "a"
        if body.endswith(base) and body[:-len(base)] in PREFIXES:
            si, value = BASES[base]
            value *= PREFIXES[body[:-len(base)]]
            return (si if power == 1 else f"{si}^{power}"), value ** power
    raise AssertionError(f"cannot spell unit term {term!r}; add its base or prefix to this test")


#: pure numbers with a name: parts per million (1e-6, SI brochure's ppm) and the strain unit
#: microstrain (1e-6 m/m)
RATIOS = {"ppm": 1e-6, "microstrain": sc.micro}


def _spell(unit: str) -> tuple[str, float]:
    """A unit name -> (its SI unit, the SI value of one of it), from prefixes and bases."""
    if unit in ("", "x"):
        return "", 1.0
    if unit in RATIOS:
        return "", RATIOS[unit]
    num, _, den = unit.partition("/")
    si_parts, value = [], 1.0
    for i, side in enumerate((num, den)):
        terms = [t for t in re.split(r"[ *.\u00b7]", side) if t] if side else []
        names = []
        for t in terms:
            si, v = _factor(t)
            value = value * v if i == 0 else value / v
            if si:
                names.append(si)
        si_parts.append(" ".join(names))
    top, bottom = si_parts
    if not bottom:
        return top, value
    return f"{top or '1'}/{bottom}", value


@pytest.mark.parametrize("display", sorted(UNITS))
def test_every_display_unit_measures_its_si_unit(display):
    si, factor = UNITS[display]
    spelled_si, spelled = _spell(display)
    assert spelled_si == si, f"{display!r} measures {spelled_si!r}, the table says {si!r}"
    assert factor == pytest.approx(spelled, rel=1e-12)
    assert _spell(si) == (si, 1.0), f"the SI unit {si!r} of {display!r} is itself prefixed"


@pytest.mark.parametrize("display, value", [
    ("nm", sc.nano), ("um", sc.micro), ("mm", sc.milli), ("pm", sc.pico),
    ("deg", sc.degree), ("nN", sc.nano), ("pN", sc.pico), ("GPa", sc.giga), ("kPa", sc.kilo),
    ("MPa", sc.mega), ("ng", sc.nano * sc.gram), ("ng/us", sc.nano * sc.gram / sc.micro),
    ("kHz", sc.kilo), ("MHz", sc.mega), ("um/s", sc.micro), ("1/cm^3", 1 / sc.centi ** 3),
    ("mJ/m^2", sc.milli), ("GHz/nm", sc.giga / sc.nano), ("mW", sc.milli), ("mT", sc.milli)])
def test_scales_agree_with_scipy_constants(display, value):
    assert UNITS[display][1] == pytest.approx(value, rel=1e-15)
    assert unit_scale(display) == pytest.approx(1 / value, rel=1e-15)


def test_power_of_ten_scales_are_exact():
    # 1 / 1e-9 is 999999999.9999999 in floating point: a "nm" scale was not 1e9
    assert unit_scale("nm") == 1e9
    assert unit_scale("um") == 1e6
    assert unit_scale("pm") == 1e12
    assert unit_scale("ng/us") == 1e6


@given(st.integers(-10**6, 10**6), st.sampled_from(["um", "nm", "pm", "mm", "nN", "kPa", "GPa",
                                                     "kHz", "ms", "us", "mV", "1/cm^3"]))
def test_to_si_is_the_decimal_literal(n, display):
    """``to_si(20)`` in um is the float ``20e-6`` (it was 1.9999999999999998e-05, below a bound)."""
    si, factor = UNITS[display]
    exponent = round(math.log10(factor))
    p = Parameter(name="q", unit=si, display_unit=display, default=0.0)
    assert p.to_si(n) == float(f"{n}e{exponent}")
    assert p.to_display(float(f"{n}e{exponent}")) == n
    np.testing.assert_array_equal(p.to_si([n, n]), [float(f"{n}e{exponent}")] * 2)


def test_a_lever_at_its_lower_bound_round_trips():
    p = Parameter(name="length", unit="m", display_unit="um", default=450e-6, low=20e-6, high=1e-3)
    assert p.check(p.to_si(20.0)) == 20e-6  # the slider's lower end is accepted by the model


LEVER = dict(name="length", unit="m", display_unit="um", default=450e-6, low=20e-6, high=1e-3)


@pytest.mark.parametrize("changes, message", [
    (dict(default=2e-3), r"^parameter length: default must be a real number in \[low, high\] = "
                         r"\[2e-05, 0.001\] m, got 0.002$"),
    (dict(default=math.nan), r"^parameter length: default must be .* got nan$"),
    (dict(default="450e-6"), r"^parameter length: default must be a real number"),
    (dict(default=True), r"^parameter length: default must be a real number .* got True"),
    (dict(slider_low=10e-6), r"^parameter length: slider_low and slider_high must lie in the "),
    (dict(slider_high=2e-3), r"^parameter length: slider_low and slider_high must lie in the "),
    (dict(slider_low=500e-6, slider_high=400e-6),
     r"^parameter length: slider_low must be below slider_high"),
    (dict(low=0.0, log=True), r"^parameter length: a log slider needs slider_low > 0"),
    (dict(slider_low=0.0, low=-1.0, log=True), r"a log slider needs slider_low > 0"),
    (dict(display_unit="nN"), r"display_unit 'nN' measures 'N', not 'm'"),
    (dict(display_unit="furlong"), r"display_unit must be one of"),
    (dict(unit="metre", display_unit="metre"), r"unit must be an SI unit"),
    (dict(unit="N", display_unit="um"), r"unit must be an SI unit|measures 'm', not 'N'"),
    (dict(low=math.nan), r"^parameter length: low must be a real number"),
    (dict(high=math.nan), r"^parameter length: high must be a real number"),
    (dict(low=1e-3, high=20e-6), r"^parameter length: low must be below high"),
    (dict(slider_low=math.nan), r"slider_low must be a real number"),
    (dict(name="lever length"), r"^Parameter name must be a Python identifier"),
    (dict(name=3), r"^Parameter name must be a Python identifier"),
])
def test_parameter_rejects_an_inconsistent_description(changes, message):
    with pytest.raises(ValueError, match=message):
        Parameter(**{**LEVER, **changes})


@pytest.mark.parametrize("changes", [dict(log="yes"), dict(low_inclusive=1), dict(label=None),
                                     dict(unit=None), dict(display_unit=1e-6)])
def test_parameter_rejects_wrong_types(changes):
    with pytest.raises(TypeError, match="parameter length: "):
        Parameter(**{**LEVER, **changes})


def test_parameter_is_keyword_only_frozen_and_checks_open_bounds():
    with pytest.raises(TypeError):
        Parameter("length", "m", "um", 450e-6)  # noqa - positional fields were the old way
    p = Parameter(name="nu", unit="", default=0.3, low=0.0, high=0.5, high_inclusive=False)
    with pytest.raises(ValueError, match=r"^nu must be in \[0, 0.5\), got 0.5$"):
        p.check(0.5)
    with pytest.raises(Exception):
        p.default = 0.4  # frozen
    assert p.with_(default=0.2).default == 0.2 and p.default == 0.3
    with pytest.raises(ValueError, match=r"parameter nu: default must be .* \[0, 0.5\)"):
        p.with_(default=0.5)
    assert p.title == "nu" and LEVER_P.title == "lever length L [um]"


LEVER_P = Parameter(**LEVER, label="lever length L")


def test_read_only_defaults():
    d = read_only({"a": 1})
    assert d["a"] == 1
    with pytest.raises(TypeError):
        d["a"] = 2
    with pytest.raises(TypeError, match=r"^mapping must be a mapping \(a dict\), got list"):
        read_only([("a", 1)])


def test_unit_scale_names_a_wrong_type():
    with pytest.raises(TypeError, match=r"^display_unit must be a str, got \['nm'\]"):
        unit_scale(["nm"])
    with pytest.raises(TypeError, match=r"^unit must be a str"):
        unit_scale("nm", 1)


@given(st.floats(-1e30, 1e30, allow_nan=False, allow_infinity=False),
       st.sampled_from(sorted(UNITS)))
def test_conversions_round_trip_to_an_ulp(x, display):
    si, _ = UNITS[display]
    p = Parameter(name="q", unit=si, display_unit=display, default=0.0)
    back = p.to_si(p.to_display(x))
    assert back == pytest.approx(x, rel=4e-16, abs=1e-300)


@pytest.mark.parametrize("bad", ["20", True, 1j, None, ["a"], np.array([1j])])
def test_conversions_reject_what_is_not_a_number(bad):
    # to_si("20") read the string as a number and to_display(True) gave 1e6
    with pytest.raises(TypeError, match=r"^display_value must be (a )?real number"):
        LEVER_P.to_si(bad)
    with pytest.raises(TypeError, match=r"^si_value must be (a )?real number"):
        LEVER_P.to_display(bad)
