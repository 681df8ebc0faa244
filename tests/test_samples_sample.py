"""The Sample's grid: extents, crop, resample and unit conversion keep the pixel size, checked
against index arithmetic and an analytic plane (linear interpolation reproduces a plane)."""
import numpy as np
import pytest

from afmsmiler import samples
from afmsmiler.samples import Sample


def _plane(rows=30, cols=50, dx=2e-9, dy=3e-9):
    y, x = np.mgrid[0:rows, 0:cols]
    return Sample(1e-3 * x * dx + 2e-3 * y * dy, dx, "plane", dy, metadata={"source": "test"})


def test_grid_properties():
    s = _plane()
    assert s.shape == (30, 50) and s.channel == "height" and s.unit == "m"
    assert s.width == pytest.approx(49 * 2e-9) and s.height_extent == pytest.approx(29 * 3e-9)
    np.testing.assert_allclose(s.y, np.arange(30) * 3e-9)
    np.testing.assert_allclose(s.x, np.arange(50) * 2e-9)
    line = samples.step(10, 1e-9)
    assert line.height_extent == 0.0 and line.y.tolist() == [0.0]
    with pytest.raises(TypeError):
        s.metadata["source"] = "changed"  # read-only
    assert s.metadata["source"] == "test"


def test_crop_takes_the_pixels_of_the_window():
    s = _plane()
    c = s.crop(x=(10e-9, 40e-9), y=(3e-9, 30e-9))
    np.testing.assert_array_equal(c.heights, s.heights[1:11, 5:21])
    assert (c.pixel_size, c.pixel_size_y, c.unit) == (2e-9, 3e-9, "m")
    assert c.metadata["source"] == "test"
    np.testing.assert_array_equal(s.crop(y=(0, 3e-9)).heights, s.heights[:2])
    line = samples.step(100, 1e-9, 5e-9)
    np.testing.assert_array_equal(line.crop(x=(20e-9, 30e-9)).heights, line.heights[20:31])
    with pytest.raises(ValueError, match=r"x must be a pair \(start, end\) with 0 <= start < "
                                         r"end <= 9.8e-08 m"):
        s.crop(x=(0, 1e-6))
    with pytest.raises(ValueError, match="x must hold at least 2 pixels"):
        s.crop(x=(1e-9, 2.5e-9))
    with pytest.raises(ValueError, match="y must be None for a line"):
        line.crop(x=(0, 10e-9), y=(0, 1e-9))


def test_resample_reproduces_a_plane_on_the_new_grid():
    s = _plane()
    r = s.resample(1e-9, 1.5e-9)
    assert r.shape == (59, 99) and (r.pixel_size, r.pixel_size_y) == (1e-9, 1.5e-9)
    y, x = np.mgrid[0:59, 0:99]
    np.testing.assert_allclose(r.heights, 1e-3 * x * 1e-9 + 2e-3 * y * 1.5e-9, rtol=0,
                               atol=1e-24)
    r2 = s.resample(shape=(10, 8))
    assert r2.width == pytest.approx(s.width) and r2.height_extent == pytest.approx(
        s.height_extent)
    y, x = np.mgrid[0:10, 0:8]
    np.testing.assert_allclose(r2.heights, 1e-3 * x * r2.pixel_size + 2e-3 * y * r2.pixel_size_y,
                               rtol=0, atol=1e-24)
    # coarser: whole pixels that fit in the extent (98 nm / 7 nm = 14 steps)
    assert s.resample(7e-9).shape[1] == 15
    line = samples.step(11, 1e-9, 1.0e-9, position=0.5)
    assert line.resample(0.5e-9).shape == (21,)
    with pytest.raises(ValueError, match="give either pixel_size"):
        s.resample()
    with pytest.raises(ValueError, match="give either pixel_size"):
        s.resample(1e-9, shape=(4, 4))
    with pytest.raises(ValueError, match="pixel_size must give at most"):
        s.resample(1e-20)


def test_values_in_display_units():
    s = _plane()
    np.testing.assert_allclose(s.values_in("nm"), s.heights * 1e9, rtol=1e-15)
    with pytest.raises(ValueError, match="measures 'N', not 'm'"):
        s.values_in("nN")
    v = Sample(np.ones((2, 2)) * 0.5, 1e-9, channel="Amplitude", unit="V")
    np.testing.assert_allclose(v.values_in("mV"), 500.0)
    p = Sample(np.full((2, 2), 90.0), 1e-9, channel="Phase", unit="deg")
    np.testing.assert_allclose(p.values_in("rad"), np.pi / 2)


def test_with_heights_and_line_keep_the_grid():
    s = _plane()
    t = s.with_heights(np.zeros((30, 50)))
    assert (t.pixel_size, t.pixel_size_y, t.metadata["source"]) == (2e-9, 3e-9, "test")
    with pytest.raises(ValueError, match=r"heights must have this sample's shape \(30, 50\)"):
        s.with_heights(np.zeros((3, 5)))
    assert s.line(2).pixel_size == 2e-9 and s.line(2).channel == "height"


@pytest.mark.parametrize("kwargs, error, match", [
    (dict(unit="furlong"), ValueError, "unit must be one of"),
    (dict(channel=3), TypeError, "channel must be a str"),
    (dict(metadata=3), TypeError, "metadata must be a mapping"),
])
def test_bad_fields(kwargs, error, match):
    with pytest.raises(error, match=match):
        Sample(np.zeros((2, 2)), 1e-9, **kwargs)
