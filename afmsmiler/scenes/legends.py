"""Legends and text of a 3D scene.

In a :class:`~afmsmiler.scenes.SceneView` a legend is screen-space HTML in the view's corner
(:func:`legend_html` for a colorbar; a line of text for a caption), so it never tilts, clips or
hides the scene. Drawn into another visualizer (a test's recorder, meshcat's own server), meshcat
draws no text, so a legend is a PNG texture (rendered by Pillow in about a millisecond) on a thin
plate: :class:`ColorLegend` (a colorbar with its tick labels and unit) and :class:`TextPlate`
(one line of text).
"""
from __future__ import annotations

import html
import io
import math
from functools import lru_cache

import meshcat
import meshcat.geometry as g
import numpy as np

from ..validation import check_array, check_instance, check_integer, check_positive
from .colors import ColorScale
from .transforms import check_visualizer, translation

__all__ = ["colorbar_png", "text_png", "legend_html", "tick_labels", "legend_title",
           "ColorLegend", "TextPlate"]


def _view(vis):
    """The 3D view ``vis`` draws into (its legend is screen-space HTML), or None (a recorder:
    the legend is drawn in the scene as a textured plate)."""
    from .view import view_of
    return view_of(vis)


@lru_cache(maxsize=8)
def _font(size: int):
    from PIL import ImageFont
    try:
        return ImageFont.load_default(size=size)  # scalable (FreeType) in Pillow >= 10.1
    except (TypeError, ImportError, OSError):  # pragma: no cover - old Pillow or no FreeType
        return ImageFont.load_default()


#: Font size of a colorbar's title and tick labels, as a fraction of its image's height.
_COLORBAR_FONT = 0.25
#: Font size of a text plate, as a fraction of its image's height.
_TEXT_FONT = 0.6


def _fitting_font(draw, text, size, width):
    """The font of ``size`` px, or the largest smaller one (>= 8 px) in which ``text`` fits in
    ``width`` px (a long title shrinks instead of spilling over the plate's edges)."""
    for s in range(size, 7, -1):  # bounded: at most size - 7 measures
        left, _, right, _ = draw.textbbox((0, 0), text, font=_font(s))
        if right - left <= width:
            return _font(s)
    return _font(8)


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
    check_instance("scale", scale, ColorScale)
    exponent = check_integer("exponent", exponent, -330, 330)  # the powers of ten of a float
    if exponent == 0:
        return scale.title
    unit = f" {scale.unit}" if scale.unit else ""
    return f"{scale.label} [x 10^{exponent}{unit}]"


def colorbar_png(scale: ColorScale, size_px=(480, 120), n_ticks: int = 5) -> bytes:
    """A horizontal colorbar of ``scale`` with tick labels and ``"label [unit]"``, as PNG bytes.

    Drawn with Pillow (matplotlib's imaging library) in about a millisecond, so that a legend
    can follow a slider: the title on top, the bar in the middle, the tick labels below, their
    font a quarter of the image's height (a title too long for the width gets a smaller one).

    Parameters
    ----------
    scale : ColorScale
        The scale to draw.
    size_px : (int, int)
        Image width and height in pixels (100 to 4096 wide, 40 to 4096 high).
    n_ticks : int
        Evenly spaced tick labels from ``vmin`` to ``vmax`` (2 to 21).
    """
    check_instance("scale", scale, ColorScale)
    from PIL import Image, ImageDraw

    n_ticks = check_integer("n_ticks", n_ticks, 2, 21)
    if not isinstance(size_px, (tuple, list)) or len(size_px) != 2:
        raise ValueError(f"size_px must be (width, height) in pixels, at least 100 x 40, got "
                         f"{size_px!r:.60}")
    width = check_integer("size_px[0] (the width)", size_px[0], 100, 4096)
    height = check_integer("size_px[1] (the height)", size_px[1], 40, 4096)
    margin = width // 16
    top, bottom = int(0.32 * height), int(0.56 * height)
    img = np.full((height, width, 3), 255, dtype=np.uint8)
    bar = scale.rgb(np.linspace(scale.vmin, scale.vmax, width - 2 * margin))
    img[top:bottom, margin:width - margin] = np.rint(255 * bar).astype(np.uint8)[None, :, :]
    im = Image.fromarray(img)
    draw = ImageDraw.Draw(im)
    size = max(8, int(_COLORBAR_FONT * height))
    font = _font(size)
    labels, exponent = tick_labels(np.linspace(scale.vmin, scale.vmax, n_ticks))
    title = legend_title(scale, exponent)
    _centred_text(draw, width / 2, int(0.02 * height), title, _fitting_font(draw, title, size,
                                                                            width - 4), width)
    for i, text in enumerate(labels):
        x = margin + i * (width - 2 * margin - 1) / (n_ticks - 1)
        draw.line([(x, bottom), (x, bottom + int(0.04 * height))], fill=(0, 0, 0),
                  width=max(1, height // 60))
        _centred_text(draw, x, bottom + int(0.05 * height), text, font, width)
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
    font = _font(int(_TEXT_FONT * height))
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

    #: Height of a line of its text as a fraction of the plate's width (the font is 60 % of the
    #: 80-pixel-high image, the plate 1/6 as high as wide); see :attr:`text_height`.
    TEXT_FRACTION = _TEXT_FONT / 6

    def __init__(self, vis: meshcat.Visualizer, text: str, width: float = 1.0):
        check_visualizer("vis", vis)
        self.text = check_instance("text", text, str)
        self.vis = vis
        self.width = check_positive("width", width)
        view = _view(vis)
        if view is not None:  # screen-space text in the view's legend: never tilted or clipped
            view.set_legend_part(vis.path.lower(), f"<div>{html.escape(self.text)}</div>")
            return
        h = self.width / 6
        material = g.MeshBasicMaterial(map=g.ImageTexture(image=g.PngImage(text_png(self.text))),
                                       color=0xffffff)
        vis["plate"].set_object(g.Box([self.width, self.width / 100, h]), material)
        vis["plate"].set_transform(translation([self.width / 2, 0.0, h / 2]))

    @property
    def text_height(self) -> float:
        """Height of a line of the plate's text in scene units (its font size): size the plate
        with :func:`~afmsmiler.scenes.camera.readable_width` so that this reads on screen."""
        return self.TEXT_FRACTION * self.width


def legend_html(scale: ColorScale, n_stops: int = 9, width_px: int = 240) -> str:
    """The legend of ``scale`` as an HTML snippet: a CSS gradient bar, its limits and its unit.

    ``n_stops`` colors (2 to 64) make the gradient; the bar is ``width_px`` pixels wide (40 to
    4096).
    """
    check_instance("scale", scale, ColorScale)
    n_stops = check_integer("n_stops", n_stops, 2, 64)
    width_px = check_integer("width_px", width_px, 40, 4096)
    stops = scale.rgb(np.linspace(scale.vmin, scale.vmax, n_stops))
    css = ", ".join(f"rgb({int(255 * r)},{int(255 * gg)},{int(255 * b)})" for r, gg, b in stops)
    ticks = ([scale.vmin, 0.0, scale.vmax] if scale.vmin < 0 < scale.vmax
             else [scale.vmin, scale.vmax])
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

    #: Height of its tick labels as a fraction of the plate's width (the font is a quarter of
    #: the image's height, the plate 1/4 as high as wide); see :attr:`text_height`.
    TEXT_FRACTION = _COLORBAR_FONT / 4

    def __init__(self, vis: meshcat.Visualizer, scale: ColorScale, width: float = 1.6):
        check_visualizer("vis", vis)
        self.vis = vis
        self.width = check_positive("width", width)
        self.scale = None
        self.set(scale)

    @property
    def text_height(self) -> float:
        """Height of a line of the plate's text in scene units (its font size): size the plate
        with :func:`~afmsmiler.scenes.camera.readable_width` so that this reads on screen."""
        return self.TEXT_FRACTION * self.width

    def set(self, scale: ColorScale) -> bool:
        """Show ``scale``; return True if the texture had to be redrawn."""
        check_instance("scale", scale, ColorScale)
        if scale == self.scale:
            return False
        view = _view(self.vis)
        if view is not None:  # screen-space text in the view's legend: never tilted or clipped
            view.set_legend_part(self.vis.path.lower(), legend_html(scale))
            self.scale = scale
            return True
        png = colorbar_png(scale)
        h = self.width / 4
        material = g.MeshBasicMaterial(map=g.ImageTexture(image=g.PngImage(png)), color=0xffffff)
        # thick enough (1 % of its width) that the depth buffer keeps its front and back faces
        # apart: a thinner plate shows the mirrored back texture through the front one
        self.vis["plate"].set_object(g.Box([self.width, self.width / 100, h]), material)
        self.vis["plate"].set_transform(translation([self.width / 2, 0.0, h / 2]))
        self.scale = scale
        return True
