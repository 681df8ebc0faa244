"""Tip shapes of module (d): force F(Z_s) and contact radius r(Z_s) of a rigid tip on a sample.

A rigid, frictionless, axisymmetric (or, for the pyramid, four-sided) tip pressed by Z_s into an
elastic half-space of Young's modulus E and Poisson's ratio nu feels the force F(Z_s), with the
reduced modulus of the sample ``E* = E / (1 - nu^2)`` (the tip is taken rigid, so only the sample
enters E*). Writing r for the contact radius (Hertz 1882; Sneddon, Int. J. Eng. Sci. 3, 47 (1965);
Bilodeau, J. Appl. Mech. 59, 519 (1992))::

    parabolic,  radius R:        F = (4 sqrt(R) / 3) E* Z_s^(3/2),     Z_s = r^2 / R
    spherical,  radius R:        F = E* [(r^2 + R^2)/2 ln((R + r)/(R - r)) - r R],
                                 Z_s = (r / 2) ln((R + r)/(R - r)),   r < R
    conical,    half angle a:    F = E* (2 tan(a) / pi) Z_s^2,          Z_s = pi r / (2 tan(a))
    pyramidal,  face angle b:    F = c E* tan(b) Z_s^2,                 Z_s = r / (c tan(b))

with, for the four-sided pyramid, c = 1/sqrt(2) = 0.7071 (Rico et al., Phys. Rev. E 72, 021914
(2005); the source paper's Eq. 12: ``Pyramidal(form="rico")``, the default, which the course's
paper reproduction keeps) or c = 0.7453 (Bilodeau, J. Appl. Mech. 59, 519 (1992), the form vendor
software such as JPK's reports: ``Pyramidal(form="bilodeau")``, the default of
:func:`~afmsmiler.contact.fit_curve`). The two differ by 5.4 %: a modulus fitted with one is
1.054 times the one fitted with the other.

For every axisymmetric punch the contact stiffness is dF/dZ_s = 2 E* r (Sneddon); the four
formulas above share it, which the solvers use as the derivative.

Each shape is a frozen dataclass carrying its metadata (:data:`TIPS` maps a key to the class; each
class lists its :class:`~afmsmiler.parameters.Parameter` entries with SI unit, default, valid range,
the practical unit and range of its slider), so widgets, tables and the book are generated from the
data instead of being typed twice, as in nanite's model registry. Each shape also draws itself
(:meth:`Tip.outline`, the cross-section the figures and the 3D view share) and says whether the
adhesion models apply to it (:attr:`Tip.adhesive`).

The sphere is evaluated in the dimensionless contact radius u = r / R: Z_s = R u artanh(u) and
F = E* R^2 [(1 + u^2) artanh(u) - u]. The bracket vanishes like 4 u^3 / 3, so for u < 0.3 it is
summed as its series sum_n 4 n u^(2n+1) / (4 n^2 - 1) instead of being computed by cancellation;
this keeps full precision for Z_s << R, where the sphere tends to the paraboloid.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, fields
from typing import ClassVar

import numpy as np

from ..parameters import Parameter, read_only
from ..validation import check_array, check_choice, check_integer, check_positive, check_range
from ._solvers import bracketed_newton

__all__ = ["Tip", "Parabolic", "Spherical", "Conical", "Pyramidal", "TIPS",
           "make_tip", "reduced_modulus", "tip_table", "MAX_EXTENT"]


def reduced_modulus(youngs_modulus, poisson_ratio) -> float:
    """Reduced modulus E* = E / (1 - nu^2) of a sample indented by a rigid tip, in Pa.

    Parameters
    ----------
    youngs_modulus : float
        Young's modulus E of the sample in Pa, > 0.
    poisson_ratio : float
        Poisson's ratio nu of the sample, in [0, 0.5).

    Returns
    -------
    float
        E* in Pa.

    Raises
    ------
    ValueError
        If E is not finite and positive or nu is outside [0, 0.5).
    """
    e = check_range("youngs_modulus", youngs_modulus, 0.0, math.inf, "Pa", low_inclusive=False,
                    high_inclusive=False)
    nu = check_range("poisson_ratio", poisson_ratio, 0.0, 0.5, high_inclusive=False)
    return e / (1.0 - nu * nu)


# the registry's parameters, with their defaults, in one place (SI; display units through UNITS)
# R >= 1 pm: a hundredth of an atom, below any tip; a smaller R would overflow R-divided terms
# (the JKR curve's a^2 / R) for contact radii inside the valid range
RADIUS = Parameter(name="radius", unit="m", display_unit="nm", default=20e-9, low=1e-12,
                   high=1e-2, slider_low=1e-9, slider_high=5e-6, log=True,
                   label="tip radius R")
HALF_ANGLE = Parameter(name="half_angle", unit="rad", display_unit="deg",
                       default=math.radians(20.0), low=0.0, high=math.pi / 2, low_inclusive=False,
                       high_inclusive=False, slider_low=math.radians(5.0),
                       slider_high=math.radians(85.0), label="half opening angle alpha")
FACE_ANGLE = Parameter(name="face_angle", unit="rad", display_unit="deg",
                       default=math.radians(35.0), low=0.0, high=math.pi / 2, low_inclusive=False,
                       high_inclusive=False, slider_low=math.radians(5.0),
                       slider_high=math.radians(85.0), label="face angle beta")

#: The four-sided pyramid's prefactor c in F = c E* tan(beta) Z_s^2, with its source.
PYRAMID_FORMS = read_only({
    "rico": (1.0 / math.sqrt(2.0), "Rico et al., Phys. Rev. E 72, 021914 (2005): "
             "c = 1/sqrt(2) = 0.7071 (the source paper's Eq. 12)"),
    "bilodeau": (0.7453, "Bilodeau, J. Appl. Mech. 59, 519 (1992): c = 0.7453 "
                 "(vendor software, e.g. JPK's)"),
})

_N_OUTLINE = 121
_MAX_OUTLINE = 100_000

#: Largest indentation Z_s and largest distance from the axis (contact radius, profile) in m that
#: the tips accept: the positioner's travel (``PARAMETERS["z_np"]``, +-100 m, far beyond any
#: positioner), which bounds Z_s <= Z_np. Physical, and inside it no force law overflows.
MAX_EXTENT = 100.0


class Tip:
    """Base class of a tip shape: subclasses are frozen dataclasses with registry metadata.

    Subclasses define ``key``, ``title``, ``parameters`` (tuple of
    :class:`~afmsmiler.parameters.Parameter`), ``adhesive``, the
    closed forms ``_force_unit(z)`` (F at E* = 1 Pa), ``_radius(z)``, ``_depth(r)`` and
    ``profile(r)``, and ``_solve(z_np, k, e_star)`` for the cantilever equation.
    """

    key: ClassVar[str]
    title: ClassVar[str]
    formula: ClassVar[str]
    parameters: ClassVar[tuple[Parameter, ...]]
    #: Whether the adhesion models (DMT, JKR: a smooth apex of radius R) apply to this shape.
    adhesive: ClassVar[bool] = False
    #: Number of flat faces (4 for the pyramid), or None for a body of revolution: how to draw it.
    faces: ClassVar[int | None] = None

    def __post_init__(self):
        for p in self.parameters:
            object.__setattr__(self, p.name, p.check(getattr(self, p.name)))

    # -- checked public API ----------------------------------------------------------------
    def _depth_array(self, z_s) -> np.ndarray:
        return check_array("z_s", z_s, "m", low=0.0, high=self.depth_limit)

    @property
    def depth_limit(self) -> float:
        """Largest indentation Z_s in m the model accepts (:data:`MAX_EXTENT`, or R for a sphere).

        Z_s <= Z_np, and the positioner's travel is bounded by :data:`MAX_EXTENT` (100 m, beyond
        any positioner); the bound keeps every force law finite in floating point.
        """
        return MAX_EXTENT

    def force(self, z_s, reduced_modulus):
        """Force F(Z_s) in N on the tip at indentation ``z_s``.

        Parameters
        ----------
        z_s : float or array_like
            Indentation Z_s of the sample at the apex in m, in [0, :attr:`depth_limit`] (100 m,
            or R for a sphere).
        reduced_modulus : float
            E* = E / (1 - nu^2) of the sample in Pa (see :func:`reduced_modulus`).

        Returns
        -------
        float or ndarray
            F in N, shaped like ``z_s``.

        Raises
        ------
        ValueError
            On negative, non-finite or (sphere) too deep indentations, or E* <= 0.
        """
        z = self._depth_array(z_s)
        e_star = check_range("reduced_modulus", reduced_modulus, 0.0, math.inf, "Pa",
                             low_inclusive=False, high_inclusive=False)
        out = e_star * self._force_unit(z)
        return out if out.ndim else float(out)

    def contact_radius(self, z_s):
        """Contact radius r(Z_s) in m at indentation ``z_s``.

        Parameters
        ----------
        z_s : float or array_like
            Indentation in m, >= 0 (and <= R for a sphere).

        Returns
        -------
        float or ndarray
            r in m (for the pyramid: the radius of the circle of the same Z_s-r law, the
            inscribed half-width of the square contact).
        """
        out = self._radius(self._depth_array(z_s))
        return out if out.ndim else float(out)

    def depth_for_radius(self, contact_radius):
        """Indentation Z_s(r) in m that gives the contact radius ``contact_radius``.

        Parameters
        ----------
        contact_radius : float or array_like
            r in m, in [0, :attr:`max_radius`] (r at the deepest indentation accepted; < R for a
            sphere).

        Returns
        -------
        float or ndarray
            Z_s in m.
        """
        r = check_array("contact_radius", contact_radius, "m", low=0.0, high=self.max_radius)
        out = self._depth(r)
        return out if out.ndim else float(out)

    @property
    def max_radius(self) -> float:
        """Largest contact radius in m the shape allows: r at :attr:`depth_limit` (R for a sphere).
        """
        return float(self._radius(np.array(self.depth_limit)))

    def contact_stiffness(self, z_s, reduced_modulus):
        """dF/dZ_s = 2 E* r(Z_s) in N/m (Sneddon's result, shared by every shape here).

        Parameters
        ----------
        z_s : float or array_like
            Indentation in m.
        reduced_modulus : float
            E* in Pa.
        """
        e_star = check_range("reduced_modulus", reduced_modulus, 0.0, math.inf, "Pa",
                             low_inclusive=False, high_inclusive=False)
        return 2.0 * e_star * np.asarray(self.contact_radius(z_s))

    @property
    def max_profile_radius(self) -> float:
        """Largest distance from the axis in m at which :meth:`profile` is defined.

        :data:`MAX_EXTENT` (100 m: a tip is far smaller, and the bound keeps the profile finite),
        or R for a sphere.
        """
        return MAX_EXTENT

    def profile(self, r):
        """Height of the tip surface above its apex at distance ``r`` from the axis, in m.

        Paraboloid r^2 / (2 R); sphere R - sqrt(R^2 - r^2) (r <= R); cone r / tan(alpha);
        pyramid r / tan(beta) across a face.

        Parameters
        ----------
        r : float or array_like
            Distance from the axis in m, in [0, 100] (<= R for a sphere; for the pyramid, measured
            perpendicular to a face's base edge).

        Returns
        -------
        float or ndarray
            The height in m, shaped like ``r``.

        Raises
        ------
        ValueError
            On a negative or non-finite distance, or (sphere) one beyond R.
        """
        r = check_array("r", r, "m", low=0.0, high=self.max_profile_radius)
        out = self._profile(r)
        return out if out.ndim else float(out)

    def _profile(self, r):
        raise NotImplementedError

    def _outline_radii(self, height: float, n: int) -> np.ndarray:
        """Distances from the axis (m, from 0 outwards) at which the outline is sampled."""
        raise NotImplementedError

    def outline(self, height, n: int = _N_OUTLINE):
        """Outline (x, z) in m of the tip's cross-section, apex at the origin, up to ``height``.

        The one drawing of the tip that the figures (:mod:`afmsmiler.plots.contact`) and the 3D
        view (:mod:`afmsmiler.scenes.contact`) share.

        Parameters
        ----------
        height : float
            Height of the drawn part above the apex in m, > 0.
        n : int
            Points on each flank, 3 to 100000.

        Returns
        -------
        (x, z) : tuple of ndarray
            A path from the left flank's top through the apex to the right flank's top (2 n - 1
            points, or 2 n + 1 for a sphere drawn taller than its radius, which continues as a
            cylindrical shank of its radius); a pyramid is cut through the centres of two
            opposite faces.

        Raises
        ------
        ValueError
            If ``height`` is not finite and positive or ``n`` is out of range.
        """
        height = check_positive("height", height, "m")
        n = check_integer("n", n, 3, _MAX_OUTLINE)
        r = self._outline_radii(height, n)
        z = self._profile(r)
        if isinstance(self, Spherical) and height > self.radius:
            r, z = np.r_[r, self.radius], np.r_[z, height]
        return np.r_[-r[::-1], r[1:]], np.r_[z[::-1], z[1:]]

    def values(self) -> dict:
        """The tip's parameters as a dict name -> SI value."""
        return {f.name: getattr(self, f.name) for f in fields(self)}

    # -- solver ------------------------------------------------------------------------------
    def _solve(self, z_np: np.ndarray, k: float, e_star: float) -> np.ndarray:
        """Z_s solving k (Z_np - Z_s) = F(Z_s) for Z_np > 0 (unchecked, vectorised)."""
        raise NotImplementedError

    def _solve_state(self, z_np, k, e_star):
        """(Z_s, F / E*, r) at the solution, for Z_np > 0 (unchecked, vectorised)."""
        z_s = self._solve(z_np, k, e_star)
        return z_s, self._force_unit(z_s), self._radius(z_s)


class _PowerLaw(Tip):
    """F = c E* Z^2 with r = g Z (cone and pyramid): the cantilever equation is a quadratic."""

    def _coefficients(self) -> tuple[float, float]:  # (c, g)
        raise NotImplementedError

    def _force_unit(self, z):
        c, _ = self._coefficients()
        return c * z * z

    def _radius(self, z):
        return self._coefficients()[1] * z

    def _depth(self, r):
        return r / self._coefficients()[1]

    def _solve(self, z_np, k, e_star):
        # a Z^2 + k Z - k Z_np = 0, the root in [0, Z_np], in the form free of cancellation
        a = self._coefficients()[0] * e_star
        return 2.0 * k * z_np / (k + np.sqrt(k * k + 4.0 * a * k * z_np))


@dataclass(frozen=True)
class Parabolic(Tip):
    """A paraboloid of apex radius R (Hertz): F = (4 sqrt(R) / 3) E* Z_s^(3/2), Z_s = r^2 / R.

    Parameters
    ----------
    radius : float
        Apex radius of curvature R in m, in [1e-12, 1e-2].

    Raises
    ------
    ValueError
        If ``radius`` is outside [1e-12, 1e-2] m.
    """

    radius: float = RADIUS.default
    key: ClassVar[str] = "parabolic"
    title: ClassVar[str] = "paraboloid (Hertz)"
    adhesive: ClassVar[bool] = True
    formula: ClassVar[str] = r"F = \frac{4\sqrt{R}}{3} E^* Z_s^{3/2},\quad Z_s = r^2/R"
    parameters: ClassVar[tuple[Parameter, ...]] = (RADIUS,)

    def _force_unit(self, z):
        return 4.0 / 3.0 * math.sqrt(self.radius) * z * np.sqrt(z)

    def _radius(self, z):
        return np.sqrt(self.radius * z)

    def _depth(self, r):
        return r * r / self.radius

    def _profile(self, r):
        return r * r / (2.0 * self.radius)

    def _outline_radii(self, height, n):
        return np.linspace(0.0, math.sqrt(2.0 * self.radius * height), n)

    def _solve(self, z_np, k, e_star):
        # with s = sqrt(Z_s): beta s^3 + s^2 - Z_np = 0, beta = 4 sqrt(R) E* / (3 k); the left side
        # is increasing and convex in s >= 0, and both sqrt(Z_np) and (Z_np / beta)^(1/3) bound
        # the root from above, so Newton from their minimum converges monotonically
        beta = 4.0 * math.sqrt(self.radius) * e_star / (3.0 * k)
        hi = np.minimum(np.sqrt(z_np), np.cbrt(z_np / beta))

        def g(s):
            s2 = s * s
            return beta * s2 * s + s2 - z_np, s * (3.0 * beta * s + 2.0)

        s = bracketed_newton(g, np.zeros_like(hi), hi, hi)
        return s * s


# --- the sphere, in u = r / R ------------------------------------------------------------------
_SERIES = np.array([4.0 * n / (4.0 * n * n - 1.0) for n in range(1, 24)])
_U_SERIES = 0.3


def _sphere_depth(u):
    """h(u) = u artanh(u) = Z_s / R."""
    return u * np.arctanh(u)


def _sphere_depth_slope(u):
    """h'(u) = artanh(u) + u / (1 - u^2)."""
    return np.arctanh(u) + u / ((1.0 - u) * (1.0 + u))


def _sphere_force(u):
    """G(u) = (1 + u^2) artanh(u) - u = F / (E* R^2), by its series below u = 0.3."""
    u = np.asarray(u, dtype=float)
    v = u * u
    series = np.zeros_like(u)
    for c in _SERIES[::-1]:
        series = series * v + c
    direct = (1.0 + v) * np.arctanh(np.minimum(u, 1.0)) - u
    return np.where(u < _U_SERIES, u * v * series, direct)


def _sphere_u_for_depth(zeta):
    """Invert h(u) = zeta for zeta in [0, 1] (monotone Newton from above, vectorised)."""
    zeta = np.asarray(zeta, dtype=float)
    hi = np.minimum(np.sqrt(zeta), 0.999)  # h(u) >= u^2, and h(0.999) > 1: both above the root

    def g(u):
        return _sphere_depth(u) - zeta, _sphere_depth_slope(u)

    u = bracketed_newton(g, np.zeros_like(hi), hi, hi)
    return np.where(zeta > 0, u, 0.0)


#: u at which the sphere is indented by its own radius, h(u) = 1.
_U_AT_RADIUS = float(_sphere_u_for_depth(np.array(1.0)))


@dataclass(frozen=True)
class Spherical(Tip):
    """A sphere of radius R (Sneddon): exact for contact radii up to R.

    F = E* [(r^2 + R^2)/2 ln((R + r)/(R - r)) - r R],  Z_s = (r/2) ln((R + r)/(R - r)).

    Indentations deeper than R are rejected (there the tip's shank, not its sphere, would touch).

    Parameters
    ----------
    radius : float
        Sphere radius R in m, in [1e-12, 1e-2].

    Raises
    ------
    ValueError
        If ``radius`` is outside [1e-12, 1e-2] m.
    """

    radius: float = RADIUS.default
    key: ClassVar[str] = "spherical"
    title: ClassVar[str] = "sphere (Sneddon)"
    adhesive: ClassVar[bool] = True
    formula: ClassVar[str] = (r"F = E^*\left[\frac{r^2+R^2}{2}\ln\frac{R+r}{R-r} - rR\right],\quad "
                              r"Z_s = \frac{r}{2}\ln\frac{R+r}{R-r}")
    parameters: ClassVar[tuple[Parameter, ...]] = (RADIUS,)

    @property
    def depth_limit(self) -> float:
        """Largest indentation accepted: the sphere's radius R, in m."""
        return self.radius

    @property
    def max_radius(self) -> float:
        """Contact radius at which Z_s diverges: R, in m (excluded)."""
        return self.radius

    def depth_for_radius(self, contact_radius):
        """Indentation Z_s = (r / 2) ln((R + r)/(R - r)) in m for contact radius r < R.

        Parameters
        ----------
        contact_radius : float or array_like
            r in m, in [0, R).
        """
        r = check_array("contact_radius", contact_radius, "m", low=0.0, high=self.radius,
                        high_inclusive=False)
        out = self._depth(r)
        return out if out.ndim else float(out)

    def _force_unit(self, z):
        return self.radius ** 2 * _sphere_force(_sphere_u_for_depth(z / self.radius))

    def _radius(self, z):
        return self.radius * _sphere_u_for_depth(z / self.radius)

    def _depth(self, r):
        return self.radius * _sphere_depth(r / self.radius)

    @property
    def max_profile_radius(self) -> float:
        """The sphere's radius R in m: its profile ends at the equator."""
        return self.radius

    def _profile(self, r):
        r = np.minimum(r, self.radius)
        return r * r / (self.radius + np.sqrt((self.radius - r) * (self.radius + r)))

    def _outline_radii(self, height, n):
        top = min(height, self.radius)
        return self.radius * np.sin(np.linspace(0.0, math.acos(1.0 - top / self.radius), n))

    def max_z_np(self, spring_constant: float, reduced_modulus: float) -> float:
        """Largest Z_np in m before the solved indentation exceeds R: R + F(R) / k.

        Parameters
        ----------
        spring_constant : float
            k in N/m, > 0.
        reduced_modulus : float
            E* in Pa, > 0.

        Returns
        -------
        float
            The limit in m.

        Raises
        ------
        ValueError
            If k or E* is not finite and positive.
        """
        spring_constant = check_positive("spring_constant", spring_constant, "N/m")
        reduced_modulus = check_positive("reduced_modulus", reduced_modulus, "Pa")
        return self.radius + reduced_modulus * self.radius ** 2 * float(
            _sphere_force(np.array(_U_AT_RADIUS))) / spring_constant

    def _solve(self, z_np, k, e_star):
        # in u = r / R: h(u) + kappa G(u) = Z_np / R with kappa = E* R / k; h and G are increasing
        # and convex with h >= u^2 and G >= 4 u^3 / 3, so the paraboloid's root bounds u from
        # above and Newton from there converges monotonically; G'(u) = 2 u h'(u)
        return self.radius * _sphere_depth(self._solve_u(z_np, k, e_star))

    def _solve_u(self, z_np, k, e_star):
        radius = self.radius
        kappa = e_star * radius / k
        zeta = z_np / radius
        u_par = np.sqrt(Parabolic(radius)._solve(z_np, k, e_star) / radius)
        hi = np.minimum(u_par, _U_AT_RADIUS)

        def g(u):
            return (_sphere_depth(u) + kappa * _sphere_force(u) - zeta,
                    _sphere_depth_slope(u) * (1.0 + 2.0 * kappa * u))

        return bracketed_newton(g, np.zeros_like(hi), hi, hi)

    def _solve_state(self, z_np, k, e_star):
        u = self._solve_u(z_np, k, e_star)
        return self.radius * _sphere_depth(u), self.radius ** 2 * _sphere_force(u), self.radius * u


@dataclass(frozen=True)
class Conical(_PowerLaw):
    """A cone of half opening angle alpha (Sneddon): F = E* (2 tan(alpha) / pi) Z_s^2.

    Z_s = pi r / (2 tan(alpha)).

    Parameters
    ----------
    half_angle : float
        Half opening angle alpha in rad, in (0, pi/2).

    Raises
    ------
    ValueError
        If ``half_angle`` is outside (0, pi/2).
    """

    half_angle: float = HALF_ANGLE.default
    key: ClassVar[str] = "conical"
    title: ClassVar[str] = "cone (Sneddon)"
    formula: ClassVar[str] = (r"F = E^* \frac{2\tan\alpha}{\pi} Z_s^2,\quad "
                              r"Z_s = \frac{\pi r}{2\tan\alpha}")
    parameters: ClassVar[tuple[Parameter, ...]] = (HALF_ANGLE,)

    def _coefficients(self):
        t = math.tan(self.half_angle)
        return 2.0 * t / math.pi, 2.0 * t / math.pi

    def _profile(self, r):
        return r / math.tan(self.half_angle)

    def _outline_radii(self, height, n):
        return np.linspace(0.0, height * math.tan(self.half_angle), n)


@dataclass(frozen=True)
class Pyramidal(_PowerLaw):
    """A four-sided pyramid of face angle beta: F = c E* tan(beta) Z_s^2, Z_s = r / (c tan(beta)).

    beta is the angle between a face and the axis. Two published prefactors c (see
    :data:`PYRAMID_FORMS`): ``form="rico"``, c = 1/sqrt(2) = 0.7071 (Rico et al., Phys. Rev. E 72,
    021914 (2005); the source paper's Eq. 12, the default here) and ``form="bilodeau"``,
    c = 0.7453 (Bilodeau, J. Appl. Mech. 59, 519 (1992), what vendor software reports and the
    default of :func:`~afmsmiler.contact.fit_curve`).

    Parameters
    ----------
    face_angle : float
        Face angle beta in rad, in (0, pi/2).
    form : {"rico", "bilodeau"}
        Which published prefactor to use.

    Raises
    ------
    ValueError
        If ``face_angle`` is outside (0, pi/2) or ``form`` is unknown.
    """

    face_angle: float = FACE_ANGLE.default
    form: str = "rico"
    key: ClassVar[str] = "pyramidal"
    title: ClassVar[str] = "4-sided pyramid (Rico/Bilodeau)"
    formula: ClassVar[str] = (r"F = c\, E^* \tan\beta\, Z_s^2,\quad "
                              r"Z_s = \frac{r}{c \tan\beta},\quad c = 1/\sqrt{2}\ "
                              r"\mathrm{(Rico)}\ \mathrm{or}\ 0.7453\ \mathrm{(Bilodeau)}")
    parameters: ClassVar[tuple[Parameter, ...]] = (FACE_ANGLE,)
    faces: ClassVar[int | None] = 4

    def __post_init__(self):
        super().__post_init__()
        check_choice("form", self.form, tuple(PYRAMID_FORMS))

    @property
    def prefactor(self) -> float:
        """The prefactor c of the chosen form (0.7071 or 0.7453)."""
        return PYRAMID_FORMS[self.form][0]

    @property
    def source(self) -> str:
        """The publication the chosen form follows."""
        return PYRAMID_FORMS[self.form][1]

    def _coefficients(self):
        c = self.prefactor * math.tan(self.face_angle)
        return c, c

    def _profile(self, r):
        return r / math.tan(self.face_angle)

    def _outline_radii(self, height, n):
        return np.linspace(0.0, height * math.tan(self.face_angle), n)


#: The registry: key -> tip class, in teaching order.
TIPS: dict[str, type[Tip]] = {cls.key: cls for cls in (Parabolic, Spherical, Conical, Pyramidal)}


def make_tip(key: str, **parameters) -> Tip:
    """Build a tip from its registry key and SI parameters (defaults from the registry).

    Parameters
    ----------
    key : str
        One of :data:`TIPS` (``"parabolic"``, ``"spherical"``, ``"conical"``, ``"pyramidal"``).
    **parameters
        The tip's parameters in SI units (and the pyramid's ``form``); missing ones take their
        registry defaults.

    Returns
    -------
    Tip

    Raises
    ------
    ValueError
        For an unknown key or a parameter outside its valid range.
    TypeError
        For a parameter the tip does not have.
    """
    check_choice("key", key, tuple(TIPS))
    cls = TIPS[key]
    names = {f.name for f in fields(cls)}
    unknown = set(parameters) - names
    if unknown:
        raise TypeError(f"{cls.__name__} has no parameter(s) {sorted(unknown)}; "
                        f"valid: {sorted(names)}")
    return cls(**parameters)


def tip_table() -> str:
    """A Markdown table of the registry: tip, formula, parameters, units, defaults, ranges."""
    rows = ["| key | tip | F(Z_s), r(Z_s) | parameter | default | valid range |",
            "|---|---|---|---|---|---|"]
    for key, cls in TIPS.items():
        for p in cls.parameters:
            high = "inf" if not math.isfinite(p.high) else f"{p.to_display(p.high):g}"
            left, right = "[" if p.low_inclusive else "(", "]" if p.high_inclusive else ")"
            rows.append(f"| `{key}` | {cls.title} | ${cls.formula}$ | "
                        f"{p.title} | {p.to_display(p.default):g} | "
                        f"{left}{p.to_display(p.low):g}, {high}{right} |")
    return "\n".join(rows)
