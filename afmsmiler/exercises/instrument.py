"""Exercise checkers of module (e), the instrument overview and its laser alignment.

Each checker computes the right answer with the head's model (:mod:`afmsmiler.instrument`) and
returns a :class:`~afmsmiler.exercises.Feedback`; wrong answers that are common slips (a unit
prefix, a per cent, the reciprocal, a forgotten factor of the optical lever) are named, the
right value is never given. A placeholder answer (``None``) gets "Not yet" and a hint.

The givens of the exercises come from :func:`givens` (the default head aligned by
:func:`~afmsmiler.instrument.align`, as the student aligns it on the panel). Each checker is an
exercise of notebook 05 (:mod:`afmsmiler.exercises.registry`) whose solution the head's model
computes (:func:`deflection_sensitivity`, :func:`spot_direction`, :func:`half_off_sum`).
"""
from __future__ import annotations

import math
from functools import lru_cache

from ..instrument import KNOBS, OpticalHead, align
from ..instrument.optics import interval_fraction
from ..parameters import read_only
from ..validation import check_choice, check_range
from . import Feedback, check_close, read_number
from .registry import exercise

__all__ = ["givens", "deflection_sensitivity", "check_deflection_sensitivity", "spot_direction",
           "check_spot_direction", "half_off_sum", "check_half_off_sum", "DIRECTIONS"]

#: Accepted spellings of the two ways to turn a knob (seen from its end), and their sign.
DIRECTIONS = read_only({"clockwise": 1, "cw": 1, "+": 1, "+1": 1, "1": 1, "positive": 1,
                        "counter-clockwise": -1, "counterclockwise": -1, "anticlockwise": -1,
                        "anti-clockwise": -1, "ccw": -1, "-": -1, "-1": -1, "negative": -1})

_MOVES = read_only({"up": ("detector_vertical", "vertical_normalised", 1),
                    "down": ("detector_vertical", "vertical_normalised", -1),
                    "left": ("detector_lateral", "lateral_normalised", 1),
                    "right": ("detector_lateral", "lateral_normalised", -1)})


@lru_cache(maxsize=1)
def _aligned_knobs() -> tuple:
    head = OpticalHead()
    align(head)
    return tuple(head.knobs.items())


def _aligned_head() -> OpticalHead:
    head = OpticalHead()
    head.set(**dict(_aligned_knobs()))
    return head


def givens() -> dict:
    """The aligned default head's numbers the exercises start from (SI units).

    Returns
    -------
    dict
        ``sum`` (V), ``optical_path`` D (m), ``lever_length`` L (m), ``detector_spot_radius``
        w(D) (m, 1/e^2), ``spring_constant`` k (N/m), ``spot_from_end`` (m, the aligned spot's
        centre from the lever's free end), ``knob_turns`` (each knob's setting in turns, as the
        panel's sliders show them; one turn is 2 pi rad).
    """
    head = _aligned_head()
    s = head.signals()
    return dict(sum=s.sum, optical_path=head.optical_path, lever_length=head.lever.length,
                detector_spot_radius=head.detector_spot_radius,
                spring_constant=head.lever.spring_constant,
                spot_from_end=head.lever.length - s.spot_on_lever[0],
                knob_turns={k: KNOBS[k].to_display(v) for k, v in s.knobs.items()})


def deflection_sensitivity() -> float:
    """The aligned head's deflection sensitivity in m/V (exercise 1), from its model.

    Returns
    -------
    float
        1 / (d VERT / dz) (:meth:`~afmsmiler.instrument.OpticalHead.sensitivity` with
        ``normalised=False``).
    """
    return float(1.0 / _aligned_head().sensitivity(normalised=False))


@exercise("05.1", "The deflection sensitivity", answers=("answer",),
          solution=deflection_sensitivity)
def check_deflection_sensitivity(answer, rtol: float = 0.03) -> Feedback:
    """Exercise 1: the aligned head's deflection sensitivity (the "InvOLS") in m/V.

    How many metres of tip deflection make one volt of VERT? With the spot at the lever's end
    the reflected beam turns by 2 theta(L) = 3 z / L, the spot moves by D 3 z / L on the
    photodiode and, for a Gaussian spot of radius w centred on the split, VERT changes by
    SUM sqrt(8 / pi) / w per metre of spot motion (Meyer and Amer 1988; module (b)).

    Parameters
    ----------
    answer : float or None
        The student's deflection sensitivity in m/V (SI; 1 nm/V is 1e-9 m/V).
    rtol : float
        Accepted relative error (the first-order formula is within 0.1 % of the model).

    Returns
    -------
    Feedback
        Compared with 1 / (d VERT / dz) of the aligned head's model
        (:meth:`~afmsmiler.instrument.OpticalHead.sensitivity` with ``normalised=False``).
    """
    rtol = check_range("rtol", rtol, 0.0, 1.0, low_inclusive=False)
    hint = ("dVERT/dz = SUM sqrt(8/pi) / w(D) x 3 D / L (the reflection doubles the lever's end "
            "slope 3 z / (2 L)); the sensitivity is its inverse. Use givens() and give it in "
            "m/V.")
    value, fail = read_number("a deflection sensitivity", answer, hint)
    if fail is not None:
        return fail
    expected = deflection_sensitivity()
    for n in range(-6, 7):      # the slope dVERT/dz (V/m, or V/nm...) given for its inverse
        scale = 10.0 ** (3 * n)
        if abs(value - scale / expected) <= rtol * scale / expected:
            return Feedback(False, "that looks like the slope dVERT/dz (volts per length), the "
                                   "inverse of what is asked: give metres of deflection per "
                                   "volt, in m/V.")
    for factor, slip in ((2.0, "twice the right one: the reflection doubles the lever's angle "
                               "(2 theta), count it once"),
                         (0.5, "half the right one: the reflection's factor 2 (2 theta) went in "
                               "twice, or the end slope lost its 3/2"),
                         (1.5, "1.5 times the right one: the end slope is 3 z / (2 L), not "
                               "z / L"),
                         (2 / 3, "2/3 of the right one: the end slope is 3 z / (2 L)")):
        if abs(value - factor * expected) <= rtol * factor * expected:
            return Feedback(False, f"your answer is {slip}. {hint}")
    return check_close("the deflection sensitivity", value, expected, rtol, "m/V", hint)


def _spot_moves(move: str, direction: str) -> bool:
    """Whether turning the knob of ``move`` a twentieth of a turn ``direction`` moves the spot
    ``move`` on the aligned head's photodiode."""
    knob, signal, sign = _MOVES[move]
    head = _aligned_head()
    before = getattr(head.signals(), signal)
    after = getattr(head.turn(knob, DIRECTIONS[direction] * 2 * math.pi / 20), signal)
    return (after - before) * sign > 0


def spot_direction(move: str = "up") -> str:
    """Which way to turn a photodiode knob to move the spot ``move`` (exercise 2), on the model.

    Parameters
    ----------
    move : {"up", "down", "left", "right"}
        Where the spot is to go on the photodiode.

    Returns
    -------
    str
        ``"clockwise"`` or ``"counter-clockwise"``: the way that, a twentieth of a turn on the
        aligned head, moves the spot there.
    """
    move = check_choice("move", move, _MOVES)
    return "clockwise" if _spot_moves(move, "clockwise") else "counter-clockwise"


@exercise("05.2", "Which way?", answers=("direction",), solution=spot_direction)
def check_spot_direction(direction, move: str = "up") -> Feedback:
    """Exercise 2: which way to turn a photodiode knob to move the spot ``move`` on it?

    Parameters
    ----------
    direction : str, int or None
        ``"clockwise"`` (or ``"cw"``, ``+1``) or ``"counter-clockwise"`` (``"ccw"``, ``-1``),
        seen from the knob's end.
    move : {"up", "down", "left", "right"}
        Where the spot is to go on the photodiode (up: VERT rises; left: HORZ rises). Up and
        down take ``detector_vertical``, left and right ``detector_lateral``.

    Returns
    -------
    Feedback
        Checked on the model: the aligned head's knob turned a twentieth of a turn that way.
    """
    move = check_choice("move", move, _MOVES)
    knob = _MOVES[move][0]
    hint = (f"the knob moves the photodiode, not the beam: the spot moves the other way on it. "
            f"Try it on the panel with {knob} and watch "
            f"{'VERT' if knob.endswith('vertical') else 'HORZ'}.")
    if direction is None:
        return Feedback(False, f"enter 'clockwise' or 'counter-clockwise'. {hint}")
    if isinstance(direction, (int, float)) and not isinstance(direction, bool) \
            and direction in (1, -1):
        direction = "+" if direction > 0 else "-"          # +1.0 as well as +1
    key = str(direction).strip().lower().replace(" ", "").replace("_", "-")
    if key not in DIRECTIONS:
        return Feedback(False, f"direction must be one of 'clockwise' or 'counter-clockwise' "
                               f"(or +1 / -1), got {direction!r}.")
    key = "clockwise" if DIRECTIONS[key] > 0 else "counter-clockwise"
    if _spot_moves(move, key):
        return Feedback(True, f"turning {knob} {key} moves the photodiode so that the spot "
                              f"goes {move} on it.")
    return Feedback(False, f"turning {knob} {key} moves the spot the other way. {hint}")


def half_off_sum() -> float:
    """SUM with the spot's centre on the lever's free end over the best SUM (exercise 3).

    The closed-form Gaussian overlap of the head's model: the lever's share of the spot with
    its centre at x = L over the share with the spot at the lever's centre
    (:func:`~afmsmiler.instrument.optics.interval_fraction`, the spot's radius along the lever
    w / cos(tilt)).

    Returns
    -------
    float
        The ratio, a plain number.
    """
    head = OpticalHead()
    length, w_along = head.lever.length, head.waist / math.cos(head.holder_tilt)
    return float(interval_fraction(length, w_along, 0.0, length)
                 / interval_fraction(length / 2, w_along, 0.0, length))


@exercise("05.3", "Half off the end", answers=("ratio",), solution=half_off_sum)
def check_half_off_sum(ratio, rtol: float = 0.02) -> Feedback:
    """Exercise 3: SUM with the spot's centre on the lever's free end, over the best SUM.

    Parameters
    ----------
    ratio : float or None
        The student's SUM(end) / SUM(best), a plain number (not per cent).
    rtol : float
        Accepted relative error.

    Returns
    -------
    Feedback
        Compared with the closed-form Gaussian overlap: the lever's share of the spot with its
        centre at x = L over the share with the spot at the lever's centre (the photodiode
        catching the reflection in both).
    """
    rtol = check_range("rtol", rtol, 0.0, 1.0, low_inclusive=False)
    hint = ("the spot is a 2-D Gaussian; along the lever its centre sits on the edge, across it "
            "nothing changed. Give a plain ratio, not a per cent.")
    value, fail = read_number("a ratio", ratio, hint)
    if fail is not None:
        return fail
    expected = half_off_sum()
    if abs(value - expected ** 2) <= rtol * expected ** 2:
        return Feedback(False, "that is the square of the right ratio: only the direction along "
                               "the lever loses light; across the lever the spot is still "
                               f"centred. {hint}")
    return check_close("SUM(end) / SUM(best)", value, expected, rtol, "", hint)
