"""Image corrections (Gwyddion's Plane Level, Align Rows, Remove Scars) against independent
sources: numpy.linalg.lstsq and numpy.polyfit fits, analytic tilted surfaces, a synthetic scar,
and the artefact the notebook teaches (line flattening beside a tall particle), quantified
analytically (a row mean) and by order statistics (scipy.stats)."""
import numpy as np
import pytest
from scipy import stats

from afmsmiler.imaging.corrections import (PARAMETERS, fit_plane, flatten_lines, level_plane,
                                           mark_scars, mask_features, remove_scars)
from afmsmiler.samples import Sample

DX, DY = 4e-9, 5e-9


def _grid(rows, cols, dx=DX, dy=DY):
    y, x = np.mgrid[0:rows, 0:cols]
    return x * dx, y * dy


def _particle(rows, cols, centre, radius, dx=DX, dy=DY):
    """A sphere of ``radius`` lying on z = 0 at ``centre`` (x, y): its upper half, exact."""
    x, y = _grid(rows, cols, dx, dy)
    rho2 = (x - centre[0]) ** 2 + (y - centre[1]) ** 2
    return np.where(rho2 < radius ** 2, radius + np.sqrt(np.clip(radius ** 2 - rho2, 0, None)),
                    0.0)


# -- plane levelling --------------------------------------------------------------------------

def test_plane_fit_equals_numpy_lstsq_on_a_noisy_plane_with_and_without_a_mask():
    rng = np.random.default_rng(3)
    x, y = _grid(48, 64)
    h = 2e-9 + 0.01 * x - 0.02 * y + rng.normal(0, 1e-9, x.shape)
    sample = Sample(h, DX, pixel_size_y=DY)
    mask = rng.random(h.shape) < 0.3
    for use, kw in [(np.ones(h.shape, bool), {}), (~mask, dict(mask=mask)),
                    (mask, dict(mask=mask, masking="include")),
                    (np.ones(h.shape, bool), dict(mask=mask, masking="ignore"))]:
        a = np.column_stack([np.ones(use.sum()), x[use], y[use]])
        ref = np.linalg.lstsq(a, h[use], rcond=None)[0]
        np.testing.assert_allclose(fit_plane(sample, **kw), ref, rtol=1e-9, atol=1e-20)
        out = level_plane(sample, **kw)
        np.testing.assert_allclose(out.heights, h - (ref[0] + ref[1] * x + ref[2] * y),
                                   atol=1e-21)
        assert abs(out.heights[use].mean()) < 1e-21  # the fitted pixels have zero mean


def test_level_plane_flattens_an_analytic_tilted_surface_and_keeps_the_grid():
    x, y = _grid(32, 40)
    tilt = 5e-9 + 0.03 * x + 0.01 * y
    sample = Sample(tilt, DX, name="tilted", pixel_size_y=DY)
    out = level_plane(sample)
    assert np.abs(out.heights).max() < 1e-20
    assert (out.pixel_size, out.pixel_size_y, out.heights.shape) == (DX, DY, (32, 40))
    assert out.name.startswith("tilted") and sample.heights is not out.heights
    np.testing.assert_array_equal(sample.heights, tilt)  # the input is untouched


@pytest.mark.parametrize("correct", [level_plane, flatten_lines, remove_scars,
                                     lambda s: flatten_lines(s, "polynomial", 2)])
def test_every_correction_keeps_the_grid_channel_unit_and_metadata(correct):
    rng = np.random.default_rng(0)
    sample = Sample(rng.normal(0, 1, (16, 20)), DX, name="phase", pixel_size_y=DY,
                    channel="Phase", unit="rad", metadata={"instrument": "twin"})
    out = correct(sample)
    assert (out.pixel_size, out.pixel_size_y, out.channel, out.unit) == (DX, DY, "Phase", "rad")
    assert out.metadata["instrument"] == "twin" and out.name.startswith("phase, ")
    assert out.heights.shape == (16, 20)


def test_a_tall_particle_tilts_the_plane_unless_it_is_masked():
    rows, cols = 64, 64
    x, y = _grid(rows, cols)
    particle = _particle(rows, cols, (200e-9, 250e-9), 40e-9)
    h = 0.02 * x - 0.01 * y + particle
    sample = Sample(h, DX, pixel_size_y=DY)
    biased = level_plane(sample).heights
    background = particle == 0
    assert np.ptp(biased[background]) > 1e-9  # the substrate no longer flat
    exact = level_plane(sample, particle > 0).heights
    assert np.abs(exact[background]).max() < 1e-20
    np.testing.assert_allclose(exact[~background], particle[~background], atol=1e-20)


# -- line flattening --------------------------------------------------------------------------

def test_polynomial_flattening_equals_numpy_polyfit_per_row_with_a_mask():
    rng = np.random.default_rng(5)
    rows, cols = 20, 50
    x, _ = _grid(rows, cols)
    h = rng.normal(0, 1e-9, (rows, cols)) + rng.normal(0, 5e-9, (rows, 1)) \
        + rng.normal(0, 0.01, (rows, 1)) * x + rng.normal(0, 1e4, (rows, 1)) * x ** 2
    mask = rng.random(h.shape) < 0.4
    sample = Sample(h, DX, pixel_size_y=DY)
    for degree in range(4):
        out = flatten_lines(sample, "polynomial", degree, mask).heights
        for r in range(rows):
            keep = ~mask[r]
            c = np.polyfit(x[r, keep], h[r, keep], degree)
            np.testing.assert_allclose(out[r], h[r] - np.polyval(c, x[r]), atol=1e-17)


def test_median_flattening_removes_line_offsets_and_per_row_tilt_needs_degree_one():
    rng = np.random.default_rng(7)
    rows, cols = 30, 80
    x, _ = _grid(rows, cols)
    offsets = rng.normal(0, 10e-9, (rows, 1))
    out = flatten_lines(Sample(np.zeros((rows, cols)) + offsets, DX)).heights
    assert np.abs(out).max() == 0.0
    slopes = rng.normal(0, 0.02, (rows, 1))
    tilted = Sample(offsets + slopes * x, DX)
    assert np.abs(flatten_lines(tilted, "polynomial", 1).heights).max() < 1e-20
    assert np.abs(flatten_lines(tilted).heights).max() > 1e-9  # a median keeps the tilt


def test_line_flattening_beside_a_tall_particle_leaves_dark_bands_unless_masked():
    """The notebook's lesson, quantified: a row's mean (polynomial degree 0) through a particle
    is raised by the particle's row sum / columns, so after flattening the substrate beside the
    particle lies that far below zero; with the particle masked it stays at zero."""
    rows, cols = 64, 128
    particle = _particle(rows, cols, (256e-9, 160e-9), 50e-9)
    offsets = np.random.default_rng(2).normal(0, 3e-9, (rows, 1))  # the loop's line offsets
    sample = Sample(particle + offsets, DX, pixel_size_y=DY)
    out = flatten_lines(sample, "polynomial", 0).heights
    background = particle == 0
    band = -particle.sum(axis=1) / cols  # analytic: minus the row mean of the particle
    for r in range(rows):
        np.testing.assert_allclose(out[r, background[r]], band[r], atol=1e-20)
    assert band.min() < -8e-9  # 8 nm deep beside a 100 nm particle: clearly visible
    mask = mask_features(sample, 1e-9)
    assert mask[~background].all()  # the whole particle is marked
    flat = flatten_lines(sample, "polynomial", 0, mask).heights
    assert np.abs(flat[~mask]).max() < 1e-20
    np.testing.assert_allclose(flat[~background], particle[~background], atol=1e-20)


def test_median_flattening_band_beside_a_ridge_follows_order_statistics():
    """On a rough substrate (Gaussian, sigma) a ridge covering a fraction f of each row shifts
    the row's median to the substrate's quantile 0.5 / (1 - f): the band lies
    sigma * Phi^-1(0.5 / (1 - f)) low (scipy.stats.norm); masked, it is gone."""
    rng = np.random.default_rng(11)
    rows, cols, f, sigma = 60, 2000, 0.3, 1e-9
    h = rng.normal(0, sigma, (rows, cols))
    ridge = np.zeros((rows, cols), bool)
    ridge[:, 700:700 + int(f * cols)] = True
    h[ridge] += 30e-9
    sample = Sample(h, DX)
    out = flatten_lines(sample, "median").heights
    expected = -sigma * stats.norm.ppf(0.5 / (1 - f))
    shift = np.mean(out[~ridge]) - 0.0
    # the median of 1400 Gaussian values scatters by 1.25 sigma / sqrt(1400) per row: 0.005 sigma
    # over 60 rows; 0.02 sigma is four standard errors
    assert shift == pytest.approx(expected, abs=0.02 * sigma)
    assert expected < -0.5 * sigma
    masked = flatten_lines(sample, "median", mask=ridge).heights
    assert abs(np.mean(masked[~ridge])) < 0.02 * sigma


def test_rows_fully_masked_take_their_neighbours_background():
    rows, cols = 5, 10
    offsets = np.arange(rows, dtype=float)[:, None] * 1e-9
    h = np.zeros((rows, cols)) + offsets
    mask = np.zeros_like(h, bool)
    mask[2] = True
    for method in ("median", "polynomial"):
        out = flatten_lines(Sample(h, DX), method, 0, mask).heights
        assert np.abs(out).max() < 1e-24  # row 2's offset interpolated from rows 1 and 3


def test_flatten_lines_rejects_bad_settings_naming_them():
    s = Sample(np.zeros((4, 6)), DX)
    with pytest.raises(ValueError, match="method"):
        flatten_lines(s, "mean")
    with pytest.raises(ValueError, match="degree"):
        flatten_lines(s, "polynomial", 9)
    with pytest.raises(ValueError, match="mask"):
        flatten_lines(s, mask=np.zeros((3, 6), bool))
    with pytest.raises(ValueError, match="mask"):
        flatten_lines(s, mask=np.zeros((4, 6)))
    with pytest.raises(ValueError, match="masking"):
        level_plane(s, masking="exclusive")
    with pytest.raises(ValueError, match="mask"):
        level_plane(s, np.ones((4, 6), bool))
    with pytest.raises(ValueError, match="one line"):  # a diagonal fixes no plane
        level_plane(Sample(np.zeros((5, 5)), DX), np.eye(5, dtype=bool), masking="include")
    with pytest.raises(ValueError, match="sample"):
        flatten_lines(Sample(np.zeros(6), DX))
    with pytest.raises(TypeError, match="sample"):
        level_plane(np.zeros((4, 6)))


# -- scars ------------------------------------------------------------------------------------

def _ramp(rows=64, cols=128):
    """A surface linear along y (so the interpolation across a scar is exact) with a sine
    along x."""
    x, y = _grid(rows, cols)
    return 0.002 * y + 1e-9 * np.sin(x / 40e-9)


def test_a_known_scar_is_found_exactly_and_removed_to_round_off():
    truth = _ramp()
    h = truth.copy()
    h[20:22, 30:70] += 6e-9  # a positive scar, 2 rows x 40 pixels
    h[40, 80:120] -= 6e-9    # a negative scar, 1 row x 40 pixels
    h[50, 10:18] += 6e-9     # too short: 8 pixels < 16 (Gwyddion's default minimum)
    sample = Sample(h, DX, pixel_size_y=DY)
    expected = np.zeros(h.shape, bool)
    expected[20:22, 30:70] = True
    expected[40, 80:120] = True
    np.testing.assert_array_equal(mark_scars(sample), expected)
    out = remove_scars(sample)
    np.testing.assert_allclose(out.heights[expected], truth[expected], rtol=1e-12, atol=1e-22)
    np.testing.assert_array_equal(out.heights[~expected], h[~expected])  # the rest untouched
    assert out.pixel_size == DX and out.pixel_size_y == DY
    # the polarity and the minimum length are the user's
    only_up = mark_scars(sample, kind="positive")
    assert only_up[20:22, 30:70].all() and not only_up[40].any()
    short_ok = mark_scars(sample, min_length=6 * DX)
    assert short_ok[50, 10:18].all()


def test_features_wider_than_max_width_are_not_scars():
    truth = _ramp()
    h = truth + _particle(64, 128, (250e-9, 160e-9), 30e-9)  # 12 rows tall
    h[10, 20:60] += 6e-9
    marks = mark_scars(Sample(h, DX, pixel_size_y=DY))
    assert marks[10, 20:60].all()
    assert marks.sum() == 40


def test_scar_settings_are_checked():
    s = Sample(_ramp(), DX, pixel_size_y=DY)
    with pytest.raises(ValueError, match="threshold"):
        mark_scars(s, 0.1, extension_threshold=0.5)
    with pytest.raises(ValueError, match="max_width"):
        mark_scars(s, max_width=17)
    with pytest.raises(ValueError, match="min_length"):
        mark_scars(s, min_length=-1e-9)
    with pytest.raises(ValueError, match="kind"):
        remove_scars(s, kind="up")
    with pytest.raises(ValueError, match="threshold"):
        remove_scars(s, threshold=0.0)
    assert PARAMETERS["threshold"].default == 0.666  # Gwyddion's defaults
    assert PARAMETERS["extension_threshold"].default == 0.25
    # a flat image has no scars (and no division by its zero row-to-row RMS)
    assert not mark_scars(Sample(np.zeros((8, 32)), DX)).any()


# -- with the scanner -------------------------------------------------------------------------

def test_levelling_removes_the_tilt_the_scanner_adds_to_the_sample():
    """The issue's lesson end to end: a sample scanned tilted by (alpha_x, alpha_y) levels back
    to the untilted scan; the fitted slopes differ by tan(alpha) (the plane the scanner adds)."""
    from afmsmiler.imaging.scan_modes import Mode, ModeLine
    from afmsmiler.imaging.scanner import ScanSettings, scan
    from afmsmiler.samples import particles

    class Topography(Mode):  # the apex surface itself: no loop between the tilt and the image
        channels = ("height trace", "height retrace")

        def line(self, plan, row, state):
            return ModeLine({"height trace": plan.trace[row],
                             "height retrace": plan.retrace[row]}, state)

    sample = particles((32, 40), 4e-9, count=4, radius=12e-9, seed=2)
    tilt = (np.radians(2.0), np.radians(-1.0))

    def image(**kw):
        settings = ScanSettings(40 * 4e-9, scan_size_y=32 * 4e-9, pixels=40, lines=32, **kw)
        return scan(sample, None, Topography(), settings).channels["height trace"]

    flat, tilted = image(), image(tilt=tilt)
    p0, p1 = fit_plane(flat), fit_plane(tilted)
    assert p1.slope_x - p0.slope_x == pytest.approx(np.tan(tilt[0]), rel=1e-9)
    assert p1.slope_y - p0.slope_y == pytest.approx(np.tan(tilt[1]), rel=1e-9)
    np.testing.assert_allclose(level_plane(tilted).heights, level_plane(flat).heights,
                               atol=1e-9 * 1e-6)


# -- bad input found by the API campaign (tests/test_api_campaign.py) -------------------------
def test_a_plane_is_fitted_whatever_the_pixel_size():
    # the fit runs in pixel indices: the squares of tiny pixel sizes (1e-400) no longer
    # underflow to a zero determinant ("pixels on one line")
    x, y = _grid(8, 16, 1.0, 1.0)
    for px in (1e-200, 1e-12, 1e3):
        sample = Sample(1e-9 * (2.0 + 0.5 * x - 0.25 * y), px)
        p = fit_plane(sample)
        assert p.offset == pytest.approx(2e-9, rel=1e-12)
        assert p.slope_x == pytest.approx(0.5e-9 / px, rel=1e-12)
        assert p.slope_y == pytest.approx(-0.25e-9 / px, rel=1e-12)
        assert np.abs(level_plane(sample).heights).max() < 1e-12 * 1e-9


def test_heights_near_the_largest_float_are_levelled_and_flattened_without_overflow():
    # a tilted plane reaching 1.6e308: its sums and its rows' medians overflowed a float before
    x, y = _grid(8, 16, 1.0, 1.0)
    sample = Sample(1e307 * (1.0 + x / 2.0 - y / 2.0 + 3.5), DX, pixel_size_y=DY)
    assert np.abs(level_plane(sample).heights).max() < 1e-10 * 1e307
    rows = Sample(np.full((4, 6), 1.7e308), DX)  # the median of two 1.7e308 was inf
    assert not flatten_lines(rows).heights.any()
    assert np.abs(flatten_lines(rows, "polynomial", 2).heights).max() <= 1e-14 * 1.7e308


def test_a_correction_that_would_overflow_names_the_sample():
    h = np.full((4, 6), 1.7e308)
    h[:, 0] = -1.7e308  # each row's median is 1.7e308: -1.7e308 - 1.7e308 overflows
    with pytest.raises(ValueError, match="^sample values must stay finite when lines flattened"):
        flatten_lines(Sample(h, DX))


@pytest.mark.parametrize("unit", [1e-290, 1e290])
def test_scars_are_found_whatever_the_scale_of_the_values(unit):
    # the row-to-row RMS squared its differences: it underflowed to 0 for values of 1e-290
    # (no scar found) and overflowed to inf for 1e290 (none found either)
    h = _ramp()
    h[20:22, 30:70] += 6e-9
    h[40, 80:120] -= 6e-9
    expected = mark_scars(Sample(h, DX, pixel_size_y=DY))
    assert expected.sum() == 120
    scaled = Sample(h / 1e-9 * unit, DX, pixel_size_y=DY)
    np.testing.assert_array_equal(mark_scars(scaled), expected)
    np.testing.assert_allclose(remove_scars(scaled).heights / unit,
                               remove_scars(Sample(h, DX, pixel_size_y=DY)).heights / 1e-9,
                               rtol=1e-12, atol=1e-12)
