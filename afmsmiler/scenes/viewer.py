"""Where a scene builder draws: its own 3D view, over the kernel's own connection.

Every scene builder in :mod:`afmsmiler.scenes` takes ``vis=`` (a :class:`meshcat.Visualizer`,
or a test's recorder) and otherwise draws into a new :class:`~afmsmiler.scenes.view.SceneView`,
a widget that carries meshcat's commands as comm messages: no server, no second port, nothing to
close. A view lives as long as the object that holds it and its kernel; each scene shows only its
own objects.
"""
from __future__ import annotations

import meshcat

from .transforms import check_visualizer
from .view import SceneView, save_static_html, static_html, view_of

__all__ = ["scene_root", "SceneDisplay", "static_html", "save_static_html", "view_of"]


def scene_root(vis: meshcat.Visualizer | None = None, height: int = 400) -> meshcat.Visualizer:
    """``vis``, or the root visualizer of a new :class:`SceneView` of ``height`` px."""
    return SceneView(height=height).vis if vis is None else check_visualizer("vis", vis)


class SceneDisplay:
    """What every scene builder shares: its view, shown as the last expression of a cell.

    A scene builder sets ``self.root`` (the visualizer it draws into).
    """

    root: meshcat.Visualizer

    @property
    def view(self) -> SceneView | None:
        """The widget that shows this scene (None when it draws into a test's recorder)."""
        return view_of(self.root)

    def _ipython_display_(self) -> None:
        from IPython.display import display
        view = self.view
        display(view if view is not None else repr(self))
