"""The 3D view of module (f): the sample and the image being scanned as height fields, and the
tip at its current position.

Scale: one scene unit is :attr:`ImagingScene.unit` metres, a fixed fraction of the sample's
width (the sample is :data:`DEFAULTS` ``["side"]`` units wide), true to scale along x and y;
heights are multiplied by :attr:`ImagingScene.exaggeration` (a round number, stated in the
scene's caption), so that nanometre relief on a micrometre image can be seen. Each field is a
:func:`~afmsmiler.scenes.meshes.height_map_mesh` coloured by height (``"afmhot"``, in nm, um or
mm by the sample's relief: :func:`height_unit`), standing on its own lowest point, decimated
(every s-th row and column) to at most ``max_vertices`` vertices for a big image. The sample lies on the left (x < 0), the image on the
right, the colour legend of the sample below both.

The tip is module (d)'s tip (:func:`~afmsmiler.scenes.contact.tip_mesh` of its outline), drawn
once; while a scan runs, :meth:`ImagingScene.move_tip` only sends a transform, and
:meth:`ImagingScene.show_image` (or :meth:`ImagingScene.show_scan`, from a scan's result)
replaces the image's mesh only when a new line has finished.
Scenes take ``vis=`` (a :class:`meshcat.Visualizer`, or ``tests/recording.py``'s recorder).
"""
from __future__ import annotations

import math

import meshcat
import meshcat.geometry as g
import numpy as np

from ..contact import Tip
from ..parameters import UNITS, read_only
from ..samples import Sample
from ..validation import (check_finite, check_flag, check_instance, check_integer, check_positive,
                          check_shape)
from .camera import readable_width, set_camera, show_helpers
from .colors import ColorScale, nice_ceil
from .contact import tip_mesh
from .legends import ColorLegend, TextPlate
from .meshes import MAX_VERTICES, height_map_mesh
from .transforms import translation
from .view import fit_camera
from .viewer import SceneDisplay, scene_root

__all__ = ["DEFAULTS", "ImagingScene", "decimation", "auto_exaggeration", "height_unit"]

#: Defaults of the scene, in one place.
DEFAULTS = read_only(dict(
    max_vertices=128 * 128,   # per field: smooth in a browser, still 128 x 128 samples
    side=4.0,                 # the sample's width in scene units
    relief=0.15,              # automatic exaggeration: the relief drawn at most this x width
    gap=0.15,                 # between the sample and the image, x the sample's width
    tip_height=0.3,           # drawn tip height, x the sample's width (after exaggeration)
    camera_direction=(0.0, -1.0, 0.9),
    camera_distance=1.25,     # x the extent of both fields (width, or depth if larger)
    cmap="afmhot"))

_TIP_COLOR = 0x8a8a8a

#: The tallest drawn relief, in widths of the field: an exaggeration beyond would only draw a
#: needle (and, far beyond, vertices past float32).
MAX_RELIEF = 1e3


def decimation(shape, max_vertices: int = DEFAULTS["max_vertices"]) -> int:
    """The stride s (every s-th row and column) that leaves at most ``max_vertices`` vertices.

    Parameters
    ----------
    shape : (int, int)
        Rows and columns of the image.
    max_vertices : int
        The most vertices, 4 to :data:`~afmsmiler.scenes.meshes.MAX_VERTICES`.

    Returns
    -------
    int
        s >= 1 with ceil(rows / s) ceil(columns / s) <= max_vertices.
    """
    max_vertices = check_integer("max_vertices", max_vertices, 4, MAX_VERTICES)
    rows, cols = check_shape("shape", shape)
    s = max(1, math.isqrt(rows * cols // max_vertices))
    while math.ceil(rows / s) * math.ceil(cols / s) > max_vertices:
        s += 1
    return s


def _check_exaggeration(exaggeration, width: float, relief: float) -> float:
    """A factor given on the heights, or a ValueError naming it: > 0, and drawing the relief at
    most :data:`MAX_RELIEF` times the field's width tall (beyond, the vertices leave float32)."""
    exaggeration = check_positive("exaggeration", exaggeration)
    if relief > 0 and exaggeration * relief > MAX_RELIEF * width:
        raise ValueError(f"exaggeration must be in (0, {MAX_RELIEF * width / relief:.3g}] for "
                         f"this sample (its relief of {relief:.3g} m drawn at most {MAX_RELIEF:g} "
                         f"times its width of {width:.3g} m tall), got {exaggeration:g}")
    return exaggeration


def auto_exaggeration(width: float, relief: float, fraction: float = DEFAULTS["relief"]) -> float:
    """The round factor (1, 2 or 5 x 10^n) that draws ``relief`` at most ``fraction`` of
    ``width`` tall (at least 1: a rough sample is drawn to scale, never flattened).

    Parameters
    ----------
    width : float
        Width of the field in m.
    relief : float
        Its height range in m (>= 0; 0 gives 1).
    fraction : float
        Drawn relief over width, > 0.

    Returns
    -------
    float
    """
    width = check_positive("width", width, "m")
    fraction = check_positive("fraction", fraction)
    relief = check_finite("relief", relief, "m")
    if relief <= 0.0:
        return 1.0
    target = fraction * width / relief
    if target <= 1.0:
        return 1.0
    exponent = math.floor(math.log10(target))
    best = 10.0 ** exponent
    for mantissa in (2.0, 5.0):
        if mantissa * 10.0 ** exponent <= target:
            best = float(f"{mantissa}e{exponent}")
    return float(f"{best:.1g}")


def height_unit(relief: float) -> str:
    """The legend's unit for a height field of ``relief`` m: nm below 1 um, um below 1 mm, else
    mm (a printed sample of module (h) read in nm would show millions)."""
    return "nm" if relief < UNITS["um"][1] else "um" if relief < UNITS["mm"][1] else "mm"


def _scale_of(values: np.ndarray, cmap: str, unit: str = "nm") -> ColorScale:
    """A colour scale from the lowest value to a round range above it (values in ``unit``)."""
    low = float(values.min())
    span = nice_ceil(float(values.max()) - low, 1e-3)
    return ColorScale(low, low + span, cmap=cmap, label="height", unit=unit)


class ImagingScene(SceneDisplay):
    """The sample and the image as height fields in meshcat, and the tip over the sample.

    Parameters
    ----------
    sample : Sample
        The sample (an image, heights in m) drawn on the left.
    tip : Tip, optional
        Module (d)'s tip, drawn at :meth:`move_tip`'s positions (none if None).
    vis : meshcat.Visualizer, optional
        The root visualizer; by default a new 3D view's (:class:`~afmsmiler.scenes.SceneView`).
    path : str
        Path of this scene in the viewer.
    exaggeration : float, optional
        Factor on all heights (> 0, drawing the sample's relief at most :data:`MAX_RELIEF`
        times its width tall); default :func:`auto_exaggeration` of the sample.
    max_vertices : int
        The most vertices of each field's mesh (4 to
        :data:`~afmsmiler.scenes.meshes.MAX_VERTICES`); larger images are decimated.
    camera : bool
        Place the camera to see both fields from the front, above.

    Attributes
    ----------
    unit : float
        Metres per scene unit.
    exaggeration : float
        The factor on the heights, as the caption states it.
    stride, image_stride : int
        Every how many rows and columns of the sample and of the image a vertex is drawn.
    image_lines : int or None
        The row after the last row of the image given (None before any image).
    """

    def __init__(self, sample: Sample, *, tip: Tip | None = None,
                 vis: meshcat.Visualizer | None = None, path: str = "afmsmiler/imaging",
                 exaggeration: float | None = None,
                 max_vertices: int = DEFAULTS["max_vertices"], camera: bool = True):
        check_instance("sample", sample, Sample)
        if sample.heights.ndim != 2:
            raise ValueError(f"sample must be an image (2-D heights), got shape "
                             f"{sample.heights.shape}")
        if tip is not None:
            check_instance("tip", tip, Tip)
        check_instance("path", path, str)
        camera = check_flag("camera", camera)
        self.max_vertices = check_integer("max_vertices", max_vertices, 4, MAX_VERTICES)
        rows, cols = sample.heights.shape
        self.width = (cols - 1) * sample.pixel_size
        self.depth = (rows - 1) * sample.pixel_size_y
        self.unit = self.width / DEFAULTS["side"]
        relief = float(np.ptp(sample.heights))
        self.exaggeration = (auto_exaggeration(self.width, relief) if exaggeration is None
                             else _check_exaggeration(exaggeration, self.width, relief))
        self.sample = sample
        self.root = scene_root(vis)
        self.vis = self.root[path]
        self.vis.delete()
        gap = DEFAULTS["gap"] * self.width
        # lower-left corners (m) of the two fields: the sample left of x = 0, the image right
        self.sample_origin = (-gap / 2 - self.width, -self.depth / 2)
        self.image_slot = (gap / 2, -self.depth / 2)
        self.stride = decimation(sample.heights.shape, self.max_vertices)
        self.image_stride = None
        self.image_lines = None
        self._image_key = None
        self._image_drawn = False
        self.sample_floor = float(sample.heights.min())
        self.height_unit = height_unit(float(np.ptp(sample.heights)))
        self._per_unit = UNITS[self.height_unit][1]  # m per legend unit
        self.scale = _scale_of(sample.heights / self._per_unit, DEFAULTS["cmap"],
                               self.height_unit)
        self.image_scale = None
        self._draw_field(self.vis["sample"], sample.heights, sample, self.stride,
                         self.sample_origin, self.sample_floor, self.scale)
        # the camera and the legend under the fields, facing the camera
        e = max(2 * self.width + gap, self.depth) / self.unit  # the extent of both fields
        direction = np.asarray(DEFAULTS["camera_direction"], dtype=float)
        self.camera_position = DEFAULTS["camera_distance"] * e * direction / np.linalg.norm(
            direction)
        below = [0.0, -self.depth / 2 / self.unit, -0.1 * e]
        width = min(0.45 * e, readable_width(ColorLegend.TEXT_FRACTION, below,
                                             self.camera_position))
        self.legend = ColorLegend(self.vis["legend"], self.scale, width=width)
        self.legend_corner = np.array([-width / 2, below[1], below[2] - width / 4])
        self.vis["legend"].set_transform(translation(self.legend_corner))
        self.caption = (f"sample (left) and image (right), heights x {self.exaggeration:g}"
                        if self.exaggeration != 1 else "sample (left) and image (right), to scale")
        plate = TextPlate(self.vis["caption"], self.caption, width=width)
        self.caption_plate = plate
        self.vis["caption"].set_transform(translation(
            [-width / 2, below[1], below[2] - width / 4 - 1.2 * width / 6]))
        if camera:
            set_camera(self.root, self.camera_position)
            show_helpers(self.root, grid=False, axes=False)
            # both fields (the image fills its slot later) fill the view
            top = float(np.ptp(sample.heights)) * self.exaggeration / self.unit
            x, y = -self.sample_origin[0] / self.unit, self.depth / 2 / self.unit
            fit_camera(self.vis, margin=0.9, points=[[sx, sy, z] for sx in (-x, x)
                                                     for sy in (-y, y) for z in (0.0, top)])
        self.tip = tip
        self.tip_position = None
        if tip is not None:
            # drawn tip_height x the width tall once exaggerated (to scale across)
            height = DEFAULTS["tip_height"] * self.width / self.exaggeration
            v, f = tip_mesh(tip, height, self.unit)
            self.vis["tip"].set_object(g.TriangularMeshGeometry(v, f),
                                       g.MeshLambertMaterial(color=_TIP_COLOR, side=2))
            self.vis["tip"].set_property("visible", False)

    # -- fields ---------------------------------------------------------------------------
    def _draw_field(self, node, heights, grid: Sample, stride, origin, floor, scale):
        h = heights[::stride, ::stride]
        mesh = height_map_mesh(h - floor, grid.pixel_size * stride, unit=self.unit,
                               pixel_size_y=grid.pixel_size_y * stride, origin=origin,
                               exaggeration=self.exaggeration, values=h / self._per_unit)
        node.set_object(mesh.geometry(scale), g.MeshLambertMaterial(vertexColors=True, side=2))
        return mesh

    def show_image(self, image: Sample, *, lines: int | None = None, first_row: int = 0,
                   force: bool = False) -> bool:
        """Draw an image, or the finished rows of one being scanned, on the right.

        ``image`` holds rows ``first_row`` to ``first_row + rows - 1`` of an image of ``lines``
        rows (a scan's finished lines, as :attr:`ScanResult.channels
        <afmsmiler.imaging.scanner.ScanResult.channels>` gives them); the full image is centred
        in its place, so the rows do not move as lines are added. The mesh is replaced only when
        these rows or the grid differ from the last call's: during a scan, at most once per
        finished line however often this is called. An image of fewer than two (drawn) rows
        removes the mesh.

        Parameters
        ----------
        image : Sample
            The rows to draw (2-D, heights in m), on their own grid (a scan may cover part of the
            sample).
        lines : int, optional
            Rows of the full image, at least ``first_row`` + the image's rows; default the
            image's rows (a complete image).
        first_row : int
            The full image's row that the image's first row is, >= 0.
        force : bool
            Redraw even if nothing changed (new values on the same rows).

        Returns
        -------
        bool
            True if the mesh was sent (or removed), False if nothing changed.
        """
        check_instance("image", image, Sample)
        if image.heights.ndim != 2:
            raise ValueError(f"image must be 2-D, got shape {image.heights.shape}")
        rows, cols = image.heights.shape
        first_row = check_integer("first_row", first_row, 0)
        lines = rows + first_row if lines is None else check_integer(
            "lines", lines, rows + first_row, MAX_VERTICES)
        key = (rows, cols, first_row, lines, image.pixel_size, image.pixel_size_y)
        if key == self._image_key and not force:
            return False
        self._image_key = key
        self.image_lines = first_row + rows
        s = self.image_stride = decimation((lines, cols), self.max_vertices)
        # the full image's rows 0, s, 2s ... that are among the rows given
        start = (-first_row) % s
        done = image.heights[start::s, ::s]
        if done.shape[0] < 2 or done.shape[1] < 2:
            if self._image_drawn:
                self.vis["image"].delete()
                self._image_drawn = False
            return True
        floor = float(done.min())
        self.image_scale = _scale_of(done / self._per_unit, DEFAULTS["cmap"], self.height_unit)
        # the full image centred in its slot (a scan range smaller than the sample, smaller)
        w = (cols - 1) * image.pixel_size
        d = (lines - 1) * image.pixel_size_y
        origin = (self.image_slot[0] + (self.width - w) / 2,
                  -d / 2 + (first_row + start) * image.pixel_size_y)
        h = done
        mesh = height_map_mesh(h - floor, image.pixel_size * s, unit=self.unit,
                               pixel_size_y=image.pixel_size_y * s, origin=origin,
                               exaggeration=self.exaggeration, values=h / self._per_unit)
        self.vis["image"].set_object(mesh.geometry(self.image_scale),
                                     g.MeshLambertMaterial(vertexColors=True, side=2))
        self.image_mesh = mesh
        self._image_drawn = True
        return True

    def show_scan(self, result, channel: str = "height trace") -> bool:
        """Draw a scan's finished lines of one channel (see :meth:`show_image`).

        Parameters
        ----------
        result : ScanResult
            A :class:`~afmsmiler.imaging.scanner.ScanResult` (its ``channels``, ``lines`` and
            ``first_row``), at any time during the scan.
        channel : str
            The channel to draw, a height in m (``"height trace"`` ...).

        Returns
        -------
        bool
            True if the mesh was sent (or removed).
        """
        for attr in ("channels", "lines", "first_row"):
            if not hasattr(result, attr):
                raise TypeError(f"result must be a ScanResult (with channels, lines and "
                                f"first_row), got {type(result).__name__}")
        channels = result.channels
        if channel not in channels:
            if channels:
                raise ValueError(f"channel must be one of {sorted(channels)}, got {channel!r}")
            # no line finished yet: nothing to draw
            changed = self._image_drawn
            if changed:
                self.vis["image"].delete()
            self._image_drawn, self._image_key, self.image_lines = False, None, 0
            return changed
        return self.show_image(channels[channel], lines=result.lines,
                               first_row=result.first_row)

    # -- tip ------------------------------------------------------------------------------
    def move_tip(self, x: float, y: float, z: float) -> None:
        """Put the tip's apex at (x, y, z) over the sample (only a transform is sent).

        Parameters
        ----------
        x, y : float
            Position in m from the sample's first pixel (x along its rows, y along its
            columns).
        z : float
            Height of the apex in m, in the sample's height frame (a height the sample has at
            some pixel touches that pixel's drawn surface).
        """
        x = check_finite("x", x, "m")
        y = check_finite("y", y, "m")
        z = check_finite("z", z, "m")
        if self.tip is None:
            raise ValueError("move_tip needs a scene built with a tip (tip=None was given)")
        position = np.array([self.sample_origin[0] + x, self.sample_origin[1] + y,
                             (z - self.sample_floor) * self.exaggeration]) / self.unit
        matrix = translation(position)
        matrix[2, 2] = self.exaggeration  # the tip's heights exaggerated as the surface's
        if self.tip_position is None:
            self.vis["tip"].set_property("visible", True)
        self.vis["tip"].set_transform(matrix)
        self.tip_position = (x, y, z)

    def update(self, image: Sample | None = None, tip_position=None, *,
               lines: int | None = None, first_row: int = 0) -> None:
        """One step of a scan: the image (redrawn if a line finished) and the tip's position.

        Parameters
        ----------
        image : Sample, optional
            The finished rows so far (see :meth:`show_image`).
        tip_position : (float, float, float), optional
            The apex's (x, y, z) in m (see :meth:`move_tip`).
        lines : int, optional
            Rows of the full image (see :meth:`show_image`).
        first_row : int
            The full image's row that ``image``'s first row is.
        """
        if image is not None:
            self.show_image(image, lines=lines, first_row=first_row)
        if tip_position is not None:
            self.move_tip(*tip_position)
