"""Module (b)'s figure and panel without a browser: set controls, compare the plotted data with the
model and with closed forms; sliders are generated from the metadata and cannot leave its ranges."""
import math

import numpy as np
import pytest

from afmsmiler.plots.transducers import TransducerFigure, chain_curves, frequency_grid
from afmsmiler.transducers import PRINCIPLES, Electrostatic, OpticalBeamDeflection
from afmsmiler.ui.transducers import TransducerPanel, control_for


@pytest.fixture
def panel():
    return TransducerPanel(scene=False)


def test_sliders_are_generated_from_the_metadata(panel):
    for key, cls in PRINCIPLES.items():
        panel.set(principle=key)
        table = cls.parameter_table()
        assert set(panel.controls) == {"principle", "mode", "input", *table}
        for name, p in table.items():
            c = panel.controls[name]
            assert p.display_unit in c.description
            lo, hi = (10 ** c.min, 10 ** c.max) if p.log else (c.min, c.max)
            # bounds inside the valid range, in the unit shown
            tol = 1e-9 * max(abs(p.low), abs(p.high)) * p.scale
            assert lo >= p.low * p.scale - tol and hi <= p.high * p.scale + tol
            assert c.value == pytest.approx(p.default * p.scale)
        q = cls().input_quantity()
        assert panel.controls["input"].min == pytest.approx(q.low * q.scale)


@pytest.mark.parametrize("key", list(PRINCIPLES))
def test_every_slider_extreme_is_a_valid_model(panel, key):
    panel.set(principle=key)
    names = [n for n in panel.controls if n not in ("principle", "mode")]
    for name in names:
        c = panel.controls[name]
        for end in ("min", "max"):
            value = getattr(c, end)
            panel.set(**{name: 10 ** value if hasattr(c, "base") else value})
            assert panel.last.model.key == key   # no ValueError from the model


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
    curves = chain_curves(model, 0.0, n_points=11)
    fig = TransducerFigure(curves)
    assert len(fig.lines["output"].get_xdata()) == 11
    assert curves.sensitivity == pytest.approx(model.sensitivity() * 1e-9)
    with pytest.raises(ValueError, match="^deflection must be in"):
        chain_curves(model, 1.0)
    with pytest.raises(ValueError, match="^n_points must be an integer"):
        chain_curves(model, 0.0, n_points=1)
    p = OpticalBeamDeflection.parameter_table()["power"]
    s = control_for(p)
    assert s.value == pytest.approx(1.0) and "mW" in s.description
    assert 10 ** s.min == pytest.approx(1e-3) and math.isclose(10 ** s.max, 20.0)


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
        assert list(lever.children) == [panel.controls[n] for n in lever_names] + [panel.readout]
        assert chain.children[:2] == (panel.controls["principle"], panel.controls["mode"])
        assert len(chain.children) == len(panel.controls) - len(lever_names)
        assert len(chain.children) <= 10
        # labels aligned within each column, also for the swapped-in sliders
        widths = {c.layout.width for c in chain.children[2:]}
        assert len(widths) == 1
        total = int(widths.pop().removesuffix("px")) + int(panel.readout.layout.width[:-2])
        assert total <= 1100
    fig_w, fig_h = panel.fig.get_size_inches() * panel.fig.dpi
    assert fig_w <= 1000 and fig_h <= 400


def test_after_close_viewer_the_readout_says_how_to_get_the_3d_view_back():
    # "Run All" ends notebook 02 with close_viewer(): the sliders go on updating plots and
    # readout without starting a server, and the readout tells the student what to do.
    from afmsmiler.scenes import close_viewer, viewer
    try:
        panel = TransducerPanel(scene=True)
        assert panel.scene is not None and "3D view closed" not in panel.readout.value
        close_viewer()
        panel.controls["input"].value = 100.0  # as a user would move it
        assert panel.error is None and panel.scene is None and not viewer.viewer_running()
        assert panel.last.value == pytest.approx(100e-9)
        assert "3D view closed" in panel.readout.value and "jupyter_cell()" in panel.readout.value
        vis = viewer.get_viewer()  # the student re-runs the view cell, then moves a slider
        panel.set(input=-50.0)
        assert panel.scene is not None and panel.scene.root is vis
        assert "3D view closed" not in panel.readout.value
    finally:
        close_viewer()
