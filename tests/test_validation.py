import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from afmsmiler.validation import (check_array, check_choice, check_integer, check_nonnegative,
                                  check_positive, check_range, check_real)


def test_messages_name_parameter_value_and_range():
    with pytest.raises(ValueError, match=r"^k_s must be > 0 N/m and finite, got -1$"):
        check_positive("k_s", -1, "N/m")
    with pytest.raises(ValueError, match=r"^b_c must be >= 0 N s/m and finite, got nan$"):
        check_nonnegative("b_c", math.nan, "N s/m")
    with pytest.raises(ValueError, match=r"^nu must be in \[0, 0.5\), got 0.5$"):
        check_range("nu", 0.5, 0, 0.5, high_inclusive=False)
    with pytest.raises(ValueError, match="must be a real number"):
        check_positive("L", "1e-6")
    with pytest.raises(ValueError, match="must be a real number"):
        check_positive("L", True)


def test_arrays():
    np.testing.assert_array_equal(check_array("x", [0, 1, 2], increasing=True), [0.0, 1.0, 2.0])
    with pytest.raises(ValueError, match=r"x must be strictly increasing, but element 2 \(1\) follows 2"):
        check_array("x", [0, 2, 1], increasing=True)
    with pytest.raises(ValueError, match=r"x must be finite, got inf \(at index 1\)"):
        check_array("x", [0, math.inf])
    with pytest.raises(ValueError, match="must have 3 elements"):
        check_array("height", [1, 2], size=3)
    with pytest.raises(ValueError, match="must be a 1-D array"):
        check_array("x", [[1]], ndim=1)


def test_choice_and_integer():
    assert check_choice("tip", "cone", {"cone", "sphere"}) == "cone"
    with pytest.raises(ValueError, match="tip must be one of"):
        check_choice("tip", "blob", {"cone", "sphere"})
    with pytest.raises(ValueError, match=r"mode must be an integer in \[1, 5\], got 6"):
        check_integer("mode", 6, 1, 5)
    with pytest.raises(ValueError, match="must be an integer"):
        check_integer("mode", 1.0)


@pytest.mark.parametrize("bad, kind", [
    ([1 + 2j, 3.0], "complex"), ([True, False], "bool"), (["1.0", "2"], "<U"), ("12", "<U"),
    (np.array([1.0, None], dtype=object), "object")])
def test_arrays_reject_what_is_not_real_numbers(bad, kind):
    # np.asarray(..., dtype=float) dropped the imaginary part and read strings and booleans as numbers
    with pytest.raises(ValueError, match=f"x must be an array of real numbers, got an array of {kind}"):
        check_array("x", bad)
    with pytest.raises(ValueError, match="x must be an array of real numbers"):
        check_array("x", [[1.0, 2.0], [3.0]])  # ragged


def test_objects_are_checked_by_name():
    from afmsmiler.cantilever import Cantilever
    from afmsmiler.validation import check_instance
    with pytest.raises(TypeError, match=r"^lever must be a Cantilever, got str 'silicon'$"):
        check_instance("lever", "silicon", Cantilever)
    lever = Cantilever(450e-6, 50e-6, 2e-6, 169e9, 2330.0)
    assert check_instance("lever", lever, Cantilever) is lever


@pytest.mark.parametrize("bad", [np.complex128(1 + 2j), np.bool_(True), 1j, None, "1", [1.0],
                                 {"a": 1}, object()])
def test_scalars_reject_what_is_not_a_real_number(bad):
    # np.complex128 passed as an np.number and float() dropped its imaginary part
    with pytest.raises(ValueError, match=r"^x must be a real number, got "):
        check_positive("x", bad)


def test_an_integer_beyond_float_range_is_named():
    # float(10**400) raised OverflowError; the message gives the valid range
    with pytest.raises(ValueError, match=r"^x must be in \[0, 1\] m, got an integer of 401 "
                                         r"digits \(beyond the float range\)"):
        check_range("x", 10**400, 0, 1, "m")
    with pytest.raises(ValueError, match=r"^k must be > 0 N/m and finite, got an integer of 401"):
        check_positive("k", -10**400, "N/m")
    with pytest.raises(ValueError, match=r"^d must be >= 0 and finite, got an integer of 4301 "):
        check_nonnegative("d", 10**4300)  # beyond str()'s 4300 digits too
    # NaN and inf are the caller's to judge; a number beyond floats is not a number it can use
    assert math.isinf(check_real("high", math.inf)) and math.isnan(check_real("x", math.nan))
    with pytest.raises(ValueError, match=r"^low must be a real number in float range, got an "
                                         r"integer of 401 digits"):
        check_real("low", 10**400)
    with pytest.raises(ValueError, match=r"^low must be a real number, got 'a'"):
        check_real("low", "a")


def test_parameters_and_optics_name_an_integer_beyond_float_range():
    """Parameter's bounds, its unit conversions, shown() and the optics' interval ends called
    float() or math.isinf() on 10**400 and raised OverflowError."""
    from afmsmiler.instrument.optics import interval_fraction
    from afmsmiler.parameters import Parameter, shown
    p = Parameter(name="length", unit="m", display_unit="um", default=1e-4, low=0.0, high=1e-3)
    for call, name in ((lambda: Parameter(name="length", unit="m", default=1e-4, low=0.0,
                                          high=10**400), "high"),
                       (lambda: Parameter(name="length", unit="m", default=1e-4, low=0.0,
                                          high=1e-3, slider_low=-10**400), "slider_low"),
                       (lambda: p.to_si(10**400), "display_value"),
                       (lambda: p.to_display(10**400), "si_value"),
                       (lambda: shown(10**400, "nm"), "si_value"),
                       (lambda: interval_fraction(0.0, 1e-5, -10**400, 1e-5), "low")):
        with pytest.raises(ValueError, match=f"{name} must be a real number in float range"):
            call()
    with pytest.raises(ValueError, match=r"spec must be a format specification of a float"):
        shown(1e-9, "nm", "9" * 30)  # "Too many decimal digits in format string"
    with pytest.raises(TypeError, match=r"spec must be a format specification \(a str"):
        shown(1e-9, "nm", 4)


def test_choice_of_an_unhashable_value_is_named():
    # `[1] in {"a"}` raised TypeError: unhashable type: 'list'
    with pytest.raises(ValueError, match=r"^tip must be one of \['cone'\], got \[1\]"):
        check_choice("tip", [1], {"cone"})
    # an array asked of a tuple raised "The truth value of an array ... is ambiguous"
    with pytest.raises(ValueError, match=r"^mode must be one of \['a', 'b'\], got array"):
        check_choice("mode", np.ones(3), ("a", "b"))


def test_integer_messages_give_the_range():
    with pytest.raises(ValueError, match=r"^mode must be an integer in \[1, 5\], got 1.0$"):
        check_integer("mode", 1.0, 1, 5)
    with pytest.raises(ValueError,
                       match=r"^mode must be an integer in \[1, 5\], got (np\.)?True_?$"):
        check_integer("mode", np.bool_(True), 1, 5)


def test_sizes_and_shapes_are_bounded():
    from afmsmiler.validation import MAX_SIZE, check_shape, check_size
    assert check_size("n_length", 200, 10_000) == 200
    for bad in (0, -1, 10**9, 2.0, True, None, "10"):
        with pytest.raises(ValueError, match=r"^n_length must be an integer in \[1, 10000\] "
                                             r"\(a size this machine runs in seconds\), got "):
            check_size("n_length", bad, 10_000)
    assert check_shape("shape", (64, 32)) == (64, 32)
    assert check_shape("n", 5, ndim=1) == (5,)
    with pytest.raises(ValueError, match=r"^shape must have at most 10000000 elements in all"):
        check_shape("shape", (10**4, 10**4))
    assert MAX_SIZE == 10_000_000
    with pytest.raises(ValueError, match=r"^shape\[1\] must be an integer in"):
        check_shape("shape", (64, 0))
    for bad in ((64,), (1, 2, 3), 64, "64x64", None, (64.0, 64)):
        with pytest.raises(ValueError, match=r"^shape"):
            check_shape("shape", bad)


def test_array_size_is_bounded_before_copying():
    with pytest.raises(ValueError, match=r"^x must have at most 10 elements, got 11$"):
        check_array("x", np.zeros(11), max_size=10)
    with pytest.raises(ValueError, match=r"^x must have at most 10 elements, got 11$"):
        check_array("x", [0.0] * 11, max_size=10)
    assert check_array("x", np.zeros(11), max_size=None).size == 11


@given(st.one_of(st.floats(), st.integers(-10**400, 10**400), st.complex_numbers(),
                 st.text(max_size=5), st.none(), st.booleans(), st.lists(st.floats(), max_size=3)))
def test_scalar_checks_raise_only_named_value_errors(value):
    for check in (lambda v: check_positive("k_s", v, "N/m"),
                  lambda v: check_nonnegative("k_s", v, "N/m"),
                  lambda v: check_range("k_s", v, 0, 1, "N/m", high_inclusive=False),
                  lambda v: check_integer("k_s", v, 0, 10)):
        try:
            out = check(value)
        except ValueError as exc:
            assert str(exc).startswith("k_s must be"), str(exc)
        else:
            assert math.isfinite(out)


@given(st.one_of(st.lists(st.one_of(st.floats(), st.integers(-10**30, 10**30)), max_size=6),
                 st.lists(st.lists(st.floats(), max_size=3), max_size=3),
                 st.lists(st.complex_numbers(), min_size=1, max_size=3),
                 st.text(max_size=5), st.none()))
def test_array_check_raises_only_named_value_errors(values):
    try:
        out = check_array("x", values, "m", low=0.0)
    except ValueError as exc:
        assert str(exc).startswith("x must"), str(exc)
    else:
        assert np.isfinite(out).all() and (out >= 0).all()
