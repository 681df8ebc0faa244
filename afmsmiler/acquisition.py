"""One acquisition interface: an image scanned line by line, simulated or by a device.

An :class:`Acquisition` is what every scan in the course is, whoever scans: module (f)'s virtual
scanner (:class:`~afmsmiler.imaging.acquisition.ScanAcquisition`) or a device's session over a
transport (:class:`~afmsmiler.hardware.macro.session.MacroSession`,
:class:`~afmsmiler.hardware.educational.session.EducationalSession`). It

- runs as a state machine: ``idle`` -> :meth:`~Acquisition.start` -> ``scanning`` <->
  ``paused`` (:meth:`~Acquisition.pause`, :meth:`~Acquisition.resume`) -> ``done``,
  ``aborted`` (:meth:`~Acquisition.abort`) or ``fault`` (the tip crashed, the device faulted,
  the link went away);
- advances in bounded steps: :meth:`~Acquisition.step` scans (or reads) at most one line, and a
  device's session waits at most ``wait`` seconds, so whoever drives it (a test, a notebook's
  event loop) stays responsive between steps;
- takes new settings from the next line on (:meth:`~Acquisition.apply`), where the scanner or
  the device can; where it cannot it refuses them with :class:`SettingsRefused` and scans on
  (and a device that cannot pause says so with :class:`NotSupported`);
- holds the image once: its channels, NaN where no pixel was measured yet. Whoever shows it
  reads :meth:`~Acquisition.snapshot`, an immutable :class:`Snapshot` (read-only copies, the
  same object until something changes), never the arrays being filled;
- keeps the finished lines whatever ends the scan: a fault is recorded in the snapshot
  (``state="fault"``, :attr:`Snapshot.fault`) instead of being raised from :meth:`step`.

The UI piece that drives any acquisition (the kernel's event loop, the buttons, the progress
bar) is :mod:`afmsmiler.ui.acquisition`; nothing here imports a widget.
"""
from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Mapping

import numpy as np

from .samples import Sample
from .validation import check_integer, check_nonnegative

__all__ = ["Acquisition", "Snapshot", "Channel", "SettingsRefused", "NotSupported", "STATES"]

#: The states of an acquisition, in the order a scan passes them.
STATES = ("idle", "scanning", "paused", "done", "aborted", "fault")

#: States in which an acquisition is running (started and not ended).
_RUNNING = ("scanning", "paused")


class SettingsRefused(RuntimeError):
    """New settings an acquisition cannot take during a scan (the scan goes on without them)."""


class NotSupported(RuntimeError):
    """An action the scanner or device cannot do (the educational AFM cannot pause); the scan
    goes on as it was."""


@dataclass(frozen=True)
class Channel:
    """One channel of a snapshot: the full image, NaN where no pixel was measured yet.

    Attributes
    ----------
    heights : numpy.ndarray
        Values in ``unit``, shape (lines, pixels), read-only.
    pixel_size, pixel_size_y : float
        Spacing of the pixels along x and of the lines along y in m.
    unit : str
        SI unit of the values (``"m"`` for heights and deflections).
    name : str
        The channel's name.
    """

    heights: np.ndarray
    pixel_size: float
    pixel_size_y: float
    unit: str = "m"
    name: str = ""

    def finished(self, lines_done: int) -> Sample:
        """The finished lines as a Sample (rows 0 to ``lines_done - 1``).

        Parameters
        ----------
        lines_done : int
            Lines finished, at least 2 (a Sample holds at least two values per axis).

        Returns
        -------
        Sample
        """
        lines_done = check_integer("lines_done", lines_done, 2, self.heights.shape[0])
        return Sample(self.heights[:lines_done], self.pixel_size, self.name, self.pixel_size_y,
                      channel=self.name, unit=self.unit)


def _frozen(a: np.ndarray) -> np.ndarray:
    a = np.array(a, dtype=float)  # a copy: the acquisition goes on filling its own
    a.setflags(write=False)
    return a


@dataclass(frozen=True)
class Snapshot:
    """The image of an acquisition at one moment: immutable, NaN where nothing was measured.

    Attributes
    ----------
    images : Mapping
        Channel name -> read-only (lines, pixels) array in SI units, NaN where no pixel came.
    units : Mapping
        Channel name -> SI unit.
    pixel_size, pixel_size_y : float
        Pixel spacing along x and line spacing along y in m.
    lines_done : int
        Lines finished: rows 0 to ``lines_done - 1``.
    pixels_done : int
        Pixels measured (in scan order).
    state : str
        One of :data:`STATES`.
    fault : object
        What ended the scan in ``state == "fault"``: the exception a device raised, or the
        simulated tip's :class:`~afmsmiler.imaging.scan_modes.Crash`; None otherwise.
    changes : tuple of int
        The rows from which new settings applied (:meth:`Acquisition.apply`).
    main : str
        The channel that is the image (what a view shows first).
    name : str
        What was scanned.
    """

    images: Mapping
    units: Mapping
    pixel_size: float
    pixel_size_y: float
    lines_done: int
    pixels_done: int
    state: str
    fault: object = None
    changes: tuple = ()
    main: str = ""
    name: str = ""
    _channels: dict = field(default=None, repr=False, compare=False)

    @classmethod
    def blank(cls, units: Mapping, shape: tuple, pixel_size: float,
              pixel_size_y: float | None = None, *, main: str = "", name: str = "",
              state: str = "idle") -> "Snapshot":
        """A snapshot of nothing measured yet: every channel all NaN.

        Parameters
        ----------
        units : Mapping
            Channel name -> SI unit.
        shape : tuple of int
            (lines, pixels).
        pixel_size, pixel_size_y : float
            Pixel and line spacing in m (``pixel_size_y`` default ``pixel_size``).
        main, name, state : str
            As the attributes.

        Returns
        -------
        Snapshot
        """
        empty = np.full(shape, np.nan)
        empty.setflags(write=False)
        return cls(MappingProxyType({c: empty for c in units}), MappingProxyType(dict(units)),
                   float(pixel_size), float(pixel_size if pixel_size_y is None
                                            else pixel_size_y),
                   0, 0, state, main=main or next(iter(units), ""), name=name)

    @property
    def lines(self) -> int:
        """Lines of the whole image."""
        return next(iter(self.images.values())).shape[0] if self.images else 0

    @property
    def pixels(self) -> int:
        """Pixels per line."""
        return next(iter(self.images.values())).shape[1] if self.images else 0

    @property
    def running(self) -> bool:
        """Started and not ended (paused included)."""
        return self.state in _RUNNING

    @property
    def paused(self) -> bool:
        """The scan waits after its last finished line (or pixel) for a resume."""
        return self.state == "paused"

    @property
    def stopped(self) -> bool:
        """The scan was aborted before its end."""
        return self.state == "aborted"

    @property
    def error(self) -> str | None:
        """The fault as text (``"DeviceError: ..."`` for an exception), None without one."""
        if self.fault is None:
            return None
        if isinstance(self.fault, BaseException):
            return f"{type(self.fault).__name__}: {self.fault}"
        return str(self.fault)

    @property
    def channels(self) -> Mapping:
        """Channel name -> :class:`Channel` (the full image, NaN where nothing came)."""
        if self._channels is None:
            object.__setattr__(self, "_channels", MappingProxyType({
                name: Channel(a, self.pixel_size, self.pixel_size_y, self.units[name], name)
                for name, a in self.images.items()}))
        return self._channels

    def finished(self, channel: str | None = None) -> Sample:
        """The finished lines of a channel (default :attr:`main`) as a Sample.

        Parameters
        ----------
        channel : str, optional
            A channel name.

        Returns
        -------
        Sample

        Raises
        ------
        ValueError
            With fewer than two finished lines (a Sample needs two).
        """
        name = self.main if channel is None else channel
        if name not in self.images:
            raise ValueError(f"channel must be one of {sorted(self.images)}, got {name!r}")
        if self.lines_done < 2:
            raise ValueError(f"a Sample needs at least 2 finished lines, got {self.lines_done}")
        return self.channels[name].finished(self.lines_done)


class Acquisition(ABC):
    """An image scanned line by line: the state machine, the image (held once), snapshots.

    Subclasses say how to begin (:meth:`_begin`), how to advance by at most one line
    (:meth:`_advance`, filling :attr:`_images` and counting :attr:`_pixels_done`) and how to
    pause, resume, abort and apply settings on their scanner or device. Everything else is here,
    once.

    Parameters
    ----------
    units : Mapping
        Channel name -> SI unit (the channels, in the order shown).
    shape : tuple of int
        (lines, pixels) of the image before the first start.
    pixel_size, pixel_size_y : float
        Pixel and line spacing in m (``pixel_size_y`` default ``pixel_size``).
    main : str
        The channel that is the image; default the first.
    name : str
        What is scanned.

    Attributes
    ----------
    pause_after : int
        Pause by itself once this many lines are finished (0: never); read as each line ends
        (a device that cannot pause scans on).
    """

    def __init__(self, units: Mapping, shape: tuple, pixel_size: float,
                 pixel_size_y: float | None = None, *, main: str = "", name: str = ""):
        self._units = dict(units)
        self._main = main or next(iter(self._units))
        self._name = name
        self._state = "idle"
        self._fault = None
        self.pause_after = 0
        self._allocate(shape, pixel_size, pixel_size_y)

    # -- what subclasses call ------------------------------------------------------------------
    def _allocate(self, shape: tuple, pixel_size: float, pixel_size_y: float | None = None):
        """New NaN images of ``shape`` (lines, pixels); nothing measured."""
        self._images = {c: np.full(shape, np.nan) for c in self._units}
        self._pixel = (float(pixel_size), float(pixel_size if pixel_size_y is None
                                                else pixel_size_y))
        self._pixels_done = 0
        self._changes = []
        self._changed()

    def _changed(self) -> None:
        """Something in the image or the state changed: the next snapshot is a new one."""
        self._snapshot = None

    def _end(self, state: str, fault=None) -> None:
        self._state, self._fault = state, fault
        self._changed()

    # -- what subclasses implement -------------------------------------------------------------
    @abstractmethod
    def _begin(self, **settings) -> None:
        """Start the scan (the images are allocated for it)."""

    @abstractmethod
    def _advance(self, wait: float) -> None:
        """Scan or read at most one line (waiting at most ``wait`` s); call :meth:`_end` at
        the end. An exception raised here ends the scan as a fault (the lines stay)."""

    def _pause(self) -> bool:
        """Pause the scanner or device; False if it had already finished (raise
        :class:`NotSupported` if it cannot pause)."""
        return True

    def _resume(self) -> None:
        """Resume the scanner or device."""

    def _abort(self) -> None:
        """Stop the scanner or device."""

    def _apply(self, **settings) -> None:
        """Take ``settings`` from the next line on, or raise :class:`SettingsRefused`."""
        raise SettingsRefused(f"{type(self).__name__} takes no new settings during a scan")

    # -- the interface -------------------------------------------------------------------------
    @property
    def state(self) -> str:
        """One of :data:`STATES`."""
        return self._state

    @property
    def running(self) -> bool:
        """Started and not ended (paused included)."""
        return self._state in _RUNNING

    @property
    def paused(self) -> bool:
        """Waiting for :meth:`resume`."""
        return self._state == "paused"

    @property
    def lines_done(self) -> int:
        """Lines finished (rows 0 to ``lines_done - 1``)."""
        return self._pixels_done // self._images[self._main].shape[1]

    @property
    def line_time(self) -> float | None:
        """The time one line takes on the instrument in s, for a live loop to pace the steps;
        None when :meth:`step` itself waits for the device."""
        return None

    def start(self, **settings) -> None:
        """Start a scan from the first line (a running one is aborted first).

        Parameters
        ----------
        **settings
            What the subclass's scan takes (none for a simulated scan, whose settings were
            given when it was made).
        """
        if self.running:
            self.abort()
        self._fault = None
        self._begin(**settings)
        self._state = "scanning"
        self._changed()

    def pause(self) -> bool:
        """Pause after the line (simulated) or pixel (device) under way; the lines stay.

        Returns
        -------
        bool
            True if paused (or already paused), False if not running or already finished.
        """
        if self._state != "scanning":
            return self._state == "paused"
        if not self._pause():
            return False
        self._state = "paused"
        self._changed()
        return True

    def resume(self) -> None:
        """Go on with a paused scan."""
        if self._state != "paused":
            return
        self._resume()
        self._state = "scanning"
        self._changed()

    def abort(self) -> None:
        """Stop the scan: the lines finished so far stay."""
        if not self.running:
            return
        try:
            self._abort()
        finally:
            self._end("aborted")

    def apply(self, **settings) -> None:
        """Scan from the next line on with new settings (the finished lines stay).

        Parameters
        ----------
        **settings
            What the subclass takes.

        Raises
        ------
        SettingsRefused
            If the scanner or device cannot take them during a scan (it scans on as it was).
        """
        self._apply(**settings)
        self._changed()

    def step(self, wait: float = 0.0) -> bool:
        """Advance by at most one line; a fault ends the scan with its lines kept.

        Parameters
        ----------
        wait : float
            The longest time in s to wait for a device's pixels (a simulated scan computes its
            line and never waits).

        Returns
        -------
        bool
            True while the scan runs (paused included), False once it has ended.
        """
        wait = check_nonnegative("wait", wait, "s")  # checked in every state
        if self._state != "scanning":
            return self.running
        before = self.lines_done
        try:
            self._advance(wait)
        except Exception as exc:  # the finished lines stay; the snapshot says what happened
            self._end("fault", exc)
            return False
        self._changed()
        after = self.lines_done
        if (self._state == "scanning" and self.pause_after
                and before < self.pause_after <= after):
            try:
                self.pause()
            except NotSupported:  # a device that cannot pause scans on
                pass
        return self.running

    def snapshot(self) -> Snapshot:
        """The image so far and the state: immutable, NaN where nothing was measured.

        Returns
        -------
        Snapshot
            The same object until the image or the state changes.
        """
        if self._snapshot is None:
            dx, dy = self._pixel
            self._snapshot = Snapshot(
                MappingProxyType({c: _frozen(a) for c, a in self._images.items()}),
                MappingProxyType(dict(self._units)), dx, dy, self.lines_done,
                self._pixels_done, self._state, self._fault, tuple(self._changes), self._main,
                self._name)
        return self._snapshot
