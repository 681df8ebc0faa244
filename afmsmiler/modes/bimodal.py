"""Bimodal AFM: the first two flexural modes driven at their resonances, the second as a probe.

The lever is two point-mass oscillators, its first two flexural modes, whose deflections add up
at the tip, z = z_1 + z_2 (Rodriguez and Garcia, Appl. Phys. Lett. 84, 449 (2004); Garcia and
Proksch, "Nanomechanical mapping of soft matter by bimodal force microscopy", Eur. Polym. J. 49,
1897 (2013), Eq. 1)::

    (k_i / w_i^2) z_i'' + (k_i / (Q_i w_i)) z_i' + k_i z_i
        = F_1 cos(w_d1 t) + F_2 cos(w_d2 t) + F_ts(z_c + z_1 + z_2, z_1' + z_2'),   i = 1, 2

with the tip-sample force of :mod:`afmsmiler.modes._forces` (van der Waals, DMT, sample
damping), mode 1 driven at W w_1 (the tapping lever's drive) and mode 2 at its resonance w_2.

**The modes from module (a)'s beam** (:func:`modal_stiffness`,
:meth:`BimodalLever.from_cantilever`): w_n = (b_n L)^2 sqrt(E J / (rho w h)) / L^2, so
w_2 / w_1 = (b_2 L / b_1 L)^2 = 6.2669 for a rectangular clamped-free beam, and the stiffness of
mode n seen at the tip is its modal mass times w_n^2, k_n = w_n^2 rho w h int_0^L phi_n(x)^2 dx
with the mode shape phi_n normalised to 1 at the tip (Melcher, Hu and Raman, Appl. Phys. Lett.
91, 053101 (2007)). The integral is L / 4 for every
mode of a uniform beam, so k_2 / k_1 = (w_2 / w_1)^2 = 39.27.

**The free response** is linear: at each drive frequency w_dj the tip moves with the complex
amplitude F_j sum_i H_i(w_dj) / k_i, H_i(w) = 1 / (1 - (w / w_i)^2 + i (w / w_i) / Q_i) (both modes
answer both drives); F_j is the drive that gives the free amplitude A_0j there
(:meth:`BimodalLever.free_response`).

**Near the sample** (:func:`bimodal_response`) the motion is integrated with scipy's ``odeint``
(ODEPACK's LSODA, its steps in Fortran: five times faster than ``solve_ivp``'s DOP853 at the same
tolerances, the states agreeing to 2e-6) from the free motion, in blocks of :data:`BLOCK_PERIODS` periods of mode 1 (15 periods
of mode 1 are 94.003 periods of mode 2: both tones nearly whole), until the amplitudes change by
less than 1e-4 of their free values and the phases by 0.01 deg per estimated remaining transient
(as :func:`afmsmiler.modes.integrate` does); the amplitude and phase lag at each drive frequency
come from a joint least-squares fit of the last block to a constant and the two tones (a
two-frequency lock-in without leakage between the tones). The first mode's amplitude is the
topography feedback's signal; the second mode's phase is the compositional channel: with
A_2 << A_1 the second mode feels the force gradient averaged over the first mode's cycle, an
added stiffness k_eff = <-dF_ts/dz>, and its phase lag at w_2 is atan2(k_2 / Q_2, k_eff)
(Garcia and Proksch (2013), Sec. 2; Kawai et al., Phys. Rev. B 81, 085420 (2010)). At one
distance (7 nm, A_01 = 10 nm) it separates a 1 GPa from a 10 GPa sample by about twice the
first mode's phase difference (``tests/test_modes_bimodal.py``).

One integration takes some 300 periods of mode 1 (Q_1 = 100) and several seconds: a demo of a
few distances, not an imaging mode.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import odeint

from ..cantilever import Cantilever, eigenvalue
from ..parameters import QUALITY_FACTOR, Parameter, read_only
from ..validation import check_instance, check_integer, check_range
from ._forces import _force
from .tapping import PARAMETERS as TAPPING_PARAMETERS
from .tapping import TappingLever
from .oscillator import Oscillator

__all__ = ["PARAMETERS", "FLEXURAL_RATIO", "BimodalLever", "BimodalState", "modal_stiffness",
           "bimodal_response", "averaged_gradient", "BLOCK_PERIODS", "MAX_PERIODS",
           "DEFAULT_QUALITY_FACTOR"]

#: w_2 / w_1 of a rectangular clamped-free beam, (b_2 L / b_1 L)^2 (module (a)'s eigenvalues).
FLEXURAL_RATIO = (eigenvalue(2) / eigenvalue(1)) ** 2
#: Q_1 of the default :class:`BimodalLever` (a short transient for the demo).
DEFAULT_QUALITY_FACTOR = 100.0
#: Periods of mode 1 per block of the transient criterion and of the final lock-in.
BLOCK_PERIODS = 15
#: Most periods of mode 1 one :func:`bimodal_response` integrates (some 6 s on one core).
MAX_PERIODS = 1000
# samples per period of mode 2 in the lock-in
_SAMPLES = 16
#: Most internal steps LSODA takes between two output samples.
_MAX_STEPS = 100_000
_AMPLITUDE_TOL, _PHASE_TOL = 1e-4, 1e-2

#: The second mode's quantities (SI); the first mode and the sample are the tapping lever's
#: (:data:`afmsmiler.modes.tapping.PARAMETERS`). A second mode of Q_2 = 3 Q_1 driven to 1 nm.
#: The default first mode has Q_1 = 100 (:data:`DEFAULT_QUALITY_FACTOR`): its transient
#: settles in some 300 periods, a few seconds of integration.
PARAMETERS = read_only({p.name: p for p in (
    QUALITY_FACTOR.with_(name="quality_factor_2", default=300.0, slider_low=1.0,
                         slider_high=5000.0, label="quality factor Q_2 (mode 2)"),
    Parameter(name="free_amplitude_2", unit="m", display_unit="nm", default=1e-9, low=0.0,
              high=1e-6, low_inclusive=False, slider_low=0.05e-9, slider_high=5e-9,
              label="free amplitude A_02 (mode 2)"),
    Parameter(name="mode_frequency_ratio", unit="", default=FLEXURAL_RATIO, low=1.5, high=50.0,
              slider_low=2.0, slider_high=10.0, label="f_2 / f_1"),
    Parameter(name="mode_stiffness_ratio", unit="", default=FLEXURAL_RATIO ** 2, low=1.0,
              high=2500.0, slider_low=2.0, slider_high=100.0, log=True, label="k_2 / k_1"),
)})


def modal_stiffness(cantilever: Cantilever, mode: int = 1) -> float:
    """Stiffness k_n = w_n^2 rho w h int_0^L phi_n^2 dx in N/m of flexural mode n at the tip.

    Parameters
    ----------
    cantilever : afmsmiler.cantilever.Cantilever
        Module (a)'s rectangular lever.
    mode : int
        Mode number, 1 to 10.

    Returns
    -------
    float
        The modal mass (with phi_n normalised to 1 at the tip, module (a)'s
        :meth:`~afmsmiler.cantilever.Cantilever.mode_shape`) times w_n^2; the integral by
        200-point Gauss-Legendre quadrature.

    Raises
    ------
    TypeError
        If ``cantilever`` is not a Cantilever.
    ValueError
        If ``mode`` is not an integer in [1, 10].
    """
    check_instance("cantilever", cantilever, Cantilever)
    n = check_integer("mode", mode, 1, 10)
    x, w = np.polynomial.legendre.leggauss(200)
    length = cantilever.length
    xs = 0.5 * length * (x + 1.0)
    integral = 0.5 * length * float(np.sum(w * cantilever.mode_shape(xs, n) ** 2))
    mass = cantilever.density * cantilever.width * cantilever.thickness * integral
    return (2.0 * math.pi * cantilever.resonance_frequency(n)) ** 2 * mass


@dataclass(frozen=True)
class BimodalLever:
    """A lever's first two flexural modes over a sample (SI units).

    Parameters
    ----------
    lever : afmsmiler.modes.TappingLever
        Mode 1 (k_1, f_1, Q_1, drive ratio W, free amplitude A_01) and the sample's force law
        (default: the tapping lever with Q_1 = :data:`DEFAULT_QUALITY_FACTOR`).
    quality_factor_2 : float
        Q_2 of mode 2.
    free_amplitude_2 : float
        Free amplitude A_02 in m at w_2 (the drive F_2 that gives it).
    mode_frequency_ratio : float
        f_2 / f_1 (6.2669 for a rectangular beam).
    mode_stiffness_ratio : float
        k_2 / k_1 (39.27 for a rectangular beam: equal modal masses).

    Raises
    ------
    TypeError
        If ``lever`` is not a TappingLever.
    ValueError
        Naming the value out of range (:data:`PARAMETERS`).
    """

    lever: TappingLever = field(
        default_factory=lambda: TappingLever(quality_factor=DEFAULT_QUALITY_FACTOR))
    quality_factor_2: float = PARAMETERS["quality_factor_2"].default
    free_amplitude_2: float = PARAMETERS["free_amplitude_2"].default
    mode_frequency_ratio: float = PARAMETERS["mode_frequency_ratio"].default
    mode_stiffness_ratio: float = PARAMETERS["mode_stiffness_ratio"].default

    def __post_init__(self):
        check_instance("lever", self.lever, TappingLever)
        for name in PARAMETERS:
            object.__setattr__(self, name, PARAMETERS[name].check(getattr(self, name)))

    @classmethod
    def from_cantilever(cls, cantilever: Cantilever, *,
                        quality_factor: float = DEFAULT_QUALITY_FACTOR,
                        quality_factor_2: float = PARAMETERS["quality_factor_2"].default,
                        free_amplitude: float = TAPPING_PARAMETERS["free_amplitude"].default,
                        free_amplitude_2: float = PARAMETERS["free_amplitude_2"].default,
                        **sample) -> "BimodalLever":
        """The two modes of module (a)'s beam: f_1, f_2 and k_1, k_2 from its mode shapes.

        Parameters
        ----------
        cantilever : afmsmiler.cantilever.Cantilever
            The rectangular lever.
        quality_factor, quality_factor_2 : float
            Q_1 and Q_2.
        free_amplitude, free_amplitude_2 : float
            A_01 and A_02 in m.
        **sample
            The force law's quantities of :class:`~afmsmiler.modes.TappingLever` (``radius``,
            ``hamaker_constant``, ``youngs_modulus``, ``poisson_ratio``,
            ``intermolecular_distance``, ``sample_viscosity``, ``frequency_ratio``).

        Returns
        -------
        BimodalLever
        """
        check_instance("cantilever", cantilever, Cantilever)
        k1, k2 = modal_stiffness(cantilever, 1), modal_stiffness(cantilever, 2)
        f1, f2 = cantilever.resonance_frequency(1), cantilever.resonance_frequency(2)
        lever = TappingLever(spring_constant=k1, resonance_frequency=f1,
                             quality_factor=quality_factor, free_amplitude=free_amplitude,
                             **sample)
        return cls(lever, quality_factor_2, free_amplitude_2, f2 / f1, k2 / k1)

    @property
    def stiffnesses(self) -> tuple[float, float]:
        """(k_1, k_2) in N/m."""
        k1 = self.lever.spring_constant
        return k1, k1 * self.mode_stiffness_ratio

    @property
    def angular_frequencies(self) -> tuple[float, float]:
        """(w_1, w_2) in rad/s, the modes' resonances."""
        w1 = 2.0 * math.pi * self.lever.resonance_frequency
        return w1, w1 * self.mode_frequency_ratio

    @property
    def drive_frequencies(self) -> tuple[float, float]:
        """(w_d1, w_d2) = (W w_1, w_2) in rad/s."""
        w1, w2 = self.angular_frequencies
        return self.lever.frequency_ratio * w1, w2

    @property
    def oscillators(self) -> tuple[Oscillator, Oscillator]:
        """The two modes as point-mass oscillators (k_n, f_n, Q_n)
        (:class:`~afmsmiler.modes.oscillator.Oscillator`): mode 1 is the tapping lever's own.

        Raises
        ------
        ValueError
            If mode 2's k_2 = k_1 (k_2 / k_1) or f_2 = f_1 (f_2 / f_1) leaves the shared range
            of :data:`afmsmiler.parameters.PARAMETERS` (a ratio at its extreme on a lever at
            its extreme).
        """
        k2 = self.stiffnesses[1]
        return (self.lever.oscillator,
                Oscillator(k2, self.lever.resonance_frequency * self.mode_frequency_ratio,
                           self.quality_factor_2))

    @property
    def quality_factors(self) -> tuple[float, float]:
        """(Q_1, Q_2)."""
        return self.lever.quality_factor, self.quality_factor_2

    def compliance(self, angular_frequency: float) -> complex:
        """Free tip response sum_i H_i(w) / k_i in m/N to a force F cos(w t) (complex).

        Parameters
        ----------
        angular_frequency : float
            w in rad/s, > 0.

        Returns
        -------
        complex
            Its modulus is the amplitude per newton, minus its argument the phase lag.
        """
        w = check_range("angular_frequency", angular_frequency, 0.0, 1e12, "rad/s",
                        low_inclusive=False)
        out = 0.0j
        for k, wi, q in zip(self.stiffnesses, self.angular_frequencies, self.quality_factors):
            r = w / wi
            out += 1.0 / (k * complex(1.0 - r * r, r / q))
        return out

    @property
    def drive_forces(self) -> tuple[float, float]:
        """(F_1, F_2) in N: the drives that give the free amplitudes A_01 and A_02."""
        a = (self.lever.free_amplitude, self.free_amplitude_2)
        return tuple(ai / abs(self.compliance(w)) for ai, w in zip(a, self.drive_frequencies))

    def free_response(self) -> tuple[tuple[float, float], tuple[float, float]]:
        """((A_1, phi_1), (A_2, phi_2)): the free tip's amplitude (m) and lag (rad) per drive.

        Returns
        -------
        tuple
            A_j = F_j |sum_i H_i(w_dj) / k_i| (= A_0j by construction) and
            phi_j = -arg(sum_i H_i(w_dj) / k_i).
        """
        out = []
        for f, w in zip(self.drive_forces, self.drive_frequencies):
            c = self.compliance(w)
            out.append((f * abs(c), -math.atan2(c.imag, c.real)))
        return tuple(out)


@dataclass(frozen=True)
class BimodalState:
    """The steady state of :func:`bimodal_response` (SI units).

    Parameters
    ----------
    distance : float
        Rest tip-sample distance z_c in m.
    amplitude_1, phase_1 : float
        Amplitude in m and phase lag in rad of the tip at w_d1.
    amplitude_2, phase_2 : float
        The same at w_d2 (the compositional channel).
    mean_deflection : float
        Mean tip deflection in m.
    periods : int
        Periods of mode 1 integrated.
    converged : bool
        Whether the transient criterion was met before :data:`MAX_PERIODS`.
    time, deflection : numpy.ndarray
        The last period of mode 1: times in s and tip deflection z_1 + z_2 in m.
    """

    distance: float
    amplitude_1: float
    phase_1: float
    amplitude_2: float
    phase_2: float
    mean_deflection: float
    periods: int
    converged: bool
    time: np.ndarray = field(repr=False)
    deflection: np.ndarray = field(repr=False)


def bimodal_response(distance: float, lever: BimodalLever | None = None, *,
                     max_periods: int = MAX_PERIODS, start_ratio: float = 1.0) -> BimodalState:
    """Integrate the two-mode lever at one distance to its steady state (module notes).

    Parameters
    ----------
    distance : float
        Rest tip-sample distance z_c in m, in (a0, 1e-5].
    lever : BimodalLever, optional
        The lever (default :class:`BimodalLever` ()).
    max_periods : int
        Most periods of mode 1, 2 x BLOCK_PERIODS to :data:`MAX_PERIODS`.
    start_ratio : float
        Start from the free motion scaled by this factor, in (0, 1] (1: the free motion; less:
        off the steady state, to test the transient); near the sample it is lowered further,
        to 0.9 (z_c - a0) / (A_01 + A_02), so that the tip starts outside the sample.

    Returns
    -------
    BimodalState

    Raises
    ------
    ValueError
        Naming the argument out of range, or a start inside the sample, before integrating.
    TypeError
        If ``lever`` is not a BimodalLever.
    """
    lever = BimodalLever() if lever is None else check_instance("lever", lever, BimodalLever)
    zc = TAPPING_PARAMETERS["distance"].check(distance)
    n_max = check_integer("max_periods", max_periods, 2 * BLOCK_PERIODS, MAX_PERIODS)
    ratio = check_range("start_ratio", start_ratio, 0.0, 1.0, low_inclusive=False)
    t1 = lever.lever
    a01, a02 = t1.free_amplitude, lever.free_amplitude_2
    if zc <= t1.intermolecular_distance:
        raise ValueError(f"distance must be > a0 = {t1.intermolecular_distance:g} m (the tip "
                         f"at rest outside the sample), got {zc:g} m")
    # the free motion, shrunk where it would start inside the sample: the tip starts outside
    # and its amplitudes grow from below (onto the low, attractive branch where two coexist)
    ratio = min(ratio, 0.9 * (zc - t1.intermolecular_distance) / (a01 + a02))
    (k1, k2), (w1, w2), (q1, q2) = lever.stiffnesses, lever.angular_frequencies, \
        lever.quality_factors
    wd1, wd2 = lever.drive_frequencies
    f1, f2 = lever.drive_forces
    scale = a01
    # the free motion of each mode at each drive (the start): z_i = sum_j Re(F_j H_ij e^(iwt))
    h = [[1.0 / (k * complex(1 - (w / wi) ** 2, (w / wi) / q)) for w in (wd1, wd2)]
         for k, wi, q in ((k1, w1, q1), (k2, w2, q2))]
    y0 = []
    for i in range(2):
        c1, c2 = ratio * f1 * h[i][0], ratio * f2 * h[i][1]
        y0 += [(c1.real + c2.real) / scale, -(c1.imag * wd1 + c2.imag * wd2) / (scale * w1)]
    # dimensionless: x = z / A_01, s = w1 t
    r2, rd1, rd2 = w2 / w1, wd1 / w1, wd2 / w1
    g1, g2 = f1 / (k1 * scale), f2 / (k1 * scale)
    kr = k1 / k2
    hr6 = t1.hamaker_constant * t1.radius / 6.0
    a0 = t1.intermolecular_distance
    e43 = 4.0 / 3.0 * t1.reduced_modulus * math.sqrt(t1.radius)
    eta_r = t1.sample_viscosity * math.sqrt(t1.radius)
    adhesion = hr6 / (a0 * a0)
    inv = 1.0 / (k1 * scale)

    def rhs(s, y):
        x1, v1, x2, v2 = y
        d = zc + scale * (x1 + x2)
        if d > a0:
            fts = -hr6 / (d * d) * inv
        else:
            delta = a0 - d
            sq = math.sqrt(delta)
            fts = (-adhesion + e43 * sq * delta - eta_r * sq * scale * w1 * (v1 + v2)) * inv
        drive = g1 * math.cos(rd1 * s) + g2 * math.cos(rd2 * s) + fts
        return [v1, -x1 - v1 / q1 + drive,
                v2, r2 * r2 * (-x2 - v2 / (q2 * r2) + kr * drive)]

    period = 2.0 * math.pi
    samples = int(math.ceil(BLOCK_PERIODS * rd2 * _SAMPLES))
    basis_t = np.arange(samples + 1) / samples * BLOCK_PERIODS * period

    def run(s0, y):
        """One block from s0: the end state and the block's samples (end excluded)."""
        t_eval = s0 + basis_t
        ys, info = odeint(rhs, y, t_eval, tfirst=True, rtol=1e-8, atol=1e-10,
                          mxstep=_MAX_STEPS, full_output=True)
        if info["message"] != "Integration successful.":  # pragma: no cover - bounded system
            raise RuntimeError(f"time integration failed: {info['message']}")
        ys = ys.T
        return t_eval[-1], ys[:, -1], t_eval[:-1], ys[:, :-1]

    def lockin(t, x):
        """Joint least squares of x(t) on 1, cos/sin(rd1 t), cos/sin(rd2 t)."""
        m = np.column_stack((np.ones_like(t), np.cos(rd1 * t), np.sin(rd1 * t),
                             np.cos(rd2 * t), np.sin(rd2 * t)))
        c = np.linalg.lstsq(m, x, rcond=None)[0]
        return (c[0] * scale, math.hypot(c[1], c[2]) * scale, math.atan2(c[2], c[1]),
                math.hypot(c[3], c[4]) * scale, math.atan2(c[4], c[3]))

    slow = min(1.0 / q1, r2 / q2)  # the slower decay rate per radian of s
    ratio_block = math.exp(-slow * BLOCK_PERIODS * period / 2.0)
    tail = ratio_block / (1.0 - ratio_block)
    s, y = 0.0, np.array(y0)
    done, previous, converged = 0, None, False
    while done + BLOCK_PERIODS <= n_max:  # bounded by max_periods
        s, y, t, ys = run(s, y)
        done += BLOCK_PERIODS
        now = lockin(t, ys[0] + ys[2])
        if previous is not None and all(
                abs(now[i] - previous[i]) * tail < _AMPLITUDE_TOL * ref for i, ref in
                ((1, a01), (3, a02))) and all(
                abs(math.degrees(now[i] - previous[i])) * tail < _PHASE_TOL for i in (2, 4)):
            converged = True
            break
        previous = now
    mean, amp1, ph1, amp2, ph2 = now
    ph1 = ph1 + 2 * math.pi if ph1 < -0.5 * math.pi else ph1
    ph2 = ph2 + 2 * math.pi if ph2 < -0.5 * math.pi else ph2
    last = t >= t[-1] - period
    return BimodalState(zc, amp1, ph1, amp2, ph2, mean, done, converged, t[last] / w1,
                        (ys[0] + ys[2])[last] * scale)


def averaged_gradient(distance: float, amplitude: float, lever: BimodalLever | None = None,
                      *, mean_deflection: float = 0.0, points: int = 20001) -> float:
    """<-dF_ts/dz> in N/m over a harmonic motion z_c + <z> + A cos(theta) (the stiffness mode 2
    feels).

    Parameters
    ----------
    distance : float
        Rest distance z_c in m.
    amplitude : float
        Amplitude A of mode 1 in m.
    lever : BimodalLever, optional
        The lever and sample.
    mean_deflection : float
        Mean deflection <z> in m added to z_c.
    points : int
        Samples of theta over a period (midpoint rule), 101 to 10^6.

    Returns
    -------
    float
        (1 / 2 pi) int_0^2pi -dF_ts/dz (z_c + <z> + A cos(theta)) d theta, with the conservative
        force (no damping), by central differences of 1e-13 m.

    Raises
    ------
    ValueError
        Naming the argument out of range.
    """
    lever = BimodalLever() if lever is None else check_instance("lever", lever, BimodalLever)
    zc = TAPPING_PARAMETERS["distance"].check(distance)
    a = check_range("amplitude", amplitude, 0.0, 1e-6, "m")
    mean = check_range("mean_deflection", mean_deflection, -1e-6, 1e-6, "m")
    n = check_integer("points", points, 101, 10 ** 6)
    t1 = lever.lever
    theta = (np.arange(n) + 0.5) * 2 * math.pi / n
    d = zc + mean + a * np.cos(theta)
    eps = 1e-13

    def f(x):
        return _force(x, 0.0, t1.radius, t1.hamaker_constant, t1.reduced_modulus,
                      t1.intermolecular_distance, 0.0)

    return float(np.mean(-(f(d + eps) - f(d - eps)) / (2 * eps)))
