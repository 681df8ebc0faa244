"""Module (e)'s two instruments as a pure model of their assembly: parts, sizes, places, groups.

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
scene's methods take SI (metres, radians). The lever itself (450 um, the optics model's) is drawn to scale too, so it is a
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

This module is data and geometry only (numpy; no meshcat): the parts (:class:`Part`, each made
of :class:`Shape` primitives), where each sits assembled, how it moves in the exploded view
(its disassembly direction and distance), its group and whether it is housing or a knob, and
per instrument the optics' anchors, the cameras that frame it and the parts the coarse approach
moves (:class:`Instrument`, :data:`INSTRUMENTS`). :mod:`afmsmiler.scenes.instrument` draws it.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..geometry import reflect, rotation_between
from ..parameters import read_only, unit_scale
from ..validation import check_choice

__all__ = ["Shape", "Part", "Instrument", "INSTRUMENTS", "SHAPE_KINDS"]

_MM = 1.0 / unit_scale("mm")   # metres per millimetre (the dimension tables are in mm)

#: The kinds of primitive a :class:`Shape` can be.
SHAPE_KINDS = ("box", "cylinder", "cone", "sphere", "ellipsoid", "tube", "knurl", "quadrants", "wire")


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
        check_choice("kind", self.kind, SHAPE_KINDS)


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
        :meth:`afmsmiler.scenes.instrument.InstrumentScene.set_housing_opacity`).
    knob : bool
        A knob that :meth:`afmsmiler.scenes.instrument.InstrumentScene.turn_knob` turns about
        ``axis``.
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
