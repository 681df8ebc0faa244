"""Module (h) speed: frames through the codec and a pty, and a twin scan, against the wire.

The named peer is the serial line itself: a 115200 baud 8N1 link carries 11520 bytes/s, so a
pixel frame (``0 PX 12 34 -1205 13143*XX``, about 26 bytes) takes about 2.3 ms on the wire. The
driver must decode faster than that (peer/ours > 1 means it keeps up with a board); the pty run
measures frames/s end to end (twin -> pty -> pyserial -> decode). The twin's scan is compared with
the real machine's time for the same image (the twin's own clock at time_scale 1).
"""
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _timing import best_time, report  # noqa: E402

from afmsmiler.hardware import MacroAFM, SerialTransport, open_twin  # noqa: E402
from afmsmiler.hardware.framing import Frame, encode_frame  # noqa: E402
from afmsmiler.hardware.macro import MacroAFMCodec, MacroAFMTwin, printed_sample  # noqa: E402
from afmsmiler.hardware.twin import Twin  # noqa: E402

BAUD_BYTES = 115200 / 10  # 8N1: 10 bits per byte
LINES = [encode_frame(Frame(0, "PX", (i // 128, i % 128, -1205 + i, 13143 - i)))
         for i in range(1000)]


def wire_time(lines) -> float:
    return sum(len(line) for line in lines) / BAUD_BYTES


def decode_all():
    parse = MacroAFMCodec.parse
    for line in LINES:
        parse(line)


class Streamer(Twin):
    """A twin that streams N pixel frames on ``GO`` as fast as the link takes them."""

    def __init__(self, n):
        super().__init__()
        self.todo = 0
        self.n = n

    def execute(self, frame):
        self.todo = self.n
        return [self.ok(frame)]

    def poll(self, now):
        super().poll(now)
        out = []
        while self.todo and len(out) < 32:
            self.todo -= 1
            out.append(Frame(0, "PX", (0, self.todo % 128, self.todo, 13143)))
        return out

    def next_due(self):
        return self.now if self.todo else None


def through_pty(n=2000) -> float:
    path, server = open_twin(Streamer(n), pty=True)
    host = SerialTransport(path)
    try:
        host.write(encode_frame(Frame(1, "GO")))
        host.readline(2.0)
        t0 = time.perf_counter()
        for _ in range(n):
            MacroAFMCodec.parse(host.readline(2.0))
        return (time.perf_counter() - t0) / n
    finally:
        host.close()
        server.stop()


def twin_scan(pixels=32):
    twin = MacroAFMTwin(sample=printed_sample(pixels=pixels, pixel_size=0.4e-3, height=1e-3))
    host, server = open_twin(twin)
    try:
        afm = MacroAFM(host)
        afm.connect()
        afm.configure(pixels=pixels, lines=pixels, pitch=0.4e-3, mode="contact")
        afm.home()
        start = twin.now
        t0 = time.perf_counter()
        afm.scan()
        return time.perf_counter() - t0, twin.now - start
    finally:
        server.stop()


def main():
    t_decode = best_time(decode_all, repeat=5) / len(LINES)
    t_pty = through_pty()
    t_scan, t_machine = twin_scan()
    per_frame_wire = wire_time(LINES) / len(LINES)
    print(f"peer: the 115200 baud wire, {per_frame_wire * 1e3:.2f} ms per pixel frame; the "
          f"machine's 32 x 32 contact scan takes {t_machine:.0f} s", flush=True)
    report([
        ("hardware: decode one pixel frame (codec)", t_decode, per_frame_wire, per_frame_wire),
        ("hardware: one pixel frame twin -> pty -> pyserial -> decode", t_pty, per_frame_wire,
         per_frame_wire),
        ("hardware: twin scan 32 x 32 through MacroAFM (time_scale 0)", t_scan, 10.0, t_machine),
    ])


if __name__ == "__main__":
    main()
