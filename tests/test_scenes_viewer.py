"""The meshcat layer: one server per kernel, loopback only, and none survives its kernel."""
import os
import signal
import subprocess
import sys
import time

import meshcat.geometry as g
import numpy as np
import psutil
import pytest

from afmsmiler.scenes import close_viewer, get_viewer, viewer
from afmsmiler.scenes.camera import set_camera
from afmsmiler.scenes.colors import ColorScale
from afmsmiler.scenes.legends import ColorLegend
from afmsmiler.scenes.meshes import beam_mesh
from afmsmiler.scenes.shapes import Arrow

pytestmark = pytest.mark.viewer  # every test here starts a real meshcat server

CHILD = """
import os, sys
from afmsmiler.scenes import viewer
vis = viewer.get_viewer()
print(viewer._proc.pid, flush=True)
sys.stdin.read()
"""


def _listening_addresses(pid):
    return {c.laddr.ip for c in psutil.Process(pid).net_connections(kind="tcp")
            if c.status == psutil.CONN_LISTEN}


def test_one_server_reused_loopback_only_and_closed():
    vis = viewer.get_viewer()
    pid = viewer._proc.pid
    try:
        assert viewer.get_viewer() is vis  # reused, not a second server
        assert vis.url().startswith("http://127.0.0.1:")
        assert _listening_addresses(pid) == {"127.0.0.1"}
        assert psutil.Process(pid).environ()[viewer.OWNER_ENV] == str(os.getpid())
        html = viewer.static_html()
        assert "<html" in html.lower() and len(html) > 1000
    finally:
        viewer.close_viewer()
    assert not viewer.viewer_running()
    assert not psutil.pid_exists(pid) or psutil.Process(pid).status() == psutil.STATUS_ZOMBIE
    viewer.close_viewer()  # idempotent


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="PR_SET_PDEATHSIG is Linux-only")
def test_server_dies_with_a_hard_killed_kernel():
    kernel = subprocess.Popen([sys.executable, "-c", CHILD], stdin=subprocess.PIPE,
                              stdout=subprocess.PIPE, text=True)
    server_pid = int(kernel.stdout.readline())
    assert psutil.pid_exists(server_pid)
    kernel.send_signal(signal.SIGKILL)  # what nbval does to a kernel
    kernel.wait()
    deadline = time.time() + 10
    while time.time() < deadline:
        if (not psutil.pid_exists(server_pid)
                or psutil.Process(server_pid).status() == psutil.STATUS_ZOMBIE):
            break
        time.sleep(0.05)
    else:
        os.kill(server_pid, signal.SIGKILL)
        pytest.fail("the meshcat server outlived its kernel")


def test_leak_check_detects_an_orphaned_server():
    """The after-notebooks check must be able to fail: an orphan with a dead owner is reported."""
    import importlib.util
    from pathlib import Path
    spec = importlib.util.spec_from_file_location(
        "check_servers", Path(__file__).parent / "after_notebooks" / "check_servers.py")
    check = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(check)
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    env = dict(os.environ, **{viewer.OWNER_ENV: str(dead.pid)})
    orphan = subprocess.Popen([sys.executable, "-m", "afmsmiler.scenes._server"], env=env,
                              stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
    try:
        orphan.stdout.readline()  # zmq_url=...: the server is up
        assert (orphan.pid, str(dead.pid)) in check.orphaned_servers()
    finally:
        orphan.kill()
        orphan.wait()
    assert (orphan.pid, str(dead.pid)) not in check.orphaned_servers()


def test_save_static_html(tmp_path):
    try:
        path = viewer.save_static_html(tmp_path / "scene.html")
        assert open(path, encoding="utf-8").read().lower().count("<html") >= 1
    finally:
        viewer.close_viewer()


def test_scene_pieces_in_a_real_viewer_update_in_place():
    try:
        vis = get_viewer()["test_pieces"]
        x = np.linspace(0.0, 2.0, 21)
        mesh = beam_mesh(x, 0.1 * x ** 2, 0.3, 0.04, np.linspace(x, -x, 5).T)
        scale = ColorScale.symmetric(2.0, unit="MPa")
        vis["beam"].set_object(mesh.geometry(scale), g.MeshLambertMaterial(vertexColors=True))
        arrow = Arrow(vis["force"])
        arrow.set([0, 0, 0], [0, 0, 0.3])
        legend = ColorLegend(vis["legend"], scale)
        assert legend.set(scale) is False  # same scale: no new texture
        assert legend.set(ColorScale.symmetric(5.0, unit="MPa")) is True
        before = len(get_viewer().static_html())
        set_camera(get_viewer(), [1.0, -3.0, 1.0])
        arrow.set([0, 0, 0], [0, 0, 0.5])  # moved in place: one transform per part, no new object
        assert len(get_viewer().static_html()) - before < 2000
    finally:
        close_viewer()

