"""Legends and text plates: the PNGs state the unit, the ticks stay short and inside the plate."""
import io
import math

import matplotlib
import matplotlib.image
import numpy as np
import pytest

from afmsmiler.scenes.camera import READABLE_TEXT, camera_ndc, readable_width
from afmsmiler.scenes.colors import ColorScale
from afmsmiler.scenes.legends import (ColorLegend, TextPlate, colorbar_png, legend_html,
                                      legend_title, text_png, tick_labels)
from tests.recording import Recorder


def test_legend_png_and_html_state_the_unit():
    scale = ColorScale.symmetric(5.0, label="bending stress", unit="MPa")
    png = colorbar_png(scale, size_px=(400, 100))
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    img = matplotlib.image.imread(io.BytesIO(png))
    assert img.shape[:2] == (100, 400)
    row = img[int(0.44 * 100)]  # through the bar (it spans 32 % to 56 % from the top)
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




# --- readable in the default camera view -------------------------------------------------------
def _world(rec, path):
    """The world transform of ``path``: the product of the transforms along it."""
    parts = path.strip("/").split("/")
    m = np.eye(4)
    for i in range(1, len(parts) + 1):
        t = rec.log.get("/" + "/".join(parts[:i]), {}).get("transform")
        m = m @ t if t is not None else m
    return m


def _text_on_screen(rec, plate_path, camera_position, text_fraction):
    """The height of the plate's text as a fraction of the view's height, by camera_ndc."""
    geom, _ = rec.log[plate_path]["object"]
    width = geom.lengths[0]
    centre = (_world(rec, plate_path) @ [0.0, 0.0, 0.0, 1.0])[:3]
    half = 0.5 * text_fraction * width
    ndc = camera_ndc([centre - [0, 0, half], centre + [0, 0, half]], camera_position)
    return abs(ndc[1, 1] - ndc[0, 1]) / 2


def _scenes():
    from afmsmiler.cantilever import Cantilever
    from afmsmiler.contact import Parabolic, indent
    from afmsmiler.scenes.cantilever import CantileverScene
    from afmsmiler.scenes.contact import ContactScene
    from afmsmiler.scenes.transducers import DEFAULTS, TransducerScene
    from afmsmiler.transducers import OpticalBeamDeflection
    for length in (100e-6, 450e-6):
        rec = Recorder()
        sc = CantileverScene(Cantilever(length, 50e-6, 2e-6, 169e9, 2330.0).bending(0.0), vis=rec)
        yield (f"cantilever {length * 1e6:.0f} um", rec, "/afmsmiler/cantilever/legend/plate",
               sc.camera_position, ColorLegend.TEXT_FRACTION, 0.95)
    tip = Parabolic(20e-9)
    for z_np in (30e-9, 150e-9):
        rec = Recorder()
        sc = ContactScene(tip, indent([z_np], 0.1, tip, 1e6, 0.3), vis=rec)
        # under a deep indentation the sample is drawn thicker and its legend lower (further)
        yield (f"contact {z_np * 1e9:.0f} nm", rec, "/afmsmiler/contact/legend/plate",
               sc.camera_position, ColorLegend.TEXT_FRACTION, 0.95 if z_np < 100e-9 else 0.85)
    rec = Recorder()
    TransducerScene(OpticalBeamDeflection().operate(20e-9), vis=rec)
    yield ("transducer meter", rec, "/afmsmiler/transducers/meter/label/plate",
           DEFAULTS["camera"], TextPlate.TEXT_FRACTION, 0.95)


def test_legends_and_labels_read_in_the_default_view():
    # before: their text spanned 1.2 % (contact), 1.6 % (transducer) and 1.7 % (cantilever) of
    # the view's height, 5 to 7 px in the 400 px frame meshcat opens in a notebook
    for name, rec, path, camera, fraction, at_least in _scenes():
        on_screen = _text_on_screen(rec, path, camera, fraction)
        assert at_least * READABLE_TEXT <= on_screen <= 1.5 * READABLE_TEXT, (name, on_screen)


def test_readable_width_puts_text_at_the_asked_height_on_screen():
    cam = [0.0, -10.0, 0.0]  # on the -y axis looking at the origin: no foreshortening there
    w = readable_width(0.1, [0.0, 0.0, 0.0], cam)
    # by hand: the view is 2 * 10 * tan(37.5 deg) = 15.35 units high at depth 10
    assert w * 0.1 == pytest.approx(READABLE_TEXT * 2 * 10 * math.tan(math.radians(37.5)),
                                    rel=1e-6)
    assert readable_width(0.1, [0.0, 10.0, 0.0], cam) == pytest.approx(2 * w, rel=1e-6)
    # a plate seen from 60 deg above is foreshortened by cos(60 deg): twice as wide
    above = [0.0, -10.0 * math.cos(math.radians(60)), 10.0 * math.sin(math.radians(60))]
    assert readable_width(0.1, [0, 0, 0], above) == pytest.approx(2 * w, rel=1e-3)
    with pytest.raises(ValueError, match="position must be in front of the camera"):
        readable_width(0.1, [0.0, -20.0, 0.0], cam)
    with pytest.raises(ValueError, match="text_fraction must be > 0"):
        readable_width(0.0, [0.0, 0.0, 0.0], cam)
