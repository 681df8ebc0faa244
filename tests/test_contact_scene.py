"""The contact scene as a student sees it: a cut-away of the tip pressing into the sample, framed by
the camera, with its depth legend; the cut faces follow the contact solution."""
import numpy as np
import pytest

from afmsmiler.contact import Conical, Parabolic, Pyramidal, Spherical, indent, surface_displacement
from afmsmiler.scenes.camera import camera_ndc
from afmsmiler.scenes.contact import DEFAULTS, ContactScene, cut_mesh, surface_mesh, tip_mesh
from tests.recording import Recorder

UNIT = 20e-9
TIPS = [Parabolic(20e-9), Spherical(40e-9), Conical(0.4), Pyramidal(0.6)]


@pytest.mark.parametrize("tip", TIPS, ids=lambda t: t.key)
def test_half_meshes_are_the_far_half_closed_by_their_cross_sections(tip):
    v, f = tip_mesh(tip, 100e-9, UNIT, half=True)
    assert f.min() == 0 and f.max() == v.shape[0] - 1 and np.isfinite(v).all()
    assert v[:, 1].min() >= -1e-6  # only y >= 0
    # the cross-section on y = 0 is the tip's outline: |x| at each height as tip_outline says
    on_cut = np.abs(v[:, 1]) < 1e-6
    on_cut[-1] = False  # the centre of the flat top (the lid), not a point of the outline
    x, z = tip.outline(100e-9)
    flank = x >= 0
    expected = np.interp(v[on_cut, 2] * UNIT, z[flank], x[flank])
    np.testing.assert_allclose(np.abs(v[on_cut, 0]) * UNIT, expected, rtol=1e-4, atol=1e-12)
    cut_faces = [t for t in f if on_cut[t].all()]
    assert len(cut_faces) == np.sum(on_cut) - 2  # the outline is filled: apex + 2 per ring gap

    cur = indent([40e-9], 0.2, tip, 2e6, 0.3)
    v, f, depth = surface_mesh(tip, cur, 150e-9, UNIT, 20, half=True)
    assert f.max() == v.shape[0] - 1 and v[:, 1].min() >= -1e-6
    cv, cf = cut_mesh(v, 20, 3.0)
    assert np.all(cv[:, 1] == 0.0) and cf.max() == cv.shape[0] - 1
    top = cv[: cv.shape[0] // 2]
    assert np.all(np.diff(top[:, 0]) > 0)  # from -extent to +extent along x
    # the wall's top edge is Sneddon's profile, its bottom flat at -slab
    np.testing.assert_allclose(-top[:, 2] * UNIT, surface_displacement(tip, cur.z_s[0], np.abs(
        top[:, 0].astype(float)) * UNIT), rtol=1e-5, atol=1e-15)
    assert np.all(cv[cv.shape[0] // 2:, 2] == -3.0)


def _scene(tip, z_np, **kw):
    rec = Recorder()
    cur = indent([z_np], 0.1, tip, 1e6, 0.3)
    return ContactScene(tip, cur, vis=rec, **kw), rec, cur


@pytest.mark.parametrize("tip", TIPS, ids=lambda t: t.key)
@pytest.mark.parametrize("z_np", [-30e-9, 60e-9, 150e-9])
def test_camera_frames_the_contact_the_sample_and_the_legend(tip, z_np):
    if isinstance(tip, Spherical):
        z_np = min(z_np, 55e-9)  # the model's limit for this sphere is 61 nm
    sc, rec, cur = _scene(tip, z_np)
    e = sc.extent / sc.unit
    shift = np.array([0.0, 0.0, -DEFAULTS["lowered"] * e])  # the scene's own transform
    apex = np.array([0.0, 0.0, sc.last_apex / sc.unit]) + shift
    rim = np.array([[-e, 0, 0], [e, 0, 0], [-e, 0, -sc.slab], [e, 0, -sc.slab]]) + shift
    w = sc.legend.width
    legend = sc.legend_corner + shift + np.array([[0, 0, 0], [w, 0, 0], [0, 0, w / 4],
                                                  [w, 0, w / 4]])
    ndc = camera_ndc(np.vstack([apex, rim, legend]), sc.camera_position, aspect=1.5)
    assert np.all(np.abs(ndc) <= 1.0), ndc
    # the apex is at the contact solution, and a buried tip is drawn taller than the indentation
    assert sc.last_apex == pytest.approx(float(cur.separation[0]))
    assert sc.tip_height > 1.4 * max(float(cur.z_s[0]), 0.0)
    assert rec.log["/Grid"]["visible"] is False and rec.log["/Axes"]["visible"] is False


def test_legend_follows_the_depth_in_round_numbers():
    tip = Parabolic(20e-9)
    sc, rec, cur = _scene(tip, 60e-9)
    depth_nm = float(cur.z_s[0]) * 1e9
    assert sc.depth_scale.unit == "nm" and depth_nm <= sc.depth_scale.vmax <= 2.5 * depth_nm
    assert sc.legend.scale == sc.depth_scale
    sc.update(tip, indent([5e-9], 0.1, tip, 1e6, 0.3))
    assert sc.legend.scale == sc.depth_scale and sc.depth_scale.vmax < depth_nm


def test_a_scale_past_float32_or_too_small_for_the_camera_is_named():
    """extent = 1e300 m (or unit = 1e-300 m) drew vertices at -inf and extent = 1e-300 m put the
    camera on the contact: both were errors of the camera naming neither parameter."""
    tip = Parabolic(50e-9)
    current = indent([-5e-9], 0.1, tip, 1e6, 0.3)
    for kw in (dict(extent=1e300), dict(unit=1e-300), dict(extent=1e-300), dict(unit=1e300)):
        with pytest.raises(ValueError, match=r"^extent / unit \(the drawn size in scene units\) "
                                             r"must be in \(0.001, 1e\+06\], got "):
            ContactScene(tip, current, vis=Recorder(), **kw)
    with pytest.raises(ValueError, match=r"^height / unit"):
        tip_mesh(tip, 1e300, 1e-9)
    for bad in ("no", float("nan"), np.ones(2)):
        with pytest.raises(TypeError, match="^half must be True or False"):
            tip_mesh(tip, 50e-9, 1e-9, half=bad)
        with pytest.raises(TypeError, match="^camera must be True or False"):
            ContactScene(tip, current, vis=Recorder(), camera=bad)
        with pytest.raises(TypeError, match="^path must be a str"):
            ContactScene(tip, current, vis=Recorder(), path=np.ones(2))
