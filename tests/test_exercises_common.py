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


@pytest.mark.parametrize("factor, words", [
    (-1.0, "sign is wrong"), (1e3, "10^3 times"), (1e-6, "10^-6 times"), (1e9, "10^9 times"),
    (-1e-3, "sign is wrong too"), (180 / math.pi, "degrees where radians"),
    (math.pi / 180, "radians where degrees"), (2 * math.pi, "2 pi"), (100.0, "10^2")])
def test_common_slips_are_named_without_the_answer(factor, words):
    expected = 0.123456
    fb = check_close("x", factor * expected * (1 + 0.002), expected, rtol=0.01, unit="m")
    assert not fb and words in str(fb)
    assert "0.1235" not in str(fb) and "0.123" not in str(fb).replace(f"{factor * expected * 1.002:.4g}", "")


def test_a_far_off_answer_is_a_factor_not_a_huge_percentage():
    fb = check_close("k", 1.004e20, 1.0, rtol=0.01, unit="N/m")  # not a slip of 10^3n
    assert not fb and "factor of about" in str(fb) and "e+21" not in str(fb)
