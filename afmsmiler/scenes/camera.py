"""The camera of a scene: where meshcat's default camera stands, where points land on its screen,
and meshcat's helper grid and axes."""
from __future__ import annotations

import math

import meshcat
import numpy as np

from ..validation import check_array, check_flag, check_positive, check_range
from .transforms import check_point, check_visualizer

__all__ = ["set_camera", "CAMERA_FOV", "camera_ndc", "show_helpers", "READABLE_TEXT",
           "readable_width"]


def set_camera(vis: meshcat.Visualizer, position) -> None:
    """Put the default camera of viewer ``vis`` at ``position`` (world frame, z up, scene units).

    The camera keeps looking at the world origin, so scene builders centre their objects there.
    """
    check_visualizer("vis", vis)
    x, y, z = check_point("position", position)
    # the camera node is rotated by +pi/2 about x (three.js is y-up): world (x, y, z) -> (x, z, -y)
    vis["/Cameras/default/rotated/<object>"].set_property("position", [x, z, -y])


#: Vertical field of view of meshcat's default camera in degrees (three.js's
#: ``PerspectiveCamera(75, ...)``).
CAMERA_FOV = 75.0


def camera_ndc(points, position, target=(0.0, 0.0, 0.0), fov_deg: float = CAMERA_FOV,
               aspect: float = 1.5) -> np.ndarray:
    """Where ``points`` land on the screen of a camera at ``position`` looking at ``target``.

    A pinhole projection with z up (meshcat's orbit camera), used to check that a scene builder
    frames its objects: a point is in view when both coordinates lie in [-1, 1].

    Parameters
    ----------
    points : array_like, shape (N, 3)
        World positions in scene units.
    position, target : array_like, shape (3,)
        Camera position and the point it looks at (meshcat's default: the origin).
    fov_deg : float
        Vertical field of view in degrees, in (0, 180).
    aspect : float
        Width / height of the view (> 0), e.g. 1.5 for 1200 x 800 pixels.

    Returns
    -------
    ndarray, shape (N, 2)
        Normalised device coordinates (x right, y up); ``inf`` for points behind the camera.
    """
    pts = check_array("points", points, ndim=2)
    if pts.shape[1] != 3:
        raise ValueError(f"points must have shape (N, 3), got {pts.shape}")
    pos, tgt = check_point("position", position), check_point("target", target)
    fov = check_range("fov_deg", fov_deg, 0.0, 180.0, "deg", low_inclusive=False,
                      high_inclusive=False)
    aspect = check_positive("aspect", aspect)
    forward = tgt - pos
    if np.linalg.norm(forward) == 0 or np.linalg.norm(np.cross(forward, [0, 0, 1])) == 0:
        raise ValueError("the camera must look at a target other than its position, not straight "
                         f"up or down; got position {pos.tolist()} and target {tgt.tolist()}")
    forward /= np.linalg.norm(forward)
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    d = pts - pos
    depth = d @ forward
    t = math.tan(math.radians(fov) / 2)
    with np.errstate(divide="ignore", invalid="ignore"):
        ndc = np.stack([(d @ right) / (depth * t * aspect), (d @ up) / (depth * t)], -1)
    ndc[depth <= 0] = np.inf
    return ndc


def show_helpers(vis: meshcat.Visualizer, grid: bool = True, axes: bool = True) -> None:
    """Show or hide meshcat's ground grid (the plane z = 0) and its x-y-z axes at the origin.

    Scene builders centre their objects on the origin, where the axes would poke through them,
    and a sample surface at z = 0 would fight with the grid: hide what gets in the way.

    Parameters
    ----------
    vis : meshcat.Visualizer
        Any visualizer of the viewer (the helpers live at its root).
    grid, axes : bool
        Whether to show the grid and the axes.
    """
    check_visualizer("vis", vis)
    grid, axes = check_flag("grid", grid), check_flag("axes", axes)
    vis["/Grid"].set_property("visible", grid)
    vis["/Axes"].set_property("visible", axes)


#: The smallest height, as a fraction of the view's height, at which a line of text in a scene
#: reads: 10 px in the 400-pixel-high frame meshcat opens in a notebook cell, 20 px in an
#: 800-pixel-high browser tab.
READABLE_TEXT = 0.025


def readable_width(text_fraction: float, position, camera_position, target=(0.0, 0.0, 0.0), *,
                   fov_deg: float = CAMERA_FOV, text_height: float = READABLE_TEXT) -> float:
    """Width of an upright text plate centred at ``position`` whose text spans ``text_height``
    of the view's height.

    A legend sized by a fixed number of scene units reads in one scene and is a smudge in the
    next; sized by this, its text has the same height on screen whatever the scene's scale. The
    plates (:class:`~afmsmiler.scenes.legends.ColorLegend`, ``TextPlate``) stand upright, so the
    text's height is measured along z, projected by :func:`camera_ndc`: a plate seen from above
    or below is foreshortened, and one far off the axis of view stretched, as on screen.

    Parameters
    ----------
    text_fraction : float
        Height of the plate's text as a fraction of the plate's width (> 0), e.g.
        :attr:`~afmsmiler.scenes.legends.ColorLegend.TEXT_FRACTION`.
    position : array_like, shape (3,)
        Where the plate's centre will be, world frame, scene units.
    camera_position, target : array_like, shape (3,)
        The camera and the point it looks at (see :func:`camera_ndc`).
    fov_deg : float
        Vertical field of view in degrees, in (0, 180).
    text_height : float
        The fraction of the view's height the text must span, in (0, 1]; by default
        :data:`READABLE_TEXT`.

    Returns
    -------
    float
        The plate's width in scene units.

    Raises
    ------
    ValueError
        If a parameter is out of range or ``position`` is not in front of the camera.
    """
    text_fraction = check_positive("text_fraction", text_fraction)
    text_height = check_range("text_height", text_height, 0.0, 1.0, low_inclusive=False)
    pos, cam = check_point("position", position), check_point("camera_position", camera_position)
    depth = float(np.linalg.norm(pos - cam))
    # a short upright segment through the centre: the screen's height per scene unit there
    half = 1e-3 * max(depth, 1e-300)
    ndc = camera_ndc([pos - [0.0, 0.0, half], pos + [0.0, 0.0, half]], cam, target,
                     fov_deg=fov_deg, aspect=1.0)
    if not np.isfinite(ndc).all():
        raise ValueError(f"position must be in front of the camera, got {pos.tolist()} for a "
                         f"camera at {cam.tolist()} looking at {np.asarray(target).tolist()}")
    per_unit = abs(float(ndc[1, 1] - ndc[0, 1])) / 2 / (2 * half)  # fraction of view height
    if per_unit <= 0:
        raise ValueError(f"position must not be seen edge-on from the camera, got "
                         f"{pos.tolist()} for a camera at {cam.tolist()}")
    return text_height / (per_unit * text_fraction)
