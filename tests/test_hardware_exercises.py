"""Exercise checkers of module (h), part 1 (the macroscopic AFM, the print).

References computed here by hand, not by the checkers: the ruler's spring constant and first
resonance from the Euler-Bernoulli closed forms k = E w t^3 / (4 L^3) and
f1 = 1.87510^2 / (2 pi L^2) sqrt(E t^2 / (12 rho)) (Blevins, Table 8-1), the paper's 6 Hz; the
lift summed from its three parts; the bed's scale from the footprint.
"""
import json
import math
from pathlib import Path

import numpy as np
import pytest

from afmsmiler.exercises import hardware as ex
from afmsmiler.hardware import printing
from afmsmiler.hardware.macro.mechanics import RULER, STEEL

D = ex.DEFAULTS


def _k():
    return STEEL["youngs_modulus"] * RULER["width"] * RULER["thickness"] ** 3 / (
        4 * RULER["length"] ** 3)


def test_the_ruler_is_the_papers_6_hz_steel_rule():
    E, rho = STEEL["youngs_modulus"], STEEL["density"]
    t, L = RULER["thickness"], RULER["length"]
    f1 = 1.8751040687 ** 2 / (2 * math.pi * L ** 2) * math.sqrt(E * t ** 2 / (12 * rho))
    assert ex.ruler().resonance_frequency(1) == pytest.approx(f1, rel=1e-6)
    assert 5.0 < f1 < 7.0  # "about 6 Hz" (source paper)
    assert ex.ruler().spring_constant == pytest.approx(_k(), rel=1e-12)


def _force():
    per_m = D["calibration_counts"] / (D["calibration_steps"] * D["z_step"])  # 3e7 counts/m
    return _k() * (D["contact_counts"] - D["free_counts"]) / per_m


def test_force_from_the_gauge():
    assert ex.ruler_force() == pytest.approx(_force(), rel=1e-12)
    assert ex.check_ruler_force(_force())
    assert ex.check_ruler_force(_force() * 1.005)
    assert not ex.check_ruler_force(None)


@pytest.mark.parametrize("answer, said", [
    (lambda: _force() * 1e3, "10^3"),                       # mN for N
    (lambda: -_force(), "sign"),
    (lambda: _force() * D["contact_counts"] / (D["contact_counts"] - D["free_counts"]),
     "free"),                                               # the free reading kept
    (lambda: _force() * (RULER["width"] / RULER["thickness"]) ** 2, "swapped"),
    (lambda: _force() * 4.0, "w t^3 / 12"),
    (lambda: _force() * 1.5, "off by"),
])
def test_force_slips_are_named(answer, said):
    fb = ex.check_ruler_force(answer())
    assert not fb and said in fb.message
    assert f"= {_force():.4g}" not in fb.message  # the answer is not given away


def _lift():
    per_m = D["calibration_counts"] / (D["calibration_steps"] * D["z_step"])
    shell = ex.printed_shell()
    rise = np.diff(shell.heights, axis=1).max()
    total = D["setpoint_counts"] / per_m + D["pull_off_force"] / _k() + rise
    return math.ceil(total / D["z_step"]), rise


def test_jumping_lift():
    n, rise = _lift()
    assert ex.jumping_lift() == n
    assert ex.check_jumping_lift(n) and ex.check_jumping_lift(n + 1)
    assert not ex.check_jumping_lift(n - 1)
    assert "not the smallest" in ex.check_jumping_lift(n + 10).message
    assert "micro-steps" in ex.check_jumping_lift(n * D["z_step"]).message
    for wrong_sign in (-n, -(n + 1), 0):  # a lift down into the sample is a sign slip, not short
        fb = ex.check_jumping_lift(wrong_sign)
        assert not fb and "positive" in fb.message and "too short" not in fb.message
    per_m = D["calibration_counts"] / (D["calibration_steps"] * D["z_step"])
    no_adhesion = math.ceil((D["setpoint_counts"] / per_m + rise) / D["z_step"])
    assert "adhesion" in ex.check_jumping_lift(no_adhesion).message
    # the printed shell: 0.2 mm pixels over 32 mm
    assert ex.printed_shell().shape == (161, 161)
    assert ex.printed_shell().pixel_size == pytest.approx(0.2e-3)


def test_jumping_lift_solved_as_the_notebook_teaches():
    """Notebook 08's exercise 2 from the givens it names: the setpoint is setpoint_counts above
    the free reading, converted with exercise 1's calibration (584 counts per 20 micro-steps);
    the pull-off force over k = E w t^3 / (4 L^3); the largest rise along a line. A student who
    first takes the free reading off the setpoint as well (exercise 1's step) is told which
    reading the given is, without the answer."""
    per_step = D["calibration_counts"] / D["calibration_steps"]          # counts per micro-step
    rise = np.diff(ex.printed_shell().heights, axis=1).max() / D["z_step"]
    adhesion = D["pull_off_force"] / _k() / D["z_step"]
    wrong = math.ceil((D["setpoint_counts"] - D["free_counts"]) / per_step + adhesion + rise)
    fb = ex.check_jumping_lift(wrong)
    assert not fb and "already counted above the free reading" in fb.message
    assert "too short" not in fb.message and str(ex.jumping_lift()) not in fb.message
    assert not ex.check_jumping_lift(wrong + 1)           # rounded up once more: the same slip
    right = math.ceil(D["setpoint_counts"] / per_step + adhesion + rise)
    assert ex.check_jumping_lift(right), ex.check_jumping_lift(right).message
    # the text's given is what the notebook's markdown names
    nb = json.loads((Path(__file__).parents[1] / "notebooks"
                     / "08_hardware_interaction.ipynb").read_text())
    cell, = ("".join(c["source"]) for c in nb["cells"] if "**2. The jumping lift.**"
             in "".join(c["source"]))
    assert "setpoint_counts" in cell and "above the free reading" in cell


def test_print_scale():
    shell = printing.seashell()
    expected = (D["bed"][0] - 2 * D["margin"]) / shell.width
    assert ex.print_scale() == pytest.approx(expected, rel=1e-12)
    assert ex.check_print_scale(expected)
    assert "margin" in ex.check_print_scale(D["bed"][0] / shell.width).message
    assert "twice" in ex.check_print_scale((D["bed"][0] - D["margin"]) / shell.width).message
    assert "10^-3" in ex.check_print_scale(expected * 1e-3).message
    assert not ex.check_print_scale("big")
