"""House rules for notebooks: committed without outputs, one per module, thin."""
import json
import re
from pathlib import Path

import pytest

NOTEBOOKS = sorted((Path(__file__).parents[1] / "notebooks").glob("*.ipynb"))


def test_there_are_notebooks():
    assert NOTEBOOKS, "notebooks/ holds one notebook per module"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.name for p in NOTEBOOKS])
def test_committed_without_outputs(path):
    nb = json.loads(path.read_text(encoding="utf-8"))
    dirty = [i for i, c in enumerate(nb["cells"]) if c["cell_type"] == "code"
             and (c.get("outputs") or c.get("execution_count") is not None)]
    assert not dirty, f"{path.name}: cells {dirty} carry outputs; strip them before committing"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.name for p in NOTEBOOKS])
def test_notebooks_are_thin_and_close_nothing(path):
    nb = json.loads(path.read_text(encoding="utf-8"))
    code = ["".join(c["source"]) for c in nb["cells"] if c["cell_type"] == "code"]
    for src in code:
        # a notebook never defines a function longer than a few lines
        lines = src.splitlines()
        for i, line in enumerate(lines):
            if line.lstrip().startswith("def "):
                body = [ln for ln in lines[i + 1:] if ln.startswith((" ", "\t")) or not ln.strip()]
                assert len([b for b in body if b.strip()]) <= 8, f"{path.name}: long function in a cell"
    # whatever a notebook starts (a 3D view, a device link) lives as long as its kernel: a cell
    # that closed it broke every panel and view a student used after "Run All"
    for src in code:
        assert "close_viewer" not in src and "get_viewer" not in src, f"{path.name}: {src!r}"
        for name in re.findall(r"(\w+)\.(?:close|stop)\(\)", src):
            # only what the same cell opened (so running it again opens it again)
            assert re.search(rf"\b{name}\s*=|\b{name}\.open\(", src), \
                f"{path.name}: a cell closes {name}, which a student may still use: {src!r}"
