"""Exercise checkers of module (d), contact mechanics.

Exercise 1 (fitting): :func:`fitting_exercise` hands out a noisy synthetic approach curve of a
sample of unknown Young's modulus; the student recovers E (and the contact point) by fitting, and
:func:`check_fitted_modulus` / :func:`check_contact_point` compare with the values the curve was
made from. Exercise 2 (adhesion): :func:`check_pull_off_forces` compares the predicted DMT and
JKR pull-off forces with those of the simulated approach-retract cycles (:func:`pull_off_feedback`
checks one model's answer on its own).

The hints name only what a notebook has (the exercise is ``ex``, as notebook 04 calls it; a test
runs every piece of code a hint quotes in backticks), say where to look rather than give the
answer, and the checkers name the common slips (a unit prefix, the sign) through
:func:`~afmsmiler.exercises.check_close` and :func:`~afmsmiler.exercises.diagnose_slip`.

Each checker is an exercise of notebook 04 (:mod:`afmsmiler.exercises.registry`) whose solution
the models compute: the fit that exercise 1's hint shows (:func:`fitted_modulus`,
:func:`fitted_contact_point`) and the simulated cycle's pull-off force (:func:`pull_off_force`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..contact import ContactSystem, ForceCurve, Parabolic, Tip, fit_curve, synthetic_curve
from ..parameters import read_only, shown
from ..validation import check_choice, check_integer, check_positive, check_range
from . import Feedback, check_close, diagnose_slip, read_number
from .registry import exercise

__all__ = ["DEFAULTS", "HINTS", "FitExercise", "fitting_exercise", "fitted_modulus",
           "check_fitted_modulus", "fitted_contact_point", "check_contact_point",
           "pull_off_force", "pull_off_feedback", "pull_off_forces",
           "check_pull_off_forces"]

#: The exercises' givens, in one place (SI units).
DEFAULTS = read_only(dict(
    radius=20e-9, poisson_ratio=0.5 - 0.05, spring_constant=0.05, noise=15e-12,
    modulus_range=(20e3, 2e6), points=800, z_np_range=(-300e-9, 400e-9),
    contact_range=(-40e-9, 60e-9), youngs_modulus=1e7, pull_off_k=0.1))

#: The hints, in one place (code in backticks runs in notebook 04 with its exercise ``ex``).
HINTS = read_only(dict(
    modulus=("Fit the curve with the lever's bending taken into account: "
             "`fit_curve(ex.curve.z_np, ex.curve.force, ex.tip, ex.poisson_ratio, "
             "spring_constant=ex.curve.spring_constant)` and give E in Pa "
             "(the result's youngs_modulus)."),
    contact_point=("The fit returns it as contact_point, in m on the Z_np axis "
                   "(1 nm = 1e-9 m)."),
    pull_off=("Look up the pull-off force of each model in the book chapter's section on "
              "adhesion (it cites Derjaguin-Muller-Toporov 1975 and Johnson-Kendall-Roberts "
              "1971), or read the panel's readout with adhesion on. Give the magnitude in N."),
))


@dataclass(frozen=True)
class FitExercise:
    """A force curve to fit: what the student gets, and (hidden in the repr) the truth.

    Attributes
    ----------
    curve : ForceCurve
        The noisy approach curve (Z_np in m, force in N, the lever's k).
    tip : Tip
        The tip used (a paraboloid).
    poisson_ratio : float
        The sample's nu, given.
    noise : float
        The force noise in N.
    """

    curve: ForceCurve
    tip: Tip
    poisson_ratio: float
    noise: float
    _youngs_modulus: float = field(repr=False)
    _contact_point: float = field(repr=False)


def fitting_exercise(seed: int = 0) -> FitExercise:
    """A noisy approach curve on a sample whose E is drawn at random (log-uniform, 20 kPa-2 MPa).

    Parameters
    ----------
    seed : int
        Seed of the draw (E, contact point and noise), >= 0.

    Returns
    -------
    FitExercise
    """
    seed = check_integer("seed", seed, 0, 2 ** 32 - 1)
    rng = np.random.default_rng(seed)
    lo, hi = DEFAULTS["modulus_range"]
    e = float(math.exp(rng.uniform(math.log(lo), math.log(hi))))
    cp = float(rng.uniform(*DEFAULTS["contact_range"]))
    tip = Parabolic(DEFAULTS["radius"])
    curve = synthetic_curve(tip, spring_constant=DEFAULTS["spring_constant"], youngs_modulus=e,
                            poisson_ratio=DEFAULTS["poisson_ratio"],
                            z_np_range=DEFAULTS["z_np_range"], points=DEFAULTS["points"],
                            contact_point=cp, baseline=float(rng.normal(0.0, 50e-12)),
                            noise=DEFAULTS["noise"], seed=int(rng.integers(2 ** 31)))
    return FitExercise(curve, tip, DEFAULTS["poisson_ratio"], DEFAULTS["noise"], e, cp)


def _fit(exercise: FitExercise):
    """The fit that exercise 1's hint shows (the lever's bending taken into account)."""
    if not isinstance(exercise, FitExercise):
        raise ValueError(f"exercise must be a FitExercise, got {exercise!r}")
    c = exercise.curve
    return fit_curve(c.z_np, c.force, exercise.tip, exercise.poisson_ratio,
                     spring_constant=c.spring_constant)


def fitted_modulus(exercise: FitExercise) -> float:
    """Young's modulus in Pa fitted to ``exercise.curve`` as exercise 1's hint shows.

    Parameters
    ----------
    exercise : FitExercise
        The curve to fit.

    Returns
    -------
    float
        The fit's ``youngs_modulus`` (:func:`~afmsmiler.contact.fit_curve` with the lever's
        spring constant).
    """
    return float(_fit(exercise).youngs_modulus)


@exercise("04.1a", "Measure a sample: Young's modulus", answers=("answer",),
          solution=fitted_modulus)
def check_fitted_modulus(answer, exercise: FitExercise, rtol: float = 0.05) -> Feedback:
    """Exercise 1: the Young's modulus recovered from ``exercise.curve``.

    Parameters
    ----------
    answer : float or None
        The student's E in Pa.
    exercise : FitExercise
        The curve that was fitted.
    rtol : float
        Accepted relative error (the fit's own uncertainty is about 1 %).

    Returns
    -------
    Feedback
    """
    if not isinstance(exercise, FitExercise):
        raise ValueError(f"exercise must be a FitExercise, got {exercise!r}")
    rtol = check_range("rtol", rtol, 0.0, 1.0, low_inclusive=False)
    hint = HINTS["modulus"]
    if answer is None:
        return Feedback(False, f"enter E in Pa. {hint}")
    return check_close("E", answer, exercise._youngs_modulus, rtol, "Pa", hint)


def fitted_contact_point(exercise: FitExercise) -> float:
    """The contact point in m fitted to ``exercise.curve`` as exercise 1's hint shows.

    Parameters
    ----------
    exercise : FitExercise
        The curve to fit.

    Returns
    -------
    float
        The fit's ``contact_point`` (Z_np at first touch).
    """
    return float(_fit(exercise).contact_point)


@exercise("04.1b", "Measure a sample: the contact point", answers=("answer",),
          solution=fitted_contact_point)
def check_contact_point(answer, exercise: FitExercise, tolerance: float = 2e-9) -> Feedback:
    """Exercise 1b: the contact point (Z_np at first touch) of ``exercise.curve``.

    Parameters
    ----------
    answer : float or None
        The student's contact point in m.
    exercise : FitExercise
        The curve.
    tolerance : float
        Accepted absolute error in m.

    Returns
    -------
    Feedback
    """
    if not isinstance(exercise, FitExercise):
        raise ValueError(f"exercise must be a FitExercise, got {exercise!r}")
    tolerance = check_positive("tolerance", tolerance, "m")
    hint = HINTS["contact_point"]
    try:
        value = float(answer)
    except (TypeError, ValueError, OverflowError):  # OverflowError: an int such as 10**400
        return Feedback(False, f"enter the contact point in m. {hint}")
    if not math.isfinite(value):
        return Feedback(False, f"the contact point must be finite, got {value!r}. {hint}")
    truth = exercise._contact_point
    err = abs(value - truth)
    if err <= tolerance:
        return Feedback(True, f"contact point {shown(value, 'nm')} "
                              f"(truth {shown(truth, 'nm')}).")
    slip = diagnose_slip(value, truth, min(tolerance / abs(truth), 0.2), "m") if truth else None
    if slip:
        return Feedback(False, f"contact point: {slip} {hint}")
    return Feedback(False, f"contact point {shown(value, 'nm')} is {shown(err, 'nm', '.3g')} off "
                           f"(needs to be within {shown(tolerance, 'nm', 'g')}). {hint}")


def _pull_off_system(model: str, radius: float, work_of_adhesion: float) -> ContactSystem:
    model = check_choice("model", model, ("dmt", "jkr"))
    radius = check_positive("radius", radius, "m")
    w = check_positive("work_of_adhesion", work_of_adhesion, "J/m^2")
    return ContactSystem(tip=Parabolic(radius), spring_constant=DEFAULTS["pull_off_k"],
                         youngs_modulus=DEFAULTS["youngs_modulus"], poisson_ratio=0.3,
                         adhesion=model, work_of_adhesion=w)


def pull_off_force(model: str = "dmt", radius: float = DEFAULTS["radius"],
                   work_of_adhesion: float = 0.05) -> float:
    """The pull-off force (its magnitude, N) of the simulated approach-retract cycle (exercise 2).

    Parameters
    ----------
    model : {"dmt", "jkr"}
        The adhesion model.
    radius : float
        Tip radius R in m.
    work_of_adhesion : float
        w in J/m^2.

    Returns
    -------
    float
        The most adhesive force of the cycle (paraboloid, E = 10 MPa, k = 0.1 N/m).
    """
    return float(_pull_off_system(model, radius, work_of_adhesion).pull_off_force)


def _pull_off_verdict(answer, model: str, radius: float, work_of_adhesion: float,
                      rtol: float) -> Feedback:
    """The verdict on one model's pull-off force, without the hint (see the checkers below)."""
    model = check_choice("model", model, ("dmt", "jkr"))
    expected = pull_off_force(model, radius, work_of_adhesion)
    if answer is None:
        return Feedback(False, f"enter the {model.upper()} pull-off force in N.")
    feedback = check_close(f"{model.upper()} pull-off force", answer, expected, rtol, "N")
    value, unread = read_number("a force", answer, "")
    if not feedback.passed and unread is None:
        other = "jkr" if model == "dmt" else "dmt"
        other_force = pull_off_force(other, radius, work_of_adhesion)
        if abs(value - other_force) <= rtol * abs(other_force):  # the other model's law
            return Feedback(False, f"that is the {other.upper()} pull-off force; this asks the "
                                   f"{model.upper()} one: compare the two models' laws.")
    return feedback


def pull_off_feedback(answer, model: str, radius: float = DEFAULTS["radius"],
                      work_of_adhesion: float = 0.05, rtol: float = 0.02) -> Feedback:
    """Feedback on a predicted pull-off force (its magnitude) of a DMT or JKR contact: one
    model's part of exercise 2 (:func:`check_pull_off_forces` grades both), on its own.

    Parameters
    ----------
    answer : float or None
        The student's pull-off force in N (positive).
    model : {"dmt", "jkr"}
        The adhesion model.
    radius : float
        Tip radius R in m.
    work_of_adhesion : float
        w in J/m^2.
    rtol : float
        Accepted relative error.

    Returns
    -------
    Feedback
        Compared with the most adhesive force of the simulated approach-retract cycle
        (paraboloid, E = 10 MPa, k = 0.1 N/m); the other model's force given for this one is
        named as such.
    """
    model = check_choice("model", model, ("dmt", "jkr"))
    _pull_off_system(model, radius, work_of_adhesion)  # the givens checked before the answer
    rtol = check_range("rtol", rtol, 0.0, 1.0, low_inclusive=False)
    verdict = _pull_off_verdict(answer, model, radius, work_of_adhesion, rtol)
    return verdict if verdict.passed else Feedback(False, f"{verdict.message} {HINTS['pull_off']}")


def pull_off_forces(radius: float = DEFAULTS["radius"],
                    work_of_adhesion: float = 0.05) -> tuple[float, float]:
    """The DMT and the JKR pull-off forces (magnitudes, N) of exercise 2 (:func:`pull_off_force`).

    Parameters
    ----------
    radius : float
        Tip radius R in m.
    work_of_adhesion : float
        w in J/m^2.

    Returns
    -------
    (dmt, jkr) : tuple of float
    """
    return (pull_off_force("dmt", radius, work_of_adhesion),
            pull_off_force("jkr", radius, work_of_adhesion))


@exercise("04.2", "Pull-off", answers=("dmt", "jkr"), solution=pull_off_forces)
def check_pull_off_forces(dmt, jkr, radius: float = DEFAULTS["radius"],
                          work_of_adhesion: float = 0.05, rtol: float = 0.02) -> Feedback:
    """Exercise 2: predict the pull-off force (its magnitude) with DMT and with JKR.

    Parameters
    ----------
    dmt, jkr : float or None
        The student's pull-off forces in N (positive), of each model.
    radius : float
        Tip radius R in m.
    work_of_adhesion : float
        w in J/m^2.
    rtol : float
        Accepted relative error of each.

    Returns
    -------
    Feedback
        Both right, or what is wrong with each (:func:`pull_off_feedback`).
    """
    _pull_off_system("dmt", radius, work_of_adhesion)  # the givens checked before the answers
    rtol = check_range("rtol", rtol, 0.0, 1.0, low_inclusive=False)
    verdicts = [_pull_off_verdict(a, m, radius, work_of_adhesion, rtol)
                for a, m in ((dmt, "dmt"), (jkr, "jkr"))]
    if all(v.passed for v in verdicts):
        return Feedback(True, " ".join(v.message for v in verdicts))
    wrong = " ".join(f"{m.upper()}: {v.message}" for v, m in zip(verdicts, ("dmt", "jkr"))
                     if not v.passed)
    right = [m.upper() for v, m in zip(verdicts, ("dmt", "jkr")) if v.passed]
    return Feedback(False, (f"{' and '.join(right)} right; " if right else "")
                    + f"{wrong} {HINTS['pull_off']}")

