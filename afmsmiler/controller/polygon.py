"""Response of a linear system to a polygon (piecewise-linear) input, in O(N), from closed forms.

The paper's method: the polygon through the knots (t_k, u_k) is a step u_0 at t_0 plus ramps of
slope change Delta_k = s_k - s_{k-1} starting at every knot t_k (the slope after the last knot is
zero: the input is held). The response is the superposition of the closed-form step and ramp
responses (:mod:`afmsmiler.controller.closed_forms`), which costs O(N^2) if every ramp is
evaluated at every time.

Here it costs O(N): the forced (polynomial) parts of all the ramps add up to
q1 (u(t) - u_0) + q0 s(t), and each exponential block's coefficients are carried from knot to knot
in local time tau = t - t_k. A term c t^j e^{p t} started at t_j becomes, after a shift by h,
e^{p h} sum_i C(j, i) h^(j-i) c t^i: a first-order recursion x_k = e^{p h_k} x_{k-1} + d_k per
coefficient, run by ``scipy.signal.lfilter`` (C speed) when the knots are equally spaced and by a
vectorised associative scan (log2 N passes) when they are not. This is the exact first-order-hold
discretisation of the system, with no step-size error.

When every root is simple (distinct real, complex pairs) the same superposition is arranged so
that nothing cancels: a simple root p with residue R contributes R (e^{p t} - 1 - p t) / p^2 to
the ramp response, whose mode and polynomial parts are each of order R / p^2 and cancel to
order R t^2 when |p| t is small (a slow root, e.g. a weak integrator: up to 4e-8 of the peak at
the corners of the panel's sliders). Carried from knot to knot,
z_k = e^{p h} z_{k-1} + h (phi1(p h) u_{k-1} + phi2(p h) (u_k - u_{k-1})) with
phi1(x) = (e^x - 1) / x and phi2(x) = (e^x - 1 - x) / x^2 evaluated without cancellation, and
y = feedthrough u + Re sum R z, where R = p times the step response's mode coefficient.
Repeated roots keep the coefficient recursion above, for a block of any length: a double root
carries 2 coefficients, a triple root 3, and a cluster of three close roots (expanded about their
mean, see :mod:`afmsmiler.controller.closed_forms`) the 5 to 16 terms of its series, with
the sequences F_j(k) = sum_{i <= k} Delta_i (t_k - t_i)^j e^{p (t_k - t_i)}, each one recursion.
"""
from __future__ import annotations

import cmath
from math import comb as _binom

import numpy as np
from scipy.signal import lfilter

__all__ = ["polygon_response"]

_UNIFORM_RTOL = 1e-12


def _recursion(lam, d, uniform):
    """x_k = lam_k x_{k-1} + d_k along the last axis, x_{-1} = 0 (lam_0 is not used)."""
    if d.shape[-1] < 2:
        return d.copy()
    if uniform:
        return lfilter([1.0], [1.0, -lam[1]], d, axis=-1)
    x = d.copy()
    a = lam.astype(complex).copy()
    a[0] = 0.0
    n = x.shape[-1]
    shift = 1
    while shift < n:
        x[..., shift:] = x[..., shift:] + a[shift:] * x[..., :-shift]
        a[shift:] = a[shift:] * a[:-shift]
        shift *= 2
    return x


_PHI_SERIES = 0.5  # |x| below which phi1, phi2 are summed as series (18 terms: < 1e-20)
_FACT = [float(np.prod(np.arange(1, k + 1))) for k in range(21)]


def _phi12(x):
    """phi1(x) = (e^x - 1) / x and phi2(x) = (e^x - 1 - x) / x^2 (complex), without cancellation."""
    x = np.asarray(x, dtype=complex)
    small = np.abs(x) < _PHI_SERIES
    xs = np.where(small, x, 0.0)
    phi1 = np.zeros_like(x)
    phi2 = np.zeros_like(x)
    for k in range(17, -1, -1):  # Horner: sum x^k / (k + 1)!, sum x^k / (k + 2)!
        phi1 = phi1 * xs + 1.0 / _FACT[k + 1]
        phi2 = phi2 * xs + 1.0 / _FACT[k + 2]
    if not small.all():
        xl = np.where(small, 1.0, x)
        em1 = np.expm1(xl)
        phi1 = np.where(small, phi1, em1 / xl)
        phi2 = np.where(small, phi2, (em1 - xl) / xl ** 2)
    return phi1, phi2


def _phi12_scalar(x: complex):
    """:func:`_phi12` for one number, in plain Python (a scan's uniform spacing)."""
    if abs(x) < _PHI_SERIES:
        phi1 = phi2 = 0.0
        for k in range(17, -1, -1):
            phi1 = phi1 * x + _INV_FACT[k + 1]
            phi2 = phi2 * x + _INV_FACT[k + 2]
        return complex(phi1), complex(phi2)
    try:
        em1 = cmath.exp(x) - 1.0
    except OverflowError:  # an unstable mode over one step: inf (then nan), as numpy gives
        return tuple(complex(f) for f in _phi12(x))
    return em1 / x, (em1 - x) / (x * x)


_INV_FACT = [1.0 / f for f in _FACT]


def _simple_modes(step_forms, u, hh, slope, idx, tau, uniform):
    """Outputs for simple roots only: the cancellation-free recursion of the module docstring."""
    n_out = len(step_forms)
    u_now = u if idx is None else u[..., idx] + slope[..., idx] * tau
    out = np.empty((n_out,) + u_now.shape)
    for o in range(n_out):
        out[o] = step_forms[o].feedthrough * u_now
    u_prev = np.zeros(u.shape)
    u_prev[..., 1:] = u[..., :-1]
    step = u - u_prev
    step[..., 0] = 0.0  # no segment ends at the first knot: z_0 = 0
    for b, (p, _) in enumerate(step_forms[0].blocks):
        if uniform and hh.size > 1:  # one spacing: scalars (hh[0] = 0 multiplies u_prev = 0)
            lam = np.array([1.0, np.exp(p * hh[1])])
            phi1, phi2 = (hh[1] * f for f in _phi12_scalar(complex(p * hh[1])))
        else:
            lam = np.exp(p * hh)
            phi1, phi2 = (hh * f for f in _phi12(p * hh))
        z = _recursion(lam, phi1 * u_prev + phi2 * step, uniform)
        if idx is not None:
            ph1, ph2 = _phi12(p * tau)
            z = (np.exp(p * tau) * z[..., idx] + tau * ph1 * u[..., idx]
                 + tau ** 2 * ph2 * slope[..., idx])
        for o in range(n_out):
            residue = step_forms[o].blocks[b][1][0] * p  # the step response's mode is R / p
            out[o] += (residue * z).real
    return out


def _shifted(seq):
    """seq_{k-1} along the last axis, with 0 for k = 0."""
    out = np.zeros_like(seq)
    out[..., 1:] = seq[..., :-1]
    return out


def polygon_response(step_forms, ramp_forms, t_knots, u_knots, t_eval=None, *, uniform=None):
    """Outputs of a linear system driven by the polygon through (t_knots, u_knots), from rest.

    The input is 0 before ``t_knots[0]``, steps to ``u_knots[0]`` there, follows the polygon and
    is held at ``u_knots[-1]`` after the last knot. Inputs are not validated here (see
    :meth:`afmsmiler.controller.ContactLoop.response`).

    Parameters
    ----------
    step_forms, ramp_forms : sequence of ClosedForm
        Step and ramp closed forms of each output (all with the same roots, in the same order).
    t_knots : numpy.ndarray
        Knot times in s, shape (N,), strictly increasing.
    u_knots : numpy.ndarray
        Input at the knots, shape (..., N): a batch of polygons on the same knot times.
    t_eval : numpy.ndarray, optional
        Evaluation times in s, shape (M,); default: the knots.
    uniform : bool, optional
        True when the caller knows the knots are equally spaced (e.g. ``arange(N) * dt``, whose
        computed differences scatter by N eps relative, too much for the automatic test on long
        inputs): the spacing is then taken as (t_N - t_0) / (N - 1) exactly. Default: detect it.

    Returns
    -------
    numpy.ndarray
        Shape (n_outputs, ..., M). The modes of an unstable system grow like e^{sigma t} and
        overflow to inf (then nan) once that exceeds ~1e308; no warning is raised for it.
    """
    with np.errstate(over="ignore", invalid="ignore"):
        return _polygon_response(step_forms, ramp_forms, t_knots, u_knots, t_eval, uniform)


def _polygon_response(step_forms, ramp_forms, t_knots, u_knots, t_eval, uniform):
    t = np.asarray(t_knots, dtype=float)
    u = np.asarray(u_knots, dtype=float)
    n = t.size
    if uniform and n > 1:
        h = np.full(n - 1, (t[-1] - t[0]) / (n - 1))
    else:
        h = np.diff(t)
    slope = np.zeros(u.shape)
    if n > 1:
        slope[..., :-1] = np.diff(u, axis=-1) / h
    delta = slope.copy()
    delta[..., 1:] -= slope[..., :-1]
    u0 = u[..., :1]
    if uniform is None:
        uniform = n < 3 or np.ptp(h) <= _UNIFORM_RTOL * h.mean()
    elapsed = t - t[0]
    hh = np.concatenate(([0.0], h))

    if t_eval is None:
        idx, tau, before = None, None, None
    else:
        te = np.asarray(t_eval, dtype=float)
        idx = np.searchsorted(t, te, side="right") - 1
        before = idx < 0
        idx = np.maximum(idx, 0)
        tau = te - t[idx]

    if all(len(cs) == 1 for _, cs in step_forms[0].blocks):
        out = _simple_modes(step_forms, u, hh, slope, idx, tau, uniform)
        if before is not None and before.any():
            out[..., before] = 0.0
        return out

    n_out = len(step_forms)
    if idx is None:
        u_now = u
        s_now = slope
    else:
        s_now = slope[..., idx]
        u_now = u[..., idx] + s_now * tau
    out = np.empty((n_out,) + u_now.shape)
    for o in range(n_out):
        out[o] = (step_forms[o].q0 * u0 + ramp_forms[o].q1 * (u_now - u0)
                  + ramp_forms[o].q0 * s_now)

    has_step = bool(np.any(u0 != 0))
    delta_c = delta.astype(complex)
    for b, (p, _) in enumerate(step_forms[0].blocks):
        m = len(step_forms[0].blocks[b][1])
        lam = np.exp(p * hh)
        # basis sequences: F (driven by the slope changes), G, K (carried polynomial terms)
        # F_j(k) = sum_{i <= k} Delta_i (t_k - t_i)^j e^{p (t_k - t_i)}, carried by
        # F_j(k) = lam_k (F_j(k-1) + sum_{i < j} C(j, i) h_k^(j-i) F_i(k-1)) (+ Delta_k for j = 0)
        basis = [_recursion(lam, delta_c, uniform)]
        shifted, lam_h = [], [lam]  # F_i(k-1) and lam_k h_k^n
        for j in range(1, m):
            shifted.append(_shifted(basis[j - 1]))
            lam_h.append(lam_h[-1] * hh)
            drive = lam_h[1] * shifted[j - 1] * j
            for i in range(j - 1):
                drive = drive + (_binom(j, i) * lam_h[j - i]) * shifted[i]
            basis.append(_recursion(lam, drive, uniform))
        E = np.exp(p * elapsed) if has_step else None
        for o in range(n_out):
            c = ramp_forms[o].blocks[b][1]
            sc = step_forms[o].blocks[b][1]
            # coefficient j of the block at each knot, in local time tau = t - t_k
            n_coef = 1 if idx is None else m
            coef = []
            for j in range(n_coef):
                a = c[j] * basis[0]
                for i in range(j + 1, m):
                    a = a + c[i] * _binom(i, j) * basis[i - j]
                if has_step:
                    shift_poly = sc[j]
                    for i in range(j + 1, m):
                        shift_poly = shift_poly + sc[i] * _binom(i, j) * elapsed ** (i - j)
                    a = a + u0 * (E * shift_poly)
                coef.append(a)
            if idx is None:
                out[o] += coef[0].real
            else:
                poly = np.zeros(u_now.shape, dtype=complex)
                for j in reversed(range(m)):
                    poly = poly * tau + coef[j][..., idx]
                out[o] += (poly * np.exp(p * tau)).real
    if before is not None and before.any():
        out[..., before] = 0.0
    return out

