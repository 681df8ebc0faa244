"""Module (e)'s panel without a browser: sliders come from the Parameter tables; one user action
runs the head's model once; the display, the figure and the 3D scene (a recorder) show what an
independent OpticalHead computes; the guided setup runs on the panel as the notebook tells the
student to; unknown parts and knobs beyond their travel are named."""
import math
import re

import numpy as np
import pytest
from tests.recording import Recorder

from afmsmiler.instrument import KNOBS, OpticalHead, align
from afmsmiler.instrument.walkthrough import SETUP, STEP_TOLERANCES
from afmsmiler.plots.live import describe
from afmsmiler.scenes.instrument import INSTRUMENTS
from afmsmiler.scenes.instrument import PARAMETERS as SCENE
from afmsmiler.ui.instrument import InstrumentPanel

TURN = 2 * math.pi


@pytest.fixture(scope="module")
def aligned_turns():
    head = OpticalHead()
    align(head)
    return {k: v / TURN for k, v in head.knobs.items()}


@pytest.fixture
def panel():
    return InstrumentPanel()


def test_sliders_are_built_from_the_parameter_tables(panel):
    for name, p in {**KNOBS, **SETUP, "housing_opacity": SCENE["housing_opacity"],
                    "explode_fraction": SCENE["explode_fraction"]}.items():
        c = panel.controls[name]
        assert c.parameter is p
        assert c.value == pytest.approx(p.to_display(p.default))
    for name, p in KNOBS.items():   # the knob's travel, in turns
        assert panel.controls[name].min == pytest.approx(p.low / TURN)
        assert panel.controls[name].max == pytest.approx(p.high / TURN)
    assert [v for _, v in panel.controls["instrument"].options] == list(INSTRUMENTS)


def test_display_equals_an_independent_head(panel, aligned_turns):
    panel.set(**aligned_turns)
    head = OpticalHead()
    expected = head.set(**{k: v * TURN for k, v in aligned_turns.items()})
    s = panel.last.signals
    assert s.sum == pytest.approx(expected.sum, rel=1e-9)
    assert s.vertical == pytest.approx(expected.vertical, abs=1e-9)
    assert expected.readout() in panel.display_html.value
    # the figure's spots in the units shown (um on the lever, mm on the photodiode)
    x, y = panel.figure.lines["lever_centre"].get_data()
    assert x[0] == pytest.approx(expected.spot_on_lever[0] * 1e6)
    assert y[0] == pytest.approx(expected.spot_on_lever[1] * 1e6)
    lat, v = panel.figure.lines["detector_centre"].get_data()
    assert (lat[0], v[0]) == pytest.approx((expected.spot_on_detector[1] * 1e3,
                                            expected.spot_on_detector[0] * 1e3))
    sx, sy = panel.figure.lines["detector_spot"].get_data()
    radius = np.hypot(np.asarray(sx) - lat[0], np.asarray(sy) - v[0])
    np.testing.assert_allclose(radius, head.detector_spot_radius * 1e3, rtol=1e-9)
    describe(panel.fig)     # every artist is one a live figure draws


def test_lever_is_free_until_the_approach(panel, aligned_turns):
    panel.set(**aligned_turns, deflection=20.0)
    assert panel.last.deflection == 0.0 and abs(panel.last.signals.vertical) < 0.05
    panel.set(approach_gap=0.0)
    assert panel.last.deflection == pytest.approx(20e-9)
    expected = OpticalHead()
    expected.set(**{k: v * TURN for k, v in aligned_turns.items()})
    assert panel.last.signals.vertical == pytest.approx(expected.signals(20e-9).vertical,
                                                        rel=1e-9)
    assert "in contact" in panel.display_html.value


@pytest.fixture
def count_runs(monkeypatch):
    counts = {"signals": 0}
    original = OpticalHead.signals

    def counted(self, *args, **kwargs):
        counts["signals"] += 1
        return original(self, *args, **kwargs)
    monkeypatch.setattr(OpticalHead, "signals", counted)
    return counts


def test_one_user_action_is_one_model_run(count_runs):
    panel = InstrumentPanel(vis=Recorder())
    assert count_runs["signals"] == 1
    moves = [dict(laser_x=1.0), dict(detector_vertical=-0.5), dict(deflection=10.0),
             dict(approach_gap=0.0), dict(part="photodiode"), dict(housing_opacity=0.1),
             dict(explode_fraction=0.5), dict(mounted=False), dict(instrument="educational"),
             dict(instrument="obd", part="laser_x")]
    for move in moves:
        count_runs["signals"] = 0
        panel.set(**move)
        assert count_runs["signals"] == 1, move
    for action in (panel.next_step, panel.back_step):
        count_runs["signals"] = 0
        action()
        assert count_runs["signals"] == 1
    count_runs["signals"] = 0
    panel.check_step()
    assert count_runs["signals"] == 0      # the check reads the last run
    # a browser echo (less than half a slider step) runs nothing
    panel.controls["laser_x"].value = 1.0 + 1e-4
    assert count_runs["signals"] == 0


def test_scene_follows_the_panel(aligned_turns):
    rec = Recorder()
    panel = InstrumentPanel(vis=rec)
    scene = panel.scene
    assert scene is not None and scene.instrument.key == "obd"
    panel.set(laser_x=1.5)
    assert scene.knob_angles["laser_x"] == pytest.approx(1.5 * TURN)
    assert rec.log[scene.node_path("laser_x")]["transform"] is not None
    panel.set(**aligned_turns)
    s = panel.last.signals
    points, spots = scene.beam
    np.testing.assert_allclose(spots[0], scene.lever_point(*s.spot_on_lever), atol=1e-15)
    np.testing.assert_allclose(spots[1], scene.photodiode_point(*s.spot_on_detector),
                               atol=1e-15)
    panel.set(part="probe_chip")                  # the notebook: "the camera goes there"
    np.testing.assert_allclose(scene.offset[:3, 3], -scene.transform("probe_chip")[:3, 3])
    panel.set(part="photodiode")
    assert set(scene.highlighted) == {"photodiode"}
    assert "photodiode" in panel.part_html.value.lower()
    assert not np.allclose(scene.offset, np.eye(4))       # the camera went to the part
    panel.set(explode_fraction=1.0, housing_opacity=0.2)
    assert scene.fraction == 1.0 and scene.housing_opacity == pytest.approx(0.2)
    np.testing.assert_allclose(rec.log[scene.node_path("head_cover")]["transform"],
                               scene.transform("head_cover", 1.0))
    scene.animate_explode(2, back=False)          # as the notebook does; then the slider
    assert scene.fraction == 1.0                  # "the exploded view stays when it ends"
    panel.set(explode_fraction=0.0)
    assert scene.fraction == 0.0
    np.testing.assert_allclose(rec.log[scene.node_path("head_cover")]["transform"],
                               scene.transform("head_cover", 0.0))
    panel.set(approach_gap=500.0)
    assert scene.gap == pytest.approx(500e-6)
    panel.set(instrument="educational", part="active_probe")
    assert panel.scene.instrument.key == "educational" and panel.scene is not scene
    assert set(panel.scene.highlighted) == {"active_probe"}
    assert "piezoresistive" in panel.display_html.value


def test_no_scene_unless_asked():
    panel = InstrumentPanel()
    panel.set(laser_x=1.0, part="photodiode")
    assert panel.scene is None


def test_guided_setup_on_the_panel(panel, aligned_turns):
    """What notebook 05 tells the student to do, done on the panel."""
    assert panel.walkthrough.step.key == "mount"
    assert panel.check_step()
    panel.next_step()
    assert panel.last.part == "laser_x" and "laser" in panel.step_html.value
    assert not panel.check_step() and "Not yet" in panel.result_html.value
    # "turn laser_y and laser_x until SUM rises": the spot finds the lever
    panel.set(laser_y=aligned_turns["laser_y"])
    sums = []
    for turns in np.arange(0.0, aligned_turns["laser_x"] + 0.01, 0.25):
        panel.set(laser_x=float(turns))
        sums.append(panel.last.signals.sum)
    assert sums[0] < 0.01 * sums[-1] and sums[-1] > 0.9 * panel.head.best_sum
    # "walk it off the free end: SUM halves; come back until it recovers"
    panel.set(laser_x=aligned_turns["laser_x"] + 0.1)
    assert panel.last.signals.sum < 0.6 * sums[-1]
    panel.set(**{k: aligned_turns[k] for k in ("laser_x", "laser_y")})
    assert panel.check_step()
    panel.next_step()
    assert not panel.check_step()        # the photodiode is not centred yet
    panel.set(detector_vertical=aligned_turns["detector_vertical"],
              detector_lateral=aligned_turns["detector_lateral"])
    assert panel.check_step()
    panel.next_step()
    assert not panel.check_step()        # setpoint 0
    panel.set(deflection=20.0)
    assert panel.check_step()
    panel.next_step()
    assert not panel.check_step()
    panel.set(approach_gap=STEP_TOLERANCES["approach_range"].default * 1e6)
    assert panel.check_step() and panel.walkthrough.done
    panel.next_step()
    assert panel.walkthrough.step.key == "approach"
    panel.back_step()
    assert panel.walkthrough.step.key == "setpoint"


def test_on_the_slider_grid_the_photodiode_step_can_pass(panel, aligned_turns):
    step = panel.controls["detector_vertical"].step
    snapped = {k: round(v / step) * step for k, v in aligned_turns.items()}
    panel.set(**snapped)
    s = panel.last.signals
    assert abs(s.vertical_normalised) <= 0.02 and abs(s.lateral_normalised) <= 0.02


def test_errors_name_the_control(panel):
    with pytest.raises(ValueError, match="part"):
        panel.set(part="flux_capacitor")
    with pytest.raises(ValueError, match="part"):
        panel.set(instrument="educational", part="photodiode")    # not on that instrument
    with pytest.raises(ValueError, match="laser_x"):
        panel.set(laser_x=7.0)                                   # beyond the travel
    with pytest.raises(ValueError, match="instrument"):
        panel.set(instrument="stm")
    with pytest.raises(TypeError, match="unknown control"):
        panel.set(laser_z=1.0)
    assert panel.last.instrument == "obd"


def test_numbers_the_notebook_states():
    """Notebook 05 says: a laser knob's turn tilts the mirror ~0.6 deg and moves the spot ~0.4 mm;
    the waist is ~17 um; the lever is 0.19 N/m and 20 nm of setpoint is ~4 nN."""
    head = OpticalHead()
    tilt = math.degrees(math.atan(head.mirror_screw_pitch / head.mirror_arm))
    assert tilt == pytest.approx(0.6, abs=0.05)
    x0 = head.signals().spot_on_lever[0]
    x1 = head.turn("laser_x", TURN).spot_on_lever[0]
    move = (x1 - x0) * math.cos(head.holder_tilt)       # in the focal plane
    assert move == pytest.approx(0.4e-3, rel=0.05)
    assert head.waist == pytest.approx(17e-6, rel=0.05)
    k = head.lever.spring_constant
    assert k == pytest.approx(0.19, rel=0.05) and k * 20e-9 == pytest.approx(4e-9, rel=0.1)


@pytest.mark.slow
def test_instrument_pages_for_the_book(tmp_path):
    """The book's 3D pages: both instruments exported from their own views."""
    from afmsmiler.ui.pages import INSTRUMENT_PAGES, instrument_page, write_instrument_pages
    paths = write_instrument_pages(tmp_path / "pages")
    assert sorted(p.stem for p in paths) == sorted(INSTRUMENT_PAGES)
    for path in paths:
        page = path.read_text()
        assert page.lstrip().lower().startswith("<!doctype html") or "<html" in page[:500]
        assert "meshcat" in page.lower() and len(page) > 100_000
    with pytest.raises(ValueError, match="kind"):
        instrument_page("stm")


def test_browser_changes_and_buttons(count_runs, aligned_turns):
    panel = InstrumentPanel()
    count_runs["signals"] = 0
    panel.controls["instrument"].value = "educational"      # as the browser sends it
    assert count_runs["signals"] == 1 and panel.last.instrument == "educational"
    assert [v for _, v in panel.controls["part"].options][1:] == \
        [p.name for p in INSTRUMENTS["educational"].parts]
    panel.controls["part"].value = "hood"
    assert panel.last.part == "hood" and "hood" in panel.part_html.value
    panel.buttons["Next"].click()                          # the walkthrough is on the OBD head
    assert panel.walkthrough.step.key == "laser" and panel.last.instrument == "obd"
    panel.buttons["Check"].click()
    assert "Not yet" in panel.result_html.value and "laser_x" in panel.result_html.value
    panel.buttons["Back"].click()
    assert panel.walkthrough.step.key == "mount" and panel.result_html.value == ""
    box = panel.widget()
    assert panel.buttons["Check"] in box.children[0].children[1].children[1].children


def test_without_a_probe_no_light_comes_back(panel, aligned_turns):
    panel.set(**aligned_turns, mounted=False)
    assert "none mounted" in panel.display_html.value
    assert not panel.figure.lines["detector_spot"].get_visible()
    assert not panel.check_step() and "holder" in panel.result_html.value
    panel.set(mounted=True)
    assert panel.figure.lines["detector_spot"].get_visible()
    assert panel.check_step()


def test_the_spot_stays_in_view(panel, aligned_turns):
    for values in ({}, aligned_turns, dict(laser_x=-5.0, laser_y=5.0), dict(laser_x=5.0)):
        panel.set(**values)
        x, y = panel.figure.lines["lever_centre"].get_data()
        ax = panel.figure.ax_lever
        assert ax.get_xlim()[0] < x[0] < ax.get_xlim()[1], values
        assert ax.get_ylim()[0] < y[0] < ax.get_ylim()[1], values
        assert ax.get_xlim()[0] <= -0.3 * 450 and ax.get_xlim()[1] >= 1.3 * 450  # the lever


def test_walkthrough_moves_the_camera_and_highlights_in_the_scene():
    from afmsmiler.instrument.walkthrough import STEPS
    rec = Recorder()
    panel = InstrumentPanel(vis=rec)
    for step in STEPS[1:]:
        panel.next_step()
        scene = panel.scene
        first = step.parts[0]
        assert set(scene.highlighted) == {first}
        # the part's nodes were repainted with the highlight colour, and the camera target is it
        amber = [c / 255 for c in (0xff, 0xb0, 0x00)]
        painted = [k for k, v in rec.log.items() if k.startswith(scene.node_path(first) + "/")
                   and "color" in v and np.allclose(v["color"][:3], amber, atol=1e-3)]
        assert painted, first
        np.testing.assert_allclose(rec.log[scene.vis.path.lower()]["transform"][:3, 3],
                                   -scene.transform(first)[:3, 3])
    panel.back_step()
    assert set(panel.scene.highlighted) == {STEPS[-2].parts[0]}


@pytest.mark.slow  # over a second: make test runs it, make unit does not
def test_align_sets_the_knobs_where_the_manuals_procedure_ends(panel):
    """Notebook 05's one-line call: the panel runs align() from a freshly mounted head and sets
    the sliders (in turns) to its knobs; the display is then that head's, aligned."""
    run = panel.align()
    assert run.alignment
    reference = align(OpticalHead()).alignment.signals  # the same procedure, run again
    for name, angle in reference.knobs.items():
        assert panel.values()[name] == pytest.approx(angle / TURN, abs=1e-9)
    assert panel.last.signals.sum == pytest.approx(reference.sum, rel=1e-9)


def test_after_align_the_guide_goes_on_from_the_first_step_not_done(panel):
    """Run All: the panel's align() set the knobs, so the guide shows the setpoint step (the
    first not done) and says that mount, laser and photodiode are done, not step 1."""
    assert panel.walkthrough.step.key == "mount"
    panel.align()
    assert panel.walkthrough.step.key == "setpoint"
    assert "4. Set the deflection setpoint" in panel.step_html.value
    assert panel.last.part == "probe_chip"            # the step's part is picked
    text = panel.result_html.value
    for title in ("1. Mount the probe", "2. Put the laser", "3. Centre the spot"):
        assert title in text
    assert "Not yet" in text and "deflection setpoint" in text
    panel.set(deflection=20.0)
    assert panel.check_step()


def test_the_probe_description_gives_the_lever_the_optics_use():
    """The part picker's description of the OBD probe names the lever the head models (module
    (a)'s default 450 x 50 x 2 um, or the one passed), not another drawing's."""
    from afmsmiler.cantilever import Cantilever
    for lever, size in ((None, "450 x 50 x 2 um"),
                        (Cantilever.from_material("silicon", length=125e-6, width=30e-6,
                                                  thickness=4e-6), "125 x 30 x 4 um")):
        panel = InstrumentPanel() if lever is None else InstrumentPanel(lever=lever)
        panel.set(part="probe_chip")
        assert f"lever {size}" in panel.last.description
        assert len(re.findall(r"lever \d", panel.last.description)) == 1
        assert "3.4 x 1.6 mm chip" in panel.last.description


def test_knob_sliders_say_which_way_is_clockwise(panel):
    """Exercise 2 asks clockwise or counter-clockwise: each knob's slider says + is clockwise,
    and + is clockwise in the model (OpticalHead.turn: positive clockwise seen from its end;
    the exercise's checker takes clockwise as +)."""
    from afmsmiler.exercises.instrument import DIRECTIONS
    for name in KNOBS:
        assert "+ clockwise" in panel.controls[name].description
        assert "[turn]" in panel.controls[name].description
    assert DIRECTIONS["clockwise"] == 1 and "positive clockwise" in OpticalHead.turn.__doc__


def test_a_bad_deflection_moves_no_knob():
    head = OpticalHead()
    before = dict(head.knobs)
    with pytest.raises(ValueError, match="deflection"):
        head.set(laser_x=KNOBS["laser_x"].to_si(1.0), deflection=1.0)  # a metre: out of range
    assert dict(head.knobs) == before
