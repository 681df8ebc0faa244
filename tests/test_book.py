"""The course book: its table of contents names existing chapters, and book <-> notebook links hold."""
import inspect
import json
import re
from pathlib import Path

import pytest

from afmsmiler import apps
from afmsmiler.ui import pages
from afmsmiler.ui.registry import MODULES, PANELS

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


# -- the book <-> notebook <-> page triangle (issue 22, part 4) ----------------------------------
def _chapter(module: str) -> tuple[str, str]:
    """The stem of module ``module``'s notebook (= its chapter's) and the chapter's text."""
    stem = MODULES[module][0][: -len(".ipynb")]
    return stem, (BOOK / f"{stem}.md").read_text(encoding="utf-8")


def _slug(heading: str) -> str:
    """The anchor docutils (and GitHub) give a plain heading: lower case, words joined by '-'."""
    return re.sub(r"[^a-z0-9]+", "-", heading.lower()).strip("-")


def test_the_pages_cover_every_panel_of_the_registry_once():
    names = [n for m in MODULES for n in pages.module_pages(m)]
    assert len(names) == len(set(names))
    assert set(names) == {*pages.PANELS, *pages.SCENE_PAGES, *pages.INSTRUMENT_PAGES,
                          *pages.VIEW_PAGES}
    assert set(pages.PANELS) == {e.key for e in PANELS}  # module (h)'s four included
    assert {e.key for e in PANELS if e.module == "h"} <= set(names)
    assert set(pages.SCENE_PAGES) == {f"scene_{e.key}" for e in PANELS if e.scene}


def test_every_chapter_embeds_its_modules_pages_and_no_other():
    for m in MODULES:
        stem, text = _chapter(m)
        embedded = re.findall(r'<iframe src="_static/panels/(\w+)\.html"', text)
        assert sorted(embedded) == sorted(pages.module_pages(m)), \
            f"book/{stem}.md embeds {embedded}, module ({m}) has {pages.module_pages(m)}"


def test_every_chapter_links_its_notebook_and_says_how_to_start_its_app():
    for m in MODULES:
        stem, text = _chapter(m)
        assert f"{{download}}`notebooks/{stem}.ipynb <../notebooks/{stem}.ipynb>`" in text, stem
        assert f"`make app NB={stem}`" in text, stem
        # the link to the app where `make app` serves it (voila_command's default port)
        port = inspect.signature(apps.voila_command).parameters["port"].default
        assert f"[the web app](http://127.0.0.1:{port}/)" in text, stem
        assert "## Notebook, web app and figures" in text, stem


def test_every_notebook_links_back_to_its_chapter_section():
    headings = {}
    for f in _toc_files():
        text = (BOOK / f"{f}.md").read_text(encoding="utf-8")
        headings[f] = {_slug(h) for h in re.findall(r"^#+ (.+)$", text, flags=re.M)}
    for nb in sorted((ROOT / "notebooks").glob("*.ipynb")):
        first = "".join(json.loads(nb.read_text(encoding="utf-8"))["cells"][0]["source"])
        links = re.findall(r"\]\(\.\./book/([\w.-]+)\.md#([\w-]+)\)", first)
        assert (nb.stem, "notebook-web-app-and-figures") in links, \
            f"{nb.name}'s first cell has no link to its chapter's section: {links}"
        for stem, anchor in links:
            assert anchor in headings[stem], f"{nb.name} links to book/{stem}.md#{anchor}: no such section"


def test_the_instructor_guide_is_in_the_book_and_quotes_the_measured_times():
    assert "instructor_guide" in _toc_files()
    guide = (BOOK / "instructor_guide.md").read_text(encoding="utf-8")
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    measured = dict(re.findall(r"^\| \d \| `(\d\d_\w+)` \| [^|]+ \| (\d+ s) \|", readme, flags=re.M))
    quoted = dict(re.findall(r"^\| `(\d\d_\w+)` \| (\d+ s) \|", guide, flags=re.M))
    assert len(measured) == len(list((ROOT / "notebooks").glob("*.ipynb"))) and quoted == measured


def test_module_pages_refuses_an_unknown_module():
    with pytest.raises(ValueError, match="module"):
        pages.module_pages("z")


def _vendor_mathjax():
    import importlib.util
    spec = importlib.util.spec_from_file_location("vendor_mathjax", ROOT / "tools" / "vendor_mathjax.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_mathjax_integrity_is_npms_sha512_format():
    # npm's dist.integrity of an empty file: SHA-512 of b"" (FIPS 180-4's test value), base64
    assert _vendor_mathjax().integrity_of(b"") == (
        "sha512-z4PhNX7vuL3xVChQ1m2AB9Yg5AULVxXcg/SpIdNs6c5H0NE8XYXysP+DGNKHfuwvY7kxvUdBeoGlODJ6+SfaPg==")


def test_mathjax_tarball_that_is_not_the_pin_is_refused(tmp_path, monkeypatch):
    fake = tmp_path / "mathjax-3.2.2.tgz"
    fake.write_bytes(b"not mathjax")
    monkeypatch.setenv("MATHJAX_TARBALL", str(fake))
    vendor = _vendor_mathjax()
    with pytest.raises(SystemExit, match="MATHJAX_TARBALL=.* hashes to sha512-"):
        vendor.vendor(tmp_path / "mathjax", cache=tmp_path / "cache.tgz")
    assert not (tmp_path / "mathjax").exists()  # nothing unpacked


def test_the_book_loads_mathjax_from_its_build():
    config = (BOOK / "_config.yml").read_text(encoding="utf-8")
    entry = _vendor_mathjax().ENTRY
    assert f"mathjax_path: ../mathjax/{entry}" in config and 'html_extra_path: ["_extra"]' in config


def test_the_instructor_guide_counts_each_notebooks_exercises():
    guide = (BOOK / "instructor_guide.md").read_text(encoding="utf-8")
    counted = {nb: int(n) for nb, n in
               re.findall(r"^\| `(\d\d_\w+)` \| \d+ s \| [^|]+ \| (\d+) \|", guide, flags=re.M)}
    for path in sorted((ROOT / "notebooks").glob("*.ipynb")):
        cells = json.loads(path.read_text(encoding="utf-8"))["cells"]
        text = "\n".join("".join(c["source"]) for c in cells if c["cell_type"] == "markdown")
        numbers = {int(n) for n in re.findall(r"^\*\*(\d+)\. ", text, flags=re.M)}  # **2. Title.**
        assert numbers == set(range(1, len(numbers) + 1)) and counted[path.stem] == len(numbers), \
            f"the guide gives {path.stem} {counted.get(path.stem)} exercises, it has {sorted(numbers)}"
