"""Checkers of module (a), judged against independent closed forms and published eigenvalues."""
import math

import pytest

from afmsmiler.exercises import Feedback
from afmsmiler.exercises.cantilever import (check_largest_stress, check_mode_ratio,
                                            check_thickness_for_spring_constant)

# Silicon <110>: E = 169 GPa (Hopcroft, Nix and Kenny, JMEMS 19, 229 (2010)).
E_SI = 169e9
# Clamped-free eigenvalues b_n L (Blevins, Formulas for Natural Frequency and Mode Shape, Table 8-1).
BL = (1.87510407, 4.69409113, 7.85475744)


@pytest.mark.parametrize("k, L, w", [(0.1, 450e-6, 50e-6), (40.0, 125e-6, 30e-6), (2.0, 225e-6, 40e-6)])
def test_thickness_from_the_closed_form_passes(k, L, w):
    h = (4 * k * L ** 3 / (E_SI * w)) ** (1 / 3)  # from k = E w h^3 / (4 L^3)
    fb = check_thickness_for_spring_constant(h, target_k=k, length=L, width=w, material="silicon")
    assert isinstance(fb, Feedback) and fb.passed, str(fb)
    # 2 % too thick is 6 % too stiff: rejected
    assert not check_thickness_for_spring_constant(1.02 * h, target_k=k, length=L, width=w)
    assert not check_thickness_for_spring_constant(0.98 * h, target_k=k, length=L, width=w)


def test_thickness_placeholders_and_nonsense_get_not_yet():
    for answer in (None, -1e-6, 0.0, "two microns", math.nan):
        fb = check_thickness_for_spring_constant(answer)
        assert not fb and str(fb).startswith("Not yet")
    # a thickness in um instead of m is caught (k is 1e18 times too large)
    h_um = (4 * 0.1 * 450e-6 ** 3 / (E_SI * 50e-6)) ** (1 / 3) * 1e6
    assert not check_thickness_for_spring_constant(h_um)


@pytest.mark.parametrize("mode", [2, 3])
def test_mode_ratio_against_published_eigenvalues(mode):
    ratio = (BL[mode - 1] / BL[0]) ** 2  # 6.2669, 17.5475
    assert check_mode_ratio(ratio, mode=mode).passed
    assert not check_mode_ratio(ratio * 1.01, mode=mode)
    assert not check_mode_ratio(mode ** 2, mode=mode)  # the string's n^2 is not a beam's
    assert not check_mode_ratio(None, mode=mode)


def test_mode_ratio_bad_input():
    with pytest.raises(ValueError, match="mode must be an integer in"):
        check_mode_ratio(1.0, mode=1)


def test_largest_stress_is_at_the_clamp_with_the_right_sign():
    # sigma_top(x) = -6 F (L - x) / (w h^2): largest at x = 0, compressive on top for F > 0
    assert check_largest_stress("clamp", "compression", force=1e-7).passed
    assert check_largest_stress("clamp", "tension", force=-1e-7).passed
    assert not check_largest_stress("clamp", "tension", force=1e-7)
    assert not check_largest_stress("free end", "compression", force=1e-7)
    assert not check_largest_stress("middle", "compression")
    assert not check_largest_stress(None, None)
    assert "one of" in str(check_largest_stress("tip", "compression"))
    with pytest.raises(ValueError, match="force must be"):
        check_largest_stress("clamp", "compression", force=0.0)
