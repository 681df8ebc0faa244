"""Module (e)'s figure: the laser spot on the lever and on the quadrant photodiode.

:class:`InstrumentFigure` draws the optical head's state (:mod:`afmsmiler.instrument`) that the
instrument panel (:mod:`afmsmiler.ui.instrument`) computed once per user action; it computes no
optics itself.
"""
from __future__ import annotations

import math

import numpy as np

from ..instrument import OpticalHead, Signals
from ..parameters import unit_scale

__all__ = ["InstrumentFigure", "SPOT_POINTS"]

#: Points of a drawn spot's outline.
SPOT_POINTS = 65


def _circle(cx, cy, rx, ry, n):
    t = np.linspace(0.0, 2 * math.pi, n)
    return cx + rx * np.cos(t), cy + ry * np.sin(t)


class InstrumentFigure:
    """Two views: the laser spot on the lever (top view, um) and on the photodiode (mm).

    The lever is the rectangle [0, L] x [-w/2, w/2], the chip's body the dashed one behind x = 0
    (the view widens to keep a spot that missed the lever in sight); the spot is
    drawn as its 1/e^2 ellipse (radii w0 / cos(alpha) along the lever and w0 across). The
    photodiode is the square of side ``detector_size`` with its quadrant gaps, seen from the
    lever (vertical up, lateral +y to the left, as the quadrants A B / C D are named); the spot
    is its 1/e^2 circle of radius w(D). Only Line2D artists and texts: a live figure draws them.

    Parameters
    ----------
    head : OpticalHead
        Sets the fixed outlines (lever, photodiode) and the spots' radii.
    fig : matplotlib.figure.Figure
        The figure to draw into (two axes are added).
    """

    def __init__(self, head: OpticalHead, fig):
        self.fig = fig
        um, mm = unit_scale("um"), unit_scale("mm")
        self._um, self._mm = um, mm
        self.ax_lever, self.ax_detector = fig.subplots(1, 2)
        lever = head.lever
        L, w = lever.length * um, lever.width * um
        ax = self.ax_lever
        ax.plot([0, L, L, 0], [-w / 2, -w / 2, w / 2, w / 2], color="0.3", lw=1.5,
                label="lever")
        cl, cw = head.chip_length * um, head.chip_width * um
        ax.plot([0, -cl, -cl, 0, 0], [-cw / 2, -cw / 2, cw / 2, cw / 2, -cw / 2], color="0.3",
                lw=1, ls="--", label="chip")
        self._lever_box = (-0.3 * L, 1.3 * L, -2 * w, 2 * w)
        self.lines = {}
        self.lines["lever_spot"], = ax.plot([], [], color="#d62728", lw=1.5, label="laser spot")
        self.lines["lever_centre"], = ax.plot([], [], "o", color="#d62728", ms=3)
        ax.set_xlim(*self._lever_box[:2])
        ax.set_ylim(*self._lever_box[2:])
        ax.set_xlabel("along the lever x [um] (free end at L)")
        ax.set_ylabel("across y [um]")
        ax.set_title("spot on the lever (top view, y stretched)")
        a = head.detector_size / 2 * mm
        ax = self.ax_detector
        ax.plot([-a, a, a, -a, -a], [-a, -a, a, a, -a], color="0.3", lw=1.5, label="photodiode")
        ax.plot([-a, a], [0, 0], color="0.3", lw=0.8)
        ax.plot([0, 0], [-a, a], color="0.3", lw=0.8)
        for label, (x, y) in zip("ABCD", ((0.5, 0.5), (-0.5, 0.5), (0.5, -0.5), (-0.5, -0.5))):
            ax.text(x * a, y * a, label, ha="center", va="center", color="0.5")
        self.lines["detector_spot"], = ax.plot([], [], color="#d62728", lw=1.5,
                                               label="reflected spot")
        self.lines["detector_centre"], = ax.plot([], [], "o", color="#d62728", ms=3)
        ax.set_xlim(1.5 * a, -1.5 * a)      # lateral +y to the left: A and C on the left
        ax.set_ylim(-1.5 * a, 1.5 * a)
        ax.set_aspect("equal")
        ax.set_xlabel("lateral [mm] (+ to the left)")
        ax.set_ylabel("vertical [mm]")
        ax.set_title("spot on the photodiode")
        fig.tight_layout()

    def update(self, head: OpticalHead, signals: Signals, mounted: bool = True) -> None:
        """Move the spots to where ``signals`` says (no physics here).

        Parameters
        ----------
        head : OpticalHead
            The head the signals come from (spot radii).
        signals : Signals
            One model run's result.
        mounted : bool
            Without a probe no light comes back: the photodiode's spot is hidden.
        """
        n = SPOT_POINTS
        um, mm = self._um, self._mm
        x, y = signals.spot_on_lever
        rx, ry = head.waist / math.cos(head.holder_tilt), head.waist
        self.lines["lever_spot"].set_data(*_circle(x * um, y * um, rx * um, ry * um, n))
        self.lines["lever_centre"].set_data([x * um], [y * um])
        # the lever's neighbourhood, widened to keep a spot that missed it in view
        x0, x1, y0, y1 = self._lever_box
        mx, my = 1.5 * rx * um, 1.5 * ry * um
        self.ax_lever.set_xlim(min(x0, x * um - mx), max(x1, x * um + mx))
        self.ax_lever.set_ylim(min(y0, y * um - my), max(y1, y * um + my))
        v, lat = signals.spot_on_detector
        r = head.detector_spot_radius * mm
        lit = mounted and signals.sum > 0.01 * head.best_sum
        self.lines["detector_spot"].set_data(*_circle(lat * mm, v * mm, r, r, n))
        self.lines["detector_centre"].set_data([lat * mm], [v * mm])
        for name in ("detector_spot", "detector_centre"):
            self.lines[name].set_visible(bool(lit))
