"""The "your probe" panel of notebook 01 (afmsmiler.ui.probe.ProbePanel).

The panel keeps the panel contract (one model run per move, SI values, a preset moving the
geometry controls without runs of their own), draws what the model computed (the figure's data
is the model's spectrum in pm^2/Hz and kHz), and every suggestion notebook 01 makes for it
("Things to try") holds from the panel's defaults: one ``test_notebook_suggestion_*`` each. The
physics behind the numbers is checked in tests/test_probe_model.py, test_hydrodynamics_model.py
and test_calibration_model.py against their sources.
"""
import json
import math
from pathlib import Path

import pytest

from afmsmiler.calibration import optical_lever_correction
from afmsmiler.planform import PRESETS, preset
from afmsmiler.probe import probe_report
from afmsmiler.ui.probe import CUSTOM, DEFAULTS, ProbePanel

NOTEBOOK = Path(__file__).parents[1] / "notebooks" / "01_cantilever_mechanics.ipynb"
CELLS = json.loads(NOTEBOOK.read_text(encoding="utf-8"))["cells"]
CODE = ["".join(c["source"]) for c in CELLS if c["cell_type"] == "code"]
MARKDOWN = ["".join(c["source"]) for c in CELLS if c["cell_type"] == "markdown"]


def _count_runs(panel):
    calls = []
    update = panel.update
    panel.update = lambda **v: (calls.append(v), update(**v))
    return calls


def test_defaults_show_the_model_of_the_contal_g_in_air():
    p = ProbePanel()
    assert p.values() == dict(DEFAULTS)
    r = probe_report(preset("ContAl-G"), "air", seed=0)
    assert p.last.spring_constant == r.spring_constant
    assert p.last.thermal.spring_constant == pytest.approx(r.thermal.spring_constant, rel=1e-12)
    assert p.last.modes["water"].quality_factor == r.modes["water"].quality_factor
    lines = p.figure.lines
    x, y = lines["psd"].get_data()
    assert y == pytest.approx(r.spectrum.psd * 1e24, rel=1e-12)   # m^2/Hz -> pm^2/Hz
    assert x == pytest.approx(r.spectrum.frequency / 1e3, rel=1e-12)  # Hz -> kHz
    assert lines["spot"].get_data()[0][0] == pytest.approx(450.0)   # um, at the free end
    html = p.readout.value
    assert "0.189 N/m" in html and "56.6" in html and "2.3" in html and "why they differ" in html


def test_a_preset_moves_the_geometry_in_one_run():
    p = ProbePanel()
    calls = _count_runs(p)
    p.controls["probe"].value = "MLCT-E"
    assert len(calls) == 1 and calls[0]["probe"] == "MLCT-E"
    v = p.values()
    assert (v["planform"], v["material"], v["length"], v["arm_width"]) == (
        "v_shaped", "silicon_nitride", pytest.approx(140.0), pytest.approx(18.0))
    assert p.last.lever.name == "MLCT-E" and p.last.lever.coating is not None


def test_only_the_sliders_that_shape_the_planform_can_move():
    p = ProbePanel(probe=CUSTOM, planform="rectangular")
    c = p.controls
    calls = _count_runs(p)
    assert c["point_length"].disabled and c["arm_width"].disabled
    assert not any(c[n].disabled for n in ("length", "width", "thickness", "spot"))
    # what the disabled ones would have moved: nothing, for a rectangle
    k = p.last.spring_constant
    p.set(point_length=c["point_length"].value * 1.5, arm_width=c["arm_width"].value * 0.8)
    assert p.last.spring_constant == k
    held = (c["point_length"].value, c["arm_width"].value)
    c["planform"].value = "pointed"
    assert not c["point_length"].disabled and c["arm_width"].disabled
    c["planform"].value = "v_shaped"
    assert c["point_length"].disabled and not c["arm_width"].disabled
    assert (c["point_length"].value, c["arm_width"].value) == held  # values kept
    assert len(calls) == 3  # the set and the two planform moves: enabling ran nothing
    c["probe"].value = "MLCT-E"  # a preset sets its planform, and with it the sliders
    assert c["planform"].value == "v_shaped" and not c["arm_width"].disabled
    c["probe"].value = "ContAl-G"
    assert c["point_length"].disabled and c["arm_width"].disabled


def test_a_geometry_move_makes_the_lever_custom_in_one_run():
    p = ProbePanel(probe="AC240TS")
    calls = _count_runs(p)
    p.controls["length"].value = 200.0
    assert len(calls) == 1
    assert p.values()["probe"] == CUSTOM
    lever = p.last.lever
    assert (lever.planform, lever.length, lever.width, lever.point_length) == (
        "pointed", pytest.approx(200e-6), pytest.approx(40e-6), pytest.approx(20e-6))
    assert lever.name == "" and lever.coating is None


def test_a_browser_echo_of_a_slider_keeps_the_preset_and_runs_nothing():
    # the browser sends a slider's value back as min + n * step, a rounding error off the value
    # the kernel set: no move, so the preset stays chosen and the model does not run again
    p = ProbePanel()
    calls = _count_runs(p)
    for name in ("length", "width", "thickness", "point_length", "arm_width"):
        c = p.controls[name]
        echo = c.min + round((c.value - c.min) / c.step) * c.step
        c.value = echo * (1 + 2e-16) if echo == c.value else echo
        assert p.values()["probe"] == "ContAl-G", name
    assert calls == []


def test_set_with_a_preset_and_geometry_starts_from_the_preset():
    p = ProbePanel()
    calls = _count_runs(p)
    p.set(thickness=1.5, probe="Tap150Al-G")
    assert len(calls) == 1
    v = p.values()
    assert v["probe"] == CUSTOM and v["length"] == pytest.approx(125.0)
    assert p.last.lever.thickness == pytest.approx(1.5e-6)


def test_the_spot_slider_reaches_the_model_in_si_once():
    p = ProbePanel()
    calls = _count_runs(p)
    p.set(spot=0.8)
    assert len(calls) == 1 and calls[0]["spot"] == 0.8 and calls[0]["length"] == 450e-6
    assert p.figure.lines["spot"].get_data()[0][0] == pytest.approx(360.0)


def test_bad_values_are_refused_by_name():
    with pytest.raises(ValueError, match="probe"):
        ProbePanel(probe="AC240TS", length=100.0)
    with pytest.raises(ValueError, match="probe"):
        ProbePanel(probe="nonesuch")
    with pytest.raises(ValueError, match="spot"):
        ProbePanel(spot=0.1)
    p = ProbePanel(probe=CUSTOM)
    with pytest.raises(ValueError, match="thickness"):   # thin-strip torsion: t <= w / 5
        p.set(width=5.0, thickness=2.0)
    with pytest.raises(ValueError, match="seed"):
        ProbePanel(seed=1.5)


@pytest.mark.slow
def test_every_preset_can_be_chosen():
    p = ProbePanel()
    for name in PRESETS:
        p.set(probe=name)
        assert p.last.lever.name == name and math.isfinite(p.last.thermal.spring_constant)


# -- notebook 01's "Things to try" for this panel, from the defaults --------------------------
def test_notebook_suggestion_water_drops_q_and_biases_both_methods():
    p = ProbePanel()
    air = p.last.modes["air"]
    p.set(fluid="water")
    water = p.last.modes["water"]
    assert air.resonance_frequency / 1e3 == pytest.approx(13.4, abs=0.05)
    assert water.resonance_frequency / 1e3 == pytest.approx(3.4, abs=0.05)
    assert air.quality_factor == pytest.approx(57, abs=1)
    assert water.quality_factor == pytest.approx(2.3, abs=0.05)
    assert 0.06 < p.last.thermal_error < 0.12        # "about 9 % high"
    assert 0.25 < p.last.sader_error < 0.35          # "about 30 %"


def test_notebook_suggestion_spot_at_0_7_lowers_the_thermal_k_by_chi_squared():
    p = ProbePanel()
    k = p.last.thermal.spring_constant
    p.set(spot=0.7)
    chi2 = (optical_lever_correction(1, 0.7) / optical_lever_correction(1, 1.0)) ** 2
    assert chi2 == pytest.approx(0.89, abs=0.005)
    assert p.last.thermal.spring_constant / k == pytest.approx(chi2, rel=1e-3)   # "11 %"


def test_notebook_suggestion_mlct_e_thermal_close_sader_far():
    p = ProbePanel()
    p.set(probe="MLCT-E")
    assert abs(p.last.thermal_error) < 0.05                       # "within a few per cent"
    assert 1.0 + p.last.sader_error == pytest.approx(1.5, abs=0.1)   # "about 1.5 times"


def test_notebook_suggestion_custom_half_thickness():
    p = ProbePanel()
    p.set(probe=CUSTOM)
    before = p.last
    p.set(thickness=1.0)
    after = p.last
    assert after.spring_constant / before.spring_constant == pytest.approx(1 / 8, rel=1e-6)
    assert after.vacuum_frequency / before.vacuum_frequency == pytest.approx(1 / 2, rel=1e-6)
    assert before.modes["air"].quality_factor == pytest.approx(56, abs=1)
    assert after.modes["air"].quality_factor == pytest.approx(18, abs=1)


def test_notebook_suggestion_friction_twists_the_lever():
    # notebook 01: at 500 nN the ContAl-G's tip section twists about 0.58 mrad, F_L (h + t/2) /
    # k_phi with Saint-Venant's k_phi ~ G w t^3 / (3 L) (its coating adds 2 %); drawn x 500; the
    # MLCT-E is eleven times softer in torsion and twists about 2.6 mrad
    from tests.recording import Recorder
    p = ProbePanel(vis=Recorder())
    runs = p.model_runs
    p.set(lateral_force=500.0)
    assert p.model_runs == runs  # the twist alone: no report again
    lever = p.last.lever
    # the coated strip's Saint-Venant stiffness: k_phi = (4 w / L) int G(z) (z - z0)^2 dz, z0
    # the G-weighted centre (w t^3 G / (3 L) for one layer); the aluminium adds about 2 %
    t, tc = lever.thickness, lever.coating_thickness
    layers = [(lever.shear_modulus, 0.0, t), (lever.coating.shear_modulus, t, t + tc)]
    z0 = sum(g * (b * b - a * a) / 2 for g, a, b in layers) / sum(g * (b - a)
                                                               for g, a, b in layers)
    k_phi = 4 * lever.width / lever.length * sum(
        g * ((b - z0) ** 3 - (a - z0) ** 3) / 3 for g, a, b in layers)
    strip = lever.shear_modulus * lever.width * t ** 3 / (3 * lever.length)
    assert k_phi / strip == pytest.approx(1.02, abs=0.005)
    assert f"{p.twist * 1e3:.2g}" == "0.58"
    assert p.twist == pytest.approx(500e-9 * (lever.tip_height + t / 2) / k_phi, rel=3e-3)
    assert p.scene.factor == 500.0 and "twist x 500" in p.readout.value
    p.set(probe="MLCT-E")
    assert f"{p.twist * 1e3:.2g}" == "2.6"
    assert round(preset("ContAl-G").torsional_stiffness / preset("MLCT-E").torsional_stiffness) \
        == 11


def test_the_twist_of_an_uncoated_rectangle_is_saint_venants():
    # a custom silicon rectangle, no coating: phi = F_L (h_tip + t/2) 3 L / (G w t^3) (Saint-Venant's
    # thin strip, Timoshenko and Goodier), to the frame model's discretisation
    p = ProbePanel(probe=CUSTOM, planform="rectangular", lateral_force=-200.0)
    lever = p.last.lever
    assert lever.coating is None
    k_phi = lever.shear_modulus * lever.width * lever.thickness ** 3 / (3 * lever.length)
    arm = lever.tip_height + lever.thickness / 2
    assert p.twist == pytest.approx(-200e-9 * arm / k_phi, rel=2e-3)  # the sign of the force
    assert "N m/rad" in p.readout.value and "mrad" in p.readout.value
    assert "beyond small twists" not in p.readout.value
    # a long thin lever at the slider's largest force: the readout says the model no longer holds
    p.set(length=1000.0, width=5.0, thickness=0.2, lateral_force=500.0)
    assert p.twist > 1.0 and "beyond small twists" in p.readout.value


def test_the_notebooks_list_of_things_to_try_names_these_tests():
    section = [m for m in MARKDOWN if m.startswith("## Your probe")]
    assert len(section) == 1
    text = section[0]
    assert "tests/test_probe_ui.py" in text
    tries = sum(1 for n in range(1, 10) if f"\n{n}. " in text)
    own = Path(__file__).read_text(encoding="utf-8").count("def " + "test_notebook_suggestion_")
    assert tries == own == 5
    assert any(src.startswith("probe = ProbePanel(scene=True)") for src in CODE)


def _run(*sources):
    namespace = {}
    *body, last = "\n".join(sources).rstrip().splitlines()
    exec("\n".join(body), namespace)
    return eval(last.split("#")[0], namespace)


@pytest.mark.slow
def test_exercise_5_cell_asks_and_names_the_slips():
    cell = next(src for src in CODE if "check_unseen_lever_calibration(k_lever)" in src)
    imports = next(src for src in CODE if src.startswith("import sympy"))
    assert not _run(imports, cell)   # k_lever = None: not yet
    # a first try without the optical-lever factor: the checker says so
    forgot = cell.replace("k_lever = None", "k_lever = 0.971 * k_B * T / fit.area")
    feedback = _run(imports, forgot)
    assert not feedback and "optical-lever factor" in str(feedback)
    right = cell.replace("k_lever = None", "k_lever = 0.971 * k_B * T / (1.0897 ** 2 * fit.area)")
    assert _run(imports, right)
