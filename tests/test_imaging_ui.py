"""Module (f)'s panel without a browser: the image grows one line per step, one model run and one
redraw each; Stop keeps the finished lines; a slider moved during a scan applies from the next
line or restarts, as chosen. The reference is the scanner run directly on the same settings."""
import asyncio
import math

import numpy as np
import pytest

from afmsmiler.contact import ContactSystem, make_tip
from afmsmiler.controller import PRESETS
from afmsmiler.imaging import scan_modes as modes
from afmsmiler.imaging.scanner import PARAMETERS as SCAN, Scan, ScanSettings
from afmsmiler.parameters import UNITS
from afmsmiler.ui import imaging as ui
from afmsmiler.ui.imaging import DEFAULTS, ImagingPanel

NM = 1 / UNITS["nm"][1]
PIXELS = 16


def _direct(panel, **changes):
    """The scan the panel's values describe, run directly with the scanner (SI, by hand)."""
    v = {**panel.values(), **changes}
    tip = make_tip(v["tip"], radius=v["radius"] * UNITS["nm"][1])
    if v["mode"] == "constant force":
        loop = PRESETS[ui.PLANT].loop.replace(kp=v["kp"], ki=v["ki"] / UNITS["us"][1])
        mode = modes.ConstantForce(loop, setpoint=v["setpoint"] * UNITS["nm"][1])
    else:
        mode = modes.ConstantHeight(ContactSystem(tip=tip), z_np=v["z_np"] * UNITS["nm"][1],
                                    damage_force=v["damage_force"] * UNITS["nN"][1])
    settings = ScanSettings(v["scan_size"] * UNITS["um"][1], pixels=v["pixels"],
                            scan_speed=v["scan_speed"] * UNITS["um/s"][1],
                            angle=math.radians(v["angle"]),
                            tilt=(math.radians(v["tilt_x"]), 0.0),
                            noise=v["noise"] * UNITS["nm"][1])
    return Scan(ui.sample(v["sample"]), tip, mode, settings).run()


@pytest.fixture
def runs(monkeypatch):
    """Count the modes' runs: ``start`` (once per scan) and ``line`` (once per line)."""
    calls = {"start": 0, "line": 0}
    for cls in (modes.ConstantForce, modes.ConstantHeight):
        for name in ("start", "line"):
            original = getattr(cls, name)

            def counting(self, *args, _original=original, _name=name, **kwargs):
                calls[_name] += 1
                return _original(self, *args, **kwargs)

            monkeypatch.setattr(cls, name, counting)
    return calls


@pytest.fixture
def panel():
    return ImagingPanel(pixels=PIXELS)


def test_each_step_scans_one_line_with_one_model_run_and_one_redraw(panel, runs):
    panel.start(run=False)
    # the start's frame is sent only if it changed the figure (LiveFigure.sync sends no
    # repeat): count from after it
    frames = panel.live.frames_sent
    assert panel.running and panel.last.lines_done == 0 and runs["line"] == 0
    for k in range(1, 6):
        assert panel.step()
        assert runs["line"] == k and panel.last.lines_done == k
        assert panel.live.frames_sent == frames + k  # one frame per line
        assert panel.progress.value == k and panel.progress.max == PIXELS
    assert runs["start"] == 1  # the loop's image is computed once, not once per line
    reference = _direct(panel)
    image = panel.figure.images["image"].get_array()
    h = reference.images["height trace"]
    np.testing.assert_allclose(np.ma.filled(image, np.nan)[:5], h[:5] * NM, rtol=1e-12)
    assert np.ma.getmaskarray(image)[5:].all()  # rows not scanned yet are not drawn
    e = reference.images["error trace"]
    np.testing.assert_allclose(panel.last.channels["error trace"].heights[:5], e[:5],
                               rtol=1e-12)


def test_stop_half_way_keeps_the_finished_lines(panel):
    panel.start(run=False)
    for _ in range(PIXELS // 2):
        panel.step()
    panel.stop()
    assert not panel.running and not panel.step()
    r = panel.last
    assert r.stopped and r.lines_done == PIXELS // 2 and r.lines == PIXELS
    ref = _direct(panel).images["height trace"]
    h = r.channels["height trace"].heights
    np.testing.assert_allclose(h[:PIXELS // 2], ref[:PIXELS // 2], rtol=1e-12)
    assert np.isnan(h[PIXELS // 2:]).all()
    assert r.channels["height trace"].finished(r.lines_done).heights.shape == (PIXELS // 2,
                                                                              PIXELS)
    assert "stopped" in panel.figure.axes["image"].get_title()
    assert "stopped" in panel.status.value
    # a slider moved now scans nothing, but the image says it was made with other values
    panel.set(kp=1.0)
    assert panel.last.lines_done == PIXELS // 2
    assert "settings changed" in panel.figure.axes["image"].get_title()
    panel.start(run=False)
    assert "settings changed" not in panel.figure.axes["image"].get_title()


def test_pause_after_a_line_waits_with_its_lines_and_resume_goes_on(panel, runs):
    # a scan paused after line 5 scans nothing more however long it waits; a slider moved then
    # applies from line 6, when Resume goes on; the image equals the scans run directly
    panel.pause_at.value = 5
    panel.start()  # (off a notebook: to the end or to the pause, at once)
    assert panel.running and panel.paused and panel.last.paused and runs["line"] == 5
    assert panel.last.lines_done == 5 and "paused after line 5" in panel.status.value
    assert panel.pause_button.description == "Resume" and not panel.stop_button.disabled
    assert not panel.step() and runs["line"] == 5  # paused: nothing is scanned
    before = panel.last.channels["height trace"].heights[:5].copy()
    panel.set(scan_speed=1000.0)
    assert runs["line"] == 5 and panel.last.lines_done == 5
    panel.resume()
    r = panel.last
    assert not panel.running and not r.paused and r.lines_done == PIXELS and r.changes == (5,)
    np.testing.assert_array_equal(r.channels["height trace"].heights[:5], before)
    fast = _direct(panel).images["height trace"]
    np.testing.assert_allclose(r.channels["height trace"].heights[5:], fast[5:], rtol=1e-12)
    assert panel.pause_button.disabled and panel.pause_button.description == "Pause"


def test_the_pause_button_pauses_after_the_line_under_way_and_resumes(panel, runs):
    panel.start(run=False)
    for _ in range(3):
        panel.step()
    panel.pause_button.click()
    assert panel.paused and not panel.step() and runs["line"] == 3
    assert not panel.start_button.disabled  # Start may begin anew from a pause
    panel.pause_button.click()  # Resume: off a notebook it runs to the end at once
    assert not panel.running and panel.last.lines_done == PIXELS and runs["line"] == PIXELS
    # a restart while paused starts the scan from the first line, running
    panel.pause_at.value = 2
    panel.start()
    assert panel.paused and panel.last.lines_done == 2
    panel.set(kp=1.0, on_change="restart")
    assert panel.running and not panel.paused and panel.last.lines_done == 0
    # Stop while paused keeps the lines
    assert panel.step() and not panel.step() and panel.paused  # after its line 2 too
    panel.stop()
    assert not panel.running and not panel.paused and panel.last.stopped


def test_in_a_notebook_a_scan_paused_after_a_line_waits_and_resumes(monkeypatch):
    monkeypatch.setattr(ui, "running_as_notebook", lambda: True)
    monkeypatch.setattr(ImagingPanel, "MAX_LINE_WAIT", 0.0)
    p = ImagingPanel(pixels=PIXELS)
    p.pause_at.value = 4

    async def session():
        p.start()
        for _ in range(50):
            await asyncio.sleep(0)
        paused = (p.paused, p.last.lines_done, p.acquisition.state)
        p.set(scan_speed=1000.0)
        p.resume()
        for _ in range(100):
            await asyncio.sleep(0)
            if not p.running:
                break
        return paused

    paused = asyncio.run(session())
    assert paused == (True, 4, "paused")
    assert not p.running and p.last.lines_done == PIXELS and p.last.changes == (4,)


def test_a_slider_moved_during_a_scan_applies_from_the_next_line(panel, runs):
    panel.set(scan_speed=1000.0)  # fast: the gains show in the image
    panel.start(run=False)
    for _ in range(6):
        panel.step()
    before = panel.last.channels["height trace"].heights[:6].copy()
    lines = runs["line"]
    panel.set(kp=2.0)  # one update: nothing scanned, the finished lines kept
    assert runs["line"] == lines and panel.running and panel.last.lines_done == 6
    while panel.step():
        pass
    assert runs["line"] == PIXELS  # one model run per line, none repeated
    r = panel.last
    assert r.lines_done == PIXELS and r.changes == (6,)
    h = r.channels["height trace"].heights
    np.testing.assert_array_equal(h[:6], before)
    ref = _direct(panel).images["height trace"]  # the whole scan with K_P = 2
    np.testing.assert_allclose(h[6:], ref[6:], rtol=1e-12)
    # the first lines were scanned with the other gain
    assert np.abs(h[:6] - ref[:6]).max() > 0.01 * np.ptp(ref[:6])


def test_or_restarts_the_scan_when_so_chosen(panel, runs):
    panel.set(on_change="restart")
    panel.start(run=False)
    for _ in range(6):
        panel.step()
    panel.set(kp=2.0)
    assert panel.running and panel.last.lines_done == 0
    assert np.isnan(panel.last.channels["height trace"].heights).all()
    while panel.step():
        pass
    assert runs["line"] == 6 + PIXELS
    ref = _direct(panel).images["height trace"]
    np.testing.assert_allclose(panel.last.channels["height trace"].heights, ref, rtol=1e-12)


@pytest.mark.parametrize("change", [dict(pixels=32), dict(sample="rough surface"),
                                    dict(angle=30.0), dict(mode="constant height")])
def test_another_image_always_restarts(panel, change):
    panel.start(run=False)
    for _ in range(3):
        panel.step()
    panel.set(**change)  # on_change is "apply on next line"
    assert panel.running and panel.last.lines_done == 0


def test_an_idle_slider_move_scans_nothing_and_keeps_the_image(panel, runs):
    panel.start()  # not in a live notebook: runs to the end at once
    assert panel.last.lines_done == PIXELS and not panel.running and runs["line"] == PIXELS
    done = panel.last.channels["height trace"].heights.copy()
    panel.set(kp=3.0, scan_speed=100.0)
    assert runs["line"] == PIXELS
    np.testing.assert_array_equal(panel.last.channels["height trace"].heights, done)
    panel.start()
    ref = _direct(panel).images["height trace"]
    np.testing.assert_allclose(panel.last.channels["height trace"].heights, ref, rtol=1e-12)


def test_a_crash_in_constant_height_stops_the_scan_and_keeps_the_lines(runs):
    p = ImagingPanel(pixels=PIXELS, mode="constant height", sample="particles")
    # a damage force above line 0's largest force and below the scan's: a later line crashes
    full = _direct(p, damage_force=1000.0).images
    k = ContactSystem().spring_constant
    force = k * np.maximum(full["deflection trace"], full["deflection retrace"]).max(axis=1)
    p.set(damage_force=0.5 * (force[0] + force.max()) * NM)
    p.start()
    r = p.last
    assert r.fault is not None and not p.running
    assert r.lines_done == r.fault.row and 0 < r.lines_done < PIXELS
    ref = _direct(p)
    assert (ref.crashed.row, ref.crashed.column) == (r.fault.row, r.fault.column)
    assert ref.crashed.force == pytest.approx(r.fault.force, rel=1e-12)
    np.testing.assert_allclose(r.channels["deflection trace"].heights[:r.lines_done],
                               ref.images["deflection trace"][:r.lines_done], rtol=1e-12)
    assert "crashed" in p.figure.axes["image"].get_title()


def test_sliders_come_from_the_models_parameters_and_no_position_is_refused():
    p = ImagingPanel(pixels=PIXELS)
    for name in ui.SCAN_SLIDERS:
        assert p.controls[name].parameter is SCAN[name]
    for mode, sliders in ui.MODE_SLIDERS.items():
        for name, parameter in sliders.items():
            assert p.controls[name].parameter is parameter
    assert p.controls["radius"].parameter is ui.TIP_CONTROLS["radius"]
    # the scan size's slider ends where the scan leaves the chosen sample at the chosen angle:
    # the scanner accepts the end, and a scan 1 % larger is refused by the panel and the scanner
    c, a = p.controls["scan_size"], p.controls["angle"]
    for name in ui.SAMPLES:
        s = ui.sample(name)
        rows, cols = s.heights.shape
        width = min((cols - 1) * s.pixel_size, (rows - 1) * s.pixel_size_y)  # centre to centre
        for angle in (a.min, -30.0, 0.0, 45.0, a.max):
            p.set(sample=name, angle=angle)
            top = SCAN["scan_size"].to_si(c.base ** c.max)
            # a square of side S turned by the angle spans S (|cos| + |sin|) along x and y
            fits = width / (abs(math.cos(math.radians(angle))) + abs(math.sin(math.radians(angle))))
            assert top == pytest.approx(min(fits, SCAN["scan_size"].slider_high), rel=1e-9)
            mode = modes.ConstantForce(PRESETS[ui.PLANT].loop)
            Scan(s, None, mode, ScanSettings(top, pixels=64, angle=math.radians(angle)))
            with pytest.raises(ValueError, match="reaches beyond the sample"):
                Scan(s, None, mode, ScanSettings(1.01 * top * 64 / 63, pixels=64,
                                                 angle=math.radians(angle)))
    # the 2 um real image is scanned whole at angle 0 (every scan was capped at 0.36 um)
    p.set(sample="real image (Bruker, 2 um)", angle=0.0, scan_size=1.99)
    assert p.values()["scan_size"] == 1.99
    # back on a 0.51 um sample the slider's end comes back and the value with it
    p.set(sample="particles")
    assert c.value == pytest.approx(0.51, rel=1e-9) and p.values()["scan_size"] == c.value
    assert p._config.settings.scan_size == pytest.approx(0.51e-6, rel=1e-9)
    with pytest.raises(ValueError, match="scan_size"):
        p.set(sample="grating", scan_size=1.0)
    assert p.controls["sample"].value == "particles"  # a refused set changes nothing
    with pytest.raises(ValueError, match=r"scan_size must be <= 0\.51 um on the sample "
                                         r"'particles' at angle 0 deg"):
        p.update(**{**p.to_si(p.values()), "scan_size": 1e-6})  # update takes SI


def test_bad_values_are_named():
    with pytest.raises(TypeError, match="unknown control"):
        ImagingPanel(speed=3)
    p = ImagingPanel(pixels=PIXELS)
    with pytest.raises(ValueError, match="pixels"):
        p.set(pixels=17)
    with pytest.raises(ValueError, match="sample"):
        p.set(sample="graphene")
    assert set(DEFAULTS) == set(p.controls)


def test_only_the_chosen_tip_and_modes_sliders_are_shown():
    p = ImagingPanel(pixels=PIXELS)
    shown = {n for n, c in p.controls.items() if c.layout.display != "none"}
    assert {"kp", "ki", "setpoint", "radius"} <= shown
    assert not {"z_np", "damage_force", "half_angle"} & shown
    p.set(mode="constant height", tip="conical")
    shown = {n for n, c in p.controls.items() if c.layout.display != "none"}
    assert {"z_np", "damage_force", "half_angle"} <= shown and not {"kp", "radius"} & shown


def test_in_a_notebook_the_scan_runs_as_a_task_and_stop_keeps_its_lines(monkeypatch):
    # the kernel's loop runs the scan one line per iteration: between lines it handles the
    # widgets' messages (here: the coroutine's own steps, then Stop)
    monkeypatch.setattr(ui, "running_as_notebook", lambda: True)
    p = ImagingPanel(pixels=PIXELS)

    async def session():
        p.start()
        assert p.running and p.last.lines_done == 0  # nothing scanned before the loop runs
        for _ in range(4):
            await asyncio.sleep(0)
        done = p.last.lines_done
        p.stop()
        await asyncio.sleep(0)
        return done

    done = asyncio.run(session())
    assert 0 < done < PIXELS and p.last.lines_done == done and p.last.stopped


def test_layout_holds_every_control_once():
    import ipywidgets as widgets
    p = ImagingPanel(pixels=PIXELS)
    w = p.widget()

    def walk(box):
        for c in box.children:
            yield c
            if isinstance(c, widgets.Box):
                yield from walk(c)

    shown = list(walk(w))
    for c in p.controls.values():
        assert sum(x is c for x in shown) == 1
    assert any(x is p.start_button for x in shown) and any(x is p.progress for x in shown)


# --- what notebook 06 suggests, followed step by step -------------------------------------------
def _rms(a):
    return float(np.sqrt(np.nanmean(np.asarray(a) ** 2)))


def _lag(image, reference):
    """Pixels by which ``image`` lies behind ``reference`` along +x (best whole shift)."""
    shifts = range(-8, 9)
    misfit = [np.nanmean((np.roll(reference, k, axis=1) - image)[:, 8:-8] ** 2) for k in shifts]
    return shifts[int(np.argmin(misfit))]


def test_notebook_faster_mid_scan_the_error_grows_from_the_next_line():
    # notebook 06, item 1, from the defaults: "set pause after line to 20 and Start; when it
    # pauses raise the scan speed to 1000 um/s and Resume: from the next line on the error image
    # lights up (its RMS grows more than four-fold) and trace and retrace part, each late in its
    # own direction"
    p = ImagingPanel()
    assert DEFAULTS["sample"] == "particles" and DEFAULTS["mode"] == "constant force"
    assert DEFAULTS["scan_speed"] == 10.0
    p.pause_at.value = 20
    p.start()
    assert p.paused and p.last.lines_done == 20
    p.set(scan_speed=1000.0)
    p.resume()
    r = p.last
    assert r.lines_done == r.lines == 64 and r.changes == (20,)
    e = r.channels["error trace"].heights
    assert _rms(e[20:]) > 4 * _rms(e[:20])
    trace = r.channels["height trace"].heights
    retrace = r.channels["height retrace"].heights
    slow = _direct(p, scan_speed=10.0).images["height trace"]  # the scan at 10 um/s throughout
    assert _lag(trace[:20], slow[:20]) == 0 and _lag(retrace[:20], slow[:20]) == 0
    assert _lag(trace[20:], slow[20:]) > 0  # the trace runs along +x: late towards +x
    assert _lag(retrace[20:], slow[20:]) < 0  # the retrace along -x: late towards -x


def test_notebook_stop_half_way_keeps_the_finished_lines():
    # notebook 06, item 2, from the defaults: Stop half-way; the finished lines stay, the rest
    # is empty
    p = ImagingPanel()
    p.start(run=False)
    for _ in range(32):
        p.step()
    p.stop()
    h = p.last.channels["height trace"].heights
    ref = _direct(p).images["height trace"]
    np.testing.assert_allclose(h[:32], ref[:32], rtol=1e-9, atol=1e-18)  # round-off
    assert np.isnan(h[32:]).all() and p.last.stopped


def test_notebook_a_blunt_tip_widens_the_particles():
    # notebook 06, item 3, from the defaults: "a tip radius of 100 nm instead of the default
    # 20 nm: the particles cover some two and a half times the area they did (above 5 nm), at
    # the same height (30 nm), and neighbours merge"
    from scipy import ndimage
    p = ImagingPanel()
    assert DEFAULTS["radius"] == 20.0
    cover, top, islands = {}, {}, {}
    for radius in (20.0, 100.0):
        p.set(radius=radius)
        p.start()
        h = p.last.channels["height trace"].heights
        cover[radius], top[radius] = float((h > 5e-9).mean()), float(h.max())
        islands[radius] = ndimage.label(h > 5e-9)[1]
    assert 2.0 < cover[100.0] / cover[20.0] < 3.0
    assert islands[100.0] < islands[20.0]  # separate particles run together
    assert top[100.0] == pytest.approx(top[20.0], rel=0.02)
    assert top[20.0] == pytest.approx(2 * ui.SAMPLES["particles"][1]["radius"], rel=0.02)


def test_notebook_a_lower_damage_force_mid_scan_crashes_a_later_line():
    # notebook 06, item 4, from the defaults (the 20 nm tip): "switch to constant height, set
    # pause after line to 20 and Start; when it pauses lower the damage force to 2 nN and
    # Resume: the tip breaks on a particle of a later line, the scan stops there, and the lines
    # before it are kept"
    p = ImagingPanel()
    p.set(mode="constant height")
    p.pause_at.value = 20
    p.start()
    assert p.paused and p.last.lines_done == 20 and p.last.fault is None
    before = p.last.channels["deflection trace"].heights[:20].copy()
    p.set(damage_force=2.0)
    p.resume()
    r = p.last
    assert r.fault is not None and 20 <= r.fault.row == r.lines_done < r.lines
    np.testing.assert_array_equal(r.channels["deflection trace"].heights[:20], before)
    assert "crashed" in p.status.value


@pytest.fixture
def kernel():
    """A Jupyter kernel as a notebook has it (no test flags); yields run(code) -> printed words."""
    import os
    from pathlib import Path

    from jupyter_client.manager import start_new_kernel

    root = str(Path(ui.__file__).parents[2])
    env = {k: v for k, v in os.environ.items()
           if k not in ("AFMSMILER_TESTING", "CI", "NBVAL", "PYTEST_CURRENT_TEST")}
    env["PYTHONPATH"] = os.pathsep.join([root, env.get("PYTHONPATH", "")])
    km, kc = start_new_kernel(kernel_name="python3", env=env, cwd=root)

    def run(code):
        msg_id = kc.execute(code)
        out = []
        while True:
            m = kc.get_iopub_msg(timeout=60)
            if m["parent_header"].get("msg_id") != msg_id:
                continue
            if m["msg_type"] == "stream":
                out.append(m["content"]["text"])
            elif m["msg_type"] == "error":
                raise AssertionError("\n".join(m["content"]["traceback"]))
            elif m["msg_type"] == "status" and m["content"]["execution_state"] == "idle":
                return "".join(out).split()

    try:
        yield run
    finally:
        kc.stop_channels()
        km.shutdown_kernel(now=True)


@pytest.mark.slow
def test_a_real_kernel_answers_between_lines_and_stop_keeps_them(kernel):
    # a Jupyter kernel as the notebook has it: Start returns at once, the scan proceeds line by
    # line on the kernel's loop, and requests (here: cells; in JupyterLab also the widgets'
    # messages) are answered between two lines; Stop ends it with the lines finished kept
    import time

    run = kernel

    run("from afmsmiler.ui.imaging import ImagingPanel\np = ImagingPanel(pixels=256)")
    assert run("p.start(); print(p.running, p.last.lines_done)") == ["True", "0"]
    seen = []
    for _ in range(50):
        running, done = run("print(p.running, p.last.lines_done)")
        seen.append(int(done))
        if seen[-1] > 0:
            break
        time.sleep(0.05)
    assert running == "True" and 0 < seen[-1] < 256
    # a slider moved now (a widget's message is handled like this cell) applies from the
    # next line on; to a slower speed: a live scan takes each line's own time (at most
    # MAX_LINE_WAIT), so the scan is still running when Stop comes (moved to 1000 um/s, the
    # remaining lines took 0.6 ms each and a loaded CI machine finished all 256 before it)
    moved = run("print(p.running)\nif p.running: p.set(scan_speed=5.0)")
    time.sleep(0.05)
    changes = run("print(*p.last.changes)")
    if moved == ["True"]:  # (still scanning when the cell ran)
        assert changes and int(changes[0]) >= seen[-1]
    done = run("p.stop(); print(p.running, p.last.lines_done, p.last.stopped)")
    assert done[0] == "False" and done[2] == "True" and int(done[1]) < 256
    time.sleep(0.3)  # the cancelled task scans nothing more
    assert run("print(p.last.lines_done, p.error)") == [done[1], "None"]


@pytest.mark.slow
def test_a_real_kernel_waits_at_the_pause_for_as_long_as_the_student_needs(kernel):
    # notebook 06, item 1, in a Jupyter kernel as the notebook has it: the scan pauses after line
    # 20 and scans nothing more while the student takes their time; the speed raised then applies
    # from line 20 on when Resume goes on
    import time

    run = kernel

    def wait(condition, seconds=30.0):
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            if run(f"print({condition})") == ["True"]:
                return True
            time.sleep(0.1)
        return False

    run("from afmsmiler.ui.imaging import ImagingPanel\np = ImagingPanel()\n"
        "p.pause_at.value = 20\np.start()")
    assert wait("p.paused")
    assert run("print(p.last.lines_done, p.running)") == ["20", "True"]
    time.sleep(2.0)  # the student takes their time: nothing more is scanned
    assert run("print(p.last.lines_done, p.paused)") == ["20", "True"]
    run("p.set(scan_speed=1000.0)\np.resume()")
    assert wait("not p.running")
    assert run("print(p.last.lines_done, *p.last.changes, p.error)") == ["64", "20", "None"]


def test_the_3d_view_shows_the_finished_lines_and_the_tip_where_the_last_line_ended():
    from tests.recording import Recorder

    rec = Recorder()
    p = ImagingPanel(pixels=PIXELS, vis=rec)
    scene = p.scene
    assert scene is not None and scene.tip == make_tip("parabolic", radius=20e-9)
    assert scene.image_lines is None  # nothing scanned: no image mesh
    p.start(run=False)
    for _ in range(5):
        p.step()
    assert scene.image_lines == 5  # the rows drawn: the lines finished
    job = p.acquisition.scan
    x, y = job.position(4, 0, "retrace")
    assert scene.tip_position == pytest.approx((x, y, job.plan.retrace[4, 0]), rel=1e-12)
    meshes = rec.log[scene.vis["image"].key]["n_objects"]
    p.set(kp=2.0)  # a slider move: the figure and the scene shown again, no new image mesh
    assert rec.log[scene.vis["image"].key]["n_objects"] == meshes
    p.step()
    assert rec.log[scene.vis["image"].key]["n_objects"] == meshes + 1  # one mesh per line
    p.set(radius=40.0, on_change="restart")  # another tip: the scene is drawn anew
    assert p.scene is not scene and p.scene.tip.radius == pytest.approx(40e-9)
    p.step()
    p.step()
    assert p.scene.image_lines == 2
    p.set(pixels=32)  # another image: the old lines' mesh goes
    assert p.scene.image_lines == 1 and p.last.lines_done == 0


def test_choosing_what_later_moves_do_changes_nothing_now(panel, runs):
    panel.start(run=False)
    for _ in range(3):
        panel.step()
    starts = runs["start"]
    panel.set(on_change="restart")
    assert panel.running and panel.last.lines_done == 3
    panel.step()
    assert runs["start"] == starts and panel.last.lines_done == 4 and panel.last.changes == ()


def test_a_failure_during_a_live_scan_is_shown_under_the_panel(monkeypatch):
    # a task's exception would be lost in the kernel's log: the panel shows it and can start again
    monkeypatch.setattr(ui, "running_as_notebook", lambda: True)
    p = ImagingPanel(pixels=PIXELS)

    def broken(self, *args, **kwargs):
        raise RuntimeError("the loop broke")

    async def session():
        monkeypatch.setattr(modes.ConstantForce, "line", broken)
        p.start()
        for _ in range(3):
            await asyncio.sleep(0)

    asyncio.run(session())
    assert not p.running and "the loop broke" in p.error
    assert not p.start_button.disabled and p.stop_button.disabled


def test_a_line_not_shown_appears_in_the_next_picture(panel, runs):
    """A live scan draws at most one picture per FRAME_INTERVAL (``step(show=False)`` between):
    every line drawn sent a 0.5 MB image pair and a cell run during the scan waited seconds for
    its answer behind them. The lines scanned meanwhile are all in the next picture."""
    panel.start(run=False)
    frames = panel.live.frames_sent
    for _ in range(3):
        assert panel.step(show=False)
    assert runs["line"] == 3 and panel.live.frames_sent == frames  # scanned, not drawn
    assert panel.step()
    assert panel.live.frames_sent == frames + 1 and panel.progress.value == 4
    image = np.ma.getmaskarray(panel.figure.images["image"].get_array())
    assert not image[:4].any() and image[4:].all()  # the four lines, and only those



def test_start_configures_only_what_changed_since_the_last_update(monkeypatch):
    """Start ran the configuration a second time after update had run it: now once."""
    calls = {"n": 0}
    original = ImagingPanel._configure

    def counting(self, values):
        calls["n"] += 1
        return original(self, values)

    monkeypatch.setattr(ImagingPanel, "_configure", counting)
    p = ImagingPanel(pixels=PIXELS)
    p.set(kp=1.0)
    before = calls["n"]
    p.start(run=False)
    assert calls["n"] == before  # the values update configured are the scan's
    p.set(mode="constant height")
    p.start(run=False)
    assert calls["n"] == before + 1


def test_the_image_is_the_modes_main_channel():
    """The panel named its channel by isinstance; the mode says which channel is its image."""
    p = ImagingPanel(pixels=PIXELS, mode="constant height")
    assert p.last.main == modes.ConstantHeight.main_channel == "deflection trace"
    p.start(run=False)
    p.step()
    assert p.last.main == "deflection trace" and "deflection trace" in \
        p.figure.axes["image"].get_title()
