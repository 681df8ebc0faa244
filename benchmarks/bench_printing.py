"""Module (h) speed: an AFM image printed as an STL, and the print read back as a height map.

Reading back (``printing.mesh_to_sample``, a numpy z-buffer over the upward-facing triangles)
against the named peer, matplotlib's ``LinearTriInterpolator`` on the top surface's triangulation
(a trapezoid-map point location, then linear interpolation): the same surface for a mesh made by
``sample_to_mesh``, which the script asserts before timing. The peer needs the top surface as a
planar triangulation, so it cannot read an arbitrary mesh (two boxes, overhangs) as ours does.

Writing (``sample_to_mesh`` then ``write_stl``): against a target of 2 s for the largest print
allowed (``MAX_TRIANGLES``, a 1000 x 1000 image), the bound the module promises.
"""
import sys
import tempfile
from pathlib import Path

import numpy as np
from matplotlib.tri import LinearTriInterpolator, Triangulation

sys.path.insert(0, str(Path(__file__).parent))
from _timing import best_time, report  # noqa: E402

from afmsmiler import samples  # noqa: E402
from afmsmiler.hardware import printing  # noqa: E402


def peer(mesh, pitch):
    """matplotlib's linear interpolation on the top surface's triangles, at the grid points."""
    rows, cols = mesh.metadata["shape"]
    top = mesh.vertices[:rows * cols]
    faces = mesh.faces[:2 * (rows - 1) * (cols - 1)]
    tri = Triangulation(top[:, 0], top[:, 1], faces)
    interp = LinearTriInterpolator(tri, top[:, 2])
    nx = int(np.floor(top[:, 0].max() / pitch + 1e-6)) + 1
    ny = int(np.floor(top[:, 1].max() / pitch + 1e-6)) + 1
    x, y = np.meshgrid(np.arange(nx) * pitch, np.arange(ny) * pitch)
    return lambda: interp(x, y).filled(np.nan)


def main():
    rows = []
    for n in (128, 256):
        image = samples.rough_surface((n, n), 0.5e-6, rms=0.5e-6, correlation_length=5e-6,
                                      seed=1)
        mesh = printing.sample_to_mesh(image, lateral_scale=400)
        mesh.metadata["shape"] = image.shape
        pitch = 0.5e-6 * 400 / 2  # half the printed pixel: points inside the triangles
        ours = printing.mesh_to_sample(mesh, pitch).heights
        theirs = peer(mesh, pitch)() - mesh.bounds[0, 2]
        assert np.allclose(ours, theirs, rtol=0, atol=1e-12), "ours != matplotlib"
        t_peer = best_time(peer(mesh, pitch), repeat=3, number=1)
        t_ours = best_time(lambda: printing.mesh_to_sample(mesh, pitch), repeat=3, number=1)
        rows.append((f"matplotlib LinearTriInterpolator {n}x{n} image, half pitch", t_peer,
                     None, None))
        rows.append(("  ours: mesh_to_sample (z-buffer)", t_ours, None, t_peer))
    big = samples.rough_surface((1000, 1000), 1e-6, rms=0.5e-6, correlation_length=10e-6,
                                seed=1)
    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "big.stl"
        t_write = best_time(lambda: printing.save_stl(big, path, lateral_scale=100), repeat=2,
                            number=1)
    rows.append((f"save_stl 1000x1000 ({printing.triangle_count(big.shape)} triangles)",
                 t_write, 2.0, None))
    report(rows)


if __name__ == "__main__":
    main()
