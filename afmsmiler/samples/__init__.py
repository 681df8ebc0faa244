"""Samples for the virtual AFM: the :class:`Sample` type, synthetic generators and file readers.

Every sample carries its heights (m) together with its pixel size (m), so that a scan, a plot or
a 3D view never has to guess its units (:mod:`.sample`). Lines are 1-D samples, images 2-D (rows
along the slow axis y, columns along the fast scan axis x).

- :mod:`.synthetic`: :func:`step`, :func:`grating`, :func:`rough_surface`, :func:`particles`
  (random surfaces take a ``seed`` and are reproducible);
- :mod:`.readers`: :func:`from_file` reads a real image (WSxM ``.top``/``.stp``) in SI units;
  :data:`REAL_IMAGE` is one that ships with the package (DNA on mica, 500 nm), and
  :func:`real_image` reads it;
- :mod:`.profiles`: the named line profiles (:data:`PROFILES`, :func:`profile`) that module
  (c)'s controller scans.
"""
from .profiles import PROFILES, REAL_LINE_ROW, profile
from .readers import REAL_IMAGE, from_file, real_image
from .sample import MAX_LINE_PIXELS, MAX_PIXELS, Sample
from .synthetic import grating, particles, rough_surface, step

__all__ = ["Sample", "MAX_PIXELS", "MAX_LINE_PIXELS", "step", "grating", "rough_surface",
           "particles", "PROFILES", "profile", "REAL_LINE_ROW", "from_file", "REAL_IMAGE",
           "real_image"]
