"""Module (f): virtual imaging, built on modules (a), (c) and (d), still pure (no UI, no I/O).

- :mod:`.dilation`: the surface the tip apex follows (grey-scale dilation of the sample by the
  tip), the certainty map and blind tip estimation;
- :mod:`.scanner`: the scanner (scan range, pixels, speed, angle, trace and retrace, noise,
  drift, tilt) and its imaging modes, pluggable behind one interface;
- :mod:`.corrections` and :mod:`.statistics`: levelling, line flattening, scar removal, and the
  statistics users read off an image.
"""
