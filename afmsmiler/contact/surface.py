"""The deformed sample surface around a rigid axisymmetric tip (for drawing the contact).

Inside the contact (rho <= a) the surface follows the tip: u(rho) = Z_s - h(rho), with h the tip's
height above its apex. Outside, Sneddon's solution for an axisymmetric punch (Sneddon, Int. J.
Eng. Sci. 3, 47 (1965)) reads, with D(t) the indentation at which the contact radius is t::

    u(rho) = (2 / pi) integral_0^a (Z_s - D(t)) / sqrt(rho^2 - t^2) dt
           = (2 / pi) integral_0^asin(a / rho) (Z_s - D(rho sin theta)) d theta

(the second form has a smooth integrand and is summed by Gauss-Legendre quadrature). For the
paraboloid it is Hertz's u = [(2 a^2 - rho^2) asin(a / rho) + a sqrt(rho^2 - a^2)] / (pi R). The
four-sided pyramid is drawn through its axisymmetric equivalent, the cone with the same D(t).
"""
from __future__ import annotations

import math

import numpy as np

from ..validation import check_array
from .tips import Pyramidal, Tip

__all__ = ["surface_displacement"]

_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(48)


def surface_displacement(tip, z_s, rho):
    """Downward displacement u(rho) of the sample surface in m at indentation ``z_s``.

    Parameters
    ----------
    tip : Tip
        The tip shape.
    z_s : float
        Indentation at the apex in m, >= 0 (<= R for a sphere).
    rho : array_like
        Distances from the axis in m, >= 0.

    Returns
    -------
    ndarray
        u(rho) in m (positive: pushed down), shaped like ``rho``; u(0) = Z_s, u -> 0 far away.
    """
    if not isinstance(tip, Tip):
        raise ValueError(f"tip must be a Tip, got {tip!r}")
    a = tip.contact_radius(z_s)
    z_s = float(z_s)
    rho = check_array("rho", rho, "m", low=0.0)
    out = np.zeros_like(rho)
    if a <= 0:
        return out
    inside = rho <= a
    r_in = rho[inside]
    if isinstance(tip, Pyramidal):
        h = 2.0 / math.pi * tip._depth(r_in)
    else:
        h = tip.profile(r_in)
    out[inside] = z_s - h
    r_out = rho[~inside]
    theta_max = np.arcsin(a / r_out)
    theta = 0.5 * theta_max[:, None] * (_NODES[None, :] + 1.0)
    integrand = z_s - tip._depth(r_out[:, None] * np.sin(theta))
    out[~inside] = (2.0 / math.pi) * 0.5 * theta_max * (integrand @ _WEIGHTS)
    return out
