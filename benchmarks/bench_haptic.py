"""Module (h) haptic speed: the force bridge's achieved rate and jitter at a 1 kHz target.

For 5 s each, the ForceBridge streams module (d)'s indentation force (the test load: a table
lookup per tick at the handle's latest position) to the haptic twin served in this process
(its firmware loop, motor and finger simulated tick by tick in the server's thread), over
(1) a MemoryTransport pair and (2) a pty opened by pyserial at 1 000 000 baud, as a real port
would be. The bridge measures itself (BridgeStats: achieved rate, median and 99th percentile of
|period - 1 ms|, missed deadlines). The named peer, measured in the same run on the same link,
is the loop a student would write first: ``time.sleep(1 ms)`` after each tick. Printed: the
figures of both and the peer's jitter over ours.
"""
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

from afmsmiler.contact import ContactSystem, Parabolic  # noqa: E402
from afmsmiler.hardware import SerialTransport, open_twin  # noqa: E402
from afmsmiler.hardware.haptic import HapticDevice, HapticTwin  # noqa: E402
from afmsmiler.hardware.haptic.bridge import ForceBridge, IndentationSource  # noqa: E402

DURATION = 5.0
RATE = 1000.0


def _source():
    system = ContactSystem(tip=Parabolic(radius=20e-9), youngs_modulus=1e9, poisson_ratio=0.3)
    return IndentationSource(system, max_depth=50e-9)


def _device(pty: bool):
    twin = HapticTwin()
    link, server = open_twin(twin, pty=pty, time_scale=1.0)
    host = SerialTransport(link, baudrate=1_000_000) if pty else link
    dev = HapticDevice(host, timeout=1.0)
    dev.connect()
    dev.configure(spring=500.0)
    dev.enable()
    dev.start_stream(1e-3)
    return dev, server


def _naive(source, dev, duration):
    """The peer: force, send, sleep one period; its rate and jitter measured the same way."""
    starts = []
    t0 = time.perf_counter()
    while time.perf_counter() - t0 < duration:
        starts.append(time.perf_counter())
        s = dev.latest()
        dev.send_force(1e7 * source.force(0.0, 1e-5 * (s.position if s else 0.0)))
        time.sleep(1.0 / RATE)
    import numpy as np
    d = np.diff(starts)
    err = np.abs(d - 1.0 / RATE)
    return (len(starts) - 1) / (starts[-1] - starts[0]), float(np.median(err)), \
        float(np.percentile(err, 99))


def _line(label, rate, med, p99, missed=None):
    extra = "" if missed is None else f", missed {missed}"
    print(f"{label:<44s} rate {rate:8.1f} Hz   jitter median {med * 1e6:8.1f} us   "
          f"p99 {p99 * 1e6:8.1f} us{extra}", flush=True)


def main():
    source = _source()
    for name, pty in (("MemoryTransport", False), ("pty at 1 Mbaud", True)):
        dev, server = _device(pty)
        try:
            bridge = ForceBridge(source, dev, rate=RATE, force_scale=1e7, position_scale=1e-5)
            stats = bridge.run(duration=DURATION)
            _line(f"ForceBridge -> twin, {name}", stats.rate, stats.jitter_median,
                  stats.jitter_p99, stats.missed)
            rate, med, p99 = _naive(source, dev, DURATION)
            _line(f"peer: sleep(1 ms) loop, {name}", rate, med, p99)
            print(f"{'':<44s} peer/ours p99 jitter = {p99 / stats.jitter_p99:6.1f}x, "
                  f"rate ours/peer = {stats.rate / rate:5.2f}x", flush=True)
        finally:
            dev.close()
            server.stop()


if __name__ == "__main__":
    main()
