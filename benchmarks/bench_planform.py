"""Module (a)'s planforms: a V-shaped lever's spring constant and first three modes.

Target (issue 23): under 20 ms for k and f_1..f_3 of a V-shaped lever, built afresh each call
(nothing cached: a slider moving the geometry builds a new Lever). The frame model assembles
the half lever (48 elements, about 130 unknowns) vectorised, solves the static load once and
the generalised eigenproblem once (scipy.linalg.eigh).

Peer: the closed-form rectangle of the same size, ``Cantilever`` (k = 3 E J / L^3 and three
roots of cos(bL) cosh(bL) = -1, cached), which is what the numerical model costs against; and
the frame model of the rectangle, for the price of the method itself.
"""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

from _timing import best_time, report  # noqa: E402

from afmsmiler.cantilever import Cantilever  # noqa: E402
from afmsmiler.planform import Lever  # noqa: E402

TARGET = 20e-3


def main():
    def v_shaped():
        lever = Lever.v_shaped("silicon_nitride", 140e-6, 18e-6, 140e-6, 0.55e-6)
        return lever.spring_constant, lever.frequencies(3)

    def pointed():
        lever = Lever.pointed("silicon", 240e-6, 40e-6, 2.3e-6, 20e-6)
        return lever.spring_constant, lever.frequencies(3)

    def rectangle_frame():
        lever = Lever.rectangular("silicon", 240e-6, 40e-6, 2.3e-6)
        return lever.spring_constant, lever.frequencies(3)

    def closed_form():
        lever = Cantilever.from_material("silicon", 240e-6, 40e-6, 2.3e-6)
        return lever.spring_constant, [lever.resonance_frequency(n) for n in (1, 2, 3)]

    t_v = best_time(v_shaped)
    t_p = best_time(pointed)
    t_r = best_time(rectangle_frame)
    t_c = best_time(closed_form)
    print("k and f_1..f_3 of a lever built afresh (frame model: 48 elements, half lever)")
    report([
        ("V-shaped Lever (MLCT-E size): k + 3 flexural modes", t_v, TARGET, None),
        ("pointed Lever (AC240TS size): k + 3 flexural modes", t_p, TARGET, None),
        ("rectangular Lever (frame model): k + 3 flexural modes", t_r, TARGET, None),
        ("closed-form Cantilever: k + 3 frequencies (peer)", t_c, None, None),
    ])
    for label, t in (("V-shaped", t_v), ("pointed", t_p), ("rectangular frame", t_r)):
        print(f"{label} / closed-form rectangle = {t / t_c:.0f}x the time")
    print("(a machine shared with other work slows LAPACK's threads on these small matrices; "
          "OPENBLAS_NUM_THREADS=1 shows the model's own cost)")


if __name__ == "__main__":
    main()
