"""The imaging scene with the recording fake: the fields are the heights, exaggerated by the
stated factor and decimated to the vertex bound, coloured by matplotlib's colormap; the tip's
apex lands on the drawn surface; during a scan the tip only moves (transforms) and the image's
mesh is replaced once per finished line; the camera frames both fields."""
from types import SimpleNamespace

import matplotlib
import numpy as np
import pytest

from afmsmiler.contact import Conical, Parabolic
from afmsmiler.samples import Sample
from afmsmiler.scenes.camera import camera_ndc
from afmsmiler.scenes.imaging import (DEFAULTS, ImagingScene, auto_exaggeration, decimation)
from tests.recording import Recorder

DX = 4e-9


def _sample(rows=60, cols=80, dx=DX, relief=20e-9):
    y, x = np.mgrid[0:rows, 0:cols]
    h = 0.5 * relief * (np.sin(x / 6.0) * np.cos(y / 9.0) + 1.0) + 3e-9
    return Sample(h, dx, name="test", pixel_size_y=1.5 * dx)


def _scene(sample=None, **kw):
    rec = Recorder()
    kw.setdefault("tip", Parabolic(20e-9))
    return ImagingScene(sample or _sample(), vis=rec, path="img", **kw), rec


def _geometry(rec, name):
    return rec.log[f"/img/{name}"]["object"][0]


@pytest.mark.parametrize("shape, max_vertices", [((60, 80), 16384), ((300, 260), 4096),
                                                 ((513, 100), 1000)])
def test_sample_field_is_the_heights_exaggerated_and_decimated(shape, max_vertices):
    sample = _sample(*shape)
    sc, rec = _scene(sample, max_vertices=max_vertices, exaggeration=5.0)
    geo = _geometry(rec, "sample")
    s = sc.stride
    assert geo.vertices.shape[0] <= max_vertices
    assert s == decimation(shape, max_vertices)
    assert (s == 1) == (shape[0] * shape[1] <= max_vertices)
    h = sample.heights[::s, ::s]
    v = geo.vertices.reshape(h.shape + (3,)).astype(float)
    floor = sample.heights.min()  # the field stands on the lowest pixel, drawn or not
    np.testing.assert_allclose(v[..., 2] * sc.unit / 5.0, h - floor, rtol=1e-6,
                               atol=1e-6 * h.max())
    np.testing.assert_allclose(np.diff(v[0, :, 0]) * sc.unit, s * DX, rtol=1e-5)
    np.testing.assert_allclose(np.diff(v[:, 0, 1]) * sc.unit, s * 1.5 * DX, rtol=1e-5)
    # coloured by height through matplotlib's afmhot on the scene's scale (nm)
    cmap = matplotlib.colormaps[DEFAULTS["cmap"]]
    t = (h.ravel() * 1e9 - sc.scale.vmin) / (sc.scale.vmax - sc.scale.vmin)
    np.testing.assert_allclose(geo.color, cmap(t)[:, :3], atol=0.02)  # a 256-colour table


def test_exaggeration_is_round_stated_and_bounds_the_drawn_relief():
    sample = _sample(relief=20e-9)  # 316 nm wide, 20 nm of relief
    sc, rec = _scene(sample)
    width = (80 - 1) * DX
    assert sc.exaggeration == 2.0  # 0.15 x 316 / 20 = 2.4 -> 2
    drawn = np.ptp(_geometry(rec, "sample").vertices[:, 2]) * sc.unit
    assert DEFAULTS["relief"] * width / 2.5 < drawn <= DEFAULTS["relief"] * width
    assert "x 2" in sc.caption
    assert auto_exaggeration(1e-6, 1e-9) == 100.0  # 150 -> 100
    assert auto_exaggeration(1e-6, 0.0) == 1.0
    assert auto_exaggeration(1e-6, 1e-6) == 1.0    # never flattened
    assert auto_exaggeration(1e-6, 0.6e-9) == 200.0


def test_tip_apex_lands_on_the_drawn_surface_and_only_moves():
    sample = _sample()
    sc, rec = _scene(sample, exaggeration=10.0)
    assert rec.log["/img/tip"]["visible"] is False  # until it has a position
    v = _geometry(rec, "sample").vertices.reshape(60, 80, 3)
    for i, j in [(0, 0), (30, 41), (59, 79)]:
        sc.move_tip(j * DX, i * 1.5 * DX, sample.heights[i, j])
        m = rec.log["/img/tip"]["transform"]
        np.testing.assert_allclose(m[:3, 3], v[i, j], rtol=1e-5, atol=1e-5)
        assert m[2, 2] == 10.0  # the tip's heights exaggerated as the surface's
    assert rec.log["/img/tip"]["visible"] is True
    assert rec.log["/img/tip"]["n_objects"] == 1
    with pytest.raises(ValueError, match="z"):
        sc.move_tip(0.0, 0.0, float("nan"))
    sc2, _ = _scene(sample, tip=None)
    with pytest.raises(ValueError, match="tip"):
        sc2.move_tip(0.0, 0.0, 0.0)


def _partial(image, first, done):
    """Rows first .. done - 1 of image, as a scan's result gives its finished lines."""
    return Sample(image.heights[first:done], image.pixel_size, pixel_size_y=image.pixel_size_y)


def test_during_a_scan_the_image_mesh_is_replaced_once_per_line_and_the_tip_only_moves():
    sample = _sample(40, 50)
    sc, rec = _scene(sample, tip=Conical(0.3))
    image = Sample(sample.heights[5:25, 10:40] + 7e-9, DX, pixel_size_y=1.5 * DX)
    rows, cols = image.heights.shape
    rec.calls.clear()
    corner = None
    for line in range(1, rows + 1):  # line = lines finished
        for j in range(cols):  # the tip moves along the line, many times per line
            sc.update(_partial(image, 0, line), ((10 + j) * DX, (5 + line) * 1.5 * DX, 20e-9),
                      lines=rows)
        if line >= 2:  # the rows drawn stay where they are as lines are added
            v0 = _geometry(rec, "image").vertices[0]
            corner = v0 if corner is None else corner
            np.testing.assert_array_equal(v0[:2], corner[:2])
    sent = [c for c in rec.calls if c[1] == "/img/image" and c[0] in ("set_object", "delete")]
    assert len(sent) == rows - 1  # one mesh per finished line from the second (two rows) on
    tip_calls = [c for c in rec.calls if c[1] == "/img/tip"]
    assert [c[0] for c in tip_calls].count("set_object") == 0
    assert [c[0] for c in tip_calls].count("set_transform") == rows * cols
    assert not any(c[1] == "/img/sample" for c in rec.calls)  # the sample is never resent
    # the finished image: its heights (a scan range smaller than the sample, drawn smaller)
    v = _geometry(rec, "image").vertices.reshape(rows, cols, 3).astype(float)
    np.testing.assert_allclose(v[..., 2] * sc.unit / sc.exaggeration,
                               image.heights - image.heights.min(), rtol=1e-5, atol=1e-13)
    assert np.ptp(v[..., 0]) * sc.unit == pytest.approx((cols - 1) * DX, rel=1e-5)
    assert np.ptp(v[..., 1]) * sc.unit == pytest.approx((rows - 1) * 1.5 * DX, rel=1e-5)
    assert v[..., 0].min() > 0  # on the right of the sample
    assert sc.image_lines == rows
    # new values on the same rows are drawn only when asked
    assert sc.show_image(image) is False and sc.show_image(image, force=True) is True


def test_a_decimated_scan_keeps_its_rows_in_place_and_a_result_is_shown_as_is():
    big = Sample(np.random.default_rng(0).normal(0, 1e-9, (120, 90)), DX)
    sc, rec = _scene(_sample(), max_vertices=1000)
    s = decimation((120, 90), 1000)
    assert s > 1
    sc.show_image(_partial(big, 7, 61), lines=120, first_row=7)
    v = _geometry(rec, "image").vertices.astype(float)
    y = np.unique(np.round(v[:, 1] * sc.unit / DX, 6))  # drawn rows, in pixels
    full = np.round(np.arange(0, 120, s) - 119 / 2, 6)   # the full image's drawn rows, centred
    np.testing.assert_allclose(y, full[(full + 119 / 2 >= 7) & (full + 119 / 2 < 61)],
                               atol=1e-3)
    # a ScanResult: its channels (finished rows), lines and first_row
    result = SimpleNamespace(channels={"height trace": _partial(big, 0, 30)}, lines=120,
                             first_row=0)
    assert sc.show_scan(result) is True and sc.show_scan(result) is False
    assert sc.image_lines == 30
    with pytest.raises(ValueError, match="channel"):
        sc.show_scan(result, "phase")
    empty = SimpleNamespace(channels={}, lines=120, first_row=0)
    assert sc.show_scan(empty) is True and "/img/image" not in rec.log
    assert sc.show_scan(empty) is False
    with pytest.raises(TypeError, match="result"):
        sc.show_scan(big)


def test_camera_frames_both_fields_and_the_legend():
    sample = _sample()
    sc, rec = _scene(sample)
    sc.show_image(sample)
    pts = np.vstack([_geometry(rec, "sample").vertices, _geometry(rec, "image").vertices])
    w = sc.legend.width
    legend = sc.legend_corner + np.array([[0, 0, 0], [w, 0, 0], [0, 0, w / 4], [w, 0, w / 4]])
    ndc = camera_ndc(np.vstack([pts, legend]), sc.camera_position, aspect=1.5)
    assert np.all(np.abs(ndc) <= 1.0)
    assert rec.log["/Grid"]["visible"] is False


def test_bad_input_is_named():
    with pytest.raises(ValueError, match="sample"):
        ImagingScene(Sample(np.zeros(10), DX), vis=Recorder())
    with pytest.raises(TypeError, match="tip"):
        ImagingScene(_sample(), tip="cone", vis=Recorder())
    with pytest.raises(ValueError, match="max_vertices"):
        ImagingScene(_sample(), vis=Recorder(), max_vertices=2)
    with pytest.raises(ValueError, match="exaggeration"):
        ImagingScene(_sample(), vis=Recorder(), exaggeration=0.0)
    with pytest.raises(ValueError, match=r"^exaggeration must be in \(0, .*\] for this sample "
                                         r"\(its relief of .* drawn at most 1000 times"):
        ImagingScene(_sample(), vis=Recorder(), exaggeration=1e300)
    with pytest.raises(TypeError, match="^camera must be True or False"):
        ImagingScene(_sample(), vis=Recorder(), camera="yes")
    sc, _ = _scene()
    with pytest.raises(ValueError, match="lines"):
        sc.show_image(_sample(), lines=59)
    with pytest.raises(ValueError, match="first_row"):
        sc.show_image(_sample(), first_row=-1)
    with pytest.raises(TypeError, match="image"):
        sc.show_image(np.zeros((4, 4)))


@pytest.mark.slow
def test_real_view_takes_the_meshes_and_a_scan_does_not_grow_the_scene():
    from afmsmiler.scenes import static_html
    sample = _sample(40, 50)
    sc = ImagingScene(sample, tip=Parabolic(20e-9))
    sc.show_image(_partial(sample, 0, 2), lines=40)
    size0 = len(static_html(sc.root))
    for line in range(3, 41):
        sc.update(_partial(sample, 0, line), (50e-9, line * 6e-9, 20e-9), lines=40)
    # the image's mesh is replaced in place: the stored scene grows only with its rows
    assert len(static_html(sc.root)) < 3 * size0


def test_a_real_scan_is_drawn_line_by_line_with_the_tip_where_the_scanner_says():
    """With module (f)'s scanner (constant force through module (c)'s loop): one image mesh per
    finished line, the tip moved by transforms to Scan.position, the last mesh the result."""
    from afmsmiler.controller import ContactLoop
    from afmsmiler.imaging.scan_modes import ConstantForce
    from afmsmiler.imaging.scanner import Scan, ScanSettings
    from afmsmiler.samples import particles

    sample = particles((24, 32), 4e-9, count=3, radius=10e-9, seed=1)
    settings = ScanSettings(32 * 4e-9, scan_size_y=24 * 4e-9, pixels=32, lines=24,
                            scan_speed=1e-3)
    tip = Parabolic(10e-9)
    run = Scan(sample, tip, ConstantForce(ContactLoop(kp=0.3, ki=5e3)), settings)
    sc, rec = _scene(sample, tip=tip)
    rec.calls.clear()
    for record in run.lines():
        result = run.result
        for column in range(32):  # the tip along the line just scanned
            x, y = run.position(record.row, column)
            z = float(result.images["height trace"][record.row, column])
            sc.move_tip(x, y, z)
            sc.show_scan(result)
    image = run.result.channels["height trace"]
    sent = [c for c in rec.calls if c[1] == "/img/image" and c[0] == "set_object"]
    assert len(sent) == 23  # lines 2 to 24
    v = _geometry(rec, "image").vertices.reshape(24, 32, 3).astype(float)
    np.testing.assert_allclose(v[..., 2] * sc.unit / sc.exaggeration,
                               image.heights - image.heights.min(), rtol=1e-5,
                               atol=1e-6 * np.ptp(image.heights))
    m = rec.log["/img/tip"]["transform"]
    x, y = run.position(23, 31)
    np.testing.assert_allclose(m[:2, 3] * sc.unit, [sc.sample_origin[0] + x,
                                                    sc.sample_origin[1] + y], rtol=1e-6)
    assert rec.log["/img/tip"]["n_objects"] == 1


def test_the_legend_reads_a_printed_sample_in_mm_and_an_afm_image_in_nm():
    """A module (h) print (mm relief) had its legend in nm: 'x10^6 nm'."""
    from afmsmiler.scenes.imaging import height_unit
    assert (height_unit(3e-9), height_unit(2e-6), height_unit(2e-3)) == ("nm", "um", "mm")
    y, x = np.mgrid[0:16, 0:16]
    printed = Sample(2e-3 * (x > 7), 0.2e-3, "print")
    scene = ImagingScene(printed, vis=Recorder())
    assert scene.scale.unit == "mm"
    assert scene.scale.vmax - scene.scale.vmin == pytest.approx(2.0)  # 2 mm of relief, in mm
