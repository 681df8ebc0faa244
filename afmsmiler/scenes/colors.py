"""Colours for scene meshes: a value -> RGB map through a matplotlib colormap.

:class:`ColorScale` maps values to the colours of a colormap through a 256-entry lookup table,
so colouring a mesh costs microseconds (e.g. the diverging ``"RdBu_r"`` map for tension (red) /
compression (blue)); :func:`nice_ceil` rounds colour limits to 1, 2 or 5 x 10^n, so a legend
changes only when a value crosses a round number; :func:`rgb_hex` gives meshcat's 0xRRGGBB.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import matplotlib
import numpy as np

from ..validation import check_positive, check_range

__all__ = ["ColorScale", "nice_ceil", "rgb_hex"]

_LUT_SIZE = 256


@lru_cache(maxsize=32)
def _lut(cmap: str) -> np.ndarray:
    try:
        colormap = matplotlib.colormaps[cmap]
    except KeyError:
        raise ValueError(f"cmap must be a matplotlib colormap name, got {cmap!r}") from None
    lut = colormap(np.linspace(0.0, 1.0, _LUT_SIZE))[:, :3].astype(np.float32)
    lut.setflags(write=False)
    return lut


def rgb_hex(rgb) -> int:
    """The 0xRRGGBB integer meshcat materials take, of ``rgb``, an RGB triple in [0, 1]."""
    r, gr, b = (int(round(255 * float(np.clip(c, 0.0, 1.0)))) for c in rgb[:3])
    return (r << 16) | (gr << 8) | b


@dataclass(frozen=True)
class ColorScale:
    """A linear map from values to colors of a matplotlib colormap.

    Parameters
    ----------
    vmin, vmax : float
        Values mapped to the two ends of the colormap (``vmin < vmax``); values outside are
        clipped to the end colors.
    cmap : str
        A matplotlib colormap name; the default ``"RdBu_r"`` is diverging: ``vmin`` blue,
        ``vmax`` red, the midpoint white.
    label : str
        What the values are, e.g. ``"bending stress"``.
    unit : str
        Their unit as shown on the legend, e.g. ``"MPa"``.

    Raises
    ------
    ValueError
        If the limits are not finite with ``vmin < vmax`` or ``cmap`` is unknown.
    """

    vmin: float
    vmax: float
    cmap: str = "RdBu_r"
    label: str = ""
    unit: str = ""

    def __post_init__(self):
        vmin = check_range("vmin", self.vmin, -math.inf, math.inf, self.unit)
        check_range("vmax", self.vmax, vmin, math.inf, self.unit, low_inclusive=False)
        _lut(self.cmap)

    @classmethod
    def symmetric(cls, limit: float, cmap: str = "RdBu_r", label: str = "",
                  unit: str = "") -> "ColorScale":
        """A scale from ``-limit`` to ``+limit`` (a diverging map: 0 is the middle color)."""
        limit = check_positive("limit", limit, unit)
        return cls(-limit, limit, cmap, label, unit)

    def normalize(self, values) -> np.ndarray:
        """``values`` as fractions of the scale in [0, 1] (clipped: -inf and +inf go to the ends).

        Parameters
        ----------
        values : array_like
            Real numbers in the scale's unit; NaN has no place on a scale.

        Raises
        ------
        ValueError
            If ``values`` holds NaN or anything but real numbers.
        """
        try:
            v = np.asarray(values)
        except (TypeError, ValueError):  # ragged nested sequences
            raise ValueError("values must be an array of real numbers") from None
        if v.dtype.kind not in "iuf":
            raise ValueError(f"values must be real numbers, got an array of {v.dtype}")
        v = v.astype(float, copy=False)
        n_nan = int(np.count_nonzero(np.isnan(v)))
        if n_nan:
            raise ValueError(f"values must not be NaN, got {n_nan} NaN of {v.size} values")
        # halved, so that limits near +-1.8e308 do not overflow their difference
        span = 0.5 * self.vmax - 0.5 * self.vmin
        return np.clip((0.5 * v - 0.5 * self.vmin) / span, 0.0, 1.0)

    def rgb(self, values) -> np.ndarray:
        """RGB colors in [0, 1] of ``values``: an array of shape ``values.shape + (3,)`` (float32).

        Parameters
        ----------
        values : array_like
            Real numbers in the scale's unit (see :meth:`normalize`).
        """
        idx = np.rint(self.normalize(values) * (_LUT_SIZE - 1)).astype(np.intp)
        return _lut(self.cmap)[idx]

    @property
    def title(self) -> str:
        """``"label [unit]"`` as written on the legend."""
        return f"{self.label} [{self.unit}]" if self.unit else self.label


def nice_ceil(value: float, floor: float) -> float:
    """The smallest 1, 2 or 5 x 10^n that is >= ``value`` (and >= ``floor`` > 0).

    Used for color limits, so that a legend changes only when a value crosses a round number.
    """
    floor = check_positive("floor", floor)
    value = check_range("value", value, -math.inf, math.inf)
    value = max(abs(value), floor)
    exponent = math.floor(math.log10(value))
    for mantissa in (1.0, 2.0, 5.0, 10.0):
        candidate = mantissa * 10.0 ** exponent
        if candidate >= value * (1 - 1e-12):
            return candidate
    return 10.0 ** (exponent + 1)  # pragma: no cover - the loop always returns

