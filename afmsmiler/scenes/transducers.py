"""The 3D scale models of module (b): the lever with each transducer's laser path or embedded part.

Scale: the lever (length, width, thickness) is drawn to scale at **1 scene unit = 100 um**
(:data:`SCENE_UNIT`), clamped at x = 0 to a grey chip and bent along +x; its deflection is
exaggerated so that the full input range of the principle bends the tip by
``DEFAULTS["max_tip"]`` x L, and the beam is colored by the (relative) bending strain,
tension red, compression blue. Laser paths, detectors, magnets, electrodes and cavities are
schematic (an optical path of 30 mm would be 300 units), placed around the lever so that each
principle is recognisable:

==========================  ===================================================================
optical beam deflection     laser, incident and reflected beam, four-quadrant photodiode, spot
astigmatic detection        pickup head above the tip, beam, quadrant detector, elliptical spot
interferometry              fibre above the tip, the beam in the gap
piezo-acoustic              orange piezo shaker under the chip, moving with the base amplitude
photothermal                blue heating laser on the tip
electromagnetic             current loop along the lever's edges, magnet, force arrow
electrostatic               counter-electrode under the tip end, force arrow
optomechanical              microdisk cavity and its waveguide beside the tip
piezoresistive              U-shaped resistor at the clamp (red: R up, blue: R down)
electrothermal              heater meander along the lever
piezoelectric               the film and its electrode on the lever
==========================  ===================================================================

Every principle also has a signal meter beside the chip: a green bar whose height is the output
as a fraction of its largest value over the input range (full scale: the translucent frame).
:class:`TransducerScene` draws into its own 3D view
(:class:`~afmsmiler.scenes.SceneView`) and updates in place: a new input moves the parts with
``set_transform`` and re-sends only the bent geometry; a new principle replaces the
principle's group of objects under its own path. It draws a model run
(:meth:`~afmsmiler.transducers.base.Transducer.operate`, an
:class:`~afmsmiler.transducers.base.Operation`) and evaluates no physics itself: the lever's
shape comes from the model's ``deflection_shape``, every fraction and ratio from the run's stages.

The optical lever's parts (laser, beams, four-quadrant photodiode, spot and the law of
reflection on the drawn lever) are a reusable piece, :class:`OpticalLever`, drawn under any
``vis`` node, with :func:`quadrant_photodiode`: module (e)'s laser alignment uses them too.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import meshcat
import meshcat.geometry as g
import numpy as np

from ..parameters import read_only
from ..transducers.base import Operation
from ..validation import (check_array, check_flag, check_instance, check_integer,
                          check_positive, check_range)
from .camera import readable_width, set_camera, show_helpers
from .colors import ColorScale
from .legends import TextPlate
from .meshes import beam_mesh
from .shapes import Arrow, cone, Segment, sphere, Tube
from .transforms import check_visualizer, reflect, rotation_between, translation
from .viewer import SceneDisplay, scene_root

__all__ = ["SCENE_UNIT", "DEFAULTS", "TransducerScene", "LeverPose", "lever_pose", "OpticalLever",
           "quadrant_photodiode"]

#: Metres per scene unit (1 scene unit = 100 um), for the lever.
SCENE_UNIT = 100e-6

#: Defaults of the scene, in one place.
DEFAULTS = read_only(dict(
    max_tip=0.12,         # drawn tip deflection at the largest input, as a fraction of L
    n_length=41,          # stations along the drawn lever
    meter_x=-1.4,         # position of the signal meter (scene units)
    beam_radius=0.012,    # laser beams
    detector_distance=1.5,  # optical beam deflection: tip to photodiode, scene units
    camera=(0.8, -3.6, 2.8),  # a little from above: the photodiode's face is not edge-on
))

_WHITE, _GREY, _RED, _BLUE, _GREEN = 0xffffff, 0x9a9a9a, 0xe03030, 0x3060e0, 0x20a040
_COPPER, _ORANGE, _GOLD = 0xb87333, 0xf08020, 0xd4af37
_STRAIN = ColorScale.symmetric(1.0, "RdBu_r", "bending strain (relative)", "")


def _mat(color, opacity=1.0):
    return g.MeshLambertMaterial(color=color, opacity=opacity, transparent=opacity < 1)


@dataclass(frozen=True)
class LeverPose:
    """The lever as drawn (scene units), from a transducer's run at one input.

    Attributes
    ----------
    x : ndarray
        Stations along the lever.
    z : ndarray
        Drawn (exaggerated) centre-line height at each station.
    slope : ndarray
        dz/dx of the drawn centre line.
    strain : ndarray
        Relative bending strain of the top surface at each station, in [-1, 1].
    fraction : float
        Tip deflection as a signed fraction of the largest over the input range.
    output_fraction : float
        Output as a signed fraction of the largest |output| over the input range.
    """

    x: np.ndarray
    z: np.ndarray
    slope: np.ndarray
    strain: np.ndarray
    fraction: float
    output_fraction: float


def lever_pose(operation: Operation, n_length: int = DEFAULTS["n_length"], *,
               fraction: float | None = None) -> LeverPose:
    """The drawn lever for a model run (:meth:`~afmsmiler.transducers.base.Transducer.operate`).

    No model is evaluated: the deflection and output fractions come from the run's sweep, the
    shape from the model's :meth:`~afmsmiler.transducers.base.Transducer.deflection_shape`.

    Parameters
    ----------
    operation : Operation
        The model run.
    n_length : int
        Stations along the lever, 2 to 10000.
    fraction : float, optional
        Draw the lever at this signed fraction of the largest deflection instead of the run's
        (the ends of the range are -1 and 1 for a symmetric one), in [-1, 1].

    Returns
    -------
    LeverPose
        The model's shape (end load, or mode 1 for base excitation) scaled so that the largest
        deflection over the input range is ``DEFAULTS["max_tip"]`` L.
    """
    op = check_instance("operation", operation, Operation)
    n_length = check_integer("n_length", n_length, 2, 10_000)
    model = op.model
    if fraction is None:
        fraction = op.deflection_fraction
    fraction = check_range("fraction", fraction, -1.0, 1.0)
    length = model.length / SCENE_UNIT
    u = np.linspace(0.0, 1.0, n_length)
    shape, dshape, curv = model.deflection_shape(u)
    amplitude = DEFAULTS["max_tip"] * length * fraction
    strain = -np.sign(fraction) * np.abs(fraction) * curv / max(np.abs(curv).max(), 1e-12)
    return LeverPose(u * length, amplitude * shape, amplitude * dshape / length, strain,
                     fraction, op.output_fraction)


def quadrant_photodiode(vis: meshcat.Visualizer, centre, normal, size: float = 0.5) -> np.ndarray:
    """A four-quadrant photodiode: four thin plates in the plane through ``centre``.

    Parameters
    ----------
    vis : meshcat.Visualizer
        The node to draw under (its children ``q0`` to ``q3``).
    centre : array_like
        Centre of the detector, scene units (3 values).
    normal : array_like
        Normal of its face (3 values, not zero).
    size : float
        Side of the square detector, scene units, > 0.

    Returns
    -------
    ndarray
        The 4 x 4 rotation taking +z to ``normal``.
    """
    check_visualizer("vis", vis)
    centre = check_array("centre", centre, size=3)
    n = check_array("normal", normal, size=3)
    if not np.linalg.norm(n) > 0:
        raise ValueError(f"normal must not be zero, got {normal!r}")
    size = check_positive("size", size)
    n = n / np.linalg.norm(n)
    rot = np.eye(4)
    rot[:3, :3] = rotation_between([0.0, 0.0, 1.0], n)
    colors = (0x4060a0, 0x5070b0, 0x5070b0, 0x4060a0)
    half = size / 2
    for i, (a, b) in enumerate(((1, 1), (-1, 1), (-1, -1), (1, -1))):
        node = vis[f"q{i}"]
        node.set_object(g.Box([half * 0.96, half * 0.96, 0.01]), _mat(colors[i]))
        node.set_transform(translation(centre) @ rot
                           @ translation([a * half / 2, b * half / 2, 0.0]))
    return rot


class OpticalLever:
    """The optical lever's parts, reusable by any scene: laser, beams, four-quadrant photodiode
    and spot, with the reflection computed on the drawn lever (law of reflection).

    The detector faces the beam that the undeflected lever reflects, ``detector_distance`` from
    the reflection point ``target``. Module (b)'s transducer scene draws the optical beam
    deflection with it; a laser-alignment scene can move ``source`` and redraw.

    Parameters
    ----------
    vis : meshcat.Visualizer
        The node to draw under (children ``laser``, ``detector``, ``incident``, ``reflected``,
        ``spot``).
    source : array_like
        The laser's position, scene units (3 values).
    target : array_like
        Where the beam meets the undeflected lever's top face, scene units (3 values).
    detector_distance : float
        From ``target`` to the detector's centre along the nominal reflected beam, > 0.
    beam_radius : float
        Radius of the drawn beams, > 0.

    Attributes
    ----------
    detector : ndarray
        The detector's centre.
    normal : ndarray
        Its face's normal (towards the lever).
    rotation : ndarray or None
        The detector's 4 x 4 rotation once drawn (:meth:`draw_detector`).
    """

    def __init__(self, vis: meshcat.Visualizer, *, source, target,
                 detector_distance: float = DEFAULTS["detector_distance"],
                 beam_radius: float = DEFAULTS["beam_radius"]):
        check_visualizer("vis", vis)
        self.vis = vis
        self.source = check_array("source", source, size=3)
        target = check_array("target", target, size=3)
        detector_distance = check_positive("detector_distance", detector_distance)
        beam_radius = check_positive("beam_radius", beam_radius)
        d = target - self.source
        if not np.linalg.norm(d) > 0:
            raise ValueError("target must differ from source")
        d = d / np.linalg.norm(d)
        nominal = d - 2 * d[2] * np.array([0.0, 0.0, 1.0])
        self.detector = target + detector_distance * nominal
        self.normal = -nominal
        self.rotation = None
        vis["laser"].set_object(g.Box([0.5, 0.25, 0.25]), _mat(0x333333))
        vis["laser"].set_transform(translation(self.source))
        self._incident = Segment(vis["incident"], color=_RED, radius=beam_radius)
        self._reflected = Segment(vis["reflected"], color=_RED, radius=beam_radius,
                                    opacity=0.8)
        sphere(vis["spot"], 1.0, color=0xff0000, opacity=0.85)

    def hit(self, top, slope: float) -> np.ndarray:
        """Where the beam reflected at ``top`` of a surface of slope dz/dx ``slope`` meets the
        detector's plane.

        Parameters
        ----------
        top : array_like
            The reflection point, scene units (3 values).
        slope : float
            dz/dx of the reflecting surface there (drawn).

        Returns
        -------
        ndarray
            The point on the detector's plane, scene units.
        """
        top = check_array("top", top, size=3)
        slope = check_range("slope", slope, -math.inf, math.inf)
        d = top - self.source
        d /= np.linalg.norm(d)
        n = np.array([-slope, 0.0, 1.0])
        n /= np.linalg.norm(n)
        r = reflect(d, n)
        facing = np.dot(r, self.normal)
        if not facing < -1e-9:   # the detector faces the nominal beam: -normal
            raise ValueError(f"slope {slope:g} sends the reflected beam away from the detector")
        return top + np.dot(self.detector - top, self.normal) / facing * r

    def draw_detector(self, size: float) -> None:
        """Draw the four-quadrant photodiode, a square of side ``size`` (scene units, > 0)."""
        self.rotation = quadrant_photodiode(self.vis["detector"], self.detector, self.normal,
                                            size)

    def move(self, top, slope: float, spot_radius: float) -> np.ndarray:
        """Draw the beams to and from ``top`` and the spot (radius ``spot_radius``) on the detector.

        Parameters
        ----------
        top : array_like
            The reflection point, scene units (3 values).
        slope : float
            dz/dx of the reflecting surface there.
        spot_radius : float
            Drawn spot radius, scene units, > 0.

        Returns
        -------
        ndarray
            The spot's centre.
        """
        spot_radius = check_positive("spot_radius", spot_radius)
        hit = self.hit(top, slope)
        self._incident.set(self.source, np.asarray(top, float))
        self._reflected.set(np.asarray(top, float), hit)
        rot = self.rotation if self.rotation is not None else np.eye(4)
        flat = np.eye(4)
        flat[:3, :3] = rot[:3, :3] @ np.diag([spot_radius, spot_radius, 0.02])  # a disc
        self.vis["spot"].set_transform(translation(hit - 0.02 * self.normal) @ flat)
        return hit


class TransducerScene(SceneDisplay):
    """A transducer's scale model in meshcat, updated in place (see the module docstring).

    Parameters
    ----------
    operation : Operation
        The first model run to draw (:meth:`~afmsmiler.transducers.base.Transducer.operate`).
    vis : meshcat.Visualizer, optional
        The root visualizer; by default a new 3D view's (:class:`~afmsmiler.scenes.SceneView`).
    path : str
        Path of this scene in the viewer.
    camera : bool
        Place the camera to look at the lever from the front.

    Attributes
    ----------
    key : str
        The principle drawn.
    pose : LeverPose
        The lever as last drawn.
    parts : dict
        Name -> latest placement of each principle-specific moving part (scene units), for tests.
    """

    def __init__(self, operation: Operation, *, vis: meshcat.Visualizer | None = None,
                 path: str = "afmsmiler/transducers", camera: bool = True):
        check_instance("operation", operation, Operation)
        check_instance("path", path, str)
        camera = check_flag("camera", camera)
        self.root = scene_root(vis)
        self.path = path
        self.vis = self.root[path]
        self.vis.delete()
        self.key = None
        self.pose = None
        self.parts = {}
        self._beam_material = g.MeshLambertMaterial(vertexColors=True)
        self._segments = {}
        self._lines = {}
        self._arrows = {}
        self._draw_common()
        self.update(operation)
        if camera:
            set_camera(self.root, list(DEFAULTS["camera"]))
            show_helpers(self.root, grid=True, axes=False)  # the axes would pierce the lever

    # -- drawn once -----------------------------------------------------------------------------
    def _draw_common(self):
        v = self.vis
        v["chip"].set_object(g.Box([1.0, 1.2, 0.3]), _mat(_GREY))
        cone(v["tip"], 0.15, 0.05, color=0x707070)
        mx = DEFAULTS["meter_x"]
        v["meter"]["frame"].set_object(g.Box([0.16, 0.16, 2.0]), _mat(0xcccccc, 0.25))
        v["meter"]["frame"].set_transform(translation([mx, 0.0, 0.0]))
        v["meter"]["bar"].set_object(g.Box([0.12, 0.12, 1.0]), _mat(_GREEN))
        # what the bar is: the output as a fraction of its largest value over the input range
        width = readable_width(TextPlate.TEXT_FRACTION, [mx, 0.0, 1.1], DEFAULTS["camera"])
        label = TextPlate(v["meter"]["label"], "output / max", width=width)
        v["meter"]["label"].set_transform(translation([mx - label.width / 2, 0.0, 1.05]))

    # -- the update -------------------------------------------------------------------------------
    def update(self, operation: Operation) -> None:
        """Redraw for a model run, in place (no model is evaluated here).

        Parameters
        ----------
        operation : Operation
            The run (a new principle replaces the principle's objects).
        """
        op = check_instance("operation", operation, Operation)
        model = op.model
        pose = lever_pose(op)
        self.pose = pose
        u = SCENE_UNIT
        h, w = model.thickness / u, model.width / u
        nt = 3
        values = np.outer(pose.strain, np.linspace(-1.0, 1.0, nt))
        mesh = beam_mesh(pose.x, pose.z, w, h, values, slope=pose.slope)
        self.vis["beam"].set_object(mesh.geometry(_STRAIN), self._beam_material)
        self.vis["chip"].set_transform(translation([-0.5, 0.0, h / 2 - 0.15]))
        self.vis["tip"].set_transform(translation([pose.x[-1], 0.0, pose.z[-1] - h / 2]))
        s = pose.output_fraction
        bar = max(abs(s), 1e-3)
        self.vis["meter"]["bar"].set_transform(
            translation([DEFAULTS["meter_x"], 0.0, np.sign(s) * bar / 2])
            @ np.diag([1.0, 1.0, bar, 1.0]))
        if model.key != self.key:
            self.vis["element"].delete()
            self._segments, self._arrows, self.parts, self._lines = {}, {}, {}, {}
            self.key = model.key
            getattr(self, f"_draw_{model.key}")(op)
        getattr(self, f"_move_{model.key}")(op, pose)
        self.vis.set_transform(translation([-pose.x[-1] / 2, 0.0, 0.0]))

    # -- helpers ----------------------------------------------------------------------------------
    def _segment(self, name, color, radius=None, opacity=1.0):
        seg = Segment(self.vis["element"][name], color=color,
                      radius=radius or DEFAULTS["beam_radius"], opacity=opacity)
        self._segments[name] = seg
        return seg

    def _arrow(self, name, color=0x202020):
        arrow = Arrow(self.vis["element"][name], color=color, radius=0.02, head_length=0.1)
        self._arrows[name] = arrow
        return arrow

    def _box(self, name, size, centre, color, opacity=1.0):
        node = self.vis["element"][name]
        node.set_object(g.Box(list(size)), _mat(color, opacity))
        node.set_transform(translation(centre))
        return node

    @staticmethod
    def _tip_top(model, pose):
        h = model.thickness / SCENE_UNIT
        return np.array([pose.x[-1], 0.0, pose.z[-1] + h / 2])

    def _surface_line(self, name, model, pose, ys, x_range=(0.0, 1.0), color=_COPPER,
                      radius=0.012):
        """A wire on the lever's top surface along a path of (u, y): u the fraction of
        ``x_range`` (itself a fraction of L), y the lateral offset in scene units.

        Drawn as a thin tube (WebGL lines are one pixel wide, too thin to see) lying on the
        bent surface: legs along the lever are cut into pieces of at most L / 12 that follow it.
        The tube is one mesh, sent in one message per update.
        """
        h = model.thickness / SCENE_UNIT
        L = pose.x[-1]
        path = []
        for (u0, y0), (u1, y1) in zip(ys[:-1], ys[1:]):
            n = max(1, int(np.ceil(abs(u1 - u0) * (x_range[1] - x_range[0]) * 12)))
            for t in np.linspace(0.0, 1.0, n + 1)[(1 if path else 0):]:
                path.append((u0 + t * (u1 - u0), y0 + t * (y1 - y0)))
        pts = []
        for u, y in path:
            xs = (x_range[0] + u * (x_range[1] - x_range[0])) * L
            pts.append([xs, y, np.interp(xs, pose.x, pose.z) + h / 2 + radius])
        pts = np.array(pts)
        if self._lines.get(name, (None,))[0] != (color, radius):
            self._lines[name] = ((color, radius), Tube(self.vis["element"][name], color=color,
                                                       radius=radius))
        self._lines[name][1].set(pts)
        self.parts[name] = pts

    def _quadrants(self, name, centre, normal, size=0.5):
        """A four-quadrant photodiode under ``element/name`` (see :func:`quadrant_photodiode`)."""
        rot = quadrant_photodiode(self.vis["element"][name], centre, normal, size)
        n = np.asarray(normal, float) / np.linalg.norm(normal)
        self.parts[name] = (np.asarray(centre, float), n, rot)

    # -- optical beam deflection ------------------------------------------------------------------
    def _draw_optical_beam_deflection(self, op):
        model = op.model
        L = model.length / SCENE_UNIT
        source = np.array([L - 1.6, 0.0, 2.2])
        tip = np.array([L, 0.0, model.thickness / SCENE_UNIT / 2])  # the undeflected top face
        self._optical_lever = lever = OpticalLever(self.vis["element"], source=source, target=tip)
        # The drawn lever tilts ~13x more than the real one and the detector is ~20x nearer than
        # the real optical path D, so the drawn spot is scaled like its travel: at the ends of
        # the input range, travel / radius on the drawing = s / w of the model on average (the
        # drawn tip's own up-down motion, negligible in a real AFM, adds +-12 %), and the spot
        # crosses the split line as far (in spot radii) as the model's signal says.
        z = op.sweep.stage("deflection").values
        spot = op.sweep.stage("spot_displacement").values
        z_max = float(np.abs(z).max()) or 1.0
        travel, ratio = [], []
        for i in (0, -1):
            pose = lever_pose(op, fraction=float(z[i]) / z_max)
            hit = lever.hit(self._tip_top(model, pose), float(pose.slope[-1]))
            travel.append(float(np.linalg.norm(hit - lever.detector)))
            ratio.append(travel[-1] * model.spot_radius / abs(float(spot[i])))
        self._spot_radius = float(np.mean(ratio))
        lever.draw_detector(2.1 * (max(travel) + self._spot_radius))
        self.parts["detector"] = (lever.detector, lever.normal, lever.rotation)

    def _move_optical_beam_deflection(self, op, pose):
        top = self._tip_top(op.model, pose)
        hit = self._optical_lever.move(top, float(pose.slope[-1]), self._spot_radius)
        self.parts["spot"] = hit
        self.parts["spot_radius"] = self._spot_radius

    # -- astigmatic detection ---------------------------------------------------------------------
    def _draw_astigmatic(self, op):
        model = op.model
        L = model.length / SCENE_UNIT
        self._head = np.array([L, 0.0, 1.8])
        self._box("pickup_head", (0.9, 0.7, 0.35), self._head, 0x303030)
        self._box("objective", (0.3, 0.3, 0.05), self._head - [0, 0, 0.2], 0x8080ff, 0.6)
        # the quadrant detector, drawn as a window on the head's top face (it sits inside)
        self._quadrants("detector", self._head + [0.0, 0.0, 0.185], [0.0, 0.0, 1.0], size=0.4)
        self._segment("beam", _RED, opacity=0.8)
        sphere(self.vis["element"]["spot"], 1.0, color=0xff2020)

    def _move_astigmatic(self, op, pose):
        top = self._tip_top(op.model, pose)
        self._segments["beam"].set(top, self._head - [0, 0, 0.22])
        ratio = float(op.point.stage("axis_ratio").values[0])   # w_y / w_x, from the model
        sx, sy = 0.1 / math.sqrt(ratio), 0.1 * math.sqrt(ratio)  # area as at focus
        centre = self._head + [0.0, 0.0, 0.2]
        self.vis["element"]["spot"].set_transform(
            translation(centre) @ np.diag([sx, sy, 0.02, 1.0]))
        self.parts["spot"] = (sx, sy)

    # -- interferometry ---------------------------------------------------------------------------
    def _draw_interferometry(self, op):
        model = op.model
        L = model.length / SCENE_UNIT
        node = self.vis["element"]["fibre"]
        node.set_object(g.Cylinder(1.6, radius=0.12), _mat(0xe0e0c0, 0.9))
        rot = np.array([[1, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 0], [0, 0, 0, 1]], dtype=float)
        node.set_transform(translation([L, 0.0, 1.3]) @ rot)
        self._fibre_end = np.array([L, 0.0, 0.5])
        self._segment("beam", _RED, opacity=0.7)

    def _move_interferometry(self, op, pose):
        model = op.model
        top = self._tip_top(model, pose)
        self._segments["beam"].set(self._fibre_end, top)
        self.parts["gap"] = float(self._fibre_end[2] - top[2])

    # -- piezo-acoustic ---------------------------------------------------------------------------
    def _draw_piezo_acoustic(self, op):
        self._box("shaker", (1.0, 1.2, 0.3), [-0.5, 0.0, -0.45], _ORANGE)

    def _move_piezo_acoustic(self, op, pose):
        # the base moves by the tip amplitude / (gamma |H|): barely at resonance; the ratio of
        # the two amplitudes is the model's (its chain's base and tip stages)
        base = np.abs(op.sweep.stage("base_amplitude").values).max()
        tip = np.abs(op.sweep.stage("deflection").values).max()
        offset = pose.z[-1] * (base / tip if tip > 0 else 0.0)
        offset = float(np.clip(offset, -0.3, 0.3))
        self.vis["element"]["shaker"].set_transform(translation([-0.5, 0.0, -0.45 + offset]))
        self.parts["base_offset"] = offset

    # -- photothermal -----------------------------------------------------------------------------
    def _draw_photothermal(self, op):
        model = op.model
        L = model.length / SCENE_UNIT
        self._source = np.array([L + 1.2, 0.0, 2.0])
        self._box("laser", (0.4, 0.22, 0.22), self._source, 0x222266)
        self._segment("heating_beam", _BLUE, radius=0.02, opacity=0.8)

    def _move_photothermal(self, op, pose):
        model, value = op.model, op.value
        top = self._tip_top(model, pose)
        self._segments["heating_beam"].set(self._source, top)
        self.vis["element"]["heating_beam"].set_property("visible", bool(value > 0))
        self.parts["beam_on"] = bool(value > 0)

    # -- electromagnetic --------------------------------------------------------------------------
    def _draw_electromagnetic(self, op):
        model = op.model
        L = model.length / SCENE_UNIT
        self._box("magnet_n", (0.4, 1.0, 0.6), [L + 0.6, 0.0, 0.0], _RED)
        self._box("magnet_s", (0.4, 1.0, 0.6), [L + 1.0, 0.0, 0.0], _BLUE)
        self._arrow("force")

    def _move_electromagnetic(self, op, pose):
        model = op.model
        w = model.width / SCENE_UNIT
        e = 0.4 * w
        loop = [(0.0, -e), (1.0, -e), (1.0, e), (0.0, e)]
        self._surface_line("loop", model, pose, loop, color=_COPPER)
        top = self._tip_top(model, pose)
        vec = np.array([0.0, 0.0, 0.8 * pose.output_fraction])
        self._arrows["force"].set(top + [0.0, 0.0, 0.05], vec)
        self.parts["force"] = vec

    # -- electrostatic ----------------------------------------------------------------------------
    def _draw_electrostatic(self, op):
        model = op.model
        L = model.length / SCENE_UNIT
        le = model.electrode_length / SCENE_UNIT
        self._box("electrode", (le, 0.6, 0.05), [L - le / 2, 0.0, -0.45], _GOLD)
        self._arrow("force")

    def _move_electrostatic(self, op, pose):
        model = op.model
        L = model.length / SCENE_UNIT
        le = model.electrode_length / SCENE_UNIT
        self.vis["element"]["electrode"].set_transform(translation([L - le / 2, 0.0, -0.45]))
        top = self._tip_top(model, pose)
        vec = np.array([0.0, 0.0, 0.8 * pose.output_fraction])
        self._arrows["force"].set(top + [0.0, 0.0, 0.05], vec)
        self.parts["force"] = vec

    # -- optomechanical ---------------------------------------------------------------------------
    def _draw_optomechanical(self, op):
        model = op.model
        L = model.length / SCENE_UNIT
        w = model.width / SCENE_UNIT
        node = self.vis["element"]["disk"]
        node.set_object(g.Cylinder(0.03, radius=0.35), _mat(0xb0b0ff, 0.9))
        rot = np.array([[1, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 0], [0, 0, 0, 1]], dtype=float)
        node.set_transform(translation([L - 0.1, w / 2 + 0.38, 0.0]) @ rot)
        self._box("waveguide", (4.0, 0.04, 0.03), [L - 0.1, w / 2 + 0.78, 0.0], 0x8080c0)

    def _move_optomechanical(self, op, pose):
        self.parts["detuning_fraction"] = pose.fraction

    # -- piezoresistive ---------------------------------------------------------------------------
    def _draw_piezoresistive(self, op):
        pass

    def _move_piezoresistive(self, op, pose):
        model = op.model
        w = model.width / SCENE_UNIT
        lr = model.resistor_length / model.length
        e = 0.3 * w
        color = _RED if pose.output_fraction * np.sign(model.piezo_coefficient) < 0 else _BLUE
        self._surface_line("resistor", model, pose, [(0.0, -e), (1.0, -e), (1.0, e), (0.0, e)],
                           x_range=(0.0, lr), color=color)

    # -- electrothermal ---------------------------------------------------------------------------
    def _draw_electrothermal(self, op):
        pass

    def _move_electrothermal(self, op, pose):
        model = op.model
        w = model.width / SCENE_UNIT
        e = 0.35 * w
        n = 6
        path = []
        for i in range(n + 1):
            u = 0.05 + 0.9 * i / n
            path += [(u, -e), (u, e)] if i % 2 == 0 else [(u, e), (u, -e)]
        self._surface_line("heater", model, pose, path, color=0xff3000)

    # -- piezoelectric ----------------------------------------------------------------------------
    def _draw_piezoelectric(self, op):
        self._film_material = g.MeshLambertMaterial(color=_GOLD)

    def _move_piezoelectric(self, op, pose):
        model = op.model
        u = SCENE_UNIT
        h, w, t = model.thickness / u, model.width / u, max(model.film_thickness / u, 0.01)
        le = model.electrode_length / u
        n = max(int(np.searchsorted(pose.x, le)), 2)
        x = np.linspace(0.0, le, n)
        z = np.interp(x, pose.x, pose.z)
        slope = np.interp(x, pose.x, pose.slope)
        off = (h + t) / 2
        mesh = beam_mesh(x, z + off, 0.8 * w, t, np.zeros((n, 2)), slope=slope)
        self.vis["element"]["film"].set_object(
            g.TriangularMeshGeometry(mesh.vertices, mesh.faces), self._film_material)
        self.parts["film_length"] = le
