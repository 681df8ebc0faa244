"""The macroscopic AFM's driver, codec and twin (issue 13 items 2 and 3), without hardware.

- a table of (call, bytes sent, device reply, parsed value) run against a scripted transport,
  scikit-rf's driver tests (``skrf/vi``) without their mocked constructor;
- the twin through a memory link and through a pty opened by pyserial scans a full image that
  matches the virtual sample (its surface as the needle meets it: module (f)'s dilation) within
  the z micro-step and the pitch;
- every fault of issue 13 through FaultyTransport: a clear error, retries where safe, no hang, the
  finished lines kept and saved;
- the ruler's stiffness, resonance and gauge counts against the closed forms (Euler-Bernoulli:
  k = E w h^3 / (4 L^3), f1 = 1.8751^2 / (2 pi L^2) sqrt(E h^2 / (12 rho)); strain at the gauge
  6 F (L - x) / (E w h^2); the HX711's counts from its datasheet);
- the ``hardware`` marker runs the same connect/scan against a real board.
"""
import math
import os
import re
import threading
import time
from pathlib import Path

import numpy as np
import pytest

from afmsmiler.hardware import FrameError as errors_FrameError
from afmsmiler.hardware import (DeviceError, DeviceNotResponding, FaultyTransport, HardwareError,
                                ProtocolVersionError, SerialTransport, TransportClosed,
                                TransportTimeout, open_twin)
from afmsmiler.hardware.errors import ChecksumError
from afmsmiler.hardware.framing import Frame, decode_frame, encode_frame
from afmsmiler.hardware.macro import (Command, ErrorCode, ErrorReply, Event, EventMsg, Flag,
                                      GaugeCalibration, LineEnd, MacroAFM, MacroAFMCodec,
                                      MacroAFMTwin, Param, Pixel, Reply, State, Status,
                                      printed_sample, ruler)
from afmsmiler.hardware.macro.device import DeviceInfo
from afmsmiler.hardware.macro.twin import _move_time
from afmsmiler.samples import Sample, load

REPO = Path(__file__).resolve().parents[1]


@pytest.fixture(autouse=True)
def no_leaked_threads():
    before = set(threading.enumerate())
    yield
    deadline = time.monotonic() + 3.0
    while time.monotonic() < deadline:
        leaked = [t for t in threading.enumerate() if t not in before and t.is_alive()]
        if not leaked:
            break
        time.sleep(0.01)
    assert not leaked, f"threads left running: {leaked}"


def crc8_bitwise(data: bytes) -> int:
    crc = 0
    for byte in data:
        crc ^= byte
        for _ in range(8):
            crc = ((crc << 1) ^ 0x07) & 0xFF if crc & 0x80 else (crc << 1) & 0xFF
    return crc


def wire(body: str) -> bytes:
    return body.encode() + b"*%02X\n" % crc8_bitwise(body.encode())


# -- the codec ----------------------------------------------------------------------------------
def test_codec_enums_follow_the_contract():
    assert {c.name: c.value for c in Command} == {
        "IDENTIFY": "ID", "SET": "SP", "GET": "GP", "HOME": "HM", "START": "SS", "PAUSE": "PA",
        "RESUME": "RS", "ABORT": "AB", "STATUS": "ST", "GAUGE": "RG", "GETLINE": "GL"}
    assert {e.name: e.value for e in ErrorCode} == {
        "CHECKSUM": 1, "UNKNOWN_COMMAND": 2, "BAD_ARGUMENT": 3, "BUSY": 4, "NOT_HOMED": 5,
        "LIMIT": 6, "ESTOP": 7, "SENSOR": 8, "MALFORMED": 9, "STATE": 10}
    assert [e.value for e in Event] == ["BOOT", "HOMED", "DONE", "PAUSED", "ABORTED", "LIMIT",
                                        "ESTOP", "BUTTON"]
    assert {p.name: p.value for p in Param} == {
        "NX": "NX", "NY": "NY", "PITCH": "DX", "ZSTEP": "ZS", "SETPOINT": "SE", "MODE": "MO",
        "LIFT": "LI", "SPEED": "VE", "ACCEL": "AC", "PRESET": "PR"}


@pytest.mark.parametrize("line, message", [
    (wire("0 PX 3 17 -1205 4711"), Pixel(3, 17, -1205, 4711)),
    (wire("0 LN 3 128"), LineEnd(3, 128)),
    (wire("0 EV LIMIT X"), EventMsg(Event.LIMIT, "X")),
    (wire("0 EV BUTTON 2"), EventMsg(Event.BUTTON, 2)),
    (wire("0 EV DONE"), EventMsg(Event.DONE)),
    (wire("0 ER 6"), ErrorReply(0, ErrorCode.LIMIT)),
    (wire("7 ER 3 DX"), ErrorReply(7, ErrorCode.BAD_ARGUMENT, "DX")),
    (wire("7 OK GP DX 200"), Reply(7, Command.GET, ("DX", 200))),
    (wire("1 OK ID MACROAFM 1 0.1.0"), Reply(1, Command.IDENTIFY, ("MACROAFM", 1, "0.1.0"))),
])
def test_codec_parses(line, message):
    assert MacroAFMCodec.parse(line) == message


@pytest.mark.parametrize("line", [wire("0 PX 1 2 3"), wire("0 PX 1 2 3 X"), wire("0 QQ 1"),
                                  wire("0 OK ST"), wire("0 EV"), wire("5 PX 1 2 3 4")])
def test_codec_rejects_frames_outside_the_protocol(line):
    with pytest.raises(ValueError):
        MacroAFMCodec.parse(line)


def test_status_reply():
    reply = MacroAFMCodec.parse(wire("4 OK ST PAUSED 12 5 3"))
    status = MacroAFMCodec.status(reply)
    assert status == Status(State.PAUSED, 12, 5, Flag.HOMED | Flag.LIMIT_X)
    assert status.homed
    every = MacroAFMCodec.status(MacroAFMCodec.parse(wire("4 OK ST FAULT 0 0 31")))
    assert every.flags == Flag.HOMED | Flag.LIMIT_X | Flag.LIMIT_Y | Flag.LIMIT_Z | Flag.ESTOP


@pytest.mark.parametrize("flags, unknown", [(32, "32"), (16 + 64, "64"), (1 << 30, str(1 << 30)),
                                            (-1, "-1")])
def test_status_refuses_flag_bits_it_does_not_know(flags, unknown):
    """A bit that protocol version 1 does not name is a FrameError (not a ChecksumError), never
    silently dropped: it may be a switch or an E-stop the driver would not see."""
    reply = MacroAFMCodec.parse(wire(f"4 OK ST IDLE 0 0 {flags}"))
    with pytest.raises(errors_FrameError, match=f"flags {flags} .*\\({unknown};") as info:
        MacroAFMCodec.status(reply)
    assert not isinstance(info.value, ChecksumError)
    # the driver's status() raises it too (no retry: the line itself was sound)
    link = Scripted([("1 ST", [f"1 OK ST IDLE 0 0 {flags}"])])
    with pytest.raises(errors_FrameError, match="does not know"):
        MacroAFM(link, timeout=0.05, retries=2).status()
    assert link.sent == [wire("1 ST")]


def _defines(path):
    text = path.read_text()
    return dict(re.findall(r"#define\s+(\w+)\s+(\S+)", text))


def golden_frames(text: str) -> list:
    """(mark, line, answer) of every line of the spec's ``frames`` blocks: ``>`` host to device (a
    line at column 0), ``<`` device to host (indented by four spaces), with answer None; and
    ``!`` a line that is not a valid frame on purpose, with the device's answer (the spec's table
    of such lines: ``| ! `line` | `answer` |``)."""
    out = []
    for block in re.findall(r"^```frames\n(.*?)^```", text, re.M | re.S):
        for line in block.splitlines():
            if line.strip():
                out.append(("<" if line.startswith("    ") else ">", line.strip(), None))
    out += [("!", line, answer)
            for line, answer in re.findall(r"^\| ! `([^`]*)` \| `([^`]*)` \|", text, re.M)]
    return out


def check_unreadable(line: str, answer: str) -> int:
    """Check one row of the table of unreadable lines; its answer code (1 or 9).

    The answer is the frame ``0 ER 1`` or ``0 ER 9`` exactly; ``decode_frame`` rejects the line
    with a ChecksumError for ``0 ER 1`` and with a FrameError that is not a ChecksumError for
    ``0 ER 9`` (the device and the twin's server answer by that distinction)."""
    reply = decode_frame(answer.encode())
    assert encode_frame(reply) == answer.encode() + b"\n", answer
    assert (reply.seq, reply.code) == (0, "ER") and reply.args in ((1,), (9,)), answer
    code = reply.args[0]
    with pytest.raises(errors_FrameError) as info:
        decode_frame(line.encode())
    assert isinstance(info.value, ChecksumError) == (code == 1), \
        f"{line!r} is answered {answer!r} but decode_frame raises {info.value!r}"
    return code


def check_golden(frames) -> int:
    for mark, text, answer in frames:
        assert mark in "<>!", f"unknown mark {mark!r}"
        if mark == "!":
            check_unreadable(text, answer)
            continue
        assert answer is None
        frame = decode_frame(text.encode())
        assert encode_frame(frame) == text.encode() + b"\n"
        if mark == "<":
            MacroAFMCodec.message(frame)  # every device frame is a message of the protocol
    return len(frames)


def replay_unreadable(rows) -> list:
    """Send each (line, answer) to a MacroAFMTwin served by TwinServer on a MemoryTransport pair;
    the (line, expected, got) that differ (the server answers malformed lines, as the firmware)."""
    from afmsmiler.hardware.transport import MemoryTransport
    from afmsmiler.hardware.twin import TwinServer

    host, device_end = MemoryTransport.pair()
    server = TwinServer(MacroAFMTwin(sample=printed_sample(pixels=8)), device_end,
                        time_scale=0.0).start()
    try:
        host.write(wire("200 ID"))  # past the boot event: the reply to ID comes last
        while not host.readline(2.0).startswith(b"200 OK ID "):
            pass
        differ = []
        for line, answer in rows:
            host.write(line.encode() + b"\n")
            got = host.readline(2.0).decode()
            if got != answer:
                differ.append((line, answer, got))
        return differ
    finally:
        server.stop()
        host.close()


def test_golden_frames_parser_on_a_sample_block():
    text = ("x\n```frames\n1 ID*C1\n    1 OK ID MACROAFM 1 0.1.0*22\n```\n\n"
            "| line | answer |\n|---|---|\n| ! `1 ID*C2` | `0 ER 1*DF` |\n"
            "| ! `1  ID*84` | `0 ER 9*E7` |\n")
    frames = golden_frames(text)
    assert [m for m, _, _ in frames] == [">", "<", "!", "!"]
    assert frames[2:] == [("!", "1 ID*C2", "0 ER 1*DF"), ("!", "1  ID*84", "0 ER 9*E7")]
    assert check_golden(frames) == 4


@pytest.mark.parametrize("line, answer", [
    ("18  ST*1D", "0 ER 9*E7"),  # the spec's old row: its checksum is wrong, so ER 1, not ER 9
    ("17 GP NX*4C", "0 ER 1*DF"),  # a valid frame listed as unreadable
    ("17 GP NX*00", "0 ER 9*E7"),  # a checksum error listed as malformed
    ("17 GP NX*00", "0 ER 1*00"),  # the answer's own checksum wrong
    ("17 GP NX*00", "0 ER 3*D1"),  # neither 1 nor 9
])
def test_check_golden_catches_a_wrong_unreadable_row(line, answer):
    with pytest.raises((AssertionError, pytest.fail.Exception, errors_FrameError)):
        check_golden([("!", line, answer)])


def test_golden_frames_of_the_protocol_spec():
    spec = REPO / "hardware" / "macro_afm" / "PROTOCOL.md"
    if not spec.exists():
        pytest.skip(f"{spec.relative_to(REPO)} not in this checkout (h-firmware writes it)")
    frames = golden_frames(spec.read_text())
    assert check_golden(frames) > 10, "PROTOCOL.md lists (almost) no golden frames"
    codes = [check_unreadable(line, answer) for mark, line, answer in frames if mark == "!"]
    assert 1 in codes and 9 in codes  # both decoder paths are exercised
    # an integer outside int32 is malformed, not a word
    assert any(re.search(r" -?\d{10,}\*", line) for mark, line, _ in frames if mark == "!")


def test_twin_server_answers_the_specs_unreadable_lines():
    """Every row of PROTOCOL.md's table, sent to the twin's server: exactly the table's answer."""
    spec = REPO / "hardware" / "macro_afm" / "PROTOCOL.md"
    if not spec.exists():
        pytest.skip(f"{spec.relative_to(REPO)} not in this checkout (h-firmware writes it)")
    rows = [(line, answer) for mark, line, answer in golden_frames(spec.read_text())
            if mark == "!"]
    assert len(rows) >= 2
    assert replay_unreadable(rows) == []


# -- the driver against a scripted transport (scikit-rf style) -----------------------------------
class Scripted:
    """A transport that answers each expected line with the scripted reply lines."""

    def __init__(self, script):
        self.script = {wire(sent): [wire(r) for r in replies] for sent, replies in script}
        self.sent = []
        self.pending = []

    def write(self, data):
        self.sent.append(data)
        self.pending += self.script.get(data, [])

    def readline(self, timeout):
        if self.pending:
            return self.pending.pop(0).rstrip(b"\n")
        raise TransportTimeout("scripted: nothing to read")

    def close(self):
        pass


CAL = GaugeCalibration.from_ruler()
TABLE = [
    # (name, call, [(line sent, [reply lines])], parsed value)
    ("connect", lambda afm: afm.connect(),
     [("1 ID", ["0 EV BOOT", "1 OK ID MACROAFM 1 0.1.0"]), ("2 GP ZS", ["2 OK GP ZS 2500"])],
     DeviceInfo("MACROAFM", 1, "0.1.0", 2.5e-6)),
    ("status", lambda afm: afm.status(), [("1 ST", ["1 OK ST SCANNING 3 7 1"])],
     Status(State.SCANNING, 3, 7, Flag.HOMED)),
    ("gauge", lambda afm: afm.gauge(), [("1 RG", ["1 OK RG 4711"])], 4711),
    ("force", lambda afm: afm.force(), [("1 RG", ["1 OK RG 13143"])],
     pytest.approx(13143 / CAL.counts_per_newton)),
    ("get", lambda afm: afm.get(Param.NX), [("1 GP NX", ["1 OK GP NX 128"])], 128),
    ("pitch", lambda afm: afm.configure(pitch=0.2e-3), [("1 SP DX 200", ["1 OK SP DX 200"])],
     {Param.PITCH: 200}),
    ("setpoint force", lambda afm: afm.configure(setpoint_force=10e-3),
     [(f"1 SP SE {round(CAL.counts(10e-3))}", [f"1 OK SP SE {round(CAL.counts(10e-3))}"])],
     {Param.SETPOINT: round(CAL.counts(10e-3))}),
    ("mode", lambda afm: afm.configure(mode="jumping"), [("1 SP MO 1", ["1 OK SP MO 1"])],
     {Param.MODE: 1}),
    ("size", lambda afm: afm.configure(pixels=64, lines=32),
     [("1 SP NX 64", ["1 OK SP NX 64"]), ("2 SP NY 32", ["2 OK SP NY 32"])],
     {Param.NX: 64, Param.NY: 32}),
    ("speed", lambda afm: afm.configure(step_rate=1500, step_acceleration=8000),
     [("1 SP VE 1500", ["1 OK SP VE 1500"]), ("2 SP AC 8000", ["2 OK SP AC 8000"])],
     {Param.SPEED: 1500, Param.ACCEL: 8000}),
    ("pause", lambda afm: afm.pause(), [("1 PA", ["1 OK PA", "0 EV PAUSED"])], None),
    ("resume", lambda afm: afm.resume(), [("1 RS", ["1 OK RS"])], None),
    ("abort", lambda afm: afm.abort(), [("1 AB", ["1 OK AB", "0 EV ABORTED"])], None),
    ("home", lambda afm: afm.home(), [("1 HM", ["1 OK HM", "0 EV HOMED"])], None),
    ("stale reply ignored", lambda afm: afm.gauge(),
     [("1 RG", ["9 OK RG 1", "0 PX 0 0 1 1", "1 OK RG 5"])], 5),
]


@pytest.mark.parametrize("name, call, script, value", TABLE, ids=[t[0] for t in TABLE])
def test_driver_table(name, call, script, value):
    link = Scripted(script)
    afm = MacroAFM(link, timeout=0.05, retries=0)
    assert call(afm) == value
    assert link.sent == [wire(sent) for sent, _ in script]


@pytest.mark.parametrize("reply, code, word", [("1 ER 4", ErrorCode.BUSY, ""),
                                               ("1 ER 3 NX", ErrorCode.BAD_ARGUMENT, "NX")])
def test_driver_error_reply(reply, code, word):
    afm = MacroAFM(Scripted([("1 SP NX 5", [reply])]), timeout=0.05)
    with pytest.raises(DeviceError) as info:
        afm.set(Param.NX, 5)
    assert info.value.code == code and info.value.word == word
    assert "SP" in str(info.value) and code.name in str(info.value)


def test_driver_resends_the_same_seq_after_a_checksum_error():
    link = Scripted([("1 RG", ["0 ER 1"])])
    link.script[wire("1 RG")] = [wire("0 ER 1")]
    calls = []
    original = link.write

    def write(data):
        calls.append(data)
        original(data)
        if len(calls) == 2:
            link.pending = [wire("1 OK RG 42")]

    link.write = write
    afm = MacroAFM(link, timeout=0.05, retries=2)
    assert afm.gauge() == 42
    assert calls == [wire("1 RG"), wire("1 RG")]  # the same SEQ: a safe retry


def test_driver_gives_up_after_its_retries_in_bounded_time(hang_guard):
    link = Scripted([])
    afm = MacroAFM(link, timeout=0.05, retries=3)
    with hang_guard(5, expected=0.2), pytest.raises(DeviceNotResponding, match="3 retries"):
        afm.status()  # 4 tries x 0.05 s
    assert link.sent == [wire("1 ST")] * 4  # the retries counted, not timed


def test_seq_wraps_255_to_1():
    afm = MacroAFM(Scripted([]), timeout=0.01)
    seqs = [afm._next_seq() for _ in range(256)]
    assert seqs[0] == 1 and seqs[254] == 255 and seqs[255] == 1


@pytest.mark.parametrize("values, name", [
    ({"pixels": 0}, "pixels"), ({"pixels": 2.5}, "pixels"), ({"lines": 2000}, "lines"),
    # the firmware's limits (config.h): 128 pixels per line, a 25 um pitch, presets 0..3
    ({"pixels": 129}, "pixels"), ({"pixels": 1024}, "pixels"), ({"pitch": 1e-6}, "pitch"),
    ({"preset": 4}, "preset"), ({"preset": 9}, "preset"), ({"step_rate": 20_000}, "step_rate"),
    ({"pitch": -1e-3}, "pitch"), ({"pitch": float("nan")}, "pitch"),
    ({"setpoint_force": 10.0}, "setpoint_force"), ({"mode": "tapping"}, "mode"),
    ({"step_rate": 0}, "step_rate"), ({"pixels": 64, "pitch": 1.0}, "pitch"),
])
def test_configure_validates_before_sending_anything(values, name):
    link = Scripted([])
    afm = MacroAFM(link, timeout=0.01)
    with pytest.raises(ValueError, match=name):
        afm.configure(**values)
    assert link.sent == []


def test_configure_rejects_unknown_keywords():
    with pytest.raises(TypeError, match="speed"):
        MacroAFM(Scripted([])).configure(speed=3)


def test_device_rejects_a_non_transport():
    with pytest.raises(TypeError, match="transport"):
        MacroAFM("/dev/ttyACM0")


# -- the twin: full scans -----------------------------------------------------------------------
def _twin(**kwargs):
    kwargs.setdefault("sample", printed_sample(pixels=32, pixel_size=0.4e-3, height=2e-3))
    return MacroAFMTwin(**kwargs)


def _matches(image: Sample, twin: MacroAFMTwin) -> float:
    """Largest miss (m) of the image against the needle's surface, within one pitch.

    Each pixel's height, less the constant offset (the base and the setpoint's deflection), must
    lie within the surface's range over the pixels one pitch around it, widened by one z
    micro-step.
    """
    rows, cols = image.shape
    apex = twin.apex.heights[:rows, :cols]
    offset = float(np.median(image.heights - apex))
    h = image.heights - offset
    pad = np.pad(apex, 1, mode="edge")
    near = np.stack([pad[1 + i:1 + i + rows, 1 + j:1 + j + cols]
                     for i in (-1, 0, 1) for j in (-1, 0, 1)])
    below = np.maximum(near.min(axis=0) - h, 0.0)
    above = np.maximum(h - near.max(axis=0), 0.0)
    return float(np.max(np.maximum(below, above)))


def _scan(twin, host, *, mode="jumping", pixels=32, lines=32, timeout=0.3, **kw):
    afm = MacroAFM(host, timeout=timeout, stream_timeout=1.0, **kw)
    afm.connect()
    afm.configure(pixels=pixels, lines=lines, pitch=0.4e-3, mode=mode, setpoint_force=10e-3,
                  lift=0.5e-3)
    afm.home()
    return afm


@pytest.mark.parametrize("mode", ["jumping", "contact"])
def test_twin_scan_matches_the_virtual_sample(mode):
    twin = _twin(friction=0.0)
    host, server = open_twin(twin)
    try:
        afm = _scan(twin, host, mode=mode)
        seen = []
        image = afm.scan(seen.append)
    finally:
        server.stop()
    assert image.shape == (32, 32)
    assert image.pixel_size == pytest.approx(0.4e-3)
    assert _matches(image, twin) <= twin.z_step * 1.0001
    assert len(seen) == 32 * 32 and seen[-1].fraction == 1.0
    assert seen[0].image is seen[-1].image  # one live array for the live figure
    np.testing.assert_array_equal(seen[-1].image, image.heights)


def test_twin_scan_through_a_pty_opened_by_pyserial():
    twin = _twin()
    path, server = open_twin(twin, pty=True)
    host = SerialTransport(path)
    try:
        afm = _scan(twin, host, pixels=16, lines=8)
        image = afm.scan()
    finally:
        host.close()
        server.stop()
    assert image.shape == (8, 16)
    assert _matches(image, twin) <= twin.z_step * 1.0001


@pytest.mark.slow
def test_contact_mode_friction_spoils_tall_walls_and_jumping_mode_does_not():
    images = {}
    tall = printed_sample(pixels=32, pixel_size=0.4e-3, height=3e-3)  # 3 mm walls, 1.6 mm apart
    for mode in ("contact", "jumping"):
        twin = _twin(sample=tall, friction=0.5, tip_radius=0.1e-3)
        host, server = open_twin(twin)
        try:
            images[mode] = _scan(twin, host, mode=mode).scan()
        finally:
            server.stop()
    assert _matches(images["jumping"], twin) <= twin.z_step * 1.0001
    assert _matches(images["contact"], twin) > 0.2e-3  # the caught needle misses the walls


def test_saved_image_keeps_its_pixel_size(tmp_path):
    twin = _twin()
    host, server = open_twin(twin)
    try:
        afm = _scan(twin, host, pixels=8, lines=4)
        image = afm.scan()
        path = afm.save(tmp_path / "scan.gwy")
    finally:
        server.stop()
    back = load(path, "height")
    assert back.pixel_size == pytest.approx(0.4e-3)
    np.testing.assert_allclose(back.heights, image.heights)


# -- faults -------------------------------------------------------------------------------------
# The faulty runs keep a real machine's ratio of pixel time to the host's timeouts: the twin at a
# tenth of the machine's pace (about 25 ms a pixel in contact mode) and 50 ms reply timeouts. At
# time_scale 0 the twin would stream whole lines while the host waits out one lost reply, and a
# device keeps only its last two lines for GL.
FAULT_PACE = 0.1


def _low(**kwargs):
    """A twin over a low grating (0.2 mm) and 10 mm of z travel: a quick scan at FAULT_PACE."""
    return _twin(sample=printed_sample(pixels=32, pixel_size=0.4e-3, height=0.2e-3),
                 travel=(0.22, 0.22, 0.01), **kwargs)


def _faulty_run(twin, faults, *, retries=6, pixels=8, lines=8, timeout=0.05, pace=FAULT_PACE):
    host, server = open_twin(twin, time_scale=pace)
    link = FaultyTransport(host, **faults)
    try:
        afm = _scan(twin, link, mode="contact", pixels=pixels, lines=lines, retries=retries,
                    timeout=timeout)
        t0 = time.monotonic()
        try:
            image = afm.scan()
            error = None
        except HardwareError as exc:
            image, error = None, exc
        elapsed = time.monotonic() - t0
    finally:
        server.stop()
    return afm, image, error, elapsed, link


@pytest.mark.slow
@pytest.mark.parametrize("faults", [
    {"garbage": 0.05, "seed": 1}, {"partial": 0.03, "seed": 2}, {"corrupt": 0.03, "seed": 3},
    {"drop": 0.03, "seed": 4}, {"garbage": 0.02, "partial": 0.02, "corrupt": 0.02, "drop": 0.02,
                                "seed": 5},
], ids=["garbage", "partial", "checksum", "dropped", "all"])
def test_noisy_line_still_gives_the_full_image(faults, hang_guard):
    twin = _low(friction=0.0)
    afm, image, error, elapsed, link = _faulty_run(twin, faults)
    assert error is None, error
    assert sum(link.counts[k] for k in ("garbage", "partial", "corrupt", "drop")) > 0
    assert _matches(image, twin) <= twin.z_step * 1.0001
    hang_guard.check(elapsed, 60, expected=3.5)  # about 3.5 s on one loaded core
    # retries were safe: the twin never executed one command twice
    keys = [(f.seq, f.code, f.args) for f in twin.executed]
    assert all(a != b for a, b in zip(keys, keys[1:]))


@pytest.mark.slow
def test_checksum_errors_are_retried_with_the_same_seq():
    twin = _low(friction=0.0)
    afm, image, error, _, link = _faulty_run(twin, {"corrupt": 0.1, "seed": 11}, retries=10)
    assert error is None, error
    assert afm.retried > 0 and link.counts["corrupt"] > 0
    assert afm.garbage > 0


@pytest.mark.slow
def test_unplugged_mid_scan_keeps_the_finished_lines(tmp_path):
    twin = _low()
    afm, image, error, elapsed, _ = _faulty_run(twin, {"unplug_after_lines": 60}, pixels=16)
    assert isinstance(error, TransportClosed)
    assert "unplugged" in str(error)
    partial = error.partial
    assert partial is not None and 1 <= partial.shape[0] < 8 and partial.shape[1] == 16
    assert not np.isnan(partial.heights).any()
    assert afm.result is partial
    saved = load(afm.save(tmp_path / "partial.gwy"), "height")
    assert saved.shape == partial.shape and saved.pixel_size == pytest.approx(0.4e-3)


def test_unplugged_at_full_speed_keeps_the_finished_lines(hang_guard):
    twin = _low()
    _, _, error, elapsed, _ = _faulty_run(twin, {"unplug_after_lines": 100}, pixels=16, pace=0)
    assert isinstance(error, TransportClosed)
    hang_guard.check(elapsed, 5, expected=0.1)
    assert error.partial.shape[1] == 16 and 1 <= error.partial.shape[0] < 8


@pytest.mark.slow
def test_silent_device_raises_device_not_responding_in_bounded_time(hang_guard):
    twin = _low()
    afm, image, error, elapsed, _ = _faulty_run(twin, {"silent_after_lines": 50}, retries=2,
                                                pixels=16)
    assert isinstance(error, DeviceNotResponding)
    assert error.partial is not None and error.partial.shape[0] >= 1
    # the lines before the silence, stream_timeout 1 s, ST's 3 x 50 ms: about 3 s
    hang_guard.check(elapsed, 30, expected=3)


def test_wrong_firmware_version_is_refused_naming_both():
    twin = _twin()
    twin.protocol_version = 2
    host, server = open_twin(twin)
    try:
        with pytest.raises(ProtocolVersionError, match="version 2.*version 1"):
            MacroAFM(host, timeout=0.2).connect()
    finally:
        server.stop()


def test_limit_switch_mid_scan(tmp_path):
    twin = _twin()
    twin.trigger_limit("X", at=(5, 3))
    host, server = open_twin(twin)
    try:
        afm = _scan(twin, host, pixels=16, lines=16)
        with pytest.raises(DeviceError) as info:
            afm.scan()
        assert afm.status().state == State.FAULT
        with pytest.raises(DeviceError, match="NOT_HOMED"):
            afm._command(Command.START)
        afm.home()  # homing clears the fault
        assert afm.status() == Status(State.IDLE, 0, 0, Flag.HOMED)
    finally:
        server.stop()
    error = info.value
    assert error.code == ErrorCode.LIMIT and error.word == "X" and "LIMIT" in str(error)
    assert error.partial.shape == (5, 16)
    assert _matches(error.partial, twin) <= twin.z_step * 1.0001
    assert load(afm.save(tmp_path / "limit.gwy"), "height").shape == (5, 16)


def test_scan_larger_than_the_travel_is_refused():
    twin = _twin(travel=(4e-3, 0.22, 0.05))  # 4 mm of x: 16 pixels at 0.4 mm span 6 mm
    host, server = open_twin(twin)
    try:
        afm = _scan(twin, host, pixels=16, lines=4)
        with pytest.raises(DeviceError) as info:
            afm.scan()
    finally:
        server.stop()
    assert info.value.code == ErrorCode.BAD_ARGUMENT and info.value.command == "SS"
    assert info.value.partial is None  # not one line finished


def test_start_before_homing_is_refused():
    twin = _twin()
    host, server = open_twin(twin)
    try:
        afm = MacroAFM(host, timeout=0.2)
        afm.connect()
        with pytest.raises(DeviceError, match="NOT_HOMED"):
            afm.scan()
    finally:
        server.stop()


# -- pause, resume, abort -------------------------------------------------------------------------
def test_pause_resume_and_abort_from_the_callback():
    twin = _twin()
    host, server = open_twin(twin)
    states = []
    try:
        afm = _scan(twin, host, pixels=8, lines=8)

        def on_pixel(p):
            if p.done == 10:
                afm.pause()
                states.append(afm.status().state)
                afm.resume()
                states.append(afm.status().state)
            if p.done == 30:
                afm.abort()

        image = afm.scan(on_pixel)
    finally:
        server.stop()
    assert states == [State.PAUSED, State.SCANNING]
    assert 3 <= image.shape[0] < 8 and image.shape[1] == 8
    assert any(e.event == Event.ABORTED for e in afm.events)


@pytest.mark.slow
def test_pause_from_another_thread_while_scanning():
    twin = _low()
    host, server = open_twin(twin, time_scale=0.01)  # about 25 ms a pixel
    try:
        afm = _scan(twin, host, pixels=8, lines=4)
        result = {}
        first = threading.Event()

        def run():
            result["image"] = afm.scan(lambda p: first.set())

        scanner = threading.Thread(target=run)
        scanner.start()
        assert first.wait(5.0)
        afm.pause()  # queued to the scanning thread, which sends it
        assert afm.status().state == State.PAUSED
        afm.resume()
        scanner.join(20)
        assert not scanner.is_alive()
    finally:
        server.stop()
    assert result["image"].shape == (4, 8)
    assert [f.code for f in twin.executed].count("PA") == 1


# -- the twin's mechanics and pace -------------------------------------------------------------
def test_ruler_against_the_closed_forms():
    E, rho, L, w, h = 200e9, 7850.0, 0.26, 25e-3, 0.5e-3
    lever = ruler()
    assert lever.spring_constant == pytest.approx(E * w * h ** 3 / (4 * L ** 3), rel=1e-12)
    f1 = 1.875104 ** 2 / (2 * math.pi * L ** 2) * math.sqrt(E * h ** 2 / (12 * rho))
    assert lever.resonance_frequency(1) == pytest.approx(f1, rel=1e-5)
    assert 5.5 < f1 < 6.5  # the paper's "about 6 Hz"
    x = 5e-3
    strain_per_newton = 6 * (L - x) / (E * w * h ** 2)
    cal = GaugeCalibration.from_ruler()
    assert cal.counts_per_newton == pytest.approx(128 * 2 ** 22 * 2.0 * strain_per_newton,
                                                  rel=1e-12)
    assert cal.counts_per_metre == pytest.approx(cal.counts_per_newton * lever.spring_constant)


def test_calibration_from_weights():
    cal = GaugeCalibration.from_weights(1000, 1000 - 12890.0, 0.001, spring_constant=8.89)
    assert cal.counts_per_newton == pytest.approx(12890.0 / (0.001 * 9.80665))
    with pytest.raises(ValueError, match="loaded_counts"):
        GaugeCalibration.from_weights(5, 5, 0.001, spring_constant=1.0)


def test_twin_gauge_reads_the_ruler_force():
    twin = _twin(gauge_noise=0.0)
    twin.x = twin.y = 0.0
    surface = twin.surface(0.0, 0.0)
    twin.z = int(surface / twin.z_step) - 100  # 0.25 mm into the surface
    deflection = surface - twin.z * twin.z_step
    expected = deflection * ruler().spring_constant * twin.calibration.counts_per_newton
    assert twin.gauge() == round(expected)


def test_trapezoidal_move_time():
    # 1000 steps at 2000 steps/s and 20000 steps/s^2: cruise, t = n / v + v / a
    assert _move_time(1000, 2000, 20000) == pytest.approx(1000 / 2000 + 2000 / 20000)
    # 50 steps never reach 2000 steps/s: triangle, t = 2 sqrt(n / a)
    assert _move_time(50, 2000, 20000) == pytest.approx(2 * math.sqrt(50 / 20000))
    assert _move_time(0, 2000, 20000) == 0.0


def test_twin_pixel_takes_the_machines_time():
    twin = _twin(gauge_noise=0.0)
    twin.poll(0.0)
    twin.handle(Frame(1, "HM"))
    twin.poll(twin.next_due())
    for i, (par, value) in enumerate((("NX", 4), ("NY", 1), ("DX", 400), ("MO", 0))):
        twin.handle(Frame(2 + i, "SP", (par, value)))
    twin.handle(Frame(9, "SS"))
    frames = twin.poll(twin.next_due())  # the first pixel
    assert frames[0].code == "PX"
    t_first = twin.now
    z_before = frames[0].args[2]
    frames = twin.poll(twin.next_due())
    steps = abs(frames[0].args[2] - z_before)
    move = _move_time(400e-6 / 12.5e-6, 2000, 20000)  # 32 x steps
    expected = move + (steps + 1) * (1 / 80)  # >= one gauge reading per z step
    assert twin.now - t_first == pytest.approx(expected, rel=0.2, abs=3 / 80)


def test_twin_protocol_errors():
    twin = _twin()
    assert twin.handle(Frame(1, "SP", ("ZS", 5))) == [Frame(1, "ER", (3, "READONLY"))]
    assert twin.handle(Frame(2, "SP", ("NX", 129))) == [Frame(2, "ER", (3,))]
    assert twin.handle(Frame(12, "SP", ("DX", 210))) == [Frame(12, "ER", (3,))]  # 25 um grid
    assert twin.handle(Frame(3, "SP", ("QQ", 1))) == [Frame(3, "ER", (3,))]
    assert twin.handle(Frame(4, "RS")) == [Frame(4, "ER", (10,))]
    assert twin.handle(Frame(5, "XY")) == [Frame(5, "ER", (2,))]
    assert twin.handle(Frame(6, "GL", (0,))) == [Frame(6, "ER", (3,))]
    assert twin.handle(Frame(7, "GP", ("ZS",))) == [Frame(7, "OK", ("GP", "ZS", 2500))]


def test_printed_samples():
    grating = printed_sample("grating", pixels=16, pixel_size=1e-3, height=3e-3)
    assert grating.shape == (16, 16) and grating.height_extent == pytest.approx(15e-3)
    assert np.ptp(grating.heights) == pytest.approx(3e-3)
    with pytest.raises(ValueError, match="kind"):
        printed_sample("seashell")


@pytest.mark.slow
def test_printed_afm_image():
    sample = printed_sample("afm", pixels=64, pixel_size=0.2e-3, height=1.5e-3)
    assert sample.shape == (64, 64) and np.ptp(sample.heights) == pytest.approx(1.5e-3)


# -- a real board -------------------------------------------------------------------------------
@pytest.mark.hardware
@pytest.mark.skipif(os.environ.get("AFMSMILER_HARDWARE") != "1",
                    reason="no board: set AFMSMILER_HARDWARE=1 and AFMSMILER_PORT=/dev/ttyACM0")
def test_real_board_connect_and_scan(tmp_path):
    port = os.environ.get("AFMSMILER_PORT", "/dev/ttyACM0")
    with MacroAFM(SerialTransport(port), timeout=2.0, stream_timeout=60.0) as afm:
        info = afm.connect()
        assert info.device == "MACROAFM" and info.protocol_version == 1
        afm.configure(pixels=8, lines=4, pitch=0.5e-3, mode="jumping", setpoint_force=10e-3)
        afm.home()
        image = afm.scan()
        assert image.shape == (4, 8) and not np.isnan(image.heights).any()
        assert load(afm.save(tmp_path / "board.gwy"), "height").shape == (4, 8)


def test_start_button_runs_a_preset_scan_the_host_follows():
    twin = _low(friction=0.0)
    # a real machine's pace (a fiftieth): at time_scale 0 the twin would run lines ahead while the
    # host reads the scan's size after the button's event
    host, server = open_twin(twin, time_scale=0.02)
    try:
        afm = _scan(twin, host, mode="contact", pixels=8, lines=8)
        threading.Timer(0.05, twin.press_button, args=(0,)).start()
        assert afm.wait_button(5.0) == 0
        image = afm.scan(start=False)
    finally:
        server.stop()
    assert image.shape == (8, 8)  # preset 0: the current parameters
    assert _matches(image, twin) <= twin.z_step * 1.0001


def test_nobody_presses_the_button():
    twin = _low()
    host, server = open_twin(twin)
    try:
        afm = _scan(twin, host, pixels=8, lines=8)
        with pytest.raises(TransportTimeout, match="button"):
            afm.wait_button(0.1)
    finally:
        server.stop()


def test_emergency_stop_mid_scan():
    twin = _low()
    host, server = open_twin(twin)
    try:
        afm = _scan(twin, host, pixels=8, lines=8)

        def on_pixel(p):
            if p.done == 20:
                twin.press_estop()

        with pytest.raises(DeviceError) as info:
            afm.scan(on_pixel)
        status = afm.status()
    finally:
        server.stop()
    assert info.value.code == ErrorCode.ESTOP and "ESTOP" in str(info.value)
    assert status.state == State.FAULT and status.flags & Flag.ESTOP and not status.homed
    assert info.value.partial is not None and info.value.partial.shape[1] == 8


def test_a_scan_left_unfinished_aborts_the_machine():
    twin = _low()
    host, server = open_twin(twin)
    try:
        afm = _scan(twin, host, pixels=8, lines=8)
        it = afm.scan_iter()
        for _ in range(5):
            next(it)
        it.close()  # the notebook's loop broke off (or the kernel was interrupted)
        assert afm.status().state == State.IDLE
        assert afm.result is None  # not one line finished
    finally:
        server.stop()
    assert any(f.code == "AB" for f in twin.executed)


def replay_first_session(text: str) -> list:
    """Send the spec's first frames block (a session before homing) to a fresh twin; return the
    (expected, got) replies that differ."""
    twin = MacroAFMTwin(sample=printed_sample(pixels=8))
    twin.poll(0.0)  # the boot event
    block = golden_frames(text.split("```frames", 2)[0] + "```frames"
                          + text.split("```frames", 2)[1])
    got, expected = [], []
    for mark, line, _ in block:
        if mark == ">":
            got += [encode_frame(f).rstrip(b"\n").decode()
                    for f in twin.handle(decode_frame(line.encode()))]
        elif mark == "<":
            expected.append(line)
    return [(e, g) for e, g in zip(expected, got) if e != g] + \
        ([("count", (len(expected), len(got)))] if len(expected) != len(got) else [])


def test_twin_replays_the_specs_session_before_homing():
    spec = REPO / "hardware" / "macro_afm" / "PROTOCOL.md"
    if not spec.exists():
        pytest.skip(f"{spec.relative_to(REPO)} not in this checkout (h-firmware writes it)")
    assert replay_first_session(spec.read_text()) == []


def test_configuration_reads_back_what_configure_set():
    twin = _low()
    host, server = open_twin(twin)
    try:
        afm = MacroAFM(host, timeout=0.3)
        afm.connect()
        wanted = dict(pixels=16, lines=12, pitch=0.5e-3, setpoint_force=5e-3, mode="jumping",
                      lift=1e-3, step_rate=3000.0, step_acceleration=30_000.0, preset=2)
        afm.configure(**wanted)
        back = afm.configuration()
    finally:
        server.stop()
    assert back.keys() == wanted.keys()
    for name, value in wanted.items():
        if name == "setpoint_force":  # rounded to whole counts
            assert back[name] == pytest.approx(value, abs=1 / afm.calibration.counts_per_newton)
        elif isinstance(value, str):
            assert back[name] == value
        else:
            assert back[name] == pytest.approx(value)
