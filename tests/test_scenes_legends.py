"""Legends and text plates: the PNGs state the unit, the ticks stay short and inside the plate."""
import io

import matplotlib
import matplotlib.image
import numpy as np
import pytest

from afmsmiler.scenes.colors import ColorScale
from afmsmiler.scenes.legends import (TextPlate, colorbar_png, legend_html, legend_title,
                                      text_png, tick_labels)
from recording import Recorder


def test_legend_png_and_html_state_the_unit():
    scale = ColorScale.symmetric(5.0, label="bending stress", unit="MPa")
    png = colorbar_png(scale, size_px=(400, 100))
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    img = matplotlib.image.imread(io.BytesIO(png))
    assert img.shape[:2] == (100, 400)
    row = img[int(0.3 * 100)]  # through the bar (the bar spans 15%-45% from the top)
    # blue on the left, red on the right
    assert row[30, 2] > row[30, 0] and row[370, 0] > row[370, 2]
    html = legend_html(scale)
    assert "bending stress [MPa]" in html and ">-5<" in html and ">5<" in html


@pytest.mark.parametrize("limit, exponent", [(1e-3, -3), (5e-3, -3), (0.05, -3), (0.1, 0),
                                             (0.5, 0), (5.0, 0),
                                             (500.0, 0), (1e3, 3), (2e3, 3), (5e4, 3), (1e6, 6)])
def test_legend_ticks_are_short_with_a_common_power_of_ten(limit, exponent):
    # the 1, 2, 5 x 10^n limits of a stress legend: at 1000 MPa "%.3g" wrote "1e+03", wider than
    # the space beside the bar's end; now the labels stay within 5 characters (-0.25, -250)
    ticks = np.linspace(-limit, limit, 5)
    labels, e = tick_labels(ticks)
    assert e == exponent
    assert all(len(t) <= 5 and "e" not in t for t in labels), labels
    np.testing.assert_allclose([float(t) * 10.0 ** e for t in labels], ticks, rtol=1e-12)
    scale = ColorScale.symmetric(limit, label="bending stress", unit="MPa")
    title = legend_title(scale, e)
    assert title == ("bending stress [MPa]" if e == 0 else f"bending stress [x 10^{e} MPa]")
    assert (f"{title}</div>" in legend_html(scale)) and (f">{labels[0]}<" in legend_html(scale))


@pytest.mark.parametrize("limit", [1e3, 5e4, 1e-3, 0.5])
def test_legend_texts_stay_inside_the_plate(limit):
    # the bar stops 1/16 of the width from each edge: a label spilling past the plate would leave
    # dark pixels in the outermost columns (and be cut off in the 3D view)
    png = colorbar_png(ColorScale.symmetric(limit, label="bending stress", unit="MPa"))
    img = matplotlib.image.imread(io.BytesIO(png))[..., :3]
    assert img[:, :2].min() > 0.9 and img[:, -2:].min() > 0.9
    assert img[int(0.7 * img.shape[0]):, :30].min() < 0.5  # but the first label is drawn

def test_text_plate_is_a_png_of_the_text_on_a_plate():
    img = matplotlib.image.imread(io.BytesIO(text_png("output / max", size_px=(300, 50))))
    assert img.shape[:2] == (50, 300)
    dark = img[..., 0] < 0.5
    assert dark[:, 100:200].any() and not dark[:, :10].any()  # centred text, white margins
    rec = Recorder()
    plate = TextPlate(rec["label"], "output / max", width=1.2)
    geom, material = rec.log["/label/plate"]["object"]
    np.testing.assert_allclose(geom.lengths, [1.2, 1.2 / 100, 0.2])
    assert material.map is not None
    np.testing.assert_allclose(rec.log["/label/plate"]["transform"][:3, 3], [0.6, 0.0, 0.1])
    assert plate.text == "output / max"


