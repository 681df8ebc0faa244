"""The haptic panels: Q control seen (and felt), and the force bridge's source and status.

- :class:`QControlPanel`: sliders for the lever's Q and the controller's gain and phase; one user
  action runs the closed form once with and once without the controller
  (:func:`~afmsmiler.modes.qcontrol.closed_loop_response`, :func:`~afmsmiler.modes.qcontrol.
  ring_down`) and draws the resonance curves and ring-downs
  (:class:`~afmsmiler.plots.haptic.QControlFigure`); given a haptic device, it also sends the
  gain and phase to the device's own Q controller, so the handle rings as the figure shows.
- :class:`BridgePanel`: the source the finger feels (module (d)'s indentation, module (g)'s
  tapping lever slowed down, module (a)'s lever as a spring, the macroscopic AFM's strain gauge)
  and the force scale; the figure shows the force law as the device will render it (clipped at
  its maximum force); :meth:`BridgePanel.run` streams it through a
  :class:`~afmsmiler.hardware.haptic.bridge.ForceBridge` and shows the measured rate, jitter and
  saturation.

Every slider comes from a model's :class:`~afmsmiler.parameters.Parameter`
(:data:`afmsmiler.modes.qcontrol.PARAMETERS`, :data:`afmsmiler.hardware.haptic.bridge.PARAMETERS`)
through :func:`~afmsmiler.ui.controls.control`.
"""
from __future__ import annotations

import functools
import html
import math
from dataclasses import dataclass

import ipywidgets as widgets
import numpy as np

from ..hardware.haptic import bridge as bridge_module
from ..hardware.haptic.bridge import (BridgeStats, CantileverSource, ForceBridge, GaugeSource,
                                      IndentationSource, TappingSource)
from ..modes import qcontrol
from ..modes.qcontrol import (ClosedLoopResponse, QControl, RingDown, closed_loop_response,
                              ring_down, stable_gains)
from ..parameters import read_only, shown
from ..plots.haptic import ForceLawFigure, QControlFigure
from ..validation import check_choice, check_range
from .panel import Panel, initial_values, slider

__all__ = ["QControlPanel", "QControlState", "BridgePanel", "BridgeState", "SOURCES", "status_html",
           "Q_DEFAULTS", "BRIDGE_DEFAULTS"]

_Q = qcontrol.PARAMETERS
_B = bridge_module.PARAMETERS
#: Initial Q-control values in the units shown: a tapping lever in air (Q = 400), no control.
Q_DEFAULTS = read_only({n: _Q[n].to_display(_Q[n].default)
                        for n in ("quality_factor", "gain", "phase")})
#: Most points of a drawn curve.
_CURVE_POINTS = 801
_RING_POINTS_PER_PERIOD = 24
_MAX_RING_PERIODS = 400


@dataclass(frozen=True)
class QControlState:
    """What the Q-control panel last computed (SI units).

    Attributes
    ----------
    qc : QControl
        The lever and controller.
    free, controlled : ClosedLoopResponse
        Resonance curves without and with the controller.
    ring_free, ring : RingDown
        Ring-downs without and with the controller.
    stable_gains : tuple of float
        The open interval of stable gains at this phase.
    """

    qc: QControl
    free: ClosedLoopResponse
    controlled: ClosedLoopResponse
    ring_free: RingDown
    ring: RingDown
    stable_gains: tuple


class QControlPanel(Panel):
    """Sliders for Q, the gain g and the phase phi; the resonance and ring-down figure.

    Controls (units as shown): ``quality_factor`` (log), ``gain``, ``phase`` [deg].

    Parameters
    ----------
    device : HapticDevice, optional
        A haptic device (or its twin's driver): each update also sets its ``qgain`` and
        ``qphase``, so the handle's own Q control follows the sliders (the device's gain is
        relative to its virtual spring KS; see PROTOCOL.md).
    resonance_frequency : float
        The lever's f0 in Hz (drawn as f / f0).
    **initial
        Initial control values (keys of :data:`Q_DEFAULTS`), in the units shown.

    Attributes
    ----------
    last : QControlState
        The last model result.
    figure : QControlFigure
        The two plots.
    readout : ipywidgets.HTML
        Q_eff, f_eff / f0 and the stable gains.
    """

    def __init__(self, device=None, *, resonance_frequency: float = _Q["resonance_frequency"]
                 .default, **initial):
        v = initial_values(initial, Q_DEFAULTS)
        if device is not None and not callable(getattr(device, "configure", None)):
            raise TypeError(f"device must be a HapticDevice, got {type(device).__name__}")
        self.device = device
        self.resonance_frequency = _Q["resonance_frequency"].check(resonance_frequency)
        self.controls = {n: slider(n, _Q[n], v[n]) for n in Q_DEFAULTS}
        self.readout = widgets.HTML()
        self.fig = self.new_figure(figsize=(10.0, 4.2))
        self.figure = QControlFigure(self.fig)
        super().__init__()

    def update(self, *, quality_factor, gain, phase) -> None:
        """Run the closed form once without and once with the controller; draw both.

        Parameters
        ----------
        quality_factor : float
            Q of the lever without control.
        gain : float
            Controller gain g.
        phase : float
            Phase lag phi in rad.
        """
        qc = QControl(resonance_frequency=self.resonance_frequency,
                      quality_factor=quality_factor, gain=gain, phase=phase)
        free_qc = qc.replace(gain=0.0)
        q_eff = qc.effective_quality_factor
        q_low = min(qc.quality_factor, q_eff if math.isfinite(q_eff) and q_eff > 0 else
                    qc.quality_factor)
        q_high = max(qc.quality_factor, q_eff if math.isfinite(q_eff) else qc.quality_factor)
        shift = abs(qc.effective_resonance_frequency / qc.resonance_frequency - 1.0) \
            if qc.stiffness_ratio > 0 else 0.5
        half = min(0.9, max(0.02, 6.0 / q_low, 2.0 * shift))
        f = qc.resonance_frequency * np.linspace(max(1e-3, 1.0 - half), 1.0 + half,
                                                 _CURVE_POINTS)
        periods = min(_MAX_RING_PERIODS, max(5.0, 2.0 * q_high))
        t = np.linspace(0.0, periods, int(periods * _RING_POINTS_PER_PERIOD) + 1) / \
            qc.resonance_frequency
        free = closed_loop_response(f, free_qc)
        controlled = closed_loop_response(f, qc)
        ring_free = ring_down(t, free_qc)
        ring = ring_down(t, qc)
        gains = stable_gains(qc.quality_factor, qc.phase)
        self.last = QControlState(qc, free, controlled, ring_free, ring, gains)
        self.figure.update(free, controlled, ring_free, ring)
        self.redraw()
        self.readout.value = self._readout(qc, gains)
        if self.device is not None:
            self.device.configure(qgain=qc.gain, qphase=qc.phase)

    @staticmethod
    def _readout(qc: QControl, gains) -> str:
        low, high = gains
        if qc.stable:
            q = qc.effective_quality_factor
            state = (f"Q_eff = {q:.4g} (Q = {qc.quality_factor:.4g}), f_eff / f0 = "
                     f"{qc.effective_resonance_frequency / qc.resonance_frequency:.4g}")
        else:
            state = ("<b style='color:#b00020'>unstable</b>: the feedback gives more energy than "
                     "the damping takes, the lever self-oscillates")
        return (f"<div>{state}<br>stable gains at this phase: {low:.4g} &lt; g &lt; "
                f"{high:.4g}</div>")

    def widget(self) -> widgets.Widget:
        """Controls, readout and figure."""
        from .panel import arrange
        box = widgets.VBox([*self.controls.values(), self.readout])
        children = [box] if self.live is None else [box, self.live]
        return arrange(widgets.HBox(children))


# -- the bridge -----------------------------------------------------------------------------------
def _indentation():
    from ..contact import ContactSystem, Parabolic
    system = ContactSystem(tip=Parabolic(radius=20e-9), youngs_modulus=1e9, poisson_ratio=0.3)
    return IndentationSource(system, max_depth=50e-9)


@functools.lru_cache(maxsize=1)
def _tapping():
    from ..modes import TappingLever
    return TappingSource(6e-9, TappingLever(quality_factor=20.0))


def _cantilever():
    from ..cantilever import Cantilever
    return CantileverSource(Cantilever.from_material("silicon", length=125e-6, width=30e-6,
                                                     thickness=4e-6))


#: Source name -> (factory, position_scale, time_scale, what the x axis is): module (d)'s
#: indentation (1 mm of handle = 10 nm into a 1 GPa sample under a 20 nm tip), module (g)'s
#: tapping lever (Q = 20, 300 kHz, at z_c = 6 nm, felt at 2 taps a second) and module (a)'s
#: silicon lever (1 mm of handle = 1 nm of deflection). The gauge is added when a reader is given.
SOURCES = read_only({
    "indentation": (_indentation, 1e-5, 1.0, "position"),
    "tapping": (_tapping, 1.0, 2.0 / 300e3, "time"),
    "cantilever": (_cantilever, 1e-6, 1.0, "position"),
})
#: Initial bridge controls in the units shown.
BRIDGE_DEFAULTS = read_only({"source": "indentation", "force_scale": 1e7})
_HANDLE_TRAVEL = 5e-3  # m of handle shown in a force law


@dataclass(frozen=True)
class BridgeState:
    """What the bridge panel last computed (SI units).

    Attributes
    ----------
    source : str
        The chosen source.
    force_scale : float
        Device N per source N.
    x : ndarray
        Handle positions in m or real times in s of the force law.
    force : ndarray
        Device force in N there, clipped at the maximum force.
    stats : BridgeStats or None
        The bridge's measurement of its last run.
    """

    source: str
    force_scale: float
    x: np.ndarray
    force: np.ndarray
    stats: BridgeStats | None


class BridgePanel(Panel):
    """The force bridge: choose the source and the force scale; run it; see rate and jitter.

    Controls: ``source`` (a drop-down of :data:`SOURCES`, plus ``"gauge"`` when ``gauge`` is
    given), ``force_scale`` (log; device N per source N).

    Parameters
    ----------
    device : HapticDevice, optional
        The device to stream to (needed by :meth:`run` and :meth:`start`).
    gauge : callable, optional
        A gauge reader ``read() -> counts`` (the macroscopic AFM's), with ``gauge_calibration``.
    gauge_calibration : float
        N per gauge count.
    max_force : float
        The device's maximum force in N (default: read from the device, else 2 N).
    **initial
        Initial control values (keys of :data:`BRIDGE_DEFAULTS`).

    Attributes
    ----------
    last : BridgeState
        The last force law and, after a run, the bridge's statistics.
    bridge : ForceBridge or None
        The running or last bridge.
    status : ipywidgets.HTML
        Measured rate, jitter (median, 99th percentile), missed deadlines, saturation.
    """

    def __init__(self, device=None, *, gauge=None, gauge_calibration: float = 1e-3,
                 max_force=None, **initial):
        v = initial_values(initial, BRIDGE_DEFAULTS)
        self.device = device
        self.sources = dict(SOURCES)
        if gauge is not None:
            self.sources["gauge"] = (lambda: GaugeSource(gauge, force_per_count=gauge_calibration),
                                     1.0, 1.0, "position")
        if max_force is None:
            max_force = float(getattr(device, "max_force", 2.0)) if device is not None else 2.0
        self.max_force = check_range("max_force", max_force, 0.0, 100.0, "N",
                                     low_inclusive=False)
        check_choice("source", v["source"], list(self.sources))
        self._built = {}
        self.bridge = None
        self.controls = {
            "source": widgets.Dropdown(options=list(self.sources), value=v["source"],
                                       description="source"),
            "force_scale": slider("force_scale", _B["force_scale"], v["force_scale"]),
        }
        self.status = widgets.HTML("<i>bridge not run yet</i>")
        self.fig = self.new_figure(figsize=(6.5, 4.0))
        self.figure = ForceLawFigure(self.fig)
        super().__init__()

    def _source(self, name):
        """The source object, built once per choice (tapping integrates module (g)'s lever)."""
        if name not in self._built:
            self._built[name] = self.sources[name][0]()
        return self._built[name]

    def update(self, *, source, force_scale) -> None:
        """Build (once) the chosen source and draw its force law as the device will render it.

        Parameters
        ----------
        source : str
            A key of the panel's sources.
        force_scale : float
            Device N per source N.
        """
        scale = force_scale
        src = self._source(source)
        _, pscale, tscale, kind = self.sources[source]
        if kind == "time":
            period = getattr(src, "period", 1.0) / tscale
            x = np.linspace(0.0, 2.0 * period, _CURVE_POINTS)
            raw = np.array([src.force(t * tscale, 0.0) for t in x])
            xs, label = x, "time [s] (as felt)"
        else:
            x = np.linspace(-0.2 * _HANDLE_TRAVEL, _HANDLE_TRAVEL, _CURVE_POINTS)
            raw = np.array([src.force(0.0, xi * pscale) for xi in x])
            xs, label = x * 1e3, "handle position [mm]"
        force = np.clip(scale * raw, -self.max_force, self.max_force)
        stats = self.bridge.stats() if self.bridge is not None else None
        self.last = BridgeState(source, scale, x, force, stats)
        self.figure.update(xs, force, self.max_force, label, getattr(src, "name", source))
        self.redraw()

    def _bridge(self) -> ForceBridge:
        if self.device is None:
            raise RuntimeError("BridgePanel needs a device to stream to: BridgePanel(device)")
        name = self.last.source
        _, pscale, tscale, _ = self.sources[name]
        return ForceBridge(self._source(name), self.device, force_scale=self.last.force_scale,
                           time_scale=tscale, position_scale=pscale, max_force=self.max_force)

    def run(self, duration: float = 1.0) -> BridgeStats:
        """Stream the source to the device for ``duration`` s in this thread; show the status.

        Parameters
        ----------
        duration : float
            Seconds, in (0, 600].

        Returns
        -------
        BridgeStats
        """
        duration = check_range("duration", duration, 0.0, 600.0, "s", low_inclusive=False)
        self.stop()
        self.bridge = self._bridge()
        stats = self.bridge.run(duration=duration)
        self._show(stats)
        return stats

    def start(self) -> None:
        """Stream in the bridge's own thread until :meth:`stop` (call :meth:`refresh` to see)."""
        self.stop()
        self.bridge = self._bridge().start()

    def stop(self) -> BridgeStats | None:
        """Stop a running bridge; its statistics.

        Returns
        -------
        BridgeStats or None
        """
        if self.bridge is None or not self.bridge.running:
            return None
        stats = self.bridge.stop()
        self._show(stats)
        return stats

    def refresh(self) -> BridgeStats | None:
        """Show the running bridge's statistics now.

        Returns
        -------
        BridgeStats or None
        """
        if self.bridge is None:
            return None
        stats = self.bridge.stats()
        self._show(stats)
        return stats

    def _show(self, stats: BridgeStats) -> None:
        self.last = BridgeState(self.last.source, self.last.force_scale, self.last.x,
                                self.last.force, stats)
        self.status.value = status_html(stats)

    def widget(self) -> widgets.Widget:
        """Controls, status and figure."""
        from .panel import arrange
        box = widgets.VBox([*self.controls.values(), self.status])
        children = [box] if self.live is None else [box, self.live]
        return arrange(widgets.HBox(children))


def status_html(stats: BridgeStats) -> str:
    """The bridge's measurement as a short HTML table.

    Parameters
    ----------
    stats : BridgeStats
        From :meth:`ForceBridge.stats`.

    Returns
    -------
    str
    """
    rate = "n/a" if math.isnan(stats.rate) else f"{stats.rate:.1f} Hz"
    rows = [("measured rate", f"{rate} (target {stats.target_rate:g} Hz, {stats.ticks} ticks)"),
            ("jitter, median", "n/a" if math.isnan(stats.jitter_median)
             else shown(stats.jitter_median, "us", ".3g")),
            ("jitter, 99th percentile", "n/a" if math.isnan(stats.jitter_p99)
             else shown(stats.jitter_p99, "us", ".3g")),
            ("missed deadlines", str(stats.missed)),
            ("saturated", f"{100 * stats.saturation:.1f} % of ticks (at "
                          f"{shown(stats.max_force, 'N', '.3g')})")]
    body = "".join(f"<tr><td>{html.escape(a)}</td><td>{html.escape(b)}</td></tr>"
                   for a, b in rows)
    return f"<table>{body}</table>"
