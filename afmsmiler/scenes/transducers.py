"""The 3D scale models of module (b): the lever with each transducer's laser path or embedded element.

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
:class:`TransducerScene` draws into the kernel's single viewer
(:func:`~afmsmiler.scenes.get_viewer`) and updates in place: a new input moves the parts with
``set_transform`` and re-sends only the bent geometry; a new principle replaces the
principle's group of objects under its own path.
"""
from __future__ import annotations

from dataclasses import dataclass

import meshcat
import meshcat.geometry as g
import numpy as np

from ..transducers.acoustic import mode_slope_factor
from ..transducers.base import Transducer
from ..validation import check_range
from .camera import readable_width, set_camera, show_helpers
from .colors import ColorScale
from .legends import TextPlate
from .meshes import beam_mesh
from .shapes import Arrow, Segment, Tube, cone, sphere
from .transforms import rotation_between, translation
from .viewer import get_viewer

__all__ = ["SCENE_UNIT", "DEFAULTS", "TransducerScene", "LeverPose", "lever_pose"]

#: Metres per scene unit (1 scene unit = 100 um), for the lever.
SCENE_UNIT = 100e-6

#: Defaults of the scene, in one place.
DEFAULTS = dict(
    max_tip=0.12,         # drawn tip deflection at the largest input, as a fraction of L
    n_length=41,          # stations along the drawn lever
    n_sweep=21,           # inputs sampled to find the largest deflection and output
    meter_x=-1.4,         # position of the signal meter (scene units)
    beam_radius=0.012,    # laser beams
    detector_distance=1.5,  # optical beam deflection: tip to photodiode, scene units
    camera=(0.8, -3.6, 2.8),  # a little from above: the photodiode's face is not edge-on
)

_WHITE, _GREY, _RED, _BLUE, _GREEN = 0xffffff, 0x9a9a9a, 0xe03030, 0x3060e0, 0x20a040
_COPPER, _ORANGE, _GOLD = 0xb87333, 0xf08020, 0xd4af37
_STRAIN = ColorScale.symmetric(1.0, "RdBu_r", "bending strain (relative)", "")


def _mat(color, opacity=1.0):
    return g.MeshLambertMaterial(color=color, opacity=opacity, transparent=opacity < 1)


@dataclass(frozen=True)
class LeverPose:
    """The lever as drawn (scene units), from a transducer's chain at one input.

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


def lever_pose(model: Transducer, value: float, mode: str | None = None,
               n_length: int = DEFAULTS["n_length"]) -> LeverPose:
    """The drawn lever for ``model`` at input ``value`` (SI): shape, exaggeration and strain.

    Parameters
    ----------
    model : Transducer
        The transducer model (its lever and chain).
    value : float
        The input in SI units.
    mode : str, optional
        ``"sensing"`` or ``"actuation"`` for a model that does both.
    n_length : int
        Stations along the lever.

    Returns
    -------
    LeverPose
        The end-load shape (3 u^2 - u^3) / 2 (mode 1 for base excitation) scaled so that the
        largest deflection over the input range is ``DEFAULTS["max_tip"]`` L.
    """
    q = model.input_quantity(mode)
    sweep = model.chain(np.linspace(q.low, q.high, DEFAULTS["n_sweep"]), mode)
    here = model.chain(np.array([value]), mode)
    z_max = float(np.abs(sweep.stage("deflection").values).max()) or 1.0
    out_max = float(np.abs(sweep.output.values).max()) or 1.0
    fraction = float(here.stage("deflection").values[0]) / z_max
    length = model.length / SCENE_UNIT
    u = np.linspace(0.0, 1.0, n_length)
    if model.key == "piezo_acoustic":
        shape = model.lever.mode_shape(u * model.length, 1)
        dshape = np.gradient(shape, u)
        curv = np.gradient(dshape, u)
    else:
        shape = (3 * u ** 2 - u ** 3) / 2
        dshape = 3 * (u - u ** 2 / 2)
        curv = 3 * (1 - u)
    amplitude = DEFAULTS["max_tip"] * length * fraction
    strain = -np.sign(fraction) * np.abs(fraction) * curv / max(np.abs(curv).max(), 1e-12)
    return LeverPose(u * length, amplitude * shape, amplitude * dshape / length, strain,
                     fraction, float(here.output.values[0]) / out_max)


class TransducerScene:
    """A transducer's scale model in meshcat, updated in place (see the module docstring).

    Parameters
    ----------
    model : Transducer
        The first model to draw.
    value : float
        Its input in SI units.
    mode : str, optional
        ``"sensing"`` or ``"actuation"`` for a model that does both.
    vis : meshcat.Visualizer, optional
        The root visualizer; by default the kernel's :func:`~afmsmiler.scenes.get_viewer`.
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

    def __init__(self, model: Transducer, value: float, mode: str | None = None, *,
                 vis: meshcat.Visualizer | None = None, path: str = "afmsmiler/transducers",
                 camera: bool = True):
        if not isinstance(model, Transducer):
            raise ValueError(f"model must be a Transducer, got {model!r}")
        self.root = vis if vis is not None else get_viewer()
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
        self.update(model, value, mode)
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
    def update(self, model: Transducer, value: float, mode: str | None = None) -> None:
        """Redraw for a model and input (SI), in place.

        Parameters
        ----------
        model : Transducer
            The model (a new principle replaces the principle's objects).
        value : float
            The input in SI units, inside its range.
        mode : str, optional
            ``"sensing"`` or ``"actuation"`` for a model that does both.
        """
        if not isinstance(model, Transducer):
            raise ValueError(f"model must be a Transducer, got {model!r}")
        q = model.input_quantity(mode)
        value = check_range(q.name, value, q.low, q.high, q.unit)
        pose = lever_pose(model, value, mode)
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
            getattr(self, f"_draw_{model.key}")(model)
        getattr(self, f"_move_{model.key}")(model, value, mode, pose)
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
        """A four-quadrant photodiode: four thin plates in the plane through ``centre``."""
        n = np.asarray(normal, float) / np.linalg.norm(normal)
        rot = np.eye(4)
        rot[:3, :3] = rotation_between([0.0, 0.0, 1.0], n)
        colors = (0x4060a0, 0x5070b0, 0x5070b0, 0x4060a0)
        half = size / 2
        for i, (a, b) in enumerate(((1, 1), (-1, 1), (-1, -1), (1, -1))):
            node = self.vis["element"][name][f"q{i}"]
            node.set_object(g.Box([half * 0.96, half * 0.96, 0.01]), _mat(colors[i]))
            node.set_transform(translation(centre) @ rot
                               @ translation([a * half / 2, b * half / 2, 0.0]))
        self.parts[name] = (np.asarray(centre, float), n, rot)

    # -- optical beam deflection ------------------------------------------------------------------
    def _draw_optical_beam_deflection(self, model):
        L = model.length / SCENE_UNIT
        self._source = np.array([L - 1.6, 0.0, 2.2])
        self._box("laser", (0.5, 0.25, 0.25), self._source, 0x333333)
        tip = np.array([L, 0.0, model.thickness / SCENE_UNIT / 2])  # the undeflected top face
        d = tip - self._source
        d /= np.linalg.norm(d)
        nominal = d - 2 * d[2] * np.array([0.0, 0.0, 1.0])
        self._detector = tip + DEFAULTS["detector_distance"] * nominal
        self.parts["detector"] = (self._detector, -nominal, None)
        # The drawn lever tilts ~13x more than the real one and the detector is ~20x nearer than
        # the real optical path D, so the drawn spot is scaled like its travel: at the ends of
        # the input range, travel / radius on the drawing = s / w of the model on average (the
        # drawn tip's own up-down motion, negligible in a real AFM, adds +-12 %), and the spot
        # crosses the split line as far (in spot radii) as the model's signal says.
        q = model.input_quantity(None)
        travel, ratio = [], []
        for end in (q.low, q.high):
            pose = lever_pose(model, end)
            hit = self._reflect(model, self._tip_top(model, pose), pose)
            travel.append(float(np.linalg.norm(hit - self._detector)))
            s = float(model.chain(np.array([end])).stage("spot_displacement").values[0])
            ratio.append(travel[-1] * model.spot_radius / abs(s))
        self._spot_radius = float(np.mean(ratio))
        size = 2.1 * (max(travel) + self._spot_radius)
        self._quadrants("detector", self._detector, -nominal, size=size)
        self._segment("incident", _RED)
        self._segment("reflected", _RED, opacity=0.8)
        sphere(self.vis["element"]["spot"], 1.0, color=0xff0000, opacity=0.85)

    def _reflect(self, model, top, pose):
        """Where the beam from the laser, reflected at ``top`` of the lever drawn as ``pose``,
        meets the detector plane (law of reflection on the drawn surface)."""
        d = top - self._source
        d /= np.linalg.norm(d)
        n = np.array([-pose.slope[-1], 0.0, 1.0])
        n /= np.linalg.norm(n)
        r = d - 2 * np.dot(d, n) * n
        centre, normal = self._detector, self.parts["detector"][1]
        return top + np.dot(centre - top, normal) / np.dot(r, normal) * r

    def _move_optical_beam_deflection(self, model, value, mode, pose):
        top = self._tip_top(model, pose)
        self._segments["incident"].set(self._source, top)
        hit = self._reflect(model, top, pose)
        self._segments["reflected"].set(top, hit)
        _, normal, rot = self.parts["detector"]
        a = self._spot_radius
        flat = np.eye(4)
        flat[:3, :3] = rot[:3, :3] @ np.diag([a, a, 0.02])  # a disc on the detector's plane
        self.vis["element"]["spot"].set_transform(translation(hit - 0.02 * normal) @ flat)
        self.parts["spot"] = hit
        self.parts["spot_radius"] = a

    # -- astigmatic detection ---------------------------------------------------------------------
    def _draw_astigmatic(self, model):
        L = model.length / SCENE_UNIT
        self._head = np.array([L, 0.0, 1.8])
        self._box("pickup_head", (0.9, 0.7, 0.35), self._head, 0x303030)
        self._box("objective", (0.3, 0.3, 0.05), self._head - [0, 0, 0.2], 0x8080ff, 0.6)
        # the quadrant detector, drawn as a window on the head's top face (it sits inside)
        self._quadrants("detector", self._head + [0.0, 0.0, 0.185], [0.0, 0.0, 1.0], size=0.4)
        self._segment("beam", _RED, opacity=0.8)
        sphere(self.vis["element"]["spot"], 1.0, color=0xff2020)

    def _move_astigmatic(self, model, value, mode, pose):
        top = self._tip_top(model, pose)
        self._segments["beam"].set(top, self._head - [0, 0, 0.22])
        wx, wy = model.spot_radii(value)
        scale = 0.1 / np.sqrt(wx * wy)
        centre = self._head + [0.0, 0.0, 0.2]
        self.vis["element"]["spot"].set_transform(
            translation(centre) @ np.diag([wx * scale, wy * scale, 0.02, 1.0]))
        self.parts["spot"] = (float(wx * scale), float(wy * scale))

    # -- interferometry ---------------------------------------------------------------------------
    def _draw_interferometry(self, model):
        L = model.length / SCENE_UNIT
        node = self.vis["element"]["fibre"]
        node.set_object(g.Cylinder(1.6, radius=0.12), _mat(0xe0e0c0, 0.9))
        rot = np.array([[1, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 0], [0, 0, 0, 1]], dtype=float)
        node.set_transform(translation([L, 0.0, 1.3]) @ rot)
        self._fibre_end = np.array([L, 0.0, 0.5])
        self._segment("beam", _RED, opacity=0.7)

    def _move_interferometry(self, model, value, mode, pose):
        top = self._tip_top(model, pose)
        self._segments["beam"].set(self._fibre_end, top)
        self.parts["gap"] = float(self._fibre_end[2] - top[2])

    # -- piezo-acoustic ---------------------------------------------------------------------------
    def _draw_piezo_acoustic(self, model):
        self._box("shaker", (1.0, 1.2, 0.3), [-0.5, 0.0, -0.45], _ORANGE)

    def _move_piezo_acoustic(self, model, value, mode, pose):
        # the base moves by the tip amplitude / (gamma |H|): barely at resonance
        gain = float(np.abs(model.base_transfer(model.drive_ratio * model.resonance_frequency)))
        offset = pose.z[-1] / max(gain, 1e-12)
        offset = float(np.clip(offset, -0.3, 0.3))
        self.vis["element"]["shaker"].set_transform(translation([-0.5, 0.0, -0.45 + offset]))
        self.parts["base_offset"] = offset
        self.parts["slope_factor"] = mode_slope_factor()

    # -- photothermal -----------------------------------------------------------------------------
    def _draw_photothermal(self, model):
        L = model.length / SCENE_UNIT
        self._source = np.array([L + 1.2, 0.0, 2.0])
        self._box("laser", (0.4, 0.22, 0.22), self._source, 0x222266)
        self._segment("heating_beam", _BLUE, radius=0.02, opacity=0.8)

    def _move_photothermal(self, model, value, mode, pose):
        top = self._tip_top(model, pose)
        self._segments["heating_beam"].set(self._source, top)
        self.vis["element"]["heating_beam"].set_property("visible", bool(value > 0))
        self.parts["beam_on"] = bool(value > 0)

    # -- electromagnetic --------------------------------------------------------------------------
    def _draw_electromagnetic(self, model):
        L = model.length / SCENE_UNIT
        self._box("magnet_n", (0.4, 1.0, 0.6), [L + 0.6, 0.0, 0.0], _RED)
        self._box("magnet_s", (0.4, 1.0, 0.6), [L + 1.0, 0.0, 0.0], _BLUE)
        self._arrow("force")

    def _move_electromagnetic(self, model, value, mode, pose):
        w = model.width / SCENE_UNIT
        e = 0.4 * w
        loop = [(0.0, -e), (1.0, -e), (1.0, e), (0.0, e)]
        self._surface_line("loop", model, pose, loop, color=_COPPER)
        top = self._tip_top(model, pose)
        vec = np.array([0.0, 0.0, 0.8 * pose.output_fraction])
        self._arrows["force"].set(top + [0.0, 0.0, 0.05], vec)
        self.parts["force"] = vec

    # -- electrostatic ----------------------------------------------------------------------------
    def _draw_electrostatic(self, model):
        L = model.length / SCENE_UNIT
        le = model.electrode_length / SCENE_UNIT
        self._box("electrode", (le, 0.6, 0.05), [L - le / 2, 0.0, -0.45], _GOLD)
        self._arrow("force")

    def _move_electrostatic(self, model, value, mode, pose):
        L = model.length / SCENE_UNIT
        le = model.electrode_length / SCENE_UNIT
        self.vis["element"]["electrode"].set_transform(translation([L - le / 2, 0.0, -0.45]))
        top = self._tip_top(model, pose)
        vec = np.array([0.0, 0.0, 0.8 * pose.output_fraction])
        self._arrows["force"].set(top + [0.0, 0.0, 0.05], vec)
        self.parts["force"] = vec

    # -- optomechanical ---------------------------------------------------------------------------
    def _draw_optomechanical(self, model):
        L = model.length / SCENE_UNIT
        w = model.width / SCENE_UNIT
        node = self.vis["element"]["disk"]
        node.set_object(g.Cylinder(0.03, radius=0.35), _mat(0xb0b0ff, 0.9))
        rot = np.array([[1, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 0], [0, 0, 0, 1]], dtype=float)
        node.set_transform(translation([L - 0.1, w / 2 + 0.38, 0.0]) @ rot)
        self._box("waveguide", (4.0, 0.04, 0.03), [L - 0.1, w / 2 + 0.78, 0.0], 0x8080c0)

    def _move_optomechanical(self, model, value, mode, pose):
        self.parts["detuning_fraction"] = pose.fraction

    # -- piezoresistive ---------------------------------------------------------------------------
    def _draw_piezoresistive(self, model):
        pass

    def _move_piezoresistive(self, model, value, mode, pose):
        w = model.width / SCENE_UNIT
        lr = model.resistor_length / model.length
        e = 0.3 * w
        color = _RED if pose.output_fraction * np.sign(model.piezo_coefficient) < 0 else _BLUE
        self._surface_line("resistor", model, pose, [(0.0, -e), (1.0, -e), (1.0, e), (0.0, e)],
                           x_range=(0.0, lr), color=color)

    # -- electrothermal ---------------------------------------------------------------------------
    def _draw_electrothermal(self, model):
        pass

    def _move_electrothermal(self, model, value, mode, pose):
        w = model.width / SCENE_UNIT
        e = 0.35 * w
        n = 6
        path = []
        for i in range(n + 1):
            u = 0.05 + 0.9 * i / n
            path += [(u, -e), (u, e)] if i % 2 == 0 else [(u, e), (u, -e)]
        self._surface_line("heater", model, pose, path, color=0xff3000)

    # -- piezoelectric ----------------------------------------------------------------------------
    def _draw_piezoelectric(self, model):
        self._film_material = g.MeshLambertMaterial(color=_GOLD)

    def _move_piezoelectric(self, model, value, mode, pose):
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
