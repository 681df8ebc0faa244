"""Meshes: the beam follows the given deflection with true thickness and carries its values on
the right faces; a height map puts each height where its grid says; sizes are bounded."""
import meshcat.geometry as g
import matplotlib
import numpy as np
import pytest

from afmsmiler.scenes.colors import ColorScale
from afmsmiler.scenes.meshes import MAX_VERTICES, beam_faces, beam_mesh, height_map_mesh


NL, NT = 21, 5
X = np.linspace(0.0, 2.0, NL)
W, H = 0.3, 0.04


def levels(values_top, values_bottom):
    return np.linspace(values_bottom, values_top, NT).T  # (NL, NT), bottom -> top


def test_flat_beam_is_a_box_with_values_on_the_right_faces():
    vals = levels(-X, X)  # top = -x, bottom = +x
    mesh = beam_mesh(X, np.zeros(NL), W, H, vals)
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
    mesh = beam_mesh(X, z, W, H, np.zeros((NL, NT)), slope=2 * a * X)
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
    mesh2 = beam_mesh(X, z, W, H, np.zeros((NL, NT)))
    np.testing.assert_allclose(mesh2.vertices, mesh.vertices, atol=1e-12)  # exact for a parabola


def test_beam_mesh_geometry_carries_vertex_colors_of_the_scale():
    vals = levels(np.full(NL, 3.0), np.full(NL, -3.0))
    mesh = beam_mesh(X, np.zeros(NL), W, H, vals)
    scale = ColorScale.symmetric(3.0, unit="MPa")
    geom = mesh.geometry(scale)
    assert isinstance(geom, g.TriangularMeshGeometry)
    top = mesh.vertices[:, 2] > H / 2 - 1e-12
    red_end = matplotlib.colormaps["RdBu_r"](1.0)[:3]
    np.testing.assert_allclose(geom.color[top], np.tile(red_end, (top.sum(), 1)),
                               atol=1e-6)


def test_beam_mesh_bad_input():
    with pytest.raises(ValueError, match="values must have shape"):
        beam_mesh(X, np.zeros(NL), W, H, np.zeros((NL, 1)))
    with pytest.raises(ValueError, match="deflection must have 21 elements"):
        beam_mesh(X, np.zeros(NL - 1), W, H, np.zeros((NL, NT)))
    with pytest.raises(ValueError, match="thickness must be > 0"):
        beam_mesh(X, np.zeros(NL), W, -1.0, np.zeros((NL, NT)))
    with pytest.raises(ValueError, match="x must be strictly increasing"):
        beam_mesh(X[::-1], np.zeros(NL), W, H, np.zeros((NL, NT)))

