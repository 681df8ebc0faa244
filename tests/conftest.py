"""Shared test configuration: hypothesis profiles for the property and bad-input tests.

``make unit`` and ``make test`` use the ``default`` profile: few examples, no deadline (a shared
CI machine must not turn a slow example into a failure; the bad-input campaign bounds each call
with its own 10 s alarm instead). ``HYPOTHESIS_PROFILE=deep`` runs many more examples when you
change validation or the slider factory.
"""
import os

from hypothesis import HealthCheck, settings

settings.register_profile("default", max_examples=60, deadline=None, derandomize=True,
                          suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("deep", max_examples=1000, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow])
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "default"))
