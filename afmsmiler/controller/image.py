"""Constant-force contact-mode imaging: a height map scanned line after line.

A real instrument stays engaged from one line to the next: it traces row i, retraces it, steps
along the slow axis to row i + 1 (at the same x, over one pixel time, so that the topography
under the tip goes in a straight line from the end of row i's retrace to the start of row
i + 1's trace) and traces that row starting from the state the retrace left the loop in. The
whole image is therefore ONE polygon in time,

    trace 0, retrace 0, trace 1, retrace 1, ...

with a knot every pixel time, and :func:`scan_image` runs it through the O(N) closed-form
recursion of :mod:`afmsmiler.controller.polygon` in one call (``chained=True``, the default).
``chained=False`` scans every row independently instead, from the steady state at its first
pixel, as if the tip were re-engaged before each line (all rows as one batch).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..validation import check_flag, check_array, check_instance, check_integer, check_range
from .loop import PARAMETERS, ContactLoop, ScanLine, ScanPass, check_size
from .polygon import polygon_response

#: Most pixels of a scanned image (2048 x 2048 take about 4 s).
MAX_IMAGE_PIXELS = 2048 * 2048
#: Largest pixel size in m: 1 mm, ten times the scan range of any AFM (about 100 um). Beyond
#: some 1e300 m the image's times (pixel / speed, times the pixel count) overflow double precision.
MAX_PIXEL_SIZE = 1e-3

__all__ = ["ScanImage", "scan_image", "MAX_IMAGE_PIXELS", "MAX_PIXEL_SIZE"]


@dataclass(frozen=True)
class ScanImage:
    """Trace and retrace images of a constant-force scan, columns in increasing x.

    Every finished line is kept: row i of each array is line i; :meth:`line` returns one row as
    a :class:`~afmsmiler.controller.ScanLine` (with its times since the start of the image).

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
    heights : numpy.ndarray, optional
        The scanned topography T in m, same shape.
    speed : float
        Scan speed in m/s.
    setpoint : float
        Deflection setpoint R in m.
    offset : float
        Steady-state value of estimate minus topography in m (-k_c R / k_s when K_I > 0).
    chained : bool
        True if each row started from the state the previous row's retrace left (the
        default of :func:`scan_image`), False if each row started from its own steady state.
    """

    trace: np.ndarray
    retrace: np.ndarray
    trace_z_np: np.ndarray
    retrace_z_np: np.ndarray
    pixel_size: float
    stable: bool
    z_np_flat: float = 0.0
    heights: np.ndarray | None = None
    speed: float = np.nan
    setpoint: float = np.nan
    offset: float = 0.0
    chained: bool = True

    @property
    def height_trace(self) -> np.ndarray:
        """The constant-force "height" image of the trace, -(Z_np - z_np_flat), in m."""
        return -(self.trace_z_np - self.z_np_flat)

    @property
    def height_retrace(self) -> np.ndarray:
        """The constant-force "height" image of the retrace, -(Z_np - z_np_flat), in m."""
        return -(self.retrace_z_np - self.z_np_flat)

    @property
    def pixel_time(self) -> float:
        """Time in s from one pixel to the next (pixel_size / speed)."""
        return self.pixel_size / self.speed

    @property
    def line_time(self) -> float:
        """Time in s from the start of one row's trace to the start of the next row's trace.

        (2 columns - 1) pixel times: trace, retrace (sharing the turn-around pixel) and the
        one-pixel step along the slow axis.
        """
        return (2 * self.trace.shape[1] - 1) * self.pixel_time

    def line(self, row: int) -> ScanLine:
        """Row ``row`` of the image as a :class:`~afmsmiler.controller.ScanLine`.

        Parameters
        ----------
        row : int
            Row index (0-based; negative counts from the end).

        Returns
        -------
        ScanLine
            Times in s since the start of the image's first trace.

        Raises
        ------
        ValueError
            If the row does not exist or the image was built without its heights.
        """
        rows, n = self.trace.shape
        if self.heights is None:
            raise ValueError("line() needs the heights: build the ScanImage with scan_image")
        row = check_integer("row", row, -rows, rows - 1) % rows  # rejects a bool too
        x = np.arange(n) * self.pixel_size
        t0 = row * self.line_time if self.chained else 0.0
        t_trace = t0 + np.arange(n) * self.pixel_time
        t_retrace = t_trace[-1] + np.arange(n) * self.pixel_time
        h = self.heights[row]
        z_np_t, z_np_r = self.trace_z_np[row], self.retrace_z_np[row, ::-1]
        trace = ScanPass(t_trace, x, h, self.trace[row] + z_np_t, z_np_t)
        retrace = ScanPass(t_retrace, x[::-1], h[::-1], self.retrace[row, ::-1] + z_np_r, z_np_r)
        return ScanLine(trace, retrace, self.stable, self.setpoint, self.speed, self.offset)


def scan_image(loop: ContactLoop, heights, pixel_size: float, *,
               speed: float = PARAMETERS["speed"].default,
               setpoint: float = PARAMETERS["setpoint"].default,
               chained: bool = True) -> ScanImage:
    """Scan a height map row after row (trace then retrace of each row), at constant speed.

    Parameters
    ----------
    loop : ContactLoop
        The feedback loop.
    heights : array_like
        Topography in m, shape (rows, columns), at most :data:`MAX_IMAGE_PIXELS` values; the
        fast axis is along the columns, rows are scanned in increasing order.
    pixel_size : float
        Pixel size in m, in (0, :data:`MAX_PIXEL_SIZE`] (1 mm, beyond any AFM's scan range).
    speed : float
        Scan speed in m/s (> 0; keyword-only, like ``setpoint`` and ``chained``).
    setpoint : float
        Deflection setpoint in m.
    chained : bool
        True (default): the tip stays engaged, the loop starts at its steady state at the
        first pixel of row 0 and every later row continues from the end state of the previous
        row's retrace, after a one-pixel-time ramp from that row's first height to the next
        row's. False: every row starts from the steady state at its own first pixel
        (:meth:`ContactLoop.scan_line` row by row).

    Returns
    -------
    ScanImage

    Raises
    ------
    ValueError
        On non-finite heights, a non-2-D array, fewer than 2 columns, pixel_size outside
        (0, 1 mm] or speed out of its range.

    Notes
    -----
    Both modes cost O(rows x columns): one pass of the closed-form recursion over the image's
    rows x (2 columns - 1) knots. An unstable loop still scans (its signals grow to inf, then
    nan) and is flagged by ``stable``.
    """
    check_instance("loop", loop, ContactLoop)
    check_size("heights", heights, MAX_IMAGE_PIXELS)
    h = check_array("heights", heights, "m", ndim=2)
    if h.shape[1] < 2:
        raise ValueError(f"heights must have at least 2 columns, got shape {h.shape}")
    pixel_size = check_range("pixel_size", pixel_size, 0.0, MAX_PIXEL_SIZE, "m",
                             low_inclusive=False)
    speed = PARAMETERS["speed"].check(speed)
    setpoint = PARAMETERS["setpoint"].check(setpoint)
    chained = check_flag("chained", chained)
    rows, n = h.shape
    dt = pixel_size / speed
    path = np.concatenate((h, h[:, ::-1][:, 1:]), axis=1)  # trace then retrace, (rows, 2n - 1)
    forms = loop._forms["step"], loop._forms["ramp"]
    zc0, znp0 = loop.steady_state(setpoint, 0.0)
    zc1, znp1 = loop.steady_state(setpoint, 1.0)
    if chained:
        flat = path.ravel()
        t = np.arange(flat.size) * dt
        z_c, z_np = polygon_response(*forms, t, flat - flat[0], None, uniform=True)
        h0 = flat[0]
        z_c, z_np = z_c.reshape(path.shape), z_np.reshape(path.shape)
    else:
        t = np.arange(2 * n - 1) * dt
        h0 = h[:, :1]
        z_c, z_np = polygon_response(*forms, t, path - h0, None, uniform=True)
    # the steady state at the start height h0 (linear in it), added to the response from rest
    z_c = z_c + zc0 + (zc1 - zc0) * h0
    z_np = z_np + znp0 + (znp1 - znp0) * h0
    topo = z_c - z_np
    return ScanImage(topo[:, :n], topo[:, n - 1:][:, ::-1], z_np[:, :n], z_np[:, n - 1:][:, ::-1],
                     pixel_size, bool(loop.is_stable()), float(znp0), h, speed, setpoint,
                     loop._offset(setpoint), bool(chained))
