"""The course's servers send a kernel's messages at once (afmsmiler/serving.py).

The connection class sets TCP_NODELAY on the kernel's websocket, checked on a real socket; every
way the course serves a notebook (``make lab``, the apps, Binder's and a hub's image, the tests'
own servers, whose figures the benchmarks report) uses it.
"""
import json
import os
import re
import shutil
import socket
import subprocess
import sys
from pathlib import Path

import pytest

from afmsmiler import apps
from afmsmiler.serving import (CONNECTION_CLASS, SERVER_OPTION, VOILA_OPTION, NoDelayConnection,
                               write_server_config)

ROOT = Path(__file__).resolve().parents[1]


class _Handler:
    """The part of a kernel websocket handler the connection touches: a real TCP socket."""

    def __init__(self, sock):
        self.sock, self.calls = sock, []

    def set_nodelay(self, value):  # as tornado's WebSocketHandler.set_nodelay -> IOStream
        self.calls.append(("set_nodelay", value))
        self.sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1 if value else 0)


@pytest.fixture
def tcp_pair():
    server = socket.create_server(("127.0.0.1", 0))
    client = socket.create_connection(server.getsockname())
    accepted, _ = server.accept()
    yield accepted
    for s in (client, accepted, server):
        s.close()


def test_the_connection_sets_no_delay_on_the_kernel_socket_before_it_connects(tcp_pair,
                                                                              monkeypatch):
    assert tcp_pair.getsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY) == 0  # Nagle by default
    handler = _Handler(tcp_pair)
    parent = NoDelayConnection.__mro__[1]
    monkeypatch.setattr(parent, "connect", lambda self: handler.calls.append("connect"))
    conn = NoDelayConnection.__new__(NoDelayConnection)
    conn._trait_values["websocket_handler"] = handler
    conn.connect()
    assert handler.calls == [("set_nodelay", True), "connect"]
    assert tcp_pair.getsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY) != 0


def test_a_socket_already_gone_is_logged_and_the_connection_goes_on(monkeypatch):
    class Gone:
        def set_nodelay(self, value):
            raise AssertionError("ws_connection is None")  # tornado's own check

    parent = NoDelayConnection.__mro__[1]
    calls = []
    monkeypatch.setattr(parent, "connect", lambda self: calls.append("connect"))
    warnings = []
    conn = NoDelayConnection.__new__(NoDelayConnection)
    conn._trait_values["websocket_handler"] = Gone()
    conn._trait_values["log"] = type("L", (), {"warning": lambda s, *a: warnings.append(a)})()
    conn.connect()
    assert calls == ["connect"] and "TCP_NODELAY" in warnings[0][0]


def test_the_servers_themselves_take_the_options_and_the_config_file(tmp_path):
    """A misspelt option or config key is only warned about by Jupyter and ignored: the servers'
    own application classes are asked which connection class they would use."""
    from jupyter_server.serverapp import ServerApp
    from traitlets.config.loader import JSONFileConfigLoader
    lab = ServerApp()
    lab.parse_command_line([SERVER_OPTION])
    assert lab.kernel_websocket_connection_class is NoDelayConnection
    voila_app = pytest.importorskip("voila.app")
    voila = voila_app.Voila()
    voila.parse_command_line([VOILA_OPTION, "x.ipynb"])
    assert voila.kernel_websocket_connection_class is NoDelayConnection
    path = write_server_config(tmp_path)
    config = JSONFileConfigLoader(path.name, str(path.parent)).load_config()
    assert ServerApp(config=config).kernel_websocket_connection_class is NoDelayConnection
    # and by its name from a fresh interpreter (a server imports it so)
    module, _, name = CONNECTION_CLASS.rpartition(".")
    out = subprocess.run([sys.executable, "-c", f"import {module} as m; print(m.{name}.__mro__[1])"],
                         capture_output=True, text=True, check=True).stdout
    assert "ZMQChannelsWebsocketConnection" in out


def test_every_server_the_course_starts_uses_it(tmp_path):
    make = (ROOT / "Makefile").read_text()
    recipe = re.search(r"^lab:.*?\n((?:\t.*\n)+)", make, re.M).group(1)
    assert SERVER_OPTION in recipe.replace("\\\n", " ").replace("\t", " ")
    assert VOILA_OPTION in apps.voila_command(apps.NOTEBOOKS, port=8899)
    from tests import browser as B
    assert SERVER_OPTION in B.Server("lab", tmp_path).command()
    # the tests' hub: its single-user servers' arguments, as its configuration file sets them
    from traitlets.config import Config
    from tests.hub import Hub
    hub = Hub(["course-student-1"])
    try:
        c = Config()
        exec(hub._config().read_text(), {"c": c})
        assert SERVER_OPTION in c.Spawner.args
    finally:
        shutil.rmtree(hub.dir, ignore_errors=True)


def test_binder_s_image_configures_every_jupyter_server_with_it(tmp_path):
    """postBuild's Python, run against a scratch prefix: the server's config names the class."""
    script = (ROOT / "binder" / "postBuild").read_text()
    python = script.split("<<'PY'\n", 1)[1].split("\nPY", 1)[0]
    python = python.replace("Path(sys.prefix)", f"Path({str(tmp_path)!r})")
    (tmp_path / "share" / "jupyter").mkdir(parents=True)  # the image's Jupyter has made it
    subprocess.run([sys.executable, "-c", python], check=True, cwd=ROOT,
                   env={**os.environ, "PYTHONPATH": str(ROOT)})
    conf = json.loads((tmp_path / "etc" / "jupyter" / "jupyter_server_config.d" /
                       "afmsmiler.json").read_text())
    assert conf == {"ServerApp": {"kernel_websocket_connection_class": CONNECTION_CLASS}}


def test_an_environment_of_one_s_own_is_configured_by_the_module(tmp_path):
    out = subprocess.run([sys.executable, "-m", "afmsmiler.serving", str(tmp_path)],
                         capture_output=True, text=True, check=True, cwd=ROOT).stdout
    path = tmp_path / "etc" / "jupyter" / "jupyter_server_config.d" / "afmsmiler.json"
    assert str(path) in out
    assert json.loads(path.read_text())["ServerApp"]["kernel_websocket_connection_class"] == \
        CONNECTION_CLASS
    with pytest.raises(ValueError, match="prefix must be an existing folder"):
        write_server_config(tmp_path / "missing")
    # not a path at all: named before anything is written (Path(3) raised a bare TypeError)
    with pytest.raises(TypeError, match=r"prefix must be a str or os.PathLike .*, got int 3"):
        write_server_config(3)
