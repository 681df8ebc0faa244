import math

from afmsmiler.exercises import Feedback, check_close


def test_check_close():
    assert check_close("k", 0.1005, 0.1, rtol=0.01, unit="N/m")
    fb = check_close("k", 0.2, 0.1, rtol=0.01, unit="N/m", hint="Thinner lever.")
    assert not fb and "100.0%" in str(fb) and "Thinner" in str(fb)
    assert not check_close("k", math.nan, 0.1, rtol=0.01)
    assert not check_close("k", "abc", 0.1, rtol=0.01)
    assert str(Feedback(True, "ok")).startswith("Correct")
