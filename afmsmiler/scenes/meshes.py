"""Triangle meshes with one scalar per vertex, coloured by a :class:`~.colors.ColorScale`.

- :func:`beam_mesh`: a deformable box beam following a centre-line deflection z(x), with one
  scalar per vertex on the top, bottom and side faces (the sides carry the values through the
  thickness) and on both end caps.
- :func:`height_map_mesh`: a regular grid of heights (a sample surface, an AFM image), in SI,
  as a surface in scene units.
- :func:`hollow_cylinder_mesh` and :func:`prism_mesh`: plain solids of the instrument scene (a
  piezo tube, a knurled knob), vertices and triangles only.

Both return a :class:`ScalarMesh`, whose :meth:`ScalarMesh.geometry` is the meshcat
``TriangularMeshGeometry`` with vertex colours.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import meshcat.geometry as g
import numpy as np

from ..validation import check_array, check_integer, check_positive
from .colors import ColorScale

#: The most vertices a mesh may have: a 2048 x 2048 height map (an AFM image of that size), or a
#: beam of as many; built in about a second, and already more than a browser draws smoothly.
MAX_VERTICES = 2048 * 2048

__all__ = ["ScalarMesh", "beam_mesh", "beam_faces", "height_map_mesh", "MAX_VERTICES",
           "hollow_cylinder_mesh", "prism_mesh", "knurl_outline"]


def _check_vertices(name: str, n_vertices: int, sizes: str) -> None:
    if n_vertices > MAX_VERTICES:
        raise ValueError(f"{name} must make at most {MAX_VERTICES} vertices, got {sizes}: "
                         f"{n_vertices} vertices")


def _grid_faces(rows: int, cols: int, base: int) -> np.ndarray:
    """Two triangles per cell of a rows x cols vertex grid numbered base + r * cols + c.

    Seen from +z with rows along +y and columns along +x, the triangles turn clockwise (their
    normals point to -z); reverse each one (``[:, ::-1]``) for a surface facing +z."""
    r, c = np.meshgrid(np.arange(rows - 1), np.arange(cols - 1), indexing="ij")
    a = base + r * cols + c
    b, d, e = a + cols, a + cols + 1, a + 1
    return np.concatenate([np.stack([a, b, d], -1).reshape(-1, 3),
                           np.stack([a, d, e], -1).reshape(-1, 3)])


def _beam_vertices(n_length: int, n_thickness: int) -> int:
    return 2 * n_length * n_thickness + 4 * n_length + 4 * n_thickness


@lru_cache(maxsize=16)
def beam_faces(n_length: int, n_thickness: int) -> np.ndarray:
    """Triangle indices of a :func:`beam_mesh` with the given numbers of stations (cached).

    The vertex blocks, in order: side y = -w/2 (n_length x n_thickness), side y = +w/2 (same),
    top (n_length x 2), bottom (n_length x 2), clamp end cap (2 x n_thickness), free end cap
    (2 x n_thickness).

    Parameters
    ----------
    n_length : int
        Stations along the beam, 2 to :data:`MAX_VERTICES`.
    n_thickness : int
        Levels through the thickness, 2 to 1000.

    Raises
    ------
    ValueError
        If a number is out of range or the mesh would have more than :data:`MAX_VERTICES`
        vertices.
    """
    nl = check_integer("n_length", n_length, 2, MAX_VERTICES)
    nt = check_integer("n_thickness", n_thickness, 2, 1000)
    _check_vertices("n_length and n_thickness", _beam_vertices(nl, nt),
                    f"n_length={nl} and n_thickness={nt}")
    blocks = [(nl, nt), (nl, nt), (nl, 2), (nl, 2), (2, nt), (2, nt)]
    faces, base = [], 0
    for rows, cols in blocks:
        faces.append(_grid_faces(rows, cols, base))
        base += rows * cols
    out = np.concatenate(faces).astype(np.uint32)
    out.setflags(write=False)
    return out


@dataclass(frozen=True)
class ScalarMesh:
    """A triangle mesh with one scalar value per vertex (:func:`beam_mesh`,
    :func:`height_map_mesh`).

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


def beam_mesh(x, deflection, width: float, thickness: float, values, *, slope=None) -> ScalarMesh:
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
    ScalarMesh
        ``2 n_length n_thickness + 4 n_length + 4 n_thickness`` vertices.

    Raises
    ------
    ValueError
        If the shapes disagree, a value is not finite or the mesh would have more than
        :data:`MAX_VERTICES` vertices.
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
    _check_vertices("values", _beam_vertices(nl, nt), f"shape {values.shape}")
    s = (np.gradient(z, x, edge_order=2) if slope is None
         else check_array("slope", slope, ndim=1, size=nl))

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
    return ScalarMesh(vertices, beam_faces(nl, nt), vals)



def height_map_mesh(heights, pixel_size: float, *, unit: float, pixel_size_y: float | None = None,
                    origin=(0.0, 0.0), exaggeration: float = 1.0, values=None) -> ScalarMesh:
    """A regular grid of heights as a surface in scene units: two triangles per grid cell.

    Vertex ``(i, j)`` (row i, column j, numbered ``i * columns + j``) lies at
    ``x = x0 + j * pixel_size``, ``y = y0 + i * pixel_size_y``, ``z = exaggeration *
    heights[i, j]``, all divided by ``unit``: rows run along y (an AFM image's slow axis),
    columns along x (the fast axis), as in :class:`afmsmiler.samples.Sample`. The triangles
    face +z (counter-clockwise seen from above).

    Parameters
    ----------
    heights : array_like, shape (rows, columns)
        Heights in m, finite, at least 2 x 2.
    pixel_size : float
        Distance between neighbouring columns (along x) in m, > 0.
    unit : float
        Metres per scene unit, > 0.
    pixel_size_y : float, optional
        Distance between neighbouring rows (along y) in m, > 0; default ``pixel_size``.
    origin : (float, float)
        Position (x0, y0) of vertex (0, 0) in m.
    exaggeration : float
        Factor on the heights (> 0): 1 draws the surface to scale.
    values : array_like, shape (rows, columns), optional
        The scalar to colour each vertex by (in the caller's unit); default ``heights`` (m).

    Returns
    -------
    ScalarMesh
        ``rows * columns`` vertices (float32) and ``2 (rows - 1) (columns - 1)`` triangles.

    Raises
    ------
    ValueError
        If a parameter is out of range, ``values`` does not have the shape of ``heights``, the
        grid has more than :data:`MAX_VERTICES` points, or a vertex would be too far away for
        float32 (the drawing's precision).

    Examples
    --------
    >>> mesh = height_map_mesh([[0.0, 1e-9], [2e-9, 3e-9]], 10e-9, unit=1e-9)
    >>> mesh.vertices.tolist()
    [[0.0, 0.0, 0.0], [10.0, 0.0, 1.0], [0.0, 10.0, 2.0], [10.0, 10.0, 3.0]]
    >>> mesh.faces.tolist()
    [[3, 2, 0], [1, 3, 0]]
    """
    h = check_array("heights", heights, "m", ndim=2)
    rows, cols = h.shape
    if rows < 2 or cols < 2:
        raise ValueError(f"heights must have at least 2 x 2 points, got shape {h.shape}")
    _check_vertices("heights", rows * cols, f"shape {h.shape}")
    dx = check_positive("pixel_size", pixel_size, "m")
    dy = dx if pixel_size_y is None else check_positive("pixel_size_y", pixel_size_y, "m")
    unit = check_positive("unit", unit, "m")
    x0, y0 = check_array("origin", origin, "m", ndim=1, size=2)
    exaggeration = check_positive("exaggeration", exaggeration)
    vals = h if values is None else check_array("values", values, ndim=2)
    if vals.shape != h.shape:
        raise ValueError(f"values must have the shape of heights {h.shape}, got {vals.shape}")
    reach = max(abs(x0), abs(x0 + dx * (cols - 1)), abs(y0), abs(y0 + dy * (rows - 1)),
                float(np.abs(h).max()) * exaggeration) / unit
    if not reach <= float(np.finfo(np.float32).max) or not math.isfinite(exaggeration / unit):
        raise ValueError(f"heights, pixel sizes and origin divided by unit must stay below "
                         f"{float(np.finfo(np.float32).max):.3g} scene units, got {reach:.3g} "
                         f"(unit={unit!r} m)")
    vertices = np.empty((rows, cols, 3), dtype=np.float32)
    vertices[..., 0] = ((x0 + dx * np.arange(cols)) / unit)[None, :]
    vertices[..., 1] = ((y0 + dy * np.arange(rows)) / unit)[:, None]
    vertices[..., 2] = h * (exaggeration / unit)
    faces = _grid_faces(rows, cols, 0)[:, ::-1].astype(np.uint32)
    return ScalarMesh(vertices.reshape(-1, 3), faces, vals.ravel())


def hollow_cylinder_mesh(outer_radius: float, inner_radius: float, length: float,
                         sides: int = 32) -> tuple[np.ndarray, np.ndarray]:
    """Vertices and triangles of a hollow cylinder (a piezo tube) along z, centred at the origin.

    Parameters
    ----------
    outer_radius, inner_radius : float
        Radii in scene units, ``0 < inner_radius < outer_radius``.
    length : float
        Length along z in scene units, > 0.
    sides : int
        Vertices around each ring, 3 to 256.

    Returns
    -------
    (vertices, faces) : tuple of ndarray
        ``4 sides`` vertices (float32) and ``8 sides`` triangles: outer and inner walls and the
        two end rings.
    """
    ro = check_positive("outer_radius", outer_radius)
    ri = check_positive("inner_radius", inner_radius)
    if not ri < ro:
        raise ValueError(f"inner_radius must be below outer_radius = {ro:g}, got {ri:g}")
    h = check_positive("length", length) / 2
    n = check_integer("sides", sides, 3, 256)
    a = 2 * np.pi * np.arange(n) / n
    c, s = np.cos(a), np.sin(a)
    rings = [np.stack([r * c, r * s, np.full(n, z)], -1)
             for r, z in ((ro, -h), (ro, h), (ri, -h), (ri, h))]
    j = np.arange(n)
    k = (j + 1) % n

    def band(p, q):  # quads between ring p and ring q (vertex blocks of n)
        return np.concatenate([np.stack([p * n + j, p * n + k, q * n + k], -1),
                               np.stack([p * n + j, q * n + k, q * n + j], -1)])
    faces = np.concatenate([band(0, 1), band(3, 2), band(1, 3), band(2, 0)])
    return np.concatenate(rings).astype(np.float32), faces.astype(np.uint32)


def prism_mesh(outline, length: float) -> tuple[np.ndarray, np.ndarray]:
    """Vertices and triangles of a prism: a star-shaped outline in x-y extruded along z.

    Used for knurled knobs and thumb wheels (an outline with ridges), centred at the origin.

    Parameters
    ----------
    outline : array_like, shape (n, 2)
        The outline's corners in order, scene units, n from 3 to 1024, star-shaped about the
        origin (every corner seen from the origin), so the end caps are fans from the centre.
    length : float
        Length along z in scene units, > 0.

    Returns
    -------
    (vertices, faces) : tuple of ndarray
        ``2 n + 2`` vertices (float32) and ``4 n`` triangles.
    """
    xy = check_array("outline", outline, ndim=2)
    if xy.shape[1] != 2 or not 3 <= xy.shape[0] <= 1024:
        raise ValueError(f"outline must have shape (n, 2) with 3 <= n <= 1024, got {xy.shape}")
    h = check_positive("length", length) / 2
    n = xy.shape[0]
    bottom = np.column_stack([xy, np.full(n, -h)])
    top = np.column_stack([xy, np.full(n, h)])
    centres = np.array([[0.0, 0.0, -h], [0.0, 0.0, h]])
    j = np.arange(n)
    k = (j + 1) % n
    walls = np.concatenate([np.stack([j, k, n + k], -1), np.stack([j, n + k, n + j], -1)])
    caps = np.concatenate([np.stack([np.full(n, 2 * n), k, j], -1),
                           np.stack([np.full(n, 2 * n + 1), n + j, n + k], -1)])
    vertices = np.concatenate([bottom, top, centres]).astype(np.float32)
    return vertices, np.concatenate([walls, caps]).astype(np.uint32)


def knurl_outline(radius: float, ridges: int = 24, depth: float = 0.08) -> np.ndarray:
    """The outline of a knurled wheel: ``2 ridges`` corners alternating between ``radius`` and
    ``radius (1 - depth)`` (for :func:`prism_mesh`).

    Parameters
    ----------
    radius : float
        Outer radius in scene units.
    ridges : int
        Ridges around the wheel.
    depth : float
        Depth of a groove as a fraction of the radius.

    Returns
    -------
    ndarray, shape (2 ridges, 2)
    """
    a = np.pi * np.arange(2 * ridges) / ridges
    r = np.where(np.arange(2 * ridges) % 2 == 0, radius, radius * (1 - depth))
    return np.column_stack([r * np.cos(a), r * np.sin(a)])
