"""Run a filled-in notebook headless and score its exercises (nbclient, a kernel per notebook).

The notebook runs top to bottom in a fresh ``python3`` kernel of this environment (nbclient),
in the notebook's folder, importing the afmsmiler that grades, with ``AFMSMILER_TESTING=1``
(animations and scans short, as under test), ``MPLBACKEND=Agg`` and :data:`~afmsmiler.exercises.registry.GRADE_LOG` naming a file in a
temporary folder, to which each checker the notebook calls appends its verdict. A cell that
raises does not stop the run (the next exercises still count). The whole run is bounded by
``timeout`` seconds; the kernel is shut down at the end however the run ended, and killed if it
is still alive. Nothing of the run is kept but the scores.

nbclient and nbformat come with the ``lab`` and ``test`` extras; they are imported when a
notebook is run.
"""
from __future__ import annotations

import asyncio
import json
import math
import os
import subprocess
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

from ..exercises import Feedback
from ..exercises.registry import GRADE_LOG, exercises_of
from ..validation import check_integer
from .notebooks import cell_errors, checker_calls, notebook_number, read_notebook
from .scoring import NotebookScore, read_verdicts, score_notebook

__all__ = ["DEFAULT_TIMEOUT", "MAX_TIMEOUT", "MAX_JOBS", "Run", "run_notebook", "grade_notebook", "grade"]

#: Seconds a notebook may run by default (the course's longest, 08, runs in about 15 s here).
DEFAULT_TIMEOUT = 600.0
#: The longest run allowed, in seconds.
MAX_TIMEOUT = 24 * 3600.0
#: Most notebooks :func:`grade` runs at once.
MAX_JOBS = 8
#: The kernel that runs the notebooks (jupyter_client starts this Python for it).
KERNEL_NAME = "python3"


@dataclass(frozen=True)
class Run:
    """What a notebook's run left.

    Attributes
    ----------
    path : Path
        The notebook.
    notebook : dict
        The executed notebook (nbformat 4 JSON, with outputs).
    verdicts : tuple of Feedback
        The checkers' verdicts in the order given.
    timed_out : bool
        Whether the run was stopped at its time limit.
    seconds : float
        How long it ran (wall clock).
    problem : str or None
        What else stopped the run before its end (the kernel died), if anything.
    """

    path: Path
    notebook: dict
    verdicts: tuple[Feedback, ...]
    timed_out: bool
    seconds: float
    problem: str | None = None


def _check_timeout(timeout) -> float:
    if isinstance(timeout, bool) or not isinstance(timeout, (int, float)) \
            or not (math.isfinite(timeout) and 0 < timeout <= MAX_TIMEOUT):
        raise ValueError(f"timeout must be in (0, {MAX_TIMEOUT:g}] s, got {timeout!r}")
    return float(timeout)


async def _execute(nb, folder: Path, env: dict, timeout: float) -> tuple[bool, str | None]:
    """Run ``nb`` (an nbformat NotebookNode, filled in place).

    Returns whether it ran out of time, and what stopped it otherwise (the kernel died), if
    anything.
    """
    from nbclient import NotebookClient
    from nbclient.exceptions import CellTimeoutError, DeadKernelError

    client = NotebookClient(nb, timeout=int(math.ceil(timeout)), allow_errors=True,
                            kernel_name=KERNEL_NAME, shutdown_kernel="immediate",
                            resources={"metadata": {"path": str(folder)}})
    km = client.create_kernel_manager()  # ours too: killed below whatever nbclient did
    # the kernel's own stdout and stderr (its start-up warnings) are not the student's
    task = asyncio.ensure_future(client.async_execute(env=env, stdout=subprocess.DEVNULL,
                                                      stderr=subprocess.DEVNULL))
    try:
        done, _ = await asyncio.wait({task}, timeout=timeout)
        if not done:  # nbclient turns the cancellation into DeadKernelError: not a death
            task.cancel()
            try:
                await task
            except (asyncio.CancelledError, Exception):  # noqa: BLE001 - stopped on purpose
                pass
            return True, None
        try:
            task.result()
        except CellTimeoutError:
            return True, None
        except DeadKernelError as err:
            return False, f"the kernel died ({err})"
        except Exception as err:  # noqa: BLE001 - no kernel (a missing kernelspec...): said
            return False, f"the notebook could not be run ({type(err).__name__}: {err})"
        return False, None
    finally:
        if km.has_kernel and await km.is_alive():
            await km.shutdown_kernel(now=True)


def _python_path(python_path: str) -> str:
    """PYTHONPATH for the kernel: it imports the afmsmiler that grades (a checkout's, if this is
    one), and relative entries are made absolute (the kernel runs in the notebook's folder)."""
    entries = [str(Path(p).resolve()) for p in python_path.split(os.pathsep) if p]
    root = Path(__file__).resolve().parents[2]
    if root.name not in ("site-packages", "dist-packages"):
        entries.insert(0, str(root))
    return os.pathsep.join(dict.fromkeys(entries))


def run_notebook(path, *, timeout: float = DEFAULT_TIMEOUT) -> Run:
    """Run a notebook headless as the grader does and collect its checkers' verdicts.

    Parameters
    ----------
    path : str or os.PathLike
        The notebook (``.ipynb``).
    timeout : float
        Longest run in s, in (0, :data:`MAX_TIMEOUT`].

    Returns
    -------
    Run
    """
    timeout = _check_timeout(timeout)
    path = Path(path)
    nb_json = read_notebook(path)
    import nbformat
    from jupyter_core.utils import run_sync

    nb = nbformat.reads(json.dumps(nb_json), as_version=4)  # sources joined, as nbclient wants
    with tempfile.TemporaryDirectory(prefix="afmsmiler-grade-") as tmp:
        log = Path(tmp) / "verdicts.jsonl"
        log.touch()
        env = dict(os.environ, AFMSMILER_TESTING="1", MPLBACKEND="Agg")
        env[GRADE_LOG] = str(log)
        env["PYTHONPATH"] = _python_path(env.get("PYTHONPATH", ""))
        start = time.monotonic()
        timed_out, problem = run_sync(_execute)(nb, path.resolve().parent, env, timeout)
        seconds = time.monotonic() - start
        verdicts = read_verdicts(log.read_text(encoding="utf-8"))
    return Run(path, json.loads(json.dumps(nb)), tuple(verdicts), timed_out, seconds, problem)


def _reasons(run: Run, notebook: str, calls: dict, errors: dict, timeout: float) -> dict:
    """Why each exercise without a verdict has none."""
    reasons = {}
    for e in exercises_of(notebook):
        call = calls.get(e.key)
        name = e.checker.__name__
        if call is None:
            reasons[e.key] = (f"no cell ends with a call of {name} (put the checker call back as "
                              f"its cell's last line)")
        elif call.cell in errors:
            reasons[e.key] = f"the cell that calls {name} stopped with {errors[call.cell]}"
        elif run.timed_out:
            reasons[e.key] = f"the notebook ran out of time ({timeout:g} s) before {name}"
        elif run.problem:
            reasons[e.key] = f"{run.problem} before {name}"
        else:
            reasons[e.key] = f"the cell that calls {name} gave no verdict"
    return reasons


def grade_notebook(path, *, timeout: float = DEFAULT_TIMEOUT) -> NotebookScore:
    """Run a notebook and score its exercises (:func:`run_notebook`,
    :func:`~afmsmiler.grade.scoring.score_notebook`).

    Which course notebook it is comes from its file name's two-digit number (``01_...``), else
    from the exercises its checkers graded.

    Parameters
    ----------
    path : str or os.PathLike
        The notebook.
    timeout : float
        Longest run in s, in (0, :data:`MAX_TIMEOUT`].

    Returns
    -------
    NotebookScore

    Raises
    ------
    ValueError
        If neither the name nor the verdicts tell which course notebook it is.
    """
    timeout = _check_timeout(timeout)
    run = run_notebook(path, timeout=timeout)
    number = notebook_number(run.path)
    keys = {v.exercise.split(".")[0] for v in run.verdicts if v.exercise}
    if number is None and len(keys) == 1:
        number = keys.pop()
    if number is None:
        raise ValueError(f"path must be a course notebook named NN_... (01_cantilever_mechanics"
                         f".ipynb), or one whose checkers ran, got {run.path.name}")
    errors = cell_errors(run.notebook)
    calls = checker_calls(run.notebook, number)
    notes = [f"ran out of time after {timeout:g} s"] if run.timed_out else []
    if run.problem:
        notes.append(run.problem)
    if errors:
        notes.append(f"{len(errors)} cell(s) raised an error")
    return score_notebook(run.path.name, exercises_of(number), run.verdicts,
                          reasons=_reasons(run, number, calls, errors, timeout), notes=notes)


def grade(paths, *, timeout: float = DEFAULT_TIMEOUT, jobs: int = 1) -> list[NotebookScore]:
    """Grade notebooks (:func:`grade_notebook`), ``jobs`` of them at a time.

    Parameters
    ----------
    paths : sequence of str or os.PathLike
        The notebooks, at most 100.
    timeout : float
        Longest run of each in s.
    jobs : int
        Notebooks run at once, each in its own kernel, 1 to :data:`MAX_JOBS` (a kernel waits
        for its cells' output much of the time: two at once on two cores take little more than
        one).

    Returns
    -------
    list of NotebookScore
        In the order of ``paths``.
    """
    paths = [paths] if isinstance(paths, (str, os.PathLike)) else list(paths)
    if not 1 <= len(paths) <= 100:
        raise ValueError(f"paths must name 1 to 100 notebooks, got {len(paths)}")
    timeout = _check_timeout(timeout)
    jobs = check_integer("jobs", jobs, 1, MAX_JOBS)
    if jobs == 1:
        return [grade_notebook(p, timeout=timeout) for p in paths]
    from concurrent.futures import ThreadPoolExecutor
    with ThreadPoolExecutor(max_workers=jobs) as pool:  # the kernels are processes
        return list(pool.map(lambda p: grade_notebook(p, timeout=timeout), paths))
