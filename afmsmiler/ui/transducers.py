"""The widget panel of module (b): a selector over the eleven transducers, sliders, plots, 3D.

:class:`TransducerPanel` offers the principles of :data:`afmsmiler.transducers.PRINCIPLES`; for the
chosen one it builds a slider for the chain's input and one per parameter from the model's
metadata (:meth:`~afmsmiler.transducers.base.Transducer.parameter_table`): label, practical unit
(um, mW, kHz, ...), bounds (the parameter's valid range, in the unit shown) and linear or log
scale. Parameters bounded by another (an electrode no longer than the lever, see
``BOUNDED_BY``) get their slider's maximum moved with it, so no slider position makes the model
raise. :meth:`TransducerPanel.update` converts the values to SI, builds the model, and updates
the figure (:class:`~afmsmiler.plots.transducers.TransducerFigure`), the 3D view
(:class:`~afmsmiler.scenes.transducers.TransducerScene`) and the readout in place.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import ipywidgets as widgets

from ..plots.transducers import ChainCurves, TransducerFigure, chain_curves
from ..transducers import PRINCIPLES
from ..transducers.base import LEVER_PARAMETERS, Parameter, Resolution, SignalChain, Transducer
from .panel import Panel, log_slider, slider

__all__ = ["TransducerPanel", "TransducerState", "DEFAULTS", "control_for"]

#: Panel defaults, in one place.
DEFAULTS = dict(principle="optical_beam_deflection", bandwidth=1e3, figsize=(10.0, 3.8),
                slider_steps=400)

_FIXED = ("principle", "mode", "input")
#: The sliders of the lever every model shares; :meth:`TransducerPanel.widget` gives them a column.
_LEVER = tuple(p.name for p in LEVER_PARAMETERS)


def control_for(p: Parameter, value: float | None = None, high: float | None = None):
    """A slider for parameter ``p`` in its display unit, bounded by its valid range.

    Parameters
    ----------
    p : Parameter
        The parameter's metadata.
    value : float, optional
        Initial value in SI (default: the parameter's default).
    high : float, optional
        A tighter upper bound in SI (for parameters bounded by another).

    Returns
    -------
    ipywidgets.FloatSlider or ipywidgets.FloatLogSlider
    """
    value = p.default if value is None else value
    hi = p.high if high is None else min(high, p.high)
    s = p.scale
    label = p.label or p.name
    if p.log:
        return log_slider(label, value * s, p.low * s, hi * s, unit=p.display_unit)
    step = (hi - p.low) * s / DEFAULTS["slider_steps"]
    return slider(label, value * s, p.low * s, hi * s, step=step, unit=p.display_unit)


@dataclass(frozen=True)
class TransducerState:
    """What the panel last computed (SI units), for tests and exercises.

    Attributes
    ----------
    model : Transducer
        The model built from the sliders.
    mode : str
        ``"sensing"`` or ``"actuation"``.
    value : float
        The input in SI units.
    chain : SignalChain
        The chain at that input.
    curves : ChainCurves
        The plotted curves (units shown).
    sensitivity : float
        Small-signal sensitivity at the input (SI, ``model.sensitivity_quantity(mode).unit``).
    resolution : Resolution
        Noise-limited resolution in ``DEFAULTS["bandwidth"]``, referred to the input.
    """

    model: Transducer
    mode: str
    value: float
    chain: SignalChain
    curves: ChainCurves
    sensitivity: float
    resolution: Resolution


class TransducerPanel(Panel):
    """Selector, mode, input and parameter sliders for any of the eleven transducer models.

    Controls: ``principle`` (a key of :data:`~afmsmiler.transducers.PRINCIPLES`), ``mode``
    (``"sensing"``/``"actuation"``; a choice only for the piezoelectric film), ``input`` (the
    chain's input in its display unit, e.g. nm of tip deflection or V of drive) and one slider per
    model parameter, named like the parameter, in its display unit. Changing the principle or the
    mode rebuilds the sliders (``controls`` changes with it).

    Parameters
    ----------
    principle : str
        The principle shown first.
    scene : bool
        Draw the 3D view in the kernel's meshcat viewer (show it with
        ``get_viewer().jupyter_cell()``; close it with ``close_viewer()``).

    Attributes
    ----------
    last : TransducerState
        The last model result.
    figure : TransducerFigure
        The three plots.
    scene : TransducerScene or None
        The 3D view.
    readout : ipywidgets.HTML
        Table I's row of the principle, k, f1, the sensitivity and the resolution (and, after
        ``close_viewer()``, how to get the 3D view back).
    """

    def __init__(self, principle: str = DEFAULTS["principle"], scene: bool = True):
        if principle not in PRINCIPLES:
            raise ValueError(f"principle must be one of {list(PRINCIPLES)}, got {principle!r}")
        self._selector = widgets.Dropdown(
            options=[(cls.name, key) for key, cls in PRINCIPLES.items()], value=principle,
            description="principle")
        self._mode = widgets.ToggleButtons(options=list(PRINCIPLES[principle].MODES),
                                           description="mode")
        self.readout = widgets.HTML()
        # the two columns of widget(): the principle's chain, and the lever with the readout
        self._chain, self._lever = widgets.VBox(), widgets.VBox()
        self.figure = None
        self.scene = None
        self._want_scene = bool(scene)
        self._ready = False
        self.fig = self.new_figure(figsize=DEFAULTS["figsize"])
        self._build(principle)
        self._selector.observe(self._on_principle, names="value")
        self._mode.observe(self._on_mode, names="value")
        super().__init__()
        self._ready = True

    # -- building the controls from the metadata --------------------------------------------------
    @property
    def model_class(self) -> type:
        return PRINCIPLES[self._selector.value]

    def _build(self, principle: str, mode: str | None = None) -> None:
        cls = PRINCIPLES[principle]
        modes = list(cls.MODES)
        mode = modes[0] if mode is None else mode
        hold, self._hold = self._hold, True
        try:
            if list(self._mode.options) != modes:
                self._mode.options = modes
            self._mode.value = mode
            self._mode.disabled = len(modes) == 1
            model = cls()
            sliders = {"input": control_for(model.input_quantity(mode))}
            for name, p in cls.parameter_table().items():
                sliders[name] = control_for(p, high=model.upper_bound(name))
            old = getattr(self, "controls", {})
            for name, c in old.items():
                if name not in ("principle", "mode"):
                    c.unobserve_all()
            self.controls = {"principle": self._selector, "mode": self._mode, **sliders}
            if self._ready:
                for c in sliders.values():
                    c.observe(self._on_change, names="value")
            self._chain.children = [self._selector, self._mode,
                                    *(c for n, c in sliders.items() if n not in _LEVER)]
            self._lever.children = [*(c for n, c in sliders.items() if n in _LEVER),
                                    self.readout]
        finally:
            self._hold = hold

    def _on_principle(self, change) -> None:
        self._build(change["new"])

    def _on_mode(self, change) -> None:
        if not self._hold and change["new"] is not None:
            self._switch_mode(change["new"])

    def _switch_mode(self, mode: str) -> None:
        """Rebuild the input slider for ``mode``, keeping the parameters' values."""
        keep = {n: c.value for n, c in self.controls.items() if n not in _FIXED}
        self._build(self._selector.value, mode)
        hold, self._hold = self._hold, True
        try:
            for n, v in keep.items():
                self.controls[n].value = v
        finally:
            self._hold = hold

    def set(self, **values) -> None:
        """Set control values as a user would (one update at the end).

        ``principle`` and ``mode`` are applied first, so their sliders can be set in the same call.
        """
        hold, self._hold = self._hold, True
        try:
            if "principle" in values and values["principle"] != self._selector.value:
                if values["principle"] not in PRINCIPLES:
                    raise ValueError(f"principle must be one of {list(PRINCIPLES)}, "
                                     f"got {values['principle']!r}")
                self._selector.value = values["principle"]
            if "mode" in values and values["mode"] != self._mode.value:
                if values["mode"] not in self._mode.options:
                    raise ValueError(f"mode must be one of {list(self._mode.options)}, "
                                     f"got {values['mode']!r}")
                self._switch_mode(values["mode"])
            rest = {k: v for k, v in values.items() if k not in ("principle", "mode")}
            unknown = set(rest) - set(self.controls)
            if unknown:
                raise TypeError(f"unknown control(s) {sorted(unknown)}; "
                                f"valid: {sorted(self.controls)}")
            for name, v in rest.items():
                self.controls[name].value = v
        finally:
            self._hold = hold
        self._run(self.values())

    # -- the callback -----------------------------------------------------------------------------
    def _bound_linked_sliders(self, cls, values: dict) -> dict:
        """Move the maxima of sliders bounded by another parameter; return the clamped values."""
        table = cls.parameter_table()
        for name, (other, factor) in cls.BOUNDED_BY.items():
            p = table[name]
            high = min(p.high, factor * values[other] / table[other].scale) * p.scale
            control = self.controls[name]
            if control.max != high:
                hold, self._hold = self._hold, True
                try:
                    if control.value > high:
                        control.value = high
                    control.max = high
                finally:
                    self._hold = hold
            values[name] = control.value
        return values

    @staticmethod
    def _to_si(cls, params: dict) -> dict:
        """Slider values -> SI, kept inside the valid ranges against float round-off.

        The sliders' bounds are the ranges in display units; dividing by the display scale can
        land one rounding error outside them (20 mW -> 0.020000000000000004 W).
        """
        table = cls.parameter_table()
        si = {n: min(max(v / table[n].scale, table[n].low), table[n].high)
              for n, v in params.items()}
        for name, (other, factor) in cls.BOUNDED_BY.items():
            si[name] = min(si[name], factor * si[other])
        return si

    def update(self, principle, mode, input, **params) -> None:  # noqa: A002 - a control name
        """Convert the control values to SI, run the model, update plots, scene and readout."""
        cls = PRINCIPLES[principle]
        params = self._bound_linked_sliders(cls, dict(params))
        model = cls(**self._to_si(cls, params))
        q = model.input_quantity(mode)
        value = min(max(input / q.scale, q.low), q.high)
        curves = chain_curves(model, value, mode)
        if self.figure is None:
            self.figure = TransducerFigure(curves, fig=self.fig)
        else:
            self.figure.update(curves)
        if self._want_scene and self.scene_open():  # not after close_viewer()
            if self.scene is None:
                from ..scenes.transducers import TransducerScene
                self.scene = TransducerScene(model, value, mode)
            else:
                self.scene.update(model, value, mode)
        self.last = TransducerState(
            model=model, mode=mode, value=value, chain=model.chain(value, mode), curves=curves,
            sensitivity=curves.sensitivity_si,
            resolution=model.resolution(DEFAULTS["bandwidth"], mode=mode))
        self.readout.value = self._readout_html()
        self.redraw()

    def _readout_html(self) -> str:
        s = self.last
        m = s.model
        sq = m.sensitivity_quantity(s.mode)
        q = m.input_quantity(s.mode)
        res = s.resolution
        total = res.total * q.scale
        rows = [("Table I", f"{m.function}; {m.signal}; {m.size}"),
                ("lever k, f1",
                 f"{m.spring_constant:.3g} N/m, {m.resonance_frequency / 1e3:.4g} kHz"),
                ("sensitivity here", f"{s.sensitivity * sq.scale:.4g} {sq.display_unit}"),
                (f"resolution in {DEFAULTS['bandwidth'] / 1e3:g} kHz",
                 (f"{total:.3g} {q.display_unit} (mostly {res.dominant})"
                  if math.isfinite(total) else "no small-signal response here"))]
        table = "".join(f"<tr><td>{k}</td><td style='text-align:right'><b>{v}</b></td></tr>"
                        for k, v in rows)
        notes = "".join(f"<div style='color:#b00'>{n}</div>"
                        for n in m.validity(s.value, s.mode))
        if self._want_scene and self.scene is None and self._viewer_closed:
            notes += ("<div style='margin-top:6px'>3D view closed (<code>close_viewer()</code>); "
                      "run <code>get_viewer().jupyter_cell()</code> and move a slider to see it "
                      "again</div>")
        return f"<div><i>{m.summary}</i></div><table>{table}</table>{notes}"

    def widget(self) -> widgets.Widget:
        """The principle's controls beside the lever's sliders and the readout, the figure below.

        With selector, mode, up to thirteen sliders and the readout in one column and the figure
        under it, the panel was 1100-1300 px high: the student could not see a slider and the
        plots it moves at the same time. Here the first column holds the selector, the mode, the
        input and the principle's own parameters, the second the lever's (length, width,
        thickness, Q, temperature) with the readout under them; the figure (1000 x 380 px)
        follows: about 750 px high, at most about 1100 px wide. In a narrower notebook
        :func:`~afmsmiler.ui.panel.arrange` wraps the second column below the first, still above
        the figure. The columns' children change with the principle.

        Returns
        -------
        ipywidgets.VBox
            ``[HBox([chain column, lever column + readout]), figure]``.
        """
        figure = super().widget().children[1]
        self._lever.layout.margin = "0 0 0 16px"
        self.readout.layout.margin = "8px 0 0 0"
        self.readout.layout.width = "460px"  # as wide as the lever's sliders: long lines wrap
        return widgets.VBox([widgets.HBox([self._chain, self._lever]), figure])
