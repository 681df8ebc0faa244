"""Where a notebook's exercises are, and the notebooks made from it (pure: JSON in, JSON out).

A course notebook asks each exercise in a *checker cell*: a code cell whose last statement calls
the exercise's checker (``check_tip_slope(theta, force=100e-9, ...)``), the answers passed as
variables that an earlier line sets to None (``theta = None  # theta(L) in rad``), in the same
cell or an earlier one. The checker's other arguments are the exercise's givens. When a notebook
calls a checker in several cells (a wrong first try shown on purpose, then the student's turn),
the last is the checker cell. Nothing else marks them: no tag or metadata.

From that this module makes

* :func:`solved_copy`: the notebook with each answer computed by the exercise's solution, with
  the notebook's own givens (``theta = check_tip_slope.solution(force=100e-9, ...)``), placed
  just before the cell's checker call or at the end of the answer cell;
* :func:`nbgrader_source`: nbgrader's source version: each answer cell a solution cell with the
  solution between ``### BEGIN SOLUTION`` and ``### END SOLUTION``, each checker call an
  autograder test cell of the exercise's points (``check_...(...).require()``: it raises
  AssertionError with the checker's hint on a wrong answer).

Notebooks are the nbformat 4 JSON as :func:`json.load` gives it; the functions never change
their argument.
"""
from __future__ import annotations

import ast
import copy
import inspect
import json
import os
import re
from dataclasses import dataclass
from pathlib import Path

from ..exercises.registry import Exercise, exercises_of

__all__ = ["CheckerCall", "notebook_number", "read_notebook", "write_notebook", "cell_source",
           "checker_calls", "cell_errors", "solution_code", "solved_copy", "nbgrader_source",
           "SCHEMA_VERSION", "BEGIN_SOLUTION", "END_SOLUTION"]

#: nbgrader's cell metadata schema that :func:`nbgrader_source` writes.
SCHEMA_VERSION = 3
#: The markers of a solution region in nbgrader's source notebooks.
BEGIN_SOLUTION = "### BEGIN SOLUTION"
END_SOLUTION = "### END SOLUTION"
#: The largest notebook file read, in bytes (the course's are about 100 kB without outputs).
MAX_BYTES = 64 * 2**20


@dataclass(frozen=True)
class CheckerCall:
    """An exercise's checker cell in a notebook.

    Attributes
    ----------
    exercise : Exercise
        The exercise.
    cell : int
        The index of its checker cell in the notebook's cells.
    function : str
        The checker as the call names it (``"check_tip_slope"``, ``"ex.check_fast_scan"``).
    answers : tuple
        For each of the exercise's answers, the variable the call passes, or None where it
        passes something else (or nothing).
    givens : tuple of (str, str)
        The call's other arguments: (parameter, source text).
    """

    exercise: Exercise
    cell: int
    function: str
    answers: tuple[str | None, ...]
    givens: tuple[tuple[str, str], ...]


def notebook_number(path) -> str | None:
    """The course notebook's two-digit number a file name starts with (``"01"``), or None.

    Parameters
    ----------
    path : str or os.PathLike
        A notebook's path or name.

    Returns
    -------
    str or None
    """
    if not isinstance(path, (str, os.PathLike)):
        raise TypeError(f"path must be a path, got {path!r}")
    match = re.match(r"(\d\d)(?:_|\.|$)", os.path.basename(os.fspath(path)))
    return match.group(1) if match else None


def read_notebook(path) -> dict:
    """A notebook file as its nbformat 4 JSON.

    Parameters
    ----------
    path : str or os.PathLike
        An ``.ipynb`` file of at most :data:`MAX_BYTES`.

    Returns
    -------
    dict

    Raises
    ------
    ValueError
        If the file is too large, not JSON or not an nbformat 4 notebook.
    """
    path = Path(path)
    size = path.stat().st_size
    if size > MAX_BYTES:
        raise ValueError(f"path must be a notebook of at most {MAX_BYTES} bytes, got {path} "
                         f"({size} bytes)")
    try:
        nb = json.loads(path.read_text(encoding="utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError) as err:
        raise ValueError(f"path must be a notebook (JSON), got {path}: {err}") from None
    if not isinstance(nb, dict) or nb.get("nbformat") != 4 or not isinstance(nb.get("cells"),
                                                                              list):
        raise ValueError(f"path must be an nbformat 4 notebook, got {path}")
    return nb


def write_notebook(nb: dict, path) -> Path:
    """Write a notebook as the course keeps them: JSON with indent 1, UTF-8, a final newline.

    Parameters
    ----------
    nb : dict
        The notebook.
    path : str or os.PathLike
        Where to write it (its folder is made).

    Returns
    -------
    Path
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(nb, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
    return path


def cell_source(cell: dict) -> str:
    """A cell's source as one string (nbformat stores a string or a list of lines).

    Parameters
    ----------
    cell : dict
        A notebook cell.

    Returns
    -------
    str
    """
    source = cell.get("source", "")
    return "".join(source) if isinstance(source, list) else str(source)


def _lines(text: str) -> list[str]:
    """nbformat's list of lines of a source (each but the last with its newline)."""
    return text.splitlines(keepends=True)


def _parse(cell: dict):
    """The module AST of a code cell, or None (a markdown cell, a magic, a syntax error)."""
    if cell.get("cell_type") != "code":
        return None
    try:
        return ast.parse(cell_source(cell))
    except SyntaxError:
        return None


def _final_call(tree) -> ast.Call | None:
    """The call a cell ends with, seen through a trailing ``.require()``."""
    if tree is None or not tree.body or not isinstance(tree.body[-1], ast.Expr):
        return None
    call = tree.body[-1].value
    if isinstance(call, ast.Call) and isinstance(call.func, ast.Attribute) \
            and call.func.attr == "require" and not call.args and not call.keywords \
            and isinstance(call.func.value, ast.Call):
        call = call.func.value
    return call if isinstance(call, ast.Call) else None


def _called(call: ast.Call) -> str | None:
    func = call.func
    return func.id if isinstance(func, ast.Name) else \
        func.attr if isinstance(func, ast.Attribute) else None


def _exercises(notebook) -> list[Exercise]:
    if not isinstance(notebook, str):
        raise TypeError(f"notebook must be a notebook's number such as '01', got {notebook!r}")
    return exercises_of(notebook)


def checker_calls(nb: dict, notebook: str) -> dict[str, CheckerCall]:
    """The checker cell of each exercise of notebook ``notebook`` that ``nb`` holds.

    Parameters
    ----------
    nb : dict
        The notebook (a course notebook, a student's copy, a solved or nbgrader copy).
    notebook : str
        Which course notebook it is: its number (``"01"``).

    Returns
    -------
    dict
        Exercise key -> :class:`CheckerCall`, for the exercises whose checker some cell's last
        statement calls (the last such cell); an exercise left out has no checker cell.
    """
    by_name = {e.checker.__name__: e for e in _exercises(notebook)}
    found: dict[str, CheckerCall] = {}
    for index, cell in enumerate(_cells(nb)):
        tree = _parse(cell)
        call = _final_call(tree)
        exercise = by_name.get(_called(call)) if call is not None else None
        if exercise is None:
            continue
        source = cell_source(cell)
        try:
            bound = inspect.signature(exercise.checker).bind_partial(
                *call.args, **{k.arg: k.value for k in call.keywords if k.arg is not None})
            arguments = bound.arguments if not any(isinstance(a, ast.Starred)
                                                   for a in call.args) else {}
        except TypeError:  # more arguments than the checker takes: nothing can be told
            arguments = {}
        answers = tuple(arguments[a].id if isinstance(arguments.get(a), ast.Name) else None
                        for a in exercise.answers)
        givens = tuple((name, ast.get_source_segment(source, node))
                       for name, node in arguments.items() if name not in exercise.answers)
        found[exercise.key] = CheckerCall(exercise, index, ast.get_source_segment(source,
                                                                                  call.func),
                                          answers, givens)
    return found


def _cells(nb: dict) -> list:
    if not isinstance(nb, dict) or not isinstance(nb.get("cells"), list):
        raise TypeError(f"nb must be a notebook (nbformat 4 JSON), got {type(nb).__name__}")
    return nb["cells"]


def cell_errors(nb: dict) -> dict[int, str]:
    """The error each executed code cell stopped with, from its outputs.

    Parameters
    ----------
    nb : dict
        An executed notebook.

    Returns
    -------
    dict
        Cell index -> ``"Name: value"`` of its first error output.
    """
    errors = {}
    for index, cell in enumerate(_cells(nb)):
        for out in cell.get("outputs", []) if cell.get("cell_type") == "code" else []:
            if out.get("output_type") == "error":
                errors[index] = f"{out.get('ename', 'Error')}: {out.get('evalue', '')}".strip()
                break
    return errors


def _none_assignments(tree) -> set[str]:
    """The names a cell's top-level statements set to None (``a = None``, ``a, b = None, None``)."""
    names = set()
    for stmt in tree.body if tree is not None else ():
        if not isinstance(stmt, ast.Assign):
            continue
        for target in stmt.targets:
            if isinstance(target, ast.Name) and _is_none(stmt.value):
                names.add(target.id)
            elif isinstance(target, ast.Tuple) and isinstance(stmt.value, ast.Tuple) \
                    and len(target.elts) == len(stmt.value.elts):
                names.update(t.id for t, v in zip(target.elts, stmt.value.elts, strict=True)
                             if isinstance(t, ast.Name) and _is_none(v))
    return names


def _is_none(node) -> bool:
    return isinstance(node, ast.Constant) and node.value is None


def solution_code(call: CheckerCall) -> str:
    """The line that sets an exercise's answers to its solution, with the call's givens.

    Only the givens that the solution takes are passed (a tolerance is the checker's, not the
    exercise's).

    Parameters
    ----------
    call : CheckerCall
        The exercise's checker cell, each answer a variable.

    Returns
    -------
    str
        e.g. ``"theta = check_tip_slope.solution(force=100e-9)"``.

    Raises
    ------
    ValueError
        If an answer is not passed as a variable.
    """
    if not isinstance(call, CheckerCall):
        raise TypeError(f"call must be a CheckerCall, got {call!r}")
    if None in call.answers:
        missing = [a for a, v in zip(call.exercise.answers, call.answers, strict=True) if v is None]
        raise ValueError(f"exercise {call.exercise.key}'s checker call must pass each answer "
                         f"({', '.join(call.exercise.answers)}) as a variable, got none for "
                         f"{missing}")
    takes = inspect.signature(call.exercise.solution).parameters
    givens = ", ".join(f"{name}={src}" for name, src in call.givens if name in takes)
    return f"{', '.join(call.answers)} = {call.function}.solution({givens})"


def _plan(nb: dict, notebook: str):
    """Each exercise's call, and the (exercise, solution line)s each answer cell gets."""
    calls = checker_calls(nb, notebook)
    exercises = _exercises(notebook)
    missing = [e.key for e in exercises if e.key not in calls]
    if missing:
        raise ValueError(f"nb must hold a checker cell for each exercise of notebook {notebook}: "
                         f"none found for {missing} (a code cell whose last line calls the "
                         f"checker)")
    assigned = [_none_assignments(_parse(cell)) for cell in nb["cells"]]
    answer_lines: dict[int, list[tuple[Exercise, str]]] = {}
    for e in exercises:
        call = calls[e.key]
        code = solution_code(call)
        cells = []
        for name in call.answers:
            where = [i for i in range(call.cell + 1) if name in assigned[i]]
            if not where:
                raise ValueError(f"nb must set {name} = None before exercise {e.key}'s checker "
                                 f"cell (where the student answers)")
            cells.append(where[-1])
        answer_lines.setdefault(max(cells), []).append((e, code))
    return calls, answer_lines


def _split_at_final(cell: dict, names) -> tuple[list[str], str | None]:
    """A cell's lines before its last statement and that statement's call, if it calls one of
    the checkers ``names``; else all its lines and None."""
    source = cell_source(cell)
    tree = _parse(cell)
    call = _final_call(tree)
    if call is None or _called(call) not in names:
        return _lines(source), None
    final = tree.body[-1]
    head = _lines(source)[:final.lineno - 1]
    return head, ast.get_source_segment(source, final.value)


def _join(lines: list[str]) -> str:
    return "".join(line if line.endswith("\n") else line + "\n" for line in lines).rstrip("\n")


def solved_copy(nb: dict, notebook: str) -> dict:
    """The notebook with every exercise answered by its solution.

    Parameters
    ----------
    nb : dict
        A course notebook.
    notebook : str
        Its number (``"01"``).

    Returns
    -------
    dict
        A copy whose answer cells set each answer to the exercise's solution (after the student's
        ``= None``, before the cell's checker call).

    Raises
    ------
    ValueError
        If an exercise of the notebook has no checker cell, or an answer is not a variable set
        to None before it.
    """
    _, answer_lines = _plan(nb, notebook)
    names = {e.checker.__name__ for e in _exercises(notebook)}
    out = copy.deepcopy(nb)
    for index, lines in answer_lines.items():
        cell = out["cells"][index]
        head, final = _split_at_final(cell, names)
        body = head + [code for _, code in lines] + ([final] if final is not None else [])
        cell["source"] = _lines(_join(body))
    return out


def _nbgrader(grade_id: str, *, solution: bool = False, points: float | None = None) -> dict:
    meta = dict(grade=points is not None, grade_id=grade_id, locked=points is not None,
                schema_version=SCHEMA_VERSION, solution=solution, task=False)
    if points is not None:
        meta["points"] = points
    return meta


def _code_cell(source: str, cell_id: str | None, metadata: dict) -> dict:
    cell = dict(cell_type="code", execution_count=None, metadata=metadata, outputs=[],
                source=_lines(source))
    if cell_id is not None:
        cell["id"] = cell_id
    return cell


def nbgrader_source(nb: dict, notebook: str) -> dict:
    """nbgrader's source version of a course notebook: solution cells and autograder tests.

    Each answer cell becomes a solution cell (nbgrader metadata ``solution``) that keeps the
    student's lines and adds the solution between :data:`BEGIN_SOLUTION` and
    :data:`END_SOLUTION`; each checker call becomes a locked autograder test cell worth the
    exercise's points, ``grade_id`` :attr:`~afmsmiler.exercises.registry.Exercise.grade_id`,
    which raises AssertionError with the checker's message on a wrong answer
    (:meth:`~afmsmiler.exercises.Feedback.require`). A cell that holds both is split in two.
    ``nbgrader generate_assignment`` turns it into the students' version.

    Parameters
    ----------
    nb : dict
        A course notebook.
    notebook : str
        Its number (``"01"``).

    Returns
    -------
    dict

    Raises
    ------
    ValueError
        As :func:`solved_copy`.
    """
    calls, answer_lines = _plan(nb, notebook)
    by_cell = {c.cell: c.exercise for c in calls.values()}
    names = {e.checker.__name__ for e in _exercises(notebook)}
    out = copy.deepcopy(nb)
    cells = []
    for index, cell in enumerate(nb["cells"]):
        if index not in answer_lines and index not in by_cell:
            cells.append(copy.deepcopy(cell))
            continue
        head, final = _split_at_final(cell, names)
        ids = iter([cell.get("id"), f"{cell.get('id')}-test"] if cell.get("id") else [None] * 2)
        metadata = dict(cell.get("metadata", {}))
        if index in answer_lines:
            first = answer_lines[index][0][0]
            body = head + [BEGIN_SOLUTION] + [code for _, code in answer_lines[index]] \
                + [END_SOLUTION]
            cells.append(_code_cell(_join(body), next(ids), {
                **metadata, "nbgrader": _nbgrader("answer" + first.grade_id[2:], solution=True)}))
        elif any(line.strip() for line in head):
            cells.append(_code_cell(_join(head), next(ids), metadata))
        if final is None:
            continue
        if index in by_cell:
            exercise = by_cell[index]
            test = final if final.rstrip().endswith(".require()") else f"{final}.require()"
            cells.append(_code_cell(test, next(ids), {
                "nbgrader": _nbgrader(exercise.grade_id, points=exercise.points)}))
        else:  # a checker shown before the student's turn (a wrong first try): as it was
            cells.append(_code_cell(final, next(ids), {}))
    out["cells"] = cells
    return out
