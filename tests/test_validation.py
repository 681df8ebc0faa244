import math

import numpy as np
import pytest

from afmsmiler.validation import (check_array, check_choice, check_integer, check_nonnegative,
                                  check_positive, check_range)


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
