"""The widget panel of module (f): scan a sample and watch the image form, line by line.

Controls: the sample (synthetic generators of :mod:`afmsmiler.samples` and the real image that
ships), the imaging mode, the tip, the scan settings and the mode's own settings, every slider
built by :func:`~afmsmiler.ui.controls.control` from a :class:`~afmsmiler.parameters.Parameter`
of the model layer (:data:`afmsmiler.imaging.settings.PARAMETERS`, the controller's and the contact
model's), and the choice of what a slider moved during a scan does: apply from the next line on,
or restart the scan. Start, Pause/Resume and Stop buttons, a "pause after line" box and a progress
bar sit beside them: a scan paused (by the button, or by itself after the line the box names) waits
with its finished lines kept, for as long as the student needs to move a slider, and Resume goes on
from the next line.

The scan is an acquisition below the UI (:class:`~afmsmiler.imaging.acquisition.ScanAcquisition`):
it holds the image, scans one line per step (one model run) and takes a slider moved during the
scan from the next line on. The panel reads values -> acquisition -> view: :meth:`update` turns
the controls' values into a sample, tip, mode and settings (no scan); Start makes the acquisition
and starts it; the buttons, the progress bar and the live loop on the kernel's event loop are
module (h)'s too (:class:`~afmsmiler.ui.acquisition.AcquisitionControls`): in a live notebook the
steps run as an asyncio task, one line per line time of the instrument (at most
:attr:`ImagingPanel.MAX_LINE_WAIT`), so the kernel keeps handling the widgets' messages between
lines; at most one picture per :attr:`ImagingPanel.FRAME_INTERVAL`. Tests (and nbval) drive the
steps synchronously: ``start(run=False)``, then ``step()`` / ``pause()`` / ``resume(run=False)`` /
``stop()``. Lines already finished are never lost.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import ipywidgets as widgets
import numpy as np

from .. import samples as _samples
from ..contact import PARAMETERS as CONTACT
from ..contact import TIPS, ContactSystem, Tip, make_tip
from ..controller import PARAMETERS as LOOP, PRESETS
from ..acquisition import SettingsRefused, Snapshot
from ..imaging import scan_modes as _modes
from ..imaging import settings as _settings
from ..imaging.acquisition import ScanAcquisition
from ..imaging.scan_modes import PARAMETERS as MODE_PARAMETERS
from ..parameters import read_only
from ..plots.imaging import ImagingFigure, crash_note, scan_view
from ..samples import Sample
from ..validation import check_choice, check_finite
from .acquisition import Acquiring, AcquisitionControls
from .controls import WIDTH
from .panel import Panel, check_control_value, initial_values, running_as_notebook, slider

__all__ = ["ImagingPanel", "DEFAULTS", "SAMPLES", "MODES", "ON_CHANGE", "SCAN_SLIDERS", "sample",
           "max_scan_size", "MODE_SLIDERS", "TIP_CONTROLS", "PIXELS"]

#: The samples to scan: name -> (generator in :mod:`afmsmiler.samples`, its arguments in SI).
#: Every synthetic one is 256 x 256 pixels of 2 nm (0.51 um); the real image is 2 um wide.
SAMPLES = read_only({
    "particles": ("particles", read_only(dict(shape=(256, 256), pixel_size=2e-9, count=12,
                                              radius=15e-9, rms=0.3e-9, seed=1))),
    "grating": ("grating", read_only(dict(shape=(256, 256), pixel_size=2e-9, period=100e-9,
                                          height=20e-9, duty=0.5))),
    "terraces": ("terraces", read_only(dict(shape=(256, 256), pixel_size=2e-9,
                                            step_height=1e-9, terrace_width=60e-9,
                                            direction=0.3))),
    "fibres (DNA-like)": ("fibres", read_only(dict(shape=(256, 256), pixel_size=2e-9,
                                                   count=5, seed=2))),
    "rough surface": ("rough_surface", read_only(dict(shape=(256, 256), pixel_size=2e-9,
                                                      rms=3e-9, correlation_length=20e-9,
                                                      seed=1))),
    "real image (Bruker, 2 um)": ("real_image", read_only({})),
})

#: Imaging modes: name -> class of :mod:`afmsmiler.imaging.scan_modes`.
MODES = ("constant force", "constant height")

#: What a slider moved during a scan does.
ON_CHANGE = ("apply on next line", "restart")

#: Pixels per line (and lines) offered; a scan of 256 x 256 takes a few seconds live.
PIXELS = (16, 32, 64, 128, 256)

#: The scan's sliders, from :data:`afmsmiler.imaging.settings.PARAMETERS`.
SCAN_SLIDERS = ("scan_size", "scan_speed", "angle", "tilt_x", "noise")

#: The modes' sliders: mode -> control name -> Parameter of the model layer.
MODE_SLIDERS = read_only({
    "constant force": read_only({name: LOOP[name] for name in ("kp", "ki", "setpoint")}),
    "constant height": read_only({"z_np": CONTACT["z_np"],
                                  "damage_force": MODE_PARAMETERS["damage_force"]}),
})

#: Tip-parameter controls from the registry :data:`afmsmiler.contact.TIPS` (shared names once).
TIP_CONTROLS = read_only({p.name: p for cls in TIPS.values() for p in cls.parameters})

#: Controls whose change makes another image (another grid, channel or sample): they restart
#: the scan whatever ``on_change`` says.
RESTART = ("sample", "mode", "pixels", "scan_size", "angle")

#: The scan range at the start in m (a 300 nm square: every sample holds it at any angle).
SCAN_SIZE = 300e-9

#: The mechanics of constant force: preset (a) of module (c) (a stiff sample, stable gains).
PLANT = "a_good_tracking"


def _extent(s: Sample) -> float:
    """The shorter side of a sample in m (first to last pixel)."""
    rows, cols = np.shape(s.heights)
    return min((cols - 1) * s.pixel_size, (rows - 1) * s.pixel_size_y)


def max_scan_size(name: str, angle: float = 0.0) -> float:
    """The largest scan range in m that fits on sample ``name`` at scan ``angle``.

    A square scan of side S rotated by ``angle`` spans S (|cos angle| + |sin angle|) along x and
    y, so S <= W / (|cos| + |sin|) for the sample's shorter side W (first to last pixel) keeps
    the scan on the sample: the whole 2 um real image at angle 0, 1.41 um of it at 45 deg (one
    range for every sample and angle capped every scan at 0.36 um). The scan-size slider ends
    there, so no slider position makes the scanner refuse the scan.

    Parameters
    ----------
    name : str
        A key of :data:`SAMPLES`.
    angle : float
        Scan angle in rad.

    Returns
    -------
    float

    Raises
    ------
    ValueError
        For an unknown sample or an angle that is not finite.
    """
    width = _extent(sample(name))
    angle = check_finite("angle", angle, "rad")
    return width / (abs(math.cos(angle)) + abs(math.sin(angle)))


def _slider_defaults() -> dict:
    out = {name: _settings.PARAMETERS[name].to_display(_settings.PARAMETERS[name].default)
           for name in SCAN_SLIDERS}
    for sliders in MODE_SLIDERS.values():
        out.update({name: p.to_display(p.default) for name, p in sliders.items()})
    out.update({name: p.to_display(p.default) for name, p in TIP_CONTROLS.items()})
    loop = PRESETS[PLANT].loop
    out.update(kp=loop.kp, ki=LOOP["ki"].to_display(loop.ki),
               scan_size=_settings.PARAMETERS["scan_size"].to_display(SCAN_SIZE))
    return {k: float(f"{v:.12g}") for k, v in out.items()}


#: Initial control values, in the units the controls show.
DEFAULTS = read_only(dict(sample="particles", mode="constant force", tip="parabolic", pixels=64,
                          on_change="apply on next line", **_slider_defaults()))

_SAMPLE_CACHE: dict = {}


def sample(name: str) -> Sample:
    """The sample ``name`` of :data:`SAMPLES` (made once per kernel).

    Parameters
    ----------
    name : str
        A key of :data:`SAMPLES`.

    Returns
    -------
    Sample
    """
    check_choice("sample", name, list(SAMPLES))
    if name not in _SAMPLE_CACHE:
        generator, kwargs = SAMPLES[name]
        _SAMPLE_CACHE[name] = getattr(_samples, generator)(**kwargs)
    return _SAMPLE_CACHE[name]


@dataclass
class _Config:
    """What one update decided (SI), to build a Scan from."""

    sample: Sample
    tip: Tip
    mode: object
    settings: object
    key: tuple = field(default=())


class ImagingPanel(Acquiring, Panel):
    """Scan a sample in a chosen mode and watch the image grow, line by line.

    Controls (units as shown): ``sample``, ``mode`` (constant force, constant height), ``tip``
    and its parameters (only the chosen shape's are shown), ``pixels`` (pixels per line = lines),
    ``scan_size`` [um], ``scan_speed`` [um/s], ``angle`` [deg], ``tilt_x`` [deg] (the sample's
    tilt along x), ``noise`` [nm], the mode's sliders (constant force: ``kp``, ``ki`` [1/us],
    ``setpoint`` [nm] on the mechanics of module (c)'s preset (a); constant height: ``z_np``
    [nm], ``damage_force`` [nN]), and ``on_change`` (``"apply on next line"`` or ``"restart"``).
    Buttons: Start, Pause (Resume while paused), Stop; a "pause after line" box (0: never), a
    progress bar.

    Parameters
    ----------
    scene : bool
        Draw the 3D view (:class:`~afmsmiler.scenes.imaging.ImagingScene`: the sample, the
        image's finished lines, the tip where the last line ended) in the kernel's viewer.
    vis : meshcat.Visualizer, optional
        Where the 3D view draws instead of the kernel's viewer (tests pass a recorder); implies
        ``scene``.
    **initial
        Initial control values (keys of :data:`DEFAULTS`), in the units shown.

    Attributes
    ----------
    last : afmsmiler.acquisition.Snapshot
        The image so far (immutable; every channel, NaN where no line was scanned), the lines
        done, the state (``stopped``, ``paused``), the crash (``fault``) and the rows from which
        new settings applied (``changes``).
    acquisition : afmsmiler.imaging.acquisition.ScanAcquisition or None
        The scan (None before the first Start); it holds the image.
    figure : ImagingFigure
        The image, the error channel and the last line's profiles.
    scene : ImagingScene or None
        The 3D view (None without ``scene``).
    progress : ipywidgets.IntProgress
        Lines done out of the lines of the scan.
    running : bool
        A scan is under way (started, neither finished nor stopped; also while paused).
    paused : bool
        The running scan waits after its last finished line until :meth:`resume`.
    pause_at : ipywidgets.BoundedIntText
        Pause by itself once this many lines are finished (0: never); read when each line ends.
    """

    def __init__(self, scene: bool = False, vis=None, **initial):
        v = initial_values(initial, DEFAULTS)
        check_choice("sample", v["sample"], list(SAMPLES))
        check_choice("mode", v["mode"], list(MODES))
        check_choice("tip", v["tip"], list(TIPS))
        check_choice("pixels", v["pixels"], list(PIXELS))
        check_choice("on_change", v["on_change"], list(ON_CHANGE))
        layout = widgets.Layout(width=WIDTH)
        c = {"sample": widgets.Dropdown(options=list(SAMPLES), value=v["sample"],
                                        description="sample", layout=layout),
             "mode": widgets.Dropdown(options=list(MODES), value=v["mode"], description="mode",
                                      layout=layout),
             "tip": widgets.Dropdown(options=[(cls.title, key) for key, cls in TIPS.items()],
                                     value=v["tip"], description="tip", layout=layout)}
        for name, p in TIP_CONTROLS.items():
            c[name] = slider(name, p, v[name])
        c["pixels"] = widgets.Dropdown(options=list(PIXELS), value=v["pixels"],
                                       description="pixels per line", layout=layout)
        for name in SCAN_SLIDERS:
            p = _settings.PARAMETERS[name]
            c[name] = slider(name, p, v[name], high=max_scan_size(
                v["sample"], math.radians(v["angle"])) if name == "scan_size" else None)
        for sliders in MODE_SLIDERS.values():
            for name, p in sliders.items():
                c[name] = slider(name, p, v[name])
        c["on_change"] = widgets.ToggleButtons(options=list(ON_CHANGE), value=v["on_change"],
                                               description="slider during a scan",
                                               style={"description_width": "initial"})
        self.controls = c
        self.control = AcquisitionControls(
            start=self.start, pause=self.pause, resume=self.resume, stop=self.stop,
            show=self._show, report=self._report_error, live=lambda: running_as_notebook(),
            stop_label="Stop", unit="lines")
        self.progress = self.control.progress
        self.start_button = self.control.buttons["start"]
        self.pause_button = self.control.buttons["pause"]
        self.stop_button = self.control.buttons["stop"]
        self.pause_at = widgets.BoundedIntText(value=0, min=0, max=max(PIXELS), step=1,
                                               description="pause after line (0: never)",
                                               style={"description_width": "initial"})
        self.pause_at.observe(lambda ch: self._pause_after(), names="value")
        self.status = widgets.HTML()
        self.figure = None
        self.scene = None
        self._scene_key = None
        self.fig = self.new_figure(figsize=(10.0, 7.0))
        self.acquisition = None  # the scan (it holds the image)
        self._blank = None       # what is shown before any scan: the configured grid, all NaN
        self._config = None
        self._scanned = None  # the values the image shown was started with
        self._physics = None  # the values (but on_change) of self._config
        self.controls["tip"].observe(lambda ch: self._show_controls(), names="value")
        self.controls["mode"].observe(lambda ch: self._show_controls(), names="value")
        self._show_controls(v["tip"], v["mode"])
        # before the panel's own observers: a sample or angle moves the scan size's end first
        # (clamping its value), then the model runs once with both
        for name in ("sample", "angle"):
            self.controls[name].observe(lambda ch: self._fit_scan_size(), names="value")
        self._fit_scan_size()
        super().__init__(scene=scene, vis=vis)

    # -- controls ---------------------------------------------------------------------------
    def _show_controls(self, tip: str | None = None, mode: str | None = None) -> None:
        """Show only the chosen tip's and the chosen mode's sliders."""
        tip = self.controls["tip"].value if tip is None else tip
        mode = self.controls["mode"].value if mode is None else mode
        shown = {p.name for p in TIPS[tip].parameters} | set(MODE_SLIDERS[mode])
        hidden = set(TIP_CONTROLS) | {n for s in MODE_SLIDERS.values() for n in s}
        for name in hidden:
            self.controls[name].layout.display = None if name in shown else "none"

    def _fit_scan_size(self, sample_name: str | None = None, angle: float | None = None) -> None:
        """End the scan-size slider at :func:`max_scan_size` of the sample and angle (default:
        the controls'), in its display unit; a value beyond is clamped there by the slider."""
        c = self.controls["scan_size"]
        p = c.parameter
        sample_name = self.controls["sample"].value if sample_name is None else sample_name
        angle = self.controls["angle"].value if angle is None else angle
        hi = min(p.to_display(max_scan_size(sample_name, math.radians(angle))),
                 p.to_display(p.slider_high))
        e = math.log10(hi)
        while 10.0 ** e > hi:  # 10 ** log10(x) can pass x by an ulp: the scan would not fit
            e = math.nextafter(e, -math.inf)
        if e != c.max:
            c.max = e

    def set(self, **values) -> None:
        """Set control values as a user would (one update at the end).

        As :meth:`Panel.set`; a ``scan_size`` set with a ``sample`` or ``angle`` is checked
        against the range on that sample at that angle (the slider's end moves with them).
        """
        moves = {k: values[k] for k in ("sample", "angle") if k in values}
        if "scan_size" not in values or not moves:
            super().set(**values)
            return
        for name, v in moves.items():
            check_control_value(name, self.controls[name], v)
        before = {name: self.controls[name].value for name in moves}
        hold, self._hold = self._hold, True
        try:
            for name, v in moves.items():
                self.controls[name].value = v
            check_control_value("scan_size", self.controls["scan_size"], values["scan_size"])
        except Exception:
            for name, v in before.items():
                self.controls[name].value = v
            raise
        finally:
            self._hold = hold
        super().set(**values)

    # -- the callback -----------------------------------------------------------------------
    def _configure(self, values: dict) -> _Config:
        """Turn the values (checked, sliders in SI: the panel contract) into a sample, tip, mode
        and settings."""
        mode, key, pixels = values["mode"], values["tip"], values["pixels"]
        tip = make_tip(key, **{p.name: values[p.name] for p in TIPS[key].parameters})
        scan = {name: values[name] for name in SCAN_SLIDERS}
        scan["tilt"] = (scan.pop("tilt_x"), 0.0)
        knobs = {name: values[name] for name in MODE_SLIDERS[mode]}
        if mode == "constant force":
            loop = PRESETS[PLANT].loop.replace(kp=knobs["kp"], ki=knobs["ki"])
            model = _modes.ConstantForce(loop, setpoint=knobs["setpoint"])
        else:
            model = _modes.ConstantHeight(ContactSystem(tip=tip), z_np=knobs["z_np"],
                                          damage_force=knobs["damage_force"])
        top = max_scan_size(values["sample"], scan["angle"])
        if scan["scan_size"] > top * (1 + 1e-12):
            p = _settings.PARAMETERS["scan_size"]
            angle = _settings.PARAMETERS["angle"]
            raise ValueError(f"scan_size must be <= {p.to_display(top):.4g} {p.display_unit} on "
                             f"the sample {values['sample']!r} at angle "
                             f"{angle.to_display(values['angle']):g} {angle.display_unit} "
                             f"(it would leave the sample), got "
                             f"{p.to_display(values['scan_size']):g} {p.display_unit}")
        settings = _settings.ScanSettings(scan.pop("scan_size"), pixels=pixels, lines=pixels,
                                         **scan)
        s = sample(values["sample"])
        return _Config(s, tip, model, settings,
                       key=tuple(values[name] for name in RESTART))

    def update(self, sample, mode, tip, pixels, on_change, **sliders) -> None:
        """Apply the controls' values (units shown): prepare, restart or change the scan.

        Idle, the values are kept for the next Start (the image shown stays). During a scan,
        ``on_change="restart"`` (or a change of sample, mode, pixels, scan size or angle, which
        make another image) starts the scan again from the first line; ``"apply on next
        line"`` keeps the lines finished and scans the following ones with the new values.
        Nothing is scanned here: lines are scanned by :meth:`step`, one model run each.

        Parameters
        ----------
        sample : str
            A key of :data:`SAMPLES`.
        mode : str
            One of :data:`MODES`.
        tip : str
            A key of :data:`afmsmiler.contact.TIPS`.
        pixels : int
            Pixels per line (and lines), one of :data:`PIXELS`.
        on_change : str
            One of :data:`ON_CHANGE`.
        **sliders : float
            The sliders' values in the units shown: ``scan_size`` [nm], ``scan_speed``
            [um/s], ``angle`` [deg], ``noise`` [nm], ``kp``, ``ki`` [1/us], ``setpoint`` [nm],
            ``z_np`` [nm] and the tips' parameters (``radius`` [nm], angles [deg]).

        Raises
        ------
        TypeError, ValueError
            For an unknown or missing control, or a value outside its valid range, before any
            work.

        Notes
        -----
        "Apply on next line" builds a new :class:`~afmsmiler.imaging.scanner.Scan` with the new
        values and takes its lines from the next one on (the lines before are not scanned
        again). In constant force the loop of the new scan has run with the new values from the
        first line (:class:`~afmsmiler.imaging.scan_modes.ConstantForce` solves the whole image as
        one polygon in time), so the line after the change shows the settled loop, not the
        transient a real instrument shows right after its gains change.
        """
        expected = set(DEFAULTS) - {"sample", "mode", "tip", "pixels", "on_change"}
        if set(sliders) != expected:
            raise TypeError(f"update needs exactly the sliders {sorted(expected)}, got "
                            f"{sorted(sliders)}")
        values = dict(sliders, sample=sample, mode=mode, tip=tip, pixels=pixels,
                      on_change=on_change)
        physics = {k: v for k, v in values.items() if k != "on_change"}
        if self._config is not None and physics == self._physics:
            self._show()  # only the choice for later moves changed: the scan goes on as it was
            return
        config = self._configure(values)
        previous, self._config, self._physics = self._config, config, physics
        if self.running:
            restart = on_change == "restart" or previous is None or config.key != previous.key
            if not restart:
                try:  # from the next line on (after Resume if paused)
                    self.acquisition.apply(tip=config.tip, mode=config.mode,
                                           settings=config.settings)
                except SettingsRefused:
                    restart = True
            if restart:  # a new scan from the first line: it runs, paused no more
                self._begin(config)
                if running_as_notebook():
                    self._run_steps()
        elif self.figure is None or previous is None or config.key != previous.key:
            self._clear(config)
        self._show()

    # -- the scan ---------------------------------------------------------------------------
    @property
    def last(self) -> Snapshot:
        """The image so far: the acquisition's snapshot (immutable)."""
        if self.acquisition is not None:
            return self.acquisition.snapshot()
        return self._blank

    @last.setter
    def last(self, value) -> None:  # Panel.__init__ starts it at None
        self._blank = value

    def _clear(self, config: _Config) -> None:
        """No scan: the grid ``config`` describes, every channel all NaN."""
        mode, settings = config.mode, config.settings
        self.acquisition = None
        self.control.attach(None)
        self._blank = Snapshot.blank({c: mode.unit(c) for c in mode.channels}, settings.shape,
                                     settings.pixel_size, settings.pixel_size_y,
                                     main=mode.main_channel or mode.channels[0])

    def _begin(self, config: _Config) -> None:
        """A new scan from the first line (the image of the one before is let go)."""
        acquisition = ScanAcquisition(config.sample, config.tip, config.mode, config.settings)
        acquisition.pause_after = self.pause_at.value
        acquisition.start()
        self.acquisition = acquisition
        self.control.attach(acquisition)
        self._scanned = config

    def _pause_after(self) -> None:
        if self.acquisition is not None:
            self.acquisition.pause_after = self.pause_at.value

    def start(self, run: bool = True) -> None:
        """Start a scan from the first line with the controls' values.

        The values were configured when the controls last changed (:meth:`update`): Start
        configures only what changed since (nothing, after a slider move).

        Parameters
        ----------
        run : bool
            Run it: in a live notebook as an asyncio task on the kernel's loop (one line per
            step, the kernel responsive between lines); elsewhere (tests, nbval) to the end at
            once. With ``run=False`` the scan only starts: call :meth:`step` for each line.
        """
        self.stop(redraw=False)
        values = self.to_si(self.values())
        physics = {k: v for k, v in values.items() if k != "on_change"}
        if self._config is None or physics != self._physics:
            self._config, self._physics = self._configure(values), physics
        self._begin(self._config)
        self._show()
        if run:
            self._run_steps()

    def _run_steps(self) -> None:
        """Run the steps: as a task in a live notebook, else to the end (or the pause) at once."""
        self.control.run(frame_interval=self.FRAME_INTERVAL, max_line_wait=self.MAX_LINE_WAIT,
                         read_wait=0.0)

    def pause(self) -> None:
        """Pause the running scan after the line under way: its lines stay, nothing more is
        scanned until :meth:`resume` (sliders moved meanwhile apply as ``on_change`` says)."""
        if not self.running or self.paused:
            return
        self.acquisition.pause()
        self._show()

    def resume(self, run: bool = True) -> None:
        """Go on with the paused scan from the next line.

        Parameters
        ----------
        run : bool
            Run it as :meth:`start` does; with ``run=False`` call :meth:`step` for each line.
        """
        if not self.paused:
            return
        self.acquisition.resume()
        self._show()
        if run:
            self._run_steps()

    #: s between two pictures of a running scan in a live notebook. Every line drawn sent a
    #: 256 x 256 image pair (0.5 MB) 18 times a second, and a cell run during the scan waited
    #: 3.5 s for its answer behind them; the lines scanned meanwhile appear in the next picture.
    FRAME_INTERVAL = 0.1
    #: s: the longest a live scan waits per line. A live scan takes the instrument's own line
    #: time (trace and retrace at the scan speed, :attr:`ScanSettings.line_time`), so that a
    #: faster scan visibly runs faster; a slower scan than this waits this long (and is
    #: computed, not waited, beyond). To change something at a chosen line a student pauses
    #: there (:attr:`pause_at`, :meth:`pause`): 64 lines take only a few seconds.
    MAX_LINE_WAIT = 0.25

    def step(self, show: bool = True) -> bool:
        """Scan the next line (one model run) and redraw once.

        Parameters
        ----------
        show : bool
            Redraw (figure, progress, 3D view) after the line; the scan's last line (and a
            pause) is always shown. A live scan shows at most one picture per
            :attr:`FRAME_INTERVAL`.

        Returns
        -------
        bool
            True while lines remain and the scan goes on, False once it has ended (finished,
            stopped or crashed) or is paused (after the line :attr:`pause_at` names, or by
            :meth:`pause`; a paused scan scans nothing until :meth:`resume`).
        """
        return self.control.step(show=show) and not self.paused

    def stop(self, redraw: bool = True) -> None:
        """Stop the scan: the lines finished so far stay in the image.

        Parameters
        ----------
        redraw : bool
            Show the stopped image (one redraw).
        """
        if not self.running:
            return
        self.acquisition.abort()
        if redraw:
            self._show()

    # -- what is shown ----------------------------------------------------------------------
    def _show(self) -> None:
        """The image so far into the figure (one redraw), the progress bar and the status."""
        snap = self.last
        fault = snap.fault
        crash = fault is not None and not isinstance(fault, Exception)
        # an image on screen made with other values than the controls now show says so
        changed = (not snap.running and snap.lines_done > 0 and self._scanned is not None
                   and self._config is not self._scanned)
        status = ("settings changed: Start scans with them" if changed
                  else crash_note(fault) if crash else None)
        view = scan_view(snap, main=snap.main, status=status)
        self.draw(ImagingFigure, view)  # the figure's frame leaves first: its pixels wait for nothing else
        self._draw_scene(snap)
        self.control.refresh(snap)
        done = snap.lines_done
        state = (f"paused after line {done}: move a slider if you like, then Resume"
                 if snap.paused else "scanning" if snap.running
                 else "crashed" if crash else "failed" if fault is not None
                 else "stopped" if snap.stopped else
                 "done" if snap.state == "done" else "ready")
        self.status.value = f"<b>{state}</b>"

    def _draw_scene(self, snap: Snapshot) -> None:
        """The 3D view: the sample (rebuilt for another sample or tip), the finished lines of
        the height image in m, the tip where the last line ended (no physics here: the scan's
        own positions)."""
        if not self._want_scene:
            return
        config = self._config
        key = (id(config.sample), config.tip)
        if self.scene is None or key != self._scene_key:
            from ..scenes.imaging import ImagingScene
            self.scene = ImagingScene(config.sample, tip=config.tip, vis=self.scene_root())
            self._scene_key = key
        channel = snap.channels.get("height trace")  # constant force's image
        drawn = self.scene.image_lines or 0
        done = snap.lines_done
        if channel is not None and (done >= 2 or drawn >= 2):
            # one row (a scan restarted) removes the image's mesh, as show_image says
            rows = max(done, 1)
            heights = np.nan_to_num(channel.heights[:rows])
            self.scene.show_image(Sample(heights, channel.pixel_size, "height trace",
                                         channel.pixel_size_y), lines=snap.lines)
        scan = self.acquisition.scan if self.acquisition is not None else None
        if scan is not None and done > 0 and self.scene.tip is not None:
            row = done - 1  # the apex where the line ended: the retrace's first pixel
            x, y = scan.position(row, 0, "retrace")
            self.scene.move_tip(x, y, float(scan.plan.retrace[row, 0]))

    def widget(self) -> widgets.Widget:
        """Controls on the left (sample, tip, scan, mode), buttons and progress, the figure below.

        Returns
        -------
        ipywidgets.VBox
        """
        figure = super().widget().children[1]
        left = widgets.VBox([self.controls[n] for n in ("sample", "mode", "tip", *TIP_CONTROLS,
                                                        "pixels")])
        right = widgets.VBox([self.controls[n] for n in (*SCAN_SLIDERS,
                                                         *[n for s in MODE_SLIDERS.values()
                                                           for n in s])])
        run = widgets.VBox([self.controls["on_change"],
                            widgets.HBox([self.start_button, self.pause_button,
                                          self.stop_button]),
                            self.pause_at, self.progress, self.status])
        return widgets.VBox([widgets.HBox([left, right, run]), figure])

