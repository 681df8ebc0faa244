"""Tip dilation, reconstruction, certainty map and blind tip estimation (module (f), item 2).

Checked against an independent implementation: ``scipy.ndimage.grey_dilation`` with the tip's
structuring function b(y) = -t(-y) written out here from the tips' textbook formulas (not from
:func:`tip_surface`), over a footprint as large as the whole image (no cut), with
``mode="constant", cval=-inf`` (points outside the image are never touched). Tolerances are
round-off: a few ulps of the heights.
"""
import math

import numpy as np
import pytest
from scipy import ndimage

from afmsmiler.contact.tips import Conical, Parabolic, Pyramidal, Spherical
from afmsmiler.imaging import dilation
from afmsmiler.imaging.dilation import (certainty_map, dilate, erode, estimate_tip_radius,
                                        sphere_apparent_width, tip_surface)
from afmsmiler.samples import Sample

TIPS = [Parabolic(radius=6e-9), Spherical(radius=5e-9), Conical(half_angle=math.radians(25)),
        Pyramidal(face_angle=math.radians(35))]
IDS = ["parabolic", "spherical", "conical", "pyramidal"]


def textbook_t(tip, u, v):
    """t(u, v) in m from the tips' formulas (inf where the sphere's shank stands)."""
    if isinstance(tip, Parabolic):
        return (u * u + v * v) / (2 * tip.radius)
    if isinstance(tip, Spherical):
        rho2 = u * u + v * v
        with np.errstate(invalid="ignore"):
            inside = rho2 <= tip.radius ** 2 * (1 + 1e-12)  # the equator, to round-off
            return np.where(inside, tip.radius - np.sqrt(np.maximum(tip.radius ** 2 - rho2, 0)),
                            np.inf)
    if isinstance(tip, Conical):
        return np.hypot(u, v) / math.tan(tip.half_angle)
    return np.maximum(abs(u), abs(v)) / math.tan(tip.face_angle)


def scipy_dilation(heights, tip, dx, dy=None):
    """scipy's grey dilation by b = -t over a footprint covering the whole image."""
    if heights.ndim == 1:
        n = heights.shape[0]
        u = np.arange(-(n - 1), n) * dx
        b = -textbook_t(tip, u, 0.0 * u)
    else:
        ny, nx = heights.shape
        u = np.arange(-(nx - 1), nx) * dx
        v = np.arange(-(ny - 1), ny) * dy
        b = -textbook_t(tip, u[None, :], v[:, None])
    return ndimage.grey_dilation(heights, structure=b, mode="constant", cval=-np.inf)


def rough(shape, rms, seed):
    rng = np.random.default_rng(seed)
    h = ndimage.gaussian_filter(rng.normal(size=shape), 1.0)
    return h / h.std() * rms


def round_off(h):
    return 16 * np.finfo(float).eps * np.max(np.abs(h))


# --- tip_surface -----------------------------------------------------------------------------
@pytest.mark.parametrize("tip", TIPS, ids=IDS)
def test_tip_surface_is_the_textbook_tip_cut_at_max_height(tip):
    dx, dy, cut = 1e-9, 1.5e-9, 4e-9
    t = tip_surface(tip, dx, dy, max_height=cut)
    ny, nx = (k // 2 for k in t.shape)
    assert t.shape == (2 * ny + 1, 2 * nx + 1) and t[ny, nx] == 0.0 and np.all(t >= 0)
    u = np.arange(-nx, nx + 1) * dx
    v = np.arange(-ny, ny + 1) * dy
    ref = np.minimum(textbook_t(tip, u[None, :], v[:, None]), cut)
    np.testing.assert_allclose(t, ref, rtol=1e-12, atol=1e-24)
    # the grid reaches as far as the tip stays below the cut, and no farther
    assert textbook_t(tip, (nx + 1) * dx, 0.0) > cut * (1 - 1e-12) or isinstance(tip, Spherical)
    assert textbook_t(tip, nx * dx, 0.0) <= cut * (1 + 1e-12)


def test_tip_surface_default_cut_and_sphere_shank():
    t = tip_surface(Conical(half_angle=0.4), 1e-9)
    assert t.shape == (65, 65)  # 32 pixels from the apex along x by default
    s = tip_surface(Spherical(radius=3e-9), 1e-9, max_height=10e-9)
    assert s.shape == (7, 7) and s[3, 0] == pytest.approx(3e-9)  # the equator, at R
    assert s[0, 0] == 10e-9  # beyond R: the shank, clipped at the cut


def test_tip_surface_rejects_bad_input():
    with pytest.raises(TypeError, match="tip"):
        tip_surface("parabolic", 1e-9)
    with pytest.raises(ValueError, match="pixel_size"):
        tip_surface(Parabolic(), 0.0)
    with pytest.raises(ValueError, match="pixel_size_y"):
        tip_surface(Parabolic(), 1e-9, -1.0)
    with pytest.raises(ValueError, match="max_height"):
        tip_surface(Parabolic(), 1e-9, max_height=-1e-9)
    with pytest.raises(ValueError, match="max_height"):  # a grid beyond MAX_TIP_PIXELS
        tip_surface(Conical(half_angle=1.5), 1e-9, max_height=1e-6)


# --- dilate: equal to scipy for every tip -----------------------------------------------------
@pytest.mark.parametrize("tip", TIPS, ids=IDS)
def test_dilate_image_equals_scipy_grey_dilation(tip):
    h = rough((24, 31), 1e-9, seed=1)
    sample = Sample(h, 0.8e-9, "rough", pixel_size_y=1.1e-9)
    out = dilate(sample, tip)
    ref = scipy_dilation(h, tip, 0.8e-9, 1.1e-9)
    np.testing.assert_allclose(out.heights, ref, rtol=0, atol=round_off(h))
    assert out.pixel_size == 0.8e-9 and out.pixel_size_y == 1.1e-9 and out.name == "rough"
    assert np.all(out.heights >= h)


@pytest.mark.parametrize("tip", TIPS, ids=IDS)
def test_dilate_line_equals_scipy_grey_dilation(tip):
    h = rough((301,), 3e-9, seed=2)
    out = dilate(Sample(h, 0.5e-9), tip)
    np.testing.assert_allclose(out.heights, scipy_dilation(h, tip, 0.5e-9), rtol=0,
                               atol=round_off(h))


@pytest.mark.parametrize("shape, dx, dy", [((40, 40), 1e-9, 1e-9), ((33, 57), 0.7e-9, 2.3e-9),
                                           ((64, 21), 1.9e-9, 0.6e-9)])
def test_parabolic_separable_path_equals_general_path(shape, dx, dy):
    """Felzenszwalb-Huttenlocher envelope (rows, then columns) = the loop over the tip's pixels."""
    tip = Parabolic(radius=7e-9)
    h = rough(shape, 1e-9, seed=3)
    h[5, 3] = h.max() + 2e-9  # a spike, so the envelope has long stretches of one parabola
    height = float(np.ptp(h))
    t = tip_surface(tip, dx, dy, max_height=height)
    general = dilation._dilate_general(h, t, height)
    fast = dilate(Sample(h, dx, pixel_size_y=dy), tip).heights
    np.testing.assert_allclose(fast, general, rtol=0, atol=round_off(h))
    np.testing.assert_allclose(fast, scipy_dilation(h, tip, dx, dy), rtol=0, atol=round_off(h))


def test_parabolic_envelope_on_adversarial_lines():
    """Ties, plateaus, a line of one pixel's rise, a concave line (every parabola popped)."""
    x = np.arange(50.0)
    lines = np.array([np.zeros(50), -(x - 25) ** 2 * 1e-3, (x - 25) ** 2 * 1e-3,
                      np.where(x % 7 == 0, 1.0, 0.0), x * 0.3, -x * 0.3,
                      np.repeat([0.0, 1.0], 25)])
    a = 0.05
    got = dilation._envelope_lines(lines, a)
    p = x[None, :]
    ref = np.max(lines[:, None, :] - a * (x[:, None] - p) ** 2, axis=-1)
    np.testing.assert_allclose(got, ref, rtol=0, atol=1e-13)


def test_flat_sample_is_its_own_image():
    h = np.full((8, 9), 3e-9)
    for tip in TIPS:
        assert np.array_equal(dilate(Sample(h, 1e-9), tip).heights, h)


def test_dilate_rejects_bad_input(monkeypatch):
    h = np.zeros((20, 20))
    h[10, 10] = 50e-9
    sample = Sample(h, 1e-9)
    with pytest.raises(TypeError, match="sample"):
        dilate(h, Parabolic())
    with pytest.raises(TypeError, match="tip"):
        dilate(sample, 20e-9)
    # a tip wider than the image at the sample's height range: sqrt(2 R H) = 45 nm > 19 nm
    with pytest.raises(ValueError, match="tip.*wider than the image"):
        dilate(sample, Parabolic(radius=20e-9))
    with pytest.raises(ValueError, match="tip.*wider than the image"):
        dilate(Sample(h[10], 1e-9), Conical(half_angle=0.5))
    # the general path's work bound, stated and honoured before any work
    monkeypatch.setattr(dilation, "MAX_WORK", 1000)
    with pytest.raises(ValueError, match="MAX_WORK"):
        dilate(sample, Spherical(radius=5e-9))
