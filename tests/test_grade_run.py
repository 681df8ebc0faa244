"""The grade command and nbgrader on the course's notebooks, run for real (slow: two session
fixtures run 22 notebooks, the grade command's two at a time, 1.5 to 3 minutes on two shared
cores; the times are printed).

* the notebooks as students get them (every answer None), through the command line: every
  exercise 0, with the checker's hint;
* their solved copies (each answer computed by the exercise's solution): full marks;
* nbgrader: each notebook's source version (``--nbgrader-source``) released with
  ``generate_assignment``, a student's submission that solves every other exercise, leaves the
  others as released and slips a unit in two (a thickness in um, a slope in mrad), autograded by
  nbgrader and graded by the grade command: the same score for every exercise, and the slips
  get the checker's hint. Notebooks 01, 04 and 06 (:data:`NBGRADER`): the others' exercises
  are asked as theirs are (the same cells, checked statically in
  tests/test_grade_notebooks.py);
* a run past its time limit is stopped, its kernel gone, and each exercise without a verdict
  says why.
"""
import contextlib
import io
import json
import os
import shutil
import sys
import time
from pathlib import Path

import psutil
import pytest

from afmsmiler.exercises.registry import exercises_of
from afmsmiler.grade import cli
from afmsmiler.grade.notebooks import (BEGIN_SOLUTION, END_SOLUTION, checker_calls,
                                       nbgrader_source, notebook_number, read_notebook,
                                       solution_code, solved_copy, write_notebook)
from afmsmiler.grade.run import grade

pytestmark = [pytest.mark.slow, pytest.mark.xdist_group("grade_run"),
              pytest.mark.filterwarnings("ignore::Warning")]  # nbgrader's SQLAlchemy warnings

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = sorted((ROOT / "notebooks").glob("0*.ipynb"))
#: nbgrader's comparison: the notebooks whose exercises take every kind of answer (a number with
#: a unit slip, a pair of words, a number per material, an image's width), each run by both
#: graders; the others are asked the same way (tests/test_grade_notebooks.py checks them).
NBGRADER = [p for p in NOTEBOOKS if p.name[:2] in ("01", "04", "06")]
#: Notebooks graded at once (each in its own kernel).
JOBS = 2
#: Answers given with a unit slip: the thickness in um, the slope in mrad.
SLIPS = {"01.1": "1e6 * ", "01.4": "1e3 * "}
STUB = "# YOUR CODE HERE\nraise NotImplementedError()"


def _solved_in_submission(key: str, index: int) -> bool:
    """Whether the mixed submission answers exercise ``key`` (the ``index``-th of its notebook)
    rightly: every other one, but the slips."""
    return index % 2 == 0 and key not in SLIPS


def _submission(release: dict, source: dict, number: str) -> dict:
    """A student's copy of the released notebook: the solution of every other exercise typed
    where the stub is, two with a unit slip, the rest left as released."""
    keys = {solution_code(c): k for k, c in checker_calls(source, number).items()}
    order = [e.key for e in exercises_of(number)]
    solutions = {}
    for cell in source["cells"]:
        meta = cell["metadata"].get("nbgrader") or {}
        if meta.get("solution"):
            text = "".join(cell["source"])
            region = text.split(BEGIN_SOLUTION + "\n")[1].split(END_SOLUTION)[0].splitlines()
            solutions[meta["grade_id"]] = region
    out = json.loads(json.dumps(release))
    for cell in out["cells"]:
        meta = cell["metadata"].get("nbgrader") or {}
        if not meta.get("solution"):
            continue
        lines = []
        for line in solutions[meta["grade_id"]]:
            key = keys[line]
            if key in SLIPS:
                lines.append(line.replace(" = ", " = " + SLIPS[key], 1))
            elif _solved_in_submission(key, order.index(key)):
                lines.append(line)
        text = "".join(cell["source"])
        assert STUB in text
        if lines:
            cell["source"] = text.replace(STUB, "\n".join(lines)).splitlines(keepends=True)
    return out


def _kernels():
    return {p.pid for p in psutil.Process().children(recursive=True)}


def _left(before) -> list:
    """Processes started since ``before`` that are still alive (kernels the grading left)."""
    return [p for p in _kernels() - before if psutil.pid_exists(p)]


@pytest.fixture(scope="session")
def kernels_before():
    return _kernels()


@pytest.fixture(scope="session")
def graded(tmp_path_factory, kernels_before):
    """The notebooks as students get them (through the command line) and their solved copies,
    graded; and how long it took."""
    root = tmp_path_factory.mktemp("grade")
    seconds = {}
    t0 = time.monotonic()
    unsolved = root / "unsolved"
    unsolved.mkdir()
    for p in NOTEBOOKS:
        shutil.copy(p, unsolved / p.name)
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        code = cli.main([*(str(unsolved / p.name) for p in NOTEBOOKS), "--json",
                         "--jobs", str(JOBS)])
    seconds[f"unsolved ({len(NOTEBOOKS)} notebooks, grade command)"] = time.monotonic() - t0
    t0 = time.monotonic()
    solved = grade([write_notebook(solved_copy(read_notebook(p), notebook_number(p)),
                                   root / "solved" / p.name) for p in NOTEBOOKS], jobs=JOBS)
    seconds[f"solved ({len(NOTEBOOKS)} notebooks, grade command)"] = time.monotonic() - t0
    return dict(code=code, unsolved=json.loads(out.getvalue()), solved=solved, seconds=seconds,
                left=_left(kernels_before))


@pytest.fixture(scope="session")
def autograded(tmp_path_factory, kernels_before):
    """nbgrader: each notebook released, a mixed submission autograded; the grade command on
    the same files."""
    pytest.importorskip("nbgrader", reason="nbgrader comes with the test and course extras")
    from nbgrader.api import Gradebook
    from nbgrader.apps import NbGraderAPI
    from traitlets.config import Config

    course = tmp_path_factory.mktemp("course")
    config = Config()
    config.CourseDirectory.root = str(course)
    config.CourseDirectory.db_url = f"sqlite:///{course / 'gradebook.db'}"
    config.Execute.timeout = 600
    api = NbGraderAPI(config=config)
    submissions, scores, notebooks, seconds = [], {}, {}, {}
    with pytest.MonkeyPatch.context() as mp:
        # nbgrader runs `alembic` and its kernels as this Python, with this checkout's afmsmiler
        mp.setenv("PATH", str(Path(sys.executable).parent) + os.pathsep + os.environ["PATH"])
        mp.setenv("PYTHONPATH", os.pathsep.join(
            [str(ROOT)] + [str(Path(p).resolve()) for p in
                           os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]))
        mp.setenv("AFMSMILER_TESTING", "1")
        mp.setenv("MPLBACKEND", "Agg")
        t0 = time.monotonic()
        for p in NBGRADER:
            number, name = notebook_number(p), p.stem
            source = nbgrader_source(read_notebook(p), number)
            write_notebook(source, course / "source" / name / p.name)
            result = api.generate_assignment(name)
            assert result["success"], result.get("log")
            release = read_notebook(course / "release" / name / p.name)
            submission = course / "submitted" / "student" / name / p.name
            write_notebook(_submission(release, source, number), submission)
            submissions.append(submission)
            result = api.autograde(name, "student")
            assert result["success"], result.get("log")
            with Gradebook(config.CourseDirectory.db_url) as gb:
                notebook = gb.find_submission_notebook(name, name, "student")
                scores[name] = {g.name: g.score for g in notebook.grades}
            notebooks[name] = read_notebook(course / "autograded" / "student" / name / p.name)
        seconds[f"nbgrader ({len(NBGRADER)} notebooks, release and autograde)"] = \
            time.monotonic() - t0
    t0 = time.monotonic()
    mixed = grade(submissions, jobs=JOBS)
    seconds[f"the same submissions ({len(NBGRADER)} notebooks, grade command)"] = \
        time.monotonic() - t0
    return dict(mixed=mixed, nbgrader=scores, autograded=notebooks, seconds=seconds,
                left=_left(kernels_before))


def _unsolved_copies_score_zero_with_each_checkers_hint(graded):
    assert graded["code"] == 0
    assert [nb["notebook"] for nb in graded["unsolved"]] == [p.name for p in NOTEBOOKS]
    for nb in graded["unsolved"]:
        number = nb["notebook"][:2]
        assert [e["key"] for e in nb["exercises"]] == [e.key for e in exercises_of(number)]
        assert nb["score"] == 0 and nb["points"] == len(nb["exercises"]) and not nb["notes"]
        for e in nb["exercises"]:
            # the checker's own verdict on None: what to enter and a hint, never "no verdict"
            assert e["score"] == 0 and e["feedback"].startswith("Not yet. "), e
            assert len(e["feedback"]) > 20


def _solved_copies_get_full_marks(graded):
    assert len(graded["solved"]) == len(NOTEBOOKS)
    for nb in graded["solved"]:
        assert nb.score == nb.points == len(exercises_of(nb.notebook)) > 0, nb
        assert not nb.notes, nb.notes  # no cell raised, nothing ran out of time
        assert all(e.feedback.startswith("Correct! ") for e in nb.exercises)


def _nbgrader_autograde_agrees_with_the_grade_command(autograded):
    graded = autograded
    assert len(graded["mixed"]) == len(NBGRADER)
    for nb in graded["mixed"]:
        name = nb.notebook[:-len(".ipynb")]
        exercises = exercises_of(nb.notebook)
        ours = {e.grade_id: s.score for e, s in zip(exercises, nb.exercises, strict=True)}
        assert graded["nbgrader"][name] == ours, name
        # and both are what the submission deserves: neither grader is trivially right
        expected = {e.grade_id: float(_solved_in_submission(e.key, i))
                    for i, e in enumerate(exercises)}
        assert ours == expected, name
        assert 0 < nb.score < nb.points


def _a_units_slip_gets_the_checkers_hint(autograded):
    graded = autograded
    from afmsmiler.exercises.cantilever import thickness_for_spring_constant, tip_slope
    first = graded["mixed"][0]
    feedback = {e.key: e.feedback for e in first.exercises}
    assert feedback["01.1"].startswith("Not yet. ")
    assert "10^6 times the right one" in feedback["01.1"] and "prefix" in feedback["01.1"]
    assert "10^3 times the right one" in feedback["01.4"]
    for value in (thickness_for_spring_constant(), tip_slope()):  # the answer is never shown
        assert f"{value:.4g}" not in feedback["01.1"] + feedback["01.4"]
    # nbgrader's student sees the same hint: the test cell's AssertionError
    errors = {(c["metadata"].get("nbgrader") or {}).get("grade_id"): o
              for c in graded["autograded"]["01_cantilever_mechanics"]["cells"]
              for o in c.get("outputs", []) if o.get("output_type") == "error"}
    assert errors["ex01_1"]["ename"] == "AssertionError"
    assert feedback["01.1"] == errors["ex01_1"]["evalue"]


# One test per fixture: under xdist the tests of this module's group were spread over both
# workers, and each worker graded every notebook again for its share of the tests.
def test_the_grade_command_on_unsolved_and_solved_copies(graded):
    _unsolved_copies_score_zero_with_each_checkers_hint(graded)
    _solved_copies_get_full_marks(graded)
    assert graded["left"] == []  # no kernel outlives the grading
    print("\n".join(f"{what}: {s:.0f} s" for what, s in graded["seconds"].items()))


def test_nbgrader_and_the_grade_command_on_the_same_submissions(autograded):
    _nbgrader_autograde_agrees_with_the_grade_command(autograded)
    _a_units_slip_gets_the_checkers_hint(autograded)
    assert autograded["left"] == []
    print("\n".join(f"{what}: {s:.0f} s" for what, s in autograded["seconds"].items()))


def test_a_run_is_bounded_and_says_why_an_exercise_has_no_verdict(tmp_path, hang_guard):
    from afmsmiler.grade.run import grade_notebook
    cells = ["from afmsmiler.exercises.cantilever import *",
             "ratio = mode_ratio(2)\ncheck_mode_ratio(ratio)",
             "h = not_defined_here\ncheck_thickness_for_spring_constant(h)",
             "import time\ntime.sleep(3600)",  # the run's time limit stops it
             "check_tip_slope(tip_slope())"]    # never reached; 01.3, 01.5 are not asked
    nb = dict(cells=[dict(cell_type="code", execution_count=None, id=f"c{i}", metadata={},
                          outputs=[], source=src) for i, src in enumerate(cells)],
              metadata={}, nbformat=4, nbformat_minor=5)
    path = write_notebook(nb, tmp_path / "01_late.ipynb")
    before = _kernels()
    with hang_guard(150, expected=15):  # a kernel's start and the 10 s limit
        score = grade_notebook(path, timeout=10)
    assert [p for p in _kernels() - before if psutil.pid_exists(p)] == []
    feedback = {e.key: e.feedback for e in score.exercises}
    assert feedback["01.2"].startswith("Correct! ")
    assert feedback["01.1"] == ("No verdict: the cell that calls "
                                "check_thickness_for_spring_constant stopped with NameError: "
                                "name 'not_defined_here' is not defined.")
    assert "no cell ends with a call of check_largest_stress" in feedback["01.3"]
    assert feedback["01.4"] == "No verdict: the notebook ran out of time (10 s) before " \
                               "check_tip_slope."
    assert "no cell ends with a call of check_unseen_lever_calibration" in feedback["01.5"]
    assert (score.score, score.points) == (1, 5)
    assert score.notes == ("ran out of time after 10 s", "1 cell(s) raised an error")
