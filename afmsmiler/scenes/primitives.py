"""Small reusable meshcat building blocks for the scene builders of every module.

All geometry here is in *scene units*: each scene builder chooses a scale (for instance 1 scene
unit = 100 um for the cantilever) and converts its SI model results before calling these helpers.
The world frame is meshcat's: z up, the default camera looking from +x (use :func:`set_camera`).

Contents
--------
- :class:`ColorScale` and :func:`nice_ceil`: value -> RGB vertex colors through a matplotlib
  colormap (a 256-entry lookup table, so coloring a mesh costs microseconds), e.g. the diverging
  ``"RdBu_r"`` map for tension (red) / compression (blue).
- :func:`beam_mesh` / :class:`BeamMesh`: a deformable box beam following a centre-line deflection
  z(x), with one scalar per vertex on the top, bottom and side faces (the sides carry the values
  through the thickness) and on both end caps; :meth:`BeamMesh.geometry` gives the meshcat
  ``TriangularMeshGeometry`` with vertex colors.
- :class:`Arrow` (cylinder + cone), :class:`Segment` (a thin cylinder between two points, e.g. a
  laser beam), :func:`cone`, :func:`sphere`, :func:`polyline`: drawn once, then moved in place
  with ``set_transform`` (no new objects per update).
- :class:`ColorLegend`: meshcat has no text, so the legend is a colorbar with tick labels and its
  unit rendered (by Pillow, in about a millisecond) into a PNG texture on a thin plate;
  :func:`legend_html` gives the same legend as an HTML snippet for a widget.
"""
from __future__ import annotations

import io
import math
from dataclasses import dataclass
from functools import lru_cache

import matplotlib
import meshcat
import meshcat.geometry as g
import numpy as np

from ..validation import check_array, check_integer, check_positive, check_range

__all__ = ["ColorScale", "nice_ceil", "BeamMesh", "beam_mesh", "beam_faces", "rotation_between",
           "translation", "Arrow", "Segment", "cone", "sphere", "polyline", "colorbar_png",
           "legend_html", "ColorLegend", "set_camera", "rgb_hex", "CAMERA_FOV", "camera_ndc",
           "show_helpers", "text_png", "TextPlate", "tick_labels", "legend_title"]

_LUT_SIZE = 256


@lru_cache(maxsize=32)
def _lut(cmap: str) -> np.ndarray:
    try:
        colormap = matplotlib.colormaps[cmap]
    except KeyError:
        raise ValueError(f"cmap must be a matplotlib colormap name, got {cmap!r}") from None
    lut = colormap(np.linspace(0.0, 1.0, _LUT_SIZE))[:, :3].astype(np.float32)
    lut.setflags(write=False)
    return lut


def rgb_hex(rgb) -> int:
    """The 0xRRGGBB integer meshcat materials take, of ``rgb``, an RGB triple in [0, 1]."""
    r, gr, b = (int(round(255 * float(np.clip(c, 0.0, 1.0)))) for c in rgb[:3])
    return (r << 16) | (gr << 8) | b


@dataclass(frozen=True)
class ColorScale:
    """A linear map from values to colors of a matplotlib colormap.

    Parameters
    ----------
    vmin, vmax : float
        Values mapped to the two ends of the colormap (``vmin < vmax``); values outside are
        clipped to the end colors.
    cmap : str
        A matplotlib colormap name; the default ``"RdBu_r"`` is diverging: ``vmin`` blue,
        ``vmax`` red, the midpoint white.
    label : str
        What the values are, e.g. ``"bending stress"``.
    unit : str
        Their unit as shown on the legend, e.g. ``"MPa"``.

    Raises
    ------
    ValueError
        If the limits are not finite with ``vmin < vmax`` or ``cmap`` is unknown.
    """

    vmin: float
    vmax: float
    cmap: str = "RdBu_r"
    label: str = ""
    unit: str = ""

    def __post_init__(self):
        vmin = check_range("vmin", self.vmin, -math.inf, math.inf, self.unit)
        check_range("vmax", self.vmax, vmin, math.inf, self.unit, low_inclusive=False)
        _lut(self.cmap)

    @classmethod
    def symmetric(cls, limit: float, cmap: str = "RdBu_r", label: str = "",
                  unit: str = "") -> "ColorScale":
        """A scale from ``-limit`` to ``+limit`` (a diverging map: 0 is the middle color)."""
        limit = check_positive("limit", limit, unit)
        return cls(-limit, limit, cmap, label, unit)

    def normalize(self, values) -> np.ndarray:
        """``values`` as fractions of the scale in [0, 1] (clipped)."""
        v = np.asarray(values, dtype=float)
        return np.clip((v - self.vmin) / (self.vmax - self.vmin), 0.0, 1.0)

    def rgb(self, values) -> np.ndarray:
        """RGB colors in [0, 1] of ``values``: an array of shape ``values.shape + (3,)`` (float32)."""
        idx = np.rint(self.normalize(values) * (_LUT_SIZE - 1)).astype(np.intp)
        return _lut(self.cmap)[idx]

    @property
    def title(self) -> str:
        """``"label [unit]"`` as written on the legend."""
        return f"{self.label} [{self.unit}]" if self.unit else self.label


def nice_ceil(value: float, floor: float) -> float:
    """The smallest 1, 2 or 5 x 10^n that is >= ``value`` (and >= ``floor`` > 0).

    Used for color limits, so that a legend changes only when a value crosses a round number.
    """
    floor = check_positive("floor", floor)
    value = check_range("value", value, -math.inf, math.inf)
    value = max(abs(value), floor)
    exponent = math.floor(math.log10(value))
    for mantissa in (1.0, 2.0, 5.0, 10.0):
        candidate = mantissa * 10.0 ** exponent
        if candidate >= value * (1 - 1e-12):
            return candidate
    return 10.0 ** (exponent + 1)  # pragma: no cover - the loop always returns


# --- the beam mesh ---------------------------------------------------------------------------
def _grid_faces(rows: int, cols: int, base: int) -> np.ndarray:
    """Two triangles per cell of a rows x cols vertex grid numbered base + r * cols + c."""
    r, c = np.meshgrid(np.arange(rows - 1), np.arange(cols - 1), indexing="ij")
    a = base + r * cols + c
    b, d, e = a + cols, a + cols + 1, a + 1
    return np.concatenate([np.stack([a, b, d], -1).reshape(-1, 3),
                           np.stack([a, d, e], -1).reshape(-1, 3)])


@lru_cache(maxsize=16)
def beam_faces(n_length: int, n_thickness: int) -> np.ndarray:
    """Triangle indices of a :func:`beam_mesh` with the given numbers of stations (cached).

    The vertex blocks, in order: side y = -w/2 (n_length x n_thickness), side y = +w/2 (same),
    top (n_length x 2), bottom (n_length x 2), clamp end cap (2 x n_thickness), free end cap
    (2 x n_thickness).
    """
    nl, nt = n_length, n_thickness
    blocks = [(nl, nt), (nl, nt), (nl, 2), (nl, 2), (2, nt), (2, nt)]
    faces, base = [], 0
    for rows, cols in blocks:
        faces.append(_grid_faces(rows, cols, base))
        base += rows * cols
    out = np.concatenate(faces).astype(np.uint32)
    out.setflags(write=False)
    return out


@dataclass(frozen=True)
class BeamMesh:
    """A beam as a triangle mesh with one scalar value per vertex (see :func:`beam_mesh`).

    Attributes
    ----------
    vertices : ndarray, shape (n_vertices, 3)
        Positions in scene units.
    faces : ndarray, shape (n_faces, 3)
        Vertex indices of the triangles.
    values : ndarray, shape (n_vertices,)
        The scalar at each vertex (in the caller's unit), to be colored by a :class:`ColorScale`.
    """

    vertices: np.ndarray
    faces: np.ndarray
    values: np.ndarray

    def colors(self, scale: ColorScale) -> np.ndarray:
        """Vertex colors (n_vertices x 3, RGB in [0, 1]) of :attr:`values` on ``scale``."""
        return scale.rgb(self.values)

    def geometry(self, scale: ColorScale) -> g.TriangularMeshGeometry:
        """The meshcat geometry with vertex colors on ``scale``; draw it with a
        ``vertexColors=True`` material."""
        return g.TriangularMeshGeometry(self.vertices, self.faces, self.colors(scale))


def beam_mesh(x, deflection, width: float, thickness: float, values, *, slope=None) -> BeamMesh:
    """Mesh a box beam of rectangular section whose centre line follows ``(x, 0, deflection)``.

    The section at each station is offset along the centre line's normal, so the thickness stays
    true where the (exaggerated) deflection is steep.

    Parameters
    ----------
    x : array_like, shape (n_length,)
        Stations along the beam, strictly increasing, in scene units (n_length >= 2).
    deflection : array_like, shape (n_length,)
        Centre-line height z at each station, in scene units (as drawn, i.e. exaggerated).
    width, thickness : float
        Width (along y) and thickness in scene units, > 0.
    values : array_like, shape (n_length, n_thickness)
        A scalar at each station and each of ``n_thickness >= 2`` evenly spaced levels through
        the thickness, from the bottom (z_b = -thickness/2) to the top (z_b = +thickness/2). The
        top face carries ``values[:, -1]``, the bottom ``values[:, 0]``, the sides and end caps
        all levels.
    slope : array_like, shape (n_length,), optional
        dz/dx of the drawn centre line; by default ``np.gradient(deflection, x, edge_order=2)``.

    Returns
    -------
    BeamMesh
        ``2 n_length n_thickness + 4 n_length + 4 n_thickness`` vertices.

    Raises
    ------
    ValueError
        If the shapes disagree or a value is not finite.
    """
    x = check_array("x", x, ndim=1, min_size=2, increasing=True)
    nl = x.size
    z = check_array("deflection", deflection, ndim=1, size=nl)
    width = check_positive("width", width)
    thickness = check_positive("thickness", thickness)
    values = check_array("values", values, ndim=2)
    if values.shape[0] != nl or values.shape[1] < 2:
        raise ValueError(f"values must have shape ({nl}, n_thickness >= 2), got {values.shape}")
    nt = values.shape[1]
    s = np.gradient(z, x, edge_order=2) if slope is None else check_array("slope", slope, ndim=1, size=nl)

    inv = 1.0 / np.sqrt(1.0 + s * s)
    nx_, nz_ = -s * inv, inv                                  # unit normal in the x-z plane
    zb = np.linspace(-0.5, 0.5, nt) * thickness               # levels through the thickness
    px = x[:, None] + zb[None, :] * nx_[:, None]              # (nl, nt)
    pz = z[:, None] + zb[None, :] * nz_[:, None]
    hw = 0.5 * width

    def sheet(xx, yy, zz):
        xx, yy, zz = np.broadcast_arrays(xx, yy, zz)
        return np.stack([xx, yy, zz], -1).reshape(-1, 3)

    sides = [sheet(px, -hw, pz), sheet(px, hw, pz)]
    ys = np.array([-hw, hw])[None, :]
    top = sheet(px[:, -1:], ys, pz[:, -1:])
    bottom = sheet(px[:, :1], ys, pz[:, :1])
    ends = [sheet(px[i][None, :], ys.T, pz[i][None, :]) for i in (0, -1)]
    vertices = np.concatenate(sides + [top, bottom] + ends)

    vals = np.concatenate([values.ravel(), values.ravel(),
                           np.repeat(values[:, -1], 2), np.repeat(values[:, 0], 2),
                           np.tile(values[0], 2), np.tile(values[-1], 2)])
    return BeamMesh(vertices, beam_faces(nl, nt), vals)


# --- rigid primitives moved in place ---------------------------------------------------------
def translation(p) -> np.ndarray:
    """4x4 homogeneous translation to point ``p`` (3 values)."""
    t = np.eye(4)
    t[:3, 3] = np.asarray(p, dtype=float)
    return t


def rotation_between(a, b) -> np.ndarray:
    """3x3 rotation matrix turning direction ``a`` into direction ``b`` (Rodrigues)."""
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    a = a / np.linalg.norm(a)
    b = b / np.linalg.norm(b)
    v = np.cross(a, b)
    c = float(np.dot(a, b))
    if c < -1 + 1e-12:  # opposite: turn by pi about any axis perpendicular to a
        axis = np.cross(a, [1.0, 0.0, 0.0])
        if np.linalg.norm(axis) < 1e-6:
            axis = np.cross(a, [0.0, 1.0, 0.0])
        axis /= np.linalg.norm(axis)
        return 2 * np.outer(axis, axis) - np.eye(3)
    vx = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
    return np.eye(3) + vx + vx @ vx / (1 + c)


def _material(color, opacity=1.0, **kwargs):
    return g.MeshLambertMaterial(color=color, opacity=opacity, **kwargs)


def _check_point(name, p):
    return check_array(name, p, ndim=1, size=3)


def _show(obj, visible: bool) -> None:
    # meshcat's server appends every set_property to the node's list (kept for static_html), so
    # send a visibility change only when it changes
    if visible != obj._visible:
        obj.vis.set_property("visible", visible)
        obj._visible = visible


class Arrow:
    """An arrow (cylinder shaft + cone head) drawn once at ``vis`` and moved with :meth:`set`.

    Parameters
    ----------
    vis : meshcat.Visualizer
        Where to draw (the arrow's own path, e.g. ``get_viewer()["mod/force"]``).
    color : int
        0xRRGGBB.
    radius : float
        Shaft radius in scene units; the head is 2.5x as wide and ``head_length`` long.
    head_length : float
        Length of the cone head in scene units (shrunk for arrows shorter than the head).
    """

    def __init__(self, vis: meshcat.Visualizer, color: int = 0x202020, radius: float = 0.01,
                 head_length: float = 0.06):
        self.vis = vis
        self.radius = check_positive("radius", radius)
        self.head_length = check_positive("head_length", head_length)
        mat = _material(color)
        vis["shaft"].set_object(g.Cylinder(1.0, radius=self.radius), mat)
        vis["head"].set_object(g.Cylinder(self.head_length, radiusTop=0.0,
                                          radiusBottom=2.5 * self.radius), mat)
        self.start = np.zeros(3)
        self.vector = np.zeros(3)
        self._visible = True

    def transforms(self, start, vector) -> tuple[np.ndarray, np.ndarray] | None:
        """The shaft and head transforms for an arrow from ``start`` along ``vector`` (None if 0)."""
        start = _check_point("start", start)
        vector = _check_point("vector", vector)
        length = float(np.linalg.norm(vector))
        if length < 1e-12:
            return None
        d = vector / length
        rot = np.eye(4)
        rot[:3, :3] = rotation_between([0.0, 1.0, 0.0], d)  # meshcat cylinders lie along y
        head = min(self.head_length, length)
        shaft = length - head
        shaft_t = translation(start + d * shaft / 2) @ rot @ np.diag([1.0, max(shaft, 1e-9), 1.0, 1.0])
        s = head / self.head_length
        head_t = translation(start + d * (shaft + head / 2)) @ rot @ np.diag([s, s, s, 1.0])
        return shaft_t, head_t

    def set(self, start, vector) -> None:
        """Point the arrow from ``start`` along ``vector`` (scene units); hide it if ``vector`` is 0."""
        t = self.transforms(start, vector)
        self.start, self.vector = np.asarray(start, float), np.asarray(vector, float)
        _show(self, t is not None)
        if t is not None:
            self.vis["shaft"].set_transform(t[0])
            self.vis["head"].set_transform(t[1])


class Segment:
    """A thin cylinder between two points (a laser beam, a wire), moved with :meth:`set`.

    Parameters
    ----------
    vis : meshcat.Visualizer
        Where to draw.
    color : int
        0xRRGGBB.
    radius : float
        Radius in scene units.
    opacity : float
        In (0, 1].
    """

    def __init__(self, vis: meshcat.Visualizer, color: int = 0xff2020, radius: float = 0.005,
                 opacity: float = 1.0):
        self.vis = vis
        self.radius = check_positive("radius", radius)
        opacity = check_range("opacity", opacity, 0.0, 1.0, low_inclusive=False)
        vis.set_object(g.Cylinder(1.0, radius=self.radius), _material(color, opacity))
        self._visible = True

    @staticmethod
    def transform(start, end) -> np.ndarray | None:
        """The transform of a unit cylinder spanning ``start`` -> ``end`` (None if they coincide)."""
        start = _check_point("start", start)
        end = _check_point("end", end)
        v = end - start
        length = float(np.linalg.norm(v))
        if length < 1e-12:
            return None
        rot = np.eye(4)
        rot[:3, :3] = rotation_between([0.0, 1.0, 0.0], v / length)
        return translation((start + end) / 2) @ rot @ np.diag([1.0, length, 1.0, 1.0])

    def set(self, start, end) -> None:
        """Span the segment from ``start`` to ``end`` (scene units)."""
        t = self.transform(start, end)
        _show(self, t is not None)
        if t is not None:
            self.vis.set_transform(t)


class Tube:
    """A thick polyline (a wire on a lever) drawn as one triangle mesh, redrawn with :meth:`set`.

    One ``set_object`` per update, instead of one transform per :class:`Segment`, keeps a bent
    wire of many pieces cheap to follow a slider.

    Parameters
    ----------
    vis : meshcat.Visualizer
        Where to draw.
    color : int
        0xRRGGBB.
    radius : float
        Radius in scene units.
    sides : int
        Vertices around the tube (3 to 32).
    """

    def __init__(self, vis: meshcat.Visualizer, color: int = 0xb87333, radius: float = 0.01,
                 sides: int = 6):
        self.vis = vis
        self.color = color
        self.radius = check_positive("radius", radius)
        self.sides = check_integer("sides", sides, 3, 32)

    @staticmethod
    def mesh(points, radius: float, sides: int = 6) -> tuple[np.ndarray, np.ndarray]:
        """Vertices (N * sides x 3) and triangles ((N - 1) * sides * 2 x 3) of a tube.

        Parameters
        ----------
        points : array_like
            The centre line, N >= 2 points x 3 (scene units).
        radius : float
            Tube radius (scene units).
        sides : int
            Vertices on each ring, which is centred on its point and normal to the mean of the
            neighbouring legs.
        """
        pts = check_array("points", points, ndim=2)
        if pts.shape[1] != 3 or pts.shape[0] < 2:
            raise ValueError(f"points must have shape (N >= 2, 3), got {pts.shape}")
        radius = check_positive("radius", radius)
        legs = np.diff(pts, axis=0)
        legs /= np.maximum(np.linalg.norm(legs, axis=1, keepdims=True), 1e-300)
        tangent = np.vstack([legs[:1], legs[:-1] + legs[1:], legs[-1:]])
        tangent /= np.maximum(np.linalg.norm(tangent, axis=1, keepdims=True), 1e-300)
        ref = np.where(np.abs(tangent[:, 2:3]) > 0.9, [[1.0, 0.0, 0.0]], [[0.0, 0.0, 1.0]])
        normal = np.cross(tangent, ref)
        normal /= np.linalg.norm(normal, axis=1, keepdims=True)
        binormal = np.cross(tangent, normal)
        angle = 2 * np.pi * np.arange(sides) / sides
        rings = (pts[:, None, :] + radius * (np.cos(angle)[None, :, None] * normal[:, None, :]
                                             + np.sin(angle)[None, :, None] * binormal[:, None, :]))
        i = np.arange(len(pts) - 1)[:, None] * sides
        j = np.arange(sides)[None, :]
        a, b = i + j, i + (j + 1) % sides
        c, d = a + sides, b + sides
        faces = np.concatenate([np.stack([a, b, d], -1), np.stack([a, d, c], -1)], axis=1)
        return rings.reshape(-1, 3), faces.reshape(-1, 3)

    def set(self, points) -> None:
        """Draw the tube along ``points`` (N x 3, scene units), replacing the previous one."""
        vertices, faces = self.mesh(points, self.radius, self.sides)
        self.vis.set_object(g.TriangularMeshGeometry(vertices.astype(np.float32), faces),
                            _material(self.color))


def cone(vis: meshcat.Visualizer, height: float, radius: float, color: int = 0x808080) -> None:
    """A cone with its apex at the origin of ``vis``, pointing along -z, base at z = +height.

    Place it with ``vis.set_transform(...)`` (an AFM tip under a cantilever's free end).

    Parameters
    ----------
    vis : meshcat.Visualizer
        Where to draw (the cone itself goes to ``vis["shape"]``).
    height, radius : float
        Height and base radius in scene units.
    color : int
        0xRRGGBB.
    """
    height = check_positive("height", height)
    radius = check_positive("radius", radius)
    # meshcat's cone points along +y with its centre at the origin: turn it apex-down and lift it
    fix = translation([0.0, 0.0, height / 2]) @ np.array(
        [[1, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0], [0, 0, 0, 1]], dtype=float)
    vis["shape"].set_object(g.Cylinder(height, radiusTop=0.0, radiusBottom=radius), _material(color))
    vis["shape"].set_transform(fix)


def sphere(vis: meshcat.Visualizer, radius: float, color: int = 0x808080,
           opacity: float = 1.0) -> None:
    """A sphere of ``radius`` scene units centred at the origin of ``vis``, of ``color``
    (0xRRGGBB) and ``opacity`` in (0, 1]."""
    radius = check_positive("radius", radius)
    vis.set_object(g.Sphere(radius), _material(color, opacity))


def polyline(vis: meshcat.Visualizer, points, color: int = 0x202020) -> None:
    """A polyline through ``points`` (N x 3, scene units) at ``vis``, of ``color`` (0xRRGGBB).

    WebGL draws lines one pixel wide whatever their width; use :class:`Segment` for a thick one.
    """
    pts = check_array("points", points, ndim=2)
    if pts.shape[1] != 3 or pts.shape[0] < 2:
        raise ValueError(f"points must have shape (N >= 2, 3), got {pts.shape}")
    vis.set_object(g.Line(g.PointsGeometry(pts.T.astype(np.float32)),
                          g.LineBasicMaterial(color=color)))


# --- the legend ------------------------------------------------------------------------------
@lru_cache(maxsize=8)
def _font(size: int):
    from PIL import ImageFont
    try:
        return ImageFont.load_default(size=size)  # scalable (FreeType) in Pillow >= 10.1
    except (TypeError, ImportError, OSError):  # pragma: no cover - old Pillow or no FreeType
        return ImageFont.load_default()


def _centred_text(draw, x, y, text, font, width=None):
    """Draw ``text`` centred on x, shifted inwards if it would cross the image's edges."""
    left, _, right, _ = draw.textbbox((0, 0), text, font=font)
    x0 = x - (right - left) / 2
    if width is not None:
        x0 = min(max(x0, 1 - left), width - 1 - right)
    draw.text((x0, y), text, fill=(0, 0, 0), font=font)


def tick_labels(values) -> tuple[list[str], int]:
    """Short tick labels for a legend: the values divided by a common 10^exponent.

    The exponent is a multiple of 3, nonzero only when the largest |value| is >= 1000 or below
    0.1, so every label has at most 3 significant digits and 5 characters ("-0.25", "1")
    instead of "1e+03"; the legend's title then says "x 10^exponent" (:func:`legend_title`).

    Parameters
    ----------
    values : array_like
        The tick values (in the legend's unit), finite.

    Returns
    -------
    (labels, exponent) : tuple of (list of str, int)
        ``float(labels[i]) * 10**exponent`` is ``values[i]`` to 3 significant digits of the
        largest value; values below 1e-12 of it are written "0".
    """
    v = check_array("values", values, ndim=1)
    top = float(np.abs(v).max()) if v.size else 0.0
    exponent = 0
    if top > 0 and not 0.1 <= top < 1000:
        exponent = 3 * math.floor(math.log10(top) / 3)
    scaled = v / 10.0 ** exponent
    scaled[np.abs(v) < 1e-12 * top] = 0.0
    return [f"{x:.3g}" for x in scaled], exponent


def legend_title(scale: ColorScale, exponent: int = 0) -> str:
    """``"label [unit]"``, or ``"label [x 10^exponent unit]"`` for ticks from :func:`tick_labels`.

    Parameters
    ----------
    scale : ColorScale
        The scale whose label and unit make the title.
    exponent : int
        The power of ten shared by the tick labels (0: none).
    """
    if exponent == 0:
        return scale.title
    unit = f" {scale.unit}" if scale.unit else ""
    return f"{scale.label} [x 10^{exponent}{unit}]"


def colorbar_png(scale: ColorScale, size_px=(480, 120), n_ticks: int = 5) -> bytes:
    """A horizontal colorbar of ``scale`` with tick labels and ``"label [unit]"``, as PNG bytes.

    Drawn with Pillow (matplotlib's imaging library) in about a millisecond, so that a legend
    can follow a slider: the title on top, the bar in the middle, the tick labels below.

    Parameters
    ----------
    scale : ColorScale
        The scale to draw.
    size_px : (int, int)
        Image width and height in pixels (at least 100 x 40).
    n_ticks : int
        Evenly spaced tick labels from ``vmin`` to ``vmax`` (2 to 21).
    """
    from PIL import Image, ImageDraw

    n_ticks = check_integer("n_ticks", n_ticks, 2, 21)
    width = check_integer("width_px", int(size_px[0]), 100, 4096)
    height = check_integer("height_px", int(size_px[1]), 40, 4096)
    margin = width // 16
    top, bottom = int(0.28 * height), int(0.60 * height)
    img = np.full((height, width, 3), 255, dtype=np.uint8)
    bar = scale.rgb(np.linspace(scale.vmin, scale.vmax, width - 2 * margin))
    img[top:bottom, margin:width - margin] = np.rint(255 * bar).astype(np.uint8)[None, :, :]
    im = Image.fromarray(img)
    draw = ImageDraw.Draw(im)
    font = _font(max(8, int(0.2 * height)))
    labels, exponent = tick_labels(np.linspace(scale.vmin, scale.vmax, n_ticks))
    _centred_text(draw, width / 2, int(0.03 * height), legend_title(scale, exponent), font,
                  width)
    for i, text in enumerate(labels):
        x = margin + i * (width - 2 * margin - 1) / (n_ticks - 1)
        draw.line([(x, bottom), (x, bottom + int(0.05 * height))], fill=(0, 0, 0), width=1)
        _centred_text(draw, x, bottom + int(0.08 * height), text, font, width)
    buf = io.BytesIO()
    im.save(buf, format="PNG", compress_level=1)
    return buf.getvalue()


def text_png(text: str, size_px=(480, 80)) -> bytes:
    """One line of black ``text`` centred on a white image, as PNG bytes (Pillow).

    Parameters
    ----------
    text : str
        The text.
    size_px : (int, int)
        Image width and height in pixels (at least 100 x 20); the font is 60 % of the height.
    """
    from PIL import Image, ImageDraw

    width = check_integer("width_px", int(size_px[0]), 100, 4096)
    height = check_integer("height_px", int(size_px[1]), 20, 4096)
    im = Image.new("RGB", (width, height), (255, 255, 255))
    draw = ImageDraw.Draw(im)
    font = _font(int(0.6 * height))
    _centred_text(draw, width / 2, int(0.15 * height), str(text), font)
    buf = io.BytesIO()
    im.save(buf, format="PNG", compress_level=1)
    return buf.getvalue()


class TextPlate:
    """A line of text in the scene (meshcat draws none): a PNG texture on a thin plate.

    Like :class:`ColorLegend`, the plate lies in the x-z plane, readable from the -y side, with
    its lower-left corner at the origin of ``vis`` (place it with ``vis.set_transform``).

    Parameters
    ----------
    vis : meshcat.Visualizer
        Where to draw.
    text : str
        The text.
    width : float
        Plate width in scene units (its height is ``width / 6``).
    """

    def __init__(self, vis: meshcat.Visualizer, text: str, width: float = 1.0):
        self.vis = vis
        self.width = check_positive("width", width)
        self.text = str(text)
        h = self.width / 6
        material = g.MeshBasicMaterial(map=g.ImageTexture(image=g.PngImage(text_png(self.text))),
                                       color=0xffffff)
        vis["plate"].set_object(g.Box([self.width, self.width / 100, h]), material)
        vis["plate"].set_transform(translation([self.width / 2, 0.0, h / 2]))


def legend_html(scale: ColorScale, n_stops: int = 9, width_px: int = 240) -> str:
    """The legend of ``scale`` as an HTML snippet: a CSS gradient bar, its limits and its unit.

    ``n_stops`` colors (2 to 64) make the gradient; the bar is ``width_px`` pixels wide.
    """
    n_stops = check_integer("n_stops", n_stops, 2, 64)
    stops = scale.rgb(np.linspace(scale.vmin, scale.vmax, n_stops))
    css = ", ".join(f"rgb({int(255 * r)},{int(255 * gg)},{int(255 * b)})" for r, gg, b in stops)
    ticks = [scale.vmin, 0.0, scale.vmax] if scale.vmin < 0 < scale.vmax else [scale.vmin, scale.vmax]
    labels, exponent = tick_labels(ticks)
    spans = "".join(f"<span>{t}</span>" for t in labels)
    title = legend_title(scale, exponent)
    return (f'<div style="width:{width_px}px;font-size:12px"><div>{title}</div>'
            f'<div style="height:12px;background:linear-gradient(to right, {css})"></div>'
            f'<div style="display:flex;justify-content:space-between">{spans}</div></div>')


class ColorLegend:
    """A colorbar plate in the scene (meshcat draws no text: the labels are a PNG texture).

    The plate lies in the x-z plane, readable from the -y side (see :func:`set_camera`), with its
    lower-left corner at the origin of ``vis``; place it with ``vis.set_transform``. The texture
    is re-rendered only when the scale changes (use :func:`nice_ceil` limits to keep that rare).

    Parameters
    ----------
    vis : meshcat.Visualizer
        Where to draw.
    scale : ColorScale
        The scale to show.
    width : float
        Plate width in scene units (its height follows the 4:1 image).
    """

    def __init__(self, vis: meshcat.Visualizer, scale: ColorScale, width: float = 1.6):
        self.vis = vis
        self.width = check_positive("width", width)
        self.scale = None
        self.set(scale)

    def set(self, scale: ColorScale) -> bool:
        """Show ``scale``; return True if the texture had to be redrawn."""
        if scale == self.scale:
            return False
        png = colorbar_png(scale)
        h = self.width / 4
        material = g.MeshBasicMaterial(map=g.ImageTexture(image=g.PngImage(png)), color=0xffffff)
        # thick enough (1 % of its width) that the depth buffer keeps its front and back faces
        # apart: a thinner plate shows the mirrored back texture through the front one
        self.vis["plate"].set_object(g.Box([self.width, self.width / 100, h]), material)
        self.vis["plate"].set_transform(translation([self.width / 2, 0.0, h / 2]))
        self.scale = scale
        return True


def set_camera(vis: meshcat.Visualizer, position) -> None:
    """Put the default camera of viewer ``vis`` at ``position`` (world frame, z up, scene units).

    The camera keeps looking at the world origin, so scene builders centre their objects there.
    """
    x, y, z = _check_point("position", position)
    # the camera node is rotated by +pi/2 about x (three.js is y-up): world (x, y, z) -> (x, z, -y)
    vis["/Cameras/default/rotated/<object>"].set_property("position", [x, z, -y])


#: Vertical field of view of meshcat's default camera in degrees (three.js PerspectiveCamera(75, ...)).
CAMERA_FOV = 75.0


def camera_ndc(points, position, target=(0.0, 0.0, 0.0), fov_deg: float = CAMERA_FOV,
               aspect: float = 1.5) -> np.ndarray:
    """Where ``points`` land on the screen of a camera at ``position`` looking at ``target``.

    A pinhole projection with z up (meshcat's orbit camera), used to check that a scene builder
    frames its objects: a point is in view when both coordinates lie in [-1, 1].

    Parameters
    ----------
    points : array_like, shape (N, 3)
        World positions in scene units.
    position, target : array_like, shape (3,)
        Camera position and the point it looks at (meshcat's default: the origin).
    fov_deg : float
        Vertical field of view in degrees, in (0, 180).
    aspect : float
        Width / height of the view (> 0), e.g. 1.5 for 1200 x 800 pixels.

    Returns
    -------
    ndarray, shape (N, 2)
        Normalised device coordinates (x right, y up); ``inf`` for points behind the camera.
    """
    pts = check_array("points", points, ndim=2)
    if pts.shape[1] != 3:
        raise ValueError(f"points must have shape (N, 3), got {pts.shape}")
    pos, tgt = _check_point("position", position), _check_point("target", target)
    fov = check_range("fov_deg", fov_deg, 0.0, 180.0, "deg", low_inclusive=False,
                      high_inclusive=False)
    aspect = check_positive("aspect", aspect)
    forward = tgt - pos
    if np.linalg.norm(forward) == 0 or np.linalg.norm(np.cross(forward, [0, 0, 1])) == 0:
        raise ValueError("the camera must look at a target other than its position, not straight "
                         f"up or down; got position {pos.tolist()} and target {tgt.tolist()}")
    forward /= np.linalg.norm(forward)
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    d = pts - pos
    depth = d @ forward
    t = math.tan(math.radians(fov) / 2)
    with np.errstate(divide="ignore", invalid="ignore"):
        ndc = np.stack([(d @ right) / (depth * t * aspect), (d @ up) / (depth * t)], -1)
    ndc[depth <= 0] = np.inf
    return ndc


def show_helpers(vis: meshcat.Visualizer, grid: bool = True, axes: bool = True) -> None:
    """Show or hide meshcat's ground grid (the plane z = 0) and its x-y-z axes at the origin.

    Scene builders centre their objects on the origin, where the axes would poke through them,
    and a sample surface at z = 0 would fight with the grid: hide what gets in the way.

    Parameters
    ----------
    vis : meshcat.Visualizer
        Any visualizer of the viewer (the helpers live at its root).
    grid, axes : bool
        Whether to show the grid and the axes.
    """
    vis["/Grid"].set_property("visible", bool(grid))
    vis["/Axes"].set_property("visible", bool(axes))
