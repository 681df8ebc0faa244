"""The macroscopic AFM (issue 13): codec, mechanics, device class and simulated twin.

- :mod:`.codec`: the protocol's enums and messages, bytes <-> messages (pure);
- :mod:`.mechanics`: the steel ruler (module (a)'s beam), the strain gauge, the calibration;
- :mod:`.device`: :class:`MacroAFM`, the driver (takes a transport);
- :mod:`.twin`: :class:`MacroAFMTwin`, the simulated machine over a virtual printed sample.
"""
from .codec import (Command, ErrorCode, ErrorReply, Event, EventMsg, Flag, LineEnd,
                    MacroAFMCodec, Param, Pixel, Reply, State, Status)
from .device import DeviceInfo, MacroAFM, ScanProgress
from .mechanics import GaugeCalibration, ruler
from .twin import MacroAFMTwin, printed_sample

__all__ = ["Command", "ErrorCode", "Event", "Param", "State", "Flag", "Pixel", "LineEnd",
           "EventMsg", "Reply", "ErrorReply", "Status", "MacroAFMCodec", "MacroAFM",
           "DeviceInfo", "ScanProgress", "GaugeCalibration", "ruler", "MacroAFMTwin",
           "printed_sample"]
