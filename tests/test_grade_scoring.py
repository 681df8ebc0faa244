"""Scores from verdicts (afmsmiler.grade.scoring): the last verdict of an exercise counts, an
exercise without one scores 0 and says why, the report and the JSON carry every feedback."""
import json

import pytest

from afmsmiler.exercises import Feedback
from afmsmiler.exercises.registry import exercises_of
from afmsmiler.grade.scoring import (MAX_VERDICTS, NotebookScore, read_verdicts, report,
                                     score_notebook)

EX = exercises_of("02")


def _v(key, passed, message="m"):
    return Feedback(passed, message, key)


def test_the_last_verdict_of_each_exercise_counts():
    verdicts = [_v("02.1", True), _v("02.1", False, "then wrong"),   # a right answer undone
                _v("02.2", False, "first try"), _v("02.2", True, "fixed"),
                _v("01.1", True), _v(None, True)]                    # other notebooks: ignored
    s = score_notebook("02_probe_transducers.ipynb", EX, verdicts,
                       reasons={"02.3": "its cell stopped with NameError: x", "02.2": "unused"})
    assert [(e.key, e.score) for e in s.exercises] == [("02.1", 0), ("02.2", 1), ("02.3", 0),
                                                       ("02.4", 0)]
    assert s.exercises[0].feedback == "Not yet. then wrong"
    assert s.exercises[1].feedback == "Correct! fixed" and s.exercises[1].passed
    assert s.exercises[2].feedback == "No verdict: its cell stopped with NameError: x."
    assert s.exercises[3].feedback == "No verdict: its checker cell did not run."
    assert (s.score, s.points) == (1, 4)


def test_points_weigh_the_exercises():
    from dataclasses import replace
    heavy = [replace(EX[0], points=3.0), EX[1]]
    s = score_notebook("nb", heavy, [_v("02.1", True), _v("02.2", True)])
    assert (s.score, s.points) == (4, 4)
    s = score_notebook("nb", heavy, [_v("02.2", True)])
    assert (s.score, s.points) == (1, 4)


def test_report_and_json_carry_every_feedback():
    a = score_notebook("02.ipynb", EX, [_v("02.1", True, "ok"), _v("02.4", False, "a hint")],
                       notes=["1 cell(s) raised an error"])
    b = score_notebook("empty.ipynb", [], [])
    text = report([a, b])
    assert text.splitlines()[0] == "02.ipynb: 1/4"
    assert "(1 cell(s) raised an error)" in text and "Correct! ok" in text
    assert "Not yet. a hint" in text and text.count("No verdict") == 2
    assert "empty.ipynb: 0/0" in text and text.endswith("total: 1/4 (25%)")
    assert report([b]).endswith("total: 0/0")
    data = json.loads(json.dumps(a.as_dict()))
    assert data["score"] == 1 and data["points"] == 4 and data["notes"]
    assert [e["passed"] for e in data["exercises"]] == [True, False, False, False]
    assert data["exercises"][3]["feedback"] == "Not yet. a hint"


def test_read_verdicts():
    text = "\n".join(json.dumps(dict(exercise=k, passed=p, message=m))
                     for k, p, m in (("02.1", True, "é ok"), ("02.2", False, "no"))) + "\n\n"
    assert read_verdicts(text) == [_v("02.1", True, "é ok"), _v("02.2", False, "no")]
    assert read_verdicts("") == []
    for bad in ("{not json\n", '{"exercise": "02.1"}\n', "[1, 2]\n", "{not json\n{}"):
        with pytest.raises(ValueError, match="line 1"):
            read_verdicts(bad)
    # a kernel stopped while it wrote its last verdict: the line it never finished is left out
    assert read_verdicts(text + '{"exercise": "02.3", "pas') == read_verdicts(text)
    with pytest.raises(TypeError, match="text must be"):
        read_verdicts(b"{}")
    many = (json.dumps(dict(exercise="02.1", passed=True, message="")) + "\n") * (MAX_VERDICTS + 5)
    assert len(read_verdicts(many)) == MAX_VERDICTS


def test_wrong_inputs_are_named():
    with pytest.raises(TypeError, match="exercises must be"):
        score_notebook("nb", ["02.1"], [])
    with pytest.raises(TypeError, match="verdicts must be"):
        score_notebook("nb", EX, [{"exercise": "02.1"}])
    with pytest.raises(TypeError, match="scores must be"):
        report([{"score": 1}])
    assert isinstance(score_notebook("nb", EX, []), NotebookScore)
