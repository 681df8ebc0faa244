"""The one slider factory: every panel control is built from a
:class:`~afmsmiler.parameters.Parameter`.

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
from ..validation import (check_choice, check_finite, check_instance, check_integer,
                          check_positive, check_range)

__all__ = ["control", "nice_step", "grid", "WIDTH", "TYPED", "medium_control", "medium"]

#: Width of a control in px (a panel column; :func:`~afmsmiler.ui.panel.arrange` aligns labels).
WIDTH = "420px"
#: A choice drop-down's entry for values typed on the sliders (a lever's k, f0 and Q; its Q in
#: vacuum), against a preset or a fluid that sets them.
TYPED = "typed"


def medium_control(typed: str, value: str = TYPED) -> widgets.Dropdown:
    """The ``medium`` drop-down of a lever: in vacuum with a typed Q, or in a fluid.

    Parameters
    ----------
    typed : str
        The label of the vacuum entry (what types its Q), e.g. ``"vacuum: Q typed below"``.
    value : str
        :data:`TYPED` or a fluid of :data:`afmsmiler.hydrodynamics.FLUID_NAMES`.

    Returns
    -------
    ipywidgets.Dropdown
        Values :data:`TYPED` and the fluids (:func:`medium` turns one into a model's ``fluid``).
    """
    from ..hydrodynamics import FLUID_NAMES
    options = [(typed, TYPED), *((f"{f}: f1 and Q from Sader", f) for f in FLUID_NAMES)]
    check_choice("fluid", value, [v for _, v in options])
    return widgets.Dropdown(options=options, value=value, description="medium")


def medium(value: str) -> str | None:
    """A ``medium`` drop-down's value as a model's ``fluid``: None for :data:`TYPED`."""
    return None if value == TYPED else value


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

    Raises
    ------
    ValueError
        If ``span`` is not a finite positive number or ``steps`` not an integer in range.
    """
    span = check_positive("span", span)
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
        The finite range the grid must stay inside, ``low <= high``.
    step : float
        The largest step wanted, > 0; at most 100000 steps may fit in ``[low, high]``.
    search : bool
        Look for a smaller nice step that divides ``value`` (linear sliders); else anchor at once.

    Returns
    -------
    tuple of float
        ``(min, max, step)`` with ``low <= min <= value <= max <= high`` and value = min + n step.

    Raises
    ------
    ValueError
        If a number is not finite, the range is empty or holds more than 100000 steps, or
        ``value`` lies outside it.
    """
    low = check_finite("low", low)
    high = check_finite("high", high)
    if not low <= high:
        raise ValueError(f"low must be <= high, got low={low:g}, high={high:g}")
    value = check_range("value", value, low, high)
    step = check_positive("step", step)
    if (high - low) / step > _MAX_STEPS:
        raise ValueError(f"step must divide [{low:g}, {high:g}] into at most {_MAX_STEPS} steps, "
                         f"got {step:g} ({(high - low) / step:.3g} steps)")
    chosen = step
    if search and value != 0 and not _on_grid(value, step):
        for k in range(0, 3):
            for m in (5.0, 2.5, 2.0, 1.0):
                s = m * 10.0 ** (math.floor(math.log10(step)) - k)
                if s <= step and _on_grid(value, s) and (high - low) / s <= _MAX_STEPS:
                    chosen = s
                    break
            else:
                continue
            break
    # An end that lies on the grid up to round-off is kept (the tolerance), but never overshot:
    # a grid end 1e-12 beyond ``low`` would be a slider position the model rejects.
    below = math.floor((value - low) / chosen * (1 + 1e-12))
    above = math.floor((high - value) / chosen * (1 + 1e-12))
    return max(value - below * chosen, low), min(value + above * chosen, high), chosen


def _inside(p: Parameter) -> tuple[float, float]:
    """The slider's range in display units (before the grid keeps clear of open bounds)."""
    return p.to_display(p.slider_low), p.to_display(p.slider_high)


def _valid(p: Parameter, display_value: float) -> bool:
    """Whether the model accepts a slider position (converted to SI as a panel does)."""
    try:
        p.check(p.to_si(display_value))
    except ValueError:
        return False
    return True


def _keep_inside(p: Parameter, lo: float, hi: float, step: float, value: float,
                 position) -> tuple[float, float]:
    """Move a grid end that the model would reject (an open bound, round-off) a step inwards.

    ``position(x)`` is the display value of grid coordinate ``x`` (``10 ** x`` for a log slider).
    """
    for _ in range(2):  # round-off moves an end by less than a step; an open bound by one
        if lo < value and not _valid(p, position(lo)):
            lo = min(lo + step, value)
        if hi > value and not _valid(p, position(hi)):
            hi = max(hi - step, value)
    # An end at the value itself is the value's own position (valid; a log end may miss it by
    # an ulp, which the panel takes as the browser's echo).
    if not all(end == value or _valid(p, position(end)) for end in (lo, hi)):  # pragma: no cover
        raise ValueError(f"{p.name}: no slider grid through {value!r} stays in the valid range")
    return lo, hi


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
        If ``value`` is not valid for ``p``, ``p`` has no finite slider range or ``high`` is
        below the slider's lower end.
    TypeError
        If ``p`` is not a :class:`~afmsmiler.parameters.Parameter`.
    """
    check_instance("p", p, Parameter)
    v = p.check(p.default if value is None else value)
    lo, hi = _inside(p)
    if not (math.isfinite(lo) and math.isfinite(hi)):
        raise ValueError(f"parameter {p.name} needs a finite slider range for a control, got "
                         f"[{p.slider_low:g}, {p.slider_high:g}] {p.unit}")
    if high is not None:
        high = check_finite("high", high, p.unit)
        if not high > p.slider_low:
            raise ValueError(f"high must be above {p.name}'s slider minimum "
                             f"{p.slider_low:g} {p.unit}, got {high!r}")
        hi = min(hi, p.to_display(p.check(high)))
    if not isinstance(readout_format, str):
        raise TypeError(f"readout_format must be a str, got {readout_format!r}")
    shown = min(max(p.to_display(v), lo), hi)
    common = dict(description=p.title, readout_format=readout_format, continuous_update=True,
                  style={"description_width": "initial"}, layout=widgets.Layout(width=WIDTH))
    if p.log:
        step = 1.0 / STEPS_PER_DECADE
        e_v = math.log10(shown)
        e_lo, e_hi, step = grid(e_v, min(math.log10(lo), e_v), max(math.log10(hi), e_v), step,
                                search=False)
        e_lo, e_hi = _keep_inside(p, e_lo, e_hi, step, e_v, lambda e: 10.0 ** e)
        # 10 ** log10(x) can miss x by an ulp; ipywidgets then clamps the value to the end
        # (38.72 um became 38.720000000000006). Move such an end out by a few ulps of exponent.
        for _ in range(64):
            if 10.0 ** e_lo <= shown:
                break
            e_lo = math.nextafter(e_lo, -math.inf)
        for _ in range(64):
            if 10.0 ** e_hi >= shown:
                break
            e_hi = math.nextafter(e_hi, math.inf)
        w = widgets.FloatLogSlider(value=shown, base=10, min=e_lo, max=e_hi, step=step, **common)
    else:
        step = nice_step(hi - lo)
        g_lo, g_hi, step = grid(shown, lo, hi, step)
        g_lo, g_hi = _keep_inside(p, g_lo, g_hi, step, shown, lambda x: x)
        w = widgets.FloatSlider(value=shown, min=g_lo, max=g_hi, step=step, **common)
    w.parameter = p
    return w
