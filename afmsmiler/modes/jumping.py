"""Jumping mode: a force curve at every pixel, the lateral moves made with the tip lifted.

At each pixel the positioner brings the sample towards the tip until the lever's force reaches
a maximum, the trigger F_t (the feedback's setpoint); the height of the positioner there is the
pixel's height. It then retracts the sample by a lift height L, beyond the point where the tip
jumps off an adhesive surface, and moves to the next pixel with the tip in the air: no friction,
no lateral force, however tall, steep or sticky the sample (de Pablo, Colchero, Gomez-Herrero
and Baro, "Jumping mode scanning force microscopy", Appl. Phys. Lett. 73, 3300 (1998);
Moreno-Herrero et al., Appl. Surf. Sci. 210, 22 (2003)). This is why the source paper's
macroscopic AFM (AFM SMILER, module (g)) images in this mode.

**The force curve of a pixel** (:func:`jump_curve`) is module (d)'s approach-retract cycle of a
:class:`~afmsmiler.contact.ContactSystem` (Hertz/Sneddon with DMT or JKR adhesion, the lever in
series): the approach runs Z_np from Z_t - L up to Z_t, the positioner displacement at which
the approach force equals F_t, and the retract runs back. The adhesion channel is the retract's
pull-off force (DMT: 2 pi R w; JKR: (3/2) pi R w; module (d)'s exact values). The lift must
reach beyond the jump-off, Z_t - L < Z_snap-off (:attr:`ContactSystem.snap_off_z_np`), or the
tip is still stuck when the move starts (a ValueError says how much lift is needed).

**The image** (:class:`JumpingMode`, a :class:`~afmsmiler.imaging.scan_modes.Mode` of module (f)'s
scanner). The scanner hands the apex surface r (the sample dilated by the tip, module (f)); the
tip touches at the positioner height H = r (the undeflected apex at the surface), and the trigger
comes at H_t = r - Z_t(material). The height channel is H_t + Z_t(first material): the apex
surface itself where the sample is the first material (the true topography up to the tip's
dilation), lower where a softer material lets the tip sink further before the trigger. The
tip is lifted to H_t + L and moved to the next pixel (pass order: trace forwards, retrace
backwards, then the next line); where the apex surface there rises above the lifted tip, the
tip runs into the feature's side while moving: a :class:`~afmsmiler.imaging.scan_modes.Crash`
(force inf: a rigid wall), and the lift must be raised above the tallest step between pixels.
The lateral force channel is the largest lateral force felt while moving: 0.

**The price: time.** Each pixel costs an approach and a retract at the z speed v_z on top of the
lateral move: t_pixel = 2 L / v_z + dx / v (the approach over a pixel lower than the previous
one is longer by the height difference; along a pass these differences add up to the
difference between its first and last pixel, at most the height range per pass, so
:meth:`JumpingMode.acquisition_time` is exact on a flat sample and within 2 x range / v_z per
pass otherwise). Contact mode's scan takes lines x (2 pixels - 1) dx / v
(:attr:`~afmsmiler.imaging.settings.ScanSettings.scan_time`).
"""
from __future__ import annotations

import math
from functools import lru_cache
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import NamedTuple

import numpy as np

from ..contact import ContactSystem
from ..imaging.scan_modes import DIRECTIONS, Crash, Mode, ModeLine, ScanPlan
from ..parameters import Parameter, read_only
from ..validation import check_array, check_instance, check_integer, check_range

__all__ = ["PARAMETERS", "TRIGGER_FORCE", "LIFT_HEIGHT", "Z_SPEED", "JumpCurve", "JumpingMode",
           "ModeComparison", "ApexPath", "apex_path", "jump_curve", "trigger_z_np",
           "compare_with_contact", "MAX_CURVE_POINTS", "MAX_MATERIALS"]

#: Most points of one branch of :func:`jump_curve`.
MAX_CURVE_POINTS = 100_000
#: Most materials (contact systems) one :class:`JumpingMode` tells apart.
MAX_MATERIALS = 16
# doublings of the bracket on Z_np in the search for the trigger (2^200 covers any range)
_MAX_DOUBLINGS = 200

#: Trigger force F_t: the largest force at each pixel (the jumping mode's setpoint).
TRIGGER_FORCE = Parameter(name="trigger_force", unit="N", display_unit="nN", default=2e-9,
                          low=0.0, high=1e-3, low_inclusive=False, slider_low=0.1e-9,
                          slider_high=50e-9, log=True, label="trigger force F_t")
#: Lift height L: how far the sample is retracted from the trigger before the lateral move.
LIFT_HEIGHT = Parameter(name="lift_height", unit="m", display_unit="nm", default=100e-9,
                        low=0.0, high=1e-5, low_inclusive=False, slider_low=5e-9,
                        slider_high=1e-6, log=True, label="lift height L")
#: Speed v_z of the positioner during the approach and the retract.
Z_SPEED = Parameter(name="z_speed", unit="m/s", display_unit="um/s", default=20e-6, low=1e-9,
                    high=1.0, slider_low=1e-6, slider_high=1e-3, log=True,
                    label="approach/retract speed v_z")

#: The jumping mode's user-settable quantities (SI), by keyword name (read-only).
PARAMETERS = read_only({p.name: p for p in (TRIGGER_FORCE, LIFT_HEIGHT, Z_SPEED)})


def trigger_z_np(system: ContactSystem, trigger_force: float = TRIGGER_FORCE.default) -> float:
    """Positioner displacement Z_t in m at which the approach force reaches the trigger.

    Parameters
    ----------
    system : afmsmiler.contact.ContactSystem
        Tip, lever and sample (module (d)).
    trigger_force : float
        Trigger force F_t in N, > 0.

    Returns
    -------
    float
        Z_t > 0 (from the undeformed surface touching the resting tip), found on module (d)'s
        approach branch, whose force rises with Z_np (the lever's equation k (Z_np - Z_s) =
        F(Z_s) has one root on the stable branch), by bracketing, grid refinement and
        interpolation (see ``_trigger_z_np``), to 1e-15 m + 1e-12 Z_t.

    Raises
    ------
    TypeError
        If ``system`` is not a ContactSystem.
    ValueError
        If ``trigger_force`` is out of range, or a sphere would be indented past its radius
        before the force reaches it.
    """
    check_instance("system", system, ContactSystem)
    return _trigger_z_np(system, TRIGGER_FORCE.check(trigger_force))


#: Z_np values per model run of the trigger's search (one vectorised approach branch).
_GRID = 257
#: The bracketing run's geometric steps per doubling of Z_np (8 doublings a run: 2.2 % cells).
_PER_DOUBLING = 32
#: Grid refinements of the trigger's search at most: each narrows the bracket 256-fold (16 from
#: any bracket a double can hold; one or two in practice, see ``_trigger_z_np``).
_MAX_REFINEMENTS = 16
#: The trigger's tolerance: |Z_found - Z_t| <= _XTOL + _RTOL |Z_t| (m, relative).
_XTOL, _RTOL = 1e-15, 1e-12


def _approach_force(system: ContactSystem, z: np.ndarray) -> np.ndarray:
    """Module (d)'s approach force in N at the increasing Z_np values ``z`` (one model run).

    The approach branch at a Z_np does not depend on the ramp's other points (the tip touches
    from Z_np = 0 on; only the retract remembers where it has been): each value is
    ``system.at(z_i, "approach")``'s (tested).
    """
    return system.approach_retract(z).approach.force


@lru_cache(maxsize=64)
def _trigger_z_np(system: ContactSystem, f_t: float) -> float:
    """:func:`trigger_z_np` of a checked system and force, kept for the systems last asked for
    (a frozen, hashable system: a jumping panel's move of the lift or the speed, and the mode
    beside its curve, ask for the same trigger again).

    The approach force F(Z) rises with Z_np on the stable branch. One model run on a geometric
    grid from 2 F_t / k up (8 doublings of :data:`_PER_DOUBLING` steps, more runs while F stays
    below F_t, up to the tip's limit) brackets Z_t in a cell 2.2 % wide; uniform grids of
    :data:`_GRID` values (one vectorised run each) narrow it. The root is the linear
    interpolation in the last cell, whose error is at most h^2 / 8 max|F''| / |F'| (the
    interpolation remainder; F' and F'' from the grid's first and second differences): the
    search stops once ten times that, or the cell itself, is within 1e-15 m + 1e-12 Z_t. A
    scalar root finder needed some ten runs of the model, 1 ms each (issue 24); this takes two
    or three.
    """
    limit = system.z_np_limit
    top = limit * (1.0 - 1e-9)
    lo, hi = 0.0, 2.0 * f_t / system.spring_constant + 1e-12
    ratios = 2.0 ** (np.arange(8 * _PER_DOUBLING + 1) / _PER_DOUBLING)
    for _ in range(_MAX_DOUBLINGS // 8 + 1):  # bounded: 8 doublings a model run
        z = hi * ratios
        capped = bool(z[-1] >= top)
        z = np.r_[lo, z[z < top], top] if capped else np.r_[lo, z]
        f = _approach_force(system, z)
        above = np.flatnonzero(f[1:] >= f_t)
        if above.size:
            lo, hi = float(z[above[0]]), float(z[above[0] + 1])
            break
        if capped:
            raise ValueError(f"trigger_force {f_t:g} N is never reached: the sphere would "
                             f"be indented past its radius first (Z_np limit {limit:g} m); "
                             f"choose a smaller trigger_force")
        lo, hi = float(z[-1]), 2.0 * float(z[-1])
    else:
        raise ValueError(f"trigger_force {f_t:g} N is not reached below Z_np = {lo:g} m")
    for _ in range(_MAX_REFINEMENTS):  # bounded: each run narrows the bracket 256-fold
        z = np.linspace(lo, hi, _GRID)
        f = _approach_force(system, z)
        i = max(1, int(np.argmax(f >= f_t)))  # f[-1] >= f_t: the first grid value above
        lo, hi, f_lo, f_hi = float(z[i - 1]), float(z[i]), float(f[i - 1]), float(f[i])
        h, tol = hi - lo, _XTOL + _RTOL * hi
        if h <= tol:
            break
        curvature = max(abs(f[j + 1] - 2.0 * f[j] + f[j - 1]) for j in (i - 1, i)
                        if 1 <= j <= _GRID - 2) / (h * h)
        slope = (f_hi - f_lo) / h
        if slope > 0 and 10.0 * h * h / 8.0 * curvature / slope <= tol:
            break
    if f_hi == f_lo:
        return hi
    return lo + (f_t - f_lo) / (f_hi - f_lo) * (hi - lo)


def _sequence(name: str, values, kind) -> tuple:
    """One ``kind`` or a sequence of them as a tuple (a TypeError naming ``name`` otherwise)."""
    if isinstance(values, kind):
        return (values,)
    if isinstance(values, (str, bytes)) or not hasattr(values, "__iter__"):
        raise TypeError(f"{name} must be a {kind.__name__} or a sequence of them, got "
                        f"{type(values).__name__}")
    return tuple(values)


def _material_index(material, x, y, count: int) -> np.ndarray:
    """``material(x, y)`` checked to give integers in [0, count) shaped like x (0 if None)."""
    if material is None:
        return np.zeros(np.shape(x), dtype=int)
    m = np.asarray(material(x, y))
    if m.shape != np.shape(x) or m.dtype.kind not in "iu" or m.size and \
            (m.min() < 0 or m.max() >= count):
        raise ValueError(f"material(x, y) must give integers in [0, {count - 1}] shaped like "
                         f"x, got {m.dtype} {m.shape}")
    return m


def _lift_needed(system: ContactSystem, z_t: float) -> float:
    """Smallest lift in m that takes the tip off the surface: Z_t - snap-off Z_np."""
    return z_t - min(system.snap_off_z_np, 0.0)


def _check_lift(lift: float, systems, z_t) -> None:
    needed = max(_lift_needed(s, z) for s, z in zip(systems, z_t))
    if lift <= needed:
        raise ValueError(f"lift_height must be > {needed:g} m to take the tip off the surface "
                         f"(beyond the indentation at the trigger_force and the adhesive "
                         f"jump-off), got {lift:g} m")


@dataclass(frozen=True)
class JumpCurve:
    """The force curve of one jumping-mode pixel (:func:`jump_curve`), SI units.

    Parameters
    ----------
    approach_z_np, retract_z_np : numpy.ndarray
        Positioner displacement Z_np in m along the approach (up to the trigger) and the retract
        (back down by the lift).
    approach_force, retract_force : numpy.ndarray
        Force on the tip in N along each branch (negative: adhesion).
    approach_time, retract_time : numpy.ndarray
        Time in s since the start of the approach.
    trigger_z_np : float
        Z_t in m, where the approach force reaches the trigger.
    trigger_force : float
        F_t in N.
    pull_off_force : float
        Magnitude in N of the most adhesive force on the retract (module (d)'s exact value).
    snap_off_z_np : float
        Z_np in m at which the tip jumps off the surface on the retract (0 without adhesion).
    lift_height : float
        L in m.
    z_speed : float
        v_z in m/s.
    """

    approach_z_np: np.ndarray = field(repr=False)
    approach_force: np.ndarray = field(repr=False)
    approach_time: np.ndarray = field(repr=False)
    retract_z_np: np.ndarray = field(repr=False)
    retract_force: np.ndarray = field(repr=False)
    retract_time: np.ndarray = field(repr=False)
    trigger_z_np: float
    trigger_force: float
    pull_off_force: float
    snap_off_z_np: float
    lift_height: float
    z_speed: float

    @property
    def cycle_time(self) -> float:
        """Time in s of the approach and the retract, 2 L / v_z."""
        return 2.0 * self.lift_height / self.z_speed


class ApexPath(NamedTuple):
    """Where the apex is along jumping cycles over a run of pixels (:func:`apex_path`), SI.

    Parameters
    ----------
    height : numpy.ndarray
        Apex height in m at each frame (the surface while touching, |Z_np| above it while free).
    x : numpy.ndarray
        Position in m along the line (the pixel's).
    touching : numpy.ndarray of bool
        Whether the tip touches the surface.
    """

    height: np.ndarray
    x: np.ndarray
    touching: np.ndarray


def apex_path(curve: JumpCurve, surface, pixel_size: float, *, frames: int = 12) -> ApexPath:
    """The apex's path through one jumping cycle per pixel, pixel after pixel.

    Each pixel: the curve's approach (touching from Z_np = 0 on), then its retract (touching
    until the snap-off Z_np, or Z_np = 0 without adhesion), ``frames`` points of each, evenly
    spread over the curve's points; the apex sits on the surface while touching and |Z_np| above
    it while free; then the lateral move to the next pixel, the tip lifted.

    Parameters
    ----------
    curve : JumpCurve
        One pixel's curve (:func:`jump_curve`).
    surface : array_like
        Surface height in m under each pixel (1-D, finite, at least one pixel).
    pixel_size : float
        Pixel pitch in m, > 0.
    frames : int
        Points of the approach and of the retract per pixel, 2 to the curve's points.

    Returns
    -------
    ApexPath
        2 ``frames`` points per pixel.

    Raises
    ------
    TypeError
        If ``curve`` is not a JumpCurve.
    ValueError
        On a surface that is not 1-D and finite, a pixel size <= 0 or ``frames`` out of range.
    """
    check_instance("curve", curve, JumpCurve)
    surface = check_array("surface", surface, "m", ndim=1, min_size=1)
    pitch = check_range("pixel_size", pixel_size, 0.0, math.inf, "m", low_inclusive=False)
    n = check_integer("frames", frames, 2, curve.approach_z_np.size)
    pick = np.linspace(0, curve.approach_z_np.size - 1, n).round().astype(int)
    z_app, z_ret = curve.approach_z_np[pick], curve.retract_z_np[pick]
    heights, xs, touching = [], [], []
    for j in range(surface.size):
        for z, touch in ((z_app, z_app >= 0.0),
                         (z_ret, z_ret >= min(curve.snap_off_z_np, 0.0))):
            heights += list(surface[j] + np.where(touch, 0.0, -z))
            touching += list(touch)
            xs += [j * pitch] * z.size
    return ApexPath(np.array(heights), np.array(xs), np.array(touching))


def jump_curve(system: ContactSystem, *, trigger_force: float = TRIGGER_FORCE.default,
               lift_height: float = LIFT_HEIGHT.default, z_speed: float = Z_SPEED.default,
               points: int = 400) -> JumpCurve:
    """The approach to the trigger and the retract by the lift at one pixel.

    Parameters
    ----------
    system : afmsmiler.contact.ContactSystem
        Tip, lever, sample and adhesion (module (d)).
    trigger_force : float
        Trigger force F_t in N.
    lift_height : float
        Lift L in m; must exceed Z_t minus the snap-off Z_np (the tip must leave the surface).
    z_speed : float
        Approach and retract speed v_z in m/s.
    points : int
        Samples of each branch, 2 to :data:`MAX_CURVE_POINTS`.

    Returns
    -------
    JumpCurve

    Raises
    ------
    TypeError
        If ``system`` is not a ContactSystem.
    ValueError
        Naming the argument out of range (a lift that does not take the tip off the surface
        included), before the curve is computed.

    Examples
    --------
    >>> from afmsmiler.contact import ContactSystem, Parabolic
    >>> system = ContactSystem(spring_constant=0.5, tip=Parabolic(radius=20e-9),
    ...                        youngs_modulus=1e9, adhesion="dmt", work_of_adhesion=0.05)
    >>> curve = jump_curve(system, trigger_force=5e-9, lift_height=50e-9)
    >>> round(curve.pull_off_force / (2 * 3.141592653589793 * 20e-9 * 0.05), 9)  # DMT 2 pi R w
    1.0
    >>> round(float(curve.approach_force[-1]) * 1e9, 6)  # the trigger, in nN
    5.0
    """
    check_instance("system", system, ContactSystem)
    f_t = TRIGGER_FORCE.check(trigger_force)
    lift = LIFT_HEIGHT.check(lift_height)
    v = Z_SPEED.check(z_speed)
    n = check_integer("points", points, 2, MAX_CURVE_POINTS)
    z_t = trigger_z_np(system, f_t)
    _check_lift(lift, (system,), (z_t,))
    ramp = np.linspace(z_t - lift, z_t, n)
    cycle = system.approach_retract(ramp)
    t_app = (ramp - ramp[0]) / v
    t_ret = lift / v + (z_t - cycle.retract.z_np) / v
    return JumpCurve(ramp, cycle.approach.force, t_app, cycle.retract.z_np, cycle.retract.force,
                     t_ret, z_t, f_t, float(system.pull_off_force), float(system.snap_off_z_np),
                     lift, v)


class JumpingMode(Mode):
    """Jumping mode as an imaging mode of module (f)'s scanner (see the module notes).

    Parameters
    ----------
    systems : ContactSystem or sequence of ContactSystem
        Module (d)'s contact system on each material (the same tip and lever, a different
        sample: modulus, adhesion, ...), 1 to :data:`MAX_MATERIALS`.
    trigger_force : float
        Trigger force F_t in N.
    lift_height : float
        Lift L in m, beyond every material's jump-off.
    z_speed : float
        Approach and retract speed v_z in m/s.
    material : callable, optional
        ``material(x, y)`` -> integer array (index into ``systems``) of the material at
        positions x, y in m on the sample (arrays of one shape); default: the first everywhere.

    Raises
    ------
    TypeError
        If a system is not a ContactSystem, the systems' tips differ or ``material`` is not
        callable.
    ValueError
        Naming the argument out of range (a lift that does not take the tip off included),
        before any scan.

    Notes
    -----
    Channels (trace and retrace, columns in increasing x): ``"height"`` in m (the positioner
    height at the trigger, see the module notes), ``"adhesion"`` in N (the pull-off force of
    the retract), ``"lateral force"`` in N (the largest lateral force while moving: 0). The
    tip the mode touches with is the systems' tip: give the scanner the same one.

    Examples
    --------
    >>> import numpy as np
    >>> from afmsmiler.contact import ContactSystem, Parabolic
    >>> from afmsmiler.imaging.scanner import ScanSettings, scan
    >>> from afmsmiler.samples import grating
    >>> tip = Parabolic(radius=10e-9)
    >>> mode = JumpingMode(ContactSystem(spring_constant=1.0, tip=tip, youngs_modulus=1e9),
    ...                    trigger_force=2e-9, lift_height=150e-9)
    >>> sample = grating((32, 64), 10e-9, period=320e-9, height=100e-9)
    >>> result = scan(sample, tip, mode, ScanSettings(300e-9, pixels=30, lines=4))
    >>> float(np.max(np.abs(result.images["lateral force trace"])))
    0.0
    """

    channels = ("height trace", "height retrace", "adhesion trace", "adhesion retrace",
                "lateral force trace", "lateral force retrace")
    units = MappingProxyType({"adhesion trace": "N", "adhesion retrace": "N",
                              "lateral force trace": "N", "lateral force retrace": "N"})

    def __init__(self, systems, *, trigger_force: float = TRIGGER_FORCE.default,
                 lift_height: float = LIFT_HEIGHT.default, z_speed: float = Z_SPEED.default,
                 material=None):
        systems = _sequence("systems", systems, ContactSystem)
        if not 1 <= len(systems) <= MAX_MATERIALS:
            raise ValueError(f"systems must hold 1 to {MAX_MATERIALS} contact systems, got "
                             f"{len(systems)}")
        self.systems = tuple(check_instance("systems", s, ContactSystem) for s in systems)
        if any(s.tip != self.systems[0].tip for s in self.systems):
            raise TypeError("systems must share one tip (the tip that both blurs and touches)")
        self.trigger_force = TRIGGER_FORCE.check(trigger_force)
        self.lift_height = LIFT_HEIGHT.check(lift_height)
        self.z_speed = Z_SPEED.check(z_speed)
        if material is not None and not callable(material):
            raise TypeError(f"material must be a callable material(x, y), got "
                            f"{type(material).__name__}")
        self.material = material
        self.tip = self.systems[0].tip
        #: Per material: trigger Z_t in m and pull-off force in N.
        self.trigger = np.array([trigger_z_np(s, self.trigger_force) for s in self.systems])
        _check_lift(self.lift_height, self.systems, self.trigger)
        self.pull_off = np.array([s.pull_off_force for s in self.systems])

    def __repr__(self) -> str:
        return (f"JumpingMode({len(self.systems)} systems, trigger_force={self.trigger_force!r}, "
                f"lift_height={self.lift_height!r}, z_speed={self.z_speed!r})")

    def _which(self, x, y):
        return _material_index(self.material, x, y, len(self.systems))

    def pixel_time(self, settings) -> float:
        """Time in s per pixel: approach and retract, 2 L / v_z, plus the move dx / v.

        Parameters
        ----------
        settings : afmsmiler.imaging.settings.ScanSettings
            The scan (pixel size and lateral speed).

        Returns
        -------
        float
        """
        from ..imaging.scanner import ScanSettings
        check_instance("settings", settings, ScanSettings)
        return 2.0 * self.lift_height / self.z_speed + settings.pixel_time

    def acquisition_time(self, settings) -> float:
        """Time in s of a whole image, trace and retrace: lines x 2 pixels x :meth:`pixel_time`.

        Parameters
        ----------
        settings : afmsmiler.imaging.settings.ScanSettings
            The scan.

        Returns
        -------
        float
            Compare with contact mode's ``settings.scan_time`` (lines (2 pixels - 1) dx / v).
        """
        pixel = self.pixel_time(settings)  # checks settings first
        return settings.lines * 2 * settings.pixels * pixel

    def line(self, plan: ScanPlan, row: int, state=None) -> ModeLine:
        """One line: height, adhesion and lateral force at each pixel, trace and retrace.

        Parameters
        ----------
        plan : afmsmiler.imaging.scan_modes.ScanPlan
            The scan.
        row : int
            Line index.
        state : float or None
            Height in m of the lifted tip after the previous line (None: it starts above
            everything).

        Returns
        -------
        afmsmiler.imaging.scan_modes.ModeLine
            With a :class:`~afmsmiler.imaging.scan_modes.Crash` where the apex surface at the next
            pixel rises above the lifted tip (the tip runs into the feature's side).

        Raises
        ------
        TypeError
            If ``plan`` is not a ScanPlan or ``state`` neither None nor a number.
        ValueError
            If ``row`` is not a line of the plan or ``state`` is not finite.
        """
        row = self._row(plan, row)
        if state is not None and not isinstance(state, (float, np.floating)):
            raise TypeError(f"state must be None or the lifted tip's height in m, got "
                            f"{type(state).__name__}")
        if state is not None and not math.isfinite(state):
            raise ValueError(f"state must be None or the lifted tip's height in m (finite), "
                             f"got {state!r}")
        n = plan.shape[1]
        r = np.concatenate((plan.trace[row], plan.retrace[row][::-1]))  # in pass order
        m = np.concatenate((self._which(plan.x_trace[row], plan.y_trace[row]),
                            self._which(plan.x_retrace[row], plan.y_retrace[row])[::-1]))
        h_t = r - self.trigger[m]            # positioner height at the trigger
        lifted = h_t + self.lift_height     # and lifted, for the move to the next pixel
        before = np.concatenate(([math.inf if state is None else state], lifted[:-1]))
        hit = r > before
        height = h_t + self.trigger[0]
        adhesion = self.pull_off[m].astype(float)
        lateral = np.zeros(2 * n)
        crash = None
        if hit.any():
            k = int(np.argmax(hit))
            direction = DIRECTIONS[k // n]
            column = k if k < n else 2 * n - 1 - k
            crash = Crash(int(row), int(column), math.inf, direction)
            for values in (height, adhesion, lateral):
                values[k:] = np.nan
        out = {}
        for name, values in (("height", height), ("adhesion", adhesion),
                             ("lateral force", lateral)):
            out[f"{name} trace"] = values[:n]
            out[f"{name} retrace"] = values[n:][::-1].copy()
        return ModeLine(out, float(lifted[-1]), crash)


@dataclass(frozen=True)
class ModeComparison:
    """Jumping and contact mode on one sample (:func:`compare_with_contact`), SI units.

    Arrays are (lines, pixels) trace images.

    Parameters
    ----------
    true_height : numpy.ndarray
        The apex surface, the sample dilated by the tip (module (f)): the best image a tip of
        that shape can give.
    jumping_height, contact_height : numpy.ndarray
        The height channels of the two modes in m.
    jumping_lateral, contact_lateral : numpy.ndarray
        Lateral force in N: 0 for jumping (it moves in the air), the friction loop's trace for
        contact mode (friction on the load plus the adhesion, and the slope term).
    normal_force : float
        Contact mode's load in N: the setpoint force k_c R plus the pull-off force.
    jumping_time, contact_time : float
        Acquisition time of each image in s.
    crashed : object
        The jumping scan's :class:`~afmsmiler.imaging.scan_modes.Crash` (lift too small), or None.
    """

    true_height: np.ndarray = field(repr=False)
    jumping_height: np.ndarray = field(repr=False)
    contact_height: np.ndarray = field(repr=False)
    jumping_lateral: np.ndarray = field(repr=False)
    contact_lateral: np.ndarray = field(repr=False)
    normal_force: float
    jumping_time: float
    contact_time: float
    crashed: object = None

    @property
    def jumping_error(self) -> float:
        """Largest |height - true height| in m of the jumping image (NaN pixels left out)."""
        return float(np.nanmax(np.abs(self.jumping_height - self.true_height)))

    @property
    def contact_error(self) -> float:
        """Largest |height - true height| in m of the contact-mode image."""
        return float(np.nanmax(np.abs(self.contact_height - self.true_height)))

    @property
    def contact_lateral_max(self) -> float:
        """Largest |lateral force| in N contact mode exerts (at the steepest edge)."""
        return float(np.max(np.abs(self.contact_lateral)))


def compare_with_contact(sample, tip, settings, *, system: ContactSystem, loop=None,
                         setpoint: float | None = None, friction_coefficient: float = 0.2,
                         trigger_force: float = TRIGGER_FORCE.default,
                         lift_height: float = LIFT_HEIGHT.default,
                         z_speed: float = Z_SPEED.default) -> ModeComparison:
    """Scan one sample in jumping mode and in contact mode and compare heights, forces, time.

    Parameters
    ----------
    sample : afmsmiler.samples.Sample
        The sample (2-D heights in m).
    tip : afmsmiler.contact.Tip
        The tip (the systems' tip: it blurs and touches).
    settings : afmsmiler.imaging.settings.ScanSettings
        The scan (the same for both modes).
    system : afmsmiler.contact.ContactSystem
        The contact of jumping mode's curves (its pull-off force adds to contact mode's load).
    loop : afmsmiler.controller.ContactLoop, optional
        Contact mode's feedback loop (default: module (c)'s defaults).
    setpoint : float, optional
        Contact mode's deflection setpoint R in m (default: module (c)'s).
    friction_coefficient : float
        mu of the sample for contact mode's lateral force (module (g)'s lateral model).
    trigger_force : float
        Jumping mode's trigger F_t in N.
    lift_height : float
        Jumping mode's lift L in m.
    z_speed : float
        Jumping mode's approach and retract speed in m/s.

    Returns
    -------
    ModeComparison

    Raises
    ------
    TypeError, ValueError
        As :class:`JumpingMode`, :class:`~afmsmiler.imaging.scan_modes.ConstantForce`,
        :func:`~afmsmiler.imaging.scanner.scan` and
        :func:`~afmsmiler.modes.lateral.friction_loop`, before any scan.
    """
    from ..controller import PARAMETERS as LOOP_PARAMETERS
    from ..controller import ContactLoop
    from ..imaging.scan_modes import ConstantForce
    from ..imaging.scanner import Scan, ScanSettings
    from .lateral import FRICTION_COEFFICIENT, friction_loop

    check_instance("settings", settings, ScanSettings)
    loop = ContactLoop() if loop is None else check_instance("loop", loop, ContactLoop)
    r = LOOP_PARAMETERS["setpoint"].default if setpoint is None else setpoint
    mu = FRICTION_COEFFICIENT.check(friction_coefficient)
    jumping = JumpingMode(system, trigger_force=trigger_force, lift_height=lift_height,
                          z_speed=z_speed)
    contact_mode = ConstantForce(loop, setpoint=r)
    normal_force = loop.k_c * contact_mode.setpoint + system.pull_off_force
    if normal_force <= 0:
        raise ValueError(f"setpoint must press the tip on the sample (k_c R + pull-off force "
                         f"> 0), got a load of {normal_force:g} N")
    scan_j = Scan(sample, tip, jumping, settings)
    scan_c = Scan(sample, tip, contact_mode, settings)
    result_j, result_c = scan_j.run(), scan_c.run()
    truth = scan_j.plan.trace
    lateral = np.array([friction_loop(row, mu, settings.pixel_size,
                                      normal_force=normal_force).trace for row in truth])
    return ModeComparison(truth, result_j.images["height trace"],
                          result_c.images["height trace"],
                          result_j.images["lateral force trace"], lateral, normal_force,
                          jumping.acquisition_time(settings), settings.scan_time,
                          result_j.crashed)
