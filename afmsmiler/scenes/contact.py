"""The 3D view of module (d): a rigid tip pressing into a deforming sample surface.

Scale: one scene unit is :attr:`ContactScene.unit` metres, chosen when the scene is built (by
default 20 nm), and lengths are true to scale in all three directions. The sample is a disc of
radius ``extent`` whose surface follows the contact solution: inside the contact it fits the tip,
outside it is Sneddon's displacement profile (:func:`~afmsmiler.contact.surface_displacement`),
colored by the depth of the depression. The tip is a mesh of its own shape (a body of revolution,
or four faces for the pyramid) whose apex sits at the separation Z_c - Z_np (-Z_s in contact).

Built once by :class:`ContactScene`; :meth:`ContactScene.update` replaces the surface mesh with
``set_object`` on the same path and moves the tip with ``set_transform`` (its mesh is rebuilt only
when the tip shape changes), always in the kernel's single viewer.
"""
from __future__ import annotations

import math

import meshcat
import meshcat.geometry as g
import numpy as np

from ..contact import IndentationCurve, Pyramidal, Tip, surface_displacement
from ..plots.contact import tip_outline
from ..validation import check_integer, check_positive
from . import primitives as P
from .viewer import get_viewer

__all__ = ["DEFAULTS", "ContactScene", "surface_mesh", "tip_mesh"]

#: Defaults of the scene, in one place.
DEFAULTS = dict(unit=20e-9, extent=150e-9, n_radial=40, n_angular=48, tip_height=120e-9,
                depth_floor=1e-9)

_TIP_COLOR = 0x8a8a8a


def _polar_faces(n_r: int, n_t: int) -> np.ndarray:
    """Triangles of a polar grid: vertex 0 is the centre, then n_r rings of n_t vertices."""
    faces = [[0, 1 + (j + 1) % n_t, 1 + j] for j in range(n_t)]
    for i in range(n_r - 1):
        a = 1 + i * n_t
        b = a + n_t
        for j in range(n_t):
            j1 = (j + 1) % n_t
            faces += [[a + j, a + j1, b + j1], [a + j, b + j1, b + j]]
    return np.asarray(faces, dtype=np.uint32)


def surface_mesh(tip, current, extent, unit, n_radial=DEFAULTS["n_radial"],
                 n_angular=DEFAULTS["n_angular"]):
    """Vertices (scene units), faces and depths (m) of the deformed sample surface.

    Parameters
    ----------
    tip : Tip
        The tip shape.
    current : IndentationCurve
        The current state (its first point is drawn).
    extent : float
        Radius of the drawn disc in m.
    unit : float
        Metres per scene unit.
    n_radial, n_angular : int
        Rings and points per ring of the polar grid.

    Returns
    -------
    (vertices, faces, depth) : tuple of ndarray
        depth is the downward displacement u of each vertex in m.
    """
    extent = check_positive("extent", extent, "m")
    unit = check_positive("unit", unit, "m")
    n_r = check_integer("n_radial", n_radial, 2, 2000)
    n_t = check_integer("n_angular", n_angular, 3, 2000)
    # rings crowd towards the axis, where the contact is
    rho = extent * np.linspace(0.0, 1.0, n_r + 1)[1:] ** 1.5
    z_s = float(current.z_s[0])
    if current.in_contact[0] and z_s > 0:
        u = surface_displacement(tip, z_s, np.r_[0.0, rho])
    else:
        u = np.zeros(n_r + 1)
    theta = np.linspace(0.0, 2 * math.pi, n_t, endpoint=False)
    x = np.r_[0.0, (rho[:, None] * np.cos(theta)[None, :]).ravel()]
    y = np.r_[0.0, (rho[:, None] * np.sin(theta)[None, :]).ravel()]
    depth = np.r_[u[0], np.repeat(u[1:], n_t)]
    vertices = np.stack([x, y, -depth], -1) / unit
    return vertices.astype(np.float32), _polar_faces(n_r, n_t), depth


def tip_mesh(tip, height, unit, n_angular=DEFAULTS["n_angular"]):
    """Vertices (scene units, apex at the origin) and faces of a tip, closed by a flat top.

    Parameters
    ----------
    tip : Tip
        The tip shape (the pyramid gets four flat faces, the others are bodies of revolution).
    height : float
        Drawn height in m.
    unit : float
        Metres per scene unit.
    n_angular : int
        Points per ring for bodies of revolution.

    Returns
    -------
    (vertices, faces) : tuple of ndarray
    """
    unit = check_positive("unit", unit, "m")
    x, z = tip_outline(tip, height)
    half = x.size // 2
    r, z = x[half:], z[half:]  # one flank: from the apex outwards
    n_t = 4 if isinstance(tip, Pyramidal) else check_integer("n_angular", n_angular, 3, 2000)
    # a pyramid's outline is cut across its faces; its corners lie sqrt(2) further out
    scale = math.sqrt(2.0) if n_t == 4 else 1.0
    theta = np.linspace(0.0, 2 * math.pi, n_t, endpoint=False) + (math.pi / 4 if n_t == 4 else 0.0)
    rings = r[1:, None] * scale
    xs = np.r_[0.0, (rings * np.cos(theta)[None, :]).ravel(), 0.0]
    ys = np.r_[0.0, (rings * np.sin(theta)[None, :]).ravel(), 0.0]
    zs = np.r_[0.0, np.repeat(z[1:], n_t), z[-1]]
    vertices = np.stack([xs, ys, zs], -1) / unit
    faces = _polar_faces(r.size - 1, n_t)[:, ::-1]  # outward normals
    top = vertices.shape[0] - 1
    last = 1 + (r.size - 2) * n_t
    lid = [[top, last + j, last + (j + 1) % n_t] for j in range(n_t)]
    return vertices.astype(np.float32), np.vstack([faces, np.asarray(lid, dtype=np.uint32)])


class ContactScene:
    """A tip pressing into a deforming sample, in meshcat, to scale.

    Parameters
    ----------
    tip : Tip
        The tip to draw first.
    current : IndentationCurve
        The state to draw first (its first point).
    vis : meshcat.Visualizer, optional
        The root visualizer; by default the kernel's :func:`~afmsmiler.scenes.get_viewer`.
    path : str
        Path of this scene in the viewer.
    unit : float
        Metres per scene unit (default 20 nm).
    extent : float
        Radius of the drawn sample disc in m.
    camera : bool
        Place the camera to look at the contact slightly from above.

    Attributes
    ----------
    unit : float
        Metres per scene unit.
    depth_scale : ColorScale
        Colors of the depression depth, in nm.
    """

    def __init__(self, tip, current, *, vis: meshcat.Visualizer | None = None,
                 path: str = "afmsmiler/contact", unit: float = DEFAULTS["unit"],
                 extent: float = DEFAULTS["extent"], camera: bool = True):
        if not isinstance(tip, Tip):
            raise ValueError(f"tip must be a Tip, got {tip!r}")
        self.unit = check_positive("unit", unit, "m")
        self.extent = check_positive("extent", extent, "m")
        self.root = vis if vis is not None else get_viewer()
        self.vis = self.root[path]
        self.vis.delete()
        self._tip = None
        self.depth_scale = P.ColorScale(0.0, 1.0, cmap="viridis_r", label="depression", unit="nm")
        if camera:
            P.set_camera(self.root, [self.extent / self.unit * 1.6, -self.extent / self.unit * 1.6,
                                     self.extent / self.unit * 0.9])
        self.update(tip, current)

    def update(self, tip, current) -> None:
        """Redraw the surface and move (or, for a new shape, rebuild) the tip.

        Parameters
        ----------
        tip : Tip
            The tip shape.
        current : IndentationCurve
            The state to draw (its first point).
        """
        if not isinstance(current, IndentationCurve):
            raise ValueError(f"current must be an IndentationCurve, got {current!r}")
        if tip != self._tip:
            v, f = tip_mesh(tip, DEFAULTS["tip_height"], self.unit)
            self.vis["tip"].set_object(g.TriangularMeshGeometry(v, f),
                                       g.MeshLambertMaterial(color=_TIP_COLOR, opacity=0.9))
            self._tip = tip
        v, f, depth = surface_mesh(tip, current, self.extent, self.unit)
        limit = P.nice_ceil(float(depth.max()) * 1e9, DEFAULTS["depth_floor"] * 1e9)
        if limit != self.depth_scale.vmax:
            self.depth_scale = P.ColorScale(0.0, limit, cmap="viridis_r", label="depression",
                                            unit="nm")
        colors = self.depth_scale.rgb(depth * 1e9)
        self.vis["surface"].set_object(g.TriangularMeshGeometry(v, f, colors),
                                       g.MeshLambertMaterial(vertexColors=True, side=2))
        apex = float(current.separation[0])
        self.vis["tip"].set_transform(P.translation([0.0, 0.0, apex / self.unit]))
        self.last_vertices = v
        self.last_apex = apex
