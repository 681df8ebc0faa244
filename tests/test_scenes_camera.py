"""The camera: where meshcat's camera is put, where points land on its screen, the helpers."""
import math

import numpy as np
import pytest

from afmsmiler.scenes.camera import CAMERA_FOV, camera_ndc, set_camera, show_helpers
from tests.recording import Recorder


def test_set_camera_converts_to_the_y_up_camera_frame():
    rec = Recorder()
    set_camera(rec, [1.0, -3.0, 2.0])
    # three.js camera frame is y-up, rotated +90 deg about x: world (x, y, z) = (x', -z', y')
    x_, y_, z_ = rec.log["/Cameras/default/rotated/<object>"]["position"]
    assert (x_, -z_, y_) == (1.0, -3.0, 2.0)



def test_camera_ndc_is_a_pinhole_projection():
    cam = [0.0, -4.0, 0.0]  # on the -y axis, looking at the origin: screen x = world x, up = z
    t = math.tan(math.radians(CAMERA_FOV / 2))
    pts = [[0, 0, 0], [4 * t * 1.5, 0, 0], [0, 0, -4 * t], [1, 2, 1], [0, -5, 0]]
    ndc = camera_ndc(pts, cam, aspect=1.5)
    np.testing.assert_allclose(ndc[:3], [[0, 0], [1, 0], [0, -1]], atol=1e-12)
    np.testing.assert_allclose(ndc[3], [1 / (6 * t * 1.5), 1 / (6 * t)], rtol=1e-12)  # depth 6
    assert np.isinf(ndc[4]).all()  # behind the camera
    with pytest.raises(ValueError, match="camera"):
        camera_ndc(pts, [0, 0, 3])  # straight down: no up direction
    with pytest.raises(ValueError, match="fov_deg"):
        camera_ndc(pts, cam, fov_deg=180)


def test_show_helpers_hides_the_grid_and_axes():
    rec = Recorder()
    show_helpers(rec, grid=False, axes=False)
    assert rec.log["/Grid"]["visible"] is False and rec.log["/Axes"]["visible"] is False

