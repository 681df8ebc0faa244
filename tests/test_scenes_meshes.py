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



def test_beam_sizes_are_bounded_by_name_before_any_work():
    # beam_faces(10**6, 1000) asked numpy for ~10^9 indices: a MemoryError, or minutes of swap
    with pytest.raises(ValueError, match="n_length and n_thickness must make at most"):
        beam_faces(10 ** 6, 1000)
    with pytest.raises(ValueError, match="n_thickness must be"):
        beam_faces(10, 10 ** 6)
    with pytest.raises(ValueError, match="n_length must be"):
        beam_faces(1, 5)
    with pytest.raises(ValueError, match="values must make at most"):
        beam_mesh(np.arange(2100.0), np.zeros(2100), 1.0, 1.0, np.zeros((2100, 1000)))


@pytest.mark.slow
def test_the_largest_beam_is_built_within_seconds():
    n_length = (MAX_VERTICES - 8) // 8  # the largest beam of 2 levels
    assert beam_faces(n_length, 2).max() == 8 * n_length + 8 - 1


# --- the height map ----------------------------------------------------------------------------
def test_height_map_vertices_of_a_hand_computed_grid():
    # 2 rows x 3 columns; 2 nm between columns (x), 5 nm between rows (y), drawn in nm
    h = np.array([[0.0, 1.0, 2.0], [3.0, 4.0, 5.0]]) * 1e-9
    mesh = height_map_mesh(h, 2e-9, unit=1e-9, pixel_size_y=5e-9, origin=(10e-9, -5e-9))
    expected = [[10, -5, 0], [12, -5, 1], [14, -5, 2],
                [10, 0, 3], [12, 0, 4], [14, 0, 5]]
    np.testing.assert_allclose(mesh.vertices, expected, rtol=1e-6)
    assert mesh.vertices.dtype == np.float32
    np.testing.assert_array_equal(mesh.values, h.ravel())  # coloured by height (m) by default
    # two triangles per cell, every vertex used, each cell covered once: total area 4 nm x 5 nm
    assert mesh.faces.shape == (2 * 1 * 2, 3) and set(mesh.faces.ravel()) == set(range(6))
    flat = height_map_mesh(np.zeros((2, 3)), 2e-9, unit=1e-9, pixel_size_y=5e-9)
    p = flat.vertices[flat.faces].astype(float)
    normals = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    np.testing.assert_allclose(normals[:, :2], 0.0)
    assert np.all(normals[:, 2] > 0)  # facing up: counter-clockwise seen from +z
    assert 0.5 * normals[:, 2].sum() == pytest.approx(4.0 * 5.0)


def test_height_map_of_a_tilted_plane_has_one_normal():
    # z = a x + b y: every triangle's normal is (-a, -b, 1) / sqrt(1 + a^2 + b^2), by hand
    a, b, dx = 0.3, -0.2, 1e-8
    rows, cols = 4, 7
    y, x = np.mgrid[0:rows, 0:cols] * dx
    mesh = height_map_mesh(a * x + b * y, dx, unit=dx, exaggeration=2.0)
    p = mesh.vertices[mesh.faces].astype(float)
    n = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    n /= np.linalg.norm(n, axis=1)[:, None]
    expected = np.array([-2 * a, -2 * b, 1.0]) / np.sqrt(1 + 4 * a * a + 4 * b * b)  # x2 drawn
    np.testing.assert_allclose(n, np.tile(expected, (len(n), 1)), atol=1e-6)
    assert len(n) == 2 * (rows - 1) * (cols - 1)


def test_height_map_colours_its_values_and_rejects_bad_input_by_name():
    h = np.arange(6.0).reshape(2, 3) * 1e-9
    mesh = height_map_mesh(h, 1e-9, unit=1e-9, values=h * 1e9)
    geom = mesh.geometry(ColorScale(0.0, 5.0, "viridis"))
    np.testing.assert_allclose(geom.color[[0, -1]], [matplotlib.colormaps["viridis"](0.0)[:3],
                                                     matplotlib.colormaps["viridis"](1.0)[:3]],
                               atol=1e-6)
    bad = [((np.full((2, 2), np.nan), 1e-9), {}, "heights"),
           ((np.zeros((1, 5)), 1e-9), {}, "at least 2 x 2"),
           ((np.zeros(5), 1e-9), {}, "heights"),
           ((np.zeros((2, 2)), 0.0), {}, "pixel_size must be > 0"),
           ((np.zeros((2, 2)), 1e-9), {"unit": -1.0}, "unit must be > 0"),
           ((np.zeros((2, 2)), 1e-9), {"values": np.zeros((3, 2))}, "values must have the shape"),
           ((np.zeros((2, 2)), 1e-9), {"exaggeration": 0.0}, "exaggeration must be > 0"),
           ((np.zeros((2049, 2048)), 1e-9), {}, "heights must make at most"),
           # 1 m in units of 1e-40 m: 1e40 scene units, inf in float32 (before: silently)
           ((np.ones((2, 2)), 1e-9), {"unit": 1e-40}, "must stay below 3.4e\\+38 scene units")]
    for args, kwargs, match in bad:
        with pytest.raises(ValueError, match=match):
            height_map_mesh(*args, **{"unit": 1e-9, **kwargs})


def test_the_contact_scene_draws_its_sample_as_a_height_map():
    from afmsmiler.contact import Parabolic, indent, surface_displacement
    from afmsmiler.scenes.contact import surface_mesh
    tip = Parabolic(20e-9)
    cur = indent([40e-9], 0.2, tip, 2e6, 0.3)
    v, f, depth = surface_mesh(tip, cur, 100e-9, 20e-9, 4, half=True)
    x = np.linspace(-100e-9, 100e-9, 9)
    y = x[4:]
    u = surface_displacement(tip, cur.z_s[0], np.hypot(x[None, :], y[:, None]))
    mesh = height_map_mesh(-u, 25e-9, unit=20e-9, origin=(-100e-9, 0.0))
    np.testing.assert_allclose(v, mesh.vertices, rtol=1e-6, atol=1e-6)
    np.testing.assert_array_equal(f, mesh.faces)
    np.testing.assert_allclose(depth, u.ravel(), rtol=1e-12)
