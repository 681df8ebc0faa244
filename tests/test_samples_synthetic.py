"""The 2-D generators against their definitions: a self-affine surface's RMS, correlation length
(the 1/e length of its autocorrelation) and Hurst exponent (the slope of its height-height
correlation), a worm-like chain's tangent correlation exp(-s / (2 P)), particles' coverage,
size spread and spacing, terraces' steps and a 2-D grating's pitch and duty."""
import math

import numpy as np
import pytest

from afmsmiler import samples
from afmsmiler.samples.synthetic import MAX_FIBRE_POINTS


def _acf_x(h, lags):
    """The normalised autocorrelation along x (periodic: the surfaces are made periodic)."""
    return np.array([np.mean(h * np.roll(h, -lag, axis=1)) for lag in lags]) / h.var()


@pytest.mark.parametrize("hurst", [0.4, 0.7, 1.0])
def test_rough_surface_rms_and_correlation_length(hurst):
    # G(r) = rms^2 exp(-(r / T)^(2 H)): at r = T the normalised ACF is 1/e whatever H. Averaged
    # over 6 seeds of 256 x 256 pixels with T = 8 pixels, the ACF estimate's spread is about
    # 0.01 (Bartlett: var ~ sum(acf^2) / N over ~ (2 T)^2 / 256^2 independent areas), so
    # 0.04 is four of them; the 1/e length then lies within 10 % of T (the ACF's slope at T
    # is 2 H / (e T)).
    T, lags = 8, np.arange(0, 25)
    acf = np.zeros(lags.size)
    for seed in range(6):
        s = samples.rough_surface((256, 256), 1e-9, 2e-9, T * 1e-9, hurst=hurst, seed=seed)
        assert s.heights.std() == pytest.approx(2e-9, rel=1e-12)
        acf += _acf_x(s.heights, lags) / 6
    np.testing.assert_allclose(acf, np.exp(-(lags / T) ** (2 * hurst)), atol=0.04)
    one_over_e = np.interp(-np.exp(-1.0), -acf, lags)  # first crossing (acf falls)
    assert one_over_e == pytest.approx(T, rel=0.1)
    assert s.metadata["hurst"] == hurst


@pytest.mark.parametrize("hurst", [0.3, 0.5, 0.8])
def test_rough_surface_hurst_exponent_from_the_height_height_correlation(hurst):
    # H(r) = <(h(x + r) - h(x))^2> = 2 rms^2 (1 - exp(-(r / T)^(2 H))), which grows as r^(2 H)
    # for r << T. Its log-log slope between r = 1 and 4 pixels with T = 16 pixels is that of
    # the formula (2 H less the next term's (r / T)^(2 H) / 2: 0.516 for H = 0.3, 0.934 for 0.5,
    # 1.565 for 0.8); 4 seeds of 256 x 256 estimate it to about 1 %: 3 % is three of them.
    T, r = 16, np.array([1.0, 2.0, 4.0])
    hh = np.zeros(3)
    for seed in range(4):
        h = samples.rough_surface((256, 256), 1e-9, 1e-9, T * 1e-9, hurst=hurst,
                                  seed=seed).heights
        hh += [np.mean((np.roll(h, -int(k), axis=1) - h) ** 2) for k in r]
    slope = np.polyfit(np.log(r), np.log(hh), 1)[0]
    model = np.polyfit(np.log(r), np.log(1 - np.exp(-(r / T) ** (2 * hurst))), 1)[0]
    assert slope == pytest.approx(model, rel=0.03)
    assert model == pytest.approx(2 * hurst, rel=0.15)  # the power law r^(2 H) below T
    # and the smoother surface has the steeper correlation: H orders the slopes
    assert (slope > 1.0) == (hurst > 0.5)


def test_rough_surface_gaussian_is_unchanged_and_hurst_is_bounded():
    a = samples.rough_surface((64, 64), 1e-9, 1e-9, 5e-9, seed=3)
    b = samples.rough_surface((64, 64), 1e-9, 1e-9, 5e-9, hurst=1.0, seed=3)
    np.testing.assert_array_equal(a.heights, b.heights)
    with pytest.raises(ValueError, match=r"hurst must be in \[0.1, 1\]"):
        samples.rough_surface((64, 64), 1e-9, 1e-9, 5e-9, hurst=1.5)


def test_fibres_are_worm_like_chains_of_their_persistence_length():
    # 2-D worm-like chain: <cos(theta(s) - theta(0))> = exp(-s / (2 P)) (Rivetti et al. 1996).
    # 1000 chains of 4 P: each s-average has about 2000 independent pairs of variance <= 0.5,
    # a spread of 0.016; the tolerance 0.05 is three of them.
    P, L = 50e-9, 200e-9
    f = samples.fibres((16, 16), 2e-9, count=1000, contour_length=L, persistence_length=P,
                       seed=7)
    step = f.metadata["step"]
    tangents = [np.arctan2(*np.diff(p, axis=0).T[::-1]) for p in f.metadata["paths"]]
    for s in (P / 2, P, 2 * P, 3 * P):
        k = int(round(s / step))
        c = np.mean([np.mean(np.cos(t[k:] - t[:-k])) for t in tangents])
        assert c == pytest.approx(math.exp(-s / (2 * P)), abs=0.05), s
    lengths = [np.sum(np.hypot(*np.diff(p, axis=0).T)) for p in f.metadata["paths"]]
    np.testing.assert_allclose(lengths, L, rtol=1e-9)


def test_a_stiff_fibre_has_its_height_and_width():
    # persistence 1000 x its length: a straight tube of half-ellipse section; the pixels above
    # half its height form a band sqrt(3)/2 * width wide along its length
    w, ht, L, px = 10e-9, 2e-9, 300e-9, 1e-9
    f = samples.fibres((400, 400), px, count=1, contour_length=L, persistence_length=1e3 * L,
                       width=w, height=ht, rms=0.0, seed=1)
    p = f.metadata["paths"][0]
    assert np.ptp(np.diff(np.arctan2(*np.diff(p, axis=0).T[::-1]))) < 0.01
    assert f.heights.max() == pytest.approx(ht, rel=0.01)
    inside = np.all((p > 0) & (p < 400 * px), axis=1).mean()  # the part inside the image
    area = np.count_nonzero(f.heights > ht / 2) * px * px
    assert area == pytest.approx(inside * L * math.sqrt(3) / 2 * w, rel=0.1)


def test_particles_coverage_spread_and_no_overlap():
    s = samples.particles((256, 256), 2e-9, radius=6e-9, coverage=0.3, spread=0.2,
                          overlap=False, rms=0.0, seed=4)
    c, r = s.metadata["centres"], s.metadata["radii"]
    assert s.metadata["count"] == round(0.3 * (512e-9) ** 2 / (math.pi * 36e-18))
    d = np.hypot(*(c[:, None, :] - c[None, :, :]).transpose(2, 0, 1))
    np.fill_diagonal(d, np.inf)
    assert np.all(d >= r[:, None] + r[None, :] - 1e-18)
    # log-normal radii: mean 6 nm and relative spread 0.2, to 3 standard errors of ~700 radii
    n = r.size
    assert r.mean() == pytest.approx(6e-9, rel=3 * 0.2 / math.sqrt(n))
    assert r.std() / r.mean() == pytest.approx(0.2, rel=3 / math.sqrt(2 * n))
    assert s.heights.max() == pytest.approx(2 * r.max(), rel=0.02)
    with pytest.raises(ValueError, match="coverage must be in"):
        samples.particles(coverage=0.6)
    with pytest.raises(ValueError, match="non-overlapping particles fit"):
        samples.particles((32, 32), 1e-9, count=50, radius=10e-9, overlap=False)


def test_terraces_steps_and_widths():
    t = samples.terraces((32, 200), 1e-9, step_height=0.3e-9, terrace_width=20e-9)
    levels = np.unique(np.round(t.heights / 0.3e-9, 9))
    np.testing.assert_array_equal(levels, np.arange(10))
    row = t.heights[5]
    edges = np.flatnonzero(np.diff(row)) + 1
    np.testing.assert_array_equal(np.diff(edges), 20)  # 20 pixels a terrace
    np.testing.assert_allclose(np.diff(row)[edges - 1], 0.3e-9, rtol=1e-12)
    np.testing.assert_array_equal(t.heights[0], t.heights[31])  # steps along y
    up = samples.terraces((100, 16), 1e-9, 0.3e-9, 20e-9, direction=math.pi / 2)
    assert np.all(np.diff(up.heights[:, 3]) >= 0) and np.ptp(up.heights[:, 3]) > 1e-9
    with pytest.raises(ValueError, match=r"terrace_width must be in \[2e-09, inf\] m"):
        samples.terraces((8, 8), 1e-9, 0.3e-9, 1e-9)


def test_grating_as_an_image_keeps_pitch_and_duty():
    g = samples.grating((40, 400), 1e-9, period=100e-9, height=20e-9, duty=0.25)
    np.testing.assert_array_equal(g.heights[0], samples.grating(400, 1e-9, 100e-9, 20e-9,
                                                                0.25).heights)
    np.testing.assert_array_equal(g.heights, np.broadcast_to(g.heights[0], (40, 400)))
    sq = samples.grating((200, 200), 1e-9, 100e-9, 20e-9, 0.5, pattern="squares")
    assert np.count_nonzero(sq.heights) == 4 * 50 * 50  # 4 pillars of 50 x 50 pixels
    with pytest.raises(ValueError, match="pattern 'squares' needs an image"):
        samples.grating(64, 1e-9, 10e-9, pattern="squares")
    with pytest.raises(ValueError, match="shape must be an int or a pair"):
        samples.grating((2, 2, 2))


def test_fibre_points_are_bounded():
    with pytest.raises(ValueError, match=f"at most {MAX_FIBRE_POINTS} chain points"):
        samples.fibres((64, 64), 1e-9, count=1000, contour_length=6e-6)
