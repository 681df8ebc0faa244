"""``python -m afmsmiler.grade``: see :mod:`afmsmiler.grade` (its docstring is the help)."""
import sys

from .cli import main

if __name__ == "__main__":
    sys.exit(main())
