"""The 3D illustrations of module (g): each imaging mode's lever, tip, sample and laser spot.

One schematic instrument (not to scale): a sample block, a lever along x with its tip under the
free end, a laser whose beam reflects off the lever's end onto a four-quadrant photodiode
(:func:`~afmsmiler.scenes.transducers.quadrant_photodiode`), and the laser spot on it. The
animations (:class:`meshcat.animation.Animation`, played by the viewer) are built from the
models' results, never from physics computed here:

- :meth:`ModesScene.animate_tapping`: the lever and tip oscillating at the amplitude A about the
  rest distance z_c of a steady state of :func:`~afmsmiler.modes.amplitude_curve` (or
  :func:`~afmsmiler.modes.setpoint_state`), the tip touching the sample (a contact marker shows)
  in the frames where the distance z_c + A cos(theta) falls below the contact distance a0, the
  spot moving up and down with the deflection;
- :meth:`ModesScene.animate_fm`: the lever oscillating at constant amplitude beside a faint
  ghost of the free lever; the frequency shift df of :func:`~afmsmiler.modes.frequency_shift`
  makes the two drift apart (df is a few Hz out of hundreds of kHz: multiplied by a stated
  factor);
- :meth:`ModesScene.animate_lateral`: the tip scanned across the lever's axis (trace, then
  retrace) over a two-material sample, the lever twisting by the model's twist angle and the
  spot moving sideways by the model's lateral photodiode signal, opposite on trace and retrace;
- :meth:`ModesScene.animate_jumping`: the approach, contact, retract and lateral move of a
  jumping-mode cycle, from the tip heights a model gives per step.

Distances are nanometres under a lever of hundreds of micrometres: the drawing is schematic and
every motion is multiplied by a round factor (1, 2 or 5 x 10^n) that the scene's caption states
(:attr:`ModesScene.caption`). meshcat animates rigid transforms only (position and rotation), so
the lever moves as a rigid body. One scene path is shared by the modes: the panel moved last
draws its mode there (:meth:`ModesScene.draw`). Scenes take ``vis=`` (a
:class:`meshcat.Visualizer` or ``tests/recording.py``'s recorder).
"""
from __future__ import annotations

import html
import math

import meshcat
import meshcat.geometry as g
import numpy as np
from meshcat.animation import Animation

from ..parameters import read_only, unit_scale
from ..validation import (check_array, check_choice, check_flag, check_instance, check_integer,
                          check_positive, check_range)
from .animation import quaternions_about_x, set_track, set_translations
from .camera import set_camera, show_helpers
from .legends import text_png
from .shapes import cone, polyline
from .transducers import quadrant_photodiode
from .transforms import translation
from .view import fit_camera, view_of
from .viewer import SceneDisplay, scene_root

__all__ = ["DEFAULTS", "LIMITS", "KINDS", "ModesScene", "round_factor", "factor_text"]

#: The modes a scene draws.
KINDS = ("tapping", "fm", "lateral", "jumping")

#: Geometry (scene units) and animation defaults, in one place.
DEFAULTS = read_only(dict(
    sample=(3.0, 3.0, 0.3),        # sample block: x, y, thickness (top face at z = 0)
    lever=(2.0, 0.4, 0.06),        # lever: length (along -x from the tip), width, thickness
    tip_height=0.5,                # drawn tip height (apex to the lever's underside)
    rest_height=0.6,               # drawn apex height for the largest distance shown
    motion=0.35,                   # the largest drawn motion (amplitude), scene units
    twist=0.35,                    # the largest drawn twist, rad
    scan_half=1.1,                 # half the drawn scan line (lateral), scene units
    laser=(-1.9, 0.0, 2.6),
    detector=(1.8, 0.0, 2.8),
    detector_size=0.6,
    spot_radius=0.06,
    spot_travel=0.8,               # the largest drawn spot offset, x half the detector's side
    camera=(0.8, -5.0, 2.6),
    caption_width=4.4,             # caption plates: width (scene units) and image size (px)
    caption_px=(1400, 80),
    frames=24,                     # frames per oscillation period
    periods=3,
    fps=24,
))

#: Bounds that keep each call within a second: frames per period, periods, lateral frames.
LIMITS = read_only(dict(frames=240, periods=50, animation_frames=2400, scan_frames=400))

_LEVER, _TIP, _SAMPLE, _B = 0xb0b0b8, 0x8a8a8a, 0xc9b48a, 0x5e8fbf
_GHOST, _CONTACT, _SPOT, _BEAM = 0xd0d0d0, 0xff8c00, 0xff0000, 0xff4040

_NM = unit_scale("nm", "m")

# the shared path: the scene of the panel moved last owns it
_OWNER: dict = {}


def round_factor(target: float) -> float:
    """The round factor (1, 2 or 5 x 10^n) at most ``target`` (> 0): a stated magnification.

    Parameters
    ----------
    target : float
        The factor that would make a motion exactly as large as wanted, > 0.

    Returns
    -------
    float
    """
    target = check_positive("target", target)
    exponent = math.floor(math.log10(target))
    best = 10.0 ** exponent
    for mantissa in (2.0, 5.0):
        if mantissa * 10.0 ** exponent <= target * (1 + 1e-12):
            best = mantissa * 10.0 ** exponent
    return float(f"{best:.1g}")


def factor_text(factor: float) -> str:
    """A magnification as the captions write it: ``"x 2e7"``, ``"x 50"``, ``"x 1"``.

    Parameters
    ----------
    factor : float
        A round factor (:func:`round_factor`), > 0.

    Returns
    -------
    str
    """
    factor = check_positive("factor", factor)
    if 1 <= factor < 1000:
        return f"x {factor:g}"
    mantissa, exponent = f"{factor:.0e}".split("e")
    return f"x {mantissa}e{int(exponent)}"


def _column(values: np.ndarray, at: int) -> np.ndarray:
    """Points (n, 3) that are zero but for coordinate ``at``, which holds ``values``."""
    out = np.zeros((np.size(values), 3))
    out[:, at] = values
    return out


class ModesScene(SceneDisplay):
    """The schematic instrument of module (g) and the animations of its modes.

    Parameters
    ----------
    kind : str
        The mode drawn first, one of :data:`KINDS` (``"lateral"`` adds a second material and
        turns the scan across the lever).
    vis : meshcat.Visualizer, optional
        The root visualizer; by default a new 3D view's (:class:`~afmsmiler.scenes.SceneView`).
    path : str
        Path of the scene in the viewer (shared by the modes: the last one drawn owns it).
    camera : bool
        Place the camera to see the instrument from the front, above.

    Attributes
    ----------
    kind : str
        The mode drawn.
    caption : str
        What the last animation shows and by how much each motion is magnified.
    factors : dict
        The magnifications of the last animation (``"distance"``, ``"twist"``, ``"signal"``,
        ``"frequency"``), each a round number.
    animation : meshcat.animation.Animation or None
        The last animation sent.
    """

    def __init__(self, kind: str = "tapping", *, vis: meshcat.Visualizer | None = None,
                 path: str = "afmsmiler/modes", camera: bool = True):
        self.kind = check_choice("kind", kind, KINDS)
        check_instance("path", path, str)
        camera = check_flag("camera", camera)
        self.root = scene_root(vis)
        self.path = path
        self.vis = self.root[path]
        self.caption = ""
        self.factors = {}
        self.animation = None
        self._camera = camera
        self.draw()

    # -- the instrument -----------------------------------------------------------------------
    @property
    def owns_view(self) -> bool:
        """Whether this scene is the one drawn at its path now (the last drawn there)."""
        return _OWNER.get((id(self.root), self.path)) is self

    def draw(self, kind: str | None = None) -> None:
        """(Re)draw the instrument at the scene's path for ``kind`` (default: the scene's).

        Parameters
        ----------
        kind : str, optional
            One of :data:`KINDS`.
        """
        if kind is not None:
            self.kind = check_choice("kind", kind, KINDS)
        d = DEFAULTS
        v = self.vis
        v.delete()
        sx, sy, sz = d["sample"]
        v["sample"].set_object(g.Box([sx, sy, sz]), g.MeshLambertMaterial(color=_SAMPLE))
        v["sample"].set_transform(translation([0.0, 0.0, -sz / 2]))
        length, width, thick = d["lever"]
        th = d["tip_height"]
        # the probe: apex at the node's origin, the lever along -x above it
        probe = v["probe"]
        probe["lever"].set_object(g.Box([length, width, thick]),
                                  g.MeshLambertMaterial(color=_LEVER))
        probe["lever"].set_transform(translation([-length / 2 + 0.1, 0.0, th + thick / 2]))
        cone(probe["tip"], th, 0.14, color=_TIP)
        sphere = g.Sphere(0.09)
        v["contact"].set_object(sphere, g.MeshLambertMaterial(color=_CONTACT))
        v["contact"].set_property("visible", False)
        if self.kind == "fm":  # the free lever, a faint ghost behind the one that feels the force
            ghost = v["ghost"]
            ghost["lever"].set_object(g.Box([length, width, thick]),
                                      g.MeshLambertMaterial(color=_GHOST, opacity=0.35,
                                                            transparent=True))
            ghost["lever"].set_transform(translation([-length / 2 + 0.1, 0.0, th + thick / 2]))
        self._rest = d["rest_height"]
        top = np.array([0.0, 0.0, self._rest + th + thick])
        laser = np.asarray(d["laser"], dtype=float)
        self.detector = np.asarray(d["detector"], dtype=float)
        v["laser"].set_object(g.Box([0.45, 0.22, 0.22]), g.MeshLambertMaterial(color=0x333333))
        v["laser"].set_transform(translation(laser))
        self._laser = laser
        self._aim(top[2])
        normal = top - self.detector
        self.normal = normal / np.linalg.norm(normal)
        self.rotation = quadrant_photodiode(v["detector"], self.detector, self.normal,
                                            d["detector_size"])
        v["spot"].set_object(g.Sphere(d["spot_radius"]), g.MeshLambertMaterial(color=_SPOT))
        v["spot"].set_transform(translation(self.spot_position(0.0, 0.0)))
        v["probe"].set_transform(translation([0.0, 0.0, self._rest]))
        if self.kind == "fm":
            v["ghost"].set_transform(translation([0.0, 0.6, self._rest]))
        if self._camera:
            set_camera(self.root, d["camera"])
            show_helpers(self.root, grid=False, axes=False)
            fit_camera(self.vis, margin=0.95)  # the instrument fills the view (captions: legend)
        _OWNER[(id(self.root), self.path)] = self

    def _aim(self, height: float) -> None:
        """Draw the beams to the lever's top at ``height`` (scene units): its mean position in
        the animation (the beams are drawn still; the spot moves)."""
        top = np.array([0.0, 0.0, height])
        polyline(self.vis["incident"], np.array([self._laser, top]), color=_BEAM)
        polyline(self.vis["reflected"], np.array([top, self.detector]), color=_BEAM)

    def _lever_top(self, apex: float) -> float:
        """Height of the lever's top face (scene units) over an apex at ``apex``."""
        return apex + DEFAULTS["tip_height"] + DEFAULTS["lever"][2]

    def spot_position(self, vertical: float, lateral: float) -> np.ndarray:
        """The spot's centre (scene units) for offsets in units of the largest drawn offset.

        Parameters
        ----------
        vertical : float
            Offset along the detector's vertical axis, in [-1, 1] (deflection).
        lateral : float
            Offset along its lateral axis (y), in [-1, 1] (twist).

        Returns
        -------
        ndarray
            The point on the detector's face (slightly in front of it).
        """
        vertical = check_range("vertical", vertical, -1.0, 1.0)
        lateral = check_range("lateral", lateral, -1.0, 1.0)
        return self._spots(np.array([vertical]), np.array([lateral]))[0]

    def _spots(self, vertical: np.ndarray, lateral: np.ndarray) -> np.ndarray:
        """:meth:`spot_position` of many offsets at once (arrays in [-1, 1]), shape (n, 3)."""
        half = DEFAULTS["detector_size"] / 2 * DEFAULTS["spot_travel"]
        local = np.zeros((np.size(vertical), 3))
        local[:, 0] = vertical * half
        local[:, 1] = lateral * half
        return self.detector + local @ self.rotation[:3, :3].T + 0.03 * self.normal

    def _ensure(self, kind: str) -> None:
        if kind != self.kind or not self.owns_view:
            self.draw(kind)

    def _caption(self, text: str) -> None:
        """Show ``text`` under the instrument, one plate per ``"; "``-separated part."""
        self.caption = text
        self.vis["caption"].delete()
        view = view_of(self.root)
        if view is not None:  # screen-space text in the view's corner: never tilted or clipped
            view.set_legend_part(self.vis["caption"].path.lower(), "".join(
                f"<div>{html.escape(line)}</div>" for line in text.split("; ")))
            return
        width, px = DEFAULTS["caption_width"], DEFAULTS["caption_px"]
        height = width * px[1] / px[0]
        for i, line in enumerate(text.split("; ")):
            plate = self.vis["caption"][f"line{i}"]
            texture = g.ImageTexture(image=g.PngImage(text_png(line, size_px=px)))
            plate.set_object(g.Box([width, width / 200, height]),
                             g.MeshBasicMaterial(map=texture, color=0xffffff))
            plate.set_transform(translation([0.0, -1.9, -0.6 - 1.15 * height * i]))

    def _send(self, anim: Animation, play: bool, repetitions: int) -> Animation:
        repetitions = check_integer("repetitions", repetitions, 1, 1000)
        self.root.set_animation(anim, play=bool(play), repetitions=repetitions)
        self.animation = anim
        return anim

    @staticmethod
    def _timing(frames, periods, fps):
        frames = check_integer("frames", frames, 4, LIMITS["frames"])
        periods = check_integer("periods", periods, 1, LIMITS["periods"])
        fps = check_integer("fps", fps, 1, 120)
        if frames * periods > LIMITS["animation_frames"]:
            raise ValueError(f"frames x periods must be at most {LIMITS['animation_frames']}, "
                             f"got {frames} x {periods}")
        return frames, periods, fps

    # -- tapping ------------------------------------------------------------------------------
    def animate_tapping(self, distance: float, amplitude: float, *, free_amplitude: float,
                        contact_distance: float, frames: int = DEFAULTS["frames"],
                        periods: int = DEFAULTS["periods"], fps: int = DEFAULTS["fps"],
                        repetitions: int = 20, play: bool = True) -> Animation:
        """Animate the tapping lever: apex at z_c + A cos(theta), touching below a0.

        Parameters
        ----------
        distance : float
            Rest tip-sample distance z_c in m (a steady state of the model).
        amplitude : float
            Its amplitude A in m.
        free_amplitude : float
            The free amplitude A0 in m (sets the magnification: A0 is drawn
            ``DEFAULTS["motion"]`` tall).
        contact_distance : float
            The distance a0 in m below which tip and sample touch (the model's
            ``intermolecular_distance``).
        frames : int
            Frames per period (slow motion: the lever oscillates at hundreds of kHz).
        periods : int
            Periods in the animation.
        fps : int
            Frames per second.
        repetitions : int
            How many times the viewer plays it.
        play : bool
            Start playing at once.

        Returns
        -------
        meshcat.animation.Animation
        """
        zc = check_positive("distance", distance, "m")
        a = check_range("amplitude", amplitude, 0.0, math.inf, "m")
        a0 = check_positive("free_amplitude", free_amplitude, "m")
        contact = check_positive("contact_distance", contact_distance, "m")
        frames, periods, fps = self._timing(frames, periods, fps)
        self._ensure("tapping")
        scale = round_factor(DEFAULTS["motion"] / a0)  # scene units per m
        self.factors = {"distance": scale}
        self._aim(self._lever_top(zc * scale))
        anim = Animation(default_framerate=fps)
        k = np.arange(frames * periods + 1)
        c = np.cos(2 * math.pi * k / frames)
        z = zc + a * c
        touching = z < contact
        touches = int(touching.sum())
        set_translations(anim, self.vis["probe"], k, _column(z * scale, at=2))
        set_translations(anim, self.vis["spot"], k,
                         self._spots(np.clip(a * c / a0, -1, 1), np.zeros(k.size)))
        set_track(anim, self.vis["contact"], "visible", k, touching)
        self.touching_frames = touches
        nm_per_unit = _NM / scale
        self._caption(f"tapping: z_c {zc * _NM:.3g} nm, A {a * _NM:.3g} nm"
                      f"{' (touches: orange)' if touches else ' (never touches)'}; "
                      f"heights {factor_text(scale)}: 1 unit = {nm_per_unit:.3g} nm, slowed down")
        return self._send(anim, play, repetitions)

    # -- frequency modulation -----------------------------------------------------------------
    def animate_fm(self, distance: float, amplitude: float, frequency_shift: float, *,
                   resonance_frequency: float, frames: int = DEFAULTS["frames"],
                   periods: int = 8, fps: int = DEFAULTS["fps"], repetitions: int = 10,
                   play: bool = True) -> Animation:
        """Animate the FM lever beside the free one: the frequency shift makes them drift apart.

        The lever oscillates between the closest distance z and z + 2 A (phase theta (1 +
        m df / f0) at frame theta of the ghost), with df multiplied by the round factor m that
        makes the drift half a period over the animation (:attr:`factors` ``["frequency"]``).

        Parameters
        ----------
        distance : float
            Closest tip-sample distance z in m.
        amplitude : float
            Oscillation amplitude A in m.
        frequency_shift : float
            df in Hz at z (from :func:`~afmsmiler.modes.frequency_shift`).
        resonance_frequency : float
            f0 in Hz.
        frames : int
            Frames per period.
        periods : int
            Periods of the free lever in the animation.
        fps : int
            Frames per second.
        repetitions : int
            How many times the viewer plays it.
        play : bool
            Start playing at once.

        Returns
        -------
        meshcat.animation.Animation
        """
        z = check_positive("distance", distance, "m")
        a = check_positive("amplitude", amplitude, "m")
        df = check_range("frequency_shift", frequency_shift, -math.inf, math.inf, "Hz")
        f0 = check_positive("resonance_frequency", resonance_frequency, "Hz")
        frames, periods, fps = self._timing(frames, periods, fps)
        self._ensure("fm")
        scale = round_factor(DEFAULTS["motion"] / a)
        ratio = abs(df) / f0
        boost = round_factor(0.5 / (periods * ratio)) if ratio > 0 else 1.0
        self.factors = {"distance": scale, "frequency": boost}
        self._aim(self._lever_top((z + a) * scale))
        anim = Animation(default_framerate=fps)
        k = np.arange(frames * periods + 1)
        theta = 2 * math.pi * k / frames
        c = np.cos(theta * (1 + boost * df / f0))
        set_translations(anim, self.vis["probe"], k, _column((z + a * (1 + c)) * scale, at=2))
        ghost = _column((z + a * (1 + np.cos(theta))) * scale, at=2)
        ghost[:, 1] = 0.6
        set_translations(anim, self.vis["ghost"], k, ghost)
        set_translations(anim, self.vis["spot"], k, self._spots(c, np.zeros(k.size)))
        self._caption(f"FM: df = {df:.3g} Hz at z = {z * _NM:.3g} nm (grey: free lever); "
                      f"df {factor_text(boost)}, heights {factor_text(scale)}")
        return self._send(anim, play, repetitions)

    # -- lateral force ------------------------------------------------------------------------
    def animate_lateral(self, position, twist, signal, *, materials=None,
                        frames: int = 60, fps: int = DEFAULTS["fps"], repetitions: int = 10,
                        play: bool = True) -> Animation:
        """Animate a friction loop: the tip across the lever's axis, the lever twisting.

        Parameters
        ----------
        position : array_like
            Positions along the line in m (n values, increasing).
        twist : array_like
            Twist angle in rad of the lever's end at each position, shape (2, n): trace, then
            retrace (from :meth:`~afmsmiler.modes.LateralLever.twist` of the loop's forces).
        signal : array_like
            The lateral photodiode signal at each position, shape (2, n), in [-1, 1] (from
            :meth:`~afmsmiler.modes.LateralLever.signal`).
        materials : array_like of bool, optional
            Where the second material is (n values), drawn as blue patches on the sample.
        frames : int
            Frames per pass (trace or retrace), 2 to ``LIMITS["scan_frames"]``.
        fps : int
            Frames per second.
        repetitions : int
            How many times the viewer plays it.
        play : bool
            Start playing at once.

        Returns
        -------
        meshcat.animation.Animation
        """
        x = check_array("position", position, "m", ndim=1, min_size=2, increasing=True)
        n = x.size
        phi = check_array("twist", twist, "rad", ndim=2, size=2 * n)
        s = check_array("signal", signal, "", ndim=2, size=2 * n, low=-1.0, high=1.0)
        if phi.shape != (2, n) or s.shape != (2, n):
            raise ValueError(f"twist and signal must have shape (2, {n}) (trace, retrace), got "
                             f"{phi.shape} and {s.shape}")
        frames = check_integer("frames", frames, 2, LIMITS["scan_frames"])
        fps = check_integer("fps", fps, 1, 120)
        self._ensure("lateral")
        half = DEFAULTS["scan_half"]
        y = -half + 2 * half * (x - x[0]) / (x[-1] - x[0])
        if materials is not None:
            mask = np.asarray(materials, dtype=bool)
            if mask.shape != (n,):
                raise ValueError(f"materials must hold one flag per position ({n}), got shape "
                                 f"{mask.shape}")
            edges = np.flatnonzero(np.diff(np.concatenate(([0], mask.astype(int), [0]))))
            dy = 2 * half / (n - 1)
            for i, (lo, hi) in enumerate(zip(edges[::2], edges[1::2])):
                width = (hi - lo) * dy
                node = self.vis["materials"][f"b{i}"]
                node.set_object(g.Box([DEFAULTS["sample"][0], width, 0.01]),
                                g.MeshLambertMaterial(color=_B))
                node.set_transform(translation([0.0, y[lo] - dy / 2 + width / 2, 0.005]))
        # no twist at all (no friction, no slope) is drawn as it is: x 1
        largest_twist, largest_signal = float(np.abs(phi).max()), float(np.abs(s).max())
        twist_factor = round_factor(DEFAULTS["twist"] / largest_twist) if largest_twist else 1.0
        signal_factor = round_factor(1.0 / largest_signal) if largest_signal else 1.0
        self.factors = {"twist": twist_factor, "signal": signal_factor}
        self._aim(self._lever_top(0.0))
        pick = np.unique(np.linspace(0, n - 1, frames).round().astype(int))
        anim = Animation(default_framerate=fps)
        passes = np.concatenate((np.zeros(pick.size, int), np.ones(pick.size, int)))
        order = np.concatenate((pick, pick[::-1]))  # trace, then retrace
        k = np.arange(order.size)
        set_translations(anim, self.vis["probe"], k, _column(y[order], at=1),
                         quaternions_about_x(twist_factor * phi[passes, order]))
        lateral = np.clip(signal_factor * s[passes, order], -1.0, 1.0)
        set_translations(anim, self.vis["spot"], k, self._spots(np.zeros(k.size), lateral))
        self._caption(f"lateral force: trace (to +y), then retrace; "
                      f"twist {factor_text(twist_factor)}, "
                      f"spot offset {factor_text(signal_factor)}")
        return self._send(anim, play, repetitions)

    # -- jumping ------------------------------------------------------------------------------
    def animate_jumping(self, heights, positions, *, pixel_size: float, contact=None,
                        fps: int = DEFAULTS["fps"], repetitions: int = 10,
                        play: bool = True) -> Animation:
        """Animate a jumping-mode cycle: approach, touch, retract, move while lifted.

        Parameters
        ----------
        heights : array_like
            Apex height in m above the sample's zero at each step of the cycle (as the model
            gives it), at most ``LIMITS["animation_frames"]`` values.
        positions : array_like
            The lateral position of each step in m (same length).
        pixel_size : float
            A length in m that sets the magnification (the largest height is drawn
            ``DEFAULTS["motion"]`` x 2 tall, the positions across the sample).
        contact : array_like of bool, optional
            Whether the tip touches at each step (the contact marker shows).
        fps : int
            Frames per second.
        repetitions : int
            How many times the viewer plays it.
        play : bool
            Start playing at once.

        Returns
        -------
        meshcat.animation.Animation
        """
        h = check_array("heights", heights, "m", ndim=1, min_size=2,
                        max_size=LIMITS["animation_frames"])
        xs = check_array("positions", positions, "m", ndim=1, size=h.size)
        px = check_positive("pixel_size", pixel_size, "m")
        touching = (np.zeros(h.size, bool) if contact is None
                    else np.asarray(contact, dtype=bool))
        if touching.shape != h.shape:
            raise ValueError(f"contact must hold one flag per step ({h.size}), got shape "
                             f"{touching.shape}")
        fps = check_integer("fps", fps, 1, 120)
        self._ensure("jumping")
        top = max(float(np.abs(h).max()), px)
        scale = round_factor(2 * DEFAULTS["motion"] / top)
        span = max(float(np.ptp(xs)), px)
        lateral = 2 * DEFAULTS["scan_half"] / span
        self.factors = {"distance": scale}
        self._aim(self._lever_top(float(np.median(h)) * scale))
        anim = Animation(default_framerate=fps)
        k = np.arange(h.size)
        y = -DEFAULTS["scan_half"] + (xs - xs.min()) * lateral
        probe = _column(y, at=1)
        probe[:, 2] = h * scale
        set_translations(anim, self.vis["probe"], k, probe)
        set_translations(anim, self.vis["contact"], k, _column(y, at=1))
        set_track(anim, self.vis["contact"], "visible", k, touching)
        self._caption(f"jumping: approach, touch, retract, move; heights {factor_text(scale)}")
        return self._send(anim, play, repetitions)
