"""The panels' static pages (the book's figures) hold each panel's figure at its defaults."""
import json
import re

import pytest

from afmsmiler.plots.live import describe
from afmsmiler.ui.pages import PANELS, _panel, panel_page, write_panel_pages


def _frame(page):
    """The frame embedded in a page's drawStatic call."""
    call = re.search(r"drawStatic\(document\.getElementById\(\"[^\"]+\"\), (.*), \"([A-Za-z0-9+/=]*)\"\);",
                     page, re.S)
    layout_and_frame = call.group(1)
    decoder = json.JSONDecoder()
    layout, end = decoder.raw_decode(layout_and_frame)
    frame, _ = decoder.raw_decode(layout_and_frame[end + 2:])
    return layout, frame


@pytest.mark.parametrize("name", sorted(PANELS))
def test_a_page_holds_its_panels_figure_at_the_defaults(name):
    page = panel_page(name)
    assert page.startswith("<!DOCTYPE html>") and "uPlot" in page
    layout, frame = _frame(page)
    fresh = describe(_panel(name).fig)  # a panel built anew at its defaults
    assert layout == json.loads(json.dumps(fresh.layout))
    assert [a["axes"]["y"]["lim"] for a in frame["axes"]] == \
        [a["axes"]["y"]["lim"] for a in fresh.frame["axes"]]


def test_pages_are_written_and_unknown_panels_refused(tmp_path):
    paths = write_panel_pages(tmp_path / "panels")
    assert sorted(p.stem for p in paths) == sorted(PANELS)
    assert all(p.read_text().count("drawStatic(") == 2 for p in paths)  # defined once, called once
    with pytest.raises(ValueError, match="name must be one of"):
        panel_page("afm")
