"""A device's session: one connected device (and its twin's server) as an acquisition.

:class:`DeviceSession` is what the devices' sessions share, written once: connecting a driver on
a transport (closed again if it cannot connect), connecting to a device's twin on an in-memory
link, and closing (a running scan aborted first, then the link and the twin's server). Each
device's session (:class:`~afmsmiler.hardware.macro.session.MacroSession`,
:class:`~afmsmiler.hardware.educational.session.EducationalSession`) says which driver and twin
it takes and how its scan begins, advances, pauses and stops
(:class:`~afmsmiler.acquisition.Acquisition`).
"""
from __future__ import annotations

from typing import ClassVar

from ..acquisition import Acquisition
from ..validation import check_instance

__all__ = ["DeviceSession", "connect_or_close"]


def connect_or_close(device, server=None):
    """Connect ``device``; if it cannot connect, close it and stop its twin's ``server``.

    Parameters
    ----------
    device : FramedDevice or HapticDevice
        A driver on its transport, not yet connected.
    server : TwinServer, optional
        The twin's server serving the far end.

    Returns
    -------
    object
        ``device``, connected.
    """
    try:
        device.connect()
    except Exception:
        device.close()
        if server is not None:
            server.stop()
        raise
    return device


def _check_server(server):
    """``server`` if it is a TwinServer or None, else TypeError naming it."""
    from .twin import TwinServer
    return None if server is None else check_instance("server", server, TwinServer)


class DeviceSession(Acquisition):
    """A connected device as an acquisition (a base: see the devices' sessions).

    Parameters
    ----------
    device : object
        The connected driver (an instance of :attr:`driver`).
    server : TwinServer or None
        The twin's server when the far end is the twin (stopped by :meth:`close`).
    units, shape, pixel_size, main, name
        As :class:`~afmsmiler.acquisition.Acquisition`.

    Attributes
    ----------
    device : object
    server : TwinServer or None
    """

    #: The driver class the session connects (takes a transport and options).
    driver: ClassVar[type] = object
    #: The twin class that stands for the device (takes what it scans).
    twin_class: ClassVar[type] = object

    def __init__(self, device, server, units, shape, pixel_size: float, *, main: str = "",
                 name: str = ""):
        if not isinstance(device, self.driver) or getattr(device, "info", None) is None:
            raise TypeError(f"device must be a connected {self.driver.__name__}, got "
                            f"{device!r}")
        _check_server(server)
        self.device, self.server = device, server
        super().__init__(units, shape, pixel_size, main=main, name=name)

    @classmethod
    def open(cls, transport, server=None, **options) -> "DeviceSession":
        """Connect the driver on ``transport`` (it is closed again if it cannot connect).

        Parameters
        ----------
        transport : Transport
            The link (a :class:`~afmsmiler.hardware.transport.SerialTransport`, a twin's host
            end, a :class:`~afmsmiler.hardware.transport.FaultyTransport` around either).
        server : TwinServer, optional
            The twin's server serving the far end (stopped if the connection fails).
        **options
            The driver's options (``timeout``, ``retries``).

        Returns
        -------
        DeviceSession
        """
        _check_server(server)
        return cls(connect_or_close(cls.driver(transport, **options), server), server)

    @classmethod
    def twin(cls, scanned, *, time_scale: float = 0.0, **options) -> "DeviceSession":
        """Connect to the device's twin scanning ``scanned`` (a Sample in m), in memory.

        Parameters
        ----------
        scanned : afmsmiler.samples.Sample
            What the twin scans.
        time_scale : float
            The twin's pace (see :class:`~afmsmiler.hardware.twin.TwinServer`; 0: at once).
        **options
            The driver's options.

        Returns
        -------
        DeviceSession
        """
        from .. import hardware  # looked up at the call: tests wrap open_twin's link
        from ..samples import Sample
        check_instance("scanned", scanned, Sample)
        try:
            twin = cls.twin_class(scanned)
        except (TypeError, ValueError) as exc:  # the twin names it as its own sample
            raise type(exc)(f"scanned (the twin's sample): {exc}") from exc
        host, server = hardware.open_twin(twin, time_scale=time_scale)
        return cls.open(host, server, **options)

    def _release(self) -> None:
        """What the session holds of a scan besides the link (closed by :meth:`close`)."""

    def close(self) -> None:
        """Abort a running scan, then close the link and the twin's server."""
        if self.running:
            try:
                self.abort()
            except Exception:  # the link may be gone already
                pass
        self._release()
        try:
            self.device.close()
        finally:
            if self.server is not None:
                self.server.stop()
