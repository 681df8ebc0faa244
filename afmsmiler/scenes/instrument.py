"""Module (e)'s two instruments in 3D: named parts that come apart, a housing that fades, knobs.

Two procedural scale models (meshcat primitives and meshes generated here; no vendor CAD):

- ``"obd"``: a conventional AFM with optical beam deflection (OBD) sensing and a piezo tube
  scanner, laid out like a Bruker MultiMode: a base with the coarse approach (two thumb screws
  and a motor-driven rear screw), the piezo tube in its can, the sample puck on the tube's cap,
  and the optical head: laser diode, focusing lens, cantilever holder with the probe chip
  (tilted by 12 degrees), steering mirror, four-quadrant photodiode, the two laser-positioning
  knobs on top and the two photodiode knobs on the side, under a head cover.
- ``"educational"``: a low-cost educational AFM with an active probe (piezoresistive sensing,
  electrothermal actuation) on its board: base plate, manual x-y stage, piezo x-y flexure
  scanner, sample holder, a gantry with a stepper-motor coarse approach, the z piezo, the probe
  board with the bridge amplifier, the controller and the high-voltage amplifier, a USB camera
  for the approach, a ribbon cable and an acrylic hood.

The origin is the probe's tip (touching the sample), z up, the lever along +x (its free end at
the tip): the camera of meshcat orbits the origin, so both instruments are framed around the
tip. Everything is drawn to scale at **1 scene unit = 1 cm** (:data:`SCENE_UNIT`); the public
methods take SI (metres, radians). The lever itself (450 um, the optics model's) is drawn to scale too, so it is a
speck at the instrument's scale: :meth:`InstrumentScene.focus` zooms in on the chip. The laser
beam is drawn 0.7 mm thick everywhere (schematic: the focused spot on the lever is a few tens of
micrometres).

Dimensions assumed: typical values of the commercial parts, from data sheets and photographs,
not measured drawings. The probe chip (3.4 x 1.6 x 0.3 mm) is the industry's standard size (e.g.
NanoWorld, BudgetSensors and Bruker data sheets); piezo tubes of 1/2 inch (12.7 mm) outer
diameter are common in tube scanners; 15 mm steel discs are the usual AFM specimen discs; the
photodiode is a 3 x 3 mm quadrant cell in a TO-5 can (e.g. Hamamatsu S4349); the laser diode a
5.6 mm TO can; the stepper motor a NEMA 17 frame (42 mm); the active probe follows the
self-sensing, self-actuating cantilevers of Rangelow's group (a few hundred micrometres long).
Placement (mm from the tip): OBD base top 80 below, head plate 8 to 12 above, head cover 12 to
52 above; laser exit 38 and lens 22 from the lever end along the incident beam (12 degrees
from vertical), mirror 35 along the reflected beam, photodiode 8 past the mirror. Educational:
base plate top 39 below, the sample stages stacked up to the tip, the gantry 40 behind it.

========================  ======================================================================
OBD AFM part              assumed dimensions
========================  ======================================================================
base                      150 x 170 x 60 mm
scanner_can               45 mm dia x 68 mm
support_ring              100 mm OD, 20 mm ID, 4 mm thick
piezo_tube                12.7 mm OD, 10.7 mm ID, 60 mm long
scanner_cap               16 mm dia x 1.2 mm
sample_puck               15 mm dia x 0.8 mm disc, 5 x 5 x 0.5 mm sample
coarse_screw_left         4 mm dia x 24 mm, 14 mm dia thumb wheel
coarse_screw_right        4 mm dia x 24 mm, 14 mm dia thumb wheel
coarse_screw_rear         4 mm dia x 24 mm, 14 mm dia thumb wheel
approach_motor            20 mm dia x 30 mm
head_plate                100 x 100 x 4 mm with a 36 x 36 mm window
cantilever_holder         24 x 14 x 3 mm block, 6 x 4 x 0.5 mm clip
probe_chip                3.4 x 1.6 x 0.3 mm chip, lever 450 x 50 x 2 um, tip 15 um
laser_diode               5.6 mm TO can in a 9 mm dia x 14 mm tube
focusing_lens             8 mm dia biconvex lens, f = 22 mm
steering_mirror           10 x 10 x 1.5 mm mirror on a 12 x 12 x 3 mm mount
photodiode                3 x 3 mm quadrant cell, 9 mm dia TO-5 can
head_cover                64 x 64 x 40 mm
laser_x                   10 mm dia x 10 mm knurled knob
laser_y                   10 mm dia x 10 mm knurled knob
detector_vertical         10 mm dia x 10 mm knurled knob
detector_lateral          10 mm dia x 10 mm knurled knob
========================  ======================================================================

========================  ======================================================================
educational AFM part      assumed dimensions
========================  ======================================================================
base_plate                200 x 160 x 10 mm
manual_stage              60 x 60 x 18 mm, two 10 mm dia x 25 mm micrometers
xy_scanner                40 x 40 x 12 mm
sample_holder             10 mm dia x 8 mm post, 12 mm dia x 1 mm disc
gantry                    two 20 x 20 x 110 mm pillars, 30 x 150 x 12 mm bridge
stepper_motor             42 x 42 x 34 mm (NEMA 17)
lead_screw                8 mm dia x 60 mm
carriage                  30 x 50 x 15 mm block, 18 x 20 x 6 mm arm
z_piezo                   10 x 10 x 20 mm
probe_board               40 x 25 x 1.6 mm PCB, tilted 5 deg
active_probe              2 x 1 x 0.4 mm chip, lever 350 x 140 x 5 um, tip 10 um
piezoresistor             two 60 x 20 um legs and a 20 x 100 um bar
heater                    250 x 20 um stripe
bridge_amplifier          30 x 20 x 5 mm board
controller                60 x 70 x 15 mm
hv_amplifier              60 x 40 x 25 mm
usb_camera                12 mm dia x 50 mm
ribbon_cable              3 mm dia bundle
hood                      210 x 170 x 160 mm
========================  ======================================================================

What a scene offers (all one-line calls for the notebook and the guided setup):

- :meth:`InstrumentScene.parts` and :meth:`~InstrumentScene.describe`: the named parts (meshcat
  paths ``group/part`` under the scene's path) and their short descriptions,
  :meth:`~InstrumentScene.table` for all of them, and :meth:`~InstrumentScene.pick` (highlight
  one part, optionally focus on it, and return its description: a part menu's callback);
- :meth:`~InstrumentScene.set_housing_opacity` (0: hidden, 1: opaque);
- :meth:`~InstrumentScene.explode` (0: assembled, 1: exploded, each part moved along its own
  direction by its own distance, :attr:`Part.explode_direction` and
  :attr:`Part.explode_distance`) and
  :meth:`~InstrumentScene.animate_explode` (a meshcat Animation of a bounded number of frames);
- :meth:`~InstrumentScene.highlight` and :meth:`~InstrumentScene.unhighlight` (colour and back);
- :meth:`~InstrumentScene.set_gap` (the coarse approach: the probe and what carries it lifted
  above the sample, for the walkthrough's approach step);
- hooks for the laser-alignment model: :meth:`~InstrumentScene.turn_knob` turns a knob on its
  axis, :meth:`~InstrumentScene.show_beam` draws a beam through given points (metres) with its
  spots, :meth:`~InstrumentScene.nominal_beam` / :attr:`InstrumentScene.anchors` give the
  drawn optics' positions (metres) the model's geometry can be matched to, and
  :meth:`~InstrumentScene.lever_point` / :meth:`~InstrumentScene.photodiode_point` place the
  model's spot coordinates (on the lever, on the detector) in the scene, and
  :meth:`~InstrumentScene.show_alignment` draws the beam from them in one call;
- :meth:`~InstrumentScene.focus` (the camera near one part) and
  :meth:`~InstrumentScene.static_html` (the page the book embeds).

The scene draws; it evaluates no physics (the beam's points come from the alignment model; the
nominal beam only joins the drawn optics' centres).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import meshcat
import meshcat.geometry as g
import numpy as np
from meshcat.animation import Animation

from ..parameters import Parameter, read_only, unit_scale
from ..validation import (check_array, check_choice, check_integer, check_positive,
                          check_range)
from .camera import set_camera, show_helpers
from .view import fit_camera
from .shapes import Segment, Tube, _show, sphere
from .transducers import quadrant_photodiode
from .transforms import reflect, rotation_between, translation
from .viewer import SceneDisplay, save_static_html as _save_static_html, scene_root, static_html as _static_html

__all__ = ["SCENE_UNIT", "PARAMETERS", "LIMITS", "DEFAULTS", "Shape", "Part", "Instrument",
           "INSTRUMENTS", "InstrumentScene", "hollow_cylinder_mesh", "prism_mesh"]

#: Metres per scene unit (1 scene unit = 1 cm).
SCENE_UNIT = 0.01
_MM = 1.0 / unit_scale("mm")   # metres per millimetre (the dimension tables are in mm)

#: The settings of a scene a notebook may give a slider (SI; angles in rad).
PARAMETERS = read_only(dict(
    housing_opacity=Parameter(name="housing_opacity", unit="", default=0.35, low=0.0, high=1.0,
                              label="housing opacity"),
    explode_fraction=Parameter(name="explode_fraction", unit="", default=0.0, low=0.0,
                               high=1.0, label="exploded view"),
    knob_angle=Parameter(name="knob_angle", unit="rad", display_unit="deg", default=0.0,
                         low=-20 * math.pi, high=20 * math.pi, label="knob angle"),
    approach_gap=Parameter(name="approach_gap", unit="m", display_unit="mm", default=0.0,
                           low=0.0, high=0.01, label="tip-sample gap (coarse approach)"),
))

#: Bounds that keep every call within seconds: animation frames, transforms sent by one
#: animation, beam points and spots, and how far from the tip a beam point may be (m).
LIMITS = read_only(dict(frames=600, animation_transforms=20_000, beam_points=32, spots=8,
                        reach=1.0, spot_radius=0.01))

#: Defaults of the scene, in one place (lengths in m).
DEFAULTS = read_only(dict(
    frames=48,              # frames of the explode animation (one way)
    fps=24,                 # its frame rate
    highlight=0xffb000,     # colour of a highlighted part
    beam_radius=0.35e-3,    # drawn laser beam (m)
    beam_color=0xff2020,
    spot_radius=0.6e-3,     # drawn spots (m)
    focus_distance=0.12,    # camera distance from a focused part (m)
    focus_direction=(1.0, -1.4, 1.3),  # from a focused part to the camera (front right, above)
))


def hollow_cylinder_mesh(outer_radius: float, inner_radius: float, length: float,
                         sides: int = 32) -> tuple[np.ndarray, np.ndarray]:
    """Vertices and triangles of a hollow cylinder (a piezo tube) along z, centred at the origin.

    Parameters
    ----------
    outer_radius, inner_radius : float
        Radii in scene units, ``0 < inner_radius < outer_radius``.
    length : float
        Length along z in scene units, > 0.
    sides : int
        Vertices around each ring, 3 to 256.

    Returns
    -------
    (vertices, faces) : tuple of ndarray
        ``4 sides`` vertices (float32) and ``8 sides`` triangles: outer and inner walls and the
        two end rings.
    """
    ro = check_positive("outer_radius", outer_radius)
    ri = check_positive("inner_radius", inner_radius)
    if not ri < ro:
        raise ValueError(f"inner_radius must be below outer_radius = {ro:g}, got {ri:g}")
    h = check_positive("length", length) / 2
    n = check_integer("sides", sides, 3, 256)
    a = 2 * np.pi * np.arange(n) / n
    c, s = np.cos(a), np.sin(a)
    rings = [np.stack([r * c, r * s, np.full(n, z)], -1)
             for r, z in ((ro, -h), (ro, h), (ri, -h), (ri, h))]
    j = np.arange(n)
    k = (j + 1) % n

    def band(p, q):  # quads between ring p and ring q (vertex blocks of n)
        return np.concatenate([np.stack([p * n + j, p * n + k, q * n + k], -1),
                               np.stack([p * n + j, q * n + k, q * n + j], -1)])
    faces = np.concatenate([band(0, 1), band(3, 2), band(1, 3), band(2, 0)])
    return np.concatenate(rings).astype(np.float32), faces.astype(np.uint32)


def prism_mesh(outline, length: float) -> tuple[np.ndarray, np.ndarray]:
    """Vertices and triangles of a prism: a star-shaped outline in x-y extruded along z.

    Used for knurled knobs and thumb wheels (an outline with ridges), centred at the origin.

    Parameters
    ----------
    outline : array_like, shape (n, 2)
        The outline's corners in order, scene units, n from 3 to 1024, star-shaped about the
        origin (every corner seen from the origin), so the end caps are fans from the centre.
    length : float
        Length along z in scene units, > 0.

    Returns
    -------
    (vertices, faces) : tuple of ndarray
        ``2 n + 2`` vertices (float32) and ``4 n`` triangles.
    """
    xy = check_array("outline", outline, ndim=2)
    if xy.shape[1] != 2 or not 3 <= xy.shape[0] <= 1024:
        raise ValueError(f"outline must have shape (n, 2) with 3 <= n <= 1024, got {xy.shape}")
    h = check_positive("length", length) / 2
    n = xy.shape[0]
    bottom = np.column_stack([xy, np.full(n, -h)])
    top = np.column_stack([xy, np.full(n, h)])
    centres = np.array([[0.0, 0.0, -h], [0.0, 0.0, h]])
    j = np.arange(n)
    k = (j + 1) % n
    walls = np.concatenate([np.stack([j, k, n + k], -1), np.stack([j, n + k, n + j], -1)])
    caps = np.concatenate([np.stack([np.full(n, 2 * n), k, j], -1),
                           np.stack([np.full(n, 2 * n + 1), n + j, n + k], -1)])
    vertices = np.concatenate([bottom, top, centres]).astype(np.float32)
    return vertices, np.concatenate([walls, caps]).astype(np.uint32)


def _knurl_outline(radius: float, ridges: int = 24, depth: float = 0.08) -> np.ndarray:
    a = np.pi * np.arange(2 * ridges) / ridges
    r = np.where(np.arange(2 * ridges) % 2 == 0, radius, radius * (1 - depth))
    return np.column_stack([r * np.cos(a), r * np.sin(a)])


_KINDS = ("box", "cylinder", "cone", "sphere", "ellipsoid", "tube", "knurl", "quadrants", "wire")


@dataclass(frozen=True)
class Shape:
    """One primitive of a part, in the part's own frame (millimetres, as the tables).

    Attributes
    ----------
    name : str
        Its node's name under the part.
    kind : str
        ``"box"`` (size: x, y, z), ``"cylinder"`` (diameter, length), ``"cone"`` (base
        diameter, height; ``axis`` points to the apex), ``"sphere"`` (diameter,),
        ``"ellipsoid"`` (diameters x, y, z), ``"tube"`` (outer and inner diameter, length: a
        hollow cylinder), ``"knurl"`` (diameter, length: a knurled wheel), ``"quadrants"``
        (side,: a four-quadrant photodiode facing ``axis``) or ``"wire"`` (diameter,: a tube
        through ``points``).
    size : tuple of float
        Dimensions in mm, as listed for ``kind``.
    color : int
        0xRRGGBB.
    at : tuple of float
        Centre in the part's frame, mm.
    axis : tuple of float
        Axis of a cylinder, cone, tube or knurl, normal of the quadrants, z of an ellipsoid.
    opacity : float
        In (0, 1].
    points : tuple of tuple
        A wire's centre line in the part's frame, mm.
    """

    name: str
    kind: str
    size: tuple
    color: int
    at: tuple = (0.0, 0.0, 0.0)
    axis: tuple = (0.0, 0.0, 1.0)
    opacity: float = 1.0
    points: tuple = ()

    def __post_init__(self):
        check_choice("kind", self.kind, _KINDS)


@dataclass(frozen=True)
class Part:
    """A named part: where it sits (assembled), what it is, how it moves in the exploded view.

    Attributes
    ----------
    name : str
        Its name (unique in the instrument; the meshcat path is ``group/name``).
    group : str
        The assembly it belongs to (``"base"``, ``"scanner"``, ``"head"``, ...).
    label : str
        Its name for people.
    description : str
        What it is and does, in a sentence or two (shown when the part is picked).
    dimensions : str
        Its assumed dimensions, in words.
    position_mm : tuple of float
        Origin of the part's frame in the scene frame (assembled), mm.
    shapes : tuple of Shape
        Its primitives.
    explode_mm : tuple of float
        Its displacement in the fully exploded view, mm (direction times distance).
    axis : tuple of float
        Where the part's own z axis points in the scene frame (a knob's axis, a tilt).
    housing : bool
        Part of the housing (made transparent by
        :meth:`InstrumentScene.set_housing_opacity`).
    knob : bool
        A knob that :meth:`InstrumentScene.turn_knob` turns about ``axis``.
    """

    name: str
    group: str
    label: str
    description: str
    dimensions: str
    position_mm: tuple
    shapes: tuple
    explode_mm: tuple
    axis: tuple = (0.0, 0.0, 1.0)
    housing: bool = False
    knob: bool = False

    @property
    def position(self) -> np.ndarray:
        """Origin of the part's frame when assembled, m."""
        return np.asarray(self.position_mm, float) * _MM

    @property
    def explode_distance(self) -> float:
        """How far the part moves from assembled to exploded, m."""
        return float(np.linalg.norm(self.explode_mm)) * _MM

    @property
    def explode_direction(self) -> np.ndarray:
        """The unit vector along which the part moves in the exploded view."""
        v = np.asarray(self.explode_mm, float)
        return v / np.linalg.norm(v)

    @property
    def rotation(self) -> np.ndarray:
        """3 x 3 rotation of the part's frame (its z axis to :attr:`axis`)."""
        return rotation_between([0.0, 0.0, 1.0], self.axis)


@dataclass(frozen=True)
class Instrument:
    """An instrument's description: its parts, cameras and (for an optical head) its beam.

    Attributes
    ----------
    key : str
        ``"obd"`` or ``"educational"``.
    title : str
        Its name for people.
    parts : tuple of Part
        Its parts.
    camera_mm, exploded_camera_mm : tuple of float
        Camera positions (mm) that frame it assembled and exploded, relative to ``centre_mm``.
    centre_mm : tuple of float
        The point (mm, scene frame) the camera looks at: the middle of the assembled
        instrument (the scene is shifted to put it at meshcat's camera target).
    anchors_mm : dict
        Name -> point (mm) of the drawn optics (the nominal beam's corners).
    beam : tuple of str
        Anchors the nominal beam joins, in order (empty: no laser).
    spots : tuple of str
        Anchors where the nominal beam makes a spot.
    approach_parts : tuple of str
        The parts the coarse approach lifts and lowers (the head, or the carriage and what it
        carries).
    lever : tuple
        ``(part, clamp_mm, length_mm)``: the part that carries the lever, the middle of the
        lever's top face at the clamp in that part's frame (mm), and the lever's length (mm).
    """

    key: str
    title: str
    parts: tuple
    camera_mm: tuple
    exploded_camera_mm: tuple
    centre_mm: tuple = (0.0, 0.0, 0.0)
    anchors_mm: dict = field(default_factory=dict)
    beam: tuple = ()
    spots: tuple = ()
    lever: tuple = ()
    approach_parts: tuple = ()


# -- colours ---------------------------------------------------------------------------------
_ALU, _DARK, _STEEL, _CERAMIC = 0xb8bcc2, 0x34373c, 0x8a8d91, 0xe8e0cc
_GOLD, _SILICON, _PCB, _BLACK = 0xd4af37, 0x6a7080, 0x1f7a3a, 0x1a1a1a
_GLASS, _MIRROR, _RED, _BRASS, _WHITE = 0x9fd3ff, 0xe6eef5, 0xd03030, 0xc9a44a, 0xf4f4f4
_ORANGE, _COPPER, _ACRYLIC = 0xe07020, 0xb87333, 0xcfe8ff


def _unit(v) -> np.ndarray:
    v = np.asarray(v, float)
    return v / np.linalg.norm(v)


def _knob(name, group, label, description, position, axis, explode):
    """A knurled knob (10 mm dia x 10 mm) with a white index mark on its end face."""
    return Part(name, group, label, description, "10 mm dia x 10 mm knurled knob",
                tuple(position), (Shape("wheel", "knurl", (10.0, 10.0), _DARK, (0, 0, 5)),
                                  Shape("mark", "box", (1.2, 3.5, 0.6), _WHITE, (0, 2.4, 10.2))),
                tuple(explode), axis=tuple(axis), knob=True)


def _obd() -> Instrument:
    tilt = math.radians(12.0)                        # the lever's tilt in the holder
    z_lever = (math.sin(tilt), 0.0, math.cos(tilt))  # the probe frame's z axis
    lever_top = np.array([-0.005, 0.0, 0.017])       # lever end, top face, in the probe frame
    lever_end = rotation_between([0, 0, 1], z_lever) @ lever_top
    to_laser = _unit([-12.0, 0.0, 48.0])            # from the lever end towards the laser
    laser, lens = 38.0 * to_laser, 22.0 * to_laser
    d = -to_laser
    n = np.asarray(z_lever)
    reflected = reflect(d, n)                          # law of reflection on the tilted lever
    mirror = 35.0 * reflected
    mirror_normal = _unit([1.0, 0.0, 0.0] - reflected)  # folds the beam to +x
    photodiode = mirror + [8.0, 0.0, 0.0]

    def t(v):
        return tuple(float(x) for x in v)

    parts = (
        Part("base", "base", "base",
             "The instrument's base: it holds the scanner and the electronics that drive it, "
             "and stands on the vibration isolation.", "150 x 170 x 60 mm",
             (0, 0, -110), (Shape("body", "box", (150, 170, 60), _DARK),), (0, 0, -60)),
        Part("scanner_can", "scanner", "scanner can",
             "The stainless can around the piezo tube: it shields the tube and carries the "
             "head's support ring (housing).", "45 mm dia x 68 mm",
             (0, 0, -46), (Shape("can", "cylinder", (45, 68), _STEEL),), (0, -90, -30),
             housing=True),
        Part("support_ring", "scanner", "head support ring",
             "The ring on top of the scanner on which the head's three coarse screws rest.",
             "100 mm OD, 20 mm ID, 4 mm thick",
             (0, 0, -10), (Shape("ring", "tube", (100, 20, 4), _ALU),), (0, 0, -20)),
        Part("piezo_tube", "scanner", "piezo tube scanner",
             "A tube of piezoceramic (PZT) with four outer electrodes: opposite voltages on "
             "two opposite quadrants bend it (x, y scan), the same voltage on all stretches "
             "it (z).", "12.7 mm OD, 10.7 mm ID, 60 mm long",
             (0, 0, -32.5),
             (Shape("tube", "tube", (12.7, 10.7, 60), _CERAMIC),)
             + tuple(Shape(f"electrode{i}", "box", (0.2, 2.0, 56) if i % 2 == 0
                           else (2.0, 0.2, 56), _GOLD,
                           (6.45 * math.cos(i * math.pi / 2), 6.45 * math.sin(i * math.pi / 2), 0))
                     for i in range(4)),
             (0, 0, -30)),
        Part("scanner_cap", "scanner", "scanner cap",
             "The magnetic cap on the tube's free end that holds the sample puck.",
             "16 mm dia x 1.2 mm", (0, 0, -1.9),
             (Shape("cap", "cylinder", (16, 1.2), _STEEL),), (0, 0, -12)),
        Part("sample_puck", "scanner", "sample puck",
             "A steel specimen disc with the sample glued on it, held by the cap's magnet.",
             "15 mm dia x 0.8 mm disc, 5 x 5 x 0.5 mm sample", (0, 0, 0),
             (Shape("disc", "cylinder", (15, 0.8), _STEEL, (0, 0, -0.9)),
              Shape("sample", "box", (5, 5, 0.5), 0x505a78, (0, 0, -0.25))), (0, 0, 6)),
        *(Part(f"coarse_screw_{side}", "base", f"coarse approach screw ({side})",
               "A fine-thread screw with a thumb wheel: turning it lowers the head and the probe "
               "towards the sample (coarse approach) and tilts the head."
               + (" The rear screw is driven by the approach motor." if side == "rear" else ""),
               "4 mm dia x 24 mm, 14 mm dia thumb wheel", (x, y, -8),
               (Shape("ball", "sphere", (4,), _STEEL), Shape("shaft", "cylinder", (4, 24), _STEEL,
                                                              (0, 0, 12)),
                Shape("wheel", "knurl", (14, 4), _BRASS, (0, 0, 23))), explode)
          for side, x, y, explode in (("left", -40, -36, (-25, -20, 40)),
                                      ("right", 40, -36, (25, -20, 40)),
                                      ("rear", 0, 40, (0, 30, 40)))),
        Part("approach_motor", "base", "approach motor",
             "The gear motor on the rear screw: it drives the automatic approach until the "
             "deflection setpoint is reached.", "20 mm dia x 30 mm", (0, 40, 17),
             (Shape("motor", "cylinder", (20, 30), _BLACK, (0, 0, 15)),), (0, 40, 110)),
        Part("head_plate", "head", "head plate",
             "The head's frame: it rests on the three screws and carries the optics and the "
             "cantilever holder.", "100 x 100 x 4 mm with a 36 x 36 mm window", (0, 0, 10),
             (Shape("front", "box", (100, 32, 4), _ALU, (0, -34, 0)),
              Shape("back", "box", (100, 32, 4), _ALU, (0, 34, 0)),
              Shape("left", "box", (32, 36, 4), _ALU, (-34, 0, 0)),
              Shape("right", "box", (32, 36, 4), _ALU, (34, 0, 0))), (0, 0, 35)),
        Part("cantilever_holder", "probe", "cantilever holder",
             "Holds the probe chip under a spring clip at the lever's tilt of 12 degrees, so "
             "that the tip, not the chip, touches the sample; slides into the head.",
             "24 x 14 x 3 mm block, 6 x 4 x 0.5 mm clip", (0, 0, 0),
             (Shape("block", "box", (24, 14, 3), _DARK, (-14.12, 0, 1.815)),
              Shape("clip", "box", (6, 4, 0.5), _STEEL, (-4.0, 0, 3.565))), (-45, 0, 20),
             axis=z_lever),
        Part("probe_chip", "probe", "probe chip",
             "The silicon chip with the cantilever and its tip: the laser is reflected off the "
             "back of the lever's free end.",
             "3.4 x 1.6 x 0.3 mm chip, lever 450 x 50 x 2 um, tip 15 um", (0, 0, 0),
             (Shape("chip", "box", (3.4, 1.6, 0.3), _SILICON, (-2.145, 0, 0.165)),
              Shape("lever", "box", (0.45, 0.05, 0.002), _SILICON, (-0.22, 0, 0.016)),
              Shape("tip", "cone", (0.008, 0.015), _SILICON, (0, 0, 0.0075), (0, 0, -1))),
             (-20, 0, 15), axis=z_lever),
        Part("laser_diode", "head", "laser diode",
             "The light source: a red laser diode (about 670 nm, about 1 mW) with its "
             "collimator, aimed at the lever through the focusing lens.",
             "5.6 mm TO can in a 9 mm dia x 14 mm tube", t(laser),
             (Shape("collimator", "cylinder", (9, 14), _DARK, (0, 0, 7)),
              Shape("can", "cylinder", (5.6, 3), _STEEL, (0, 0, 15.5)),
              Shape("aperture", "cylinder", (2, 0.2), _RED, (0, 0, -0.1))),
             (-40, 0, 110), axis=to_laser),
        Part("focusing_lens", "head", "focusing lens",
             "Focuses the laser to a spot of a few tens of micrometres on the lever's end.",
             "8 mm dia biconvex lens, f = 22 mm", t(lens),
             (Shape("glass", "ellipsoid", (8, 8, 2.4), _GLASS, opacity=0.6),
              Shape("mount", "tube", (11, 8.4, 2.5), _DARK)), (-25, -30, 70), axis=to_laser),
        Part("steering_mirror", "head", "steering mirror",
             "A first-surface mirror that folds the beam reflected by the lever onto the "
             "photodiode.", "10 x 10 x 1.5 mm mirror on a 12 x 12 x 3 mm mount", t(mirror),
             (Shape("mirror", "box", (10, 10, 1.5), _MIRROR, (0, 0, -0.75)),
              Shape("mount", "box", (12, 12, 3), _DARK, (0, 0, -3.0))), (30, 0, 85),
             axis=mirror_normal),
        Part("photodiode", "head", "four-quadrant photodiode",
             "Four photodiodes in a square: the sum measures the reflected power, "
             "top minus bottom the lever's bending (vertical deflection), left minus right "
             "its twist (lateral deflection).", "3 x 3 mm quadrant cell, 9 mm dia TO-5 can",
             t(photodiode),
             (Shape("cell", "quadrants", (3.0,), 0x4060a0),
              Shape("can", "cylinder", (9, 3), _STEEL, (0, 0, -1.6))), (65, 0, 75),
             axis=(-1.0, 0.0, 0.0)),
        Part("head_cover", "head", "head cover",
             "The head's housing: it keeps stray light out and the optics clean (made "
             "transparent here to show them).", "64 x 64 x 40 mm", (0, 0, 32),
             (Shape("cover", "box", (64, 64, 40), 0x5a6270),), (0, 0, 150), housing=True),
        _knob("laser_x", "knobs", "laser knob x",
              "Moves the laser spot along the lever (x), by tilting the laser and its lens.",
              (-24, -14, 52), (0, 0, 1), (-30, -20, 175)),
        _knob("laser_y", "knobs", "laser knob y",
              "Moves the laser spot across the lever (y).", (-24, 14, 52), (0, 0, 1),
              (-30, 20, 175)),
        _knob("detector_vertical", "knobs", "photodiode knob vertical",
              "Moves the photodiode up and down, to zero the vertical difference (T-B).",
              (32, -16, 36), (1, 0, 0), (90, -25, 70)),
        _knob("detector_lateral", "knobs", "photodiode knob lateral",
              "Moves the photodiode sideways, to zero the lateral difference (L-R).",
              (32, -16, 20), (1, 0, 0), (90, -25, 70)),
    )
    anchors = dict(laser=t(laser), lens=t(lens), lever_end=t(lever_end), mirror=t(mirror),
                   photodiode=t(photodiode))
    return Instrument("obd", "conventional AFM with optical beam deflection (MultiMode-like)",
                      parts, (145.0, -195.0, 90.0), (265.0, -415.0, 200.0), (0.0, 0.0, -45.0),
                      read_only(anchors),
                      ("laser", "lens", "lever_end", "mirror", "photodiode"),
                      ("lever_end", "photodiode"), ("probe_chip", (-0.445, 0.0, 0.017), 0.45),
                      tuple(p.name for p in parts if p.group in ("head", "probe", "knobs")))


def _educational() -> Instrument:
    tilt = math.radians(5.0)
    z_board = (math.sin(tilt), 0.0, math.cos(tilt))
    look = _unit([1.0, -1.0, 0.8])                   # from the tip towards the USB camera
    parts = (
        Part("base_plate", "base", "base plate",
             "An aluminium plate that carries everything; a heavy plate damps vibrations.",
             "200 x 160 x 10 mm", (0, 0, -44), (Shape("plate", "box", (200, 160, 10), _ALU),),
             (0, 0, -60)),
        Part("manual_stage", "stages", "manual x-y stage",
             "Two micrometer screws move the sample by millimetres to choose where to scan.",
             "60 x 60 x 18 mm, two 10 mm dia x 25 mm micrometers", (0, 0, -30),
             (Shape("stage", "box", (60, 60, 18), _STEEL),
              Shape("micrometer_x", "cylinder", (10, 25), _ALU, (-42.5, 0, 0), (1, 0, 0)),
              Shape("micrometer_y", "cylinder", (10, 25), _ALU, (0, -42.5, 0), (0, 1, 0))),
             (0, 0, -40)),
        Part("xy_scanner", "stages", "piezo x-y scanner",
             "A flexure stage pushed by two piezo stacks: it scans the sample under the tip "
             "(about 100 um range).", "40 x 40 x 12 mm", (0, 0, -15),
             (Shape("flexure", "box", (40, 40, 12), _ALU),
              Shape("stack_x", "box", (8, 4, 4), _ORANGE, (-22, 0, 0)),
              Shape("stack_y", "box", (4, 8, 4), _ORANGE, (0, -22, 0))), (0, 0, -22)),
        Part("sample_holder", "stages", "sample holder",
             "A magnetic post with the sample disc on it.", "10 mm dia x 8 mm post, 12 mm "
             "dia x 1 mm disc", (0, 0, 0),
             (Shape("post", "cylinder", (10, 8), _STEEL, (0, 0, -5)),
              Shape("sample", "cylinder", (12, 1), 0x505a78, (0, 0, -0.5))), (0, 0, -8)),
        Part("gantry", "frame", "gantry",
             "Two pillars and a bridge that hold the coarse approach above the sample.",
             "two 20 x 20 x 110 mm pillars, 30 x 150 x 12 mm bridge", (-40, 0, 16),
             (Shape("pillar_left", "box", (20, 20, 110), _ALU, (0, -60, 0)),
              Shape("pillar_right", "box", (20, 20, 110), _ALU, (0, 60, 0)),
              Shape("bridge", "box", (30, 150, 12), _ALU, (0, 0, 61))), (-90, 0, 0)),
        Part("stepper_motor", "approach", "stepper motor",
             "Turns the lead screw in small steps to lower the probe to the sample (coarse "
             "approach).", "42 x 42 x 34 mm (NEMA 17)", (-40, 0, 100),
             (Shape("motor", "box", (42, 42, 34), _BLACK),), (-100, 0, 60)),
        Part("lead_screw", "approach", "lead screw",
             "Converts the motor's steps into a vertical motion of the carriage.",
             "8 mm dia x 60 mm", (-40, 0, 41),
             (Shape("screw", "cylinder", (8, 60), _STEEL),), (-40, 0, 70)),
        Part("carriage", "approach", "carriage",
             "The slide block on the lead screw; its arm carries the z piezo and the probe.",
             "30 x 50 x 15 mm block, 18 x 20 x 6 mm arm", (-40, 0, 27.5),
             (Shape("block", "box", (30, 50, 15), _DARK),
              Shape("arm", "box", (18, 20, 6), _DARK, (9, 0, 0))), (-60, 0, 45)),
        Part("z_piezo", "approach", "z piezo",
             "A piezo stack that moves the probe up and down by micrometres: the feedback "
             "loop's actuator for the topography.", "10 x 10 x 20 mm", (-28, 0, 14),
             (Shape("stack", "box", (10, 10, 20), _ORANGE),), (-35, 0, 30)),
        Part("probe_board", "probe", "probe board",
             "The printed circuit board the active probe is glued and wire-bonded to; its "
             "tracks lead the bridge and heater currents to the connector.",
             "40 x 25 x 1.6 mm PCB, tilted 5 deg", (0, 0, 0),
             (Shape("pcb", "box", (40, 25, 1.6), _PCB, (-21.0, 0, 1.21)),), (-10, 0, 22),
             axis=z_board),
        Part("active_probe", "probe", "active probe",
             "A self-sensing, self-actuating cantilever chip: no laser; the lever's bending is "
             "read by a piezoresistive bridge and driven by an electrothermal (bimorph) heater.",
             "2 x 1 x 0.4 mm chip, lever 350 x 140 x 5 um, tip 10 um", (0, 0, 0),
             (Shape("chip", "box", (2.0, 1.0, 0.4), _SILICON, (-1.35, 0, 0.21)),
              Shape("lever", "box", (0.35, 0.14, 0.005), _SILICON, (-0.17, 0, 0.0125)),
              Shape("tip", "cone", (0.006, 0.01), _SILICON, (0, 0, 0.005), (0, 0, -1))),
             (-8, 0, 12), axis=z_board),
        Part("piezoresistor", "probe", "piezoresistive bridge",
             "U-shaped resistors at the lever's clamp, where the bending strain is largest: "
             "their resistance changes with the deflection (the sensor).",
             "two 60 x 20 um legs and a 20 x 100 um bar", (0, 0, 0),
             (Shape("leg_left", "box", (0.06, 0.02, 0.001), _GOLD, (-0.315, -0.04, 0.0155)),
              Shape("leg_right", "box", (0.06, 0.02, 0.001), _GOLD, (-0.315, 0.04, 0.0155)),
              Shape("bar", "box", (0.02, 0.1, 0.001), _GOLD, (-0.28, 0, 0.0155))),
             (0, 0, 4), axis=z_board),
        Part("heater", "probe", "electrothermal heater",
             "A resistor along the lever: its current heats the lever's bimorph layers, which "
             "bend it (the actuator).", "250 x 20 um stripe", (0, 0, 0),
             (Shape("stripe", "box", (0.25, 0.02, 0.001), _RED, (-0.18, 0, 0.0155)),),
             (0, 0, 7), axis=z_board),
        Part("bridge_amplifier", "electronics", "bridge amplifier",
             "Amplifies the piezoresistive bridge's small voltage close to the probe.",
             "30 x 20 x 5 mm board", (-24, 25, 6), (Shape("board", "box", (30, 20, 5), _PCB),),
             (0, 45, 20)),
        Part("controller", "electronics", "controller",
             "A microcontroller board with the converters: it runs the feedback loop, the "
             "scan and the approach and talks to the computer over USB.",
             "60 x 70 x 15 mm", (65, 40, -31.5),
             (Shape("board", "box", (60, 70, 15), _PCB),
              Shape("chip", "box", (14, 14, 2), _BLACK, (0, 0, 8.5))), (60, 40, 0)),
        Part("hv_amplifier", "electronics", "high-voltage amplifier",
             "Amplifies the controller's scan and z signals to the tens of volts the piezos "
             "need.", "60 x 40 x 25 mm", (65, -45, -26.5),
             (Shape("box", "box", (60, 40, 25), _DARK),), (60, -40, 0)),
        Part("usb_camera", "electronics", "USB camera",
             "A small microscope camera that watches the tip come down to the sample during "
             "the coarse approach.", "12 mm dia x 50 mm", tuple(30.0 * look),
             (Shape("body", "cylinder", (12, 50), _BLACK, (0, 0, 25)),
              Shape("lens", "cylinder", (8, 1), _GLASS, (0, 0, -0.5))),
             tuple(float(x) for x in 60.0 * look),
             axis=look),
        Part("ribbon_cable", "electronics", "ribbon cable",
             "Carries the bridge, heater and piezo signals between the probe side and the "
             "controller.", "3 mm dia bundle", (0, 0, 0),
             (Shape("cable", "wire", (3.0,), 0x707070,
                    points=((-38, 8, 4), (-50, 30, 30), (20, 72, 10), (55, 60, -22))),),
             (0, 60, -10)),
        Part("hood", "housing", "acrylic hood",
             "A clear cover against air currents, sound and dust (made more transparent here).",
             "210 x 170 x 160 mm", (0, 0, 41),
             (Shape("hood", "box", (210, 170, 160), _ACRYLIC),), (0, 0, 200), housing=True),
    )
    return Instrument("educational", "low-cost educational AFM with an active probe", parts,
                      (165.0, -215.0, 145.0), (285.0, -420.0, 250.0), (0.0, 0.0, 36.0),
                      lever=("active_probe", (-0.345, 0.0, 0.015), 0.35),
                      approach_parts=("carriage", "z_piezo", "probe_board", "active_probe",
                                      "piezoresistor", "heater", "bridge_amplifier"))


#: The two instruments, by key.
INSTRUMENTS = read_only({i.key: i for i in (_obd(), _educational())})


class _Canvas:
    """Forwards drawing to a visualizer node and remembers each node's colour and opacity, so a
    highlight can be undone, whoever drew the node (e.g. module (b)'s photodiode)."""

    def __init__(self, vis, colors: dict, rel: str = ""):
        self.vis, self.colors, self.rel = vis, colors, rel

    def __getitem__(self, name):
        return _Canvas(self.vis[name], self.colors, f"{self.rel}/{name}".lstrip("/"))

    def set_object(self, geometry, material=None):
        self.vis.set_object(geometry, material)
        if material is not None and getattr(material, "color", None) is not None:
            self.colors[self.rel] = (int(material.color), float(material.opacity))

    def set_transform(self, matrix=np.eye(4)):
        self.vis.set_transform(matrix)

    def set_property(self, key, value):
        self.vis.set_property(key, value)


def _material(color, opacity=1.0, see_through=False):
    if see_through:  # a housing the student looks through: it writes no depth, so its own
        # overlapping faces cannot hide each other in stripes (z-fighting) or hide the parts inside
        return g.MeshLambertMaterial(color=color, opacity=opacity, transparent=True,
                                     depthWrite=False)
    return g.MeshLambertMaterial(color=color, opacity=opacity, transparent=opacity < 1)


def _rgba(color: int, opacity: float) -> list:
    return [((color >> 16) & 255) / 255, ((color >> 8) & 255) / 255, (color & 255) / 255,
            float(opacity)]


def _draw_shape(canvas: _Canvas, shape: Shape, see_through: bool = False) -> None:
    """Draw ``shape`` at ``canvas[shape.name]`` (scene units from the shape's mm)."""
    s = np.asarray(shape.size, float) * _MM / SCENE_UNIT
    at = np.asarray(shape.at, float) * _MM / SCENE_UNIT
    node = canvas[shape.name]
    mat = _material(shape.color, shape.opacity, see_through)
    along_y = np.eye(4)
    along_y[:3, :3] = rotation_between([0.0, 1.0, 0.0], shape.axis)
    along_z = np.eye(4)
    along_z[:3, :3] = rotation_between([0.0, 0.0, 1.0], shape.axis)
    kind = shape.kind
    if kind == "box":
        node.set_object(g.Box(s.tolist()), mat)
        node.set_transform(translation(at))
    elif kind == "cylinder":
        node.set_object(g.Cylinder(s[1], radius=s[0] / 2), mat)
        node.set_transform(translation(at) @ along_y)
    elif kind == "cone":
        node.set_object(g.Cylinder(s[1], radiusTop=0.0, radiusBottom=s[0] / 2), mat)
        node.set_transform(translation(at) @ along_y)
    elif kind == "sphere":
        node.set_object(g.Sphere(s[0] / 2), mat)
        node.set_transform(translation(at))
    elif kind == "ellipsoid":
        node.set_object(g.Ellipsoid((s / 2).tolist()), mat)
        node.set_transform(translation(at) @ along_z)
    elif kind == "tube":
        v, f = hollow_cylinder_mesh(s[0] / 2, s[1] / 2, s[2])
        node.set_object(g.TriangularMeshGeometry(v, f), mat)
        node.set_transform(translation(at) @ along_z)
    elif kind == "knurl":
        v, f = prism_mesh(_knurl_outline(s[0] / 2), s[1])
        node.set_object(g.TriangularMeshGeometry(v, f), mat)
        node.set_transform(translation(at) @ along_z)
    elif kind == "quadrants":   # module (b)'s four-quadrant photodiode
        quadrant_photodiode(node, at, shape.axis, s[0])
    else:  # wire: module (b)'s tube
        Tube(node, color=shape.color, radius=s[0] / 2).set(
            np.asarray(shape.points, float) * _MM / SCENE_UNIT)


class InstrumentScene(SceneDisplay):
    """One of the two instruments in meshcat: named parts, housing, exploded view, knobs, beam.

    See the module docstring for the instruments and their assumed dimensions.

    Parameters
    ----------
    kind : {"obd", "educational"}
        Which instrument (:data:`INSTRUMENTS`).
    vis : meshcat.Visualizer, optional
        The root visualizer; by default a new 3D view's (:class:`~afmsmiler.scenes.SceneView`).
    path : str, optional
        Path of this scene in the viewer; default ``"afmsmiler/instrument/<kind>"``.
    camera : bool
        Place the camera to frame the assembled instrument and hide meshcat's grid and axes
        (they would cut through it at the sample's plane).
    housing_opacity : float
        The housing's opacity, 0 (hidden) to 1 (opaque).

    Attributes
    ----------
    instrument : Instrument
        What is drawn.
    fraction : float
        The exploded view's fraction (0 assembled, 1 exploded).
    housing_opacity : float
        The housing's opacity.
    knob_angles : dict
        Knob name -> its angle, rad.
    highlighted : dict
        Part name -> its highlight colour (0xRRGGBB).
    gap : float
        How far the coarse approach has lifted the probe above the sample, m
        (:meth:`set_gap`).
    beam : tuple or None
        ``(points, spots)`` (m) last drawn by :meth:`show_beam`.
    offset : ndarray
        The 4 x 4 shift of the whole instrument (scene units) that puts the camera's target
        (the instrument's middle, or a focused part) at meshcat's origin.

    Raises
    ------
    ValueError
        If ``kind`` or ``housing_opacity`` is not valid.

    Examples
    --------
    >>> [p.name for p in INSTRUMENTS["obd"].parts if p.knob]
    ['laser_x', 'laser_y', 'detector_vertical', 'detector_lateral']
    >>> scene = InstrumentScene("obd")  # doctest: +SKIP
    >>> scene.pick("steering_mirror")  # doctest: +SKIP
    'steering mirror: A first-surface mirror that folds the beam reflected by the lever ...'
    >>> scene.set_housing_opacity(0.2); scene.animate_explode()  # doctest: +SKIP
    """

    def __init__(self, kind: str = "obd", *, vis: meshcat.Visualizer | None = None,
                 path: str | None = None, camera: bool = True,
                 housing_opacity: float = PARAMETERS["housing_opacity"].default):
        check_choice("kind", kind, INSTRUMENTS)
        opacity = PARAMETERS["housing_opacity"].check(housing_opacity)
        self.instrument = INSTRUMENTS[kind]
        self._parts = {p.name: p for p in self.instrument.parts}
        self.root = scene_root(vis)
        self.path = path if path is not None else f"afmsmiler/instrument/{kind}"
        self.vis = self.root[self.path]
        self.vis.delete()
        self.fraction = 0.0
        self.gap = 0.0
        self.housing_opacity = 1.0
        self.knob_angles = {p.name: 0.0 for p in self.instrument.parts if p.knob}
        self.highlighted = {}
        self.beam = None
        self._colors = {}        # part name -> {node path under the part: (colour, opacity)}
        self._legs, self._spots = [], []
        self._beam_visible = True
        self._beam_hidden_near = False  # the camera is at the lever: the drawn beam would cover it
        for part in self.instrument.parts:
            canvas = _Canvas(self.vis[part.group][part.name], self._colors.setdefault(
                part.name, {}))
            for shape in part.shapes:
                _draw_shape(canvas, shape, see_through=part.housing)
            self._place(part)
        self.set_housing_opacity(opacity)
        if self.instrument.beam:
            self.show_beam(*self.nominal_beam())
        self.offset = np.eye(4)
        if camera:
            self.focus()
            show_helpers(self.root, grid=False, axes=False)

    # -- parts and their descriptions -----------------------------------------------------------
    def parts(self) -> tuple[str, ...]:
        """The names of the instrument's parts, in drawing order."""
        return tuple(self._parts)

    def part(self, name: str) -> Part:
        """The description of part ``name`` (a :class:`Part`).

        Parameters
        ----------
        name : str
            One of :meth:`parts`.

        Raises
        ------
        ValueError
            If there is no such part (the message lists the valid names).
        """
        check_choice("part", name, self._parts)
        return self._parts[name]

    def describe(self, name: str) -> str:
        """``"label: description (dimensions)"`` of part ``name``, for the notebook.

        Parameters
        ----------
        name : str
            One of :meth:`parts`.

        Raises
        ------
        ValueError
            If there is no such part.
        """
        p = self.part(name)
        return f"{p.label}: {p.description} ({p.dimensions})"

    def node_path(self, name: str) -> str:
        """The meshcat path of part ``name`` (e.g. ``"/afmsmiler/instrument/obd/head/lens"``).

        Parameters
        ----------
        name : str
            One of :meth:`parts`.
        """
        p = self.part(name)
        return self.vis[p.group][p.name].path.lower()

    def table(self) -> tuple[tuple[str, str, str, str], ...]:
        """Rows ``(name, label, description, dimensions)``, one per part."""
        return tuple((p.name, p.label, p.description, p.dimensions)
                     for p in self.instrument.parts)

    def table_html(self) -> str:
        """:meth:`table` as an HTML table (the notebook shows it in a widget)."""
        import html
        rows = "".join(f"<tr><td><code>{html.escape(n)}</code></td><td>{html.escape(lab)}</td>"
                       f"<td>{html.escape(d)}</td><td>{html.escape(dim)}</td></tr>"
                       for n, lab, d, dim in self.table())
        return ("<table><tr><th>part</th><th>name</th><th>what it does</th>"
                f"<th>dimensions</th></tr>{rows}</table>")

    # -- transforms -----------------------------------------------------------------------------
    def transform(self, name: str, fraction: float | None = None) -> np.ndarray:
        """The 4 x 4 transform (scene units) of part ``name`` at an exploded-view fraction.

        Parameters
        ----------
        name : str
            One of :meth:`parts`.
        fraction : float, optional
            0 (assembled) to 1 (exploded); default the current :attr:`fraction`.

        Returns
        -------
        ndarray
            translation(position + fraction x explode (+ the approach's lift)) @
            rotation(axis) @ the knob's turn.
        """
        p = self.part(name)
        f = self.fraction if fraction is None else PARAMETERS["explode_fraction"].check(
            fraction)
        rot = np.eye(4)
        rot[:3, :3] = p.rotation
        angle = self.knob_angles.get(name, 0.0)
        turn = np.eye(4)
        turn[:2, :2] = [[math.cos(angle), -math.sin(angle)], [math.sin(angle), math.cos(angle)]]
        origin = (p.position + f * p.explode_distance * p.explode_direction) / SCENE_UNIT
        if name in self.instrument.approach_parts:
            origin[2] += self.gap / SCENE_UNIT
        return translation(origin) @ rot @ turn

    def _place(self, part: Part) -> None:
        self.vis[part.group][part.name].set_transform(self.transform(part.name))

    def explode(self, fraction: float) -> None:
        """Move every part between assembled (0) and exploded (1) along its own direction.

        The beam of :meth:`show_beam` is drawn for the assembled instrument, so it is hidden
        unless ``fraction`` is 0.

        Parameters
        ----------
        fraction : float
            0 to 1 (:data:`PARAMETERS` ``["explode_fraction"]``).

        Raises
        ------
        ValueError
            If ``fraction`` is outside [0, 1].
        """
        self.fraction = PARAMETERS["explode_fraction"].check(fraction)
        for part in self.instrument.parts:
            self._place(part)
        self._show_beam_group(self.fraction == 0.0)

    def set_gap(self, gap: float) -> None:
        """Lift the probe (and what the coarse approach moves with it) ``gap`` above the
        sample: 0 is in contact. The beam of :meth:`show_beam` moves with the head.

        Parameters
        ----------
        gap : float
            Tip-sample distance, m (:data:`PARAMETERS` ``["approach_gap"]``, 0 to 10 mm).

        Raises
        ------
        ValueError
            If ``gap`` is out of range.
        """
        self.gap = PARAMETERS["approach_gap"].check(gap)
        for name in self.instrument.approach_parts:
            self._place(self._parts[name])
        if self.instrument.beam:
            self.vis["beam"].set_transform(translation([0.0, 0.0, self.gap / SCENE_UNIT]))

    def animate_explode(self, frames: int = DEFAULTS["frames"], *, fps: int = DEFAULTS["fps"],
                        back: bool = True, repetitions: int = 1,
                        play: bool = True) -> Animation:
        """Animate the exploded view: assembled -> exploded (-> assembled if ``back``).

        The fraction eases in and out (``(1 - cos(pi k / frames)) / 2`` at frame k); the parts
        end where the animation ends, and :attr:`fraction` says so. The beam is hidden (call
        ``explode(0)`` to see it again).

        Parameters
        ----------
        frames : int
            Frames one way, 2 to ``LIMITS["frames"]`` (twice as many with ``back``).
        fps : int
            Frames per second, 1 to 120.
        back : bool
            Come back to assembled.
        repetitions : int
            How many times the viewer plays it, 1 to 100.
        play : bool
            Start playing at once.

        Returns
        -------
        meshcat.animation.Animation
            The animation sent to the viewer.

        Raises
        ------
        ValueError
            If a number is out of range or the animation would send more than
            ``LIMITS["animation_transforms"]`` transforms.
        """
        frames = check_integer("frames", frames, 2, LIMITS["frames"])
        fps = check_integer("fps", fps, 1, 120)
        repetitions = check_integer("repetitions", repetitions, 1, 100)
        total = 2 * frames if back else frames
        n = len(self.instrument.parts) * (total + 1)
        if n > LIMITS["animation_transforms"]:
            raise ValueError(f"frames must make at most {LIMITS['animation_transforms']} "
                             f"transforms, got frames={frames}: {n}")
        anim = Animation(default_framerate=fps)
        for k in range(total + 1):
            f = self.fractions(frames, back)[k]
            with anim.at_frame(self.vis, k) as frame:
                for p in self.instrument.parts:
                    frame[p.group][p.name].set_transform(self.transform(p.name, f))
        self.explode(0.0 if back else 1.0)
        self._show_beam_group(False)
        self.root.set_animation(anim, play=bool(play), repetitions=repetitions)
        return anim

    @staticmethod
    def fractions(frames: int, back: bool = True) -> np.ndarray:
        """The exploded-view fraction at each frame of :meth:`animate_explode`.

        Parameters
        ----------
        frames : int
            Frames one way, 2 to ``LIMITS["frames"]``.
        back : bool
            Come back to assembled.

        Returns
        -------
        ndarray
            ``frames + 1`` values from 0 to 1 (``2 frames + 1``, back to 0, with ``back``).
        """
        frames = check_integer("frames", frames, 2, LIMITS["frames"])
        k = np.arange((2 if back else 1) * frames + 1)
        return 0.5 - 0.5 * np.cos(np.pi * k / frames)

    # -- housing and highlighting ---------------------------------------------------------------
    def set_housing_opacity(self, opacity: float) -> None:
        """Make the housing (the parts with ``housing=True``) transparent: 0 hides it.

        Parameters
        ----------
        opacity : float
            0 (hidden) to 1 (opaque) (:data:`PARAMETERS` ``["housing_opacity"]``).

        Raises
        ------
        ValueError
            If ``opacity`` is outside [0, 1].
        """
        self.housing_opacity = PARAMETERS["housing_opacity"].check(opacity)
        for part in self.instrument.parts:
            if part.housing:
                self._paint(part.name)
                self.vis[part.group][part.name].set_property("visible",
                                                             self.housing_opacity > 0)

    def _paint(self, name: str) -> None:
        part = self._parts[name]
        node = self.vis[part.group][part.name]
        for rel, (color, opacity) in self._colors[name].items():
            if part.housing:
                opacity = self.housing_opacity
            color = self.highlighted.get(name, color)
            target = node
            for piece in rel.split("/"):
                target = target[piece]
            target.set_property("color", _rgba(color, opacity))

    def highlight(self, name: str, color: int = DEFAULTS["highlight"]) -> None:
        """Paint part ``name`` in ``color`` until :meth:`unhighlight`.

        Parameters
        ----------
        name : str
            One of :meth:`parts`.
        color : int
            0xRRGGBB, 0 to 0xffffff.

        Raises
        ------
        ValueError
            If there is no such part or ``color`` is not a colour.
        """
        self.part(name)
        self.highlighted[name] = check_integer("color", color, 0, 0xFFFFFF)
        self._paint(name)

    def unhighlight(self, name: str | None = None) -> None:
        """Give part ``name`` (every highlighted part if None) its own colours back.

        Parameters
        ----------
        name : str, optional
            One of :meth:`parts`.

        Raises
        ------
        ValueError
            If there is no such part.
        """
        names = list(self.highlighted) if name is None else [self.part(name).name]
        for n in names:
            if self.highlighted.pop(n, None) is not None:
                self._paint(n)

    def pick(self, name: str, *, focus: bool = False) -> str:
        """Pick part ``name`` (the notebook's part menu calls this): highlight it alone, bring
        the camera to it if ``focus``, and return its :meth:`describe` text.

        meshcat reports no mouse picks to the kernel, so a part is picked from a menu of
        :meth:`parts`.

        Parameters
        ----------
        name : str
            One of :meth:`parts`.
        focus : bool
            Also :meth:`focus` the camera on it (at ``DEFAULTS["focus_distance"]``).

        Returns
        -------
        str
            ``"label: description (dimensions)"``.

        Raises
        ------
        ValueError
            If there is no such part.
        """
        text = self.describe(name)
        self.unhighlight()
        self.highlight(name)
        if focus:
            self.focus(name)
        return text

    def colors(self, name: str) -> dict:
        """Node (under the part) -> ``(0xRRGGBB, opacity)`` as part ``name`` was drawn.

        Parameters
        ----------
        name : str
            One of :meth:`parts`.
        """
        self.part(name)
        return dict(self._colors[name])

    # -- hooks for the laser-alignment model ----------------------------------------------------
    def knobs(self) -> tuple[str, ...]:
        """The names of the knobs (parts :meth:`turn_knob` turns)."""
        return tuple(self.knob_angles)

    def turn_knob(self, name: str, angle: float) -> None:
        """Turn knob ``name`` to ``angle`` about its axis (right-handed), in place.

        Parameters
        ----------
        name : str
            One of :meth:`knobs`.
        angle : float
            Angle from its rest position, rad (:data:`PARAMETERS` ``["knob_angle"]``).

        Raises
        ------
        ValueError
            If there is no such knob or ``angle`` is out of range.
        """
        check_choice("knob", name, self.knob_angles)
        self.knob_angles[name] = PARAMETERS["knob_angle"].check(angle)
        self._place(self._parts[name])

    def set_knobs(self, **angles) -> None:
        """Turn several knobs at once, e.g. ``set_knobs(laser_x=0.5, laser_y=-0.2)`` (rad).

        All names and angles are checked before any knob turns.

        Parameters
        ----------
        **angles
            Knob name (one of :meth:`knobs`) -> angle, rad.

        Raises
        ------
        ValueError
            If a knob does not exist or an angle is out of range.
        """
        checked = {check_choice("knob", name, self.knob_angles):
                   PARAMETERS["knob_angle"].check(angle) for name, angle in angles.items()}
        for name, angle in checked.items():
            self.knob_angles[name] = angle
            self._place(self._parts[name])

    @property
    def anchors(self) -> dict:
        """Name -> position (m, scene frame: origin at the tip, z up) of the drawn optics:
        ``laser`` (the laser's exit), ``lens``, ``lever_end``, ``mirror``, ``photodiode``
        (empty for an instrument without a laser)."""
        return {k: np.asarray(v, float) * _MM for k, v in self.instrument.anchors_mm.items()}

    def lever_point(self, x: float, y: float = 0.0) -> np.ndarray:
        """Where a point on the lever's top face is in the scene frame (m, assembled, in
        contact: the frame of :meth:`show_beam`'s points).

        For the alignment model's spot on the lever: module (a)'s coordinates, ``x`` from the
        clamp towards the free end, ``y`` across the lever (to the left seen from the clamp).

        Parameters
        ----------
        x : float
            Distance from the clamp along the lever, m (0 at the clamp, the lever's length at
            its free end; outside the lever is allowed: a spot may miss it), |x| <= 0.01 m.
        y : float
            Distance from the lever's centre line, m, |y| <= 0.01 m.

        Returns
        -------
        ndarray, shape (3,)
            The point, m.

        Raises
        ------
        ValueError
            If a coordinate is not finite or too far from the lever.
        """
        x = check_range("x", x, -0.01, 0.01, "m")
        y = check_range("y", y, -0.01, 0.01, "m")
        part, clamp, _ = self.instrument.lever
        p = self._parts[part]
        local = np.asarray(clamp, float) * _MM + [x, y, 0.0]
        return p.position + p.rotation @ local

    def photodiode_point(self, vertical: float, lateral: float = 0.0) -> np.ndarray:
        """Where a point on the photodiode's face is in the scene frame (m, assembled).

        For the alignment model's spot on the detector: the face is the plane x = const
        (facing the mirror), ``vertical`` is along +z (towards the top quadrants) and
        ``lateral`` along +y (towards the left quadrants, seen along the incoming beam), from
        the detector's centre.

        Parameters
        ----------
        vertical, lateral : float
            Offsets from the centre, m, each within +-0.01 m.

        Returns
        -------
        ndarray, shape (3,)
            The point, m.

        Raises
        ------
        ValueError
            If the instrument has no photodiode or an offset is out of range.
        """
        if "photodiode" not in self.instrument.anchors_mm:
            raise ValueError(f"the {self.instrument.title} has no photodiode")
        vertical = check_range("vertical", vertical, -0.01, 0.01, "m")
        lateral = check_range("lateral", lateral, -0.01, 0.01, "m")
        return self.anchors["photodiode"] + [0.0, lateral, vertical]

    def show_alignment(self, spot_on_lever, spot_on_detector, *, reflected: bool = True,
                       knobs=None) -> np.ndarray:
        """Draw the beam for the alignment model's spots, and turn the knobs to its angles.

        The beam runs laser -> lens -> the spot on the lever -> the mirror's centre -> the spot
        on the photodiode (schematic between the drawn optics; the spots are where the model
        puts them), e.g. ``scene.show_alignment(s.spot_on_lever, s.spot_on_detector,
        knobs=s.knobs)`` for a model's signals ``s``.

        Parameters
        ----------
        spot_on_lever : (float, float)
            ``(x, y)`` on the lever in m (:meth:`lever_point`).
        spot_on_detector : (float, float)
            ``(vertical, lateral)`` on the photodiode in m (:meth:`photodiode_point`).
        reflected : bool
            False when no light comes back (the spot missed the lever): the beam ends on the
            lever's plane.
        knobs : mapping, optional
            Knob name -> angle in rad, for :meth:`set_knobs`.

        Returns
        -------
        ndarray, shape (N, 3)
            The beam's points, m.

        Raises
        ------
        ValueError
            If the instrument has no laser, or a spot, knob or angle is not valid.
        """
        lever = check_array("spot_on_lever", spot_on_lever, "m", ndim=1, size=2)
        detector = check_array("spot_on_detector", spot_on_detector, "m", ndim=1, size=2)
        if "photodiode" not in self.instrument.anchors_mm:
            raise ValueError(f"the {self.instrument.title} has no laser beam")
        a = self.anchors
        on_lever = self.lever_point(*lever)
        on_detector = self.photodiode_point(*detector)
        points = [a["laser"], a["lens"], on_lever]
        spots = [on_lever]
        if reflected:
            points += [a["mirror"], on_detector]
            spots.append(on_detector)
        if knobs is not None:
            self.set_knobs(**dict(knobs))
        self.show_beam(np.array(points), np.array(spots))
        return np.array(points)

    def nominal_beam(self) -> tuple[np.ndarray, np.ndarray]:
        """The aligned beam through the drawn optics' centres: ``(points, spots)`` in m.

        Raises
        ------
        ValueError
            If the instrument has no laser.
        """
        if not self.instrument.beam:
            raise ValueError(f"the {self.instrument.title} has no laser beam")
        a = self.anchors
        return (np.array([a[k] for k in self.instrument.beam]),
                np.array([a[k] for k in self.instrument.spots]))

    def show_beam(self, points, spots=(), *, spot_radius: float = DEFAULTS["spot_radius"]):
        """Draw the laser beam through ``points`` and a spot at each of ``spots``, in place.

        For the laser-alignment model: it traces the beam (laser, lens, lever, mirror,
        photodiode, or wherever it goes) and gives the points; the scene only joins them.

        Parameters
        ----------
        points : array_like, shape (N, 3)
            The beam's corners in m, scene frame (origin at the tip, z up, lever along +x; see
            :attr:`anchors`), 2 <= N <= ``LIMITS["beam_points"]``, within ``LIMITS["reach"]``
            of the tip.
        spots : array_like, shape (M, 3)
            Spot centres in m (on the lever, on the photodiode), M <= ``LIMITS["spots"]``.
        spot_radius : float
            Drawn spot radius, m, > 0 and <= ``LIMITS["spot_radius"]``.

        Raises
        ------
        ValueError
            If the instrument has no laser, or a shape, value or count is out of range.
        """
        if not self.instrument.beam:
            raise ValueError(f"the {self.instrument.title} has no laser beam (it senses with "
                             "a piezoresistive bridge)")
        pts = self._points("points", points, 2, LIMITS["beam_points"])
        sp = (np.zeros((0, 3)) if len(np.atleast_1d(np.asarray(spots, dtype=object))) == 0
              else self._points("spots", spots, 1, LIMITS["spots"]))
        radius = check_positive("spot_radius", spot_radius, "m")
        if radius > LIMITS["spot_radius"]:
            raise ValueError(f"spot_radius must be <= {LIMITS['spot_radius']} m, got {radius}")
        beam = self.vis["beam"]
        while len(self._legs) < len(pts) - 1:
            self._legs.append(Segment(beam[f"leg{len(self._legs):02d}"],
                                      color=DEFAULTS["beam_color"],
                                      radius=DEFAULTS["beam_radius"] / SCENE_UNIT, opacity=0.9))
        for i, leg in enumerate(self._legs):
            if i < len(pts) - 1:
                leg.set(pts[i] / SCENE_UNIT, pts[i + 1] / SCENE_UNIT)
            else:
                _show(leg, False)
        while len(self._spots) < len(sp):
            node = beam[f"spot{len(self._spots)}"]
            sphere(node, 1.0, color=0xff0000, opacity=0.85)
            self._spots.append([node, True])
        scale = np.diag([radius / SCENE_UNIT] * 3 + [1.0])
        for i, entry in enumerate(self._spots):
            node, visible = entry
            if i < len(sp):
                node.set_transform(translation(sp[i] / SCENE_UNIT) @ scale)
            if visible != (i < len(sp)):
                node.set_property("visible", i < len(sp))
                entry[1] = i < len(sp)
        self.beam = (pts, sp)
        self._show_beam_group(self.fraction == 0.0)

    @staticmethod
    def _points(name, values, low, high):
        pts = check_array(name, values, "m", ndim=2)
        if pts.shape[1] != 3 or not low <= pts.shape[0] <= high:
            raise ValueError(f"{name} must have shape (N, 3) with {low} <= N <= {high}, got "
                             f"{pts.shape}")
        reach = float(np.abs(pts).max())
        if reach > LIMITS["reach"]:
            raise ValueError(f"{name} must be in m within {LIMITS['reach']} m of the tip, got a "
                             f"coordinate of {reach:g} (mm given as m?)")
        return pts

    def _show_beam_group(self, visible: bool) -> None:
        visible = visible and not self._beam_hidden_near
        if self.instrument.beam and visible != self._beam_visible:
            self.vis["beam"].set_property("visible", bool(visible))
            self._beam_visible = bool(visible)

    # -- camera and export ----------------------------------------------------------------------
    def focus(self, name: str | None = None, distance: float = DEFAULTS["focus_distance"],
              ) -> None:
        """Bring the camera to part ``name``: the instrument is shifted so that the part is at
        the camera's target (the origin) and the camera is ``distance`` away, from the front
        right and above (``DEFAULTS["focus_direction"]``). ``focus()`` goes back to the whole
        instrument.

        Parameters
        ----------
        name : str, optional
            One of :meth:`parts`; None frames the whole instrument.
        distance : float
            Camera distance from the part, m, > 0 and <= 1.

        Raises
        ------
        ValueError
            If there is no such part or ``distance`` is out of range.
        """
        distance = check_positive("distance", distance, "m")
        if distance > 1.0:
            raise ValueError(f"distance must be <= 1 m, got {distance}")
        view = np.asarray(self.instrument.camera_mm, float) * _MM
        self._hide_beam_near(name is not None and name == self.instrument.lever[0])
        if name is None:
            self._shift(np.asarray(self.instrument.centre_mm, float) * _MM / SCENE_UNIT)
            set_camera(self.root, list(view / SCENE_UNIT))
            fit_camera(self.vis, margin=1.0)
            self._label_groups()
            return
        self._shift(self.transform(name)[:3, 3])
        set_camera(self.root, list(_unit(DEFAULTS["focus_direction"]) * distance / SCENE_UNIT))
        part = self.part(name)
        # in a 3D view the part fills the view from that direction (a 450 um lever on its 3 mm
        # chip was a few pixels wide at a fixed distance), and its pieces are labelled
        fit_camera(self.vis[part.group][part.name], margin=1.15)
        self._label({f"{part.label}: {s.name}" if len(part.shapes) > 1 else part.label:
                     (self.offset @ self.transform(name) @ np.append(
                         np.asarray(s.at, float) * _MM / SCENE_UNIT, 1.0))[:3]
                     for s in part.shapes if s.kind != "wire"})

    def _hide_beam_near(self, hide: bool) -> None:
        """Hide the drawn laser beam while the camera is at the lever's part, and say why."""
        if not self.instrument.beam or hide == self._beam_hidden_near:
            return
        self._beam_hidden_near = hide
        self._show_beam_group(self.fraction == 0.0)
        view = self.view
        if view is not None:
            radius = DEFAULTS["beam_radius"] * 1e3
            view.set_legend_part(self.vis["beam"].path.lower(), None if not hide else (
                f"laser beam not drawn here: drawn {2 * radius:g} mm thick (schematic), it would "
                f"cover "
                f"the 50 um wide lever of the {self.part(self.instrument.lever[0]).label}"))

    def _label(self, labels: dict) -> None:
        view = self.view
        if view is not None:
            view.set_labels({k: [float(x) for x in v] for k, v in labels.items()})

    def _label_groups(self) -> None:
        """Label each group of parts (head, scanner, probe, ...) at the middle of its parts."""
        groups = {}
        for p in self.instrument.parts:
            if p.group != "housing":
                groups.setdefault(p.group, []).append((self.offset @ self.transform(p.name))[:3, 3])
        self._label({g: np.mean(points, axis=0) for g, points in groups.items()})

    def _shift(self, centre) -> None:
        """Shift the instrument so that ``centre`` (scene units) is at the camera's target."""
        self.offset = translation(-np.asarray(centre, float))
        self.vis.set_transform(self.offset)

    def exploded_view(self) -> None:
        """Explode the instrument fully and move the camera back to see all of it."""
        self.explode(1.0)
        self._shift(np.asarray(self.instrument.centre_mm, float) * _MM / SCENE_UNIT)
        set_camera(self.root, list(np.asarray(self.instrument.exploded_camera_mm) * _MM
                                   / SCENE_UNIT))

    def static_html(self) -> str:
        """The scene as one self-contained HTML page (meshcat's ``static_html``), for the book."""
        return _static_html(self.root)

    def save_static_html(self, path) -> str:
        """Write :meth:`static_html` to ``path`` (an HTML file in an existing folder).

        Parameters
        ----------
        path : str or os.PathLike
            The file to write.

        Returns
        -------
        str
            The path written.
        """
        return _save_static_html(path, self.root)
