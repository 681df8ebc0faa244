"""The deformed sample surface around a rigid axisymmetric tip (for drawing the contact).

Inside the contact (rho <= a) the surface follows the tip: u(rho) = Z_s - h(rho), with h the tip's
height above its apex. Outside, Sneddon's solution for an axisymmetric punch (Sneddon, Int. J.
Eng. Sci. 3, 47 (1965)) reads, with D(t) the indentation at which the contact radius is t::

    u(rho) = (2 / pi) integral_0^a (Z_s - D(t)) / sqrt(rho^2 - t^2) dt
           = (2 / pi) integral_0^asin(a / rho) (Z_s - D(rho sin theta)) d theta

(the second form has a smooth integrand and is summed by Gauss-Legendre quadrature). For the
paraboloid it is Hertz's u = [(2 a^2 - rho^2) asin(a / rho) + a sqrt(rho^2 - a^2)] / (pi R). The
four-sided pyramid is drawn through its axisymmetric equivalent, the cone with the same D(t).

With adhesion (JKR) the contact radius a is larger than the elastic one at the same Z_s: the
pressure is Hertz's for the contact radius a plus a flat punch's of radius a (Johnson, Kendall
and Roberts 1971; K. L. Johnson, Contact Mechanics (1985), sec. 5.5), so the surface is the
elastic one of contact radius a, indented by D(a), plus the punch's displacement
(2 / pi) (Z_s - D(a)) asin(a / rho) outside and Z_s - D(a) inside. Z_s - D(a) < 0: the surface is
pulled up into a neck around the tip, and with Z_s < 0 the apex is above the undeformed surface
while still touching it.
"""
from __future__ import annotations

import math

import numpy as np

from ..validation import check_array, check_finite, check_instance, check_range
from .indent import IndentationCurve
from .tips import Pyramidal, Tip

__all__ = ["surface_displacement", "contact_surface"]

_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(48)


def surface_displacement(tip, z_s, rho, *, contact_radius=None):
    """Downward displacement u(rho) of the sample surface in m at indentation ``z_s``.

    Parameters
    ----------
    tip : Tip
        The tip shape.
    z_s : float
        Indentation at the apex in m: >= 0 (<= R for a sphere) for an elastic contact, any sign
        with ``contact_radius`` (a JKR neck has Z_s < 0).
    rho : array_like
        Distances from the axis in m, >= 0.
    contact_radius : float, optional
        The contact radius a in m of an adhesive contact (an
        :class:`~afmsmiler.contact.IndentationCurve`'s ``contact_radius``); by default the
        elastic one, r(Z_s).

    Returns
    -------
    ndarray
        u(rho) in m (positive: pushed down), shaped like ``rho``; u(0) = Z_s, u -> 0 far away.

    Raises
    ------
    TypeError
        If ``tip`` is not a Tip.
    ValueError
        On a non-finite or (elastic) negative ``z_s``, a negative ``rho`` or contact radius, or
        a contact radius beyond a sphere's radius.
    """
    check_instance("tip", tip, Tip)
    rho = check_array("rho", rho, "m", low=0.0)
    if contact_radius is None:
        z_s = check_range("z_s", z_s, 0.0, tip.depth_limit, "m")
        a = tip.contact_radius(z_s)
    else:
        z_s = check_finite("z_s", z_s, "m")
        a = check_range("contact_radius", contact_radius, 0.0, tip.max_radius, "m",
                        high_inclusive=False)
    out = np.zeros_like(rho)
    if a <= 0:
        return out
    punch = z_s - tip._depth(np.array(a))  # 0 for an elastic contact, < 0 for a JKR neck
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
    integrand = (z_s - punch) - tip._depth(r_out[:, None] * np.sin(theta))
    out[~inside] = (2.0 / math.pi) * (0.5 * theta_max * (integrand @ _WEIGHTS)
                                      + float(punch) * theta_max)
    return out


def contact_surface(tip, current, rho):
    """Downward displacement u(rho) in m of the surface in the state ``current`` (its first point).

    The model's :func:`surface_displacement` at the state's indentation and
    contact radius (an adhesive neck included), zero out of contact: what the figure and the 3D
    view both draw.

    Parameters
    ----------
    tip : Tip
        The tip shape.
    current : IndentationCurve
        The state (its first point).
    rho : array_like
        Distances from the axis in m, >= 0.

    Returns
    -------
    ndarray
        u in m, shaped like ``rho``.
    """
    check_instance("tip", tip, Tip)
    check_instance("current", current, IndentationCurve)
    rho = check_array("rho", rho, "m", low=0.0)
    if current.in_contact[0] and float(current.contact_radius[0]) > 0:
        return surface_displacement(tip, float(current.z_s[0]), rho,
                                    contact_radius=float(current.contact_radius[0]))
    return np.zeros_like(rho)
