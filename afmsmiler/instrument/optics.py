"""Paraxial optics of an optical-beam-deflection head: rays, a steering mirror, Gaussian beams.

The pieces that :mod:`afmsmiler.instrument.alignment` assembles into the laser path of an AFM
head, each a textbook formula (SI units throughout):

* Ray transfer (ABCD) matrices of free space and a thin lens, acting on a paraxial ray
  (height x in m, slope theta in rad) (Siegman, *Lasers*, University Science Books 1986, ch. 15;
  Saleh and Teich, *Fundamentals of Photonics*, Wiley 2007, sec. 1.4). A collimated beam tilted
  by theta and a lens of focal length f meet in the lens's back focal plane at x = f theta, and a
  steering mirror in the front focal plane makes the focused beam telecentric (its slope there is
  zero, whatever theta): :func:`focal_plane_ray`.
* The law of reflection in vector form, r = d - 2 (d . n) n, for the beam deviation of a tilted
  fold mirror: a tilt phi about the normal of the plane of incidence turns the beam by 2 phi in
  that plane, a tilt psi about the in-plane axis by 2 psi cos(i) out of it (i the angle of
  incidence) to first order: :func:`mirror_deviation`.
* A Gaussian beam (1/e^2 intensity radius w): the waist w0 = w_in f / sqrt(f^2 + z_in^2) that a
  lens of focal length f makes of a collimated beam of radius w_in with its waist at the lens
  (z_in = pi w_in^2 / lambda its Rayleigh range; ~ lambda f / (pi w_in) for f << z_in), the
  Rayleigh range z_R = pi w0^2 / lambda and the radius w(z) = w0 sqrt(1 + (z / z_R)^2) a distance
  z from the waist (Saleh and Teich, sec. 3.1 and 3.2, "transmission through a thin lens").
* The share of a Gaussian spot's power inside an interval, a rectangle, and the spot's
  intensity-weighted first and second moments over an interval (truncated normal moments, with
  sigma = w / 2 because exp(-2 x^2 / w^2) = exp(-x^2 / (2 sigma^2))).
"""
from __future__ import annotations

import math

import numpy as np
from scipy.special import ndtr

from ..validation import check_array, check_range, check_real

#: Largest length in m the functions accept (a bench is metres long; beyond, nothing is optics
#: of an AFM and the squares of lengths would leave double precision).
MAX_LENGTH = 1e3
#: Shortest waist and wavelength in m (an X-ray's): below, a Gaussian beam is meaningless here.
MIN_LENGTH = 1e-12

__all__ = ["MAX_LENGTH", "MIN_LENGTH", "free_space", "thin_lens", "focal_plane_ray",
           "mirror_deviation", "focused_waist", "rayleigh_range", "beam_radius_at",
           "interval_fraction", "rectangle_fraction", "interval_moments"]


def _length(name, value, low=MIN_LENGTH, high=MAX_LENGTH):
    """A length in m in [low, high] (ValueError naming it otherwise)."""
    return check_range(name, value, low, high, "m")


def _end(name, value):
    """An interval's end in m: a real number in [-MAX_LENGTH, MAX_LENGTH] or -inf/inf."""
    if isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(
            value, (bool, np.bool_)) and math.isinf(check_real(name, value)):
        return float(value)
    return check_range(name, value, -MAX_LENGTH, MAX_LENGTH, "m")


def free_space(distance: float) -> np.ndarray:
    """The ray transfer matrix [[1, d], [0, 1]] of free space of length ``distance``.

    Parameters
    ----------
    distance : float
        Propagation distance d in m, in [0, MAX_LENGTH].

    Returns
    -------
    ndarray, shape (2, 2)
        Acts on a column (height in m, slope in rad).
    """
    d = _length("distance", distance, 0.0)
    return np.array([[1.0, d], [0.0, 1.0]])


def thin_lens(focal_length: float) -> np.ndarray:
    """The ray transfer matrix [[1, 0], [-1/f, 1]] of a thin lens of focal length f.

    Parameters
    ----------
    focal_length : float
        f in m, in [MIN_LENGTH, MAX_LENGTH] (a converging lens).

    Returns
    -------
    ndarray, shape (2, 2)
    """
    f = _length("focal_length", focal_length)
    return np.array([[1.0, 0.0], [-1.0 / f, 1.0]])


def focal_plane_ray(slope, focal_length: float):
    """Height and slope in the back focal plane of a ray leaving the front focal plane on axis.

    The steering mirror sits on the axis in the lens's front focal plane and sends the collimated
    beam off with a ``slope``; after free space f, the lens and free space f the ray is at
    x = f slope with slope 0 (the matrix [[0, f], [-1/f, 0]]): the spot moves across the chip
    parallel to itself, so moving it does not tilt the reflected beam.

    Parameters
    ----------
    slope : float or array_like
        Slope of the beam leaving the mirror in rad (a paraxial slope, tan of the angle), at most
        1 either way.
    focal_length : float
        f in m, in [MIN_LENGTH, MAX_LENGTH].

    Returns
    -------
    tuple of ndarray
        (height in m, slope in rad), each of the shape of ``slope``.
    """
    slope = check_array("slope", slope, "rad", low=-1.0, high=1.0)
    f = _length("focal_length", focal_length)
    m = free_space(f) @ thin_lens(f) @ free_space(f)  # the ray starts on the axis: (0, slope)
    return m[0, 1] * slope, m[1, 1] * slope


def mirror_deviation(tilt_in_plane: float, tilt_out_of_plane: float,
                     incidence: float = math.pi / 4):
    """Slopes of the beam after a fold mirror tilted from its nominal orientation.

    The beam arrives along +x, the mirror (nominal normal at ``incidence`` to it, in the x-z
    plane) sends it down along -z. The mirror's normal is rotated by ``tilt_in_plane`` about y
    (the normal of the plane of incidence) and by ``tilt_out_of_plane`` about the in-plane axis
    of the mirror's surface; the reflected direction is r = d - 2 (d . n) n exactly, returned as
    paraxial slopes about the nominal direction. To first order the in-plane slope is
    2 tilt_in_plane and the out-of-plane slope 2 tilt_out_of_plane cos(incidence).

    Parameters
    ----------
    tilt_in_plane : float
        Rotation of the mirror about the normal of the plane of incidence in rad, |.| <= 0.2.
    tilt_out_of_plane : float
        Rotation about the in-plane axis of the mirror's surface in rad, |.| <= 0.2.
    incidence : float
        Nominal angle of incidence i in rad, in (0, pi/2) (pi/4: a 90 degree fold).

    Returns
    -------
    tuple of float
        (in-plane slope, out-of-plane slope) in rad of the reflected beam (tangents of the
        angles to the nominal reflected direction).
    """
    a = check_range("tilt_in_plane", tilt_in_plane, -0.2, 0.2, "rad")
    b = check_range("tilt_out_of_plane", tilt_out_of_plane, -0.2, 0.2, "rad")
    i = check_range("incidence", incidence, 0.0, math.pi / 2, "rad", low_inclusive=False,
                    high_inclusive=False)
    u, w = _mirror_slopes(np.asarray(a), np.asarray(b), i)
    return float(u), float(w)


def _mirror_slopes(a, b, i):
    """:func:`mirror_deviation` without checks, for arrays of tilts ``a``, ``b`` (rad)."""
    a, b = np.broadcast_arrays(np.asarray(a, float), np.asarray(b, float))
    d = np.array([1.0, 0.0, 0.0])
    e_w = np.array([0.0, 1.0, 0.0])
    normal0 = np.array([-math.cos(i), 0.0, -math.sin(i)])
    reflected0 = d - 2 * (d @ normal0) * normal0        # the nominal output direction
    in_plane_axis = np.cross(normal0, e_w)              # in the mirror, in the x-z plane
    n = _rotate(_rotate(np.broadcast_to(normal0, a.shape + (3,)), e_w, a), in_plane_axis, b)
    r = d - 2 * (n @ d)[..., None] * n                  # the law of reflection, exactly
    e_u = np.cross(e_w, reflected0)                     # the output frame, normal to r0
    along = r @ reflected0
    return r @ e_u / along, r @ e_w / along


def _rotate(v, axis, angle):
    """Rodrigues' rotation of vectors ``v`` (..., 3) about the unit ``axis`` by ``angle`` (...)."""
    k = np.asarray(axis, float) / np.linalg.norm(axis)
    c, s = np.cos(angle)[..., None], np.sin(angle)[..., None]
    return v * c + np.cross(k, v) * s + k * (v @ k)[..., None] * (1 - c)


def focused_waist(beam_radius: float, focal_length: float, wavelength: float) -> float:
    """Waist radius w0 in m that a thin lens makes of a collimated Gaussian beam.

    w0 = w_in f / sqrt(f^2 + z_in^2) with z_in = pi w_in^2 / lambda (the input waist at the lens;
    Saleh and Teich sec. 3.2), ~ lambda f / (pi w_in) when f << z_in. The new waist lies
    f z_in^2 / (f^2 + z_in^2) behind the lens, at the focal plane when f << z_in.

    Parameters
    ----------
    beam_radius : float
        1/e^2 intensity radius w_in of the collimated beam in m, in [MIN_LENGTH, 1].
    focal_length : float
        f in m, in [MIN_LENGTH, MAX_LENGTH].
    wavelength : float
        lambda in m, in [MIN_LENGTH, 1 mm].
    """
    w_in = _length("beam_radius", beam_radius, high=1.0)
    f = _length("focal_length", focal_length)
    lam = _length("wavelength", wavelength, high=1e-3)
    z_in = math.pi * w_in ** 2 / lam
    return w_in * f / math.hypot(f, z_in)


def rayleigh_range(waist: float, wavelength: float) -> float:
    """z_R = pi w0^2 / lambda in m.

    Parameters
    ----------
    waist : float
        Waist radius w0 in m, in [MIN_LENGTH, 1].
    wavelength : float
        lambda in m, in [MIN_LENGTH, 1 mm].
    """
    w0 = _length("waist", waist, high=1.0)
    return math.pi * w0 ** 2 / _length("wavelength", wavelength, high=1e-3)


def beam_radius_at(distance: float, waist: float, wavelength: float) -> float:
    """Radius w(z) = w0 sqrt(1 + (z / z_R)^2) in m a ``distance`` z from the waist.

    Parameters
    ----------
    distance : float
        z in m, in [0, MAX_LENGTH].
    waist : float
        w0 in m, in [MIN_LENGTH, 1].
    wavelength : float
        lambda in m, in [MIN_LENGTH, 1 mm].
    """
    z = _length("distance", distance, 0.0)
    z_r = rayleigh_range(waist, wavelength)
    return waist * math.hypot(1.0, z / z_r)


def interval_fraction(centre, radius, low, high):
    """Share of a 1D Gaussian's power (centre m, 1/e^2 radius w) inside [low, high].

    Phi((high - m) / sigma) - Phi((low - m) / sigma), sigma = w / 2, Phi the standard normal
    distribution function; for the 2D spot it multiplies with the other axis's share.

    Parameters
    ----------
    centre : float or array_like
        The spot's centre m in m, |m| <= MAX_LENGTH.
    radius : float
        Its 1/e^2 intensity radius w in m along this axis, in [MIN_LENGTH, MAX_LENGTH].
    low, high : float
        The interval's ends in m (``-inf``/``inf`` allowed, else |.| <= MAX_LENGTH),
        low <= high.

    Returns
    -------
    ndarray
        In [0, 1], of the shape of ``centre``.
    """
    m = check_array("centre", centre, "m", low=-MAX_LENGTH, high=MAX_LENGTH)
    w = _length("radius", radius)
    lo, hi = _interval("low", low, "high", high)
    return _fraction(m, w / 2, lo, hi)


def _interval(low_name, low, high_name, high):
    lo, hi = _end(low_name, low), _end(high_name, high)
    if not lo <= hi:
        raise ValueError(f"{high_name} must be >= {low_name} = {lo:g} m, got {hi:g}")
    return lo, hi


def _fraction(m, sigma, low, high):
    """Phi((high - m) / sigma) - Phi((low - m) / sigma), unchecked."""
    return np.clip(ndtr((high - m) / sigma) - ndtr((low - m) / sigma), 0.0, 1.0)


def rectangle_fraction(centre_x, centre_y, radius_x, radius_y, x_range, y_range):
    """Share of an elliptical Gaussian spot's power on an axis-aligned rectangle (closed form).

    The product of :func:`interval_fraction` along x and along y (the spot separates).

    Parameters
    ----------
    centre_x, centre_y : float or array_like
        The spot's centre in m (broadcast together), |.| <= MAX_LENGTH.
    radius_x, radius_y : float
        Its 1/e^2 radii in m along x and y, in [MIN_LENGTH, MAX_LENGTH].
    x_range, y_range : tuple of float
        (low, high) of the rectangle along x and y in m.

    Returns
    -------
    ndarray
        In [0, 1].
    """
    mx = check_array("centre_x", centre_x, "m", low=-MAX_LENGTH, high=MAX_LENGTH)
    my = check_array("centre_y", centre_y, "m", low=-MAX_LENGTH, high=MAX_LENGTH)
    wx, wy = _length("radius_x", radius_x), _length("radius_y", radius_y)
    ranges = []
    for name, pair in (("x_range", x_range), ("y_range", y_range)):
        if not isinstance(pair, (tuple, list)) or len(pair) != 2:
            raise TypeError(f"{name} must be a (low, high) pair in m, got {pair!r:.60}")
        ranges.append(_interval(f"{name}[0]", pair[0], f"{name}[1]", pair[1]))
    return _fraction(mx, wx / 2, *ranges[0]) * _fraction(my, wy / 2, *ranges[1])


def interval_moments(centre, radius, low, high):
    """Mass, mean and mean square of a 1D Gaussian spot's intensity restricted to [low, high].

    With t = x - m and g = exp(-t^2 / (2 sigma^2)) (sigma = w / 2), over [a, b]:
    int g = sigma sqrt(2 pi) (Phi(beta) - Phi(alpha)), int t g = sigma^2 (g(a) - g(b)),
    int t^2 g = sigma^2 ((a - m) g(a) - (b - m) g(b)) + sigma^2 int g (integration by parts).

    Parameters
    ----------
    centre : float or array_like
        The spot's centre m in m, |m| <= MAX_LENGTH.
    radius : float
        1/e^2 radius w in m, in [MIN_LENGTH, MAX_LENGTH].
    low, high : float
        The finite interval [a, b] in m, a < b, |.| <= MAX_LENGTH.

    Returns
    -------
    tuple of ndarray
        (fraction of the spot's power in [a, b], mean of x there in m, mean of x^2 there in
        m^2); where the fraction is below 1e-12 (rounding would swamp the moments) the means
        are those of the interval's nearer end.
    """
    m = check_array("centre", centre, "m", low=-MAX_LENGTH, high=MAX_LENGTH)
    sigma = _length("radius", radius) / 2
    a = check_range("low", low, -MAX_LENGTH, MAX_LENGTH, "m")
    b = check_range("high", high, -MAX_LENGTH, MAX_LENGTH, "m")
    if not a < b:
        raise ValueError(f"high must be > low = {a:g} m, got {b:g}")
    mass = np.clip(ndtr((b - m) / sigma) - ndtr((a - m) / sigma), 0.0, 1.0)
    norm = sigma * math.sqrt(2 * math.pi)
    ga, gb = np.exp(-0.5 * ((a - m) / sigma) ** 2), np.exp(-0.5 * ((b - m) / sigma) ** 2)
    first = sigma ** 2 * (ga - gb) / norm
    second = sigma ** 2 * ((a - m) * ga - (b - m) * gb) / norm + sigma ** 2 * mass
    ok = mass > 1e-12
    safe = np.where(ok, mass, 1.0)
    nearer = np.where(m < a, a, np.where(m > b, b, m))
    mean_t = np.clip(np.where(ok, first / safe, nearer - m), a - m, b - m)
    mean_t2 = np.where(ok, second / safe, (nearer - m) ** 2)
    return mass, m + mean_t, m ** 2 + 2 * m * mean_t + mean_t2
