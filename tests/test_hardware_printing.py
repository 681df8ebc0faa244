"""An AFM image as a printable STL and back (issue 13, item 5).

References, none of them the code under test: trimesh's own watertightness and winding checks;
the volume of the piecewise-linear top surface summed cell by cell with numpy (each triangle its
area times its mean height) and, for a plane, the trapezoid rule; the binary STL format read with
a numpy structured dtype (80-byte header, uint32 count, 50-byte records of float32: normal, three
vertices, uint16 attribute), not trimesh's loader; trimesh's primitive boxes; the source paper's
example scale (an 80 um image printed 400x is 32 mm wide).
"""
import numpy as np
import pytest
import trimesh

from afmsmiler import samples
from afmsmiler.hardware import printing as pr
from afmsmiler.samples import Sample

MM = 1e-3
UM = 1e-6


@pytest.fixture(scope="module")
def image():
    """A rough 80 um image of 33 x 41 pixels (2.5 um / 2 um pixels: non-square, non-square grid)."""
    s = samples.rough_surface((33, 41), 2e-6, rms=0.5e-6, correlation_length=10e-6, seed=3)
    return Sample(s.heights, 2e-6, "rough", pixel_size_y=2.5e-6)


def _exact_volume(z, dx, dy):
    """Volume under the surface through the pixels, cells split along (j,i)-(j+1,i+1)."""
    z00, z01 = z[:-1, :-1], z[:-1, 1:]  # (j, i), (j, i+1)
    z11, z10 = z[1:, 1:], z[1:, :-1]    # (j+1, i+1), (j+1, i)
    return float(np.sum(dx * dy / 6 * (2 * z00 + z01 + 2 * z11 + z10)))


def _read_binary_stl(path):
    """Triangles (n, 3, 3) of a binary STL, read by hand from the format."""
    raw = path.read_bytes()
    count = int(np.frombuffer(raw[80:84], dtype="<u4")[0])
    record = np.dtype([("normal", "<f4", 3), ("v", "<f4", (3, 3)), ("attr", "<u2")])
    assert len(raw) == 84 + count * record.itemsize  # 50 bytes a triangle
    return np.frombuffer(raw[84:], dtype=record, count=count)["v"].astype(float)


def test_the_mesh_is_a_closed_consistently_wound_solid(image):
    mesh = pr.sample_to_mesh(image, lateral_scale=400, base_thickness=2 * MM)
    assert mesh.is_watertight and mesh.is_winding_consistent and mesh.is_volume
    assert mesh.volume > 0  # normals outward: the signed volume is positive
    assert len(mesh.faces) == pr.triangle_count(image.shape)
    rows, cols = image.shape
    assert len(mesh.faces) == 2 * (rows - 1) * (cols - 1) + 6 * (rows + cols - 2)
    # the top faces point up, the base down, the walls sideways
    normals = mesh.face_normals
    n_top = 2 * (rows - 1) * (cols - 1)
    assert (normals[:n_top, 2] > 0).all()
    assert np.allclose(normals[-2 * (rows + cols - 2):], [0, 0, -1])
    assert np.allclose(normals[n_top:-2 * (rows + cols - 2), 2], 0, atol=1e-12)
    # no degenerate triangle (a slicer drops them)
    assert mesh.area_faces.min() > 0


def test_volume_is_the_integral_of_height_plus_base(image):
    ls, vs, base = 400.0, 1000.0, 1.5 * MM
    mesh = pr.sample_to_mesh(image, lateral_scale=ls, vertical_scale=vs, base_thickness=base)
    z = base + vs * (image.heights - image.heights.min())
    expected = _exact_volume(z, image.pixel_size * ls, image.pixel_size_y * ls)
    assert mesh.volume == pytest.approx(expected, rel=1e-12)
    # for a plane the trapezoid rule is exact too
    yy, xx = np.mgrid[0:20, 0:30]
    plane = Sample((0.3 * xx + 0.7 * yy) * 1e-7, 1e-6)
    mesh = pr.sample_to_mesh(plane, lateral_scale=1000, base_thickness=MM)
    zp = MM + 1000 * plane.heights
    trap = np.trapezoid(np.trapezoid(zp, dx=1 * MM, axis=1), dx=1 * MM)
    assert mesh.volume == pytest.approx(trap, rel=1e-12)


def test_the_stl_read_back_has_the_image_heights_at_the_scale(image, tmp_path):
    ls, vs, base = 400.0, 2000.0, 2 * MM
    path = pr.save_stl(image, tmp_path / "shell.stl", lateral_scale=ls, vertical_scale=vs,
                       base_thickness=base)
    assert path.exists() and not (tmp_path / "shell.stl.part").exists()
    tri = _read_binary_stl(path)
    assert len(tri) == pr.triangle_count(image.shape)
    v = tri.reshape(-1, 3) * MM  # the file is in mm
    rows, cols = image.shape
    # the top vertices: the highest z at each pixel position
    i = np.rint(v[:, 0] / (image.pixel_size * ls)).astype(int)
    j = np.rint(v[:, 1] / (image.pixel_size_y * ls)).astype(int)
    top = np.full((rows, cols), -np.inf)
    np.maximum.at(top, (j, i), v[:, 2])
    expected = base + vs * (image.heights - image.heights.min())
    # float32 holds 24 bits: a few mm to about 1e-7 mm
    np.testing.assert_allclose(top, expected, rtol=0, atol=4 * np.finfo(np.float32).eps *
                               expected.max())
    assert v[:, 2].min() == 0.0  # the base's underside is the bed
    # every vertex sits on the pixel grid (x, y) to float32 round-off
    np.testing.assert_allclose(v[:, 0], np.clip(i, 0, cols - 1) * image.pixel_size * ls,
                               atol=1e-6 * MM)


def test_mesh_to_sample_at_the_printed_pitch_gives_the_image_back(image, tmp_path):
    ls, vs, base = 400.0, 400.0, 2 * MM
    square = Sample(image.heights, 2e-6)  # mesh_to_sample's grid is square
    expected = base + vs * (square.heights - square.heights.min())
    # from the mesh in m (exact) ...
    mesh = pr.sample_to_mesh(square, lateral_scale=ls, vertical_scale=vs, base_thickness=base)
    back = pr.mesh_to_sample(mesh, 2e-6 * ls)
    assert back.shape == square.shape and back.pixel_size == pytest.approx(0.8 * MM)
    np.testing.assert_allclose(back.heights, expected, rtol=0, atol=1e-15)
    # ... and from the STL file in mm (float32)
    path = pr.save_stl(square, tmp_path / "s.stl", lateral_scale=ls, vertical_scale=vs,
                       base_thickness=base)
    back = pr.mesh_to_sample(path, 0.8 * MM)
    np.testing.assert_allclose(back.heights, expected, rtol=0,
                               atol=4 * np.finfo(np.float32).eps * expected.max())


def test_mesh_to_sample_between_pixels_follows_the_facets():
    """A plane is its own linear interpolation: any pitch gives the plane back."""
    yy, xx = np.mgrid[0:11, 0:16]
    plane = Sample((2.0 * xx + 3.0 * yy) * 1e-7, 1e-6)  # slopes 0.2 and 0.3
    mesh = pr.sample_to_mesh(plane, lateral_scale=1000, vertical_scale=1000, base_thickness=MM)
    back = pr.mesh_to_sample(mesh, 0.37 * MM)
    x, y = np.meshgrid(back.x, back.y)
    np.testing.assert_allclose(back.heights, MM + 0.2 * x + 0.3 * y, rtol=1e-12)


def test_mesh_to_sample_sees_the_highest_surface_of_any_mesh():
    """Two trimesh boxes, a 4 mm one standing on a 10 mm one: the top of each where it is."""
    lower = trimesh.creation.box(extents=(10 * MM, 10 * MM, 2 * MM))
    lower.apply_translation((5 * MM, 5 * MM, 1 * MM))
    upper = trimesh.creation.box(extents=(4 * MM, 4 * MM, 3 * MM))
    upper.apply_translation((5 * MM, 5 * MM, 2.5 * MM))  # z from 1 to 4 mm: overlapping
    back = pr.mesh_to_sample(trimesh.util.concatenate([lower, upper]), 0.5 * MM)
    assert back.shape == (21, 21)
    x, y = np.meshgrid(back.x, back.y)
    on_top = (np.abs(x - 5 * MM) <= 2 * MM + 1e-12) & (np.abs(y - 5 * MM) <= 2 * MM + 1e-12)
    np.testing.assert_allclose(back.heights, np.where(on_top, 4 * MM, 2 * MM), rtol=1e-12)


def test_the_papers_scale_80_um_printed_400x_is_32_mm():
    # 129 pixels of 0.625 um: 80 um first to last pixel; printed 400x
    shell = samples.rough_surface((129, 129), 0.625 * UM, rms=2 * UM, correlation_length=8 * UM,
                                  seed=1)
    assert shell.width == pytest.approx(80 * UM)
    x, y, z = pr.print_size(shell, lateral_scale=400, base_thickness=2 * MM)
    assert x == pytest.approx(32 * MM) and y == pytest.approx(32 * MM)
    assert z == pytest.approx(2 * MM + 400 * np.ptp(shell.heights))
    mesh = pr.sample_to_mesh(shell, lateral_scale=400, base_thickness=2 * MM)
    np.testing.assert_allclose(mesh.extents, (x, y, z), rtol=1e-12)
    # the macroscopic AFM re-images it at 0.2 mm: 32 / 0.2 + 1 = 161 pixels a side
    back = pr.mesh_to_sample(mesh, 0.2 * MM)
    assert back.shape == (161, 161)
    # it fits an Ender 3's 220 mm bed up to 220 / 80 um = 2750x
    assert pr.fitting_scale(shell, (0.22, 0.22)) == pytest.approx(2750)
    assert pr.fitting_scale(shell, (0.22, 0.22), margin=10 * MM) == pytest.approx(2500)


@pytest.mark.parametrize("kwargs, match", [
    (dict(lateral_scale=-1.0), "lateral_scale"),
    (dict(lateral_scale=0.0), "lateral_scale"),
    (dict(vertical_scale=float("nan")), "vertical_scale"),
    (dict(base_thickness=0.0), "base_thickness"),
    (dict(lateral_scale=1e9), "lateral_scale"),   # a 32 km print: a unit slip
])
def test_bad_parameters_are_named_before_any_work(image, kwargs, match):
    with pytest.raises(ValueError, match=match):
        pr.sample_to_mesh(image, **kwargs)


def test_bad_inputs_are_named(image, tmp_path):
    with pytest.raises(TypeError, match="sample"):
        pr.sample_to_mesh(image.heights)
    with pytest.raises(ValueError, match="sample must be a 2-D image"):
        pr.sample_to_mesh(image.line(0))
    with pytest.raises(ValueError, match="path must end in .stl"):
        pr.save_stl(image, tmp_path / "x.obj")
    with pytest.raises(ValueError, match="path must be in an existing folder"):
        pr.save_stl(image, tmp_path / "nowhere" / "x.stl")
    with pytest.raises(ValueError, match="pitch"):
        pr.mesh_to_sample(pr.sample_to_mesh(image), -1.0)
    with pytest.raises(ValueError, match="pitch must give"):
        pr.mesh_to_sample(pr.sample_to_mesh(image, lateral_scale=400), 1e-7)
    with pytest.raises(ValueError, match="existing STL file"):
        pr.mesh_to_sample(tmp_path / "missing.stl")
    with pytest.raises(TypeError, match="mesh_or_path"):
        pr.mesh_to_sample(3.0)
    with pytest.raises(ValueError, match="bed"):
        pr.fitting_scale(image, (0.2, -1.0))


def test_size_limit_on_triangles_is_named():
    big = Sample(np.zeros((1100, 1100)), 1e-6)
    with pytest.raises(ValueError, match="sample must give at most"):
        pr.sample_to_mesh(big, lateral_scale=10)


def test_a_hole_in_the_surface_is_reported():
    box = trimesh.creation.box(extents=(10 * MM, 10 * MM, 2 * MM))
    up = box.face_normals[:, 2] > 0.5
    holed = trimesh.Trimesh(box.vertices, box.faces[~up | (np.arange(len(up)) !=
                                                          np.flatnonzero(up)[0])])
    with pytest.raises(ValueError, match="under no"):
        pr.mesh_to_sample(holed, 1 * MM)


def test_the_seashell_is_the_papers_80_um_object():
    shell = pr.seashell()
    assert shell.shape == (128, 128) and shell.width == pytest.approx(80 * UM)
    assert shell.heights.min() == 0.0 and 4 * UM < np.ptp(shell.heights) < 10 * UM
    x, y, _ = pr.print_size(shell, lateral_scale=400)
    assert x == pytest.approx(32 * MM) and y == pytest.approx(32 * MM)
    with pytest.raises(ValueError, match="shape"):
        pr.seashell(shape=64)
    with pytest.raises(ValueError, match="ribs"):
        pr.seashell(ribs=0)


def test_compare_scan_removes_the_offset_and_measures_the_shape_error():
    ref = Sample(np.arange(30.0).reshape(5, 6) * 1e-5, 0.2 * MM)
    rng = np.random.default_rng(0)
    noise = rng.normal(size=(4, 6)) * 1e-6
    scan = Sample(ref.heights[:4] + 7e-3 + noise, 0.2 * MM)  # 4 lines done, homed 7 mm up
    c = pr.compare_scan(ref, scan)
    expected = noise - noise.mean()
    np.testing.assert_allclose(c.difference.heights, expected, atol=1e-15)
    # one zero for both: the print's lowest point in the scanned corner; the 7 mm home offset gone
    np.testing.assert_allclose(c.reference.heights, ref.heights[:4] - ref.heights[:4].min(),
                               atol=1e-15)
    np.testing.assert_allclose(c.image.heights, ref.heights[:4] - ref.heights[:4].min()
                               + expected, atol=1e-15)
    assert c.rms == pytest.approx(np.sqrt(np.mean(expected ** 2)))
    assert c.max_abs == pytest.approx(np.abs(expected).max())
    with pytest.raises(ValueError, match="pixel_size"):
        pr.compare_scan(ref, Sample(scan.heights, 0.3 * MM))
    with pytest.raises(ValueError, match="fit"):
        pr.compare_scan(scan, ref)


def test_bad_values_found_by_the_api_campaign_are_named():
    """The lead's bad-input campaign, run on this module, found these (each failed before)."""
    extreme = Sample(np.array([[-1e308, 1e308], [0.0, 1.0]]), 1e-6)
    for call in (lambda: pr.print_size(extreme), lambda: pr.sample_to_mesh(extreme)):
        with pytest.raises(ValueError, match="sample"):
            call()
    for shape in (float("nan"), "ab", (2,), (1, 5), (3.5, 4)):
        with pytest.raises((TypeError, ValueError), match="shape"):
            pr.triangle_count(shape)
    for margin in (None, "1", float("nan"), -1.0, 0.2):
        with pytest.raises((TypeError, ValueError), match="margin"):
            pr.fitting_scale(pr.seashell(), (0.22, 0.22), margin=margin)
    big = Sample(np.zeros((3, 3)), 1e-6)
    with pytest.raises(ValueError, match="sample"):  # the scale's message names the sample
        pr.sample_to_mesh(big, lateral_scale=1e9)
