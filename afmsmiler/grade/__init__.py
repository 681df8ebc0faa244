"""Grade the course's exercises: self-study and small classes, and nbgrader for a course.

**Students (self-study).** Do the exercises in a notebook (put each answer where it says
``None``), save it, and run::

    python -m afmsmiler.grade notebooks/01_cantilever_mechanics.ipynb [more notebooks ...]

Each notebook runs from top to bottom in a fresh kernel, headless (no browser; animations and
scans short, as under test), for at most ``--timeout`` seconds. The grader prints, for each
exercise, its score and the checker's feedback (the same hint the notebook shows: a unit, a
sign, what to look at; never the answer), each notebook's score and the total. An exercise
counts when its checker's *last* verdict in the notebook is "Correct!"; one whose checker cell
raised or never ran scores 0 and says why. A file keeps its course name's number (``01_``...),
so that the grader knows which exercises it holds. ``--json`` prints the scores as JSON. The exit
code is 0 whatever the score.

**Instructors (nbgrader).** The checkers of :mod:`afmsmiler.exercises` are the single source of
truth: the grade command scores their verdicts, and nbgrader's autograder tests call them.
``python -m afmsmiler.grade --nbgrader-source COURSE/source notebooks/*.ipynb`` (``make
assignments``) writes each notebook as nbgrader's source assignment
``COURSE/source/NN_name/NN_name.ipynb``: the cells where students answer become solution cells
(the solution, computed by the exercise's ``solution`` function with the notebook's givens,
between ``### BEGIN SOLUTION`` and ``### END SOLUTION``), each checker call a locked autograder
test cell worth the exercise's points (1 each) that raises AssertionError with the checker's hint
on a wrong answer. Then, in ``COURSE``, the usual nbgrader steps: ``nbgrader generate_assignment
NN_name`` (the students' version in ``release/``), collect the submissions into
``submitted/STUDENT/NN_name/``, ``nbgrader autograde NN_name`` and ``nbgrader
generate_feedback``. Autograde with ``AFMSMILER_TESTING=1`` in the environment and
``Execute.timeout = 600`` (s per cell): ``make assignments`` writes a ``COURSE/nbgrader_config.py``
that sets both. The grade command gives a submission the same scores as nbgrader's autograder
(tests/test_grade_run.py checks it on notebooks 01-07). ``--solved DIR`` writes the notebooks
with every answer solved (the grade command gives them full marks).

The parts: :mod:`~afmsmiler.grade.notebooks` (the exercises' cells, the solved and nbgrader
notebooks; pure), :mod:`~afmsmiler.grade.scoring` (scores from verdicts; pure),
:mod:`~afmsmiler.grade.run` (runs a notebook with nbclient, from the ``lab`` or ``test`` extra).
"""
from .notebooks import (CheckerCall, checker_calls, nbgrader_source, notebook_number,
                        read_notebook, solved_copy, write_notebook)
from .run import DEFAULT_TIMEOUT, Run, grade, grade_notebook, run_notebook
from .scoring import ExerciseScore, NotebookScore, read_verdicts, report, score_notebook

__all__ = ["CheckerCall", "checker_calls", "nbgrader_source", "notebook_number", "read_notebook",
           "solved_copy", "write_notebook", "DEFAULT_TIMEOUT", "Run", "grade", "grade_notebook",
           "run_notebook", "ExerciseScore", "NotebookScore", "read_verdicts", "report",
           "score_notebook"]
