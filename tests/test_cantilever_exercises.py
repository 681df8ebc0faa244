"""Checkers of module (a), judged against independent closed forms and published eigenvalues."""
import math

import pytest
import scipy.constants

from afmsmiler.exercises import Feedback
from afmsmiler.exercises.cantilever import (check_largest_stress, check_mode_ratio,
                                            check_thickness_for_spring_constant, check_tip_slope)

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


# The closed-form answers (independent of the model): h from k = E w h^3 / (4 L^3); theta(L) =
# F L^2 / (2 E J) = 6 F L^2 / (E w h^3); f2/f1 = (b_2 L / b_1 L)^2 (Blevins, Table 8-1).
H_ANSWER = (4 * 0.1 * 450e-6 ** 3 / (E_SI * 50e-6)) ** (1 / 3)
THETA_ANSWER = 6 * 100e-9 * 450e-6 ** 2 / (E_SI * 50e-6 * 2e-6 ** 3)
RATIO_ANSWER = (BL[1] / BL[0]) ** 2


def _no_answer(fb, answer, given=None):
    """The feedback states no digits of the answer (other than the student's own value echoed)."""
    text = str(fb)
    if given is not None:
        text = text.replace(f"{given:.4g}", "<given>")
    for digits in (2, 3, 4, 5, 6):
        assert f"{answer:.{digits}g}" not in text, text


def test_thickness_slips_are_named_without_the_answer():
    # 01 used to say "off by 100397289849108348928.0 %" for a thickness in um
    assert check_thickness_for_spring_constant(H_ANSWER).passed
    for factor, words in ((1e6, "10^6 times"), (1e9, "10^9 times"), (1e3, "10^3 times"),
                          (1e-3, "10^-3 times"), (-1.0, "sign is wrong"),
                          (-1e6, "10^6 times the right one and the sign is wrong")):
        fb = check_thickness_for_spring_constant(H_ANSWER * factor)
        assert not fb and words in str(fb), (factor, str(fb))
        assert "%" not in str(fb)
        _no_answer(fb, H_ANSWER, H_ANSWER * factor)


def test_tip_slope_against_the_closed_form_and_its_slips():
    assert THETA_ANSWER == pytest.approx(1.797e-3, rel=1e-3)  # 3 z(L) / (2 L), z(L) = 539 nm
    assert check_tip_slope(THETA_ANSWER).passed
    assert check_tip_slope(-THETA_ANSWER, force=-100e-9).passed
    assert not check_tip_slope(1.03 * THETA_ANSWER)
    for answer, words in ((THETA_ANSWER * 180 / math.pi, "in degrees where radians are asked"),
                          (THETA_ANSWER * 1e3, "10^3 times"), (-THETA_ANSWER, "sign is wrong")):
        fb = check_tip_slope(answer)
        assert not fb and words in str(fb), str(fb)
        _no_answer(fb, THETA_ANSWER, answer)
    for answer in (None, "1 degree", math.inf, True):
        assert not check_tip_slope(answer)
    with pytest.raises(ValueError, match="force must be"):
        check_tip_slope(1e-3, force=0.0)


def test_mode_ratio_slips_are_named_without_the_answer():
    for answer, words in ((-RATIO_ANSWER, "sign is wrong"), (RATIO_ANSWER * 1e3, "10^3 times"),
                          (RATIO_ANSWER * 2 * math.pi, "2 pi times")):
        fb = check_mode_ratio(answer, mode=2)
        assert not fb and words in str(fb), str(fb)
        _no_answer(fb, RATIO_ANSWER, answer)


def test_hints_name_only_what_exists_and_give_nothing_away():
    # every hint of module (a) is shown for a placeholder; none states a number of the answer
    for fb, answer in ((check_thickness_for_spring_constant(None), H_ANSWER),
                       (check_mode_ratio(None), RATIO_ANSWER), (check_tip_slope(None), THETA_ANSWER)):
        assert not fb
        _no_answer(fb, answer)
    fb = check_largest_stress("middle", "tension")  # wrong place and wrong side
    assert "MPa" not in str(fb) and "clamp" not in str(fb) and "compression" not in str(fb)


def test_checker_inputs_are_validated_by_name():
    with pytest.raises(ValueError, match="target_k must be in"):
        check_thickness_for_spring_constant(1e-6, target_k=-1.0)
    with pytest.raises(ValueError, match="length must be in"):
        check_thickness_for_spring_constant(1e-6, length=math.nan)
    with pytest.raises(ValueError, match="material must be one of"):
        check_thickness_for_spring_constant(1e-6, material="cheese")
    with pytest.raises(ValueError, match="rtol must be in"):
        check_mode_ratio(6.0, rtol=2.0)


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


@pytest.mark.parametrize("answer", [1e300, -1e300, 1e-300, 5e-324])
def test_extreme_answers_get_feedback_not_an_exception(answer):
    for checker in (check_thickness_for_spring_constant, check_mode_ratio, check_tip_slope):
        fb = checker(answer)
        assert not fb and str(fb).startswith("Not yet")


@pytest.mark.parametrize("mode", [2, 3])
def test_mode_ratio_upside_down_is_named_without_the_answer(mode):
    # f1/f2 = (1.8751 / 4.6941)^2 = 0.1596 (Blevins) was "off by a factor of about 39"
    inverse = (BL[0] / BL[mode - 1]) ** 2
    fb = check_mode_ratio(inverse, mode=mode)
    assert not fb and f"f1/f{mode}" in str(fb)
    right = (BL[mode - 1] / BL[0]) ** 2
    assert f"{right:.4g}" not in str(fb) and f"{right:.3g}" not in str(fb)
    assert check_mode_ratio(right, mode=mode)


# -- exercise 5: calibrate a lever the student has not seen ----------------------------------
def _student_k(seed=2026):
    """The student's way: fit mode 1's peak, then k = share_1 k_B T / (chi^2 <z*^2>) with
    share_1 = 12 / (b_1 L)^4 (Blevins' eigenvalue) and chi from module (a)'s mode shape."""
    from afmsmiler.calibration import fit_thermal_spectrum
    from afmsmiler.exercises.cantilever import unseen_lever_spectrum
    from tests.test_calibration_model import _chi_by_finite_differences
    spectrum = unseen_lever_spectrum(seed)
    area = fit_thermal_spectrum(spectrum).area
    chi = _chi_by_finite_differences(1, 1.0)
    k = 12 / BL[0] ** 4 * scipy.constants.k * spectrum.temperature / (chi ** 2 * area)
    return k, spectrum, chi


def test_unseen_lever_right_answer_and_the_true_k():
    from afmsmiler.exercises.cantilever import check_unseen_lever_calibration
    k, spectrum, _ = _student_k()
    assert check_unseen_lever_calibration(k).passed
    assert check_unseen_lever_calibration(k * 1.008).passed
    assert not check_unseen_lever_calibration(k * 1.02)
    # the calibration lands on the hidden lever's true k = E w h^3 / (4 L^3) within the
    # method's bias in air (0.5 %) and a few tenths of a per cent of statistics
    lever = spectrum.lever
    true_k = E_SI * lever.width * lever.thickness ** 3 / (4 * lever.length ** 3)
    assert k == pytest.approx(true_k, rel=0.015)
    # another seed is another lever
    assert _unseen_k_differs(k)


def _unseen_k_differs(k):
    other, _, _ = _student_k(7)
    return abs(other / k - 1) > 0.05


@pytest.mark.parametrize("factor, words", [
    (12 / BL[0] ** 4, ("share",)),   # the 0.971 forgotten: k / 0.971
    (None, ("optical-lever",)),      # chi^2 forgotten: k chi^2
    (2 * math.pi, ("rad/s",)), (1 / (2 * math.pi), ("rad/s",)),
    (0.5, ("two-sided",)), (2.0, ("two-sided",)),
    ("both", ("share", "optical-lever")), ("share+2pi", ("share", "rad/s"))])
def test_unseen_lever_slips_are_named_without_the_answer(factor, words):
    from afmsmiler.exercises.cantilever import check_unseen_lever_calibration
    k, _, chi = _student_k()
    share = 12 / BL[0] ** 4
    answer = {None: k * chi ** 2, "both": k * chi ** 2 / share,
              "share+2pi": k / share * 2 * math.pi}.get(factor)
    if answer is None:
        answer = k / factor if factor == share else k * factor
    fb = check_unseen_lever_calibration(answer)
    assert not fb
    for word in words:
        assert word in str(fb), str(fb)
    _no_answer(fb, k, answer)
    assert "%" not in str(fb)


def test_unseen_lever_placeholders_and_bad_arguments():
    from afmsmiler.exercises.cantilever import check_unseen_lever_calibration
    for answer in (None, "stiff", math.inf, True):
        fb = check_unseen_lever_calibration(answer)
        assert not fb and str(fb).startswith("Not yet")
    k, _, _ = _student_k()
    _no_answer(check_unseen_lever_calibration(None), k)
    assert "off by" in str(check_unseen_lever_calibration(3 * k))
    with pytest.raises(ValueError, match="rtol must be in"):
        check_unseen_lever_calibration(1.0, rtol=0.05)
    with pytest.raises(ValueError, match="seed must be an integer"):
        check_unseen_lever_calibration(1.0, seed=-1)
