"""The 3D view of module (d): a rigid tip pressing into a deforming sample surface.

Scale: one scene unit is :attr:`ContactScene.unit` metres, chosen when the scene is built (by
default 20 nm), and lengths are true to scale in all three directions. The sample is a square
of half side ``extent`` (a :func:`~afmsmiler.scenes.meshes.height_map_mesh`, as module (f)'s
images) whose surface follows the contact solution: inside the contact it fits the tip, outside
it is Sneddon's displacement profile (:func:`~afmsmiler.contact.surface_displacement`),
colored by the depth of the depression (legend under the sample). The scene shows the sample cut
away along the plane y = 0: only the far halves (y >= 0) of the sample and of the tip are drawn,
closed by their cross-sections on the cut, so the camera (on the -y side, slightly above) sees
the tip's outline pressing into the depression's profile, as in a textbook figure, instead of
the near edge of the full sample and the flank of the tip. The tip is a mesh of its own shape (a body of revolution,
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

from ..contact import IndentationCurve, Tip, contact_surface
from ..parameters import read_only
from ..validation import check_flag, check_instance, check_integer, check_positive
from .camera import readable_width, set_camera, show_helpers
from .colors import ColorScale, nice_ceil
from .legends import ColorLegend
from .meshes import height_map_mesh
from .transforms import translation
from .viewer import SceneDisplay, scene_root

__all__ = ["DEFAULTS", "ContactScene", "surface_mesh", "tip_mesh", "cut_mesh"]

#: Defaults of the scene, in one place.
DEFAULTS = read_only(dict(
    unit=20e-9, extent=150e-9, n_grid=40, n_angular=48, tip_height=120e-9, depth_floor=1e-9,
    slab=0.35,                       # drawn sample thickness, as a fraction of extent
    camera_direction=(0.25, -1.0, 0.42),  # from the contact, slightly from above
    camera_distance=1.6,             # in units of the extent
    lowered=0.2))                    # the drawing's shift down, in units of the extent

_CUT_COLOR = 0xb89f7a

_TIP_COLOR = 0x8a8a8a

#: The largest drawn size (a length over the scene's unit) in scene units: a million keeps every
#: vertex and the camera's distance well inside float32, the drawing's precision.
MAX_SCENE_SIZE = 1e6


def _check_scale(name: str, length: float, unit: float, low: float = 0.0) -> float:
    """``length / unit``, the drawn size in scene units, or a ValueError naming both (a scene
    too large for float32, or too small for the camera to stand off it)."""
    size = length / unit
    if not low < size <= MAX_SCENE_SIZE:
        raise ValueError(f"{name} / unit (the drawn size in scene units) must be in "
                         f"({low:g}, {MAX_SCENE_SIZE:g}], got {name}={length!r} m over "
                         f"unit={unit!r} m = {size:.3g}")
    return size


def _polar_faces(n_r: int, n_t: int, closed: bool = True) -> np.ndarray:
    """Triangles of a polar grid: vertex 0 is the centre, then n_r rings of n_t vertices.

    ``closed=False`` leaves out the cells between the last and the first point of each ring (a
    sector such as a half disc)."""
    last = n_t if closed else n_t - 1
    faces = [[0, 1 + (j + 1) % n_t, 1 + j] for j in range(last)]
    for i in range(n_r - 1):
        a = 1 + i * n_t
        b = a + n_t
        for j in range(last):
            j1 = (j + 1) % n_t
            faces += [[a + j, a + j1, b + j1], [a + j, b + j1, b + j]]
    return np.asarray(faces, dtype=np.uint32)


def surface_mesh(tip, current, extent, unit, n_grid=DEFAULTS["n_grid"], *, half=False):
    """Vertices (scene units), faces and depths (m) of the deformed sample surface.

    A :func:`~afmsmiler.scenes.meshes.height_map_mesh` of the square grid of ``2 n_grid + 1``
    columns from x = -extent to +extent and as many rows over y (or ``n_grid + 1`` rows from
    y = 0 to +extent if ``half``); the centre of the contact is at the origin.

    Parameters
    ----------
    tip : Tip
        The tip shape.
    current : IndentationCurve
        The current state (its first point is drawn).
    extent : float
        Half the side of the drawn square in m (``extent / unit`` at most
        :data:`MAX_SCENE_SIZE`).
    unit : float
        Metres per scene unit.
    n_grid : int
        Grid steps from the axis to the edge, 1 to 1000.
    half : bool
        Draw only the half y >= 0 (its first row lies on y = 0), for a cut-away view.

    Returns
    -------
    (vertices, faces, depth) : tuple of ndarray
        depth is the downward displacement u of each vertex in m.
    """
    extent = check_positive("extent", extent, "m")
    _check_scale("extent", extent, check_positive("unit", unit, "m"))
    n = check_integer("n_grid", n_grid, 1, 1000)
    half = check_flag("half", half)
    x = np.linspace(-extent, extent, 2 * n + 1)
    y = x[n:] if half else x
    rho = np.hypot(x[None, :], y[:, None])
    # the state the readout gives, an adhesive neck included (the figure draws the same)
    rho_1, where = np.unique(rho, return_inverse=True)  # the grid's symmetry: fewer radii
    depth = contact_surface(tip, current, rho_1)[where].reshape(rho.shape)
    mesh = height_map_mesh(-depth, extent / n, unit=unit, origin=(-extent, y[0]), values=depth)
    return mesh.vertices, mesh.faces, mesh.values


def cut_mesh(vertices, n_grid, slab):
    """The cross-section wall on the plane y = 0 of a half :func:`surface_mesh`.

    Parameters
    ----------
    vertices : ndarray
        Vertices of ``surface_mesh(..., half=True)`` in scene units.
    n_grid : int
        The grid they were made with (their first ``2 n_grid + 1`` vertices lie on y = 0).
    slab : float
        Depth of the wall's flat bottom below z = 0, in scene units (> 0).

    Returns
    -------
    (vertices, faces) : tuple of ndarray
        A strip from the surface profile along the x axis (from -extent to +extent) down to
        z = -slab.
    """
    slab = check_positive("slab", slab)
    v = np.asarray(vertices, dtype=np.float32)
    top = v[:2 * check_integer("n_grid", n_grid, 1, 1000) + 1].copy()
    top[:, 1] = 0.0
    bottom = top.copy()
    bottom[:, 2] = -slab
    n = top.shape[0]
    i = np.arange(n - 1)
    faces = np.concatenate([np.stack([i, i + 1, n + i + 1], -1),
                            np.stack([i, n + i + 1, n + i], -1)])
    return np.vstack([top, bottom]).astype(np.float32), faces.astype(np.uint32)


def tip_mesh(tip, height, unit, n_angular=DEFAULTS["n_angular"], *, half=False):
    """Vertices (scene units, apex at the origin) and faces of a tip, closed by a flat top.

    Parameters
    ----------
    tip : Tip
        The tip shape (the pyramid gets four flat faces, the others are bodies of revolution).
    height : float
        Drawn height in m (``height / unit`` at most :data:`MAX_SCENE_SIZE`).
    unit : float
        Metres per scene unit.
    n_angular : int
        Points per ring for bodies of revolution (of the half ring if ``half``).
    half : bool
        Draw only the half y >= 0, closed by its cross-section on the plane y = 0 (the tip's
        outline), for a cut-away view.

    Returns
    -------
    (vertices, faces) : tuple of ndarray
    """
    unit = check_positive("unit", unit, "m")
    check_instance("tip", tip, Tip)
    _check_scale("height", check_positive("height", height, "m"), unit)
    half = check_flag("half", half)
    x, z = tip.outline(height)
    mid = x.size // 2
    r, z = x[mid:], z[mid:]  # one flank: from the apex outwards
    pyramid = tip.faces == 4  # the model says how the shape is drawn, not its class name
    if pyramid:
        # the outline is cut across the faces; the corners (at 45 deg) lie sqrt(2) further out
        corner = [math.pi / 4, 3 * math.pi / 4, 5 * math.pi / 4, 7 * math.pi / 4]
        theta = np.array([0.0] + corner[:2] + [math.pi]) if half else np.array(corner)
        scale = (np.array([1.0, math.sqrt(2.0), math.sqrt(2.0), 1.0]) if half
                 else np.full(4, math.sqrt(2.0)))
    else:
        n = check_integer("n_angular", n_angular, 3, 2000)
        theta = (np.linspace(0.0, math.pi, n) if half
                 else np.linspace(0.0, 2 * math.pi, n, endpoint=False))
        scale = np.ones(n)
    n_t = theta.size
    rings = r[1:, None] * scale[None, :]
    xs = np.r_[0.0, (rings * np.cos(theta)[None, :]).ravel(), 0.0]
    ys = np.r_[0.0, (rings * np.sin(theta)[None, :]).ravel(), 0.0]
    zs = np.r_[0.0, np.repeat(z[1:], n_t), z[-1]]
    vertices = np.stack([xs, ys, zs], -1) / unit
    n_r = r.size - 1
    faces = [_polar_faces(n_r, n_t, closed=not half)[:, ::-1]]  # outward normals
    top = vertices.shape[0] - 1
    last = 1 + (n_r - 1) * n_t
    lid = [[top, last + j, last + (j + 1) % n_t] for j in range(n_t if not half else n_t - 1)]
    faces.append(np.asarray(lid, dtype=np.uint32))
    if half:  # the cross-section: a strip between the flanks at theta = 0 and theta = pi
        right = 1 + np.arange(n_r) * n_t
        left = right + n_t - 1
        cut = [[0, left[0], right[0]]]
        for i in range(n_r - 1):
            cut += [[right[i], left[i], left[i + 1]], [right[i], left[i + 1], right[i + 1]]]
        faces.append(np.asarray(cut, dtype=np.uint32))
    return vertices.astype(np.float32), np.vstack(faces).astype(np.uint32)


class ContactScene(SceneDisplay):
    """A tip pressing into a deforming sample, in meshcat, to scale.

    Parameters
    ----------
    tip : Tip
        The tip to draw first.
    current : IndentationCurve
        The state to draw first (its first point).
    vis : meshcat.Visualizer, optional
        The root visualizer; by default a new 3D view's (:class:`~afmsmiler.scenes.SceneView`).
    path : str
        Path of this scene in the viewer.
    unit : float
        Metres per scene unit (default 20 nm).
    extent : float
        Half the side of the drawn square of sample in m; ``extent / unit`` in (0.001,
        :data:`MAX_SCENE_SIZE`] scene units (the camera stands off it by 1.6 times that).
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
        check_instance("tip", tip, Tip)
        check_instance("path", path, str)
        camera = check_flag("camera", camera)
        self.unit = check_positive("unit", unit, "m")
        self.extent = check_positive("extent", extent, "m")
        _check_scale("extent", self.extent, self.unit, low=1e-3)  # the camera stands off
        self.root = scene_root(vis)
        self.vis = self.root[path]
        self.vis.delete()
        self._tip = None
        self.depth_scale = ColorScale(0.0, 1.0, cmap="viridis_r", label="depression", unit="nm")
        e = self.extent / self.unit
        direction = np.asarray(DEFAULTS["camera_direction"], dtype=float)
        self.camera_position = DEFAULTS["camera_distance"] * e * direction / np.linalg.norm(direction)
        # its text READABLE_TEXT of the view's height where it stands, under the sample
        below = (DEFAULTS["lowered"] + DEFAULTS["slab"] + 0.25) * e
        width = readable_width(ColorLegend.TEXT_FRACTION, [0.0, 0.0, -below],
                               self.camera_position)
        self.legend = ColorLegend(self.vis["legend"], self.depth_scale, width=width)
        # lowered a little, so that the camera (looking at the origin) sees the tip's shank too
        self.vis.set_transform(translation([0.0, 0.0, -DEFAULTS["lowered"] * e]))
        if camera:
            set_camera(self.root, self.camera_position)
            show_helpers(self.root, grid=False, axes=False)  # the grid would cut the sample
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
        check_instance("tip", tip, Tip)
        check_instance("current", current, IndentationCurve)
        z_s = max(float(current.z_s[0]), 0.0) if current.in_contact[0] else 0.0
        # the drawn tip doubles in height when an indentation would bury 2/3 of it
        height = DEFAULTS["tip_height"] * 2.0 ** max(
            0, math.ceil(math.log2(max(1.5 * z_s / DEFAULTS["tip_height"], 1e-300))))
        if (tip, height) != (self._tip, getattr(self, "tip_height", None)):
            v, f = tip_mesh(tip, height, self.unit, half=True)
            self.vis["tip"].set_object(g.TriangularMeshGeometry(v, f),
                                       g.MeshLambertMaterial(color=_TIP_COLOR, side=2))
            self._tip, self.tip_height = tip, height
        n_grid = DEFAULTS["n_grid"]
        e = self.extent / self.unit
        v, f, depth = surface_mesh(tip, current, self.extent, self.unit, n_grid, half=True)
        floor = DEFAULTS["depth_floor"] * 1e9
        limit = nice_ceil(float(depth.max()) * 1e9, floor)
        # an adhesive neck pulls the surface up (negative depth): the scale reaches down to it
        low = -nice_ceil(-float(depth.min()) * 1e9, floor) if depth.min() < 0 else 0.0
        if (low, limit) != (self.depth_scale.vmin, self.depth_scale.vmax):
            self.depth_scale = ColorScale(low, limit, cmap="viridis_r",
                                            label="depression (< 0: pulled up)" if low else
                                            "depression", unit="nm")
            self.legend.set(self.depth_scale)
        colors = self.depth_scale.rgb(depth * 1e9)
        self.vis["surface"].set_object(g.TriangularMeshGeometry(v, f, colors),
                                       g.MeshLambertMaterial(vertexColors=True, side=2))
        # the sample is drawn thicker than the deepest point of the depression
        self.slab = max(DEFAULTS["slab"] * e, 1.2 * float(depth.max()) / self.unit + 0.05 * e)
        cv, cf = cut_mesh(v, n_grid, self.slab)
        self.vis["cut"].set_object(g.TriangularMeshGeometry(cv, cf),
                                   g.MeshLambertMaterial(color=_CUT_COLOR, side=2))
        # the legend: a caption under the sample's cut face, facing the camera
        width = self.legend.width
        self.legend_corner = np.array([-width / 2, 0.0, -self.slab - 0.05 * e - width / 4])
        self.vis["legend"].set_transform(translation(self.legend_corner))
        apex = float(current.separation[0])
        self.vis["tip"].set_transform(translation([0.0, 0.0, apex / self.unit]))
        self.last_vertices = v
        self.last_apex = apex
