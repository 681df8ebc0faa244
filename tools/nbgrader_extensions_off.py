"""Turn nbgrader's Jupyter server and JupyterLab extensions off in this environment (sys-prefix).

nbgrader (the ``test`` and ``course`` extras) is used through its command line and Python API
only; its extensions would load into every Jupyter server of the environment (JupyterLab, voila,
a hub's servers). This writes what ``jupyter server extension disable --sys-prefix NAME`` and
``jupyter labextension disable --level=sys_prefix @jupyter/nbgrader`` write, through the same
functions of jupyter_server and jupyterlab, without starting either command line: each of those
imports and validates every installed extension first (about 4 s per call, 21 s for the five).

Usage: ``python tools/nbgrader_extensions_off.py [PREFIX]`` (PREFIX defaults to ``sys.prefix``,
the environment of the Python that runs it).
"""
from __future__ import annotations

import os
import sys

#: nbgrader's server extensions (its ``jupyter_server_config.d/nbgrader.json`` enables them).
SERVER_EXTENSIONS = tuple(f"nbgrader.server_extensions.{name}" for name in
                          ("formgrader", "assignment_list", "course_list",
                           "validate_assignment"))
#: nbgrader's JupyterLab extension.
LAB_EXTENSION = "@jupyter/nbgrader"


def turn_off(prefix: str) -> None:
    """Disable nbgrader's server and lab extensions at ``prefix``'s ``etc/jupyter``."""
    from jupyter_server.extension.config import ExtensionConfigManager
    config_dir = os.path.join(prefix, "etc", "jupyter")
    manager = ExtensionConfigManager(
        read_config_path=[config_dir],
        write_config_dir=os.path.join(config_dir, "jupyter_server_config.d"))
    for name in SERVER_EXTENSIONS:
        manager.disable(name)
    # jupyterlab's page_config.json at the sys-prefix level (labconfig/ under etc/jupyter):
    # the file `jupyter labextension disable --level=sys_prefix` merges into
    from jupyter_server.config_manager import BaseJSONConfigManager
    lab = BaseJSONConfigManager(config_dir=os.path.join(config_dir, "labconfig"))
    lab.update("page_config", {"disabledExtensions": {LAB_EXTENSION: True}})


if __name__ == "__main__":
    if len(sys.argv) > 2:
        sys.exit(__doc__)
    turn_off(sys.argv[1] if len(sys.argv) == 2 else sys.prefix)
