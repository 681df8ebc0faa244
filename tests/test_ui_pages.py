"""The panels' static pages (the book's figures) hold each panel's figure at its defaults."""
import base64
import json
import re

import numpy as np
import pytest
import umsgpack

from afmsmiler.ui.pages import PANELS, SCANNED_FIRST, _panel, panel_page, write_panel_pages


def _frame(page):
    """The frame embedded in a page's drawStatic call."""
    call = re.search(r"drawStatic\(document\.getElementById\(\"[^\"]+\"\), (.*), \"([A-Za-z0-9+/=]*)\"\);",
                     page, re.S)
    layout_and_frame = call.group(1)
    decoder = json.JSONDecoder()
    layout, end = decoder.raw_decode(layout_and_frame)
    frame, _ = decoder.raw_decode(layout_and_frame[end + 2:])
    return layout, frame


@pytest.mark.parametrize("name", [
    # a panel shown after its first scan takes 2 s (the scan, twice: the page and the check)
    pytest.param(name, marks=pytest.mark.slow) if name in SCANNED_FIRST else name
    for name in sorted(PANELS)])
def test_a_page_holds_its_panels_figure_at_the_defaults(name):
    page = panel_page(name)
    assert page.startswith("<!DOCTYPE html>") and "uPlot" in page
    _layout, frame = _frame(page)
    # against the matplotlib axes of a panel built anew at its defaults (not the describer)
    hosts, seen = [], []
    for ax in _panel(name).fig.axes:
        if hasattr(ax, "_colorbar"):
            continue  # a colour bar is drawn with its image's axes
        if ax.get_subplotspec() not in seen:  # a twin shares its host's place
            seen.append(ax.get_subplotspec())
            hosts.append(ax)
    assert [a["title"]["text"] for a in frame["axes"]] == [ax.get_title() for ax in hosts]
    for a, ax in zip(frame["axes"], hosts):
        np.testing.assert_allclose(a["axes"]["x"]["lim"], ax.get_xlim(), rtol=1e-12)
        np.testing.assert_allclose(a["axes"]["y"]["lim"], ax.get_ylim(), rtol=1e-12)
        assert a["axes"]["x"]["label"] == ax.get_xlabel()


@pytest.mark.slow  # over a second: make test runs it, make unit does not
def test_pages_are_written_and_unknown_panels_refused(tmp_path):
    paths = write_panel_pages(tmp_path / "panels")
    assert sorted(p.stem for p in paths) == sorted(PANELS)
    assert all(p.read_text().count("drawStatic(") == 2 for p in paths)  # defined once, called once
    with pytest.raises(ValueError, match="name must be one of"):
        panel_page("afm")


@pytest.mark.slow  # nine panels built with their 3D views: about 2 s
def test_scene_pages_hold_each_panels_3d_view_and_unknown_names_are_refused(tmp_path):
    from afmsmiler.ui.pages import SCENE_PAGES, scene_page, write_scene_pages
    from afmsmiler.ui.registry import PANELS as REGISTRY
    assert sorted(SCENE_PAGES) == sorted(f"scene_{e.key}" for e in REGISTRY if e.scene)
    paths = write_scene_pages(tmp_path / "scenes")
    assert sorted(p.stem for p in paths) == sorted(SCENE_PAGES)
    for path in paths:
        page = path.read_text(encoding="utf-8")
        # the view's commands embedded (a scene with nothing in it would pass an empty list)
        commands = re.search(r"drawStatic\(document\.getElementById\('scene'\), (\[.*?\]), ", page, re.S)
        assert page.startswith("<!DOCTYPE html>") and len(json.loads(commands.group(1))) > 0
    with pytest.raises(ValueError, match="name must be one of"):
        scene_page("scene_controller")  # module (c)'s panel has no 3D view


def test_view_pages_hold_notebook_08s_3d_views_with_what_they_draw(tmp_path):
    # notebook 08's print_scene and stream_scene: each page embeds its view's commands, among
    # them the sample's height field and (the streamed scan, run to its end) the image's
    from afmsmiler.ui.pages import VIEW_PAGES, module_pages, view_page, write_view_pages
    assert set(VIEW_PAGES) == {"view_print", "view_stream"}
    assert set(VIEW_PAGES) <= set(module_pages("h"))
    paths = write_view_pages(tmp_path / "views")
    assert sorted(p.stem for p in paths) == sorted(VIEW_PAGES)
    drawn = {}
    for path in paths:
        page = path.read_text(encoding="utf-8")
        commands = re.search(r"drawStatic\(document\.getElementById\('scene'\), (\[.*?\]), ",
                             page, re.S)
        assert page.startswith("<!DOCTYPE html>")
        drawn[path.stem] = {(c["type"], c["path"].rsplit("/", 1)[-1]) for c in
                            (umsgpack.unpackb(base64.b64decode(x))
                             for x in json.loads(commands.group(1)))}
    # both show their sample; the streamed scan, run to its end, its image beside it too
    assert ("set_object", "sample") in drawn["view_print"] & drawn["view_stream"]
    assert ("set_object", "image") in drawn["view_stream"] - drawn["view_print"]
    with pytest.raises(ValueError, match="name must be one of"):
        view_page("view_seashell")


@pytest.mark.slow  # one scan of module (f)'s panel: about a second
@pytest.mark.parametrize("name", SCANNED_FIRST)
def test_a_scanned_panels_page_shows_its_finished_first_scan(name):
    snapshot = _panel(name).last
    assert snapshot.state == "done" and snapshot.lines_done == snapshot.lines > 0
