"""Module (h) part 2 speed: one lock-in panel update (the educational AFM's chain simulated over
the record the default filter needs, demodulated at 2 omega, its spectrum taken; target < 0.2 s),
against the named peer, a time integration of the same drive (scipy solve_ivp: the heater's
first-order thermal lag and the lever's mode, from rest, over the same record), timed in the same
run.

Ours computes the periodic steady state in the frequency domain (one FFT of the heater power, the
transfer function at every bin, one inverse FFT) plus the noise; the peer integrates the ODEs
through the lever's ring-up (Q = 150 cycles) and the record, the way a user without the
frequency-domain method would, and gives no noise.
"""
import math
import sys
import time
from pathlib import Path

from scipy.integrate import solve_ivp

sys.path.insert(0, str(Path(__file__).parent))
from _timing import best_time, report  # noqa: E402

from afmsmiler.signals import ActiveProbe  # noqa: E402
from afmsmiler.signals.demo import lock_in_demo  # noqa: E402
from afmsmiler.signals.lockin import TIME_CONSTANT, settling_time  # noqa: E402

PROBE = ActiveProbe()


def ours():
    lock_in_demo()


def peer():
    """solve_ivp of tau T' = P - T, z'' + (w1/Q) z' + w1^2 z = w1^2 k_P T, from rest."""
    a = PROBE.actuator
    w1, q, tau = 2 * math.pi * a.resonance_frequency, a.quality_factor, a.thermal_time_constant
    w = w1 / 2
    gain = a.deflection_per_watt()
    record = settling_time(TIME_CONSTANT.default, 4) + 200 / (2 * w / (2 * math.pi))

    def rhs(t, s):
        temp, z, v = s
        p = (a.ac_voltage * math.sin(w * t)) ** 2 / a.resistance
        return [(p - temp) / tau, v, -w1 / q * v - w1 ** 2 * (z - gain * temp)]
    t0 = time.perf_counter()
    solve_ivp(rhs, (0.0, record), [0.0, 0.0, 0.0], rtol=1e-6, atol=1e-15, method="RK45",
              max_step=2 * math.pi / w1 / 16)
    return time.perf_counter() - t0


def main():
    t = best_time(ours, repeat=5)
    t_peer = peer()
    report([("lock-in panel update: chain + lock-in + spectrum", t, 0.2, t_peer)])


if __name__ == "__main__":
    main()
