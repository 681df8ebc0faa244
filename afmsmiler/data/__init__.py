"""Data files that ship with afmsmiler, behind one accessor.

``path(name)`` gives the file's path whatever the working directory, in a checkout or in an
installed package (``README.md`` here names each file's origin and licence), as underactuated's
``FindResource`` does for its course data. Notebooks and tests read shipped data only through it.
"""
from __future__ import annotations

from importlib import resources
from pathlib import Path

__all__ = ["path", "names"]


def names() -> tuple[str, ...]:
    """The names of the shipped data files (not the README or this module).

    Returns
    -------
    tuple of str
    """
    root = resources.files(__name__)
    return tuple(sorted(p.name for p in root.iterdir()
                        if p.is_file() and not p.name.endswith((".py", ".pyc", ".md"))))


def path(name: str) -> Path:
    """The path of the shipped data file ``name``.

    Parameters
    ----------
    name : str
        One of :func:`names` (``"bruker_d3100.spm"``, ``"spot3-0192.jpk-force"``).

    Returns
    -------
    pathlib.Path

    Raises
    ------
    ValueError
        If no shipped file has that name.

    Examples
    --------
    >>> path("bruker_d3100.spm").name
    'bruker_d3100.spm'
    """
    valid = names()
    if not isinstance(name, str) or name not in valid:
        raise ValueError(f"name must be one of {list(valid)}, got {name!r}")
    return Path(str(resources.files(__name__).joinpath(name)))
