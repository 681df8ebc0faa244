"""Notebook 07 as a student runs it: JupyterLab in headless Debian Chromium (``tests/browser.py``),
Run All with no test flags, no cell or panel showing an error; a key press on each module (g)
panel's slider changes its figure's pixels and the kernel's panel follows the slider; an
exercise answered wrong, then right, in the notebook's kernel.

Marked ``slow`` and ``browser`` (``make unit`` skips them); skipped, saying why, when Chromium,
Playwright or JupyterLab is missing."""
import shutil

import pytest

from tests import browser as B

pytestmark = [pytest.mark.slow, pytest.mark.browser,
              pytest.mark.xdist_group("modes_browser")]  # its servers on one worker

NOTEBOOK = "07_imaging_modalities.ipynb"
SELECTOR = B.figure_selector()
#: Panel variable in the notebook -> (part of) its slider's description, the control's name,
#: the key to press.
SLIDERS = {"tapping": ("setpoint A_sp / A0", "setpoint_ratio", "ArrowRight"),
           "lateral": ("sample tilt", "tilt", "ArrowRight"),
           "fm": ("oscillation amplitude A", "amplitude", "ArrowLeft"),
           "jumping": ("lift height", "lift_height", "ArrowLeft"),
           "volume": ("force noise", "force_noise", "ArrowRight")}


@pytest.fixture(scope="module")
def lab(chromium):
    root = B.notebook_root("afm-modalities-")
    try:
        with B.Server("lab", root) as server:
            page = B.new_page(chromium)
            try:
                B.open_lab(page, server, NOTEBOOK, timeout=120)
                B.run_all(page, timeout=400)
                yield server, page
                B.close_lab_notebook(page, server)
            finally:
                page.close()
    finally:
        shutil.rmtree(root, ignore_errors=True)


def test_run_all_shows_no_error(lab):
    _, page = lab
    assert B.lab_errors(page) == []


@pytest.mark.parametrize("panel", list(SLIDERS))
def test_each_panel_follows_its_slider(lab, panel):
    _, page = lab
    description, attr, key = SLIDERS[panel]
    slider = B.find_slider(page, description)
    B.focus_panel(page, slider, SELECTOR)
    times = B.press(page, slider, key, 1, selector=SELECTOR, timeout=15.0)
    assert times[0] is not None, f"{panel}: the figure did not change within 15 s"
    shown = float(B.slider_value(slider))
    value = float(B.kernel_eval(page, f"print({panel}.values()[{attr!r}])"))
    assert value == pytest.approx(shown, rel=1e-3, abs=1e-3)
    assert B.lab_errors(page) == []


def test_an_exercise_wrong_then_right(lab):
    _, page = lab
    wrong = B.kernel_eval(page, "print(ex.check_attractive_setpoint(10))")
    assert wrong.startswith("Not yet") and "in nm" in wrong
    right = B.kernel_eval(page, "print(ex.check_attractive_setpoint("
                                "round(ex.lowest_attractive_setpoint() + 0.01, 2)))")
    assert right.startswith("Correct")
