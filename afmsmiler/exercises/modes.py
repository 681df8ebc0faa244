"""Exercise checkers of module (g), imaging modalities.

Each checker computes its reference with the library's models (:func:`~afmsmiler.modes.
setpoint_state`, :func:`~afmsmiler.modes.friction_loop`, :meth:`TappingLever.dissipated_energy
<afmsmiler.modes.TappingLever.dissipated_energy>`), never from a stored number, and returns a
:class:`~afmsmiler.exercises.Feedback`. A placeholder answer (``None``) gets "Not yet" and a hint;
the common slips are named without giving the answer away.

1. :func:`check_attractive_setpoint`: the lowest setpoint A_sp / A0 that keeps a tapping tip on
   the attractive branch (the model's branch map); a setpoint given in nm, m or per cent is
   recognised.
2. :func:`check_friction_coefficient`: the friction coefficient from the friction loop of a tilted
   line (:func:`friction_loop_data`); the trace alone (slope-contaminated), the retrace alone,
   the full difference (a factor 2), the slope term and a force not divided by the load are
   recognised.
3. :func:`check_dissipated_energy`: E_dis per cycle from an amplitude and a phase
   (:func:`dissipation_givens`); the phase's sine taken of degrees as radians, the free lever's
   term left out and a unit prefix or electronvolts are recognised.
"""
from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from ..modes.lateral import FrictionLoop, friction_loop
from ..modes.tapping import TappingLever, setpoint_state
from ..parameters import read_only, unit_scale
from . import Feedback, check_close, diagnose_slip, read_number
from .registry import exercise

__all__ = ["DEFAULTS", "tapping_lever", "lowest_attractive_setpoint",
           "check_attractive_setpoint", "friction_loop_data", "friction_from_loop",
           "check_friction_coefficient", "dissipation_lever", "dissipation_givens",
           "dissipated_energy", "check_dissipated_energy"]

#: The exercises' givens, in one place (SI units).
DEFAULTS = read_only(dict(
    # 1. a 12 nm free amplitude on the default lever and sample (k = 40 N/m, Q = 400, 1 GPa)
    free_amplitude=12e-9, setpoint_tolerance=0.05,
    # 2. a line tilted by 4 deg, mu = 0.25 under 20 nN, 128 pixels of 5 nm, 0.2 nN of noise
    tilt=math.radians(4.0), friction=0.25, load=20e-9, loop_pixels=128, loop_pixel=5e-9,
    loop_noise=0.2e-9, friction_rtol=0.03,
    # 3. a viscous sample (200 Pa s) held at 0.7 A0 of 10 nm
    viscosity=200.0, dissipation_setpoint=0.7, energy_rtol=0.03,
))

_NM = unit_scale("nm", "m")
_NN = unit_scale("nN", "N")

#: Joules per electronvolt (CODATA 2018, exact).
_EV = 1.602176634e-19


# -- 1. the attractive branch ------
def tapping_lever() -> TappingLever:
    """Exercise 1's lever and sample: the defaults of :class:`TappingLever` at A0 = 12 nm.

    Returns
    -------
    TappingLever
    """
    return TappingLever(free_amplitude=DEFAULTS["free_amplitude"])


@lru_cache(maxsize=1)
def lowest_attractive_setpoint() -> float:
    """The lowest setpoint ratio at which exercise 1's approach stays on the attractive branch.

    Bisection (to 1e-3) between 0.5 (repulsive) and 0.99 (attractive) on the branch
    :func:`~afmsmiler.modes.setpoint_state` reports.

    Returns
    -------
    float
        r* in (0.5, 0.99): attractive at and above it, repulsive below.
    """
    lever = tapping_lever()
    lo, hi = 0.5, 0.99
    if setpoint_state(lo, lever)[3] or not setpoint_state(hi, lever)[3]:
        raise RuntimeError("exercise 1's lever no longer changes branch between 0.5 and 0.99")
    for _ in range(12):  # bounded: (0.49 / 2^12) < 1e-3
        mid = 0.5 * (lo + hi)
        if setpoint_state(mid, lever)[3]:
            hi = mid
        else:
            lo = mid
    return hi


@exercise("07.1", "Stay on the attractive branch", answers=("ratio",),
          solution=lowest_attractive_setpoint)
def check_attractive_setpoint(ratio,
                              tolerance: float = DEFAULTS["setpoint_tolerance"]) -> Feedback:
    """Exercise 1: the lowest setpoint A_sp / A0 that keeps the tip on the attractive branch.

    Parameters
    ----------
    ratio : float or None
        The student's setpoint as a fraction of the free amplitude (A_sp / A0).
    tolerance : float
        How far above the lowest one an answer may be (0.05: within 0.05 of it).

    Returns
    -------
    Feedback
        Passed when the approach at ``ratio`` stays on the attractive branch (the model's branch
        map) and ``ratio`` is at most the lowest such setpoint + ``tolerance``.
    """
    hint = ("Move the setpoint on the tapping panel with A0 = 12 nm and watch which branch the "
            "approach ends on; the answer is a fraction A_sp / A0 between 0 and 1.")
    r, feedback = read_number("a setpoint ratio", ratio, hint)
    if feedback is not None:
        return feedback
    a0 = DEFAULTS["free_amplitude"]
    a0_nm = a0 * _NM
    if not 0 < r < 1:
        if 1 <= r <= a0_nm:
            return Feedback(False, f"{r:g} looks like the setpoint amplitude in nm: the setpoint "
                                   f"is the fraction A_sp / A0 (divide by A0 = {a0_nm:g} nm).")
        if a0_nm < r < 100:
            return Feedback(False, f"{r:g} looks like a per cent: give the fraction A_sp / A0 "
                                   f"(between 0 and 1).")
        return Feedback(False, f"the setpoint ratio must lie between 0 and 1 (A_sp below the "
                               f"free amplitude), got {r:g}. {hint}")
    if r < 1e-6 and 0 < r / a0 < 1:
        return Feedback(False, f"{r:g} looks like an amplitude in m: the setpoint is the "
                               f"fraction A_sp / A0.")
    lever = tapping_lever()
    try:
        zc, _, _, attractive = setpoint_state(r, lever)
    except ValueError:
        return Feedback(False, f"at {r:g} A0 the approach never gets down to the setpoint; "
                               f"choose a larger one.")
    where = f"the feedback holds the lever at z_c = {zc * _NM:.3g} nm"
    if not attractive:
        return Feedback(False, f"At {r:g} A0 {where}, but the approach has jumped to the "
                               f"repulsive branch: the tip taps the sample hard. Raise the "
                               f"setpoint.")
    best = lowest_attractive_setpoint()
    if r > best + tolerance:
        return Feedback(False, f"At {r:g} A0 the tip stays on the attractive branch ({where}), "
                               f"but you can go lower and still stay there (and follow the "
                               f"surface more closely).")
    depth = lever.indentation(zc, r * lever.free_amplitude)
    touch = (f"its tip still dips {depth * _NM:.2g} nm into the sample once per cycle, but the "
             f"net force over a cycle stays attractive" if depth > 0 else
             f"its tip stays {-depth * _NM:.2g} nm clear of the sample")
    return Feedback(True, f"At {r:g} A0 {where} on the attractive branch, close to the lowest "
                          f"setpoint that keeps it there: {touch}.")


# -- 2. friction from a loop ------
@lru_cache(maxsize=1)
def friction_loop_data() -> FrictionLoop:
    """Exercise 2's friction loop: one material on a line tilted along the scan, with noise.

    Returns
    -------
    FrictionLoop
        ``x`` in m, ``trace`` and ``retrace`` in N (Gaussian noise of
        ``DEFAULTS["loop_noise"]`` RMS added, seed 7), ``normal_force`` in N.
    """
    d = DEFAULTS
    n = d["loop_pixels"]
    heights = math.tan(d["tilt"]) * np.arange(n) * d["loop_pixel"]
    loop = friction_loop(heights, d["friction"], d["loop_pixel"], normal_force=d["load"])
    rng = np.random.default_rng(7)
    return FrictionLoop(loop.x, loop.trace + rng.normal(0.0, d["loop_noise"], n),
                        loop.retrace + rng.normal(0.0, d["loop_noise"], n), loop.normal_force,
                        loop.lateral_stiffness)


def friction_from_loop() -> float:
    """Exercise 2's answer from :func:`friction_loop_data`, as the hint says.

    Half the difference of trace and retrace (friction flips sign with the scan direction, the
    slope term does not), averaged over the line but its two turn-around pixels (where the tip
    sticks; the notebook's first try leaves them out too), over the load.

    Returns
    -------
    float
        The friction coefficient (dimensionless).
    """
    loop = friction_loop_data()
    return float(np.mean((loop.trace[1:-1] - loop.retrace[1:-1]) / 2.0) / loop.normal_force)


@exercise("07.2", "Friction from a friction loop", answers=("mu",), solution=friction_from_loop)
def check_friction_coefficient(mu, rtol: float = DEFAULTS["friction_rtol"]) -> Feedback:
    """Exercise 2: the friction coefficient from :func:`friction_loop_data`.

    Parameters
    ----------
    mu : float or None
        The student's friction coefficient (dimensionless).
    rtol : float
        Accepted relative error.

    Returns
    -------
    Feedback
        Passed within ``rtol`` of the coefficient the loop was made with.
    """
    hint = ("Friction flips sign with the scan direction, the slope term does not: combine "
            "trace and retrace so that the slope cancels, then divide by the load.")
    value, feedback = read_number("a friction coefficient", mu, hint)
    if feedback is not None:
        return feedback
    d = DEFAULTS
    expected, load = d["friction"], d["load"]
    tan = math.tan(d["tilt"])

    def near(x):
        return abs(value - x) <= rtol * abs(x)

    for wrong, message in (
            (expected + tan, "That is the trace alone over the load: it holds the slope term as "
                             "well as friction (the line is tilted)."),
            (expected - tan, "That is the retrace alone over the load: the slope term is still "
                             "in it, with the other sign."),
            (2 * expected, "That is twice the friction coefficient: trace - retrace holds the "
                           "friction force twice (once each way)."),
            (tan, "That is the slope term (trace + retrace) / 2 over the load, the part that "
                  "does NOT flip with the scan direction."),
            (expected * load, "That is a force in N: divide by the load."),
            (expected * load * _NN, "That looks like a force in nN: divide by the load (in the "
                                     "same unit).")):
        if near(wrong) and not near(expected):
            return Feedback(False, f"mu = {value:.4g}. {message}")
    return check_close("friction coefficient", value, expected, rtol, hint=hint)


# -- 3. dissipation from the phase ------
def dissipation_lever() -> TappingLever:
    """Exercise 3's lever and sample: the defaults of :class:`TappingLever` on a viscous sample.

    Returns
    -------
    TappingLever
    """
    return TappingLever(sample_viscosity=DEFAULTS["viscosity"])


@lru_cache(maxsize=1)
def dissipation_givens() -> dict:
    """What exercise 3 gives: k, Q, A0, the setpoint amplitude A and the phase lag in degrees.

    The phase is the model's (:func:`~afmsmiler.modes.setpoint_state` at
    ``DEFAULTS["dissipation_setpoint"]``), rounded to 0.01 deg; the drive is at resonance.

    Returns
    -------
    dict
        ``spring_constant`` (N/m), ``quality_factor``, ``free_amplitude`` (m), ``amplitude``
        (m), ``phase_deg`` (deg).
    """
    lever = dissipation_lever()
    r = DEFAULTS["dissipation_setpoint"]
    phase = setpoint_state(r, lever)[1]
    return dict(spring_constant=lever.spring_constant, quality_factor=lever.quality_factor,
                free_amplitude=lever.free_amplitude, amplitude=r * lever.free_amplitude,
                phase_deg=round(math.degrees(phase), 2))


def dissipated_energy() -> float:
    """Exercise 3's answer: E_dis in J at :func:`dissipation_givens`, from the lever's model.

    Returns
    -------
    float
        :meth:`~afmsmiler.modes.TappingLever.dissipated_energy` at the givens' amplitude and
        phase (in rad).
    """
    g = dissipation_givens()
    return float(dissipation_lever().dissipated_energy(g["amplitude"], math.radians(g["phase_deg"])))


@exercise("07.3", "Dissipation from the phase", answers=("energy",), solution=dissipated_energy)
def check_dissipated_energy(energy, rtol: float = DEFAULTS["energy_rtol"]) -> Feedback:
    """Exercise 3: the energy in J the sample takes per cycle, from :func:`dissipation_givens`.

    Parameters
    ----------
    energy : float or None
        The student's E_dis in J.
    rtol : float
        Accepted relative error.

    Returns
    -------
    Feedback
        Passed within ``rtol`` of E_dis = (pi k A^2 / Q)[(A0 / A) sin(phi) - 1] (the lever's
        :meth:`~afmsmiler.modes.TappingLever.dissipated_energy` at the givens).
    """
    hint = ("E_dis = (pi k A^2 / Q) [(A0 / A) sin(phi) - omega / omega0] with omega = omega0 "
            "here; answer in J.")
    value, feedback = read_number("an energy", energy, hint)
    if feedback is not None:
        return feedback
    g = dissipation_givens()
    phi = math.radians(g["phase_deg"])
    expected = dissipated_energy()
    k, q, a0, a = g["spring_constant"], g["quality_factor"], g["free_amplitude"], g["amplitude"]
    base = math.pi * k * a * a / q

    def near(x):
        return x != 0 and abs(value - x) <= rtol * abs(x)

    for wrong, message in (
            (base * ((a0 / a) * math.sin(g["phase_deg"]) - 1.0),
             "The sine was taken of the phase in degrees as if it were radians: convert the "
             "phase to radians first (or use a sine in degrees)."),
            (base * (a0 / a) * math.sin(phi),
             "The lever's own damping was left out: subtract the free lever's part "
             "(the omega / omega0 term), which the drive spends even without a sample."),
            (base * ((a0 / a) * math.cos(phi) - 1.0),
             "That uses the cosine of the phase: the energy the drive puts in goes with "
             "sin(phi).")):
        if near(wrong) and not near(expected):
            return Feedback(False, f"E_dis = {value:.4g} J. {message}")
    if near(expected / _EV) and not near(expected):
        return Feedback(False, f"E_dis = {value:.4g}: that looks like electronvolts; answer in "
                               f"J.")
    for prefix in ("aJ", "zJ"):  # beyond diagnose_slip's 10^18 for zJ
        if near(expected * unit_scale(prefix, "J")) and not near(expected):
            return Feedback(False, f"E_dis = {value:.4g}: that looks like {prefix}; answer in "
                                   f"J.")
    slip = diagnose_slip(value, expected, rtol, "J")
    if slip is not None and abs(value - expected) > rtol * abs(expected):
        return Feedback(False, f"E_dis = {value:.4g} J. {slip}")
    return check_close("E_dis", value, expected, rtol, "J", hint=hint)
