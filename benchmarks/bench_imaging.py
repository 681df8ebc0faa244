"""Module (f): a 256 x 256 constant-force image, trace and retrace, with an exact paraboloid tip.

Ours, end to end: ``Scan(sample, tip, ConstantForce(loop), settings).run()``, i.e. the exact
paraboloid dilation of the sample (separable lower envelopes of parabolas), the scan grid's
bilinear sampling, module (c)'s closed-form loop over the whole image (trace 0, retrace 0,
trace 1, ...) and the line-by-line assembly of the four channels.

Peer: spmsimu 0.0.2 (the digital-twin microscope's scanner, PyPI ``spmsimu``) on the same image
(heights in nm) with the same tip as its kernel (1 - t(u) in nm, from ``tip_surface``): its
``tip_scan`` (the grey dilation, numba-parallel) then its ``pi_loop`` on the trace and on the
retrace (the reversed lines). spmsimu's numba functions are compiled on their first call in
every Python process (no on-disk cache), so the peer is timed twice: cold, the first call in a
fresh interpreter as a user meets it (the issue measured 11.9 s that way), and warm, the best of
a few later calls in this process. The two dilations are compared first, away from the image's
edges (spmsimu pads with -1 nm, ours touches only the sample), so that the ratio compares equal
work. Target (issue 10): ours < 0.5 s and >= 20x faster than the peer.
"""
import subprocess
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))
from _timing import best_time, report  # noqa: E402

from afmsmiler.contact import Parabolic  # noqa: E402
from afmsmiler.controller import ContactLoop, scan_image  # noqa: E402
from afmsmiler.imaging.dilation import dilate, tip_surface  # noqa: E402
from afmsmiler.imaging.scan_modes import ConstantForce  # noqa: E402
from afmsmiler.imaging.scanner import Scan, ScanSettings  # noqa: E402
from afmsmiler.samples import particles  # noqa: E402

N, PX, SPEED = 256, 4e-9, 1e-3
sample = particles((N, N), PX)
tip = Parabolic(radius=20e-9)
settings = ScanSettings(N * PX, pixels=N, scan_speed=SPEED)
loop = ContactLoop()
kernel = 1.0 - tip_surface(tip, PX, max_height=float(np.ptp(sample.heights))) * 1e9
heights_nm = sample.heights * 1e9


def ours():
    return Scan(sample, tip, ConstantForce(loop), settings).run()


def peer():
    from spmsimu.simulator import pi_loop, tip_scan
    image = tip_scan(heights_nm, kernel)
    return image, pi_loop(image), pi_loop(image[:, ::-1])


_COLD = """
import sys, time, numpy as np
from spmsimu.simulator import pi_loop, tip_scan
h, k = np.load(sys.argv[1]), np.load(sys.argv[2])
t0 = time.perf_counter()
image = tip_scan(h, k)
pi_loop(image), pi_loop(image[:, ::-1])
print(time.perf_counter() - t0)
"""


def peer_cold(tmp: Path) -> float:
    """The peer's first call in a fresh interpreter (numba compiles on it), in s."""
    np.save(tmp / "h.npy", heights_nm)
    np.save(tmp / "k.npy", kernel)
    out = subprocess.run([sys.executable, "-c", _COLD, str(tmp / "h.npy"), str(tmp / "k.npy")],
                         capture_output=True, text=True, timeout=600, check=True)
    return float(out.stdout.split()[-1])


if __name__ == "__main__":
    import tempfile
    try:
        import spmsimu  # noqa: F401
    except ImportError:
        print("spmsimu is not installed (the `bench` extra): only our time is measured")
        report([("256 x 256 constant force, trace+retrace, paraboloid (ours)",
                 best_time(ours, repeat=5, number=1), 0.5, None)])
        raise SystemExit(0)
    with tempfile.TemporaryDirectory() as tmp:
        t_cold = peer_cold(Path(tmp))
    apex = dilate(sample, tip).heights * 1e9
    theirs = peer()[0]
    m = kernel.shape[0] // 2
    err = np.max(np.abs(apex[m:-m, m:-m] - theirs[m:-m, m:-m]))
    print(f"dilation, ours vs spmsimu's tip_scan: max |difference| = {err:.2e} nm on a "
          f"{np.ptp(apex):.1f} nm range (away from the {m}-pixel edges)")
    result = ours()
    assert result.finished and result.images["height trace"].shape == (N, N)
    t_ours = best_time(ours, repeat=5, number=1)
    t_warm = best_time(peer, repeat=3, number=1)
    t_dilate = best_time(lambda: dilate(sample, tip), repeat=5, number=1)
    t_loop = best_time(lambda: scan_image(loop, apex * 1e-9, PX, speed=SPEED), repeat=5, number=1)
    report([
        ("256 x 256 constant force, trace+retrace, paraboloid (ours)", t_ours, 0.5, t_cold),
        ("  of which the paraboloid dilation", t_dilate, None, None),
        ("  of which module (c)'s scan_image (the loop)", t_loop, None, None),
        ("  spmsimu tip_scan + pi_loop x 2, first call (peer, cold)", t_cold, None, None),
        ("  spmsimu, later calls (peer, warm)", t_warm, None, None),
    ])
    print(f"peer/ours: {t_cold / t_ours:.1f}x against the cold peer (target >= 20x), "
          f"{t_warm / t_ours:.1f}x against the warm peer")
