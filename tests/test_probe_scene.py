"""Module (a)'s "your probe" 3D view (afmsmiler.scenes.probe): the plan view as a slab, twisted.

The mesh is checked against the lever's own geometry: its top face covers the plan-view area
(the closed forms of :attr:`afmsmiler.planform.Lever.area`), its bounding box is the lever's, and
a section turned by the twist is the untwisted one rotated about the long axis (a rotation
matrix, written here); the drawn tip's apex moves sideways by (h_tip + t/2) sin(drawn twist).
"""
import math

import numpy as np
import pytest

from afmsmiler.modes.lateral import LATERAL_FORCE, LateralLever
from afmsmiler.planform import Lever, preset
from afmsmiler.probe import half_widths, planform_outline
from afmsmiler.scenes.camera import camera_ndc
from afmsmiler.scenes.probe import SCENE_UNIT, ProbeScene, lever_mesh
from tests.recording import Recorder

LEVERS = ["ContAl-G", "AC160TS", "MLCT-E"]   # a rectangle, a pointed end, a V


def _top_area(verts, faces, t):
    tri = verts[faces]
    top = np.all(np.isclose(tri[:, :, 2], t / 2, rtol=0, atol=1e-15), axis=1)
    a, b, c = tri[top, 0, :2], tri[top, 1, :2], tri[top, 2, :2]
    cross = (b - a)[:, 0] * (c - a)[:, 1] - (b - a)[:, 1] * (c - a)[:, 0]
    return 0.5 * np.abs(cross).sum()


@pytest.mark.parametrize("name", LEVERS)
def test_the_untwisted_slab_is_the_plan_view(name):
    lever = preset(name)
    verts, faces = lever_mesh(lever, 0.0)
    assert faces.min() >= 0 and faces.max() < len(verts)
    lo, hi = verts.min(axis=0), verts.max(axis=0)
    np.testing.assert_allclose(lo, [0.0, -lever.width / 2, -lever.thickness / 2], atol=1e-15)
    np.testing.assert_allclose(hi, [lever.length, lever.width / 2, lever.thickness / 2],
                               atol=1e-15)
    # the area under the top face: the plan view's (exact for straight edges sampled at their
    # corners)
    assert _top_area(verts, faces, lever.thickness) == pytest.approx(lever.area, rel=1e-9)


def _signed_volume(verts, faces):
    v0, v1, v2 = verts[faces[:, 0]], verts[faces[:, 1]], verts[faces[:, 2]]
    return float(np.einsum("ij,ij->i", v0, np.cross(v1, v2)).sum() / 6)


@pytest.mark.parametrize("name", LEVERS)
def test_the_slab_is_closed_and_wound_outwards(name):
    # the divergence theorem on a closed surface wound counter-clockwise from outside: its signed
    # volume is the slab's, area x thickness; inside out it would be negative, open it would
    # depend on the origin (shifted here)
    lever = preset(name)
    volume = lever.area * lever.thickness
    for twist in (0.0, 0.4):
        verts, faces = lever_mesh(lever, twist)
        for shift in ((0, 0, 0), (1e-3, -2e-3, 5e-4)):
            assert _signed_volume(verts + shift, faces) == pytest.approx(
                volume, rel=1e-9 if twist == 0 else 1e-2)


@pytest.mark.parametrize("name", LEVERS)
def test_half_widths_follow_the_outline(name):
    # the plan view's outline (planform_outline, the figure's polygon) crossed at each station:
    # on the side y >= 0 its crossings are the section's edges, the axis where it is inside
    lever = preset(name)
    from matplotlib.path import Path as Polygon
    ox, oy = planform_outline(lever)
    outline = Polygon(np.column_stack([ox, oy]))
    x = np.linspace(0.0, lever.length, 41)[1:-1]
    inner, outer = half_widths(lever, x)
    for xi, lo, hi in zip(x, inner, outer):
        ys = []
        for (x0, y0), (x1, y1) in zip(zip(ox[:-1], oy[:-1]), zip(ox[1:], oy[1:])):
            if min(x0, x1) <= xi <= max(x0, x1) and x0 != x1:
                ys.append(y0 + (y1 - y0) * (xi - x0) / (x1 - x0))
        ys = sorted(y for y in ys if y >= 0)
        axis_inside = outline.contains_point((xi, 0.0))
        expect_lo = 0.0 if axis_inside else ys[0]
        assert (lo, hi) == pytest.approx((expect_lo, ys[-1]), abs=1e-12), (name, xi)
    with pytest.raises(ValueError, match="x"):
        half_widths(lever, [2 * lever.length])


def test_a_section_turns_by_the_twist_growing_to_the_tip():
    lever = Lever.rectangular("silicon", 450e-6, 50e-6, 2e-6)
    phi = 0.4
    flat, _ = lever_mesh(lever, 0.0, stations=11)
    bent, _ = lever_mesh(lever, phi, stations=11)
    for x_frac in (0.0, 0.5, 1.0):
        at = np.isclose(flat[:, 0], x_frac * lever.length)
        a = phi * x_frac   # the tip at the free end: the twist grows linearly to it
        rot = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
        np.testing.assert_allclose(bent[at, 1:], flat[at, 1:] @ rot.T, atol=1e-15)
        np.testing.assert_allclose(bent[at, 0], flat[at, 0])


def test_the_scene_draws_the_models_twist_magnified_and_the_tip_turns_with_it():
    rec = Recorder()
    lever = preset("ContAl-G")
    lateral = LateralLever(lever)
    twist = lateral.twist(100e-9)
    sc = ProbeScene(lever, twist, vis=rec)
    # one round factor per lever: the slider's largest force drawn at 0.5 rad at most
    largest = sc.factor * abs(lateral.twist(LATERAL_FORCE.slider_high))
    assert 0.1 < largest <= 0.5
    assert sc.factor in {m * 10 ** e for m in (1, 2, 5) for e in range(0, 8)}
    drawn = sc.factor * twist
    arm = (lever.tip_height + lever.thickness / 2) / SCENE_UNIT
    tip = rec.log["/afmsmiler/probe/tip"]["transform"]
    apex = tip @ np.array([0.0, 0.0, 0.0, 1.0])   # the cone's apex at its node's origin
    np.testing.assert_allclose(apex[1:3], [arm * math.sin(drawn), -arm * math.cos(drawn)],
                               rtol=1e-12)
    np.testing.assert_allclose(apex[:3], sc.apex(), rtol=1e-12)
    assert f"twist x {sc.factor:g}" in sc.caption
    n = rec.log["/afmsmiler/probe/lever"]["n_objects"]
    sc.update(lever, twist)    # nothing changed (the spot moved): nothing sent
    assert rec.log["/afmsmiler/probe/lever"]["n_objects"] == n
    sc.update(lever, -twist)   # the force reversed: the other way, the same factor
    assert rec.log["/afmsmiler/probe/lever"]["n_objects"] == n + 1
    assert sc.apex()[1] == pytest.approx(-arm * math.sin(drawn))


def test_bad_input_is_refused_by_name():
    lever = preset("ContAl-G")
    with pytest.raises(ValueError, match="twist"):
        lever_mesh(lever, 2.0)
    with pytest.raises(TypeError, match="lever"):
        lever_mesh("ContAl-G", 0.0)
    with pytest.raises(ValueError, match="stations"):
        lever_mesh(lever, 0.0, stations=1)
    with pytest.raises(ValueError, match="twist"):
        ProbeScene(lever, float("nan"), vis=Recorder())


@pytest.mark.parametrize("name", LEVERS)
def test_the_camera_frames_the_lever_and_its_tip(name):
    lever = preset(name)
    rec = Recorder()
    sc = ProbeScene(lever, LateralLever(lever).twist(LATERAL_FORCE.slider_high), vis=rec)
    verts, _ = lever_mesh(lever, sc.factor * sc.twist)
    points = (verts - [lever.length / 2, 0.0, 0.0]) / SCENE_UNIT
    ndc = camera_ndc(np.vstack([points, sc.apex()]), sc.camera_position, aspect=1.5)
    assert np.all(np.abs(ndc) < 0.95), (name, np.abs(ndc).max(axis=0))
    # ... and fills a good part of the view: the lever spans over a third of its width
    assert np.ptp(ndc[:, 0]) > 0.66, (name, np.ptp(ndc[:, 0]))
    assert rec.log["/Grid"]["visible"] is False


def test_a_twist_beyond_a_quarter_turn_is_drawn_held_there_and_said_so():
    # a long thin custom lever at the slider's largest force twists some 11 rad in the linear
    # model: drawn at a quarter turn, the caption says so, nothing raised
    lever = Lever.rectangular("silicon", 1000e-6, 5e-6, 0.2e-6)
    twist = LateralLever(lever).twist(LATERAL_FORCE.slider_high)
    assert twist > 2 * math.pi
    sc = ProbeScene(lever, twist, vis=Recorder())
    assert sc.factor == 1.0  # never shrunk
    assert "held at a quarter turn" in sc.caption and "drawn 90 deg" in sc.caption
    arm = (lever.tip_height + lever.thickness / 2) / SCENE_UNIT
    assert sc.apex()[1:] == pytest.approx([arm, 0.0], abs=1e-12)


def test_a_tip_set_back_twists_as_far_as_the_tip_and_no_further():
    lever = Lever.rectangular("silicon", 450e-6, 50e-6, 2e-6, tip_position=400e-6)
    verts, _ = lever_mesh(lever, 0.3)
    mid = verts[np.argmin(np.abs(verts[:, 0] - 200e-6)), 0]   # the station nearest 200 um
    for x, angle in ((mid, 0.3 * mid / 400e-6), (400e-6, 0.3), (450e-6, 0.3)):
        at = np.isclose(verts[:, 0], x) & np.isclose(verts[:, 2], math.sin(angle) * 25e-6
                                                     + math.cos(angle) * 1e-6)
        # the top outer corner (y = w/2, z = t/2) turned by the angle of its section
        assert at.any(), x
        np.testing.assert_allclose(verts[at, 1], math.cos(angle) * 25e-6 - math.sin(angle) * 1e-6,
                                   rtol=1e-9)
