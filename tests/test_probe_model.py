"""afmsmiler.probe: a vendor's lever in air and water, and its calibration ("your probe").

References: a rectangular Lever's equivalent rectangle is the Cantilever of the same dimensions
(closed forms, Euler-Bernoulli); the plan view's area by the shoelace formula against the
planform's own area; the mass per area from the lever's layers; a misplaced spot scales the
thermal k by (chi(s) / chi(1))^2 (Butt and Jaschke 1995; Proksch et al. 2004, chi(1) = 1.09);
Sader's k is proportional to the length it is given (Sader, Chon and Mulvaney 1999), so from the
plan view of a non-rectangular lever it is off by L / L_e; a Monte Carlo mean of the thermal k.
"""
import math

import numpy as np
import pytest

from afmsmiler.calibration import optical_lever_correction, sader_spring_constant
from afmsmiler.cantilever import Cantilever
from afmsmiler.hydrodynamics import fluid_mode
from afmsmiler.planform import PRESETS, Lever, preset
from afmsmiler.probe import (SPOT, equivalent_cantilever, mean_width, planform_outline,
                             probe_report)


def _shoelace(x, y):
    return 0.5 * abs(float(np.dot(x[:-1], y[1:]) - np.dot(x[1:], y[:-1])))


def test_a_rectangle_is_its_own_equivalent():
    lever = Lever.rectangular("silicon", 450e-6, 50e-6, 2e-6)
    rect = equivalent_cantilever(lever)
    closed = Cantilever.from_material("silicon", 450e-6, 50e-6, 2e-6)
    # the frame model's f1 converges to the closed form to ~1e-6 (planform's notes), k to 1e-9
    for name in ("length", "width", "thickness", "youngs_modulus", "density"):
        assert getattr(rect, name) == pytest.approx(getattr(closed, name), rel=1e-5), name
    ours, sader = fluid_mode(rect, "water"), fluid_mode(closed, "water")
    assert ours.resonance_frequency == pytest.approx(sader.resonance_frequency, rel=1e-5)
    assert ours.quality_factor == pytest.approx(sader.quality_factor, rel=1e-5)


@pytest.mark.parametrize("name", ["AC240TS", "Arrow-NCR", "MLCT-E", "SNL-10-B", "Tap300Al-G"])
def test_equivalent_rectangle_has_the_levers_k_f1_width_and_mass_per_area(name):
    lever = preset(name)
    rect = equivalent_cantilever(lever)
    assert rect.spring_constant == pytest.approx(lever.spring_constant, rel=1e-9)
    assert rect.resonance_frequency(1) == pytest.approx(lever.resonance_frequency(1), rel=1e-9)
    x, y = planform_outline(lever)
    area = _shoelace(x, y)   # the outline's area, independent of Lever.area
    assert lever.area == pytest.approx(area, rel=1e-12)
    assert rect.width == pytest.approx(area / lever.length, rel=1e-12) == mean_width(lever)
    # the fluid's mass loading: the lever's mass per area (coating included) over rho h
    assert rect.density * rect.thickness == pytest.approx(lever.mass / lever.area, rel=1e-12)


def test_outlines_of_the_three_planforms():
    L, w = 240e-6, 40e-6
    x, y = planform_outline(Lever.rectangular("silicon", L, w, 2e-6))
    assert _shoelace(x, y) == pytest.approx(L * w, rel=1e-12)
    x, y = planform_outline(Lever.pointed("silicon", L, w, 2e-6, 20e-6))
    assert _shoelace(x, y) == pytest.approx(L * w - 20e-6 * w / 2, rel=1e-12)
    v = Lever.v_shaped("silicon", 140e-6, 18e-6, 140e-6, 0.55e-6)
    x, y = planform_outline(v)
    # the inner edges meet on the axis at x_j, where the arms' inner edges (parallel to the outer
    # ones, one arm width away) cross: x_j = L - b / sin(theta)
    theta = math.atan(70e-6 / 140e-6)
    assert x[4] == pytest.approx(140e-6 - 18e-6 / math.sin(theta), rel=1e-12)
    assert x[0] == x[-1] and y[0] == y[-1]


def test_report_in_water_follows_sader_for_a_rectangle():
    lever = preset("ContAl-G")
    r = probe_report(lever, "water", seed=3)
    rect = equivalent_cantilever(lever)
    assert r.modes["water"].quality_factor == pytest.approx(
        fluid_mode(rect, "water").quality_factor, rel=1e-12)
    assert 2.0 < r.modes["water"].quality_factor < 2.6 < 50 < r.modes["air"].quality_factor
    assert r.spring_constant == lever.spring_constant
    fit = r.thermal.fit
    assert r.sader == pytest.approx(sader_spring_constant(
        lever.length, lever.width, fit.resonance_frequency, fit.quality_factor, "water"))
    assert any("Q >> 1" in s for s in r.reasons())


@pytest.mark.parametrize("spot", [0.5, 0.7, 0.9])
def test_a_misplaced_spot_scales_the_thermal_k_by_chi_squared(spot):
    lever = preset("ContAl-G")
    at_end = probe_report(lever, "air", seed=5)
    moved = probe_report(lever, "air", spot=spot, seed=5)   # the same noise
    expected = (optical_lever_correction(1, spot) / optical_lever_correction(1, 1.0)) ** 2
    assert moved.spot_bias == pytest.approx(expected, rel=1e-12)
    assert optical_lever_correction(1, 1.0) == pytest.approx(1.09, abs=0.005)  # Proksch 2004
    # mode 1's area scales by exactly 1 / chi(spot)^2; the fit sees the other modes and the
    # floor unchanged, which moves it by far less than 0.1 %
    ratio = moved.thermal.spring_constant / at_end.thermal.spring_constant
    assert ratio == pytest.approx(expected, rel=1e-3)
    assert any("chi(spot)" in s for s in moved.reasons())


def test_sader_from_the_plan_view_of_a_v_is_off_by_the_length_ratio():
    r = probe_report(preset("MLCT-E"), "air", seed=2)
    # Sader's k is proportional to L: with the equivalent rectangle's L_e it is the rectangle's
    # own Sader k (a few per cent from the truth in air)
    own = sader_spring_constant(r.cantilever.length, r.cantilever.width,
                                r.thermal.fit.resonance_frequency,
                                r.thermal.fit.quality_factor, "air")
    assert own == pytest.approx(r.spring_constant, rel=0.06)
    assert r.sader / own == pytest.approx(r.plan_view_ratio, rel=1e-12)
    assert r.plan_view_ratio > 1.3
    assert any("not a rectangle" in s for s in r.reasons())
    assert abs(r.thermal_error) < 4 * r.thermal.uncertainty / r.thermal.spring_constant


def test_thermal_k_is_unbiased_over_many_spectra():
    lever = preset("AC240TS")
    errors, sigmas = [], []
    for seed in range(24):
        r = probe_report(lever, "air", seed=seed)
        errors.append(r.thermal_error)
        sigmas.append(r.thermal.uncertainty / r.thermal.spring_constant)
    # the spread matches the fit's Fisher error, and the mean lies within 3 standard errors
    assert np.std(errors) == pytest.approx(np.mean(sigmas), rel=0.4)
    assert abs(np.mean(errors)) < 3 * np.mean(sigmas) / math.sqrt(len(errors)) + 0.005


@pytest.mark.slow
def test_every_preset_gives_a_report():
    for name in PRESETS:
        r = probe_report(preset(name), "air", points=2 ** 12, averages=4, seed=1)
        assert math.isfinite(r.thermal.spring_constant) and r.spring_constant > 0


def test_bad_input_is_refused_by_name():
    lever = preset("AC240TS")
    with pytest.raises(TypeError, match="lever"):
        probe_report(Cantilever.from_material("silicon"))
    with pytest.raises(ValueError, match="fluid"):
        probe_report(lever, "oil")
    for bad in (0.0, 1.5, math.nan):
        with pytest.raises(ValueError, match="spot"):
            probe_report(lever, spot=bad)
    with pytest.raises(ValueError, match="assumed_spot"):
        probe_report(lever, assumed_spot=-0.1)
    with pytest.raises(ValueError, match="points"):
        probe_report(lever, points=2 ** 30)
    with pytest.raises(TypeError, match="lever"):
        equivalent_cantilever("AC240TS")
    assert SPOT.check(1.0) == 1.0


def test_the_books_plan_view_ratios():
    # book/01_cantilever_mechanics.md, "Your probe": L / L_e of 1.13 for the AC240TS and 1.4 to
    # 2.2 for the V-shaped presets
    def ratio(name):
        lever = preset(name)
        return lever.length / equivalent_cantilever(lever).length

    assert ratio("AC240TS") == pytest.approx(1.13, abs=0.005)
    vs = [ratio(n) for n, p in PRESETS.items() if p.planform == "v_shaped"]
    assert 1.4 <= min(vs) and max(vs) < 2.25
    assert ratio("ContAl-G") == pytest.approx(1.0, abs=1e-5)
