"""The browser tests' own helpers (``tests/browser.py``) that need no browser."""
import math

import pytest

from tests import browser as B


@pytest.mark.parametrize("interval", [-0.01, math.nan, -math.inf])
def test_press_keys_names_a_bad_interval_before_pressing_anything(interval):
    # no page: a press would raise AttributeError, so the check comes first
    with pytest.raises(ValueError, match=r"interval must be a number >= 0 s, got"):
        B.press_keys(None, "ArrowLeft", 3, interval)
