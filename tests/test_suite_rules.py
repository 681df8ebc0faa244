"""The suite's own rules, checked on its source: no wall-clock upper bound but through the
``hang_guard`` fixture (tests check correctness, ``make bench`` measures speed), and helpers
imported from the ``tests`` package, never through ``sys.path``.
"""
import re
from pathlib import Path

HERE = Path(__file__).parent
#: An upper bound on a clock difference: ``assert time.monotonic() - t0 < 1`` or ``elapsed < 1``.
UPPER_BOUND = re.compile(r"assert\b.*(\b(perf_counter|monotonic|time)\(\)\s*-\s*\w+|\belapsed)"
                         r"\s*(<|<=)")


def _sources():
    return sorted(p for p in HERE.glob("*.py") if p.name not in ("conftest.py", Path(__file__).name))


def test_no_wall_clock_bound_but_a_hang_guard():
    found = [f"{p.name}:{i}: {line.strip()}" for p in _sources()
             for i, line in enumerate(p.read_text().splitlines(), 1) if UPPER_BOUND.search(line)]
    assert not found, ("wall-clock bounds outside the hang_guard fixture (tests/conftest.py):\n"
                       + "\n".join(found))
    assert UPPER_BOUND.search("    assert time.monotonic() - t0 < 0.5")  # the pattern works
    assert UPPER_BOUND.search("assert isinstance(error, X) and elapsed < 1.0")


def test_helpers_are_imported_from_the_tests_package():
    found = [f"{p.name}:{i}: {line.strip()}" for p in _sources()
             for i, line in enumerate(p.read_text().splitlines(), 1)
             if re.match(r"\s*sys\.path\.insert\(", line)
             or re.match(r"\s*(from|import) (browser|recording|sympy_reference|api_campaign_\w+"
                         r"|test_\w+)\b", line)]
    assert not found, "\n".join(found)
