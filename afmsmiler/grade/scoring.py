"""Scores from the checkers' verdicts (pure: no notebook is run here).

A graded notebook's kernel leaves the verdicts of the registered checkers, in the order they
were given (:mod:`afmsmiler.exercises.registry`). An exercise's score is its points when its
*last* verdict passed (a notebook may show a wrong first try before the student's answer, and a
student may check an answer several times), else 0; an exercise without a verdict scores 0 and
says why (its cell stopped with an error, the notebook ran out of time, ...). The feedback is
the checker's own message: its hint, never the answer.
"""
from __future__ import annotations

import json
from dataclasses import dataclass

from ..exercises import Feedback
from ..exercises.registry import Exercise

__all__ = ["ExerciseScore", "NotebookScore", "read_verdicts", "score_notebook", "report",
           "MAX_VERDICTS"]

#: The most verdicts read from one notebook's log (a checker called in a loop stops counting).
MAX_VERDICTS = 100_000


@dataclass(frozen=True)
class ExerciseScore:
    """One exercise's score.

    Attributes
    ----------
    key : str
        The exercise's key (``"01.1"``).
    title : str
        Its title.
    points : float
        What it is worth.
    score : float
        ``points`` if passed, else 0.
    feedback : str
        The checker's last verdict as the student reads it ("Correct! ..." or "Not yet. ..."),
        or why there is none.
    """

    key: str
    title: str
    points: float
    score: float
    feedback: str

    @property
    def passed(self) -> bool:
        """Whether the exercise earned its points."""
        return self.score > 0


@dataclass(frozen=True)
class NotebookScore:
    """A notebook's scores, exercise by exercise.

    Attributes
    ----------
    notebook : str
        The notebook's name.
    exercises : tuple of ExerciseScore
        In the notebook's order.
    notes : tuple of str
        What the grader saw besides (the notebook ran out of time, a cell raised).
    """

    notebook: str
    exercises: tuple[ExerciseScore, ...]
    notes: tuple[str, ...] = ()

    @property
    def score(self) -> float:
        """The points earned."""
        return sum(e.score for e in self.exercises)

    @property
    def points(self) -> float:
        """The points there are."""
        return sum(e.points for e in self.exercises)

    def as_dict(self) -> dict:
        """The scores as plain data (what ``--json`` prints).

        Returns
        -------
        dict
            ``notebook``, ``score``, ``points``, ``notes`` and ``exercises`` (a list of dicts with
            ``key``, ``title``, ``points``, ``score``, ``passed`` and ``feedback``).
        """
        return dict(notebook=self.notebook, score=self.score, points=self.points,
                    notes=list(self.notes),
                    exercises=[dict(key=e.key, title=e.title, points=e.points, score=e.score,
                                    passed=e.passed, feedback=e.feedback)
                               for e in self.exercises])


def read_verdicts(text: str) -> list[Feedback]:
    """The verdicts of a grade log: one JSON object per line, as the checkers write them.

    Parameters
    ----------
    text : str
        The log's content (:data:`~afmsmiler.exercises.registry.GRADE_LOG`).

    Returns
    -------
    list of Feedback
        In the order they were given, at most :data:`MAX_VERDICTS` (the first ones); a last
        line cut short (no newline: the kernel was stopped while writing it) is left out.

    Raises
    ------
    ValueError
        If a whole line is not a verdict (JSON with ``exercise``, ``passed`` and ``message``).
    """
    if not isinstance(text, str):
        raise TypeError(f"text must be a str, got {type(text).__name__}")
    verdicts = []
    lines = text.splitlines()
    for number, line in enumerate(lines, 1):
        if len(verdicts) >= MAX_VERDICTS:
            break
        if not line.strip():
            continue
        try:
            item = json.loads(line)
            verdicts.append(Feedback(bool(item["passed"]), str(item["message"]),
                                     str(item["exercise"])))
        except (json.JSONDecodeError, KeyError, TypeError) as err:
            if number == len(lines) and not text.endswith("\n"):
                break  # a kernel stopped while writing its last verdict: it never finished
            raise ValueError(f"text must hold one verdict per line, got line {number}: "
                             f"{line[:80]!r} ({err})") from None
    return verdicts


def score_notebook(notebook: str, exercises, verdicts, *, reasons=None,
                   notes=()) -> NotebookScore:
    """Score a notebook's exercises from the verdicts its run left.

    Parameters
    ----------
    notebook : str
        The notebook's name (for the report).
    exercises : sequence of Exercise
        The notebook's exercises (:func:`~afmsmiler.exercises.registry.exercises_of`).
    verdicts : sequence of Feedback
        The verdicts in the order given; those of other exercises are ignored.
    reasons : dict, optional
        Exercise key -> why it has no verdict (used only where it has none).
    notes : sequence of str
        Passed on to the result.

    Returns
    -------
    NotebookScore
    """
    exercises = tuple(exercises)
    if not all(isinstance(e, Exercise) for e in exercises):
        raise TypeError(f"exercises must be Exercise entries, got {exercises!r}"[:200])
    last: dict[str, Feedback] = {}
    for verdict in verdicts:
        if not isinstance(verdict, Feedback):
            raise TypeError(f"verdicts must be Feedback, got {verdict!r}"[:200])
        last[verdict.exercise] = verdict
    reasons = dict(reasons or {})
    scores = []
    for e in exercises:
        verdict = last.get(e.key)
        if verdict is None:
            why = reasons.get(e.key, "its checker cell did not run")
            scores.append(ExerciseScore(e.key, e.title, e.points, 0.0, f"No verdict: {why}."))
        else:
            scores.append(ExerciseScore(e.key, e.title, e.points,
                                        e.points if verdict.passed else 0.0, str(verdict)))
    return NotebookScore(str(notebook), tuple(scores), tuple(str(n) for n in notes))


def _points(x: float) -> str:
    return f"{x:g}"


def report(scores) -> str:
    """The scores as text: each exercise with its score and feedback, each notebook's and the
    total.

    Parameters
    ----------
    scores : sequence of NotebookScore

    Returns
    -------
    str
    """
    scores = list(scores)
    if not all(isinstance(s, NotebookScore) for s in scores):
        raise TypeError("scores must be NotebookScore results")
    out = []
    for nb in scores:
        out.append(f"{nb.notebook}: {_points(nb.score)}/{_points(nb.points)}")
        for note in nb.notes:
            out.append(f"  ({note})")
        for e in nb.exercises:
            out.append(f"  {e.key:<6} {_points(e.score)}/{_points(e.points)}  {e.title}")
            out.append(f"         {e.feedback}")
        out.append("")
    total, points = sum(s.score for s in scores), sum(s.points for s in scores)
    share = f" ({100 * total / points:.0f}%)" if points else ""
    out.append(f"total: {_points(total)}/{_points(points)}{share}")
    return "\n".join(out)
