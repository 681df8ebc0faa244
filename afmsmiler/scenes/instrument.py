"""Module (e)'s two instruments in 3D: named parts that come apart, a housing that fades, knobs.

The scene draws the pure model of the instruments' assembly (:mod:`afmsmiler.instrument.assembly`:
the parts, their sizes, places, groups and disassembly; the assumed dimensions are listed there)
with meshcat primitives and the meshes of :mod:`afmsmiler.scenes.meshes`. The origin is the
probe's tip, z up; everything is drawn to scale at **1 scene unit = 1 cm**
(:data:`SCENE_UNIT`); the public methods take SI (metres, radians).

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
import meshcat
import meshcat.geometry as g
import numpy as np
from meshcat.animation import Animation
from meshcat.transformations import quaternion_from_matrix

from ..instrument.assembly import INSTRUMENTS, Instrument, Part, Shape
from ..parameters import Parameter, read_only, unit_scale
from ..validation import (check_array, check_choice, check_integer, check_positive,
                          check_range)
from .animation import set_translations
from .camera import set_camera, show_helpers
from .meshes import hollow_cylinder_mesh, knurl_outline, prism_mesh
from .view import fit_camera
from .shapes import Segment, Tube, _show, sphere
from .transducers import quadrant_photodiode
from .transforms import rotation_between, translation
from .viewer import SceneDisplay, save_static_html as _save_static_html, scene_root, static_html as _static_html

__all__ = ["SCENE_UNIT", "PARAMETERS", "LIMITS", "DEFAULTS", "Shape", "Part", "Instrument",
           "INSTRUMENTS", "InstrumentScene", "hollow_cylinder_mesh", "prism_mesh"]

#: Metres per scene unit (1 scene unit = 1 cm).
SCENE_UNIT = 0.01
_MM = 1.0 / unit_scale("mm")   # metres per millimetre (the model's tables are in mm)

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
        v, f = prism_mesh(knurl_outline(s[0] / 2), s[1])
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
        f = self.fractions(frames, back)[:, None]
        k = np.arange(total + 1)
        for p in self.instrument.parts:  # each part's pose is linear in the fraction
            start, end = self.transform(p.name, 0.0), self.transform(p.name, 1.0)
            positions = start[:3, 3] + f * (end[:3, 3] - start[:3, 3])
            w, x, y, z = quaternion_from_matrix(start)  # the part turns not while it moves
            set_translations(anim, self.vis[p.group][p.name], k, positions,
                             np.tile([x, y, z, w], (k.size, 1)))
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
        look = np.asarray(DEFAULTS["focus_direction"], float)
        set_camera(self.root, list(look / np.linalg.norm(look) * distance / SCENE_UNIT))
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
