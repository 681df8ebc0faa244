"""The browser tests' own helpers (``tests/browser.py``) that need no browser."""
import math

import pytest

from tests import browser as B


@pytest.mark.parametrize("interval", [-0.01, math.nan, -math.inf])
def test_press_keys_names_a_bad_interval_before_pressing_anything(interval):
    # no page: a press would raise AttributeError, so the check comes first
    with pytest.raises(ValueError, match=r"interval must be a number >= 0 s, got"):
        B.press_keys(None, "ArrowLeft", 3, interval)


def _windowing_setting(server):
    import json
    path = (server._settings() / "@jupyterlab" / "notebook-extension"
            / "tracker.jupyterlab-settings")
    return json.loads(path.read_text())


def test_the_tests_keep_every_cell_rendered_and_a_benchmark_can_ask_for_jupyterlab_s_own(
        tmp_path):
    # the tests' server: every cell in the DOM and rendered
    assert _windowing_setting(B.Server("lab", tmp_path / "a")) == {"windowingMode": "none"}
    # a student's (`make lab` passes no settings): no windowing mode of ours, JupyterLab's own
    assert _windowing_setting(B.Server("lab", tmp_path / "b", windowing=None)) == {}
    # and the modes JupyterLab's own schema offers are the ones the server takes
    import json
    import sys
    from pathlib import Path
    schema = (Path(sys.prefix) / "share" / "jupyter" / "lab" / "schemas" / "@jupyterlab"
              / "notebook-extension" / "tracker.json")
    if not schema.exists():
        pytest.skip(f"JupyterLab's schema is not installed at {schema}")
    modes = json.loads(schema.read_text())["properties"]["windowingMode"]
    assert sorted(m["const"] for m in modes["oneOf"]) == sorted(B.WINDOWING)
    for mode in B.WINDOWING:
        assert _windowing_setting(B.Server("lab", tmp_path / mode, windowing=mode)) == {
            "windowingMode": mode}


@pytest.mark.parametrize("windowing", ["", "None", "contentvisibility", 0])
def test_a_server_names_a_windowing_mode_it_does_not_know(tmp_path, windowing):
    with pytest.raises(ValueError, match=r"windowing must be None or one of none, full, defer, "
                                         r"contentVisibility, got"):
        B.Server("lab", tmp_path, windowing=windowing)


@pytest.mark.parametrize("code, prefix", [(B.FLOOR_CODE, "_floor_"),
                                          (B.NULL_FIGURE_CODE, "_null_")],
                         ids=["floor", "null figure"])
def test_a_cell_added_to_a_course_notebook_keeps_its_cells_and_its_names(tmp_path, code, prefix):
    import shutil

    import nbformat
    course = sorted(B.NOTEBOOKS.glob("*.ipynb"))[0]
    path = shutil.copy2(course, tmp_path / course.name)
    before = nbformat.read(str(path), as_version=4).cells
    B.append_cell(path, code)
    after = nbformat.read(str(path), as_version=4).cells
    assert [c.source for c in after[:-1]] == [c.source for c in before]
    assert after[-1].cell_type == "code" and after[-1].source == code
    # run as a cell would be: it takes no name of the notebook, and its output follows its slider
    body, last = code.rsplit("\n", 1)
    names = {}
    exec(body, names)
    slider, shown = eval(last, names).children  # the cell's output: the box it shows
    assert all(n.lower().startswith(prefix) for n in names if n != "__builtins__")
    if code == B.FLOOR_CODE:
        assert slider.description == B.FLOOR_SLIDER
        slider.value = 123
        assert shown.value == "123"
    else:
        assert slider.description == B.NULL_FIGURE_SLIDER
        sent = shown.frames_sent
        slider.value = 123
        assert shown.frames_sent == sent + 1
        assert names["_null_line"].get_ydata()[1] == 123


def test_the_floor_notebook_holds_the_floor_cell(tmp_path):
    import nbformat
    cells = nbformat.read(str(B.floor_notebook(tmp_path / "floor.ipynb")), as_version=4).cells
    assert [c.source for c in cells] == [B.FLOOR_CODE]
