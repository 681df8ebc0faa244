"""The widget panel of module (b): a selector over the eleven transducers, sliders, plots, 3D.

:class:`TransducerPanel` offers the principles of :data:`afmsmiler.transducers.PRINCIPLES`; for the
chosen one it builds a slider for the chain's input and one per parameter from the model's
:class:`~afmsmiler.parameters.Parameter` entries
(:meth:`~afmsmiler.transducers.base.Transducer.parameter_table`) with the one slider factory,
:func:`afmsmiler.ui.controls.control`: label, practical unit (um, mW, kHz, ...), slider range,
linear or log, and the grid through the default (so the browser's echo never changes a value).
Parameters bounded by another (an electrode no longer than the lever, see ``BOUNDED_BY``) get
their slider's maximum moved with it when the other moves. :meth:`TransducerPanel.update`
converts the values it is given to SI, runs the model once
(:meth:`~afmsmiler.transducers.base.Transducer.operate`: the signal chain evaluated once over the
input range and at the input), and hands the result to the figure
(:class:`~afmsmiler.plots.transducers.TransducerFigure`), the 3D view
(:class:`~afmsmiler.scenes.transducers.TransducerScene`) and the readout, which compute nothing.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import ipywidgets as widgets

from ..parameters import read_only, shown
from ..plots.transducers import ChainCurves, TransducerFigure, chain_curves, frequency_grid
from ..transducers import PRINCIPLES
from ..transducers.base import (LEVER_PARAMETERS, Operation, Resolution, SignalChain,
                                Transducer)
from ..validation import check_choice
from .controls import TYPED, control, medium, medium_control
from .panel import Panel, to_si

__all__ = ["TransducerPanel", "TransducerState", "DEFAULTS", "to_si"]

#: Panel defaults, in one place.
DEFAULTS = read_only(dict(principle="optical_beam_deflection", bandwidth=1e3,
                          figsize=(10.0, 3.8)))

_FIXED = ("principle", "mode", "fluid", "input")
#: The sliders of the lever every model shares; :meth:`TransducerPanel.widget` gives them a column.
_LEVER = tuple(p.name for p in LEVER_PARAMETERS)


@dataclass(frozen=True)
class TransducerState:
    """What the panel last computed (SI units), for tests and exercises.

    Attributes
    ----------
    model : Transducer
        The model built from the control values.
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
    operation : Operation
        The model run all of the above come from.
    """

    model: Transducer
    mode: str
    value: float
    chain: SignalChain
    curves: ChainCurves
    sensitivity: float
    resolution: Resolution
    operation: Operation


class TransducerPanel(Panel):
    """Selector, mode, input and parameter sliders for any of the eleven transducer models.

    Controls: ``principle`` (a key of :data:`~afmsmiler.transducers.PRINCIPLES`), ``mode``
    (``"sensing"``/``"actuation"``; a choice only for the piezoelectric film), ``fluid`` (the
    lever's medium: ``"typed"``, in vacuum with the Q slider's value, or ``"air"``/``"water"``,
    where the lever rings at its f1 in the fluid with the fluid's Q, Sader 1998, and the Q slider
    is disabled), ``input`` (the
    chain's input in its display unit, e.g. nm of tip deflection or V of drive) and one slider per
    model parameter, named like the parameter, in its display unit. Changing the principle or the
    mode rebuilds the sliders (``controls`` changes with it).

    Parameters
    ----------
    principle : str
        The principle shown first.
    scene : bool
        Draw the 3D view in its own widget, shown below the panel by
        :meth:`show` (over the kernel's connection; nothing to close).
    vis : meshcat.Visualizer, optional
        Where to draw instead (tests pass a recorder); implies ``scene``.

    Attributes
    ----------
    last : TransducerState
        The last model result.
    figure : TransducerFigure
        The three plots.
    scene : TransducerScene or None
        The 3D view.
    readout : ipywidgets.HTML
        Table I's row of the principle, k, f1, the sensitivity and the resolution.
    """

    def __init__(self, principle: str = DEFAULTS["principle"], scene: bool = False, vis=None):
        check_choice("principle", principle, PRINCIPLES)
        self._selector = widgets.Dropdown(
            options=[(cls.name, key) for key, cls in PRINCIPLES.items()], value=principle,
            description="principle")
        self._mode = widgets.ToggleButtons(options=list(PRINCIPLES[principle].MODES),
                                           description="mode")
        self._fluid = medium_control("vacuum: Q typed below")
        self.readout = widgets.HTML()
        # the two columns of widget(): the principle's chain, and the lever with the readout
        self._chain, self._lever = widgets.VBox(), widgets.VBox()
        self.figure = None
        self.scene = None
        self._ready = False
        self.fig = self.new_figure(figsize=DEFAULTS["figsize"])
        self._build(principle)
        self._selector.observe(self._on_principle, names="value")
        self._mode.observe(self._on_mode, names="value")
        self._fluid.observe(lambda change: self._typed_q(), names="value")
        super().__init__(scene=scene, vis=vis)
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
            sliders = {"input": control(model.input_quantity(mode))}
            for name, p in cls.parameter_table().items():
                high = model.upper_bound(name) if name in cls.BOUNDED_BY else None
                sliders[name] = control(p, high=high)
            old = getattr(self, "controls", {})
            for name, c in old.items():
                if name not in ("principle", "mode", "fluid"):
                    c.unobserve_all()
            self.controls = {"principle": self._selector, "mode": self._mode,
                             "fluid": self._fluid, **sliders}
            if self._ready:
                for c in sliders.values():
                    c.observe(self._on_change, names="value")
            self._typed_q()
            self._chain.children = [self._selector, self._mode,
                                    *(c for n, c in sliders.items() if n not in _LEVER)]
            self._lever.children = [self._fluid, *(c for n, c in sliders.items() if n in _LEVER),
                                    self.readout]
        finally:
            self._hold = hold

    def _typed_q(self) -> None:
        """The Q slider is the lever's Q only in vacuum; in a fluid the fluid sets Q (readout)."""
        self.controls["quality_factor"].disabled = self._fluid.value != TYPED

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

        Raises
        ------
        ValueError
            For an unknown principle or mode (naming the valid choices), or a value outside its
            slider's range (naming the control and the range).
        TypeError
            For a name that is not a control (of the principle being set).
        """
        if "principle" in values:
            check_choice("principle", values["principle"], PRINCIPLES)
        if "mode" in values:
            principle = values.get("principle", self._selector.value)
            check_choice("mode", values["mode"], PRINCIPLES[principle].MODES)
        hold, self._hold = self._hold, True
        try:
            if "principle" in values and values["principle"] != self._selector.value:
                self._selector.value = values["principle"]
            if "mode" in values and values["mode"] != self._mode.value:
                self._switch_mode(values["mode"])
            rest = {k: v for k, v in values.items() if k not in ("principle", "mode")}
            self.check_values(rest)
            for name, v in rest.items():
                self.controls[name].value = v
        except Exception:
            if not hold:  # the principle may have changed: show what the controls now say
                self._hold = hold
                self._run(self.values())
            raise
        finally:
            self._hold = hold
        if not hold:
            self._run({**self.values(), **rest})

    # -- the callback -----------------------------------------------------------------------------
    def _run(self, values: dict) -> None:
        """Move the maxima of sliders bounded by another parameter, then update once.

        When the student shortens the lever, an electrode slider's maximum follows it (the
        electrode cannot be longer than the lever), and so does its value if it was longer.
        """
        cls = PRINCIPLES[check_choice("principle", values.get("principle"), PRINCIPLES)]
        table = cls.parameter_table()
        values = dict(values)
        hold, self._hold = self._hold, True
        try:
            for name, (other, factor) in cls.BOUNDED_BY.items():
                c = self.controls.get(name)
                if c is None or other not in values:
                    continue
                p = table[name]
                high = min(p.slider_high, factor * to_si(table[other], values[other]))
                shown = p.to_display(high)
                if c.max != shown:
                    if values[name] > shown:
                        values[name] = shown
                        c.value = shown
                    c.max = shown
        finally:
            self._hold = hold
        super()._run(values)

    def update(self, principle, mode, fluid, input, **params) -> None:  # noqa: A002 - a control name
        """Run the model once with the values given and update plots, scene and readout.

        Parameters
        ----------
        principle : str
            A key of :data:`~afmsmiler.transducers.PRINCIPLES`.
        mode : str
            One of the principle's modes.
        fluid : str
            ``"typed"`` (vacuum, the Q slider's Q), ``"air"`` or ``"water"``.
        input : float
            The chain's input in SI (m of deflection, V, A, W, ...).
        **params : float
            Every model parameter of the principle by name, in SI.

        Raises
        ------
        TypeError, ValueError
            For a missing or unknown control, an unknown principle or mode (naming the choices),
            or a value outside its valid range (naming the parameter and the range; nothing is
            clamped), before any work (the panel contract).
        """
        cls = PRINCIPLES[principle]
        model = cls(fluid=medium(fluid), **params)
        value = input
        op = self.run_model(model.operate, value, mode, frequencies=frequency_grid(model),
                           bandwidth=DEFAULTS["bandwidth"])
        curves = chain_curves(op)
        self.draw(TransducerFigure, curves)  # the figure's frame leaves first: its pixels wait for nothing else
        if self._want_scene:
            if self.scene is None:
                from ..scenes.transducers import TransducerScene
                self.scene = TransducerScene(op, vis=self.scene_root())
            else:
                scene = self.scene
                self.after_frame(lambda: scene.update(op))
        self.last = TransducerState(
            model=model, mode=mode, value=value, chain=op.point, curves=curves,
            sensitivity=op.sensitivity, resolution=op.resolution, operation=op)
        self.readout.value = self._readout_html()

    def _readout_html(self) -> str:
        s = self.last
        m = s.model
        sq = m.sensitivity_quantity(s.mode)
        q = m.input_quantity(s.mode)
        res = s.resolution
        total = q.to_display(res.total) if math.isfinite(res.total) else math.inf
        rows = [("Table I", f"{m.function}; {m.signal}; {m.size}"),
                ("lever k, f1",
                 f"{m.spring_constant:.3g} N/m, {shown(m.resonance_frequency, 'kHz')}"),
                ("medium, Q", f"vacuum, Q = {m.quality_factor:.3g} (typed)" if m.fluid is None else
                 f"{m.fluid} (Sader): Q = {m.quality_factor:.3g}, f1 in vacuum "
                 f"{shown(m.lever.resonance_frequency(1), 'kHz')}"),
                ("sensitivity here", f"{sq.to_display(s.sensitivity) + 0.0:.4g} {sq.display_unit}"),
                (f"resolution in {shown(DEFAULTS['bandwidth'], 'kHz', 'g')}",
                 (f"{total:.3g} {q.display_unit} (mostly {res.dominant})"
                  if math.isfinite(total) else "no small-signal response here"))]
        table = "".join(f"<tr><td>{k}</td><td style='text-align:right'><b>{v}</b></td></tr>"
                        for k, v in rows)
        notes = "".join(f"<div style='color:#b00'>{n}</div>"
                        for n in s.operation.validity)
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
