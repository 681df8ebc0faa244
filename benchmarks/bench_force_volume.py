"""Module (g) speed: a force-volume map (target: a 64 x 64 map within 10 s, "seconds, not
minutes"), against the named peers, timed in the same run: scipy.optimize.curve_fit once per
curve, and module (d)'s one-curve ``fit_curve`` once per curve (what the map did before).

Ours: :func:`afmsmiler.modes.force_volume.force_volume` on a 64 x 64 two-material map (the
default ramp of 500 samples per branch, 20 pN noise): module (d)'s curves once per material, the
noise, adhesion, DMT correction and loop areas vectorised, and module (d)'s batched fit
``fit_curves`` once per material and block of 2^20 points (Levenberg-Marquardt on every curve's
3 x 3 normal equations at once). Its time per curve is the map's time over its pixels.

The fit alone, per curve: ``fit_curves`` on 4096 noisy DMT-corrected retracts of the matrix
(the map's curves of one material), against ``curve_fit`` (its default Levenberg-Marquardt on
F = F0 + (4/3) E* sqrt(R) max(x - x0, 0)^(3/2), started from the true values' neighbourhood,
as a user who knows the answer would; no contact detection, no error on failure: the lower
bound of a hand-written loop) and against the ``fit_curve`` loop, each on 100 of those curves.
A peer's time per map is its time per curve times the pixels, plus our map's time outside the
fit (curves, noise, adhesion, loop areas), so that the rows compare whole maps.
"""
import math
import sys
import time
from pathlib import Path

import numpy as np
from scipy.optimize import curve_fit

sys.path.insert(0, str(Path(__file__).parent))
from _timing import report  # noqa: E402

from afmsmiler.contact import Parabolic, fit_curve  # noqa: E402
from afmsmiler.contact.fit import fit_curves  # noqa: E402
from afmsmiler.modes.force_volume import (BLEND, PARAMETERS, force_volume,  # noqa: E402
                                          two_material_sample)

TIP = Parabolic(radius=10e-9)
SHAPE = (64, 64)
PEER_CURVES = 100


def ours():
    sample, labels = two_material_sample(SHAPE, 20e-9, island_radius=250e-9, island_count=10,
                                         seed=2)
    t0 = time.perf_counter()
    fv = force_volume(sample, BLEND, TIP, labels=labels, seed=7)
    return time.perf_counter() - t0, fv


def corrected_curves(fv, count):
    """``count`` noisy retracts of the matrix, DMT-corrected as the map does: (x, force)."""
    k = PARAMETERS["spring_constant"].default
    sigma = PARAMETERS["force_noise"].default
    rng = np.random.default_rng(0)
    z = fv.z_np[0][::-1]
    curves = fv.retract[0][None, :] + rng.normal(0, sigma, (count, z.size))
    adhesion = -curves.min(axis=1)
    jump = np.argmax(np.diff(curves, axis=1), axis=1)
    contact = np.arange(z.size)[None, :] <= jump[:, None]
    g = np.where(contact, curves + adhesion[:, None], curves)
    return z[None, :] - curves / k, g


def batched(x, g):
    nu = BLEND[0].poisson_ratio
    t0 = time.perf_counter()
    r = fit_curves(x, g, TIP, nu)
    return (time.perf_counter() - t0) / len(x), float(np.nanmedian(r.youngs_modulus))


def loop(x, g):
    nu = BLEND[0].poisson_ratio
    t0 = time.perf_counter()
    found = [fit_curve(xi, gi, TIP, nu).youngs_modulus for xi, gi in zip(x, g)]
    return (time.perf_counter() - t0) / len(x), float(np.median(found))


def peer(x, g):
    """curve_fit on each curve."""
    nu = BLEND[0].poisson_ratio
    e_star = BLEND[0].youngs_modulus / (1 - nu ** 2)
    c = 4 / 3 * math.sqrt(TIP.radius)

    def model(x, f0, e, x0):
        return f0 + e * c * np.maximum(x - x0, 0.0) ** 1.5

    t0 = time.perf_counter()
    found = [curve_fit(model, xi, gi, p0=(0.0, 0.8 * e_star, 0.1e-9))[0][1] for xi, gi in zip(x, g)]
    return (time.perf_counter() - t0) / len(x), float(np.median(found) * (1 - nu ** 2))


def main():
    t_map, fv = ours()
    pixels = SHAPE[0] * SHAPE[1]
    x, g = corrected_curves(fv, pixels)
    t_batch, e_batch = batched(x, g)
    t_loop, e_loop = loop(x[:PEER_CURVES], g[:PEER_CURVES])
    t_peer, e_peer = peer(x[:PEER_CURVES], g[:PEER_CURVES])
    e_map = float(np.nanmedian(fv.modulus[fv.labels == 0]))
    print(f"matrix modulus: map {e_map / 1e9:.4f} GPa, fit_curves {e_batch / 1e9:.4f} GPa, "
          f"fit_curve loop {e_loop / 1e9:.4f} GPa, curve_fit {e_peer / 1e9:.4f} GPa "
          f"(true {BLEND[0].youngs_modulus / 1e9:g} GPa)", flush=True)
    rest = max(t_map - t_batch * pixels, 0.0)  # the map's time outside the fit
    report([
        ("fit per curve: fit_curves (peer: curve_fit)", t_batch, None, t_peer),
        ("fit per curve: fit_curves (peer: fit_curve loop)", t_batch, None, t_loop),
        ("force volume: per curve, whole map", t_map / pixels, None, None),
        ("force volume: 64 x 64 map (peer: curve_fit loop)", t_map, 10.0,
         rest + t_peer * pixels),
        ("force volume: 64 x 64 map (peer: fit_curve loop)", t_map, 10.0,
         rest + t_loop * pixels),
    ])


if __name__ == "__main__":
    main()
