"""The reference solver of the tapping lever: time integration to the steady state.

The reference solver (:func:`integrate`). scipy's ``odeint`` (ODEPACK's LSODA: Adams steps,
switching to BDF where the sample's stiffness makes the system stiff in hard contact; relative
tolerance 1e-9, absolute 1e-11 A0) integrates the equation of motion (:mod:`~afmsmiler.modes.tapping.lever`)
in the dimensionless time w0 t from a chosen start (the top of a harmonic motion of given
amplitude and phase, so that the tip starts out of contact on the branch the start lies on) in
blocks of :data:`BLOCK_PERIODS` drive periods.
The amplitude A and phase lag phi of the first harmonic, z ~ A cos(w t - phi), are taken by
lock-in over the last whole period of each block (64 samples a period, an exact quadrature for a
periodic signal's first harmonic up to the 63rd harmonic). A transient decays as exp(-pi W n / Q),
so a change c between two successive blocks leaves at most c r / (1 - r) to come, r = exp(-pi W
BLOCK_PERIODS / Q); the transient is over when that estimate is below 1e-4 A0 in amplitude and
0.01 deg in phase (far below the 1 % and 2 deg the comparisons need), at most :data:`MAX_PERIODS`
periods. The result is then the lock-in over :data:`LOCKIN_PERIODS` whole periods.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import odeint

from ...validation import check_array, check_integer, check_range
from .lever import PARAMETERS, TappingLever, _check_lever, free_response

__all__ = ["MAX_PERIODS", "BLOCK_PERIODS", "LOCKIN_PERIODS", "SteadyState", "integrate"]

#: Longest time integration in drive periods (bounded loop; the transient criterion stops first).
MAX_PERIODS = 20_000
#: Most internal steps LSODA takes between two output samples (a 64th of a period).
_MAX_STEPS = 100_000
#: Drive periods per block of the transient criterion, and periods of the final lock-in.
BLOCK_PERIODS = 10
LOCKIN_PERIODS = 10

#: Samples per period of the lock-in.
_SAMPLES = 64
# transient criterion: estimated remaining error in amplitude (fraction of A0) and phase (deg)
_AMPLITUDE_TOL, _PHASE_TOL = 1e-4, 1e-2


@dataclass(frozen=True)
class SteadyState:
    """The steady state of a time integration (SI units), from lock-in over whole periods.

    Parameters
    ----------
    lever : TappingLever
        The lever and sample.
    distance : float
        Rest tip-sample distance z_c in m.
    amplitude : float
        Amplitude A of the first harmonic in m.
    phase : float
        Phase lag phi of the first harmonic behind the drive in rad.
    mean_deflection : float
        Mean deflection <z> in m (the static part, <F_ts> / k).
    damping_work : float
        Energy in J the sample's damping force took per period, -(1/N) int F_damp z' dt over
        the N lock-in periods (integrated with the motion, as a third state variable).
    periods : int
        Drive periods integrated in all (transient included).
    converged : bool
        Whether the transient criterion was met before :data:`MAX_PERIODS`.
    time : ndarray
        Times in s of the samples of the last period.
    deflection : ndarray
        Deflection z in m at those times (for plots of the motion).
    """

    lever: TappingLever
    distance: float
    amplitude: float
    phase: float
    mean_deflection: float
    damping_work: float
    periods: int
    converged: bool
    time: np.ndarray
    deflection: np.ndarray

    @property
    def dissipated_energy(self) -> float:
        """E_dis in J from this state's amplitude and phase (``lever.dissipated_energy``)."""
        return self.lever.dissipated_energy(self.amplitude, self.phase)


def integrate(distance: float, lever: TappingLever | None = None, *, start=None,
              max_periods: int = MAX_PERIODS) -> SteadyState:
    """Integrate the driven lever at one distance to its steady state (the reference solver).

    Parameters
    ----------
    distance : float
        Rest tip-sample distance z_c in m, in (0, 1e-5].
    lever : TappingLever, optional
        Lever and sample (default :class:`TappingLever` ()).
    start : (float, float), optional
        (A, phi): start at the top of the motion A cos(w t - phi), i.e. z = A, z' = 0 at
        w t = phi, so that a start on a branch of :func:`amplitude_curve` stays on it. Default:
        the free motion (A0, free phase). The tip must start outside the sample:
        z_c + A > a0.
    max_periods : int
        Most drive periods to integrate, BLOCK_PERIODS + LOCKIN_PERIODS to :data:`MAX_PERIODS`:
        the bound of its cost. Far from the sample a run takes well under a second; in hard
        contact (z_c of a nanometre or less) the stiff contact force makes each period costly,
        and a run can take tens of seconds: it is the reference, :func:`amplitude_curve` is the
        fast solver.

    Returns
    -------
    SteadyState

    Raises
    ------
    ValueError
        On a distance out of range, a start inside the sample or out of range, or bad
        ``max_periods``, before any integration.
    """
    lever = TappingLever() if lever is None else _check_lever(lever)
    zp = PARAMETERS["distance"]
    zc = zp.check(distance)
    n_max = check_integer("max_periods", max_periods, BLOCK_PERIODS + LOCKIN_PERIODS,
                          MAX_PERIODS)
    if start is None:
        a_start, phi_start = free_response(lever)
    else:
        if np.shape(start) != (2,):
            raise ValueError(f"start must be (amplitude, phase), got {start!r:.60}")
        fa = PARAMETERS["free_amplitude"]
        a_start = check_range("start amplitude", start[0], fa.low, fa.high, "m",
                              low_inclusive=False)
        phi_start = check_array("start phase", start[1], "rad", low=-2 * math.pi,
                                high=2 * math.pi).item()
    a0 = lever.intermolecular_distance
    if zc + a_start <= a0:
        raise ValueError(f"start amplitude: the tip would start inside the sample (z_c + A = "
                         f"{zc + a_start:g} m <= a0 = {a0:g} m); start it above the sample")
    # dimensionless: x = z / A0, tau = w0 t
    scale = lever.free_amplitude
    k, q, w = lever.spring_constant, lever.quality_factor, lever.frequency_ratio
    f_drive = lever.drive_force / (k * scale)
    w0 = 2.0 * math.pi * lever.resonance_frequency
    hr6 = lever.hamaker_constant * lever.radius / 6.0
    e43 = 4.0 / 3.0 * lever.reduced_modulus * math.sqrt(lever.radius)
    eta_r = lever.sample_viscosity * math.sqrt(lever.radius)
    adhesion = hr6 / (a0 * a0)
    inv = 1.0 / (k * scale)

    def force(d, v):  # F_ts / (k A0) and its damping part, plain floats (the inner loop)
        if d > a0:
            return -hr6 / (d * d) * inv, 0.0
        delta = a0 - d
        sq = math.sqrt(delta)
        damp = -eta_r * sq * v
        return (-adhesion + e43 * sq * delta + damp) * inv, damp * inv

    def rhs(tau, y):  # y[2]: work done on the sample's damping, in units of k A0^2
        x, xd = y[0], y[1]
        f, damp = force(zc + scale * x, scale * w0 * xd)
        return [xd, -x - xd / q + f_drive * math.cos(w * tau) + f, -damp * xd]

    period = 2.0 * math.pi / w
    tau = phi_start / w
    y = np.array([a_start / scale, 0.0, 0.0])

    def run(n, tau, y):
        """n periods from tau; returns the end state and the last n periods' samples."""
        t_eval = tau + period * (np.arange(n * _SAMPLES + 1) / _SAMPLES)
        # LSODA's steps run in Fortran: five times faster than solve_ivp's DOP853 (Python
        # steps) at the same tolerances, the steady states agreeing to 1e-7 in amplitude
        ys, info = odeint(rhs, y, t_eval, tfirst=True, rtol=1e-9, atol=1e-11,
                          mxstep=_MAX_STEPS, full_output=True)
        if info["message"] != "Integration successful.":  # pragma: no cover - bounded system
            raise RuntimeError(f"time integration failed: {info['message']}")
        ys = ys.T
        return t_eval[-1], ys[:, -1], t_eval[:-1], ys[:, :-1]

    def lockin(t, x):
        """(A, phi) of x(t) sampled over whole periods (t on the drive's phase grid)."""
        c = np.cos(w * t)
        s = np.sin(w * t)
        ac = 2.0 * np.mean(x * c)
        as_ = 2.0 * np.mean(x * s)
        return math.hypot(ac, as_) * scale, math.atan2(as_, ac)

    # a transient decaying as exp(-pi W n / Q) changes by (1 - r) of what is left per block:
    # what is left after a change c is at most c r / (1 - r), r = exp(-pi W BLOCK_PERIODS / Q)
    ratio = math.exp(-math.pi * w * BLOCK_PERIODS / q)
    tail = ratio / (1.0 - ratio)
    done, previous, converged = 0, None, False
    while done + BLOCK_PERIODS + LOCKIN_PERIODS <= n_max:
        tau, y, t, xs = run(BLOCK_PERIODS, tau, y)
        done += BLOCK_PERIODS
        now = lockin(t[-_SAMPLES:], xs[0, -_SAMPLES:])
        if previous is not None and abs(now[0] - previous[0]) * tail < _AMPLITUDE_TOL * scale \
                and abs(math.degrees(now[1] - previous[1])) * tail < _PHASE_TOL:
            converged = True
            break
        previous = now
    tau, y, t, xs = run(LOCKIN_PERIODS, tau, y)
    done += LOCKIN_PERIODS
    amp, phi = lockin(t, xs[0])
    if phi < -0.5 * math.pi:  # the lag lives in (0, pi); atan2 may wrap just below -pi
        phi += 2.0 * math.pi
    # the work of the damping force on the tip, sign flipped (the energy the sample took),
    # integrated as a third state over the lock-in periods, per period
    work = (y[2] - xs[2, 0]) / LOCKIN_PERIODS * k * scale * scale
    return SteadyState(lever, zc, amp, phi, float(np.mean(xs[0]) * scale), float(work), done,
                       converged, t[-_SAMPLES:] / w0, xs[0, -_SAMPLES:] * scale)
