"""Module (f): virtual imaging, built on modules (a), (c) and (d), still pure (no UI, no I/O).

- :mod:`.dilation`: the surface the tip apex follows (grey-scale dilation of the sample by the
  tip), the certainty map and blind tip estimation;
- :mod:`.settings`, :mod:`.scanner` and :mod:`.modes`: the scanner's settings, the scanner (scan
  range, pixels, speed, angle, trace and retrace, noise, drift, tilt) and its imaging modes,
  pluggable behind one interface;
- :mod:`.acquisition`: a scan as an acquisition (start, pause, resume, abort, new settings from
  the next line, immutable partial snapshots), the interface the devices' sessions share;
- :mod:`.corrections` and :mod:`.statistics`: levelling, line flattening, scar removal, and the
  statistics users read off an image.
"""
from .corrections import (Plane, fit_plane, flatten_lines, level_plane, mark_scars, mask_features,
                          remove_scars)
from .dilation import (certainty_map, dilate, erode, estimate_tip_radius, sphere_apparent_width,
                       tip_radius_from_width, tip_surface)
from .scan_modes import ConstantForce, ConstantHeight, Crash, Mode, ModeLine, ScanPlan
from .scan_modes import PARAMETERS as MODE_PARAMETERS
from .scanner import LineRecord, Scan, ScanResult, scan
from .settings import PARAMETERS as SCAN_PARAMETERS
from .settings import ScanSettings
from .statistics import Histogram, Profile, histogram, line_profile, ra, rms

__all__ = ["tip_surface", "dilate", "erode", "certainty_map", "estimate_tip_radius",
           "sphere_apparent_width", "tip_radius_from_width", "ScanSettings", "Scan", "ScanResult", "LineRecord", "scan",
           "SCAN_PARAMETERS", "Mode", "ScanPlan", "ModeLine", "Crash", "ConstantForce",
           "ConstantHeight", "MODE_PARAMETERS", "Plane", "fit_plane", "level_plane",
           "flatten_lines", "mask_features", "mark_scars", "remove_scars", "rms", "ra",
           "Histogram", "histogram", "Profile", "line_profile"]
