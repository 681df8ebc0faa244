"""Rigid shapes drawn once and moved in place: arrows, segments (a laser beam), tubes (wires),
cones (a tip), spheres and polylines.

All in scene units, in meshcat's world frame (z up). An :class:`Arrow` or a :class:`Segment`
is drawn once and then moved with ``set_transform`` (no new objects per update); a
:class:`Tube` is one triangle mesh per update.
"""
from __future__ import annotations

import meshcat
import meshcat.geometry as g
import numpy as np

from ..validation import check_array, check_integer, check_positive, check_range
from .transforms import check_point, check_visualizer, rotation_between, translation

__all__ = ["Arrow", "Segment", "Tube", "cone", "sphere", "polyline"]


def _material(color, opacity=1.0, **kwargs):
    return g.MeshLambertMaterial(color=color, opacity=opacity, **kwargs)


def _check_color(color) -> int:
    """``color`` as an int 0xRRGGBB, or a ValueError naming it (a float, None or a string would
    reach the browser as a colour three.js cannot read)."""
    return check_integer("color (0xRRGGBB)", color, 0, 0xFFFFFF)



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
        Where to draw (the arrow's own path, e.g. ``SceneView().vis["mod/force"]``).
    color : int
        0xRRGGBB.
    radius : float
        Shaft radius in scene units; the head is 2.5x as wide and ``head_length`` long.
    head_length : float
        Length of the cone head in scene units (shrunk for arrows shorter than the head).
    """

    def __init__(self, vis: meshcat.Visualizer, color: int = 0x202020, radius: float = 0.01,
                 head_length: float = 0.06):
        check_visualizer("vis", vis)
        color = _check_color(color)
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
        """The shaft and head transforms for an arrow from ``start`` along ``vector``
        (None if ``vector`` is 0)."""
        start = check_point("start", start)
        vector = check_point("vector", vector)
        length = float(np.linalg.norm(vector))
        if length < 1e-12:
            return None
        d = vector / length
        rot = np.eye(4)
        rot[:3, :3] = rotation_between([0.0, 1.0, 0.0], d)  # meshcat cylinders lie along y
        head = min(self.head_length, length)
        shaft = length - head
        stretch = np.diag([1.0, max(shaft, 1e-9), 1.0, 1.0])
        shaft_t = translation(start + d * shaft / 2) @ rot @ stretch
        s = head / self.head_length
        head_t = translation(start + d * (shaft + head / 2)) @ rot @ np.diag([s, s, s, 1.0])
        return shaft_t, head_t

    def set(self, start, vector) -> None:
        """Point the arrow from ``start`` along ``vector`` (scene units); hide it if
        ``vector`` is 0."""
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
        check_visualizer("vis", vis)
        color = _check_color(color)
        self.vis = vis
        self.radius = check_positive("radius", radius)
        opacity = check_range("opacity", opacity, 0.0, 1.0, low_inclusive=False)
        vis.set_object(g.Cylinder(1.0, radius=self.radius), _material(color, opacity))
        self._visible = True

    @staticmethod
    def transform(start, end) -> np.ndarray | None:
        """The transform of a unit cylinder spanning ``start`` -> ``end`` (None if they
        coincide)."""
        start = check_point("start", start)
        end = check_point("end", end)
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
        check_visualizer("vis", vis)
        self.vis = vis
        self.color = _check_color(color)
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
    check_visualizer("vis", vis)
    height = check_positive("height", height)
    radius = check_positive("radius", radius)
    color = _check_color(color)
    # meshcat's cone points along +y with its centre at the origin: turn it apex-down and lift it
    fix = translation([0.0, 0.0, height / 2]) @ np.array(
        [[1, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0], [0, 0, 0, 1]], dtype=float)
    vis["shape"].set_object(g.Cylinder(height, radiusTop=0.0, radiusBottom=radius),
                            _material(color))
    vis["shape"].set_transform(fix)


def sphere(vis: meshcat.Visualizer, radius: float, color: int = 0x808080,
           opacity: float = 1.0) -> None:
    """A sphere of ``radius`` scene units centred at the origin of ``vis``, of ``color``
    (0xRRGGBB) and ``opacity`` in (0, 1]."""
    check_visualizer("vis", vis)
    radius = check_positive("radius", radius)
    color = _check_color(color)
    opacity = check_range("opacity", opacity, 0.0, 1.0, low_inclusive=False)
    vis.set_object(g.Sphere(radius), _material(color, opacity))


def polyline(vis: meshcat.Visualizer, points, color: int = 0x202020) -> None:
    """A polyline through ``points`` (N x 3, scene units) at ``vis``, of ``color`` (0xRRGGBB).

    WebGL draws lines one pixel wide whatever their width; use :class:`Segment` for a thick one.
    """
    check_visualizer("vis", vis)
    color = _check_color(color)
    pts = check_array("points", points, ndim=2)
    if pts.shape[1] != 3 or pts.shape[0] < 2:
        raise ValueError(f"points must have shape (N >= 2, 3), got {pts.shape}")
    vis.set_object(g.Line(g.PointsGeometry(pts.T.astype(np.float32)),
                          g.LineBasicMaterial(color=color)))

