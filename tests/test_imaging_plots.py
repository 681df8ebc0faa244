"""Module (f)'s live figure: an image growing line by line, drawn from a scan's result.

The figure reads what it shows from the result (no physics): the checks compare its artists and
the browser's description with the arrays put in, converted with the one unit table.
"""
from types import SimpleNamespace

import numpy as np
import pytest

from afmsmiler.parameters import UNITS
from afmsmiler.imaging.scan_modes import Crash
from afmsmiler.plots.imaging import (ImagingFigure, crash_note, error_channel, length_unit,
                                     main_channel, scan_view, side_channel)
from afmsmiler.plots.live import describe
from afmsmiler.samples import Sample

NM = 1 / UNITS["nm"][1]  # nm per m, from the unit table
UM = 1 / UNITS["um"][1]


def _result(lines_done, rows=12, cols=20, pixel=25e-9, channels=("height", "error")):
    rng = np.random.default_rng(3)
    out = {}
    for name in channels:
        for way in ("trace", "retrace"):
            out[f"{name} {way}"] = Sample(rng.normal(size=(rows, cols)) * 1e-9, pixel,
                                          f"{name} {way}")
    return SimpleNamespace(channels=out, lines_done=lines_done, crashed=None, stopped=False)


def test_unfinished_rows_are_nan_and_the_rest_in_nm_over_um():
    r = _result(5)
    v = scan_view(r)
    h = r.channels["height trace"].heights
    assert np.isnan(v.image[5:]).all() and np.isnan(v.error[5:]).all()
    np.testing.assert_allclose(v.image[:5], h[:5] * NM, rtol=1e-12)
    np.testing.assert_allclose(v.error[:5], r.channels["error trace"].heights[:5] * NM)
    # 20 pixels of 25 nm: 0.5 um, shown in nm; pixel edges around the centres
    assert v.length_unit == "nm"
    assert v.extent == pytest.approx((-12.5, 487.5, -12.5, 287.5))
    assert v.row == 4 and v.lines_done == 5 and v.lines == 12
    np.testing.assert_allclose(v.trace, h[4] * NM)
    np.testing.assert_allclose(v.retrace, r.channels["height retrace"].heights[4] * NM)
    assert v.image_label == "height trace [nm]" and v.error_label == "error trace [nm]"


def test_micrometres_from_one_micrometre_of_scan():
    assert length_unit(0.999e-6) == "nm" and length_unit(1e-6) == "um"
    v = scan_view(_result(12, cols=64, pixel=50e-9))  # 3.2 um
    assert v.length_unit == "um"
    np.testing.assert_allclose(v.x, np.arange(64) * 50e-9 * UM)


def test_channels_chosen_for_constant_force_and_constant_height():
    assert main_channel(_result(1).channels) == "height trace"
    cf = _result(1).channels
    assert error_channel(cf, "height trace") == "error trace"
    ch = _result(1, channels=("deflection",)).channels
    assert main_channel(ch) == "deflection trace" and error_channel(ch, "deflection trace") is None
    # constant height has no error channel: the deflection's retrace stands beside its trace,
    # on the trace's colour map and scale (an empty "no error channel" axes stood there)
    assert side_channel(cf, "height trace") == "error trace"
    assert side_channel(ch, "deflection trace") == "deflection retrace"
    r = _result(3, channels=("deflection",))
    v = scan_view(r)
    assert v.error_is_retrace and v.error_label == "deflection retrace [nm]"
    np.testing.assert_allclose(v.error[:3], r.channels["deflection retrace"].heights[:3] * NM)
    f = ImagingFigure(v)
    assert f.images["error"].get_cmap().name == f.images["image"].get_cmap().name
    assert f.images["error"].get_clim() == f.images["image"].get_clim()
    assert f.axes["error"].get_title() == "deflection retrace"
    assert describe(f.fig).frame["axes"][1]["colorbar"]["cmap"] == "afmhot"
    f.update(scan_view(_result(3)))  # back to constant force: the error's diverging map
    assert f.images["error"].get_cmap().name == "RdBu_r"
    lo, hi = f.images["error"].get_clim()
    assert lo == -hi
    only = {"deflection trace": r.channels["deflection trace"]}
    v = scan_view(SimpleNamespace(channels=only, lines_done=3))
    assert np.isnan(v.error).all() and v.error_label == "no error channel"
    assert not v.error_is_retrace
    with pytest.raises(ValueError, match="main must be one of"):
        scan_view(_result(1), main="phase trace")
    with pytest.raises(ValueError, match="channels must hold"):
        main_channel({})


def test_before_the_first_line_nothing_is_drawn_and_bad_counts_are_refused():
    v = scan_view(_result(0))
    assert v.row is None and np.isnan(v.image).all() and np.isnan(v.trace).all()
    with pytest.raises(ValueError, match="lines_done"):
        scan_view(_result(13))


def test_the_figure_is_described_for_the_browser_line_after_line():
    f = ImagingFigure(scan_view(_result(0)))
    n_artists = (len(f.fig.axes), sum(len(a.lines) + len(a.images) for a in f.fig.axes))
    for done in (1, 6, 12):
        r = _result(done)
        f.update(scan_view(r))
        d = describe(f.fig)  # no NotImplementedError: the browser can draw all of it
        image = d.frame["axes"][0]["images"][0]
        values = d.values(image["data"]).reshape(image["shape"])
        expected = r.channels["height trace"].heights * NM
        expected[done:] = np.nan
        np.testing.assert_allclose(values, expected, rtol=1e-6, atol=1e-6)  # float32
        cb = d.frame["axes"][0]["colorbar"]
        assert cb["label"] == "height trace [nm]"
        finite = expected[np.isfinite(expected)]
        assert (cb["vmin"], cb["vmax"]) == pytest.approx((finite.min(), finite.max()), rel=1e-6)
        assert d.frame["axes"][0]["title"]["text"] == f"height trace: line {done} of 12"
        # the profile of that line carries the same number (it said "line 11" under "12 of 12")
        assert f.axes["profile"].get_title() == f"line {done}: trace and retrace"
        x, y = f.lines["trace"].get_data()
        np.testing.assert_allclose(y, expected[done - 1])
        lo, hi = f.axes["profile"].get_ylim()
        both = np.r_[y, f.lines["retrace"].get_ydata()]
        assert lo <= both.min() and both.max() <= hi
    # no artist was added by the updates
    assert n_artists == (len(f.fig.axes), sum(len(a.lines) + len(a.images) for a in f.fig.axes))


def test_a_stopped_or_crashed_scan_says_so():
    r = _result(4)
    r.stopped = True
    assert "stopped" in ImagingFigure(scan_view(r)).axes["image"].get_title()
    r.crashed = "row 3, 120 nN"
    v = scan_view(r)
    assert v.status == "crashed: row 3, 120 nN"
    # a Crash in words, lines and pixels counted from 1 (the title showed its Python repr)
    r.crashed = Crash(row=4, column=16, force=-1.2e-7, direction="retrace")
    title = ImagingFigure(scan_view(r)).axes["image"].get_title()
    assert title == ("height trace: line 4 of 12; tip crashed: -120 nN on line 5 (retrace), "
                     "pixel 17")
    assert "Crash(" not in title
    assert crash_note(Crash(0, 2, float("inf"))) == ("tip crashed: tip buried (force without "
                                                     "bound) on line 1 (trace), pixel 3")


def test_images_side_by_side_in_nm_with_their_own_colour_scales():
    a = Sample(np.arange(12.0).reshape(3, 4) * 1e-9, 0.5e-6, "a")
    b = Sample(np.ones((3, 4)) * 2e-9, 0.5e-6, "b")
    from afmsmiler.plots.imaging import images_figure
    fig = images_figure(a, b, titles=["first", "second"])
    (ia,), (ib,) = fig.axes[0].images, fig.axes[1].images
    lo, hi = ib.get_clim()  # a flat image still gets a span
    assert lo < 2 < hi
    np.testing.assert_allclose(ia.get_array(), a.heights * NM)
    assert ia.get_clim() == pytest.approx((0, 11)) and fig.axes[1].get_title() == "second"
    assert fig.axes[0].get_xlabel() == "x [um]"  # 2 um wide
    describe(fig)
    with pytest.raises(ValueError, match="one title per image"):
        images_figure(a, titles=["x", "y"])
    with pytest.raises(ValueError, match="1 to 4"):
        images_figure()


def test_the_error_colour_scale_is_centred_on_zero():
    r = _result(7)
    f = ImagingFigure(scan_view(r))
    e = r.channels["error trace"].heights[:7] * NM
    lo, hi = f.images["error"].get_clim()
    assert lo == pytest.approx(-np.abs(e).max()) and hi == pytest.approx(np.abs(e).max())
    assert f.axes["profile"].get_ylabel() == "height [nm]"


def test_a_scanners_result_is_shown_as_it_grows():
    from afmsmiler.controller import ContactLoop
    from afmsmiler.imaging.scan_modes import ConstantForce
    from afmsmiler.imaging.scanner import Scan, ScanSettings
    sample = Sample(np.random.default_rng(1).normal(size=(40, 40)) * 1e-9, 10e-9)
    scan = Scan(sample, None, ConstantForce(ContactLoop()), ScanSettings(300e-9, pixels=16))
    for _ in range(5):
        scan.step()
    r = scan.result
    v = scan_view(r)
    assert v.lines == 16 and v.lines_done == 5 and v.row == 4
    np.testing.assert_allclose(v.image[:5], r.images["height trace"][:5] * NM, rtol=1e-12)
    assert np.isnan(v.image[5:]).all()
    dx = 300e-9 / 16 * NM
    assert v.extent == pytest.approx((-dx / 2, 16 * dx - dx / 2, -dx / 2, 16 * dx - dx / 2))
    np.testing.assert_allclose(v.retrace, r.images["height retrace"][4] * NM, rtol=1e-12)
    assert v.error_label == "error trace [nm]"
    describe(ImagingFigure(v).fig)
