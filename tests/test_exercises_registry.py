"""The exercises' registry: every checker an exercise with its key, answers and a solution that
the model computes; verdicts carry their key and are recorded (in the process and in the grade
log the grader reads); Feedback.require is what nbgrader's test cells call."""
import ast
import json
import math
import re
from pathlib import Path

import pytest

from afmsmiler.exercises import Feedback
from afmsmiler.exercises.registry import (GRADE_LOG, Exercise, all_exercises, exercise,
                                          exercises_of, recording)
from afmsmiler.grade.notebooks import checker_calls, notebook_number, read_notebook

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = sorted((ROOT / "notebooks").glob("0*.ipynb"))
EXERCISES = all_exercises()
#: Solutions that take a second or more (a search over gains, an alignment, a bisection).
SLOW = {"03.1", "05.1", "07.1"}


def test_every_checker_is_an_exercise_of_its_notebook():
    import importlib
    import inspect

    from afmsmiler.exercises import registry
    checkers = {f"{m}.{name}" for m in registry.MODULES
                for name, obj in vars(importlib.import_module(f"afmsmiler.exercises.{m}")).items()
                if name.startswith("check_") and inspect.isfunction(obj)
                and obj.__module__ == f"afmsmiler.exercises.{m}"}
    registered = {f"{e.checker.__module__.rsplit('.', 1)[1]}.{e.checker.__name__}"
                  for e in EXERCISES.values()}
    assert checkers == registered
    assert len(EXERCISES) == 28
    # notebook NN's checkers live in the NN-th module of the course's order
    for e in EXERCISES.values():
        assert e.checker.__module__.endswith(registry.MODULES[int(e.notebook) - 1]), e.key
        assert e.checker.exercise is e and e.checker.solution is e.solution


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_each_notebook_asks_its_exercises_in_order_with_their_titles(path):
    nb = read_notebook(path)
    number = notebook_number(path)
    calls = checker_calls(nb, number)
    exercises = exercises_of(number)
    assert [c.exercise.key for c in sorted(calls.values(), key=lambda c: c.cell)] == \
        [e.key for e in exercises]
    markdown = "\n".join("".join(c["source"]) for c in nb["cells"] if c["cell_type"] == "markdown")
    for e in exercises:
        number_in_text = re.match(r"\d+", e.key.split(".")[1]).group()
        # the title (before a part's colon) is the notebook's bold heading of that exercise
        assert f"**{number_in_text}. {e.title.split(':')[0]}" in markdown, e.key
        # each answer is a variable the student sets (where it says None)
        assert None not in calls[e.key].answers, (e.key, calls[e.key])


def _givens(key):
    """The exercise's givens as its notebook passes them (``ex`` of notebook 04 rebuilt)."""
    path = next(p for p in NOTEBOOKS if p.name.startswith(key[:2]))
    nb = read_notebook(path)
    call = checker_calls(nb, key[:2])[key]
    namespace = {}
    for cell in nb["cells"]:  # notebook 04's ``ex = fitting_exercise(seed=...)``
        for line in "".join(cell["source"]).splitlines():
            if line.startswith("ex = fitting_exercise("):
                from afmsmiler.exercises.contact import fitting_exercise
                namespace = {"ex": eval(line.split("=", 1)[1], {"fitting_exercise": fitting_exercise})}
    return {name: (ast.literal_eval(src) if name != "exercise" else namespace["ex"])
            for name, src in call.givens}


@pytest.mark.parametrize("key", [pytest.param(k, marks=[pytest.mark.slow] if k in SLOW else [])
                                 for k in EXERCISES])
def test_the_solution_passes_and_a_placeholder_does_not(key):
    e = EXERCISES[key]
    givens = _givens(key)
    import inspect
    takes = inspect.signature(e.solution).parameters
    answer = e.solution(**{k: v for k, v in givens.items() if k in takes})
    answers = answer if len(e.answers) > 1 else (answer,)
    assert len(answers) == len(e.answers)
    with recording() as verdicts:
        right = e.checker(**dict(zip(e.answers, answers)), **givens)
        empty = e.checker(**dict.fromkeys(e.answers), **givens)
    assert right.passed, right
    assert not empty.passed and str(empty).startswith("Not yet.")
    assert [(v.exercise, v.passed) for v in verdicts] == [(key, True), (key, False)]


# -- the solutions that search or measure, against independent values ---------------------------
def test_thickness_solution_is_the_closed_form():
    # k = E w h^3 / (4 L^3) (Euler-Bernoulli, end load): h = (4 k L^3 / (E w))^(1/3)
    from afmsmiler.exercises.cantilever import thickness_for_spring_constant
    from afmsmiler.materials import lookup
    e = lookup("silicon", "material").youngs_modulus
    h = (4 * 0.1 * 450e-6 ** 3 / (e * 50e-6)) ** (1 / 3)
    assert thickness_for_spring_constant(target_k=0.1, length=450e-6, width=50e-6,
                                         material="silicon") == pytest.approx(h, rel=1e-9)


def test_doubling_length_halves_the_lever():
    # the spot moves by 2 D theta with theta = 3 z / (2 L) (Meyer and Amer 1988): S ~ 1 / L
    from afmsmiler.exercises.transducers import doubling_length
    assert doubling_length(225e-6) == pytest.approx(112.5e-6, rel=1e-9)


def test_quadrature_is_a_quarter_fringe():
    # P = P0 (1 + V cos(4 pi d / lambda + phi)) is steepest where sin(phi) = +-1
    from afmsmiler.exercises.transducers import quadrature_phase
    assert quadrature_phase() == pytest.approx(math.pi / 2, abs=1e-6)


def test_friction_and_tip_radius_are_found_back():
    from afmsmiler.exercises import imaging, modes
    # the loop was made with mu = 0.25 and 0.2 nN of noise on 5 nN of friction
    assert modes.friction_from_loop() == pytest.approx(modes.DEFAULTS["friction"], rel=0.01)
    # the image was made with a 12 nm paraboloid (the measured width is a pixel short)
    assert imaging.tip_radius_from_width() == pytest.approx(12e-9, rel=0.05)
    assert imaging.measured_width() == pytest.approx(72e-9, abs=1.5e-9)


# -- verdicts carry their exercise and are recorded --------------------------------------------
def test_verdicts_are_recorded_in_the_grade_log(tmp_path, monkeypatch):
    from afmsmiler.exercises.cantilever import check_mode_ratio
    from afmsmiler.grade.scoring import read_verdicts
    log = tmp_path / "verdicts.jsonl"
    monkeypatch.setenv(GRADE_LOG, str(log))
    given = [check_mode_ratio(None), check_mode_ratio(6.267)]
    monkeypatch.delenv(GRADE_LOG)
    check_mode_ratio(None)  # no log: nothing written
    lines = log.read_text(encoding="utf-8").splitlines()
    assert [json.loads(line)["exercise"] for line in lines] == ["01.2", "01.2"]
    assert read_verdicts(log.read_text(encoding="utf-8")) == given
    assert [v.passed for v in given] == [False, True]


def test_require_raises_with_the_hint():
    from afmsmiler.exercises.cantilever import check_tip_slope, tip_slope
    good = check_tip_slope(tip_slope())
    assert good.require() is good and good.exercise == "01.4"
    with pytest.raises(AssertionError, match=r"Not yet\. .*10\^3 times the right one"):
        check_tip_slope(1e3 * tip_slope()).require()   # mrad for rad


def test_a_feedback_of_no_exercise_is_not_recorded():
    with recording() as verdicts:
        fb = Feedback(False, "x")
    assert verdicts == [] and fb.exercise is None


@pytest.mark.parametrize("kwargs, words", [
    (dict(key="1.1"), "key must be"), (dict(key="01.0"), "key must be"),
    (dict(title=" "), "title must be"), (dict(answers="x"), "answers must be"),
    (dict(answers=()), "answers must be"), (dict(answers=("nope",)), "answers of 09.9"),
    (dict(solution=1.0), "solution must be callable"), (dict(points=0), "points must be"),
    (dict(points=math.nan), "points must be"), (dict(points=True), "points must be"),
    (dict(solution=lambda x: x), "solution of 09.9"),
    (dict(solution=lambda given, extra: given), "solution of 09.9"),
])
def test_registration_is_checked(kwargs, words):
    args = dict(key="09.9", title="A test", answers=("x",), solution=lambda given=1.0: given)
    args.update(kwargs)
    with pytest.raises(ValueError, match=words):
        exercise(args.pop("key"), args.pop("title"), **args)(lambda x, given=1.0: Feedback(True, ""))


def test_a_key_is_one_checker():
    from afmsmiler.exercises.cantilever import check_mode_ratio
    with pytest.raises(ValueError, match="already"):
        exercise("01.2", "Again", answers=("x",), solution=lambda: 1.0)(lambda x: None)
    assert isinstance(check_mode_ratio.exercise, Exercise)
    assert check_mode_ratio.exercise.grade_id == "ex01_2"


def test_exercises_of_takes_a_number_or_a_name():
    assert [e.key for e in exercises_of("04")] == ["04.1a", "04.1b", "04.2"]
    assert exercises_of("04_contact_mechanics.ipynb") == exercises_of(Path("x/04_a.ipynb"))
    assert exercises_of("09") == []
    for bad in ("contact", 4, None):
        with pytest.raises(ValueError, match="notebook must be"):
            exercises_of(bad)
