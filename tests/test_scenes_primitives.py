"""The meshcat building blocks: mesh geometry follows the given deflection, colors map the ends of
the scale to the colormap's ends, rigid primitives land where asked; one real-viewer smoke test."""
import io
import math

import matplotlib
import matplotlib.image
import meshcat.geometry as g
import numpy as np
import pytest

from afmsmiler.scenes import close_viewer, get_viewer, primitives as P
from recording import Recorder



def apply(t, p):
    return (t @ np.append(p, 1.0))[:3]


# --- colors ------------------------------------------------------------------------------------
def test_color_scale_maps_extremes_to_the_colormap_ends_and_clips():
    scale = P.ColorScale.symmetric(2.0, "RdBu_r", "stress", "MPa")
    cmap = matplotlib.colormaps["RdBu_r"]
    rgb = scale.rgb([-2.0, 2.0, -50.0, 50.0, 0.0])
    np.testing.assert_allclose(rgb[0], cmap(0.0)[:3], atol=1e-6)
    np.testing.assert_allclose(rgb[1], cmap(1.0)[:3], atol=1e-6)
    np.testing.assert_allclose(rgb[2], rgb[0])  # clipped below
    np.testing.assert_allclose(rgb[3], rgb[1])  # clipped above
    assert rgb[1][0] > rgb[1][2] and rgb[0][2] > rgb[0][0]  # tension red, compression blue
    assert rgb[4].min() > 0.9  # the middle of a diverging map is (nearly) white
    assert scale.title == "stress [MPa]"
    assert P.rgb_hex([1.0, 0.0, 0.0]) == 0xff0000


def test_color_scale_shape_and_bad_input():
    scale = P.ColorScale(0.0, 1.0, "viridis")
    assert scale.rgb(np.zeros((4, 5))).shape == (4, 5, 3)
    with pytest.raises(ValueError, match="vmax must be in"):
        P.ColorScale(1.0, 1.0)
    with pytest.raises(ValueError, match="cmap must be"):
        P.ColorScale(0.0, 1.0, "no-such-map")
    with pytest.raises(ValueError, match="limit must be > 0"):
        P.ColorScale.symmetric(0.0)


@pytest.mark.parametrize("value, expected", [(0.13, 0.2), (1.0, 1.0), (3.0, 5.0), (7.0, 10.0),
                                             (-0.0042, 0.005), (0.0, 1e-3), (1.2e5, 2e5)])
def test_nice_ceil(value, expected):
    assert P.nice_ceil(value, floor=1e-3) == pytest.approx(expected, rel=1e-12)


# --- the beam mesh -----------------------------------------------------------------------------
NL, NT = 21, 5
X = np.linspace(0.0, 2.0, NL)
W, H = 0.3, 0.04


def levels(values_top, values_bottom):
    return np.linspace(values_bottom, values_top, NT).T  # (NL, NT), bottom -> top


def test_flat_beam_is_a_box_with_values_on_the_right_faces():
    vals = levels(-X, X)  # top = -x, bottom = +x
    mesh = P.beam_mesh(X, np.zeros(NL), W, H, vals)
    n = 2 * NL * NT + 4 * NL + 4 * NT
    assert mesh.vertices.shape == (n, 3) and mesh.values.shape == (n,)
    assert mesh.faces.max() == n - 1 and len(np.unique(mesh.faces)) == n  # every vertex is used
    lo, hi = mesh.vertices.min(0), mesh.vertices.max(0)
    np.testing.assert_allclose(lo, [0.0, -W / 2, -H / 2], atol=1e-15)
    np.testing.assert_allclose(hi, [2.0, W / 2, H / 2], atol=1e-15)
    # the value at a vertex is the one given for its station and level
    for v, val in zip(mesh.vertices, mesh.values):
        i = int(np.argmin(abs(X - v[0])))
        j = int(round((v[2] / H + 0.5) * (NT - 1)))
        assert val == pytest.approx(vals[i, j], abs=1e-12)
    top = mesh.vertices[:, 2] == H / 2
    np.testing.assert_allclose(mesh.values[top], -mesh.vertices[top, 0], atol=1e-12)


def test_deflected_beam_follows_the_centre_line_with_true_thickness():
    a = 0.4
    z = a * X ** 2
    mesh = P.beam_mesh(X, z, W, H, np.zeros((NL, NT)), slope=2 * a * X)
    side = mesh.vertices[:NL * NT].reshape(NL, NT, 3)
    mid = side[:, NT // 2]  # the middle level is the centre line itself
    np.testing.assert_allclose(mid[:, 0], X, atol=1e-12)
    np.testing.assert_allclose(mid[:, 2], z, atol=1e-12)
    # top and bottom lie h apart along the normal of the centre line (-z', 0, 1)/sqrt(1+z'^2)
    d = side[:, -1] - side[:, 0]
    np.testing.assert_allclose(np.linalg.norm(d, axis=1), H, rtol=1e-12)
    normal = np.stack([-2 * a * X, np.zeros(NL), np.ones(NL)], 1)
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    np.testing.assert_allclose(d / H, normal, atol=1e-12)
    # the default slope is the numerical derivative: same mesh within its truncation error
    mesh2 = P.beam_mesh(X, z, W, H, np.zeros((NL, NT)))
    np.testing.assert_allclose(mesh2.vertices, mesh.vertices, atol=1e-12)  # exact for a parabola


def test_beam_mesh_geometry_carries_vertex_colors_of_the_scale():
    vals = levels(np.full(NL, 3.0), np.full(NL, -3.0))
    mesh = P.beam_mesh(X, np.zeros(NL), W, H, vals)
    scale = P.ColorScale.symmetric(3.0, unit="MPa")
    geom = mesh.geometry(scale)
    assert isinstance(geom, g.TriangularMeshGeometry)
    top = mesh.vertices[:, 2] > H / 2 - 1e-12
    red_end = matplotlib.colormaps["RdBu_r"](1.0)[:3]
    np.testing.assert_allclose(geom.color[top], np.tile(red_end, (top.sum(), 1)),
                               atol=1e-6)


def test_beam_mesh_bad_input():
    with pytest.raises(ValueError, match="values must have shape"):
        P.beam_mesh(X, np.zeros(NL), W, H, np.zeros((NL, 1)))
    with pytest.raises(ValueError, match="deflection must have 21 elements"):
        P.beam_mesh(X, np.zeros(NL - 1), W, H, np.zeros((NL, NT)))
    with pytest.raises(ValueError, match="thickness must be > 0"):
        P.beam_mesh(X, np.zeros(NL), W, -1.0, np.zeros((NL, NT)))
    with pytest.raises(ValueError, match="x must be strictly increasing"):
        P.beam_mesh(X[::-1], np.zeros(NL), W, H, np.zeros((NL, NT)))


# --- rigid primitives --------------------------------------------------------------------------
@pytest.mark.parametrize("vector", [[0.0, 0.0, 0.5], [0.3, -0.2, -0.4], [0.0, -1.0, 0.0],
                                    [0.0, 0.0, 0.02]])
def test_arrow_spans_start_to_start_plus_vector(vector):
    rec = Recorder()
    arrow = P.Arrow(rec, radius=0.01, head_length=0.06)
    start = np.array([1.0, 2.0, -0.5])
    arrow.set(start, vector)
    shaft, head = rec.log["/shaft"]["transform"], rec.log["/head"]["transform"]
    length = np.linalg.norm(vector)
    head_len = min(0.06, length)
    d = np.asarray(vector) / length
    np.testing.assert_allclose(apply(shaft, [0, -0.5, 0]), start, atol=1e-9)
    np.testing.assert_allclose(apply(shaft, [0, 0.5, 0]), start + d * (length - head_len), atol=1e-9)
    np.testing.assert_allclose(apply(head, [0, 0.03, 0]), start + np.asarray(vector), atol=1e-12)  # apex
    assert "visible" not in rec.log.get("", {})  # visible from the start: nothing sent
    arrow.set(start, [0, 0, 0])
    assert rec.log["/"]["visible"] is False
    arrow.set(start, vector)
    assert rec.log["/"]["visible"] is True


def test_segment_and_cone_and_camera():
    rec = Recorder()
    seg = P.Segment(rec["laser"])
    a, b = np.array([0.0, 0.0, 1.0]), np.array([1.0, 0.5, 0.0])
    seg.set(a, b)
    t = rec.log["/laser"]["transform"]
    np.testing.assert_allclose(apply(t, [0, -0.5, 0]), a, atol=1e-12)
    np.testing.assert_allclose(apply(t, [0, 0.5, 0]), b, atol=1e-12)
    P.cone(rec["tip"], height=0.1, radius=0.03)
    t = rec.log["/tip/shape"]["transform"]
    np.testing.assert_allclose(apply(t, [0, 0.05, 0]), [0, 0, 0], atol=1e-12)  # apex at the origin
    np.testing.assert_allclose(apply(t, [0, -0.05, 0]), [0, 0, 0.1], atol=1e-12)  # base above
    P.set_camera(rec, [1.0, -3.0, 2.0])
    # three.js camera frame is y-up, rotated +90 deg about x: world (x, y, z) = (x', -z', y')
    x_, y_, z_ = rec.log["/Cameras/default/rotated/<object>"]["position"]
    assert (x_, -z_, y_) == (1.0, -3.0, 2.0)


def test_legend_png_and_html_state_the_unit():
    scale = P.ColorScale.symmetric(5.0, label="bending stress", unit="MPa")
    png = P.colorbar_png(scale, size_px=(400, 100))
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    img = matplotlib.image.imread(io.BytesIO(png))
    assert img.shape[:2] == (100, 400)
    row = img[int(0.3 * 100)]  # through the bar (the bar spans 15%-45% from the top)
    assert row[30, 2] > row[30, 0] and row[370, 0] > row[370, 2]  # blue on the left, red on the right
    html = P.legend_html(scale)
    assert "bending stress [MPa]" in html and ">-5<" in html and ">5<" in html


@pytest.mark.parametrize("limit, exponent", [(1e-3, -3), (5e-3, -3), (0.05, -3), (0.1, 0),
                                             (0.5, 0), (5.0, 0),
                                             (500.0, 0), (1e3, 3), (2e3, 3), (5e4, 3), (1e6, 6)])
def test_legend_ticks_are_short_with_a_common_power_of_ten(limit, exponent):
    # the 1, 2, 5 x 10^n limits of a stress legend: at 1000 MPa "%.3g" wrote "1e+03", wider than
    # the space beside the bar's end; now the labels stay within 5 characters (-0.25, -250)
    ticks = np.linspace(-limit, limit, 5)
    labels, e = P.tick_labels(ticks)
    assert e == exponent
    assert all(len(t) <= 5 and "e" not in t for t in labels), labels
    np.testing.assert_allclose([float(t) * 10.0 ** e for t in labels], ticks, rtol=1e-12)
    scale = P.ColorScale.symmetric(limit, label="bending stress", unit="MPa")
    title = P.legend_title(scale, e)
    assert title == ("bending stress [MPa]" if e == 0 else f"bending stress [x 10^{e} MPa]")
    assert (f"{title}</div>" in P.legend_html(scale)) and (f">{labels[0]}<" in P.legend_html(scale))


@pytest.mark.parametrize("limit", [1e3, 5e4, 1e-3, 0.5])
def test_legend_texts_stay_inside_the_plate(limit):
    # the bar stops 1/16 of the width from each edge: a label spilling past the plate would leave
    # dark pixels in the outermost columns (and be cut off in the 3D view)
    png = P.colorbar_png(P.ColorScale.symmetric(limit, label="bending stress", unit="MPa"))
    img = matplotlib.image.imread(io.BytesIO(png))[..., :3]
    assert img[:, :2].min() > 0.9 and img[:, -2:].min() > 0.9
    assert img[int(0.7 * img.shape[0]):, :30].min() < 0.5  # but the first label is drawn


def test_primitives_in_a_real_viewer_update_in_place():
    try:
        vis = get_viewer()["test_primitives"]
        mesh = P.beam_mesh(X, 0.1 * X ** 2, W, H, levels(-X, X))
        scale = P.ColorScale.symmetric(2.0, unit="MPa")
        vis["beam"].set_object(mesh.geometry(scale), g.MeshLambertMaterial(vertexColors=True))
        arrow = P.Arrow(vis["force"])
        arrow.set([0, 0, 0], [0, 0, 0.3])
        legend = P.ColorLegend(vis["legend"], scale)
        assert legend.set(scale) is False  # same scale: no new texture
        assert legend.set(P.ColorScale.symmetric(5.0, unit="MPa")) is True
        before = len(get_viewer().static_html())
        P.set_camera(get_viewer(), [1.0, -3.0, 1.0])
        arrow.set([0, 0, 0], [0, 0, 0.5])  # moved in place: one transform per part, no new object
        assert len(get_viewer().static_html()) - before < 2000
    finally:
        close_viewer()


def test_camera_ndc_is_a_pinhole_projection():
    cam = [0.0, -4.0, 0.0]  # on the -y axis, looking at the origin: screen x = world x, up = z
    t = math.tan(math.radians(P.CAMERA_FOV / 2))
    pts = [[0, 0, 0], [4 * t * 1.5, 0, 0], [0, 0, -4 * t], [1, 2, 1], [0, -5, 0]]
    ndc = P.camera_ndc(pts, cam, aspect=1.5)
    np.testing.assert_allclose(ndc[:3], [[0, 0], [1, 0], [0, -1]], atol=1e-12)
    np.testing.assert_allclose(ndc[3], [1 / (6 * t * 1.5), 1 / (6 * t)], rtol=1e-12)  # depth 6
    assert np.isinf(ndc[4]).all()  # behind the camera
    with pytest.raises(ValueError, match="camera"):
        P.camera_ndc(pts, [0, 0, 3])  # straight down: no up direction
    with pytest.raises(ValueError, match="fov_deg"):
        P.camera_ndc(pts, cam, fov_deg=180)


def test_show_helpers_hides_the_grid_and_axes():
    rec = Recorder()
    P.show_helpers(rec, grid=False, axes=False)
    assert rec.log["/Grid"]["visible"] is False and rec.log["/Axes"]["visible"] is False


def test_text_plate_is_a_png_of_the_text_on_a_plate():
    img = matplotlib.image.imread(io.BytesIO(P.text_png("output / max", size_px=(300, 50))))
    assert img.shape[:2] == (50, 300)
    dark = img[..., 0] < 0.5
    assert dark[:, 100:200].any() and not dark[:, :10].any()  # centred text, white margins
    rec = Recorder()
    plate = P.TextPlate(rec["label"], "output / max", width=1.2)
    geom, material = rec.log["/label/plate"]["object"]
    np.testing.assert_allclose(geom.lengths, [1.2, 1.2 / 100, 0.2])
    assert material.map is not None
    np.testing.assert_allclose(rec.log["/label/plate"]["transform"][:3, 3], [0.6, 0.0, 0.1])
    assert plate.text == "output / max"


# --- tube (wires) -------------------------------------------------------------------------------
def test_tube_rings_sit_at_the_radius_around_their_points():
    pts = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [1, 1, 0.5]], float)
    v, f = P.Tube.mesh(pts, radius=0.1, sides=8)
    assert v.shape == (4 * 8, 3) and f.shape == (3 * 8 * 2, 3)
    assert f.min() == 0 and f.max() == len(v) - 1
    rings = v.reshape(4, 8, 3)
    np.testing.assert_allclose(np.linalg.norm(rings - pts[:, None, :], axis=2), 0.1, rtol=1e-12)
    np.testing.assert_allclose(rings.mean(axis=1), pts, atol=1e-12)
    # on a straight leg the ring is normal to the leg
    np.testing.assert_allclose((rings[0] - pts[0]) @ (pts[1] - pts[0]), 0.0, atol=1e-12)


def test_tube_is_one_object_per_update():
    rec = Recorder()
    tube = P.Tube(rec["wire"], radius=0.02)
    for k in range(3):
        tube.set([[0, 0, 0], [1, 0, 0.1 * k], [2, 0, 0]])
    assert rec.log["/wire"]["n_objects"] == 3 and len(rec.calls) == 3
    with pytest.raises(ValueError, match="points must have shape"):
        tube.set([[0, 0, 0]])
