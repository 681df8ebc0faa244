"""The guided setup's steps: every check passes and fails on states built for it, the hints point
the right way on the model (following them converges), and a head aligned by ``align()``'s knob
settings passes the alignment steps. The setpoint force is checked against the Euler-Bernoulli
spring constant k = E w t^3 / (4 L^3) computed here from the lever's dimensions."""
import math

import numpy as np
import pytest

from afmsmiler.instrument import DEFAULT_LEVER, KNOBS, TOLERANCES, OpticalHead, align
from afmsmiler.instrument.walkthrough import (SETUP, STEP_TOLERANCES, STEPS, SetupState, Step,
                                              StepCheck, Walkthrough, step_index)
from afmsmiler.scenes.instrument import INSTRUMENTS

TURN = 2 * math.pi
STEP = {s.key: s for s in STEPS}


@pytest.fixture(scope="module")
def aligned_knobs():
    head = OpticalHead()
    run = align(head)
    assert run.alignment
    return dict(head.knobs)


def aligned_head(knobs, **changes):
    head = OpticalHead()
    head.set(**{**knobs, **changes})
    return head


def test_steps_are_the_manuals_order_and_name_real_parts():
    assert [s.key for s in STEPS] == ["mount", "laser", "photodiode", "setpoint", "approach"]
    parts = {p.name for p in INSTRUMENTS["obd"].parts}
    for s in STEPS:
        assert isinstance(s, Step) and s.text and s.title
        assert s.parts and set(s.parts) <= parts, s.key
    # the alignment steps use the head's knobs
    assert set(STEP["laser"].controls) | set(STEP["photodiode"].controls) == set(KNOBS)


def test_mount():
    head = OpticalHead()
    assert STEP["mount"].check(SetupState(head, mounted=True))
    result = STEP["mount"].check(SetupState(head, mounted=False))
    assert not result and "holder" in result.hint
    assert not STEP["laser"].check(SetupState(head, mounted=False))


def test_align_run_passes_the_alignment_steps(aligned_knobs):
    state = SetupState(aligned_head(aligned_knobs))
    for key in ("mount", "laser", "photodiode"):
        result = STEP[key].check(state)
        assert result and result.hint == "", (key, str(result))


def test_laser_step_fails_off_the_lever_and_says_which_way(aligned_knobs):
    head = OpticalHead()                      # just mounted: the spot is on the chip's body
    result = STEP["laser"].check(SetupState(head))
    assert not result and "laser_x clockwise (+)" in result.hint
    # spot beyond the free end: a full turn further along (0.4 mm at the lever)
    head = aligned_head(aligned_knobs, laser_x=aligned_knobs["laser_x"] + 0.25 * TURN)
    s = head.signals()
    assert s.spot_on_lever[0] > DEFAULT_LEVER.length + TOLERANCES["end_distance"].default
    result = STEP["laser"].check(SetupState(head, signals=s))
    assert not result and "laser_x counter-clockwise (-)" in result.hint
    # on the lever but half-way along: sum fine, not at the end
    head = aligned_head(aligned_knobs, laser_x=aligned_knobs["laser_x"] - 0.5 * TURN)
    s = head.signals()
    assert 0 < s.spot_on_lever[0] < DEFAULT_LEVER.length - TOLERANCES["end_distance"].default
    result = STEP["laser"].check(SetupState(head, signals=s))
    assert not result and "laser_x clockwise (+)" in result.hint and "short of" in result.hint
    # off the side of the lever
    head = aligned_head(aligned_knobs, laser_y=aligned_knobs["laser_y"] + 0.3 * TURN)
    result = STEP["laser"].check(SetupState(head))
    assert not result and "laser_y counter-clockwise (-)" in result.hint
    # no numbers given away
    assert not any(ch.isdigit() for ch in result.hint)


def test_knob_directions_the_hints_give_are_the_models(aligned_knobs):
    head = aligned_head(aligned_knobs)
    s0 = head.signals()
    s = head.turn("laser_x", 0.01 * TURN)
    assert s.spot_on_lever[0] > s0.spot_on_lever[0]        # + moves along, to the free end
    head.set(**aligned_knobs)
    s = head.turn("laser_y", 0.01 * TURN)
    assert s.spot_on_lever[1] > s0.spot_on_lever[1]        # + moves to +y
    head.set(**aligned_knobs)
    assert head.turn("detector_vertical", 0.01 * TURN).vertical_normalised < -0.01
    head.set(**aligned_knobs)
    assert head.turn("detector_lateral", 0.01 * TURN).lateral_normalised < -0.01


def test_photodiode_step_and_following_its_hints_converges(aligned_knobs):
    head = aligned_head(aligned_knobs, detector_vertical=0.0, detector_lateral=0.0)
    result = STEP["photodiode"].check(SetupState(head))
    assert not result and "detector_vertical" in result.hint and "detector_lateral" in result.hint
    # a student who only follows the hints: turn the named knob the named way, halve the turn
    # when the hint reverses
    turn = {"detector_vertical": 0.5 * TURN, "detector_lateral": 0.5 * TURN}
    last = {}
    for _ in range(200):
        result = STEP["photodiode"].check(SetupState(head))
        if result:
            break
        for knob in turn:
            if f"{knob} clockwise" in result.hint:
                sign = 1
            elif f"{knob} counter-clockwise" in result.hint:
                sign = -1
            else:
                continue
            if last.get(knob, sign) != sign:
                turn[knob] /= 2
            last[knob] = sign
            head.turn(knob, sign * turn[knob])
    assert result, str(result)
    assert abs(head.signals().vertical_normalised) <= TOLERANCES["max_difference"].default


def test_photodiode_step_needs_light():
    result = STEP["photodiode"].check(SetupState(OpticalHead()))
    assert not result and "step 2" in result.hint


def test_setpoint_force_is_k_z():
    lever = DEFAULT_LEVER
    k = lever.youngs_modulus * lever.width * lever.thickness ** 3 / (4 * lever.length ** 3)
    assert lever.spring_constant == pytest.approx(k, rel=1e-9)
    head = OpticalHead()
    lo, hi = STEP_TOLERANCES["min_force"].default, STEP_TOLERANCES["max_force"].default
    check = STEP["setpoint"].check
    assert not check(SetupState(head, deflection=0.0))
    wrong_sign = check(SetupState(head, deflection=-20e-9))
    assert not wrong_sign and "above zero" in wrong_sign.hint
    small = check(SetupState(head, deflection=0.5 * lo / k))
    assert not small and "raise" in small.hint
    large = check(SetupState(head, deflection=min(1.2 * hi / k, SETUP["deflection"].high)))
    assert not large and "lower" in large.hint
    good = check(SetupState(head, deflection=20e-9))
    assert good and f"{k * 20e-9 * 1e9:.3g} nN" in good.message


def test_approach(aligned_knobs):
    head = aligned_head(aligned_knobs)
    check = STEP["approach"].check
    far = check(SetupState(head, approach_gap=SETUP["approach_gap"].default))
    assert not far and "coarse approach" in far.hint
    near = STEP_TOLERANCES["approach_range"].default
    assert check(SetupState(head, approach_gap=near))
    assert check(SetupState(head, approach_gap=0.0))
    assert not check(SetupState(head, approach_gap=1.01 * near))
    # approaching blind (the laser off the lever) is refused
    blind = check(SetupState(OpticalHead(), approach_gap=0.0))
    assert not blind and "step 2" in blind.hint


def test_walkthrough_navigation_and_record(aligned_knobs):
    w = Walkthrough()
    assert w.step.key == "mount" and w.back().key == "mount"
    state = SetupState(aligned_head(aligned_knobs), deflection=20e-9, approach_gap=0.0)
    for key in ("mount", "laser", "photodiode", "setpoint", "approach"):
        assert w.step.key == key
        assert isinstance(w.check(state), StepCheck)
        w.next()
    assert w.step.key == "approach" and w.done
    assert Walkthrough("photodiode").index == 2 == step_index(2)


def test_errors_name_the_problem():
    head = OpticalHead()
    with pytest.raises(ValueError, match="step"):
        step_index("calibrate")
    with pytest.raises(ValueError, match="step"):
        step_index(7)
    with pytest.raises(ValueError, match="deflection"):
        SetupState(head, deflection=1e-3)
    with pytest.raises(ValueError, match="approach_gap"):
        SetupState(head, approach_gap=-1e-6)
    with pytest.raises(TypeError, match="head"):
        SetupState("head")
    with pytest.raises(TypeError, match="state"):
        Walkthrough().check(head)
    assert np.isfinite(SetupState(head).signals.sum)
