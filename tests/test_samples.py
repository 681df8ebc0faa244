"""Sample generators: shapes, physical sizes and statistics against their definitions (the
readers are tested in test_samples_readers.py, the Sample's grid in test_samples_sample.py)."""
import math
import re

import numpy as np
import pytest

from afmsmiler import samples
from afmsmiler.samples.synthetic import MAX_HEIGHT


def test_step_and_grating_geometry():
    s = samples.step(100, 2e-9, 30e-9, position=0.5)
    assert s.heights.shape == (100,) and s.pixel_size == 2e-9
    assert s.size == pytest.approx(99 * 2e-9)
    np.testing.assert_allclose(s.x, np.arange(100) * 2e-9)
    assert set(np.unique(s.heights)) == {0.0, 30e-9}
    assert np.count_nonzero(s.heights) == 50  # x/(n-1) >= 0.5 for the upper half
    g = samples.grating(400, 1e-9, period=100e-9, height=20e-9, duty=0.25)
    # 25 of every 100 pixels raised, 4 periods
    assert np.count_nonzero(g.heights) == 100
    np.testing.assert_array_equal(g.heights[:100], g.heights[100:200])
    assert g.heights[0] == 20e-9 and g.heights[25] == 0.0


def test_rough_surface_statistics():
    s = samples.rough_surface((256, 256), 2e-9, rms=3e-9, correlation_length=10e-9, seed=4)
    assert s.heights.std() == pytest.approx(3e-9, rel=1e-12)
    assert abs(s.heights.mean()) < 1e-12 * 3e-9  # relative to the mean plane
    # neighbours (r = T/5) are strongly correlated, points 5 T apart are not
    h = s.heights
    near = np.mean(h[:, :-1] * h[:, 1:]) / h.var()
    far = np.mean(h[:, :-25] * h[:, 25:]) / h.var()
    assert near > 0.9 and abs(far) < 0.1
    np.testing.assert_array_equal(s.heights, samples.rough_surface(
        (256, 256), 2e-9, rms=3e-9, correlation_length=10e-9, seed=4).heights)
    assert samples.rough_surface(64, 1e-9, correlation_length=5e-9).heights.shape == (64,)


def test_rough_surface_autocorrelation_is_the_gaussian_of_its_correlation_length():
    # Gwyddion's (and ISO 25178's) Gaussian surface: G(r) = rms^2 exp(-r^2 / T^2), so the
    # normalised autocorrelation at r = T is 1/e = 0.368 and at r = T/2 exp(-1/4) = 0.779 (the
    # old filter gave exp(-r^2 / (2 T^2)): 0.607 at r = T). Averaged over 8 seeds of 256 x 256
    # pixels, T = 8 pixels: the estimate's spread is about 0.01.
    T = 8
    acf = np.zeros(T + 1)
    for seed in range(8):
        h = samples.rough_surface((256, 256), 1e-9, 1e-9, T * 1e-9, seed=seed).heights
        lags = np.array([np.mean(h * np.roll(h, -lag, axis=1)) for lag in range(T + 1)])
        acf += lags / h.var() / 8
    assert acf[T] == pytest.approx(np.exp(-1.0), abs=0.04)
    assert acf[T // 2] == pytest.approx(np.exp(-0.25), abs=0.04)


def test_rough_surface_longer_than_the_image_is_named_not_flat():
    # before: a perfectly flat surface at -4.6e6 m, noise at the level of rounding scaled up
    with pytest.raises(ValueError, match=r"correlation_length must be in \(0, 6.4e-08\] m, got "
                                         r"1e-06"):
        samples.rough_surface((64, 64), 4e-9, 2e-9, 1e-6)
    s = samples.rough_surface((64, 64), 4e-9, 2e-9, 64e-9)  # the longest allowed: T = P / 4
    assert s.heights.std() == pytest.approx(2e-9, rel=1e-12) and np.ptp(s.heights) < 20e-9
    assert abs(s.heights.mean()) < 1e-20


def test_particles_and_profiles():
    img = samples.particles((64, 128), 4e-9, count=5, radius=20e-9, rms=0.5e-9)
    assert img.heights.shape == (64, 128)
    assert img.heights.max() == pytest.approx(40e-9, rel=0.02)  # sphere top at 2 r
    line = img.line(3)
    np.testing.assert_array_equal(line.heights, img.heights[3])
    for name in samples.PROFILES:
        p = samples.profile(name, 256, 4e-9, 50e-9)
        assert p.heights.shape == (256,) and p.pixel_size == 4e-9
        assert np.ptp(p.heights) == pytest.approx(50e-9, rel=0.1)


def test_particles_paint_the_same_heights_as_the_whole_image_sum():
    # the reference: every particle's cap evaluated over the whole image; outside the caps the
    # substrate keeps its own heights (the old loop put max(substrate, 0) there: its valleys
    # were cut flat at the mean plane wherever there was at least one particle)
    rows, cols, px, r = 40, 60, 4e-9, 18e-9
    img = samples.particles((rows, cols), px, count=12, radius=r, rms=0.5e-9, seed=5)
    h = samples.particles((rows, cols), px, count=0, rms=0.5e-9, seed=5).heights.copy()
    rng = np.random.default_rng(6)
    y, x = np.mgrid[0:rows, 0:cols] * px
    for cy, cx in zip(rng.uniform(0, rows * px, 12), rng.uniform(0, cols * px, 12)):
        rho2 = (x - cx) ** 2 + (y - cy) ** 2
        h = np.maximum(h, np.where(rho2 < r * r, r + np.sqrt(np.maximum(r * r - rho2, 0)), -1))
    np.testing.assert_array_equal(img.heights, h)
    assert img.heights.min() < -0.5e-9  # the substrate's valleys are still there


def test_rough_surface_at_any_pixel_size():
    # before: (pi T k)^2 in m^-2 overflowed for tiny pixels: NaN, named "heights must be finite"
    for pixel in (1e-300, 1e-9, 1e3):
        s = samples.rough_surface((32, 32), pixel, rms=1e-9, correlation_length=4 * pixel)
        assert s.heights.std() == pytest.approx(1e-9, rel=1e-12)
    np.testing.assert_allclose(samples.rough_surface((32, 32), 1e-300, 1e-9, 4e-300).heights,
                               samples.rough_surface((32, 32), 1e-9, 1e-9, 4e-9).heights,
                               rtol=1e-9, atol=1e-24)  # the same surface, in pixels


def test_particles_too_much_work_is_named():
    # before: 10000 particles each painted over the whole 256 x 256 image (minutes at 2048^2)
    with pytest.raises(ValueError, match="count and radius must cover at most"):
        samples.particles((256, 256), count=10000, radius=1e-6)
    with pytest.raises(ValueError, match="shape must have at most 4194304 elements"):
        samples.particles((4096, 4096))
    with pytest.raises(ValueError, match="shape must have at most"):
        samples.rough_surface((3000, 3000), correlation_length=4e-9)


@pytest.mark.slow
def test_the_largest_particle_image_is_made_within_seconds(hang_guard):
    with hang_guard(60, expected=5):  # about 5 s on one loaded core; before: past two minutes
        img = samples.particles((2048, 2048), count=10000)
    assert img.heights.max() == pytest.approx(50e-9, rel=0.05)


@pytest.mark.parametrize("call, match", [
    (lambda: samples.step(1), "shape must be an integer in"),
    (lambda: samples.step(10, -1e-9), "pixel_size must be > 0 m"),
    (lambda: samples.step(10, 1e-9, np.nan), "height must be a finite"),
    (lambda: samples.grating(10, 1e-9, period=0.0), r"period must be in \[2e-09, inf\] m"),
    (lambda: samples.grating(10, 1e-9, duty=1.0), r"duty must be in \(0, 1\)"),
    (lambda: samples.rough_surface((4, 4, 4)), "shape must be"),
    (lambda: samples.rough_surface(8, rms=-1e-9), "rms must be in"),
    (lambda: samples.rough_surface((64, 64), rms=1e308, correlation_length=1e-8),
     r"rms must be in \[0, 0.001\] m"),  # before: "heights must be finite"
    (lambda: samples.grating(10, 1e-9, period=1.5e-9), r"period must be in \[2e-09, inf\] m"),
    (lambda: samples.profile("moon"), "name must be one of"),
    (lambda: samples.Sample(np.zeros((2, 2, 2)), 1e-9), "heights must be a 1-D or 2-D"),
    (lambda: samples.Sample([0.0, np.inf], 1e-9), "heights must be finite"),
    (lambda: samples.step(10).line(0), "line\\(\\) needs a 2-D sample"),
    (lambda: samples.Sample(np.zeros((2, 2)), 1e-9, pixel_size_y=0.0),
     "pixel_size_y must be > 0 m"),
])
def test_bad_input(call, match):
    with pytest.raises(ValueError, match=match):
        call()


# -- found by the bad-input campaign (tests/test_api_campaign.py) ------------------------------
@pytest.mark.parametrize("call, named", [
    # before: "period must be in [2e+300, inf] m, got 5e-07", the pixel size unnamed
    (lambda: samples.grating(pixel_size=1e300), "pixel_size = 1e+300 m"),
    # before: "correlation_length must be in (0, 6.4e-299] m", the pixel size unnamed
    (lambda: samples.rough_surface(pixel_size=1e-300), "pixel_size = 1e-300 m"),
])
def test_a_bound_set_by_the_pixel_size_names_it(call, named):
    with pytest.raises(ValueError, match=re.escape(named)):
        call()


def test_particle_radius_is_bounded_by_the_z_range_not_an_overflow():
    # before: OverflowError "cannot convert float infinity to integer" (radius / pixel_size)
    with pytest.raises(ValueError, match=r"radius must be in \(0, 0.0005\] m, got 1e\+300"):
        samples.particles((32, 32), radius=1e300)
    # the largest radius and the smallest pixels: particles as large as the image, finite
    img = samples.particles((16, 16), pixel_size=1e-300, count=2, radius=MAX_HEIGHT / 2)
    assert np.isfinite(img.heights).all() and img.heights.max() <= MAX_HEIGHT + 1e-9


@pytest.mark.parametrize("name", [math.nan, True, 1 + 1j, object(), np.array([0.0, np.nan])])
def test_sample_name_must_be_text(name):
    # before: accepted silently, then printed as a title
    with pytest.raises(TypeError, match="name must be a str"):
        samples.Sample(np.zeros((2, 2)), 1e-9, name)
