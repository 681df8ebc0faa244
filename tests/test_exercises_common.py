import math

import pytest

from afmsmiler.exercises import Feedback, check_close


def test_check_close():
    assert check_close("k", 0.1005, 0.1, rtol=0.01, unit="N/m")
    fb = check_close("k", 0.15, 0.1, rtol=0.01, unit="N/m", hint="Thinner lever.")
    assert not fb and "50.0%" in str(fb) and "Thinner" in str(fb)
    fb = check_close("k", 0.7, 0.1, rtol=0.01, unit="N/m")
    assert not fb and "factor of about 7" in str(fb) and "%" in str(fb)
    assert not check_close("k", math.nan, 0.1, rtol=0.01)
    assert not check_close("k", "abc", 0.1, rtol=0.01)
    assert str(Feedback(True, "ok")).startswith("Correct")


@pytest.mark.parametrize("factor, words, unit", [
    (-1.0, "sign is wrong", "m"), (1e3, "10^3 times", "m"), (1e-6, "10^-6 times", "m"),
    (1e9, "10^9 times", "m"), (-1e-3, "sign is wrong too", "m"),
    (180 / math.pi, "degrees where radians", "rad"), (math.pi / 180, "radians where degrees", "deg"),
    (2 * math.pi, "2 pi", "Hz"), (1 / (2 * math.pi), "1/(2 pi)", "rad/s"), (2 * math.pi, "2 pi", ""),
    (100.0, "10^2", "m")])
def test_common_slips_are_named_without_the_answer(factor, words, unit):
    expected = 0.123456
    fb = check_close("x", factor * expected * (1 + 0.002), expected, rtol=0.01, unit=unit)
    assert not fb and words in str(fb)
    assert "0.1235" not in str(fb) and "0.123" not in str(fb).replace(f"{factor * expected * 1.002:.4g}", "")


def test_a_far_off_answer_is_a_factor_not_a_huge_percentage():
    fb = check_close("k", 1.004e20, 1.0, rtol=0.01, unit="N/m")  # not a slip of 10^3n
    assert not fb and "factor of about" in str(fb) and "e+21" not in str(fb)


@pytest.mark.parametrize("unit", ["N/m", "W", "V", "Pa", "N", "m/s", "J", "m"])
def test_an_angle_or_2_pi_slip_is_named_only_where_the_unit_can_make_it(unit):
    # a spring constant 57.3 times the right one is not "in degrees"; a force 2 pi times the
    # right one is not "rad/s where Hz is asked": the checker says how far off it is instead
    for factor in (180 / math.pi, math.pi / 180, 2 * math.pi, 1 / (2 * math.pi)):
        fb = check_close("x", factor * 0.123456, 0.123456, rtol=0.01, unit=unit)
        assert not fb and "degrees" not in str(fb) and "radians" not in str(fb) \
            and "2 pi" not in str(fb), str(fb)
