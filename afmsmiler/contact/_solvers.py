"""Vectorised root finders shared by the contact models (private).

Every equation solved in :mod:`afmsmiler.contact` is, after a change of variable, ``g(x) = 0`` with
``g`` increasing on a known bracket ``[lo, hi]``. :func:`bracketed_newton` runs Newton's method on
a whole array at once, keeps the bracket up to date from the sign of ``g`` and falls back to
bisection whenever a Newton step would leave it, so it converges for every element (quadratically
near the root) and stops when the steps reach round-off.
"""
from __future__ import annotations

import numpy as np

EPS = np.finfo(float).eps


def bracketed_newton(func, lo, hi, x0, *, maxiter: int = 100, rtol: float = 4 * EPS):
    """Solve ``g(x) = 0`` elementwise for increasing ``g`` with a root in ``[lo, hi]``.

    Parameters
    ----------
    func : callable
        ``func(x) -> (g, dg)``, both arrays shaped like ``x``.
    lo, hi : ndarray
        Brackets, ``g(lo) <= 0 <= g(hi)``.
    x0 : ndarray
        Starting points inside the brackets.
    maxiter : int
        Iteration cap (bisection alone would need about 60 for full precision).
    rtol : float
        Stop when, for every element, the step or the bracket is below ``rtol * |x|`` (or the
        residual is exactly zero): round-off then decides the last digits.

    Returns
    -------
    ndarray
        The roots.
    """
    x = np.array(x0, dtype=float, copy=True)
    lo = np.array(lo, dtype=float, copy=True)
    hi = np.array(hi, dtype=float, copy=True)
    for _ in range(maxiter):
        g, dg = func(x)
        above = g > 0
        hi = np.where(above, x, hi)
        lo = np.where(above, lo, x)
        with np.errstate(divide="ignore", invalid="ignore"):
            xn = x - g / dg
        outside = ~((xn >= lo) & (xn <= hi))  # also catches NaN from dg == 0
        xn = np.where(outside, 0.5 * (lo + hi), xn)
        step = np.abs(xn - x)
        x = xn
        tol = rtol * np.abs(x)
        if np.all((step <= tol) | (g == 0) | (hi - lo <= tol)):
            break
    return x
