"""The lock-in panel: drive the educational AFM's heater, demodulate at 2 omega, see the spectrum.

:class:`LockInPanel` has sliders (each made by :func:`afmsmiler.ui.controls.control` from its
:class:`~afmsmiler.parameters.Parameter`) for the heater's drive amplitude, the drive frequency
relative to f1 / 2, the amplifier noise, an interfering tone at three times the reference and
the lock-in's time constant, and drop-downs for the filter order and the reference shape (sine or
square). :meth:`LockInPanel.update` runs the model once
(:func:`afmsmiler.signals.demo.lock_in_demo`) and hands the result to the figure
(:class:`~afmsmiler.plots.lockin.LockInFigure`), which computes nothing. The student sees the
recovered amplitude and phase against the closed-form truth, the spectrum with its 2-omega line,
and the 1/3, 1/5 ... that a square reference reads from the odd harmonics.
"""
from __future__ import annotations

import ipywidgets as widgets

from ..hydrodynamics import FLUID_NAMES
from ..parameters import read_only
from ..plots.lockin import LockInFigure
from ..signals.chain import AC_VOLTAGE, AMPLIFIER_NOISE, HALF_RESONANCE_RATIO, INTERFERENCE
from ..signals.demo import LockInDemo, lock_in_demo, max_ac_voltage
from ..signals.lockin import FILTER_ORDER, REFERENCES, TIME_CONSTANT
from ..validation import check_choice, check_integer
from .controls import TYPED, medium, medium_control
from .panel import Panel, initial_values, slider

__all__ = ["LockInPanel", "DEFAULTS", "SLIDERS"]

#: The panel's sliders, by control name, from the models' Parameters.
SLIDERS = read_only({"ac_voltage": AC_VOLTAGE, "half_resonance_ratio": HALF_RESONANCE_RATIO,
                     "amplifier_noise": AMPLIFIER_NOISE, "interference": INTERFERENCE,
                     "time_constant": TIME_CONSTANT})
#: Choices of the drop-downs and their defaults.
DEFAULTS = read_only(dict(orders=(1, 2, 3, 4, 6, 8), order=int(FILTER_ORDER.default),
                          shape="sine", seed=0, fluid=TYPED))
_SEED = DEFAULTS["seed"]


class LockInPanel(Panel):
    """Sliders, the lock-in's reading against the truth, the spectrum and the harmonic pickup.

    Controls: ``ac_voltage`` (V), ``half_resonance_ratio``, ``amplifier_noise`` (nV^2/Hz),
    ``interference`` (uV), ``time_constant`` (ms), ``order``, ``shape`` and ``fluid`` (the
    lever's medium: ``"typed"``, in vacuum with module (b)'s typed Q, or ``"air"``/``"water"``,
    its f1 and Q there from Sader's hydrodynamics). The drive's slider ends where module (b)'s
    bridge would leave its range in the medium where the lever rings most (the highest Q), so
    that no medium makes a drive the student set invalid.

    Parameters
    ----------
    seed : int
        Seed of the chain's noise, 0 to 2**32 - 1 (the same for every update, so a slider move
        changes only what it moves).
    **initial
        Initial control values in the units shown (keys of :attr:`DEFAULTS`).

    Attributes
    ----------
    last : LockInDemo
        The last model run.
    """

    SLIDERS = SLIDERS
    DEFAULTS = read_only({**{name: p.to_display(p.default) for name, p in SLIDERS.items()},
                          "order": DEFAULTS["order"], "shape": DEFAULTS["shape"],
                          "fluid": DEFAULTS["fluid"]})

    def __init__(self, *, seed: int = _SEED, **initial):
        self.seed = check_integer("seed", seed, 0, 2**32 - 1)
        values = initial_values(initial, self.DEFAULTS)
        self.controls = self.declared_controls(initial)
        # the drive stops where module (b)'s bridge would leave its range (at resonance)
        top = min(max_ac_voltage(fluid=f) for f in (None, *FLUID_NAMES))
        self.controls["ac_voltage"] = slider("ac_voltage", AC_VOLTAGE, values["ac_voltage"],
                                             high=top)
        check_choice("order", values["order"], DEFAULTS["orders"])
        check_choice("shape", values["shape"], list(REFERENCES))
        self.controls["order"] = widgets.Dropdown(options=list(DEFAULTS["orders"]),
                                                  value=values["order"],
                                                  description="filter order")
        self.controls["shape"] = widgets.ToggleButtons(options=list(REFERENCES),
                                                       value=values["shape"],
                                                       description="reference")
        self.controls["fluid"] = medium_control("vacuum: Q typed (module b)", values["fluid"])
        self.figure = None
        self.fig = None
        super().__init__()

    def update(self, *, ac_voltage, half_resonance_ratio, amplifier_noise, interference,
               time_constant, order, shape, fluid) -> None:
        """Run the demonstration once with these control values (sliders in SI) and draw it."""
        demo = self.run_model(lock_in_demo, ac_voltage=ac_voltage,
                              half_resonance_ratio=half_resonance_ratio,
                              amplifier_noise=amplifier_noise, interference=interference,
                              time_constant=time_constant, order=int(order), shape=shape,
                              seed=self.seed, fluid=medium(fluid))
        self.last = demo
        if self.figure is None:
            self.figure = LockInFigure(demo, fig=self.new_figure(figsize=(11.0, 3.8)))
            self.fig = self.figure.fig
        else:
            self.figure.update(demo)
        self.redraw()

    @property
    def demo(self) -> LockInDemo:
        """The last run (the same as :attr:`last`)."""
        return self.last
