"""Module (e)'s exercise checkers: right answers pass, computed independently (the optical lever's
first-order formula of Meyer and Amer with the Gaussian split-detector slope sqrt(8/pi)/w; the
Gaussian's symmetry, erf(0) = 0, for the spot centred on the lever's edge; the direction measured
on the panel); unit, sign, per-cent, reciprocal and factor slips are named without the answer;
what notebook 05 asks the student to do on the panel is done here."""
import math

import numpy as np
import pytest
from scipy.special import erf

from afmsmiler.exercises.instrument import (check_deflection_sensitivity, check_half_off_sum,
                                          check_spot_direction, givens)
from afmsmiler.instrument import OpticalHead
from afmsmiler.ui.instrument import InstrumentPanel

TURN = 2 * math.pi


@pytest.fixture(scope="module")
def g():
    return givens()


def first_order_sensitivity(g):
    """m/V: 1 / (SUM sqrt(8/pi) / w x 2 D x 3 / (2 L)), the spot at the lever's end."""
    slope = g["sum"] * math.sqrt(8 / math.pi) / g["detector_spot_radius"]
    return 1.0 / (slope * 2 * g["optical_path"] * 1.5 / g["lever_length"])


def test_givens_are_the_aligned_head(g):
    assert g["spot_from_end"] < 40e-6 and g["sum"] > 0.9 * OpticalHead().best_sum
    assert g["lever_length"] == pytest.approx(450e-6) and g["optical_path"] == 0.03
    # the knobs as the panel shows them: in turns (one turn is 2 pi rad)
    head = OpticalHead()
    head.set(**{k: v * TURN for k, v in g["knob_turns"].items()})
    assert head.signals().sum == pytest.approx(g["sum"], rel=1e-12)
    assert set(g) >= {"knob_turns"} and "knobs" not in g


def test_deflection_sensitivity(g):
    right = first_order_sensitivity(g)
    assert 300e-9 < right < 370e-9          # ~ 335 nm/V, a typical contact-mode InvOLS
    assert check_deflection_sensitivity(right)
    for wrong, words in ((right * 1e9, "10^9"), (1 / right, "inverse"),
                         (1 / right * 1e-9, "inverse"), (2 * right, "twice"),
                         (right / 2, "half"), (1.5 * right, "3 z / (2 L)"),
                         (-right, "sign")):
        fb = check_deflection_sensitivity(wrong)
        assert not fb and words in fb.message, (wrong, fb.message)
        assert f"{right:.3g}" not in fb.message          # the answer is not given away
    assert not check_deflection_sensitivity(None)
    assert not check_deflection_sensitivity("a lot")


def test_spot_direction_is_what_the_panel_shows(g):
    panel = InstrumentPanel()
    panel.set(**g["knob_turns"])
    vert = panel.last.signals.vertical
    start = panel.controls["detector_vertical"].value
    panel.set(detector_vertical=start - 0.05)        # counter-clockwise
    up = "counter-clockwise" if panel.last.signals.vertical > vert else "clockwise"
    down = "clockwise" if up == "counter-clockwise" else "counter-clockwise"
    assert check_spot_direction(up, move="up")
    assert not check_spot_direction(down, move="up")
    assert check_spot_direction(down, move="down")
    for spelling in ("ccw", "anticlockwise", "counter clockwise", -1, -1.0):
        assert bool(check_spot_direction(spelling, move="up")) == (up == "counter-clockwise")
    assert check_spot_direction("ccw", move="left")     # HORZ rises the same way
    assert not check_spot_direction("upwards") and not check_spot_direction(True)
    assert not check_spot_direction(None)
    with pytest.raises(ValueError, match="move"):
        check_spot_direction("cw", move="sideways")


def test_half_off_sum_is_one_half():
    # centred on the edge along the lever: (erf(sqrt 2 L / w) - erf(0)) / 2 over the centre's
    head = OpticalHead()
    w = head.waist / math.cos(head.holder_tilt)
    length = head.lever.length
    expected = 0.5 * erf(math.sqrt(2) * length / w) / erf(math.sqrt(2) * length / 2 / w)
    assert expected == pytest.approx(0.5, abs=1e-12)
    assert check_half_off_sum(0.5)
    for wrong, words in ((50.0, "per cent"), (0.25, "square"), (-0.5, "sign"), (0.7, "%")):
        fb = check_half_off_sum(wrong)
        assert not fb and words in fb.message, (wrong, fb.message)
    assert not check_half_off_sum(None)


def test_half_off_sum_on_the_panel(g):
    """The notebook: 'walk the spot along the lever until its centre is on the free end'."""
    panel = InstrumentPanel()
    panel.set(**g["knob_turns"])
    start = panel.controls["laser_x"].value
    sums = []                            # the best SUM: the plateau, a little back from the end
    for back in np.arange(0.0, 0.3, 0.02):
        panel.set(laser_x=start - back)
        sums.append(panel.last.signals.sum)
    best = max(sums)
    lo, hi = panel.controls["laser_x"].value, panel.controls["laser_x"].value + 0.5
    for _ in range(60):                  # bisection on the knob: the spot's centre at x = L
        mid = (lo + hi) / 2
        panel.set(laser_x=mid)
        if panel.last.signals.spot_on_lever[0] < g["lever_length"]:
            lo = mid
        else:
            hi = mid
    ratio = panel.last.signals.sum / best
    assert ratio == pytest.approx(0.5, rel=0.03)
    assert check_half_off_sum(ratio)
    assert np.isfinite(ratio)
