"""Amplitude feedback with a finite bandwidth: the PI loop of tapping-mode imaging.

The loop of :func:`amplitude_feedback` and ``TappingMode(..., feedback="pi")``. Averaging the
equation of motion (:mod:`~afmsmiler.modes.tapping.lever`) over a period with
z = A cos(w t - phi) (variation of parameters; Nayfeh and Mook (1979)) gives the slow flow of the
amplitude and phase::

    dA/dt     = [F0 sin(phi) - I_s - (k W / Q) A] / (2 m w)
    A dphi/dt = [F0 cos(phi) - k (1 - W^2) A + I_c] / (2 m w)

whose fixed points are the balance above. For the free lever it is linear in the complex
amplitude a = A e^(-i phi): da/dt = -(1 / tau - i Delta)(a - a_ss), with the time constant
tau = 2 Q / w0 and Delta = w0 (1 - W^2) / (2 W): the amplitude follows a change with tau, the
bandwidth limit of amplitude-modulation AFM (Sulchek et al., Appl. Phys. Lett. 76, 1473 (2000)).
The loop keeps that rate near the sample too (the first approximation of the feedback models;
the force gradient of the contact adds a frequency shift it leaves out), with a_ss(z_c) the
state of the slow approach, and a PI controller on the amplitude error moves the positioner.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ...parameters import Parameter, read_only
from ...validation import check_array
from .balance import SETPOINT_GRID, amplitude_curve, setpoint_state
from .lever import PARAMETERS, TappingLever, _check_lever, free_response

__all__ = ["FEEDBACKS", "FEEDBACK_PARAMETERS", "MAX_FEEDBACK_STEPS", "FeedbackLine",
           "amplitude_feedback"]

#: How :class:`TappingMode` holds the amplitude at the setpoint: ``"ideal"`` (infinitely fast:
#: every pixel at its setpoint state) or ``"pi"`` (a PI controller on the amplitude error, the
#: amplitude following a height change with the lever's time constant 2 Q / w0).
FEEDBACKS = ("ideal", "pi")
#: Most time steps of one :func:`amplitude_feedback` call or one :class:`TappingMode` scan with
#: ``feedback="pi"`` (a Python loop of some 10 us a step: a few seconds; a 64 x 64 image of the
#: default lever at two lines a second).
MAX_FEEDBACK_STEPS = 600_000
# time steps per amplitude time constant (the lag is integrated exactly over each step; the PI
# controller's integral explicitly, which needs K_I h well below 1)
_STEPS_PER_TAU = 4

#: The amplitude loop's gains: the positioner moves by K_P per metre of amplitude error and at
#: K_I times the error per second. The defaults close the loop at about 2 kHz for the default
#: lever (tau = 2 Q / w0 = 0.42 ms).
FEEDBACK_PARAMETERS = read_only({p.name: p for p in (
    Parameter(name="amplitude_kp", unit="", default=0.3, low=0.0, high=100.0,
              slider_low=0.0, slider_high=5.0, label="amplitude loop K_P"),
    Parameter(name="amplitude_ki", unit="1/s", display_unit="1/s", default=2000.0, low=0.0,
              high=1e7, slider_low=10.0, slider_high=1e5, log=True,
              label="amplitude loop K_I"),
)})


def _approach_table(lever: TappingLever):
    """The approach's steady complex amplitude A e^(-i phi) on an increasing grid of z_c.

    The slow approach of :func:`setpoint_state` (:meth:`AmplitudeCurve.sweep`) on
    :data:`SETPOINT_GRID` distances from 0.01 A0 to 1.5 A0; beyond, the free lever. Returns
    (z_first, dz, real parts, imaginary parts) as Python lists (the loop's inner step).
    """
    a0 = lever.free_amplitude
    z = a0 * np.linspace(0.01, 1.5, SETPOINT_GRID)
    amp, phs, _ = amplitude_curve(z, lever).sweep("approach")
    ok = np.isfinite(amp)
    if not ok.all():  # no stable root on the sweep there: the nearest distance's state
        idx = np.flatnonzero(ok)
        near = idx[np.abs(np.arange(z.size)[:, None] - idx[None, :]).argmin(axis=1)]
        amp, phs = amp[near], phs[near]
    free_a, free_phi = free_response(lever)
    amp = np.append(amp, free_a)
    phs = np.append(phs, free_phi)
    return (float(z[0]), float(z[1] - z[0]), (amp * np.cos(phs)).tolist(),
            (-amp * np.sin(phs)).tolist())


def _run_feedback(tables, r, t, m, a_sp, kp, ki, lever, ref, state):
    """The PI amplitude loop along a path: surface r (m), times t (s), materials m, in order.

    ``state`` = (t, r, Z, A, phi, e) at the point before the path, or None to start settled at
    the setpoint over the path's first point. Returns Z, A, phi at each point and the state.
    The complex amplitude a = A e^(-i phi) relaxes towards its steady state at the free lever's
    slow-flow rate 1 / tau - i Delta, exactly over each step for a steady state held fixed.
    """
    n = len(r)
    out_z, out_a, out_p = np.empty(n), np.empty(n), np.empty(n)
    tau = lever.time_constant
    w = lever.frequency_ratio
    delta = math.pi * lever.resonance_frequency * (1.0 - w * w) / w  # w0 (1 - W^2) / (2 W)
    if state is None:
        z0, dz, res, ims = tables[m[0]]
        zc = ref[m[0]]
        phi = math.atan2(-_lookup(zc, z0, dz, ims), _lookup(zc, z0, dz, res))
        state = (t[0], r[0], r[0] + zc, a_sp, phi, 0.0)
    t_prev, r_prev, big_z, amp, phi, e = state
    re, im = amp * math.cos(phi), -amp * math.sin(phi)
    h_max = tau / _STEPS_PER_TAU
    for i in range(n):  # bounded: the path's points, in at most MAX_FEEDBACK_STEPS steps
        span = t[i] - t_prev
        steps = max(1, math.ceil(span / h_max - 1e-9)) if span > 0 else 0
        z0, dz, res, ims = tables[m[i]]
        last = len(res) - 1
        if steps:
            h = span / steps
            decay = math.exp(-h / tau)
            cr, ci = decay * math.cos(delta * h), decay * math.sin(delta * h)
            slope = (r[i] - r_prev) / steps
            surface = r_prev
            for _ in range(steps):
                surface += slope
                x = (big_z - surface - z0) / dz  # z_c on the table's grid
                if x <= 0.0:
                    sr, si = res[0], ims[0]
                elif x >= last - 1:  # beyond 1.5 A0: the free lever
                    sr, si = res[last], ims[last]
                else:
                    j = int(x)
                    f = x - j
                    sr = res[j] + f * (res[j + 1] - res[j])
                    si = ims[j] + f * (ims[j + 1] - ims[j])
                dr, di = re - sr, im - si
                re, im = sr + cr * dr - ci * di, si + cr * di + ci * dr
                e_new = a_sp - math.hypot(re, im)
                big_z += kp * (e_new - e) + ki * h * e_new
                e = e_new
        t_prev, r_prev = t[i], r[i]
        out_z[i], out_a[i], out_p[i] = big_z, math.hypot(re, im), math.atan2(-im, re)
    return out_z, out_a, out_p, (t_prev, r_prev, big_z, float(out_a[-1]), float(out_p[-1]), e)


def _lookup(zc, z0, dz, values):
    x = min(max((zc - z0) / dz, 0.0), len(values) - 2.0)
    j = min(int(x), len(values) - 2)
    return values[j] + (x - j) * (values[j + 1] - values[j])


def _steps(t, tau, state_time=None) -> int:
    """Time steps the loop takes along times ``t`` (after ``state_time``, if given)."""
    t = np.asarray(t, dtype=float)
    if state_time is not None:
        t = np.concatenate(([state_time], t))
    spans = np.diff(t)
    return int(np.sum(np.maximum(1, np.ceil(spans / (tau / _STEPS_PER_TAU) - 1e-9))))


@dataclass(frozen=True)
class FeedbackLine:
    """The amplitude loop along a path (:func:`amplitude_feedback`), SI units.

    Parameters
    ----------
    time : numpy.ndarray
        Times in s of the points.
    surface : numpy.ndarray
        Height of the sample under the tip in m.
    height : numpy.ndarray
        The height channel in m: the positioner's height Z minus the setpoint distance z_c,sp
        (the surface itself once the loop has settled).
    amplitude, phase : numpy.ndarray
        Amplitude A in m and phase lag in rad.
    error : numpy.ndarray
        Amplitude error A - A_sp in m (the error channel).
    distance : numpy.ndarray
        Rest tip-sample distance z_c = Z - surface in m.
    state : tuple
        (t, surface, Z, A, phi, e) at the last point, to continue from.
    """

    time: np.ndarray
    surface: np.ndarray
    height: np.ndarray
    amplitude: np.ndarray
    phase: np.ndarray
    error: np.ndarray
    distance: np.ndarray
    state: tuple = field(repr=False)


def amplitude_feedback(heights, times, lever: TappingLever | None = None, *,
                       setpoint_ratio: float = PARAMETERS["setpoint_ratio"].default,
                       amplitude_kp: float = FEEDBACK_PARAMETERS["amplitude_kp"].default,
                       amplitude_ki: float = FEEDBACK_PARAMETERS["amplitude_ki"].default,
                       state=None) -> FeedbackLine:
    """Amplitude-modulation feedback with a finite bandwidth along a path over the sample.

    The amplitude follows its steady state A_ss(z_c) (the slow approach of
    :func:`setpoint_state`) as a first-order lag with the lever's time constant
    tau = 2 Q / w0, dA/dt = (A_ss(z_c) - A) / tau (and the phase alike), the decay of the
    averaged (slow-flow) equations of the driven lever,
    dA/dt = [F0 sin(phi) - I_s - (k W / Q) A] / (2 m w), whose free solution relaxes as
    exp(-w0 t / (2 Q)) (Sulchek et al., Appl. Phys. Lett. 76, 1473 (2000); Nayfeh and Mook,
    *Nonlinear Oscillations* (1979)). A PI controller on the error e = A_sp - A moves the
    positioner: dZ/dt = K_P de/dt + K_I e (Z up, away from the sample, when the amplitude is
    below the setpoint), and z_c = Z - r(t) with r the surface under the tip (linear between the
    points). On a down step the amplitude can rise at most to A0, the error saturates at
    A_sp - A0, and the tip descends no faster than K_I (A0 - A_sp): it parachutes, out of
    contact, until it lands (the error image shows it).

    Parameters
    ----------
    heights : array_like
        Surface height r in m under the tip at each point (1-D, at least 1 point).
    times : array_like
        Time in s of each point, non-decreasing (a repeated time: no step).
    lever : TappingLever, optional
        Lever and sample (default :class:`TappingLever` ()).
    setpoint_ratio : float
        Setpoint A_sp / A0, in (0, 1).
    amplitude_kp : float
        Proportional gain K_P (m of height per m of amplitude error).
    amplitude_ki : float
        Integral gain K_I in 1/s.
    state : tuple, optional
        A previous call's :attr:`FeedbackLine.state`; default: start settled at the setpoint
        over the first point.

    Returns
    -------
    FeedbackLine

    Raises
    ------
    ValueError
        Naming the argument out of range (times not non-decreasing, more than
        :data:`MAX_FEEDBACK_STEPS` time steps of tau / 4, K_I too large for that step), before
        the loop runs.
    TypeError
        If ``lever`` is not a TappingLever.
    """
    lever = TappingLever() if lever is None else _check_lever(lever)
    r = check_array("heights", heights, "m", ndim=1, min_size=1)
    t = check_array("times", times, "s", ndim=1, low=0.0, nondecreasing=True)
    if t.size != r.size:
        raise ValueError(f"heights and times must have one value per point: heights has "
                         f"{r.size}, times {t.size}")
    ratio = PARAMETERS["setpoint_ratio"].check(setpoint_ratio)
    kp = FEEDBACK_PARAMETERS["amplitude_kp"].check(amplitude_kp)
    ki = FEEDBACK_PARAMETERS["amplitude_ki"].check(amplitude_ki)
    tau = lever.time_constant
    _check_gain(ki, tau)
    if state is not None:
        state = _check_state(state, t[0])
    steps = _steps(t, tau, None if state is None else state[0])
    if steps > MAX_FEEDBACK_STEPS:
        raise ValueError(f"times must span at most {MAX_FEEDBACK_STEPS} steps of tau / "
                         f"{_STEPS_PER_TAU} = {tau / _STEPS_PER_TAU:g} s, got {steps}: a shorter "
                         f"path or a faster scan (or the ideal feedback)")
    zc_sp = setpoint_state(ratio, lever)[0]
    tables = [_approach_table(lever)]
    m = [0] * r.size
    out_z, amp, phi, new = _run_feedback(tables, r.tolist(), t.tolist(), m,
                                         ratio * lever.free_amplitude, kp, ki, lever, [zc_sp],
                                         state)
    return FeedbackLine(t, r, out_z - zc_sp, amp, phi, amp - ratio * lever.free_amplitude,
                        out_z - r, new)


def _check_gain(ki, tau):
    limit = 0.5 * _STEPS_PER_TAU / tau
    if ki * tau / _STEPS_PER_TAU > 0.5:
        raise ValueError(f"amplitude_ki must be <= {limit:g} 1/s for the loop's time step "
                         f"tau / {_STEPS_PER_TAU} (tau = {tau:g} s), got {ki:g} 1/s")


def _check_state(state, t0):
    if not isinstance(state, tuple) or len(state) != 6:
        raise TypeError(f"state must be a FeedbackLine.state (a 6-tuple), got "
                        f"{type(state).__name__}")
    values = tuple(float(check_array("state", v, ndim=0)) for v in state)
    if values[0] > t0:
        raise ValueError(f"state must come before the first time {t0:g} s, got "
                         f"{values[0]:g} s")
    return values
