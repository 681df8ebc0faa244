"""Exercise checkers of module (b), probe transducers.

Each checker computes the right answer with a model of :mod:`afmsmiler.transducers` and returns a
:class:`~afmsmiler.exercises.Feedback`. A placeholder answer (``None``) gets "Not yet" and a hint.
Each is an exercise of notebook 02 (:mod:`afmsmiler.exercises.registry`) whose solution the
models compute (:func:`doubling_length`, :func:`two_omega_power`, :func:`bridge_output`,
:func:`quadrature_phase`).
"""
from __future__ import annotations

import math

from scipy.optimize import brentq, minimize_scalar

from ..parameters import read_only
from ..transducers import Electrothermal, Interferometer, OpticalBeamDeflection, Piezoresistive
from ..validation import check_range
from . import Feedback, check_close, diagnose_slip, read_number
from .registry import exercise

__all__ = ["DEFAULTS", "doubling_length", "check_length_doubling_sensitivity",
           "two_omega_power", "check_two_omega_power", "bridge_output", "check_bridge_output",
           "quadrature_phase", "check_quadrature_phase"]

#: The exercises' givens, in one place (SI units).
DEFAULTS = read_only(dict(length=225e-6, ac_voltage=2.0, resistance=1e3, deflection=100e-9))


def doubling_length(reference_length: float = DEFAULTS["length"]) -> float:
    """The lever length in m at which the optical lever is twice as sensitive (exercise 1).

    Found on the model, without its formula: the root of
    ``sensitivity(L) / sensitivity(reference_length) - 2`` between the model's shortest length
    and ``reference_length`` (Brent's method).

    Parameters
    ----------
    reference_length : float
        The lever length (m) whose sensitivity is to be doubled (other parameters: defaults),
        inside the model's range of lengths.

    Returns
    -------
    float
        L in m.

    Raises
    ------
    ValueError
        If no length in the model's range doubles the sensitivity.
    """
    p = OpticalBeamDeflection.parameter_table()["length"]
    reference_length = check_range("reference_length", reference_length, p.low, p.high, "m")
    base = OpticalBeamDeflection(length=reference_length).sensitivity()

    def excess(length):
        return OpticalBeamDeflection(length=length).sensitivity() / base - 2.0

    if not excess(p.low) > 0:
        raise ValueError(f"reference_length must be long enough for a lever of the model's "
                         f"lengths to double its sensitivity, got {reference_length!r}")
    return float(brentq(excess, p.low, reference_length, xtol=1e-12 * reference_length))


@exercise("02.1", "Shorter levers", answers=("length",), solution=doubling_length)
def check_length_doubling_sensitivity(length, reference_length: float = DEFAULTS["length"],
                                      rtol: float = 0.02) -> Feedback:
    """Exercise 1: which lever length doubles the optical lever's sensitivity?

    Parameters
    ----------
    length : float or None
        The student's lever length in m.
    reference_length : float
        The lever length (m) whose sensitivity is to be doubled (other parameters: defaults),
        inside the model's range of lengths.
    rtol : float
        Accepted relative error of the resulting sensitivity ratio (2).

    Returns
    -------
    Feedback
        Passed when :class:`~afmsmiler.transducers.OpticalBeamDeflection` with that length is
        twice as sensitive as with ``reference_length``.
    """
    p = OpticalBeamDeflection.parameter_table()["length"]
    reference_length = check_range("reference_length", reference_length, p.low, p.high, "m")
    rtol = check_range("rtol", rtol, 0.0, 1.0, low_inclusive=False)
    hint = ("The spot moves by 2 D theta and theta = 3 z / (2 L) for a tip deflection z: how does "
            "the signal per nm depend on L? Give L in metres.")
    value, fail = read_number("a length", length, hint)
    if fail is not None:
        return fail
    if not p.low <= value <= p.high:
        # a length in um or mm (or negative) is the usual slip: name it, not only the range
        slip = diagnose_slip(value, doubling_length(reference_length), 0.05, "m")
        return Feedback(False, slip + f" {hint}" if slip else
                        f"the model takes lengths in [{p.low:g}, {p.high:g}] m, got {value:g}. "
                        f"{hint}")
    base = OpticalBeamDeflection(length=reference_length).sensitivity()
    ratio = OpticalBeamDeflection(length=value).sensitivity() / base
    return check_close(f"the sensitivity ratio of the {value * 1e6:.4g} um lever", ratio, 2.0,
                       rtol, "", hint)


def two_omega_power(ac_voltage: float = DEFAULTS["ac_voltage"],
                    resistance: float = DEFAULTS["resistance"]) -> float:
    """The power amplitude in W at 2 omega of an unbiased heater (exercise 2), from the model.

    Parameters
    ----------
    ac_voltage : float
        V_ac in V.
    resistance : float
        The heater's R in ohm.

    Returns
    -------
    float
        :meth:`~afmsmiler.transducers.Electrothermal.power_components` ``.second`` at V_dc = 0.
    """
    model = Electrothermal(ac_voltage=ac_voltage, resistance=resistance)
    return float(model.power_components(0.0).second)


@exercise("02.2", "The 2ω term", answers=("amplitude",), solution=two_omega_power)
def check_two_omega_power(amplitude, ac_voltage: float = DEFAULTS["ac_voltage"],
                          resistance: float = DEFAULTS["resistance"],
                          rtol: float = 1e-3) -> Feedback:
    """Exercise 2: an unbiased heater gets V_ac cos(omega t); what power oscillates at 2 omega?

    Parameters
    ----------
    amplitude : float or None
        The student's 2-omega power amplitude in W.
    ac_voltage : float
        V_ac in V.
    resistance : float
        The heater's R in ohm.
    rtol : float
        Accepted relative error.

    Returns
    -------
    Feedback
        Compared with :meth:`~afmsmiler.transducers.Electrothermal.power_components` at V_dc = 0.
    """
    model = Electrothermal(ac_voltage=ac_voltage, resistance=resistance)
    rtol = check_range("rtol", rtol, 0.0, 1.0, low_inclusive=False)
    hint = "Expand (V_ac cos wt)^2 / R with cos^2 x = (1 + cos 2x) / 2. Give it in W."
    value, fail = read_number("a power amplitude", amplitude, hint)
    if fail is not None:
        return fail
    return check_close("the 2-omega power amplitude", value,
                       two_omega_power(model.ac_voltage, model.resistance), rtol, "W", hint)


def bridge_output(deflection: float = DEFAULTS["deflection"]) -> float:
    """The default piezoresistive lever's quarter-bridge output in V (exercise 3), from the model.

    Parameters
    ----------
    deflection : float
        Tip deflection in m.

    Returns
    -------
    float
        The exact bridge output of :class:`~afmsmiler.transducers.Piezoresistive`.
    """
    model = Piezoresistive()
    return float(model.respond(model.input_quantity().check(deflection)))


@exercise("02.3", "The bridge", answers=("voltage",), solution=bridge_output)
def check_bridge_output(voltage, deflection: float = DEFAULTS["deflection"],
                        rtol: float = 0.02) -> Feedback:
    """Exercise 3: the quarter-bridge output of the default piezoresistive lever for a deflection.

    Parameters
    ----------
    voltage : float or None
        The student's bridge output in V (mind the sign).
    deflection : float
        Tip deflection in m.
    rtol : float
        Accepted relative error (the small-signal formula is within it).

    Returns
    -------
    Feedback
        Compared with the exact bridge output of :class:`~afmsmiler.transducers.Piezoresistive`.
    """
    model = Piezoresistive()
    q = model.input_quantity()
    deflection = q.check(deflection)
    rtol = check_range("rtol", rtol, 0.0, 1.0, low_inclusive=False)
    hint = ("F = k z; the stress at the resistor is 6 F (L - l_r/2) / (w h^2) scaled to the "
            "junction's mid-depth, dR/R = pi_l sigma and V_out = V_b dR / (4 R). A lever bent up "
            "compresses its top. Give V_out in V.")
    value, fail = read_number("a voltage", voltage, hint)
    if fail is not None:
        return fail
    expected = bridge_output(deflection)
    # a wrong sign is named, never answered with the right value (check_close's slips)
    return check_close("the bridge output", value, expected, rtol, "V", hint)


def quadrature_phase() -> float:
    """The operating phase in rad, in [0, pi], where the interferometer is most sensitive.

    Found on the model, without its formula: the largest |sensitivity| of
    :class:`~afmsmiler.transducers.Interferometer` over the phase (bounded Brent search).

    Returns
    -------
    float
        phi in rad.
    """
    model = Interferometer()
    best = minimize_scalar(lambda p: -abs(model.replace(phase=p).sensitivity()),
                           bounds=(0.0, math.pi), method="bounded",
                           options=dict(xatol=1e-9, maxiter=200))
    return float(best.x)


@exercise("02.4", "Quadrature", answers=("phase",), solution=quadrature_phase)
def check_quadrature_phase(phase, rtol: float = 0.01) -> Feedback:
    """Exercise 4: at which operating phase phi is the interferometer most sensitive?

    Parameters
    ----------
    phase : float or None
        The student's phase in rad.
    rtol : float
        Accepted shortfall of the sensitivity from its largest value.

    Returns
    -------
    Feedback
        Passed when :class:`~afmsmiler.transducers.Interferometer` at that phase reaches at least
        (1 - rtol) of the largest sensitivity 4 pi V P0 / lambda.
    """
    rtol = check_range("rtol", rtol, 0.0, 1.0, low_inclusive=False)
    hint = ("P = P0 (1 + V cos(4 pi d / lambda + phi)): where is the fringe steepest? "
            "Give phi in rad.")
    value, fail = read_number("a phase", phase, hint)
    if fail is not None:
        return fail
    wrapped = math.remainder(value, 2 * math.pi)
    model = Interferometer()
    best = max(abs(model.replace(phase=p).sensitivity()) for p in (-math.pi / 2, math.pi / 2))
    got = abs(model.replace(phase=wrapped).sensitivity())
    if got >= (1 - rtol) * best:
        return Feedback(True, f"phi = {value:.4g} rad is a quadrature point: "
                              f"{got * 1e-3:.4g} uW/nm of {best * 1e-3:.4g} uW/nm.")
    return Feedback(False, f"at phi = {value:.4g} rad the slope is {got * 1e-3:.4g} uW/nm, "
                           f"{100 * got / best:.0f}% of the best. {hint}")
