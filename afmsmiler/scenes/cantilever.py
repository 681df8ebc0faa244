"""The 3D view of module (a): a cantilever drawn as a deformed beam colored by bending stress.

Scale: **1 scene unit = 100 um** (:data:`SCENE_UNIT`), so a 450 um lever is 4.5 units long. The
lever lies along +x from its clamp, z is up, and the camera looks at the x-z plane from the -y
side, so the near side face shows the stress through the thickness (compression blue, tension
red, the neutral plane white). The deflection is drawn exaggerated (default x100); lengths along
x, the width and the thickness are true to scale. The whole drawing is shifted by -L/2 along x so
that the camera, which looks at the origin, sees the lever centred.

Everything is drawn once by :class:`CantileverScene` and then updated in place
(:meth:`CantileverScene.update` replaces the beam mesh and moves the tip and arrow with
``set_transform``), in its own 3D view (:class:`~afmsmiler.scenes.SceneView`).
The scene draws the model's result, a :class:`~afmsmiler.cantilever.Bending` (deflection, slope
and stress on a grid), and computes no physics itself: a panel runs the model once per slider move
and hands the same result to its figures and to this scene.
"""
from __future__ import annotations

import math

import meshcat
import meshcat.geometry as g
import numpy as np
from meshcat.animation import Animation

from ..cantilever import EXAGGERATION, Bending, Cantilever, check_modes
from ..parameters import read_only, unit_scale
from ..validation import check_flag, check_instance, check_integer, check_positive, check_range
from .camera import camera_ndc, readable_width, set_camera, show_helpers
from .colors import ColorScale, nice_ceil
from .legends import ColorLegend, TextPlate
from .meshes import beam_mesh
from .shapes import Arrow, cone
from .transforms import check_visualizer, translation
from .viewer import SceneDisplay, scene_root, static_html as _static_html

__all__ = ["SCENE_UNIT", "DEFAULTS", "LIMITS", "CantileverScene", "mode_animation"]

#: Metres per scene unit (1 scene unit = 100 um).
SCENE_UNIT = 100e-6

#: Defaults of the scene, in one place.
DEFAULTS = read_only(dict(
    exaggeration=EXAGGERATION.default,  # deflection drawn x100
    tip_height=12e-6,        # m, the cone under the free end
    tip_radius=4e-6,         # m, radius of its base
    force_per_unit=100e-9,   # N drawn as one scene unit of arrow
    stress_floor=1e-3,       # MPa, smallest color limit (for F = 0)
    mode_segments=30,        # rigid segments per animated mode beam
    mode_frames=48,          # frames per period of the mode animation
    mode_fps=24,             # frames per second of the mode animation
    mode_amplitude=0.15,     # animated tip amplitude as a fraction of L
    max_drawn_tip=0.5,       # the drawn tip deflection is capped at this fraction of L
    camera_direction=(0.0, -0.914, 0.406),  # from the lever's centre, slightly from above
    chip_in_view=0.7,        # scene units of the chip kept in view behind the clamp
    min_distance=1.2,        # scene units, the closest camera (short levers)
    reframe_ratio=1.3,       # re-aim the camera when L changes by more than this factor
    frame_margin=0.95,       # ... or when the free end leaves this inner part of the view
    aspect=1.5,              # width / height of the view framed for (1200 x 800 pixels)
))

#: Largest drawings the viewer is sent (each takes about a second or less): beam-mesh vertices
#: (stations x levels of the Bending drawn), and segments x (frames + 1) x modes of an animation.
LIMITS = read_only(dict(mesh_points=200_000, animation_transforms=20_000))

_STRESS_LABEL = "bending stress"
_STRESS_UNIT = "MPa"
_MPA = unit_scale(_STRESS_UNIT, "Pa")  # MPa per Pa
_KHZ = unit_scale("kHz", "Hz")
_BEAM_MATERIAL_ARGS = dict(vertexColors=True)
_MODE_COLORS = (0x1f77b4, 0xff7f0e, 0x2ca02c)


class CantileverScene(SceneDisplay):
    """A cantilever in meshcat: stress-colored deformed beam, tip, force arrow and legend.

    Parameters
    ----------
    bending : Bending
        The model's result to draw first (:meth:`Cantilever.bending`: the lever, the end force
        and the deflection, slope and stress on its grid, drawn as the mesh's stations and levels).
    exaggeration : float
        Factor applied to the drawn deflection (1 to 10^6; default x100).
    vis : meshcat.Visualizer, optional
        The root visualizer; by default a new 3D view's (:class:`~afmsmiler.scenes.SceneView`).
    path : str
        Path of this scene in the viewer.
    force_per_unit : float
        Force in N drawn as one scene unit (100 um) of arrow, in [1e-15, 1e3].
    stress_limit : float, optional
        Fixed color limit in Pa; by default the next round number (1, 2, 5 x 10^n MPa) above
        the largest stress, so the legend changes only when the stress crosses one.
    camera : bool
        Place the camera to look at the lever's side face.

    Raises
    ------
    TypeError
        If ``bending`` is not a :class:`~afmsmiler.cantilever.Bending`.
    ValueError
        For an argument outside its range, or a grid of more than ``LIMITS["mesh_points"]``.

    Notes
    -----
    One scene unit is 100 um (:data:`SCENE_UNIT`). Drawn deflection = exaggeration x z(x), except
    that the exaggeration actually used (:attr:`drawn_exaggeration`) is lowered when the drawn
    tip would move by more than ``max_drawn_tip`` x L (soft levers under large forces), so the
    lever stays in view and does not look stretched;
    the arrow's length is force / ``force_per_unit`` scene units, drawn from below the tip apex
    when the force pushes the tip up (a repulsive sample), from the apex downwards when it pulls.
    """

    def __init__(self, bending: Bending, *,
                 exaggeration: float = DEFAULTS["exaggeration"],
                 vis: meshcat.Visualizer | None = None, path: str = "afmsmiler/cantilever",
                 force_per_unit: float = DEFAULTS["force_per_unit"],
                 stress_limit: float | None = None, camera: bool = True):
        check_instance("bending", bending, Bending)
        check_instance("path", path, str)
        camera = check_flag("camera", camera)
        self.root = scene_root(vis)
        self.path = path
        self.vis = self.root[path]
        exaggeration = EXAGGERATION.check(exaggeration)
        self.force_per_unit = check_range("force_per_unit", force_per_unit, 1e-15, 1e3, "N")
        self.stress_limit = (None if stress_limit is None
                             else check_positive("stress_limit", stress_limit, "Pa"))
        self._material = g.MeshLambertMaterial(**_BEAM_MATERIAL_ARGS)
        self._tip_drawn_for = None
        self._base_drawn_for = None
        self.arrow = Arrow(self.vis["force"], color=0x303030, radius=0.015, head_length=0.08)
        self.legend = None
        self.scale = None
        self.mesh = None
        self.field = None
        self.camera = camera
        self.camera_position = None
        self._framed_for = None
        self.update(bending, exaggeration=exaggeration)

    # -- framing ------------------------------------------------------------------------------
    @staticmethod
    def framing(length: float, aspect: float = DEFAULTS["aspect"]) -> tuple[np.ndarray, float]:
        """Camera position and legend width (scene units) that frame a lever ``length`` units long.

        The camera looks at the lever's centre (the origin) along ``camera_direction``, from the
        smallest distance (at least ``min_distance``) at which, in a view ``aspect`` times wider
        than high, the clamp with ``chip_in_view`` units of chip, the free end deflected up or
        down by the largest drawn deflection, and the legend all fit inside 92 % of the view (see
        :func:`~afmsmiler.scenes.camera.camera_ndc`). The legend's width grows with that
        distance (:func:`~afmsmiler.scenes.camera.readable_width`), so it reads the same for
        every lever.

        Parameters
        ----------
        length : float
            Lever length in scene units (> 0, at most 10^4: a 1 m lever).
        aspect : float
            Width / height of the view, in [0.1, 10].

        Returns
        -------
        position : ndarray, shape (3,)
            Camera position in scene units.
        legend_width : float
            Legend width in scene units.
        """
        length = check_range("length", length, 0.0, 1e4, low_inclusive=False)
        aspect = check_range("aspect", aspect, 0.1, 10.0)
        direction = np.asarray(DEFAULTS["camera_direction"], dtype=float)
        cap = DEFAULTS["max_drawn_tip"] * length
        distance = DEFAULTS["min_distance"]
        for _ in range(400):  # grow by 5 % steps (to 3e8 x): the legend grows with the distance
            # its text READABLE_TEXT of the view's height where its centre stands
            camera = distance * direction
            try:
                legend = readable_width(ColorLegend.TEXT_FRACTION, [0.0, 0.5, 0.0], camera)
                for _ in range(2):  # where its centre stands: it moves with its width
                    corner = CantileverScene._legend_corner(length, legend) - [length / 2, 0, 0]
                    legend = readable_width(ColorLegend.TEXT_FRACTION,
                                            corner + [legend / 2, 0.0, legend / 8], camera)
            except ValueError:  # the legend would stand behind a camera this close: back off
                distance *= 1.05
                continue
            corner = CantileverScene._legend_corner(length, legend) - [length / 2, 0.0, 0.0]
            points = np.array([[-length / 2 - DEFAULTS["chip_in_view"], 0.0, 0.0],
                               [length / 2, 0.0, cap], [length / 2, 0.0, -cap - 0.15],
                               corner, corner + [legend, 0.0, legend / 4]])
            ndc = camera_ndc(points, distance * direction, aspect=aspect)
            if np.abs(ndc).max() <= 0.92:
                break
            distance *= 1.05
        return distance * direction, legend

    @staticmethod
    def _legend_corner(length: float, legend_width: float) -> np.ndarray:
        return np.array([-0.3 * legend_width, 0.5, 0.25 * legend_width + 0.1 * length])

    def _frame(self, length: float, free_end=()) -> None:
        """Aim the camera at a lever ``length`` units long and size the legend; only when the
        length changed by more than ``reframe_ratio`` since the last time (a slider drag does
        not move the camera under the student's hand at every step), or when a point of
        ``free_end`` (world frame, scene units: the drawn end of the lever and the tip apex)
        would leave the inner ``frame_margin`` of the view (a lever lengthened within the ratio
        while its deflection is drawn capped at ``max_drawn_tip`` x L)."""
        if self._framed_for is not None and (1 / DEFAULTS["reframe_ratio"]
                                             < length / self._framed_for
                                             < DEFAULTS["reframe_ratio"]):
            if not self.camera or len(free_end) == 0 or np.abs(camera_ndc(
                    np.asarray(free_end, dtype=float), self.camera_position,
                    aspect=DEFAULTS["aspect"])).max() <= DEFAULTS["frame_margin"]:
                return
        position, legend_width = self.framing(length)
        if self.camera:
            set_camera(self.root, position)
            show_helpers(self.root, grid=True, axes=False)  # the axes would pierce the lever
        self.camera_position = position
        self.legend_width = legend_width
        self._framed_for = length
        if self.legend is not None:
            self.legend = ColorLegend(self.vis["legend"], self.scale, width=legend_width)

    # -- in-place update ----------------------------------------------------------------------
    def color_scale(self, field: Bending) -> ColorScale:
        """The (symmetric, MPa) color scale for ``field``: fixed or the next round number.

        Parameters
        ----------
        field : Bending
            The model's result (its stress).
        """
        if self.stress_limit is not None:
            limit = self.stress_limit * _MPA
        else:
            limit = nice_ceil(float(np.abs(field.stress).max()) * _MPA, DEFAULTS["stress_floor"])
        return ColorScale.symmetric(limit, "RdBu_r", _STRESS_LABEL, _STRESS_UNIT)

    def update(self, bending: Bending, *, exaggeration: float | None = None) -> None:
        """Redraw for a new result (lever and/or force), in place (same viewer, same paths).

        Parameters
        ----------
        bending : Bending
            The model's result (:meth:`Cantilever.bending`).
        exaggeration : float, optional
            New deflection exaggeration (1 to 10^6); by default keep the current one.
        """
        field = check_instance("bending", bending, Bending)
        n_length, n_thickness = field.x.size, field.z_b.size
        if n_length * n_thickness > LIMITS["mesh_points"]:
            raise ValueError(f"bending must have at most {LIMITS['mesh_points']} grid points to "
                             f"draw, got {n_length} x {n_thickness}")
        if exaggeration is not None:
            self.exaggeration = EXAGGERATION.check(exaggeration)
        lever, force = field.lever, field.force
        self.lever, self.force = lever, force
        self.n_length, self.n_thickness = n_length, n_thickness
        scale = self.color_scale(field)
        tip = abs(float(field.deflection[-1]))
        cap = DEFAULTS["max_drawn_tip"] * lever.length / tip if tip > 0 else math.inf
        self.drawn_exaggeration = min(self.exaggeration, cap)
        u, ex = SCENE_UNIT, self.drawn_exaggeration
        mesh = beam_mesh(field.x / u, ex * field.deflection / u, lever.width / u,
                           lever.thickness / u, field.stress * _MPA, slope=ex * field.slope)
        self.vis["beam"].set_object(mesh.geometry(scale), self._material)
        self.field, self.mesh = field, mesh
        self._draw_base(lever)
        self._place_tip(field)
        length = lever.length / u
        x_l = np.array([-length / 2, 0.0, 0.0])  # the lever frame in the world
        end = np.array([length, 0.0, ex * float(field.deflection[-1]) / u])
        self._frame(length, [end + x_l, self.apex(self.tip_pose(field)) + x_l])
        if self.legend is None:
            self.legend = ColorLegend(self.vis["legend"], scale, width=self.legend_width)
        else:
            self.legend.set(scale)
        self.scale = scale
        # above the clamp, behind the lever, facing the camera
        self.vis["legend"].set_transform(translation(self.legend_corner(length)))
        self.vis.set_transform(translation([-length / 2, 0.0, 0.0]))  # centre the lever

    def legend_corner(self, length: float) -> np.ndarray:
        """Lower-left corner of the legend plate in the lever's frame (scene units): above the
        clamp, behind the lever.

        Parameters
        ----------
        length : float
            Lever length in scene units.
        """
        return self._legend_corner(length, self.legend_width)

    def _draw_base(self, lever: Cantilever) -> None:
        """The chip the lever is clamped to (a grey block behind x = 0), redrawn when h changes."""
        key = lever.thickness
        if key == self._base_drawn_for:
            return
        u = SCENE_UNIT
        self.vis["chip"].set_object(g.Box([1.0, 1.2, 0.3]), g.MeshLambertMaterial(color=0x9a9a9a))
        # top flush with the lever's top face
        self.vis["chip"].set_transform(translation([-0.5, 0.0, lever.thickness / u / 2 - 0.15]))
        self._base_drawn_for = key

    def tip_pose(self, field: Bending) -> np.ndarray:
        """4x4 pose of the tip frame: origin on the beam's bottom face at the free end, z along
        the local normal of the drawn beam (scene units), for the lever drawn from ``field``.

        Parameters
        ----------
        field : Bending
            The result drawn (its lever, end deflection and end slope).
        """
        field = check_instance("field", field, Bending)
        lever = field.lever
        u, ex = SCENE_UNIT, self.drawn_exaggeration
        s = ex * float(field.slope[-1])
        n = np.array([-s, 0.0, 1.0]) / math.hypot(1.0, s)
        tangent = np.array([1.0, 0.0, s]) / math.hypot(1.0, s)
        inset = min(DEFAULTS["tip_radius"] * 1.5, 0.2 * lever.length) / u
        centre = np.array([lever.length / u, 0.0, ex * float(field.deflection[-1]) / u])
        origin = centre - inset * tangent - 0.5 * lever.thickness / u * n
        pose = np.eye(4)
        pose[:3, 0], pose[:3, 1], pose[:3, 2], pose[:3, 3] = tangent, [0.0, 1.0, 0.0], n, origin
        return pose

    def _place_tip(self, field: Bending) -> None:
        u = SCENE_UNIT
        if self._tip_drawn_for is None:
            cone(self.vis["tip"], DEFAULTS["tip_height"] / u, DEFAULTS["tip_radius"] / u,
                   0x707070)
            self._tip_drawn_for = True
        pose = self.tip_pose(field)
        # the cone (apex at its origin, base at +height) hangs below the bottom face
        self.vis["tip"].set_transform(pose @ translation([0.0, 0.0, -DEFAULTS["tip_height"] / u]))
        apex = self.apex(pose)
        length = self.force / self.force_per_unit
        if length >= 0:   # pushed up from below: the arrow ends at the apex
            self.arrow.set(apex - [0.0, 0.0, length], [0.0, 0.0, length])
        else:             # pulled down: the arrow starts at the apex
            self.arrow.set(apex, [0.0, 0.0, length])

    @staticmethod
    def apex(pose: np.ndarray) -> np.ndarray:
        """Position of the tip apex (scene units) for a tip pose from :meth:`tip_pose`."""
        return (pose @ np.array([0.0, 0.0, -DEFAULTS["tip_height"] / SCENE_UNIT, 1.0]))[:3]

    # -- modes ----------------------------------------------------------------------------
    def animate_modes(self, modes=(1, 2, 3), *, frames: int = DEFAULTS["mode_frames"],
                      repetitions: int = 3, play: bool = True) -> Animation:
        """Animate the first flexural mode shapes of the current lever beside it.

        Each mode is drawn as a beam of rigid segments behind the static lever (see
        :func:`mode_animation`), oscillating in its shape (from the result drawn, so the modes must
        be among those it holds) with a tip amplitude of 15 % of L. All modes are shown with the
        same period (their real frequencies differ by f_n/f_1 = 6.27, 17.5, ...; see the plot of
        the mode shapes).

        Parameters
        ----------
        modes : sequence of int
            Mode numbers (1-based), at most the number of modes of the result drawn.
        frames : int
            Frames per period.
        repetitions : int
            How many periods the viewer plays.
        play : bool
            Start playing at once.

        Returns
        -------
        meshcat.animation.Animation
            The animation sent to the viewer (play it again with ``vis.set_animation``).
        """
        anim = mode_animation(self.field, self.vis["modes"], modes=modes, frames=frames)
        self.root.set_animation(anim, play=play, repetitions=check_integer(
            "repetitions", repetitions, 1, 10_000))
        return anim

    def clear_modes(self) -> None:
        """Remove the mode beams."""
        self.vis["modes"].delete()

    # -- export ---------------------------------------------------------------------------
    def static_html(self) -> str:
        """The scene as one self-contained HTML page (meshcat's ``static_html``), for the book."""
        return _static_html(self.root)


def mode_animation(bending: Bending, vis: meshcat.Visualizer, modes=(1, 2, 3), *,
                   frames: int = DEFAULTS["mode_frames"],
                   segments: int = DEFAULTS["mode_segments"],
                   amplitude: float = DEFAULTS["mode_amplitude"],
                   fps: int = DEFAULTS["mode_fps"]) -> Animation:
    """Draw segmented beams for ``modes`` under ``vis``; return their oscillation as an Animation.

    meshcat animates transforms, not vertices, so each mode beam is made of ``segments`` rigid
    boxes whose poses follow A phi_n(x) sin(2 pi k / frames) for k = 0..frames. Mode n is placed
    behind the lever at y = n (0.3 + 1.5 w) scene units (1 unit = 100 um), labelled with its
    number and frequency (a :class:`~afmsmiler.scenes.legends.TextPlate` beside its clamp).
    The shapes and frequencies are the model's (``bending.mode_shapes``), read at the segment
    centres by linear interpolation; nothing is computed from the lever here.

    Parameters
    ----------
    bending : Bending
        The model's result: L, w, h, and the mode shapes and frequencies (its ``modes`` must
        include every mode asked for).
    vis : meshcat.Visualizer
        Parent path of the mode beams.
    modes : sequence of int
        Mode numbers (1-based).
    frames : int
        Frames per period (>= 2).
    segments : int
        Rigid segments per beam (>= 2).
    amplitude : float
        Tip amplitude as a fraction of L, in (0, 1].
    fps : int
        Frame rate of the animation.

    Returns
    -------
    meshcat.animation.Animation
    """
    check_visualizer("vis", vis)
    check_instance("bending", bending, Bending)
    frames = check_integer("frames", frames, 2, 10_000)
    segments = check_integer("segments", segments, 2, 1_000)
    amplitude = check_range("amplitude", amplitude, 0.0, 1.0, low_inclusive=False)
    fps = check_integer("fps", fps, 1, 240)
    modes = check_modes(modes)
    if max(modes) > len(bending.frequencies):
        raise ValueError(f"modes must be at most {len(bending.frequencies)} (the modes of "
                         f"bending), got {max(modes)}")
    if segments * (frames + 1) * len(modes) > LIMITS["animation_transforms"]:
        raise ValueError(f"segments x (frames + 1) x modes must be at most "
                         f"{LIMITS['animation_transforms']} (a longer animation takes minutes to "
                         f"build and send), got {segments} x {frames + 1} x {len(modes)}")
    lever, x = bending.lever, bending.x
    u = SCENE_UNIT
    L, w, h = lever.length / u, lever.width / u, lever.thickness / u
    pitch = 0.3 + 1.5 * w
    edges = np.linspace(0.0, lever.length, segments + 1)
    mids = 0.5 * (edges[1:] + edges[:-1])
    anim = Animation(default_framerate=fps)
    for n in modes:
        shape = bending.mode_shapes[n - 1]
        phi = np.interp(mids, x, shape)
        dphi = np.interp(mids, x, np.gradient(shape, x / lever.length))  # d phi / d(x/L)
        # which beam is which: "mode n: f_n" beside its clamp end (meshcat has no text)
        label = TextPlate(vis[f"label{n}"], f"mode {n}: "
                            f"{bending.frequencies[n - 1] * _KHZ:.3g} kHz",
                            width=max(0.25 * L, 0.3))
        vis[f"label{n}"].set_transform(translation([-1.05 * label.width, pitch * n, 0.02]))
        for i in range(segments):
            box = vis[f"mode{n}"][f"s{i:03d}"]
            # slightly longer than the pitch so the joints stay closed while bending
            box.set_object(g.Box([1.08 * L / segments, w, h]),
                           g.MeshLambertMaterial(color=_MODE_COLORS[(n - 1) % len(_MODE_COLORS)]))
            # at rest (straight) until the animation plays, not piled up at the clamp
            box.set_transform(translation([mids[i] / u, pitch * n, 0.0]))
        for k in range(frames + 1):
            a = amplitude * L * math.sin(2 * math.pi * k / frames)
            with anim.at_frame(vis, k) as frame:
                for i in range(segments):
                    angle = math.atan(a / L * dphi[i])
                    c, s = math.cos(angle), math.sin(angle)
                    t = np.array([[c, 0, -s, mids[i] / u], [0, 1, 0, pitch * n],
                                  [s, 0, c, a * phi[i]], [0, 0, 0, 1]])
                    frame[f"mode{n}"][f"s{i:03d}"].set_transform(t)
    return anim
