"""Module (b)'s figure and panel without a browser: set controls, compare the plotted data with the
model and with closed forms; sliders are generated from the metadata and cannot leave its ranges;
one user action runs the signal chain once; out-of-range values and unknown choices are named."""
import math

import numpy as np
import pytest

from afmsmiler.plots.transducers import TransducerFigure, chain_curves, frequency_grid
from afmsmiler.transducers import PRINCIPLES, Electrostatic, OpticalBeamDeflection
from afmsmiler.transducers.base import Transducer
from afmsmiler.ui.controls import control
from afmsmiler.ui.transducers import TransducerPanel, to_si


@pytest.fixture
def panel():
    return TransducerPanel(scene=False)


def test_sliders_are_generated_from_the_metadata(panel):
    for key, cls in PRINCIPLES.items():
        panel.set(principle=key)
        table = cls.parameter_table()
        assert set(panel.controls) == {"principle", "mode", "fluid", "input", *table}
        for name, p in table.items():
            c = panel.controls[name]
            assert p.display_unit in c.description
            lo, hi = (10 ** c.min, 10 ** c.max) if p.log else (c.min, c.max)
            # bounds inside the valid range, in the unit shown
            tol = 1e-9 * max(abs(p.low), abs(p.high)) * p.scale
            assert lo >= p.low * p.scale - tol and hi <= p.high * p.scale + tol
            assert c.value == pytest.approx(p.default * p.scale)
            assert c.parameter is p     # built by ui.controls.control from the Parameter
        q = cls().input_quantity()
        c = panel.controls["input"]
        assert c.parameter is q and c.value == pytest.approx(q.to_display(q.default))
        assert q.to_display(q.low) - 1e-9 * c.step <= c.min < q.to_display(q.low) + c.step


@pytest.mark.parametrize("key", list(PRINCIPLES))
def test_every_slider_extreme_is_a_valid_model(panel, key):
    # in vacuum and in water too, where a long thin lever is overdamped (Q < 1/2): the thermal
    # spectrum's closed form holds for any Q > 0 (tests/test_brownian_model.py)
    panel.set(principle=key)
    names = [n for n in panel.controls if n not in ("principle", "mode", "fluid")]
    for fluid in ("typed", "water"):
        panel.set(fluid=fluid)
        for name in names:
            c = panel.controls[name]
            for end in ("min", "max"):
                value = getattr(c, end)
                panel.set(**{name: 10 ** value if hasattr(c, "base") else value})
                assert panel.last.model.key == key   # no ValueError from the model


@pytest.mark.parametrize("key", list(PRINCIPLES))
def test_every_corner_of_the_lever_in_every_medium_is_a_valid_model(panel, key):
    # the sliders one at a time never reach the overdamped corner (1 mm x 5 um x 0.2 um: Q 0.16
    # in water); set together, each corner of the lever's box, in vacuum, air and water
    import itertools
    panel.set(principle=key)
    ends = {n: tuple(10 ** v if hasattr(c, "base") else v for v in (c.min, c.max))
            for n, c in ((n, panel.controls[n]) for n in ("length", "width", "thickness"))}
    for fluid in ("typed", "air", "water"):
        for corner in itertools.product(*ends.values()):
            panel.set(fluid=fluid, **dict(zip(ends, corner)))
            assert panel.last.model.key == key and panel.last.model.fluid == (
                None if fluid == "typed" else fluid)
            assert not math.isnan(panel.last.resolution.total)


def test_lines_equal_the_model_in_the_units_shown(panel):
    panel.set(principle="optical_beam_deflection", input=150.0, optical_path=50.0, length=120.0)
    model = OpticalBeamDeflection(optical_path=50e-3, length=120e-6)
    assert panel.last.model == model and panel.last.value == pytest.approx(150e-9)
    lines = panel.figure.lines
    x_nm, s = lines["output"].get_data()
    z = np.linspace(-2e-6, 2e-6, len(x_nm))       # the input's valid range
    np.testing.assert_allclose(x_nm, z * 1e9, rtol=1e-12)
    np.testing.assert_allclose(s, model.respond(z), rtol=1e-12)
    x_nm, slope_mrad = lines["left"].get_data()
    np.testing.assert_allclose(slope_mrad, 1.5 * np.asarray(x_nm) * 1e-9 / 120e-6 * 1e3,
                               rtol=1e-12)
    px, py = lines["point"].get_data()
    assert px[0] == pytest.approx(150.0) and py[0] == pytest.approx(float(model.respond(150e-9)))
    # the tangent has the small-signal slope at the input (per nm shown)
    tx, ty = lines["tangent"].get_data()
    assert (ty[1] - ty[0]) / (tx[1] - tx[0]) == pytest.approx(model.sensitivity(at=150e-9) * 1e-9)
    f, mag = lines["magnitude"].get_data()
    fr = model.frequency_response(f)
    np.testing.assert_allclose(mag, np.abs(fr.response) * 1e-9, rtol=1e-12)   # 1/N -> 1/nN
    assert panel.last.sensitivity == pytest.approx(model.sensitivity(at=150e-9))
    assert "sensing; DC&AC; bulk" in panel.readout.value


def test_actuator_chain_and_readout(panel):
    panel.set(principle="electrostatic", input=10.0, gap=4.0, ac_voltage=0.0)
    model = Electrostatic(gap=4e-6, ac_voltage=0.0)
    # F = (1/2) dC/dz V^2, dC/dz = -eps0 w l_e / g^2
    force = -0.5 * 8.8541878188e-12 * model.width * model.electrode_length / 16e-12 * 100
    assert panel.last.chain.stage("force").values == pytest.approx(force, rel=1e-12)
    x, f_nn = panel.figure.lines["left"].get_data()
    assert f_nn[np.argmin(np.abs(np.asarray(x) - 10.0))] == pytest.approx(force * 1e9, rel=1e-9)
    assert "nm/V" in panel.readout.value and "resolution" in panel.readout.value
    assert "pull-in" not in panel.readout.value
    panel.set(gap=0.5, input=20.0)
    assert "pull-in" in panel.readout.value


def test_piezoelectric_offers_both_modes(panel):
    panel.set(principle="piezoelectric")
    assert tuple(panel.controls["mode"].options) == ("sensing", "actuation")
    assert not panel.controls["mode"].disabled
    panel.set(d31=-100.0)
    panel.set(mode="actuation", input=4.0)
    assert panel.last.mode == "actuation" and panel.last.model.d31 == pytest.approx(-100e-12)
    per_volt = panel.last.model.deflection_per_volt
    assert panel.last.chain.output.values == pytest.approx(4.0 * per_volt)
    panel.set(principle="piezoresistive")
    assert panel.controls["mode"].disabled and panel.last.mode == "sensing"


@pytest.mark.slow  # two principle changes, each a full panel rebuild (~0.6-1 s)
def test_readout_says_where_models_stop_holding(panel):
    # a stubby piezoresistive lever bent 2 um: the clamp sees 1.5 E h z / L^2 = 127 GPa
    panel.set(principle="piezoresistive", length=20.0, thickness=10.0, resistor_length=4.0,
              input=2000.0)
    assert "breaks at 1-3 GPa" in panel.readout.value
    _, out_uv = panel.figure.lines["output"].get_data()
    vb_uv = panel.last.model.bias_voltage * 1e6
    assert np.all(np.abs(out_uv) <= vb_uv / 2 * (1 + 1e-12))     # the bridge's rails
    # base excitation far above the resonance: the second mode matters
    panel.set(principle="piezo_acoustic", drive_ratio=3.0)
    assert "second mode" in panel.readout.value
    panel.set(drive_ratio=1.0)
    assert "second mode" not in panel.readout.value


def test_linked_slider_follows_the_lever(panel):
    panel.set(principle="electrostatic", electrode_length=200.0)
    panel.set(length=100.0)
    assert panel.controls["electrode_length"].max == pytest.approx(100.0)
    assert panel.last.model.electrode_length <= panel.last.model.length
    panel.controls["length"].value = 60.0     # as a user would drag it
    assert panel.last.model.electrode_length == pytest.approx(60e-6)


def test_selector_change_from_the_widget(panel):
    panel.controls["principle"].value = "photothermal"
    assert panel.last.model.key == "photothermal" and "laser_power" not in panel.controls
    assert "absorptance" in panel.controls
    panel.controls["input"].value = 5.0       # mW
    assert panel.last.value == pytest.approx(5e-3)


def test_bad_controls(panel):
    with pytest.raises(TypeError, match="unknown control"):
        panel.set(colour=1.0)
    with pytest.raises(ValueError, match="principle must be one of"):
        panel.set(principle="telepathy")
    with pytest.raises(ValueError, match="principle must be one of"):
        TransducerPanel(principle="telepathy", scene=False)
    with pytest.raises(ValueError, match="mode must be one of"):
        panel.set(mode="actuation")


def test_figure_and_control_helpers():
    model = OpticalBeamDeflection()
    f = frequency_grid(model, 50)
    assert f[0] == pytest.approx(1e-2) and f[-1] == pytest.approx(10 * model.resonance_frequency)
    curves = chain_curves(model.operate(0.0, frequencies=f, n_points=11))
    fig = TransducerFigure(curves)
    assert len(fig.lines["output"].get_xdata()) == 11
    assert curves.sensitivity == pytest.approx(model.sensitivity() * 1e-9)
    with pytest.raises(ValueError, match="^deflection must be in"):
        model.operate(1.0)
    with pytest.raises(ValueError, match="^n_points must be an integer"):
        model.operate(0.0, n_points=1)
    with pytest.raises(TypeError, match="^operation must be"):
        chain_curves(model)
    with pytest.raises(ValueError, match="^operation must carry a frequency response"):
        chain_curves(model.operate(0.0))
    p = OpticalBeamDeflection.parameter_table()["power"]
    s = control(p)
    assert s.value == pytest.approx(1.0) and "mW" in s.description
    # a log grid through the default 1 mW, inside [1 uW, 20 mW]
    assert 10 ** s.min == pytest.approx(1e-3) and 19.0 < 10 ** s.max <= 20.0


def test_one_user_action_is_one_update():
    panel = TransducerPanel(principle="piezoelectric", scene=False)
    calls = []
    original = panel.update
    panel.update = lambda **v: (calls.append(v["mode"]), original(**v))
    panel.set(mode="actuation", input=3.0)
    panel.controls["mode"].value = "sensing"            # a click on the toggle
    panel.controls["principle"].value = "interferometry"  # a new choice in the selector
    panel.controls["input"].value = 40.0                 # a slider drag
    assert calls == ["actuation", "sensing", "sensing", "sensing"]
    assert panel.last.model.key == "interferometry" and panel.last.value == pytest.approx(40e-9)


def _leaves(w):
    """Every widget in the tree under ``w`` (depth first)."""
    yield w
    for child in getattr(w, "children", ()):
        yield from _leaves(child)


def test_controls_and_readout_share_a_row_above_the_figure():
    # In one column (selector, mode, up to 13 sliders, the readout) with the figure below it,
    # the panel was 1100-1300 px high in JupyterLab: no slider and the plots on one screen.
    import ipywidgets as widgets

    from afmsmiler.transducers.base import LEVER_PARAMETERS
    from afmsmiler.ui.panel import arrange
    panel = TransducerPanel(scene=False)
    w = arrange(panel.widget())
    row, figure = w.children
    assert isinstance(w, widgets.VBox) and isinstance(row, widgets.HBox)
    chain, lever = row.children
    assert row.layout.flex_flow == "row wrap"
    assert chain.layout.flex == lever.layout.flex == "0 0 auto"
    lever_names = [p.name for p in LEVER_PARAMETERS]
    for key in ("optical_beam_deflection", "piezoresistive", "electromagnetic"):
        panel.set(principle=key)  # the columns follow the new controls
        in_row = list(_leaves(row))
        assert all(any(c is x for x in in_row) for c in panel.controls.values())
        assert any(x is panel.readout for x in in_row)
        assert not any(x is figure for x in in_row) and figure is not panel.readout
        # the readout is beside the principle's column, not under it
        assert list(lever.children) == ([panel.controls["fluid"]]
                                        + [panel.controls[n] for n in lever_names]
                                        + [panel.readout])
        assert chain.children[:2] == (panel.controls["principle"], panel.controls["mode"])
        assert len(chain.children) == len(panel.controls) - len(lever_names) - 1
        assert len(chain.children) <= 10
        # labels aligned within each column, also for the swapped-in sliders
        widths = {c.layout.width for c in chain.children[2:]}
        assert len(widths) == 1
        total = int(widths.pop().removesuffix("px")) + int(panel.readout.layout.width[:-2])
        assert total <= 1100
    fig_w, fig_h = panel.fig.get_size_inches() * panel.fig.dpi
    assert fig_w <= 1000 and fig_h <= 400


def test_the_panel_shows_its_own_3d_view_and_keeps_it():
    # the 3D view is the panel's widget: "Run All" cannot close it, a slider move updates it
    panel = TransducerPanel(scene=True)
    view = panel.scene_view()
    assert view is not None and view is panel.scene.view
    sent = view.commands_sent
    panel.controls["input"].value = 100.0  # as a user would move it
    assert panel.error is None and panel.scene_view() is view and view.commands_sent > sent
    assert panel.last.value == pytest.approx(100e-9)
    assert TransducerPanel(scene=True).scene_view() is not view  # each panel its own scene


# --- one user action = one model run ------------------------------------------------------------
class _ChainCounter:
    def __init__(self, monkeypatch):
        self.n = 0
        original = Transducer.chain

        def counting(model, *args, **kwargs):
            self.n += 1
            return original(model, *args, **kwargs)

        monkeypatch.setattr(Transducer, "chain", counting)


def _browser_echo(c):
    """What the browser sends back after drawing slider ``c``: its value snapped to the grid."""
    if hasattr(c, "base"):
        e = c.min + round((np.log10(c.value) - c.min) / c.step) * c.step
        return float(10 ** e)
    return c.min + round((c.value - c.min) / c.step) * c.step


@pytest.mark.parametrize("key", list(PRINCIPLES))
def test_one_slider_move_runs_the_signal_chain_once(key, monkeypatch):
    # before: five runs per move (the figure's sweep and point, the scene's sweep and point, the
    # panel's own chain); the figure and the 3D view now draw from one Operation
    from tests.recording import Recorder

    from afmsmiler.scenes.transducers import TransducerScene
    panel = TransducerPanel(principle=key, scene=False)
    panel.scene = TransducerScene(panel.last.operation, vis=Recorder(), camera=False)
    counter = _ChainCounter(monkeypatch)
    c = panel.controls["input"]
    c.value = c.min + 3 * c.step if c.value != c.min + 3 * c.step else c.min   # a student's drag
    assert counter.n == 1
    panel.controls["temperature"].value = 300.0
    assert counter.n == 2


def test_one_principle_change_is_one_update_even_with_the_browser_echo():
    # the drop-down ran 10-14 full updates: the browser echoed every new slider's value snapped
    # to a grid that did not hold it; the grid now holds every default, so the echo is ignored
    panel = TransducerPanel(scene=False)
    calls = []
    original = panel.update
    panel.update = lambda **v: (calls.append(v["principle"]), original(**v))
    for key in PRINCIPLES:
        if key == panel.controls["principle"].value:
            continue
        calls.clear()
        panel.controls["principle"].value = key           # the student picks a principle
        for name, c in list(panel.controls.items()):      # the browser draws the new sliders
            if name not in ("principle", "mode", "fluid"):
                c.value = _browser_echo(c)
        assert calls == [key], key
        model = PRINCIPLES[key]()
        assert panel.last.model == model   # every default kept: 225 um, Q 150, 295 K, ...


def test_out_of_range_values_are_rejected_not_clamped(panel):
    # the panel clamped: power 1e300 W became 0.02 W and the model ran with it
    with pytest.raises(ValueError, match=r"^power must be in \[.*\] mW, got 1e\+300"):
        panel.set(power=1e300)
    si = panel.to_si(panel.values())  # update takes every control, in SI (the panel contract)
    with pytest.raises(ValueError, match=r"^power must be in \[1e-06, 0.02\] W"):
        panel.update(**{**si, "power": 1e300})
    with pytest.raises(ValueError, match="^input must be in"):
        panel.update(**{**si, "input": 1e9})
    with pytest.raises(ValueError, match="^length must be"):
        panel.update(**{**si, "length": math.nan})
    assert panel.last.model.power == pytest.approx(1e-3)   # the last good run is kept
    # a slider's own end, one rounding error outside the range once in SI, is the end
    p = OpticalBeamDeflection.parameter_table()["power"]
    assert to_si(p, 20.000000000000004) == 0.02
    with pytest.raises(ValueError, match="^power must be in"):
        to_si(p, 20.001)


def test_unknown_choices_name_the_valid_ones(panel):
    si = panel.to_si(panel.values())
    with pytest.raises(ValueError, match=r"^principle must be one of .*optical_beam_deflection"):
        panel.update(**{**si, "principle": "telepathy"})
    with pytest.raises(ValueError, match=r"^mode must be one of .*sensing"):
        panel.update(**{**si, "mode": "actuation"})
    with pytest.raises(TypeError, match="unknown.*colour"):
        panel.update(**{**si, "colour": 1.0})
    with pytest.raises(TypeError, match="missing.*power"):
        panel.update(**{k: v for k, v in si.items() if k != "power"})
    with pytest.raises(ValueError, match="^mode must be one of"):
        panel.set(principle="interferometry", mode="actuation")


def test_update_uses_exactly_the_values_it_is_given(panel):
    panel.set(principle="electrostatic", mode="actuation")
    si = panel.to_si(panel.values())
    panel.update(**{**si, "input": 7.0, "gap": 4e-6})  # SI: 7 V, 4 um
    assert panel.last.model == Electrostatic(gap=4e-6) and panel.last.value == 7.0
    assert panel.controls["gap"].value != 4.0   # the widgets are not read


def test_phase_is_continuous_through_the_resonance(panel):
    # notebook 02: the phase jumped from -170 deg to +175 deg at resonance (np.angle wraps)
    for key in ("optical_beam_deflection", "piezo_acoustic", "photothermal", "electrostatic"):
        panel.set(principle=key)
        f, phase = panel.figure.lines["phase"].get_data()
        assert np.max(np.abs(np.diff(phase))) < 180.0, key   # a wrap jumps by ~360 deg
        lo, hi = panel.figure.axes["phase"].get_ylim()
        assert lo <= np.min(phase) and np.max(phase) <= hi
    panel.set(principle="optical_beam_deflection")
    f, phase = panel.figure.lines["phase"].get_data()
    f1 = panel.last.model.resonance_frequency
    # below resonance in phase with the force, -90 deg at f1, towards -180 deg above
    # (the detector's 2 MHz low-pass adds a little lag): the phase only falls
    assert np.all(np.diff(phase) <= 1e-9)
    assert np.interp(f1, f, phase) == pytest.approx(-90.0, abs=3.0)    # f1 is on the grid
    assert np.interp(5 * f1, f, phase) < -170.0


def test_frequency_response_shows_the_resonance_peak(panel):
    # a 400-point log grid steps by ~4 % near f1, wider than the f1 / Q = 0.7 % resonance of a
    # Q = 150 lever: the plotted peak fell well below Q. The peak of a damped oscillator's
    # |H| is Q / sqrt(1 - 1/(4 Q^2)) times its static gain (here the sensitivity / k, 1/nN shown;
    # the detector's 2 MHz low-pass takes 0.1 % at f1)
    model = OpticalBeamDeflection()
    f, mag = panel.figure.lines["magnitude"].get_data()
    q = model.quality_factor
    static = model.sensitivity() / model.spring_constant * 1e-9
    lowpass = 1 / abs(1 + 1j * model.resonance_frequency / model.detector_bandwidth)
    assert np.max(mag) == pytest.approx(static * q / math.sqrt(1 - 1 / (4 * q * q)) * lowpass,
                                        rel=2e-3)
    assert np.all(np.diff(f) > 0) and len(f) <= 400 + 101


def test_sensitivity_in_one_unit_in_title_and_readout(panel):
    # the plot title said 1/m and the readout 1/um: both now use the sensitivity's display unit
    title = panel.figure.axes["output"].get_title()
    model = OpticalBeamDeflection()
    shown = f"{model.sensitivity(at=panel.last.value) * 1e-6:.4g} 1/um"   # at the input, 20 nm
    assert shown in title and shown in panel.readout.value


def test_the_notebooks_things_to_try_do_what_it_says(panel):
    # notebook 02: "make the optical lever shorter; move the interferometer's phase off
    # quadrature; drive the electrothermal heater with no DC bias; shake the base at half the
    # resonance frequency" - each followed here on the panel, as a student would
    panel.set(principle="optical_beam_deflection", input=0.0)
    long_lever = panel.last.sensitivity
    panel.set(length=112.5)
    assert panel.last.sensitivity == pytest.approx(2 * long_lever, rel=1e-9)   # ~ 1/L
    panel.set(principle="interferometry", input=0.0)
    quadrature = abs(panel.last.sensitivity)
    panel.set(phase=-0.3)
    assert abs(panel.last.sensitivity) < 0.5 * quadrature    # cos falls off quadrature
    panel.set(principle="electrothermal", input=0.0)
    assert panel.last.sensitivity == 0.0                      # no 1-omega response unbiased
    assert "<b>0 nm/V</b>" in panel.readout.value             # the readout says so
    panel.set(principle="piezo_acoustic", drive_ratio=1.0)
    at_resonance = abs(panel.last.sensitivity)
    panel.set(drive_ratio=0.5)
    # |gamma r^2 H(r)| at r = 1/2: 1.566 / 4 / 0.75 = 0.52 against 1.566 Q = 235 at resonance
    assert abs(panel.last.sensitivity) < at_resonance / 100


# --- limits that hold while the curves stay inside them (issue 9) ---------------------------------
def _ylims(figure):
    return {k: a.get_ylim() for k, a in figure.axes.items()}


def test_one_slider_step_moves_the_curves_not_the_axes(panel):
    # slope = 1.5 z / L: one length step changes the slope curve, on the same axes
    before = _ylims(panel.figure)
    slope = np.max(panel.figure.lines["left"].get_data()[1])
    length = panel.controls["length"]
    panel.set(length=length.value + length.step)
    assert np.max(panel.figure.lines["left"].get_data()[1]) != slope
    assert _ylims(panel.figure) == before
    # one Q step moves the resonance peak of |H(f)|, not its axis
    peak = np.max(panel.figure.lines["magnitude"].get_data()[1])
    q = panel.controls["quality_factor"]
    panel.set(quality_factor=q.value * 10 ** q.step)   # a log slider: its step in decades
    assert np.max(panel.figure.lines["magnitude"].get_data()[1]) > peak
    assert _ylims(panel.figure) == before


def test_a_big_move_rescales_and_keeps_the_curves_inside(panel):
    before = _ylims(panel.figure)
    panel.set(length=40.0, quality_factor=10 ** panel.controls["quality_factor"].max)
    after = _ylims(panel.figure)
    for key, line in (("lever", "left"), ("lever_right", "right"), ("response", "magnitude")):
        y = np.asarray(panel.figure.lines[line].get_data()[1])
        lo, hi = after[key]
        assert after[key] != before[key], key
        assert lo <= y.min() and y.max() <= hi, key


def test_a_new_principle_fits_its_own_quantities(panel):
    # other quantities on the axes: the limits of a fresh figure, not the old principle's
    panel.set(length=40.0)
    for key in ("electrostatic", "photothermal", "optical_beam_deflection"):
        panel.set(principle=key)
        fresh = TransducerFigure(panel.last.curves)
        assert _ylims(panel.figure) == _ylims(fresh), key


def test_the_medium_sets_f1_and_q_and_never_moves_the_q_slider():
    # notebook 02's suggestion, from the defaults: in water the optical lever's resolution in
    # 1 kHz is set by the lever's Brownian motion, no longer by the shot noise
    from afmsmiler.hydrodynamics import fluid_mode
    panel = TransducerPanel(scene=False)
    assert "mostly shot" in panel.readout.value
    q_slider = panel.controls["quality_factor"]
    typed_q, updates = q_slider.value, panel.updates
    panel.set(fluid="water")
    assert panel.updates == updates + 1
    assert q_slider.disabled and q_slider.value == typed_q
    water = fluid_mode(panel.last.model.lever, "water", 1)
    assert panel.last.model.resonance_frequency == water.resonance_frequency
    assert panel.last.model.quality_factor == water.quality_factor
    assert "mostly thermal" in panel.readout.value and "water (Sader)" in panel.readout.value
    # the notebook's words: f1 falls to less than half, Q to about 4
    assert panel.last.model.resonance_frequency < 0.5 * OpticalBeamDeflection().resonance_frequency
    assert 3.5 < panel.last.model.quality_factor < 4.5
    assert "Q &gt;&gt; 1" in panel.readout.value or "Q >> 1" in panel.readout.value
    panel.set(principle="piezoresistive")   # the medium stays, and so does the disabled Q
    assert panel.last.model.fluid == "water" and panel.controls["quality_factor"].disabled
    panel.set(principle="optical_beam_deflection", fluid="typed")
    assert not panel.controls["quality_factor"].disabled
    assert panel.last.model == OpticalBeamDeflection()
