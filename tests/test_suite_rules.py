"""The suite's own rules, checked on its source: no wall-clock upper bound but through the
``hang_guard`` fixture (tests check correctness, ``make bench`` measures speed), and helpers
imported from the ``tests`` package, never through ``sys.path``; and the xdist groups that
``make test`` relies on hold.
"""
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

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


GROUPED = '''
import os
import pytest

pytestmark = pytest.mark.xdist_group("together")


@pytest.mark.parametrize("i", range(6))
def test_grouped(i):
    with open(os.environ["WORKERS_FILE"], "a") as f:
        f.write(os.environ.get("PYTEST_XDIST_WORKER", "none") + "\\n")


@pytest.mark.parametrize("i", range(6))
def test_free(i):
    pass
'''


@pytest.mark.slow
def test_an_xdist_group_runs_on_one_worker(tmp_path):
    """`make test` relies on --dist loadgroup: the tests of a group share a worker (and the
    servers their module starts). pytest-xdist 3.8 writes the group into a node id field that
    pytest 9.2 no longer reads, and then every test of a group goes out alone, without a word:
    a grouped module's tests, run on two workers, must all report the same one."""
    (tmp_path / "test_grouped.py").write_text(GROUPED)
    workers = tmp_path / "workers.txt"
    env = {**os.environ, "WORKERS_FILE": str(workers)}
    proc = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
                           "-p", "no:nbval", "-n", "2", "--dist", "loadgroup",
                           str(tmp_path / "test_grouped.py")],
                          cwd=tmp_path, env=env, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stdout[-2000:] + proc.stderr[-2000:]
    ran = workers.read_text().split()
    assert len(ran) == 6 and len(set(ran)) == 1, f"the group ran on workers {ran}"


def test_every_browser_test_is_in_one_of_the_two_browser_groups():
    from tests.conftest import BROWSER_GROUPS
    modules = [m for group in BROWSER_GROUPS.values() for m in group]
    assert len(modules) == len(set(modules)), "a module in both browser groups"
    marked = sorted(p.name for p in HERE.glob("test_*.py")
                    if re.search(r"pytest\.mark\.browser\b", p.read_text()))
    assert marked == sorted(modules), "browser modules and tests/conftest.py:BROWSER_GROUPS differ"
