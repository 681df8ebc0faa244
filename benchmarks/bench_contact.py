"""Module (d) speed: 1000-point indentation curves for the four tips (target: < 5 ms in total),
against the named peer, a scalar scipy.optimize.brentq loop solving the same points (target:
>= 20x).

Both sides solve k (Z_np - Z_s) = F(Z_s) to full precision; the peer calls brentq once per point on
the bracket [0, Z_np] (the paper's approach, with a proper root finder) with each force law written
as a plain-float ``math`` function: the paraboloid, cone and pyramid in Z_s, the sphere in its
parametric variable u = r / R on [0, 1) (its F(Z_s) has no closed form). A peer calling the
library's array functions point by point would pay numpy's per-call overhead and, for the sphere,
a nested inversion, and would flatter the ratio (it did: 874x).
"""
import math
import sys
from pathlib import Path

import numpy as np
from scipy.optimize import brentq

sys.path.insert(0, str(Path(__file__).parent))
from _timing import best_time, report  # noqa: E402

from afmsmiler.contact import (Conical, ContactSystem, Parabolic, Pyramidal,  # noqa: E402
                               Spherical, reduced_modulus)

K, E, NU = 0.1, 1e6, 0.3
E_STAR = reduced_modulus(E, NU)
TIPS = [Parabolic(20e-9), Spherical(500e-9), Conical(math.radians(20)), Pyramidal(math.radians(35))]
SYSTEMS = [ContactSystem(spring_constant=K, tip=tip, youngs_modulus=E, poisson_ratio=NU)
           for tip in TIPS]
Z = np.linspace(-50e-9, 300e-9, 1000)


def ours():
    for system in SYSTEMS:
        system.indent(Z)


def _scalar_law(tip):
    """(g, lo, hi, to_depth): the peer's residual in its own variable, bracket and map to Z_s."""
    if isinstance(tip, Spherical):
        r = tip.radius

        def g(u, z):
            at = math.atanh(u)
            return K * (z - r * u * at) - E_STAR * r * r * ((1.0 + u * u) * at - u)
        return g, (lambda z: 1.0 - 1e-15), (lambda u: r * u * math.atanh(u))
    if isinstance(tip, Parabolic):
        c = 4.0 / 3.0 * math.sqrt(tip.radius) * E_STAR

        def g(s, z):
            return K * (z - s) - c * s * math.sqrt(s)
    else:
        t = math.tan(tip.half_angle) * 2.0 / math.pi if isinstance(tip, Conical) else \
            math.tan(tip.face_angle) / math.sqrt(2.0)  # Rico's form, the Pyramidal default
        c = t * E_STAR

        def g(s, z):
            return K * (z - s) - c * s * s
    return g, (lambda z: z), (lambda s: s)


def peer_tip(tip):
    g, hi, to_depth = _scalar_law(tip)
    out = np.zeros_like(Z)
    for i, z in enumerate(Z.tolist()):
        if z > 0:
            out[i] = to_depth(brentq(g, 0.0, hi(z), args=(z,), xtol=1e-300,
                                     rtol=4 * np.finfo(float).eps))
    return out


def peer():
    for tip in TIPS:
        peer_tip(tip)


def main():
    for system in SYSTEMS:  # same answers before timing anything
        np.testing.assert_allclose(system.indent(Z).z_s, peer_tip(system.tip), rtol=1e-12,
                                   atol=1e-24)
    rows = []
    for system in SYSTEMS:
        t = best_time(lambda system=system: system.indent(Z))
        rows.append((f"indent, 1000 points, {system.tip.key}", t, None, None))
    t_ours = best_time(ours)
    t_peer = best_time(peer, repeat=3)
    rows.append(("indent, 1000 points x 4 tips (afmsmiler)", t_ours, 5e-3, t_peer))
    rows.append(("scalar brentq loop, 1000 points x 4 tips (peer)", t_peer, None, None))
    report(rows)
    print(f"ratio brentq / afmsmiler = {t_peer / t_ours:.1f}x (target >= 20x)", flush=True)


if __name__ == "__main__":
    main()
