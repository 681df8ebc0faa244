"""Module (g) speed: the tapping-mode amplitude-distance curve, 200 distances (target: < 50 ms),
against the named peer, the reference time integration (scipy solve_ivp to steady state,
:func:`afmsmiler.modes.integrate`), timed in the same run.

Ours finds every steady state (both branches, their stability) at each of 200 distances from
0.5 nm to 15 nm for the default lever (k = 40 N/m, f0 = 300 kHz, Q = 400, A0 = 10 nm; R = 10 nm,
E = 1 GPa, sample viscosity 100 Pa s). The peer integrates the motion from the free oscillation
(the start a user without the fast solver has) until the transient criterion holds, at three of
those distances (far, attractive and repulsive regime); its time for 200 distances is 200 times
its mean per distance, printed as such. It finds one state per distance (the one its start leads
to); ours finds all of them.
"""
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))
from _timing import best_time, report  # noqa: E402

from afmsmiler.modes import TappingLever, amplitude_curve, integrate  # noqa: E402

LEVER = TappingLever(sample_viscosity=100.0)
Z = np.linspace(0.5e-9, 15e-9, 200)
PEER_Z = (12e-9, 7e-9, 3e-9)


def ours():
    amplitude_curve(Z, LEVER)


def peer_per_point():
    t0 = time.perf_counter()
    periods = [integrate(z, LEVER).periods for z in PEER_Z]
    return (time.perf_counter() - t0) / len(PEER_Z), periods


def main():
    t = best_time(ours)
    t_peer, periods = peer_per_point()
    print(f"peer: {len(PEER_Z)} integrations, {periods} drive periods to steady state", flush=True)
    report([("tapping: amplitude_curve, 200 distances, all roots", t, 0.05, 200 * t_peer)])


if __name__ == "__main__":
    main()
