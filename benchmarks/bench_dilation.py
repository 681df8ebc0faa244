"""Module (f) speed: exact paraboloid tip dilation of a 256 x 256 and a 512 x 512 image, against the
named peer, ``scipy.ndimage.grey_dilation`` with the same structuring function (target: >= 10x).

The image: spheres of radius 8-25 nm on a 1 um x 1 um substrate (0.5 nm RMS), the course's
nanoparticle scene, imaged by a paraboloid of R = 20 nm. The peer gets the tip as its structuring
function b = -t on the smallest exact footprint (the tip cut at the sample's height range, which
cannot change the result; a larger footprint would only slow it down) and ``mode="constant",
cval=-inf`` (points outside the image are never touched, as ours). Before timing, the script
asserts that both give the same image to round-off.

Rows: ours as ``dilate`` runs it (the direct separable window, for windows up to
``WINDOW_LIMIT`` pixels), ours forced through the O(N) Felzenszwalb-Huttenlocher envelope, both
against the peer. A last row, 1024 x 1024 with a blunt R = 2 um tip (a window of about 440
pixels, beyond ``WINDOW_LIMIT``; scipy would take minutes there, so ours only): the envelope
(what ``dilate`` runs) against the forced window, the crossover that sets ``WINDOW_LIMIT``.
"""
import sys
from pathlib import Path

import numpy as np
from scipy import ndimage

sys.path.insert(0, str(Path(__file__).parent))
from _timing import best_time, report  # noqa: E402

from afmsmiler.contact.tips import Parabolic  # noqa: E402
from afmsmiler.imaging import dilation  # noqa: E402
from afmsmiler.imaging.dilation import dilate, tip_surface  # noqa: E402
from afmsmiler.samples import Sample  # noqa: E402

SCAN = 1e-6


def nanoparticles(n, seed=3):
    """n x n pixels over 1 um: 40 spheres (radius 8-25 nm) on a 0.5 nm RMS substrate."""
    rng = np.random.default_rng(seed)
    dx = SCAN / (n - 1)
    x = np.arange(n) * dx
    h = ndimage.gaussian_filter(rng.normal(size=(n, n)), 2.0)
    h *= 0.5e-9 / h.std()
    for _ in range(40):
        r = rng.uniform(8e-9, 25e-9)
        cx, cy = rng.uniform(0.05, 0.95, 2) * SCAN
        rho2 = (x[None, :] - cx) ** 2 + (x[:, None] - cy) ** 2
        h = np.maximum(h, np.where(rho2 <= r * r, r + np.sqrt(np.maximum(r * r - rho2, 0)), 0))
    return Sample(h, dx)


def peer(sample, tip):
    """scipy's grey dilation with the tip's structuring function on its exact footprint."""
    height = float(np.ptp(sample.heights))
    b = -tip_surface(tip, sample.pixel_size, max_height=height)
    return lambda: ndimage.grey_dilation(sample.heights, structure=b, mode="constant",
                                         cval=-np.inf)


def forced(sample, tip, method):
    h, height = sample.heights, float(np.ptp(sample.heights))
    return lambda: dilation._dilate_parabolic(h, tip.radius, sample.pixel_size,
                                              sample.pixel_size, height, method)


def main():
    rows = []
    for n, radius in [(256, 20e-9), (512, 20e-9)]:
        sample, tip = nanoparticles(n), Parabolic(radius=radius)
        ref = peer(sample, tip)()
        tol = 16 * np.finfo(float).eps * np.max(np.abs(sample.heights))
        assert np.max(np.abs(dilate(sample, tip).heights - ref)) <= tol, "ours != scipy"
        assert np.max(np.abs(forced(sample, tip, "envelope")() - ref)) <= tol, "ours != scipy"
        footprint = tip_surface(tip, sample.pixel_size, max_height=float(np.ptp(sample.heights)))
        label = f"{n}x{n}, R = {radius * 1e9:g} nm, footprint {footprint.shape[0]}^2"
        t_peer = best_time(peer(sample, tip), repeat=3, number=1)
        t_ours = best_time(lambda: dilate(sample, tip), repeat=5)
        t_env = best_time(forced(sample, tip, "envelope"), repeat=3, number=1)
        rows.append((f"scipy grey_dilation {label}", t_peer, None, None))
        rows.append(("  ours: dilate (target: peer/ours >= 10x)", t_ours, None, t_peer))
        rows.append(("  ours: the envelope alone", t_env, None, t_peer))
    sample, tip = nanoparticles(1024), Parabolic(radius=2e-6)
    window, envelope = forced(sample, tip, "window"), forced(sample, tip, "envelope")
    assert np.array_equal(dilate(sample, tip).heights, envelope())
    tol = 16 * np.finfo(float).eps * np.max(np.abs(sample.heights))
    assert np.max(np.abs(window() - envelope())) <= tol, "window != envelope"
    t_window = best_time(window, repeat=1, number=1)
    rows.append(("ours, window, 1024x1024, R = 2 um", t_window, None, None))
    rows.append(("  ours: dilate = the envelope (window/envelope)",
                 best_time(envelope, repeat=1, number=1), None, t_window))
    report(rows)


if __name__ == "__main__":
    main()
