"""Static pages of the panels' figures, for the book (``make book``) and any page without a kernel.

Each page is the panel's live figure at its default settings, drawn by the same renderer as in
JupyterLab (:func:`afmsmiler.plots.live.static_html`: uPlot inlined, the data embedded), so the book
shows what the notebook's panel shows before the student moves a slider. Run as

    python -m afmsmiler.ui.pages DIRECTORY

to write into ``DIRECTORY`` one ``<panel>.html`` per panel of the registry
(:data:`afmsmiler.ui.registry.PANELS`, every module's, (h)'s four included), one
``scene_<panel>.html`` per panel that the notebook shows with a 3D view (:func:`scene_page`: the
panel's scene at its defaults, as the 3D view's own static page) and one
``instrument_<kind>.html`` per 3D instrument of module (e) (:func:`instrument_page`) and one
``view_<name>.html`` per 3D view a notebook shows outside its panels (:data:`VIEW_PAGES`, module
(h)'s print and stream, :func:`view_page`). The pages
iterate the registry, so a panel added there gets its pages and a test
(``tests/test_book.py``) fails until its module's chapter embeds them; :func:`module_pages`
says which pages belong to a module's chapter.
"""
from __future__ import annotations

import argparse
import html
import sys
from pathlib import Path

from ..plots.live import static_html
from ..validation import check_choice
from .registry import MODULES, PANELS as REGISTRY

__all__ = ["PANELS", "SCENE_PAGES", "INSTRUMENT_PAGES", "panel_page", "write_panel_pages",
           "scene_page", "write_scene_pages", "instrument_page", "write_instrument_pages",
           "VIEW_PAGES", "view_page", "write_view_pages", "module_pages", "write_pages"]

#: Page name -> the panel's entry in :data:`afmsmiler.ui.registry.PANELS` (every panel).
PANELS = {e.key: e for e in REGISTRY}

#: Page name (``scene_<key>``) -> the entry of every panel the notebook shows with its 3D view.
SCENE_PAGES = {f"scene_{e.key}": e for e in REGISTRY if e.scene}

#: Page name -> the 3D instrument (a key of :data:`afmsmiler.scenes.instrument.INSTRUMENTS`).
INSTRUMENT_PAGES = {"instrument_obd": "obd", "instrument_educational": "educational"}

#: The module whose chapter shows the instruments' pages.
INSTRUMENT_MODULE = "e"


def _print_view():
    """Notebook 08's ``print_scene``: the macroscopic AFM panel's print at its defaults (the
    seashell's STL, read back on the printer's grid), as the notebook first shows it."""
    import tempfile
    from ..hardware import printing
    from ..scenes.imaging import ImagingScene
    with tempfile.TemporaryDirectory() as folder:
        stl = _panel("macro_afm").export_stl(Path(folder) / "seashell_print.stl")
        return ImagingScene(printing.mesh_to_sample(stl))


def _stream_view():
    """Notebook 08's ``stream_scene``: the educational AFM's twin scanning its sample, each
    finished line drawn beside it (the notebook's scan, at its end)."""
    from ..hardware import experiments
    from ..hardware.educational import live_view
    from ..scenes.imaging import ImagingScene
    sample = experiments.stream_sample()
    afm, server = experiments.educational_twin(sample)
    try:
        scene = ImagingScene(sample)
        afm.scan(on_line=live_view(scene))
    finally:
        afm.close()
        server.stop()
    return scene


#: Page name -> (module, what builds the scene) of the 3D views a notebook shows outside its
#: panels: module (h)'s print of an AFM image and its educational AFM's streamed scan.
VIEW_PAGES = {"view_print": ("h", _print_view), "view_stream": ("h", _stream_view)}


#: Panels whose pages show the scan their notebook starts right below them (their sliders apply to
#: the next scan, ``figure=False``), rather than empty axes. Not the macroscopic AFM: its twin
#: streams the pixels in real time, so the line its figure shows last depends on the timing.
SCANNED_FIRST = ("imaging",)


def _made(entry, scene: bool = False):
    """The panel of ``entry`` at its defaults, as its notebook first shows it.

    A panel of :data:`SCANNED_FIRST` is shown after one scan at its defaults (``panel.start()``,
    run to the end at once outside a live notebook), as the notebook's next cell starts it.
    """
    panel = entry.make(scene=True) if scene else entry.make()
    if entry.key in SCANNED_FIRST:
        panel.start()
    return panel


def _panel(name: str):
    return _made(PANELS[name])  # without a 3D view


def panel_page(name: str) -> str:
    """A complete HTML page with panel ``name``'s figure at its defaults.

    A panel of :data:`SCANNED_FIRST` is shown after the scan its notebook starts at its
    defaults.

    Parameters
    ----------
    name : str
        A key of :data:`PANELS`.

    Returns
    -------
    str

    Raises
    ------
    ValueError
        For an unknown ``name``, listing the panels.
    """
    if name not in PANELS:
        raise ValueError(f"name must be one of {sorted(PANELS)}, got {name!r}")
    e = PANELS[name]
    title = html.escape(f"Module ({e.module}): {e.title}")
    body = static_html(_panel(name).fig)
    return (f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>{title}</title></head>"
            f"<body style='margin:0'>{body}</body></html>\n")


def write_panel_pages(directory) -> list[Path]:
    """Write ``<name>.html`` for every panel of :data:`PANELS` into ``directory``.

    Parameters
    ----------
    directory : str or os.PathLike
        Created if missing.

    Returns
    -------
    list of pathlib.Path
        The pages written.
    """
    return _write(directory, PANELS, panel_page)


def _write(directory, names, page) -> list[Path]:
    """Write ``page(name)`` as ``<name>.html`` into ``directory`` for each of ``names``."""
    out = Path(directory)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for name in names:
        path = out / f"{name}.html"
        path.write_text(page(name), encoding="utf-8")
        written.append(path)
    return written


def scene_page(name: str) -> str:
    """A complete HTML page with the 3D view of panel ``name`` at its defaults.

    The panel is built with its 3D view (:class:`~afmsmiler.scenes.SceneView`, no browser or
    server needed), after its first scan as in :func:`panel_page`, and the view is exported as its static page (meshcat's three.js bundle and
    the scene's commands inlined, so the page needs no network).

    Parameters
    ----------
    name : str
        A key of :data:`SCENE_PAGES` (``"scene_<panel>"``).

    Returns
    -------
    str

    Raises
    ------
    ValueError
        For an unknown ``name``, listing the 3D pages.
    """
    if name not in SCENE_PAGES:
        raise ValueError(f"name must be one of {sorted(SCENE_PAGES)}, got {name!r}")
    return _made(SCENE_PAGES[name], scene=True).scene_view().static_html()


def write_scene_pages(directory) -> list[Path]:
    """Write ``scene_<panel>.html`` for every panel of :data:`SCENE_PAGES` into ``directory``.

    Parameters
    ----------
    directory : str or os.PathLike
        Created if missing.

    Returns
    -------
    list of pathlib.Path
        The pages written.
    """
    return _write(directory, SCENE_PAGES, scene_page)


def view_page(name: str) -> str:
    """A complete HTML page with the 3D view ``name`` a notebook shows outside its panels.

    Parameters
    ----------
    name : str
        A key of :data:`VIEW_PAGES` (``"view_<name>"``).

    Returns
    -------
    str

    Raises
    ------
    ValueError
        For an unknown ``name``, listing the views.
    """
    check_choice("name", name, list(VIEW_PAGES))
    return VIEW_PAGES[name][1]().view.static_html()


def write_view_pages(directory) -> list[Path]:
    """Write ``view_<name>.html`` for every view of :data:`VIEW_PAGES` into ``directory``.

    Parameters
    ----------
    directory : str or os.PathLike
        Created if missing.

    Returns
    -------
    list of pathlib.Path
        The pages written.
    """
    return _write(directory, VIEW_PAGES, view_page)


def instrument_page(kind: str) -> str:
    """The 3D instrument ``kind`` as one self-contained page (meshcat's static HTML).

    The scene is drawn in a view of its own (:class:`~afmsmiler.scenes.SceneView`, no browser
    needed), exported with its camera and the housing at its default opacity.

    Parameters
    ----------
    kind : str
        A value of :data:`INSTRUMENT_PAGES` (``"obd"`` or ``"educational"``).

    Returns
    -------
    str

    Raises
    ------
    ValueError
        For an unknown ``kind``, listing the instruments.
    """
    from ..scenes.instrument import INSTRUMENTS, InstrumentScene
    check_choice("kind", kind, INSTRUMENTS)
    return InstrumentScene(kind).static_html()


def write_instrument_pages(directory) -> list[Path]:
    """Write ``instrument_<kind>.html`` for both instruments into ``directory``.

    Parameters
    ----------
    directory : str or os.PathLike
        Created if missing.

    Returns
    -------
    list of pathlib.Path
        The pages written.
    """
    out = Path(directory)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for name, kind in INSTRUMENT_PAGES.items():
        path = out / f"{name}.html"
        path.write_text(instrument_page(kind), encoding="utf-8")
        written.append(path)
    return written


def module_pages(module: str) -> list[str]:
    """The names of the pages (without ``.html``) that module ``module``'s chapter embeds.

    Its panels' figures, then their 3D views, then (module (e)) the two instruments and (module
    (h)) the 3D views its notebook shows outside its panels (:data:`VIEW_PAGES`).

    Parameters
    ----------
    module : str
        A module's letter, a key of :data:`afmsmiler.ui.registry.MODULES`.

    Returns
    -------
    list of str

    Raises
    ------
    ValueError
        For an unknown ``module``, listing the modules.
    """
    check_choice("module", module, list(MODULES))
    names = [k for k, e in PANELS.items() if e.module == module]
    names += [k for k, e in SCENE_PAGES.items() if e.module == module]
    if module == INSTRUMENT_MODULE:
        names += list(INSTRUMENT_PAGES)
    names += [k for k, (m, _) in VIEW_PAGES.items() if m == module]
    return names


def write_pages(directory) -> list[Path]:
    """Write every page of the book (figures, 3D views, instruments) into ``directory``.

    Parameters
    ----------
    directory : str or os.PathLike
        Created if missing.

    Returns
    -------
    list of pathlib.Path
        The pages written.
    """
    return [*write_panel_pages(directory), *write_scene_pages(directory),
            *write_instrument_pages(directory), *write_view_pages(directory)]


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description="Write the panels' figures and 3D views as "
                                                 "static pages.")
    parser.add_argument("directory")
    args = parser.parse_args(argv)
    for path in write_pages(args.directory):
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
