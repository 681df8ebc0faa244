"""A 3D view carried over the kernel's own connection: meshcat's three.js viewer in a widget.

Every scene builder in :mod:`afmsmiler.scenes` draws with meshcat's Python API
(``vis["path"].set_object(...)``, ``set_transform``, ``set_property``, ``delete``). Instead of a
meshcat server on a second port, shown in an iframe (blank over SSH, on JupyterHub or in voila
served elsewhere, and closed by a notebook's last cell), a :class:`SceneView` is a widget: its
:attr:`SceneView.vis` is a real :class:`meshcat.Visualizer` whose window packs each command with
msgpack exactly as meshcat's own ``ViewerWindow`` does and sends it as a comm message of the
widget; the browser hands it to meshcat's viewer (``handle_command_bytearray``), from the
``main.min.js`` that the meshcat package ships. So the scene builders keep their meshcat API, no
second port or process exists, and a view works in JupyterLab, voila, JupyterHub and VS Code alike
and dies with its kernel.

Each view holds its own scene: the last command of each kind per path (:class:`SceneState`, the
same bookkeeping as meshcat's server), so a view displayed later, a second view of the same widget
or a reloaded page is replayed the whole scene, and :meth:`SceneView.static_html` exports it as
one self-contained page for the book (meshcat's static HTML).

meshcat's three.js bundle (about 850 kB) travels once per page in a shared library widget
(:func:`library`), not once per view. A view also draws screen-space text over the scene:
a legend (:attr:`SceneView.legend`, HTML in a corner, never clipped or tilted) and labels pinned
to points of the scene (:meth:`SceneView.set_labels`).

Examples
--------
>>> import meshcat.geometry as g
>>> view = SceneView()
>>> view.vis["ball"].set_object(g.Sphere(0.1))
>>> view.vis["ball"].set_transform()
>>> [path for _, path, _ in view.state.keys()]
['/meshcat/ball', '/meshcat/ball']
"""
from __future__ import annotations

import base64
import contextlib
import json
import threading
import uuid
from functools import lru_cache
from pathlib import Path

import anywidget
import ipywidgets as widgets
import meshcat
import msgpack
import numpy as np
import traitlets
import umsgpack

from ..validation import check_instance, check_integer, check_writable_path

__all__ = ["SceneView", "SceneState", "library", "view_of", "fit_camera", "static_html",
           "save_static_html", "HEIGHT_RANGE"]

STATIC = Path(__file__).with_name("static")
#: The height of a view in CSS pixels: at least a readable view, at most a screen.
HEIGHT_RANGE = (150, 2000)
#: Most commands a view remembers (distinct path, kind and property); a scene builder that
#: creates paths without bound fails loudly instead of growing a replay without end.
MAX_ENTRIES = 100_000


def _meshcat_bundle() -> Path:
    return Path(meshcat.__file__).parent / "viewer" / "dist" / "main.min.js"


@lru_cache(maxsize=None)
def _read(name: str) -> str:
    return (STATIC / name).read_text(encoding="utf-8")


@lru_cache(maxsize=None)
def _library_esm() -> str:
    """meshcat's UMD bundle as a module that hands ``MeshCat`` to the views (see scene_view.js)."""
    bundle = _meshcat_bundle().read_text(encoding="utf-8")
    # The UMD header takes the CommonJS branch when ``module`` and ``exports`` are objects, so the
    # bundle defines nothing global and no AMD loader on the page (VS Code, classic) can take it.
    return ("const module = { exports: {} };\nconst exports = module.exports;\n" + bundle +
            "\nconst hub = (globalThis.__afmsmilerMeshCat ??= {});\n"
            "hub.MeshCat = module.exports;\n"
            "if (hub.resolve) hub.resolve(module.exports);\n"
            "export default {};\n")


class _Library(anywidget.AnyWidget):
    """meshcat's three.js viewer, sent to the browser once per kernel and shared by every view."""

    _esm = traitlets.Unicode().tag(sync=True)

    def __init__(self):
        super().__init__(_esm=_library_esm())


_library: _Library | None = None
_library_lock = threading.Lock()


def library() -> _Library:
    """This kernel's one meshcat library widget (made on first use)."""
    global _library
    with _library_lock:
        if _library is None:
            _library = _Library()
        return _library


class SceneState:
    """The scene as a view must replay it: the last command of each kind at each path, in order.

    The same bookkeeping as meshcat's server (``meshcat.servers.zmqserver``): a new object at a
    path drops that path's properties, a delete drops the path and everything below it; unlike the
    server's, a property is kept once per name (the last value), so a slider that sets an opacity
    a thousand times keeps one entry, not a thousand.
    """

    def __init__(self):
        self._entries: dict[tuple[str, str, str], bytes] = {}

    def apply(self, kind: str, path: str, prop: str, data: bytes) -> bool:
        """Record one packed command; return False for a set_object that changes nothing.

        Parameters
        ----------
        kind : str
            meshcat's command type (``set_object``, ``set_transform``, ``set_property``,
            ``set_animation``, ``delete``).
        path : str
            The command's path (``/meshcat/...``).
        prop : str
            The property a ``set_property`` sets (empty for the others).
        data : bytes
            The command packed with msgpack, as meshcat's window sends it.
        """
        if kind == "delete":
            below = path.rstrip("/") + "/"
            for key in [k for k in self._entries if k[1] == path or k[1].startswith(below)]:
                del self._entries[key]
            return True
        key = (kind, path, prop)
        if kind == "set_object":
            if self._entries.get(key) == data:
                return False  # meshcat's own cache: the same object again is not re-sent
            for k in [k for k in self._entries if k[0] == "set_property" and k[1] == path]:
                del self._entries[k]
        self._entries.pop(key, None)  # re-inserted last: the replay keeps the order of changes
        if len(self._entries) >= MAX_ENTRIES:
            raise RuntimeError(f"a 3D view holds at most {MAX_ENTRIES} commands; a scene that "
                               "creates new paths without end must delete the old ones")
        self._entries[key] = data
        return True

    def keys(self) -> list[tuple[str, str, str]]:
        """(kind, path, property) of each command, in the order a replay sends them."""
        return list(self._entries)

    def commands(self) -> list[bytes]:
        """The packed commands, in the order a replay sends them."""
        return list(self._entries.values())

    def __len__(self) -> int:
        return len(self._entries)


class _Fit:
    """A command of afmsmiler's own that views handle beside meshcat's: fit the camera to a path.

    Packed like meshcat's commands, so it is replayed and exported in the scene's order.
    """

    def __init__(self, path, margin: float, points):
        self.path, self.margin, self.points = path, margin, points

    def lower(self) -> dict:
        out = {"type": "afm_fit", "path": self.path.lower(), "margin": self.margin}
        if self.points is not None:
            out["points"] = [[float(v) for v in p] for p in self.points]
        return out


def fit_camera(vis, margin: float = 1.0, points=None) -> None:
    """Turn the camera of the view ``vis`` draws into to frame the objects under ``vis``.

    The view keeps the camera's direction and moves its target to the centre of the objects'
    bounding sphere and its distance so that the sphere fills the view's height (``margin`` > 1
    leaves room around it). A scene builder calls it once when it draws (a later call moves the
    camera again, so not on every update: the student's own orbit would be lost). Nothing
    happens for a visualizer that is not a :class:`SceneView`'s (a test's recorder).

    Parameters
    ----------
    vis : meshcat.Visualizer
        The path whose objects to frame (e.g. ``scene.vis["sample"]``).
    margin : float
        The sphere's diameter as a fraction of the view's height, inverted: 1 fits it exactly,
        in [0.3, 5].
    points : array_like, shape (N, 3), optional
        Frame these points (the scene's world frame, scene units) instead of the objects under
        ``vis``: a region objects will fill later (a scan's image beside its sample).
    """
    from ..validation import check_array, check_range
    margin = check_range("margin", margin, 0.3, 5.0)
    if points is not None:
        points = check_array("points", points, ndim=2)
        if points.shape[1] != 3 or not 1 <= len(points) <= 64:
            raise ValueError(f"points must have shape (N, 3) with 1 <= N <= 64, got {points.shape}")
    window = getattr(vis, "window", None)
    if isinstance(window, _Window):
        window.send(_Fit(vis.path, margin, points))


def _ext(obj):
    if isinstance(obj, umsgpack.Ext):  # meshcat's typed arrays (geometry, animation tracks)
        return msgpack.ExtType(obj.type, obj.data)
    raise TypeError(f"cannot pack a {type(obj).__name__} into a 3D view's command")


def packb(data) -> bytes:
    """A command packed as meshcat's window packs it (``umsgpack.packb``), the same bytes.

    msgpack's C packer, some 7 times quicker than the pure-Python ``umsgpack`` on the commands
    of a stress-coloured lever's slider move. meshcat's typed arrays (``umsgpack.Ext``) become
    msgpack's extension objects of the same code and data.

    Parameters
    ----------
    data : dict
        A meshcat command, lowered (``command.lower()``).

    Returns
    -------
    bytes
    """
    return msgpack.packb(data, default=_ext, use_bin_type=True)


class _Window:
    """The window of :attr:`SceneView.vis`: meshcat's ``ViewerWindow`` API over the widget."""

    def __init__(self, view: "SceneView"):
        self.view = view

    def send(self, command) -> None:
        data = command.lower()
        kind = data["type"]
        path = "" if kind == "afm_fit" else data.get("path", "")  # one camera: the last fit
        self.view._command(kind, path, str(data.get("property", "")), packb(data))

    def get_scene(self) -> str:
        return self.view.static_html()

    def get_image(self):
        raise NotImplementedError("a SceneView cannot capture an image in the kernel; take a "
                                  "screenshot of the browser (the browser tests do)")

    def __repr__(self) -> str:
        return f"<SceneView window: {len(self.view.state)} commands>"


class SceneView(anywidget.AnyWidget):
    """A 3D view: a meshcat scene drawn in the browser, its commands sent over the kernel's comm.

    Parameters
    ----------
    height : int
        Height of the view in CSS pixels, in :data:`HEIGHT_RANGE`; its width follows the page.

    Attributes
    ----------
    vis : meshcat.Visualizer
        Where scene builders draw (``vis["part"].set_object(...)``), the root of this view's scene.
    state : SceneState
        The scene as sent so far (what a new view is replayed).
    commands_sent : int
        Commands sent to the browser so far.
    legend : str
        HTML shown in the view's top-left corner, in screen space (a colour scale, a caption).
    """

    _esm = traitlets.Unicode(_read("scene_common.js") + _read("scene_view.js")).tag(sync=True)
    _css = traitlets.Unicode(_read("scene_view.css")).tag(sync=True)
    _library = traitlets.Instance(_Library).tag(sync=True, **widgets.widget_serialization)
    _uid = traitlets.Unicode().tag(sync=True)
    height = traitlets.Int(400).tag(sync=True)
    legend = traitlets.Unicode("").tag(sync=True)
    _labels = traitlets.List().tag(sync=True)

    def __init__(self, height: int = 400):
        height = check_integer("height", height, *HEIGHT_RANGE)
        super().__init__(_library=library(), height=height, _uid=uuid.uuid4().hex)
        self.state = SceneState()
        self.commands_sent = 0
        self._seq = 0
        self._pending: list[tuple[dict, bytes]] | None = None
        self._lock = threading.RLock()
        self.vis = meshcat.Visualizer(window=_Window(self))
        self._legends: dict[str, str] = {}
        self.on_msg(self._handle_message)

    # -- commands ---------------------------------------------------------------------------
    def _command(self, kind: str, path: str, prop: str, data: bytes) -> None:
        with self._lock:
            if not self.state.apply(kind, path, prop, data):
                return
            if kind == "delete":  # a deleted scene takes its legends along
                below = path.rstrip("/") + "/"
                gone = [k for k in self._legends if k == path or k.startswith(below)]
                for key in gone:
                    del self._legends[key]
                if gone:
                    self._join_legends()
            self._seq += 1
            meta = {"kind": kind, "path": path, "prop": prop, "seq": self._seq}
            if self._pending is not None:
                self._pending.append((meta, data))
            else:
                self._send_batch([(meta, data)])

    def _send_batch(self, batch) -> None:
        if not batch:
            return
        self.commands_sent += len(batch)
        self.send({"type": "commands", "commands": [m for m, _ in batch]},
                  [d for _, d in batch])

    @contextlib.contextmanager
    def hold(self):
        """Send the commands made inside the block as one message at its end, and the changes
        of the view's own state (its legend, its labels) as one more: one repaint."""
        with self._lock:
            outer = self._pending is not None
            if not outer:
                self._pending = []
        try:
            with self.hold_sync():
                yield self
        finally:
            if not outer:
                with self._lock:
                    batch, self._pending = self._pending, None
                    self._send_batch(batch)

    def _handle_message(self, _widget, content, _buffers) -> None:
        if isinstance(content, dict) and content.get("type") == "replay":
            self.replay()

    def replay(self) -> None:
        """Send the whole scene again (a page reloaded or a view the browser asked to fill)."""
        with self._lock:
            keys, data = self.state.keys(), self.state.commands()
            self.send({"type": "replay", "seq": self._seq,
                       "commands": [{"kind": k, "path": p, "prop": q} for k, p, q in keys]}, data)

    def clear(self) -> None:
        """Delete this view's scene (meshcat's ``vis.delete()`` of the root)."""
        self.vis.delete()

    # -- screen-space text ---------------------------------------------------------------------
    def set_labels(self, labels) -> None:
        """Pin text labels to points of the scene; they stay upright and readable as it turns.

        Parameters
        ----------
        labels : dict or sequence of (str, array_like)
            Text -> point (x, y, z) in the scene's world frame (scene units), or pairs of them.
            An empty one removes the labels.
        """
        items = labels.items() if isinstance(labels, dict) else labels
        out = []
        for item in items:
            try:
                text, point = item
            except (TypeError, ValueError):
                raise TypeError(f"labels must map text to points, got {item!r}") from None
            if not isinstance(text, str):
                raise TypeError(f"a label's text must be a str, got {text!r}")
            p = np.asarray(point, dtype=float)
            if p.shape != (3,) or not np.all(np.isfinite(p)):
                raise ValueError(f"label {text!r} needs a finite point (x, y, z), got {point!r}")
            out.append({"text": text, "at": [float(v) for v in p]})
        self._labels = out

    def set_legend_part(self, key: str, html: str | None) -> None:
        """Show ``html`` in the view's legend under ``key`` (a scene path), or remove it (None).

        The legend (:attr:`legend`) is the parts in the order they were first set, one below the
        other, in the view's corner: screen-space text that never tilts, clips or hides the scene.
        A part whose path is deleted from the scene goes with it.
        """
        if html is None:
            self._legends.pop(key, None)
        else:
            self._legends[key] = str(html)
        self._join_legends()

    def _join_legends(self) -> None:
        self.legend = "".join(f"<div class='afm-legend-part'>{h}</div>"
                              for h in self._legends.values())

    @property
    def labels(self) -> list[dict]:
        """The labels shown (``{"text": ..., "at": [x, y, z]}``)."""
        return list(self._labels)

    # -- the static page -----------------------------------------------------------------------
    def static_html(self) -> str:
        """The scene as one self-contained HTML page (meshcat's static export; no kernel)."""
        bundle = _meshcat_bundle().read_text(encoding="utf-8")
        scene = json.dumps([base64.b64encode(d).decode() for d in self.state.commands()])
        labels = json.dumps(self._labels).replace("</", "<\\/")
        legend = json.dumps(self.legend).replace("</", "<\\/")
        return ("<!DOCTYPE html>\n<html><head><meta charset=utf-8><title>MeshCat</title>"
                f"<style>{_read('scene_view.css')}\nbody {{margin: 0;}} .afm-scene {{height: 100vh;}}"
                "</style></head><body><div class='afm-scene' id='scene'></div>"
                f"<script>{bundle}</script><script>\n{_read('scene_common.js')}\n"
                f"{_read('scene_static.js')}\n"
                f"drawStatic(document.getElementById('scene'), {scene}, {legend}, {labels});"
                "\n</script></body></html>")


def view_of(vis) -> SceneView | None:
    """The :class:`SceneView` that ``vis`` draws into, or None (a test's recorder)."""
    window = getattr(vis, "window", None)
    return window.view if isinstance(window, _Window) else None


def static_html(vis: meshcat.Visualizer) -> str:
    """The scene of the view ``vis`` draws into, as one self-contained HTML page.

    Parameters
    ----------
    vis : meshcat.Visualizer
        A visualizer of a :class:`SceneView` (``view.vis`` or a path below it).

    Raises
    ------
    TypeError
        If ``vis`` is not a visualizer of a :class:`SceneView`.
    """
    check_instance("vis", vis, meshcat.Visualizer)
    view = view_of(vis)
    if view is None:
        raise TypeError(f"vis must draw into a SceneView to be exported, got {vis!r}")
    return view.static_html()


def save_static_html(path, vis: meshcat.Visualizer) -> str:
    """Write :func:`static_html` of ``vis`` to ``path`` (for the course book); return the path.

    Parameters
    ----------
    path : str or os.PathLike
        The HTML file to write, in an existing folder (replaced if it exists).
    vis : meshcat.Visualizer
        A visualizer of a :class:`SceneView`.

    Raises
    ------
    ValueError
        If ``path`` is not a path, names a folder, lies in a folder that does not exist or
        cannot be written (the message names ``path`` and the operating system's reason).
    TypeError
        If ``vis`` is not a visualizer of a :class:`SceneView`.
    """
    path = check_writable_path("path", path, "an HTML file")
    html = static_html(vis)  # before the file is opened: a failed export leaves no empty file
    try:
        with open(path, "w", encoding="utf-8") as f:
            f.write(html)
    except OSError as err:
        raise ValueError(f"path {path!r} cannot be written: {err.strerror or err}") from None
    return path
