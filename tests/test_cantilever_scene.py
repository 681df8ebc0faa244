"""The cantilever scene against closed forms: the drawn centre line is the exaggerated Eq. (1), the
colors are the textbook clamp stress 6 F L / (w h^2), the tip and arrow sit at the free end, the
modes have their published nodes, and a real viewer is updated in place (one server, same paths)."""
import math

import numpy as np
import pytest
from meshcat.path import Path

from afmsmiler.cantilever import Cantilever
from afmsmiler.scenes.camera import camera_ndc
from afmsmiler.scenes.legends import text_png
from afmsmiler.scenes.cantilever import (DEFAULTS, LIMITS, SCENE_UNIT, CantileverScene,
                                         mode_animation)
from tests.recording import Recorder

E, RHO = 169e9, 2330.0
L, W, H = 450e-6, 50e-6, 2e-6
F = 120e-9
LEVER = Cantilever(L, W, H, E, RHO)


def bend(lever, force):
    """The model's result the scene draws: 61 stations, 9 levels (the panel's grid is finer)."""
    return lever.bending(force, n_length=61, n_thickness=9)



def closed_form_tip(force):
    k = E * W * H ** 3 / (4 * L ** 3)  # 3 E J / L^3 with J = w h^3 / 12, by hand
    return force / k


@pytest.fixture
def scene():
    rec = Recorder()
    return CantileverScene(bend(LEVER, F), vis=rec, path="lever"), rec


def centre_line(sc):
    nl, nt = sc.n_length, sc.n_thickness
    side = sc.mesh.vertices[:nl * nt].reshape(nl, nt, 3)
    return side[:, nt // 2]


def test_drawn_centre_line_is_the_exaggerated_deflection(scene):
    sc, _ = scene
    mid = centre_line(sc)
    u = mid[:, 0] * SCENE_UNIT / L
    ref = closed_form_tip(F) / 2 * (3 * u ** 2 - u ** 3)  # z(L) (3u^2 - u^3)/2, Eq. (1)
    np.testing.assert_allclose(mid[:, 0], np.linspace(0, L / SCENE_UNIT, sc.n_length), rtol=1e-6)
    np.testing.assert_allclose(mid[:, 2], 100 * ref / SCENE_UNIT, rtol=1e-5, atol=1e-7)
    sc.update(bend(LEVER, F), exaggeration=250)
    np.testing.assert_allclose(centre_line(sc)[:, 2], 250 * ref / SCENE_UNIT, rtol=1e-5, atol=1e-7)
    # the width and thickness are drawn true to scale (1 unit = 100 um)
    v = sc.mesh.vertices
    assert v[:, 1].max() - v[:, 1].min() == pytest.approx(W / SCENE_UNIT, rel=1e-6)


def test_colors_are_the_bending_stress_through_length_and_thickness(scene):
    sc, rec = scene
    sigma_clamp = 6 * F * L / (W * H ** 2) / 1e6  # MPa, textbook surface stress at the clamp
    v, vals = sc.mesh.vertices, sc.mesh.values
    top = sc.mesh.values[:sc.n_length * sc.n_thickness].reshape(sc.n_length, sc.n_thickness)
    # F > 0 lifts the tip: top surface compressed, bottom stretched, zero on the neutral plane
    assert top[0, -1] == pytest.approx(-sigma_clamp, rel=1e-12)
    assert top[0, 0] == pytest.approx(sigma_clamp, rel=1e-12)
    np.testing.assert_allclose(top[:, sc.n_thickness // 2], 0.0, atol=1e-12 * sigma_clamp)
    # linear in z_b through the thickness and in (L - x) along the length
    np.testing.assert_allclose(top[0], np.linspace(sigma_clamp, -sigma_clamp, sc.n_thickness), rtol=1e-12)
    np.testing.assert_allclose(top[:, -1], -sigma_clamp * np.linspace(1, 0, sc.n_length), atol=1e-9)
    # the color limit is the next round number above the peak, in MPa
    assert sc.scale.unit == "MPa" and sigma_clamp <= sc.scale.vmax <= 2.5 * sigma_clamp
    geom, material = rec.log["/lever/beam"]["object"]
    assert material.vertexColors
    np.testing.assert_allclose(geom.color, sc.scale.rgb(vals), atol=1e-7)
    assert len(vals) == len(v)


def test_fixed_stress_limit_maps_the_clamp_to_the_colormap_ends():
    rec = Recorder()
    sigma_clamp = 6 * F * L / (W * H ** 2)
    sc = CantileverScene(bend(LEVER, F), vis=rec, stress_limit=sigma_clamp)
    geom, _ = rec.log["/afmsmiler/cantilever/beam"]["object"]
    top_clamp = np.argmin(sc.mesh.values)
    bottom_clamp = np.argmax(sc.mesh.values)
    np.testing.assert_allclose(geom.color[top_clamp], sc.scale.rgb(-1e9), atol=1e-7)  # blue end
    np.testing.assert_allclose(geom.color[bottom_clamp], sc.scale.rgb(1e9), atol=1e-7)  # red end
    assert geom.color[bottom_clamp][0] > geom.color[bottom_clamp][2]


def test_tip_and_force_arrow_sit_at_the_free_end(scene):
    sc, rec = scene
    ex = 100
    z_tip = ex * closed_form_tip(F) / SCENE_UNIT
    pose = sc.tip_pose(sc.field)
    apex = sc.apex(pose)
    # the tip hangs below the bottom face near the free end, along the drawn beam's normal there:
    # drawn slope = ex theta(L) = ex 3 z(L) / (2 L) (textbook), normal (-s, 0, 1) / sqrt(1 + s^2)
    s = ex * 1.5 * closed_form_tip(F) / L
    n = np.array([-s, 0, 1]) / math.hypot(1, s)
    t = np.array([1, 0, s]) / math.hypot(1, s)
    d = apex - [L / SCENE_UNIT, 0, z_tip]
    assert d @ n == pytest.approx(-(H / 2 + DEFAULTS["tip_height"]) / SCENE_UNIT, rel=1e-9)
    assert -0.1 < d @ t <= 0 and abs(d[1]) < 1e-12
    # arrow: length F / force_per_unit, pointing up, ending at the apex
    assert np.allclose(sc.arrow.vector, [0, 0, F / DEFAULTS["force_per_unit"]])
    np.testing.assert_allclose(sc.arrow.start + sc.arrow.vector, apex, atol=1e-12)
    sc.update(bend(LEVER, -F))  # pulled down: starts at the apex, points down
    apex = sc.apex(sc.tip_pose(sc.field))
    np.testing.assert_allclose(sc.arrow.start, apex, atol=1e-12)
    assert sc.arrow.vector[2] == pytest.approx(-F / DEFAULTS["force_per_unit"])


def test_drawn_deflection_is_capped_at_a_fraction_of_the_lever_length(scene):
    sc, _ = scene
    soft = Cantilever(500e-6, 5e-6, 0.2e-6, 10e9, RHO)  # k ~ 1e-6 N/m: z(L) = 0.6 m at 500 nN
    sc.update(bend(soft, 5e-7), exaggeration=1e4)
    mid = centre_line(sc)
    cap = DEFAULTS["max_drawn_tip"] * soft.length
    assert mid[-1, 2] == pytest.approx(cap / SCENE_UNIT, rel=1e-6)
    assert sc.drawn_exaggeration == pytest.approx(cap / (5e-7 / soft.spring_constant))
    sc.update(bend(LEVER, F), exaggeration=100)  # a stiff lever is drawn with the asked exaggeration
    assert sc.drawn_exaggeration == 100


def test_update_is_in_place(scene):
    sc, rec = scene
    def objects():
        return {k for k, v in rec.log.items() if k.startswith("/") and "object" in v}

    paths = objects()
    counts = {k: rec.log[k].get("n_objects", 0) for k in paths}
    for f in np.linspace(-2e-7, 2e-7, 7):
        sc.update(bend(Cantilever(L * 0.8, W, H * 1.1, E, RHO), f), exaggeration=50)
    assert objects() == paths
    assert rec.log["/lever/force"]["visible"] is True  # hidden at F = 0, shown again after
    grown = {k for k in paths if rec.log[k].get("n_objects", 0) > counts[k]}
    assert grown <= {"/lever/beam", "/lever/chip", "/lever/legend/plate"}  # only the mesh is resent


@pytest.mark.slow
def test_modes_have_their_published_nodes():
    # Node positions x/L of a clamped-free beam: mode 2 at 0.783; mode 3 at 0.504 and 0.868
    # (Blevins, Formulas for Natural Frequency and Mode Shape, Table 8-1).
    rec = Recorder()
    segs, frames = 60, 8
    fine = LEVER.bending(0.0, n_length=2001, modes=3)  # the shapes interpolated at segment centres
    anim = mode_animation(fine, rec["modes"], modes=(1, 2, 3), frames=frames, segments=segs)
    quarter = frames // 4  # sin = 1
    mids = (np.arange(segs) + 0.5) / segs
    for n, nodes in ((1, []), (2, [0.783]), (3, [0.504, 0.868])):
        z = []
        for i in range(segs):
            clip = anim.clips[Path(("modes", f"mode{n}", f"s{i:03d}"))]
            track = clip.tracks["position"]
            z.append(track.values[track.frames.index(quarter)][2])
        z = np.array(z)
        crossings = mids[:-1][np.diff(np.sign(z)) != 0]
        assert len(crossings) == len(nodes)
        for c, node in zip(crossings, nodes):
            assert abs(c + 0.5 / segs - node) <= 1.0 / segs
        tip = z[-1] + (z[-1] - z[-2]) / 2  # extrapolated from the last segment centres to x = L
        assert tip == pytest.approx(DEFAULTS["mode_amplitude"] * L / SCENE_UNIT, rel=0.01)


def test_bad_input():
    rec = Recorder()
    with pytest.raises(ValueError, match=r"exaggeration must be in \[1, 1e\+06\]"):
        CantileverScene(bend(LEVER, F), vis=rec, exaggeration=0)
    with pytest.raises(TypeError, match="bending must be a Bending"):
        CantileverScene("silicon", vis=rec)
    with pytest.raises(TypeError, match="bending must be a Bending"):
        CantileverScene(LEVER, vis=rec)  # the scene draws a result, it does not compute one
    sc = CantileverScene(bend(LEVER, F), vis=rec)
    with pytest.raises(ValueError, match="force must be in"):
        sc.update(bend(LEVER, math.nan))
    with pytest.raises(TypeError, match="bending must be a Bending"):
        sc.update(None)
    with pytest.raises(ValueError, match="frames must be an integer"):
        mode_animation(bend(LEVER, F), rec, frames=1)
    with pytest.raises(TypeError, match="bending must be a Bending"):
        mode_animation(LEVER, rec)  # the scene draws the model's mode shapes, not its own
    with pytest.raises(ValueError, match=r"^modes must be at most 3 \(the modes of bending\)"):
        mode_animation(bend(LEVER, F), rec, modes=(1, 4))


def test_sizes_are_bounded_before_any_work():
    rec = Recorder()
    sc = CantileverScene(bend(LEVER, F), vis=rec)
    n_calls = len(rec.calls)
    huge = LEVER.bending(F, n_length=10_000, n_thickness=21)  # valid for the model, too many to draw
    assert huge.x.size * huge.z_b.size > LIMITS["mesh_points"]
    with pytest.raises(ValueError, match=r"^bending must have at most"):
        sc.update(huge)
    with pytest.raises(ValueError, match=r"^segments x \(frames \+ 1\) x modes must be at most"):
        mode_animation(LEVER.bending(F, modes=50), rec["modes"], frames=10_000, segments=1_000,
                       modes=range(1, 51))
    with pytest.raises(ValueError, match=r"^modes must name 1 to"):
        mode_animation(bend(LEVER, F), rec["modes"], modes=())
    assert len(rec.calls) == n_calls  # nothing was sent


@pytest.mark.slow
def test_largest_allowed_drawings_take_seconds_not_minutes(hang_guard):
    rec = Recorder()
    with hang_guard(60, expected=3):  # about 3 s on one loaded core
        CantileverScene(LEVER.bending(F, n_length=10_000,
                                      n_thickness=LIMITS["mesh_points"] // 10_000), vis=rec)
        frames = LIMITS["animation_transforms"] // (20 * 3) - 1
        mode_animation(bend(LEVER, F), rec["modes"], frames=frames, segments=20, modes=(1, 2, 3))


@pytest.mark.slow
def test_real_view_updated_in_place():
    sc = CantileverScene(bend(LEVER, F))
    size0 = len(sc.static_html())
    for f in np.linspace(0, 3e-7, 10):
        sc.update(bend(LEVER, f), exaggeration=200)
    # in place: the stored scene holds one mesh, so it does not grow with updates
    assert abs(len(sc.static_html()) - size0) < 0.05 * size0
    sc.animate_modes(frames=4, repetitions=1)
    assert "<html" in sc.static_html().lower()


def _must_see(sc, lever):
    """World points a student must see: clamp, free end (top face and the tip apex), the four
    corners of the legend plate and the chip behind the clamp."""
    length = lever.length / SCENE_UNIT
    x_l = np.array([-length / 2, 0.0, 0.0])  # the lever frame in the world
    nl, nt = sc.n_length, sc.n_thickness
    side = sc.mesh.vertices[:nl * nt].reshape(nl, nt, 3) + x_l
    w, h = sc.legend_width, sc.legend_width / 4
    legend = sc.legend_corner(length) + x_l + np.array(
        [[0, 0, 0], [w, 0, 0], [0, 0, h], [w, 0, h]])
    apex = sc.apex(sc.tip_pose(sc.field)) + x_l
    chip = x_l + [-DEFAULTS["chip_in_view"], 0.0, 0.0]
    return np.vstack([side[0, nt // 2], side[-1, 0], side[-1, -1], legend, apex, chip])


@pytest.mark.parametrize("length", [20e-6, 100e-6, 450e-6, 500e-6])
@pytest.mark.parametrize("force", [0.0, 5e-7, -5e-7])
def test_camera_frames_the_lever_tip_chip_and_legend(length, force):
    """Every part a student must see projects inside a 1200 x 800 view of meshcat's camera."""
    rec = Recorder()
    soft = Cantilever(length, 5e-6, 0.2e-6, 10e9, RHO)  # deflection capped: the extreme pose
    sc = CantileverScene(bend(soft, force), vis=rec, path="lever", exaggeration=1e4)
    ndc = camera_ndc(_must_see(sc, soft), sc.camera_position, aspect=1.5)
    assert np.all(np.abs(ndc) <= 1.0), ndc
    # the camera looks at the origin, which lies on the lever between clamp and free end
    mid = centre_line(sc) + [-length / SCENE_UNIT / 2, 0.0, 0.0]
    assert mid[0, 0] < 0.0 < mid[-1, 0]
    x_, y_, z_ = rec.log["/Cameras/default/rotated/<object>"]["position"]
    np.testing.assert_allclose((x_, -z_, y_), sc.camera_position)
    assert rec.log["/Axes"]["visible"] is False  # meshcat's axes would pierce the lever


@pytest.mark.parametrize("start", [400e-6, 450e-6, 20e-6, 100e-6])
@pytest.mark.parametrize("force", [5e-7, -5e-7])
def test_capped_tip_stays_in_view_when_the_lever_grows_a_little(start, force):
    # the live test: a soft lever under a large force (deflection drawn capped at
    # max_drawn_tip x L), then L moved up by less than reframe_ratio: the camera, framed for the
    # shorter lever, used to stay put and the tip left the top of the view (ndc y = 1.05 for
    # 450 -> 500 um). Sweep L in slider steps up to just below the ratio.
    rec = Recorder()
    sc = CantileverScene(bend(Cantilever(start, 5e-6, 0.2e-6, 10e9, RHO), force), vis=rec,
                         path="lever", exaggeration=1e4)
    for length in np.linspace(start, start * DEFAULTS["reframe_ratio"] * 0.999, 12)[1:]:
        soft = Cantilever(length, 5e-6, 0.2e-6, 10e9, RHO)
        sc.update(bend(soft, force))
        z_drawn = centre_line(sc)[-1, 2]
        assert abs(z_drawn) == pytest.approx(DEFAULTS["max_drawn_tip"] * length / SCENE_UNIT,
                                             rel=1e-6)  # capped indeed
        ndc = camera_ndc(_must_see(sc, soft), sc.camera_position, aspect=1.5)
        assert np.all(np.abs(ndc) <= 1.0), (length, ndc)
        x_, y_, z_ = rec.log["/Cameras/default/rotated/<object>"]["position"]
        np.testing.assert_allclose((x_, -z_, y_), sc.camera_position)  # the viewer was told


def test_camera_follows_only_large_changes_of_length():
    rec = Recorder()
    sc = CantileverScene(bend(LEVER, F), vis=rec)
    first = sc.camera_position.copy()
    sc.update(bend(Cantilever(L * 1.1, W, H, E, RHO), F))
    np.testing.assert_array_equal(sc.camera_position, first)  # small change: camera kept
    sc.update(bend(Cantilever(L / 4, W, H, E, RHO), F))
    assert np.linalg.norm(sc.camera_position) < np.linalg.norm(first)  # short lever: closer


def test_mode_beams_are_labelled_with_number_and_frequency():
    rec = Recorder()
    mode_animation(bend(LEVER, 0.0), rec["modes"], modes=(1, 2), frames=4, segments=4)
    J = W * H ** 3 / 12
    for n, beta in ((1, 1.8751040687), (2, 4.6940911330)):  # b_n L, Blevins Table 8-1
        f = beta ** 2 / (2 * math.pi * L ** 2) * math.sqrt(E * J / (RHO * W * H))
        png = rec.log[f"/modes/label{n}/plate"]["object"][1].map.image.data
        assert png == text_png(f"mode {n}: {f / 1e3:.3g} kHz")
        # the label sits beside the clamp end of its own beam (same y), left of x = 0
        t = rec.log[f"/modes/label{n}"]["transform"]
        beam_y = rec.log[f"/modes/mode{n}/s000"]["object"] and n * (0.3 + 1.5 * W / SCENE_UNIT)
        assert t[1, 3] == pytest.approx(beam_y) and t[0, 3] < 0
        # before it plays, the beam lies straight behind the lever (not piled up at the clamp)
        seg = rec.log[f"/modes/mode{n}/s003"]["transform"]
        np.testing.assert_allclose(seg[:3, 3], [3.5 / 4 * L / SCENE_UNIT, beam_y, 0.0])


def test_scene_arguments_are_checked_by_name_before_drawing():
    rec = Recorder()
    for kwargs, match in ((dict(exaggeration=None), "exaggeration must be"),
                          (dict(exaggeration=math.nan), "exaggeration must be"),
                          (dict(force_per_unit=1e-300), "force_per_unit must be in"),
                          (dict(stress_limit=-1.0), "stress_limit must be"),
                          (dict(path=3), "path must be a str")):
        with pytest.raises((TypeError, ValueError), match=match):
            CantileverScene(bend(LEVER, F), vis=rec, **kwargs)
    assert rec.calls == []
    with pytest.raises(TypeError, match="^modes must be a sequence"):
        mode_animation(bend(LEVER, F), rec, modes=2)
    with pytest.raises(ValueError, match="^length must be in"):
        CantileverScene.framing(math.nan)
    # a 1 m lever (the longest valid) is still framed: the camera backs off far enough
    length = 1.0 / SCENE_UNIT
    position, _ = CantileverScene.framing(length)
    ends = np.array([[-length / 2, 0.0, 0.0], [length / 2, 0.0, 0.0]])
    assert np.all(np.abs(camera_ndc(ends, position, aspect=1.5)) <= 1.0)
