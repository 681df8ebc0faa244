"""The low-cost educational AFM (module (h), part 2): its pixel stream, a driver and a twin.

- :mod:`.codec`: the EDUAFM protocol's codes and frames (pure); ``hardware/educational_afm/``
  (PROTOCOL.md, protocol.h) at the repository's root is the specification;
- :mod:`.twin`: :class:`EducationalAFMTwin`, module (f)'s scanner imaging a sample, streaming
  ``0 PX row col z``;
- :mod:`.device`: :class:`EducationalAFM`, which collects the stream into a
  :class:`~afmsmiler.samples.Sample` and, through :func:`live_view`, module (f)'s 3D height field.
"""
from .codec import DEVICE, Command, ErrorCode, Event, Param, State
from .device import DeviceInfo, EducationalAFM, live_view
from .twin import EducationalAFMTwin

__all__ = ["DEVICE", "Command", "ErrorCode", "Event", "Param", "State", "EducationalAFM",
           "DeviceInfo", "live_view", "EducationalAFMTwin"]
