"""The educational AFM's session: a connected :class:`EducationalAFM` as an acquisition.

:class:`EducationalSession` puts the instrument's pixel stream behind the one acquisition
interface (:class:`~afmsmiler.acquisition.Acquisition`). The driver's
:meth:`~afmsmiler.hardware.educational.device.EducationalAFM.scan` reads the whole stream in one
call, so the session runs it on a reader thread, the only thread that talks to the instrument
during a scan: each pixel's height goes from the driver's callback straight into the
acquisition's image (one array cell; no message in between), and
:meth:`~afmsmiler.acquisition.Acquisition.step` waits (at most ``wait`` seconds) for the pixels
to reach the end of the line under way. Abort asks the reader to stop at the next pixel; the
reader then sends ``AB`` itself. A fault (the cable pulled, a silent instrument, a sensor fault)
ends the scan with the pixels received kept.

The instrument's protocol has no pause and takes no settings during a scan: pause raises
:class:`~afmsmiler.acquisition.NotSupported`, apply
:class:`~afmsmiler.acquisition.SettingsRefused`, and the scan goes on.
"""
from __future__ import annotations

import threading
import time

from ...acquisition import NotSupported, SettingsRefused
from ..errors import HardwareError
from ..session import DeviceSession
from .device import EducationalAFM
from .twin import EducationalAFMTwin

__all__ = ["EducationalSession"]


class _Aborted(Exception):
    """Raised in the driver's pixel callback to end its scan (the reader then sends AB)."""


class EducationalSession(DeviceSession):
    """A connected educational AFM (or its twin), scanning as an acquisition.

    Parameters
    ----------
    device : EducationalAFM
        Connected.
    server : TwinServer, optional
        The twin's server when the far end is the twin (stopped by :meth:`close`).

    """

    #: s: the longest :meth:`abort` and :meth:`close` wait for the reader thread, beyond the
    #: driver's own timeout and retries.
    JOIN_MARGIN = 1.0

    driver = EducationalAFM
    twin_class = EducationalAFMTwin

    def __init__(self, device: EducationalAFM, server=None):
        super().__init__(device, server, {"height": "m"}, (2, 2), 1.0, main="height",
                         name="educational AFM scan")
        self._thread = None
        self._stop = threading.Event()
        self._arrived = threading.Condition()
        self._received = 0
        # pixels the reader received that no step has counted yet: a step writes them into the
        # image, so a snapshot never shows a pixel its pixels_done does not count
        self._pending = []
        self._outcome = None   # ("done",), ("aborted",) or ("fault", exc) once the reader ends

    # -- the reader thread ---------------------------------------------------------------------
    def _on_pixel(self, row: int, col: int, height: float) -> None:
        if self._stop.is_set():
            raise _Aborted
        lines, n = self._images["height"].shape
        if 0 <= row < lines and 0 <= col < n:
            with self._arrived:  # at most lines x n pending: one per pixel of the scan
                self._pending.append((row, col, height))
                self._received = max(self._received, row * n + col + 1)
                self._arrived.notify_all()

    def _read(self) -> None:
        try:
            self.device.scan(on_pixel=self._on_pixel)
            outcome = ("done",)
        except _Aborted:
            try:
                self.device.abort()
            except HardwareError:
                pass  # the link may be gone: the scan is over for the host either way
            outcome = ("aborted",)
        except Exception as exc:  # handed to the stepping thread, which ends the scan with it
            outcome = ("fault", exc)
        with self._arrived:
            self._outcome = outcome
            self._arrived.notify_all()

    def _join(self) -> None:
        thread = self._thread
        if thread is not None:
            d = self.device
            thread.join(d.timeout * (d.retries + 2) + self.JOIN_MARGIN)
            self._thread = None

    # -- the acquisition -----------------------------------------------------------------------
    def _begin(self, *, pixels: int, pitch: float, lines: int | None = None) -> None:
        """Send the settings (pixels, lines, pitch in m) and start the reader thread."""
        self._join()
        self.device.configure(pixels=pixels, lines=lines, pitch=pitch)
        self._allocate((pixels if lines is None else lines, pixels), pitch)
        self._stop.clear()
        self._received, self._outcome, self._pending = 0, None, []
        self._thread = threading.Thread(target=self._read, name="educational AFM reader",
                                        daemon=True)
        self._thread.start()

    def _advance(self, wait: float) -> None:
        """The pixels that arrive within ``wait`` s, until the line under way is finished."""
        n = self._images["height"].shape[1]
        line_end = (self._pixels_done // n + 1) * n
        deadline = time.monotonic() + wait
        with self._arrived:
            while self._received < line_end and self._outcome is None:
                remaining = deadline - time.monotonic()
                if remaining <= 0:
                    break
                self._arrived.wait(remaining)
            self._pixels_done, outcome = self._received, self._outcome
            pending, self._pending = self._pending, []
        image = self._images["height"]
        for row, col, height in pending:
            image[row, col] = height
        if outcome is None:
            return
        self._join()
        if outcome[0] == "fault":
            raise outcome[1]
        self._end(outcome[0])

    def _pause(self) -> bool:
        raise NotSupported("the educational AFM cannot pause (its protocol has no such "
                           "command): abort, or let the scan end")

    def _apply(self, **settings) -> None:
        raise SettingsRefused("the educational AFM takes settings only between scans: abort, "
                              "then start with them")

    def _abort(self) -> None:
        self._stop.set()
        self._join()
