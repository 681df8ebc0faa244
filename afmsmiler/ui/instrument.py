"""The widget panel of module (e): the instrument overview, the laser alignment and the setup.

The four knobs of the optical head (:data:`afmsmiler.instrument.KNOBS`), the deflection
setpoint and the coarse approach (:data:`afmsmiler.instrument.walkthrough.SETUP`), the housing's
opacity and the exploded view (:data:`afmsmiler.scenes.instrument.PARAMETERS`) are sliders made
by :func:`~afmsmiler.ui.controls.control`; the instrument and the part to look at are drop-downs;
"probe mounted" is a check box. One user action is one :meth:`InstrumentPanel.update`, which runs
the head's model once (:meth:`~afmsmiler.instrument.OpticalHead.signals`) and hands the result
to the display (SUM, VERT, HORZ), to the figure (:class:`InstrumentFigure`: the spot on the lever
and on the four-quadrant photodiode) and, when a viewer is asked for, to the 3D instrument
(:class:`~afmsmiler.scenes.instrument.InstrumentScene`: knobs turned, beam traced through the
spots the model computed, housing, exploded view, the approach's gap, the picked part
highlighted). The guided setup (:mod:`afmsmiler.instrument.walkthrough`) runs under the panel:
Back / Next move through its steps (the step's first part is picked, the camera goes there),
Check checks the step on the state the model last computed (no model run).

The lever is free (deflection 0) until the approach brings the tip within the scanner's reach;
then the feedback holds it at the deflection setpoint and the display shows that.
"""
from __future__ import annotations

import html
from dataclasses import dataclass

import ipywidgets as widgets
import numpy as np

from ..instrument import DEFAULT_LEVER, KNOBS, AlignmentRun, OpticalHead, Signals, align
from ..instrument.walkthrough import (SETUP, STEP_TOLERANCES, STEPS, SetupState, StepCheck,
                                      Walkthrough)
from ..parameters import read_only, shown
from ..scenes.instrument import INSTRUMENTS
from ..scenes.instrument import PARAMETERS as SCENE
from ..validation import check_flag, check_choice
from ..plots.instrument import InstrumentFigure
from .controls import control
from .panel import Panel

__all__ = ["InstrumentPanel", "InstrumentState", "DEFAULTS"]

#: The panel's defaults in one place: the first instrument, the figure's size (inches), the
#: knob sliders' step (turn: a fine screw; 1/200 turn moves the photodiode 2.5 um, so the
#: differences can be brought within the walkthrough's tolerance).
DEFAULTS = read_only(dict(instrument="obd", figsize=(9.0, 3.6), knob_step=0.005))

_KNOB_NAMES = tuple(KNOBS)
_WHOLE = ""   # the part picker's "whole instrument"


@dataclass(frozen=True)
class InstrumentState:
    """What the panel last computed (SI units), for tests and exercises.

    Attributes
    ----------
    head : OpticalHead
        The head with its knobs as the sliders set them.
    signals : Signals
        The display's signals (one model run).
    setup : SetupState
        What the walkthrough's checks read.
    deflection : float
        The lever's deflection the signals were computed at, m (0 while the lever is free).
    instrument : str
        The instrument shown.
    part : str
        The picked part ("" for the whole instrument).
    description : str
        The picked part's description.
    """

    head: OpticalHead
    signals: Signals
    setup: SetupState
    deflection: float
    instrument: str
    part: str
    description: str


class InstrumentPanel(Panel):
    """The instrument overview: knobs, display, photodiode figure, parts, the guided setup.

    Controls: ``instrument`` (``"obd"`` or ``"educational"``, :data:`INSTRUMENTS`), ``part``
    (a part of that instrument, ``""`` for the whole), ``housing_opacity`` and
    ``explode_fraction`` (0 to 1), ``mounted`` (the probe in its holder), the four knobs
    ``laser_x``, ``laser_y``, ``detector_vertical``, ``detector_lateral`` (turns),
    ``deflection`` (the deflection setpoint, nm) and ``approach_gap`` (the coarse approach's
    tip-sample gap, um). The knobs, the display and the walkthrough belong to the OBD head; the
    educational AFM is shown in 3D with its parts.

    Parameters
    ----------
    instrument : str
        The instrument shown first.
    scene : bool
        Draw the 3D instrument in its own widget, shown below the panel by
        :meth:`show` (over the kernel's connection; nothing to close).
    vis : meshcat.Visualizer, optional
        Draw the 3D instrument into this visualizer instead (a recorder in tests); implies a
        scene.
    lever : Cantilever
        The lever (module (a)); default :data:`~afmsmiler.instrument.DEFAULT_LEVER`.
    mounted : bool
        Whether the probe starts in its holder.

    Attributes
    ----------
    head : OpticalHead
        The head the knobs turn.
    last : InstrumentState
        The last model result.
    walkthrough : Walkthrough
        The guided setup's position and its checks.
    figure : InstrumentFigure
        The spot on the lever and on the photodiode.
    scene : InstrumentScene or None
        The 3D view.
    display_html, part_html, step_html, result_html : ipywidgets.HTML
        The instrument's display, the picked part's description, the step's narration and the
        last check's result.
    """

    def __init__(self, instrument: str = DEFAULTS["instrument"], *, scene: bool = False,
                 vis=None, lever=DEFAULT_LEVER, mounted: bool = True):
        check_choice("instrument", instrument, INSTRUMENTS)
        self.head = OpticalHead(lever)
        self.walkthrough = Walkthrough()
        self.scene = None
        self._scene_applied = {}
        self.display_html, self.part_html = widgets.HTML(), widgets.HTML()
        self.step_html, self.result_html = widgets.HTML(), widgets.HTML()
        c = {"instrument": widgets.Dropdown(
            options=[(i.title, k) for k, i in INSTRUMENTS.items()], value=instrument,
            description="instrument")}
        c["part"] = widgets.Dropdown(options=self._part_options(instrument), value=_WHOLE,
                                     description="part")
        c["housing_opacity"] = control(SCENE["housing_opacity"])
        c["explode_fraction"] = control(SCENE["explode_fraction"])
        mounted = check_flag("mounted", mounted)
        c["mounted"] = widgets.Checkbox(value=mounted, description="probe mounted")
        for name in _KNOB_NAMES:
            c[name] = control(KNOBS[name])
            c[name].step = DEFAULTS["knob_step"]   # a fine screw; the grid still through 0
        c["deflection"] = control(SETUP["deflection"])
        c["approach_gap"] = control(SETUP["approach_gap"])
        self.controls = c
        self.buttons = {name: widgets.Button(description=name) for name in ("Back", "Next",
                                                                            "Check")}
        self.buttons["Back"].on_click(lambda _b: self.back_step())
        self.buttons["Next"].on_click(lambda _b: self.next_step())
        self.buttons["Check"].on_click(lambda _b: self.check_step())
        self.fig = self.new_figure(figsize=DEFAULTS["figsize"])
        self.figure = InstrumentFigure(self.head, self.fig)
        super().__init__(scene=scene, vis=vis)
        self._show_step()

    @staticmethod
    def _part_options(instrument: str) -> list:
        return [("(whole instrument)", _WHOLE)] + [(p.label, p.name)
                                                   for p in INSTRUMENTS[instrument].parts]

    # -- setting controls -------------------------------------------------------------------------
    def set(self, **values) -> None:
        """Set control values as a user would (one update at the end).

        ``instrument`` is applied first (it changes the part picker's choices), so a part of the
        new instrument can be picked in the same call.

        Raises
        ------
        ValueError
            For an unknown instrument or part (naming the choices) or a value outside a
            slider's range (naming the control and the range).
        TypeError
            For a name that is not a control.
        """
        if "instrument" in values:
            instrument = check_choice("instrument", values["instrument"], INSTRUMENTS)
            if "part" in values:
                check_choice("part", values["part"],
                             [v for _, v in self._part_options(instrument)])
            hold, self._hold = self._hold, True
            try:
                self._switch_parts(instrument, values.get("part", _WHOLE))
            finally:
                self._hold = hold
        super().set(**values)

    def _switch_parts(self, instrument: str, part: str = _WHOLE) -> None:
        c = self.controls["part"]
        options = self._part_options(instrument)
        if list(c.options) != options:
            c.options = options
            c.value = part
        self.controls["instrument"].value = instrument

    def _on_change(self, change) -> None:
        # the instrument drop-down changes the part picker's choices before the update
        if not self._hold and change.get("owner") is self.controls["instrument"]:
            hold, self._hold = self._hold, True
            try:
                self._switch_parts(change["new"])
            finally:
                self._hold = hold
        super()._on_change(change)

    # -- the callback -----------------------------------------------------------------------------
    def update(self, instrument, part, housing_opacity, explode_fraction, mounted, laser_x,
               laser_y, detector_vertical, detector_lateral, deflection,
               approach_gap) -> None:
        """Run the head's model once with the values given; update display, figure and scene.

        Parameters
        ----------
        instrument : str
            A key of :data:`~afmsmiler.scenes.instrument.INSTRUMENTS`.
        part : str
            One of the instrument's parts, or ``""`` for the whole instrument.
        housing_opacity, explode_fraction : float
            0 to 1.
        mounted : bool
            The probe in its holder.
        laser_x, laser_y, detector_vertical, detector_lateral : float
            Knob rotations in turn, within their travel.
        deflection : float
            The deflection setpoint in m.
        approach_gap : float
            The tip-sample gap in m.

        Raises
        ------
        TypeError, ValueError
            For a missing or unknown control, a value outside its valid range or an unknown
            instrument or part, before any work (the panel contract).
        """
        parts = {p.name: p for p in INSTRUMENTS[instrument].parts}
        opacity, fraction = housing_opacity, explode_fraction
        knobs = dict(laser_x=laser_x, laser_y=laser_y, detector_vertical=detector_vertical,
                     detector_lateral=detector_lateral)
        setpoint, gap = deflection, approach_gap
        in_contact = gap <= STEP_TOLERANCES["approach_range"].default
        z = setpoint if in_contact and mounted else 0.0
        signals = self.run_model(self.head.set, deflection=z, **knobs)  # the one model run
        setup = SetupState(self.head, signals=signals, deflection=setpoint, approach_gap=gap,
                           mounted=mounted)
        p = parts.get(part)
        description = (f"{p.label}: {p.description} ({self._dimensions(instrument, p)})"
                       if p is not None else INSTRUMENTS[instrument].title)
        self.last = InstrumentState(head=self.head, signals=signals, setup=setup, deflection=z,
                                  instrument=instrument, part=part, description=description)
        self.figure.update(self.head, signals, mounted)
        self.redraw()
        if self._want_scene:
            self._update_scene(instrument, part, opacity, fraction, knobs, gap, signals,
                               mounted)
        self.display_html.value = self._display_html()
        self.part_html.value = f"<div style='max-width:560px'>{html.escape(description)}</div>"

    def _dimensions(self, instrument: str, part) -> str:
        """The part's dimensions; the OBD probe's lever is the one the head's optics use (its
        length decides where the free end is and every signal), whatever the drawing's."""
        if instrument != "obd" or part.name != "probe_chip":
            return part.dimensions
        lever = self.head.lever
        size = " x ".join(f"{v * 1e6:.3g}" for v in (lever.length, lever.width,
                                                      lever.thickness))
        chip = f"{self.head.chip_length * 1e3:.3g} x {self.head.chip_width * 1e3:.3g} mm chip"
        rest = [piece.strip() for piece in part.dimensions.split(",")   # the tip's, say
                if not piece.strip().startswith("lever") and "chip" not in piece]
        return ", ".join([chip, f"lever {size} um (the lever the optics model)", *rest])

    def _update_scene(self, instrument, part, opacity, fraction, knobs, gap, signals,
                      mounted) -> None:
        """Send the scene what changed (the scene draws, computes nothing)."""
        from ..scenes.instrument import InstrumentScene
        if self.scene is None or self.scene.instrument.key != instrument:
            if self.scene is not None:
                self.scene.vis.delete()
            self.scene = InstrumentScene(instrument, vis=self.scene_root(), housing_opacity=opacity)
            self._scene_applied = {}
        scene, done = self.scene, self._scene_applied

        def changed(key, value):
            if done.get(key, None) is None or not np.array_equal(done[key], value):
                done[key] = value
                return True
            return False

        # compared with the scene's own state: a notebook may have animated it meanwhile
        if scene.housing_opacity != opacity:
            scene.set_housing_opacity(opacity)
        if scene.fraction != fraction:
            scene.explode(fraction)
        if scene.gap != gap:
            scene.set_gap(gap)
        if scene.instrument.beam:
            if any(scene.knob_angles[n] != v for n, v in knobs.items()):
                scene.set_knobs(**knobs)
            beam = self._beam_points(scene, signals, mounted)
            if changed("beam", beam[0]):
                scene.show_beam(*beam)
        if changed("part", part):
            if part == _WHOLE:
                scene.unhighlight()
                scene.focus()
            else:
                scene.pick(part, focus=True)

    @staticmethod
    def _beam_points(scene, signals: Signals, mounted: bool):
        """The beam through the drawn optics and the model's two spots (m, scene frame)."""
        a = scene.anchors
        x, y = (float(np.clip(c, -0.0099, 0.0099)) for c in signals.spot_on_lever)
        v, lat = (float(np.clip(c, -0.0099, 0.0099)) for c in signals.spot_on_detector)
        on_lever = scene.lever_point(x, y)
        if not mounted:
            return np.array([a["laser"], a["lens"], on_lever]), np.array([on_lever])
        on_detector = scene.photodiode_point(v, lat)
        return (np.array([a["laser"], a["lens"], on_lever, a["mirror"], on_detector]),
                np.array([on_lever, on_detector]))

    def _display_html(self) -> str:
        s, state = self.last.signals, self.last
        mounted = state.setup.mounted
        line = s.readout() if mounted else "SUM 0.00 V  VERT 0.000 V  HORZ 0.000 V"
        rows = [("display", f"<code>{line}</code>")]
        if mounted:
            rows += [("VERT / SUM, HORZ / SUM",
                      f"{s.vertical_normalised + 0.0:.3f}, {s.lateral_normalised + 0.0:.3f}"),
                     ("lever deflection", shown(state.deflection, "nm", ".3g")
                      + (" (in contact: the setpoint)" if state.deflection else
                         " (the lever is free)"))]
        else:
            rows += [("probe", "none mounted: no light comes back")]
        note = ("" if state.instrument == "obd" else
                "<div><i>The knobs and the display belong to the optical head of the OBD AFM; "
                "the educational AFM senses with a piezoresistive bridge on its probe.</i></div>")
        table = "".join(f"<tr><td>{k}</td><td><b>{v}</b></td></tr>" for k, v in rows)
        return f"<table>{table}</table>{note}"

    # -- the guided setup ------------------------------------------------------------------------
    def _show_step(self) -> None:
        step = self.walkthrough.step
        self.step_html.value = (f"<h4 style='margin:4px 0'>{html.escape(step.title)}</h4>"
                                f"<div style='max-width:560px'>{html.escape(step.text)}</div>"
                                f"<div><small>look at: {', '.join(step.parts)}; use: "
                                f"{', '.join(step.controls)}</small></div>")
        self.result_html.value = ""

    def _go_to_step(self) -> None:
        self._show_step()
        step = self.walkthrough.step
        self.set(instrument="obd", part=step.parts[0])   # one update: highlight, camera

    def next_step(self) -> None:
        """Go to the next step of the guided setup: its text, its part picked (one update)."""
        self.walkthrough.next()
        self._go_to_step()

    def back_step(self) -> None:
        """Go back one step of the guided setup (one update)."""
        self.walkthrough.back()
        self._go_to_step()

    def align(self) -> AlignmentRun:
        """Align a freshly mounted head as the manual does and set the knobs to the result.

        Runs :func:`afmsmiler.instrument.align` from the just-mounted state (not from the knobs
        shown), then sets the four knob sliders to where it ended (one update), and the guided
        setup goes on from the first step not yet done
        (:meth:`~afmsmiler.instrument.walkthrough.Walkthrough.resume`), saying which steps the
        alignment completed.

        Returns
        -------
        AlignmentRun
            The steps it took and the alignment reached.
        """
        run = align(OpticalHead(self.head.lever))
        self.set(**{name: KNOBS[name].to_display(angle)
                    for name, angle in run.alignment.signals.knobs.items()})
        walkthrough = self.walkthrough
        walkthrough.resume(self.last.setup)
        self._go_to_step()
        done = [s.title for s in STEPS if walkthrough.results.get(s.key)]
        result = walkthrough.results[walkthrough.step.key]
        self.result_html.value = (
            f"<div>Done: {html.escape(', '.join(done) or 'no step')}.</div>"
            f"<div style='color:{'#1a7f37' if result else '#b00020'}'>"
            f"{html.escape(str(result))}</div>")
        return run

    def check_step(self) -> StepCheck:
        """Check the current step on what the model last computed (no model run).

        Returns
        -------
        StepCheck
            Also shown under the step's text.
        """
        result = self.walkthrough.check(self.last.setup)
        colour = "#1a7f37" if result else "#b00020"
        self.result_html.value = f"<div style='color:{colour}'>{html.escape(str(result))}</div>"
        return result

    # -- layout ---------------------------------------------------------------------------------
    def widget(self) -> widgets.Widget:
        """Controls and the display on the left, the walkthrough on the right, the figure below.

        Returns
        -------
        ipywidgets.VBox
        """
        figure = super().widget().children[1:]
        c = self.controls
        left = widgets.VBox([c["instrument"], c["part"], self.part_html, c["housing_opacity"],
                             c["explode_fraction"], c["mounted"],
                             *(c[n] for n in _KNOB_NAMES), c["deflection"], c["approach_gap"],
                             self.display_html])
        right = widgets.VBox([self.step_html, widgets.HBox(list(self.buttons.values())),
                              self.result_html])
        right.layout.margin = "0 0 0 16px"
        return widgets.VBox([widgets.HBox([left, right]), *figure])
