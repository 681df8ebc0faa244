"""Module (b) against independent sources: sympy derivations, python-control, numerical
integration and textbook limits, each cited where it is used. No number asserted here comes from
the code under test."""
import math

import control
import mpmath
import numpy as np
import pytest
import sympy as sp
from scipy import integrate

from afmsmiler.cantilever import Cantilever
from afmsmiler.materials import get_material
from afmsmiler.transducers import (PRINCIPLES, AstigmaticDetection, Electromagnetic,
                                   Electrostatic, Electrothermal, Interferometer,
                                   OpticalBeamDeflection, Optomechanical, Photothermal,
                                   PiezoAcoustic, Piezoelectric, Piezoresistive, get_principle,
                                   table_one, table_one_html, table_one_markdown)
from afmsmiler.transducers.acoustic import mode_slope_factor, participation_factor
from afmsmiler.transducers.base import (BOLTZMANN, mechanical_response,
                                       thermal_deflection_noise)
from afmsmiler.transducers.embedded import quarter_bridge_output
from afmsmiler.transducers.thermal import THERMAL, bimorph_curvature

# --- Table I, typed from the issue (the source paper's Table I) as the independent source -------
# "optical beam deflection (sensing; DC and AC; bulk), astigmatic detection (sensing; DC and AC;
# bulk), interferometry (sensing; DC and AC; bulk), piezo-acoustic (actuation; AC only; bulk),
# photothermal (actuation; DC and AC; bulk), electromagnetic (actuation; DC and AC; bulk),
# electrostatic (actuation; DC and AC; bulk), optomechanical (sensing; DC and AC; embedded),
# piezoresistive (sensing; DC and AC; embedded), electrothermal (actuation; DC and AC; embedded),
# piezoelectric (both; AC mostly; embedded)."
TABLE_I_TEXT = """\
optical beam deflection (sensing; DC and AC; bulk), astigmatic detection (sensing; DC and AC;
bulk), interferometry (sensing; DC and AC; bulk), piezo-acoustic (actuation; AC only; bulk),
photothermal (actuation; DC and AC; bulk), electromagnetic (actuation; DC and AC; bulk),
electrostatic (actuation; DC and AC; bulk), optomechanical (sensing; DC and AC; embedded),
piezoresistive (sensing; DC and AC; embedded), electrothermal (actuation; DC and AC; embedded),
piezoelectric (both; AC mostly; embedded)"""


def _parse_table_i():
    rows = []
    for item in " ".join(TABLE_I_TEXT.split()).split("), "):
        name, rest = item.rstrip(")").split(" (")
        function, signal, size = (s.strip() for s in rest.split(";"))
        rows.append((name, function, signal.replace("DC and AC", "DC&AC"), size))
    return rows


def test_table_one_matches_the_paper():
    expected = _parse_table_i()
    assert len(expected) == 11
    got = [(r.name, r.function, r.signal, r.size) for r in table_one()]
    assert got == expected
    assert list(PRINCIPLES) == [r.key for r in table_one()]


def test_table_one_is_rendered():
    md, html = table_one_markdown(), table_one_html()
    assert md.count("\n") == 2 + 11
    for name, function, signal, size in _parse_table_i():
        assert f"| {name} | {function} | {signal} | {size} |" in md
        assert f"<td>{name}</td><td>{function}</td>" in html
    assert html.count("<tr>") == 12


def test_book_chapter_shows_the_generated_table():
    from pathlib import Path
    chapter = Path(__file__).parents[1] / "book" / "02_probe_transducers.md"
    assert table_one_markdown() in chapter.read_text(encoding="utf-8")


@pytest.mark.parametrize("key", list(PRINCIPLES))
def test_signal_class_follows_from_the_physics(key):
    """'DC&AC' models respond at DC; 'AC only' never does; 'AC mostly' has a mode that does not."""
    model = get_principle(key)
    dc = {mode: abs(model.frequency_response([0.0], mode).response[0]) for mode in model.MODES}
    ac = {mode: abs(model.frequency_response([model.resonance_frequency / 3], mode).response[0])
          for mode in model.MODES}
    assert all(v > 0 for v in ac.values())
    if model.signal == "DC&AC":
        assert all(v > 0 for v in dc.values())
    elif model.signal == "AC only":
        assert all(v == 0 for v in dc.values())
    else:
        assert any(v == 0 for v in dc.values()) and any(v > 0 for v in dc.values())
    assert set(model.MODES) == ({"sensing", "actuation"} if model.function == "both"
                                else {model.function})


# --- the metadata (nanite-style: every model described by data) ----------------------------------
@pytest.mark.parametrize("key", list(PRINCIPLES))
def test_metadata_is_complete(key):
    cls = PRINCIPLES[key]
    model = cls()
    assert model.key == key and model.name and model.summary
    for name, p in cls.parameter_table().items():
        assert p.name == name and p.low <= p.default <= p.high
        assert getattr(model, name) == p.default
        if p.unit:
            assert p.display_unit, f"{key}.{name} needs a display unit"
        if p.display_unit == p.unit:
            assert p.scale == 1.0, f"{key}.{name}: same unit, so the scale must be 1"
        assert p.scale > 0
    for mode in model.MODES:
        q = model.input_quantity(mode)
        assert q.scale == 1.0 or q.display_unit != q.unit
        chain = model.chain(np.linspace(q.low, q.high, 7), mode)
        assert chain.input.quantity is q and "deflection" in chain.names and "slope" in chain.names
        for stage in chain.stages:
            assert stage.values.shape == (7,) and np.isfinite(stage.values).all()
        assert chain.output.quantity == model.output_quantity(mode)
        assert math.isfinite(model.sensitivity(mode)) and model.sensitivity(mode) != 0
        res = model.resolution(1e3, mode=mode)
        assert res.total > 0 and res.quantity is q and "thermal" in res.contributions


#: What the outputs of the sensors can physically be: a normalised difference lies in [-1, 1], a
#: detected power between 0 and its maximum, a quarter bridge between its rails -V_b/2 and V_b/2
#: (a resistance cannot be negative).
OUTPUT_BOUNDS = {
    "optical_beam_deflection": lambda m: (-1.0, 1.0),
    "astigmatic": lambda m: (-1.0, 1.0),
    "interferometry": lambda m: (0.0, m.power * (1 + m.visibility)),
    "optomechanical": lambda m: (0.0, m.power),
    "piezoresistive": lambda m: (-m.bias_voltage / 2, m.bias_voltage / 2),
}


@pytest.mark.parametrize("key", list(PRINCIPLES))
def test_every_corner_of_the_parameter_space_gives_finite_numbers(key):
    """Parameters at their bounds or anywhere between, in random combinations (a slider user):
    the chain, the sensitivity, the response and the resolution stay finite and never raise, and
    a sensor's output stays physical."""
    cls = PRINCIPLES[key]
    table = cls.parameter_table()
    rng = np.random.default_rng(20261123)
    for _ in range(60):
        values = {}
        for name, p in table.items():
            pick = rng.integers(3)
            if pick < 2:
                values[name] = (p.low, p.high)[pick]
            elif p.log:
                values[name] = math.exp(rng.uniform(math.log(p.low), math.log(p.high)))
            else:
                values[name] = rng.uniform(p.low, p.high)
        for name, (other, factor) in cls.BOUNDED_BY.items():
            values[name] = min(values[name], factor * values[other])
        model = cls(**values)
        for mode in model.MODES:
            q = model.input_quantity(mode)
            chain = model.chain(np.linspace(q.low, q.high, 41), mode)
            for stage in chain.stages:
                assert np.isfinite(stage.values).all(), (values, stage.quantity.name)
            if key in OUTPUT_BOUNDS:
                low, high = OUTPUT_BOUNDS[key](model)
                out = chain.output.values
                assert np.all((out >= low - 1e-12 * abs(low)) & (out <= high + 1e-12 * abs(high)))
            assert math.isfinite(model.sensitivity(mode))
            f = np.geomspace(1e-2, 10 * model.resonance_frequency, 30)
            assert np.isfinite(model.frequency_response(f, mode).response).all()
            assert model.resolution(1e3, mode=mode).total > 0
            model.validity(q.low, mode)


# --- the lever's dynamics and its thermal floor --------------------------------------------------
def test_mechanical_response_is_a_damped_oscillator():
    # python-control: G(s) = w1^2 / (s^2 + (w1/Q) s + w1^2)
    f1, q = 80e3, 150.0
    w1 = 2 * math.pi * f1
    sys = control.tf([w1 ** 2], [1, w1 / q, w1 ** 2])
    f = np.array([0.0, 1e3, 40e3, 79e3, f1, 81e3, 300e3])
    np.testing.assert_allclose(mechanical_response(f, f1, q), sys(2j * math.pi * f), rtol=1e-12)


def test_thermal_floor_integrates_to_equipartition():
    # Equipartition (k <z^2> = k_B T): the one-sided PSD S_z(0) |H(f)|^2 integrated over all f
    # must give k_B T / k; S_z(0) is the floor the model uses (thermal_noise(B)^2 / B).
    model = OpticalBeamDeflection(quality_factor=30.0)
    s0 = model.thermal_noise(1.0) ** 2
    f1, q = model.resonance_frequency, model.quality_factor
    total, _ = integrate.quad(lambda f: s0 * abs(mechanical_response(f, f1, q)) ** 2, 0, np.inf,
                              points=None, limit=500)
    assert total == pytest.approx(BOLTZMANN * model.temperature / model.spring_constant, rel=1e-6)


def test_band_integral_of_the_brownian_spectrum():
    # the closed-form antiderivative differentiates back to |H|^2 (sympy, 30 digits)
    r, q = sp.symbols("r Q", positive=True)
    b = sp.sqrt(4 - 1 / q ** 2)
    x = b * r / (1 + r ** 2)
    antiderivative = (r / (2 * (1 + r ** 2)) * sp.atanh(x) / x
                      + q / 2 * sp.atan2(r, q * (1 - r ** 2)))
    residual = sp.diff(antiderivative, r) - 1 / ((1 - r ** 2) ** 2 + r ** 2 / q ** 2)
    for qv, rv in (("0.51", "0.3"), ("0.7", "2"), ("30", "0.99"), ("10000", "1.0001"),
                   ("150", "7")):
        assert abs(sp.N(residual.subs({q: sp.Rational(qv), r: sp.Rational(rv)}), 30)) < 1e-20
    # the model's band noise against scipy's quadrature of S_0 |H|^2 (python-control's H above)
    for qv in (0.5, 0.7, 30.0, 1e4):
        model = OpticalBeamDeflection(quality_factor=qv)
        f1 = model.resonance_frequency
        s0 = 4 * BOLTZMANN * model.temperature / (model.spring_constant * 2 * math.pi * f1 * qv)
        w1 = 2 * math.pi * f1
        sys = control.tf([w1 ** 2], [1, w1 / qv, w1 ** 2])
        for lo, hi in ((1.0, 1e3), (0.5 * f1, 1.5 * f1), (0.0, 3 * f1), (2 * f1, 20 * f1)):
            ref, _ = integrate.quad(lambda f: s0 * abs(sys(2j * math.pi * f)) ** 2, lo, hi,
                                    points=[p for p in (f1,) if lo < p < hi], limit=2000,
                                    epsabs=0, epsrel=1e-11)
            assert model.thermal_noise(hi - lo, lo) == pytest.approx(math.sqrt(ref), rel=1e-8)
            np.testing.assert_allclose(model.thermal_noise_density([lo, hi]),
                                       [s0 * abs(sys(2j * math.pi * f)) ** 2 for f in (lo, hi)],
                                       rtol=1e-12)
    # all frequencies: equipartition, k <z^2> = k_B T with k = E w h^3 / (4 L^3)
    model = OpticalBeamDeflection(quality_factor=150.0)
    k = 169e9 * model.width * model.thickness ** 3 / (4 * model.length ** 3)
    assert model.thermal_noise(1e6 * model.resonance_frequency, 0.0) == pytest.approx(
        math.sqrt(BOLTZMANN * model.temperature / k), rel=1e-6)
    # a sensor's resolution counts the band's motion, resonance included; a drive, the white floor
    wide = model.resolution(2 * model.resonance_frequency)
    assert wide.contributions["thermal"] == pytest.approx(
        model.thermal_noise(2 * model.resonance_frequency, 1.0), rel=1e-12)
    assert wide.contributions["thermal"] > 10 * model.thermal_noise(2 * model.resonance_frequency)
    drive = Electromagnetic(quality_factor=150.0).resolution(2 * model.resonance_frequency)
    assert drive.contributions["thermal"] == pytest.approx(
        model.thermal_noise(2 * model.resonance_frequency) / Electromagnetic().sensitivity(),
        rel=1e-12)
    with pytest.raises(ValueError, match="^quality_factor must be in"):
        thermal_deflection_noise(model.lever, 0.3, 300.0, 1e3, 0.0)
    with pytest.raises(ValueError, match="^low_frequency must be in"):
        model.thermal_noise(1e3, -1.0)


# --- optical beam deflection ---------------------------------------------------------------------
def test_free_end_slope_is_three_halves_z_over_l():
    model = OpticalBeamDeflection()
    lever = model.lever
    force = 1e-8
    z = float(lever.deflection(lever.length, force))
    assert float(lever.slope(lever.length, force)) == pytest.approx(1.5 * z / lever.length,
                                                                    rel=1e-13)
    chain = model.chain([z])
    assert chain.stage("slope").values[0] == pytest.approx(float(lever.slope(lever.length, force)),
                                                           rel=1e-13)


def test_optical_lever_angle_to_spot_factor_is_twice_the_path():
    # reflection doubles the angle: spot travel / tilt -> 2 D as the tilt -> 0 (law of reflection)
    model = OpticalBeamDeflection(optical_path=25e-3)
    for theta in (1e-7, 1e-6, 1e-5):
        assert model.spot_displacement(theta) / theta == pytest.approx(2 * 25e-3, rel=1e-9)


def test_split_detector_signal_against_numerical_integration():
    # the fraction of a Gaussian spot (1/e^2 radius w) on each half of a split photodiode,
    # integrated numerically over the half planes
    model = OpticalBeamDeflection(spot_radius=0.4e-3)
    w = model.spot_radius
    for s in (0.0, 0.05e-3, 0.2e-3, -0.3e-3, 0.6e-3):
        def intensity(u):  # u = y / w; the x integral cancels in the ratio
            return np.exp(-2 * (u - s / w) ** 2)
        upper, _ = integrate.quad(intensity, 0, np.inf)
        lower, _ = integrate.quad(intensity, -np.inf, 0)
        assert float(model.split_signal(s)) == pytest.approx((upper - lower) / (upper + lower),
                                                             abs=1e-10)


def test_optical_lever_sensitivity_against_sympy():
    z, L, D, w = sp.symbols("z L D w", positive=True)
    theta = sp.Rational(3, 2) * z / L            # end-loaded lever
    s = D * sp.tan(2 * theta)                    # reflected beam turned by 2 theta
    signal = sp.erf(sp.sqrt(2) * s / w)          # Gaussian spot on a split detector
    slope = sp.diff(signal, z)
    assert sp.simplify(slope.subs(z, 0) - sp.sqrt(8 / sp.pi) * 3 * D / (w * L)) == 0
    model = OpticalBeamDeflection(optical_path=40e-3, spot_radius=0.3e-3, length=150e-6)
    subs = {L: model.length, D: model.optical_path, w: model.spot_radius}
    for at in (0.0, 50e-9, -300e-9, 1e-6):
        ref = float(slope.subs(subs).subs(z, at))
        assert model.sensitivity(at=at) == pytest.approx(ref, rel=1e-12)
    # and the chain's output is the same function
    zs = np.array([-1e-6, 2e-7, 1.5e-6])
    ref = [float(signal.subs(subs).subs(z, v)) for v in zs]
    np.testing.assert_allclose(model.respond(zs), ref, rtol=1e-12)


def test_optical_lever_sensitivity_scales_as_path_over_length():
    base = OpticalBeamDeflection()
    assert base.replace(length=base.length / 2).sensitivity() == pytest.approx(
        2 * base.sensitivity(), rel=1e-12)
    assert base.replace(optical_path=3 * base.optical_path).sensitivity() == pytest.approx(
        3 * base.sensitivity(), rel=1e-12)


def test_optical_lever_shot_noise():
    # Schottky: i_n = sqrt(2 q I B); normalised by I it is sqrt(2 q B / I)
    model = OpticalBeamDeflection(power=1e-3, responsivity=0.5)
    res = model.resolution(1e4)
    current = 0.5e-3
    slope = math.sqrt(8 / math.pi) * 3 * model.optical_path / (model.spot_radius * model.length)
    expected = math.sqrt(2 * 1.602176634e-19 * current * 1e4) / current / slope
    assert res.contributions["shot"] == pytest.approx(expected, rel=1e-12)
    assert res.total == pytest.approx(math.hypot(expected, res.contributions["thermal"]), rel=1e-12)


def test_astigmatic_and_interferometer_shot_noise():
    # the displacement whose signal equals the photocurrent's shot noise sqrt(2 q I B) (Schottky)
    q_e, bw = 1.602176634e-19, 1e3
    ast = AstigmaticDetection(power=200e-6, responsivity=0.5)
    a, zr = ast.astigmatic_distance / 2, math.pi * ast.waist ** 2 / ast.wavelength
    slope = 8 * a / (math.pi * (zr ** 2 + a ** 2))      # FES slope at focus (sympy test above)
    expected = math.sqrt(2 * q_e * 0.5 * 200e-6 * bw) / (0.5 * 200e-6) / slope
    assert ast.resolution(bw).contributions["shot"] == pytest.approx(expected, rel=1e-12)
    # interferometer at quadrature: delta_d = lambda / (4 pi V) sqrt(2 q B / (R P0))
    # (Rugar, Mamin and Guethner, Appl. Phys. Lett. 55, 2588 (1989))
    ifm = Interferometer(wavelength=1310e-9, visibility=0.8, power=100e-6, responsivity=0.9)
    expected = 1310e-9 / (4 * math.pi * 0.8) * math.sqrt(2 * q_e * bw / (0.9 * 100e-6))
    assert ifm.resolution(bw).contributions["shot"] == pytest.approx(expected, rel=1e-12)
    # off quadrature (phi = 0): the mean power P0 (1 + V) and the slope vanishes
    assert ifm.replace(phase=0.0).resolution(bw).contributions["shot"] > 1e6 * expected


def test_optomechanical_shot_noise():
    # at Delta_0 = -gamma/2 the transmission is P (1 - D/2) and the slope D P G / gamma
    q_e, bw = 1.602176634e-19, 1e3
    model = Optomechanical(power=50e-6, dip_depth=0.6, coupling=2e18, responsivity=0.8)
    gamma = 299792458.0 / (model.wavelength * model.optical_q)
    current = 0.8 * 50e-6 * (1 - 0.6 / 2)
    expected = math.sqrt(2 * q_e * current * bw) / 0.8 / (0.6 * 50e-6 * 2e18 / gamma)
    assert model.resolution(bw).contributions["shot"] == pytest.approx(expected, rel=1e-12)


# --- astigmatic detection ------------------------------------------------------------------------
def _fes_by_integration(wx, wy):
    """((A+C)-(B+D))/sum for an elliptical Gaussian on quadrants split along the diagonals."""
    def density(phi):  # angular density of an elliptical Gaussian (integrated over radius)
        return 1.0 / ((math.cos(phi) / wx) ** 2 + (math.sin(phi) / wy) ** 2)
    total, _ = integrate.quad(density, 0, 2 * math.pi, limit=200)
    # |x| > |y| sectors: phi in (-pi/4, pi/4) and (3pi/4, 5pi/4)
    ac, _ = integrate.quad(density, -math.pi / 4, math.pi / 4, limit=200)
    ac *= 2
    return (2 * ac - total) / total


def test_astigmatic_fes_against_integration_over_quadrants():
    model = AstigmaticDetection()
    for d in (0.0, 0.3e-6, -0.7e-6, 1.5e-6, 6e-6):
        wx, wy = model.spot_radii(d)
        # the model names A + C the pair along the y axis of the spot, hence the sign
        assert float(model.focus_error(d)) == pytest.approx(-_fes_by_integration(wx, wy),
                                                            abs=1e-9)


def test_astigmatic_s_curve_and_slope_against_sympy():
    d, a, zr = sp.symbols("d a z_R", positive=True)
    wx = sp.sqrt(1 + ((2 * d - a) / zr) ** 2)
    wy = sp.sqrt(1 + ((2 * d + a) / zr) ** 2)
    fes = 4 / sp.pi * sp.atan(wy / wx) - 1
    slope0 = sp.simplify(sp.diff(fes, d).subs(d, 0))
    assert sp.simplify(slope0 - 8 * a / (sp.pi * (zr ** 2 + a ** 2))) == 0
    # the largest slope at focus is at a = z_R: 4 / (pi z_R)
    best = sp.solve(sp.diff(slope0, a), a)
    assert best == [zr] and sp.simplify(slope0.subs(a, zr) - 4 / (sp.pi * zr)) == 0
    model = AstigmaticDetection()
    subs = {a: model.astigmatic_distance / 2, zr: math.pi * model.waist ** 2 / model.wavelength}
    dslope = sp.lambdify(d, sp.diff(fes, d).subs(subs))
    for at in (0.0, 0.4e-6, -1.1e-6):
        assert model.sensitivity(at=at) == pytest.approx(float(dslope(at)), rel=1e-10)
    # an S-curve: odd, zero in focus, back towards zero far away, linear range of a few um
    z = np.linspace(-10e-6, 10e-6, 2001)
    f = model.focus_error(z)
    np.testing.assert_allclose(f, -f[::-1], atol=1e-12)
    assert abs(float(model.focus_error(0.0))) < 1e-15
    assert np.all(np.diff(f[np.argmax(f):]) < 0)
    assert float(model.focus_error(200e-6)) < 0.05 * f.max()
    # the extrema: d(w_y / w_x)^2 / dd = 0 at 2 d = sqrt(a^2 + z_R^2) (sympy), a few um here
    ratio2 = ((1 + ((2 * d + a) / zr) ** 2) / (1 + ((2 * d - a) / zr) ** 2))
    (extremum,) = sp.solve(sp.numer(sp.together(sp.diff(ratio2, d))), d)
    assert sp.simplify(extremum - sp.sqrt(a ** 2 + zr ** 2) / 2) == 0
    peak = float(extremum.subs(subs))
    assert 0.5e-6 < peak < 5e-6
    assert model.sensitivity(at=peak) == pytest.approx(0.0, abs=1e-9 * model.sensitivity())
    assert z[np.argmax(f)] == pytest.approx(peak, abs=z[1] - z[0])


# --- interferometry ------------------------------------------------------------------------------
def test_interferometer_quadrature_slope_and_nonlinearity():
    model = Interferometer(wavelength=633e-9, visibility=0.9, power=200e-6)
    # textbook: dP/dd at quadrature = 4 pi V P0 / lambda (Rugar et al. 1989)
    assert model.sensitivity() == pytest.approx(4 * math.pi * 0.9 * 200e-6 / 633e-9, rel=1e-12)
    h = 1e-12
    numerical = (model.fringe(h) - model.fringe(-h)) / (2 * h)
    assert model.sensitivity() == pytest.approx(float(numerical), rel=1e-6)
    # a quarter wavelength of travel further (phase + pi) the slope reverses; lambda/8 -> 0
    assert model.sensitivity(at=633e-9 / 4) == pytest.approx(-model.sensitivity(), rel=1e-9)
    assert abs(model.sensitivity(at=633e-9 / 8)) < 1e-9 * model.sensitivity()
    # the fringe repeats every lambda / 2 of displacement
    np.testing.assert_allclose(model.fringe(0.1e-6 + 633e-9 / 2), model.fringe(0.1e-6), rtol=1e-12)
    # off quadrature (phi = 0) the small-signal slope vanishes: the nonlinearity
    assert abs(model.replace(phase=0.0).sensitivity()) < 1e-20


# --- piezo-acoustic base excitation --------------------------------------------------------------
def _mode_by_mpmath(n):
    """Mode n of a clamped-free beam on [0, 1] in 30-digit arithmetic, independent of module (a):
    b from cos(b) cosh(b) = -1 by mpmath.findroot, phi = cosh bx - cos bx - s (sinh bx - sin bx)
    with s = (cosh b + cos b) / (sinh b + sin b) (Rao, Mechanical Vibrations, sec. 8.5)."""
    b = mpmath.findroot(lambda x: mpmath.cos(x) * mpmath.cosh(x) + 1, (n - 0.5) * mpmath.pi)
    s = (mpmath.cosh(b) + mpmath.cos(b)) / (mpmath.sinh(b) + mpmath.sin(b))
    return b, (lambda x: mpmath.cosh(b * x) - mpmath.cos(b * x)
               - s * (mpmath.sinh(b * x) - mpmath.sin(b * x)))


def _gamma_by_mpmath(n):
    """gamma_n = phi(1) int phi / int phi^2 (the mode normalised to 1 at the tip), by quadrature."""
    with mpmath.workdps(30):
        _, phi = _mode_by_mpmath(n)
        return float(phi(1) * mpmath.quad(phi, [0, 1]) / mpmath.quad(lambda x: phi(x) ** 2, [0, 1]))


def test_participation_factor_against_the_modal_integral():
    # Erturk and Inman, J. Intell. Mater. Syst. Struct. 19, 1311 (2008): mu_1 = 1.566 (relative
    # transverse motion at the tip, mode 1, no tip mass); then the modal integral to round-off
    assert participation_factor() == pytest.approx(1.566, abs=5e-4)
    assert participation_factor(1) == pytest.approx(_gamma_by_mpmath(1), rel=1e-13)
    assert participation_factor(2) == pytest.approx(_gamma_by_mpmath(2), rel=1e-13)
    # closed form of the same integrals: int phi = 2 s / b, int phi^2 = 1, phi(1) = 2 (mode 1)
    with mpmath.workdps(30):
        b, phi = _mode_by_mpmath(1)
        s = (mpmath.cosh(b) + mpmath.cos(b)) / (mpmath.sinh(b) + mpmath.sin(b))
        assert participation_factor() == pytest.approx(float(4 * s / b), rel=1e-13)
    with pytest.raises(ValueError, match="^mode must be an integer"):
        participation_factor(0)


def test_mode_slope_factor_against_the_analytic_mode_shape():
    # L phi'(L) / phi(L) by mpmath's numerical derivative of the independently built mode shape
    with mpmath.workdps(30):
        _, phi = _mode_by_mpmath(1)
        ref = float(mpmath.diff(phi, 1) / phi(1))
    assert mode_slope_factor() == pytest.approx(ref, rel=1e-14)
    assert 1.37 < mode_slope_factor() < 1.5    # flatter at the end than the static shape (1.5)


def test_base_excitation_against_python_control():
    model = PiezoAcoustic(quality_factor=80.0, shaker_coefficient=1e-9)
    w1 = 2 * math.pi * model.resonance_frequency
    gamma = _gamma_by_mpmath(1)
    # relative motion u = x - y, projected on mode 1: u'' + (w1/Q) u' + w1^2 u = -gamma y''
    # -> U/Y = -gamma s^2 / (s^2 + w1/Q s + w1^2) (Rao, Mechanical Vibrations, base excitation)
    sys = control.tf([-gamma, 0, 0], [1, w1 / 80.0, w1 ** 2])
    f = np.array([10.0, 1e3, 0.5, 0.9, 1.0, 1.1, 3.0])
    f[2:] *= model.resonance_frequency
    np.testing.assert_allclose(model.base_transfer(f), sys(2j * math.pi * f), rtol=1e-12)
    fr = model.frequency_response(f)
    np.testing.assert_allclose(fr.response, 1e-9 * model.base_transfer(f), rtol=1e-12)
    # resonance gain gamma Q at -90 degrees, DC gain 0 (AC only), high-frequency gain -gamma
    h1 = model.base_transfer(model.resonance_frequency)
    assert h1 == pytest.approx(-1j * gamma * 80, rel=1e-12)
    assert model.base_transfer(0.0) == 0
    r = 1e4
    assert model.base_transfer(r * model.resonance_frequency) == pytest.approx(
        -gamma * r * r / (r * r - 1 - 1j * r / 80), rel=1e-12)
    # the sensitivity at the drive frequency, d |U/Y| (half the resonance here)
    r = 0.5
    assert model.replace(drive_ratio=r).sensitivity() == pytest.approx(
        1e-9 * gamma * r * r / abs(1 - r * r + 1j * r / 80.0), rel=1e-12)
    # the chain at the drive frequency: amplitude = d V |U/Y|; the slope follows the mode shape
    chain = model.replace(drive_ratio=1.0).chain([2.0])
    assert chain.output.values[0] == pytest.approx(2.0 * 1e-9 * gamma * 80, rel=1e-12)
    assert chain.stage("base_amplitude").values[0] == pytest.approx(2e-9, rel=1e-15)
    assert chain.stage("slope").values[0] == pytest.approx(
        mode_slope_factor() * chain.output.values[0] / model.length, rel=1e-15)


def test_base_excitation_says_when_mode_2_matters():
    # two modes, each u_n / Y = gamma_n r_n^2 / (1 - r_n^2 + j r_n / Q), r_n = f / f_n, and
    # f2 / f1 = (b2 / b1)^2 = 6.267 (Rao, Mechanical Vibrations, Table 8.4)
    with mpmath.workdps(30):
        ratio = float((_mode_by_mpmath(2)[0] / _mode_by_mpmath(1)[0]) ** 2)
    g1, g2, q = _gamma_by_mpmath(1), _gamma_by_mpmath(2), 150.0
    for r in (0.5, 1.0, 2.0, 3.0):
        model = PiezoAcoustic(drive_ratio=r, quality_factor=q)
        r2 = r / ratio
        share = abs(g2 * r2 ** 2 / (1 - r2 ** 2 + 1j * r2 / q)) / abs(
            g1 * r ** 2 / (1 - r ** 2 + 1j * r / q))
        assert model.mode_2_share() == pytest.approx(share, rel=1e-9)
        assert bool(model.validity(0.1)) == (share > 0.05)
    assert PiezoAcoustic(drive_ratio=1.0).validity(1.0) == ()
    assert "second mode" in PiezoAcoustic(drive_ratio=3.0).validity(1.0)[0]


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


def _fourier_coefficients(expr, th):
    """DC, cos(theta) and cos(2 theta) amplitudes of a 2 pi-periodic expression (sympy)."""
    dc = sp.integrate(expr, (th, 0, 2 * sp.pi)) / (2 * sp.pi)
    first = sp.integrate(expr * sp.cos(th), (th, 0, 2 * sp.pi)) / sp.pi
    second = sp.integrate(expr * sp.cos(2 * th), (th, 0, 2 * sp.pi)) / sp.pi
    return sp.simplify(dc), sp.simplify(first), sp.simplify(second)


def test_electrothermal_power_harmonics_against_sympy_and_fft():
    th, vdc, vac, r = sp.symbols("theta V_dc V_ac R", positive=True)
    dc, first, second = _fourier_coefficients((vdc + vac * sp.cos(th)) ** 2 / r, th)
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


# --- electrostatic -------------------------------------------------------------------------------
def test_electrostatic_harmonics_against_sympy():
    th, vdc, vac, dc_dz = sp.symbols("theta V_dc V_ac Cprime", real=True)
    dc, first, second = _fourier_coefficients(dc_dz / 2 * (vdc + vac * sp.cos(th)) ** 2, th)
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


def test_models_say_where_their_assumptions_fail():
    assert Electrostatic().validity(5.0) == ()
    (note,) = Electrostatic(gap=0.5e-6).validity(20.0)
    assert "pull-in" in note
    assert Electrothermal().validity(1.0) == ()
    # 5 V on 100 ohm is 250 mW: P L / (2 G) is far beyond 300 K
    assert "K above ambient" in Electrothermal(resistance=100.0).validity(5.0)[0]
    assert OpticalBeamDeflection().validity(1e-6) == ()
    with pytest.raises(ValueError, match="^dc_voltage must be in"):
        Electrostatic().validity(100.0)


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
    mech = np.abs(mechanical_response(f, model.resonance_frequency, model.quality_factor))
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


# --- bad input -----------------------------------------------------------------------------------
CASES = [(key, name, p) for key, cls in PRINCIPLES.items()
         for name, p in cls.parameter_table().items()]


@pytest.mark.parametrize("key, name, p", CASES, ids=[f"{c[0]}-{c[1]}" for c in CASES])
def test_out_of_range_parameter_names_itself(key, name, p):
    bad = [math.nan, math.inf]
    bad.append(p.high * 2 + 1 if math.isfinite(p.high) else -math.inf)
    bad.append(p.low - abs(p.low) - 1 if math.isfinite(p.low) else math.nan)
    for value in bad:
        with pytest.raises(ValueError, match=rf"^{name} must be"):
            get_principle(key, **{name: value})


@pytest.mark.parametrize("key", list(PRINCIPLES))
def test_bad_calls_raise(key):
    model = get_principle(key)
    with pytest.raises(TypeError, match="unknown parameter"):
        get_principle(key, colour=1.0)
    q = model.input_quantity()
    with pytest.raises(ValueError, match=rf"^{q.name} must be in"):
        model.chain([0.0, q.high * 2 + 1])
    with pytest.raises(ValueError, match=rf"^{q.name} must be in"):
        model.sensitivity(at=q.low - abs(q.low) - 1)
    with pytest.raises(ValueError, match="^mode must be one of"):
        model.chain(0.0, mode="telepathy")
    with pytest.raises(ValueError, match="^bandwidth must be > 0 Hz"):
        model.resolution(0.0)
    with pytest.raises(ValueError, match="^low_frequency must be > 0 Hz"):
        model.resolution(1.0, low_frequency=-1.0)
    with pytest.raises(ValueError, match="^f must be in"):
        model.frequency_response([1.0, -1.0])


HELPER_CASES = [
    # (call, argument name in the message)
    (lambda v: OpticalBeamDeflection().spot_displacement(v), "slope",
     (math.nan, 0.8, -math.pi / 4)),
    (lambda v: OpticalBeamDeflection().split_signal(v), "spot", (math.nan, math.inf)),
    (lambda v: AstigmaticDetection().spot_radii(v), "d", (math.nan, -math.inf)),
    (lambda v: AstigmaticDetection().focus_error([0.0, v]), "d", (math.nan, math.inf)),
    (lambda v: Interferometer().fringe(v), "d", (math.nan, math.inf)),
    (lambda v: Optomechanical().transmission(v), "x", (math.nan, math.inf)),
    (lambda v: Electromagnetic().lorentz_force(v), "current", (math.nan, math.inf)),
    (lambda v: Photothermal().temperature_profile(v, 1e-3), "x", (math.nan, -1e-6, 1.0)),
    (lambda v: Photothermal().temperature_profile(0.0, v), "power", (math.nan, -1e-3)),
    (lambda v: Electrothermal().thermal_lag(v), "f", (math.nan, -1.0)),
    (lambda v: quarter_bridge_output(v, 0.01), "bias_voltage", (math.nan, math.inf)),
    (lambda v: quarter_bridge_output(1.0, v), "relative_change", (math.nan, -1.5)),
    (lambda v: bimorph_curvature(2.6e-6, v, 169e9, 14e-6, 5e-8, 79e9), "thickness_1",
     (math.nan, 0.0, -1e-6)),
    (lambda v: bimorph_curvature(2.6e-6, 3e-6, 169e9, 14e-6, 5e-8, v), "modulus_2",
     (math.inf, 0.0)),
    (lambda v: bimorph_curvature(v, 3e-6, 169e9, 14e-6, 5e-8, 79e9), "expansion_1",
     (math.nan, math.inf)),
    (lambda v: mechanical_response(v, 1e5, 100.0), "f", (math.nan, -1.0)),
    (lambda v: mechanical_response(1e3, v, 100.0), "resonance_frequency", (0.0, math.inf)),
    (lambda v: mechanical_response(1e3, 1e5, v), "quality_factor", (-1.0, math.nan)),
    (lambda v: thermal_deflection_noise(OpticalBeamDeflection().lever, 100.0, 300.0, v),
     "bandwidth", (0.0, math.inf)),
    (lambda v: thermal_deflection_noise(OpticalBeamDeflection().lever, v, 300.0, 1.0),
     "quality_factor", (0.0, math.nan)),
    (lambda v: thermal_deflection_noise(OpticalBeamDeflection().lever, 100.0, v, 1.0),
     "temperature", (-1.0, math.nan)),
    (lambda v: thermal_deflection_noise(v, 100.0, 300.0, 1.0), "lever", (1.0, None)),
    (lambda v: OpticalBeamDeflection().upper_bound(v), "name", ("colour", "")),
    (lambda v: participation_factor(v), "mode", (0, 1.5)),
]


@pytest.mark.parametrize("call, name, values", HELPER_CASES,
                         ids=[f"{i}-{c[1]}" for i, c in enumerate(HELPER_CASES)])
def test_public_helpers_reject_bad_input(call, name, values):
    for value in values:
        with pytest.raises(ValueError, match=rf"^{name} must be"):
            call(value)


def test_cross_parameter_checks():
    with pytest.raises(ValueError, match=r"^electrode_length must be in \(0, 0.0001\] m"):
        Electrostatic(length=100e-6, electrode_length=150e-6)
    with pytest.raises(ValueError, match="^electrode_length must be in"):
        Piezoelectric(length=100e-6, electrode_length=150e-6)
    with pytest.raises(ValueError, match="^resistor_length must be in"):
        Piezoresistive(length=100e-6, resistor_length=200e-6)
    with pytest.raises(ValueError, match="^junction_depth must be in"):
        Piezoresistive(thickness=1e-6, junction_depth=0.8e-6)
    assert Piezoresistive(thickness=1e-6).upper_bound("junction_depth") == pytest.approx(0.5e-6)
    assert Electrostatic(length=100e-6).upper_bound("electrode_length") == pytest.approx(100e-6)
    assert Electrostatic().upper_bound("gap") == Electrostatic.parameter_table()["gap"].high
    with pytest.raises(ValueError, match="^key must be one of"):
        get_principle("telekinesis")
    with pytest.raises(ValueError, match="^frequency must be >= 0 Hz"):
        Electrothermal().deflection_components(1.0, -5.0)
    with pytest.raises(ValueError, match="^dc_voltage must be in"):
        Electrostatic().force_components(500.0)


def test_models_are_values():
    a, b = OpticalBeamDeflection(), OpticalBeamDeflection()
    assert a == b and a.replace(optical_path=0.05) != a
    assert a.replace(optical_path=0.05).optical_path == 0.05 and a.optical_path == 30e-3
    assert "optical_path=0.03" in repr(a)
    assert isinstance(a.lever, Cantilever)
    with pytest.raises(AttributeError):
        a.no_such_thing  # noqa: B018
