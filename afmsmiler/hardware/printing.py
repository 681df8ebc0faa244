"""An AFM image as a printable object, and the printed object as a sample again.

The source paper's macroscopic AFM scans 3D-printed samples: a seashell surface from an 80 um AFM
image printed 400 times larger (32 mm). :func:`sample_to_mesh` turns a
:class:`~afmsmiler.samples.Sample` into that object: a closed triangle mesh (:mod:`trimesh`) whose
top surface is the height grid scaled by ``lateral_scale`` along x and y and ``vertical_scale``
along z, standing on a base plate ``base_thickness`` thick, with four vertical walls. The mesh is
watertight (every edge shared by exactly two triangles) and its triangles wind consistently with
outward normals, so that a slicer (Cura, PrusaSlicer) reads it as a solid. :func:`save_stl` writes
it as a binary STL in millimetres (the unit slicers assume, :data:`STL_UNIT`).

:func:`mesh_to_sample` reads a printed object back into a :class:`~afmsmiler.samples.Sample` on a
regular grid of pitch ``pitch``: the surface a tip coming down from above meets first, i.e. a ray
cast straight down at every grid point, computed as a z-buffer over the mesh's upward-facing
triangles (the highest triangle over each point, by barycentric interpolation). It works for any
mesh, not only one made here; for one made here at the image's own printed pixel spacing it gives
the image's heights back exactly (to the STL's float32 round-off). The macroscopic AFM's twin then
images the printed object as the real machine images the print.

Geometry (SI, metres, before the STL's mm): pixel ``(row j, column i)`` of the image sits at
``x = i * pixel_size * lateral_scale``, ``y = j * pixel_size_y * lateral_scale``; its top is at
``z = base_thickness + vertical_scale * (h[j, i] - min(h))``; the base plate's underside is the
plane ``z = 0`` (the print bed). Each grid cell is split into two triangles along the diagonal
from pixel ``(j, i)`` to ``(j + 1, i + 1)``, so the top surface is the piecewise-linear surface
through the pixels. Its volume is therefore, exactly,
``sum over cells dx dy / 6 (2 z00 + z10 + 2 z11 + z01)`` (each triangle: its area times the mean of
its three heights).
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..parameters import UNITS, Parameter, read_only
from ..samples import Sample
from ..samples.sample import MAX_PIXELS
from ..validation import check_instance, check_range, check_shape, check_writable_path

__all__ = ["PARAMETERS", "STL_UNIT", "MAX_TRIANGLES", "MAX_PRINT_SIZE", "MAX_RASTER_WORK",
           "sample_to_mesh", "save_stl", "write_stl", "mesh_to_sample", "print_size",
           "triangle_count", "fitting_scale", "seashell", "PrintComparison", "compare_scan"]

#: The unit of an STL file's coordinates: millimetres, as every slicer assumes.
STL_UNIT = "mm"

#: The most triangles of a printed sample: 2^21 (a 1000 x 1000 image), a 100 MB binary STL that
#: trimesh builds and writes in about two seconds.
MAX_TRIANGLES = 1 << 21

#: The largest printed object along any axis in m: a 3D printer's bed is a few hundred mm; a
#: larger object is a unit slip (a nm image scaled as if it were in um).
MAX_PRINT_SIZE = 1.0

#: The most (triangle, grid point) pairs :func:`mesh_to_sample` tests: about a second of numpy.
MAX_RASTER_WORK = 1 << 24

#: The printed sample's parameters (SI; scales are pure numbers, print size / image size).
PARAMETERS = read_only({p.name: p for p in (
    Parameter(name="lateral_scale", unit="", display_unit="x", default=400.0, low=0.0,
              low_inclusive=False, high=1e9, slider_low=1.0, slider_high=1e7, log=True,
              label="lateral scale (print / image)"),
    Parameter(name="vertical_scale", unit="", display_unit="x", default=400.0, low=0.0,
              low_inclusive=False, high=1e9, slider_low=1.0, slider_high=1e7, log=True,
              label="vertical scale (print / image)"),
    Parameter(name="base_thickness", unit="m", display_unit="mm", default=2e-3, low=0.0,
              low_inclusive=False, high=0.1, slider_low=0.4e-3, slider_high=10e-3,
              label="base plate thickness"),
    Parameter(name="pitch", unit="m", display_unit="mm", default=0.2e-3, low=0.0,
              low_inclusive=False, high=0.1, slider_low=0.05e-3, slider_high=2e-3, log=True,
              label="pixel spacing of the printed sample"),
)})

_P = PARAMETERS


def _check_image(sample, name: str = "sample") -> Sample:
    check_instance(name, sample, Sample)
    if sample.heights.ndim != 2:
        raise ValueError(f"{name} must be a 2-D image (rows, columns) to print, got shape "
                         f"{sample.heights.shape}")
    if sample.unit != "m":
        raise ValueError(f"{name} must hold heights in m to print, got a {sample.channel!r} "
                         f"channel in {sample.unit!r}")
    with np.errstate(over="ignore", invalid="ignore"):
        relief = float(np.ptp(sample.heights))
    if not math.isfinite(relief):
        raise ValueError(f"{name} must have a finite relief (max - min of its heights), got "
                         f"heights from {sample.heights.min():g} to {sample.heights.max():g} m")
    return sample


def triangle_count(shape) -> int:
    """Triangles of the printed mesh of an image of ``shape`` (rows, columns).

    Top: two per grid cell; walls: two per boundary segment; base: one per boundary segment (a
    fan around the base's centre), so ``2 (r-1)(c-1) + 6 (r-1) + 6 (c-1)``.

    Parameters
    ----------
    shape : tuple of int
        (rows, columns), each >= 2.

    Returns
    -------
    int

    Raises
    ------
    ValueError
        If ``shape`` is not two integers >= 2.
    """
    rows, cols = check_shape("shape", shape, 2, limit=1 << 60, low=2)
    return 2 * (rows - 1) * (cols - 1) + 6 * (rows - 1) + 6 * (cols - 1)


def print_size(sample: Sample, *, lateral_scale: float = _P["lateral_scale"].default,
               vertical_scale: float | None = None,
               base_thickness: float = _P["base_thickness"].default) -> tuple:
    """The printed object's size (x, y, z) in m: footprint and total height above the bed.

    Parameters
    ----------
    sample : Sample
        A 2-D height image.
    lateral_scale : float
        Printed length per image length along x and y (400: 1 um of image is 0.4 mm of print).
    vertical_scale : float, optional
        Printed height per image height; default ``lateral_scale`` (the shape kept).
    base_thickness : float
        Thickness of the base plate in m.

    Returns
    -------
    tuple of float
        ``(width * lateral_scale, height_extent * lateral_scale,
        base_thickness + vertical_scale * (max(h) - min(h)))``.
    """
    sample = _check_image(sample)
    ls = _P["lateral_scale"].check(lateral_scale)
    vs = ls if vertical_scale is None else _P["vertical_scale"].check(vertical_scale)
    base = _P["base_thickness"].check(base_thickness)
    relief = float(np.ptp(sample.heights))
    return (sample.width * ls, sample.height_extent * ls, base + vs * relief)


def fitting_scale(sample: Sample, bed: tuple = (0.22, 0.22), *, margin: float = 0.0) -> float:
    """The largest lateral scale at which the image's footprint fits on a print bed.

    Parameters
    ----------
    sample : Sample
        A 2-D height image.
    bed : tuple of float
        The bed's (x, y) size in m (a Creality Ender 3, as in the source paper: 220 x 220 mm).
        The image's columns run along the bed's x.
    margin : float
        Free border kept on each side of the bed in m.

    Returns
    -------
    float
        ``min((bed_x - 2 margin) / width, (bed_y - 2 margin) / height_extent)``.
    """
    sample = _check_image(sample)
    try:
        bx, by = (float(b) for b in bed)
    except (TypeError, ValueError):
        raise ValueError(f"bed must be a pair (x, y) in m, got {bed!r}") from None
    if not (math.isfinite(bx) and math.isfinite(by) and bx > 0 and by > 0):
        raise ValueError(f"bed must be a pair of positive sizes in m, got {bed!r}")
    margin = check_range("margin", margin, 0.0, min(bx, by) / 2, "m", high_inclusive=False)
    return min((bx - 2 * margin) / sample.width, (by - 2 * margin) / sample.height_extent)


def sample_to_mesh(sample: Sample, *, lateral_scale: float = _P["lateral_scale"].default,
                   vertical_scale: float | None = None,
                   base_thickness: float = _P["base_thickness"].default):
    """A watertight, printable triangle mesh of a height image, in m.

    Parameters
    ----------
    sample : Sample
        A 2-D height image (heights in m, finite).
    lateral_scale : float
        Printed length per image length along x and y, > 0 (400 prints an 80 um image 32 mm
        wide).
    vertical_scale : float, optional
        Printed height per image height, > 0; default ``lateral_scale`` (the shape kept; a larger
        one exaggerates the relief, as AFM images are usually shown).
    base_thickness : float
        Thickness of the base plate under the lowest pixel in m, > 0.

    Returns
    -------
    trimesh.Trimesh
        Vertices in m: the image's ``rows * columns`` top vertices (row-major, pixel ``(j, i)`` is
        vertex ``j * columns + i``), then the base's boundary ring at ``z = 0``, then the base's
        centre. Watertight, consistently wound, normals outward; its volume is positive.

    Raises
    ------
    TypeError
        If ``sample`` is not a Sample.
    ValueError
        If ``sample`` is not a 2-D height image, a scale or the thickness is out of range, the
        mesh would have more than :data:`MAX_TRIANGLES` triangles or the object be larger than
        :data:`MAX_PRINT_SIZE` along an axis (each naming the parameter), before any work.

    Examples
    --------
    >>> from afmsmiler import samples
    >>> s = samples.rough_surface((33, 33), 2.5e-6, rms=0.5e-6, correlation_length=10e-6, seed=1)
    >>> mesh = sample_to_mesh(s, lateral_scale=400)   # 80 um -> 32 mm
    >>> mesh.is_watertight, round(float(mesh.bounds[1, 0]) * 1e3, 6)
    (True, 32.0)
    """
    import trimesh

    sample = _check_image(sample)
    ls = _P["lateral_scale"].check(lateral_scale)
    vs = ls if vertical_scale is None else _P["vertical_scale"].check(vertical_scale)
    base = _P["base_thickness"].check(base_thickness)
    rows, cols = sample.heights.shape
    n_tri = triangle_count((rows, cols))
    if n_tri > MAX_TRIANGLES:
        raise ValueError(f"sample must give at most {MAX_TRIANGLES} triangles "
                         f"(about {int(math.sqrt(MAX_TRIANGLES / 2))} x "
                         f"{int(math.sqrt(MAX_TRIANGLES / 2))} pixels), got {rows} x {cols} "
                         f"pixels ({n_tri} triangles): resample it first")
    size = print_size(sample, lateral_scale=ls, vertical_scale=vs, base_thickness=base)
    for axis, s, name in zip("xyz", size, ("lateral_scale", "lateral_scale", "vertical_scale")):
        if not s <= MAX_PRINT_SIZE:  # NaN and inf too (heights near the float limit)
            value = vs if name == "vertical_scale" else ls
            raise ValueError(f"{name} = {value:g} makes the print of sample (extent "
                             f"{sample.width:g} x {sample.height_extent:g} m, relief "
                             f"{float(np.ptp(sample.heights)):g} m) {s:g} m along {axis}, more "
                             f"than {MAX_PRINT_SIZE:g} m: check the scale (print / image size)")

    h = sample.heights
    x = np.arange(cols) * (sample.pixel_size * ls)
    y = np.arange(rows) * (sample.pixel_size_y * ls)
    z = base + vs * (h - h.min())
    xx, yy = np.meshgrid(x, y)
    top = np.column_stack([xx.ravel(), yy.ravel(), z.ravel()])

    # top: cell (j, i) with corners a=(j,i), b=(j,i+1), c=(j+1,i+1), d=(j+1,i), counter-clockwise
    # seen from +z (x along columns, y along rows): triangles (a, b, c) and (a, c, d) face up
    idx = np.arange(rows * cols).reshape(rows, cols)
    a, b = idx[:-1, :-1].ravel(), idx[:-1, 1:].ravel()
    c, d = idx[1:, 1:].ravel(), idx[1:, :-1].ravel()
    faces_top = np.concatenate([np.column_stack([a, b, c]), np.column_stack([a, c, d])])

    # the boundary, counter-clockwise seen from above: y = 0 (x up), x = max (y up), y = max
    # (x down), x = 0 (y down); each corner once
    ring = np.concatenate([idx[0, :-1], idx[:-1, -1], idx[-1, :0:-1], idx[:0:-1, 0]])
    n_ring = ring.size
    bottom = top[ring].copy()
    bottom[:, 2] = 0.0
    first_bottom = rows * cols
    centre = first_bottom + n_ring
    vertices = np.vstack([top, bottom, [[x[-1] / 2, y[-1] / 2, 0.0]]])
    t0, t1 = ring, np.roll(ring, -1)
    b0 = first_bottom + np.arange(n_ring)
    b1 = np.roll(b0, -1)
    # walls: travelling counter-clockwise, outside is on the right; (b0, b1, t1) and (b0, t1,
    # t0) wind counter-clockwise seen from outside
    faces_wall = np.concatenate([np.column_stack([b0, b1, t1]), np.column_stack([b0, t1, t0])])
    # base: a fan around the centre, wound clockwise seen from above (its normal points down)
    faces_base = np.column_stack([np.full(n_ring, centre), b1, b0])
    faces = np.concatenate([faces_top, faces_wall, faces_base])
    return trimesh.Trimesh(vertices=vertices, faces=faces, process=False, validate=False)


def save_stl(sample: Sample, path, *, lateral_scale: float = _P["lateral_scale"].default,
             vertical_scale: float | None = None,
             base_thickness: float = _P["base_thickness"].default) -> Path:
    """Write the printable mesh of a height image as a binary STL in mm (:data:`STL_UNIT`).

    Parameters
    ----------
    sample : Sample
        A 2-D height image.
    path : str or os.PathLike
        The file to write (``.stl``), in an existing folder.
    lateral_scale : float
        Printed length per image length (see :func:`sample_to_mesh`).
    vertical_scale : float, optional
        Printed height per image height; default ``lateral_scale``.
    base_thickness : float
        Thickness of the base plate in m.

    Returns
    -------
    pathlib.Path
        The file written.

    Raises
    ------
    ValueError
        If ``path`` is not a writable file or does not end in ``.stl``, or as
        :func:`sample_to_mesh`, before anything is written.
    """
    path = _stl_path(path)
    mesh = sample_to_mesh(sample, lateral_scale=lateral_scale, vertical_scale=vertical_scale,
                          base_thickness=base_thickness)
    return write_stl(mesh, path)


def _stl_path(path) -> str:
    path = check_writable_path("path", path, "an STL file")
    if not path.lower().endswith(".stl"):
        raise ValueError(f"path must end in .stl, got {path!r}")
    return path


def write_stl(mesh, path) -> Path:
    """Write a mesh in m (as :func:`sample_to_mesh` returns) as a binary STL in mm.

    Parameters
    ----------
    mesh : trimesh.Trimesh
        The mesh, coordinates in m (left unchanged).
    path : str or os.PathLike
        The file to write, ending in ``.stl``, in an existing folder.

    Returns
    -------
    pathlib.Path
        The file written.
    """
    import trimesh

    check_instance("mesh", mesh, trimesh.Trimesh)
    path = _stl_path(path)
    scaled = trimesh.Trimesh(vertices=mesh.vertices / UNITS[STL_UNIT][1], faces=mesh.faces,
                             process=False, validate=False)  # a copy in mm, no processing
    data = scaled.export(file_type="stl")  # binary STL: 80-byte header, count, 50 B/triangle
    tmp = f"{path}.part"
    with open(tmp, "wb") as fh:
        fh.write(data)
    os.replace(tmp, path)  # a failed write leaves no half file under the name asked for
    return Path(path)


def _load_mesh(mesh_or_path):
    import trimesh

    if isinstance(mesh_or_path, trimesh.Trimesh):
        return mesh_or_path, 1.0
    try:
        path = os.fspath(mesh_or_path)
    except TypeError:
        raise TypeError(f"mesh_or_path must be a trimesh.Trimesh (in m) or the path of an STL "
                        f"file (in mm), got {type(mesh_or_path).__name__}") from None
    if not os.path.isfile(path):
        raise ValueError(f"mesh_or_path must name an existing STL file, got {path!r}")
    try:
        mesh = trimesh.load(path, file_type="stl", force="mesh", process=False)
    except Exception as exc:  # trimesh raises many kinds on a file that is not an STL
        raise ValueError(f"mesh_or_path {path!r} is not a readable STL file ({exc})") from None
    return mesh, UNITS[STL_UNIT][1]


def mesh_to_sample(mesh_or_path, pitch: float = _P["pitch"].default, *,
                   name: str | None = None) -> Sample:
    """The printed object's top surface as a height image on a grid of spacing ``pitch``.

    At every grid point the height is that of the highest upward-facing triangle above it: what a
    ray cast straight down (or a tip lowered from above) meets first. It is computed as a z-buffer
    (each triangle tested against the grid points inside its bounding box, barycentric
    coordinates, the highest hit kept), in numpy; trimesh's own ray casting needs rtree or
    embree, which the course does not install.

    Parameters
    ----------
    mesh_or_path : trimesh.Trimesh or str or os.PathLike
        A mesh in m (as :func:`sample_to_mesh` returns) or an STL file in mm (as :func:`save_stl`
        writes, or from any CAD program).
    pitch : float
        Grid spacing along x and y in m (the macroscopic AFM's pixel spacing, 0.2 mm in the
        source paper).
    name : str, optional
        The sample's name; default ``"printed sample"``.

    Returns
    -------
    Sample
        Heights in m above the mesh's lowest point (the print bed), pixel size ``pitch``; column
        ``i`` at ``x = xmin + i * pitch``, row ``j`` at ``y = ymin + j * pitch``, as many as fit
        in the mesh's footprint (its bounding box in x and y).

    Raises
    ------
    TypeError
        If ``mesh_or_path`` is neither a mesh nor a path.
    ValueError
        If the file is missing or not an STL, ``pitch`` is out of range or gives more than
        :data:`MAX_PIXELS` pixels or :data:`MAX_RASTER_WORK` tests, or a grid point of the
        footprint lies under no triangle (the mesh is not one surface over its bounding box).
    """
    pitch = _P["pitch"].check(pitch)
    if name is not None:
        check_instance("name", name, str)
    mesh, to_m = _load_mesh(mesh_or_path)
    tri = np.asarray(mesh.triangles, dtype=float) * to_m
    if tri.size == 0:
        raise ValueError("mesh_or_path holds no triangles")
    lo, hi = tri.reshape(-1, 3).min(axis=0), tri.reshape(-1, 3).max(axis=0)
    counts = [int(math.floor((hi[k] - lo[k]) / pitch + 1e-6)) + 1 for k in (0, 1)]
    if counts[0] * counts[1] > MAX_PIXELS or min(counts) < 2:
        raise ValueError(f"pitch must give 2 to {MAX_PIXELS} pixels over the mesh's footprint "
                         f"{hi[0] - lo[0]:g} x {hi[1] - lo[1]:g} m, got pitch = {pitch:g} m "
                         f"({counts[0]} x {counts[1]} pixels)")
    nx, ny = counts
    # upward-facing triangles (a downward ray meets their top side); walls and base drop out
    e1, e2 = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    nz = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]  # twice the signed area projected on xy
    tri = tri[nz > 1e-12 * pitch * pitch]
    txy = (tri[:, :, :2] - lo[:2]) / pitch  # in grid units
    i0 = np.maximum(np.ceil(txy[:, :, 0].min(axis=1) - 1e-6), 0).astype(int)
    i1 = np.minimum(np.floor(txy[:, :, 0].max(axis=1) + 1e-6), nx - 1).astype(int)
    j0 = np.maximum(np.ceil(txy[:, :, 1].min(axis=1) - 1e-6), 0).astype(int)
    j1 = np.minimum(np.floor(txy[:, :, 1].max(axis=1) + 1e-6), ny - 1).astype(int)
    wi, wj = i1 - i0 + 1, j1 - j0 + 1
    keep = (wi > 0) & (wj > 0)
    tri, txy, i0, j0, wi, wj = tri[keep], txy[keep], i0[keep], j0[keep], wi[keep], wj[keep]
    work = int(np.sum(wi * wj)) if tri.size else 0
    kmax, lmax = (int(wi.max()), int(wj.max())) if tri.size else (0, 0)
    if work > MAX_RASTER_WORK or len(tri) * kmax * lmax > 4 * MAX_RASTER_WORK:
        raise ValueError(f"pitch = {pitch:g} m is too fine for this mesh: {work} (triangle, "
                         f"point) tests, at most {MAX_RASTER_WORK}; choose a larger pitch")
    zbuf = np.full(ny * nx, -np.inf)
    x0, y0 = txy[:, 0, 0], txy[:, 0, 1]
    ux, uy = txy[:, 1, 0] - x0, txy[:, 1, 1] - y0
    vx, vy = txy[:, 2, 0] - x0, txy[:, 2, 1] - y0
    det = ux * vy - uy * vx
    za, zb, zc = tri[:, 0, 2], tri[:, 1, 2], tri[:, 2, 2]
    eps = 1e-9
    for da in range(kmax):
        for db in range(lmax):
            sel = (da < wi) & (db < wj)
            if not sel.any():
                continue
            i, j = i0[sel] + da, j0[sel] + db
            px, py = i - x0[sel], j - y0[sel]
            d = det[sel]
            s = (px * vy[sel] - py * vx[sel]) / d  # barycentric weight of vertex 1
            t = (ux[sel] * py - uy[sel] * px) / d  # of vertex 2
            inside = (s >= -eps) & (t >= -eps) & (s + t <= 1 + eps)
            if not inside.any():
                continue
            zs = (za[sel] + s * (zb[sel] - za[sel]) + t * (zc[sel] - za[sel]))[inside]
            np.maximum.at(zbuf, (j * nx + i)[inside], zs)
    if not np.isfinite(zbuf).all():
        missing = int(np.sum(~np.isfinite(zbuf)))
        raise ValueError(f"mesh_or_path: {missing} grid point(s) of the footprint lie under no "
                         f"upward-facing triangle (a hole, or not one surface over its bounding "
                         f"box); pitch = {pitch:g} m")
    heights = zbuf.reshape(ny, nx) - lo[2]
    return Sample(heights, pitch, "printed sample" if name is None else name,
                  metadata={"source": "mesh", "origin": (float(lo[0]), float(lo[1]))})


def seashell(shape=(128, 128), pixel_size: float = 80e-6 / 127, *, height: float = 8e-6,
             rib_height: float = 1.5e-6, ribs: int = 18, growth_period: float = 6e-6) -> Sample:
    """A synthetic scallop-shell surface, the stand-in for the source paper's seashell image.

    A dome (a paraboloid cap over the image) carrying radial ribs that fan out from a hinge at
    the middle of the first row, crossed by faint concentric growth lines: the relief a scallop
    shows under an AFM's 80 um scan. Printed 400x (the paper's scale) it is 32 mm wide and a few
    mm high, a relief the macroscopic AFM's 2.5 um z micro-step resolves.

    Parameters
    ----------
    shape : tuple of int
        (rows, columns), each 2 to 1024.
    pixel_size : float
        Pixel size in m (default: 80 um first to last pixel over 128 pixels).
    height : float
        Height of the dome at its top in m.
    rib_height : float
        Peak-to-valley height of the ribs in m.
    ribs : int
        Number of ribs over the half circle, 1 to 200.
    growth_period : float
        Spacing of the concentric growth lines in m (their height is a tenth of the ribs').

    Returns
    -------
    Sample
        Heights in m, the lowest pixel at 0.
    """
    from ..samples.sample import check_shape as check_sample_shape
    from ..validation import check_integer, check_positive

    checked = check_sample_shape(shape)
    if len(checked) != 2 or max(checked) > 1024:
        raise ValueError(f"shape must be (rows, columns), each 2 to 1024, got {shape!r}")
    rows, cols = checked
    dx = check_positive("pixel_size", pixel_size, "m")
    h0 = check_positive("height", height, "m")
    hr = check_positive("rib_height", rib_height, "m")
    n = check_integer("ribs", ribs, 1, 200)
    period = check_positive("growth_period", growth_period, "m")
    y, x = np.mgrid[0:rows, 0:cols] * dx
    xc, radius = x[0, -1] / 2, max(x[0, -1], y[-1, 0])
    r = np.hypot(x - xc, y)
    theta = np.arctan2(y, x - xc)
    fade = np.clip(r / (0.15 * radius), 0.0, 1.0)  # the ribs start off the hinge
    dome = h0 * (1 - ((x - xc) / radius) ** 2 - ((y - 0.6 * radius) / radius) ** 2)
    rib = 0.5 * hr * np.cos(2 * n * theta) * fade
    growth = 0.05 * hr * np.cos(2 * math.pi * r / period) * fade
    h = dome + rib + growth
    return Sample(h - h.min(), dx, "seashell (synthetic)",
                  metadata=dict(height=h0, rib_height=hr, ribs=n, growth_period=period))


@dataclass(frozen=True)
class PrintComparison:
    """A scan of a printed object against the printed surface (SI units, m).

    Attributes
    ----------
    reference : Sample
        The printed surface on the scan's grid (rows, columns of the scan), its relief above
        its lowest point there.
    image : Sample
        The scan on the same zero (shifted by its mean difference from the reference: both have
        the same mean).
    difference : Sample
        ``image - reference`` in m.
    rms : float
        RMS of the difference in m.
    max_abs : float
        Largest absolute difference in m.
    """

    reference: Sample
    image: Sample
    difference: Sample
    rms: float
    max_abs: float


def compare_scan(reference: Sample, image: Sample) -> PrintComparison:
    """Compare a scan of a printed object with the printed surface on the same grid.

    The scan starts at the reference's first pixel (its origin) and runs on the same pitch; its
    rows and columns are a corner of the reference's (a partial scan compares its finished
    lines). Both are put on one zero, the printed surface's lowest point in that corner: the
    reference as its relief above that point, the scan shifted by the one offset that the
    machine's z zero (its home position, not the bed) leaves unknown, fitted as the difference
    of the means. So the difference shows the shape error alone, and the print and its scan
    read the same heights.

    Parameters
    ----------
    reference : Sample
        The printed surface (e.g. :func:`mesh_to_sample` of the print at the scan's pitch), 2-D,
        heights in m.
    image : Sample
        The scan (2-D, heights in m), on the same pixel sizes (to 1e-9 relative), at most as
        many rows and columns as ``reference``.

    Returns
    -------
    PrintComparison

    Raises
    ------
    ValueError
        If the pixel sizes differ, or the scan is larger than the reference.
    """
    reference, image = _check_image(reference, "reference"), _check_image(image, "image")
    for name, s in (("reference", reference), ("image", image)):  # a printable object's size
        if np.max(np.abs(s.heights)) > MAX_PRINT_SIZE:
            raise ValueError(f"{name} must have heights within +-{MAX_PRINT_SIZE:g} m (a printed "
                             f"object), got up to {np.max(np.abs(s.heights)):g} m")
    for what in ("pixel_size", "pixel_size_y"):
        a, b = getattr(reference, what), getattr(image, what)
        if abs(a - b) > 1e-9 * max(a, b):
            raise ValueError(f"image must have the reference's {what} {a:g} m, got {b:g} m")
    rows, cols = image.shape
    if rows > reference.shape[0] or cols > reference.shape[1]:
        raise ValueError(f"image must fit in the reference's {reference.shape} pixels, got "
                         f"{image.shape}")
    ref = reference.heights[:rows, :cols]
    ref = ref - ref.min()
    img = image.heights - (image.heights.mean() - ref.mean())
    diff = img - ref
    grid = dict(pixel_size=image.pixel_size, pixel_size_y=image.pixel_size_y)
    return PrintComparison(Sample(ref, name="printed surface", **grid),
                           Sample(img, name=image.name or "scan", **grid),
                           Sample(diff, name="scan - printed surface", **grid),
                           float(np.sqrt(np.mean(diff ** 2))), float(np.abs(diff).max()))
