"""Sample generators: shapes, physical sizes and statistics against their definitions."""
import numpy as np
import pytest

from afmsmiler import samples


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
    # Gaussian filter exp(-(pi l f)^2) on white noise: autocorrelation exp(-r^2 / (2 l^2)) / ...
    # so neighbours (r = l/5) are strongly correlated, points 5 l apart are not
    h = s.heights - s.heights.mean()
    near = np.mean(h[:, :-1] * h[:, 1:]) / h.var()
    far = np.mean(h[:, :-25] * h[:, 25:]) / h.var()
    assert near > 0.9 and abs(far) < 0.1
    np.testing.assert_array_equal(s.heights, samples.rough_surface(
        (256, 256), 2e-9, rms=3e-9, correlation_length=10e-9, seed=4).heights)
    assert samples.rough_surface(64, 1e-9).heights.shape == (64,)


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


@pytest.mark.parametrize("call, match", [
    (lambda: samples.step(1), "pixels must be an integer in"),
    (lambda: samples.step(10, -1e-9), "pixel_size must be > 0 m"),
    (lambda: samples.step(10, 1e-9, np.nan), "height must be a finite"),
    (lambda: samples.grating(10, 1e-9, period=0.0), "period must be > 0 m"),
    (lambda: samples.grating(10, 1e-9, duty=1.0), r"duty must be in \(0, 1\)"),
    (lambda: samples.rough_surface((4, 4, 4)), "shape must be"),
    (lambda: samples.rough_surface(8, rms=-1e-9), "rms must be in"),
    (lambda: samples.profile("moon"), "name must be one of"),
    (lambda: samples.Sample(np.zeros((2, 2, 2)), 1e-9), "heights must be a 1-D or 2-D"),
    (lambda: samples.Sample([0.0, np.inf], 1e-9), "heights must be finite"),
    (lambda: samples.step(10).line(0), "line\\(\\) needs a 2-D sample"),
])
def test_bad_input(call, match):
    with pytest.raises(ValueError, match=match):
        call()
