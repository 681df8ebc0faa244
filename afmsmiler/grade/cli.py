"""The command line of :mod:`afmsmiler.grade` (``python -m afmsmiler.grade --help``)."""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

__all__ = ["main"]


def _parser() -> argparse.ArgumentParser:
    from . import __doc__ as help_text
    from .run import DEFAULT_TIMEOUT, MAX_JOBS, MAX_TIMEOUT

    def seconds(text):
        value = float(text)
        if not 0 < value <= MAX_TIMEOUT:
            raise argparse.ArgumentTypeError(f"must be in (0, {MAX_TIMEOUT:g}] s, got {text}")
        return value

    parser = argparse.ArgumentParser(
        prog="python -m afmsmiler.grade", formatter_class=argparse.RawDescriptionHelpFormatter,
        description=help_text.split("The parts:")[0].replace(":mod:", "").replace("``", "'"))
    parser.add_argument("notebooks", nargs="+", type=Path, metavar="NOTEBOOK",
                        help="notebooks (.ipynb) named as the course's (NN_name.ipynb)")
    parser.add_argument("--timeout", type=seconds, default=DEFAULT_TIMEOUT,
                        help=f"longest run of each notebook in s (default {DEFAULT_TIMEOUT:g})")
    parser.add_argument("--jobs", type=int, default=1, choices=range(1, MAX_JOBS + 1),
                        metavar="N", help=f"notebooks run at once, 1 to {MAX_JOBS} (default 1)")
    parser.add_argument("--json", action="store_true", help="print the scores as JSON")
    what = parser.add_mutually_exclusive_group()
    what.add_argument("--nbgrader-source", type=Path, metavar="DIR",
                      help="write nbgrader's source assignments DIR/NN_name/NN_name.ipynb "
                           "instead of grading")
    what.add_argument("--solved", type=Path, metavar="DIR",
                      help="write the notebooks with every exercise solved into DIR instead of "
                           "grading")
    return parser


def _write(args) -> int:
    from .notebooks import nbgrader_source, notebook_number, read_notebook, solved_copy
    from .notebooks import write_notebook

    for path in args.notebooks:
        number = notebook_number(path)
        if number is None:
            print(f"{path}: not a course notebook (NN_name.ipynb)", file=sys.stderr)
            return 2
        nb = read_notebook(path)
        if args.nbgrader_source is not None:
            out = write_notebook(nbgrader_source(nb, number),
                                 args.nbgrader_source / path.stem / path.name)
        else:
            out = write_notebook(solved_copy(nb, number), args.solved / path.name)
        print(out)
    return 0


def main(argv=None) -> int:
    """Grade notebooks, or write their nbgrader or solved versions (see ``--help``).

    Parameters
    ----------
    argv : list of str, optional
        The arguments (default: the command line's).

    Returns
    -------
    int
        The exit code: 0 (graded or written), 2 (a notebook missing or not the course's, or
        nbclient missing).
    """
    args = _parser().parse_args(argv)
    missing = [str(p) for p in args.notebooks if not p.is_file()]
    if missing:
        print(f"no such notebook: {', '.join(missing)}", file=sys.stderr)
        return 2
    try:
        if args.nbgrader_source is not None or args.solved is not None:
            return _write(args)
        from .run import grade
        from .scoring import report

        scores = grade(args.notebooks, timeout=args.timeout, jobs=args.jobs)
    except ValueError as err:
        print(f"error: {err}", file=sys.stderr)
        return 2
    except ImportError as err:  # nbclient and nbformat come with the lab extra
        print(f"error: grading runs the notebooks with nbclient ({err}): install afmsmiler's "
              f"lab extra", file=sys.stderr)
        return 2
    if args.json:
        print(json.dumps([s.as_dict() for s in scores], indent=1, ensure_ascii=False))
    else:
        print(report(scores))
    return 0
