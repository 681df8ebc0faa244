"""3D scenes: scene builders per module, each drawn in its own view over the kernel's connection.

Scene builders take model results and draw them with meshcat's API; they never compute physics
themselves. Each draws into a :class:`~afmsmiler.scenes.view.SceneView` (a widget carrying
meshcat's commands as comm messages, so it works wherever the kernel's widgets do) unless a
``vis=`` is given.
"""
from .view import SceneView, save_static_html, static_html, view_of

__all__ = ["SceneView", "static_html", "save_static_html", "view_of"]
