"""afmsmiler.ui.controls: the one slider factory.

Over many random parameters (hypothesis: units, ranges, open or closed bounds, defaults at the
ends, linear and log) every slider must hold its value exactly on its grid ``min + n * step`` (the
browser snaps to that grid and echoes the result), stay inside the slider range and the valid
range, and offer no position that the model rejects once the panel converts it to SI (an open
bound such as a Poisson ratio < 0.5 is never reached). The positions are computed as the browser
does (``min + n * step``, clamped to ``max``; ``base ** exponent`` for a log slider).
"""
import math

import ipywidgets as widgets
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

from afmsmiler.parameters import UNITS, Parameter
from afmsmiler.ui.controls import STEPS, control, grid, nice_step

DISPLAY = ["um", "nm", "deg", "N/m", "", "GPa", "ng/us", "kHz", "mm/s", "1/us"]


def _positions(w):
    """A sample of the slider's positions (display values) as the browser computes them."""
    n_max = round((w.max - w.min) / w.step)
    ns = sorted({0, 1, 2, n_max // 2, n_max - 2, n_max - 1, n_max} & set(range(n_max + 1)))
    for n in ns:
        x = min(w.min + n * w.step, w.max)
        yield n, (w.base ** x if isinstance(w, widgets.FloatLogSlider) else x)


def _model_accepts(p, display_value):
    p.check(p.to_si(display_value))  # raises ValueError naming the parameter otherwise
    return True


@st.composite
def parameters(draw, log=None):
    display = draw(st.sampled_from(DISPLAY))
    si, _ = UNITS[display]
    log = draw(st.booleans()) if log is None else log
    if log:
        lo_d = 10.0 ** draw(st.floats(-4, 3))
        hi_d = lo_d * 10.0 ** draw(st.floats(0.2, 6))
    else:
        lo_d = draw(st.floats(-1e3, 1e3))
        hi_d = lo_d + 10.0 ** draw(st.floats(-3, 4))
    t = draw(st.one_of(st.just(0.0), st.just(1.0), st.floats(0, 1)))
    default_d = lo_d + t * (hi_d - lo_d) if not log else lo_d * (hi_d / lo_d) ** t
    default_d = float(f"{default_d:.{draw(st.integers(2, 17))}g}")  # a typed default, or not
    low_inc, high_inc = draw(st.booleans()), draw(st.booleans())
    q = Parameter(name="q", unit=si, display_unit=display, default=0.0)
    try:
        return Parameter(name="q", unit=si, display_unit=display, default=q.to_si(default_d),
                         low=q.to_si(lo_d), high=q.to_si(hi_d), low_inclusive=low_inc,
                         high_inclusive=high_inc, log=log)
    except ValueError:  # the default fell on an open bound or outside: not a valid description
        assume(False)


def _check_slider(p, w, value):
    shown = p.to_display(value)
    assert w.value == shown  # the default itself, not a neighbour on the grid
    assert w.parameter is p and w.description == p.title
    log = isinstance(w, widgets.FloatLogSlider)
    coord = math.log10(shown) if log else shown
    n = (coord - w.min) / w.step
    assert abs(n - round(n)) <= 1e-6, f"value {shown} is not on the grid ({n} steps from min)"
    assert w.min <= coord + 1e-12 * max(1.0, abs(coord)) and coord <= w.max + 1e-12 * max(
        1.0, abs(coord))
    ends = [w.base ** w.min, w.base ** w.max] if log else [w.min, w.max]
    lo, hi = p.to_display(p.slider_low), p.to_display(p.slider_high)
    tol = 1e-9 * max(abs(lo), abs(hi))
    assert lo - tol <= ends[0] and ends[1] <= hi + tol
    for _, x in _positions(w):
        # A log slider's end may sit an ulp of exponent beyond the value so that ipywidgets does
        # not clamp it (10 ** log10(x) != x); that position is the value itself to round-off,
        # which the panel takes as the browser's echo.
        if abs(x - shown) > 1e-12 * abs(shown):
            assert _model_accepts(p, x)


@given(parameters(log=False))
def test_linear_slider_holds_its_default_on_a_grid_inside_the_valid_range(p):
    w = control(p)
    assert isinstance(w, widgets.FloatSlider)
    _check_slider(p, w, p.default)
    assert round((w.max - w.min) / w.step) >= STEPS - 4 or w.step < nice_step(
        p.to_display(p.slider_high) - p.to_display(p.slider_low))


@given(parameters(log=True))
def test_log_slider_holds_its_default_on_a_grid_inside_the_valid_range(p):
    w = control(p)
    assert isinstance(w, widgets.FloatLogSlider)
    _check_slider(p, w, p.default)


@given(parameters(), st.floats(0, 1))
def test_any_valid_value_is_on_the_grid_too(p, t):
    value = p.slider_low + t * (p.slider_high - p.slider_low)
    try:
        value = p.check(value)
    except ValueError:
        assume(False)
    _check_slider(p, control(p, value), value)


POISSON = Parameter(name="poisson_ratio", unit="", default=0.3, low=0.0, high=0.5,
                    high_inclusive=False)
LEVER = Parameter(name="length", unit="m", display_unit="um", default=225e-6, low=20e-6,
                  high=1e-3)


def test_an_open_bound_is_never_a_slider_position():
    w = control(POISSON)
    assert w.max < 0.5  # it was 0.5, which the model rejects
    assert all(_model_accepts(POISSON, x) for _, x in _positions(w))
    angle = Parameter(name="half_angle", unit="rad", display_unit="deg", default=math.radians(20),
                      low=0.0, high=math.pi / 2, low_inclusive=False, high_inclusive=False)
    w = control(angle)
    assert 0 < w.min and w.max < 90 and w.value == 20.0


def test_the_lever_slider_reaches_its_bounds_exactly():
    w = control(LEVER)
    assert (w.min, w.max, w.value) == (20.0, 1000.0, 225.0)
    assert LEVER.check(LEVER.to_si(w.min)) == 20e-6


def test_a_tighter_high_and_a_value():
    w = control(LEVER, 100e-6, high=500e-6)
    assert w.value == 100.0 and w.max <= 500.0


@pytest.mark.parametrize("call, error, message", [
    (lambda: nice_step(0.0), ValueError, r"^span must be > 0"),
    (lambda: nice_step(math.nan), ValueError, r"^span must be > 0"),
    (lambda: nice_step(math.inf), ValueError, r"^span must be > 0"),
    (lambda: nice_step("1"), ValueError, r"^span must be a real number"),
    (lambda: nice_step(1.0, 0), ValueError, r"^steps must be an integer in \[1, 100000\]"),
    (lambda: nice_step(1.0, 2.5), ValueError, r"^steps must be an integer"),
    (lambda: nice_step(1.0, 10**9), ValueError, r"^steps must be an integer in"),
    (lambda: grid(1.0, 0.0, 2.0, 0.0), ValueError, r"^step must be > 0"),
    (lambda: grid(1.0, 0.0, 2.0, -0.1), ValueError, r"^step must be > 0"),
    (lambda: grid(1.0, 0.0, 2.0, math.nan), ValueError, r"^step must be > 0"),
    (lambda: grid(math.nan, 0.0, 2.0, 0.1), ValueError, r"^value must be in \[0, 2\], got nan"),
    (lambda: grid(5.0, 0.0, 2.0, 0.1), ValueError, r"^value must be in \[0, 2\], got 5"),
    (lambda: grid(1.0, -math.inf, 2.0, 0.1), ValueError, r"^low must be a finite number"),
    (lambda: grid(1.0, 2.0, 0.0, 0.1), ValueError, r"^low must be <= high"),
    (lambda: grid(1.0, 0.0, 1e10, 1e-10), ValueError, r"^step must divide .* at most 100000"),
    (lambda: grid("1", 0.0, 2.0, 0.1), ValueError, r"^value must be a real number"),
    (lambda: control("length"), TypeError, r"^p must be a Parameter, got str"),
    (lambda: control(LEVER, math.nan), ValueError, r"^length must be in .* got nan"),
    (lambda: control(LEVER, 2e-3), ValueError, r"^length must be in \[2e-05, 0.001\] m, got 0.002"),
    (lambda: control(LEVER, high=math.nan), ValueError, r"^high must be a finite number"),
    (lambda: control(LEVER, high=10e-6), ValueError, r"^high must be above length's slider min"),
    (lambda: control(LEVER, readout_format=3), TypeError, r"^readout_format must be a str"),
    (lambda: control(Parameter(name="offset", unit="m", default=0.0)), ValueError,
     r"^parameter offset needs a finite slider range"),
])
def test_bad_inputs_are_named(call, error, message):
    with pytest.raises(error, match=message):
        call()


def test_grid_ends_never_overshoot_the_range():
    # the round-off tolerance that keeps an end on the grid put it 1e-12 beyond low before
    lo, hi, step = grid(0.3, 0.1, 0.7, 0.1)
    assert 0.1 <= lo and hi <= 0.7
