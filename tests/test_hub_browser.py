"""A class on a local JupyterHub: two students log in, pull the course, Run All, move a slider.

The hub of ``tests/hub.py``: JupyterHub (PyPI) with configurable-http-proxy (npm registry,
``make hub-proxy``) on 127.0.0.1, the dummy authenticator restricted to the system users
``course-student-1`` and ``-2`` (created here with ``useradd``, homes mode 0700), the
local-process spawner starting each one's JupyterLab as that user. Both students, in one headless
Chromium with a context each, log in at once through an nbgitpuller link that clones the course
into their home and opens module (d); they Run All, and press the contact panel's slider
together: every press changes their own figure's pixels, no cell shows an error, both kernels
still answer, no page asks for anything beyond 127.0.0.1, and the first student's kernel cannot
read the second's notebook; the hub, its proxy and every student's server and kernel listen on
127.0.0.1 only. Skipped, saying why, when not root or when JupyterHub, the proxy or
Chromium is missing. ``make bench`` (``benchmarks/bench_hub.py``) measures 1, 4 and 8 students.
Marked ``browser`` and ``slow``, in the xdist group that conftest.BROWSER_GROUPS gives it.
"""
import pytest

from tests import hub as H

pytestmark = [pytest.mark.slow, pytest.mark.browser]  # its xdist group: conftest.BROWSER_GROUPS

N_STUDENTS = 2


@pytest.fixture(scope="module")
def hub():
    reason = H.unavailable()
    if reason:
        pytest.skip(reason)
    names = H.students(N_STUDENTS)
    with H.Hub(names, short=True) as running:
        yield running


def test_two_students_pull_the_course_run_it_and_move_a_slider(chromium, hub):
    for name in hub.names:
        assert H.home_mode(name) == 0o700, f"{name}'s home can be read by others"
    students = H.class_session(chromium, hub, presses=2, timeout=600)
    assert [s.name for s in students] == hub.names
    for s in students:
        assert s.errors == [], f"{s.name}: {s.errors}"
        assert s.first_figure_s is not None and s.first_figure_s > 0, s
        assert None not in s.presses, f"{s.name}: a press changed no pixel {s.presses}"
        assert s.kernel_alive, f"{s.name}'s kernel no longer answers"
        assert s.foreign == [], f"{s.name}'s pages asked beyond 127.0.0.1: {s.foreign[:5]}"
        assert s.memory["rss"] > 0, f"no process runs as {s.name}"
    # the hub, its proxy, each student's JupyterLab and kernel: on 127.0.0.1 only
    sockets = hub.listening()
    ports = {port for _, _, port in sockets}
    assert {hub.port, hub.hub_port, hub.api_port} <= ports, sockets  # proxy, hub, proxy's API
    assert len(ports) >= 3 + 2 * N_STUDENTS, sockets  # and each student's server and kernel
    assert [s for s in sockets if s[1] != "127.0.0.1"] == [], sockets
