"""Module (g)'s checkers: the right answers pass, the common slips are named and never pass, and
no message gives the answer away. References: the branch the model's approach ends on
(setpoint_state), the friction coefficient the loop was made with, and the energy balance
E_dis = (pi k A^2 / Q)[(A0 / A) sin(phi) - 1] (Cleveland et al. 1998) written out here."""
import math

import numpy as np
import pytest

from afmsmiler.exercises import modes as ex
from afmsmiler.modes import setpoint_state


# -- 1. the attractive branch ------
def test_the_lowest_attractive_setpoint_separates_the_branches():
    best = ex.lowest_attractive_setpoint()
    lever = ex.tapping_lever()
    assert 0.5 < best < 0.99
    assert setpoint_state(best, lever)[3] is True
    assert setpoint_state(best - 2e-3, lever)[3] is False


def test_exercise_1_solved_on_the_tapping_panel_as_the_notebook_teaches():
    # notebook 07: the first guess 0.8 fails (repulsive); then, on the tapping panel at its
    # defaults (A0 = 12 nm), raise the setpoint in steps of 0.01 and read the branch in the
    # readout: the first attractive one is the answer within 0.05
    from afmsmiler.ui.modes import TappingPanel
    first = ex.check_attractive_setpoint(0.8)
    assert not first and "repulsive" in str(first)
    panel = TappingPanel()
    assert panel.values()["free_amplitude"] == 12.0
    answer = None
    for step in range(1, 20):
        r = round(0.8 + 0.01 * step, 2)
        panel.set(setpoint_ratio=r)
        if "<b>attractive</b>" in panel.readout.value:
            answer = r
            break
    assert answer is not None
    fb = ex.check_attractive_setpoint(answer)
    assert fb, str(fb)


def test_setpoint_right_answer_passes_and_says_why():
    best = ex.lowest_attractive_setpoint()
    for r in (best + 0.005, best + 0.04):
        fb = ex.check_attractive_setpoint(round(r, 3))
        assert fb, str(fb)
        assert "attractive" in str(fb)


@pytest.mark.parametrize("answer, words", [
    (None, "enter"), ("half", "number"), (0.8, "repulsive"), (0.97, "go lower"),
    (10.3, "in nm"), (85.0, "per cent"), (10.3e-9, "amplitude in m"), (150.0, "between 0 and 1"),
])
def test_setpoint_slips_are_named(answer, words):
    fb = ex.check_attractive_setpoint(answer)
    assert not fb
    assert words in str(fb)
    best = f"{ex.lowest_attractive_setpoint():.3g}"
    assert best not in str(fb)


# -- 2. friction from a loop ------
def _loop_numbers():
    loop = ex.friction_loop_data()
    inner = slice(1, -1)  # the stuck turn-arounds at the ends
    f = loop.normal_force
    return dict(right=float(np.mean(loop.trace[inner] - loop.retrace[inner])) / 2 / f,
                trace=float(np.mean(loop.trace[inner])) / f,
                retrace=-float(np.mean(loop.retrace[inner])) / f,
                slope=float(np.mean(loop.trace[inner] + loop.retrace[inner])) / 2 / f,
                force=float(np.mean(loop.trace[inner] - loop.retrace[inner])) / 2)


def test_friction_loop_data_holds_friction_and_a_slope():
    n = _loop_numbers()
    assert n["right"] == pytest.approx(ex.DEFAULTS["friction"], rel=0.01)
    assert n["slope"] == pytest.approx(math.tan(ex.DEFAULTS["tilt"]), rel=0.05)


def test_friction_right_answer_passes():
    fb = ex.check_friction_coefficient(_loop_numbers()["right"])
    assert fb, str(fb)


@pytest.mark.parametrize("slip, words", [
    ("trace", "trace alone"), ("retrace", "retrace alone"), ("double", "twice"),
    ("slope", "slope term"), ("force", "force in N"), ("nN", "force in nN")])
def test_friction_slips_are_named(slip, words):
    n = _loop_numbers()
    value = dict(trace=n["trace"], retrace=n["retrace"], double=2 * n["right"],
                 slope=n["slope"], force=n["force"], nN=n["force"] / 1e-9)[slip]
    fb = ex.check_friction_coefficient(value)
    assert not fb and words in str(fb), str(fb)
    assert "0.25" not in str(fb)


# -- 3. E_dis from the phase ------
def _energy(sine=math.sin, in_degrees=False, free_term=True):
    g = ex.dissipation_givens()
    phi = g["phase_deg"] if in_degrees else math.radians(g["phase_deg"])
    k, q, a0, a = g["spring_constant"], g["quality_factor"], g["free_amplitude"], g["amplitude"]
    return math.pi * k * a * a / q * ((a0 / a) * sine(phi) - (1.0 if free_term else 0.0))


def test_dissipation_givens_are_the_model_state():
    g = ex.dissipation_givens()
    zc, phase, e_dis, _ = setpoint_state(ex.DEFAULTS["dissipation_setpoint"],
                                         ex.dissipation_lever())
    assert g["phase_deg"] == pytest.approx(math.degrees(phase), abs=0.005)
    assert _energy() == pytest.approx(e_dis, rel=1e-3)  # rounding of the phase only
    assert _energy() > 0


def test_dissipation_right_answer_passes():
    assert ex.check_dissipated_energy(_energy())


@pytest.mark.parametrize("value, words", [
    (lambda: _energy(in_degrees=True), "degrees"),
    (lambda: _energy(free_term=False), "own damping"),
    (lambda: _energy(sine=math.cos), "cosine"),
    (lambda: _energy() / 1.602176634e-19, "electronvolts"),
    (lambda: _energy() * 1e21, "zJ"),
    (lambda: -_energy(), "sign"),
    (lambda: None, "enter"),
])
def test_dissipation_slips_are_named(value, words):
    fb = ex.check_dissipated_energy(value())
    assert not fb and words in str(fb), str(fb)
    # the student's own value is echoed (the sign slip is the answer's size), the model's never
    assert "model" not in str(fb)
