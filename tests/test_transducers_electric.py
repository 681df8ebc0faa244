"""Module (b)'s electrostatic and electromagnetic actuators against sympy (harmonics, pull-in),
the parallel-plate gradient and the Lorentz force and magnetic torque."""
import pytest
import sympy as sp
from scipy import integrate

from afmsmiler.transducers import Electromagnetic, Electrostatic

from tests.sympy_reference import fourier_coefficients


# --- electrostatic -------------------------------------------------------------------------------
@pytest.mark.slow  # a sympy derivation or a heat-equation reference, ~1-4 s
def test_electrostatic_harmonics_against_sympy():
    th, vdc, vac, dc_dz = sp.symbols("theta V_dc V_ac Cprime", real=True)
    dc, first, second = fourier_coefficients(dc_dz / 2 * (vdc + vac * sp.cos(th)) ** 2, th)
    assert sp.simplify(first - dc_dz * vdc * vac) == 0
    assert sp.simplify(second - dc_dz * vac ** 2 / 4) == 0
    model = Electrostatic(ac_voltage=2.0)
    g = model.capacitance_gradient
    comp = model.force_components(3.0)
    values = {vdc: 3.0, vac: 2.0, dc_dz: g}
    assert comp.dc == pytest.approx(float(dc.subs(values)), rel=1e-12)
    assert comp.first == pytest.approx(float(first.subs(values)), rel=1e-12)
    assert comp.second == pytest.approx(float(second.subs(values)), rel=1e-12)
    assert comp.first == pytest.approx(g * 3.0 * 2.0) and comp.second == pytest.approx(g * 4 / 4)


def test_parallel_plate_gradient_and_distributed_load():
    model = Electrostatic(gap=3e-6, electrode_length=60e-6)
    area = model.width * model.electrode_length

    def cap(z):  # C(z) = eps0 A / (g + z), z up, electrode below
        return 8.8541878188e-12 * area / (3e-6 + z)  # epsilon_0: CODATA 2022
    h = 1e-12
    assert model.capacitance_gradient == pytest.approx((cap(h) - cap(-h)) / (2 * h), rel=1e-6)
    # tip deflection of a uniform load on [a, L] by Maxwell-Betti reciprocity: the tip moves under
    # a unit load at s as much as s moves under a unit tip load, i.e. module (a)'s deflection(s, 1)
    lever = model.lever
    a = model.length - model.electrode_length
    q = 1.0 / model.electrode_length
    ref, _ = integrate.quad(lambda s: q * float(lever.deflection(s, 1.0)), a, model.length)
    assert model.compliance[0] == pytest.approx(ref, rel=1e-10)
    # limits: a load spread over the whole lever: q L^4 / (8 E J) = 3 F / (8 k) (Roark, Table 8.1);
    # a load concentrated at the end: F / k
    full = model.replace(electrode_length=model.length)
    assert full.compliance[0] == pytest.approx(3 / (8 * lever.spring_constant), rel=1e-12)
    end = model.replace(electrode_length=1e-6)
    assert end.compliance[0] == pytest.approx(1 / lever.spring_constant, rel=2e-2)
    # the chain: force from the voltage, deflection towards the electrode
    chain = model.chain([10.0])
    f = 0.5 * model.capacitance_gradient * (100 + model.ac_voltage ** 2 / 2)
    assert chain.stage("force").values[0] == pytest.approx(f, rel=1e-12)
    assert chain.output.values[0] < 0
    # small signal: d/dV of (1/2) C' V^2 = C' V, C' = -eps0 A / g^2, times the quadrature compliance
    expected = ref * (-8.8541878188e-12 * area / 3e-6 ** 2) * 10.0
    assert model.sensitivity(at=10.0) == pytest.approx(expected, rel=1e-10)


@pytest.mark.slow  # a sympy derivation, ~0.6-0.8 s
def test_pull_in_voltage_against_sympy():
    # spring k against the parallel-plate pull eps0 A V^2 / (2 (g - x)^2): the equilibrium is lost
    # where the total stiffness vanishes too (Senturia, Microsystem Design, sec. 6.4)
    x, k, g, c, v = sp.symbols("x k g c V", positive=True)     # c = eps0 A
    net = k * x - c * v ** 2 / (2 * (g - x) ** 2)
    sol = sp.solve([net, sp.diff(net, x)], [x, v], dict=True)
    assert sol == [{x: g / 3, v: sp.sqrt(8 * k * g ** 3 / (27 * c))}]
    model = Electrostatic(gap=2e-6)
    subs = {k: 1 / model.compliance[0], g: 2e-6,
            c: 8.8541878188e-12 * model.width * model.electrode_length}
    assert model.pull_in_voltage == pytest.approx(float(sol[0][v].subs(subs)), rel=1e-12)


# --- electromagnetic -----------------------------------------------------------------------------
def test_lorentz_force_and_magnetic_torque():
    model = Electromagnetic(field=0.2, conductor_length=30e-6)
    lever = model.lever
    chain = model.chain([10e-3])
    force = 0.2 * 10e-3 * 30e-6                      # F = B I l
    assert chain.stage("force").values[0] == pytest.approx(force, rel=1e-12)
    assert chain.output.values[0] == pytest.approx(float(lever.deflection(lever.length, force)),
                                                   rel=1e-12)
    # sensitivity B l / k with k = E w h^3 / (4 L^3) (silicon <110>, 169 GPa)
    k = 169e9 * model.width * model.thickness ** 3 / (4 * model.length ** 3)
    assert model.sensitivity() == pytest.approx(0.2 * 30e-6 / k, rel=1e-12)
    assert model.moment_force(1e-12, 50.0) == pytest.approx(5e-11)
    # an end moment M: E J z'' = M, z(0) = z'(0) = 0 (sympy)
    x, L, EJ, M = sp.symbols("x L EJ M", positive=True)
    zf = sp.Function("z")
    sol = sp.dsolve(sp.Eq(EJ * zf(x).diff(x, 2), M), zf(x),
                    ics={zf(0): 0, zf(x).diff(x).subs(x, 0): 0}).rhs
    moment = 1e-12 * 0.2  # m B sin(90 deg)
    subs = {L: lever.length, EJ: lever.flexural_rigidity, M: moment}
    z_ref = float(sol.subs(x, L).subs(subs))
    th_ref = float(sol.diff(x).subs(x, L).subs(subs))
    z, th = model.moment_torque_deflection(1e-12)
    assert z == pytest.approx(z_ref, rel=1e-12) and th == pytest.approx(th_ref, rel=1e-12)
