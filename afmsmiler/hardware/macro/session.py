"""The macroscopic AFM's session: a connected :class:`MacroAFM` as an acquisition.

:class:`MacroSession` is the link to one machine (a board on a serial port, or the twin served on
an in-memory link) and the scans made over it, behind the one acquisition interface
(:class:`~afmsmiler.acquisition.Acquisition`): :meth:`~MacroSession.start` homes if needed,
sends the settings once and starts the scan; each :meth:`~afmsmiler.acquisition.Acquisition.step`
reads the pixels the machine has streamed (up to the end of a line, or ``wait`` seconds); pause,
resume and abort are the machine's ``PA``, ``RS`` and ``AB``.

A pixel's way: the machine's ``PX`` frame (bytes) -> the driver's
:class:`~afmsmiler.hardware.macro.codec.Pixel` -> its height written by the driver into the scan's
image (:attr:`ScanProgress.image <afmsmiler.hardware.macro.device.ScanProgress.image>`), which
this session holds as its ``height`` channel (the image is not copied; only a
:meth:`~afmsmiler.acquisition.Acquisition.snapshot` copies it, read-only). A fault (a limit
switch, the cable pulled, a silent board) ends the scan with its finished lines kept.

The machine takes no settings during a scan (it answers ``BUSY``):
:meth:`~afmsmiler.acquisition.Acquisition.apply` refuses them with
:class:`~afmsmiler.acquisition.SettingsRefused` before anything is sent.
"""
from __future__ import annotations

import time

from ...acquisition import SettingsRefused
from ...parameters import shown
from ..errors import DeviceError
from .codec import ErrorCode
from ..session import DeviceSession
from .device import MacroAFM
from .twin import MacroAFMTwin

__all__ = ["MacroSession", "CHANNELS"]

#: The session's channels and their SI units: the height (z micro-steps x ZS) and the gauge's
#: counts above its free reading.
CHANNELS = {"height": "m", "gauge": ""}


class MacroSession(DeviceSession):
    """A connected macroscopic AFM (or its twin), scanning as an acquisition.

    Parameters
    ----------
    device : MacroAFM
        Connected (:meth:`MacroAFM.connect` has identified it).
    server : TwinServer, optional
        The twin's server when the far end is the twin (stopped by :meth:`close`).

    Attributes
    ----------
    identity : str
        Device, protocol and firmware versions, z micro-step (and "(twin)").
    z_step : float
        The z micro-step in m.
    """

    driver = MacroAFM
    twin_class = MacroAFMTwin

    def __init__(self, device: MacroAFM, server=None):
        super().__init__(device, server, CHANNELS, (2, 2), 1.0, main="height",
                         name="macroscopic AFM scan")
        info = device.info
        self.z_step = info.z_step
        self.identity = (f"{info.device} protocol {info.protocol_version}, firmware "
                         f"{info.firmware_version}, z step {shown(info.z_step, 'um', '.3g')}"
                         + (" (twin)" if server is not None else ""))
        self._iter = None

    @classmethod
    def port(cls, port: str) -> "MacroSession":
        """Connect to a board on the serial port ``port`` (pyserial).

        Parameters
        ----------
        port : str
            The port's device name (``"/dev/ttyACM0"``, ``"COM3"``).

        Returns
        -------
        MacroSession
        """
        from ..transport import SerialTransport
        from .codec import BAUDRATE
        return cls.open(SerialTransport(port, baudrate=BAUDRATE))

    # -- the acquisition -----------------------------------------------------------------------
    def _begin(self, *, mode: str, pixels: int, pitch: float, setpoint_force: float,
               lift: float) -> None:
        """Home if needed, send the settings (SI) once, start the scan (``SS``)."""
        self._close_stream()
        if not self.device.status().homed:
            self.device.home()
        self.device.configure(pixels=pixels, lines=pixels, pitch=pitch,
                              setpoint_force=setpoint_force, mode=mode, lift=lift)
        self._allocate((pixels, pixels), pitch)
        self._iter = self.device.scan_iter()

    def _advance(self, wait: float) -> None:
        """The pixels that arrive within ``wait`` s, at most to the end of a line."""
        height, gauge = self._images["height"], self._images["gauge"]
        lines, n = height.shape
        deadline = time.monotonic() + wait
        while True:
            try:
                p = next(self._iter)
            except StopIteration:
                self._iter = None
                self._end("done")
                return
            if p.image is not height and p.image.shape == height.shape:
                self._images["height"] = height = p.image  # the driver's image: held once
            if 0 <= p.row < lines and 0 <= p.col < n:
                gauge[p.row, p.col] = p.counts
                self._pixels_done = max(self._pixels_done, p.row * n + p.col + 1)
            if p.col == n - 1 or time.monotonic() >= deadline:
                break
        if self._pixels_done >= height.size:  # the last pixel came: read to the scan's end
            for _ in self._iter:
                pass
            self._iter = None
            self._end("done")

    def _pause(self) -> bool:
        try:
            self.device.pause()
        except DeviceError as exc:
            if exc.code != ErrorCode.STATE:
                raise
            return False  # the machine had finished: its last pixels are on the way
        return True

    def _resume(self) -> None:
        self.device.resume()

    def _abort(self) -> None:
        try:
            self.device.abort()
        finally:
            self._close_stream()

    def _apply(self, **settings) -> None:
        raise SettingsRefused("the macroscopic AFM takes settings only between scans (it "
                              "answers BUSY while scanning or paused): abort, then start with "
                              "them")

    def _close_stream(self) -> None:
        """Close the scan's generator (the driver forgets the scan; late pixels are ignored)."""
        it, self._iter = self._iter, None
        if it is not None:
            it.close()

    def _release(self) -> None:
        self._close_stream()
