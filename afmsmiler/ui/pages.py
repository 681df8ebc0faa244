"""Static pages of the panels' figures, for the book (``make book``) and any page without a kernel.

Each page is the panel's live figure at its default settings, drawn by the same renderer as in
JupyterLab (:func:`afmsmiler.plots.live.static_html`: uPlot inlined, the data embedded), so the book
shows what the notebook's panel shows before the student moves a slider. Run as

    python -m afmsmiler.ui.pages DIRECTORY

to write one ``<panel>.html`` per panel into ``DIRECTORY``, and one ``instrument_<kind>.html`` per
3D instrument of module (e) (:func:`instrument_page`: meshcat's own static page of the scene, which
needs the kernel's meshcat server for the export; it is started and closed again).
"""
from __future__ import annotations

import argparse
import html
import sys
from pathlib import Path

from ..plots.live import static_html
from ..validation import check_choice
from .registry import PANELS as REGISTRY

__all__ = ["PANELS", "INSTRUMENT_PAGES", "panel_page", "write_panel_pages", "instrument_page",
           "write_instrument_pages"]

#: Page name -> the panel's entry in :data:`afmsmiler.ui.registry.PANELS` (every panel).
PANELS = {e.key: e for e in REGISTRY}

#: Page name -> the 3D instrument (a key of :data:`afmsmiler.scenes.instrument.INSTRUMENTS`).
INSTRUMENT_PAGES = {"instrument_obd": "obd", "instrument_educational": "educational"}


def _panel(name: str):
    return PANELS[name].make()  # at its defaults, without a 3D view


def panel_page(name: str) -> str:
    """A complete HTML page with panel ``name``'s figure at its defaults.

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
    out = Path(directory)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for name in PANELS:
        path = out / f"{name}.html"
        path.write_text(panel_page(name), encoding="utf-8")
        written.append(path)
    return written


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


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description="Write the panels' figures as static pages.")
    parser.add_argument("directory")
    args = parser.parse_args(argv)
    for path in [*write_panel_pages(args.directory), *write_instrument_pages(args.directory)]:
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
