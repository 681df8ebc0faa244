"""The batched fit of many force curves, fit_curves: batching invariance, the same as an
independent scipy fit of an independently written model, the vendor's fit of a real JPK curve
inside a batch, per-curve failures, and bad input named before any work.

``fit_curve`` is the one-curve case of ``fit_curves`` (the same code), so comparing the two checks
*batching invariance* only: a curve's result does not depend on the other curves of its batch,
their order, or the chunk it falls in. What makes the fit right is checked beside each of those
tests by a source that shares no code with it: scipy's curve_fit below, the JPK software's fit,
the true modulus within three standard errors, the scatter of E over noise draws.

Independent sources: scipy.optimize.curve_fit (MINPACK's Levenberg-Marquardt with a
finite-difference Jacobian, and its own covariance) on the model written here from the tips'
public force law (no cantilever) or from module (d)'s forward solver ``indent`` (with the
lever); the JPK data-processing software's fit of spot3-0192.jpk-force (E = 233.1 kPa, contact
point 18.03 um, as in tests/test_contact_fit.py). Tolerances: 1e-6 relative on E (as the task
asks; the two fits solve one least-squares problem, and agree to some 1e-9 in practice); against
curve_fit 1e-5 relative on E and 1e-3 on its standard error (a finite-difference Jacobian
carries some 1e-6 to 1e-4 of relative error into its covariance).
"""
import math

import numpy as np
import pytest
from scipy.optimize import curve_fit

from afmsmiler import data
from afmsmiler.contact import (Conical, Parabolic, Pyramidal, Spherical, fit_curve, indent,
                               load_curve, synthetic_curve)
from afmsmiler.contact import fit as fit_module
from afmsmiler.contact.fit import MAX_BATCH_POINTS, FitResults, fit_curves

TIPS = [Parabolic(20e-9), Spherical(5e-6), Conical(math.radians(20)),
        Pyramidal(math.radians(35), form="bilodeau")]
IDS = [t.key for t in TIPS]
NU, K, NOISE, F0 = 0.45, 0.05, 20e-12, 1e-10
# (E in Pa, contact point in m): a soft gel to a stiffer one, contact early to late in the ramp
CASES = [(50e3, -100e-9), (200e3, 50e-9), (1e6, 0.0), (3e6, 150e-9)]


def _curves(tip, seed=0):
    return [synthetic_curve(tip, spring_constant=K, youngs_modulus=e, poisson_ratio=NU,
                            z_np_range=(-300e-9, 500e-9), points=800, contact_point=cp,
                            baseline=F0, noise=NOISE, seed=seed + i)
            for i, (e, cp) in enumerate(CASES)]


def _axis(curve, with_k):
    return curve.z_np if with_k else curve.tip_position


@pytest.mark.parametrize("with_k", [True, False], ids=["Z_np with k", "tip position"])
@pytest.mark.parametrize("tip", TIPS, ids=IDS)
def test_batching_invariance_each_curve_fits_as_it_does_alone(tip, with_k):
    curves = _curves(tip, seed=10)
    k = K if with_k else None
    batch = fit_curves([_axis(c, with_k) for c in curves], [c.force for c in curves], tip, NU,
                       spring_constant=k)
    assert isinstance(batch, FitResults) and len(batch) == len(CASES) and batch.fitted.all()
    assert batch.model == fit_curve(_axis(curves[0], with_k), curves[0].force, tip, NU,
                                    spring_constant=k).model
    for i, c in enumerate(curves):
        one = fit_curve(_axis(c, with_k), c.force, tip, NU, spring_constant=k)
        assert batch.youngs_modulus[i] == pytest.approx(one.youngs_modulus, rel=1e-6)
        assert batch.youngs_modulus_error[i] == pytest.approx(one.youngs_modulus_error,
                                                              rel=1e-6)
        assert abs(batch.contact_point[i] - one.contact_point) <= 1e-6 * one.contact_point_error
        assert abs(batch.baseline[i] - one.baseline) <= 1e-6 * one.baseline_error
        assert batch.residual_rms[i] == pytest.approx(one.residual_rms, rel=1e-6)
        np.testing.assert_allclose(batch.model_force[i], one.model_force, rtol=0,
                                   atol=1e-6 * NOISE)
        if with_k:  # and the truth within 3 standard errors (on the tip-position axis the
            # force noise leaks into the abscissa, x = Z_np - F / k, and biases E: fit_curve)
            assert abs(one.youngs_modulus - CASES[i][0]) <= 3 * one.youngs_modulus_error


def _reference(tip, x, force, with_k, start):
    """curve_fit of the model written independently: F_0 + E* F_tip(x - x_0) at E* = 1 (the
    tip's public force law), or with the lever module (d)'s forward solver indent."""
    scale = np.array([start[0], 1e-9, 1e-12])  # E, x_0, F_0 to order 1

    def model(x, e, x0, f0):
        e, x0, f0 = np.array([e, x0, f0]) * scale
        if with_k:
            return f0 + indent(x - x0, K, tip, e, NU).force
        z = np.clip(x - x0, 0.0, 0.999 * tip.depth_limit)
        return f0 + e / (1 - NU ** 2) * np.asarray(tip.force(z, 1.0))

    p, cov = curve_fit(model, x, force, p0=np.asarray(start) / scale, xtol=1e-14, ftol=1e-14,
                       gtol=1e-14, maxfev=20000)
    return p * scale, np.sqrt(np.diag(cov)) * scale


@pytest.mark.parametrize("with_k", [True, False], ids=["Z_np with k", "tip position"])
@pytest.mark.parametrize("tip", TIPS, ids=IDS)
def test_batch_equals_an_independent_scipy_fit(tip, with_k):
    curves = _curves(tip, seed=20)[:2]
    k = K if with_k else None
    batch = fit_curves([_axis(c, with_k) for c in curves], [c.force for c in curves], tip, NU,
                       spring_constant=k)
    for i, c in enumerate(curves):
        e, cp = CASES[i]
        (e_ref, x0_ref, f0_ref), err = _reference(tip, _axis(c, with_k), c.force, with_k,
                                                  (1.1 * e, cp + 2e-9, 0.0))
        assert batch.youngs_modulus[i] == pytest.approx(e_ref, rel=1e-5)
        assert batch.youngs_modulus_error[i] == pytest.approx(err[0], rel=1e-3)
        assert abs(batch.contact_point[i] - x0_ref) <= 1e-4 * err[1]
        assert abs(batch.baseline[i] - f0_ref) <= 1e-4 * err[2]


def test_batching_invariance_and_the_vendors_fit_of_the_real_jpk_curve():
    pytest.importorskip("afmformats")
    curve = load_curve(data.path("spot3-0192.jpk-force"))
    x, f = curve.tip_position, curve.force
    # the same curve twice, once in reversed order (each row is sorted internally), and a
    # noisier copy: the batch fits each as fit_curve does alone
    noisy = f + np.random.default_rng(0).normal(0.0, 20e-12, f.size)
    batch = fit_curves([x, x[::-1], x], [f, f[::-1], noisy], Parabolic(40e-9), 0.0)
    one = fit_curve(x, f, Parabolic(40e-9), 0.0)
    alone = fit_curve(x, noisy, Parabolic(40e-9), 0.0)
    for i, ref in ((0, one), (1, one), (2, alone)):
        assert batch.youngs_modulus[i] == pytest.approx(ref.youngs_modulus, rel=1e-6)
        assert batch.youngs_modulus_error[i] == pytest.approx(ref.youngs_modulus_error,
                                                              rel=1e-6)
        assert abs(batch.contact_point[i] - ref.contact_point) <= 1e-6 * ref.contact_point_error
    np.testing.assert_allclose(batch.model_force[1], one.model_force[::-1], rtol=0, atol=1e-15)
    # the vendor's (JPK) fit, E(nu = 0.5) = 0.75 E*: half a unit in its last printed digit
    assert 0.75 * batch.youngs_modulus[0] == pytest.approx(233.1e3, rel=0, abs=0.05e3)
    assert -batch.contact_point[0] == pytest.approx(18.03e-6, rel=0, abs=0.005e-6)


def test_a_curve_without_contact_is_nan_with_fit_curves_message():
    tip = Parabolic(20e-9)
    good = _curves(tip)[1]
    z = good.z_np
    flat = np.random.default_rng(1).normal(0.0, NOISE, z.size)  # noise only: no contact
    batch = fit_curves([z, z, z], [good.force, flat, good.force], tip, NU, spring_constant=K)
    with pytest.raises(ValueError, match="no contact") as raised:
        fit_curve(z, flat, tip, NU, spring_constant=K)
    assert batch.failure == ("", str(raised.value), "")
    assert list(batch.fitted) == [True, False, True]
    for name in ("youngs_modulus", "youngs_modulus_error", "contact_point", "baseline",
                 "residual_rms"):
        assert np.isnan(getattr(batch, name)[1])
    assert np.isnan(batch.model_force[1]).all()
    one = fit_curve(z, good.force, tip, NU, spring_constant=K)
    assert batch.youngs_modulus[0] == batch.youngs_modulus[2]
    assert batch.youngs_modulus[0] == pytest.approx(one.youngs_modulus, rel=1e-6)


def test_chunks_do_not_change_the_results(monkeypatch):
    # chunks of 3 curves (the default holds 2^18 points): the same results as one chunk
    tip = Parabolic(20e-9)
    curves = _curves(tip, seed=30) * 2
    args = ([c.z_np for c in curves], [c.force for c in curves], tip, NU)
    whole = fit_curves(*args, spring_constant=K)
    monkeypatch.setattr(fit_module, "_CHUNK_POINTS", 3 * curves[0].z_np.size)
    chunked = fit_curves(*args, spring_constant=K)
    np.testing.assert_allclose(chunked.youngs_modulus, whole.youngs_modulus, rtol=1e-6)
    np.testing.assert_allclose(chunked.model_force, whole.model_force, rtol=0, atol=1e-6 * NOISE)
    assert chunked.failure == whole.failure


@pytest.mark.parametrize("with_k", [True, False], ids=["with k", "without k"])
def test_rows_that_all_fall_fit_as_the_same_rows_rising(with_k):
    # issue 24: a batch whose every row falls (a force-volume map's retracts) is fitted on the
    # rows reversed without a sort; the results are those of the rows given rising, bit for bit,
    # and of the sorted path (one row of the batch that is not monotonic)
    tip = Parabolic(20e-9)
    curves = _curves(tip, seed=40)
    x = np.array([c.z_np for c in curves])  # rising on every row (a noisy tip position is not)
    f = np.array([c.force for c in curves])
    assert (np.diff(x, axis=1) > 0).all()
    k = K if with_k else None
    rising = fit_curves(x, f, tip, NU, spring_constant=k)
    falling = fit_curves(x[:, ::-1], f[:, ::-1], tip, NU, spring_constant=k)
    mixed_x, mixed_f = np.vstack([x[:, ::-1], x[:1]]), np.vstack([f[:, ::-1], f[:1]])
    sorted_path = fit_curves(mixed_x, mixed_f, tip, NU, spring_constant=k)
    for name in ("youngs_modulus", "youngs_modulus_error", "contact_point", "baseline",
                 "residual_rms"):
        np.testing.assert_array_equal(getattr(falling, name), getattr(rising, name))
        np.testing.assert_array_equal(getattr(sorted_path, name)[:-1], getattr(rising, name))
    np.testing.assert_array_equal(falling.model_force, rising.model_force[:, ::-1])
    np.testing.assert_array_equal(sorted_path.model_force[:-1], rising.model_force[:, ::-1])


@pytest.mark.slow
def test_batching_invariance_across_the_chunks_of_a_large_batch():
    # 400 curves of 800 points: two chunks (of 327 curves, 2^18 points); each curve as alone
    tip = Parabolic(20e-9)
    e, cp = CASES[1]
    base = synthetic_curve(tip, spring_constant=K, youngs_modulus=e, poisson_ratio=NU,
                           z_np_range=(-300e-9, 500e-9), points=800, contact_point=cp,
                           baseline=F0)
    forces = base.force + np.random.default_rng(5).normal(0.0, NOISE, (400, base.z_np.size))
    z = np.broadcast_to(base.z_np, forces.shape)
    batch = fit_curves(z, forces, tip, NU, spring_constant=K)
    assert batch.fitted.all()
    for i in (0, 326, 327, 399):  # first, either side of the chunks' border, last
        one = fit_curve(z[i], forces[i], tip, NU, spring_constant=K)
        assert batch.youngs_modulus[i] == pytest.approx(one.youngs_modulus, rel=1e-6)
    # the scatter of E over the noise draws is the reported standard error (within 15 %)
    assert np.std(batch.youngs_modulus) == pytest.approx(np.median(batch.youngs_modulus_error),
                                                         rel=0.15)


# --- bad input: named, before any work ------------------------------------------------------
def _good():
    c = _curves(Parabolic(20e-9))[1]
    return dict(position=np.stack([c.z_np, c.z_np]), force=np.stack([c.force, c.force]),
                tip=Parabolic(20e-9), poisson_ratio=NU, spring_constant=K)


@pytest.mark.parametrize("with_k", [True, False], ids=["Z_np with k", "tip position"])
@pytest.mark.parametrize("tip", TIPS, ids=IDS)
def test_the_step_tolerance_stops_where_a_tight_one_agrees(tip, with_k, monkeypatch):
    # the fit stops at scipy least_squares' default xtol (1e-8): a fit ground on to 1e-13 (where
    # only round-off moves) gives the same E to 1e-7 and contact point to 1e-4 of its error
    curves = _curves(tip, seed=30)
    args = ([_axis(c, with_k) for c in curves], [c.force for c in curves], tip, NU)
    k = K if with_k else None
    stopped = fit_curves(*args, spring_constant=k)
    monkeypatch.setattr(fit_module, "_XTOL", 1e-13)
    tight = fit_curves(*args, spring_constant=k)
    np.testing.assert_allclose(stopped.youngs_modulus, tight.youngs_modulus, rtol=1e-7)
    np.testing.assert_allclose(stopped.youngs_modulus_error, tight.youngs_modulus_error,
                               rtol=1e-6)
    assert np.all(np.abs(stopped.contact_point - tight.contact_point)
                  <= 1e-4 * tight.contact_point_error)


@pytest.mark.parametrize("change, error, match", [
    (dict(position=np.zeros(800)), ValueError, r"^position must be a 2-D array"),
    (dict(force=np.zeros((2, 799))), ValueError, r"^force must have the shape of position"),
    (dict(force=np.zeros((3, 800))), ValueError, r"^force must have the shape of position"),
    (dict(position=np.zeros((2, 9)), force=np.zeros((2, 9))), ValueError,
     r"^position must have at least one curve of at least 10 points"),
    (dict(position=np.zeros((0, 20)), force=np.zeros((0, 20))), ValueError,
     r"^position must have at least one curve"),
    (dict(force=np.full((2, 800), math.nan)), ValueError, r"^force must be finite \(in N\)"),
    (dict(position=[[1.0, "a"] * 10]), ValueError, r"^position must be an array of real"),
    (dict(tip="parabolic"), TypeError, r"^tip must be"),
    (dict(poisson_ratio=0.5), ValueError, r"^poisson_ratio must be in"),
    (dict(spring_constant=0.0), ValueError, r"^spring_constant must be in \[1e-06, 1e\+06\] N/m"),
    (dict(pyramid_form="sneddon"), ValueError, r"^pyramid_form must be one of"),
])
def test_bad_input_is_named(change, error, match):
    with pytest.raises(error, match=match):
        fit_curves(**{**_good(), **change})


def test_the_size_limit_is_checked_before_anything_is_allocated():
    # a read-only view of 10 million points per array: refused from its size alone
    n = MAX_BATCH_POINTS // 1000 + 1
    huge = np.broadcast_to(0.0, (n, 1000))
    with pytest.raises(ValueError, match=rf"^position must have at most {MAX_BATCH_POINTS}"):
        fit_curves(huge, huge, Parabolic(20e-9), NU)
    ok = np.broadcast_to(np.linspace(0, 1e-7, 1000), (2, 1000))
    with pytest.raises(ValueError, match=rf"^force must have at most {MAX_BATCH_POINTS}"):
        fit_curves(ok, huge, Parabolic(20e-9), NU)
