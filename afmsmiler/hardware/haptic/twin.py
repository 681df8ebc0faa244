"""The haptic device's twin: the firmware's control loop, its motor and a finger on the handle.

:class:`HapticTwin` runs what ``hardware/haptic/haptic.ino`` runs, tick by tick (one tick =
:data:`TICK` = 1 ms, the firmware's 1 kHz loop), against a model of the mechanics:

- the handle (a capstan-driven sector, reflected moving mass ``handle_mass`` and viscous
  friction ``handle_damping``) read by a quadrature encoder of ``resolution`` metres a count at
  the handle (the position is quantised to whole counts);
- the motor in current mode: the amplifier follows the commanded current with a first-order lag
  of bandwidth ``amplifier_bandwidth`` (Hz) and saturates at the current limit; the force on the
  handle is ``force_constant`` (N/A) times the current;
- a finger pressing on the handle, a mass-spring-damper about its rest position x = 0 (Hajian and
  Howe, J. Biomech. Eng. 119, 109 (1997): at the fingertip, an effective mass of a few grams,
  damping of a few N s/m and a stiffness of a few hundred N/m, growing with the grip force;
  :class:`Finger`'s defaults lie in those ranges).

Between ticks the motor current command is constant and the mechanics are linear, so each tick
advances the state (x, v, i) exactly with the matrix exponential (zero-order hold).

The firmware's force each tick (SI here, integers on the board)::

    F = FS * F_stream + F_spring + F_wall + F_q,          clipped to +-MF (flag SATURATED)
    F_spring = -KS x,    F_wall = -KW (x - XW) for x > XW
    F_q = g_c KS [cos(phi_c) x_f - sin(phi_c) v_f / w_ref]

with x_f, v_f the centred position and the backward-difference velocity through a first-order
low-pass of cut-off VF. The firmware compensates its own estimator's and output's lag at the
reference frequency: phi_c = phi + arg H(w_ref), g_c = g / |H(w_ref)|, H the low-pass times
e^{-i w T} (half a tick for the difference, half for the zero-order hold) times the
amplifier's 1 / (1 + i w / w_a); so at w_ref the feedback is exactly g KS e^{-i phi} x, the Q
controller of :mod:`afmsmiler.modes.qcontrol` with gain g KS / k_total.

E-stop (``ES`` or :meth:`HapticTwin.press_estop`) and the travel limit zero the current and go to
FAULT; no ``FO`` frame for WD ms while ACTIVE zeroes the current and goes to IDLE (event
WATCHDOG), so a host that dies leaves the finger free.
"""
from __future__ import annotations

import cmath
import math
from dataclasses import dataclass

import numpy as np

from ...validation import check_finite, check_nonnegative, check_positive
from scipy.linalg import expm

from ..framing import Frame, event_frame
from ..twin import Twin
from ..errors import ErrorCode
from .codec import (DEVICE, FIRMWARE_VERSION, PARAMETERS, Command, Event, Flag, Param,
                    force_from_wire, position_frame, status_results)

__all__ = ["HapticTwin", "Finger", "Mechanics", "TICK", "MAX_TICKS_PER_POLL"]

#: The firmware's control period in s (1 kHz loop).
TICK = 1e-3
#: Most ticks one :meth:`HapticTwin.poll` simulates (10 s); a clock that jumped further is
#: followed by skipping the rest (the twin's clock is never more than this behind).
MAX_TICKS_PER_POLL = 10_000


@dataclass(frozen=True)
class Finger:
    """A fingertip on the handle: mass-spring-damper about x = 0 (Hajian and Howe 1997).

    Parameters
    ----------
    mass : float
        Effective mass in kg.
    stiffness : float
        Stiffness in N/m.
    damping : float
        Damping in N s/m.
    """

    mass: float = 0.006
    stiffness: float = 300.0
    damping: float = 2.0

    def __post_init__(self):
        for name, unit in (("mass", "kg"), ("stiffness", "N/m")):
            object.__setattr__(self, name, check_positive(name, getattr(self, name), unit))
        object.__setattr__(self, "damping", check_nonnegative("damping", self.damping, "N s/m"))


@dataclass(frozen=True)
class Mechanics:
    """The device's mechanics and electronics (a maxon DCX 22 S on a 15:1 capstan, 75 mm sector).

    Parameters
    ----------
    handle_mass : float
        Moving mass reflected to the handle in kg (rotor inertia times 15^2 / r^2 plus sector).
    handle_damping : float
        Viscous friction at the handle in N s/m.
    resolution : float
        Encoder resolution at the handle in m per count (1024-line encoder, x4, 15:1, 75 mm).
    force_constant : float
        Force on the handle per motor current in N/A (k_t 15 / 0.075 m).
    current_limit : float
        Amplifier current limit in A.
    amplifier_bandwidth : float
        Current loop bandwidth in Hz (first-order).
    """

    handle_mass: float = 0.015
    handle_damping: float = 0.05
    resolution: float = PARAMETERS[Param.RESOLUTION].to_si(PARAMETERS[Param.RESOLUTION].default)
    force_constant: float = PARAMETERS[Param.FORCE_CONSTANT].to_si(
        PARAMETERS[Param.FORCE_CONSTANT].default)
    current_limit: float = PARAMETERS[Param.CURRENT_LIMIT].to_si(
        PARAMETERS[Param.CURRENT_LIMIT].default)
    amplifier_bandwidth: float = 1000.0

    def __post_init__(self):
        for name in ("handle_mass", "handle_damping", "resolution", "force_constant",
                     "current_limit", "amplifier_bandwidth"):
            value = getattr(self, name)
            check = check_nonnegative if name == "handle_damping" else check_positive
            object.__setattr__(self, name, check(name, value))


class HapticTwin(Twin):
    """The haptic device, simulated: protocol, firmware loop, motor, encoder and finger.

    Parameters
    ----------
    finger : Finger or None
        The finger on the handle (None: a free handle).
    mechanics : Mechanics
        The device's mechanics and electronics.

    Attributes
    ----------
    state : str
        ``"IDLE"``, ``"ACTIVE"`` or ``"FAULT"``.
    external_force : float
        A force in N pushed on the handle from outside (the student's hand beyond the finger
        model), constant until changed.
    """

    DEVICE = DEVICE
    FIRMWARE_VERSION = FIRMWARE_VERSION

    def __init__(self, finger: Finger | None = Finger(), mechanics: Mechanics = Mechanics()):
        super().__init__()
        if finger is not None and not isinstance(finger, Finger):
            raise TypeError(f"finger must be a Finger or None, got {type(finger).__name__}")
        if not isinstance(mechanics, Mechanics):
            raise TypeError(f"mechanics must be a Mechanics, got {type(mechanics).__name__}")
        self.finger = finger
        self.mechanics = mechanics
        self.params = {p: spec.default for p, spec in PARAMETERS.items()}
        for p, value in ((Param.RESOLUTION, mechanics.resolution),
                         (Param.FORCE_CONSTANT, mechanics.force_constant),
                         (Param.CURRENT_LIMIT, mechanics.current_limit)):
            self.params[p] = PARAMETERS[p].to_wire(value)
        self.state = "IDLE"
        self.external_force = 0.0
        self.flags = Flag(0)
        self._x = np.zeros(3)  # position m, velocity m/s, current A
        self._ticks = 0        # ticks simulated since boot
        self._offset = 0       # encoder count of the position called zero
        self._stream_ticks = 0
        self._next_stream = None
        self._last_force = -math.inf
        self._stream_force = 0.0
        self._command = 0.0    # force last asked of the motor, N
        self._prev = 0         # previous encoder count
        self._xf = 0.0
        self._vf = 0.0
        self._fault_code = ErrorCode.STATE
        self._events = [event_frame(Event.BOOT)]
        self._discretise()
        self._compensate()

    # -- the mechanics ---------------------------------------------------------------------
    @property
    def moving_mass(self) -> float:
        """Handle plus finger mass in kg."""
        return self.mechanics.handle_mass + (self.finger.mass if self.finger else 0.0)

    def _discretise(self):
        mech, f = self.mechanics, self.finger
        m = self.moving_mass
        c = mech.handle_damping + (f.damping if f else 0.0)
        k = f.stiffness if f else 0.0
        wa = 2.0 * math.pi * mech.amplifier_bandwidth
        a = np.array([[0.0, 1.0, 0.0],
                      [-k / m, -c / m, mech.force_constant / m],
                      [0.0, 0.0, -wa]])
        b = np.array([[0.0, 0.0], [0.0, 1.0 / m], [wa, 0.0]])  # inputs: i_cmd, external force
        big = np.zeros((5, 5))
        big[:3, :3], big[:3, 3:] = a, b
        e = expm(big * TICK)
        self._ad, self._bd = e[:3, :3], e[:3, 3:]

    def _compensate(self):
        """g_c and phi_c from the parameters (the firmware does this on every SP)."""
        p = self.params
        f_ref = self._si(Param.QFREQ)
        w = 2.0 * math.pi * f_ref
        alpha = 1.0 - math.exp(-2.0 * math.pi * p[Param.VFILTER] * TICK)
        z = cmath.exp(-1j * w * TICK)
        h = alpha / (1.0 - (1.0 - alpha) * z) * z  # low-pass, half a tick + half a tick
        h /= 1.0 + 1j * f_ref / self.mechanics.amplifier_bandwidth
        self._alpha = alpha
        self._w_ref = w
        gain = self._si(Param.QGAIN) / abs(h)
        phase = self._si(Param.QPHASE) + cmath.phase(h)
        self._qc = gain * math.cos(phase)
        self._qs = gain * math.sin(phase) / w

    @property
    def position(self) -> float:
        """True handle position in m (not quantised)."""
        return float(self._x[0])

    @property
    def velocity(self) -> float:
        """True handle velocity in m/s."""
        return float(self._x[1])

    @property
    def current(self) -> float:
        """Motor current in A."""
        return float(self._x[2])

    def push(self, force: float) -> None:
        """Push the handle with a constant external force (the student's hand), in N.

        Parameters
        ----------
        force : float
            Force along +x in N.
        """
        self.external_force = check_finite("force", force, "N")

    def press_estop(self) -> None:
        """Press the device's emergency-stop button (as the ``ES`` command)."""
        self._fault(Event.ESTOP, Flag.ESTOP)

    # -- the firmware's tick ------------------------------------------------------------------
    def _fault(self, event, flag):
        self.state = "FAULT"
        self.flags |= flag
        self._fault_code = ErrorCode.ESTOP if flag == Flag.ESTOP else ErrorCode.LIMIT
        self._command = 0.0
        self._stream_force = 0.0
        self._events.append(event_frame(event))

    def _si(self, param) -> float:
        """The SI value of a parameter's current wire value (the table's unit)."""
        return PARAMETERS[param].to_si(self.params[param])

    def _tick(self):
        p = self.params
        res = self._si(Param.RESOLUTION)
        count = int(math.floor(self._x[0] / res + 0.5)) - self._offset
        x = count * res
        x_prev = self._prev * res
        self._xf += self._alpha * (0.5 * (x + x_prev) - self._xf)
        self._vf += self._alpha * ((x - x_prev) / TICK - self._vf)
        self._prev = count
        now_ms = self._ticks  # one tick = 1 ms
        force = 0.0
        if self.state == "ACTIVE":
            if now_ms - self._last_force > p[Param.WATCHDOG]:
                self.state = "IDLE"
                self.flags |= Flag.WATCHDOG
                self._stream_force = 0.0
                self._events.append(event_frame(Event.WATCHDOG))
            elif abs(x) > self._si(Param.TRAVEL):
                self._fault(Event.LIMIT, Flag.LIMIT)
            else:
                ks = self._si(Param.SPRING)
                force = self._stream_force * self._si(Param.FORCE_SCALE) - ks * x
                xw = self._si(Param.WALL_POSITION)
                if x > xw:
                    force -= self._si(Param.WALL_STIFFNESS) * (x - xw)
                force += ks * (self._qc * self._xf - self._qs * self._vf)
                limit = self._si(Param.MAX_FORCE)
                if abs(force) > limit:
                    force = math.copysign(limit, force)
                    self.flags |= Flag.SATURATED
        self._command = force
        i_cmd = force / self.mechanics.force_constant
        lim = self.mechanics.current_limit
        i_cmd = max(-lim, min(lim, i_cmd))
        self._x = self._ad @ self._x + self._bd @ np.array([i_cmd, self.external_force])
        self._ticks += 1
        return x

    def _position_frame(self, x):
        return position_frame(x, self._vf, self._ticks * TICK)

    # -- the Twin protocol --------------------------------------------------------------------
    def poll(self, now: float) -> list[Frame]:
        """Run the firmware's ticks due by ``now`` (s); the PO and EV frames they sent.

        Parameters
        ----------
        now : float
            The twin's clock in s.

        Returns
        -------
        list of Frame
        """
        super().poll(now)
        out = self._take_events()
        n = int(math.floor(self.now / TICK + 1e-9)) - self._ticks
        if n > MAX_TICKS_PER_POLL:
            self._ticks += n - MAX_TICKS_PER_POLL
            self._last_force += n - MAX_TICKS_PER_POLL
            if self._next_stream is not None:
                self._next_stream = self._ticks
            n = MAX_TICKS_PER_POLL
        for _ in range(max(0, n)):
            x = self._tick()
            out.extend(self._take_events())
            if self._next_stream is not None and self._ticks >= self._next_stream:
                out.append(self._position_frame(x))
                self._next_stream += self._stream_ticks
        return out

    def _take_events(self):
        out, self._events = self._events, []
        return out

    def next_due(self) -> float | None:
        """When the next PO frame (or the watchdog) is due, in s; None when nothing is.

        Returns
        -------
        float or None
        """
        if self._next_stream is not None:
            return self._next_stream * TICK
        if self.state == "ACTIVE":
            return (self._last_force + self.params[Param.WATCHDOG] + 1) * TICK
        return None

    def execute(self, frame: Frame) -> list[Frame]:
        """One host command (see PROTOCOL.md); FO frames (SEQ 0) get no reply.

        Parameters
        ----------
        frame : Frame
            A valid frame from the host (not a retry).

        Returns
        -------
        list of Frame
        """
        self._host_frame(frame)
        code, args = frame.code, frame.args
        if code == Command.FORCE.value:
            if frame.seq != 0 or len(args) != 1 or not isinstance(args[0], int):
                return [] if frame.seq == 0 else [self.error(frame, ErrorCode.BAD_ARGUMENT)]
            self._stream_force = force_from_wire(args[0])
            self._last_force = self._ticks
            return []
        if frame.seq == 0:
            return []
        handler = {
            Command.SET.value: self._set, Command.GET.value: self._get,
            Command.ENABLE.value: self._enable, Command.DISABLE.value: self._disable,
            Command.ZERO.value: self._zero, Command.STREAM.value: self._stream,
            Command.STATUS.value: self._status, Command.ESTOP.value: self._estop,
        }.get(code)
        if handler is None:
            return [self.error(frame, ErrorCode.UNKNOWN_COMMAND, code)]
        return handler(frame)

    def _param(self, frame, n_args):
        if len(frame.args) != n_args or not isinstance(frame.args[0], str):
            return None
        try:
            return Param(frame.args[0])
        except ValueError:
            return None

    def _set(self, frame):
        p = self._param(frame, 2)
        if p is None or not isinstance(frame.args[1], int):
            return [self.error(frame, ErrorCode.BAD_ARGUMENT)]
        spec, value = PARAMETERS[p], frame.args[1]
        if spec.read_only or not spec.low <= value <= spec.high:
            return [self.error(frame, ErrorCode.BAD_ARGUMENT, p.value)]
        self.params[p] = value
        self._compensate()
        return [self.ok(frame, p.value, value)]

    def _get(self, frame):
        p = self._param(frame, 1)
        if p is None:
            return [self.error(frame, ErrorCode.BAD_ARGUMENT)]
        return [self.ok(frame, p.value, self.params[p])]

    def _enable(self, frame):
        if self.state == "FAULT":  # DS clears a fault first
            return [self.error(frame, self._fault_code)]
        self.state = "ACTIVE"
        self._last_force = self._ticks  # the watchdog starts now
        return [self.ok(frame)]

    def _disable(self, frame):
        self.state = "IDLE"
        self._command = 0.0
        self._stream_force = 0.0
        return [self.ok(frame)]

    def _zero(self, frame):
        if self.state == "ACTIVE":
            return [self.error(frame, ErrorCode.STATE)]
        res = self._si(Param.RESOLUTION)
        self._offset = int(math.floor(self._x[0] / res + 0.5))
        self._prev, self._xf, self._vf = 0, 0.0, 0.0
        return [self.ok(frame)]

    def _stream(self, frame):
        if len(frame.args) != 1 or not isinstance(frame.args[0], int) or \
                not (frame.args[0] == 0 or 1 <= frame.args[0] <= 1000):
            return [self.error(frame, ErrorCode.BAD_ARGUMENT)]
        ms = frame.args[0]
        if ms == 0:
            self._next_stream = None
        else:
            self._stream_ticks = ms
            self._next_stream = self._ticks + ms
        return [self.ok(frame, ms)]

    def _status(self, frame):
        res = self._si(Param.RESOLUTION)
        x = (int(math.floor(self._x[0] / res + 0.5)) - self._offset) * res
        flags, self.flags = self.flags, Flag(0)
        return [self.ok(frame, *status_results(self.state, flags, x, self._command))]

    def _estop(self, frame):
        self._fault(Event.ESTOP, Flag.ESTOP)
        return self._take_events() + [self.ok(frame)]
