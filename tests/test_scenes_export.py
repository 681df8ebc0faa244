"""Exporting a scene as a static HTML page: a bad path or viewer is named before any work."""
import os

import pytest

from afmsmiler.scenes import SceneView, save_static_html, static_html
from tests.recording import Recorder


@pytest.mark.parametrize("path, match", [
    (".", "path must name a file, got the folder"),
    ("", "path must name a file"),
    (os.path.join("no-such-folder", "deeper", "scene.html"), "path must be in an existing folder"),
    (3, r"path must be a str or os.PathLike naming an HTML file, got 3 \(int\)"),
    (None, "path must be a str or os.PathLike"),
])
def test_a_bad_path_is_a_value_error_naming_path(tmp_path, monkeypatch, path, match):
    # before: IsADirectoryError, FileNotFoundError, TypeError (from open)
    monkeypatch.chdir(tmp_path)
    with pytest.raises(ValueError, match=match):
        save_static_html(path, SceneView().vis)
    assert os.listdir(tmp_path) == []


def test_a_folder_given_as_path_object_and_a_wrong_viewer(tmp_path):
    with pytest.raises(ValueError, match="path must name a file, got the folder"):
        save_static_html(tmp_path, SceneView().vis)
    with pytest.raises(TypeError, match="vis must be"):  # before: AttributeError
        save_static_html(tmp_path / "scene.html", vis=Recorder())
    with pytest.raises(TypeError, match="vis must be"):
        static_html(Recorder())
    assert not (tmp_path / "scene.html").exists()
