"""The macroscopic AFM's simulated twin: the firmware's protocol over a virtual printed sample.

:class:`MacroAFMTwin` speaks protocol version 1 exactly as the firmware does (served on a
transport by :class:`~afmsmiler.hardware.twin.TwinServer`, so that pyserial can open it through a
pty like a board). Underneath:

- the sample is a :class:`~afmsmiler.samples.Sample` at the macro scale (heights in m, e.g. a
  3D-printed AFM image, :func:`printed_sample`), and the needle follows its grey-scale dilation by
  the needle's apex (module (f)'s :func:`~afmsmiler.imaging.dilation.dilate`), sampled bilinearly
  at the stage's position (x and y quantised to the stepper's step, row 0 the first line scanned,
  columns along the fast axis x);
- the ruler is module (a)'s steel cantilever (:mod:`.mechanics`): a deflection d of the needle
  reads ``counts = k d * counts_per_newton`` plus the gauge's white noise (seeded);
- z moves in micro-steps of ``ZS`` nm (0.0025 mm, the paper's); the needle's free height is
  ``z * ZS`` above the bed and it touches where the surface is higher;
- every line starts lifted by ``LIFT`` micro-steps at x = 0 (both modes);
- contact mode: the needle stays on the surface while the stage steps to the next pixel; z steps
  (one gauge reading each) until the reading first reaches ``SETPOINT`` counts coming down.
  Friction: climbing a wall steeper than the friction angle (slope > 1 / friction) the needle
  catches at its foot and is dragged until the ruler slips, at most ``slip_length`` later
  (the artefact that jumping mode avoids on tall samples);
- jumping mode: lift by ``LIFT`` micro-steps, move while lifted, come down to ``SETPOINT``;
- limit switches at the ends of travel (a pixel beyond them faults, and
  :meth:`MacroAFMTwin.trigger_limit` trips one), an emergency stop, homing (z to the top, x and y
  to 0, gauge tared), pause/resume/abort, and the last two lines kept for ``GL``;
- the pace: stepper moves with a trapezoidal speed profile (``SPEED`` steps/s, ``ACCEL``
  steps/s^2), one gauge reading per z step at the HX711's 80 samples/s; a TwinServer's
  time_scale 1 keeps that pace, 0 runs as fast as the computer can.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...contact import Parabolic
from ...imaging.dilation import dilate
from ...samples import Sample
from ...validation import (check_finite, check_instance, check_integer, check_positive,
                           check_range)
from ..errors import ErrorCode
from ..framing import Frame
from ..twin import Twin
from .codec import (DEVICE, TABLE, Command, ErrorReply, Event, EventMsg, Flag, LineEnd,
                    MacroAFMCodec, Param, Pixel, State)
from .mechanics import GaugeCalibration

__all__ = ["MacroAFMTwin", "printed_sample", "FIRMWARE_VERSION"]

FIRMWARE_VERSION = "0.1.0"
#: The pre-programmed scans of the start button (PRESET 0..3 of :data:`~.codec.TABLE`): (NX, NY,
#: DX um, MODE, LIFT); 0 runs the current parameters; 2 and 3 are the paper's 128 x 128 at 0.2 mm.
PRESETS = {0: None, 1: (16, 16, 500, 0, 400), 2: (128, 128, 200, 0, 400),
           3: (128, 128, 200, 1, 400)}
#: Stepper resolution of x and y (m): an Ender 3's 80 steps/mm.
XY_STEP = 12.5e-6
#: HX711 output rate (samples/s, RATE pin high).
GAUGE_RATE = 80.0


def printed_sample(kind: str = "grating", *, pixels: int = 64, pixel_size: float = 0.4e-3,
                   height: float = 2e-3) -> Sample:
    """A virtual 3D-printed sample at the macro scale (heights in m).

    Parameters
    ----------
    kind : {"grating", "afm"}
        ``"grating"``: square pillars (a tall calibration grating, period 8 pixels);
        ``"afm"``: the shipped AFM image (:func:`afmsmiler.samples.real_image`, 2 um wide)
        printed larger: laterally to ``pixels * pixel_size``, its height range to ``height``.
    pixels : int
        Pixels per side (8 to 512).
    pixel_size : float
        The printed pixel's size in m (0.01 to 5 mm).
    height : float
        The tallest feature in m (0.01 to 20 mm).

    Returns
    -------
    Sample
    """
    from ...samples import grating, real_image
    from ...validation import check_choice, check_integer

    check_choice("kind", kind, ("grating", "afm"))
    pixels = check_integer("pixels", pixels, 8, 512)
    pixel_size = check_range("pixel_size", pixel_size, 1e-5, 5e-3, "m")
    height = check_range("height", height, 1e-5, 20e-3, "m")
    if kind == "grating":
        return grating((pixels, pixels), pixel_size=pixel_size, period=8 * pixel_size,
                       height=height, duty=0.5, pattern="squares")
    image = real_image()
    h = image.heights[::max(1, image.shape[0] // pixels)][:pixels, ::max(1, image.shape[1]
                                                                        // pixels)][:, :pixels]
    h = (h - h.min()) * (height / max(float(np.ptp(h)), 1e-300))
    return Sample(np.ascontiguousarray(h), pixel_size, "printed AFM image")


def _move_time(steps: float, rate: float, accel: float) -> float:
    """Time (s) of a trapezoidal move of ``steps`` from rest to rest at most ``rate``."""
    steps = abs(steps)
    if steps == 0:
        return 0.0
    if steps >= rate * rate / accel:
        return steps / rate + rate / accel
    return 2.0 * math.sqrt(steps / accel)


@dataclass
class _ScanState:
    row: int = 0
    col: int = 0
    due: float = 0.0           # when the pending pixel (or fault) is sent
    pending: list = None       # the frames to send then
    remaining: float = 0.0     # time left on the pending pixel when paused
    jam_x: float | None = None  # where the needle is caught (contact mode), None if free
    lines: dict = None         # row -> list of (col, z, counts), the last two lines


class MacroAFMTwin(Twin):
    """The macroscopic AFM, simulated, speaking the firmware's protocol.

    Parameters
    ----------
    sample : Sample, optional
        The printed sample (heights in m); default :func:`printed_sample` ("grating"). Its first
        pixel sits at the stage's home (x = y = 0); outside it the needle meets its edge values.
    tip_radius : float
        The needle's apex radius in m.
    calibration : GaugeCalibration, optional
        Counts per newton and the ruler's stiffness (default: predicted from the steel ruler).
    gauge_noise : float
        RMS of the gauge's white noise in counts.
    friction : float
        Needle-sample friction coefficient (0: none).
    slip_length : float
        The farthest (m) the stage drags a caught needle before the ruler slips.
    travel : tuple of float
        (x, y, z) travel in m between the limit switches.
    z_step : float
        The z micro-step in m (``ZS``), a whole number of nm.
    base : float
        Height in m of the sample's zero above the bottom of z's travel (the bed and the print's
        base plate).
    seed : int
        Seed of the gauge noise.

    Attributes
    ----------
    params : dict
        The current parameters (:class:`Param` -> int).
    state : State
    z : int
        The z axis in micro-steps (the needle's free height is ``z * ZS``).
    """

    DEVICE = DEVICE
    FIRMWARE_VERSION = FIRMWARE_VERSION

    def __init__(self, sample: Sample | None = None, *, tip_radius: float = 0.3e-3,
                 calibration: GaugeCalibration | None = None, gauge_noise: float = 3.0,
                 friction: float = 0.5, slip_length: float = 1.2e-3,
                 travel: tuple = (0.22, 0.22, 0.05), z_step: float = 2.5e-6,
                 base: float = 5e-3, seed: int = 0):
        super().__init__()
        seed = check_integer("seed", seed, 0)
        sample = printed_sample() if sample is None else check_instance("sample", sample, Sample)
        if sample.heights.ndim != 2 or sample.unit != "m":
            raise ValueError(f"sample must be an image of heights in m, got shape "
                             f"{sample.heights.shape} in {sample.unit!r}")
        self.sample = sample
        self.tip = Parabolic(check_range("tip_radius", tip_radius, 1e-6, 5e-3, "m"))
        self.apex = dilate(sample, self.tip)
        self.calibration = GaugeCalibration.from_ruler() if calibration is None else \
            check_instance("calibration", calibration, GaugeCalibration)
        self.gauge_noise = check_range("gauge_noise", gauge_noise, 0.0, 1e6)
        self.friction = check_range("friction", friction, 0.0, 10.0)
        self.slip_length = check_range("slip_length", slip_length, 0.0, 0.1, "m")
        try:
            self.travel = tuple(check_positive(f"travel[{i}]", t, "m")
                                for i, t in enumerate(travel))
        except TypeError:
            raise ValueError(f"travel must be (x, y, z) in m, got {travel!r}") from None
        if len(self.travel) != 3:
            raise ValueError(f"travel must be (x, y, z) in m, got {travel!r}")
        self.base = check_range("base", base, 0.0, self.travel[2], "m")
        zs = TABLE[Param.ZSTEP]
        zs_nm = round(check_range("z_step", z_step, zs.to_si(zs.low), zs.to_si(zs.high), "m")
                      / zs.scale)
        self.params = {Param(code): value for code, value in TABLE.defaults().items()}
        self.params[Param.ZSTEP] = TABLE[Param.ZSTEP].check_reply(zs_nm)
        self._rng = np.random.default_rng(seed)
        self.state = State.IDLE
        self.homed = False
        self.limits = {"X": False, "Y": False, "Z": False}
        self.estop = False
        self.x = self.y = 0.0
        self.z = int(self.travel[2] / self.z_step) // 2
        self._booted = False
        self._homing_done = None
        self._scan = None
        self._fault_at = {}
        self._button = None
        self.executed = []  # every command executed (not retries): for tests and teaching

    # -- physics -------------------------------------------------------------------------------
    @property
    def z_step(self) -> float:
        """The z micro-step in m."""
        return TABLE[Param.ZSTEP].to_si(self.params[Param.ZSTEP])

    @property
    def z_top(self) -> int:
        """The z axis's home (the top of its travel) in micro-steps."""
        return int(self.travel[2] / self.z_step)

    def surface(self, x: float, y: float) -> float:
        """The height (m) the needle's apex meets at stage position (x, y) in m.

        Parameters
        ----------
        x, y : float
            Stage position in m from home (the sample's first pixel); outside the sample the
            edge's values.

        Returns
        -------
        float
            Above the bottom of z's travel (the sample's heights plus :attr:`base`).
        """
        x, y = check_finite("x", x, "m"), check_finite("y", y, "m")
        h = self.apex.heights
        rows, cols = h.shape
        px = min(max(x / self.apex.pixel_size, 0.0), cols - 1.0)
        py = min(max(y / self.apex.pixel_size_y, 0.0), rows - 1.0)
        j0, i0 = min(int(px), cols - 2), min(int(py), rows - 2)
        fx, fy = px - j0, py - i0
        top = h[i0, j0] * (1 - fx) + h[i0, j0 + 1] * fx
        bottom = h[i0 + 1, j0] * (1 - fx) + h[i0 + 1, j0 + 1] * fx
        return float(top * (1 - fy) + bottom * fy) + self.base

    def _counts(self, surface: float, z) -> np.ndarray:
        """Noiseless counts at z micro-steps (array) over a surface height."""
        d = np.maximum(surface - np.asarray(z, dtype=float) * self.z_step, 0.0)
        return d * self.calibration.counts_per_metre

    def _read(self, surface: float, z) -> np.ndarray:
        z = np.asarray(z)
        noise = self._rng.normal(0.0, self.gauge_noise, z.shape) if self.gauge_noise else 0.0
        return np.rint(self._counts(surface, z) + noise).astype(np.int64)

    def gauge(self) -> int:
        """One gauge reading (counts above the free reading) where the needle is now.

        Returns
        -------
        int
        """
        return int(self._read(self.surface(self.x, self.y), np.array([self.z]))[0])

    def _regulate(self, surface: float, z: int) -> tuple[int, int, int]:
        """Step z to the first reading >= SETPOINT coming down; (z, counts, steps taken)."""
        setpoint = self.params[Param.SETPOINT]
        steps = 0
        z_contact = surface / self.z_step  # where the needle starts to touch
        sigma = self.gauge_noise
        # go up while the reading is at or above the setpoint (vectorised, bounded)
        reading = int(self._read(surface, np.array([z]))[0])
        if reading >= setpoint:
            top = max(z + 1, math.ceil(z_contact) + 2)
            ups = np.arange(z + 1, top + 1)
            below = np.nonzero(self._read(surface, ups) < setpoint)[0]
            up_to = int(ups[below[0]]) if below.size else top
            steps += up_to - z
            z = up_to
        # come down until the reading reaches the setpoint
        d_set = (setpoint + 6 * sigma + 1) / self.calibration.counts_per_metre
        bottom = min(z - 1, math.floor((surface - d_set) / self.z_step) - 1)
        downs = np.arange(z - 1, bottom - 1, -1)
        readings = self._read(surface, downs)
        hit = np.nonzero(readings >= setpoint)[0]
        k = int(hit[0]) if hit.size else len(downs) - 1
        steps += k + 1
        return int(downs[k]), int(readings[k]), steps

    # -- scanning ------------------------------------------------------------------------------
    def trigger_limit(self, axis: str = "X", at: tuple | None = None) -> None:
        """Trip a limit switch: now, or when the scan reaches pixel ``at``.

        Parameters
        ----------
        axis : {"X", "Y", "Z"}
            The switch.
        at : tuple of int, optional
            (row, col): trip it as the scan reaches that pixel (deterministic tests).
        """
        if not isinstance(axis, str) or axis not in ("X", "Y", "Z"):
            raise ValueError(f"axis must be 'X', 'Y' or 'Z', got {axis!r}")
        if at is not None:
            if not isinstance(at, (tuple, list)) or len(at) != 2:
                raise ValueError(f"at must be a pixel (row, col) of two integers >= 0 or None, "
                                 f"got {at!r}"[:160])
            at = tuple(check_integer(f"at[{i}]", v, 0) for i, v in enumerate(at))
        self._fault_at[at] = (Event.LIMIT, axis)

    def press_button(self, preset: int | None = None) -> None:
        """Press the start button: at its next poll an idle machine runs a preset scan.

        Parameters
        ----------
        preset : int, optional
            Which of :data:`PRESETS` (default the ``PRESET`` parameter); the machine sends
            ``0 EV BUTTON <preset>`` and streams the scan as after ``SS`` (homing first if it
            is not homed, as the firmware does).
        """
        preset = self.params[Param.PRESET] if preset is None else preset
        if not TABLE[Param.PRESET].valid(preset):
            raise ValueError(f"preset must be one of {sorted(PRESETS)}, got {preset!r}")
        self._button = preset

    def _button_scan(self) -> list[Frame]:
        preset, self._button = self._button, None
        if self.state not in (State.IDLE, State.FAULT):
            return []
        if PRESETS[preset] is not None:
            nx, ny, dx, mode, lift = PRESETS[preset]
            self.params.update({Param.NX: nx, Param.NY: ny, Param.PITCH: dx, Param.MODE: mode,
                                Param.LIFT: lift})
        self.params[Param.PRESET] = preset
        if not self.homed:  # the firmware homes first (taken here at once)
            self._home_done()
        if not self._fits():
            return []
        self._start(self.now)
        return [self._frame(EventMsg(Event.BUTTON, preset))]

    def press_estop(self) -> None:
        """Press the emergency stop (the scan faults at its next pixel)."""
        self._fault_at[None] = (Event.ESTOP, None)

    def _fault(self, event: Event, word) -> list[Frame]:
        """Enter FAULT and return the event and ``0 ER <n>`` frames."""
        self.state = State.FAULT
        self.homed = False
        if event == Event.LIMIT:
            self.limits[word] = True
            code = ErrorCode.LIMIT
        else:
            self.estop = True
            code = ErrorCode.ESTOP
        return [self._frame(EventMsg(event, word)), self._frame(ErrorReply(0, code))]

    def _next_pixel(self, start: float) -> None:
        """Compute the scan's next pixel (or fault) and when it is due."""
        s, p = self._scan, self.params
        rate, accel = p[Param.SPEED], p[Param.ACCEL]
        fault = self._fault_at.pop((s.row, s.col), None) or self._fault_at.pop(None, None)
        pitch = TABLE[Param.PITCH].to_si(p[Param.PITCH])
        x_new = round(s.col * pitch / XY_STEP) * XY_STEP
        y_new = round(s.row * pitch / XY_STEP) * XY_STEP
        if fault is None:
            for axis, pos, travel in (("X", x_new, self.travel[0]), ("Y", y_new, self.travel[1])):
                if pos > travel:
                    fault = (Event.LIMIT, axis)
        xy_steps = max(abs(x_new - self.x), abs(y_new - self.y)) / XY_STEP
        if fault is not None:
            frac = 0.5  # the switch trips half-way through the move
            s.due = start + frac * _move_time(xy_steps, rate, accel)
            s.pending = ("fault", fault)
            return
        jumping = p[Param.MODE] == 1
        z_time = 0.0
        if jumping or s.col == 0:  # jumping mode lifts at every pixel, both before a new line
            lift = p[Param.LIFT]
            self.z = min(self.z + lift, self.z_top)
            z_time += _move_time(lift, rate, accel)
            s.jam_x = None
            needle_x = x_new
        else:
            needle_x = self._drag(x_new, y_new, new_line=(s.col == 0))
        surface = self.surface(needle_x, y_new)
        z, counts, steps = self._regulate(surface, self.z)
        if z < 0:  # the needle would have to go below the bed: the z switch trips
            s.due, s.pending = start, ("fault", (Event.LIMIT, "Z"))
            return
        self.x, self.y, self.z = x_new, y_new, z
        z_time += steps * max(1.0 / rate, 1.0 / GAUGE_RATE)
        s.due = start + _move_time(xy_steps, rate, accel) + z_time
        s.pending = ("pixel", (s.row, s.col, z, counts))

    def _drag(self, x_new: float, y: float, new_line: bool) -> float:
        """Where the needle is in contact mode after the stage moved to x_new (friction)."""
        s = self._scan
        if new_line or self.friction == 0 or x_new <= self.x:
            s.jam_x = None
            return x_new
        x_from = self.x if s.jam_x is None else s.jam_x
        rise = self.surface(x_new, y) - self.surface(x_from, y)
        steep = rise > (x_new - x_from) / self.friction
        if steep and x_new - x_from <= self.slip_length:
            s.jam_x = x_from  # caught at the wall's foot, the ruler dragged along
            return x_from
        s.jam_x = None
        return x_new

    def _emit_due(self) -> list[Frame]:
        s, p = self._scan, self.params
        kind, payload = s.pending
        if kind == "fault":
            return self._fault(*payload)
        row, col, z, counts = payload
        out = [self._frame(Pixel(*payload))]
        s.lines.setdefault(row, []).append((col, z, counts))
        for old in [r for r in s.lines if r < row - 1]:
            del s.lines[old]
        s.col += 1
        if s.col == p[Param.NX]:
            out.append(self._frame(LineEnd(row, p[Param.NX])))
            s.col = 0
            s.row += 1
            if s.row == p[Param.NY]:
                out.append(self._frame(EventMsg(Event.DONE)))
                self.state = State.IDLE
                return out
        self._next_pixel(s.due)
        return out

    # -- the Twin interface ----------------------------------------------------------------------
    def poll(self, now: float) -> list[Frame]:
        """Stream frames due by ``now``: the boot event, homing's end, pixels, lines, faults.

        Parameters
        ----------
        now : float
            The twin's time in s.

        Returns
        -------
        list of Frame
        """
        super().poll(now)
        out = []
        if not self._booted:
            self._booted = True
            out.append(self._frame(EventMsg(Event.BOOT)))
        if self.state == State.HOMING and self._homing_done <= self.now:
            self._home_done()
            out.append(self._frame(EventMsg(Event.HOMED)))
        if self._button is not None:
            out += self._button_scan()
        while self.state == State.SCANNING and self._scan.due <= self.now:
            out += self._emit_due()
        return out

    def next_due(self) -> float | None:
        """When the next stream frame is due (s), None if nothing is scheduled.

        Returns
        -------
        float or None
        """
        if not self._booted or self._button is not None:
            return self.now
        if self.state == State.HOMING:
            return self._homing_done
        if self.state == State.SCANNING:
            return self._scan.due
        return None

    def _home_done(self):
        self.state = State.IDLE
        self.homed = True
        self.limits = {"X": False, "Y": False, "Z": False}
        self.estop = False
        self.x = self.y = 0.0
        self.z = self.z_top

    def _fits(self) -> bool:
        """Whether the scan's grid lies within the x and y travel."""
        p = self.params
        span = TABLE[Param.PITCH].to_si(p[Param.PITCH])
        return ((p[Param.NX] - 1) * span <= self.travel[0]
                and (p[Param.NY] - 1) * span <= self.travel[1])

    def _start(self, now: float):
        p = self.params
        self._scan = _ScanState(lines={})
        self.state = State.SCANNING
        # coarse approach at full speed to 6 sigma above the first pixel's contact
        surface = self.surface(0.0, 0.0)
        target = max(int(surface / self.z_step) + 20, 0)
        t = _move_time(max(abs(self.x), abs(self.y)) / XY_STEP, p[Param.SPEED], p[Param.ACCEL])
        t += _move_time(self.z - target, p[Param.SPEED], p[Param.ACCEL])
        self.z = min(self.z, target)
        self._next_pixel(now + t)

    def execute(self, frame: Frame) -> list[Frame]:
        """Run one host command as the firmware does.

        Parameters
        ----------
        frame : Frame
            A host command (not a retry).

        Returns
        -------
        list of Frame
            Its reply, after any stream frames it causes (``GL``) and before events it causes
            (``PA``, ``AB``).
        """
        self._host_frame(frame)
        if frame.seq == 0:
            return []
        self.executed.append(frame)
        try:
            command = Command(frame.code)
        except ValueError:
            return [self.error(frame, ErrorCode.UNKNOWN_COMMAND)]
        handler = getattr(self, "_cmd_" + command.name.lower())
        return handler(frame)

    _frame = staticmethod(MacroAFMCodec.frame)

    def _param(self, frame, index=0):
        try:
            return Param(frame.args[index])
        except (ValueError, IndexError):
            return None

    def _cmd_identify(self, frame):  # pragma: no cover - Twin.handle answers ID
        return [self.ok(frame, self.DEVICE, self.protocol_version, self.FIRMWARE_VERSION)]

    def _cmd_set(self, frame):
        param = self._param(frame)
        if param is None or len(frame.args) != 2 or not isinstance(frame.args[1], int):
            return [self.error(frame, ErrorCode.BAD_ARGUMENT)]
        if param == Param.ZSTEP:
            return [self.error(frame, ErrorCode.BAD_ARGUMENT, "READONLY")]
        if self.state in (State.SCANNING, State.PAUSED, State.HOMING):
            return [self.error(frame, ErrorCode.BUSY)]
        value = frame.args[1]
        if not TABLE[param].valid(value):
            return [self.error(frame, ErrorCode.BAD_ARGUMENT)]
        self.params[param] = frame.args[1]
        return [self.ok(frame, param.value, frame.args[1])]

    def _cmd_get(self, frame):
        param = self._param(frame)
        if param is None or len(frame.args) != 1:
            return [self.error(frame, ErrorCode.BAD_ARGUMENT)]
        return [self.ok(frame, param.value, self.params[param])]

    def _cmd_home(self, frame):
        if self.state in (State.SCANNING, State.PAUSED, State.HOMING):
            return [self.error(frame, ErrorCode.BUSY)]
        p = self.params
        steps = max(self.x / XY_STEP, self.y / XY_STEP, self.z_top - self.z)
        self._homing_done = self.now + _move_time(steps, p[Param.SPEED], p[Param.ACCEL]) + 0.5
        self.state = State.HOMING
        self._scan = None
        return [self.ok(frame)]

    def _cmd_start(self, frame):
        if frame.args:
            return [self.error(frame, ErrorCode.BAD_ARGUMENT)]
        if not self.homed:
            return [self.error(frame, ErrorCode.NOT_HOMED)]
        if self.state != State.IDLE:
            return [self.error(frame, ErrorCode.BUSY)]
        if not self._fits():
            return [self.error(frame, ErrorCode.BAD_ARGUMENT)]
        self._start(self.now)
        return [self.ok(frame)]

    def _cmd_pause(self, frame):
        if self.state != State.SCANNING:
            return [self.error(frame, ErrorCode.STATE)]
        self.state = State.PAUSED
        self._scan.remaining = max(0.0, self._scan.due - self.now)
        return [self.ok(frame), self._frame(EventMsg(Event.PAUSED))]

    def _cmd_resume(self, frame):
        if self.state != State.PAUSED:
            return [self.error(frame, ErrorCode.STATE)]
        self.state = State.SCANNING
        self._scan.due = self.now + self._scan.remaining
        return [self.ok(frame)]

    def _cmd_abort(self, frame):
        if self.state not in (State.SCANNING, State.PAUSED, State.HOMING):
            return [self.error(frame, ErrorCode.STATE)]
        self.state = State.IDLE
        return [self.ok(frame), self._frame(EventMsg(Event.ABORTED))]

    def _cmd_status(self, frame):
        flags = Flag(0)
        if self.homed:
            flags |= Flag.HOMED
        for axis, bit in (("X", Flag.LIMIT_X), ("Y", Flag.LIMIT_Y), ("Z", Flag.LIMIT_Z)):
            if self.limits[axis]:
                flags |= bit
        if self.estop:
            flags |= Flag.ESTOP
        row, col = (self._scan.row, self._scan.col) if self._scan is not None else (0, 0)
        return [self.ok(frame, self.state.value, row, col, int(flags))]

    def _cmd_gauge(self, frame):
        return [self.ok(frame, self.gauge())]

    def _cmd_getline(self, frame):
        if len(frame.args) != 1 or not isinstance(frame.args[0], int):
            return [self.error(frame, ErrorCode.BAD_ARGUMENT)]
        row = frame.args[0]
        lines = self._scan.lines if self._scan is not None else {}
        if row not in lines:
            return [self.error(frame, ErrorCode.BAD_ARGUMENT)]
        pixels = lines[row]
        out = [self._frame(Pixel(row, col, z, counts)) for col, z, counts in pixels]
        return out + [self.ok(frame, row, len(pixels))]
