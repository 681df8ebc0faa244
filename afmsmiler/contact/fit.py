"""Fitting force-distance curves: Young's modulus, contact point and baseline with uncertainties.

The force-volume workflow: for each curve, convert the positioner displacement to the tip
position x = Z_np - F / k (the apex's travel towards the sample; with no lever correction the
input already is the tip position), then fit::

    F(x) = F_0 + E / (1 - nu^2) psi(max(x - x_0, 0))

with psi the tip's force law at unit reduced modulus, for E, the contact point x_0 and the
baseline F_0, by least squares with the analytic Jacobian (dF/dx_0 = -2 E* r(x - x_0)):
Levenberg-Marquardt steps on the 3 x 3 normal equations, bounded to E > 0 and a contact point
at most one indentation depth before the data (Levenberg, Q. Appl. Math. 2, 164 (1944);
Marquardt, J. SIAM 11, 431 (1963); Nocedal and Wright, *Numerical Optimization*, 2nd ed.,
Sec. 10.3). The uncertainties are the square roots of the diagonal of s^2 (J^T J)^-1, with s^2
the residual variance: the usual linearised covariance (as :func:`scipy.optimize.curve_fit`
reports it).

:func:`fit_curves` fits many curves at once (a force-volume map: thousands of curves), the
solver's steps vectorised over the curves with NumPy, each curve converging on its own;
:func:`fit_curve` is its one-curve case, so that both share one model (``_model``), one
contact detection and one solver. They agree with scipy's ``curve_fit`` on the same problem
(``tests/test_contact_fit_batch.py``), and with the per-curve scipy ``least_squares`` fit they
replaced to some 1e-9 in E.

Curves come from :func:`synthetic_curve` (the exact model with Gaussian noise) or from a file of
any format the kept library ``afmformats`` reads (JPK, Asylum/Igor, AFM workshop, NT-MDT, its own
tab and HDF5 exports) via :func:`load_curve`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from ..validation import (check_array, check_choice, check_instance, check_integer,
                          check_range)
from .indent import indent
from .quantities import PARAMETERS
from .tips import PYRAMID_FORMS, Pyramidal, Spherical, Tip

__all__ = ["ForceCurve", "FitResult", "FitResults", "synthetic_curve", "load_curve",
           "fit_curve", "fit_curves", "MAX_FILE_POINTS", "MAX_BATCH_POINTS"]


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


#: Most points (curves x points per curve) one call of :func:`fit_curves` takes: 80 MB per
#: input array; a 64 x 64 force-volume map of 2000-point curves (8.2e6) fits. The fit works on
#: chunks of :data:`_CHUNK_POINTS` points, so that its working memory stays some 30 MB whatever
#: the batch, and takes about a second per million points (``benchmarks/bench_force_volume.py``).
MAX_BATCH_POINTS = 10_000_000
_CHUNK_POINTS = 1 << 18
#: Levenberg-Marquardt iterations per curve at most (a curve converges in some 5 to 30).
_MAX_ITERATIONS = 200
# converged when the step in the scaled parameters (each of order 1) is below this: the default
# xtol of scipy.optimize.least_squares, with its test |dx| <= xtol (xtol + |x|). A tighter one
# (1e-12) only grinds round-off: twice the model evaluations (a force-volume map's 19, not 6)
# for changes in E of under 1e-8 relative, a millionth of its standard error
# (tests/test_contact_fit_batch.py, the tolerance against a tight one)
_XTOL = 1e-8
# damping at which a curve whose steps all fail (round-off at its minimum) is declared converged
_MAX_DAMPING = 1e12


@dataclass(frozen=True)
class FitResults:
    """Result of :func:`fit_curves`: one value per curve (NaN where a curve was not fitted).

    Parameters
    ----------
    youngs_modulus, youngs_modulus_error : ndarray
        E and its standard error in Pa, shape (n_curves,).
    contact_point, contact_point_error : ndarray
        x_0 (on the abscissa fitted) and its standard error in m.
    baseline, baseline_error : ndarray
        F_0 and its standard error in N.
    residual_rms : ndarray
        Root-mean-square residual in N.
    failure : tuple of str
        Why each curve was not fitted (the message :func:`fit_curve` raises for it), or ``""``
        where it was.
    tip : Tip
        The tip shape fitted.
    poisson_ratio : float
        The Poisson's ratio assumed.
    model_force : ndarray
        The fitted model at each input point in N, shape (n_curves, n_points), in the input's
        order (NaN on curves not fitted).
    model : str
        The force law fitted and its source (as :attr:`FitResult.model`).
    """

    youngs_modulus: np.ndarray
    youngs_modulus_error: np.ndarray
    contact_point: np.ndarray
    contact_point_error: np.ndarray
    baseline: np.ndarray
    baseline_error: np.ndarray
    residual_rms: np.ndarray
    failure: tuple
    tip: Tip
    poisson_ratio: float
    model_force: np.ndarray = field(repr=False)
    model: str = ""

    @property
    def fitted(self) -> np.ndarray:
        """Boolean array, True where the curve was fitted."""
        return np.array([not reason for reason in self.failure], dtype=bool)

    def __len__(self) -> int:
        return len(self.failure)


def _model_description(tip) -> str:
    if isinstance(tip, Pyramidal):
        return f"{tip.title}, form {tip.form!r}: {tip.source}"
    return tip.title


def _check_fit_options(tip, poisson_ratio, spring_constant, pyramid_form):
    """The checked (tip with the pyramid form fitted, nu, k or None)."""
    check_instance("tip", tip, Tip)
    check_choice("pyramid_form", pyramid_form, tuple(PYRAMID_FORMS))
    if isinstance(tip, Pyramidal):
        tip = replace(tip, form=pyramid_form)
    nu = check_range("poisson_ratio", poisson_ratio, 0.0, 0.5, high_inclusive=False)
    k = None
    if spring_constant is not None:
        k = PARAMETERS["spring_constant"].check(spring_constant)  # [1e-6, 1e6] N/m, as a curve's
    return tip, nu, k


def _model(tip, k, x, e_star, x0, baseline):
    """The fitted force law on rows of curves: the one model of :func:`fit_curve(s)`.

    Parameters: ``x`` (n, m) sorted abscissae in m; ``e_star``, ``x0``, ``baseline`` (n,) in Pa,
    m, N. Returns the model force (n, m) in N and its derivatives dF/dE* (m^2) and dF/dx_0 (N/m).
    Without k: F = F_0 + E* psi(x - x_0); with k, the cantilever solution F(Z_np - x_0), whose
    derivatives follow from k (Z - Z_s) = E* psi(Z_s) (notes of :func:`fit_curve`).
    """
    # out of contact z_s = 0, where every tip's psi and r are exactly 0
    zc = np.maximum(x - x0[:, None], 0.0)
    es = e_star[:, None]
    if k is None:
        z_s = np.minimum(zc, 0.999 * tip.depth_limit)
    else:
        if isinstance(tip, Spherical):  # max_z_np = R + E* (F(R) / E*) / k: linear in E*
            radius = tip.radius
            zc = np.minimum(zc, 0.999 * (radius + es * (tip.max_z_np(k, 1.0) - radius)))
        z_s = tip._solve(zc, k, es)
    psi = tip._force_unit(z_s)
    stiff = 2.0 * es * tip._radius(z_s)
    force = baseline[:, None] + es * psi
    if k is None:
        return force, psi, -stiff
    return force, k * psi / (k + stiff), -k * stiff / (k + stiff)


def _start(x, f, tip, scale_nu, k):
    """Contact detection and starting values of sorted curves (n, m), vectorised.

    Returns (failure messages or "" per curve, x0_guess, depth, f0, f_scale, e_guess), the
    scales being 1 on failed curves so that nothing there overflows.
    """
    n, m = x.shape
    rows = np.arange(n)
    # the baseline: median and robust standard deviation of the first 40 % (off contact)
    head = f[:, :max(5, int(0.4 * m))]
    f0 = np.median(head, axis=1)
    sigma = 1.4826 * np.median(np.abs(head - f0[:, None]), axis=1)
    rise = f - f0[:, None]
    floor = np.maximum(8.0 * sigma, 1e-9 * np.max(np.abs(f), axis=1))
    above = rise > floor[:, None]
    tail = max(3, m // 50)
    contact = (rise[:, -1] > floor) & (np.count_nonzero(above[:, -tail:], axis=1) >= tail)
    below = ~above
    last_below = m - 1 - np.argmax(below[:, ::-1], axis=1)
    x0_guess = np.where(below.any(axis=1), x[rows, last_below], x[:, 0])
    depth = x[:, -1] - x0_guess
    failure = []
    for i in range(n):  # messages only (bounded by the batch's size)
        if not contact[i]:
            failure.append(
                "the curve shows no contact: the force never rises clearly above its baseline "
                f"(largest rise {float(rise[i].max()):.3g} N vs noise {float(sigma[i]):.3g} N); "
                "nothing to fit")
        elif depth[i] <= 0:
            failure.append("the curve shows no contact: no indentation after the estimated "
                           "contact point")
        else:
            failure.append("")
    good = np.array([not reason for reason in failure], dtype=bool)
    depth = np.where(good, depth, 1.0)
    f_scale = np.where(good, np.maximum(rise[:, -1], floor), 1.0)
    limit = tip.depth_limit
    d_end = depth - (f_scale / k if k else 0.0)
    d_end = np.minimum(np.maximum(d_end, 0.05 * depth), 0.99 * limit)
    with np.errstate(divide="ignore", over="ignore"):
        e_guess = f_scale / tip._force_unit(d_end) * scale_nu
    e_guess = np.where(good & np.isfinite(e_guess), e_guess, 1.0)
    return failure, x0_guess, depth, f0, f_scale, e_guess


def _solve_rows(x, f, tip, scale_nu, k):
    """Fit sorted curves (n, m) at once: Levenberg-Marquardt on each curve's 3 x 3 normal
    equations, in parameters scaled by the starting values (E / e_guess, x_0 shifted by the
    guess over the depth, F_0 shifted by the baseline over the force rise), residuals in units
    of the force rise, bounds E > 0 and x_0 in [x_first - depth, x_last] (as in scipy's
    ``least_squares`` before). Returns a dict of per-curve arrays and the model (n, m)."""
    n, m = x.shape
    failure, x0_guess, depth, f0, f_scale, e_guess = _start(x, f, tip, scale_nu, k)
    lower = np.stack([np.full(n, 1e-9), (x[:, 0] - x0_guess) / depth - 1.0,
                      np.full(n, -np.inf)], axis=1)
    upper = np.stack([np.full(n, np.inf), np.ones(n), np.full(n, np.inf)], axis=1)
    p = np.zeros((n, 3))
    p[:, 0] = 1.0

    def evaluate(q):
        """Residuals (in units of f_scale) and the Jacobian's columns of E and x_0 in the
        scaled parameters q of the active curves (the baseline's column is 1)."""
        model, d_e, d_x0 = _model(tip, k, xa, ea * q[:, 0] / scale_nu, x0a + da * q[:, 1],
                                  f0a + fsa * q[:, 2])
        fs = fsa[:, None]
        res = (model - fa) / fs
        d_e *= (ea / scale_nu)[:, None] / fs
        d_x0 *= da[:, None] / fs
        return res, d_e, d_x0

    def normal_equations(res, j_e, j_x0):
        """J^T J (n, 3, 3) and J^T r (n, 3) from the residuals and the Jacobian's columns."""
        a = np.empty((res.shape[0], 3, 3))
        cols = (j_e, j_x0)
        for i in range(2):
            for j in range(i, 2):
                a[:, i, j] = a[:, j, i] = np.einsum("ij,ij->i", cols[i], cols[j])
            a[:, i, 2] = a[:, 2, i] = cols[i].sum(axis=1)
        a[:, 2, 2] = res.shape[1]
        g = np.stack([np.einsum("ij,ij->i", j_e, res), np.einsum("ij,ij->i", j_x0, res),
                      res.sum(axis=1)], axis=1)
        return a, g

    # the active curves' data, taken out once and shrunk as curves converge
    active = np.flatnonzero([not reason for reason in failure])
    xa, fa, ea, x0a, da, f0a, fsa, lo, hi, pa = (
        v[active] for v in (x, f, e_guess, x0_guess, depth, f0, f_scale, lower, upper, p))
    res, j_e, j_x0 = evaluate(pa)
    cost = np.einsum("ij,ij->i", res, res)
    damping = np.full(active.size, 1e-3)
    final_cost = np.zeros(n)
    final_a = np.zeros((n, 3, 3))
    final_res = np.zeros((n, m))
    for iteration in range(_MAX_ITERATIONS):  # bounded; each curve leaves once converged
        if active.size == 0:
            break
        a, g = normal_equations(res, j_e, j_x0)
        diag = np.diagonal(a, axis1=1, axis2=2)
        damped = a + damping[:, None, None] * (diag[:, :, None] * np.eye(3))
        try:
            step = np.linalg.solve(damped, -g[:, :, None])[:, :, 0]
        except np.linalg.LinAlgError:  # a singular curve: fall back to the pseudo-inverse
            step = -(np.linalg.pinv(damped) @ g[:, :, None])[:, :, 0]
        step = np.nan_to_num(step)
        q = np.clip(pa + step, lo, hi)
        moved = q - pa
        new_res, new_j_e, new_j_x0 = evaluate(q)
        new_cost = np.einsum("ij,ij->i", new_res, new_res)
        better = new_cost < cost
        pa = np.where(better[:, None], q, pa)
        if better.all():
            res, j_e, j_x0 = new_res, new_j_e, new_j_x0
        elif better.any():
            res[better], j_e[better], j_x0[better] = (new_res[better], new_j_e[better],
                                                      new_j_x0[better])
        cost = np.where(better, new_cost, cost)
        damping = np.where(better, np.maximum(damping / 10.0, 1e-15), damping * 10.0)
        size = np.sqrt(np.sum(moved * moved, axis=1))
        done = (size <= _XTOL * (np.sqrt(np.sum(pa ** 2, axis=1)) + _XTOL)) | \
            (damping > _MAX_DAMPING)
        if iteration == _MAX_ITERATIONS - 1:  # out of iterations: report where they stopped
            done[:] = True
        if done.any():
            rows = active[done]
            p[rows] = pa[done]
            final_cost[rows] = cost[done]
            final_res[rows] = res[done]
            final_a[rows] = normal_equations(res[done], j_e[done], j_x0[done])[0]
            keep = ~done
            active, xa, fa, ea, x0a, da, f0a, fsa, lo, hi, pa = (
                v[keep] for v in (active, xa, fa, ea, x0a, da, f0a, fsa, lo, hi, pa))
            res, j_e, j_x0, cost, damping = (
                v[keep] for v in (res, j_e, j_x0, cost, damping))

    e = e_guess * p[:, 0]
    x0 = x0_guess + depth * p[:, 1]
    b = f0 + f_scale * p[:, 2]
    dof = max(m - 3, 1)
    s2 = final_cost / dof  # in units of f_scale^2
    cov = np.linalg.pinv(final_a) * s2[:, None, None]
    err = np.sqrt(np.clip(np.diagonal(cov, axis1=1, axis2=2), 0.0, np.inf)) * \
        np.stack([e_guess, depth, f_scale], axis=1)
    fitted = final_res * f_scale[:, None] + f
    for i in range(n):
        if not failure[i] and not (x[i, 0] < x0[i] < x[i, -1]):
            failure[i] = (f"the fitted contact point {x0[i]:g} m lies outside the data "
                          f"[{x[i, 0]:g}, {x[i, -1]:g}] m: the curve shows no usable contact")
    bad = np.array([bool(reason) for reason in failure])
    values = dict(youngs_modulus=e, youngs_modulus_error=err[:, 0], contact_point=x0,
                  contact_point_error=err[:, 1], baseline=b, baseline_error=err[:, 2],
                  residual_rms=np.sqrt(s2) * f_scale)
    for name in values:
        values[name] = np.where(bad, np.nan, values[name])
    return values, np.where(bad[:, None], np.nan, fitted), failure


def _fit_sorted(x, f, tip, nu, k):
    """Fit curves (n, m) in chunks of bounded memory, each row sorted by x; return the results
    in the input's order: (values dict, model (n, m), failure list)."""
    n, m = x.shape
    per_chunk = max(1, _CHUNK_POINTS // m)
    values, failure = {}, []
    fitted = np.empty_like(f)
    for i in range(0, n, per_chunk):  # bounded: n / per_chunk chunks
        rows = slice(i, i + per_chunk)
        # the stable sort's order without sorting where every row rises or strictly falls (a
        # force-volume map's retracts: the sort and its scatter were some 1.5 ms of 100 curves)
        step = np.diff(x[rows], axis=1)
        if np.all(step < 0):
            part, model, reasons = _solve_rows(np.ascontiguousarray(x[rows, ::-1]),
                                               np.ascontiguousarray(f[rows, ::-1]), tip,
                                               1.0 - nu * nu, k)
            fitted[rows] = model[:, ::-1]
        elif np.all(step >= 0):
            part, model, reasons = _solve_rows(x[rows], f[rows], tip, 1.0 - nu * nu, k)
            fitted[rows] = model
        else:
            order = np.argsort(x[rows], axis=1, kind="stable")
            part, model, reasons = _solve_rows(np.take_along_axis(x[rows], order, axis=1),
                                               np.take_along_axis(f[rows], order, axis=1),
                                               tip, 1.0 - nu * nu, k)
            np.put_along_axis(fitted[rows], order, model, axis=1)
        for name, value in part.items():
            values.setdefault(name, []).append(value)
        failure.extend(reasons)
    return {name: np.concatenate(parts) for name, parts in values.items()}, fitted, failure


def fit_curves(position, force, tip, poisson_ratio, *, spring_constant=None,
               pyramid_form="bilodeau") -> FitResults:
    """Fit E, the contact point and the baseline of many approach curves at once.

    The batched form of :func:`fit_curve` (which is its one-curve case): the same model, the
    same starting values and contact detection, and the same least-squares problem, solved for
    all curves together by Levenberg-Marquardt steps on each curve's 3 x 3 normal equations
    (Levenberg 1944; Marquardt 1963; Nocedal and Wright, *Numerical Optimization*, 2nd ed.,
    Sec. 10.3), vectorised over the curves with NumPy.

    Parameters
    ----------
    position : array_like
        Shape (n_curves, n_points): per curve, Z_np in m if ``spring_constant`` is given, else
        the tip position in m; increasing towards the sample (each row sorted internally).
    force : array_like
        Force in N, the same shape (n_points >= 10), at most :data:`MAX_BATCH_POINTS` values.
    tip : Tip
        The tip shape (its parameters held fixed).
    poisson_ratio : float
        nu of the samples, in [0, 0.5), held fixed.
    spring_constant : float, optional
        k in N/m, as in :func:`fit_curve`.
    pyramid_form : {"bilodeau", "rico"}
        For a pyramidal tip, the prefactor fitted, as in :func:`fit_curve`.

    Returns
    -------
    FitResults
        Per-curve arrays; a curve without contact, or whose contact point falls outside its
        data, is NaN there and its ``failure`` says why (the message :func:`fit_curve` raises).

    Raises
    ------
    ValueError
        On bad input (arrays not 2-D, of different shapes, non-finite, fewer than 10 points per
        curve or more than :data:`MAX_BATCH_POINTS` in all; nu or k out of range), before any
        fit.
    TypeError
        If ``tip`` is not a :class:`Tip`.

    Examples
    --------
    >>> from afmsmiler.contact import Parabolic, synthetic_curve
    >>> curves = [synthetic_curve(Parabolic(20e-9), spring_constant=0.1, youngs_modulus=e,
    ...                           poisson_ratio=0.3, noise=1e-12, seed=1) for e in (1e6, 3e6)]
    >>> r = fit_curves([c.z_np for c in curves], [c.force for c in curves], Parabolic(20e-9),
    ...                0.3, spring_constant=0.1)
    >>> [round(float(e) / 1e6, 2) for e in r.youngs_modulus]
    [1.0, 3.0]
    """
    x = check_array("position", position, "m", ndim=2, max_size=MAX_BATCH_POINTS)
    if x.shape[1] < 10 or x.shape[0] < 1:
        raise ValueError(f"position must have at least one curve of at least 10 points, got "
                         f"shape {x.shape}")
    f = check_array("force", force, "N", max_size=MAX_BATCH_POINTS)
    if f.shape != x.shape:
        raise ValueError(f"force must have the shape of position {x.shape}, got {f.shape}")
    tip, nu, k = _check_fit_options(tip, poisson_ratio, spring_constant, pyramid_form)
    values, fitted, failure = _fit_sorted(x, f, tip, nu, k)
    return FitResults(**values, failure=tuple(failure), tip=tip, poisson_ratio=nu,
                      model_force=fitted, model=_model_description(tip))


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
        k in N/m, in [1e-6, 1e6]. With it, the model is the full cantilever solution
        F(Z_np - x_0) of :func:`~afmsmiler.contact.indent` (so the noise of F does not leak into
        the abscissa, as it would through x = Z_np - F / k); without it, the tip-shape law
        F(x - x_0) itself.
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
    The one-curve case of :func:`fit_curves` (one model, one solver). With k the derivatives
    follow from differentiating k (Z - Z_s) = E* psi(Z_s): with the contact stiffness
    S = 2 E* r, dF/dx_0 = -k S / (k + S) and dF/dE* = k psi / (k + S).
    """
    x = check_array("position", position, "m", ndim=1, min_size=10)
    f = check_array("force", force, "N", ndim=1, size=x.size)
    tip, nu, k = _check_fit_options(tip, poisson_ratio, spring_constant, pyramid_form)
    values, fitted, failure = _fit_sorted(x[None, :], f[None, :], tip, nu, k)
    if failure[0]:
        raise ValueError(failure[0])
    v = {name: float(value[0]) for name, value in values.items()}
    return FitResult(v["youngs_modulus"], v["youngs_modulus_error"], v["contact_point"],
                     v["contact_point_error"], v["baseline"], v["baseline_error"],
                     v["residual_rms"], tip, nu, x, fitted[0], _model_description(tip))
