"""The course's exercises: which checker grades which exercise, what it asks, its solution.

Each checker of :mod:`afmsmiler.exercises` is registered with :func:`exercise`, which gives it

* a key, ``"NN.M"`` (notebook NN's exercise M, as the notebook numbers it, with a letter for
  its parts: ``"04.1a"``), a title (the notebook's) and points;
* its answers: the names of the checker's parameters the student answers (the others are the
  exercise's givens, which the notebook passes);
* its solution: a function of the same givens (by the same names) that computes the answer with
  the library's models, as the checker computes its reference; never a number typed by hand.

The registered checker returns its Feedback with the exercise's key
(:attr:`~afmsmiler.exercises.Feedback.exercise`) and records it: in this process for
:func:`recording`, and as a JSON line in the file that the environment variable
:data:`GRADE_LOG` names, which ``python -m afmsmiler.grade`` sets for the kernel of the notebook it
grades. The checkers are so the single source of truth of the grades: the grade command scores
their verdicts, nbgrader's test cells call them (:meth:`~afmsmiler.exercises.Feedback.require`).
The checker is reached as ``check_x``, its solution as ``check_x.solution`` and its entry as
``check_x.exercise``.
"""
from __future__ import annotations

import functools
import importlib
import inspect
import json
import math
import os
import re
from collections.abc import Callable
from contextlib import contextmanager
from dataclasses import dataclass, replace

from . import Feedback

__all__ = ["GRADE_LOG", "MODULES", "EXERCISES", "Exercise", "exercise", "exercises_of",
           "all_exercises", "recording"]

#: The environment variable naming the file to which every registered checker appends its
#: verdict, one JSON object per line: ``{"exercise": key, "passed": bool, "message": str}``.
GRADE_LOG = "AFMSMILER_GRADE_LOG"

#: The modules of checkers, in the course's order: notebook NN's checkers are in the NN-th.
MODULES = ("cantilever", "transducers", "controller", "contact", "instrument", "imaging", "modes",
           "hardware")

#: The registered exercises by key (filled as the checker modules are imported; see
#: :func:`all_exercises`).
EXERCISES: dict[str, Exercise] = {}

_KEY = re.compile(r"^(0[1-9])\.([1-9][a-z]?)$")
_IDENTIFIER = re.compile(r"^[A-Za-z_]\w*$")
_recorders: list[list[Feedback]] = []


@dataclass(frozen=True)
class Exercise:
    """An exercise of a notebook, graded by its checker.

    Attributes
    ----------
    key : str
        ``"NN.M"``: notebook NN's exercise M (``"04.1a"`` for part a).
    title : str
        Its title in the notebook.
    checker : callable
        The registered checker (it records its verdicts).
    answers : tuple of str
        The checker's parameters that the student answers, in order.
    solution : callable
        Takes the checker's givens (its other parameters) by name, as the notebook passes them
        to the checker, and returns the answer (a tuple of them, in the order of ``answers``,
        when there are several).
    points : float
        What the exercise is worth.
    """

    key: str
    title: str
    checker: Callable
    answers: tuple[str, ...]
    solution: Callable
    points: float = 1.0

    @property
    def notebook(self) -> str:
        """The notebook's number, ``"01"`` to ``"09"``."""
        return self.key.split(".")[0]

    @property
    def grade_id(self) -> str:
        """The exercise's name in nbgrader (its test cell's ``grade_id``): ``"ex01_1"``."""
        return "ex" + self.key.replace(".", "_")


def exercise(key: str, title: str, *, answers, solution: Callable,
             points: float = 1.0) -> Callable:
    """Register the decorated checker as the exercise ``key`` (a decorator).

    Parameters
    ----------
    key : str
        ``"NN.M"`` (NN 01-09, M 1-9 and an optional letter of a part), not yet registered.
    title : str
        The exercise's title in the notebook, not empty.
    answers : tuple of str
        Names of the checker's parameters the student answers (at least one).
    solution : callable
        The answer from the model, as a function of the checker's givens: each of its
        parameters is a parameter of the checker that is not an answer, or has a default.
    points : float
        What the exercise is worth, in (0, 100].

    Returns
    -------
    callable
        The decorator: it returns the checker wrapped so that each verdict carries ``key`` and
        is recorded (:func:`recording`, :data:`GRADE_LOG`), with ``.exercise`` (the
        :class:`Exercise`) and ``.solution``.

    Raises
    ------
    ValueError
        If the key, the title, the answers, the solution's parameters or the points are not as
        above (when the checker is decorated, that is when its module is imported).
    """
    if not isinstance(key, str) or not _KEY.match(key):
        raise ValueError(f"key must be 'NN.M' (NN 01-09, M 1-9 and a letter of a part), "
                         f"got {key!r}")
    if not isinstance(title, str) or not title.strip():
        raise ValueError(f"title must be a non-empty string, got {title!r}")
    if isinstance(answers, str) or not isinstance(answers, (tuple, list)) or not answers \
            or not all(isinstance(a, str) and _IDENTIFIER.match(a) for a in answers):
        raise ValueError(f"answers must be a tuple of parameter names, got {answers!r}")
    if not callable(solution):
        raise ValueError(f"solution must be callable, got {solution!r}")
    if isinstance(points, bool) or not isinstance(points, (int, float)) \
            or not (math.isfinite(points) and 0 < points <= 100):
        raise ValueError(f"points must be in (0, 100], got {points!r}")
    answers = tuple(answers)

    def register(checker: Callable) -> Callable:
        params = inspect.signature(checker).parameters
        missing = [a for a in answers if a not in params]
        if missing:
            raise ValueError(f"answers of {key} must be parameters of {checker.__name__}, got "
                             f"{missing}")
        wrong = [p.name for p in inspect.signature(solution).parameters.values()
                 if p.name in answers or (p.name not in params and p.default is p.empty)]
        if wrong:
            raise ValueError(f"solution of {key} must take {checker.__name__}'s givens (and "
                             f"settings of its own with defaults), got {wrong}")
        if key in EXERCISES and EXERCISES[key].checker.__qualname__ != checker.__qualname__:
            raise ValueError(f"key {key} is already {EXERCISES[key].checker.__qualname__}")

        @functools.wraps(checker)
        def checked(*args, **kwargs):
            verdict = replace(checker(*args, **kwargs), exercise=key)
            _record(verdict)
            return verdict

        entry = Exercise(key, title.strip(), checked, answers, solution, float(points))
        checked.exercise = entry
        checked.solution = solution
        EXERCISES[key] = entry
        return checked

    return register


def _record(verdict: Feedback) -> None:
    """Hand a verdict to the active :func:`recording` lists and to the :data:`GRADE_LOG` file."""
    for verdicts in _recorders:
        verdicts.append(verdict)
    path = os.environ.get(GRADE_LOG)
    if path:
        line = json.dumps(dict(exercise=verdict.exercise, passed=bool(verdict.passed),
                               message=str(verdict.message)), ensure_ascii=False)
        with open(path, "a", encoding="utf-8") as log:
            log.write(line + "\n")


@contextmanager
def recording():
    """Collect the verdicts of the registered checkers called inside the ``with`` block.

    Returns
    -------
    context manager
        Yields a list that receives each verdict (a Feedback with its exercise's key) in the
        order the checkers gave them.

    Examples
    --------
    >>> from afmsmiler.exercises.cantilever import check_mode_ratio
    >>> with recording() as verdicts:
    ...     _ = check_mode_ratio(None)
    >>> [(v.exercise, v.passed) for v in verdicts]
    [('01.2', False)]
    """
    verdicts: list[Feedback] = []
    _recorders.append(verdicts)
    try:
        yield verdicts
    finally:
        _recorders.remove(verdicts)


def all_exercises() -> dict[str, Exercise]:
    """Every exercise of the course, by key in the course's order (imports :data:`MODULES`).

    Returns
    -------
    dict
        Key -> :class:`Exercise`.
    """
    for name in MODULES:
        importlib.import_module(f"{__package__}.{name}")
    return {k: EXERCISES[k] for k in sorted(EXERCISES, key=_order)}


def _order(key: str) -> tuple:
    notebook, number = key.split(".")
    return notebook, int(number.rstrip("abcdefghijklmnopqrstuvwxyz")), number


def exercises_of(notebook: str) -> list[Exercise]:
    """The exercises of one notebook, in its order.

    Parameters
    ----------
    notebook : str
        The notebook's number (``"01"``) or a name or path that starts with it
        (``"01_cantilever_mechanics.ipynb"``).

    Returns
    -------
    list of Exercise
        Empty for a notebook without exercises.

    Raises
    ------
    ValueError
        If ``notebook`` does not start with a notebook's two-digit number.
    """
    if not isinstance(notebook, (str, os.PathLike)):
        raise ValueError(f"notebook must be a number such as '01' or a file name that starts "
                         f"with it, got {notebook!r}")
    match = re.match(r"(\d\d)(?:_|\.|$)", os.path.basename(os.fspath(notebook)))
    if match is None:
        raise ValueError(f"notebook must be a number such as '01' or a file name that starts "
                         f"with it, got {notebook!r}")
    return [e for e in all_exercises().values() if e.notebook == match.group(1)]
