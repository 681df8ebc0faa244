"""Indentation curves: the cantilever in series with the contact, with or without adhesion.

The nano-positioner moves the sample up by Z_np; the cantilever deflects by Z_c, the sample is
indented by Z_s at the apex, and (paper, module d)::

    Z_np = Z_s + Z_c,     F = k Z_c = F(Z_s)

so Z_s solves k (Z_np - Z_s) = F(Z_s). The left side falls and the right side rises with Z_s, so
for Z_np > 0 there is exactly one root in [0, Z_np]; for Z_np <= 0 the tip is not in contact and
F = 0. The roots are found for a whole curve at once: in closed form for the cone and the pyramid
(a quadratic in Z_s), by Newton's method on the cubic in sqrt(Z_s) for the paraboloid and on the
parametric Sneddon equations for the sphere, each started from an upper bound on a convex,
increasing function so that it converges monotonically, with bisection as a safeguard
(:mod:`._solvers`). The residual k (Z_np - Z_s) - F(Z_s) is at round-off relative to k Z_np.

Adhesion (sphere or paraboloid of radius R, work of adhesion w, in J/m^2):

* DMT (Derjaguin, Muller and Toporov, J. Colloid Interface Sci. 53, 314 (1975)): in contact
  F = F_elastic(Z_s) - 2 pi R w. The tip snaps on at Z_np = 0 and, on retract, stays on until
  Z_s = 0, where it leaves at the pull-off force -2 pi R w.
* JKR (Johnson, Kendall and Roberts, Proc. R. Soc. A 324, 301 (1971)), parametric in the contact
  radius a, for a paraboloid (for a sphere, its apex paraboloid)::

      Z_s = a^2 / R - sqrt(2 pi w a / E*),     F = 4 E* a^3 / (3 R) - sqrt(8 pi w E* a^3)

  Equilibria with the lever satisfy Z_np(a) = Z_s(a) + F(a) / k, and they are stable where
  dZ_np/da > 0 (where the contact stiffness dF/dZ_s exceeds -k). The tip snaps on at Z_np = 0 to
  the stable branch and snaps off, on retract, at the minimum of Z_np(a): the cantilever
  instability. On the way the force passes its minimum -(3/2) pi R w (JKR's pull-off force,
  at dF/da = 0); the force at the jump itself tends to that value for a soft lever (k -> 0) and
  to -(5/6) pi R w (displacement control) for a stiff one.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from ..validation import check_array, check_choice, check_instance, check_positive, check_range
from ._solvers import bracketed_newton
from .quantities import PARAMETERS
from .tips import MAX_EXTENT, RADIUS, Spherical, Tip, reduced_modulus

__all__ = ["IndentationCurve", "ApproachRetract", "indent", "approach_retract", "residual",
           "adhesion_extrema",
           "ADHESION_MODELS", "jkr_curve", "jkr_instability", "z_np_limit"]

#: Adhesion models offered by :func:`approach_retract` (None: purely elastic).
ADHESION_MODELS = (None, "dmt", "jkr")

#: Bracket doublings allowed before a JKR search gives up (2^1100 overflows any float range).
_MAX_DOUBLINGS = 1100

#: Range of the reduced modulus E* = E / (1 - nu^2) in Pa that the JKR functions accept: what
#: E and nu in their ranges (:data:`PARAMETERS`) give, [E_min, E_max / (1 - 0.5^2)].
E_STAR_RANGE = (PARAMETERS["youngs_modulus"].low, PARAMETERS["youngs_modulus"].high / 0.75)


def _check_reduced_modulus(value) -> float:
    return check_range("reduced_modulus", value, *E_STAR_RANGE, "Pa")


def _check_work(value) -> float:
    """w in [0, w_max] J/m^2: 0 (no adhesion) is valid where no adhesion model is asked for."""
    return check_range("work_of_adhesion", value, 0.0, PARAMETERS["work_of_adhesion"].high,
                       "J/m^2")


@dataclass(frozen=True)
class IndentationCurve:
    """One branch (approach or retract) of an indentation curve, all arrays in SI units.

    Parameters
    ----------
    z_np : ndarray
        Nano-positioner displacement Z_np towards the tip in m (0: the undeformed surface touches
        the tip with the lever at rest).
    z_s : ndarray
        Indentation of the sample at the apex in m (0 out of contact; negative for JKR necks).
    z_c : ndarray
        Cantilever deflection in m (F / k).
    force : ndarray
        Tip-sample force in N (positive pushes the tip up, negative is adhesion).
    contact_radius : ndarray
        Contact radius in m (0 out of contact).
    in_contact : ndarray of bool
        Whether the tip touches the sample.
    """

    z_np: np.ndarray
    z_s: np.ndarray
    z_c: np.ndarray
    force: np.ndarray
    contact_radius: np.ndarray
    in_contact: np.ndarray

    @property
    def tip_position(self) -> np.ndarray:
        """Position of the apex towards the sample, Z_np - Z_c, in m (= Z_s in contact)."""
        return self.z_np - self.z_c

    @property
    def separation(self) -> np.ndarray:
        """Tip-sample separation Z_c - Z_np in m (negative: indentation)."""
        return self.z_c - self.z_np


@dataclass(frozen=True)
class ApproachRetract:
    """An approach-retract cycle over a Z_np ramp.

    Parameters
    ----------
    approach, retract : IndentationCurve
        The two branches; ``retract.z_np`` is ``approach.z_np`` reversed.
    pull_off_force : float
        Magnitude of the most negative force on retract in N (0 without adhesion): the adhesion a
        force curve measures. Exact values of the model, not sampled minima.
    snap_off_force : float
        Force in N just before the tip jumps off the surface on retract (signed; 0 without
        adhesion). For DMT it equals -pull_off_force; for JKR it lies between -(3/2) pi R w (soft
        lever) and -(5/6) pi R w (stiff lever).
    snap_off_z_np : float
        Z_np in m at which the tip leaves the surface on retract (0 without adhesion).
    adhesion : str or None
        The adhesion model used.
    """

    approach: IndentationCurve
    retract: IndentationCurve
    pull_off_force: float
    snap_off_force: float
    snap_off_z_np: float
    adhesion: str | None


#: Most Z_np points one call solves (a slider ramp has 400; a JKR cycle of this many takes a few s).
MAX_POINTS = 100_000


def _check_common(z_np, spring_constant, tip, youngs_modulus, poisson_ratio):
    if np.size(z_np) > MAX_POINTS:
        raise ValueError(f"z_np must have at most {MAX_POINTS} points, got {np.size(z_np)}")
    zp = PARAMETERS["z_np"]
    z = check_array("z_np", z_np, "m", low=zp.low, high=zp.high)
    k = PARAMETERS["spring_constant"].check(spring_constant)
    check_instance("tip", tip, Tip)
    e = PARAMETERS["youngs_modulus"].check(youngs_modulus)
    e_star = reduced_modulus(e, PARAMETERS["poisson_ratio"].check(poisson_ratio))
    return z, k, e_star


def _check_depth(tip, z, k, e_star):
    if isinstance(tip, Spherical) and z.size and z.max() > 0:
        limit = tip.max_z_np(k, e_star)
        if z.max() > limit:
            raise ValueError(
                f"z_np must be <= {limit:g} m for this sphere (R = {tip.radius:g} m, "
                f"k = {k:g} N/m, E* = {e_star:g} Pa): beyond it the sphere would be indented "
                f"past its radius, got {z.max():g}")


def _elastic(tip, z, k, e_star) -> IndentationCurve:
    contact = z > 0
    z_s, force, radius = np.zeros_like(z), np.zeros_like(z), np.zeros_like(z)
    if contact.any():
        z_s[contact], psi, radius[contact] = tip._solve_state(z[contact], k, e_star)
        force[contact] = e_star * psi
    # Z_c = F / k rather than Z_np - Z_s, which would lose digits when Z_s ~ Z_np (soft samples)
    return IndentationCurve(z, z_s, force / k, force, radius, contact)


def indent(z_np, spring_constant, tip, youngs_modulus, poisson_ratio) -> IndentationCurve:
    """Solve k (Z_np - Z_s) = F(Z_s) for every Z_np of an array (elastic, no adhesion).

    Parameters
    ----------
    z_np : float or array_like
        Nano-positioner displacements Z_np in m; Z_np <= 0 is out of contact (F = 0).
    spring_constant : float
        Cantilever spring constant k in N/m, > 0.
    tip : Tip
        The tip shape (:class:`~afmsmiler.contact.tips.Parabolic`, ``Spherical``, ``Conical``,
        ``Pyramidal``).
    youngs_modulus : float
        Young's modulus E of the sample in Pa, > 0.
    poisson_ratio : float
        Poisson's ratio nu of the sample, in [0, 0.5).

    Returns
    -------
    IndentationCurve
        Arrays z_np, z_s, z_c, force, contact_radius, in_contact (1-D, even for a scalar input).

    Raises
    ------
    ValueError
        On non-finite Z_np, k <= 0, E <= 0, nu outside [0, 0.5), or a sphere that would be
        indented past its radius.

    Notes
    -----
    The relative residual |k (Z_np - Z_s) - F(Z_s)| / (k Z_np) is at round-off (see
    :func:`residual`). Normalising by k Z_np = k Z_s + F, the sum of the magnitudes of the terms,
    is the backward error of the equation; relative to F alone it is the same unless the sample
    is much softer than the lever, where even the correctly rounded Z_s leaves a residual of order
    eps k Z_s >> eps F. The stronger statement holds too: Z_s, F and Z_c = F / k are each within a
    few eps of the exact root relative to themselves (tested against a 50-digit solution).
    """
    z, k, e_star = _check_common(z_np, spring_constant, tip, youngs_modulus, poisson_ratio)
    z = np.atleast_1d(z)
    _check_depth(tip, z, k, e_star)
    return _elastic(tip, z, k, e_star)


def residual(curve: IndentationCurve, spring_constant, tip, youngs_modulus, poisson_ratio):
    """Relative residual |k (Z_np - Z_s) - F(Z_s)| / (k Z_np) of an elastic curve (0 off contact).

    Parameters
    ----------
    curve : IndentationCurve
        A result of :func:`indent`.
    spring_constant : float
        k in N/m.
    tip : Tip
        The tip used.
    youngs_modulus : float
        E in Pa.
    poisson_ratio : float
        nu.

    Returns
    -------
    ndarray
        The residual of every point, with F(Z_s) recomputed from the returned Z_s by the tip's
        public :meth:`~afmsmiler.contact.tips.Tip.force`.
    """
    check_instance("curve", curve, IndentationCurve)
    check_instance("tip", tip, Tip)
    k = check_positive("spring_constant", spring_constant, "N/m")
    e_star = reduced_modulus(youngs_modulus, poisson_ratio)
    c = curve.in_contact
    out = np.zeros_like(curve.z_np)
    out[c] = np.abs(k * (curve.z_np[c] - curve.z_s[c]) - tip.force(curve.z_s[c], e_star)) / (
        k * curve.z_np[c])
    return out


# --- adhesion -----------------------------------------------------------------------------------
def _adhesive_radius(tip) -> float:
    if not tip.adhesive:
        raise ValueError("adhesion (DMT, JKR) needs a parabolic or spherical tip, "
                         f"got {type(tip).__name__}")
    return tip.radius


def _jkr_terms(a, radius, w, e_star, k):
    """Z_s(a), F(a) and dZ_np/da of JKR with a lever k (a > 0)."""
    sa = np.sqrt(a)
    c1 = math.sqrt(2.0 * math.pi * w / e_star)
    c2 = math.sqrt(8.0 * math.pi * w * e_star)
    z_s = a * a / radius - c1 * sa
    force = 4.0 * e_star * a ** 3 / (3.0 * radius) - c2 * a * sa
    dz = 2.0 * a / radius - 0.5 * c1 / sa + (4.0 * e_star * a * a / radius - 1.5 * c2 * sa) / k
    return z_s, force, dz


def jkr_instability(spring_constant, radius, work_of_adhesion,
                    reduced_modulus) -> tuple[float, float, float]:
    """The JKR snap-off point with a lever: the minimum of Z_np(a) = Z_s(a) + F(a) / k.

    Parameters
    ----------
    spring_constant : float
        k in N/m, > 0 (beyond the lever range, for the soft and stiff limits).
    radius : float
        Tip radius R in m, in [1e-12, 1e-2].
    work_of_adhesion : float
        w in J/m^2, in [1e-6, 10].
    reduced_modulus : float
        E* in Pa, in :data:`E_STAR_RANGE` ([1, 1.33e13]: what E and nu in their ranges give).

    Returns
    -------
    (a, z_np, force) : tuple of float
        Contact radius (m), positioner displacement (m) and force (N) at snap-off.

    Notes
    -----
    With t = sqrt(a), t dZ_np/da = 2 t^3 / R - c1 + (4 E* t^5 / R - c2 t^2) / k, which is negative
    at t = 0, first falls and then rises: it has exactly one positive root, found by Brent's method.
    """
    k = check_positive("spring_constant", spring_constant, "N/m")  # the limits k -> 0, inf too
    radius = RADIUS.check(radius)
    w = PARAMETERS["work_of_adhesion"].check(work_of_adhesion)
    e_star = _check_reduced_modulus(reduced_modulus)
    c1 = 0.5 * math.sqrt(2.0 * math.pi * w / e_star)
    c2 = 1.5 * math.sqrt(8.0 * math.pi * w * e_star)

    def p(t):
        t = np.float64(t)  # overflow to inf rather than OverflowError
        with np.errstate(over="ignore", invalid="ignore"):
            return float(2.0 * t ** 3 / radius - c1 + (4.0 * e_star * t ** 5 / radius - c2 * t * t)
                         / k)

    hi = max((c1 * radius / 2.0) ** (1 / 3), (c2 * radius / (4.0 * e_star)) ** (1 / 3))
    for _ in range(_MAX_DOUBLINGS):
        with np.errstate(over="ignore", invalid="ignore"):
            above = p(hi) > 0
        if above or not math.isfinite(hi):
            break
        hi *= 2.0
    if not (math.isfinite(hi) and math.isfinite(c1) and math.isfinite(c2) and p(hi) > 0):
        raise ValueError(
            "the JKR snap-off point cannot be bracketed in floating point for spring_constant = "
            f"{k:g} N/m, radius = {radius:g} m, work_of_adhesion = {w:g} J/m^2, reduced_modulus "
            f"= {e_star:g} Pa: choose values nearer the physical ranges (k in [1e-4, 1e3] N/m, "
            "R in [1e-10, 1e-3] m, w in [1e-4, 1] J/m^2, E* in [1e2, 1e12] Pa)")
    t = brentq(p, 0.0, hi, xtol=1e-300, rtol=4 * np.finfo(float).eps, maxiter=500)
    a = t * t
    z_s, force, _ = _jkr_terms(np.array(a), radius, w, e_star, k)
    return a, float(z_s + force / k), float(force)


def jkr_curve(contact_radius, radius, work_of_adhesion,
              reduced_modulus) -> tuple[np.ndarray, np.ndarray]:
    """JKR indentation Z_s(a) and force F(a) for contact radii ``a``.

    Parameters
    ----------
    contact_radius : float or array_like
        a in m, in [0, 100] (the positioner's travel bounds the contact, see
        :data:`~afmsmiler.contact.tips.MAX_EXTENT`).
    radius : float
        Tip radius R in m, in [1e-12, 1e-2].
    work_of_adhesion : float
        w in J/m^2, in [0, 10] (0 gives Hertz).
    reduced_modulus : float
        E* in Pa, in :data:`E_STAR_RANGE` ([1, 1.33e13]: what E and nu in their ranges give).

    Returns
    -------
    (z_s, force) : tuple of ndarray
        Z_s = a^2/R - sqrt(2 pi w a / E*) in m and F = 4 E* a^3 / (3R) - sqrt(8 pi w E* a^3) in N.
    """
    a = check_array("contact_radius", contact_radius, "m", low=0.0, high=MAX_EXTENT)
    radius = RADIUS.check(radius)
    w = _check_work(work_of_adhesion)
    e_star = _check_reduced_modulus(reduced_modulus)
    z_s = a * a / radius - np.sqrt(2.0 * math.pi * w * a / e_star)
    force = 4.0 * e_star * a ** 3 / (3.0 * radius) - np.sqrt(8.0 * math.pi * w * e_star * a ** 3)
    return z_s, force


def _jkr_stable(z, k, radius, w, e_star, a_min, z_min) -> IndentationCurve:
    """Points of the stable JKR branch at Z_np = z (all z >= z_min)."""
    # bracket: a_min below; above, grow a_hi until Z_np(a_hi) >= max z
    z_hi = z.max()
    a_hi = max(2.0 * a_min, math.sqrt(radius * max(z_hi, 0.0)) * 2.0)
    for _ in range(_MAX_DOUBLINGS):
        with np.errstate(over="ignore", invalid="ignore"):
            zs, f, _ = _jkr_terms(np.array(a_hi), radius, w, e_star, k)
            reached = zs + f / k >= z_hi
        if reached or not math.isfinite(a_hi):
            break
        a_hi *= 2.0
    if not (reached and math.isfinite(a_hi)):
        raise ValueError(
            f"z_np up to {z_hi:g} m cannot be reached on the JKR branch in floating point "
            f"(spring_constant = {k:g} N/m, radius = {radius:g} m, work_of_adhesion = {w:g} J/m^2, "
            f"reduced_modulus = {e_star:g} Pa): choose values nearer the physical ranges")

    def g(a):
        zs, f, dz = _jkr_terms(a, radius, w, e_star, k)
        return zs + f / k - z, dz

    lo = np.full_like(z, a_min)
    hi = np.full_like(z, a_hi)
    a = bracketed_newton(g, lo, hi, 0.5 * (lo + hi))
    z_s, force, _ = _jkr_terms(a, radius, w, e_star, k)
    return z_s, force, a


def _branch(z, k, z_s, force, radius, contact):
    z_s = np.where(contact, z_s, 0.0)
    force = np.where(contact, force, 0.0)
    return IndentationCurve(z, z_s, force / k, force, np.where(contact, radius, 0.0), contact)


def z_np_limit(spring_constant, tip, youngs_modulus, poisson_ratio, *, adhesion=None,
               work_of_adhesion=0.0) -> float:
    """Largest Z_np in m the model accepts: before a sphere is indented past its radius.

    Parameters
    ----------
    spring_constant : float
        k in N/m.
    tip : Tip
        The tip shape (only a :class:`Spherical` tip has a finite limit).
    youngs_modulus : float
        E in Pa.
    poisson_ratio : float
        nu, in [0, 0.5).
    adhesion : {None, "dmt", "jkr"}
        Adhesion model, as for :func:`approach_retract`.
    work_of_adhesion : float
        w in J/m^2, in [0, 10] (checked even without adhesion); in [1e-6, 10] with adhesion.

    Returns
    -------
    float
        inf for the paraboloid, cone and pyramid; for a sphere R + F(R)/k (elastic),
        that minus 2 pi R w / k (DMT), or Z_np at which the JKR contact radius reaches R. It can be
        negative (or -inf for JKR) when adhesion alone would bury the sphere.
    """
    _, k, e_star = _check_common(0.0, spring_constant, tip, youngs_modulus, poisson_ratio)
    check_choice("adhesion", adhesion, ADHESION_MODELS)
    _check_work(work_of_adhesion)
    if isinstance(tip, Spherical) and adhesion is not None:
        work_of_adhesion = PARAMETERS["work_of_adhesion"].check(work_of_adhesion)
    return _z_np_limit(k, tip, e_star, adhesion, work_of_adhesion)


def _z_np_limit(k, tip, e_star, adhesion, w) -> float:
    """:func:`z_np_limit` of checked values (k in N/m, E* in Pa, w in J/m^2)."""
    if not isinstance(tip, Spherical):
        return math.inf
    if adhesion is None:
        return tip.max_z_np(k, e_star)
    if adhesion == "dmt":
        return tip.max_z_np(k, e_star) - 2.0 * math.pi * tip.radius * w / k
    a_min, _, _ = jkr_instability(k, tip.radius, w, e_star)
    if a_min >= tip.radius:
        return -math.inf
    z_s, force, _ = _jkr_terms(np.array(tip.radius), tip.radius, w, e_star, k)
    return float(z_s + force / k)


def approach_retract(z_np, spring_constant, tip, youngs_modulus, poisson_ratio, *,
                     adhesion=None, work_of_adhesion=0.0) -> ApproachRetract:
    """Approach and retract over a Z_np ramp, elastic or with DMT / JKR adhesion.

    Parameters
    ----------
    z_np : array_like
        The approach ramp of Z_np in m, strictly increasing; the retract runs it backwards.
    spring_constant : float
        k in N/m, > 0.
    tip : Tip
        The tip shape (adhesion needs :class:`Parabolic` or :class:`Spherical`).
    youngs_modulus : float
        E of the sample in Pa, > 0.
    poisson_ratio : float
        nu of the sample, in [0, 0.5).
    adhesion : {None, "dmt", "jkr"}
        Adhesion model (see the module docstring).
    work_of_adhesion : float
        w in J/m^2, in [0, 10] (checked even without adhesion); in [1e-6, 10] when
        ``adhesion`` is given.

    Returns
    -------
    ApproachRetract

    Raises
    ------
    ValueError
        On bad parameters, a ramp that is not increasing, adhesion with a cone or pyramid, or a
        sphere indented past its radius.

    Notes
    -----
    The snap-in (approach) and snap-off (retract) of the adhesive models happen between ramp
    samples; ``pull_off_force`` and ``snap_off_z_np`` are the exact values of the model.
    """
    z = check_array("z_np", z_np, "m", ndim=1, min_size=2, increasing=True)
    z, k, e_star = _check_common(z, spring_constant, tip, youngs_modulus, poisson_ratio)
    check_choice("adhesion", adhesion, ADHESION_MODELS)
    _check_work(work_of_adhesion)
    return _approach_retract(z, k, tip, youngs_modulus, poisson_ratio, e_star, adhesion,
                             work_of_adhesion)


def _check_ramp(z_np) -> np.ndarray:
    """The checks of :func:`approach_retract` on its ramp alone, in its order: a system's
    parameters were checked when it was made (:meth:`ContactSystem.approach_retract`)."""
    z = check_array("z_np", z_np, "m", ndim=1, min_size=2, increasing=True)
    if z.size > MAX_POINTS:
        raise ValueError(f"z_np must have at most {MAX_POINTS} points, got {z.size}")
    zp = PARAMETERS["z_np"]
    return check_array("z_np", z, "m", low=zp.low, high=zp.high)


def _approach_retract(z, k, tip, youngs_modulus, poisson_ratio, e_star, adhesion,
                      work_of_adhesion) -> ApproachRetract:
    """:func:`approach_retract` of a checked ramp and checked parameters (E* their
    reduced modulus)."""
    if adhesion is None:
        _check_depth(tip, z, k, e_star)
        app = _elastic(tip, z, k, e_star)
        rz = z[::-1]
        ret = IndentationCurve(rz, app.z_s[::-1], app.z_c[::-1], app.force[::-1],
                               app.contact_radius[::-1], app.in_contact[::-1])
        return ApproachRetract(app, ret, 0.0, 0.0, 0.0, None)
    radius = _adhesive_radius(tip)
    w = PARAMETERS["work_of_adhesion"].check(work_of_adhesion)
    try:
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            cycle = _adhesive_cycle(z, k, tip, youngs_modulus, poisson_ratio, e_star, adhesion,
                                    radius, w)
    except (OverflowError, ZeroDivisionError, FloatingPointError) as exc:
        cycle, cause = None, exc
    else:
        cause = None
    if cycle is None or not _finite(cycle):
        raise ValueError(
            f"the {adhesion.upper()} cycle is out of floating-point range for spring_constant = "
            f"{k:g} N/m, radius = {radius:g} m, work_of_adhesion = {w:g} J/m^2, reduced_modulus = "
            f"{e_star:g} Pa: choose values nearer the physical ranges") from cause
    return cycle


def _finite(cycle: ApproachRetract) -> bool:
    arrays = [getattr(b, f) for b in (cycle.approach, cycle.retract)
              for f in ("z_s", "z_c", "force", "contact_radius")]
    return all(np.isfinite(a).all() for a in arrays) and all(
        math.isfinite(x) for x in (cycle.pull_off_force, cycle.snap_off_force, cycle.snap_off_z_np))


def _adhesive_cycle(z, k, tip, youngs_modulus, poisson_ratio, e_star, adhesion, radius, w):
    """The DMT or JKR cycle of :func:`approach_retract` (inputs checked)."""
    limit = _z_np_limit(k, tip, e_star, adhesion, w)
    if z.max() >= limit:
        raise ValueError(
            f"z_np must be < {limit:g} m for this sphere (R = {radius:g} m) with "
            f"{adhesion.upper()} adhesion (w = {w:g} J/m^2, k = {k:g} N/m): beyond it the sphere "
            f"would be indented past its radius, got {z.max():g}")
    rz = z[::-1]
    if adhesion == "dmt":
        f_ad = 2.0 * math.pi * radius * w
        shift = f_ad / k

        # both branches are the elastic solution at Z_np + F_ad / k: solved once (elementwise,
        # so the retract's is the approach's reversed, bit for bit), cut where each touches
        el = _elastic(tip, z + shift, k, e_star)

        def dmt(zz, way, contact):
            force = np.where(contact, el.force[way] - f_ad, 0.0)
            z_s = np.where(contact, el.z_s[way], 0.0)
            return IndentationCurve(zz, z_s, force / k, force,
                                    np.where(contact, el.contact_radius[way], 0.0), contact)

        forward, backward = slice(None), slice(None, None, -1)
        return ApproachRetract(dmt(z, forward, z >= 0), dmt(rz, backward, rz + shift > 0), f_ad,
                               -f_ad, -shift, "dmt")
    a_min, z_min, f_min = jkr_instability(k, radius, w, e_star)
    pull_off = _jkr_pull_off(k, radius, w, e_star, a_min, f_min)

    def jkr(zz, contact):
        z_s = np.zeros_like(zz)
        force = np.zeros_like(zz)
        a = np.zeros_like(zz)
        if contact.any():
            z_s[contact], force[contact], a[contact] = _jkr_stable(
                zz[contact], k, radius, w, e_star, a_min, z_min)
        return _branch(zz, k, z_s, force, a, contact)

    return ApproachRetract(jkr(z, z >= 0), jkr(rz, rz >= z_min), pull_off, f_min, z_min, "jkr")


def _jkr_pull_off(k, radius, w, e_star, a_min, f_min) -> float:
    """The most adhesive force of the stable JKR branch, magnitude in N."""
    # dF/da = 0 at a^3 = 9 pi w R^2 / (8 E*) when it lies on the branch (it always does: there
    # dZ_s/da > 0), else the snap-off point
    a_c = max(a_min, (9.0 * math.pi * w / (8.0 * e_star)) ** (1.0 / 3.0) * radius ** (2.0 / 3.0))
    f_c = float(_jkr_terms(np.array(a_c), radius, w, e_star, k)[1])
    return -min(f_c, f_min)


def adhesion_extrema(spring_constant, tip, youngs_modulus, poisson_ratio, *, adhesion,
                     work_of_adhesion) -> tuple[float, float, float]:
    """Snap-off Z_np, snap-off force and pull-off force of an adhesive contact (no curve solved).

    Parameters
    ----------
    spring_constant : float
        k in N/m, > 0.
    tip : Tip
        A tip with a smooth apex (``tip.adhesive``: paraboloid or sphere).
    youngs_modulus : float
        E in Pa, > 0.
    poisson_ratio : float
        nu, in [0, 0.5).
    adhesion : {"dmt", "jkr"}
        The adhesion model.
    work_of_adhesion : float
        w in J/m^2, > 0.

    Returns
    -------
    (snap_off_z_np, snap_off_force, pull_off_force) : tuple of float
        In m, N (signed) and N (magnitude): the values :func:`approach_retract` reports.

    Raises
    ------
    ValueError
        On bad parameters or values out of floating-point range.
    """
    _, k, e_star = _check_common(0.0, spring_constant, tip, youngs_modulus, poisson_ratio)
    check_choice("adhesion", adhesion, ("dmt", "jkr"))
    radius = _adhesive_radius(tip)
    w = PARAMETERS["work_of_adhesion"].check(work_of_adhesion)
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        if adhesion == "dmt":
            f_ad = 2.0 * math.pi * radius * w
            out = (-f_ad / k, -f_ad, f_ad)
        else:
            a_min, z_min, f_min = jkr_instability(k, radius, w, e_star)
            out = (z_min, f_min, _jkr_pull_off(k, radius, w, e_star, a_min, f_min))
    if not all(math.isfinite(x) for x in out):
        raise ValueError(
            f"the {adhesion.upper()} snap-off is out of floating-point range for spring_constant = "
            f"{k:g} N/m, radius = {radius:g} m, work_of_adhesion = {w:g} J/m^2, reduced_modulus = "
            f"{e_star:g} Pa: choose values nearer the physical ranges")
    return out
