"""Exercise checkers of module (c), contact-mode controller tuning.

Each checker simulates the student's answer with :class:`~afmsmiler.controller.ContactLoop` and
returns a :class:`~afmsmiler.exercises.Feedback`. A placeholder answer (``None``) gets "Not yet"
and a hint. Answers are in SI units: K_I in 1/s, K_D in s, speed in m/s. Each is an exercise of
notebook 03 (:mod:`afmsmiler.exercises.registry`) whose solution the loop's model finds
(:func:`fast_scan_gains`, :func:`critical_ki`).
"""
from __future__ import annotations

import numpy as np
from scipy.optimize import brentq

from ..controller import PARAMETERS, PRESETS, ContactLoop
from ..controller.defaults import SETPOINT, line_profile
from ..validation import (check_choice, check_instance, check_nonnegative, check_positive,
                          check_range)
from ..parameters import read_only
from ..samples.profiles import PROFILES
from . import Feedback, check_close
from .registry import exercise

__all__ = ["DEFAULTS", "height_error", "fast_scan_gains", "check_fast_scan", "critical_ki",
           "check_critical_ki", "unit_slip"]

#: The exercises' givens, in one place (SI units).
DEFAULTS = read_only(dict(plant="a_good_tracking", profile="real line", min_speed=1e-3,
                          max_rms_error=1e-9, unstable="d_unstable"))


def height_error(loop: ContactLoop, speed: float, profile: str = DEFAULTS["profile"]) -> float:
    """RMS height error of a scan: -Z_np against the topography, less the constant offset.

    In constant-force mode the image is the positioner height: -Z_np follows T shifted by
    (k_c + k_s) R / k_s. The error is the RMS of -Z_np - (T - that shift) over trace and retrace
    (the worse of the two), on the 512-pixel line ``profile``.

    Parameters
    ----------
    loop : ContactLoop
        The loop.
    speed : float
        Scan speed in m/s.
    profile : str
        ``"real line"``, ``"step"`` or ``"grating"``.

    Returns
    -------
    float
        RMS error in m (inf if the signals overflow).
    """
    check_instance("loop", loop, ContactLoop)
    check_choice("profile", profile, PROFILES)
    line = line_profile(profile)
    scan = loop.scan_line(line.x, line.heights, speed=speed, setpoint=SETPOINT)
    shift = loop.steady_state(SETPOINT, 0.0).z_np
    with np.errstate(over="ignore", invalid="ignore"):
        errs = [np.sqrt(np.mean((-(p.z_np - shift) - p.height) ** 2))
                for p in (scan.trace, scan.retrace)]
    worst = max(errs)
    return float(worst) if np.isfinite(worst) else float("inf")


def unit_slip(name: str, value: float) -> str | None:
    """Name a unit-prefix slip (a factor 10^6: us for s, 1/us for 1/s, um/s for m/s), or None.

    A value outside the range the panel's slider offers (:data:`PARAMETERS`) whose 10^6 or
    10^-6 multiple lies inside it is such a slip: K_D = 1 s is a derivative time of 1 us typed in
    the wrong unit, K_I = 3 1/s one of 3 per us. The message says which way, not the answer.

    Parameters
    ----------
    name : str
        ``"ki"``, ``"kd"`` or ``"speed"`` (a key of :data:`PARAMETERS`).
    value : float
        The student's value in SI.

    Returns
    -------
    str or None
    """
    p = PARAMETERS[name]
    lo, hi = p.slider_low, p.slider_high
    if value == 0 or lo <= value <= hi or not p.display_unit or p.display_unit == p.unit:
        return None
    label = p.label or name
    shown = f"[{p.to_display(lo):g}, {p.to_display(hi):g}] {p.display_unit}"
    for factor, way in ((1e-6, "above"), (1e6, "below")):
        if lo <= value * factor <= hi:
            return (f"{label} = {value:.4g} {p.unit} is 10^6 times {way} the range the panel "
                    f"offers ({shown}): a value in {p.display_unit} typed as {p.unit}? "
                    f"Give {label} in {p.unit} (1 {p.display_unit} = "
                    f"{p.to_si(1.0):g} {p.unit}).")
    return None


def critical_ki(kp: float, kd: float = 0.0, plant: str = DEFAULTS["unstable"]) -> float:
    """The K_I (1/s) at which the loop of ``plant`` with gains kp, kd loses stability.

    Found numerically, without the Routh-Hurwitz formula: the root of the largest real part of
    the closed-loop poles as a function of K_I (Brent's method on a bracket found by growing
    K_I four-fold from 1000 1/s up to the largest K_I the model accepts).

    Parameters
    ----------
    kp : float
        Proportional gain.
    kd : float
        Derivative gain in s.
    plant : str
        Preset whose mechanics to use.

    Returns
    -------
    float
        Critical K_I in 1/s (inf if the loop is stable for every K_I the model accepts, up to
        ``PARAMETERS["ki"].high``).
    """
    check_choice("plant", plant, list(PRESETS))
    base = PRESETS[plant].loop.replace(kp=check_nonnegative("kp", kp),
                                       kd=check_nonnegative("kd", kd, "s"))

    def growth(ki):
        return float(np.max(base.replace(ki=ki).poles.real))

    top = PARAMETERS["ki"].high  # beyond it ContactLoop rejects K_I: at most 16 steps
    low, high = 0.0, 1e3  # K_I = 0 is a second-order loop with positive coefficients: stable
    while growth(high) < 0:
        if high >= top:
            return float("inf")
        low, high = high, min(high * 4, top)
    return float(brentq(growth, low, high, xtol=1e-12 * high, rtol=1e-12))


def fast_scan_gains(speed=DEFAULTS["min_speed"],
                    max_rms_error: float = DEFAULTS["max_rms_error"]) -> tuple[float, float, float]:
    """Gains (K_P, K_I in 1/s, K_D in s) with which preset (a)'s loop scans at ``speed`` within
    ``max_rms_error`` (exercise 1), found on the model as the checker's hint says.

    K_P is raised a decade at a time from 1 to the panel's largest, K_I set to half the
    critical K_I of that K_P (:func:`critical_ki`: the loop stays stable) and K_D to 0; the
    first gains whose :func:`height_error` is within the bound are returned.

    Parameters
    ----------
    speed : float
        Scan speed in m/s.
    max_rms_error : float
        Largest accepted RMS height error in m.

    Returns
    -------
    (kp, ki, kd) : tuple of float

    Raises
    ------
    ValueError
        If no K_P of the search scans within the bound.
    """
    speed = PARAMETERS["speed"].check(speed)
    max_rms_error = check_positive("max_rms_error", max_rms_error, "m")
    loop = PRESETS[DEFAULTS["plant"]].loop
    kp = 1.0
    while kp <= PARAMETERS["kp"].slider_high:  # at most 4 decades: 1 to 1000
        ki = min(0.5 * critical_ki(kp, 0.0, DEFAULTS["plant"]), PARAMETERS["ki"].slider_high)
        if height_error(loop.replace(kp=kp, ki=ki, kd=0.0), speed) <= max_rms_error:
            return kp, ki, 0.0
        kp *= 10.0
    raise ValueError(f"speed must allow an RMS error within max_rms_error with K_P up to "
                     f"{PARAMETERS['kp'].slider_high:g}, got speed={speed!r} m/s, "
                     f"max_rms_error={max_rms_error!r} m")


@exercise("03.1", "The fastest scan", answers=("kp", "ki", "kd"), solution=fast_scan_gains)
def check_fast_scan(kp, ki, kd, speed=DEFAULTS["min_speed"],
                    max_rms_error: float = DEFAULTS["max_rms_error"],
                    min_speed: float = DEFAULTS["min_speed"]) -> Feedback:
    """Exercise 1: gains for a fast scan (at least ``min_speed``) with a small height error.

    The plant is the one of preset (a) (stiff sample); the line is the "real line" profile (a
    row of a real AFM image, see :func:`afmsmiler.samples.profile`).

    Parameters
    ----------
    kp : float or None
        Proportional gain K_P (dimensionless).
    ki : float or None
        Integral gain K_I in 1/s.
    kd : float or None
        Derivative gain K_D in s.
    speed : float
        Scan speed in m/s (the faster the better; at least ``min_speed``).
    max_rms_error : float
        Largest accepted RMS height error in m.
    min_speed : float
        Slowest accepted speed in m/s.

    Returns
    -------
    Feedback
        Passed when the loop is stable, the speed is at least ``min_speed`` and the error
        (:func:`height_error`) is at most ``max_rms_error``.
    """
    max_rms_error = check_positive("max_rms_error", max_rms_error, "m")
    min_speed = check_positive("min_speed", min_speed, "m/s")
    hint = ("Raise K_P first (it adds damping and stiffness to the loop), then K_I as far as "
            "the poles allow: the loop must stay stable. K_I in 1/s, K_D in s.")
    if kp is None or ki is None or kd is None:
        return Feedback(False, f"enter K_P, K_I [1/s] and K_D [s]. {hint}")
    try:
        answer = dict(kp=check_nonnegative("kp", kp), ki=check_nonnegative("ki", ki, "1/s"),
                      kd=check_nonnegative("kd", kd, "s"),
                      speed=check_positive("speed", speed, "m/s"))
    except ValueError as err:
        return Feedback(False, f"{err}. {hint}")
    for name in ("ki", "kd", "speed"):
        slip = unit_slip(name, answer[name])
        if slip is not None:  # a unit slip is rejected even when the loop happens to track
            return Feedback(False, slip)
    try:
        speed = PARAMETERS["speed"].check(answer.pop("speed"))
        loop = PRESETS[DEFAULTS["plant"]].loop.replace(**answer)
    except ValueError as err:
        return Feedback(False, f"{err}. {hint}")
    um_s = PARAMETERS["speed"]
    if speed < min_speed:
        return Feedback(False, f"scan at {um_s.to_display(min_speed):g} um/s or faster "
                               f"(you chose {um_s.to_display(speed):.4g} um/s).")
    if not loop.is_stable():
        return Feedback(False, f"the loop is unstable (Routh-Hurwitz margin "
                               f"{loop.stability_margin:.3g}): the oscillation grows. {hint}")
    err = height_error(loop, speed)
    nm = PARAMETERS["height"].scale
    msg = (f"RMS height error {err * nm:.3g} nm at {um_s.to_display(speed):.4g} um/s "
           f"(limit {max_rms_error * nm:.3g} nm).")
    if err <= max_rms_error:
        return Feedback(True, msg + " Now try to go faster still.")
    return Feedback(False, f"{msg} {hint}")


@exercise("03.2", "Where does it become unstable?", answers=("ki",), solution=critical_ki)
def check_critical_ki(ki, kp: float = 100.0, kd: float = 0.0, rtol: float = 0.01) -> Feedback:
    """Exercise 2: the largest K_I for which preset (d)'s loop (K_P = 100, K_D = 0) is stable.

    Parameters
    ----------
    ki : float or None
        The student's K_I in 1/s (from the Hurwitz condition B C = A D).
    kp : float
        Proportional gain.
    kd : float
        Derivative gain in s.
    rtol : float
        Accepted relative error.

    Returns
    -------
    Feedback
    """
    rtol = check_range("rtol", rtol, 0.0, 1.0, low_inclusive=False)
    hint = ("Write B C = A D with A = m_c + m_s + b_s K_D, B = b_c + b_s + b_s K_P + k_s K_D, "
            "C = k_c + k_s + b_s K_I + k_s K_P, D = k_s K_I, and solve for K_I (in 1/s).")
    if ki is None:
        return Feedback(False, f"enter K_I in 1/s. {hint}")
    return check_close("critical K_I", ki, critical_ki(kp, kd), rtol, "1/s", hint)
