"""Module (c): contact-mode feedback loop, solved analytically.

:class:`ContactLoop` holds cantilever, sample and PID gains in SI units and gives the closed-loop
transfer functions (python-control), the Routh-Hurwitz verdict, and responses to polygon
topographies from the closed forms of :mod:`~afmsmiler.controller.derivation` (14 cases),
superposed in O(N) (:mod:`~afmsmiler.controller.polygon`). :data:`PARAMETERS` describes every
user-settable quantity (SI unit, display unit, default, valid and slider ranges).
:func:`scan_image` scans a height map line after line with the tip engaged throughout (each line
continues from the state the previous retrace left); :data:`PRESETS` are the paper's four Fig. 4
scenarios.
"""
from .closed_forms import ClosedForm, classify_roots, closed_form
from .defaults import PRESETS, Preset
from .image import ScanImage, scan_image
from .loop import (LOOP_PARAMETERS, PARAMETERS, ContactLoop, LoopResponse, ScanLine, ScanPass,
                   Stability, polished_roots, routh_hurwitz)

__all__ = ["ContactLoop", "Stability", "LoopResponse", "ScanLine", "ScanPass", "ScanImage",
           "scan_image", "routh_hurwitz", "ClosedForm", "closed_form", "classify_roots",
           "PRESETS", "Preset", "PARAMETERS", "LOOP_PARAMETERS", "polished_roots"]
