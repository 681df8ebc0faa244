"""The exercises' cells found in a notebook, and the notebooks made from it (afmsmiler.grade.
notebooks): the solved copy and nbgrader's source version, on a small notebook and on the
course's (no notebook is run here: tests/test_grade_run.py runs them)."""
from pathlib import Path

import pytest

from afmsmiler.grade import cli
from afmsmiler.grade.notebooks import (BEGIN_SOLUTION, END_SOLUTION, cell_errors, checker_calls,
                                       nbgrader_source, notebook_number, read_notebook,
                                       solution_code, solved_copy, write_notebook)

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = sorted((ROOT / "notebooks").glob("0*.ipynb"))


def _nb(*sources):
    cells = [dict(cell_type="markdown", id="m0", metadata={}, source=["# 01\n", "text"])]
    cells += [dict(cell_type="code", execution_count=None, id=f"c{i}", metadata={}, outputs=[],
                   source=src.splitlines(keepends=True)) for i, src in enumerate(sources, 1)]
    return dict(cells=cells, metadata={}, nbformat=4, nbformat_minor=5)


#: A notebook 01 in small: its five exercises asked the ways the course's notebooks ask them.
SMALL = _nb("from afmsmiler.exercises.cantilever import *",
            "h = None  # in m\ncheck_thickness_for_spring_constant(h, target_k=0.1)",
            "check_mode_ratio(6.0)   # a wrong first try, shown on purpose",
            "ratio = None\n",
            "check_mode_ratio(ratio, mode=2)",
            "location, top_surface = None, None\ntheta = None\nx = 1\n"
            "check_largest_stress(location, top_surface,\n                     force=100e-9)",
            "check_tip_slope(theta, force=100e-9)  # a comment",
            "k_lever = None\ncheck_unseen_lever_calibration(k_lever)",
            "%matplotlib inline")


def test_checker_cells_and_answers_are_found():
    calls = checker_calls(SMALL, "01")
    assert {k: c.cell for k, c in calls.items()} == {"01.1": 2, "01.2": 5, "01.3": 6, "01.4": 7,
                                                        "01.5": 8}
    assert calls["01.3"].answers == ("location", "top_surface")
    assert calls["01.3"].givens == (("force", "100e-9"),)
    assert solution_code(calls["01.1"]) == \
        "h = check_thickness_for_spring_constant.solution(target_k=0.1)"
    assert solution_code(calls["01.3"]) == \
        "location, top_surface = check_largest_stress.solution(force=100e-9)"
    # a literal answer cannot be set to the solution; a call wrapped in .require() is found
    odd = _nb("check_mode_ratio(6.0, mode=2).require()", "check_tip_slope()")
    calls = checker_calls(odd, "01")
    assert calls["01.2"].answers == (None,) and calls["01.4"].answers == (None,)
    with pytest.raises(ValueError, match="as a variable"):
        solution_code(calls["01.2"])


def test_solved_copy_sets_each_answer_before_its_check():
    out = solved_copy(SMALL, "01")
    src = ["".join(c["source"]) for c in out["cells"]]
    assert src[2] == ("h = None  # in m\n"
                      "h = check_thickness_for_spring_constant.solution(target_k=0.1)\n"
                      "check_thickness_for_spring_constant(h, target_k=0.1)")
    assert src[3] == "check_mode_ratio(6.0)   # a wrong first try, shown on purpose"
    assert src[4] == "ratio = None\nratio = check_mode_ratio.solution(mode=2)"
    assert src[6] == ("location, top_surface = None, None\ntheta = None\nx = 1\n"
                      "location, top_surface = check_largest_stress.solution(force=100e-9)\n"
                      "theta = check_tip_slope.solution(force=100e-9)\n"
                      "check_largest_stress(location, top_surface,\n"
                      "                     force=100e-9)")
    assert src[7] == "check_tip_slope(theta, force=100e-9)  # a comment"
    assert src[8] == ("k_lever = None\nk_lever = check_unseen_lever_calibration.solution()\n"
                      "check_unseen_lever_calibration(k_lever)")
    assert "".join(SMALL["cells"][2]["source"]) == "h = None  # in m\n" \
        "check_thickness_for_spring_constant(h, target_k=0.1)"  # the argument is not changed
    # what the copy says runs: the solutions pass (the first try of 01.2 does not)
    from afmsmiler.exercises.registry import recording
    with recording() as verdicts:
        namespace = {}
        for cell in out["cells"][1:-1]:
            exec("".join(cell["source"]), namespace)
    assert [(v.exercise, v.passed) for v in verdicts] == [
        ("01.1", True), ("01.2", False), ("01.2", True), ("01.3", True), ("01.4", True),
        ("01.5", True)]


def test_nbgrader_source_has_solution_and_test_cells():
    out = nbgrader_source(SMALL, "01")
    cells = [("".join(c["source"]), c.get("id"), c["metadata"].get("nbgrader"))
             for c in out["cells"]]
    src = [c[0] for c in cells]
    assert src[2] == ("h = None  # in m\n" + BEGIN_SOLUTION + "\n"
                      "h = check_thickness_for_spring_constant.solution(target_k=0.1)\n"
                      + END_SOLUTION)
    assert cells[2][1:] == ("c2", dict(grade=False, grade_id="answer01_1", locked=False,
                                       schema_version=3, solution=True, task=False))
    assert cells[3][0] == "check_thickness_for_spring_constant(h, target_k=0.1).require()"
    assert cells[3][1:] == ("c2-test", dict(grade=True, grade_id="ex01_1", locked=True,
                                            points=1.0, schema_version=3, solution=False,
                                            task=False))
    assert cells[4] == ("check_mode_ratio(6.0)   # a wrong first try, shown on purpose", "c3",
                        None)
    assert src[5].startswith("ratio = None\n" + BEGIN_SOLUTION)
    assert cells[6] == ("check_mode_ratio(ratio, mode=2).require()", "c5",
                        dict(grade=True, grade_id="ex01_2", locked=True, points=1.0,
                             schema_version=3, solution=False, task=False))
    assert cells[7][2]["grade_id"] == "answer01_3" and "theta = check_tip_slope" in src[7]
    assert src[8] == "check_largest_stress(location, top_surface,\n" \
                     "                     force=100e-9).require()"
    assert src[9] == "check_tip_slope(theta, force=100e-9).require()"
    assert src[10].startswith("k_lever = None\n" + BEGIN_SOLUTION)
    assert src[11] == "check_unseen_lever_calibration(k_lever).require()"
    assert src[12] == "%matplotlib inline" and len(cells) == 13
    ids = [c[1] for c in cells]
    assert len(set(ids)) == len(ids)
    grade_ids = [c[2]["grade_id"] for c in cells if c[2]]
    assert len(set(grade_ids)) == len(grade_ids) == 9  # 01.3 and 01.4 answered in one cell


@pytest.mark.parametrize("sources, words", [
    (("check_mode_ratio(ratio)",), "must hold a checker cell"),   # 01.1, 01.3, 01.4 missing
    (("check_thickness_for_spring_constant(h)", "check_mode_ratio(r)",
      "check_largest_stress(a, b)", "t = None\ncheck_tip_slope(t)", "k = None\ncheck_unseen_lever_calibration(k)"),
     "must set h = None"),
    (("h = None\ncheck_thickness_for_spring_constant(h)", "r = 1\ncheck_mode_ratio(r)",
      "a = b = None\ncheck_largest_stress(a, b)", "t = None\ncheck_tip_slope(t)", "k = None\ncheck_unseen_lever_calibration(k)"),
     "must set r = None"),
    (("h = None\ncheck_thickness_for_spring_constant(h)", "check_mode_ratio(0.5)",
      "check_largest_stress()", "t = None\ncheck_tip_slope(t)", "k = None\ncheck_unseen_lever_calibration(k)"),
     "as a variable"),
])
def test_a_notebook_that_cannot_be_solved_says_why(sources, words):
    for make in (solved_copy, nbgrader_source):
        with pytest.raises(ValueError, match=words):
            make(_nb(*sources), "01")


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_course_notebooks_make_both_versions(path):
    nb = read_notebook(path)
    number = notebook_number(path)
    calls = checker_calls(nb, number)
    solved = solved_copy(nb, number)
    source = nbgrader_source(nb, number)
    # every answer line of the solved copy is one of nbgrader's solution lines
    solved_lines = {line for c in solved["cells"] for line in "".join(c["source"]).splitlines()
                    if ".solution(" in line}
    solution_lines = {line for c in source["cells"] if (c["metadata"].get("nbgrader") or {})
                      .get("solution") for line in "".join(c["source"]).splitlines()
                      if ".solution(" in line}
    assert solved_lines == solution_lines and len(solved_lines) == len(calls)
    tests = [c for c in source["cells"] if (c["metadata"].get("nbgrader") or {}).get("grade")]
    assert [c["metadata"]["nbgrader"]["grade_id"] for c in tests] == \
        [c.exercise.grade_id for c in sorted(calls.values(), key=lambda c: c.cell)]
    assert all("".join(c["source"]).endswith(".require()") for c in tests)
    # the markdown and the other code cells are kept as they are
    plain = [c for c in nb["cells"] if c["cell_type"] == "markdown"]
    assert plain == [c for c in source["cells"] if c["cell_type"] == "markdown"]


def test_cell_errors():
    nb = _nb("1", "x")
    nb["cells"][2]["outputs"] = [dict(output_type="stream", name="stdout", text="a"),
                                 dict(output_type="error", ename="NameError", evalue="x",
                                      traceback=[])]
    assert cell_errors(nb) == {2: "NameError: x"}
    with pytest.raises(TypeError, match="nb must be"):
        cell_errors([])


def test_notebook_number_and_files(tmp_path):
    assert notebook_number("a/01_cantilever_mechanics.ipynb") == "01"
    assert notebook_number(Path("07.ipynb")) == "07"
    assert notebook_number("my_01.ipynb") is None and notebook_number("100_x.ipynb") is None
    path = write_notebook(SMALL, tmp_path / "sub" / "01_x.ipynb")
    assert read_notebook(path) == SMALL
    assert path.read_text(encoding="utf-8").endswith("}\n")
    (tmp_path / "bad.ipynb").write_text("{", encoding="utf-8")
    with pytest.raises(ValueError, match="notebook"):
        read_notebook(tmp_path / "bad.ipynb")
    (tmp_path / "v3.ipynb").write_text('{"nbformat": 3, "worksheets": []}', encoding="utf-8")
    with pytest.raises(ValueError, match="nbformat 4"):
        read_notebook(tmp_path / "v3.ipynb")


def test_command_writes_both_versions(tmp_path, capsys):
    paths = [str(p) for p in NOTEBOOKS[:2]]
    assert cli.main(["--nbgrader-source", str(tmp_path / "source"), *paths]) == 0
    assert cli.main(["--solved", str(tmp_path / "solved"), *paths]) == 0
    for p in NOTEBOOKS[:2]:
        assert read_notebook(tmp_path / "source" / p.stem / p.name)["cells"]
        assert read_notebook(tmp_path / "solved" / p.name)["cells"]
    assert capsys.readouterr().out.count(".ipynb") == 4
    assert cli.main([str(tmp_path / "missing.ipynb")]) == 2
    write_notebook(SMALL, tmp_path / "x.ipynb")
    assert cli.main(["--solved", str(tmp_path), str(tmp_path / "x.ipynb")]) == 2
    assert "not a course notebook" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        cli.main(["--timeout", "-1", paths[0]])
