"""The course's Jupyter servers send a kernel's messages to the browser at once.

jupyter_server leaves Nagle's algorithm on for a kernel's websocket (tornado's default, see
``tornado.websocket.WebSocketHandler.set_nodelay``). A slider's drag is a steady exchange of small
messages: the page sends a move, the kernel answers with its status, the slider's echo, the new
figure and its status again, and ipywidgets sends the next move only once that last status is in.
With Nagle on, the server sends the first small message and holds the rest until the browser
acknowledges it; the browser's TCP delays that acknowledgement (up to 40 ms on Linux) because it
has nothing to send, as it waits for the status. So every round trip of a drag waited about
40 ms: a text label (the floor of ``benchmarks/bench_browser.py``) dragged at 30 key presses a
second changed 91-105 ms after the last key; with the kernel's websocket in no-delay mode, 24-25 ms,
what one key press costs. A single press after a pause is mostly spared (after an idle spell Linux
acknowledges at once), which is why drags showed it and single presses hardly did.

:class:`NoDelayConnection` is jupyter_server's own kernel connection with no-delay set when the
websocket opens; every server the course starts uses it through its option: ``make lab``
(:data:`SERVER_OPTION`), the apps (:data:`VOILA_OPTION`, :func:`afmsmiler.apps.voila_command`), the
image of a class's JupyterHub and of Binder (``binder/postBuild`` writes it into the servers'
configuration with :func:`write_server_config`; ``python -m afmsmiler.serving`` does the same for
an environment of one's own, The Littlest JupyterHub's) and the tests' servers.
"""
from __future__ import annotations

import json
import os
import sys
from pathlib import Path

from jupyter_server.services.kernels.connection.channels import ZMQChannelsWebsocketConnection

from .validation import check_instance

__all__ = ["CONNECTION_CLASS", "NoDelayConnection", "SERVER_OPTION", "VOILA_OPTION",
           "write_server_config"]


class NoDelayConnection(ZMQChannelsWebsocketConnection):
    """jupyter_server's kernel websocket connection, its socket in no-delay mode (TCP_NODELAY).

    Every message the kernel sends leaves the server when it is written, instead of waiting for
    the browser to acknowledge the one before (see the module's notes).
    """

    def connect(self):
        """Set no-delay on the websocket, then connect it to the kernel as jupyter_server does."""
        try:
            self.websocket_handler.set_nodelay(True)
        except Exception as exc:  # a socket gone already: the connection fails as it would
            self.log.warning("afmsmiler: could not set TCP_NODELAY on a kernel websocket: %s",
                             exc)
        return super().connect()


#: The class's import name, as Jupyter's configuration takes it.
CONNECTION_CLASS = "afmsmiler.serving.NoDelayConnection"  # (not __module__: "__main__" under -m)
#: The option that makes a Jupyter server (JupyterLab, a hub's single-user server) use it.
SERVER_OPTION = f"--ServerApp.kernel_websocket_connection_class={CONNECTION_CLASS}"
#: The same option for voila's own server (:func:`afmsmiler.apps.voila_command`).
VOILA_OPTION = f"--Voila.kernel_websocket_connection_class={CONNECTION_CLASS}"


def write_server_config(prefix=None) -> Path:
    """Make every Jupyter server of an environment use :class:`NoDelayConnection`.

    Writes ``PREFIX/etc/jupyter/jupyter_server_config.d/afmsmiler.json``, which every Jupyter
    server started from that environment reads (JupyterLab, a hub's single-user server and the
    voila pages it serves).

    Parameters
    ----------
    prefix : str or os.PathLike, optional
        The environment's prefix; this Python's (``sys.prefix``) by default.

    Returns
    -------
    pathlib.Path
        The file written.
    """
    if prefix is not None:
        check_instance("prefix", prefix, (str, os.PathLike), "str or os.PathLike (a folder)")
    prefix = Path(sys.prefix if prefix is None else prefix)
    if not prefix.is_dir():
        raise ValueError(f"prefix must be an existing folder, got {str(prefix)!r}")
    folder = prefix / "etc" / "jupyter" / "jupyter_server_config.d"
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / "afmsmiler.json"
    path.write_text(json.dumps({"ServerApp": {"kernel_websocket_connection_class":
                                              CONNECTION_CLASS}}, indent=2) + "\n")
    return path


if __name__ == "__main__":
    print(f"wrote {write_server_config(sys.argv[1] if len(sys.argv) > 1 else None)}")
