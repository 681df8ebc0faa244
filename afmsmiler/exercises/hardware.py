"""Exercise checkers of module (h), part 1: the macroscopic AFM and its printed samples.

Each checker computes its reference with the library's models (module (a)'s beam for the ruler,
:mod:`afmsmiler.hardware.printing` for the print), never from a stored number, and returns a
:class:`~afmsmiler.exercises.Feedback`. A placeholder answer (``None``) gets "Not yet" and a hint;
a unit or sign slip is named (:func:`~afmsmiler.exercises.diagnose_slip`) without giving the
answer, and so are the slips particular to each exercise. Answers are in SI units (the lift in z
micro-steps).

1. :func:`check_ruler_force`: from the strain gauge's counts and the calibration, the force the
   ruler's tip presses with.
2. :func:`check_jumping_lift`: the smallest jumping-mode lift (in z micro-steps) that releases the
   setpoint's load, breaks the adhesion and clears the next pixel of the printed seashell.
3. :func:`check_print_scale`: the largest lateral scale at which the seashell image fits the
   printer's bed with a margin.

Each checker is an exercise of notebook 08 (:mod:`afmsmiler.exercises.registry`) whose solution
is the function that computes its reference (:func:`ruler_force`, :func:`jumping_lift`,
:func:`print_scale`).
"""
from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from ..cantilever import Cantilever
from ..hardware import printing
from ..hardware.macro import mechanics
from ..parameters import read_only
from ..samples import Sample
from . import Feedback, check_close, diagnose_slip, read_number
from .registry import exercise

__all__ = ["DEFAULTS", "ruler", "gauge_deflection", "ruler_force", "check_ruler_force",
           "printed_shell", "jumping_lift", "check_jumping_lift", "print_scale",
           "check_print_scale"]

#: The exercises' givens, in one place (SI units; counts are the HX711's raw readings). The
#: ruler is the macroscopic AFM's (:data:`afmsmiler.hardware.macro.mechanics.RULER`); the gauge's
#: numbers are what its calibration predicts (584 counts per 50 um, 1.31e6 counts per N).
DEFAULTS = read_only(dict(
    # 1. the gauge: free reading, the reading in contact, and the calibration (pressing the tip
    # down by 20 z micro-steps of 2.5 um changed the reading by 584 counts)
    free_counts=8410, contact_counts=14981, calibration_counts=584, calibration_steps=20,
    z_step=2.5e-6, force_rtol=0.01,
    # 2. jumping mode over the seashell printed 400x and scanned at 0.2 mm: the setpoint, counted
    # above the free reading (the gauge reads free_counts + setpoint_counts there; 10 mN), and
    # the pull-off force of the needle from the print
    setpoint_counts=13143, pull_off_force=0.5e-3, lateral_scale=400.0, pitch=0.2e-3,
    # 3. the print bed (Creality Ender 3, as in the paper) and the margin kept on each side
    bed=(0.22, 0.22), margin=10e-3, scale_rtol=0.01,
))


def ruler() -> Cantilever:
    """The macroscopic AFM's ruler as module (a)'s beam (a clamped steel rule).

    Returns
    -------
    Cantilever
        :func:`afmsmiler.hardware.macro.mechanics.ruler`: its ``spring_constant`` (about
        8.9 N/m) and ``resonance_frequency(1)`` (about 6 Hz).
    """
    return mechanics.ruler()


def _counts_per_metre() -> float:
    d = DEFAULTS
    return d["calibration_counts"] / (d["calibration_steps"] * d["z_step"])


def gauge_deflection(counts: float) -> float:
    """The ruler tip's deflection in m for a gauge reading of ``counts`` (raw HX711 counts).

    Parameters
    ----------
    counts : float
        The reading; the free (out of contact) reading gives 0.

    Returns
    -------
    float
        ``(counts - free_counts) / (calibration_counts / (calibration_steps * z_step))``.
    """
    return (float(counts) - DEFAULTS["free_counts"]) / _counts_per_metre()


# -- 1. the force from the gauge ---------------------------------------------------------------
def ruler_force() -> float:
    """The force in N the ruler presses with at ``contact_counts`` (exercise 1's answer).

    Returns
    -------
    float
        ``k * deflection``, k = 3 E J / L^3 of :func:`ruler`.
    """
    return ruler().spring_constant * gauge_deflection(DEFAULTS["contact_counts"])


@exercise("08.1", "The force on the needle", answers=("force",), solution=ruler_force)
def check_ruler_force(force) -> Feedback:
    """Check exercise 1: the force in N from the gauge's counts and the calibration.

    Parameters
    ----------
    force : float
        The student's force in N.

    Returns
    -------
    Feedback
    """
    hint = ("The calibration turns counts into deflection (counts per micro-step, a micro-step "
            "is 2.5 um); the ruler's spring constant, k = 3 E J / L^3 with J = w t^3 / 12, "
            "turns deflection into force. Give it in N.")
    value, feedback = read_number("the force (in N)", force, hint)
    if feedback is not None:
        return feedback
    d = DEFAULTS
    expected = ruler_force()
    rtol = d["force_rtol"]
    lever = ruler()
    k = lever.spring_constant
    slips = (
        (k * d["contact_counts"] / _counts_per_metre(),
         "You used the whole reading: subtract the free (out of contact) reading first."),
        (k * (d["contact_counts"] - d["free_counts"]) / d["calibration_counts"],
         "The calibration gives counts per 20 micro-steps of 2.5 um, not per metre."),
        (expected * (mechanics.RULER["width"] / mechanics.RULER["thickness"]) ** 2,
         "Width and thickness are swapped in J: the ruler bends about its thin direction, "
         "J = w t^3 / 12 with t the 0.5 mm thickness."),
        (expected * 4.0, "J = w t^3 / 12 (a rectangle about its centre), not w t^3 / 3."),
        (expected / 3.0, "The end-load spring constant is 3 E J / L^3."),
    )
    for wrong, message in slips:
        if abs(value - wrong) <= rtol * abs(wrong):
            return Feedback(False, f"force = {value:.4g} N. {message}")
    return check_close("force", value, expected, rtol, "N", hint)


# -- 2. the jumping lift -----------------------------------------------------------------------
@lru_cache(maxsize=1)
def printed_shell() -> Sample:
    """The seashell printed at ``lateral_scale`` and re-imaged at ``pitch`` (heights in m).

    Returns
    -------
    Sample
        :func:`~afmsmiler.hardware.printing.seashell` printed 400x (no base plate counted: heights
        above the lowest pixel), read back at 0.2 mm by
        :func:`~afmsmiler.hardware.printing.mesh_to_sample`.
    """
    d = DEFAULTS
    mesh = printing.sample_to_mesh(printing.seashell(), lateral_scale=d["lateral_scale"],
                                   base_thickness=1e-3)
    s = printing.mesh_to_sample(mesh, d["pitch"], name="seashell, printed 400x")
    return s.with_heights(s.heights - s.heights.min())


def _lift_parts() -> tuple[float, float, float]:
    """(setpoint deflection, adhesion deflection, largest rise to the next pixel) in m."""
    d = DEFAULTS
    setpoint = d["setpoint_counts"] / _counts_per_metre()
    adhesion = d["pull_off_force"] / ruler().spring_constant
    rise = float(np.max(np.diff(printed_shell().heights, axis=1)))  # along the fast axis
    return setpoint, adhesion, max(rise, 0.0)


def jumping_lift() -> int:
    """The smallest lift in z micro-steps that frees the tip and clears the next pixel.

    Returns
    -------
    int
        ``ceil((setpoint deflection + pull-off force / k + largest rise) / z_step)``.
    """
    return int(math.ceil(sum(_lift_parts()) / DEFAULTS["z_step"] - 1e-9))


@exercise("08.2", "The jumping lift", answers=("steps",), solution=jumping_lift)
def check_jumping_lift(steps) -> Feedback:
    """Check exercise 2: the smallest jumping-mode lift, in z micro-steps.

    The setpoint is given as ``setpoint_counts`` counts above the free reading; a lift that
    takes the free reading off it once more (exercise 1's step, not needed here) is recognised
    and named, as are a lift that leaves out one of its three parts, one in metres and one
    longer than needed.

    Parameters
    ----------
    steps : int
        The student's lift in z micro-steps (one more is accepted: rounding).

    Returns
    -------
    Feedback
    """
    hint = ("After a pixel the tip is pressed in by the setpoint (setpoint_counts above the "
            "free reading, converted with exercise 1's calibration); retracting it must first "
            "undo that deflection, then stretch the ruler until it pulls with the pull-off force "
            "(F = k d), then clear the highest rise to the next pixel along the line "
            "(np.diff of printed_shell().heights along axis 1). Give micro-steps of 2.5 um.")
    value, feedback = read_number("the lift (in z micro-steps)", steps, hint)
    if feedback is not None:
        return feedback
    expected = jumping_lift()
    if value <= 0:
        return Feedback(False, f"lift = {value:g} micro-steps: a lift moves the tip up, away from "
                               "the sample; give it as a positive number of micro-steps.")
    if expected <= value <= expected + 1 and float(value).is_integer():
        return Feedback(True, f"lift = {int(value)} micro-steps ({value * 2.5:g} um): it frees "
                              f"the tip and clears every pixel (smallest: {expected}).")
    z = DEFAULTS["z_step"]
    setpoint, adhesion, rise = _lift_parts()
    # the other reading of the setpoint: the free reading taken off it as in exercise 1, but
    # setpoint_counts already counts from the free reading
    free = DEFAULTS["free_counts"] / _counts_per_metre()
    twice = math.ceil((setpoint - free + adhesion + rise) / z - 1e-9)
    if twice <= value <= twice + 1:
        return Feedback(False, f"lift = {value:g} micro-steps takes the free reading off the "
                               "setpoint, but setpoint_counts is already counted above the free "
                               "reading (the gauge reads free_counts + setpoint_counts at the "
                               "setpoint): convert setpoint_counts as it is.")
    missing = ((setpoint, "the setpoint's deflection (the tip is pressed in first)"),
               (adhesion, "the adhesion: the ruler must pull with the pull-off force"),
               (rise, "the rise to the next pixel"))
    for part, what in missing:
        short = math.ceil((setpoint + adhesion + rise - part) / z - 1e-9)
        if short <= value <= short + 1 and part > 2 * z:
            return Feedback(False, f"lift = {value:g} micro-steps leaves out {what}.")
    if not float(value).is_integer():
        slip = diagnose_slip(value, expected * z, 0.02, "m")
        if slip is not None or abs(value - expected * z) <= 0.02 * expected * z:
            return Feedback(False, f"lift = {value:g}: give the lift in z micro-steps of "
                                   f"2.5 um (an integer), not in m.")
    if value > expected + 1:
        return Feedback(False, f"lift = {value:g} micro-steps frees the tip, but it is not the "
                               "smallest: every extra step costs time at every pixel. "
                               + hint)
    return Feedback(False, f"lift = {value:g} micro-steps is too short: the tip stays stuck or "
                           f"drags into a rib. {hint}")


# -- 3. the scale that fits the bed ------------------------------------------------------------
def print_scale() -> float:
    """The largest lateral scale that fits the seashell on the bed with the margin.

    Returns
    -------
    float
        :func:`~afmsmiler.hardware.printing.fitting_scale` of the seashell.
    """
    d = DEFAULTS
    return printing.fitting_scale(printing.seashell(), d["bed"], margin=d["margin"])


@exercise("08.3", "The print that fits", answers=("scale",), solution=print_scale)
def check_print_scale(scale) -> Feedback:
    """Check exercise 3: the largest lateral scale (print size / image size) that fits the bed.

    Parameters
    ----------
    scale : float
        The student's scale, a pure number (2000 means 1 um of image is 2 mm of print).

    Returns
    -------
    Feedback
    """
    hint = ("The print's footprint is the image's width times the scale; keep 10 mm free on "
            "each side of the 220 mm bed.")
    value, feedback = read_number("the scale", scale, hint)
    if feedback is not None:
        return feedback
    d = DEFAULTS
    expected = print_scale()
    shell = printing.seashell()
    slips = ((printing.fitting_scale(shell, d["bed"]), "Keep the margin free on each side."),
             (printing.fitting_scale(shell, d["bed"], margin=d["margin"] / 2),
              "The margin is on each side: the bed loses it twice along each axis."))
    for wrong, message in slips:
        if abs(value - wrong) <= 0.3 * d["scale_rtol"] * wrong:
            return Feedback(False, f"scale = {value:.4g}. {message}")
    return check_close("scale", value, expected, d["scale_rtol"], "", hint)
