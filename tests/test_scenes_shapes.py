"""Rigid shapes land where asked: arrows, segments, cones, tubes."""
import numpy as np
import pytest

from afmsmiler.scenes.shapes import Arrow, Segment, Tube, cone
from tests.recording import Recorder


def apply(t, p):
    return (t @ np.append(p, 1.0))[:3]


@pytest.mark.parametrize("vector", [[0.0, 0.0, 0.5], [0.3, -0.2, -0.4], [0.0, -1.0, 0.0],
                                    [0.0, 0.0, 0.02]])
def test_arrow_spans_start_to_start_plus_vector(vector):
    rec = Recorder()
    arrow = Arrow(rec, radius=0.01, head_length=0.06)
    start = np.array([1.0, 2.0, -0.5])
    arrow.set(start, vector)
    shaft, head = rec.log["/shaft"]["transform"], rec.log["/head"]["transform"]
    length = np.linalg.norm(vector)
    head_len = min(0.06, length)
    d = np.asarray(vector) / length
    np.testing.assert_allclose(apply(shaft, [0, -0.5, 0]), start, atol=1e-9)
    np.testing.assert_allclose(apply(shaft, [0, 0.5, 0]), start + d * (length - head_len),
                               atol=1e-9)
    np.testing.assert_allclose(apply(head, [0, 0.03, 0]), start + np.asarray(vector),
                               atol=1e-12)  # apex
    assert "visible" not in rec.log.get("", {})  # visible from the start: nothing sent
    arrow.set(start, [0, 0, 0])
    assert rec.log["/"]["visible"] is False
    arrow.set(start, vector)
    assert rec.log["/"]["visible"] is True


def test_segment_and_cone_land_where_asked():
    rec = Recorder()
    seg = Segment(rec["laser"])
    a, b = np.array([0.0, 0.0, 1.0]), np.array([1.0, 0.5, 0.0])
    seg.set(a, b)
    t = rec.log["/laser"]["transform"]
    np.testing.assert_allclose(apply(t, [0, -0.5, 0]), a, atol=1e-12)
    np.testing.assert_allclose(apply(t, [0, 0.5, 0]), b, atol=1e-12)
    cone(rec["tip"], height=0.1, radius=0.03)
def test_tube_rings_sit_at_the_radius_around_their_points():
    pts = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [1, 1, 0.5]], float)
    v, f = Tube.mesh(pts, radius=0.1, sides=8)
    assert v.shape == (4 * 8, 3) and f.shape == (3 * 8 * 2, 3)
    assert f.min() == 0 and f.max() == len(v) - 1
    rings = v.reshape(4, 8, 3)
    np.testing.assert_allclose(np.linalg.norm(rings - pts[:, None, :], axis=2), 0.1, rtol=1e-12)
    np.testing.assert_allclose(rings.mean(axis=1), pts, atol=1e-12)
    # on a straight leg the ring is normal to the leg
    np.testing.assert_allclose((rings[0] - pts[0]) @ (pts[1] - pts[0]), 0.0, atol=1e-12)


def test_tube_is_one_object_per_update():
    rec = Recorder()
    tube = Tube(rec["wire"], radius=0.02)
    for k in range(3):
        tube.set([[0, 0, 0], [1, 0, 0.1 * k], [2, 0, 0]])
    assert rec.log["/wire"]["n_objects"] == 3 and len(rec.calls) == 3
    with pytest.raises(ValueError, match="points must have shape"):
        tube.set([[0, 0, 0]])


def test_a_wrong_visualizer_is_named_before_drawing():
    """A string or a number given as ``vis`` raised "string indices must be integers" or
    AttributeError: 'float' object has no attribute 'set_object' from inside the shape."""
    from afmsmiler.scenes.transforms import check_visualizer
    vis = Recorder()
    assert check_visualizer("vis", vis) is vis and check_visualizer("vis", vis["a"]) is not None
    for bad in ("/scene", 3.0, None, object()):
        with pytest.raises(TypeError, match=r"^vis must be a meshcat.Visualizer \(or draw like "
                                            r"one\), got "):
            cone(bad, 1.0, 0.5)
        with pytest.raises(TypeError, match="^vis must be a meshcat.Visualizer"):
            Segment(bad)
    assert vis.calls == []  # nothing drawn


def test_a_colour_is_an_int_0xRRGGBB_named_before_drawing():
    """A float, a string or NaN given as a colour reached the browser as a colour three.js
    cannot read (accepted silently)."""
    from afmsmiler.scenes.shapes import polyline, sphere
    vis = Recorder()
    for bad in (0.5, "red", None, float("nan"), -1, 0x1000000, True):
        with pytest.raises(ValueError, match=r"^color \(0xRRGGBB\) must be an integer in "
                                             r"\[0, 16777215\], got "):
            Arrow(vis, color=bad)
        with pytest.raises(ValueError, match=r"^color \(0xRRGGBB\)"):
            polyline(vis, np.zeros((2, 3)), color=bad)
    with pytest.raises(ValueError, match=r"^opacity must be in \(0, 1\]"):
        sphere(vis, 1.0, opacity=float("nan"))
    assert vis.calls == []  # nothing drawn
