"""Module (e)'s two instruments in 3D, headless: scene tree, exploded view, housing, highlights,
knobs and the beam hook, checked on the recording fake (``tests/recording.py``) against the
declared tables (:data:`afmsmiler.scenes.instrument.INSTRUMENTS`), never against the scene's own
methods alone. One test (``browser``, ``viewer``, ``slow``) renders each instrument's static HTML
in headless Chromium and checks the screenshot shows it.
"""
import itertools
import math
import os
import re
import time

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from afmsmiler.parameters import Parameter
from afmsmiler.scenes.camera import camera_ndc
from afmsmiler.scenes.instrument import (DEFAULTS, INSTRUMENTS, LIMITS, PARAMETERS, SCENE_UNIT,
                                         InstrumentScene, hollow_cylinder_mesh, prism_mesh)
from tests.recording import Recorder

KINDS = list(INSTRUMENTS)
MM = 1e-3 / SCENE_UNIT  # scene units per mm (the tables are in mm)


def scene(kind="obd", **kwargs):
    rec = Recorder()
    return InstrumentScene(kind, vis=rec, **kwargs), rec


def rgba(color, opacity):
    return [((color >> 16) & 255) / 255, ((color >> 8) & 255) / 255, (color & 255) / 255,
            opacity]


def shape_nodes(part):
    """The nodes (relative to the part) that hold an object, from the part's table."""
    for s in part.shapes:
        if s.kind == "quadrants":
            yield from (f"{s.name}/q{i}" for i in range(4))
        else:
            yield s.name


# -- the scene tree --------------------------------------------------------------------------
@pytest.mark.parametrize("kind", KINDS)
def test_every_named_part_is_drawn_under_its_path(kind):
    sc, rec = scene(kind)
    parts = INSTRUMENTS[kind].parts
    names = [p.name for p in parts]
    assert sc.parts() == tuple(names) and len(set(names)) == len(names)
    for p in parts:
        path = f"/afmsmiler/instrument/{kind}/{p.group}/{p.name}"
        assert sc.node_path(p.name) == path
        for node in shape_nodes(p):
            assert "object" in rec.log[f"{path}/{node}"], (p.name, node)
        np.testing.assert_allclose(rec.log[path]["transform"][:3, 3],
                                   np.asarray(p.position_mm) * MM, atol=1e-12)
    assert len(parts) >= 18


def test_the_obd_afm_has_the_parts_the_issue_names():
    names = set(INSTRUMENTS["obd"].parts[i].name for i in range(len(INSTRUMENTS["obd"].parts)))
    assert {"base", "coarse_screw_left", "coarse_screw_right", "coarse_screw_rear",
            "piezo_tube", "sample_puck", "laser_diode", "focusing_lens", "steering_mirror",
            "cantilever_holder", "probe_chip", "photodiode", "laser_x", "laser_y",
            "detector_vertical", "detector_lateral", "head_cover"} <= names
    edu = {p.name for p in INSTRUMENTS["educational"].parts}
    assert {"active_probe", "probe_board", "piezoresistor", "heater", "xy_scanner",
            "manual_stage", "stepper_motor", "z_piezo", "controller", "hood"} <= edu


def test_proportions_are_the_stated_ones():
    obd = {p.name: p for p in INSTRUMENTS["obd"].parts}
    chip = {s.name: s for s in obd["probe_chip"].shapes}
    assert chip["chip"].size == (3.4, 1.6, 0.3)          # a standard silicon probe chip
    # the lever the optics reflect off (module (e)'s OpticalHead): 450 x 50 x 2 um, in mm
    from afmsmiler.instrument import OpticalHead
    lever = OpticalHead().lever
    assert chip["lever"].size == pytest.approx(
        (lever.length * 1e3, lever.width * 1e3, lever.thickness * 1e3), rel=1e-12)
    # the lever ends at the tip (x = 0, with the chip's 5 um overhang) and starts at the chip
    lo = chip["lever"].at[0] - chip["lever"].size[0] / 2
    assert chip["chip"].at[0] + chip["chip"].size[0] / 2 == pytest.approx(lo, abs=1e-9)
    assert obd["piezo_tube"].shapes[0].size == (12.7, 10.7, 60)
    assert obd["sample_puck"].shapes[0].size == (15, 0.8)
    # the probe's tip apex is the origin, touching the top of the sample
    top = obd["sample_puck"].shapes[1]
    assert top.at[2] + top.size[2] / 2 == pytest.approx(0.0)


def test_the_module_docstring_states_every_part_s_dimensions():
    import afmsmiler.instrument.assembly as module  # the model holds the tables
    for inst in INSTRUMENTS.values():
        for p in inst.parts:
            assert re.search(rf"^{p.name} +{re.escape(p.dimensions)}$", module.__doc__,
                             re.MULTILINE), p.name


def test_describe_and_the_table():
    sc, _ = scene()
    text = sc.describe("steering_mirror")
    p = sc.part("steering_mirror")
    assert text.startswith("steering mirror: ") and p.description in text
    assert p.dimensions in text
    rows = sc.table()
    assert [r[0] for r in rows] == list(sc.parts())
    assert all(r[2] and r[3] for r in rows)
    html = sc.table_html()
    assert html.count("<tr>") == len(rows) + 1 and "four-quadrant photodiode" in html


def test_pick_highlights_one_part_and_returns_its_description():
    sc, rec = scene()
    sc.highlight("base")
    assert sc.pick("photodiode") == sc.describe("photodiode")
    assert set(sc.highlighted) == {"photodiode"}
    assert rec.log[f"{sc.node_path('base')}/body"]["color"] == pytest.approx(
        rgba(sc.part("base").shapes[0].color, 1.0))
    sc.pick("laser_diode", focus=True)
    np.testing.assert_allclose(rec.log["/afmsmiler/instrument/obd"]["transform"][:3, 3],
                               -sc.part("laser_diode").position / SCENE_UNIT)


@pytest.mark.parametrize("call", [
    lambda sc: sc.describe("laser"), lambda sc: sc.part("Base"), lambda sc: sc.highlight("x"),
    lambda sc: sc.unhighlight("nope"), lambda sc: sc.transform("lens"),
    lambda sc: sc.focus("camera"), lambda sc: sc.node_path(""), lambda sc: sc.pick("tip"),
])
def test_an_unknown_part_is_a_value_error_listing_the_valid_ones(call):
    sc, _ = scene()
    with pytest.raises(ValueError, match=r"part must be one of \[.*'focusing_lens'.*"
                                         r"'steering_mirror'.*\], got"):
        call(sc)


def test_an_unknown_instrument_and_bad_settings_are_errors():
    with pytest.raises(ValueError, match=r"kind must be one of \['educational', 'obd'\]"):
        InstrumentScene("multimode", vis=Recorder())
    with pytest.raises(ValueError, match=r"housing_opacity must be in \[0, 1\], got 2"):
        InstrumentScene("obd", vis=Recorder(), housing_opacity=2)


# -- the exploded view ------------------------------------------------------------------------
@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("fraction", [0.0, 0.25, 0.5, 1.0])
def test_explode_moves_each_part_along_its_declared_direction(kind, fraction):
    sc, rec = scene(kind)
    sc.explode(fraction)
    assert sc.fraction == fraction
    for p in INSTRUMENTS[kind].parts:
        t = rec.log[sc.node_path(p.name)]["transform"]
        expected = (np.asarray(p.position_mm) + fraction * np.asarray(p.explode_mm)) * MM
        np.testing.assert_allclose(t[:3, 3], expected, atol=1e-9, err_msg=p.name)
        # the direction and distance it declares, and only a translation: no turn
        moved = t[:3, 3] - np.asarray(p.position_mm) * MM
        if fraction > 0:
            np.testing.assert_allclose(np.linalg.norm(moved),
                                       fraction * p.explode_distance / SCENE_UNIT, rtol=1e-12)
            np.testing.assert_allclose(moved / np.linalg.norm(moved), p.explode_direction,
                                       atol=1e-12)
        np.testing.assert_allclose(t[:3, :3], p.rotation, atol=1e-12)


def test_every_part_moves_in_the_exploded_view():
    for inst in INSTRUMENTS.values():
        for p in inst.parts:
            assert p.explode_distance > 0.0, p.name
            assert np.linalg.norm(p.explode_direction) == pytest.approx(1.0)


@pytest.mark.parametrize("bad", [-0.01, 1.01, math.nan, math.inf, "half", None])
def test_explode_outside_zero_one_is_rejected(bad):
    sc, rec = scene()
    n = len(rec.calls)
    with pytest.raises((ValueError, TypeError), match="explode_fraction"):
        sc.explode(bad)
    assert len(rec.calls) == n and sc.fraction == 0.0


def test_the_animation_runs_assembled_exploded_assembled():
    sc, rec = scene()
    frames = 10
    anim = sc.animate_explode(frames, fps=20)
    assert rec.log["animation"] is anim and anim.default_framerate == 20
    f = sc.fractions(frames)
    assert f[0] == 0 and f[frames] == pytest.approx(1) and f[-1] == pytest.approx(0)
    assert np.all(np.diff(f[:frames + 1]) > 0)  # monotonic out, then back
    clips = {path.lower(): clip for path, clip in anim.clips.items()}
    for p in INSTRUMENTS["obd"].parts:
        clip = clips[sc.node_path(p.name)]
        keys = clip.tracks["position"]
        assert list(keys.frames) == list(range(2 * frames + 1))
        for k in (0, 3, frames, 2 * frames):
            expected = (np.asarray(p.position_mm) + f[k] * np.asarray(p.explode_mm)) * MM
            np.testing.assert_allclose(keys.values[k], expected, atol=1e-9)
    assert sc.fraction == 0.0  # where the animation ends
    sc.animate_explode(4, back=False)
    assert sc.fraction == 1.0


@pytest.mark.parametrize("kwargs, match", [
    (dict(frames=1), "frames must be"), (dict(frames=LIMITS["frames"] + 1), "frames must be"),
    (dict(frames=10, fps=0), "fps must be"), (dict(frames=10, repetitions=0), "repetitions"),
    (dict(frames=2.5), "frames must be"),
])
def test_animation_bounds(kwargs, match):
    sc, rec = scene()
    with pytest.raises(ValueError, match=match):
        sc.animate_explode(**kwargs)
    assert "animation" not in rec.log


@pytest.mark.slow
def test_the_longest_animation_stays_within_the_transform_budget():
    sc, _ = scene("obd")
    anim = sc.animate_explode(LIMITS["frames"], back=False, play=False)
    n = sum(len(c.tracks["position"].frames) for c in anim.clips.values())
    assert n <= LIMITS["animation_transforms"]


@pytest.mark.parametrize("kind", KINDS)
def test_the_coarse_approach_lifts_the_probe_and_its_carrier_only(kind):
    sc, rec = scene(kind)
    lifted = set(INSTRUMENTS[kind].approach_parts)
    probe = INSTRUMENTS[kind].lever[0]
    assert probe in lifted and "base" not in lifted and "base_plate" not in lifted
    sc.set_gap(2e-3)
    for p in INSTRUMENTS[kind].parts:
        z = rec.log[sc.node_path(p.name)]["transform"][2, 3]
        lift = 2e-3 / SCENE_UNIT if p.name in lifted else 0.0
        assert z == pytest.approx(p.position_mm[2] * MM + lift, abs=1e-12), p.name
    if INSTRUMENTS[kind].beam:  # the beam goes with the head
        assert rec.log[f"/afmsmiler/instrument/{kind}/beam"]["transform"][2, 3] == \
            pytest.approx(2e-3 / SCENE_UNIT)
    with pytest.raises(ValueError, match=r"approach_gap must be in \[0, 0.01\] m"):
        sc.set_gap(-1e-6)
    assert sc.gap == 2e-3


# -- housing and highlighting -----------------------------------------------------------------
@pytest.mark.parametrize("kind", KINDS)
def test_housing_opacity_reaches_only_the_housing(kind):
    sc, rec = scene(kind)
    housing = [p for p in INSTRUMENTS[kind].parts if p.housing]
    assert housing
    sc.set_housing_opacity(0.2)
    for p in INSTRUMENTS[kind].parts:
        path = sc.node_path(p.name)
        for shape in p.shapes:
            node = rec.log.get(f"{path}/{shape.name}", {})
            if p.housing:
                assert node["color"] == pytest.approx(rgba(shape.color, 0.2))
                assert rec.log[path]["visible"] is True
            else:
                assert "color" not in node, p.name
    sc.set_housing_opacity(0)
    assert all(rec.log[sc.node_path(p.name)]["visible"] is False for p in housing)
    sc.set_housing_opacity(1)
    assert all(rec.log[sc.node_path(p.name)]["visible"] is True for p in housing)


@pytest.mark.parametrize("bad", [-0.1, 1.5, math.nan])
def test_housing_opacity_outside_zero_one_is_rejected(bad):
    sc, _ = scene()
    with pytest.raises(ValueError, match=r"housing_opacity must be in \[0, 1\]"):
        sc.set_housing_opacity(bad)
    assert sc.housing_opacity == PARAMETERS["housing_opacity"].default


def test_highlight_paints_the_part_and_unhighlight_restores_its_table_colours():
    sc, rec = scene()
    part = sc.part("steering_mirror")
    path = sc.node_path("steering_mirror")
    sc.highlight("steering_mirror")
    for s in part.shapes:
        assert rec.log[f"{path}/{s.name}"]["color"] == pytest.approx(
            rgba(DEFAULTS["highlight"], 1.0))
    assert "color" not in rec.log[f"{sc.node_path('focusing_lens')}/glass"]  # others untouched
    sc.unhighlight("steering_mirror")
    for s in part.shapes:
        assert rec.log[f"{path}/{s.name}"]["color"] == pytest.approx(rgba(s.color, s.opacity))
    assert sc.highlighted == {}


def test_highlight_of_parts_drawn_by_module_b_and_of_the_housing():
    sc, rec = scene()
    # the photodiode's quadrants come from module (b)'s quadrant_photodiode: their colours
    # (two shades, as drawn there) come back after the highlight
    path = sc.node_path("photodiode")
    before = sc.colors("photodiode")
    assert {f"cell/q{i}" for i in range(4)} <= set(before)
    assert len({before[f"cell/q{i}"][0] for i in range(4)}) == 2
    sc.highlight("photodiode", 0x00ff00)
    assert rec.log[f"{path}/cell/q1"]["color"] == pytest.approx(rgba(0x00ff00, 1.0))
    sc.unhighlight()
    for i in range(4):
        assert rec.log[f"{path}/cell/q{i}"]["color"] == pytest.approx(
            rgba(*before[f"cell/q{i}"]))
    # a highlighted housing keeps the housing's opacity
    sc.set_housing_opacity(0.3)
    sc.highlight("head_cover")
    assert rec.log[f"{sc.node_path('head_cover')}/cover"]["color"][3] == pytest.approx(0.3)
    with pytest.raises(ValueError, match="color must be"):
        sc.highlight("base", 0x1000000)


# -- hooks for the alignment model: knobs and the beam ---------------------------------------
def test_knobs_turn_about_their_declared_axes():
    sc, rec = scene()
    assert set(sc.knobs()) == {"laser_x", "laser_y", "detector_vertical", "detector_lateral"}
    for name, angle in (("laser_x", 0.7), ("detector_lateral", -2.0), ("laser_y", 3.0)):
        sc.turn_knob(name, angle)
        p = sc.part(name)
        t = rec.log[sc.node_path(name)]["transform"]
        turn = t[:3, :3] @ p.rotation.T      # the turn on top of the resting orientation
        rotvec = Rotation.from_matrix(turn).as_rotvec()
        np.testing.assert_allclose(rotvec, angle * np.asarray(p.axis, float), atol=1e-9)
        np.testing.assert_allclose(t[:3, 3], np.asarray(p.position_mm) * MM, atol=1e-12)
    sc.explode(0.5)  # a turned knob keeps its turn while it moves
    t = rec.log[sc.node_path("laser_x")]["transform"]
    np.testing.assert_allclose(Rotation.from_matrix(t[:3, :3]).as_rotvec(), [0, 0, 0.7],
                               atol=1e-9)
    assert scene("educational")[0].knobs() == ()


def test_a_knob_outside_its_range_or_unknown_is_an_error():
    sc, _ = scene()
    with pytest.raises(ValueError, match=r"knob must be one of \['detector_lateral', "
                                         r"'detector_vertical', 'laser_x', 'laser_y'\], "
                                         r"got 'base'"):
        sc.turn_knob("base", 0.1)
    with pytest.raises(ValueError, match=r"knob_angle must be in \[-62.8\d*, 62.8\d*\] rad"):
        sc.turn_knob("laser_x", 100.0)
    assert sc.knob_angles["laser_x"] == 0.0
    with pytest.raises(ValueError, match="knob_angle must be"):
        sc.set_knobs(laser_y=0.5, laser_x=-100.0)
    assert sc.knob_angles["laser_y"] == 0.0  # nothing turned
    sc.set_knobs(laser_y=0.5, detector_vertical=-0.25)
    assert sc.knob_angles == dict(laser_x=0.0, laser_y=0.5, detector_vertical=-0.25,
                                  detector_lateral=0.0)


def _leg_ends(t):
    """Ends of a unit cylinder along y (meshcat's) under transform t."""
    return [(t @ [0.0, s, 0.0, 1.0])[:3] for s in (-0.5, 0.5)]


def test_show_beam_draws_given_points_and_spots():
    sc, rec = scene()
    pts = np.array([[-0.01, 0.0, 0.04], [-0.005, 0.001, 0.02], [0.0, 0.0, 0.0],
                    [0.02, 0.0, 0.03]])
    spots = np.array([[0.0, 0.0, 0.0], [0.03, 0.002, 0.028]])
    sc.show_beam(pts, spots, spot_radius=1e-3)
    beam = "/afmsmiler/instrument/obd/beam"
    for i in range(3):
        a, b = _leg_ends(rec.log[f"{beam}/leg{i:02d}"]["transform"])
        np.testing.assert_allclose(a, pts[i] / SCENE_UNIT, atol=1e-9)
        np.testing.assert_allclose(b, pts[i + 1] / SCENE_UNIT, atol=1e-9)
    # the nominal beam had 4 legs: the fourth is hidden now
    assert rec.log[f"{beam}/leg03"]["visible"] is False
    for i, s in enumerate(spots):
        t = rec.log[f"{beam}/spot{i}"]["transform"]
        np.testing.assert_allclose(t[:3, 3], s / SCENE_UNIT, atol=1e-12)
        np.testing.assert_allclose(np.diag(t)[:3], 1e-3 / SCENE_UNIT)
    np.testing.assert_array_equal(sc.beam[0], pts)
    n_objects = sum(v.get("n_objects", 0) for k, v in rec.log.items() if k.startswith(beam))
    sc.show_beam(pts[:2] + 1e-3, spots[:1])  # in place: no new objects
    assert sum(v.get("n_objects", 0) for k, v in rec.log.items()
               if k.startswith(beam)) == n_objects
    assert rec.log[f"{beam}/spot1"]["visible"] is False
    # drawn for the assembled instrument: hidden while exploded
    sc.explode(0.4)
    assert rec.log[beam]["visible"] is False
    sc.explode(0.0)
    assert rec.log[beam]["visible"] is True


@pytest.mark.parametrize("points, spots, match", [
    ([[0, 0, 0]], (), r"points must have shape \(N, 3\) with 2 <= N"),
    ([[0, 0], [1e-3, 0]], (), r"points must have shape \(N, 3\)"),
    (np.zeros((LIMITS["beam_points"] + 1, 3)), (), "points must have shape"),
    ([[0, 0, 0], [0, 0, 45.0]], (), r"points must be in m within 1.0 m of the tip, got a "
                                    r"coordinate of 45 \(mm given as m\?\)"),
    ([[0, 0, 0], [0, 0, math.nan]], (), "points must"),
    ([[0, 0, 0], [0, 0, 0.01]], [[0, 0]], r"spots must have shape"),
    ([[0, 0, 0], [0, 0, 0.01]], np.zeros((LIMITS["spots"] + 1, 3)), "spots must have shape"),
])
def test_bad_beams_are_rejected(points, spots, match):
    sc, _ = scene()
    with pytest.raises(ValueError, match=match):
        sc.show_beam(points, spots)


def test_no_beam_on_the_active_probe_afm_and_bad_spot_radius():
    edu, _ = scene("educational")
    with pytest.raises(ValueError, match="has no laser beam"):
        edu.show_beam([[0, 0, 0], [0, 0, 0.01]])
    with pytest.raises(ValueError, match="has no laser beam"):
        edu.nominal_beam()
    assert edu.anchors == {}
    sc, _ = scene()
    with pytest.raises(ValueError, match="spot_radius must be"):
        sc.show_beam([[0, 0, 0], [0, 0, 0.01]], spot_radius=0.5)


def test_the_nominal_beam_joins_the_drawn_optics_by_the_law_of_reflection():
    sc, _ = scene()
    a = sc.anchors
    obd = {p.name: p for p in INSTRUMENTS["obd"].parts}
    for anchor, part in (("laser", "laser_diode"), ("lens", "focusing_lens"),
                         ("mirror", "steering_mirror"), ("photodiode", "photodiode")):
        np.testing.assert_allclose(a[anchor], obd[part].position, atol=1e-15)
    # reflection at the lever end: the lever tilts 12 degrees, so its normal is
    # (sin 12, 0, cos 12) and the angle of incidence equals the angle of reflection
    n = np.array([math.sin(math.radians(12)), 0.0, math.cos(math.radians(12))])
    to_laser = a["laser"] - a["lever_end"]
    to_mirror = a["mirror"] - a["lever_end"]
    cos_in = to_laser @ n / np.linalg.norm(to_laser)
    cos_out = to_mirror @ n / np.linalg.norm(to_mirror)
    assert cos_in == pytest.approx(cos_out, abs=1e-3)
    assert np.cross(to_laser, n) @ np.cross(to_mirror, n) < 0  # on opposite sides of n
    # the lens on the incident beam, the mirror's normal bisecting the fold
    d = to_laser / np.linalg.norm(to_laser)
    off = (a["lens"] - a["lever_end"]) - ((a["lens"] - a["lever_end"]) @ d) * d
    assert np.linalg.norm(off) < 1e-4
    m = np.asarray(obd["steering_mirror"].axis)
    u_in = to_mirror / np.linalg.norm(to_mirror)   # travelling from the lever to the mirror
    u_out = (a["photodiode"] - a["mirror"]) / np.linalg.norm(a["photodiode"] - a["mirror"])
    np.testing.assert_allclose(u_in - 2 * (u_in @ m) * m, u_out, atol=1e-3)
    pts, spots = sc.nominal_beam()
    assert pts.shape == (5, 3) and spots.shape == (2, 3)


@pytest.mark.parametrize("kind", KINDS)
def test_points_on_the_lever_are_on_its_drawn_top_face(kind):
    sc, _ = scene(kind)
    part_name, _, length_mm = INSTRUMENTS[kind].lever
    part = sc.part(part_name)
    lever = next(s for s in part.shapes if s.name == "lever")
    # the lever's box in the part's frame (mm): its top face, clamp end and free end
    top = lever.at[2] + lever.size[2] / 2
    clamp_x, free_x = lever.at[0] - lever.size[0] / 2, lever.at[0] + lever.size[0] / 2
    assert lever.size[0] == pytest.approx(length_mm)
    for x_mm, y_mm, local_x in ((0.0, 0.0, clamp_x), (length_mm, 0.0, free_x),
                                (length_mm / 2, lever.size[1] / 2, (clamp_x + free_x) / 2)):
        local = np.array([local_x, y_mm, top]) * 1e-3
        expected = part.position + Rotation.align_vectors([part.axis], [[0, 0, 1]])[0].apply(
            local)
        np.testing.assert_allclose(sc.lever_point(x_mm * 1e-3, y_mm * 1e-3), expected,
                                   atol=1e-12)
    with pytest.raises(ValueError, match="x must be"):
        sc.lever_point(0.5)


def test_points_on_the_photodiode():
    sc, _ = scene()
    np.testing.assert_allclose(sc.photodiode_point(0.0), sc.anchors["photodiode"])
    p = sc.photodiode_point(1e-3, -0.5e-3) - sc.anchors["photodiode"]
    np.testing.assert_allclose(p, [0.0, -0.5e-3, 1e-3], atol=1e-15)
    assert p @ np.asarray(sc.part("photodiode").axis) == pytest.approx(0.0)  # in its face
    with pytest.raises(ValueError, match="lateral must be"):
        sc.photodiode_point(0.0, math.nan)
    with pytest.raises(ValueError, match="has no photodiode"):
        scene("educational")[0].photodiode_point(0.0)


def test_show_alignment_draws_the_beam_through_the_model_s_spots():
    sc, rec = scene()
    beam = "/afmsmiler/instrument/obd/beam"
    pts = sc.show_alignment((100e-6, 5e-6), (0.4e-3, -0.2e-3),
                            knobs=dict(laser_x=0.3, detector_vertical=-1.0))
    assert sc.knob_angles["laser_x"] == 0.3 and sc.knob_angles["detector_vertical"] == -1.0
    a = sc.anchors
    np.testing.assert_allclose(pts, [a["laser"], a["lens"], sc.lever_point(100e-6, 5e-6),
                                     a["mirror"], sc.photodiode_point(0.4e-3, -0.2e-3)])
    a0, b0 = _leg_ends(rec.log[f"{beam}/leg02"]["transform"])  # lever -> mirror
    np.testing.assert_allclose(a0, pts[2] / SCENE_UNIT, atol=1e-9)
    np.testing.assert_allclose(rec.log[f"{beam}/spot1"]["transform"][:3, 3],
                               pts[4] / SCENE_UNIT, atol=1e-12)
    missed = sc.show_alignment((-0.5e-3, 0.0), (0.0, 0.0), reflected=False)
    assert len(missed) == 3                       # no light comes back
    assert rec.log[f"{beam}/leg02"]["visible"] is False
    assert rec.log[f"{beam}/spot1"]["visible"] is False
    with pytest.raises(ValueError, match="spot_on_lever must"):
        sc.show_alignment((0.0,), (0.0, 0.0))
    with pytest.raises(ValueError, match="knob must be one of"):
        sc.show_alignment((0.0, 0.0), (0.0, 0.0), knobs=dict(mirror=1.0))
    with pytest.raises(ValueError, match="has no laser beam"):
        scene("educational")[0].show_alignment((0.0, 0.0), (0.0, 0.0))


# -- camera ---------------------------------------------------------------------------------------
def _shape_corners(shape):
    """The 8 corners (mm, part frame) of a box around ``shape``, from its table entry."""
    size = np.asarray(shape.size, float)
    signs = np.array(list(itertools.product((-1, 1), repeat=3)), float)
    if shape.kind == "wire":
        return np.concatenate([np.asarray(q, float) + signs * size[0] / 2 for q in shape.points])
    half = {"box": size / 2, "ellipsoid": size / 2, "sphere": np.full(3, size[0] / 2),
            "quadrants": np.array([size[0] / 2, size[0] / 2, 0.05])}.get(
        shape.kind, np.array([size[0] / 2, size[0] / 2, size[-1] / 2]))  # round: (d, ..., L)
    rot = np.eye(3) if shape.kind in ("box", "sphere") else Rotation.align_vectors(
        [shape.axis], [[0.0, 0.0, 1.0]])[0].as_matrix()   # z to the axis (scipy)
    return np.asarray(shape.at, float) + (rot @ (signs * half).T).T


def _corners(sc, fraction, names=None):
    """World positions (scene units, as shown) of the corners of every shape's box."""
    out = []
    for name in names or sc.parts():
        t = sc.offset @ sc.transform(name, fraction)
        for s in sc.part(name).shapes:
            pts = _shape_corners(s) * MM
            out.append(pts @ t[:3, :3].T + t[:3, 3])
    return np.concatenate(out)


def _boxes(sc, fraction):
    return {n: (_corners(sc, fraction, [n]).min(0), _corners(sc, fraction, [n]).max(0))
            for n in sc.parts()}


@pytest.mark.parametrize("kind", KINDS)
def test_the_exploded_view_separates_every_part(kind):
    sc, _ = scene(kind)

    def overlapping(boxes):
        return [(a, b) for a, b in itertools.combinations(boxes, 2)
                if np.all(boxes[a][0] < boxes[b][1]) and np.all(boxes[b][0] < boxes[a][1])]

    assert len(overlapping(_boxes(sc, 0.0))) > 10  # assembled, parts sit in and on each other
    assert overlapping(_boxes(sc, 1.0)) == []      # exploded, no two parts' boxes overlap


@pytest.mark.parametrize("kind", KINDS)
def test_the_cameras_frame_the_assembled_and_the_exploded_instrument(kind):
    sc, rec = scene(kind)
    inst = INSTRUMENTS[kind]
    cam = np.asarray(inst.camera_mm) * MM
    ndc = camera_ndc(_corners(sc, 0.0), cam)
    assert np.abs(ndc).max() < 1.0
    assert np.abs(ndc[:, 1]).max() > 0.5  # and fills a good part of the view
    assert rec.log["/Cameras/default/rotated/<object>"]["position"] == pytest.approx(
        [cam[0], cam[2], -cam[1]])
    assert rec.log["/Grid"]["visible"] is False
    sc.exploded_view()
    ndc = camera_ndc(_corners(sc, 1.0), np.asarray(inst.exploded_camera_mm) * MM)
    assert np.abs(ndc).max() < 1.0


def test_focus_brings_a_part_to_the_camera_target_and_back():
    sc, rec = scene()
    sc.focus("probe_chip", 0.02)
    root = rec.log["/afmsmiler/instrument/obd"]["transform"]
    np.testing.assert_allclose(root[:3, 3], -sc.transform("probe_chip")[:3, 3], atol=1e-12)
    cam = np.asarray(rec.log["/Cameras/default/rotated/<object>"]["position"])
    assert np.linalg.norm(cam) == pytest.approx(0.02 / SCENE_UNIT)
    x, z, minus_y = cam   # three.js is y-up
    direction = np.asarray(DEFAULTS["focus_direction"], float)
    np.testing.assert_allclose([x, -minus_y, z], 0.02 / SCENE_UNIT * direction
                               / np.linalg.norm(direction))
    sc.focus()
    np.testing.assert_allclose(rec.log["/afmsmiler/instrument/obd"]["transform"][:3, 3],
                               -np.asarray(INSTRUMENTS["obd"].centre_mm) * MM)
    with pytest.raises(ValueError, match="distance must be"):
        sc.focus("base", 2.0)


# -- updates in place -----------------------------------------------------------------------------
def test_each_action_sends_only_what_it_changes():
    sc, rec = scene()
    n_parts = len(sc.parts())

    def sent(action):
        start = len(rec.calls)
        action()
        return [c[0] for c in rec.calls[start:]]

    calls = sent(lambda: sc.explode(0.5))  # one transform per part, the beam hidden once
    assert calls.count("set_transform") == n_parts and "set_object" not in calls
    assert calls.count("set_property") == 1
    assert sent(lambda: sc.explode(0.6)).count("set_property") == 0
    assert sent(lambda: sc.turn_knob("laser_x", 1.0)) == ["set_transform"]
    n_shapes = len(sc.part("steering_mirror").shapes)
    assert sent(lambda: sc.highlight("steering_mirror")) == ["set_property"] * n_shapes
    housing = [p for p in INSTRUMENTS["obd"].parts if p.housing]
    calls = sent(lambda: sc.set_housing_opacity(0.5))
    assert calls == ["set_property"] * sum(len(p.shapes) + 1 for p in housing)
    assert "set_object" not in sent(lambda: sc.show_beam(*sc.nominal_beam()))


def test_parameters_make_sliders():
    from afmsmiler.ui.controls import control
    for p in PARAMETERS.values():
        slider = control(p)
        assert p.to_si(slider.value) == pytest.approx(p.default)
    assert control(PARAMETERS["knob_angle"]).max == pytest.approx(3600.0)  # degrees shown


# -- generated meshes and parameters ---------------------------------------------------------
def test_hollow_cylinder_mesh():
    v, f = hollow_cylinder_mesh(2.0, 1.5, 4.0, sides=12)
    r = np.hypot(v[:, 0], v[:, 1])
    assert sorted(set(np.round(r, 6))) == [1.5, 2.0]
    assert set(np.round(v[:, 2], 6)) == {-2.0, 2.0}
    assert f.shape == (8 * 12, 3) and f.max() == len(v) - 1
    # closed surface: every edge is shared by exactly two triangles
    edges = np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1)
    _, counts = np.unique(edges, axis=0, return_counts=True)
    assert np.all(counts == 2)
    with pytest.raises(ValueError, match="inner_radius must be below outer_radius"):
        hollow_cylinder_mesh(1.0, 1.0, 1.0)
    with pytest.raises(ValueError, match="sides must be"):
        hollow_cylinder_mesh(2.0, 1.0, 1.0, sides=2)


def test_prism_mesh():
    square = [[1, 1], [-1, 1], [-1, -1], [1, -1]]
    v, f = prism_mesh(square, 2.0)
    assert v.shape == (10, 3) and f.shape == (16, 3)
    edges = np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1)
    _, counts = np.unique(edges, axis=0, return_counts=True)
    assert np.all(counts == 2)
    # its volume (divergence theorem over the triangles) is the square's area x length
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    assert abs(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6) == pytest.approx(8.0)
    with pytest.raises(ValueError, match="outline must have shape"):
        prism_mesh([[0, 0], [1, 1]], 1.0)


def test_parameters_describe_the_settings():
    assert all(isinstance(p, Parameter) for p in PARAMETERS.values())
    assert PARAMETERS["knob_angle"].unit == "rad"
    assert PARAMETERS["housing_opacity"].low == 0 and PARAMETERS["housing_opacity"].high == 1


# -- a real browser -------------------------------------------------------------------------
CHROMIUM = os.environ.get("AFMSMILER_CHROMIUM", "/usr/bin/chromium")


def _screenshot(browser, html, path):
    path.write_text(html, encoding="utf-8")
    page = browser.new_page(viewport={"width": 900, "height": 600})
    try:
        page.goto(path.as_uri())
        page.wait_for_selector("canvas", timeout=30_000)
        from io import BytesIO
        from PIL import Image

        def shot():
            return np.asarray(Image.open(BytesIO(page.screenshot())).convert("RGB"), float)

        # drawn once the canvas shows something (not one colour) and two shots 0.5 s apart
        # agree (a loaded machine drew a page after a fixed 2.5 s wait only some of the time:
        # the shot of a blank page differed everywhere); a wait for the drawing, bounded, not a
        # check of its speed
        # (below meshcat's "Open Controls" bar, 20 px of page over the canvas: with it, a canvas
        # not yet drawn, one colour, was not one colour, and a CI run compared a blank shot)
        box = page.locator("canvas").first.bounding_box()
        rows = slice(int(box["y"]) + 40, int(box["y"] + box["height"]))
        cols = slice(int(box["x"]), int(box["x"] + box["width"]))
        page.wait_for_timeout(500)
        last, deadline = shot(), time.monotonic() + 30.0
        while time.monotonic() < deadline:
            page.wait_for_timeout(500)
            now = shot()
            if np.array_equal(now, last) and np.ptp(now[rows, cols]) > 0:
                return now
            last = now
        return last
    finally:
        page.close()


@pytest.mark.slow
@pytest.mark.browser
def test_static_html_of_each_instrument_shows_it_in_chromium(tmp_path):
    if not os.access(CHROMIUM, os.X_OK):
        pytest.skip(f"no browser at {CHROMIUM} (make test installs Debian's chromium as root)")
    sync_api = pytest.importorskip("playwright.sync_api")
    pages = {}
    for kind in KINDS:
        sc = InstrumentScene(kind)
        pages[kind] = sc.static_html()
        sc.vis.delete()
    pages["empty"] = sc.static_html()  # the same camera and background, no instrument
    with sync_api.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, headless=True,
                                    args=["--no-sandbox", "--use-gl=swiftshader",
                                          "--enable-unsafe-swiftshader"])
        try:
            empty_html = pages.pop("empty")
            empty = _screenshot(browser, empty_html, tmp_path / "empty.html")
            for kind, html in pages.items():
                # a shot that fails is taken again with the empty scene's, twice at most: on a
                # loaded CI machine a stable, not one-colour canvas was once not yet the drawn
                # scene (every edge differed from the empty scene's); a scene drawn wrongly
                # fails all three
                for attempt in range(3):
                    if attempt:
                        empty = _screenshot(browser, empty_html, tmp_path / "empty.html")
                    img = _screenshot(browser, html, tmp_path / f"{kind}.html")
                    failure = _instrument_shot_failure(kind, img, empty)
                    if failure is None:
                        break
                assert failure is None, failure
        finally:
            browser.close()


def _instrument_shot_failure(kind, img, empty):
    """What is wrong with ``img``, the shot of instrument ``kind``'s page (``empty``: the same
    camera and background, no instrument), or None."""
    sc, _ = scene(kind)   # the same scene, recorded: where each part lands on the screen
    drawn = np.abs(img - empty).max(axis=2) > 24   # pixels the instrument changed
    h, w = drawn.shape
    if not drawn.mean() > 0.10:
        return f"{kind}: only {drawn.mean():.1%} of the frame drawn"
    rows, cols = np.nonzero(drawn)
    # spread over the frame: the drawing spans much of its height and width ...
    if not (np.ptp(rows) > 0.5 * h and np.ptp(cols) > 0.3 * w):
        return f"{kind}: drawn over rows {np.ptp(rows)} of {h}, columns {np.ptp(cols)} of {w}"
    # ... and is in view: not cut off by more than a sliver at any edge
    edges = [drawn[:3].mean(), drawn[-3:].mean(), drawn[:, :3].mean(), drawn[:, -3:].mean()]
    if not max(edges) < 0.2:
        return f"{kind}: cut at the frame's edge ({edges})"
    # every part is in view: drawn pixels where its centre is projected
    cam = np.asarray(INSTRUMENTS[kind].camera_mm) * MM
    missing = []
    for name in sc.parts():
        centre = (sc.offset @ sc.transform(name))[:3, 3]
        x, y = camera_ndc([centre], cam, aspect=w / h)[0]
        if not (abs(x) < 1 and abs(y) < 1):
            return f"{kind}: {name} projected out of view at {(x, y)}"
        col, row = int((x + 1) / 2 * w), int((1 - y) / 2 * h)
        if not drawn[max(row - 4, 0):row + 5, max(col - 4, 0):col + 5].any():
            missing.append(name)
    return f"{kind}: nothing drawn where these parts are: {missing}" if missing else None


@pytest.mark.parametrize("kind", KINDS)
def test_the_see_through_housing_writes_no_depth(kind):
    # a translucent housing that writes depth hides its own back faces in stripes (z-fighting)
    # and the parts inside it; every other part keeps its depth
    sc, rec = scene(kind)
    housing = {p.name for p in INSTRUMENTS[kind].parts if p.housing}
    assert housing
    for path, node in rec.log.items():
        if "object" not in node or node["object"][1] is None:
            continue
        part = next((n for n in housing if f"/{n}/" in path + "/"), None)
        depth_write = node["object"][1].properties.get("depthWrite", True)
        assert depth_write is (part is None), path


def test_at_the_lever_the_schematic_beam_is_hidden_and_the_view_says_why():
    # the beam is drawn 0.7 mm thick: at the lever (50 um wide) it covered the lever entirely
    from afmsmiler.scenes import SceneView
    view = SceneView()
    sc = InstrumentScene("obd", vis=view.vis)
    beam = sc.vis["beam"].path.lower()
    sc.focus("probe_chip")
    assert not sc._beam_visible and "laser beam not drawn here" in view.legend
    assert "0.7 mm" in view.legend  # the drawn thickness, from DEFAULTS
    sc.show_beam(*sc.nominal_beam())  # a new beam while there stays hidden
    assert not sc._beam_visible
    sc.focus()  # back to the whole instrument: the beam again, the note gone
    assert sc._beam_visible and "laser beam" not in view.legend
    hidden = [c for c in view.state.keys() if c[1] == beam and c[2] == "visible"]
    assert hidden  # the browser was told
