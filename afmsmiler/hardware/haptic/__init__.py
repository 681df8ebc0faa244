"""The haptic force-feedback device (module (h), part 2): codec, driver, twin and force bridge.

- :mod:`.codec`: the protocol's codes and messages (``hardware/haptic/protocol.h``), pure;
- :mod:`.device`: :class:`HapticDevice`, the driver that takes a transport;
- :mod:`.twin`: :class:`HapticTwin`, the firmware's loop with the motor, encoder and a finger;
- :mod:`.bridge`: :class:`ForceBridge`, forces from a source streamed at a steady rate.
"""
from .codec import DEVICE, Command, ErrorCode, Event, Flag, Param, PositionSample, Status
from .device import HapticDevice, open_haptic
from .twin import Finger, HapticTwin, Mechanics

__all__ = ["DEVICE", "Command", "ErrorCode", "Event", "Flag", "Param", "PositionSample",
           "open_haptic", "Status", "HapticDevice", "HapticTwin", "Finger", "Mechanics"]
