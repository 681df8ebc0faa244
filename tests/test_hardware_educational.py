"""The educational AFM's protocol, twin and driver: golden frames, the image, and the faults.

The image the driver collects is compared with module (f)'s own scan of the same sample (run here,
not by the twin), within the stated resolution: half a ZS count. The fault tests are part 1's,
through the shared FaultyTransport: damaged, garbage, partial and lost lines; an unplugged
cable; a silent device; a wrong protocol version; a device fault; each a clear error, retries
only where safe, every read bounded, the finished lines kept.
"""
import re
from pathlib import Path

import numpy as np
import pytest

from afmsmiler.controller import ContactLoop
from afmsmiler.hardware import (DeviceError, DeviceNotResponding, FaultyTransport, Frame,
                                ProtocolVersionError, SerialTransport, TransportClosed,
                                decode_frame, encode_frame, open_twin)
from afmsmiler.hardware.educational import (Command, EducationalAFM, EducationalAFMTwin,
                                            ErrorCode, Event, Param, live_view)
from afmsmiler.hardware.educational import codec
from afmsmiler.imaging import ScanSettings, scan
from afmsmiler.imaging.scan_modes import ConstantForce
from afmsmiler.samples import particles
from afmsmiler.scenes.imaging import ImagingScene
from tests.recording import Recorder

HERE = Path(__file__).resolve().parents[1] / "hardware" / "educational_afm"  # the spec
SAMPLE = particles(shape=(64, 64), pixel_size=20e-9, count=6, radius=80e-9, seed=3)
NX, NY, PITCH = 12, 8, 60e-9


def _expected():
    """Module (f)'s scan of the sample, as the instrument's settings ask (m, min at 0)."""
    settings = ScanSettings(NX * PITCH, scan_size_y=NY * PITCH, pixels=NX, lines=NY, seed=0)
    h = scan(SAMPLE, None, ConstantForce(ContactLoop()), settings).images["height trace"]
    return h - h.min()


EXPECTED = _expected()


def _session(wrap=None, timeout=0.3, **twin_kw):
    twin = EducationalAFMTwin(SAMPLE, **twin_kw)
    host, server = open_twin(twin)
    link = wrap(host) if wrap else host
    afm = EducationalAFM(link, timeout=timeout, retries=4)
    return afm, server, host


@pytest.fixture
def session():
    made = []

    def make(wrap=None, **kw):
        afm, server, host = _session(wrap, **kw)
        made.append((server, host))
        return afm
    yield make
    for server, host in made:
        server.stop()
        host.close()


def test_golden_frames_of_the_spec_decode_and_reencode():
    text = (HERE / "PROTOCOL.md").read_text()
    block = text.split("## Golden frames", 1)[1].split("```")[1]
    lines = [ln for ln in block.splitlines() if ln.strip()]
    assert len(lines) >= 20
    for line in lines:
        frame = decode_frame(line.encode())
        assert encode_frame(frame) == line.encode() + b"\n"


def test_protocol_header_matches_the_codec():
    text = (HERE / "protocol.h").read_text()
    defines = dict(re.findall(r"#define (\w+) (\S+)", text))
    assert int(defines.pop("PROTOCOL_VERSION")) == 1
    for prefix, enum in (("CMD_", codec.Command), ("PAR_", codec.Param), ("EVT_", codec.Event)):
        found = {k[len(prefix):]: v.strip('"') for k, v in defines.items() if k.startswith(prefix)}
        assert found == {m.name: m.value for m in enum}
    errors = {k[4:]: int(v) for k, v in defines.items() if k.startswith("ERR_")}
    assert errors == {m.name: m.value for m in codec.ErrorCode}


def test_scan_from_the_twin_matches_module_f_within_half_a_count(session):
    afm = session()
    info = afm.connect()
    assert (info.device, info.protocol, info.z_step) == ("EDUAFM", 1, 100e-12)
    afm.configure(pixels=NX, lines=NY, pitch=PITCH)
    seen, lines = [], []
    image = afm.scan(on_pixel=lambda r, c, z: seen.append((r, c)),
                     on_line=lambda img, n: lines.append((img.shape[0], n)))
    assert image.shape == (NY, NX) and image.pixel_size == pytest.approx(PITCH)
    assert np.max(np.abs(image.heights - EXPECTED)) <= 0.5 * info.z_step + 1e-15
    assert len(seen) == NX * NY
    assert lines == [(k, NY) for k in range(1, NY + 1)]


def test_live_view_draws_each_finished_line_in_the_height_field(session):
    afm = session()
    afm.connect()
    afm.configure(pixels=NX, lines=NY, pitch=PITCH)
    rec = Recorder()
    scene = ImagingScene(SAMPLE, vis=rec, camera=False)
    image = afm.scan(on_line=live_view(scene))
    assert scene.image_lines == NY
    sets = [c for c in rec.calls if c[0] == "set_object" and c[1].endswith("/image")]
    assert len(sets) == NY - 1              # from the second line on (a field needs two rows)
    assert image.shape == (NY, NX)


@pytest.mark.parametrize("faults", [dict(corrupt=0.05), dict(garbage=0.05),
                                    dict(partial=0.05), dict(drop=0.03),
                                    dict(corrupt=0.03, garbage=0.03, partial=0.03, drop=0.02)])
def test_damaged_lines_are_recovered_and_the_image_is_exact(session, faults):
    wrapped = []

    def wrap(host):
        wrapped.append(FaultyTransport(host, seed=11, **faults))
        return wrapped[0]
    afm = session(wrap)
    afm.connect()
    afm.configure(pixels=NX, lines=NY, pitch=PITCH)
    image = afm.scan()
    assert np.max(np.abs(image.heights - EXPECTED)) <= 0.5 * afm.info.z_step + 1e-15
    injected = sum(v for k, v in wrapped[0].counts.items() if k != "lines")
    assert injected > 0
    assert afm.stats["retries"] + afm.stats["bad_lines"] + afm.stats["refetched_lines"] > 0


def test_unplugged_mid_scan_keeps_the_finished_lines(session):
    afm = session(lambda host: FaultyTransport(host, unplug_after_lines=60))
    afm.connect()
    afm.configure(pixels=NX, lines=NY, pitch=PITCH)
    with pytest.raises(TransportClosed) as info:
        afm.scan()
    partial = info.value.partial
    assert partial is not None and 1 <= partial.shape[0] < NY
    rows = partial.shape[0]
    assert np.max(np.abs(partial.heights - EXPECTED[:rows])) <= 0.5 * afm.info.z_step + 1e-15


def test_a_silent_device_raises_in_bounded_time_with_the_partial_image(session, hang_guard):
    afm = session(lambda host: FaultyTransport(host, silent_after_lines=50), timeout=0.1)
    afm.connect()
    afm.configure(pixels=NX, lines=NY, pitch=PITCH)
    with hang_guard(10, expected=0.6), pytest.raises(DeviceNotResponding) as info:
        afm.scan()
    assert info.value.partial is None or info.value.partial.shape[0] < NY


def test_silent_before_the_reply_exhausts_the_retries(session, hang_guard):
    afm = session(lambda host: FaultyTransport(host, silent_after_lines=0), timeout=0.05)
    with hang_guard(5, expected=0.25), \
            pytest.raises(DeviceNotResponding, match="did not answer ID after 5 tries"):
        afm.connect()  # 5 tries x 0.05 s


def test_wrong_protocol_version_is_refused():
    twin = EducationalAFMTwin(SAMPLE)
    twin.protocol_version = 2
    host, server = open_twin(twin)
    try:
        afm = EducationalAFM(host, timeout=0.3)
        with pytest.raises(ProtocolVersionError, match="version 2.*version 1"):
            afm.connect()
        assert afm.info is None
    finally:
        server.stop()
        host.close()


def test_a_probe_fault_stops_the_scan_with_the_finished_lines(session):
    afm = session(fault_at=NX * 3 + 5)
    afm.connect()
    afm.configure(pixels=NX, lines=NY, pitch=PITCH)
    with pytest.raises(DeviceError) as info:
        afm.scan()
    assert info.value.code == ErrorCode.SENSOR
    assert info.value.partial.shape == (3, NX)


def test_device_errors_are_named(session):
    afm = session()
    afm.connect()
    with pytest.raises(ValueError, match="ZSTEP .* is read-only"):
        afm.set(Param.ZSTEP, 5)                       # the table refuses it, nothing sent
    with pytest.raises(ValueError, match=r"NX \(pixels per line\) must be an integer 2..512"):
        afm.set(Param.NX, 513)
    with pytest.raises(DeviceError) as info:
        afm.request(Command.SET, Param.ZSTEP, 5)      # the device refuses it too
    assert info.value.code == ErrorCode.BAD_ARGUMENT and info.value.word == "ZS"
    with pytest.raises(DeviceError) as info:
        afm.request(Command.ABORT)                    # nothing to abort
    assert info.value.code == ErrorCode.STATE
    with pytest.raises(ValueError, match="pitch"):
        afm.configure(pixels=8, pitch=1e-3)


def test_twin_alone_streams_lines_and_done():
    twin = EducationalAFMTwin(SAMPLE, pixel_time=1e-3)
    boot = twin.poll(0.0)
    assert boot == [Frame(0, "EV", ("BOOT",))]
    for code, args in (("SP", ("NX", 4)), ("SP", ("NY", 2)), ("SP", ("DX", 50))):
        assert twin.handle(Frame(1, code, args))[0].code == "OK"
    assert twin.handle(Frame(2, "SS", ())) == [Frame(2, "OK", ("SS",))]
    assert twin.next_due() == pytest.approx(1e-3)
    frames = twin.poll(0.0045)
    assert [f.code for f in frames] == ["PX", "PX", "PX", "PX", "LN"]
    assert twin.handle(Frame(3, "ST", ()))[0].args == ("ST", "SCANNING", 1, 0)
    frames = twin.poll(1.0)
    assert frames[-1] == Frame(0, "EV", (Event.DONE.value,))
    assert twin.next_due() is None


@pytest.mark.slow
def test_over_a_pty_with_pyserial_like_a_real_port():
    twin = EducationalAFMTwin(SAMPLE)
    path, server = open_twin(twin, pty=True)
    port = SerialTransport(path)
    try:
        afm = EducationalAFM(port, timeout=0.5)
        afm.connect()
        afm.configure(pixels=NX, lines=NY, pitch=PITCH)
        image = afm.scan()
        assert np.max(np.abs(image.heights - EXPECTED)) <= 0.5 * afm.info.z_step + 1e-15
    finally:
        port.close()
        server.stop()


@pytest.mark.hardware
def test_a_real_instrument_scans_when_one_is_plugged_in():
    """The same scan against the instrument: AFMSMILER_HARDWARE=1 and AFMSMILER_EDUAFM_PORT."""
    import os
    port = os.environ.get("AFMSMILER_EDUAFM_PORT")
    if not os.environ.get("AFMSMILER_HARDWARE") or not port:
        pytest.skip("no educational AFM: set AFMSMILER_HARDWARE=1 and AFMSMILER_EDUAFM_PORT")
    link = SerialTransport(port)
    try:
        afm = EducationalAFM(link, timeout=2.0)
        assert afm.connect().device == "EDUAFM"
        afm.configure(pixels=8, lines=4, pitch=PITCH)
        image = afm.scan()
        assert image.shape == (4, 8) and np.all(np.isfinite(image.heights))
    finally:
        link.close()
