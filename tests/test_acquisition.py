"""The one acquisition interface, implemented by the simulated scan and the macroscopic AFM's
session: start, pause, resume, abort, new settings from the next line, immutable snapshots with
NaN where nothing was measured, and the finished lines kept when a device faults.

References: the scanner run directly (:meth:`Scan.run`) on the same settings, for the simulated
scan; the driver's own image (:attr:`MacroAFM.result`) and the twin's surface, for the session.
Faults come from the twin (a limit switch) and from module (h)'s fault-injecting transport (the
cable pulled after a number of lines).
"""
import numpy as np
import pytest

from afmsmiler.acquisition import STATES, Acquisition, NotSupported, SettingsRefused, Snapshot
from afmsmiler.controller import ContactLoop
from afmsmiler.hardware import FaultyTransport, open_twin
from afmsmiler.hardware.educational import EducationalAFMTwin
from afmsmiler.hardware.educational.session import EducationalSession
from afmsmiler.hardware.macro import MacroAFMTwin
from afmsmiler.hardware.macro.session import MacroSession
from afmsmiler.imaging.acquisition import ScanAcquisition
from afmsmiler.imaging.scan_modes import ConstantForce
from afmsmiler.imaging.scanner import Scan
from afmsmiler.imaging.settings import ScanSettings
from afmsmiler.samples import particles

LINES = 8
SCAN = dict(mode="contact", pixels=LINES, pitch=1e-3, setpoint_force=10e-3, lift=0.5e-3)
EDU_SAMPLE = particles(shape=(64, 64), pixel_size=20e-9, count=6, radius=80e-9, seed=3)
EDU_SCAN = dict(pixels=LINES, pitch=60e-9)


def _educational(wrap=None, **options):
    """The educational AFM's twin at its own pace (1 ms per pixel: 8 ms per line)."""
    host, server = open_twin(EducationalAFMTwin(EDU_SAMPLE), time_scale=1.0)
    return EducationalSession.open(wrap(host) if wrap else host, server, **options)


def _simulated(**settings):
    sample = particles(shape=(64, 64), pixel_size=5e-9, count=4, radius=20e-9, seed=1)
    s = ScanSettings(250e-9, pixels=LINES, **settings)
    return ScanAcquisition(sample, None, ConstantForce(ContactLoop()), s)


def _direct(acq, settings=None):
    s = acq.scan
    return Scan(s.sample, s.tip, s.mode, settings or s.settings).run()


@pytest.fixture
def macro():
    session = MacroSession.open(*open_twin(MacroAFMTwin()))
    yield session
    session.close()


@pytest.fixture(params=["simulated", "macro", "educational"])
def acquisition(request):
    """Each implementation, started (the macroscopic AFM at 8 x 8 pixels of 1 mm, the
    educational AFM at 8 x 8 pixels of 60 nm)."""
    if request.param == "simulated":
        acq = _simulated()
        acq.start()
        yield acq
        return
    if request.param == "macro":
        session, settings = MacroSession.open(*open_twin(MacroAFMTwin())), SCAN
    else:
        session, settings = _educational(), EDU_SCAN
    session.start(**settings)
    yield session
    session.close()


def _lines(acq, n):
    """Step until ``n`` lines are finished (a device may need several reads per line)."""
    for _ in range(50 * n):
        if acq.snapshot().lines_done >= n or not acq.step(0.25):
            break
    assert acq.snapshot().lines_done >= n


def _to_end(acq):
    """Step to the scan's end; its last snapshot."""
    while acq.step(0.25):
        pass
    return acq.snapshot()


def _refused_then_done(session, settings, match, **new):
    """Start, finish a line, have ``new`` refused by name, scan on to the end."""
    session.start(**settings)
    _lines(session, 1)
    with pytest.raises(SettingsRefused, match=match):
        session.apply(**new)
    snap = _to_end(session)
    assert snap.state == "done" and np.isfinite(snap.images[snap.main]).all()
    return snap


def test_both_are_acquisitions_with_the_same_states(acquisition):
    assert isinstance(acquisition, Acquisition)
    snap = acquisition.snapshot()
    assert snap.state == "scanning" and snap.state in STATES and snap.running
    assert snap.lines_done == 0 and snap.pixels_done == 0
    assert all(np.isnan(a).all() for a in snap.images.values())  # nothing measured yet


def test_snapshots_are_immutable_and_nan_where_nothing_was_measured(acquisition):
    _lines(acquisition, 2)
    snap = acquisition.snapshot()
    main = snap.images[snap.main]
    assert acquisition.snapshot() is snap  # nothing changed: the same object
    with pytest.raises(ValueError, match="read-only"):
        main[0, 0] = 1.0
    with pytest.raises(TypeError):
        snap.images["other"] = main
    with pytest.raises(AttributeError):
        snap.lines_done = 0
    done = snap.lines_done
    assert np.isfinite(main[:done]).all() and np.isnan(main[done + 1:]).all()
    kept = main.copy()
    acquisition.step(0.25)
    assert acquisition.snapshot() is not snap  # a new one; the old one did not change
    np.testing.assert_array_equal(snap.images[snap.main], kept)
    assert snap.finished().shape == (done, LINES)


def test_pause_scans_nothing_until_resume_and_loses_nothing(acquisition):
    _lines(acquisition, 2)
    if isinstance(acquisition, EducationalSession):  # its protocol has no pause: it says so
        with pytest.raises(NotSupported, match="cannot pause"):
            acquisition.pause()
        assert acquisition.state == "scanning" and acquisition.step(0.25)
        return
    assert acquisition.pause() and acquisition.paused and acquisition.state == "paused"
    # a device's pixels under way still arrive after a pause: read them, then nothing comes
    acquisition.resume()
    acquisition.pause()
    before = acquisition.snapshot()
    for _ in range(5):
        assert acquisition.step(0.02)  # paused: running, nothing scanned or read
    assert acquisition.snapshot() is before
    acquisition.resume()
    while acquisition.step(0.25):
        pass
    snap = acquisition.snapshot()
    assert snap.state == "done" and snap.lines_done == LINES and not snap.running
    assert np.isfinite(snap.images[snap.main]).all()


def test_abort_keeps_the_finished_lines(acquisition):
    _lines(acquisition, 3)
    acquisition.abort()
    snap = acquisition.snapshot()
    assert snap.state == "aborted" and snap.stopped and not acquisition.step(0.1)
    assert 3 <= snap.lines_done < LINES
    assert np.isfinite(snap.images[snap.main][:snap.lines_done]).all()
    assert snap.finished().shape == (snap.lines_done, LINES)


def test_the_simulated_scan_takes_new_settings_from_the_next_line():
    acq = _simulated()
    acq.start()
    _lines(acq, 3)
    first = acq.snapshot().images["height trace"][:3].copy()
    faster = acq.scan.settings.replace(scan_speed=1e-3)
    acq.apply(settings=faster)
    assert acq.snapshot().lines_done == 3  # nothing scanned by apply itself
    while acq.step():
        pass
    snap = acq.snapshot()
    assert snap.changes == (3,) and snap.state == "done"
    h = snap.images["height trace"]
    np.testing.assert_array_equal(h[:3], first)  # the lines before stay as scanned
    reference = _direct(acq, faster).images["height trace"]
    np.testing.assert_allclose(h[3:], reference[3:], rtol=1e-12)


def test_the_simulated_scan_refuses_settings_that_make_another_image():
    acq = _simulated()
    acq.start()
    acq.step()
    with pytest.raises(SettingsRefused, match="another image"):
        acq.apply(settings=acq.scan.settings.replace(pixels=16))
    assert acq.step() and acq.snapshot().lines_done == 2 and acq.snapshot().changes == ()


def test_the_simulated_scan_is_the_scanners_and_holds_its_image_once():
    acq = _simulated()
    acq.pause_after = 5
    acq.start()
    while acq.step():
        if acq.paused:
            break
    assert acq.paused and acq.snapshot().lines_done == 5  # paused by itself after line 5
    acq.resume()
    while acq.step():
        pass
    reference = _direct(acq)
    for name, image in acq.snapshot().images.items():
        np.testing.assert_allclose(image, reference.images[name], rtol=1e-12)
    # the scan writes into the acquisition's arrays: no second image
    assert acq.scan._images is acq._images


def test_the_machine_refuses_new_settings_during_a_scan_and_scans_on(macro):
    snap = _refused_then_done(macro, SCAN, "BUSY", setpoint_force=20e-3)
    assert snap.pixels_done == LINES * LINES
    np.testing.assert_array_equal(snap.images["height"], macro.device.result.heights)
    assert np.isfinite(snap.images["gauge"]).all() and snap.units["gauge"] == ""


def test_a_limit_switch_ends_the_scan_as_a_fault_with_its_lines(macro):
    macro.server.twin.trigger_limit("X", at=(4, 3))
    macro.start(**SCAN)
    while macro.step(0.25):
        pass
    snap = macro.snapshot()
    assert snap.state == "fault" and "DeviceError" in snap.error and not snap.running
    assert snap.lines_done == 4 and np.isfinite(snap.images["height"][:4]).all()
    assert np.isnan(snap.images["height"][5:]).all()


def test_a_cable_pulled_mid_scan_keeps_the_finished_lines():
    host, server = open_twin(MacroAFMTwin())
    session = MacroSession.open(FaultyTransport(host, unplug_after_lines=60), server)
    try:
        session.device.timeout, session.device.stream_timeout = 0.2, 0.5
        session.start(**SCAN)
        while session.step(0.25):
            pass
        snap = session.snapshot()
        assert snap.state == "fault" and "TransportClosed" in snap.error
        assert 2 <= snap.lines_done < LINES
        assert np.isfinite(snap.images["height"][:snap.lines_done]).all()
        assert snap.finished().shape == (snap.lines_done, LINES)
    finally:
        session.close()


def test_a_blank_snapshot_has_every_channel_all_nan():
    snap = Snapshot.blank({"height": "m", "gauge": ""}, (3, 4), 1e-3, main="height")
    assert snap.lines == 3 and snap.pixels == 4 and snap.state == "idle"
    assert all(np.isnan(c.heights).all() for c in snap.channels.values())
    with pytest.raises(ValueError, match="2 finished lines"):
        snap.finished()
    with pytest.raises(ValueError, match="channel"):
        snap.finished("deflection")


def test_step_refuses_a_wait_that_is_no_time():
    acq = _simulated()
    acq.start()
    for bad in (-1.0, float("nan"), float("inf")):
        with pytest.raises(ValueError, match="wait"):
            acq.step(bad)


def test_a_scan_writes_into_given_images_of_its_shape_only():
    acq = _simulated()
    s = acq.scan
    with pytest.raises(ValueError, match="shape"):
        Scan(s.sample, s.tip, s.mode, s.settings, images={"height trace": np.zeros((2, 2))})
    with pytest.raises(TypeError, match="images"):
        Scan(s.sample, s.tip, s.mode, s.settings, images=[])
    images = {}
    Scan(s.sample, s.tip, s.mode, s.settings, images=images).run()
    assert set(images) == set(s.mode.channels) and np.isfinite(images["height trace"]).all()


def test_one_ui_piece_drives_either_implementation():
    from afmsmiler.ui.acquisition import AcquisitionControls
    shown = []
    for acq, start in ((_simulated(), {}), (MacroSession.open(*open_twin(MacroAFMTwin())),
                                            SCAN)):
        controls = AcquisitionControls(start=lambda: None, pause=lambda: None,
                                       resume=lambda: None, stop=lambda: None,
                                       show=lambda: shown.append(1), report=print,
                                       live=lambda: False, unit="pixels")
        acq.start(**start)
        controls.attach(acq)
        controls.run(frame_interval=0.0)
        controls.refresh()
        assert acq.state == "done" and controls.progress.value == LINES * LINES
        assert controls.buttons["stop"].disabled and not controls.buttons["start"].disabled
        if isinstance(acq, MacroSession):
            acq.close()
    assert shown


class _Stuck(Acquisition):
    """A device that answers every read and never finishes a pixel."""

    def __init__(self):
        super().__init__({"height": "m"}, (4, 4), 1e-9)
        self.reads = 0

    def _begin(self, **settings):
        pass

    def _advance(self, wait):
        self.reads += 1


def test_running_to_the_end_gives_up_on_a_scan_that_measures_nothing():
    from afmsmiler.ui.acquisition import AcquisitionControls
    reports, shown = [], []
    controls = AcquisitionControls(start=lambda: None, pause=lambda: None, resume=lambda: None,
                                   stop=lambda: None, show=lambda: shown.append(1),
                                   report=reports.append, live=lambda: False)
    acq = _Stuck()
    acq.start()
    controls.attach(acq)
    controls.IDLE_SECONDS = 0.05   # a minute in a notebook
    controls.run(wait=True, max_line_wait=0.0)  # returns: the loop is bounded in time
    assert acq.state == "aborted" and acq.reads >= 1
    assert len(reports) == 1 and "measured nothing for" in str(reports[0]), reports
    assert shown  # the aborted scan is drawn, its (empty) lines kept
    acq = _Stuck()   # and in steps, whatever they waited
    acq.start()
    controls.attach(acq)
    controls.IDLE_SECONDS, controls.MAX_IDLE_STEPS = 1e9, 300
    controls.run(wait=True, max_line_wait=0.0)
    assert acq.state == "aborted" and acq.reads == 300 and "(300 steps)" in str(reports[-1])


def test_the_educational_session_refuses_settings_and_keeps_lines_on_a_pulled_cable():
    session = _educational()
    try:
        snap = _refused_then_done(session, EDU_SCAN, "between scans", pitch=80e-9)
        assert snap.units["height"] == "m" and snap.pixel_size == pytest.approx(60e-9)
    finally:
        session.close()
    session = _educational(lambda host: FaultyTransport(host, unplug_after_lines=60),
                           timeout=0.2)
    try:
        session.start(**EDU_SCAN)
        snap = _to_end(session)
        assert snap.state == "fault" and "TransportClosed" in snap.error
        assert 2 <= snap.lines_done < LINES
        assert np.isfinite(snap.images["height"][:snap.lines_done]).all()
    finally:
        session.close()


def test_pause_after_a_line_is_ignored_by_a_device_that_cannot_pause():
    session = _educational()
    try:
        session.pause_after = 2
        session.start(**EDU_SCAN)
        while session.step(0.25):
            pass
        assert session.state == "done" and session.snapshot().lines_done == LINES
    finally:
        session.close()
