"""The 3D view of module (f): the sample and the image being scanned as height fields, and the
tip at its current position.

Scale: one scene unit is :attr:`ImagingScene.unit` metres, a fixed fraction of the sample's
width (the sample is :data:`DEFAULTS` ``["side"]`` units wide), true to scale along x and y;
heights are multiplied by :attr:`ImagingScene.exaggeration` (a round number, stated in the
scene's caption), so that nanometre relief on a micrometre image can be seen. Each field is a
:func:`~afmsmiler.scenes.meshes.height_map_mesh` coloured by height (``"afmhot"``, in nm),
standing on its own lowest point, decimated (every s-th row and column) to at most
``max_vertices`` vertices for a big image. The sample lies on the left (x < 0), the image on the
right, the colour legend of the sample below both.

The tip is module (d)'s tip (:func:`~afmsmiler.scenes.contact.tip_mesh` of its outline), drawn
once; while a scan runs, :meth:`ImagingScene.move_tip` only sends a transform, and
:meth:`ImagingScene.show_image` replaces the image's mesh only when a new line has finished.
Scenes take ``vis=`` (a :class:`meshcat.Visualizer`, or ``tests/recording.py``'s recorder).
"""
from __future__ import annotations

import math

import meshcat
import meshcat.geometry as g
import numpy as np

from ..contact import Tip
from ..parameters import read_only
from ..samples import Sample
from ..validation import check_finite, check_instance, check_integer, check_positive
from .camera import readable_width, set_camera, show_helpers
from .colors import ColorScale, nice_ceil
from .contact import tip_mesh
from .legends import ColorLegend, TextPlate
from .meshes import MAX_VERTICES, height_map_mesh
from .transforms import translation
from .viewer import get_viewer

__all__ = ["DEFAULTS", "ImagingScene", "decimation", "auto_exaggeration"]

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
    rows, cols = (check_integer("shape", int(n), 1) for n in shape)
    s = max(1, math.isqrt(rows * cols // max_vertices))
    while math.ceil(rows / s) * math.ceil(cols / s) > max_vertices:
        s += 1
    return s


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


def _scale_of(values_nm: np.ndarray, cmap: str) -> ColorScale:
    """A colour scale from the lowest value to a round range above it (nm)."""
    low = float(values_nm.min())
    span = nice_ceil(float(values_nm.max()) - low, 1e-3)
    return ColorScale(low, low + span, cmap=cmap, label="height", unit="nm")


class ImagingScene:
    """The sample and the image as height fields in meshcat, and the tip over the sample.

    Parameters
    ----------
    sample : Sample
        The sample (an image, heights in m) drawn on the left.
    tip : Tip, optional
        Module (d)'s tip, drawn at :meth:`move_tip`'s positions (none if None).
    vis : meshcat.Visualizer, optional
        The root visualizer; by default the kernel's :func:`~afmsmiler.scenes.get_viewer`.
    path : str
        Path of this scene in the viewer.
    exaggeration : float, optional
        Factor on all heights (> 0); default :func:`auto_exaggeration` of the sample.
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
        Rows and columns skipped between vertices of the sample's and the image's meshes.
    image_lines : int or None
        Rows of the image drawn (None before any).
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
        self.max_vertices = check_integer("max_vertices", max_vertices, 4, MAX_VERTICES)
        rows, cols = sample.heights.shape
        self.width = (cols - 1) * sample.pixel_size
        self.depth = (rows - 1) * sample.pixel_size_y
        self.unit = self.width / DEFAULTS["side"]
        relief = float(np.ptp(sample.heights))
        self.exaggeration = (auto_exaggeration(self.width, relief) if exaggeration is None
                             else check_positive("exaggeration", exaggeration))
        self.sample = sample
        self.root = vis if vis is not None else get_viewer()
        self.vis = self.root[path]
        self.vis.delete()
        gap = DEFAULTS["gap"] * self.width
        # lower-left corners (m) of the two fields: the sample left of x = 0, the image right
        self.sample_origin = (-gap / 2 - self.width, -self.depth / 2)
        self.image_slot = (gap / 2, -self.depth / 2)
        self.stride = decimation(sample.heights.shape, self.max_vertices)
        self.image_stride = None
        self.image_lines = None
        self._image_shape = None
        self.sample_floor = float(sample.heights.min())
        self.scale = _scale_of(sample.heights * 1e9, DEFAULTS["cmap"])
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
                               exaggeration=self.exaggeration, values=h * 1e9)
        node.set_object(mesh.geometry(scale), g.MeshLambertMaterial(vertexColors=True, side=2))
        return mesh

    def show_image(self, image: Sample, lines_done: int | None = None) -> bool:
        """Draw the image's first ``lines_done`` rows (all if None) on the right.

        The mesh is replaced only when ``lines_done`` differs from the last call's (at most once
        per finished line during a scan) or for a complete image (``lines_done=None``).

        Parameters
        ----------
        image : Sample
            The image (2-D, heights in m), on its own grid (a scan may cover part of the
            sample).
        lines_done : int, optional
            Rows finished, 0 to the image's rows.

        Returns
        -------
        bool
            True if the mesh was sent (or removed), False if nothing changed.
        """
        check_instance("image", image, Sample)
        if image.heights.ndim != 2:
            raise ValueError(f"image must be 2-D, got shape {image.heights.shape}")
        rows, cols = image.heights.shape
        if lines_done is not None:
            lines_done = check_integer("lines_done", lines_done, 0, rows)
            if lines_done == self.image_lines and image.heights.shape == self._image_shape:
                return False
        n = rows if lines_done is None else lines_done
        self.image_lines, self._image_shape = lines_done, image.heights.shape
        if self.image_stride is None or image.heights.shape != getattr(self, "_stride_shape",
                                                                        None):
            self.image_stride = decimation(image.heights.shape, self.max_vertices)
            self._stride_shape = image.heights.shape
        s = self.image_stride
        done = image.heights[:n]
        if done[::s].shape[0] < 2 or cols < 2:
            self.vis["image"].delete()
            return True
        floor = float(done.min())
        self.image_scale = _scale_of(done * 1e9, DEFAULTS["cmap"])
        # the image centred in its slot (a scan range smaller than the sample is drawn smaller)
        w = (cols - 1) * image.pixel_size
        d = (rows - 1) * image.pixel_size_y
        origin = (self.image_slot[0] + (self.width - w) / 2, -d / 2)
        self.image_mesh = self._draw_field(self.vis["image"], done, image, s, origin, floor,
                                           self.image_scale)
        return True

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

    def update(self, image: Sample | None = None, lines_done: int | None = None,
               tip_position=None) -> None:
        """One step of a scan: the image (if a line finished) and the tip's position.

        Parameters
        ----------
        image : Sample, optional
            The image so far (see :meth:`show_image`).
        lines_done : int, optional
            Rows of ``image`` finished.
        tip_position : (float, float, float), optional
            The apex's (x, y, z) in m (see :meth:`move_tip`).
        """
        if image is not None:
            self.show_image(image, lines_done)
        if tip_position is not None:
            self.move_tip(*tip_position)
