"""Module (b)'s common machinery: Table I (typed from the source paper) generated from the models,
the parameter metadata, the whole parameter space, the model run a panel draws from, and bad input
named by parameter."""
import math

import ipywidgets as widgets
import mpmath
import numpy as np
import pytest

from afmsmiler.cantilever import Cantilever
from afmsmiler.parameters import UNITS, Parameter
from afmsmiler.transducers import (PRINCIPLES, AstigmaticDetection, Electromagnetic,
                                   Electrostatic, Electrothermal, Interferometer,
                                   OpticalBeamDeflection, Optomechanical, Photothermal,
                                   PiezoAcoustic, Piezoelectric, Piezoresistive, get_principle,
                                   table_one, table_one_html, table_one_markdown)
from afmsmiler.transducers.acoustic import participation_factor
from afmsmiler.transducers.base import Transducer
from afmsmiler.transducers.embedded import quarter_bridge_output
from afmsmiler.transducers.thermal import bimorph_curvature
from afmsmiler.ui.controls import control


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
    # beyond the pickup's 1 mm working distance, before: radii inf and FES NaN at d = 1e300
    (lambda v: AstigmaticDetection().spot_radii(v), "d", (math.nan, -math.inf, 1.1e-3, -1e300)),
    (lambda v: AstigmaticDetection().focus_error([0.0, v]), "d", (math.nan, math.inf, 1e300)),
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
    # mechanical_response and thermal_deflection_noise: tests/test_brownian_model.py
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


# --- one parameter vocabulary ---------------------------------------------------------------------
def _all_quantities():
    """Every Parameter a transducer model declares: parameters, inputs, outputs, sensitivities,
    stage quantities (found by running each chain) and the frequency response's input."""
    for key, cls in PRINCIPLES.items():
        model = cls()
        yield from ((key, p) for p in cls.parameter_table().values())
        for mode in cls.MODES:
            yield key, model.input_quantity(mode)
            yield key, model.output_quantity(mode)
            yield key, model.sensitivity_quantity(mode)
            yield from ((key, st.quantity) for st in model.chain([0.0 if model.input_quantity(
                mode).low <= 0.0 else model.input_quantity(mode).low], mode).stages)
            fr = model.frequency_response([1.0], mode)
            yield key, fr.input
            yield key, fr.output


def test_every_quantity_is_a_house_parameter_with_one_unit_per_name():
    # one class for every quantity (afmsmiler.parameters.Parameter, keyword-only, the display
    # scale derived from the unit table) and one SI unit per name across module (b)
    units = {}
    for key, q in _all_quantities():
        assert isinstance(q, Parameter), (key, q)
        assert q.scale == pytest.approx(1.0 / UNITS[q.display_unit][1], rel=1e-15)
        assert UNITS[q.display_unit][0] == q.unit, (key, q.name)
        units.setdefault(q.name, set()).add(q.unit)
    clashes = {n: u for n, u in units.items() if len(u) > 1}
    assert not clashes
    with pytest.raises(TypeError):
        Parameter("length", "m", "um", 225e-6)  # positional fields are gone


def test_display_scales_against_a_spelled_out_table():
    # the scales the models had typed by hand (display value per SI value), now derived
    expected = {("1/m", "1/um"): 1e-6, ("V/m", "uV/nm"): 1e-3, ("W/m", "uW/nm"): 1e-3,
                ("C/m", "fC/nm"): 1e6, ("m/A", "nm/mA"): 1e6, ("m/W", "nm/mW"): 1e6,
                ("m/V", "nm/V"): 1e9, ("", "ppm"): 1e6, ("C", "fC"): 1e15, ("N m", "nN m"): 1e9,
                ("Hz", "GHz"): 1e-9, ("1/Pa", "1e-11/Pa"): 1e11, ("1/m^3", "1/cm^3"): 1e-6,
                ("Hz/m", "GHz/nm"): 1e-18, ("V", "uV"): 1e6}
    seen = set()
    for _, q in _all_quantities():
        if (q.unit, q.display_unit) in expected:
            assert q.scale == pytest.approx(expected[q.unit, q.display_unit], rel=1e-12)
            seen.add((q.unit, q.display_unit))
    assert seen == set(expected)


def _browser_snap(c):
    """The value the browser sends back after drawing slider ``c`` (snapped to its grid)."""
    if isinstance(c, widgets.FloatLogSlider):
        e = math.log10(c.value)
        return 10 ** (c.min + round((e - c.min) / c.step) * c.step)
    return c.min + round((c.value - c.min) / c.step) * c.step


@pytest.mark.parametrize("key", list(PRINCIPLES))
def test_slider_grid_holds_every_default_exactly(key):
    # the browser snapped 225 um to 225.8 um, Q 150 to 158.1 and T 295 K to 294.5 K: every
    # slider of every principle (built with ui.controls.control) has its default on its grid
    cls = PRINCIPLES[key]
    model = cls()
    qs = [(p, model.upper_bound(n) if n in cls.BOUNDED_BY else None)
          for n, p in cls.parameter_table().items()]
    qs += [(model.input_quantity(m), None) for m in cls.MODES]
    for p, high in qs:
        c = control(p, high=high)
        assert c.value == pytest.approx(p.to_display(p.default), rel=1e-12)
        assert _browser_snap(c) == pytest.approx(p.to_display(p.default), rel=1e-9, abs=1e-12), \
            p.name
    lever = {p.name: control(p) for p in cls.parameter_table().values()
             if p.name in ("length", "quality_factor", "temperature")}
    assert _browser_snap(lever["length"]) == pytest.approx(225.0, rel=1e-12)
    assert _browser_snap(lever["quality_factor"]) == pytest.approx(150.0, rel=1e-9)
    assert _browser_snap(lever["temperature"]) == pytest.approx(295.0, rel=1e-12)


# --- the model run a panel draws from -------------------------------------------------------------
@pytest.mark.parametrize("key", list(PRINCIPLES))
def test_operate_runs_the_chain_once_and_agrees_with_the_chain(key, monkeypatch):
    model = get_principle(key)
    for mode in model.MODES:
        q = model.input_quantity(mode)
        value = q.default
        calls = []
        original = Transducer.chain

        def counting(self, *args, **kwargs):
            calls.append(args)
            return original(self, *args, **kwargs)

        monkeypatch.setattr(Transducer, "chain", counting)
        f = np.geomspace(1.0, 1e6, 7)
        op = model.operate(value, mode, frequencies=f, bandwidth=1e3, n_points=11)
        monkeypatch.setattr(Transducer, "chain", original)
        assert len(calls) == 1
        sweep = model.chain(np.linspace(q.low, q.high, 11), mode)
        here = model.chain(np.array([value]), mode)
        for a, b in zip(op.sweep.stages, sweep.stages):
            np.testing.assert_allclose(a.values, b.values, rtol=1e-14, atol=0)
        for a, b in zip(op.point.stages, here.stages):
            np.testing.assert_allclose(a.values, b.values, rtol=1e-14, atol=0)
        assert op.sensitivity == model.sensitivity(mode, at=value)
        np.testing.assert_allclose(op.response.response,
                                   model.frequency_response(f, mode).response, rtol=1e-14)
        assert op.resolution.total == model.resolution(1e3, mode=mode).total
        assert op.validity == model.validity(value, mode)
    q = model.input_quantity()
    with pytest.raises(ValueError, match=f"^{q.name} must be in"):
        model.operate(q.high * 2 + 1)
    with pytest.raises(ValueError, match="^n_points must be"):
        model.operate(q.default, n_points=1)
    with pytest.raises(ValueError, match="^frequencies must be"):
        model.operate(q.default, frequencies=[1.0, math.nan])
    with pytest.raises(ValueError, match="^mode must be one of"):
        model.operate(q.default, mode="telepathy")


def test_the_model_says_how_its_lever_bends():
    # the scene draws this instead of branching on a principle's key: an end load everywhere
    # (3 u^2 - u^3) / 2, the first mode shape for the piezo shaker (base excitation), from the
    # analytic clamped-free mode with b_1 L from mpmath
    u = np.linspace(0.0, 1.0, 21)
    for key in PRINCIPLES:
        if key == "piezo_acoustic":
            continue
        shape, slope, curvature = get_principle(key).deflection_shape(u)
        np.testing.assert_allclose(shape, (3 * u ** 2 - u ** 3) / 2, rtol=1e-14)
        np.testing.assert_allclose(slope, 3 * u - 1.5 * u ** 2, rtol=1e-14)
        np.testing.assert_allclose(curvature, 3 * (1 - u), rtol=1e-14)
    mpmath.mp.dps = 30
    b = float(mpmath.findroot(lambda x: mpmath.cos(x) + 1 / mpmath.cosh(x), 1.875))
    s = (math.cosh(b) + math.cos(b)) / (math.sinh(b) + math.sin(b))

    def phi(x):
        return np.cosh(b * x) - np.cos(b * x) - s * (np.sinh(b * x) - np.sin(b * x))

    shape, _, _ = PiezoAcoustic().deflection_shape(u)
    np.testing.assert_allclose(shape, phi(u) / phi(1.0), rtol=1e-9, atol=1e-12)
    with pytest.raises(ValueError, match="^u must be in"):
        PiezoAcoustic().deflection_shape([1.5])


@pytest.mark.parametrize("name", [np.ones((3, 3)), np.array([]), 3.0, None])
def test_chain_stage_name_must_be_a_str(name):
    # before: numpy's "truth value of an array is ambiguous" for an array, naming nothing
    chain = OpticalBeamDeflection().chain([1e-9, 2e-9])
    with pytest.raises(TypeError, match="^name must be a str"):
        chain.stage(name)
    assert chain.stage(chain.names[-1]) is chain.output
