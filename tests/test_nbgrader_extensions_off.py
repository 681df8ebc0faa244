"""`make install` turns nbgrader's Jupyter extensions off (tools/nbgrader_extensions_off.py).

The tool writes the configuration that ``jupyter server extension disable --sys-prefix`` and
``jupyter labextension disable --level=sys_prefix`` write; jupyter_server's own config manager
reads it back, over nbgrader's file that turns its extensions on, and the list of extensions is
nbgrader's own (so a renamed or new extension fails here).
"""
import importlib.util
import json
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
_spec = importlib.util.spec_from_file_location("nbgrader_extensions_off",
                                               ROOT / "tools" / "nbgrader_extensions_off.py")
tool = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(tool)

config = pytest.importorskip("jupyter_server.extension.config",
                             reason="jupyter_server (the lab extra) is not installed")
#: nbgrader's own file that turns its server extensions on, as its wheel installs it.
NBGRADER_ON = Path(sys.prefix) / "etc" / "jupyter" / "jupyter_server_config.d" / "nbgrader.json"


def _nbgrader_on() -> dict:
    if not NBGRADER_ON.exists():
        pytest.skip(f"nbgrader is not installed in this environment ({NBGRADER_ON} is missing)")
    return json.loads(NBGRADER_ON.read_text())


def test_the_tool_names_every_server_extension_nbgrader_installs():
    on = _nbgrader_on()["ServerApp"]["jpserver_extensions"]
    assert set(tool.SERVER_EXTENSIONS) == set(on)


def test_jupyter_reads_them_off_over_nbgraders_own_file(tmp_path):
    etc = tmp_path / "etc" / "jupyter"
    (etc / "jupyter_server_config.d").mkdir(parents=True)
    (etc / "jupyter_server_config.d" / "nbgrader.json").write_text(json.dumps(_nbgrader_on()))
    manager = config.ExtensionConfigManager(read_config_path=[str(etc)])
    assert all(manager.enabled(name) for name in tool.SERVER_EXTENSIONS)  # before: on

    tool.turn_off(str(tmp_path))
    manager = config.ExtensionConfigManager(read_config_path=[str(etc)])
    assert [name for name in tool.SERVER_EXTENSIONS if manager.enabled(name)] == []
    page = json.loads((etc / "labconfig" / "page_config.json").read_text())
    assert page["disabledExtensions"] == {tool.LAB_EXTENSION: True}


def test_a_lab_setting_already_there_is_kept(tmp_path):
    labconfig = tmp_path / "etc" / "jupyter" / "labconfig"
    labconfig.mkdir(parents=True)
    (labconfig / "page_config.json").write_text(json.dumps(
        {"disabledExtensions": {"@other/extension": True}, "lockedExtensions": {"x": True}}))
    tool.turn_off(str(tmp_path))
    page = json.loads((labconfig / "page_config.json").read_text())
    assert page == {"disabledExtensions": {"@other/extension": True, tool.LAB_EXTENSION: True},
                    "lockedExtensions": {"x": True}}
