"""Axis limits that hold still while the data stays inside them and rescale when it leaves.

A live figure that refits its axes to the data on every slider move shows a curve that never
seems to move: the force doubles, the axes double with it and the picture is the same. With
:func:`sticky_limits` the axes keep their limits while the data lies inside them and still fills
a fair part of them (a fraction ``shrink`` of the span); when the data leaves them, or has shrunk
below that fraction, they are refitted with some ``headroom`` on the side(s) the data moved
towards, so that the next moves in the same direction do not rescale again at once. The first
fit (no current limits) is the data plus a small ``margin``, as a plain refit would be.

A ``floor`` span keeps all-zero data (an end force F = 0) readable; log axes work in decades (the
margin and headroom are fractions of the span in decades, the floor is in decades); non-finite
values (and, on a log axis, values <= 0) are ignored; no data keeps the current limits.

:func:`hold` applies the policy to one axis of a matplotlib ``Axes`` (any object with
``get_xlim``/``set_xlim``/``get_xscale`` and the y counterparts: no matplotlib import here) and
:func:`data_range` gives the finite extent of a few arrays. Nothing here computes physics.
"""
from __future__ import annotations

import math

import numpy as np

from ..parameters import read_only
from ..validation import check_choice, check_nonnegative, check_range

__all__ = ["DEFAULTS", "data_range", "sticky_limits", "hold"]

#: The policy's defaults, as fractions of the data's span (of its span in decades on a log
#: axis). ``margin``: on each side of a fit; ``headroom``: added on the side(s) the data moved
#: towards when it rescales; ``shrink``: the data must fill at least this fraction of the span,
#: else the axes shrink to it. A rescale leaves the data filling at least
#: 1 / (1 + 2 margin + 2 headroom) = 0.46 of the span, above ``shrink``, so the limits it sets
#: hold at the next update. One 5 % step of a slider (a 5 nN step at F = 100 nN) stays inside
#: the first fit's 8 % margin.
DEFAULTS = read_only(dict(margin=0.08, headroom=0.5, shrink=0.3))

_AXES = ("x", "y")


def data_range(*arrays, log: bool = False) -> tuple[float, float]:
    """The smallest and largest finite values of ``arrays`` (positive ones only if ``log``).

    Parameters
    ----------
    *arrays : array_like
        Data of any shape (scalars too).
    log : bool
        Ignore values <= 0 as well (they cannot be shown on a log axis).

    Returns
    -------
    (low, high) : tuple of float
        ``(nan, nan)`` if no value qualifies (then :func:`sticky_limits` keeps the current
        limits).
    """
    low, high = math.inf, -math.inf
    for a in arrays:
        v = np.asarray(a, dtype=float).ravel()
        keep = np.isfinite(v) & (v > 0) if log else np.isfinite(v)
        v = v[keep]
        if v.size:
            low, high = min(low, float(v.min())), max(high, float(v.max()))
    return (low, high) if low <= high else (math.nan, math.nan)


def _check_policy(margin, headroom, shrink, floor):
    margin = check_range("margin", margin, 0.0, 10.0)
    headroom = check_range("headroom", headroom, 0.0, 10.0)
    floor = check_nonnegative("floor", floor)
    if not math.isfinite(floor):
        raise ValueError(f"floor must be a finite number >= 0, got {floor:g}")
    top = 1.0 / (1.0 + 2.0 * margin + 2.0 * headroom)
    shrink = check_range("shrink", shrink, 0.0, top, high_inclusive=False)
    return margin, headroom, shrink, floor


def _usable(v, log):
    return v is not None and math.isfinite(v) and (v > 0 or not log)


def sticky_limits(current, low, high, *, log: bool = False, margin: float = DEFAULTS["margin"],
                  headroom: float = DEFAULTS["headroom"], shrink: float = DEFAULTS["shrink"],
                  floor: float = 0.0) -> tuple[float, float]:
    """New axis limits for data spanning [low, high], given the limits shown now.

    Parameters
    ----------
    current : (float, float) or None
        The limits shown now (lo < hi); None (or unusable limits: not finite, not increasing,
        not positive on a log axis) for a first fit.
    low, high : float
        The data's extent in the axis's units (order free); a non-finite end (or one <= 0 on a
        log axis) is ignored, both ignored = no data.
    log : bool
        A log axis: the policy works on log10 of the values (spans in decades).
    margin : float
        Fraction of the data's span added on each side of a fit, 0 to 10.
    headroom : float
        Fraction of the data's span added, on a rescale, on the side(s) the data moved towards
        (the side it left through; after a shrink, the side(s) it drew away from), 0 to 10.
    shrink : float
        Rescale when the data fills less than this fraction of the current span; 0 to
        1 / (1 + 2 margin + 2 headroom), exclusive, so that a rescale holds.
    floor : float
        Smallest span of the data, in its units (in decades on a log axis): a narrower extent is
        widened about its middle (all-zero data still gives readable axes), >= 0.

    Returns
    -------
    (lo, hi) : tuple of float
        ``current`` itself (as floats) while the data lies inside it and fills at least
        ``shrink`` of it; else the refit limits, which contain the data. Without data, the
        current limits (or (0, 1), (1, 10) on a log axis, if there are none).

    Raises
    ------
    ValueError
        If a policy parameter is out of its range.

    Examples
    --------
    >>> sticky_limits(None, 0.0, 100.0)                 # first fit: the data and 8 % margins
    (-8.0, 108.0)
    >>> sticky_limits((-8.0, 108.0), 0.0, 95.0)         # a small move inside: unchanged
    (-8.0, 108.0)
    >>> sticky_limits((-8.0, 108.0), 0.0, 120.0)        # it left: headroom on the top
    (-9.6, 189.6)
    """
    margin, headroom, shrink, floor = _check_policy(margin, headroom, shrink, floor)
    to = math.log10 if log else float
    back = (lambda v: 10.0 ** v) if log else float
    ends = [float(v) for v in (low, high) if _usable(float(v), log)]
    cur = None
    if current is not None:
        c0, c1 = (float(v) for v in current)
        if _usable(c0, log) and _usable(c1, log) and c0 < c1:
            cur = (c0, c1)
    if not ends:
        if cur is not None:
            return cur
        return (1.0, 10.0) if log else ((-0.5 * floor, 0.5 * floor) if floor else (0.0, 1.0))
    d_lo, d_hi = min(ends), max(ends)  # the data's ends, untransformed
    a, b = to(d_lo), to(d_hi)
    if b - a < floor:
        mid = 0.5 * (a + b)
        a, b = mid - 0.5 * floor, mid + 0.5 * floor
    span = b - a
    if cur is None:
        grow_low = grow_high = False
    else:
        lo, hi = to(cur[0]), to(cur[1])
        if lo <= a and b <= hi and span >= shrink * (hi - lo):
            return cur
        grow_low, grow_high = a < lo, b > hi
        if not (grow_low or grow_high):  # shrunk: room on the side(s) it drew away from
            gap_low, gap_high = a - lo, hi - b
            grow_low = gap_low >= 0.5 * max(gap_low, gap_high)
            grow_high = gap_high >= 0.5 * max(gap_low, gap_high)
    new_lo = back(a - span * (margin + headroom * grow_low))
    new_hi = back(b + span * (margin + headroom * grow_high))
    # never cut the data (rounding through log10 and back, or an overflow to inf)
    new_lo = min(new_lo, d_lo) if math.isfinite(new_lo) else d_lo
    new_hi = max(new_hi, d_hi) if math.isfinite(new_hi) else d_hi
    if not new_lo < new_hi:  # one value and no floor: a span around it
        if log:
            new_lo, new_hi = new_lo / 2.0, new_hi * 2.0
        else:
            pad = 0.1 * abs(new_lo) or 1.0
            new_lo, new_hi = new_lo - pad, new_hi + pad
    return new_lo, new_hi


def hold(ax, axis: str, low: float, high: float, *, reset: bool = False, log: bool | None = None,
         margin: float = DEFAULTS["margin"], headroom: float = DEFAULTS["headroom"],
         shrink: float = DEFAULTS["shrink"], floor: float = 0.0) -> tuple[float, float]:
    """Apply :func:`sticky_limits` to one axis of ``ax``; set its limits only if they change.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes (read with ``get_xlim``/``get_ylim``, set with ``set_xlim``/``set_ylim``).
    axis : {"x", "y"}
        Which axis.
    low, high : float
        The data's extent (see :func:`sticky_limits`; :func:`data_range` of the lines' data).
    reset : bool
        Ignore the limits shown (a figure's first draw, or a change of quantity on the axis).
    log : bool, optional
        A log axis; by default read from the axis's scale (``"log"``).
    margin, headroom, shrink, floor : float
        The policy (see :func:`sticky_limits`).

    Returns
    -------
    (lo, hi) : tuple of float
        The limits now shown.
    """
    axis = check_choice("axis", axis, _AXES)
    get, put = getattr(ax, f"get_{axis}lim"), getattr(ax, f"set_{axis}lim")
    if log is None:
        log = getattr(ax, f"get_{axis}scale")() == "log"
    current = None if reset else tuple(float(v) for v in get())
    new = sticky_limits(current, low, high, log=log, margin=margin, headroom=headroom,
                        shrink=shrink, floor=floor)
    if new != current:
        put(*new)
    return new
