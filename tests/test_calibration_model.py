"""Spring-constant calibration (Sader, thermal noise, added mass) against independent sources.

Sources: the authors' published calibration code for Sader, Chon and Mulvaney (1999) (its worked
input, the 397 x 29 um lever of their Table I at 17.36 kHz and Q = 55.5 in their air), evaluated
here with mpmath's Bessel functions; the clamped-free eigenvalue b_1 L = 1.87510407 (Blevins,
Table 8-1); Butt and Jaschke (1995)'s 0.971 and 0.817 and their sum rule 4/3 for an optical
lever over all modes; Proksch et al. (2004)'s chi = 1.09; finite differences of module (a)'s
own mode shapes (a different code path from the calibration's closed-form slope); equipartition
(the fluctuation-dissipation spectrum of every mode integrates to share_n k_B T / k, whatever the
fluid); the chi-squared statistics of averaged periodograms (mean 1, variance 1/M); Monte Carlo
spreads against the Fisher-matrix errors the fit reports.
"""
import dataclasses
import math

import mpmath
import numpy as np
import pytest
import scipy.constants
import scipy.special

from afmsmiler.brownian import mode_share
from afmsmiler.calibration import (SADER_FACTOR, ThermalSpectrum, added_mass_spring_constant,
                                   fit_thermal_spectrum, optical_lever_correction,
                                   sader_calibration, sader_spring_constant, thermal_calibration,
                                   thermal_spectrum)
from afmsmiler.cantilever import Cantilever
from afmsmiler.hydrodynamics import FLUIDS, fluid_mode

KB = scipy.constants.k
B1 = 1.87510407  # Blevins, Table 8-1
SHARE1 = 12 / B1 ** 4   # Butt and Jaschke (1995): 0.971


def _contact():
    return Cantilever.from_material("silicon", 450e-6, 50e-6, 2e-6)


def _tapping():
    return Cantilever.from_material("silicon", 125e-6, 30e-6, 4e-6)


# -- Sader's method --------------------------------------------------------------------------
def _sader_authors(length_um, width_um, f_khz, q):
    """k[L, b, f, Q] of the authors' Mathematica code (normal.math), with mpmath's Bessel K:
    rho = 1.18, eta = 1.86e-5, Re = rho w b^2 / (4 eta), k = 0.1906 rho b^2 L Q Im(Gamma) w^2."""
    rho, eta = 1.18, 1.86e-5
    b, length, w = width_um * 1e-6, length_um * 1e-6, 2 * math.pi * 1000 * f_khz
    re = rho * w * b ** 2 / 4 / eta
    x = math.log10(re)
    omre = ((0.91324 - 0.48274 * x + 0.46842 * x ** 2 - 0.12886 * x ** 3 + 0.044055 * x ** 4
             - 0.0035117 * x ** 5 + 0.00069085 * x ** 6)
            / (1 - 0.56964 * x + 0.48690 * x ** 2 - 0.13444 * x ** 3 + 0.045155 * x ** 4
               - 0.0035862 * x ** 5 + 0.00069085 * x ** 6))
    omimag = ((-0.024134 - 0.029256 * x + 0.016294 * x ** 2 - 0.00010961 * x ** 3
               + 0.000064577 * x ** 4 - 0.000044510 * x ** 5)
              / (1 - 0.59702 * x + 0.55182 * x ** 2 - 0.18357 * x ** 3 + 0.079156 * x ** 4
                 - 0.014369 * x ** 5 + 0.0028361 * x ** 6))
    root = mpmath.sqrt(1j * re)
    circ = 1 + 4j * mpmath.besselk(1, -1j * root) / (root * mpmath.besselk(0, -1j * root))
    gamma = complex((omre + 1j * omimag) * circ)
    return 0.1906 * rho * b ** 2 * length * q * gamma.imag * w ** 2


@pytest.mark.parametrize("length, width, f, q", [(397, 29, 17.36, 55.5), (197, 29, 66.0, 140.0),
                                                 (125, 30, 300.0, 500.0), (450, 50, 13.0, 60.0)])
def test_sader_reproduces_the_authors_code(length, width, f, q):
    k = sader_spring_constant(length * 1e-6, width * 1e-6, f * 1e3, q, "air_sader1999")
    assert k == pytest.approx(_sader_authors(length, width, f, q), rel=1e-9)


def test_sader_constant_is_the_effective_mass_of_mode_1():
    # k = M_e omega_vac^2 with M_e = k / omega_vac^2 = 3 / (b_1 L)^4 M = 0.2427 M, times pi / 4
    assert SADER_FACTOR == pytest.approx(math.pi / 4 * 3 / B1 ** 4, rel=1e-4)


@pytest.mark.parametrize("fluid", ["air", "water"])
def test_sader_on_the_models_own_resonance_returns_the_true_k(fluid):
    # with f and Q from Sader's own weak-damping relations, Q Gamma_i omega_f^2 = omega_vac^2 / T
    # exactly, and the method returns M_e omega_vac^2 = k up to the rounding of 0.1906 (3e-5):
    # a check of the algebra, not of the method's accuracy (see the thermal fit below)
    for lever in (_contact(), _tapping(), Cantilever.from_material("silicon", 225e-6, 28e-6, 3e-6)):
        assert sader_calibration(lever, fluid).relative_error == pytest.approx(0.0, abs=1e-4)


def test_sader_from_a_fitted_spectrum_works_in_air_and_fails_in_water():
    # the lab's way: f_f and Q_f from the thermal peak's SHO fit. In air (Q >> 1) the method
    # holds within a few per cent; in water (Q ~ 2) the SHO's Q is not Sader's and k is far off
    lever = _contact()
    for fluid, low, high in (("air", -0.03, 0.03), ("water", 0.1, 0.6)):
        fit = fit_thermal_spectrum(thermal_spectrum(lever, fluid, points=2 ** 16, averages=16,
                                                    seed=5))
        k = sader_spring_constant(lever.length, lever.width, fit.resonance_frequency,
                                  fit.quality_factor, fluid)
        assert low < k / lever.spring_constant - 1 < high, fluid


def test_sader_bad_input_is_named():
    with pytest.raises(ValueError, match="width = .* resonance_frequency = .* outside the range"):
        sader_spring_constant(0.1, 0.01, 1e6, 100.0, "water")
    with pytest.raises(ValueError, match="quality_factor"):
        sader_spring_constant(400e-6, 30e-6, 1e4, -1.0)
    with pytest.raises(ValueError, match="fluid"):
        sader_spring_constant(400e-6, 30e-6, 1e4, 50.0, "honey")


# -- the added-mass method -------------------------------------------------------------------
def test_added_mass_recovers_k_of_a_point_mass_oscillator():
    lever = _contact()
    k, m_eff = lever.spring_constant, lever.effective_mass
    for added in (0.1 * m_eff, m_eff, 10 * m_eff):
        nu0 = math.sqrt(k / m_eff) / (2 * math.pi)
        nu1 = math.sqrt(k / (m_eff + added)) / (2 * math.pi)
        assert added_mass_spring_constant(added, nu1, nu0) == pytest.approx(k, rel=1e-12)
    with pytest.raises(ValueError, match="loaded_frequency must be below"):
        added_mass_spring_constant(1e-12, 2e4, 1e4)
    with pytest.raises(ValueError, match="added_mass"):
        added_mass_spring_constant(-1e-12, 1e4, 2e4)


# -- the optical lever -----------------------------------------------------------------------
def _chi_by_finite_differences(mode, spot):
    """chi from module (a)'s mode shape: [3 (2u - u^2) / 2] / [L phi'(uL) / phi(L)]."""
    lever = _contact()
    length = lever.length
    h = 1e-5 * length
    x = spot * length
    xs = np.array([x - h, x]) if spot == 1.0 else np.array([x - h, x + h])
    phi = lever.mode_shape(xs, mode)   # normalised to 1 at the free end
    derivative = (phi[1] - phi[0]) / (xs[1] - xs[0])
    if spot == 1.0:   # one-sided: add the second-order correction from a third point
        phi2 = lever.mode_shape(np.array([x - 2 * h]), mode)[0]
        derivative = (3 * phi[1] - 4 * phi[0] + phi2) / (2 * h)
    return 1.5 * (2 * spot - spot ** 2) / (length * derivative)


@pytest.mark.parametrize("mode, spot", [(1, 1.0), (1, 0.8), (1, 0.5), (2, 1.0), (2, 0.7),
                                        (3, 0.9)])
def test_optical_lever_correction_from_the_mode_shape(mode, spot):
    assert optical_lever_correction(mode, spot) == pytest.approx(
        _chi_by_finite_differences(mode, spot), rel=1e-5)


def test_optical_lever_published_numbers():
    chi = optical_lever_correction(1, 1.0)
    assert round(chi, 2) == 1.09   # Proksch et al., Nanotechnology 15, 1344 (2004)
    assert round(SHARE1 / chi ** 2, 3) == 0.817   # Butt and Jaschke (1995): k = 0.817 k_B T / <z*^2>
    # Butt and Jaschke's sum over all modes for an optical lever: <z*^2> = 4 k_B T / (3 k); the
    # tail beyond mode 50 from the high-mode limits share_n = 12 / (b_n L)^4, chi_n = 1.5 / (b_n L)
    total = sum(mode_share(n) / optical_lever_correction(n, 1.0) ** 2 for n in range(1, 51))
    tail = sum(12 / ((n - 0.5) * math.pi) ** 2 / 2.25 for n in range(51, 200_000))
    assert total + tail == pytest.approx(4 / 3, rel=1e-5)
    with pytest.raises(ValueError, match="spot"):
        optical_lever_correction(1, 0.0)
    # a spot near the clamp: chi stays finite and continuous across the switch to the Taylor
    # series of the mode's slope at b_1 u = 1e-3
    near = [optical_lever_correction(1, u / B1) for u in (0.99e-3, 1.01e-3, 1e-30)]
    assert near[0] == pytest.approx(near[1], rel=1e-5) and math.isfinite(near[2])


# -- the simulated spectrum ------------------------------------------------------------------
@pytest.mark.parametrize("fluid", ["air", "water"])
def test_each_mode_carries_its_share_of_kT_in_any_fluid(fluid):
    # equipartition (fluctuation-dissipation + Kramers-Kronig): mode 1 alone, seen at the end
    # through the optical lever, integrates to share_1 k_B T / (chi^2 k), water or air
    lever = _contact()
    spectrum = thermal_spectrum(lever, fluid, sample_rate=100 * lever.resonance_frequency(1),
                                points=2 ** 19, averages=1, detector_noise=0.0, modes=1, seed=1)
    area = spectrum.expected.sum() * spectrum.resolution
    expected = SHARE1 * KB * spectrum.temperature / (1.0897 ** 2 * lever.spring_constant)
    assert area == pytest.approx(expected, rel=2e-3)


def test_the_bins_have_chi_squared_statistics():
    lever = _tapping()
    for m in (1, 4, 32):
        s = thermal_spectrum(lever, "air", points=2 ** 16, averages=m, seed=m)
        ratio = s.psd / s.expected
        # mean 1 and variance 1/M of Gamma(M, 1/M), to 5 standard errors of 65536 bins
        assert ratio.mean() == pytest.approx(1.0, abs=5 * math.sqrt(1 / m / ratio.size))
        assert ratio.var() == pytest.approx(1 / m, rel=5 * math.sqrt(2 / ratio.size)
                                            * math.sqrt(1 + 3 / m))
        # why the fit is not least squares on log P: E[ln P] - ln S = psi(M) - ln M (-0.577 at
        # M = 1; the variance of ln P is the trigamma psi'(M))
        assert np.log(ratio).mean() == pytest.approx(
            scipy.special.digamma(m) - math.log(m),
            abs=5 * math.sqrt(scipy.special.polygamma(1, m) / ratio.size))
    a = thermal_spectrum(lever, "air", points=256, seed=7)
    b = thermal_spectrum(lever, "air", points=256, seed=7)
    assert np.array_equal(a.psd, b.psd)   # seeded: deterministic


def test_spectrum_axes_and_floor():
    lever = _contact()
    s = thermal_spectrum(lever, "air", sample_rate=1e6, points=2 ** 12, detector_noise=1e-12)
    assert s.resolution == pytest.approx(1e6 / 2 ** 13) and s.sample_rate == pytest.approx(1e6)
    assert s.frequency[0] == pytest.approx(s.resolution) and s.record_time == pytest.approx(
        2 ** 13 / 1e6)
    # far above every resonance included, only the detector's floor is left (m^2/Hz)
    assert s.expected[-1] == pytest.approx(1e-24, rel=0.05)
    for kwargs, name in ((dict(points=8), "points"), (dict(averages=0), "averages"),
                         (dict(spot=1.5), "spot"), (dict(detector_noise=-1.0), "detector_noise"),
                         (dict(sample_rate=0.0), "sample_rate"), (dict(modes=0), "modes"),
                         (dict(points=2 ** 30), "points")):
        with pytest.raises(ValueError, match=name):
            thermal_spectrum(lever, "air", **kwargs)


def _fresh_spectrum(*args, **kwargs):
    from afmsmiler import calibration
    calibration._mode_lines.cache_clear()
    calibration._gamma_draws.cache_clear()
    return thermal_spectrum(*args, **kwargs)


@pytest.mark.parametrize("kept", [True, False])
def test_a_spectrum_from_kept_line_shapes_and_draws_is_the_one_computed_afresh(
        kept, monkeypatch):
    from afmsmiler import calibration
    if not kept:  # too large to keep: computed each time
        monkeypatch.setattr(calibration, "_KEPT_VALUES", 15)
    lever, kw = _tapping(), dict(points=2 ** 12, averages=8, seed=11)
    fresh = _fresh_spectrum(lever, "water", spot=0.6, **kw)
    # a panel's moves: the spot, the temperature, the detector, the same lever and bins
    thermal_spectrum(lever, "water", spot=0.9, **kw)
    thermal_spectrum(lever, "water", spot=0.6, temperature=310.0, detector_noise=1e-13, **kw)
    again = thermal_spectrum(lever, "water", spot=0.6, **kw)
    for name in ("frequency", "expected", "psd"):
        np.testing.assert_array_equal(getattr(again, name), getattr(fresh, name))
        assert not getattr(again, name).flags.writeable
    assert (calibration._mode_lines.cache_info().hits > 0) is kept
    # the noise is numpy's own draw for the seed, whether kept or not
    draws = np.random.default_rng(11).standard_gamma(8, 2 ** 12)
    np.testing.assert_array_equal(again.psd, again.expected * draws / 8)
    # another lever, fluid or seed is not served from the kept ones
    other = thermal_spectrum(_contact(), "water", spot=0.6, **kw)
    assert other.frequency[0] != again.frequency[0]
    air = thermal_spectrum(lever, "air", spot=0.6, **kw)
    np.testing.assert_array_equal(air.expected,
                                  _fresh_spectrum(lever, "air", spot=0.6, **kw).expected)
    # water's added mass lowers mode 1 (Sader 1998): its peak is not air's kept line
    peak = (fluid_mode(lever, "air").resonance_frequency,
            fluid_mode(lever, "water").resonance_frequency)
    for s, f in zip((air, again), peak):
        assert s.frequency[np.argmax(s.expected)] == pytest.approx(f, rel=0.05)
    reseeded = thermal_spectrum(lever, "water", spot=0.6, **dict(kw, seed=12))
    np.testing.assert_array_equal(
        reseeded.psd, reseeded.expected * np.random.default_rng(12).standard_gamma(8, 2 ** 12)
        / 8)


def test_kept_line_shapes_cannot_be_changed_through_a_spectrum():
    s = thermal_spectrum(_tapping(), "air", points=2 ** 10, seed=3)
    for a in (s.frequency, s.expected, s.psd):
        with pytest.raises(ValueError, match="read-only"):
            a[0] = 0.0
    from afmsmiler.calibration import _gamma_draws, _mode_lines
    f, shapes = _mode_lines(_tapping(), s.fluid, s.sample_rate, 2 ** 10, s.modes)
    assert not f.flags.writeable and not shapes.flags.writeable
    assert not _gamma_draws(3, s.averages, 2 ** 10).flags.writeable


# -- the fit ---------------------------------------------------------------------------------
def test_the_fit_recovers_an_exact_sho_line():
    # a noise-free SHO line on a floor, written out here: the fit must return its parameters
    base = thermal_spectrum(_contact(), "air", sample_rate=1e5, points=2 ** 14, seed=0)
    f = base.frequency
    f0, q, area, white = 12_345.0, 80.0, 2e-20, 3e-27
    line = area * 2 / (math.pi * q * f0) / ((1 - (f / f0) ** 2) ** 2 + (f / (q * f0)) ** 2)
    exact = dataclasses.replace(base, psd=line + white)
    fit = fit_thermal_spectrum(exact)
    assert fit.resonance_frequency == pytest.approx(f0, rel=1e-8)
    assert fit.quality_factor == pytest.approx(q, rel=1e-7)
    assert fit.area == pytest.approx(area, rel=1e-7)
    assert fit.background == pytest.approx(white, rel=1e-5)
    assert fit.bins_per_linewidth == pytest.approx(f0 / q / (1e5 / 2 ** 15), rel=1e-6)
    assert fit.model(np.array([f0])) == pytest.approx(area * 2 * q / (math.pi * f0) + white,
                                                      rel=1e-6)
    with pytest.raises(ValueError, match="band"):
        fit_thermal_spectrum(exact, band=(12_000.0, 12_001.0))
    with pytest.raises(ValueError, match="band"):
        fit_thermal_spectrum(exact, band=(1.0,))
    with pytest.raises(TypeError, match="spectrum"):
        fit_thermal_spectrum(line)


def _spread(lever, fluid, points, runs, seed0):
    ks, sigmas = [], []
    for i in range(runs):
        c = thermal_calibration(thermal_spectrum(lever, fluid, points=points, averages=4,
                                                 seed=seed0 + i))
        ks.append(c.spring_constant / c.true_spring_constant)
        sigmas.append(c.uncertainty / c.true_spring_constant)
    return np.array(ks), float(np.mean(sigmas))


@pytest.mark.slow   # 140 simulated and fitted spectra: a second or two
def test_thermal_calibration_recovers_k_within_bias_and_statistics():
    # a contact lever in air (Q ~ 56): over 100 spectra of 2^12 bins and 4 averages, the mean k
    # lies within the method's bias (the SHO line is not exactly the hydrodynamic line: 0.5 %)
    # plus 4 standard errors of the mean, and the spread equals the Fisher error the fit reports
    lever = _contact()
    ks, sigma = _spread(lever, "air", 2 ** 12, 100, 1000)
    spread = ks.std(ddof=1)
    assert abs(ks.mean() - 1) < 0.005 + 4 * spread / math.sqrt(ks.size)
    assert spread == pytest.approx(sigma, rel=0.25)   # 100 samples: the spread's own error ~ 7 %
    # the spread shrinks as the record grows: 16 times the record (df / 16), a quarter the spread
    long_ks, long_sigma = _spread(lever, "air", 2 ** 16, 40, 5000)
    assert long_ks.std(ddof=1) == pytest.approx(spread / 4, rel=0.35)
    assert long_sigma == pytest.approx(sigma / 4, rel=0.1)
    assert abs(long_ks.mean() - 1) < 0.005 + 4 * long_ks.std(ddof=1) / math.sqrt(long_ks.size)


def test_thermal_calibration_one_spectrum_and_its_biases():
    lever = _tapping()
    spectrum = thermal_spectrum(lever, "air", points=2 ** 17, averages=16, seed=11)
    c = thermal_calibration(spectrum)
    assert abs(c.relative_error) < 0.005 + 4 * c.uncertainty / c.spring_constant
    assert c.mode_share == pytest.approx(SHARE1, rel=1e-8)
    assert c.fit.resonance_frequency == pytest.approx(
        fluid_mode(lever, "air").resonance_frequency, rel=1e-3)
    # the spot was really at 0.8 L but assumed at the end: k is off by (chi(0.8) / chi(1))^2
    # (finite differences of module (a)'s mode shape), and right when the spot is known
    off = thermal_spectrum(lever, "air", points=2 ** 17, averages=16, seed=11, spot=0.8)
    wrong, right = thermal_calibration(off), thermal_calibration(off, spot=0.8)
    factor = (_chi_by_finite_differences(1, 0.8) / _chi_by_finite_differences(1, 1.0)) ** 2
    assert wrong.spring_constant / right.spring_constant == pytest.approx(factor, rel=1e-4)
    assert abs(right.relative_error) < 0.005 + 4 * right.uncertainty / right.spring_constant


def test_thermal_calibration_in_water_is_biased_by_the_sho_line():
    # at Q ~ 2 the thermal peak is not an SHO line (Gamma changes across it): the fitted area,
    # hence k, is off by several per cent; at Q ~ 8 (a stiff lever) by about 2 %
    soft = thermal_calibration(thermal_spectrum(_contact(), "water", points=2 ** 17,
                                                averages=16, seed=3))
    stiff = thermal_calibration(thermal_spectrum(_tapping(), "water", points=2 ** 17,
                                                 averages=16, seed=3))
    assert 0.03 < soft.relative_error < 0.2
    assert abs(stiff.relative_error) < 0.04
    assert fluid_mode(_contact(), "water").quality_factor < 3 < 6 < fluid_mode(
        _tapping(), "water").quality_factor


def test_bad_fluid_reaches_the_spectrum_as_a_named_error():
    with pytest.raises(ValueError, match="fluid"):
        thermal_spectrum(_contact(), "vacuum")
    with pytest.raises(TypeError, match="lever"):
        thermal_spectrum("lever")
    assert isinstance(thermal_spectrum(_contact(), FLUIDS["water"], points=64), ThermalSpectrum)


def test_the_spectrums_interpolated_gamma_is_the_direct_one():
    from afmsmiler.calibration import _gamma_interpolated
    from afmsmiler.hydrodynamics import hydrodynamic_function
    re = np.linspace(3e-5, 2e4, 200_000)   # 9 decades, more values than grid points
    direct = hydrodynamic_function(re, extrapolate=True)
    fast = _gamma_interpolated(re)
    assert np.max(np.abs(fast.real / direct.real - 1)) < 1e-6
    assert np.max(np.abs(fast.imag / direct.imag - 1)) < 1e-6


def test_calibrate_runs_every_method_on_one_lever():
    from afmsmiler.calibration import calibrate
    lever = _contact()
    lab = calibrate(lever, "air", points=2 ** 14, averages=16, seed=4)
    rows = lab.rows()
    assert [r[0] for r in rows][0].startswith("model") and rows[0][1] == lever.spring_constant
    # E w h^3 / (4 L^3) with E = 169 GPa (Hopcroft et al.)
    assert lab.true_spring_constant == pytest.approx(169e9 * 50e-6 * 2e-6 ** 3 / (4 * 450e-6 ** 3),
                                                     rel=1e-12)
    for _, k, error in rows[1:]:
        assert abs(error) < 0.05 and k == pytest.approx(lever.spring_constant * (1 + error))
    # the spot at 0.8 L but assumed at the end: only the thermal method notices
    moved = calibrate(lever, "air", spot=0.8, points=2 ** 14, averages=16, seed=4)
    factor = (_chi_by_finite_differences(1, 0.8) / _chi_by_finite_differences(1, 1.0)) ** 2
    assert moved.thermal.spring_constant / calibrate(
        lever, "air", spot=0.8, assumed_spot=0.8, points=2 ** 14, averages=16,
        seed=4).thermal.spring_constant == pytest.approx(factor, rel=1e-4)
    assert moved.sader == pytest.approx(lab.sader, rel=0.05)
