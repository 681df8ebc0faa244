"""One meshcat viewer per kernel, bound to 127.0.0.1, closed on demand and never leaked.

Every scene builder in :mod:`afmsmiler.scenes` draws into the :class:`meshcat.Visualizer` returned
by :func:`get_viewer`. The first call starts one server process; later calls reuse it. A notebook
ends with :func:`close_viewer`. Because nbval and a crashed kernel kill the kernel hard, the
server is also started with ``PR_SET_PDEATHSIG`` (Linux), so the kernel's death takes the server
with it, and it is tagged with the environment variable ``AFMSMILER_MESHCAT_OWNER`` (the owner's
pid) so that a test can prove that none outlives its kernel.
"""
from __future__ import annotations

import atexit
import ctypes
import os
import re
import signal
import subprocess
import sys
import threading

import meshcat
from meshcat.visualizer import ViewerWindow

from ..validation import check_instance, check_writable_path

__all__ = ["get_viewer", "close_viewer", "viewer_running", "static_html", "save_static_html",
           "OWNER_ENV"]

OWNER_ENV = "AFMSMILER_MESHCAT_OWNER"
_START_TIMEOUT = 30.0

_lock = threading.Lock()
_proc: subprocess.Popen | None = None
_vis: meshcat.Visualizer | None = None


def _die_with_parent():  # runs in the child between fork and exec
    if sys.platform.startswith("linux"):
        try:
            libc = ctypes.CDLL("libc.so.6", use_errno=True)
            PR_SET_PDEATHSIG = 1
            libc.prctl(PR_SET_PDEATHSIG, signal.SIGKILL)
        except OSError:
            pass


def _start_server() -> tuple[subprocess.Popen, str, str]:
    env = dict(os.environ)
    env[OWNER_ENV] = str(os.getpid())
    proc = subprocess.Popen(
        [sys.executable, "-u", "-m", "afmsmiler.scenes._server"],
        stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
        env=env, start_new_session=True, preexec_fn=_die_with_parent)
    urls = {}
    timer = threading.Timer(_START_TIMEOUT, proc.kill)
    timer.start()
    try:
        while len(urls) < 2:
            line = proc.stdout.readline().decode("utf-8", "replace")
            if not line:
                raise RuntimeError(f"the meshcat server exited before it was ready "
                                   f"(exit code {proc.wait()})")
            m = re.match(r"(zmq_url|web_url)=(\S+)", line.strip())
            if m:
                urls[m.group(1)] = m.group(2)
    finally:
        timer.cancel()
    # Keep draining stdout so the server never blocks on a full pipe.
    threading.Thread(target=lambda: proc.stdout.read(), daemon=True).start()
    return proc, urls["zmq_url"], urls["web_url"]


def get_viewer() -> meshcat.Visualizer:
    """Return this kernel's meshcat visualizer, starting its server on first use.

    Returns
    -------
    meshcat.Visualizer
        The root visualizer; scene builders draw below their own path in it.
    """
    global _proc, _vis
    with _lock:
        if _vis is not None and _proc is not None and _proc.poll() is None:
            return _vis
        _proc, zmq_url, web_url = _start_server()
        window = ViewerWindow.__new__(ViewerWindow)  # connect without meshcat's own launcher
        window.server_proc, window.zmq_url, window.web_url = _proc, zmq_url, web_url
        window.connect_zmq()
        _vis = meshcat.Visualizer(window=window)
        return _vis


def viewer_running() -> bool:
    """True while this kernel's meshcat server is alive."""
    return _proc is not None and _proc.poll() is None


def close_viewer() -> None:
    """Stop this kernel's meshcat server (safe to call any number of times)."""
    global _proc, _vis
    with _lock:
        if _vis is not None:
            try:
                _vis.window.zmq_socket.close(linger=0)
            except Exception:
                pass
        if _proc is not None and _proc.poll() is None:
            _proc.kill()
            _proc.wait(timeout=10)
        _proc = None
        _vis = None


atexit.register(close_viewer)


def static_html(vis: meshcat.Visualizer | None = None) -> str:
    """Return the current scene as one self-contained HTML page (meshcat's ``static_html``).

    Parameters
    ----------
    vis : meshcat.Visualizer, optional
        The visualizer to export; this kernel's viewer by default.

    Raises
    ------
    TypeError
        If ``vis`` is not a :class:`meshcat.Visualizer`.
    """
    if vis is None:
        vis = get_viewer()
    check_instance("vis", vis, meshcat.Visualizer)
    return vis.static_html()


def save_static_html(path, vis: meshcat.Visualizer | None = None) -> str:
    """Write :func:`static_html` to ``path`` (for the course book) and return the path.

    Parameters
    ----------
    path : str or os.PathLike
        The HTML file to write, in an existing folder (replaced if it exists).
    vis : meshcat.Visualizer, optional
        The visualizer to export; this kernel's viewer by default.

    Raises
    ------
    ValueError
        If ``path`` is not a path, names a folder, lies in a folder that does not exist or
        cannot be written (the message names ``path`` and the operating system's reason).
    TypeError
        If ``vis`` is not a :class:`meshcat.Visualizer`.
    """
    path = check_writable_path("path", path, "an HTML file")
    if vis is not None:
        check_instance("vis", vis, meshcat.Visualizer)
    html = static_html(vis)  # before the file is opened: a failed export leaves no empty file
    try:
        with open(path, "w", encoding="utf-8") as f:
            f.write(html)
    except OSError as err:
        raise ValueError(f"path {path!r} cannot be written: {err.strerror or err}") from None
    return path
