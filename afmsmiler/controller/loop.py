"""The contact-mode feedback loop: cantilever and sample in contact, PID control of the height.

Cantilever (m_c, b_c, k_c) and sample (m_s, b_s, k_s) move together while in contact; the
topography T(t) under the tip is a disturbance, Z_c the measured deflection, Z_np the height of
the nano-positioner, R the deflection setpoint::

    Z_c = P(s) (Z_np + T),    P(s) = (b_s s + k_s) / ((m_c + m_s) s^2 + (b_c + b_s) s + (k_c + k_s))
    Z_np = C(s) (R - Z_c),    C(s) = K_P + K_I / s + K_D s

Solved in :mod:`afmsmiler.controller.derivation` (sympy)::

    Z_c / T  =  s (b_s s + k_s) / den
    Z_np / T = -(b_s s + k_s)(K_D s^2 + K_P s + K_I) / den
    den      =  A s^3 + B s^2 + C s + D
    A = m_c + m_s + b_s K_D              B = b_c + b_s + b_s K_P + k_s K_D
    C = k_c + k_s + b_s K_I + k_s K_P    D = k_s K_I

For K_I = 0 a factor s cancels and the loop is of second order. The estimated topography is
Z_c - Z_np; at steady state (K_I > 0) Z_c = R and Z_np = (k_c + k_s) R / k_s - T, so the estimate
is T - k_c R / k_s: the topography shifted by the indentation of the sample under the setpoint
force k_c R.
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import cached_property
from typing import NamedTuple

import numpy as np

from ..cantilever import Cantilever
from ..parameters import UNDERDAMPED_QUALITY_FACTOR, Parameter, read_only
from ..validation import check_array, check_choice, check_finite, check_instance
from .closed_forms import ClosedForm, classify_roots, closed_form, normalise
from .polygon import polygon_response

__all__ = ["ContactLoop", "Stability", "LoopResponse", "ScanPass", "ScanLine", "routh_hurwitz",
           "polished_roots", "check_size", "MAX_LINE_PIXELS", "MAX_KNOTS", "MAX_TIME",
           "MAX_POSITION", "PARAMETERS",
           "LOOP_PARAMETERS"]


def _mass(name, label):
    return Parameter(name=name, unit="kg", display_unit="ng", default=1e-12, low=1e-18,
                     high=1e-3, slider_low=1e-14, slider_high=1e-10, log=True, label=label)


def _damping(name, label):
    return Parameter(name=name, unit="kg/s", display_unit="ng/us", default=1.5e-8, low=0.0,
                     high=1.0, slider_low=1e-10, slider_high=1e-5, log=True, label=label)


def _stiffness(name, label, default, slider_high):
    return Parameter(name=name, unit="N/m", default=default, low=1e-6, high=1e6,
                     slider_low=0.01, slider_high=slider_high, log=True, label=label)


#: Every user-settable quantity of module (c), in SI, with its display unit, default (the paper's
#: preset (a): m = 1 ng, b = 0.015 ng/us, k_c = 1 N/m, k_s = 100 N/m, K_P = 0.5, K_I = 0.01/us,
#: K_D = 0, 10 um/s, R = 10 nm, 50 nm features), valid range and slider range (a part of it).
#: The valid ranges reach far beyond any AFM (1 fg to 1 g, up to 1 kg/s, 1 uN/m to 1 MN/m, K_P up
#: to 1e30, K_I up to 1e15 1/s, K_D up to 1 s, 1 nm/s to 1 m/s) but stop where the double-precision
#: closed forms would overflow. The masses, damping, stiffnesses, gains and speed span decades:
#: log sliders.
PARAMETERS = read_only({p.name: p for p in (
    _mass("m_c", "lever m_c"),
    _mass("m_s", "sample m_s"),
    _damping("b_c", "lever b_c"),
    _damping("b_s", "sample b_s"),
    _stiffness("k_c", "lever k_c", 1.0, 100.0),
    _stiffness("k_s", "sample k_s", 100.0, 1000.0),
    Parameter(name="kp", unit="", default=0.5, low=0.0, high=1e30, slider_low=1e-3,
              slider_high=1e3, log=True, label="K_P"),
    Parameter(name="ki", unit="1/s", display_unit="1/us", default=1e4, low=0.0, high=1e15,
              slider_low=10.0, slider_high=1e9, log=True, label="K_I"),
    Parameter(name="kd", unit="s", display_unit="us", default=0.0, low=0.0, high=1.0,
              slider_low=0.0, slider_high=2e-6, label="K_D"),
    Parameter(name="speed", unit="m/s", display_unit="um/s", default=1e-5, low=1e-9, high=1.0,
              slider_low=1e-6, slider_high=1e-2, log=True, label="scan speed"),
    Parameter(name="setpoint", unit="m", display_unit="nm", default=10e-9, low=-1e-6,
              high=1e-6, slider_low=0.0, slider_high=100e-9, label="setpoint R"),
    Parameter(name="height", unit="m", display_unit="nm", default=50e-9, low=0.0, high=1e-5,
              low_inclusive=False, slider_low=1e-9, slider_high=500e-9, label="feature h"),
    UNDERDAMPED_QUALITY_FACTOR,  # Q >= 1/2: the lever's damping m w / Q stays bounded
)})

#: Most pixels of a scanned line (a 2**18-pixel line, trace and retrace, takes about 1.5 s).
MAX_LINE_PIXELS = 2 ** 18
#: Most knots, topography values and evaluation times of :meth:`ContactLoop.response`.
MAX_KNOTS = 2 ** 19
#: Largest |time| in s of :meth:`ContactLoop.response` (1e12 s, some 30 000 years: beyond any
#: experiment; near 1e300 s the forced parts q1 t of the ramps overflow to inf - inf = nan).
MAX_TIME = 1e12
#: Largest |x| in m of :meth:`ContactLoop.scan_line` (1 m, beyond any AFM's scan range of about
#: 100 um; at slow speeds lines near 1e300 m overflowed the same way).
MAX_POSITION = 1.0


def check_size(name: str, values, limit: int) -> None:
    """Raise ``ValueError`` naming ``name`` if ``values`` holds more than ``limit`` elements.

    Parameters
    ----------
    name : str
        The parameter's name.
    values : array_like
        The values (not converted: the size is read from their shape).
    limit : int
        The largest size the model honours within seconds.
    """
    n = int(np.size(values)) if not hasattr(values, "size") else int(values.size)
    if n > limit:
        raise ValueError(f"{name} must have at most {limit} values (a bound the model honours "
                         f"in seconds), got {n}")


#: The parameters of :class:`ContactLoop`, in the order of its fields.
LOOP_PARAMETERS = ("m_c", "m_s", "b_c", "b_s", "k_c", "k_s", "kp", "ki", "kd")


@dataclass(frozen=True)
class Stability:
    """Routh-Hurwitz verdict on the closed loop; truthy when the loop is stable.

    Parameters
    ----------
    stable : bool
        True if every pole has a negative real part.
    margin : float
        Dimensionless margin, > 0 exactly when stable: 1 - A D / (B C) for the third-order loop
        (the Hurwitz condition B C > A D), the damping ratio B / (2 sqrt(A C)) for the second.
    routh_column : tuple of float
        First column of the Routh array (all > 0 when stable).
    """

    stable: bool
    margin: float
    routh_column: tuple

    def __bool__(self) -> bool:
        return self.stable


def polished_roots(den) -> np.ndarray:
    """Roots of a real 2nd- or 3rd-order polynomial, the slowest real one kept accurate.

    The eigenvalues of the companion matrix are accurate to about eps times the largest root:
    a real root far slower than the others (K_I = 1e-24 1/s, or K_P = 1e19, gives one about
    1e-36 of the fastest) comes back as 0 or with no correct digit. When the slowest root is real
    and at most a tenth of the others in modulus, it is taken from the product of the roots
    (Vieta: prod p_i = (-1)^n a_n / a_0), which the accurate fast roots give to full precision.

    Parameters
    ----------
    den : array_like
        Coefficients, highest power first, 3 or 4 of them, finite, leading one nonzero.

    Returns
    -------
    numpy.ndarray
        The roots (complex), in 1/s for a loop's denominator.

    Raises
    ------
    ValueError
        If ``den`` is not 3 or 4 finite numbers with a nonzero leading one, or its ratios to the
        leading coefficient overflow.
    """
    den = check_array("den", den, ndim=1)
    if den.size not in (3, 4):
        raise ValueError(f"den must have 3 or 4 coefficients, got {den.size}")
    if den[0] == 0:
        raise ValueError(f"den's leading coefficient must be nonzero, got {den.tolist()}")
    companion = np.diag(np.ones(den.size - 2), -1)
    with np.errstate(over="ignore"):
        companion[0] = -den[1:] / den[0]
    if not np.all(np.isfinite(companion)):
        raise ValueError(f"den's coefficients over the leading one overflow double precision, "
                         f"got {den.tolist()}")
    roots = np.linalg.eigvals(companion).astype(complex)
    k = int(np.argmin(np.abs(roots)))
    others = np.delete(roots, k)
    n = den.size - 1
    if roots[k].imag == 0 and np.all(np.abs(roots[k]) <= 0.1 * np.abs(others)):
        product = (-1) ** n * den[-1] / den[0]
        roots[k] = product / np.prod(others).real
    return roots


def routh_hurwitz(den) -> Stability:
    """Routh-Hurwitz test of a 2nd- or 3rd-order polynomial (Routh array of its coefficients).

    A negative leading coefficient is normalised away (the polynomial times -1 has the same
    roots: -s^2 - 2 s - 3 is as stable as s^2 + 2 s + 3).

    Parameters
    ----------
    den : sequence of float
        Coefficients, highest power first: (A, B, C) or (A, B, C, D); finite, A != 0.

    Returns
    -------
    Stability

    Raises
    ------
    ValueError
        If there are not 3 or 4 coefficients, one is not finite or the leading one is 0.

    Notes
    -----
    For a cubic A s^3 + B s^2 + C s + D with A > 0 the first column of the Routh array is
    (A, B, (B C - A D) / B, D): all roots lie in the open left half-plane exactly when
    B, D > 0 and B C > A D (Ogata, *Modern Control Engineering*, 5th ed., Sec. 5-6).

    Examples
    --------
    >>> bool(routh_hurwitz([-1.0, -2.0, -3.0]))
    True
    """
    try:
        den = [float(c) for c in den]
    except (TypeError, ValueError):
        raise ValueError(f"den must be a sequence of 3 or 4 real numbers, got {den!r}") from None
    if len(den) not in (3, 4):
        raise ValueError(f"den must have 3 or 4 coefficients, got {len(den)}")
    if not all(np.isfinite(den)):
        raise ValueError(f"den must hold finite coefficients, got {den}")
    if den[0] == 0:
        raise ValueError(f"den's leading coefficient must be nonzero, got {den}")
    if den[0] < 0:
        den = [-c for c in den]
    if len(den) == 3:
        A, B, C = den
        column = (A, B, C)
        margin = B / (2 * np.sqrt(A * C)) if A * C > 0 else -np.inf
    else:
        A, B, C, D = den
        third = (B * C - A * D) / B if B != 0 else -np.inf
        column = (A, B, third, D)
        margin = 1 - A * D / (B * C) if B * C > 0 else -np.inf
    stable = all(c > 0 for c in column)
    return Stability(bool(stable), float(margin), column)


class LoopResponse(NamedTuple):
    """Deflection and positioner height in m (unpacks as ``z_c, z_np``).

    Parameters
    ----------
    z_c : numpy.ndarray
        Cantilever deflection Z_c in m.
    z_np : numpy.ndarray
        Nano-positioner height Z_np in m.
    """

    z_c: np.ndarray
    z_np: np.ndarray


@dataclass(frozen=True)
class ScanPass:
    """One pass (trace or retrace) over a line, in scan order.

    Parameters
    ----------
    t : numpy.ndarray
        Time in s since the start of the trace.
    x : numpy.ndarray
        Tip position along the line in m.
    height : numpy.ndarray
        True topography T under the tip in m.
    z_c, z_np : numpy.ndarray
        Deflection and positioner height in m.
    """

    t: np.ndarray
    x: np.ndarray
    height: np.ndarray
    z_c: np.ndarray
    z_np: np.ndarray

    @property
    def topography(self) -> np.ndarray:
        """Estimated topography Z_c - Z_np in m."""
        return self.z_c - self.z_np

    @property
    def error(self) -> np.ndarray:
        """Estimate minus the true topography, in m (includes the steady indentation offset)."""
        return self.topography - self.height


@dataclass(frozen=True)
class ScanLine:
    """Trace and retrace of one line (see :meth:`ContactLoop.scan_line`).

    Parameters
    ----------
    trace, retrace : ScanPass
        The two passes; the retrace starts where and in the state the trace ended.
    stable : bool
        Routh-Hurwitz verdict on the loop (an unstable loop still simulates, flagged here).
    setpoint : float
        Deflection setpoint R in m.
    speed : float
        Scan speed in m/s.
    offset : float
        Steady-state value of estimate minus topography, in m (-k_c R / k_s when K_I > 0).
    """

    trace: ScanPass
    retrace: ScanPass
    stable: bool
    setpoint: float
    speed: float
    offset: float = field(default=0.0)

    @property
    def gap(self) -> float:
        """Largest difference of Z_np between trace and retrace at the same pixel, in m.

        The positioner lags behind the topography in the direction of the scan, so a slow loop's
        trace and retrace disagree (the paper's Fig. 4c); 0 for a loop that keeps up.
        """
        with np.errstate(over="ignore", invalid="ignore"):
            d = np.abs(self.trace.z_np - self.retrace.z_np[::-1])
        return float(np.max(d)) if np.all(np.isfinite(d)) else float("inf")


_P = PARAMETERS
#: Slowest integrator pole in 1/s that the loop keeps as a third pole (see ContactLoop.order).
SLOWEST_POLE = 1e-100


@dataclass(frozen=True, kw_only=True)
class ContactLoop:
    """Cantilever and sample in contact under PID control of the positioner height, in SI units.

    All keyword-only, validated with :data:`PARAMETERS` (defaults: the paper's preset (a)).

    Parameters
    ----------
    m_c, m_s : float
        Effective masses of cantilever and sample in kg (> 0).
    b_c, b_s : float
        Damping coefficients of cantilever and sample in kg/s (>= 0).
    k_c, k_s : float
        Spring constants of cantilever and sample in N/m (> 0).
    kp : float
        Proportional gain K_P (dimensionless, >= 0).
    ki : float
        Integral gain K_I in 1/s (>= 0; 0 makes the loop second order).
    kd : float
        Derivative gain K_D in s (>= 0).

    Raises
    ------
    ValueError
        If a parameter is not finite or out of its range (the message names it and the range).

    Notes
    -----
    The closed-loop transfer functions are those of the module docstring, derived with sympy in
    :mod:`afmsmiler.controller.derivation` (``tests/test_controller_derivation.py`` checks that
    the coefficients here equal the derivation and python-control's ``feedback``). Responses
    come from the closed forms of the 14 cases, superposed in O(N) along a polygon
    (:mod:`afmsmiler.controller.polygon`).

    Examples
    --------
    >>> from afmsmiler.controller import PRESETS
    >>> loop = PRESETS["a_good_tracking"].loop
    >>> bool(loop.is_stable())
    True
    """

    m_c: float = _P["m_c"].default
    m_s: float = _P["m_s"].default
    b_c: float = _P["b_c"].default
    b_s: float = _P["b_s"].default
    k_c: float = _P["k_c"].default
    k_s: float = _P["k_s"].default
    kp: float = _P["kp"].default
    ki: float = _P["ki"].default
    kd: float = _P["kd"].default

    def __post_init__(self):
        for name in LOOP_PARAMETERS:
            object.__setattr__(self, name, PARAMETERS[name].check(getattr(self, name)))

    @classmethod
    def from_cantilever(cls, lever, *, sample_stiffness: float = _P["k_s"].default,
                        sample_mass: float = _P["m_s"].default,
                        sample_damping: float = _P["b_s"].default,
                        quality_factor: float = _P["quality_factor"].default,
                        kp: float = _P["kp"].default, ki: float = _P["ki"].default,
                        kd: float = _P["kd"].default) -> "ContactLoop":
        """The loop of a module (a) cantilever in contact with a sample (joins modules (a), (c)).

        The lever enters as the point-mass oscillator of its first flexural mode: k_c its
        end-load spring constant 3 E J / L^3, m_c its effective mass k_c / omega_1^2
        (= 3 m / (b_1 L)^4 = 0.2427 m for a rectangular beam, with b_1 L = 1.8751) and b_c the
        damping that gives the quality factor Q: b_c = m_c omega_1 / Q, omega_1 = 2 pi f_1.

        Parameters
        ----------
        lever : afmsmiler.cantilever.Cantilever
            The cantilever.
        sample_stiffness : float
            Sample stiffness k_s in N/m (> 0).
        sample_mass : float
            Sample effective mass m_s in kg (> 0).
        sample_damping : float
            Sample damping b_s in kg/s (>= 0).
        quality_factor : float
            Quality factor Q of the lever's first mode (dimensionless, 0.5 to 1e5).
        kp : float
            Proportional gain K_P (dimensionless, >= 0).
        ki : float
            Integral gain K_I in 1/s (>= 0).
        kd : float
            Derivative gain K_D in s (>= 0).

        Returns
        -------
        ContactLoop

        Raises
        ------
        TypeError
            If ``lever`` is not a Cantilever.
        ValueError
            If a value is out of its range, named as given (``sample_stiffness``, ...), or if
            the lever's k_c, m_c or b_c lies outside the loop's range (named ``lever``).

        Notes
        -----
        The effective mass is the one of the modal (Rayleigh) reduction of the first mode, as in
        Butt and Jaschke, Nanotechnology 6, 1 (1995); the damping follows from the definition
        Q = m omega_1 / b of a damped oscillator.

        Examples
        --------
        >>> from afmsmiler.cantilever import Cantilever
        >>> lever = Cantilever.from_material("silicon", length=450e-6, width=50e-6,
        ...                                  thickness=2e-6)
        >>> loop = ContactLoop.from_cantilever(lever, sample_stiffness=10.0)
        >>> round(loop.m_c / lever.mass, 4)
        0.2427
        """
        check_instance("lever", lever, Cantilever)
        # checked under the names the caller passed (not the loop's k_s, m_s, b_s)
        for name, key, value in (("sample_stiffness", "k_s", sample_stiffness),
                                 ("sample_mass", "m_s", sample_mass),
                                 ("sample_damping", "b_s", sample_damping)):
            _P[key].with_(name=name).check(value)
        q = _P["quality_factor"].check(quality_factor)
        sample = {name: _P[key].with_(name=name).check(value) for name, key, value in (
            ("sample_stiffness", "k_s", sample_stiffness), ("sample_mass", "m_s", sample_mass),
            ("sample_damping", "b_s", sample_damping))}  # named as the caller spells them
        k_c = lever.spring_constant
        m_c = lever.effective_mass
        omega = 2 * np.pi * lever.resonance_frequency(1)
        derived = (("k_c", k_c, "its spring constant"), ("m_c", m_c, "its effective mass"),
                   ("b_c", m_c * omega / q, "its damping m_c omega_1 / Q"))
        for key, value, what in derived:  # a lever the loop cannot hold is named as the lever
            try:
                _P[key].check(value)
            except ValueError as err:
                raise ValueError(f"lever must give the loop a valid {key} ({what}): {err}, "
                                 f"for {lever!r}") from None
        return cls(m_c=m_c, m_s=sample["sample_mass"], b_c=derived[2][1],
                   b_s=sample["sample_damping"], k_c=k_c, k_s=sample["sample_stiffness"],
                   kp=kp, ki=ki, kd=kd)

    def replace(self, **changes) -> "ContactLoop":
        """A copy with some parameters changed (validated again).

        Parameters
        ----------
        **changes
            New values of any of m_c, m_s, b_c, b_s, k_c, k_s, kp, ki, kd (SI).

        Returns
        -------
        ContactLoop
        """
        return replace(self, **changes)

    # -- transfer functions ----------------------------------------------------------------
    @property
    def order(self) -> int:
        """3, or 2 when K_I = 0 (the integrator pole cancels).

        Also 2 when the integrator's pole, about -k_s K_I / (k_c + k_s + k_s K_P + b_s K_I), is
        slower than :data:`SLOWEST_POLE` (a time constant above 1e100 s, when the closed forms'
        1/p^2 would underflow): over any time the model can reach, such a loop responds as with
        K_I = 0 (the responses converge as K_I -> 0); it still settles at its K_I > 0 steady state
        (:meth:`steady_state`).
        """
        C = self.k_c + self.k_s + self.b_s * self.ki + self.k_s * self.kp
        return 3 if self.k_s * self.ki > SLOWEST_POLE * C else 2

    @cached_property
    def coefficients(self) -> dict:
        """Numerators and denominator of Z_c/T and Z_np/T, highest power first (minimal order).

        Returns
        -------
        dict
            ``{"den": ..., "Zc_T": ..., "Znp_T": ...}`` as numpy arrays.
        """
        M, B, K = self.m_c + self.m_s, self.b_c + self.b_s, self.k_c + self.k_s
        bs, ks, kp, ki, kd = self.b_s, self.k_s, self.kp, self.ki, self.kd
        den = np.array([M + bs * kd, B + bs * kp + ks * kd, K + bs * ki + ks * kp, ks * ki])
        zc = np.array([bs, ks, 0.0])
        znp = -np.array([bs * kd, bs * kp + ks * kd, bs * ki + ks * kp, ks * ki])
        if self.order == 2:  # cancel the common factor s
            den, zc, znp = den[:-1], zc[:-1], znp[:-1]
        return {"den": den, "Zc_T": zc, "Znp_T": znp}

    def closed_loop(self):
        """The closed-loop transfer functions Z_c/T and Z_np/T (python-control).

        Returns
        -------
        tuple of control.TransferFunction
            (Z_c/T, Z_np/T), in SI (s in 1/s).
        """
        import control
        c = self.coefficients
        return control.tf(c["Zc_T"], c["den"]), control.tf(c["Znp_T"], c["den"])

    @property
    def poles(self) -> np.ndarray:
        """Closed-loop poles in 1/s (roots of the denominator, 2 or 3 of them).

        A slow real pole far below the others (a tiny K_I, or a huge K_P) is taken from the
        product of the roots (Vieta), not from the eigenvalues, which lose it entirely below
        about 1e-16 of the largest pole (it came back as exactly 0 and the closed forms divided
        by it).
        """
        return self._roots.copy()

    @cached_property
    def _roots(self) -> np.ndarray:
        return polished_roots(self.coefficients["den"])

    def is_stable(self) -> Stability:
        """Routh-Hurwitz test of the closed loop; the result is truthy when stable.

        Returns
        -------
        Stability
            With the margin and the first column of the Routh array.
        """
        return routh_hurwitz(self.coefficients["den"])

    @property
    def stability_margin(self) -> float:
        """The Routh-Hurwitz margin of :meth:`is_stable` (> 0 when stable)."""
        return self.is_stable().margin

    def steady_state(self, setpoint: float, height: float = 0.0) -> LoopResponse:
        """Equilibrium for a constant setpoint R and a constant topography T.

        Parameters
        ----------
        setpoint : float
            Deflection setpoint R in m.
        height : float
            Topography T under the tip in m.

        Returns
        -------
        LoopResponse
            Z_c and Z_np in m: (R, (k_c + k_s) R / k_s - T) when K_I > 0.
        """
        R = check_finite("setpoint", setpoint, "m")
        T = check_finite("height", height, "m")
        K = self.k_c + self.k_s
        if self.ki > 0:
            return LoopResponse(np.float64(R), np.float64(K * R / self.k_s - T))
        C0 = K + self.k_s * self.kp  # den(0) of the second-order loop
        z_c = (self.k_s * self.kp * R + self.k_s * T) / C0
        z_np = (self.kp * K * R - self.k_s * self.kp * T) / C0
        return LoopResponse(np.float64(z_c), np.float64(z_np))

    # -- closed forms ------------------------------------------------------------------------
    @cached_property
    def _structure(self):
        return classify_roots(self._roots)

    def closed_forms(self, input: str = "step") -> tuple[ClosedForm, ClosedForm]:
        """Closed-form responses of Z_c and Z_np to a unit step or unit-slope ramp of T.

        Parameters
        ----------
        input : str
            ``"step"`` (T = 1 m for t >= 0) or ``"ramp"`` (T = t x 1 m/s).

        Returns
        -------
        tuple of ClosedForm
            (Z_c, Z_np), callables of the time in s.
        """
        check_choice("input", input, ("step", "ramp"))
        return self._forms[input]

    @cached_property
    def _forms(self):
        structure, params = self._structure
        den = self.coefficients["den"]
        out = {}
        for inp in ("step", "ramp"):
            out[inp] = tuple(closed_form(normalise(self.coefficients[k], den)[0], structure,
                                         params, inp) for k in ("Zc_T", "Znp_T"))
        return out

    # -- responses ----------------------------------------------------------------------------
    def response(self, t_knots, T_knots, t_eval=None) -> LoopResponse:
        """Z_c and Z_np for a polygon topography T(t) through the knots, from rest.

        The loop is at rest (all zero) before ``t_knots[0]``; T steps to ``T_knots[0]`` there,
        follows the polygon and is held at ``T_knots[-1]`` after the last knot. The setpoint is
        not included (add :meth:`steady_state` for a constant R: the loop is linear).

        Parameters
        ----------
        t_knots : array_like
            Knot times in s, 1-D, strictly increasing (spacing may vary), within
            +-:data:`MAX_TIME` (like ``t_eval``), at most :data:`MAX_KNOTS` of them (4 times that
            for ``T_knots`` and ``t_eval``).
        T_knots : array_like
            Topography at the knots in m, same length (or shape (..., N) for a batch).
        t_eval : array_like, optional
            Times in s at which to evaluate (any order, between knots too); default: the knots.

        Returns
        -------
        LoopResponse
            ``(z_c, z_np)`` in m, each of the shape of ``t_eval`` (batch axes first).

        Raises
        ------
        ValueError
            On non-finite values, non-increasing knot times or mismatched lengths.
        """
        check_size("t_knots", t_knots, MAX_KNOTS)
        check_size("T_knots", T_knots, 4 * MAX_KNOTS)
        if t_eval is not None:
            check_size("t_eval", t_eval, 4 * MAX_KNOTS)
        t = check_array("t_knots", t_knots, "s", ndim=1, min_size=1, increasing=True,
                        low=-MAX_TIME, high=MAX_TIME)
        T = check_array("T_knots", T_knots, "m", min_size=1)
        if T.ndim == 0 or T.shape[-1] != t.size:
            raise ValueError(f"T_knots must have {t.size} values along its last axis (same as "
                             f"t_knots), got shape {T.shape}")
        te = None if t_eval is None else check_array("t_eval", t_eval, "s", ndim=1,
                                                     low=-MAX_TIME, high=MAX_TIME)
        steps, ramps = self._forms["step"], self._forms["ramp"]
        z_c, z_np = polygon_response(steps, ramps, t, T, te)
        return LoopResponse(z_c, z_np)

    def scan_line(self, x, height, *, speed: float = _P["speed"].default,
                  setpoint: float = _P["setpoint"].default) -> ScanLine:
        """Trace then retrace one line at constant speed, in contact at constant setpoint.

        The tip is engaged at the first pixel: the loop starts at its steady state for the
        setpoint and the first height (an instrument engaged at the setpoint waits there), then
        the topography under the tip follows the polygon through the pixels at the scan speed.
        The retrace runs back from the last pixel starting from the trace's end state (one
        continuous simulation).

        Parameters
        ----------
        x : array_like
            Pixel positions along the line in m, 1-D, strictly increasing, within
            +-:data:`MAX_POSITION` (1 m), 2 to :data:`MAX_LINE_PIXELS` of them.
        height : array_like
            Topography at the pixels in m, same length.
        speed : float
            Scan speed in m/s (> 0; keyword-only, default 10 um/s).
        setpoint : float
            Deflection setpoint R in m (keyword-only, default 10 nm).

        Returns
        -------
        ScanLine
            Trace and retrace (each in scan order) with t, x, height, z_c, z_np, the estimated
            topography Z_c - Z_np, and the stability flag.

        Raises
        ------
        ValueError
            On non-finite values, non-increasing x, mismatched lengths or speed <= 0.
        """
        check_size("x", x, MAX_LINE_PIXELS)
        x = check_array("x", x, "m", ndim=1, min_size=2, increasing=True, low=-MAX_POSITION,
                        high=MAX_POSITION)
        h = check_array("height", height, "m", ndim=1)
        if h.size != x.size:  # name both: either may be the wrong one
            raise ValueError(f"height must have as many values as x ({x.size}), got {h.size}")
        speed = _P["speed"].check(speed)
        setpoint = _P["setpoint"].check(setpoint)
        n = x.size
        t_trace = (x - x[0]) / speed
        t_retrace = t_trace[-1] + (x[-1] - x[::-1]) / speed
        t_all = np.concatenate((t_trace, t_retrace[1:]))
        h_all = np.concatenate((h, h[::-1][1:]))
        z0 = self.steady_state(setpoint, h[0])
        z_c, z_np = polygon_response(self._forms["step"], self._forms["ramp"], t_all,
                                     h_all - h[0], None)
        z_c = z_c + z0.z_c
        z_np = z_np + z0.z_np
        trace = ScanPass(t_trace, x, h, z_c[:n], z_np[:n])
        retrace = ScanPass(t_retrace, x[::-1], h[::-1], z_c[n - 1:], z_np[n - 1:])
        return ScanLine(trace, retrace, bool(self.is_stable()), setpoint, speed,
                        self._offset(setpoint))

    def _offset(self, setpoint):
        z = self.steady_state(setpoint, 0.0)
        return float(z.z_c - z.z_np)  # estimate - T at equilibrium (for T = 0 when K_I = 0)
