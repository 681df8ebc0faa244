"""The widget panels of module (g): what each imaging mode measures, one model run per move.

- :class:`TappingPanel` (amplitude modulation): free amplitude, setpoint, Q, k, f0 (typed, or a
  vendor's probe in air or water: :func:`afmsmiler.probe.oscillator`), Hamaker constant, modulus
  and sample viscosity. One :func:`~afmsmiler.modes.amplitude_curve` per move
  (none when only the setpoint moved: the curve is the same), drawn by
  :class:`~afmsmiler.plots.modes.TappingFigure` with both branches, and the state the amplitude
  feedback holds at the setpoint, on the branch the approach picks (read off the same curve as
  :func:`~afmsmiler.modes.setpoint_state` reads its own).
- :class:`LateralPanel` (lateral force): the two materials' friction coefficients, the sample's
  tilt (a slope), the load and the noise. One :func:`~afmsmiler.modes.friction_scan` of
  :func:`~afmsmiler.modes.friction_sample` per move; the friction loop is the scan's middle line.
- :class:`FrequencyShiftPanel` (frequency modulation): amplitude, k, f0 and the force law's
  Hamaker constant, tip radius and modulus. One :func:`~afmsmiler.modes.frequency_shift_curve`
  (Giessibl's df, then the Sader-Jarvis inversion) per move.
- :class:`JumpingPanel` (jumping mode): trigger force, lift height, z speed, modulus and work of
  adhesion. One :func:`~afmsmiler.modes.jumping.jump_curve` (a pixel's force curve) and one scan
  of a tall grating by :class:`~afmsmiler.modes.jumping.JumpingMode` per move.
- :class:`ForceVolumePanel` (force volume): peak force, force noise, ramp size and the lever's
  k. One :func:`~afmsmiler.modes.force_volume.force_volume` map of a two-material blend per move.

Every slider is built by :func:`~afmsmiler.ui.controls.control` from a
:class:`~afmsmiler.parameters.Parameter` of :mod:`afmsmiler.modes`. With ``scene=True`` (or a
``vis``) a panel also animates its mode in the 3D view (:class:`~afmsmiler.scenes.modes.
ModesScene`) from the same results. ``model_runs`` counts the model's runs (tests check one per
move).
"""
from __future__ import annotations

import functools
import html
import math
from dataclasses import dataclass

import ipywidgets as widgets
import numpy as np

from ..cantilever import Cantilever
from ..contact import PARAMETERS as CONTACT
from ..contact import ContactSystem, Parabolic
from ..imaging.scanner import ScanResult, ScanSettings
from ..imaging.scanner import scan as _scan
from ..modes import force_volume as _fv
from ..modes import jumping
from ..modes import fm, lateral, tapping
from ..modes._forces import FORCE_PARAMETERS
from ..modes.fm import FrequencyShiftCurve
from ..modes.lateral import FrictionImages, FrictionLoop, LateralLever
from ..modes.tapping import AmplitudeCurve, TappingLever, operating_point
from ..parameters import read_only, shown
from ..planform import preset
from ..plots.live import PAINT_WAIT
from ..plots.modes import (ForceVolumeFigure, FrequencyShiftFigure, JumpingFigure,
                           LateralFigure, TappingFigure)
from ..probe import FLUID_NAMES, oscillator
from ..samples import grating
from ..validation import check_choice
from .controls import TYPED
from .panel import _PAINT_POLL, Panel, _live_loop, initial_values

__all__ = ["TappingPanel", "TappingState", "TAPPING_PROBES", "TAPPING_FLUIDS", "TAPPING_LEVER",
           "TYPED", "tapping_oscillator", "LateralPanel", "LateralState",
           "FrequencyShiftPanel", "FrequencyShiftState", "TAPPING_SLIDERS", "LATERAL_SLIDERS",
           "FM_SLIDERS", "TAPPING_DEFAULTS", "LATERAL_DEFAULTS", "FM_DEFAULTS",
           "operating_point", "LATERAL_SAMPLE", "FM_DISTANCES", "lateral_lever",
           "JumpingPanel", "JumpingState", "JUMPING_SLIDERS", "JUMPING_DEFAULTS", "JUMPING_SCAN",
           "ForceVolumePanel", "FORCE_VOLUME_SLIDERS", "FORCE_VOLUME_DEFAULTS", "FORCE_VOLUME_MAP"]


def _display(sliders, **si) -> dict:
    """The sliders' initial values in the units shown (their Parameter's default, or ``si``)."""
    return {name: float(f"{p.to_display(si.get(name, p.default)):.12g}")
            for name, p in sliders.items()}


#: Seconds a slider must rest (from the page's paint of the quick answer) before a panel that
#: showed a quick answer during a drag computes the full one (``_SliderPanel._quick_then_full``):
#: three repeats of a held key (some 30 a second), so that a full answer made at once (some
#: 40 ms in a live kernel) rarely holds up a drag's next move.
FULL_DELAY = 0.1


class _SliderPanel(Panel):
    """A panel of sliders only (declared as :attr:`Panel.SLIDERS`), a readout beside them."""

    FIGSIZE = (9.0, 7.0)
    #: The loop's handle of a full answer still to come after a quick one, else None.
    _full_pending = None
    #: The sequence number of the figure's frame that showed the last quick answer
    #: (``_quick_then_full``), None before any: what the page shows of a drag's last position
    #: until the full answer comes.
    last_quick_frame = None

    def __init__(self, scene: bool = False, vis=None, **initial):
        self.controls = self.declared_controls(initial)
        self.readout = widgets.HTML()
        #: The 3D view's caption (its magnifications), under the readout.
        self.caption = widgets.HTML()
        self.figure = None
        self.scene = None
        self.fig = self.new_figure(figsize=self.FIGSIZE)
        super().__init__(scene=scene, vis=vis)

    def _scene(self, kind: str):
        """The 3D view to draw in, or None (no scene asked for)."""
        if not self._want_scene:
            return None
        if self.scene is None:
            from ..scenes.modes import ModesScene
            self.scene = ModesScene(kind, vis=self.scene_root())
        return self.scene

    def _animate(self, kind: str, animate) -> None:
        """Show this update's motion in the 3D view, ``animate(scene)``, and its caption; during
        a drag once the page painted the figure (:meth:`~afmsmiler.ui.panel.Panel.after_frame`).
        """
        scene = self._scene(kind)
        if scene is None:
            return

        def show():
            animate(scene)
            self.caption.value = f"<div>3D view: {html.escape(scene.caption)}</div>"
        self.after_frame(show)

    #: Seconds a slider must rest, from the page's paint of the quick answer, before the full
    #: answer starts (:data:`FULL_DELAY`; a panel whose full answer runs in steps that a move
    #: interrupts may wait less).
    full_delay = FULL_DELAY
    #: The steps of a full answer under way (a generator, see :meth:`_quick_then_full`), else
    #: None.
    _full_steps = None

    def _quick_then_full(self, quick, full) -> None:
        """Run ``full()``; for a move from the browser in a live notebook ``quick()`` at once
        and ``full()`` only once the student saw the quick answer and left the slider for
        :attr:`full_delay` s.

        For a model that cannot answer every step of a drag in a kernel round trip (issue 24):
        ``quick`` shows a coarse answer and says so on screen, with no readout from it; ``full``
        shows the whole answer and the readouts. ``full`` may be a generator function: then the
        kernel's loop runs one of its steps per turn, a move from the browser that comes
        meanwhile goes first (its update drops the rest), and the answer shows at its last
        step. The panel's first update, a value a cell sets (which the cell may read at once)
        and everything outside a live kernel (tests, nbval, a script) run ``full`` at once and
        whole, and ``quick`` never. A newer move cancels a full answer still pending.

        The delay counts from the page's paint of the quick answer
        (:attr:`~afmsmiler.plots.live.LiveFigure.frames_painted`; at most
        :data:`~afmsmiler.plots.live.PAINT_WAIT` s after it was sent, and from its sending for
        a page that never says what it painted): a page busy with the student's keys paints
        nothing and sends no move until they stop, and a full answer begun meanwhile, for a
        value already passed, would hold up the next move's quick answer and add a frame
        for the page to paint first.
        """
        self._cancel_full()
        loop = _live_loop()
        if loop is None or not self.in_drag:
            steps = full()
            if steps is not None:
                for _ in steps:  # bounded: the model's steps are
                    pass
            return
        quick()
        if self.live is not None:
            self.last_quick_frame = self.live.frames_sent
        self._full_pending = loop.call_soon(self._full_after_paint, loop, full,
                                            loop.time() + PAINT_WAIT)

    def _full_after_paint(self, loop, full, until: float) -> None:
        """Schedule the full answer :attr:`full_delay` s after the page painted the quick one
        (a loop callback; polled every :data:`~afmsmiler.ui.panel._PAINT_POLL` s until
        ``until``, ``loop.time()``)."""
        live = self.live
        if live is not None and 0 < live.frames_painted < (self.last_quick_frame or 0) and \
                loop.time() < until:
            self._full_pending = loop.call_later(_PAINT_POLL, self._full_after_paint, loop,
                                                 full, until)
            return
        self._full_pending = loop.call_later(self.full_delay, self._full_step, loop, full)

    def _cancel_full(self) -> None:
        """Drop the full answer an older move left pending or under way
        (``_quick_then_full``)."""
        if self._full_pending is not None:
            self._full_pending.cancel()
            self._full_pending = None
        if self._full_steps is not None:
            self._full_steps.close()
            self._full_steps = None

    def _full_step(self, loop, full) -> None:
        """The pending full answer's next step (a loop callback: a failure shows under the
        panel): the first calls ``full``; a generator it returns is kept (:attr:`_full_steps`)
        and each later call runs one of its steps."""
        self._full_pending = None
        if self._deferred:
            # a move from the browser waits for its update: it goes first, and drops these
            # steps (unless it changed nothing, an echo: then they go on)
            self._full_pending = loop.call_later(_PAINT_POLL, self._full_step, loop, full)
            return
        try:
            if self._full_steps is None:
                steps = full()
                if steps is None:  # a plain function: shown
                    return
                self._full_steps = steps
            next(self._full_steps)
        except StopIteration:
            self._full_steps = None
            return
        except Exception as exc:  # shown, not lost in the kernel's log
            self._full_steps = None
            self._report_error(exc)
            return
        self._full_pending = loop.call_soon(self._full_step, loop, full)

    def widget(self) -> widgets.Widget:
        """Sliders with the readout beside them, the figure below.

        Returns
        -------
        ipywidgets.VBox
        """
        figure = super().widget().children[1]
        readouts = widgets.VBox([self.readout, self.caption])
        readouts.layout.margin = "0 0 0 16px"
        readouts.layout.width = "420px"
        top = widgets.HBox([widgets.VBox(list(self.controls.values())), readouts])
        return widgets.VBox([top, figure])


def _table(rows) -> str:
    return "<table>" + "".join(f"<tr><td>{k}</td><td style='text-align:right'><b>{v}</b></td>"
                               f"</tr>" for k, v in rows) + "</table>"


# -- tapping -------------------------------------------------------------------------------------
#: The tapping panel's sliders: name -> Parameter of :data:`afmsmiler.modes.TAPPING_PARAMETERS`.
TAPPING_SLIDERS = read_only({name: tapping.PARAMETERS[name] for name in (
    "free_amplitude", "setpoint_ratio", "quality_factor", "spring_constant",
    "resonance_frequency", "hamaker_constant", "youngs_modulus", "sample_viscosity")})

#: The lever's sliders, set by a vendor's probe in its fluid.
TAPPING_LEVER = ("spring_constant", "resonance_frequency", "quality_factor")
#: Vendors' tapping probes (:data:`afmsmiler.planform.PRESETS`) the panel offers: mode 1 in air
#: and in water within the sliders (a test checks each; contact levers ring below 10 kHz in water).
TAPPING_PROBES = ("Tap300Al-G", "PPP-NCHR", "Arrow-NCR", "AC160TS", "Tap150Al-G", "Multi75Al-G",
                  "PPP-FMR", "AC240TS")
#: The fluids a probe taps in (keys of :data:`afmsmiler.hydrodynamics.FLUIDS`).
TAPPING_FLUIDS = FLUID_NAMES

#: A browser's move of the lever or the sample first shows the curve at every
#: TAPPING_COARSE_STRIDE-th distance (50 of 400: in a process of its own the panel's step some
#: 7 ms, against 12-18 ms for 100 and some 40 ms for the full curve; in a live JupyterLab kernel
#: about twice these), then the full curve, its jumps and the held state once the student left
#: the slider for :attr:`TappingPanel.full_delay` s.
TAPPING_COARSE_STRIDE = 8
#: Distances of the full curve sampled per turn of the kernel's loop (1/8 of them: at most some
#: 7 ms in a process of its own; the roots of all of them then take some 8 ms more,
#: :func:`~afmsmiler.modes.tapping.amplitude_curve_steps`), so that a move made meanwhile waits
#: for one block only.
TAPPING_FULL_BLOCK = 50

#: Initial values in the units shown: a 12 nm free amplitude, where the setpoint decides the
#: branch (0.8 A0 ends on the repulsive branch, 0.9 A0 stays on the attractive one), on a typed
#: lever (k = 40 N/m, f0 = 300 kHz, Q = 400).
TAPPING_DEFAULTS = read_only({"probe": TYPED, "fluid": "air",
                              **_display(TAPPING_SLIDERS, free_amplitude=12e-9)})


def _on_grid(slider) -> float:
    """``slider``'s value moved to the nearest point of its grid (a log slider's, in the
    exponent), as the browser would show it."""
    log = isinstance(slider, widgets.FloatLogSlider)
    v = math.log(slider.value, slider.base) if log else slider.value
    top = math.floor((slider.max - slider.min) / slider.step + 1e-9)
    x = slider.min + min(max(round((v - slider.min) / slider.step), 0), top) * slider.step
    return float(f"{slider.base ** x if log else x:.12g}")


@functools.lru_cache(maxsize=None)
def tapping_oscillator(probe: str, fluid: str) -> dict:
    """The k, f0 and Q (SI) of ``probe``'s mode 1 in ``fluid`` (:func:`afmsmiler.probe.
    oscillator`), solved once per kernel."""
    return read_only(oscillator(preset(probe), fluid))


@dataclass(frozen=True)
class TappingState:
    """What the tapping panel last computed (SI), for tests and exercises.

    Attributes
    ----------
    lever : TappingLever
    curve : AmplitudeCurve
        Both branches on A0 x linspace(1.5, 0.01, SETPOINT_GRID).
    setpoint_ratio : float
    distance, phase, dissipated_energy : float
        The held state: z_c in m, phase lag in rad, E_dis in J (NaN when the approach never
        gets down to the setpoint).
    attractive : bool
        Whether the held state is on the attractive branch (the net force over a cycle is
        attractive; its tip may still touch the sample, see ``indentation``).
    indentation : float
        How deep the held state's tip dips into the sample in m, a0 - (z_c - A)
        (:meth:`~afmsmiler.modes.TappingLever.indentation`): > 0 when it touches, < 0 the gap
        by which it stays clear, NaN when nothing is held.
    """

    lever: TappingLever
    curve: AmplitudeCurve
    setpoint_ratio: float
    distance: float
    phase: float
    dissipated_energy: float
    attractive: bool
    indentation: float = math.nan

    @property
    def branch(self) -> str:
        """``"attractive"`` or ``"repulsive"``."""
        return "attractive" if self.attractive else "repulsive"

    @property
    def touches(self) -> bool:
        """Whether the held state's tip touches the sample once per cycle (indentation > 0)."""
        return bool(self.indentation > 0)


class TappingPanel(_SliderPanel):
    """Amplitude and phase against distance, both branches; the branch the setpoint picks.

    Controls (units as shown): ``probe`` (``"typed"`` or a vendor's probe of
    :data:`TAPPING_PROBES`), ``fluid`` (``"air"`` or ``"water"``: where a vendor's probe taps),
    and the sliders ``free_amplitude`` [nm], ``setpoint_ratio`` (A_sp / A0), ``quality_factor``,
    ``spring_constant`` [N/m], ``resonance_frequency`` [kHz], ``hamaker_constant`` [zJ],
    ``youngs_modulus`` [GPa] and ``sample_viscosity`` [Pa s]. A vendor's probe puts its mode 1
    in the fluid (Sader's hydrodynamics) on the k, f0 and Q sliders, which it disables.

    In a live notebook a slider move of the lever or the sample in the browser shows the curve
    at every :data:`TAPPING_COARSE_STRIDE`-th distance at once (each root exactly the full
    curve's; the figure's title says so and the readouts wait), and the full curve, its jumps,
    the held state and the 3D view once the slider rested :attr:`full_delay` s, made in blocks
    of :data:`TAPPING_FULL_BLOCK` distances, one per turn of the kernel's loop, that a newer
    move interrupts. A setpoint move reuses the curve shown. The first update, values a cell
    sets and everything outside a live kernel (tests, nbval, a script) make the full curve at
    once.

    Parameters
    ----------
    scene : bool
        Animate the tapping lever in the kernel's 3D viewer.
    vis : meshcat.Visualizer, optional
        Where to draw instead (tests pass a recorder); implies ``scene``.
    **initial
        Initial slider values in the units shown.

    Attributes
    ----------
    last : TappingState
        The state on the full curve of the last values it was made for.
    coarse : AmplitudeCurve or None
        The coarse curve shown while the full one is pending (None once it is shown).
    figure : TappingFigure
    scene : ModesScene or None
    model_runs : int
        :func:`~afmsmiler.modes.amplitude_curve` runs so far (one per move that changes the
        lever or sample, none for a setpoint move; in a live notebook one coarse per such move
        and one full per drag).
    """

    coarse = None
    #: As :attr:`ForceVolumePanel.full_delay`: a move waits for one block of the full curve at
    #: most.
    full_delay = 0.04

    SLIDERS = TAPPING_SLIDERS
    DEFAULTS = TAPPING_DEFAULTS
    FIGSIZE = (8.5, 7.5)

    def declared_controls(self, initial) -> dict:
        """The probe and fluid drop-downs, then the sliders (a probe's lever on them).

        A vendor's probe sets the k, f0 and Q sliders to its mode 1 in the fluid (Sader's
        hydrodynamics, :func:`tapping_oscillator`) and disables them; ``"typed"`` frees them
        (and the fluid, which then decides nothing, is disabled). Moving a lever slider in code
        makes the lever typed.
        """
        v = initial_values(initial, self.DEFAULTS)
        probe = check_choice("probe", v["probe"], [TYPED, *TAPPING_PROBES])
        fluid = check_choice("fluid", v["fluid"], TAPPING_FLUIDS)
        if probe != TYPED:
            given = sorted(set(initial) & set(TAPPING_LEVER))
            if given:
                raise ValueError(f"probe must be {TYPED!r} when {given} are given (a probe's "
                                 f"lever is its own), got {probe!r}")
            initial = {**initial, **self._lever_display(probe, fluid)}
        controls = {
            "probe": widgets.Dropdown(
                options=[("typed: k, f0, Q below", TYPED), *((p, p) for p in TAPPING_PROBES)],
                value=probe, description="probe"),
            "fluid": widgets.Dropdown(options=list(TAPPING_FLUIDS), value=fluid,
                                       description="fluid"),
            **super().declared_controls(initial)}
        # before the panel's own observers: one choice is one update
        for name in ("probe", "fluid"):
            controls[name].observe(self._on_probe, names="value")
        for name in TAPPING_LEVER:
            controls[name].observe(self._on_lever_slider, names="value")
        self.controls = controls
        self._enable_lever()
        return controls

    def _lever_display(self, probe: str, fluid: str) -> dict:
        """The lever sliders' values (units shown) of ``probe`` in ``fluid``."""
        o = tapping_oscillator(probe, fluid)
        return {n: float(f"{self.SLIDERS[n].to_display(o[n]):.12g}") for n in TAPPING_LEVER}

    #: Grid step (in the exponent) of a lever slider a probe drives: the browser snaps a value
    #: to its slider's grid, and the 6 % steps of a typed lever would show a probe's Q of 7.475
    #: as 7.535 beside the readout's 7.48.
    FINE_STEP = 1e-5

    def _enable_lever(self) -> None:
        """Lever sliders free for a typed lever; for a probe's, disabled, on a grid fine enough
        to show its values as they are (the typed grid back when it is typed again)."""
        typed = self.controls["probe"].value == TYPED
        self.controls["fluid"].disabled = typed
        steps = self.__dict__.setdefault("_typed_steps", {
            n: self.controls[n].step for n in TAPPING_LEVER})
        for name in TAPPING_LEVER:
            c = self.controls[name]
            c.disabled = not typed
            c.step = steps[name] if typed else self.FINE_STEP

    def _on_probe(self, change) -> None:
        """A probe or fluid was chosen: its lever on the sliders, no update of their own (the
        drop-down's own change runs the one update). Back to typed, the lever starts from the
        probe's values on the sliders' own grid (what the browser shows is what runs)."""
        self._enable_lever()
        probe = self.controls["probe"].value
        if probe != TYPED:
            self.sync_controls(self._lever_display(probe, self.controls["fluid"].value))
        elif change.get("name") == "value" and change.get("owner") is self.controls["probe"]:
            self.sync_controls({n: _on_grid(self.controls[n]) for n in TAPPING_LEVER})

    def set(self, **values) -> None:
        """Set control values as a user would, in one update (see :meth:`Panel.set`).

        A probe (and fluid) is applied first; k, f0 or Q given with it then make the lever
        typed, starting from the probe's.

        Parameters
        ----------
        **values
            Control names and values, in the units shown.
        """
        self.check_values(values)
        super().set(**self.choice_first(values, ("probe", "fluid"), TAPPING_LEVER, TYPED))

    def _on_lever_slider(self, change) -> None:
        """A lever slider moved (in code: the browser cannot move a disabled one): the lever is
        typed from now on. A browser's echo of a synced value is no move."""
        if self.controls["probe"].value == TYPED or self.is_echo(change):
            return
        self.sync_controls({"probe": TYPED})

    def update(self, **values) -> None:
        """Run the model (unless only the setpoint moved) and draw the curves and the state.

        Parameters
        ----------
        **values
            Exactly the controls: ``probe`` and ``fluid`` (str) and the sliders of
            :data:`TAPPING_SLIDERS` in SI. With a vendor's probe its lever in the fluid
            replaces the k, f0 and Q given.

        Raises
        ------
        TypeError, ValueError
            For a missing or unknown control or a value out of range, before any work.
        """
        si = dict(values)
        r = si.pop("setpoint_ratio")
        probe, fluid = si.pop("probe"), si.pop("fluid")
        if probe != TYPED:
            si.update(tapping_oscillator(probe, fluid))
        lever = TappingLever(**si)
        self._cancel_full()  # a move back to the lever shown needs no curve still pending
        previous = self.last
        if previous is not None and previous.lever == lever:
            self._show_state(previous.curve, r, probe, fluid)
            return
        distances = lever.free_amplitude * np.linspace(1.5, 0.01, tapping.SETPOINT_GRID)

        def quick():
            self.coarse = self.run_model(tapping.amplitude_curve,
                                         distances[::TAPPING_COARSE_STRIDE], lever)
            self.draw(TappingFigure, self.coarse, None, jumps=None, status=(
                f"coarse curve: every {TAPPING_COARSE_STRIDE}th distance "
                f"({self.coarse.distance.size} of {distances.size}); the jumps, the held state "
                f"and the numbers follow when the slider rests"))
            self.readout.value = _table([("held at z_c", "computing the full curve ...")])

        def full():  # in steps of TAPPING_FULL_BLOCK distances: a move waits for one block
            curve = yield from self.run_model(tapping.amplitude_curve_steps, distances, lever,
                                              block_distances=TAPPING_FULL_BLOCK)
            self._show_state(curve, r, probe, fluid)

        self._quick_then_full(quick, full)

    def _show_state(self, curve, r: float, probe: str, fluid: str) -> None:
        """Hold the lever at setpoint ``r`` on ``curve`` (the full curve); draw it and the
        state, animate the 3D view and write the readouts."""
        self.coarse = None
        lever = curve.lever
        try:
            zc, phase, e_dis, attractive = operating_point(curve, r)
        except ValueError:  # the approach never gets down to the setpoint: nothing is held
            zc = phase = e_dis = math.nan
            attractive = False
            point = None
        else:
            point = (r, zc, phase, e_dis, attractive)
        depth = math.nan if point is None else lever.indentation(zc, r * lever.free_amplitude)
        self.last = TappingState(lever, curve, r, zc, phase, e_dis, attractive, depth)
        jumps = curve.jumps  # the same run of the approach as operating_point's
        self.draw(TappingFigure, curve, point, jumps=jumps, status="")
        if point is None:
            self.readout.value = (f"<div><b>The approach never gets down to {r:g} A0</b> (down "
                                  f"to z_c = {shown(float(curve.distance.min()), 'nm', '.3g')}): "
                                  f"no state is held; raise the setpoint.</div>")
            if self.scene is not None:  # its view keeps the last state it drew, and says so
                self._after = None
                self.caption.value = ("<div>3D view: still the last state held, "
                                      f"{html.escape(self.scene.caption)}</div>")
            return
        self._animate("tapping", lambda scene: scene.animate_tapping(
            zc, r * lever.free_amplitude, free_amplitude=lever.free_amplitude,
            contact_distance=lever.intermolecular_distance))
        s = self.last
        self.readout.value = _table([
            ("lever", "typed" if probe == TYPED else
             f"{probe} in {fluid}: Q = {lever.quality_factor:.3g}, f0 = "
             f"{shown(lever.resonance_frequency, 'kHz', '.4g')} (Sader)"),
            ("held at z_c", shown(zc, "nm")), ("amplitude A", shown(r * lever.free_amplitude,
                                                                   "nm")),
            ("phase lag", shown(phase, "deg")), ("E_dis per cycle", shown(e_dis, "zJ")),
            ("branch (net force)", s.branch),
            ("tip touches the sample", f"yes, {shown(depth, 'nm', '.2g')} deep" if s.touches
             else f"no, {shown(-depth, 'nm', '.2g')} clear")])


# -- lateral force --------------------------------------------------------------------------------
_MU = lateral.FRICTION_COEFFICIENT
#: The lateral panel's sliders: name -> Parameter of :data:`afmsmiler.modes.LATERAL_PARAMETERS`.
LATERAL_SLIDERS = read_only({
    "friction_a": _MU.with_(name="friction_a", default=0.1,
                            label="friction coefficient mu of material A"),
    "friction_b": _MU.with_(name="friction_b", default=0.4,
                            label="friction coefficient mu of material B"),
    "tilt": lateral.TILT, "normal_force": lateral.NORMAL_FORCE,
    "lateral_noise": lateral.LATERAL_NOISE})

#: Initial values in the units shown: a tilted sample (3 deg), so that the slope shows.
LATERAL_DEFAULTS = read_only(_display(LATERAL_SLIDERS, tilt=np.radians(3.0)))

#: The sample the lateral panel scans: (rows, columns), pixel size in m (a disc and a stripe of
#: material B on material A, :func:`~afmsmiler.modes.friction_sample`).
LATERAL_SAMPLE = read_only(dict(shape=(32, 64), pixel_size=10e-9))


@functools.lru_cache(maxsize=1)
def lateral_lever() -> LateralLever:
    """The lever of the lateral panel: silicon, 450 x 50 x 2 um, a 15 um tip (k_t ~ 105 N/m).

    Returns
    -------
    LateralLever
    """
    return LateralLever(Cantilever.from_material("silicon", length=450e-6, width=50e-6,
                                                 thickness=2e-6), tip_height=15e-6)


@dataclass(frozen=True)
class LateralState:
    """What the lateral panel last computed (SI).

    Attributes
    ----------
    images : FrictionImages
        The scan's trace and retrace images.
    loop : FrictionLoop
        Its middle line.
    row : int
        The row of the loop.
    friction : ndarray
        The friction-coefficient map the sample was made with.
    twist, signal : ndarray
        Shape (2, n): the lever's twist in rad and the lateral photodiode signal along the loop
        (trace, retrace).
    """

    images: FrictionImages
    loop: FrictionLoop
    row: int
    friction: np.ndarray
    twist: np.ndarray
    signal: np.ndarray


class LateralPanel(_SliderPanel):
    """A friction loop and the friction and slope maps of a tilted two-material sample.

    Sliders (units as shown): ``friction_a``, ``friction_b`` (mu of the two materials),
    ``tilt`` [deg] (of the sample along the fast axis: a slope), ``normal_force`` [nN],
    ``lateral_noise`` [nN].

    Parameters
    ----------
    scene : bool
        Animate the twisting lever in the kernel's 3D viewer.
    vis : meshcat.Visualizer, optional
        Where to draw instead; implies ``scene``.
    **initial
        Initial slider values in the units shown.

    Attributes
    ----------
    last : LateralState
    figure : LateralFigure
    model_runs : int
        :func:`~afmsmiler.modes.friction_scan` runs so far (one per move).
    """

    SLIDERS = LATERAL_SLIDERS
    DEFAULTS = LATERAL_DEFAULTS
    FIGSIZE = (9.0, 7.0)

    def update(self, **values) -> None:
        """Scan the sample once with these values and draw the loop and the maps.

        Parameters
        ----------
        **values : float
            Exactly the sliders of :data:`LATERAL_SLIDERS`, in SI.

        Raises
        ------
        TypeError, ValueError
            For a missing or unknown slider or a value out of range, before any work.
        """
        si = dict(values)
        lever = lateral_lever()
        topo, mu = lateral.friction_sample(
            LATERAL_SAMPLE["shape"], LATERAL_SAMPLE["pixel_size"],
            coefficients=(si["friction_a"], si["friction_b"]), tilt=si["tilt"])
        images = self.run_model(lateral.friction_scan, topo, mu, normal_force=si["normal_force"],
                                       lateral_stiffness=lever.spring_constant,
                                       lateral_noise=si["lateral_noise"], seed=0)
        row = LATERAL_SAMPLE["shape"][0] // 2
        x = np.arange(LATERAL_SAMPLE["shape"][1]) * topo.pixel_size
        loop = FrictionLoop(x, images.trace.heights[row], images.retrace.heights[row],
                            images.normal_force, lever.spring_constant)
        forces = np.vstack((loop.trace, loop.retrace))
        twist, signal = lever.twist(forces), lever.signal(forces)
        self.last = LateralState(images, loop, row, mu.heights, twist, signal)
        self.draw(LateralFigure, loop, images, row)
        self._animate("lateral", lambda scene: scene.animate_lateral(
            x, twist, signal, materials=mu.heights[row] == si["friction_b"]))
        sliding = slice(1, -1)
        self.readout.value = _table([
            ("mean friction / load (line)",
             f"{float(np.mean(loop.friction_coefficient[sliding])):.4g}"),
            ("mean trace / load (line)",
             f"{float(np.mean(loop.trace[sliding])) / loop.normal_force:.4g}"),
            ("lateral stiffness k_t", shown(lever.spring_constant, "N/m")),
            ("largest twist", shown(float(np.abs(twist).max()), "mrad"))])


# -- frequency modulation -------------------------------------------------------------------------
#: The FM panel's sliders: the lever's (:data:`afmsmiler.modes.FM_PARAMETERS`) and the force
#: law's (:data:`afmsmiler.modes.FORCE_PARAMETERS`).
FM_SLIDERS = read_only({
    **{name: fm.PARAMETERS[name] for name in ("amplitude", "spring_constant",
                                              "resonance_frequency")},
    **{name: FORCE_PARAMETERS[name] for name in ("hamaker_constant", "radius",
                                                 "youngs_modulus")}})

#: Initial values in the units shown.
FM_DEFAULTS = read_only(_display(FM_SLIDERS))

#: The closest distances of the FM panel's curve, in m (from just above the contact distance
#: a0 = 0.165 nm, where the inversion is valid, to 12 nm), and the one the 3D view animates.
FM_DISTANCES = read_only(dict(low=0.2e-9, high=12e-9, points=300, shown=1e-9))


@dataclass(frozen=True)
class FrequencyShiftState:
    """What the FM panel last computed (SI).

    Attributes
    ----------
    curve : FrequencyShiftCurve
        Force, df and the force recovered.
    force_law : dict
        The force law's parameters (SI), as given to
        :func:`~afmsmiler.modes.tip_sample_force`.
    """

    curve: FrequencyShiftCurve
    force_law: dict


class FrequencyShiftPanel(_SliderPanel):
    """The frequency shift of a force law and the force the Sader-Jarvis inversion recovers.

    Sliders (units as shown): ``amplitude`` [nm], ``spring_constant`` [N/m],
    ``resonance_frequency`` [kHz], and the force law's ``hamaker_constant`` [zJ], ``radius``
    [nm] and ``youngs_modulus`` [GPa] (van der Waals above a0, DMT contact below).

    Parameters
    ----------
    scene : bool
        Animate the FM lever in the kernel's 3D viewer.
    vis : meshcat.Visualizer, optional
        Where to draw instead; implies ``scene``.
    **initial
        Initial slider values in the units shown.

    Attributes
    ----------
    last : FrequencyShiftState
    figure : FrequencyShiftFigure
    model_runs : int
        :func:`~afmsmiler.modes.frequency_shift_curve` runs so far (one per move).
    """

    SLIDERS = FM_SLIDERS
    DEFAULTS = FM_DEFAULTS
    FIGSIZE = (8.5, 6.5)

    def update(self, **values) -> None:
        """Run the round trip once with these values and draw it.

        Parameters
        ----------
        **values : float
            Exactly the sliders of :data:`FM_SLIDERS`, in SI.

        Raises
        ------
        TypeError, ValueError
            For a missing or unknown slider or a value out of range, before any work.
        """
        si = dict(values)
        law = {name: si[name] for name in ("hamaker_constant", "radius", "youngs_modulus")}
        from ..modes import tip_sample_force
        force = functools.partial(tip_sample_force, **law)
        d = FM_DISTANCES
        z = np.linspace(d["low"], d["high"], d["points"])
        curve = self.run_model(fm.frequency_shift_curve, force, z, amplitude=si["amplitude"],
                                         spring_constant=si["spring_constant"],
                                         resonance_frequency=si["resonance_frequency"])
        self.last = FrequencyShiftState(curve, law)
        self.draw(FrequencyShiftFigure, curve)
        i = int(np.argmin(np.abs(z - d["shown"])))
        self._animate("fm", lambda scene: scene.animate_fm(
            float(z[i]), curve.amplitude, float(curve.frequency_shift[i]),
            resonance_frequency=curve.resonance_frequency))
        peak = float(np.max(np.abs(curve.force)))
        self.readout.value = _table([
            (f"df at z = {shown(float(z[i]), 'nm', '.3g')}",
             shown(float(curve.frequency_shift[i]), "Hz")),
            ("small-amplitude df there", shown(float(curve.gradient_shift[i]), "Hz")),
            ("largest inversion error", f"{100 * float(np.max(np.abs(curve.error))) / peak:.2g}"
                                        f" % of the peak force")])


# -- jumping --------------------------------------------------------------------------------------
#: The jumping panel's sliders: :data:`afmsmiler.modes.jumping.PARAMETERS` and the sample's
#: modulus and work of adhesion (:data:`afmsmiler.contact.PARAMETERS`).
JUMPING_SLIDERS = read_only({**jumping.PARAMETERS,
                             "youngs_modulus": CONTACT["youngs_modulus"],
                             "work_of_adhesion": CONTACT["work_of_adhesion"]})

#: Initial values in the units shown: a lift of 150 nm, above the grating's 100 nm bars.
JUMPING_DEFAULTS = read_only(_display(JUMPING_SLIDERS, lift_height=150e-9, youngs_modulus=1e9,
                                      work_of_adhesion=0.05))

#: The jumping panel's scan (SI): a grating of 100 nm tall bars (period 320 nm, 64 x 32 pixels
#: of 10 nm), a 300 nm scan of 32 pixels x 8 lines, a 1 N/m lever with a 10 nm paraboloid tip.
JUMPING_SCAN = read_only(dict(shape=(32, 64), pixel_size=10e-9, period=320e-9, height=100e-9,
                              scan_size=300e-9, pixels=32, lines=8, spring_constant=1.0,
                              tip_radius=10e-9))


@dataclass(frozen=True)
class JumpingState:
    """What the jumping panel last computed (SI).

    Attributes
    ----------
    system : ContactSystem
        Tip, lever and sample (module (d)).
    curve : JumpCurve
        One pixel's force curve.
    result : ScanResult
        The image of the grating.
    acquisition_time, contact_time : float
        The image's time in s in jumping mode and in contact mode (same scan speed).
    """

    system: ContactSystem
    curve: jumping.JumpCurve
    result: ScanResult
    acquisition_time: float
    contact_time: float


class JumpingPanel(_SliderPanel):
    """A jumping-mode pixel's force curve and the image of a grating of tall bars.

    Sliders (units as shown): ``trigger_force`` [nN], ``lift_height`` [nm], ``z_speed`` [um/s],
    ``youngs_modulus`` [MPa] and ``work_of_adhesion`` [mJ/m^2] of the sample.

    Parameters
    ----------
    scene : bool
        Animate the jumping cycle in the kernel's 3D viewer.
    vis : meshcat.Visualizer, optional
        Where to draw instead; implies ``scene``.
    **initial
        Initial slider values in the units shown.

    Attributes
    ----------
    last : JumpingState
    figure : JumpingFigure
    model_runs : int
        Runs of the models so far: one :func:`~afmsmiler.modes.jumping.jump_curve` and one scan
        per move (counted as one each).
    """

    SLIDERS = JUMPING_SLIDERS
    DEFAULTS = JUMPING_DEFAULTS
    FIGSIZE = (9.5, 7.0)

    def update(self, **values) -> None:
        """Compute one pixel's curve and the image with these values, and draw them.

        Parameters
        ----------
        **values : float
            Exactly the sliders of :data:`JUMPING_SLIDERS`, in SI.

        Raises
        ------
        TypeError, ValueError
            For a missing or unknown slider, a value out of range, or a lift that does not take
            the tip off the surface (the model's message), before any work.
        """
        si = dict(values)
        d = JUMPING_SCAN
        tip = Parabolic(radius=d["tip_radius"])
        system = ContactSystem(spring_constant=d["spring_constant"], tip=tip,
                               youngs_modulus=si["youngs_modulus"], adhesion="dmt",
                               work_of_adhesion=si["work_of_adhesion"])
        settings = {name: si[name] for name in jumping.PARAMETERS}
        curve = jumping.jump_curve(system, **settings)
        mode = jumping.JumpingMode(system, **settings)
        sample = grating(d["shape"], d["pixel_size"], period=d["period"], height=d["height"])
        scan_settings = ScanSettings(d["scan_size"], pixels=d["pixels"], lines=d["lines"])
        result = self.run_model(_scan, sample, tip, mode, scan_settings)
        self.last = JumpingState(system, curve, result, mode.acquisition_time(scan_settings),
                                 scan_settings.scan_time)
        self.draw(JumpingFigure, curve, result)

        def animate(scene):
            heights, xs, touching = self._cycle(curve, result)
            scene.animate_jumping(heights, xs, pixel_size=result.pixel_size, contact=touching)
        self._animate("jumping", animate)
        crash = result.crashed
        self.readout.value = _table([
            ("pull-off force", shown(curve.pull_off_force, "nN")),
            ("time per pixel (approach + retract)", shown(curve.cycle_time, "ms")),
            ("image in jumping mode", f"{self.last.acquisition_time:.3g} s"),
            ("image in contact mode", f"{self.last.contact_time:.3g} s"),
            ("largest lateral force", shown(float(np.nanmax(np.abs(
                result.images["lateral force trace"]))), "nN")),
            ("crash", "none" if crash is None  # counted from 1, as the figures count lines
             else f"line {crash.row + 1}, pixel {crash.column + 1}")])

    @staticmethod
    def _cycle(curve, result, pixels: int = 4, frames: int = 12):
        """The apex's path (:func:`~afmsmiler.modes.jumping.apex_path`) over ``pixels`` pixels
        of the middle line."""
        row = result.images["height trace"].shape[0] // 2
        surface = np.nan_to_num(result.images["height trace"][row, :pixels])
        return jumping.apex_path(curve, surface, result.pixel_size, frames=frames)


# -- force volume ---------------------------------------------------------------------------------
#: The force-volume panel's sliders: :data:`afmsmiler.modes.force_volume.PARAMETERS`' peak force,
#: ramp size, force noise and spring constant.
FORCE_VOLUME_SLIDERS = read_only({name: _fv.PARAMETERS[name] for name in (
    "peak_force", "ramp_size", "force_noise", "spring_constant")})

#: Initial values in the units shown.
FORCE_VOLUME_DEFAULTS = read_only(_display(FORCE_VOLUME_SLIDERS))

#: The mapped sample (SI): 10 x 10 pixels of 24 nm (one fit per pixel: the full map some 18 ms
#: in a process of its own, the coarse one some 5 ms),
#: two islands of 70 nm radius of the blend's soft, sticky material in its stiff matrix
#: (:data:`afmsmiler.modes.force_volume.BLEND`), a 10 nm paraboloid tip, DMT adhesion, seed 0 of
#: the noise.
FORCE_VOLUME_MAP = read_only(dict(shape=(10, 10), pixel_size=24e-9, island_radius=70e-9,
                                  island_count=2, seed=3, tip_radius=10e-9, noise_seed=0))


#: A live move first shows the map of every COARSE_STRIDE-th pixel (a quarter of the fits), then
#: the full map once the student left the slider for :attr:`ForceVolumePanel.full_delay` s.
COARSE_STRIDE = 2
#: Pixels the full map fits per turn of the kernel's loop (a quarter of the map: some 3.5 ms in
#: a process of its own), so that a move made meanwhile waits for one block only.
FULL_BLOCK = 25


class ForceVolumePanel(_SliderPanel):
    """Modulus, adhesion, deformation and dissipation maps of a two-material blend.

    Sliders (units as shown): ``peak_force`` [nN], ``ramp_size`` [nm], ``force_noise`` [pN]
    and ``spring_constant`` [N/m].

    In a live notebook a slider move in the browser shows a coarse map at once (every
    :data:`COARSE_STRIDE`-th pixel of every other row, computed exactly as in the full map, the
    figure's title says so) and the full map once the slider rested :attr:`full_delay` s, made
    in blocks of :data:`FULL_BLOCK` pixels, one per turn of the kernel's loop, that a newer
    move interrupts; the readouts come from the full map only. The first update, values a cell sets and
    everything outside a live kernel (tests, nbval, a script) make the full map at once.

    Parameters
    ----------
    scene : bool
        Unused (the maps are 2D); accepted for a uniform interface.
    vis : meshcat.Visualizer, optional
        Unused.
    **initial
        Initial slider values in the units shown.

    Attributes
    ----------
    last : ForceVolume
        The full maps of the last values the full map was made for.
    coarse : ForceVolume or None
        The coarse map shown while the full one is pending (None once it is shown).
    labels : ndarray
        The material of each pixel (the truth).
    figure : ForceVolumeFigure
    model_runs : int
        :func:`~afmsmiler.modes.force_volume.force_volume` runs so far (one per move; in a live
        notebook one coarse per move and one full per drag).
    """

    coarse = None
    #: A move waits for one block of the full map at most, not for all of it (as for a full
    #: answer made at once, :data:`FULL_DELAY`): the map begins 40 ms after the page painted the
    #: coarse one, a little more than a held key's repeat (some 30 a second).
    full_delay = 0.04

    SLIDERS = FORCE_VOLUME_SLIDERS
    DEFAULTS = FORCE_VOLUME_DEFAULTS
    FIGSIZE = (10.0, 6.5)

    def update(self, **values) -> None:
        """Map the sample once with these values and draw the maps.

        Parameters
        ----------
        **values : float
            Exactly the sliders of :data:`FORCE_VOLUME_SLIDERS`, in SI.

        Raises
        ------
        TypeError, ValueError
            For a missing or unknown slider, a value out of range or a ramp too short to take
            the tip off (the model's message), before any work.
        """
        si = dict(values)

        def quick():
            self.coarse = self._map(si, COARSE_STRIDE)
            shape, full = self.coarse.modulus.shape, FORCE_VOLUME_MAP["shape"]
            self._show(self.coarse, status=(
                f"coarse map: every {COARSE_STRIDE}nd pixel ({shape[0]} x {shape[1]} of "
                f"{full[0]} x {full[1]}); the full map follows when the slider rests"))

        def full():  # in steps of FULL_BLOCK pixels: a move waits for one block, not the map
            volume = yield from self._map(si, block_pixels=FULL_BLOCK)
            self._show(volume)

        self._quick_then_full(quick, full)

    def _map(self, si: dict, stride: int = 1, block_pixels: int | None = None):
        """The model: the blend's maps for slider values ``si`` (SI), every ``stride``-th pixel;
        with ``block_pixels`` the generator of its steps
        (:func:`~afmsmiler.modes.force_volume.force_volume_steps`)."""
        d = FORCE_VOLUME_MAP
        sample, labels = _fv.two_material_sample(d["shape"], d["pixel_size"],
                                                 island_radius=d["island_radius"],
                                                 island_count=d["island_count"], seed=d["seed"])
        self.labels = labels
        model, more = ((_fv.force_volume, {}) if block_pixels is None else
                       (_fv.force_volume_steps, {"block_pixels": block_pixels}))
        return self.run_model(model, sample, _fv.BLEND, Parabolic(radius=d["tip_radius"]),
                              labels=labels, seed=d["noise_seed"], stride=stride, **si, **more)

    def _show(self, volume, status: str = "") -> None:
        """Draw ``volume``; a full map (no ``status``) also becomes :attr:`last` and the readouts."""
        self.draw(ForceVolumeFigure, volume, made_with={"names": [m.name for m in _fv.BLEND]},
                  status=status)
        if status:
            self.readout.value = _table([("the maps' medians", "computing the full map ...")])
            return
        self.coarse = None
        self.last = volume
        labels = volume.labels
        rows = []

        def median(values, unit):
            finite = values[np.isfinite(values)]
            return shown(float(np.median(finite)), unit, ".4g") if finite.size else \
                "no fit converged"

        for i, m in enumerate(_fv.BLEND):
            mask = labels == i
            rows.append((f"{m.name}: E (median of the map)",
                         median(volume.modulus[mask], "MPa") +
                         f" (true {shown(m.youngs_modulus, 'MPa', '.4g')})"))
            rows.append((f"{m.name}: adhesion (median)", median(volume.adhesion[mask], "nN")))
        self.readout.value = _table(rows)
