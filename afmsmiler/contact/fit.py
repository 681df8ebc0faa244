"""Fitting force-distance curves: Young's modulus, contact point and baseline with uncertainties.

The force-volume workflow: for each curve, convert the positioner displacement to the tip
position x = Z_np - F / k (the apex's travel towards the sample; with no lever correction the
input already is the tip position), then fit::

    F(x) = F_0 + E / (1 - nu^2) psi(max(x - x_0, 0))

with psi the tip's force law at unit reduced modulus, for E, the contact point x_0 and the
baseline F_0, by :func:`scipy.optimize.least_squares` with the analytic Jacobian
(dF/dx_0 = -2 E* r(x - x_0)). The uncertainties are the square roots of the diagonal of
s^2 (J^T J)^-1, with s^2 the residual variance: the usual linearised covariance (as
:func:`scipy.optimize.curve_fit` reports it).

Curves come from :func:`synthetic_curve` (the exact model with Gaussian noise) or from a file of
any format the kept library ``afmformats`` reads (JPK, Asylum/Igor, AFM workshop, NT-MDT, its own
tab and HDF5 exports) via :func:`load_curve`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.optimize import least_squares

from ..validation import (check_array, check_choice, check_instance, check_integer,
                          check_positive, check_range)
from .indent import indent
from .quantities import PARAMETERS
from .tips import PYRAMID_FORMS, Pyramidal, Spherical, Tip

__all__ = ["ForceCurve", "FitResult", "synthetic_curve", "load_curve", "fit_curve",
           "MAX_FILE_POINTS"]


@dataclass(frozen=True)
class ForceCurve:
    """A measured or synthetic force-distance curve (one segment), SI units.

    Parameters
    ----------
    z_np : ndarray
        Positioner displacement towards the tip in m (for files: minus the measured height), a
        1-D array of finite values (at least 2).
    force : ndarray
        Force on the tip in N, finite, as many values as ``z_np``.
    spring_constant : float or None
        Lever spring constant in N/m, if known (needed for the tip position), in the range of
        ``PARAMETERS["spring_constant"]`` ([1e-6, 1e6] N/m).
    name : str
        Where the curve comes from.

    Raises
    ------
    ValueError
        On non-finite or mismatched arrays or a spring constant out of range.
    TypeError
        If ``name`` is not a str.
    """

    z_np: np.ndarray
    force: np.ndarray
    spring_constant: float | None = None
    name: str = ""

    def __post_init__(self):
        z = check_array("z_np", self.z_np, "m", ndim=1, min_size=2)
        f = check_array("force", self.force, "N", ndim=1)
        if f.size != z.size:
            raise ValueError(f"force and z_np must have the same length, got {f.size} forces for "
                             f"{z.size} positions")
        k = self.spring_constant
        if k is not None:
            k = PARAMETERS["spring_constant"].check(k)
        check_instance("name", self.name, str)
        object.__setattr__(self, "z_np", z)
        object.__setattr__(self, "force", f)
        object.__setattr__(self, "spring_constant", k)

    @property
    def tip_position(self) -> np.ndarray:
        """Z_np - F / k in m (the apex's travel towards the sample)."""
        if self.spring_constant is None:
            raise ValueError("spring_constant is needed for the tip position, got None")
        return self.z_np - self.force / self.spring_constant


@dataclass(frozen=True)
class FitResult:
    """Result of :func:`fit_curve`, with 1-sigma uncertainties from the fit covariance.

    Parameters
    ----------
    youngs_modulus, youngs_modulus_error : float
        E and its standard error in Pa.
    contact_point, contact_point_error : float
        x_0 (on the abscissa fitted: Z_np or tip position) and its standard error in m.
    baseline, baseline_error : float
        F_0 and its standard error in N.
    residual_rms : float
        Root-mean-square residual in N.
    tip : Tip
        The tip shape fitted.
    poisson_ratio : float
        The Poisson's ratio assumed.
    x : ndarray
        The abscissa fitted, in m (Z_np with a spring constant, else the tip position).
    model_force : ndarray
        The fitted model on ``x``, in N.
    model : str
        The force law fitted and its source (for a pyramid: which prefactor, Bilodeau's or
        Rico's), so that a modulus is compared with one fitted the same way.
    """

    youngs_modulus: float
    youngs_modulus_error: float
    contact_point: float
    contact_point_error: float
    baseline: float
    baseline_error: float
    residual_rms: float
    tip: Tip
    poisson_ratio: float
    x: np.ndarray = field(repr=False)
    model_force: np.ndarray = field(repr=False)
    model: str = ""


def synthetic_curve(tip, *, spring_constant, youngs_modulus, poisson_ratio,
                    z_np_range=(-100e-9, 200e-9), points=1000, contact_point=0.0, baseline=0.0,
                    noise=0.0, seed=None) -> ForceCurve:
    """An approach curve from the exact model, with optional Gaussian force noise.

    Parameters
    ----------
    tip : Tip
        The tip shape.
    spring_constant : float
        k in N/m (keyword: the quantities come in the order of
        :class:`~afmsmiler.contact.ContactSystem`).
    youngs_modulus : float
        E of the sample in Pa.
    poisson_ratio : float
        nu of the sample, in [0, 0.5).
    z_np_range : (float, float)
        First and last Z_np in m (the ramp), increasing, each in [-100, 100] (the range of
        ``PARAMETERS["z_np"]``), relative to ``contact_point``'s frame.
    points : int
        Number of samples, in [10, 1e7].
    contact_point : float
        Z_np at which the tip touches the sample, in m, such that the ramp shifted by it,
        ``z_np_range - contact_point``, stays in [-100, 100].
    baseline : float
        Force offset in N (a deflection offset of the detector), |baseline| <= 1e10
        (:data:`MAX_FORCE`).
    noise : float
        Standard deviation of the Gaussian force noise in N, in [0, 1e10] (:data:`MAX_FORCE`).
    seed : int or None
        Seed of the noise generator, an integer in [0, 2^63 - 1], or None for a fresh one.

    Raises
    ------
    ValueError
        On a value outside its range (naming it), or a ramp that is not a pair of increasing
        numbers.

    Returns
    -------
    ForceCurve
    """
    points = check_integer("points", points, 10, 10 ** 7)
    zp = PARAMETERS["z_np"]
    if isinstance(z_np_range, (str, bytes)) or np.shape(z_np_range) != (2,):
        raise ValueError("z_np_range must be a pair (first, last) of positioner displacements in "
                         f"m, got {z_np_range!r:.60}")
    lo = check_range("z_np_range[0]", z_np_range[0], zp.low, zp.high, "m")
    hi = check_range("z_np_range[1]", z_np_range[1], lo, zp.high, "m", low_inclusive=False)
    cp = check_range("contact_point", contact_point, zp.low, zp.high, "m")
    f0 = check_range("baseline", baseline, -MAX_FORCE, MAX_FORCE, "N")
    sigma = check_range("noise", noise, 0.0, MAX_FORCE, "N")
    if seed is not None:
        seed = check_integer("seed", seed, 0, 2 ** 63 - 1)
    z = np.linspace(lo, hi, points)
    shifted = check_array("z_np_range - contact_point", z - cp, "m", low=zp.low, high=zp.high)
    curve = indent(shifted, spring_constant, tip, youngs_modulus, poisson_ratio)
    rng = np.random.default_rng(seed)
    force = curve.force + f0 + (rng.normal(0.0, sigma, points) if sigma > 0 else 0.0)
    return ForceCurve(z, force, float(spring_constant),
                      f"synthetic {tip.key}, E = {youngs_modulus:g} Pa, noise {sigma:g} N")


#: Largest force in N a synthetic curve's baseline and noise may have: far beyond any force a lever
#: carries (k Z_np <= 1e6 N/m * 100 m = 1e8 N); it keeps the noise finite in floating point.
MAX_FORCE = 1e10


#: Most points a curve read from a file may have (a JPK map's curve has a few thousand; this many
#: doubles are 80 MB): a header claiming more is refused before anything is allocated.
MAX_FILE_POINTS = 10_000_000


def load_curve(path, *, segment="approach", index=0) -> ForceCurve:
    """Read one force-distance segment from a file with ``afmformats``.

    Parameters
    ----------
    path : str or path-like
        A file afmformats reads (``.jpk-force``, ``.ibw``, ``.tab``, ``.h5``, ...).
    segment : {"approach", "retract"}
        Which segment to return.
    index : int
        Which curve of a multi-curve file (maps), from 0.

    Returns
    -------
    ForceCurve
        ``z_np`` = -(height (measured)) (or -(height (piezo)) when no measured height is
        stored), in m, and the spring constant from the file's metadata.

    Raises
    ------
    ValueError
        Naming ``path``: for a missing file, one afmformats cannot read, a header that claims
        more than :data:`MAX_FILE_POINTS` points (checked before any data is read), channels of
        different lengths (a truncated file) or non-finite heights or forces; and for an unknown
        segment or a curve index beyond the file.
    """
    import os

    import afmformats  # a kept library of the field, imported only when a file is read

    if not isinstance(path, (str, os.PathLike)):
        raise TypeError(f"path must be a str or path-like, got {type(path).__name__}")
    segment = check_choice("segment", segment, ("approach", "retract"))
    where = f"path {os.fspath(path)!r}"
    if not os.path.isfile(path):
        raise ValueError(f"{where}: no such file")
    # afmformats' own errors derive from BaseException, not Exception
    errors = (Exception, getattr(getattr(afmformats, "errors", None), "AFMFileFormatError",
                                 Exception))
    try:
        data = afmformats.load_data(path, modality="force-distance")
    except errors as exc:  # format not supported, corrupt archive...
        raise ValueError(f"{where}: afmformats cannot read it as a force-distance curve "
                         f"({type(exc).__name__}: {exc})") from exc
    if len(data) == 0:
        raise ValueError(f"{where}: no force-distance curve in the file")
    index = check_integer("index", index, 0, len(data) - 1)
    fd = data[index]
    claimed = fd.metadata.get("point count") if hasattr(fd.metadata, "get") else None
    if claimed is not None and not (0 < float(claimed) <= MAX_FILE_POINTS):
        raise ValueError(f"{where}: its header claims {claimed} points, outside "
                         f"[1, {MAX_FILE_POINTS}]: refused before reading (a corrupt header?)")
    try:
        columns = fd.columns
        column = "height (measured)" if "height (measured)" in columns else "height (piezo)"
        seg = fd.appr if segment == "approach" else fd.retr
        height = np.asarray(seg[column], dtype=float)
        force = np.asarray(seg["force"], dtype=float)
    except (MemoryError, OverflowError) as exc:
        raise ValueError(f"{where}: too large to read ({exc})") from exc
    except errors as exc:  # e.g. IndexError when a channel is shorter than the others
        raise ValueError(f"{where}: its channels cannot be read together, the file is "
                         f"truncated or corrupt ({type(exc).__name__}: {exc})") from exc
    for name, values in ((column, height), ("force", force)):
        if values.size < 2:
            raise ValueError(f"{where}: channel {name!r} of the {segment} has "
                             f"{values.size} points")
        bad = np.flatnonzero(~np.isfinite(values))
        if bad.size:
            raise ValueError(f"{where}: channel {name!r} of the {segment} has {bad.size} "
                             f"non-finite values (first at index {bad[0]})")
    if height.size != force.size:
        raise ValueError(f"{where}: channels {column!r} ({height.size} points) and 'force' "
                         f"({force.size}) differ in length: the file is truncated or corrupt")
    k = fd.metadata.get("spring constant") if hasattr(fd.metadata, "get") else None
    try:
        k = float(k) if k is not None else None
    except (TypeError, ValueError):
        k = None
    kp = PARAMETERS["spring_constant"]
    k = k if k is not None and math.isfinite(k) and kp.low <= k <= kp.high else None
    return ForceCurve(-height, force, k, str(path))


def _baseline_stats(x, force):
    """Median and robust standard deviation of the first 40 % of the curve (off contact)."""
    n = max(5, int(0.4 * x.size))
    head = force[:n]
    med = float(np.median(head))
    sigma = 1.4826 * float(np.median(np.abs(head - med)))
    return med, sigma


def _model_description(tip) -> str:
    if isinstance(tip, Pyramidal):
        return f"{tip.title}, form {tip.form!r}: {tip.source}"
    return tip.title


def fit_curve(position, force, tip, poisson_ratio, *, spring_constant=None,
              pyramid_form="bilodeau") -> FitResult:
    """Fit E, the contact point and the baseline of an approach curve.

    Parameters
    ----------
    position : array_like
        Z_np in m if ``spring_constant`` is given, else the tip position in m; increasing
        towards the sample (sorted internally).
    force : array_like
        Force in N, same length (>= 10 points).
    tip : Tip
        The tip shape to fit with (its parameters are held fixed).
    poisson_ratio : float
        nu of the sample, in [0, 0.5), held fixed.
    spring_constant : float, optional
        k in N/m. With it, the model is the full cantilever solution F(Z_np - x_0) of
        :func:`~afmsmiler.contact.indent` (so the noise of F does not leak into the abscissa, as
        it would through x = Z_np - F / k); without it, the tip-shape law F(x - x_0) itself.
    pyramid_form : {"bilodeau", "rico"}
        For a :class:`~afmsmiler.contact.Pyramidal` tip, the prefactor fitted (it replaces the
        tip's own ``form``): Bilodeau's 0.7453 by default, as vendor software (JPK) reports, so
        that a fitted E compares with theirs; ``"rico"`` for the source paper's Eq. 12
        (1/sqrt(2): E comes out 5.4 % higher). ``FitResult.model`` says which was used.

    Returns
    -------
    FitResult

    Raises
    ------
    ValueError
        On bad input; if the curve shows no contact (the force never rises clearly above the
        noise of its baseline); if the fitted contact point falls outside the data.

    Notes
    -----
    With k the derivatives follow from differentiating k (Z - Z_s) = E* psi(Z_s): with the
    contact stiffness S = 2 E* r, dF/dx_0 = -k S / (k + S) and dF/dE* = k psi / (k + S).
    """
    x = check_array("position", position, "m", ndim=1, min_size=10)
    f = check_array("force", force, "N", ndim=1, size=x.size)
    check_instance("tip", tip, Tip)
    check_choice("pyramid_form", pyramid_form, tuple(PYRAMID_FORMS))
    if isinstance(tip, Pyramidal):
        tip = replace(tip, form=pyramid_form)
    nu = check_range("poisson_ratio", poisson_ratio, 0.0, 0.5, high_inclusive=False)
    k = None
    if spring_constant is not None:
        k = check_positive("spring_constant", spring_constant, "N/m")
    order = np.argsort(x, kind="stable")
    x, f = x[order], f[order]
    scale_nu = 1.0 - nu * nu

    # -- no contact? ------------------------------------------------------------------------
    f0, sigma = _baseline_stats(x, f)
    rise = f - f0
    floor = max(8.0 * sigma, 1e-9 * float(np.max(np.abs(f))) if np.any(f) else 0.0)
    above = rise > floor
    tail = max(3, x.size // 50)
    if rise[-1] <= floor or np.count_nonzero(above[-tail:]) < tail:
        raise ValueError(
            "the curve shows no contact: the force never rises clearly above its baseline "
            f"(largest rise {float(rise.max()):.3g} N vs noise {sigma:.3g} N); nothing to fit")

    # -- starting values ----------------------------------------------------------------------
    last_below = np.flatnonzero(~above)
    x0_guess = float(x[last_below[-1]]) if last_below.size else float(x[0])
    depth = float(x[-1] - x0_guess)
    if depth <= 0:
        raise ValueError("the curve shows no contact: no indentation after the estimated "
                         "contact point")
    f_scale = max(float(rise[-1]), floor)
    limit = tip.depth_limit
    d_end = depth - (f_scale / k if k else 0.0)
    d_end = min(max(d_end, 0.05 * depth), 0.99 * limit)
    e_guess = f_scale / float(tip._force_unit(np.array(d_end))) * scale_nu

    def unpack(p):
        return e_guess * p[0], x0_guess + depth * p[1], f0 + f_scale * p[2]

    def evaluate(p):
        """Model force, and dF/dE*, dF/dx_0 (per unit parameter)."""
        e, x0, b = unpack(p)
        e_star = e / scale_nu
        z = x - x0
        contact = z > 0
        z_s = np.zeros_like(z)
        if k is None:
            z_s[contact] = np.minimum(z[contact], 0.999 * limit)
        elif contact.any():
            zc = z[contact]
            if isinstance(tip, Spherical):
                zc = np.minimum(zc, 0.999 * tip.max_z_np(k, e_star))
            z_s[contact] = tip._solve(zc, k, e_star)
        psi = np.where(contact, tip._force_unit(z_s), 0.0)
        stiff = np.where(contact, 2.0 * e_star * tip._radius(z_s), 0.0)
        if k is None:
            return b + e_star * psi, psi, -stiff
        return b + e_star * psi, k * psi / (k + stiff), -k * stiff / (k + stiff)

    def residuals(p):  # in units of the force rise, so that the tolerances are relative
        return (evaluate(p)[0] - f) / f_scale

    def jacobian(p):
        _, d_e, d_x0 = evaluate(p)
        j = np.empty((x.size, 3))
        j[:, 0] = d_e * e_guess / scale_nu / f_scale
        j[:, 1] = d_x0 * depth / f_scale
        j[:, 2] = 1.0
        return j

    lower = [1e-9, (x[0] - x0_guess) / depth - 1.0, -np.inf]
    upper = [np.inf, 1.0, np.inf]
    sol = least_squares(residuals, [1.0, 0.0, 0.0], jac=jacobian, bounds=(lower, upper),
                        xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=5000)
    e, x0, b = unpack(sol.x)
    if not (x[0] < x0 < x[-1]):
        raise ValueError(f"the fitted contact point {x0:g} m lies outside the data "
                         f"[{x[0]:g}, {x[-1]:g}] m: the curve shows no usable contact")
    dof = max(x.size - 3, 1)
    s2 = 2.0 * sol.cost / dof  # residual variance in units of f_scale^2
    jac = jacobian(sol.x)
    cov = np.linalg.pinv(jac.T @ jac) * s2
    err = np.sqrt(np.clip(np.diag(cov), 0.0, np.inf)) * np.array([e_guess, depth, f_scale])
    fitted = evaluate(sol.x)[0]
    inv = np.empty_like(order)
    inv[order] = np.arange(order.size)
    return FitResult(float(e), float(err[0]), float(x0), float(err[1]), float(b), float(err[2]),
                     float(math.sqrt(s2) * f_scale), tip, nu, x[inv], fitted[inv],
                     _model_description(tip))
