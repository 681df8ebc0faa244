"""Frequency-modulation mode: Giessibl's frequency shift and the Sader-Jarvis inversion.

References used as the independent source: the analytic small-amplitude limit
df = -f0 / (2 k) dF/dz (Giessibl, PRB 56, 16010 (1997)), scipy's adaptive quadrature with the
algebraic endpoint weight (QUADPACK's QAWS) for both integrals, and analytic force laws.
"""
import math

import numpy as np
import pytest
from scipy.integrate import quad

from afmsmiler.modes import fm

K, F0 = 40.0, 300e3
LEVER = dict(spring_constant=K, resonance_frequency=F0)
# A Morse force (bond-like: repulsive wall, attractive well): depth U0, decay length LAM
U0, LAM, Z0 = 1e-19, 0.2e-9, 0.3e-9


def morse(z):
    e = np.exp(-(np.asarray(z, dtype=float) - Z0) / LAM)
    return 2 * U0 / LAM * (e * e - e)


def morse_gradient(z):
    e = np.exp(-(np.asarray(z, dtype=float) - Z0) / LAM)
    return 2 * U0 / LAM ** 2 * (e - 2 * e * e)


HR = 1e-27  # Hamaker constant x tip radius / 6 in N m^2: F = -HR / z^2 (sphere over a plane)


def vdw(z):
    return -HR / np.asarray(z, dtype=float) ** 2


def giessibl_quad(force, z, amplitude):
    """Giessibl's integral by QUADPACK's algebraic-weight rule (independent of the code)."""
    integral = quad(lambda u: float(force(z + amplitude * (1 + u))) * u, -1, 1,
                    weight="alg", wvar=(-0.5, -0.5), limit=200)[0]
    return -F0 / (math.pi * K * amplitude) * integral


@pytest.mark.parametrize("amplitude", [1e-12, 0.1e-9, 1e-9, 10e-9])
@pytest.mark.parametrize("z", [0.22e-9, 0.3e-9, 0.6e-9])
def test_frequency_shift_matches_adaptive_quadrature(amplitude, z):
    got = fm.frequency_shift(morse, z, amplitude=amplitude, **LEVER)
    assert got == pytest.approx(giessibl_quad(morse, z, amplitude), rel=1e-5, abs=1e-9)


@pytest.mark.parametrize("ratio, nodes, tolerance", [(500, 256, 1e-12), (5000, 256, 1e-4),
                                                     (5000, 512, 1e-10)])
def test_quadrature_converges_as_documented(ratio, nodes, tolerance):
    z = np.linspace(0.2e-9, 2e-9, 10)
    a = ratio * LAM
    reference = fm.frequency_shift(morse, z, amplitude=a, nodes=4096, **LEVER)
    got = fm.frequency_shift(morse, z, amplitude=a, nodes=nodes, **LEVER)
    assert np.allclose(got, reference, rtol=tolerance, atol=0)


def test_frequency_shift_small_amplitude_limit():
    z = np.linspace(0.2e-9, 1e-9, 50)
    a = 1e-13
    df = fm.frequency_shift(morse, z, amplitude=a, **LEVER)
    # the analytic gradient (not the code's) at the rest position z + A, the centre of the
    # oscillation: the mean over the cycle differs from it by O((A / LAM)^2)
    expected = -F0 / (2 * K) * morse_gradient(z + a)
    assert np.allclose(df, expected, rtol=1e-5, atol=1e-9 * np.abs(expected).max())
    assert np.allclose(fm.force_gradient_shift(morse_gradient(z + a), **LEVER), expected)


def test_frequency_shift_of_a_linear_force_is_independent_of_amplitude():
    for a in (1e-12, 1e-9, 1e-7):
        assert fm.frequency_shift(lambda z: -3.0 * z + 1e-9, [1e-9, 5e-9], amplitude=a,
                                  **LEVER) == pytest.approx([F0 * 3 / (2 * K)] * 2, rel=1e-12)


def test_large_amplitude_vdw_closed_form():
    """For A >> z only the lower turning point matters: with u = -1 + x, F = -c / (z + A x)^2
    and sqrt(1 - u^2) ~ sqrt(2 x), the integral is c / sqrt(2) z^(-3/2) A^(-1/2) B(1/2, 3/2),
    B(1/2, 3/2) = pi / 2, so df -> -f0 c / (2 sqrt(2) k A^(3/2) z^(3/2)) (Giessibl, Rev. Mod.
    Phys. 75, 949 (2003), the large-amplitude limit for an inverse-power force)."""
    z, a = 0.5e-9, 500e-9
    got = fm.frequency_shift(vdw, z, amplitude=a, nodes=2048, **LEVER)
    assert got == pytest.approx(fm.frequency_shift(vdw, z, amplitude=a, nodes=4096, **LEVER),
                                rel=1e-6)  # converged in the nodes
    limit = -F0 * HR / (2 * math.sqrt(2) * K * a ** 1.5 * z ** 1.5)
    assert got == pytest.approx(limit, rel=3 * z / a)


def sader_jarvis_quad(z, amplitude, force=morse, span=30 * LAM):
    """Sader and Jarvis's Eq. (9) by adaptive quadrature of the exact df(z) (its own error)."""
    def omega(t):
        return fm.frequency_shift(force, t, amplitude=amplitude, nodes=512, **LEVER) / F0

    def slope(t, h=1e-14):
        return (omega(t + h) - omega(t - h)) / (2 * h)
    end = z + span
    t1 = quad(omega, z, end, limit=200)[0]
    t2 = quad(omega, z, end, weight="alg", wvar=(-0.5, 0), limit=200)[0]
    t3 = quad(slope, z, end, weight="alg", wvar=(-0.5, 0), limit=200)[0]
    return 2 * K * (t1 + math.sqrt(amplitude) / (8 * math.sqrt(math.pi)) * t2
                    - amplitude ** 1.5 / math.sqrt(2) * t3)


@pytest.mark.parametrize("ratio", [0.01, 0.1, 1.0, 10.0])
def test_sader_jarvis_discretisation_matches_adaptive_quadrature(ratio):
    """The discrete inversion equals Eq. (9) integrated adaptively (within 0.3 % of the peak)."""
    a = ratio * LAM
    z = np.linspace(0.2e-9, 0.2e-9 + 30 * LAM, 1501)  # LAM / 250 spacing
    df = fm.frequency_shift(morse, z, amplitude=a, nodes=512, **LEVER)
    force = fm.sader_jarvis(z, df, amplitude=a, **LEVER)
    peak = np.abs(morse(z)).max()
    for i in (0, 10, 50, 150):
        assert abs(force[i] - sader_jarvis_quad(z[i], a)) < 3e-3 * peak


@pytest.mark.parametrize("ratio", [0.005, 10.0, 50.0])
def test_round_trip_morse_within_one_percent(ratio):
    """Force -> df -> force within 1 % of the peak force at every sample (valid regimes)."""
    a = ratio * LAM
    z = np.linspace(0.2e-9, 0.2e-9 + 20 * LAM, 401)  # LAM / 20 spacing
    df = fm.frequency_shift(morse, z, amplitude=a, **LEVER)
    force = fm.sader_jarvis(z, df, amplitude=a, **LEVER)
    peak = np.abs(morse(z)).max()
    assert np.abs(force - morse(z)).max() < 0.01 * peak


@pytest.mark.parametrize("amplitude", [1e-12, 20e-9])
def test_round_trip_vdw_pointwise(amplitude):
    """For F ~ 1/z^2, pointwise within 1 % wherever F(last sample) < 1 % F(z) (z < z_end / 10)."""
    z = np.linspace(0.5e-9, 50e-9, 2000)
    df = fm.frequency_shift(vdw, z, amplitude=amplitude, **LEVER)
    force = fm.sader_jarvis(z, df, amplitude=amplitude, **LEVER)
    inside = z <= z[-1] / 10
    assert np.allclose(force[inside], vdw(z[inside]), rtol=0.01, atol=0)
    # beyond, the cut tail shows: the error grows to about F(z_end) / F(z) = (z / z_end)^2
    far = np.searchsorted(z, z[-1] / 2)
    assert abs(force[far] / vdw(z[far]) - 1) > 0.1


# van der Waals above a0, DMT contact below (Garcia and Perez, Surf. Sci. Rep. 47, 197 (2002),
# Eqs. 19-21): a 10 nm tip on a 1 GPa polymer, written here independently of the tapping model
H, R, A0, E_STAR = 6.4e-20, 10e-9, 0.165e-9, 1.07e9


def vdw_dmt(d):
    d = np.asarray(d, dtype=float)
    far = d > A0
    vdw = -H * R / (6 * np.where(far, d, A0) ** 2)
    return vdw + np.where(far, 0.0, 4 / 3 * E_STAR * math.sqrt(R) * np.maximum(A0 - d, 0) ** 1.5)


@pytest.mark.parametrize("amplitude", [1e-12, 10e-9, 50e-9])
def test_round_trip_vdw_dmt_out_of_contact(amplitude):
    """Closest distances above a0 (the tip never indents): within 1 % pointwise up to a tenth
    of the sampled range, whatever the amplitude (the lower turning point dominates)."""
    z = np.linspace(0.2e-9, 20e-9, 2000)
    df = fm.frequency_shift(vdw_dmt, z, amplitude=amplitude, nodes=1024, **LEVER)
    force = fm.sader_jarvis(z, df, amplitude=amplitude, **LEVER)
    inside = z <= 2e-9
    assert np.allclose(force[inside], vdw_dmt(z[inside]), rtol=0.01, atol=0)


def test_round_trip_across_the_contact_kink():
    """A curve that starts in contact: the kink of F at a0 (vdW capped, DMT beginning) is not
    resolved by an inversion that assumes a smooth curve; the error there is some per cent of
    the adhesion force, and below 1 % again a few a0 above it."""
    a = 10e-9
    z = np.linspace(-0.5e-9, 20e-9, 2000)
    df = fm.frequency_shift(vdw_dmt, z, amplitude=a, nodes=1024, **LEVER)
    error = np.abs(fm.sader_jarvis(z, df, amplitude=a, **LEVER) - vdw_dmt(z))
    adhesion = H * R / (6 * A0 ** 2)
    assert 0.01 < error[z < 2e-9].max() / adhesion < 0.05
    assert error[(z > 4 * A0) & (z < 2e-9)].max() < 0.01 * adhesion


def test_formula_error_at_intermediate_amplitude_is_a_few_percent():
    """Where A ~ the decay length, Eq. (9) itself is off by some per cent (Sader and Jarvis's
    stated accuracy): the round trip is no better, and says so."""
    a = 0.1 * LAM
    z = np.linspace(0.2e-9, 0.2e-9 + 20 * LAM, 801)
    df = fm.frequency_shift(morse, z, amplitude=a, **LEVER)
    error = np.abs(fm.sader_jarvis(z, df, amplitude=a, **LEVER) - morse(z)).max()
    assert 0.01 < error / np.abs(morse(z)).max() < 0.08


def test_uneven_sampling():
    z = np.geomspace(0.5e-9, 50e-9, 800)
    df = fm.frequency_shift(vdw, z, amplitude=1e-12, **LEVER)
    force = fm.sader_jarvis(z, df, amplitude=1e-12, **LEVER)
    inside = z <= 5e-9
    assert np.allclose(force[inside], vdw(z[inside]), rtol=0.01)


@pytest.mark.parametrize("kwargs, name", [
    (dict(spring_constant=0.0), "spring_constant"),
    (dict(spring_constant=-1.0), "spring_constant"),
    (dict(resonance_frequency=0.0), "resonance_frequency"),
    (dict(amplitude=-1e-9), "amplitude"),
    (dict(amplitude=1.0), "amplitude"),
    (dict(nodes=1), "nodes"),
    (dict(nodes=10 ** 6), "nodes"),
    (dict(z=[1e-9, math.nan]), "z"),
    (dict(z=np.zeros(10 ** 6)), "z"),
])
def test_frequency_shift_rejects_bad_input_before_calling_the_force(kwargs, name):
    calls = []

    def force(z):
        calls.append(z)
        return vdw(z)
    args = dict(z=1e-9)
    args.update(kwargs)
    z = args.pop("z")
    with pytest.raises(ValueError, match=name):
        fm.frequency_shift(force, z, **args)
    assert not calls


def test_frequency_shift_checks_the_force():
    with pytest.raises(TypeError, match="force"):
        fm.frequency_shift(3.0, 1e-9)
    with pytest.raises(ValueError, match="shape"):
        fm.frequency_shift(lambda z: 1.0, [1e-9, 2e-9])
    with pytest.raises(ValueError, match="inside the sample"):  # a hard wall below 1 nm
        fm.frequency_shift(lambda z: np.where(z < 1e-9, np.nan, vdw(z)), 0.5e-9,
                           amplitude=1e-9)


@pytest.mark.parametrize("law", [
    lambda z: vdw(z) + 1e-12j,  # a complex array: float() would drop the imaginary part
    lambda z: vdw(z).astype(object) * (1 + 1j),  # Python complex numbers in an object array
    lambda z: vdw(z).astype(str),  # text that float() would parse
])
@pytest.mark.filterwarnings("error")  # no ComplexWarning: an error before any conversion
def test_frequency_shift_refuses_a_force_that_is_not_real(law):
    z = np.linspace(1e-9, 3e-9, 3)
    with pytest.raises(TypeError, match="force"):
        fm.frequency_shift(law, z, amplitude=1e-9)
    with pytest.raises(TypeError, match="force"):
        fm.frequency_shift_curve(law, z, amplitude=1e-9)


@pytest.mark.parametrize("z, df, name", [
    ([1e-9, 2e-9], [0.0, 0.0], "z"),  # too short
    ([1e-9, 3e-9, 2e-9], [0.0, 0.0, 0.0], "z"),  # not increasing
    ([1e-9, 2e-9, 3e-9], [0.0, 0.0], "df"),  # lengths differ
    ([1e-9, 2e-9, 3e-9], [0.0, math.inf, 0.0], "df"),
    (np.arange(6000) * 1e-10, np.zeros(6000), "z"),  # beyond LIMITS["curve_points"]
])
def test_sader_jarvis_rejects_bad_input(z, df, name):
    with pytest.raises(ValueError, match=name):
        fm.sader_jarvis(z, df)


def test_frequency_shift_curve_is_the_round_trip_in_one_call():
    z = np.linspace(0.2e-9, 0.2e-9 + 20 * LAM, 401)
    curve = fm.frequency_shift_curve(morse, z, amplitude=10 * LAM, **LEVER)
    assert np.array_equal(curve.force, morse(z))
    assert np.array_equal(curve.frequency_shift,
                          fm.frequency_shift(morse, z, amplitude=10 * LAM, **LEVER))
    assert np.abs(curve.error).max() < 0.01 * np.abs(morse(z)).max()
    assert np.allclose(curve.gradient_shift, -F0 / (2 * K) * morse_gradient(z),
                       rtol=0.01, atol=1e-3 * F0 / (2 * K) * np.abs(morse_gradient(z)).max())
    calls = []
    with pytest.raises(ValueError, match="amplitude"):
        fm.frequency_shift_curve(lambda z: calls.append(z) or vdw(z), z, amplitude=0.0)
    assert not calls


def test_parameters_are_consistent():
    for p in fm.PARAMETERS.values():
        assert p.check(p.default) == p.default
    assert fm.frequency_shift(vdw, 1e-9) < 0  # the defaults work together


@pytest.mark.slow
def test_largest_inversion_returns(hang_guard):
    """The inversion at LIMITS['curve_points'] (O(n^2), 1-5 s) returns: a hang guard, not a
    speed test (``make bench`` times it)."""
    z = np.linspace(0.5e-9, 50e-9, fm.LIMITS["curve_points"])
    with hang_guard(60, expected=5):
        fm.sader_jarvis(z, np.zeros_like(z))


def _reference_inversion(z, df, k, f0, a):
    """The Sader-Jarvis inversion as the loop over lower ends it was before issue 24."""
    omega = df / f0
    slope = np.gradient(omega, z, edge_order=2)
    force = np.zeros_like(z)
    c2 = math.sqrt(a) / (8 * math.sqrt(math.pi))
    c3 = a ** 1.5 / math.sqrt(2)
    for j in range(z.size - 1):
        u = z[j:] - z[j]
        lo, hi = u[:-1], u[1:]
        h = hi - lo
        i0 = 2 * (np.sqrt(hi) - np.sqrt(lo))
        i1 = 2 / 3 * (hi ** 1.5 - lo ** 1.5)

        def pole(values):
            b = np.diff(values) / h
            return np.sum((values[:-1] - b * lo) * i0 + b * i1)
        om = omega[j:]
        trapezoid = np.sum(0.5 * (om[:-1] + om[1:]) * h)
        force[j] = 2 * k * (trapezoid + c2 * pole(om) - c3 * pole(slope[j:]))
    return force


@pytest.mark.parametrize("spacing", ["even", "uneven"])
def test_the_vectorised_inversion_equals_the_loop(spacing, monkeypatch):
    # issue 24: every lower end at once (in blocks), the same sums to round-off
    rng = np.random.default_rng(1)
    z = np.linspace(0.2e-9, 12e-9, 300) if spacing == "even" else \
        np.sort(rng.uniform(0.2e-9, 12e-9, 300))
    df = -40.0 * np.exp(-z / 1.5e-9) + 3.0 * np.sin(z / 0.7e-9)
    ref = _reference_inversion(z, df, 40.0, 300e3, 5e-9)
    # one block, several, one row each; the weights kept for the grid (computed at the first
    # call, read at the second) or computed at each call
    for kept in (z.size, 0):
        for block in (fm._INVERSION_BLOCK, 7 * z.size, 1):
            monkeypatch.setattr(fm, "_INVERSION_BLOCK", block)
            monkeypatch.setattr(fm, "_WEIGHTS_KEPT_POINTS", kept)
            monkeypatch.setattr(fm, "_weights_kept", {})
            for _ in range(2):
                got = fm.sader_jarvis(z, df, spring_constant=40.0, resonance_frequency=300e3,
                                      amplitude=5e-9)
                np.testing.assert_allclose(got, ref, rtol=1e-10,
                                           atol=1e-12 * np.max(np.abs(ref)))
                assert got[-1] == 0.0
            assert len(fm._weights_kept) == (1 if kept else 0)


def test_the_inversion_keeps_the_weights_of_two_grids_at_most():
    fm._weights_kept.clear()
    for n in (100, 200, 300, 400):
        z = np.linspace(0.2e-9, 12e-9, n)
        fm.sader_jarvis(z, -1e-18 / z ** 2)
    assert len(fm._weights_kept) == 2
    z = np.linspace(0.2e-9, 12e-9, fm._WEIGHTS_KEPT_POINTS + 1)  # too large to keep
    fm.sader_jarvis(z, -1e-18 / z ** 2)
    assert len(fm._weights_kept) == 2
    assert not any(i0.flags.writeable for blocks in fm._weights_kept.values()
                   for _, i0, _ in blocks)
