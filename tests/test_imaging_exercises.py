"""Module (f)'s exercise checkers: each tries a wrong answer, a unit slip, then the right one, and
the references are checked against sources independent of the checker (a brute-force tangency,
the tilt put into the scan, the scanner run at either side of the fastest speed)."""
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from afmsmiler.exercises import imaging as ex
from afmsmiler.imaging.corrections import flatten_lines, level_plane, mask_features
from afmsmiler.samples import Sample


# -- 1. the fastest scan -------------------------------------------------------------------------
def test_fastest_scan_wrong_then_slip_then_right():
    best = ex.fastest_speed()
    bound = ex.DEFAULTS["max_rms_error"]
    # the reference: the scanner's own error just below and above it brackets the bound
    assert ex.scan_error(0.98 * best) < bound < ex.scan_error(1.02 * best)
    assert not ex.check_fast_scan(None)
    too_fast = ex.check_fast_scan(3 * best)
    assert not too_fast and "Too fast" in str(too_fast)
    slow = ex.check_fast_scan(0.5 * best)
    assert not slow and "faster" in str(slow)
    um = ex.check_fast_scan(best * 1e6)  # typed in um/s
    assert not um and "10^6" in str(um)
    mm = ex.check_fast_scan(best * 1e3)  # typed in mm/s
    assert not mm and "10^3" in str(mm)
    good = ex.check_fast_scan(0.95 * best)
    assert good
    # the answer is never given away: no message names the fastest speed
    for fb in (too_fast, slow, um, mm):
        assert f"{best * 1e6:.3g}" not in str(fb) and f"{best:.3g}" not in str(fb)


def test_exercise_1_solved_by_the_search_the_notebook_teaches():
    # notebook 06: six particles 20 nm high; "double the speed until the bound is passed, then
    # halve the step", starting from the panel's 10 um/s; the first speed past the bound is
    # wrong, the search's answer passes
    from scipy import ndimage
    heights = ex.speed_sample().heights
    assert heights.max() == pytest.approx(20e-9, rel=0.01)
    assert ndimage.label(heights > 10e-9)[1] == 6
    bound = 1e-9  # "below 1 nm"
    assert ex.DEFAULTS["max_rms_error"] == bound
    speed = 10e-6
    assert ex.scan_error(speed) < bound
    for _ in range(30):  # double until the bound is passed
        if ex.scan_error(2 * speed) >= bound:
            break
        speed *= 2
    too_fast = ex.check_fast_scan(2 * speed)
    assert not too_fast and "Too fast" in str(too_fast)
    step = speed
    for _ in range(6):  # then halve the step, keeping what stays within the bound
        step /= 2
        if ex.scan_error(speed + step) < bound:
            speed += step
    fb = ex.check_fast_scan(speed)
    assert fb, str(fb)


# -- 2. the particle and the tip radius ------------------------------------------------------------
def _brute_force_width(r, big_r):
    """2 X0: the largest apex distance from the sphere's axis at which a paraboloid of radius R,
    its apex on the substrate, still touches the sphere (dense sampling, no formula)."""
    theta = np.linspace(0.0, math.pi, 200001)
    px, pz = r * np.sin(theta), r - r * np.cos(theta)  # the sphere's outline, x >= 0

    def clearance(x0):  # tip surface minus sphere, least over the outline
        return float(np.min((px - x0) ** 2 / (2 * big_r) - pz))

    return 2 * brentq(clearance, r * 1e-3, 10 * (r + big_r), xtol=1e-15)


def test_apparent_width_wrong_then_slip_then_right():
    image = ex.particle_image()
    top = np.unravel_index(np.argmax(image.heights), image.heights.shape)[0]
    row = image.heights[top]  # "the line through its top"
    assert abs(top - image.heights.shape[0] // 2) <= 1  # centred (two rows share the top)
    measured = (row > 0).sum() * image.pixel_size  # what the notebook suggests
    truth = _brute_force_width(ex.DEFAULTS["particle_radius"], ex._TIP_RADIUS)
    assert measured == pytest.approx(truth, abs=2 * image.pixel_size)
    assert not ex.check_apparent_width(None)
    assert not ex.check_apparent_width(2 * ex.DEFAULTS["particle_radius"])  # the true diameter
    slip = ex.check_apparent_width(measured * 1e9)
    assert not slip and "10^9" in str(slip)
    assert ex.check_apparent_width(measured)


def test_tip_radius_wrong_then_slip_then_right():
    image = ex.particle_image()
    row = image.heights[image.heights.shape[0] // 2]
    width = (row > 0).sum() * image.pixel_size
    r = ex.DEFAULTS["particle_radius"]
    assert not ex.check_tip_radius(None)
    spheres = ex.check_tip_radius(width ** 2 / (16 * r))  # two touching spheres
    assert not spheres and "two touching spheres" in str(spheres)
    # the notebook's recipe, checked here against the brute-force tangency
    c = brentq(lambda c: (1 + c) ** 1.5 / (1 - c) ** 0.5 - width / (2 * r), 1e-9, 1 - 1e-9)
    radius = 2 * r * c * c / (1 - c)
    c_true = brentq(lambda c: (1 + c) ** 1.5 / (1 - c) ** 0.5
                    - _brute_force_width(r, ex._TIP_RADIUS) / (2 * r), 1e-9, 1 - 1e-9)
    assert 2 * r * c_true ** 2 / (1 - c_true) == pytest.approx(ex._TIP_RADIUS, rel=1e-6)
    # and it agrees with the dilation module's own inverse (Brent on the forward formula)
    from afmsmiler.imaging.dilation import tip_radius_from_width
    assert tip_radius_from_width(r, width) == pytest.approx(radius, rel=1e-6)
    slip = ex.check_tip_radius(radius * 1e9)
    assert not slip and "10^9" in str(slip)
    sign = ex.check_tip_radius(-radius)
    assert not sign and "sign" in str(sign)
    good = ex.check_tip_radius(radius)
    assert good


# -- 3. levelling and line flattening -------------------------------------------------------------
def test_levelling_wrong_then_right():
    tilted = ex.tilted_image()
    # the reference sees the tilt that the scan put in (tan of the angles), to 2 %
    sx, sy = ex.substrate_tilt(tilted)
    tx, ty = np.tan(ex.DEFAULTS["tilt"])
    assert sx == pytest.approx(tx, rel=0.02) and sy == pytest.approx(ty, rel=0.02)
    assert not ex.check_levelled(None)
    assert not ex.check_levelled(tilted)
    assert not ex.check_levelled(flatten_lines(tilted))  # rows shifted, still tilted along x
    plain = ex.check_levelled(level_plane(tilted))  # the particles tilt the fitted plane
    assert not plain and "mask" in str(plain)
    assert not ex.check_levelled(Sample(np.zeros((8, 8)), 1e-9))
    assert not ex.check_levelled(np.zeros((64, 64)))
    # the notebook's suggestion: mask the particles, then level (on the image as scanned, or
    # on a first levelling, as mask_features advises for a tilted image)
    assert ex.check_levelled(level_plane(tilted, mask_features(tilted)))
    assert ex.check_levelled(level_plane(tilted, mask_features(level_plane(tilted))))


def test_flattening_artefact_wrong_then_right():
    assert not ex.check_flattening_artefact(None)
    assert not ex.check_flattening_artefact(2)
    for wrong in ("a", "c", "d", "the tip is blunt"):
        assert not ex.check_flattening_artefact(wrong)
    assert ex.check_flattening_artefact("b") and ex.check_flattening_artefact(" B ")
    assert ex.check_flattening_artefact(
        "The median of every row that crosses a tall particle is pulled up, so that row is "
        "lowered too much")
    assert set(ex.CHOICES) == {"a", "b", "c", "d"}
