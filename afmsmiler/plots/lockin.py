"""The lock-in panel's figure: the lock-in outputs settling, the spectrum, the reference's pickup.

:class:`LockInFigure` draws three axes once and moves their data in place
(:meth:`LockInFigure.update`) from a :class:`~afmsmiler.signals.demo.LockInDemo`; nothing here
computes physics:

1. X(t) and Y(t) after the low-pass, with the closed-form truth (dashed) and the settling time;
2. the output's amplitude spectrum against frequency / drive frequency: the drive's own omega is
   absent from an unbiased heater's motion; 2 omega is the signal; 6 omega is where an
   interference sits that a square reference at 2 omega reads with weight 1/3;
3. the reference's weight on its harmonics h = 1..7 (at h x 2 omega): 1 for a sine at h = 1 only,
   1, 0, 1/3, 0, 1/5 ... for a square.
"""
from __future__ import annotations

import math

import numpy as np
from matplotlib.figure import Figure

from ..parameters import read_only, shown, unit_scale
from ..signals.demo import LockInDemo
from ..validation import check_instance
from .limits import data_range, hold

__all__ = ["LockInFigure", "DEFAULTS", "peaks"]

#: Figure defaults: size, the most points of the spectrum drawn, the display unit of voltages.
DEFAULTS = read_only(dict(figsize=(11.0, 3.8), max_points=3000, unit="mV"))


def peaks(x, y, max_points: int = DEFAULTS["max_points"]):
    """At most ``max_points`` points of (x, y) keeping each group's largest y (peaks stay).

    Parameters
    ----------
    x, y : array_like
        The curve.
    max_points : int
        The most points returned.

    Returns
    -------
    tuple of ndarray
        The decimated x and y.
    """
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    step = max(1, math.ceil(x.size / max_points))
    if step == 1:
        return x, y
    n = (x.size // step) * step
    groups = y[:n].reshape(-1, step)
    k = np.argmax(groups, axis=1) + np.arange(groups.shape[0]) * step
    return x[k], y[k]


class LockInFigure:
    """Three axes: the lock-in's outputs, the spectrum, the reference's harmonic pickup.

    Parameters
    ----------
    demo : LockInDemo
        The first run to show.
    fig : matplotlib.figure.Figure, optional
        Where to draw; a new pyplot-free Figure by default.

    Attributes
    ----------
    axes : dict
        ``"outputs"``, ``"spectrum"``, ``"pickup"``.
    lines : dict
        ``"x"``, ``"y"``, ``"x_true"``, ``"y_true"``, ``"settle"``, ``"spectrum"``,
        ``"pickup"``, updated in place.
    """

    def __init__(self, demo: LockInDemo, fig: Figure | None = None):
        self.fig = fig if fig is not None else Figure(figsize=DEFAULTS["figsize"])
        outputs, spectrum, pickup = self.fig.subplots(1, 3)
        self.axes = dict(outputs=outputs, spectrum=spectrum, pickup=pickup)
        u = DEFAULTS["unit"]
        ln = self.lines = {}
        ln["x"], = outputs.plot([], [], color="C0", label="X")
        ln["y"], = outputs.plot([], [], color="C1", label="Y")
        ln["x_true"] = outputs.axhline(0.0, color="C0", ls="--", lw=1, label="X true")
        ln["y_true"] = outputs.axhline(0.0, color="C1", ls="--", lw=1, label="Y true")
        ln["settle"] = outputs.axvline(0.0, color="0.6", ls=":", lw=1, label="settled")
        outputs.set(xlabel="time [ms]", ylabel=f"lock-in output [{u}]")
        outputs.legend(loc="lower right", fontsize="small")
        ln["spectrum"], = spectrum.semilogy([], [], color="C2", lw=0.8)
        spectrum.set(xlabel="frequency / drive frequency f (dimensionless)",
                     ylabel=f"amplitude [{u}]",
                     title="output spectrum (2f: the signal)")
        ln["pickup"], = pickup.plot([], [], "o-", color="C3")
        pickup.set(xlabel="harmonic h of the reference (at 2 h f) (dimensionless)",
                   ylabel="weight (dimensionless)",
                   ylim=(-0.05, 1.1), xlim=(0.5, 7.5))
        self.fig.set_layout_engine("constrained")
        self.update(demo)

    def update(self, demo: LockInDemo) -> None:
        """Show a new run: line data, readouts in the titles, limits.

        Parameters
        ----------
        demo : LockInDemo
            From :func:`afmsmiler.signals.demo.lock_in_demo`.
        """
        demo = check_instance("demo", demo, LockInDemo)
        u = DEFAULTS["unit"]
        ax, ln = self.axes, self.lines
        r, run = demo.reading, demo.run
        scale = unit_scale(u, "V")
        ms = unit_scale("ms", "s")
        t_ms = r.time * ms
        step = max(1, math.ceil(t_ms.size / DEFAULTS["max_points"]))
        ln["x"].set_data(t_ms[::step], r.x_trace[::step] * scale)
        ln["y"].set_data(t_ms[::step], r.y_trace[::step] * scale)
        truth = demo.truth
        ln["x_true"].set_ydata([truth.real * scale] * 2)
        ln["y_true"].set_ydata([truth.imag * scale] * 2)
        ln["settle"].set_xdata([r.settle_time * ms] * 2)
        ax["outputs"].set_xlim(0.0, t_ms[-1])
        lo, hi = data_range(np.concatenate([r.x_trace[-t_ms.size // 2:],
                                            r.y_trace[-t_ms.size // 2:],
                                            [truth.real, truth.imag, 0.0]]) * scale)
        hold(ax["outputs"], "y", lo, hi, reset=True)
        ax["outputs"].set_title(
            f"R = {shown(r.amplitude, u)} (true {shown(abs(truth), u)}, "
            + (f"{100 * demo.amplitude_error:+.2f} %)" if math.isfinite(demo.amplitude_error)
               else "no drive)") + f"\nphase {math.degrees(r.phase):.2f} deg "
            f"(error {math.degrees(demo.phase_error):+.2f} deg), ENBW {r.enbw:.3g} Hz",
            fontsize="medium")
        f, a = peaks(demo.spectrum.frequency / run.drive_frequency, demo.spectrum.amplitude)
        floor = max(float(np.max(a)) * 1e-9, 1e-30)
        ln["spectrum"].set_data(f, np.maximum(a, floor) * scale)
        ax["spectrum"].set_xlim(0.0, float(f[-1]))
        hold(ax["spectrum"], "y", *data_range(np.maximum(a, floor) * scale, log=True),
             reset=True, log=True, margin=0.1, floor=1.0)
        h = np.arange(1, demo.pickup.size + 1)
        ln["pickup"].set_data(h, demo.pickup)
        ax["pickup"].set_title(f"{r.shape} reference: what it reads", fontsize="medium")
