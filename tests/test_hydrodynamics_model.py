"""Sader's hydrodynamic function and the lever's modes in air and water, against independent sources.

Sources: mpmath's modified Bessel functions (an implementation independent of scipy's AMOS); the
small- and large-Reynolds-number limits of Stokes' oscillating cylinder; the inviscid added mass
of a flat plate (Lamb, *Hydrodynamics*, Sec. 71: pi rho_f b^2 / 4 per length, Gamma_rect -> 1);
the rational fit of Sader, J. Appl. Phys. 84, 64 (1998), Eqs. (21a,b), transcribed here a second
time from the authors' own calibration code (Mathematica, ampc.ms.unimelb.edu.au, with
-0.000044510 in Omega_i); CRC Handbook values of water and air; the clamped-free eigenvalue
b_1 L = 1.87510407 (Blevins, Table 8-1).
"""
import math

import mpmath
import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from afmsmiler.cantilever import Cantilever
from afmsmiler.hydrodynamics import (FLUIDS, REYNOLDS_RANGE, Fluid, circular_hydrodynamic_function,
                                     fluid_mode, fluid_modes, get_fluid, hydrodynamic_function,
                                     mass_loading, rectangular_correction, reynolds_number)

B1 = 1.87510407  # Blevins, Table 8-1


def _gamma_circ_mpmath(re):
    """1 + 4 i K1(-i sqrt(i Re)) / (sqrt(i Re) K0(-i sqrt(i Re))) with mpmath, 20 digits."""
    with mpmath.workdps(20):
        root = mpmath.sqrt(1j * mpmath.mpf(re))
        z = -1j * root
        return complex(1 + 4j * mpmath.besselk(1, z) / (root * mpmath.besselk(0, z)))


def _omega_authors(re):
    """Sader 1998 Eqs. (21a,b), as in the authors' code (omre, omimag), written out in Horner form."""
    x = math.log10(re)
    num_r = ((((((0.00069085 * x - 0.0035117) * x + 0.044055) * x - 0.12886) * x + 0.46842) * x
              - 0.48274) * x + 0.91324)
    den_r = ((((((0.00069085 * x - 0.0035862) * x + 0.045155) * x - 0.13444) * x + 0.48690) * x
              - 0.56964) * x + 1.0)
    num_i = (((((-0.000044510 * x + 0.000064577) * x - 0.00010961) * x + 0.016294) * x
              - 0.029256) * x - 0.024134)
    den_i = ((((((0.0028361 * x - 0.014369) * x + 0.079156) * x - 0.18357) * x + 0.55182) * x
              - 0.59702) * x + 1.0)
    return complex(num_r / den_r, num_i / den_i)


@pytest.mark.parametrize("re", [1e-6, 3e-4, 0.02, 1.0, 7.5, 300.0, 1e4, 1e7])
def test_circular_function_equals_mpmath(re):
    assert circular_hydrodynamic_function(re) == pytest.approx(_gamma_circ_mpmath(re), rel=1e-10)


def test_circular_function_has_stokes_limits():
    # low frequency: K1(z) ~ 1/z, K0(z) ~ -ln(z/2) - gamma, so Gamma ~ 1 + 4 i / (Re K0(z))
    # (Stokes' slowly oscillating cylinder); the neglected terms are O(|z|^2 ln|z|) = O(Re ln Re)
    for re in (1e-8, 1e-6):
        z = -1j * np.sqrt(1j * re)
        low = 1 + 4j / (re * (-np.log(z / 2) - np.euler_gamma))
        assert circular_hydrodynamic_function(re) == pytest.approx(low, rel=1e-5)
    # high frequency: a thin Stokes layer, K1/K0 -> 1 + 1/(2z): Gamma - 1 ~ 2 sqrt(2) (1 + i) / sqrt(Re)
    for re in (1e6, 1e8):
        g = circular_hydrodynamic_function(re) - 1
        assert g == pytest.approx(2 * math.sqrt(2) * (1 + 1j) / math.sqrt(re),
                                  rel=2 / math.sqrt(re))


@pytest.mark.parametrize("re", [1e-6, 1e-4, 0.01, 0.3, 1.0, 10.0, 1e3, 1e4])
def test_rectangular_correction_as_printed_by_the_authors(re):
    assert rectangular_correction(re) == pytest.approx(_omega_authors(re), rel=1e-12)
    assert hydrodynamic_function(re) == pytest.approx(_omega_authors(re)
                                                      * _gamma_circ_mpmath(re), rel=1e-10)


def test_rectangular_function_tends_to_the_inviscid_flat_plate():
    # Lamb, Hydrodynamics, Sec. 71: a plate of width b moving broadside carries pi rho_f b^2 / 4
    # per length, Gamma_r -> 1, and the viscous damping Gamma_i -> 0 as Re grows
    g = [hydrodynamic_function(re) for re in (1e2, 1e3, 1e4)]
    assert all(1.0 < x.real for x in g) and g[0].real > g[1].real > g[2].real
    assert abs(g[2] - 1) < 0.06 and g[2].imag < 0.04
    assert g[0].imag > g[1].imag > g[2].imag > 0
    # damping dominates at low Re, the added mass diverges more slowly (Gamma_i / Gamma_r grows)
    low = hydrodynamic_function(1e-5)
    assert low.imag > low.real > 0
    # beyond the fit, Omega is held at the range's end: Gamma stays finite and near the plate's 1
    far = hydrodynamic_function(1e10, extrapolate=True)
    assert far == pytest.approx(_omega_authors(1e4) * _gamma_circ_mpmath(1e10), rel=1e-9)


def test_reynolds_range_is_enforced_unless_extrapolating():
    for re in (0.5 * REYNOLDS_RANGE[0], 2 * REYNOLDS_RANGE[1]):
        with pytest.raises(ValueError, match="re must be in"):
            hydrodynamic_function(re)
        assert np.isfinite(hydrodynamic_function(re, extrapolate=True))
    with pytest.raises(ValueError, match="re must"):
        hydrodynamic_function(-1.0, extrapolate=True)
    arr = hydrodynamic_function(np.logspace(-6, 4, 5))
    assert arr.shape == (5,) and np.iscomplexobj(arr)


def test_reynolds_number_is_rho_omega_b2_over_4_eta():
    water = FLUIDS["water"]
    assert reynolds_number(2 * math.pi * 1e4, 30e-6, water) == pytest.approx(
        water.density * 2 * math.pi * 1e4 * (30e-6) ** 2 / (4 * water.viscosity), rel=1e-14)
    with pytest.raises(ValueError, match="angular_frequency"):
        reynolds_number(-1.0, 30e-6)


# CRC Handbook of Chemistry and Physics (97th ed.): water 998.21 kg/m^3 and 1.0016 mPa s at 20 C,
# 997.05 kg/m^3 and 0.8900 mPa s at 25 C; dry air at 1 atm: 1.2041 kg/m^3 and 18.2 uPa s at 20 C
@pytest.mark.parametrize("fluid, density, viscosity, rtol_eta", [
    (Fluid.water(293.15), 998.21, 1.0016e-3, 0.01), (Fluid.water(298.15), 997.05, 0.8900e-3, 0.01),
    (Fluid.air(293.15), 1.2041, 1.82e-5, 0.01)])
def test_fluid_presets_match_handbook_values(fluid, density, viscosity, rtol_eta):
    assert fluid.density == pytest.approx(density, rel=2e-4)
    assert fluid.viscosity == pytest.approx(viscosity, rel=rtol_eta)
    assert fluid.kinematic_viscosity == pytest.approx(fluid.viscosity / fluid.density)


def test_presets_and_lookup():
    assert get_fluid("water") is FLUIDS["water"] and get_fluid(FLUIDS["air"]) is FLUIDS["air"]
    assert FLUIDS["air_sader1999"].density == 1.18 and FLUIDS["air_sader1999"].viscosity == 1.86e-5
    # a gas's viscosity does not depend on its pressure, its density does (ideal gas)
    assert Fluid.air(pressure=2 * 101325.0).viscosity == Fluid.air().viscosity
    assert Fluid.air(pressure=2 * 101325.0).density == pytest.approx(2 * Fluid.air().density)
    with pytest.raises(ValueError, match="fluid must be one of"):
        get_fluid("honey")
    with pytest.raises(TypeError, match="fluid"):
        get_fluid(3.0)
    with pytest.raises(ValueError, match="temperature"):
        Fluid.water(400.0)


@pytest.mark.parametrize("kwargs, name", [
    (dict(density=1000.0, viscosity=-1e-3), "viscosity"), (dict(density=-1.0, viscosity=1e-3),
                                                            "density"),
    (dict(density=1000.0, viscosity=0.0), "viscosity"), (dict(density=math.nan, viscosity=1e-3),
                                                         "density"),
    (dict(density=1000.0, viscosity="thick"), "viscosity")])
def test_a_bad_fluid_is_refused_naming_the_parameter(kwargs, name):
    with pytest.raises(ValueError, match=rf"^{name} must"):
        Fluid("bad", **kwargs)


def _levers():
    return [Cantilever.from_material("silicon", 450e-6, 50e-6, 2e-6),   # contact
            Cantilever.from_material("silicon", 125e-6, 30e-6, 4e-6),   # tapping
            Cantilever.from_material("silicon_nitride", 200e-6, 20e-6, 0.6e-6)]


@pytest.mark.parametrize("fluid", ["air", "water"])
def test_modes_in_a_fluid_satisfy_sader(fluid):
    for lever in _levers():
        for m in fluid_modes(lever, fluid, 3):
            t = math.pi * m.fluid.density * lever.width / (4 * lever.density * lever.thickness)
            assert mass_loading(lever, fluid) == pytest.approx(t, rel=1e-14)
            g = hydrodynamic_function(m.reynolds_number, extrapolate=True)
            # omega_R = omega_vac (1 + T Gamma_r(omega_R))^(-1/2), Q = (1/T + Gamma_r) / Gamma_i
            assert m.resonance_frequency == pytest.approx(
                m.vacuum_frequency / math.sqrt(1 + t * g.real), rel=1e-10)
            assert m.quality_factor == pytest.approx((1 / t + g.real) / g.imag, rel=1e-10)
            assert m.reynolds_number == pytest.approx(reynolds_number(
                m.angular_frequency, lever.width, fluid), rel=1e-12)
            assert m.vacuum_frequency == lever.resonance_frequency(m.mode)
            assert 0 < m.frequency_ratio < 1


def test_air_and_water_as_the_lab_sees_them():
    contact, tapping, _ = _levers()
    air, water = fluid_mode(contact, "air"), fluid_mode(contact, "water")
    # a soft contact lever keeps ~99 % of its frequency in air and rings a few times in water,
    # at a quarter to a third of it (Sader 1998, Fig. 7 and the typical Q of 1-5 in water)
    assert 0.97 < air.frequency_ratio < 1.0 and 20 < air.quality_factor < 200
    assert 0.15 < water.frequency_ratio < 0.5 and 1 < water.quality_factor < 5
    # a stiff tapping lever: Q of several hundred in air
    assert 300 < fluid_mode(tapping, "air").quality_factor < 2000
    # higher modes ring with higher Q (Q grows with the mode's frequency in air)
    qs = [m.quality_factor for m in fluid_modes(contact, "air", 3)]
    assert qs[0] < qs[1] < qs[2]


def test_the_fluid_response_peaks_at_the_fluid_resonance():
    # the tip's response to a force, 1 / (1 - (w/w_vac)^2 (1 + T Gamma(w))), evaluated with
    # mpmath's Gamma: its peak sits at omega_R to O(1/Q^2) plus Gamma's drift over the line
    lever = _levers()[0]
    m = fluid_mode(lever, "air")
    t = mass_loading(lever, "air")
    scale = m.fluid.density * lever.width ** 2 / (4 * m.fluid.viscosity)

    def response(w):
        re = scale * w
        g = _omega_authors(re) * _gamma_circ_mpmath(re)
        return abs(1 / (1 - (w / (2 * math.pi * m.vacuum_frequency)) ** 2 * (1 + t * g)))
    w0 = m.angular_frequency
    best = minimize_scalar(lambda x: -response(x * w0), bounds=(0.97, 1.03), method="bounded",
                           options={"xatol": 1e-6, "maxiter": 60})
    assert best.x == pytest.approx(1.0, abs=2 / m.quality_factor ** 2 + 1e-5)
    # the peak height is ~ Q (the weak-damping reading of the same response)
    assert -best.fun == pytest.approx(m.quality_factor, rel=0.05)


def test_the_mode_stiffness_and_oscillator_kwargs():
    lever = _levers()[1]
    m = fluid_mode(lever, "water", 2)
    # k_n = k (b_n L)^4 / 12: 1.0302 k for mode 1 (Butt and Jaschke's share 12 / (b_1 L)^4)
    assert fluid_mode(lever, "air").spring_constant == pytest.approx(
        lever.spring_constant * B1 ** 4 / 12, rel=1e-8)
    assert m.oscillator() == {"spring_constant": m.spring_constant,
                              "resonance_frequency": m.resonance_frequency,
                              "quality_factor": m.quality_factor}
    from afmsmiler.modes.oscillator import Oscillator
    from afmsmiler.modes.tapping import TappingLever
    tapping = TappingLever(**fluid_mode(lever, "air").oscillator())
    assert tapping.quality_factor == fluid_mode(lever, "air").quality_factor
    # the point mass of mode 2 in water: k_n / omega_R^2, the modal mass with the fluid's load
    assert Oscillator(**m.oscillator()).mass == pytest.approx(
        m.spring_constant / m.angular_frequency ** 2, rel=1e-12)
    assert m.in_fit_range


def test_fluid_mode_bad_input_is_named():
    lever = _levers()[0]
    with pytest.raises(ValueError, match="mode"):
        fluid_mode(lever, "air", 0)
    with pytest.raises(TypeError, match="lever"):
        fluid_mode("lever", "air")
    with pytest.raises(ValueError, match="fluid"):
        fluid_mode(lever, "glycerol")


def test_circular_function_far_beyond_the_bessel_routines():
    # above Re = 1e12 the large-argument expansion of K1/K0 takes over: continuous there, and
    # Stokes' thin layer 2 sqrt(2) (1 + i) / sqrt(Re) up to Re = 1e300
    a = circular_hydrodynamic_function(0.999e12) - 1
    b = circular_hydrodynamic_function(1.001e12) - 1
    assert b == pytest.approx(a * math.sqrt(0.999 / 1.001), rel=1e-9)
    for re in (1e20, 1e300):
        assert circular_hydrodynamic_function(re) - 1 == pytest.approx(
            2 * math.sqrt(2) * (1 + 1j) / math.sqrt(re), rel=1e-9)
    assert np.isfinite(circular_hydrodynamic_function(1e-200))
    with pytest.raises(TypeError, match="extrapolate"):
        hydrodynamic_function(1.0, extrapolate="yes")
