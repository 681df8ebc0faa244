"""Figures of module (b): a transducer's signal chain and its frequency response.

:func:`chain_curves` samples a transducer model (:mod:`afmsmiler.transducers`) over its input
range and converts every stage to the units the figure shows (each stage's ``display_unit``);
:class:`TransducerFigure` draws three panels once and :meth:`TransducerFigure.update` moves the
line data in place:

1. the lever: the first intermediate stage (the force, power, moment or slope) and the stage
   that feeds the output (the spot travel, stress, detuning, ... or the slope) against the input;
2. the output against the input, the operating point and the tangent of slope = the
   small-signal sensitivity there;
3. the frequency response |H(f)| (and its phase) from the model.
"""
from __future__ import annotations

import textwrap
from dataclasses import dataclass

import numpy as np
from matplotlib.figure import Figure

from ..parameters import Parameter, read_only
from ..transducers.base import Operation, Transducer
from ..validation import check_instance, check_integer
from .limits import data_range, hold

__all__ = ["DEFAULTS", "ChainCurves", "chain_curves", "TransducerFigure", "frequency_grid"]

#: Defaults of the figures, in one place.
DEFAULTS = read_only(dict(n_frequencies=400, n_resonance=101, f_low=1e-2, f_high_ratio=10.0,
                          figsize=(11.0, 3.8), label_width=40))


def frequency_grid(model: Transducer, n_frequencies: int = DEFAULTS["n_frequencies"]) -> np.ndarray:
    """Log-spaced frequencies in Hz from 0.01 Hz to 10 f1 of ``model``'s lever, dense at f1.

    A log grid of a few hundred points steps by ~4 % near f1, wider than the resonance of a lever
    with Q = 150 (f1 / Q): the plotted peak then fell anywhere below Q and the phase seemed to
    jump. ``DEFAULTS["n_resonance"]`` more points span f1 (1 +- 5 / Q), f1 itself included.

    Parameters
    ----------
    model : Transducer
        The model (its first resonance and Q set the top and the dense part of the grid).
    n_frequencies : int
        Number of log-spaced frequencies, 2 to 100000.

    Returns
    -------
    ndarray
        Increasing frequencies in Hz.
    """
    check_instance("model", model, Transducer)
    n_frequencies = check_integer("n_frequencies", n_frequencies, 2, 100_000)
    f1 = model.resonance_frequency
    top = DEFAULTS["f_high_ratio"] * f1
    half_width = min(5.0 / model.quality_factor, 0.9)
    dense = f1 * (1.0 + np.linspace(-half_width, half_width, DEFAULTS["n_resonance"]))
    grid = np.concatenate([np.geomspace(DEFAULTS["f_low"], top, n_frequencies), dense])
    return np.unique(grid[(grid >= DEFAULTS["f_low"]) & (grid <= top)])


@dataclass(frozen=True)
class ChainCurves:
    """What a :class:`TransducerFigure` shows, in the units it shows (each quantity's display unit).

    Attributes
    ----------
    title : str
        The principle's name and mode.
    quantities : tuple of Parameter
        The stages' quantities, input first, output last.
    x : ndarray
        The input sweep (display unit).
    stages : tuple of ndarray
        Each stage along the sweep (display units), aligned with ``quantities``.
    value : float
        The current input (display unit).
    point : tuple of float
        Each stage at the current input (display units).
    sensitivity : float
        Small-signal slope at the current input, output per input, in display units.
    sensitivity_si : float
        The same in SI units (``sensitivity_unit``).
    sensitivity_unit : str
        SI unit of ``sensitivity_si``.
    sensitivity_display : float
        The sensitivity in its display unit (the readout's: 1/um for the optical lever).
    sensitivity_display_unit : str
        That unit, from the model's sensitivity quantity.
    frequency : ndarray
        Frequencies in Hz.
    magnitude : ndarray
        |H(f)| in display units of output per input (the input of the frequency response).
    phase_deg : ndarray
        Phase of H(f) in degrees, unwrapped (continuous through the resonance: -170 deg is
        followed by -185 deg, not +175 deg).
    response_label : str
        What ``magnitude`` is, with its unit.
    """

    title: str
    quantities: tuple
    x: np.ndarray
    stages: tuple
    value: float
    point: tuple
    sensitivity: float
    sensitivity_si: float
    sensitivity_unit: str
    sensitivity_display: float
    sensitivity_display_unit: str
    frequency: np.ndarray
    magnitude: np.ndarray
    phase_deg: np.ndarray
    response_label: str


def chain_curves(operation: Operation) -> ChainCurves:
    """The curves of a model run (:meth:`~afmsmiler.transducers.base.Transducer.operate`), in
    the units the figure shows; no model is evaluated here.

    Parameters
    ----------
    operation : Operation
        The model's sweep, point, sensitivity and frequency response (``frequencies`` given).

    Returns
    -------
    ChainCurves

    Raises
    ------
    TypeError
        If ``operation`` is not an Operation.
    ValueError
        If it carries no frequency response.
    """
    op = check_instance("operation", operation, Operation)
    if op.response is None:
        raise ValueError("operation must carry a frequency response (operate(frequencies=...))")
    model, sweep, here = op.model, op.sweep, op.point
    q = sweep.input.quantity
    quantities = tuple(st.quantity for st in sweep.stages)
    out = sweep.output.quantity
    sq = model.sensitivity_quantity(op.mode)
    fr = op.response
    mag_scale = fr.output.scale / fr.input.scale
    in_unit = fr.input.display_unit or fr.input.unit
    out_unit = fr.output.display_unit or "1"
    label = f"|{fr.output.label or fr.output.name}| per {fr.input.label} [{out_unit}/{in_unit}]"
    mode_name = sweep.mode if len(model.MODES) > 1 else model.function
    return ChainCurves(
        title=f"{model.name} ({mode_name})",
        quantities=quantities,
        x=q.to_display(sweep.input.values),
        stages=tuple(st.quantity.to_display(st.values) for st in sweep.stages),
        value=q.to_display(op.value),
        point=tuple(st.quantity.to_display(float(st.values[0])) for st in here.stages),
        sensitivity=op.sensitivity * out.scale / q.scale,
        sensitivity_si=op.sensitivity,
        sensitivity_unit=sq.unit,
        sensitivity_display=sq.to_display(op.sensitivity),
        sensitivity_display_unit=sq.display_unit,
        frequency=fr.frequency,
        magnitude=np.abs(fr.response) * mag_scale,
        phase_deg=np.degrees(np.unwrap(np.angle(fr.response))),
        response_label=label,
    )


def _title(q: Parameter) -> str:
    """The axis label of ``q``: ``"label [unit]"``, or ``"label (dimensionless)"`` for a ratio."""
    return q.title if q.display_unit else f"{q.title} (dimensionless)"


def _phase_limits(phase_deg) -> tuple[float, float]:
    """Phase axis limits in degrees: multiples of 90 deg around the (unwrapped) data."""
    lo, hi = float(np.min(phase_deg)), float(np.max(phase_deg))
    return 90.0 * np.floor(lo / 90.0 - 0.1), 90.0 * np.ceil(hi / 90.0 + 0.1)


def _wrap(text: str, width: int = DEFAULTS["label_width"]) -> str:
    """``text`` broken into lines of about ``width`` characters (long axis labels fit the axes)."""
    return textwrap.fill(text, width, break_long_words=False)


class TransducerFigure:
    """Three panels: the lever's stages, the output with its tangent, the frequency response.

    Parameters
    ----------
    curves : ChainCurves
        The first data to show.
    fig : matplotlib.figure.Figure, optional
        Where to draw; a new pyplot-free Figure by default.

    Attributes
    ----------
    axes : dict
        ``"lever"`` (with its twin ``"lever_right"``), ``"output"``, ``"response"`` (with
        ``"phase"``).
    lines : dict
        ``"left"``, ``"right"`` (the lever panel's stages), ``"output"``, ``"tangent"``,
        ``"point"``, ``"point_left"``, ``"point_right"``, ``"magnitude"``, ``"phase"`` and
        ``"f1"`` (the resonance marker), updated in place by :meth:`update`.
    """

    def __init__(self, curves: ChainCurves, fig: Figure | None = None):
        check_instance("curves", curves, ChainCurves)
        self.fig = (check_instance("fig", fig, Figure) if fig is not None
                    else Figure(figsize=DEFAULTS["figsize"]))
        lever, output, response = self.fig.subplots(1, 3)
        self.axes = dict(lever=lever, lever_right=lever.twinx(), output=output, response=response,
                         phase=response.twinx())
        ax = self.axes
        self.lines = {}
        self.lines["left"], = ax["lever"].plot([], [], color="C0")
        self.lines["right"], = ax["lever_right"].plot([], [], color="C1", ls="--")
        self.lines["point_left"], = ax["lever"].plot([], [], "o", color="C0", ms=5)
        self.lines["point_right"], = ax["lever_right"].plot([], [], "o", color="C1", ms=5)
        self.lines["output"], = ax["output"].plot([], [], color="C3")
        self.lines["tangent"], = ax["output"].plot([], [], color="0.3", ls=":", lw=1.5)
        self.lines["point"], = ax["output"].plot([], [], "o", color="C3", ms=6)
        self.lines["magnitude"], = ax["response"].loglog([], [], color="C2")
        self.lines["phase"], = ax["phase"].semilogx([], [], color="C4", lw=0.8, alpha=0.7)
        self.lines["f1"] = ax["response"].axvline(1.0, color="0.7", ls=":", lw=1)
        ax["phase"].set_ylabel("phase [deg]", color="C4")
        ax["output"].set_title("detector / output signal")
        ax["lever"].set_title("through the lever")
        ax["response"].set(xlabel="frequency [Hz]", title="frequency response")
        for key in ("lever", "output"):
            ax[key].axhline(0.0, color="0.85", lw=0.8)
            ax[key].axvline(0.0, color="0.85", lw=0.8)
        self.fig.set_layout_engine("constrained")
        self.update(curves)

    def update(self, curves: ChainCurves) -> None:
        """Show new curves: set the line data, labels and limits (no new artists).

        The stages' and the response's axes hold their limits while the curves stay inside them
        and fill a fair part of them (:func:`~afmsmiler.plots.limits.sticky_limits`), so that a
        slider move shows the curves move; the first draw and a change of principle or mode
        (other quantities on the axes) fit the data. The input sweep, the frequency grid and
        the phase (multiples of 90 deg) keep exact limits.

        Parameters
        ----------
        curves : ChainCurves
            From :func:`chain_curves`.
        """
        ax, ln = self.axes, self.lines
        key = (curves.title, curves.quantities)
        reset = getattr(self, "_limits_key", None) != key  # first draw, or other quantities
        q, x = curves.quantities, curves.x
        n = len(q)
        left = 1
        right = n - 2 if n - 2 > left else None
        xlabel = _title(q[0])
        ln["left"].set_data(x, curves.stages[left])
        ln["point_left"].set_data([curves.value], [curves.point[left]])
        ax["lever"].set(xlabel=xlabel)
        ax["lever"].set_ylabel(_title(q[left]), color="C0")
        ax["lever"].set_xlim(x[0], x[-1])
        hold(ax["lever"], "y", *data_range(curves.stages[left]), reset=reset)
        if right is not None:
            ln["right"].set_data(x, curves.stages[right])
            ln["point_right"].set_data([curves.value], [curves.point[right]])
            ax["lever_right"].set_ylabel(_title(q[right]), color="C1")
            hold(ax["lever_right"], "y", *data_range(curves.stages[right]), reset=reset)
            ax["lever_right"].set_visible(True)
        else:
            ln["right"].set_data([], [])
            ln["point_right"].set_data([], [])
            ax["lever_right"].set_visible(False)
        y = curves.stages[-1]
        ln["output"].set_data(x, y)
        ln["point"].set_data([curves.value], [curves.point[-1]])
        half = 0.15 * (x[-1] - x[0])
        tx = np.array([curves.value - half, curves.value + half])
        ln["tangent"].set_data(tx, curves.point[-1] + curves.sensitivity * (tx - curves.value))
        ax["output"].set(xlabel=xlabel, ylabel=_title(q[-1]))
        ax["output"].set_xlim(x[0], x[-1])
        hold(ax["output"], "y", *data_range(y), reset=reset)
        ax["output"].set_title(f"{curves.title}\nslope {curves.sensitivity_display:.4g} "
                               f"{curves.sensitivity_display_unit}", fontsize="medium")
        f, mag = curves.frequency, curves.magnitude
        ln["magnitude"].set_data(f, mag)
        ln["phase"].set_data(f, curves.phase_deg)
        ax["phase"].set_ylim(*_phase_limits(curves.phase_deg))
        ax["response"].set_xlim(f[0], f[-1])
        # |H| on a log axis: the policy in decades, at least one decade shown
        hold(ax["response"], "y", *data_range(mag, log=True), reset=reset, log=True,
             margin=0.1, floor=1.0)
        ax["response"].set_ylabel(_wrap(curves.response_label), fontsize="small")
        ln["f1"].set_xdata([f[-1] / DEFAULTS["f_high_ratio"]] * 2)
        self._limits_key = key
