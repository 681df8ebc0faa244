"""Sticky axis limits (:mod:`afmsmiler.plots.limits`): the data always lies inside them, they
hold while the data stays inside and fills them, they rescale (with headroom) when it leaves
or shrinks; log axes in decades; non-finite values ignored."""
import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from matplotlib.figure import Figure

from afmsmiler.plots.limits import DEFAULTS, data_range, hold, sticky_limits

#: Values well inside float range (a span of two of them never overflows).
VALUE = st.floats(-1e12, 1e12, allow_nan=False, allow_infinity=False)
POSITIVE = st.floats(1e-12, 1e12, allow_nan=False, allow_infinity=False)
FLOOR = st.sampled_from([0.0, 1e-3, 1.0])


def _inside(limits, low, high):
    lo, hi = limits
    return lo < hi and lo <= min(low, high) and max(low, high) <= hi


@settings(max_examples=300, deadline=None)
@given(VALUE, VALUE, st.one_of(st.none(), st.tuples(VALUE, VALUE)), FLOOR)
def test_the_data_always_lies_inside(low, high, current, floor):
    assert _inside(sticky_limits(current, low, high, floor=floor), low, high)


@settings(max_examples=300, deadline=None)
@given(POSITIVE, POSITIVE, st.one_of(st.none(), st.tuples(POSITIVE, POSITIVE)),
       st.sampled_from([0.0, 0.1, 1.0]))
def test_the_data_always_lies_inside_on_a_log_axis(low, high, current, floor):
    assert _inside(sticky_limits(current, low, high, log=True, floor=floor), low, high)


@settings(max_examples=300, deadline=None)
@given(VALUE, st.floats(1e-6, 1e12), st.floats(DEFAULTS["shrink"], 1.0), st.floats(0.0, 1.0))
def test_unchanged_while_inside_and_not_shrunk(lo, span, fill, where):
    # data filling a fraction fill >= shrink of the limits, anywhere inside them
    hi = lo + span
    assume(lo < hi)
    low = lo + where * (1.0 - fill) * (hi - lo)
    high = min(low + fill * (hi - lo), hi)
    assume(high - low >= DEFAULTS["shrink"] * (hi - lo))
    assert sticky_limits((lo, hi), low, high) == (lo, hi)


@settings(max_examples=200, deadline=None)
@given(VALUE, VALUE, st.floats(-0.05, 0.05))
def test_a_small_move_after_the_first_fit_keeps_the_limits(low, high, move):
    # a 5 % change of the data's top (one slider step of a curve from 0) stays inside the fit
    low, high = sorted((low, high))
    assume(high - low > 1e-6 * max(abs(low), abs(high), 1.0))
    first = sticky_limits(None, low, high)
    assert sticky_limits(first, low, high + move * (high - low)) == first


def test_the_first_fit_is_the_data_with_margins():
    m = DEFAULTS["margin"]
    assert sticky_limits(None, 0.0, 10.0) == pytest.approx((-10 * m, 10 + 10 * m))
    assert sticky_limits(None, 10.0, 0.0) == pytest.approx((-10 * m, 10 + 10 * m))


def test_growth_beyond_rescales_with_headroom_on_that_side():
    m, h = DEFAULTS["margin"], DEFAULTS["headroom"]
    first = sticky_limits(None, 0.0, 10.0)
    new = sticky_limits(first, 0.0, 20.0)
    assert new == pytest.approx((-20 * m, 20 + 20 * (m + h)))
    # the next moves in the same direction hold, up to the headroom
    assert sticky_limits(new, 0.0, 25.0) == new
    assert sticky_limits(new, 0.0, 20 + 20 * (m + h)) == new
    # leaving through the bottom puts the headroom there
    low = sticky_limits(first, -20.0, 5.0)
    assert low == pytest.approx((-20 - 25 * (m + h), 5 + 25 * m))


def test_a_shrunk_curve_rescales_instead_of_going_flat():
    first = sticky_limits(None, 0.0, 100.0)
    span = first[1] - first[0]
    kept = DEFAULTS["shrink"] * span * 1.01
    assert sticky_limits(first, 0.0, kept) == first
    new = sticky_limits(first, 0.0, DEFAULTS["shrink"] * span * 0.99)
    assert new != first and _inside(new, 0.0, DEFAULTS["shrink"] * span * 0.99)
    # the headroom goes to the side it drew away from (the top), a margin below 0
    lo, hi = new
    assert -lo < 0.2 * (hi - lo)
    # and it holds at the next update
    assert sticky_limits(new, 0.0, DEFAULTS["shrink"] * span * 0.99) == new


def test_a_rescale_holds_at_the_next_update():
    for current, low, high in (((0.0, 1.0), 5.0, 6.0), ((0.0, 1.0), 0.4, 0.41),
                               ((-1.0, 1.0), -50.0, 50.0), (None, 3.0, 4.0)):
        new = sticky_limits(current, low, high)
        assert sticky_limits(new, low, high) == new


def test_all_zero_data_gets_the_floor_span():
    lo, hi = sticky_limits(None, 0.0, 0.0, floor=1e-3)
    assert lo < 0 < hi and hi - lo == pytest.approx(1e-3 * (1 + 2 * DEFAULTS["margin"]))
    assert sticky_limits((lo, hi), 0.0, 0.0, floor=1e-3) == (lo, hi)
    # without a floor one value still gets a span around it: 10 % of it, or 1 around 0
    assert sticky_limits(None, 3.0, 3.0) == pytest.approx((2.7, 3.3))
    assert sticky_limits(None, 0.0, 0.0) == (-1.0, 1.0)
    assert sticky_limits(None, 1e-300, 1e-300)[0] < 1e-300 < sticky_limits(None, 1e-300,
                                                                           1e-300)[1]


def test_log_axes_work_in_decades():
    m, h = DEFAULTS["margin"], DEFAULTS["headroom"]
    lo, hi = sticky_limits(None, 1e-3, 1e3, log=True)  # 6 decades, 8 % of them each side
    assert math.log10(lo) == pytest.approx(-3 - 6 * m)
    assert math.log10(hi) == pytest.approx(3 + 6 * m)
    assert sticky_limits((lo, hi), 2e-3, 5e2, log=True) == (lo, hi)  # inside
    grown = sticky_limits((lo, hi), 1e-3, 1e6, log=True)  # 9 decades, headroom on top
    assert math.log10(grown[1]) == pytest.approx(6 + 9 * (m + h))
    assert math.log10(grown[0]) == pytest.approx(-3 - 9 * m)
    # values <= 0 are ignored, a floor in decades
    assert sticky_limits(None, 0.0, 1e2, log=True) == pytest.approx((1e2 / 2, 1e2 * 2))
    lo, hi = sticky_limits(None, 1e2, 1e2, log=True, floor=1.0)
    assert math.log10(hi / lo) == pytest.approx(1 + 2 * m)


def test_non_finite_values_are_ignored_and_no_data_keeps_the_limits():
    assert sticky_limits((0.0, 1.0), math.nan, math.nan) == (0.0, 1.0)
    assert sticky_limits((0.0, 1.0), math.inf, -math.inf) == (0.0, 1.0)
    # one end ignored: the other is the data
    assert sticky_limits((0.0, 1.0), math.nan, 0.5) == sticky_limits((0.0, 1.0), 0.5, 0.5)
    assert sticky_limits((0.0, 1.0), 0.2, math.inf) == sticky_limits((0.0, 1.0), 0.2, 0.2)
    assert sticky_limits(None, math.nan, math.nan) == (0.0, 1.0)
    assert sticky_limits(None, math.nan, math.nan, log=True) == (1.0, 10.0)
    # unusable current limits: a first fit
    for bad in ((1.0, 1.0), (2.0, 1.0), (math.nan, 1.0), (0.0, math.inf)):
        assert sticky_limits(bad, 0.0, 10.0) == sticky_limits(None, 0.0, 10.0)
    assert sticky_limits((0.0, 10.0), 1.0, 5.0, log=True) == sticky_limits(None, 1.0, 5.0,
                                                                           log=True)


def test_data_range_ignores_non_finite_and_non_positive_on_log():
    assert data_range([1.0, np.nan, -3.0], np.array([[np.inf, 7.0]]), 2.0) == (-3.0, 7.0)
    assert data_range([-1.0, 0.0, 4.0, 0.5], log=True) == (0.5, 4.0)
    lo, hi = data_range([np.nan], [])
    assert math.isnan(lo) and math.isnan(hi)


def test_policy_parameters_are_checked():
    with pytest.raises(ValueError, match="^margin must be in"):
        sticky_limits(None, 0, 1, margin=-0.1)
    with pytest.raises(ValueError, match="^headroom must be in"):
        sticky_limits(None, 0, 1, headroom=math.nan)
    with pytest.raises(ValueError, match="^floor must be"):
        sticky_limits(None, 0, 1, floor=-1.0)
    # a shrink threshold above what a rescale leaves would rescale at every update
    with pytest.raises(ValueError, match="^shrink must be in"):
        sticky_limits(None, 0, 1, shrink=0.9)
    with pytest.raises(ValueError, match="^axis must be one of"):
        hold(Figure().add_subplot(), "z", 0.0, 1.0)


def test_hold_sets_matplotlib_limits_only_when_they_change():
    ax = Figure().add_subplot()
    first = hold(ax, "y", 0.0, 10.0, reset=True)
    assert ax.get_ylim() == pytest.approx(first)
    calls = []
    ax.callbacks.connect("ylim_changed", lambda a: calls.append(a.get_ylim()))
    assert hold(ax, "y", 0.0, 9.5) == first and not calls
    new = hold(ax, "y", 0.0, 30.0)
    assert ax.get_ylim() == pytest.approx(new) and len(calls) == 1
    # a log axis is recognised from its scale
    ax.set_xscale("log")
    lo, hi = hold(ax, "x", 1.0, 1e4, reset=True)
    assert math.log10(lo) == pytest.approx(-4 * DEFAULTS["margin"])
