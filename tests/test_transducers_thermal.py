"""Module (b)'s photothermal and electrothermal bimorphs against sympy (Timoshenko's bilayer,
the fin equation, Fourier coefficients), numerical heat-equation solutions and an FFT."""
import math

import control
import mpmath
import numpy as np
import pytest
import sympy as sp
from scipy import integrate

from afmsmiler.materials import get_material
from afmsmiler.transducers import Electrothermal, Photothermal
from afmsmiler.transducers.thermal import THERMAL, bimorph_curvature

from tests.sympy_reference import fourier_coefficients


# --- photothermal and electrothermal bimorphs ----------------------------------------------------
def test_timoshenko_curvature_against_sympy_bilayer():
    """Derive the bilayer from force and moment balance plus strain compatibility."""
    a1, a2, t1, t2, e1, e2, dT, P, kap, w = sp.symbols(
        "alpha1 alpha2 t1 t2 E1 E2 DeltaT P kappa w", positive=True)
    # layer 1 (bottom) in tension P, layer 2 (top) in compression P (no net force); curvature
    # kappa concave towards layer 1 (down), which stretches the upper fibres of each layer;
    # moment balance P (t1 + t2)/2 = (E1 I1 + E2 I2) kappa; compatibility at the interface: the
    # top fibre of layer 1 and the bottom fibre of layer 2 strain alike
    i1, i2 = w * t1 ** 3 / 12, w * t2 ** 3 / 12
    eqs = [sp.Eq(P * (t1 + t2) / 2, (e1 * i1 + e2 * i2) * kap),
           sp.Eq(a1 * dT + P / (e1 * t1 * w) + t1 * kap / 2,
                 a2 * dT - P / (e2 * t2 * w) - t2 * kap / 2)]
    sol = sp.solve(eqs, [P, kap], dict=True)[0]
    values = {a1: 2.6e-6, a2: 14.2e-6, t1: 3e-6, t2: 50e-9, e1: 169e9, e2: 79e9, dT: 1.0, w: 1.0}
    expected = float(sol[kap].subs(values))
    got = bimorph_curvature(2.6e-6, 3e-6, 169e9, 14.2e-6, 50e-9, 79e9)
    assert got == pytest.approx(expected, rel=1e-12)
    # and a thick, equal-modulus bilayer (m = n = 1): 3 (alpha2 - alpha1) / (2 h)
    assert bimorph_curvature(1e-6, 1e-6, 1e11, 3e-6, 1e-6, 1e11) == pytest.approx(
        3 * 2e-6 / (2 * 2e-6), rel=1e-12)


def _heat_solution(kind):
    """Steady 1-D conduction G T'' = -q(x), T(0) = 0, flux P out of the free end or spread."""
    x, L, G, P = sp.symbols("x L G P", positive=True)
    T = sp.Function("T")
    if kind == "tip":
        sol = sp.dsolve(sp.Eq(G * T(x).diff(x, 2), 0), T(x),
                        ics={T(0): 0, T(x).diff(x).subs(x, L): P / G}).rhs
    else:
        sol = sp.dsolve(sp.Eq(G * T(x).diff(x, 2), -P / L), T(x),
                        ics={T(0): 0, T(x).diff(x).subs(x, L): 0}).rhs
    return (x, L, G, P), sol


@pytest.mark.parametrize("cls", [Photothermal, Electrothermal])
def test_bimorph_deflection_from_conduction_and_curvature(cls):
    model = cls()
    kind = model.HEATING
    (x, L, G, P), temp = _heat_solution(kind)
    subs = {L: model.length, G: model.thermal_conductance, P: 1e-3}
    tfun = sp.lambdify(x, temp.subs(subs))
    xs = np.linspace(0, model.length, 7)
    np.testing.assert_allclose(model.temperature_profile(xs, 1e-3), tfun(xs), rtol=1e-12,
                               atol=1e-15)
    # z(L) = int (L - x) z''(x) dx with z'' = -C Delta T(x), by quadrature
    c = model.curvature_per_kelvin
    z_tip, _ = integrate.quad(lambda s: (model.length - s) * -c * float(tfun(s)), 0, model.length)
    slope, _ = integrate.quad(lambda s: -c * float(tfun(s)), 0, model.length)
    if cls is Photothermal:
        chain = model.chain([1e-3 / model.absorptance])
    else:
        v = math.sqrt(1e-3 * model.resistance - model.ac_voltage ** 2 / 2)
        chain = model.chain([v])
    assert chain.stage("deflection").values[0] == pytest.approx(z_tip, rel=1e-9)
    assert chain.stage("slope").values[0] == pytest.approx(slope, rel=1e-9)
    assert z_tip < 0  # a top film that expands more bends the lever towards the sample
    # the small-signal sensitivity: z per incident watt (A z_tip / 1 mW) for the laser; for the
    # heater, d/dV of (V^2 + V_ac^2 / 2) / R times z per watt, 2 V / R (z_tip / 1 mW)
    if cls is Photothermal:
        assert model.sensitivity() == pytest.approx(model.absorptance * z_tip / 1e-3, rel=1e-9)
    else:
        assert model.sensitivity(at=v) == pytest.approx(2 * v / model.resistance * z_tip / 1e-3,
                                                        rel=1e-9)


def _fin_tip_deflection_by_sympy(kind):
    """The tip deflection per its DC value of the heated fin at complex wavenumber k (sympy).

    Periodic heat P e^{j w t}: G T'' - j w c' T = -q(x), T(0) = 0 (clamp at ambient), and at the
    free end G T'(L) = P (a laser spot) or 0 with q = P / L along the lever (a heater); with
    k^2 = j w c' / G = j w / D. The bimorph's curvature is -C T(x), so the tip deflection goes as
    int_0^L (L - x) T(x) dx (Timoshenko; module (a)'s clamped-free lever).
    """
    x, L, G, P = sp.symbols("x L G P", positive=True)
    k = sp.symbols("k")
    T = sp.Function("T")
    if kind == "tip":
        sol = sp.dsolve(sp.Eq(T(x).diff(x, 2) - k ** 2 * T(x), 0), T(x),
                        ics={T(0): 0, T(x).diff(x).subs(x, L): P / G}).rhs
        dc = P * L ** 3 / (6 * G)
    else:
        sol = sp.dsolve(sp.Eq(T(x).diff(x, 2) - k ** 2 * T(x), -P / (L * G)), T(x),
                        ics={T(0): 0, T(x).diff(x).subs(x, L): 0}).rhs
        dc = P * L ** 3 / (8 * G)
    ratio = sp.integrate(sp.expand((L - x) * sol), (x, 0, L)) / dc
    return sp.lambdify((k, L), ratio.subs({P: 1, G: 1}), "mpmath")


@pytest.mark.slow  # a sympy derivation or a heat-equation reference, ~1-4 s
@pytest.mark.parametrize("cls", [Photothermal, Electrothermal])
def test_thermal_lag_solves_the_heat_equation(cls):
    model = cls()
    tau = model.thermal_time_constant
    # the slowest mode of the heat equation with T(0) = 0, T'(L) = 0 has k L = pi / 2
    si, film = THERMAL["silicon"], THERMAL[model.FILM]
    t1, t2 = model.thickness, getattr(model, model.FILM_THICKNESS)
    diffusivity = ((si.conductivity * t1 + film.conductivity * t2)
                   / (get_material("silicon").density * si.specific_heat * t1
                      + get_material(model.FILM).density * film.specific_heat * t2))
    assert tau == pytest.approx(1 / (diffusivity * (math.pi / (2 * model.length)) ** 2), rel=1e-12)
    fc = 1 / (2 * math.pi * tau)
    # the exact fin response, from sympy's solution evaluated in 30-digit arithmetic
    exact = _fin_tip_deflection_by_sympy(model.HEATING)
    # (|s| = (f / fc) pi^2 / 4: the series below 0.02, i.e. f < 0.0081 fc, the closed form above)
    f = np.array([1e-6, 1e-3, 0.0081, 0.0082, 0.3, 1.0, 3.0, 30.0, 100.0, 1e4]) * fc
    with mpmath.workdps(30):
        # every float enters as an mpf first: double-precision products inside the expression
        # (7 L k, ...) would spoil its cancellations at low frequency
        length = mpmath.mpf(model.length)
        ref = [complex(exact(mpmath.sqrt(2j * mpmath.pi * mpmath.mpf(fi) / diffusivity), length))
               for fi in f]
    np.testing.assert_allclose(model.thermal_lag(f), ref, rtol=1e-12)
    assert model.thermal_lag(0.0) == 1.0
    # below fc it is the slowest mode's first-order low-pass (python-control's 1 / (tau s + 1));
    # far above, steeper: the heat stays near where it is deposited
    first_order = control.tf([1], [tau, 1])
    low = np.array([0.01, 0.1, 1.0]) * fc
    np.testing.assert_allclose(np.abs(model.thermal_lag(low)),
                               np.abs(first_order(2j * math.pi * low)), rtol=0.01)
    assert abs(np.angle(model.thermal_lag(fc)) + math.pi / 4) < math.radians(7)
    # asymptotes (u = L sqrt(j w / D) large): tanh -> 1, sech -> 0 in the fin's solution, so
    # 6 / u^3 for heat at the free end, 4 / u^2 for heat spread along the lever
    u = model.length * np.sqrt(2j * math.pi * 1e5 * fc / diffusivity)
    far = 6 / u ** 3 if cls is Photothermal else 4 / u ** 2
    assert model.thermal_lag(1e5 * fc) == pytest.approx(far, rel=1e-2)
    # the full response: the static sensitivity times the fin and the lever's first mode
    # (python-control's w1^2 / (s^2 + w1/Q s + w1^2))
    assert fc < model.resonance_frequency / 50
    w1 = 2 * math.pi * model.resonance_frequency
    lever = control.tf([w1 ** 2], [1, w1 / model.quality_factor, w1 ** 2])
    f = np.array([0.0, fc, 0.5 * model.resonance_frequency, model.resonance_frequency])
    with mpmath.workdps(30):
        fin = [1.0] + [complex(exact(mpmath.sqrt(2j * mpmath.pi * mpmath.mpf(fi) / diffusivity),
                                     mpmath.mpf(model.length))) for fi in f[1:]]
    fr = model.frequency_response(f)
    np.testing.assert_allclose(fr.response, model.sensitivity() * np.array(fin)
                               * lever(2j * math.pi * f), rtol=1e-12)


@pytest.mark.slow  # a sympy derivation or a heat-equation reference, ~1-4 s
def test_electrothermal_power_harmonics_against_sympy_and_fft():
    th, vdc, vac, r = sp.symbols("theta V_dc V_ac R", positive=True)
    dc, first, second = fourier_coefficients((vdc + vac * sp.cos(th)) ** 2 / r, th)
    assert sp.simplify(first - 2 * vdc * vac / r) == 0
    assert sp.simplify(second - vac ** 2 / (2 * r)) == 0      # the 2-omega term of P = V^2 / R
    assert sp.simplify(dc - (vdc ** 2 + vac ** 2 / 2) / r) == 0
    model = Electrothermal(resistance=2e3, ac_voltage=1.5)
    comp = model.power_components(0.8)
    values = {vdc: 0.8, vac: 1.5, r: 2e3}
    assert comp.dc == pytest.approx(float(dc.subs(values)), rel=1e-12)
    assert comp.first == pytest.approx(float(first.subs(values)), rel=1e-12)
    assert comp.second == pytest.approx(float(second.subs(values)), rel=1e-12)
    # numerical FFT of the time signal
    n = 64
    tt = np.arange(n) / n
    power = (0.8 + 1.5 * np.cos(2 * np.pi * tt)) ** 2 / 2e3
    spec = np.fft.rfft(power) / n
    assert comp.dc == pytest.approx(spec[0].real, rel=1e-12)
    assert comp.first == pytest.approx(2 * spec[1].real, rel=1e-12)
    assert comp.second == pytest.approx(2 * spec[2].real, rel=1e-12)
    # unbiased: the lever moves at 2 omega only
    motion = model.deflection_components(0.0, 1e3)
    assert motion.first == 0 and abs(motion.second) > 0
    # the 1-omega gain equals the small-signal sensitivity at the bias (slow drive)
    slow = model.deflection_components(0.8, 1e-3)
    assert abs(slow.first) / 1.5 == pytest.approx(abs(model.sensitivity(at=0.8)), rel=1e-6)


@pytest.mark.parametrize("cls", [Photothermal, Electrothermal])
def test_fin_response_stays_finite_up_to_the_largest_frequency(cls):
    # before: NaN at f = 1e300 (u^3 of a huge complex u overflowed into inf - inf)
    model = cls()
    diffusivity = model.thermal_diffusivity
    f = np.array([1e12, 1e60, 1e300, 1.7e308])
    lag = model.thermal_lag(f)
    assert np.isfinite(lag).all()
    # the fin's closed forms with tanh u = 1 and sech u = 0, exact to double precision for large u:
    # 6 / u^3 (heat at the tip), 4 / u^2 - 8 / u^3 + 8 / u^4 (uniform); beyond, their limit 0
    u = model.length * np.sqrt(2j * math.pi * f[:2] / diffusivity)
    far = 6 / u ** 3 if cls is Photothermal else 4 / u ** 2 - 8 / u ** 3 + 8 / u ** 4
    np.testing.assert_allclose(lag[:2], far, rtol=1e-12)
    assert abs(lag[3]) <= abs(lag[2]) < 1e-200
    assert np.isfinite(model.frequency_response(f).response).all()
