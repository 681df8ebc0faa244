"""Shared test configuration: hypothesis profiles for the property and bad-input tests, and the
browser tests' Chromium and notebook copies.

``make unit`` and ``make test`` use the ``default`` profile: few examples, no deadline (a shared
CI machine must not turn a slow example into a failure; the bad-input campaign bounds each call
with its own 10 s alarm instead). ``HYPOTHESIS_PROFILE=deep`` runs many more examples when you
change validation or the slider factory.
"""
import os
import shutil

import pytest
from hypothesis import HealthCheck, settings

settings.register_profile("default", max_examples=60, deadline=None, derandomize=True,
                          suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("deep", max_examples=1000, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow])
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "default"))


# -- the browser tests' shared pieces (tests/browser.py drives them) ----------------------------
@pytest.fixture(scope="module")
def chromium():
    """Debian's headless Chromium through Playwright, or a skip that says why it cannot run."""
    import browser as B
    reason = B.unavailable()
    if reason:
        pytest.skip(reason)
    with B.browser() as b:
        yield b


@pytest.fixture(scope="module")
def root():
    """A temporary root with copies of the course notebooks (and the floor notebook)."""
    import browser as B
    path = B.notebook_root()
    yield path
    shutil.rmtree(path, ignore_errors=True)
