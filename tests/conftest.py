"""Shared test configuration: hypothesis profiles for the property and bad-input tests, the
``hang_guard`` fixture (the suite's only wall-clock bound), and the browser tests' Chromium and
notebook copies.

``make unit`` and ``make test`` use the ``default`` profile: few examples, no deadline (a shared
CI machine must not turn a slow example into a failure; the bad-input campaign bounds each call
with its own 10 s alarm instead). ``HYPOTHESIS_PROFILE=deep`` runs many more examples when you
change validation or the slider factory.
"""
import atexit
import gc
import os
import shutil
import time
from contextlib import contextmanager

import pytest
from hypothesis import HealthCheck, settings

settings.register_profile("default", max_examples=60, deadline=None, derandomize=True,
                          suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("deep", max_examples=1000, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow])
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "default"))


# -- hang guards: the only wall-clock bounds in the suite -------------------------------------------
class HangGuard:
    """Fail a block that runs far past its expected time: a hang, not a slow machine.

    Tests check correctness, never speed (``make bench`` measures speed). A test that must show
    that a call *returns* (a timeout fires, retries end, a server stops) bounds it with
    ``with hang_guard(limit, expected=...):`` or ``hang_guard.check(elapsed, limit, expected=...)``.
    The limit must be at least :data:`FACTOR` times the expected time and never under
    :data:`FLOOR` seconds, so a loaded CI machine (two cores shared with others) does not fail it.
    A test that asks for this fixture is marked ``hang_guard`` (``-m "not hang_guard"`` skips them).
    """

    FACTOR = 10
    FLOOR = 5.0

    def _checked(self, limit: float, expected: float) -> float:
        if limit < max(self.FACTOR * expected, self.FLOOR):
            raise ValueError(f"a hang guard's limit must be >= {self.FACTOR} x the expected "
                             f"{expected} s and >= {self.FLOOR} s, got {limit} s")
        return limit

    def check(self, elapsed: float, limit: float, *, expected: float) -> None:
        """Assert that ``elapsed`` seconds stayed under ``limit`` (a hang otherwise)."""
        self._checked(limit, expected)
        assert elapsed < limit, (f"took {elapsed:.2f} s, past the {limit} s hang guard "
                                 f"(expected about {expected} s): it hangs")

    @contextmanager
    def __call__(self, limit: float, *, expected: float):
        self._checked(limit, expected)
        t0 = time.monotonic()
        yield
        self.check(time.monotonic() - t0, limit, expected=expected)


@pytest.fixture
def hang_guard():
    """The suite's one wall-clock bound: see :class:`HangGuard`."""
    return HangGuard()


#: The browser tests' two xdist groups, by module. ``make test`` runs three workers: each group on
#: a worker of its own (a group's modules share their servers and Chromium, and its tests run
#: one after the other, so two pages never compete for the cores), and every other test on the
#: third worker and then on whichever is free. The browser tests wait for pages most of their
#: time, which the third worker's models fill. The two groups take about the same time (5 to
#: 6 minutes each in CI on this machine). A browser test in a module not listed here is refused at
#: collection, so a new one cannot run outside them.
BROWSER_GROUPS = {
    "browser_panels": ("test_panels_browser.py", "test_book_browser.py"),
    "browser_notebooks": ("test_notebooks_browser.py", "test_apps_browser.py",
                          "test_hub_browser.py", "test_plots_live_browser.py",
                          "test_scenes_instrument.py", "test_scenes_viewer.py"),
}
_BROWSER_GROUP = {module: group for group, modules in BROWSER_GROUPS.items()
                  for module in modules}


@pytest.hookimpl(tryfirst=True)  # before xdist's worker reads the groups into the node ids
def pytest_collection_modifyitems(items):
    outside = set()
    for item in items:
        if item.get_closest_marker("browser") is None:
            continue
        module = item.nodeid.split("::", 1)[0].rsplit("/", 1)[-1]
        if module not in _BROWSER_GROUP:
            outside.add(module)
        elif item.get_closest_marker("xdist_group") is None:
            item.add_marker(pytest.mark.xdist_group(_BROWSER_GROUP[module]))
    if outside:
        raise pytest.UsageError(f"browser tests in {sorted(outside)}: add their modules to "
                                "tests/conftest.py:BROWSER_GROUPS")
    for item in items:  # nbval: a notebook's cells run in order in one kernel, on one worker
        path = item.nodeid.split("::", 1)[0]
        if path.endswith(".ipynb") and item.get_closest_marker("xdist_group") is None:
            item.add_marker(pytest.mark.xdist_group("notebook " + path.rsplit("/", 1)[-1]))
            item.add_marker(pytest.mark.slow)  # ordered with the slow modules (below)
    for item in items:
        if "hang_guard" in getattr(item, "fixturenames", ()):
            item.add_marker(pytest.mark.hang_guard)
    # The longest first, so that the two workers end together: the browser test modules (a
    # minute and more per notebook), then the other modules with `slow` tests, then the rest.
    # A module moves as a whole (its module-scoped fixtures, servers among them, are made once);
    # the order inside a module is kept.
    rank: dict = {}
    for item in items:
        module = item.nodeid.split("::", 1)[0]
        r = 0 if item.get_closest_marker("browser") else \
            1 if item.get_closest_marker("slow") else 2
        rank[module] = min(rank.get(module, 2), r)
    items.sort(key=lambda item: rank[item.nodeid.split("::", 1)[0]])


def pytest_unconfigure(config):
    # The process is about to end: its last garbage collection would walk the million objects
    # the tests left (figures, widgets, arrays) for seconds before the interpreter exits, and
    # each xdist worker's exit is waited for. Freezing them skips that walk; the operating
    # system takes the memory back. (atexit runs this first: registered last.)
    atexit.register(gc.freeze)


# -- per-test CPU cost: AFMSMILER_CPU_REPORT=FILE appends "cpu_s wall_s start worker nodeid" lines
# On a shared machine wall times (--durations) say more about the neighbours than the test; the
# process's CPU time (setup, call and teardown, this process only) says what a test costs.
_CPU_REPORT = os.environ.get("AFMSMILER_CPU_REPORT")
if _CPU_REPORT:
    @pytest.hookimpl(hookwrapper=True)
    def pytest_runtest_protocol(item, nextitem):
        cpu, wall, start = time.process_time(), time.perf_counter(), time.time()
        yield
        worker = os.environ.get("PYTEST_XDIST_WORKER", "-")
        with open(_CPU_REPORT, "a") as f:
            f.write(f"{time.process_time() - cpu:.4f} {time.perf_counter() - wall:.4f} "
                    f"{start:.3f} {worker} {item.nodeid}\n")


# -- the browser tests' shared pieces (tests/browser.py drives them) ----------------------------
@pytest.fixture(scope="module")
def chromium():
    """Debian's headless Chromium through Playwright, or a skip that says why it cannot run.

    Module-scoped: Playwright's sync API allows one instance per thread at a time, and some
    browser tests start their own (tests/test_plots_live_browser.py, the scenes' tests)."""
    from tests import browser as B
    reason = B.unavailable()
    if reason:
        pytest.skip(reason)
    with B.browser() as b:
        yield b


@pytest.fixture(scope="session")
def headless(tmp_path_factory):
    """A directory every xdist worker of this run shares, for :func:`tests.browser.headless_run`
    (each course notebook run once with no browser, whichever worker asks first)."""
    base = tmp_path_factory.getbasetemp()
    shared = (base.parent if os.environ.get("PYTEST_XDIST_WORKER") else base) / "headless"
    shared.mkdir(exist_ok=True)
    return shared


@pytest.fixture(scope="module")
def root():
    """A temporary root with copies of the course notebooks (and the floor notebook)."""
    from tests import browser as B
    path = B.notebook_root()
    yield path
    shutil.rmtree(path, ignore_errors=True)
