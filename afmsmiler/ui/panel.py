"""The base of every widget panel, and the one panel contract.

A panel owns a dict of controls (ipywidgets; every slider made from a
:class:`~afmsmiler.parameters.Parameter` by the one factory, :func:`afmsmiler.ui.controls.control`),
a matplotlib figure and optionally a 3D view. The contract, kept here once for every panel:

* **Initial values** (keyword arguments of the constructor, in the units the controls show) pass
  :func:`initial_values` (an unknown name is refused, listing the valid ones) and :func:`slider`
  (a value off the slider is refused, never clamped), exactly as :meth:`Panel.set` refuses them.
* **Values reach** :meth:`Panel.update` **in SI, once.** A student's move (or :meth:`Panel.set`)
  gives display values; :meth:`Panel.to_si` converts each slider's value with :func:`to_si`
  (snapped to the slider's ends and the default, checked against the parameter's valid range),
  checks the drop-downs' choices, and refuses a missing or unknown name, all before any work.
  ``update`` itself is checked the same way when a test or a student calls it directly (SI values):
  it only runs the model (through :meth:`Panel.run_model`, which counts :attr:`Panel.model_runs`)
  and draws.
* ``scene=`` (draw a 3D view, default False) and ``vis=`` (draw into this meshcat visualizer
  instead; implies a scene) are handled by :meth:`Panel.__init__` for every panel.

The figure is never rasterised in the kernel: :meth:`Panel.redraw` sends its artists' data to the
browser, which draws them (:class:`~afmsmiler.plots.live.LiveFigure`, uPlot). Every panel is listed
once in :mod:`afmsmiler.ui.registry`, which the pages, the tests, the benchmarks and the README
iterate. Tests construct a panel, call :meth:`Panel.set` and check the figure data against the model.
"""
from __future__ import annotations

import asyncio
import collections
import contextlib
import functools
import html
import math
import os
import threading
import time
import traceback
from collections.abc import Mapping

import ipywidgets as widgets
from IPython.display import display
from matplotlib.figure import Figure

from ..parameters import Parameter
from ..validation import check_choice, check_finite, check_range

__all__ = ["Panel", "arrange", "check_control_value", "initial_values", "running_as_notebook",
           "setup_notebook", "show_static", "slider", "to_si"]


def running_as_notebook() -> bool:
    """True in a live notebook kernel; False under pytest/nbval (``AFMSMILER_TESTING`` or CI).

    Use it to shorten long animations and simulations under test, as in Tedrake's course notes.
    """
    if os.environ.get("AFMSMILER_TESTING") or os.environ.get("CI") or "PYTEST_CURRENT_TEST" in os.environ:
        return False
    try:
        from IPython import get_ipython
        shell = get_ipython()
    except ImportError:
        return False
    return shell is not None and type(shell).__name__ == "ZMQInteractiveShell" and \
        not os.environ.get("NBVAL")


#: Turns of the kernel's event loop without a new move before a deferred update runs (see
#: :meth:`Panel._settle`): ipykernel reads one queued message per turn or two (the shell channel's
#: thread hands them to the main thread's stream, which reads one per event and runs it as a task).
_QUIET_TURNS = 3
#: Seconds a deferred update waits at most for moves to stop (a steady stream of moves, a mouse
#: drag at 60 Hz on a loop slowed by a busy thread, must not starve the model).
_MAX_DEFER = 0.05
#: Seconds between looks at whether the page painted the panel's last frame, while a deferred
#: update waits for it (:meth:`Panel._settle`, :meth:`afmsmiler.plots.live.LiveFigure.busy`).
_PAINT_POLL = 0.002


def _live_loop():
    """The kernel's running event loop in a live notebook, else None (tests, nbval, scripts).

    A move is deferred to this loop so that moves already queued reach the panel first and the
    model runs once, for the latest; without one (tests, nbval: :func:`running_as_notebook` is
    False) every move updates at once, as before.
    """
    if not running_as_notebook():
        return None
    try:
        return asyncio.get_running_loop()
    except RuntimeError:
        return None


def setup_notebook() -> None:
    """First line of every notebook: static figures inline (PNG, kept by an export).

    The panels' live figures are drawn in the browser whatever the backend
    (:class:`~afmsmiler.plots.live.LiveFigure`); the notebooks' other figures are static
    matplotlib images, which an exported notebook and the book keep.
    """
    try:
        from IPython import get_ipython
        shell = get_ipython()
    except ImportError:
        return
    if shell is not None and type(shell).__name__ == "ZMQInteractiveShell":
        shell.run_line_magic("matplotlib", "inline")


def to_si(p: Parameter, display_value: float) -> float:
    """A control's value (display unit) in SI, checked against ``p``'s valid range.

    The conversion is :meth:`Parameter.to_si` (120 um -> 0.00012 m, the decimal shifted).
    A slider's end converted to SI can land one rounding error outside the range
    (20 mW -> 0.020000000000000004 W); such a value, within 1e-12 of a slider end, is that end.
    Anything else outside the valid range raises (nothing is clamped).

    Parameters
    ----------
    p : Parameter
        The quantity's description.
    display_value : float
        The value in ``p.display_unit``.

    Returns
    -------
    float
        The value in SI units.

    Raises
    ------
    ValueError
        Naming the parameter and its valid range, if the value is outside it or not finite.
    """
    x = p.to_si(check_finite(p.name, display_value, p.display_unit))
    # the default shown on a slider (1.31e-6 m * 1e9 = 1309.9999999999998 nm) comes back as
    # the default, not as 1.3099999999999997e-6 m
    if math.isclose(x, p.default, rel_tol=1e-14):
        x = p.default
    for end in (p.slider_low, p.slider_high):
        if math.isfinite(end) and abs(x - end) <= 1e-12 * abs(end):
            x = end
    return p.check(x)


def initial_values(initial: Mapping, defaults: Mapping) -> dict:
    """A panel's initial control values: ``defaults`` with ``initial`` over them.

    Parameters
    ----------
    initial : mapping
        The constructor's keyword arguments (units shown).
    defaults : mapping
        Every control's default (units shown); its keys are the valid names.

    Returns
    -------
    dict

    Raises
    ------
    TypeError
        For a name that is not a control, listing the valid ones.
    """
    unknown = set(initial) - set(defaults)
    if unknown:
        raise TypeError(f"unknown control(s) {sorted(unknown)}; valid: {sorted(defaults)}")
    return {**defaults, **initial}


def slider(name: str, p: Parameter, display_value: float, *, high: float | None = None):
    """The slider of control ``name`` for ``p``, its grid through ``display_value``.

    The value must lie on the slider (its ends in the units shown): a constructor refuses what
    :meth:`Panel.set` refuses, where the factory alone would clamp it silently.

    Parameters
    ----------
    name : str
        The control's name in the panel (named in errors).
    p : Parameter
        The quantity.
    display_value : float
        The initial value in ``p.display_unit``.
    high : float, optional
        A tighter upper end in SI (see :func:`~afmsmiler.ui.controls.control`).

    Returns
    -------
    ipywidgets.FloatSlider or ipywidgets.FloatLogSlider

    Raises
    ------
    ValueError
        If the value is not finite or lies off the slider, naming ``name`` and the slider's range.
    """
    from .controls import control
    upper = p.slider_high if high is None else min(p.slider_high, high)
    low, top = sorted((p.to_display(p.slider_low), p.to_display(upper)))
    tol = 1e-12 * max(abs(low), abs(top))
    value = check_finite(name, display_value, p.display_unit)
    check_range(name, value, low - tol, top + tol, p.display_unit)
    return control(p, to_si(p, value), high=high)


_MISSING = object()


def _decimal(value):
    """A finite float to 15 significant digits (the round-off of a grid or a conversion gone)."""
    if isinstance(value, float) and math.isfinite(value):
        return float(f"{value:.15g}")
    return value


def _same(value, last, control) -> bool:
    """Whether a control's ``value`` is ``last`` snapped to its grid (a browser echo, not a move).

    The browser snaps a value the kernel set to the nearest point ``min + n * step`` of the
    slider's grid and sends that back. The nearest grid point lies within half a step of the value
    the kernel set and every other one at least half a step away, so a change of less than half a
    step is the echo, never a student's move.
    """
    if value == last:
        return True
    if isinstance(value, bool) or not isinstance(value, (int, float)) \
            or isinstance(last, bool) or not isinstance(last, (int, float)):
        return False
    step = float(getattr(control, "step", 0.0) or 0.0)
    if isinstance(control, widgets.FloatLogSlider):  # the grid is in the exponent
        if value <= 0 or last <= 0:
            return False
        return abs(math.log(value / last, control.base)) < 0.5 * step * (1 - 1e-9)
    return abs(value - last) < 0.5 * step * (1 - 1e-9) or \
        abs(value - last) <= 1e-12 * max(abs(value), abs(last))


def check_control_value(name: str, control, value):
    """Raise ``ValueError`` naming ``name`` unless ``control`` can hold ``value`` unchanged.

    A slider would clamp an out-of-range value and a drop-down raise a traitlets error; here both
    say what is valid.

    Parameters
    ----------
    name : str
        The control's name in the panel.
    control : ipywidgets.Widget
        The control.
    value : object
        The value to set (in the units the control shows).

    Returns
    -------
    object
        ``value``.
    """
    if isinstance(control, (widgets.FloatSlider, widgets.FloatLogSlider, widgets.IntSlider)):
        if isinstance(control, widgets.FloatLogSlider):
            low, high = control.base ** control.min, control.base ** control.max
        else:
            low, high = control.min, control.max
        unit = getattr(getattr(control, "parameter", None), "display_unit", "")
        x = check_finite(name, value, unit)
        tol = 1e-12 * max(abs(low), abs(high))  # the slider's own ends, up to round-off
        if not low - tol <= x <= high + tol:
            raise ValueError(f"{name} must be in [{low:.6g}, {high:.6g}]"
                             f"{' ' + unit if unit else ''}, got {x:.6g}")
    elif isinstance(control, (widgets.Dropdown, widgets.ToggleButtons, widgets.RadioButtons)):
        options = [o[1] if isinstance(o, tuple) else o for o in control.options]
        check_choice(name, value, options)
    elif isinstance(control, (widgets.Checkbox, widgets.ToggleButton)) \
            and not isinstance(value, bool):
        raise TypeError(f"{name} must be True or False, got {value!r}")
    return value


class Panel:
    """Base class of a widget panel: the panel contract (see the module's docstring).

    A subclass either declares its sliders (:attr:`SLIDERS`, :attr:`DEFAULTS`) and calls
    :meth:`declared_controls`, or builds ``self.controls`` itself (sliders from :func:`slider`);
    it sets ``self.fig`` and calls ``super().__init__(scene=..., vis=...)``, and implements
    :meth:`update`, which takes every control's value by name, sliders in SI.
    """

    controls: dict
    fig: Figure | None = None
    #: The figure drawn in the browser (made at the first :meth:`redraw`).
    live = None
    _converted = False  # update's values come from to_si (checked there)
    #: The panel's sliders declared as parameters: control name -> Parameter.
    SLIDERS: Mapping = {}
    #: Every declared control's initial value, in the units shown.
    DEFAULTS: Mapping = {}

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        if "update" in cls.__dict__:  # every update is entered through the contract's check
            raw = cls.__dict__["update"]

            @functools.wraps(raw)
            def update(self, *args, **values):
                if args:
                    raise TypeError(f"{cls.__name__}.update takes the control values by name, "
                                    f"got {len(args)} positional argument(s)")
                if not self._converted:  # values from to_si were checked there, once
                    self._check_si(values)
                raw(self, **values)

            update._raw = raw
            cls.update = update

    def __init__(self, *, scene: bool = False, vis=None):
        if not isinstance(scene, bool):
            raise TypeError(f"scene must be True or False, got {scene!r}")
        self.model_runs = 0  # see run_model
        #: Seconds each of the last updates took in the kernel (:meth:`_run`; the benchmark's
        #: kernel step), newest last.
        self.update_seconds = collections.deque(maxlen=1000)
        #: The CPU seconds the kernel's thread spent in each of those updates
        #: (``time.thread_time``): below :attr:`update_seconds` by the time the thread waited,
        #: for a CPU that another process held or for another thread (the benchmark's split of
        #: a slow step into a slow model and a busy machine), newest last.
        self.update_cpu_seconds = collections.deque(maxlen=1000)
        #: Runs of :meth:`update` through the contract (:meth:`_run`).
        self.updates = 0
        #: Moves the browser sent (a slider's updates, as ipywidgets merges them); with
        #: :attr:`updates` it shows how many a drag's coalescing folded together.
        self.moves_received = 0
        self._moves = 0  # moves seen, for the coalescing (see _settle)
        self._deferred = False  # an update is waiting on the kernel's loop
        # the thread and loop the panel was made in (a cell: the kernel's main thread), where
        # every deferred update runs; None outside a live kernel
        loop = _live_loop()
        self._home = (threading.get_ident(), loop) if loop is not None else None
        self._vis = vis
        self._want_scene = scene or vis is not None
        self.last = None  # the last model result, for tests and exercises
        self.error = None  # the message of the last failed update from a control, else None
        self._error_box = widgets.HTML()
        self._applied = {}  # the values the model last ran with, by control name
        for control in self.controls.values():
            control.observe(self._on_change, names="value")
        self._tag_controls()
        self._run(self.values())

    def _tag_controls(self) -> None:
        """Give each control the CSS class ``afm-control-<name>`` (pages and tests find it)."""
        for name, control in self.controls.items():
            tag = f"afm-control-{name}"
            if tag not in control._dom_classes:
                control.add_class(tag)

    def declared_controls(self, initial: Mapping) -> dict:
        """The sliders of :attr:`SLIDERS` at :attr:`DEFAULTS` with ``initial`` over them.

        Parameters
        ----------
        initial : mapping
            The constructor's keyword arguments (units shown), checked by
            :func:`initial_values` and :func:`slider`.

        Returns
        -------
        dict
            Control name -> slider, in the order of :attr:`SLIDERS`.
        """
        values = initial_values(initial, self.DEFAULTS)
        return {name: slider(name, p, values[name]) for name, p in self.SLIDERS.items()}

    def run_model(self, model, *args, **kwargs):
        """Call ``model(*args, **kwargs)``, counting the run in :attr:`model_runs`.

        A panel runs its model through this once per user action that changes what the model
        computes (tests check the count), and never for a move that only changes the view.
        """
        self.model_runs += 1
        return model(*args, **kwargs)

    def draw(self, figure_class, *data, made_with: Mapping | None = None, **keywords) -> None:
        """Show a model result in the panel's figure and send it to the browser (one message).

        The first call makes :attr:`figure` as ``figure_class(*data, fig=self.fig, **made_with,
        **keywords)``; later calls update it in place with ``figure.update(*data, **keywords)``
        (no new figure, no layout). The figure builders (:mod:`afmsmiler.plots`) compute no
        physics.

        Parameters
        ----------
        figure_class : type
            A figure builder of :mod:`afmsmiler.plots` with ``update``.
        *data, **keywords
            The model results it draws.
        made_with : mapping, optional
            Keywords for the builder only (fixed for the panel's life, e.g. legend names).
        """
        if self.figure is None:
            self.figure = figure_class(*data, fig=self.fig, **(made_with or {}), **keywords)
        else:
            self.figure.update(*data, **keywords)
        self.redraw()

    #: The panel's figure builder (made by :meth:`draw`), or None before the first update.
    figure = None
    #: True while an update runs for moves the browser sent in a live kernel (deferred to its
    #: loop, :meth:`_settle`); False for the first update and values a cell sets, which a cell
    #: may read at once.
    in_drag = False

    # -- the contract's conversion ---------------------------------------------------------
    def _check_names(self, values: Mapping) -> None:
        if set(values) != set(self.controls):
            missing, unknown = set(self.controls) - set(values), set(values) - set(self.controls)
            raise TypeError(f"update needs exactly the controls {sorted(self.controls)}; "
                            + (f"missing {sorted(missing)}" if missing else "")
                            + ("; " if missing and unknown else "")
                            + (f"unknown {sorted(unknown)}" if unknown else ""))

    def to_si(self, values: Mapping) -> dict:
        """Every control's value (units shown) as :meth:`update` takes it: sliders in SI.

        Parameters
        ----------
        values : mapping
            Exactly the panel's controls, by name.

        Returns
        -------
        dict

        Raises
        ------
        TypeError
            For a missing or unknown control.
        ValueError
            For a value no control could hold, naming the control and what is valid.
        """
        self._check_names(values)
        out = {}
        for name, value in values.items():
            control = self.controls[name]
            p = getattr(control, "parameter", None)
            if p is not None:  # errors name the control (a transducer's input is a deflection)
                out[name] = to_si(p if p.name == name else p.with_(name=name), value)
            else:
                out[name] = check_control_value(name, control, value)
        return out

    def _check_si(self, values: Mapping) -> None:
        """Refuse, before any work, what :meth:`update` must not take (values in SI)."""
        self._check_names(values)
        for name, value in values.items():
            control = self.controls[name]
            p = getattr(control, "parameter", None)
            if p is not None:
                (p if p.name == name else p.with_(name=name)).check(
                    check_finite(name, value, p.unit))
            else:
                check_control_value(name, control, value)

    # -- values ---------------------------------------------------------------------------
    def values(self) -> dict:
        """Current control values (in the units the controls show).

        A slider whose value differs from the one the model last ran with by round-off only
        (the browser's echo of a value it snapped to the slider's grid) reports the value the
        model ran with: the browser never changes a value the student did not touch.
        """
        out = {}
        for name, c in self.controls.items():
            v, last = c.value, self._applied.get(name, _MISSING)
            out[name] = last if last is not _MISSING and _same(v, last, c) else v
        return out

    def _run(self, values: dict) -> None:
        """Run :meth:`update` once with ``values`` and remember them as applied.

        Numbers are taken to 15 significant digits, more than a slider or a typed value carries:
        a grid point the browser computes as ``min + n * step`` (29.999999999999996 for 30) and a
        unit conversion (50e-6 m * 1e6 = 49.99999999999999 um) are one unit in the last place off
        the decimal the student reads, and the model runs with the decimal.
        """
        values = {k: _decimal(v) for k, v in values.items()}
        si = self.to_si(values)
        start, start_cpu = time.perf_counter(), time.thread_time()
        with self._held_view():
            self._converted = True
            try:
                self.update(**si)
            finally:
                self._converted = False
                self.update_seconds.append(time.perf_counter() - start)
                self.update_cpu_seconds.append(time.thread_time() - start_cpu)
                self.updates += 1
        self._applied = dict(values)

    def set(self, **values) -> None:
        """Set control values as a user would (one update at the end).

        Raises
        ------
        TypeError
            For a name that is not a control.
        ValueError
            For a value outside a slider's range or not among a drop-down's options, naming the
            control, the value and what is valid (a slider would silently clamp it).
        """
        self.check_values(values)
        hold, self._hold = self._hold, True
        try:
            for name, v in values.items():
                self.controls[name].value = v
        finally:
            self._hold = hold
        if not hold:
            self._run({**self.values(), **values})

    _hold = False
    _syncing = False

    def sync_controls(self, values: Mapping) -> None:
        """Set controls to the values a choice implies (a preset's geometry), with no update of
        their own: the choice's own change runs the one update.

        The browser echoes each value snapped to its slider's grid, possibly before that update
        has run; :meth:`is_echo` knows such an echo for what it is.

        Parameters
        ----------
        values : mapping
            Control name -> value, in the units shown.
        """
        synced = self.__dict__.setdefault("_synced", {})
        hold, self._hold, self._syncing = self._hold, True, True
        try:
            for name, value in values.items():
                check_control_value(name, self.controls[name], value)  # never clamped
                self.controls[name].value = value
                # the last few: echoes of two syncs in a row (air, then water) may come late
                synced.setdefault(name, collections.deque(maxlen=4)).append(
                    self.controls[name].value)
        finally:
            self._hold, self._syncing = hold, False

    def choice_first(self, values: dict, choices, implied, custom: str) -> dict:
        """``values`` of :meth:`set` reordered so that a choice (a preset, its fluid) comes
        first: applied now, with no update, and, when values of the ``implied`` controls are
        given too, the ``"probe"`` choice made ``custom`` so that they start from what it implied.

        Parameters
        ----------
        values : dict
            Control names and values (units shown), checked; the choices are taken out of it.
        choices : sequence of str
            The choice controls (``"probe"`` first).
        implied : sequence of str
            The controls a chosen probe sets.
        custom : str
            The probe drop-down's entry for values typed on the controls.

        Returns
        -------
        dict
            The values for :meth:`Panel.set`, the choices first.
        """
        given = {n: values.pop(n) for n in choices if n in values}
        if given.get("probe", self.controls["probe"].value) != custom and \
                set(values) & set(implied):
            hold, self._hold = self._hold, True
            try:
                for name, value in given.items():   # what the choice implies, no update
                    self.controls[name].value = value
            finally:
                self._hold = hold
            given["probe"] = custom
        return {**given, **values}

    def is_echo(self, change) -> bool:
        """Whether a control's change is no student's move: made by :meth:`sync_controls`, or
        the browser's echo, snapped to the grid, of a value one of the last syncs or the model's
        last run set.

        Parameters
        ----------
        change : dict
            The traitlets change (``owner``, ``new``).

        Returns
        -------
        bool
        """
        if self._syncing:
            return True
        owner = change.get("owner")
        name = next((n for n, c in self.controls.items() if c is owner), None)
        held = [*self.__dict__.get("_synced", {}).get(name, ())]
        if name in self._applied:
            held.append(self._applied[name])
        return any(_same(change["new"], v, owner) for v in held)

    def check_values(self, values: Mapping) -> None:
        """Refuse control values (units shown) that no control could hold, naming them.

        Raises
        ------
        TypeError
            For a name that is not a control, listing the valid ones.
        ValueError
            For a value outside a slider's range or not among a drop-down's options.
        """
        unknown = set(values) - set(self.controls)
        if unknown:
            raise TypeError(f"unknown control(s) {sorted(unknown)}; valid: {sorted(self.controls)}")
        for name, v in values.items():
            check_control_value(name, self.controls[name], v)

    def sweep(self, name: str, values) -> None:
        """Move control ``name`` through ``values`` (one update each, an animation), then back.

        The control ends where the student left it: a sweep left at the slider's end made the
        student's next key press do nothing.

        Parameters
        ----------
        name : str
            A control.
        values : iterable
            The values to show in turn (in the units the control shows), each checked as by
            :meth:`set` before the sweep starts.
        """
        if name not in self.controls:
            raise TypeError(f"unknown control {name!r}; valid: {sorted(self.controls)}")
        values = list(values)
        for v in values:
            check_control_value(name, self.controls[name], v)
        start = self.values()[name]
        try:
            for v in values:
                self.set(**{name: v})
        finally:
            self.set(**{name: start})

    def _on_change(self, change) -> None:
        """A control moved: update, and show a failure in the panel instead of losing it.

        ipywidgets runs this callback outside any cell, so an exception raised here would only
        reach JupyterLab's log console while the panel silently stopped updating. In a live
        notebook the error is shown under the panel (:attr:`error`); elsewhere (tests) it is
        shown and raised again. A move from the browser is coalesced with the moves queued behind
        it (:meth:`_move`); a value a cell sets updates at once.
        """
        owner = change.get("owner") if isinstance(change, Mapping) else None
        if self._hold:
            return
        lock = getattr(owner, "_property_lock", None) or {}
        self._move(from_browser="value" in lock)

    def _move(self, *, from_browser: bool) -> None:
        """Update for the controls' current values: now, or once the queued moves are in.

        A move from the browser in a live kernel is deferred to the kernel's event loop
        (:meth:`_settle`): the moves of a drag that queued while the model ran are applied to the
        controls first, and the model runs once, for the newest values (never for each value the
        student passed over, so a slow panel's last frame comes one model run after the last
        key, not one per key). Anywhere else (tests, nbval, a cell setting a value) it updates at
        once. No value is changed: the model runs for exactly the values the controls hold, and
        the value the student stops at is always the last one run.
        """
        loop = _live_loop() if from_browser else None
        if loop is not None and self._home is not None and \
                self._home[0] != threading.get_ident():
            # JupyterLab sends a widget's own updates on a kernel subshell, handled in a thread
            # of its own while the main thread may be running this panel's model: the move is
            # handed to the panel's home loop, so that its updates never run at once
            self._home[1].call_soon_threadsafe(functools.partial(self._move,
                                                                 from_browser=True))
            return
        if from_browser:
            self.moves_received += 1
        self._moves += 1
        if loop is None:
            self._flush()
        elif not self._deferred:
            self._deferred = True
            loop.call_soon(self._settle, loop, self._moves, 0, loop.time() + _MAX_DEFER)

    def _settle(self, loop, seen: int, quiet: int, until: float) -> None:
        """Run the deferred update once :data:`_QUIET_TURNS` turns of the loop brought no move.

        ipykernel handles queued messages one at a time, a turn or two of its loop each, so an
        update run at the first turn would see only the first of the moves that queued behind
        the last model run; waiting for a few quiet turns (microseconds when nothing is queued)
        lets every queued move land first. Moves that keep coming run it after
        :data:`_MAX_DEFER` s anyway. While the page has more frames of the panel to paint than
        :data:`~afmsmiler.plots.live.FRAMES_AHEAD` (:meth:`~afmsmiler.plots.live.LiveFigure.busy`,
        at most :data:`~afmsmiler.plots.live.PAINT_WAIT` s after the last was sent) the update
        waits too, and the moves made meanwhile fold into it: a page slower than the model gets
        the newest frame, not a queue of steps already passed.
        """
        if (self._moves != seen or quiet < _QUIET_TURNS) and loop.time() < until:
            quiet = 0 if self._moves != seen else quiet + 1
            loop.call_soon(self._settle, loop, self._moves, quiet, until)
            return
        if self.live is not None and self.live.busy(loop.time()):
            # the page has two frames to paint: the moves that come meanwhile fold into this
            # update (bounded: see LiveFigure.busy)
            loop.call_later(_PAINT_POLL, self._settle, loop, self._moves, _QUIET_TURNS, until)
            return
        self._deferred = False
        self.in_drag = True  # a move from the browser (see in_drag)
        try:
            self._flush()  # a failure is shown under the panel (_apply, live)
        finally:
            self.in_drag = False

    #: The newest view update waiting for the page to paint its figure's frame
    #: (:meth:`after_frame`), else None.
    _after = None

    def after_frame(self, show) -> None:
        """Run ``show()``, a view's update the figure's frame need not wait for (a 3D view's
        animation), once the page painted the frame this update sent.

        In a live kernel, for a move from the browser (:attr:`in_drag`), with a page that says
        what it painted: the figure's frame reaches the page while the kernel is idle, and the
        3D view (which renders only once the figure painted, ``scene_view.js``) gets its
        commands then (a whole :data:`~afmsmiler.plots.live.PAINT_WAIT` at most after the frame
        was sent). A newer update's ``show`` replaces one still waiting, so the view shows the
        newest values. Anywhere else (the first update, a cell, tests, nbval) it runs at once. A
        failure is shown under the panel, as an update's.
        """
        self._after = None
        loop = _live_loop() if self.in_drag else None
        live = self.live
        if loop is None or live is None or live.frames_painted == 0:
            show()
            return
        from ..plots.live import PAINT_WAIT
        self._after = show
        seq, until = live.frames_sent, loop.time() + PAINT_WAIT

        def poll():
            if self._after is not show:  # a newer update brought its own
                return
            if live.frames_painted < seq and loop.time() < until:
                loop.call_later(_PAINT_POLL, poll)
                return
            self._after = None
            try:
                with self._held_view():
                    show()
            except Exception as exc:  # shown, not lost in the kernel's log
                self._report_error(exc)
        loop.call_soon(poll)

    def _held_view(self):
        """The panel's 3D view held (:meth:`~afmsmiler.scenes.SceneView.hold`): the commands
        of one update, or of one deferred animation (:meth:`after_frame`), leave as one message
        and its legend as one more (one repaint of the view, one message less for the page per
        scene call); a null context without a view."""
        view = self._view
        return view.hold() if view is not None else contextlib.nullcontext()

    def _flush(self) -> None:
        values = self.values()
        if values == self._applied:  # a browser echo of what the model already shows
            return
        self._apply(values)

    def _apply(self, values: dict) -> None:
        try:
            self._run(values)
        except Exception as exc:
            self._report_error(exc)
            if not running_as_notebook():
                raise
        else:
            if self.error is not None:
                self.error = None
                self._error_box.value = ""

    def _report_error(self, exc: Exception) -> None:
        self.error = f"{type(exc).__name__}: {exc}"
        tb = "".join(traceback.format_exception(exc)[-6:])
        self._error_box.value = (
            "<div style='color:#b00020'><b>The panel could not update</b> "
            f"({html.escape(self.error)})<pre style='font-size:11px'>{html.escape(tb)}</pre>"
            "</div>")

    # -- the callback ---------------------------------------------------------------------
    def update(self, **values) -> None:  # pragma: no cover - abstract
        """Run the model once for these control values (sliders in SI) and draw the result."""
        raise NotImplementedError

    # -- the 3D view ----------------------------------------------------------------------
    #: The panel's scene builder (an object of :mod:`afmsmiler.scenes`), or None without one.
    scene = None
    #: A visualizer given to the panel to draw in instead of its own view (tests: a recorder).
    _vis = None
    _view = None

    def scene_root(self):
        """Where the panel's scenes draw: the ``vis`` it was given, or its own 3D view's root.

        The panel makes one :class:`~afmsmiler.scenes.SceneView` on first use and every scene it
        builds later (another instrument, sample or principle) draws into that same view, so the
        view the notebook shows is always the one the panel updates.
        """
        if self._vis is not None:
            return self._vis
        if self._view is None:
            from ..scenes.view import SceneView
            self._view = SceneView()
        return self._view.vis

    def scene_view(self):
        """The widget of the panel's 3D view, or None when the panel draws no scene.

        The view carries meshcat's commands over the kernel's own connection: it lives as long
        as the panel and its kernel, and nothing needs closing.
        """
        if self.scene is None:
            return None
        from ..scenes.view import view_of
        return view_of(self.scene.root)

    # -- display --------------------------------------------------------------------------
    @staticmethod
    def new_figure(**kwargs) -> Figure:
        """A figure for a panel: a pyplot-free Figure, drawn in the browser by :meth:`redraw`.

        It is not pyplot's current figure: made with ``plt.figure`` it was, so a student's next
        ``plt.plot(...)`` drew into the panel's axes, and every re-run of a panel cell added a
        figure to pyplot's list (warning after 20).
        """
        return Figure(**kwargs)

    def redraw(self) -> None:
        """Send the figure's current artists to the browser (one message; nothing rasterised).

        The first call makes :attr:`live`; a view of it shows every later frame, including those
        sent before the browser displayed it.
        """
        if self.fig is None:
            return
        from ..plots.live import LiveFigure
        if self.live is None:
            self.live = LiveFigure(self.fig)
        else:
            self.live.sync()
        self._tag_controls()

    def widget(self) -> widgets.Widget:
        """The panel as one widget: controls on the left, the figure on the right."""
        box = widgets.VBox(list(self.controls.values()))
        children = [box] if self.live is None else [box, self.live]
        return arrange(widgets.HBox(children))

    def show(self) -> None:
        """Display the panel (call as the last line of a notebook cell).

        The panel is laid out with :func:`arrange` (controls keep their width; the figure moves
        below them when the notebook is too narrow for both), with a line under it where a
        failed update is reported and, below, the panel's 3D view (:meth:`scene_view`); then
        :func:`show_static` adds the figure's static copy.
        """
        children = [arrange(self.widget()), self._error_box]
        view = self.scene_view()
        if view is not None:
            children.append(view)
        box = self._shown = widgets.VBox(children)
        box.add_class(f"afm-panel-{type(self).__name__}")  # see registry.PanelEntry.selector
        box.add_class("afm-panel")  # not painted while out of view (plots/static/live.css)
        display(box)
        if self.fig is not None and self.fig.axes:
            show_static(self.fig)


def show_static(fig) -> None:
    """Display ``fig``'s static copy, for the pages where no widget manager draws its live one.

    An exported notebook (nbconvert, the book) or a saved one opened without a kernel cannot draw
    a widget, and an export that stored the widgets' state draws them only with the network. The
    copy is the same renderer with the frame embedded (:func:`afmsmiler.plots.live.static_html`);
    where the live figure is drawn beside it (JupyterLab, voila), the copy hides itself.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        A figure drawn live beside this output.
    """
    from ..plots.live import static_html
    display({"text/html": static_html(fig),
             "text/plain": "(the figure above, drawn without a kernel)"}, raw=True)


def arrange(box: widgets.Widget) -> widgets.Widget:
    """Lay out a panel's boxes so that nothing is squeezed or clipped; return ``box``.

    In a row (HBox) every child keeps its natural width (CSS ``flex: 0 0 auto``) and the row
    wraps: when the notebook is narrower than controls + figure, the figure moves below the
    controls instead of squeezing them into a clipped, scrolling strip (which is what a flex row
    does by default next to a fixed-size ipympl canvas). In a column (VBox) the sliders and
    drop-downs get one label width, so their tracks start and end at the same place whatever
    their labels' lengths. Nested boxes are arranged too.

    Parameters
    ----------
    box : ipywidgets.Widget
        The panel's widget (usually from :meth:`Panel.widget`); other widgets pass unchanged.

    Returns
    -------
    ipywidgets.Widget
        ``box`` itself, its layout changed in place.
    """
    if isinstance(box, widgets.Box):
        if isinstance(box, widgets.VBox):
            _align_labels(box.children)
            if not getattr(box, "_labels_aligned", False):  # controls swapped in later, too
                box.observe(lambda change: _align_labels(change["new"]), names="children")
                box._labels_aligned = True
        if isinstance(box, widgets.HBox):
            box.layout.flex_flow = "row wrap"
            box.layout.align_items = "flex-start"
            for child in box.children:
                if isinstance(child, widgets.DOMWidget):
                    child.layout.flex = "0 0 auto"
        for child in box.children:
            arrange(child)
    return box


#: Label widths are estimated (the kernel cannot measure text): px per character of JupyterLab's
#: 13 px widget font, with margin; the track and readout of a slider keep this much room.
_LABEL_PX_PER_CHAR, _TRACK_PX = 7.5, 300


def _align_labels(children) -> None:
    """Give the sliders and drop-downs in one column a common label width (in place)."""
    aligned = [c for c in children if isinstance(c, (widgets.FloatSlider, widgets.FloatLogSlider,
                                                     widgets.IntSlider, widgets.Dropdown))
               and c.description]
    if len(aligned) < 2:
        return
    label = int(max(len(c.description) for c in aligned) * _LABEL_PX_PER_CHAR) + 8
    for c in aligned:
        c.style.description_width = f"{label}px"
        c.layout.width = f"{label + _TRACK_PX}px"
