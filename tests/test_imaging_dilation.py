"""Tip dilation, reconstruction, certainty map and blind tip estimation (module (f), item 2).

Checked against an independent implementation: ``scipy.ndimage.grey_dilation`` with the tip's
structuring function b(y) = -t(-y) written out here from the tips' textbook formulas (not from
:func:`tip_surface`), over a footprint as large as the whole image (no cut), with
``mode="constant", cval=-inf`` (points outside the image are never touched). Tolerances are
round-off: a few ulps of the heights.
"""
import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import pytest
from scipy import ndimage

from afmsmiler.contact.tips import Conical, Parabolic, Pyramidal, Spherical, Tip
from afmsmiler.imaging import dilation
from afmsmiler.imaging.dilation import (certainty_map, dilate, erode, estimate_tip_radius,
                                        sphere_apparent_width, tip_radius_from_width,
                                        tip_surface)
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


def scipy_dilation(heights, tip, dx, dy=None, cut=True):
    """scipy's grey dilation by b = -t over a footprint covering the whole image.

    With ``cut``, the footprint is cropped to the box where the textbook t stays below the
    heights' range (the rest cannot win; the tests with ``cut=False`` show it), for speed.
    """
    if heights.ndim == 1:
        n = heights.shape[0]
        u = np.arange(-(n - 1), n) * dx
        b = -textbook_t(tip, u, 0.0 * u)
    else:
        ny, nx = heights.shape
        u = np.arange(-(nx - 1), nx) * dx
        v = np.arange(-(ny - 1), ny) * dy
        b = -textbook_t(tip, u[None, :], v[:, None])
    if cut:
        keep = -b <= np.ptp(heights) * (1 + 1e-9)
        box = tuple(slice(ix.min(), ix.max() + 1) for ix in np.nonzero(keep))
        b = b[box]
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


@dataclass(frozen=True)
class Quartic(Tip):
    """A tip shape the module does not know: t = L (rho / L)^4, L = 10 nm (bisection path)."""

    key: ClassVar[str] = "quartic"
    title: ClassVar[str] = "quartic"
    formula: ClassVar[str] = "t = L (rho / L)^4"
    parameters: ClassVar[tuple] = ()

    def _profile(self, r):
        return 1e-8 * (r / 1e-8) ** 4


def test_any_tip_shape_is_dilated_exactly():
    tip = Quartic()
    t = tip_surface(tip, 1e-9, max_height=5e-9)
    n = t.shape[1] // 2
    assert 1e-8 * (n * 1e-9 / 1e-8) ** 4 <= 5e-9 < 1e-8 * ((n + 1) * 1e-9 / 1e-8) ** 4
    h = rough((30, 30), 1e-9, seed=9)
    u = np.arange(-29, 30) * 1e-9
    b = -1e-8 * (np.hypot(u[None, :], u[:, None]) / 1e-8) ** 4
    ref = ndimage.grey_dilation(h, structure=b, mode="constant", cval=-np.inf)
    np.testing.assert_allclose(dilate(Sample(h, 1e-9), tip).heights, ref, rtol=0,
                               atol=round_off(h))


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
    with pytest.raises(ValueError, match="pixel_size_y"):  # the same, from a tiny pixel
        tip_surface(Parabolic(), 1e-9, 1e-300)


# --- dilate: equal to scipy for every tip -----------------------------------------------------
@pytest.mark.parametrize("tip", TIPS, ids=IDS)
def test_dilate_image_equals_scipy_grey_dilation(tip):
    h = rough((24, 31), 1e-9, seed=1)
    sample = Sample(h, 0.8e-9, "rough", pixel_size_y=1.1e-9)
    out = dilate(sample, tip)
    ref = scipy_dilation(h, tip, 0.8e-9, 1.1e-9, cut=False)
    np.testing.assert_allclose(out.heights, ref, rtol=0, atol=round_off(h))
    assert out.pixel_size == 0.8e-9 and out.pixel_size_y == 1.1e-9 and out.name == "rough"
    assert np.all(out.heights >= h)


@pytest.mark.parametrize("tip", TIPS, ids=IDS)
def test_dilate_line_equals_scipy_grey_dilation(tip):
    h = rough((301,), 3e-9, seed=2)
    out = dilate(Sample(h, 0.5e-9), tip)
    np.testing.assert_allclose(out.heights, scipy_dilation(h, tip, 0.5e-9, cut=False), rtol=0,
                               atol=round_off(h))


@pytest.mark.parametrize("shape, dx, dy", [((40, 40), 1e-9, 1e-9), ((33, 57), 0.7e-9, 2.3e-9),
                                           ((64, 21), 1.9e-9, 0.6e-9)])
@pytest.mark.parametrize("method", ["envelope", "window", "auto"])
def test_parabolic_separable_path_equals_general_path(shape, dx, dy, method):
    """Rows then columns, by the Felzenszwalb-Huttenlocher envelope or by the direct window,
    equal the loop over the tip's pixels and scipy."""
    tip = Parabolic(radius=7e-9)
    h = rough(shape, 1e-9, seed=3)
    h[5, 3] = h.max() + 2e-9  # a spike, so the envelope has long stretches of one parabola
    height = float(np.ptp(h))
    t = tip_surface(tip, dx, dy, max_height=height)
    general = dilation._dilate_general(h, t, height)
    fast = dilation._dilate_parabolic(h, tip.radius, dx, dy, height, method)
    np.testing.assert_allclose(fast, general, rtol=0, atol=round_off(h))
    np.testing.assert_allclose(fast, scipy_dilation(h, tip, dx, dy), rtol=0, atol=round_off(h))
    line = dilation._dilate_parabolic(h[0], tip.radius, dx, dy, float(np.ptp(h[0])), method)
    np.testing.assert_allclose(line, scipy_dilation(h[0], tip, dx), rtol=0, atol=round_off(h))


def test_dilate_takes_the_envelope_beyond_the_window_limit(monkeypatch):
    """A window wider than WINDOW_LIMIT pixels: dilate takes the O(N) envelope, same image."""
    calls = []
    envelope = dilation._envelope_lines
    monkeypatch.setattr(dilation, "_envelope_lines", lambda g, a: calls.append(g.shape) or
                        envelope(g, a))
    monkeypatch.setattr(dilation, "WINDOW_LIMIT", 3)
    tip = Parabolic(radius=30e-9)
    h = rough((60, 90), 1e-9, seed=4)
    out = dilate(Sample(h, 0.5e-9, pixel_size_y=0.9e-9), tip).heights
    assert calls == [(60, 90), (90, 60)]  # rows, then columns, all lines at once
    np.testing.assert_allclose(out, scipy_dilation(h, tip, 0.5e-9, 0.9e-9), rtol=0,
                               atol=round_off(h))


def test_parabolic_envelope_on_adversarial_lines():
    """Ties, plateaus, a line of one pixel's rise, a concave line (every parabola popped)."""
    x = np.arange(50.0)
    lines = np.array([np.zeros(50), -(x - 25) ** 2 * 1e-3, (x - 25) ** 2 * 1e-3,
                      np.where(x % 7 == 0, 1.0, 0.0), x * 0.3, -x * 0.3,
                      np.repeat([0.0, 1.0], 25)])
    for a in (1e-4, 0.05, 10.0):  # from one parabola over everything to none over another
        ref = np.max(lines[:, None, :] - a * (x[:, None] - x[None, :]) ** 2, axis=-1)
        vector = dilation._envelope_vector(lines, a)
        scalar = np.array([dilation._envelope_scalar(line, a) for line in lines])
        np.testing.assert_allclose(vector, ref, rtol=0, atol=1e-13)
        np.testing.assert_allclose(scalar, ref, rtol=0, atol=1e-13)


@pytest.mark.parametrize("n", [2, 7, 8])
def test_window_up_to_the_whole_line(n):
    """The direct window for every w from 0 to beyond the line (edges, 2 d >= n)."""
    g = np.random.default_rng(n).normal(size=(n, 3))
    x = np.arange(n)
    for w in range(n + 2):
        d = x[:, None] - x[None, :]
        cost = np.where(abs(d) <= w, 0.3 * d * d, np.inf)
        ref = np.max(g[None, :, :] - cost[:, :, None], axis=1)
        np.testing.assert_array_equal(dilation._window_axis0(g, 0.3, w), ref)


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
    phase = Sample(h, 1e-9, channel="Phase", unit="deg")
    with pytest.raises(ValueError, match="sample must hold heights in m.*'Phase'.*'deg'"):
        dilate(phase, Parabolic())
    with pytest.raises(ValueError, match="image must hold heights"):
        estimate_tip_radius(phase)
    # a tip wider than the image at the sample's height range: sqrt(2 R H) = 45 nm > 19 nm
    with pytest.raises(ValueError, match="tip.*wider than the image"):
        dilate(sample, Parabolic(radius=20e-9))
    with pytest.raises(ValueError, match="tip.*wider than the image"):
        dilate(Sample(h[10], 1e-9), Conical(half_angle=0.5))
    # the general path's work bound, stated and honoured before any work
    monkeypatch.setattr(dilation, "MAX_WORK", 1000)
    with pytest.raises(ValueError, match="MAX_WORK"):
        dilate(sample, Spherical(radius=5e-9))


# --- a sphere on a substrate: the apparent width ----------------------------------------------
@pytest.mark.slow
def test_paraboloid_on_sphere_width_derivation_with_sympy():
    """The closed form of sphere_apparent_width, derived again with sympy.

    The tip z = (x - X0)^2 / (2 R), its apex on the substrate at X0, touches the sphere's upper
    surface z = r + sqrt(r^2 - x^2): equal heights and slopes at the contact x. Parametrised by
    c = cos(slope angle), R = 2 r c^2 / (1 - c) (the quadratic 2 r c^2 + R c - R = 0), the
    contact x = r sqrt(1 - c^2) and X0 = m (R + r c), m = sqrt(1 - c^2) / c, satisfy both
    equations identically; and sympy's nsolve of the two equations for (x, X0), from a rough
    start, gives the same X0 as the library.
    """
    sp = pytest.importorskip("sympy")
    r, c, x, x0, big_r = sp.symbols("r c x X0 R", positive=True)
    sphere = r + sp.sqrt(r ** 2 - x ** 2)
    tip = (x - x0) ** 2 / (2 * big_r)
    m = sp.sqrt(1 - c ** 2) / c
    at = {big_r: 2 * r * c ** 2 / (1 - c), x: r * sp.sqrt(1 - c ** 2)}
    at[x0] = m * (at[big_r] + r * c)
    for eq in (sphere - tip, sp.diff(sphere, x) - sp.diff(tip, x)):
        assert sp.simplify(eq.subs(at)) == 0
    # c in (0, 1) solves the quadratic with the library's root
    for rv, rr in [(10e-9, 30e-9), (10e-9, 3e-9), (5e-9, 500e-9)]:
        numbers = {r: sp.Float(rv / 1e-9, 30), big_r: sp.Float(rr / 1e-9, 30)}
        eqs = [e.subs(numbers) for e in (sphere - tip, sp.diff(sphere, x) - sp.diff(tip, x))]
        guess = (0.7 * rv / 1e-9, 0.5 * (2 * rv + 2 * math.sqrt(rv * rr)) / 1e-9)
        sol = sp.nsolve(eqs, (x, x0), guess, prec=30)
        width = 2 * float(sol[1]) * 1e-9
        assert sphere_apparent_width(rv, Parabolic(radius=rr)) == pytest.approx(width, rel=1e-12)


def test_sphere_width_limits():
    r = 10e-9
    # a blunt paraboloid tends to the sphere-sphere result 4 sqrt(R r)
    blunt = 1e-4
    assert sphere_apparent_width(r, Parabolic(radius=blunt)) == pytest.approx(
        4 * math.sqrt(blunt * r), rel=1e-4)
    # a sharp one to the particle's width plus the tip's reach 2 sqrt(2 r R)
    sharp = 1e-12
    assert sphere_apparent_width(r, Parabolic(radius=sharp)) == pytest.approx(
        2 * r + 2 * math.sqrt(2 * r * sharp), rel=1e-4)
    assert sphere_apparent_width(r, Spherical(radius=40e-9)) == pytest.approx(4 * 20e-9)
    assert sphere_apparent_width(r, Spherical(radius=4e-9)) == pytest.approx(28e-9)
    # a vanishing particle: the closed form stays free of cancellation (no 0 / 0)
    assert sphere_apparent_width(1e-300, Parabolic(radius=20e-9)) == pytest.approx(
        4 * math.sqrt(1e-300 * 20e-9), rel=1e-9)
    with pytest.raises(ValueError, match="particle_radius"):
        sphere_apparent_width(0.0, Parabolic())
    with pytest.raises(ValueError, match="particle_radius"):
        sphere_apparent_width(1e300, Parabolic())
    with pytest.raises(TypeError, match="tip"):
        sphere_apparent_width(r, Conical())


def test_tip_radius_from_width_inverts_the_apparent_width():
    r = 10e-9
    radii = np.logspace(-11, -4, 30)
    widths = [sphere_apparent_width(r, Parabolic(radius=R)) for R in radii]
    assert np.all(np.diff(widths) > 0)  # monotone: the inversion is unique
    for R, w in zip(radii, widths):
        assert tip_radius_from_width(r, w) == pytest.approx(R, rel=1e-9)
    # the blunt-tip limit, the classic W^2 / (16 r)
    w = 4 * math.sqrt(1e-3 * r)
    assert tip_radius_from_width(r, w) == pytest.approx(1e-3, rel=1e-4)
    with pytest.raises(ValueError, match="width"):
        tip_radius_from_width(r, 2 * r)  # the particle's own width: no tip is that sharp
    with pytest.raises(ValueError, match="width"):
        tip_radius_from_width(r, -1.0)
    with pytest.raises(ValueError, match="particle_radius"):
        tip_radius_from_width(float("nan"), 30e-9)


def sphere_on_substrate(r, dx, half_width, dy=None):
    """A sphere of radius r on the substrate z = 0, centred in a line (dy None) or an image."""
    n = int(round(half_width / dx))
    x = np.arange(-n, n + 1) * dx
    if dy is None:
        rho2 = x * x
    else:
        m = int(round(half_width / dy))
        y = np.arange(-m, m + 1) * dy
        rho2 = x[None, :] ** 2 + y[:, None] ** 2
    return np.where(rho2 <= r * r, r + np.sqrt(np.maximum(r * r - rho2, 0.0)), 0.0)


def measured_width(line, dx):
    """Width in m of the part of the image above the substrate (to a pixel)."""
    return np.count_nonzero(line > 1e-6 * line.max()) * dx


@pytest.mark.parametrize("tip", [Parabolic(radius=30e-9), Parabolic(radius=3e-9),
                                 Spherical(radius=15e-9), Spherical(radius=4e-9)],
                         ids=["paraboloid blunt", "paraboloid sharp", "sphere R > r",
                              "sphere R < r (shank)"])
def test_dilated_sphere_has_the_analytic_width(tip):
    """The line through the sphere's centre: within two pixels (0.1 nm) of the closed form."""
    r, dx = 10e-9, 0.05e-9
    width = sphere_apparent_width(r, tip)
    line = sphere_on_substrate(r, dx, width / 2 + 2 * tip.radius + 5e-9)
    image = dilate(Sample(line, dx), tip).heights
    assert measured_width(image, dx) == pytest.approx(width, abs=2 * dx)


def test_dilated_sphere_image_has_the_analytic_width_on_its_centre_row():
    """The 2-D image (non-square pixels): the centre row's width, within two pixels."""
    r, dx, dy = 10e-9, 0.25e-9, 0.4e-9
    tip = Parabolic(radius=20e-9)
    width = sphere_apparent_width(r, tip)
    h = sphere_on_substrate(r, dx, width / 2 + 10e-9, dy)
    image = dilate(Sample(h, dx, pixel_size_y=dy), tip).heights
    centre = image[image.shape[0] // 2]
    assert measured_width(centre, dx) == pytest.approx(width, abs=2 * dx)
    assert image.max() == pytest.approx(2 * r)  # the top is where the sphere's top is


# --- reconstruction, certainty map, blind estimation -----------------------------------------
def holes_and_spikes(shape=(40, 48), seed=5):
    """A gently rough surface with narrow deep holes (the tip cannot enter) and sharp spikes."""
    h = rough(shape, 0.3e-9, seed)
    h[10, 10] -= 6e-9
    h[25, 30:32] -= 5e-9
    h[30, 12] += 4e-9
    h[8, 38] += 3e-9
    return h


@pytest.mark.parametrize("tip", TIPS, ids=IDS)
def test_erode_equals_scipy_grey_erosion(tip):
    h = rough((24, 31), 1e-9, seed=6)
    dx, dy = 0.8e-9, 1.1e-9
    got = erode(Sample(h, dx, pixel_size_y=dy), tip).heights
    ny, nx = h.shape
    u = np.arange(-(nx - 1), nx) * dx
    v = np.arange(-(ny - 1), ny) * dy
    b = -textbook_t(tip, u[None, :], v[:, None])
    ref = ndimage.grey_erosion(h, structure=b, mode="constant", cval=np.inf)
    np.testing.assert_allclose(got, ref, rtol=0, atol=round_off(h))


@pytest.mark.parametrize("tip", TIPS, ids=IDS)
def test_reconstruction_bounds_the_surface_and_is_exact_where_certain(tip):
    """Villarrubia: r = erode(dilate(s)) is the closing of s, r >= s, and r = s where certain.

    (r <= s would be the opening, erode then dilate; the reconstruction of an image is the
    other order.) The image is open: dilating its reconstruction gives it back.
    """
    h = holes_and_spikes()
    sample = Sample(h, 1e-9, pixel_size_y=1.2e-9)
    image = dilate(sample, tip)
    r = erode(image, tip).heights
    tol = round_off(h)
    assert np.all(r >= h - tol) and np.all(r <= image.heights + tol)
    certain = certainty_map(image, tip)
    assert certain.shape == h.shape and certain.dtype == bool
    np.testing.assert_allclose(r[certain], h[certain], rtol=0, atol=tol)
    # the holes' bottoms are out of the tip's reach, so neither reconstructed nor certain
    assert not certain[10, 10] and r[10, 10] > h[10, 10] + 1e-9
    # the spikes' tops are where the tip touched
    assert certain[30, 12] and certain[8, 38]
    reimaged = dilate(Sample(r, 1e-9, pixel_size_y=1.2e-9), tip).heights
    np.testing.assert_allclose(reimaged, image.heights, rtol=0, atol=tol)


def test_certainty_map_of_a_line():
    h = rough((200,), 0.5e-9, seed=7)
    h[50] += 5e-9
    h[120] -= 5e-9
    tip = Conical(half_angle=math.radians(20))
    image = dilate(Sample(h, 1e-9), tip)
    certain = certainty_map(image, tip)
    r = erode(image, tip).heights
    assert certain[50] and not certain[120]
    np.testing.assert_allclose(r[certain], h[certain], rtol=0, atol=round_off(h))


def spikes(shape, pixel_size, heights, seed=8):
    """Single-pixel spikes on a flat substrate, well apart and away from the edges."""
    rng = np.random.default_rng(seed)
    h = np.zeros(shape)
    ny, nx = shape
    for k, height in enumerate(heights):
        h[rng.integers(ny // 4, 3 * ny // 4) if k else ny // 2,
          (k + 1) * nx // (len(heights) + 1)] = height
    return h


@pytest.mark.parametrize("radius, dx, dy", [(20e-9, 2e-9, 2e-9), (5e-9, 0.5e-9, 0.8e-9),
                                            (200e-9, 5e-9, 5e-9)])
def test_estimate_tip_radius_from_sharp_spikes(radius, dx, dy):
    """A spike sharper than the tip images as the inverted paraboloid: R back to 1e-9."""
    h = spikes((64, 200), dx, [10e-9, 14e-9, 8e-9, 12e-9])
    image = dilate(Sample(h, dx, pixel_size_y=dy), Parabolic(radius=radius))
    assert estimate_tip_radius(image) == pytest.approx(radius, rel=1e-9)
    assert estimate_tip_radius(image, peaks=4) == pytest.approx(radius, rel=1e-9)
    line = dilate(Sample(h[32], dx), Parabolic(radius=radius))
    assert estimate_tip_radius(line) == pytest.approx(radius, rel=1e-9)


def test_estimate_tip_radius_is_an_upper_bound_on_any_image():
    """Blind estimation gives an upper bound of the tip: no image of R is sharper than R."""
    for seed in range(3):
        h = rough((50, 60), 2e-9, seed)
        image = dilate(Sample(h, 1e-9), Parabolic(radius=8e-9))
        assert estimate_tip_radius(image) >= 8e-9 * (1 - 1e-9)
    flat = Sample(np.zeros((5, 5)), 1e-9)
    assert estimate_tip_radius(flat) == math.inf


def test_reconstruction_rejects_bad_input():
    with pytest.raises(TypeError, match="image"):
        erode(np.zeros((4, 4)), Parabolic())
    with pytest.raises(TypeError, match="tip"):
        certainty_map(Sample(np.zeros((4, 4)), 1e-9), "cone")
    with pytest.raises(ValueError, match="peaks"):
        estimate_tip_radius(Sample(np.zeros((4, 4)), 1e-9), peaks=0)
    with pytest.raises(ValueError, match="image"):
        estimate_tip_radius(Sample(np.zeros((2, 8)), 1e-9))
