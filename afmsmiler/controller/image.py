"""Constant-force contact-mode imaging: a height map scanned line after line."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..validation import check_array, check_finite, check_positive
from .loop import ContactLoop
from .polygon import polygon_response

__all__ = ["ScanImage", "scan_image"]


@dataclass(frozen=True)
class ScanImage:
    """Trace and retrace images of a constant-force scan, columns in increasing x.

    Parameters
    ----------
    trace, retrace : numpy.ndarray
        Estimated topography Z_c - Z_np in m, shape (rows, columns).
    trace_z_np, retrace_z_np : numpy.ndarray
        Positioner height Z_np in m, same shape.
    pixel_size : float
        Pixel size in m.
    stable : bool
        Routh-Hurwitz verdict on the loop.
    z_np_flat : float
        Z_np in m at equilibrium on a flat sample at height 0 (the positioner's offset).
    """

    trace: np.ndarray
    retrace: np.ndarray
    trace_z_np: np.ndarray
    retrace_z_np: np.ndarray
    pixel_size: float
    stable: bool
    z_np_flat: float = 0.0

    @property
    def height_trace(self) -> np.ndarray:
        """The constant-force "height" image of the trace, -(Z_np - z_np_flat), in m."""
        return -(self.trace_z_np - self.z_np_flat)

    @property
    def height_retrace(self) -> np.ndarray:
        """The constant-force "height" image of the retrace, -(Z_np - z_np_flat), in m."""
        return -(self.retrace_z_np - self.z_np_flat)


def scan_image(loop: ContactLoop, heights, pixel_size: float, speed: float,
               setpoint: float) -> ScanImage:
    """Scan a height map row after row (trace then retrace of each row), at constant speed.

    Each row is scanned as :meth:`ContactLoop.scan_line` does (engaged at the steady state of
    its first pixel, the retrace continuing from the trace's end state); all rows go through the
    O(N) closed-form recursion together, as one batch.

    Parameters
    ----------
    loop : ContactLoop
        The feedback loop.
    heights : array_like
        Topography in m, shape (rows, columns); the fast axis is along the columns.
    pixel_size : float
        Pixel size in m (> 0).
    speed : float
        Scan speed in m/s (> 0).
    setpoint : float
        Deflection setpoint in m.

    Returns
    -------
    ScanImage

    Raises
    ------
    ValueError
        On non-finite heights, a non-2-D array, pixel_size <= 0 or speed <= 0.
    """
    h = check_array("heights", heights, "m", ndim=2)
    if h.shape[1] < 2:
        raise ValueError(f"heights must have at least 2 columns, got shape {h.shape}")
    pixel_size = check_positive("pixel_size", pixel_size, "m")
    speed = check_positive("speed", speed, "m/s")
    setpoint = check_finite("setpoint", setpoint, "m")
    n = h.shape[1]
    dt = pixel_size / speed
    t = np.arange(2 * n - 1) * dt
    path = np.concatenate((h, h[:, ::-1][:, 1:]), axis=1)
    h0 = h[:, :1]
    z_c, z_np = polygon_response(loop._forms["step"], loop._forms["ramp"], t, path - h0, None)
    zc0, znp0 = loop.steady_state(setpoint, 0.0)
    if loop.ki > 0:
        z_c, z_np = z_c + zc0, z_np + znp0 - h0
    else:
        zc1, znp1 = loop.steady_state(setpoint, 1.0)
        z_c, z_np = z_c + zc0 + (zc1 - zc0) * h0, z_np + znp0 + (znp1 - znp0) * h0
    topo = z_c - z_np
    return ScanImage(topo[:, :n], topo[:, n - 1:][:, ::-1], z_np[:, :n], z_np[:, n - 1:][:, ::-1],
                     pixel_size, bool(loop.is_stable()), float(znp0))
