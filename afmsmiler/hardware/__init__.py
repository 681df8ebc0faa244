"""Module (h): hardware interaction, drivers that take a transport (no UI imports).

Layers, bottom to top (scikit-rf's ``skrf.vi`` without its coupling: a device class never opens a
port itself):

- :mod:`.errors`: one exception family (:class:`HardwareError`);
- :mod:`.framing`: the frame format every device speaks (``BODY*CC``, CRC-8/SMBUS), pure;
- :mod:`.protocol`: one declarative parameter table per device (wire code, unit from the one
  unit table, range, default, read-only), pure;
- :mod:`.framed`: :class:`FramedDevice`, the host side every device shares (sequence numbers,
  one deadline per request, retries, identify, replies checked against the table);
- :mod:`.transport`: a serial port (pyserial), a pty, an in-memory pair, a fault injector;
- :mod:`.twin`: a device's protocol simulated in Python and served on a transport;
- device packages (:mod:`.macro`: the macroscopic AFM; :mod:`.educational`: the low-cost
  educational AFM's pixel stream; :mod:`.haptic`: the haptic device and its force bridge)
  with a codec, a device class and a twin;
- :mod:`.printing`: an AFM image as a watertight, printable STL and back;
- :mod:`.ad2`: the Analog Discovery 2 through pydwf (WaveForms runtime needed; a simulated
  library stands in for tests).
"""
from .errors import (ChecksumError, DeviceError, DeviceNotResponding, ErrorCode, FrameError,
                     HardwareError, ProtocolVersionError, ReplyError, TransportClosed,
                     TransportTimeout, WatchdogTripped)
from .framing import MAX_BODY, PROTOCOL_VERSION, Frame, crc8, decode_frame, encode_frame
from .protocol import WIRE_UNITS, ParamTable, WireParam
from .framed import FramedDevice
from .transport import FaultyTransport, MemoryTransport, PtyLink, SerialTransport, Transport
from .twin import Twin, TwinServer, open_twin
from .macro import GaugeCalibration, MacroAFM, MacroAFMCodec, MacroAFMTwin, printed_sample
from .educational import EducationalAFM, EducationalAFMTwin, live_view
from .haptic import HapticDevice, HapticTwin
from .haptic.bridge import ForceBridge
from .ad2 import (AD2Config, AD2Unavailable, AnalogDiscovery2, SimulatedDwfLibrary, open_library,
                  pattern_timing)

__all__ = ["HardwareError", "FrameError", "ChecksumError", "TransportTimeout", "TransportClosed",
           "DeviceNotResponding", "WatchdogTripped", "ProtocolVersionError", "DeviceError",
           "ReplyError", "ErrorCode",
           "ParamTable", "WireParam", "WIRE_UNITS", "FramedDevice",
           "PROTOCOL_VERSION", "MAX_BODY", "crc8", "Frame", "encode_frame", "decode_frame",
           "Transport", "MemoryTransport", "SerialTransport", "PtyLink", "FaultyTransport",
           "Twin", "TwinServer", "open_twin",
           "MacroAFM", "MacroAFMTwin", "MacroAFMCodec", "GaugeCalibration", "printed_sample",
           "EducationalAFM", "EducationalAFMTwin", "live_view", "HapticDevice", "HapticTwin",
           "ForceBridge", "AD2Config", "AD2Unavailable",
           "AnalogDiscovery2", "SimulatedDwfLibrary", "open_library", "pattern_timing"]
