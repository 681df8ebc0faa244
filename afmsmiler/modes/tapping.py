"""Amplitude-modulation (tapping) AFM: a driven cantilever tapping a sample, two solvers.

The cantilever is a point mass m = k / w0^2 on a spring k with quality factor Q (module (a)'s
first flexural mode), its rest position a distance z_c above the sample, driven at the angular
frequency w = 2 pi f by the force F0 cos(w t) that gives the free amplitude A0::

    m z'' + (m w0 / Q) z' + k z = F0 cos(w t) + F_ts(z_c + z, z'),
    F0 = k A0 sqrt((1 - W^2)^2 + (W / Q)^2),     W = w / w0

with the tip-sample force F_ts of :mod:`afmsmiler.modes._forces` (van der Waals, DMT contact,
optional sample damping; Garcia and Perez, Surf. Sci. Rep. 47, 197 (2002)).

**Reference: time integration** (:func:`integrate`). scipy's ``solve_ivp`` (DOP853, relative
tolerance 1e-9, absolute 1e-11 A0) integrates the equation in the dimensionless time w0 t from a
chosen start (the top of a harmonic motion of given amplitude and phase, so that the tip starts
out of contact on the branch the start lies on) in blocks of :data:`BLOCK_PERIODS` drive periods.
The amplitude A and phase lag phi of the first harmonic, z ~ A cos(w t - phi), are taken by
lock-in over the last whole period of each block (64 samples a period, an exact quadrature for a
periodic signal's first harmonic up to the 63rd harmonic). A transient decays as exp(-pi W n / Q),
so a change c between two successive blocks leaves at most c r / (1 - r) to come, r = exp(-pi W
BLOCK_PERIODS / Q); the transient is over when that estimate is below 1e-4 A0 in amplitude and
0.01 deg in phase (far below the 1 % and 2 deg the comparisons need), at most :data:`MAX_PERIODS`
periods. The result is then the lock-in over :data:`LOCKIN_PERIODS` whole periods.

**Fast steady state: first-harmonic balance** (:func:`amplitude_curve`). With z = A cos(theta),
theta = w t - phi, projecting the equation on cos(theta) and sin(theta) over one period (the
virial and energy-balance equations of San Paulo and Garcia, Phys. Rev. B 64, 193411 (2001);
Lee and Jhe, Phys. Rev. Lett. 97, 036104 (2006) in the same form)::

    F0 cos(phi) = k (1 - W^2) A - I_c(z_c, A),     I_c = (1/pi) int_0^2pi F_ts cos(theta) d theta
    F0 sin(phi) = (k W / Q) A + I_s(z_c, A),       I_s = (1/pi) int_0^2pi F_ts sin(theta) d theta

so the amplitude solves g(A) = |(k (1 - W^2) A - I_c, (k W / Q) A + I_s)| - F0 = 0. I_c > 0 is
a net attraction (phi above the free phase), I_c < 0 a net repulsion. Where two stable roots
coexist, the lower is the attractive (L) branch and the higher the repulsive (H) one (whose net
force turns attractive at its far end); a slow approach or retraction follows its branch until
it ends and jumps there (:meth:`AmplitudeCurve.sweep`). The names say the sign of the net force
over a cycle, not whether the tip touches: the tip touches where its closest distance z_c - A
falls below a0 (:meth:`TappingLever.indentation`), on the whole repulsive branch and, at the
defaults, on the attractive branch too near its end (at A0 = 12 nm and z_c between about 9.5 and
11.7 nm it dips up to 0.4 nm into the sample while the attraction still wins). Since I_s >= 0
(damping only takes energy), every root lies in (0, F0 Q / (k W)] (= A0 at resonance). Each I
is evaluated in closed form without contact (I_c = (H R / 3) A / (z_c^2 - A^2)^(3/2)) and by Gauss-Legendre quadrature over
the two parts of the period with contact (the contact part in the variable s, theta = theta_c +
(pi - theta_c) s^2, which makes the square-root edge smooth). All roots at every z_c are found at
once: g on a grid of :data:`AMPLITUDE_GRID` even steps up to A_max (and 11 geometric steps
from 1e-5 A_max up to the first), every sign change refined by the Illinois
method, all vectorised over z_c. A root is stable where g rises through zero (dg/dA > 0: the
slow flow of the averaged equations pushes a slightly larger amplitude back down; the middle of
three roots is the saddle; Nayfeh and Mook, *Nonlinear Oscillations* (1979)). Two roots
closer than one grid step (at the very ends of a coexistence region) can be missed; the region
then looks at most one grid step (A_max / AMPLITUDE_GRID) shorter in amplitude.

The energy the sample takes per cycle follows from the phase (energy balance: the drive's work
pi F0 A sin(phi) minus the lever's damping pi k W A^2 / Q; Cleveland et al., Appl. Phys. Lett. 72,
2613 (1998))::

    E_dis = pi F0 A sin(phi) - pi k W A^2 / Q = (pi k A^2 / Q) [(A0 / A) sin(phi) - W]   (W = 1)

in the convention that the phase lag phi is 90 deg for the free lever at resonance and that
positive E_dis is energy lost to the sample. At a root the balance makes it pi A I_s, the
difference of two nearly equal terms: where the sample takes nothing (out of contact, or no
viscosity) the formula leaves round-off, some 1e-11 zJ of either sign. Its accuracy is bounded
per root (``AmplitudeCurve.dissipated_energy_error``): the root's residual g(A) leaves
pi A S |g| / F0 (sin(phi) = S / (F0 + g)), and the rounding at most
:data:`DISSIPATION_ROUNDINGS` units of round-off eps of each term: of phi (a rounding of phi
moves F0 sin(phi) by F0 |cos(phi)| eps (|phi| + 1), which near phi = pi, where sin(phi) is
small, outweighs the term itself), of F0 sin(phi) and of k W A / Q. An E_dis within that bound
is zero within the model's accuracy and is returned as 0 (:func:`operating_point` interpolates
these values). The first-harmonic balance leaves out the static
deflection <F_ts> / k and the higher harmonics; for a stiff lever of high Q (k = 40 N/m, Q = 400,
the defaults) both move A by well under 1 % (the tests compare it with the time integration).

**Amplitude feedback with a finite bandwidth** (:func:`amplitude_feedback`, ``TappingMode(...,
feedback="pi")``). Averaging the equation of motion over a period with z = A cos(w t - phi)
(variation of parameters; Nayfeh and Mook (1979)) gives the slow flow of the amplitude and phase::

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
from dataclasses import dataclass, field, fields
from types import MappingProxyType

import numpy as np
from scipy.integrate import solve_ivp

from ..brownian import QUALITY_FACTOR
from ..contact.quantities import PARAMETERS as CONTACT
from ..contact.tips import reduced_modulus
from ..imaging.modes import Mode, ModeLine, ScanPlan
from ..parameters import Parameter, read_only
from ..validation import check_array, check_choice, check_instance, check_integer, check_range
from ._forces import FORCE_PARAMETERS, _force

__all__ = ["PARAMETERS", "TappingLever", "AmplitudeCurve", "SteadyState", "amplitude_curve",
           "integrate", "free_response", "setpoint_state", "TappingMode", "BRANCHES",
           "AMPLITUDE_GRID", "MAX_DISTANCES", "MAX_PERIODS", "BLOCK_PERIODS", "LOCKIN_PERIODS",
           "SETPOINT_GRID", "FEEDBACKS", "FEEDBACK_PARAMETERS", "FeedbackLine",
           "amplitude_feedback", "MAX_FEEDBACK_STEPS", "DISSIPATION_ROUNDINGS"]

#: The two branches of the amplitude-distance curve.
BRANCHES = ("attractive", "repulsive")
#: Amplitudes on which g(A) is sampled for its sign changes, per distance.
AMPLITUDE_GRID = 160
#: Most distances one :func:`amplitude_curve` call solves (10 000 take about a second).
MAX_DISTANCES = 10_000
#: Longest time integration in drive periods (bounded loop; the transient criterion stops first).
MAX_PERIODS = 20_000
#: Drive periods per block of the transient criterion, and periods of the final lock-in.
BLOCK_PERIODS = 10
LOCKIN_PERIODS = 10
#: Rounded operations in E_dis = pi A (F0 sin(phi) - k W A / Q) from the balance's (P, S): P
#: and S (1 each, as they enter atan2), atan2 (2 ulp), sin (1), F0 sin (1), k W A / Q (3, one
#: counted with the difference); pi A outside scales both terms alike. Each contributes at most
#: one unit of round-off (eps) of the quantity it rounds.
DISSIPATION_ROUNDINGS = 8

#: Samples per period of the lock-in.
_SAMPLES = 64
# Gauss-Legendre nodes on the free and the contact part of a half period
_FREE_NODES, _CONTACT_NODES = 32, 16
_X_FREE, _W_FREE = np.polynomial.legendre.leggauss(_FREE_NODES)
_X_CONTACT, _W_CONTACT = np.polynomial.legendre.leggauss(_CONTACT_NODES)
_ILLINOIS_STEPS = 40
# the amplitude grid as a fraction of the largest amplitude: AMPLITUDE_GRID even steps, below the
# first of them a geometric run down to 1e-5 (the small amplitudes of a tip held near the sample)
_GRID = np.concatenate((np.geomspace(1e-5, 1.0 / AMPLITUDE_GRID, 12)[:-1],
                        np.arange(1, AMPLITUDE_GRID + 1) / AMPLITUDE_GRID))
# transient criterion: estimated remaining error in amplitude (fraction of A0) and phase (deg)
_AMPLITUDE_TOL, _PHASE_TOL = 1e-4, 1e-2

#: The user-settable quantities of the tapping model (SI), with :data:`FORCE_PARAMETERS`: a
#: tapping lever (k = 40 N/m, f0 = 300 kHz, Q = 400 in air) at A0 = 10 nm, driven at resonance.
PARAMETERS = read_only({**{p.name: p for p in (
    CONTACT["spring_constant"].with_(default=40.0, slider_low=0.5, slider_high=100.0),
    Parameter(name="resonance_frequency", unit="Hz", display_unit="kHz", default=300e3,
              low=100.0, high=1e8, slider_low=10e3, slider_high=2e6, log=True,
              label="resonance frequency f0"),
    QUALITY_FACTOR.with_(default=400.0, low=0.0, low_inclusive=False, slider_low=1.0,
                         slider_high=2000.0),
    Parameter(name="frequency_ratio", unit="", default=1.0, low=0.5, high=1.5,
              slider_low=0.98, slider_high=1.02, label="drive frequency / f0"),
    Parameter(name="free_amplitude", unit="m", display_unit="nm", default=10e-9, low=0.0,
              high=1e-6, low_inclusive=False, slider_low=1e-9, slider_high=100e-9,
              label="free amplitude A0"),
    Parameter(name="distance", unit="m", display_unit="nm", default=8e-9, low=0.0, high=1e-5,
              low_inclusive=False, slider_low=0.2e-9, slider_high=30e-9,
              label="rest tip-sample distance z_c"),
    Parameter(name="setpoint_ratio", unit="", default=0.8, low=0.0, high=1.0,
              low_inclusive=False, high_inclusive=False, slider_low=0.05, slider_high=0.99,
              label="setpoint A_sp / A0"),
)}, **FORCE_PARAMETERS})


@dataclass(frozen=True)
class TappingLever:
    """A driven lever and a sample: every quantity of the tapping model, validated (SI units).

    Parameters
    ----------
    spring_constant : float
        Spring constant k in N/m.
    resonance_frequency : float
        Free resonance frequency f0 in Hz.
    quality_factor : float
        Quality factor Q, > 0.
    frequency_ratio : float
        Drive frequency over f0, W = w / w0, in [0.5, 1.5] (a drive near resonance).
    free_amplitude : float
        Free amplitude A0 in m (the drive force F0 is the one that gives it far from the sample).
    radius : float
        Tip radius R in m.
    hamaker_constant : float
        Hamaker constant H in J.
    youngs_modulus : float
        Young's modulus E of the sample in Pa (rigid tip).
    poisson_ratio : float
        Poisson's ratio nu of the sample.
    intermolecular_distance : float
        Intermolecular distance a0 in m.
    sample_viscosity : float
        Sample viscosity eta in Pa s (0: no dissipation in the sample).

    Raises
    ------
    ValueError
        Naming the first parameter outside its range (:data:`PARAMETERS`), before any work.

    Examples
    --------
    >>> lever = TappingLever()
    >>> round(lever.drive_force * 1e9, 3)  # F0 = k A0 / Q at resonance, in nN
    1.0
    """

    spring_constant: float = PARAMETERS["spring_constant"].default
    resonance_frequency: float = PARAMETERS["resonance_frequency"].default
    quality_factor: float = PARAMETERS["quality_factor"].default
    frequency_ratio: float = PARAMETERS["frequency_ratio"].default
    free_amplitude: float = PARAMETERS["free_amplitude"].default
    radius: float = PARAMETERS["radius"].default
    hamaker_constant: float = PARAMETERS["hamaker_constant"].default
    youngs_modulus: float = PARAMETERS["youngs_modulus"].default
    poisson_ratio: float = PARAMETERS["poisson_ratio"].default
    intermolecular_distance: float = PARAMETERS["intermolecular_distance"].default
    sample_viscosity: float = PARAMETERS["sample_viscosity"].default

    def __post_init__(self):
        for f in fields(self):
            object.__setattr__(self, f.name, PARAMETERS[f.name].check(getattr(self, f.name)))

    @property
    def reduced_modulus(self) -> float:
        """E* = E / (1 - nu^2) in Pa (module (d), rigid tip)."""
        return reduced_modulus(self.youngs_modulus, self.poisson_ratio)

    @property
    def drive_force(self) -> float:
        """Drive amplitude F0 = k A0 sqrt((1 - W^2)^2 + (W / Q)^2) in N."""
        w, q = self.frequency_ratio, self.quality_factor
        return self.spring_constant * self.free_amplitude * math.hypot(1.0 - w * w, w / q)

    @property
    def free_phase(self) -> float:
        """Phase lag of the free lever, atan2(W / Q, 1 - W^2), in rad (pi / 2 at resonance)."""
        w = self.frequency_ratio
        return math.atan2(w / self.quality_factor, 1.0 - w * w)

    @property
    def time_constant(self) -> float:
        """Amplitude time constant tau = 2 Q / w0 in s (the slow flow's decay, module notes)."""
        return 2.0 * self.quality_factor / (2.0 * math.pi * self.resonance_frequency)

    @property
    def max_amplitude(self) -> float:
        """Bound F0 Q / (k W) in m on every steady amplitude (the sample only takes energy)."""
        return self.drive_force * self.quality_factor / (self.spring_constant *
                                                         self.frequency_ratio)

    def force(self, distance, velocity=0.0):
        """Tip-sample force F_ts(d, v) in N (see :func:`~afmsmiler.modes.tip_sample_force`).

        Parameters
        ----------
        distance : float or array_like
            Tip-sample distance d in m.
        velocity : float or array_like
            Tip velocity in m/s, positive away from the sample.

        Returns
        -------
        float or ndarray
        """
        d = check_array("distance", distance, "m", low=-1e-6)
        v = check_array("velocity", velocity, "m/s")
        out = _force(d, v, self.radius, self.hamaker_constant, self.reduced_modulus,
                     self.intermolecular_distance, self.sample_viscosity)
        return out if out.ndim else float(out)

    def indentation(self, distance, amplitude):
        """Deepest indentation a0 - (z_c - A) in m of the motion z_c + A cos(theta).

        The tip touches the sample where the tip-sample distance d = z_c + z falls below a0
        (the force law's contact, :mod:`afmsmiler.modes._forces`); the first harmonic's closest
        distance is z_c - A, so the tip touches once per cycle exactly when this is > 0, and it
        is then how far it presses into the sample. A negative value is the gap (a0 less the
        closest distance) by which it stays clear. The static deflection and the higher
        harmonics the first-harmonic balance leaves out shift the closest distance by far less
        than a0 for the stiff lever of the defaults (the tests compare it with the time
        integration, where the sample's damping takes energy only in contact).

        Parameters
        ----------
        distance : float or array_like
            Rest tip-sample distance z_c in m, in (0, 1e-5].
        amplitude : float or array_like
            Amplitude A of the first harmonic in m, in [0, 1e-6].

        Returns
        -------
        float or ndarray
            a0 - (z_c - A) in m (> 0: the tip touches the sample, this deep).

        Raises
        ------
        ValueError
            Naming ``distance`` or ``amplitude`` out of range, or both when their shapes do not
            broadcast together.

        Examples
        --------
        >>> lever = TappingLever()
        >>> round(lever.indentation(8e-9, 9e-9) * 1e9, 3)  # z_c - A = -1 nm: 1.165 nm deep
        1.165
        """
        zp, ap = PARAMETERS["distance"], PARAMETERS["free_amplitude"]
        z = check_array("distance", distance, "m", low=zp.low, high=zp.high,
                        low_inclusive=False)
        a = check_array("amplitude", amplitude, "m", low=0.0, high=ap.high)
        try:
            np.broadcast_shapes(z.shape, a.shape)
        except ValueError:
            raise ValueError(f"distance and amplitude must broadcast together, got shapes "
                             f"{z.shape} and {a.shape}") from None
        out = self.intermolecular_distance - (z - a)
        return out if out.ndim else float(out)

    def dissipated_energy(self, amplitude, phase):
        """E_dis = pi F0 A sin(phi) - pi k W A^2 / Q in J from amplitude and phase lag.

        Parameters
        ----------
        amplitude : float or array_like
            Amplitude A of the first harmonic in m, in [0, 1e-6] (the free amplitude's range).
        phase : float or array_like
            Phase lag phi of the tip behind the drive in rad (pi / 2: free, at resonance).

        Returns
        -------
        float or ndarray
            Energy in J the sample takes per cycle ((pi k A^2 / Q)[(A0 / A) sin(phi) - W]).
        """
        a = check_array("amplitude", amplitude, "m", low=0.0,
                        high=PARAMETERS["free_amplitude"].high)
        phi = check_array("phase", phase, "rad", low=-2 * math.pi, high=2 * math.pi)
        out = math.pi * a * (self.drive_force * np.sin(phi) - self.spring_constant *
                             self.frequency_ratio * a / self.quality_factor)
        return out if out.ndim else float(out)


def free_response(lever: TappingLever | None = None) -> tuple[float, float]:
    """Amplitude and phase lag of the driven harmonic oscillator far from the sample.

    Parameters
    ----------
    lever : TappingLever, optional
        The lever (default: :class:`TappingLever` ()).

    Returns
    -------
    (float, float)
        A = F0 / (k sqrt((1 - W^2)^2 + (W / Q)^2)) in m (= A0 by construction) and
        phi = atan2(W / Q, 1 - W^2) in rad.
    """
    lever = TappingLever() if lever is None else _check_lever(lever)
    w, q = lever.frequency_ratio, lever.quality_factor
    return (lever.drive_force / (lever.spring_constant * math.hypot(1.0 - w * w, w / q)),
            lever.free_phase)


def _check_lever(lever):
    if not isinstance(lever, TappingLever):
        raise TypeError(f"lever must be a TappingLever, got {type(lever).__name__}")
    return lever


# -- the first-harmonic integrals -----------------------------------------------------------------
def _integrals(lever: TappingLever, zc: np.ndarray, a: np.ndarray):
    """I_c and I_s in N for arrays of distances and amplitudes of one shape (a > 0)."""
    hr = lever.hamaker_constant * lever.radius
    a0 = lever.intermolecular_distance
    i_c = np.empty_like(a)
    i_s = np.zeros_like(a)
    u = (a0 - zc) / a  # cos(theta_c): contact where cos(theta) < u
    free = u <= -1.0
    if free.any():
        z, b = zc[free], a[free]
        i_c[free] = hr / 3.0 * b / (z * z - b * b) ** 1.5
    touch = ~free
    if touch.any():
        z, b = zc[touch, None], a[touch, None]
        tc = np.arccos(np.clip(u[touch], -1.0, 1.0))[:, None]
        # free part, theta in [0, theta_c] (empty when the tip never leaves the sample)
        th = 0.5 * tc * (_X_FREE + 1.0)
        c = np.cos(th)
        d = z + b * c
        free_part = np.sum(_W_FREE * (-hr / 6.0) / (d * d) * c, axis=1) * 0.5 * tc[:, 0]
        # contact part, theta = theta_c + (pi - theta_c) s^2, s in [0, 1]
        s = 0.5 * (_X_CONTACT + 1.0)
        span = math.pi - tc
        th = tc + span * s * s
        c = np.cos(th)
        delta = np.maximum(a0 - z - b * c, 0.0)
        jac = _W_CONTACT * span * s  # 0.5 (GL on [0, 1]) * 2 s span
        sq = np.sqrt(lever.radius * delta)
        elastic = 4.0 / 3.0 * lever.reduced_modulus * sq * delta
        contact_part = (-hr / (6.0 * a0 * a0) * (-np.sin(tc[:, 0]) + 0.0)
                        + np.sum(jac * elastic * c, axis=1))
        # the constant adhesion integrates exactly: int_{theta_c}^{pi} cos = -sin(theta_c)
        i_c[touch] = 2.0 / math.pi * (free_part + contact_part)
        if lever.sample_viscosity > 0.0:
            w = 2.0 * math.pi * lever.resonance_frequency * lever.frequency_ratio
            gamma = lever.sample_viscosity * sq
            i_s[touch] = 2.0 / math.pi * w * b[:, 0] * np.sum(jac * gamma * np.sin(th) ** 2,
                                                              axis=1)
    return i_c, i_s


def _balance(lever: TappingLever, zc, a):
    """(g, P, S): g = |(P, S)| - F0 with P = F0 cos(phi), S = F0 sin(phi) of amplitude a."""
    i_c, i_s = _integrals(lever, zc, a)
    k, w, q = lever.spring_constant, lever.frequency_ratio, lever.quality_factor
    p = k * (1.0 - w * w) * a - i_c
    s = k * w / q * a + i_s
    return np.hypot(p, s) - lever.drive_force, p, s


@dataclass(frozen=True)
class AmplitudeCurve:
    """Every steady state of the first-harmonic balance at each distance (SI units).

    Arrays are (distances, roots), roots in increasing amplitude, NaN where a distance has fewer
    roots than the most any distance has.

    Parameters
    ----------
    lever : TappingLever
        The lever and sample.
    distance : ndarray, shape (n,)
        Rest tip-sample distances z_c in m.
    amplitude : ndarray, shape (n, r)
        Amplitudes A in m.
    phase : ndarray, shape (n, r)
        Phase lags phi in rad (pi / 2 for the free lever at resonance).
    stable : ndarray of bool, shape (n, r)
        Whether each root is stable.
    attractive : ndarray of bool, shape (n, r)
        Whether the net interaction over a cycle is attractive (I_c > 0, phase lag above the
        free one; else repulsive).
    repulsive_branch : ndarray of bool, shape (n, r)
        Whether a stable root lies on the high-amplitude (repulsive, H) branch rather than the
        low (attractive, L) one: the higher of two coexisting stable roots, or a lone stable
        root with a net repulsion. (At the far end of the H branch its net force turns
        attractive while it is still the higher root.)
    dissipated_energy : ndarray, shape (n, r)
        E_dis in J per cycle from the phase; 0 where it is zero within
        ``dissipated_energy_error``.
    dissipated_energy_error : ndarray, shape (n, r)
        The bound in J of E_dis's error at each root: the root's residual and the formula's
        round-off (module notes); NaN where there is no root.
    """

    lever: TappingLever
    distance: np.ndarray
    amplitude: np.ndarray
    phase: np.ndarray
    stable: np.ndarray
    attractive: np.ndarray
    repulsive_branch: np.ndarray
    dissipated_energy: np.ndarray
    dissipated_energy_error: np.ndarray

    def branch(self, name: str) -> tuple[np.ndarray, np.ndarray]:
        """Amplitude and phase of the stable root on one branch at each distance (NaN if none).

        Parameters
        ----------
        name : str
            ``"attractive"`` (low) or ``"repulsive"`` (high).

        Returns
        -------
        (ndarray, ndarray)
            A in m and phi in rad, shape (n,); where a branch has two stable roots (rare), the
            one of largest amplitude.
        """
        check_choice("name", name, BRANCHES)
        mask = self.stable & (~self.repulsive_branch if name == "attractive"
                              else self.repulsive_branch)
        amp = np.where(mask, self.amplitude, -np.inf)
        j = np.argmax(amp, axis=1)
        rows = np.arange(self.distance.size)
        has = mask.any(axis=1)
        return (np.where(has, self.amplitude[rows, j], np.nan),
                np.where(has, self.phase[rows, j], np.nan))

    @property
    def indentation(self) -> np.ndarray:
        """Deepest indentation a0 - (z_c - A) in m of each root, shaped like ``amplitude``.

        Positive where that state's tip touches the sample once per cycle
        (:meth:`TappingLever.indentation`), NaN where there is no root.
        """
        return self.lever.intermolecular_distance - (self.distance[:, None] - self.amplitude)

    @property
    def coexist(self) -> np.ndarray:
        """Distances where both branches have a stable root, as a bool mask (n,)."""
        a, _ = self.branch("attractive")
        r, _ = self.branch("repulsive")
        return np.isfinite(a) & np.isfinite(r)

    def sweep(self, direction: str = "approach"):
        """The state a slow approach (or retraction) follows, with its jump.

        The tip stays on the branch it is on (the lower or the higher of two coexisting stable
        roots) while that branch exists; where it ends (two stable roots become one, nearer the
        other branch's amplitude) it jumps. The approach starts far away, on the low branch;
        the retraction starts close in, on the highest stable root.

        Parameters
        ----------
        direction : str
            ``"approach"`` (decreasing z_c) or ``"retract"`` (increasing z_c).

        Returns
        -------
        (ndarray, ndarray, list of float)
            Amplitude in m and phase lag in rad at each distance (in this curve's order), and
            the distances in m at which the tip jumped between branches.
        """
        check_choice("direction", direction, ("approach", "retract"))
        order = np.argsort(self.distance)
        order = order[::-1] if direction == "approach" else order
        n = self.distance.size
        amp, phs = np.full(n, np.nan), np.full(n, np.nan)
        jumps, prev, side = [], None, None  # side: 0 lowest, -1 highest of the stable roots
        for i in order:  # bounded: one pass over the distances
            js = np.flatnonzero(self.stable[i] & np.isfinite(self.amplitude[i]))
            if js.size == 0:
                continue
            js = js[np.argsort(self.amplitude[i, js])]
            here = self.amplitude[i, js]
            if prev is None:  # far away: the one (low) root; close in: the highest
                pick = 0 if direction == "approach" else js.size - 1
            elif js.size >= 2 and prev.size >= 2:
                pick = 0 if side == 0 else js.size - 1  # stay on the branch
            else:  # entering or leaving a coexistence: follow the nearest root
                mine = prev[side]
                pick = int(np.argmin(np.abs(here - mine)))
                if prev.size >= 2 and js.size == 1 and \
                        np.argmin(np.abs(prev - here[0])) != (side % prev.size):
                    jumps.append(float(self.distance[i]))  # our branch ended
            side = 0 if pick == 0 else -1
            amp[i], phs[i] = here[pick], self.phase[i, js[pick]]
            prev = here
        return amp, phs, jumps


def amplitude_curve(distances, lever: TappingLever | None = None) -> AmplitudeCurve:
    """All steady states (both branches, with stability) of the tapping lever at each distance.

    Parameters
    ----------
    distances : array_like
        Rest tip-sample distances z_c in m, each in (0, 1e-5], at most :data:`MAX_DISTANCES`.
    lever : TappingLever, optional
        Lever and sample (default :class:`TappingLever` ()).

    Returns
    -------
    AmplitudeCurve

    Raises
    ------
    ValueError
        On distances out of range or too many of them.
    TypeError
        If ``lever`` is not a :class:`TappingLever`.

    Examples
    --------
    >>> curve = amplitude_curve([30e-9, 5e-9])
    >>> round(float(curve.branch("attractive")[0][0]) * 1e9, 3)  # far: the free amplitude
    10.0
    """
    lever = TappingLever() if lever is None else _check_lever(lever)
    zp = PARAMETERS["distance"]
    zc = check_array("distances", distances, "m", low=zp.low, high=zp.high,
                     low_inclusive=False, max_size=MAX_DISTANCES).ravel()
    n = zc.size
    a_max = lever.max_amplitude * (1.0 + 1e-9)
    grid = a_max * _GRID
    m = grid.size
    zz = np.repeat(zc, m)
    aa = np.tile(grid, n)
    g = _balance(lever, zz, aa)[0].reshape(n, m)
    # sign changes of g between neighbouring grid amplitudes (an exact zero counts once)
    lo_neg = g[:, :-1] < 0
    change = lo_neg != (g[:, 1:] < 0)
    rows, cols = np.nonzero(change)
    lo, hi = grid[cols], grid[cols + 1]
    glo, ghi = g[rows, cols], g[rows, cols + 1]
    z = zc[rows]
    root = lo.copy()
    for _ in range(_ILLINOIS_STEPS):  # Illinois: regula falsi that halves a retained end's g
        new = hi - ghi * (hi - lo) / np.where(ghi != glo, ghi - glo, 1.0)
        gnew = _balance(lever, z, new)[0]
        keep = np.sign(gnew) == np.sign(ghi)  # hi is replaced; lo is retained once more
        lo, glo = np.where(keep, lo, hi), np.where(keep, 0.5 * glo, ghi)
        hi, ghi = new, gnew
        done = np.all(np.abs(new - root) <= 1e-13 * a_max)
        root = new
        if done:
            break
    residual, p, s = _balance(lever, z, root)
    i_c = lever.spring_constant * (1.0 - lever.frequency_ratio ** 2) * root - p
    rising = g[rows, cols] < 0
    counts = np.bincount(rows, minlength=n)
    r = max(int(counts.max()) if counts.size else 0, 1)
    slot = np.arange(rows.size) - np.concatenate(([0], np.cumsum(counts)[:-1]))[rows]
    shape = (n, r)
    amplitude, phase = np.full(shape, np.nan), np.full(shape, np.nan)
    stable, attractive = np.zeros(shape, bool), np.zeros(shape, bool)
    amplitude[rows, slot] = root
    phase[rows, slot] = np.arctan2(s, p)
    stable[rows, slot] = rising
    attractive[rows, slot] = i_c > 0
    # branch labels: where two stable roots coexist the higher is the repulsive (H) branch and
    # the lower the attractive (L) one, whatever the sign of the net force (which turns at the
    # far end of the H branch); a lone stable root is named by the sign of its net force
    high = stable & ~attractive
    two = stable.sum(axis=1) >= 2
    if two.any():
        top = np.argmax(np.where(stable, np.nan_to_num(amplitude, nan=-1.0), -1.0), axis=1)
        high[two] = False
        high[np.flatnonzero(two), top[two]] = True
    e_dis, e_err = np.full(shape, np.nan), np.full(shape, np.nan)
    phi = phase[rows, slot]
    drive = lever.drive_force * np.sin(phi)
    damping = lever.spring_constant * lever.frequency_ratio * root / lever.quality_factor
    e = math.pi * root * (drive - damping)
    # its accuracy (module notes): the root's residual, and the rounding of phi and the terms
    rounding = (lever.drive_force * np.abs(np.cos(phi)) * (np.abs(phi) + 1.0) + np.abs(drive) +
                np.abs(damping))
    err = math.pi * root * (np.abs(s) * np.abs(residual) / lever.drive_force +
                            DISSIPATION_ROUNDINGS * np.finfo(float).eps * rounding)
    e_dis[rows, slot] = np.where(np.abs(e) <= err, 0.0, e)
    e_err[rows, slot] = err
    return AmplitudeCurve(lever, zc, amplitude, phase, stable, attractive, high, e_dis, e_err)


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
        sol = solve_ivp(rhs, (tau, t_eval[-1]), y, method="DOP853", t_eval=t_eval,
                        rtol=1e-9, atol=1e-11)
        if not sol.success:  # pragma: no cover - DOP853 on a smooth bounded system
            raise RuntimeError(f"time integration failed: {sol.message}")
        return t_eval[-1], sol.y[:, -1], t_eval[:-1], sol.y[:, :-1]

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


#: Distances (as multiples of A0 from 0.01 A0 to 1.5 A0) on which :func:`setpoint_state` follows
#: the approach.
SETPOINT_GRID = 400


def setpoint_state(setpoint_ratio: float = PARAMETERS["setpoint_ratio"].default,
                   lever: TappingLever | None = None) -> tuple[float, float, float, bool]:
    """Where amplitude feedback holds the lever: the state of a slow approach at A = r A0.

    The approach (:meth:`AmplitudeCurve.sweep`, from far away, on the attractive branch until it
    ends) is followed on :data:`SETPOINT_GRID` distances from 1.5 A0 down to 0.01 A0, and the
    first distance at which the amplitude falls to r A0 is interpolated linearly.

    Parameters
    ----------
    setpoint_ratio : float
        Setpoint r = A_sp / A0, in (0, 1).
    lever : TappingLever, optional
        Lever and sample (default :class:`TappingLever` ()).

    Returns
    -------
    (float, float, float, bool)
        Rest distance z_c in m, phase lag in rad, E_dis in J per cycle there, and whether the
        state is on the attractive (low) branch.

    Raises
    ------
    ValueError
        If ``setpoint_ratio`` is outside (0, 1) (a setpoint at or above the free amplitude is
        never reached), or if the approach never gets down to it.
    """
    r = PARAMETERS["setpoint_ratio"].check(setpoint_ratio)
    lever = TappingLever() if lever is None else _check_lever(lever)
    z = lever.free_amplitude * np.linspace(1.5, 0.01, SETPOINT_GRID)
    return operating_point(amplitude_curve(z, lever), r)


def operating_point(curve: AmplitudeCurve,
                    setpoint_ratio: float) -> tuple[float, float, float, bool]:
    """The state amplitude feedback holds at ``setpoint_ratio``, read off ``curve``.

    Follow the slow approach (:meth:`AmplitudeCurve.sweep`) from the curve's farthest distance
    to the first distance at which the amplitude falls to r A0, and interpolate the distance,
    the phase and E_dis linearly between the two grid points around it. E_dis is the curve's
    own at the two roots (0 where zero within its accuracy), interpolated, not recomputed from
    the interpolated phase: it is very sensitive to the phase (pi F0 A cos(phi) per radian), and
    a phase interpolated to 1e-5 rad would invent some 0.1 zJ on a sample that dissipates
    nothing.
    :func:`setpoint_state` is this on A0 x linspace(1.5, 0.01, :data:`SETPOINT_GRID`).

    Parameters
    ----------
    curve : AmplitudeCurve
        An amplitude curve (:func:`amplitude_curve`) of the lever.
    setpoint_ratio : float
        r = A_sp / A0 in (0, 1).

    Returns
    -------
    (float, float, float, bool)
        Rest distance z_c in m, phase lag in rad, E_dis in J per cycle there, and whether the
        state is on the attractive (low) branch.

    Raises
    ------
    ValueError
        If ``setpoint_ratio`` is outside (0, 1), or if the approach never reaches it on the
        curve's distances.
    TypeError
        If ``curve`` is not an :class:`AmplitudeCurve`.
    """
    check_instance("curve", curve, AmplitudeCurve)
    r = PARAMETERS["setpoint_ratio"].check(setpoint_ratio)
    lever = curve.lever
    amp, phs, _ = curve.sweep("approach")
    order = np.argsort(curve.distance)[::-1]  # the sweep's order: the farthest distance first
    z, amp, phs = curve.distance[order], amp[order], phs[order]
    target = r * lever.free_amplitude
    below = np.flatnonzero(np.isfinite(amp) & (amp <= target))
    if below.size == 0 or below[0] == 0:
        raise ValueError(f"setpoint_ratio: the approach never reaches A = {r:g} A0 between "
                         f"z_c = {z[0]:g} and {z[-1]:g} m; choose a larger setpoint_ratio")
    i = below[0]
    f = (amp[i - 1] - target) / (amp[i - 1] - amp[i])
    zc = z[i - 1] + f * (z[i] - z[i - 1])
    phase = phs[i - 1] + f * (phs[i] - phs[i - 1])
    roots = [(order[k], int(np.nanargmin(np.abs(curve.amplitude[order[k]] - amp[k]))))
             for k in (i - 1, i)]  # the curve's roots the sweep took there
    e = [float(curve.dissipated_energy[r, j]) for r, j in roots]
    e_dis = e[0] + f * (e[1] - e[0])
    row, j = roots[1]
    return float(zc), float(phase), float(e_dis), not bool(curve.repulsive_branch[row, j])


# -- amplitude feedback with a finite bandwidth -------------------------------------------------
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


class TappingMode(Mode):
    """Amplitude-modulation imaging through module (f)'s scanner: height and phase channels.

    With ``feedback="ideal"`` (the default) an infinitely fast amplitude feedback holds the
    amplitude at the setpoint r A0: at every pixel the lever rests at the distance
    z_c(material) of :func:`setpoint_state` above the apex surface, with the phase lag and the
    dissipation of that state. The height channels are the apex surface plus
    z_c(material) - z_c(first material): the topography where the sample is the first material,
    plus the apparent step a change of material makes (a stiffer or less adhesive material lifts
    the lever). The phase channels show the materials' contrast, which dissipation in the
    sample makes (E_dis = (pi k A^2 / Q)[(A0 / A) sin(phi) - W]).

    With ``feedback="pi"`` the loop of :func:`amplitude_feedback` runs along the scan in time
    (trace, retrace, the step to the next line, each line continuing from the state the
    previous one left): the amplitude lags height changes with tau = 2 Q / w0 and a PI
    controller moves the positioner. Scanning faster than the loop can follow gives the known
    artefacts: the height lags at edges, the tip parachutes off a down step (the amplitude
    rises towards A0 and the error saturates), and the error channels (A - A_sp) show the
    edges. The height channel is the positioner's height minus the first material's setpoint
    distance; phase and dissipation are those of the lagging amplitude and phase.

    Parameters
    ----------
    levers : TappingLever or sequence of TappingLever
        The lever on each material (same lever, a different sample: modulus, viscosity, ...);
        at most 16 (with ``feedback="pi"``, one lever: module (f)'s levers differ only in the
        sample, and the loop's time constant is the lever's).
    setpoint_ratio : float
        Setpoint r = A_sp / A0, in (0, 1).
    material : callable, optional
        ``material(x, y)`` -> integer array (index into ``levers``) of the material at positions
        x, y in m on the sample (arrays of one shape); default: the first everywhere.
    feedback : str
        ``"ideal"`` or ``"pi"`` (:data:`FEEDBACKS`).
    amplitude_kp, amplitude_ki : float
        The PI gains (``feedback="pi"`` only; :data:`FEEDBACK_PARAMETERS`).

    Raises
    ------
    ValueError
        On a setpoint outside (0, 1), no lever, an unknown feedback or gains out of range,
        before any scan; with ``feedback="pi"``, a scan needing more than
        :data:`MAX_FEEDBACK_STEPS` steps (when the scan starts).
    TypeError
        If a lever is not a :class:`TappingLever` or ``material`` is not callable.
    """

    channels = ("height trace", "height retrace", "phase trace", "phase retrace",
                "dissipation trace")
    units = MappingProxyType({"phase trace": "rad", "phase retrace": "rad",
                              "dissipation trace": "J"})

    def __init__(self, levers, setpoint_ratio: float = PARAMETERS["setpoint_ratio"].default,
                 material=None, *, feedback: str = "ideal",
                 amplitude_kp: float = FEEDBACK_PARAMETERS["amplitude_kp"].default,
                 amplitude_ki: float = FEEDBACK_PARAMETERS["amplitude_ki"].default):
        if not isinstance(levers, TappingLever) and (isinstance(levers, (str, bytes))
                                                     or not hasattr(levers, "__iter__")):
            raise TypeError(f"levers must be a TappingLever or a sequence of them, got "
                            f"{type(levers).__name__}")
        levers = (levers,) if isinstance(levers, TappingLever) else tuple(levers)
        if not 1 <= len(levers) <= 16:
            raise ValueError(f"levers must hold 1 to 16 levers, got {len(levers)}")
        self.levers = tuple(check_instance("levers", lever, TappingLever) for lever in levers)
        self.setpoint_ratio = PARAMETERS["setpoint_ratio"].check(setpoint_ratio)
        if material is not None and not callable(material):
            raise TypeError(f"material must be a callable material(x, y), got "
                            f"{type(material).__name__}")
        self.material = material
        self.feedback = check_choice("feedback", feedback, FEEDBACKS)
        self.amplitude_kp = FEEDBACK_PARAMETERS["amplitude_kp"].check(amplitude_kp)
        self.amplitude_ki = FEEDBACK_PARAMETERS["amplitude_ki"].check(amplitude_ki)
        if self.feedback == "pi":
            taus = {lever.time_constant for lever in self.levers}
            if len(taus) != 1:
                raise ValueError(f"levers must share one quality factor and resonance "
                                 f"frequency with feedback='pi' (one lever, one time "
                                 f"constant), got time constants {sorted(taus)}")
            _check_gain(self.amplitude_ki, self.levers[0].time_constant)
            self.channels = TappingMode.channels + ("error trace", "error retrace")
        states = [setpoint_state(self.setpoint_ratio, lever) for lever in self.levers]
        #: Per material: rest distance z_c in m, phase lag in rad, E_dis in J.
        self.distance = np.array([s[0] for s in states])
        self.phase = np.array([s[1] for s in states])
        self.dissipation = np.array([s[2] for s in states])
        self._tables = None

    def _which(self, x, y):
        if self.material is None:
            return np.zeros(np.shape(x), dtype=int)
        m = np.asarray(self.material(x, y))
        if m.shape != np.shape(x) or m.dtype.kind not in "iu" or m.size and \
                (m.min() < 0 or m.max() >= len(self.levers)):
            raise ValueError(f"material(x, y) must give integers in [0, {len(self.levers) - 1}] "
                             f"shaped like x, got {m.dtype} {m.shape}")
        return m

    def start(self, plan: ScanPlan):
        """Check the scan's length for the PI loop and tabulate the approach (``"pi"`` only).

        Parameters
        ----------
        plan : afmsmiler.imaging.modes.ScanPlan
            The scan.

        Returns
        -------
        None

        Raises
        ------
        TypeError
            If ``plan`` is not a ScanPlan.
        ValueError
            With ``feedback="pi"``, if the scan needs more than :data:`MAX_FEEDBACK_STEPS`
            steps of the loop.
        """
        super().start(plan)
        if self.feedback == "pi":
            tau = self.levers[0].time_constant
            lines, n = plan.shape
            span = plan.t_retrace[-1, 0] - plan.t_trace[0, 0]
            steps = lines * (2 * n - 1) + int(math.ceil(span / (tau / _STEPS_PER_TAU)))
            if steps > MAX_FEEDBACK_STEPS:
                raise ValueError(f"scan_speed: this scan needs about {steps} steps of the "
                                 f"amplitude loop (tau / {_STEPS_PER_TAU} = "
                                 f"{tau / _STEPS_PER_TAU:g} s over {span:g} s), more than "
                                 f"{MAX_FEEDBACK_STEPS}: scan faster, fewer pixels, or use "
                                 f"feedback='ideal'")
            if self._tables is None:
                self._tables = [_approach_table(lever) for lever in self.levers]
        return None

    def line(self, plan: ScanPlan, row: int, state=None) -> ModeLine:
        """One line: height, phase and dissipation at each pixel of trace and retrace.

        Parameters
        ----------
        plan : afmsmiler.imaging.modes.ScanPlan
            The scan.
        row : int
            Line index.
        state : object
            ``"ideal"``: unused (nothing carries over). ``"pi"``: the loop's state at the end
            of the previous line (None before the first: settled at the setpoint).

        Returns
        -------
        afmsmiler.imaging.modes.ModeLine
        """
        row = self._row(plan, row)
        if self.feedback == "pi":
            return self._line_pi(plan, row, state)
        out = {}
        ref = self.distance[0]
        for name, heights, x, y in (("trace", plan.trace, plan.x_trace, plan.y_trace),
                                    ("retrace", plan.retrace, plan.x_retrace, plan.y_retrace)):
            m = self._which(x[row], y[row])
            out[f"height {name}"] = heights[row] + self.distance[m] - ref
            out[f"phase {name}"] = self.phase[m]
            if name == "trace":
                out["dissipation trace"] = self.dissipation[m]
        return ModeLine(out, None)

    def _line_pi(self, plan, row, state):
        if self._tables is None:
            self.start(plan)
        n = plan.shape[1]
        m_t = self._which(plan.x_trace[row], plan.y_trace[row])
        m_r = self._which(plan.x_retrace[row], plan.y_retrace[row])
        # the path in time: the trace, then the retrace from its second pixel (the first is the
        # trace's last, at the same time)
        r = np.concatenate((plan.trace[row], plan.retrace[row][::-1][1:]))
        t = np.concatenate((plan.t_trace[row], plan.t_retrace[row][::-1][1:]))
        m = np.concatenate((m_t, m_r[::-1][1:]))
        lever = self.levers[0]
        a_sp = self.setpoint_ratio * lever.free_amplitude
        big_z, amp, phi, new = _run_feedback(self._tables, r.tolist(), t.tolist(), m.tolist(),
                                             a_sp, self.amplitude_kp, self.amplitude_ki,
                                             lever, self.distance.tolist(), state)
        height = big_z - self.distance[0]
        e_dis = np.empty(n)
        for k in np.unique(m[:n]):  # at most 16 materials
            sel = m[:n] == k
            e_dis[sel] = self.levers[k].dissipated_energy(amp[:n][sel], phi[:n][sel])
        back = slice(n - 1, None)  # the retrace in increasing x: pixel n - 1 is the turn-around
        out = {"height trace": height[:n], "height retrace": height[back][::-1].copy(),
               "phase trace": phi[:n], "phase retrace": phi[back][::-1].copy(),
               "dissipation trace": e_dis,
               "error trace": amp[:n] - a_sp, "error retrace": (amp[back] - a_sp)[::-1].copy()}
        return ModeLine(out, new)
