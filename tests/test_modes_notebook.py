"""What notebook 07 claims happens: its first tries at the exercises are wrong, and the checker
says why (run here from the notebook's own cells); every "Things to try" list names the test file
that follows it, and that file holds a test for each suggestion."""
import json
from pathlib import Path

import pytest

NOTEBOOK = Path(__file__).parents[1] / "notebooks" / "07_imaging_modalities.ipynb"
CELLS = json.loads(NOTEBOOK.read_text(encoding="utf-8"))["cells"]
CODE = ["".join(c["source"]) for c in CELLS if c["cell_type"] == "code"]
MARKDOWN = ["".join(c["source"]) for c in CELLS if c["cell_type"] == "markdown"]


def _run(*sources):
    """Run cells of the notebook in one namespace; return the last expression's value."""
    namespace = {}
    exec("from afmsmiler.exercises import modes as ex", namespace)
    *body, last = "\n".join(sources).rstrip().splitlines()
    exec("\n".join(body), namespace)
    return eval(last.split("#")[0], namespace)


def _cell(text):
    matches = [src for src in CODE if text in src]
    assert len(matches) == 1, f"one cell holds {text!r}"
    return matches[0]


@pytest.mark.parametrize("cells, words", [
    (("check_attractive_setpoint(0.8)",), "repulsive"),
    (("loop.trace[1:-1].mean()",), "trace alone"),
    (("g = ex.dissipation_givens()", "math.sin(g[\"phase_deg\"])"), "degrees"),
])
def test_first_tries_are_wrong_and_the_checker_says_why(cells, words):
    feedback = _run(*(_cell(text) for text in cells))
    assert not feedback
    assert words in str(feedback)


def test_placeholders_ask_for_an_answer():
    for text in ("setpoint = None", "mu = None", "energy = None"):
        assert not _run(_cell(text))


def test_every_list_of_things_to_try_is_followed_by_tests():
    lists = [m for m in MARKDOWN if "Things to try" in m]
    assert len(lists) == 5  # lateral, tapping, FM, jumping, force volume
    ui_tests = (Path(__file__).parent / "test_modes_ui.py").read_text(encoding="utf-8")
    items = 0
    for m in lists:
        assert "tests/test_modes_ui.py" in m
        assert m.count("\n1. ") == 1 and m.count("\n2. ") == 1  # two suggestions at least
        items += sum(m.count(f"\n{i}. ") for i in range(1, 10))
    assert items == 11  # tapping has a third: its probe in water
    # one test per suggestion: the suggestions' own tests
    suggestions = ui_tests.count("def test_notebook_suggestion_") + \
        ui_tests.count("def test_lateral_noise_stays_within_its_rms") + \
        ui_tests.count("def test_fm_panel_inversion_within_a_few_per_cent")
    assert suggestions == items
