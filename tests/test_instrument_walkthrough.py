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


def _spot_at(head, mx, my):
    """Turn the laser knobs so the spot's centre is at (mx, my) on the lever (Newton steps on
    the spot position the model reports, no optimiser)."""
    k = np.array([head.knobs["laser_x"], head.knobs["laser_y"]])
    for _ in range(20):
        miss = np.array(head.set(laser_x=k[0], laser_y=k[1]).spot_on_lever) - [mx, my]
        jac = np.column_stack([
            (np.array(head.set(laser_x=k[0] + d[0], laser_y=k[1] + d[1]).spot_on_lever)
             - [mx, my] - miss) / 1e-3 for d in np.eye(2) * 1e-3])
        k = k - np.linalg.solve(jac, miss)
    s = head.set(laser_x=k[0], laser_y=k[1])
    assert np.allclose(s.spot_on_lever, (mx, my), atol=1e-9)
    return s


def test_spot_hanging_over_the_end_is_sent_back_with_laser_x(aligned_knobs):
    """The spot's centre just past the free end (within the end tolerance, centred across, the
    photodiode under it): little light comes back because part of the spot misses the lever.
    laser_y is at its best, so the hint turns laser_x back and says nothing of laser_y."""
    length = DEFAULT_LEVER.length
    for beyond in (0.0, 15e-6, 30e-6):
        head = aligned_head(aligned_knobs)
        s = _spot_at(head, length + beyond, 0.0)
        assert s.lever_fraction < 0.6 * head.best_overlap      # half off, or more
        result = STEP["laser"].check(SetupState(head, signals=s))
        assert not result, beyond
        assert "laser_x counter-clockwise (-)" in result.hint and "laser_y" not in result.hint
        # laser_y cannot bring the sum back (a few per cent at most either way, for
        # a tenth of a turn), laser_x turned back does
        y0 = head.knobs["laser_y"]
        sums = [head.set(laser_y=y0 + dy * TURN).sum for dy in np.linspace(-0.1, 0.1, 41)]
        assert max(sums) < 1.05 * s.sum < TOLERANCES["min_sum_fraction"].default * head.best_sum
        head.set(laser_y=y0)
        assert head.turn("laser_x", -0.1 * TURN).sum > 0.9 * head.best_sum


def _follow(head, step_key, knobs, first_turn, limit=300):
    """A student who only follows the hints of ``step_key``: turn each knob the hint names the
    way it names, halving that knob's turn when the hint reverses; the photodiode's hints
    (step 3) are followed the same way when the laser step asks for them."""
    turn = dict(first_turn)
    last = {}
    for _ in range(limit):
        result = STEP[step_key].check(SetupState(head))
        if result:
            return result
        hint = result.hint
        if "centre it (step 3)" in hint:
            hint += " " + STEP["photodiode"].check(SetupState(head)).hint
        for knob in knobs:
            if f"{knob} clockwise" in hint:
                sign = 1
            elif f"{knob} counter-clockwise" in hint:
                sign = -1
            else:
                continue
            if last.get(knob, sign) != sign:
                turn[knob] /= 2
            last[knob] = sign
            meta = KNOBS[knob]
            head.set(**{knob: min(max(head.knobs[knob] + sign * turn[knob], meta.low),
                                  meta.high)})
    return STEP[step_key].check(SetupState(head))


@pytest.mark.parametrize("where", ["as-mounted", "over-the-end", "far-beyond", "half-way",
                                   "off-the-side"])
def test_following_the_laser_hints_aligns(aligned_knobs, where):
    """From the spot on the chip's body, hanging over the end, far beyond it, half-way along
    and off the side, following only the laser step's hints ends with the step passed."""
    length = DEFAULT_LEVER.length
    head = aligned_head(aligned_knobs)
    if where == "as-mounted":
        head.set(laser_x=0.0, laser_y=0.0)
    elif where == "over-the-end":
        _spot_at(head, length + 20e-6, 0.0)
    elif where == "far-beyond":
        _spot_at(head, length + 150e-6, 0.0)
    elif where == "half-way":
        _spot_at(head, length / 2, 0.0)
    else:
        _spot_at(head, length - 20e-6, 45e-6)
    knobs = ("laser_x", "laser_y", "detector_vertical", "detector_lateral")
    result = _follow(head, "laser", knobs, {"laser_x": 0.1 * TURN, "laser_y": 0.02 * TURN,
                                            "detector_vertical": 0.5 * TURN,
                                            "detector_lateral": 0.5 * TURN})
    assert result, (where, str(result))
    s = head.signals()
    assert abs(length - s.spot_on_lever[0]) <= TOLERANCES["end_distance"].default
    assert s.sum >= TOLERANCES["min_sum_fraction"].default * head.best_sum


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


def test_resume_goes_to_the_first_step_not_done(aligned_knobs):
    """Knobs set behind the guide's back (align() on the panel, a re-run notebook): the guide
    records the steps done and goes on from the first that is not."""
    w = Walkthrough()
    step = w.resume(SetupState(aligned_head(aligned_knobs)))        # setpoint still 0
    assert step.key == "setpoint" == w.step.key
    assert [bool(w.results.get(k)) for k in ("mount", "laser", "photodiode", "setpoint")] == [
        True, True, True, False]
    assert w.resume(SetupState(OpticalHead())).key == "laser"        # just mounted
    assert w.resume(SetupState(OpticalHead(), mounted=False)).key == "mount"
    done = SetupState(aligned_head(aligned_knobs), deflection=20e-9, approach_gap=0.0)
    assert w.resume(done).key == "approach" and w.done
    with pytest.raises(TypeError, match="state"):
        w.resume("aligned")


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
