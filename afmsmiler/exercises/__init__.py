"""Exercise checkers for the notebooks (one module per course module).

A checker takes the student's answer (in SI units unless its docstring says otherwise), compares it
with what the model says, and returns a :class:`Feedback` that prints as a friendly message and is
truthy when the answer is right, so that tests can assert on it and notebooks can just show it.

Each checker is one exercise of :mod:`afmsmiler.exercises.registry` (its key, its answers, its
solution computed by the model): its Feedback carries the exercise's key, and the grader
(``python -m afmsmiler.grade``, nbgrader's tests) scores from these verdicts.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["Feedback", "check_close", "diagnose_slip", "read_number"]


@dataclass(frozen=True)
class Feedback:
    """The verdict of a checker: ``passed``, a message for the student and the exercise's key.

    Attributes
    ----------
    passed : bool
        Whether the answer is right.
    message : str
        What the student reads (a hint when the answer is wrong, never the answer).
    exercise : str or None
        The key of the exercise that gave it (``"01.1"``; see
        :mod:`afmsmiler.exercises.registry`), None for a verdict of no registered exercise.
    """

    passed: bool
    message: str
    exercise: str | None = None

    def __bool__(self) -> bool:
        return self.passed

    def require(self) -> Feedback:
        """This verdict if it passed; else raise AssertionError with its message.

        nbgrader's autograder counts an exercise failed when its test cell raises: the test
        cells that ``python -m afmsmiler.grade --nbgrader-source`` writes end with
        ``check_...(answer).require()``.

        Returns
        -------
        Feedback
            ``self``, passed (a notebook shows it as it shows any verdict).

        Raises
        ------
        AssertionError
            If the answer is not right, with the checker's message (its hint).
        """
        if not self.passed:
            raise AssertionError(str(self))
        return self

    def __str__(self) -> str:
        return ("Correct! " if self.passed else "Not yet. ") + self.message

    def _repr_markdown_(self) -> str:
        return ("**Correct!** " if self.passed else "**Not yet.** ") + self.message


#: Units of an angle: only for these is an answer 180/pi off named degrees for radians (and back).
ANGLE_UNITS = ("rad", "deg", "\u00b0")
#: Units of a frequency: only for these (and a ratio, unit "") is an answer 2 pi off named rad/s
#: for Hz (and back).
FREQUENCY_UNITS = ("Hz", "kHz", "MHz", "rad/s", "1/s")


def diagnose_slip(value: float, expected: float, rtol: float, unit: str = "") -> str | None:
    """Name the common slip that turns the right answer into ``value``, without giving the answer.

    The slips recognised: the wrong sign; a factor 10^(3n) (|n| = 1..6, a unit prefix such as um
    for m or 1/us for 1/s), also with the wrong sign; a factor 10^2 (cm, per cent); degrees
    for radians and back (180/pi), only for an angle (``unit`` rad or deg); hertz for radians per
    second and back (2 pi), only for a frequency (``unit`` Hz, kHz, MHz, rad/s or 1/s) or a
    dimensionless ratio (``unit`` ""), a ratio of frequencies among them. The message says
    which slip it is and what to check, never the expected value.

    Parameters
    ----------
    value : float
        The student's answer, finite.
    expected : float
        The right answer, finite and nonzero.
    rtol : float
        The tolerance of the check, > 0.
    unit : str
        The unit the answer must be in, for the message.

    Returns
    -------
    str or None
        The diagnosis, or None if the answer is not a recognised slip of the right one.
    """
    if not (math.isfinite(value) and math.isfinite(expected) and expected != 0 and rtol > 0):
        return None
    in_unit = f" in {unit}" if unit else ""

    def near(factor):
        return abs(value - factor * expected) <= rtol * abs(factor * expected)

    if near(-1.0):
        return "The size is right but the sign is wrong: check which direction is positive."
    for n in (1, -1, 2, -2, 3, -3, 4, -4, 5, -5, 6, -6):
        for sign in (1.0, -1.0):
            if near(sign * 10.0 ** (3 * n)):
                both = " and the sign is wrong too" if sign < 0 else ""
                return (f"Your answer is 10^{3 * n} times the right one{both}: a unit prefix "
                        f"slipped (milli, micro, nano, ...); give it in SI units{in_unit}.")
    slips = [(100.0, "10^2 times the right one (centi, or a per cent?)"),
             (0.01, "10^-2 times the right one (centi, or a per cent?)")]
    if unit in ANGLE_UNITS:
        slips += [(180.0 / math.pi, "in degrees where radians are asked"),
                  (math.pi / 180.0, "in radians where degrees are asked")]
    if unit in FREQUENCY_UNITS or unit == "":
        slips += [(2.0 * math.pi, "2 pi times the right one (rad/s where Hz is asked?)"),
                  (1.0 / (2.0 * math.pi), "1/(2 pi) of the right one (Hz where rad/s is asked?)")]
    for factor, what in slips:
        if near(factor):
            return f"Your answer looks {what}; check the unit{in_unit}."
    return None


def check_close(quantity: str, answer, expected: float, rtol: float, unit: str = "",
                hint: str = "") -> Feedback:
    """Feedback on a numerical answer that must match ``expected`` within ``rtol`` (relative).

    A wrong answer that is a common slip of the right one (sign, unit prefix, degrees, 2 pi; see
    :func:`diagnose_slip`) is told so; any other is told how far off it is, as a per cent when it
    is within a factor of two and as a factor otherwise.

    Parameters
    ----------
    quantity : str
        What the answer is, for the message (e.g. ``"thickness"``).
    answer : float
        The student's value.
    expected : float
        The model's value.
    rtol : float
        Accepted relative error.
    unit : str
        Unit shown in the message.
    hint : str
        Added to the message when the answer is off.
    """
    try:
        value = float(answer)
    except (TypeError, ValueError, OverflowError):  # OverflowError: 10**400
        return Feedback(False, f"{quantity} must be a number, got {answer!r}.")
    if not math.isfinite(value):
        return Feedback(False, f"{quantity} must be finite, got {value!r}.")
    err = abs(value - expected) / abs(expected) if expected else abs(value)
    u = f" {unit}" if unit else ""
    if err <= rtol:
        return Feedback(True, f"{quantity} = {value:.4g}{u} (model: {expected:.4g}{u}).")
    slip = diagnose_slip(value, expected, rtol, unit)
    if slip is not None:
        return Feedback(False, f"{quantity} = {value:.4g}{u}. {slip}")
    if expected and (value == 0 or value / expected > 2 or value / expected < 0.5):
        how = ("has the wrong sign and size" if value / expected < 0 else
               f"is off by a factor of about {max(abs(value / expected), abs(expected / value)):.2g}"
               if value else "is zero")
        return Feedback(False, f"{quantity} = {value:.4g}{u} {how} (needs to be within "
                               f"{100 * rtol:g}%). {hint}".strip())
    return Feedback(False, f"{quantity} = {value:.4g}{u} is off by {100 * err:.1f}% "
                           f"(needs to be within {100 * rtol:g}%). {hint}".strip())


def read_number(name: str, answer, hint: str):
    """A student's answer as a finite float, or the feedback that asks for one.

    Parameters
    ----------
    name : str
        What is asked for, as the message names it ("a length").
    answer : object
        The student's answer (None when not yet given).
    hint : str
        Added to the message.

    Returns
    -------
    (value, feedback) : tuple
        ``(float, None)`` for a finite number, else ``(None, Feedback)`` saying what is wrong.
    """
    if answer is None:
        return None, Feedback(False, f"enter {name}. {hint}")
    try:
        value = float(answer)
    except (TypeError, ValueError, OverflowError):  # OverflowError: an int such as 10**400
        return None, Feedback(False, f"{name} must be a number, got {answer!r}. {hint}")
    if not math.isfinite(value):
        return None, Feedback(False, f"{name} must be finite, got {value!r}. {hint}")
    return value, None

