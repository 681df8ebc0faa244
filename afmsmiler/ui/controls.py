"""The one slider factory: every panel control is built from a :class:`~afmsmiler.parameters.Parameter`.

:func:`control` turns a parameter's description into an ipywidgets slider in the parameter's
display unit, bounded by its slider range (inside the valid range, so no position makes the model
raise), linear or logarithmic as described, with the value (the default unless given) *on the
slider's grid*. The browser snaps a slider's value to ``min + n * step`` and echoes it to the
kernel when it first draws the slider; a default off the grid therefore came back changed (a
225 um lever became 225.8 um, a damping of 0.015 ng/us became 0.01585) and the model silently ran
with values nobody chose. Here the grid is anchored on the value, so the echo is the value itself
to within round-off, which :class:`~afmsmiler.ui.panel.Panel` ignores.
"""
from __future__ import annotations

import math

import ipywidgets as widgets

from ..parameters import Parameter
from ..validation import check_integer

__all__ = ["control", "nice_step", "grid", "WIDTH"]

#: Width of a control in px (a panel column; :func:`~afmsmiler.ui.panel.arrange` aligns labels).
WIDTH = "420px"
#: Linear sliders get at least this many steps over their range, log sliders this many per decade.
STEPS, STEPS_PER_DECADE = 200, 40
_NICE = (1.0, 2.0, 2.5, 5.0)
_MAX_STEPS = 100_000  # a slider with more positions than this is not a slider


def nice_step(span: float, steps: int = STEPS) -> float:
    """The largest step of the form {1, 2, 2.5, 5} x 10^n that divides ``span`` into >= ``steps``.

    Parameters
    ----------
    span : float
        The slider's range (high - low), > 0.
    steps : int
        Minimum number of steps, 1 to 100000.

    Returns
    -------
    float
    """
    if not (math.isfinite(span) and span > 0):
        raise ValueError(f"span must be > 0 and finite, got {span!r}")
    check_integer("steps", steps, 1, _MAX_STEPS)
    target = span / steps
    exponent = math.floor(math.log10(target))
    best = 10.0 ** (exponent - 1) * 5.0
    for e in (exponent, exponent + 1):
        for m in _NICE:
            s = m * 10.0 ** e
            if s <= target * (1 + 1e-12):
                best = max(best, s)
    return best


def _on_grid(value: float, step: float) -> bool:
    n = value / step
    return abs(n - round(n)) <= 1e-9 * max(1.0, abs(n))


def grid(value: float, low: float, high: float, step: float, *,
         search: bool = True) -> tuple[float, float, float]:
    """A slider grid (min, max, step) inside [low, high] on which ``value`` lies.

    The step is the largest divisor of ``value`` among the nice steps from ``step`` down to a
    hundredth of it (so the grid reads 0, 0.5, 1, ... when it can); if none divides it, the grid is
    anchored on ``value`` itself.

    Parameters
    ----------
    value : float
        The value that must lie on the grid, in [low, high].
    low, high : float
        The range the grid must stay inside.
    step : float
        The largest step wanted, > 0.
    search : bool
        Look for a smaller nice step that divides ``value`` (linear sliders); else anchor at once.

    Returns
    -------
    tuple of float
        ``(min, max, step)`` with min >= low, max <= high and value = min + n step.
    """
    if not (low <= value <= high):
        raise ValueError(f"value must be in [{low:g}, {high:g}], got {value:g}")
    chosen = step
    if search and value != 0 and not _on_grid(value, step):
        for k in range(0, 3):
            for m in (5.0, 2.5, 2.0, 1.0):
                s = m * 10.0 ** (math.floor(math.log10(step)) - k)
                if s <= step and _on_grid(value, s):
                    chosen = s
                    break
            else:
                continue
            break
    below = math.floor((value - low) / chosen * (1 + 1e-12))
    above = math.floor((high - value) / chosen * (1 + 1e-12))
    return value - below * chosen, value + above * chosen, chosen


def _inside(p: Parameter) -> tuple[float, float]:
    """The slider's range in display units, closed (an open valid bound is never reached)."""
    return p.to_display(p.slider_low), p.to_display(p.slider_high)


def control(p: Parameter, value: float | None = None, *, high: float | None = None,
            readout_format: str = ".4g") -> widgets.FloatSlider | widgets.FloatLogSlider:
    """A slider for ``p`` in its display unit, its grid through ``value``.

    Parameters
    ----------
    p : Parameter
        The parameter's description.
    value : float, optional
        Initial value in SI units (default: ``p.default``); clipped into the slider range.
    high : float, optional
        A tighter upper end in SI (a parameter bounded by another, e.g. an electrode no longer
        than the lever).
    readout_format : str
        Format of the number beside the slider.

    Returns
    -------
    ipywidgets.FloatSlider or ipywidgets.FloatLogSlider
        Labelled ``"label [display unit]"``; its ``parameter`` attribute is ``p``.

    Raises
    ------
    ValueError
        If ``value`` is not valid for ``p`` or ``high`` is below the slider's lower end.
    """
    v = p.check(p.default if value is None else value)
    lo, hi = _inside(p)
    if high is not None:
        hi = min(hi, p.to_display(p.check(high)))
        if not hi > lo:
            raise ValueError(f"high must be above {p.name}'s slider minimum "
                             f"{p.slider_low:g} {p.unit}, got {high!r}")
    shown = min(max(p.to_display(v), lo), hi)
    common = dict(description=p.title, readout_format=readout_format, continuous_update=True,
                  style={"description_width": "initial"}, layout=widgets.Layout(width=WIDTH))
    if p.log:
        step = 1.0 / STEPS_PER_DECADE
        e_lo, e_hi, step = grid(math.log10(shown), math.log10(lo), math.log10(hi), step,
                                  search=False)
        w = widgets.FloatLogSlider(value=shown, base=10, min=e_lo, max=e_hi, step=step, **common)
    else:
        step = nice_step(hi - lo)
        g_lo, g_hi, step = grid(shown, lo, hi, step)
        w = widgets.FloatSlider(value=shown, min=g_lo, max=g_hi, step=step, **common)
    w.parameter = p
    return w
