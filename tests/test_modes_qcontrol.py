"""Q control (afmsmiler.modes.qcontrol) against independent derivations.

- sympy derives the closed loop's characteristic polynomial from the equation of motion with the
  feedback g k [cos(phi) z - sin(phi) z'/w0], and the phasor form g k e^{-i phi} Z of a harmonic
  at w0 (that is what "a phase lag phi" means); the module's k_eff, f_eff and Q_eff must equal it;
- python-control builds the loop as a plant 1 / (m s^2 + c s + k) in positive feedback with the
  controller g k (cos(phi) - sin(phi) s / w0): its poles give Q_eff (Q = 1 / (2 zeta)) and its
  frequency response's peak and half-power width give f_eff and Q_eff;
- scipy's solve_ivp integrates the loop with the phase shifter realised as a pure delay
  z(t - phi / w0) (how Anczykowski et al. 1998 built it), whose ring-down must give Hoelscher et
  al.'s Q_eff = 1 / (1/Q + g) at phi = 90 deg within 1 % for Q_eff >= 20 (the delay equals the
  module's derivative form only at w0: the error is of order 1 / Q_eff^2).
"""
import functools
import math

import control
import numpy as np
import pytest
import sympy as sp
from scipy.integrate import solve_ivp

from afmsmiler.modes.qcontrol import (PARAMETERS, QControl, closed_loop_response,
                                      fit_ring_down, quality_factor_from_ringdown, ring_down,
                                      stable_gains)

CASES = [dict(quality_factor=400.0, gain=0.0075, phase=math.pi / 2),
         dict(quality_factor=3.0, gain=-0.25, phase=math.pi / 2),
         dict(quality_factor=50.0, gain=0.2, phase=math.radians(30.0)),
         dict(quality_factor=10.0, gain=-0.1, phase=math.radians(120.0)),
         dict(quality_factor=2.0, gain=0.0, phase=0.0)]


@functools.lru_cache(maxsize=None)
def _sympy_closed_form():
    """(k_eff/k, 1/Q_lin, Q_eff) as sympy expressions in g, phi, Q, derived from the ODE."""
    m, k, q, g, phi, s, z = sp.symbols("m k Q g phi s Z", positive=True)
    w0 = sp.sqrt(k / m)
    # Laplace transform of m z'' + (m w0/Q) z' + k z - g k (cos(phi) z - sin(phi) z'/w0) = 0
    char = sp.expand(m * s**2 + m * w0 / q * s + k - g * k * (sp.cos(phi) - sp.sin(phi) * s / w0))
    poly = sp.Poly(char / m, s)
    a2, a1, a0 = poly.all_coeffs()
    assert sp.simplify(a2 - 1) == 0
    w_eff = sp.sqrt(a0)                      # s^2 + (w_eff / Q_eff) s + w_eff^2
    q_eff = sp.simplify(w_eff / a1)
    # phasor check: the feedback of a harmonic at w0 equals g k e^{-i phi} Z
    phasor = sp.simplify((g * k * (sp.cos(phi) - sp.sin(phi) * sp.I * w0 / w0)) * z
                         - g * k * sp.exp(-sp.I * phi) * z)
    assert sp.simplify(phasor.rewrite(sp.cos)) == 0
    ratio = sp.simplify(a0 / w0**2)
    lin = sp.simplify(a1 / w0)
    return (sp.lambdify((g, phi, q), ratio), sp.lambdify((g, phi, q), lin),
            sp.lambdify((g, phi, q, m, k), q_eff))


@pytest.mark.parametrize("case", CASES)
def test_closed_form_equals_sympy_derivation(case):
    ratio, lin, q_eff = _sympy_closed_form()
    qc = QControl(**case)
    args = (case["gain"], case["phase"], case["quality_factor"])
    assert qc.stiffness_ratio == pytest.approx(ratio(*args), rel=1e-12)
    assert qc.damping_ratio == pytest.approx(lin(*args), rel=1e-12)
    assert qc.effective_quality_factor == pytest.approx(q_eff(*args, qc.mass,
                                                              qc.spring_constant), rel=1e-9)
    assert qc.effective_resonance_frequency == pytest.approx(
        qc.resonance_frequency * math.sqrt(ratio(*args)), rel=1e-12)


def _control_loop(qc):
    w0 = 2 * math.pi * qc.resonance_frequency
    m, k = qc.mass, qc.spring_constant
    plant = control.tf([1.0], [m, m * w0 / qc.quality_factor, k])
    ctrl = control.tf([-qc.gain * k * math.sin(qc.phase) / w0, qc.gain * k * math.cos(qc.phase)],
                      [1.0])
    return control.feedback(plant, ctrl, sign=+1)


@pytest.mark.parametrize("case", CASES)
def test_poles_of_python_control_loop(case):
    qc = QControl(**case)
    loop = _control_loop(qc)
    wn, zeta, _ = control.damp(loop, doprint=False)
    # python-control: the natural frequency and damping of the closed loop's poles
    assert wn[0] / (2 * math.pi) == pytest.approx(qc.effective_resonance_frequency, rel=1e-9)
    assert 0.5 / zeta[0] == pytest.approx(qc.effective_quality_factor, rel=1e-9)
    # the steady state of the module's closed form equals python-control's frequency response
    f = qc.resonance_frequency * np.linspace(0.5, 1.5, 41)
    mag, phase, _ = control.frequency_response(loop, 2 * math.pi * f)
    ours = closed_loop_response(f, qc)
    np.testing.assert_allclose(ours.amplitude / qc.spring_constant, mag, rtol=1e-9)
    np.testing.assert_allclose(np.cos(ours.phase), np.cos(-phase), atol=1e-9)


@pytest.mark.parametrize("gain", [0.0075, -0.002, 0.0])
def test_resonance_width_of_python_control_response_gives_q_eff(gain):
    """Peak and half-power width of python-control's |H(f)|: Q = f_peak / df to O(1/Q^2)."""
    qc = QControl(quality_factor=400.0, gain=gain)
    loop = _control_loop(qc)
    q = qc.effective_quality_factor
    f0 = qc.effective_resonance_frequency
    f = f0 * (1.0 + np.linspace(-4.0, 4.0, 200_001) / q)
    mag = control.frequency_response(loop, 2 * math.pi * f).magnitude.ravel()
    above = f[mag >= mag.max() / math.sqrt(2.0)]
    width = above[-1] - above[0]
    assert f[np.argmax(mag)] == pytest.approx(f0, rel=1.0 / q**2 + 1e-7)
    assert f0 / width == pytest.approx(q, rel=2.0 / q + 1e-3)


def test_hoelscher_velocity_feedback_limit():
    # phi = 90 deg: the resonance stays and Q_eff = 1 / (1/Q + g) (Hoelscher et al. 2006, eq. 5)
    for q, g in ((400.0, 0.0075), (3.0, -0.25), (20.0, -0.049)):
        qc = QControl(quality_factor=q, gain=g, phase=math.pi / 2)
        assert qc.effective_quality_factor == pytest.approx(1.0 / (1.0 / q + g), rel=1e-12)
        assert qc.effective_resonance_frequency == pytest.approx(qc.resonance_frequency,
                                                                 rel=1e-12)


def _delay_ringdown(qc, periods):
    """Ring-down of m z'' + c z' + k z = g k z(t - phi/w0), the delay realisation.

    Classical fourth-order Runge-Kutta in the dimensionless time w0 t, 256 steps a period, the
    delayed deflection read (linearly interpolated) from the stored past; before t = 0 the
    history is the free harmonic motion cos(t) (the lever released from a steady oscillation).
    """
    n_per = 256
    h = 2 * math.pi / n_per
    lag = qc.phase / h  # the delay in steps
    n = periods * n_per
    z = np.empty(n + 1)
    z[0], v = 1.0, 0.0

    def past(t_index):
        if t_index <= 0.0:
            return math.cos(t_index * h)
        i = int(t_index)
        return z[i] + (t_index - i) * (z[min(i + 1, n)] - z[i])

    def acc(x, xd, t_index):
        return -x - xd / qc.quality_factor + qc.gain * past(t_index - lag)

    for i in range(n):
        x = z[i]
        k1x, k1v = v, acc(x, v, i)
        k2x, k2v = v + 0.5 * h * k1v, acc(x + 0.5 * h * k1x, v + 0.5 * h * k1v, i + 0.5)
        k3x, k3v = v + 0.5 * h * k2v, acc(x + 0.5 * h * k2x, v + 0.5 * h * k2v, i + 0.5)
        k4x, k4v = v + h * k3v, acc(x + h * k3x, v + h * k3v, i + 1.0)
        z[i + 1] = x + h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x)
        v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v)
    return np.arange(n + 1) * h, z


@pytest.mark.parametrize("q,gain", [(100.0, 0.015), (100.0, -0.005), (20.0, 0.0), (400.0, 0.0075)])
def test_delay_realisation_ringdown_matches_closed_form(q, gain):
    """The delay e^{-s phi/w0} equals the derivative form at s = i w0; off it, the pole moves by
    a relative pi |g| / 4 (first order in s - i w0): that plus 0.3 % is the tolerance."""
    qc = QControl(quality_factor=q, gain=gain, phase=math.pi / 2)
    t, z = _delay_ringdown(qc, periods=40)
    q_meas = quality_factor_from_ringdown(t, z, skip=2)
    assert q_meas == pytest.approx(qc.effective_quality_factor, rel=0.003 + math.pi * abs(gain) / 4)


@pytest.mark.parametrize("case", CASES[:4])
def test_ring_down_closed_form_equals_ode_integration(case):
    qc = QControl(**case)
    w0 = 2 * math.pi * qc.resonance_frequency
    t = np.linspace(0.0, 30.0 / qc.resonance_frequency, 3001)

    def rhs(_, y):
        return [y[1], (-qc.spring_constant * y[0] - qc.mass * w0 / qc.quality_factor * y[1]
                       + qc.feedback_force(y[0], y[1])) / qc.mass]

    sol = solve_ivp(rhs, (0.0, t[-1]), [1e-9, 0.0], t_eval=t, rtol=1e-10, atol=1e-22,
                    method="DOP853")
    ours = ring_down(t, qc, amplitude=1e-9)
    np.testing.assert_allclose(ours.deflection, sol.y[0], atol=1e-6 * 1e-9)


def test_ringdown_estimator_on_the_closed_form():
    for q in (5.0, 50.0, 400.0):
        qc = QControl(quality_factor=q, resonance_frequency=1e3)
        t = np.linspace(0.0, min(3 * q, 300) / 1e3, 60_001)
        rd = ring_down(t, qc)
        assert quality_factor_from_ringdown(rd.time, rd.deflection) == pytest.approx(q, rel=1e-4)


@pytest.mark.parametrize("q", [0.8, 2.4, 24.0])
def test_fit_ring_down_recovers_q_and_f_of_the_closed_form(q):
    qc = QControl(quality_factor=q, resonance_frequency=31.0)
    t = np.arange(0, 1.0, 1e-3)
    rd = ring_down(t, qc, amplitude=1e-3)
    rng = np.random.default_rng(0)
    noisy = rd.deflection + 2e-3 + rng.uniform(-3.8e-6, 3.8e-6, t.size)  # an encoder count
    q_fit, f_fit = fit_ring_down(t, noisy)
    assert q_fit == pytest.approx(q, rel=0.01)
    assert f_fit == pytest.approx(31.0, rel=0.002)
    with pytest.raises(ValueError, match="decay"):
        fit_ring_down(t, np.cos(2 * np.pi * 31 * t) * np.exp(t))


def test_overdamped_and_critical_ring_down_are_finite_and_start_at_amplitude():
    for q in (0.5, 0.2):
        rd = ring_down(np.linspace(0, 1e-5, 11), QControl(quality_factor=q), amplitude=2e-9)
        assert rd.deflection[0] == pytest.approx(2e-9)
        assert np.all(np.isfinite(rd.deflection)) and np.all(rd.deflection > 0)


def test_stability_limit():
    assert stable_gains(400.0, math.pi / 2) == (pytest.approx(-0.0025), math.inf)
    low, high = stable_gains(10.0, math.radians(30.0))
    assert low == pytest.approx(-0.2) and high == pytest.approx(1.0 / math.cos(math.radians(30)))
    assert QControl(quality_factor=400.0, gain=-0.0024).stable
    unstable = QControl(quality_factor=400.0, gain=-0.0026)
    assert not unstable.stable and math.isnan(unstable.effective_quality_factor)
    # the loop's poles (python-control) cross into the right half plane at the limit
    assert max(np.real(control.poles(_control_loop(unstable)))) > 0
    assert max(np.real(control.poles(_control_loop(unstable.replace(gain=-0.0024))))) < 0
    assert QControl(quality_factor=400.0, gain=-0.0025).effective_quality_factor == math.inf


@pytest.mark.parametrize("case", [*CASES, dict(quality_factor=400.0, gain=-0.005),
                                  dict(quality_factor=10.0, gain=1.5, phase=0.0)])
def test_stability_is_decided_by_the_poles_of_python_control(case):
    """The module's poles are python-control's (the plant in positive feedback with the
    controller), and the loop is stable exactly when they lie in the left half plane."""
    qc = QControl(**case)
    theirs = np.sort_complex(control.poles(_control_loop(qc)))
    np.testing.assert_allclose(np.sort_complex(np.array(qc.poles)), theirs,
                               rtol=1e-9, atol=1e-9 * 2 * math.pi * qc.resonance_frequency)
    assert qc.stable == bool(np.all(theirs.real < 0))


def test_an_unstable_loop_has_no_steady_resonance():
    """Beyond g = -1/Q (phi = 90 deg) or with k_eff < 0 the closed form's |H| would still be a
    smooth curve, but the lever never reaches it: the response says there is no steady state."""
    f = 300e3 * np.linspace(0.9, 1.1, 11)
    for qc in (QControl(quality_factor=400.0, gain=-0.005),
               QControl(quality_factor=10.0, gain=1.5, phase=0.0)):
        assert max(np.real(control.poles(_control_loop(qc)))) > 0        # python-control
        r = closed_loop_response(f, qc)
        assert not r.steady and np.all(np.isnan(r.amplitude)) and np.all(np.isnan(r.phase))
        # its free motion grows instead, at the rate of python-control's rightmost pole
        sigma = max(np.real(control.poles(_control_loop(qc))))
        t = np.linspace(0.0, math.log(100.0) / sigma, 20001)     # e^(sigma t) reaches 100
        grows = abs(ring_down(t, qc).deflection)
        period = 1.0 / qc.resonance_frequency
        late = grows[t >= t[-1] - period].max()                   # the last period's peak
        half = grows[(t >= t[-1] / 2 - period) & (t <= t[-1] / 2)].max()
        assert late / half == pytest.approx(10.0, rel=0.1)         # e^(sigma t / 2)
    stable = closed_loop_response(f, QControl(quality_factor=400.0, gain=-0.002))
    assert stable.steady and np.all(np.isfinite(stable.amplitude))


def test_validation_names_the_parameter():
    with pytest.raises(ValueError, match="gain"):
        QControl(gain=11.0)
    with pytest.raises(ValueError, match="phase"):
        QControl(phase=4.0)
    with pytest.raises(TypeError, match="qc"):
        closed_loop_response([1.0], qc="lever")
    with pytest.raises(ValueError, match="frequency"):
        closed_loop_response([-1.0])
    with pytest.raises(ValueError, match="amplitude"):
        ring_down([0.0], amplitude=0.0)
    assert set(PARAMETERS) == {"spring_constant", "resonance_frequency", "quality_factor",
                               "gain", "phase"}
