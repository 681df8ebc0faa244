"""Module (f)'s panel without a browser: the image grows one line per step, one model run and one
redraw each; Stop keeps the finished lines; a slider moved during a scan applies from the next
line or restarts, as chosen. The reference is the scanner run directly on the same settings."""
import asyncio
import math

import numpy as np
import pytest

from afmsmiler.contact import ContactSystem, make_tip
from afmsmiler.controller import PRESETS
from afmsmiler.imaging import modes
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
    assert r.crashed is not None and not p.running
    assert r.lines_done == r.crashed.row and 0 < r.lines_done < PIXELS
    ref = _direct(p)
    assert (ref.crashed.row, ref.crashed.column) == (r.crashed.row, r.crashed.column)
    assert ref.crashed.force == pytest.approx(r.crashed.force, rel=1e-12)
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
        p.update(**{**p.values(), "scan_size": 1.0})


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


def test_notebook_faster_mid_scan_the_error_grows_from_the_next_line():
    # "Start, and after a few lines raise the speed to 1000 um/s: from the next line on the
    # error image lights up (several times the RMS) and trace and retrace part"
    p = ImagingPanel()
    p.start(run=False)
    for _ in range(20):
        p.step()
    p.set(scan_speed=1000.0)
    while p.step():
        pass
    e = p.last.channels["error trace"].heights
    assert _rms(e[20:]) > 4 * _rms(e[:20])
    gap = np.abs(p.last.channels["height trace"].heights
                 - p.last.channels["height retrace"].heights)
    assert gap[20:].max() > 2 * gap[:20].max()


@pytest.mark.slow
def test_notebook_a_blunt_tip_widens_the_particles():
    # "a 100 nm tip instead of 5 nm: the particles cover several times the area"
    cover = {}
    for radius in (5.0, 100.0):
        p = ImagingPanel(radius=radius)
        p.start()
        cover[radius] = float((p.last.channels["height trace"].heights > 5e-9).mean())
    assert cover[100.0] > 3 * cover[5.0]


def test_notebook_a_lower_damage_force_mid_scan_crashes_a_later_line():
    # "in constant height, lower the damage force to 2 nN half-way: the tip breaks on a
    # particle of a later line; the scan stops there and the lines before stay"
    p = ImagingPanel(mode="constant height")
    p.start(run=False)
    for _ in range(20):
        p.step()
    before = p.last.channels["deflection trace"].heights[:20].copy()
    p.set(damage_force=2.0)
    while p.step():
        pass
    r = p.last
    assert r.crashed is not None and 20 <= r.crashed.row == r.lines_done < r.lines
    np.testing.assert_array_equal(r.channels["deflection trace"].heights[:20], before)
    assert "crashed" in p.status.value


@pytest.mark.slow
def test_a_real_kernel_answers_between_lines_and_stop_keeps_them():
    # a Jupyter kernel as the notebook has it: Start returns at once, the scan proceeds line by
    # line on the kernel's loop, and requests (here: cells; in JupyterLab also the widgets'
    # messages) are answered between two lines; Stop ends it with the lines finished kept
    import os
    import time
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
        # next line on
        moved = run("print(p.running)\nif p.running: p.set(scan_speed=1000.0)")
        time.sleep(0.05)
        changes = run("print(*p.last.changes)")
        if moved == ["True"]:  # (still scanning when the cell ran)
            assert changes and int(changes[0]) >= seen[-1]
        done = run("p.stop(); print(p.running, p.last.lines_done, p.last.stopped)")
        assert done[0] == "False" and done[2] == "True" and int(done[1]) < 256
        time.sleep(0.3)  # the cancelled task scans nothing more
        assert run("print(p.last.lines_done, p.error)") == [done[1], "None"]
    finally:
        kc.stop_channels()
        km.shutdown_kernel(now=True)


def test_the_3d_view_shows_the_finished_lines_and_the_tip_where_the_last_line_ended():
    import sys
    from pathlib import Path
    sys.path.insert(0, str(Path(__file__).parent))
    from recording import Recorder

    rec = Recorder()
    p = ImagingPanel(pixels=PIXELS, vis=rec)
    scene = p.scene
    assert scene is not None and scene.tip == make_tip("parabolic", radius=20e-9)
    assert scene.image_lines is None  # nothing scanned: no image mesh
    p.start(run=False)
    for _ in range(5):
        p.step()
    assert scene.image_lines == 5  # the rows drawn: the lines finished
    job = p._job.scan
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

