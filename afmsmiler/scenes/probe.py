"""The 3D view of module (a)'s "your probe": the lever's plan view, twisted by a friction force.

Scale: **1 scene unit = 100 um** (:data:`SCENE_UNIT`, as module (a)'s other view). The lever lies
along +x from its clamp (shifted by -L/2 so that the camera, which looks at the origin, sees it
centred), z up, its tip under it at the tip position. The lever is drawn from its plan view
(:func:`afmsmiler.probe.half_widths`: a rectangle, a pointed end or a V's two arms), true to
scale, and twisted about its long axis: the model gives the twist of the tip's section,
phi = F_L (h_tip + t/2) / k_phi (:meth:`afmsmiler.modes.LateralLever.twist`); the drawing
magnifies it by :attr:`ProbeScene.factor`, one round factor per lever (the twist at the slider's
largest force drawn at about 30 deg), so that the drawn twist follows the force. Along the lever
the drawn twist grows linearly from the clamp to the tip's section, as it does in a uniform bar
under an end torque (Saint-Venant torsion), and stays the tip's beyond it; for a pointed or
V-shaped lever this shape is a drawing, the tip's twist is the model's.

The scene draws what the panel computed (a :class:`~afmsmiler.planform.Lever` and a twist angle)
and computes no physics: the mesh is sent again at each update (one message).
"""
from __future__ import annotations

import math

import meshcat
import meshcat.geometry as g
import numpy as np

from ..modes.lateral import LATERAL_FORCE, LateralLever
from ..parameters import read_only
from ..planform import Lever
from ..probe import half_widths
from ..validation import check_instance, check_range
from .camera import set_camera, show_helpers
from .modes import factor_text, round_factor
from .shapes import cone
from .transforms import translation
from .viewer import SceneDisplay, scene_root

__all__ = ["SCENE_UNIT", "DEFAULTS", "ProbeScene", "lever_mesh"]

#: Metres per scene unit (1 scene unit = 100 um).
SCENE_UNIT = 100e-6

#: Defaults of the scene, in one place.
DEFAULTS = read_only(dict(
    stations=60,            # sections along the lever (plus the planform's corners)
    twist=0.5,              # rad: the drawn twist at the slider's largest force, at most
    tip_radius=0.35,        # the tip's base radius as a fraction of its height
    color=0x8fa7c4,         # the lever (silicon, a grey blue)
    tip_color=0x606060,
    chip=(1.6, 2.0, 0.3),   # the chip behind the clamp (scene units: x, y, z)
    camera=(0.75, -0.7, 0.3),  # camera position over the length: from the free end's side
))


def lever_mesh(lever: Lever, twist: float = 0.0, *, stations: int = DEFAULTS["stations"]):
    """Vertices and triangles of ``lever``'s plan view as a slab, twisted (SI units, m).

    Each half (y >= 0 and y <= 0) is a strip of sections between its inner and outer edge
    (:func:`~afmsmiler.probe.half_widths`) at ``stations`` points along x and the planform's
    corners, the thickness t about the mid-plane z = 0: top, bottom, outer and inner walls and
    the end faces. A section at x is turned about the x axis by ``twist`` min(x / x_tip, 1).

    Parameters
    ----------
    lever : Lever
        The lever.
    twist : float
        The drawn twist of the tip's section in rad, in [-pi/2, pi/2].
    stations : int
        Sections along the lever, 2 to 1000.

    Returns
    -------
    vertices : ndarray, shape (n, 3)
    faces : ndarray of int, shape (m, 3)
    """
    lever = check_instance("lever", lever, Lever)
    twist = check_range("twist", twist, -math.pi / 2, math.pi / 2, "rad")
    stations = int(check_range("stations", stations, 2, 1000))
    L, t = lever.length, lever.thickness
    marks = [lever.tip_position]
    if lever.planform == "pointed":
        marks.append(L - lever.point_length)
    elif lever.planform == "v_shaped":
        marks.append(lever.solid_from)
    x = np.unique(np.concatenate([np.linspace(0.0, L, stations), marks]))
    inner, outer = half_widths(lever, x)
    n = x.size
    angle = twist * np.clip(x / lever.tip_position, 0.0, 1.0)
    verts, faces = [], []
    for side in (1.0, -1.0):
        # per station: inner-top, outer-top, outer-bottom, inner-bottom (a ring of 4)
        y = np.stack([inner, outer, outer, inner], axis=1) * side
        z = np.tile([t / 2, t / 2, -t / 2, -t / 2], (n, 1))
        c, s = np.cos(angle)[:, None], np.sin(angle)[:, None]
        ring = np.stack([np.repeat(x[:, None], 4, axis=1), y * c - z * s, y * s + z * c],
                        axis=2).reshape(-1, 3)
        base = sum(len(v) for v in verts)
        verts.append(ring)
        k = np.arange(n - 1)[:, None]
        for a in range(4):  # the four walls between station k and k + 1
            b = (a + 1) % 4
            p, q = base + 4 * k + a, base + 4 * k + b
            faces.append(np.hstack([p, q, q + 4]))
            faces.append(np.hstack([p, q + 4, p + 4]))
        for end in (0, n - 1):  # the clamp's and the free end's faces
            r = base + 4 * end
            faces.append(np.array([[r, r + 1, r + 2], [r, r + 2, r + 3]]))
    faces = np.vstack(faces)
    if np.any(faces < 0):  # pragma: no cover - built above
        raise AssertionError(faces)
    return np.vstack(verts), faces


class ProbeScene(SceneDisplay):
    """A vendor's lever (or a custom one) in meshcat: its plan view twisted by a friction force.

    Parameters
    ----------
    lever : Lever
        The lever to draw first.
    twist : float
        The model's twist of the tip's section in rad (from
        :meth:`~afmsmiler.modes.LateralLever.twist`).
    vis : meshcat.Visualizer, optional
        The root visualizer; by default a new 3D view's (:class:`~afmsmiler.scenes.SceneView`).
    path : str
        Path of this scene in the viewer.

    Attributes
    ----------
    factor : float
        The magnification of the drawn twist (a round factor, one per lever).
    """

    def __init__(self, lever: Lever, twist: float, *, vis: meshcat.Visualizer | None = None,
                 path: str = "afmsmiler/probe"):
        check_instance("path", path, str)
        self.root = scene_root(vis)
        self.vis = self.root[path]
        self._material = g.MeshLambertMaterial(color=DEFAULTS["color"])
        self.lever = None
        self.factor = 1.0
        self.twist = 0.0
        self.update(lever, twist)

    @staticmethod
    def factor_for(lever: Lever) -> float:
        """The round magnification that draws the twist at the slider's largest force at about
        ``DEFAULTS["twist"]`` rad."""
        largest = abs(LateralLever(lever).twist(LATERAL_FORCE.slider_high))
        return round_factor(DEFAULTS["twist"] / largest) if largest > 0 else 1.0

    @staticmethod
    def camera_for(lever: Lever) -> list:
        """The camera's position (scene units) for ``lever``: from the free end's side, at a
        distance that grows with its length."""
        d = max(lever.length / SCENE_UNIT, 1.0)
        return [v * d for v in DEFAULTS["camera"]]

    @property
    def caption(self) -> str:
        """What the view shows and how much it magnifies."""
        return (f"twist {factor_text(self.factor)} (tip's section {math.degrees(self.twist):.3g}"
                f" deg, drawn {math.degrees(self.factor * self.twist):.3g} deg); "
                "1 unit = 100 um")

    def update(self, lever: Lever, twist: float) -> None:
        """Draw ``lever`` twisted by ``twist`` (rad, the model's), magnified by :attr:`factor`.

        Parameters
        ----------
        lever : Lever
            The lever.
        twist : float
            The tip section's twist in rad.
        """
        lever = check_instance("lever", lever, Lever)
        twist = check_range("twist", twist, -math.pi / 2, math.pi / 2, "rad")
        if lever == self.lever and twist == self.twist:
            return  # nothing to draw again (a move of the spot or the fluid)
        if lever != self.lever:
            self.factor = self.factor_for(lever)
        drawn = float(np.clip(self.factor * twist, -math.pi / 2, math.pi / 2))
        verts, faces = lever_mesh(lever, drawn)
        shift = np.array([lever.length / 2, 0.0, 0.0])
        self.vis["lever"].set_object(
            g.TriangularMeshGeometry((verts - shift) / SCENE_UNIT, faces), self._material)
        h = lever.tip_height / SCENE_UNIT
        if lever != self.lever:
            cone(self.vis["tip"], h, DEFAULTS["tip_radius"] * h, color=DEFAULTS["tip_color"])
            cx, cy, cz = DEFAULTS["chip"]
            self.vis["chip"].set_object(g.Box([cx, cy, cz]),
                                        g.MeshLambertMaterial(color=0x505a66))
            self.vis["chip"].set_transform(translation(
                [-lever.length / SCENE_UNIT / 2 - cx / 2, 0.0,
                 lever.thickness / SCENE_UNIT / 2 - cz / 2]))
            self.camera_position = self.camera_for(lever)
            set_camera(self.root, self.camera_position)
            show_helpers(self.root, grid=False, axes=False)  # the grid would cut the lever
        # the tip hangs under the tip's section and turns with it (apex h_tip + t/2 below the
        # mid-plane, the lever arm of the twist)
        c, s = math.cos(drawn), math.sin(drawn)
        rot = np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1]], dtype=float)
        at = translation([(lever.tip_position - lever.length / 2) / SCENE_UNIT, 0.0, 0.0])
        down = translation([0.0, 0.0, -(lever.thickness / 2 + lever.tip_height) / SCENE_UNIT])
        self.vis["tip"].set_transform(at @ rot @ down)
        self.lever, self.twist = lever, float(twist)

    def apex(self) -> np.ndarray:
        """Where the drawn tip's apex is (scene units), for tests."""
        drawn = self.factor * self.twist
        arm = (self.lever.thickness / 2 + self.lever.tip_height) / SCENE_UNIT
        return np.array([(self.lever.tip_position - self.lever.length / 2) / SCENE_UNIT,
                         arm * math.sin(drawn), -arm * math.cos(drawn)])
