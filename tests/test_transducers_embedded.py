"""Module (b)'s embedded transducers (optomechanical cavity, piezoresistor, piezoelectric film)
against the resistor divider, the clamp stress, sympy and quadrature of the noise spectra."""
import math

import control
import numpy as np
import pytest
import sympy as sp
from scipy import integrate

from afmsmiler.transducers import Optomechanical, Piezoelectric, Piezoresistive
from afmsmiler.brownian import mechanical_response
from afmsmiler.transducers.base import BOLTZMANN
from afmsmiler.transducers.embedded import quarter_bridge_output


def test_piezoresistor_says_where_it_stops_being_linear():
    # the clamp's surface stress 6 F L / (w h^2) with F = k z = E w h^3 z / (4 L^3) is
    # 1.5 E h z / L^2 (Timoshenko and Gere, Mechanics of Materials): 30 MPa for the default at 2 um
    model = Piezoresistive()
    assert 1.5 * 169e9 * 3e-6 * 2e-6 / 225e-6 ** 2 < 0.1 * model.FRACTURE_STRESS
    assert model.validity(2e-6) == () and model.validity(-2e-6) == ()
    # a stubby lever bent by 2 um: 1.5 * 169 GPa * 10 um * 2 um / (20 um)^2 = 127 GPa
    stub = Piezoresistive(length=20e-6, thickness=10e-6, resistor_length=4e-6)
    notes = stub.validity(2e-6)
    assert any("GPa" in n and "breaks" in n for n in notes)
    assert any("clipped at -1" in n for n in notes)
    # dR/R of a resistance cannot pass -1: the active arm shorts and the bridge sits at -V_b / 2
    chain = stub.chain([2e-6, -2e-6])
    assert chain.stage("relative_change").values[0] == -1.0
    assert chain.output.values[0] == pytest.approx(-stub.bias_voltage / 2, rel=1e-15)
    assert 0 < chain.output.values[1] < stub.bias_voltage / 2
    assert stub.sensitivity(at=2e-6) == 0.0


# --- optomechanical ------------------------------------------------------------------------------
def test_cavity_slope_at_half_linewidth():
    model = Optomechanical(detuning=-0.5, power=50e-6, dip_depth=0.6, coupling=2e18)
    gamma = model.linewidth
    assert gamma == pytest.approx(299792458.0 / (model.wavelength * model.optical_q), rel=1e-12)
    # textbook: slope of a Lorentzian dip at its half-width point = D P G / gamma
    assert model.sensitivity() == pytest.approx(0.6 * 50e-6 * 2e18 / gamma, rel=1e-12)
    h = 1e-15
    numerical = (model.transmission(h) - model.transmission(-h)) / (2 * h)
    assert model.sensitivity() == pytest.approx(float(numerical), rel=1e-5)
    # the steepest point lies at |Delta| = gamma / (2 sqrt 3) (sympy), 3 sqrt(3)/4 steeper
    d, g = sp.symbols("Delta gamma", positive=True)
    lor = (g / 2) ** 2 / (d ** 2 + (g / 2) ** 2)
    best = [s for s in sp.solve(sp.diff(lor, d, 2), d) if s.is_positive]
    assert best == [g / (2 * sp.sqrt(3))]
    steep = model.replace(detuning=-1 / (2 * math.sqrt(3))).sensitivity()
    assert steep / model.sensitivity() == pytest.approx(3 * math.sqrt(3) / 4, rel=1e-12)


# --- piezoresistive ------------------------------------------------------------------------------
def test_quarter_bridge_against_the_resistor_divider():
    vb, r, delta = sp.symbols("V_b R delta", positive=True)
    rx = r * (1 + delta)
    # two dividers: the active arm over R against R over R
    vout = vb * (rx / (rx + r) - r / (r + r))
    exact = sp.simplify(vout)
    assert sp.simplify(exact - vb / 4 * delta / (1 + delta / 2)) == 0
    assert sp.series(exact, delta, 0, 2).removeO() == vb * delta / 4     # small signal V_b dR/(4R)
    f = sp.lambdify((vb, delta), exact)
    for d in (1e-5, 0.01, 0.3, -0.2):
        assert quarter_bridge_output(2.5, d) == pytest.approx(f(2.5, d), rel=1e-13)


def test_piezoresistive_sensitivity_from_the_clamp_stress():
    model = Piezoresistive(resistor_length=40e-6, junction_depth=0.4e-6)
    lever = model.lever
    z = 20e-9
    force = lever.spring_constant * z
    # textbook surface stress of an end-loaded lever, 6 F (L - x) / (w h^2), at the resistor's
    # centre x = l_r / 2, scaled linearly to the mid-depth of the junction (1 - d_j / h)
    sigma = -6 * force * (lever.length - 20e-6) / (lever.width * lever.thickness ** 2) * (
        1 - 0.4e-6 / lever.thickness)
    chain = model.chain([z])
    assert chain.stage("stress").values[0] == pytest.approx(sigma, rel=1e-12)
    delta = model.piezo_coefficient * sigma
    assert chain.output.values[0] == pytest.approx(2.0 / 4 * delta / (1 + delta / 2), rel=1e-12)
    # small signal: V_b / 4 * pi_l * d sigma / dz
    assert model.sensitivity() == pytest.approx(2.0 / 4 * model.piezo_coefficient * sigma / z,
                                                rel=1e-12)
    # gauge factor of p-Si <110>: pi_l E = 71.8e-11 * 169e9 = 121 (Smith 1954; Kanda 1982)
    assert model.gauge_factor == pytest.approx(121.3, abs=0.1)


def test_piezoresistive_noise():
    model = Piezoresistive(resistance=1e3, temperature=300.0)
    res = model.resolution(1.0, low_frequency=1e3)
    sens = abs(model.sensitivity())
    # Johnson noise of 1 kOhm at 300 K: 4.07 nV/sqrt(Hz) (Horowitz and Hill, 3rd ed., 8.1.1)
    assert res.contributions["johnson"] * sens == pytest.approx(4.07e-9, rel=2e-3)
    # the bridge of four arms R1..R4 (R1 active), derived with sympy: its output resistance is
    # R1 || R2 + R3 || R4 and each arm's fluctuation dR_i reaches the output as dV/dR_i dR_i
    vb, r1, r2, r3, r4 = sp.symbols("V_b R1 R2 R3 R4", positive=True)
    vout = vb * (r1 / (r1 + r2) - r4 / (r3 + r4))
    arms = (r1, r2, r3, r4)
    r = model.resistance
    at_balance = dict.fromkeys(arms, r)
    r_out = (r1 * r2 / (r1 + r2) + r3 * r4 / (r3 + r4)).subs(at_balance)
    johnson = math.sqrt(4 * BOLTZMANN * 300.0 * float(r_out) * 1.0)
    assert res.contributions["johnson"] * sens == pytest.approx(johnson, rel=1e-12)
    # Hooge (Hooge, Phys. Lett. A 29, 139 (1969)): each arm's resistance fluctuates with
    # S_R / R^2 = alpha_H / (N f), independently; N = p x (two legs l_r long, w/4 wide, d_j deep)
    gain2 = sum((sp.diff(vout, ri) * ri) ** 2 for ri in arms).subs(at_balance)
    n = model.carrier_density * 2 * model.resistor_length * (model.width / 4) * model.junction_depth
    s_times_f = float(gain2.subs(vb, model.bias_voltage)) * model.hooge / n
    band, _ = integrate.quad(lambda f: s_times_f / f, 1e3, 1e3 + 1.0)
    assert res.contributions["hooge"] * sens == pytest.approx(math.sqrt(band), rel=1e-10)


# --- piezoelectric -------------------------------------------------------------------------------
def test_piezoelectric_sensing_and_actuation_against_sympy():
    x, L, EJ, F, le, zp, d31, ep, w, V = sp.symbols("x L EJ F l_e z_p d31 E_p w V", real=True)
    curv = F * (L - x) / EJ                                   # end-loaded lever (module (a))
    charge = d31 * ep * w * sp.integrate(-zp * curv, (x, 0, le))
    moment = -d31 * ep * w * zp * V                           # film force d31 E_p w V, arm z_p
    z_tip = sp.integrate((L - x) * moment / EJ, (x, 0, le))   # curvature only under the film
    model = Piezoelectric(d31=-60e-12, film_modulus=70e9, electrode_length=80e-6)
    lever = model.lever
    subs = {L: lever.length, EJ: lever.flexural_rigidity, le: 80e-6, d31: -60e-12, ep: 70e9,
            w: lever.width, zp: (lever.thickness + model.film_thickness) / 2}
    zz = 10e-9
    q_ref = float(charge.subs(subs).subs(F, lever.spring_constant * zz))
    assert model.respond(zz, "sensing") == pytest.approx(q_ref, rel=1e-12)
    assert model.respond(3.0, "actuation") == pytest.approx(float(z_tip.subs(subs).subs(V, 3.0)),
                                                            rel=1e-12)
    # Maxwell reciprocity: charge per tip force (short circuit) = tip deflection per volt (free)
    assert model.sensitivity("sensing") / lever.spring_constant == pytest.approx(
        model.sensitivity("actuation"), rel=1e-12)


def test_piezoelectric_leakage_noise_against_quadrature():
    # Johnson current of the leak R = tau / C, 4 k_B T / R (A^2/Hz), integrated by the charge
    # amplifier: S_q(f) = S_i / (2 pi f)^2, summed over [f1, f1 + B] by quadrature
    model = Piezoelectric(leakage_time_constant=0.1, temperature=300.0)
    cap = 8.8541878188e-12 * model.permittivity * model.width * model.electrode_length / (
        model.film_thickness)
    r_leak = 0.1 / cap
    f1, bw = 10.0, 1e3
    q2, _ = integrate.quad(lambda f: 4 * BOLTZMANN * 300.0 / r_leak / (2 * math.pi * f) ** 2,
                           f1, f1 + bw)
    res = model.resolution(bw, low_frequency=f1, mode="sensing")
    assert res.contributions["leakage"] * abs(model.sensitivity("sensing")) == pytest.approx(
        math.sqrt(q2), rel=1e-10)
    assert set(model.resolution(bw, mode="actuation").contributions) == {"thermal"}


def test_piezoelectric_sensing_is_ac_mostly():
    model = Piezoelectric(leakage_time_constant=0.01)
    fc = 1 / (2 * math.pi * 0.01)
    f = np.array([0.0, fc, 1e3 * fc])
    fr = model.frequency_response(f, "sensing")
    # the charge high-pass on top of the lever's first mode (checked against python-control above)
    static = model.sensitivity("sensing") / model.spring_constant
    mech = np.abs(mechanical_response(f, resonance_frequency=model.resonance_frequency,
                                      quality_factor=model.quality_factor))
    assert fr.response[0] == 0
    assert abs(fr.response[1]) == pytest.approx(static * mech[1] / math.sqrt(2), rel=1e-12)
    assert abs(fr.response[2]) == pytest.approx(static * mech[2] / math.sqrt(1 + 1e-6), rel=1e-12)
    # python-control: the charge amplifier's high-pass tau s / (tau s + 1) on the first mode
    w1 = 2 * math.pi * model.resonance_frequency
    sys = (control.tf([0.01, 0], [0.01, 1])
           * control.tf([w1 ** 2], [1, w1 / model.quality_factor, w1 ** 2]))
    np.testing.assert_allclose(fr.response, static * sys(2j * math.pi * f), rtol=1e-12)
    act = model.frequency_response([0.0], "actuation")
    assert act.response[0].real == pytest.approx(model.sensitivity("actuation"), rel=1e-12)
