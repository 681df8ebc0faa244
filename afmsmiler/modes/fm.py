"""Frequency-modulation (non-contact) AFM: the frequency shift from a force, and back.

In FM-AFM the lever oscillates at its own resonance with a constant amplitude A; a tip-sample
force F(z) shifts the resonance frequency by df. Over a cycle the tip moves between the distance
of closest approach z (the lower turning point) and z + 2 A. First-order perturbation theory
(Giessibl, Phys. Rev. B 56, 16010 (1997), Eq. (5) written in the closest distance) gives for
any amplitude::

    df(z) = -f0 / (pi k A) * integral_{-1}^{1} F(z + A (1 + u)) u / sqrt(1 - u^2) du

which tends to the force-gradient result df = -f0 / (2 k) dF/dz for A much smaller than the
force's decay length. The integrable endpoint singularity is the weight 1 / sqrt(1 - u^2) of
Gauss-Chebyshev quadrature (of the first kind): integral g(u) / sqrt(1 - u^2) du = (pi / n)
sum g(u_i) at the nodes u_i = cos((2 i - 1) pi / (2 n)), exact for polynomials g of degree
< 2 n; the nodes crowd at u = -1 where a short-range force is largest
(:func:`frequency_shift`, vectorised over z).

The inverse, the force from a measured df(z) curve, is the Sader-Jarvis formula (Sader and
Jarvis, Appl. Phys. Lett. 84, 1801 (2004), Eq. (9)), with the normalised shift
Omega(z) = df(z) / f0::

    F(z) = 2 k integral_z^inf [(1 + A^(1/2) / (8 sqrt(pi (t - z)))) Omega(t)
                               - A^(3/2) / sqrt(2 (t - z)) dOmega/dt] dt

accurate to a few per cent for any amplitude (their Fig. 1). The 1 / sqrt(t - z) poles are
integrated exactly (product integration: Omega and dOmega/dt linear between the samples, their
products with (t - z)^(-1/2) integrated in closed form), which is the careful version of the
small correction terms Sader and Jarvis add for the interval next to the pole;
the force is taken as zero beyond the last sample (:func:`sader_jarvis`).

Validity of the round trip (``tests/test_modes_fm.py``): the formula itself is approximate, to
a few per cent of the peak force when A is comparable to the force's decay length lambda (Sader
and Jarvis's Fig. 1; here up to 6 % for a Morse force at A = 0.1 lambda and A = lambda, the same
as an adaptive quadrature of Eq. (9) gives). Force -> df -> force agrees within 1 % of the peak
|F| for A below lambda / 100 (the force-gradient regime) or above 10 lambda, at every distance
from the first sample on, provided that the samples are spaced by less than lambda / 20 and that
the force at the last sample is below 1 % of the force recovered (the curve is cut there and
the force beyond taken as zero: for F ~ 1 / z^2 that is z below a tenth of the last distance).
For the van der Waals + DMT force of the dynamic modes the same holds for closest distances
above the contact distance a0 at any amplitude; a curve that starts in contact is recovered to
some per cent of the adhesion force near a0 (the force's kink there is not a smooth curve), and
within 1 % again from a few a0 on.

Module (g) of the AFM SMILER toolkit ("AFM SMILER: A Scale Model Interactive Learning Extended
Reality Toolkit for Atomic Force Microscopy Created with Digital Twin Technology") only animates
the modes; this module computes what the frequency-modulation mode measures. See also Giessibl,
Rev. Mod. Phys. 75, 949 (2003), section V.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import parameters
from ..parameters import Parameter, read_only
from ..validation import check_array, check_integer

__all__ = ["frequency_shift", "sader_jarvis", "force_gradient_shift", "frequency_shift_curve",
           "FrequencyShiftCurve", "PARAMETERS", "LIMITS",
           "SPRING_CONSTANT", "RESONANCE_FREQUENCY", "AMPLITUDE"]

# -- the parameter vocabulary of the FM mode ------------------------------------------------
# Defaults: a silicon non-contact lever (k = 40 N/m, f0 = 300 kHz, e.g. NanoWorld/Nanosensors
# NCH) at A = 5 nm; a qPlus sensor (k = 1800 N/m, f0 = 32.768 kHz, A of 50 pm) lies in range.
#: Lever spring constant k.
SPRING_CONSTANT = parameters.SPRING_CONSTANT.with_(default=40.0, slider_low=0.1,
                                                   slider_high=5000.0, label="spring constant k")
#: Free resonance frequency f0 of the lever (the FM loop keeps it oscillating there).
RESONANCE_FREQUENCY = parameters.RESONANCE_FREQUENCY
#: Oscillation amplitude A (half the peak-to-peak motion), kept constant by the FM loop.
AMPLITUDE = Parameter(name="amplitude", unit="m", display_unit="nm", default=5e-9, low=1e-13,
                      high=1e-6, slider_low=10e-12, slider_high=100e-9, log=True,
                      label="oscillation amplitude A")

#: Every user-settable quantity of the FM mode, by keyword name (read-only).
PARAMETERS = read_only({p.name: p for p in (SPRING_CONSTANT, RESONANCE_FREQUENCY, AMPLITUDE)})

# intervals the Sader-Jarvis inversion handles per block (rows x points; some 10 arrays of 8 MB)
_INVERSION_BLOCK = 1 << 20
#: Size limits (each call at them takes well under a second): distances per call, quadrature
#: nodes, samples of a df(z) curve to invert (the inversion costs O(n^2)).
LIMITS = read_only(dict(points=100_000, nodes=4096, nodes_x_points=4_000_000,
                        curve_points=5000))


def _check_force(force):
    if not callable(force):
        raise TypeError(f"force must be a callable F(z) in N of a distance z in m, got "
                        f"{type(force).__name__} {force!r:.60}")
    return force


def _call_force(force, z):
    raw = np.asarray(force(z))
    if np.iscomplexobj(raw):
        # float(complex) would warn (ComplexWarning) and drop the imaginary part
        raise TypeError(f"force must return real values in N, got {raw.dtype} (complex)")
    if raw.dtype.kind not in "biufO":
        raise TypeError(f"force must return real numbers in N, got an array of {raw.dtype}")
    try:
        values = raw.astype(float)
    except (TypeError, ValueError) as exc:  # objects such as Python complex numbers or None
        raise TypeError(f"force must return real numbers in N: {exc}") from None
    if values.shape != z.shape:
        raise ValueError(f"force must return an array of the shape of its argument {z.shape}, "
                         f"got shape {values.shape}")
    if not np.all(np.isfinite(values)):
        bad = z[~np.isfinite(values)]
        raise ValueError(f"force returned non-finite values at z = {bad.min():g} m (is the "
                         f"closest distance inside the sample?)")
    return values


def _check_lever(spring_constant, resonance_frequency, amplitude):
    return (SPRING_CONSTANT.check(spring_constant),
            RESONANCE_FREQUENCY.check(resonance_frequency), AMPLITUDE.check(amplitude))


def frequency_shift(force, z, *, spring_constant: float = SPRING_CONSTANT.default,
                    resonance_frequency: float = RESONANCE_FREQUENCY.default,
                    amplitude: float = AMPLITUDE.default, nodes: int = 256):
    """Frequency shift df in Hz at closest distances ``z`` (Giessibl's large-amplitude formula).

    Parameters
    ----------
    force : callable
        F(z) in N (positive repulsive) of an array of distances z in m, vectorised: called once
        with a 2-D array (points, nodes) of the distances the tip visits, it returns an array
        of that shape.
    z : float or array_like
        Distance of closest approach (the lower turning point) in m, at most
        ``LIMITS["points"]`` values.
    spring_constant : float
        Lever spring constant k in N/m.
    resonance_frequency : float
        Free resonance frequency f0 in Hz.
    amplitude : float
        Oscillation amplitude A in m.
    nodes : int
        Gauss-Chebyshev nodes over the cycle, 2 to ``LIMITS["nodes"]`` (exact when F is a
        polynomial of degree < 2 nodes - 1 over the cycle). The error falls exponentially once
        the nodes exceed about 4 sqrt(A / lambda) for a force decaying over lambda: 256 give
        1e-13 at A = 500 lambda and 3e-5 at A = 5000 lambda (then take 512).

    Returns
    -------
    float or ndarray
        df(z) in Hz, of the shape of ``z`` (negative for an attractive force that grows towards
        the sample).

    Raises
    ------
    TypeError
        If ``force`` is not callable, or returns values that are not real numbers (complex).
    ValueError
        Naming the argument out of range (before the force is called), or if the force returns
        a wrong shape or non-finite values.

    Notes
    -----
    df = -f0 / (pi k A) int_{-1}^{1} F(z + A (1 + u)) u / sqrt(1 - u^2) du (Giessibl 1997),
    by Gauss-Chebyshev quadrature of the first kind: -f0 / (k A n) sum_i F(z + A (1 + u_i)) u_i.

    Examples
    --------
    A linear force F = -c z has the gradient -c everywhere: df = f0 c / (2 k) for any A.

    >>> df = frequency_shift(lambda z: -2.0 * z, 1e-9, spring_constant=40.0,
    ...                      resonance_frequency=300e3, amplitude=5e-9)
    >>> round(float(df), 6)  # Hz: 300e3 * 2 / (2 * 40)
    7500.0
    """
    force = _check_force(force)
    k, f0, a = _check_lever(spring_constant, resonance_frequency, amplitude)
    z = check_array("z", z, "m", max_size=LIMITS["points"])
    nodes = check_integer("nodes", nodes, 2, LIMITS["nodes"])
    if z.size * nodes > LIMITS["nodes_x_points"]:
        raise ValueError(f"z.size x nodes must be at most {LIMITS['nodes_x_points']}, got "
                         f"{z.size} x {nodes}")
    u = np.cos((2 * np.arange(1, nodes + 1) - 1) * math.pi / (2 * nodes))
    visited = z.reshape(-1, 1) + a * (1.0 + u)
    f = _call_force(force, visited)
    df = -f0 / (k * a * nodes) * (f @ u)
    return df.reshape(z.shape) if z.ndim else float(df[0])


def force_gradient_shift(force_gradient, *, spring_constant: float = SPRING_CONSTANT.default,
                         resonance_frequency: float = RESONANCE_FREQUENCY.default):
    """Small-amplitude frequency shift df = -f0 / (2 k) dF/dz in Hz.

    Parameters
    ----------
    force_gradient : float or array_like
        dF/dz in N/m (the force gradient k_ts with the opposite sign).
    spring_constant : float
        Lever spring constant k in N/m.
    resonance_frequency : float
        Free resonance frequency f0 in Hz.

    Returns
    -------
    float or ndarray
        df in Hz, the limit of :func:`frequency_shift` for A -> 0.
    """
    k = SPRING_CONSTANT.check(spring_constant)
    f0 = RESONANCE_FREQUENCY.check(resonance_frequency)
    g = check_array("force_gradient", force_gradient, "N/m")
    out = -f0 / (2 * k) * g
    return out if g.ndim else float(out)


def sader_jarvis(z, df, *, spring_constant: float = SPRING_CONSTANT.default,
                 resonance_frequency: float = RESONANCE_FREQUENCY.default,
                 amplitude: float = AMPLITUDE.default):
    """Force F(z) in N recovered from a frequency-shift curve df(z) (Sader-Jarvis inversion).

    Parameters
    ----------
    z : array_like
        Distances of closest approach in m, strictly increasing, 3 to ``LIMITS["curve_points"]``
        values (need not be evenly spaced).
    df : array_like
        Frequency shift in Hz at each ``z`` (same length).
    spring_constant : float
        Lever spring constant k in N/m.
    resonance_frequency : float
        Free resonance frequency f0 in Hz.
    amplitude : float
        Oscillation amplitude A in m at which ``df`` was measured.

    Returns
    -------
    ndarray
        F at each ``z`` in N (zero at the last sample: the force is taken to vanish beyond it).

    Raises
    ------
    ValueError
        Naming the argument out of range, before any work.

    Notes
    -----
    F(z) = 2 k int_z^inf [(1 + A^(1/2) / (8 sqrt(pi (t - z)))) Omega - A^(3/2) /
    sqrt(2 (t - z)) dOmega/dt] dt with Omega = df / f0 (Sader and Jarvis 2004, Eq. (9)).
    Omega is linear between samples (the first term is the trapezoid rule); dOmega/dt, from
    second-order differences (``numpy.gradient``), too; the products with (t - z)^(-1/2) are
    integrated in closed form over each interval, so the pole at t = z costs no accuracy.
    The formula is good to a few per cent of the peak force (worst for A near the force's decay
    length), the discretisation to well below 1 % for samples spaced by less than a twentieth
    of the decay length; the force beyond the last sample is taken as zero (see the module
    notes for the range of validity); O(n^2) work, vectorised over the lower ends in blocks of
    :data:`_INVERSION_BLOCK` intervals.

    Examples
    --------
    The inversion of a small-amplitude df = -f0 / (2 k) dF/dz of F = -c / z^2 returns F (to
    the formula's own accuracy: its A^(1/2) term is 0.5 % of F here, at A / z = 0.001):

    >>> z = np.linspace(1e-9, 40e-9, 2000)
    >>> df = -300e3 / (2 * 40.0) * 2e-27 / z ** 3  # dF/dz for c = 1e-27 N m^2
    >>> f = sader_jarvis(z, df, spring_constant=40.0, resonance_frequency=300e3,
    ...                  amplitude=1e-12)
    >>> round(float(f[0] / (-1e-27 / z[0] ** 2)), 3)
    1.005
    """
    k, f0, a = _check_lever(spring_constant, resonance_frequency, amplitude)
    z = check_array("z", z, "m", ndim=1, min_size=3, increasing=True,
                    max_size=LIMITS["curve_points"])
    df = check_array("df", df, "Hz", ndim=1, size=z.size)
    omega = df / f0
    slope = np.gradient(omega, z, edge_order=2)
    c2 = math.sqrt(a) / (8 * math.sqrt(math.pi))
    c3 = a ** 1.5 / math.sqrt(2)
    # Over interval i, Omega and dOmega/dt are linear: v_i + b_i (t - z_i) with b_i = their step
    # over dz_i, so each pole term of row j (the lower end z_j) is sum_i I0[j, i] v_i +
    # W[j, i] b_i, with weights that depend on the distances alone (_sader_jarvis_weights)
    dz = np.diff(z)
    values = c2 * omega[:-1] - c3 * slope[:-1]
    steps = (c2 * np.diff(omega) - c3 * np.diff(slope)) / dz
    middle = 0.5 * (omega[:-1] + omega[1:]) * dz  # the trapezoid rule, summed from each z_j
    trapezoid = np.cumsum(middle[::-1])[::-1]
    force = np.zeros_like(z)
    for rows, i0, w in _sader_jarvis_weights(z):  # bounded: n / rows blocks
        force[rows] = 2 * k * (trapezoid[rows] + i0 @ values + w @ steps)
    return force


#: Most distances of a grid whose Sader-Jarvis weights are kept (two n x n matrices, 2 MB each
#: at this size), for the last two grids inverted: a panel inverts on one grid at every move.
_WEIGHTS_KEPT_POINTS = 512
_weights_kept: dict = {}


def _sader_jarvis_weights(z: np.ndarray):
    """Blocks ``(rows, I0, W)`` of the inversion's weights on the grid ``z`` (n values).

    For the lower end z_j (a row) and the interval [z_i, z_i+1] (a column, i >= j; zero
    below), with lo = z_i - z_j and hi = z_i+1 - z_j: I0 = int_lo^hi u^-1/2 du =
    2 (hi^1/2 - lo^1/2) and W = int_lo^hi (u - lo) u^-1/2 du = 2/3 (hi^3/2 - lo^3/2) - lo I0,
    the closed forms of a linear function over the pole (t - z_j)^-1/2. A grid of at most
    :data:`_WEIGHTS_KEPT_POINTS` values is computed once and kept (the last two grids); a larger
    one in blocks of :data:`_INVERSION_BLOCK` entries, one at a time, at each call.
    """
    if z.size > _WEIGHTS_KEPT_POINTS:
        return _weight_blocks(z)
    key = z.tobytes()
    blocks = _weights_kept.get(key)
    if blocks is None:
        blocks = list(_weight_blocks(z))
        for _, i0, w in blocks:
            i0.flags.writeable = w.flags.writeable = False
        if len(_weights_kept) >= 2:
            _weights_kept.pop(next(iter(_weights_kept)))
        _weights_kept[key] = blocks
    return blocks


def _weight_blocks(z: np.ndarray):
    n = z.size
    intervals = np.arange(n - 1)
    step = max(1, _INVERSION_BLOCK // n)
    for start in range(0, n - 1, step):  # bounded: n / step blocks
        j = np.arange(start, min(start + step, n - 1))
        inside = intervals[None, :] >= j[:, None]
        u = z[None, :] - z[j, None]
        lo = np.where(inside, u[:, :-1], 0.0)
        hi = np.where(inside, u[:, 1:], 0.0)
        root_hi, root_lo = np.sqrt(hi), np.sqrt(lo)
        i0 = 2 * (root_hi - root_lo)
        yield slice(start, int(j[-1]) + 1), i0, 2 / 3 * (hi * root_hi - lo * root_lo) - lo * i0


@dataclass(frozen=True)
class FrequencyShiftCurve:
    """A force curve, its frequency shift and the force recovered from it
    (:func:`frequency_shift_curve`), in SI units; figures draw it without computing again.

    Attributes
    ----------
    z : ndarray
        Distances of closest approach in m.
    force : ndarray
        The force F(z) in N put in.
    frequency_shift : ndarray
        df(z) in Hz at the amplitude (Giessibl).
    gradient_shift : ndarray
        The small-amplitude df = -f0 / (2 k) dF/dz in Hz (dF/dz by second-order differences of
        ``force``), for comparison.
    recovered_force : ndarray
        F(z) in N from ``frequency_shift`` by the Sader-Jarvis inversion.
    spring_constant, resonance_frequency, amplitude : float
        k in N/m, f0 in Hz, A in m.
    """

    z: np.ndarray
    force: np.ndarray
    frequency_shift: np.ndarray
    gradient_shift: np.ndarray
    recovered_force: np.ndarray
    spring_constant: float
    resonance_frequency: float
    amplitude: float

    @property
    def error(self) -> np.ndarray:
        """Recovered minus input force in N."""
        return self.recovered_force - self.force


def frequency_shift_curve(force, z, *, spring_constant: float = SPRING_CONSTANT.default,
                          resonance_frequency: float = RESONANCE_FREQUENCY.default,
                          amplitude: float = AMPLITUDE.default,
                          nodes: int = 256) -> FrequencyShiftCurve:
    """The FM round trip in one call: F(z) -> df(z) -> F(z) (what an FM panel shows).

    Parameters
    ----------
    force : callable
        F(z) in N of distances in m, vectorised (as for :func:`frequency_shift`).
    z : array_like
        Distances of closest approach in m, strictly increasing, 3 to
        ``LIMITS["curve_points"]`` values.
    spring_constant : float
        Lever spring constant k in N/m.
    resonance_frequency : float
        Free resonance frequency f0 in Hz.
    amplitude : float
        Oscillation amplitude A in m.
    nodes : int
        Gauss-Chebyshev nodes of :func:`frequency_shift`.

    Returns
    -------
    FrequencyShiftCurve

    Raises
    ------
    TypeError
        If ``force`` is not callable, or returns values that are not real numbers (complex).
    ValueError
        Naming the argument out of range, before the force is called.

    Examples
    --------
    >>> curve = frequency_shift_curve(lambda z: -1e-27 / z ** 2, np.linspace(1e-9, 40e-9, 400),
    ...                               amplitude=10e-9)
    >>> bool(abs(curve.error[0] / curve.force[0]) < 0.01)
    True
    """
    _check_force(force)
    k, f0, a = _check_lever(spring_constant, resonance_frequency, amplitude)
    z = check_array("z", z, "m", ndim=1, min_size=3, increasing=True,
                    max_size=LIMITS["curve_points"])
    nodes = check_integer("nodes", nodes, 2, LIMITS["nodes"])
    lever = dict(spring_constant=k, resonance_frequency=f0)
    f = _call_force(force, z)
    df = frequency_shift(force, z, amplitude=a, nodes=nodes, **lever)
    gradient = -f0 / (2 * k) * np.gradient(f, z, edge_order=2)
    return FrequencyShiftCurve(z, f, df, gradient, sader_jarvis(z, df, amplitude=a, **lever),
                               k, f0, a)
