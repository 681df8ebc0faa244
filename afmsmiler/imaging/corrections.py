"""The corrections every AFM user applies to an image, as Gwyddion names them.

- :func:`level_plane` ("Plane Level"): subtract the least-squares plane, optionally fitted on
  part of the image only (a mask);
- :func:`flatten_lines` ("Align Rows", median or polynomial): subtract a representative height
  or a polynomial from each scan line, optionally ignoring masked pixels (tall features);
- :func:`remove_scars` ("Remove Scars"): find short horizontal strips, a few rows wide, that
  stand out from the rows above and below, and replace them by the rows around them;
- :func:`mask_features`: mark what stands out above each line's background, to exclude it.

Each takes and returns a :class:`~afmsmiler.samples.Sample` on the same grid (same pixel sizes,
name, units and metadata; only the values change), and never modifies its input.

Masks follow Gwyddion's "Masking" option: ``mask`` is a boolean array of the image's shape that
marks features (True), and ``masking="exclude"`` (the default) fits the background on the other
pixels, ``"include"`` only on the marked ones (a mask of the pixels to use), ``"ignore"`` on all.

Source: P. Klapetek, D. Nečas and C. Anderson, *Gwyddion user guide*, chapter "Data Processing
and Analysis": sections "Leveling" (Plane Level), "Scan Line Artefacts" (Align Rows) and "Data
Edit and Correction" (Mark Scars / Remove Scars), https://gwyddion.net/documentation/.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np
from scipy import ndimage

from ..parameters import Parameter, read_only
from ..samples import Sample
from ..validation import check_choice, check_instance, check_integer, check_range

__all__ = ["PARAMETERS", "DEFAULTS", "MASKING", "METHODS", "MAX_DEGREE", "MAX_SCAR_WIDTH", "Plane",
           "fit_plane", "level_plane", "flatten_lines", "mask_features", "mark_scars",
           "remove_scars"]

#: Gwyddion's masking options: fit on the unmasked pixels, on the masked ones, or on all.
MASKING = ("exclude", "include", "ignore")
#: The line flattening methods of :func:`flatten_lines`.
METHODS = ("median", "polynomial")
#: The highest polynomial degree of :func:`flatten_lines` (Gwyddion's Align Rows offers up to
#: 5; beyond that a row's fit follows its features).
MAX_DEGREE = 5
#: The widest scar in rows (Gwyddion's "Maximum width" goes to 16).
MAX_SCAR_WIDTH = 16

#: The user-settable parameters of the corrections (thresholds are in multiples of the image's
#: RMS difference between neighbouring rows, as Gwyddion states them).
PARAMETERS = read_only({p.name: p for p in (
    Parameter(name="threshold", unit="", default=0.666, low=0.0, high=2.0,
              low_inclusive=False, label="scar threshold (x row-to-row RMS)"),
    Parameter(name="extension_threshold", unit="", default=0.25, low=0.0, high=2.0,
              low_inclusive=False, label="scar extension threshold (x row-to-row RMS)"),
    Parameter(name="min_height", unit="m", display_unit="nm", default=2e-9, low=0.0,
              high=1e-3, low_inclusive=False, slider_low=0.1e-9, slider_high=100e-9, log=True,
              label="feature height above the line's median"),
)})

#: Defaults of the corrections that are counts, not Parameters (Gwyddion's for the scars).
DEFAULTS = read_only(dict(max_width=4, min_length_pixels=16, grow=1))


class Plane(NamedTuple):
    """A plane z = offset + slope_x x + slope_y y (x, y from the image's first pixel).

    Attributes
    ----------
    offset : float
        Height at the first pixel (x = y = 0) in m.
    slope_x, slope_y : float
        Slopes along the fast (x) and slow (y) axes in m/m.
    """

    offset: float
    slope_x: float
    slope_y: float


def _check_sample(sample, ndim=2) -> Sample:
    check_instance("sample", sample, Sample)
    if ndim is not None and sample.heights.ndim != ndim:
        kind = "an image (2-D heights)" if ndim == 2 else "a line (1-D heights)"
        raise ValueError(f"sample must be {kind}, got heights of shape {sample.heights.shape}")
    return sample


def _weights(sample: Sample, mask, masking: str) -> np.ndarray | None:
    """The pixels to fit on (bool array), or None for all of them."""
    check_choice("masking", masking, MASKING)
    if mask is None or masking == "ignore":
        return None
    m = np.asarray(mask)
    if m.dtype != bool:
        raise ValueError(f"mask must be a boolean array (True on features), got an array of "
                         f"{m.dtype}")
    if m.shape != sample.heights.shape:
        raise ValueError(f"mask must have the image's shape {sample.heights.shape}, got "
                         f"{m.shape}")
    return ~m if masking == "exclude" else m.copy()


def _with_heights(sample: Sample, heights: np.ndarray, what: str) -> Sample:
    """``sample`` with new values on the same grid (every other field kept)."""
    return sample.with_heights(heights, f"{sample.name}, {what}" if sample.name else what)


def fit_plane(sample: Sample, mask=None, *, masking: str = "exclude") -> Plane:
    """The least-squares plane through an image's heights (Gwyddion's "Plane Level" fit).

    Minimises sum (z_ij - offset - slope_x x_j - slope_y y_i)^2 over the pixels used, with
    x_j = j pixel_size and y_i = i pixel_size_y.

    Parameters
    ----------
    sample : Sample
        An image (2-D heights in m).
    mask : ndarray of bool, optional
        Features (True), of the image's shape.
    masking : {"exclude", "include", "ignore"}
        Fit on the unmasked pixels, on the masked ones, or on all of them.

    Returns
    -------
    Plane

    Raises
    ------
    ValueError
        If the mask does not fit the image or leaves fewer than three pixels not on a line.
    """
    sample = _check_sample(sample)
    use = _weights(sample, mask, masking)
    rows, cols = sample.heights.shape
    w = np.ones((rows, cols)) if use is None else use.astype(float)
    wx, wy = w.sum(axis=0), w.sum(axis=1)  # pixels used per column and per row
    n = float(wx.sum())
    if n < 3 or np.count_nonzero(wx) < 2 or np.count_nonzero(wy) < 2:
        raise ValueError(f"mask must leave at least three pixels not on one line to fit a plane "
                         f"(masking={masking!r}), got {int(n)} pixels")
    z = sample.heights * w
    x = np.arange(cols) * sample.pixel_size
    y = np.arange(rows) * sample.pixel_size_y
    # the sums of the centred normal equations, a pass each (no copy of the pixels used); the
    # offset decouples, the slopes solve a 2 x 2 system
    xm, ym = wx @ x / n, wy @ y / n
    dx, dy = x - xm, y - ym
    zm = float(z.sum()) / n
    sxx, syy, sxy = wx @ dx ** 2, wy @ dy ** 2, dy @ w @ dx
    sxz, syz = z.sum(axis=0) @ dx, z.sum(axis=1) @ dy
    det = sxx * syy - sxy * sxy
    if not det > 1e-9 * sxx * syy:  # the pixels used lie on one line (a diagonal, say)
        raise ValueError(f"mask must leave at least three pixels not on one line to fit a plane "
                         f"(masking={masking!r}), got {int(n)} pixels on one line")
    slope_x = (syy * sxz - sxy * syz) / det
    slope_y = (sxx * syz - sxy * sxz) / det
    return Plane(float(zm - slope_x * xm - slope_y * ym), float(slope_x), float(slope_y))


def level_plane(sample: Sample, mask=None, *, masking: str = "exclude") -> Sample:
    """Subtract the least-squares plane (:func:`fit_plane`): Gwyddion's "Plane Level".

    The plane is fitted on the pixels the mask selects and subtracted from all of them, so the
    fitted pixels have zero mean afterwards. A tilted sample, or a scanner whose plane is not
    the sample's, shows as such a plane; a tall feature left in the fit tilts it (mask it).

    Parameters
    ----------
    sample : Sample
        An image (2-D heights in m).
    mask : ndarray of bool, optional
        Features (True), of the image's shape.
    masking : {"exclude", "include", "ignore"}
        Fit on the unmasked pixels (default), only on the masked ones (a mask of the pixels to
        use), or on all of them.

    Returns
    -------
    Sample
        The levelled image, same grid.
    """
    p = fit_plane(sample, mask, masking=masking)
    rows, cols = sample.heights.shape
    plane = (p.offset + p.slope_x * sample.pixel_size * np.arange(cols)[None, :]
             + p.slope_y * sample.pixel_size_y * np.arange(rows)[:, None])
    return _with_heights(sample, sample.heights - plane, "plane levelled")


def _fill_rows(values: np.ndarray, valid: np.ndarray) -> np.ndarray:
    """``values`` (rows x k) with the rows that are not ``valid`` interpolated from the nearest
    valid rows above and below (held constant beyond the first and last)."""
    if valid.all():
        return values
    if not valid.any():
        raise ValueError("mask must leave enough pixels in at least one row to fit a line's "
                         "background, got none")
    r = np.arange(values.shape[0])
    return np.stack([np.interp(r, r[valid], values[valid, c]) for c in range(values.shape[1])],
                    axis=1)


def _row_medians(h: np.ndarray, use) -> np.ndarray:
    if use is None:
        return np.median(h, axis=1)
    masked = np.where(use, h, np.nan)
    valid = use.any(axis=1)
    med = np.zeros(h.shape[0])
    if valid.any():
        med[valid] = np.nanmedian(masked[valid], axis=1)
    return _fill_rows(med[:, None], valid)[:, 0]


def _row_polynomials(h: np.ndarray, use, degree: int) -> np.ndarray:
    """The per-row least-squares polynomial background (rows x columns)."""
    rows, cols = h.shape
    t = np.linspace(-1.0, 1.0, cols)  # Legendre basis on [-1, 1]: well conditioned
    v = np.polynomial.legendre.legvander(t, degree)  # (cols, degree + 1)
    w = np.ones_like(h) if use is None else use.astype(float)
    # the normal equations of every row at once: (V^T W_r V) c_r = V^T W_r z_r
    a = np.einsum("rj,jk,jl->rkl", w, v, v)
    b = np.einsum("rj,jk,rj->rk", w, v, h)
    # a row needs degree + 1 distinct used columns; the others take their neighbours' background
    valid = (w > 0).sum(axis=1) >= degree + 1
    coef = np.zeros((rows, degree + 1))
    if valid.any():
        coef[valid] = np.linalg.solve(a[valid], b[valid][..., None])[..., 0]
    coef = _fill_rows(coef, valid)
    return coef @ v.T


def flatten_lines(sample: Sample, method: str = "median", degree: int = 1, mask=None, *,
                  masking: str = "exclude") -> Sample:
    """Flatten each scan line (row) on its own: Gwyddion's "Align Rows".

    ``"median"`` subtracts each row's median height, ``"polynomial"`` the least-squares
    polynomial of ``degree`` in x fitted to the row (0: its mean, 1: its offset and slope, 2: a
    bow ...). Lines are shifted (and tilted) independently because the loop's integrator, drift
    and creep shift each line of an AFM image by its own amount.

    A tall feature that a row crosses pulls that row's median or fit up, so the row is lowered
    too much and the background beside the feature shows dark bands: exclude the feature with
    a mask (e.g. :func:`mask_features`). A row whose unmasked pixels are too few (fewer than
    ``degree + 1``, or none for the median) takes the background of its nearest rows above and
    below, interpolated.

    Parameters
    ----------
    sample : Sample
        An image (2-D heights in m).
    method : {"median", "polynomial"}
        What to subtract from each row.
    degree : int
        Polynomial degree, 0 to :data:`MAX_DEGREE` (``"polynomial"`` only).
    mask : ndarray of bool, optional
        Features (True), of the image's shape.
    masking : {"exclude", "include", "ignore"}
        Fit each row on its unmasked pixels (default), on its masked ones, or on all.

    Returns
    -------
    Sample
        The flattened image, same grid.

    Raises
    ------
    ValueError
        On an unknown method or masking, a degree out of range, a mask that does not fit or
        that leaves no row with enough pixels.
    """
    sample = _check_sample(sample)
    check_choice("method", method, METHODS)
    degree = check_integer("degree", degree, 0, MAX_DEGREE)
    use = _weights(sample, mask, masking)
    h = sample.heights
    if method == "median":
        background = _row_medians(h, use)[:, None]
        what = "lines flattened (median)"
    else:
        background = _row_polynomials(h, use, degree)
        what = f"lines flattened (polynomial, degree {degree})"
    return _with_heights(sample, h - background, what)


def mask_features(sample: Sample, min_height: float = PARAMETERS["min_height"].default,
                  *, grow: int = DEFAULTS["grow"]) -> np.ndarray:
    """Mark the pixels that stand more than ``min_height`` above their line's background.

    The background of each row is its median; pixels above median + min_height are marked and
    the marks are grown by ``grow`` pixels in every direction (a feature's flanks start below
    the threshold), as Gwyddion's "Mark by Threshold" followed by "Grow Mask". Level the image
    first (:func:`level_plane`) if it is tilted along the rows.

    Parameters
    ----------
    sample : Sample
        An image (2-D heights in m).
    min_height : float
        Height above the row's median in m, > 0.
    grow : int
        Pixels added around each mark, 0 to 100.

    Returns
    -------
    ndarray of bool
        True on features, the image's shape.
    """
    sample = _check_sample(sample)
    min_height = PARAMETERS["min_height"].check(min_height)
    grow = check_integer("grow", grow, 0, 100)
    h = sample.heights
    mask = h - np.median(h, axis=1, keepdims=True) > min_height
    if grow:
        mask = ndimage.binary_dilation(mask, np.ones((3, 3), bool), iterations=grow)
    return mask


def _min_length_pixels(sample: Sample, min_length) -> int:
    if min_length is None:
        return min(DEFAULTS["min_length_pixels"], sample.heights.shape[1])
    row = (sample.heights.shape[1] - 1) * sample.pixel_size
    length = check_range("min_length", min_length, 0.0, row, "m", low_inclusive=False)
    return max(1, int(np.ceil(length / sample.pixel_size - 1e-9)))


def _runs_keep(flags: np.ndarray, keep_run) -> np.ndarray:
    """``flags`` keeping only the horizontal runs (within a row) for which ``keep_run`` (given
    the label image and the number of labels) returns True per label (index 0 = background)."""
    labels, n = ndimage.label(flags, structure=[[0, 0, 0], [1, 1, 1], [0, 0, 0]])
    if n == 0:
        return flags
    keep = keep_run(labels, n)
    keep[0] = False
    return keep[labels]


def mark_scars(sample: Sample, threshold: float = PARAMETERS["threshold"].default, *,
               extension_threshold: float = PARAMETERS["extension_threshold"].default,
               min_length: float | None = None, max_width: int = DEFAULTS["max_width"],
               kind: str = "both") -> np.ndarray:
    """Find scars: short strips of rows that stand out from the rows above and below.

    Gwyddion's "Mark Scars" (the first half of "Remove Scars"), in its words: scars are
    horizontal linear defects of shifted values, at most ``max_width`` rows wide and at least
    ``min_length`` long. With sigma the RMS difference between neighbouring rows over the whole
    image, a strip of k <= ``max_width`` rows over a column is a positive scar candidate when its
    lowest value exceeds the higher of the pixels just above and just below it by at least
    ``extension_threshold`` sigma (a negative scar: its highest value lies that far below the
    lower neighbour); each pixel of the strip scores its own excess over that neighbour, in
    sigma. Along each row, a run of candidates is a scar if one of its pixels scores at least
    ``threshold`` (hysteresis: the hard threshold finds the scar, the lower one extends it), and
    if it is at least ``min_length`` long.

    Parameters
    ----------
    sample : Sample
        An image (2-D heights in m, rows along the slow axis).
    threshold : float
        Hard threshold in multiples of sigma, in (0, 2], at least ``extension_threshold``.
    extension_threshold : float
        Threshold for extending a scar along its row, in multiples of sigma, in (0, 2].
    min_length : float, optional
        Shortest scar in m along x (at least one pixel); default 16 pixels (Gwyddion's), or the
        row if shorter.
    max_width : int
        Widest scar in rows, 1 to :data:`MAX_SCAR_WIDTH`.
    kind : {"both", "positive", "negative"}
        Scars that stand up (positive), down (negative), or both.

    Returns
    -------
    ndarray of bool
        True on scar pixels, the image's shape. The first and last rows are never marked (a
        scar needs a row on each side).
    """
    sample = _check_sample(sample)
    high = PARAMETERS["threshold"].check(threshold)
    low = PARAMETERS["extension_threshold"].check(extension_threshold)
    if high < low:
        raise ValueError(f"threshold must be at least extension_threshold ({low:g}), got "
                         f"{high:g}")
    min_px = _min_length_pixels(sample, min_length)
    max_width = check_integer("max_width", max_width, 1, MAX_SCAR_WIDTH)
    check_choice("kind", kind, ("both", "positive", "negative"))
    h = sample.heights
    rows, cols = h.shape
    sigma = float(np.sqrt(np.sum(np.diff(h, axis=0) ** 2) / h.size))
    marks = np.zeros(h.shape, bool)
    if sigma == 0.0 or rows < 3:
        return marks
    width = min(max_width, rows - 2)
    signs = {"both": (1.0, -1.0), "positive": (1.0,), "negative": (-1.0,)}[kind]
    for sign in signs:
        z = sign * h
        score = np.zeros(h.shape)
        z_1d, score_1d = z.reshape(-1), score.reshape(-1)  # views, indexed by row * cols + col
        found = np.zeros((rows - 2, cols), bool)  # start rows whose smallest strip was found
        inner = np.full((rows - 2, cols), np.inf)  # lowest value of rows s+1 .. s+k
        for k in range(1, width + 1):
            n_start = rows - 1 - k  # strips of k rows: rows s+1 .. s+k, neighbours s and s+k+1
            inner = np.minimum(inner[:n_start], z[k:k + n_start])
            ref = np.maximum(z[:n_start], z[k + 1:k + 1 + n_start])
            hit = inner - ref >= low * sigma
            hit &= ~found[:n_start]
            found[:n_start] |= hit
            flat = np.flatnonzero(hit)  # = start row * cols + column
            base = ref.ravel()[flat]
            for s in range(1, k + 1):  # score each pixel of the strip against the neighbours
                at = flat + s * cols
                score_1d[at] = np.maximum(score_1d[at], (z_1d[at] - base) / sigma)

        candidates = score >= low

        def has_hard(labels, n, hard=score >= high):
            keep = np.zeros(n + 1, bool)
            keep[labels[hard]] = True
            return keep

        scars = _runs_keep(candidates, has_hard)
        scars = _runs_keep(scars, lambda labels, n: np.bincount(labels.ravel(),
                                                                minlength=n + 1) >= min_px)
        marks |= scars
    return marks


def remove_scars(sample: Sample, threshold: float = PARAMETERS["threshold"].default, *,
                 extension_threshold: float = PARAMETERS["extension_threshold"].default,
                 min_length: float | None = None, max_width: int = DEFAULTS["max_width"],
                 kind: str = "both") -> Sample:
    """Remove scars: Gwyddion's "Remove Scars".

    The scars :func:`mark_scars` finds are replaced, column by column, by the straight line
    between the pixels just above and just below them (linear interpolation along the slow
    axis, as Gwyddion does); the rest of the image is untouched.

    Parameters
    ----------
    sample : Sample
        An image (2-D heights in m).
    threshold : float
        Hard threshold in multiples of the row-to-row RMS difference (see :func:`mark_scars`).
    extension_threshold : float
        Threshold for extending a scar along its row, same unit.
    min_length : float, optional
        Shortest scar in m; default 16 pixels.
    max_width : int
        Widest scar in rows, 1 to :data:`MAX_SCAR_WIDTH`.
    kind : {"both", "positive", "negative"}
        Which scars to remove.

    Returns
    -------
    Sample
        The image without its scars, same grid.
    """
    marks = mark_scars(sample, threshold, extension_threshold=extension_threshold,
                       min_length=min_length, max_width=max_width, kind=kind)
    h = sample.heights.copy()
    if marks.any():
        rows = np.arange(h.shape[0])[:, None] * np.ones(h.shape[1], int)[None, :]
        good = ~marks
        # the nearest unmarked row above and below each pixel, per column
        above = np.maximum.accumulate(np.where(good, rows, -1), axis=0)
        below = np.minimum.accumulate(np.where(good, rows, h.shape[0])[::-1], axis=0)[::-1]
        col = np.nonzero(marks)[1]
        r = np.nonzero(marks)[0]
        a, b = above[marks], below[marks]
        # mark_scars never marks the first or last row, so both neighbours exist
        t = (r - a) / (b - a)
        h[marks] = (1.0 - t) * sample.heights[a, col] + t * sample.heights[b, col]
    return _with_heights(sample, h, "scars removed")
