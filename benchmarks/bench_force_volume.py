"""Module (g) speed: a force-volume map (target: a 64 x 64 map within 10 s, "seconds, not
minutes"), against the named peer, fitting each curve with scipy.optimize.curve_fit, timed in
the same run.

Ours: :func:`afmsmiler.modes.force_volume.force_volume` on a 32 x 32 two-material map (the
default ramp of 500 samples per branch, 20 pN noise): module (d)'s curves once per material, the
noise, adhesion, DMT correction and loop areas vectorised, module (d)'s ``fit_curve`` once per
pixel. Its time per curve is the map's time over its pixels; a 64 x 64 map is four times the
32 x 32 one (every step is linear in the pixels). The peer fits the same DMT-corrected retract
curves, F = F0 + (4/3) E* sqrt(R) max(x - x0, 0)^(3/2), with ``curve_fit`` (its default
Levenberg-Marquardt, started from the true values' neighbourhood, as a user who knows the
answer would), on 100 curves; its time per map is its time per curve times the pixels. The
peer gets no uncertainty-aware contact detection and no error on failure: it is the lower
bound of a hand-written loop.

The fit dominates ours: module (d)'s ``fit_curve`` (scipy's bounded trust-region least squares
with tolerances of 1e-15 and the covariance) costs some 4 ms a curve, about ten times the
peer's bare ``curve_fit``, so the 64 x 64 target is missed on a shared 2-core machine; a
batched variant of module (d)'s fit (curves on one ramp fitted together) would remove it.
"""
import math
import sys
import time
from pathlib import Path

import numpy as np
from scipy.optimize import curve_fit

sys.path.insert(0, str(Path(__file__).parent))
from _timing import report  # noqa: E402

from afmsmiler.contact import Parabolic  # noqa: E402
from afmsmiler.modes.force_volume import (BLEND, PARAMETERS, force_volume,  # noqa: E402
                                          two_material_sample)

TIP = Parabolic(radius=10e-9)
SHAPE = (32, 32)
PEER_CURVES = 100


def ours():
    sample, labels = two_material_sample(SHAPE, 40e-9, island_radius=250e-9, island_count=5,
                                         seed=2)
    t0 = time.perf_counter()
    fv = force_volume(sample, BLEND, TIP, labels=labels, seed=7)
    return time.perf_counter() - t0, fv


def peer(fv):
    """curve_fit on PEER_CURVES noisy, DMT-corrected retracts of the matrix."""
    k = PARAMETERS["spring_constant"].default
    sigma = PARAMETERS["force_noise"].default
    rng = np.random.default_rng(0)
    z = fv.z_np[0][::-1]
    curves = fv.retract[0][None, :] + rng.normal(0, sigma, (PEER_CURVES, z.size))
    e_star = BLEND[0].youngs_modulus / (1 - BLEND[0].poisson_ratio ** 2)
    c = 4 / 3 * math.sqrt(TIP.radius)

    def model(x, f0, e, x0):
        return f0 + e * c * np.maximum(x - x0, 0.0) ** 1.5

    t0 = time.perf_counter()
    found = []
    for f in curves:
        adhesion = -f.min()
        jump = int(np.argmax(np.diff(f)))
        g = f.copy()
        g[:jump + 1] += adhesion
        x = z - f / k
        p, _ = curve_fit(model, x, g, p0=(0.0, 0.8 * e_star, 0.1e-9))
        found.append(p[1])
    per_curve = (time.perf_counter() - t0) / PEER_CURVES
    return per_curve, float(np.median(found) * (1 - BLEND[0].poisson_ratio ** 2))


def main():
    t_map, fv = ours()
    pixels = SHAPE[0] * SHAPE[1]
    t_peer, e_peer = peer(fv)
    e_ours = float(np.nanmedian(fv.modulus[fv.labels == 0]))
    print(f"matrix modulus: ours {e_ours / 1e9:.4f} GPa, peer {e_peer / 1e9:.4f} GPa "
          f"(true {BLEND[0].youngs_modulus / 1e9:g} GPa)", flush=True)
    report([
        ("force volume: per curve (fit_curve)", t_map / pixels, None, t_peer),
        ("force volume: 32 x 32 map", t_map, 2.5, t_peer * pixels),
        ("force volume: 64 x 64 map (4 x the 32 x 32)", 4 * t_map, 10.0, 4 * t_peer * pixels),
    ])


if __name__ == "__main__":
    main()
