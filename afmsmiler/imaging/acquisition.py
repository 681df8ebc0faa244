"""Module (f)'s scan as an acquisition: the virtual scanner behind :class:`~afmsmiler.acquisition.Acquisition`.

:class:`ScanAcquisition` runs a :class:`~afmsmiler.imaging.scanner.Scan` one line per
:meth:`~afmsmiler.acquisition.Acquisition.step` (one model run), pauses between lines, and takes
a new tip, mode or settings from the next line on (:meth:`~afmsmiler.acquisition.Acquisition.apply`):
a new :class:`Scan` that writes its lines, from the next one on, into the image the acquisition
holds (the lines before stay as they were scanned). A tip that crashes ends the scan as a fault
(:attr:`~afmsmiler.acquisition.Snapshot.fault` is the :class:`~afmsmiler.imaging.scan_modes.Crash`);
its crashed line holds the pixels reached.
"""
from __future__ import annotations

from ..acquisition import Acquisition, SettingsRefused
from ..contact import Tip
from ..samples import Sample
from ..validation import check_instance
from .scan_modes import Mode
from .scanner import Scan
from .settings import ScanSettings

__all__ = ["ScanAcquisition"]


class ScanAcquisition(Acquisition):
    """A simulated scan of ``sample`` with ``tip`` in ``mode``, as an acquisition.

    Parameters
    ----------
    sample : afmsmiler.samples.Sample
        The sample (2-D heights in m).
    tip : afmsmiler.contact.Tip or None
        The tip (None: ideal).
    mode : afmsmiler.imaging.scan_modes.Mode
        The imaging mode; its :attr:`~afmsmiler.imaging.scan_modes.Mode.main_channel` is the image.
    settings : afmsmiler.imaging.settings.ScanSettings
        The scan's settings.

    Raises
    ------
    TypeError, ValueError
        As :class:`~afmsmiler.imaging.scanner.Scan` does, at once (before :meth:`start`).

    Attributes
    ----------
    scan : afmsmiler.imaging.scanner.Scan
        The scan the lines come from now (a new one from the line new settings applied at).

    Examples
    --------
    >>> import numpy as np
    >>> from afmsmiler.controller import ContactLoop
    >>> from afmsmiler.imaging.scan_modes import ConstantForce
    >>> acq = ScanAcquisition(Sample(np.zeros((32, 32)), 10e-9), None,
    ...                       ConstantForce(ContactLoop()), ScanSettings(300e-9, pixels=8))
    >>> acq.start(); acq.step(), acq.snapshot().lines_done
    (True, 1)
    >>> bool(np.isnan(acq.snapshot().images["height trace"][1:]).all())
    True
    """

    def __init__(self, sample: Sample, tip: Tip | None, mode: Mode, settings: ScanSettings):
        check_instance("mode", mode, Mode)
        check_instance("settings", settings, ScanSettings)
        super().__init__({c: mode.unit(c) for c in mode.channels}, settings.shape,
                         settings.pixel_size, settings.pixel_size_y,
                         main=mode.main_channel or mode.channels[0],
                         name=getattr(sample, "name", ""))
        self.scan = Scan(sample, tip, mode, settings, images=self._images)
        self._fresh = True  # the scan made here has scanned nothing: the first start uses it
        self._lines = None
        self._pending = None

    @property
    def line_time(self) -> float:
        """The instrument's time for one line in s (trace, retrace, step to the next)."""
        return self.scan.settings.line_time

    def _begin(self) -> None:
        if not self._fresh:  # started again: a new image, a new scan (its first line on)
            s = self.scan
            self._allocate(s.settings.shape, s.settings.pixel_size, s.settings.pixel_size_y)
            self.scan = Scan(s.sample, s.tip, s.mode, s.settings, images=self._images)
        self._fresh = False
        self._lines = self.scan.lines()
        self._pending = None

    def _apply(self, *, tip: Tip | None = None, mode: Mode | None = None,
               settings: ScanSettings | None = None) -> None:
        """Scan from the next line on with another tip, mode or settings (None: as they are).

        Raises
        ------
        SettingsRefused
            If they make another image (another grid or other channels): start a new scan.
        """
        now = self._pending or (self.scan.tip, self.scan.mode, self.scan.settings)
        tip = now[0] if tip is None else check_instance("tip", tip, Tip)
        mode = now[1] if mode is None else check_instance("mode", mode, Mode)
        settings = now[2] if settings is None else check_instance("settings", settings,
                                                                   ScanSettings)
        old = self.scan.settings
        if (mode.channels != self.scan.mode.channels or settings.shape != old.shape
                or settings.scan_size != old.scan_size or settings.scan_size_y != old.scan_size_y
                or settings.angle != old.angle or settings.offset != old.offset):
            raise SettingsRefused("another mode, grid, scan range, angle or offset makes "
                                  "another image: start a new scan with it")
        self._pending = (tip, mode, settings)

    def _advance(self, wait: float) -> None:
        if self._pending is not None:  # new settings from this line on; the lines before stay
            tip, mode, settings = self._pending
            self._pending = None
            self.scan = Scan(self.scan.sample, tip, mode, settings, images=self._images)
            self._lines = self.scan.lines(start=self.lines_done)
            self._changes.append(self.lines_done)
        record = next(self._lines, None)
        if record is None:
            self._end("done")
            return
        n = self.scan.settings.pixels
        self._pixels_done = (record.row + (record.crash is None)) * n
        if record.crash is not None:
            self._end("fault", record.crash)
        elif self.lines_done >= self.scan.settings.lines:
            self._end("done")
