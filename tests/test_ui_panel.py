"""The panel base class as a student meets it in JupyterLab, checked without a browser.

Each test here stands for a problem seen in a real JupyterLab (headless Chromium): a failing update
from a slider that only reached the log console while the panel froze, controls squeezed into a
clipped strip next to the figure, a panel figure that was pyplot's current one, and a figure
that only an Agg redraw could update (now it is sent to the browser as data, one message a move).
"""
import time

import ipywidgets as widgets
import matplotlib.pyplot as plt
import numpy as np
import pytest

import afmsmiler.ui.panel as panel_module
from afmsmiler.parameters import Parameter
from afmsmiler.ui.controls import control
from afmsmiler.ui.panel import Panel, arrange


def slider(label, value, low, high, unit=""):
    """A slider from the one factory, for a quantity shown in ``unit`` (SI = display here)."""
    si = {"": "", "m": "m", "um": "m", "mm": "m", "mW": "W"}[unit]
    p = Parameter(name="x", unit=si, display_unit=unit or None, default=value,
                  low=low, high=high, label=label)
    scale = p.scale
    p = p.with_(default=value / scale, low=low / scale, high=high / scale,
                slider_low=low / scale, slider_high=high / scale)
    return control(p)


class Square(Panel):
    """A minimal panel: y = x^2, refusing x < 0 as a model would."""

    def __init__(self, low=-1.0):
        self.controls = dict(x=slider("x", 1.0, low, 2.0, unit="m"))
        self.fig = self.new_figure(figsize=(2.0, 1.5))
        self.ax = self.fig.add_subplot()
        (self.line,) = self.ax.plot([0.0], [0.0])
        super().__init__()

    def update(self, x):
        if x < 0:
            raise ValueError(f"x must be >= 0 m, got {x}")
        self.line.set_data([x], [x * x])
        self.last = x * x
        self.redraw()


def test_a_failing_slider_update_is_shown_in_the_panel_and_raised_under_test():
    p = Square()
    with pytest.raises(ValueError, match="x must be >= 0 m, got -0.5"):
        p.controls["x"].value = -0.5  # as a user would move it
    assert p.error == "ValueError: x must be >= 0 m, got -0.5"
    assert "could not update" in p._error_box.value and "got -0.5" in p._error_box.value
    assert p.last == 1.0  # the last good result is kept
    p.controls["x"].value = 1.5
    assert p.error is None and p._error_box.value == "" and p.last == 2.25


def test_in_a_live_notebook_the_failure_is_shown_not_lost(monkeypatch):
    # ipywidgets calls observers outside any cell: an exception raised there only reaches
    # JupyterLab's log console, so the panel must show it itself and keep working.
    monkeypatch.setattr(panel_module, "running_as_notebook", lambda: True)
    p = Square()
    p.controls["x"].value = -0.25  # no exception escapes to ipywidgets
    assert p.error == "ValueError: x must be >= 0 m, got -0.25"
    assert "x must be &gt;= 0 m, got -0.25" in p._error_box.value  # escaped for HTML
    p.controls["x"].value = 0.5
    assert p.error is None and p.line.get_ydata()[0] == 0.25


def test_set_still_raises_for_tests_and_exercises():
    p = Square()
    with pytest.raises(ValueError, match="got -1"):
        p.set(x=-1.0)


def test_arrange_keeps_controls_unsqueezed_and_wraps_the_figure():
    left = widgets.VBox([slider("a", 1.0, 0.0, 2.0), widgets.HBox([widgets.HTML("k"),
                                                                    widgets.HTML("f")])])
    right = widgets.Output()
    box = arrange(widgets.HBox([left, right]))
    assert box.layout.flex_flow == "row wrap" and box.layout.align_items == "flex-start"
    assert left.layout.flex == "0 0 auto" and right.layout.flex == "0 0 auto"
    inner = left.children[1]
    assert inner.layout.flex_flow == "row wrap"
    assert all(c.layout.flex == "0 0 auto" for c in inner.children)
    assert left.layout.flex_flow is None  # a column stays a column
    assert arrange(right) is right  # a non-box passes through


def test_show_displays_the_arranged_panel_and_a_static_copy_of_its_figure(monkeypatch):
    shown = []
    monkeypatch.setattr(panel_module, "display",
                        lambda *objs, **kw: shown.extend((o, kw) for o in objs))
    p = Square()
    assert shown == []  # building and updating a panel displays nothing
    p.show()
    (outer, kw), (copy, kw_copy) = shown
    assert isinstance(outer, widgets.VBox) and kw == {}
    body, errors = outer.children
    assert errors is p._error_box
    assert body.layout.flex_flow == "row wrap"
    assert body.children[0].layout.flex == "0 0 auto"
    assert body.children[1] is p.live  # the figure drawn in the browser
    # an export without a widget manager shows the same figure, drawn by the same renderer
    assert kw_copy == {"raw": True} and set(copy) == {"text/html", "text/plain"}
    html = copy["text/html"]
    assert "afm-live-static" in html and "drawStatic(" in html and "<script" in html


def test_a_slider_move_sends_one_frame_and_never_rasterises(monkeypatch):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    p = Square()
    drawn, messages = [], []
    monkeypatch.setattr(FigureCanvasAgg, "draw", lambda self: drawn.append(self))
    monkeypatch.setattr(p.live, "send_state", lambda key=None: messages.append(set(key or ())))
    sent = p.live.frames_sent
    p.controls["x"].value = 1.5
    assert p.live.frames_sent == sent + 1 and drawn == []
    # hold_sync gathers the frame's traits into one message
    assert len(messages) == 1 and {"_frame", "_buffer"} <= set(messages[0])
    d = p.live.sync()
    x, y = (d.values(d.frame["axes"][0]["series"][0][k]) for k in ("x", "y"))
    assert x[0] == pytest.approx(1.5) and y[0] == pytest.approx(2.25)


def test_show_puts_the_3d_view_below_the_panel(monkeypatch):
    from types import SimpleNamespace

    from afmsmiler.scenes import SceneView
    shown = []
    monkeypatch.setattr("afmsmiler.ui.panel.display", lambda *a, **k: shown.append(a[0]))
    monkeypatch.setattr("afmsmiler.ui.panel.show_static", lambda fig: None)
    p = Square()
    assert p.scene_view() is None
    p.show()
    assert not any(isinstance(c, SceneView) for c in shown[0].children)
    view = SceneView()
    p.scene = SimpleNamespace(root=view.vis)
    assert p.scene_view() is view
    p.show()
    assert shown[-1].children[-1] is view


def test_a_column_of_controls_shares_one_label_width():
    # with each label as wide as its text, the tracks began and ended at different places
    short = slider("h", 1.0, 0.0, 2.0, unit="um")
    long = slider("optical path D (lever to detector)", 1.0, 0.0, 2.0, unit="mm")
    menu = widgets.Dropdown(options=["a", "b"], description="material")
    lone = widgets.HTML("readout")
    arrange(widgets.VBox([short, long, menu, lone]))
    widths = {c.style.description_width for c in (short, long, menu)}
    assert len(widths) == 1
    label_px = int(widths.pop().removesuffix("px"))
    assert label_px >= 7 * len(long.description)  # room for the longest label
    assert short.layout.width == long.layout.width == menu.layout.width
    assert int(short.layout.width.removesuffix("px")) > label_px + 200  # and for the track


def test_controls_swapped_into_an_arranged_column_are_aligned_too():
    # the transducer panel replaces its sliders when the principle changes
    column = widgets.VBox([slider("a", 1.0, 0.0, 2.0), slider("b", 1.0, 0.0, 2.0)])
    arrange(column)
    arrange(column)  # arranging twice registers one observer
    new = [slider("laser power on the detector", 1.0, 0.0, 2.0, unit="mW"),
           slider("Q", 1.0, 0.0, 2.0)]
    column.children = new
    assert new[0].style.description_width == new[1].style.description_width != "initial"
    assert len(column._trait_notifiers["children"]["change"]) == 1


def test_panel_figure_stays_out_of_pyplot():
    # made with plt.figure, the panel's figure was pyplot's current one: a student's next
    # plt.plot(...) drew into the panel, and each re-run of the panel cell added a figure
    before = plt.get_fignums()
    panels = [Square() for _ in range(3)]
    assert plt.get_fignums() == before
    fig, ax = plt.subplots()
    assert plt.gcf() is fig and all(p.fig is not fig for p in panels)
    plt.close(fig)
    p = panels[0]
    p.controls["x"].value = 1.5  # still updates in place
    assert p.line.get_ydata()[0] == 2.25


class Lever(Panel):
    """A panel over two controls built by the slider factory, counting its updates."""

    def __init__(self):
        from afmsmiler.parameters import Parameter
        from afmsmiler.ui.controls import control
        length = Parameter(name="length", unit="m", display_unit="um", default=225e-6,
                           low=20e-6, high=1e-3)
        q = Parameter(name="quality_factor", unit="", default=150.0, low=0.5, high=1e5, log=True)
        self.controls = dict(length=control(length), quality_factor=control(q),
                             shape=widgets.Dropdown(options=["a", "b"], value="a"))
        self.calls = []
        super().__init__()

    def update(self, length, quality_factor, shape):
        # update takes SI (the panel contract); recorded as the slider shows it (um)
        shown = self.controls["length"].parameter.to_display(length)
        self.calls.append((float(f"{shown:.12g}"), quality_factor, shape))


def test_the_browser_echo_of_a_snapped_value_changes_nothing():
    # The browser snaps a value the kernel set to the slider's grid and sends it back: 225 um on
    # a grid of 2.45 um from 20 um came back as 225.8 um and the model ran with it. Less than half
    # a step away, it is taken as the echo: no update, and values() keeps what the model ran with.
    p = Lever()
    assert p.calls == [(225.0, 150.0, "a")]
    length, q = p.controls["length"], p.controls["quality_factor"]
    length.value = 225.0 + 0.4 * length.step          # the echo of a value off the grid
    q.value = 150.0 * 10 ** (0.4 * q.step)              # the same on a log slider
    assert len(p.calls) == 1 and p.values()["length"] == 225.0
    assert p.values()["quality_factor"] == 150.0
    length.value = 225.0 + length.step                  # a student's move: one step
    assert p.calls[-1][0] == pytest.approx(225.0 + length.step)
    q.value = 150.0 * 10 ** q.step
    assert p.calls[-1][1] == pytest.approx(150.0 * 10 ** q.step) and len(p.calls) == 3


def test_set_rejects_what_a_control_cannot_hold_instead_of_clamping_it():
    p = Lever()
    with pytest.raises(ValueError, match=r"length must be in \[20, 1000\] um, got 1e\+300"):
        p.set(length=1e300)
    with pytest.raises(ValueError, match=r"quality_factor must be in \[0.50\d*, 9\d+\.?\d*\], got 0.1"):
        p.set(quality_factor=0.1)
    with pytest.raises(ValueError, match=r"shape must be one of \['a', 'b'\], got 'cube'"):
        p.set(shape="cube")
    with pytest.raises(ValueError, match="length must be a real number"):
        p.set(length="long")
    assert len(p.calls) == 1 and p.values() == {"length": 225.0, "quality_factor": 150.0,
                                                 "shape": "a"}
    p.set(length=300.0, shape="b")  # two values, one update, exactly the values given
    assert p.calls[-1] == (300.0, 150.0, "b") and len(p.calls) == 2


def _browser(p, name, value):
    """A move of control ``name`` from the browser, applied as ipywidgets applies a slider's
    update (under its property lock: the panel knows it comes from the page)."""
    p.controls[name].set_state({"value": value})


def test_each_update_from_the_browser_runs_the_model_once():
    # ipywidgets sends one update of a slider at a time and merges the moves made meanwhile;
    # outside a live kernel (tests, nbval) each update that reaches the panel runs the model
    p = Lever()
    length = p.controls["length"]
    steps = [225.0 + k * length.step for k in range(1, 6)]
    for v in steps:
        _browser(p, "length", v)
    assert [c[0] for c in p.calls[1:]] == pytest.approx(steps)
    assert p.moves_received == 5 and p.updates == 6
    _browser(p, "length", steps[-1])  # an update that changes nothing: no model run
    assert len(p.calls) == 6


def test_a_sweep_shows_each_value_and_leaves_the_control_where_it_was():
    p = Lever()
    start = p.values()["length"]
    p.sweep("length", [100.0, 200.0, 300.0])
    assert [c[0] for c in p.calls[1:]] == [100.0, 200.0, 300.0, start]
    assert p.values()["length"] == start
    with pytest.raises(ValueError, match="length must be in"):
        p.sweep("length", [100.0, 1e9])  # checked before any update
    assert len(p.calls) == 5
    with pytest.raises(TypeError, match="unknown control"):
        p.sweep("width", [1.0])


class _Loop:
    """A stand-in for the kernel's event loop: callbacks run when the test turns it."""

    def __init__(self):
        self.ready = []
        self.later = []  # (when, callback, args)
        self.now = 0.0  # its clock stands still unless a test moves it

    def time(self):
        return self.now

    def call_soon(self, callback, *args):
        self.ready.append((callback, args))

    call_soon_threadsafe = call_soon  # list.append is atomic

    def call_later(self, delay, callback, *args):
        self.later.append((self.now + delay, callback, args))

    def turn(self):
        due = [c for c in self.later if c[0] <= self.now]
        self.later = [c for c in self.later if c[0] > self.now]
        ready, self.ready = self.ready + [(c, a) for _, c, a in due], []
        for callback, args in ready:
            callback(*args)

    def run(self, turns=100):
        for _ in range(turns):
            if not self.ready and not any(when <= self.now for when, _, _ in self.later):
                return
            self.turn()
        raise AssertionError("the loop never went quiet")


def _lever_with_figure():
    from matplotlib.figure import Figure
    from afmsmiler.plots.live import LiveFigure
    p = Lever()
    fig = Figure()
    fig.add_subplot().plot([0, 1], [0, 1])
    return p, LiveFigure(fig)


def test_a_drag_queued_while_the_kernel_was_busy_runs_the_model_once_for_its_last_step(
        monkeypatch):
    # issue 24: newer moves replace queued ones; the model runs for the latest value, never for
    # every value passed over, and the value the student stops at is the one it ran for
    loop = _Loop()
    monkeypatch.setattr(panel_module, "_live_loop", lambda: loop)
    p, live = _lever_with_figure()
    length = p.controls["length"]
    steps = [225.0 + k * length.step for k in range(1, 16)]
    for v in steps[:5]:  # queued behind a model run: they arrive one loop turn after the other
        _browser(p, "length", v)
        loop.turn()
    for v in steps[5:]:
        _browser(p, "length", v)
    assert len(p.calls) == 1  # nothing ran while moves kept coming
    loop.run()
    assert [c[0] for c in p.calls[1:]] == [steps[-1]]
    assert p.moves_received == 15 and p.values()["length"] == steps[-1]
    assert len(p.update_seconds) == 2
    # both sliders moved by the browser before the loop turns: one run, for both
    _browser(p, "quality_factor", 200.0)
    _browser(p, "length", steps[0])
    loop.run()
    assert p.calls[-1][:2] == (steps[0], 200.0) and len(p.calls) == 3


def _drawing_lever(loop):
    """A lever whose every update sends a frame of its live figure (sent at the test
    loop's clock), as a panel's figure does."""
    p, live = _lever_with_figure()
    p.live = live
    line = live.figure.axes[0].lines[0]
    update = p.update

    def drawn(**values):
        update(**values)
        line.set_ydata([0.0, values["length"]])
        live.sync()
        live._sent_at = loop.now
    p.update = drawn
    return p, live


def test_a_drag_computes_one_frame_ahead_of_the_page_and_no_more(monkeypatch):
    # issue 24: a page slower than the model (a saturated main thread paints a frame in 20-40
    # ms) got every frame the kernel computed, queued, and showed the last 0.3-0.5 s after the
    # last key; so the next update waits while the page has more than FRAMES_AHEAD (one) frame to
    # paint, and the moves made meanwhile fold into it. One frame may be in flight: waiting for
    # every paint put a round trip between the last key's move and its frame (bench_browser,
    # interleaved in one session: a drag's last frame 112-170 ms after the last key, 77-109 ms
    # one frame ahead)
    from afmsmiler.plots.live import FRAMES_AHEAD, PAINT_WAIT
    assert FRAMES_AHEAD == 1
    loop = _Loop()
    monkeypatch.setattr(panel_module, "_live_loop", lambda: loop)
    p, live = _drawing_lever(loop)
    step = p.controls["length"].step
    assert not live.busy(loop.now)  # no page has said anything: nothing is ever waited for
    live._handle_message(live, {"painted": live.frames_sent}, [])  # the page painted the first
    _browser(p, "length", 225.0 + step)
    loop.run()
    assert [c[0] for c in p.calls[1:]] == [225.0 + step]  # sent at once: nothing in flight
    assert not live.busy(loop.now)  # one frame in flight: the next is computed meanwhile
    _browser(p, "length", 225.0 + 2 * step)
    loop.run()
    assert [c[0] for c in p.calls[2:]] == [225.0 + 2 * step]
    sent = live.frames_sent
    assert live.busy(loop.now)  # two frames unpainted: no third
    for k in range(3, 9):  # the student keeps going while the page paints
        _browser(p, "length", 225.0 + k * step)
        loop.turn()
    for _ in range(20):
        loop.now += 0.002
        loop.turn()
    assert len(p.calls) == 3 and live.frames_sent == sent  # waiting for a paint
    live._handle_message(live, {"painted": sent - 1}, [])  # the older of the two painted
    loop.now += 0.002
    loop.run()
    assert [c[0] for c in p.calls[3:]] == [225.0 + 8 * step]  # once, for the newest step
    # a page that never answers (closed, hidden) costs at most PAINT_WAIT
    _browser(p, "length", 225.0 + 9 * step)
    start = loop.now
    while len(p.calls) == 4:
        loop.now += 0.002
        loop.turn()
        assert loop.now - start < PAINT_WAIT + 0.01
    assert p.calls[-1][0] == 225.0 + 9 * step
    assert loop.now - start >= PAINT_WAIT - 0.003


def test_a_view_waits_for_the_figure_s_paint_during_a_drag_and_the_newest_wins(monkeypatch):
    # issue 24: a 3D view's animation (3-6 ms of the kernel's step on the modes panels) ran
    # while the figure's frame was on its way; during a drag it now runs once the page painted
    # that frame, and only the newest update's
    from afmsmiler.plots.live import PAINT_WAIT
    loop = _Loop()
    monkeypatch.setattr(panel_module, "_live_loop", lambda: loop)
    p, live = _drawing_lever(loop)
    shown = []
    p.after_frame(lambda: shown.append("cell"))  # not a move from the browser: at once
    assert shown == ["cell"]
    p.in_drag = True
    p.after_frame(lambda: shown.append("no page yet"))  # no page ever said it painted: at once
    assert shown[-1] == "no page yet"
    live._handle_message(live, {"painted": live.frames_sent}, [])
    live.figure.axes[0].lines[0].set_ydata([0.0, 7.0])
    sent = live.frames_sent
    live.sync()  # an update's frame
    assert live.frames_sent == sent + 1
    p.after_frame(lambda: shown.append("old"))
    p.after_frame(lambda: shown.append("new"))  # a newer update before the paint
    p.in_drag = False
    for _ in range(10):
        loop.now += 0.002
        loop.turn()
    assert shown[-1] == "no page yet"  # waiting for the paint
    live._handle_message(live, {"painted": live.frames_sent}, [])
    loop.now += 0.002
    loop.run()
    assert shown[2:] == ["new"]
    # a deferred animation's commands leave as one message, its legend as one more
    vis = p.scene_root()
    view = p._view
    sent = []
    view.send = lambda content, buffers=None: sent.append(("commands", len(buffers or [])))
    view._send = lambda msg, buffers=None: sent.append(("state", sorted(msg["state"])))

    def animate():
        for x in range(3):
            vis["tip"].set_transform(np.diag([1.0, 1.0, 1.0, 1.0]) + x * np.eye(4, k=3))
        view.set_legend_part("a", "A")
        view.set_legend_part("b", "B")
    live._handle_message(live, {"painted": live.frames_sent}, [])
    live.figure.axes[0].lines[0].set_ydata([0.0, 8.0])
    live.sync()  # an update's frame, not painted yet
    p.in_drag = True
    p.after_frame(animate)
    p.in_drag = False
    assert sent == []  # waiting for the paint
    live._handle_message(live, {"painted": live.frames_sent}, [])
    loop.now += 0.002
    loop.run()
    assert p.error is None and sent == [("state", ["legend"]), ("commands", 3)]
    # a page that never answers costs at most PAINT_WAIT; a failure is shown, not raised
    p.in_drag = True
    p.after_frame(lambda: 1 / 0)
    p.in_drag = False
    start = loop.now
    while p.error is None:
        loop.now += 0.002
        loop.turn()
        assert loop.now - start < PAINT_WAIT + 0.01
    assert "ZeroDivisionError" in p.error


def test_a_painted_message_is_taken_only_for_a_frame_sent():
    _, live = _lever_with_figure()
    for bad in ({"painted": 0}, {"painted": -1}, {"painted": live.frames_sent + 1},
                {"painted": True}, {"painted": 1.0}, {"painted": "1"}, {"painted": None}):
        live._handle_message(live, bad, [])
        assert live.frames_painted == 0, bad
    live._handle_message(live, {"painted": live.frames_sent}, [])
    assert live.frames_painted == live.frames_sent and not live.busy()


def test_moves_that_keep_coming_still_run_the_model(monkeypatch):
    # a steady stream of moves (a mouse drag on a loop slowed by a busy thread) never leaves the
    # loop quiet; the deferred update runs after panel._MAX_DEFER s all the same
    loop = _Loop()
    monkeypatch.setattr(panel_module, "_live_loop", lambda: loop)
    p, live = _lever_with_figure()
    step = p.controls["length"].step
    for k in range(1, 40):
        _browser(p, "length", 225.0 + k * step)
        loop.turn()
        loop.now += 0.004
    assert 2 <= len(p.calls) - 1 <= 4  # one run per _MAX_DEFER (156 ms of moves), not 39
    loop.run()
    assert p.calls[-1][0] == pytest.approx(225.0 + 39 * step)


def test_a_move_handled_in_another_thread_runs_in_the_panels_own(monkeypatch):
    # JupyterLab sends a slider's own update on a kernel subshell, handled in a thread of its
    # own: run there, the update ran at the same time as the main thread's (a force-volume map
    # computed twice at once); the move is handed to the loop the panel was made in
    import threading
    loop = _Loop()
    monkeypatch.setattr(panel_module, "_live_loop", lambda: loop)
    p, live = _lever_with_figure()
    threads = []

    def update(**values):
        threads.append(threading.get_ident())
    p.update = update  # the instance's own: records the thread it runs in
    worker = threading.Thread(target=_browser, args=(p, "length", 240.0))
    worker.start()
    worker.join()
    assert threads == [] and p.values()["length"] == 240.0  # nothing ran in the other thread
    loop.run()
    assert threads == [threading.get_ident()] and p._applied["length"] == 240.0


def test_without_a_live_loop_every_move_updates_at_once_and_a_cell_set_wins():
    # tests and nbval (running_as_notebook() is False): no deferral, as before
    p, live = _lever_with_figure()
    length = p.controls["length"]
    _browser(p, "length", 230.0)
    assert p.calls[-1][0] == 230.0 and p.values()["length"] == 230.0
    p.set(length=240.0)  # a cell's value after the browser's
    assert p.calls[-1][0] == 240.0 and p.values()["length"] == 240.0 and length.value == 240.0


def test_a_value_a_cell_sets_updates_at_once_even_in_a_live_kernel(monkeypatch):
    loop = _Loop()
    monkeypatch.setattr(panel_module, "_live_loop", lambda: loop)
    p, _live = _lever_with_figure()
    p.controls["length"].value = 250.0  # a cell's assignment: no browser lock
    assert p.calls[-1][0] == 250.0 and loop.ready == []


class _Timed(Square):
    """Square whose update waits (sleeps) and then works (spins) for set times."""

    wait = work = 0.0

    def update(self, x):
        time.sleep(self.wait)
        end = time.thread_time() + self.work
        while time.thread_time() < end:
            pass
        super().update(x=x)


def test_an_update_s_cpu_time_leaves_out_its_waits_and_keeps_its_work():
    p = _Timed()
    drawn = len(p.update_seconds)  # the first draw's
    p.wait, p.work = 0.2, 0.0
    p.controls["x"].value = 1.5
    # the thread waited 0.2 s without the CPU: the wall clock counts it, the CPU time does not
    assert p.update_seconds[-1] >= 0.2
    assert p.update_cpu_seconds[-1] < p.update_seconds[-1] - 0.15
    p.wait, p.work = 0.0, 0.05
    p.controls["x"].value = 1.25
    # the thread worked 0.05 s of CPU: both count it
    assert p.update_cpu_seconds[-1] >= 0.05 and p.update_seconds[-1] >= 0.05
    assert len(p.update_seconds) == len(p.update_cpu_seconds) == drawn + 2
