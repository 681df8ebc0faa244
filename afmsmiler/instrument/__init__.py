"""Module (e): the instrument. The optical head of an AFM and its laser alignment, as physics.

:mod:`.optics` holds the paraxial optics (ray matrices, the steering mirror, Gaussian beams and
their overlaps); :mod:`.alignment` the head: its parameter tables (:data:`HEAD`, :data:`KNOBS`
with their travel, :data:`TOLERANCES`), :class:`OpticalHead` with ``turn``/``set``/``signals``/
``aligned``, and :func:`align`, the procedure a student follows, driven by scipy.optimize;
:mod:`.assembly` the two instruments' parts (sizes, places, groups, disassembly) as pure data,
which :mod:`afmsmiler.scenes.instrument` draws.
"""
from .alignment import (DEFAULT_LEVER, HEAD, KNOBS, MAX_SEARCH_POINTS, TOLERANCES, Alignment,
                        AlignmentRun, OpticalHead, Signals, align)
from .assembly import INSTRUMENTS, Instrument, Part, Shape

__all__ = ["DEFAULT_LEVER", "HEAD", "KNOBS", "MAX_SEARCH_POINTS", "TOLERANCES", "Alignment",
           "AlignmentRun", "OpticalHead", "Signals", "align", "INSTRUMENTS", "Instrument", "Part",
           "Shape"]
