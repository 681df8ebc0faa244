"""Figures of the haptic panels: the Q-controlled resonance and ring-down, the felt force law.

They draw model results the panels (:mod:`afmsmiler.ui.haptic`) computed once per user action
and compute no physics themselves; only Line2D artists and texts, so a live figure
(:class:`~afmsmiler.plots.live.LiveFigure`) draws them in the browser.
"""
from __future__ import annotations

import numpy as np

__all__ = ["QControlFigure", "ForceLawFigure"]


class QControlFigure:
    """The closed loop's resonance curve (log amplitude) and its ring-down, beside the free
    lever's.

    Frequencies are drawn as f / f0 and times in periods t / T0 of the free lever, so one figure
    serves a 300 kHz lever and a 30 Hz handle alike.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure to draw into (two axes are added).
    """

    def __init__(self, fig):
        self.fig = fig
        self.ax_response, self.ax_ring = fig.subplots(1, 2)
        ax = self.ax_response
        self.lines = {}
        self.lines["free"], = ax.plot([], [], color="0.6", lw=1.2, ls="--",
                                      label="without Q control")
        self.lines["controlled"], = ax.plot([], [], color="#1f77b4", lw=1.8,
                                            label="with Q control")
        ax.set_yscale("log")
        ax.set_xlabel("drive frequency f / f0 (dimensionless)")
        ax.set_ylabel("amplitude / static deflection (dimensionless)")
        ax.set_title("resonance")
        ax.legend(loc="upper right")
        ax = self.ax_ring
        # solid, not dashed: a ring-down of Q = 400 over 2 Q periods fills the axis, a path of
        # some 150 axis widths (70,000 px), which a dashed stroke cuts into ~10^4 dashes each
        # frame in the browser (issue 24); grey and thinner tells it from the controlled one
        self.lines["ring_free"], = ax.plot([], [], color="0.7", lw=0.8,
                                           label="without Q control")
        self.lines["ring"], = ax.plot([], [], color="#1f77b4", lw=1.4, label="with Q control")
        ax.set_xlabel("time t / T0 (dimensionless)")
        ax.set_ylabel("deflection / initial deflection (dimensionless)")
        ax.set_title("ring-down")
        ax.legend(loc="upper right")
        fig.tight_layout()

    def update(self, free, controlled, ring_free, ring) -> None:
        """Draw two responses and two ring-downs (no physics here).

        Parameters
        ----------
        free, controlled : afmsmiler.modes.qcontrol.ClosedLoopResponse
            Without and with the controller; a controlled loop without a steady state
            (``steady`` false: unstable) draws no resonance curve and says so in the title.
        ring_free, ring : afmsmiler.modes.qcontrol.RingDown
            Without and with the controller, from the same initial deflection.
        """
        f0 = controlled.qc.resonance_frequency
        for name, r in (("free", free), ("controlled", controlled)):
            self.lines[name].set_data(r.frequency / f0, r.amplitude)   # NaN: no steady state
        self.ax_response.set_title(
            "resonance" if controlled.steady else
            "unstable: no steady resonance with Q control",
            color="black" if controlled.steady else "#b00020")
        a0 = ring.deflection[0]
        for name, r in (("ring_free", ring_free), ("ring", ring)):
            self.lines[name].set_data(r.time * f0, r.deflection / a0)
        f = controlled.frequency / f0
        amps = np.concatenate([free.amplitude, controlled.amplitude])
        amps = amps[np.isfinite(amps) & (amps > 0)]
        self.ax_response.set_xlim(float(f[0]), float(f[-1]))
        if amps.size:
            self.ax_response.set_ylim(float(amps.min()) / 1.5, float(amps.max()) * 1.5)
        t = ring.time * f0
        self.ax_ring.set_xlim(0.0, float(t[-1]))
        d = np.concatenate([ring.deflection, ring_free.deflection]) / a0
        d = d[np.isfinite(d)]
        top = float(min(np.abs(d).max(), 1e3)) if d.size else 1.0
        self.ax_ring.set_ylim(-1.1 * top, 1.1 * top)


class ForceLawFigure:
    """The force the finger will feel: device force against handle position or time.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure to draw into (one axes is added).
    """

    def __init__(self, fig):
        self.fig = fig
        self.ax = fig.subplots(1, 1)
        self.lines = {}
        self.lines["force"], = self.ax.plot([], [], color="#1f77b4", lw=1.8,
                                            label="force on the finger")
        self.lines["max"], = self.ax.plot([], [], color="#d62728", lw=1.0, ls="--",
                                          label="device's maximum force")
        self.lines["min"], = self.ax.plot([], [], color="#d62728", lw=1.0, ls="--")
        self.ax.set_ylabel("force on the handle [N]")
        self.ax.legend(loc="upper right")
        fig.tight_layout()

    def update(self, x, force, max_force, xlabel: str, title: str) -> None:
        """Draw a force law (already in the units shown).

        Parameters
        ----------
        x : array_like
            Positions (mm) or times (s).
        force : array_like
            Device force in N, clipped as the bridge clips it.
        max_force : float
            The device's maximum force in N.
        xlabel : str
            The x axis's label.
        title : str
            What the source is.
        """
        x = np.asarray(x, dtype=float)
        force = np.asarray(force, dtype=float)
        self.lines["force"].set_data(x, force)
        self.lines["max"].set_data([x[0], x[-1]], [max_force, max_force])
        self.lines["min"].set_data([x[0], x[-1]], [-max_force, -max_force])
        self.ax.set_xlim(float(x[0]), float(x[-1]))
        self.ax.set_ylim(-1.2 * max_force, 1.2 * max_force)
        self.ax.set_xlabel(xlabel)
        self.ax.set_title(title)
