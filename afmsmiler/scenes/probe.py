"""The 3D view of module (a)'s "your probe": the lever's plan view, twisted by a friction force.

Scale: **1 scene unit = 100 um** (:data:`SCENE_UNIT`, as module (a)'s other view). The lever lies
along +x from its clamp (shifted by -L/2 so that the camera, which looks at the origin, sees it
centred), z up, its tip under it at the tip position. The lever is drawn from its plan view
(:func:`afmsmiler.probe.half_widths`: a rectangle, a pointed end or a V's two arms), true to
scale, and twisted about its long axis: the model gives the twist of the tip's section,
phi = F_L (h_tip + t/2) / k_phi (:meth:`afmsmiler.modes.LateralLever.twist`); the drawing
magnifies it by :attr:`ProbeScene.factor`, one round factor of at least 1 per lever (the twist
at the slider's largest force drawn at 0.5 rad, 29 deg, at most), so that the drawn twist follows
the force; a drawn twist is never more than a quarter turn (the caption says when it is held
there). Along the lever
the drawn twist grows linearly from the clamp to the tip's section, as it does in a uniform bar
under an end torque (Saint-Venant torsion), and stays the tip's beyond it; for a pointed or
V-shaped lever this shape is a drawing, the tip's twist is the model's. The chip the lever
comes out of is drawn above it (the side away from the tip), smaller than a real chip's
1.6 x 3.4 x 0.3 mm so that the lever fills the view.

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
from ..validation import check_finite, check_instance, check_integer, check_range
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


def _oriented(quads: np.ndarray, outward) -> np.ndarray:
    """``quads`` (m, 4, 3) turned so that each faces ``outward`` (counter-clockwise seen from
    there), those of no area left out."""
    normal = np.cross(quads[:, 2] - quads[:, 0], quads[:, 3] - quads[:, 1])
    keep = np.linalg.norm(normal, axis=1) > 0
    quads, normal = quads[keep], normal[keep]
    flip = normal @ np.asarray(outward, float) < 0
    quads[flip] = quads[flip][:, ::-1]
    return quads


def lever_mesh(lever: Lever, twist: float = 0.0, *, stations: int = DEFAULTS["stations"]):
    """Vertices and triangles of ``lever``'s plan view as a slab, twisted (SI units, m).

    Each half (y >= 0 and y <= 0) is a strip of sections between its inner and outer edge
    (:func:`~afmsmiler.probe.half_widths`) at ``stations`` points along x and the planform's
    corners, the thickness t about the mid-plane z = 0: top, bottom and outer walls, the inner
    walls where the arms of a V are apart, the clamp's face and the free end's where it has a
    width. Every face is wound counter-clockwise seen from outside and has its own vertices (flat
    shading). A section at x is turned about the x axis by ``twist`` min(x / x_tip, 1).

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
    stations = check_integer("stations", stations, 2, 1000)
    L, t = lever.length, lever.thickness
    marks = [lever.tip_position]
    if lever.planform == "pointed":
        marks.append(L - lever.point_length)
    elif lever.planform == "v_shaped":
        marks.append(lever.solid_from)
    x = np.unique(np.concatenate([np.linspace(0.0, L, stations), marks]))
    inner, outer = half_widths(lever, x)
    quads = []
    for side in (1.0, -1.0):
        def edge(y, z):
            return np.stack([x, side * y, np.full_like(x, z)], axis=1)
        top_in, top_out = edge(inner, t / 2), edge(outer, t / 2)
        bot_in, bot_out = edge(inner, -t / 2), edge(outer, -t / 2)

        def strip(p, q, outward):
            quads.append(_oriented(np.stack([p[:-1], p[1:], q[1:], q[:-1]], axis=1), outward))

        strip(top_in, top_out, (0, 0, 1))
        strip(bot_in, bot_out, (0, 0, -1))
        strip(top_out, bot_out, (0, side, 0))
        apart = (inner[:-1] > 0) | (inner[1:] > 0)  # the inner edge of a V's arm
        wall = np.stack([top_in[:-1], top_in[1:], bot_in[1:], bot_in[:-1]], axis=1)[apart]
        quads.append(_oriented(wall, (0, -side, 0)))
        for k, outward in ((0, (-1, 0, 0)), (-1, (1, 0, 0))):  # the clamp's and the free end's
            quads.append(_oriented(np.stack([top_in[k], top_out[k], bot_out[k], bot_in[k]])[None],
                                   outward))
    q = np.concatenate(quads)
    angle = twist * np.clip(q[..., 0] / lever.tip_position, 0.0, 1.0)
    c, s = np.cos(angle), np.sin(angle)
    q = np.stack([q[..., 0], q[..., 1] * c - q[..., 2] * s, q[..., 1] * s + q[..., 2] * c],
                 axis=-1)
    i = 4 * np.arange(len(q))[:, None]
    faces = np.vstack([i + [0, 1, 2], i + [0, 2, 3]])
    return q.reshape(-1, 3), faces


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
        return max(1.0, round_factor(DEFAULTS["twist"] / largest)) if largest > 0 else 1.0

    @staticmethod
    def camera_for(lever: Lever) -> list:
        """The camera's position (scene units) for ``lever``: from the free end's side, at a
        distance that grows with its length."""
        d = max(lever.length / SCENE_UNIT, 1.0)
        return [v * d for v in DEFAULTS["camera"]]

    @property
    def caption(self) -> str:
        """What the view shows and how much it magnifies."""
        drawn = self._drawn(self.twist)
        held = ", held at a quarter turn" if abs(drawn) < abs(self.factor * self.twist) else ""
        return (f"twist {factor_text(self.factor)} (tip's section {math.degrees(self.twist):.3g}"
                f" deg, drawn {math.degrees(drawn):.3g} deg{held}); the apex moves along F_L; "
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
        twist = check_finite("twist", twist, "rad")
        if lever == self.lever and twist == self.twist:
            return  # nothing to draw again (a move of the spot or the fluid)
        if lever != self.lever:
            self.factor = self.factor_for(lever)
        drawn = self._drawn(twist)
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
            self.vis["chip"].set_transform(translation(  # its underside the lever's
                [-lever.length / SCENE_UNIT / 2 - cx / 2, 0.0,
                 -lever.thickness / SCENE_UNIT / 2 + cz / 2]))
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

    def _drawn(self, twist: float) -> float:
        """The drawn twist in rad: ``twist`` magnified, held within a quarter turn."""
        return float(np.clip(self.factor * twist, -math.pi / 2, math.pi / 2))

    def apex(self) -> np.ndarray:
        """Where the drawn tip's apex is (scene units), for tests."""
        drawn = self._drawn(self.twist)
        arm = (self.lever.thickness / 2 + self.lever.tip_height) / SCENE_UNIT
        return np.array([(self.lever.tip_position - self.lever.length / 2) / SCENE_UNIT,
                         arm * math.sin(drawn), -arm * math.cos(drawn)])
