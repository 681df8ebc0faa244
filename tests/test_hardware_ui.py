"""The macroscopic AFM's panel without a browser: the twin scans, the image grows from the
streamed pixels, pause/resume/abort/save act as the notebook says, a fault keeps the finished
lines, contact mode fails on the tall pillars where jumping mode does not, and a print exported
from the panel is scanned back within the z micro-step.

References: the twin's own dilated surface (module (f)'s dilation of the print by the needle,
what the needle can follow), the z micro-step's rounding error (RMS step / sqrt(12) for a uniform
error), the .gwy file read back by module (f)'s reader, trimesh's watertightness check.
"""
import asyncio
import math
import os
import time

import numpy as np
import pytest
import trimesh

from afmsmiler.hardware import PtyLink, TwinServer, printing
from afmsmiler.hardware.macro import MacroAFMTwin
from afmsmiler.samples import load
from afmsmiler.ui import hardware as ui
from afmsmiler.ui.hardware import DEFAULTS, TWIN, MacroAFMPanel

Z_STEP = 2.5e-6
QUANTISATION = Z_STEP / math.sqrt(12)  # RMS of a uniform rounding to the z micro-step


@pytest.fixture
def panel():
    p = MacroAFMPanel(pixels=16, pitch=1.0)
    yield p
    p.close()


@pytest.fixture
def meshes(monkeypatch):
    """Count the meshes built (the panel's only costly model besides the scan)."""
    calls = {"n": 0}
    original = printing.sample_to_mesh

    def counting(*args, **kwargs):
        calls["n"] += 1
        return original(*args, **kwargs)

    monkeypatch.setattr(printing, "sample_to_mesh", counting)
    return calls


def test_the_twin_is_the_default_and_serial_ports_are_offered(monkeypatch):
    class Port:
        device, description = "/dev/ttyACM0", "Arduino Mega 2560"

    monkeypatch.setattr("serial.tools.list_ports.comports", lambda: [Port()])
    p = MacroAFMPanel()
    options = p.controls["port"].options
    assert options[0][1] == TWIN and p.values()["port"] == TWIN
    assert ("/dev/ttyACM0 (Arduino Mega 2560)", "/dev/ttyACM0") in options
    with pytest.raises(ValueError, match="port"):
        p.set(port="/dev/ttyUSB9")
    with pytest.raises(ValueError, match="pixels"):
        p.set(pixels=7)
    with pytest.raises(TypeError, match="unknown control"):
        MacroAFMPanel(speed=3)


def test_a_slider_move_builds_nothing_an_export_one_mesh(panel, meshes, tmp_path):
    panel.set(lateral_scale=1000.0)
    panel.set(vertical_scale=2000.0, base_thickness=3.0)
    assert meshes["n"] == 0 and panel.mesh_runs == 0 and panel.device is None
    x, y, z = panel.last.print_size
    shell = printing.seashell()
    assert x == pytest.approx(shell.width * 1000) and z == pytest.approx(
        3e-3 + 2000 * np.ptp(shell.heights))
    path = panel.export_stl(tmp_path / "shell.stl")
    assert meshes["n"] == 1 and panel.mesh_runs == 1
    mesh = trimesh.load(path)
    assert mesh.is_watertight
    np.testing.assert_allclose(mesh.extents, np.array([x, y, z]) * 1e3, rtol=1e-6)  # mm
    assert "your print (shell.stl)" in panel.controls["sample"].options
    assert panel.values()["sample"] == DEFAULTS["sample"]  # the choice is kept


def test_each_step_adds_the_streamed_pixels_up_to_a_line(panel):
    panel.connect()
    panel.start(run=False)
    assert panel.running and panel.last.pixels_done == 0 and panel.progress.max == 256
    assert panel.step()
    first = panel.last.pixels_done
    assert 0 < first <= 16  # at most one line per step
    while panel.step():
        pass
    r = panel.last
    assert r.state == "done" and r.pixels_done == 256 and r.lines_done == 16
    assert panel.progress.value == 256
    # the image is the driver's: heights in m from z micro-steps times ZS
    np.testing.assert_array_equal(r.height, panel.device.result.heights)
    assert r.finished().pixel_size == pytest.approx(1e-3)


def test_the_seashell_is_scanned_within_the_z_micro_step(panel):
    panel.start()
    c = panel.last.comparison
    assert c is not None and c.image.shape == (16, 16)
    # the twin's gauge noise adds a little to the rounding's 0.72 um
    assert c.rms < 1.5 * QUANTISATION and c.max_abs < 2 * Z_STEP


@pytest.mark.slow
def test_contact_mode_fails_on_the_tall_pillars_and_jumping_mode_does_not(panel):
    """The notebook's claim: on 2 mm pillars, contact mode's image is dragged (friction), jumping
    mode's is the surface the needle can follow, to the z micro-step."""
    panel.set(sample="pillars (2 mm tall grating)", pixels=32, pitch=0.4, lift=2.5)
    panel.set(mode="contact")
    panel.start()
    contact = panel.last.comparison
    panel.set(mode="jumping")
    panel.start()
    jumping = panel.last.comparison
    assert jumping.rms < 1.5 * QUANTISATION
    assert contact.rms > 50e-6 and contact.max_abs > 0.5e-3  # ~0.1 mm; at 2 mm tall walls
    # all of contact mode's error is at the walls: where it exceeds a few steps, the surface
    # changes by more than 0.1 mm within a pixel along the fast axis
    ref = contact.reference.heights
    wall = np.zeros_like(ref, dtype=bool)
    step = np.abs(np.diff(ref, axis=1)) > 0.1e-3
    wall[:, 1:] |= step
    wall[:, :-1] |= step
    wrong = np.abs(contact.difference.heights - np.median(contact.difference.heights)) \
        > 5 * Z_STEP
    assert wrong.any() and wall[wrong].all()


def test_pause_stops_the_stream_and_resume_goes_on_without_loss(panel):
    # the link holds 256 bytes, as a board's serial buffer: the twin waits for the host
    panel.start(run=False)
    for _ in range(3):
        panel.step()
    panel.pause()
    done = panel.last.pixels_done
    assert panel.paused and panel.buttons["pause"].description == "Resume"
    for _ in range(3):
        assert panel.step()  # paused: running, nothing read
    assert panel.last.pixels_done == done and panel.last.state == "paused"
    panel.resume()
    while panel.step():
        pass
    assert panel.last.state == "done" and panel.last.pixels_done == 256, panel.last.error
    assert panel.last.comparison.rms < 1.5 * QUANTISATION


def test_pause_after_the_machine_finished_is_harmless(panel):
    panel.set(pixels=8)
    panel.start(run=False)
    while panel.last.pixels_done < 56:  # into the last line: its pixels fit in the link
        panel.step()
    twin = panel._session.server.twin
    for _ in range(500):  # at pace 0 the twin streams the whole scan at once
        if twin.state.value == "IDLE":
            break
        time.sleep(0.01)
    panel.pause()  # the machine is done: the pause is refused (STATE) and ignored
    assert not panel.paused and "already finished" in panel.status.value
    while panel.step():
        pass
    assert panel.last.state == "done"


def test_abort_keeps_the_finished_lines_and_save_writes_them(panel, tmp_path):
    panel.start(run=False)
    for _ in range(6):
        panel.step()
    panel.abort()
    r = panel.last
    assert not panel.running and r.state == "aborted" and not panel.step()
    assert 2 <= r.lines_done < 16
    path = panel.save_gwy(tmp_path / "half.gwy")
    back = load(path, "height")  # save_gwy names the channel "height" (module (f))
    assert back.shape == (r.lines_done, 16) and back.pixel_size == pytest.approx(1e-3)
    np.testing.assert_allclose(back.heights, r.height[:r.lines_done], rtol=1e-12)
    # the link still works: another scan runs to the end
    panel.start()
    assert panel.last.state == "done"


def test_a_limit_switch_ends_the_scan_in_the_panel_and_keeps_the_lines(panel):
    panel.connect()
    panel._session.server.twin.trigger_limit("X", at=(5, 3))
    panel.start()  # runs to the fault: no exception escapes, the panel shows it
    r = panel.last
    assert r.state == "fault" and not panel.running
    assert "DeviceError" in panel.error and "DeviceError" in r.error
    assert r.lines_done == 5 and np.isfinite(r.height[:5]).all()
    assert "fault" in panel.figure.axes["height"].get_title()
    assert panel.last.finished().shape == (5, 16)


@pytest.mark.slow
def test_a_print_exported_from_the_panel_is_scanned_back(panel, tmp_path):
    panel.set(source="real image (Bruker, 2 um)", lateral_scale=10000.0,
              vertical_scale=2e4, base_thickness=2.0)
    panel.export_stl(tmp_path / "real.stl")
    panel.set(sample="your print (real.stl)", mode="jumping", pitch=1.0, lift=0.5)
    panel.start()
    c = panel.last.comparison
    assert c.image.shape == (16, 16) and c.rms < 1.5 * QUANTISATION


@pytest.mark.slow
def test_a_real_port_is_opened_with_pyserial(monkeypatch):
    """A pty served by the twin stands for the Arduino's USB port: the panel opens it by name."""
    link = PtyLink()
    server = TwinServer(MacroAFMTwin(), link.device_end, time_scale=0.0).start()
    try:
        monkeypatch.setattr(ui, "serial_ports", lambda: [(link.path, link.path)])
        p = MacroAFMPanel(port=link.path, pixels=8, pitch=1.0)
        assert "MACROAFM" in p.connect() and "twin" not in p._session.identity
        p.start()
        assert p.last.state == "done" and p.last.comparison is None  # no print known
        p.close()
    finally:
        server.stop()
        link.close()


def test_in_a_notebook_the_scan_runs_as_a_task_and_abort_keeps_its_lines(monkeypatch, panel):
    monkeypatch.setattr(ui, "running_as_notebook", lambda: True)
    panel.connect()

    async def session():
        panel.start()
        assert panel.running and panel.last.pixels_done == 0
        for _ in range(40):
            await asyncio.sleep(0.01)
            if panel.last.lines_done >= 3:
                break
        panel.abort()
        await asyncio.sleep(0)

    asyncio.run(session())
    assert panel.last.state == "aborted" and panel.last.lines_done >= 2


def test_layout_holds_every_control_and_button_once(panel):
    import ipywidgets as widgets
    w = panel.widget()
    seen = []

    def walk(x):
        seen.append(x)
        for child in getattr(x, "children", ()):
            walk(child)

    walk(w)
    for c in [*panel.controls.values(), *panel.buttons.values()]:
        assert sum(x is c for x in seen) == 1
    assert isinstance(w, widgets.VBox)


def test_wait_runs_the_scan_to_the_end_in_a_live_notebook_too(monkeypatch, panel):
    monkeypatch.setattr(ui, "running_as_notebook", lambda: True)
    panel.start(wait=True)  # a cell that uses the image next
    assert panel.last.state == "done" and panel.last.lines_done == 16


def test_a_slider_move_sends_nothing_to_the_machine_and_start_one_scan(monkeypatch, panel):
    from afmsmiler.hardware.macro import MacroAFM
    sent = []
    original = MacroAFM._command

    def counting(self, command, *args):
        sent.append(command.value)
        return original(self, command, *args)

    monkeypatch.setattr(MacroAFM, "_command", counting)
    panel.connect()
    sent.clear()
    panel.set(setpoint_force=20.0, lift=1.0, mode="jumping")
    panel.set(lateral_scale=800.0)
    assert sent == []  # the values wait for Start
    panel.start()
    assert sent.count("SS") == 1 and sent.count("SP") == 6  # NX NY DX SE MO LI, once each
    assert panel.device.events[-1].event.value == "DONE"


@pytest.mark.slow
def test_the_notebooks_seashell_print_is_scanned_back_within_the_z_step(tmp_path):
    """Notebook 08's cells: the seashell exported at the default scales, scanned in jumping mode
    at 32 pixels of 1 mm: the rounding to the z micro-step is all that is left."""
    p = MacroAFMPanel()
    try:
        p.export_stl(tmp_path / "seashell_print.stl")
        p.set(sample="your print (seashell_print.stl)", mode="jumping", pixels=32, pitch=1.0,
              lift=0.5)
        p.start(wait=True)
        c = p.last.comparison
        assert c.image.shape == (32, 32) and c.rms < 1.5 * QUANTISATION
    finally:
        p.close()


@pytest.mark.hardware
@pytest.mark.skipif(os.environ.get("AFMSMILER_HARDWARE") != "1",
                    reason="no board: set AFMSMILER_HARDWARE=1 and AFMSMILER_PORT=/dev/ttyACM0")
def test_the_panel_scans_with_a_real_board(monkeypatch, tmp_path):
    port = os.environ.get("AFMSMILER_PORT", "/dev/ttyACM0")
    monkeypatch.setattr(ui, "serial_ports", lambda: [(port, port)])
    p = MacroAFMPanel(port=port, pixels=8, pitch=0.5, mode="jumping")
    try:
        assert "MACROAFM protocol 1" in p.connect()
        p.start(wait=True)
        assert p.last.state == "done" and p.last.lines_done == 8
        assert load(p.save_gwy(tmp_path / "board.gwy"), "height").shape == (8, 8)
    finally:
        p.close()


@pytest.mark.parametrize("fault, expected", [
    (dict(unplug_after_lines=150), "TransportClosed"),     # the cable pulled mid-scan
    pytest.param(dict(silent_after_lines=150), "DeviceNotResponding",  # the board hangs
                 marks=pytest.mark.slow),
])
def test_a_lost_link_ends_the_scan_in_the_panel_and_keeps_the_lines(monkeypatch, fault,
                                                                   expected, tmp_path):
    import afmsmiler.hardware as hw
    original = hw.open_twin

    def faulty(twin, **kwargs):
        host, server = original(twin, **kwargs)
        return hw.FaultyTransport(host, **fault), server

    monkeypatch.setattr(hw, "open_twin", faulty)
    p = MacroAFMPanel(pixels=16, pitch=1.0)
    try:
        p.connect()
        p.device.timeout, p.device.stream_timeout = 0.2, 0.5  # no long waits in a test
        p.start()
        r = p.last
        assert r.state == "fault" and expected in p.error and not p.running
        assert 2 <= r.lines_done < 16 and np.isfinite(r.height[:r.lines_done]).all()
        assert load(p.save_gwy(tmp_path / "kept.gwy"), "height").shape == (r.lines_done, 16)
    finally:
        p.close()


def test_a_print_exported_again_under_its_name_replaces_the_old_one(panel, tmp_path):
    panel.export_stl(tmp_path / "p.stl")
    panel.set(sample="your print (p.stl)", pixels=8, pitch=1.0)
    panel.start()
    first = panel.last.height.copy()
    panel.set(vertical_scale=800.0)  # twice the relief
    panel.export_stl(tmp_path / "p.stl")
    panel.start()
    second = panel.last.height
    relief = [np.ptp(h) for h in (first, second)]
    assert relief[1] == pytest.approx(2 * relief[0], rel=0.05)
    assert panel.last.comparison.rms < 1.5 * QUANTISATION


def test_commands_during_a_paced_scan_lose_no_pixels():
    p = MacroAFMPanel(pixels=16, pitch=1.0, time_scale=0.001)
    try:
        p.start(run=False)
        p.step()
        for _ in range(20):  # status requests while the machine streams, as Pause/Resume do
            p.device.status()
            time.sleep(0.005)
        while p.step():
            pass
        assert p.last.state == "done", p.last.error
    finally:
        p.close()


def test_the_figure_shows_the_streamed_pixels_in_um_over_mm(panel):
    from afmsmiler.parameters import UNITS
    um = 1 / UNITS["um"][1]
    panel.start(run=False)
    for _ in range(3):
        panel.step()
    shown_image = np.ma.filled(panel.figure.images["height"].get_array(), np.nan)
    h = panel.last.height
    # the relief above the lowest pixel so far (the machine's z zero is its home), NaN where no
    # pixel came
    np.testing.assert_allclose(shown_image, (h - np.nanmin(h)) * um, rtol=1e-12, atol=1e-9)
    assert np.isnan(shown_image).sum() == h.size - panel.last.pixels_done
    assert panel.figure.images["height"].get_extent() == pytest.approx(
        [-0.5, 15.5, -0.5, 15.5])  # 16 pixels of 1 mm, pixel edges in mm
    assert f"{panel.last.pixels_done}/256" in panel.figure.axes["height"].get_title()
    # the line of the last pixel streamed, counted from 1 (the profile said "line 0")
    line = (panel.last.pixels_done - 1) // 16
    assert panel.figure.axes["profile"].get_title() == f"line {line + 1} of 16"
    while panel.step():
        pass
    c = panel.last.comparison
    diff = np.ma.filled(panel.figure.images["difference"].get_array(), np.nan)
    np.testing.assert_allclose(diff, c.difference.heights * um, rtol=1e-12)
    assert f"{c.rms * um:.3g}" in panel.figure.axes["difference"].get_title()


def test_the_print_reads_the_same_heights_in_both_rows(panel):
    """The issue: the same print read 6,000-8,250 um in the top row (the machine's z, from its
    home) and -1,000...500 um in the bottom one (mean removed). Both now show the relief above
    the lowest point: the scan's range is the print's, to a few z micro-steps."""
    from afmsmiler.parameters import UNITS
    um = 1 / UNITS["um"][1]
    panel.set(sample="pillars (2 mm tall grating)", mode="jumping", pixels=16, pitch=1.0,
              lift=2.5)
    panel.start()
    h = panel.last.finished().heights
    assert h.min() > 3e-3                      # raw: millimetres above the bed, from home
    top = np.ma.filled(panel.figure.images["height"].get_array(), np.nan)
    ref = np.ma.filled(panel.figure.images["reference"].get_array(), np.nan)
    scan = np.ma.filled(panel.figure.images["image"].get_array(), np.nan)
    c = panel.last.comparison
    np.testing.assert_allclose(ref, (c.reference.heights - c.reference.heights.min()) * um,
                               atol=1e-9)
    for shown in (top, scan):
        assert np.nanmin(shown) == pytest.approx(0.0, abs=3 * Z_STEP * um)
        assert np.nanmax(shown) == pytest.approx(np.nanmax(ref), abs=3 * Z_STEP * um)
    assert np.nanmax(ref) > 500                 # the print's relief, in um: hundreds, not 0


def test_modes_figure_shows_where_two_scans_differ():
    """Two scans of one print, one dragged at a wall: the figure's error maps are the scans
    minus the print in um on one shared symmetric scale, and the profile is the line with the
    dragged pixel."""
    from afmsmiler.plots.hardware import modes_figure
    from afmsmiler.samples import Sample
    mm = 1e-3
    ref = np.zeros((6, 8))
    ref[:, 4:] = 2 * mm                                   # a 2 mm wall along the fast axis
    good = Sample(ref + 7 * mm, 0.4 * mm)                 # the machine's z: 7 mm from home
    dragged = ref.copy()
    dragged[3, 4] = 0.0                                   # the foot of the wall, one pixel late
    bad = Sample(dragged + 7 * mm, 0.4 * mm)
    reference = Sample(ref, 0.4 * mm)
    comparisons = [printing.compare_scan(reference, s) for s in (bad, good)]
    fig = modes_figure(*comparisons, labels=["contact", "jumping"])
    axes = [ax for ax in fig.axes if ax.get_images() or ax.get_lines()]   # not colour bars
    images = [im for ax in axes for im in ax.get_images()]
    scans, errors = images[0::2], images[1::2]
    for im, c in zip(errors, comparisons):
        np.testing.assert_allclose(np.ma.filled(im.get_array(), np.nan),
                                   c.difference.heights * 1e6, atol=1e-6)
        assert im.get_clim() == errors[0].get_clim() and im.get_clim()[0] == -im.get_clim()[1]
    assert errors[0].get_clim()[1] == pytest.approx(np.abs(comparisons[0].difference.heights
                                                           ).max() * 1e6)
    for im in scans:                                      # relief: 0 to 2000 um, not 7 mm
        assert np.nanmax(np.ma.filled(im.get_array(), np.nan)) == pytest.approx(2000, abs=400)
    profile = [ax for ax in axes if ax.get_lines()][-1]
    assert "line 3" in profile.get_title()
    assert "RMS" in axes[1].get_title() and "contact" in axes[1].get_title()
    with pytest.raises(ValueError, match="labels"):
        modes_figure(*comparisons, labels=["contact"])


def test_a_port_that_cannot_be_opened_is_reported_in_the_panel(monkeypatch):
    monkeypatch.setattr(ui, "serial_ports", lambda: [("gone", "/dev/ttyACM9")])
    p = MacroAFMPanel(port="/dev/ttyACM9")
    p.buttons["connect"].click()  # ipywidgets' dispatcher logs what the action raises again
    assert "TransportClosed" in p.error and "/dev/ttyACM9" in p.error and p.device is None and p.last.state == "idle"
    p.set(port=TWIN)  # the twin still works
    assert "twin" in p.connect()
    p.close()


def test_buttons_pressed_in_another_thread_act_between_steps(panel):
    """ipykernel 7 runs a click handler in another thread than the loop reading the scan. The
    driver queued a command from there to the reading thread, which a paused scan never ran:
    Resume and Abort hung for the driver's timeout (35 s). The panel now queues the action
    itself and the next step runs it."""
    import threading

    def press(name):
        t = threading.Thread(target=panel.buttons[name].click)
        t.start()
        t.join(5.0)
        assert not t.is_alive(), f"{name} hung in the click handler"

    panel.set(mode="jumping")
    panel.start(run=False)
    for _ in range(3):
        panel.step()
    press("pause")
    assert panel.step() and panel.paused
    done = panel.last.pixels_done
    press("pause")  # now labelled Resume
    assert panel.step() and not panel.paused and panel.last.pixels_done > done
    press("pause")
    panel.step()
    press("abort")
    assert not panel.step() and panel.last.state == "aborted"
    assert panel.error is None
