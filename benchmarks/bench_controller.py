"""Module (c): a 512-pixel line (trace and retrace, both outputs) and a 256 x 256 image.

The image is scanned as an engaged instrument does it (the default of ``scan_image``): one
polygon through trace 0, retrace 0, trace 1, ..., each row continuing from the previous one's
end state; the independent-rows batch (``chained=False``) is timed too.

Peer: python-control's ``forced_response`` on the same closed-loop transfer functions and the same
back-and-forth polygon (its exact linear-hold discretisation, one matrix exponential per call and
a Python loop over the samples). Parameters change before every call (a new loop each time), as
when a slider moves. Targets (issue 3): >= 10x faster than the peer and < 0.5 ms per line;
< 0.2 s per 256 x 256 image.
"""
import sys
from pathlib import Path

import control
import numpy as np

sys.path.insert(0, str(Path(__file__).parent))
from _timing import best_time, report  # noqa: E402

from afmsmiler import samples  # noqa: E402
from afmsmiler.controller import ContactLoop, scan_image  # noqa: E402
from afmsmiler.controller.defaults import BASE, SETPOINT  # noqa: E402

SPEED = 1e-3
line = samples.profile("real line", 512, 4e-9, 50e-9)
image = samples.particles((256, 256), 4e-9)
rng = np.random.default_rng(0)
gains = rng.uniform(0.2, 2.0, size=(1000, 2))
state = {"i": 0}


def next_loop():
    state["i"] = (state["i"] + 1) % len(gains)
    kp, ki = gains[state["i"]]
    return ContactLoop(**{**BASE, "kp": kp, "ki": ki * BASE["ki"]})


def ours():
    return next_loop().scan_line(line.x, line.heights, speed=SPEED, setpoint=SETPOINT)


t_path = np.arange(2 * line.heights.size - 1) * line.pixel_size / SPEED
h_path = np.concatenate((line.heights, line.heights[::-1][1:])) - line.heights[0]


def peer():
    loop = next_loop()
    zc_T, znp_T = loop.closed_loop()
    z0 = loop.steady_state(SETPOINT, line.heights[0])
    z_c = control.forced_response(zc_T, t_path, h_path).outputs + z0.z_c
    z_np = control.forced_response(znp_T, t_path, h_path).outputs + z0.z_np
    return z_c, z_np


def image_scan():
    return scan_image(next_loop(), image.heights, image.pixel_size, speed=SPEED, setpoint=SETPOINT)


def image_scan_rows_alone():
    return scan_image(next_loop(), image.heights, image.pixel_size, speed=SPEED, setpoint=SETPOINT,
                      chained=False)


if __name__ == "__main__":
    # same numbers first (so that the ratio compares equal work)
    state["i"] = 0
    a = ours()
    state["i"] = 0
    b = peer()
    err = np.max(np.abs(np.concatenate((a.trace.z_np, a.retrace.z_np[1:])) - b[1]))
    print(f"ours vs peer, max |dZ_np| = {err:.2e} m on a {np.ptp(b[1]):.2e} m range")
    t_ours = best_time(ours)
    t_peer = best_time(peer, repeat=5)
    t_img = best_time(image_scan, repeat=5, number=3)
    t_rows = best_time(image_scan_rows_alone, repeat=5, number=3)
    report([
        ("512-pixel line, trace+retrace, Z_c and Z_np (ours)", t_ours, 0.5e-3, t_peer),
        ("  same with control.forced_response (peer)", t_peer, None, None),
        ("256 x 256 image, rows chained (ours, default)", t_img, 0.2, None),
        ("  same, rows restarted independently (batch)", t_rows, 0.2, None),
    ])
