"""The macroscopic AFM's firmware (hardware/macro_afm): protocol.h against the codec, PROTOCOL.md's
golden frames, the avr-gcc build and its flash/RAM use, and the firmware itself run in simavr behind
the C harness (hardware/macro_afm/sim/harness.c) that stands in for the machine.

The firmware tests skip with the reason when avr-gcc, Debian's Arduino core or simavr is missing
(``make firmware`` installs them). Each emulated board is a harness process that this file starts
and kills (every read has a timeout; no process outlives its test).
"""
from __future__ import annotations

import re
import select
import shutil
import subprocess
import time
from pathlib import Path

import numpy as np
import pytest

from afmsmiler.hardware.errors import ChecksumError, FrameError, TransportTimeout
from afmsmiler.hardware.framing import Frame, crc8, decode_frame, encode_frame

ROOT = Path(__file__).resolve().parents[1]
MACRO = ROOT / "hardware" / "macro_afm"
PROTOCOL_H = MACRO / "firmware" / "protocol.h"
PROTOCOL_MD = MACRO / "PROTOCOL.md"
ARDUINO_AVR = Path("/usr/share/arduino/hardware/arduino/avr")

#: ATmega2560: 256 KiB flash less the 8 KiB bootloader, 8 KiB SRAM.
FLASH_BYTES = 256 * 1024 - 8 * 1024
RAM_BYTES = 8 * 1024
#: SRAM that static data may take, leaving the rest to the stack (deepest call chains, Serial).
RAM_BUDGET = 6 * 1024

#: x/y and z micro-steps of the machine (firmware/config.h, the harness).
XY_STEP_UM = 12.5
Z_STEP_UM = 2.5
#: Micro-steps an axis moves off its home switch after the switch opened (config.h).
HOME_BACKOFF = 80


# -- what the firmware tests need -------------------------------------------------------------
def toolchain_missing() -> str | None:
    """Why the firmware cannot be built and emulated here, or None if it can.

    Returns
    -------
    str or None
        The missing piece (avr-gcc, the Arduino core, simavr's headers or library, gcc).
    """
    for tool in ("avr-gcc", "avr-g++", "avr-size", "gcc"):
        if shutil.which(tool) is None:
            return f"{tool} not found (make firmware installs gcc-avr, avr-libc, simavr)"
    if not (ARDUINO_AVR / "cores" / "arduino" / "Arduino.h").is_file():
        return f"Debian's Arduino core is not at {ARDUINO_AVR} (apt-get install arduino-core-avr)"
    if not Path("/usr/include/simavr/sim_avr.h").is_file():
        return "simavr's headers are missing (apt-get install libsimavr-dev)"
    return None


def needs_toolchain():
    reason = toolchain_missing()
    if reason:
        pytest.skip(reason)


@pytest.fixture(scope="module")
def build(tmp_path_factory):
    """Build the firmware and the harness once for this file (hardware/macro_afm/build.sh)."""
    needs_toolchain()
    out = tmp_path_factory.mktemp("macro_afm_build")
    run = subprocess.run(["sh", str(MACRO / "build.sh"), str(out)], capture_output=True,
                         text=True, timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
    return out


# -- protocol.h against the codec ---------------------------------------------------------------
_DEFINE = re.compile(
    r'#define\s+(PROTOCOL_VERSION|(CMD|ERR|EVT|PAR)_(\w+))\s+("([^"]*)"|(\d+))\s*$')


def parse_protocol_h(path: Path = PROTOCOL_H) -> dict:
    """The #define lines of a protocol.h as {"CMD": {name: value}, ..., "PROTOCOL_VERSION": n}."""
    table = {"CMD": {}, "ERR": {}, "EVT": {}, "PAR": {}}
    for line in path.read_text().splitlines():
        if not line.startswith("#define") or "_H" in line.split()[1][-2:]:
            continue
        m = _DEFINE.match(line.strip())
        assert m, f"protocol.h line not of the contract's forms: {line!r}"
        value = m.group(5) if m.group(5) is not None else int(m.group(6))
        if m.group(1) == "PROTOCOL_VERSION":
            table["PROTOCOL_VERSION"] = value
        else:
            table[m.group(2)][m.group(3)] = value
    return table


def test_protocol_h_has_only_the_contract_forms():
    table = parse_protocol_h()
    assert table["PROTOCOL_VERSION"] == 1
    assert set(table["CMD"]) == {"IDENTIFY", "SET", "GET", "HOME", "START", "PAUSE", "RESUME",
                                 "ABORT", "STATUS", "GAUGE", "GETLINE"}
    assert all(re.fullmatch(r"[A-Z]{2}", v) for v in table["CMD"].values())
    assert all(re.fullmatch(r"[A-Z]{2}", v) for v in table["PAR"].values())
    # the contract's shared error numbers
    assert table["ERR"] == dict(CHECKSUM=1, UNKNOWN_COMMAND=2, BAD_ARGUMENT=3, BUSY=4,
                                NOT_HOMED=5, LIMIT=6, ESTOP=7, SENSOR=8, MALFORMED=9, STATE=10)


def test_protocol_h_matches_the_codec():
    codec = pytest.importorskip("afmsmiler.hardware.macro.codec",
                                reason="h-macro's codec is not merged into this branch yet")
    table = parse_protocol_h()
    from afmsmiler.hardware.framing import PROTOCOL_VERSION

    assert table["PROTOCOL_VERSION"] == PROTOCOL_VERSION
    for prefix, enum in (("CMD", codec.Command), ("ERR", codec.ErrorCode), ("EVT", codec.Event),
                         ("PAR", codec.Param)):
        in_codec = {m.name: m.value for m in enum}
        assert table[prefix] == in_codec, prefix


# -- PROTOCOL.md's golden frames ----------------------------------------------------------------
def golden_blocks(path: Path = PROTOCOL_MD) -> list[list[tuple[str, bytes]]]:
    """The ```frames blocks of PROTOCOL.md as lists of (direction, wire bytes with \\n):
    ">" host to device (a line at column 0), "<" device to host (indented by four spaces)."""
    blocks, current = [], None
    for line in path.read_text().splitlines():
        if line.strip() == "```frames":
            current = []
            continue
        if current is not None and line.strip() == "```":
            blocks.append(current)
            current = None
            continue
        if current is not None:
            assert line == line.rstrip() and line.strip(), f"golden frame line {line!r}"
            mark = "<" if line.startswith("    ") else ">"
            assert line.startswith("    " + line.strip()) or mark == ">", line
            current.append((mark, line.strip().encode("ascii") + b"\n"))
    assert current is None, "unterminated frames block"
    return blocks


def unreadable_lines(path: Path = PROTOCOL_MD) -> list[tuple[bytes, bytes]]:
    """PROTOCOL.md's table of lines that are not frames on purpose: (line sent, answer)."""
    rows = re.findall(r"^\| ! `([^`]*)` \| `([^`]*)` \|", path.read_text(), re.M)
    return [(sent.encode() + b"\n", answer.encode() + b"\n") for sent, answer in rows]


def test_golden_frames_have_right_checksums():
    blocks = golden_blocks()
    assert len(blocks) == 3
    frames = [f for block in blocks for f in block]
    assert len(frames) > 40
    for mark, wire in frames:
        frame = decode_frame(wire)
        assert encode_frame(frame) == wire  # canonical: what the encoder sends, byte for byte
        if mark == ">":
            assert frame.seq != 0, wire  # every host command here expects a reply
        elif frame.seq == 0:
            assert frame.code in ("PX", "LN", "EV", "ER"), wire
    bad = unreadable_lines()
    codes = [answer_code(sent, answer) for sent, answer in bad]
    assert 1 in codes and 9 in codes  # both of the decoders' paths
    # an integer outside int32 is malformed, not a word (the firmware once took it as a word)
    assert any(re.search(rb" -?\d{10,}\*", sent) for sent, _ in bad)


def answer_code(sent: bytes, answer: bytes) -> int:
    """The table's answer code (1 or 9) for a line sent, checked against decode_frame: ``0 ER 1``
    exactly when it raises a ChecksumError, ``0 ER 9`` when a FrameError that is not one."""
    reply = decode_frame(answer)
    assert encode_frame(reply) == answer, answer
    assert (reply.seq, reply.code) == (0, "ER") and reply.args in ((1,), (9,)), answer
    with pytest.raises(FrameError) as info:
        decode_frame(sent)
    assert isinstance(info.value, ChecksumError) == (reply.args[0] == 1), (sent, answer)
    return reply.args[0]


@pytest.mark.parametrize("sent, answer", [
    (b"18  ST*1D\n", b"0 ER 9*E7\n"),  # PROTOCOL.md's old row: a checksum error (ER 1)
    (b"17 GP NX*00\n", b"0 ER 9*E7\n"),  # a checksum error listed as malformed
    (b"18  ST*D6\n", b"0 ER 1*DF\n"),  # malformed listed as a checksum error
    (b"17 GP NX*4C\n", b"0 ER 1*DF\n"),  # a valid frame
])
def test_answer_code_catches_a_wrong_row(sent, answer):
    with pytest.raises((AssertionError, pytest.fail.Exception)):
        answer_code(sent, answer)


def test_golden_replies_echo_their_commands():
    """Every reply (seq != 0) follows a command with its SEQ, and OK replies echo its CODE."""
    for block in golden_blocks():
        pending = {}
        for mark, wire in block:
            frame = decode_frame(wire)
            if mark == ">":
                pending[frame.seq] = frame.code
            elif frame.seq:
                assert frame.seq in pending, wire
                if frame.code == "OK":
                    assert frame.args[0] == pending[frame.seq], wire


# -- the build ------------------------------------------------------------------------------------
def avr_size(elf: Path) -> dict:
    """Section sizes (bytes) from avr-size -A."""
    out = subprocess.run(["avr-size", "-A", str(elf)], capture_output=True, text=True,
                         timeout=30, check=True).stdout
    sizes = {}
    for line in out.splitlines():
        parts = line.split()
        if len(parts) >= 2 and parts[0].startswith(".") and parts[1].isdigit():
            sizes[parts[0]] = int(parts[1])
    return sizes


@pytest.mark.slow
def test_firmware_builds_and_fits_the_mega(build):
    elf = build / "macro_afm.elf"
    assert elf.is_file() and (build / "macro_afm.hex").is_file() and (build / "harness").is_file()
    sizes = avr_size(elf)
    flash = sizes[".text"] + sizes.get(".data", 0)
    ram = sizes.get(".data", 0) + sizes.get(".bss", 0) + sizes.get(".noinit", 0)
    assert flash < FLASH_BYTES
    assert ram <= RAM_BUDGET, f"static RAM {ram} B of {RAM_BYTES} leaves too little stack"
    # the machine code really is for the ATmega2560
    head = elf.read_bytes()[:20]
    assert head[:4] == b"\x7fELF" and int.from_bytes(head[18:20], "little") == 83  # EM_AVR


# -- BUILD.md's calibration example ---------------------------------------------------------------
#: BUILD.md's ruler (free length, width, thickness in m), spring steel, the gauge 5 mm from the
#: clamp with gauge factor 2.0, the HX711 at gain 128, the z micro-step.
RULER = dict(length=0.26, width=25e-3, thickness=0.5e-3, youngs_modulus=200e9, density=7850.0)
GAUGE_AT, GAUGE_FACTOR, HX711_GAIN = 5e-3, 2.0, 128


def calibration() -> dict:
    """BUILD.md's worked example, computed with module (a)'s beam model."""
    from afmsmiler.cantilever import Cantilever

    lever = Cantilever(**RULER)
    k = lever.spring_constant
    deflection = 1e-6  # 1 um at the needle
    strain_per_um = abs(float(lever.strain(GAUGE_AT, RULER["thickness"] / 2, k * deflection)))
    strain_per_count = 1.0 / (HX711_GAIN * 2 ** 22 * GAUGE_FACTOR)
    counts_per_um = strain_per_um / strain_per_count
    return dict(k=k, f1=lever.resonance_frequency(1), strain_per_um=strain_per_um,
                strain_per_count=strain_per_count, counts_per_um=counts_per_um,
                counts_per_step=counts_per_um * Z_STEP_UM,
                force_per_count=k * 1e-6 / counts_per_um,
                setpoint_um=2000 / counts_per_um, setpoint_force=2000 / counts_per_um * 1e-6 * k,
                contact_um=300 / counts_per_um,
                counts_per_newton=counts_per_um * 1e6 / k)


def test_calibration_follows_the_closed_forms():
    """Module (a)'s numbers against the hand formulas of BUILD.md (independent of the code)."""
    c = calibration()
    L, w, h, E, rho = (RULER[k] for k in ("length", "width", "thickness", "youngs_modulus",
                                            "density"))
    J = w * h ** 3 / 12
    assert c["k"] == pytest.approx(3 * E * J / L ** 3, rel=1e-12)
    # strain(a) = 3 h (L - a) / (2 L^3) * deflection
    assert c["strain_per_um"] == pytest.approx(3 * h * (L - GAUGE_AT) / (2 * L ** 3) * 1e-6,
                                               rel=1e-12)
    # first mode: (1.8751)^2 / (2 pi L^2) sqrt(E J / (rho w h)) (Blevins, Table 8-1)
    assert c["f1"] == pytest.approx(1.87510407 ** 2 / (2 * np.pi * L ** 2)
                                    * np.sqrt(E * J / (rho * w * h)), rel=1e-8)
    assert 5.5 < c["f1"] < 6.5  # the paper's "about 6 Hz"


def test_build_md_example_runs():
    """BUILD.md's Python example runs and gives this file's numbers."""
    text = (MACRO / "BUILD.md").read_text()
    code = text.split("```python\n", 1)[1].split("```", 1)[0]
    names = {}
    exec(compile(code, "BUILD.md", "exec"), names)
    c = calibration()
    for name in ("k", "f1", "strain_per_um", "counts_per_um", "force_per_count"):
        assert names[name] == pytest.approx(c[name], rel=1e-12), name


def test_build_md_numbers():
    """Every number of BUILD.md's worked example is the one computed here."""
    text = (MACRO / "BUILD.md").read_text()
    c = calibration()
    expected = [f"| stiffness k | {c['k']:.2f} N/m |",
                f"| first resonance f1 | {c['f1']:.1f} Hz",
                f"| strain per um of tip deflection at the gauge | {c['strain_per_um']:.2e} |",
                f"| strain per count | {c['strain_per_count']:.2e} |",
                f"| counts per um of tip deflection | {c['counts_per_um']:.1f} |",
                f"| counts per z micro-step (2.5 um) | {c['counts_per_step']:.1f} |",
                f"| force per count | {c['force_per_count'] * 1e6:.2f} uN |",
                f"| default setpoint SE = 2000 counts | {c['setpoint_um']:.0f} um of deflection, "
                f"{c['setpoint_force'] * 1e3:.2f} mN |",
                f"| contact threshold 300 counts | {c['contact_um']:.1f} um of deflection |",
                f"Predicted here: {c['counts_per_um']:.1f} counts/um x",
                f"= {c['counts_per_newton']:.2e} counts/N"]
    for line in expected:
        assert line in text, line


# -- the emulated board -------------------------------------------------------------------------
def write_map(path: Path, heights_um: np.ndarray, pitch_um: float) -> Path:
    """Write a height map (um) in the harness' text format (row 0 = first line, x along a row)."""
    ny, nx = heights_um.shape
    rows = "\n".join(" ".join(f"{h:.3f}" for h in row) for row in heights_um)
    path.write_text(f"# virtual sample for tests/test_hardware_firmware.py\nmacro_afm_map 1\n"
                    f"{nx} {ny} {pitch_um:g}\n{rows}\n")
    return path


class Board:
    """One harness process: the firmware in simavr behind a pty, and the harness' control lines.

    Parameters
    ----------
    build : Path
        The build directory (macro_afm.elf, harness).
    *args : str
        Harness options (--map, --gain, ...).
    """

    def __init__(self, build: Path, *args: str):
        from afmsmiler.hardware.transport import SerialTransport

        self.proc = subprocess.Popen([str(build / "harness"), str(build / "macro_afm.elf"),
                                      *args], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                     stderr=subprocess.PIPE, text=True, bufsize=1)
        try:
            line = self._control_line(10.0)
            assert line.startswith("PTY "), line
            self.path = line.split()[1]
            self.port = SerialTransport(self.path)
        except BaseException:
            self.close()
            raise
        self.seq = 0

    def _control_line(self, timeout: float) -> str:
        ready, _, _ = select.select([self.proc.stdout], [], [], timeout)
        if not ready:
            raise TimeoutError("the harness did not answer")
        line = self.proc.stdout.readline()
        if not line:
            raise RuntimeError(f"the harness exited: {self.proc.stderr.read()}")
        return line.strip()

    def control(self, command: str, timeout: float = 10.0) -> str:
        """Send a harness command (POS, ORIGIN, ESTOP 1, BUTTON START, ...); its answer."""
        self.proc.stdin.write(command + "\n")
        self.proc.stdin.flush()
        return self._control_line(timeout)

    def position(self) -> tuple[int, int, int]:
        """The harness' x, y, z in micro-steps (machine coordinates)."""
        x, y, z = self.control("POS").split()[1:4]
        return int(x), int(y), int(z)

    def send_raw(self, data: bytes):
        self.port.write(data)

    def read(self, timeout: float = 10.0) -> Frame:
        """The next valid frame (lines that are not frames, e.g. a boot fragment, are skipped)."""
        deadline = time.monotonic() + timeout
        while True:
            left = deadline - time.monotonic()
            if left <= 0:
                raise TransportTimeout("no frame from the firmware")
            line = self.port.readline(left)
            try:
                return decode_frame(line)
            except FrameError:
                continue

    def command(self, *tokens, seq: int | None = None, timeout: float = 10.0):
        """Send one command frame and return (reply, unsolicited frames seen before it)."""
        if seq is None:
            self.seq = self.seq % 255 + 1
            seq = self.seq
        self.send_raw(encode_frame(Frame(seq, tokens[0], tuple(tokens[1:]))))
        seen = []
        while True:
            frame = self.read(timeout)
            if frame.seq == seq:
                return frame, seen
            seen.append(frame)

    def until(self, predicate, timeout: float = 60.0) -> list[Frame]:
        """Frames up to and including the first for which predicate(frame) is true."""
        frames = []
        deadline = time.monotonic() + timeout
        while True:
            frame = self.read(max(0.01, deadline - time.monotonic()))
            frames.append(frame)
            if predicate(frame):
                return frames

    def close(self):
        try:
            if getattr(self, "port", None) is not None:
                self.port.close()
        finally:
            if self.proc.poll() is None:
                self.proc.kill()
            self.proc.wait(timeout=10)
            for stream in (self.proc.stdin, self.proc.stdout, self.proc.stderr):
                stream.close()


def eventually(condition, timeout: float = 20.0, every: float = 0.05) -> bool:
    """Poll ``condition()`` until it is true (the emulator's pace depends on the machine's load);
    False after ``timeout`` s."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if condition():
            return True
        time.sleep(every)
    return False


def ok(frame: Frame, code: str) -> tuple:
    assert frame.code == "OK" and frame.args[0] == code, frame
    return frame.args[1:]


@pytest.fixture
def board_factory(build):
    """Start emulated boards; every one is killed at the end of the test."""
    boards = []

    def start(*args: str) -> Board:
        board = Board(build, *args)
        boards.append(board)
        return board

    yield start
    for board in boards:
        board.close()
    assert all(b.proc.poll() is not None for b in boards)


#: Harness options of the tests: the switches and the sample close to where the axes start, so
#: that homing and the approach take little simulated time; a little gauge noise; the gauge's
#: counts per um of deflection of BUILD.md's ruler.
GAIN = calibration()["counts_per_um"]
OFFSET = 100000
BASE = ("--gain", str(GAIN), "--offset", str(OFFSET), "--noise", "2", "--z-top", "3",
        "--start", "1,1,2.5")


@pytest.mark.slow
def test_identify_and_parameters(board_factory):
    board = board_factory(*BASE)
    reply, _ = board.command("ID")
    assert ok(reply, "ID") == ("MACROAFM", 1, "0.1.0")
    reply, _ = board.command("GP", "ZS")
    assert ok(reply, "GP") == ("ZS", 2500)
    for par, value in (("NX", 16), ("NY", 5), ("DX", 350), ("SE", 1500), ("MO", 1), ("LI", 77),
                       ("VE", 3000), ("AC", 20000), ("PR", 2)):
        reply, _ = board.command("SP", par, value)
        assert ok(reply, "SP") == (par, value)
        reply, _ = board.command("GP", par)
        assert ok(reply, "GP") == (par, value)
    for par, bad in (("NX", 0), ("NX", 129), ("DX", 30), ("MO", 2), ("PR", 4), ("QQ", 1)):
        reply, _ = board.command("SP", par, bad)
        assert reply.code == "ER" and reply.args[0] == 3, (par, bad, reply)
    reply, _ = board.command("SP", "ZS", 1000)
    assert (reply.code, reply.args) == ("ER", (3, "READONLY"))
    reply, _ = board.command("GP", "NX")
    assert ok(reply, "GP") == ("NX", 16)  # refused values changed nothing
    reply, _ = board.command("ZZ")
    assert (reply.code, reply.args) == ("ER", (2,))
    reply, _ = board.command("SS")
    assert (reply.code, reply.args) == ("ER", (5,))  # not homed
    reply, _ = board.command("RG")  # tared at power-up: counts above the free reading
    assert ok(reply, "RG") and abs(reply.args[1]) < 20


@pytest.mark.slow
def test_golden_session_replays_against_the_firmware(board_factory):
    """PROTOCOL.md's first block, byte for byte (the firmware's replies are deterministic)."""
    board = board_factory(*BASE)
    board.command("ID", seq=200)  # sync past the boot frame
    block = golden_blocks()[0]
    for i, (mark, wire) in enumerate(block):
        if mark != ">":
            continue
        board.send_raw(wire)
        expected = block[i + 1][1]
        line = board.port.readline(10.0) + b"\n"
        assert line == expected


@pytest.mark.slow
def test_unreadable_lines_of_the_spec_against_the_firmware(board_factory):
    """Every row of PROTOCOL.md's table of unreadable lines: exactly the table's answer, byte for
    byte; int32's ends are still integers (answered ER 3: out of NX's range, not malformed)."""
    board = board_factory(*BASE)
    board.command("ID", seq=200)  # sync past the boot frame
    rows = unreadable_lines()
    assert len(rows) >= 2
    for sent, answer in rows:
        board.send_raw(sent)
        assert board.port.readline(10.0) + b"\n" == answer, sent
    for value in (2147483647, -2147483648):
        reply, _ = board.command("SP", "NX", value)
        assert (reply.code, reply.args) == ("ER", (3,)), value
    reply, _ = board.command("GP", "NX")
    assert ok(reply, "GP") == ("NX", 8)


@pytest.mark.slow
def test_bad_lines_and_retries(board_factory, tmp_path):
    sample = write_map(tmp_path / "sample.txt", bumpy(8, 8), 200)
    board = board_factory(*BASE, "--map", str(sample))
    board.command("ID")
    board.send_raw(b"5 GP NX*00\n")  # wrong checksum
    frame = board.read()
    assert (frame.seq, frame.code, frame.args) == (0, "ER", (1,))
    for junk in (b"5 GP NX\n", b"5  GP*%02X\n" % crc8(b"5  GP"), b"x" * 300 + b"\n",
                 b"05 GP NX*%02X\n" % crc8(b"05 GP NX"), b"5 GP NX*4c\n",
                 b"5 SP NX 99999999999*%02X\n" % crc8(b"5 SP NX 99999999999")):
        with pytest.raises(FrameError) as info:  # malformed, not a checksum error, for both
            decode_frame(junk)
        assert not isinstance(info.value, ChecksumError), junk
        board.send_raw(junk)
        frame = board.read()
        assert (frame.seq, frame.code, frame.args) == (0, "ER", (9,)), junk
    too_long = b"5 GP " + b"N" * 116  # a 121-character body, its checksum right
    board.send_raw(too_long + b"*%02X\n" % crc8(too_long))
    frame = board.read()
    assert (frame.seq, frame.code, frame.args) == (0, "ER", (9,))
    # the retried command after a bad line is executed once
    reply, _ = board.command("GP", "NX", seq=5)
    assert ok(reply, "GP") == ("NX", 8)
    board.send_raw(b"12 GP NY*%02X\r\n" % crc8(b"12 GP NY"))  # \r\n is accepted
    frame = board.read()
    assert (frame.seq, frame.code, frame.args) == (12, "OK", ("GP", "NY", 8))
    # home, then a START that is retried (same SEQ, same body): the same reply, not a second
    # execution (which would be ER 4 BUSY)
    reply, _ = board.command("HM", seq=6)
    ok(reply, "HM")
    board.until(lambda f: f.code == "EV" and f.args[0] == "HOMED", timeout=60)
    reply, _ = board.command("SS", seq=7)
    ok(reply, "SS")
    reply, _ = board.command("SS", seq=7)
    ok(reply, "SS")
    reply, _ = board.command("SS", seq=8)  # a new command is executed: busy
    assert (reply.code, reply.args) == ("ER", (4,))
    # ABORT once: one ABORTED; its retry gets OK AB again and no second event
    reply, _ = board.command("AB", seq=9)
    ok(reply, "AB")
    board.until(lambda f: f.code == "EV" and f.args[0] == "ABORTED", timeout=10)
    reply, seen = board.command("AB", seq=9)
    ok(reply, "AB")
    reply, seen2 = board.command("ST", seq=10)
    assert ok(reply, "ST")[0] == "IDLE"
    assert not [f for f in seen + seen2 if f.code == "EV" and f.args[0] == "ABORTED"]
    reply, _ = board.command("AB", seq=11)
    assert (reply.code, reply.args) == ("ER", (10,))


@pytest.mark.slow
def test_homing(board_factory, hang_guard):
    board = board_factory(*BASE)
    before = board.position()
    reply, _ = board.command("HM")
    ok(reply, "HM")
    reply, _ = board.command("ST")
    assert ok(reply, "ST")[0] == "HOMING"
    reply, _ = board.command("SP", "NX", 4)
    assert (reply.code, reply.args) == ("ER", (4,))  # busy
    t0 = time.monotonic()
    board.until(lambda f: f.code == "EV" and f.args[0] == "HOMED", timeout=60)
    x, y, z = board.position()
    # each axis stopped on its switch (x, y at 0; z at the 3 mm top), moved off until it opened
    # (one step) and 80 steps more
    home = HOME_BACKOFF + 1
    assert (x, y, z) == (home, home, round(3000 / Z_STEP_UM) - home)
    assert before != (x, y, z)
    reply, _ = board.command("ST")
    state, row, col, flags = ok(reply, "ST")
    assert state == "IDLE" and flags & 1 and not flags & (2 | 4 | 8 | 16)
    hang_guard.check(time.monotonic() - t0, 60, expected=3)  # 2.6 s at a load of 8 on 2 cores


def bumpy(nx: int, ny: int) -> np.ndarray:
    """Heights (um) of a virtual sample: a slope, a sine and a 150 um tall block."""
    i, j = np.meshgrid(np.arange(nx), np.arange(ny))
    h = 500.0 + 300.0 * np.sin(i / 2.0) + 40.0 * j
    h[2:5, 3:6] += 150.0
    return h


def scan_raw(board: Board, nx: int, ny: int, timeout: float = 120.0):
    """Run SS and collect (z image in micro-steps, counts image, line ends, frames)."""
    reply, _ = board.command("SS")
    ok(reply, "SS")
    frames = board.until(lambda f: f.code == "EV" and f.args[0] in ("DONE",) or f.code == "ER",
                         timeout=timeout)
    z = np.full((ny, nx), np.nan)
    counts = np.full((ny, nx), np.nan)
    for f in frames:
        if f.code == "PX":
            row, col, zz, cc = f.args
            z[row, col], counts[row, col] = zz, cc
    lines = [f.args for f in frames if f.code == "LN"]
    return z, counts, lines, frames


@pytest.mark.slow
@pytest.mark.parametrize("mode", [0, 1], ids=["contact", "jumping"])
def test_scan_matches_the_virtual_sample(board_factory, tmp_path, mode, hang_guard):
    nx = ny = 8
    pitch = 200
    setpoint = 2000
    heights = bumpy(nx, ny)
    sample = write_map(tmp_path / "sample.txt", heights, pitch)
    board = board_factory(*BASE, "--map", str(sample))
    ok(board.command("HM")[0], "HM")
    board.until(lambda f: f.code == "EV" and f.args[0] == "HOMED", timeout=60)
    x0, y0, z0 = board.position()
    assert board.control("ORIGIN").startswith("OK ORIGIN")
    for par, value in (("NX", nx), ("NY", ny), ("DX", pitch), ("SE", setpoint), ("MO", mode),
                       ("LI", 40)):
        ok(board.command("SP", par, value)[0], "SP")
    t0 = time.monotonic()
    z, counts, lines, frames = scan_raw(board, nx, ny)
    elapsed = time.monotonic() - t0
    assert frames[-1].code == "EV" and frames[-1].args == ("DONE",), frames[-1]
    assert lines == [(row, nx) for row in range(ny)]
    assert not np.isnan(z).any()
    # the height image: z micro-steps x ZS; the needle sits where the ruler is bent by the
    # setpoint, SE / gain below the surface, and z counts from the home height
    height_um = z * Z_STEP_UM
    expected_um = heights - setpoint / GAIN - z0 * Z_STEP_UM
    error = height_um - expected_um
    assert np.abs(error).max() <= Z_STEP_UM, error  # within one z micro-step
    # each pixel's deflection is the setpoint within half a z micro-step's counts (plus noise)
    assert np.abs(counts - setpoint).max() <= 0.5 * GAIN * Z_STEP_UM + 10
    # the last pixel was measured (NX - 1) pitches along x and (NY - 1) along y from the origin
    x, y, _ = board.position()
    steps = pitch / XY_STEP_UM
    assert (x - x0, y - y0) == ((nx - 1) * steps, (ny - 1) * steps)
    # 23 s (contact) and 54 s (jumping) at a load of 8 on 2 cores
    hang_guard.check(elapsed, 600, expected=60)
    print(f"\nsimavr {['contact', 'jumping'][mode]} scan {nx}x{ny}: {elapsed:.1f} s")


@pytest.mark.slow
def test_limit_switch_mid_scan_keeps_the_finished_lines(board_factory, tmp_path):
    nx, ny, pitch = 6, 8, 200
    sample = write_map(tmp_path / "sample.txt", bumpy(nx, ny), pitch)
    # y's far switch 1.5 mm from y's home switch: rows 0..2 fit (0.6 + 0.4 mm), row 3 does not
    board = board_factory(*BASE, "--map", str(sample), "--y-max", "1.6")
    ok(board.command("HM")[0], "HM")
    board.until(lambda f: f.code == "EV" and f.args[0] == "HOMED", timeout=60)
    board.control("ORIGIN")
    for par, value in (("NX", nx), ("NY", ny), ("DX", pitch), ("MO", 1), ("LI", 40)):
        ok(board.command("SP", par, value)[0], "SP")
    z, counts, lines, frames = scan_raw(board, nx, ny)
    codes = [(f.code, f.args) for f in frames[-2:]]
    assert codes == [("EV", ("LIMIT", "Y")), ("ER", (6,))]
    assert lines == [(0, nx), (1, nx), (2, nx)]
    assert not np.isnan(z[:3]).any() and np.isnan(z[3:]).all()
    state, row, col, flags = ok(board.command("ST")[0], "ST")
    assert state == "FAULT" and row == 3 and flags & 4 and not flags & 1
    # the finished lines are still there: GETLINE re-sends the last two
    reply, seen = board.command("GL", 2)
    assert ok(reply, "GL") == (2, nx)
    assert [f.args for f in seen] == [(2, c, int(z[2, c]), int(counts[2, c])) for c in range(nx)]
    assert board.command("GL", 0)[0].args == (3,)  # older lines are gone: ER 3
    assert board.command("SS")[0].args == (5,)  # not homed after a fault


@pytest.mark.slow
def test_estop_stops_the_scan(board_factory, tmp_path):
    nx, ny, pitch = 8, 8, 200
    sample = write_map(tmp_path / "sample.txt", bumpy(nx, ny), pitch)
    board = board_factory(*BASE, "--map", str(sample))
    ok(board.command("HM")[0], "HM")
    board.until(lambda f: f.code == "EV" and f.args[0] == "HOMED", timeout=60)
    board.control("ORIGIN")
    ok(board.command("SS")[0], "SS")
    done = board.until(lambda f: f.code == "LN", timeout=60)  # one line finished
    assert board.control("ESTOP 1") == "OK ESTOP 1"
    tail = board.until(lambda f: f.code == "ER", timeout=30)
    assert [(f.code, f.args) for f in tail[-2:]] == [("EV", ("ESTOP",)), ("ER", (7,))]
    at_stop = board.position()
    time.sleep(0.3)
    assert board.position() == at_stop  # nothing moves any more
    state, row, col, flags = ok(board.command("ST")[0], "ST")
    assert state == "FAULT" and flags & 16
    assert ok(board.command("GL", 0)[0], "GL") == (0, nx)  # the finished line is kept
    assert board.command("HM")[0].args == (7,)  # E-stop still open
    assert board.command("SS")[0].args == (7,)
    board.control("ESTOP 0")
    ok(board.command("HM")[0], "HM")
    board.until(lambda f: f.code == "EV" and f.args[0] == "HOMED", timeout=60)
    assert done[-1].args == (0, nx)


@pytest.mark.slow
def test_button_starts_the_preset_and_display_shows_it(board_factory, tmp_path):
    sample = write_map(tmp_path / "sample.txt", bumpy(8, 8), 200)
    home = (HOME_BACKOFF + 1) * XY_STEP_UM / 1000  # mm: where homing puts x = y = 0
    board = board_factory(*BASE, "--map", str(sample), "--origin", f"{home},{home}")
    board.command("ID")
    board.control("BUTTON SELECT")  # preset 0 -> 1 (pressed for 100 ms, debounced 30 ms)
    assert eventually(lambda: ok(board.command("GP", "PR")[0], "GP") == ("PR", 1))
    ok(board.command("SP", "PR", 0)[0], "SP")
    board.control("BUTTON START")  # not homed: homes, then scans preset 0
    frames = board.until(lambda f: f.code == "PX", timeout=60)
    words = [f.args for f in frames if f.code == "EV"]
    assert ("BUTTON", 0) in words and ("HOMED",) in words
    assert eventually(lambda: board.control("DISPLAY").startswith("DISPLAY SCANNING P0 H"))
    ok(board.command("AB")[0], "AB")


# -- h-macro's driver against the emulated firmware ---------------------------------------------
def macro_afm(board: Board):
    """h-macro's MacroAFM on the emulated board's pty (the board's own port object)."""
    device = pytest.importorskip("afmsmiler.hardware.macro.device",
                                 reason="h-macro's MacroAFM is not merged into this branch yet")
    # an emulator is slower than the board: generous reply and stream timeouts
    return device.MacroAFM(board.port, timeout=3.0, retries=3, stream_timeout=20.0,
                           home_timeout=60.0)


def homed_driver(board: Board):
    afm = macro_afm(board)
    info = afm.connect()
    assert (info.device, info.protocol_version, info.firmware_version) == ("MACROAFM", 1, "0.1.0")
    assert info.z_step == pytest.approx(Z_STEP_UM * 1e-6)
    afm.home()
    x0, y0, z0 = board.position()
    board.control("ORIGIN")
    return afm, z0


@pytest.mark.slow
@pytest.mark.parametrize("mode", ["contact", "jumping"])
def test_driver_scans_the_virtual_sample(board_factory, tmp_path, mode):
    """MacroAFM.scan through the pty: the image is the sample within one z micro-step."""
    nx = ny = 8
    pitch = 200e-6
    heights = bumpy(nx, ny)
    sample = write_map(tmp_path / "sample.txt", heights, pitch * 1e6)
    board = board_factory(*BASE, "--map", str(sample))
    afm, z0 = homed_driver(board)
    wire = afm.configure(pixels=nx, lines=ny, pitch=pitch, mode=mode, lift=0.1e-3,
                         setpoint_force=2e-3, step_rate=4000, step_acceleration=40000)
    setpoint = wire[next(p for p in wire if p.value == "SE")]
    seen = []
    t0 = time.monotonic()
    image = afm.scan(callback=lambda progress: seen.append((progress.row, progress.col,
                                                            progress.fraction)))
    elapsed = time.monotonic() - t0
    assert len(seen) == nx * ny and seen[-1][2] == 1.0
    assert image.pixel_size == pytest.approx(pitch)
    assert image.heights.shape == (ny, nx)
    expected = (heights - setpoint / GAIN - z0 * Z_STEP_UM) * 1e-6
    assert np.abs(image.heights - expected).max() <= Z_STEP_UM * 1e-6
    path = afm.save(tmp_path / f"{mode}.gwy")
    assert path.stat().st_size > 0
    print(f"\nMacroAFM on simavr, {mode} {nx}x{ny}: {elapsed:.1f} s")


@pytest.mark.slow
def test_driver_keeps_the_finished_lines_of_a_limit_fault(board_factory, tmp_path):
    from afmsmiler.hardware.errors import DeviceError

    nx, ny, pitch = 6, 8, 200e-6
    heights = bumpy(nx, ny)
    sample = write_map(tmp_path / "sample.txt", heights, pitch * 1e6)
    board = board_factory(*BASE, "--map", str(sample), "--y-max", "1.6")
    afm, z0 = homed_driver(board)
    afm.configure(pixels=nx, lines=ny, pitch=pitch, mode="jumping", lift=0.1e-3)
    with pytest.raises(DeviceError) as info:
        afm.scan()
    assert info.value.code == 6 and "Y" in str(info.value)
    partial = info.value.partial
    assert partial.heights.shape == (3, nx) and not np.isnan(partial.heights).any()
    assert afm.save(tmp_path / "partial.gwy").stat().st_size > 0
    assert afm.status().state.value == "FAULT"


@pytest.mark.slow
def test_driver_reports_the_estop(board_factory, tmp_path):
    from afmsmiler.hardware.errors import DeviceError

    nx = ny = 8
    sample = write_map(tmp_path / "sample.txt", bumpy(nx, ny), 200)
    board = board_factory(*BASE, "--map", str(sample))
    afm, _ = homed_driver(board)
    afm.configure(pixels=nx, lines=ny, pitch=200e-6, mode="contact")

    def press_after_two_lines(progress):
        if progress.done == 2 * nx + 1:
            board.control("ESTOP 1")

    with pytest.raises(DeviceError) as info:
        afm.scan(callback=press_after_two_lines)
    assert info.value.code == 7
    assert info.value.partial.heights.shape[0] == 2
    board.control("ESTOP 0")
    afm.home()  # cleared by homing once the E-stop is released
    assert afm.status().state.value == "IDLE"


@pytest.mark.slow
def test_driver_survives_a_noisy_cable(board_factory, tmp_path):
    """Corrupted, garbage, partial and lost lines both ways: the real firmware's retry handling
    (same SEQ -> the last reply again, never a second execution) and GL give the whole image."""
    from afmsmiler.hardware.transport import FaultyTransport

    nx = ny = 6
    heights = bumpy(nx, ny)
    sample = write_map(tmp_path / "sample.txt", heights, 200)
    board = board_factory(*BASE, "--map", str(sample))
    _, z0 = homed_driver(board)
    device = pytest.importorskip("afmsmiler.hardware.macro.device")
    cable = FaultyTransport(board.port, seed=7, corrupt=0.04, garbage=0.04, drop=0.04,
                            partial=0.04)
    afm = device.MacroAFM(cable, timeout=2.0, retries=6, stream_timeout=5.0,
                          home_timeout=60.0)
    afm.connect()
    wire = afm.configure(pixels=nx, lines=ny, pitch=200e-6, mode="contact", setpoint_force=2e-3)
    setpoint = wire[next(p for p in wire if p.value == "SE")]
    image = afm.scan()
    expected = (heights - setpoint / GAIN - z0 * Z_STEP_UM) * 1e-6
    assert np.abs(image.heights - expected).max() <= Z_STEP_UM * 1e-6
    injected = {k: v for k, v in cable.counts.items() if k != "lines"}
    assert sum(injected.values()) >= 4, injected
    assert afm.retried + afm.garbage > 0


@pytest.mark.slow
def test_driver_keeps_the_lines_when_the_board_goes_away(board_factory, tmp_path, hang_guard):
    """The emulated board dies mid-scan (the USB cable pulled): TransportClosed, lines kept."""
    from afmsmiler.hardware.errors import TransportClosed

    nx = ny = 6
    sample = write_map(tmp_path / "sample.txt", bumpy(nx, ny), 200)
    board = board_factory(*BASE, "--map", str(sample))
    afm, _ = homed_driver(board)
    afm.configure(pixels=nx, lines=ny, pitch=200e-6, mode="contact")

    def unplug(progress):
        if progress.done == 2 * nx + 1:
            board.proc.kill()
            board.proc.wait(timeout=10)

    # the whole test took 14 s at a load of 8 on 2 cores
    with hang_guard(300, expected=15), pytest.raises(TransportClosed) as info:
        afm.scan(callback=unplug)
    assert info.value.partial.heights.shape == (2, nx)
    assert afm.save(tmp_path / "unplugged.gwy").stat().st_size > 0


@pytest.mark.slow
def test_driver_gives_up_on_a_frozen_board(board_factory, tmp_path, hang_guard):
    """The emulator stopped (SIGSTOP): DeviceNotResponding within the driver's bounds, lines
    kept."""
    import signal

    from afmsmiler.hardware.errors import DeviceNotResponding

    nx = ny = 6
    sample = write_map(tmp_path / "sample.txt", bumpy(nx, ny), 200)
    board = board_factory(*BASE, "--map", str(sample))
    device = pytest.importorskip("afmsmiler.hardware.macro.device")
    afm = device.MacroAFM(board.port, timeout=0.5, retries=2, stream_timeout=2.0,
                          home_timeout=60.0)
    afm.connect()
    afm.home()
    board.control("ORIGIN")
    afm.configure(pixels=nx, lines=ny, pitch=200e-6, mode="contact")

    def freeze(progress):
        if progress.done == nx + 1:
            board.proc.send_signal(signal.SIGSTOP)

    t0 = time.monotonic()
    try:
        with pytest.raises(DeviceNotResponding) as info:
            afm.scan(callback=freeze)
    finally:
        board.proc.send_signal(signal.SIGCONT)
    # stream_timeout, then ST with its retries; the lines streamed before the freeze may still
    # be arriving (the pty holds them), so allow a few stream timeouts
    # the whole test took 13 s at a load of 8 on 2 cores
    hang_guard.check(time.monotonic() - t0, 300, expected=15)
    assert info.value.partial is not None and info.value.partial.heights.shape[0] >= 1


@pytest.mark.slow
def test_jumping_mode_images_a_tall_block_that_contact_mode_misses(board_factory, tmp_path):
    """The paper's reason for jumping mode: in contact the needle catches on a wall taller than
    it can climb (the harness' --catch) and the block is missed; jumping lifts over it."""
    nx = ny = 6
    pitch = 200e-6
    heights = np.full((ny, nx), 300.0)
    heights[1:5, 2:4] += 600.0  # 0.4 mm wide, 0.6 mm tall
    sample = write_map(tmp_path / "tall.txt", heights, pitch * 1e6)
    errors = {}
    for mode, lift in (("contact", 0.1e-3), ("jumping", 1.0e-3)):
        board = board_factory(*BASE, "--map", str(sample), "--catch", "200", "--z-top", "4")
        afm, z0 = homed_driver(board)
        wire = afm.configure(pixels=nx, lines=ny, pitch=pitch, mode=mode, lift=lift,
                             setpoint_force=2e-3, step_rate=8000, step_acceleration=80000)
        setpoint = wire[next(p for p in wire if p.value == "SE")]
        image = afm.scan()
        expected = (heights - setpoint / GAIN - z0 * Z_STEP_UM) * 1e-6
        errors[mode] = np.abs(image.heights - expected)
        board.close()
    block = heights > 600
    # contact: the needle stays behind the block's first wall: the block is missed
    assert errors["contact"][block].max() > 500e-6
    assert errors["contact"][~block].max() <= Z_STEP_UM * 1e-6
    # jumping: every pixel within one z micro-step
    assert errors["jumping"].max() <= Z_STEP_UM * 1e-6


@pytest.mark.slow
def test_pause_getline_resume(board_factory, tmp_path):
    nx = ny = 4
    sample = write_map(tmp_path / "sample.txt", bumpy(nx, ny), 200)
    board = board_factory(*BASE, "--map", str(sample))
    ok(board.command("HM")[0], "HM")
    board.until(lambda f: f.code == "EV" and f.args[0] == "HOMED", timeout=60)
    board.control("ORIGIN")
    for par, value in (("NX", nx), ("NY", ny)):
        ok(board.command("SP", par, value)[0], "SP")
    assert board.command("RS")[0].args == (10,)  # not paused
    ok(board.command("SS")[0], "SS")
    first = board.until(lambda f: f.code == "LN", timeout=60)
    reply, seen = board.command("PA")
    ok(reply, "PA")
    seen += board.until(lambda f: f.code == "EV" and f.args[0] == "PAUSED", timeout=30)
    state, row, col, flags = ok(board.command("ST")[0], "ST")
    assert state == "PAUSED" and flags & 1
    at_pause = board.position()
    time.sleep(0.3)
    assert board.position() == at_pause
    reply, again = board.command("GL", 0)
    assert ok(reply, "GL") == (0, nx)
    assert [f.args for f in again] == [f.args for f in first if f.code == "PX"]
    assert board.command("SP", "NX", 8)[0].args == (4,)  # busy while paused
    ok(board.command("RS")[0], "RS")
    rest = board.until(lambda f: f.code == "EV" and f.args[0] == "DONE", timeout=60)
    pixels = {f.args[:2] for f in first + seen + rest if f.code == "PX"}
    assert pixels == {(r, c) for r in range(ny) for c in range(nx)}


@pytest.mark.slow
def test_gauge_disconnected_mid_scan(board_factory, tmp_path):
    """The HX711 stops answering: ER 8 (SENSOR) after 500 ms, FAULT, the finished line kept."""
    nx = ny = 4
    sample = write_map(tmp_path / "sample.txt", bumpy(nx, ny), 200)
    board = board_factory(*BASE, "--map", str(sample))
    ok(board.command("HM")[0], "HM")
    board.until(lambda f: f.code == "EV" and f.args[0] == "HOMED", timeout=60)
    board.control("ORIGIN")
    for par, value in (("NX", nx), ("NY", ny)):
        ok(board.command("SP", par, value)[0], "SP")
    ok(board.command("SS")[0], "SS")
    board.until(lambda f: f.code == "LN", timeout=60)
    assert board.control("GAUGE 0") == "OK GAUGE 0"
    tail = board.until(lambda f: f.code == "ER", timeout=30)
    assert (tail[-1].seq, tail[-1].args) == (0, (8,))
    assert ok(board.command("ST")[0], "ST")[0] == "FAULT"
    # after 500 ms of simulated time without a reading
    assert eventually(lambda: board.command("RG")[0].args == (8,))
    assert ok(board.command("GL", 0)[0], "GL") == (0, nx)
    board.control("GAUGE 1")
    assert eventually(lambda: board.command("RG")[0].code == "OK")
