"""Imaging modes: what the tip does at each pixel of a line, behind one interface.

The scanner (:mod:`afmsmiler.imaging.scanner`) decides where the tip is and when: it dilates
the sample by the tip, samples the apex surface along every line (trace and retrace, with the
scan angle, offset, drift and creep of its :class:`~afmsmiler.imaging.settings.ScanSettings`) and
hands the result to a mode as a :class:`ScanPlan`. A :class:`Mode` turns the plan's lines into
channels, one line at a time. Two modes live here:

- :class:`ConstantForce`: module (c)'s feedback loop (:class:`~afmsmiler.controller.ContactLoop`)
  keeps the deflection at its setpoint; the height image is the positioner's motion and the error
  channel the deflection minus the setpoint. Trace and retrace of every line are one polygon in
  time, each line continuing from the state the previous retrace left, exactly as
  :func:`afmsmiler.controller.scan_image` computes it (same numbers).
- :class:`ConstantHeight`: the lever's base is held at one height and module (d)'s contact
  solver (:class:`~afmsmiler.contact.ContactSystem`) gives the deflection at every pixel; the tip
  crashes when the force passes a damage threshold (the line and the scan stop there).

Writing a new mode (module (g) adds tapping, jumping and force-volume this way, without touching
the scanner): subclass :class:`Mode`, list the channel names it produces in ``channels`` (and
their SI units in ``units`` when not m), and implement :meth:`Mode.line`, which receives the plan,
a row index and the state the previous line returned, and gives back a :class:`ModeLine` (the
line's channels, the state for the next line, and a :class:`Crash` if the tip broke).
:meth:`Mode.start` runs once before the first line (precompute there). The scanner adds sensor
noise to every channel in m and assembles the images; a mode never sees noise or the images.
"""
from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any, ClassVar, Mapping

import numpy as np

from ..contact import ContactSystem
from ..contact import PARAMETERS as CONTACT_PARAMETERS
from ..controller import PARAMETERS as LOOP_PARAMETERS
from ..controller import ContactLoop, scan_image
from ..controller.polygon import polygon_response
from ..parameters import Parameter, read_only
from ..validation import check_choice, check_instance, check_integer

__all__ = ["Mode", "ScanPlan", "ModeLine", "Crash", "ConstantForce", "ConstantHeight",
           "PARAMETERS", "DIRECTIONS"]

#: The two passes over a line, in scan order.
DIRECTIONS = ("trace", "retrace")

#: The modes' user-settable quantities that no other module describes: the force in N beyond
#: which a tip in constant-height mode is damaged (a silicon tip of 10 nm radius blunts above
#: some 10 nN to 100 nN). The setpoint (module (c)) and z_np (module (d)) are described there.
PARAMETERS = read_only({p.name: p for p in (
    Parameter(name="damage_force", unit="N", display_unit="nN", default=100e-9, low=0.0,
              high=1.0, low_inclusive=False, slider_low=1e-9, slider_high=1e-6, log=True,
              label="damage force"),
)})


@dataclass(frozen=True)
class ScanPlan:
    """Everything the scanner hands a mode: where the tip goes, when, and what it meets there.

    Arrays are (lines, pixels), rows along the slow axis, columns along the fast axis in
    increasing x for both passes (the retrace runs from the last column to the first in time).

    Parameters
    ----------
    trace, retrace : numpy.ndarray
        Height in m of the apex surface (the sample dilated by the tip, tilt included) under the
        apex at each pixel of each pass.
    t_trace, t_retrace : numpy.ndarray
        Time in s since the start of the scan at which the tip is at each pixel: line i's trace
        starts at i (2 pixels - 1) pixel times, its retrace starts at the trace's last pixel
        (shared) and the step to the next line takes one pixel time (as in
        :func:`afmsmiler.controller.scan_image`).
    x_trace, y_trace, x_retrace, y_retrace : numpy.ndarray
        Position of the apex on the sample in m (from the sample's first pixel), drift and
        creep included.
    pixel_size, pixel_size_y : float
        Pixel spacing in m of the image along the fast and the slow axis.
    scan_speed : float
        Tip speed along the fast axis in m/s.
    apex : afmsmiler.samples.Sample
        The apex surface that was sampled, on the sample's grid: the part of it the scan can
        feel (the scan's bounding box widened by the tip's reach), from ``apex_origin`` on.
    tip : afmsmiler.contact.Tip or None
        The tip (None: an ideal, infinitely sharp one).
    settings : afmsmiler.imaging.settings.ScanSettings
        The settings of the scan.
    apex_origin : tuple of float
        (x, y) in m of ``apex``'s first pixel on the sample.
    """

    trace: np.ndarray
    retrace: np.ndarray
    t_trace: np.ndarray
    t_retrace: np.ndarray
    x_trace: np.ndarray
    y_trace: np.ndarray
    x_retrace: np.ndarray
    y_retrace: np.ndarray
    pixel_size: float
    pixel_size_y: float
    scan_speed: float
    apex: Any
    tip: Any
    settings: Any
    apex_origin: tuple = (0.0, 0.0)

    @property
    def shape(self) -> tuple[int, int]:
        """(lines, pixels) of the image."""
        return self.trace.shape

    @property
    def pixel_time(self) -> float:
        """Time in s from one pixel to the next (pixel_size / scan_speed)."""
        return self.pixel_size / self.scan_speed


@dataclass(frozen=True)
class Crash:
    """Where and how hard the tip hit the sample (the scan stopped there).

    Parameters
    ----------
    row, column : int
        The pixel (line index, column index) at which |force| first passed the threshold.
    force : float
        The force there in N (signed; inf when the tip would have been buried, or when an
        unstable loop's signals overflowed).
    direction : str
        ``"trace"`` or ``"retrace"``.
    """

    row: int
    column: int
    force: float
    direction: str = "trace"


@dataclass(frozen=True)
class ModeLine:
    """One line as a mode computed it.

    Parameters
    ----------
    channels : Mapping
        Channel name -> 1-D array (pixels,) in the channel's SI unit, columns in increasing x
        (a retrace too). After a crash, the pixels not reached hold NaN.
    state : object
        Whatever the mode needs for the next line (handed back to :meth:`Mode.line`).
    crash : Crash or None
        Set when the tip crashed on this line: the scanner keeps the pixels reached, does not
        count the line as finished and stops the scan.
    """

    channels: Mapping
    state: Any = None
    crash: Crash | None = None


def _short(value) -> str:
    """``repr(value)`` cut to a line, for a message."""
    text = repr(value)
    return text if len(text) <= 80 else text[:77] + "..."


class Mode(ABC):
    """An imaging mode: turns the apex surface along each line into channels.

    Subclasses set ``channels`` (names, e.g. ``("height trace", "height retrace")``) and, for
    channels not in m, ``units`` (name -> SI unit), and implement :meth:`line`; they may override
    :meth:`start` to precompute. ``tip`` is the tip the mode's own physics uses, if any (the
    scanner checks that it is the tip it dilates with).

    Examples
    --------
    A mode that records the apex surface itself (an ideal, infinitely fast feedback) and counts
    its lines in its state:

    >>> import numpy as np
    >>> from afmsmiler.samples import Sample
    >>> from afmsmiler.imaging.scanner import ScanSettings, scan
    >>> class Ideal(Mode):
    ...     channels = ("height trace", "lines so far")
    ...     units = {"lines so far": ""}
    ...     def line(self, plan, row, state):
    ...         count = (state or 0) + 1
    ...         return ModeLine({"height trace": plan.trace[row],
    ...                          "lines so far": np.full(plan.shape[1], count)}, count)
    >>> sample = Sample(np.arange(64.0).reshape(8, 8) * 1e-9, 1e-9)
    >>> result = scan(sample, None, Ideal(), ScanSettings(8e-9, pixels=8, scan_speed=1e-6))
    >>> bool(np.array_equal(result.images["height trace"], sample.heights))
    True
    >>> result.images["lines so far"][:, 0]
    array([1., 2., 3., 4., 5., 6., 7., 8.])
    """

    #: Names of the channels the mode produces, in the order a panel shows them.
    channels: ClassVar[tuple[str, ...]] = ()
    #: The channel that is the mode's image (what a panel shows first); default the first one.
    main_channel: ClassVar[str | None] = None
    #: SI unit of each channel that is not in m.
    units: ClassVar[Mapping[str, str]] = MappingProxyType({})
    #: The tip of the mode's own physics (None: the mode does not model one).
    tip = None

    def unit(self, channel: str) -> str:
        """SI unit of a channel ("m" unless ``units`` says otherwise).

        Parameters
        ----------
        channel : str
            One of :attr:`channels`.

        Returns
        -------
        str

        Raises
        ------
        ValueError
            If ``channel`` is not one of :attr:`channels`.
        """
        check_choice("channel", channel, self.channels)
        return self.units.get(channel, "m")

    def start(self, plan: ScanPlan) -> Any:
        """Called once before the first line; returns the state handed to line 0.

        Parameters
        ----------
        plan : ScanPlan
            The whole scan's geometry and apex heights.

        Returns
        -------
        object
            The state for :meth:`line` (default None).

        Raises
        ------
        TypeError
            If ``plan`` is not a :class:`ScanPlan`.
        """
        check_instance("plan", plan, ScanPlan)
        return None

    @staticmethod
    def _row(plan: ScanPlan, row) -> int:
        """``row`` checked to be a line of ``plan`` (after checking ``plan``), as an int."""
        check_instance("plan", plan, ScanPlan)
        return check_integer("row", row, 0, plan.shape[0] - 1)

    @abstractmethod
    def line(self, plan: ScanPlan, row: int, state: Any) -> ModeLine:
        """Scan line ``row`` (trace then retrace).

        Parameters
        ----------
        plan : ScanPlan
            The scan.
        row : int
            Line index, 0 to lines - 1, called in increasing order.
        state : object
            What :meth:`start` (for row 0) or the previous line's :class:`ModeLine` returned.

        Returns
        -------
        ModeLine
        """


class ConstantForce(Mode):
    """Constant-force contact mode through module (c)'s feedback loop.

    Parameters
    ----------
    loop : afmsmiler.controller.ContactLoop
        Lever, sample and PID gains.
    setpoint : float
        Deflection setpoint R in m (module (c)'s ``setpoint``; keyword-only).

    Raises
    ------
    TypeError
        If ``loop`` is not a ContactLoop.
    ValueError
        If ``setpoint`` is out of its range.

    Notes
    -----
    Channels: ``"height trace"``/``"height retrace"``, the positioner's motion
    -(Z_np - Z_np,flat) (Z_np,flat: its height at equilibrium over a flat sample at 0), which
    equals the apex surface once the loop has settled; ``"error trace"``/``"error retrace"``, the
    deflection minus the setpoint Z_c - R (the error signal the loop acts on).

    The whole scan is one polygon in time (trace 0, retrace 0, trace 1, ...), solved in one call
    of :func:`afmsmiler.controller.scan_image` when the mode starts (O(lines x pixels), some
    20 ms for 256 x 256): module (c)'s closed-form recursion carries its state internally and
    cannot resume from a given one, and running it again over all earlier lines at every line
    would cost O(lines^2 x pixels). :meth:`line` then hands out row by row, so a scan run line by
    line gives bitwise the numbers of the whole image in one call. When drift or creep make the
    retrace pass over other points than the trace, the same chained polygon goes through module
    (c)'s solver directly (:func:`afmsmiler.controller.polygon.polygon_response`, as in
    ``scan_image``), with the retrace's own heights.

    An unstable loop (:meth:`ContactLoop.is_stable`) still scans, as in module (c): its signals
    grow until they overflow. The line on which they stop being finite is a :class:`Crash` (the
    tip, driven by a diverging loop, hits the sample): the scan stops there with force inf, the
    pixels from there on are NaN, and the finished lines are kept.
    """

    channels = ("height trace", "height retrace", "error trace", "error retrace")
    main_channel = "height trace"

    def __init__(self, loop: ContactLoop, *, setpoint: float = LOOP_PARAMETERS["setpoint"].default):
        self.loop = check_instance("loop", loop, ContactLoop)
        self.setpoint = LOOP_PARAMETERS["setpoint"].check(setpoint)

    def __repr__(self) -> str:
        return f"ConstantForce({self.loop!r}, setpoint={self.setpoint!r})"

    def start(self, plan: ScanPlan) -> dict:
        """Run the whole scan through the loop (see the class notes); returns the images.

        Parameters
        ----------
        plan : ScanPlan
            The scan.

        Returns
        -------
        dict
            Channel name -> (lines, pixels) array.

        Raises
        ------
        TypeError
            If ``plan`` is not a :class:`ScanPlan`.
        """
        check_instance("plan", plan, ScanPlan)
        with np.errstate(over="ignore", invalid="ignore"):  # an unstable loop: see line()
            return self._images(plan)

    def _images(self, plan: ScanPlan) -> dict:
        loop, setpoint = self.loop, self.setpoint
        if np.array_equal(plan.trace, plan.retrace):
            image = scan_image(loop, plan.trace, plan.pixel_size, speed=plan.scan_speed,
                               setpoint=setpoint)
            z_np_t, z_np_r = image.trace_z_np, image.retrace_z_np
            z_c_t, z_c_r = image.trace + z_np_t, image.retrace + z_np_r
            z_np_flat = image.z_np_flat
        else:
            lines, n = plan.shape
            path = np.concatenate((plan.trace, plan.retrace[:, ::-1][:, 1:]), axis=1).ravel()
            t = np.arange(path.size) * plan.pixel_time
            forms = loop.closed_forms("step"), loop.closed_forms("ramp")
            z_c, z_np = polygon_response(*forms, t, path - path[0], None, uniform=True)
            zc0, znp0 = loop.steady_state(setpoint, 0.0)
            zc1, znp1 = loop.steady_state(setpoint, 1.0)
            z_c = (z_c + zc0 + (zc1 - zc0) * path[0]).reshape(lines, 2 * n - 1)
            z_np = (z_np + znp0 + (znp1 - znp0) * path[0]).reshape(lines, 2 * n - 1)
            z_c_t, z_c_r = z_c[:, :n], z_c[:, n - 1:][:, ::-1]
            z_np_t, z_np_r = z_np[:, :n], z_np[:, n - 1:][:, ::-1]
            z_np_flat = float(znp0)
        return {"height trace": -(z_np_t - z_np_flat), "height retrace": -(z_np_r - z_np_flat),
                "error trace": z_c_t - setpoint, "error retrace": z_c_r - setpoint}

    def line(self, plan: ScanPlan, row: int, state: dict) -> ModeLine:
        """Row ``row`` of the images computed by :meth:`start`.

        Parameters
        ----------
        plan : ScanPlan
            The scan.
        row : int
            Line index.
        state : dict
            The images from :meth:`start`.

        Returns
        -------
        ModeLine
            Its channels are views of ``state`` (the scanner copies them); where an unstable
            loop's signals overflowed, a :class:`Crash` (force inf) and NaN from that pixel on.

        Raises
        ------
        TypeError
            If ``plan`` is not a ScanPlan or ``state`` not what :meth:`start` returned.
        ValueError
            If ``row`` is not a line of the plan, or ``state`` holds images of another shape.
        """
        row = self._row(plan, row)
        if not isinstance(state, Mapping) or set(state) != set(self.channels):
            raise TypeError(f"state must be the images ConstantForce.start returned (a mapping "
                            f"of the channels {list(self.channels)}), got {_short(state)}")
        for name in self.channels:
            shape = np.shape(state[name])
            if shape != plan.shape:
                raise ValueError(f"state must hold images of the plan's shape {plan.shape}, got "
                                 f"{name!r} of shape {shape}")
        channels = {name: state[name][row] for name in self.channels}
        passes = {d: [name for name in self.channels if name.endswith(" " + d)]
                  for d in DIRECTIONS}
        # where a diverging loop first overflowed, in scan order (trace, then retrace backwards)
        bad = [np.logical_or.reduce([~np.isfinite(channels[name]) for name in passes[d]])
               for d in DIRECTIONS]
        bad = np.concatenate((bad[0], bad[1][::-1]))
        if not bad.any():
            return ModeLine(channels, state)
        n = plan.shape[1]
        k = int(np.argmax(bad))
        direction = DIRECTIONS[k // n]
        column = k if k < n else 2 * n - 1 - k
        channels = {name: values.copy() for name, values in channels.items()}
        not_reached = {"trace": (slice(column, None), slice(None)),
                       "retrace": (None, slice(None, column + 1))}[direction]
        for d, cut in zip(DIRECTIONS, not_reached):
            for name in passes[d] if cut is not None else ():
                channels[name][cut] = np.nan
        return ModeLine(channels, state, Crash(row, column, math.inf, direction))


class ConstantHeight(Mode):
    """Constant-height contact mode: the lever's base held still, the deflection recorded.

    Parameters
    ----------
    system : afmsmiler.contact.ContactSystem
        Tip, lever spring constant, sample and adhesion (module (d)).
    z_np : float
        Positioner displacement Z_np in m over the sample's height 0: at a pixel where the apex
        surface is at height r, the tip meets the sample as module (d)'s contact at
        Z_np = z_np + r (Z_np <= 0: out of contact, no force without adhesion).
    damage_force : float
        Force in N beyond which the tip is damaged (|F| > damage_force crashes the scan).

    Raises
    ------
    TypeError
        If ``system`` is not a ContactSystem.
    ValueError
        If ``z_np`` or ``damage_force`` is out of range.

    Notes
    -----
    Channels ``"deflection trace"``/``"deflection retrace"``: Z_c = F / k in m, module (d)'s
    quasi-static state at every pixel (the lever follows the contact without dynamics). The tip
    touches where the apex surface is; the dilated surface already holds the contact geometry of
    the tip's flanks, the solver adds the indentation at the apex.

    Elastic (``adhesion=None``): :meth:`ContactSystem.indent` at Z_np = z_np + r, pixel by pixel.
    With DMT or JKR adhesion the state depends on the path: the tip touches down where
    Z_np >= 0 (the approach branch) and, once in contact, stays stuck until Z_np falls below
    the snap-off :attr:`ContactSystem.snap_off_z_np` (the retract branch), along the scan order
    (trace, retrace, next line), as :meth:`ContactSystem.approach_retract` gives it on a ramp.

    When |F| first exceeds ``damage_force`` (in scan order, trace then retrace) the line stops at
    that pixel (the later ones are NaN) and the scan stops: a :class:`Crash`. A sphere that would
    be buried beyond its radius crashes too (force inf).
    """

    channels = ("deflection trace", "deflection retrace")
    main_channel = "deflection trace"

    def __init__(self, system: ContactSystem, z_np: float = CONTACT_PARAMETERS["z_np"].default,
                 damage_force: float = PARAMETERS["damage_force"].default):
        self.system = check_instance("system", system, ContactSystem)
        self.z_np = CONTACT_PARAMETERS["z_np"].check(z_np)
        self.damage_force = PARAMETERS["damage_force"].check(damage_force)
        self.tip = system.tip

    def __repr__(self) -> str:
        return (f"ConstantHeight({self.system!r}, z_np={self.z_np!r}, "
                f"damage_force={self.damage_force!r})")

    def _states(self, z, contact):
        """Deflection and force at Z_np = z (scan order), from the contact state before."""
        sy = self.system
        force = np.full(z.shape, math.inf)
        deflection = np.full(z.shape, math.inf)
        ok = z < sy.z_np_limit
        if sy.adhesion is None:
            curve = sy.indent(z[ok])
            force[ok], deflection[ok] = curve.force, curve.z_c
            return deflection, force, contact
        ramp = np.unique(z[ok])
        if ramp.size == 1:  # approach_retract needs a ramp: add a point below (as ``at`` does)
            ramp = np.concatenate((ramp - max(1e-9, 1e-9 * abs(ramp[0])), ramp))
        if ramp.size:
            cycle = sy.approach_retract(ramp)
            stuck = cycle.retract.in_contact[::-1]  # on the ramp's points, increasing z
            f_in, zc_in = cycle.retract.force[::-1], cycle.retract.z_c[::-1]
            f_out, zc_out = cycle.approach.force, cycle.approach.z_c
        if not ramp.size:
            return deflection, force, contact
        # along the pixels in scan order, contact_k = z_k >= 0 or (contact_(k-1) and stuck there):
        # a latch, set where z >= 0 and reset where it is out of contact on both branches; in
        # contact wherever the last set comes after the last reset (the previous line's contact
        # counts as a set before the first pixel)
        zk = z[ok]
        i = np.searchsorted(ramp, zk)
        sets = zk >= 0.0
        resets = ~sets & ~stuck[i]
        index = np.arange(zk.size)
        last_set = np.maximum.accumulate(np.where(sets, index, -1 if contact else -2))
        last_reset = np.maximum.accumulate(np.where(resets, index, -2))
        touching = last_set > last_reset
        force[ok] = np.where(touching, f_in[i], f_out[i])
        deflection[ok] = np.where(touching, zc_in[i], zc_out[i])
        return deflection, force, bool(touching[-1])

    def line(self, plan: ScanPlan, row: int, state: Any = None) -> ModeLine:
        """Deflection along line ``row``, trace and retrace; a :class:`Crash` if the tip broke.

        Parameters
        ----------
        plan : ScanPlan
            The scan.
        row : int
            Line index.
        state : object
            Whether the tip was in contact at the end of the previous line (None before the
            first: not in contact).

        Returns
        -------
        ModeLine

        Raises
        ------
        TypeError
            If ``plan`` is not a ScanPlan or ``state`` neither None nor a bool.
        ValueError
            If ``row`` is not a line of the plan.
        """
        row = self._row(plan, row)
        if state is not None and not isinstance(state, (bool, np.bool_)):
            raise TypeError(f"state must be None or a bool (in contact at the end of the "
                            f"previous line), got {_short(state)}")
        n = plan.shape[1]
        z = self.z_np + np.concatenate((plan.trace[row], plan.retrace[row][::-1]))  # scan order
        deflection, forces, contact = self._states(z, bool(state))
        over = np.abs(forces) > self.damage_force
        crash = None
        if over.any():
            k = int(np.argmax(over))
            direction = DIRECTIONS[k // n]
            column = k if k < n else 2 * n - 1 - k
            crash = Crash(int(row), int(column), float(forces[k]), direction)
            deflection[k + 1:] = np.nan
            if not np.isfinite(deflection[k]):  # a sphere buried: no deflection to show
                deflection[k] = np.nan
        return ModeLine({"deflection trace": deflection[:n],
                         "deflection retrace": deflection[n:][::-1].copy()}, contact, crash)
