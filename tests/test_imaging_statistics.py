"""Image statistics against closed forms and independent implementations: a sine's Rq = A/sqrt(2)
and Ra = 2A/pi, numpy's histogram, scipy's RegularGridInterpolator for line profiles, and exact
values on a plane."""
import math

import numpy as np
import pytest
from scipy.interpolate import RegularGridInterpolator

from afmsmiler.imaging.statistics import histogram, line_profile, ra, rms
from afmsmiler.samples import Sample

DX, DY = 2e-9, 3e-9


def _sine(amplitude=3e-9, rows=40, cols=400, periods=8):
    x = np.arange(cols) / cols  # whole periods: the mean is exactly 0 and the sums are exact
    return Sample(np.tile(amplitude * np.sin(2 * np.pi * periods * x), (rows, 1)) + 7e-9, DX,
                  pixel_size_y=DY)


def test_roughness_of_a_sine_is_the_closed_form():
    a = 3e-9
    s = _sine(a)
    assert rms(s) == pytest.approx(a / math.sqrt(2), rel=1e-12)
    # Ra of a sine sampled N = 50 times a period is exactly A (2/N) cot(pi/N) (a sum of sines),
    # which tends to 2A/pi as (pi/N)^2/3 relative: 1.3e-3 here, 1.3e-5 with N = 500
    assert ra(s) == pytest.approx(a * 2 / 50 / math.tan(math.pi / 50), rel=1e-12)
    assert ra(s) == pytest.approx(2 * a / math.pi, rel=1.4e-3)
    assert ra(_sine(a, rows=4, cols=4000)) == pytest.approx(2 * a / math.pi, rel=1.4e-5)
    line = s.line(0)
    assert rms(line) == pytest.approx(a / math.sqrt(2), rel=1e-12)


def test_roughness_about_the_mean_and_with_a_mask():
    rng = np.random.default_rng(1)
    h = rng.normal(5e-9, 2e-9, (50, 60))
    mask = rng.random(h.shape) < 0.2
    s = Sample(h, DX)
    assert rms(s) == pytest.approx(np.std(h), rel=1e-12)
    assert rms(s, mask) == pytest.approx(np.std(h[~mask]), rel=1e-12)
    assert ra(s, mask) == pytest.approx(np.mean(np.abs(h[~mask] - h[~mask].mean())), rel=1e-12)
    with pytest.raises(ValueError, match="mask"):
        rms(s, np.ones(h.shape, bool))
    with pytest.raises(ValueError, match="mask"):
        ra(s, np.zeros((2, 2), bool))


def test_histogram_equals_numpy_and_its_density_integrates_to_one():
    rng = np.random.default_rng(2)
    h = rng.normal(0, 1e-9, (64, 64))
    s = Sample(h, DX)
    hist = histogram(s, 50)
    counts, edges = np.histogram(h, 50)
    np.testing.assert_array_equal(hist.counts, counts)
    np.testing.assert_allclose(hist.edges, edges)
    assert np.sum(hist.density * np.diff(hist.edges)) == pytest.approx(1.0)
    np.testing.assert_allclose(hist.centres, 0.5 * (edges[1:] + edges[:-1]))
    fixed = histogram(s, 10, range=(-1e-9, 1e-9))
    assert fixed.edges[0] == -1e-9 and fixed.edges[-1] == 1e-9
    with pytest.raises(ValueError, match="bins"):
        histogram(s, 0)
    with pytest.raises(ValueError, match="range"):
        histogram(s, 10, range=(1e-9, -1e-9))


def test_line_profile_on_a_plane_is_exact_and_positions_are_in_metres():
    rows, cols = 30, 40
    y, x = np.mgrid[0:rows, 0:cols]
    plane = 1e-9 + 0.01 * x * DX - 0.02 * y * DY
    s = Sample(plane, DX, pixel_size_y=DY)
    start, end = (5e-9, 10e-9), (70e-9, 80e-9)
    p = line_profile(s, start, end)
    length = math.hypot(65e-9, 70e-9)
    assert p.distance[0] == 0.0 and p.distance[-1] == pytest.approx(length)
    assert p.x[0] == 5e-9 and p.y[-1] == pytest.approx(80e-9)
    assert p.heights.size == math.ceil(length / DX) + 1  # one point per (smaller) pixel
    np.testing.assert_allclose(p.heights, 1e-9 + 0.01 * p.x - 0.02 * p.y, rtol=1e-12,
                               atol=1e-24)
    assert p.as_sample().pixel_size == pytest.approx(length / (p.heights.size - 1))


def test_line_profile_equals_scipy_regular_grid_interpolation():
    rng = np.random.default_rng(4)
    h = rng.normal(0, 1e-9, (25, 35))
    s = Sample(h, DX, pixel_size_y=DY)
    ref = RegularGridInterpolator((np.arange(25) * DY, np.arange(35) * DX), h)
    p = line_profile(s, (1e-9, 70e-9), (66e-9, 3e-9), points=77)
    np.testing.assert_allclose(p.heights, ref(np.column_stack([p.y, p.x])), rtol=1e-10,
                               atol=1e-22)
    # a sine across the image, sampled with cubic splines, follows the closed form
    x = np.arange(200) * DX
    sine = Sample(np.tile(np.sin(2 * np.pi * x / 80e-9), (10, 1)) * 1e-9, DX)
    q = line_profile(sine, (0.0, 9e-9), (398e-9, 9e-9), points=1000, order=3)
    inside = (q.x > 40e-9) & (q.x < 360e-9)  # the spline's end conditions reach a few pixels in
    # the cubic spline's error on a sine of 40 pixels a period: (2 pi / 40)^4 / 384 = 1.6e-6
    np.testing.assert_allclose(q.heights[inside], 1e-9 * np.sin(2 * np.pi * q.x[inside] / 80e-9),
                               atol=5e-15)


def test_line_profile_rejects_points_outside_the_image_naming_them():
    s = Sample(np.zeros((10, 10)), DX)
    with pytest.raises(ValueError, match="end"):
        line_profile(s, (0.0, 0.0), (19e-9, 0.0))
    with pytest.raises(ValueError, match="start"):
        line_profile(s, (-1e-9, 0.0), (5e-9, 0.0))
    with pytest.raises(ValueError, match="end must differ"):
        line_profile(s, (1e-9, 1e-9), (1e-9, 1e-9))
    with pytest.raises(ValueError, match="points"):
        line_profile(s, (0.0, 0.0), (5e-9, 0.0), points=1)
    with pytest.raises(ValueError, match="order"):
        line_profile(s, (0.0, 0.0), (5e-9, 0.0), order=2)
    with pytest.raises(ValueError, match="image"):
        line_profile(Sample(np.zeros(10), DX), (0.0, 0.0), (5e-9, 0.0))
