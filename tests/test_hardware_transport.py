"""Transports of module (h): memory pair, pyserial port, pty, fault injector; and the twin server.

No hardware: the pty test opens the pseudo-terminal with pyserial exactly as a real port.
"""
import threading
import time

import pytest
import serial

from afmsmiler.hardware import (ChecksumError, FaultyTransport, Frame, FrameError,
                                MemoryTransport, PtyLink, SerialTransport, TransportClosed,
                                TransportTimeout, Twin, TwinServer, decode_frame, encode_frame,
                                open_twin)
from afmsmiler.hardware.transport import MAX_LINE


@pytest.fixture(autouse=True)
def no_leaked_threads():
    before = set(threading.enumerate())
    yield
    deadline = time.monotonic() + 2.0
    while time.monotonic() < deadline:
        leaked = [t for t in threading.enumerate() if t not in before and t.is_alive()]
        if not leaked:
            break
        time.sleep(0.01)
    assert not leaked, f"threads left running: {leaked}"


# -- MemoryTransport ------------------------------------------------------------------------
def test_memory_pair_lines_both_ways():
    a, b = MemoryTransport.pair()
    a.write(b"hello\r\nwor")
    a.write(b"ld\n")
    assert b.readline(0.1) == b"hello"
    assert b.readline(0.1) == b"world"
    b.write(b"back\n")
    assert a.readline(0.1) == b"back"


def test_memory_readline_times_out_in_bounded_time(hang_guard):
    a, b = MemoryTransport.pair()
    b.write(b"partial line without newline")
    t0 = time.monotonic()
    with hang_guard(5, expected=0.05), pytest.raises(TransportTimeout):
        a.readline(0.05)
    assert time.monotonic() - t0 > 0.04  # it waited its timeout (a load only makes it later)
    with pytest.raises(TransportTimeout):
        a.readline(0)


def test_memory_long_run_without_newline_is_one_junk_line():
    a, b = MemoryTransport.pair()
    b.write(b"x" * (MAX_LINE + 10) + b"\n")
    junk = a.readline(0.1)
    assert len(junk) == MAX_LINE
    with pytest.raises(FrameError):
        decode_frame(junk)
    assert a.readline(0.1) == b"x" * 10


def test_memory_close_is_seen_by_both_ends():
    a, b = MemoryTransport.pair()
    a.write(b"last\n")
    a.close()
    assert b.readline(0.1) == b"last"  # what was sent before the close still arrives
    with pytest.raises(TransportClosed):
        b.readline(0.1)
    with pytest.raises(TransportClosed):
        b.write(b"x\n")
    with pytest.raises(TransportClosed):
        a.write(b"x\n")
    a.close()  # idempotent


def test_memory_close_wakes_a_blocked_reader(hang_guard):
    a, b = MemoryTransport.pair()
    threading.Timer(0.05, a.close).start()
    # woken by the close after 0.05 s, long before the 60 s timeout
    with hang_guard(5, expected=0.05), pytest.raises(TransportClosed):
        b.readline(60.0)


def test_memory_is_thread_safe():
    a, b = MemoryTransport.pair()
    frames = [encode_frame(Frame(0, "PX", (w, i, i, -i))) for w in range(4) for i in range(200)]

    def writer(w):
        for i in range(200):
            a.write(encode_frame(Frame(0, "PX", (w, i, i, -i))))

    threads = [threading.Thread(target=writer, args=(w,)) for w in range(4)]
    for t in threads:
        t.start()
    got = [b.readline(2.0) + b"\n" for _ in frames]
    for t in threads:
        t.join()
    assert sorted(got) == sorted(frames)


@pytest.mark.parametrize("bad", [-1, float("nan"), float("inf"), None, "one"])
def test_readline_rejects_bad_timeouts(bad):
    a, _ = MemoryTransport.pair()
    with pytest.raises(ValueError, match="timeout"):
        a.readline(bad)


# -- PtyLink and SerialTransport ----------------------------------------------------------------
def test_pty_opened_by_pyserial_like_a_real_port():
    with PtyLink() as link:
        port = serial.Serial(link.path, 115200, timeout=0.5)
        try:
            port.write(b"1 ID*C1\r\n")
            assert link.device_end.readline(1.0) == b"1 ID*C1"  # \r dropped on input
            link.device_end.write(b"1 OK\r\n")
            assert port.readline() == b"1 OK\r\n"  # raw: no newline translation
            port.write(b"abc\n")
            assert port.read(10) == b""  # no echo: nothing comes back
            assert link.device_end.readline(1.0) == b"abc"
        finally:
            port.close()


def test_serial_transport_over_pty(hang_guard):
    with PtyLink() as link:
        host = SerialTransport(link.path)
        try:
            link.device_end.write(b"0 PX 1 2 3 4*00\npartial")
            assert host.readline(1.0) == b"0 PX 1 2 3 4*00"
            with hang_guard(5, expected=0.05), pytest.raises(TransportTimeout):
                host.readline(0.05)
            link.device_end.write(b" end\n")
            assert host.readline(1.0) == b"partial end"
            host.write(b"1 ST*00\n")
            assert link.device_end.readline(1.0) == b"1 ST*00"
        finally:
            host.close()


def test_serial_transport_unplugged_raises_transport_closed():
    link = PtyLink()
    host = SerialTransport(link.path)
    try:
        link.close()  # the board is unplugged
        with pytest.raises(TransportClosed):
            for _ in range(3):
                host.readline(0.2)
    finally:
        host.close()


def test_serial_transport_closed_port_raises_transport_closed():
    with PtyLink() as link:
        host = SerialTransport(link.path)
        host.close()
        with pytest.raises(TransportClosed):
            host.write(b"x\n")
        with pytest.raises(TransportClosed):
            host.readline(0.1)


def test_serial_transport_missing_port():
    with pytest.raises(TransportClosed, match="/dev/ttyNOPE"):
        SerialTransport("/dev/ttyNOPE")


# -- FaultyTransport ----------------------------------------------------------------------------
def _lines(n):
    return [encode_frame(Frame(0, "PX", (0, i, 10 * i, i))) for i in range(n)]


def _read_all(faulty, n_expected):
    out = []
    while True:
        try:
            out.append(faulty.readline(0.01))
        except TransportTimeout:
            return out


def _feed(n, **faults):
    host, device = MemoryTransport.pair()
    for line in _lines(n):
        device.write(line)
    return FaultyTransport(host, **faults), device


@pytest.mark.parametrize("fault", ["corrupt", "garbage", "drop", "partial"])
def test_faults_are_deterministic_with_a_seed(fault):
    runs = []
    for _ in range(2):
        faulty, _ = _feed(200, seed=7, **{fault: 0.2})
        runs.append((_read_all(faulty, 200), dict(faulty.counts)))
    assert runs[0] == runs[1]
    assert 15 < runs[0][1][fault] < 70  # about 20 % of 200
    other, _ = _feed(200, seed=8, **{fault: 0.2})
    assert _read_all(other, 200) != runs[0][0]


def test_no_faults_is_transparent():
    faulty, _ = _feed(50)
    assert [line + b"\n" for line in _read_all(faulty, 50)] == _lines(50)


def test_corrupted_lines_fail_their_checksum():
    faulty, _ = _feed(300, seed=1, corrupt=1.0)
    got = _read_all(faulty, 300)
    assert len(got) == 300
    for line in got:
        with pytest.raises(FrameError):
            decode_frame(line)
    assert sum(1 for line in got if _is_checksum_error(line)) > 250  # mostly body bytes


def _is_checksum_error(line):
    try:
        decode_frame(line)
    except ChecksumError:
        return True
    except FrameError:
        return False
    return False


def test_garbage_comes_before_the_real_line_which_is_kept():
    faulty, _ = _feed(100, seed=2, garbage=0.3)
    got = _read_all(faulty, 100)
    good = [line for line in got if not _bad(line)]
    assert [g + b"\n" for g in good] == _lines(100)
    assert len(got) - len(good) == faulty.counts["garbage"] > 10


def _bad(line):
    try:
        decode_frame(line)
    except FrameError:
        return True
    return False


def test_dropped_and_partial_lines():
    faulty, _ = _feed(200, seed=3, drop=0.1, partial=0.1)
    got = _read_all(faulty, 200)
    assert len(got) == 200 - faulty.counts["drop"]
    assert sum(_bad(line) for line in got) == faulty.counts["partial"] > 5


def test_unplug_after_lines():
    faulty, device = _feed(20, unplug_after_lines=5)
    for _ in range(5):
        faulty.readline(0.1)
    with pytest.raises(TransportClosed):
        faulty.readline(0.1)
    with pytest.raises(TransportClosed):
        faulty.write(b"1 ST*00\n")
    with pytest.raises(TransportClosed):
        device.write(b"x\n")  # the far end sees the cable gone too


def test_silent_after_lines(hang_guard):
    faulty, device = _feed(20, silent_after_lines=3)
    for _ in range(3):
        faulty.readline(0.1)
    t0 = time.monotonic()
    with hang_guard(5, expected=0.05), pytest.raises(TransportTimeout):
        faulty.readline(0.05)
    assert time.monotonic() - t0 > 0.04  # it waited its timeout (a load only makes it later)
    faulty.write(b"1 ST*00\n")  # lost
    with pytest.raises(TransportTimeout):
        device.readline(0.01)


def test_write_faults():
    host, device = MemoryTransport.pair()
    faulty = FaultyTransport(host, seed=4, drop=0.5)
    for line in _lines(100):
        faulty.write(line)
    received = _read_all(device, 100)
    assert len(received) == 100 - faulty.counts["drop"]
    quiet = FaultyTransport(MemoryTransport.pair()[0], drop=1.0, writes=False)
    quiet.write(b"x\n")  # writes=False: never dropped
    assert quiet.counts["drop"] == 0


@pytest.mark.parametrize("kwargs, name", [
    ({"corrupt": 1.5}, "corrupt"), ({"drop": -0.1}, "drop"), ({"garbage": "x"}, "garbage"),
    ({"unplug_after_lines": -1}, "unplug_after_lines"),
    ({"silent_after_lines": 1.5}, "silent_after_lines"),
])
def test_faulty_validates(kwargs, name):
    with pytest.raises(ValueError, match=name):
        FaultyTransport(MemoryTransport.pair()[0], **kwargs)


# -- Twin and TwinServer ------------------------------------------------------------------------
class Counter(Twin):
    """A tiny device: ``CT`` counts how often it ran; ``TK n`` streams n ticks 0.01 s apart."""

    DEVICE = "COUNTER"

    def __init__(self):
        super().__init__()
        self.count = 0
        self.ticks = []

    def execute(self, frame):
        if frame.code == "CT":
            self.count += 1
            return [self.ok(frame, self.count)]
        if frame.code == "TK":
            n = frame.args[0]
            self.ticks = [self.now + 0.01 * (i + 1) for i in range(n)]
            return [self.ok(frame)]
        if frame.code == "BG":
            raise RuntimeError("a bug in the twin")
        return super().execute(frame)

    def poll(self, now):
        super().poll(now)
        out = []
        while self.ticks and self.ticks[0] <= self.now:
            self.ticks.pop(0)
            out.append(Frame(0, "TI", (len(self.ticks),)))
        return out

    def next_due(self):
        return self.ticks[0] if self.ticks else None


def _ask(host, frame, timeout=1.0):
    host.write(encode_frame(frame))
    return decode_frame(host.readline(timeout))


def test_twin_handle_is_pure_and_retries_are_safe():
    twin = Counter()
    assert twin.handle(Frame(1, "ID")) == [Frame(1, "OK", ("ID", "COUNTER", 1, "0.1.0"))]
    assert twin.handle(Frame(2, "CT")) == [Frame(2, "OK", ("CT", 1))]
    assert twin.handle(Frame(2, "CT")) == [Frame(2, "OK", ("CT", 1))]  # a retry: not run again
    assert twin.count == 1
    assert twin.handle(Frame(3, "CT")) == [Frame(3, "OK", ("CT", 2))]
    assert twin.handle(Frame(4, "ZZ")) == [Frame(4, "ER", (2, "ZZ"))]
    assert twin.handle(Frame(0, "ZZ")) == []  # a host stream frame gets no reply


def test_server_answers_like_the_firmware():
    host, server = open_twin(Counter())
    try:
        assert _ask(host, Frame(1, "ID")).args == ("ID", "COUNTER", 1, "0.1.0")
        host.write(b"1 ID*C2\n")
        assert decode_frame(host.readline(1.0)) == Frame(0, "ER", (1,))
        host.write(b"\x00\x01 hello\n")
        assert decode_frame(host.readline(1.0)) == Frame(0, "ER", (9,))
        assert _ask(host, Frame(2, "CT")).args == ("CT", 1)
        assert _ask(host, Frame(2, "CT")).args == ("CT", 1)
        assert server.twin.count == 1
    finally:
        server.stop()
        host.close()
    assert not server.running


def test_server_streams_as_fast_as_possible_at_time_scale_0(hang_guard):
    host, server = open_twin(Counter(), time_scale=0.0)
    try:
        # 30 s of twin time (3000 ticks 0.01 s apart) in well under 30 s: the server never waits
        with hang_guard(15, expected=0.5):
            assert _ask(host, Frame(1, "TK", (3000,))).code == "OK"
            ticks = [decode_frame(host.readline(1.0)) for _ in range(3000)]
        assert ticks[-1] == Frame(0, "TI", (0,))
        assert server.twin.now == pytest.approx(30.0)
    finally:
        server.stop()


def test_server_keeps_the_real_pace_at_time_scale_1(hang_guard):
    host, server = open_twin(Counter(), time_scale=1.0)
    try:
        t0 = time.monotonic()
        with hang_guard(5, expected=0.1):
            _ask(host, Frame(1, "TK", (10,)))
            for _ in range(10):
                host.readline(1.0)
        assert time.monotonic() - t0 > 0.09  # 10 ticks 0.01 s apart: never ahead of real time
    finally:
        server.stop()


def test_server_over_pty_opened_by_pyserial():
    path, server = open_twin(Counter(), pty=True)
    host = SerialTransport(path)
    try:
        assert _ask(host, Frame(1, "ID")).args[1] == "COUNTER"
    finally:
        host.close()
        server.stop()


def test_server_stops_when_the_host_goes_away():
    host, server = open_twin(Counter())
    host.close()
    deadline = time.monotonic() + 2.0
    while server.running and time.monotonic() < deadline:
        time.sleep(0.01)
    assert not server.running
    server.stop()


def test_a_twin_bug_surfaces_on_stop():
    host, server = open_twin(Counter())
    host.write(encode_frame(Frame(1, "BG")))
    deadline = time.monotonic() + 2.0
    while server.running and time.monotonic() < deadline:
        time.sleep(0.01)
    with pytest.raises(RuntimeError, match="a bug in the twin"):
        server.stop()


def test_server_validates():
    with pytest.raises(TypeError, match="twin"):
        TwinServer(object(), MemoryTransport.pair()[1])
    with pytest.raises(ValueError, match="time_scale"):
        TwinServer(Counter(), MemoryTransport.pair()[1], time_scale=-1)


def test_memory_capacity_makes_a_fast_writer_wait_for_its_reader():
    a, b = MemoryTransport.pair(capacity=64)
    a.write(b"x" * 63 + b"\n")
    got = []
    threading.Timer(0.1, lambda: got.append(b.readline(1.0))).start()
    t0 = time.monotonic()
    a.write(b"y\n")  # waits until the reader has taken the first line
    assert time.monotonic() - t0 > 0.05  # it waited for the reader (a load only makes it later)
    time.sleep(0.05)
    assert got == [b"x" * 63]
    assert b.readline(0.1) == b"y"
    with pytest.raises(ValueError, match="capacity"):
        MemoryTransport.pair(capacity=0)


def test_server_stops_promptly_when_the_host_never_reads(hang_guard):
    host, server = open_twin(Counter())
    host.write(encode_frame(Frame(1, "TK", (500,))))  # 500 ticks, far more than the link holds
    time.sleep(0.2)
    with hang_guard(5, expected=0.05):
        server.stop()
