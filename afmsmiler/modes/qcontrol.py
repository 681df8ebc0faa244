"""Active Q control: a driven lever with phase-shifted deflection feedback.

A Q controller adds to the lever's drive its own deflection, amplified by a gain g and delayed by
a phase phi (Anczykowski, Cleveland, Krueger, Elings and Fuchs, Appl. Phys. A 66, S885 (1998);
Hoelscher, Ebeling and Schwarz, J. Appl. Phys. 99, 084311 (2006); Tamayo, Humphris and Miles,
Appl. Phys. Lett. 77, 582 (2000)). Near the resonance the phase shifter is, to first order, the
combination of the deflection and its derivative that shifts a harmonic of the resonance
frequency w0 by exactly phi, which is what this module models (and what the haptic device's
firmware computes from its encoder)::

    m z'' + (m w0 / Q) z' + k z = F_drive(t) + g k [cos(phi) z - sin(phi) z' / w0]

For z = Z e^{i w0 t} the bracket is e^{-i phi} Z: the feedback lags the deflection by phi, and
phi = 90 deg (a quarter period's delay, z(t - T/4) = -z'/w0) makes it a pure velocity feedback.
The closed loop is again a damped oscillator (derived with sympy in the tests):

    k_eff = k (1 - g cos(phi)),                   f_eff = f0 sqrt(1 - g cos(phi))
    1 / Q_lin = 1 / Q + g sin(phi),               Q_eff = sqrt(1 - g cos(phi)) Q_lin

so at phi = 90 deg the resonance stays and Q_eff = 1 / (1/Q + g) (Hoelscher et al.'s result):
g > 0 damps (faster tapping in air), g < 0 undamps (sharper resonance in liquid). The in-phase
part g cos(phi) shifts the resonance (the spring is softened or stiffened). The loop is stable
while both coefficients stay positive, 1 - g cos(phi) > 0 and 1/Q + g sin(phi) > 0: at phi = 90
deg the gain must stay above -1/Q, where the feedback cancels all the lever's damping and it
self-oscillates (the limit of Q enhancement, :func:`stable_gains`).

Frequency response (m/N), W = w / w0::

    Z / F = 1 / (k [(1 - g cos(phi)) - W^2 + i W (1/Q + g sin(phi))])

A free decay from z(0) = A, z'(0) = 0 is A (l2 e^{l1 t} - l1 e^{l2 t}) / (l2 - l1) with the roots
l1, l2 of s^2 + (w0 / Q_lin) s + w0^2 (1 - g cos(phi)) (any damping, over- or underdamped).
"""
from __future__ import annotations

import cmath
import math
from dataclasses import dataclass, fields

import numpy as np

from ..parameters import Parameter, read_only
from ..validation import check_array, check_integer, check_range
from .oscillator import PointMassLever
from .tapping import PARAMETERS as TAPPING

__all__ = ["PARAMETERS", "QControl", "ClosedLoopResponse", "RingDown", "stable_gains",
           "closed_loop_response", "ring_down", "quality_factor_from_ringdown", "fit_ring_down",
           "MAX_POINTS"]

#: Most frequencies or times one call computes (a second of numpy work is far more).
MAX_POINTS = 1_000_000

#: The user-settable quantities of the Q-control model (SI): the tapping lever of module (g)
#: (k = 40 N/m, f0 = 300 kHz, Q = 400 in air) and the controller's gain and phase.
PARAMETERS = read_only({p.name: p for p in (
    TAPPING["spring_constant"],
    TAPPING["resonance_frequency"],  # down to a lever felt by hand (~10 Hz) and below
    TAPPING["quality_factor"].with_(slider_low=1.0, slider_high=1000.0),
    Parameter(name="gain", unit="", default=0.0, low=-10.0, high=10.0, slider_low=-0.05,
              slider_high=0.05, label="Q-control gain g"),
    Parameter(name="phase", unit="rad", display_unit="deg", default=math.pi / 2, low=-math.pi,
              high=math.pi, label="Q-control phase shift phi"),
)})


@dataclass(frozen=True)
class QControl(PointMassLever):
    """A lever with a Q controller: every quantity of the closed loop, validated (SI units).

    Parameters
    ----------
    spring_constant : float
        Spring constant k in N/m.
    resonance_frequency : float
        Free resonance frequency f0 in Hz.
    quality_factor : float
        Quality factor Q of the lever without control, > 0.
    gain : float
        Feedback gain g (dimensionless: the feedback force per k times the deflection), in
        [-10, 10].
    phase : float
        Phase lag phi of the feedback behind the deflection at f0, in rad, in [-pi, pi]
        (pi / 2: velocity feedback).

    Raises
    ------
    ValueError
        Naming the first parameter outside its range (:data:`PARAMETERS`), before any work.

    Examples
    --------
    >>> round(QControl(quality_factor=400.0, gain=0.0075).effective_quality_factor, 6)
    100.0
    """

    PARAMETERS = PARAMETERS  # checked field by field in PointMassLever.__post_init__

    spring_constant: float = PARAMETERS["spring_constant"].default
    resonance_frequency: float = PARAMETERS["resonance_frequency"].default
    quality_factor: float = PARAMETERS["quality_factor"].default
    gain: float = PARAMETERS["gain"].default
    phase: float = PARAMETERS["phase"].default

    @property
    def mass(self) -> float:
        """Effective mass m = k / w0^2 in kg."""
        return self.oscillator.mass

    @property
    def stiffness_ratio(self) -> float:
        """k_eff / k = 1 - g cos(phi) (the in-phase part of the feedback)."""
        return 1.0 - self.gain * math.cos(self.phase)

    @property
    def damping_ratio(self) -> float:
        """1 / Q_lin = 1/Q + g sin(phi): the damping in units of m w0 (the quadrature part)."""
        return 1.0 / self.quality_factor + self.gain * math.sin(self.phase)

    @property
    def poles(self) -> tuple:
        """The closed loop's two poles in rad/s (complex): the roots of
        s^2 + w0 (1/Q + g sin(phi)) s + w0^2 (1 - g cos(phi)), the Laplace transform of the
        equation of motion above over m."""
        w0 = 2.0 * math.pi * self.resonance_frequency
        b, c = w0 * self.damping_ratio, w0 * w0 * self.stiffness_ratio
        disc = cmath.sqrt(b * b - 4.0 * c)
        return (0.5 * (-b + disc), 0.5 * (-b - disc))

    @property
    def stable(self) -> bool:
        """Whether the closed loop is stable: both :attr:`poles` in the open left half plane
        (for this second-order loop, k_eff > 0 and 1/Q + g sin(phi) > 0)."""
        return all(p.real < 0.0 for p in self.poles)

    @property
    def effective_stiffness(self) -> float:
        """k_eff = k (1 - g cos(phi)) in N/m."""
        return self.spring_constant * self.stiffness_ratio

    @property
    def effective_resonance_frequency(self) -> float:
        """f_eff = f0 sqrt(1 - g cos(phi)) in Hz (nan where k_eff <= 0)."""
        r = self.stiffness_ratio
        return self.resonance_frequency * math.sqrt(r) if r > 0.0 else math.nan

    @property
    def effective_quality_factor(self) -> float:
        """Q_eff = sqrt(1 - g cos(phi)) / (1/Q + g sin(phi)) (inf at, nan beyond, the limit)."""
        r, d = self.stiffness_ratio, self.damping_ratio
        if r <= 0.0 or d < 0.0:
            return math.nan
        return math.inf if d == 0.0 else math.sqrt(r) / d

    def feedback_force(self, deflection, velocity):
        """The controller's force g k [cos(phi) z - sin(phi) z' / w0] in N.

        Parameters
        ----------
        deflection : float or array_like
            Deflection z in m.
        velocity : float or array_like
            Deflection velocity z' in m/s.

        Returns
        -------
        float or ndarray
        """
        z = check_array("deflection", deflection, "m")
        v = check_array("velocity", velocity, "m/s")
        w0 = 2.0 * math.pi * self.resonance_frequency
        out = self.gain * self.spring_constant * (math.cos(self.phase) * z -
                                                  math.sin(self.phase) * v / w0)
        return out if out.ndim else float(out)

    def replace(self, **changes) -> "QControl":
        """A copy with some fields changed (validated again).

        Parameters
        ----------
        **changes
            New values of any of the fields (SI).

        Returns
        -------
        QControl
        """
        return QControl(**{**{f.name: getattr(self, f.name) for f in fields(self)}, **changes})


def _check(qc) -> QControl:
    if qc is None:
        return QControl()
    if not isinstance(qc, QControl):
        raise TypeError(f"qc must be a QControl, got {type(qc).__name__}")
    return qc


def stable_gains(quality_factor: float = PARAMETERS["quality_factor"].default,
                 phase: float = PARAMETERS["phase"].default) -> tuple[float, float]:
    """The open interval of gains g for which the closed loop is stable, at a phase phi.

    From 1 - g cos(phi) > 0 and 1/Q + g sin(phi) > 0 (the two coefficients of the closed loop's
    characteristic polynomial; a second-order polynomial is Hurwitz iff both are positive).

    Parameters
    ----------
    quality_factor : float
        Q of the lever without control, > 0.
    phase : float
        Phase lag phi in rad, in [-pi, pi].

    Returns
    -------
    (float, float)
        (g_low, g_high), either may be -inf or inf; at phi = 90 deg (-1/Q, inf).

    Examples
    --------
    >>> stable_gains(400.0, 0.5 * 3.141592653589793)[0]
    -0.0025
    """
    q = PARAMETERS["quality_factor"].check(quality_factor)
    phi = PARAMETERS["phase"].check(phase)
    low, high = -math.inf, math.inf
    c, s = math.cos(phi), math.sin(phi)
    if abs(c) > 1e-15:  # g cos(phi) < 1
        (high, low) = (min(high, 1.0 / c), low) if c > 0 else (high, max(low, 1.0 / c))
    if abs(s) > 1e-15:  # g sin(phi) > -1/Q
        (low, high) = (max(low, -1.0 / (q * s)), high) if s > 0 else (low, min(high, -1.0 /
                                                                               (q * s)))
    return float(low), float(high)


@dataclass(frozen=True)
class ClosedLoopResponse:
    """The closed loop's frequency response (SI units).

    Parameters
    ----------
    qc : QControl
        The lever and controller.
    frequency : ndarray
        Drive frequencies in Hz.
    amplitude : ndarray
        |Z / F| k: the amplitude per static deflection F / k (1 at low frequency without
        control); NaN when the loop is unstable (no steady state).
    phase : ndarray
        Phase lag of the deflection behind the drive in rad, in [0, pi]; NaN when unstable.
    steady : bool
        Whether a steady state exists: the closed loop is stable (:attr:`QControl.stable`, its
        poles in the left half plane). An unstable lever does not settle into a resonance curve
        at all: any disturbance grows at its own frequency until something not modelled here
        (the sample, the drive's limits) stops it.
    """

    qc: QControl
    frequency: np.ndarray
    amplitude: np.ndarray
    phase: np.ndarray
    steady: bool = True


def closed_loop_response(frequency, qc: QControl | None = None) -> ClosedLoopResponse:
    """Amplitude and phase of the driven lever under Q control (the closed form above).

    Parameters
    ----------
    frequency : float or array_like
        Drive frequencies in Hz, >= 0, at most :data:`MAX_POINTS`.
    qc : QControl, optional
        Lever and controller (default :class:`QControl` ()).

    Returns
    -------
    ClosedLoopResponse
        The steady state of a stable loop; for an unstable one (:attr:`QControl.stable`
        false) ``steady`` is False and the amplitude and phase are NaN: the closed form's
        |H(i w)| is then no response the lever ever reaches.

    Raises
    ------
    ValueError
        On negative or too many frequencies.
    """
    qc = _check(qc)
    f = np.atleast_1d(check_array("frequency", frequency, "Hz", low=0.0, min_size=1,
                                  max_size=MAX_POINTS))
    if not qc.stable:
        nan = np.full(f.shape, np.nan)
        return ClosedLoopResponse(qc, f, nan, nan.copy(), steady=False)
    w = f / qc.resonance_frequency
    h = 1.0 / (qc.stiffness_ratio - w * w + 1j * w * qc.damping_ratio)
    return ClosedLoopResponse(qc, f, np.abs(h), -np.angle(h))


@dataclass(frozen=True)
class RingDown:
    """A free decay of the controlled lever (SI units).

    Parameters
    ----------
    qc : QControl
        The lever and controller.
    time : ndarray
        Times in s.
    deflection : ndarray
        Deflection z in m at those times.
    """

    qc: QControl
    time: np.ndarray
    deflection: np.ndarray


def ring_down(time, qc: QControl | None = None, *, amplitude: float = 1e-9) -> RingDown:
    """The free decay from z(0) = A, z'(0) = 0 of the controlled lever (closed form).

    Parameters
    ----------
    time : float or array_like
        Times in s, >= 0, at most :data:`MAX_POINTS`.
    qc : QControl, optional
        Lever and controller (default :class:`QControl` ()); an unstable loop grows.
    amplitude : float
        Initial deflection A in m, > 0 (at most 1 m).

    Returns
    -------
    RingDown

    Raises
    ------
    ValueError
        On negative or too many times or a bad amplitude.
    """
    qc = _check(qc)
    t = np.atleast_1d(check_array("time", time, "s", low=0.0, min_size=1, max_size=MAX_POINTS))
    a = check_range("amplitude", amplitude, 0.0, 1.0, "m", low_inclusive=False)
    w0 = 2.0 * math.pi * qc.resonance_frequency
    b, c = w0 * qc.damping_ratio, w0 * w0 * qc.stiffness_ratio
    disc = cmath.sqrt(b * b - 4.0 * c)
    if abs(disc) < 1e-9 * w0:  # a double root: the critically damped limit
        lam = -0.5 * b
        z = a * (1.0 - lam * t) * np.exp(lam * t)
    else:
        l1, l2 = 0.5 * (-b + disc), 0.5 * (-b - disc)
        z = (a * (l2 * np.exp(l1 * t) - l1 * np.exp(l2 * t)) / (l2 - l1)).real
    return RingDown(qc, t, z)


def quality_factor_from_ringdown(time, deflection, *, skip: int = 1) -> float:
    """Q of a decaying oscillation from its successive maxima (logarithmic decrement).

    With the decrement delta = ln(A_n / A_{n+1}) per period averaged by a straight-line fit of
    ln(A_n) over n, the damping ratio is zeta = delta / sqrt(4 pi^2 + delta^2) and
    Q = 1 / (2 zeta) (exact for a linear damped oscillator). Each maximum is refined by a
    parabola through its three samples.

    Parameters
    ----------
    time : array_like
        Evenly spaced times in s (at least 8 samples a period are advised).
    deflection : array_like
        The oscillation in m (about zero), same length.
    skip : int
        Maxima to skip at the start (the transient of a release), 0 to 1000.

    Returns
    -------
    float
        Q.

    Raises
    ------
    ValueError
        On arrays of different shapes or fewer than 3 samples, or fewer than 3 maxima left
        after ``skip``.
    """
    t = check_array("time", time, "s")
    z = check_array("deflection", deflection, "m")
    if t.ndim != 1 or t.shape != z.shape or t.size < 3:
        raise ValueError(f"time and deflection must be 1-D arrays of the same length >= 3, got "
                         f"shapes {t.shape} and {z.shape}")
    skip = check_integer("skip", skip, 0, 1000)
    i = np.flatnonzero((z[1:-1] > z[:-2]) & (z[1:-1] >= z[2:]) & (z[1:-1] > 0.0)) + 1
    if i.size - skip < 3:
        raise ValueError(f"skip must leave at least 3 maxima of the deflection, got skip = "
                         f"{skip} of the {i.size} maxima found")
    i = i[skip:]
    y0, y1, y2 = z[i - 1], z[i], z[i + 1]
    den = y0 - 2.0 * y1 + y2
    shift = np.where(den != 0.0, 0.5 * (y0 - y2) / np.where(den != 0.0, den, 1.0), 0.0)
    peaks = y1 - 0.25 * (y0 - y2) * shift
    delta = -np.polyfit(np.arange(peaks.size), np.log(peaks), 1)[0]
    if delta <= 0.0:
        return math.inf
    zeta = delta / math.sqrt(4.0 * math.pi ** 2 + delta * delta)
    return 0.5 / zeta


def fit_ring_down(time, deflection) -> tuple[float, float]:
    """Q and natural frequency of a measured free decay, by a least-squares damped cosine.

    Fits z(t) = A e^{-sigma t} cos(w_d t + p) + c (scipy's ``curve_fit``, started from the
    strongest FFT line and Q = 5), then w_n = sqrt(sigma^2 + w_d^2), Q = w_n / (2 sigma): valid
    for any underdamped decay (Q > 1/2), also with few periods, where counting maxima
    (:func:`quality_factor_from_ringdown`) fails.

    Parameters
    ----------
    time : array_like
        Times in s from the release, evenly spaced, at least 8 samples.
    deflection : array_like
        The decay in m (any offset), same length.

    Returns
    -------
    (float, float)
        Q and the natural frequency f_n = w_n / (2 pi) in Hz.

    Raises
    ------
    ValueError
        On bad arrays, or if the fit does not converge (no decaying oscillation).
    """
    from scipy.optimize import curve_fit
    t = check_array("time", time, "s")
    z = check_array("deflection", deflection, "m")
    if t.ndim != 1 or t.shape != z.shape or t.size < 8:
        raise ValueError(f"time and deflection must be 1-D arrays of the same length >= 8, got "
                         f"shapes {t.shape} and {z.shape}")
    if not np.ptp(z) > 0:
        raise ValueError("the deflection does not move: no oscillation to fit")
    t = t - t[0]
    dt = float(np.mean(np.diff(t)))
    spectrum = np.abs(np.fft.rfft(z - z.mean()))
    k = int(np.argmax(spectrum[1:])) + 1
    w = 2.0 * math.pi * k / (t.size * dt)

    def model(tt, a, sigma, wd, p, c):
        return a * np.exp(-sigma * tt) * np.cos(wd * tt + p) + c

    try:
        popt, _ = curve_fit(model, t, z, p0=[z[0] - z[-1], w / 10.0, w, 0.0, z[-1]],
                            maxfev=20_000)
    except RuntimeError as exc:
        raise ValueError(f"no decaying oscillation found in the data ({exc})") from None
    _, sigma, wd, _, _ = popt
    wn = math.hypot(sigma, wd)
    if sigma <= 0:
        raise ValueError("the oscillation does not decay (sigma <= 0): unstable or driven")
    return wn / (2.0 * abs(sigma)), wn / (2.0 * math.pi)
