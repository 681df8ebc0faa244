"""3D scenes on meshcat: one server per kernel (:mod:`.viewer`), scene builders per module.

Scene builders take model results and draw them; they never compute physics themselves.
"""
from .viewer import close_viewer, get_viewer, save_static_html, static_html, viewer_running

__all__ = ["get_viewer", "close_viewer", "viewer_running", "static_html", "save_static_html"]
