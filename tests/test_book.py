"""The course book: its table of contents names existing chapters, and book <-> notebook links hold."""
import re
from pathlib import Path

ROOT = Path(__file__).parents[1]
BOOK = ROOT / "book"


def _toc_files():
    return re.findall(r"file:\s*(\S+)", (BOOK / "_toc.yml").read_text(encoding="utf-8"))


def test_toc_chapters_exist():
    for name in ["intro", *_toc_files()]:
        assert (BOOK / f"{name}.md").exists(), f"book/_toc.yml names {name}, which has no file"


def test_every_notebook_has_a_chapter_that_links_to_it():
    chapters = {f: (BOOK / f"{f}.md").read_text(encoding="utf-8") for f in _toc_files()}
    for nb in sorted((ROOT / "notebooks").glob("*.ipynb")):
        assert any(nb.name in text for text in chapters.values()), \
            f"no chapter of the book links to notebooks/{nb.name}"


def test_chapter_links_point_to_existing_notebooks():
    for f in _toc_files():
        for link in re.findall(r"notebooks/([\w.-]+\.ipynb)", (BOOK / f"{f}.md").read_text(encoding="utf-8")):
            assert (ROOT / "notebooks" / link).exists(), f"book/{f}.md links to missing notebooks/{link}"
