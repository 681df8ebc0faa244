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
from afmsmiler.probe import half_widths
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


def test_half_widths_follow_the_outline():
    v = preset("MLCT-E")
    inner, outer = half_widths(v, [0.0, v.solid_from, v.length])
    h = v.width / 2
    assert inner[0] == pytest.approx(h - v.arm_width / math.cos(v.half_angle))
    assert inner[1] == 0.0 and outer[2] == 0.0 and outer[0] == pytest.approx(h)
    p = preset("AC160TS")
    _, outer = half_widths(p, [p.length - p.point_length, p.length])
    assert outer == pytest.approx([p.width / 2, 0.0])
    with pytest.raises(ValueError, match="x"):
        half_widths(p, [2 * p.length])


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
