"""Samples for the virtual AFM: the :class:`Sample` type, synthetic generators and file readers.

Every sample carries its values (heights in m) together with its pixel size (m), channel, unit
and metadata, so that a scan, a plot or a 3D view never has to guess its units (:mod:`.sample`);
cropping, resampling and unit conversion are one call each and keep the pixel size. Lines are
1-D samples, images 2-D (rows along the slow axis y, columns along the fast scan axis x).

- :mod:`.synthetic`: :func:`step`, :func:`grating` (a line or a 2-D grating), :func:`terraces`,
  :func:`particles`, :func:`fibres`, :func:`rough_surface` (random surfaces take a ``seed`` and
  are reproducible);
- :mod:`.readers`: :func:`load` reads a real image (AFMReader: ``.spm``, ``.ibw``, ``.jpk``,
  ``.asd``, ``.top``, ``.stp``; gwyfile: ``.gwy``; ``.npy`` and text maps) in SI units,
  :func:`channels` lists a file's channels, :func:`save_gwy` writes a ``.gwy``;
  :data:`REAL_IMAGE` is a real image that ships with the package (a Bruker NanoScope file,
  2 um), and :func:`real_image` reads it;
- :mod:`.profiles`: the named line profiles (:data:`PROFILES`, :func:`profile`) that module
  (c)'s controller scans.
"""
from .profiles import PROFILES, REAL_LINE_ROW, profile
from .readers import REAL_IMAGE, SUFFIXES, channels, from_file, load, real_image, save_gwy
from .sample import MAX_LINE_PIXELS, MAX_PIXELS, Sample
from .synthetic import fibres, grating, particles, rough_surface, step, terraces

__all__ = ["Sample", "MAX_PIXELS", "MAX_LINE_PIXELS", "step", "grating", "terraces",
           "rough_surface", "particles", "fibres", "PROFILES", "profile", "REAL_LINE_ROW",
           "load", "channels", "save_gwy", "SUFFIXES", "from_file", "REAL_IMAGE", "real_image"]
