"""Module (c), the derivation: sympy closed loop vs python-control's feedback, steady state, and the
14 closed forms vs python-control's step_response / forced_response on the same transfer function.

Tolerance: 1e-9 of the peak. python-control simulates the state-space realisation of the same
TransferFunction with the exact matrix exponential of the first-order-hold augmented system
(``forced_response``), exact for steps and ramps, so the two agree to rounding (~1e-13 here).
"""
import control
import numpy as np
import pytest
import sympy as sp

from afmsmiler.controller import ContactLoop, derivation
from afmsmiler.controller.closed_forms import (MERGE_TOLERANCE, classify_roots, closed_form,
                                                normalise)

S = derivation.SYMBOLS


def random_params(rng, ki_zero=False):
    """Parameters in SI around the paper's scale (ng, us, um)."""
    return dict(m_c=rng.uniform(0.3, 3) * 1e-12, m_s=rng.uniform(0.3, 3) * 1e-12,
                b_c=rng.uniform(0, 0.1) * 1e-6, b_s=rng.uniform(0, 0.1) * 1e-6,
                k_c=rng.uniform(0.1, 10), k_s=rng.uniform(0.1, 100), kp=rng.uniform(0, 5),
                ki=0.0 if ki_zero else rng.uniform(0, 2) * 1e6, kd=rng.uniform(0, 0.5) * 1e-6)


# --- the closed loop ------------------------------------------------------------------------------
def test_denominator_is_the_one_in_the_docs():
    A, B, C, D = derivation.denominator_coefficients()
    m_c, m_s, b_c, b_s, k_c, k_s = (S[k] for k in ("m_c", "m_s", "b_c", "b_s", "k_c", "k_s"))
    kp, ki, kd = S["kp"], S["ki"], S["kd"]
    assert sp.expand(A - (m_c + m_s + b_s * kd)) == 0
    assert sp.expand(B - (b_c + b_s + b_s * kp + k_s * kd)) == 0
    assert sp.expand(C - (k_c + k_s + b_s * ki + k_s * kp)) == 0
    assert sp.expand(D - k_s * ki) == 0
    # the numerators as the module docstring writes them
    s = S["s"]
    pid = kd * s ** 2 + kp * s + ki
    docs = {"Zc_T": s * (b_s * s + k_s), "Znp_T": -(b_s * s + k_s) * pid,
            "Zc_R": (b_s * s + k_s) * pid,
            "Znp_R": ((m_c + m_s) * s ** 2 + (b_c + b_s) * s + k_c + k_s) * pid}
    den = A * s ** 3 + B * s ** 2 + C * s + D
    for name, num in docs.items():
        got_num, got_den = derivation.closed_loop()[name]
        assert sp.expand(got_den - den) == 0, name
        assert sp.expand(got_num - num) == 0, name
    assert "A = m_c + m_s + b_s K_D" in derivation.__doc__
    assert "D = k_s K_I" in derivation.__doc__


@pytest.mark.parametrize("seed", range(6))
def test_closed_loop_equals_python_control_feedback(seed):
    rng = np.random.default_rng(seed)
    p = random_params(rng, ki_zero=seed % 3 == 0)
    # P and C built independently with python-control
    P = control.tf([p["b_s"], p["k_s"]], [p["m_c"] + p["m_s"], p["b_c"] + p["b_s"],
                                          p["k_c"] + p["k_s"]])
    C = control.tf([p["kd"], p["kp"], p["ki"]], [1, 0])
    zc_ref = control.feedback(P, C)             # Z_c/T = P / (1 + P C)
    znp_ref = -control.feedback(P * C, 1)       # Z_np/T = -P C / (1 + P C)
    zc, znp = ContactLoop(**p).closed_loop()
    s = np.array([1e5j, 3e5 + 2e6j, -4e4 + 1e7j, 2e6])
    for ours, ref in ((zc, zc_ref), (znp, znp_ref)):
        np.testing.assert_allclose(ours(s), ref(s), rtol=1e-9)
    # and the numeric coefficients equal the sympy derivation
    subs = {S[k]: v for k, v in p.items()}
    num, den = derivation.closed_loop()["Zc_T"]
    G = sp.lambdify(S["s"], (num / den).subs(subs), "numpy")
    np.testing.assert_allclose(zc(s), G(s), rtol=1e-12)


@pytest.mark.parametrize("seed", range(8))
def test_denominator_is_the_characteristic_polynomial(seed):
    """A s^3 + B s^2 + C s + D (sympy, substituted) equals the denominator python-control forms
    for the loop closed from P and C built independently: den(P) den(C) + num(P) num(C), the
    characteristic polynomial of 1 + P C (coefficient by coefficient, K_I = 0 included), and its
    roots are python-control's closed-loop poles."""
    rng = np.random.default_rng(20 + seed)
    p = random_params(rng, ki_zero=seed % 4 == 0)
    P = control.tf([p["b_s"], p["k_s"]], [p["m_c"] + p["m_s"], p["b_c"] + p["b_s"],
                                          p["k_c"] + p["k_s"]])
    C = control.tf([p["kd"], p["kp"], p["ki"]], [1, 0])
    loop_tf = control.feedback(P, C)
    char = np.asarray(loop_tf.den[0][0], dtype=float)
    subs = {S[k]: v for k, v in p.items()}
    ours = np.array([float(c.subs(subs)) for c in derivation.denominator_coefficients()])
    assert char.size == 4
    # same scale: both lead with A = m_c + m_s + b_s K_D (python-control's dP dC has lead M,
    # num(P) num(C) adds b_s K_D)
    np.testing.assert_allclose(ours, char, rtol=1e-12, atol=0)  # each coefficient, own scale
    poles = control.poles(loop_tf)
    np.testing.assert_allclose(np.sort_complex(np.roots(ours)), np.sort_complex(poles),
                               rtol=1e-8, atol=1e-8 * np.max(np.abs(poles)))


@pytest.mark.parametrize("ki", [0.0, 3e5])
def test_steady_state(ki):
    ss = derivation.steady_state()
    R = sp.Symbol("R")
    assert sp.simplify(ss["Zc"] - R) == 0
    assert sp.simplify(ss["Znp"] - (S["k_c"] + S["k_s"]) * R / S["k_s"]) == 0
    rng = np.random.default_rng(3)
    p = {**random_params(rng), "ki": ki, "kd": 0.0}
    loop = ContactLoop(**p)
    P = control.tf([p["b_s"], p["k_s"]], [p["m_c"] + p["m_s"], p["b_c"] + p["b_s"],
                                          p["k_c"] + p["k_s"]])
    # python-control, independently: Z_c/R = P C / (1 + P C), Z_np/R = C / (1 + P C), at s -> 0
    if ki == 0:
        C = control.tf([p["kp"]], [1])
        zc_R, znp_R = control.feedback(P * C, 1)(0).real, control.feedback(C, P)(0).real
    else:
        zc_R, znp_R = 1.0, (p["k_c"] + p["k_s"]) / p["k_s"]
        C = control.tf([p["kp"], p["ki"]], [1, 0])
        assert control.feedback(P * C, 1)(1e-6).real == pytest.approx(zc_R, rel=1e-6)
    z = loop.steady_state(2e-8, 0.0)
    assert z.z_c == pytest.approx(zc_R * 2e-8, rel=1e-12)
    assert z.z_np == pytest.approx(znp_R * 2e-8, rel=1e-12)
    # a constant topography: Z_c/T and Z_np/T at s = 0 from python-control
    zc_T, znp_T = loop.closed_loop()
    z1 = loop.steady_state(0.0, 1e-8)
    assert z1.z_c == pytest.approx(zc_T(0).real * 1e-8, abs=1e-22)
    assert z1.z_np == pytest.approx(znp_T(0).real * 1e-8, rel=1e-12)


# --- the 14 closed forms ------------------------------------------------------------------------
@pytest.mark.slow
def test_generated_code_text_is_up_to_date():
    """The text check holds only under the sympy release that printed the file: another release
    may order the same formulas differently (the numeric check below covers any release)."""
    from afmsmiler.controller import _generated
    if _generated.SYMPY_VERSION != sp.__version__:
        pytest.skip(f"_generated.py was printed by sympy {_generated.SYMPY_VERSION}, this is "
                    f"sympy {sp.__version__}: text check skipped, numbers checked below")
    assert derivation.GENERATED.read_text(encoding="utf-8") == derivation.generate_code()
    assert len(derivation.CASES) == 14


@pytest.mark.slow
@pytest.mark.parametrize("case", derivation.CASES, ids=lambda c: c.name)
def test_generated_functions_equal_the_derivation_numerically(case):
    """Each generated function against the derived sympy expressions, lambdified, on random
    numerators and roots (tolerance 1e-9: both evaluate the same formulas in double precision,
    differently arranged; they agree to ~1e-14)."""
    assert derivation.numeric_mismatch(case, samples=20, seed=1) <= 1e-9


@pytest.mark.slow
def test_numeric_check_catches_a_wrong_generated_function(monkeypatch):
    from afmsmiler.controller import _generated
    case = derivation.CASES[3]
    right = _generated.FUNCTIONS[case.name]

    def wrong(b, *roots):
        q0, q1, modes = right(b, *roots)
        return q0, q1, tuple(m * (1 + 1e-6) for m in modes)

    monkeypatch.setitem(_generated.FUNCTIONS, case.name, wrong)
    assert derivation.numeric_mismatch(case) > 1e-9


@pytest.mark.slow
@pytest.mark.parametrize("case", derivation.CASES, ids=lambda c: c.name)
def test_closed_form_inverts_the_laplace_transform(case):
    assert derivation.check_case(case)


ROOTS = {
    (2, "distinct"): [-1.0, -3.0],
    (2, "double"): [-2.0, -2.0],
    (2, "complex"): [-0.4 + 2.5j, -0.4 - 2.5j],
    (3, "distinct"): [-0.7, -2.0, -5.0],
    (3, "real_complex"): [-1.0, -0.3 + 3.0j, -0.3 - 3.0j],
    (3, "double_single"): [-2.0, -2.0, -0.7],
    (3, "triple"): [-1.5, -1.5, -1.5],
}


def _reference(G, t, inp):
    if inp == "step":
        return control.step_response(G, t).outputs
    return control.forced_response(G, t, t).outputs  # u = t: exact with the linear-hold update


def _compare(roots, inp, seed=0, t_end=15.0, expect=None):
    rng = np.random.default_rng(seed)
    den = np.real(np.poly(roots)) * rng.uniform(0.5, 2)  # not monic: normalise() must do it
    num = rng.normal(size=len(roots) + 1)  # with a direct feedthrough
    G = control.tf(num, den)
    b, den_monic = normalise(num, den)
    structure, params = classify_roots(np.roots(den_monic))
    form = closed_form(b, structure, params, inp)
    if expect is not None:
        assert form.case == expect
    t = np.linspace(0, t_end, 3001)
    ref = _reference(G, t, inp)
    err = np.max(np.abs(form(t) - ref)) / np.max(np.abs(ref))
    return err


@pytest.mark.parametrize("case", derivation.CASES, ids=lambda c: c.name)
@pytest.mark.parametrize("seed", [0, 1])
def test_every_case_matches_python_control(case, seed):
    err = _compare(ROOTS[(case.order, case.structure)], case.input, seed, expect=case.name)
    assert err < 1e-9


@pytest.mark.parametrize("inp", ["step", "ramp"])
@pytest.mark.parametrize("roots, expect", [
    ([-1.0, -1.0 * (1 + 1e-8)], "o2_double"),                   # merged: below the threshold
    ([-1.0, -1.0 * (1 + 9e-6)], "o2_double"),                   # just below it
    ([-1.0, -1.0 * (1 + 1.2e-5)], "o2_distinct"),               # kept apart: just above it
    ([-1.0, -1.0 * (1 + 1e-4)], "o2_distinct"),
    ([-1.0 + 1e-8j, -1.0 - 1e-8j], "o2_double"),
    ([-1.0 + 4e-6j, -1.0 - 4e-6j], "o2_double"),
    ([-1.0 + 3.5e-6j, -1.0 - 3.5e-6j], "o2_double"),
    ([-1.0 + 6e-6j, -1.0 - 6e-6j], "o2_complex"),               # 2 omega > 1e-5: a pair
    ([-1.0 + 1e-5j, -1.0 - 1e-5j], "o2_complex"),
    ([-1.0, -1.0 * (1 + 1e-8), -3.0], "o3_double_single"),
    ([-1.0, -1.0 * (1 + 9e-6), -3.0], "o3_double_single"),
    ([-1.0, -1.0 * (1 + 1.2e-5), -3.0], "o3_distinct"),
    ([-3.0, -1.0 + 1e-8j, -1.0 - 1e-8j], "o3_double_single"),
    ([-3.0, -1.0 + 3e-6j, -1.0 - 3e-6j], "o3_double_single"),
    ([-3.0, -1.0 + 6e-6j, -1.0 - 6e-6j], "o3_real_complex"),
    ([-1.0, -1.0 * (1 + 1e-8), -1.0 * (1 - 1e-8)], "o3_triple"),
    ([-1.0, -1.0 + 1e-9j, -1.0 - 1e-9j], "o3_triple"),
    ([-2.0, -1.0 * (1 + 1e-3), -1.0], "o3_distinct"),
])
def test_near_repeated_roots_keep_their_accuracy(roots, expect, inp):
    """Root structures at the boundaries between cases, against python-control, over |p| t up to
    15 and 60 (the span of a scan)."""
    assert _compare(roots, inp, expect=f"{inp}_{expect}") < 1e-9
    assert _compare(roots, inp, t_end=60.0) < 1e-9


def test_merge_threshold_is_relative():
    assert classify_roots([-1e6, -1e6 * (1 + 0.1 * MERGE_TOLERANCE)])[0] == "double"
    assert classify_roots([-1e6, -1e6 * (1 + 10 * MERGE_TOLERANCE)])[0] == "distinct"


@pytest.mark.parametrize("spread", [1e-5, 3e-5, 1e-4, 2e-4, 5e-4, 1e-3])
def test_three_clustered_roots_documented_accuracy(spread):
    """Three roots spread by 1e-5..1e-3 (expanded about their mean in closed_forms) keep the
    issue's 1e-9 of the peak, like tighter and wider clusters."""
    for roots in ([-1.0, -1.0 * (1 + spread), -1.0 * (1 - spread)],
                  [-1.0, -1.0 + spread * 1j, -1.0 - spread * 1j]):
        for inp in ("step", "ramp"):
            assert _compare(roots, inp) < 1e-9


@pytest.mark.slow
def test_derivation_script_check_mode(monkeypatch, capsys):
    assert derivation.main(["--check"]) == 0
    from afmsmiler.controller import _generated
    monkeypatch.setattr(_generated, "SYMPY_VERSION", "0.0")  # as under another sympy release
    assert derivation.main(["--check"]) == 0
    assert "text check skipped" in capsys.readouterr().out
