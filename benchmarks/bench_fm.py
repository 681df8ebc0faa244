"""Module (g) speed, frequency modulation and lateral force: a 200-point df(z) curve by
Giessibl's formula (target: < 10 ms, slider speed) against the named peer, a scipy.integrate.quad
loop with QUADPACK's algebraic endpoint weight (QAWS) over the same points; the Sader-Jarvis
inversion of a 1000-point curve (target: < 100 ms); a 256 x 256 friction scan (target: < 50 ms).

Both sides of the df comparison integrate the same Morse force to about 1e-6; the peer calls the
force as a plain-float ``math`` function (numpy's per-call overhead would flatter the ratio).
"""
import math
import sys
from pathlib import Path

import numpy as np
from scipy.integrate import quad

sys.path.insert(0, str(Path(__file__).parent))
from _timing import best_time, report  # noqa: E402

from afmsmiler.modes.fm import frequency_shift, sader_jarvis  # noqa: E402
from afmsmiler.modes.lateral import friction_sample, friction_scan  # noqa: E402

K, F0, A = 40.0, 300e3, 1e-9
U0, LAM, Z0 = 1e-19, 0.2e-9, 0.3e-9
Z = np.linspace(0.2e-9, 3e-9, 200)


def morse(z):
    e = np.exp(-(z - Z0) / LAM)
    return 2 * U0 / LAM * (e * e - e)


def morse_scalar(z):
    e = math.exp(-(z - Z0) / LAM)
    return 2 * U0 / LAM * (e * e - e)


def ours():
    return frequency_shift(morse, Z, spring_constant=K, resonance_frequency=F0, amplitude=A)


def peer():
    return [-F0 / (math.pi * K * A) * quad(lambda u: morse_scalar(z + A * (1 + u)) * u, -1, 1,
                                           weight="alg", wvar=(-0.5, -0.5))[0] for z in Z]


def main():
    assert np.allclose(ours(), peer(), rtol=1e-5, atol=1e-9)
    z = np.linspace(0.2e-9, 6e-9, 1000)
    df = frequency_shift(morse, z, spring_constant=K, resonance_frequency=F0, amplitude=A)
    topo, mu = friction_sample((256, 256), 10e-9, tilt=0.1, bump_height=20e-9)
    t_ours, t_peer = best_time(ours), best_time(peer, repeat=3)
    report([
        ("frequency_shift, 200 points (peer: quad QAWS loop)", t_ours, 10e-3, t_peer),
        ("sader_jarvis, 1000 points", best_time(lambda: sader_jarvis(
            z, df, spring_constant=K, resonance_frequency=F0, amplitude=A), repeat=3), 0.1,
         None),
        ("friction_scan, 256 x 256", best_time(lambda: friction_scan(topo, mu), repeat=3),
         50e-3, None),
    ])


if __name__ == "__main__":
    main()
