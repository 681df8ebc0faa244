"""The PNG export, read back with Pillow: the scale bar's length in PNG pixels matches its label
through the pixel size, the image keeps its orientation and colours (matplotlib's colormap),
and bad input is named."""
import math
import re

import matplotlib
import numpy as np
import pytest
from PIL import Image

from afmsmiler.parameters import UNITS
from afmsmiler.plots.export import (BAR_FRACTION, save_png, scale_bar_label,
                                    scale_bar_length)
from afmsmiler.samples import Sample


def _label_metres(label: str) -> float:
    value, unit = re.fullmatch(r"([0-9.]+) (nm|µm|mm)", label).groups()
    return float(value) * UNITS[unit.replace("µ", "u")][1]


def _longest_white_run(png, width):
    """The longest horizontal run of pure white pixels inside the image part of the PNG."""
    white = (png[:, :width, :3] == 255).all(-1)
    best = 0
    for row in white:
        d = np.diff(np.r_[0, row.astype(int), 0])
        if d.any():
            best = max(best, int((np.nonzero(d == -1)[0] - np.nonzero(d == 1)[0]).max()))
    return best


def _surface(rows, cols):
    y, x = np.mgrid[0:rows, 0:cols]
    return 1e-9 * (np.sin(x / 7.0) + np.cos(y / 5.0))


@pytest.mark.parametrize("pixel_size, pixel_size_y, shape, zoom", [
    (7.7e-9, None, (100, 130), None),      # a 1 um image: a 200 nm bar
    (0.31e-9, None, (64, 64), 5),          # 20 nm wide: a 5 nm bar
    (45e-9, 60e-9, (80, 120), 3),          # 5.4 um, rectangular pixels: a 1 um bar
    (2e-9, None, (300, 200), 1),
])
@pytest.mark.parametrize("colorbar", [False, True])
def test_scale_bar_pixels_match_its_label_through_the_pixel_size(tmp_path, pixel_size,
                                                                pixel_size_y, shape, zoom,
                                                                colorbar):
    sample = Sample(_surface(*shape), pixel_size, pixel_size_y=pixel_size_y)
    out = save_png(sample, tmp_path / "image.png", cmap="viridis", colorbar=colorbar, zoom=zoom)
    png = np.asarray(Image.open(out.path))
    rows, cols = shape
    aspect = (pixel_size_y or pixel_size) / pixel_size
    image_width = cols * out.zoom
    assert png.shape[1] == out.size[0] and png.shape[0] == out.size[1]
    assert png.shape[0] == round(rows * aspect * out.zoom)
    assert (png.shape[1] > image_width) == colorbar
    if zoom is not None:
        assert out.zoom == zoom
    length = _label_metres(out.bar_label)  # the label, read as a length
    assert length == pytest.approx(out.bar_length)
    expected = length / pixel_size * out.zoom
    assert _longest_white_run(png, image_width) == pytest.approx(expected, abs=1.0)
    # a round length, and the longest one within BAR_FRACTION of the width
    width = cols * pixel_size
    assert length <= BAR_FRACTION * width
    mantissa = length / 10 ** math.floor(math.log10(length))
    assert round(mantissa, 9) in (1.0, 2.0, 5.0)
    assert {1.0: 2.0, 2.0: 2.5, 5.0: 2.0}[round(mantissa, 9)] * length > BAR_FRACTION * width


def test_first_row_at_the_bottom_in_the_colormap_colours(tmp_path):
    rows, cols = 20, 30
    h = np.zeros((rows, cols))
    h[0, 0] = 4e-9   # y = 0, x = 0: bottom left (y grows upwards), the highest
    h[-1, -1] = -4e-9
    h[5, 20] = 1e-9
    out = save_png(Sample(h, 1e-9), tmp_path / "a.png", scale_bar=False, zoom=8)
    assert out.bar_length is None and out.bar_label == "" and out.bar_pixels == 0.0
    png = np.asarray(Image.open(out.path))[..., :3].astype(int)
    cmap = matplotlib.colormaps["afmhot"]
    for (i, j) in [(0, 0), (rows - 1, cols - 1), (5, 20), (10, 10)]:
        expected = np.array(cmap((h[i, j] + 4e-9) / 8e-9)[:3]) * 255
        pixel = png[(rows - 1 - i) * 8 + 4, j * 8 + 4]
        np.testing.assert_allclose(pixel, expected, atol=1.5)


def test_scale_bar_length_and_label_are_round():
    assert scale_bar_length(1e-6) == 2e-7
    assert scale_bar_length(10e-6) == 2e-6
    assert scale_bar_length(1.5e-6) == 2e-7  # 0.45 um allowed: 200 nm (500 nm is too long)
    assert scale_bar_length(1.7e-6) == 5e-7
    assert scale_bar_label(2e-7) == "200 nm"
    assert scale_bar_label(5e-6) == "5 µm"
    assert scale_bar_label(1e-6) == "1 µm"
    assert scale_bar_label(2e-3) == "2 mm"
    assert scale_bar_label(5e-10) == "0.5 nm"
    with pytest.raises(ValueError, match="width"):
        scale_bar_length(0.0)


def test_bad_input_is_named(tmp_path):
    s = Sample(_surface(10, 10), 1e-9)
    with pytest.raises(ValueError, match="sample"):
        save_png(Sample(np.zeros(10), 1e-9), tmp_path / "a.png")
    with pytest.raises(TypeError, match="sample"):
        save_png(np.zeros((10, 10)), tmp_path / "a.png")
    with pytest.raises(ValueError, match="cmap"):
        save_png(s, tmp_path / "a.png", cmap="nope")
    with pytest.raises(ValueError, match="zoom"):
        save_png(s, tmp_path / "a.png", zoom=1000)
    with pytest.raises(ValueError, match="path"):
        save_png(s, tmp_path / "missing" / "a.png")
    with pytest.raises(ValueError, match="path"):
        save_png(s, tmp_path)


def test_save_png_names_a_flag_that_is_not_a_bool_and_a_png_too_long(tmp_path):
    """Found by the bad-input campaign: ``scale_bar=None`` or ``"no"`` was accepted (drawn or not
    by its truth value), and a sample with very anisotropic pixels asked matplotlib for a PNG of
    16 x 160000000 pixels, whose error named no parameter."""
    from afmsmiler.plots.export import MAX_PNG_SIDE, save_png
    from afmsmiler.samples import Sample
    s = Sample(np.zeros((8, 8)), 1e-9)
    for name in ("scale_bar", "colorbar"):
        for bad in (None, "no", np.nan, np.ones(2)):
            with pytest.raises(TypeError, match=name):
                save_png(s, tmp_path / "x.png", **{name: bad})
    tall = Sample(np.zeros((16, 16)), 1e-9, pixel_size_y=1e-9 * (MAX_PNG_SIDE / 8))
    with pytest.raises(ValueError, match=r"sample would need a PNG of 16 x \d+ pixels"):
        save_png(tall, tmp_path / "y.png")
    assert not (tmp_path / "y.png").exists()
    save_png(s, tmp_path / "ok.png", scale_bar=np.bool_(False))  # numpy's bool is a bool
