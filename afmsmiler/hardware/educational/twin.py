"""The educational AFM's twin: module (f)'s scanner images a sample and the pixels stream out.

Pure (no threads, no I/O): :class:`EducationalAFMTwin` answers the protocol of
:mod:`.codec` (PROTOCOL.md) and, once started, emits one ``0 PX`` frame per pixel at the
instrument's pixel rate on its clock. The image is module (f)'s scan
(:func:`afmsmiler.imaging.scan`) of the sample in constant-force mode with module (c)'s loop, the
heights rounded to the ZS count. Serve it with :func:`afmsmiler.hardware.open_twin`.
"""
from __future__ import annotations

import numpy as np

from ...controller import ContactLoop
from ...imaging import ScanSettings, scan
from ...imaging.scan_modes import ConstantForce
from ...imaging.settings import PARAMETERS as SCAN_PARAMETERS
from ...samples import Sample
from ...validation import check_instance, check_integer, check_positive
from ..framing import Frame
from ..twin import Twin
from .codec import (DEVICE, READ_ONLY, TABLE, Command, ErrorCode, Event, Param, State, event,
                    line_end, pixel, stream_error)

__all__ = ["EducationalAFMTwin"]


class EducationalAFMTwin(Twin):
    """The device side of the EDUAFM protocol, imaging ``sample``.

    Parameters
    ----------
    sample : Sample
        The virtual sample (2-D heights in m), larger than the scan (NX x DX).
    pixel_time : float
        Time per pixel in s on the twin's clock (the instrument's 2-omega lock-in settles in a
        few time constants: 1 ms by default).
    z_step : int
        Height per count in pm (the read-only ZS).
    noise : float
        Rms height noise in m added to each pixel (the lock-in's amplitude noise through the
        loop), in [0, 1e-6] (the scan settings' range).
    seed : int
        Seed of the noise.
    fault_at : int, optional
        Pixel index (row x NX + col) at which the probe's signal is lost (a test of the host's
        fault handling): the twin sends ``0 EV FAULT`` and ``0 ER 8`` there.

    Attributes
    ----------
    image : ndarray or None
        The current scan's heights in counts (rows x NX).
    """

    DEVICE = DEVICE
    FIRMWARE_VERSION = "0.1.0"

    def __init__(self, sample: Sample, *, pixel_time: float = 1e-3,
                 z_step: int = TABLE[Param.ZSTEP].default,
                 noise: float = 0.0, seed: int = 0, fault_at: int | None = None):
        super().__init__()
        self.sample = check_instance("sample", sample, Sample)
        self.pixel_time = check_positive("pixel_time", pixel_time, "s")
        zs = TABLE[Param.ZSTEP]
        self.z_step = check_integer("z_step", z_step, zs.low, zs.high)
        self.noise = SCAN_PARAMETERS["noise"].check(noise)
        self.seed = check_integer("seed", seed, 0)
        self.fault_at = None if fault_at is None else check_integer("fault_at", fault_at, 0)
        self.params = {Param(code): value for code, value in TABLE.defaults().items()}
        self.params[Param.ZSTEP] = self.z_step
        self.state = State.IDLE
        self.image = None
        self._next = 0          # the next pixel to stream (row x NX + col)
        self._start = 0.0       # the twin's time of pixel 0
        self._queued = [event(Event.BOOT)]

    # -- the scan ---------------------------------------------------------------------------
    def _image(self) -> np.ndarray:
        nx, ny = self.params[Param.NX], self.params[Param.NY]
        pitch = TABLE[Param.PITCH].to_si(self.params[Param.PITCH])
        settings = ScanSettings(nx * pitch, scan_size_y=ny * pitch, pixels=nx, lines=ny,
                                noise=self.noise, seed=self.seed)
        result = scan(self.sample, None, ConstantForce(ContactLoop()), settings)
        heights = result.images["height trace"]
        count = TABLE[Param.ZSTEP].to_si(self.z_step)
        return np.rint((heights - np.min(heights)) / count).astype(np.int64)

    def _total(self) -> int:
        return self.params[Param.NX] * self.params[Param.NY]

    def _due_pixel(self, index: int) -> float:
        return self._start + (index + 1) * self.pixel_time

    def next_due(self):
        """When the next stream frame is due (s), or None when nothing is queued or scanning."""
        if self._queued:
            return self.now
        if self.state is State.SCANNING:
            return self._due_pixel(self._next)
        return None

    def poll(self, now: float) -> list[Frame]:
        """Pixels (and line ends, events) due by ``now``.

        Parameters
        ----------
        now : float
            The twin's time in s.
        """
        super().poll(now)
        out, self._queued = self._queued, []
        nx = self.params[Param.NX]
        while self.state is State.SCANNING and self._due_pixel(self._next) <= self.now:
            i = self._next
            row, col = divmod(i, nx)
            if self.fault_at is not None and i == self.fault_at:
                self.state = State.FAULT
                out += [event(Event.FAULT), stream_error(ErrorCode.SENSOR)]
                break
            out.append(pixel(row, col, int(self.image[row, col])))
            self._next += 1
            if col == nx - 1:
                out.append(line_end(row, nx))
            if self._next == self._total():
                self.state = State.IDLE
                out.append(event(Event.DONE))
        return out

    # -- commands ---------------------------------------------------------------------------
    def execute(self, frame: Frame) -> list[Frame]:
        """Run one host command (see PROTOCOL.md).

        Parameters
        ----------
        frame : Frame
            The command.
        """
        self._host_frame(frame)
        if frame.seq == 0:
            return []
        try:
            code = Command(frame.code)
        except ValueError:
            return [self.error(frame, ErrorCode.UNKNOWN_COMMAND, frame.code)]
        args = frame.args
        if code is Command.SET:
            if len(args) != 2 or not isinstance(args[1], int):
                return [self.error(frame, ErrorCode.MALFORMED)]
            try:
                par = Param(args[0])
            except ValueError:
                return [self.error(frame, ErrorCode.BAD_ARGUMENT, str(args[0]))]
            if self.state is State.SCANNING:
                return [self.error(frame, ErrorCode.BUSY)]
            if par in READ_ONLY or not TABLE[par].valid(args[1]):
                return [self.error(frame, ErrorCode.BAD_ARGUMENT, par.value)]
            self.params[par] = args[1]
            return [self.ok(frame, par.value, args[1])]
        if code is Command.GET:
            try:
                par = Param(args[0]) if len(args) == 1 else None
            except ValueError:
                par = None
            if par is None:
                return [self.error(frame, ErrorCode.BAD_ARGUMENT)]
            return [self.ok(frame, par.value, self.params[par])]
        if code is Command.START:
            if self.state is State.SCANNING:
                return [self.error(frame, ErrorCode.BUSY)]
            try:
                self.image = self._image()
            except ValueError:                     # the scan range leaves the sample
                return [self.error(frame, ErrorCode.BAD_ARGUMENT, Param.PITCH.value)]
            self.state, self._next, self._start = State.SCANNING, 0, self.now
            return [self.ok(frame)]
        if code is Command.ABORT:
            if self.state is not State.SCANNING:
                return [self.error(frame, ErrorCode.STATE)]
            self.state = State.IDLE
            return [self.ok(frame), event(Event.ABORTED)]
        if code is Command.STATUS:
            row, col = divmod(self._next, self.params[Param.NX])
            return [self.ok(frame, self.state.value, row, col)]
        if code is Command.GETLINE:
            nx = self.params[Param.NX]
            if len(args) != 1 or not isinstance(args[0], int) or self.image is None \
                    or not 0 <= args[0] < self._next // nx + (self._next % nx > 0):
                return [self.error(frame, ErrorCode.BAD_ARGUMENT)]
            row = args[0]
            n = min(nx, self._next - row * nx)
            return [pixel(row, c, int(self.image[row, c])) for c in range(n)] + \
                [self.ok(frame, row, n)]
        return [self.error(frame, ErrorCode.UNKNOWN_COMMAND, frame.code)]
